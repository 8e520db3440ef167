"""A MoorDyn deck's time settings and ``OUTPUTS`` channels, and those channels from a
moorline dynamics run.

Time settings: ``TMax`` (simulated time; MoorDyn v1 decks and drivers) makes the converted case
a statics then a dynamics analysis of that duration; ``dtOut`` becomes the output interval
(``output.every``). ``dtM`` is MoorDyn's explicit integration step (~1e-3 s) and is not used:
moorline's implicit Newmark step is ``min(dtOut, 0.05)`` s (0.05 s without ``dtOut``). Both
are written as comments at the top of the converted case.

Channels (MoorDyn-C v2.7, ``source/MoorDyn2.cpp`` reading ``OUTPUTS``, ``Line::GetLineOutput``,
and the ``.out`` file of moordyn 2.7.2 checked in ``tests/test_moordyn_io.py``): names are
read like MoorDyn (leading letters, number, letters, number, letters; case-insensitive).

- ``FairTen<n>``, ``AnchTen<n>``, ``L<n>N<m>T`` at an end node, ``L<n>NBT``/``L<n>NAT``: the
  magnitude of the net force on the line's end node. In moorline that is the end-point force
  (the top segment's tension plus the end node's share of weight, buoyancy and seabed
  contact). MoorDyn's API ``GetLineFairTen`` is something else: the top segment's tension,
  ``1-2 %`` lower on a chain (written here as ``FairSegTen<n>``/``AnchSegTen<n>``).
- ``L<n>N<m>T`` at an inner node: the mean of the two adjacent segments' tensions.
- ``L<n>N<m>PX|PY|PZ|VX|VY|VZ``: node position and velocity (node 0 at end A, NumSegs at B).
- ``L<n>N<m>FX|FY|FZ`` at an end node: the end-point force components (the force the line
  exerts on the point, moorline's convention).
- ``P<n>`` / ``Point<n>`` (and v1 ``Con<n>``) with ``PX..VZ``: point position and velocity;
  ``FX|FY|FZ`` (``T``: its magnitude): the sum of the forces of the lines on the point
  (MoorDyn's net point force also holds the point's own weight, buoyancy and drag: the same
  for points without mass, volume or drag, as fairleads and anchors usually are).

Line and point numbers are MoorDyn's: the n-th line and n-th point of the case, in order.
"""

from __future__ import annotations

import csv
import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..model import DynamicsSettings, OutputSettings, StaticsSettings

if TYPE_CHECKING:
    from ..model import System

#: moorline's implicit time step when the deck asks for a dynamics run [s].
DEFAULT_DT = 0.05
CHANNELS_FILE = "moordyn_channels.csv"
_WORD = re.compile(r"^([A-Z]*)(\d*)([A-Z]*)(\d*)([A-Z]*)$")
_NODE_QUANTITIES = {"PX", "PY", "PZ", "VX", "VY", "VZ", "T", "TEN", "FX", "FY", "FZ"}
_POINT_QUANTITIES = {"PX", "PY", "PZ", "VX", "VY", "VZ", "FX", "FY", "FZ", "T", "TEN"}


def _option(raw: Mapping[str, str], key: str) -> float | None:
    for k, v in raw.items():
        if k.lower() == key:
            try:
                return float(v)
            except ValueError:
                return None
    return None


def time_settings(raw: Mapping[str, str], outputs: tuple[str, ...], current: bool,
                  warn: Callable[[str], None]) -> tuple[tuple[Any, ...], OutputSettings]:
    """The converted case's analyses and output settings from a deck's options.

    Parameters
    ----------
    raw
        ``OPTIONS`` rows ``{key: value}``.
    outputs
        The deck's ``OUTPUTS`` channels (carried in ``output.channels``).
    current
        The deck's current was read: statics include the current drag.
    warn
        Called with each note (kept in the case's header comments).
    """
    statics = StaticsSettings(current_drag=True) if current else StaticsSettings()
    dtm, tmax, dtout = (_option(raw, k) for k in ("dtm", "tmax", "dtout"))
    every = dtout if dtout and dtout > 0 else OutputSettings().every
    output = OutputSettings(every=every, channels=outputs)
    if tmax and tmax > 0:
        dt = min(every, DEFAULT_DT) if dtout and dtout > 0 else DEFAULT_DT
        note = f"TMax = {tmax:g} s: a dynamics analysis of {tmax:g} s with dt = {dt:g} s"
        if dtm:
            note += (f" (dtM = {dtm:g} s is MoorDyn's explicit step, not needed by moorline's "
                     "implicit Newmark step)")
        warn(note + (f", output every dtOut = {dtout:g} s" if dtout else ""))
        return (statics, DynamicsSettings(duration=tmax, dt=dt)), output
    parts = [f"dtM = {dtm:g} s" if dtm else "", f"dtOut = {dtout:g} s" if dtout else ""]
    if any(parts):
        warn(f"{', '.join(p for p in parts if p)}: no TMax, so no dynamics analysis is made "
             "(statics only; dtOut, if given, is the case's output interval)")
    return (statics,), output


