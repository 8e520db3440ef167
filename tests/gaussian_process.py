"""Realizations of stationary Gaussian processes for the fatigue and extremes tests.

Spectral synthesis with random complex Gaussian Fourier coefficients (not deterministic
amplitudes): ``x(t) = sum_k Re(c_k e^(i w_k t))`` with ``E|c_k|^2 = 2 S(w_k) dw`` on the
grid ``w_k = 2 pi k / T``, so that every realization is a sample of a zero-mean Gaussian
process of one-sided spectrum ``S`` (periodic over ``T``; Shinozuka & Deodatis 1991 with
Rayleigh amplitudes).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np


def realize(spectrum: Callable[[np.ndarray], np.ndarray], duration: float, dt: float,
            seeds: int, seed: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """``seeds`` realizations (seeds, n) of the process of one-sided spectrum ``spectrum(w)``
    [per rad/s] over ``duration`` sampled every ``dt``; returns ``(t, x)``."""
    n = int(round(duration / dt))
    d_omega = 2.0 * np.pi / (n * dt)
    omega = np.arange(n // 2 + 1) * d_omega
    s = spectrum(omega)
    s[0] = 0.0
    rng = np.random.default_rng(seed)
    coef = (rng.standard_normal((seeds, len(omega)))
            + 1j * rng.standard_normal((seeds, len(omega)))) * np.sqrt(s * d_omega)
    x = np.fft.irfft(coef, n=n, axis=1) * (n / 2.0)  # irfft doubles the k > 0 terms
    return np.arange(n) * dt, x


def grid(spectrum: Callable[[np.ndarray], np.ndarray], d_omega: float = 1e-3,
         omega_max: float = 20.0) -> tuple[np.ndarray, np.ndarray, float]:
    """The spectrum on a fine grid for its moments: ``(omega, S, d_omega)``."""
    omega = np.arange(1, int(omega_max / d_omega)) * d_omega
    return omega, spectrum(omega), d_omega
