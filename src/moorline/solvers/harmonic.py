"""Periodic response by harmonic balance (the Fourier method of Tcheou 1997, ch. 2-4).

Tcheou writes the motion under a harmonic top force as a Fourier series in time,
``r(s, t) = sum_{k=-n}^{n} C_k(s) exp(i k omega t)`` (eq. 2.15), substitutes it in the equation
of motion (eq. 2.6: inertia with added mass, tension, drag, fluid inertia, net weight) and the
stretch condition, identifies the coefficients of each ``exp(i k omega t)`` and solves the
resulting time-independent nonlinear equations for the ``C_k`` by Newton-Raphson (sec. 4.2),
after a finite-difference discretization in ``s``.

moorline applies the same idea to its own finite-element model, so that the periodic answer
is that of the time-domain equations exactly (the steady state a long time-domain run tends
to). The free node positions are the real Fourier series

    x(t) = X_0 + sum_{k=1}^{n} (A_k cos k omega t + B_k sin k omega t),

and the residual of the dynamic equilibrium ``R(x, v, a, t) = M_s a - F(x, v, a, t)``
(:class:`moorline.solvers.dynamic_model.DynamicModel`: axial forces, drag on the relative
velocity, added mass, fluid inertia, seabed, point loads, prescribed motions) is made
orthogonal to every harmonic: ``sum_j E(t_j)^T R(t_j) = 0`` over ``N_t`` equally spaced
instants of the period (the alternating frequency-time scheme: Tcheou's identification of
exponential terms done numerically, which handles the non-polynomial ``|v| v`` drag and slack
elements; ``N_t = 4 (n + 1)`` by default, well above ``2n + 1``, keeps aliasing small). The
Jacobian is exact, ``sum_j E_j^T (K_j E_j + C_j E'_j + M_j E''_j)`` with the tangent blocks
of the time-domain model at every instant, assembled block-sparse: ordered dof by dof, it has
the sparsity of one instant's tangent with a dense (2 n + 1)^2 block per stored entry, built
from the tangents' sparse values (no dense matrix; memory linear in the number of nodes), and
factored by sparse LU. Newton (with backtracking) starts from the static state.

The excitation must be periodic with the analysis period after any ramp (harmonic forces on
free points or bodies, harmonic motions of prescribed points with a period that divides it,
regular waves and their exciting-force tables).

Rigid bodies (:mod:`moorline.solvers.harmonic_bodies`): a free body adds its origin and a
rotation vector relative to its static orientation, six Fourier series, to the unknowns; at
every instant the time-domain body model (:class:`~moorline.solvers.body_model.BodyModel`:
rigid and constant added mass, damping, hydrostatics as nonlinear as in the time domain,
drag, force histories, exciting-force tables, the lines' forces through the master-slave
transformation) gives the body residual and its tangent blocks, and the attached nodes move
with the body. The instant's tangent is chained to the generalized coordinates ``(q, q',
q'')`` (the rotation vector's kinematics exactly), so the Jacobian keeps its form
``sum_j E_j^T (K_j E_j + C_j E'_j + M_j E''_j)``, assembled over the union of the instants'
sparsity. A body's frequency-dependent radiation (``Body.radiation``) acts per harmonic,
``A(k w)`` and ``B(k w)``. Viscoelastic lines (:mod:`moorline.solvers.harmonic_material`):
the Maxwell branch's periodic state per harmonic, with its exact (non-local in time) Jacobian.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from ..errors import MoorlineError
from ..mesh import dynamic_mesh
from ..model import HarmonicSettings, System
from ..physics.rigid_body import rotation_matrix, rotation_vector
from ..results import HarmonicResult, StaticResult
from .assembly import BlockPattern, factorize, gather_free, scatter_free
from .bodies import BodyState, transformation
from .body_model import BodyModel
from .dynamic_model import DynamicModel
from .excitation import Excitation
from .harmonic_bodies import angular_kinematics, radiation_matrices
from .harmonic_material import maxwell_operator
from .newton import Counters, NewtonPolicy, TangentCache
from .newton import solve as newton_solve
from .statics import equilibrium_for

FloatArray = NDArray[np.float64]


def _basis(times: FloatArray, omega: float, n: int) -> tuple[FloatArray, ...]:
    """``E``, ``E'``, ``E''`` (n_t, 2 n + 1): the mean, ``cos k w t``, ``sin k w t``."""
    k = np.arange(1, n + 1)
    arg = np.outer(times, k * omega)
    c, s = np.cos(arg), np.sin(arg)
    E = np.ones((len(times), 2 * n + 1))
    dE = np.zeros_like(E)
    ddE = np.zeros_like(E)
    E[:, 1::2], E[:, 2::2] = c, s
    dE[:, 1::2], dE[:, 2::2] = -k * omega * s, k * omega * c
    ddE[:, 1::2], ddE[:, 2::2] = -(k * omega) ** 2 * c, -(k * omega) ** 2 * s
    return E, dE, ddE


