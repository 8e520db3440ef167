"""Sparse assembly through a precomputed index pattern.

The pattern maps every entry of every element block (6x6) and node block (3x3) that couples two
free degrees of freedom to its slot in a CSR matrix, once. Assembling is then a single
``np.bincount`` over the block values: no Python loop, no COO sorting per call.

scipy is imported where a matrix object, a banded LAPACK factorization or SuperLU is used
(about 0.15 s at a process' first use): the stored entries (:meth:`BlockPattern.values`),
the ordering (:mod:`moorline.solvers.rcm`) and the factorization of a small system solved a
few times (:meth:`SparseFactor.for_few_solves`, :mod:`moorline.solvers.band_lu`) do without
it.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from .band_lu import MAX_SMALL, BandLU
from .rcm import reverse_cuthill_mckee

if TYPE_CHECKING:
    import scipy.sparse as sp

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]


class BlockPattern:
    """CSR pattern of element (6x6) and node (3x3) blocks over the dofs of ``dof_of_node``.

    Parameters
    ----------
    elements
        Node pairs (n_elements, 2): a mesh's elements, or its
        :attr:`~moorline.mesh.Mesh.pattern_pairs` (elements, then the outer node pairs of its
        bending triplets).
    dof_of_node
        Dof numbers (n_nodes, 3); -1 marks a degree of freedom left out.
    """

    def __init__(self, elements: IntArray, dof_of_node: IntArray) -> None:
        self.n = int(dof_of_node.max(initial=-1)) + 1
        el_dofs = dof_of_node[elements].reshape(len(elements), 6)
        node_dofs = dof_of_node
        el_rows, el_cols = np.repeat(el_dofs, 6, axis=1), np.tile(el_dofs, (1, 6))
        nd_rows, nd_cols = np.repeat(node_dofs, 3, axis=1), np.tile(node_dofs, (1, 3))
        rows = np.concatenate((el_rows.ravel(), nd_rows.ravel()))
        cols = np.concatenate((el_cols.ravel(), nd_cols.ravel()))
        self._keep = (rows >= 0) & (cols >= 0)
        key = rows[self._keep] * max(self.n, 1) + cols[self._keep]
        unique, self._slot = np.unique(key, return_inverse=True)
        self.indices = (unique % max(self.n, 1)).astype(np.int32)
        counts = np.bincount(unique // max(self.n, 1), minlength=self.n)
        self.indptr = np.concatenate(([0], np.cumsum(counts))).astype(np.int32)
        self._n_el_entries = el_rows.size
        self._diag_slot = self._find_diagonal()

    def _find_diagonal(self) -> IntArray:
        slots = np.empty(self.n, dtype=np.int64)
        for_row = np.repeat(np.arange(self.n), np.diff(self.indptr))
        is_diag = for_row == self.indices
        slots[for_row[is_diag]] = np.flatnonzero(is_diag)
        return slots

    @property
    def nnz(self) -> int:
        """Number of stored entries."""
        return len(self.indices)

    def assemble(
        self,
        element_blocks: FloatArray | None = None,
        node_blocks: FloatArray | None = None,
        diagonal: FloatArray | None = None,
    ) -> sp.csr_matrix:
        """Sum blocks into a CSR matrix (see :meth:`values` for the arguments)."""
        return self.csr(self.values(element_blocks, node_blocks, diagonal))

    def diagonal(self, data: FloatArray) -> FloatArray:
        """The diagonal (n,) of the matrix of stored entries ``data`` (every node block, so
        the whole diagonal, is in the pattern)."""
        return data[self._diag_slot]

    def dense(self, data: FloatArray) -> FloatArray:
        """The matrix of stored entries ``data`` (storage order) as a numpy array."""
        matrix = np.zeros((self.n, self.n))
        matrix[self.rows, self.indices] = data
        return matrix

    def csr(self, data: FloatArray) -> sp.csr_matrix:
        """The CSR matrix of stored entries ``data`` (storage order)."""
        import scipy.sparse as sp

        return sp.csr_matrix((data, self.indices, self.indptr), shape=(self.n, self.n))

    def values(
        self,
        element_blocks: FloatArray | None = None,
        node_blocks: FloatArray | None = None,
        diagonal: FloatArray | None = None,
    ) -> FloatArray:
        """Sum blocks into a CSR matrix.

        Parameters
        ----------
        element_blocks
            (n_elements, 6, 6) or ``None``; fewer blocks than the pattern's pairs are the
            first pairs' (the elements of :attr:`moorline.mesh.Mesh.pattern_pairs`, without
            the bending pairs after them).
        node_blocks
            (n_nodes, 3, 3) or ``None``.
        diagonal
            (n,) values added to the diagonal, or ``None``.
        """
        values = np.zeros(self._keep.size)
        if element_blocks is not None:  # fewer blocks than pairs: the first pairs'
            values[: element_blocks.size] = element_blocks.ravel()
        if node_blocks is not None:
            values[self._n_el_entries :] = node_blocks.ravel()
        data = np.bincount(self._slot, values[self._keep], minlength=self.nnz)
        if diagonal is not None:
            data[self._diag_slot] += diagonal
        return data

    @property
    def rows(self) -> NDArray[np.int32]:
        """Row of every stored entry, in storage order."""
        return np.repeat(np.arange(self.n, dtype=np.int32), np.diff(self.indptr))


class SparseFactor:
    """Factorizations of matrices with a fixed :class:`BlockPattern`.

    The unknowns are reordered once by reverse Cuthill-McKee. When the reordered matrix is
    narrow-banded (cables: nodes along lines), LAPACK's banded LU (``dgbtrf``/``dgbtrs``) is
    used, filled through a precomputed map from storage slots to band positions: cost linear
    in the number of unknowns and a few microseconds of Python per call. Otherwise SuperLU.
    With ``small_below``, a narrow-banded system of fewer unknowns is factored by
    :class:`moorline.solvers.band_lu.BandLU` instead (the same algorithm in Python, a
    millisecond at 171 unknowns, no scipy): for a few solves, such as a statics' Newton
    steps (:meth:`for_few_solves`); a time loop keeps LAPACK.
    """

    def __init__(self, pattern: BlockPattern, max_band: int = 120,
                 small_below: int = 0) -> None:
        self.pattern = pattern
        n = pattern.n
        perm = reverse_cuthill_mckee(pattern.indptr, pattern.indices).astype(np.int64)
        inverse = np.empty_like(perm)
        inverse[perm] = np.arange(n)
        rows, cols = inverse[pattern.rows], inverse[pattern.indices]
        self.kl = int(np.max(rows - cols, initial=0))
        self.ku = int(np.max(cols - rows, initial=0))
        self.banded = n > 0 and self.kl + self.ku + 1 <= max_band
        self.small = self.banded and n < small_below
        self.perm, self.inverse = perm, inverse
        self.shape = (2 * self.kl + self.ku + 1, n)
        self.band_slot = (self.kl + self.ku + rows - cols) * n + cols
        self._permuted = (rows, cols)
        self._lu = None

    @classmethod
    def for_few_solves(cls, pattern: BlockPattern) -> SparseFactor:
        """The factorization of a pattern factored a few times only (a statics' Newton
        steps): in Python below :data:`~moorline.solvers.band_lu.MAX_SMALL` unknowns."""
        return cls(pattern, small_below=MAX_SMALL)

    def factor(self, data: FloatArray) -> SparseFactor:
        """Factorize the matrix with entries ``data`` (storage order of the pattern).

        Raises
        ------
        numpy.linalg.LinAlgError
            When a pivot is exactly zero.
        """
        p = self.pattern
        if self.small:
            matrix = np.zeros((p.n, p.n))
            matrix[self._permuted] = data
            self._lu = BandLU(matrix, self.kl, self.ku)
        elif self.banded:
            from scipy.linalg.lapack import dgbtrf

            ab = np.zeros(self.shape[0] * self.shape[1])
            ab[self.band_slot] = data
            lu, piv, info = dgbtrf(ab.reshape(self.shape), self.kl, self.ku, overwrite_ab=1)
            if info > 0:
                raise np.linalg.LinAlgError(f"singular matrix (zero pivot at {info - 1})")
            self._lu = (lu, piv)
        else:
            self._lu = MatrixFactor(p.csr(data))
        return self

    def solve(self, rhs: FloatArray) -> FloatArray:
        """Solve with the last factorization."""
        if self.small:
            return self._lu.solve(rhs[self.perm])[self.inverse]
        if not self.banded:
            return self._lu.solve(rhs)
        from scipy.linalg.lapack import dgbtrs

        lu, piv = self._lu
        y, info = dgbtrs(lu, self.kl, self.ku, rhs[self.perm], piv)
        return y[self.inverse]


class MatrixFactor:
    """LU factorization of a general sparse matrix (SuperLU), for systems whose pattern is
    not a :class:`BlockPattern` (bodies coupled through the master-slave transformation,
    harmonic balance, condensation)."""

    def __init__(self, matrix: sp.spmatrix) -> None:
        import scipy.sparse as sp
        import scipy.sparse.linalg as spla  # imported on use (with scipy.linalg: 0.15 s)

        self.shape = matrix.shape
        try:
            self._lu = spla.splu(sp.csc_matrix(matrix))
        except RuntimeError as exc:  # SuperLU: "Factor is exactly singular"
            raise np.linalg.LinAlgError(f"singular matrix ({exc})") from None

    def solve(self, rhs: FloatArray) -> FloatArray:
        """Solve ``A x = rhs`` (``rhs`` a vector or a matrix of columns; real or complex)."""
        return self._lu.solve(np.asarray(rhs))


def factorize(matrix: sp.spmatrix) -> MatrixFactor:
    """Factorize a sparse matrix once, to solve with it many times."""
    return MatrixFactor(matrix)


def solve_sparse(matrix: sp.spmatrix, rhs: FloatArray) -> FloatArray:
    """Solve one sparse system."""
    return factorize(matrix).solve(rhs)


def gather_free(values: FloatArray, dof_of_node: IntArray) -> FloatArray:
    """Nodal vectors (n_nodes, 3) to a dof vector (n_dofs,), dropping left-out dofs."""
    mask = dof_of_node >= 0
    out = np.empty(int(dof_of_node.max(initial=-1)) + 1)
    out[dof_of_node[mask]] = values[mask]
    return out


def scatter_free(dof_values: FloatArray, dof_of_node: IntArray) -> FloatArray:
    """A dof vector back to nodal vectors (n_nodes, 3), zero at left-out dofs."""
    out = np.zeros(dof_of_node.shape)
    mask = dof_of_node >= 0
    out[mask] = dof_values[dof_of_node[mask]]
    return out
