"""Sloped and gridded seabed kernels (issue 14, deliverable 3): the bilinear surface against
MoorDyn-C's interpolation rule, and the exact tangents of the contact and friction on a
surface with a twist (a bilinear cell) against central finite differences."""

from __future__ import annotations

import numpy as np
import pytest

from moorline.physics import seabed
from moorline.physics.bathymetry import SeabedSurface, grid, plane

# one bilinear cell with a twist, inside a 3 x 3 grid (heights in m)
GX = np.array([-10.0, 0.0, 25.0])
GY = np.array([-5.0, 5.0, 12.0])
GZ = np.array([[-50.0, -48.0, -47.0], [-52.0, -49.0, -45.0], [-55.0, -50.0, -49.0]])
TWISTED = grid(GX, GY, GZ)


def _points(surface: SeabedSurface, heights: np.ndarray) -> np.ndarray:
    xy = np.array([[3.0, 1.0], [17.0, 9.0], [-4.0, -2.0], [11.0, 6.5]])
    z = surface.height(xy) + heights
    return np.column_stack([xy, z])


def test_bilinear_grid_matches_the_corner_heights_the_cell_centre_and_clamps_outside() -> None:
    """MoorDyn-C's rule (Seafloor.cpp getDepthAt, Util/Interp.hpp): the node heights, the mean
    of the four corners at a cell centre, and beyond the grid the height at its edge."""
    nodes = np.array([[x, y] for x in GX for y in GY])
    assert np.allclose(TWISTED.height(nodes), GZ.ravel(), rtol=0, atol=1e-12)
    centre = TWISTED.height(np.array([[12.5, 8.5]]))[0]
    assert centre == pytest.approx(GZ[1:, 1:].mean(), abs=1e-12)
    outside = TWISTED.height(np.array([[100.0, 8.5], [-40.0, -30.0]]))
    assert outside == pytest.approx([0.5 * (GZ[2, 1] + GZ[2, 2]), GZ[0, 0]], abs=1e-12)
    h, G, _ = TWISTED.evaluate(np.array([[100.0, 8.5]]))
    assert G[0, 0] == 0.0 and G[0, 1] == pytest.approx((GZ[2, 2] - GZ[2, 1]) / 7.0)


def test_a_grid_sampled_from_a_plane_is_that_plane() -> None:
    p = plane(300.0, 4.0, 35.0)
    gx, gy = np.array([-900.0, -100.0, 50.0, 700.0]), np.array([-600.0, 20.0, 800.0])
    gz = p.height(np.array([[x, y] for x in gx for y in gy])).reshape(4, 3)
    xy = np.random.default_rng(1).uniform([-899.0, -599.0], [699.0, 799.0], size=(50, 2))
    h1, G1, _ = p.evaluate(xy)
    h2, G2, H2 = grid(gx, gy, gz).evaluate(xy)
    assert np.allclose(h2, h1, rtol=0, atol=1e-10)
    assert np.allclose(G2, G1, rtol=0, atol=1e-13) and np.allclose(H2, 0.0, atol=1e-15)
    # the plane goes down at 4 deg towards 35 deg: the gradient points the other way
    assert np.hypot(*G1[0]) == pytest.approx(np.tan(np.radians(4.0)))
    assert np.degrees(np.arctan2(-G1[0, 1], -G1[0, 0])) == pytest.approx(35.0)


def _fd(fun, x: np.ndarray, h: float) -> np.ndarray:
    """Central differences of fun (n, ...) with respect to each node's x, y, z: (n, ..., 3)."""
    cols = []
    for j in range(3):
        dx = np.zeros_like(x)
        dx[:, j] = h
        cols.append((fun(x + dx) - fun(x - dx)) / (2 * h))
    return np.stack(cols, axis=-1)


@pytest.mark.parametrize("surface", [TWISTED, plane(100.0, 20.0, 150.0)],
                         ids=["bilinear", "plane"])
def test_normal_distance_gradient_and_hessian(surface) -> None:
    x = _points(surface, np.array([0.3, -0.2, 1.5, 0.0]))
    d, grad, hess = seabed.normal_distance(x, surface)
    assert np.allclose(_fd(lambda y: seabed.normal_distance(y, surface)[0], x, 1e-5), grad,
                       atol=1e-8)
    assert np.allclose(_fd(lambda y: seabed.normal_distance(y, surface)[1], x, 1e-5), hess,
                       atol=1e-8)
    n, dn = seabed.surface_normal(x, surface)
    assert np.allclose(np.linalg.norm(n, axis=1), 1.0)
    assert np.allclose(_fd(lambda y: seabed.surface_normal(y, surface)[0], x, 1e-5), dn,
                       atol=1e-8)


def test_plane_distance_is_the_euclidean_distance() -> None:
    p = plane(50.0, 30.0, 0.0)
    x = np.array([[10.0, 3.0, p.height(np.array([[10.0, 3.0]]))[0] + 2.0]])
    # 2 m above the surface vertically is 2 cos(30 deg) along the normal
    assert seabed.normal_distance(x, p)[0][0] == pytest.approx(2.0 * np.cos(np.radians(30.0)))


