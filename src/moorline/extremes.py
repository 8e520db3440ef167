"""Extreme-value kernels: peaks, fitted most probable maxima, percentiles, and the Rayleigh
most probable maximum of a Gaussian process.

The most probable maximum (MPM) of the largest of ``n`` independent peaks of distribution
``F`` is taken as the characteristic largest value ``u_n``, ``n (1 - F(u_n)) = 1`` (the
mode of the largest value tends to it as ``n`` grows; Gumbel 1958, Ochi 1990). For Rayleigh
peaks of a zero-mean Gaussian process of variance ``m0`` it is ``sqrt(2 m0 ln n)``, with
``n = nu_0 T`` the number of zero-up-crossings in the exposure ``T`` (the classic result of
Longuet-Higgins 1952 for narrow-band processes). For Gumbel-distributed block maxima
(location ``mu``, scale ``beta``), the largest of ``k`` independent blocks is Gumbel with
location ``mu + beta ln k``: its mode, the MPM over ``k`` blocks.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["gumbel_fit", "gumbel_mpm", "peaks", "percentiles", "rayleigh_mpm",
           "weibull_fit", "weibull_mpm"]

FloatArray = NDArray[np.float64]


def peaks(x: ArrayLike, level: float | None = None) -> FloatArray:
    """The largest value between successive up-crossings of ``level`` (default the mean):
    one peak per up-crossing cycle, the incomplete cycles at both ends dropped.

    Parameters
    ----------
    x
        Signal (n,).
    level
        Reference level; default the signal's mean.
    """
    x = np.asarray(x, dtype=float).ravel()
    if len(x) < 2:
        return np.zeros(0)
    level = float(np.mean(x)) if level is None else float(level)
    up = np.flatnonzero((x[:-1] < level) & (x[1:] >= level)) + 1
    if len(up) < 2:
        return np.zeros(0)
    return np.maximum.reduceat(x[up[0]:up[-1]], up[:-1] - up[0])


def weibull_fit(excess: ArrayLike) -> tuple[float, float]:
    """Maximum-likelihood two-parameter Weibull fit ``P(X > x) = exp(-(x/scale)^shape)`` of
    peak excesses over a level (``scipy.stats.weibull_min`` with location 0).

    Returns
    -------
    shape, scale
    """
    from scipy.stats import weibull_min

    y = np.asarray(excess, dtype=float)
    y = y[y > 0]
    if len(y) < 2:
        raise ValueError("a Weibull fit needs at least two peaks above the level")
    shape, _, scale = weibull_min.fit(y, floc=0.0)
    return float(shape), float(scale)


def weibull_mpm(level: ArrayLike, shape: ArrayLike, scale: ArrayLike,
                n: ArrayLike) -> FloatArray:
    """Characteristic largest of ``n`` Weibull peaks over ``level``:
    ``level + scale (ln n)^(1/shape)``."""
    n = np.maximum(np.asarray(n, dtype=float), 1.0)
    return np.asarray(level) + np.asarray(scale) * np.log(n) ** (1.0 / np.asarray(shape))


def gumbel_fit(maxima: ArrayLike) -> tuple[float, float]:
    """Maximum-likelihood Gumbel fit ``F(x) = exp(-exp(-(x - loc)/scale))`` of block maxima
    (``scipy.stats.gumbel_r``).

    Returns
    -------
    loc, scale
    """
    from scipy.stats import gumbel_r

    y = np.asarray(maxima, dtype=float).ravel()
    if len(y) < 3:
        raise ValueError("a Gumbel fit needs at least three maxima (seeds or blocks)")
    loc, scale = gumbel_r.fit(y)
    return float(loc), float(scale)


def gumbel_mpm(loc: ArrayLike, scale: ArrayLike, blocks: ArrayLike) -> FloatArray:
    """Mode of the largest of ``blocks`` Gumbel(``loc``, ``scale``) maxima:
    ``loc + scale ln(blocks)``."""
    return np.asarray(loc) + np.asarray(scale) * np.log(np.maximum(
        np.asarray(blocks, dtype=float), 1.0))


def rayleigh_mpm(mean: ArrayLike, m0: ArrayLike, m2: ArrayLike,
                 duration: float) -> FloatArray:
    """Most probable maximum of a stationary Gaussian process over ``duration``:
    ``mean + sqrt(2 m0 ln(nu_0 T))``, ``nu_0 = sqrt(m2/m0) / (2 pi)`` (the mean where fewer
    than one up-crossing is expected).

    Parameters
    ----------
    mean
        Mean of the process.
    m0, m2
        Spectral moments of its fluctuation (circular frequency).
    duration
        Exposure ``T`` [s].
    """
    from .spectral import upcrossing_rate

    n = upcrossing_rate(m0, m2) * float(duration)
    return np.asarray(mean) + np.sqrt(2.0 * np.asarray(m0) * np.log(np.maximum(n, 1.0)))


def percentiles(x: ArrayLike, q: ArrayLike, axis: int = 0) -> FloatArray:
    """Sample percentiles ``q`` [%] along ``axis`` (linear interpolation,
    :func:`numpy.percentile`)."""
    return np.percentile(np.asarray(x, dtype=float), np.asarray(q, dtype=float), axis=axis)
