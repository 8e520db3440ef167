"""Forces of the moving cable system and their exact derivatives (the dynamic residual).

The equation of motion at the free dofs is ``M_s a = F(x, v, a, t)`` (Tuah eq. 4.2.1-4.2.6):
``F`` holds the constant loads (submerged weight, point loads), point force histories, the
axial element forces (elastic, standard linear solid or MoorDyn's static-dynamic rope, plus
Kelvin-Voigt damping ``BA``),
seabed contact, Morison drag on relative velocity, fluid inertia and minus the added-mass
force ``M_a(x) a`` (Tuah eq. 3.2.a.6, 4.2.3). ``M_s`` is the lumped structural mass. The
derivatives are returned as element (6x6) and node (3x3) blocks: ``K = -dF/dx``,
``C = -dF/dv``, ``M_a = -dF/da``. Lines with bending stiffness add the elastic bending
forces of :mod:`moorline.physics.bending` (no bending damping); the element blocks then run
over the mesh's :attr:`~moorline.mesh.Mesh.pattern_pairs` (elements, then the bending pairs),
``C`` and ``M_a`` zero on the bending pairs.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import NDArray

from ..mesh import Mesh
from ..physics import element, hydro, material, sag, seabed, static_dynamic, syrope
from .equilibrium import StaticModel, bending_loads

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class MaterialState:
    """Internal variables of the elements at the end of the last completed step.

    ``strain`` is each element's strain and ``maxwell`` its internal force variable: the force
    in the Maxwell branch of the standard linear solid, the static branch's spring force ``s``
    of the static-dynamic rope (:mod:`moorline.physics.static_dynamic`), the slow strain ``z``
    of the Syrope rope (:mod:`moorline.physics.syrope`), zero for elastic elements. ``peak``:
    the Syrope elements' running maximum mean tension [force] (NaN on other elements;
    ``None`` without Syrope elements).
    """

    strain: FloatArray
    maxwell: FloatArray
    peak: FloatArray | None = None


@dataclass(frozen=True)
class Evaluation:
    """Forces (and optionally tangents) at one trial state."""

    nodal: FloatArray                 # (n_nodes, 3) F without structural inertia
    inertial: FloatArray              # (n_nodes, 3) the added-mass part of ``nodal``
    tension: FloatArray               # (n_el,)
    material: MaterialState           # internal variables if this state is accepted
    element_forces: FloatArray        # (n_el, 2, 3) axial force (and bending shear) of each
    #                                   element on its nodes
    K: FloatArray | None = None       # (n_el, 6, 6) -dF/dx, element part
    C: FloatArray | None = None       # (n_el, 6, 6) -dF/dv, element part
    Ma: FloatArray | None = None      # (n_el, 6, 6) -dF/da, element part (added mass)
    node_K: FloatArray | None = None  # (n_nodes, 3, 3)
    node_C: FloatArray | None = None
    node_M: FloatArray | None = None  # point added mass
    Ka: FloatArray | None = None      # (n_el, 6, 6) the added-mass forces' part of K,
    #                                   -d(-M_a(x) a)/dx (inertial: HHT weights it by 1)


class DynamicModel:
    """Residual pieces of the dynamic balance of a mesh in a fluid field.

    Parameters
    ----------
    mesh
        The discretized system.
    fluid
        Any object with ``kinematics(points, t) -> (velocity, acceleration, elevation)``.
    viscoelastic_update
        ``exponential`` (exact for strain linear over a step) or ``incremental`` (Tuah eq.
        2.2.b.3, first order in dt).
    seabed_model
        The :class:`~moorline.model.Seabed` (for friction); None: frictionless.
    kernel
        ``numba``: the element loads are computed by the compiled kernel
        :class:`moorline.physics.fused.FusedLoads` (same results to round-off, much faster;
        tension-strain tables, the strain offsets of the fibre-rope dynamic stiffness,
        sag-corrected elements and standard-linear-solid elements with the ``exponential``
        update included); systems with the ``incremental`` viscoelastic update or MoorDyn's
        static-dynamic or Syrope ropes, evaluations with given Maxwell-branch forces, and
        ``numpy``, use the numpy path (the reference). ``self.kernel`` is the one in use.
        Bending stiffness is added by numpy on either path.
    slack_damping
        Keep the Kelvin-Voigt dashpot ``BA`` in slack elements (MoorDyn's law: a slack element
        then pushes by ``BA`` times its strain rate) instead of blending it off with the
        tension over the slack band, at the element's strain at the start of the step
        (:func:`moorline.physics.element.lagged_dashpot_share`).
    drag_velocity
        ``element``: an element's drag at the mean of its node velocities, half to each node
        (:func:`moorline.physics.hydro.drag_forces`); ``node``: each node's half at its own
        velocity (:func:`moorline.physics.hydro.nodal_drag_forces`, MoorDyn's node-based
        drag). Both options run on either kernel.
    """

    def __init__(self, mesh: Mesh, fluid, viscoelastic_update: str = "exponential",
                 seabed_model=None, kernel: Literal["numpy", "numba"] = "numba",
                 slack_damping: bool = False,
                 drag_velocity: Literal["element", "node"] = "element") -> None:
        self.mesh = mesh
        self.fluid = fluid
        static = StaticModel(mesh)
        self._static = static
        self.sag = static.sag
        self.external = static.external
        self.k_seabed = static.node_seabed_stiffness
        m = mesh
        self.c_seabed = m.seabed_damping_per_area * m.node_contact_area
        self.rho = m.water_density
        self.node_mass = element.lumped_mass(m.elements, m.length0, m.mass_per_length,
                                             m.n_nodes) + m.node_mass
        self.has_drag = bool(np.any(m.Cd > 0) or np.any(m.Ct > 0)) and self.rho > 0
        self.has_added_mass = bool(np.any(m.Ca > 0) or np.any(m.Cat > 0)) and self.rho > 0
        self.has_point_hydro = bool(np.any(m.node_Cd * m.node_drag_area > 0)
                                    or np.any(m.node_Ca * m.node_volume > 0))
        self.series = (None if m.static_dynamic is None
                       else np.flatnonzero(np.isfinite(m.static_dynamic[:, 0])))
        self.any_viscoelastic = (bool(np.any(m.viscoelastic)) or self.series is not None
                                 or m.syrope is not None)
        if self.sag is not None and (np.any(m.viscoelastic & m.sag_corrected) or (
                self.series is not None and np.any(m.sag_corrected[self.series])) or (
                m.syrope is not None and np.any(m.sag_corrected[m.syrope.index]))):
            raise ValueError("sag-corrected elements (element: sag_corrected) must be elastic: "
                             "a viscoelastic, static_dynamic or syrope line type has straight "
                             "elements")
        self.viscoelastic_update = viscoelastic_update
        self.seabed_ramp = static.seabed_ramp
        self.surface = m.seabed_surface
        self.friction = _friction_coefficients(seabed_model) if seabed_model else None
        if kernel not in ("numpy", "numba"):
            raise ValueError(f"kernel must be 'numpy' or 'numba', got {kernel!r}")
        if drag_velocity not in ("element", "node"):
            raise ValueError(f"drag_velocity must be 'element' or 'node', got {drag_velocity!r}")
        self.slack_damping = bool(slack_damping)
        self._drag = hydro.nodal_drag_forces if drag_velocity == "node" else hydro.drag_forces
        self._fused = None
        self.compiled_refusal = self._compiled_refusal(kernel)
        if self.compiled_refusal is None:
            from ..physics import fused  # imports numba only when used

            laws = m.strain_laws if m.strain_laws is not None and m.strain_laws.active else None
            self._fused = fused.FusedLoads(
                m.elements, m.n_nodes, m.length0, m.EA, m.slack_ratio, m.slack_smoothing, m.BA,
                m.diameter, m.Cd, m.Ct, m.Ca, m.Cat, self.rho, laws, m.strain_offset,
                with_drag=self.has_drag, with_added_mass=self.has_added_mass, sag=self.sag,
                weight_per_length=m.weight_per_length, slack_damping=self.slack_damping,
                node_drag=drag_velocity == "node", EA1=m.EA1, tau=m.tau,
                viscoelastic=m.viscoelastic)
            self._midpoints = fused.midpoints
        self.kernel = "numba" if self._fused is not None else "numpy"

    def _compiled_refusal(self, kernel: str) -> str | None:
        """Why the element loads stay on the numpy path (None: the compiled kernel)."""
        if kernel == "numpy":
            return "the numpy kernel"
        if self.series is not None or self.mesh.syrope is not None:
            return "static-dynamic or Syrope ropes"
        if np.any(self.mesh.viscoelastic) and self.viscoelastic_update != "exponential":
            return (f"viscoelastic lines with the {self.viscoelastic_update!r} update (the "
                    "compiled kernel has the exponential one)")
        return None

    def initial_material(self, x: FloatArray) -> MaterialState:
        """Material state in equilibrium at positions ``x`` (relaxed Maxwell branch; a relaxed
        static-dynamic rope's static branch carries the static tension ``EA eps``; a Syrope
        rope at rest on its working curve, :meth:`~moorline.physics.syrope.SyropeRope.\
relaxed_state`)."""
        length, _ = element.element_geometry(x, self.mesh.elements)
        strain = length / self.mesh.length0 - 1.0
        internal = np.zeros_like(strain)
        if self.series is not None:
            internal[self.series] = self.mesh.EA[self.series] * strain[self.series]
        sy, peak = self.mesh.syrope, None
        if sy is not None:
            peak = np.full_like(strain, np.nan)
            for g, rope in enumerate(sy.ropes):
                on = sy.group == g
                k = sy.index[on]
                internal[k], peak[k] = rope.relaxed_state(strain[k], sy.Tmax0[on])
        return MaterialState(strain, internal, peak)

    def evaluate(self, x: FloatArray, v: FloatArray, a: FloatArray, t: float,
                 previous: MaterialState, dt: float, tangent: bool,
                 point_forces: FloatArray | None = None,
                 maxwell: FloatArray | None = None) -> Evaluation:
        """Forces at a trial state ``(x, v, a)`` at time ``t``; tangents if ``tangent``.

        ``maxwell``: the Maxwell-branch forces of the viscoelastic elements given (n_el,)
        instead of integrated from ``previous`` (harmonic balance solves them per harmonic,
        :mod:`moorline.solvers.harmonic_material`): their tension is then the linear law
        ``EA eps + Q`` and its tangent ``EA`` (``Q``'s own dependence on the strain history
        is the caller's)."""
        if maxwell is not None and (self.series is not None or self.mesh.syrope is not None):
            raise ValueError("the static-dynamic and Syrope ropes (MoorDyn's mean-load "
                             "dependent viscoelastic models) are time-domain only: no harmonic "
                             "balance")
        m = self.mesh
        el = m.elements
        if self._fused is not None and (maxwell is None or not self._fused.viscoelastic):
            u_f = a_f = None
            if self.has_drag or self.has_added_mass:
                u_f, a_f, _ = self.fluid.kinematics(self._midpoints(x, el), t)
            r = self._fused(x, v, a, u_f, a_f, tangent, strain_before=previous.strain,
                            maxwell_before=previous.maxwell, dt=dt)
            out = {}
            if tangent:
                out = {"K": r.K, "C": r.C, "Ma": r.Ma if self.has_added_mass else None,
                       "Ka": r.Ka if self.has_added_mass else None}
            inertial = r.nodal_added_mass if self.has_added_mass else np.zeros((m.n_nodes, 3))
            nodal = r.nodal + self.external
            if point_forces is not None:
                nodal += point_forces
            nodal, el_forces, out = self._bending(x, nodal, r.element_forces, out, tangent)
            nodal, inertial, out = self._nodes(x, v, a, t, nodal, inertial, out, tangent)
            return Evaluation(nodal, inertial, r.tension, MaterialState(
                r.strain, previous.maxwell if r.maxwell is None else r.maxwell,
                previous.peak), el_forces, **out)
        length, unit = element.element_geometry(x, el)
        dv = v[el[:, 1]] - v[el[:, 0]]
        T, dT_dl, state, share, sag_law = self._axial_tension(x, length, unit, dv, previous, dt,
                                                              maxwell)
        el_forces = element.nodal_forces(T, unit)
        forces = el_forces.copy()
        out = {}
        if tangent:
            out["K"] = self._axial_tangent(length, unit, dv, T, dT_dl, share, sag_law)
            out["C"] = _axial_damping_blocks(unit, m.BA * share / m.length0)
        mid = 0.5 * (x[el[:, 0]] + x[el[:, 1]])
        if self.has_drag or self.has_added_mass:
            u_f, a_f, _ = self.fluid.kinematics(mid, t)
            forces, out = self._morison(x, v, a, u_f, a_f, forces, out, tangent)
        inertial = np.zeros((m.n_nodes, 3))
        if "f_am" in out:
            inertial = hydro.sum_to_nodes(out.pop("f_am"), el, m.n_nodes)
        nodal = hydro.sum_to_nodes(forces, el, m.n_nodes) + self.external
        if point_forces is not None:
            nodal += point_forces
        nodal, el_forces, out = self._bending(x, nodal, el_forces, out, tangent)
        nodal, inertial, out = self._nodes(x, v, a, t, nodal, inertial, out, tangent)
        return Evaluation(nodal, inertial, T, state, el_forces, **out)

    def _bending(self, x, nodal, el_forces, out, tangent):
        """Bending forces added to ``nodal`` and to the element forces (as shear,
        :func:`moorline.solvers.equilibrium.bending_loads`); with ``tangent`` the element
        blocks extended over the bending pairs."""
        m = self.mesh
        if not m.has_bending:
            return nodal, el_forces, out
        shear, K = bending_loads(m, x, out["K"] if tangent else None)
        if tangent:
            pad = np.zeros((len(m.bend_nodes), 6, 6))
            out = dict(out, K=K, **{key: np.concatenate((out[key], pad))
                                    for key in ("C", "Ma", "Ka")
                                    if out.get(key) is not None})
        return (nodal + hydro.sum_to_nodes(shear, m.elements, m.n_nodes), el_forces + shear,
                out)

    def _axial_tension(self, x, length, unit, dv, previous, dt, given=None):
        """Axial force with damping, ``dT/dl``, the material state, the dashpot share and
        (sag-corrected elements) the sag law and ``dphi/dx`` (else ``None``)."""
        m = self.mesh
        strain = length / m.length0 - 1.0
        sag_law = None
        if self.sag is None:
            T, dT_deps = element.axial_tension(length, m.length0, m.EA, m.slack_ratio,
                                               m.slack_smoothing, **m.axial_law)
        else:
            sag_law = self._static.sag_tension(x, length, unit, m.slack_ratio,
                                               m.slack_smoothing)
            T, dT_deps = sag_law[0].tension, sag_law[0].dT_dl
        dT_deps = dT_deps * m.length0
        maxwell = previous.maxwell
        if self.any_viscoelastic and given is not None:
            ve = m.viscoelastic
            T, dT_deps, maxwell = T.copy(), dT_deps.copy(), np.asarray(given, dtype=float)
            T[ve] = m.EA[ve] * strain[ve] + maxwell[ve]
            dT_deps[ve] = m.EA[ve]
        elif self.any_viscoelastic:
            ve = m.viscoelastic
            T, dT_deps, maxwell = T.copy(), dT_deps.copy(), previous.maxwell.copy()
            T[ve], maxwell[ve], dT_deps[ve] = self._viscoelastic(
                strain[ve], previous.strain[ve], previous.maxwell[ve], dt, m.EA[ve], m.EA1[ve],
                m.tau[ve], m.slack_ratio[ve])
        if self.series is not None and given is None:
            sd, k = m.static_dynamic[self.series], self.series
            T[k], maxwell[k], dT_deps[k] = static_dynamic.static_dynamic_update(
                strain[k], previous.strain[k], previous.maxwell[k], dt, m.EA[k], sd[:, 0],
                sd[:, 1], sd[:, 2], sd[:, 3], m.slack_ratio[k])
        peak = previous.peak
        if m.syrope is not None and given is None:
            peak = previous.peak.copy()
            sy = m.syrope
            for g, rope in enumerate(sy.ropes):
                on = sy.group == g
                k = sy.index[on]
                T[k], maxwell[k], peak[k], dT_deps[k] = syrope.syrope_update(
                    strain[k], previous.strain[k], previous.maxwell[k], previous.peak[k], dt,
                    rope, sy.c1[on], sy.c2[on], m.slack_ratio[k] * m.EA[k])
        if self.slack_damping:
            share = np.ones_like(length)
        else:  # held over the step at its start (element.lagged_dashpot_share)
            share = element.lagged_dashpot_share(previous.strain, m.slack_smoothing,
                                                 m.strain_offset)
        strain_rate = np.einsum("ij,ij->i", unit, dv) / m.length0
        T = T + m.BA * share * strain_rate
        return T, dT_deps / m.length0, MaterialState(strain, maxwell, peak), share, sag_law

    def _viscoelastic(self, strain, strain_old, maxwell_old, dt, EA, EA1, tau, slack_ratio):
        """Standard linear solid update: exact exponential integration of the Maxwell branch
        (default) or the source's incremental form, Tuah (1982) eq. 2.2.b.3."""
        if self.viscoelastic_update == "exponential":
            return material.sls_update_exponential(strain, strain_old, maxwell_old, dt, EA, EA1,
                                                   tau, slack_ratio)
        tension_old = EA * strain_old + maxwell_old
        T, k = material.sls_update_incremental(strain, strain_old, tension_old, dt, EA, EA1,
                                               tau)
        return T, T - EA * strain, k

    def _axial_tangent(self, length, unit, dv, T, dT_dl, share, sag_law=None):
        m = self.mesh
        if sag_law is None:
            blocks = element.tangent_blocks(length, unit, T, dT_dl)
        else:
            blocks = sag.sag_blocks(length, unit, sag_law[0]._replace(tension=T, dT_dl=dT_dl),
                                    sag_law[1])
        damping = m.BA * share / (m.length0 * length)
        if np.any(damping):
            transverse = dv - np.einsum("ij,ij->i", dv, unit)[:, None] * unit
            k = damping[:, None, None] * unit[:, :, None] * transverse[:, None, :]
            blocks[:, :3, :3] += k
            blocks[:, 3:, 3:] += k
            blocks[:, :3, 3:] -= k
            blocks[:, 3:, :3] -= k
        return blocks

    def _morison(self, x, v, a, u_f, a_f, forces, out, tangent):
        m = self.mesh
        el = m.elements
        if self.has_drag:
            f, dF_dv, dF_dx = self._drag(x, v, u_f, el, m.length0, m.diameter, m.Cd,
                                                m.Ct, self.rho)
            forces = forces + f
            if tangent:
                out["K"] = out["K"] - dF_dx
                out["C"] = out["C"] - dF_dv
        if self.has_added_mass:
            f_in, dFin_dx = hydro.fluid_inertia_forces(x, a_f, el, m.length0, m.diameter, m.Ca,
                                                       m.Cat, self.rho)
            Ma = hydro.added_mass_blocks(x, el, m.length0, m.diameter, m.Ca, m.Cat, self.rho)
            a_el = np.concatenate((a[el[:, 0]], a[el[:, 1]]), axis=1)
            f_am = -np.einsum("eij,ej->ei", Ma, a_el).reshape(-1, 2, 3)
            forces = forces + f_in + f_am
            out["f_am"] = f_am
            if tangent:
                dMa_dx = hydro.added_mass_position_derivative(x, a, el, m.length0, m.diameter,
                                                              m.Ca, m.Cat, self.rho)
                out["K"] = out["K"] - dFin_dx - dMa_dx
                out["Ma"] = Ma
                out["Ka"] = -dMa_dx
        return forces, out

    def _friction(self, x, v, contact, nodal, node_K, node_C, tangent):
        """Seabed friction on resting nodes, driven by the contact force, in the seabed's
        tangent plane; the line direction at a node is the mean of its elements' directions
        projected on that plane (its change with the positions is left out of the
        tangent)."""
        m = self.mesh
        mu_a, mu_t, v_s = self.friction
        n = contact.unit_normal
        axis = np.zeros_like(x)
        if mu_a != mu_t:
            chord = x[m.elements[:, 1]] - x[m.elements[:, 0]]
            for k in range(3):
                axis[:, k] = (np.bincount(m.elements[:, 0], chord[:, k], m.n_nodes)
                              + np.bincount(m.elements[:, 1], chord[:, k], m.n_nodes))
            axis -= n * np.einsum("ij,ij->i", axis, n)[:, None]
            norm = np.linalg.norm(axis, axis=1)
            fallback = np.cross(n, np.cross(np.array([1.0, 0.0, 0.0]), n))
            axis = np.where(norm[:, None] > 0, axis / np.maximum(norm, 1e-300)[:, None],
                            fallback)
        flat = self.surface.is_flat
        f, df_dv, df_dn, df_dx = seabed.friction_force(
            v, contact.normal, axis, mu_a, mu_t, v_s, None if flat else n,
            None if flat else contact.dunit_dx)
        nodal += f
        if tangent:
            node_C -= df_dv + df_dn[:, :, None] * contact.dnormal_dv[:, None, :]
            node_K -= df_dx + df_dn[:, :, None] * contact.dnormal_dx[:, None, :]

    def _nodes(self, x, v, a, t, nodal, inertial, out, tangent):
        m = self.mesh
        n = m.n_nodes
        node_K = np.zeros((n, 3, 3)) if tangent else None
        node_C = np.zeros((n, 3, 3)) if tangent else None
        node_M = None
        if self.surface is not None:
            contact = seabed.surface_contact(x, v, self.surface, self.k_seabed, self.c_seabed,
                                             self.seabed_ramp)
            nodal += contact.force
            if tangent:
                node_K -= contact.stiffness
                node_C -= contact.damping
            if self.friction is not None:
                self._friction(x, v, contact, nodal, node_K, node_C, tangent)
        if self.has_point_hydro:
            u_f, a_f, _ = self.fluid.kinematics(x, t)
            area = m.node_drag_area * m.node_Cd
            f, dF_dv = hydro.point_drag(u_f - v, area, np.ones(n), self.rho)
            added = self.rho * m.node_Ca * m.node_volume
            nodal += f + (self.rho * m.node_volume + added)[:, None] * a_f - added[:, None] * a
            inertial = inertial - added[:, None] * a
            if tangent:
                node_C += dF_dv  # d(drag)/d(u_rel) = -d(drag)/dv
                node_M = added[:, None, None] * np.eye(3)
        if tangent:
            out.update(node_K=node_K, node_C=node_C, node_M=node_M)
        return nodal, inertial, out


def _friction_coefficients(seabed_model) -> tuple[float, float, float] | None:
    """(axial, transverse, slip velocity) of a :class:`~moorline.model.Seabed`, or None."""
    mu = seabed_model.friction
    mu_a = seabed_model.friction_axial if seabed_model.friction_axial is not None else mu
    mu_t = (seabed_model.friction_transverse if seabed_model.friction_transverse is not None
            else mu)
    if mu_a == 0 and mu_t == 0:
        return None
    return mu_a, mu_t, seabed_model.slip_velocity


def _axial_damping_blocks(unit: FloatArray, c: FloatArray) -> FloatArray:
    """Damping blocks ``c n n^T [[1, -1], [-1, 1]]`` of the Kelvin-Voigt axial dashpots."""
    return element.pair_blocks(c[:, None, None] * unit[:, :, None] * unit[:, None, :])
