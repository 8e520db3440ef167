"""LU factorization with partial pivoting of a small banded matrix, in plain Python.

For the few solves of a small system (a statics' Newton steps, a run's initial
accelerations, a condensed stiffness) where scipy's banded LAPACK would cost its import
(about 0.15 s) and numpy's dense LAPACK starts OpenBLAS's threads (which spin, and on a busy
2-core machine made one 171-unknown solve take 0.15 s of wall time). The algorithm is
LAPACK's unblocked ``gbtf2``/``gbtrs``: column by column, the pivot is the largest entry of
the column within the ``kl`` sub-diagonals, rows are swapped over the band (whose upper width
grows to ``kl + ku``), the multipliers are kept in place of the eliminated entries; a solve
applies the swaps and ``L`` in the same order, then back-substitutes with ``U``. The cost is
``n kl (kl + ku)`` multiply-adds: about a millisecond for the 171 unknowns of three OC3 lines
of 20 segments (``kl = ku = 5``).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from .rcm import reverse_cuthill_mckee

__all__ = ["MAX_SMALL", "BandLU", "bandwidths", "small_band_solver"]

FloatArray = NDArray[np.float64]

MAX_SMALL = 400
"""Most unknowns factored here (above, the banded LAPACK of scipy is cheaper than Python)."""

MAX_WIDTH = 60
"""Widest band ``kl + ku + 1`` factored here."""


def bandwidths(rows: NDArray[np.integer], cols: NDArray[np.integer]) -> tuple[int, int]:
    """``(kl, ku)``: the lower and upper bandwidths of the entries at ``rows``, ``cols``."""
    return int(np.max(rows - cols, initial=0)), int(np.max(cols - rows, initial=0))


class BandLU:
    """The factors of a square matrix (given dense, its entries outside ``kl`` sub- and
    ``ku`` super-diagonals zero).

    Raises
    ------
    numpy.linalg.LinAlgError
        When a pivot is exactly zero (the matrix is singular).
    """

    def __init__(self, matrix: FloatArray, kl: int, ku: int) -> None:
        a = np.asarray(matrix, dtype=float).tolist()
        n = len(a)
        piv = list(range(n))
        for k in range(n):
            lo, hi = min(n, k + kl + 1), min(n, k + kl + ku + 1)
            p, best = k, abs(a[k][k])
            for i in range(k + 1, lo):
                if abs(a[i][k]) > best:
                    p, best = i, abs(a[i][k])
            if best == 0.0:
                raise np.linalg.LinAlgError(f"singular matrix (zero pivot at {k})")
            piv[k] = p
            if p != k:
                a[k][k:hi], a[p][k:hi] = a[p][k:hi], a[k][k:hi]
            upper = a[k][k + 1:hi]
            pivot = a[k][k]
            for i in range(k + 1, lo):
                row = a[i]
                f = row[k] / pivot
                row[k] = f
                if f != 0.0:
                    for j, u in enumerate(upper, k + 1):
                        row[j] -= f * u
        self._a, self._piv, self._kl, self._ku = a, piv, kl, ku

    def solve(self, rhs: FloatArray) -> FloatArray:
        """``A^-1 rhs`` (``rhs`` (n,) or (n, m))."""
        rhs = np.asarray(rhs, dtype=float)
        columns = rhs.reshape(len(rhs), -1).T.tolist()
        out = np.array([self._solve(b) for b in columns]).T
        return out.reshape(rhs.shape)

    def _solve(self, b: list[float]) -> list[float]:
        a, piv, kl, ku = self._a, self._piv, self._kl, self._ku
        n = len(b)
        for k in range(n):
            p = piv[k]
            if p != k:
                b[k], b[p] = b[p], b[k]
            bk = b[k]
            if bk != 0.0:
                for i in range(k + 1, min(n, k + kl + 1)):
                    b[i] -= a[i][k] * bk
        for k in range(n - 1, -1, -1):
            row = a[k]
            s = b[k]
            for j in range(k + 1, min(n, k + kl + ku + 1)):
                s -= row[j] * b[j]
            b[k] = s / row[k]
        return b


def small_band_solver(matrix: FloatArray):
    """A solver ``rhs -> matrix^-1 rhs`` of a small dense ``matrix`` (fewer than
    :data:`MAX_SMALL` unknowns) that is narrow-banded once its unknowns are in reverse
    Cuthill-McKee order (:class:`BandLU` on the reordered matrix); ``None`` for a larger or a
    wider one.

    Raises
    ------
    numpy.linalg.LinAlgError
        When the matrix is singular.
    """
    n = len(matrix)
    if n >= MAX_SMALL:
        return None
    rows, cols = np.nonzero(matrix)
    rows, cols = np.concatenate((rows, np.arange(n))), np.concatenate((cols, np.arange(n)))
    key = np.unique(np.concatenate((rows * n + cols, cols * n + rows)))  # symmetric pattern
    indptr = np.concatenate(([0], np.cumsum(np.bincount(key // max(n, 1), minlength=n))))
    perm = reverse_cuthill_mckee(indptr, key % max(n, 1)).astype(np.int64)
    inverse = np.empty_like(perm)
    inverse[perm] = np.arange(n)
    kl, ku = bandwidths(inverse[rows], inverse[cols])
    if kl + ku + 1 > MAX_WIDTH:
        return None
    lu = BandLU(np.asarray(matrix)[np.ix_(perm, perm)], kl, ku)
    return lambda rhs: lu.solve(np.asarray(rhs)[perm])[inverse]
