"""Free rigid bodies in the compiled step and loop (moorline.solvers.fast_bodies) against the
general stepper (moorline.solvers.newmark.Stepper with BodyModel, an independent code: its own
body loads, sparse master-slave assembly and sparse LU): the same states, body histories and
work; the compiled tangent's body border against finite differences of the compiled residual;
the refusals of what keeps the general stepper."""

from dataclasses import replace
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
from differences import central_tangent

from moorline.io.case import load_case
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
    WaveExcitation,
    Waves,
)
from moorline.solvers import dynamics
from moorline.solvers.dynamics import simulate
from moorline.solvers.fast_path import body_refusal, fast_path_reason
from moorline.solvers.statics import solve_statics

CASES = Path(__file__).parents[1] / "cases"


def wang_forced() -> System:
    """cases/wang_box.yaml with Wang's surge force ``2e5 sin(1.6 t)`` N (W2) and a diagonal
    damping matrix."""
    system = load_case(CASES / "wang_box.yaml")
    box = replace(system.bodies["box"],
                  force_history=Motion("harmonic", amplitude=(2e5, 0.0, 0.0),
                                       period=2 * np.pi / 1.6),
                  damping=tuple(map(tuple, np.diag([1e4, 1e4, 5e4, 1e5, 1e5, 1e5]))))
    return replace(system, bodies={"box": box})


def buoy(waves: bool = True) -> System:
    """A buoy on three chains lying on the seabed, in a 6 s Airy wave (or still water):
    centre of gravity off every axis, full (coupled) added-mass, damping and hydrostatic
    stiffness matrices, a constant buoyancy at an offset centre, a wind load, and an
    exciting-force table with moments (it rolls, pitches and yaws)."""
    rng = np.random.default_rng(3)
    chain = LineType("chain", diameter=0.07, mass_per_length=100.0, EA=4.0e8, Cd=1.4,
                     Ca=1.0, Ct=0.05)

    def spd(diag):
        q = rng.normal(size=(6, 6)) * 0.1
        return np.diag(diag) + q @ q.T * np.sqrt(np.outer(diag, diag))

    stiffness = spd(np.array([2e3, 2e3, 3.1e5, 6e6, 6e6, 1e4]))
    table = WaveExcitation(omegas=(0.5, 1.0, 1.5),
                           amplitude=((2e4, 5e3, 6e4, 2e4, 5e4, 1e4),) * 3,
                           phase_deg=((-80.0, 10.0, 5.0, 30.0, -60.0, 45.0),) * 3)
    body = Body("buoy", position=(0.0, 0.0, 0.0), mass=6.0e4,
                center_of_gravity=(0.3, -0.2, -1.5),
                inertia=((9e5, 2e4, -1e4), (2e4, 8e5, 3e4), (-1e4, 3e4, 4e5)),
                added_mass=tuple(map(tuple, spd(np.array([2e4, 2e4, 6e4, 3e5, 3e5, 1e4])))),
                damping=tuple(map(tuple, spd(np.array([1e4, 1e4, 4e4, 2e5, 2e5, 5e4])))),
                hydrostatics=Hydrostatics("matrix", stiffness=tuple(map(tuple, stiffness)),
                                          volume=80.0, center_of_buoyancy=(0.1, 0.1, -1.0)),
                force=(2e4, 5e3, 0.0, 0.0, 0.0, 2e4), excitation=table)
    points, lines = {}, {}
    for k in range(3):
        angle = 2 * np.pi * k / 3 + 0.3
        c, s = np.cos(angle), np.sin(angle)
        points[f"f{k}"] = Point(f"f{k}", "body", (3 * c, 3 * s, -2.0), body="buoy")
        points[f"a{k}"] = Point(f"a{k}", "fixed", (250 * c, 250 * s, -80.0))
        lines[f"l{k}"] = Line(f"l{k}", "chain", 280.0, 14, f"a{k}", f"f{k}")
    env = Environment(depth=80.0, water_density=1025.0, gravity=9.81,
                      waves=Waves(kind="airy", height=3.0, period=6.0) if waves else Waves())
    return System("buoy", environment=env, line_types={"chain": chain}, points=points,
                  lines=lines, bodies={"buoy": body})


def _runs(system: System, settings: DynamicsSettings, monkeypatch):
    from backends import reference_run

    start = solve_statics(system)
    assert start.success, start.message
    fast = simulate(system, replace(settings, fast_path=True), initial=start,
                    output_every=settings.dt)
    return fast, reference_run(system, settings, start, settings.dt, monkeypatch)