def test_surface_contact_tangents_and_energy() -> None:
    """Stiffness and damping of the contact on the twisted cell (nodes within and beyond the
    blend-in band, moving), and the force is minus the energy gradient without damping."""
    x = _points(TWISTED, np.array([-0.004, -0.0005, 0.0, -0.02]))
    v = np.array([[0.1, -0.2, -0.05], [0.0, 0.3, 0.01], [0.2, 0.1, -0.3], [-0.1, 0.0, 0.02]])
    k, c, ramp = np.full(4, 2e5), np.full(4, 3e4), np.full(4, 0.002)
    con = seabed.surface_contact(x, v, TWISTED, k, c, ramp)
    assert np.all(con.normal > 0)
    K = _fd(lambda y: seabed.surface_contact(y, v, TWISTED, k, c, ramp).force, x, 1e-7)
    C = _fd(lambda w: seabed.surface_contact(x, w, TWISTED, k, c, ramp).force, v, 1e-7)
    scale = np.abs(con.stiffness).max()
    assert np.allclose(K, con.stiffness, atol=1e-6 * scale)
    assert np.allclose(C, con.damping, atol=1e-6 * np.abs(con.damping).max())
    dN = _fd(lambda y: seabed.surface_contact(y, v, TWISTED, k, c, ramp).normal[:, None], x,
             1e-7)[:, 0]
    assert np.allclose(dN, con.dnormal_dx, atol=1e-6 * scale)
    zero = np.zeros(4)
    still = seabed.surface_contact(x, np.zeros_like(x), TWISTED, k, zero, ramp).force
    grad = np.array([[(seabed.surface_energy(x + _unit(i, j, 1e-7), TWISTED, k, ramp)
                       - seabed.surface_energy(x - _unit(i, j, 1e-7), TWISTED, k, ramp)) / 2e-7
                      for j in range(3)] for i in range(4)])
    assert np.allclose(-grad, still, atol=1e-6 * np.abs(still).max())


def _unit(i: int, j: int, h: float) -> np.ndarray:
    e = np.zeros((4, 3))
    e[i, j] = h
    return e


@pytest.mark.parametrize("mu", [(0.6, 0.6), (0.8, 0.3)], ids=["isotropic", "anisotropic"])
def test_friction_in_the_tangent_plane_and_its_derivatives(mu) -> None:
    x = _points(TWISTED, np.full(4, -0.001))
    v = np.array([[0.01, -0.02, 0.005], [0.0, 0.003, 0.0], [0.2, 0.1, -0.3], [1e-4, 0.0, 0.0]])
    normal = np.array([100.0, 50.0, 80.0, 10.0])
    n, dn = seabed.surface_normal(x, TWISTED)
    axis = np.cross(n, [0.0, 1.0, 0.0])
    axis /= np.linalg.norm(axis, axis=1)[:, None]

    def force(y, w, N=normal):
        u, du = seabed.surface_normal(y, TWISTED)
        return seabed.friction_force(w, N, axis, *mu, 0.01, u, du)[0]

    f, d_dv, d_dn, d_dx = seabed.friction_force(v, normal, axis, *mu, 0.01, n, dn)
    assert np.allclose(np.einsum("ij,ij->i", f, n), 0.0, atol=1e-12)  # in the tangent plane
    assert np.allclose(_fd(lambda w: force(x, w), v, 1e-8), d_dv, atol=1e-5 * normal.max())
    dn_fd = (force(x, v, normal + 1e-6) - force(x, v, normal - 1e-6)) / 2e-6
    assert np.allclose(dn_fd, d_dn, atol=1e-8)
    if mu[0] == mu[1]:  # the anisotropic law leaves out the turning of its axes
        assert np.allclose(_fd(lambda y: force(y, v), x, 1e-6), d_dx, atol=1e-6 * normal.max())


def test_static_friction_derivative_on_a_twisted_cell() -> None:
    x = _points(TWISTED, np.full(4, -0.001))
    far = x + np.array([[8.0, 1.0, 0.5], [-6.0, 3.0, 1.0], [5.0, -5.0, 2.0], [0.5, 9.0, 0.1]])
    k, ramp, zero = np.full(4, 2e5), np.full(4, 0.002), np.zeros(4)
    EA, L0, mu = 1e6, np.linalg.norm(far - x, axis=1) * 0.999, 0.5
    load = np.array([[0.0, 0.0, -300.0], [50.0, 0.0, -400.0], [0.0, 0.0, -5000.0],
                     [0.0, -20.0, -100.0]])

    def evaluate(y, z):
        con = seabed.surface_contact(y, np.zeros_like(y), TWISTED, k, zero, ramp)
        chord = z - y
        length = np.linalg.norm(chord, axis=1)
        tension = EA * (length / L0 - 1.0)
        return seabed.static_friction(con.normal, con.dnormal_dx, tension, EA / L0,
                                      chord / length[:, None], length, mu, con.unit_normal,
                                      con.dunit_dx, load)

    f, df = evaluate(x, far)
    assert np.any(mu * seabed.surface_contact(x, np.zeros_like(x), TWISTED, k, zero,
                                              ramp).normal < EA * (np.linalg.norm(far - x, axis=1)
                                                                   / L0 - 1))
    own = _fd(lambda y: evaluate(y, far)[0], x, 1e-7)
    other = _fd(lambda z: evaluate(x, z)[0], far, 1e-7)
    scale = np.abs(df).max()
    assert np.allclose(own, df[:, :, :3], atol=1e-6 * scale)
    assert np.allclose(other, df[:, :, 3:], atol=1e-6 * scale)
    assert np.allclose(np.einsum("ij,ij->i", f, seabed.surface_normal(x, TWISTED)[0]), 0.0,
                       atol=1e-9)
