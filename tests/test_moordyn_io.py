"""MoorDyn input files (reader, writer) and the MoorDyn runner used for comparisons."""

from __future__ import annotations

import dataclasses
import logging
import math
from pathlib import Path

import numpy as np
import pytest

from moorline.errors import CaseError
from moorline.io.moordyn import read_moordyn, read_moordyn_deck, write_moordyn
from moorline.model import Environment, LineType, Motion, Point, Seabed, System
from moorline.physics.rigid_body import rotation_matrix

DATA = Path(__file__).parent / "data" / "moordyn"
OC3 = DATA / "oc3.dat"


def _oc3_single(motion: Motion | None = None) -> System:
    """Line 1 of the OC3 sample deck alone, its fairlead optionally moving."""
    system = read_moordyn(OC3)
    fairlead = dataclasses.replace(system.points["fairlead1"], motion=motion)
    return dataclasses.replace(
        system, name="oc3-line", points={"anchor1": system.points["anchor1"],
                                         "fairlead1": fairlead},
        lines={"line1": system.lines["line1"]})


# --------------------------------------------------------------------------- reading


def test_read_oc3_every_field() -> None:
    deck = read_moordyn_deck(OC3)
    s = deck.system
    assert deck.version == "v2"
    assert deck.notes == ()
    assert s.name == "oc3" and s.units == "SI" and s.source == str(OC3)
    env = s.environment
    assert (env.depth, env.water_density, env.gravity) == (320.0, 1025.0, 9.80665)
    assert env.seabed == Seabed(stiffness=3.0e6, damping=3.0e5, friction=0.0)
    assert env.current.speed == 0.0 and env.waves.kind == "none"
    assert s.line_types == {"main": LineType(
        name="main", diameter=0.09, mass_per_length=77.7066, EA=384.243e6, BA=-0.8,
        Ca=1.0, Cat=0.0, Cd=1.6, Ct=0.05)}
    assert list(s.points) == ["anchor1", "anchor2", "anchor3",
                              "fairlead1", "fairlead2", "fairlead3"]
    for k in range(3):
        anchor, fair = s.points[f"anchor{k + 1}"], s.points[f"fairlead{k + 1}"]
        assert anchor.kind == "fixed" and fair.kind == "prescribed"
        assert math.hypot(*anchor.position[:2]) == pytest.approx(853.87, abs=1e-3)
        assert anchor.position[2] == -320.0
        assert math.hypot(*fair.position[:2]) == pytest.approx(5.2, abs=1e-4)
        assert fair.position[2] == -70.0
        for p in (anchor, fair):
            assert (p.mass, p.volume, p.force, p.Cd, p.drag_area, p.Ca) == (
                0.0, 0.0, (0.0, 0.0, 0.0), 0.0, 0.0, 0.0)
            assert p.motion is None
        line = s.lines[f"line{k + 1}"]
        assert (line.line_type, line.length, line.segments) == ("main", 902.2, 20)
        assert (line.end_a, line.end_b) == (f"anchor{k + 1}", f"fairlead{k + 1}")
    assert deck.point_ids["fairlead2"] == 5 and deck.line_ids["line3"] == 3
    assert deck.options["dtM"] == "0.002" and deck.options["TmaxIC"] == "100.0"


def test_read_v1_layout() -> None:
    deck = read_moordyn_deck(DATA / "oc3_v1.dat")
    s = deck.system
    assert deck.version == "v1"
    lt = s.line_types["chain"]
    # v1 order: Can Cat Cdn Cdt
    assert (lt.Ca, lt.Cat, lt.Cd, lt.Ct, lt.BA) == (0.9, 0.1, 1.5, 0.04, -0.8)
    assert [p.kind for p in s.points.values()] == ["fixed", "free", "prescribed"]
    buoy = s.points["point2"]
    assert (buoy.mass, buoy.volume, buoy.force) == (500.0, 0.5, (0.0, 0.0, -100.0))
    assert (buoy.Cd, buoy.drag_area, buoy.Ca) == (1.0, 0.8, 1.0)
    # v1 line rows: ID type UnstrLen NumSegs NodeAnch NodeFair
    line = s.lines["line2"]
    assert (line.length, line.segments, line.end_a, line.end_b) == (402.2, 10, "point2",
                                                                    "point3")
    assert s.environment.seabed.stiffness == 3.0e6 and s.environment.depth == 320.0


