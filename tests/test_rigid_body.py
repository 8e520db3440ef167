"""Rigid-body kernels (moorline.physics.rigid_body): the exp/log maps, their Jacobians, the
rigid-body mass and inertia load against point-mass systems and closed forms, and every
tangent against central finite differences (rotations as ``exp([eps e_k x]) R``)."""

from __future__ import annotations

import numpy as np
import pytest

from moorline.physics import rigid_body as rb

EPS = 1e-6


def _vee(S):
    return np.array([S[2, 1], S[0, 2], S[1, 0]])


def _random_rotations(rng, n):
    q, r = np.linalg.qr(rng.normal(size=(n, 3, 3)))
    q = q * np.sign(np.diagonal(r, axis1=1, axis2=2))[:, None, :]
    return q * np.sign(np.linalg.det(q))[:, None, None]


def _rotated(R, k, eps):
    e = np.zeros(3)
    e[k] = eps
    return rb.rotation_matrix(e) @ R


def _fd_rotation(fun, R, eps=EPS):
    """Central differences of ``fun(R)`` (an array) along ``exp([eps e_k x]) R``; last axis k."""
    return np.stack([(fun(_rotated(R, k, eps)) - fun(_rotated(R, k, -eps))) / (2 * eps)
                     for k in range(3)], axis=-1)


def _fd(fun, x, eps=EPS):
    """Central differences of ``fun(x)`` along each component of the last axis of ``x``."""
    cols = []
    for k in range(x.shape[-1]):
        d = np.zeros_like(x)
        d[..., k] = eps
        cols.append((fun(x + d) - fun(x - d)) / (2 * eps))
    return np.stack(cols, axis=-1)


def _body(rng, n):
    """``n`` random bodies: mass, body-frame cog, a full SPD inertia about G, rotation."""
    mass = rng.uniform(1.0, 5.0, n)
    cog = rng.normal(size=(n, 3))
    A = rng.normal(size=(n, 3, 3))
    inertia = A @ np.swapaxes(A, 1, 2) + np.eye(3)
    return mass, cog, inertia, _random_rotations(rng, n)


def _point_masses(rng, n_points=7):
    """A cloud of point masses: masses, body-frame positions, and the rigid body they make."""
    m = rng.uniform(0.5, 2.0, n_points)
    p = rng.normal(size=(n_points, 3)) + np.array([0.3, -0.2, 0.5])
    mass = m.sum()
    cog = (m[:, None] * p).sum(axis=0) / mass
    q = p - cog
    inertia = sum(mi * (qi @ qi * np.eye(3) - np.outer(qi, qi))
                  for mi, qi in zip(m, q, strict=True))
    return m, p, mass, cog, inertia


# ---------------------------------------------------------------------- rotations
def test_skew_is_the_cross_product():
    rng = np.random.default_rng(0)
    a, b = rng.normal(size=(2, 4, 3))
    np.testing.assert_allclose(np.einsum("kij,kj->ki", rb.skew(a), b), np.cross(a, b),
                               rtol=0, atol=1e-15)


@pytest.mark.parametrize("angle", [0.0, 1e-12, 1e-7, 3e-5, 0.3, 2.0, np.pi - 1e-3,
                                   np.pi - 1e-9])
def test_exp_and_log_are_inverse(angle):
    rng = np.random.default_rng(1)
    axes = rng.normal(size=(5, 3))
    axes /= np.linalg.norm(axes, axis=1)[:, None]
    phi = angle * axes
    R = rb.rotation_matrix(phi)
    np.testing.assert_allclose(R @ np.swapaxes(R, 1, 2), np.broadcast_to(np.eye(3), R.shape),
                               atol=1e-15)
    np.testing.assert_allclose(np.linalg.det(R), 1.0, atol=1e-14)
    np.testing.assert_allclose(rb.rotation_vector(R), phi, rtol=0, atol=1e-12)
    # Rodrigues at a quarter turn about z, written out
    np.testing.assert_allclose(rb.rotation_matrix([0.0, 0.0, np.pi / 2]),
                               [[0, -1, 0], [1, 0, 0], [0, 0, 1]], atol=1e-15)


