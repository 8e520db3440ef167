"""Pinned bodies (translation held at a pin, rotation free; MoorDyn's ``Pinned`` and
``CoupledPinned`` rods and ``CoupledPinned`` bodies): a compound pendulum against its
closed-form period, a rod held by a line against the moment balance about its pin, a
pendulum on an accelerating pin against the exact mean angle, and the exact tangents of the
statics and of the time step against finite differences."""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from moorline.io.moordyn import read_moordyn_deck
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
from moorline.physics.rigid_body import rotation_matrix
from moorline.solvers.dynamics import simulate
from moorline.solvers.statics import solve_statics

RHO, G = 1025.0, 9.80665


def _central_differences(residual, n: int, columns, h: float = 1e-6) -> np.ndarray:
    """Minus the central-difference derivative of ``residual(du)`` (a step ``du`` of the
    ``n`` unknowns) over the given ``columns``: the tangent's finite-difference twin."""
    fd = np.zeros((n, n))
    for j in columns:
        e = np.zeros(n)
        e[j] = h
        fd[:, j] = -(residual(e) - residual(-e)) / (2 * h)
    return fd


def rod_deck(path: Path, *, d: float, mpl: float, Ca: float, a: tuple, b: tuple,
             lines: str = "", points: str = "", segments: int = 10, options: str = "") -> Path:
    """A MoorDyn v2 deck with one ``Pinned`` rod (no drag) from ``a`` to ``b``, a dummy wire
    between two fixed points far away (a deck needs a line) and the given extra points and
    lines."""
    text = f"""pinned rod
--- LINE TYPES ---
Name Diam MassDen EA BA EI Can Cat Cdn Cdt
(-) (m) (kg/m) (N) (-) (-) (-) (-) (-) (-)
wire 0.05 5.0 1e7 -0.8 0 1 0 1 0
--- ROD TYPES ---
Name Diam Mass/m Cd Ca CdEnd CaEnd
(-) (m) (kg/m) (-) (-) (-) (-)
can {d!r} {mpl!r} 0 {Ca!r} 0 0
--- RODS ---
ID RodType Attachment Xa Ya Za Xb Yb Zb NumSegs Outputs
(#) (-) (-) (m) (m) (m) (m) (m) (m) (-) (-)
1 can Pinned {a[0]!r} {a[1]!r} {a[2]!r} {b[0]!r} {b[1]!r} {b[2]!r} {segments} -
--- POINTS ---
ID Type X Y Z M V CdA Ca
(#) (-) (m) (m) (m) (kg) (m^3) (m^2) (-)
1 Fixed 50 0 -30 0 0 0 0
2 Fixed 55 0 -30 0 0 0 0
{points}--- LINES ---
ID LineType AttachA AttachB UnstrLen NumSegs Outputs
(#) (-) (-) (-) (m) (-) (-)
1 wire 1 2 5 2 -
{lines}--- OPTIONS ---
{RHO!r} WtrDnsty
{G!r} g
100 WtrDpth
{options}--- END ---
"""
    path.write_text(text, encoding="utf-8")
    return path


def _period(time: np.ndarray, x: np.ndarray) -> float:
    """Mean period of ``x`` about its mean from its zero crossings (linear interpolation)."""
    x = x - 0.5 * (x.max() + x.min())
    s = np.sign(x)
    i = np.nonzero(s[:-1] * s[1:] < 0)[0]
    crossing = time[i] - x[i] * (time[i + 1] - time[i]) / (x[i + 1] - x[i])
    return float(2.0 * (crossing[-1] - crossing[0]) / (len(crossing) - 1))


