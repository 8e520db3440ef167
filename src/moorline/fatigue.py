"""Fatigue kernels: rainflow counting, Palmgren-Miner damage, spectral (narrow-band and
Dirlik) damage.

Ranges are normalized by the curve's scale (:meth:`moorline.tn_curves.TNCurve.scale`), so a
curve is ``N = K x^-m`` and the damage of ``n_i`` cycles of normalized range ``x_i`` is
``D = sum n_i x_i^m / K`` (Palmgren-Miner).

Rainflow counting uses the four-point algorithm of ``fatpack`` (Amzallag et al. 1994, as
implemented by ``fatpack.find_rainflow_cycles``) on the exact turning points of the signal
(no load classes); the residue is counted as half cycles, which gives the counts of the
three-point procedure of ASTM E1049-85 sec. 5.4.4 (McInnes & Meehan 2008), or closed by
repeating it (Marsh et al. 2016, the stationary-process convention).
"""

from __future__ import annotations

import math
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["dirlik_moment", "miner_damage", "narrow_band_moment", "rainflow", "reversals",
           "spectral_damage"]

FloatArray = NDArray[np.float64]


def reversals(x: ArrayLike) -> FloatArray:
    """The turning points (peaks and valleys) of a signal, its first and last points
    included, with plateaus (repeated values) merged.

    Parameters
    ----------
    x
        Signal (n,).

    Returns
    -------
    numpy.ndarray
        The alternating sequence of extrema (ASTM E1049-85 sec. 3.1.5-3.1.6).
    """
    x = np.asarray(x, dtype=float).ravel()
    if len(x) == 0:
        return x
    x = x[np.r_[True, np.diff(x) != 0.0]]
    if len(x) < 3:
        return x
    slope = np.sign(np.diff(x))
    turns = np.flatnonzero(slope[1:] != slope[:-1]) + 1
    return x[np.r_[0, turns, len(x) - 1]]