class HarmonicBalance:
    """The harmonic-balance equations of a system: residual and sparse Jacobian.

    The unknowns are the coefficients ``X`` (2 n + 1, n_u) of the free node dofs and the six
    dofs of every free body (its origin, then its rotation vector ``phi`` relative to the
    static orientation, ``R = exp([phi x]) R_static``) (the mean, then ``A_k``, ``B_k``),
    flattened dof by dof, ``u[p (2 n + 1) + k] = X[k, p]``, so that the Jacobian is a
    block-sparse matrix with the pattern of the time-domain tangent and a dense
    (2 n + 1)^2 block per stored entry.

    Parameters
    ----------
    system
        The problem (lines, points, bodies; periodic excitation).
    settings
        Period, harmonics, samples.
    statics
        The static state linearized from (solved when not given).

    Raises
    ------
    MoorlineError
        With bad settings, or a regular wave whose period does not divide the analysis'.
    """

    def __init__(self, system: System, settings: HarmonicSettings,
                 statics: StaticResult | None = None) -> None:
        from ..waves import fluid_field_from_environment

        if not (settings.period > 0 and settings.harmonics >= 1):
            raise MoorlineError("harmonic balance needs period > 0 and harmonics >= 1")
        statics = equilibrium_for(system, statics, "harmonic balance")
        mesh = dynamic_mesh(statics.mesh, statics.positions)
        n = settings.harmonics
        n_t = settings.samples or 4 * (n + 1)
        if n_t < 2 * n + 1:
            raise MoorlineError(f"harmonic balance: samples ({n_t}) must be >= 2 n + 1 = "
                                f"{2 * n + 1}")
        _check_wave_period(system, settings.period)
        self.system, self.settings, self.statics, self.mesh = system, settings, statics, mesh
        self.system_name, self.units = system.name, system.units
        self.n_terms, self.n_t = 2 * n + 1, n_t
        self.period, self.omega = settings.period, 2.0 * math.pi / settings.period
        fluid = fluid_field_from_environment(system.environment)
        self.model = DynamicModel(mesh, fluid, "exponential", system.environment.seabed)
        self.x_static = statics.positions
        excitation = Excitation(mesh, self.x_static)
        # evaluate the excitation after its ramps, a whole number of periods on
        ramps = [p.motion.ramp_time for p in system.points.values() if p.motion is not None] + \
            [p.force_history.ramp_time for p in system.points.values()
             if p.force_history is not None] + \
            [b.force_history.ramp_time for b in system.bodies.values()
             if b.force_history is not None]
        self.shift = self.period * math.ceil(max(ramps, default=0.0) / self.period + 1e-12)
        self.times = self.period * np.arange(n_t) / n_t
        self.basis = _basis(self.times, self.omega, n)
        self.material = self.model.initial_material(self.x_static)
        self.pattern = BlockPattern(mesh.elements, mesh.dof_of_node)
        self.node_mass = self.model.node_mass[:, None, None] * np.eye(3)
        self.constrained = [excitation.constrained_state(self.shift + t) for t in self.times]
        self.forces = [excitation.point_forces(self.shift + t, mesh.n_nodes)
                       for t in self.times]
        self.coupled = bool(mesh.body_names)
        self.body_model = self.static_bodies = None
        self.n_u = mesh.n_dofs
        if self.coupled:
            self.static_bodies = BodyState.from_pose(statics.body_pose)
            self.body_model = BodyModel(mesh, fluid, self.static_bodies)
            self.n_u = self.body_model.layout.n_unknowns
        self.radiation = self._radiation_tables()
        ve = np.flatnonzero(mesh.viscoelastic)
        self.viscoelastic = ve
        self.maxwell_map = (maxwell_operator(self.basis[0], self.omega, mesh.EA1[ve],
                                             mesh.tau[ve]) if len(ve) else None)
        E = self.basis[0]
        # the Jacobian's time weights, E_j[k] B_j[l] per instant j for B = E, E', E'' (the
        # factors of K_j, C_j, M_j), over n_t (the residual is the mean over the instants)
        self._weights = [np.einsum("jk,jl->jkl", E, B).reshape(n_t, -1) / n_t
                         for B in self.basis]
        weights = [b.mass * mesh.gravity for b in system.bodies.values()]
        self.scale = max(float(np.abs(self.model.external).max(initial=0.0)),
                         float(np.abs(statics.tension).max(initial=0.0)),
                         max(weights, default=0.0), 1e-12)

    def _radiation_tables(self) -> dict[int, tuple[FloatArray, FloatArray]]:
        """``A(k w)``, ``B(k w)`` per harmonic term of the free bodies with a radiation
        table, by body index."""
        if self.body_model is None:
            return {}
        return {b: radiation_matrices(body.radiation, self.omega, self.settings.harmonics)
                for b, body in enumerate(self.body_model.bodies)
                if body.radiation is not None and self.body_model.body_dof[b] >= 0}

    @property
    def n_unknowns(self) -> int:
        """Number of unknowns, (2 n + 1) n_u."""
        return self.n_terms * self.n_u

    def unknowns(self, X: FloatArray) -> FloatArray:
        """Coefficients (2 n + 1, n_u) to the flat unknown vector (dof by dof)."""
        return np.ascontiguousarray(X.T).ravel()

    def coefficients_of(self, u: FloatArray) -> FloatArray:
        """The flat unknown vector back to coefficients (2 n + 1, n_u)."""
        return u.reshape(self.n_u, self.n_terms).T

    def initial(self) -> FloatArray:
        """The static state as unknowns (the mean; no harmonics)."""
        X = np.zeros((self.n_terms, self.n_u))
        X[0, :self.mesh.n_dofs] = gather_free(self.x_static, self.mesh.dof_of_node)
        if self.coupled:
            for b, d in enumerate(self.body_model.body_dof):
                if d >= 0:
                    X[0, d:d + 3] = self.static_bodies.r[b]
        return self.unknowns(X)

    def body_motion(self, X: FloatArray) -> tuple[list[BodyState], dict]:
        """The bodies' states at every instant and, per free body, the kinematic chain
        ``(J, d omega / d phi, d alpha / d phi, d alpha / d phi')`` (each (n_t, 3, 3)) and
        the generalized velocity and acceleration (n_t, 6)."""
        bm, s0 = self.body_model, self.static_bodies
        nb, n_t = len(bm.bodies), self.n_t
        r = np.repeat(s0.r[None], n_t, axis=0)
        R = np.repeat(s0.R[None], n_t, axis=0)
        vel, acc = np.zeros((n_t, nb, 6)), np.zeros((n_t, nb, 6))
        chains = {}
        E, dE, ddE = self.basis
        for b, d in enumerate(bm.body_dof):
            if d < 0:
                continue
            c = X[:, d:d + 6]
            x, v, a = E @ c, dE @ c, ddE @ c
            w, al, J, dw, da, dd = angular_kinematics(x[:, 3:], v[:, 3:], a[:, 3:])
            r[:, b] = x[:, :3]
            R[:, b] = rotation_matrix(x[:, 3:]) @ s0.R[b]
            vel[:, b, :3], vel[:, b, 3:] = v[:, :3], w
            acc[:, b, :3], acc[:, b, 3:] = a[:, :3], al
            chains[b] = (J, dw, da, dd)
        states = [BodyState(r[j], R[j], vel[j], acc[j]) for j in range(n_t)]
        return states, {"chains": chains, "vel": vel, "acc": acc}

    def states(self, X: FloatArray, bodies: list[BodyState] | None = None
               ) -> list[tuple[FloatArray, FloatArray, FloatArray]]:
        """Positions, velocities, accelerations (n_nodes, 3) at every instant (the attached
        nodes on the ``bodies``' states when given)."""
        dof, free = self.mesh.dof_of_node, self.mesh.free_nodes
        nd = self.mesh.n_dofs
        xs, vs, as_ = (np.einsum("tk,kd->td", B, X[:, :nd]) for B in self.basis)
        out = []
        for j in range(self.n_t):
            x = self.x_static.copy()
            v, a = np.zeros_like(x), np.zeros_like(x)
            x[free], v[free], a[free] = (scatter_free(arr[j], dof)[free]
                                         for arr in (xs, vs, as_))
            x[~free], v[~free], a[~free] = self.constrained[j]
            if bodies is not None:
                self.body_model.place(x, v, a, bodies[j])
            out.append((x, v, a))
        return out

    def _maxwell(self, states) -> list[FloatArray | None]:
        """The viscoelastic elements' Maxwell-branch forces at every instant (n_el,) from
        the strains at all instants (``None`` without viscoelastic elements)."""
        if self.maxwell_map is None:
            return [None] * self.n_t
        el, ve = self.mesh.elements[self.viscoelastic], self.viscoelastic
        eps = np.array([np.linalg.norm(x[el[:, 1]] - x[el[:, 0]], axis=1)
                        / self.mesh.length0[ve] - 1.0 for x, _, _ in states])  # (n_t, n_ve)
        Q = np.einsum("eji,ie->je", self.maxwell_map, eps)
        out = []
        for j in range(self.n_t):
            q = np.zeros(self.mesh.n_elements)
            q[ve] = Q[j]
            out.append(q)
        return out

    def evaluate(self, u: FloatArray, tangent: bool
                 ) -> tuple[FloatArray, sp.spmatrix | None, FloatArray]:
        """Residual, Jacobian and tensions at the unknowns ``u``.

        The residual is ``(1 / N_t) sum_j E_j^T R_j`` with ``R_j = M a_j - F(x_j, v_j, a_j,
        t_j)`` the time-domain residual at instant ``j`` (bodies: minus their generalized
        forces); its Jacobian is ``(1 / N_t) sum_j E_j^T (K_j E_j + C_j E'_j + M_j E''_j)``,
        assembled block-sparse from the sparse tangents of every instant (never a dense
        matrix), plus the non-local terms of the Maxwell branches and of frequency-dependent
        radiation.

        Returns
        -------
        residual
            (n_unknowns,), in the order of ``u``.
        jacobian
            (n_unknowns, n_unknowns) sparse matrix, or ``None`` without ``tangent``.
        tension
            Element tensions at every instant (n_t, n_elements).
        """
        mesh, model, n_t = self.mesh, self.model, self.n_t
        dof, E = mesh.dof_of_node, self.basis[0]
        X = self.coefficients_of(u)
        bodies, motion = self.body_motion(X) if self.coupled else (None, None)
        states = self.states(X, bodies)
        maxwell = self._maxwell(states)
        R = np.zeros((self.n_terms, self.n_u))
        tension = np.zeros((n_t, mesh.n_elements))
        collected = _Collector(self.n_u) if tangent and self.coupled else None
        tangents = np.empty((3, n_t, self.pattern.nnz)) if tangent and not self.coupled \
            else None
        maps = []  # per instant: (rows map T^T, columns map P_x) for the Maxwell terms
        for j, (x, v, a) in enumerate(states):
            t = float(self.shift + self.times[j])
            ev = model.evaluate(x, v, a, t, self.material, self.period / n_t, tangent,
                                self.forces[j], maxwell[j])
            tension[j] = ev.tension
            if not self.coupled:
                R += np.outer(E[j], gather_free(model.node_mass[:, None] * a - ev.nodal, dof))
                if tangent:
                    nodes_m = self.node_mass + (ev.node_M if ev.node_M is not None else 0.0)
                    tangents[0, j] = self.pattern.values(ev.K, ev.node_K)
                    tangents[1, j] = self.pattern.values(ev.C, ev.node_C)
                    tangents[2, j] = self.pattern.values(ev.Ma, nodes_m)
                continue
            r_j, mats, pair = self._coupled_instant(x, a, bodies[j], motion, j, t, ev, tangent)
            R += np.outer(E[j], r_j)
            if tangent:
                collected.add(j, mats)
                maps.append(pair)
        R += self._radiation_residual(motion)
        if not tangent:
            return self.unknowns(R) / n_t, None, tension
        if self.coupled:
            indices, indptr, values = collected.values(n_t)
            J = self._jacobian(values, indices, indptr)
        else:
            J = self._jacobian(tangents, self.pattern.indices, self.pattern.indptr)
        extra = [self._maxwell_jacobian(states, maps), self._radiation_jacobian(motion),
                 self._neutral_mean(J)]
        for part in extra:
            if part is not None:
                J = J + part
        return self.unknowns(R) / n_t, J, tension

    def _neutral_mean(self, J: sp.spmatrix) -> sp.csr_matrix | None:
        """A vanishing shift (1e-9 of the largest diagonal entry) of the free bodies' mean
        rows: a body free to turn about an axis with nothing resisting it (the yaw of a
        buoy on one line attached on its axis) has a neutral mean there, which leaves the
        Jacobian singular; the harmonics have inertia. As in the coupled statics
        (:mod:`moorline.solvers.coupled_statics`), the shift changes the Newton step, not
        the solution (the residual is unshifted)."""
        if not self.coupled:
            return None
        first = [d for d in self.body_model.body_dof if d >= 0]
        if not first:
            return None
        idx = ((np.asarray(first)[:, None] + np.arange(6)) * self.n_terms).ravel()
        shift = 1e-9 * float(np.abs(J.diagonal()).max(initial=1.0))
        size = self.n_unknowns
        return sp.csr_matrix((np.full(idx.size, shift), (idx, idx)), shape=(size, size))

    def _coupled_instant(self, x, a, bs: BodyState, motion: dict, j: int, t: float, ev,
                         tangent: bool):
        """Residual (n_u,) of one instant of a system with bodies and, with ``tangent``, its
        derivatives with respect to the generalized coordinates, velocities and
        accelerations ``(K, C, M)`` (sparse, n_u x n_u), and the maps ``(T^T, P_x)`` of
        the lines' forces to the unknowns and of the unknowns to the node positions."""
        mesh, bm, layout = self.mesh, self.body_model, self.body_model.layout
        m_s = self.model.node_mass[:, None]
        other, inertial = ev.nodal - ev.inertial, ev.inertial - m_s * a
        arms = np.einsum("kij,kj->ki", bs.R[mesh.slave_body], mesh.slave_arm)
        r = np.zeros(self.n_u)
        r[:layout.n_free] = gather_free(m_s * a - ev.nodal, mesh.dof_of_node)
        body_other, body_inertial = bm.forces(bs, other, inertial, arms, t)
        for b, d in enumerate(bm.body_dof):
            if d >= 0:
                r[d:d + 6] = -(body_other[b] + body_inertial[b])
        if not tangent:
            return r, None, None
        pat = layout.pattern
        nodes_m = self.model.node_mass[:, None, None] * np.eye(3)
        if ev.node_M is not None:
            nodes_m = nodes_m + ev.node_M
        Kl, Cl, Ml = (pat.assemble(ev.K, ev.node_K), pat.assemble(ev.C, ev.node_C),
                      pat.assemble(ev.Ma, nodes_m))
        chain = self._chain(bs, motion, j)
        # the attached nodes' kinematics with respect to the body's pose (d r, d theta),
        # velocity and acceleration (Newmark factors 0/1 pick the parts apart)
        zeros = np.zeros((len(bm.bodies), 6))
        bx, bv0, ba0 = bm.kinematic_blocks(bs, arms, zeros, 0.0, 0.0)
        _, bv1, ba1 = bm.kinematic_blocks(bs, arms, zeros, 0.0, 1.0)
        ba2 = bm.kinematic_blocks(bs, arms, zeros, 1.0, 0.0)[2]
        sv, sa_v, sa_a = bv1 - bv0, ba1 - ba0, ba2 - ba0
        sb = mesh.slave_body
        Tq, Vq, Vqd, Aq, Aqd, Aqdd = (chain[k][sb] for k in range(6))
        blocks = {"xq": bx @ Tq, "vq": bv0 @ Tq + sv @ Vq, "vqd": sv @ Vqd,
                  "aq": ba0 @ Tq + sa_v @ Vq + sa_a @ Aq, "aqd": sa_v @ Vqd + sa_a @ Aqd,
                  "aqdd": sa_a @ Aqdd}
        scale = {"xq": 1.0, "vq": 0.0, "vqd": 1.0, "aq": 0.0, "aqd": 0.0, "aqdd": 1.0}
        P = {k: transformation(mesh, layout.ext_dofs, layout.n_free, bm.body_dof, arms,
                               blocks[k], scale[k]) for k in blocks}
        Tt = transformation(mesh, layout.ext_dofs, layout.n_free, bm.body_dof, arms).T
        K = Tt @ (Kl @ P["xq"] + Cl @ P["vq"] + Ml @ P["aq"])
        C = Tt @ (Cl @ P["vqd"] + Ml @ P["aqd"])
        M = Tt @ (Ml @ P["aqdd"])
        node_forces = other + inertial
        base = bm.blocks(bs, node_forces, arms, t, 0.0, 0.0, 1.0)
        with_m = bm.blocks(bs, node_forces, arms, t, 1.0, 0.0, 1.0)
        with_c = bm.blocks(bs, node_forces, arms, t, 0.0, 1.0, 1.0)
        Kb, Cb, Mb = [], [], []
        for b in range(len(bm.bodies)):
            kb, cb, mb = base[b], with_c[b] - base[b], with_m[b] - base[b]
            tq, vq, vqd, aq, aqd, aqdd = (chain[k][b] for k in range(6))
            Kb.append(kb @ tq + cb @ vq + mb @ aq)
            Cb.append(cb @ vqd + mb @ aqd)
            Mb.append(mb @ aqdd)
        mats = [(K + self._body_matrix(Kb)).tocoo(), (C + self._body_matrix(Cb)).tocoo(),
                (M + self._body_matrix(Mb)).tocoo()]
        return r, mats, (Tt, P["xq"])

    def _chain(self, bs: BodyState, motion: dict, j: int) -> list[FloatArray]:
        """Per body (nb, 6, 6): how its pose change ``(d r, d theta)``, velocity and
        acceleration follow the generalized ``(q, q', q'')`` at instant ``j``:
        ``Tq, Vq, Vq', Aq, Aq', Aq''`` (identity-like for held bodies: unused)."""
        nb = len(self.body_model.bodies)
        eye = np.eye(3)
        out = [np.zeros((nb, 6, 6)) for _ in range(6)]
        for b in range(nb):
            J = dw = da = dd = None
            if b in motion["chains"]:
                J, dw, da, dd = (c[j] for c in motion["chains"][b])
            else:
                J, dw, da, dd = eye, np.zeros((3, 3)), np.zeros((3, 3)), np.zeros((3, 3))
            for k in (0, 2, 5):  # Tq, Vq', Aq'': diag(I, J)
                out[k][b, :3, :3], out[k][b, 3:, 3:] = eye, J
            out[1][b, 3:, 3:], out[3][b, 3:, 3:], out[4][b, 3:, 3:] = dw, da, dd
        return out

    def _body_matrix(self, blocks: list[FloatArray]) -> sp.csr_matrix:
        """The free bodies' (6, 6) blocks as a sparse matrix over the unknowns."""
        rows, cols, vals = [], [], []
        for d, block in zip(self.body_model.body_dof, blocks, strict=True):
            if d < 0:
                continue
            i, k = np.meshgrid(np.arange(6) + d, np.arange(6) + d, indexing="ij")
            rows.append(i.ravel())
            cols.append(k.ravel())
            vals.append(np.asarray(block).ravel())
        n = self.n_u
        if not rows:
            return sp.csr_matrix((n, n))
        return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows),
                                                    np.concatenate(cols))), shape=(n, n))

    def _radiation_residual(self, motion: dict | None) -> FloatArray:
        """``sum_j E_j[k] (A_k acc_j + B_k vel_j)`` of the bodies with a radiation table
        (the harmonic-``k`` row with ``A(k w)``, ``B(k w)``), (2 n + 1, n_u)."""
        R = np.zeros((self.n_terms, self.n_u))
        E = self.basis[0]
        for b, (A, B) in self.radiation.items():
            d = self.body_model.body_dof[b]
            vel, acc = motion["vel"][:, b], motion["acc"][:, b]  # (n_t, 6)
            R[:, d:d + 6] += np.einsum("jk,kpq,jq->kp", E, A, acc) + \
                np.einsum("jk,kpq,jq->kp", E, B, vel)
        return R

    def _radiation_jacobian(self, motion: dict | None) -> sp.csr_matrix | None:
        """The derivative of :meth:`_radiation_residual` (dense per body, sparse overall)."""
        if not self.radiation:
            return None
        E, dE, ddE = self.basis
        m, n_t = self.n_terms, self.n_t
        rows, cols, vals = [], [], []
        for b, (A, B) in self.radiation.items():
            d = self.body_model.body_dof[b]
            chain = [np.zeros((n_t, 6, 6)) for _ in range(5)]  # Vq, Vq', Aq, Aq', Aq''
            J, dw, da, dd = motion["chains"][b]
            for c in (chain[1], chain[4]):
                c[:, :3, :3], c[:, 3:, 3:] = np.eye(3), J
            chain[0][:, 3:, 3:], chain[2][:, 3:, 3:], chain[3][:, 3:, 3:] = dw, da, dd
            d_vel = np.einsum("jl,jrq->jlrq", E, chain[0]) + np.einsum("jl,jrq->jlrq", dE,
                                                                        chain[1])
            d_acc = (np.einsum("jl,jrq->jlrq", E, chain[2])
                     + np.einsum("jl,jrq->jlrq", dE, chain[3])
                     + np.einsum("jl,jrq->jlrq", ddE, chain[4]))
            block = (np.einsum("jk,kpr,jlrq->pkql", E, A, d_acc)
                     + np.einsum("jk,kpr,jlrq->pkql", E, B, d_vel)) / n_t
            idx = (d + np.arange(6))[:, None] * m + np.arange(m)[None, :]  # (6, m)
            rows.append(np.broadcast_to(idx[:, :, None, None], block.shape).ravel())
            cols.append(np.broadcast_to(idx[None, None], block.shape).ravel())
            vals.append(block.ravel())
        size = self.n_unknowns
        return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows),
                                                    np.concatenate(cols))),
                             shape=(size, size))

    def _maxwell_jacobian(self, states, maps) -> sp.csr_matrix | None:
        """The non-local part of the viscoelastic elements' Jacobian: the tension at instant
        ``j`` through the Maxwell force ``Q_j = sum_i L_ji eps_i`` depends on the strain at
        every instant ``i``:
        ``(1 / N_t) sum_ji E_j^T g_j L_ji h_i^T E_i``, ``g_j = d R_j / d T`` (minus the
        element's nodal forces per unit tension, mapped to the unknowns by ``T^T``) and
        ``h_i = d eps_i / d u`` (through the master-slave map ``P_x``)."""
        if self.maxwell_map is None:
            return None
        mesh, ve, n_t, m = self.mesh, self.viscoelastic, self.n_t, self.n_terms
        E = self.basis[0]
        el = mesh.elements[ve]
        ext = self.body_model.layout.ext_map if self.coupled else mesh.dof_of_node
        n_ext = self.body_model.layout.ext_dofs if self.coupled else mesh.n_dofs
        G = np.zeros((n_t, self.n_u, len(ve)))
        H = np.zeros((n_t, len(ve), self.n_u))
        for j, (x, _, _) in enumerate(states):
            chord = x[el[:, 1]] - x[el[:, 0]]
            unit = chord / np.linalg.norm(chord, axis=1)[:, None]
            g_ext, h_ext = np.zeros((n_ext, len(ve))), np.zeros((len(ve), n_ext))
            for side, sign in ((0, -1.0), (1, 1.0)):
                d = ext[el[:, side]]  # (n_ve, 3)
                for c in range(3):
                    ok = d[:, c] >= 0
                    e_ok = np.flatnonzero(ok)
                    g_ext[d[ok, c], e_ok] += sign * unit[ok, c]
                    h_ext[e_ok, d[ok, c]] += sign * unit[ok, c] / mesh.length0[ve][ok]
            if self.coupled:
                Tt, Px = maps[j]
                G[j], H[j] = Tt @ g_ext, (Px.T @ h_ext.T).T
            else:
                G[j], H[j] = g_ext, h_ext
        rows, cols, vals = [], [], []
        for e in range(len(ve)):
            r = np.flatnonzero(np.abs(G[:, :, e]).max(axis=0) > 0)
            c = np.flatnonzero(np.abs(H[:, e, :]).max(axis=0) > 0)
            block = np.einsum("jr,jk,ji,ic,il->rkcl", G[:, r, e], E, self.maxwell_map[e],
                              H[:, e, c], E) / n_t
            ri = (r[:, None] * m + np.arange(m)).reshape(len(r), m, 1, 1)
            ci = (c[:, None] * m + np.arange(m)).reshape(1, 1, len(c), m)
            rows.append(np.broadcast_to(ri, block.shape).ravel())
            cols.append(np.broadcast_to(ci, block.shape).ravel())
            vals.append(block.ravel())
        size = self.n_unknowns
        return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows),
                                                    np.concatenate(cols))),
                             shape=(size, size))

    def _jacobian(self, tangents: FloatArray, indices: NDArray, indptr: NDArray
                  ) -> sp.bsr_matrix:
        """The block-sparse Jacobian from the tangent values (3, n_t, nnz) of every instant
        on the pattern ``(indices, indptr)``: the block of stored entry ``s`` is
        ``sum_j sum_b tangents[b, j, s] w_b[j]``."""
        m, nnz = self.n_terms, len(indices)
        blocks = sum(t.T @ w for t, w in zip(tangents, self._weights, strict=True))
        size = m * (len(indptr) - 1)
        return sp.bsr_matrix((blocks.reshape(nnz, m, m), indices, indptr),
                             shape=(size, size))

    def result(self, u: FloatArray, tension: FloatArray, history: list[float],
               counters: dict | None = None, success: bool = True, message: str = ""
               ) -> HarmonicResult:
        """The periodic response of the unknowns ``u`` (tensions at the instants)."""
        mesh, n, n_t = self.mesh, self.settings.harmonics, self.n_t
        X, dof, free = self.coefficients_of(u), mesh.dof_of_node, mesh.free_nodes
        t_out = self.period * np.arange(self.settings.output_points) / \
            self.settings.output_points
        E_out = _basis(t_out, self.omega, n)[0]
        # coefficients of every node (constrained and attached nodes from their motion, by
        # projection)
        coefficients = np.zeros((self.n_terms, mesh.n_nodes, 3))
        for k in range(self.n_terms):
            coefficients[k][free] = scatter_free(X[k, :mesh.n_dofs], dof)[free]
        bodies = self.body_motion(X)[0] if self.coupled else None
        xc = np.array([x[~free] for x, _, _ in self.states(X, bodies)])  # (n_t, n_c, 3)
        fit = np.linalg.lstsq(self.basis[0], xc.reshape(n_t, -1), rcond=None)[0]
        coefficients[:, ~free] = fit.reshape(self.n_terms, -1, 3)
        positions = np.einsum("tk,knc->tnc", E_out, coefficients)
        tension_out = _resample(tension, self.times, t_out, self.omega, n)
        body = {}
        if self.coupled:
            body = self._body_output(X, E_out)
        return HarmonicResult(period=self.period, omega=self.omega, coefficients=coefficients,
                              time=t_out, positions=positions, tension=tension_out,
                              static_positions=self.x_static.copy(),
                              iterations=len(history), residual_history=history, mesh=mesh,
                              settings=self.settings,
                              counters={"samples": n_t, "unknowns": self.n_unknowns,
                                        **(counters or {})},
                              success=success, status="converged" if success else "failed",
                              message=message or f"converged in {len(history)} Newton "
                                                 f"iterations ({n} harmonics)",
                              case=self.system_name, units=self.units, **body)

    def _body_output(self, X: FloatArray, E_out: FloatArray) -> dict[str, FloatArray]:
        """Body coefficients (2 n + 1, nb, 6) of the origin and of the rotation vector
        relative to the static orientation (held bodies: their static pose), and the pose
        (origin, rotation vector) over one period (n_out, nb, 6)."""
        bm, s0 = self.body_model, self.static_bodies
        coef = np.zeros((self.n_terms, len(bm.bodies), 6))
        coef[0, :, :3] = s0.r
        for b, d in enumerate(bm.body_dof):
            if d >= 0:
                coef[:, b] = X[:, d:d + 6]
        motion = np.einsum("tk,kbc->tbc", E_out, coef)
        pose = motion.copy()
        pose[:, :, 3:] = rotation_vector(rotation_matrix(motion[:, :, 3:]) @ s0.R[None])
        return {"body_coefficients": coef, "body_pose": pose}