@pytest.mark.parametrize("case,scheme", [("wang", "newmark"), ("buoy", "newmark"),
                                         ("buoy", "hht")])
def test_compiled_bodies_equal_the_general_stepper(case, scheme, monkeypatch):
    """Over 6 s (120 steps): body poses within 1e-9 of the body's size, velocities and the
    lines' forces on the bodies, line positions and tensions to the Newton tolerance's
    round-off, and the same iterations and factorizations (the Newton tolerance, 1e-8 of the
    largest tension, bounds the difference of two implementations of one algorithm only by
    their round-off as long as they take the same iterations)."""
    from backends import assert_same_bodies, assert_same_run

    system = wang_forced() if case == "wang" else buoy()
    settings = DynamicsSettings(duration=6.0, dt=0.05, ramp_time=2.0, scheme=scheme,
                                alpha=-0.1)
    fast, slow = _runs(system, settings, monkeypatch)
    assert_same_run(fast, slow)
    size = 10.0
    assert np.abs(slow.body_pose[-1] - slow.body_pose[0]).max() > 1e-3  # it moved
    assert np.abs(slow.body_pose[:, 0, 3:]).max() > 1e-4  # and turned
    assert_same_bodies(fast, slow, size)
    assert np.array_equal(fast.body_pin_force, slow.body_pin_force)


def pinned_buoy() -> System:
    """:func:`buoy` pinned at its origin, the pin surging and heaving (its centre of gravity
    off the pin: the pin's acceleration turns it, with the waves' exciting moments)."""
    system = buoy()
    motion = Motion("harmonic", amplitude=(0.6, 0.2, 0.1), period=8.0)
    body = replace(system.bodies["buoy"], kind="pinned", motion=motion)
    return replace(system, bodies={"buoy": body})


def cut_step(fast, slow, excitation, state, s_slow, h):
    """A step of ``h`` the compiled stepper is given one Newton iteration for (so it may
    fail), then the two halves ``_advance`` would take, on both steppers from fresh
    tangents. Returns (the failed attempt's (new state, converged)), the compiled and the
    general stepper's states after the halves."""
    strict = fast.newton_args
    fast.newton_args = (strict[0], 1, *strict[2:])
    new, ok, _ = fast.step(state, h, excitation.constrained_state(state.t + h), None)
    fast.newton_args = strict
    attempt = (new, ok)
    fast.forget_tangent()
    slow.forget_tangent()
    for _ in range(2):  # two halves, as _advance cuts
        c = excitation.constrained_state(state.t + h / 2)
        state, ok, _ = fast.step(state, h / 2, c, None)
        s_slow, ok_slow, _ = slow.step(s_slow, h / 2, c, None)
        assert ok and ok_slow
    return attempt, state, s_slow


@pytest.mark.parametrize("scheme", ["newmark", "hht"])
def test_compiled_pinned_body_equals_the_general_stepper(scheme, monkeypatch):
    """A body pinned in space, its pin moving (held translations, the pin's force as their
    residual): over 6 s the same poses, velocities, pin forces (to the Newton tolerance's
    round-off of the largest) and line results as the general stepper, the same work."""
    from backends import assert_same_run

    system = pinned_buoy()
    settings = DynamicsSettings(duration=6.0, dt=0.05, ramp_time=2.0, scheme=scheme,
                                alpha=-0.1)
    start = solve_statics(system)
    assert type(dynamics.start(system, settings, start)[-1]).__name__ == "FastStepper"
    fast, slow = _runs(system, settings, monkeypatch)
    assert_same_run(fast, slow)
    assert np.abs(slow.body_pose[:, 0, 3:]).max() > 1e-3  # it turns on its pin
    assert np.abs(slow.body_pose[:, 0, 0] - slow.body_pose[0, 0, 0]).max() > 0.3  # moved
    assert np.allclose(fast.body_pose, slow.body_pose, rtol=0, atol=1e-9 * 10.0)
    assert np.allclose(fast.body_velocity, slow.body_velocity, rtol=0,
                       atol=1e-8 * np.abs(slow.body_velocity).max())
    pin = np.abs(slow.body_pin_force).max()
    assert pin > 1e4  # [N]
    assert np.allclose(fast.body_pin_force, slow.body_pin_force, rtol=0, atol=1e-7 * pin)
    ends = np.abs(slow.end_force).max()
    assert np.allclose(fast.end_force, slow.end_force, rtol=0, atol=1e-7 * ends)


