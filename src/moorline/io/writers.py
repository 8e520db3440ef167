"""Result writers: NetCDF datasets and the run summary (``summary.json`` and ``summary.txt``).

The summary is a plain dict (the object ``moorline statics --json`` prints). It is written
twice: as JSON for scripts, and as a readable table (rendered with rich) for people.
Non-finite numbers become ``null`` in JSON so that every output is strict JSON.
"""

from __future__ import annotations

import json
import math
from collections.abc import Iterable
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr
from rich.console import Console, RenderableType
from rich.markup import escape
from rich.table import Table
from rich.text import Text

from .units import DIMENSIONS

__all__ = [
    "jsonable",
    "render_summary",
    "summary_json",
    "summary_text",
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
    ds.to_netcdf(path, engine="netcdf4")
    return path


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
    kind = summary.get("kind", "statics")
    if kind != "statics":
        return [Text(f"{kind}: {_status(summary.get('converged'))}")]
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
