"""The compiled step (moorline.solvers.fast_newmark) against the general stepper: same
algorithm, same results, on a case with every load the fast path supports."""

from dataclasses import replace
from pathlib import Path

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
    Waves,
)
from moorline.solvers.assembly import BlockPattern
from moorline.solvers.dynamics import simulate
from moorline.solvers.fast_newmark import _band_lu, _band_solve, band_ordering
from moorline.solvers.statics import solve_statics


def _system(friction: float, current: float) -> System:
    lt = LineType("chain", diameter=0.09, mass_per_length=77.7, EA=3.8e8, Cd=1.6, Ct=0.05,
                  Ca=1.0, Cat=0.1, BA=-0.8)
    motion = Motion("harmonic", amplitude=(2.0, 1.0, 0.5), period=8.0, ramp_time=4.0)
    points = {
        "a1": Point("a1", "fixed", (-450.0, 0.0, -150.0)),
        "a2": Point("a2", "fixed", (300.0, 300.0, -150.0)),
        "f": Point("f", "prescribed", (0.0, 0.0, -20.0), motion=motion),
    }
    lines = {"l1": Line("l1", "chain", 500.0, 12, "a1", "f"),
             "l2": Line("l2", "chain", 470.0, 10, "a2", "f")}
    env = Environment(depth=150.0, seabed=Seabed(friction=friction, slip_velocity=0.05),
                      current=Current(speed=current, heading_deg=30.0))
    return System("fast", environment=env, line_types={"chain": lt}, points=points, lines=lines)


def assert_fast_equals_slow(system: System, duration: float = 12.0) -> None:
    """The compiled and the general stepper from the statics of ``system``: positions within
    1e-7 of their scale, tensions within 1e-6, the same number of steps."""
    start = solve_statics(system)
    assert start.success, start.message
    settings = dict(duration=duration, dt=0.05, ramp_time=4.0)
    slow = simulate(system, DynamicsSettings(**settings, fast_path=False), initial=start,
                    output_every=0.5)
    fast = simulate(system, DynamicsSettings(**settings, fast_path=True), initial=start,
                    output_every=0.5)
    scale = np.abs(slow.positions).max()
    assert np.allclose(fast.positions, slow.positions, rtol=0, atol=1e-7 * scale)
    assert np.allclose(fast.tension, slow.tension, rtol=1e-6, atol=1e-6 * slow.tension.max())
    assert fast.counters["steps"] == slow.counters["steps"]


@pytest.mark.parametrize("friction,current", [(0.0, 0.0), (0.5, 0.8)])
def test_fast_step_reproduces_the_general_stepper(friction, current):
    assert_fast_equals_slow(_system(friction, current))


@pytest.mark.parametrize("waves", [False, True])
def test_compiled_step_with_a_sheared_current_equals_the_general_stepper(waves, caplog):
    """A current profile over depth (speed 0.2 -> 0.6 -> 1.0 m/s and heading 10 -> 40 -> 350
    deg from the seabed to the surface: the heading turns the short way through 0) on the
    compiled step, with and without an Airy wave, against the general stepper evaluating
    :meth:`moorline.waves.CurrentProfile.velocity`; the profile changes the run against the
    uniform current of its surface value."""
    import logging

    base = _system(0.0, 0.0)
    profile = Current(z_levels=(-150.0, -60.0, 0.0), speeds=(0.2, 0.6, 1.0),
                      headings_deg=(10.0, 40.0, 350.0))
    env = replace(base.environment, current=profile,
                  waves=Waves(kind="airy", height=2.0, period=7.0) if waves else Waves())
    system = replace(base, environment=env)
    with caplog.at_level(logging.INFO, logger="moorline"):
        assert_fast_equals_slow(system)
    # only the reference run (fast_path off) took the general stepper
    reasons = [r.getMessage() for r in caplog.records if "general stepper" in r.getMessage()]
    assert reasons == ["general stepper (compiled step not used: disabled)"]
    uniform = replace(system, environment=replace(env, current=Current(speed=1.0,
                                                                       heading_deg=350.0)))
    start = solve_statics(system)
    settings = DynamicsSettings(duration=6.0, dt=0.05, ramp_time=4.0)
    sheared = simulate(system, settings, initial=start, output_every=0.5)
    flat = simulate(uniform, settings, initial=solve_statics(uniform), output_every=0.5)
    assert np.abs(sheared.positions - flat.positions).max() > 0.1


