"""``moorline export --moordyn`` (MoorDyn's main ``.out`` file) and the deck writer's
``OUTPUTS``/``TMax``/``dtOut`` (issue 14, deliverable 4).

The ``.out`` layout is MoorDyn-C v2.7's (``source/MoorDyn2.cpp``: ``setw(10)`` ``Time``,
``setw(20)`` per channel; units row ``(s)`` then the bare units; rows ``%10.4f`` then
``%20.7e``), checked here by a parser written for this test and, with the [compare] extra,
against the file moordyn 2.7.2 itself writes for the same deck.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import netCDF4
import numpy as np
import pytest
import yaml
from click.testing import CliRunner

from moorline.cli import cli
from moorline.io import load_case
from moorline.io.moordyn import read_moordyn_deck, write_moordyn

DATA = Path(__file__).parent / "data" / "moordyn"
PUBLIC = DATA / "public"
#: The channels of oc3_outputs.dat moorline writes (L1T20 is no MoorDyn name: left out).
WRITTEN = ["FairTen1", "AnchTen1", "L1N19T", "L1N10T", "L1NBFX", "L1N20FZ", "Point4FX",
           "Con1FX", "L1N10PZ", "FairSegTen1"]
ROW = re.compile(r"^ *\d+\.\d{4}$")
VALUE = re.compile(r"^ *-?(\d\.\d{7}e[+-]\d{2,3}|nan|inf)$")


def parse_out(path: Path) -> tuple[list[str], list[str], np.ndarray, list[str]]:
    """Names, units, the numbers and the raw lines of a MoorDyn main ``.out`` file; every
    row is checked to be MoorDyn's fixed-width layout (10 characters for Time, 20 a
    channel, right-aligned, without separators)."""
    lines = path.read_text().splitlines()
    names, units = lines[0].split(), lines[1].split()
    assert len(names) == len(units)
    width = 10 + 20 * (len(names) - 1)
    for line in lines:
        assert len(line) == width, line
        fields = [line[:10]] + [line[10 + 20 * k:30 + 20 * k] for k in range(len(names) - 1)]
        assert all(f.startswith(" ") for f in fields), line  # right-aligned, space-separated
    for line in lines[2:]:
        assert ROW.match(line[:10]), line
        assert all(VALUE.match(line[10 + 20 * k:30 + 20 * k]) for k in range(len(names) - 1))
    rows = np.array([[float(v) for v in line.split()] for line in lines[2:]])
    return names, units, rows, lines


def printed(value: float) -> float:
    """Half a unit of the 8th significant digit of ``value`` (``%.7e``), the rounding of the
    printed number."""
    return 0.5 * 10.0 ** (math.floor(math.log10(abs(value))) - 7) if value else 0.0


@pytest.fixture(scope="module")
def moving_run(tmp_path_factory: pytest.TempPathFactory) -> dict:
    """oc3_outputs.dat converted, fairlead1 moved 2 m in surge at a 2 s period (0.5 s ramp)
    for its TMax = 1 s (dtOut 0.1 s), run and exported with ``--moordyn``."""
    tmp = tmp_path_factory.mktemp("mdout")
    case = tmp / "oc3_outputs.yaml"
    runner = CliRunner()
    result = runner.invoke(cli, ["convert", str(DATA / "oc3_outputs.dat"), "--out", str(case),
                                 "-q"])
    assert result.exit_code == 0, result.output
    data = yaml.safe_load(case.read_text())
    data["points"]["fairlead1"]["motion"] = {"kind": "harmonic", "amplitude": [2.0, 0, 0],
                                             "period": 2.0, "ramp_time": 0.5}
    case.write_text(yaml.safe_dump(data))
    result = runner.invoke(cli, ["run", str(case), "--out", str(tmp / "out"), "--no-plots",
                                 "-q"])
    assert result.exit_code == 0, result.output
    results = tmp / "out" / "oc3_outputs" / "results.nc"
    result = runner.invoke(cli, ["export", str(results), "--moordyn", "--line-outputs", "pts",
                                 "--out", str(tmp / "md"), "-q"])
    assert result.exit_code == 0, result.output
    assert sorted(p.name for p in (tmp / "md").iterdir()) == [
        "oc3_outputs.out", *(f"oc3_outputs_Line{k}.out" for k in (1, 2, 3))]
    return {"case": case, "results": results, "out": tmp / "md" / "oc3_outputs.out"}


def test_out_file_parses_back_with_the_results_values(moving_run) -> None:
    """Header, units and rows of the case's channels; every number equals the results'
    value to its printed digits (FairTen1 also against the end force read with netCDF4,
    and the motion makes every row different)."""
    from moorline.io.moordyn_outputs import channel_series, parse_channel
    from moorline.io.writers import read_group

    names, units, rows, _ = parse_out(moving_run["out"])
    assert names == ["Time", *WRITTEN]
    assert units == ["(s)", *["N"] * 8, "m", "N"]
    ds = read_group(moving_run["results"], "dynamics")
    time = ds["time"].values
    assert len(rows) == len(time) == 11
    np.testing.assert_allclose(rows[:, 0], time, rtol=0, atol=0.5e-4 + 1e-12)
    for k, name in enumerate(WRITTEN, start=1):
        expected = channel_series(parse_channel(name), ds)  # type: ignore[arg-type]
        bound = np.array([printed(v) for v in expected]) * (1 + 1e-9)
        assert np.all(np.abs(rows[:, k] - expected) <= bound), name
    with netCDF4.Dataset(moving_run["results"]) as root:
        force = np.asarray(root["dynamics"]["end_force"][:])[:, 0, 1]  # line1, end b
    fair = np.linalg.norm(force, axis=-1)
    assert np.all(np.abs(rows[:, 1] - fair) <= [printed(v) * (1 + 1e-9) for v in fair])
    assert len(np.unique(rows[:, 1])) == len(rows)  # the motion changes it every record
    assert rows[:, 1].max() - rows[:, 1].min() > 1e3


def test_line_file_holds_nodes_and_segments(moving_run) -> None:
    """oc3_outputs_Line1.out for the flags ``pts``: node positions from end A (the anchor
    first), segment tensions, strains; the strain at t = 0 (at rest: no damping) is
    T / EA of the elastic chain (EA = 384.243e6 N)."""
    from moorline.io.writers import read_group

    names, units, rows, _ = parse_out(moving_run["out"].with_name("oc3_outputs_Line1.out"))
    assert names == ["Time", *(f"Node{i}p{x}" for i in range(21) for x in "xyz"),
                     *(f"Seg{i}Te" for i in range(1, 21)), *(f"Seg{i}St" for i in range(1, 21))]
    assert units == ["(s)", *["(m)"] * 63, *["(N)"] * 20, *["(-)"] * 20]
    ds = read_group(moving_run["results"], "dynamics")
    position = rows[:, 1:64].reshape(len(rows), 21, 3)
    np.testing.assert_allclose(position[:, 0], [[853.87, 0.0, -320.0]] * len(rows), atol=1e-4)
    np.testing.assert_allclose(position[:, -1], ds["position"].values[:, 3], rtol=1e-7)
    elements = np.flatnonzero(ds["element_line"].values == "line1")
    np.testing.assert_allclose(rows[:, 64:84], ds["tension"].values[:, elements], rtol=1e-7)
    np.testing.assert_allclose(rows[0, 84:], rows[0, 64:84] / 384.243e6, rtol=1e-6)


def test_default_channels_are_the_end_tensions(moving_run) -> None:
    """Without channels: FairTen<n> then AnchTen<n> of every line (MoorDyn would write only
    Time), in the same layout."""
    from moorline.io.moordyn_out import main_out_text
    from moorline.io.writers import read_group

    ds = read_group(moving_run["results"], "dynamics")
    head, units, first = main_out_text(ds, ()).splitlines()[:3]
    assert head.split() == ["Time", "FairTen1", "FairTen2", "FairTen3", "AnchTen1",
                            "AnchTen2", "AnchTen3"]
    assert units.split() == ["(s)", *["N"] * 6]
    expected = np.linalg.norm(ds["end_force"].values[0], axis=-1)  # (line, end)
    np.testing.assert_allclose([float(v) for v in first.split()[1:]],
                               [*expected[:, 1], *expected[:, 0]], rtol=1e-7)


def test_export_moordyn_bad_input(moving_run, tmp_path: Path) -> None:
    both = CliRunner().invoke(cli, ["export", str(moving_run["results"]), "--moordyn",
                                    "--text"])
    assert both.exit_code == 2
    alone = CliRunner().invoke(cli, ["export", str(moving_run["results"]), "--line-outputs",
                                     "p"])
    assert alone.exit_code == 2
    statics = tmp_path / "statics.nc"
    with netCDF4.Dataset(moving_run["results"]) as source, \
            netCDF4.Dataset(statics, "w") as target:  # the root and the statics group only
        target.setncatts({k: source.getncattr(k) for k in source.ncattrs()})
        group = target.createGroup("statics")
        group.setncattr("analysis", "statics")
    result = CliRunner().invoke(cli, ["export", str(statics), "--moordyn", "--out",
                                      str(tmp_path)])
    assert result.exit_code == 2 and "no dynamics" in result.output


@pytest.mark.parametrize("deck", [DATA / "oc3_outputs.dat",
                                  PUBLIC / "MoorPy" / "examples" / "volturn_chain.dat",
                                  PUBLIC / "MoorPy" / "tests" / "case1.dat"])
def test_deck_writer_round_trips_outputs_and_time_settings(deck: Path, tmp_path: Path) -> None:
    """convert -> write_moordyn -> read: the same channels (those moorline can compute) and
    the same analyses (TMax: a dynamics analysis of that duration) and output interval."""
    case = tmp_path / "case.yaml"
    result = CliRunner().invoke(cli, ["convert", str(deck), "--out", str(case), "-q"])
    assert result.exit_code == 0, result.output
    system = load_case(case)
    original = read_moordyn_deck(deck)
    assert system.output.channels == original.outputs and system.output.channels
    back = read_moordyn_deck(write_moordyn(system, tmp_path / "back.dat", 0.002))
    from moorline.io.moordyn_outputs import parse_channel

    assert back.outputs == tuple(n for n in original.outputs if parse_channel(n))
    assert back.system.analyses == system.analyses
    assert back.system.output == system.output.__class__(system.output.every, back.outputs)


def test_deck_writer_time_options_from_the_analyses(tmp_path: Path) -> None:
    """TMax from the first dynamics analysis, dtOut from output.every; a statics-only case
    with the default interval writes neither; channels naming a missing line or node are
    left out (MoorDyn refuses such a deck)."""
    import dataclasses

    from moorline.model import DynamicsSettings, OutputSettings, StaticsSettings

    system = read_moordyn_deck(DATA / "oc3.dat").system
    statics = write_moordyn(system, tmp_path / "s.dat", 0.002).read_text()
    assert not re.search(r"^\S+\s+(TMax|dtOut)\b", statics, re.M)
    dynamic = dataclasses.replace(
        system, analyses=(StaticsSettings(), DynamicsSettings(duration=30.0, dt=0.02)),
        output=OutputSettings(every=0.25, channels=("FairTen3", "FairTen4", "L1N21T",
                                                    "L2N20PX")))
    text = write_moordyn(dynamic, tmp_path / "d.dat", 0.002).read_text()
    assert re.search(r"^30\.0\s+TMax$", text, re.M) and re.search(r"^0\.25\s+dtOut$", text,
                                                                   re.M)
    assert len(re.findall(r"^\S+\s+dtM$", text, re.M)) == 1  # the dt argument only
    section = text.split("OUTPUTS")[1].split("need this line")[0].split()
    assert section[1:-1] == ["FairTen3", "L2N20PX", "END"]


@pytest.mark.compare
def test_same_layout_as_moordyns_own_out_file(moving_run, tmp_path: Path) -> None:
    """MoorDyn-C (moordyn 2.7.2) on the deck moorline writes for the same case, held at
    rest: its ``moorline.out`` has the channels it reads (not Con1FX, a v1 name, nor
    FairSegTen1, moorline's), and moorline's file for those channels has byte-identical
    name and unit rows and rows of the same widths. Values: MoorDyn's at rest against
    moorline's t = 0 record (the static state), to 5e-4: the statics difference of the two
    codes measured in tests/test_moordyn_io.py::test_channels_match_moordyn_out_file."""
    pytest.importorskip("moordyn")
    from moorline.compare.moordyn_runner import run_moordyn
    from moorline.io.moordyn_out import main_out_text
    from moorline.io.writers import read_group

    system = load_case(moving_run["case"])
    rest = system.points["fairlead1"].position
    run = run_moordyn(system, 0.3, 0.002, 0.1, {"fairlead1": lambda t: (rest, np.zeros(3))},
                      tmax_ic=500.0, workdir=tmp_path)
    assert run["success"], run["message"]
    names, units, rows, lines = parse_out(tmp_path / "moorline.out")
    assert names == ["Time", *(n for n in WRITTEN if n not in ("Con1FX", "FairSegTen1"))]
    assert units == ["(s)", *["N"] * 7, "m"]
    np.testing.assert_allclose(rows[:, 0], [0.1, 0.2, 0.3])  # no t = 0 row when dtOut > 0
    ds = read_group(moving_run["results"], "dynamics")
    ours = main_out_text(ds, names[1:])
    (tmp_path / "ours.out").write_text(ours)
    _, _, our_rows, our_lines = parse_out(tmp_path / "ours.out")
    assert our_lines[:2] == lines[:2]
    assert {len(line) for line in our_lines} == {len(line) for line in lines}
    for k, name in enumerate(names[1:], start=1):
        assert rows[-1, k] == pytest.approx(our_rows[0, k], rel=5e-4), name


@pytest.mark.compare
def test_same_line_file_layout_as_moordyn(moving_run, tmp_path: Path) -> None:
    """MoorDyn-C on oc3_outputs.dat itself (line 1 flagged ``pt``; its IC converged with
    threshIC 1e-5, TmaxIC 500 s) writes oc3_outputs_Line1.out: moorline's file for the same
    flags has byte-identical name and unit rows and rows of the same width. Values at rest:
    segment tensions to 5e-4 (the statics difference measured in
    tests/test_moordyn_io.py::test_channels_match_moordyn_out_file), node positions to 5e-4
    of the line's length (the same relative difference)."""
    moordyn = pytest.importorskip("moordyn")
    import shutil

    from moorline.io.moordyn_out import line_out_text
    from moorline.io.writers import read_group

    deck = Path(shutil.copy(DATA / "oc3_outputs.dat", tmp_path / "oc3_outputs.dat"))
    system = load_case(moving_run["case"])
    x = np.concatenate([system.points[f"fairlead{k}"].position for k in (1, 2, 3)])
    md = moordyn.Create(str(deck))
    try:
        moordyn.Init(md, x, np.zeros(9))
        moordyn.Step(md, x, np.zeros(9), 0.0, 0.1)
    finally:
        moordyn.Close(md)
    names, _, rows, lines = parse_out(tmp_path / "oc3_outputs_Line1.out")
    ds = read_group(moving_run["results"], "dynamics")
    (tmp_path / "ours.out").write_text(line_out_text(ds, 1, "pt"))
    ours, _, our_rows, our_lines = parse_out(tmp_path / "ours.out")
    assert our_lines[:2] == lines[:2] and len(our_lines[2]) == len(lines[2])
    np.testing.assert_allclose(our_rows[0, 64:], rows[-1, 64:], rtol=5e-4)
    np.testing.assert_allclose(our_rows[0, 1:64], rows[-1, 1:64], rtol=0, atol=5e-4 * 902.2)


def test_us_case_writes_its_own_units(tmp_path: Path) -> None:
    """A US case (cases/tuah_ex7.yaml, ft and lbf) with 0.2 s of dynamics and channels of
    each kind: the units row holds the results' units (lbf, ft, ft/s), the numbers are in
    them (FairTen1 equals the results' end force in lbf)."""
    from moorline.io.writers import read_group

    case = yaml.safe_load((Path(__file__).parents[1] / "cases" / "tuah_ex7.yaml").read_text())
    case["analyses"].append({"kind": "dynamics", "duration": 0.2, "dt": 0.05})
    case["output"] = {"every": 0.1, "channels": ["FairTen1", "L1N1PZ", "L2N1VX", "P1FZ"]}
    path = tmp_path / "us.yaml"
    path.write_text(yaml.safe_dump(case))
    out = tmp_path / "out"
    result = CliRunner().invoke(cli, ["run", str(path), "--out", str(out), "--no-plots", "-q"])
    assert result.exit_code == 0, result.output
    (results,) = out.glob("*/results.nc")
    result = CliRunner().invoke(cli, ["export", str(results), "--moordyn", "--out",
                                      str(tmp_path / "md"), "-q"])
    assert result.exit_code == 0, result.output
    (written,) = (tmp_path / "md").glob("*.out")
    names, units, rows, _ = parse_out(written)
    assert names == ["Time", "FairTen1", "L1N1PZ", "L2N1VX", "P1FZ"]
    assert units == ["(s)", "lbf", "ft", "ft/s", "lbf"]
    ds = read_group(results, "dynamics")
    assert ds["end_force"].attrs["units"] == "lbf"
    fair = np.linalg.norm(ds["end_force"].values[:, 0, 1], axis=-1)
    np.testing.assert_allclose(rows[:, 1], fair, rtol=1e-7)
