"""Rigid bodies in harmonic balance: the body motion as Fourier series and its kinematics.

A free body's six unknowns per harmonic are its origin ``r(t)`` and a rotation vector
``phi(t)`` relative to its static orientation, ``R(t) = exp([phi(t) x]) R_s``, each a real
Fourier series like the node positions (:mod:`moorline.solvers.harmonic`). The time-domain
body model (:class:`~moorline.solvers.body_model.BodyModel`) wants world angular velocity and
acceleration; for the left-acting exponential map (``d R R^T = [(J(phi) d phi) x]``, ``J`` the
left Jacobian of :func:`moorline.physics.rigid_body.left_jacobian`)

    omega = J(phi) phi',
    alpha = J(phi) phi'' + (dJ/dt) phi'
          = J phi'' + 2 (phi . phi') (b_s phi x phi' + c_s phi x (phi x phi'))
            + c phi' x (phi x phi'),

with ``J = I + b P + c P^2``, ``P = [phi x]``, ``b = (1 - cos t) / t^2``, ``c = (t - sin t) /
t^3``, ``t = |phi|``, and ``b_s``, ``c_s`` their derivatives with respect to ``s = t^2``
(the identity ``d/dt (P^2) phi' = phi' x (phi x phi')`` because ``phi' x phi' = 0``). The
derivatives of ``omega`` and ``alpha`` with respect to ``phi`` and ``phi'`` are taken by the
complex step (exact to round-off: the functions are analytic in ``s``, evaluated by series
near zero), so the harmonic-balance Jacobian stays exact.

Frequency-dependent radiation (:class:`~moorline.model.RadiationTable`) enters per harmonic:
the force of harmonic ``k`` is ``-A(k w) a_k - B(k w) v_k`` (``a_k``, ``v_k`` the harmonic-
``k`` parts of the body's generalized acceleration and velocity), which
:func:`radiation_matrices` tabulates.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from ..physics.rigid_body import rotation_matrix, rotation_vector, skew
from .assembly import gather_free
from .bodies import BodyState, refuse_pinned, transformation
from .body_model import BodyModel

FloatArray = NDArray[np.float64]

_SERIES = 1e-2  # |s| = |phi|^2 below this: the coefficients by their Taylor series


def _coefficients(s):
    """``b, c, db/ds, dc/ds`` of ``s = t^2`` (complex-safe; series for small ``|s|``)."""
    s = np.asarray(s)
    small = np.abs(s) < _SERIES
    ss = np.where(small, 1.0, s)
    t = np.sqrt(ss)
    one_minus_cos, t_minus_sin = 1.0 - np.cos(t), t - np.sin(t)
    b = one_minus_cos / ss
    c = t_minus_sin / (ss * t)
    db = (t * np.sin(t) - 2.0 * one_minus_cos) / (2.0 * ss * ss)
    dc = (one_minus_cos * t - 3.0 * t_minus_sin) / (2.0 * ss * ss * t)
    # Taylor series in s (truncation below 1e-15 relative for |s| < 1e-2)
    b_s = 1 / 2 - s / 24 + s**2 / 720 - s**3 / 40320 + s**4 / 3628800
    c_s = 1 / 6 - s / 120 + s**2 / 5040 - s**3 / 362880 + s**4 / 39916800
    db_s = -1 / 24 + s / 360 - s**2 / 13440 + s**3 / 907200
    dc_s = -1 / 120 + s / 2520 - s**2 / 120960 + s**3 / 9979200
    return (np.where(small, b_s, b), np.where(small, c_s, c), np.where(small, db_s, db),
            np.where(small, dc_s, dc))


def _cross(a, b):
    """Cross product of (..., 3) arrays (complex-safe)."""
    return np.stack((a[..., 1] * b[..., 2] - a[..., 2] * b[..., 1],
                     a[..., 2] * b[..., 0] - a[..., 0] * b[..., 2],
                     a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]), axis=-1)


def _omega_alpha(phi, dphi, ddphi):
    """World angular velocity and acceleration (..., 3) of ``R = exp([phi x]) R_s``."""
    s = np.einsum("...i,...i->...", phi, phi)
    b, c, db, dc = (x[..., None] for x in _coefficients(s))
    p_d = _cross(phi, dphi)
    pp_d = _cross(phi, p_d)
    omega = dphi + b * p_d + c * pp_d
    p_dd = _cross(phi, ddphi)
    jdd = ddphi + b * p_dd + c * _cross(phi, p_dd)
    rate = 2.0 * np.einsum("...i,...i->...", phi, dphi)[..., None]
    alpha = jdd + rate * (db * p_d + dc * pp_d) + c * _cross(dphi, p_d)
    return omega, alpha


def left_jacobians(phi: FloatArray) -> FloatArray:
    """``J(phi)`` (..., 3, 3) (the same series as the kinematics)."""
    s = np.einsum("...i,...i->...", phi, phi)
    b, c = (x[..., None, None] for x in _coefficients(s)[:2])
    P = skew(phi)
    return np.eye(3) + b * P + c * (P @ P)


def angular_kinematics(phi: FloatArray, dphi: FloatArray, ddphi: FloatArray
                       ) -> tuple[FloatArray, ...]:
    """Angular velocity and acceleration of rotation-vector histories, with derivatives.

    Parameters
    ----------
    phi, dphi, ddphi
        Rotation vector and its first two time derivatives at the instants (n, 3).

    Returns
    -------
    omega, alpha
        (n, 3) each.
    J
        ``d omega / d phi' = d alpha / d phi''`` = ``J(phi)`` (n, 3, 3), also the map of a
        change ``d phi`` to the left rotation it applies, ``d theta = J d phi``.
    d_omega_d_phi, d_alpha_d_phi, d_alpha_d_dphi
        (n, 3, 3) each, by the complex step.
    """
    phi, dphi, ddphi = (np.asarray(a, dtype=float) for a in (phi, dphi, ddphi))
    omega, alpha = _omega_alpha(phi, dphi, ddphi)
    h = 1e-30
    n = phi.shape[0]
    dw_dp, da_dp, da_dd = (np.zeros((n, 3, 3)) for _ in range(3))
    for i in range(3):
        e = np.zeros(3)
        e[i] = h
        w, al = _omega_alpha(phi + 1j * e, dphi, ddphi)
        dw_dp[:, :, i], da_dp[:, :, i] = w.imag / h, al.imag / h
        da_dd[:, :, i] = _omega_alpha(phi, dphi + 1j * e, ddphi)[1].imag / h
    return omega, alpha, left_jacobians(phi), dw_dp, da_dp, da_dd


def interpolate_radiation(table, omegas: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Added mass and damping of a :class:`~moorline.model.RadiationTable` at ``omegas``
    (m,): linear interpolation per coefficient, held at the table's first and last values
    outside it. Returns ``A``, ``B`` (m, 6, 6)."""
    w = np.asarray(table.omegas, dtype=float)
    A = np.asarray(table.added_mass, dtype=float).reshape(len(w), 36)
    B = np.asarray(table.damping, dtype=float).reshape(len(w), 36)
    omegas = np.asarray(omegas, dtype=float)
    out = [np.column_stack([np.interp(omegas, w, M[:, i]) for i in range(36)])
           .reshape(-1, 6, 6) for M in (A, B)]
    return out[0], out[1]


