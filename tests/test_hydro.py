"""Morison kernels (Tuah 1982 sec. 3.2.a): derivatives against central finite differences,
hand-computed loads, objectivity and vectorized speed.

Finite-difference step: the kernels are smooth (C^2 away from u_n = 0, and cubic-free
quadratics in u), so the central-difference truncation error is O(h^2 |f'''|) and the rounding
error O(eps_mach |f| / h). With velocities and lengths of order 1 and h = 1e-5 both are
<= 1e-9 relative, well inside the 1e-6 tolerance, also near u_n = 0 as long as |u_n| >> h
(the third derivative of |w|w grows like 1/|w|): the nearly tangent case uses |u_n| ~ 1e-2.
"""


import numpy as np
import pytest

from moorline.physics import hydro

RNG = np.random.default_rng(11)
RHO, CD, CT, D = 1025.0, 1.2, 0.4, 0.08
H = 1e-5


def _chain(n_el):
    x = np.cumsum(RNG.normal(size=(n_el + 1, 3)), axis=0)
    elements = np.column_stack((np.arange(n_el), np.arange(1, n_el + 1)))
    return x, elements


def _fd(fun, z, h=H):
    """Central differences of fun (returning (n_el, 2, 3)) with respect to z (n_nodes, 3):
    dense (n_el*6, n_nodes*3)."""
    cols = []
    for j in range(z.size):
        dz = np.zeros(z.size)
        dz[j] = h
        dz = dz.reshape(z.shape)
        cols.append(((fun(z + dz) - fun(z - dz)) / (2 * h)).ravel())
    return np.column_stack(cols)


def _dense(blocks, elements, n_nodes):
    """Element blocks (n_el, 6, 6) scattered into the (n_el*6, n_nodes*3) layout of _fd."""
    n_el = len(elements)
    out = np.zeros((n_el * 6, n_nodes * 3))
    for e, (i, j) in enumerate(elements):
        for a in range(2):
            rows = slice(6 * e + 3 * a, 6 * e + 3 * a + 3)
            out[rows, 3 * i:3 * i + 3] += blocks[e, 3 * a:3 * a + 3, :3]
            out[rows, 3 * j:3 * j + 3] += blocks[e, 3 * a:3 * a + 3, 3:]
    return out


def _assert_close(exact, fd):
    scale = np.abs(exact).max()
    assert scale > 0
    assert np.allclose(exact, fd, rtol=1e-6, atol=1e-6 * scale)


def _flow_cases(x, elements):
    """Node velocities and midpoint fluid velocities: generic, nearly tangent, nearly normal,
    exactly tangent and exactly normal relative flow (relative speed ~ 1 m/s)."""
    _, t = hydro._tangent(x, elements)
    n_el = len(elements)
    v = 0.3 * RNG.normal(size=(len(x), 3))
    vmid = 0.5 * (v[elements[:, 0]] + v[elements[:, 1]])
    perp = np.cross(t, RNG.normal(size=(n_el, 3)))
    perp /= np.linalg.norm(perp, axis=1)[:, None]
    cases = {
        "generic": RNG.normal(size=(n_el, 3)),
        "nearly_tangent": t + 1e-2 * perp,
        "nearly_normal": perp + 1e-2 * t,
        "tangent": -t,
        "normal": perp,
    }
    return v, {k: vmid + u for k, u in cases.items()}


@pytest.mark.parametrize("case", ["generic", "nearly_tangent", "nearly_normal", "tangent",
                                  "normal"])
def test_drag_derivatives_match_central_differences(case):
    x, elements = _chain(4)
    v, uf_cases = _flow_cases(x, elements)
    uf = uf_cases[case]
    L0 = RNG.uniform(0.5, 2.0, len(elements))
    _, dF_dv, dF_dx = hydro.drag_forces(x, v, uf, elements, L0, D, CD, CT, RHO)
    n = len(x)

    def by_v(vv):
        return hydro.drag_forces(x, vv, uf, elements, L0, D, CD, CT, RHO)[0]

    def by_x(xx):
        return hydro.drag_forces(xx, v, uf, elements, L0, D, CD, CT, RHO)[0]

    fd_v = _fd(by_v, v)
    fd_x = _fd(by_x, x)
    if case in ("tangent", "normal"):
        # exactly on the kink-free but non-C2 point u_n = 0 (or u_t = 0): the central
        # difference of |w|w across w = 0 is O(h) off; compare with an absolute O(h) bound
        ex_v, ex_x = _dense(dF_dv, elements, n), _dense(dF_dx, elements, n)
        bound = 10 * H * RHO * max(CD, CT * np.pi) * D * L0.max()
        assert np.abs(ex_v - fd_v).max() < bound
        assert np.abs(ex_x - fd_x).max() < bound
        assert np.abs(ex_x).max() > 0
    else:
        _assert_close(_dense(dF_dv, elements, n), fd_v)
        _assert_close(_dense(dF_dx, elements, n), fd_x)
    # the damping matrix -dF_dv is symmetric (Tuah eq. 3.2.a.6) and positive semi-definite
    assert np.allclose(dF_dv, np.swapaxes(dF_dv, 1, 2), atol=1e-12 * np.abs(dF_dv).max())
    assert np.linalg.eigvalsh(-dF_dv).min() > -1e-10 * np.abs(dF_dv).max()


