"""Compiled implicit step for the common case: elastic lines (constant ``EA``, tension-strain
tables, the fibre-rope dynamic stiffness) in still water or a uniform current, on a seabed
with contact, damping and (isotropic) friction, Newmark beta = 1/4, gamma = 1/2 with
equilibrium iterations (Tuah 1982 eq. 4.2.7-4.2.11).

It is the same algorithm as :class:`moorline.solvers.newmark.Stepper` (same residual, same
exact tangent, same modified-Newton refresh rule, backtracking on the residual norm), moved
into one numba function per step so that Python overhead does not dominate a step that takes
tens of microseconds. The element loads come from :func:`moorline.physics.fused._kernel`; the
effective tangent is assembled straight into band storage (nodes ordered by reverse
Cuthill-McKee) and factored by a banded LU without pivoting (the effective tangent
``M / (beta h^2) + gamma C / (beta h) + K`` is dominated by its mass and stiffness blocks,
which are symmetric positive definite). Tests compare it step by step with the general
stepper.
"""

from __future__ import annotations

import math

import numba
import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray
from scipy.sparse.csgraph import reverse_cuthill_mckee

from ..physics.fused import _kernel

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]

_JIT = {"cache": True, "fastmath": False, "error_model": "numpy"}


def band_ordering(elements: IntArray, dof_of_node: IntArray) -> tuple[IntArray, int]:
    """Band position of every node dof (``-1`` for constrained) and the half bandwidth.

    Free nodes are ordered by reverse Cuthill-McKee on the element graph, their three dofs
    kept together.
    """
    n_nodes = len(dof_of_node)
    free = dof_of_node[:, 0] >= 0
    index = np.full(n_nodes, -1, dtype=np.int64)
    index[free] = np.arange(int(free.sum()))
    both = free[elements[:, 0]] & free[elements[:, 1]]
    a, b = index[elements[both, 0]], index[elements[both, 1]]
    n_free = int(free.sum())
    graph = sp.csr_matrix((np.ones(2 * len(a)), (np.r_[a, b], np.r_[b, a])),
                          shape=(n_free, n_free))
    order = reverse_cuthill_mckee(graph, symmetric_mode=True) if n_free else np.zeros(0, int)
    rank = np.empty(n_free, dtype=np.int64)
    rank[order] = np.arange(n_free)
    band = np.full((n_nodes, 3), -1, dtype=np.int64)
    band[free] = 3 * rank[index[free]][:, None] + np.arange(3)
    spread = np.abs(rank[a] - rank[b]).max(initial=0) if len(a) else 0
    return band, int(3 * spread + 2)


@numba.njit(**_JIT)
def _band_lu(ab, bw):
    """In-place LU (no pivoting) of a band matrix stored as ``ab[i, j - i + bw]``."""
    n = ab.shape[0]
    for k in range(n):
        pivot = ab[k, bw]
        if pivot == 0.0:
            return False
        for i in range(k + 1, min(n, k + bw + 1)):
            f = ab[i, k - i + bw] / pivot
            ab[i, k - i + bw] = f
            if f != 0.0:
                for j in range(k + 1, min(n, k + bw + 1)):
                    ab[i, j - i + bw] -= f * ab[k, j - k + bw]
    return True


@numba.njit(**_JIT)
def _band_solve(lu, bw, b):
    """Solve in place with the factors of :func:`_band_lu`."""
    n = lu.shape[0]
    for i in range(n):
        s = b[i]
        for j in range(max(0, i - bw), i):
            s -= lu[i, j - i + bw] * b[j]
        b[i] = s
    for i in range(n - 1, -1, -1):
        s = b[i]
        for j in range(i + 1, min(n, i + bw + 1)):
            s -= lu[i, j - i + bw] * b[j]
        b[i] = s / lu[i, bw]


