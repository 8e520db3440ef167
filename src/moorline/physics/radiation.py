"""Radiation forces of a floating body in the time domain: the Cummins (1962) equation.

A body with frequency-dependent added mass ``A(w)`` and damping ``B(w)`` (a hydrodynamic
database) moves in the time domain under Cummins' (1962) equation

    (M + A_inf) x'' + int_0^t K(t - s) x'(s) ds + C x = F(t),

with the retardation (memory) kernels ``K_ij(t) = 2/pi int_0^inf B_ij(w) cos(w t) dw`` and,
from Ogilvie's (1964) relation, ``A(w) = A_inf - 1/w int_0^inf K(t) sin(w t) dt``. In the
frequency domain the kernel's transform is ``K^(w) = int_0^inf K(t) e^{-i w t} dt = B(w) +
i w (A(w) - A_inf)``.

This module holds pure, vectorized kernels over a table ``(omegas, A (n, ...), B (n, ...))``:

* :func:`damping_model`: ``B(w)`` everywhere: linear interpolation of the table, from
  ``B(0) = 0`` (radiation damping vanishes at zero frequency) up to the first frequency, and
  beyond the last frequency ``w_N`` the tail ``B(w) = B(w_N) (w_N / w)^3``;
* :func:`retardation_kernel`: ``K(t)``, the cosine transform of that ``B(w)`` integrated
  exactly (Filon's idea: the piecewise-linear integrand times ``cos`` in closed form; the
  cubic tail by the cosine integral ``Ci``), no truncation in frequency;
* :func:`added_mass_offset`: ``A(w) - A_inf`` from Ogilvie's relation with ``K`` the cosine
  transform of ``B``, i.e. the Kramers-Kronig relation ``A(w) - A_inf = 2/pi int_0^inf
  (B(v) - B(w)) / (v^2 - w^2) dv`` (``PV int_0^inf dv / (v^2 - w^2) = 0`` removes the
  singularity; Gauss-Legendre on every table interval and on the tail mapped to ``(0, 1]``),
  which needs no truncation of ``K`` in time;
* :func:`infinite_frequency_added_mass`: ``A_inf`` as the least-squares constant over the
  table, ``mean_k (A(w_k) - (A(w_k) - A_inf)_Ogilvie)``;
* :func:`fit_memory`: a state-space (sum of complex exponentials) model of every kernel,
  ``K_ij(t) = Re sum_m c_m e^{p_m t}``, fitted to ``K^(w) = B(w) + i w (A(w) - A_inf)`` in the
  frequency domain (as recommended by Perez and Fossen 2008) by vector fitting
  (Gustavsen and Semlyen 1999): strictly proper (``K^ -> 0`` as ``w -> inf``), stable poles
  (unstable ones reflected), order raised until the fit is within a tolerance over the table;
* :class:`MemoryModel`: the memory force ``mu(t) = int_0^t K(t - s) v(s) ds`` as states
  ``z_m' = p_m z_m + v_j`` (``mu_i = sum Re(c_m z_m)``), advanced exactly over a step for a
  velocity linear in time (first-order hold), with ``d mu(t + h) / d v(t + h)``.

Sources: Cummins, W. E. (1962) "The impulse response function and ship motions", Schiffstechnik
9, 101-109. Ogilvie, T. F. (1964) "Recent progress toward the understanding and prediction of
ship motions", 5th Symp. Naval Hydrodynamics, 3-128. Gustavsen, B. and Semlyen, A. (1999)
"Rational approximation of frequency domain responses by vector fitting", IEEE Trans. Power
Delivery 14(3), 1052-1061. Perez, T. and Fossen, T. I. (2008) "Time- vs. frequency-domain
identification of parametric radiation force models for marine structures at zero speed",
Modeling, Identification and Control 29(1), 1-19.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]

_GAUSS = np.polynomial.legendre.leggauss(8)


# ---------------------------------------------------------------------- damping and kernel
def _nodes(omegas: ArrayLike, damping: ArrayLike) -> tuple[FloatArray, FloatArray]:
    """The table with the node ``(0, 0)`` in front (``B(0) = 0``), damping as (n + 1, m)."""
    w = np.asarray(omegas, dtype=float)
    B = np.asarray(damping, dtype=float).reshape(len(w), -1)
    if w[0] > 0:
        w, B = np.concatenate(([0.0], w)), np.vstack((np.zeros((1, B.shape[1])), B))
    return w, B


def damping_model(omegas: ArrayLike, damping: ArrayLike, w: ArrayLike) -> FloatArray:
    """``B(w)`` (len(w), ...) of the table (``damping`` (n, ...)): linear from ``B(0) = 0``,
    linear between the table's frequencies, ``B(w_N) (w_N / w)^3`` beyond the last one."""
    shape = np.shape(damping)[1:]
    nodes, B = _nodes(omegas, damping)
    w = np.atleast_1d(np.asarray(w, dtype=float))
    inside = np.column_stack([np.interp(w, nodes, B[:, k]) for k in range(B.shape[1])])
    tail = B[-1] * (nodes[-1] / np.maximum(w, nodes[-1]))[:, None] ** 3
    return np.where((w > nodes[-1])[:, None], tail, inside).reshape((len(w),) + shape)