def test_step_cuts_restore_the_bodies():
    """One step at a time through :meth:`FastStepper.step` (the Python path of step cuts,
    :func:`moorline.solvers.dynamics._advance`): a step that does not converge (one
    iteration allowed) hands back the state it started from, and the two halves from it
    reach the general stepper's halves."""
    system = wang_forced()
    settings = DynamicsSettings(duration=1.0, dt=0.05, ramp_time=0.5)
    start = solve_statics(system)
    _, _, excitation, state, fast = dynamics.start(system, settings, start)
    _, _, _, s_slow, slow = dynamics.start(system, replace(settings, fast_path=False), start)
    assert type(fast).__name__ == "FastStepper" and type(slow).__name__ == "Stepper"
    failed = 0
    h = 0.1
    for _ in range(8):
        start_state = state
        (new, ok), state, s_slow = cut_step(fast, slow, excitation, state, s_slow, h)
        if not ok:
            failed += 1
            assert new is start_state
        np.testing.assert_allclose(state.bodies.r, s_slow.bodies.r, rtol=0, atol=1e-10)
        np.testing.assert_allclose(state.bodies.R, s_slow.bodies.R, rtol=0, atol=1e-11)
        np.testing.assert_allclose(state.bodies.vel, s_slow.bodies.vel, rtol=0, atol=1e-9)
    assert failed > 0


# ---------------------------------------------------------------- the compiled tangent
def _compiled_problem(stepper, s0, h: float, constrained):
    """The compiled step's residual (band rows, then the bodies') at unknowns ``(x_band,
    dq)`` and its effective tangent as a dense matrix (band ``A``, border ``B, C, D``)."""
    from moorline.physics.fused import set_dashpot_shares, set_viscoelastic_step
    from moorline.solvers import fast_bodies as fb
    from moorline.solvers.fast_fluid import fluid_at_midpoints
    from moorline.solvers.fast_newmark import (
        _assemble,
        _evaluate,
        _kinematics,
        _residual_norm,
        make_buffers,
    )

    (free, band, bw, elements, props, laws, with_drag, wam, node_mass, external, seabed_on,
     seabed_z, k_sb, c_sb, ramp, mu, v_slip, sag_on, sag_active, sag_load, beta, gamma,
     alpha) = stepper.model_args
    mesh = stepper.model.mesh
    inputs = stepper.body_inputs
    n = stepper.lu.shape[0]
    nb = inputs.nb
    fluid = stepper._fluid_inputs(np.array([s0.t + h]))
    other0 = s0.evaluation.nodal - s0.evaluation.inertial
    x0, v0, a0 = s0.x, s0.v, s0.a
    fixed = ~free

    def evaluate(u, tangent):
        buf = make_buffers(mesh.n_elements, mesh.n_nodes)
        strain0 = np.array(s0.material.strain, dtype=float)
        set_dashpot_shares(strain0, props)
        set_viscoelastic_step(strain0, np.array(s0.material.maxwell, dtype=float), h, props)
        x1, v1, a1 = np.empty_like(x0), np.empty_like(x0), np.empty_like(x0)
        x1[fixed], v1[fixed], a1[fixed] = constrained
        for node in np.flatnonzero(free):
            x1[node] = u[band[node]]
        _kinematics(x0, v0, a0, x1, h, beta, gamma, free, v1, a1)
        state = inputs.state(s0.bodies, None)
        state[4][:] = u[n:].reshape(nb, 6)
        times = np.array([s0.t + h])
        bodies = (inputs.links, inputs.loads, state, inputs.forces(times),
                  tuple(np.zeros_like(w) for w in inputs.work), inputs.memory(s0.memory),
                  inputs.pins(times, None))
        fb.predict(bodies, h, 0)  # the sub-step (the predicted step is overwritten)
        state[4][:] = u[n:].reshape(nb, 6)
        fb.place(bodies, False, h, beta, gamma, x1, v1, a1)
        uf, af = np.zeros((mesh.n_elements, 3)), np.zeros((mesh.n_elements, 3))
        if fluid[0] or fluid[6]:
            fluid_at_midpoints(x1, elements, 0, fluid, uf, af)
        _evaluate(x1, v1, a1, uf, af, elements, props, laws, with_drag, wam, node_mass,
                  external, np.zeros_like(x0), seabed_on, seabed_z, k_sb, c_sb, ramp, mu,
                  v_slip, sag_on, sag_active, sag_load, tangent, buf)
        rvec = np.zeros(n + 6 * nb)
        _residual_norm(buf, band, rvec, alpha, node_mass, a1, buf[10], other0)
        fb.residual(bodies, 0, buf, rvec, alpha, node_mass, a1, 0.0)
        return rvec, buf, bodies

    def residual(u):
        return evaluate(u, False)[0]

    def tangent(u):
        _, buf, bodies = evaluate(u, True)
        ca = 1.0 / (beta * h * h)
        cv, ck = (1 + alpha) * gamma / (beta * h), 1.0 + alpha
        ab = np.zeros((n, 2 * bw + 1))
        _assemble(ab, bw, band, elements, buf[6], buf[7], buf[8], buf[19], wam, node_mass, ca,
                  cv, ck, buf[12], buf[13], buf[14], buf[15], buf[16], seabed_on)
        fb.couplings(bodies, band, elements, buf, wam, node_mass, ca, cv, ck, seabed_on)
        K = np.zeros((n + 6 * nb, n + 6 * nb))
        for i in range(n):
            for j in range(max(0, i - bw), min(n, i + bw + 1)):
                K[i, j] = ab[i, j - i + bw]
        BT, Cr, D, _ = bodies[4]
        K[:n, n:], K[n:, :n], K[n:, n:] = BT.T, Cr, D
        return K

    u = np.zeros(n + 6 * nb)
    for node in np.flatnonzero(free):
        u[band[node]] = x0[node] + h * v0[node]
    u[n:] = (h * s0.bodies.vel + 0.5 * h * h * s0.bodies.acc).ravel()
    return residual, tangent, u


