"""Spectral moments of one-sided response spectra and the rates that follow from them.

Shared by spectral fatigue (:mod:`moorline.fatigue`) and frequency-domain extremes
(:mod:`moorline.extremes`). A spectrum here is one-sided in circular frequency:
``var = int_0^inf S(omega) d omega``, sampled on equally spaced ``omega`` with step
``d_omega`` (the stochastic analysis's grid, :class:`moorline.results.StochasticResult`).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["peak_rate", "spectral_moments", "upcrossing_rate"]

FloatArray = NDArray[np.float64]


def spectral_moments(omega: ArrayLike, spectrum: ArrayLike, d_omega: float,
                     orders: tuple[int, ...] = (0, 1, 2, 4)) -> FloatArray:
    """Moments ``m_n = sum_k omega_k^n S(omega_k) d_omega`` of one-sided spectra.

    Parameters
    ----------
    omega
        Circular frequencies (n_w,) [rad/s].
    spectrum
        One-sided spectra (n_w, ...) per rad/s; the trailing axes are independent signals.
    d_omega
        Frequency step [rad/s] (the rectangle rule of the stochastic analysis, whose
        variances are ``sum |H|^2 S d_omega``).
    orders
        The moments wanted.

    Returns
    -------
    numpy.ndarray
        ``(len(orders), ...)``: ``m_n`` in ``[spectrum] (rad/s)^n``.
    """
    w = np.asarray(omega, dtype=float)
    s = np.asarray(spectrum, dtype=float)
    powers = w[None, :] ** np.asarray(orders, dtype=float)[:, None]  # (n_orders, n_w)
    return np.tensordot(powers, s, axes=(1, 0)) * float(d_omega)


def upcrossing_rate(m0: ArrayLike, m2: ArrayLike) -> FloatArray:
    """Mean zero-up-crossing rate ``nu_0 = sqrt(m2 / m0) / (2 pi)`` [Hz] of a stationary
    Gaussian process (Rice 1944, eq. 3.3-11); 0 where ``m0 = 0``."""
    m0, m2 = np.asarray(m0, dtype=float), np.asarray(m2, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        rate = np.sqrt(m2 / m0) / (2.0 * np.pi)
    return np.where(m0 > 0, rate, 0.0)


def peak_rate(m2: ArrayLike, m4: ArrayLike) -> FloatArray:
    """Mean rate of maxima ``nu_p = sqrt(m4 / m2) / (2 pi)`` [Hz] (Rice 1944); 0 where
    ``m2 = 0``."""
    m2, m4 = np.asarray(m2, dtype=float), np.asarray(m4, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        rate = np.sqrt(m4 / m2) / (2.0 * np.pi)
    return np.where(m2 > 0, rate, 0.0)
