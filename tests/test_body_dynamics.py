"""Rigid bodies in dynamics: free decay on linear springs against the analytic frequency, and
a forced response that settles to the forcing period."""

import numpy as np
import pytest

from moorline.model import (
    Body,
    DynamicsSettings,
    Environment,
    Hydrostatics,
    Line,
    LineType,
    Motion,
    Point,
    System,
)
from moorline.solvers.dynamics import simulate
from moorline.solvers.statics import solve_statics

MASS, ADDED, K_HYDRO, EA, LENGTH, F0 = 2.0e4, 5.0e3, 4.0e5, 2.0e6, 50.0, 2.0e4


def spring_body(push: float) -> System:
    """A body on a linear heave spring (hydrostatic matrix) and four vertical massless taut
    lines (axial springs EA/L), pushed down by a constant force ``push``."""
    lt = LineType("rope", diameter=0.05, mass_per_length=0.0, EA=EA, displaced_area=0.0,
                  Cd=0.0, Ca=0.0, Ct=0.0)
    stiffness = np.zeros((6, 6))
    stiffness[2, 2] = K_HYDRO
    stiffness[3, 3] = stiffness[4, 4] = stiffness[5, 5] = 1.0e7
    stiffness[0, 0] = stiffness[1, 1] = 1.0e5
    added = np.zeros((6, 6))
    added[2, 2] = ADDED
    # buoyancy balances weight + line pretension (lines 0.1 % stretched)
    pre = 4 * EA * 1e-3
    body = Body("b", position=(0.0, 0.0, 0.0), mass=MASS,
                inertia=((1e5, 0, 0), (0, 1e5, 0), (0, 0, 1e5)),
                added_mass=tuple(map(tuple, added)),
                hydrostatics=Hydrostatics("matrix", stiffness=tuple(map(tuple, stiffness)),
                                          volume=(MASS * 9.81 + pre) / (1025 * 9.81)),
                force=(0.0, 0.0, -push, 0.0, 0.0, 0.0),
                force_history=Motion("table", times=(0.0, 1e6),
                                     values=((0.0, 0.0, push), (0.0, 0.0, push))))
    points, lines = {}, {}
    for k, (x, y) in enumerate([(2, 2), (-2, 2), (-2, -2), (2, -2)]):
        points[f"p{k}"] = Point(f"p{k}", "body", (x, y, 0.0), body="b")
        points[f"a{k}"] = Point(f"a{k}", "fixed", (x, y, -LENGTH * 1.001))
        lines[f"l{k}"] = Line(f"l{k}", "rope", LENGTH, 4, f"a{k}", f"p{k}")
    env = Environment(water_density=1025.0, gravity=9.81)
    return System("spring", environment=env, line_types={"rope": lt}, points=points,
                  lines=lines, bodies={"b": body})


def test_free_decay_frequency_matches_the_analytic_one():
    system = spring_body(F0)
    start = solve_statics(system)
    assert start.success, start.message
    k = K_HYDRO + 4 * EA / LENGTH  # heave: hydrostatic spring plus four axial springs
    omega = np.sqrt(k / (MASS + ADDED))
    period = 2 * np.pi / omega
    dt = period / 100
    result = simulate(system, DynamicsSettings(duration=6 * period, dt=dt, tolerance=1e-9),
                      initial=start, output_every=dt)
    z = result.body_history("b")[:, 2]
    z = z - z.mean()
    i = np.flatnonzero((z[:-1] < 0) & (z[1:] >= 0))
    crossings = result.time[i] - z[i] * dt / (z[i + 1] - z[i])
    measured = float(np.mean(np.diff(crossings)))
    # Newmark's period elongation at omega dt = 2 pi / 100 is ~0.03 %, inside the tolerance
    assert measured == pytest.approx(period, rel=5e-3)
    amplitude = F0 / k
    assert np.abs(z).max() == pytest.approx(amplitude, rel=2e-2)


def test_floating_cylinder_follows_a_long_wave():
    """A small floating cylinder with long-wave loads in a 20 s Airy wave heaves with the
    wave: the amplitude of the linear heave oscillator ``rho g A eta / |k - m w^2 + i B w|``,
    within 5 % (the fluid acceleration term, the exponential decay over the draft and the
    light mooring line make the rest)."""
    from moorline.model import Waves

    d, h = 4.0, 4.0
    area = np.pi * d**2 / 4
    mass = 1025 * area * 2.0  # draft 2 m
    lt = LineType("rope", diameter=0.02, mass_per_length=1.0, EA=1e6, Cd=1.0, Ca=0.0, Ct=0.0)
    body = Body("buoy", position=(0.0, 0.0, 0.0), mass=mass,
                center_of_gravity=(0.0, 0.0, -1.5),  # ballasted: stable in pitch and roll
                inertia=((5e4, 0, 0), (0, 5e4, 0), (0, 0, 5e4)),
                # radiation damping (an undamped body keeps its start-up transients forever)
                damping=tuple(tuple(v if i == j else 0.0 for j in range(6))
                              for i, v in enumerate([3e3, 3e3, 1e4, 3e4, 3e4, 3e3])),
                hydrostatics=Hydrostatics("cylinder", diameter=d, height=h), wave_loads=True,
                force=(2000.0, 0.0, 0.0, 0.0, 0.0, 0.0))  # a wind load holds the line out
    points = {"anchor": Point("anchor", "fixed", (-60.0, 0.0, -50.0)),
              "pad": Point("pad", "body", (0.0, 0.0, -2.0), body="buoy")}
    lines = {"rope": Line("rope", "rope", 85.0, 6, "anchor", "pad")}
    env = Environment(depth=50.0, water_density=1025.0, gravity=9.81,
                      waves=Waves(kind="airy", height=1.0, period=20.0))
    system = System("heave", environment=env, line_types={"rope": lt}, points=points,
                    lines=lines, bodies={"buoy": body})
    start = solve_statics(system)
    assert start.success, start.message
    result = simulate(system, DynamicsSettings(duration=120.0, dt=0.1, ramp_time=20.0),
                      initial=start, output_every=0.1)
    z = result.body_history("buoy")[:, 2]
    late = result.time > 60.0
    amplitude = 0.5 * (z[late].max() - z[late].min())
    omega, k = 2 * np.pi / 20.0, 1025 * 9.81 * area
    expected = 0.5 * k / abs(k - mass * omega**2 + 1j * 1e4 * omega)
    assert amplitude == pytest.approx(expected, rel=5e-2)


