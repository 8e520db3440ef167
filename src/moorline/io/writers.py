"""Result writers: the run's NetCDF results file and its summary (``summary.json``/``.txt``).

A run writes one NetCDF-4 file, ``results.nc``, with one group per analysis (``statics``,
``dynamics``; numbered when a kind repeats: ``statics1``, ``statics2``). Its root group holds
only attributes: ``case``, ``units``, ``moorline_version``, ``analyses`` (the group names in
order), ``complete`` (1 when every analysis ran to its end) and ``status``. Each group is a
dataset of :func:`moorline.datasets.build_dataset` (the same attributes in every group, units
and long_name on every variable): written whole (:func:`write_group`, through
:func:`moorline.io.netcdf_write.write_dataset`, which does not import dask), or, for time
histories, streamed by :class:`moorline.io.stream.HistoryWriter`.

The summary is a plain dict (the object ``moorline statics --json`` prints). It is written
twice: as JSON for scripts, and as a readable table (rendered with rich) for people.
Non-finite numbers become ``null`` in JSON so that every output is strict JSON.
"""

from __future__ import annotations

import json
import math
from collections.abc import Iterable
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from rich.console import Console, RenderableType
from rich.markup import escape
from rich.table import Table
from rich.text import Text

from .netcdf_write import nc_attrs, write_dataset
from .units import DIMENSIONS

if TYPE_CHECKING:
    import xarray as xr

__all__ = [
    "jsonable",
    "read_group",
    "render_summary",
    "result_groups",
    "start_results",
    "summary_json",
    "summary_text",
    "update_results",
    "write_group",
    "write_netcdf",
    "write_summary",
]


def write_netcdf(ds: xr.Dataset, path: str | Path) -> Path:
    """Write ``ds`` to a NetCDF-4 file, creating the parent directories.

    Parameters
    ----------
    ds
        The dataset (e.g. :meth:`moorline.results.StaticResult.to_xarray`).
    path
        Target file; an existing file is replaced.

    Returns
    -------
    Path
        The path written.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    write_dataset(ds, path)
    return path


def start_results(path: str | Path, attrs: dict[str, Any]) -> Path:
    """Create a fresh results file (replacing an old one) holding only root attributes.

    Parameters
    ----------
    path
        The file, usually ``out/<case>/results.nc`` (parent directories are created).
    attrs
        Root attributes (``case``, ``units``, ...); ``complete = 0`` and ``status =
        "running"`` are added unless given.

    Returns
    -------
    Path
        The path written.
    """
    import netCDF4

    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.unlink(missing_ok=True)
    with netCDF4.Dataset(path, "w", format="NETCDF4") as root:
        root.setncatts(nc_attrs({"complete": 0, "status": "running", **attrs}))
    return path


def update_results(path: str | Path, attrs: dict[str, Any]) -> None:
    """Set root attributes of an existing results file (e.g. ``complete`` and ``status``)."""
    import netCDF4

    with netCDF4.Dataset(Path(path), "a") as root:
        root.setncatts(nc_attrs(attrs))


def write_group(ds: xr.Dataset, path: str | Path, group: str) -> Path:
    """Add ``ds`` as group ``group`` of the results file ``path`` (created if missing).

    The group's name is appended to the root attribute ``analyses``.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    if not path.exists():
        start_results(path, {})
    write_dataset(ds, path, group=group, mode="a")
    add_analysis(path, group)
    return path


def add_analysis(path: str | Path, group: str) -> None:
    """Append ``group`` to the root attribute ``analyses`` (comma-separated group names)."""
    import netCDF4

    with netCDF4.Dataset(Path(path), "a") as root:
        names = [n for n in str(getattr(root, "analyses", "")).split(",") if n]
        root.setncattr("analyses", ",".join([*names, group]))


def result_groups(path: str | Path) -> dict[str, str]:
    """The analysis groups of a results file, in order: group name -> analysis kind.

    A file of one analysis without groups (an older ``statics.nc``) gives ``{"": kind}``.

    Raises
    ------
    OSError
        When the file cannot be opened as NetCDF.
    """
    import netCDF4

    with netCDF4.Dataset(Path(path), "r") as root:
        groups = {name: str(getattr(group, "analysis", ""))
                  for name, group in root.groups.items()}
        if not groups and "position" in root.variables:
            groups = {"": str(getattr(root, "analysis", "statics"))}
    return groups


def read_group(path: str | Path, group: str) -> xr.Dataset:
    """Load one group of a results file into memory (``""``: the root group)."""
    import xarray as xr

    with xr.open_dataset(Path(path), group=group or None, engine="netcdf4") as opened:
        return opened.load()