def _moving_buoy(scheme: str, pinned: bool = False):
    """The still-water buoy (the lines' fluid loads then have an exact tangent; in waves the
    tangent leaves out how the fluid kinematics change with position, in both steppers) at
    its static state with a random body velocity and acceleration, its compiled stepper, the
    compiled problem (:func:`_compiled_problem`) and unknowns with a finite body step.
    ``pinned``: the buoy pinned at its origin, the pin moving (:func:`pinned_buoy`)."""
    system = buoy(waves=False)
    if pinned:
        body = replace(pinned_buoy().bodies["buoy"], excitation=None)
        system = replace(system, bodies={"buoy": body})
    return moving_body(system, scheme)


def moving_body(system: System, scheme: str):
    """``system``'s body at its static state with a random velocity and acceleration, its
    compiled stepper, the compiled problem (:func:`_compiled_problem`) and unknowns with a
    finite body step (0.2 rad)."""
    from moorline.solvers.bodies import BodyState

    settings = DynamicsSettings(duration=2.0, dt=0.05, scheme=scheme, alpha=-0.1)
    start = solve_statics(system)
    _, _, excitation, state, stepper = dynamics.start(system, settings, start)
    rng = np.random.default_rng(8)  # the body moving and turning
    state = replace(state, bodies=BodyState(state.bodies.r, state.bodies.R,
                                            rng.normal(size=(1, 6)) * 0.3,
                                            rng.normal(size=(1, 6)) * 0.5))
    h = settings.dt
    constrained = excitation.constrained_state(state.t + h)
    residual, tangent, u = _compiled_problem(stepper, state, h, constrained)
    n = stepper.lu.shape[0]
    u[n + 3:n + 6] += (0.1, -0.15, 0.08)  # a finite rotation step
    u[n:n + 3] += (0.2, -0.1, 0.05)
    return stepper, state, h, constrained, residual, tangent, u


@pytest.mark.parametrize("scheme", ["newmark", "hht"])
def test_compiled_body_tangent_matches_finite_differences(scheme):
    """The border of the compiled effective tangent (coupling columns ``B``, rows ``C`` and
    the bodies' block ``D``: kinematic blocks, ``T^T``, the arms turning, hydrostatics,
    weight at an offset centre of gravity, gyroscopic and centripetal inertia, the left
    Jacobian of a 0.2 rad step; with HHT the lines' added-mass forces' position derivative
    weighted 1, as they are in the residual) against central differences of the compiled
    residual, within 1e-7 of each column's largest entry."""
    stepper, _, _, _, residual, tangent, u = _moving_buoy(scheme)
    assert_border_matches_differences(stepper.lu.shape[0], residual, tangent, u)


