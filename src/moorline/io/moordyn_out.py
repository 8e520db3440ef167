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
(:func:`default_channels`).

Per-line files (``--line-outputs FLAGS``): MoorDyn's ``<deck>_Line<n>.out``
(``Line::Output`` in ``source/Line.cpp``, same widths and number format, units *in*
parentheses) for the flags ``p``, ``v``, ``t``, ``s`` (:func:`line_out_text`). The deck's
``LineOutputs`` column is not carried into the case (only a comment of the converted case),
so the flags are given for every line at export.
"""

from __future__ import annotations

import logging
from pathlib import Path
from typing import Any

import numpy as np

from .moordyn_outputs import channel_columns, end_tension_channel, line_indices
from .writers import read_group, result_groups

__all__ = ["CHANNELS_ATTR", "default_channels", "export_moordyn", "line_out_text",
           "main_out_text"]

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
    return _table(ds, list(columns), [u for _, u in columns.values()],
                  [s for s, _ in columns.values()])


#: Per-line flags moorline writes (MoorDyn's ``Line::Output``, in its order) and the
#: dimension of each: node positions, node velocities, segment tensions, segment strains.
LINE_FLAGS = {"p": "length", "v": "velocity", "t": "force", "s": "-"}


def line_out_text(ds: Any, number: int, flags: str) -> str:
    """The text of MoorDyn's per-line file ``<deck>_Line<n>.out`` of line ``number`` (from
    1) for the output ``flags`` (MoorDyn's ``LineOutputs`` column; case-sensitive): ``p``
    ``Node<i>px/py/pz``, ``v`` ``Node<i>vx/vy/vz`` (nodes 0 to NumSegs from end A), ``t``
    ``Seg<i>Te`` (segment tension), ``s`` ``Seg<i>St`` (strain, the nodes' distance over the
    unstretched segment length minus 1), in MoorDyn's order; its other flags are not
    written (a warning). Layout of ``source/Line.cpp``: as the main file, the units in
    parentheses."""
    k = number - 1
    nodes, elements = line_indices(ds, k)
    position = np.asarray(ds["position"].values)[:, nodes]
    unit = {"length": str(ds["position"].attrs.get("units", "")),
            "velocity": str(ds["velocity"].attrs.get("units", "")),
            "force": str(ds["tension"].attrs.get("units", "")), "-": "-"}
    units: list[str] = []
    names: list[str] = []
    series: list[np.ndarray] = []
    for flag in (f for f in LINE_FLAGS if f in flags):
        if flag in "pv":
            values = position if flag == "p" else np.asarray(ds["velocity"].values)[:, nodes]
            names += [f"Node{i}{flag}{x}" for i in range(len(nodes)) for x in "xyz"]
            series += [values[:, i, j] for i in range(len(nodes)) for j in range(3)]
        elif flag == "t":
            names += [f"Seg{i}Te" for i in range(1, len(elements) + 1)]
            series += list(np.asarray(ds["tension"].values)[:, elements].T)
        else:
            length0 = np.diff(np.asarray(ds["line_arc_length"].values)[k, :len(nodes)])
            stretched = np.linalg.norm(np.diff(position, axis=1), axis=-1)
            names += [f"Seg{i}St" for i in range(1, len(elements) + 1)]
            series += list((stretched / length0 - 1.0).T)
        units += [f"({unit[LINE_FLAGS[flag]]})"] * (len(names) - len(units))
    ignored = sorted(set(flags) - set(LINE_FLAGS) - {"-"})
    if ignored:
        logging.getLogger(__name__).warning("line %d: output flags %s not written", number,
                                            ", ".join(ignored))
    return _table(ds, names, units, series)


def _table(ds: Any, names: list[str], units: list[str], series: list[np.ndarray]) -> str:
    """A table in MoorDyn's output layout: names, units, then the records of ``ds``."""
    head = f"{'Time':>{TIME_WIDTH}}" + "".join(f"{n:>{WIDTH}}" for n in names)
    unit_row = f"{'(s)':>{TIME_WIDTH}}" + "".join(f"{u:>{WIDTH}}" for u in units)
    time = np.asarray(ds["time"].values, dtype=float)
    values = np.column_stack([np.asarray(s, dtype=float) for s in series]) if series \
        else np.zeros((len(time), 0))
    rows = [f"{t:{TIME_WIDTH}.4f}" + "".join(f"{v:{WIDTH}.{PRECISION}e}" for v in row)
            for t, row in zip(time, values, strict=True)]
    return "\n".join([head, unit_row, *rows]) + "\n"


def export_moordyn(path: str | Path, directory: str | Path, line_flags: str = ""
                   ) -> list[Path]:
    """Write MoorDyn's main ``.out`` file of every dynamics group of a results file.

    Parameters
    ----------
    path
        ``results.nc``.
    directory
        Output directory (created if needed).
    line_flags
        MoorDyn line output flags (``p``, ``v``, ``t``, ``s``: :func:`line_out_text`) to
        write for every line as ``<name>_Line<n>.out``; empty: none.

    Returns
    -------
    list of Path
        ``<case>.out`` (then its line files) for a file with one dynamics group, ``<group>.out``
        per group with several; empty without dynamics groups.
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
        ds = read_group(path, group)
        stem = case if len(groups) == 1 else group or case
        written.append(directory / f"{stem}.out")
        written[-1].write_text(main_out_text(ds, channels), encoding="utf-8")
        for number in range(1, ds.sizes["line"] + 1) if line_flags.strip("-") else ():
            written.append(directory / f"{stem}_Line{number}.out")
            written[-1].write_text(line_out_text(ds, number, line_flags), encoding="utf-8")
    return written