def test_pinned_rod_pendulum_period_is_the_compound_pendulum_formula(tmp_path):
    """A 10 m rod (d 0.5 m, 400 kg/m, Ca 1, no drag) pinned at its end A 20 m deep, released
    at rest 2 deg off the vertical in still water: the period of its small oscillations is
    ``2 pi sqrt(I / ((m - rho V) g L / 2))`` with ``I = m (L^2/3 + d^2/16) + Ca rho A L^3/3``
    about the pin (the solid rod's transverse inertia as MoorDyn's, the transverse added mass
    of the submerged rod). Tolerance 5e-4: the amplitude's nonlinear lengthening
    ``theta0^2 / 16 = 7.6e-5`` and the average-acceleration scheme's period elongation
    ``(omega dt)^2 / 12 = 1.0e-4`` at dt = 0.05 s, plus the zero-crossing estimate."""
    L, d, mpl, Ca, tilt = 10.0, 0.5, 400.0, 1.0, math.radians(2.0)
    deck = rod_deck(tmp_path / "pendulum.dat", d=d, mpl=mpl, Ca=Ca, a=(0.0, 0.0, -20.0),
                    b=(L * math.sin(tilt), 0.0, -20.0 - L * math.cos(tilt)))
    system = read_moordyn_deck(deck).system
    body = system.bodies["rod1"]
    assert body.kind == "pinned" and body.position == (0.0, 0.0, -20.0)
    static = solve_statics(system)
    assert static.success, static.message
    A = math.pi * d * d / 4
    m, V = mpl * L, A * L
    # hanging straight down, the pin carrying the weight less the buoyancy
    axis = rotation_matrix(static.body_rotation("rod1")) @ np.array([1.0, 0.0, 0.0])
    assert axis == pytest.approx([0.0, 0.0, -1.0], abs=1e-8)
    assert static.pin_reaction("rod1") == pytest.approx([0.0, 0.0, (m - RHO * V) * G],
                                                        rel=1e-9, abs=1e-6)
    released = solve_statics(replace(system, bodies={"rod1": replace(body, kind="fixed")}))
    run = simulate(system, DynamicsSettings(duration=20.0, dt=0.05), initial=released)
    assert run.success, run.message
    axes = rotation_matrix(run.body_pose[:, 0, 3:])[:, :, 0]
    angle = np.arctan2(axes[:, 0], -axes[:, 2])
    assert angle.max() == pytest.approx(tilt, rel=1e-3)  # no drag: no decay
    inertia = m * (L * L / 3 + d * d / 16) + Ca * RHO * A * L**3 / 3
    expected = 2 * math.pi * math.sqrt(inertia / ((m - RHO * V) * G * L / 2))
    assert _period(run.time, angle) == pytest.approx(expected, rel=5e-4)
    # the pin carries the rod: its vertical force averages the submerged weight
    pin = run.body_pin_force[1:, 0]
    assert np.abs(pin[:, 2] / ((m - RHO * V) * G) - 1).max() < 1e-2


def test_pinned_rod_held_by_a_line_balances_its_moments_about_the_pin(tmp_path):
    """A buoyant rod (d 1 m, 200 kg/m, 12 m) pinned at its end A on the seabed's anchor,
    its end B held down by a 22 m rope to an anchor 25 m away: at equilibrium the moments about
    the pin of the rope's force at end B, the weight at the middle and the buoyancy at the
    submerged centroid sum to zero, and the pin's reaction is minus the sum of the three
    forces (the rope's force read from the result, the rest written here)."""
    L, d, mpl = 12.0, 1.0, 200.0
    pin = np.array([0.0, 0.0, -60.0])
    deck = rod_deck(tmp_path / "held.dat", d=d, mpl=mpl, Ca=1.0, a=(0.0, 0.0, -60.0),
                    b=(0.0, 0.0, -48.0), points="3 Fixed 25 0 -60 0 0 0 0\n",
                    lines="2 rope 3 R1B 22 20 -\n")
    deck.write_text(deck.read_text().replace("wire 0.05 5.0 1e7 -0.8 0 1 0 1 0",
                                             "wire 0.05 5.0 1e7 -0.8 0 1 0 1 0\n"
                                             "rope 0.08 10.0 5e7 -0.8 0 1 0 1 0"))
    system = read_moordyn_deck(deck).system
    static = solve_statics(system)
    assert static.success, static.message
    axis = rotation_matrix(static.body_rotation("rod1")) @ np.array([1.0, 0.0, 0.0])
    assert static.body_position("rod1") == pytest.approx(pin, abs=1e-12)
    assert axis[0] > 0.3  # pulled over towards the anchor
    end_b = pin + L * axis
    line = next(n for n, ln in system.lines.items() if "rod1B" in (ln.end_a, ln.end_b))
    end = "a" if system.lines[line].end_a == "rod1B" else "b"
    rope = static.end_force(line, end)
    weight = np.array([0.0, 0.0, -mpl * L * G])
    buoyancy = np.array([0.0, 0.0, RHO * G * math.pi * d * d / 4 * L])
    middle = pin + 0.5 * L * axis
    moment = (np.cross(end_b - pin, rope) + np.cross(middle - pin, weight + buoyancy))
    scale = L * float(np.linalg.norm(buoyancy + weight))
    assert np.abs(moment).max() < 1e-6 * scale
    assert static.pin_reaction("rod1") == pytest.approx(-(rope + weight + buoyancy),
                                                        abs=1e-6 * scale / L)