def test_missing_depth_follows_moordyn(tmp_path: Path, caplog: pytest.LogCaptureFixture) -> None:
    text = "\n".join(line for line in OC3.read_text().splitlines() if "WtrDpth" not in line)
    path = tmp_path / "nodepth.dat"
    path.write_text(text)
    with caplog.at_level(logging.WARNING):
        deck = read_moordyn_deck(path)
    assert deck.system.environment.depth == 320.0  # lowered to the anchors, as MoorDyn-C does
    assert any("water depth" in n for n in deck.notes)


def test_unknown_option_is_kept_and_logged(tmp_path: Path,
                                           caplog: pytest.LogCaptureFixture) -> None:
    text = OC3.read_text().replace("0.001         threshIC",
                                   "0.001 threshIC\n42  MysteryKnob  who knows")
    path = tmp_path / "mystery.dat"
    path.write_text(text)
    with caplog.at_level(logging.WARNING, logger="moorline.io.moordyn"):
        deck = read_moordyn_deck(path)
    assert deck.options["MysteryKnob"] == "42"
    assert "MysteryKnob" in caplog.text


# --------------------------------------------------------------------------- bad decks


def _line_of(text: str, fragment: str) -> int:
    return next(i for i, line in enumerate(text.splitlines(), start=1) if fragment in line)


BAD = {
    "missing section": (
        lambda t: t[:t.index("---------------------- LINES")] + t[t.index("------------------"
                                                                           "---- OPTIONS"):],
        None, "missing section LINES"),
    "columns": (
        lambda t: t.replace("5     Coupled     -2.6     4.5033   -70.0   0      0       0      0",
                            "5     Coupled     -2.6     4.5033   -70.0   0      0       0"),
        "5     Coupled", "expected 9 columns"),
    "attachment": (
        lambda t: t.replace("2     main       2        5 ", "2     main       2        7 "),
        "2     main       2        7", "unknown attachment AttachB '7'"),
    "non-numeric": (
        lambda t: t.replace("main       0.09    77.7066", "main       0.09    heavy"),
        "main       0.09    heavy", "must be a number, got 'heavy'"),
    "point type": (
        lambda t: t.replace("4     Coupled", "4     Body1  "), "4     Body1",
        "unknown point attachment 'Body1'"),
    "line type": (
        lambda t: t.replace("3     main       3", "3     wire       3"), "3     wire",
        "unknown line type 'wire'"),
    "ids": (
        lambda t: t.replace("3     Fixed       -426.935", "7     Fixed       -426.935"),
        "7     Fixed", "IDs must run 1, 2, 3"),
}


@pytest.mark.parametrize("case", list(BAD))
def test_bad_decks_name_file_and_line(case: str, tmp_path: Path) -> None:
    edit, fragment, message = BAD[case]
    text = edit(OC3.read_text())
    assert text != OC3.read_text()
    path = tmp_path / "bad.dat"
    path.write_text(text)
    with pytest.raises(CaseError) as info:
        read_moordyn(path)
    err = info.value
    assert err.file == str(path)
    assert message in err.reason
    if fragment is not None:
        assert f"line {_line_of(text, fragment)}" in err.field
    assert str(path) in str(err)


def test_unreadable_file(tmp_path: Path) -> None:
    with pytest.raises(CaseError, match="cannot read"):
        read_moordyn(tmp_path / "absent.dat")


# --------------------------------------------------------------------------- writing


def _rich_system() -> System:
    """Everything a MoorDyn deck can hold: two line types, all point kinds, a buoy."""
    base = read_moordyn(OC3)
    wire = LineType(name="wire", diameter=0.05, mass_per_length=12.5, EA=2.0e8, BA=1.5e5,
                    Cd=1.2, Ca=0.8, Ct=0.01, Cat=0.2)
    buoy = Point(name="buoy", kind="free", position=(300.0, 0.0, -150.0), mass=1200.0,
                 volume=4.0, Cd=1.0, drag_area=2.5, Ca=0.7)
    points = {**base.points, "buoy": buoy}
    lines = dict(base.lines)
    lines["line1"] = dataclasses.replace(lines["line1"], end_b="buoy", length=600.0,
                                         segments=12)
    lines["riser"] = dataclasses.replace(lines["line1"], name="riser", line_type="wire",
                                         end_a="buoy", end_b="fairlead1", length=320.5,
                                         segments=8)
    env = Environment(depth=321.5, water_density=1027.0, gravity=9.81,
                      seabed=Seabed(stiffness=1.0e6, damping=2.0e4, friction=0.4))
    return dataclasses.replace(base, name="rich", environment=env,
                               line_types={**base.line_types, "wire": wire},
                               points=points, lines=lines, source=None)


