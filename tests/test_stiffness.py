"""Point and rigid-group stiffness by static condensation vs finite differences of re-solved
equilibria (foundation issue, item 7)."""

from dataclasses import replace

import numpy as np
import pytest

from moorline.model import Environment, Line, LineType, Point, StaticsSettings, System
from moorline.solvers.statics import solve_statics
from moorline.solvers.stiffness import group_stiffness, point_stiffness

# straight start on purpose: exercises the step limit and energy line search from slack chords
SETTINGS = StaticsSettings(tolerance=1e-10, max_iterations=300, start="straight")


def _system(**positions) -> System:
    """Two fairleads F1, F2 held by lines through free buoyed junctions to seabed anchors."""
    lt = LineType("rope", diameter=0.05, mass_per_length=8.0, EA=2.0e6)
    pts = {
        "A1": Point("A1", "fixed", (-300.0, -20.0, -100.0)),
        "A2": Point("A2", "fixed", (300.0, 30.0, -100.0)),
        "J1": Point("J1", "free", (-150.0, -10.0, -60.0), volume=0.05),
        "J2": Point("J2", "free", (150.0, 15.0, -60.0), force=(0.0, 0.0, 300.0)),
        "F1": Point("F1", "prescribed", positions.get("F1", (-10.0, 0.0, -5.0))),
        "F2": Point("F2", "prescribed", positions.get("F2", (10.0, 5.0, -5.0))),
    }
    lines = {
        "a1": Line("a1", "rope", 180.0, 12, "A1", "J1"),
        "b1": Line("b1", "rope", 160.0, 12, "J1", "F1"),
        "a2": Line("a2", "rope", 180.0, 12, "A2", "J2"),
        "b2": Line("b2", "rope", 160.0, 12, "J2", "F2"),
    }
    env = Environment(depth=100.0)
    return System("stiff", environment=env, line_types={"rope": lt}, points=pts, lines=lines)


def _reaction(result, system, point):
    total = np.zeros(3)
    for name, line in system.lines.items():
        if line.end_a == point:
            total += result.end_force(name, "a")
        if line.end_b == point:
            total += result.end_force(name, "b")
    return total


@pytest.fixture(scope="module")
def base():
    system = _system()
    result = solve_statics(system, SETTINGS)
    assert result.success, result.message
    return system, result


def test_prescribed_point_stiffness_matches_finite_differences(base):
    system, result = base
    K = point_stiffness(result, "F1")
    h = 1e-3
    K_fd = np.zeros((3, 3))
    for j in range(3):
        forces = []
        for sign in (1, -1):
            pos = np.array(system.points["F1"].position)
            pos[j] += sign * h
            sys_j = _system(F1=tuple(pos))
            r = solve_statics(sys_j, SETTINGS, initial=result.positions)
            assert r.success
            forces.append(_reaction(r, sys_j, "F1"))
        K_fd[:, j] = -(forces[0] - forces[1]) / (2 * h)
    assert np.allclose(K, K_fd, rtol=1e-4, atol=1e-4 * np.abs(K).max())


def test_free_point_stiffness_is_the_inverse_compliance(base):
    system, result = base
    K = point_stiffness(result, "J2")
    dF = 1e-2
    C_fd = np.zeros((3, 3))
    for j in range(3):
        moves = []
        for sign in (1, -1):
            f = np.array(system.points["J2"].force)
            f[j] += sign * dF
            pts = dict(system.points)
            pts["J2"] = replace(pts["J2"], force=tuple(f))
            r = solve_statics(replace(system, points=pts), SETTINGS, initial=result.positions)
            moves.append(r.point_position("J2"))
        C_fd[:, j] = (moves[0] - moves[1]) / (2 * dF)
    assert np.allclose(K @ C_fd, np.eye(3), atol=1e-4)


def test_rigid_group_stiffness_matches_finite_differences(base):
    system, result = base
    ref = np.array([0.0, 2.0, -5.0])
    K6 = group_stiffness(result, ["F1", "F2"], ref)
    arms = {p: np.array(system.points[p].position) - ref for p in ("F1", "F2")}
    h = 1e-4

    def generalized_force(q):
        rot = _rotation(q[3:])
        new = {p: tuple(ref + q[:3] + rot @ a) for p, a in arms.items()}
        sys_q = _system(**new)
        r = solve_statics(sys_q, SETTINGS, initial=result.positions)
        assert r.success
        F, M = np.zeros(3), np.zeros(3)
        for p in arms:
            f = _reaction(r, sys_q, p)
            F += f
            M += np.cross(np.array(new[p]) - (ref + q[:3]), f)
        return np.concatenate((F, M))

    K_fd = np.zeros((6, 6))
    for j in range(6):
        dq = np.zeros(6)
        dq[j] = h
        K_fd[:, j] = -(generalized_force(dq) - generalized_force(-dq)) / (2 * h)
    np.set_printoptions(precision=4, linewidth=150)
    assert np.allclose(K6, K_fd, rtol=1e-4, atol=1e-4 * np.abs(K6).max()), (K6 - K_fd)


def _rotation(v):
    """Rodrigues rotation matrix of a rotation vector."""
    angle = np.linalg.norm(v)
    if angle == 0:
        return np.eye(3)
    k = v / angle
    Kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + np.sin(angle) * Kx + (1 - np.cos(angle)) * Kx @ Kx