def assert_border_matches_differences(n: int, residual, tangent, u,
                                      relative: float = 1e-6) -> None:
    """The body border (after the ``n`` band unknowns) of ``tangent(u)`` against central
    differences of ``residual`` at ``u`` (steps ``relative``, :func:`central_tangent`),
    within 1e-7 of each column's largest entry."""
    K = tangent(u)
    fd = central_tangent(residual, u, relative)
    body = slice(n, None)
    for block, ref in ((K[:, body], fd[:, body]), (K[body, :], fd[body, :])):
        scale = np.abs(ref).max(axis=0, keepdims=True)
        assert np.allclose(block, ref, rtol=0, atol=1e-7 * scale)


@pytest.mark.parametrize("scheme", ["newmark", "hht"])
def test_compiled_pinned_body_tangent_matches_finite_differences(scheme):
    """With the buoy pinned on a moving pin: the compiled tangent against central
    differences of the compiled residual in every unknown but the held translations (their
    rows, the pin's force, are zero in the residual; their rows and columns of the tangent
    zero but the diagonal), within 1e-7 of each column's largest entry."""
    stepper, _, _, _, residual, tangent, u = _moving_buoy(scheme, pinned=True)
    n = stepper.lu.shape[0]
    K = tangent(u)
    held = np.zeros(len(u), dtype=bool)
    held[n:n + 3] = True
    keep = np.flatnonzero(~held)
    fd = np.zeros((len(u), len(keep)))
    for col, k in enumerate(keep):
        eps = 1e-6 * max(1.0, abs(u[k]))
        up, um = u.copy(), u.copy()
        up[k] += eps
        um[k] -= eps
        fd[:, col] = -(residual(up) - residual(um)) / (2 * eps)
    assert not fd[held].any()
    assert not K[np.ix_(held, ~held)].any() and not K[np.ix_(~held, held)].any()
    mine, ref = K[np.ix_(keep, keep)], fd[keep]
    body = slice(n, None)  # the body's rotations (after the band in the kept unknowns)
    for block, fd_block in ((mine[:, body], ref[:, body]), (mine[body, :], ref[body, :])):
        scale = np.abs(fd_block).max(axis=0, keepdims=True)
        assert np.allclose(block, fd_block, rtol=0, atol=1e-7 * scale)


@pytest.mark.parametrize("scheme", ["newmark", "hht"])
def test_compiled_body_tangent_is_the_general_steppers(scheme):
    """The compiled residual and bordered tangent equal the general stepper's
    (:meth:`Stepper.residual`, :meth:`Stepper.tangent_matrix`: sparse master-slave
    assembly) at the same unknowns, to round-off (HHT's residual but for the constant
    ``-alpha F0``, zero in the compiled problem here)."""
    from moorline.solvers.newmark import _Step

    stepper, state, h, constrained, residual, tangent, u = _moving_buoy(scheme)
    mesh = stepper.model.mesh
    n = stepper.lu.shape[0]
    free = mesh.free_nodes
    x1 = state.x.copy()
    for node in np.flatnonzero(free):
        x1[node] = u[stepper.band[node]]
    x1[~free] = constrained[0]
    general = stepper.general
    general._current = _Step(state, h, constrained, None)
    dq = u[n:].reshape(-1, 6)
    trial = general.residual((x1, dq), True)
    order = np.empty(n, dtype=int)
    order[stepper.band[free].ravel()] = mesh.dof_of_node[free].ravel()
    order = np.r_[order, np.arange(n, len(u))]
    K = general.tangent_matrix((x1, dq), trial).toarray()[np.ix_(order, order)]
    mine = tangent(u)
    assert np.allclose(mine, K, rtol=0, atol=1e-12 * np.abs(K).max())
    if scheme == "newmark":
        r = trial.r[order]
        assert np.allclose(residual(u), r, rtol=0, atol=1e-12 * np.abs(r).max())


# ---------------------------------------------------------------- refusals
@pytest.mark.parametrize("change,reason", [
    ({"kind": "fixed"}, "a fixed body (box)"),
    ({"kind": "pinned", "pin_body": "hull"}, "a pinned body on another body (box)"),
    ({"wave_loads": True}, "long-wave loads on body box"),
])
def test_bodies_the_compiled_step_does_not_take_keep_the_general_stepper(change, reason):
    from moorline.mesh import discretize

    system = load_case(CASES / "wang_box.yaml")
    mesh = discretize(system)
    assert body_refusal(mesh) is None
    box = replace(system.bodies["box"], **change)
    changed = SimpleNamespace(bodies=[box])
    assert body_refusal(changed) == reason
    assert fast_path_reason(SimpleNamespace(mesh=changed), None, "newmark", "iterative",
                            True) == reason