def test_log_of_random_rotations_and_half_turns():
    rng = np.random.default_rng(2)
    R = _random_rotations(rng, 20)
    phi = rb.rotation_vector(R)
    assert np.all(np.linalg.norm(phi, axis=1) <= np.pi + 1e-15)
    np.testing.assert_allclose(rb.rotation_matrix(phi), R, atol=1e-14)
    half = rb.rotation_matrix(np.pi * np.array([[1.0, 0, 0], [0, 0.6, 0.8], [0.48, 0.6, 0.64]]))
    np.testing.assert_allclose(rb.rotation_matrix(rb.rotation_vector(half)), half, atol=1e-14)
    np.testing.assert_allclose(np.linalg.norm(rb.rotation_vector(half), axis=1), np.pi,
                               atol=1e-12)


@pytest.mark.parametrize("angle", [0.0, 5e-5, 0.7, 2.9])
def test_left_jacobian_is_the_exp_map_derivative(angle):
    rng = np.random.default_rng(3)
    axis = rng.normal(size=3)
    phi = angle * axis / np.linalg.norm(axis)
    R = rb.rotation_matrix(phi)
    dR = _fd(rb.rotation_matrix, phi)  # (3, 3, k)
    fd = np.column_stack([_vee(dR[:, :, k] @ R.T) for k in range(3)])
    J = rb.left_jacobian(phi)
    np.testing.assert_allclose(J, fd, rtol=0, atol=1e-9)
    np.testing.assert_allclose(J @ rb.inverse_left_jacobian(phi), np.eye(3), atol=1e-12)


@pytest.mark.parametrize("angle", [0.0, 5e-7, 1e-3, 0.7, 2.9])
def test_inverse_left_jacobian_is_the_log_map_derivative(angle):
    rng = np.random.default_rng(4)
    axis = rng.normal(size=3)
    phi = angle * axis / np.linalg.norm(axis)
    fd = _fd_rotation(rb.rotation_vector, rb.rotation_matrix(phi))
    np.testing.assert_allclose(rb.inverse_left_jacobian(phi), fd, rtol=0, atol=1e-8)


# ---------------------------------------------------------------------- inertia
def test_rigid_mass_equals_rigidly_attached_point_masses():
    """sum_i T_i^T m_i T_i with T_i = [I, -[R p_i x]]: the mass of the point cloud for small
    rigid motions about the origin."""
    rng = np.random.default_rng(5)
    m, p, mass, cog, inertia = _point_masses(rng)
    R = _random_rotations(rng, 1)[0]
    ref = np.zeros((6, 6))
    for mi, pi in zip(m, p, strict=True):
        T = np.hstack((np.eye(3), -rb.skew(R @ pi)))
        ref += mi * T.T @ T
    np.testing.assert_allclose(rb.rigid_mass(mass, cog, inertia, R), ref, rtol=1e-13,
                               atol=1e-13 * np.abs(ref).max())
    # principal values give the diagonal tensor; bodies broadcast over the leading axis
    diag = np.array([2.0, 3.0, 5.0])
    Rs = _random_rotations(rng, 3)
    np.testing.assert_allclose(rb.rigid_mass(np.full(3, mass), np.tile(cog, (3, 1)),
                                             np.tile(diag, (3, 1)), Rs),
                               [rb.rigid_mass(mass, cog, np.diag(diag), Rk) for Rk in Rs],
                               rtol=1e-15, atol=1e-14)


