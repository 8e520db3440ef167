"""``moorline run`` with a dynamics analysis: the results file, plots, ``--json`` and failure
(signals: test_cli_signals.py)."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import netCDF4
import numpy as np
import pytest
import xarray as xr
import yaml
from click.testing import CliRunner, Result

from moorline.cli import cli

ROOT = Path(__file__).resolve().parents[1]
OC3_LINE = ROOT / "cases" / "oc3_line.yaml"
OC3_DYNAMICS = ROOT / "cases" / "oc3_dynamics.yaml"
PLOTS = ("configuration_xz.png", "configuration_3d.png", "tension_history.png",
         "motion_history.png")

pytestmark = pytest.mark.skipif(not OC3_LINE.is_file(), reason="cases/oc3_line.yaml missing")


def _invoke(*args: Any) -> Result:
    return CliRunner().invoke(cli, [str(a) for a in args])


def _small_case(directory: Path, **dynamics: Any) -> Path:
    """The OC3 line, 10 segments, fairlead surging 5 m / 10 s, statics then 5 s of dynamics."""
    case = yaml.safe_load(OC3_LINE.read_text())
    case["line_types"]["chain"]["BA"] = -0.8
    case["lines"]["line1"]["segments"] = 10
    case["lines"]["line1"]["element"] = "straight"  # the case's sag correction is for statics
    case["points"]["fairlead"]["motion"] = {"kind": "harmonic", "amplitude": [5, 0, 0],
                                            "period": 10}
    case["analyses"] = [{"kind": "statics", "method": "newton"},
                        {"kind": "dynamics", "duration": 5.0, "dt": 0.05, **dynamics}]
    case["output"] = {"every": 0.25}
    path = directory / "small_dynamics.yaml"
    path.write_text(yaml.safe_dump(case))
    return path


@pytest.fixture(scope="module")
def dynamics_run(tmp_path_factory: pytest.TempPathFactory) -> tuple[Result, Path]:
    """``moorline run <small case> --json`` once for the module (progress bar on)."""
    tmp = tmp_path_factory.mktemp("dyn")
    result = _invoke("run", _small_case(tmp), "--out", tmp / "out", "--json")
    return result, tmp / "out" / "oc3-line"


def test_run_writes_one_results_file_with_both_groups(dynamics_run: tuple[Result, Path]) -> None:
    result, directory = dynamics_run
    assert result.exit_code == 0, result.stderr
    assert sorted(p.name for p in directory.glob("*.nc")) == ["results.nc"]
    for name in (*PLOTS, "summary.json", "summary.txt"):
        assert (directory / name).stat().st_size > 0, name
    with netCDF4.Dataset(directory / "results.nc") as root:
        assert set(root.groups) == {"statics", "dynamics"}
        assert root.analyses == "statics,dynamics"
        assert root.complete == 1 and root.status == "complete"
        assert root["dynamics"].complete == 1
    with xr.open_dataset(directory / "results.nc", group="statics") as statics:
        assert statics["position"].dims == ("node", "xyz")
        assert statics.attrs["seabed_z"] == pytest.approx(-320.0)
        assert list(statics["point_kind"].values) == ["fixed", "prescribed"]
    with xr.open_dataset(directory / "results.nc", group="dynamics") as dyn:
        assert dyn.sizes["time"] == 21  # 0 to 5 s every 0.25 s
        assert dyn["time"].values[-1] == pytest.approx(5.0)
        assert dyn["position"].dims == ("time", "node", "xyz")
        assert np.isfinite(dyn["end_force"].values).all()
        assert list(dyn["point_kind"].values) == ["fixed", "prescribed"]
        fairlead = dyn["position"].values[:, int(dyn["point_node"].values[1])]
        assert fairlead[:, 0].max() == pytest.approx(-5.2 + 5.0, abs=0.05)
    assert "dynamics" in (directory / "summary.txt").read_text()


def test_run_json_contract_for_dynamics(dynamics_run: tuple[Result, Path]) -> None:
    result, directory = dynamics_run
    summary = json.loads(result.stdout)  # progress went to stderr: stdout is one document
    assert json.loads((directory / "summary.json").read_text()) == summary
    assert {"case", "converged", "units", "analyses"} <= set(summary)
    assert summary["converged"] is True and summary["units"] == "SI"
    statics, dynamics = summary["analyses"]
    assert statics["kind"] == "statics" and "end_b" in statics["lines"]["line1"]
    assert dynamics["kind"] == "dynamics" and dynamics["converged"] is True
    for end in ("end_a", "end_b"):
        stats = dynamics["lines"]["line1"][end]
        assert set(stats) == {"max", "min", "mean", "std"}
        assert stats["min"] <= stats["mean"] <= stats["max"] and stats["std"] >= 0
    # the run starts from the statics of the same run
    start = statics["lines"]["line1"]["end_a"]["tension"]
    assert dynamics["lines"]["line1"]["end_a"]["min"] <= start * 1.01
    fairlead = dynamics["points"]["fairlead"]
    assert fairlead["kind"] == "prescribed"
    assert fairlead["max"][0] == pytest.approx(-5.2 + 5.0, abs=0.05)  # 5 s: half a period
    assert fairlead["min"][0] == pytest.approx(-5.2, abs=1e-9)
    assert dynamics["points"]["anchor"]["min"] == pytest.approx([-853.87, 0.0, -320.0])
    counters = dynamics["counters"]
    assert {"steps", "iterations", "factorizations", "step_cuts"} <= set(counters)
    assert counters["steps"] == 100 and counters["iterations"] >= counters["steps"]


def test_plot_replots_statics_and_histories(dynamics_run: tuple[Result, Path],
                                            tmp_path: Path) -> None:
    _, directory = dynamics_run
    result = _invoke("plot", directory / "results.nc", "--out", tmp_path, "--quiet")
    assert result.exit_code == 0, result.stderr
    for name in PLOTS:
        assert (tmp_path / name).stat().st_size > 0, name


def test_dynamics_failure_exits_1_and_keeps_the_records(tmp_path: Path) -> None:
    case = _small_case(tmp_path, dt=2.5, max_iterations=1, max_step_cuts=0, tolerance=1e-12)
    result = _invoke("run", case, "--out", tmp_path / "out", "--quiet", "--json")
    assert result.exit_code == 1
    message = result.stderr.strip().splitlines()
    assert len(message) == 1, result.stderr
    assert message[0].startswith(f"error: {case}: dynamics failed: ")
    assert "at t = " in message[0] and "line1" in message[0]
    summary = json.loads(result.stdout)
    assert summary["converged"] is False
    assert summary["analyses"][1]["converged"] is False
    path = tmp_path / "out" / "oc3-line" / "results.nc"
    with netCDF4.Dataset(path) as root:
        assert root.complete == 0 and root.status.startswith("dynamics failed")
        group = root["dynamics"]
        assert group.complete == 0 and group.success == 0 and group.status == "failed"
        assert "at t = " in group.message
    with xr.open_dataset(path, group="dynamics") as dyn:
        assert dyn.sizes["time"] >= 1  # the initial state
        assert np.isfinite(dyn["position"].values).all()