@numba.njit(**_JIT)
def _seabed(x, v, seabed_z, k, c, ramp, mu, v_slip, force, kzz, czz, fric_c, fric_kz, fric_cz):
    """Seabed contact (:func:`moorline.physics.seabed.contact_force`, pushing only) and
    isotropic regularized friction (:func:`~moorline.physics.seabed.friction_force` with equal
    coefficients) per node, with their tangent terms (K = -dF/dx, C = -dF/dv)."""
    for n in range(x.shape[0]):
        kzz[n] = 0.0
        czz[n] = 0.0
        for r in range(2):
            fric_kz[n, r] = 0.0
            fric_cz[n, r] = 0.0
            for s in range(2):
                fric_c[n, r, s] = 0.0
        p = seabed_z - x[n, 2]
        q = p + 0.5 * ramp[n]
        if q <= 0.0:
            continue
        share = min(q / ramp[n], 1.0)
        full = q >= ramp[n]
        spring = k[n] * p if full else 0.5 * k[n] * q * share
        total = spring - c[n] * share * v[n, 2]
        if total <= 0.0:
            continue
        force[n, 2] += total
        d_spring = k[n] if full else k[n] * share
        d_damp = 0.0 if full else c[n] * v[n, 2] / ramp[n]
        kzz[n] = d_spring - d_damp  # -d(total)/dz
        czz[n] = c[n] * share       # -d(total)/dvz
        if mu == 0.0:
            continue
        vx, vy = v[n, 0], v[n, 1]
        speed = math.sqrt(vx * vx + vy * vy)
        th = math.tanh(speed / v_slip)
        ratio = th / speed if speed > 0.0 else 1.0 / v_slip
        force[n, 0] += -mu * total * ratio * vx
        force[n, 1] += -mu * total * ratio * vy
        ux = vx / speed if speed > 0.0 else 0.0
        uy = vy / speed if speed > 0.0 else 0.0
        for r in range(2):
            ur = ux if r == 0 else uy
            for s in range(2):
                us = ux if s == 0 else uy
                eye = 1.0 if r == s else 0.0
                dfdv = -mu * total * (ratio * (eye - ur * us)
                                      + (1.0 - th * th) / v_slip * ur * us)
                fric_c[n, r, s] = -dfdv
            dfdn = -mu * ratio * (vx if r == 0 else vy)
            fric_kz[n, r] = dfdn * kzz[n]  # -dF_r/dz = -dfdn dN/dz
            fric_cz[n, r] = dfdn * czz[n]  # -dF_r/dvz = -dfdn dN/dvz


@numba.njit(**_JIT)
def _evaluate(x, v, a, uf, af, elements, props, laws, with_drag, with_added_mass, node_mass,
              external, point_force, seabed_on, seabed_z, k_sb, c_sb, ramp, mu, v_slip, tangent,
              buf):
    """All nodal forces minus structural inertia at (x, v, a); fills ``buf``'s arrays."""
    (el_forces, total, f_am, tension, strain, taut, K, C, Ma, nodal, nodal_am, resid,
     kzz, czz, fric_c, fric_kz, fric_cz) = buf
    _kernel(x, v, a, uf, af, elements, props, laws, tangent, with_drag, with_added_mass,
            el_forces, total, f_am, tension, strain, taut, K, C, Ma, nodal, nodal_am)
    for n in range(x.shape[0]):
        for c in range(3):
            resid[n, c] = nodal[n, c] + external[n, c] + point_force[n, c] \
                - node_mass[n] * a[n, c]
    if seabed_on:
        _seabed(x, v, seabed_z, k_sb, c_sb, ramp, mu, v_slip, resid, kzz, czz, fric_c,
                fric_kz, fric_cz)


@numba.njit(**_JIT)
def _norm_inf_free(resid, band, out):
    """Gather the free dofs of ``resid`` into ``out`` (band order); return max |r| (``inf``
    when an entry is NaN: a NaN state never passes for converged)."""
    m = 0.0
    for n in range(resid.shape[0]):
        for c in range(3):
            k = band[n, c]
            if k >= 0:
                out[k] = resid[n, c]
                a = abs(out[k])
                if not (a <= m):
                    m = a if a == a else math.inf
    return m


