"""Stream time histories to NetCDF as a run goes, so nothing computed is lost on interrupt.

The histories go into a group of a NetCDF-4 file (the run's ``results.nc``, next to the groups
of the other analyses) or into the root group of a file of their own. The group has an
unlimited ``time`` dimension. Records are copied as they come into a block buffer allocated
once (a long block the caller hands over, the compiled time loop's, is held as it is instead:
:data:`HOLD_RECORDS`) and written in blocks: a block is written and the file synced when the
group is created and at the first record, then when :data:`SYNC_WALL` of wall time will have
passed since the last write by the next record (judged from the last interval between records)
or the buffer is full (:data:`BLOCK_RECORDS`, :data:`BLOCK_BYTES`). So a run killed outright
(SIGKILL) loses at most about the last second of wall time (more only when one output interval
suddenly takes far longer than those before it), while the output costs little beside the
stepping even at one record per step: a block costs one write per variable and held segment
(:func:`moorline.io.netcdf_write.put_rows`, without netCDF4's slicing, which cost 0.14 ms a
call), the envelope is updated per block, vectorized, and what remains is moving the data:
into the buffer (not for a held block) and to the operating system, the chunks of the large
variables straight from the block (:func:`_chunking`). Fresh memory is what made that dear
(on a virtual machine a page touched for the first time costs about as much as copying it ten
times): the buffer is reused from block to block, and no chunk cache holds a block's copy.
A block is written with SIGINT and SIGTERM held back, so a signal never leaves a half-written
record.
:class:`HistoryWriter` is a context manager: leaving it (normally, by an exception, by
Ctrl-C or SIGTERM) writes what is buffered and closes the file with its final attributes:
``success`` and ``complete`` (1 or 0), ``status`` (``completed``, ``failed``,
``interrupted``, ``terminated``) and ``message``.
"""

from __future__ import annotations

import time
from pathlib import Path
from types import TracebackType
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..datasets import dynamics_dataset, record_variables
from ..envelope import TensionEnvelope
from ..mesh import Mesh
from ..signals import Terminated, signals_deferred
from ..status import Status
from .netcdf_write import nc_attrs, put_rows, write_into
from .preallocate import reserve

FloatArray = NDArray[np.float64]

SYNC_WALL = 1.0
"""Wall-clock time [s] after which the buffered records are written and synced to disk."""

BLOCK_RECORDS = 8192
"""Records buffered at most before a block is written (usually :data:`SYNC_WALL` comes first:
every block costs a sync, an envelope update and the rewrite of the chunks it ends in, a few
ms on a 2-core machine)."""

BLOCK_BYTES = 32 << 20
"""Size of a block at most [bytes] (fewer records per block on large meshes)."""

HOLD_RECORDS = 64
"""Records of an owned block (:meth:`HistoryWriter.append_block`) from which it is held as
given until written instead of copied into the buffer: the compiled loop's blocks of
thousands of records (the copy, into memory touched for the first time, cost a fifth of the
streaming); shorter ones are copied, so that they are written together."""


