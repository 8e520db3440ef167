"""Bad case files through the command line: one line on stderr, exit code 2, no traceback."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time
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
    ("motion_period_below_two_steps", "points.fairlead.motion.period"),
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


CHILD = """
import json, signal, sys, tempfile
from pathlib import Path
from click.testing import CliRunner
from moorline.cli import cli

def overrun(signum, frame):
    raise SystemExit(f"more than 5 s of CPU time on {path}")

signal.signal(signal.SIGPROF, overrun)
out, tmp = [], Path(tempfile.mkdtemp())
for path in sys.argv[1:]:
    command = "convert" if path.endswith(".dat") else "statics"
    target = tmp / (Path(path).stem + (".yaml" if command == "convert" else ""))
    signal.setitimer(signal.ITIMER_PROF, 5.0)
    result = CliRunner().invoke(cli, [command, path, "--out", str(target), "--quiet"])
    signal.setitimer(signal.ITIMER_PROF, 0.0)
    out.append([path, result.exit_code, result.stderr])
# peak resident memory of this process image (VmHWM: the kernel's ru_maxrss would also count
# the pytest process this child was forked from, whatever its size)
hwm = next(int(line.split()[1]) for line in open("/proc/self/status")
           if line.startswith("VmHWM:"))
print(json.dumps({"results": out, "peak_kb": hwm}))
"""


@pytest.mark.skipif(sys.platform != "linux", reason="os.wait4, FIFOs and /dev/zero")
def test_every_bad_input_exits_2_within_5_s_and_500_mb(tmp_path: Path) -> None:
    """Every bad file (case files, MoorDyn decks, /dev/zero, a FIFO), one after the other in a
    child process: exit 2 with one line naming the file, each within 5 s of CPU time (a
    profiling timer, blind to the load of other processes) and the child within 500 MB."""
    fifo = tmp_path / "pipe.yaml"
    os.mkfifo(fifo)
    inputs = [*map(str, BAD_FILES), *map(str, sorted((BAD / "moordyn").glob("*.dat"))),
              "/dev/zero", str(fifo)]
    out = tmp_path / "child.json"
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(p for p in sys.path if p)}
    with open(out, "w") as stdout:
        proc = subprocess.Popen([sys.executable, "-c", CHILD, *inputs], stdout=stdout, env=env)
    try:
        # a hang guard only: a blocking read uses no CPU time, so the child's timer misses it
        deadline = time.monotonic() + 300.0
        while (done := os.wait4(proc.pid, os.WNOHANG))[0] == 0:
            assert time.monotonic() < deadline, "the bad inputs hang"
            time.sleep(0.2)
    finally:
        if proc.poll() is None and proc.returncode is None:
            proc.kill()
    _, status, _ = done
    assert os.waitstatus_to_exitcode(status) == 0, out.read_text()
    report = json.loads(out.read_text())
    assert report["peak_kb"] * 1024 <= 500 * 1024**2, report["peak_kb"]
    results = report["results"]
    assert [r[0] for r in results] == inputs
    for path, code, stderr in results:
        assert code == 2, (path, stderr)
        lines = stderr.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith(f"error: {path}: "), (path, stderr)


@pytest.mark.parametrize("command", ["plot", "sweep", "convert", "bem"])
def test_other_commands_refuse_a_device_at_once(command: str, tmp_path: Path) -> None:
    args = [command, "/dev/zero", "--out", str(tmp_path / "o")]
    if command == "bem":
        args += ["--body", "hull", "--omega", "1"]
    result = CliRunner().invoke(cli, args)
    assert result.exit_code == 2, result.output
    assert result.stderr.startswith("error: /dev/zero: cannot read ")
    assert result.stderr.strip().endswith("not a regular file (a character device)")