@pytest.mark.parametrize("depth", [321.5, math.inf])
def test_round_trip(depth: float, tmp_path: Path) -> None:
    system = _rich_system()
    system = dataclasses.replace(system, environment=dataclasses.replace(
        system.environment, depth=depth))
    path = write_moordyn(system, tmp_path / "rich.dat", dt=0.001)
    back = read_moordyn_deck(path)
    assert back.notes == ()
    assert dataclasses.replace(back.system, source=None) == system
    assert float(back.options["dtM"]) == 0.001


def test_round_trip_drops_only_motion(tmp_path: Path) -> None:
    system = _oc3_single(Motion("harmonic", amplitude=(5.0, 0.0, 0.0), period=10.0))
    back = read_moordyn(write_moordyn(system, tmp_path / "oc3-line.dat", dt=0.002))
    assert back.points["fairlead1"].motion is None
    assert back == dataclasses.replace(
        system, source=str(tmp_path / "oc3-line.dat"),
        points={**system.points, "fairlead1": dataclasses.replace(
            system.points["fairlead1"], motion=None)})


def test_write_refuses_what_moordyn_cannot_hold(tmp_path: Path) -> None:
    system = _oc3_single()
    visco = dataclasses.replace(system, line_types={"main": dataclasses.replace(
        system.line_types["main"], material="viscoelastic", EA1=1e8, tau=2.0)})
    with pytest.raises(CaseError, match="viscoelastic"):
        write_moordyn(visco, tmp_path / "v.dat", dt=0.001)
    pushed = dataclasses.replace(system, points={**system.points, "anchor1": dataclasses.replace(
        system.points["anchor1"], force=(10.0, 0.0, 0.0))})
    with pytest.raises(CaseError, match="horizontal force"):
        write_moordyn(pushed, tmp_path / "f.dat", dt=0.001)


# --------------------------------------------------------------------------- MoorDyn itself


@pytest.mark.compare
def test_moordyn_reads_written_three_line_deck() -> None:
    pytest.importorskip("moordyn")
    from moorline.compare import run_moordyn

    system = read_moordyn(OC3)
    run = run_moordyn(system, 1.0, 0.002, 0.5, thresh_ic=1e-4)
    assert run["success"], run["message"]
    assert run["coupled_points"] == ["fairlead1", "fairlead2", "fairlead3"]
    assert run["fairlead_tension"].shape == (3, 3)
    # the three lines are the same line rotated by 120 degrees
    assert np.ptp(run["fairlead_tension"][0]) < 1e-3 * run["fairlead_tension"][0, 0]


@pytest.mark.compare
def test_moordyn_oc3_initial_tension_matches_moorline_statics() -> None:
    """MoorDyn-C's static IC and moorline's statics model the same lumped-mass line: with
    threshIC = 1e-5 they agree to ~1e-5 (the seabed contact models differ slightly), far
    inside the 1 % asked for."""
    pytest.importorskip("moordyn")
    from moorline.compare import run_moordyn
    from moorline.solvers.statics import solve_statics

    system = _oc3_single(Motion("harmonic", amplitude=(5.0, 0.0, 0.0), period=10.0))
    run = run_moordyn(system, 20.0, 0.001, 0.05)
    assert run["success"], run["message"]
    assert run["ic_residual"] < 1e-4  # MoorDyn's IC solve reached equilibrium
    static = solve_statics(system)
    assert static.success
    expected = static.end_force("line1", "b")
    got = run["end_force"][0, 0, 1]
    assert run["fairlead_tension"][0, 0] == pytest.approx(np.linalg.norm(expected), rel=1e-2)
    np.testing.assert_allclose(got, expected, rtol=1e-2)
    np.testing.assert_allclose(run["point_force"]["fairlead1"][0], got)
    tension = run["fairlead_tension"][:, 0]
    assert np.isfinite(tension).all() and tension.max() > 1.2 * tension[0]
    assert run["time"][-1] == pytest.approx(20.0)
    assert run["wall_time_total"] >= run["wall_time_loop"] > 0