def test_pinned_rod_pendulum_against_moordyn():
    """The pendulum deck of :func:`test_pinned_rod_pendulum_period_is_the_compound_pendulum_
    formula` (40 rod segments, no initial-condition solve, ``dtM`` 0.5 ms) in MoorDyn-C and
    in moorline (dt 0.05 s): periods within 3e-4. Convergence study of MoorDyn's period
    against the formula at 10, 20, 40 rod segments: +9.13e-4, +2.81e-4, +1.25e-4 (second
    order: its lumped transverse added mass), extrapolated +7.3e-5 (the amplitude's
    ``theta0^2 / 16 = 7.6e-5``); moorline +1.7e-4 at dt 0.05 s (its period elongation,
    +9.3e-5 at 0.02 s). MoorDyn's remaining discretization (5e-5) and moorline's step error
    (1e-4) give the tolerance."""
    moordyn = pytest.importorskip("moordyn")
    import tempfile

    from moorline.compare.moordyn_runner import silenced_fd

    L, tilt = 10.0, math.radians(2.0)
    with tempfile.TemporaryDirectory() as folder:
        deck = rod_deck(Path(folder) / "pendulum.dat", d=0.5, mpl=400.0, Ca=1.0,
                        a=(0.0, 0.0, -20.0),
                        b=(L * math.sin(tilt), 0.0, -20.0 - L * math.cos(tilt)), segments=40,
                        options="0 TmaxIC\n0.0005 dtM\n")
        with silenced_fd(1):
            md = moordyn.Create(str(deck))
            moordyn.SetVerbosity(md, moordyn.LEVEL_ERR)
            assert moordyn.Init(md, [], []) == 0
            rod = moordyn.GetRod(md, 1)
            last = moordyn.GetRodN(rod)
            t, times, theirs = 0.0, [], []
            try:
                for _ in range(400):
                    moordyn.Step(md, [], [], t, 0.05)
                    t += 0.05
                    axis = (np.array(moordyn.GetRodNodePos(rod, last))
                            - np.array(moordyn.GetRodNodePos(rod, 0)))
                    times.append(t)
                    theirs.append(math.atan2(axis[0], -axis[2]))
            finally:
                moordyn.Close(md)
        system = read_moordyn_deck(deck).system
    body = system.bodies["rod1"]
    released = solve_statics(replace(system, bodies={"rod1": replace(body, kind="fixed")}))
    run = simulate(system, DynamicsSettings(duration=20.0, dt=0.05), initial=released)
    assert run.success, run.message
    axes = rotation_matrix(run.body_pose[:, 0, 3:])[:, :, 0]
    ours = np.arctan2(axes[:, 0], -axes[:, 2])
    assert _period(run.time, ours) == pytest.approx(_period(np.array(times),
                                                            np.array(theirs)), rel=3e-4)
    assert ours.max() == pytest.approx(max(theirs), rel=1e-3)


def _accelerating_pin(accel: float, duration: float, dt: float) -> System:
    """MoorDyn's ``tests/Mooring/body_tests/pinnedBody.txt`` as moorline objects: a pinned
    body at (0, 0, -5) carrying a 10 m rod (d 2 m, 5 t/m) hanging below it, in a vacuum
    (the deck's ``WtrDnsty 0``), its pin moved along y by ``accel t^2 / 2`` (MoorDyn's
    ``tests/bodies.cpp`` "Pinned body")."""
    L, d, mpl = 10.0, 2.0, 5.0e3
    m = mpl * L
    transverse = m * (L * L / 12 + d * d / 16)
    times = tuple(np.linspace(0.0, duration + 1.0, 41))
    motion = Motion("table", times=times, values=tuple((0.0, 0.5 * accel * t * t, 0.0)
                                                      for t in times))
    body = Body("pin", "pinned", position=(0.0, 0.0, -5.0), mass=m,
                center_of_gravity=(0.0, 0.0, -10.0),
                inertia=((transverse, 0, 0), (0, transverse, 0), (0, 0, m * d * d / 8)),
                motion=motion)
    lt = LineType("nylon", 0.124, 35.0, 5515288.0, Cd=0.0, Ca=0.0)
    points = {"1": Point("1", "fixed", (30.0, 0.0, -5.0)),
              "2": Point("2", "fixed", (30.0, 0.0, -10.0))}
    env = Environment(depth=30.0, water_density=0.0, gravity=G)
    return System("pinned_body", environment=env, line_types={"nylon": lt}, points=points,
                  lines={"1": Line("1", "nylon", 5.0, 1, "1", "2")}, bodies={"pin": body})