def radiation_matrices(table, omega: float, n: int) -> tuple[FloatArray, FloatArray]:
    """``A(k w)``, ``B(k w)`` per harmonic term (2 n + 1, 6, 6): the mean, then the cosine
    and the sine of every harmonic ``k`` (the same matrices for both). The mean's are zero:
    the radiation force has no mean (``B(0) = 0``, and a periodic motion's mean
    acceleration vanishes)."""
    k = np.repeat(np.arange(1, n + 1), 2)
    A, B = interpolate_radiation(table, k * omega)
    zero = np.zeros((1, 6, 6))
    return np.concatenate((zero, A)), np.concatenate((zero, B))




class BodyTerms:
    """The bodies' part of the harmonic-balance equations: their motion at the instants,
    each instant's coupled residual and tangent, radiation per harmonic and the output.

    Parameters
    ----------
    mesh
        The mesh (with bodies).
    fluid
        The fluid field (exciting-force tables, drag).
    pose
        The bodies' static poses (n_bodies, 6).
    basis
        ``E, E', E''`` at the instants (n_t, 2 n + 1) each.
    omega
        Fundamental circular frequency.
    node_mass
        Lumped node masses (n_nodes,).
    """

    def __init__(self, mesh, fluid, pose: FloatArray, basis: tuple[FloatArray, ...],
                 omega: float, node_mass: FloatArray) -> None:
        self.mesh, self.basis, self.node_mass = mesh, basis, node_mass
        self.n_t, self.n_terms = basis[0].shape
        refuse_pinned(mesh, "harmonic")
        self.static = BodyState.from_pose(pose)
        self.model = BodyModel(mesh, fluid, self.static, radiation_memory=False)
        self.n_u = self.model.layout.n_unknowns
        n = (self.n_terms - 1) // 2
        self.radiation = {b: radiation_matrices(body.radiation, omega, n)
                          for b, body in enumerate(self.model.bodies)
                          if body.radiation is not None and self.model.body_dof[b] >= 0}

    def initial(self, X: FloatArray) -> None:
        """Put the free bodies' static origins in the mean of the coefficients (in place)."""
        for b, d in enumerate(self.model.body_dof):
            if d >= 0:
                X[0, d:d + 3] = self.static.r[b]

    def motion(self, X: FloatArray) -> tuple[list[BodyState], dict]:
        """The bodies' states at every instant and, per free body, the kinematic chain
        ``(J, d omega / d phi, d alpha / d phi, d alpha / d phi')`` (each (n_t, 3, 3)) and
        the generalized velocity and acceleration (n_t, 6)."""
        bm, s0 = self.model, self.static
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

    def instant(self, x, a, bs: BodyState, motion: dict, j: int, t: float, ev,
                tangent: bool):
        """Residual (n_u,) of one instant of a system with bodies and, with ``tangent``, its
        derivatives with respect to the generalized coordinates, velocities and
        accelerations ``(K, C, M)`` (sparse, n_u x n_u), and the maps ``(T^T, P_x)`` of
        the lines' forces to the unknowns and of the unknowns to the node positions."""
        mesh, bm, layout = self.mesh, self.model, self.model.layout
        m_s = self.node_mass[:, None]
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
        nodes_m = self.node_mass[:, None, None] * np.eye(3)
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
        nb = len(self.model.bodies)
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
        for d, block in zip(self.model.body_dof, blocks, strict=True):
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

    def radiation_residual(self, motion: dict | None) -> FloatArray:
        """``sum_j E_j[k] (A_k acc_j + B_k vel_j)`` of the bodies with a radiation table
        (the harmonic-``k`` row with ``A(k w)``, ``B(k w)``), (2 n + 1, n_u)."""
        R = np.zeros((self.n_terms, self.n_u))
        E = self.basis[0]
        for b, (A, B) in self.radiation.items():
            d = self.model.body_dof[b]
            vel, acc = motion["vel"][:, b], motion["acc"][:, b]  # (n_t, 6)
            R[:, d:d + 6] += np.einsum("jk,kpq,jq->kp", E, A, acc) + \
                np.einsum("jk,kpq,jq->kp", E, B, vel)
        return R

    def radiation_jacobian(self, motion: dict | None) -> sp.csr_matrix | None:
        """The derivative of :meth:`_radiation_residual` (dense per body, sparse overall)."""
        if not self.radiation:
            return None
        E, dE, ddE = self.basis
        m, n_t = self.n_terms, self.n_t
        rows, cols, vals = [], [], []
        for b, (A, B) in self.radiation.items():
            d = self.model.body_dof[b]
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
        size = self.n_terms * self.n_u
        return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows),
                                                    np.concatenate(cols))),
                             shape=(size, size))

    def neutral_mean(self, J: sp.spmatrix) -> sp.csr_matrix | None:
        """A vanishing shift (1e-9 of the largest diagonal entry) of the free bodies' mean
        rows: a body free to turn about an axis with nothing resisting it (the yaw of a
        buoy on one line attached on its axis) has a neutral mean there, which leaves the
        Jacobian singular; the harmonics have inertia. As in the coupled statics
        (:mod:`moorline.solvers.coupled_statics`), the shift changes the Newton step, not
        the solution (the residual is unshifted)."""
        first = [d for d in self.model.body_dof if d >= 0]
        if not first:
            return None
        idx = ((np.asarray(first)[:, None] + np.arange(6)) * self.n_terms).ravel()
        shift = 1e-9 * float(np.abs(J.diagonal()).max(initial=1.0))
        size = self.n_terms * self.n_u
        return sp.csr_matrix((np.full(idx.size, shift), (idx, idx)), shape=(size, size))

    def output(self, X: FloatArray, E_out: FloatArray) -> dict[str, FloatArray]:
        """Body coefficients (2 n + 1, nb, 6) of the origin and of the rotation vector
        relative to the static orientation (held bodies: their static pose), and the pose
        (origin, rotation vector) over one period (n_out, nb, 6)."""
        bm, s0 = self.model, self.static
        coef = np.zeros((self.n_terms, len(bm.bodies), 6))
        coef[0, :, :3] = s0.r
        for b, d in enumerate(bm.body_dof):
            if d >= 0:
                coef[:, b] = X[:, d:d + 6]
        motion = np.einsum("tk,kbc->tbc", E_out, coef)
        pose = motion.copy()
        pose[:, :, 3:] = rotation_vector(rotation_matrix(motion[:, :, 3:]) @ s0.R[None])
        return {"body_coefficients": coef, "body_pose": pose}



class Collector:
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


__all__ = ["BodyTerms", "Collector", "angular_kinematics", "interpolate_radiation",
           "left_jacobians", "radiation_matrices"]
