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
:func:`~moorline.solvers.fast_newmark._band_lu`). The sub-model lives in work arrays made
once per stepper (:func:`workspace`), its index sets are put in order by a scan of the
marked span (no sort), and the max-norm after a local step is the frozen part's (taken with
the merit's scan) and the recomputed part's. Two scans over all nodes remain per local
iteration (the window's selection, the frozen part's merit and norm); they are a few
operations per node.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from ..jit import numba
from ..physics.fused import TableLaws
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
            queue, out):
    """The window's nodes (ascending, in ``out``'s leading part; empty: no local iteration):
    free nodes whose residual (max over their dofs) exceeds ``threshold``, padded by ``pad``
    rings of elements (through any node), at most ``share`` of the free nodes
    (``Stepper.local_window``). Marks them with ``it`` in ``stamp``."""
    k = np.int64(0)  # np.int64: a literal 0 would compile _grow twice (numba)
    for n in range(band.shape[0]):
        if not free[n]:
            continue
        m = max(abs(rvec[band[n, 0]]), abs(rvec[band[n, 1]]), abs(rvec[band[n, 2]]))
        if m > threshold:
            stamp[n] = it
            queue[k] = n
            k += 1
    first = np.int64(0)
    for _ in range(pad):
        last = k
        k = _grow(stamp, it, queue, first, last, elements, ptr, inc)
        first = last
    count = 0
    lo, hi = band.shape[0], np.int64(-1)
    for q in range(k):
        n = queue[q]
        if free[n]:
            count += 1
            lo = min(lo, n)
            hi = max(hi, n)
    if count == 0 or count > share * n_free:
        return out[:0]
    return _marked(stamp, it, lo, hi, free, True, out)


@numba.njit(**_JIT)
def _marked(stamp, it, lo, hi, mask, masked, out):
    """The indices in ``lo..hi`` stamped ``it`` (and, if ``masked``, true in ``mask``),
    ascending, in ``out``'s leading part (a scan of the marked span instead of a sort)."""
    count = 0
    for n in range(lo, hi + 1):
        if stamp[n] == it and (not masked or mask[n]):
            out[count] = n
            count += 1
    return out[:count]


@numba.njit(**_JIT)
def _sub_model(window, band, elements, ptr, inc, stamps, it, queue, out):
    """The window's sub-model: ``(sub_elements, sub_nodes, band_local)``: the elements
    touching the window and its first ring of nodes (``stamps[1] == it``: their residual is
    recomputed exactly), ascending; those elements' nodes (ascending; ``stamps[3]`` their
    index among them); ``band_local`` (n_sub, 3) the window's dofs' positions in its own
    band (their band indices sorted; -1 off the window). ``out``: (elements, nodes,
    band_local, dof stamps, dof positions) arrays whose leading parts receive them."""
    ring, el_stamp, used, local = stamps
    el_out, node_out, band_out, dof_stamp, dof_pos = out
    nw = window.shape[0]
    for q in range(nw):
        ring[window[q]] = it
        queue[q] = window[q]
    k = _grow(ring, it, queue, np.int64(0), nw, elements, ptr, inc)
    lo, hi = elements.shape[0], np.int64(-1)
    for q in range(k):
        n = queue[q]
        for p in range(ptr[n], ptr[n + 1]):
            e = inc[p]
            if el_stamp[e] != it:
                el_stamp[e] = it
                lo = min(lo, e)
                hi = max(hi, e)
    sub_elements = _marked(el_stamp, it, lo, hi, ring, False, el_out)
    lo, hi = band.shape[0], np.int64(-1)
    for e in sub_elements:
        for m in range(2):
            n = elements[e, m]
            if used[n] != it:
                used[n] = it
                lo = min(lo, n)
                hi = max(hi, n)
    sub_nodes = _marked(used, it, lo, hi, ring, False, node_out)
    n_sub = sub_nodes.shape[0]
    for q in range(n_sub):
        local[sub_nodes[q]] = q
    lo, hi = dof_stamp.shape[0], np.int64(-1)
    for q in range(nw):
        for c in range(3):
            d = band[window[q], c]
            dof_stamp[d] = it
            lo = min(lo, d)
            hi = max(hi, d)
    count = 0
    for d in range(lo, hi + 1):
        if dof_stamp[d] == it:
            dof_pos[d] = count
            count += 1
    band_local = band_out[:n_sub]
    band_local[:, :] = -1
    for q in range(nw):
        for c in range(3):
            band_local[local[window[q]], c] = dof_pos[band[window[q], c]]
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
def _sub_buffers(full, ne, nn):
    """The leading ``ne`` elements' and ``nn`` nodes' part of the work arrays ``full``
    (:func:`moorline.solvers.fast_newmark.make_buffers` of the whole model)."""
    return (full[0][:ne], full[1][:ne], full[2][:ne], full[3][:ne], full[4][:ne],
            full[5][:ne], full[6][:ne], full[7][:ne], full[8][:ne], full[9][:nn],
            full[10][:nn], full[11][:nn], full[12][:nn], full[13][:nn], full[14][:nn],
            full[15][:nn], full[16][:nn], full[17][:ne], full[18][:ne], full[19][:ne])