@pytest.mark.compare
def test_largest_stable_dt_brackets_the_limit() -> None:
    pytest.importorskip("moordyn")
    from moorline.compare import largest_stable_dt

    system = _oc3_single(Motion("harmonic", amplitude=(5.0, 0.0, 0.0), period=10.0))
    found = largest_stable_dt(system, duration=5.0, rel_tol=0.5)
    assert found["dt"] is not None and found["unstable_dt"] is not None
    assert found["dt"] < found["unstable_dt"] <= 1.5 * found["dt"] + 1e-12
    stable = {t["dt"]: t["stable"] for t in found["trials"]}
    assert stable[found["dt"]] and not stable[found["unstable_dt"]]


# --------------------------------------------------------------------------- issue 14


def _edited(tmp_path: Path, old: str, new: str, name: str = "deck.dat",
            source: Path = OC3) -> Path:
    text = source.read_text()
    assert old in text
    path = tmp_path / name
    path.write_text(text.replace(old, new))
    return path


@pytest.mark.parametrize(("word", "kind"), [
    ("Fix", "fixed"), ("fixed", "fixed"), ("ANCHOR", "fixed"), ("Fixed1", "fixed"),
    ("Ves", "prescribed"), ("vessel", "prescribed"), ("Cpld", "prescribed"),
    ("COUPLED", "prescribed"), ("Fairlead", "prescribed"),
    ("Con", "free"), ("connect", "free"), ("Free", "free"), ("Point", "free"),
])
def test_point_type_aliases(word: str, kind: str, tmp_path: Path) -> None:
    """MoorDyn-C v2.7 (source/MoorDyn2.cpp, point list) compares the leading letters of the
    attachment word, upper-cased, with ANCHOR/FIXED/FIX, FAIRLEAD/VESSEL/VES/COUPLED/CPLD
    and POINT/CONNECT/CON/FREE."""
    path = _edited(tmp_path, "4     Coupled", f"4     {word:<8s}")
    assert read_moordyn(path).points["fairlead1"].kind == kind


def test_unknown_point_type_lists_the_aliases(tmp_path: Path) -> None:
    path = _edited(tmp_path, "4     Coupled", "4     Moored ")
    with pytest.raises(CaseError, match=r"'Moored'.*Fix, Anchor.*Ves, Cpld, Fairlead"):
        read_moordyn(path)


@pytest.mark.parametrize(("option", "fragment"), [
    ("3  WaveKin", "WaveKin = 3 (waves from a wave-elevation time series, grid): no "
                   "wave_elevation.txt next to the deck, waves are dropped"),
    ("6  WaveKin", "WaveKin = 6 (wave kinematics grid files) is not read: waves are dropped"),
    ("1  WaveKin", "WaveKin = 1 (wave kinematics set through the coupling API) is not read"),
    ("2  Currents", "Currents = 2 (a time-varying current profile"),
    ("1  Currents", "Currents = 1: no current_profile.txt next to the deck, the current is "
                    "dropped"),
    ("1  WaterKin", "WaterKin = 1 (line 32): MoorDyn v1 water kinematics files"),
])
def test_kinematics_options_are_warnings_not_refusals(option: str, fragment: str,
                                                      tmp_path: Path) -> None:
    path = _edited(tmp_path, "0.001         threshIC", f"{option}\n0.001 threshIC")
    deck = read_moordyn_deck(path)
    assert any(fragment in note for note in deck.notes), deck.notes
    assert deck.system.environment.current.speed == 0.0
    assert not deck.system.environment.current.z_levels
    assert deck.system.environment.waves.kind == "none"


def test_a_missing_seafloor_file_is_an_error_naming_it(tmp_path: Path) -> None:
    path = _edited(tmp_path, "0.001         threshIC", "floor.txt  SeafloorFile\n0.001 threshIC")
    with pytest.raises(CaseError, match="SeafloorFile = floor.txt: no such file"):
        read_moordyn(path)
    (tmp_path / "floor.txt").write_text("2 2\n-1e4 1e4\n-1e4 1e4\n" + "".join(
        f"{x} {y} -320\n" for x in (-1e4, 1e4) for y in (-1e4, 1e4)))
    grid = read_moordyn(path).environment.seabed.bathymetry
    assert grid is not None and grid.z == ((-320.0, -320.0), (-320.0, -320.0))


PROFILE = """--------------------- MoorDyn steady currents File ------------------------
Tabulated file with the water currents components
z (m), ux (m/s), uy (m/s), uz (m/s)
-320.0 0.0 0.0 0.0
-100.0 0.3 0.4 0.0
0.0 0.6 0.8 0.0
"""


