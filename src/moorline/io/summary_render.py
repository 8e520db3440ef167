"""The summary of a run as blocks of text and tables, for any renderer.

:func:`summary_blocks` turns a summary dict (:mod:`moorline.io.writers`) into a list of
:class:`Para` (a paragraph, maybe bold) and :class:`Grid` (a titled table of strings, each
column left- or right-justified). :mod:`moorline.io.plain_tables` lays them out as plain
text (``summary.txt``, and stdout when it is not a terminal: rich is not imported);
:func:`moorline.io.writers.render_summary` turns them into rich renderables for a terminal.
All text is literal (no markup).
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any, Literal

from .units import DIMENSIONS

__all__ = ["Block", "Grid", "Para", "summary_blocks"]


@dataclass
class Para:
    """A paragraph of literal text (wrapped at the output's width)."""

    text: str
    bold: bool = False


@dataclass
class Grid:
    """A titled table of literal strings; a cell may hold several lines."""

    title: str
    columns: list[tuple[str, Literal["left", "right"]]] = field(default_factory=list)
    rows: list[list[str]] = field(default_factory=list)

    def add_column(self, name: str, justify: Literal["left", "right"] = "left") -> None:
        """A column headed ``name``."""
        self.columns.append((name, justify))

    def add_row(self, *cells: str) -> None:
        """A row of cells, one per column."""
        self.rows.append(list(cells))


Block = Para | Grid


def summary_blocks(summary: dict) -> list[Block]:
    """The blocks (headings, paragraphs, tables) of a statics or run summary."""
    if "analyses" in summary:
        out: list[Block] = [Para(f"case {summary.get('case', '')}: "
                                 f"{_status(summary.get('converged'))}", bold=True)]
        for analysis in summary["analyses"]:
            out.extend(_render_analysis(analysis, summary.get("units", "SI")))
        return out
    return _render_analysis(summary, summary.get("units", "SI"))


def _render_analysis(summary: dict, units: str) -> list[Block]:
    """The tables of one analysis summary: statics and dynamics have their own, the other
    kinds a line with their status and message."""
    render = _RENDERERS.get(summary.get("kind", "statics"), _render_line)
    out = render(summary, units)
    if summary.get("design"):
        out.extend(_design_table(summary["design"], summary.get("units", units)))
    return out


def _design_table(design: dict, units: str) -> list[Block]:
    """Utilization, safety factor and pass/fail of every line (:mod:`moorline.design`)."""
    force = _unit("force", units)
    dnv = design.get("standard") == "DNV-OS-E301"
    what = f"{design.get('standard')} {design.get('edition', '')}, {design.get('condition')}, "\
        f"{design.get('analysis')}"
    if dnv:
        what += f", consequence class {design.get('consequence_class')}"
    table = Grid(f"Design checks ({what}) [{force}]")
    columns = ["line", "MBL", "T max", "T max / MBL", "MBL / T max",
               "design tension" if dnv else "required SF", "utilization", "check"]
    for name in columns:
        table.add_column(name, justify="left" if name in ("line", "check") else "right")
    for name, line in design.get("lines", {}).items():
        if line.get("passed") is None:
            table.add_row(name, "-", _num(line.get("max_tension")), "-", "-", "-", "-",
                          "no MBL: not checked")
            continue
        middle = (_num(line.get("design_tension")) if dnv
                  else f"{line.get('required_safety_factor'):.3g}")
        table.add_row(name, _num(line.get("MBL")), _num(line.get("max_tension")),
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
    return [table, Para("; ".join(notes))]


def _render_line(summary: dict, units: str) -> list[Block]:
    text = f"{summary.get('kind', '')}: {_status(summary.get('converged'))}"
    return [Para(f"{text}: {summary['message']}" if summary.get("message") else text)]


def _render_statics(summary: dict, units: str) -> list[Block]:
    units = summary.get("units", units)
    force, length = _unit("force", units), _unit("length", units)
    head = (f"{summary.get('case', '')} statics ({summary.get('method', '')}): "
            f"{_status(summary.get('converged'))} after {summary.get('iterations')} iterations")
    out: list[Block] = [Para(head, bold=True)]
    if summary.get("message") and not summary.get("converged"):
        out.append(Para(str(summary["message"])))
    out.append(_lines_table(summary.get("lines", {}), force, length))
    out.append(_points_table(summary.get("points", {}), force, length))
    return out


def _render_dynamics(summary: dict, units: str) -> list[Block]:
    """Heading, end-tension statistics per line, motion extremes per point, counters."""
    force, length = _unit("force", units), _unit("length", units)
    head = (f"dynamics: {summary.get('message', '')}, output t = "
            f"{_num(summary.get('time_start'))} to {_num(summary.get('time_end'))} s "
            f"({summary.get('records', 0)} records)")
    out: list[Block] = [Para(head, bold=True)]
    table = Grid(f"Line end tensions over the output records [{force}]")
    for name in ("line", "end", "max", "min", "mean", "std"):
        table.add_column(name, justify="left" if name in ("line", "end") else "right")
    for name, line in summary.get("lines", {}).items():
        for end in ("a", "b"):
            stats = line.get(f"end_{end}", {})
            table.add_row(name if end == "a" else "", end,
                          *_fmt(stats.get(k) for k in ("max", "min", "mean", "std")))
    out.append(table)
    points = Grid(f"Point motion extremes [{length}]")
    for name in ("point", "kind", "x min", "x max", "y min", "y max", "z min", "z max"):
        points.add_column(name, justify="left" if name in ("point", "kind") else "right")
    for name, point in summary.get("points", {}).items():
        low, high = point.get("min", [None] * 3), point.get("max", [None] * 3)
        points.add_row(name, point.get("kind", ""),
                       *[_num(v) for pair in zip(low, high, strict=True) for v in pair])
    out.append(points)
    envelope = summary.get("envelope") or {}
    largest = envelope.get("max_element_tension")
    if largest:
        out.append(Para(f"envelope from t = {_num(envelope.get('start'))} s "
                        f"({envelope.get('records', 0)} records): largest element tension "
                        f"{_num(largest['tension'])} {force} on {largest['line']} at "
                        f"{_num(largest['arc_length'])} {length} from end a"))
    counters = summary.get("counters") or {}
    if counters:
        out.append(Para("counters: " + ", ".join(f"{k} {v}" for k, v in counters.items())))
    return out


def _render_fatigue(summary: dict, units: str) -> list[Block]:
    """Heading, then per method the damage and life [years] at both ends of every line."""
    curves = ", ".join(f"{t}: {c}" for t, c in summary.get("curves", {}).items())
    head = (f"fatigue ({summary.get('source', '')}, {curves}): "
            f"{summary.get('message', '')}")
    out: list[Block] = [Para(head, bold=True)]
    for method, entry in summary.get("methods", {}).items():
        table = Grid(f"Fatigue, {method}: damage over "
                     f"{_num(summary.get('duration'))} s and life [years]")
        for name in ("line", "end", "damage", "life [years]"):
            table.add_column(name, justify="left" if name in ("line", "end") else "right")
        for name, damage in entry.get("damage", {}).items():
            life = entry.get("life_years", {}).get(name, {})
            for end in ("a", "b"):
                table.add_row(name if end == "a" else "", end,
                              _num(damage.get(f"end_{end}")), _num(life.get(f"end_{end}")))
        out.append(table)
        if entry.get("min_life_element") is not None:
            out.append(Para(f"least life of an element ({method}): "
                            f"{_num(entry.get('min_element_life_years'))} years "
                            f"(element {entry['min_life_element']})"))
    return out


def _render_extremes(summary: dict, units: str) -> list[Block]:
    """Heading, then the most probable maximum, sampled maximum, mean, std and percentiles
    of the tension at both ends of every line."""
    force = _unit("force", units)
    head = (f"extremes ({summary.get('source', '')}, {summary.get('method', '')}): "
            f"{summary.get('message', '')}")
    out: list[Block] = [Para(head, bold=True)]
    levels = list(summary.get("percentiles", {}))
    table = Grid(f"Line end tensions: most probable maximum over "
                 f"{_num(summary.get('duration'))} s [{force}]")
    for name in ("line", "end", "MPM", "max", "mean", "std", *(f"p{q}" for q in levels)):
        table.add_column(name, justify="left" if name in ("line", "end") else "right")
    for name, mpm in summary.get("mpm", {}).items():
        for end in ("a", "b"):
            key = f"end_{end}"
            table.add_row(name if end == "a" else "", end, _num(mpm.get(key)),
                          *(_num(summary.get(k, {}).get(name, {}).get(key))
                            for k in ("maximum", "mean", "std")),
                          *(_num(summary["percentiles"][q].get(name, {}).get(key))
                            for q in levels))
    out.append(table)
    return out


def _render_offset(summary: dict, units: str) -> list[Block]:
    """Heading, the stiffness at the undisplaced state, then per heading the restoring force
    along it and the fairlead tension of every line at each offset."""
    force, length = _unit("force", units), _unit("length", units)
    group = (f"body {summary.get('body')}" if summary.get("body")
             else "points " + ", ".join(summary.get("points", [])))
    out: list[Block] = [Para(f"offset ({group}): {_status(summary.get('converged'))}: "
                             f"{summary.get('message', '')}", bold=True)]
    stiffness = summary.get("stiffness")
    if stiffness is not None:
        about = ", ".join(_fmt(summary.get("reference", [])))
        table = Grid(f"Stiffness at zero offset about ({about}) "
                     f"[{force}/{length}, {force}/rad, {force}*{length}/rad]")
        for name in ("", "surge", "sway", "heave", "roll", "pitch", "yaw"):
            table.add_column(name, justify="left" if not name else "right")
        for name, row in zip(("surge", "sway", "heave", "roll", "pitch", "yaw"), stiffness,
                             strict=True):
            table.add_row(name, *_fmt(row))
        out.append(table)
    for entry in summary.get("headings", []):
        lines = list(entry.get("fairlead_tension", {}))
        table = Grid(f"Heading {_num(entry.get('heading'))} deg: restoring force "
                     f"along the heading and fairlead tensions [{force}]")
        for name in (f"offset [{length}]", "restoring force", *lines):
            table.add_column(name, justify="right")
        for k, offset in enumerate(entry.get("offsets", [])):
            table.add_row(_num(offset), _num(entry["restoring_force"][k]),
                          *(_num(entry["fairlead_tension"][n][k]) for n in lines))
        out.append(table)
    return out


_RENDERERS = {"statics": _render_statics, "dynamics": _render_dynamics,
              "fatigue": _render_fatigue, "extremes": _render_extremes,
              "offset": _render_offset}


def _lines_table(lines: dict, force: str, length: str) -> Grid:
    table = Grid(f"Lines (force of the line on its end point [{force}])")
    for name in ("line", "end", "Fx", "Fy", "Fz", "tension", "max tension",
                 f"on seabed [{length}]"):
        table.add_column(name, justify="left" if name in ("line", "end") else "right")
    for name, line in lines.items():
        for end in ("a", "b"):
            data = line.get(f"end_{end}", {})
            first = end == "a"
            table.add_row(name if first else "", end,
                          *_fmt(data.get("force", [None] * 3)),
                          _num(data.get("tension")),
                          _num(line.get("max_tension")) if first else "",
                          _num(line.get("seabed_length")) if first else "")
    return table


def _points_table(points: dict, force: str, length: str) -> Grid:
    table = Grid(f"Points (position [{length}], stiffness [{force}/{length}])")
    for name in ("point", "kind", "x", "y", "z", "stiffness"):
        table.add_column(name, justify="left" if name in ("point", "kind") else "right")
    for name, point in points.items():
        stiffness = point.get("stiffness")
        matrix = "-" if stiffness is None else "\n".join(
            "  ".join(f"{v:>11.4g}" if v is not None else f"{'nan':>11}" for v in row)
            for row in stiffness)
        table.add_row(name, point.get("kind", ""),
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
