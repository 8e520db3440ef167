"""Bodies without a static equilibrium in some dofs (issue 14): the free-floating buoy of
OpenFAST r-test ``md_float`` (surge, sway and yaw have no restoring: held where the deck puts
them, heave and pitch balanced) and the free rods of ``md_horizontal`` / ``md_vertical``
(sinking with nothing to hold them: "no static equilibrium"; a dynamics from the deck's pose,
``start: initial``, falls with ``(W - B) / (m + A)``). Deck origins in
tests/data/moordyn/public/README.md.

The buoy's expected values are written here from its deck (two coaxial rods on a free body,
rods hydrostatics: the buoyancy of each rod's submerged axis length, Archimedes), never from
moorline's output; md_float against MoorDyn-C 2.7 (the ``moordyn`` module) at the end."""

from __future__ import annotations

import math
import re
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from moorline.cli import cli
from moorline.io import load_case
from moorline.io.case_writer import write_case
from moorline.io.moordyn import read_moordyn
from moorline.model import DynamicsSettings
from moorline.solvers.dynamics import simulate
from moorline.solvers.statics import solve_statics

RTEST = Path(__file__).parent / "data/moordyn/public/OpenFAST-r-test/modules/moordyn"
FLOAT, HORIZONTAL, VERTICAL = (RTEST / c / "moordyn.dat"
                               for c in ("md_float", "md_horizontal", "md_vertical"))

#: md_float's rods (deck ``RODS`` and ``ROD TYPES``), vertical in the body frame: z of end A
#: and end B [m], diameter [m], mass per length [kg/m]; MoorDyn's water (``rho``, ``g``).
CAN, WEIGHT = (-1.0, 4.0, 2.0, 1.0e2), (-2.0, -1.0, 4.0, 2.15e4)
RHO, G = 1025.0, 9.80665


def float_upright(waterplane: float = 1.0) -> dict[str, float]:
    """md_float upright at rest, from its deck: mass ``m``, centre of gravity ``zg`` (body
    frame), the origin's height ``z`` at the Archimedes draft (the weight rod fully wet, the
    can wet from its end A up to ``z = 0``: ``L_sub = (m / rho - V_w) / A_can``), centre of
    buoyancy ``zb``, pitch stiffness ``k55 = W (zb - zg) + waterplane rho g pi d^4 / 64``
    (the can's waterplane inertia, ``waterplane`` times), rods as solid cylinders (MoorDyn's
    ``m (L^2 / 12 + d^2 / 16)``; ``inertia`` about the origin), added mass ``Ca rho A`` per
    wet length across (Ca = 1) and ``CaEnd rho (2/3) pi r^3`` along at each wet end
    (CaEnd = 1); ``heave_period`` ``2 pi sqrt((m + A33) / (rho g A_can))`` and
    ``pitch_period`` of the (surge, pitch) system about the origin, surge condensed."""
    rods = (CAN, WEIGHT)
    m = sum((b - a) * mpl for a, b, _, mpl in rods)
    zg = sum((b - a) * mpl * (a + b) / 2 for a, b, _, mpl in rods) / m
    area = {d: math.pi * d**2 / 4 for _, _, d, _ in rods}
    v_weight = area[4.0] * 1.0
    wet = (m / RHO - v_weight) / area[2.0]  # the can's wet length
    z = -wet - CAN[0]  # the can's end A (1 m below the origin) at z = -wet
    wet_parts = ((CAN[0], CAN[0] + wet, 2.0), (WEIGHT[0], WEIGHT[1], 4.0))
    volume = sum((b - a) * area[d] for a, b, d in wet_parts)
    zb = sum((b - a) * area[d] * (a + b) / 2 for a, b, d in wet_parts) / volume
    inertia = sum((b - a) * mpl * ((b - a) ** 2 / 12 + d**2 / 16 + ((a + b) / 2) ** 2)
                  for a, b, d, mpl in rods)  # about the origin
    a11 = sum(RHO * area[d] * (b - a) for a, b, d in wet_parts)
    a15 = sum(RHO * area[d] * (b**2 - a**2) / 2 for a, b, d in wet_parts)
    a55 = sum(RHO * area[d] * (b**3 - a**3) / 3 for a, b, d in wet_parts)
    a33 = sum(RHO * 2 / 3 * math.pi * (d / 2) ** 3 for d in (2.0, 4.0, 4.0))  # wet ends
    k55 = m * G * (zb - zg) + waterplane * RHO * G * math.pi * 2.0**4 / 64
    mass = np.array([[m + a11, m * zg + a15], [m * zg + a15, inertia + a55]])
    pitch_mass = mass[1, 1] - mass[0, 1] ** 2 / mass[0, 0]  # surge (no stiffness) condensed
    return {"m": m, "zg": zg, "inertia": inertia, "z": z, "zb": zb, "k55": k55,
            "heave_period": 2 * math.pi * math.sqrt((m + a33) / (RHO * G * area[2.0])),
            "pitch_period": 2 * math.pi * math.sqrt(pitch_mass / k55)}