def test_a_pendulum_on_an_accelerating_pin_swings_about_the_exact_tilt():
    """A pendulum whose pin accelerates at a = 0.5 m/s^2 from rest (MoorDyn's pinned-body
    test: pinnedBody.txt in a vacuum) swings between 0 and twice the tilt
    ``theta = atan(-a / g)`` of the effective gravity (exact, whatever the amplitude: the
    motion is symmetric about it), with the compound pendulum's period under
    ``sqrt(g^2 + a^2)``; 2e-4 rad and 1e-3 in period (dt 0.02 s: the scheme's period error
    is ``(omega dt)^2 / 12 = 6e-6``; the amplitude's lengthening, 1.6e-4, is in the
    expected period)."""
    a, duration, dt = 0.5, 12.0, 0.02
    system = _accelerating_pin(a, duration, dt)
    static = solve_statics(system)
    assert static.success, static.message
    run = simulate(system, DynamicsSettings(duration=duration, dt=dt), initial=static)
    assert run.success, run.message
    pose = run.body_pose[:, 0]
    assert pose[:, 1] == pytest.approx(0.5 * a * run.time**2, abs=1e-9)
    roll = pose[:, 3]
    theta = math.atan(-a / G)
    assert 0.5 * (roll.max() + roll.min()) == pytest.approx(theta, abs=2e-4)
    assert roll.max() == pytest.approx(0.0, abs=2e-4)
    L, d = 10.0, 2.0
    arm = 10.0  # pin to centre of gravity
    inertia = L * L / 12 + d * d / 16 + arm * arm  # per unit mass, about the pin
    amplitude = abs(theta)
    expected = 2 * math.pi * math.sqrt(inertia / (math.hypot(G, a) * arm)) * (
        1 + amplitude**2 / 16)
    assert _period(run.time, roll) == pytest.approx(expected, rel=1e-3)
    # the pin pushes the body along with its acceleration and holds its weight: on average
    # over whole swings (m a, m g); checked on the instantaneous balance's mean
    m = 5.0e4
    mean = run.body_pin_force[1:, 0].mean(axis=0)
    assert mean[1] == pytest.approx(m * a, rel=0.1)
    assert mean[2] == pytest.approx(m * G, rel=0.01)


def test_pinned_body_statics_tangent_matches_finite_differences():
    """The coupled statics' tangent with a pinned body off its equilibrium (a rod on a line):
    its rotational rows and columns against central differences of the residual; the held
    translations are an identity block decoupled from the rest."""
    from moorline.mesh import discretize
    from moorline.solvers.bodies import BodyState, place_slaves
    from moorline.solvers.coupled_statics import CoupledStatics
    from moorline.solvers.initial_shape import initial_positions

    system = _accelerating_pin(0.0, 1.0, 0.1)
    body = replace(system.bodies["pin"], motion=None, center_of_gravity=(0.4, -0.3, -10.0))
    points = {**system.points, "b": Point("b", "body", (1.0, 0.5, -14.0), body="pin"),
              "anchor": Point("anchor", "fixed", (20.0, 3.0, -25.0))}
    lines = {**system.lines, "2": Line("2", "nylon", 22.0, 8, "anchor", "b")}
    system = replace(system, bodies={"pin": body}, points=points, lines=lines,
                     environment=replace(system.environment, water_density=RHO))
    mesh = discretize(system)
    problem = CoupledStatics(mesh)
    poses = BodyState.initial(mesh).moved(np.zeros((1, 3)), np.array([[0.1, -0.2, 0.05]]))
    x = place_slaves(mesh, poses, initial_positions(system, mesh))
    x[mesh.free_nodes] += np.random.default_rng(3).normal(scale=0.05,
                                                           size=x[mesh.free_nodes].shape)
    R, state = problem.residual(x, poses)
    K = problem.tangent(x, poses, state).toarray()
    held = problem.held
    assert held.sum() == 3 and not R[held].any()
    n = problem.n_unknowns
    fd = _central_differences(lambda du: problem.residual(*problem.update(x, poses, du))[0],
                              n, np.flatnonzero(~held))
    free = ~held
    Kf, fdf = K[np.ix_(free, free)], fd[np.ix_(free, free)]
    assert np.allclose(Kf, fdf, rtol=1e-4, atol=1e-5 * np.abs(K).max())
    assert not K[np.ix_(held, free)].any() and not K[np.ix_(free, held)].any()
    assert np.allclose(K[np.ix_(held, held)], K[held, held][0] * np.eye(3))