def test_inertia_load_equals_the_point_mass_sum():
    """Force and moment about the origin of point masses moving rigidly, each with
    acceleration a + alpha x s + w x (w x s), s = R p_i (no formula for G or I_G used)."""
    rng = np.random.default_rng(6)
    m, p, mass, cog, inertia = _point_masses(rng)
    R = _random_rotations(rng, 1)[0]
    vel, acc = rng.normal(size=(2, 6))
    w, al = vel[3:], acc[3:]
    s = p @ R.T
    a_i = acc[:3] + np.cross(al, s) + np.cross(w, np.cross(w, s))
    ref = np.concatenate(((m[:, None] * a_i).sum(axis=0),
                          np.cross(s, m[:, None] * a_i).sum(axis=0)))
    load = rb.inertia_load(mass, cog, inertia, R, vel, acc)[0]
    np.testing.assert_allclose(load, ref, rtol=1e-12, atol=1e-12 * np.abs(ref).max())


def test_centripetal_force_of_an_offset_centre_of_gravity():
    """A body spinning at constant w about z with its centre of gravity at radius r: the
    inertia force is m a_G = -m w^2 r toward the axis, its moment about the origin zero."""
    mass, r, w = 3.0, 0.7, 2.5
    load = rb.inertia_load(mass, [r, 0.0, 0.0], [1.0, 2.0, 3.0], np.eye(3),
                           [0.0, 0.0, 0.0, 0.0, 0.0, w], np.zeros(6))[0]
    np.testing.assert_allclose(load, [-mass * w**2 * r, 0, 0, 0, 0, 0], atol=1e-13)


def test_torque_free_symmetric_top():
    """Euler's torque-free symmetric top (I1 = I2 = I, I3): in the body frame the angular
    velocity precesses about the symmetry axis at Omega = (I3 - I) w3 / I,
    w_b = (w_p cos Omega t, w_p sin Omega t, w3). With that motion the inertia moment about
    G vanishes; without the precession (alpha = 0) it is the gyroscopic moment
    w x (I_G w) = R (0, 0, ...) no longer zero."""
    I_perp, I3, w3, w_p, t = 2.0, 5.0, 3.0, 0.8, 0.37
    Om = (I3 - I_perp) * w3 / I_perp
    w_b = np.array([w_p * np.cos(Om * t), w_p * np.sin(Om * t), w3])
    dw_b = np.array([-Om * w_p * np.sin(Om * t), Om * w_p * np.cos(Om * t), 0.0])
    R = rb.rotation_matrix([0.3, -0.5, 0.9])
    vel = np.concatenate((np.zeros(3), R @ w_b))
    acc = np.concatenate((np.zeros(3), R @ dw_b))  # d(R w_b)/dt = w x w + R dw_b
    inertia = [I_perp, I_perp, I3]
    load = rb.inertia_load(7.0, np.zeros(3), inertia, R, vel, acc)[0]
    np.testing.assert_allclose(load, 0.0, atol=1e-13)
    gyro = rb.inertia_load(7.0, np.zeros(3), inertia, R, vel, np.zeros(6))[0][3:]
    expected = R @ np.cross(w_b, np.array(inertia) * w_b)
    np.testing.assert_allclose(gyro, expected, rtol=1e-13)
    assert np.linalg.norm(gyro) > 1.0


def test_inertia_load_tangents():
    rng = np.random.default_rng(7)
    n = 4
    mass, cog, inertia, R = _body(rng, n)
    vel, acc = rng.normal(size=(2, n, 6))
    _, d_acc, d_vel, d_rot = rb.inertia_load(mass, cog, inertia, R, vel, acc)

    def load(R=R, vel=vel, acc=acc):
        return rb.inertia_load(mass, cog, inertia, R, vel, acc)[0]

    scale = np.abs(load()).max()
    np.testing.assert_allclose(d_acc, _fd(lambda q: load(acc=q), acc), atol=1e-8 * scale)
    np.testing.assert_allclose(d_acc, rb.rigid_mass(mass, cog, inertia, R), atol=1e-15)
    np.testing.assert_allclose(d_vel, _fd(lambda q: load(vel=q), vel), atol=1e-8 * scale)
    def load_of(b):
        return lambda Rk: load(R=np.stack([Rk if j == b else R[j] for j in range(n)]))[b]

    fd_rot = np.stack([_fd_rotation(load_of(b), R[b]) for b in range(n)])
    np.testing.assert_allclose(d_rot[:, :, 3:], fd_rot, atol=1e-8 * scale)
    assert np.all(d_rot[:, :, :3] == 0.0) and np.all(d_vel[:, :, :3] == 0.0)
    assert np.abs(d_vel).max() > 1.0 and np.abs(d_rot).max() > 1.0


