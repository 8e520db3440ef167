"""The stream's block buffer: records are copied as they come (the caller may reuse its
arrays), and a block longer than the buffer is written as the buffer fills."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from moorline.io import load_case, stream
from moorline.io.stream import HistoryWriter
from moorline.mesh import discretize

OC3_DYNAMICS = Path(__file__).resolve().parents[1] / "cases" / "oc3_dynamics.yaml"

needs_case = pytest.mark.skipif(not OC3_DYNAMICS.is_file(),
                                reason="cases/oc3_dynamics.yaml missing")


@needs_case
def test_records_are_copied_and_a_long_block_is_written_as_the_buffer_fills(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """A buffer of 4 records, a frozen clock: a block of 10 records is written 4 + 4 as it
    comes (2 wait), the caller's arrays are overwritten after each append, and the file
    holds the values given, in order."""
    mesh = discretize(load_case(OC3_DYNAMICS))
    n, m, lines = mesh.n_nodes, mesh.n_elements, len(mesh.line_names)
    monkeypatch.setattr(stream.time, "monotonic", lambda: 0.0)
    times = 0.1 * np.arange(13)
    given = {"position": np.arange(13 * n * 3, dtype=float).reshape(13, n, 3),
             "velocity": -np.arange(13 * n * 3, dtype=float).reshape(13, n, 3),
             "tension": 1.0e5 + np.arange(13 * m, dtype=float).reshape(13, m),
             "end_force": np.tile([3.0, 0.0, 4.0], (13, lines, 2, 1)),
             "wave_elevation": np.linspace(-1.0, 1.0, 13)}
    written = []
    with HistoryWriter(tmp_path / "h.nc", mesh, {"case": "x", "units": "SI"},
                       block_records=4) as writer:
        for first, last in ((0, 10), (10, 11), (11, 13)):
            block = {key: value[first:last].copy() for key, value in given.items()}
            block |= {key: np.zeros((last - first, 0, 6))
                      for key in ("body_pose", "body_velocity", "body_mooring_force")}
            writer.append_block(times[first:last].copy(), block)
            written.append(writer.written)
            for value in block.values():
                value.fill(np.nan)  # the caller reuses its arrays
    assert written == [8, 8, 12]
    with xr.open_dataset(tmp_path / "h.nc") as ds:
        np.testing.assert_array_equal(ds["time"], times)
        for key, value in given.items():
            np.testing.assert_array_equal(ds[key], value, err_msg=key)
        np.testing.assert_array_equal(ds["fairlead_tension"], np.full((13, lines), 5.0))
        assert ds.attrs["status"] == "completed"


@needs_case
def test_owned_blocks_are_written_as_given_and_in_order(tmp_path: Path,
                                                         monkeypatch: pytest.MonkeyPatch) -> None:
    """Owned blocks (the compiled loop's): a long one is held, not copied (the writer's
    pending records share its memory), short ones between are copied; a buffer limit cuts
    a held block; the file and the envelope are those of the same records appended as
    copies, record by record."""
    mesh = discretize(load_case(OC3_DYNAMICS))
    n, m, lines = mesh.n_nodes, mesh.n_elements, len(mesh.line_names)
    monkeypatch.setattr(stream.time, "monotonic", lambda: 0.0)
    total = 3 + 2 * stream.HOLD_RECORDS + 5 + stream.HOLD_RECORDS
    rng = np.random.default_rng(3)
    times = 0.05 * np.arange(total)
    given = {"position": rng.normal(size=(total, n, 3)),
             "velocity": rng.normal(size=(total, n, 3)),
             "tension": 1.0e5 * rng.random((total, m)),
             "end_force": rng.normal(size=(total, lines, 2, 3)),
             "wave_elevation": rng.normal(size=total)}
    zeros = {key: np.zeros((total, 0, 6))
             for key in ("body_pose", "body_velocity", "body_mooring_force")}
    cuts = (0, 3, 3 + 2 * stream.HOLD_RECORDS, total - stream.HOLD_RECORDS, total)
    attrs = {"case": "x", "units": "SI"}
    limit = 3 + 2 * stream.HOLD_RECORDS + 2  # the second held block crosses it
    with HistoryWriter(tmp_path / "owned.nc", mesh, attrs, block_records=limit) as writer:
        for first, last in zip(cuts[:-1], cuts[1:], strict=True):
            block = {key: value[first:last] for key, value in (given | zeros).items()}
            writer.append_block(times[first:last], block, owned=True)
            if last - first >= stream.HOLD_RECORDS and writer._pending:
                assert np.shares_memory(writer._pending[-1][1]["position"], given["position"])
    with HistoryWriter(tmp_path / "copied.nc", mesh, attrs) as writer:
        for k in range(total):
            writer.append(times[k], {key: value[k] for key, value in (given | zeros).items()})
    with xr.open_dataset(tmp_path / "owned.nc") as owned, \
            xr.open_dataset(tmp_path / "copied.nc") as copied:
        np.testing.assert_array_equal(owned["time"], times)
        for key, value in given.items():
            np.testing.assert_array_equal(owned[key], value, err_msg=key)
        for name in ("tension_min", "tension_max", "tension_mean", "tension_std",
                     "end_tension", "fairlead_tension"):
            np.testing.assert_array_equal(owned[name], copied[name], err_msg=name)
        assert owned.attrs["envelope_records"] == total


def test_reserved_space_changes_nothing_in_the_file(tmp_path: Path) -> None:
    """The space reserved past the end of a file holds no byte of it: reserving leaves the
    size as it was; a stream written with its blocks' space reserved is, byte for byte, the
    file written without."""
    from moorline.io.preallocate import reserve

    path = tmp_path / "f.bin"
    path.write_bytes(b"x" * 5000)
    if not reserve(path, 1 << 20):
        pytest.skip("no fallocate here: nothing is reserved")
    assert path.stat().st_size == 5000 and path.read_bytes() == b"x" * 5000
    assert path.stat().st_blocks * 512 >= 1 << 20

    mesh = discretize(load_case(OC3_DYNAMICS))
    n, m, lines = mesh.n_nodes, mesh.n_elements, len(mesh.line_names)
    rng = np.random.default_rng(7)
    total = 300
    records = {"position": rng.normal(size=(total, n, 3)),
               "velocity": rng.normal(size=(total, n, 3)),
               "tension": 1.0e5 * rng.random((total, m)),
               "end_force": rng.normal(size=(total, lines, 2, 3)),
               "wave_elevation": rng.normal(size=total),
               **{key: np.zeros((total, 0, 6))
                  for key in ("body_pose", "body_velocity", "body_mooring_force")}}
    times = 0.05 * np.arange(total)
    written = []
    for name, reserving in (("reserved.nc", True), ("plain.nc", False)):
        with pytest.MonkeyPatch.context() as patch:
            if not reserving:
                patch.setattr(stream, "reserve", lambda path, nbytes: False)
            with HistoryWriter(tmp_path / name, mesh, {"case": "x", "units": "SI"}) as writer:
                for first in range(0, total, 100):
                    writer.append_block(times[first:first + 100],
                                        {k: v[first:first + 100] for k, v in records.items()},
                                        owned=True)
                    writer.flush()
        written.append((tmp_path / name).read_bytes())
    assert written[0] == written[1]