def test_wave_excitation_table_drives_the_linear_heave_response():
    """A body with a heave exciting-force table (per unit wave amplitude, interpolated at the
    wave frequency) responds with ``a |X3| / |k - (m + A) w^2 + i B w|`` in steady state."""
    from moorline.model import WaveExcitation, Waves

    lt = LineType("rope", diameter=0.02, mass_per_length=0.0, EA=1e5, displaced_area=0.0,
                  Cd=0.0, Ca=0.0, Ct=0.0)
    k_heave, mass, added, damping, x3 = 4.0e5, 2.0e4, 5.0e3, 2.0e4, 3.0e5
    stiffness = np.diag([1e5, 1e5, k_heave, 1e7, 1e7, 1e7])
    table = WaveExcitation(omegas=(0.5, 1.5),
                           amplitude=((0.0, 0.0, x3, 0.0, 0.0, 0.0),) * 2,
                           phase_deg=((0.0,) * 6,) * 2)
    body = Body("b", position=(0.0, 0.0, 0.0), mass=mass,
                inertia=((1e5, 0, 0), (0, 1e5, 0), (0, 0, 1e5)),
                added_mass=tuple(map(tuple, np.diag([0, 0, added, 0, 0, 0]))),
                damping=tuple(map(tuple, np.diag([1e4, 1e4, damping, 1e5, 1e5, 1e5]))),
                hydrostatics=Hydrostatics("matrix", stiffness=tuple(map(tuple, stiffness)),
                                          volume=mass / 1025),
                excitation=table)
    points = {"a": Point("a", "fixed", (0.0, 0.0, -30.0)),
              "p": Point("p", "body", (0.0, 0.0, 0.0), body="b")}
    lines = {"l": Line("l", "rope", 35.0, 2, "a", "p")}  # slack: carries nothing
    env = Environment(depth=30.0, water_density=1025.0, gravity=9.81,
                      waves=Waves(kind="airy", height=2.0, period=2 * np.pi))
    system = System("exc", environment=env, line_types={"rope": lt}, points=points,
                    lines=lines, bodies={"b": body})
    start = solve_statics(system)
    result = simulate(system, DynamicsSettings(duration=60.0, dt=0.05, ramp_time=10.0),
                      initial=start, output_every=0.05)
    z = result.body_history("b")[:, 2]
    late = result.time > 40.0
    amplitude = 0.5 * (z[late].max() - z[late].min())
    expected = 1.0 * x3 / abs(k_heave - (mass + added) * 1.0**2 + 1j * damping * 1.0)
    assert amplitude == pytest.approx(expected, rel=0.02)


def test_exciting_force_phases_refer_to_the_static_pose():
    """The time stepper's exciting force of a table is the wave's at the body's static
    position (where the run starts), not at the position the case file gives."""
    from dataclasses import replace

    from moorline.model import WaveExcitation
    from moorline.solvers.dynamic_model import DynamicModel
    from moorline.solvers.dynamics import _fluid, _initial_state, _stepper
    from moorline.solvers.excitation import Excitation
    from moorline.verification import tuah_ex5

    system, static = tuah_ex5.static_state(3)
    table = WaveExcitation(omegas=(0.5, 3.0), amplitude=((1e3,) * 6, (1e3,) * 6),
                           phase_deg=((30.0,) * 6, (30.0,) * 6))
    body = replace(system.bodies[tuah_ex5.BODY], excitation=table, force_history=None)
    system = replace(system, bodies={tuah_ex5.BODY: body})
    x_static = float(static.body_pose[0, 0])
    assert abs(x_static - body.position[0]) > 1.0  # the mooring moves the body
    settings = DynamicsSettings(duration=1.0, dt=0.05)
    fluid = _fluid(system, settings)
    model = DynamicModel(static.mesh, fluid)
    exc = Excitation(static.mesh, static.positions)
    state = _initial_state(model, exc, static.positions, settings.dt, initial=static)
    stepper = _stepper(model, fluid, settings, 1e-6, system, state)
    from moorline.solvers.excitation import ramp

    wave = fluid.wave if hasattr(fluid, "wave") else fluid
    assert float(getattr(wave, "phase", 0.0)) == 0.0
    t = 0.7
    got = stepper.bodies._excitation(body, 0, t)
    k, w = wave.wave_number, wave.omega
    # eta = a cos(k x - w t): the force's phase is the wave's at the static x, plus 30 deg
    expected = wave.amplitude * 1e3 * np.cos(w * t - k * x_static + np.radians(30.0))
    factor = ramp(t, float(getattr(wave, "ramp_time", 0.0)))[0]
    np.testing.assert_allclose(got, factor * expected, rtol=1e-12)