def _sinc(x: FloatArray) -> FloatArray:
    """``sin(x) / x``."""
    return np.sinc(x / np.pi)


def kernel_weights(omegas: ArrayLike, t: ArrayLike) -> FloatArray:
    """Weights ``W`` (len(t), n + 1) with ``K(t) = W @ [0, B_1, ..., B_n]``: the exact cosine
    transform ``2/pi int_0^inf B(w) cos(w t) dw`` of :func:`damping_model`'s ``B``.

    On an interval ``[w_k, w_k+1]`` with ``B = B_k + s (w - w_k)``,
    ``int B cos(w t) dw = [B(w) w sinc(w t)] - s dw wbar sinc(wbar t) sinc(dw t / 2)``
    (``sinc(x) = sin x / x``, finite at ``t = 0``); the tail
    ``B_N w_N^3 int_{w_N}^inf cos(w t) / w^3 dw = B_N w_N (cos x - x sin x + x^2 Ci(x)) / 2``
    with ``x = w_N t``.
    """
    nodes = _nodes(omegas, np.zeros(len(np.atleast_1d(omegas))))[0]
    t = np.atleast_1d(np.asarray(t, dtype=float))[:, None]
    lo, hi = nodes[:-1], nodes[1:]
    dw, mid = hi - lo, 0.5 * (lo + hi)
    # d(interval integral)/dB_k (left node) and /dB_k+1 (right node)
    edge_lo = -lo * _sinc(lo * t)
    edge_hi = hi * _sinc(hi * t)
    slope = mid * _sinc(mid * t) * _sinc(0.5 * dw * t)  # times (B_k+1 - B_k)
    W = np.zeros((t.shape[0], len(nodes)))
    W[:, :-1] += edge_lo + slope
    W[:, 1:] += edge_hi - slope
    from scipy.special import sici  # imported on use (scipy.special: 0.1 s)

    x = nodes[-1] * t[:, 0]
    ci = sici(np.where(x > 0, x, 1.0))[1]
    W[:, -1] += 0.5 * nodes[-1] * (np.cos(x) - x * np.sin(x) + np.where(x > 0, x * x * ci, 0))
    return 2.0 / np.pi * W


def retardation_kernel(omegas: ArrayLike, damping: ArrayLike, t: ArrayLike) -> FloatArray:
    """Retardation kernels ``K(t) = 2/pi int_0^inf B(w) cos(w t) dw`` (len(t), ...) of a
    damping table (``damping`` (n, ...) over ``omegas``), :func:`damping_model`'s ``B``
    transformed exactly (:func:`kernel_weights`)."""
    shape = np.shape(damping)[1:]
    _, B = _nodes(omegas, damping)
    return (kernel_weights(omegas, t) @ B).reshape((-1,) + shape)