@pytest.mark.parametrize("case", ["generic", "nearly_tangent", "nearly_normal"])
def test_nodal_drag_derivatives_match_central_differences(case):
    x, elements = _chain(4)
    v, uf_cases = _flow_cases(x, elements)
    uf = uf_cases[case]
    L0 = RNG.uniform(0.5, 2.0, len(elements))
    _, dF_dv, dF_dx = hydro.nodal_drag_forces(x, v, uf, elements, L0, D, CD, CT, RHO)
    n = len(x)
    fd_v = _fd(lambda vv: hydro.nodal_drag_forces(x, vv, uf, elements, L0, D, CD, CT, RHO)[0], v)
    fd_x = _fd(lambda xx: hydro.nodal_drag_forces(xx, v, uf, elements, L0, D, CD, CT, RHO)[0], x)
    _assert_close(_dense(dF_dv, elements, n), fd_v)
    _assert_close(_dense(dF_dx, elements, n), fd_x)
    assert np.linalg.eigvalsh(-dF_dv).min() > -1e-10 * np.abs(dF_dv).max()


def test_nodal_drag_equals_element_drag_for_equal_node_velocities_and_damps_zigzag():
    """Both rules agree when an element's nodes move together; on the odd-even mode (node
    velocities alternating in sign across a still fluid) the element rule's mean velocity is
    zero, so it exerts no drag, while the nodal rule opposes every node's motion."""
    x, elements = _chain(5)
    L0 = np.ones(len(elements))
    still = np.zeros((len(elements), 3))
    common = np.tile(RNG.normal(size=3), (len(x), 1))
    a = hydro.drag_forces(x, common, still, elements, L0, D, CD, CT, RHO)[0]
    b = hydro.nodal_drag_forces(x, common, still, elements, L0, D, CD, CT, RHO)[0]
    assert np.allclose(a, b, rtol=1e-14, atol=0.0)
    zigzag = np.outer((-1.0) ** np.arange(len(x)), [0.0, 0.0, 1.0])
    element_rule = hydro.drag_forces(x, zigzag, still, elements, L0, D, CD, CT, RHO)[0]
    nodal_rule = hydro.nodal_drag_forces(x, zigzag, still, elements, L0, D, CD, CT, RHO)[0]
    assert np.abs(element_rule).max() == 0.0
    power = np.einsum("eij,eij->", nodal_rule, zigzag[elements])
    assert power < 0.0


def test_no_nan_at_zero_relative_velocity():
    x, elements = _chain(3)
    v = np.zeros_like(x)
    f, dv, dx = hydro.drag_forces(x, v, np.zeros((3, 3)), elements, 1.0, D, CD, CT, RHO)
    assert np.all(f == 0) and np.all(dv == 0) and np.all(dx == 0)
    f, jac = hydro.point_drag(np.zeros(3), 0.5, 1.0, RHO)
    assert np.all(f == 0) and np.all(jac == 0)


def test_horizontal_element_in_vertical_flow_gets_pure_normal_drag():
    x = np.array([[0.0, 0.0, -5.0], [3.0, 0.0, -5.0]])
    elements = np.array([[0, 1]])
    U, L0 = 0.7, 2.9  # L0 != l: loads are per unstretched length
    f, _, _ = hydro.drag_forces(x, np.zeros_like(x), np.array([[0.0, 0.0, U]]), elements, L0,
                                D, CD, CT, RHO)
    total = f.sum(axis=1)[0]
    assert total == pytest.approx([0.0, 0.0, 0.5 * RHO * CD * D * L0 * U**2], rel=1e-14,
                                  abs=1e-12)
    assert np.allclose(f[0, 0], f[0, 1])


