"""The static force balance of a mesh: residual and exact tangent.

Residual ``R(x, lam) = lam F_ext + F_cable(x) + F_seabed(x)`` at the free dofs (Tuah eq. 4.1.2:
external minus internal resisting force); tangent ``K = -dR/dx`` (Tuah eq. 3.1.8a, exact form
derived in :mod:`moorline.physics.element`).

With a steady current (``current``: a fluid field), the Morison drag of the current on the
elements at rest (:func:`moorline.physics.hydro.drag_forces`, normal and tangential, lumped
half to each node) and on points with a drag area (:func:`moorline.physics.hydro.point_drag`)
joins the loads, scaled by ``lam`` like them; its position derivative through the element
direction is in the tangent (the current's variation with depth is not). Drag is not
conservative: the Newton line search holds it at its value at the start of the search and adds
its work to the potential energy (:meth:`StaticModel.potential_energy`).

Lines with bending stiffness add the forces, tangent and energy of
:mod:`moorline.physics.bending` (:func:`bending_loads`, shared with the dynamic residual);
their tangent blocks extend the element blocks over the mesh's
:attr:`~moorline.mesh.Mesh.pattern_pairs`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from ..mesh import Mesh
from ..physics import bending, element, hydro, sag, seabed
from .assembly import BlockPattern, gather_free

if TYPE_CHECKING:
    import scipy.sparse as sp

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class ForceState:
    """Everything a force evaluation produces at one configuration."""

    tension: FloatArray          # (n_elements,)
    element_forces: FloatArray   # (n_elements, 2, 3) force of each element on its nodes
    #                              (axial, plus the bending shear with bending stiffness)
    nodal: FloatArray            # (n_nodes, 3) sum of all forces on each node
    length: FloatArray           # (n_elements,) current chord lengths


class StaticModel:
    """Residual and tangent of a mesh's static balance, with a cached sparse pattern.

    With ``exact_cable`` the elements follow the cable law itself, ``T = EA max(eps, 0)``: no
    compression and no smoothing band (:func:`moorline.physics.element.axial_tension` with
    ``slack_ratio = smoothing = 0``). The static balance is then solved as a semismooth
    problem with an active set of taut elements: the tangent is the law's generalized
    Jacobian, ``EA / L0`` on taut elements, and keeps ``slack_ratio EA / L0`` on slack ones
    (Tuah sec. 6.2: "the modulus E for the slack element is set to a very small value") so
    that the Newton matrix stays usable, while the residual, and so the equilibrium, has
    neither the compression nor the band's tension of the regularized law: a slack pile on
    the seabed ends with no end force, as the closed form's, and a line lying just taut
    carries ``EA eps``, not ``EA s / 4``. The energy stays C1 (the line search's merit).
    """

    def __init__(self, mesh: Mesh, current=None, exact_cable: bool = False,
                 friction: float = 0.0) -> None:
        self.mesh = mesh
        self.exact_cable = exact_cable
        self.surface = mesh.seabed_surface
        self.friction = float(friction) if self.surface is not None else 0.0
        self._friction_map = _friction_map(mesh) if self.friction > 0 else None
        self.pattern = BlockPattern(mesh.pattern_pairs, mesh.dof_of_node)
        self.current = current if current is not None and mesh.water_density > 0 else None
        g, rho = mesh.gravity, mesh.water_density
        ext = element.lumped_weight(mesh.elements, mesh.length0, mesh.weight_per_length,
                                    mesh.n_nodes)
        ext[:, 2] += (rho * mesh.node_volume - mesh.node_mass) * g
        self.external = ext + mesh.node_force
        self.node_seabed_stiffness = mesh.seabed_stiffness_per_area * mesh.node_contact_area
        self.seabed_ramp = seabed.contact_ramp(-ext[:, 2], self.node_seabed_stiffness,
                                               float(np.max(mesh.diameter, initial=0.0)))
        self.sag = None if mesh.sag_corrected is None else sag.SagCorrection(
            mesh.sag_corrected.astype(float), mesh.elements, -self.external[:, 2],
            self.node_seabed_stiffness, self.seabed_ramp, self.surface)

    def sag_tension(self, x: FloatArray, length: FloatArray, unit: FloatArray,
                    slack_ratio: FloatArray, smoothing: FloatArray | float
                    ) -> tuple[sag.SagTension, FloatArray]:
        """Chord force of every element with the sag correction (straight elements: ``phi =
        0``, their own law) and ``dphi/dx`` of each element's nodes (n_el, 2, 3)."""
        m = self.mesh
        phi, dphi = self.sag.share(x)
        return sag.sag_tension(length, unit, m.length0, m.EA, slack_ratio, smoothing,
                               m.weight_per_length, phi, **m.axial_law), dphi

    def forces(self, x: FloatArray, lam: float = 1.0) -> ForceState:
        """All nodal forces at positions ``x`` (n_nodes, 3) with the loads scaled by ``lam``."""
        m = self.mesh
        length, unit = element.element_geometry(x, m.elements)
        law = None
        if self.sag is None:
            tension, _ = element.axial_tension(length, m.length0, m.EA, *self._law(),
                                               **m.axial_law)
        else:
            law = self.sag_tension(x, length, unit, *self._law())
            tension = law[0].tension
        el_forces = element.nodal_forces(tension, unit)
        if m.has_bending:
            el_forces = el_forces + bending_loads(m, x)[0]
        nodal = lam * self.external
        nodal = nodal + hydro.sum_to_nodes(el_forces, m.elements, m.n_nodes)
        if self.surface is not None:
            nodal = nodal + self._seabed(x).force
        if self.current is not None:
            nodal = nodal + lam * self._current_drag(x)[0]
        if self._friction_map is not None:
            nodal = nodal + self._friction(x, length, unit, law)[0]
        return ForceState(tension, el_forces, nodal, length)

    def _friction(self, x: FloatArray, length: FloatArray, unit: FloatArray,
                  law: tuple[sag.SagTension, FloatArray] | None = None
                  ) -> tuple[FloatArray, FloatArray]:
        """Seabed friction of the lying lines (:func:`moorline.physics.seabed.static_friction`)
        as node forces (n_nodes, 3), and the element blocks of its derivative (n_el, 6, 6).
        ``law``: the sag-corrected tension of the residual's law (:meth:`sag_tension`)."""
        m = self.mesh
        nodes, elems, first = self._friction_map
        contact = self._seabed(x)
        dT_dx = None
        if self.sag is not None:
            law = law or self.sag_tension(x, length, unit, *self._law())
            tension, dT = law[0].tension[elems], law[0].dT_dl[elems]
            dT_dx = _own_far(law[0], law[1], unit, elems, first)
        else:
            tension, dT = element.axial_tension(length[elems], m.length0[elems], m.EA[elems],
                                                *[a[elems] for a in self._law()],
                                                **m.axial_law_of(elems))
        sign = np.where(first, 1.0, -1.0)[:, None]
        f, df = seabed.static_friction(contact.normal[nodes], contact.dnormal_dx[nodes],
                                       tension, dT, sign * unit[elems], length[elems],
                                       self.friction, contact.unit_normal[nodes],
                                       contact.dunit_dx[nodes], self.external[nodes], dT_dx)
        nodal = np.zeros((m.n_nodes, 3))
        nodal[nodes] = f
        blocks = np.zeros((m.n_elements, 6, 6))
        own, far = np.where(first[:, None], np.arange(3), np.arange(3, 6)), \
            np.where(first[:, None], np.arange(3, 6), np.arange(3))
        rows = own[:, :, None]
        blocks[elems[:, None, None], rows, own[:, None, :]] = df[:, :, :3]
        blocks[elems[:, None, None], rows, far[:, None, :]] = df[:, :, 3:]
        return nodal, blocks

    def _current_drag(self, x: FloatArray) -> tuple[FloatArray, FloatArray | None]:
        """Node forces of the current's drag on the structure at rest (n_nodes, 3) and the
        element blocks of their position derivative (n_elements, 6, 6)."""
        m = self.mesh
        el = m.elements
        mid = 0.5 * (x[el[:, 0]] + x[el[:, 1]])
        u_mid = self.current.kinematics(mid, 0.0)[0]
        zero = np.zeros_like(x)
        f, _, dF_dx = hydro.drag_forces(x, zero, u_mid, el, m.length0, m.diameter, m.Cd,
                                        m.Ct, m.water_density)
        nodal = hydro.sum_to_nodes(f, el, m.n_nodes)
        area = m.node_drag_area * m.node_Cd
        if np.any(area > 0):
            u_nodes = self.current.kinematics(x, 0.0)[0]
            nodal = nodal + hydro.point_drag(u_nodes, area, np.ones(m.n_nodes),
                                             m.water_density)[0]
        return nodal, dF_dx

    def residual(self, x: FloatArray, lam: float = 1.0) -> tuple[FloatArray, ForceState]:
        """Out-of-balance force at the free dofs, and the force state."""
        state = self.forces(x, lam)
        return gather_free(state.nodal, self.mesh.dof_of_node), state

    def _law(self) -> tuple[FloatArray, FloatArray]:
        """``(slack_ratio, smoothing)`` of the element law in the residual and the energy."""
        m = self.mesh
        if self.exact_cable:
            return np.zeros_like(m.EA), np.zeros_like(m.EA)
        return m.slack_ratio, m.slack_smoothing

    def tangent(self, x: FloatArray, pattern: BlockPattern | None = None,
                taut_axial: bool = False, shift: float = 0.0) -> sp.csr_matrix:
        """Exact tangent ``-dR/dx`` assembled over ``pattern`` (default: the free dofs).

        With ``taut_axial`` every element gets the taut axial stiffness ``EA / L0`` and the
        geometric stiffness of ``max(T, 0)``, slack ones included: the stiffness against
        perturbations that do not change which elements are slack (strumming modes). Without
        ``exact_cable`` the generalized Jacobian of the cable law, a slack element keeping
        ``slack_ratio EA / L0`` axially and no geometric stiffness.
        ``shift`` is added to the diagonal (a Levenberg-Marquardt shift).
        """
        pattern = pattern or self.pattern
        return pattern.csr(self.tangent_values(x, pattern, taut_axial, shift))

    def tangent_values(self, x: FloatArray, pattern: BlockPattern | None = None,
                       taut_axial: bool = False, shift: float = 0.0) -> FloatArray:
        """The stored entries of :meth:`tangent` (the pattern's storage order), without
        building the matrix."""
        m = self.mesh
        length, unit = element.element_geometry(x, m.elements)
        if self.sag is not None:
            blocks = self._sag_blocks(x, length, unit, taut_axial)
        else:
            tension, dT = element.axial_tension(length, m.length0, m.EA, m.slack_ratio,
                                                0.0 if self.exact_cable else m.slack_smoothing,
                                                **m.axial_law)
            if self.exact_cable:
                tension = np.maximum(tension, 0.0)
            if taut_axial:
                tension, dT = np.maximum(tension, 0.0), self._taut_stiffness(length)
            blocks = element.tangent_blocks(length, unit, tension, dT)
        if self.current is not None:
            blocks = blocks - self._current_drag(x)[1]
        if self._friction_map is not None:
            blocks = blocks - self._friction(x, length, unit)[1]
        if m.has_bending:
            blocks = bending_loads(m, x, blocks)[1]
        node_blocks = None
        if self.surface is not None:
            node_blocks = -self._seabed(x).stiffness
        pattern = pattern or self.pattern
        diagonal = np.full(pattern.n, shift) if shift else None
        return pattern.values(blocks, node_blocks, diagonal)

    def _sag_blocks(self, x: FloatArray, length: FloatArray, unit: FloatArray,
                    taut_axial: bool) -> FloatArray:
        """Element blocks of the sag-corrected law (:func:`moorline.physics.sag.sag_blocks`),
        with the slack elements' generalized Jacobian as :meth:`tangent` describes."""
        m = self.mesh
        if taut_axial:
            raise ValueError("sag-corrected elements (lines with element: sag_corrected) have "
                             "no taut-axial tangent (strumming modes): use straight elements")
        law, dphi = self.sag_tension(x, length, unit, m.slack_ratio,
                                     0.0 if self.exact_cable else m.slack_smoothing)
        if self.exact_cable:
            law = law._replace(tension=np.maximum(law.tension, 0.0))
        return sag.sag_blocks(length, unit, law, dphi)

    def _taut_stiffness(self, length: FloatArray) -> FloatArray:
        """``dT/dl`` of every element as if taut: ``EA / L0``, or a non-linear law's tangent
        at ``max(eps, 0)`` (at the strain offset for a dynamic law)."""
        m = self.mesh
        if m.linear_axial:
            return m.EA / m.length0
        offset = 0.0 if m.strain_offset is None else m.strain_offset
        taut = m.length0 * (1.0 + np.maximum(length / m.length0 - 1.0, offset))
        zero = np.zeros_like(m.EA)
        return element.axial_tension(taut, m.length0, m.EA, zero, zero, **m.axial_law)[1]

    def _seabed(self, x: FloatArray) -> seabed.Contact:
        zero = np.zeros(self.mesh.n_nodes)
        return seabed.surface_contact(x, np.zeros_like(x), self.surface,
                                      self.node_seabed_stiffness, zero, self.seabed_ramp)

    def seabed_share(self, x: FloatArray) -> FloatArray:
        """Share of each node's own load across the seabed that the seabed carries at
        positions ``x`` (0 to 1: 1 lying, between at the touchdown node; the normal force
        over the load's component into the seabed; :mod:`moorline.physics.seabed`)."""
        if self.surface is None:
            return np.zeros(self.mesh.n_nodes)
        contact = self._seabed(x)
        load = -np.einsum("ij,ij->i", self.external, contact.unit_normal)
        with np.errstate(divide="ignore", invalid="ignore"):
            share = np.where(load > 0, contact.normal / load, 0.0)
        return np.clip(share, 0.0, 1.0)

    def resting_penetration(self) -> FloatArray:
        """Per node, the seabed penetration at which the contact carries the node's own load
        (n_nodes,): where a node lying on a flat seabed rests."""
        return seabed.resting_penetration(-self.external[:, 2], self.node_seabed_stiffness,
                                          self.seabed_ramp)

    def potential_energy(self, x: FloatArray, lam: float = 1.0,
                         frozen: FloatArray | None = None) -> float:
        """Total potential energy: strain and seabed energy minus the work of the loads.

        All static forces here are conservative but a current's drag, so ``R = -dPi/dx``; the
        Newton line search uses ``Pi`` as its merit function. ``frozen``: node forces held
        constant (a current's drag at the start of a line search), whose work is added.
        """
        m = self.mesh
        length, _ = element.element_geometry(x, m.elements)
        energy = float(element.strain_energy(length, m.length0, m.EA, *self._law(),
                                             **m.axial_law).sum())
        if m.has_bending:
            energy += float(bending.bending_energy(x, m.bend_nodes, m.bend_stiffness).sum())
            energy += float(bending.clamp_energy(x, m.elements, m.clamp_elements,
                                                 m.clamp_direction, m.clamp_stiffness).sum())
        if self.surface is not None:
            energy += seabed.surface_energy(x, self.surface, self.node_seabed_stiffness,
                                            self.seabed_ramp)
        energy -= lam * float(np.sum(self.external * x))
        if frozen is not None:
            energy -= float(np.sum(frozen * x))
        return energy

    def drag_loads(self, x: FloatArray, lam: float = 1.0) -> FloatArray | None:
        """The loads without a potential at ``x``: the current's drag with its load factor
        and the seabed friction (``None`` without either)."""
        loads = None
        if self.current is not None:
            loads = lam * self._current_drag(x)[0]
        if self._friction_map is not None:
            length, unit = element.element_geometry(x, self.mesh.elements)
            f = self._friction(x, length, unit)[0]
            loads = f if loads is None else loads + f
        return loads

    def load_scale(self) -> float:
        """Force scale for relative tolerances: the largest nodal load (or a tension scale)."""
        scale = float(np.abs(self.external).max(initial=0.0))
        return scale if scale > 0 else 1e-6 * float(np.max(self.mesh.EA, initial=1.0))

    def roundoff_floor(self, x: FloatArray) -> float:
        """Smallest out-of-balance force resolvable in double precision at positions ``x``:
        chords are differences of coordinates, so ``dT ~ EA eps |x| / L0``."""
        m = self.mesh
        if m.n_elements == 0:
            return 0.0
        reach = float(np.abs(x).max(initial=1.0))
        return 64 * np.finfo(float).eps * float(np.max(m.EA / m.length0)) * reach


def bending_loads(mesh: Mesh, x: FloatArray, element_blocks: FloatArray | None = None
                  ) -> tuple[FloatArray, FloatArray | None]:
    """Bending forces of a mesh with bending stiffness at positions ``x`` as element forces on
    their nodes (n_elements, 2, 3) (:func:`moorline.physics.bending.element_shear`), and with
    ``element_blocks`` (n_elements, 6, 6) those blocks extended by the bending tangent over
    :attr:`~moorline.mesh.Mesh.pattern_pairs` (n_elements + n_b, 6, 6); ``None`` without
    ``element_blocks``."""
    nodes, c = mesh.bend_nodes, mesh.bend_stiffness
    shear = bending.element_shear(bending.bending_forces(x, nodes, c), mesh.bend_elements,
                                  mesh.n_elements)
    clamp = (mesh.elements, mesh.clamp_elements, mesh.clamp_direction, mesh.clamp_stiffness)
    if len(mesh.clamp_elements):
        np.add.at(shear, mesh.clamp_elements, bending.clamp_forces(x, *clamp))
    if element_blocks is None:
        return shear, None
    K = bending.bending_tangent(x, nodes, c)
    blocks = bending.to_pair_blocks(K, mesh.bend_elements, mesh.n_elements, element_blocks)
    if len(mesh.clamp_elements):
        np.add.at(blocks, mesh.clamp_elements, bending.clamp_tangent(x, *clamp))
    return shear, blocks


def _own_far(law: sag.SagTension, dphi: FloatArray, unit: FloatArray, elems: NDArray[np.int64],
             first: NDArray[np.bool_]) -> FloatArray:
    """``dT/dx`` of elements ``elems`` with respect to the node ``first`` names (its first
    node, else its second) and the element's other node, (n, 6)."""
    t = law.dT_dl[elems, None] * unit[elems] + law.dT_dx2[elems]   # relative part, d/dx2
    d1 = -t + law.dT_dphi[elems, None] * dphi[elems, 0]
    d2 = t + law.dT_dphi[elems, None] * dphi[elems, 1]
    f = first[:, None]
    return np.concatenate((np.where(f, d1, d2), np.where(f, d2, d1)), axis=1)


def _friction_map(mesh: Mesh) -> tuple[NDArray[np.int64], NDArray[np.int64], NDArray[np.bool_]]:
    """For seabed friction: the interior nodes of every line with an end on the seabed (that
    end is its anchor), the element on each node's fairlead side, and whether the node is
    that element's first node. Lines with no end on the seabed get no friction (which way a
    line lying only in its middle would slide is not defined by the statics)."""
    tol = 1e-6 * max(1.0, abs(mesh.seabed_z))
    bottom = mesh.seabed_height(mesh.node_position)
    nodes, elems, first = [], [], []
    for line_nodes, els in zip(mesh.line_nodes, mesh.line_elements, strict=True):
        interior = np.arange(1, len(line_nodes) - 1)
        for end, side, forward in ((0, interior, True), (-1, interior - 1, False)):
            if mesh.node_position[line_nodes[end], 2] <= bottom[line_nodes[end]] + tol:
                nodes.append(line_nodes[interior])
                elems.append(els[side])
                first.append(np.full(len(interior), forward))
                break
    if not nodes:
        return np.zeros(0, np.int64), np.zeros(0, np.int64), np.zeros(0, bool)
    return np.concatenate(nodes), np.concatenate(elems), np.concatenate(first)
