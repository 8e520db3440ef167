"""The parameter-study driver (:mod:`moorline.sweep`) and ``moorline sweep``."""

from __future__ import annotations

import json
import math
import textwrap
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
import pytest
import xarray as xr
import yaml
from click.testing import CliRunner

from moorline.cli import cli
from moorline.errors import CaseError
from moorline.io import load_case
from moorline.sweep import (
    load_study,
    parse_quantity,
    run_one,
    run_study,
    set_path,
    study_cases,
    study_from_dict,
)

ROOT = Path(__file__).resolve().parents[1]
OC3_LINE = ROOT / "cases" / "oc3_line.yaml"
WANG_BUILDER = "moorline.verification.wang_dynamics:forced_equilibrium"


def _wang_study(**changes: Any) -> dict[str, Any]:
    """Two sag-to-span ratios of the Wang box, 8 s at dt 0.1 s (not steady: a smoke run)."""
    study = {
        "name": "tiny-wang",
        "base": {"builder": WANG_BUILDER,
                 "parameters": {"sag_to_span": "1/60", "inclination_deg": 50}},
        "variations": {"sag_to_span": ["1/45", "1/60"]},
        "dynamics": {"duration": 8.0, "dt": 0.1, "rayleigh_ratio": 0.03,
                     "rayleigh_frequencies": [1.6, 2.07]},
        "outputs": {"window": {"omega": 1.6, "periods": 1},
                    "quantities": {"surge": "amplitude box.x", "pitch": "amplitude box.ry",
                                   "max_tension": "max tension",
                                   "fairlead": "max fairlead C1",
                                   "draft": "static box.z"}},
    }
    study.update(changes)
    return study


def _oc3_study(directory: Path, **changes: Any) -> dict[str, Any]:
    """The OC3 line (10 segments) from its case file; statics only, two line lengths."""
    case = yaml.safe_load(OC3_LINE.read_text())
    case["lines"]["line1"]["segments"] = 10
    path = directory / "oc3_small.yaml"
    path.write_text(yaml.safe_dump(case))
    study = {
        "name": "oc3-length",
        "base": {"case": str(path)},
        "variations": {"lines.line1.length": [900.0, 905.0]},
        "outputs": {"quantities": {"fairlead_tension": "static fairlead line1",
                                   "max_tension": "static tension",
                                   "anchor_x": "static anchor.x"}},
    }
    study.update(changes)
    return study


@pytest.fixture(scope="module")
def wang_table() -> xr.Dataset:
    return run_study(_wang_study())


# ----------------------------------------------------------------------------- reading
def test_study_from_dict_reads_fractions_and_window():
    study = study_from_dict(_wang_study())
    assert study.base["sag_to_span"] == pytest.approx(1 / 60)
    assert study.variations["sag_to_span"] == pytest.approx((1 / 45, 1 / 60))
    assert study.period == pytest.approx(2 * math.pi / 1.6)
    assert study.dynamics["rayleigh_frequencies"] == (1.6, 2.07)
    assert [q.name for q in study.quantities] == ["surge", "pitch", "max_tension", "fairlead",
                                                  "draft"]
    assert study.quantities[1].unit == "rad" and study.quantities[2].unit == "N"


@pytest.mark.parametrize("change,field", [
    ({"name": ""}, "name"),
    ({"base": {"builder": WANG_BUILDER, "case": "x.yaml"}}, "base"),
    ({"base": {"builder": "no_colon"}}, "base.builder"),
    ({"variations": {"sag_to_span": []}}, "variations.sag_to_span"),
    ({"variations": {"sag_to_span": ["1/0"]}}, "variations.sag_to_span"),
    ({"combine": "all"}, "combine"),
    ({"dynamics": {"duration": 1.0, "timestep": 0.1}}, "dynamics"),
    ({"outputs": {"quantities": {"a": "median box.x"}}}, "outputs.quantities.a"),
    ({"outputs": {"quantities": {"a": "amplitude box.x"}}}, "outputs.window"),
    ({"dynamics": {}}, "outputs.quantities"),
])
def test_bad_studies_name_the_key(change, field):
    with pytest.raises(CaseError) as info:
        study_from_dict(_wang_study(**change), file="s.yaml")
    assert info.value.field == field and info.value.file == "s.yaml"


def test_parse_quantity():
    q = parse_quantity("t", "amplitude tension C2")
    assert (q.statistic, q.signal, q.target, q.unit) == ("amplitude", "tension", "C2", "N")
    q = parse_quantity("y", "mean fairlead.y")
    assert (q.signal, q.target, q.unit) == ("pose", "fairlead.y", "m")
    with pytest.raises(CaseError):
        parse_quantity("f", "max fairlead")