def test_pinned_body_step_tangent_matches_finite_differences():
    """The effective tangent of a time step with a pinned body on a moving pin (spinning,
    accelerating, a line on it) against central differences of the step's residual in every
    unknown but the held translations."""
    from moorline.solvers.bodies import BodyState
    from moorline.solvers.dynamic_model import DynamicModel
    from moorline.solvers.dynamics import _fluid, _initial_state, _stepper
    from moorline.solvers.excitation import Excitation
    from moorline.solvers.newmark import _Step

    system = _accelerating_pin(0.5, 2.0, 0.05)
    body = replace(system.bodies["pin"], center_of_gravity=(0.4, -0.3, -10.0),
                   added_mass=tuple(tuple(float(v) for v in row)
                                    for row in 1e3 * (np.eye(6) + 0.1)))
    points = {**system.points, "b": Point("b", "body", (1.0, 0.5, -14.0), body="pin"),
              "anchor": Point("anchor", "fixed", (20.0, 3.0, -25.0))}
    lines = {**system.lines, "2": Line("2", "nylon", 22.0, 8, "anchor", "b")}
    system = replace(system, bodies={"pin": body}, points=points, lines=lines)
    start = solve_statics(system)
    assert start.success, start.message
    settings = DynamicsSettings(dt=0.05, fast_path=False)
    fluid = _fluid(system, settings)
    model = DynamicModel(start.mesh, fluid)
    exc = Excitation(start.mesh, start.positions)
    state = _initial_state(model, exc, start.positions, settings.dt, initial=start)
    spin = np.array([[0.0, 0.3, 0.0, 0.3, -0.2, 0.4]])
    state = replace(state, bodies=BodyState(state.bodies.r, state.bodies.R, spin, 0.5 * spin))
    stepper = _stepper(model, fluid, settings, 1e-6, system)
    h = settings.dt
    stepper._current = _Step(state, h, exc.constrained_state(h), None)
    u = (state.x + h * state.v, np.array([[0.0, 0.0, 0.0, 0.04, -0.03, 0.05]]))
    K = stepper.tangent_matrix(u, stepper.residual(u, True)).toarray()
    held = stepper.layout.held
    fd = _central_differences(lambda e: stepper.residual(stepper.update(u, e), False).r,
                              K.shape[0], np.flatnonzero(~held))
    free = ~held
    assert np.allclose(K[np.ix_(free, free)], fd[np.ix_(free, free)], rtol=1e-5,
                       atol=1e-6 * np.abs(K).max())
    assert not K[np.ix_(held, free)].any() and not K[np.ix_(free, held)].any()


def test_modal_analysis_refuses_pinned_bodies():
    """Modal (and strumming, stochastic) matrices have no held body dofs: a clear error
    naming the pinned body, not spurious modes."""
    from moorline.errors import CaseError
    from moorline.solvers.modal import solve_modes

    system = _accelerating_pin(0.0, 1.0, 0.1)
    system = replace(system, bodies={"pin": replace(system.bodies["pin"], motion=None)})
    with pytest.raises(CaseError, match=r"pinned bodies \(pin\)"):
        solve_modes(system)


def test_accelerating_pin_against_moordyn_on_pinned_body_deck(tmp_path):
    """MoorDyn-C (``moordyn`` module) runs tests/Mooring/body_tests/pinnedBody.txt itself
    (the CoupledPinned body, its pin driven at 0.5 m/s^2 along y, dt 0.01 s, 12 s, as
    MoorDyn's ``tests/bodies.cpp``); moorline its equivalent (:func:`_accelerating_pin`, dt
    0.02 s). Measured: MoorDyn's mid-swing tilt is the exact one to 4e-8 rad, moorline's to
    3.5e-6 rad; periods 6.608299 s (MoorDyn) and 6.608590 s (moorline, +4.4e-5: the
    average-acceleration scheme's elongation ``(omega dt)^2 / 12 = 3.0e-5`` plus the
    zero-crossing estimate). Tolerances: 2e-5 rad on the tilt and 1e-4 on the period (about
    twice the scheme's error at this step)."""
    moordyn = pytest.importorskip("moordyn")
    from moorline.compare.moordyn_runner import silenced_fd

    source = Path(__file__).parent / "data/moordyn/public/MoorDyn/body_tests/pinnedBody.txt"
    deck = tmp_path / source.name  # MoorDyn writes its .log and .out files next to the deck
    deck.write_bytes(source.read_bytes())
    a, duration = 0.5, 12.0
    x, xd = [0.0, 0.0, -5.0, 0.0, 0.0, 0.0], [0.0] * 6
    with silenced_fd(1):
        md = moordyn.Create(str(deck))
        moordyn.SetVerbosity(md, moordyn.LEVEL_ERR)
        assert moordyn.Init(md, x, xd) == 0
        body = moordyn.GetBody(md, 1)
        t, dt, times, theirs = 0.0, 0.01, [], []
        try:
            while t < duration - 1e-9:
                x[1], xd[1] = 0.5 * a * (t + dt) ** 2, a * (t + dt)
                moordyn.Step(md, x, xd, t, dt)
                t += dt
                times.append(t)
                theirs.append(moordyn.GetBodyState(body)[0][3])
        finally:
            moordyn.Close(md)
    times, theirs = np.array(times), np.array(theirs)
    system = _accelerating_pin(a, duration, 0.02)
    run = simulate(system, DynamicsSettings(duration=duration, dt=0.02),
                   initial=solve_statics(system))
    assert run.success, run.message
    ours = run.body_pose[:, 0, 3]
    assert 0.5 * (ours.max() + ours.min()) == pytest.approx(
        0.5 * (theirs.max() + theirs.min()), abs=2e-5)
    assert _period(run.time, ours) == pytest.approx(_period(times, theirs), rel=1e-4)


