"""Closed-form elastic catenary of a single uniform line.

End A sits at the origin, end B at horizontal distance ``X >= 0`` and height ``Z`` (z up).
The line has unstretched length ``L``, axial stiffness ``EA`` and submerged weight ``w`` per
unstretched length. On the freely hanging part the tension components at unstretched arc
length ``s`` are ``H`` (constant) and ``V(s) = V_a + w s`` (Tcheou 1997 eq. 3.25 with
``V_a = V - w L``), and the elastic catenary (Tcheou 1997 eq. 3.27) is::

    x(s) = (H/w) [asinh(V(s)/H) - asinh(V_a/H)] + H s / EA
    z(s) = (H/w) [sqrt(1 + (V(s)/H)^2) - sqrt(1 + (V_a/H)^2)] + (V_a s + w s^2 / 2) / EA

(the OCR of eq. 3.24 in the seed drops parentheses inside the square roots; eq. 3.27 reads
correctly and is the form used). When a flat seabed lies at the height of end A, a length
``L_B`` rests on it and Coulomb friction ``mu w`` per unit length lowers the tension from
``H`` at touchdown to ``H_a = max(H - mu w L_B, 0)`` at A (Jonkman 2007, MAP manual).

The differences of ``asinh`` and square roots are evaluated in ``log1p`` / ratio forms that
keep full relative precision when ``V/H`` is large or ``w L / H`` is small (``w -> 0``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from moorline.errors import MoorlineError

__all__ = ["CatenaryError", "CatenarySolution", "catenary_3d", "hanging_from_forces",
           "profile_3d", "solve_catenary"]


class CatenaryError(MoorlineError):
    """Infeasible catenary geometry or non-convergence; the message gives the numbers."""


def _inv(EA: float) -> float:
    return 0.0 if math.isinf(EA) else 1.0 / EA


# ----------------------------------------------------------------------------- kernels
def _asinh_ratio(a: float, b: float) -> float:
    """``(asinh(b) - asinh(a)) / (b - a)``, ``1/sqrt(1 + a^2)`` when ``a == b``."""
    lo, hi = (a, b) if a <= b else (b, a)
    if hi <= 0.0:
        lo, hi = -hi, -lo
    if lo < 0.0:  # opposite signs: a sum of two positive numbers, no cancellation
        return (math.asinh(hi) + math.asinh(-lo)) / (hi - lo)
    s_lo = math.hypot(1.0, lo)
    q = (1.0 + (lo + hi) / (s_lo + math.hypot(1.0, hi))) / (lo + s_lo)
    x = (hi - lo) * q
    return q if x == 0.0 else q * math.log1p(x) / x


def _asinh_ratio_np(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Vectorized :func:`_asinh_ratio`."""
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    neg = hi <= 0.0
    lo, hi = np.where(neg, -hi, lo), np.where(neg, -lo, hi)
    mixed = lo < 0.0
    delta = hi - lo
    s_lo = np.hypot(1.0, lo)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        q = (1.0 + (lo + hi) / (s_lo + np.hypot(1.0, hi))) / (lo + s_lo)
        x = delta * q
        same = np.where(x == 0.0, q, q * np.log1p(np.abs(x)) / x)
        cross = (np.arcsinh(hi) + np.arcsinh(-lo)) / delta
    return np.where(mixed, cross, same)


def _ends(H, V, L, w, inv_ea, mu, contact):
    """End-B offset ``(X, Z)`` and Jacobian wrt ``(H, V_b)``, canonical frame (``w > 0``)."""
    va = V - w * L
    if contact and va < 0.0:
        return _ends_seabed(H, V, L, w, inv_ea, mu)
    a, b = va / H, V / H
    sa, sb = math.hypot(1.0, a), math.hypot(1.0, b)
    f = _asinh_ratio(a, b)
    g = (a + b) / (sa + sb)  # (sqrt(1+b^2) - sqrt(1+a^2)) / (b - a)
    if a < 0.0 < b:  # k = (b sa - a sb) / (b - a)
        k = (b * sa - a * sb) / (b - a)
    else:
        den = b * sa + a * sb
        k = (a + b) / den if den != 0.0 else 1.0 / sa
    c, ss = L / H, sa * sb
    x = L * f + H * L * inv_ea
    z = L * g + (va * L + 0.5 * w * L * L) * inv_ea
    dxdv = -c * g / ss
    return x, z, (c * (f - k / ss) + L * inv_ea, dxdv, dxdv, c * k / ss + L * inv_ea)


