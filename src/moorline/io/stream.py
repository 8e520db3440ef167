"""Stream time histories to NetCDF as a run goes, so nothing computed is lost on interrupt.

The histories go into a group of a NetCDF-4 file (the run's ``results.nc``, next to the groups
of the other analyses) or into the root group of a file of their own. The group has an
unlimited ``time`` dimension; each output record is appended and the file is synced every few
records. A record is written with SIGINT held back, so Ctrl-C never leaves a half-written
record. :class:`HistoryWriter` is a context manager: leaving it (normally, by an exception or
by Ctrl-C) closes the file with its final attributes: ``success`` and ``complete`` (1 or 0),
``status`` (``completed``, ``failed``, ``interrupted``) and ``message``.
"""

from __future__ import annotations

import signal
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from types import FrameType, TracebackType
from typing import Any

import netCDF4
import numpy as np
from numpy.typing import NDArray

from ..datasets import Status, dynamics_dataset, record_variables
from ..mesh import Mesh

FloatArray = NDArray[np.float64]


class HistoryWriter:
    """Append dynamic records to a NetCDF file, or to a group of one.

    The group is created from the same dataset builder and variable list as
    :meth:`moorline.results.DynamicResult.to_xarray`
    (:func:`moorline.datasets.dynamics_dataset`, :data:`~moorline.datasets.DYNAMIC_VARIABLES`):
    the same variables, dimensions, coordinates, ``units`` and ``long_name``, with an unlimited
    ``time`` dimension that each record extends.

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
    sync_every
        Flush to disk every this many records.
    group
        Name of the group to write (e.g. ``"dynamics"``); ``None``: the root group.

    Raises
    ------
    ValueError
        When the file already has a group of that name.
    """

    def __init__(self, path: str | Path, mesh: Mesh, attrs: dict[str, Any],
                 units: str | None = None, sync_every: int = 20,
                 group: str | None = None) -> None:
        self.path = Path(path)
        self.path.parent.mkdir(parents=True, exist_ok=True)
        self.group = group
        self.sync_every = sync_every
        self.count = 0
        self.last_time = float("nan")
        self.variables = record_variables(mesh)
        append = group is not None and self.path.exists()
        if append:
            with netCDF4.Dataset(self.path, "r") as existing:
                if group in existing.groups:
                    raise ValueError(f"{self.path} already has a group {group!r}")
        start = {**attrs, "units": units or attrs.get("units", "SI"), "success": 0,
                 "complete": 0, "status": str(Status.RUNNING)}
        skeleton = dynamics_dataset(mesh, np.zeros(0), {}, start)
        skeleton.to_netcdf(self.path, mode="a" if append else "w", group=group,
                           engine="netcdf4", unlimited_dims=["time"])
        self.root = netCDF4.Dataset(self.path, "a")
        self.ds = self.root if group is None else self.root.groups[group]

    def append(self, t: float, record: dict[str, FloatArray]) -> None:
        """Write one output record at time ``t`` (SIGINT is held back until it is whole)."""
        i = self.count
        with _sigint_deferred():
            for var in self.variables:
                self.ds[var.name][i] = var.derive(record)
            self.ds["time"][i] = t
            self.count += 1
            self.last_time = float(t)
            if self.count % self.sync_every == 0:
                self.root.sync()

    def close(self, attrs: dict[str, Any] | None = None) -> None:
        """Write final attributes of the group (default: completed) and close the file."""
        if self.root.isopen():
            final = {"complete": 1, "success": 1, "status": str(Status.COMPLETED),
                     "message": f"{self.count} records"}
            final.update(attrs or {})
            self.ds.setncatts({k: _attr(v) for k, v in final.items()})
            self.root.close()

    def __enter__(self) -> HistoryWriter:
        return self

    def __exit__(self, exc_type: type[BaseException] | None, exc: BaseException | None,
                 tb: TracebackType | None) -> None:
        if exc_type is None:
            self.close()
            return
        interrupted = issubclass(exc_type, KeyboardInterrupt)
        reason = "interrupted" if interrupted else f"failed: {exc}"
        when = f" at t = {self.last_time:.6g} s" if self.count else ""
        status = Status.INTERRUPTED if interrupted else Status.FAILED
        self.close({"complete": 0, "success": 0, "status": str(status),
                    "message": f"{reason}; {self.count} records kept{when}"})


@contextmanager
def _sigint_deferred() -> Iterator[None]:
    """Hold back SIGINT in the block and deliver it (KeyboardInterrupt) right after.

    Only in the main thread and when Python handles SIGINT; otherwise a no-op.
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = signal.getsignal(signal.SIGINT)
    if not callable(previous):
        yield
        return
    received: list[tuple[int, FrameType | None]] = []
    signal.signal(signal.SIGINT, lambda signum, frame: received.append((signum, frame)))
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)
        if received:
            previous(*received[0])


def _attr(value: Any) -> Any:
    if isinstance(value, bool):
        return int(value)
    if value is None:
        return ""
    return value
