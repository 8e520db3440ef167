"""Compiled implicit step for the common case: elastic lines (constant ``EA``, tension-strain
tables, the fibre-rope dynamic stiffness, sag-corrected elements, whose ``phi`` on the flat
seabed is computed here) and viscoelastic ones (the standard linear solid, exponential
update, its state carried from step to step) in still water, a current (uniform or a profile
over depth), Airy waves or a sea of linear components (no or Wheeler stretching), on a seabed
with contact, damping and friction (isotropic, or axial and transverse), Newmark beta = 1/4,
gamma = 1/2 or HHT-alpha (Hilber, Hughes and Taylor 1977: the non-inertial forces weighted
``1 + alpha`` at the new time and ``-alpha`` at the old) with equilibrium iterations (Tuah
1982 eq. 4.2.7-4.2.11).

It is the same algorithm as :class:`moorline.solvers.newmark.Stepper` (same residual, same
exact tangent, same modified-Newton refresh rule, backtracking on the residual norm), moved
into one numba function per step so that Python overhead does not dominate a step that takes
tens of microseconds. The element loads come from :func:`moorline.physics.fused._kernel`; the
effective tangent is assembled straight into band storage (nodes ordered by reverse
Cuthill-McKee) and factored by a banded LU without pivoting (the effective tangent
``M / (beta h^2) + gamma C / (beta h) + K`` is dominated by its mass and stiffness blocks,
which are symmetric positive definite). Free rigid bodies border the band with their six
unknowns each (:mod:`moorline.solvers.fast_bodies`: Schur complement on the body unknowns).
Tests compare it step by step with the general stepper.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..jit import numba
from ..physics.fused import _kernel, hht_stiffness, set_dashpot_shares, set_viscoelastic_step
from . import fast_bodies as fb
from .fast_fluid import fluid_at_midpoints
from .fast_path import fluid_parts
from .rcm import edge_pattern, reverse_cuthill_mckee

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
    order = reverse_cuthill_mckee(*edge_pattern(a, b, n_free)) if n_free else np.zeros(0, int)
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
def _seabed(x, v, seabed_z, k, c, ramp, mu, v_slip, force, kzz, czz, fric_c, fric_kz, fric_cz,
            elements):
    """Seabed contact (:func:`moorline.physics.seabed.contact_force`, pushing only) and
    regularized friction (:func:`~moorline.physics.seabed.friction_force`; ``mu`` the axial
    and transverse coefficients: equal, the isotropic law; different, each resists the
    velocity's part along / across the line, whose direction at a node is the horizontal
    mean of its elements' chords, ``DynamicModel._friction``, its change with the positions
    left out of the tangent as there) per node, with their tangent terms (K = -dF/dx,
    C = -dF/dv)."""
    mu_a, mu_t = mu
    axes = _node_axes(x, elements) if mu_a != mu_t else np.zeros((0, 2))
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
        if mu_a != mu_t:
            _directional_friction(n, v, total, axes[n, 0], axes[n, 1], mu_a, mu_t, v_slip,
                                  force, kzz, czz, fric_c, fric_kz, fric_cz)
            continue
        mu_i = mu_a
        if mu_i == 0.0:
            continue
        vx, vy = v[n, 0], v[n, 1]
        speed = math.sqrt(vx * vx + vy * vy)
        th = math.tanh(speed / v_slip)
        ratio = th / speed if speed > 0.0 else 1.0 / v_slip
        force[n, 0] += -mu_i * total * ratio * vx
        force[n, 1] += -mu_i * total * ratio * vy
        ux = vx / speed if speed > 0.0 else 0.0
        uy = vy / speed if speed > 0.0 else 0.0
        for r in range(2):
            ur = ux if r == 0 else uy
            for s in range(2):
                us = ux if s == 0 else uy
                eye = 1.0 if r == s else 0.0
                dfdv = -mu_i * total * (ratio * (eye - ur * us)
                                        + (1.0 - th * th) / v_slip * ur * us)
                fric_c[n, r, s] = -dfdv
            dfdn = -mu_i * ratio * (vx if r == 0 else vy)
            fric_kz[n, r] = dfdn * kzz[n]  # -dF_r/dz = -dfdn dN/dz
            fric_cz[n, r] = dfdn * czz[n]  # -dF_r/dvz = -dfdn dN/dvz


@numba.njit(**_JIT)
def _node_axes(x, elements):
    """Unit horizontal direction of the line at each node: the sum of its elements' chords,
    horizontal part, normalized (+x where it vanishes), as ``DynamicModel._friction`` on a
    flat seabed."""
    axes = np.zeros((x.shape[0], 2))
    for e in range(elements.shape[0]):
        i, j = elements[e, 0], elements[e, 1]
        for c in range(2):
            chord = x[j, c] - x[i, c]
            axes[i, c] += chord
            axes[j, c] += chord
    for n in range(x.shape[0]):
        norm = math.sqrt(axes[n, 0] * axes[n, 0] + axes[n, 1] * axes[n, 1])
        if norm > 0.0:
            axes[n, 0] /= max(norm, 1e-300)
            axes[n, 1] /= max(norm, 1e-300)
        else:
            axes[n, 0], axes[n, 1] = 1.0, 0.0
    return axes


@numba.njit(**_JIT)
def _directional_friction(n, v, total, ax, ay, mu_a, mu_t, v_slip, force, kzz, czz, fric_c,
                          fric_kz, fric_cz):
    """Node ``n``'s friction along the line (``(ax, ay)``, coefficient ``mu_a``) and across it
    (``(-ay, ax)``, ``mu_t``), each ``-mu N tanh(v_d / v_s)`` along its direction
    (:func:`moorline.physics.seabed.friction_force`), and its tangent terms."""
    for d in range(2):
        mu_d = mu_a if d == 0 else mu_t
        if mu_d == 0.0:
            continue
        dx, dy = (ax, ay) if d == 0 else (-ay, ax)
        th = math.tanh((v[n, 0] * dx + v[n, 1] * dy) / v_slip)
        f = -mu_d * total * th
        force[n, 0] += f * dx
        force[n, 1] += f * dy
        slope = -mu_d * total * (1.0 - th * th) / v_slip
        for r in range(2):
            dr = dx if r == 0 else dy
            for s in range(2):
                ds = dx if s == 0 else dy
                fric_c[n, r, s] -= slope * dr * ds
            dfdn = -mu_d * th * dr
            fric_kz[n, r] += dfdn * kzz[n]
            fric_cz[n, r] += dfdn * czz[n]


@numba.njit(**_JIT)
def _sag_share(x, elements, active, seabed_on, seabed_z, k, ramp, load, phi, dphi):
    """``phi`` and ``dphi/dx`` of the sag correction on a flat seabed
    (:meth:`moorline.physics.sag.SagCorrection.share` with
    :func:`moorline.physics.seabed.carried_share`)."""
    for e in range(elements.shape[0]):
        for m in range(2):
            for c in range(3):
                dphi[e, m, c] = 0.0
        phi[e] = active[e]
    if not seabed_on:
        return
    for e in range(elements.shape[0]):
        share = (0.0, 0.0)
        slope = (0.0, 0.0)
        for m in range(2):
            n = elements[e, m]
            p = -(x[n, 2] - seabed_z)
            q = p + 0.5 * ramp[n]
            sh = 0.0
            sl = 0.0
            half = 0.5 * load[n]
            if q > 0 and half > 0:
                full = q >= ramp[n]
                c_share = min(q / ramp[n], 1.0)
                spring = k[n] * p if full else 0.5 * k[n] * q * c_share
                if spring > 0:
                    d_spring = -(k[n] if full else k[n] * c_share)
                    u = spring / half
                    uc = min(max(u, 0.0), 1.0)
                    sh = uc * uc * (3.0 - 2.0 * uc)
                    if u < 1:
                        sl = 6.0 * uc * (1.0 - uc) * d_spring / half
            if m == 0:
                share = (sh, share[1])
                slope = (sl, slope[1])
            else:
                share = (share[0], sh)
                slope = (slope[0], sl)
        phi[e] = active[e] * (1.0 - share[0] * share[1])
        dphi[e, 0, 2] = -active[e] * share[1] * slope[0]
        dphi[e, 1, 2] = -active[e] * share[0] * slope[1]


@numba.njit(**_JIT)
def _evaluate(x, v, a, uf, af, elements, props, laws, with_drag, with_added_mass, node_mass,
              external, point_force, seabed_on, seabed_z, k_sb, c_sb, ramp, mu, v_slip, sag_on,
              sag_active, sag_load, tangent, buf):
    """All nodal forces minus structural inertia at (x, v, a); fills ``buf``'s arrays."""
    (el_forces, total, f_am, tension, strain, taut, K, C, Ma, nodal, nodal_am, resid,
     kzz, czz, fric_c, fric_kz, fric_cz, phi, dphi, Ka) = buf
    if sag_on:
        _sag_share(x, elements, sag_active, seabed_on, seabed_z, k_sb, ramp, sag_load, phi,
                   dphi)
    _kernel(x, v, a, uf, af, elements, props, laws, sag_on, phi, dphi, tangent, with_drag,
            with_added_mass, el_forces, total, f_am, tension, strain, taut, K, C, Ma, nodal,
            nodal_am, Ka)
    for n in range(x.shape[0]):
        for c in range(3):
            resid[n, c] = nodal[n, c] + external[n, c] + point_force[n, c] \
                - node_mass[n] * a[n, c]
    if seabed_on:
        _seabed(x, v, seabed_z, k_sb, c_sb, ramp, mu, v_slip, resid, kzz, czz, fric_c,
                fric_kz, fric_cz, elements)


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
def _residual_norm(buf, band, rvec, alpha, node_mass, a, f_am, other0):
    """The step's residual gathered into ``rvec`` (band order) and its max-norm: Newmark's
    ``F - M_s a`` (``buf[11]``), or with ``alpha != 0`` HHT's
    ``(1 + alpha) (F - F_am) - alpha (F0 - F_am0) + F_am - M_s a`` (Hilber, Hughes and Taylor
    1977; :mod:`moorline.solvers.newmark`, eq. 4.2.10 weighted), ``F`` all nodal forces
    without structural inertia, ``F_am`` their added-mass part, ``other0 = F0 - F_am0`` at the
    start of the step."""
    resid = buf[11]
    if alpha == 0.0:
        return _norm_inf_free(resid, band, rvec)
    m = 0.0
    for n in range(resid.shape[0]):
        for c in range(3):
            k = band[n, c]
            if k >= 0:
                inertial = f_am[n, c] - node_mass[n] * a[n, c]
                other = resid[n, c] + node_mass[n] * a[n, c] - f_am[n, c]
                rvec[k] = (1 + alpha) * other - alpha * other0[n, c] + inertial
                r = abs(rvec[k])
                if not (r <= m):
                    m = r if r == r else math.inf
    return m