# ---------------------------------------------------------------------- added mass
def added_mass_offset(omegas: ArrayLike, damping: ArrayLike, w: ArrayLike) -> FloatArray:
    """``A(w) - A_inf`` (len(w), ...) from Ogilvie's relation with the kernel of
    :func:`retardation_kernel`: ``2/pi int_0^inf (B(v) - B(w)) / (v^2 - w^2) dv``.

    Eight-point Gauss-Legendre on every interval of the table (split at ``w``), and on the
    tail ``v = w_N / u``, ``u`` in (0, 1] (split where ``v = w``); the integrand is regular
    (the linear ``B`` makes it ``s / (v + w)`` on the interval holding ``w``).
    """
    shape = np.shape(damping)[1:]
    nodes, B = _nodes(omegas, damping)
    x, g = _GAUSS
    out = []
    for wk in np.atleast_1d(np.asarray(w, dtype=float)):
        Bw = damping_model(omegas, damping, [wk]).reshape(1, -1)
        grid = np.union1d(nodes, [wk]) if wk < nodes[-1] else nodes
        lo, hi = grid[:-1], grid[1:]
        v = (0.5 * (hi - lo)[:, None] * x + 0.5 * (hi + lo)[:, None]).ravel()
        weight = (0.5 * (hi - lo)[:, None] * g).ravel()
        Bv = np.column_stack([np.interp(v, nodes, B[:, k]) for k in range(B.shape[1])])
        total = (weight / (v * v - wk * wk))[:, None] * (Bv - Bw)
        # tail: int_0^1 w_N (B_N u^3 - B(w)) / (w_N^2 - w^2 u^2) du
        cuts = [0.0, 1.0] if wk <= nodes[-1] else [0.0, nodes[-1] / wk, 1.0]
        pieces = list(zip(cuts[:-1], cuts[1:], strict=True))
        u = np.concatenate([0.5 * (b - a) * x + 0.5 * (a + b) for a, b in pieces])
        gu = np.concatenate([0.5 * (b - a) * g for a, b in pieces])
        wn = nodes[-1]
        tail = (gu * wn / (wn * wn - wk * wk * u * u))[:, None] * (B[-1] * u[:, None] ** 3
                                                                   - Bw)
        out.append(2.0 / np.pi * (total.sum(axis=0) + tail.sum(axis=0)))
    return np.array(out).reshape((-1,) + shape)


def infinite_frequency_added_mass(omegas: ArrayLike, added_mass: ArrayLike,
                                  damping: ArrayLike) -> FloatArray:
    """``A_inf`` (...) from Ogilvie's relation: the least-squares constant over the table,
    ``mean_k (A(w_k) - (A(w_k) - A_inf))`` with :func:`added_mass_offset`."""
    A = np.asarray(added_mass, dtype=float)
    return np.mean(A - added_mass_offset(omegas, damping, omegas), axis=0)


# ---------------------------------------------------------------------- vector fitting
def _basis(s: ComplexArray, poles: ComplexArray) -> ComplexArray:
    """Real-coefficient partial fractions (len(s), n_real + 2 n_pairs): ``1 / (s - p)`` for a
    real pole, ``1/(s-p) + 1/(s-p*)`` and ``i/(s-p) - i/(s-p*)`` for a pair (``Im p > 0``)."""
    cols = []
    for p in poles:
        a, b = 1.0 / (s - p), 1.0 / (s - np.conj(p))
        cols += [a] if p.imag == 0 else [a + b, 1j * a - 1j * b]
    return np.column_stack(cols)


def _realize(poles: ComplexArray) -> tuple[FloatArray, FloatArray]:
    """Real block-diagonal ``A`` and input ``b`` of :func:`_basis`'s partial fractions."""
    n = sum(1 if p.imag == 0 else 2 for p in poles)
    A, b = np.zeros((n, n)), np.zeros(n)
    k = 0
    for p in poles:
        if p.imag == 0:
            A[k, k], b[k] = p.real, 1.0
            k += 1
        else:
            A[k:k + 2, k:k + 2] = [[p.real, p.imag], [-p.imag, p.real]]
            b[k] = 2.0
            k += 2
    return A, b


