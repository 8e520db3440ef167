"""Tables of a results file as CSV or fixed-width text (``moorline export``).

Every file has the column names on its first line and their units, in parentheses, on the
second (as MoorDyn's ``.out`` file), then one row per record. Per group of ``results.nc``:

- ``dynamics``: ``<group>.csv``: ``Time``, then per line (MoorDyn's numbering: the n-th line
  of the case) ``FairTen<n>`` and ``AnchTen<n>``: the magnitude of the force of the line on
  its end point b and a (the channels of :mod:`moorline.io.moordyn_outputs`, as MoorDyn's
  ``.out`` file); with bodies ``Body<m>Surge`` ... ``Body<m>Yaw`` (the body pose: position of
  its origin and rotation-vector components).
- ``statics``: ``<group>_<line>.csv`` per line, its nodes in order from end a: ``node``,
  ``arc_length`` (unstretched, from end a), ``x``, ``y``, ``z``, ``tension`` (at an end node the
  end-point force's magnitude, at an inner node the mean of its two elements' tensions, as
  MoorDyn's ``L<n>N<m>T``); and ``<group>_ends.csv``: per line and end the force components,
  the tension and the line's ``max_tension`` (its ends included).
- other groups, per leading dimension (``time``, ``omega``, ``mode``, ``yaw``...):
  ``<group>_<dim>.csv`` with that coordinate then every variable along it, one column per
  other index (``tension_spectrum[3]``, ``body_spectrum[box,surge]``); offset curves
  (``heading, offset, ...``) give one ``<group>_heading<k>.csv`` per heading (the k-th of
  the ``heading`` coordinate, from 0). A body-dof column has its own unit (``N`` for
  ``restoring_force[surge]``, ``N*m`` for ``[pitch]``; a 6x6 stiffness entry force or moment
  per metre or radian).
"""

from __future__ import annotations

import csv
import re
from collections.abc import Iterable
from dataclasses import dataclass, field
from itertools import product
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from ..datasets import BODY_DOFS
from ..envelope import line_profile
from .moordyn_outputs import end_tension_channel
from .units import DIMENSIONS
from .writers import read_group, result_groups

__all__ = ["Table", "export_results", "group_tables", "write_table"]

#: Leading dimensions that make a table of the variables along them.
INDEX_DIMS = ("time", "omega", "offset", "yaw", "mode", "percentile")


@dataclass
class Table:
    """A named table: ``columns`` (name -> 1-D array, all of one length) and their units."""

    name: str
    columns: dict[str, np.ndarray] = field(default_factory=dict)
    units: dict[str, str] = field(default_factory=dict)

    def add(self, name: str, values: Any, unit: str) -> None:
        """Append a column."""
        self.columns[name] = np.asarray(values)
        self.units[name] = unit


def export_results(path: str | Path, directory: str | Path, text: bool = False) -> list[Path]:
    """Write the tables of every group of a results file into ``directory``.

    Parameters
    ----------
    path
        ``results.nc`` (or an older single-group file).
    directory
        Output directory (created if needed).
    text
        Fixed-width text tables (``.txt``) instead of CSV.

    Returns
    -------
    list of Path
        The files written, in the order of the groups.
    """
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    written = []
    for group, kind in result_groups(path).items():
        ds = read_group(path, group)
        for table in group_tables(ds, kind, group or kind):
            target = directory / f"{table.name}.{'txt' if text else 'csv'}"
            written.append(write_table(table, target, text))
    return written


def group_tables(ds: xr.Dataset, kind: str, name: str) -> list[Table]:
    """The tables of one group (see the module docstring); ``name`` prefixes their names."""
    if kind == "dynamics":
        return [_dynamics(ds, name)]
    if kind == "statics":
        return [*(_statics_line(ds, name, str(ln)) for ln in ds["line"].values),
                _statics_ends(ds, name)]
    return _natural(ds, name)


def _dynamics(ds: xr.Dataset, name: str) -> Table:
    table = Table(name)
    table.add("Time", ds["time"].values, ds["time"].attrs.get("units", "s"))
    unit = ds["end_tension"].attrs.get("units", "")
    for end in ("b", "a"):
        for k in range(ds.sizes["line"]):
            table.add(end_tension_channel(k + 1, end), ds["end_tension"].values[:, k,
                                                                                 "ab".index(end)],
                      unit)
    if "body_pose" in ds:
        length = DIMENSIONS["length"].unit("US" if ds.attrs.get("units") == "US" else "SI")
        for m in range(ds.sizes["body"]):
            for j, dof in enumerate(BODY_DOFS):
                table.add(f"Body{m + 1}{dof.capitalize()}", ds["body_pose"].values[:, m, j],
                          length if j < 3 else "rad")
    return table


def _statics_line(ds: xr.Dataset, name: str, line: str) -> Table:
    profile = line_profile(ds, line)
    k = [str(n) for n in ds["line"].values].index(line)
    position = np.asarray(profile["position"].values)
    element = np.asarray(profile["tension"].values)
    tension = np.concatenate([[np.nan], 0.5 * (element[:-1] + element[1:]), [np.nan]])
    tension[[0, -1]] = np.asarray(ds["end_tension"].values)[k]
    length = profile["arc_length"].attrs.get("units", "")
    table = Table(f"{name}_{line}")
    table.add("node", np.arange(len(position)), "1")
    table.add("arc_length", profile["arc_length"].values, length)
    for j, axis in enumerate("xyz"):
        table.add(axis, position[:, j], ds["position"].attrs.get("units", ""))
    table.add("tension", tension, ds["tension"].attrs.get("units", ""))
    return table


