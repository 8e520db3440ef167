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

LONG = 1.0e7  # s, the duration of the long run

posix = pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")
needs_case = pytest.mark.skipif(not OC3_DYNAMICS.is_file(),
                                reason="cases/oc3_dynamics.yaml missing")


def _moorline_command() -> list[str]:
    script = Path(sys.executable).parent / "moorline"
    return [str(script)] if script.is_file() else [sys.executable, "-m", "moorline.cli"]


def _start_long_run(tmp_path: Path) -> tuple[subprocess.Popen, Path]:
    """The OC3 three-line run, long enough never to finish before the signal: 1e7 s with a
    record every 100 s, so that the records kept in memory stay few (the compiled time loop
    finished a 90,000 s run with a record every 0.25 s before a clean clone's poller read its
    first block)."""
    long_case = tmp_path / "oc3_long.yaml"
    text = OC3_DYNAMICS.read_text(encoding="utf-8")
    text = re.sub(r"duration: *[0-9.]+", f"duration: {LONG:.0f}", text)
    text = re.sub(r"output: *\{every: *[0-9.]+\}", "output: {every: 100.0}", text)
    assert "every: 100.0" in text
    long_case.write_text(text, encoding="utf-8")
    # the writer takes no HDF5 file lock, so that this process can read the file meanwhile
    env = {**os.environ, "HDF5_USE_FILE_LOCKING": "FALSE"}
    proc = subprocess.Popen(
        [*_moorline_command(), "run", str(long_case), "--out", str(tmp_path), "--quiet"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=ROOT, env=env,
        # as in a terminal: SIGINT raises KeyboardInterrupt even if this runner ignores it
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    return proc, tmp_path / "oc3-dynamics" / "results.nc"


def _records(results: Path) -> int:
    """Dynamics records on disk (0 while the file or the group is not there yet).

    Read from a copy under a new name each time: HDF5 keeps a file it once failed to open
    half-way (the writer mid-block) in its list of open files, and later opens of the same
    file in this process see that stale state: the poller then read no record for minutes
    while the run wrote thousands (seen on clean clones). A copy is a new file each time, and
    the results file itself is first opened when the run has ended."""
    try:
        copy = results.with_name(f"poll-{time.monotonic_ns()}.nc")
        copy.write_bytes(results.read_bytes())
    except OSError:
        return 0
    try:
        with netCDF4.Dataset(copy) as root:
            return len(root["dynamics"]["time"]) if "dynamics" in root.groups else 0
    except (OSError, KeyError, IndexError, RuntimeError):
        return 0
    finally:
        copy.unlink(missing_ok=True)


def _wait_for_records(proc: subprocess.Popen, results: Path, n: int = 1) -> None:
    """Until the run has synced ``n`` dynamics records (no fixed sleep: robust under load).

    The deadline only guards against a hang: on a fresh clone the subprocess compiles the
    numba kernels first (about 40 s on a busy 2-core machine, minutes under heavy load)."""
    deadline = time.monotonic() + 900.0
    while _records(results) < n:
        assert proc.poll() is None, f"the run ended early: {proc.communicate()}"
        assert time.monotonic() < deadline, "no dynamics record within 900 s"
        time.sleep(0.1)


def _signal_and_wait(proc: subprocess.Popen, *signums: int) -> tuple[str, str]:
    try:
        for signum in signums:
            os.kill(proc.pid, signum)
        return proc.communicate(timeout=300)
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
        assert dyn["time"].values[-1] < LONG
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


@posix
@needs_case
def test_sigkill_leaves_a_readable_file_complete_up_to_the_last_block(tmp_path: Path) -> None:
    """SIGKILL (no clean-up at all) right after a block reached the disk: the file opens, the
    statics group is whole, and the dynamics group holds at least every record on disk
    before the kill, finite and in order, with the envelope of exactly those records and
    the status it had while running. The kill is sent just after a block was seen (blocks
    are SYNC_WALL = 1 s apart), not in the middle of one: HDF5 does not promise a readable
    file after a kill during a write."""
    proc, results = _start_long_run(tmp_path)
    _wait_for_records(proc, results)
    before = _records(results)
    deadline = time.monotonic() + 300.0
    while _records(results) == before:  # the next block: written about 1 s after the first
        assert proc.poll() is None, f"the run ended early: {proc.communicate()}"
        assert time.monotonic() < deadline, "no second block within 300 s"
        time.sleep(0.02)
    seen = _records(results)
    proc.kill()
    proc.communicate(timeout=60)
    assert proc.returncode == -signal.SIGKILL
    with netCDF4.Dataset(results) as root:
        assert root.complete == 0 and root.status == "running"
        group = root["dynamics"]
        assert group.status == "running" and group.complete == 0
        times = group["time"][:]
        assert len(times) >= seen > before >= 1
        assert np.all(np.diff(times) > 0)
        for name in ("position", "velocity", "tension", "end_force"):
            assert np.isfinite(group[name][:]).all(), name
        tension = np.asarray(group["tension"][:])
        start = float(group.envelope_start)
        assert group.envelope_records == int(np.sum(times >= start))
        if group.envelope_records:
            np.testing.assert_array_equal(group["tension_max"][:],
                                          tension[times >= start].max(axis=0))
    with xr.open_dataset(results, group="statics") as statics:
        assert statics.attrs["converged"] == 1


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
def test_stream_is_written_within_one_second_of_wall_time(tmp_path: Path,
                                                          monkeypatch: pytest.MonkeyPatch) -> None:
    """Records buffered, written in blocks: at the first record, then whenever SYNC_WALL = 1 s
    of wall time has passed (a clock advancing 0.3 s a record here) or the block is full, so a
    SIGKILL loses at most the last second of wall time; what is on disk is readable and in
    order while the run goes on."""
    mesh = discretize(load_case(OC3_DYNAMICS))
    n = mesh.n_nodes

    def record(t: float) -> dict[str, np.ndarray]:
        return {"position": np.full((n, 3), t), "velocity": np.zeros((n, 3)),
                "tension": np.full(len(mesh.elements), 2 * t),
                "end_force": np.zeros((len(mesh.line_names), 2, 3)),
                "body_pose": np.zeros((0, 6)), "body_velocity": np.zeros((0, 6)),
                "body_mooring_force": np.zeros((0, 6)), "wave_elevation": 0.0}

    clock = [0.0]
    monkeypatch.setattr(stream.time, "monotonic", lambda: clock[0])
    on_disk: list[int] = []
    times = 0.05 * np.arange(40)
    with HistoryWriter(tmp_path / "h.nc", mesh, {"case": "x", "units": "SI"}) as writer:
        for k, t in enumerate(times):
            clock[0] = 0.3 * k
            writer.append(float(t), record(float(t)))
            on_disk.append(writer.written)
            # what a SIGKILL now would leave: no record waiting longer than SYNC_WALL
            assert 0.3 * (k - writer.written) <= stream.SYNC_WALL + 1e-12
            if k == 20:  # records waiting: the disk holds the blocks written, in order
                with netCDF4.Dataset(tmp_path / "h.nc", "r") as mid:
                    kept = mid["time"][:]
                    assert len(kept) == writer.written < writer.count
                    np.testing.assert_array_equal(kept, times[:len(kept)])
    assert on_disk[0] == 1  # the first record at once
    with xr.open_dataset(tmp_path / "h.nc") as ds:
        np.testing.assert_array_equal(ds["time"], times)
        np.testing.assert_array_equal(ds["tension"][:, 0], 2 * times)


def _zero_record(mesh) -> dict:
    """A dynamics record of zeros for ``mesh`` (no bodies)."""
    n = mesh.n_nodes
    return {"position": np.zeros((n, 3)), "velocity": np.zeros((n, 3)),
            "tension": np.zeros(len(mesh.elements)),
            "end_force": np.zeros((len(mesh.line_names), 2, 3)),
            "body_pose": np.zeros((0, 6)), "body_velocity": np.zeros((0, 6)),
            "body_mooring_force": np.zeros((0, 6)), "wave_elevation": 0.0}


@needs_case
def test_records_further_apart_than_the_sync_interval_are_written_at_once(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Slow steps (2 s of wall time between records): every record is on disk when the next
    step starts; at a steady 0.4 s interval a block is written when the next record would
    find the oldest one waiting 1 s or more (every second record)."""
    mesh = discretize(load_case(OC3_DYNAMICS))
    record = _zero_record(mesh)
    clock = [0.0]
    monkeypatch.setattr(stream.time, "monotonic", lambda: clock[0])
    for step, expected in ((2.0, list(range(1, 8))), (0.4, [1, 1, 3, 3, 5, 5, 7])):
        clock[0] = 0.0
        with HistoryWriter(tmp_path / f"h{step}.nc", mesh, {"case": "x", "units": "SI"}) as w:
            written = []
            for k in range(7):
                clock[0] += step
                w.append(0.1 * k, record)
                written.append(w.written)
        assert written == expected, step


@needs_case
def test_stream_writes_full_blocks_without_waiting(tmp_path: Path) -> None:
    """A frozen clock: blocks are written when full (block_records), and the rest on close."""
    mesh = discretize(load_case(OC3_DYNAMICS))
    record = _zero_record(mesh)
    written = []
    with HistoryWriter(tmp_path / "h.nc", mesh, {"case": "x", "units": "SI"},
                       block_records=8) as writer:
        for k in range(30):
            writer.append(0.1 * k, record)
            written.append(writer.written)
    assert written[:10] == [1, 1, 1, 1, 1, 1, 1, 1, 9, 9]
    with xr.open_dataset(tmp_path / "h.nc") as ds:
        assert ds.sizes["time"] == 30
        assert ds.attrs["status"] == "completed"