def test_cases_one_at_a_time_and_grid():
    study = study_from_dict(_wang_study(variations={"sag_to_span": ["1/45", "1/60"],
                                                    "inclination_deg": [44, 50]}))
    cases = study_cases(study)
    assert [s for s, _ in cases] == ["sag_to_span"] * 2 + ["inclination_deg"] * 2
    assert cases[1][1] == cases[3][1]  # the base set belongs to both series
    grid = study_cases(study_from_dict(_wang_study(
        variations={"sag_to_span": ["1/45", "1/60"], "inclination_deg": [44, 50, 54]},
        combine="grid")))
    assert len(grid) == 6 and {s for s, _ in grid} == {"grid"}


def test_set_path_replaces_frozen_fields():
    system = load_case(OC3_LINE)
    changed = set_path(system, "lines.line1.length", 905)
    assert changed.lines["line1"].length == 905.0
    assert isinstance(changed.lines["line1"].length, float)
    assert system.lines["line1"].length == pytest.approx(902.2)  # the original is untouched
    moved = set_path(system, "points.anchor.position.0", -850.0)
    assert moved.points["anchor"].position == (-850.0, 0, -320)
    for bad in ("lines.nope.length", "lines.line1.colour", "environment.depth.x"):
        with pytest.raises(CaseError):
            set_path(system, bad, 1.0)


# ----------------------------------------------------------------------------- running
def test_run_study_with_a_builder(wang_table):
    ds = wang_table
    assert ds.sizes["case"] == 2
    assert list(ds["status"].values) == ["ok", "ok"]
    assert list(ds["series"].values) == ["sag_to_span", "sag_to_span"]
    assert ds["sag_to_span"].values == pytest.approx([1 / 45, 1 / 60])
    assert np.all(ds["surge"].values > 0.05) and np.all(ds["pitch"].values > 0.0)
    # the largest tension includes the ends: at least the fairlead's, and close to it
    assert np.all(ds["max_tension"].values >= ds["fairlead"].values)
    assert ds["fairlead"].values == pytest.approx(ds["max_tension"].values, rel=0.02)
    # a tauter line: higher pretension; the draft is the static body z (box centre)
    assert ds["max_tension"].values[1] > ds["max_tension"].values[0]
    assert ds["draft"].values[1] == pytest.approx(2.5 - 0.896, abs=0.01)
    assert ds["draft"].values[0] > ds["draft"].values[1]  # slacker lines pull down less
    assert ds["surge"].attrs["units"] == "m" and ds.attrs["study"] == "tiny-wang"


def test_the_loop_is_separable():
    """run_one is a function of (study, parameters); run_study maps it over the distinct
    sets with any map-like callable (the shared base set runs once)."""
    study = study_from_dict(_wang_study(
        variations={"sag_to_span": ["1/60"], "inclination_deg": [50]},
        dynamics={"duration": 2.0, "dt": 0.1}))
    seen: list[dict[str, Any]] = []

    def mapper(function, cases):
        seen.extend(cases)
        return [function(c) for c in cases]

    table = run_study(study, mapper=mapper)
    assert len(seen) == 1 and table.sizes["case"] == 2
    direct = run_one(study, seen[0])
    assert direct["surge"] == pytest.approx(float(table["surge"].values[0]), rel=1e-12)
    assert direct["status"] == "ok"


def test_run_study_from_a_case_file(tmp_path):
    table = run_study(_oc3_study(tmp_path))
    assert list(table["status"].values) == ["ok", "ok"]
    tension = table["fairlead_tension"].values
    assert tension[1] < tension[0]  # a longer line hangs slacker
    # "static tension" is the largest tension, the ends included: here the fairlead's
    assert table["max_tension"].values == pytest.approx(tension, rel=1e-12)
    assert table["anchor_x"].values == pytest.approx([-853.87, -853.87])


