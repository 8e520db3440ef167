"""``moorline export``: CSV and text tables of a results file, checked against the NetCDF
variables read independently with netCDF4; the CF attributes of the results file."""

from __future__ import annotations

import csv
from collections.abc import Callable
from pathlib import Path

import netCDF4
import numpy as np
import pytest
import xarray as xr
import yaml
from click.testing import CliRunner

from moorline.cli import cli
from moorline.datasets import build_dataset, group_attrs
from moorline.io.export import group_tables, write_table

ROOT = Path(__file__).resolve().parents[1]
BOX = ROOT / "cases" / "wang_box.yaml"
DOFS = ("Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw")


@pytest.fixture(scope="module")
def box_run(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, dict]:
    """The Wang box (a free body on four lines) at 4 segments: statics, then 1 s of
    dynamics; its results file and the case mapping."""
    case = yaml.safe_load(BOX.read_text())
    for line in case["lines"].values():
        line["segments"] = 4
    case["analyses"].append({"kind": "dynamics", "duration": 1.0, "dt": 0.1})
    case["output"] = {"every": 0.2}
    directory = tmp_path_factory.mktemp("export")
    path = directory / "box.yaml"
    path.write_text(yaml.safe_dump(case))
    result = CliRunner().invoke(cli, ["run", str(path), "--out", str(directory / "out"),
                                      "--no-plots", "-q"])
    assert result.exit_code == 0, result.output
    return directory / "out" / "wang-box" / "results.nc", case


def _read(path: Path) -> tuple[list[str], list[str], np.ndarray]:
    """Names, units (parentheses stripped) and the rows of an exported CSV file."""
    with path.open(newline="") as handle:
        rows = list(csv.reader(handle))
    units = [u.removeprefix("(").removesuffix(")") for u in rows[1]]
    return rows[0], units, np.array(rows[2:], dtype=object)


def _export(results: Path, out: Path, *flags: str) -> Path:
    result = CliRunner().invoke(cli, ["export", str(results), "--out", str(out), *flags])
    assert result.exit_code == 0, result.output
    return out


def test_dynamics_csv_has_moordyn_columns_and_values(box_run, tmp_path):
    results, case = box_run
    out = _export(results, tmp_path, "--csv")
    names, units, rows = _read(out / "dynamics.csv")
    n = len(case["lines"])
    assert names == ["Time", *(f"FairTen{k}" for k in range(1, n + 1)),
                     *(f"AnchTen{k}" for k in range(1, n + 1)),
                     *(f"Body1{d}" for d in DOFS)]
    assert units == ["s", *["N"] * 2 * n, "m", "m", "m", "rad", "rad", "rad"]
    values = rows.astype(float)
    with netCDF4.Dataset(results) as root:
        group = root["dynamics"]
        assert list(group["line"][:]) == list(case["lines"])  # MoorDyn's numbering
        force = np.asarray(group["end_force"][:])          # (time, line, end, xyz)
        assert values[:, 0] == pytest.approx(np.asarray(group["time"][:]), abs=0)
        # FairTen: the end-point force's magnitude at end b; AnchTen at end a
        fair = np.sqrt((force[:, :, 1, :] ** 2).sum(axis=-1))
        anch = np.sqrt((force[:, :, 0, :] ** 2).sum(axis=-1))
        np.testing.assert_allclose(values[:, 1:n + 1], fair, rtol=1e-14)
        np.testing.assert_allclose(values[:, n + 1:2 * n + 1], anch, rtol=1e-14)
        np.testing.assert_array_equal(values[:, 2 * n + 1:], np.asarray(group["body_pose"][:,
                                                                                       0]))
    assert len(values) == 6  # t = 0, 0.2, ..., 1.0


def test_fairten_is_the_moordyn_channel_of_the_deck_writer(box_run, tmp_path):
    """The same number as the ``OUTPUTS`` channel ``FairTen2`` of a converted deck."""
    from moorline.io.moordyn_outputs import channel_series, parse_channel
    from moorline.io.writers import read_group

    results, case = box_run
    ds = read_group(results, "dynamics")
    names, _, rows = _read(_export(results, tmp_path) / "dynamics.csv")
    for name in ("FairTen2", "AnchTen3"):
        expected = channel_series(parse_channel(name), ds)  # type: ignore[arg-type]
        np.testing.assert_allclose(rows[:, names.index(name)].astype(float), expected,
                                   rtol=1e-14)