def time_options(system: System) -> dict[str, float]:
    """The deck options of ``system``'s time settings, as :func:`time_settings` reads them:
    ``TMax`` (the first dynamics analysis's duration) and ``dtOut`` (``output.every``, with a
    dynamics analysis or when it is not the default). moorline's implicit step is not
    MoorDyn's ``dtM`` (an explicit step, about 100 times smaller) and is not written."""
    dynamics = system.first("dynamics")
    options: dict[str, float] = {}
    if dynamics is not None:
        options["TMax"] = float(dynamics.duration)
    if dynamics is not None or system.output.every != OutputSettings().every:
        options["dtOut"] = float(system.output.every)
    return options


def deck_channels(system: System, warn: Callable[[str], None] | None = None) -> list[str]:
    """The ``OUTPUTS`` rows of ``system``'s channels (one name a row): those moorline can
    compute on this system, each with a warning for the others. MoorDyn-C v2.7 refuses a
    deck naming a line, point, rod or body it does not have (or a node beyond
    ``NumSegs``), and the names moorline does not read may be such names (``R1N2T``,
    ``Body1PX`` of a deck whose rods and bodies became points); moorline-only names
    (``FairSegTen<n>``) and v1 names (``Con<n>FX``) are kept: MoorDyn skips them with a
    warning."""
    import logging

    warn = warn or logging.getLogger(__name__).warning
    kept = []
    for name in system.output.channels:
        channel = parse_channel(name)
        problem = "not supported by moorline" if channel is None else _missing(channel, system)
        if problem:
            warn(f"output channel {name!r} not written to the deck: {problem}")
        else:
            kept.append(name)
    return kept


def _missing(channel: Channel, system: System) -> str:
    """Why ``system`` has not the object or node ``channel`` names ('' when it has)."""
    objects = list(system.points if channel.what == "point" else system.lines)
    if not 1 <= channel.number <= len(objects):
        return f"there are {len(objects)} {channel.what}s"
    if channel.what == "line" and isinstance(channel.node, int):
        segments = system.lines[objects[channel.number - 1]].segments
        if channel.node > segments:
            return f"line {channel.number} has nodes 0..{segments}"
    return ""


def output_channels(section: Any, warn: Callable[[str], None]) -> tuple[str, ...]:
    """The channel names of an ``OUTPUTS`` section (``END`` and commas dropped)."""
    if section is None:
        return ()
    names: list[str] = []
    for row in section.rows:
        for token in row.tokens:
            for word in filter(None, token.split(",")):
                if word.upper() == "END":
                    continue
                if parse_channel(word) is None:
                    warn(f"OUTPUTS: channel {word!r} (line {row.lineno}) is not supported by "
                         "moorline and will not be written")
                names.append(word)
    return tuple(names)


@dataclass(frozen=True)
class Channel:
    """One MoorDyn output channel: ``what`` (``line`` or ``point``), MoorDyn's object number,
    ``node`` (line channels: a node number, ``"A"`` or ``"B"``) and the quantity."""

    name: str
    what: str
    number: int
    node: int | str | None
    quantity: str


#: MoorDyn's channel names of the end tensions: end b (the fairlead) and end a (the anchor).
END_TENSION_NAMES = {"b": "FairTen", "a": "AnchTen"}


def end_tension_channel(number: int, end: str) -> str:
    """MoorDyn's name of the tension channel at ``end`` (``"a"`` or ``"b"``) of line
    ``number`` (from 1): ``FairTen<n>`` (end b) or ``AnchTen<n>`` (end a)."""
    return f"{END_TENSION_NAMES[end]}{number}"


def parse_channel(name: str) -> Channel | None:
    """Read a channel name as MoorDyn does; None when moorline cannot write it."""
    match = _WORD.match(name.upper())
    if match is None:
        return None
    let1, num1, let2, num2, let3 = match.groups()
    if not num1:
        return None
    number = int(num1)
    ends = [n.upper() for n in END_TENSION_NAMES.values()]
    if let1 in (*ends, *(n[:4] + "SEG" + n[4:] for n in ends)) and not let2:
        end = "B" if let1.startswith("FAIR") else "A"
        return Channel(name, "line", number, end, "SEGTEN" if "SEG" in let1 else "T")
    if let1 in ("L", "LINE"):
        if let3:
            node: int | str = int(num2)
            quantity = let3 if let2 == "N" else ""
        elif let2[:2] in ("NA", "NB") and not num2:
            node, quantity = let2[1], let2[2:]
        else:
            return None
        quantity = "T" if quantity == "TEN" else quantity
        return Channel(name, "line", number, node, quantity) if quantity in \
            _NODE_QUANTITIES else None
    if let1 in ("P", "POINT", "CON", "CONNECT") and not num2 and let2 in _POINT_QUANTITIES:
        return Channel(name, "point", number, None, "T" if let2 == "TEN" else let2)
    return None


