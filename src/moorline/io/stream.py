"""Stream time histories to NetCDF as a run goes, so nothing computed is lost on interrupt.

The histories go into a group of a NetCDF-4 file (the run's ``results.nc``, next to the groups
of the other analyses) or into the root group of a file of their own. The group has an
unlimited ``time`` dimension; each output record is appended and the file is synced every few
records. A record is written with SIGINT held back, so Ctrl-C never leaves a half-written
record. :class:`HistoryWriter` is a context manager: leaving it (normally, by an exception or
by Ctrl-C) closes the file with its final attributes: ``complete`` (1 or 0) and ``status``.
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

from ..mesh import Mesh

FloatArray = NDArray[np.float64]

#: Variables of a dynamic record: name -> (dimensions after time, units key)
RECORD_VARIABLES: dict[str, tuple[tuple[str, ...], str]] = {
    "position": (("node", "xyz"), "length"),
    "velocity": (("node", "xyz"), "velocity"),
    "tension": (("element",), "force"),
    "end_force": (("line", "end", "xyz"), "force"),
    "wave_elevation": ((), "length"),
}


class HistoryWriter:
    """Append dynamic records to a NetCDF file, or to a group of one.

    Parameters
    ----------
    path
        The file (parent directories are made). Without ``group`` it is created (replacing
        an existing file); with ``group`` an existing file is opened for appending and the
        group added to it.
    mesh
        The mesh (sets the dimensions and coordinates).
    attrs
        Attributes of the group written at creation (case, units, settings...).
    units
        Unit names per units key (``length``, ``velocity``, ``force``, ``time``).
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
                 units: dict[str, str], sync_every: int = 20, group: str | None = None) -> None:
        self.path = Path(path)
        self.path.parent.mkdir(parents=True, exist_ok=True)
        self.group = group
        self.sync_every = sync_every
        self.count = 0
        self.last_time = float("nan")
        append = group is not None and self.path.exists()
        self.root = netCDF4.Dataset(self.path, "a" if append else "w", format="NETCDF4")
        try:
            if group is not None and group in self.root.groups:
                raise ValueError(f"{self.path} already has a group {group!r}")
            ds = self.root if group is None else self.root.createGroup(group)
            _define(ds, mesh, units)
            ds.setncatts({k: _attr(v) for k, v in attrs.items()})
            ds.setncattr("complete", 0)
            ds.setncattr("status", "running")
            self.root.sync()
        except BaseException:
            self.root.close()
            raise
        self.ds = ds

    def append(self, t: float, record: dict[str, FloatArray]) -> None:
        """Write one output record at time ``t`` (SIGINT is held back until it is whole)."""
        i = self.count
        with _sigint_deferred():
            for name in RECORD_VARIABLES:
                self.ds[name][i] = record[name]
            for name in ("body_pose", "body_velocity", "body_mooring_force"):
                if name in self.ds.variables:
                    self.ds[name][i] = record[name]
            self.ds["time"][i] = t
            self.count += 1
            self.last_time = float(t)
            if self.count % self.sync_every == 0:
                self.root.sync()

    def close(self, attrs: dict[str, Any] | None = None) -> None:
        """Write final attributes of the group (default: complete) and close the file."""
        if self.root.isopen():
            final = {"complete": 1, "status": f"complete: {self.count} records"}
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
        reason = "interrupted" if issubclass(exc_type, KeyboardInterrupt) else f"failed: {exc}"
        when = f" at t = {self.last_time:.6g} s" if self.count else ""
        self.close({"complete": 0,
                    "status": f"{reason}; {self.count} records kept{when}"})


def _define(ds: netCDF4.Dataset | netCDF4.Group, mesh: Mesh, units: dict[str, str]) -> None:
    """Dimensions, record variables and coordinates of a history group."""
    ds.createDimension("time", None)
    for name, size in (("node", mesh.n_nodes), ("element", mesh.n_elements), ("xyz", 3),
                       ("line", len(mesh.line_names)), ("end", 2),
                       ("point", len(mesh.point_names)), ("pair", 2)):
        ds.createDimension(name, size)
    ds.createVariable("time", "f8", ("time",)).units = units.get("time", "s")
    for name, (dims, key) in RECORD_VARIABLES.items():
        var = ds.createVariable(name, "f8", ("time", *dims), zlib=False)
        var.units = units.get(key, key)
    if mesh.body_names:
        ds.createDimension("body", len(mesh.body_names))
        ds.createDimension("dof", 6)
        var = ds.createVariable("body_pose", "f8", ("time", "body", "dof"), zlib=False)
        var.units = f"{units.get('length', 'length')} (x, y, z), rad (rotation vector)"
        var = ds.createVariable("body_velocity", "f8", ("time", "body", "dof"), zlib=False)
        var.units = f"{units.get('velocity', 'velocity')}, rad/s"
        var = ds.createVariable("body_mooring_force", "f8", ("time", "body", "dof"),
                                zlib=False)
        var.units = f"{units.get('force', 'force')}, moment about the body origin"
        ds.createVariable("body", str, ("body",))[:] = np.array(mesh.body_names, dtype=object)
        ds.createVariable("dof", str, ("dof",))[:] = np.array(
            ["x", "y", "z", "rx", "ry", "rz"], dtype=object)
    _coordinates(ds, mesh)


def _coordinates(ds: netCDF4.Dataset | netCDF4.Group, mesh: Mesh) -> None:
    def strings(name: str, dim: str, values: Any) -> None:
        ds.createVariable(name, str, (dim,))[:] = np.array(list(values), dtype=object)

    strings("xyz", "xyz", ["x", "y", "z"])
    strings("end", "end", ["a", "b"])
    strings("line", "line", mesh.line_names)
    strings("point", "point", mesh.point_names)
    strings("point_kind", "point", mesh.point_kind)
    strings("element_line", "element", [mesh.line_names[i] for i in mesh.element_line])
    ds.createVariable("element_nodes", "i8", ("element", "pair"))[:] = mesh.elements
    ds.createVariable("point_node", "i8", ("point",))[:] = np.asarray(mesh.point_node)
    # point_kind and element_line are coordinates, as in DynamicResult.to_xarray (CF: xarray
    # reads a group attribute ``coordinates`` that way)
    ds.setncattr("coordinates", "point_kind element_line")


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
