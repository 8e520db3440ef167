"""Design checks (moorline.design): the factors of API RP 2SK and DNV-OS-E301, the largest
tension of statics and stochastic runs, lines without MBL, and the summary tables."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from click.testing import CliRunner

from moorline.cli import cli
from moorline.design import line_check, most_probable_maximum
from moorline.model import DesignSettings

# (standard, condition, analysis, class) -> expected design utilization of a line with
# MBL 10, T_max 5, T_mean 3, by hand from the factors the standards print:
# API RP 2SK 3rd ed. Table 2: SF 2.00 / 1.67 intact, 1.43 / 1.25 damaged (u = T_max SF / MBL);
# DNV-OS-E301 Ch.2 Sec.2: (gamma_mean T_mean + gamma_dyn (T_max - T_mean)) / (0.95 MBL),
# ULS class 1: 1.10, 1.50; class 2: 1.40, 2.10; ALS class 1: 1.00, 1.10
CHECKS = [
    ("API-RP-2SK", "intact", "quasi-static", 1, 5 * 2.00 / 10),
    ("API-RP-2SK", "intact", "dynamic", 1, 5 * 1.67 / 10),
    ("API-RP-2SK", "damaged", "quasi-static", 1, 5 * 1.43 / 10),
    ("API-RP-2SK", "damaged", "dynamic", 1, 5 * 1.25 / 10),
    ("DNV-OS-E301", "intact", "dynamic", 1, (1.10 * 3 + 1.50 * 2) / 9.5),
    ("DNV-OS-E301", "intact", "dynamic", 2, (1.40 * 3 + 2.10 * 2) / 9.5),
    ("DNV-OS-E301", "damaged", "dynamic", 1, (1.00 * 3 + 1.10 * 2) / 9.5),
]


@pytest.mark.parametrize(("standard", "condition", "analysis", "cls", "expected"), CHECKS)
def test_factors_of_the_standards(standard: str, condition: str, analysis: str, cls: int,
                                  expected: float) -> None:
    settings = DesignSettings(standard=standard, condition=condition, consequence_class=cls)
    check = line_check(settings, analysis, 10.0, 5.0, 3.0)
    assert check["design_utilization"] == pytest.approx(expected, rel=1e-12)
    assert check["utilization"] == 0.5 and check["safety_factor"] == 2.0
    assert check["passed"] is (expected <= 1.0)


def test_a_line_over_its_limit_fails_and_one_without_mbl_is_not_checked() -> None:
    settings = DesignSettings()
    assert line_check(settings, "dynamic", 10.0, 6.5, 6.5)["passed"] is False  # SF 1.54 < 1.67
    none = line_check(settings, "dynamic", None, 6.5, 6.5)
    assert none["passed"] is None and "not checked" in none["note"]


def test_most_probable_maximum_of_a_rayleigh_storm() -> None:
    """sigma sqrt(2 ln N), N = 3 h / T_z, T_z = 2 pi sqrt(m0 / m2): e.g. T_z = 10 s over
    10800 s gives N = 1080 cycles and 3.736 sigma (Longuet-Higgins 1952)."""
    m0 = 4.0
    m2 = m0 * (2 * math.pi / 10.0) ** 2
    assert most_probable_maximum(2.0, m0, m2, 10800.0) == pytest.approx(
        2.0 * math.sqrt(2 * math.log(1080.0)), rel=1e-12)
    assert most_probable_maximum(2.0, m0, m2, 5.0) == 0.0  # less than a cycle


CASE = """\
name: design-test
units: SI
environment:
  depth: 50
  waves: {{kind: random, spectrum: jonswap, height: 3, period: 8, gamma: 3.3, seed: 2,
          record_length: 256, n_frequencies: 100}}
line_types:
  rope: {{diameter: 0.1, mass_per_length: 20, EA: 2.0e7, Cd: 1.2, Ct: 0.01, Ca: 1.0{mbl}}}
points:
  anchor: {{kind: fixed, position: [0, 0, -50]}}
  top: {{kind: fixed, position: [10, 0, -5]}}
lines:
  riser: {{type: rope, length: 46.05, segments: 20, end_a: anchor, end_b: top}}