class HistoryWriter:
    """Append dynamic records to a NetCDF file, or to a group of one.

    The group is created from the same dataset builder and variable list as
    :meth:`moorline.results.DynamicResult.to_plain`
    (:func:`moorline.datasets.dynamics_dataset`, :data:`~moorline.datasets.DYNAMIC_VARIABLES`):
    the same variables, dimensions, coordinates, ``units`` and ``long_name``, with an unlimited
    ``time`` dimension that each record extends. The tension envelope
    (:class:`moorline.envelope.TensionEnvelope`: ``tension_min`` ... ``tension_static`` and
    the attribute ``envelope_records``) is accumulated from the records as they come and
    rewritten with every block, so the file holds the envelope of the records it holds.

    Parameters
    ----------
    path
        The file (parent directories are made). Without ``group`` it is created (replacing
        an existing file); with ``group`` an existing file is opened for appending and the
        group added to it.
    mesh
        The mesh (sets the dimensions and coordinates).
    attrs
        Attributes of the group written at creation
        (:func:`moorline.datasets.group_attrs`: case, units, settings...); ``success`` 0,
        ``complete`` 0 and ``status`` ``running`` until :meth:`close`.
    units
        The unit system (``SI`` or ``US``); default ``attrs["units"]``.
    block_records
        Write a block at the latest after this many records (default :data:`BLOCK_RECORDS`,
        fewer when a block would take more than :data:`BLOCK_BYTES`).
    group
        Name of the group to write (e.g. ``"dynamics"``); ``None``: the root group.
    static_tension
        The envelope's static element tensions (the statics the run starts from); ``None``:
        the first record's.

    Attributes
    ----------
    count, written
        Records appended, records on disk.
    attrs
        The group's attributes as written (those at creation, ``envelope_records``, and
        after :meth:`close` the final ones).

    Raises
    ------
    ValueError
        When the file already has a group of that name.
    """

    def __init__(self, path: str | Path, mesh: Mesh, attrs: dict[str, Any],
                 units: str | None = None, block_records: int | None = None,
                 group: str | None = None,
                 static_tension: FloatArray | None = None) -> None:
        import netCDF4

        self.path = Path(path)
        self.path.parent.mkdir(parents=True, exist_ok=True)
        self.group = group
        self.count = 0
        self.written = 0
        self.last_time = float("nan")
        self._written_at = self._appended_at = time.monotonic()
        self.variables = record_variables(mesh)
        self._block_records = block_records
        self._limit = 0  # records per block, from the first record's size
        self._buffers: dict[str, FloatArray] = {}  # the block: record key -> (limit, ...)
        self._times = np.zeros(0)
        self._n_pending = 0  # records waiting: copied into the buffer or held
        self._n_buffered = 0  # of which copied into the buffer
        self._pending: list[tuple[FloatArray, dict[str, FloatArray]]] = []  # in order
        self._buffer_run = -1  # buffer row where the last pending segment starts (-1: held)
        append = group is not None and self.path.exists()
        start = {**attrs, "units": units or attrs.get("units", "SI"), "success": 0,
                 "complete": 0, "status": str(Status.RUNNING)}
        skeleton = dynamics_dataset(mesh, np.zeros(0), {}, start, static_tension)
        chunking, cache = _chunking(skeleton)
        self.root = netCDF4.Dataset(self.path, "a" if append else "w", format="NETCDF4")
        try:
            self.ds = write_into(self.root, skeleton, group=group, unlimited_dims=["time"],
                                 chunksizes=chunking, unfilled=chunking, chunk_cache=cache)
            self.root.sync()  # the group is on disk before the first (maybe slow) step
        except BaseException:
            self.root.close()
            raise
        self._targets = {var.name: self.ds[var.name] for var in self.variables}
        self._time = self.ds["time"]
        self._record_bytes = sum(8 * int(np.prod(chunks[1:], dtype=np.int64))
                                 for chunks in chunking.values())
        self.attrs: dict[str, Any] = nc_attrs(skeleton.attrs)
        self.envelope = TensionEnvelope(mesh.n_elements, skeleton.attrs["envelope_start"],
                                        static_tension)

    def append(self, t: float, record: dict[str, FloatArray]) -> None:
        """Buffer one output record at time ``t`` (copied: its arrays may change afterwards);
        write the block when it is the first record, when the block is full, or when
        :data:`SYNC_WALL` will have passed since the last write by the next record, judged
        from the wall time since the previous one (so the oldest record waiting is at most
        about :data:`SYNC_WALL` old when the output interval is steady, and records more
        than :data:`SYNC_WALL` apart are written at once)."""
        self.append_block(np.array([float(t)]),
                          {key: np.asarray(value)[None] for key, value in record.items()})

    def append_block(self, times: FloatArray, records: dict[str, FloatArray],
                     owned: bool = False) -> None:
        """Buffer several records at once: ``times`` (n,) and each record key stacked along
        a first axis of length n (as the compiled time loop writes them); written by the
        rules of :meth:`append`, the block counting as one arrival (a full block on the way
        is written as it fills). ``owned``: the caller hands the arrays over (never changes
        them afterwards): a block of :data:`HOLD_RECORDS` records or more is then held as it
        is until written, not copied into the buffer."""
        n = len(times)
        if n == 0:
            return
        now = time.monotonic()
        interval, self._appended_at = now - self._appended_at, now
        if not self._limit:
            self._allocate(records, n)
        first = 0
        while first < n:
            if self._n_pending == self._limit:
                self.flush()
                if self._n_pending:
                    raise ValueError(f"{self.path}: the stream is closed")
            take = min(self._limit - self._n_pending, n - first)
            if owned and take >= HOLD_RECORDS:
                self._hold(times, records, first, take)
            else:
                self._store(times, records, first, take)
            first += take
        if (self.written == 0 or self._n_pending >= self._limit
                or now - self._written_at + interval >= SYNC_WALL):
            self.flush()

    def _allocate(self, records: dict[str, Any], n: int) -> None:
        """The block buffer, for the record keys written (``records``: ``n`` records
        stacked): :meth:`_records_per_block` records of each."""
        self._limit = self._records_per_block(records, n)
        names = {var.name for var in self.variables}
        self._buffers = {key: np.empty((self._limit, *np.shape(value)[1:]))
                         for key, value in records.items() if key in names}
        self._times = np.empty(self._limit)

    def _store(self, times: FloatArray, records: dict[str, Any], first: int,
               take: int) -> None:
        """Copy records ``first`` .. ``first + take`` of a block into the buffer (counted
        once all are copied: a signal in between leaves the buffer as it was)."""
        i = self._n_buffered
        for key, buffer in self._buffers.items():
            buffer[i:i + take] = records[key][first:first + take]
        self._times[i:i + take] = times[first:first + take]
        start = self._buffer_run if self._buffer_run >= 0 else i
        segment = (self._times[start:i + take],
                   {key: buffer[start:i + take] for key, buffer in self._buffers.items()})
        if self._buffer_run >= 0:  # continues the buffered segment before it
            self._pending[-1] = segment
        else:
            self._pending.append(segment)
        self._buffer_run, self._n_buffered = start, i + take
        self._counted(times, take, first)

    def _hold(self, times: FloatArray, records: dict[str, Any], first: int,
              take: int) -> None:
        """Hold records ``first`` .. ``first + take`` of an owned block as they are."""
        self._pending.append((np.asarray(times[first:first + take], dtype=float),
                              {key: records[key][first:first + take]
                               for key in self._buffers}))
        self._buffer_run = -1
        self._counted(times, take, first)

    def _counted(self, times: FloatArray, take: int, first: int) -> None:
        self._n_pending += take
        self.count += take
        self.last_time = float(times[first + take - 1])

    def flush(self) -> None:
        """Write the waiting records, segment by segment in order (a held block, the
        records copied between held ones), and sync the file (signals held back); their
        disk space is reserved first (:func:`moorline.io.preallocate.reserve`)."""
        if self._n_pending == 0 or not self.root.isopen():
            return
        i = self.written
        with signals_deferred():
            reserve(self.path, self._n_pending * self._record_bytes)
            for times, block in self._pending:
                n = len(times)
                derived = dict(block)  # each variable derived once (end_tension: fairlead)
                for var in self.variables:
                    derived[var.name] = values = var.derive(derived)
                    put_rows(self._targets[var.name], values, i)
                put_rows(self._time, times, i)
                self.envelope.add_records(times, block["tension"])
                i += n
            self._write_envelope()
            self.root.sync()
            self.written = i
            self._n_pending = self._n_buffered = 0
            self._pending, self._buffer_run = [], -1
            self._written_at = self._appended_at = time.monotonic()

    def _write_envelope(self) -> None:
        """Write the envelope of the records so far."""
        for name, values in self.envelope.values().items():
            put_rows(self.ds[name], values)
        self.ds.setncattr("envelope_records", self.envelope.count)
        self.attrs["envelope_records"] = self.envelope.count

    def _records_per_block(self, records: dict[str, Any], n: int) -> int:
        """``block_records`` records per block, fewer when a block would exceed
        :data:`BLOCK_BYTES` (``records``: ``n`` records stacked)."""
        per_record = 8 * sum(int(np.size(value)) for value in records.values()) // n + 8
        return max(1, min(self._block_records or BLOCK_RECORDS, BLOCK_BYTES // per_record))

    def close(self, attrs: dict[str, Any] | None = None) -> None:
        """Write final attributes of the group (default: completed) and close the file."""
        if self.root.isopen():
            self.flush()
            final = {"complete": 1, "success": 1, "status": str(Status.COMPLETED),
                     "message": f"{self.count} records"}
            final.update(attrs or {})
            self.ds.setncatts(nc_attrs(final))
            self.attrs.update(nc_attrs(final))
            self.root.close()

    def __enter__(self) -> HistoryWriter:
        return self

    def __exit__(self, exc_type: type[BaseException] | None, exc: BaseException | None,
                 tb: TracebackType | None) -> None:
        if exc_type is None:
            self.close()
            return
        if issubclass(exc_type, Terminated):
            status = Status.TERMINATED
        elif issubclass(exc_type, KeyboardInterrupt):
            status = Status.INTERRUPTED
        else:
            status = Status.FAILED
        reason = f"failed: {exc}" if status == Status.FAILED else str(status)
        when = f" at t = {self.last_time:.6g} s" if self.count else ""
        self.close({"complete": 0, "success": 0, "status": str(status),
                    "message": f"{reason}; {self.count} records kept{when}"})


CHUNK_BYTES = 1 << 20
"""Target size of a NetCDF chunk of a time-dependent variable [bytes]: netCDF4's default
for an unlimited dimension is one record per chunk, which makes every block write (and every
read) thousands of small chunk operations. A chunk is allocated whole, so the file holds up
to one chunk per large variable more than its records (the benchmark's 6000 records: 24.0 MB
instead of 23.0 MB at 256 kB chunks, whose writing cost ~0.7 ms more: median of 30)."""

CHUNK_RECORDS = 4096
"""Records per chunk at most (variables of small records: ``time``, ``wave_elevation``,
the line ends' forces)."""


def _chunking(skeleton: Any) -> tuple[dict[str, tuple[int, ...]], dict[str, int]]:
    """Chunk shapes and chunk cache sizes [bytes] of the time-dependent variables.

    A chunk holds about :data:`CHUNK_BYTES` along ``time`` (at most :data:`CHUNK_RECORDS`
    records), whole along the other dimensions. The variables are written in netCDF's
    no-fill mode (every value of them is written), so HDF5 writes a chunk that does not fit
    the variable's chunk cache straight from the block, once: the variables of large records
    get no cache (a block covers whole chunks of them but their edges; through a cache of
    two chunks the 22 MB of the benchmark cost ~2.5 ms more: a copy, and the chunks written
    at the sync); those of small records, which a block only covers a piece of, keep a
    cache of two chunks (the one being filled is written at the sync; written straight, each
    piece cost ~0.1 ms)."""
    chunks: dict[str, tuple[int, ...]] = {}
    cache: dict[str, int] = {}
    for name, var in skeleton.variables.items():
        if not var.dims or var.dims[0] != "time":
            continue
        rest = tuple(max(1, int(n)) for n in var.shape[1:])
        per_record = 8 * int(np.prod(rest, dtype=np.int64))
        records = int(max(1, min(CHUNK_RECORDS, CHUNK_BYTES // per_record)))
        chunks[name] = (records, *rest)
        cache[name] = 2 * records * per_record if records == CHUNK_RECORDS else 0
    return chunks, cache
