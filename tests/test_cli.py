"""The ``moorline`` command line: outputs, the ``--json`` contract, exit codes and messages."""

from __future__ import annotations

import dataclasses
import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml
from click.testing import CliRunner, Result

from moorline import cli as cli_module
from moorline.cli import cli

ROOT = Path(__file__).resolve().parents[1]
OC3 = ROOT / "cases" / "oc3_line.yaml"
BAD = Path(__file__).resolve().parent / "data" / "bad"
BAD_FILES = sorted(BAD.glob("*.yaml")) if BAD.is_dir() else []
STATICS_FILES = ("results.nc", "summary.json", "summary.txt", "configuration_xz.png",
                 "configuration_3d.png")

needs_oc3 = pytest.mark.skipif(not OC3.is_file(), reason="cases/oc3_line.yaml not present")


def _invoke(*args: str) -> Result:
    return CliRunner().invoke(cli, [str(a) for a in args])


@pytest.fixture(scope="module")
def statics_run(tmp_path_factory: pytest.TempPathFactory) -> tuple[Result, Path]:
    """``moorline statics cases/oc3_line.yaml --json --plots`` once for the module."""
    if not OC3.is_file():
        pytest.skip("cases/oc3_line.yaml not present")
    out = tmp_path_factory.mktemp("out")
    return _invoke("statics", OC3, "--out", out, "--json", "--plots"), out


@needs_oc3
def test_statics_writes_results_summary_and_plots(statics_run: tuple[Result, Path]) -> None:
    result, out = statics_run
    assert result.exit_code == 0, result.stderr
    directory = out / "oc3-line"
    for name in STATICS_FILES:
        assert (directory / name).stat().st_size > 0, name
    assert json.loads((directory / "summary.json").read_text()) == json.loads(result.stdout)
    assert "line1" in (directory / "summary.txt").read_text()
    assert not (directory / "statics.nc").exists()
    with xr.open_dataset(directory / "results.nc", group="statics") as ds:
        assert ds.attrs["case"] == "oc3-line"
        assert ds["position"].dims == ("node", "xyz")
        assert ds["tension"].sizes["element"] == 20
        assert ds.attrs["seabed_z"] == pytest.approx(-320.0)
        assert list(ds["point_kind"].values) == ["fixed", "prescribed"]
        # max_tension includes the end tensions, as the JSON summary does
        line = json.loads(result.stdout)["lines"]["line1"]
        assert float(ds["max_tension"].sel(line="line1")) == pytest.approx(line["max_tension"])
        assert float(ds["max_tension"].sel(line="line1")) >= line["end_b"]["tension"] * (1 - 1e-12)


@needs_oc3
def test_statics_json_contract(statics_run: tuple[Result, Path]) -> None:
    result, _ = statics_run
    summary = json.loads(result.stdout)  # stdout holds exactly one JSON document
    assert {"case", "converged", "iterations", "lines", "points"} <= set(summary)
    assert summary["case"] == "oc3-line"
    assert summary["converged"] is True
    assert isinstance(summary["iterations"], int) and summary["iterations"] > 0

    line = summary["lines"]["line1"]
    assert {"end_a", "end_b", "max_tension", "seabed_length"} <= set(line)
    for end in ("end_a", "end_b"):
        force = np.array(line[end]["force"])
        assert force.shape == (3,)
        assert line[end]["tension"] == pytest.approx(np.linalg.norm(force), rel=1e-12)
        assert line["max_tension"] >= line[end]["tension"] * (1 - 1e-12)
    assert line["end_b"]["force"][2] < 0  # the line pulls the fairlead down
    assert line["end_b"]["force"][0] < 0  # ... and towards the anchor (at -x)
    assert line["seabed_length"] > 0

    points = summary["points"]
    assert points["anchor"]["position"] == pytest.approx([-853.87, 0.0, -320.0])
    assert "stiffness" not in points["anchor"]  # fixed point: no stiffness
    K = np.array(points["fairlead"]["stiffness"])
    assert K.shape == (3, 3)
    # the case's sag-corrected elements have no potential (their tangent is not symmetric,
    # moorline.physics.sag): K is symmetric to their O(h^2) error (3.4e-5 of K11 at 20
    # elements), not to round-off
    assert np.allclose(K, K.T, rtol=0, atol=1e-4 * np.abs(K).max())
    assert np.all(np.diag(K) > 0)