def test_compiled_step_with_axial_and_transverse_friction_equals_the_general_stepper(caplog):
    """Seabed friction 0.3 along the line and 1.0 across it (MoorDyn's mu_kA, mu_kT) on the
    compiled step against the general stepper (``DynamicModel._friction``); the law differs
    from the isotropic one of either coefficient."""
    import logging

    base = _system(0.0, 0.8)
    seabed = Seabed(friction=1.0, friction_axial=0.3, friction_transverse=1.0,
                    slip_velocity=0.05)
    system = replace(base, environment=replace(base.environment, seabed=seabed))
    with caplog.at_level(logging.INFO, logger="moorline"):
        assert_fast_equals_slow(system)
    reasons = [r.getMessage() for r in caplog.records if "general stepper" in r.getMessage()]
    assert reasons == ["general stepper (compiled step not used: disabled)"]
    settings = DynamicsSettings(duration=12.0, dt=0.05, ramp_time=4.0)
    runs = []
    for law in (seabed, Seabed(friction=1.0, slip_velocity=0.05),
                Seabed(friction=0.3, slip_velocity=0.05)):
        case = replace(base, environment=replace(base.environment, seabed=law))
        runs.append(simulate(case, settings, initial=solve_statics(case), output_every=0.5))
    for isotropic in runs[1:]:
        assert np.abs(runs[0].positions - isotropic.positions).max() > 1e-3


def _with_viscoelastic_line(friction: float, current: float, EA1: float) -> System:
    """:func:`_system` with its second line a polyester rope (standard linear solid:
    long-term stiffness ``EA``, Maxwell branch ``EA1`` with a 2 s relaxation time)."""
    system = _system(friction, current)
    rope = LineType("polyester", diameter=0.16, mass_per_length=20.0, EA=1.0e8, Cd=1.2,
                    Ct=0.008, Ca=1.0, Cat=0.0, BA=-0.8, material="viscoelastic", EA1=EA1,
                    tau=2.0)
    lines = dict(system.lines, l2=replace(system.lines["l2"], line_type="polyester"))
    return replace(system, line_types={**system.line_types, "polyester": rope}, lines=lines)


@pytest.mark.parametrize("friction,current", [(0.0, 0.0), (0.5, 0.8)])
def test_compiled_step_with_a_viscoelastic_line_equals_the_general_stepper(
        friction, current, monkeypatch, caplog):
    """A chain and a viscoelastic polyester rope (exponential update) on the compiled step
    against the general stepper on the numpy element kernel: the same states to the Newton
    tolerance's round-off and the same work; the rope's Maxwell branch changes the run."""
    import logging

    system = _with_viscoelastic_line(friction, current, 2.0e8)
    start = solve_statics(system)
    assert start.success, start.message
    settings = DynamicsSettings(duration=12.0, dt=0.05, ramp_time=4.0)
    with caplog.at_level(logging.INFO, logger="moorline"):
        fast = simulate(system, settings, initial=start, output_every=0.1)
    assert "general stepper" not in caplog.text  # the compiled step ran it
    assert_same_run(fast, reference_run(system, settings, start, 0.1, monkeypatch))
    relaxed = _with_viscoelastic_line(friction, current, 0.0)
    plain = simulate(relaxed, settings, initial=solve_statics(relaxed), output_every=0.1)
    rope = start.mesh.viscoelastic
    assert np.abs(plain.tension[:, rope] - fast.tension[:, rope]).max() > 0.1 * np.abs(
        plain.tension[:, rope] - plain.tension[0, rope]).max()