def rainflow(x: ArrayLike, residue: Literal["half", "repeat"] = "half"
             ) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Rainflow cycles of a signal.

    Parameters
    ----------
    x
        Signal (n,).
    residue
        ``half``: the ranges left open after the pass count as half cycles (ASTM E1049-85
        sec. 5.4.4); ``repeat``: the residue is followed by itself and counted again, closing
        its cycles (Marsh et al. 2016; the counts of ASTM E1049-85 sec. 5.4.5 for a repeating
        history; for a record of a stationary process).

    Returns
    -------
    ranges, means, counts
        Cycle ranges, means and counts (1 or 0.5), each (n_cycles,).
    """
    from fatpack import concatenate_reversals, find_rainflow_cycles

    rev = reversals(x)
    if len(rev) < 2:
        empty = np.zeros(0)
        return empty, empty, empty
    closed, rest = find_rainflow_cycles(rev)
    closed = np.asarray(closed, dtype=float).reshape(-1, 2)
    rest = np.asarray(rest, dtype=float)
    if residue == "repeat" and len(rest) >= 3:
        again, _ = find_rainflow_cycles(concatenate_reversals(rest, rest))
        pairs = [closed, np.asarray(again, dtype=float).reshape(-1, 2)]
        counts = [np.ones(len(p)) for p in pairs]
    else:
        half = np.column_stack([rest[:-1], rest[1:]])
        pairs = [closed, half]
        counts = [np.ones(len(closed)), np.full(len(half), 0.5)]
    cycles = np.concatenate(pairs)
    return (np.abs(cycles[:, 1] - cycles[:, 0]), cycles.mean(axis=1),
            np.concatenate(counts))


def miner_damage(ranges: ArrayLike, counts: ArrayLike, m: float, K: float) -> float:
    """Palmgren-Miner damage ``sum n_i x_i^m / K`` of cycles of normalized range ``x_i``
    on the curve ``N = K x^-m``."""
    x = np.asarray(ranges, dtype=float)
    return float(np.sum(np.asarray(counts, dtype=float) * x**m) / K)


def narrow_band_moment(m0: ArrayLike, m: float) -> FloatArray:
    """``E[S^m]`` of the ranges of a narrow-band Gaussian process of variance ``m0``:
    Rayleigh amplitudes, ranges twice the amplitude, ``(2 sqrt(2 m0))^m Gamma(1 + m/2)``
    (Bendat 1964)."""
    m0 = np.asarray(m0, dtype=float)
    return (2.0 * np.sqrt(2.0 * m0)) ** m * math.gamma(1.0 + m / 2.0)


def dirlik_moment(moments: ArrayLike, m: float) -> FloatArray:
    """``E[S^m]`` of the rainflow ranges by Dirlik's (1985) empirical range density.

    With ``x_m = (m1/m0) sqrt(m2/m4)``, ``gamma = m2 / sqrt(m0 m4)``, ``D1 = 2 (x_m -
    gamma^2) / (1 + gamma^2)``, ``R = (gamma - x_m - D1^2) / (1 - gamma - D1 + D1^2)``,
    ``D2 = (1 - gamma - D1 + D1^2) / (1 - R)``, ``D3 = 1 - D1 - D2``, ``Q = 1.25 (gamma - D3 -
    D2 R) / D1`` and ``Z = S / (2 sqrt(m0))``, the density is ``[D1/Q e^(-Z/Q) + D2 Z/R^2
    e^(-Z^2/(2R^2)) + D3 Z e^(-Z^2/2)] / (2 sqrt(m0))``, whose ``m``-th moment is
    ``(2 sqrt(m0))^m [D1 Q^m Gamma(1+m) + 2^(m/2) Gamma(1+m/2) (D2 |R|^m + D3)]``. At a
    single frequency (``gamma = 1``) it is the narrow-band (Rayleigh) value.

    Parameters
    ----------
    moments
        ``(m0, m1, m2, m4)`` (4, ...) as from :func:`moorline.spectral.spectral_moments`.
    m
        Inverse slope of the curve.
    """
    m0, m1, m2, m4 = np.asarray(moments, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        x_m = (m1 / m0) * np.sqrt(m2 / m4)
        gamma = m2 / np.sqrt(m0 * m4)
        d1 = 2.0 * (x_m - gamma**2) / (1.0 + gamma**2)
        r = (gamma - x_m - d1**2) / (1.0 - gamma - d1 + d1**2)
        d2 = (1.0 - gamma - d1 + d1**2) / (1.0 - r)
        d3 = 1.0 - d1 - d2
        q = 1.25 * (gamma - d3 - d2 * r) / d1
        value = (2.0 * np.sqrt(m0)) ** m * (
            d1 * q**m * math.gamma(1.0 + m)
            + 2.0 ** (m / 2.0) * math.gamma(1.0 + m / 2.0) * (d2 * np.abs(r) ** m + d3))
    # a single frequency (gamma = x_m = 1): D1 = D2 = 0, D3 = 1, Rayleigh ranges (0/0 above)
    value = np.where(gamma > 1.0 - 1e-9, narrow_band_moment(m0, m), value)
    return np.where(m0 > 0, value, 0.0)


def spectral_damage(moments: ArrayLike, m: float, K: ArrayLike, duration: float,
                    method: Literal["narrow_band", "dirlik"]) -> FloatArray:
    """Expected Miner damage over ``duration`` of a stationary Gaussian process.

    Narrow band: ``nu_0 T E[S^m] / K`` with the zero-up-crossing rate ``nu_0`` and the
    Rayleigh ranges (:func:`narrow_band_moment`); Dirlik: ``nu_p T E[S^m] / K`` with the
    rate of maxima ``nu_p`` and Dirlik's ranges (:func:`dirlik_moment`).

    Parameters
    ----------
    moments
        ``(m0, m1, m2, m4)`` (4, ...) of the normalized process (tension over the curve's
        scale), circular frequency.
    m, K
        The curve ``N = K x^-m`` (``K`` per signal allowed).
    duration
        Exposure [s].
    method
        ``narrow_band`` or ``dirlik``.
    """
    from .spectral import peak_rate, upcrossing_rate

    m0, _, m2, m4 = np.asarray(moments, dtype=float)
    if method == "narrow_band":
        cycles = upcrossing_rate(m0, m2) * duration
        moment = narrow_band_moment(m0, m)
    elif method == "dirlik":
        cycles = peak_rate(m2, m4) * duration
        moment = dirlik_moment(moments, m)
    else:
        raise ValueError(f"unknown spectral fatigue method {method!r}")
    return cycles * moment / np.asarray(K, dtype=float)