def workspace(n_el: int, n_nodes: int, n_props: int, law: IntArray, sag_active: NDArray,
              bw: int) -> tuple:
    """Work arrays of :func:`local_phase`, made once per stepper at the whole model's size
    (a window's sub-model uses their leading part): node and element stamps, a queue, the
    sub-model's element data, node data (6 vectors, 5 scalars), band matrix and right-hand
    side, the evaluation's buffers, the window, and :func:`_sub_model`'s ``out``."""
    full = lambda: np.full(n_nodes, -1, dtype=np.int64)  # noqa: E731
    return (full(), full(), np.full(n_el, -1, dtype=np.int64), full(), full(),
            np.empty(n_nodes, dtype=np.int64), np.empty((n_el, 2), dtype=np.int64),
            np.empty(n_props * n_el), np.empty(n_el, dtype=law.dtype),
            np.empty(n_el, dtype=sag_active.dtype), np.empty((n_el, 3)),
            np.empty((n_el, 3)), np.empty((6, n_nodes, 3)), np.empty((5, n_nodes)),
            np.empty((3 * n_nodes, 2 * bw + 1)), np.empty(3 * n_nodes),
            fn.make_buffers.py_func(n_el, n_nodes), np.empty(n_nodes, dtype=np.int64),
            (np.empty(n_el, dtype=np.int64), np.empty(n_nodes, dtype=np.int64),
             np.empty((n_nodes, 3), dtype=np.int64), np.full(3 * n_nodes, -1, dtype=np.int64),
             np.empty(3 * n_nodes, dtype=np.int64)))