def test_steady_current_profile_becomes_the_case_current(tmp_path: Path) -> None:
    """Currents 1 with MoorDyn's current_profile.txt (three header lines, then z ux uy uz,
    in the deck's folder as MoorDyn-C reads it): speed hypot(ux, uy), heading
    atan2(uy, ux); the zero-speed level takes its neighbour's heading; statics with the
    current drag."""
    (tmp_path / "current_profile.txt").write_text(PROFILE)
    path = _edited(tmp_path, "0.001         threshIC", "1  Currents\n0.001 threshIC")
    deck = read_moordyn_deck(path)
    current = deck.system.environment.current
    assert current.z_levels == (-320.0, -100.0, 0.0)
    assert current.speeds == pytest.approx((0.0, 0.5, 1.0), rel=1e-15)
    heading = math.degrees(math.atan2(0.8, 0.6))
    assert current.headings_deg == pytest.approx((heading,) * 3, rel=1e-15)
    assert deck.system.analyses[0].current_drag is True
    assert any("current_profile.txt is read" in n for n in deck.notes)


def test_turning_or_vertical_current_is_warned(tmp_path: Path) -> None:
    (tmp_path / "current_profile.txt").write_text(
        PROFILE.replace("-100.0 0.3 0.4 0.0", "-100.0 0.5 0.0 0.1"))
    path = _edited(tmp_path, "0.001         threshIC", "3  Currents\n0.001 threshIC")
    notes = " ".join(read_moordyn_deck(path).notes)
    assert "uz is dropped" in notes and "the current turns with depth" in notes


def test_time_settings_make_a_dynamics_analysis() -> None:
    """TMax 1, dtOut 0.1, dtM 0.002 (tests/data/moordyn/oc3_outputs.dat): statics then a
    1 s dynamics with dt = min(dtOut, 0.05), output every dtOut; said in the comments."""
    from moorline.model import DynamicsSettings, StaticsSettings

    deck = read_moordyn_deck(DATA / "oc3_outputs.dat")
    s = deck.system
    assert s.analyses == (StaticsSettings(), DynamicsSettings(duration=1.0, dt=0.05))
    assert s.output.every == 0.1
    assert any("TMax = 1 s" in c and "dtM = 0.002 s" in c for c in deck.comments)
    assert deck.line_outputs == {"line1": "pt", "line2": "-", "line3": "-"}


def test_without_tmax_statics_only_with_a_comment() -> None:
    deck = read_moordyn_deck(OC3)
    assert [a.kind for a in deck.system.analyses] == ["statics"]
    assert deck.comments == ("dtM = 0.002 s: no TMax, so no dynamics analysis is made "
                             "(statics only; dtOut, if given, is the case's output interval)",)


def test_outputs_section_is_carried() -> None:
    deck = read_moordyn_deck(DATA / "oc3_outputs.dat")
    expected = ("FairTen1", "AnchTen1", "L1N19T", "L1N10T", "L1NBFX", "L1N20FZ", "Point4FX",
                "Con1FX", "L1N10PZ", "FairSegTen1", "L1T20")
    assert deck.outputs == expected and deck.system.output.channels == expected
    assert [n for n in deck.notes if "OUTPUTS" in n] == [
        "OUTPUTS: channel 'L1T20' (line 40) is not supported by moorline and will not be "
        "written"]


@pytest.mark.parametrize(("name", "parsed"), [
    ("FairTen3", ("line", 3, "B", "T")), ("anchten2", ("line", 2, "A", "T")),
    ("FairSegTen1", ("line", 1, "B", "SEGTEN")), ("L1N10T", ("line", 1, 10, "T")),
    ("L2N3Ten", ("line", 2, 3, "T")), ("Line2N0PZ", ("line", 2, 0, "PZ")),
    ("L1NBFX", ("line", 1, "B", "FX")), ("L4NAT", ("line", 4, "A", "T")),
    ("Point4FX", ("point", 4, None, "FX")), ("P2VZ", ("point", 2, None, "VZ")),
    ("Con4Fx", ("point", 4, None, "FX")), ("POINT1T", ("point", 1, None, "T")),
])
def test_channel_names_read_like_moordyn(name: str, parsed: tuple) -> None:
    from moorline.io.moordyn_outputs import parse_channel

    channel = parse_channel(name)
    assert channel is not None
    assert (channel.what, channel.number, channel.node, channel.quantity) == parsed


@pytest.mark.parametrize("name", ["L1T20", "FairTen", "Body1PX", "R1N2T", "L1N3XX"])
def test_unsupported_channel_names(name: str) -> None:
    from moorline.io.moordyn_outputs import parse_channel

    assert parse_channel(name) is None


