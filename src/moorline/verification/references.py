"""Independent exact reference solutions for the verification suite.

Everything here is closed form or a scalar/2-D root solve on a closed form: nothing
imports moorline's own solvers, so these functions can judge them.

Contents
--------
pin_jointed_string_load, pin_jointed_string_deflection, pin_jointed_string_tension
    Large-deflection equilibrium of a pretensioned elastic string with a midspan
    point load (Tuah (1982) sec. 6.1, Example 1; also the statics of Example 4).
two_segment_catenary, TwoSegmentSolution
    Exact (inextensible or elastic) catenary of two segments with a concentrated
    vertical force at their junction (Tuah (1982) sec. 6.2, Example 2).
tuah_ex2_reference
    The Example 2 data fed to :func:`two_segment_catenary`.

Units are whatever the caller uses consistently; the Tuah data are in ft, slug, s, lbf, psf.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.optimize

__all__ = [
    "G_FT",
    "TwoSegmentSolution",
    "pin_jointed_string_deflection",
    "pin_jointed_string_load",
    "pin_jointed_string_tension",
    "tuah_ex2_reference",
    "two_segment_catenary",
]

#: Standard gravity in ft/s^2 (exact: 9.80665 m/s^2 / 0.3048 m/ft = 32.1740...).
G_FT: float = 9.80665 / 0.3048


# ---------------------------------------------------------------------------
# Example 1: pin-jointed (two-bar) string with a midspan point load
# ---------------------------------------------------------------------------


def _check_string_data(span: float, EA: float, pretension: float) -> None:
    if not span > 0.0:
        raise ValueError(f"span must be positive, got {span!r}")
    if not (EA > 0.0 and math.isfinite(EA)):
        raise ValueError(f"EA must be positive and finite, got {EA!r}")
    if not (pretension >= 0.0 and math.isfinite(pretension)):
        raise ValueError(
            "pretension must be >= 0 (a slack string has no unique equilibrium), "
            f"got {pretension!r}"
        )


def _one_minus_inv_sqrt(u: float) -> float:
    """Return ``1 - 1/sqrt(1 + u**2)`` without cancellation for small ``u``."""
    r = math.sqrt(1.0 + u * u)
    return u * u / (r * (1.0 + r))


def pin_jointed_string_tension(
    deflection: float, span: float, EA: float, pretension: float
) -> float:
    """Axial tension in either half of the string at a given midspan deflection.

    ``T = (T0 + EA) sqrt(1 + (d/a)**2) - EA`` with ``a = span/2``; see
    :func:`pin_jointed_string_load` for the derivation.

    Parameters
    ----------
    deflection : float
        Midspan deflection ``d`` (either sign; the tension is even in ``d``).
    span : float
        Distance between the two fixed ends (same height).
    EA : float
        Axial stiffness (force).
    pretension : float
        Tension ``T0`` of the straight string (``d = 0``), ``T0 >= 0``.

    Returns
    -------
    float
        Tension ``T`` (force).
    """
    _check_string_data(span, EA, pretension)
    u = deflection / (0.5 * span)
    r = math.sqrt(1.0 + u * u)
    return pretension * r + EA * u * u / (1.0 + r)


def pin_jointed_string_load(deflection: float, span: float, EA: float, pretension: float) -> float:
    """Midspan point load that holds a pretensioned elastic string at a given deflection.

    Exact large-deflection statics of Tuah (1982) sec. 6.1 (Example 1, after Webster 1974).

    Notes
    -----
    A weightless, linearly elastic string (``T = EA * strain``, strain on the unstretched
    length) is fixed at two points at the same height, ``span`` apart, and carries the
    tension ``T0`` when straight. Its unstretched length is therefore
    ``L0 = span / (1 + T0/EA)``. Under a point load ``P`` at midspan the two halves stay
    straight (no weight); by symmetry each has unstretched length ``L0/2`` and, with
    ``a = span/2`` and midspan deflection ``d``, stretched length ``l = sqrt(a**2 + d**2)``::

        T = EA * (l / (L0/2) - 1) = (EA + T0) * l/a - EA
          = T0 sqrt(1 + u**2) + EA (sqrt(1 + u**2) - 1),        u = d/a.

    Vertical equilibrium of the loaded node, ``P = 2 T sin(theta) = 2 T d / l`` with
    ``d/l = u / sqrt(1 + u**2)``, gives::

        P = 2 u [T0 + EA (1 - 1/sqrt(1 + u**2))].

    (:func:`pin_jointed_string_tension` returns ``T``; ``1 - 1/sqrt(1+u**2)`` is evaluated
    as ``u**2 / (r (1 + r))``, ``r = sqrt(1+u**2)``, to keep full precision at small ``u``.)

    Limits: for ``|u| << 1``, ``P ~ 2 T0 u + EA u**3`` (small-strain form). With
    ``T0 > 0`` and a small load it is the linear taut string ``d = P a / (2 T0)``; with
    ``T0 = 0`` it is the cubic law ``d = a (P/EA)**(1/3)`` (note: ``EA``, not ``2 EA``:
    the strain ``u**2/2`` times the slope ``u`` times the two halves gives ``EA u**3``).

    Source data (Tuah 1982, sec. 6.1): ``E = 1.0e7`` psf, ``A0 = 0.1`` ft^2, initial stress
    ``sigma0 = 500`` psf, hence ``EA = 1.0e6`` lbf and ``T0 = 50`` lbf. The span is not
    printed; Example 4 uses a 20 ft string of the same material, so 20 ft is assumed.

    Parameters
    ----------
    deflection : float
        Midspan deflection ``d`` (same sign as the load).
    span : float
        Distance between the fixed ends.
    EA : float
        Axial stiffness (force), positive and finite.
    pretension : float
        Tension ``T0`` of the straight string, ``T0 >= 0`` (``T0 = sigma0 * A0``).

    Returns
    -------
    float
        Point load ``P`` (force), odd in ``d``.
    """
    _check_string_data(span, EA, pretension)
    u = deflection / (0.5 * span)
    return 2.0 * u * (pretension + EA * _one_minus_inv_sqrt(u))


def pin_jointed_string_deflection(load: float, span: float, EA: float, pretension: float) -> float:
    """Midspan deflection of a pretensioned elastic string under a midspan point load.

    Inverse of :func:`pin_jointed_string_load` (whose docstring has the derivation,
    Tuah (1982) sec. 6.1): solves ``P = 2 u [T0 + EA (1 - 1/sqrt(1+u**2))]`` for
    ``u = d/(span/2)`` with :func:`scipy.optimize.brentq` to machine precision
    (``rtol = 4 eps``; in practice a relative error of about 1e-15).

    The load is strictly increasing in ``d`` (for ``T0 >= 0``), so the root is unique; the
    bracket ``[0, u_hi]`` starts from the smaller of the linear (``P/(2 T0)``, an upper
    bound since ``P >= 2 T0 u``) and cubic (``(P/EA)**(1/3)``) estimates and doubles
    ``u_hi`` until the load there exceeds ``P``.

    Slack case: with ``T0 = 0`` and ``P = 0`` the string is exactly taut and straight and
    the answer is ``d = 0``, unique but with zero tangent stiffness (``dP/dd = 0``): a
    stiffness-based solver starting there is singular, which is why Tuah starts Example 1
    with damping. Near it ``d`` grows like ``P**(1/3)``. Negative pretension (a slack
    string, a continuum of equilibria at ``P = 0``) is rejected.

    Parameters
    ----------
    load : float
        Point load ``P`` at midspan (force); the result has its sign.
    span : float
        Distance between the fixed ends.
    EA : float
        Axial stiffness (force), positive and finite.
    pretension : float
        Tension ``T0`` of the straight string, ``T0 >= 0``.

    Returns
    -------
    float
        Midspan deflection ``d``.
    """
    _check_string_data(span, EA, pretension)
    if not math.isfinite(load):
        raise ValueError(f"load must be finite, got {load!r}")
    if load == 0.0:
        return 0.0
    a = 0.5 * span
    p = abs(load)

    def residual(u: float) -> float:
        return 2.0 * u * (pretension + EA * _one_minus_inv_sqrt(u)) - p

    # start from the smaller of the two asymptotic estimates and double until bracketed
    u_hi = (p / EA) ** (1.0 / 3.0)
    if pretension > 0.0:
        u_hi = min(u_hi, p / (2.0 * pretension))
    u_hi = max(u_hi, 1e-300)
    while residual(u_hi) < 0.0:
        u_hi *= 2.0
    u = scipy.optimize.brentq(
        residual, 0.0, u_hi, xtol=1e-300, rtol=4.0 * np.finfo(float).eps, maxiter=500
    )
    return math.copysign(u * a, load)


# ---------------------------------------------------------------------------
# Example 2: two-segment catenary with a concentrated force at the junction
# ---------------------------------------------------------------------------


def _seg_xz(H: float, V1: float, length: float, w: float, EA: float) -> tuple[float, float]:
    """Span and rise of one elastic-catenary segment whose vertical tension starts at V1."""
    V2 = V1 + w * length
    T1 = math.hypot(H, V1)
    T2 = math.hypot(H, V2)
    x = H * length / EA + (H / w) * (math.asinh(V2 / H) - math.asinh(V1 / H))
    # (T2 - T1)/w written without cancellation: (V2^2 - V1^2)/(w (T1 + T2)) = l (V1+V2)/(T1+T2)
    z = length * (V1 + V2) / (2.0 * EA) + length * (V1 + V2) / (T1 + T2)
    return x, z


def _seg_jac(H: float, V1: float, length: float, w: float, EA: float) -> np.ndarray:
    """d(x, z)/d(H, V1) of one segment (V2 = V1 + w*length moves with V1)."""
    V2 = V1 + w * length
    T1 = math.hypot(H, V1)
    T2 = math.hypot(H, V2)
    dx_dH = length / EA + (math.asinh(V2 / H) - math.asinh(V1 / H)) / w - (V2 / T2 - V1 / T1) / w
    dx_dV = (H / w) * (1.0 / T2 - 1.0 / T1)
    dz_dH = (H / w) * (1.0 / T2 - 1.0 / T1)
    dz_dV = length / EA + (V2 / T2 - V1 / T1) / w
    return np.array([[dx_dH, dx_dV], [dz_dH, dz_dV]])


@dataclass(frozen=True)
class TwoSegmentSolution:
    """Equilibrium of a two-segment cable with a vertical point force at the junction.

    Produced by :func:`two_segment_catenary` (Tuah (1982) sec. 6.2); see it for the sign
    conventions. ``s`` below is unstretched arc length measured from A.

    Attributes
    ----------
    point_a, point_b : tuple of float
        End points ``(x, z)``; ``z`` is up.
    lengths : tuple of float
        Unstretched lengths ``(L1, L2)``; segment 1 starts at A.
    weight : float
        Submerged weight per unstretched length ``w`` (> 0, acts downward).
    junction_force : float
        Concentrated vertical force ``P`` at the junction, positive upward (a buoy).
    EA : float
        Axial stiffness; ``math.inf`` for an inextensible cable.
    H : float
        Horizontal tension component (constant along the cable).
    V_a : float
        Vertical tension component at A, positive when the cable leaves A upward.
    V_b : float
        Vertical tension component at B, positive when the cable arrives at B going up;
        ``V_b = V_a + w (L1 + L2) - P``.
    junction : tuple of float
        Position ``(x, z)`` of the junction.
    """

    point_a: tuple[float, float]
    point_b: tuple[float, float]
    lengths: tuple[float, float]
    weight: float
    junction_force: float
    EA: float
    H: float
    V_a: float
    V_b: float
    junction: tuple[float, float]

    @property
    def total_length(self) -> float:
        """Unstretched length ``L1 + L2``."""
        return self.lengths[0] + self.lengths[1]

    @property
    def tension_a(self) -> float:
        """Tension magnitude at A, ``sqrt(H**2 + V_a**2)``."""
        return math.hypot(self.H, self.V_a)

    @property
    def tension_b(self) -> float:
        """Tension magnitude at B, ``sqrt(H**2 + V_b**2)``."""
        return math.hypot(self.H, self.V_b)

    def vertical_tension(self, s: np.ndarray | float) -> np.ndarray:
        """Vertical tension component ``V(s)``; at ``s = L1`` the value just below the junction."""
        s = np.asarray(s, dtype=float)
        L1 = self.lengths[0]
        return self.V_a + self.weight * s - np.where(s > L1, self.junction_force, 0.0)

    def tension(self, s: np.ndarray | float) -> np.ndarray:
        """Tension magnitude ``sqrt(H**2 + V(s)**2)`` (jumps at the junction if ``P != 0``)."""
        return np.hypot(self.H, self.vertical_tension(s))

    def position(self, s: np.ndarray | float) -> tuple[np.ndarray, np.ndarray]:
        """Exact position ``(x(s), z(s))`` at unstretched arc length ``s`` from A."""
        s = np.asarray(s, dtype=float)
        if np.any(s < 0.0) or np.any(s > self.total_length * (1 + 1e-14)):
            raise ValueError("s outside [0, L1 + L2]")
        H, w, EA, P = self.H, self.weight, self.EA, self.junction_force
        L1 = self.lengths[0]
        seg2 = s > L1
        s0 = np.where(seg2, L1, 0.0)
        V0 = self.V_a + w * s0 - np.where(seg2, P, 0.0)
        x0 = np.where(seg2, self.junction[0], self.point_a[0])
        z0 = np.where(seg2, self.junction[1], self.point_a[1])
        ds = s - s0
        V = V0 + w * ds
        T0 = np.hypot(H, V0)
        T = np.hypot(H, V)
        x = x0 + H * ds / EA + (H / w) * (np.arcsinh(V / H) - np.arcsinh(V0 / H))
        z = z0 + ds * (V0 + V) / (2.0 * EA) + ds * (V0 + V) / (T0 + T)
        return x, z

    def profile(self, n_points: int = 201) -> tuple[np.ndarray, np.ndarray]:
        """Points ``(x, z)`` along the cable from A to B, always including the junction.

        Parameters
        ----------
        n_points : int
            Total number of points (>= 3); they are shared between the segments in
            proportion to their lengths, each segment getting at least two.

        Returns
        -------
        x, z : ndarray
            Coordinates, shape ``(n_points,)``; the junction is at index ``n1 - 1``
            with ``n1 = max(2, min(n_points - 1, round(n_points * L1 / (L1 + L2))))``.
        """
        if n_points < 3:
            raise ValueError("n_points must be at least 3")
        L1, L2 = self.lengths
        n1 = max(2, min(n_points - 1, round(n_points * L1 / (L1 + L2))))
        n2 = n_points - n1 + 1
        s = np.concatenate([np.linspace(0.0, L1, n1), L1 + np.linspace(0.0, L2, n2)[1:]])
        return self.position(s)


def _two_seg_residual(
    H: float, V_a: float, L1: float, L2: float, w: float, P: float, EA: float
) -> tuple[np.ndarray, np.ndarray]:
    x1, z1 = _seg_xz(H, V_a, L1, w, EA)
    V2 = V_a + w * L1 - P
    x2, z2 = _seg_xz(H, V2, L2, w, EA)
    J = _seg_jac(H, V_a, L1, w, EA) + _seg_jac(H, V2, L2, w, EA)
    return np.array([x1 + x2, z1 + z2]), J


def _solve_va_for_h(
    H: float, zb: float, L1: float, L2: float, w: float, P: float, EA: float
) -> float:
    """Vertical tension at A that puts B at the right height for a given H.

    ``z(B)`` is strictly increasing in ``V_a`` (each segment's rise has derivative
    ``l/EA + (V2/T2 - V1/T1)/w > 0``), so the root is unique and bracketed by expansion.
    """

    def f(Va: float) -> float:
        return _two_seg_residual(H, Va, L1, L2, w, P, EA)[0][1] - zb

    scale = w * (L1 + L2) + abs(P) + H
    lo, hi = -scale, scale
    while f(lo) > 0.0:
        lo *= 2.0
    while f(hi) < 0.0:
        hi *= 2.0
    return scipy.optimize.brentq(
        f, lo, hi, xtol=1e-14 * scale, rtol=4.0 * np.finfo(float).eps, maxiter=500
    )


def _newton(
    H: float,
    Va: float,
    xb: float,
    zb: float,
    L1: float,
    L2: float,
    w: float,
    P: float,
    EA: float,
    ref: float,
    max_iter: int = 100,
) -> tuple[float, float, bool]:
    """Damped Newton on (ln H, V_a); returns (H, V_a, converged)."""
    target = np.array([xb, zb])
    r, J = _two_seg_residual(H, Va, L1, L2, w, P, EA)
    r = r - target
    norm = float(np.linalg.norm(r))
    for _ in range(max_iter):
        if norm <= 1e-13 * ref:
            return H, Va, True
        # unknowns y = (ln H, V_a): dr/dlnH = H dr/dH
        Jy = J * np.array([H, 1.0])
        try:
            step = -np.linalg.solve(Jy, r)
        except np.linalg.LinAlgError:
            return H, Va, False
        if not np.all(np.isfinite(step)):
            return H, Va, False
        step[0] = float(np.clip(step[0], -2.0, 2.0))
        lam = 1.0
        while lam > 1e-6:
            Hn = H * math.exp(lam * step[0])
            Van = Va + lam * step[1]
            rn, Jn = _two_seg_residual(Hn, Van, L1, L2, w, P, EA)
            rn = rn - target
            nn = float(np.linalg.norm(rn))
            if np.isfinite(nn) and nn < norm:
                break
            lam *= 0.5
        else:
            # no decrease: accept only if already at round-off level
            return H, Va, norm <= 1e-11 * ref
        H, Va, r, J, norm = Hn, Van, rn, Jn, nn
    return H, Va, norm <= 1e-13 * ref


def two_segment_catenary(
    point_a: tuple[float, float],
    point_b: tuple[float, float],
    lengths: tuple[float, float],
    weight: float,
    junction_force: float,
    EA: float = math.inf,
) -> TwoSegmentSolution:
    """Exact static shape of a two-segment cable with a vertical point force at the junction.

    Reference for Tuah (1982) sec. 6.2 (Example 2), where the thesis compares its finite
    elements with "the catenary equation in which the cable is assumed inextensible".

    Notes
    -----
    Model and sign conventions.
    The cable lies in the vertical ``(x, z)`` plane, ``z`` up, from ``A`` to ``B`` with
    ``x_B > x_A``. ``s`` is unstretched arc length from A; segment 1 is ``0 <= s <= L1``,
    segment 2 is ``L1 < s <= L1 + L2``; both have submerged weight ``w`` per unstretched
    length (downward) and axial stiffness ``EA``. A concentrated force ``P`` (positive
    **up**, e.g. a buoy) acts at the junction ``s = L1``. No seabed, no current.

    Let ``(H, V(s))`` be the force that the part of the cable beyond ``s`` exerts on the part
    ``[0, s]`` (the tension ``T(s)`` times the unit tangent pointing towards B). The support
    at A pulls on the cable with ``-(H, V_a)``, ``V_a = V(0+)``. Free body ``[0, s]``:

    * horizontal: ``H(s) - H = 0``, so ``H`` is constant;
    * vertical: ``V(s) - V_a - w s + P [s > L1] = 0``, so::

          V(s) = V_a + w s                 (segment 1)
          V(s) = V_a + w s - P             (segment 2: an upward P reduces V above it)

    and ``V_b = V_a + w (L1 + L2) - P``, i.e. ``V_b - V_a = w (L1 + L2) - P``.
    ``V_a > 0`` means the cable leaves A upward; ``V_b > 0`` means it arrives at B going
    up. The cable pulls the supports with ``(H, V_a)`` at A and ``(-H, -V_b)`` at B.

    Geometry with ``T = sqrt(H**2 + V**2)``, strain ``T/EA``::

        dx/ds = (1 + T/EA) H/T,     dz/ds = (1 + T/EA) V/T,   dV/ds = w,

    which integrate over a segment with ``V: V1 -> V2 = V1 + w l`` to the elastic
    catenary (Irvine 1981)::

        x = H l/EA + (H/w) [asinh(V2/H) - asinh(V1/H)]
        z = l (V1 + V2)/(2 EA) + (T2 - T1)/w.

    The two unknowns ``(H, V_a)`` solve ``x1 + x2 = x_B - x_A`` and
    ``z1 + z2 = z_B - z_A`` (segment 2 starting from ``V1 = V_a + w L1 - P``). The sign of
    ``V`` may change inside a segment (a sag, or a hog) and ``P`` may exceed the whole
    weight: the formulas hold for any real ``V``, only ``H > 0`` is required. The tension
    jumps at the junction if ``P != 0``: the cable has a kink there.

    Solution method: a start ``H0`` from the single-catenary estimate of Peyrot and
    Goulois (1979) with the net weight ``|w L - P|`` spread along the cable, ``V_a`` from a
    bracketed 1-D solve of the height equation (``z_B`` is strictly increasing in ``V_a``),
    then Newton with an analytic Jacobian and backtracking on ``(ln H, V_a)``. If Newton
    fails, a nested bracketed solve (:func:`scipy.optimize.brentq` on ``H``, with ``V_a(H)``
    from the height equation; the span goes from 0 at ``H -> 0`` to above ``x_B`` as
    ``H -> inf``) followed by a Newton polish. Converged to a residual below ``1e-13``
    times the chord.

    Parameters
    ----------
    point_a, point_b : tuple of float
        End points ``(x, z)``; requires ``x_B > x_A``.
    lengths : tuple of float
        Unstretched lengths ``(L1, L2)``, both positive; ``L1`` is attached to A.
    weight : float
        Submerged weight per unstretched length ``w > 0``.
    junction_force : float
        Vertical point force ``P`` at the junction, positive upward.
    EA : float, optional
        Axial stiffness, ``math.inf`` (default) for an inextensible cable.

    Returns
    -------
    TwoSegmentSolution

    Raises
    ------
    ValueError
        For invalid data, or, when inextensible, if the chord is not shorter than
        ``L1 + L2`` (no catenary solution).
    RuntimeError
        If no solver converged (not observed).
    """
    xa, za = (float(c) for c in point_a)
    xb_abs, zb_abs = (float(c) for c in point_b)
    L1, L2 = (float(v) for v in lengths)
    w = float(weight)
    P = float(junction_force)
    EA = float(EA)
    xb, zb = xb_abs - xa, zb_abs - za
    if not xb > 0.0:
        raise ValueError("point_b must lie to the right of point_a (x_B > x_A)")
    if not (L1 > 0.0 and L2 > 0.0):
        raise ValueError("segment lengths must be positive")
    if not (w > 0.0 and math.isfinite(w)):
        raise ValueError("weight must be positive and finite")
    if not math.isfinite(P):
        raise ValueError("junction_force must be finite")
    if not EA > 0.0:
        raise ValueError("EA must be positive (math.inf for inextensible)")
    L = L1 + L2
    chord = math.hypot(xb, zb)
    if math.isinf(EA) and chord >= L:
        raise ValueError(
            f"inextensible cable of length {L} cannot span a chord of {chord}: no catenary solution"
        )

    # --- starting point (Peyrot & Goulois 1979 single-catenary estimate, net weight) ---
    w_net = max(abs(w * L - P), 1e-3 * w * L) / L
    if L * L > chord * chord * (1.0 + 1e-9):
        lam = math.sqrt(3.0 * ((L * L - zb * zb) / (xb * xb) - 1.0))
    else:
        lam = 0.2
    lam = max(lam, 1e-3)
    H0 = w_net * xb / (2.0 * lam)
    Va0 = _solve_va_for_h(H0, zb, L1, L2, w, P, EA)

    H, Va, ok = _newton(H0, Va0, xb, zb, L1, L2, w, P, EA, ref=chord)
    if not ok:
        # --- fallback: nested bracketed solve, then Newton polish ---
        def span_error(h: float) -> float:
            va = _solve_va_for_h(h, zb, L1, L2, w, P, EA)
            return _two_seg_residual(h, va, L1, L2, w, P, EA)[0][0] - xb

        h_lo = 1e-6 * w * L
        while span_error(h_lo) > 0.0:
            h_lo *= 1e-3
        h_hi = max(H0, w * L)
        while span_error(h_hi) < 0.0:
            h_hi *= 2.0
        H = scipy.optimize.brentq(
            span_error, h_lo, h_hi, xtol=1e-300, rtol=4.0 * np.finfo(float).eps, maxiter=500
        )
        Va = _solve_va_for_h(H, zb, L1, L2, w, P, EA)
        H, Va, ok = _newton(H, Va, xb, zb, L1, L2, w, P, EA, ref=chord)
        if not ok:
            r = _two_seg_residual(H, Va, L1, L2, w, P, EA)[0] - np.array([xb, zb])
            if float(np.linalg.norm(r)) > 1e-10 * chord:
                raise RuntimeError("two_segment_catenary did not converge")

    H, Va = float(H), float(Va)
    xj, zj = _seg_xz(H, Va, L1, w, EA)
    return TwoSegmentSolution(
        point_a=(xa, za),
        point_b=(xb_abs, zb_abs),
        lengths=(L1, L2),
        weight=w,
        junction_force=P,
        EA=EA,
        H=H,
        V_a=Va,
        V_b=Va + w * L - P,
        junction=(xa + xj, za + zj),
    )


def tuah_ex2_reference(EA: float = math.inf) -> TwoSegmentSolution:
    """Exact two-segment catenary for Tuah (1982) sec. 6.2, Example 2.

    Data as printed (ft, slug, s, lbf, psf): A = (0, 0), B = (1200, 500) ft; segments of
    500 ft (attached to A, assumed: the figure that would show the order is lost) and
    1000 ft; buoyant load 900 lbf at the junction (``P = +900``, upward);
    ``A0 = 0.0218`` ft^2, cable density 3.35 slug/ft^3, fluid density 2.0 slug/ft^3, so
    ``w = (3.35 - 2.0) * 0.0218 * g = 0.94692`` lbf/ft (``g = 32.174`` ft/s^2), total
    submerged weight 1420.4 lbf. The thesis's reference is inextensible (the default);
    the elastic variant uses ``EA = E A0 = 8.12e6 * 0.0218 = 177016`` lbf. The printed
    initial stress 0.5 psf (strain 6e-8, 9e-5 ft over the cable) is ignored: the lengths
    are taken as unstretched.

    Values computed by this module (``w = 0.946882`` lbf/ft):

    ============  =========  ========  ========  ==================  =================
    variant       H (lbf)    V_a       V_b       junction (ft)       low point (ft)
    ============  =========  ========  ========  ==================  =================
    inextensible  363.6406   72.6578   592.9812  (382.978, 301.268)  (714.14, 149.42)
    EA = 177016   359.3659   70.7856   591.1090  (383.200, 302.807)  (715.78, 147.90)
    ============  =========  ========  ========  ==================  =================

    The buoy makes the junction a kink at a local top: ``V`` is +546 lbf just below it and
    -354 lbf just above, so segment 2 runs down to a sag at ``s = 873.8`` ft and rises to B.
    Elasticity moves the junction by 1.55 ft (0.22 ft right, 1.54 ft up).

    Parameters
    ----------
    EA : float, optional
        ``math.inf`` (default) for the inextensible reference; pass
        ``8.12e6 * 0.0218`` for the elastic cable of the thesis.

    Returns
    -------
    TwoSegmentSolution
    """
    w = (3.35 - 2.0) * 0.0218 * G_FT
    return two_segment_catenary((0.0, 0.0), (1200.0, 500.0), (500.0, 1000.0), w, 900.0, EA=EA)