def float_deck(folder: Path, z: float, pitch_deg: float) -> Path:
    """md_float's deck with its body's initial pose (Z0, p0) changed (nothing else)."""
    text = FLOAT.read_text()
    row = re.compile(r"^1(\s+)free(\s+)0(\s+)0(\s+)-1(\s+)0(\s+)45 ", re.M)
    assert len(row.findall(text)) == 1
    text = row.sub(f"1\\1free\\2 0\\3 0\\4 {z!r}\\5 0\\6 {pitch_deg!r} ", text)
    deck = folder / "md_float.dat"
    deck.write_text(text)
    return deck


def test_free_floating_buoy_statics_hold_its_neutral_dofs_and_balance_heave_and_pitch():
    """md_float: the statics converge with surge, sway and yaw held at the deck's pose (the
    message names them), upright (pitch 0: the buoy is axisymmetric and stable, zb > zg) at
    the Archimedes draft (:func:`float_upright`), from the deck's 45 deg. Tolerance: the
    statics tolerance (1e-8 of the weight, 2e5 N) over the heave stiffness (3.2e4 N/m) gives
    ~1e-7 m; 1e-6 allowed (and 1e-6 rad)."""
    system = read_moordyn(FLOAT)
    env = system.environment
    assert (env.water_density, env.gravity) == (RHO, G)
    body = system.bodies["body1"]
    expected = float_upright()
    assert body.mass == pytest.approx(expected["m"], rel=1e-12)
    assert expected["zb"] > expected["zg"]
    static = solve_statics(system)
    assert static.success, static.message
    assert "held at the case's pose" in static.message
    for dof in ("surge", "sway", "yaw"):
        assert f"body1 {dof}" in static.message
    assert "heave" not in static.message and "pitch" not in static.message
    pose = static.body_pose[0]
    assert pose[[0, 1, 3, 5]] == pytest.approx(np.zeros(4), abs=1e-12)
    assert pose[2] == pytest.approx(expected["z"], abs=1e-6)
    assert pose[4] == pytest.approx(0.0, abs=1e-6)


def test_free_floating_buoy_small_pitch_decay_period_matches_its_modes(tmp_path):
    """md_float moved to its upright equilibrium (the deck's Z0 and p0 only: the converter
    takes the rods' added mass at the deck's pose) and released from 0.02 rad of pitch at
    rest: its pitch period against the linear (surge, pitch) system of
    :func:`float_upright` (surge has no stiffness and no force: condensed; heave is
    uncoupled upright). Tolerance 0.2 %: Newmark's period elongation at 100 steps a period
    is (w h)^2 / 12 = 0.03 %, and the quadratic drag and the nonlinearity at 0.02 rad are
    smaller."""
    expected = float_upright()
    system = read_moordyn(float_deck(tmp_path, expected["z"], 0.0))
    static = solve_statics(system)
    assert static.success, static.message
    assert static.body_pose[0, 4] == pytest.approx(0.0, abs=1e-9)
    pose = static.body_pose.copy()
    pose[0, 4] = 0.02
    period = expected["pitch_period"]
    dt = period / 100
    run = simulate(system, DynamicsSettings(duration=3 * period, dt=dt, start="initial"),
                   initial=replace(static, body_pose=pose), output_every=dt)
    assert run.success, run.message
    measured = _period(run.time, run.body_pose[:, 0, 4])
    assert measured == pytest.approx(period, rel=2e-3)


def _period(t: np.ndarray, y: np.ndarray) -> float:
    """Mean period between upward zero crossings of ``y`` about its mean (interpolated)."""
    y = y - y.mean()
    up = np.flatnonzero((y[:-1] < 0) & (y[1:] >= 0))
    assert len(up) >= 2
    crossings = t[up] - y[up] * (t[up + 1] - t[up]) / (y[up + 1] - y[up])
    return float(np.mean(np.diff(crossings)))