def jsonable(value: Any) -> Any:
    """``value`` with numpy types turned into Python ones and non-finite floats into ``None``.

    Parameters
    ----------
    value
        Nested dicts, lists, tuples, numpy arrays and scalars.

    Returns
    -------
    Any
        An object :func:`json.dumps` accepts with ``allow_nan=False``.
    """
    if isinstance(value, dict):
        return {str(k): jsonable(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [jsonable(v) for v in value]
    if isinstance(value, np.ndarray):
        return jsonable(value.tolist())
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def summary_json(summary: dict) -> str:
    """The summary as one strict JSON object (non-finite numbers as ``null``)."""
    return json.dumps(jsonable(summary), indent=2, allow_nan=False)


def write_summary(summary: dict, directory: str | Path) -> tuple[Path, Path]:
    """Write ``summary.json`` and ``summary.txt`` into ``directory`` (created if needed).

    Parameters
    ----------
    summary
        A statics summary (keys ``case``, ``converged``, ``iterations``, ``lines``,
        ``points``) or a run summary (keys ``case``, ``converged``, ``analyses``: a list of
        analysis summaries, each with a ``kind``).
    directory
        Output directory.

    Returns
    -------
    tuple of Path
        The JSON and the text file.
    """
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    json_path = directory / "summary.json"
    text_path = directory / "summary.txt"
    json_path.write_text(summary_json(summary) + "\n", encoding="utf-8")
    text_path.write_text(summary_text(summary), encoding="utf-8")
    return json_path, text_path


def summary_text(summary: dict, width: int = 110) -> str:
    """The summary rendered as plain-text tables."""
    console = Console(width=width, record=True, file=_NullFile(), color_system=None)
    for renderable in render_summary(summary):
        console.print(renderable)
    return console.export_text()


def render_summary(summary: dict) -> list[RenderableType]:
    """Rich renderables (a heading and tables) of a statics or run summary."""
    if "analyses" in summary:
        out: list[RenderableType] = [Text(f"case {summary.get('case', '')}: "
                                          f"{_status(summary.get('converged'))}", style="bold")]
        for analysis in summary["analyses"]:
            out.extend(_render_analysis(analysis, summary.get("units", "SI")))
        return out
    return _render_analysis(summary, summary.get("units", "SI"))


def _render_analysis(summary: dict, units: str) -> list[RenderableType]:
    """The tables of one analysis summary: statics and dynamics have their own, the other
    kinds a line with their status and message."""
    render = _RENDERERS.get(summary.get("kind", "statics"), _render_line)
    out = render(summary, units)
    if summary.get("design"):
        out.extend(_design_table(summary["design"], summary.get("units", units)))
    return out


def _design_table(design: dict, units: str) -> list[RenderableType]:
    """Utilization, safety factor and pass/fail of every line (:mod:`moorline.design`)."""
    force = _unit("force", units)
    dnv = design.get("standard") == "DNV-OS-E301"
    what = f"{design.get('standard')} {design.get('edition', '')}, {design.get('condition')}, "\
        f"{design.get('analysis')}"
    if dnv:
        what += f", consequence class {design.get('consequence_class')}"
    table = Table(title=escape(f"Design checks ({what}) [{force}]"))
    columns = ["line", "MBL", "T max", "T max / MBL", "MBL / T max",
               "design tension" if dnv else "required SF", "utilization", "check"]
    for name in columns:
        table.add_column(escape(name), justify="left" if name in ("line", "check") else "right")
    for name, line in design.get("lines", {}).items():
        if line.get("passed") is None:
            table.add_row(escape(name), "-", _num(line.get("max_tension")), "-", "-", "-", "-",
                          "no MBL: not checked")
            continue
        middle = (_num(line.get("design_tension")) if dnv
                  else f"{line.get('required_safety_factor'):.3g}")
        table.add_row(escape(name), _num(line.get("MBL")), _num(line.get("max_tension")),
                      f"{line['utilization']:.4g}", f"{line['safety_factor']:.4g}", middle,
                      f"{line['design_utilization']:.4g}",
                      "pass" if line["passed"] else "FAIL")
    notes = [f"tension: {design.get('basis', '')}",
             f"factors: {design.get('title', '')}, {design.get('clause', '')}"]
    if not design.get("verified", True):
        notes.append("(factors as commonly cited; not checked against the standard's text)")
    for key in ("note", "warning"):
        if design.get(key):
            notes.append(str(design[key]))
    return [table, Text("; ".join(notes))]


def _render_line(summary: dict, units: str) -> list[RenderableType]:
    text = f"{summary.get('kind', '')}: {_status(summary.get('converged'))}"
    return [Text(f"{text}: {summary['message']}" if summary.get("message") else text)]


def _render_statics(summary: dict, units: str) -> list[RenderableType]:
    units = summary.get("units", units)
    force, length = _unit("force", units), _unit("length", units)
    head = (f"{summary.get('case', '')} statics ({summary.get('method', '')}): "
            f"{_status(summary.get('converged'))} after {summary.get('iterations')} iterations")
    out: list[RenderableType] = [Text(head, style="bold")]
    if summary.get("message") and not summary.get("converged"):
        out.append(Text(str(summary["message"])))
    out.append(_lines_table(summary.get("lines", {}), force, length))
    out.append(_points_table(summary.get("points", {}), force, length))
    return out


def _render_dynamics(summary: dict, units: str) -> list[RenderableType]:
    """Heading, end-tension statistics per line, motion extremes per point, counters."""
    force, length = _unit("force", units), _unit("length", units)
    head = (f"dynamics: {summary.get('message', '')}, output t = "
            f"{_num(summary.get('time_start'))} to {_num(summary.get('time_end'))} s "
            f"({summary.get('records', 0)} records)")
    out: list[RenderableType] = [Text(head, style="bold")]
    table = Table(title=escape(f"Line end tensions over the output records [{force}]"))
    for name in ("line", "end", "max", "min", "mean", "std"):
        table.add_column(name, justify="left" if name in ("line", "end") else "right")
    for name, line in summary.get("lines", {}).items():
        for end in ("a", "b"):
            stats = line.get(f"end_{end}", {})
            table.add_row(escape(name) if end == "a" else "", end,
                          *_fmt(stats.get(k) for k in ("max", "min", "mean", "std")))
    out.append(table)
    points = Table(title=escape(f"Point motion extremes [{length}]"))
    for name in ("point", "kind", "x min", "x max", "y min", "y max", "z min", "z max"):
        points.add_column(name, justify="left" if name in ("point", "kind") else "right")
    for name, point in summary.get("points", {}).items():
        low, high = point.get("min", [None] * 3), point.get("max", [None] * 3)
        points.add_row(escape(name), point.get("kind", ""),
                       *[_num(v) for pair in zip(low, high, strict=True) for v in pair])
    out.append(points)
    envelope = summary.get("envelope") or {}
    largest = envelope.get("max_element_tension")
    if largest:
        out.append(Text(f"envelope from t = {_num(envelope.get('start'))} s "
                        f"({envelope.get('records', 0)} records): largest element tension "
                        f"{_num(largest['tension'])} {force} on {largest['line']} at "
                        f"{_num(largest['arc_length'])} {length} from end a"))
    counters = summary.get("counters") or {}
    if counters:
        out.append(Text("counters: " + ", ".join(f"{k} {v}" for k, v in counters.items())))
    return out


def _render_fatigue(summary: dict, units: str) -> list[RenderableType]:
    """Heading, then per method the damage and life [years] at both ends of every line."""
    curves = ", ".join(f"{t}: {c}" for t, c in summary.get("curves", {}).items())
    head = (f"fatigue ({summary.get('source', '')}, {curves}): "
            f"{summary.get('message', '')}")
    out: list[RenderableType] = [Text(head, style="bold")]
    for method, entry in summary.get("methods", {}).items():
        table = Table(title=escape(f"Fatigue, {method}: damage over "
                                   f"{_num(summary.get('duration'))} s and life [years]"))
        for name in ("line", "end", "damage", "life [years]"):
            table.add_column(name, justify="left" if name in ("line", "end") else "right")
        for name, damage in entry.get("damage", {}).items():
            life = entry.get("life_years", {}).get(name, {})
            for end in ("a", "b"):
                table.add_row(escape(name) if end == "a" else "", end,
                              _num(damage.get(f"end_{end}")), _num(life.get(f"end_{end}")))
        out.append(table)
        if entry.get("min_life_element") is not None:
            out.append(Text(f"least life of an element ({method}): "
                            f"{_num(entry.get('min_element_life_years'))} years "
                            f"(element {entry['min_life_element']})"))
    return out


def _render_extremes(summary: dict, units: str) -> list[RenderableType]:
    """Heading, then the most probable maximum, sampled maximum, mean, std and percentiles
    of the tension at both ends of every line."""
    force = _unit("force", units)
    head = (f"extremes ({summary.get('source', '')}, {summary.get('method', '')}): "
            f"{summary.get('message', '')}")
    out: list[RenderableType] = [Text(head, style="bold")]
    levels = list(summary.get("percentiles", {}))
    table = Table(title=escape(f"Line end tensions: most probable maximum over "
                               f"{_num(summary.get('duration'))} s [{force}]"))
    for name in ("line", "end", "MPM", "max", "mean", "std", *(f"p{q}" for q in levels)):
        table.add_column(name, justify="left" if name in ("line", "end") else "right")
    for name, mpm in summary.get("mpm", {}).items():
        for end in ("a", "b"):
            key = f"end_{end}"
            table.add_row(escape(name) if end == "a" else "", end, _num(mpm.get(key)),
                          *(_num(summary.get(k, {}).get(name, {}).get(key))
                            for k in ("maximum", "mean", "std")),
                          *(_num(summary["percentiles"][q].get(name, {}).get(key))
                            for q in levels))
    out.append(table)
    return out


def _render_offset(summary: dict, units: str) -> list[RenderableType]:
    """Heading, the stiffness at the undisplaced state, then per heading the restoring force
    along it and the fairlead tension of every line at each offset."""
    force, length = _unit("force", units), _unit("length", units)
    group = (f"body {summary.get('body')}" if summary.get("body")
             else "points " + ", ".join(summary.get("points", [])))
    out: list[RenderableType] = [Text(f"offset ({group}): {_status(summary.get('converged'))}: "
                                      f"{summary.get('message', '')}", style="bold")]
    stiffness = summary.get("stiffness")
    if stiffness is not None:
        about = ", ".join(_fmt(summary.get("reference", [])))
        table = Table(title=escape(f"Stiffness at zero offset about ({about}) "
                                   f"[{force}/{length}, {force}/rad, {force}*{length}/rad]"))
        for name in ("", "surge", "sway", "heave", "roll", "pitch", "yaw"):
            table.add_column(name, justify="left" if not name else "right")
        for name, row in zip(("surge", "sway", "heave", "roll", "pitch", "yaw"), stiffness,
                             strict=True):
            table.add_row(name, *_fmt(row))
        out.append(table)
    for entry in summary.get("headings", []):
        lines = list(entry.get("fairlead_tension", {}))
        table = Table(title=escape(f"Heading {_num(entry.get('heading'))} deg: restoring force "
                                   f"along the heading and fairlead tensions [{force}]"))
        for name in (f"offset [{length}]", "restoring force", *lines):
            table.add_column(escape(name), justify="right")
        for k, offset in enumerate(entry.get("offsets", [])):
            table.add_row(_num(offset), _num(entry["restoring_force"][k]),
                          *(_num(entry["fairlead_tension"][n][k]) for n in lines))
        out.append(table)
    return out


_RENDERERS = {"statics": _render_statics, "dynamics": _render_dynamics,
              "fatigue": _render_fatigue, "extremes": _render_extremes,
              "offset": _render_offset}


def _lines_table(lines: dict, force: str, length: str) -> Table:
    table = Table(title=escape(f"Lines (force of the line on its end point [{force}])"))
    for name in ("line", "end", "Fx", "Fy", "Fz", "tension", "max tension",
                 f"on seabed [{length}]"):
        table.add_column(escape(name), justify="left" if name in ("line", "end") else "right")
    for name, line in lines.items():
        for end in ("a", "b"):
            data = line.get(f"end_{end}", {})
            first = end == "a"
            table.add_row(escape(name) if first else "", end,
                          *_fmt(data.get("force", [None] * 3)),
                          _num(data.get("tension")),
                          _num(line.get("max_tension")) if first else "",
                          _num(line.get("seabed_length")) if first else "")
    return table


def _points_table(points: dict, force: str, length: str) -> Table:
    table = Table(title=escape(f"Points (position [{length}], stiffness [{force}/{length}])"))
    for name in ("point", "kind", "x", "y", "z", "stiffness"):
        table.add_column(name, justify="left" if name in ("point", "kind") else "right")
    for name, point in points.items():
        stiffness = point.get("stiffness")
        matrix = "-" if stiffness is None else "\n".join(
            "  ".join(f"{v:>11.4g}" if v is not None else f"{'nan':>11}" for v in row)
            for row in stiffness)
        table.add_row(escape(name), point.get("kind", ""),
                      *_fmt(point.get("position", [None] * 3)), matrix)
    return table


def _unit(dimension: str, units: str) -> str:
    return DIMENSIONS[dimension].unit("US" if units == "US" else "SI")


def _status(converged: Any) -> str:
    return "converged" if converged else "NOT converged"


def _num(value: Any) -> str:
    if value is None:
        return "-"
    return f"{float(value):.6g}"


def _fmt(values: Iterable[Any]) -> list[str]:
    return [_num(v) for v in values]


class _NullFile:
    """A write-only sink: the recorded console output is exported, not printed."""

    def write(self, text: str) -> int:
        return len(text)

    def flush(self) -> None:
        """Nothing to flush."""
