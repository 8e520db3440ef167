"""All element loads of an elastic or viscoelastic cable in one compiled loop (numba).

The numpy path of :meth:`moorline.solvers.dynamic_model.DynamicModel.evaluate` calls a few
dozen small vectorized kernels per evaluation (:mod:`moorline.physics.element`,
:mod:`moorline.physics.hydro` and the Kelvin-Voigt damping of the dynamic model); for the
system sizes of mooring analysis (tens to hundreds of elements) its cost is almost entirely
numpy call overhead. :func:`element_loads` does the same arithmetic in one ``numba.njit`` loop
over the elements, in the same order of operations, so that it agrees with the numpy path to
round-off (tests/test_fused.py holds every output to 1e-12 of its largest entry). Only the
chord length may differ in its last bit (numpy's ``einsum`` may use fused multiply-adds); the
ill-conditioned quantities inherit that: the strain ``l / L0 - 1`` to ~eps absolute, and in the
slack band, whose slope is ``EA / (2 s)``, the tangent to ~``eps EA / (s L0)``.

* axial: chord, length, unit vector ``n``; strain ``l / L0 - 1`` (less the element's strain
  offset in its law); the tension with the smooth slack band and its slope
  (:func:`moorline.physics.element.axial_tension`), linear ``EA`` or a tabulated
  tension-strain law (:class:`TableLaws`); the Kelvin-Voigt
  damping ``BA * share * strain_rate`` (the share blended in over the slack band at the
  strain the element had at the start of the step,
  :func:`moorline.physics.element.lagged_dashpot_share`, set into a row of the packed
  properties by :func:`set_dashpot_shares`; or whole in every element with
  ``slack_damping``, another row); the nodal
  forces
  (:func:`moorline.physics.element.nodal_forces`); with ``tangent`` the blocks ``K``
  (geometric + material + the non-symmetric rotation term of the dashpot) and ``C`` (the
  dashpot, ``BA / L0 n n^T``); elements with the sag correction (``phi != 0``) take the
  tension of :func:`moorline.physics.sag.sag_tension` (the same safeguarded Newton iteration
  per element) and the extra blocks of :func:`~moorline.physics.sag.sag_blocks`, ``phi`` and
  its node derivatives given by the caller;
* Morison drag on the relative velocity at the midpoint, normal and tangential, with its
  exact derivatives (:func:`moorline.physics.hydro.drag_forces`), or each node's half at
  that node's own velocity (``node_drag``, :func:`moorline.physics.hydro.nodal_drag_forces`);
* added mass ``M_a``, the added-mass force ``-M_a a`` and its position derivative, and the
  fluid-inertia force with its position derivative
  (:func:`moorline.physics.hydro.added_mass_blocks`,
  :func:`~moorline.physics.hydro.added_mass_position_derivative`,
  :func:`~moorline.physics.hydro.fluid_inertia_forces`).

Sign conventions are the dynamic model's: the blocks are ``K = -dF/dx``, ``C = -dF/dv`` and
``M_a = -dF/da`` of the forces ``F`` on the element's nodes, ordered ``(x1, x2)``.

Tabulated laws (:mod:`moorline.physics.load_strain`) are evaluated from the coefficients of
scipy's :class:`~scipy.interpolate.PchipInterpolator` of each table (and of its derivative),
taken once by :class:`TableLaws`: a binary search for the interval (scipy's rule, the last one
closed on the right), the polynomial summed as scipy's ``PPoly`` sums it, the same
compression-free and linear-extrapolation rules as :meth:`~.load_strain.StrainTable.__call__`,
so the tension and its exact tangent equal the numpy path's to round-off. The fibre-rope
dynamic stiffness of :func:`moorline.mesh.dynamic_mesh` is the linear law (``EA = EA_d``)
about a per-element strain offset, which the kernel takes as it is.

Viscoelastic (standard linear solid) elements, flagged in a row of the packed properties with
their ``EA1`` and ``tau``, follow :func:`moorline.physics.material.sls_update_exponential`
with its slack rule: the Maxwell-branch force at the start of the step and the step size enter
through three rows held over the step (``exp(-dt/tau) Q_old``, ``dQ/deps`` and the material
strain at the start, :func:`set_viscoelastic_step`, the same arithmetic as the numpy update);
:func:`maxwell_forces` gives the new Maxwell-branch forces at the end of the step. The
source's incremental update (Tuah eq. 2.2.b.3) and MoorDyn's static-dynamic and Syrope ropes
are not in the kernel (their systems stay on the numpy path of
:class:`~moorline.solvers.dynamic_model.DynamicModel`).

Division follows numpy (``error_model="numpy"``: inf/nan, no exception), and ``fastmath`` is
off so that the order of operations is kept. The first call compiles the kernels (about 2 s);
``cache=True`` stores the machine code in a directory named by the kernels' sources
(:mod:`moorline.numba_cache`; or in ``NUMBA_CACHE_DIR``), so later processes load it (about
0.2 s, plus 0.3 s to import numba).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..jit import numba
from .element import element_geometry
from .load_strain import StrainLaws
from .sag import MAX_ITERATIONS, NOISE, SATURATION, SagCorrection

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]
BoolArray = NDArray[np.bool_]

_TINY = float(np.finfo(float).tiny)

# rows of the packed per-element property array; the last three: the standard linear solid's
# update over the current step (set_viscoelastic_step)
(_L0, _EA, _SLACK, _SMOOTH, _BA, _DIAM, _CD, _CT, _CA, _CAT, _RHO, _OFFSET, _W, _KEEP,
 _NODE_DRAG, _DASHPOT, _EA1, _TAU, _VISCO, _AQ, _DQ, _START) = range(22)
_N_PROPS = 22


class ElementLoads(NamedTuple):
    """Outputs of :func:`element_loads` / :class:`FusedLoads`.

    Attributes
    ----------
    element_forces
        Axial force (tension incl. Kelvin-Voigt damping) of each element on its two nodes,
        shape (n_el, 2, 3).
    total_forces
        Axial + drag + fluid inertia + added-mass force on each element's nodes, (n_el, 2, 3).
    added_mass_force
        ``-M_a a`` on each element's nodes, (n_el, 2, 3) (zero without added mass).
    tension
        Axial force including the damping term, (n_el,).
    strain
        ``l / L0 - 1`` (without the strain offset), (n_el,).
    taut
        ``strain - offset > -smoothing``: where the dashpot acts (everywhere with
        ``slack_damping``), (n_el,).
    K, C, Ma
        ``-dF/dx``, ``-dF/dv``, ``-dF/da`` element blocks (n_el, 6, 6); ``None`` unless
        ``tangent`` (and, for ``Ma``, ``with_added_mass``).
    Ka
        The added-mass forces' part of ``K``, ``-d(-M_a(x) a)/dx`` (n_el, 6, 6) (HHT weights
        these inertial forces by 1, the rest of ``K`` by ``1 + alpha``); ``None`` unless
        ``tangent`` and ``with_added_mass``.
    nodal
        ``total_forces`` summed to the nodes, (n_nodes, 3).
    nodal_added_mass
        ``added_mass_force`` summed to the nodes, (n_nodes, 3).
    maxwell
        Maxwell-branch force of every element at the end of the step (the viscoelastic
        elements' updated, the others' as given), (n_el,); ``None`` without viscoelastic
        elements.
    """

    element_forces: FloatArray
    total_forces: FloatArray
    added_mass_force: FloatArray
    tension: FloatArray
    strain: FloatArray
    taut: BoolArray
    K: FloatArray | None
    C: FloatArray | None
    Ma: FloatArray | None
    nodal: FloatArray
    nodal_added_mass: FloatArray
    maxwell: FloatArray | None = None
    Ka: FloatArray | None = None


@numba.njit(cache=True, fastmath=False, error_model="numpy", inline="always")
def _projector(alpha, t, p, r, c):
    """Entry ``(r, c)`` of ``alpha (I - t t^T) + t p^T``, evaluated as hydro._projector_terms
    does: ``t_r (p_c - alpha t_c) + alpha delta_rc``."""
    g = t[r] * (p[c] - alpha * t[c])
    return g + alpha if r == c else g


@numba.njit(cache=True, fastmath=False, error_model="numpy")
def _table_law(k, g, EA, start, breaks, coef, end_slope):
    """``f(g)`` and ``f'(g)`` of table ``k`` (:meth:`StrainLaws.evaluate
    <moorline.physics.load_strain.StrainLaws.evaluate>` for one element): ``EA g``, ``EA`` for
    ``g < 0`` (or NaN); the PCHIP polynomials inside, linear beyond the last point."""
    if not g >= 0.0:
        return EA * g, EA
    lo = start[k]
    hi = start[k + 1] - 1          # index of the last breakpoint
    end = breaks[hi]
    inside = min(g, end)
    beyond = max(g - end, 0.0)
    # interval: breaks[i] <= inside < breaks[i + 1], the last one closed on the right
    # (scipy's find_interval)
    if inside == end:
        i = hi - 1
    else:
        i = lo
        top = hi - 1
        while i < top:
            mid = (i + top + 1) // 2
            if inside < breaks[mid]:
                top = mid - 1
            else:
                i = mid
    s = inside - breaks[i]
    s2 = s * s
    # the sums of scipy's evaluate_poly1: c[3] + c[2] s + c[1] s^2 + c[0] s^3, left to right
    f = ((coef[3, i] + coef[2, i] * s) + coef[1, i] * s2) + coef[0, i] * (s2 * s)
    df = (coef[6, i] + coef[5, i] * s) + coef[4, i] * s2
    return f + end_slope[k] * beyond, df


@numba.njit(cache=True, fastmath=False, error_model="numpy", inline="always")
def _axial_law(strain, s_band, sr, EA, k, start, breaks, coef, end_slope):
    """Tension and ``dT/deps`` of the law of :func:`moorline.physics.element.axial_tension` at
    ``strain`` (less the offset): linear (``k < 0``) or table ``k``, with the slack band."""
    safe_s = s_band if s_band > 0 else 1.0
    shifted = strain + s_band
    if k < 0:
        if strain >= s_band:
            return EA * strain, EA
        if strain > -s_band:
            return EA * (shifted * shifted) / (4 * safe_s), EA * shifted / (2 * safe_s)
        return sr * EA * shifted, sr * EA
    # the table at the regularized strain g: T = f(g), dT/deps = f'(g) g'
    if strain >= s_band:
        g = strain
        dg = 1.0
    elif strain > -s_band:
        g = (shifted * shifted) / (4 * safe_s)
        dg = shifted / (2 * safe_s)
    else:
        dg = sr
        g = dg * shifted
    T, df = _table_law(k, g, EA, start, breaks, coef, end_slope)
    return T, df * dg


@numba.njit(cache=True, fastmath=False, error_model="numpy", inline="always")
def _sls_law(strain, props, e):
    """Tension, Maxwell-branch force and ``dT/deps`` of viscoelastic element ``e`` at the
    strain ``l / L0 - 1`` at the end of the step: :func:`moorline.physics.material.\