def test_statics_line_tables_follow_the_line(box_run, tmp_path):
    results, case = box_run
    out = _export(results, tmp_path)
    with netCDF4.Dataset(results) as root:
        group = root["statics"]
        lines = list(group["line"][:])
        position = np.asarray(group["position"][:])
        tension = np.asarray(group["tension"][:])
        pairs = np.asarray(group["element_nodes"][:])
        end_force = np.asarray(group["end_force"][:])
        max_tension = np.asarray(group["max_tension"][:])
    for k, line in enumerate(lines):
        names, units, rows = _read(out / f"statics_{line}.csv")
        assert names == ["node", "arc_length", "x", "y", "z", "tension"]
        assert units == ["1", "m", "m", "m", "m", "N"]
        values = rows.astype(float)
        spec = case["lines"][line]
        # from end a (the anchor of the case file) to end b, over the unstretched length
        anchor = case["points"][spec["end_a"]]["position"]
        assert values[0, 2:5] == pytest.approx(anchor, abs=1e-9)
        assert values[:, 1] == pytest.approx(np.linspace(0, spec["length"], 5), rel=1e-12)
        # each consecutive pair of rows is an element of the mesh (in some orientation)
        nodes = [int(np.flatnonzero(np.all(position == xyz, axis=1))[0])
                 for xyz in values[:, 2:5]]
        elements = [int(np.flatnonzero(np.all(np.sort(pairs, axis=1) == sorted(p),
                                              axis=1))[0])
                    for p in zip(nodes[:-1], nodes[1:], strict=True)]
        inner = 0.5 * (tension[elements][:-1] + tension[elements][1:])
        ends = np.linalg.norm(end_force[k], axis=-1)
        np.testing.assert_allclose(values[:, 5], [ends[0], *inner, ends[1]], rtol=1e-14)
    names, units, rows = _read(out / "statics_ends.csv")
    assert names == ["line", "end", "Fx", "Fy", "Fz", "tension", "max_tension"]
    assert units[2:] == ["N"] * 5
    assert list(rows[:, 0]) == [ln for ln in lines for _ in "ab"]
    np.testing.assert_array_equal(rows[:, 2:5].astype(float), end_force.reshape(-1, 3))
    np.testing.assert_array_equal(rows[:, 6].astype(float), np.repeat(max_tension, 2))


def test_text_tables_hold_the_same_numbers(box_run, tmp_path):
    results, _ = box_run
    csv_dir = _export(results, tmp_path / "csv")
    text_dir = _export(results, tmp_path / "text", "--text")
    lines = (text_dir / "dynamics.txt").read_text().splitlines()
    names = lines[0].split()
    assert names[:2] == ["Time", "FairTen1"] and lines[1].split()[:2] == ["(s)", "(N)"]
    widths = {len(line) for line in lines}
    assert len(widths) == 1  # fixed width
    text = np.array([line.split() for line in lines[2:]], dtype=float)
    _, _, rows = _read(csv_dir / "dynamics.csv")
    np.testing.assert_allclose(text, rows.astype(float), rtol=1e-9, atol=1e-20)


def test_export_bad_input(tmp_path):
    missing = CliRunner().invoke(cli, ["export", str(tmp_path / "none.nc")])
    assert missing.exit_code == 2 and "none.nc" in missing.output
    both = CliRunner().invoke(cli, ["export", str(tmp_path / "none.nc"), "--csv", "--text"])
    assert both.exit_code == 2


def test_results_file_is_cf_described(box_run, undescribed: Callable[[Path], list[str]]):
    results, _ = box_run
    assert undescribed(results) == []
    with netCDF4.Dataset(results) as root:
        for name in ("dynamics",):
            time = root[name]["time"]
            assert (time.standard_name, time.axis, time.units) == ("time", "T", "s")