# ---------------------------------------------------------------------- static loads
def _fd_pose(fun, r, R, eps=EPS):
    """(6, 6) central differences of a generalized load along (dr, dtheta)."""
    cols = [(fun(r + d, R) - fun(r - d, R)) / (2 * eps) for d in eps * np.eye(3)]
    cols += list(np.moveaxis(_fd_rotation(lambda Rk: fun(r, Rk), R, eps), -1, 0))
    return np.column_stack(cols)


def test_point_and_gravity_loads():
    rng = np.random.default_rng(8)
    R = _random_rotations(rng, 1)[0]
    f, arm = rng.normal(size=(2, 3))
    load, K = rb.point_load(f, arm, R)
    np.testing.assert_allclose(load, np.concatenate((f, np.cross(R @ arm, f))), atol=1e-15)
    np.testing.assert_allclose(K, -_fd_pose(lambda r, Rk: rb.point_load(f, arm, Rk)[0],
                                            np.zeros(3), R), atol=1e-9)
    load, K = rb.gravity_load(2.0, arm, R, 9.81)
    np.testing.assert_allclose(load[:3], [0, 0, -2.0 * 9.81])
    np.testing.assert_allclose(load[3:], np.cross(R @ arm, [0, 0, -2.0 * 9.81]), atol=1e-14)


def _hull(area, i_wp, height, r, R, rho, g):
    (b, Kb), (w, Kw) = (rb.hull_buoyancy(area, height, r, R, rho, g),
                        rb.waterplane_restoring(i_wp, R, rho, g))
    return b + w, Kb + Kw


@pytest.mark.parametrize("kind", ["box", "cylinder"])
def test_hull_hydrostatics_values_and_tangent(kind):
    rho, g, height = 1025.0, 9.81, 6.0
    area, i_wp = rb.waterplane(kind, length=10.0, width=4.0, diameter=5.0)
    r = np.array([1.0, -2.0, 1.2])  # draft 1.8 m
    R = rb.rotation_matrix([0.05, -0.08, 0.3])

    def load(r, R):
        return _hull(area, i_wp, height, r, R, rho, g)[0]

    value, K = _hull(area, i_wp, height, r, R, rho, g)
    np.testing.assert_allclose(value[2], rho * g * area * 1.8, rtol=1e-14)
    np.testing.assert_allclose(K, -_fd_pose(load, r, R), rtol=0, atol=1e-7 * np.abs(K).max())
    # upright: the buoyancy is on the axis and only the waterplane restoring acts
    value, K = _hull(area, i_wp, height, r, np.eye(3), rho, g)
    np.testing.assert_allclose(value[3:], 0.0, atol=1e-9)
    expected_area = 40.0 if kind == "box" else np.pi * 25.0 / 4.0
    np.testing.assert_allclose(K[2, 2], rho * g * expected_area, rtol=1e-14)
    expected_i = (10.0 * 4.0**3 / 12.0, 4.0 * 10.0**3 / 12.0) if kind == "box" \
        else (np.pi * 5.0**4 / 64.0,) * 2
    np.testing.assert_allclose(np.diag(rb.waterplane_restoring(i_wp, np.eye(3), rho, g)[1]),
                               rho * g * np.array([0, 0, 0, *expected_i, 0.0]), rtol=1e-14)
    # out of the water or fully submerged: no heave stiffness
    for z in (height, -height):
        assert rb.hull_buoyancy(area, height, [0, 0, z], R, rho, g)[1][2, 2] == 0.0