class _Collector:
    """The instants' sparse tangents (K, C, M over the unknowns) gathered on the union of
    their sparsity patterns."""

    def __init__(self, n: int) -> None:
        self.n = n
        self.keys: list[NDArray] = []
        self.vals: list[NDArray] = []
        self.where: list[tuple[int, int, int]] = []

    def add(self, j: int, mats: list[sp.coo_matrix]) -> None:
        for b, mat in enumerate(mats):
            self.keys.append(mat.row.astype(np.int64) * self.n + mat.col)
            self.vals.append(mat.data)
            self.where.append((b, j, len(mat.data)))

    def values(self, n_t: int) -> tuple[NDArray, NDArray, FloatArray]:
        """The pattern's ``indices``, ``indptr`` and the values (3, n_t, nnz)."""
        keys = np.concatenate(self.keys)
        unique, slot = np.unique(keys, return_inverse=True)
        values = np.zeros((3 * n_t, len(unique)))
        which = np.concatenate([np.full(k, b * n_t + j) for b, j, k in self.where])
        np.add.at(values, (which, slot), np.concatenate(self.vals))
        rows = unique // self.n
        indptr = np.concatenate(([0], np.cumsum(np.bincount(rows, minlength=self.n))))
        return ((unique % self.n).astype(np.int32), indptr.astype(np.int32),
                values.reshape(3, n_t, -1))


