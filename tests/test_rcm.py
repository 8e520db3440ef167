"""moorline's reverse Cuthill-McKee ordering (:mod:`moorline.solvers.rcm`) against scipy's.

scipy's ``reverse_cuthill_mckee`` is the reference: the orderings must be the same
permutation (so the band factorizations built on them give the same numbers as before), on
random graphs (disconnected, with and without a stored diagonal, ties of degree) and on the
patterns moorline orders (lines of nodes, a body's star of lines).
"""

from __future__ import annotations

import numpy as np
import pytest

scipy_sparse = pytest.importorskip("scipy.sparse")
from scipy.sparse.csgraph import reverse_cuthill_mckee as scipy_rcm  # noqa: E402

from moorline.solvers.assembly import BlockPattern  # noqa: E402
from moorline.solvers.rcm import edge_pattern, reverse_cuthill_mckee  # noqa: E402


def _scipy(a: np.ndarray, b: np.ndarray, n: int) -> np.ndarray:
    graph = scipy_sparse.csr_matrix((np.ones(2 * len(a)), (np.r_[a, b], np.r_[b, a])),
                                    shape=(n, n))
    return scipy_rcm(graph, symmetric_mode=True)


@pytest.mark.parametrize("seed", range(6))
def test_random_graphs_are_ordered_as_scipy_orders_them(seed: int) -> None:
    rng = np.random.default_rng(seed)
    for _ in range(150):
        n = int(rng.integers(1, 200))
        m = int(rng.integers(0, 3 * n))
        a, b = rng.integers(0, n, m), rng.integers(0, n, m)
        if rng.random() < 0.5:  # the diagonal stored (a matrix pattern): degree + 1
            a, b = np.r_[a, np.arange(n)], np.r_[b, np.arange(n)]
        expected = _scipy(a, b, n)
        indptr, indices = edge_pattern(a, b, n)
        graph = scipy_sparse.csr_matrix((np.ones(len(a) * 2), (np.r_[a, b], np.r_[b, a])),
                                        shape=(n, n))
        assert np.array_equal(indptr, graph.indptr) and np.array_equal(indices, graph.indices)
        assert np.array_equal(reverse_cuthill_mckee(indptr, indices), expected)


@pytest.mark.parametrize("lines, nodes", [(3, 21), (3, 1001), (8, 40)])
def test_mooring_patterns_are_ordered_as_scipy_orders_them(lines: int, nodes: int) -> None:
    """Lines of nodes from their anchors to a shared hub (a body's star), as a block
    pattern (3 dofs per node, the diagonal stored) and as a node graph."""
    chains = [np.arange(k * nodes, (k + 1) * nodes) for k in range(lines)]
    hub = lines * nodes
    a = np.concatenate([c[:-1] for c in chains] + [np.array([c[-1] for c in chains])])
    b = np.concatenate([c[1:] for c in chains] + [np.full(lines, hub)])
    n = hub + 1
    assert np.array_equal(reverse_cuthill_mckee(*edge_pattern(a, b, n)), _scipy(a, b, n))
    pattern = BlockPattern(np.column_stack((a, b)), np.arange(3 * n).reshape(-1, 3))
    graph = scipy_sparse.csr_matrix((np.ones(pattern.nnz), pattern.indices, pattern.indptr),
                                    shape=(pattern.n, pattern.n))
    assert np.array_equal(reverse_cuthill_mckee(pattern.indptr, pattern.indices),
                          scipy_rcm(graph, symmetric_mode=True))


def test_an_empty_graph_has_an_empty_ordering() -> None:
    assert reverse_cuthill_mckee(np.zeros(1, dtype=np.int64), np.zeros(0, np.int64)).size == 0
