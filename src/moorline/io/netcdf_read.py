"""Read one group of a results file into a :class:`~moorline.plain_dataset.PlainDataset` with
netCDF4 alone (no xarray): the inverse of :func:`moorline.io.netcdf_write.write_dataset` for
the summaries of a run whose results are no longer in memory (a dynamics run that failed:
what was streamed).

Decoding (what ``xarray.open_dataset`` does for these files): values read raw (a float
``_FillValue`` is NaN, so masking changes nothing), ``int8`` variables with ``dtype = "bool"``
back to booleans, strings as numpy strings; ``_FillValue``, ``dtype`` and ``coordinates`` are
not kept as attributes; the coordinates are the variables named after a dimension and those a
``coordinates`` attribute lists.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from ..plain_dataset import PlainDataset, PlainVariable

__all__ = ["read_plain"]

_ENCODING = ("_FillValue", "dtype", "coordinates")


def read_plain(path: str | Path, group: str = "") -> PlainDataset:
    """Load group ``group`` of a NetCDF-4 file (``""``: the root group) into memory."""
    import netCDF4

    with netCDF4.Dataset(Path(path), "r") as root:
        source = root[group] if group else root
        coord_names = set(str(getattr(source, "coordinates", "")).split())
        variables: dict[str, PlainVariable] = {}
        for name, var in source.variables.items():
            var.set_auto_maskandscale(False)
            attrs = {k: var.getncattr(k) for k in var.ncattrs()}
            coord_names.update(str(attrs.get("coordinates", "")).split())
            values: Any = var[...]
            if var.dtype is str:
                values = np.asarray(values, dtype=object).astype(str)
            elif attrs.get("dtype") == "bool":
                values = np.asarray(values).astype(bool)
            variables[name] = PlainVariable(var.dimensions, values,
                                            {k: v for k, v in attrs.items() if k not in _ENCODING})
            if name in var.dimensions:
                coord_names.add(name)
        attrs = {k: source.getncattr(k) for k in source.ncattrs() if k != "coordinates"}
    # data variables, then coordinates, each in file order (as xarray.open_dataset)
    data = {n: v for n, v in variables.items() if n not in coord_names}
    coords = {n: v for n, v in variables.items() if n in coord_names}
    return PlainDataset(data, coords, attrs)