def _statics_ends(ds: xr.Dataset, name: str) -> Table:
    force = ds["end_force"].attrs.get("units", "")
    lines = [str(n) for n in ds["line"].values]
    table = Table(f"{name}_ends")
    table.add("line", [ln for ln in lines for _ in "ab"], "-")
    table.add("end", [e for _ in lines for e in "ab"], "-")
    for j, axis in enumerate("xyz"):
        table.add(f"F{axis}", np.asarray(ds["end_force"].values)[:, :, j].ravel(), force)
    table.add("tension", np.asarray(ds["end_tension"].values).ravel(), force)
    table.add("max_tension", np.repeat(np.asarray(ds["max_tension"].values), 2), force)
    return table


def _natural(ds: xr.Dataset, name: str) -> list[Table]:
    """One table per leading index dimension; offset curves one per heading."""
    tables: dict[str, Table] = {}
    system = "US" if ds.attrs.get("units") == "US" else "SI"
    for var in ds.data_vars:
        da = ds[var]
        if len(da.dims) >= 2 and da.dims[:2] == ("heading", "offset"):
            for h in range(ds.sizes["heading"]):
                table = _start(tables, f"{name}_heading{h}", ds, "offset")
                _flatten(table, str(var), da.isel(heading=h), system)
        elif da.dims and da.dims[0] in INDEX_DIMS:
            table = _start(tables, f"{name}_{da.dims[0]}", ds, str(da.dims[0]))
            _flatten(table, str(var), da, system)
    return list(tables.values())


def _start(tables: dict[str, Table], key: str, ds: xr.Dataset, dim: str) -> Table:
    if key not in tables:
        tables[key] = Table(key)
        values = ds[dim].values if dim in ds.coords else np.arange(ds.sizes[dim])
        tables[key].add(dim, values, ds[dim].attrs.get("units", "1") if dim in ds.coords
                        else "1")
    return tables[key]


def _flatten(table: Table, name: str, da: xr.DataArray, system: str) -> None:
    """Columns of ``da`` (leading dimension the table's index), one per other index."""
    values = np.asarray(da.values)
    unit = str(da.attrs.get("units", ""))
    rest = da.dims[1:]
    if not rest:
        table.add(name, values, unit)
        return
    labels = [[str(v) for v in da[d].values] if d in da.coords else
              [str(i) for i in range(da.sizes[d])] for d in rest]
    flat = values.reshape(values.shape[0], -1)
    by_label = _units_by_label(unit)
    matrix = len(rest) == 2 and all(d in ("dof", "dof_column") for d in rest)
    for j, combo in enumerate(product(*labels)):
        own = next((by_label[c] for c in combo if c in by_label), unit)
        if matrix:
            own = _stiffness_unit(*combo, system)
        table.add(f"{name}[{','.join(combo)}]", flat[:, j], own)


def _stiffness_unit(row: str, column: str, system: str) -> str:
    """Unit of a 6x6 stiffness entry: force (moment) per displacement (rotation)."""
    force, length = (DIMENSIONS[d].unit(system) for d in ("force", "length"))
    load = force if BODY_DOFS.index(row) < 3 else f"{force}*{length}"
    if BODY_DOFS.index(column) >= 3:
        return f"{load}/rad"
    return force if load != force else f"{force}/{length}"


def _units_by_label(unit: str) -> dict[str, str]:
    """``"m (surge, sway, heave), rad (roll, pitch, yaw: ...)"`` -> ``{"surge": "m", ...,
    "roll": "rad", ...}``: the unit of each body dof of a mixed-unit variable."""
    out: dict[str, str] = {}
    for part, names in _MIXED.findall(unit):
        for label in re.split(r"[,:;]", names):
            if label.strip() in BODY_DOFS:
                out[label.strip()] = part.strip()
    return out


_MIXED = re.compile(r"([^,()]+?) \(([^)]*)\)")


def write_table(table: Table, path: str | Path, text: bool = False) -> Path:
    """Write a table as CSV (names, then units in parentheses, then rows) or as a
    fixed-width text table with the same two header lines."""
    path = Path(path)
    names = list(table.columns)
    units = [f"({table.units[n]})" for n in names]
    rows = [[_cell(v, text) for v in row]
            for row in zip(*table.columns.values(), strict=True)]
    if text:
        width = 1 + max(len(c) for row in [names, units, *rows] for c in row)
        lines = ["".join(f"{c:>{width}}" for c in row) for row in [names, units, *rows]]
        path.write_text("\n".join(lines) + "\n", encoding="utf-8")
        return path
    with path.open("w", newline="", encoding="utf-8") as handle:
        writer = csv.writer(handle)
        writer.writerows(_rows(names, units, rows))
    return path


def _rows(names: list[str], units: list[str], rows: list[list[str]]) -> Iterable[list[str]]:
    yield names
    yield units
    yield from rows


def _cell(value: Any, text: bool) -> str:
    """A float exactly (``repr``) in CSV, to 10 significant digits in text."""
    if isinstance(value, float | np.floating):
        value = float(value) + 0.0  # no -0.0
        return f"{value:.10g}" if text else repr(value)
    if isinstance(value, np.integer):
        return str(int(value))
    return str(value)