@pytest.fixture(scope="module")
def channel_run(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, dict[str, np.ndarray]]:
    """oc3_outputs.dat converted and run (statics, 1 s of dynamics at rest): the directory and
    the columns of its moordyn_channels.csv."""
    import csv

    from click.testing import CliRunner

    from moorline.cli import cli

    tmp = tmp_path_factory.mktemp("channels")
    case = tmp / "oc3_outputs.yaml"
    runner = CliRunner()
    result = runner.invoke(cli, ["convert", str(DATA / "oc3_outputs.dat"), "--out", str(case),
                                 "--quiet"])
    assert result.exit_code == 0, result.output
    result = runner.invoke(cli, ["run", str(case), "--out", str(tmp / "out"), "--no-plots",
                                 "--quiet"])
    assert result.exit_code == 0, result.output
    directory = tmp / "out" / "oc3_outputs"
    with (directory / "moordyn_channels.csv").open() as handle:
        rows = list(csv.reader(handle))
    columns = {name: np.array([float(r[i]) for r in rows[1:]]) for i, name in
               enumerate(rows[0])}
    return directory, columns


def test_run_writes_the_channels_by_their_definitions(channel_run) -> None:
    """Columns: Time then the deck's channels that moorline can write (L1T20 is not, it is
    left out); each equals its definition on the results file (end-point force, mean of
    the adjacent segments, node position, sum over the lines at a point)."""
    from moorline.io.writers import read_group

    directory, columns = channel_run
    assert list(columns) == ["Time", "FairTen1", "AnchTen1", "L1N19T", "L1N10T", "L1NBFX",
                             "L1N20FZ", "Point4FX", "Con1FX", "L1N10PZ", "FairSegTen1"]
    ds = read_group(directory / "results.nc", "dynamics")
    np.testing.assert_allclose(columns["Time"], ds["time"].values, rtol=0, atol=1e-12)
    force = ds["end_force"].sel(line="line1").values
    np.testing.assert_allclose(columns["FairTen1"], np.linalg.norm(force[:, 1], axis=-1))
    np.testing.assert_allclose(columns["AnchTen1"], np.linalg.norm(force[:, 0], axis=-1))
    np.testing.assert_allclose(columns["L1NBFX"], force[:, 1, 0])
    np.testing.assert_allclose(columns["Point4FX"], force[:, 1, 0])  # one line on fairlead1
    np.testing.assert_allclose(columns["Con1FX"], force[:, 0, 0])
    elements = np.flatnonzero(ds["element_line"].values == "line1")
    tension = ds["tension"].values[:, elements]
    np.testing.assert_allclose(columns["L1N19T"], 0.5 * (tension[:, 18] + tension[:, 19]))
    np.testing.assert_allclose(columns["FairSegTen1"], tension[:, 19])
    nodes = ds["element_nodes"].values[elements]
    np.testing.assert_allclose(columns["L1N10PZ"], ds["position"].values[:, nodes[10, 0], 2])


@pytest.mark.compare
def test_channels_match_moordyn_out_file(channel_run, tmp_path: Path) -> None:
    """The same deck through MoorDyn-C (moordyn 2.7.2): its .out file after the IC (threshIC
    1e-5 m/s^2, TmaxIC 500 s: converged at 180 s) against moorline's channels at rest.
    MoorDyn's FairTen/AnchTen are the net force on the end node, so they equal moorline's
    end-point force, not the top segment's tension (its API GetLineFairTen, 1 % lower here,
    is moorline's FairSegTen). Tolerance 5e-4: the measured differences are 0.7e-4 at the
    ends and 1.7-2.7e-4 inside the line, where the two seabed contact models put the
    touchdown slightly apart (the end-to-end tension drop agrees to 1e-5); a wrong
    definition (segment tension for FairTen, one segment for L1N19T) is off by >= 0.5 %."""
    moordyn = pytest.importorskip("moordyn")
    import shutil

    deck = Path(shutil.copy(DATA / "oc3_outputs.dat", tmp_path / "oc3_outputs.dat"))
    system = moordyn.Create(str(deck))
    try:
        x = np.concatenate([read_moordyn(deck).points[f"fairlead{k}"].position
                            for k in (1, 2, 3)])
        moordyn.Init(system, x, np.zeros(9))
        api_fair_ten = moordyn.GetLineFairTen(moordyn.GetLine(system, 1))
        moordyn.Step(system, x, np.zeros(9), 0.0, 0.1)
    finally:
        moordyn.Close(system)
    lines = (tmp_path / "oc3_outputs.out").read_text().splitlines()
    names, last = lines[0].split(), [float(v) for v in lines[-1].split()]
    theirs = dict(zip(names, last, strict=True))
    _, ours = channel_run
    compared = [n for n in names[1:] if n in ours]
    assert compared == ["FairTen1", "AnchTen1", "L1N19T", "L1N10T", "L1NBFX", "L1N20FZ",
                        "Point4FX", "L1N10PZ"]  # MoorDyn skips Con1FX (v1 name) and L1T20
    for name in compared:
        assert ours[name][0] == pytest.approx(theirs[name], rel=5e-4), name
    assert ours["FairSegTen1"][0] == pytest.approx(api_fair_ten, rel=5e-4)
    assert ours["FairTen1"][0] > 1.008 * ours["FairSegTen1"][0]