def test_compiled_step_hands_back_the_viscoelastic_state_of_the_general_stepper(monkeypatch):
    """Tuah's Ex. 4 string of the viscoelastic material (released from 2 ft with its Maxwell
    branch loaded; slack in every swing, where the Maxwell branch relaxes along the material
    strain): one step at a time from the same start, the compiled step's states carry the
    strains and Maxwell-branch forces of the general stepper on the numpy kernel to
    round-off, and the same positions."""
    from moorline.mesh import discretize
    from moorline.solvers import dynamics
    from moorline.solvers.dynamic_model import DynamicModel
    from moorline.solvers.fast_newmark import FastStepper
    from moorline.verification import tuah_ex4

    system = tuah_ex4.ex4_system(viscoelastic=True)
    settings = DynamicsSettings(duration=0.3, dt=0.001, tolerance=1e-10, max_iterations=30)
    x0 = tuah_ex4.start_positions(system)
    maxwell = np.full(discretize(system).n_elements, tuah_ex4.initial_maxwell())
    _, _, excitation, fast_state, fast = dynamics.start(system, settings, x0, maxwell=maxwell)
    monkeypatch.setattr(dynamics, "DynamicModel",
                        lambda *args, **kw: DynamicModel(*args, **kw, kernel="numpy"))
    _, _, _, state, slow = dynamics.start(system, replace(settings, fast_path=False), x0,
                                          maxwell=maxwell)
    assert isinstance(fast, FastStepper) and not isinstance(slow, FastStepper)
    q_scale = abs(tuah_ex4.initial_maxwell())
    slack = 0
    for _ in range(300):
        constrained = excitation.constrained_state(state.t + settings.dt)
        fast_state, ok_fast, _ = fast.step(fast_state, settings.dt, constrained, None)
        state, ok, _ = slow.step(state, settings.dt, constrained, None)
        assert ok and ok_fast
        assert np.allclose(fast_state.x, state.x, rtol=0, atol=1e-12 * tuah_ex4.SPAN)
        assert np.allclose(fast_state.material.strain, state.material.strain, rtol=0,
                           atol=1e-12)
        assert np.allclose(fast_state.material.maxwell, state.material.maxwell, rtol=0,
                           atol=1e-9 * q_scale)
        slack += bool(np.any(state.evaluation.tension < 0))
    assert slack > 10  # steps ending slack
    assert np.abs(state.material.maxwell).max() < 0.5 * q_scale  # it relaxed


def test_band_ordering_and_lu_solve_like_dense():
    rng = np.random.default_rng(5)
    elements = np.array([[0, 3], [3, 4], [4, 1], [1, 5], [5, 2], [4, 6]])
    dof = np.arange(21).reshape(7, 3)
    dof[0] = -1
    dof[1:] -= 3
    band, bw = band_ordering(elements, dof)
    pattern = BlockPattern(elements, dof)
    blocks = rng.normal(size=(len(elements), 6, 6))
    A = pattern.assemble(blocks, np.repeat(np.eye(3)[None] * 40.0, 7, axis=0)).toarray()
    n = A.shape[0]
    # A in band order
    perm = np.empty(n, dtype=int)
    perm[band[dof >= 0]] = dof[dof >= 0]
    B = A[np.ix_(perm, perm)]
    assert np.all(np.abs(np.subtract.outer(np.arange(n), np.arange(n)))[B != 0] <= bw)
    ab = np.zeros((n, 2 * bw + 1))
    for i in range(n):
        for j in range(max(0, i - bw), min(n, i + bw + 1)):
            ab[i, j - i + bw] = B[i, j]
    assert _band_lu(ab, bw)
    b = rng.normal(size=n)
    x = b.copy()
    _band_solve(ab, bw, x)
    assert np.allclose(B @ x, b, rtol=1e-10, atol=1e-10)


CASES = sorted((Path(__file__).parents[1] / "cases").glob("*.yaml"))


@pytest.mark.parametrize("path", CASES, ids=[p.stem for p in CASES])
def test_both_backends_give_the_same_states_step_by_step_on_every_case_both_accept(
        path, monkeypatch):
    """Every case file the compiled backend accepts (waves included): the same states after
    every step as the general stepper on the numpy element kernel (the reference path) (40
    steps of its dynamics, or of a default dynamics analysis)."""
    from dataclasses import replace

    from moorline.io.case import load_case
    from moorline.solvers.dynamic_model import DynamicModel
    from moorline.solvers.dynamics import _fluid, _rayleigh
    from moorline.solvers.fast_path import fast_path_reason

    if "hydrodynamics:" in path.read_text(encoding="utf-8"):
        # a body with a hydrodynamic database: its BEM takes about a minute (the compiled
        # radiation memory: tests/test_fast_memory.py)
        pytest.skip("a hydrodynamic database (BEM) is too slow to compute for this test")
    system = load_case(path)
    settings = next((a for a in system.analyses if isinstance(a, DynamicsSettings)),
                    DynamicsSettings())
    settings = replace(settings, duration=min(settings.duration, 40 * settings.dt))
    start = solve_statics(system)
    assert start.success, start.message
    fluid = _fluid(system, settings)
    model = DynamicModel(start.mesh, fluid, settings.viscoelastic_update,
                         system.environment.seabed)
    reason = fast_path_reason(model, fluid, settings.scheme, settings.variant,
                              bool(start.mesh.body_names), _rayleigh(settings) is not None)
    if reason is not None:
        pytest.skip(f"the compiled backend does not take this case: {reason}")
    fast = simulate(system, replace(settings, fast_path=True), initial=start,
                    output_every=settings.dt)
    assert_same_run(fast, reference_run(system, settings, start, settings.dt, monkeypatch))
