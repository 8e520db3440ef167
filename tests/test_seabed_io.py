"""Seabed slope and bathymetry in case files and MoorDyn decks (issue 14, deliverable 3):
MoorDyn's seafloor file read (a public MoorDyn deck and its file), clear errors for bad
input, and the round trips through ``moorline convert``'s case writer and the MoorDyn
writer."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from moorline.errors import CaseError
from moorline.io import load_case, load_case_text
from moorline.io.case_writer import write_case
from moorline.io.moordyn import read_moordyn, read_moordyn_deck, write_moordyn
from moorline.io.seafloor import read_seafloor
from moorline.mesh import discretize

PUBLIC = Path(__file__).parent / "data" / "moordyn" / "public" / "MoorDyn"


def test_moordyns_seafloor_deck_reads_its_grid() -> None:
    """tests/Mooring/seafloor.txt of MoorDyn v2.7.1 names Mooring/3D_seafloor/
    seafloor_profile_3d.txt: a 100 x 5 grid, z = -30 + 0.2 x (its rows, checked here at the
    corners and in between against the file's own numbers)."""
    deck = read_moordyn_deck(PUBLIC / "seafloor.txt")
    grid = deck.system.environment.seabed.bathymetry
    assert grid is not None and len(grid.x) == 100 and len(grid.y) == 5
    assert grid.x[0] == -50.0 and grid.x[-1] == 50.0 and grid.y == (-2.0, -1.0, 0.0, 1.0, 2.0)
    z = np.asarray(grid.z)
    assert z[0, 0] == -40.0 and z[-1, -1] == -20.0
    assert np.allclose(z, -30.0 + 0.2 * np.asarray(grid.x)[:, None], atol=1e-12)
    assert any("SeafloorFile" in note for note in deck.notes)
    mesh = discretize(deck.system)
    # the seabed under the free point (10, -1, -28): -30 + 0.2 * 10
    assert mesh.seabed_height(np.array([[10.0, -1.0, 0.0]]))[0] == pytest.approx(-28.0)
    # the waves' depth is the grid's mean depth, as MoorDyn-C sets it (MoorDyn2.cpp), not
    # WtrDpth 500: 30 - 0.2 mean(x) from the file's z = -30 + 0.2 x
    assert deck.system.environment.depth == pytest.approx(30.0 - 0.2 * np.mean(grid.x),
                                                          rel=1e-12)
    assert any("mean depth" in note for note in deck.notes)


GOOD = "2 2\n0 10\n-5 5\n0 -5 -100\n0 5 -101\n10 -5 -102\n10 5 -103\n"


@pytest.mark.parametrize("text, says", [
    (GOOD.replace("10 5 -103\n", ""), "no height at the grid node (10, 5)"),
    (GOOD.replace("10 5 -103", "10 4 -103"), "line 7: (10, 4) is not a node of the grid"),
    (GOOD.replace("10 5 -103", "0 5 -103"), "line 7: node (0, 5) is given twice"),
    (GOOD.replace("2 2", "2 x"), "line 1: the first line must be two counts"),
    (GOOD.replace("0 10\n", "10 0\n"), "the x grid lines must increase strictly"),
    (GOOD.replace("-5 5\n", "-5 5 7\n"), "line 3: y grid lines: expected 2 values, got 3"),
    (GOOD.replace("-101", "nan"), "line 5: a grid node 'x y z': must be a number"),
    ("2 2\n0 10\n", "needs the grid sizes"),
    (GOOD.replace("-101", "101"), "below the free surface z = 0, got z = 101 at (0, 5)"),
])
def test_bad_seafloor_files_are_refused_naming_the_file_and_line(tmp_path, text, says) -> None:
    path = tmp_path / "floor.txt"
    path.write_text(text)
    with pytest.raises(CaseError, match="floor.txt") as err:
        read_seafloor(path)
    assert says in str(err.value)


CASE = """
name: sb
units: SI
environment: {{depth: 100, seabed: {{{seabed}}}}}
line_types:
  c: {{diameter: 0.1, mass_per_length: 20, EA: 1.0e8}}
points:
  a: {{kind: fixed, position: [{ax}, 0, {az}]}}
  b: {{kind: fixed, position: [150, 0, -10]}}
lines:
  l: {{type: c, length: 200, segments: 10, end_a: a, end_b: b}}
"""


def _case(seabed: str, ax: float = 0.0, az: float = -100.0) -> str:
    return CASE.format(seabed=seabed, ax=ax, az=az)


@pytest.mark.parametrize("seabed, field, says", [
    ("slope: 90", "environment.seabed.slope", "below 90 degrees"),
    ("slope: -2", "environment.seabed.slope", ">= 0"),
    ("slope: 2, bathymetry: {x: [0, 1], y: [0, 1], z: [[-1, -1], [-1, -1]]}",
     "environment.seabed.bathymetry", "either a slope or a bathymetry grid"),
    ("bathymetry: {x: [0, 1], y: [0, 1], z: [[-1, -1]]}", "environment.seabed.bathymetry",
     "2 x 2 grid nodes"),
    ("bathymetry: {x: [0], y: [0, 1], z: [[-1, -1]]}", "environment.seabed.bathymetry",
     "at least 2 x grid lines"),
    ("bathymetry: {x: [0, 1], y: [1, 0], z: [[-1, -1], [-1, -1]]}",
     "environment.seabed.bathymetry", "y grid lines must increase strictly"),
    ("bathymetry: nowhere.txt", "environment.seabed.bathymetry", "cannot read seafloor file"),
    ("slope: 5", "points.a.position[2]", "fixed point is below the seabed"),
])
def test_bad_seabed_geometry_is_refused_with_the_key(seabed, field, says) -> None:
    # with the 5 deg slope (down towards +x) the seabed under x = -50 is at -95.6
    with pytest.raises(CaseError) as err:
        load_case_text(_case(seabed, ax=-50.0, az=-99.0), file="case.yaml")
    assert err.value.field == field, str(err.value)
    assert says in str(err.value) and "case.yaml" in str(err.value)


def test_a_bathymetry_grid_needs_a_depth() -> None:
    text = _case("bathymetry: {x: [0, 1], y: [0, 1], z: [[-1, -1], [-1, -1]]}")
    with pytest.raises(CaseError, match="needs a finite environment.depth"):
        load_case_text(text.replace("depth: 100, ", ""))


def test_a_seafloor_file_relative_to_the_case_and_the_case_writer_round_trip(tmp_path) -> None:
    (tmp_path / "floor.txt").write_text("2 3\n-10 200\n-50 0 50\n" + "".join(
        f"{x} {y} {-100 - 0.01 * x + 0.001 * y * x}\n" for x in (-10, 200) for y in (-50, 0, 50)))
    case = tmp_path / "case.yaml"
    case.write_text(_case("bathymetry: floor.txt, stiffness: 1.0e6", az=-99.9))
    system = load_case(case)
    grid = system.environment.seabed.bathymetry
    assert grid.z[1][2] == pytest.approx(-100 - 2 + 10)
    again = load_case(write_case(system, tmp_path / "again.yaml"))
    assert again.environment.seabed == system.environment.seabed
    sloped = load_case_text(_case("slope: 3, slope_heading: 200"))
    back = load_case(write_case(sloped, tmp_path / "sloped.yaml"))
    assert back.environment.seabed == sloped.environment.seabed


def test_the_moordyn_writer_writes_a_seafloor_file_that_reads_back_as_the_plane(tmp_path):
    """A plane becomes a 2 x 2 MoorDyn grid reaching a line length beyond the points;
    bilinear interpolation of a plane is the plane."""
    system = load_case_text(_case("slope: 4, slope_heading: 30", az=-100.0))
    deck = write_moordyn(system, tmp_path / "deck.dat", dt=1e-3)
    assert "SeafloorFile" in deck.read_text()
    back = read_moordyn(deck)
    xy = np.array([[0.0, 0.0, 0.0], [150.0, 0.0, 0.0], [-120.0, 90.0, 0.0]])
    plane = discretize(system).seabed_height(xy)
    assert np.allclose(discretize(back).seabed_height(xy), plane, rtol=0, atol=1e-9)


@pytest.mark.compare
def test_moordyn_statics_on_a_seafloor_grid_match_moorlines() -> None:
    """The OC3 line (40 segments) over a seafloor grid that is flat at z = -300 under its
    lying part and rises towards the fairlead, with WtrDpth 320: both codes put the line on
    the grid, not on z = -320 (MoorDyn reads the grid from the SeafloorFile the writer
    makes). MoorDyn-C's IC (threshIC 1e-6) and moorline's statics: fairlead force within
    5e-4 (measured 6e-5; the OC3 comparison on a flat seabed gets 1e-5: the contact models
    differ slightly). On a sloped seabed no such comparison is possible: MoorDyn pushes only
    vertically, and its IC solve did not reach equilibrium on a 3 deg slope (residual 0.5 and
    7 m/s^2 after 78 s and 2 s)."""
    pytest.importorskip("moordyn")
    import dataclasses

    from moorline.compare import run_moordyn
    from moorline.model import Bathymetry
    from moorline.solvers.statics import solve_statics
    from moorline.verification.oc3_system import oc3_one_line

    system = oc3_one_line(40)
    env = system.environment
    grid = Bathymetry(x=(-100.0, 500.0, 1000.0), y=(-100.0, 100.0),
                      z=((-280.0, -280.0), (-300.0, -300.0), (-300.0, -300.0)))
    anchor = system.points["anchor1"]
    system = dataclasses.replace(
        system,
        environment=dataclasses.replace(env, seabed=dataclasses.replace(env.seabed,
                                                                        bathymetry=grid)),
        points={**system.points, "anchor1": dataclasses.replace(
            anchor, position=(anchor.position[0], anchor.position[1], -300.0))})
    static = solve_statics(system)
    assert static.success, static.message
    x = static.positions
    assert static.seabed_length("line1") > 150.0  # a real lying part, on the flat top
    assert np.all(x[static.seabed_share() > 0, 0] > 500.0)
    run = run_moordyn(system, 0.5, 0.001, 0.5, thresh_ic=1e-6, tmax_ic=300.0)
    assert run["success"], run["message"]
    assert run["ic_residual"] < 1e-4
    expected = static.end_force("line1", "b")
    np.testing.assert_allclose(run["end_force"][0, 0, 1], expected,
                               atol=5e-4 * np.linalg.norm(expected))
