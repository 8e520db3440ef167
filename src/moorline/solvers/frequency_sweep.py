"""``(K - omega^2 M + i omega C + E(omega)) U = F`` at many frequencies, banded and compiled.

The frequency-domain analyses solve one sparse complex system per frequency (thousands for a
3-hour sea), each of a few hundred unknowns, all with the same sparsity. Here the unknowns are
ordered once by reverse Cuthill-McKee on the union of the patterns (half bandwidth ``bw``:
5 for a line, a little more with bodies), the real matrices are stored in LAPACK's band
layout ``ab[i, j - i + bw]``, and one compiled loop (numba, cached on disk) forms the complex
band matrix at each frequency, factors it (band LU without pivoting:
:func:`moorline.solvers.fast_newmark._band_lu`, no fill outside the band) and solves: about
``n bw^2`` operations per frequency, against a dense generalized eigenproblem of twice the
size per linearization for Foss's modal sum over all modes.

``E(omega)`` are optional per-frequency terms at given positions (a body's radiation table:
``-omega^2 dA(omega) + i omega B(omega)`` on its 6x6 block).

Without pivoting the factorization is backward stable for diagonally dominant or definite
matrices; ``K - omega^2 M`` is indefinite above the first natural frequency, and damping
keeps ``A(omega)`` regular but not dominant. So every solution is checked: the residual
``|A U - F| / |F|`` is computed at every frequency (in the same loop), and the frequencies
where it exceeds :data:`RESIDUAL_TOL` (or the factorization met a zero pivot) are solved
again by the sparse LU with partial pivoting (:func:`moorline.solvers.assembly.
solve_sparse`); :attr:`FrequencySweep.refactored` counts them.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray
from scipy.sparse.csgraph import reverse_cuthill_mckee

from ..jit import numba
from .assembly import solve_sparse
from .fast_newmark import _JIT, _band_lu, _band_solve

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]
IntArray = NDArray[np.int64]

#: Relative residual ``|A U - F| / |F|`` above which a frequency is solved again with
#: pivoting (a stable factorization leaves about ``n eps |A| |U| / |F|``, 1e-13 here).
RESIDUAL_TOL = 1.0e-9


@numba.njit(**_JIT)
def _sweep(kb, mb, cb, omega, F, rank, bw, extra_i, extra_j, extra_v, out, residual):
    """Per frequency ``w``: ``ab = kb - w^2 mb + i w cb`` plus ``extra_v[w]`` at band
    positions ``(extra_i, extra_j)``, LU without pivoting, solve for ``F[:, w]`` (unknown
    ``i`` at band row ``rank[i]``) into ``out[:, w]``, and ``residual[w] = |ab x - b| /
    |b|`` with the unfactored ``ab`` (inf at a zero pivot)."""
    n, width = kb.shape
    ab = np.empty((n, width), dtype=np.complex128)
    a0 = np.empty((n, width), dtype=np.complex128)
    rhs = np.empty(n, dtype=np.complex128)
    x = np.empty(n, dtype=np.complex128)
    for f in range(omega.shape[0]):
        w = omega[f]
        for i in range(n):
            for j in range(width):
                a0[i, j] = complex(kb[i, j] - w * w * mb[i, j], w * cb[i, j])
        for e in range(extra_i.shape[0]):
            a0[extra_i[e], extra_j[e]] += extra_v[f, e]
        ab[:, :] = a0
        for i in range(n):
            rhs[rank[i]] = F[i, f]
        if not _band_lu(ab, bw):
            residual[f] = np.inf
            continue
        x[:] = rhs
        _band_solve(ab, bw, x)
        r2, b2 = 0.0, 0.0
        for i in range(n):
            s = -rhs[i]
            for j in range(max(0, i - bw), min(n, i + bw + 1)):
                s += a0[i, j - i + bw] * x[j]
            r2 += s.real * s.real + s.imag * s.imag
            b2 += rhs[i].real * rhs[i].real + rhs[i].imag * rhs[i].imag
        for i in range(n):
            out[i, f] = x[rank[i]]
        residual[f] = np.sqrt(r2 / b2) if b2 > 0.0 else (0.0 if r2 == 0.0 else np.inf)


def _band(matrix: sp.spmatrix, rank: IntArray, bw: int) -> FloatArray:
    """``matrix`` with rows and columns renumbered by ``rank``, in band storage."""
    coo = matrix.tocoo()
    i, j = rank[coo.row], rank[coo.col]
    out = np.zeros((matrix.shape[0], 2 * bw + 1))
    np.add.at(out, (i, j - i + bw), coo.data)
    return out


class FrequencySweep:
    """Solver of ``(K - omega^2 M + i omega C + E(omega)) U = F`` for fixed ``K`` and ``M``.

    Parameters
    ----------
    K, M
        Real sparse matrices (n, n) [N/m, kg].
    extra
        Positions ``(rows, cols)`` of the per-frequency terms (or ``None``).
    """

    def __init__(self, K: sp.spmatrix, M: sp.spmatrix,
                 extra: tuple[IntArray, IntArray] | None = None) -> None:
        self.K, self.M = sp.csr_matrix(K), sp.csr_matrix(M)
        self.extra = (np.zeros(0, np.int64), np.zeros(0, np.int64)) if extra is None \
            else (np.asarray(extra[0], np.int64), np.asarray(extra[1], np.int64))
        self.refactored = 0
        self._pattern: sp.csr_matrix | None = None

    def _order(self, C: sp.spmatrix) -> None:
        """Reverse Cuthill-McKee on the union of the patterns (again when ``C`` brings new
        entries)."""
        n = self.K.shape[0]
        rows, cols = self.extra
        E = sp.csr_matrix((np.ones(len(rows)), (rows, cols)), shape=(n, n))
        union = (abs(self.K) + abs(self.M) + abs(C) + E + sp.identity(n, format="csr"))
        union = (union + union.T).tocsr()
        union.data[:] = 1.0
        if self._pattern is not None and (union - self._pattern).max() <= 0:
            return
        self._pattern = union
        order = reverse_cuthill_mckee(union, symmetric_mode=True)
        self.rank = np.empty(n, dtype=np.int64)
        self.rank[order] = np.arange(n)
        coo = union.tocoo()
        self.bw = int(np.abs(self.rank[coo.row] - self.rank[coo.col]).max(initial=0))
        self.kb, self.mb = _band(self.K, self.rank, self.bw), _band(self.M, self.rank, self.bw)
        ri, rj = self.rank[rows], self.rank[cols]
        self.extra_band = (ri, rj - ri + self.bw)

    def solve(self, C: sp.spmatrix, F: ComplexArray, omega: FloatArray,
              extra_values: ComplexArray | None = None) -> ComplexArray:
        """``U`` (n_w, n) for the damping ``C`` (n, n) [N s/m], forces ``F`` (n_w, n) and
        the per-frequency terms ``extra_values`` (n_w, n_extra) at the positions given at
        construction. ``U`` is the transpose of a C-ordered (n, n_w) array, as ``F`` best
        is (no copy then)."""
        self._order(C)
        n_w, n = len(omega), self.K.shape[0]
        rank, bw = self.rank, self.bw
        cb = _band(C, rank, bw)
        values = (np.zeros((n_w, 0), dtype=complex) if extra_values is None
                  else np.ascontiguousarray(extra_values, dtype=complex))
        out = np.zeros((n, n_w), dtype=complex)  # frequency last, like the loads
        residual = np.empty(n_w)
        _sweep(self.kb, self.mb, cb, np.ascontiguousarray(omega, dtype=float),
               np.ascontiguousarray(np.asarray(F, dtype=complex).T), rank, bw,
               self.extra_band[0], self.extra_band[1], values, out, residual)
        U = out.T
        bad = ~(residual <= RESIDUAL_TOL)  # NaN too
        for f in np.flatnonzero(bad):
            U[f] = solve_sparse(self.matrix(C, omega[f], values[f]).tocsc(), F[f])
        self.refactored += int(bad.sum())
        return U

    def matrix(self, C: sp.spmatrix, w: float, extra_values: ComplexArray) -> sp.csr_matrix:
        """The system matrix at one frequency (sparse, original numbering)."""
        A = self.K - w * w * self.M + 1j * w * C
        rows, cols = self.extra
        if len(rows):
            A = A + sp.csr_matrix((extra_values, (rows, cols)), shape=A.shape)
        return sp.csr_matrix(A)


__all__ = ["RESIDUAL_TOL", "FrequencySweep"]
