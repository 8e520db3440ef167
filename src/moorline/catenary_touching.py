"""Closed-form elastic catenary of a line whose ends are both above a flat seabed and whose
sag reaches it: a U-shape (two hanging parts and a stretch lying between them).

On a frictionless seabed the horizontal tension ``H`` is the same in the two hanging parts and
the lying stretch. A hanging part of unstretched length ``s`` rising from its touchdown
(where ``V = 0``) to an end ``h`` above the seabed has (:mod:`moorline.catenary`'s elastic
catenary with ``V_a = 0``; Irvine 1981 eq. 1.22)::

    z(s) = (H/w) [sqrt(1 + (w s/H)^2) - 1] + w s^2 / (2 EA) = h
    x(s) = (H/w) asinh(w s/H) + H s / EA

and the lying stretch ``L - s_a - s_b`` is stretched by ``H / EA``. ``H`` solves
``x(s_a) + x(s_b) + (L - s_a - s_b)(1 + H/EA) = X``, the horizontal distance of the ends; the
left side grows with ``H`` from ``L - h_a - h_b`` (both parts hanging straight down) to its
value at lift-off, where ``s_a + s_b = L``. Below that range the surplus piles up (``H =
0``); above it the line clears the seabed (an ordinary catenary, :func:`moorline.catenary.
catenary_3d`). Friction is left out (the lying stretch's tension would vary along it).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .catenary import _suspended

__all__ = ["TouchingSolution", "solve_touching", "touching_3d", "touching_profile_3d"]

FloatArray = NDArray[np.float64]


def _rise(H: float, w: float, EA: float, s: ArrayLike) -> tuple[FloatArray, FloatArray]:
    """Height and horizontal span of ``s`` of hanging line from its touchdown (``V = 0``
    there: :mod:`moorline.catenary`'s suspended part)."""
    h, z = _suspended(max(H, 0.0), 0.0, w, 1.0 / EA, np.asarray(s, dtype=float))
    return z, h


def _hanging_length(h: float, H: float, w: float, EA: float) -> float:
    """Unstretched length hanging from a touchdown up to height ``h`` under ``H``.

    Newton on ``z(s) - h`` (the module docstring's ``z``), from the inextensible root
    ``sqrt(h^2 + 2 h H / w)``: ``z`` is increasing and convex in ``s``, and the elastic term
    puts ``z`` above ``h`` there, so the iterates decrease monotonically to the root (no
    bracketing search: this is called thousands of times by the free points' presolve)."""
    if h <= 0.0:
        return 0.0
    inv_ea = 1.0 / EA
    if H <= 0.0:  # hanging straight down: s + w s^2 / (2 EA) = h
        return 2.0 * h / (1.0 + math.sqrt(1.0 + 2.0 * w * h * inv_ea))
    s = math.sqrt(h * h + 2.0 * h * H / w)
    for _ in range(100):
        b = w * s / H
        r = math.hypot(1.0, b)
        step = (s * b / (1.0 + r) + 0.5 * w * s * s * inv_ea - h) / (b / r + w * s * inv_ea)
        s -= step
        if abs(step) <= 1e-15 * (s + h):
            break
    return s


@dataclass(frozen=True)
class TouchingSolution:
    """A line touching the seabed between its ends (see the module docstring).

    Attributes
    ----------
    horizontal_span, height_a, height_b
        ``X`` and the ends' heights above the seabed.
    length, EA, weight
        Unstretched length, axial stiffness, submerged weight per unstretched length.
    H
        Horizontal tension (0: the surplus piles up under ends hanging straight down).
    hanging_a, hanging_b
        Unstretched lengths hanging at ends A and B.
    """

    horizontal_span: float
    height_a: float
    height_b: float
    length: float
    EA: float
    weight: float
    H: float
    hanging_a: float
    hanging_b: float

    @property
    def lying_length(self) -> float:
        """Unstretched length on the seabed."""
        return self.length - self.hanging_a - self.hanging_b

    @property
    def force_a(self) -> tuple[float, float]:
        """Force ``(h, z)`` on end A, ``h`` along A -> B: ``(H, -w s_a)``."""
        return (self.H, -self.weight * self.hanging_a)

    @property
    def force_b(self) -> tuple[float, float]:
        """Force ``(h, z)`` on end B: ``(-H, -w s_b)``."""
        return (-self.H, -self.weight * self.hanging_b)

    def profile(self, s: ArrayLike) -> tuple[FloatArray, FloatArray]:
        """Position ``(h, z)`` relative to A at unstretched arc lengths ``s`` in ``[0, L]``
        (a pile, ``H = 0``, drawn uniformly compressed along the span)."""
        s = np.asarray(s, dtype=float)
        H, w, EA = self.H, self.weight, self.EA
        sa, sb, L, X = self.hanging_a, self.hanging_b, self.length, self.horizontal_span
        za, xa = _rise(H, w, EA, np.clip(sa - s, 0.0, sa))
        zb, xb = _rise(H, w, EA, np.clip(s - (L - sb), 0.0, sb))
        x_a = float(_rise(H, w, EA, sa)[1])
        x_b = float(_rise(H, w, EA, sb)[1])
        lying = max(self.lying_length, 0.0)
        along = np.clip(s - sa, 0.0, lying)
        bed = (x_a + along * (1.0 + H / EA) if H > 0.0 or lying == 0.0
               else along * (X / lying))
        h = np.where(s <= sa, x_a - xa, np.where(s >= L - sb, X - x_b + xb, bed))
        z = np.where(s <= sa, za, np.where(s >= L - sb, zb, 0.0)) - self.height_a
        return h, z


def solve_touching(horizontal_span: float, height_a: float, height_b: float, length: float,
                   EA: float, weight: float) -> TouchingSolution | None:
    """The U-shape of a line between ends ``height_a``, ``height_b`` above the seabed at
    horizontal distance ``horizontal_span``; ``None`` when it does not touch the seabed (its
    free catenary clears it, or the line is too short to reach it) or ``weight <= 0``."""
    X, ha, hb, L = (float(v) for v in (horizontal_span, height_a, height_b, length))
    EA, w = float(EA), float(weight)
    if w <= 0.0 or ha <= 0.0 or hb <= 0.0 or L <= ha + hb or not EA > 0.0:
        return None

    def hanging(H: float) -> tuple[float, float]:
        return _hanging_length(ha, H, w, EA), _hanging_length(hb, H, w, EA)

    def span(H: float) -> float:
        sa, sb = hanging(H)
        x = _rise(H, w, EA, np.array([sa, sb]))[1]
        return float(x.sum()) + (L - sa - sb) * (1.0 + H / EA) - X

    H_hi = w * L
    while sum(hanging(H_hi)) < L:
        H_hi *= 4.0
        if H_hi > 1e8 * w * L:
            return None
    scale = w * L
    from scipy.optimize import brentq

    H_top = float(brentq(lambda H: sum(hanging(H)) - L, 0.0, H_hi, xtol=1e-13 * scale))
    if span(H_top) < 0.0:
        return None
    H = 0.0 if span(0.0) >= 0.0 else float(brentq(span, 0.0, H_top, xtol=1e-13 * scale))
    sa, sb = hanging(H)
    return TouchingSolution(X, ha, hb, L, EA, w, H, sa, sb)


def touching_3d(point_a: ArrayLike, point_b: ArrayLike, length: float, EA: float,
                weight: float, seabed_z: float
                ) -> tuple[FloatArray, FloatArray, TouchingSolution] | None:
    """:func:`solve_touching` between 3-D points (z up) over a seabed at ``seabed_z``.

    Returns
    -------
    (force_on_a, force_on_b, solution) or None
        Forces (shape ``(3,)``) the line exerts on A and B; ``None`` where the line does not
        touch the seabed.
    """
    pa, pb = np.asarray(point_a, dtype=float), np.asarray(point_b, dtype=float)
    d = pb[:2] - pa[:2]
    X = math.hypot(d[0], d[1])
    sol = solve_touching(X, pa[2] - seabed_z, pb[2] - seabed_z, length, EA, weight)
    if sol is None:
        return None
    e = np.array([d[0] / X, d[1] / X, 0.0]) if X > 0.0 else np.zeros(3)
    (fah, faz), (fbh, fbz) = sol.force_a, sol.force_b
    return fah * e + [0.0, 0.0, faz], fbh * e + [0.0, 0.0, fbz], sol


def touching_profile_3d(solution: TouchingSolution, point_a: ArrayLike, point_b: ArrayLike,
                        s: ArrayLike) -> FloatArray:
    """Positions, shape ``(len(s), 3)``, at unstretched arc lengths ``s`` from A."""
    pa, pb = np.asarray(point_a, dtype=float), np.asarray(point_b, dtype=float)
    d = pb[:2] - pa[:2]
    X = math.hypot(d[0], d[1])
    e = np.array([d[0] / X, d[1] / X]) if X > 0.0 else np.array([1.0, 0.0])
    h, z = solution.profile(np.atleast_1d(np.asarray(s, dtype=float)))
    return pa + np.stack([h * e[0], h * e[1], z], axis=-1)
