"""A body with ``rods`` hydrostatics in the compiled step and loop (the rods' buoyancy at each
pose, moorline.solvers.fast_rigid.rods_load) against the general stepper
(moorline.solvers.newmark.Stepper with moorline.physics.rod_buoyancy, an independent code):
the compiled static loads and tangent equal the numpy ones at random poses, a forced run
gives the same states, and the compiled border matches finite differences."""


from dataclasses import replace

import numpy as np
import pytest
from test_fast_bodies import _runs, assert_border_matches_differences, moving_body

from moorline.model import (
    Body,
    Current,
    DynamicsSettings,
    Environment,
    Hydrostatics,
    Line,
    LineType,
    Motion,
    Point,
    System,
)
from moorline.solvers import dynamics
from moorline.solvers.statics import solve_statics

PIERCING = ((0.0, 0.0, -10.0), (0.0, 0.0, 4.0), 3.0)  # (end A, end B, diameter) [m]
SUBMERGED = ((-5.0, -1.0, -14.0), (5.0, 2.0, -12.0), 1.0)


def rod_buoy(shift: float = 0.0, drag: bool = False, current: float = 0.0) -> System:
    """A floater of two rods (a vertical column piercing the surface, a tilted pontoon fully
    under it) and a small constant buoyancy at an offset centre, on three chains, pushed by
    a harmonic force (it surges, heaves, pitches and rolls; both rods stay as they are).
    ``shift``: every body-frame point that much higher [m] (the origin as much lower in the
    water); ``drag``: drag areas on the body; ``current``: a uniform current [m/s]."""

    def up(p):
        return (p[0], p[1], p[2] + shift)

    chain = LineType("chain", diameter=0.07, mass_per_length=20.0, EA=4.0e8, Cd=1.4,
                     Ca=1.0, Ct=0.05)
    body = Body("float", position=(0.0, 0.0, 0.0), mass=3.6e4,
                center_of_gravity=up((0.2, -0.1, -12.0)),
                inertia=((2e6, 1e4, 0.0), (1e4, 2e6, 0.0), (0.0, 0.0, 3e5)),
                added_mass=tuple(map(tuple, np.diag([3e4, 3e4, 1e4, 1e6, 1e6, 1e5]))),
                damping=tuple(map(tuple, np.diag([2e4, 2e4, 2e4, 5e5, 5e5, 5e4]))),
                hydrostatics=Hydrostatics("rods", volume=1.0,
                                          center_of_buoyancy=up((0.5, 0.0, -3.0)),
                                          rods=tuple((up(a), up(b), d)
                                                     for a, b, d in (PIERCING, SUBMERGED))),
                drag_area=(30.0, 25.0, 10.0) if drag else (0.0, 0.0, 0.0), Cd=1.1,
                force_history=Motion("harmonic", amplitude=(4e4, 2e4, 2e4), period=5.0))
    points, lines = {}, {}
    for k in range(3):
        angle = 2 * np.pi * k / 3 + 0.3
        c, s = np.cos(angle), np.sin(angle)
        points[f"f{k}"] = Point(f"f{k}", "body", up((c, s, -8.0)), body="float")
        points[f"a{k}"] = Point(f"a{k}", "fixed", (250 * c, 250 * s, -80.0))
        lines[f"l{k}"] = Line(f"l{k}", "chain", 280.0, 14, f"a{k}", f"f{k}")
    env = Environment(depth=80.0, water_density=1025.0, gravity=9.81,
                      current=Current(speed=current, heading_deg=30.0))
    return System("rods", environment=env, line_types={"chain": chain}, points=points,
                  lines=lines, bodies={"float": body})


def test_compiled_rod_loads_are_rod_buoyancys():
    """:func:`fast_rigid.static_load` of a rods body equals :func:`bodies.body_loads` (with
    :func:`rod_buoyancy.rod_buoyancy`) to round-off at poses with the column piercing the
    surface upright, tilted, tilted past the waterline's cap (nearly horizontal), and with
    the column wet or dry at either end."""
    from moorline.mesh import discretize
    from moorline.physics.rigid_body import rotation_matrix
    from moorline.solvers.bodies import body_loads
    from moorline.solvers.body_model import BodyModel
    from moorline.solvers.fast_body_inputs import BodyInputs
    from moorline.solvers.fast_rigid import static_load

    system = rod_buoy()
    body = system.bodies["float"]
    mesh = discretize(system)
    loads = BodyInputs(BodyModel(mesh, None), mesh, 1).loads
    rng = np.random.default_rng(5)
    poses = [((0.0, 0.0, 0.3), (0.0, 0.0, 0.0)), ((0.5, -0.2, 1.0), (0.3, -0.2, 0.1)),
             ((0.0, 0.0, 0.0), (1.45, 0.2, 0.0)), ((0.0, 0.0, -2.0), (np.pi - 0.3, 0.1, 0.0)),
             ((1.0, 2.0, 30.0), (0.1, 0.0, 0.0)), ((0.0, 0.0, -30.0), (0.1, 0.2, 0.3))]
    poses += [(rng.normal(size=3), rng.normal(size=3) * 0.5) for _ in range(6)]
    for r, turn in poses:
        r, R = np.asarray(r, float), rotation_matrix(np.asarray(turn, float))
        load, K = body_loads(body, r, R, 9.81, 1025.0)
        mine = np.zeros((6, 6))
        got = static_load(0, loads, r, R, mine)
        assert np.allclose(got, load, rtol=0, atol=1e-12 * np.abs(load).max())
        assert np.allclose(mine, K, rtol=0, atol=1e-12 * np.abs(K).max())