@numba.njit(**_JIT)
def _assemble(ab, bw, band, elements, K, C, Ma, Ka, with_added_mass, node_mass, ca, cv, ck,
              kzz, czz, fric_c, fric_kz, fric_cz, seabed_on):
    """The effective tangent ``ca (M_s + M_a) + cv C + ck K`` in band storage (with HHT
    ``ck = 1 + alpha`` and ``cv`` weighted by it, eq. 4.2.9a; the added-mass forces' part
    ``Ka`` of ``K`` weighted 1, as they are in the residual)."""
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
                val = hht_stiffness(K, Ka, with_added_mass, ck, e, p, q) + cv * C[e, p, q]
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
            ab[kz, bw] += ck * kzz[n] + cv * czz[n]
            for r in range(2):
                kr = band[n, r]
                for s in range(2):
                    ab[kr, band[n, s] - kr + bw] += cv * fric_c[n, r, s]
                ab[kr, kz - kr + bw] += ck * fric_kz[n, r] + cv * fric_cz[n, r]


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
                 seabed_z, k_sb, c_sb, ramp, mu, v_slip, sag_on, sag_active, sag_load, h, beta,
                 gamma, alpha, other0, strain0, maxwell0, tol,
                 max_iter, refresh, lu, buf, rvec, trial, counters, refresh_ratio, stall_ratio,
                 stall_limit, max_halvings, fluid, j, bodies, local):
    """One Newmark (or HHT-alpha: ``alpha`` and the non-inertial forces at the start of the
    step ``other0``, :func:`_residual_norm`) step with modified-Newton iterations: the
    algorithm of :func:`moorline.solvers.newton.solve` (same refresh, line-search,
    stale-tangent and stall rules, constants from the same
    :class:`~moorline.solvers.newton.NewtonPolicy`).

    On entry ``x1, v1, a1`` hold the constrained nodes' kinematics at the new time (free
    nodes are predicted here). Line-search trials are evaluated without the tangent blocks
    (half the cost); the tangent is evaluated at the iterate when it is refreshed (the same
    numbers as evaluating it with every trial, one more residual count). ``lu`` holds the
    factored effective tangent when ``refresh`` is False. ``counters`` accumulates
    [iterations, residuals, factorizations]. The fluid velocity and acceleration ``uf, af``
    come from ``fluid`` at sub-step ``j`` at every evaluated state
    (:func:`~moorline.solvers.fast_fluid.fluid_at_midpoints`, as the general stepper's
    model evaluates them) when it has waves or a current. ``strain0``, ``maxwell0``: the
    elements' strains and Maxwell-branch forces at the start of the step (the material state
    of :class:`~moorline.solvers.dynamic_model.MaterialState`), which set the dashpot shares
    and the viscoelastic elements' update held over the step
    (:func:`~moorline.physics.fused.set_viscoelastic_step`). ``bodies``: the free rigid
    bodies, their state and the border of the tangent (:mod:`moorline.solvers.fast_bodies`;
    None without bodies); ``rvec`` then has their ``6 nb`` rows after the band's.
    ``local``: the local phase's (iterations, fraction, pad, max share, node incidence,
    work arrays)
    (:func:`moorline.solvers.fast_local.local_phase`; without bodies), ``counters[3]`` its
    iterations; None: no local phase (numba then compiles this step without its code, which
    loads faster: :data:`moorline.solvers.dynamics.LOCAL_MIN_FREE_NODES`).
    Returns (converged, final max-norm, whether the tangent was factored this step).
    """
    ca = 1.0 / (beta * h * h)
    cv = (1 + alpha) * gamma / (beta * h)
    ck = 1.0 + alpha
    set_dashpot_shares(strain0, props)  # held over the step
    set_viscoelastic_step(strain0, maxwell0, h, props)
    for n in range(x1.shape[0]):  # predictor x0 + h v0 (Stepper._predict)
        if free[n]:
            for c in range(3):
                x1[n, c] = x0[n, c] + h * v0[n, c]
    fb.predict(bodies, h, j)
    _kinematics(x0, v0, a0, x1, h, beta, gamma, free, v1, a1)
    fb.place(bodies, np.bool_(False), h, beta, gamma, x1, v1, a1)
    moving = fluid[0] or fluid[6]
    if moving:
        fluid_at_midpoints(x1, elements, j, fluid, uf, af)
    _evaluate(x1, v1, a1, uf, af, elements, props, laws, with_drag, with_added_mass,
              node_mass, external, point_force, seabed_on, seabed_z, k_sb, c_sb, ramp, mu,
              v_slip, sag_on, sag_active, sag_load, refresh, buf)
    counters[1] += 1
    norm = _residual_norm(buf, band, rvec, alpha, node_mass, a1, buf[10], other0)
    norm = fb.residual(bodies, j, buf, rvec, alpha, node_mass, a1, norm)
    have_tangent = refresh
    refactored = False
    stalled = 0
    for _ in range(max_iter):
        if norm <= tol:
            return True, norm, refactored
        if refresh:
            if not have_tangent:
                if moving:
                    fluid_at_midpoints(x1, elements, j, fluid, uf, af)
                _evaluate(x1, v1, a1, uf, af, elements, props, laws, with_drag,
                          with_added_mass, node_mass, external, point_force, seabed_on,
                          seabed_z, k_sb, c_sb, ramp, mu, v_slip, sag_on, sag_active, sag_load,
                          np.bool_(True), buf)
                counters[1] += 1
                norm = _residual_norm(buf, band, rvec, alpha, node_mass, a1, buf[10], other0)
                norm = fb.residual(bodies, j, buf, rvec, alpha, node_mass, a1, norm)
            _assemble(lu, bw, band, elements, buf[6], buf[7], buf[8], buf[19],
                      with_added_mass, node_mass, ca, cv, ck, buf[12], buf[13], buf[14],
                      buf[15], buf[16], seabed_on)
            fb.couplings(bodies, band, elements, buf, with_added_mass, node_mass, ca, cv, ck,
                         seabed_on)
            if not _band_lu(lu, bw) or not _factor_border(bodies, lu, bw):
                return False, norm, refactored
            counters[2] += 1
            refactored = True
            refresh = False
        merit0 = 0.0
        for k in range(rvec.shape[0]):
            merit0 += rvec[k] * rvec[k]
        dx = rvec.copy()
        _band_solve(lu, bw, dx)
        fb.solve(bodies, dx)
        counters[0] += 1
        step = 1.0  # line-search length
        better = False
        for _ls in range(max_halvings + 1):
            for n in range(x1.shape[0]):
                for c in range(3):
                    k = band[n, c]
                    trial[n, c] = x1[n, c] + (step * dx[k] if k >= 0 else 0.0)
            fb.try_step(bodies, step, dx)
            _kinematics(x0, v0, a0, trial, h, beta, gamma, free, v1, a1)
            fb.place(bodies, np.bool_(True), h, beta, gamma, trial, v1, a1)
            if moving:
                fluid_at_midpoints(trial, elements, j, fluid, uf, af)
            _evaluate(trial, v1, a1, uf, af, elements, props, laws, with_drag,
                      with_added_mass, node_mass, external, point_force, seabed_on, seabed_z,
                      k_sb, c_sb, ramp, mu, v_slip, sag_on, sag_active, sag_load,
                      np.bool_(False), buf)
            counters[1] += 1
            n_new = _residual_norm(buf, band, rvec, alpha, node_mass, a1, buf[10], other0)
            n_new = fb.residual(bodies, j, buf, rvec, alpha, node_mass, a1, n_new)
            merit = 0.0
            for k in range(rvec.shape[0]):
                merit += rvec[k] * rvec[k]
            if merit < merit0:
                better = True
                break
            step *= 0.5
        if not better and not refactored:
            # a stale tangent: refresh it at the same point and retry
            refresh = True
            have_tangent = False
            _kinematics(x0, v0, a0, x1, h, beta, gamma, free, v1, a1)
            fb.place(bodies, np.bool_(False), h, beta, gamma, x1, v1, a1)
            continue
        have_tangent = False  # trials are evaluated without it (made again when refreshed)
        if n_new > refresh_ratio * norm:
            refresh = True
        stalled = stalled + 1 if n_new > stall_ratio * norm else 0
        x1[:, :] = trial
        fb.take_trial(bodies)
        norm = n_new
        if local is not None and norm > tol:  # None: compiled without the local phase
            norm, worked = local_phase(
                x0, v0, a0, x1, v1, a1, free, band, bw, elements, props, laws, with_drag,
                with_added_mass, node_mass, external, point_force, uf, af, seabed_on,
                seabed_z, k_sb, c_sb, ramp, mu, v_slip, sag_on, sag_active, sag_load, h, beta,
                gamma, alpha, other0, buf, rvec, norm, tol, fluid, j, local, max_halvings,
                stall_ratio, counters)
            if worked:  # the factorization stays (refreshed by the usual rules)
                stalled = 0
        if stall_limit > 0 and stalled >= stall_limit:
            return False, norm, refactored
    return norm <= tol, norm, refactored


