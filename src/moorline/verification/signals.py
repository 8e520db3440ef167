"""Least-squares harmonic fit of a time history (the response amplitudes of the cases)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class HarmonicFit:
    """``y(t) ~ mean + slope (t - mean(t)) + sum_k (cos_k cos k w t + sin_k sin k w t)``.

    Attributes
    ----------
    mean
        The constant term (the value at the mean time when a trend is fitted).
    slope
        The linear trend (a slow drift); 0 when none is fitted.
    cos, sin
        Coefficients of ``cos k w t`` and ``sin k w t``, ``k = 1 .. harmonics``.
    """

    mean: float
    slope: float
    cos: FloatArray
    sin: FloatArray

    def phasor(self, k: int = 1) -> complex:
        """Complex amplitude ``Y`` of harmonic ``k`` with ``y_k = Re(Y e^{-i k w t})``."""
        return complex(self.cos[k - 1], self.sin[k - 1])

    def amplitude(self, k: int = 1) -> float:
        """Amplitude ``a`` of harmonic ``k``, ``y_k = a sin(k w t + phase)``."""
        return float(math.hypot(self.cos[k - 1], self.sin[k - 1]))

    def phase(self, k: int = 1) -> float:
        """Phase [rad] of harmonic ``k``, ``y_k = a sin(k w t + phase)``."""
        return float(math.atan2(self.cos[k - 1], self.sin[k - 1]))


def harmonic_fit(time: ArrayLike, signal: ArrayLike, omega: float, harmonics: int = 1,
                 trend: bool = False) -> HarmonicFit:
    """Least-squares fit of a constant, optionally a linear trend, and ``harmonics``
    harmonics of ``omega`` to a sampled signal.

    Parameters
    ----------
    time, signal
        Samples (n,).
    omega
        Fundamental circular frequency [rad/s].
    harmonics
        Number of harmonics fitted (the first response amplitude is less polluted by a
        second harmonic when that is fitted too).
    trend
        Fit a linear trend ``slope (t - mean(t))`` as well.

    Returns
    -------
    HarmonicFit
    """
    t = np.asarray(time, float)
    cols = [np.ones_like(t)]
    if trend:
        cols.append(t - t.mean())
    for k in range(1, harmonics + 1):
        cols += [np.cos(k * omega * t), np.sin(k * omega * t)]
    coef = np.linalg.lstsq(np.column_stack(cols), np.asarray(signal, float), rcond=None)[0]
    first = 2 if trend else 1
    return HarmonicFit(mean=float(coef[0]), slope=float(coef[1]) if trend else 0.0,
                       cos=coef[first::2].copy(), sin=coef[first + 1::2].copy())
