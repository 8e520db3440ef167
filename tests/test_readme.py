"""The README's numbers are produced by the code they describe (issue 12, item 10).

The statics JSON example must equal ``moorline statics cases/oc3_line.yaml --json`` to the
digits it prints, the dynamics example ``moorline run cases/oc3_dynamics.yaml --json`` to its
three significant digits (the solver counters to 2 %: the compiled kernels' round-off may
move a step cut between machines), and the iteration count quoted in the overview the
statics' one. Keys the README shows must exist in the output (the output may hold more).
When the code changes these numbers, regenerate the README examples from these commands.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from click.testing import CliRunner

from moorline.cli import cli

ROOT = Path(__file__).resolve().parents[1]
README = (ROOT / "README.md").read_text(encoding="utf-8")
needs_cases = pytest.mark.skipif(not (ROOT / "cases" / "oc3_dynamics.yaml").is_file(),
                                 reason="the case files are not present")


def _json_block_after(marker: str) -> str:
    """The first ```json block after ``marker`` in the README."""
    start = README.index(marker)
    block = re.search(r"```json\n(.*?)```", README[start:], re.S)
    assert block, f"no JSON block after {marker!r}"
    return block.group(1)


def _compare(shown, actual, path: str, relative: float | None = None) -> None:
    """Every number shown equals the actual one to the digits printed (or ``relative``)."""
    if isinstance(shown, dict):
        assert isinstance(actual, dict), path
        for key, value in shown.items():
            assert key in actual, f"{path}.{key} is in the README but not in the output"
            _compare(value, actual[key], f"{path}.{key}", relative)
    elif isinstance(shown, list):
        assert isinstance(actual, list) and len(actual) == len(shown), path
        for i, (a, b) in enumerate(zip(shown, actual, strict=True)):
            _compare(a, b, f"{path}[{i}]", relative)
    elif isinstance(shown, bool) or isinstance(shown, str) or shown is None:
        assert shown == actual, f"{path}: README {shown!r}, output {actual!r}"
    else:
        tolerance = relative * abs(shown) if relative is not None else 0.0
        assert abs(actual - shown) <= tolerance + _half_last_digit(shown), \
            f"{path}: README {shown}, output {actual}"


def _half_last_digit(value: float) -> float:
    """Half a unit of the last digit of ``value`` as written in the README."""
    text = _WRITTEN.get(id(value))
    if text is None:
        return 0.0
    mantissa, _, exponent = text.lower().partition("e")
    decimals = len(mantissa.split(".")[1]) if "." in mantissa else 0
    return 0.5 * 10.0 ** (-decimals + (int(exponent) if exponent else 0))


_WRITTEN: dict[int, str] = {}


def _parse(block: str):
    """JSON with each float remembering how it was written."""
    def number(text: str) -> float:
        value = float(text)
        _WRITTEN[id(value)] = text
        return value

    return json.loads(block, parse_float=number, parse_int=lambda t: number(t))


@needs_cases
def test_statics_example_is_the_output(tmp_path: Path) -> None:
    result = CliRunner().invoke(cli, ["statics", str(ROOT / "cases" / "oc3_line.yaml"), "--json",
                                      "--quiet", "--out", str(tmp_path)])
    assert result.exit_code == 0, result.stderr
    actual = json.loads(result.stdout)
    shown = _parse(_json_block_after("`moorline statics CASE --json`:"))
    _compare(shown, actual, "statics")
    quoted = re.search(r"the OC3 line converges in (\d+) Newton iterations", README)
    assert quoted and int(quoted.group(1)) == actual["iterations"]


@needs_cases
def test_dynamics_example_is_the_output(tmp_path: Path) -> None:
    result = CliRunner().invoke(cli, ["run", str(ROOT / "cases" / "oc3_dynamics.yaml"),
                                      "--json", "--quiet", "--no-plots", "--out",
                                      str(tmp_path)])
    assert result.exit_code == 0, result.stderr
    dynamics = next(a for a in json.loads(result.stdout)["analyses"]
                    if a["kind"] == "dynamics")
    shown = _parse(_json_block_after("a\n  dynamics object is"))
    counters = shown.pop("counters")
    _compare(shown, dynamics, "dynamics")
    _compare(counters, dynamics["counters"], "dynamics.counters", relative=0.02)
