"""Complex transfer functions of linear wave kinematics (Tuah (1982) eq. 5.2.8-5.2.10).

For a wave component of unit complex amplitude, ``eta(x, t) = Re exp(i (omega t - k . x))``
(the convention of :class:`moorline.waves.WaveComponents` with ``eta = a cos(k . x - omega t +
phi)``), the fluid velocity and acceleration at a point are ``Re H_v exp(i omega t)`` and
``Re H_a exp(i omega t)`` with::

    H_v = omega exp(-i k . x) [c cos(beta), c sin(beta), i s],    H_a = i omega H_v,
    c = cosh k(z + h) / sinh kh,   s = sinh k(z + h) / sinh kh,

``beta`` the heading (``omega c = g k cosh k(z+h) / (omega cosh kh)``: Tuah's eq. 5.2.10 form).
Points above the still water level are evaluated at ``z = 0`` (linear theory), below the seabed
at the seabed.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .dispersion import wave_number

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]


def depth_factors(k: FloatArray, z: FloatArray, depth: float) -> tuple[FloatArray, FloatArray]:
    """``cosh k(z+h) / sinh kh`` and ``sinh k(z+h) / sinh kh`` (n_w, n_p), overflow-free
    (deep water: both ``exp(k z)``)."""
    ze = np.minimum(np.maximum(z, -depth), 0.0)[None, :]
    kk = k[:, None]
    ekz = np.exp(kk * ze)
    if not math.isfinite(depth):
        return ekz, ekz
    denom = -np.expm1(-2.0 * kk * depth)
    em = np.expm1(-2.0 * kk * (ze + depth))
    return ekz * (2.0 + em) / denom, -ekz * em / denom


def kinematics_transfer(points: ArrayLike, omegas: ArrayLike, heading_deg: float,
                        depth: float, gravity: float) -> tuple[ComplexArray, ComplexArray]:
    """Velocity and acceleration per unit complex wave amplitude.

    Parameters
    ----------
    points
        Positions (n_p, 3).
    omegas
        Circular frequencies (n_w,) [rad/time], ``> 0``.
    heading_deg
        Direction of propagation [deg].
    depth, gravity
        Water depth (``inf`` for deep water) and gravitational acceleration.

    Returns
    -------
    H_v, H_a
        (n_w, n_p, 3) complex arrays.
    """
    p = np.asarray(points, dtype=float).reshape(-1, 3)
    w = np.atleast_1d(np.asarray(omegas, dtype=float))
    k = np.atleast_1d(np.asarray(wave_number(w, depth, gravity), dtype=float))
    beta = math.radians(heading_deg)
    cfac, sfac = depth_factors(k, p[:, 2], depth)
    phase = np.exp(-1j * np.outer(k, p[:, 0] * math.cos(beta) + p[:, 1] * math.sin(beta)))
    H_v = np.empty((w.size, p.shape[0], 3), dtype=complex)
    H_v[..., 0] = cfac * math.cos(beta)
    H_v[..., 1] = cfac * math.sin(beta)
    H_v[..., 2] = 1j * sfac
    H_v *= (w[:, None] * phase)[..., None]
    return H_v, 1j * w[:, None, None] * H_v


__all__ = ["depth_factors", "kinematics_transfer"]