def test_dynamics_summary_has_segment_tensions_next_to_end_forces(channel_run) -> None:
    """summary.json: per line end_a/end_b (the end-point force, MoorDyn's FairTen/AnchTen
    channels) and segment_a/segment_b (the end segment's tension, MoorDyn's
    GetLineFairTen), with the note saying which is which."""
    import json

    directory, columns = channel_run
    summary = json.loads((directory / "summary.json").read_text())
    dynamics = summary["analyses"][1]
    line = dynamics["lines"]["line1"]
    assert line["end_b"]["mean"] == pytest.approx(columns["FairTen1"].mean(), rel=1e-12)
    assert line["segment_b"]["mean"] == pytest.approx(columns["FairSegTen1"].mean(), rel=1e-12)
    assert line["segment_b"]["max"] < line["end_b"]["min"]
    assert "GetLineFairTen" in dynamics["tension_note"]


@pytest.mark.compare
def test_current_profile_statics_match_moordyn_settled_in_the_current(tmp_path: Path) -> None:
    """OC3 with Currents 1 and a sheared profile along +x (0.2 m/s at the seabed to 0.8 at
    the surface): moorline's statics with the read profile against MoorDyn-C held at the
    fairleads for 150 s in the same current (its IC ignores the current; the fairlead
    forces settle to 1e-9 within 100 s). Measured: tension within 8.4e-5, components
    within 4.9e-4 of |F| (the same IC/seabed-contact difference as without current); the
    current itself moves the tensions by 1.1e-3 to 1.6e-3 and the components by 3e-3,
    so the tolerances (3e-4, 1e-3) would catch a profile read wrong or not applied."""
    moordyn = pytest.importorskip("moordyn")
    from moorline.solvers.statics import solve_statics

    (tmp_path / "current_profile.txt").write_text(PROFILE.replace(
        "-320.0 0.0 0.0 0.0\n-100.0 0.3 0.4 0.0\n0.0 0.6 0.8 0.0",
        "-320.0 0.2 0.0 0.0\n-100.0 0.5 0.0 0.0\n0.0 0.8 0.0 0.0"))
    text = OC3.read_text().replace("0.001         threshIC", "1  Currents\n1.0e-5  threshIC")
    deck = tmp_path / "current.dat"
    deck.write_text(text.replace("100.0         TmaxIC", "500.0  TmaxIC"))
    system = read_moordyn(deck)
    assert system.environment.current.speeds == (0.2, 0.5, 0.8)
    static = solve_statics(system)
    still = solve_statics(dataclasses.replace(system, analyses=()))  # no current drag
    md = moordyn.Create(str(deck))
    try:
        x = np.concatenate([system.points[f"fairlead{k}"].position for k in (1, 2, 3)])
        moordyn.Init(md, x, np.zeros(9))
        for k in range(150):
            moordyn.Step(md, x, np.zeros(9), float(k), 1.0)
        theirs = [np.array(moordyn.GetLineNodeForce(moordyn.GetLine(md, k), 20))
                  for k in (1, 2, 3)]
    finally:
        moordyn.Close(md)
    for k, force in enumerate(theirs, start=1):
        ours = static.end_force(f"line{k}", "b")
        size = np.linalg.norm(force)
        assert np.linalg.norm(ours) == pytest.approx(size, rel=3e-4)
        assert np.abs(ours - force).max() < 1e-3 * size
        dry = still.end_force(f"line{k}", "b")
        assert abs(np.linalg.norm(dry) / size - 1) > 1e-3  # the current matters here


