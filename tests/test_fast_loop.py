"""The compiled time loop (moorline.solvers.fast_loop) against the same compiled step called
once per step from Python: the same records, bit for bit, and the same work, on cases with step
cuts (where the loop hands a step to Python and resumes), sub-stepping, a ramped current with
friction, a table motion and a point force history. Both paths against the general stepper:
tests/test_fast_newmark.py."""

import numpy as np
import pytest
from backends import assert_same_run, reference_run

from moorline.model import (
    Current,
    DynamicsSettings,
    Environment,
    Line,
    LineType,
    Motion,
    Point,
    Seabed,
    System,
)
from moorline.solvers import dynamics
from moorline.solvers.dynamics import simulate
from moorline.solvers.statics import solve_statics
from moorline.verification.oc3_system import oc3_three_lines


def _buoy_system() -> System:
    """Two chains to a fairlead moved by a table, a free buoy with a force history on one of
    them, a ramped current and seabed friction."""
    lt = LineType("chain", diameter=0.09, mass_per_length=77.7, EA=3.8e8, Cd=1.6, Ct=0.05,
                  Ca=1.0, Cat=0.1, BA=-0.8)
    table = Motion("table", times=(0.0, 2.0, 5.0, 9.0), values=(0.0, 0.0, 0.0, 3.0, 1.0, 0.0,
                                                                -2.0, 0.0, 1.0, 0.0, 0.0, 0.0))
    push = Motion("harmonic", amplitude=(3e4, 0.0, 1e4), period=3.0, ramp_time=2.0)
    points = {
        "a1": Point("a1", "fixed", (-450.0, 0.0, -150.0)),
        "a2": Point("a2", "fixed", (300.0, 300.0, -150.0)),
        "f": Point("f", "prescribed", (0.0, 0.0, -20.0), motion=table),
        "b": Point("b", "free", (-200.0, 20.0, -100.0), mass=2e3, force_history=push),
    }
    lines = {"l1": Line("l1", "chain", 300.0, 8, "a1", "b"),
             "l2": Line("l2", "chain", 250.0, 6, "b", "f"),
             "l3": Line("l3", "chain", 470.0, 10, "a2", "f")}
    env = Environment(depth=150.0, seabed=Seabed(friction=0.5, slip_velocity=0.05),
                      current=Current(speed=0.8, heading_deg=30.0))
    return System("buoy", environment=env, line_types={"chain": lt}, points=points,
                  lines=lines)


def _viscoelastic_oc3() -> System:
    """The OC3 lines of a standard linear solid: the chain's ``EA`` long-term, a Maxwell
    branch of half of it relaxing in 3 s (exponential update; the grounded elements slack)."""
    from dataclasses import replace

    system = oc3_three_lines(40, BA=6.2358e6)
    chain = system.line_types["chain"]
    return replace(system, line_types={"chain": replace(
        chain, material="viscoelastic", EA1=0.5 * chain.EA, tau=3.0)})


CASES = {
    # OC3, fairleads surging 5 m at 10 s (the benchmark P1), at most 5 iterations a step: 30
    # step cuts in 30 s (with the default 20, none)
    "oc3_surge": (lambda: oc3_three_lines(40, BA=6.2358e6),
                  dict(duration=30.0, dt=0.05, max_iterations=5), 0.05),
    # the same with viscoelastic lines: 28 step cuts
    "oc3_surge_viscoelastic": (_viscoelastic_oc3, dict(duration=30.0, dt=0.05,
                                                       max_iterations=5), 0.05),
    "buoy_current_table": (_buoy_system, dict(duration=10.0, dt=0.05, ramp_time=3.0), 0.1),
}


@pytest.mark.parametrize("name", CASES)
def test_compiled_loop_gives_the_records_of_the_step_by_step_loop(name, monkeypatch):
    make, settings, every = CASES[name]
    system = make()
    start = solve_statics(system)
    assert start.success, start.message
    runs = []
    for compiled in (True, False):
        monkeypatch.setattr(dynamics, "COMPILED_LOOP", compiled)
        runs.append(simulate(system, DynamicsSettings(**settings), initial=start,
                             output_every=every))
    loop, steps = runs
    assert loop.success and steps.success
    assert loop.counters == steps.counters
    if name.startswith("oc3_surge"):
        assert loop.counters["step_cuts"] > 0  # the loop handed steps to Python
    for key in ("time", "positions", "velocities", "tension", "end_force", "wave_elevation"):
        a, b = getattr(loop, key), getattr(steps, key)
        assert a.shape == b.shape, key
        assert np.array_equal(a, b), key


@pytest.mark.parametrize("name", CASES)
def test_compiled_hht_equals_the_general_stepper_on_the_numpy_kernel(name, monkeypatch):
    """HHT-alpha (alpha = -0.1) in the compiled loop against the general stepper on the numpy
    element kernel: the same states to the Newton tolerance's round-off, the same work."""
    make, settings, every = CASES[name]
    system = make()
    start = solve_statics(system)
    hht = DynamicsSettings(**settings, scheme="hht", alpha=-0.1)
    fast = simulate(system, hht, initial=start, output_every=every)
    newmark = simulate(system, DynamicsSettings(**settings), initial=start, output_every=every)
    assert_same_run(fast, reference_run(system, hht, start, every, monkeypatch))
    # HHT is not Newmark here: its numerical damping moves the states
    scale = float(np.abs(newmark.positions).max())
    assert not np.allclose(newmark.positions, fast.positions, rtol=0, atol=1e-5 * scale)