def _clean(roots: ComplexArray) -> ComplexArray:
    """Stable poles (unstable ones reflected), one of every conjugate pair."""
    roots = np.where(roots.real > 0, -np.conj(roots), roots)
    roots = np.where(roots.real == 0, roots - 1e-9 * (1 + abs(roots)), roots)
    real = np.abs(roots.imag) <= 1e-9 * np.abs(roots)
    out = list(roots[real].real.astype(complex))
    out += list(roots[~real & (roots.imag > 0)])
    return np.array(out, dtype=complex)


def _lstsq(M: ComplexArray, f: ComplexArray, weight: FloatArray) -> FloatArray:
    """Real least squares of ``M c = f`` over real and imaginary parts, rows weighted."""
    Mw, fw = M * weight[:, None], f * weight
    A = np.vstack((Mw.real, Mw.imag))
    scale = np.maximum(np.linalg.norm(A, axis=0), 1e-300)
    c = np.linalg.lstsq(A / scale, np.concatenate((fw.real, fw.imag)), rcond=None)[0]
    return c / scale


def vector_fit(omegas: ArrayLike, response: ArrayLike, n_pairs: int,
               weight: ArrayLike | None = None, iterations: int = 12
               ) -> tuple[ComplexArray, ComplexArray]:
    """Strictly proper rational fit ``f(i w) ~ sum_m r_m / (i w - p_m) + conj`` of one
    response (Gustavsen and Semlyen 1999): ``n_pairs`` complex starting poles
    ``-b/100 + i b``, ``b`` log-spaced over ``omegas``, relocated ``iterations`` times as the
    zeros of the weighting function ``sigma`` (unstable ones reflected), then the residues by
    linear least squares.

    Returns the poles ``p`` (real, or one of each conjugate pair) and the coefficients ``c``
    of the modes: ``K(t) = Re sum_m c_m e^{p_m t}`` (``c = 2 r`` for a pair).
    """
    w = np.asarray(omegas, dtype=float)
    f = np.asarray(response, dtype=complex)
    weight = np.ones(len(w)) if weight is None else np.asarray(weight, dtype=float)
    s = 1j * w
    beta = np.geomspace(max(w.min(), 1e-3 * w.max()), w.max(), n_pairs)
    poles = -beta / 100.0 + 1j * beta
    for _ in range(iterations):
        Phi = _basis(s, poles)
        c = _lstsq(np.hstack((Phi, -f[:, None] * Phi)), f, weight)
        A, b = _realize(poles)
        sigma = c[Phi.shape[1]:]
        poles = _clean(np.linalg.eigvals(A - np.outer(b, sigma)))
    Phi = _basis(s, poles)
    c = _lstsq(Phi, f, weight)
    coefficients, k = [], 0
    for p in poles:
        if p.imag == 0:
            coefficients.append(complex(c[k]))
            k += 1
        else:
            coefficients.append(2.0 * complex(c[k], c[k + 1]))
            k += 2
    return poles, np.array(coefficients, dtype=complex)


