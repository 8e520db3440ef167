"""The local phase of the compiled step (numba): Newton on a window of nodes around the
residual, the rest of the line frozen, after a full iteration (nonlinear elimination; the
algorithm and its sources: :mod:`moorline.solvers.newton`, :func:`~moorline.solvers.newton.
_local_phase`, whose iterates these are).

A local iteration costs in proportion to the window, not the line: only the elements touching
the window and its first ring of nodes are evaluated, on a sub-model of those elements and
their nodes (the same kernels, :func:`moorline.solvers.fast_newmark._evaluate`, on sliced
arrays; sorted, so that every node of the window and its ring sums its elements in the same
order as the full evaluation and its residual is the full residual's to the last bit; the
other nodes' residual does not change). The window's rows and columns of the effective
tangent keep the band's order, so they form a band matrix of the same bandwidth
(:func:`~moorline.solvers.fast_newmark._assemble` with a local band map,
:func:`~moorline.solvers.fast_newmark._band_lu`). Scans over all nodes (the window's
selection, the norms) remain; they are a few operations per node.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from ..jit import numba
from .fast_fluid import fluid_at_midpoints

IntArray = NDArray[np.int64]

_JIT = {"cache": True, "fastmath": False, "error_model": "numpy"}


def incidence(elements: IntArray, n_nodes: int) -> tuple[IntArray, IntArray]:
    """Elements of every node: ``inc[ptr[n]:ptr[n + 1]]``."""
    ends = elements.ravel()
    ptr = np.zeros(n_nodes + 1, dtype=np.int64)
    ptr[1:] = np.cumsum(np.bincount(ends, minlength=n_nodes))
    inc = (np.argsort(ends, kind="stable") // 2).astype(np.int64)
    return ptr, inc


@numba.njit(**_JIT)
def _grow(stamp, it, queue, first, last, elements, ptr, inc):
    """Stamp ``it`` on the nodes sharing an element with ``queue[first:last]`` (not stamped
    yet), appending them to ``queue``; returns the new end of the queue."""
    k = last
    for q in range(first, last):
        n = queue[q]
        for p in range(ptr[n], ptr[n + 1]):
            e = inc[p]
            other = elements[e, 0] + elements[e, 1] - n
            if stamp[other] != it:
                stamp[other] = it
                queue[k] = other
                k += 1
    return k


@numba.njit(**_JIT)
def _window(rvec, band, free, n_free, elements, ptr, inc, threshold, pad, share, stamp, it,
            queue):
    """The window's nodes (sorted; empty: no local iteration): free nodes whose residual
    (max over their dofs) exceeds ``threshold``, padded by ``pad`` rings of elements (through
    any node), at most ``share`` of the free nodes (``Stepper.local_window``). Marks them
    with ``it`` in ``stamp``."""
    k = 0
    for n in range(band.shape[0]):
        if not free[n]:
            continue
        m = max(abs(rvec[band[n, 0]]), abs(rvec[band[n, 1]]), abs(rvec[band[n, 2]]))
        if m > threshold:
            stamp[n] = it
            queue[k] = n
            k += 1
    first = 0
    for _ in range(pad):
        last = k
        k = _grow(stamp, it, queue, first, last, elements, ptr, inc)
        first = last
    count = 0
    for q in range(k):
        if free[queue[q]]:
            count += 1
    if count == 0 or count > share * n_free:
        return np.zeros(0, dtype=np.int64)
    out = np.empty(count, dtype=np.int64)
    count = 0
    for q in range(k):
        if free[queue[q]]:
            out[count] = queue[q]
            count += 1
    return np.sort(out)


@numba.njit(**_JIT)
def _sub_model(window, band, elements, ptr, inc, stamps, it, queue):
    """The window's sub-model: ``(sub_elements, sub_nodes, band_local)``: the elements
    touching the window and its first ring of nodes (``stamps[1] == it``: their residual is
    recomputed exactly), sorted; those elements' nodes (sorted; ``stamps[3]`` their index
    among them); ``band_local`` (n_sub, 3) the window's dofs' positions in its own band
    (their band indices sorted; -1 off the window)."""
    ring, el_stamp, used, local = stamps
    nw = window.shape[0]
    for q in range(nw):
        ring[window[q]] = it
        queue[q] = window[q]
    k = _grow(ring, it, queue, 0, nw, elements, ptr, inc)
    n_el = 0
    for q in range(k):
        n = queue[q]
        for p in range(ptr[n], ptr[n + 1]):
            e = inc[p]
            if el_stamp[e] != it:
                el_stamp[e] = it
                n_el += 1
    sub_elements = np.empty(n_el, dtype=np.int64)
    n_el = 0
    for q in range(k):
        n = queue[q]
        for p in range(ptr[n], ptr[n + 1]):
            e = inc[p]
            if el_stamp[e] == it:
                el_stamp[e] = -2 - it  # listed
                sub_elements[n_el] = e
                n_el += 1
    sub_elements.sort()
    n_sub = 0
    for e in sub_elements:
        for m in range(2):
            n = elements[e, m]
            if used[n] != it:
                used[n] = it
                queue[n_sub] = n
                n_sub += 1
    sub_nodes = np.sort(queue[:n_sub])
    for q in range(n_sub):
        local[sub_nodes[q]] = q
    dofs = np.empty(3 * nw, dtype=np.int64)
    for q in range(nw):
        for c in range(3):
            dofs[3 * q + c] = band[window[q], c]
    order = np.sort(dofs)
    band_local = np.full((n_sub, 3), -1, dtype=np.int64)
    for q in range(nw):
        for c in range(3):
            band_local[local[window[q]], c] = np.searchsorted(order, band[window[q], c])
    return sub_elements, sub_nodes, band_local


@numba.njit(**_JIT)
def _node_residual(sub, n, c, alpha, mass, a, other0):
    """The step's residual of dof ``c`` of sub-model node ``n`` (``_residual_norm``)."""
    resid = sub[11][n, c]
    if alpha == 0.0:
        return resid
    inertial = sub[10][n, c] - mass * a[n, c]
    other = resid + mass * a[n, c] - sub[10][n, c]
    return (1 + alpha) * other - alpha * other0[n, c] + inertial


