"""Rigid bodies coupled to lines in statics: equilibrium, the exact coupled tangent and the
body's 6x6 mooring stiffness against finite differences of re-solved equilibria."""

from dataclasses import replace

import numpy as np
import pytest

from moorline.mesh import discretize, rotation_matrix
from moorline.model import Body, Environment, Hydrostatics, Line, LineType, Point, System
from moorline.solvers.bodies import BodyState, place_slaves
from moorline.solvers.coupled_statics import CoupledStatics
from moorline.solvers.initial_shape import initial_positions
from moorline.solvers.statics import solve_statics
from moorline.solvers.stiffness import group_stiffness

RHO, G = 1025.0, 9.81


def box_system(kind="free", position=(0.0, 0.0, 1.7), rotation=(0.0, 0.0, 0.0)) -> System:
    """A 26 x 10 x 5 m box (Wang, Er and Iu) on four taut-ish steel lines."""
    lt = LineType("steel", diameter=0.1, mass_per_length=8000 * np.pi / 4 * 0.01,
                  EA=2e11 * np.pi / 4 * 0.01, Cd=1.2)
    body = Body("box", kind=kind, position=position, rotation=rotation, mass=1.2e5,
                center_of_gravity=(0.3, -0.2, -0.5),
                inertia=((1.0e6, 0, 0), (0, 6.0e6, 0), (0, 0, 7.0e6)),
                hydrostatics=Hydrostatics("box", length=26.0, width=10.0, height=5.0),
                force=(2.0e4, 5.0e3, 0.0, 0.0, 0.0, 1.0e4))
    points, lines = {}, {}
    span = 99.1 / np.tan(np.radians(50))
    for k, (sx, sy) in enumerate([(1, 1), (-1, 1), (-1, -1), (1, -1)]):
        points[f"f{k}"] = Point(f"f{k}", "body", (13.0 * sx, 5.0 * sy, -2.5), body="box")
        points[f"a{k}"] = Point(f"a{k}", "fixed", (13.0 * sx + sx * span, 5.0 * sy + sy * 20,
                                                   -100.0))
        lines[f"l{k}"] = Line(f"l{k}", "steel", 130.0, 11, f"a{k}", f"f{k}")
    env = Environment(depth=100.0, water_density=RHO, gravity=G)
    return System("box", environment=env, line_types={"steel": lt}, points=points, lines=lines,
                  bodies={"box": body})


@pytest.fixture(scope="module")
def floating():
    result = solve_statics(box_system())
    assert result.success, result.message
    return result


def test_free_body_is_in_equilibrium_with_its_lines(floating):
    system = box_system()
    r, rv = floating.body_position("box"), floating.body_rotation("box")
    body = system.bodies["box"]
    # independent balance: buoyancy of the (nearly level) box vs weight, loads and lines
    lines = sum(floating.end_force(f"l{k}", "b") for k in range(4))
    draft = 2.5 - r[2]
    buoyancy = RHO * G * 26 * 10 * draft
    assert abs(rv).max() < 0.05
    assert lines[2] + buoyancy - body.mass * G == pytest.approx(0.0, abs=1e-3 * body.mass * G)
    assert lines[0] + body.force[0] == pytest.approx(0.0, abs=1e-6 * body.mass * G)
    assert lines[1] + body.force[1] == pytest.approx(0.0, abs=1e-6 * body.mass * G)


def test_coupled_tangent_matches_finite_differences(floating):
    system = box_system()
    mesh = discretize(system)
    problem = CoupledStatics(mesh)
    rng = np.random.default_rng(2)
    poses = BodyState.initial(mesh)
    poses = poses.moved(np.array([[0.3, -0.2, 0.05]]), np.array([[0.02, -0.03, 0.05]]))
    x = place_slaves(mesh, poses, initial_positions(system, mesh))
    x[mesh.free_nodes] += rng.normal(scale=0.05, size=x[mesh.free_nodes].shape)
    R, state = problem.residual(x, poses)
    K = problem.tangent(x, poses, state).toarray()
    fd = np.zeros_like(K)
    h = 1e-6
    for j in range(problem.n_unknowns):
        du = np.zeros(problem.n_unknowns)
        du[j] = h
        rp = problem.residual(*problem.update(x, poses, du))[0]
        rm = problem.residual(*problem.update(x, poses, -du))[0]
        fd[:, j] = -(rp - rm) / (2 * h)
    bad = np.argwhere(~np.isclose(K, fd, rtol=1e-4, atol=1e-5 * np.abs(K).max()))
    assert not len(bad), [(i, j, K[i, j], fd[i, j]) for i, j in bad[:6]]


def _line_wrench(system: System, result, reference):
    """Force and moment about ``reference`` the lines exert on the body's points."""
    F, M = np.zeros(3), np.zeros(3)
    for k in range(4):
        f = result.end_force(f"l{k}", "b")
        F += f
        M += np.cross(result.point_position(f"f{k}") - reference, f)
    return np.concatenate((F, M))


