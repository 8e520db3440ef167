"""Helpers shared by the benchmarks: best-of timing, timed subprocesses, target verdicts.

The machine the benchmarks run on may be shared: every time printed is the smallest of a few
repetitions (the least disturbed one), and a subprocess is timed both on the wall clock and in
CPU seconds (user + system of the child and its threads, from ``os.wait4``), which another
process's load inflates much less.
"""

from __future__ import annotations

import functools
import math
import os
import subprocess
import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SRC = ROOT / "src"


def best_of(func: Callable[[], object], repeat: int = 3) -> float:
    """Smallest wall time of ``repeat`` calls [s]."""
    best = math.inf
    for _ in range(repeat):
        start = time.perf_counter()
        func()
        best = min(best, time.perf_counter() - start)
    return best


def best_cpu(func: Callable[[], object], repeat: int = 3) -> float:
    """Smallest CPU time of this process (all its threads) over ``repeat`` calls [s]."""
    best = math.inf
    for _ in range(repeat):
        start = time.process_time()
        func()
        best = min(best, time.process_time() - start)
    return best


@dataclass
class ProcessTime:
    """Wall and CPU seconds of one finished subprocess, and its exit code."""

    wall: float
    cpu: float
    returncode: int
    stderr: str = ""


def run_process(args: Sequence[str], cwd: Path | None = None,
                env: dict[str, str] | None = None) -> ProcessTime:
    """Run ``args`` to the end (stdout discarded, stderr kept); wall and CPU time."""
    start = time.perf_counter()
    proc = subprocess.Popen(list(args), cwd=cwd, env=env, stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE)
    assert proc.stderr is not None
    err = proc.stderr.read()
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - start
    proc.returncode = os.waitstatus_to_exitcode(status)
    return ProcessTime(wall, usage.ru_utime + usage.ru_stime, proc.returncode,
                       err.decode("utf-8", "replace"))


def best_process(args: Sequence[str], repeat: int, **kwargs: object) -> ProcessTime:
    """The run of ``args`` with the smallest CPU time out of ``repeat`` (wall: its smallest
    too); a failed run is returned at once."""
    best: ProcessTime | None = None
    wall = math.inf
    for _ in range(repeat):
        run = run_process(args, **kwargs)  # type: ignore[arg-type]
        if run.returncode != 0:
            return run
        wall = min(wall, run.wall)
        if best is None or run.cpu < best.cpu:
            best = run
    assert best is not None
    best.wall = wall
    return best


@functools.cache
def compile_sources() -> None:
    """Compile this checkout's moorline to bytecode (``__pycache__``), once per run.

    An installed package is compiled at installation; a checkout run with
    ``PYTHONDONTWRITEBYTECODE`` set (some shells and containers) would compile its ~150
    modules again in every timed child, about 0.1 s of CPU that MoorPy, MoorDyn and CableDyn
    (installed) do not pay.
    """
    import compileall

    compileall.compile_dir(str(SRC / "moorline"), quiet=1)


def python_env() -> dict[str, str]:
    """The environment for a child Python running this checkout's moorline (its sources
    compiled first, :func:`compile_sources`)."""
    compile_sources()
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(SRC), env.get("PYTHONPATH", "")]).rstrip(os.pathsep)
    return env


def moorline_command(*args: str) -> list[str]:
    """``python -m moorline ARGS`` with this interpreter."""
    return [sys.executable, "-m", "moorline", *args]


def verdict(value: float | None, target: float, at_most: bool = True) -> str:
    """PASS / MISS of ``value`` against ``target`` (``at_most``: value <= target)."""
    if value is None or not math.isfinite(value):
        return "n/a"
    ok = value <= target if at_most else value >= target
    return "PASS" if ok else "MISS"


def fmt(value: float | None, spec: str = ".3g") -> str:
    """A number, or n/a."""
    if value is None or not math.isfinite(value):
        return "n/a"
    return format(value, spec)