def test_open_datatree_and_open_dataset_group(box_run):
    """The README's two ways of reading results.nc with xarray."""
    results, _ = box_run
    with xr.open_dataset(results, group="dynamics") as ds:
        tension = ds["fairlead_tension"].values
        assert ds["fairlead_tension"].dims == ("time", "line")
    if not hasattr(xr, "open_datatree"):
        pytest.skip("this xarray has no open_datatree")
    with xr.open_datatree(results) as tree:
        assert {"statics", "dynamics"} <= set(tree.children)
        np.testing.assert_array_equal(tree["dynamics"]["fairlead_tension"].values, tension)
        assert tree.attrs["analyses"] == "statics,dynamics"


# ----------------------------------------------------------------------------- other groups
def _attrs(kind: str) -> dict:
    return group_attrs(kind, case="c", units="SI", success=True, status="converged",
                       message="")


def test_spectra_table_against_omega(tmp_path):
    omega = np.array([0.1, 0.2, 0.4])
    spectrum = np.arange(6.0).reshape(3, 2)
    ds = build_dataset("stochastic", {"wave_spectrum": (("omega",), [1.0, 2.0, 3.0]),
                                      "tension_spectrum": (("omega", "element"), spectrum),
                                      "tension_std": (("element",), [1.0, 2.0])},
                       {"omega": omega}, _attrs("stochastic"))
    (table,) = group_tables(ds, "stochastic", "stochastic")
    assert table.name == "stochastic_omega"
    assert list(table.columns) == ["omega", "wave_spectrum", "tension_spectrum[0]",
                                   "tension_spectrum[1]"]
    assert table.units["omega"] == "rad/s" and table.units["tension_spectrum[1]"] == "N**2*s"
    names, units, rows = _read(write_table(table, tmp_path / "s.csv"))
    np.testing.assert_array_equal(rows[:, 3].astype(float), spectrum[:, 1])
    np.testing.assert_array_equal(rows[:, 0].astype(float), omega)


def test_offset_curves_one_table_per_heading():
    offsets = np.array([0.0, 5.0, 10.0])
    tension = np.arange(12.0).reshape(2, 3, 2)  # heading, offset, line
    ds = build_dataset("offset", {"fairlead_tension": (("heading", "offset", "line"), tension)},
                       {"heading": [0.0, 90.0], "offset": offsets, "line": ["l1", "l2"]},
                       _attrs("offset"))
    tables = group_tables(ds, "offset", "offset")
    assert [t.name for t in tables] == ["offset_heading0", "offset_heading1"]
    second = tables[1]
    assert list(second.columns) == ["offset", "fairlead_tension[l1]", "fairlead_tension[l2]"]
    np.testing.assert_array_equal(second.columns["fairlead_tension[l2]"], tension[1, :, 1])
    np.testing.assert_array_equal(second.columns["offset"], offsets)


def test_offset_case_tables(tmp_path):
    """cases/oc3_offset.yaml: per heading the offset curve, each dof column in its own unit
    (force or moment; the 6x6 stiffness entries force or moment per metre or radian)."""
    out = tmp_path / "out"
    run = CliRunner().invoke(cli, ["run", str(ROOT / "cases" / "oc3_offset.yaml"), "--out",
                                   str(out), "--no-plots", "-q"])
    assert run.exit_code == 0, run.output
    (results,) = out.glob("*/results.nc")
    _export(results, tmp_path / "csv")
    with netCDF4.Dataset(results) as root:
        group = root["offset"]
        offsets = np.asarray(group["offset"][:])
        force = np.asarray(group["restoring_force"][:])  # heading, offset, dof
        n_headings = len(group["heading"][:])
    for h in range(n_headings):
        names, units, rows = _read(tmp_path / "csv" / f"offset_heading{h}.csv")
        values = {n: rows[:, k].astype(float) for k, n in enumerate(names)}
        unit = dict(zip(names, units, strict=True))
        np.testing.assert_array_equal(values["offset"], offsets)
        np.testing.assert_array_equal(values["restoring_force[surge]"], force[h, :, 0])
        np.testing.assert_array_equal(values["restoring_force[yaw]"], force[h, :, 5])
        assert (unit["restoring_force[surge]"], unit["restoring_force[pitch]"]) == ("N", "N*m")
        assert (unit["stiffness[surge,surge]"], unit["stiffness[pitch,pitch]"],
                unit["stiffness[surge,pitch]"], unit["stiffness[pitch,surge]"]) == \
            ("N/m", "N*m/rad", "N/rad", "N")
