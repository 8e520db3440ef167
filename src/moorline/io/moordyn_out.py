"""MoorDyn's main output file (``<deck>.out``) from a dynamics group of a results file
(``moorline export --moordyn``), for post-processing scripts written for MoorDyn.

Layout of MoorDyn-C v2.7 (``source/MoorDyn2.cpp``: the channel titles and units written
after the initial condition, ``MoorDyn::WriteOutputs``; checked against the file moordyn
2.7.2 writes in ``tests/test_moordyn_out.py``):

- first row: ``Time`` right-aligned in 10 characters, then each channel name right-aligned
  in 20 (C++ ``setw(10)``, ``setw(20)``);
- second row (MoorDyn's ``WriteUnits``, on by default): ``(s)`` in 10 characters, then each
  channel's unit in 20, *without* parentheses (MoorDyn's ``UnitList``: ``N``, ``m``,
  ``m/s``); moorline writes the results' units (``lbf``, ``ft``, ``ft/s`` for US cases);
- one row per record: the time in fixed notation with 4 decimals in 10 characters
  (``%10.4f``), each channel in scientific notation with 7 decimals in 20 (``%20.7e``).

Rows are the group's output records, the first at t = 0 (MoorDyn writes its t = 0 row only
when ``dtOut`` is 0; with ``dtOut > 0`` its first row is at ``dtOut``). The channels are
the case's ``output.channels`` (a deck's ``OUTPUTS``: :mod:`moorline.io.moordyn_outputs`,
written to the results file by ``moorline run`` as the root attribute
``moordyn_channels``); names moorline cannot write are left out with a warning, as MoorDyn
leaves out the names it cannot read. Without channels MoorDyn writes the ``Time`` column
only; moorline writes ``FairTen<n>`` then ``AnchTen<n>`` of every line instead
(:data:`DEFAULT` names what was used).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from .moordyn_outputs import channel_columns, end_tension_channel
from .writers import read_group, result_groups

__all__ = ["CHANNELS_ATTR", "default_channels", "export_moordyn", "main_out_text"]

#: Root attribute of a results file holding the case's channels, space-separated.
CHANNELS_ATTR = "moordyn_channels"
TIME_WIDTH = 10
WIDTH = 20
PRECISION = 7


def default_channels(n_lines: int) -> tuple[str, ...]:
    """``FairTen1 ... FairTen<n>, AnchTen1 ... AnchTen<n>``: the end tensions of every line."""
    return tuple(end_tension_channel(k, end) for end in "ba" for k in range(1, n_lines + 1))


def main_out_text(ds: Any, channels: tuple[str, ...] | list[str]) -> str:
    """The text of MoorDyn's main ``.out`` file of a dynamics group (module docstring).

    Parameters
    ----------
    ds
        A dynamics group of a results file.
    channels
        MoorDyn channel names; empty: :func:`default_channels`.
    """
    columns = channel_columns(tuple(channels) or default_channels(ds.sizes["line"]), ds)
    head = f"{'Time':>{TIME_WIDTH}}" + "".join(f"{n:>{WIDTH}}" for n in columns)
    units = f"{'(s)':>{TIME_WIDTH}}" + "".join(f"{u:>{WIDTH}}" for _, u in columns.values())
    values = np.column_stack([np.asarray(s, dtype=float) for s, _ in columns.values()]) \
        if columns else np.zeros((ds.sizes["time"], 0))
    rows = [f"{t:{TIME_WIDTH}.4f}" + "".join(f"{v:{WIDTH}.{PRECISION}e}" for v in row)
            for t, row in zip(np.asarray(ds["time"].values, dtype=float), values, strict=True)]
    return "\n".join([head, units, *rows]) + "\n"


def export_moordyn(path: str | Path, directory: str | Path) -> list[Path]:
    """Write MoorDyn's main ``.out`` file of every dynamics group of a results file.

    Parameters
    ----------
    path
        ``results.nc``.
    directory
        Output directory (created if needed).

    Returns
    -------
    list of Path
        ``<case>.out`` for a file with one dynamics group, ``<group>.out`` per group with
        several; empty without dynamics groups.
    """
    import netCDF4

    with netCDF4.Dataset(Path(path), "r") as root:
        case = str(getattr(root, "case", "") or Path(path).stem)
        channels = str(getattr(root, CHANNELS_ATTR, "")).split()
    groups = [name for name, kind in result_groups(path).items() if kind == "dynamics"]
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    written = []
    for group in groups:
        target = directory / f"{case if len(groups) == 1 else group or case}.out"
        target.write_text(main_out_text(read_group(path, group), channels), encoding="utf-8")
        written.append(target)
    return written