def _check_wave_period(system: System, period: float) -> None:
    """A regular wave must repeat over the analysis period (and a random sea never does)."""
    waves = system.environment.waves
    if waves.kind == "random":
        raise MoorlineError(f"harmonic balance of {system.name}: a random sea is not periodic "
                            "(use a stochastic or dynamics analysis)")
    if waves.kind != "airy" or not waves.height:
        return
    ratio = period / waves.period
    if abs(ratio - round(ratio)) > 1e-9 * max(ratio, 1.0) or round(ratio) < 1:
        raise MoorlineError(f"harmonic balance of {system.name}: the wave period "
                            f"({waves.period:g}) must divide the analysis period ({period:g})")


@dataclass
class _BalanceTrial:
    r: FloatArray           # minus the harmonic-balance residual
    jacobian: Any
    extra: Any

    @property
    def has_tangent(self) -> bool:
        return self.jacobian is not None


class _BalanceProblem:
    """The harmonic-balance equations as a problem of the Newton core."""

    def __init__(self, evaluate) -> None:
        self.evaluate = evaluate

    def residual(self, u: FloatArray, tangent: bool) -> _BalanceTrial:
        R, J, extra = self.evaluate(u, tangent)
        return _BalanceTrial(-R, J, extra)

    def factorize(self, u: FloatArray, trial: _BalanceTrial):
        return factorize(trial.jacobian)

    def update(self, u: FloatArray, du: FloatArray) -> FloatArray:
        return u + du


