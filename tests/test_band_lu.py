"""The banded LU in Python (:mod:`moorline.solvers.band_lu`) against numpy's dense solver
(LAPACK ``gesv``): random banded matrices of every shape of band, pivoting needed (zero
diagonals), several right-hand sides; a matrix banded only once reordered."""

from __future__ import annotations

import numpy as np
import pytest

from moorline.solvers.band_lu import BandLU, small_band_solver


def _banded(rng: np.random.Generator, n: int, kl: int, ku: int) -> np.ndarray:
    i, j = np.indices((n, n))
    a = np.where((i - j <= kl) & (j - i <= ku), rng.normal(size=(n, n)), 0.0)
    return a + np.diag(rng.uniform(2.0, 3.0, n) * (kl + ku + 1))


@pytest.mark.parametrize("n, kl, ku", [(1, 0, 0), (2, 1, 1), (7, 2, 3), (50, 5, 5),
                                       (40, 0, 4), (40, 6, 0), (171, 5, 5), (60, 11, 2)])
def test_solves_as_lapack_does(n: int, kl: int, ku: int) -> None:
    rng = np.random.default_rng(n + 10 * kl + 100 * ku)
    a = _banded(rng, n, kl, ku)
    b = rng.normal(size=(n, 3))
    lu = BandLU(a, kl, ku)
    np.testing.assert_allclose(lu.solve(b), np.linalg.solve(a, b), rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(lu.solve(b[:, 0]), np.linalg.solve(a, b[:, 0]), rtol=1e-10,
                               atol=1e-12)


def test_pivots_where_the_diagonal_is_zero() -> None:
    """Zero diagonal entries: no factorization without row swaps."""
    rng = np.random.default_rng(1)
    a = _banded(rng, 30, 3, 2)
    a[np.arange(0, 30, 2), np.arange(0, 30, 2)] = 0.0
    b = rng.normal(size=30)
    np.testing.assert_allclose(BandLU(a, 3, 2).solve(b), np.linalg.solve(a, b), rtol=1e-9)


def test_a_singular_matrix_is_refused() -> None:
    a = _banded(np.random.default_rng(2), 10, 1, 1)
    a[4] = 0.0
    with pytest.raises(np.linalg.LinAlgError):
        BandLU(a, 1, 1)


def test_a_matrix_banded_once_reordered() -> None:
    """Three chains of 57 unknowns with their unknowns shuffled: the reverse Cuthill-McKee
    order makes them banded again; a dense or large matrix is declined."""
    rng = np.random.default_rng(3)
    chains = np.zeros((171, 171))
    for k in range(3):
        part = slice(57 * k, 57 * (k + 1))
        chains[part, part] = _banded(rng, 57, 5, 5)
    shuffle = rng.permutation(171)
    a = chains[np.ix_(shuffle, shuffle)]
    b = rng.normal(size=(171, 2))
    solve = small_band_solver(a)
    assert solve is not None
    np.testing.assert_allclose(solve(b), np.linalg.solve(a, b), rtol=1e-10, atol=1e-12)
    assert small_band_solver(rng.normal(size=(80, 80))) is None  # dense: band too wide
    assert small_band_solver(np.eye(400)) is None  # too large for Python
