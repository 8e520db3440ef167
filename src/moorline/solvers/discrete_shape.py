"""The equilibrium shape of a line's finite elements (straight elements, lumped weights).

Starting the finite elements on the continuous catenary leaves them out of balance where the
elements are long against the curvature: each chord is shorter than the arc it replaces
(by ``L0^3 / (24 R^2)``), so a stiff line starts with slack elements and Newton spends its
first iterations pulling them taut (18-21 iterations on each line of MoorPy's W-shaped
``case6`` deck, 33 m elements on a 29 m catenary parameter). The discrete line has a closed
form of its own: with the weight ``W = w L0`` lumped at the nodes, the tension components in
element ``j`` are ``H`` and ``V_j = V_top - (n - 1 - j) W`` (every interior node in vertical
balance; Irvine 1981 sec. 1.5, the cable with concentrated loads), each element points along
its tension and is stretched by ``T_j / EA``. On a seabed at end A the elements with
``V_j <= 0`` lie flat (their nodes carried by the seabed, the touchdown node partly). The two
unknowns ``(H, V_top)`` are found by Newton on the position of end B, from the continuous
catenary's values; the shape then balances every interior node of the elastic model exactly
(seabed friction, current and the contact's penetration aside).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]

__all__ = ["discrete_catenary"]


def _walk(H: float, V_top: float, n: int, L0: float, EA: float, W: float,
          contact: bool) -> tuple[FloatArray, FloatArray]:
    """Horizontal and vertical extents (n,) of the elements for tension ``(H, V_top)``."""
    V = V_top - (n - 1 - np.arange(n)) * W
    if contact:
        V = np.maximum(V, 0.0)
    T = np.hypot(H, V)
    T = np.where(T > 0.0, T, 1e-300)
    stretch = L0 * (1.0 + T / EA)
    return stretch * H / T, stretch * V / T


def discrete_catenary(point_a: FloatArray, point_b: FloatArray, n: int, length: float,
                      EA: float, weight: float, contact_a: bool, H: float, V_top: float,
                      max_iterations: int = 50) -> FloatArray | None:
    """Node positions (n + 1, 3) of ``n`` equal elements in equilibrium between A and B.

    Parameters
    ----------
    point_a, point_b
        End positions (z up).
    n, length
        Number of elements and unstretched length of the line.
    EA, weight
        Axial stiffness and submerged weight per unstretched length.
    contact_a
        End A rests on a seabed at its height: elements that would have a downward tension
        component lie flat on it.
    H, V_top
        Starting horizontal tension and vertical tension component at B (the continuous
        catenary's ``H`` and ``V_b``).
    max_iterations
        Newton iterations on ``(H, V_top)``.

    Returns
    -------
    ndarray or None
        The positions (the first A, the last B to round-off), or ``None`` when Newton does
        not converge or the line has no horizontal tension (a vertical line or a pile).
    """
    a, b = np.asarray(point_a, dtype=float), np.asarray(point_b, dtype=float)
    d = b - a
    X, Z = math.hypot(d[0], d[1]), float(d[2])
    if n < 1 or not EA > 0.0 or not H > 0.0 or X <= 0.0:
        return None
    L0, W = length / n, weight * length / n
    scale = max(abs(weight) * length, H, abs(V_top), 1.0)
    tol = 1e-11 * max(length, math.hypot(X, Z))

    def miss(u: FloatArray) -> FloatArray:
        hx, vz = _walk(u[0], u[1], n, L0, EA, W, contact_a)
        return np.array([hx.sum() - X, vz.sum() - Z])

    u = np.array([H, V_top], dtype=float)
    r = miss(u)
    for _ in range(max_iterations):
        if np.abs(r).max() <= tol:
            break
        J = np.empty((2, 2))
        for k in range(2):
            h = 1e-7 * max(abs(u[k]), scale * 1e-3)
            up = u.copy()
            up[k] += h
            J[:, k] = (miss(up) - r) / h
        try:
            step = np.linalg.solve(J, -r)
        except np.linalg.LinAlgError:
            return None
        t = 1.0
        while t > 1e-4:
            trial = u + t * step
            if trial[0] > 0.0:
                r_trial = miss(trial)
                if np.abs(r_trial).max() < np.abs(r).max():
                    u, r = trial, r_trial
                    break
            t *= 0.5
        else:
            return None
    if np.abs(r).max() > tol or not np.all(np.isfinite(u)):
        return None
    hx, vz = _walk(u[0], u[1], n, L0, EA, W, contact_a)
    e = np.array([d[0] / X, d[1] / X])
    out = np.empty((n + 1, 3))
    out[0] = a
    out[1:, :2] = a[:2] + np.cumsum(hx)[:, None] * e
    out[1:, 2] = a[2] + np.cumsum(vz)
    out[-1] = b
    return out