@numba.njit(**_JIT)
def _factor_border(bodies, lu, bw):
    """The bodies' part of a factorization, after the band's (:func:`fast_bodies.schur`):
    ``A^-1 B`` by band solves, then the Schur complement's inverse."""
    if bodies is None:
        return True
    BT = bodies[4][0]
    for k in range(BT.shape[0]):
        _band_solve(lu, bw, BT[k])
    return fb.schur(bodies)


@numba.njit(**_JIT)
def make_buffers(n_el: int, n_nodes: int) -> tuple:
    """Work arrays of :func:`newmark_step` (compiled: the local phase makes them for its
    sub-models)."""
    e = np.empty
    return (e((n_el, 2, 3)), e((n_el, 2, 3)), e((n_el, 2, 3)), e(n_el), e(n_el),
            e(n_el, dtype=np.bool_), e((n_el, 6, 6)), e((n_el, 6, 6)), e((n_el, 6, 6)),
            e((n_nodes, 3)), e((n_nodes, 3)), e((n_nodes, 3)), np.zeros(n_nodes),
            np.zeros(n_nodes), np.zeros((n_nodes, 2, 2)), np.zeros((n_nodes, 2)),
            np.zeros((n_nodes, 2)), np.zeros(n_el), np.zeros((n_el, 2, 3)), e((n_el, 6, 6)))


