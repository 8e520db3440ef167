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