@numba.njit(**_JIT)
def local_phase(x0, v0, a0, x1, v1, a1, free, band, bw, elements, props, laws, with_drag,
                with_added_mass, node_mass, external, point_force, uf, af, seabed_on,
                seabed_z, k_sb, c_sb, ramp, mu, v_slip, sag_on, sag_active, sag_load, h, beta,
                gamma, alpha, other0, buf, rvec, norm, tol, fluid, j, local, max_halvings,
                stall_ratio, counters):
    """Local iterations from the iterate ``x1`` (``v1, a1``, ``buf`` and ``rvec`` evaluated
    there) of :func:`moorline.solvers.fast_newmark.newmark_step` (its arguments);
    ``local = (iterations, fraction, pad, max share, ptr, inc, work)`` (``ptr, inc``: the
    elements of every node, :func:`incidence`; ``work``: :func:`workspace`). Updates the
    iterate, its evaluation (the recomputed elements' and nodes' entries of ``buf``, ``uf``,
    ``af``) and ``rvec``; counts local iterations in ``counters[3]`` and residual evaluations
    (the iterate's with the tangent, the line search's trials) in ``counters[1]``, as
    :func:`moorline.solvers.newton._local_phase` does. Returns (max-norm, whether a local
    step was solved)."""
    n_iter, fraction, pad, share, ptr, inc, work = local
    ca = 1.0 / (beta * h * h)
    cv = (1 + alpha) * gamma / (beta * h)
    ck = 1.0 + alpha
    moving = fluid[0] or fluid[6]
    n_nodes = x1.shape[0]
    n_free = np.int64(0)
    for n in range(n_nodes):
        if free[n]:
            n_free += 1
    law, start, breaks, coef, end_slope = laws
    (stamp, ring, el_stamp, used, local_of, queue, el_w, props_w, law_w, active_w, uf_w,
     af_w, node3_w, node1_w, ab_w, dx_w, sub_w, window_w, sub_out) = work
    stamp[:] = -1
    ring[:] = -1
    el_stamp[:] = -1
    used[:] = -1
    sub_out[3][:] = -1
    stamps = (ring, el_stamp, used, local_of)
    n_props = props.shape[0]
    worked = False
    for it in range(int(n_iter)):
        window = _window(rvec, band, free, n_free, elements, ptr, inc,
                         max(fraction * norm, tol), int(pad), share, stamp, it, queue,
                         window_w)
        if window.shape[0] == 0:
            break
        sub_el, sub_nodes, band_l = _sub_model(window, band, elements, ptr, inc, stamps, it,
                                               queue, sub_out)
        ne, nn = sub_el.shape[0], sub_nodes.shape[0]
        el_l = el_w[:ne]
        props_l = props_w[:n_props * ne].reshape((n_props, ne))
        law_l = law_w[:ne]
        active_l = active_w[:ne]
        uf_l = uf_w[:ne]
        af_l = af_w[:ne]
        for q in range(ne):
            e = sub_el[q]
            el_l[q, 0] = local_of[elements[e, 0]]
            el_l[q, 1] = local_of[elements[e, 1]]
            law_l[q] = law[e]
            active_l[q] = sag_active[e]
            for p in range(n_props):
                props_l[p, q] = props[p, e]
            for c in range(3):
                uf_l[q, c] = uf[e, c]
                af_l[q, c] = af[e, c]
        x_l, v_l, a_l = node3_w[0, :nn], node3_w[1, :nn], node3_w[2, :nn]
        ext_l, pf_l, oth_l = node3_w[3, :nn], node3_w[4, :nn], node3_w[5, :nn]
        mass_l, k_l, c_l, ramp_l, load_l = (node1_w[0, :nn], node1_w[1, :nn],
                                            node1_w[2, :nn], node1_w[3, :nn],
                                            node1_w[4, :nn])
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
        laws_l = TableLaws(law_l, start, breaks, coef, end_slope)  # the step's type: one compile
        sub = _sub_buffers(sub_w, ne, nn)
        nw = 3 * window.shape[0]
        ab = ab_w[:nw]
        dx = dx_w[:nw]
        # the merit (residual 2-norm squared): the frozen nodes' part and the ring's; the
        # frozen part's max-norm (the ring's comes with the accepted trial)
        base = 0.0
        frozen = 0.0
        for n in range(n_nodes):
            if free[n] and ring[n] != it:
                for c in range(3):
                    r = rvec[band[n, c]]
                    base += r * r
                    r = abs(r)
                    if not (r <= frozen):
                        frozen = r if r == r else math.inf
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
            counters[1] += 1
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
        inside, outside = _take(sub, sub_el, sub_nodes, ring, stamp, it, window, local_of,
                                x_l, v_l, a_l, uf_l, af_l, x1, v1, a1, uf, af, buf, rvec,
                                band, free, alpha, mass_l, oth_l)
        new = max(frozen, inside, outside)
        ratio = new / norm
        norm = new
        # the largest residual left outside the window: its frozen edge, not Newton, limits
        # the local iterations; a full iteration follows
        if norm <= tol or ratio > stall_ratio or max(frozen, outside) > inside:
            break
    return norm, worked


@numba.njit(**_JIT)
def _take(sub, sub_el, sub_nodes, ring, stamp, it, window, local_of, x_l, v_l, a_l, uf_l, af_l,
          x1, v1, a1, uf, af, buf, rvec, band, free, alpha, mass_l, oth_l):
    """Accept a local trial: the window's kinematics, the recomputed elements' and nodes'
    evaluation and residual into the step's arrays; returns the max-norm of the recomputed
    residual (``inf`` with a NaN) on the window's nodes (``stamp == it``) and on the others."""
    top = 0.0
    edge = 0.0
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
                r = _node_residual(sub, q, c, alpha, mass_l[q], a_l, oth_l)
                rvec[band[g, c]] = r
                r = abs(r)
                if stamp[g] == it:
                    if not (r <= top):
                        top = r if r == r else math.inf
                elif not (r <= edge):
                    edge = r if r == r else math.inf
    return top, edge


from . import fast_newmark as fn  # noqa: E402  (a cycle: its step calls local_phase)