@pytest.mark.parametrize("deck", [HORIZONTAL, VERTICAL], ids=["horizontal", "vertical"])
def test_sinking_rod_statics_say_no_equilibrium_naming_body_dof_and_force(deck, tmp_path):
    """md_horizontal / md_vertical: a rod (10 m, 2 m in diameter, 3250 kg/m) with nothing
    holding it: `moorline statics` ends with exit 1 and one line naming the body, the dof
    (heave) and its out-of-balance force (W - B, written here)."""
    case = tmp_path / "case.yaml"
    write_case(read_moordyn(deck), case)
    result = CliRunner().invoke(cli, ["statics", str(case), "--out", str(tmp_path / "o"),
                                      "--quiet", "--no-plots"])
    assert result.exit_code == 1, result.output
    assert "Traceback" not in result.output
    lines = [line for line in result.output.splitlines() if line.startswith("error:")]
    assert len(lines) == 1, result.output
    g, rho = 9.80665, 1025.0
    net = (3250.0 * 10.0 - rho * math.pi * 1.0**2 * 10.0) * g  # weight - buoyancy [N]
    assert "no static equilibrium" in lines[0]
    assert "body rod1 has no restoring in heave" in lines[0]
    assert f"{-net:.4g}" in lines[0]


@pytest.mark.parametrize("deck", [HORIZONTAL, VERTICAL], ids=["horizontal", "vertical"])
def test_sinking_rod_falls_from_its_initial_pose(deck, tmp_path):
    """A dynamics from the deck's pose (``start: initial``, through the case file) sinks the
    rod with the acceleration ``(W - B) / (m + A_33)`` (``A_33 = rho V Ca`` across a
    horizontal rod, ``rho V CaEnd``-like end added mass along a vertical one: the case's
    added mass) over the first 0.5 s. Tolerance 0.5 %: the drag is left on; at the end of
    the 0.5 s it is ``1/2 rho Cd A (a t)^2``, below 0.3 % of ``W - B`` (bound in the test),
    and Newmark is exact for a constant acceleration."""
    system = read_moordyn(deck)
    case = tmp_path / "case.yaml"
    system = replace(system, analyses=(DynamicsSettings(duration=0.5, dt=0.01,
                                                        start="initial"),))
    write_case(system, case)
    system = load_case(case)
    settings = system.analyses[0]
    assert settings.start == "initial"
    rod = system.bodies["rod1"]
    g, rho = system.environment.gravity, system.environment.water_density
    assert rod.mass == pytest.approx(3250.0 * 10.0, rel=1e-12)  # the deck's Mass/m, length
    net = (rod.mass - rho * math.pi * 1.0**2 * 10.0) * g  # wet: its whole volume (Archimedes)
    a = net / (rod.mass + np.asarray(rod.added_mass)[2, 2])
    drag = 0.5 * rho * rod.Cd * rod.drag_area[2] * (a * 0.5) ** 2
    assert drag < 3e-3 * net
    run = simulate(system, settings, output_every=0.1)
    assert run.success, run.message
    z = run.body_pose[:, 0, 2]
    assert z[0] == pytest.approx(rod.position[2], abs=1e-12)  # started at the deck's pose
    fall = z[0] - z
    assert fall[-1] == pytest.approx(0.5 * a * run.time[-1] ** 2, rel=5e-3)
    assert -run.body_velocity[-1, 0, 2] == pytest.approx(a * run.time[-1], rel=5e-3)
    assert run.body_pose[-1, 0, [0, 1]] == pytest.approx([0.0, 0.0], abs=1e-9)


def test_dynamics_start_initial_runs_through_the_cli(tmp_path):
    """`moorline run` of md_horizontal with a dynamics ``start: initial`` and no statics:
    exit 0 (the statics alone would say "no equilibrium")."""
    system = replace(read_moordyn(HORIZONTAL),
                     analyses=(DynamicsSettings(duration=0.2, dt=0.05, start="initial"),))
    case = tmp_path / "case.yaml"
    write_case(system, case)
    result = CliRunner().invoke(cli, ["run", str(case), "--out", str(tmp_path / "o"),
                                      "--quiet", "--no-plots"])
    assert result.exit_code == 0, result.output


def test_bad_dynamics_start_is_a_case_error(tmp_path):
    """``start: rest`` is refused naming the key (exit 2)."""
    system = replace(read_moordyn(HORIZONTAL),
                     analyses=(DynamicsSettings(duration=0.2, dt=0.05),))
    case = tmp_path / "case.yaml"
    write_case(system, case)
    text = case.read_text().replace("start: statics", "start: rest")
    assert "start: rest" in text
    case.write_text(text)
    result = CliRunner().invoke(cli, ["run", str(case), "--out", str(tmp_path / "o"),
                                      "--quiet", "--no-plots"])
    assert result.exit_code == 2, result.output
    assert "start" in result.output