class FastStepper:
    """The compiled backend of :class:`~moorline.solvers.newmark.Stepper`: the same step
    (see :func:`~moorline.solvers.fast_path.fast_path_reason` for when it applies), run by
    :func:`newmark_step` inside the compiled loop
    :func:`moorline.solvers.fast_loop.advance_block`: :meth:`step` is a block of one
    sub-step, :meth:`run_block` many steps. ``bodies``: the model's free rigid bodies
    (:class:`~moorline.solvers.body_model.BodyModel`; see
    :func:`~moorline.solvers.fast_path.body_refusal`), None without bodies."""

    def __init__(self, model, coefficients, policy, bodies=None) -> None:
        from .fast_body_inputs import BodyInputs
        from .newmark import Stepper

        mesh = model.mesh
        self.model = model
        self.c = coefficients
        self.policy = policy
        self.band, self.bw = band_ordering(mesh.elements, mesh.dof_of_node)
        self.free = mesh.free_nodes
        n_dof = int(self.free.sum()) * 3
        self.lu = np.zeros((n_dof, 2 * self.bw + 1))
        self.tan = np.zeros(3)  # factorization valid, its step size, its age [steps]
        self.buf = make_buffers.py_func(mesh.n_elements, mesh.n_nodes)  # no kernel load
        self.counts = np.zeros(4, dtype=np.int64)
        self.fixed = np.flatnonzero(~self.free)
        n_el, n_nodes = mesh.n_elements, mesh.n_nodes
        # the free rigid bodies (BodyModel; None: none) and the general stepper with them
        # (HHT's forces at a state without them, the error message of a failed step)
        self.bodies = bodies
        self.body_inputs = BodyInputs(bodies, mesh, n_dof)
        self.general = None if bodies is None else \
            Stepper(model, coefficients, "iterative", policy, bodies)
        self.work = (self.lu, self.buf, np.zeros(n_dof + 6 * self.body_inputs.nb),
                     np.zeros((n_nodes, 3)),
                     np.zeros((n_nodes, 3)), np.zeros((n_el, 3)), np.zeros((n_el, 3)))
        f = model._fused
        # (axial, transverse) friction coefficients
        mu, v_slip = ((float(model.friction[0]), float(model.friction[1])), model.friction[2]) \
            if model.friction else ((0.0, 0.0), 1.0)
        self.model_args = (
            self.free, self.band, self.bw, mesh.elements, f.props, f.laws, f.with_drag,
            f.with_added_mass, model.node_mass, model.external,
            bool(np.isfinite(mesh.seabed_z)), float(mesh.seabed_z), model.k_seabed,
            model.c_seabed, model.seabed_ramp, mu, float(v_slip), *self._sag(model),
            float(coefficients.beta),
            float(coefficients.gamma), float(coefficients.alpha))
        pol = policy
        self.newton_args = (float(pol.tolerance), int(pol.max_iterations),
                            np.inf if pol.refresh_ratio is None else float(pol.refresh_ratio),
                            float(pol.stall_ratio), int(pol.stall_limit),
                            int(pol.max_halvings), float(pol.stiffness_update),
                            None if not pol.local_iterations or bodies is not None else
                            (float(pol.local_iterations), float(pol.local_fraction),
                             float(pol.local_pad), float(pol.local_max_share),
                             *incidence(mesh.elements, mesh.n_nodes),
                             local_workspace(n_el, n_nodes, f.props.shape[0], f.laws[0],
                                             self.model_args[18], self.bw)))
        self.waves, self.current = fluid_parts(model.fluid)
        if self.waves is not None:
            c = self.waves._coef
            self.wave_coef = np.ascontiguousarray(np.vstack([c[name] for name in (
                "k", "kx", "ky", "a", "aw_c", "aw_s", "aw", "aw2_c", "aw2_s", "aw2", "denom")]))
        else:
            self.wave_coef = np.zeros((11, 0))
        self.current_velocity = np.zeros(3) if self.current is None else \
            np.ascontiguousarray(self.current.velocity(np.zeros(1))[0], dtype=float)
        # a sheared profile: heights (ascending), speeds, unwrapped headings [rad] per level
        # (one level: the uniform velocity above is used)
        self.current_profile = np.zeros((3, 1)) if self.current is None else \
            np.ascontiguousarray(np.vstack((self.current._z, self.current._speed,
                                            self.current._heading)), dtype=float)

    @staticmethod
    def _sag(model) -> tuple:
        """(on, active (n_el,), node load (n_nodes,)) of the sag correction."""
        mesh, sag = model.mesh, model.sag
        return (sag is not None, np.zeros(mesh.n_elements) if sag is None else sag.active,
                np.zeros(mesh.n_nodes) if sag is None else sag.node_load)

    def forget_tangent(self) -> None:
        """Drop the factorization (after a step cut)."""
        self.tan[0] = 0.0

    def tangent_state(self) -> tuple:
        """The banded factors, the bodies' border and their age (see
        :meth:`Stepper.tangent_state`)."""
        return self.lu.copy(), self.tan.copy(), self.body_inputs.tangent_state()

    def set_tangent_state(self, saved: tuple) -> None:
        """Restore what :meth:`tangent_state` returned."""
        self.lu[...], self.tan[...] = saved[:2]
        self.body_inputs.set_tangent_state(saved[2])

    @property
    def counters(self) -> dict:
        """Same keys as :class:`~moorline.solvers.newmark.Stepper`."""
        it, res, fac, loc = (int(v) for v in self.counts)
        return {"iterations": it, "residuals": res, "tangents": fac, "factorizations": fac,
                "local_iterations": loc}

    def _fluid_inputs(self, times: FloatArray) -> tuple:
        """What :func:`moorline.solvers.fast_loop._fluid` takes for sub-steps ending at
        ``times``: the waves' phases ``phi - w t`` and ramps, the current's ramp."""
        from ..waves.airy import ramp_factor

        def ramps(field) -> FloatArray:
            if field is None:
                return np.zeros((len(times), 2))
            return np.array([ramp_factor(float(t), field.ramp_time) for t in times],
                            dtype=float).reshape(-1, 2)

        waves = self.waves
        offset = np.zeros((len(times), 0)) if waves is None else \
            waves._coef["phi"] - waves._coef["w"] * np.asarray(times)[:, None]
        depth = math.inf if waves is None else float(waves.depth)
        wheeler = waves is not None and waves.stretching == "wheeler"
        return (waves is not None, self.wave_coef, depth, wheeler, offset, ramps(waves),
                self.current is not None, self.current_velocity, ramps(self.current),
                self.current_profile)

    def run_block(self, s0, times: FloatArray, hs: FloatArray, per_step: int,
                  record: NDArray[np.bool_], kinematics: tuple, forces: tuple,
                  end_elements: IntArray, end_sides: IntArray,
                  out: tuple[FloatArray, ...] | None = None) -> Block:
        """Advance from ``s0`` by the sub-steps ``hs`` (ending at ``times``), ``per_step``
        to a full step, with the fixed and prescribed nodes' kinematics
        ``(x, v, a)`` (n_sub, n_fixed, 3) and the point forces ``(nodes, values)``
        (values (n_sub, n_forces, 3)) at those times; records after the full steps flagged
        in ``record`` (:func:`moorline.solvers.fast_loop.advance_block`), into ``out``
        (positions, velocities (n_rec, n_nodes, 3), tensions (n_rec, n_el), end element
        forces (n_rec, n_ends, 3): C-ordered, e.g. rows of the run's record arrays) or new
        arrays."""
        from .fast_loop import advance_block

        mesh = self.model.mesh
        x0, v0, a0 = s0.x.copy(), s0.v.copy(), s0.a.copy()
        x1, v1, a1 = np.empty_like(x0), np.empty_like(x0), np.empty_like(x0)
        n_el, n_nodes = mesh.n_elements, mesh.n_nodes
        material = s0.material
        saved = (np.empty((n_el, 2, 3)), np.empty(n_el), np.array(material.strain, dtype=float),
                 np.empty((n_nodes, 3)), np.empty((n_nodes, 3)),
                 np.array(material.maxwell, dtype=float))
        n_rec = int(np.count_nonzero(record))
        inputs = self.body_inputs
        if out is None:
            out = (np.empty((n_rec, n_nodes, 3)), np.empty((n_rec, n_nodes, 3)),
                   np.empty((n_rec, n_el)), np.empty((n_rec, len(end_elements), 3)))
        out = (*out, end_elements, end_sides, *inputs.records(n_rec))
        other0 = s0.evaluation.nodal - s0.evaluation.inertial  # HHT: F0 - F_am0
        body_other0 = None
        if inputs.nb and self.c.alpha:  # HHT: the bodies' F0
            body_other0 = self.general._body_other(s0)
        body_state = inputs.state(s0.bodies, body_other0)
        memory = inputs.memory(s0.memory)
        pins = inputs.pins(times, s0.pin_force)
        bodies = None if not inputs.nb else (inputs.links, inputs.loads, body_state,
                                             inputs.forces(times), inputs.work, memory, pins)
        done, stopped, norm, n_written = advance_block(
            x0, v0, a0, x1, v1, a1, hs, per_step, record, *kinematics, self.fixed, *forces,
            self._fluid_inputs(times), self.model_args, self.newton_args, self.tan,
            self.counts, self.work, other0, saved, out, bodies)
        n_sub = done * per_step + max(stopped, 0)
        state = s0
        if n_sub:
            from .dynamic_model import Evaluation, MaterialState
            from .newmark import StepState

            el_forces, tension, strain, f_am, resid, maxwell = saved
            nodal = resid + self.model.node_mass[:, None] * a0  # F without structural inertia
            ev = Evaluation(nodal, f_am, tension,
                            MaterialState(strain, maxwell, material.peak), el_forces)
            poses, body_other, states, pin_force = None, None, None, None
            if inputs.nb:
                from .bodies import BodyState

                poses = BodyState(*(q.copy() for q in body_state[:4]))
                body_other = body_state[11].copy()
                states = inputs.memory_states(memory)
                pin_force = pins[4].copy() if pins[0].any() else None
            state = StepState(float(times[n_sub - 1]), x0, v0, a0, ev.material, ev, poses,
                              body_other, states, pin_force)
        return Block(state, int(done), int(stopped), float(norm), out[0][:n_written],
                     out[1][:n_written], out[2][:n_written], out[3][:n_written],
                     tuple(q[:n_written] for q in out[6:]))

    def step(self, s0, h: float, constrained, point_forces):
        """Advance from ``s0`` by ``h`` (see :meth:`Stepper.step`): a block of one step."""
        empty = np.zeros(0, dtype=np.int64)
        forces = (empty, np.zeros((1, 0, 3))) if point_forces is None else \
            (np.arange(len(point_forces), dtype=np.int64), np.asarray(point_forces)[None])
        block = self.run_block(s0, np.array([s0.t + h]), np.array([h]), 1,
                               np.zeros(1, dtype=np.bool_),
                               tuple(np.asarray(q, dtype=float)[None] for q in constrained),
                               forces, empty, empty)
        return block.state, block.steps == 1, block.norm


@dataclass
class Block:
    """What :meth:`FastStepper.run_block` did: the state after the last converged sub-step,
    the full steps done, the sub-step of the next step where it stopped (-1: none) and its
    residual max-norm, and the records (positions, velocities, tensions, the element forces
    at the line ends; the bodies' origins, rotation matrices and velocities)."""

    state: object
    steps: int
    stopped: int
    norm: float
    positions: FloatArray
    velocities: FloatArray
    tensions: FloatArray
    end_forces: FloatArray
    bodies: tuple = ()


from .fast_local import incidence, local_phase  # noqa: E402  (it compiles in this module's kernels)
from .fast_local import workspace as local_workspace  # noqa: E402
