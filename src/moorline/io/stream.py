"""Stream time histories to NetCDF as a run goes, so nothing computed is lost on interrupt.

The file has an unlimited ``time`` dimension; each output record is appended and the file is
synced every few records. :class:`HistoryWriter` is a context manager: leaving it (normally,
by an exception or by Ctrl-C) closes the file with its final attributes.
"""

from __future__ import annotations

from pathlib import Path
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
}


class HistoryWriter:
    """Append dynamic records to a NetCDF file.

    Parameters
    ----------
    path
        File to create (parent directories are made).
    mesh
        The mesh (sets the dimensions and coordinates).
    attrs
        Global attributes written at creation (case, units, settings...).
    units
        Unit names per units key (``length``, ``velocity``, ``force``).
    sync_every
        Flush to disk every this many records.
    """

    def __init__(self, path: str | Path, mesh: Mesh, attrs: dict[str, Any],
                 units: dict[str, str], sync_every: int = 20) -> None:
        self.path = Path(path)
        self.path.parent.mkdir(parents=True, exist_ok=True)
        self.sync_every = sync_every
        self.count = 0
        ds = netCDF4.Dataset(self.path, "w", format="NETCDF4")
        ds.createDimension("time", None)
        for name, size in (("node", mesh.n_nodes), ("element", mesh.n_elements), ("xyz", 3),
                           ("line", len(mesh.line_names)), ("end", 2),
                           ("point", len(mesh.point_names))):
            ds.createDimension(name, size)
        ds.createVariable("time", "f8", ("time",)).units = units.get("time", "s")
        for name, (dims, key) in RECORD_VARIABLES.items():
            var = ds.createVariable(name, "f8", ("time", *dims), zlib=False)
            var.units = units.get(key, key)
        _coordinates(ds, mesh)
        ds.setncatts({k: _attr(v) for k, v in attrs.items()})
        ds.setncattr("complete", 0)
        self.ds = ds

    def append(self, t: float, record: dict[str, FloatArray]) -> None:
        """Write one output record at time ``t``."""
        i = self.count
        self.ds["time"][i] = t
        for name in RECORD_VARIABLES:
            self.ds[name][i] = record[name]
        self.count += 1
        if self.count % self.sync_every == 0:
            self.ds.sync()

    def close(self, attrs: dict[str, Any] | None = None) -> None:
        """Write final attributes and close the file."""
        if self.ds.isopen():
            self.ds.setncatts({k: _attr(v) for k, v in (attrs or {}).items()})
            self.ds.close()

    def __enter__(self) -> HistoryWriter:
        return self

    def __exit__(self, exc_type, exc, tb) -> None:
        if exc_type is not None:
            reason = "interrupted" if exc_type is KeyboardInterrupt else f"failed: {exc}"
            self.close({"complete": 0, "status": f"{reason} after {self.count} records"})
        else:
            self.close()


def _coordinates(ds: netCDF4.Dataset, mesh: Mesh) -> None:
    ds.createVariable("xyz", str, ("xyz",))[:] = np.array(["x", "y", "z"], dtype=object)
    ds.createVariable("end", str, ("end",))[:] = np.array(["a", "b"], dtype=object)
    ds.createVariable("line", str, ("line",))[:] = np.array(mesh.line_names, dtype=object)
    ds.createVariable("point", str, ("point",))[:] = np.array(mesh.point_names, dtype=object)
    names = np.array([mesh.line_names[i] for i in mesh.element_line], dtype=object)
    ds.createVariable("element_line", str, ("element",))[:] = names
    pair = ds.createDimension("pair", 2)
    ds.createVariable("element_nodes", "i8", ("element", pair.name))[:] = mesh.elements


def _attr(value: Any) -> Any:
    if isinstance(value, bool):
        return int(value)
    if value is None:
        return ""
    return value
