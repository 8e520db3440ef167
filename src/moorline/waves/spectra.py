"""Wave power spectra: Pierson-Moskowitz and JONSWAP (one-sided, in circular frequency).

``S(omega)`` [length^2 time/rad] with ``m0 = int_0^inf S d omega`` the variance of the surface
elevation; the significant wave height is ``Hs = 4 sqrt(m0)``.

Pierson-Moskowitz (the form Tuah 1982 sec. 6.5 uses, given by its energy ``m0`` and peak
frequency ``omega_p``; Hurricane Carla: ``m0 = 28 ft^2``, ``omega_p = 0.5 rad/s``)::

    S_PM(omega) = 5 m0 omega_p^4 / omega^5 exp(-5/4 (omega_p / omega)^4),

whose integral is exactly ``m0`` (substitute ``u = (omega_p / omega)^4``) and whose maximum is
at ``omega_p``. With ``m0 = Hs^2 / 16`` this is the familiar ``5/16 Hs^2 omega_p^4 omega^-5
exp(...)``.

JONSWAP: the Pierson-Moskowitz shape times the peak enhancement
``gamma ^ exp(-(omega - omega_p)^2 / (2 sigma^2 omega_p^2))`` with ``sigma = 0.07`` below the
peak and ``0.09`` above, scaled so that its integral is ``Hs^2 / 16`` exactly (the scale is
computed by quadrature; DNV-RP-C205's closed-form factor ``1 - 0.287 ln gamma`` is within
2 % of it for ``1 <= gamma <= 7``). ``gamma = 1`` is Pierson-Moskowitz.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

FloatArray = NDArray[np.float64]
SpectrumKind = Literal["pierson-moskowitz", "jonswap"]


def pierson_moskowitz(omega: ArrayLike, m0: float, omega_p: float) -> FloatArray:
    """Pierson-Moskowitz spectrum ``5 m0 omega_p^4 omega^-5 exp(-5/4 (omega_p/omega)^4)``.

    Parameters
    ----------
    omega
        Circular frequencies [rad/time] (``<= 0`` gives 0).
    m0
        Zeroth moment (elevation variance) [length^2].
    omega_p
        Peak frequency [rad/time].
    """
    w = np.asarray(omega, dtype=float)
    out = np.zeros_like(w)
    pos = w > 0
    r = omega_p / w[pos]
    out[pos] = 5.0 * m0 / omega_p * r**5 * np.exp(-1.25 * r**4)
    return out


def _peak_shape(w: FloatArray, omega_p: float, gamma: float, sigma_a: float,
                sigma_b: float) -> FloatArray:
    sigma = np.where(w <= omega_p, sigma_a, sigma_b)
    return gamma ** np.exp(-((w - omega_p) ** 2) / (2.0 * sigma**2 * omega_p**2))


def jonswap(omega: ArrayLike, hs: float, tp: float, gamma: float = 3.3,
            sigma_a: float = 0.07, sigma_b: float = 0.09) -> FloatArray:
    """JONSWAP spectrum of significant height ``hs`` and peak period ``tp``, normalized to
    ``m0 = hs^2 / 16`` exactly.

    Parameters
    ----------
    omega
        Circular frequencies [rad/time].
    hs, tp
        Significant wave height [length] and peak period [time].
    gamma
        Peak enhancement factor (``>= 1``; 1 gives Pierson-Moskowitz).
    sigma_a, sigma_b
        Peak widths below and above the peak.
    """
    omega_p = 2.0 * math.pi / tp
    m0 = hs * hs / 16.0
    w = np.asarray(omega, dtype=float)
    shape = pierson_moskowitz(w, m0, omega_p) * _peak_shape(w, omega_p, gamma, sigma_a,
                                                            sigma_b)
    return shape * (m0 / _jonswap_area(m0, omega_p, gamma, sigma_a, sigma_b))


def _jonswap_area(m0: float, omega_p: float, gamma: float, sigma_a: float,
                  sigma_b: float) -> float:
    """Integral of the unnormalized JONSWAP spectrum (quadrature on either side of the
    peak, in ``u = omega / omega_p``)."""
    def f(u: float) -> float:
        w = np.array([u * omega_p])
        return float((pierson_moskowitz(w, m0, omega_p)
                      * _peak_shape(w, omega_p, gamma, sigma_a, sigma_b))[0]) * omega_p

    from scipy import integrate  # imported on use (0.3 s with scipy.optimize)

    low, _ = integrate.quad(f, 0.0, 1.0, limit=200, epsabs=0.0, epsrel=1e-12)
    high, _ = integrate.quad(f, 1.0, np.inf, limit=200, epsabs=0.0, epsrel=1e-12)
    return low + high


@dataclass(frozen=True)
class WaveSpectrum:
    """A one-sided wave spectrum by its parameters.

    Attributes
    ----------
    kind
        ``pierson-moskowitz`` or ``jonswap``.
    hs, tp
        Significant wave height ``4 sqrt(m0)`` [length] and peak period ``2 pi / omega_p``
        [time].
    gamma
        JONSWAP peak enhancement (ignored for Pierson-Moskowitz).
    """

    kind: SpectrumKind
    hs: float
    tp: float
    gamma: float = 3.3

    @classmethod
    def from_moment(cls, kind: SpectrumKind, m0: float, omega_p: float,
                    gamma: float = 3.3) -> WaveSpectrum:
        """From the zeroth moment ``m0`` and peak frequency ``omega_p`` (Tuah's
        parameters)."""
        return cls(kind, 4.0 * math.sqrt(m0), 2.0 * math.pi / omega_p, gamma)

    @property
    def m0(self) -> float:
        """Elevation variance ``hs^2 / 16`` [length^2]."""
        return self.hs * self.hs / 16.0

    @property
    def omega_p(self) -> float:
        """Peak frequency [rad/time]."""
        return 2.0 * math.pi / self.tp

    def density(self, omega: ArrayLike) -> FloatArray:
        """``S(omega)`` [length^2 time/rad]."""
        if self.kind == "pierson-moskowitz":
            return pierson_moskowitz(omega, self.m0, self.omega_p)
        return jonswap(omega, self.hs, self.tp, self.gamma)


__all__ = ["SpectrumKind", "WaveSpectrum", "jonswap", "pierson_moskowitz"]