# ---------------------------------------------------------------------- memory model
@dataclass(frozen=True)
class MemoryModel:
    """Radiation memory of one body as a sum of complex exponentials:
    ``K_ij(t) = Re sum_{m: row_m = i, col_m = j} c_m e^{p_m t}``.

    Attributes
    ----------
    row, col
        The kernel entry ``(i, j)`` of every mode (the force dof and the velocity dof).
    poles, coefficients
        ``p_m`` (``Re p < 0``) and ``c_m`` (complex) of every mode.
    added_mass_infinite
        ``A_inf`` (6, 6).
    error
        Largest fit error of every entry over the table (6, 6), relative to
        ``sqrt(D_i D_j)``, ``D_i`` the largest ``|K^_kk|`` of the translations or the
        rotations as dof ``i`` (an entry of negligible size has a negligible error).
    """

    row: NDArray[np.int64]
    col: NDArray[np.int64]
    poles: ComplexArray
    coefficients: ComplexArray
    added_mass_infinite: FloatArray
    error: FloatArray

    @property
    def n_states(self) -> int:
        """Number of memory states."""
        return len(self.poles)

    def kernel(self, t: ArrayLike) -> FloatArray:
        """The fitted ``K(t)`` (len(t), 6, 6)."""
        t = np.atleast_1d(np.asarray(t, dtype=float))
        terms = (self.coefficients * np.exp(np.outer(t, self.poles))).real
        out = np.zeros((len(t), 36))
        np.add.at(out.T, 6 * self.row + self.col, terms.T)
        return out.reshape(-1, 6, 6)

    def transfer(self, omegas: ArrayLike) -> ComplexArray:
        """The fitted ``K^(w) = int_0^inf K(t) e^{-i w t} dt`` (len(w), 6, 6)."""
        s = 1j * np.atleast_1d(np.asarray(omegas, dtype=float))[:, None]
        p, c = self.poles, self.coefficients
        # Re(c e^{p t}) = (c e^{p t} + c* e^{p* t}) / 2
        terms = 0.5 * (c / (s - p) + np.conj(c) / (s - np.conj(p)))
        out = np.zeros((s.shape[0], 36), dtype=complex)
        np.add.at(out.T, 6 * self.row + self.col, terms.T)
        return out.reshape(-1, 6, 6)

    def step_weights(self, h: float) -> tuple[ComplexArray, ComplexArray, ComplexArray]:
        """``(e^{p h}, h phi_1(p h), h phi_2(p h))`` per mode: over a step ``h`` with the
        velocity linear from ``v0`` to ``v1``, ``z1 = e^{p h} z0 + h phi_1 v0 + h phi_2
        (v1 - v0)``, ``phi_1(x) = (e^x - 1) / x``, ``phi_2(x) = (e^x - 1 - x) / x^2``
        (exact)."""
        x = self.poles * h
        small = np.abs(x) < 1e-3
        xs = np.where(small, 1.0, x)
        e = np.exp(x)
        phi1 = np.where(small, 1 + x / 2 + x * x / 6, (e - 1) / xs)
        phi2 = np.where(small, 0.5 + x / 6 + x * x / 24, (e - 1 - xs) / xs**2)
        return e, h * phi1, h * phi2

    def advance(self, z0: ComplexArray | None, v0: ArrayLike, v1: ArrayLike,
                h: float) -> ComplexArray:
        """The states after a step ``h`` with the body velocity (6,) going linearly from
        ``v0`` to ``v1`` (``z0`` None: at rest, zero)."""
        e, a, b = self.step_weights(h)
        v0, v1 = np.asarray(v0, dtype=float)[self.col], np.asarray(v1, dtype=float)[self.col]
        z0 = np.zeros(self.n_states, dtype=complex) if z0 is None else z0
        return e * z0 + a * v0 + b * (v1 - v0)

    def force(self, z: ComplexArray | None) -> FloatArray:
        """The memory force ``mu`` (6,) of the states (the body feels ``-mu``)."""
        if z is None:
            return np.zeros(6)
        return np.bincount(self.row, (self.coefficients * z).real, minlength=6)

    def velocity_derivative(self, h: float) -> FloatArray:
        """``d mu(t + h) / d v(t + h)`` (6, 6) of :meth:`advance` then :meth:`force`."""
        b = self.step_weights(h)[2]
        out = np.zeros(36)
        np.add.at(out, 6 * self.row + self.col, (self.coefficients * b).real)
        return out.reshape(6, 6)


def _fit_frequencies(omegas: FloatArray) -> tuple[FloatArray, FloatArray]:
    """The table's frequencies and a few beyond it on each side (the model's ``B``, Ogilvie's
    ``A``), with their weights (1 on the table, 0.3 outside)."""
    below = omegas[0] * np.array([0.25, 0.5, 0.75])
    above = omegas[-1] * np.array([1.25, 1.5, 2.0, 3.0, 5.0])
    w = np.concatenate((below, omegas, above))
    weight = np.concatenate((np.full(3, 0.3), np.ones(len(omegas)), np.full(5, 0.3)))
    return w, weight