analyses:
  - {{kind: statics}}
  - {{kind: stochastic}}
{design}"""


def _run(tmp_path: Path, mbl: str, design: str) -> tuple[dict, Path]:
    path = tmp_path / "case.yaml"
    path.write_text(CASE.format(mbl=mbl, design=design), encoding="utf-8")
    result = CliRunner().invoke(cli, ["run", str(path), "--out", str(tmp_path), "--json",
                                      "--no-plots", "-q"])
    assert result.exit_code == 0, result.output
    return json.loads(result.stdout), tmp_path / "design-test"


def test_statics_and_stochastic_checks_in_summary_and_report(tmp_path: Path) -> None:
    """DNV-OS-E301 class 2: statics by gamma_qs T_max / (0.95 MBL), the stochastic run by its
    static tension plus the most probable maximum over 3 hours, recomputed here from the
    stored tension spectra; the JSON, the text summary and the NetCDF attribute agree."""
    summary, out = _run(tmp_path, ", MBL: '200 kN'",
                        "design: {standard: DNV-OS-E301, consequence_class: 2}\n")
    statics, stochastic = summary["analyses"]
    mbl = 200e3
    line = statics["design"]["lines"]["riser"]
    t_max = statics["lines"]["riser"]["max_tension"]
    assert line["max_tension"] == t_max and line["MBL"] == mbl
    assert line["design_utilization"] == pytest.approx(2.50 * t_max / (0.95 * mbl), rel=1e-12)
    assert statics["design"]["analysis"] == "quasi-static"

    ds = xr.open_dataset(out / "results.nc", group="stochastic")
    static = xr.open_dataset(out / "results.nc", group="statics")["tension"].values
    spectrum, omega = ds["tension_spectrum"].values, ds["omega"].values
    dw = omega[1] - omega[0]
    m0, m2 = spectrum.sum(axis=0) * dw, (omega[:, None] ** 2 * spectrum).sum(axis=0) * dw
    cycles = 10800.0 / (2 * np.pi * np.sqrt(m0 / m2))
    top = static + np.sqrt(m0) * np.sqrt(2 * np.log(cycles))
    e = int(np.argmax(top))
    check = stochastic["design"]["lines"]["riser"]
    assert check["max_tension"] == pytest.approx(top[e], rel=1e-6)
    assert check["mean_tension"] == pytest.approx(static[e], rel=1e-9)
    expected = (1.40 * static[e] + 2.10 * (top[e] - static[e])) / (0.95 * mbl)
    assert check["design_utilization"] == pytest.approx(expected, rel=1e-6)
    assert stochastic["design"]["analysis"] == "dynamic"
    assert ds.attrs["line_MBL"] == pytest.approx(mbl)

    text = (out / "summary.txt").read_text()
    assert text.count("Design checks (DNV-OS-E301") == 2
    verdict = "pass" if check["passed"] else "FAIL"
    assert f"{check['design_utilization']:.4g} │ {verdict}" in text


def test_lines_without_mbl_say_so(tmp_path: Path) -> None:
    summary, out = _run(tmp_path, "", "")
    design = summary["analyses"][0]["design"]
    assert design["passed"] is None and design["unchecked"] == ["riser"]
    assert design["standard"] == "API-RP-2SK" and "no design settings" in design["note"]
    assert "no MBL for this line type: not checked" in design["lines"]["riser"]["note"]
    assert "no MBL: not checked" in (out / "summary.txt").read_text()


def test_extremes_design_tension_is_the_largest_mpm_of_each_line() -> None:
    """The extremes analysis' design tension: the largest MPM of the line's ends and elements
    (hand-built result), the mean at the end with the larger MPM."""
    import types

    import numpy as np

    from moorline.design import extremes_extremes

    result = types.SimpleNamespace(
        line_names=("a", "b"), element_line=np.array([0, 0, 1]),
        mpm=np.array([[1.0, 5.0], [7.0, 2.0]]), element_mpm=np.array([6.0, 4.0, 3.0]),
        mean=np.array([[0.5, 4.0], [6.0, 1.5]]))
    assert extremes_extremes(result) == {"a": (6.0, 4.0), "b": (7.0, 6.0)}
