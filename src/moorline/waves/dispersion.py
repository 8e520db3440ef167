"""Linear dispersion relation of surface gravity waves, ``omega^2 = g k tanh(k h)``.

References
----------
Dean, R. G. & Dalrymple, R. A. (1991), *Water Wave Mechanics for Engineers and Scientists*,
sec. 3.4, eq. (3.31) (the dispersion relation).

Fenton, J. D. & McKee, W. D. (1990), "On calculating the lengths of water waves",
*Coastal Engineering* 14, 499-513 (the explicit first approximation used as starting value).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

FloatArray = NDArray[np.float64]

_MAX_NEWTON = 50
_RTOL = 1e-15


def wave_number(omega: ArrayLike, depth: ArrayLike, gravity: float) -> FloatArray:
    r"""Wave number ``k`` of a linear wave of angular frequency ``omega`` in water of ``depth``.

    Solves the dispersion relation (Dean & Dalrymple 1991, eq. 3.31)

    .. math:: \omega^2 = g\,k \tanh(k h)

    in the dimensionless form ``y tanh(y) = x`` with ``y = k h`` and ``x = omega^2 h / g``.
    The starting value is Fenton & McKee's (1990) explicit approximation
    ``y0 = x coth(x^(3/4))^(2/3)`` (better than 1.5 % everywhere); Newton's method then runs
    until the largest relative change of ``y`` is below ``1e-15`` (three or four steps).

    Parameters
    ----------
    omega
        Angular frequency [rad/time], any shape; only ``omega**2`` matters (the sign is ignored).
        ``omega = 0`` gives ``k = 0``.
    depth
        Water depth [length], broadcast against ``omega``; ``inf`` means deep water, where
        ``k = omega^2 / g`` exactly.
    gravity
        Gravitational acceleration [length/time^2] (no unit is assumed).

    Returns
    -------
    numpy.ndarray
        ``k`` [rad/length] with the broadcast shape of ``omega`` and ``depth`` (0-d for scalars).
    """
    if not gravity > 0.0:
        raise ValueError(f"gravity must be positive, got {gravity!r}")
    w2, h = np.broadcast_arrays(
        np.square(np.asarray(omega, dtype=float)), np.asarray(depth, dtype=float)
    )
    if np.any(h <= 0.0) or np.any(np.isnan(h)):
        raise ValueError("depth must be positive (inf for deep water)")
    if not np.all(np.isfinite(w2)):
        raise ValueError("omega must be finite")
    k = np.array(w2 / gravity, dtype=float)  # deep water; also k = 0 for omega = 0
    finite = np.isfinite(h) & (w2 > 0.0)
    if np.any(finite):
        hf = h[finite]
        x = w2[finite] * hf / gravity
        y = x / np.tanh(x**0.75) ** (2.0 / 3.0)  # Fenton & McKee (1990)
        for _ in range(_MAX_NEWTON):
            th = np.tanh(y)
            f = y * th - x
            df = th + y * (1.0 - th * th)
            step = f / df
            y = y - step
            if np.max(np.abs(step) / y) < _RTOL:
                break
        k[finite] = y / hf
    return k if k.ndim else k[()]


def omega_from_k(k: ArrayLike, depth: ArrayLike, gravity: float) -> FloatArray:
    r"""Angular frequency of a linear wave of wave number ``k``: ``omega = sqrt(g k tanh(k h))``.

    Parameters
    ----------
    k
        Wave number [rad/length], non-negative, any shape.
    depth
        Water depth [length], broadcast against ``k``; ``inf`` gives ``sqrt(g k)``.
    gravity
        Gravitational acceleration [length/time^2].

    Returns
    -------
    numpy.ndarray
        ``omega`` [rad/time] (0-d for scalar input), Dean & Dalrymple (1991) eq. 3.31.
    """
    kk = np.asarray(k, dtype=float)
    h = np.asarray(depth, dtype=float)
    if np.any(kk < 0.0):
        raise ValueError("k must be non-negative")
    with np.errstate(invalid="ignore"):
        kh = kk * h  # 0 * inf -> nan, tanh(inf) = 1 otherwise
    th = np.where(np.isinf(h), 1.0, np.tanh(np.nan_to_num(kh, nan=0.0)))
    out = np.sqrt(gravity * kk * th)
    return out if out.ndim else out[()]