def test_case_file_with_dynamics_and_point_signals(tmp_path):
    """Prescribed fairlead surge 5 m / 10 s: its x amplitude is 5 m; tensions respond."""
    case = yaml.safe_load(OC3_LINE.read_text())
    case["lines"]["line1"]["segments"] = 10
    case["line_types"]["chain"]["BA"] = -0.8
    case["points"]["fairlead"]["motion"] = {"kind": "harmonic", "amplitude": [5, 0, 0],
                                            "period": 10}
    path = tmp_path / "oc3_moving.yaml"
    path.write_text(yaml.safe_dump(case))
    table = run_study({
        "name": "oc3-moving", "base": {"case": str(path)},
        "variations": {"points.fairlead.motion.period": [10.0]},
        "dynamics": {"duration": 10.0, "dt": 0.05},
        "outputs": {"window": {"period": 10.0, "periods": 1},
                    "quantities": {"x": "amplitude fairlead.x",
                                   "t_amp": "amplitude fairlead line1",
                                   "t_mean": "mean tension line1"}}})
    assert table["x"].values[0] == pytest.approx(5.0, rel=2e-3)
    assert table["t_amp"].values[0] > 0.0 and table["t_mean"].values[0] > 0.0


def test_a_failing_case_is_recorded_not_raised(tmp_path, monkeypatch):
    module = tmp_path / "sweep_failing_builder.py"
    module.write_text(textwrap.dedent("""
        from moorline.verification.wang_dynamics import forced_equilibrium

        def build(sag_to_span, inclination_deg):
            if inclination_deg > 52:
                raise RuntimeError("no equilibrium here")
            return forced_equilibrium(sag_to_span, inclination_deg)
    """))
    monkeypatch.syspath_prepend(str(tmp_path))
    table = run_study(_wang_study(
        base={"builder": "sweep_failing_builder:build",
              "parameters": {"sag_to_span": "1/60", "inclination_deg": 50}},
        variations={"inclination_deg": [50, 54]}, dynamics={"duration": 2.0, "dt": 0.1}))
    assert table["status"].values[0] == "ok"
    assert "no equilibrium here" in table["status"].values[1]
    assert math.isnan(float(table["surge"].values[1]))


# ----------------------------------------------------------------------------- CLI
def test_cli_sweep_writes_table_and_plot(tmp_path):
    study = tmp_path / "tiny.yaml"
    study.write_text(yaml.safe_dump(_wang_study(
        variations={"sag_to_span": ["1/45", "1/60"], "inclination_deg": [50, 54]})))
    result = CliRunner().invoke(cli, ["sweep", str(study), "--out", str(tmp_path / "out"),
                                      "--json"])
    assert result.exit_code == 0, result.output
    directory = tmp_path / "out" / "tiny-wang"
    files = {p.name for p in directory.iterdir()}
    assert {"table.csv", "table.nc", "trends.png"} <= files
    csv = pd.read_csv(directory / "table.csv")
    assert len(csv) == 4 and set(csv["series"]) == {"sag_to_span", "inclination_deg"}
    assert {"surge", "max_tension", "status", "sag_to_span", "inclination_deg"} <= set(csv)
    with xr.open_dataset(directory / "table.nc") as nc:
        assert nc.sizes["case"] == 4
        assert nc["surge"].values == pytest.approx(csv["surge"].values)
        assert nc.attrs["study"] == "tiny-wang"
    assert (directory / "trends.png").stat().st_size > 10_000
    report = json.loads(result.stdout)
    assert report["study"] == "tiny-wang" and len(report["cases"]) == 4


def test_cli_sweep_grid_and_case_file(tmp_path):
    study = tmp_path / "oc3.yaml"
    study.write_text(yaml.safe_dump(_oc3_study(
        tmp_path, variations={"lines.line1.length": [900.0, 905.0],
                              "points.fairlead.position.2": [-70.0, -60.0]},
        combine="grid")))
    result = CliRunner().invoke(cli, ["sweep", str(study), "--out", str(tmp_path / "out"),
                                      "-q"])
    assert result.exit_code == 0, result.output
    assert (tmp_path / "out" / "oc3-length" / "trends.png").is_file()
    assert "oc3-length" in result.stdout