@numba.njit(**_JIT)
def local_phase(x0, v0, a0, x1, v1, a1, free, band, bw, elements, props, laws, with_drag,
                with_added_mass, node_mass, external, point_force, uf, af, seabed_on,
                seabed_z, k_sb, c_sb, ramp, mu, v_slip, sag_on, sag_active, sag_load, h, beta,
                gamma, alpha, other0, buf, rvec, norm, tol, fluid, j, local, max_halvings,
                stall_ratio, counters):
    """Local iterations from the iterate ``x1`` (``v1, a1``, ``buf`` and ``rvec`` evaluated
    there) of :func:`moorline.solvers.fast_newmark.newmark_step` (its arguments);
    ``local = (iterations, fraction, pad, max share, ptr, inc)`` (the last two: the
    elements of every node, :func:`incidence`). Updates the iterate, its evaluation
    (the recomputed elements' and nodes' entries of ``buf``, ``uf``, ``af``) and ``rvec``;
    counts local iterations in ``counters[3]``. Returns (max-norm, whether a local step was
    solved)."""
    n_iter, fraction, pad, share, ptr, inc = local
    ca = 1.0 / (beta * h * h)
    cv = (1 + alpha) * gamma / (beta * h)
    ck = 1.0 + alpha
    moving = fluid[0] or fluid[6]
    n_nodes = x1.shape[0]
    n_free = 0
    for n in range(n_nodes):
        if free[n]:
            n_free += 1
    law, start, breaks, coef, end_slope = laws
    stamp = np.full(n_nodes, -1, dtype=np.int64)
    stamps = (np.full(n_nodes, -1, dtype=np.int64), np.full(elements.shape[0], -1,
                                                             dtype=np.int64),
              np.full(n_nodes, -1, dtype=np.int64), np.full(n_nodes, -1, dtype=np.int64))
    ring, local_of = stamps[0], stamps[3]
    queue = np.empty(n_nodes, dtype=np.int64)
    worked = False
    for it in range(int(n_iter)):
        window = _window(rvec, band, free, n_free, elements, ptr, inc,
                         max(fraction * norm, tol), int(pad), share, stamp, it, queue)
        if window.shape[0] == 0:
            break
        sub_el, sub_nodes, band_l = _sub_model(window, band, elements, ptr, inc, stamps, it,
                                               queue)
        ne, nn = sub_el.shape[0], sub_nodes.shape[0]
        el_l = np.empty((ne, 2), dtype=np.int64)
        props_l = np.empty((props.shape[0], ne))
        law_l = law[sub_el]
        active_l = sag_active[sub_el]
        uf_l = np.empty((ne, 3))
        af_l = np.empty((ne, 3))
        for q in range(ne):
            e = sub_el[q]
            el_l[q, 0] = local_of[elements[e, 0]]
            el_l[q, 1] = local_of[elements[e, 1]]
            for p in range(props.shape[0]):
                props_l[p, q] = props[p, e]
            for c in range(3):
                uf_l[q, c] = uf[e, c]
                af_l[q, c] = af[e, c]
        x_l, v_l, a_l = np.empty((nn, 3)), np.empty((nn, 3)), np.empty((nn, 3))
        ext_l, pf_l, oth_l = np.empty((nn, 3)), np.empty((nn, 3)), np.empty((nn, 3))
        mass_l, k_l, c_l, ramp_l, load_l = (np.empty(nn), np.empty(nn), np.empty(nn),
                                            np.empty(nn), np.empty(nn))
        for q in range(nn):
            g = sub_nodes[q]
            for c in range(3):
                x_l[q, c] = x1[g, c]
                v_l[q, c] = v1[g, c]
                a_l[q, c] = a1[g, c]
                ext_l[q, c] = external[g, c]
                pf_l[q, c] = point_force[g, c]
                oth_l[q, c] = other0[g, c]
            mass_l[q] = node_mass[g]
            k_l[q] = k_sb[g]
            c_l[q] = c_sb[g]
            ramp_l[q] = ramp[g]
            load_l[q] = sag_load[g]
        laws_l = (law_l, start, breaks, coef, end_slope)
        sub = fn.make_buffers(ne, nn)
        nw = 3 * window.shape[0]
        ab = np.zeros((nw, 2 * bw + 1))
        dx = np.empty(nw)
        # the merit (residual 2-norm squared): the frozen nodes' part and the ring's
        base = 0.0
        for n in range(n_nodes):
            if free[n] and ring[n] != it:
                for c in range(3):
                    base += rvec[band[n, c]] * rvec[band[n, c]]
        merit0 = base
        step = 2.0
        accepted = False
        # attempt 0: the tangent at the iterate (its residual is the iterate's), then the
        # line search's trials; one call site of the kernels keeps the compiled code small
        for attempt in range(max_halvings + 2):
            if attempt > 0:
                step *= 0.5
                for g in window:
                    q = local_of[g]
                    for c in range(3):
                        x_l[q, c] = x1[g, c] + step * dx[band_l[q, c]]
                        acc = (x_l[q, c] - x0[g, c] - h * v0[g, c]
                               - h * h * (0.5 - beta) * a0[g, c]) / (beta * h * h)
                        a_l[q, c] = acc
                        v_l[q, c] = v0[g, c] + h * ((1.0 - gamma) * a0[g, c] + gamma * acc)
            if moving:
                fluid_at_midpoints(x_l, el_l, j, fluid, uf_l, af_l)
            fn._evaluate(x_l, v_l, a_l, uf_l, af_l, el_l, props_l, laws_l, with_drag,
                         with_added_mass, mass_l, ext_l, pf_l, seabed_on, seabed_z, k_l, c_l,
                         ramp_l, mu, v_slip, sag_on, active_l, load_l, attempt == 0, sub)
            merit = base
            for q in range(nn):
                g = sub_nodes[q]
                if ring[g] == it and free[g]:
                    for c in range(3):
                        r = _node_residual(sub, q, c, alpha, mass_l[q], a_l, oth_l)
                        merit += r * r
                        if attempt == 0 and band_l[q, c] >= 0:
                            dx[band_l[q, c]] = r
            if attempt == 0:
                merit0 = merit
                fn._assemble(ab, bw, band_l, el_l, sub[6], sub[7], sub[8], sub[19],
                             with_added_mass, mass_l, ca, cv, ck, sub[12], sub[13], sub[14],
                             sub[15], sub[16], seabed_on)
                counters[3] += 1
                worked = True
                if not fn._band_lu(ab, bw):
                    break
                fn._band_solve(ab, bw, dx)
            elif merit < merit0:
                accepted = True
                break
        if not accepted:
            break
        _take(sub, sub_el, sub_nodes, ring, it, window, local_of, x_l, v_l, a_l, uf_l,
              af_l, x1, v1, a1, uf, af, buf, rvec, band, free, alpha, mass_l, oth_l)
        new = 0.0
        for k in range(rvec.shape[0]):
            r = abs(rvec[k])
            if not (r <= new):
                new = r if r == r else math.inf
        ratio = new / norm
        norm = new
        if norm <= tol or ratio > stall_ratio:
            break
    return norm, worked