@numba.njit(**_JIT)
def _assemble(ab, bw, band, elements, K, C, Ma, with_added_mass, node_mass, ca, cv, kzz, czz,
              fric_c, fric_kz, fric_cz, seabed_on):
    ab[:, :] = 0.0
    for e in range(elements.shape[0]):
        for p in range(6):
            row = band[elements[e, p // 3], p % 3]
            if row < 0:
                continue
            for q in range(6):
                col = band[elements[e, q // 3], q % 3]
                if col < 0:
                    continue
                val = K[e, p, q] + cv * C[e, p, q]
                if with_added_mass:
                    val += ca * Ma[e, p, q]
                ab[row, col - row + bw] += val
    for n in range(band.shape[0]):
        if band[n, 0] < 0:
            continue
        for c in range(3):
            k = band[n, c]
            ab[k, bw] += ca * node_mass[n]
        if seabed_on:
            kz = band[n, 2]
            ab[kz, bw] += kzz[n] + cv * czz[n]
            for r in range(2):
                kr = band[n, r]
                for s in range(2):
                    ab[kr, band[n, s] - kr + bw] += cv * fric_c[n, r, s]
                ab[kr, kz - kr + bw] += fric_kz[n, r] + cv * fric_cz[n, r]


@numba.njit(**_JIT)
def _kinematics(x0, v0, a0, x1, h, beta, gamma, free, v1, a1):
    for n in range(x1.shape[0]):
        if not free[n]:
            continue
        for c in range(3):
            acc = (x1[n, c] - x0[n, c] - h * v0[n, c] - h * h * (0.5 - beta) * a0[n, c]) \
                / (beta * h * h)
            a1[n, c] = acc
            v1[n, c] = v0[n, c] + h * ((1.0 - gamma) * a0[n, c] + gamma * acc)


@numba.njit(**_JIT)
def newmark_step(x0, v0, a0, x1, v1, a1, free, band, bw, elements, props, laws, with_drag,
                 with_added_mass, node_mass, external, point_force, uf, af, seabed_on,
                 seabed_z, k_sb, c_sb, ramp, mu, v_slip, h, beta, gamma, tol, max_iter,
                 refresh, lu, buf, rvec, trial, counters, refresh_ratio, stall_ratio,
                 stall_limit, max_halvings):
    """One Newmark step with modified-Newton iterations: the algorithm of
    :func:`moorline.solvers.newton.solve` (same refresh, line-search, stale-tangent and stall
    rules, constants from the same :class:`~moorline.solvers.newton.NewtonPolicy`).

    On entry ``x1, v1, a1`` hold the constrained nodes' kinematics at the new time (free
    nodes are predicted here). ``lu`` holds the factored effective tangent when
    ``refresh`` is False. ``counters`` accumulates [iterations, residuals, factorizations].
    Returns (converged, final max-norm, whether the tangent was factored this step).
    """
    ca = 1.0 / (beta * h * h)
    cv = gamma / (beta * h)
    for n in range(x1.shape[0]):
        if free[n]:
            for c in range(3):
                x1[n, c] = x0[n, c] + h * v0[n, c] + 0.5 * h * h * a0[n, c]
    _kinematics(x0, v0, a0, x1, h, beta, gamma, free, v1, a1)
    _evaluate(x1, v1, a1, uf, af, elements, props, laws, with_drag, with_added_mass,
              node_mass, external, point_force, seabed_on, seabed_z, k_sb, c_sb, ramp, mu,
              v_slip, refresh, buf)
    counters[1] += 1
    norm = _norm_inf_free(buf[11], band, rvec)
    have_tangent = refresh
    refactored = False
    stalled = 0
    for _ in range(max_iter):
        if norm <= tol:
            return True, norm, refactored
        if refresh:
            if not have_tangent:
                _evaluate(x1, v1, a1, uf, af, elements, props, laws, with_drag,
                          with_added_mass, node_mass, external, point_force, seabed_on,
                          seabed_z, k_sb, c_sb, ramp, mu, v_slip, True, buf)
                counters[1] += 1
                norm = _norm_inf_free(buf[11], band, rvec)
            _assemble(lu, bw, band, elements, buf[6], buf[7], buf[8], with_added_mass,
                      node_mass, ca, cv, buf[12], buf[13], buf[14], buf[15], buf[16],
                      seabed_on)
            if not _band_lu(lu, bw):
                return False, norm, refactored
            counters[2] += 1
            refactored = True
            refresh = False
        merit0 = 0.0
        for k in range(rvec.shape[0]):
            merit0 += rvec[k] * rvec[k]
        dx = rvec.copy()
        _band_solve(lu, bw, dx)
        counters[0] += 1
        alpha = 1.0
        better = False
        for _ls in range(max_halvings + 1):
            for n in range(x1.shape[0]):
                for c in range(3):
                    k = band[n, c]
                    trial[n, c] = x1[n, c] + (alpha * dx[k] if k >= 0 else 0.0)
            _kinematics(x0, v0, a0, trial, h, beta, gamma, free, v1, a1)
            _evaluate(trial, v1, a1, uf, af, elements, props, laws, with_drag,
                      with_added_mass, node_mass, external, point_force, seabed_on, seabed_z,
                      k_sb, c_sb, ramp, mu, v_slip, True, buf)
            counters[1] += 1
            n_new = _norm_inf_free(buf[11], band, rvec)
            merit = 0.0
            for k in range(rvec.shape[0]):
                merit += rvec[k] * rvec[k]
            if merit < merit0:
                better = True
                break
            alpha *= 0.5
        if not better and not refactored:
            # a stale tangent: refresh it at the same point and retry
            refresh = True
            have_tangent = False
            _kinematics(x0, v0, a0, x1, h, beta, gamma, free, v1, a1)
            continue
        have_tangent = True
        if n_new > refresh_ratio * norm:
            refresh = True
        stalled = stalled + 1 if n_new > stall_ratio * norm else 0
        x1[:, :] = trial
        norm = n_new
        if stall_limit > 0 and stalled >= stall_limit:
            return False, norm, refactored
    return norm <= tol, norm, refactored


def make_buffers(n_el: int, n_nodes: int) -> tuple:
    """Work arrays of :func:`newmark_step`."""
    e = np.empty
    return (e((n_el, 2, 3)), e((n_el, 2, 3)), e((n_el, 2, 3)), e(n_el), e(n_el),
            e(n_el, dtype=np.bool_), e((n_el, 6, 6)), e((n_el, 6, 6)), e((n_el, 6, 6)),
            e((n_nodes, 3)), e((n_nodes, 3)), e((n_nodes, 3)), np.zeros(n_nodes),
            np.zeros(n_nodes), np.zeros((n_nodes, 2, 2)), np.zeros((n_nodes, 2)),
            np.zeros((n_nodes, 2)))


class FastStepper:
    """The compiled backend of :class:`~moorline.solvers.newmark.Stepper`: the same step
    (see :func:`~moorline.solvers.fast_path.fast_path_reason` for when it applies), run by
    :func:`newmark_step`."""

    def __init__(self, model, coefficients, policy) -> None:
        mesh = model.mesh
        self.model = model
        self.c = coefficients
        self.policy = policy
        self.band, self.bw = band_ordering(mesh.elements, mesh.dof_of_node)
        self.free = mesh.free_nodes
        n_dof = int(self.free.sum()) * 3
        self.lu = np.zeros((n_dof, 2 * self.bw + 1))
        self.lu_h, self.lu_age, self.lu_valid = np.nan, 0, False
        self.buf = make_buffers(mesh.n_elements, mesh.n_nodes)
        self.rvec = np.zeros(n_dof)
        self.trial = np.zeros((mesh.n_nodes, 3))
        self.counts = np.zeros(3, dtype=np.int64)
        self.fused = model._fused
        self.seabed_on = bool(np.isfinite(mesh.seabed_z))
        self.mu, self.v_slip = (model.friction[0], model.friction[2]) if model.friction \
            else (0.0, 1.0)
        self.dof = mesh.dof_of_node
        from ..waves import StillWater

        zeros = np.zeros((mesh.n_elements, 3))
        self._still = (zeros, zeros) if isinstance(model.fluid, StillWater) else None
        self._no_forces = np.zeros((mesh.n_nodes, 3))

    def forget_tangent(self) -> None:
        """Drop the factorization (after a step cut)."""
        self.lu_valid = False

    def tangent_state(self) -> tuple:
        """The banded factors and their age (see :meth:`Stepper.tangent_state`)."""
        return self.lu.copy(), self.lu_h, self.lu_age, self.lu_valid

    def set_tangent_state(self, saved: tuple) -> None:
        """Restore what :meth:`tangent_state` returned."""
        lu, self.lu_h, self.lu_age, self.lu_valid = saved
        self.lu[...] = lu

    @property
    def counters(self) -> dict:
        """Same keys as :class:`~moorline.solvers.newmark.Stepper`."""
        it, res, fac = (int(v) for v in self.counts)
        return {"iterations": it, "residuals": res, "tangents": fac, "factorizations": fac}

    def _fluid(self, t: float, x: FloatArray) -> tuple[FloatArray, FloatArray]:
        """Fluid velocity and acceleration at the element midpoints (cached zeros in still
        water)."""
        if self._still is not None:
            return self._still
        el = self.model.mesh.elements
        mid = 0.5 * (x[el[:, 0]] + x[el[:, 1]])
        u, a, _ = self.model.fluid.kinematics(mid, t)
        return np.ascontiguousarray(u, dtype=float), np.ascontiguousarray(a, dtype=float)

    def step(self, s0, h: float, constrained, point_forces):
        """Advance from ``s0`` by ``h`` (see :meth:`Stepper.step`)."""
        from .dynamic_model import Evaluation, MaterialState
        from .newmark import StepState

        mesh = self.model.mesh
        x1 = np.empty_like(s0.x)
        v1 = np.empty_like(s0.v)
        a1 = np.empty_like(s0.a)
        fixed = ~self.free
        x1[fixed], v1[fixed], a1[fixed] = constrained
        uf, af = self._fluid(s0.t + h, s0.x)
        forces = point_forces if point_forces is not None else self._no_forces
        pol = self.policy
        refresh = (not self.lu_valid) or self.lu_h != h or self.lu_age >= pol.stiffness_update
        f = self.fused
        m = self.model
        ok, norm, refactored = newmark_step(
            s0.x, s0.v, s0.a, x1, v1, a1, self.free, self.band, self.bw, mesh.elements,
            f.props, f.laws, f.with_drag, f.with_added_mass, m.node_mass, m.external, forces,
            uf, af,
            self.seabed_on, float(mesh.seabed_z), m.k_seabed, m.c_seabed, m.seabed_ramp,
            self.mu, self.v_slip, h, self.c.beta, self.c.gamma, pol.tolerance,
            pol.max_iterations, refresh, self.lu, self.buf, self.rvec, self.trial, self.counts,
            np.inf if pol.refresh_ratio is None else pol.refresh_ratio, pol.stall_ratio,
            pol.stall_limit, pol.max_halvings)
        if refactored:
            self.lu_valid, self.lu_h, self.lu_age = True, h, 0
        if not ok:
            self.lu_valid = False
            return s0, False, float(norm)
        self.lu_age += 1
        el_forces, tension, strain = self.buf[0].copy(), self.buf[3].copy(), self.buf[4].copy()
        nodal = self.buf[11] + m.node_mass[:, None] * a1  # F without structural inertia
        ev = Evaluation(nodal, self.buf[10].copy(), tension,
                        MaterialState(strain, s0.material.maxwell), el_forces)
        return StepState(s0.t + h, x1, v1, a1, ev.material, ev), True, float(norm)