@needs_oc3
def test_run_writes_statics_outputs_and_prints_tables(tmp_path: Path) -> None:
    result = _invoke("run", OC3, "--out", tmp_path, "--quiet")
    assert result.exit_code == 0, result.stderr
    for name in STATICS_FILES:
        assert (tmp_path / "oc3-line" / name).is_file(), name
    assert "converged" in result.stdout and "fairlead" in result.stdout
    assert result.stderr == ""  # --quiet: no status lines

    summary = json.loads((tmp_path / "oc3-line" / "summary.json").read_text())
    assert summary["converged"] is True
    assert [a["kind"] for a in summary["analyses"]] == ["statics"]


@needs_oc3
def test_plots_only_when_asked_for_with_json(tmp_path: Path) -> None:
    """``statics --json`` writes the numbers only (no plots unless --plots); ``run
    --no-plots`` too; plain ``statics`` draws them."""
    pngs = ("configuration_xz.png", "configuration_3d.png")
    for args, drawn in ((("statics", "--json"), False), (("run", "--no-plots"), False),
                        (("statics",), True)):
        out = tmp_path / "-".join(args)
        result = _invoke(*args[:1], OC3, "--out", out, "--quiet", *args[1:])
        assert result.exit_code == 0, result.stderr
        folder = out / "oc3-line"
        assert (folder / "results.nc").is_file() and (folder / "summary.json").is_file()
        assert all((folder / p).is_file() == drawn for p in pngs), (args, drawn)


@needs_oc3
def test_run_json_prints_one_object(tmp_path: Path) -> None:
    result = _invoke("run", OC3, "--out", tmp_path, "--json")
    assert result.exit_code == 0, result.stderr
    summary = json.loads(result.stdout)
    assert summary["case"] == "oc3-line" and summary["converged"] is True
    assert summary["analyses"][0]["lines"]["line1"]["end_b"]["force"][2] < 0


@needs_oc3
def test_run_rejects_an_analysis_kind_without_runner(tmp_path: Path,
                                                     monkeypatch: pytest.MonkeyPatch) -> None:
    from moorline import io as case_io

    @dataclasses.dataclass(frozen=True)
    class Modes:
        kind: str = "modes"

    system = case_io.load_case(OC3)
    odd = dataclasses.replace(system, analyses=(*system.analyses, Modes()))
    monkeypatch.setattr(case_io, "load_case", lambda path: odd)
    result = _invoke("run", OC3, "--out", tmp_path)
    assert result.exit_code == 2
    assert "'modes'" in result.stderr and "supported: statics, dynamics" in result.stderr
    assert "Traceback" not in result.stderr
    assert not any(tmp_path.iterdir())  # checked before anything runs


@needs_oc3
def test_plot_replots_a_saved_result(statics_run: tuple[Result, Path], tmp_path: Path) -> None:
    _, out = statics_run
    result = _invoke("plot", out / "oc3-line" / "results.nc", "--out", tmp_path, "--quiet")
    assert result.exit_code == 0, result.stderr
    assert (tmp_path / "configuration_xz.png").stat().st_size > 0
    assert (tmp_path / "configuration_3d.png").stat().st_size > 0


@needs_oc3
def test_plot_rejects_a_file_that_is_not_netcdf(statics_run: tuple[Result, Path]) -> None:
    _, out = statics_run
    path = out / "oc3-line" / "summary.json"
    result = _invoke("plot", path)
    assert result.exit_code == 2
    assert result.stderr.startswith(f"error: {path}: ")
    assert "Traceback" not in result.stderr


@needs_oc3
def test_plot_reads_a_single_statics_dataset(tmp_path: Path) -> None:
    """A file of one statics dataset without groups (``ds.to_netcdf``) plots too."""
    from moorline import io as case_io
    from moorline.solvers.statics import solve_statics

    path = tmp_path / "statics.nc"
    solve_statics(case_io.load_case(OC3)).to_xarray().to_netcdf(path)
    result = _invoke("plot", path, "--quiet")
    assert result.exit_code == 0, result.stderr
    assert (tmp_path / "configuration_xz.png").stat().st_size > 0


def test_plot_rejects_netcdf_without_results(tmp_path: Path) -> None:
    path = tmp_path / "other.nc"
    xr.Dataset({"a": ("x", [1.0, 2.0])}).to_netcdf(path)
    result = _invoke("plot", path)
    assert result.exit_code == 2
    assert result.stderr.strip() == (f"error: {path}: not a moorline results file "
                                     "(no statics or dynamics group)")