def _rods_deck(tmp_path: Path, rods: list[str]) -> tuple[Path, str]:
    """The OC3 deck with a CoupledPinned body and the given RODS rows."""
    text = OC3.read_text().replace("---------------------- POINTS", "\n".join([
        "---------------------- ROD TYPES ----", "Name Diam Mass Cd Ca CdEnd CaEnd",
        "(-) (m) (kg/m) (-) (-) (-) (-)", "rod 1.0 100 1 1 1 1",
        "---------------------- BODIES ----", "ID Attachment X0 Y0 Z0 r0 p0 y0 M CG I V CdA Ca",
        "(#) (-) (m) (m) (m) (deg) (deg) (deg) (kg) (m) (kg-m2) (m3) (m2) (-)",
        "1 CoupledPinned 0 0 -2 0 0 0 1e3 0 0 1 0 0",
        "---------------------- RODS ----", "ID RodType Attachment Xa Ya Za Xb Yb Zb NumSegs",
        "(#) (-) (-) (m) (m) (m) (m) (m) (m) (-)", *rods,
        "---------------------- POINTS"]))
    path = tmp_path / "bodies.dat"
    path.write_text(text)
    return path, text


def test_rods_pinned_to_a_pinned_body_are_refused_at_once(tmp_path: Path) -> None:
    """Two Body<k>Pinned rods on a CoupledPinned body (a pin on a pinned body): one error
    naming both, each with its line, before the lines are read."""
    path, text = _rods_deck(tmp_path, ["1 rod Body1Pinned 0 0 -1 0 0 -5 4 -",
                                       "2 rod Body1Pin 1 0 -1 1 0 -5 4 -"])
    with pytest.raises(CaseError) as info:
        read_moordyn(path)
    reason = info.value.reason
    assert f"rod 1 (Body1Pinned, line {_line_of(text, '1 rod Body1Pinned')})" in reason
    assert f"rod 2 (Body1Pin, line {_line_of(text, '2 rod Body1Pin')})" in reason
    assert "rods pinned to a pinned body" in reason and "cannot be represented" in reason


def test_pinned_rods_and_coupled_pinned_bodies_become_pinned_bodies(tmp_path: Path) -> None:
    """``Pinned`` and ``CoupledPinned`` rods and a ``CoupledPinned`` body are pinned bodies:
    a rod's pin at its end A with its x axis along the rod, its mass ``Mass/m L`` at its
    middle; the body keeps its mass and volume (as MoorDyn-C
    2.7 ``Body.cpp`` does for ``CPLDPIN``), its pin at its reference point; the rods float them
    by rods hydrostatics."""
    path, _ = _rods_deck(tmp_path, ["1 rod Pinned 0 0 -10 3 0 -14 4 -",
                                    "2 rod CoupledPinned 5 0 -1 5 0 -6 4 -"])
    system = read_moordyn(path)
    body, rod, coupled = (system.bodies[n] for n in ("body1", "rod1", "rod2"))
    assert (body.kind, rod.kind, coupled.kind) == ("pinned",) * 3
    assert body.position == (0.0, 0.0, -2.0) and body.mass == 1e3
    assert body.hydrostatics.volume == 1.0
    assert rod.position == (0.0, 0.0, -10.0) and coupled.position == (5.0, 0.0, -1.0)
    R = rotation_matrix(np.asarray(rod.rotation))
    assert R @ np.array([1.0, 0.0, 0.0]) == pytest.approx([0.6, 0.0, -0.8], abs=1e-12)
    assert rod.mass == pytest.approx(100 * 5.0)
    assert rod.center_of_gravity == pytest.approx((2.5, 0.0, 0.0), abs=1e-12)
    # rods hydrostatics: the rod, end A at the pin, 5 m along body x, 1 m in diameter
    hs = rod.hydrostatics
    assert hs.kind == "rods" and hs.volume == 0.0 and len(hs.rods) == 1
    np.testing.assert_allclose(np.asarray(hs.rods[0][:2]), [[0, 0, 0], [5, 0, 0]], atol=1e-12)
    assert hs.rods[0][2] == 1.0


def test_is_moordyn_deck() -> None:
    from moorline.io.moordyn import is_moordyn_deck

    root = Path(__file__).resolve().parents[1]
    assert is_moordyn_deck(OC3) and is_moordyn_deck(DATA / "oc3_v1.dat")
    assert not is_moordyn_deck(root / "cases" / "oc3_line.yaml")
    assert not is_moordyn_deck(DATA / "absent.dat")