def test_element_moving_through_still_water_feels_the_relative_flow():
    x = np.array([[0.0, 0.0, -5.0], [3.0, 0.0, -5.0]])
    v = np.array([[0.0, 0.0, 0.4], [0.0, 0.0, 0.6]])  # mean 0.5 upwards
    f, _, _ = hydro.drag_forces(x, v, np.zeros((1, 3)), np.array([[0, 1]]), 3.0, D, CD, CT,
                                RHO)
    assert f.sum(axis=1)[0, 2] == pytest.approx(-0.5 * RHO * CD * D * 3.0 * 0.25, rel=1e-14)


def test_element_aligned_with_flow_gets_pure_tangential_drag():
    t = np.array([1.0, 2.0, -0.5]) / np.sqrt(5.25)
    x = np.array([[1.0, 1.0, -9.0], [1.0, 1.0, -9.0] + 4.0 * t])
    U, L0 = 1.3, 3.8
    f, _, _ = hydro.drag_forces(x, np.zeros_like(x), -U * t[None], np.array([[0, 1]]), L0,
                                D, CD, CT, RHO)
    expected = -0.5 * RHO * CT * np.pi * D * L0 * U**2 * t
    assert np.allclose(f.sum(axis=1)[0], expected, rtol=1e-13, atol=1e-12)


def test_galilean_invariance_structure_moving_with_the_flow():
    x, elements = _chain(5)
    uf = RNG.normal(size=3)
    v = np.tile(uf, (len(x), 1))
    f, _, _ = hydro.drag_forces(x, v, np.tile(uf, (5, 1)), elements, 1.0, D, CD, CT, RHO)
    assert np.abs(f).max() < 1e-12


def _random_rotation():
    q, r = np.linalg.qr(RNG.normal(size=(3, 3)))
    q = q * np.sign(np.diag(r))
    return q if np.linalg.det(q) > 0 else -q


def _rotate_blocks(blocks, R):
    R6 = np.kron(np.eye(2), R)
    return R6 @ blocks @ R6.T


def test_objectivity_under_rotation():
    x, elements = _chain(6)
    v, uf_cases = _flow_cases(x, elements)
    uf = uf_cases["generic"]
    af = RNG.normal(size=(6, 3))
    a = RNG.normal(size=x.shape)
    R = _random_rotation()
    args = (elements, 1.3, D)
    f, dv, dx = hydro.drag_forces(x, v, uf, *args, CD, CT, RHO)
    fr, dvr, dxr = hydro.drag_forces(x @ R.T, v @ R.T, uf @ R.T, *args, CD, CT, RHO)
    assert np.allclose(fr, f @ R.T, rtol=1e-12, atol=1e-12 * np.abs(f).max())
    assert np.allclose(dvr, _rotate_blocks(dv, R), atol=1e-12 * np.abs(dv).max())
    assert np.allclose(dxr, _rotate_blocks(dx, R), atol=1e-12 * np.abs(dx).max())

    ma = hydro.added_mass_blocks(x, *args, 1.0, 0.2, RHO)
    assert np.allclose(hydro.added_mass_blocks(x @ R.T, *args, 1.0, 0.2, RHO),
                       _rotate_blocks(ma, R), atol=1e-12 * np.abs(ma).max())
    fi, di = hydro.fluid_inertia_forces(x, af, *args, 1.0, 0.2, RHO)
    fir, dir_ = hydro.fluid_inertia_forces(x @ R.T, af @ R.T, *args, 1.0, 0.2, RHO)
    assert np.allclose(fir, fi @ R.T, atol=1e-12 * np.abs(fi).max())
    assert np.allclose(dir_, _rotate_blocks(di, R), atol=1e-12 * np.abs(di).max())
    dm = hydro.added_mass_position_derivative(x, a, *args, 1.0, 0.2, RHO)
    dmr = hydro.added_mass_position_derivative(x @ R.T, a @ R.T, *args, 1.0, 0.2, RHO)
    assert np.allclose(dmr, _rotate_blocks(dm, R), atol=1e-12 * np.abs(dm).max())


