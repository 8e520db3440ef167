"""Element kernels and the assembled tangent against central finite differences."""

import numpy as np
import pytest

from moorline.physics import element, seabed
from moorline.solvers.assembly import BlockPattern

RNG = np.random.default_rng(7)


def _forces(x, elements, L0, EA, ratio):
    length, unit = element.element_geometry(x, elements)
    T, _ = element.axial_tension(length, L0, EA, ratio)
    f = element.nodal_forces(T, unit)
    out = np.zeros_like(x)
    np.add.at(out, elements[:, 0], f[:, 0])
    np.add.at(out, elements[:, 1], f[:, 1])
    return out


@pytest.mark.parametrize("stretch", [1.05, 0.97])  # taut and slack elements
def test_element_tangent_matches_central_differences(stretch):
    n = 6
    x = np.cumsum(RNG.normal(size=(n, 3)), axis=0)
    elements = np.column_stack((np.arange(n - 1), np.arange(1, n)))
    length, _ = element.element_geometry(x, elements)
    L0 = length / stretch
    EA = np.full(n - 1, 1.0e4)
    ratio = np.full(n - 1, 1e-3)
    length, unit = element.element_geometry(x, elements)
    T, dT = element.axial_tension(length, L0, EA, ratio)
    blocks = element.tangent_blocks(length, unit, T, dT)
    K = BlockPattern(elements, np.arange(3 * n).reshape(-1, 3)).assemble(blocks).toarray()
    h = 1e-6
    K_fd = np.zeros_like(K)
    for j in range(3 * n):
        dx = np.zeros(3 * n)
        dx[j] = h
        fp = _forces(x + dx.reshape(-1, 3), elements, L0, EA, ratio).ravel()
        fm = _forces(x - dx.reshape(-1, 3), elements, L0, EA, ratio).ravel()
        K_fd[:, j] = -(fp - fm) / (2 * h)
    assert np.allclose(K, K_fd, rtol=1e-6, atol=1e-6 * np.abs(K).max())
    assert np.allclose(K, K.T)


def test_tension_is_linear_in_stretch_and_tiny_in_compression():
    L0 = np.array([2.0, 2.0])
    T, _ = element.axial_tension(np.array([2.2, 1.8]), L0, np.array([100.0, 100.0]),
                                 np.array([1e-6, 1e-6]))
    assert T[0] == pytest.approx(100.0 * 0.1, rel=1e-14)
    assert T[1] == pytest.approx(-100.0 * 1e-6 * 0.1, rel=1e-12)


@pytest.mark.parametrize("depth_in", [-0.0002, 0.0002, 0.002, 0.05])  # in the band, beyond
def test_seabed_contact_derivatives_and_energy_match_finite_differences(depth_in):
    height, vz = np.array([-depth_in]), np.array([-0.3])
    k, c, ramp = np.array([5.0e4]), np.array([2.0e3]), np.array([0.001])
    f, dz, dv = seabed.contact_force(height, vz, k, c, ramp)
    h = 1e-8
    fd_z = (seabed.contact_force(height + h, vz, k, c, ramp)[0]
            - seabed.contact_force(height - h, vz, k, c, ramp)[0]) / (2 * h)
    fd_v = (seabed.contact_force(height, vz + h, k, c, ramp)[0]
            - seabed.contact_force(height, vz - h, k, c, ramp)[0]) / (2 * h)
    assert dz[0] == pytest.approx(fd_z[0], rel=1e-6)
    assert dv[0] == pytest.approx(fd_v[0], rel=1e-6)
    # the spring is the derivative of the stored energy (no damping)
    zero = np.zeros(1)
    spring = seabed.contact_force(height, zero, k, zero, ramp)[0][0]
    dE = (seabed.contact_energy(height - h, k, ramp)
          - seabed.contact_energy(height + h, k, ramp)) / (2 * h)
    assert spring == pytest.approx(dE, rel=1e-5)
    # beyond the band (ramp / 2 deep): MoorDyn's spring k p; inside it above k p (the band
    # starts ramp / 2 above the surface)
    if depth_in > ramp[0] / 2:
        assert spring == pytest.approx(k[0] * depth_in, rel=1e-12)
    else:
        assert spring > k[0] * depth_in