def test_compiled_loop_with_viscoelastic_lines_and_step_cuts_equals_the_general_stepper(
        monkeypatch, caplog):
    """Viscoelastic OC3 lines (standard linear solid, exponential update) in the compiled
    loop, whose Maxwell-branch forces it carries from step to step and hands to Python at
    every step cut (the cut sub-steps restarting from the saved state), against the general
    stepper on the numpy element kernel: the same states to the Newton tolerance's round-off
    and the same work; the Maxwell branch changes the run."""
    import logging

    make, settings, every = CASES["oc3_surge_viscoelastic"]
    system = make()
    start = solve_statics(system)
    assert start.success, start.message
    with caplog.at_level(logging.INFO, logger="moorline"):
        fast = simulate(system, DynamicsSettings(**settings), initial=start,
                        output_every=every)
    assert "general stepper" not in caplog.text  # the compiled loop ran it
    assert fast.counters["step_cuts"] > 0
    assert_same_run(fast, reference_run(system, DynamicsSettings(**settings), start, every,
                                        monkeypatch))
    elastic = simulate(oc3_three_lines(40, BA=6.2358e6), DynamicsSettings(**settings),
                       initial=start.positions, output_every=every)
    scale = float(np.abs(fast.tension).max())
    assert not np.allclose(elastic.tension, fast.tension, rtol=0, atol=1e-2 * scale)


def _in_waves(waves) -> System:
    """The buoy system in waves (with its current: a combined field); shallower fairlead so
    that the upper elements feel the waves."""
    from dataclasses import replace

    system = _buoy_system()
    return replace(system, environment=replace(system.environment, waves=waves))


WAVES = {
    "airy_wheeler": dict(kind="airy", height=6.0, period=9.0, heading_deg=20.0,
                         stretching="wheeler"),
    "jonswap": dict(kind="random", height=5.0, period=10.0, heading_deg=-30.0, seed=3,
                    record_length=300.0, omega_max=2.0),
}


@pytest.mark.parametrize("scheme", ["newmark", "hht"])
@pytest.mark.parametrize("name", WAVES)
def test_compiled_loop_in_waves_equals_the_general_stepper_on_the_numpy_kernel(
        name, scheme, monkeypatch):
    """Airy waves (Wheeler stretching) and a JONSWAP sea, each with a uniform current, in the
    compiled loop against the general stepper on the numpy element kernel (its wave
    kinematics from moorline.waves): the same states to the Newton tolerance's round-off and
    the same work."""
    from moorline.model import Waves

    system = _in_waves(Waves(**WAVES[name]))
    start = solve_statics(system)
    assert start.success, start.message
    settings = DynamicsSettings(duration=8.0, dt=0.05, ramp_time=2.0, scheme=scheme,
                                alpha=-0.1)
    fast = simulate(system, settings, initial=start, output_every=0.1)
    calm = simulate(_buoy_system(), settings, initial=start, output_every=0.1)
    slow = reference_run(system, settings, start, 0.1, monkeypatch)
    assert_same_run(fast, slow)
    assert np.array_equal(fast.wave_elevation, slow.wave_elevation)
    # the waves move the lines: not the still-water run
    scale = float(np.abs(slow.positions).max())
    assert not np.allclose(calm.positions, fast.positions, rtol=0, atol=1e-5 * scale)


@pytest.mark.parametrize("options", [{"slack_damping": True}, {"drag_velocity": "node"},
                                     {"slack_damping": True, "drag_velocity": "node"}])
def test_compiled_loop_with_moordyn_options_equals_the_general_stepper(options, monkeypatch,
                                                                       caplog):
    """MoorDyn's choices (``slack_damping``: the dashpot kept in slack elements;
    ``drag_velocity: node``: each node's drag at its own velocity) on the compiled loop
    against the general stepper on the numpy element kernel, on the OC3 surge case whose
    grounded elements go slack: the same states to the Newton tolerance's round-off and the
    same work; the options change the run."""
    import logging

    make, settings, every = CASES["oc3_surge"]
    settings = dict(settings, duration=15.0)
    system = make()
    start = solve_statics(system)
    on = DynamicsSettings(**settings, **options)
    with caplog.at_level(logging.INFO, logger="moorline"):
        fast = simulate(system, on, initial=start, output_every=every)
    assert "general stepper" not in caplog.text  # the compiled loop ran it
    slow = reference_run(system, on, start, every, monkeypatch)
    assert_same_run(fast, slow)
    assert np.any(slow.tension < 0)  # slack elements (where the kept dashpot pushes)
    default = simulate(system, DynamicsSettings(**settings), initial=start,
                       output_every=every)
    scale = float(np.abs(fast.tension).max())
    assert not np.allclose(default.tension, fast.tension, rtol=0, atol=1e-4 * scale)