def _ends_seabed(H, V, L, w, inv_ea, mu):
    """As :func:`_ends` with the touchdown on the seabed (``0 <= V_b < w L``)."""
    ls = V / w
    lb = L - ls
    b = V / H
    sb = math.hypot(1.0, b)
    f0, g0, c = _asinh_ratio(0.0, b), b / (1.0 + sb), ls / H
    x = lb + ls * f0 + H * L * inv_ea
    z = ls * g0 + 0.5 * V * ls * inv_ea
    dxdh, dzdh = c * (f0 - 1.0 / sb) + L * inv_ea, -c * g0 / sb
    dxdv, dzdv = dzdh, c / sb + ls * inv_ea
    if mu > 0.0 and lb > 0.0:
        slip = H / (mu * w)  # lying length over which friction takes up H
        if lb > slip:  # H_a = 0: the anchor end of the lying part is slack
            x += (0.5 * H * slip - H * lb) * inv_ea
            dxdh += (slip - lb) * inv_ea
            dxdv += H / w * inv_ea
        else:
            x -= 0.5 * mu * w * lb * lb * inv_ea
            dxdv += mu * lb * inv_ea
    return x, z, (dxdh, dxdv, dzdh, dzdv)


def _suspended(H, va, w, inv_ea, s):
    """Offsets ``(h, z)`` after arc length ``s`` of hanging line starting with ``V = va``."""
    s = np.asarray(s, dtype=float)
    if H == 0.0:  # vertical: h = 0, z = int sign(V) ds
        h, vs = np.zeros_like(s), va + w * s
        with np.errstate(divide="ignore", invalid="ignore"):
            z = np.where(va * vs >= 0.0, np.sign(va + vs) * s, (np.abs(vs) - abs(va)) / w)
    else:
        a, b = va / H, (va + w * s) / H
        h = s * _asinh_ratio_np(np.full_like(s, a), b)
        z = s * (a + b) / (math.hypot(1.0, a) + np.hypot(1.0, b))
    return h + H * s * inv_ea, z + (va * s + 0.5 * w * s * s) * inv_ea


