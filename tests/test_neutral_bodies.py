"""Bodies without a static equilibrium in some dofs (issue 14): the free-floating buoy of
OpenFAST r-test ``md_float`` (surge, sway and yaw have no restoring: held where the deck puts
them, heave and pitch balanced) and the free rods of ``md_horizontal`` / ``md_vertical``
(sinking with nothing to hold them: "no static equilibrium"; a dynamics from the deck's pose,
``start: initial``, falls with ``(W - B) / (m + A)``). Deck origins in
tests/data/moordyn/public/README.md.

md_float's 45 deg pitch decay against MoorDyn-C 2.7 (the ``moordyn`` module, 0.3 s CPU for
30 s) is not reproduced, for a modelling reason outside this test: moorline's converter
takes the surface-piercing rod's buoyancy constant at the deck's 45 deg pose with that pose's
waterplane matrix (heave-pitch coupling included), MoorDyn recomputes it node by node.
Measured: MoorDyn settles at heave -1.89 m, pitch 0, pitch period 3.75 s (mean of 6 cycles
after 5 s); moorline's equilibrium is heave -2.05 m, pitch 1.6 deg, its small-pitch mode
3.00 s, and its decay from 45 deg is dominated by the 8.6 s heave-pitch mode. The tests below
check moorline's statics and dynamics against closed forms of its own (the case's) model."""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import scipy.linalg
import scipy.optimize
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


def _rotation_y(theta: float) -> np.ndarray:
    c, s = math.cos(theta), math.sin(theta)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def _float_balance(body, g: float, rho: float):
    """Heave force and pitch moment about the origin of the converted buoy at heave ``z``
    and pitch ``theta`` (rotation about y only), from the case's inputs: weight at the
    centre of gravity, constant buoyancy ``rho g V`` at the centre of buoyancy (both on the
    body's z axis, their arms turning with it) and the case's constant hydrostatic matrix
    about the deck's pose, ``-K q``."""
    W, B = body.mass * g, rho * g * body.hydrostatics.volume
    zg, zb = body.center_of_gravity[2], body.hydrostatics.center_of_buoyancy[2]
    K = np.asarray(body.hydrostatics.stiffness)
    z0, theta0 = body.position[2], body.rotation[1]  # rotation vector [rad]

    def balance(q):
        z, theta = q
        dq = np.array([0.0, 0.0, z - z0, 0.0, theta - theta0, 0.0])
        restoring = -K @ dq
        # moment of a vertical force F at the arm R(theta) (0, 0, c): -c sin(theta) F
        moment = -zg * math.sin(theta) * (-W) - zb * math.sin(theta) * B
        return [B - W + restoring[2], moment + restoring[4]]

    return balance


def test_free_floating_buoy_statics_hold_its_neutral_dofs_and_balance_heave_and_pitch():
    """md_float: the statics converge with surge, sway and yaw held at the deck's pose (the
    message names them) and heave and pitch at the root of the balance written here from the
    case's inputs (tolerance: the statics tolerance, 1e-8 of the weight, over the stiffness
    of 4e4 N/m gives ~1e-7 m; 1e-6 allowed)."""
    system = read_moordyn(FLOAT)
    body = system.bodies["body1"]
    static = solve_statics(system)
    assert static.success, static.message
    assert "held at the case's pose" in static.message
    for dof in ("surge", "sway", "yaw"):
        assert f"body1 {dof}" in static.message
    assert "heave" not in static.message and "pitch" not in static.message
    pose = static.body_pose[0]
    assert pose[[0, 1, 3, 5]] == pytest.approx(np.zeros(4), abs=1e-12)
    g, rho = system.environment.gravity, system.environment.water_density
    root = scipy.optimize.fsolve(_float_balance(body, g, rho),
                                 [body.position[2], body.rotation[1]],
                                 xtol=1e-13)
    assert pose[2] == pytest.approx(root[0], abs=1e-6)
    assert pose[4] == pytest.approx(root[1], abs=1e-6)


