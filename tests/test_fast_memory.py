"""Radiation memory (the Cummins equation) in the compiled step and loop
(moorline.solvers.fast_bodies.advance_memory) against the general stepper
(moorline.solvers.newmark.Stepper with BodyModel's MemoryModel, an independent code): the same
body motions, memory forces and fairlead tensions; the compiled tangent's memory terms against
finite differences of the compiled residual; a step cut hands back the memory states it
started from."""

from dataclasses import replace

import numpy as np
import pytest
from differences import central_tangent
from test_fast_bodies import _compiled_problem, cut_step

from moorline.model import DynamicsSettings, RadiationTable, WaveExcitation, Waves
from moorline.solvers import dynamics
from moorline.solvers.bodies import BodyState
from moorline.solvers.dynamics import simulate
from moorline.solvers.statics import solve_statics
from moorline.verification.cummins import X3, known_table, moored_body, nested


def coupled_body(push: float = 1.0e4):
    """The Cummins tests' moored body (moorline.verification.cummins.moored_body) with the
    known kernel on heave, surge, pitch and the surge-pitch coupling (as
    test_cummins.test_the_step_tangent_with_radiation_memory_equals_finite_differences),
    released from a push, in a regular wave with an exciting-force table in surge, heave and
    pitch (the lines stay taut: with a 2e4 N push they go slack and both steppers stop
    under HHT)."""
    table = known_table()
    w = np.array(table.omegas)
    A, B = np.array(table.added_mass), np.array(table.damping)
    for (i, j), f in {(0, 0): 0.5, (4, 4): 30.0, (0, 4): 2.0, (4, 0): 2.0}.items():
        A[:, i, j], B[:, i, j] = f * A[:, 2, 2], f * B[:, 2, 2]
    excitation = WaveExcitation(omegas=(0.05, 8.0),
                                amplitude=((0.3 * X3, 0, X3, 0, 2 * X3, 0),) * 2,
                                phase_deg=((30.0, 0.0, 0.0, 0.0, -40.0, 0.0),) * 2)
    return moored_body(RadiationTable(tuple(w), nested(A), nested(B)), push=push,
                       excitation=excitation, waves=Waves(kind="airy", height=0.04, period=2.0))


@pytest.mark.parametrize("scheme", ["newmark", "hht"])
def test_compiled_memory_equals_the_general_stepper(scheme, monkeypatch):
    """Over 4 s (160 steps, the heave mode's period 1.3 s): body poses within 1e-9 m,
    velocities, the lines' forces on the body and the fairlead tensions to the Newton
    tolerance's round-off, and the same iterations and factorizations."""
    from backends import assert_same_bodies, assert_same_run, reference_run

    system = coupled_body()
    settings = DynamicsSettings(duration=4.0, dt=0.025, ramp_time=1.0, scheme=scheme,
                                alpha=-0.1)
    start = solve_statics(system)
    assert start.success, start.message
    fast = simulate(system, replace(settings, fast_path=True), initial=start,
                    output_every=settings.dt)
    assert type(dynamics.start(system, settings, start)[-1]).__name__ == "FastStepper"
    slow = reference_run(system, settings, start, settings.dt, monkeypatch)
    assert_same_run(fast, slow)
    assert slow.tension.min() > 100.0  # taut [N]
    assert np.abs(slow.body_pose[:, 0, 2] - slow.body_pose[0, 0, 2]).max() > 1e-2  # heaves
    assert np.abs(slow.body_pose[:, 0, 4]).max() > 1e-4  # and pitches
    assert_same_bodies(fast, slow, 1.0)


def _steppers(scheme: str = "newmark"):
    system = coupled_body()
    settings = DynamicsSettings(duration=1.0, dt=0.05, ramp_time=0.5, scheme=scheme,
                                alpha=-0.1)
    start = solve_statics(system)
    _, _, excitation, state, fast = dynamics.start(system, settings, start)
    _, _, _, s_slow, slow = dynamics.start(system, replace(settings, fast_path=False), start)
    assert type(fast).__name__ == "FastStepper" and type(slow).__name__ == "Stepper"
    return excitation, state, fast, s_slow, slow


