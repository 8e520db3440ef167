"""Bad case files through the command line: one line on stderr, exit code 2, no traceback."""

from __future__ import annotations

from pathlib import Path

import pytest
from click.testing import CliRunner

from moorline.cli import cli

BAD = Path(__file__).resolve().parent / "data" / "bad"
BAD_FILES = sorted(BAD.glob("*.yaml"))

# a few with the key path the message must name (the full list is in test_io.py)
WITH_FIELD = [
    ("negative_length", "lines.line1.length"),
    ("unknown_key_typo", "lines.line1.lenght"),
    ("position_component_text", "points.anchor.position[2]"),
    ("unknown_analysis_kind", "analyses[0].kind"),
    ("unknown_units_system", "units"),
    ("current_drag_with_bodies", "analyses[0].current_drag"),
    ("harmonic_with_bodies", "analyses[1].kind"),
    ("harmonic_viscoelastic", "analyses[1].kind"),
]


def _invoke(command: str, case: Path, tmp_path: Path):
    return CliRunner().invoke(cli, [command, str(case), "--out", str(tmp_path), "--quiet"])


@pytest.mark.parametrize("case", BAD_FILES, ids=[p.stem for p in BAD_FILES])
def test_bad_file_exits_2_with_one_line(case: Path, tmp_path: Path) -> None:
    result = _invoke("statics", case, tmp_path)
    assert result.exit_code == 2, result.output
    assert result.stdout == ""
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, result.stderr
    assert lines[0].startswith(f"error: {case}: ")
    assert "Traceback" not in result.stderr
    assert not any(tmp_path.iterdir())  # nothing written


@pytest.mark.parametrize(("name", "field"), WITH_FIELD)
@pytest.mark.parametrize("command", ["statics", "run"])
def test_message_names_file_and_key_path(command: str, name: str, field: str,
                                         tmp_path: Path) -> None:
    case = BAD / f"{name}.yaml"
    result = _invoke(command, case, tmp_path)
    assert result.exit_code == 2
    assert result.stderr.startswith(f"error: {case}: {field}: ")


def test_json_mode_keeps_stdout_clean(tmp_path: Path) -> None:
    case = BAD / "zero_EA.yaml"
    result = CliRunner().invoke(cli, ["statics", str(case), "--json", "--out", str(tmp_path)])
    assert result.exit_code == 2 and result.stdout == ""
    assert "line_types.chain.EA: must be > 0" in result.stderr


def test_missing_case_file_exits_2(tmp_path: Path) -> None:
    case = tmp_path / "nope.yaml"
    result = _invoke("run", case, tmp_path)
    assert result.exit_code == 2
    assert result.stderr.startswith(f"error: {case}: ")


@pytest.mark.parametrize("kind", ["device", "fifo", "directory"])
def test_non_regular_case_file_is_refused_at_once(kind: str, tmp_path: Path) -> None:
    """/dev/zero would be read until the memory runs out and a FIFO blocks until a writer
    comes: both are refused by their file type before any read."""
    import os

    if kind == "device":
        case = Path("/dev/zero")
    elif kind == "fifo":
        case = tmp_path / "pipe.yaml"
        os.mkfifo(case)
    else:
        case = tmp_path / "dir.yaml"
        case.mkdir()
    out = tmp_path / "out"
    result = _invoke("run", case, out)
    assert result.exit_code == 2, result.output
    if kind != "directory":  # click refuses a directory itself
        what = "a character device" if kind == "device" else "a named pipe"
        assert result.stderr.strip() == (f"error: {case}: cannot read the case file: not a "
                                         f"regular file ({what})")
    assert not out.exists()


def test_names_with_markup_and_mathtext_are_printed_literally(tmp_path: Path) -> None:
    """A case, a point and a line named like rich markup or matplotlib mathtext: the run
    succeeds and the tables show the names as written."""
    text = (BAD / "zero_EA.yaml").read_text(encoding="utf-8")
    text = (text.replace("name: bad-case", r"name: '[/]$\frac{$'")
            .replace("EA: 0", "EA: 5.0e8").replace("anchor", "'[bold]a[/bold]'")
            .replace("line1", r"'$\sqrt{$[/]'"))
    case = tmp_path / "names.yaml"
    case.write_text(text, encoding="utf-8")
    result = CliRunner().invoke(cli, ["statics", str(case), "--out", str(tmp_path / "out")])
    assert result.exit_code == 0, result.output
    assert "Traceback" not in result.stderr
    assert "[bold]a[/bold]" in result.stdout and r"$\sqrt{$[/]" in result.stdout