@numba.njit(**_JIT)
def _take(sub, sub_el, sub_nodes, ring, it, window, local_of, x_l, v_l, a_l, uf_l, af_l, x1, v1,
          a1, uf, af, buf, rvec, band, free, alpha, mass_l, oth_l):
    """Accept a local trial: the window's kinematics, the recomputed elements' and nodes'
    evaluation and residual into the step's arrays."""
    for g in window:
        q = local_of[g]
        for c in range(3):
            x1[g, c] = x_l[q, c]
            v1[g, c] = v_l[q, c]
            a1[g, c] = a_l[q, c]
    for q in range(sub_el.shape[0]):
        e = sub_el[q]
        for c in range(3):
            uf[e, c] = uf_l[q, c]
            af[e, c] = af_l[q, c]
            for m in range(2):
                buf[0][e, m, c] = sub[0][q, m, c]
                buf[1][e, m, c] = sub[1][q, m, c]
                buf[2][e, m, c] = sub[2][q, m, c]
        buf[3][e] = sub[3][q]
        buf[4][e] = sub[4][q]
        buf[5][e] = sub[5][q]
    for q in range(sub_nodes.shape[0]):
        g = sub_nodes[q]
        if ring[g] != it:
            continue
        for c in range(3):
            buf[9][g, c] = sub[9][q, c]
            buf[10][g, c] = sub[10][q, c]
            buf[11][g, c] = sub[11][q, c]
            if free[g]:
                rvec[band[g, c]] = _node_residual(sub, q, c, alpha, mass_l[q], a_l, oth_l)


from . import fast_newmark as fn  # noqa: E402  (a cycle: its step calls local_phase)