def _hosted() -> System:
    """A free buoy (matrix hydrostatics, four lines) carrying a rod pinned to it 1 m off its
    axis: the rod hangs 8 m below, a line from its end to the seabed pulls it over."""
    host = Body("host", "free", position=(0.0, 0.0, 0.0), mass=4.0e5,
                center_of_gravity=(0.0, 0.0, -1.0),
                inertia=((5e6, 0, 0), (0, 5e6, 0), (0, 0, 8e6)),
                hydrostatics=Hydrostatics("matrix", volume=4.6e2, center_of_buoyancy=(0, 0, -2.0),
                                          stiffness=tuple(tuple(float(v) for v in row) for row in
                                                          np.diag([0, 0, 8e5, 2e7, 2e7, 0]))))
    rod = Body("rod", "pinned", position=(1.0, 0.5, -3.0), rotation=(0.0, math.pi / 2, 0.0),
               mass=3.0e3, center_of_gravity=(4.0, 0.0, 0.0),
               inertia=((50.0, 0, 0), (0, 1.6e4, 0), (0, 0, 1.6e4)),
               hydrostatics=Hydrostatics("matrix", volume=1.0, center_of_buoyancy=(4.0, 0, 0)),
               pin_body="host")
    lt = LineType("chain", 0.1, 60.0, 5e7, Cd=1.0)
    points = {"tip": Point("tip", "body", (8.0, 0.0, 0.0), body="rod"),
              "foot": Point("foot", "fixed", (30.0, 0.0, -60.0))}
    lines = {"pull": Line("pull", "chain", 62.0, 10, "foot", "tip")}
    for k in range(4):
        c, s = math.cos(k * math.pi / 2 + 0.3), math.sin(k * math.pi / 2 + 0.3)
        points[f"f{k}"] = Point(f"f{k}", "body", (5 * c, 5 * s, -2.0), body="host")
        points[f"a{k}"] = Point(f"a{k}", "fixed", (200 * c, 200 * s, -80.0))
        lines[f"m{k}"] = Line(f"m{k}", "chain", 215.0, 12, f"a{k}", f"f{k}")
    env = Environment(depth=100.0, water_density=RHO, gravity=G)  # anchors off the seabed
    return System("hosted", environment=env, line_types={"chain": lt}, points=points,
                  lines=lines, bodies={"host": host, "rod": rod})