sls_update_exponential` with its slack rule, from the rows :func:`set_viscoelastic_step` set
    (same order of operations)."""
    EA = props[_EA, e]
    aq = props[_AQ, e]
    c = props[_DQ, e]
    start = props[_START, e]
    Q = aq + c * (strain - start)
    T = EA * strain + Q
    tangent = EA + c
    if T < 0.0:  # slack: the material at zero force, the chord shorter than it
        material = (c * start - aq) / tangent
        k_slack = props[_SLACK, e] * EA
        return k_slack * (strain - material), -EA * material, k_slack
    return T, Q, tangent


@numba.njit(cache=True, fastmath=False, error_model="numpy", inline="always")
def _chord_factor(T, weight2, perp2, phi):
    """:func:`moorline.physics.sag.chord_factor` for one element."""
    tp = max(T, 0.0)
    q = 24.0 * tp * tp + weight2 / SATURATION
    if not q > 0:
        return 1.0, 0.0, 0.0, 0.0
    return 1.0 - phi * perp2 / q, phi * perp2 * 48.0 * tp / (q * q), -phi / q, -perp2 / q


@numba.njit(cache=True, fastmath=False, error_model="numpy")
def _sag_law(length, L0, EA, s_band, sr, offset, w, nz, phi, k, start, breaks, coef,
             end_slope):
    """:func:`moorline.physics.sag.sag_tension` for one element: the same safeguarded Newton
    iteration, stopped when this element's residual is at its round-off or its step below
    ``1e-15 |T|``. Returns ``T``,
    ``dT/dc``, ``dT/dq`` (``q = W_p^2``), ``dT/dphi`` and ``W^2``."""
    weight2 = (w * L0) ** 2
    perp2 = weight2 * (1.0 - nz * nz)
    g_min = _chord_factor(0.0, weight2, perp2, phi)[0]
    lo = _axial_law(length / 1.0 / L0 - 1.0 - offset, s_band, sr, EA, k, start, breaks, coef,
                    end_slope)[0]
    hi = _axial_law(length / g_min / L0 - 1.0 - offset, s_band, sr, EA, k, start, breaks,
                    coef, end_slope)[0]
    s0 = L0 * (1.0 + offset)
    short = 1.0 - length / s0
    first = 0.0
    if short > 0:
        first = math.sqrt(max((phi * perp2 / short - weight2 / SATURATION) / 24.0, 0.0))
    T = min(max(first, lo), hi)
    step_old = step = hi - lo
    for _ in range(MAX_ITERATIONS):
        g, g_T, _g_q, _g_phi = _chord_factor(T, weight2, perp2, phi)
        A, slope = _axial_law(length / g / L0 - 1.0 - offset, s_band, sr, EA, k, start,
                              breaks, coef, end_slope)
        dA = slope / L0
        F = T - A
        dF = 1.0 + dA * length * g_T / (g * g)
        if F < 0:
            lo = T
        if F > 0:
            hi = T
        bisect = (((T - hi) * dF - F) * ((T - lo) * dF - F) > 0) \
            or (abs(2.0 * F) > abs(step_old * dF))
        step_old = step
        step = T - 0.5 * (lo + hi) if bisect else F / dF
        if abs(F) <= NOISE * (abs(T) + dA * length / g):
            step = 0.0
        T = T - step
        if abs(step) <= 1e-15 * abs(T):
            break
    g, g_T, g_q, g_phi = _chord_factor(T, weight2, perp2, phi)
    slope = _axial_law(length / g / L0 - 1.0 - offset, s_band, sr, EA, k, start, breaks,
                       coef, end_slope)[1]
    dA = slope / L0
    scale = dA / (g * (1.0 + dA * length * g_T / (g * g)))
    return T, scale, -scale * length * g_q / g, -scale * length * g_phi / g, weight2


@numba.njit(cache=True, fastmath=False, error_model="numpy", inline="always")
def _drag_share(u0, u1, u2, t, cn, ct, inv_l, du_dv):
    """One node's share of an element's drag at the relative velocity ``u``
    (:func:`moorline.physics.hydro._drag_share`, same order of operations): the force, ``w``
    (``u``'s normal part) and the coefficients of its derivatives, the velocity block
    ``t (hb t^T) + w (cw w^T) + hc I`` (``u`` changing by ``du_dv`` times the velocity) and
    the position block (``x2``) ``projector(alpha, t, p) + w (cx w^T)``."""
    s = u0 * t[0] + u1 * t[1] + u2 * t[2]
    w = (u0 - s * t[0], u1 - s * t[1], u2 - s * t[2])
    un = math.sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2])
    abs_s = abs(s)
    a_n = cn * un
    a_t = ct * abs_s * s
    fd = (a_n * w[0] + a_t * t[0], a_n * w[1] + a_t * t[1], a_n * w[2] + a_t * t[2])
    inv = 1.0 / un if un > 0.0 else 0.0
    cnw = cn * un
    beta = 2.0 * ct * abs_s - cnw
    alpha = s * (ct * abs_s - cnw) * inv_l
    p = (beta * inv_l * w[0], beta * inv_l * w[1], beta * inv_l * w[2])
    return (fd, w, du_dv * beta, du_dv * cn * inv, du_dv * cnw, alpha, p,
            -cn * s * inv * inv_l)


@numba.njit(cache=True, fastmath=False, error_model="numpy")
def _kernel(x, v, a, uf, af, elements, props, laws, sag_on, phi, dphi, tangent, with_drag,
            with_added_mass, el_forces, total, f_am, tension, strain_out, taut_out, K, C, Ma,
            nodal, nodal_am, Ka):
    """The fused loop; see :func:`element_loads`. Every operation is written in the order the
    numpy path evaluates it, so that both agree to round-off. Small vectors are tuples so that
    the unrolled 3x3 loops keep them in registers. ``sag_on``: elements with ``phi != 0``
    follow the sag-corrected law (:mod:`moorline.physics.sag`), ``dphi`` (n_el, 2, 3) the
    derivatives of their ``phi`` with respect to their nodes. ``Ka``: the added-mass
    forces' part of ``K`` (with ``tangent``)."""
    law, start, breaks, coef, end_slope = laws
    nodal[:, :] = 0.0
    nodal_am[:, :] = 0.0
    zero3 = (0.0, 0.0, 0.0)
    for e in range(elements.shape[0]):
        i = elements[e, 0]
        j = elements[e, 1]
        L0 = props[_L0, e]
        EA = props[_EA, e]
        s_band = props[_SMOOTH, e]
        BA = props[_BA, e]

        # ---- geometry (element.element_geometry; hydro._tangent clamps the length) ----
        d0 = x[j, 0] - x[i, 0]
        d1 = x[j, 1] - x[i, 1]
        d2 = x[j, 2] - x[i, 2]
        length = math.sqrt(d0 * d0 + d1 * d1 + d2 * d2)
        lc = max(length, _TINY)
        t = (d0 / lc, d1 / lc, d2 / lc)

        # ---- axial tension with the smooth slack band (element.axial_tension) ----
        strain_total = length / L0 - 1.0
        strain = strain_total - props[_OFFSET, e]
        sag = sag_on and phi[e] != 0.0
        dq = dTq = dTphi = 0.0
        if sag:  # the sag-corrected chord (sag.sag_tension)
            T, dT_dl, dTq, dTphi, weight2 = _sag_law(
                length, L0, EA, s_band, props[_SLACK, e], props[_OFFSET, e], props[_W, e],
                t[2], phi[e], law[e], start, breaks, coef, end_slope)
            dq = -2.0 * weight2 * t[2] / length  # dq/dx2 = dq (e_z - n_z n)
        elif props[_VISCO, e] != 0.0:  # standard linear solid, the step's rows
            T, _q, slope = _sls_law(strain_total, props, e)
            dT_dl = slope / L0
        else:
            T, slope = _axial_law(strain, s_band, props[_SLACK, e], EA, law[e], start, breaks,
                                  coef, end_slope)
            # the model converts dT/dl to dT/deps and back (DynamicModel._axial_tension)
            dT_dl = ((slope / L0) * L0) / L0
        # Kelvin-Voigt dashpot: the share held over the step (set_dashpot_shares; 1 with
        # slack_damping), independent of this state
        share = props[_DASHPOT, e]
        taut = share > 0
        dv0 = v[j, 0] - v[i, 0]
        dv1 = v[j, 1] - v[i, 1]
        dv2 = v[j, 2] - v[i, 2]
        ndv = t[0] * dv0 + t[1] * dv1 + t[2] * dv2
        T = T + BA * share * (ndv / L0)
        tension[e] = T
        strain_out[e] = strain_total
        taut_out[e] = taut
        f = (T * t[0], T * t[1], T * t[2])
        for c in range(3):
            el_forces[e, 0, c] = f[c]
            el_forces[e, 1, c] = -f[c]
        fn = (-f[0], -f[1], -f[2])  # accumulated totals of node 1 (f) and node 2 (fn)

        # ---- Morison drag: at the element's mean velocity, the same share on both nodes
        # (hydro.drag_forces), or each node's share at its own velocity (_NODE_DRAG,
        # hydro.nodal_drag_forces); the derivative coefficients of node 1's (0) and 2's (1)
        inv_l = 1.0 / lc
        node_drag = props[_NODE_DRAG, e] != 0.0
        w0 = w1 = p0d = p1d = zero3
        hb0 = cw0 = hc0 = al0 = cx0 = hb1 = cw1 = hc1 = al1 = cx1 = 0.0
        if with_drag:
            half = 0.25 * props[_RHO, e] * L0 * props[_DIAM, e]
            cn = half * props[_CD, e]
            ct = half * np.pi * props[_CT, e]
            if node_drag:
                fd, w0, hb0, cw0, hc0, al0, p0d, cx0 = _drag_share(
                    uf[e, 0] - v[i, 0], uf[e, 1] - v[i, 1], uf[e, 2] - v[i, 2], t, cn, ct,
                    inv_l, -1.0)
                fd1, w1, hb1, cw1, hc1, al1, p1d, cx1 = _drag_share(
                    uf[e, 0] - v[j, 0], uf[e, 1] - v[j, 1], uf[e, 2] - v[j, 2], t, cn, ct,
                    inv_l, -1.0)
            else:
                fd, w0, hb0, cw0, hc0, al0, p0d, cx0 = _drag_share(
                    uf[e, 0] - 0.5 * (v[i, 0] + v[j, 0]), uf[e, 1] - 0.5 * (v[i, 1] + v[j, 1]),
                    uf[e, 2] - 0.5 * (v[i, 2] + v[j, 2]), t, cn, ct, inv_l, -0.5)
                fd1 = fd
            f = (f[0] + fd[0], f[1] + fd[1], f[2] + fd[2])
            fn = (fn[0] + fd1[0], fn[1] + fd1[1], fn[2] + fd1[2])

        # ---- fluid inertia and added mass (hydro.fluid_inertia_forces, added_mass_blocks) --
        m = mca = dc = sf = 0.0
        if with_added_mass:
            D = props[_DIAM, e]
            m = 0.5 * props[_RHO, e] * 0.25 * np.pi * D * D * L0
            ca = props[_CA, e]
            dc = m * (props[_CAT, e] - ca)
            mca = m * ca
            sf = t[0] * af[e, 0] + t[1] * af[e, 1] + t[2] * af[e, 2]
            m1 = m * (1.0 + ca)
            fi = (m1 * af[e, 0] + (dc * sf) * t[0], m1 * af[e, 1] + (dc * sf) * t[1],
                  m1 * af[e, 2] + (dc * sf) * t[2])
            f = (f[0] + fi[0], f[1] + fi[1], f[2] + fi[2])
            fn = (fn[0] + fi[0], fn[1] + fi[1], fn[2] + fi[2])
            for r in range(3):  # -M_a a_k, M_a = (m Ca) I + m (Cat - Ca) t t^T per node
                m0 = (mca if r == 0 else 0.0) + dc * (t[r] * t[0])
                m1_ = (mca if r == 1 else 0.0) + dc * (t[r] * t[1])
                m2 = (mca if r == 2 else 0.0) + dc * (t[r] * t[2])
                f_am[e, 0, r] = -(m0 * a[i, 0] + m1_ * a[i, 1] + m2 * a[i, 2])
                f_am[e, 1, r] = -(m0 * a[j, 0] + m1_ * a[j, 1] + m2 * a[j, 2])
        else:
            for k in range(2):
                for c in range(3):
                    f_am[e, k, c] = 0.0
        for c in range(3):
            f0 = f[c] + f_am[e, 0, c]
            f1 = fn[c] + f_am[e, 1, c]
            total[e, 0, c] = f0
            total[e, 1, c] = f1
            # summed to the nodes in the order of hydro.sum_to_nodes (np.bincount)
            nodal[i, c] += f0
            nodal_am[i, c] += f_am[e, 0, c]
        for c in range(3):
            nodal[j, c] += total[e, 1, c]
            nodal_am[j, c] += f_am[e, 1, c]

        if not tangent:
            continue
        # ---- blocks K = -dF/dx, C = -dF/dv, Ma = -dF/da -------------------------------
        # axial: element.tangent_blocks, the dashpot rotation term (DynamicModel.
        # _axial_tangent) and the dashpot (_axial_damping_blocks)
        geo = T / length
        damping = BA * share / (L0 * length)
        cdash = BA * share / L0
        tr = (dv0 - ndv * t[0], dv1 - ndv * t[1], dv2 - ndv * t[2])
        # fluid inertia through t, and the added-mass force -M_a(x) a_k of node k through t
        # (hydro.fluid_inertia_forces, hydro.added_mass_position_derivative)
        cf = dc / lc
        alpha_i = cf * sf
        pi_ = zero3
        cm = -m * (props[_CAT, e] - props[_CA, e]) / lc
        alpha_0 = alpha_1 = 0.0
        p0 = p1 = zero3
        if with_added_mass:
            pi_ = (cf * (af[e, 0] - sf * t[0]), cf * (af[e, 1] - sf * t[1]),
                   cf * (af[e, 2] - sf * t[2]))
            s0 = t[0] * a[i, 0] + t[1] * a[i, 1] + t[2] * a[i, 2]
            s1 = t[0] * a[j, 0] + t[1] * a[j, 1] + t[2] * a[j, 2]
            alpha_0 = cm * s0
            alpha_1 = cm * s1
            p0 = (cm * (a[i, 0] - s0 * t[0]), cm * (a[i, 1] - s0 * t[1]),
                  cm * (a[i, 2] - s0 * t[2]))
            p1 = (cm * (a[j, 0] - s1 * t[0]), cm * (a[j, 1] - s1 * t[1]),
                  cm * (a[j, 2] - s1 * t[2]))
        for r in range(3):
            for c in range(3):
                nn = t[r] * t[c]
                eye = 1.0 if r == c else 0.0
                k = dT_dl * nn + geo * (eye - nn)
                if damping != 0.0:
                    k = k + damping * t[r] * tr[c]
                k00 = k
                k01 = -k
                k10 = -k
                k11 = k
                if sag:  # sag.sag_blocks: through the direction and the node heights
                    kd = t[r] * (dTq * (dq * ((1.0 if c == 2 else 0.0) - t[2] * t[c])))
                    a1 = t[r] * (dTphi * dphi[e, 0, c])
                    a2 = t[r] * (dTphi * dphi[e, 1, c])
                    k00 = k00 + kd - a1
                    k01 = k01 - kd - a2
                    k10 = k10 - kd + a1
                    k11 = k11 + kd + a2
                cc = cdash * t[r] * t[c]
                c00 = cc
                c01 = -cc
                c10 = -cc
                c11 = cc
                if with_drag:
                    # the position blocks are [-g, g] in a node's rows: subtracting adds g to
                    # x1's; dF/dv: the same block d on the four node-node blocks, or (node
                    # drag) each node's own on its diagonal block
                    g = _projector(al0, t, p0d, r, c) + w0[r] * (cx0 * w0[c])
                    d = t[r] * (hb0 * t[c]) + w0[r] * (cw0 * w0[c])
                    if r == c:
                        d = d + hc0
                    k00 = k00 + g
                    k01 = k01 - g
                    c00 = c00 - d
                    if node_drag:
                        g = _projector(al1, t, p1d, r, c) + w1[r] * (cx1 * w1[c])
                        d1 = t[r] * (hb1 * t[c]) + w1[r] * (cw1 * w1[c])
                        if r == c:
                            d1 = d1 + hc1
                        c11 = c11 - d1
                    else:
                        c01 = c01 - d
                        c10 = c10 - d
                        c11 = c11 - d
                    k10 = k10 + g
                    k11 = k11 - g
                g0 = g1 = 0.0
                if with_added_mass:
                    g = _projector(alpha_i, t, pi_, r, c)
                    g0 = _projector(alpha_0, t, p0, r, c)
                    g1 = _projector(alpha_1, t, p1, r, c)
                    k00 = (k00 + g) + g0
                    k01 = (k01 - g) - g0
                    k10 = (k10 + g) + g1
                    k11 = (k11 - g) - g1
                    mb = (mca if r == c else 0.0) + dc * nn
                    Ma[e, r, c] = mb
                    Ma[e, r, c + 3] = 0.0
                    Ma[e, r + 3, c] = 0.0
                    Ma[e, r + 3, c + 3] = mb
                Ka[e, r, c] = g0
                Ka[e, r, c + 3] = -g0
                Ka[e, r + 3, c] = g1
                Ka[e, r + 3, c + 3] = -g1
                K[e, r, c] = k00
                K[e, r, c + 3] = k01
                K[e, r + 3, c] = k10
                K[e, r + 3, c + 3] = k11
                C[e, r, c] = c00
                C[e, r, c + 3] = c01
                C[e, r + 3, c] = c10
                C[e, r + 3, c + 3] = c11


@numba.njit(cache=True, fastmath=False, error_model="numpy", inline="always")
def hht_stiffness(K, Ka, with_added_mass, ck, e, p, q):
    """``ck K[e, p, q]`` of :func:`_kernel`'s blocks with their added-mass forces' part
    ``Ka`` weighted 1 instead of ``ck`` (HHT, ``ck = 1 + alpha``: those forces are inertial,
    weighted 1 in the residual; as :func:`moorline.solvers.newmark._hht_stiffness`)."""
    if ck == 1.0 or not with_added_mass:
        return ck * K[e, p, q]
    return ck * (K[e, p, q] - (1.0 - 1.0 / ck) * Ka[e, p, q])


@numba.njit(cache=True, fastmath=False, error_model="numpy")
def _midpoints_into(x, elements, out):
    for e in range(elements.shape[0]):
        i = elements[e, 0]
        j = elements[e, 1]
        for c in range(3):
            out[e, c] = 0.5 * (x[i, c] + x[j, c])


def midpoints(x: FloatArray, elements: IntArray) -> FloatArray:
    """Element midpoints ``(x1 + x2) / 2``, shape (n_elements, 3) (compiled loop).

    Parameters
    ----------
    x
        Node positions, shape (n_nodes, 3), float64.
    elements
        Node indices of each element, shape (n_elements, 2), int64.
    """
    out = np.empty((elements.shape[0], 3))
    _midpoints_into(x, elements, out)
    return out


def _per_element(value: ArrayLike, n_el: int) -> FloatArray:
    return np.broadcast_to(np.asarray(value, dtype=float), (n_el,))


def pack_properties(
    n_el: int, length0: ArrayLike, EA: ArrayLike, slack_ratio: ArrayLike,
    smoothing: ArrayLike, BA: ArrayLike, diameter: ArrayLike, Cd: ArrayLike, Ct: ArrayLike,
    Ca: ArrayLike, Cat: ArrayLike, rho: ArrayLike, offset: ArrayLike | None = None,
    weight_per_length: ArrayLike | None = None, slack_damping: ArrayLike = False,
    node_drag: ArrayLike = False, EA1: ArrayLike = 0.0, tau: ArrayLike = 0.0,
    viscoelastic: ArrayLike = False,
) -> FloatArray:
    """Per-element properties (scalars broadcast) packed into one (22, n_el) array, in the
    row order the kernel reads them (after the hydrodynamic ones: the strain offset and the
    submerged weight per length of the sag correction, ``None``: 0; 1 where the dashpot is
    kept whole in slack elements, ``slack_damping``, else 0; 1 where each node's drag share is
    at its own velocity, ``node_drag``, else 0; the dashpot share over the current step, 1
    until :func:`set_dashpot_shares` sets it; the standard linear solid's Maxwell-branch
    stiffness ``EA1`` [force] and relaxation time ``tau`` [time], 1 where the element is
    ``viscoelastic``, else 0; three rows of its update over the current step, 0 until
    :func:`set_viscoelastic_step` sets them)."""
    props = np.empty((_N_PROPS, n_el))
    for row, value in enumerate((length0, EA, slack_ratio, smoothing, BA, diameter, Cd, Ct,
                                 Ca, Cat, rho, 0.0 if offset is None else offset,
                                 0.0 if weight_per_length is None else weight_per_length,
                                 np.asarray(slack_damping, dtype=float),
                                 np.asarray(node_drag, dtype=float), 1.0, EA1, tau,
                                 np.asarray(viscoelastic, dtype=float), 0.0, 0.0, 0.0)):
        props[row] = _per_element(value, n_el)
    return props


@numba.njit(cache=True, fastmath=False, error_model="numpy")
def set_dashpot_shares(strain_before, props):
    """Set the dashpot share row of ``props`` from each element's strain at the start of the
    step (``l / L0 - 1`` without the offset, (n_el,)): 1 where the dashpot is kept whole
    (``slack_damping``), else the share of
    :func:`moorline.physics.element.lagged_dashpot_share`."""
    for e in range(props.shape[1]):
        if props[_KEEP, e] != 0.0:
            props[_DASHPOT, e] = 1.0
            continue
        strain = strain_before[e] - props[_OFFSET, e]
        s_band = props[_SMOOTH, e]
        if s_band > 0:
            props[_DASHPOT, e] = min(max((strain + s_band) / (2 * s_band), 0.0), 1.0)
        else:
            props[_DASHPOT, e] = 1.0 if strain > 0 else 0.0


@numba.njit(cache=True, fastmath=False, error_model="numpy")
def set_viscoelastic_step(strain_before, maxwell_before, dt, props):
    """Set the rows of the viscoelastic elements' update over a step of ``dt`` [time] from
    their strain ``l / L0 - 1`` and Maxwell-branch force [force] at its start (n_el,): the
    terms of :func:`moorline.physics.material.sls_update_exponential` that do not depend on
    the strain at the end, ``exp(-dt/tau) Q_old`` (as ``Q_old + expm1(-dt/tau) Q_old``),
    ``dQ/deps = EA1 (1 - exp(-dt/tau)) tau / dt`` (``EA1`` at ``dt = 0``) and the material
    strain at the start, ``max(eps_old, -Q_old / EA)``."""
    for e in range(props.shape[1]):
        if props[_VISCO, e] == 0.0:
            continue
        minus_h = -(dt / props[_TAU, e])
        a_minus_1 = math.expm1(minus_h)
        phi = a_minus_1 / minus_h if minus_h < 0.0 else 1.0
        q = maxwell_before[e]
        props[_DQ, e] = props[_EA1, e] * phi
        props[_AQ, e] = q + a_minus_1 * q
        props[_START, e] = max(strain_before[e], -q / props[_EA, e])


@numba.njit(cache=True, fastmath=False, error_model="numpy")
def maxwell_forces(strain, props, out):
    """The viscoelastic elements' Maxwell-branch forces at the strains ``l / L0 - 1`` at the
    end of the step (n_el,) into ``out`` (the others' entries are left as they are), with the
    rows :func:`set_viscoelastic_step` set for the step."""
    for e in range(props.shape[1]):
        if props[_VISCO, e] != 0.0:
            out[e] = _sls_law(strain[e], props, e)[1]


class TableLaws(NamedTuple):
    """The tabulated laws of :class:`~moorline.physics.load_strain.StrainLaws` in flat arrays
    (the form the kernel reads; :meth:`of` builds it).

    Attributes
    ----------
    law
        Table of each element, ``-1``: the linear law ``EA eps`` (n_el,), int64.
    start
        Index of each table's first breakpoint in ``breaks``; ``start[-1]`` = their number
        (n_tables + 1,).
    breaks
        The tables' breakpoints (strains), one table after the other.
    coef
        Polynomial coefficients of the interval starting at each breakpoint (7, len(breaks)):
        rows 0-3 scipy's ``PchipInterpolator.c`` of the law (highest power first), rows 4-6
        those of its derivative (``.derivative().c``); the column of a table's last point
        is unused.
    end_slope
        Slope of each table at its last point (its linear extrapolation) (n_tables,).
    """

    law: IntArray
    start: IntArray
    breaks: FloatArray
    coef: FloatArray
    end_slope: FloatArray

    @classmethod
    def of(cls, laws: StrainLaws | None, n_el: int) -> TableLaws:
        """Flat arrays of a :class:`~moorline.physics.load_strain.StrainLaws` (``None``: every
        element linear)."""
        if laws is None:
            return cls(np.full(n_el, -1, dtype=np.int64), np.zeros(1, dtype=np.int64),
                       np.zeros(0), np.zeros((7, 0)), np.zeros(0))
        # a writeable copy: a read-only array (broadcast_to's view) is another numba type, and
        # every compiled step taking it would be compiled a second time
        law = np.array(np.broadcast_to(laws.ids, (n_el,)), dtype=np.int64)
        breaks, coef, start = [], [], [0]
        for table in laws.tables:
            f, df = table._f, table._df
            breaks.append(np.asarray(f.x, dtype=float))
            block = np.zeros((7, len(f.x)))
            block[:4, :-1] = f.c
            block[4:, :-1] = df.c
            coef.append(block)
            start.append(start[-1] + len(f.x))
        return cls(law, np.asarray(start, dtype=np.int64), np.concatenate(breaks),
                   np.ascontiguousarray(np.concatenate(coef, axis=1)),
                   np.array([t.end_slope for t in laws.tables], dtype=float))


class FusedLoads:
    """Element loads of a fixed set of elements, evaluated by the compiled kernel.

    Holds the packed element properties (and scratch arrays) so that a call costs one
    dispatch into the kernel plus the allocation of its outputs.

    Parameters
    ----------
    elements
        Node indices of each element, shape (n_el, 2).
    n_nodes
        Number of nodes of the positions passed to :meth:`__call__`.
    length0, EA, slack_ratio, smoothing, BA, diameter, Cd, Ct, Ca, Cat, rho
        Element properties, scalars or (n_el,) arrays (see :func:`element_loads`).
    laws, offset
        Tabulated tension-strain laws (:class:`~moorline.physics.load_strain.StrainLaws`)
        and strain offsets (n_el,) of the elements' axial laws, as
        :func:`moorline.physics.element.axial_tension` takes them (``None``: linear, 0).
    with_drag, with_added_mass
        Whether to compute the Morison drag and the added-mass / fluid-inertia terms.
        Default: where any drag (added-mass) coefficient and ``rho`` are nonzero.
    reuse_buffers
        Write every call's outputs into the same arrays (a little faster); the arrays of one
        call are then overwritten by the next, copy what you keep. Default ``False``: fresh
        arrays every call, safe to store (e.g. in an accepted time step's evaluation).
    sag, weight_per_length
        The sag correction (:class:`moorline.physics.sag.SagCorrection`, its ``phi`` taken
        at every call's positions) and the elements' submerged weight per length; ``None``:
        straight elements.
    slack_damping
        Keep the Kelvin-Voigt dashpot whole in slack elements (share 1 at every strain,
        MoorDyn's law; :class:`~moorline.solvers.dynamic_model.DynamicModel`'s option), a
        bool or one per element; default: blended off over the slack band.
    node_drag
        Each node's share of an element's drag at that node's own velocity
        (:func:`moorline.physics.hydro.nodal_drag_forces`, MoorDyn's node-based drag; the
        model's ``drag_velocity: node``) instead of at the element's mean velocity
        (:func:`~moorline.physics.hydro.drag_forces`); a bool or one per element.
    EA1, tau, viscoelastic
        The standard linear solid (:func:`moorline.physics.material.sls_update_exponential`,
        with its slack rule) of the elements flagged ``viscoelastic`` (a bool or one per
        element): Maxwell-branch stiffness [force] and relaxation time [time]; their tension
        then needs the state at the start of the step (:meth:`__call__`).
    """

    def __init__(
        self, elements: IntArray, n_nodes: int, length0: ArrayLike, EA: ArrayLike,
        slack_ratio: ArrayLike, smoothing: ArrayLike, BA: ArrayLike, diameter: ArrayLike,
        Cd: ArrayLike, Ct: ArrayLike, Ca: ArrayLike, Cat: ArrayLike, rho: ArrayLike,
        laws: StrainLaws | None = None, offset: ArrayLike | None = None,
        with_drag: bool | None = None, with_added_mass: bool | None = None,
        reuse_buffers: bool = False, sag: SagCorrection | None = None,
        weight_per_length: ArrayLike | None = None, slack_damping: ArrayLike = False,
        node_drag: ArrayLike = False, EA1: ArrayLike = 0.0, tau: ArrayLike = 0.0,
        viscoelastic: ArrayLike = False,
    ) -> None:
        self.elements = np.ascontiguousarray(elements, dtype=np.int64)
        n_el = self.elements.shape[0]
        self.n_el = n_el
        self.n_nodes = int(n_nodes)
        self.props = pack_properties(n_el, length0, EA, slack_ratio, smoothing, BA, diameter,
                                     Cd, Ct, Ca, Cat, rho, offset, weight_per_length,
                                     slack_damping, node_drag, EA1, tau, viscoelastic)
        self.viscoelastic = bool(np.any(self.props[_VISCO] != 0.0))
        self.sag = sag
        self._no_sag = (np.zeros(n_el), np.zeros((n_el, 2, 3)))
        self.laws = TableLaws.of(laws, n_el)
        wet = bool(np.any(self.props[_RHO] > 0))
        if with_drag is None:
            with_drag = wet and bool(np.any(self.props[_CD] > 0) or np.any(self.props[_CT] > 0))
        if with_added_mass is None:
            with_added_mass = wet and bool(np.any(self.props[_CA] > 0)
                                           or np.any(self.props[_CAT] > 0))
        self.with_drag = bool(with_drag)
        self.with_added_mass = bool(with_added_mass)
        self._zero_fluid = np.zeros((n_el, 3))
        self._scratch_blocks = tuple(np.empty((n_el, 6, 6)) for _ in range(4))  # not tangent
        self.reuse_buffers = reuse_buffers
        self._buffers = (self._allocate(True), self._allocate(False)) if reuse_buffers else None

    def _allocate(self, tangent: bool) -> tuple:
        """Output arrays (``K``, ``C``, ``Ma``, ``Ka``: a shared scratch unless
        ``tangent``)."""
        n_el, n = self.n_el, self.n_nodes
        empty = np.empty
        if tangent:
            K, C, Ma, Ka = (empty((n_el, 6, 6)) for _ in range(4))
        else:
            K, C, Ma, Ka = self._scratch_blocks
        return (empty((n_el, 2, 3)), empty((n_el, 2, 3)), empty((n_el, 2, 3)), empty(n_el),
                empty(n_el), empty(n_el, dtype=np.bool_), K, C, Ma, empty((n, 3)),
                empty((n, 3)), Ka)

    def _fluid(self, value: ArrayLike | None) -> FloatArray:
        if value is None:
            return self._zero_fluid
        if (type(value) is np.ndarray and value.dtype == np.float64
                and value.shape == self._zero_fluid.shape and value.flags.c_contiguous):
            return value
        arr = np.broadcast_to(np.asarray(value, dtype=np.float64), self._zero_fluid.shape)
        return np.ascontiguousarray(arr)

    def __call__(
        self, x: FloatArray, v: FloatArray, a: FloatArray,
        fluid_velocity_mid: ArrayLike | None, fluid_acceleration_mid: ArrayLike | None,
        tangent: bool, strain_before: ArrayLike | None = None,
        maxwell_before: ArrayLike | None = None, dt: float | None = None,
    ) -> ElementLoads:
        """Evaluate the loads at node positions, velocities and accelerations (n_nodes, 3).

        ``fluid_velocity_mid`` and ``fluid_acceleration_mid`` are the fluid kinematics at the
        element midpoints, (n_el, 3) or (3,); ``None`` means still water. ``K`` and ``C`` of
        the result are ``None`` unless ``tangent``, ``Ma`` unless ``tangent`` and
        ``with_added_mass``. ``strain_before``: each element's strain at the start of the
        step (``l / L0 - 1``, (n_el,)), which sets the share of its dashpot
        (:func:`set_dashpot_shares`); ``None``: the strain at ``x`` (a state of its own).
        ``maxwell_before`` (n_el,) [force] and ``dt`` [time]: the Maxwell-branch forces at the
        start of the step and its size, needed with viscoelastic elements (their strain at
        the start is ``strain_before``); the result's ``maxwell`` holds their new values.
        """
        tangent = bool(tangent)
        if self._buffers is not None:
            out = self._buffers[0 if tangent else 1]
        else:
            out = self._allocate(tangent)
        x = np.ascontiguousarray(x, dtype=np.float64)
        if strain_before is None:
            strain_before = element_geometry(x, self.elements)[0] / self.props[_L0] - 1.0
        strain_before = np.ascontiguousarray(strain_before, dtype=np.float64)
        set_dashpot_shares(strain_before, self.props)
        if self.viscoelastic:
            if maxwell_before is None or dt is None:
                raise ValueError("viscoelastic elements need maxwell_before and dt")
            maxwell = np.array(maxwell_before, dtype=np.float64)
            set_viscoelastic_step(strain_before, maxwell, float(dt), self.props)
        phi, dphi = self._no_sag if self.sag is None else self.sag.share(x)
        _kernel(x, np.ascontiguousarray(v, dtype=np.float64),
                np.ascontiguousarray(a, dtype=np.float64),
                self._fluid(fluid_velocity_mid), self._fluid(fluid_acceleration_mid),
                self.elements, self.props, self.laws, self.sag is not None, phi, dphi,
                tangent, self.with_drag, self.with_added_mass, *out)
        maxwell_out = None
        if self.viscoelastic:
            maxwell_forces(out[4], self.props, maxwell)
            maxwell_out = maxwell
        K, C, Ma, Ka = out[6], out[7], out[8], out[11]
        if not tangent:
            K = C = Ma = Ka = None
        elif not self.with_added_mass:
            Ma = Ka = None
        return ElementLoads(*out[:6], K, C, Ma, out[9], out[10], maxwell_out, Ka)


def element_loads(
    x: FloatArray, v: FloatArray, a: FloatArray, fluid_velocity_mid: ArrayLike,
    fluid_acceleration_mid: ArrayLike, elements: IntArray, length0: ArrayLike, EA: ArrayLike,
    slack_ratio: ArrayLike, smoothing: ArrayLike, BA: ArrayLike, diameter: ArrayLike,
    Cd: ArrayLike, Ct: ArrayLike, Ca: ArrayLike, Cat: ArrayLike, rho: ArrayLike,
    tangent: bool, with_added_mass: bool, with_drag: bool = True,
    laws: StrainLaws | None = None,
    offset: ArrayLike | None = None, sag: SagCorrection | None = None,
    weight_per_length: ArrayLike | None = None,
) -> ElementLoads:
    """All loads of elastic elements and their derivatives in one compiled pass.

    Convenience form of :class:`FusedLoads` (which packs the properties once and is the one to
    use in a time loop).

    Parameters
    ----------
    x, v, a
        Node positions, velocities and accelerations, shape (n_nodes, 3).
    fluid_velocity_mid, fluid_acceleration_mid
        Fluid velocity and acceleration at each element midpoint, (n_el, 3) or (3,).
    elements
        Node indices of each element, shape (n_el, 2); every element is treated as elastic.
    length0, EA, slack_ratio, smoothing, BA
        Unstretched length, axial stiffness, slack stiffness ratio, slack band and
        Kelvin-Voigt damping [force*time]; scalars or (n_el,).
    diameter, Cd, Ct, Ca, Cat, rho
        Hydrodynamic diameter, drag and added-mass coefficients and fluid density.
    tangent
        Also compute the blocks ``K``, ``C`` (and ``Ma``).
    with_added_mass
        Compute added mass and fluid inertia (set when ``Ca`` or ``Cat`` is nonzero).
    with_drag
        Compute the Morison drag.
    laws, offset
        Tabulated tension-strain laws and strain offsets (see :class:`FusedLoads`).
    sag, weight_per_length
        The sag correction and the submerged weight per length (see :class:`FusedLoads`).

    Returns
    -------
    ElementLoads
        See :class:`ElementLoads`; ``nodal`` is ``total_forces`` summed to the nodes, with
        ``n_nodes = len(x)``.
    """
    x = np.asarray(x, dtype=np.float64)
    loads = FusedLoads(elements, x.shape[0], length0, EA, slack_ratio, smoothing, BA,
                       diameter, Cd, Ct, Ca, Cat, rho, laws, offset, with_drag=with_drag,
                       with_added_mass=with_added_mass, sag=sag,
                       weight_per_length=weight_per_length)
    return loads(x, v, a, fluid_velocity_mid, fluid_acceleration_mid, tangent)
