"""MoorDyn deck forms of OpenFAST's r-test decks (issue 14): early MoorDyn-F v2 body rows,
``EXTERNAL LOADS``, MoorDyn-F's seabed-friction options and FAST.Farm turbine attachments."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from moorline.cli import cli
from moorline.errors import CaseError
from moorline.io.moordyn import read_moordyn, read_moordyn_deck

PUBLIC = Path(__file__).parent / "data" / "moordyn" / "public"
RTEST = PUBLIC / "OpenFAST-r-test"

LEGACY_BODY_DECK = """\
--------------------- MoorDyn Input File ------------------------------------
an early MoorDyn-F v2 body row (OpenFAST r-test modules/moordyn/5MW_OC4 layout)
----------------------- LINE TYPES ------------------------------------------
LineType  Diam     MassDen    EA      BA/-zeta   EI   Cd   Ca   CdAx  CaAx
(-)       (m)      (kg/m)     (N)     (N-s/-)   (Nm^2) (-) (-)   (-)   (-)
main      0.0766   113.35     7.536E8  -1.0      0    2.0  0.8  0.4   0.25
----------------------------- BODIES ---------------------------------------
BodyID  X0  Y0  Z0  r0  p0  y0  Xcg  Ycg  Zcg  M     V    IX  IY  IZ  CdA  Ca
(-)     (m) (m) (m) (deg) (deg) (deg) (m) (m) (m) (kg) (m^3) (kg-m^2) (kg-m^2) (kg-m^2) (m^2) (-)
{body}
---------------------- POINTS --------------------------------
ID  Attachment  X  Y  Z  Mass  Volume  CdA  Ca
(-)  (-)  (m)  (m)  (m)  (kg)  (m^3)  (m^2)  (-)
1   Fixed   400   0    -200  0  0  0  0
2   Fixed  -400   0    -200  0  0  0  0
3   Body1   20    0    0     0  0  0  0
4   Body1  -20    0    0     0  0  0  0
---------------------- LINES --------------------------------------
ID  LineType  AttachA  AttachB  UnstrLen  NumSegs  Outputs
(-)  (-)  (-)  (-)  (m)  (-)  (-)
1   main   1   3   420   10   -
2   main   2   4   420   10   -
---------------------- SOLVER OPTIONS ---------------------------------------
200      WtrDpth
------------------------- need this line --------------------------------------
"""


@pytest.mark.parametrize(("row", "kind"), [
    ("1free  1 2 -10  0 0 0  0.1 0.2 -0.5  1000  2  10 20 30  0  0", "free"),
    ("1      1 2 -10  0 0 0  0.1 0.2 -0.5  1000  2  10 20 30  0  0", "free"),
    ("1Coupled 1 2 -10  0 0 0  0.1 0.2 -0.5  1000  2  10 20 30  0  0", "fixed"),
])
def test_early_moordyn_f_body_row(row, kind, tmp_path):
    """The 17-column body row of early MoorDyn-F v2 (OpenFAST MoorDyn.f90's "BODY LIST"
    reader: ``<ID><type> X0 Y0 Z0 r0 p0 y0 Xcg Ycg Zcg M V IX IY IZ CdA Ca``): each column lands
    where the deck puts it (a coupled body, held, keeps none of its own mass, as MoorDyn)."""
    deck = tmp_path / "legacy.dat"
    deck.write_text(LEGACY_BODY_DECK.format(body=row))
    (body,) = read_moordyn(deck).bodies.values()
    assert body.kind == kind
    assert body.position == (1.0, 2.0, -10.0)
    if kind == "free":
        assert body.mass == 1000.0
        assert body.center_of_gravity == pytest.approx((0.1, 0.2, -0.5), abs=1e-12)
        assert np.diag(np.array(body.inertia)) == pytest.approx([10.0, 20.0, 30.0], abs=1e-9)
        assert body.hydrostatics.volume == 2.0
    else:
        assert body.mass == 0.0


def test_early_body_row_with_missing_columns_is_refused(tmp_path):
    deck = tmp_path / "legacy.dat"
    deck.write_text(LEGACY_BODY_DECK.format(body="1free 1 2 -10 0 0 0 0.1 0.2 -0.5 1000 2"))
    with pytest.raises(CaseError, match="needs 17 columns"):
        read_moordyn_deck(deck)


BODY_DECK = """\
------------------------- a buoyant free body on four taut lines ------------------------
----------------------- LINE TYPES ------------------------------------------
TypeName  Diam  MassDen  EA  BA/-zeta  EI  Cd  Ca  CdAx  CaAx
(-)  (m)  (kg/m)  (N)  (N-s/-)  (N-m^2)  (-)  (-)  (-)  (-)
poly  0.1  8.0  1.0e8  -1.0  0  1.2  1.0  0.2  0.0
---------------------------- BODIES -----------------------------------------------------
ID  Attachment  X0  Y0  Z0  r0  p0  y0  Mass  CG*  I*  Volume  CdA*  Ca
(#)  (-)  (m)  (m)  (m)  (deg)  (deg)  (deg)  (kg)  (m)  (kg-m^2)  (m^3)  (m^2)  (-)
1  free  0  0  -20  0  0  0  1.0e4  0  1.0e5  30  0  0
----------------------- POINTS ----------------------------------------------
ID  Attachment  X  Y  Z  M  V  CdA  CA
(-)  (-)  (m)  (m)  (m)  (kg)  (m^3)  (m^2)  (-)
1  Body1   10   0  0  0  0  0  0
2  Body1  -10   0  0  0  0  0  0
3  Body1   0   10  0  0  0  0  0
4  Body1   0  -10  0  0  0  0  0
5  Fixed   60   0  -100  0  0  0  0
6  Fixed  -60   0  -100  0  0  0  0
7  Fixed   0   60  -100  0  0  0  0
8  Fixed   0  -60  -100  0  0  0  0
-------------------------- LINES -------------------------------------------------
ID  LineType  AttachA  AttachB  UnstrLen  NumSegs  LineOutputs
(-)  (-)  (-)  (-)  (m)  (-)  (-)
1  poly  5  1  93  20  -
2  poly  6  2  93  20  -
3  poly  7  3  93  20  -
4  poly  8  4  93  20  -
{external}-------------------------- SOLVER OPTIONS---------------------------------------
100  WtrDpth
--------------------------- need this line -----------------------------------------------
"""

EXTERNAL = """\
---------------------- EXTERNAL LOADS --------------------------------
ID    Object   Fext   Blin   Bquad   CSys
(#)   (name)   (N)    (Ns/m) (Ns^2/m^2)  (-)
{rows}
"""


def _deck(tmp_path: Path, name: str, rows: str | None) -> Path:
    path = tmp_path / f"{name}.dat"
    path.write_text(BODY_DECK.format(external="" if rows is None else EXTERNAL.format(rows=rows)))
    return path


def _json(*args: str) -> dict:
    result = CliRunner().invoke(cli, [*args, "--json", "--quiet"])
    assert result.exit_code == 0, result.output
    return json.loads(result.stdout)


def test_external_force_on_a_free_body_shifts_it_by_the_stiffness(tmp_path):
    """A constant ``EXTERNAL LOADS`` force on a free body (MoorDyn-F: at its reference point,
    earth axes) moves its equilibrium by ``K^-1 F``, ``K`` the 6x6 mooring stiffness of the
    unloaded equilibrium from ``moorline stiffness`` (the body has no hydrostatic stiffness:
    MoorDyn's buoyancy acts at the centre of gravity, here the origin). The force is small
    (3.5 cm of surge): the second-order error, measured 6e-4 of the shift, is inside 0.5 %."""
    force = np.array([200.0, 100.0, -50.0])
    poses = {}
    for name, rows in (("free", None), ("loaded", " 1  Body1  200|100|-50  0  0  G")):
        out = tmp_path / f"{name}.yaml"
        _ = CliRunner().invoke(cli, ["convert", str(_deck(tmp_path, name, rows)), "--out",
                                     str(out), "--quiet"])
        body = _json("statics", str(out), "--out", str(tmp_path / name), "--no-plots")
        body = body["bodies"]["body1"]
        poses[name] = np.r_[body["position"], np.radians(body["rotation_deg"])]
    K = np.array(_json("stiffness", str(tmp_path / "free.yaml"), "--body", "body1")
                 ["stiffness"])
    expected = np.linalg.solve(K, np.r_[force, 0.0, 0.0, 0.0])
    shift = poses["loaded"] - poses["free"]
    assert abs(expected[0]) > 0.03  # a shift to measure
    assert shift == pytest.approx(expected, abs=5e-3 * np.abs(expected).max())


def test_external_damping_on_a_body(tmp_path):
    """``Blin`` becomes the body's additional linear damping (translation, earth axes),
    ``Bquad`` its drag area ``2 Bquad / rho`` (Cd 1: ``rho Cd A / 2 = Bquad``); two rows on
    one body add up, as MoorDyn-F sums them."""
    rows = (" 1  Body1  0  1.0e3|0.7e3|60  3.0e3|2.1e3|1.0e4  G\n"
            " 2  Body1  10|0|0  100  0  G")
    deck = read_moordyn_deck(_deck(tmp_path, "damped", rows))
    body = deck.system.bodies["body1"]
    assert body.force == (10.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    damping = np.array(body.additional_damping)
    assert np.diag(damping) == pytest.approx([1100.0, 800.0, 160.0, 0, 0, 0])
    assert np.count_nonzero(damping - np.diag(np.diag(damping))) == 0
    rho = deck.system.environment.water_density
    assert body.Cd * np.array(body.drag_area) == pytest.approx(
        2.0 * np.array([3.0e3, 2.1e3, 1.0e4]) / rho)


def test_external_force_on_a_body_point_and_in_body_axes(tmp_path):
    """A force on a point of a body goes to the body with its moment about the body origin
    (``r x F``); a body-axes (``L``) force of an unrotated body is the same in earth axes."""
    rows = " 1  Point1  0|0|100  0  0  -\n 2  Body1  0|5|0  0  0  L"
    body = read_moordyn(_deck(tmp_path, "point", rows)).bodies["body1"]
    # point 1 at (10, 0, 0): r x F = (0, -10 * 100, 0)
    assert body.force == pytest.approx((0.0, 5.0, 100.0, 0.0, -1000.0, 0.0))


@pytest.mark.parametrize(("rows", "message"), [
    (" 1  Body1  1|2  0  0  G", "Fext '1|2': expected 1 or 3"),
    (" 1  Body1  5  0  0  G", "Fext must be 0 or three numbers"),
    (" 1  Body1  0  -1  0  G", "damping coefficients must not be negative"),
    (" 1  Body1  0  0  0  X", "CSys 'X' of a body must be G"),
    (" 1  Line1  0  0  0  -", "Object 'Line1' must be Body<k>"),
    (" 2  Body1  0  0  0  G", "IDs must run 1, 2, 3"),
    (" 1  Body3  0  0  0  G", "no body 3"),
    (" 1  Point9  1|0|0  0  0  -", "no point 9"),
    (" 1  Rod1  1|0|0  0  0  -", "a force on rod 1"),
])
def test_bad_external_loads_are_refused(tmp_path, rows, message):
    deck = _deck(tmp_path, "bad", rows)
    with pytest.raises(CaseError, match="EXTERNAL LOADS") as info:
        read_moordyn_deck(deck)
    assert message in str(info.value)


def test_rtest_body_external_load_deck_force_balance(tmp_path):
    """OpenFAST r-test ``md_BdyExtLdDmpg``: a free body (all its line at its centre of gravity,
    so moorline's point) hung from a fixed point, pushed by ``Fext`` = (1.0417e5, 0.5e5,
    -1.0e4) N. MoorDyn-F's equilibrium of it: line pull + weight + Fext = 0, so the line's
    end force at the body is ``-(Fext - m g e_z)`` (moorline's end force includes the half
    element weight lumped at the node). Without the section the line would hang vertical."""
    out = tmp_path / "ext.yaml"
    deck = RTEST / "modules/moordyn/md_BdyExtLdDmpg/moordyn.dat"
    result = CliRunner().invoke(cli, ["convert", str(deck), "--out", str(out), "--quiet"])
    assert result.exit_code == 0, result.output
    assert "damping on the free point point1 are dropped" in result.stderr
    summary = _json("statics", str(out), "--out", str(tmp_path / "o"), "--no-plots")
    assert summary["converged"] is True
    g = 9.80665
    expected = -np.array([1.0417e5, 0.5e5, -1.0e4 - 2.1244e4 * g])
    end = np.array(summary["lines"]["line1"]["end_b"]["force"])
    assert end == pytest.approx(expected, rel=1e-6)


VIV = RTEST / "modules/moordyn/md_VIV/moordyn.dat"


def _viv_variant(tmp_path: Path, options: str) -> Path:
    text = VIV.read_text()
    start, end = text.index("0.5      MU_KT"), text.index("1.0      CdScaleIC")
    path = tmp_path / "viv.dat"
    path.write_text(text[:start] + options + text[end:])
    return path


def test_moordyn_f_friction_options_of_the_rtest_viv_deck():
    """OpenFAST r-test ``md_VIV``: ``MU_KT 0.5``, ``MU_KA 0.5``, ``FricDamp 20000`` (MoorDyn-F's
    ``CV``). MoorDyn-F's law ``min(mu CV |v|, mu N)`` has the slope ``mu CV`` at rest,
    moorline's ``mu N tanh(|v| / v_s)`` has ``mu N / v_s``: the slip velocity is a resting
    node's contact force over CV, ``w l_seg / CV`` (the cable: 0.69 kg/m, d 0.024 m,
    23.71 m in 100 segments)."""
    deck = read_moordyn_deck(VIV)
    seabed = deck.system.environment.seabed
    assert (seabed.friction, seabed.friction_axial, seabed.friction_transverse) == (0.5,) * 3
    w = (0.69 - 1025.0 * np.pi * 0.024**2 / 4.0) * 9.80665
    assert seabed.slip_velocity == pytest.approx(w * 23.71 / 100 / 20000.0, rel=1e-12)
    assert not any("MU_K" in note for note in deck.notes)  # read, not "unknown option"


def test_friction_options_axial_transverse_and_static_ratio(tmp_path):
    """Different axial and transverse coefficients land on their own axes (the statics'
    ``friction`` is the axial one); without CV moorline's slip velocity stays; MoorDyn-F's
    static/kinetic ratio ``MC`` has no counterpart: a note."""
    deck = read_moordyn_deck(_viv_variant(tmp_path, "0.8 MU_KT\n0.4 MU_KA\n1.5 MC\n"))
    seabed = deck.system.environment.seabed
    assert (seabed.friction, seabed.friction_axial, seabed.friction_transverse) == \
        (0.4, 0.4, 0.8)
    assert seabed.slip_velocity == 0.01
    assert any("MC (StatDynFricScale) = 1.5 has no counterpart" in n for n in deck.notes)


def test_moordyn_c_friction_damping_sets_the_slip_velocity(tmp_path):
    """MoorDyn-C's ``FrictionCoefficient`` with ``FricDamp`` (the same law, both directions):
    the coefficient and the slip velocity ``w l_seg / FricDamp``."""
    deck = read_moordyn_deck(_viv_variant(tmp_path, "0.3 FrictionCoefficient\n"
                                                     "4000 FricDamp\n"))
    seabed = deck.system.environment.seabed
    assert seabed.friction == 0.3 and seabed.friction_axial is None
    w = (0.69 - 1025.0 * np.pi * 0.024**2 / 4.0) * 9.80665
    assert seabed.slip_velocity == pytest.approx(w * 23.71 / 100 / 4000.0, rel=1e-12)


def test_bad_friction_option_is_refused(tmp_path):
    with pytest.raises(CaseError, match="option MU_KT must be a number, got 'high'"):
        read_moordyn_deck(_viv_variant(tmp_path, "high MU_KT\n"))


SHARED = RTEST / "glue-codes/fast-farm/MD_Shared/SharedMooring2.dat"
#: WT_X WT_Y WT_Z of OpenFAST r-test glue-codes/fast-farm/MD_Shared/FAST.Farm.fstf (commit
#: 71a5adcc1246d48ef65f2341e1f894a64d47b459), the FAST.Farm case that uses SharedMooring2.dat.
FARM_TURBINES = {1: (0.0, 0.0, 0.0), 2: (1600.0, 0.0, 0.0)}


def test_fast_farm_turbine_points_from_convert_turbine(tmp_path):
    """FAST.Farm's shared mooring (r-test ``MD_Shared``): points on ``Turbine<k>`` become
    prescribed points at the deck position plus turbine k's reference position (MoorDyn-F:
    ``r = Position + TranslationDisp + TurbineRefPos``); the two turbines' lines and the
    shared line with its two clump weights solve and run 2 s. Without ``--turbine`` the deck is
    refused naming the option; a turbine given twice is refused too."""
    from moorline.io import load_case
    from moorline.model import DynamicsSettings
    from moorline.solvers.dynamics import simulate
    from moorline.solvers.statics import solve_statics

    out = tmp_path / "farm.yaml"
    flags = [arg for k, xyz in FARM_TURBINES.items()
             for arg in ("--turbine", str(k), *map(str, xyz))]
    runner = CliRunner()
    result = runner.invoke(cli, ["convert", str(SHARED), "--out", str(out), "--quiet", *flags])
    assert result.exit_code == 0, result.output
    system = load_case(out)
    for name, expected in (("point1", (-58.0, 0.0, -14.0)), ("point6", (29.0, -50.229, -14.0)),
                           ("point4", (1542.0, 0.0, -14.0)),
                           ("point12", (1629.0, -50.229, -14.0))):
        point = system.points[name]
        assert point.kind == "prescribed" and point.position == pytest.approx(expected)
    assert system.points["point9"].position == (2400.0, 800.0, -600.0)  # anchors unchanged
    static = solve_statics(system)
    assert static.success, static.message
    run = simulate(system, DynamicsSettings(duration=2.0, dt=0.05), initial=static)
    assert run.success, run.message
    twice = runner.invoke(cli, ["convert", str(SHARED), "--out", str(tmp_path / "t.yaml"),
                                *flags, "--turbine", "1", "5", "0", "0"])
    assert twice.exit_code == 2 and "--turbine 1 is given twice" in twice.output
    missing = runner.invoke(cli, ["convert", str(SHARED), "--out", str(tmp_path / "m.yaml"),
                                  "--turbine", "1", "0", "0", "0"])
    assert missing.exit_code == 2
    assert "--turbine 2 X Y Z` (turbines given: 1)" in missing.output