def test_cli_sweep_bad_input_and_failure(tmp_path, monkeypatch):
    bad = tmp_path / "bad.yaml"
    bad.write_text("name: x\nbase: {case: a.yaml, builder: m:f}\n")
    result = CliRunner().invoke(cli, ["sweep", str(bad), "--out", str(tmp_path)])
    assert result.exit_code == 2 and "base" in result.stderr
    missing = CliRunner().invoke(cli, ["sweep", str(tmp_path / "none.yaml")])
    assert missing.exit_code == 2
    module = tmp_path / "sweep_always_failing.py"
    module.write_text("def build(**kw):\n    raise RuntimeError('broken builder')\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    study = tmp_path / "failing.yaml"
    study.write_text(yaml.safe_dump(_wang_study(
        base={"builder": "sweep_always_failing:build", "parameters": {}},
        variations={})))
    result = CliRunner().invoke(cli, ["sweep", str(study), "--out", str(tmp_path / "o")])
    assert result.exit_code == 1 and "broken builder" in result.stderr
    assert (tmp_path / "o" / "tiny-wang" / "table.csv").is_file()


def test_load_study_resolves_the_case_relative_to_the_file(tmp_path):
    (tmp_path / "sub").mkdir()
    study = tmp_path / "sub" / "s.yaml"
    study.write_text(yaml.safe_dump({"name": "s", "base": {"case": "line.yaml"},
                                     "outputs": {"quantities": {"t": "static tension"}}}))
    assert load_study(study).case == tmp_path / "sub" / "line.yaml"


# ----------------------------------------------------------------------------- on Dask
def test_study_on_a_local_dask_cluster_equals_the_serial_run(tmp_path):
    """The OC3 length study on two Dask worker processes gives the serial table (the same
    cases, the same numbers, the same order)."""
    pytest.importorskip("distributed")
    from moorline.sweep import dask_mapper

    study = _oc3_study(tmp_path)
    serial = run_study(study)
    done = []
    mapper, close = dask_mapper(workers=2, progress=lambda k, n: done.append((k, n)))
    try:
        parallel = run_study(study, mapper=mapper)
    finally:
        close()
    assert done[-1] == (2, 2)
    for name in ("fairlead_tension", "max_tension", "anchor_x"):
        assert np.array_equal(parallel[name].values, serial[name].values)
    assert list(parallel["status"].values) == ["ok", "ok"]


def test_cli_sweep_with_workers_and_unreachable_scheduler(tmp_path, monkeypatch):
    pytest.importorskip("distributed")
    import moorline.sweep

    monkeypatch.setattr(moorline.sweep, "SCHEDULER_TIMEOUT", "2s")
    study = tmp_path / "study.yaml"
    study.write_text(yaml.safe_dump(_oc3_study(tmp_path)))
    result = CliRunner().invoke(cli, ["sweep", str(study), "--out", str(tmp_path / "out"),
                                      "--workers", "2", "--quiet", "--json"])
    assert result.exit_code == 0, result.output
    assert (tmp_path / "out" / "oc3-length" / "table.csv").is_file()
    bad = CliRunner().invoke(cli, ["sweep", str(study), "--out", str(tmp_path / "o2"),
                                   "--scheduler", "tcp://127.0.0.1:9", "--quiet"])
    assert bad.exit_code == 2
    assert "Dask scheduler" in bad.output and "Traceback" not in bad.output


# ----------------------------------------------------------------------------- issue 12
def test_static_max_tension_is_the_summary_one(tmp_path):
    """One meaning of "max tension": the largest of the element tensions and the end-point
    forces' magnitudes (the summary's ``max_tension``), here from the statics result's end
    forces computed apart."""
    from moorline.io.case import load_case as load
    from moorline.solvers.statics import solve_statics
    from moorline.summaries import statics_summary
    from moorline.sweep import set_path

    study = _oc3_study(tmp_path, outputs={"quantities": {
        "max_tension": "static tension", "max_line1": "static tension line1"}})
    table = run_study(study)
    assert table["max_tension"].attrs["long_name"].endswith("its end tensions included")
    base = load(Path(study["base"]["case"]))
    for k, length in enumerate((900.0, 905.0)):
        static = solve_statics(set_path(base, "lines.line1.length", length))
        ends = [float(np.linalg.norm(static.end_force("line1", e))) for e in "ab"]
        largest = max(*ends, float(static.tension.max()))
        assert largest == max(ends)  # on this catenary the fairlead pull is the largest
        assert float(table["max_tension"].values[k]) == pytest.approx(largest, rel=1e-12)
        assert float(table["max_line1"].values[k]) == pytest.approx(largest, rel=1e-12)
        summary = statics_summary(static, with_stiffness=False)
        assert summary["lines"]["line1"]["max_tension"] == pytest.approx(largest, rel=1e-12)


def test_dynamic_max_tension_includes_the_ends(wang_table):
    """``max tension`` over time is at least the largest end tension (``fairlead``)."""
    assert np.all(wang_table["max_tension"].values >= wang_table["fairlead"].values)
    assert "end tensions included" in wang_table["max_tension"].attrs["long_name"]


def test_partial_results_are_kept_as_cases_finish(tmp_path, monkeypatch):
    """The table on disk after each finished case (rewrites at most every ``TABLE_WALL``
    seconds: 0 here); with rewrites rarer than the cases, the table is written when the
    study ends; a study stopped after the first case keeps it (the other: ``not run``)."""
    import moorline.sweep

    study = _oc3_study(tmp_path, variations={"lines.line1.length": [900.0, 905.0, 910.0]})
    directory = tmp_path / "partial"
    seen: list[tuple[int, int, list[str]]] = []

    def progress(done: int, total: int, elapsed: float) -> None:
        csv = pd.read_csv(directory / "table.csv")
        seen.append((done, total, list(csv["status"])))
        assert elapsed >= 0.0

    monkeypatch.setattr(moorline.sweep, "TABLE_WALL", 0.0)
    full = run_study(study, directory=directory, progress=progress)
    assert seen == [(1, 3, ["ok", "not run", "not run"]), (2, 3, ["ok", "ok", "not run"]),
                    (3, 3, ["ok", "ok", "ok"])]
    assert full.attrs["complete"] == 1

    monkeypatch.setattr(moorline.sweep, "TABLE_WALL", 1e9)
    directory = tmp_path / "rare"
    written: list[bool] = []
    run_study(study, directory=directory,
              progress=lambda *_: written.append((directory / "table.csv").exists()))
    assert written == [False, False, False]
    assert list(pd.read_csv(directory / "table.csv")["status"]) == ["ok", "ok", "ok"]

    def stopped(function, cases):
        yield function(cases[0])
        raise KeyboardInterrupt

    directory = tmp_path / "stopped"
    with pytest.raises(KeyboardInterrupt):
        run_study(study, mapper=stopped, directory=directory)
    csv = pd.read_csv(directory / "table.csv")
    assert list(csv["status"]) == ["ok", "not run", "not run"]
    assert csv["fairlead_tension"][0] == pytest.approx(full["fairlead_tension"].values[0],
                                                        rel=1e-12)
    assert csv["fairlead_tension"][1:].isna().all()
    with xr.open_dataset(directory / "table.nc") as nc:
        assert nc.attrs["complete"] == 0 and nc.attrs["finished"] == 1
        assert list(nc["status"].values) == ["ok", "not run", "not run"]
    assert not list(directory.glob("*.part"))


def test_results_in_any_order_are_matched_to_their_case(tmp_path):
    """Dask yields the cases as they finish: the rows are matched by their parameters."""
    study = _oc3_study(tmp_path)

    def reversed_mapper(function, cases):
        return [function(c) for c in reversed(cases)]

    serial = run_study(study)
    backwards = run_study(study, mapper=reversed_mapper)
    np.testing.assert_array_equal(backwards["fairlead_tension"].values,
                                  serial["fairlead_tension"].values)


def test_eta_text():
    from moorline.sweep import eta_text

    assert eta_text(0, 4, 0.0) == "0 of 4 cases done"
    assert eta_text(2, 5, 10.0) == "2 of 5 cases done, 5 s per case, about 15 s left"
    assert eta_text(1, 3, 45.0) == "1 of 3 cases done, 45 s per case, about 1 min 30 s left"
    assert eta_text(3, 3, 9.0) == "3 of 3 cases done, 3 s per case"
    assert eta_text(1, 100, 7200.0).endswith("about 198 h 0 min left")


def test_cli_sweep_logs_the_eta_and_writes_a_complete_table(tmp_path):
    study = tmp_path / "oc3.yaml"
    study.write_text(yaml.safe_dump(_oc3_study(tmp_path)))
    result = CliRunner().invoke(cli, ["sweep", str(study), "--out", str(tmp_path / "out"),
                                      "-v"])
    assert result.exit_code == 0, result.output
    assert "1 of 2 cases done" in result.stderr and "left" in result.stderr
    assert "2 of 2 cases done" in result.stderr
    with xr.open_dataset(tmp_path / "out" / "oc3-length" / "table.nc") as nc:
        assert nc.attrs["complete"] == 1 and list(nc["status"].values) == ["ok", "ok"]


def test_set_path_indexes_tuples_from_zero_and_refuses_past_the_end():
    """``position.2`` is z, ``position.-1`` the last item; ``position.3`` is not there (an
    input error, not an IndexError)."""
    system = load_case(OC3_LINE)
    assert set_path(system, "points.anchor.position.2", -300.0).points["anchor"].position[2] \
        == -300.0
    assert set_path(system, "points.anchor.position.-1", -310.0).points["anchor"].position \
        == (-853.87, 0, -310.0)
    with pytest.raises(CaseError, match="cannot step into tuple"):
        set_path(system, "points.anchor.position.3", 1.0)