@needs_oc3
def test_failed_solve_exits_1_with_message(tmp_path: Path) -> None:
    case = yaml.safe_load(OC3.read_text())
    case["analyses"] = [{"kind": "statics", "method": "relaxation", "max_iterations": 1,
                         "tolerance": 1.0e-12}]
    path = tmp_path / "hopeless.yaml"
    path.write_text(yaml.safe_dump(case))
    result = _invoke("statics", path, "--out", tmp_path / "out", "--json", "--quiet")
    assert result.exit_code == 1
    assert json.loads(result.stdout)["converged"] is False
    message = result.stderr.strip().splitlines()
    assert len(message) == 1 and message[0].startswith(f"error: {path}: statics failed: ")
    assert "did not converge" in message[0]
    path = tmp_path / "out" / "oc3-line" / "results.nc"  # written for diagnosis
    with xr.open_dataset(path, group="statics") as ds:
        assert ds.attrs["converged"] == 0


def test_verify_json_is_a_list_of_rows() -> None:
    # two quick cases with exact references (pin-jointed string, taut-string modes): every row
    # passes; the slow cases run in `make verify` (tests/test_verification.py)
    result = _invoke("verify", "--case", "tuah-ex1", "--case", "modes-string", "--json",
                     "--quiet")
    rows = json.loads(result.stdout)
    assert isinstance(rows, list) and {r["case"] for r in rows} == {"tuah-ex1", "modes-string"}
    for row in rows:
        assert row["status"] == "pass", row
        assert row["reference"]["kind"] == "exact"
        assert row["error"] <= row["tolerance"]
    assert result.exit_code == 0


def test_verify_unknown_case_exits_2_listing_known_ones() -> None:
    result = _invoke("verify", "--case", "no-such-case")
    assert result.exit_code == 2
    assert result.stdout == ""
    assert "unknown verification case 'no-such-case'; known cases:" in result.stderr


@pytest.mark.parametrize("command", ["statics", "run", "plot"])
def test_missing_file_exits_2_with_one_line(command: str, tmp_path: Path) -> None:
    path = tmp_path / "missing.yaml"
    result = _invoke(command, path, "--quiet")
    assert result.exit_code == 2
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"error: {path}: ")
    assert result.stdout == ""


@pytest.mark.skipif(not BAD_FILES, reason="tests/data/bad/ not present")
@pytest.mark.parametrize("case", BAD_FILES, ids=[p.stem for p in BAD_FILES])
def test_bad_case_file_exits_2_naming_the_file(case: Path, tmp_path: Path) -> None:
    result = _invoke("run", case, "--out", tmp_path, "--json")
    assert result.exit_code == 2, result.output
    assert "Traceback" not in result.stderr
    assert str(case) in result.stderr
    assert 1 <= len(result.stderr.strip().splitlines()) <= 2
    assert result.stdout == ""


def test_console_script_gives_no_traceback(tmp_path: Path) -> None:
    """A real process (not CliRunner): exit code and stderr as a user sees them."""
    path = tmp_path / "absent.yaml"
    proc = subprocess.run([sys.executable, "-m", "moorline.cli", "statics", str(path)],
                          capture_output=True, text=True, check=False)
    assert proc.returncode == 2
    assert proc.stderr.startswith(f"error: {path}: ")
    assert "Traceback" not in proc.stderr


@needs_oc3
def test_plot_configuration_without_seabed_attribute(tmp_path: Path) -> None:
    from moorline import io as case_io
    from moorline.plot import plot_configuration
    from moorline.solvers.statics import solve_statics

    ds = solve_statics(case_io.load_case(OC3)).to_xarray()
    ds.attrs.pop("seabed_z", None)
    ds.attrs["units"] = "US"
    plot_configuration(ds, tmp_path / "a" / "xz.png", tmp_path / "b" / "3d.png")
    assert (tmp_path / "a" / "xz.png").stat().st_size > 0
    assert (tmp_path / "b" / "3d.png").stat().st_size > 0


def test_summary_json_is_strict() -> None:
    from moorline.io.writers import jsonable, summary_json

    data = {"a": np.float64(math.nan), "b": [np.inf, np.int64(3)], "c": np.eye(2)}
    assert jsonable(data) == {"a": None, "b": [None, 3], "c": [[1.0, 0.0], [0.0, 1.0]]}
    assert json.loads(summary_json(data))["b"] == [None, 3]


def test_cli_module_exposes_main() -> None:
    assert callable(cli_module.main)
    from moorline.analyses import KINDS

    assert {"statics", "dynamics"} <= set(KINDS)
