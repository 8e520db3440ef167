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
twice: as JSON for scripts, and as readable tables for people (:mod:`moorline.io.summary_render`;
laid out without rich, :mod:`moorline.io.plain_tables`, unless rich is needed).
Non-finite numbers become ``null`` in JSON so that every output is strict JSON.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from .netcdf_write import nc_attrs, write_dataset

if TYPE_CHECKING:
    import xarray as xr
    from rich.console import RenderableType

    from .summary_render import Block

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
    """The summary rendered as plain-text tables (as rich lays them out at ``width``
    columns; by :mod:`moorline.io.plain_tables`, through rich only when that needs it)."""
    from .plain_tables import plain_text
    from .summary_render import summary_blocks

    blocks = summary_blocks(summary)
    text = plain_text(blocks, width)
    if text is not None:
        return text
    from rich.console import Console

    console = Console(width=width, record=True, file=_NullFile(), color_system=None)
    for renderable in _rich(blocks):
        console.print(renderable)
    return console.export_text()


def render_summary(summary: dict) -> list[RenderableType]:
    """Rich renderables (a heading and tables) of a statics or run summary."""
    from .summary_render import summary_blocks

    return _rich(summary_blocks(summary))


def _rich(blocks: list[Block]) -> list[RenderableType]:
    """The summary's blocks as rich renderables (text printed literally)."""
    from rich.markup import escape
    from rich.table import Table
    from rich.text import Text

    from .summary_render import Para

    out: list[RenderableType] = []
    for block in blocks:
        if isinstance(block, Para):
            out.append(Text(block.text, style="bold") if block.bold else Text(block.text))
            continue
        table = Table(title=escape(block.title))
        for name, justify in block.columns:
            table.add_column(escape(name), justify=justify)
        for row in block.rows:
            table.add_row(*(escape(cell) for cell in row))
        out.append(table)
    return out


class _NullFile:
    """A write-only sink: the recorded console output is exported, not printed."""

    def write(self, text: str) -> int:
        return len(text)

    def flush(self) -> None:
        """Nothing to flush."""