def test_find_neutral_tells_round_off_from_a_small_stiffness():
    """A row at round-off (1e-12 of the largest entry) is neutral; a small real stiffness
    (1e-6) is not; a neutral dof with a force is unbalanced, without one held."""
    from moorline.solvers.neutral_dofs import find_neutral

    S = np.diag([1e5, 1e-7, 1e5, 1e5, 0.1, 0.0])
    S[1, 3] = 1e-8  # round-off coupling in the sway row
    r = np.array([0.0, 0.0, 0.0, 0.0, 0.0, 5.0])
    out = find_neutral(S, r, np.array([0]), 0, [True], ["b"], tolerance=1e-3)
    assert out.names == ["b sway"]
    assert out.held.tolist() == [False, True, False, False, False, False]
    assert out.unbalanced == [("b", "yaw", 5.0)]
    assert "body b has no restoring in yaw and an out-of-balance moment of 5" in \
        out.no_equilibrium()


# ------------------------------------------------------------- md_float against MoorDyn-C
def _moordyn_body_history(deck: Path, duration: float, dt: float = 0.01
                          ) -> tuple[np.ndarray, np.ndarray]:
    """MoorDyn-C 2.7 (the ``moordyn`` module) on ``deck`` from its pose at rest (``TmaxIC``
    0: no initial-condition solve; ``dtM`` 1 ms, the deck's): times and body 1's pose
    (x, y, z, roll, pitch, yaw) every ``dt``."""
    moordyn = pytest.importorskip("moordyn")
    from moorline.compare.moordyn_runner import silenced_fd

    with silenced_fd(1):
        md = moordyn.Create(str(deck))
        moordyn.SetVerbosity(md, moordyn.LEVEL_ERR)
        assert moordyn.Init(md, [], []) == 0
    body = moordyn.GetBody(md, 1)
    t, times, poses = 0.0, [], []
    try:
        while t < duration - 1e-9:
            moordyn.Step(md, [], [], t, dt)
            t += dt
            times.append(t)
            poses.append(moordyn.GetBodyState(body)[0])
    finally:
        moordyn.Close(md)
    return np.array(times), np.array(poses)


def _moorline_body_history(deck: Path, duration: float, dt: float
                           ) -> tuple[np.ndarray, np.ndarray]:
    """moorline on the converted ``deck``, from the deck's pose at rest (``start:
    initial``, as MoorDyn's run): times and the body's pose (position, rotation vector)."""
    system = read_moordyn(deck)
    run = simulate(system, DynamicsSettings(duration=duration, dt=dt, start="initial"),
                   output_every=dt)
    assert run.success, run.message
    return run.time, run.body_pose[:, 0, :]


def moordyn_pitch_period(z: float) -> float:
    """md_float's small-pitch period with MoorDyn-C 2.7's rod model (``source/Rod.cpp``,
    ``Rod::doRHS``), upright with its origin at height ``z``: the transverse added mass
    ``Ca rho A dL`` lumped on the nodes (30 and 1 segments, the deck's ``NumSegs``; end nodes
    half a segment), each weighted by its wet fraction ``VOF0`` of its length ``dL`` counted
    from end A (the waterline at ``h0``, the wet axis length); the pitch stiffness
    ``W (zb - zg) + 3 rho g pi d^4 / 64`` (Rod.cpp's waterplane moment ``pi d^4 / 16 rho g sin
    cos`` less the submerged end cap's ``pi d^4 / 64 rho g sin``). Mass and inertia as
    :func:`float_upright` (MoorDyn corrects its lumped inertia to the solid cylinder's)."""
    a11 = a15 = a55 = 0.0
    for (za, zb, d, _), segments in ((CAN, 30), (WEIGHT, 1)):
        length, per_length = zb - za, RHO * math.pi * d**2 / 4  # Ca = 1
        h0 = min(length, max(0.0, -(z + za)))  # wet axis length from end A
        step, counted = length / segments, 0.0
        for i in range(segments + 1):
            dl = step / 2 if i in (0, segments) else step
            vof = min(1.0, max(0.0, (h0 - counted) / dl))
            counted += dl
            added, height = vof * per_length * dl, za + i * step
            a11, a15, a55 = a11 + added, a15 + added * height, a55 + added * height**2
    exact = float_upright(waterplane=3.0)
    m, zg, inertia = exact["m"], exact["zg"], exact["inertia"]
    mass = np.array([[m + a11, m * zg + a15], [m * zg + a15, inertia + a55]])
    pitch_mass = mass[1, 1] - mass[0, 1] ** 2 / mass[0, 0]
    return 2 * math.pi * math.sqrt(pitch_mass / exact["k55"])


