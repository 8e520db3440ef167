"""moorline convert: a MoorDyn deck becomes a case file that loads back into the same system;
and any case survives write -> load."""

from dataclasses import replace
from pathlib import Path

import pytest
from click.testing import CliRunner

from moorline.cli import cli
from moorline.io import load_case
from moorline.io.case_writer import write_case
from moorline.io.moordyn import read_moordyn

ROOT = Path(__file__).resolve().parents[1]


def _comparable(system):
    return replace(system, source=None, analyses=())


def test_convert_moordyn_deck_round_trips(tmp_path):
    deck = ROOT / "tests" / "data" / "moordyn" / "oc3.dat"
    out = tmp_path / "oc3.yaml"
    result = CliRunner().invoke(cli, ["convert", str(deck), "--out", str(out), "--quiet"])
    assert result.exit_code == 0, result.output
    assert _comparable(load_case(out)) == _comparable(read_moordyn(deck))


@pytest.mark.parametrize("case", ["oc3_line.yaml", "oc3_dynamics.yaml", "wang_box.yaml",
                                  "tuah_ex2.yaml"])
def test_case_files_survive_write_and_load(tmp_path, case):
    system = load_case(ROOT / "cases" / case)
    again = load_case(write_case(system, tmp_path / case))
    assert _comparable(again) == _comparable(system)
    assert again.analyses == system.analyses


BAD_DECKS = ROOT / "tests" / "data" / "bad" / "moordyn"


def test_deck_with_only_free_points_is_refused(tmp_path):
    """Nothing holds the lines: refused when read (statics would be singular), exit 2."""
    deck = BAD_DECKS / "only_free_points.dat"
    out = tmp_path / "x.yaml"
    result = CliRunner().invoke(cli, ["convert", str(deck), "--out", str(out), "--quiet"])
    assert result.exit_code == 2, result.output
    assert result.stderr.startswith(f"error: {deck}: the lines joining the points 'anchor1'")
    assert "held by no fixed or prescribed point" in result.stderr
    assert len(result.stderr.strip().splitlines()) == 1 and not out.exists()


@pytest.mark.parametrize(("deck", "field", "reason"), [
    ("negative_cd", "line_types.main.Cd", "must be >= 0, got -1.6"),
    ("negative_kbot", "environment.seabed.stiffness", "must be >= 0, got -3000000.0"),
    ("negative_volume", "points.fairlead2.volume", "must be >= 0, got -1.0"),
    ("zero_depth", "environment.depth", "must be > 0, got 0.0"),
])
def test_convert_refuses_what_would_not_load(tmp_path, deck, field, reason):
    """A deck with values a case may not hold: exit 2, one line naming the deck, the key of
    the case and the reason; nothing written."""
    path = BAD_DECKS / f"{deck}.dat"
    out = tmp_path / "x.yaml"
    result = CliRunner().invoke(cli, ["convert", str(path), "--out", str(out), "--quiet"])
    assert result.exit_code == 2, result.output
    assert result.stderr.strip() == (f"error: {path}: cannot be converted, the case would not "
                                     f"load (not written): {out}: {field}: {reason}")
    assert not out.exists()


@pytest.mark.parametrize(("deck", "message"), [
    ("nan_length", "line 19, LINES: UnstrLen must be a number, got nan"),
    ("huge_segments", "lines.line1.segments: must be at most 1e+12 (MAX_COUNT)"),
])
def test_convert_refuses_bad_numbers(tmp_path, deck, message):
    path = BAD_DECKS / f"{deck}.dat"
    out = tmp_path / "x.yaml"
    result = CliRunner().invoke(cli, ["convert", str(path), "--out", str(out), "--quiet"])
    assert result.exit_code == 2, result.output
    assert result.stderr.startswith(f"error: {path}: ") and message in result.stderr
    assert not out.exists()