# ----------------------------------------------------------------------------- result
@dataclass(frozen=True)
class CatenarySolution:
    """Solved elastic catenary between end A (origin) and end B.

    Sign conventions: ``(H, V_b)`` is the tension of the line at B, i.e. the force that the
    outside applies to the line at B, with ``h`` along the horizontal direction A -> B and z
    up. ``(H_a, V_a)`` is the tension at A, i.e. the force with which the line pulls on A.
    On the suspended part ``V(s) = V_b - w (L - s)``; with no seabed contact this is
    ``V_a + w s``; with contact ``V_a = 0`` (the lying part is horizontal) and
    ``V(s) = w (s - seabed_length)``. The line is in equilibrium under ``force_a``,
    ``force_b`` reversed, its weight ``w L`` and the seabed reaction (normal ``w L_B`` and
    friction ``H - H_a``).
    """

    horizontal_span: float
    vertical_span: float
    length: float
    EA: float
    weight: float
    seabed_friction: float
    H: float
    V_b: float
    V_a: float
    H_a: float
    seabed_length: float
    iterations: int

    @property
    def force_a(self) -> tuple[float, float]:
        """Force ``(h, z)`` the line exerts on point A: ``(+H_a, +V_a)`` (towards B for H)."""
        return (self.H_a, self.V_a)

    @property
    def force_b(self) -> tuple[float, float]:
        """Force ``(h, z)`` the line exerts on point B: ``(-H, -V_b)``."""
        return (-self.H, -self.V_b)

    @property
    def tension_a(self) -> float:
        """Effective tension magnitude at A."""
        return math.hypot(self.H_a, self.V_a)

    @property
    def tension_b(self) -> float:
        """Effective tension magnitude at B."""
        return math.hypot(self.H, self.V_b)

    def _bed_h(self, s: np.ndarray) -> np.ndarray:
        """Horizontal position of the lying point at arc length ``0 <= s <= L_B``."""
        lb, H, mu, w = self.seabed_length, self.H, self.seabed_friction, self.weight
        if H == 0.0:  # slack: surplus length piles up; drawn uniformly compressed
            return s * (self.horizontal_span / lb)
        s0 = max(lb - H / (mu * w), 0.0) if mu > 0.0 else 0.0  # tension starts at s0
        t0 = H - mu * w * (lb - s0)
        t = np.maximum(s - s0, 0.0)
        return s + t * (t0 + 0.5 * mu * w * t) * _inv(self.EA)

    def profile(self, s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Position ``(h, z)`` relative to A at unstretched arc length ``s`` in ``[0, L]``.

        ``h`` is along the horizontal direction A -> B. A slack weightless line (zero
        tension) is drawn along the chord; surplus length of a slack line on the seabed
        (``H = 0``) is drawn uniformly compressed along the lying part.
        """
        s = np.asarray(s, dtype=float)
        L, lb = self.length, self.seabed_length
        if self.weight == 0.0 and self.H == 0.0 and self.V_a == 0.0:
            return s * (self.horizontal_span / L), s * (self.vertical_span / L)
        h_bed = self._bed_h(np.clip(s, 0.0, lb)) if lb > 0.0 else np.zeros_like(s)
        h, z = _suspended(self.H, self.V_a, self.weight, _inv(self.EA), np.maximum(s - lb, 0.0))
        return h_bed + h, z

    def tension(self, s: np.ndarray) -> np.ndarray:
        """Effective tension at unstretched arc length ``s`` in ``[0, L]``."""
        s = np.asarray(s, dtype=float)
        lb = self.seabed_length
        t = np.hypot(self.H, self.V_a + self.weight * np.maximum(s - lb, 0.0))
        if lb <= 0.0:
            return t
        mu_w = self.seabed_friction * self.weight
        return np.where(s < lb, np.maximum(self.H - mu_w * (lb - s), 0.0), t)


# ----------------------------------------------------------------------------- solver
def _check(X, Z, L, EA, w, mu, max_strain) -> None:
    bad = [
        (not all(map(math.isfinite, (X, Z, L, w))), f"X, Z, L, w must be finite: {X, Z, L, w}"),
        (not L > 0.0, f"line length must be positive, got {L}"),
        (not EA > 0.0, f"axial stiffness EA must be positive, got {EA}"),
        (not X >= 0.0, f"horizontal span must be >= 0, got {X}"),
        (not mu >= 0.0, f"seabed friction coefficient must be >= 0, got {mu}"),
    ]
    for failed, msg in bad:
        if failed:
            raise CatenaryError(msg)
    d = math.hypot(X, Z)
    if math.isinf(EA) and d >= L:
        raise CatenaryError(
            f"inextensible line (EA = inf) of length {L:.6g} cannot span distance {d:.6g} "
            f"(X = {X:.6g}, Z = {Z:.6g}) between its ends: needs distance < length"
        )
    if d > L * (1.0 + max_strain):
        raise CatenaryError(
            f"line of length {L:.6g} would have to stretch to the end-to-end distance "
            f"{d:.6g} (X = {X:.6g}, Z = {Z:.6g}), strain {d / L - 1.0:.4g} > max_strain "
            f"{max_strain:.4g}"
        )


def _guess(X, Z, L, w, inv_ea):
    """Initial fairlead tension ``(H, V_b)``, ``X > 0``, ``w > 0``.

    Jonkman's (2007) ``lambda0`` estimate, ``H = w X / (2 lambda0)`` and
    ``V = w/2 (Z / tanh(lambda0) + L)``, where ``lambda0`` comes from the shallow-sag
    (parabolic) length of the chord, here with the elastic stretch added so that taut and
    stretched lines start close: ``L (1 + T/EA) = d + (w X / d)^2 d^3 / (24 T^2)`` with the
    chord tension ``T = H d / X``. For ``EA = inf`` this is exactly Jonkman's
    ``lambda0 = sqrt(3 ((L^2 - Z^2) / X^2 - 1))`` to first order in ``L - d``.
    """
    d = math.hypot(X, Z)
    a, b, c = L * inv_ea, d - L, (w * X) ** 2 * d / 24.0  # a T^3 - b T^2 - c = 0
    if not c > 0.0:
        return max(w * X / 1400.0, 1e-300), w * (Z + L) / 2.0
    if a == 0.0:
        t = math.sqrt(c / -b)
    else:  # Newton from an upper bound, monotone (convex beyond the root)
        t = max((2.0 * c / a) ** (1.0 / 3.0), 2.0 * b / a) if b > 0.0 else min(
            (c / a) ** (1.0 / 3.0), math.sqrt(c / -b) if b < 0.0 else math.inf)
        for _ in range(30):
            step = (a * t**3 - b * t * t - c) / (3.0 * a * t * t - 2.0 * b * t)
            t -= step
            if step <= 1e-3 * t:
                break
    lam = min(max(w * d / (2.0 * t), 1e-9), 700.0)
    return w * X / (2.0 * lam), 0.5 * w * (Z / math.tanh(lam) + L)


def _newton(X, Z, args, H, V, tol_abs, max_iter):
    """Damped Newton on (H, V_b); returns ``(H, V, iterations, converged)``."""
    contact = args[-1]
    x, z, jac = _ends(H, V, *args)
    rx, rz = x - X, z - Z
    norm = math.hypot(rx, rz)
    for it in range(max_iter + 1):
        done = max(abs(rx), abs(rz)) <= tol_abs
        a11, a12, a21, a22 = jac
        det = a11 * a22 - a12 * a21
        if not (math.isfinite(det) and det != 0.0) or (it == max_iter and not done):
            return H, V, it, done
        dh, dv = -(a22 * rx - a12 * rz) / det, -(a11 * rz - a21 * rx) / det
        if done:  # one more full step: quadratic convergence takes it to round-off
            hn, vn = H + dh, V + dv
            if hn > 0.0 and (vn >= 0.0 or not contact):
                xn, zn, _ = _ends(hn, vn, *args)
                if math.hypot(xn - X, zn - Z) <= norm:
                    return hn, vn, it + 1, True
            return H, V, it, True
        alpha = 1.0
        if dh < -0.9 * H:  # keep H > 0 (at most a tenfold drop per step)
            alpha = -0.9 * H / dh
        if contact and dv < -0.9 * V:
            alpha = min(alpha, -0.9 * V / dv)
        for _ in range(60):
            hn, vn = H + alpha * dh, V + alpha * dv
            xn, zn, jn = _ends(hn, vn, *args)
            nn = math.hypot(xn - X, zn - Z)
            if nn < (1.0 - 1e-4 * alpha) * norm:
                break
            alpha *= 0.5
        else:
            break
        H, V, jac, rx, rz, norm = hn, vn, jn, xn - X, zn - Z, nn
    return H, V, max_iter, False


def _bracketed(X, Z, args):
    """Robust fallback: nested bracketed roots, V_b(H) from Z, then H from X."""
    from scipy.optimize import brentq  # 0.2 s to import: only on this fallback

    L, w, contact = args[0], args[1], args[-1]
    v_floor = 0.0 if contact else 0.5 * w * L  # Z(H, v_floor) <= 0 <= Z

    def v_of_h(H):
        def fz(v):
            return _ends(H, v, *args)[1] - Z

        lo, step = v_floor, w * L + H
        while fz(lo + step) < 0.0:
            lo, step = lo + step, 2.0 * step
        return brentq(fz, lo, lo + step, xtol=1e-15 * (w * L + H), rtol=1e-15)

    def fx(t):
        H = math.exp(t)
        return _ends(H, v_of_h(H), *args)[0] - X

    t_lo = t_hi = math.log(w * L)
    while fx(t_lo) > 0.0 and t_lo > math.log(w * L) - 600.0:
        t_lo -= 5.0
    while fx(t_hi) < 0.0 and t_hi < math.log(w * L) + 600.0:
        t_hi += 5.0
    t = brentq(fx, t_lo, t_hi, xtol=1e-15, rtol=1e-15, maxiter=500)
    return math.exp(t), v_of_h(math.exp(t))


def _special(X, Z, L, w, inv_ea, mu, contact):
    """Closed forms: weightless or stretched far beyond sag, slack or flat on seabed, vertical.

    Returns ``(H, V_b)`` or ``None`` when the general solver is needed.
    """
    d = math.hypot(X, Z)
    t = (d / L - 1.0) / inv_ea if d > L else 0.0  # chord tension of a straight line
    if w == 0.0 or w * L < 1e-13 * t:  # weight negligible: straight; no tension when slack
        return (t * X / d, t * Z / d + 0.5 * w * L) if t > 0.0 else (0.0, 0.0)
    if contact:
        ls = 2.0 * Z / (1.0 + math.sqrt(1.0 + 2.0 * w * Z * inv_ea))  # vertical hanging length
        if ls <= L and X <= L - ls:
            return 0.0, w * ls
        if Z == 0.0:  # X > L: the whole line lies stretched; int T ds = (X - L) EA
            e = (X - L) / inv_ea
            if e >= 0.5 * mu * w * L * L:
                return (e + 0.5 * mu * w * L * L) / L, 0.0
            return math.sqrt(2.0 * mu * w * e), 0.0
    if X <= 1e-13 * L:  # folded (V crosses 0) or taut vertical line; H ~ w X is negligible
        stretch = 1.0 + 0.5 * w * L * inv_ea
        if Z <= L * stretch:
            return 0.0, w * L - 0.5 * w * (L - Z / stretch)
        return 0.0, (Z - L) / (L * inv_ea) + 0.5 * w * L
    return None


def _solve_canonical(X, Z, L, EA, w, mu, contact, tol, max_iter):
    """Solve with ``w >= 0``, ``Z >= 0``: returns ``(H, V_b, iterations)``.

    The iteration runs on the problem scaled to ``L = 1`` and ``w L = 1``.
    """
    inv_ea = _inv(EA)
    special = _special(X, Z, L, w, inv_ea, mu, contact)
    if special is not None:
        return (*special, 0)
    xs, zs, ie = X / L, Z / L, inv_ea * w * L
    if ie == 0.0 and inv_ea > 0.0 and math.hypot(xs, zs) >= 1.0:  # weight below round-off
        return (*_special(X, Z, L, 0.0, inv_ea, mu, False), 0)
    args, tol_abs = (1.0, 1.0, ie, mu, contact), tol * max(1.0, math.hypot(xs, zs))
    what = f"catenary did not converge for X = {X:.6g}, Z = {Z:.6g}, L = {L:.6g}, " \
        f"EA = {EA:.6g}, w = {w:.6g}"
    try:
        H, V, it, ok = _newton(xs, zs, args, *_guess(xs, zs, 1.0, 1.0, ie), tol_abs, max_iter)
        if not ok:
            H, V = _bracketed(xs, zs, args)
            H2, V2, it2, ok = _newton(xs, zs, args, H, V, tol_abs, 10)  # polish
            H, V, it = (H2, V2, it + it2) if ok else (H, V, it)
    except (ValueError, ZeroDivisionError, OverflowError) as exc:
        raise CatenaryError(f"{what}: {exc}") from exc
    x, z, _ = _ends(H, V, *args)
    res = max(abs(x - xs), abs(z - zs))
    if not ok and res > 1e3 * tol_abs:
        raise CatenaryError(f"{what}: end-position residual {res * L:.3e} > tolerance "
                            f"{tol_abs * L:.3e}")
    return H * w * L, V * w * L, it


def solve_catenary(
    horizontal_span: float, vertical_span: float, length: float, EA: float, weight: float, *,
    seabed_friction: float = 0.0, seabed_contact: bool = True, max_strain: float = 0.5,
    tol: float = 1e-10, max_iter: int = 100,
) -> CatenarySolution:
    """Solve the elastic catenary between ends A and B (Jonkman 2007; Tcheou 1997 eq. 3.27).

    Parameters
    ----------
    horizontal_span, vertical_span
        ``X >= 0`` and ``Z = z_B - z_A`` of end B relative to end A.
    length, EA, weight
        Unstretched length ``L > 0``, axial stiffness (``math.inf``: inextensible) and
        submerged weight per unstretched length (``<= 0``: buoyant or weightless).
    seabed_friction
        Coulomb friction coefficient ``mu`` of the lying part.
    seabed_contact
        A flat seabed lies at ``z_A``; it matters only when ``w > 0`` and ``Z >= 0``.
    max_strain
        Largest admissible axial strain ``T / EA``.
    tol
        End-position tolerance relative to ``max(L, |AB|)``.
    max_iter
        Newton iterations before the bracketed fallback.

    Returns
    -------
    CatenarySolution

    Raises
    ------
    CatenaryError
        Invalid input, infeasible geometry (over-stretched, or ``EA = inf`` and
        ``|AB| >= L``) or non-convergence.

    Notes
    -----
    Damped Newton on ``(H, V_b)`` with the analytic Jacobian from Jonkman's initial guess;
    nested Brent root finding as the fallback. Closed forms (``iterations == 0``): a slack
    line on the seabed (``H = 0``, surplus length piled up under the span), a line flat on
    the seabed (``Z = 0``), a vertical line (``X <= 1e-13 L`` is taken as ``X = 0``: ``H = 0``
    and ``V`` may change sign, a fold) and a straight line when the weight is zero or
    negligible (``w L < 1e-13 EA (|AB| / L - 1)``); a slack weightless line has no tension.
    B below A (after mirroring a buoyant line) is solved from B, without seabed contact.
    """
    X, Z, L, w = (float(v) for v in (horizontal_span, vertical_span, length, weight))
    EA, mu = float(EA), float(seabed_friction)
    _check(X, Z, L, EA, w, mu, max_strain)
    flip = w < 0.0  # buoyant line: mirror z so that it hangs down
    wc, zc = (-w, -Z) if flip else (w, Z)
    swap = zc < 0.0  # B below A: solve from B
    contact = bool(seabed_contact) and not flip and not swap and wc > 0.0
    H, vb, it = _solve_canonical(X, abs(zc), L, EA, wc, mu if contact else 0.0, contact,
                                 tol, max_iter)
    va, lb, ha = vb - wc * L, 0.0, H
    if contact and va < 0.0:
        lb, va = L - vb / wc, 0.0
        ha = max(H - mu * wc * lb, 0.0)
    if swap:
        H, vb, va, ha = ha, -va, -vb, H
    if flip:
        vb, va = -vb, -va
    sol = CatenarySolution(X, Z, L, EA, w, mu, H, vb, va, ha, lb, it)
    strain = max(sol.tension_a, sol.tension_b) * _inv(EA)
    if strain > max_strain:
        raise CatenaryError(
            f"line of length {L:.6g} between X = {X:.6g}, Z = {Z:.6g} needs tension "
            f"{max(sol.tension_a, sol.tension_b):.6g} = strain {strain:.4g} > max_strain "
            f"{max_strain:.4g} (EA = {EA:.6g})"
        )
    return sol


def hanging_from_forces(
    H: float, V: float, length: float, EA: float, weight: float
) -> tuple[float, float]:
    """End-B offset of a freely hanging line under the end force ``(H, V)`` at B.

    End A is pinned; this is the forward problem of Tcheou (1997) eqs. 3.24-3.27 evaluated
    at ``s = L`` (eq. 3.27, with ``EA = inf`` it reduces to eq. 3.24; tension by eq. 3.25,
    net weight ``w = (rho_s A_s - rho_f A_f) g`` by eq. 3.26).

    Returns
    -------
    (X, Z)
        Horizontal and vertical offset of B from A.
    """
    if not length > 0.0 or not EA > 0.0:
        raise CatenaryError(f"length and EA must be positive, got L = {length}, EA = {EA}")
    if not H >= 0.0:
        raise CatenaryError(f"horizontal force H must be >= 0, got {H}")
    h, z = _suspended(float(H), V - weight * length, float(weight), _inv(EA), length)
    return float(h), float(z)


def _unit_h(point_a, point_b) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    pa, pb = np.asarray(point_a, dtype=float), np.asarray(point_b, dtype=float)
    dxy = pb[:2] - pa[:2]
    X = math.hypot(dxy[0], dxy[1])
    return pa, pb, (dxy / X if X > 0.0 else np.array([1.0, 0.0]))


def catenary_3d(
    point_a, point_b, length: float, EA: float, weight: float, *,
    seabed_friction: float = 0.0, seabed_contact: bool = True, **kwargs,
) -> tuple[np.ndarray, np.ndarray, CatenarySolution]:
    """Catenary between 3-D points (z up); extra keywords go to :func:`solve_catenary`.

    Returns
    -------
    (force_on_a, force_on_b, solution)
        Forces (shape ``(3,)``) the line exerts on A and on B. A vertical line (``X = 0``)
        has ``H = 0``, so its forces are purely vertical.
    """
    pa, pb, e = _unit_h(point_a, point_b)
    d = pb - pa
    sol = solve_catenary(math.hypot(d[0], d[1]), d[2], length, EA, weight,
                         seabed_friction=seabed_friction, seabed_contact=seabed_contact,
                         **kwargs)
    (fah, faz), (fbh, fbz) = sol.force_a, sol.force_b
    return np.array([fah * e[0], fah * e[1], faz]), np.array([fbh * e[0], fbh * e[1], fbz]), sol


def profile_3d(solution: CatenarySolution, point_a, point_b, s) -> np.ndarray:
    """Positions, shape ``(len(s), 3)``, at unstretched arc lengths ``s`` from A."""
    pa, _, e = _unit_h(point_a, point_b)
    h, z = solution.profile(np.atleast_1d(np.asarray(s, dtype=float)))
    return pa + np.stack([h * e[0], h * e[1], z], axis=-1)