def test_float_equilibrium_against_moordyn(tmp_path):
    """MoorDyn-C released at moorline's static equilibrium of md_float (upright, the
    Archimedes draft; the deck's Z0 and p0 changed to it) stays there: over 20 s its body
    moves less than 1e-6 m and 1e-9 rad (measured: 0; the issue's limit is 1 cm). A vertical
    rod's buoyancy in MoorDyn is the pressure on its end caps, exact, as moorline's."""
    static = solve_statics(read_moordyn(FLOAT))
    assert static.success, static.message
    z = float(static.body_pose[0, 2])
    assert z == pytest.approx(float_upright()["z"], abs=1e-6)
    t, pose = _moordyn_body_history(float_deck(tmp_path, z, 0.0), 20.0, dt=0.1)
    assert t[-1] == pytest.approx(20.0)
    assert np.abs(pose[:, 2] - z).max() < 1e-6
    assert np.abs(pose[:, [0, 1]]).max() < 1e-6 and np.abs(pose[:, 3:]).max() < 1e-9


def test_float_heave_decay_against_moordyn(tmp_path):
    """md_float upright released 0.33 m above its equilibrium (deck Z0 -1.5 m, p0 0): the heave
    of moorline (dt 0.05 s) and MoorDyn (dtM 1 ms) over 3 periods. Periods within 0.05 % of
    each other (Newmark's elongation at 170 steps a period is 1.1e-4) and within 0.1 % of
    the closed form ``2 pi sqrt((m + A33) / (rho g A_can))`` (8.5515 s; end added mass of
    the three wet end caps; the end drag damps the heave by ~0.2 per cycle, ``zeta`` ~0.03,
    which lengthens the period by ~``zeta^2 / 2`` = 4e-4), and the histories within 3 mm
    (drag: MoorDyn's on the end caps, moorline's lumped at the origin: the same ``CdEnd A``
    here, all axial). Measured: MoorDyn 8.5565 s, moorline 8.5581 s, histories within
    0.4 mm; over 60 s at dt 0.02 s the cycle means agree to 1e-5 m."""
    deck = float_deck(tmp_path, -1.5, 0.0)
    expected = float_upright()["heave_period"]
    t_md, pose_md = _moordyn_body_history(deck, 3.05 * expected, dt=0.05)
    t_ml, pose_ml = _moorline_body_history(deck, 3.05 * expected, dt=0.05)
    period_md, period_ml = _period(t_md, pose_md[:, 2]), _period(t_ml, pose_ml[:, 2])
    assert period_md == pytest.approx(expected, rel=1e-3)
    assert period_ml == pytest.approx(period_md, rel=5e-4)
    n = min(len(t_md), len(t_ml))
    assert t_ml[1:n] == pytest.approx(t_md[:n - 1], abs=1e-9)  # moorline's starts at t = 0
    assert np.abs(pose_ml[1:n, 2] - pose_md[:n - 1, 2]).max() < 3e-3


def test_float_pitch_decay_against_moordyn(tmp_path):
    """md_float at its equilibrium tilted 2 deg (deck Z0 -1.832 m, p0 2): the pitch period
    of moorline (dt: 100 steps a period) and MoorDyn (dtM 1 ms) over 4 periods. They differ,
    by design: moorline's piercing can has Archimedes' waterplane moment (``rho g I``,
    :mod:`moorline.physics.rod_buoyancy`) and its added mass integrated along the rods;
    MoorDyn-C 2.7's has ``3 rho g I`` and node-lumped added mass
    (:func:`moordyn_pitch_period`). Each code's period is within 0.2 % of the closed form of
    its own model (3.8390 s and 3.7318 s; measured 3.8419 s and 3.7321 s: Newmark's
    elongation 3e-4, the amplitude of 2 deg, the crossings' interpolation), so moorline's is
    2.9 % longer than MoorDyn's (the ratio of the closed forms within 0.3 %)."""
    z = float_upright()["z"]
    deck = float_deck(tmp_path, z, 2.0)
    ours, theirs = float_upright()["pitch_period"], moordyn_pitch_period(z)
    t_md, pose_md = _moordyn_body_history(deck, 4.05 * theirs)
    t_ml, pose_ml = _moorline_body_history(deck, 4.05 * ours, dt=ours / 100)
    period_md, period_ml = _period(t_md, pose_md[:, 4]), _period(t_ml, pose_ml[:, 4])
    assert period_md == pytest.approx(theirs, rel=2e-3)
    assert period_ml == pytest.approx(ours, rel=2e-3)
    assert period_ml / period_md == pytest.approx(ours / theirs, rel=3e-3)
    assert period_ml / period_md - 1 == pytest.approx(0.029, abs=2e-3)
