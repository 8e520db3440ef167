"""The line catalogue (moorline.catalog): values against the published formulas, overrides in
case files, errors, US units and ``moorline catalog``."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from click.testing import CliRunner

from moorline.catalog import catalog_names, families, line_properties
from moorline.cli import cli
from moorline.io import load_case_text

#: 1 slug in kg and 1 lbf in N, from the exact definitions (lb = 0.45359237 kg, ft = 0.3048 m,
#: g_n = 9.80665 m/s^2): slug = lbf s^2 / ft
LBF = 0.45359237 * 9.80665
SLUG = LBF / 0.3048
FOOT = 0.3048

CASE = """\
name: catalogue-test
units: {units}
environment: {{depth: 100}}
line_types:
  rope: {{{line_type}}}
points:
  anchor: {{kind: fixed, position: [0, 0, -100]}}
  top: {{kind: fixed, position: [{span}, 0, 0]}}
lines:
  line: {{type: rope, length: {length}, segments: 10, end_a: anchor, end_b: top}}
"""


def _case(line_type: str, units: str = "SI") -> str:
    span, length = (150, 250) if units == "SI" else (492, 820)
    return CASE.format(units=units, line_type=line_type, span=span, length=length)


def _write(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "case.yaml"
    path.write_text(text, encoding="utf-8")
    return path


def test_r3_studless_120mm_matches_the_published_formulas() -> None:
    """R3 studless chain of 120 mm nominal diameter against the formulas as printed:
    mass 19.9 d^2 te/m and axial stiffness 0.854e8 d^2 kN, d in m (Orcina, OrcaFlex help
    'Chain'), MBL 0.0223 d^2 (44 - 0.08 d) kN, d in mm (DNV-OS-E302, grade R3)."""
    d = 0.120
    mass = 19.9 * d**2 * 1000.0          # kg/m: 286.56
    ea = 0.854e8 * d**2 * 1000.0         # N: 1.22976e9
    mbl = 0.0223 * 120.0**2 * (44.0 - 0.08 * 120.0) * 1000.0  # N: 1.10465e7
    values = line_properties("chain_studless_r3", d).values
    assert values["mass_per_length"] == pytest.approx(mass, rel=5e-3)
    assert values["EA"] == pytest.approx(ea, rel=5e-3)
    assert values["MBL"] == pytest.approx(mbl, rel=5e-3)
    assert values["diameter"] == pytest.approx(1.80 * d, rel=1e-12)  # OrcaFlex: OD = 1.80 d


@pytest.mark.parametrize(("grade", "c"), [("r3", 0.0223), ("r3s", 0.0249), ("r4", 0.0274),
                                          ("r4s", 0.0304), ("r5", 0.0320)])
def test_chain_grades_follow_the_grade_factors(grade: str, c: float) -> None:
    """DNV-OS-E302's grade factors c of MBL = c d^2 (44 - 0.08 d) kN, studless and studlink
    alike (76 mm: a size between the ends of the range)."""
    expected = c * 76.0**2 * (44.0 - 0.08 * 76.0) * 1000.0
    for family in ("chain_studless", "chain_studlink"):
        assert line_properties(f"{family}_{grade}", 0.076).values["MBL"] == \
            pytest.approx(expected, rel=1e-12)


def test_chain_against_moorpy() -> None:
    """Other code: MoorPy's R4 studless chain (its catalogue fit, MoorProps_default.yaml) at
    120 mm. Mass (20.0 vs 19.9 d^2 t/m) and MBL (its fit's rounded 1.21e9 d^2) agree within
    1 %; EA within 1 % too, although MoorPy's cubic term is 1000 times smaller than the
    DNV-OS-E301 R4 modulus it cites would give (see the report)."""
    helpers = pytest.importorskip("moorpy.helpers")
    mp = helpers.getLineProps(120.0, "chain", source="default")
    ours = line_properties("chain_studless_r4", 0.12).values
    assert ours["mass_per_length"] == pytest.approx(mp["m"], rel=1e-2)
    assert ours["MBL"] == pytest.approx(mp["MBL"], rel=1e-2)
    assert ours["EA"] == pytest.approx(mp["EA"], rel=1e-2)
    assert ours["diameter"] == pytest.approx(mp["d_vol"], rel=1e-12)


def test_fibre_ropes_have_static_and_dynamic_stiffness() -> None:
    """Fibre ropes carry EA (static, K_rs MBL) and EA_dynamic ((alpha + beta L_m) MBL at the
    data file's L_m); steel has no EA_dynamic."""
    for name in ("polyester", "nylon", "hmpe"):
        props = line_properties(name, 0.16)
        assert props.values["EA_dynamic"] > 0.0 and props.mean_load_percent == 20.0
    poly = line_properties("polyester", 0.16).values
    assert poly["EA"] == pytest.approx(14.0 * poly["MBL"], rel=1e-12)
    assert poly["EA_dynamic"] == pytest.approx((11.6 + 0.40 * 20.0) * poly["MBL"], rel=1e-12)
    assert "EA_dynamic" not in line_properties("wire_six_strand", 0.08).values


def test_every_value_names_its_source() -> None:
    for name in catalog_names():
        low, high = families()[name.rsplit("_r", 1)[0] if name.startswith("chain") else name][
            "diameter_range_mm"]
        props = line_properties(name, 0.5e-3 * (low + high))
        assert set(props.sources) == set(props.values)
        assert all(len(s) > 20 for s in props.sources.values())


@pytest.mark.parametrize("name", ["chain_studless_r4", "chain_studlink_r3", "wire_six_strand",
                                  "wire_spiral_strand", "polyester", "nylon", "hmpe"])
def test_case_keys_override_the_catalogue(name: str) -> None:
    """A key written next to catalog/nominal_diameter wins; the others are the catalogue's."""
    text = _case(f"catalog: {name}, nominal_diameter: 0.1, mass_per_length: 12.5, Cd: 0.7, "
                 "MBL: 2.0e6")
    lt = load_case_text(text).line_types["rope"]
    props = line_properties(name, 0.1).values
    assert (lt.mass_per_length, lt.Cd, lt.MBL) == (12.5, 0.7, 2.0e6)
    assert lt.EA == props["EA"] and lt.diameter == props["diameter"]
    assert (lt.Ct, lt.Ca, lt.Cat) == (props["Ct"], props["Ca"], props["Cat"])
    assert lt.EA_dynamic == props.get("EA_dynamic")
    assert lt.catalog == name and lt.nominal_diameter == 0.1


def test_us_case_gets_the_catalogue_in_us_units() -> None:
    """units: US: the nominal diameter in ft (or with a unit) and every value converted from
    SI with the exact foot, pound and g_n."""
    si = line_properties("chain_studless_r3", 0.12).values
    for diameter in ("'120 mm'", f"{0.12 / FOOT!r}"):
        lt = load_case_text(_case(f"catalog: chain_studless_r3, nominal_diameter: {diameter}",
                                  "US")).line_types["rope"]
        assert lt.mass_per_length == pytest.approx(si["mass_per_length"] * FOOT / SLUG, rel=1e-9)
        assert lt.EA == pytest.approx(si["EA"] / LBF, rel=1e-9)
        assert lt.MBL == pytest.approx(si["MBL"] / LBF, rel=1e-9)
        assert lt.diameter == pytest.approx(si["diameter"] / FOOT, rel=1e-9)
        assert lt.nominal_diameter == pytest.approx(0.12 / FOOT, rel=1e-12)
        assert lt.Cd == si["Cd"]
    lt = load_case_text(_case("diameter: 0.3, mass_per_length: 1.0, EA: 1.0e8, MBL: '1 MN'",
                              "US")).line_types["rope"]
    assert lt.MBL == pytest.approx(1.0e6 / LBF, rel=1e-9)


@pytest.mark.parametrize(("line_type", "field", "words"), [
    ("catalog: chain_studles_r3, nominal_diameter: 0.1", "catalog",
     "unknown catalogue line 'chain_studles_r3' (did you mean 'chain_studless_r3'?)"),
    ("catalog: chain_studless_r3, nominal_diameter: '500 mm'", "nominal_diameter",
     "nominal diameter 500 mm is outside the range of chain_studless in the catalogue, 20 to "
     "220 mm (lines.yaml)"),
    ("catalog: polyester", "nominal_diameter", "a catalogue line type needs nominal_diameter"),
    ("nominal_diameter: 0.1, diameter: 0.1, mass_per_length: 1, EA: 1e8", "nominal_diameter",
     "nominal_diameter needs a catalog entry"),
    ("diameter: 0.1, EA: 1.0e8", "mass_per_length", "missing required key 'mass_per_length'"),
    ("catalog: hmpe, nominal_diameter: 0.1, MBL: -1", "MBL", "must be > 0, got -1"),
])
def test_bad_catalogue_input_is_one_line_naming_file_and_key(tmp_path: Path, line_type: str,
                                                              field: str, words: str) -> None:
    path = _write(tmp_path, _case(line_type))
    result = CliRunner().invoke(cli, ["statics", str(path), "--out", str(tmp_path), "-q"])
    assert result.exit_code == 2, result.output
    assert result.stderr.startswith(f"error: {path}: line_types.rope.{field}: ")
    assert words in result.stderr
    assert len(result.stderr.strip().splitlines()) == 1


def test_catalog_command_lists_and_prints() -> None:
    runner = CliRunner()
    listing = runner.invoke(cli, ["catalog", "--json"])
    assert listing.exit_code == 0
    assert set(json.loads(listing.stdout)) == {"chain_studless", "chain_studlink",
                                              "wire_six_strand", "wire_spiral_strand",
                                              "polyester", "nylon", "hmpe"}
    shown = runner.invoke(cli, ["catalog", "chain_studless_r3", "120", "--json"])
    assert shown.exit_code == 0, shown.output
    data = json.loads(shown.stdout)
    assert data["values"]["MBL"] == pytest.approx(0.0223 * 120**2 * 34.4 * 1e3, rel=1e-12)
    assert "DNV-OS-E302" in data["sources"]["MBL"]
    us = json.loads(runner.invoke(cli, ["catalog", "chain_studless_r3", "120 mm", "--units",
                                        "US", "--json"]).stdout)
    assert us["values"]["MBL"] == pytest.approx(data["values"]["MBL"] / LBF, rel=1e-9)
    assert us["units_of"]["MBL"] == "lbf"
    table = runner.invoke(cli, ["catalog", "polyester", "160"])
    assert table.exit_code == 0 and "EA_dynamic" in table.stdout
    assert "Orcina" in runner.invoke(cli, ["catalog", "chain_studlink_r4", "100"]).stdout
    for args in (["catalog", "polyestr", "160"], ["catalog", "polyester", "20"],
                 ["catalog", "polyester"], ["catalog", "polyester", "abc"]):
        bad = runner.invoke(cli, args)
        assert bad.exit_code == 2, args
        assert bad.stderr.startswith("error: catalog polyest")
        assert len(bad.stderr.strip().splitlines()) == 1
    assert math.isfinite(data["nominal_diameter_m"])