def test_matrix_restoring_and_buoyancy_tangent():
    rng = np.random.default_rng(9)
    A = rng.normal(size=(6, 6))
    S = A @ A.T
    r_ref, r = rng.normal(size=(2, 3))
    R_ref = _random_rotations(rng, 1)[0]
    R = rb.rotation_matrix([0.2, -0.1, 0.3]) @ R_ref
    lift = [0.0, 0.0, 1025.0 * 9.81 * 12.0]
    cob = [0.1, 0.2, -1.0]

    def load(r, R):
        return rb.matrix_restoring(S, r, R, r_ref, R_ref)[0] + rb.point_load(lift, cob, R)[0]

    K = rb.matrix_restoring(S, r, R, r_ref, R_ref)[1] + rb.point_load(lift, cob, R)[1]
    np.testing.assert_allclose(K, -_fd_pose(load, r, R), atol=1e-7 * np.abs(K).max())
    # a small displacement from the reference: -S q to first order
    q = 1e-7 * rng.normal(size=6)
    moved = rb.matrix_restoring(S, r_ref + q[:3], rb.rotation_matrix(q[3:]) @ R_ref, r_ref,
                                R_ref)[0]
    np.testing.assert_allclose(moved, -S @ q, rtol=1e-6)


# ---------------------------------------------------------------------- fluid loads
def test_body_drag_and_tangent():
    rng = np.random.default_rng(10)
    u, v = rng.normal(size=(2, 3, 3))
    area = np.array([1.0, 2.0, 0.5])
    f, dF = rb.body_drag(1025.0, 1.2, area, u, v)
    np.testing.assert_allclose(dF, _fd(lambda q: rb.body_drag(1025.0, 1.2, area, u, q)[0], v),
                               atol=1e-6)
    f0 = rb.body_drag(1000.0, 1.0, [2.0, 0.0, 0.0], [0.0, 0, 0], [-3.0, 1.0, 0.0])[0]
    np.testing.assert_allclose(f0, [9000.0, 0.0, 0.0])  # 1/2 rho Cd A U^2 along +x


def test_long_wave_load():
    A = np.diag([100.0, 200.0, 300.0])
    f = rb.long_wave_load(1000.0, 10.0, 2.0, 3.0, A, [1.0, 0.5, -0.2], 0.4)
    np.testing.assert_allclose(f, [2100.0, 1100.0, -460.0 + 1000.0 * 10.0 * 3.0 * 0.4])


def test_wave_excitation_against_phasors():
    rng = np.random.default_rng(11)
    omegas = np.linspace(0.2, 2.0, 10)
    table_amp = rng.uniform(0, 1e4, (10, 6))
    table_phase = rng.uniform(-180, 180, (10, 6))
    w = np.array([0.2, 0.55, 1.3, 2.0, 2.5])
    amp, phase = rb.exciting_table(omegas, table_amp, table_phase, w)
    np.testing.assert_allclose(amp[0], table_amp[0])
    np.testing.assert_allclose(amp[3], table_amp[-1])
    np.testing.assert_allclose(phase[0], np.radians(table_phase[0]))
    assert np.all(amp[4] == 0.0)  # above the table
    a, shift, t = rng.uniform(0.1, 1.0, 5), rng.uniform(-3, 3, 5), 4.2
    X = amp * np.exp(1j * phase)
    ref = np.real((a[:, None] * X * np.exp(1j * (w * t - shift))[:, None]).sum(axis=0))
    np.testing.assert_allclose(rb.wave_excitation(t, a, w, shift, amp, phase, 0.5), 0.5 * ref,
                               rtol=1e-12, atol=1e-9)


def test_wave_shift_along_the_heading():
    shift = rb.wave_shift([0.1, 0.2], np.radians([0.0, 90.0]), [0.5, -1.0], [30.0, 40.0, -5.0])
    np.testing.assert_allclose(shift, [0.1 * 30.0 + 0.5, 0.2 * 40.0 - 1.0], rtol=1e-14)
