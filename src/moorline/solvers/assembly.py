"""Sparse assembly through a precomputed index pattern.

The pattern maps every entry of every element block (6x6) and node block (3x3) that couples two
free degrees of freedom to its slot in a CSR matrix, once. Assembling is then a single
``np.bincount`` over the block values: no Python loop, no COO sorting per call.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]


class BlockPattern:
    """CSR pattern of element (6x6) and node (3x3) blocks over the dofs of ``dof_of_node``.

    Parameters
    ----------
    elements
        Node pairs (n_elements, 2).
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
        """Sum blocks into a CSR matrix.

        Parameters
        ----------
        element_blocks
            (n_elements, 6, 6) or ``None``.
        node_blocks
            (n_nodes, 3, 3) or ``None``.
        diagonal
            (n,) values added to the diagonal, or ``None``.
        """
        values = np.zeros(self._keep.size)
        if element_blocks is not None:
            values[: self._n_el_entries] = element_blocks.ravel()
        if node_blocks is not None:
            values[self._n_el_entries :] = node_blocks.ravel()
        data = np.bincount(self._slot, values[self._keep], minlength=self.nnz)
        if diagonal is not None:
            data[self._diag_slot] += diagonal
        return sp.csr_matrix((data, self.indices, self.indptr), shape=(self.n, self.n))


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
