"""Gaussian expectations of the quadratic drag law with a mean flow (statistical linearization).

A Morison drag ``c |w| w`` on a relative velocity ``w = W + w'``, ``W`` the mean (a current)
and ``w'`` a zero-mean Gaussian fluctuation (the waves and the structure's response), is
replaced by ``c (E[|w| w] + G w')``. The mean-square error of the replacement is least for
``G = E[|w| w w'^T] Cov(w')^-1``, which for a Gaussian ``w'`` equals the expected Jacobian
``G = E[d(|w| w)/dw] = E[|w| Pi + w w^T / |w|]`` (Atalik & Utku (1976), Earthquake Eng.
Struct. Dyn. 4, 411-420, eq. 11; Roberts & Spanos, *Random Vibration and Statistical
Linearization* (1990) sec. 5.4), ``Pi`` the identity of the plane (or space) ``w`` lives in.

One dimension (closed form; Borgman (1972) for ``W = 0``), ``X = U + sigma xi``::

    E|X|    = sigma (2/pi)^(1/2) exp(-U^2 / (2 sigma^2)) + U erf(U / (2^(1/2) sigma)),
    E[X|X|] = (U^2 + sigma^2) erf(U / (2^(1/2) sigma))
              + sigma U (2/pi)^(1/2) exp(-U^2 / (2 sigma^2)),

and ``d/dX (X|X|) = 2|X|``, so ``G = 2 E|X|`` (``(8/pi)^(1/2) sigma`` at ``U = 0``, ``2|U|``
for ``U >> sigma``); ``dE[X|X|]/dU = 2 E|X|`` (a check).

Several dimensions (a cable's normal plane, a point's three directions): the exact
expectations over the Gaussian, along the principal axes of ``Cov(w')`` (variances below
``1e-6`` of the largest neglected). One axis with the mean on it (a planar system in a
current in its plane): one-dimensional, the closed form, ``E[|w| w] = E[X|X|] e`` and
``G = E|X| (Pi + e e^T)`` (the fluctuation's axis ``e``; note ``E|X|``, not ``2 E|X|``, across
it: Tuah's zero-mean ``B_DL (I - t t^T)`` takes ``(8/pi)^(1/2) sigma_n`` in both normal
directions). One axis with the mean off it: a dense trapezoidal rule. Two axes (a cable's
normal plane): polar coordinates of the whitened variable about the origin, the radial
integrals in closed form (truncated Gaussian moments), the trapezoidal rule over the angle
(exponential convergence) on the window of angles the Gaussian occupies (a mean flow much
larger than the fluctuation concentrates it on a needle of width ``sigma / |W|``).
Three axes (a point): tensor Gauss-Hermite quadrature (16 points per axis: ``|w|`` has a
kink at the origin, an error of order 1e-3 at zero mean, less with a current).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.polynomial.hermite_e import hermegauss
from numpy.typing import NDArray
from scipy.special import erf

FloatArray = NDArray[np.float64]

_SQRT_2_PI = math.sqrt(2.0 / math.pi)
#: Mahalanobis distance of the mean beyond which the plane rule integrates over a window of
#: angles only (:func:`_plane_expectations`).
_WINDOW = 10.0


def scalar_expectations(mean: FloatArray, sigma: FloatArray) -> tuple[FloatArray, FloatArray]:
    """``E[X|X|]`` and ``E|X|`` of ``X ~ N(mean, sigma^2)`` (element-wise, closed form).

    ``sigma = 0`` gives ``mean |mean|`` and ``|mean|``.
    """
    U = np.asarray(mean, dtype=float)
    s = np.asarray(sigma, dtype=float)
    safe = np.where(s > 0.0, s, 1.0)
    z = U / (math.sqrt(2.0) * safe)
    gauss = _SQRT_2_PI * safe * np.exp(-z * z)
    e_abs = np.where(s > 0.0, gauss + U * erf(z), np.abs(U))
    e_sq = np.where(s > 0.0, (U * U + s * s) * erf(z) + U * gauss, U * np.abs(U))
    return e_sq, e_abs


def vector_expectations(mean: FloatArray, cov: FloatArray, plane: FloatArray,
                        order: int = 16) -> tuple[FloatArray, FloatArray]:
    """``E[|w| w]`` and ``G = E[|w| Pi + w w^T / |w|]`` of ``w ~ N(mean, cov)``.

    By the principal axes of ``cov`` with non-zero variance (a variance below ``1e-6`` of the
    largest is neglected: a relative change of the expectations of that order): none, the
    values at the mean; one, the closed form when the mean lies on the axis, else a dense
    trapezoidal rule over the axis (:func:`_line_expectations`); two (a cable's normal plane),
    the radial integrals in closed form and a trapezoidal rule over the polar angle
    (:func:`_plane_expectations`); three (a point), Gauss-Hermite quadrature with ``order``
    points per axis.

    Parameters
    ----------
    mean
        Mean vectors (n, 3), in the subspace of ``plane``.
    cov
        Covariances of the fluctuation (n, 3, 3), in the same subspace.
    plane
        The projector ``Pi`` onto the subspace (n, 3, 3): ``I - t t^T`` for a cable's normal
        plane, ``I`` for a point.
    order
        Gauss-Hermite points per axis (three axes only).

    Returns
    -------
    mean_force, gain
        (n, 3) and (n, 3, 3).
    """
    mean = np.asarray(mean, dtype=float)
    n = mean.shape[0]
    out_f = np.zeros((n, 3))
    out_g = np.zeros((n, 3, 3))
    for i in range(n):
        lam, vec = np.linalg.eigh(0.5 * (cov[i] + cov[i].T))
        scale = max(float(lam.max(initial=0.0)), 0.0)
        active = lam > 1e-6 * scale if scale > 0 else np.zeros(3, bool)
        W = mean[i]
        axes, sig = vec[:, active], np.sqrt(lam[active])
        if axes.shape[1] == 0:
            norm = float(np.linalg.norm(W))
            out_f[i] = norm * W
            out_g[i] = norm * plane[i] + (np.outer(W, W) / norm if norm > 0 else 0.0)
            continue
        if axes.shape[1] == 1:
            f, g_abs, g_out = _line_expectations(W, axes[:, 0], float(sig[0]))
        elif axes.shape[1] == 2:
            f, g_abs, g_out = _plane_expectations(W, axes, sig)
        else:
            f, g_abs, g_out = _hermite_expectations(W, axes * sig, order)
        out_f[i] = f
        out_g[i] = g_abs * plane[i] + g_out
    return out_f, out_g


def _line_expectations(W: FloatArray, e: FloatArray, sigma: float
                       ) -> tuple[FloatArray, float, FloatArray]:
    """``E[|w| w]``, ``E|w|`` and ``E[w w^T / |w|]`` for ``w = W + sigma xi e``: closed form
    when ``W`` is on ``e`` (``E[w w^T/|w|] = E|X| e e^T``), else the trapezoidal rule on
    ``xi`` in [-12, 12] with 4801 points (the integrand is smooth, its kink softened by the
    mean's part off the axis)."""
    a = float(W @ e)
    off = W - a * e
    if np.linalg.norm(off) <= 1e-12 * (abs(a) + sigma):
        e_sq, e_abs = scalar_expectations(np.array(a), np.array(sigma))
        return float(e_sq) * e, float(e_abs), float(e_abs) * np.outer(e, e)
    xi = np.linspace(-12.0, 12.0, 4801)
    wts = np.exp(-0.5 * xi * xi)
    wts /= wts.sum()
    w = off[None] + (a + sigma * xi)[:, None] * e[None]
    norm = np.sqrt(np.sum(w * w, axis=1))
    return (wts @ (norm[:, None] * w), float(wts @ norm),
            np.einsum("q,qi,qj->ij", wts / norm, w, w))


def _truncated_moments(mu: FloatArray, s: FloatArray) -> tuple[FloatArray, FloatArray]:
    """``E[Y^k; Y > 0]`` for ``Y ~ N(mu, s^2)``, ``k = 2, 3``."""
    alpha = mu / s
    Phi = 0.5 * (1.0 + erf(alpha / math.sqrt(2.0)))
    phi = np.exp(-0.5 * alpha * alpha) / math.sqrt(2.0 * math.pi)
    m2 = (mu * mu + s * s) * Phi + mu * s * phi
    m3 = (mu**3 + 3.0 * mu * s * s) * Phi + s * (mu * mu + 2.0 * s * s) * phi
    return m2, m3


def _plane_expectations(W: FloatArray, axes: FloatArray, sig: FloatArray
                        ) -> tuple[FloatArray, float, FloatArray]:
    """The same for a Gaussian over a plane (axes (3, 2), standard deviations ``sig``), in
    polar coordinates of the whitened variable: ``w = axes (sig * z)``, ``z`` standard normal
    about ``m = (axes^T W) / sig`` (at Mahalanobis distance ``d = |m|`` from the origin, where
    ``|w|`` has its kink), ``z = r (cos phi, sin phi)``, ``v(phi) = axes (sig * (cos phi, sin
    phi))``, ``|w| = r |v|``. The density is ``exp(-(r^2 - 2 b r + d^2) / 2) / (2 pi)``,
    ``b = m . (cos phi, sin phi)``; the radial integrals ``int r^k exp(...) dr`` (``k = 2``
    for ``E|w|`` and ``E[w w^T/|w|]``, ``3`` for ``E[|w| w]``) are truncated moments of
    ``N(b, 1)`` in closed form, and the remaining integrand is smooth and periodic in ``phi``:
    the trapezoidal rule converges exponentially. Its peak has width ``1 / d`` in ``phi``
    whatever the axis ratio (in the unwhitened angle it has ``sig_min / |W|``: a mean flow much
    larger than the fluctuation, a line in a current, is a needle), and beyond
    ``|phi - phi_m| = asin(10 / d)`` every ray passes 10 standard deviations from the mean
    (density below ``exp(-50)`` of the peak): for ``d > 10`` the rule covers that window
    only. Points: 8 per unit of ``width * max(d, ratio)`` (``ratio = sig_max / sig_min``: the
    scale on which ``v(phi)`` turns near the minor axis), at least 256."""
    m = (axes.T @ W) / sig  # the whitened mean
    d = float(np.hypot(m[0], m[1]))
    ratio = float(sig.max() / sig.min())
    if d > _WINDOW:
        half = math.asin(_WINDOW / d)
        width = 2.0 * half
        n = int(min(max(256, 8 * width * max(d, ratio)), 1 << 16))
        phi = math.atan2(m[1], m[0]) + half * ((2.0 * np.arange(n) + 1.0) / n - 1.0)
    else:
        width = 2.0 * math.pi
        n = int(min(max(256, 8 * width * max(d, ratio)), 1 << 16))
        phi = width * np.arange(n) / n
    c, s = np.cos(phi), np.sin(phi)
    b = m[0] * c + m[1] * s
    m2, m3 = _truncated_moments(b, np.ones_like(b))
    common = np.exp(-0.5 * (d * d - b * b)) / math.sqrt(2.0 * math.pi) * (width / n)
    v = np.outer(c * sig[0], axes[:, 0]) + np.outer(s * sig[1], axes[:, 1])  # (n, 3)
    rho = np.sqrt(np.sum(v * v, axis=1))
    return (((common * m3 * rho)[:, None] * v).sum(axis=0), float((common * m2 * rho).sum()),
            np.einsum("q,qi,qj->ij", common * m2 / rho, v, v))


def _hermite_expectations(W: FloatArray, axes: FloatArray, order: int
                          ) -> tuple[FloatArray, float, FloatArray]:
    """The same by tensor Gauss-Hermite quadrature over the scaled axes (3, m)."""
    nodes, weights = hermegauss(order)
    weights = weights / weights.sum()
    m = axes.shape[1]
    grid = np.stack(np.meshgrid(*([nodes] * m), indexing="ij"), -1).reshape(-1, m)
    wts = np.prod(np.stack(np.meshgrid(*([weights] * m), indexing="ij"), -1).reshape(-1, m),
                  axis=1)
    w = W[None] + grid @ axes.T
    norm = np.sqrt(np.sum(w * w, axis=1))
    inv = np.divide(1.0, norm, out=np.zeros_like(norm), where=norm > 0.0)
    return (wts @ (norm[:, None] * w), float(wts @ norm),
            np.einsum("q,qi,qj->ij", wts * inv, w, w))


__all__ = ["scalar_expectations", "vector_expectations"]