def _newton(evaluate: Callable[[FloatArray, bool], tuple[FloatArray, sp.spmatrix | None,
                                                          Any]],
            u: FloatArray, tolerance: float, max_iterations: int, name: str,
            counters: Counters | None = None):
    """Newton-Raphson (a fresh Jacobian every iteration, the Newton core of
    :mod:`moorline.solvers.newton`) with backtracking on the largest residual.

    Parameters
    ----------
    evaluate
        ``evaluate(u, tangent) -> (residual, jacobian or None, extra)``.
    u
        Starting unknowns.
    tolerance
        Convergence when the largest residual is at most this (absolute).
    max_iterations
        Newton steps allowed.
    name
        For the messages.
    counters
        Accumulated work (a new one when not given).

    Returns
    -------
    outcome, counters, message
        The Newton core's :class:`~moorline.solvers.newton.Outcome` (``trial.extra`` holds
        the last evaluation's extra), its counters, and a message saying how it ended.
    """
    policy = NewtonPolicy(tolerance=tolerance, max_iterations=max_iterations,
                          stiffness_update=1, age_per="iteration", refresh_ratio=None,
                          stall_limit=0, max_halvings=7, merit="max")
    counters = counters if counters is not None else Counters()
    out = newton_solve(_BalanceProblem(evaluate), u, policy, TangentCache(), counters)
    if out.converged:
        return out, counters, ""
    if out.reason.startswith("singular"):
        return out, counters, f"{name}: {out.reason.replace('tangent', 'Jacobian')}"
    return out, counters, (f"{name}: Newton did not converge in {max_iterations} iterations "
                           f"(residual {out.norm:.3g}, tolerance {tolerance:.3g})")


