"""Stream time histories to NetCDF as a run goes, so nothing computed is lost on interrupt.

The histories go into a group of a NetCDF-4 file (the run's ``results.nc``, next to the groups
of the other analyses) or into the root group of a file of their own. The group has an
unlimited ``time`` dimension; each output record is appended, and the file is synced to disk
as soon as :data:`SYNC_SIMULATED` of simulated time or :data:`SYNC_WALL` of wall time has
passed since the last sync, so a run killed outright (SIGKILL, a power cut) loses at most
that. A record is written with SIGINT and SIGTERM held back, so a signal never leaves a
half-written record. :class:`HistoryWriter` is a context manager: leaving it (normally, by
an exception, by Ctrl-C or SIGTERM) closes the file with its final attributes: ``success``
and ``complete`` (1 or 0), ``status`` (``completed``, ``failed``, ``interrupted``,
``terminated``) and ``message``.
"""

from __future__ import annotations

import time
from pathlib import Path
from types import TracebackType
from typing import Any

import netCDF4
import numpy as np
from numpy.typing import NDArray

from ..datasets import Status, dynamics_dataset, record_variables
from ..mesh import Mesh
from ..signals import Terminated, signals_deferred

FloatArray = NDArray[np.float64]

SYNC_SIMULATED = 1.0
"""Simulated time [s] after which the written records are synced to disk."""

SYNC_WALL = 2.0
"""Wall-clock time [s] after which the written records are synced to disk."""


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
        Also sync every this many records.
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
        self._synced = (-np.inf, time.monotonic())
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
        """Write one output record at time ``t`` (SIGINT and SIGTERM are held back until it
        is whole); sync when :data:`SYNC_SIMULATED`, :data:`SYNC_WALL` or ``sync_every``
        records have passed since the last sync (the first record is synced at once)."""
        i = self.count
        with signals_deferred():
            for var in self.variables:
                self.ds[var.name][i] = var.derive(record)
            self.ds["time"][i] = t
            self.count += 1
            self.last_time = float(t)
            now = time.monotonic()
            if (float(t) - self._synced[0] >= SYNC_SIMULATED
                    or now - self._synced[1] >= SYNC_WALL or self.count % self.sync_every == 0):
                self.root.sync()
                self._synced = (float(t), now)

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


def _attr(value: Any) -> Any:
    if isinstance(value, bool):
        return int(value)
    if value is None:
        return ""
    return value