def test_free_floating_buoy_small_pitch_decay_period_matches_its_modes():
    """md_float released from its statics with a small motion along its pitch mode: the
    period of the pitch against the closed form of the linear (surge, heave, pitch) system
    about the equilibrium, written here from the case's inputs: mass matrix about the origin
    (``m``, ``m c_z``, ``-m c_x``, ``I_yy + m |c|^2``, ``c`` the world CoG arm) plus the
    case's constant added mass; stiffness the case's hydrostatic matrix plus the turning arms
    of weight and buoyancy ``-(z_G W - z_B B) cos(theta)`` (surge: none; it is condensed out).
    Tolerance 0.2 %: Newmark's period elongation at 100 steps a period is (w h)^2 / 12 =
    0.03 %, and the quadratic drag and the nonlinearity at 0.01 rad are smaller (measured:
    3.00096 s against 3.00066 s, 0.01 %)."""
    system = read_moordyn(FLOAT)
    body = system.bodies["body1"]
    static = solve_statics(system)
    assert static.success, static.message
    g, rho = system.environment.gravity, system.environment.water_density
    theta_e = static.body_pose[0, 4]
    W, B = body.mass * g, rho * g * body.hydrostatics.volume
    zg, zb = body.center_of_gravity[2], body.hydrostatics.center_of_buoyancy[2]
    K6 = np.asarray(body.hydrostatics.stiffness)
    A6 = np.asarray(body.added_mass)
    dofs = [0, 2, 4]  # surge, heave, pitch
    K = K6[np.ix_(dofs, dofs)].copy()
    K[2, 2] += -(zg * W - zb * B) * math.cos(theta_e)
    c = _rotation_y(theta_e) @ np.array([0.0, 0.0, zg])
    m = body.mass
    Iyy = np.asarray(body.inertia, dtype=float)
    Iyy = Iyy[1] if Iyy.ndim == 1 else Iyy[1, 1]
    M = np.array([[m, 0.0, m * c[2]], [0.0, m, -m * c[0]],
                  [m * c[2], -m * c[0], Iyy + m * (c[0] ** 2 + c[2] ** 2)]])
    M = M + A6[np.ix_(dofs, dofs)]
    w2, modes = scipy.linalg.eigh(K[1:, 1:], _condensed_mass(M))
    # the pitch-dominated mode (largest pitch share); surge follows it with no force
    k = int(np.argmax(np.abs(modes[1, :]) / np.linalg.norm(modes, axis=0)))
    period = 2 * math.pi / math.sqrt(w2[k])
    shape = modes[:, k] / modes[1, k] * 0.01  # 0.01 rad of pitch
    # released from the statics moved along the mode (the case's body keeps its pose: its
    # hydrostatic matrix refers to it), at rest, with the accelerations its loads give
    pose = static.body_pose.copy()
    pose[0, 2] += shape[0]
    pose[0, 4] += shape[1]
    dt = period / 100
    run = simulate(system, DynamicsSettings(duration=3 * period, dt=dt, start="initial"),
                   initial=replace(static, body_pose=pose), output_every=dt)
    assert run.success, run.message
    pitch = run.body_pose[:, 0, 4] - theta_e
    t = run.time
    up = np.flatnonzero((pitch[:-1] < 0) & (pitch[1:] >= 0))
    crossings = t[up] - pitch[up] * (t[up + 1] - t[up]) / (pitch[up + 1] - pitch[up])
    measured = float(np.mean(np.diff(crossings)))
    assert len(crossings) >= 2
    assert measured == pytest.approx(period, rel=2e-3)


def _condensed_mass(M: np.ndarray) -> np.ndarray:
    """The (heave, pitch) mass with the surge condensed out: surge has no stiffness and no
    force, so its acceleration follows from zero surge momentum change,
    ``M_hh - M_hs M_ss^-1 M_sh``."""
    return M[1:, 1:] - np.outer(M[1:, 0], M[0, 1:]) / M[0, 0]


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
    net = (rod.mass - rho * rod.hydrostatics.volume) * g
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