def test_added_mass_of_horizontal_element_accelerated_vertically():
    x = np.array([[0.0, 0.0, 0.0], [2.5, 0.0, 0.0]])
    L0, Ca, Cat = 2.4, 1.0, 0.3
    M = hydro.added_mass_blocks(x, np.array([[0, 1]]), L0, D, Ca, Cat, RHO)[0]
    A = np.pi * D**2 / 4
    acc = np.array([0.0, 0.0, 1.0, 0.0, 0.0, 1.0])
    assert (M @ acc).reshape(2, 3).sum(axis=0) == pytest.approx([0, 0, RHO * Ca * A * L0],
                                                                  rel=1e-14)
    along = np.array([1.0, 0.0, 0.0, 1.0, 0.0, 0.0])
    assert (M @ along).reshape(2, 3).sum(axis=0)[0] == pytest.approx(RHO * Cat * A * L0,
                                                                      rel=1e-14)
    assert np.all(M[:3, 3:] == 0) and np.allclose(M, M.T)


def test_fluid_inertia_hand_values():
    x = np.array([[0.0, 0.0, 0.0], [0.0, 1.0, 0.0]])  # along y
    L0, Ca, Cat = 1.1, 0.8, 0.1
    af = np.array([[0.5, 2.0, 0.0]])
    f, _ = hydro.fluid_inertia_forces(x, af, np.array([[0, 1]]), L0, D, Ca, Cat, RHO)
    mA = RHO * np.pi * D**2 / 4 * L0
    assert np.allclose(f.sum(axis=1)[0], [mA * 1.8 * 0.5, mA * 1.1 * 2.0, 0.0], rtol=1e-14)


def test_added_mass_and_fluid_inertia_position_derivatives():
    x, elements = _chain(4)
    L0 = RNG.uniform(0.5, 2.0, len(elements))
    a = RNG.normal(size=x.shape)
    af = RNG.normal(size=(len(elements), 3))
    Ca, Cat = 1.0, 0.15
    n = len(x)

    def added_mass_force(xx):
        M = hydro.added_mass_blocks(xx, elements, L0, D, Ca, Cat, RHO)
        acc = np.concatenate((a[elements[:, 0]], a[elements[:, 1]]), axis=1)
        return -np.einsum("nij,nj->ni", M, acc).reshape(-1, 2, 3)

    exact = hydro.added_mass_position_derivative(x, a, elements, L0, D, Ca, Cat, RHO)
    _assert_close(_dense(exact, elements, n), _fd(added_mass_force, x))

    def inertia(xx):
        return hydro.fluid_inertia_forces(xx, af, elements, L0, D, Ca, Cat, RHO)[0]

    exact = hydro.fluid_inertia_forces(x, af, elements, L0, D, Ca, Cat, RHO)[1]
    _assert_close(_dense(exact, elements, n), _fd(inertia, x))


def test_point_drag_and_added_mass():
    u = np.array([[0.3, -0.4, 1.2], [1e-3, 0.0, 0.0], [0.0, 2.0, 0.0]])
    area, cd = np.array([0.5, 0.2, 1.0]), 0.9
    f, jac = hydro.point_drag(u, area, cd, RHO)
    speed = np.linalg.norm(u, axis=1)
    assert np.allclose(f, (0.5 * RHO * cd * area * speed)[:, None] * u, rtol=1e-14)
    assert f[2] == pytest.approx([0.0, 0.5 * RHO * cd * 1.0 * 4.0, 0.0], rel=1e-14)
    for k in range(3):
        h = H * speed[k]  # relative step: the third derivative of |u|u scales like 1/|u|
        fd = np.column_stack([
            (hydro.point_drag(u[k] + h * e, area[k], cd, RHO)[0]
             - hydro.point_drag(u[k] - h * e, area[k], cd, RHO)[0]) / (2 * h)
            for e in np.eye(3)])
        _assert_close(jac[k], fd)
    ma = hydro.point_added_mass(0.2, 0.5, RHO)
    assert np.allclose(ma, RHO * 0.5 * 0.2 * np.eye(3), rtol=1e-15)
    assert hydro.point_added_mass(np.ones(4), 1.0, RHO).shape == (4, 3, 3)


def test_sum_to_nodes_matches_add_at():
    x, elements = _chain(7)
    f = RNG.normal(size=(7, 2, 3))
    ref = np.zeros_like(x)
    np.add.at(ref, elements[:, 0], f[:, 0])
    np.add.at(ref, elements[:, 1], f[:, 1])
    assert np.allclose(hydro.sum_to_nodes(f, elements, len(x)), ref, rtol=1e-14, atol=1e-14)