DRAGGED = {"shift": 8.0, "drag": True, "current": 0.8}
"""The floater's origin 2.6 m under water, with drag, in a 0.8 m/s current."""


@pytest.mark.parametrize("scheme,variant", [("newmark", {}), ("hht", {}),
                                            ("newmark", DRAGGED), ("hht", DRAGGED)])
def test_compiled_rods_body_equals_the_general_stepper(scheme, variant, monkeypatch):
    """Over 6 s (120 steps) of the forced floater (and with drag in a current): the compiled
    loop runs it, with the same poses (1e-9 of its size), velocities, lines' forces on it and
    line results as the general stepper, the same iterations and factorizations; the column
    pierces the surface and the pontoon stays under it throughout (the dragged origin
    under water)."""
    from backends import assert_same_bodies, assert_same_run

    from moorline.physics.rigid_body import rotation_matrix

    system = rod_buoy(**variant)
    settings = DynamicsSettings(duration=6.0, dt=0.05, ramp_time=2.0, scheme=scheme,
                                alpha=-0.1)
    start = solve_statics(system)
    assert type(dynamics.start(system, settings, start)[-1]).__name__ == "FastStepper"
    fast, slow = _runs(system, settings, monkeypatch)
    assert_same_run(fast, slow)
    pose = slow.body_pose[:, 0]
    assert np.abs(pose[:, 3:5]).max() > 1e-3  # it pitched and rolled
    assert np.abs(pose[:, 2] - pose[0, 2]).max() > 1e-2  # and heaved
    R = rotation_matrix(pose[:, 3:])
    if variant:
        assert pose[:, 2].max() < -1.0
    rods = system.bodies["float"].hydrostatics.rods
    for (a, b, _), wet in zip(rods, ((True, False), (True, True)), strict=True):
        za = pose[:, 2] + R[:, 2] @ np.asarray(a)
        zb = pose[:, 2] + R[:, 2] @ np.asarray(b)
        assert np.all((za < 0) == wet[0]) and np.all((zb < 0) == wet[1])
    assert_same_bodies(fast, slow, 15.0)


@pytest.mark.parametrize("scheme,variant", [("newmark", {}), ("hht", {}),
                                            ("newmark", DRAGGED), ("hht", DRAGGED)])
def test_compiled_rods_tangent_matches_finite_differences(scheme, variant):
    """The border of the compiled effective tangent of the floater (the rods' buoyancy
    moving along the column with heave and tilt, its waterplane couple, the pontoon's
    buoyancy turning with the body; the drag's damping on the relative velocity) against
    central differences of the compiled residual at a finite body step (0.18 rad, 0.2 m),
    within 1e-7 of each column's largest entry (steps of 1e-5: the moment rows' round-off,
    ~1e-16 of their 1e8 N m over the step, stays below the line columns' 1e-7 of 1e5 N/m)."""
    stepper, _, _, _, residual, tangent, u = moving_body(rod_buoy(**variant), scheme)
    assert_border_matches_differences(stepper.lu.shape[0], residual, tangent, u, 1e-5)


def test_body_drag_in_waves_or_a_sheared_current_keeps_the_general_stepper():
    """Body drag runs compiled in still water or a uniform current, not in waves or a
    current that changes over depth (the fluid velocity at the body origin would move with
    it)."""
    from moorline.model import Current, Waves

    system = rod_buoy(**DRAGGED)
    wavy = replace(system, environment=replace(system.environment,
                                               waves=Waves(kind="airy", height=2.0,
                                                           period=8.0)))
    sheared = replace(system, environment=replace(
        system.environment, current=Current(z_levels=(-50.0, 0.0), speeds=(0.2, 0.8),
                                            headings_deg=(0.0, 0.0))))
    settings = DynamicsSettings(duration=1.0, dt=0.05)
    for case, kind in ((system, "FastStepper"), (wavy, "Stepper"), (sheared, "Stepper")):
        stepper = dynamics.start(case, settings, solve_statics(case))[-1]
        assert type(stepper).__name__ == kind