def test_pin_on_a_free_body_statics_tangent_matches_finite_differences():
    """A rod pinned to a free buoy: the coupled statics' tangent (the rod's translation
    following the buoy, the pin force moved onto it) against central differences of the
    residual, off equilibrium."""
    from moorline.mesh import discretize
    from moorline.solvers.bodies import BodyState, place_slaves, spin_projection
    from moorline.solvers.coupled_statics import CoupledStatics
    from moorline.solvers.initial_shape import initial_positions

    system = _hosted()
    mesh = discretize(system)
    problem = CoupledStatics(mesh)
    poses = BodyState.initial(mesh).moved(np.array([[0.5, -0.3, 0.2], [0.0, 0.0, 0.0]]),
                                          np.array([[0.05, -0.04, 0.1], [0.1, -0.2, 0.05]]))
    poses = problem.layout.place_pins(poses)
    x = place_slaves(mesh, poses, initial_positions(system, mesh))
    x[mesh.free_nodes] += np.random.default_rng(4).normal(scale=0.05,
                                                           size=x[mesh.free_nodes].shape)
    R, state = problem.residual(x, poses)
    K = problem.tangent(x, poses, state).toarray()
    held = problem.held
    n = problem.n_unknowns
    fd = _central_differences(lambda du: problem.residual(*problem.update(x, poses, du))[0],
                              n, np.flatnonzero(~held))
    # the rod's spin about its own axis is projected out (a mechanism): compare across it
    assert problem.layout.spin.tolist() == [False, True]
    S = spin_projection(problem.layout, poses)[0].toarray()
    K, fd = S @ K @ S, S @ fd @ S
    free = ~held
    Kf, fdf = K[np.ix_(free, free)], fd[np.ix_(free, free)]
    bad = np.argwhere(~np.isclose(Kf, fdf, rtol=1e-4, atol=1e-5 * np.abs(K).max()))
    assert not len(bad), [(i, j, Kf[i, j], fdf[i, j]) for i, j in bad[:6]]
    host, rod = problem.body_dof
    assert np.abs(K[host:host + 6, rod + 3:rod + 6]).max() > 1e4  # the pin couples them


@pytest.mark.parametrize("scheme,zeta", [("newmark", 0.0), ("hht", 0.05)])
def test_pin_on_a_free_body_step_tangent_matches_finite_differences(scheme, zeta):
    """The effective tangent of a time step with a rod pinned to a free buoy, both spinning
    and accelerating (the rod's origin following the buoy's pin: position, velocity and
    acceleration), with HHT and Rayleigh damping, against central differences of the step's
    residual in every unknown but the held translations."""
    from moorline.solvers.bodies import BodyState
    from moorline.solvers.dynamic_model import DynamicModel
    from moorline.solvers.dynamics import _fluid, _initial_state, _stepper
    from moorline.solvers.excitation import Excitation
    from moorline.solvers.newmark import _Step

    system = _hosted()
    start = solve_statics(system)
    assert start.success, start.message
    settings = DynamicsSettings(dt=0.05, scheme=scheme, alpha=-0.2, rayleigh_ratio=zeta,
                                rayleigh_frequencies=(1.0, 10.0))
    fluid = _fluid(system, settings)
    model = DynamicModel(start.mesh, fluid)
    exc = Excitation(start.mesh, start.positions)
    state = _initial_state(model, exc, start.positions, settings.dt, initial=start)
    spin = np.array([[0.1, -0.05, 0.02, 0.03, -0.02, 0.04], [0.0, 0.0, 0.0, 0.2, -0.3, 0.1]])
    stepper = _stepper(model, fluid, settings, 1e-6, system)
    moving = stepper.bodies.layout.place_pins(
        BodyState(state.bodies.r, state.bodies.R, spin, 0.5 * spin))
    state = replace(state, bodies=moving)
    stepper._setup_rayleigh(state) if zeta else None
    h = settings.dt
    stepper._current = _Step(state, h, exc.constrained_state(h), None)
    u = (state.x + h * state.v, np.array([[0.01, -0.02, 0.01, 0.02, -0.01, 0.03],
                                          [0.0, 0.0, 0.0, 0.04, -0.03, 0.05]]))
    K = stepper.tangent_matrix(u, stepper.residual(u, True)).toarray()
    held = stepper.layout.held
    fd = _central_differences(lambda e: stepper.residual(stepper.update(u, e), False).r,
                              K.shape[0], np.flatnonzero(~held))
    free = ~held
    Kf, fdf = K[np.ix_(free, free)], fd[np.ix_(free, free)]
    bad = np.argwhere(~np.isclose(Kf, fdf, rtol=1e-5, atol=1e-6 * np.abs(K).max()))
    assert not len(bad), [(i, j, Kf[i, j], fdf[i, j]) for i, j in bad[:6]]