def test_seabed_force_is_continuous_at_touchdown():
    k, c, ramp = np.array([5.0e4]), np.array([2.0e3]), np.array([0.001])
    f_out = seabed.contact_force(np.array([1e-12]), np.array([-1.0]), k, c, ramp)[0]
    f_in = seabed.contact_force(np.array([-1e-12]), np.array([-1.0]), k, c, ramp)[0]
    assert abs(f_in[0] - f_out[0]) < 1e-5


def test_consistent_and_lumped_mass_carry_the_element_mass():
    L0, m = np.array([3.0, 2.0]), np.array([4.0, 1.5])
    blocks = element.consistent_mass_blocks(L0, m)
    # a rigid translation: every row block sums to the element mass in each direction
    total = blocks.reshape(2, 6, 6)[:, :, [0, 3]].sum(axis=(1, 2))
    assert np.allclose(total, m * L0)
    lumped = element.lumped_mass(np.array([[0, 1], [1, 2]]), L0, m, 3)
    assert np.allclose(lumped, [6.0, 6.0 + 1.5, 1.5])


def test_block_pattern_matches_dense_assembly_with_constrained_dofs():
    n, n_el = 5, 4
    elements = np.column_stack((np.arange(n_el), np.arange(1, n_el + 1)))
    dof = np.full((n, 3), -1)
    dof[1:4] = np.arange(9).reshape(3, 3)
    blocks = RNG.normal(size=(n_el, 6, 6))
    node_blocks = RNG.normal(size=(n, 3, 3))
    diag = RNG.normal(size=9)
    K = BlockPattern(elements, dof).assemble(blocks, node_blocks, diag).toarray()
    dense = np.zeros((3 * n, 3 * n))
    for e, (a, b) in enumerate(elements):
        idx = np.r_[3 * a:3 * a + 3, 3 * b:3 * b + 3]
        dense[np.ix_(idx, idx)] += blocks[e]
    for i in range(n):
        dense[3 * i:3 * i + 3, 3 * i:3 * i + 3] += node_blocks[i]
    keep = np.arange(3, 12)
    expected = dense[np.ix_(keep, keep)] + np.diag(diag)
    assert np.allclose(K, expected)


@pytest.mark.parametrize("max_band, small_below", [(120, 0), (1, 0), (120, 1000)])
def test_sparse_factor_solves_like_a_dense_solver(max_band, small_below):
    """Banded LAPACK, SuperLU, and the same banded LU in Python (a small system)."""
    from moorline.solvers.assembly import SparseFactor

    n, n_el = 12, 11
    elements = np.column_stack((np.arange(n_el), np.arange(1, n_el + 1)))
    elements = np.vstack((elements, [[0, 7]]))  # a loop: the reordering must cope
    dof = np.arange(3 * n).reshape(-1, 3)
    dof[5] = -1
    dof[dof > 15] -= 3
    pattern = BlockPattern(elements, dof)
    blocks = RNG.normal(size=(len(elements), 6, 6))
    data = pattern.values(blocks, np.eye(3)[None] * 50.0 + RNG.normal(size=(n, 3, 3)))
    A = np.zeros((pattern.n, pattern.n))
    A[pattern.rows, pattern.indices] = data
    b = RNG.normal(size=pattern.n)
    factor = SparseFactor(pattern, max_band=max_band, small_below=small_below)
    assert factor.banded == (max_band == 120)
    assert factor.small == bool(small_below)
    assert np.allclose(factor.factor(data).solve(b), np.linalg.solve(A, b), rtol=1e-10)
    assert np.array_equal(pattern.dense(data), A)
    assert np.array_equal(pattern.diagonal(data), np.diag(A))
    singular = data.copy()
    singular[pattern.rows == 0] = 0.0  # a zero row
    with pytest.raises(np.linalg.LinAlgError):
        factor.factor(singular)
