"""The general sparse factorization helper of the assembly module."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp

from moorline.solvers.assembly import factorize


def test_factorize_solves_a_general_sparse_system():
    """A non-symmetric block-sparse matrix: the solution against numpy's dense solve."""
    rng = np.random.default_rng(3)
    n = 40
    dense = np.diag(rng.uniform(4.0, 5.0, n)) + np.diag(rng.normal(size=n - 1), 1) \
        + np.diag(rng.normal(size=n - 3), -3)
    rhs = rng.normal(size=n)
    matrix = sp.bsr_matrix(sp.csr_matrix(dense), blocksize=(2, 2))
    assert np.allclose(factorize(matrix).solve(rhs), np.linalg.solve(dense, rhs),
                       rtol=1e-12, atol=1e-12)


def test_factorize_refuses_a_singular_matrix():
    singular = sp.csr_matrix(np.array([[1.0, 2.0], [2.0, 4.0]]))
    with pytest.raises(np.linalg.LinAlgError):
        factorize(singular)
