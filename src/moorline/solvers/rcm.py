"""Reverse Cuthill-McKee ordering of a symmetric sparsity pattern, without scipy.

The same ordering as ``scipy.sparse.csgraph.reverse_cuthill_mckee(graph,
symmetric_mode=True)`` (Cuthill and McKee 1969; scipy's variant): the components are
started from a node of least degree (ties in the order of numpy's ``argsort`` of the
degrees, as scipy sorts them), each level's new nodes taken in the order the pattern lists
them and then stably sorted by degree, the whole order reversed. The degree of a node is its
number of stored entries, plus one when the diagonal is stored. Being the same ordering, the
band factorizations built on it (:mod:`moorline.solvers.assembly`,
:func:`moorline.solvers.fast_newmark.band_ordering`) give the same numbers as with scipy's;
importing ``scipy.sparse.csgraph`` costs about 0.1 s of a process that needs nothing else
from scipy (``moorline run`` of a case the compiled time loop takes).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

__all__ = ["edge_pattern", "reverse_cuthill_mckee"]

IntArray = NDArray[np.int64]


def reverse_cuthill_mckee(indptr: NDArray[np.integer], indices: NDArray[np.integer]
                          ) -> NDArray[np.int32]:
    """The ordering (a permutation of the ``len(indptr) - 1`` nodes) of the symmetric pattern
    in CSR form (``indptr``, ``indices``; each row's column indices sorted and unique, as
    scipy's canonical format holds them)."""
    n = len(indptr) - 1
    ptr, ind = np.asarray(indptr).tolist(), np.asarray(indices).tolist()
    rows = np.repeat(np.arange(n), np.diff(indptr))
    diagonal = np.zeros(n, dtype=np.int32)
    diagonal[rows[np.asarray(indices) == rows]] = 1
    degree = (np.diff(indptr) + diagonal).astype(np.int32)  # scipy's dtype: same argsort
    deg = degree.tolist()
    visited = [False] * n
    order: list[int] = []
    for seed in np.argsort(degree).tolist():
        if visited[seed]:
            continue
        visited[seed] = True
        order.append(seed)
        start = len(order) - 1
        while start < len(order):
            end = len(order)
            for i in order[start:end]:
                first = len(order)
                for j in ind[ptr[i]:ptr[i + 1]]:
                    if not visited[j]:
                        visited[j] = True
                        order.append(j)
                if len(order) - first > 1:
                    order[first:] = sorted(order[first:], key=deg.__getitem__)
            start = end
        if len(order) == n:
            break
    return np.array(order[::-1], dtype=np.int32)


def edge_pattern(a: IntArray, b: IntArray, n: int) -> tuple[IntArray, IntArray]:
    """The symmetric CSR pattern (``indptr``, ``indices``: sorted, unique) of ``n`` nodes
    joined by the edges ``a[k]``-``b[k]`` (both directions)."""
    rows = np.concatenate((a, b)).astype(np.int64)
    cols = np.concatenate((b, a)).astype(np.int64)
    key = np.unique(rows * max(n, 1) + cols)
    indptr = np.concatenate(([0], np.cumsum(np.bincount(key // max(n, 1), minlength=n))))
    return indptr.astype(np.int64), (key % max(n, 1)).astype(np.int64)