def test_rod_pinned_to_a_free_buoy_balances_forces_and_moments():
    """The buoy and the rod pinned to it at equilibrium: the pin is internal, so the loads
    written here (weights, constant buoyancies, the buoy's heave restoring ``K33 dz``) and
    the lines' forces on both bodies sum to zero; the rod's moments about its pin sum to
    zero; and the pin sits on the buoy where it was put."""
    system = _hosted()
    static = solve_statics(system)
    assert static.success, static.message
    host, rod = system.bodies["host"], system.bodies["rod"]
    up = np.array([0.0, 0.0, 1.0])
    rise = static.body_position("host")[2] - host.position[2]
    host_load = (RHO * G * host.hydrostatics.volume - host.mass * G - 8e5 * rise) * up
    rod_load = (RHO * G * rod.hydrostatics.volume - rod.mass * G) * up
    mooring = sum(static.end_force(f"m{k}", "b") for k in range(4))
    pull = static.end_force("pull", "b")
    scale = host.mass * G
    assert np.abs(host_load + rod_load + mooring + pull).max() < 1e-6 * scale
    pin = static.body_position("rod")
    R_host = rotation_matrix(static.body_rotation("host"))
    assert pin == pytest.approx(static.body_position("host") + R_host @ [1.0, 0.5, -3.0],
                                abs=1e-9)
    axis = rotation_matrix(static.body_rotation("rod")) @ np.array([1.0, 0.0, 0.0])
    moment = np.cross(8.0 * axis, pull) + np.cross(4.0 * axis, rod_load)
    assert np.abs(moment).max() < 1e-6 * 8.0 * np.linalg.norm(pull)
    assert static.pin_reaction("rod") == pytest.approx(-(pull + rod_load), abs=1e-6 * scale)


def test_pushed_host_and_pinned_rod_move_their_centre_of_mass_as_newton_says():
    """A free body (1 t) in a vacuum without gravity, carrying a 200 kg rod pinned 1 m off
    its origin, pushed by a constant 1 kN at its origin: the rod swings and the host recoils
    through the pin, but the centre of mass of the two moves as ``F t^2 / (2 M)`` (the pin
    force is internal: what it takes from one body it gives the other; the eased-in force
    integrated twice in closed form). Tolerance 1e-4 of
    the displacement after 4 s: the step (0.01 s) integrates the rod's rotation and its
    centre's path separately, an O(dt^2) mismatch."""
    force = 1.0e3
    ramp = 1.0  # the force eases in (the run starts at rest: no jump at t = 0)
    push = Motion("table", times=(0.0, 1e6), values=((force, 0.0, 0.0), (force, 0.0, 0.0)),
                  ramp_time=ramp)
    host = Body("host", "free", mass=1.0e3, inertia=((100.0, 0, 0), (0, 100.0, 0), (0, 0, 100.0)),
                force_history=push)
    rod = Body("rod", "pinned", position=(1.0, 0.0, 0.0), rotation=(0.0, 0.0, math.pi / 2),
               mass=200.0, center_of_gravity=(2.0, 0.0, 0.0),
               inertia=((1.0, 0, 0), (0, 270.0, 0), (0, 0, 270.0)), pin_body="host")
    lt = LineType("wire", 0.01, 1.0, 1e6)
    points = {"p": Point("p", "fixed", (50.0, 0.0, 0.0)), "q": Point("q", "fixed", (52.0, 0, 0))}
    system = System("pushed", environment=Environment(water_density=0.0, gravity=0.0),
                    line_types={"wire": lt}, points=points,
                    lines={"w": Line("w", "wire", 2.0, 1, "p", "q")},
                    bodies={"host": host, "rod": rod})
    static = solve_statics(system)
    assert static.success, static.message
    run = simulate(system, DynamicsSettings(duration=4.0, dt=0.01), initial=static)
    assert run.success, run.message
    pose = run.body_pose
    centre = rotation_matrix(pose[:, 1, 3:]) @ np.array([2.0, 0.0, 0.0]) + pose[:, 1, :3]
    com = (1.0e3 * pose[:, 0, :3] + 200.0 * centre) / 1.2e3
    expected = np.zeros_like(com)
    t, acc = run.time, force / 1.2e3  # F (1 - cos(pi t / T)) / 2 twice integrated, then F
    early = acc * (t**2 / 4 - ramp**2 / (2 * math.pi**2) * (1 - np.cos(math.pi * t / ramp)))
    late = acc * (ramp**2 / 4 - ramp**2 / math.pi**2 + ramp / 2 * (t - ramp)
                  + (t - ramp) ** 2 / 2)
    expected[:, 0] = np.where(t < ramp, early, late)
    com0 = com[0]
    assert com - com0 == pytest.approx(expected, abs=1e-4 * expected[-1, 0])
    swing = np.degrees(np.abs(pose[:, 1, 3:]).max())
    assert swing > 10.0  # the rod did swing
    pin = pose[:, 0, :3] + rotation_matrix(pose[:, 0, 3:]) @ np.array([1.0, 0.0, 0.0])
    assert np.abs(pin - pose[:, 1, :3]).max() < 1e-9