def test_body_mooring_stiffness_matches_finite_differences(floating):
    """6x6 mooring stiffness (lines only) at the equilibrium, against re-solved equilibria of
    the lines with the body held at perturbed poses; 1e-4 relative (foundation + bodies
    issue)."""
    r0, rv0 = floating.body_position("box"), floating.body_rotation("box")
    held = box_system("fixed", tuple(r0), tuple(rv0))
    base = solve_statics(held)
    assert np.allclose(base.positions, floating.positions, atol=1e-6)
    names = [f"f{k}" for k in range(4)]
    K6 = group_stiffness(base, names, r0)
    R0 = rotation_matrix(rv0)
    h = np.array([1e-3] * 3 + [1e-5] * 3)
    fd = np.zeros((6, 6))
    for j in range(6):
        wrench = []
        for sign in (1, -1):
            dq = np.zeros(6)
            dq[j] = sign * h[j]
            R = rotation_matrix(dq[3:]) @ R0
            from moorline.solvers.bodies import rotation_vector

            system = box_system("fixed", tuple(r0 + dq[:3]), tuple(rotation_vector(R)))
            res = solve_statics(system, initial=base.positions)
            assert res.success
            wrench.append(_line_wrench(system, res, r0 + dq[:3]))
        fd[:, j] = -(wrench[0] - wrench[1]) / (2 * h[j])
    assert np.allclose(K6, fd, rtol=1e-4, atol=1e-4 * np.abs(K6).max())


def test_fixed_body_points_follow_the_pose():
    system = box_system("fixed", (1.0, 2.0, 1.5), (0.0, 0.1, 0.2))
    mesh = discretize(system)
    R = rotation_matrix(np.array([0.0, 0.1, 0.2]))
    node = mesh.point_node[mesh.point_index("f0")]
    assert np.allclose(mesh.node_position[node], np.array([1.0, 2.0, 1.5]) + R @ [13, 5, -2.5])
    result = solve_statics(replace(system))
    assert result.success


def test_small_rotations_reduce_to_the_linear_small_angle_form(floating):
    """The rotation-vector statics under a small extra moment matches the small-rotation
    (linear) form of the sources, K6 dq = dF, with K6 the lines' condensed stiffness plus the
    body's hydrostatic and gravity stiffness; to second order in the angle."""
    from moorline.solvers.bodies import body_loads
    from moorline.solvers.stiffness import group_stiffness

    base_system = box_system()
    body = base_system.bodies["box"]
    r0 = floating.body_position("box")
    R0 = rotation_matrix(floating.body_rotation("box"))
    K6 = group_stiffness(floating, [f"f{k}" for k in range(4)], r0)
    K6 += body_loads(body, r0, R0, G, RHO)[1]
    extra = np.array([0.0, 0.0, 0.0, 0.0, 2.0e5, 0.0])  # a pitch moment about the origin
    pushed = replace(body, force=tuple(np.asarray(body.force) + extra))
    result = solve_statics(replace(base_system, bodies={"box": pushed}),
                           initial=floating.positions)
    assert result.success, result.message
    dq = np.concatenate((result.body_position("box") - r0,
                         result.body_rotation("box") - floating.body_rotation("box")))
    linear = np.linalg.solve(K6, extra)
    assert dq[4] == pytest.approx(linear[4], rel=0.02)
    assert np.abs(dq[4]) < 0.01  # small: the linear form applies


def test_free_body_on_one_single_element_line() -> None:
    """A buoy held by one single-element line (no free line node: the line statics has no
    unknowns, which crashed the banded factorization): the body rises until the element's
    tension carries its net buoyancy less the half element's weight lumped on it."""
    from moorline.model import Seabed

    env = Environment(depth=100.0, water_density=1025.0, gravity=9.80665,
                      seabed=Seabed(3e6, 0.0, 0.0))
    lt = LineType("rope", diameter=0.05, mass_per_length=5.0, EA=1e7)
    body = Body("buoy", kind="free", position=(0.0, 0.0, -50.0), mass=1000.0,
                inertia=((100.0, 0, 0), (0, 100.0, 0), (0, 0, 100.0)),
                hydrostatics=Hydrostatics(kind="matrix", stiffness=((0.0,) * 6,) * 6,
                                          volume=3.0))
    points = {"anchor": Point("anchor", "fixed", (0.0, 0.0, -100.0)),
              "top": Point("top", "body", (0.0, 0.0, 0.0), body="buoy")}
    system = System("one", environment=env, line_types={"rope": lt}, points=points,
                    lines={"l": Line("l", "rope", 49.0, 1, "anchor", "top")},
                    bodies={"buoy": body})
    result = solve_statics(system)
    assert result.success, result.message
    g = 9.80665
    w = (5.0 - 1025.0 * lt.area_displaced) * g
    tension = (1025.0 * 3.0 - 1000.0) * g - 0.5 * w * 49.0
    z = -100.0 + 49.0 * (1.0 + tension / 1e7)
    assert result.body_pose[0, 2] == pytest.approx(z, abs=1e-9)