def fit_memory(omegas: ArrayLike, added_mass: ArrayLike, damping: ArrayLike,
               added_mass_infinite: ArrayLike | None = None, tolerance: float = 2e-3,
               max_pairs: int = 12) -> MemoryModel:
    """The :class:`MemoryModel` of a 6-dof table: ``A_inf`` (given, or
    :func:`infinite_frequency_added_mass`), then every entry with content (``max |K^_ij| >
    1e-9 sqrt(D_i D_j)``, ``D_i`` the largest ``max |K^_kk|`` of the translations or the
    rotations, as ``i``) fitted by :func:`vector_fit` with 1, 2, ... up to
    ``max_pairs`` pole pairs until the error over the table, relative to the entry's largest
    ``|K^|``, is at most ``tolerance`` (else the best fit is kept; :attr:`MemoryModel.error`
    says). The fitted data: ``K^ = B + i w (A - A_inf)`` on the table's frequencies, and on
    a few frequencies beyond either end (:func:`damping_model`'s ``B``, Ogilvie's ``A``) with
    a lower weight, which keeps the fit tame outside the table.
    """
    w = np.asarray(omegas, dtype=float)
    A = np.asarray(added_mass, dtype=float).reshape(len(w), 6, 6)
    B = np.asarray(damping, dtype=float).reshape(len(w), 6, 6)
    A_inf = (infinite_frequency_added_mass(w, A, B) if added_mass_infinite is None
             else np.asarray(added_mass_infinite, dtype=float).reshape(6, 6))
    wf, weight = _fit_frequencies(w)
    outside = np.concatenate((wf[:3], wf[-5:]))
    Af_out = A_inf + added_mass_offset(w, B, outside)
    Af = np.concatenate((Af_out[:3], A, Af_out[3:]))
    Bf = damping_model(w, B, wf)
    Kf = Bf + 1j * wf[:, None, None] * (Af - A_inf)
    table = slice(3, 3 + len(w))
    scale = np.abs(Kf).max(axis=0)
    # an entry is empty below 1e-9 of the largest diagonal of its dofs' kinds (translations,
    # rotations): numerical noise of a BEM code, e.g. the yaw of an axisymmetric hull
    diag = np.diag(scale)
    diag = np.concatenate((np.full(3, diag[:3].max()), np.full(3, diag[3:].max())))
    rows, cols, poles, coefs = [], [], [], []
    error = np.zeros((6, 6))
    for i in range(6):
        for j in range(6):
            if scale[i, j] <= 1e-9 * np.sqrt(diag[i] * diag[j]) or scale[i, j] == 0:
                continue
            best = None
            for n in range(1, max_pairs + 1):
                p, c = vector_fit(wf, Kf[:, i, j], n, weight / scale[i, j])
                fit = _modal_transfer(p, c, wf[table])
                err = float(np.abs(fit - Kf[table, i, j]).max() / scale[i, j])
                if best is None or err < best[0]:
                    best = (err, p, c)
                if err <= tolerance:
                    break
            err, p, c = best
            error[i, j] = err * scale[i, j] / np.sqrt(diag[i] * diag[j])
            rows += [i] * len(p)
            cols += [j] * len(p)
            poles.append(p)
            coefs.append(c)
    return MemoryModel(np.array(rows, dtype=np.int64), np.array(cols, dtype=np.int64),
                       _joined(poles), _joined(coefs), A_inf, error)


def _joined(parts: list) -> ComplexArray:
    return np.concatenate(parts).astype(complex) if parts else np.zeros(0, complex)


def _modal_transfer(poles: ComplexArray, coefficients: ComplexArray,
                    omegas: FloatArray) -> ComplexArray:
    """``int_0^inf Re(sum c e^{p t}) e^{-i w t} dt`` of one entry's modes."""
    s = 1j * omegas[:, None]
    c = coefficients
    return (0.5 * (c / (s - poles) + np.conj(c) / (s - np.conj(poles)))).sum(axis=1)
