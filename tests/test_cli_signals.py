"""SIGINT and SIGTERM: a real signal to a real ``moorline run`` keeps a readable results file
(exit 130 or 143), a second signal during the clean-up does not change that, and the stream
is synced often enough that SIGKILL loses little."""

from __future__ import annotations

import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import netCDF4
import numpy as np
import pytest
import xarray as xr

from moorline.io import load_case, stream
from moorline.io.stream import HistoryWriter
from moorline.mesh import discretize
from moorline.signals import Terminated, handle_signals

ROOT = Path(__file__).resolve().parents[1]
OC3_DYNAMICS = ROOT / "cases" / "oc3_dynamics.yaml"

posix = pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")
needs_case = pytest.mark.skipif(not OC3_DYNAMICS.is_file(),
                                reason="cases/oc3_dynamics.yaml missing")


def _moorline_command() -> list[str]:
    script = Path(sys.executable).parent / "moorline"
    return [str(script)] if script.is_file() else [sys.executable, "-m", "moorline.cli"]


def _start_long_run(tmp_path: Path) -> tuple[subprocess.Popen, Path]:
    """The OC3 three-line run, long enough never to finish before the signal."""
    long_case = tmp_path / "oc3_long.yaml"
    text = OC3_DYNAMICS.read_text(encoding="utf-8")
    long_case.write_text(re.sub(r"duration: *[0-9.]+", "duration: 30000", text),
                         encoding="utf-8")
    # the writer takes no HDF5 file lock, so that this process can read the file meanwhile
    env = {**os.environ, "HDF5_USE_FILE_LOCKING": "FALSE"}
    proc = subprocess.Popen(
        [*_moorline_command(), "run", str(long_case), "--out", str(tmp_path), "--quiet"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=ROOT, env=env,
        # as in a terminal: SIGINT raises KeyboardInterrupt even if this runner ignores it
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    return proc, tmp_path / "oc3-dynamics" / "results.nc"


def _records(results: Path) -> int:
    """Dynamics records on disk (0 while the file or the group is not there yet)."""
    try:
        with netCDF4.Dataset(results) as root:
            return len(root["dynamics"]["time"]) if "dynamics" in root.groups else 0
    except (OSError, KeyError, IndexError, RuntimeError):
        return 0


def _wait_for_records(proc: subprocess.Popen, results: Path, n: int = 1) -> None:
    """Until the run has synced ``n`` dynamics records (no fixed sleep: robust under load)."""
    deadline = time.monotonic() + 120.0
    while _records(results) < n:
        assert proc.poll() is None, f"the run ended early: {proc.communicate()}"
        assert time.monotonic() < deadline, "no dynamics record within 120 s"
        time.sleep(0.1)


def _signal_and_wait(proc: subprocess.Popen, *signums: int) -> tuple[str, str]:
    try:
        for signum in signums:
            os.kill(proc.pid, signum)
        return proc.communicate(timeout=60)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.communicate()


def _check_kept(results: Path, word: str) -> None:
    """The results file is readable, says ``word`` and holds finite records."""
    with netCDF4.Dataset(results) as root:
        assert root.complete == 0 and root.status.startswith(f"{word} at t = ")
        assert root["dynamics"].complete == 0 and root["dynamics"].success == 0
        assert root["dynamics"].status == word
        assert root["dynamics"].message.startswith(f"{word}; ")
    with xr.open_dataset(results, group="dynamics") as dyn:
        assert dyn.sizes["time"] >= 1
        assert dyn["time"].values[-1] < 30000.0
        for name in ("position", "velocity", "tension", "end_force"):
            assert np.isfinite(dyn[name].values).all(), name
    with xr.open_dataset(results, group="statics") as statics:
        assert statics.attrs["converged"] == 1


@posix
@needs_case
@pytest.mark.parametrize(("signum", "word", "code"), [(signal.SIGINT, "interrupted", 130),
                                                      (signal.SIGTERM, "terminated", 143)])
def test_signal_keeps_a_readable_results_file(tmp_path: Path, signum: int, word: str,
                                              code: int) -> None:
    """Ctrl-C or SIGTERM (``timeout``, a batch scheduler) in the middle of the OC3 run:
    exit 130 / 143, one line, a readable file with what was computed."""
    proc, results = _start_long_run(tmp_path)
    _wait_for_records(proc, results)
    stdout, stderr = _signal_and_wait(proc, signum)
    assert proc.returncode == code, stderr
    lines = stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in stderr, stderr
    assert re.fullmatch(rf"{word} at t = \S+ s; results so far in {re.escape(str(results))}",
                        lines[0]), lines[0]
    assert stdout == ""
    _check_kept(results, word)


@posix
@needs_case
def test_second_sigint_during_the_clean_up_still_exits_130(tmp_path: Path) -> None:
    """Two Ctrl-C at once (the second arrives while the first one's clean-up runs): still
    exit 130 and a whole file, not death by the signal (-2)."""
    proc, results = _start_long_run(tmp_path)
    _wait_for_records(proc, results)
    _, stderr = _signal_and_wait(proc, signal.SIGINT, signal.SIGINT, signal.SIGTERM)
    assert proc.returncode == 130, stderr
    assert "Traceback" not in stderr
    _check_kept(results, "interrupted")


@pytest.fixture
def own_handlers():
    """The test process' SIGINT and SIGTERM handlers, put back after the test (after a
    signal :func:`handle_signals` leaves them ignoring further ones, as the CLI wants)."""
    saved = {s: signal.getsignal(s) for s in (signal.SIGINT, signal.SIGTERM)}
    yield
    for s, handler in saved.items():
        signal.signal(s, handler)


@posix
def test_first_signal_raises_and_later_ones_do_not_interrupt_the_clean_up(
        own_handlers) -> None:
    cleaned = False
    with pytest.raises(Terminated):
        with handle_signals():
            try:
                os.kill(os.getpid(), signal.SIGTERM)
                time.sleep(1.0)  # the handler raises at the next bytecode
            finally:
                os.kill(os.getpid(), signal.SIGINT)  # during the clean-up: noted, ignored
                time.sleep(0.05)
                cleaned = True
    assert cleaned
    signal.signal(signal.SIGINT, signal.default_int_handler)
    with pytest.raises(KeyboardInterrupt) as info:
        with handle_signals():
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(1.0)
    assert not isinstance(info.value, Terminated)


@needs_case
def test_stream_is_synced_within_one_second_of_simulated_time(tmp_path: Path) -> None:
    """Records every 0.3 s: a sync at the first record and then at least every
    SYNC_SIMULATED = 1 s of simulated time, so SIGKILL loses at most that."""
    mesh = discretize(load_case(OC3_DYNAMICS))
    n = mesh.n_nodes
    record = {"position": np.zeros((n, 3)), "velocity": np.zeros((n, 3)),
              "tension": np.zeros(len(mesh.elements)),
              "end_force": np.zeros((len(mesh.line_names), 2, 3)),
              "body_pose": np.zeros((0, 6)), "body_velocity": np.zeros((0, 6)),
              "body_mooring_force": np.zeros((0, 6)), "wave_elevation": 0.0}
    synced: list[float] = []

    class Counted:
        """The NetCDF file, its syncs noted."""

        def __init__(self, root: netCDF4.Dataset) -> None:
            self.real = root

        def __getattr__(self, name: str):
            return getattr(self.real, name)

        def sync(self) -> None:
            synced.append(writer.last_time)
            self.real.sync()

    times = 0.3 * np.arange(40)
    with HistoryWriter(tmp_path / "h.nc", mesh, {"case": "x", "units": "SI"}) as writer:
        writer.root = Counted(writer.root)
        for t in times:
            writer.append(float(t), record)
    assert synced[0] == 0.0
    for t in times:  # the records a SIGKILL right after t would lose span less than 1 s
        assert t - max(s for s in synced if s <= t) < stream.SYNC_SIMULATED
    with xr.open_dataset(tmp_path / "h.nc") as ds:
        assert ds.sizes["time"] == len(times)