def solve_harmonic(system: System, settings: HarmonicSettings,
                   statics: StaticResult | None = None) -> HarmonicResult:
    """Periodic response of a line system by harmonic balance.

    Parameters
    ----------
    system
        The problem (lines, points, bodies; periodic excitation).
    settings
        Period, harmonics, samples, tolerance.
    statics
        The static state to start from (solved when not given).

    Returns
    -------
    HarmonicResult
        ``success`` False (the last iterate, the message saying why) when Newton did not
        converge.

    Raises
    ------
    MoorlineError
        With bad settings.
    ConvergenceError
        When the static state it starts from did not converge.
    """
    balance = HarmonicBalance(system, settings, statics)
    name = f"harmonic balance of {system.name}"
    tolerance = settings.tolerance * balance.scale
    out, counters, message = _newton(balance.evaluate, balance.initial(), tolerance,
                                     settings.max_iterations, name)
    return balance.result(out.u, out.trial.extra, out.history[1:], counters.as_dict(),
                          out.converged, message)


def _resample(values: FloatArray, times: FloatArray, t_out: FloatArray, omega: float,
              n: int) -> FloatArray:
    """Trigonometric interpolation (the ``n`` harmonics) of samples over one period."""
    E = _basis(times, omega, n)[0]
    coef = np.linalg.lstsq(E, values, rcond=None)[0]
    return _basis(t_out, omega, n)[0] @ coef


__all__ = ["HarmonicBalance", "HarmonicResult", "HarmonicSettings", "solve_harmonic"]