def line_indices(ds: Any, k: int) -> tuple[np.ndarray, np.ndarray]:
    """Node indices of the ``k``-th line from end A to end B (``line_nodes``) and its
    element indices in that order (the mesh numbers a line's elements from end A)."""
    nodes = np.asarray(ds["line_nodes"].values)[k]
    line = str(ds["line"].values[k])
    return nodes[nodes >= 0], np.flatnonzero(np.asarray(ds["element_line"].values) == line)


def channel_series(channel: Channel, ds: Any) -> np.ndarray:
    """The channel's time series from a dynamics group ``ds``.

    The group alone numbers the objects as MoorDyn does: the n-th ``point`` and ``line`` of
    the group are those of the case, in order; ``line_nodes`` runs from end A (its first
    node is the node of the point at end A) to end B.

    Raises
    ------
    IndexError
        No such line or point, or a node beyond the line's ``NumSegs``.
    """
    xyz = "XYZ"
    count = ds.sizes["point" if channel.what == "point" else "line"]
    if not 1 <= channel.number <= count:
        raise IndexError(f"{channel.name}: there are {count} {channel.what}s")
    end_force = np.asarray(ds["end_force"].values)
    if channel.what == "point":
        node = int(ds["point_node"].values[channel.number - 1])
        if channel.quantity[0] in "PV":
            var = "position" if channel.quantity[0] == "P" else "velocity"
            return np.asarray(ds[var].values)[:, node, xyz.index(channel.quantity[1])]
        total = np.zeros((ds.sizes["time"], 3))
        for k in range(ds.sizes["line"]):
            nodes, _ = line_indices(ds, k)
            for j, end_node in enumerate((nodes[0], nodes[-1])):
                if int(end_node) == node:
                    total = total + end_force[:, k, j]
        if channel.quantity == "T":
            return np.linalg.norm(total, axis=-1)
        return total[:, xyz.index(channel.quantity[1])]
    k = channel.number - 1
    nodes, elements = line_indices(ds, k)
    n_seg = len(elements)
    node = {"A": 0, "B": n_seg}.get(channel.node, channel.node)  # type: ignore[arg-type]
    if not 0 <= int(node) <= n_seg:
        raise IndexError(f"{channel.name}: line {channel.number} has nodes 0..{n_seg}")
    tension = np.asarray(ds["tension"].values)[:, elements]
    if channel.quantity == "SEGTEN":
        return tension[:, 0 if node == 0 else -1]
    end = 0 if node == 0 else 1 if node == n_seg else None
    if channel.quantity == "T":
        if end is not None:
            return np.linalg.norm(end_force[:, k, end], axis=-1)
        return 0.5 * (tension[:, node - 1] + tension[:, node])
    if channel.quantity[0] == "F":
        if end is None:
            return np.full(ds.sizes["time"], np.nan)
        return end_force[:, k, end, xyz.index(channel.quantity[1])]
    var = "position" if channel.quantity[0] == "P" else "velocity"
    return np.asarray(ds[var].values)[:, int(nodes[node]), xyz.index(channel.quantity[1])]


def channel_unit(channel: Channel, ds: Any) -> str:
    """The unit of a channel in the group's unit system (``N``, ``m``, ``m/s``; ``lbf``,
    ``ft``, ``ft/s`` for US cases): that of ``end_force``, ``position`` or ``velocity``."""
    kind = channel.quantity[0]
    var = "position" if kind == "P" else "velocity" if kind == "V" else "end_force"
    return str(ds[var].attrs.get("units", ""))


def channel_columns(names: tuple[str, ...] | list[str], ds: Any
                    ) -> dict[str, tuple[np.ndarray, str]]:
    """``{name: (series, unit)}`` of the channels moorline can write from a dynamics group,
    in order; the others (not supported, or no such line, point or node) are left out with
    a warning, as MoorDyn leaves out the names it cannot read."""
    import logging

    log = logging.getLogger(__name__)
    columns: dict[str, tuple[np.ndarray, str]] = {}
    for name in names:
        channel = parse_channel(name)
        try:
            if channel is None:
                raise IndexError(f"{name}: not supported")
            columns[name] = (channel_series(channel, ds), channel_unit(channel, ds))
        except IndexError as exc:
            log.warning("output channel %r not written (%s)", name, exc)
    return columns


def write_channels(ds: Any, system: System, path: Path) -> Path | None:
    """Write ``system.output.channels`` from a dynamics group as a CSV file (``Time`` then
    one column per channel, MoorDyn's names; unsupported or out-of-range channels skipped
    with a warning, :func:`channel_columns`). None when the case lists no channels."""
    if not system.output.channels:
        return None
    columns = {"Time": np.asarray(ds["time"].values, dtype=float)}
    columns.update({name: series for name, (series, _) in
                    channel_columns(system.output.channels, ds).items()})
    with path.open("w", newline="", encoding="utf-8") as handle:
        writer = csv.writer(handle)
        writer.writerow(list(columns))
        for row in zip(*columns.values(), strict=True):
            writer.writerow([repr(float(v)) for v in row])
    return path