@pytest.mark.parametrize("scheme", ["newmark", "hht"])
def test_step_cuts_restore_the_memory_states(scheme):
    """One step at a time through :meth:`FastStepper.step` (the Python path of step cuts): a
    step that does not converge (one iteration allowed) hands back the state it started
    from, memory states included, and the two halves from it reach the general stepper's
    halves: the same memory states and memory forces ``mu`` (BodyModel.memory_forces)."""
    excitation, state, fast, s_slow, slow = _steppers(scheme)
    failed = 0
    h = 0.1
    for _ in range(8):
        start_state = state
        before = None if state.memory is None else state.memory[0].copy()
        (new, ok), state, s_slow = cut_step(fast, slow, excitation, state, s_slow, h)
        if not ok:
            failed += 1
            assert new is start_state
            assert before is None or np.array_equal(start_state.memory[0], before)
        z, z_slow = state.memory[0], s_slow.memory[0]
        np.testing.assert_allclose(z, z_slow, rtol=0, atol=1e-9 * np.abs(z_slow).max())
        mu = fast.bodies.memory_forces(state.memory)
        mu_slow = slow.bodies.memory_forces(s_slow.memory)
        np.testing.assert_allclose(mu, mu_slow, rtol=0, atol=1e-9 * np.abs(mu_slow).max())
        np.testing.assert_allclose(state.bodies.r, s_slow.bodies.r, rtol=0, atol=1e-10)
    assert np.abs(mu_slow).max() > 10.0  # the memory force is there [N]
    assert failed > 0


def _memory_problem(scheme: str):
    """The compiled problem (test_fast_bodies._compiled_problem) of a step of the spinning
    body with random memory states, unknowns with a finite body step."""
    excitation, state, fast, _, _ = _steppers(scheme)
    mem = fast.bodies.memory[0]
    rng = np.random.default_rng(1)
    z0 = 0.1 * (rng.normal(size=mem.n_states) + 1j * rng.normal(size=mem.n_states))
    spin = np.array([[0.1, -0.05, 0.02, 0.3, -0.2, 0.4]])
    state = replace(state, bodies=BodyState(state.bodies.r, state.bodies.R, spin, 0.5 * spin),
                    memory=(z0,))
    h = 0.05
    constrained = excitation.constrained_state(state.t + h)
    residual, tangent, u = _compiled_problem(fast, state, h, constrained)
    n = fast.lu.shape[0]
    u[n:] += (0.02, -0.01, 0.03, 0.04, -0.03, 0.05)
    return fast, state, h, constrained, residual, tangent, u


@pytest.mark.parametrize("scheme", ["newmark", "hht"])
def test_compiled_memory_tangent_matches_finite_differences(scheme):
    """The compiled effective tangent with the radiation memory's ``d mu / d v1`` (through
    the Newmark velocity, ``gamma / (beta h)``, HHT-weighted ``1 + alpha``) against central
    differences of the compiled residual, within 1e-7 of each column's largest entry (and
    the differences' round-off); the memory block is a visible part of the body block, which
    does not match without it."""
    fast, _, h, _, residual, tangent, u = _memory_problem(scheme)
    n = fast.lu.shape[0]
    K = tangent(u)
    fd = central_tangent(residual, u)
    # 1e-7 of the column's largest entry, plus the differences' round-off in a row of
    # large entries (1e-16 of them over eps, ~1e-9 of the row's largest derivative)
    tol = 1e-7 * np.abs(fd).max(axis=0, keepdims=True) + 1e-9 * np.abs(fd).max(axis=1,
                                                                             keepdims=True)
    assert np.allclose(K, fd, rtol=0, atol=tol)
    beta, gamma = fast.c.beta, fast.c.gamma
    memory = gamma / (beta * h) * fast.bodies.memory[0].velocity_derivative(h)
    assert np.abs(memory).max() > 1e-3 * np.abs(K[n:, n:]).max()
    # and without the memory's part the body block would not match
    assert not np.allclose(K[n:, n:] - (1 + fast.c.alpha) * memory, fd[n:, n:], rtol=0,
                           atol=tol[n:, n:])
