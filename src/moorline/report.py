"""The run report: ``report.html``, one self-contained page of a case's run.

``moorline run`` (and ``statics``) write it into ``DIR/<case>/`` beside the summary: the run's
status at the top, then the inputs (environment, line types, lines, points, bodies, the
analyses), the statics tables, the stiffness matrices, the design checks, the dynamics
statistics and tension envelopes, the offset, fatigue, extremes and other analyses' results,
and every plot the run wrote. The page needs nothing else: CSS is inline, the PNG plots are
embedded as base64 ``data:`` URIs, and there is no script. Every name and text from the case
or the summary is HTML-escaped.

The numbers are those of the run summary (:func:`moorline.io.writers.render_summary` prints
the same dict as text); the inputs are read from the loaded case.
"""

from __future__ import annotations

import base64
import dataclasses
import html
from collections.abc import Iterable, Sequence
from pathlib import Path
from typing import Any

from . import __version__
from .io.units import DIMENSIONS

__all__ = ["OPTIONAL_SECTIONS", "REPORT_FILE", "SECTIONS", "render_report", "write_report"]

REPORT_FILE = "report.html"

SECTIONS: dict[str, str] = {
    "status": "Status",
    "inputs": "Inputs",
    "statics": "Statics",
    "stiffness": "Stiffness",
    "design": "Design checks",
    "dynamics": "Dynamics statistics",
    "envelopes": "Envelopes",
    "plots": "Plots",
}
"""The sections every report has (id -> heading); the offset, fatigue, extremes and other
analyses' sections (:data:`OPTIONAL_SECTIONS`) are added when the run has them."""

OPTIONAL_SECTIONS: dict[str, str] = {
    "offset": "Offset",
    "fatigue": "Fatigue",
    "extremes": "Extremes",
    "other": "Other analyses",
}

_DOFS = ("surge", "sway", "heave", "roll", "pitch", "yaw")

_CSS = """
body{font-family:system-ui,-apple-system,"Segoe UI",Helvetica,Arial,sans-serif;margin:0;
color:#1d2433;background:#fff;line-height:1.4}
header{background:#14305a;color:#fff;padding:1em 2em}
header h1{margin:0 0 .3em 0;font-size:1.6em}
header a{color:#cfe0ff}
nav{font-size:.9em}nav a{margin-right:1em}
main{padding:0 2em 2em 2em;max-width:1400px}
section{margin-top:1.5em;border-top:1px solid #ccd3de}
h2{color:#14305a;margin:.6em 0 .4em 0}h3{margin:.9em 0 .3em 0;font-size:1.05em}
table{border-collapse:collapse;margin:.4em 0 .8em 0;font-size:.9em}
caption{text-align:left;font-weight:600;padding:.2em 0}
th,td{border:1px solid #ccd3de;padding:.2em .6em;vertical-align:top}
th{background:#eef2f8;text-align:left}
td.num{text-align:right;font-variant-numeric:tabular-nums;white-space:nowrap}
.banner{display:inline-block;padding:.35em .9em;border-radius:4px;font-weight:700}
.ok{background:#d9f2df;color:#135c25}.bad{background:#fbdada;color:#8a1010}
.unknown{background:#fff1c9;color:#6b5000}
td.ok,td.bad,td.unknown{font-weight:700}
.note{color:#4a5468;font-size:.88em;margin:.2em 0}
figure{margin:.8em 0 1.2em 0}figure img{max-width:100%;border:1px solid #ccd3de}
figcaption{font-size:.88em;color:#4a5468}
.matrices{display:flex;flex-wrap:wrap;gap:0 2em}.matrix caption{max-width:28em}
"""


class _Html(str):
    """Markup that is already safe (not escaped again): a table cell with its ``<td>``."""


def _e(value: Any) -> str:
    """``value`` as escaped text (markup of :class:`_Html` as it is)."""
    return value if isinstance(value, _Html) else html.escape(str(value), quote=True)


def _num(value: Any, digits: int = 6) -> str:
    if value is None or isinstance(value, str):
        return "-" if value is None else value
    if isinstance(value, bool):
        return str(value)
    try:
        return f"{float(value):.{digits}g}"
    except (TypeError, ValueError):
        return str(value)


def _table(headers: Sequence[Any], rows: Iterable[Sequence[Any]], caption: str = "",
           text_columns: int = 1) -> str:
    """An HTML table; the first ``text_columns`` columns are text, the others numbers
    (formatted to 6 significant digits); an :class:`_Html` cell is a whole ``<td>``."""
    head = "".join(f"<th>{_e(h)}</th>" for h in headers)
    body = []
    for row in rows:
        cells = []
        for k, cell in enumerate(row):
            if isinstance(cell, _Html):
                cells.append(cell)
            elif k < text_columns or isinstance(cell, str):
                cells.append(f"<td>{_e(cell)}</td>")
            else:
                cells.append(f'<td class="num">{_e(_num(cell))}</td>')
        body.append("<tr>" + "".join(cells) + "</tr>")
    cap = f"<caption>{_e(caption)}</caption>" if caption else ""
    return f"<table>{cap}<thead><tr>{head}</tr></thead><tbody>{''.join(body)}</tbody></table>"


def _note(text: str) -> str:
    return f'<p class="note">{_e(text)}</p>'


def _unit(dimension: str, units: str) -> str:
    """The unit of ``dimension`` in the case's system, powers as superscripts."""
    unit = DIMENSIONS[dimension].unit("US" if units == "US" else "SI")
    return unit.replace("**2", "\u00b2").replace("**3", "\u00b3")


def _force_scale(values: Iterable[Any], units: str) -> tuple[float, str]:
    """Divisor and unit for a column of forces: kN or MN (SI), kip (US) by magnitude."""
    finite = [abs(float(v)) for v in values if isinstance(v, int | float) and v == v]
    largest = max(finite, default=0.0)
    if units == "US":
        return (1.0e3, "kip") if largest >= 1.0e4 else (1.0, "lbf")
    if largest >= 1.0e7:
        return 1.0e6, "MN"
    if largest >= 1.0e4:
        return 1.0e3, "kN"
    return 1.0, "N"


def _scaled(value: Any, factor: float) -> Any:
    return None if value is None else float(value) / factor


def _status_cell(passed: Any, note: str = "") -> _Html:
    if passed is None:
        return _Html(f'<td class="unknown">{_e(note or "not checked")}</td>')
    return _Html('<td class="ok">pass</td>' if passed else '<td class="bad">FAIL</td>')


def _labels(kinds: list[str]) -> list[str]:
    """Headings of the analyses: the kind, numbered when a kind repeats (as the groups)."""
    from .runners import _labels as group_labels

    return group_labels(kinds)


# ----------------------------------------------------------------------------- sections


def _status(summary: dict[str, Any]) -> tuple[str, str, str]:
    """(css class, headline, details) of the run's status."""
    analyses = summary["analyses"]
    if summary.get("status"):
        return "bad", str(summary["status"]), str(summary.get("message", ""))
    failed = [a for a in analyses if not a.get("converged", True)]
    if failed:
        return ("bad", f"{failed[0].get('kind', 'analysis')} failed",
                str(failed[0].get("message", "")))
    if not analyses:
        return "unknown", "no analysis ran", ""
    return "ok", "converged" if summary.get("converged", True) else "NOT converged", \
        f"{len(analyses)} analys{'is' if len(analyses) == 1 else 'es'} completed"


def _status_section(summary: dict[str, Any], labels: list[str]) -> str:
    rows = [[label, a.get("kind", ""), a.get("status", "converged" if a.get("converged")
                                              else "failed"), a.get("message", "")]
            for label, a in zip(labels, summary["analyses"], strict=True)]
    return _table(["analysis", "kind", "status", "message"], rows, text_columns=4)


def _fields(obj: Any, skip: tuple[str, ...] = ()) -> list[tuple[str, Any]]:
    """The fields of a settings dataclass as (name, value), nested ones flattened."""
    out: list[tuple[str, Any]] = []
    for f in dataclasses.fields(obj):
        if f.name in skip:
            continue
        value = getattr(obj, f.name)
        if dataclasses.is_dataclass(value):
            out += [(f"{f.name}.{k}", v) for k, v in _fields(value)]
        else:
            out.append((f.name, value))
    return out


def _value(value: Any) -> str:
    if isinstance(value, float | int) and not isinstance(value, bool):
        return _num(value)
    if isinstance(value, tuple | list):
        if len(value) > 8:
            return f"[{', '.join(_value(v) for v in value[:8])}, ... ({len(value)} values)]"
        return f"[{', '.join(_value(v) for v in value)}]"
    return "-" if value is None else str(value)


_ENV_UNITS = {"depth": "length", "water_density": "mass/length^3", "gravity": "acceleration",
              "seabed.stiffness": "force/length^3", "seabed.damping": "force*time/length^3",
              "seabed.slip_velocity": "velocity", "current.speed": "velocity",
              "current.z_levels": "length", "current.speeds": "velocity",
              "waves.height": "length", "waves.period": "time",
              "waves.record_length": "time", "waves.omega_max": "1/time",
              "waves.components.omegas": "1/time", "waves.components.amplitudes": "length"}
"""Dimensions of the environment's fields (headings and phases are in degrees)."""

_RANDOM_ONLY = ("spectrum", "gamma", "amplitudes", "seed", "record_length", "n_frequencies",
                "omega_max")


def _environment_rows(environment: Any, units: str) -> list[list[str]]:
    """One row per part of the environment (water, seabed, current, waves) listing its
    settings with units; unset values and the random-sea settings of regular waves left
    out."""
    groups: dict[str, list[str]] = {}
    waves = environment.waves.kind
    for name, value in _fields(environment):
        part, _, key = name.rpartition(".")
        if value is None or value == () or (part == "waves" and (
                (waves == "none" and key != "kind") or (waves != "random"
                                                       and key in _RANDOM_ONLY)
                or (waves == "components" and key in ("height", "period", "phase_deg")))):
            continue
        unit = (_unit(_ENV_UNITS[name], units) if name in _ENV_UNITS
                else "deg" if key.endswith("_deg") else "")
        groups.setdefault(part or "water", []).append(
            f"{key} {_value(value)}{' ' + unit if unit else ''}")
    return [[part, ", ".join(items)] for part, items in groups.items()]


def _inputs_section(system: Any, units: str) -> str:
    length, force, mass = (_unit(d, units) for d in ("length", "force", "mass/length"))
    parts = [_table(["case", "units", "case file"],
                    [[system.name, units, system.source or "-"]], text_columns=3)]
    parts.append(_table(["", "settings"], _environment_rows(system.environment, units),
                        "Environment", text_columns=2))
    types = list(system.line_types.values())
    scale, funit = _force_scale([t.EA for t in types] + [t.MBL for t in types], units)
    parts.append(_table(
        ["line type", "catalogue", f"nominal d [{length}]", f"d [{length}]",
         f"mass/length [{mass}]", f"EA [{funit}]", f"MBL [{funit}]", "Cd", "Ca", "Ct", "Cat",
         "material"],
        [[t.name, t.catalog or "-", t.nominal_diameter, t.diameter, t.mass_per_length,
          _scaled(t.EA, scale), _scaled(t.MBL, scale), t.Cd, t.Ca, t.Ct, t.Cat,
          t.material + (" (load-strain table)" if t.EA_table else "")] for t in types],
        "Line types", text_columns=2))
    parts.append(_table(["line", "type", f"length [{length}]", "segments", "end a", "end b"],
                        [[n.name, n.line_type, n.length, n.segments, n.end_a, n.end_b]
                         for n in system.lines.values()], "Lines", text_columns=2))
    rows = []
    for p in system.points.values():
        motion = "-"
        if p.motion is not None:
            motion = (f"harmonic, amplitude {_value(p.motion.amplitude)} {length}, period "
                      f"{_num(p.motion.period)} s" if p.motion.kind == "harmonic"
                      else f"table of {len(p.motion.times)} times")
        rows.append([p.name, p.kind, *p.position, p.body or "-", p.mass, p.volume, motion])
    parts.append(_table(["point", "kind", "x", "y", "z", "body", f"mass [{_unit('mass', units)}]",
                         f"volume [{_unit('volume', units)}]", "motion"], rows,
                        f"Points (position [{length}])", text_columns=2))
    if system.bodies:
        parts.append(_table(
            ["body", "kind", "x", "y", "z", "roll", "pitch", "yaw",
             f"mass [{_unit('mass', units)}]", "hydrostatics"],
            [[b.name, b.kind, *b.position, *b.rotation, b.mass, b.hydrostatics.kind]
             for b in system.bodies.values()],
            f"Bodies (position [{length}], rotation [deg])", text_columns=2))
    else:
        parts.append(_note("Bodies: none in this case."))
    rows = [[k + 1, getattr(a, "kind", type(a).__name__),
             ", ".join(f"{n} {_value(v)}" for n, v in _fields(a, ("kind",)))]
            for k, a in enumerate(system.analyses)]
    parts.append(_table(["#", "kind", "settings"], rows, "Analyses", text_columns=3))
    if system.design is not None:
        parts.append(_note("design settings: " + ", ".join(
            f"{n} {_value(v)}" for n, v in _fields(system.design))))
    return "".join(parts)


def _statics_section(entries: list[tuple[str, dict]], units: str) -> str:
    if not entries:
        return _note("No statics analysis in this run.")
    length = _unit("length", units)
    parts = []
    for label, s in entries:
        lines = s.get("lines", {})
        forces = [v for line in lines.values() for end in ("end_a", "end_b")
                  for v in [*line.get(end, {}).get("force", []), line.get(end, {}).get("tension")]]
        scale, funit = _force_scale(forces, units)
        parts.append(f"<h3>{_e(label)}: {_e(s.get('method', ''))}, {_e(s.get('message', ''))}"
                     "</h3>")
        rows = []
        for name, line in lines.items():
            for end in ("a", "b"):
                data = line.get(f"end_{end}", {})
                first = end == "a"
                rows.append([name if first else "", end,
                             *(_scaled(v, scale) for v in data.get("force", [None] * 3)),
                             _scaled(data.get("tension"), scale),
                             _scaled(line.get("max_tension"), scale) if first else "",
                             line.get("seabed_length") if first else ""])
        parts.append(_table(["line", "end", "Fx", "Fy", "Fz", "tension", "max tension",
                             f"on seabed [{length}]"], rows,
                            f"Line end forces (of the line on its end point) and tensions "
                            f"[{funit}]", text_columns=2))
        parts.append(_table(["point", "kind", "x", "y", "z"],
                            [[n, p.get("kind", ""), *p.get("position", [None] * 3)]
                             for n, p in s.get("points", {}).items()],
                            f"Point positions [{length}]", text_columns=2))
        bodies = s.get("bodies", {})
        if bodies:
            parts.append(_table(["body", "x", "y", "z", "roll", "pitch", "yaw"],
                                [[n, *b.get("position", []), *b.get("rotation_deg", [])]
                                 for n, b in bodies.items()],
                                f"Body poses [{length}, deg]"))
    return "".join(parts)


def _matrix(matrix: Sequence[Sequence[Any]], names: Sequence[str], caption: str) -> str:
    return '<div class="matrix">' + _table(
        ["", *names], [[n, *row] for n, row in zip(names, matrix, strict=False)],
        caption) + "</div>"


def _stiffness_section(statics: list[tuple[str, dict]], offsets: list[tuple[str, dict]],
                       units: str) -> str:
    force, length = _unit("force", units), _unit("length", units)
    parts = []
    for label, s in statics:
        for name, point in s.get("points", {}).items():
            if point.get("stiffness") is not None:
                parts.append(_matrix(point["stiffness"], ("x", "y", "z"),
                                     f"{label}: point {name}, 3x3 stiffness [{force}/{length}]"))
        for name, body in s.get("bodies", {}).items():
            if body.get("mooring_stiffness") is not None:
                parts.append(_matrix(body["mooring_stiffness"], _DOFS,
                                     f"{label}: body {name}, 6x6 mooring stiffness about its "
                                     f"origin [{force}/{length}, {force}/rad, "
                                     f"{force}*{length}/rad]"))
    for label, s in offsets:
        if s.get("stiffness") is not None:
            group = (f"body {s['body']}" if s.get("body")
                     else "points " + ", ".join(s.get("points", [])))
            parts.append(_matrix(s["stiffness"], _DOFS,
                                 f"{label}: {group}, 6x6 stiffness at zero offset about "
                                 f"({', '.join(_num(v) for v in s.get('reference', []))}) "
                                 f"[{force}/{length}, {force}/rad, {force}*{length}/rad]"))
    if parts:
        return '<div class="matrices">' + "".join(parts) + "</div>"
    return _note("No stiffness in this run (it is computed at a converged "
                                   "static equilibrium for free and prescribed points, bodies "
                                   "and offset groups).")


def _design_section(entries: list[tuple[str, dict]], units: str) -> str:
    entries = [(label, s["design"]) for label, s in entries if s.get("design")]
    if not entries:
        return _note("No design checks in this run.")
    parts = []
    for label, design in entries:
        lines = design.get("lines", {})
        scale, funit = _force_scale([v for line in lines.values()
                                     for v in (line.get("MBL"), line.get("max_tension"))], units)
        dnv = design.get("standard") == "DNV-OS-E301"
        overall = design.get("passed")
        verdict = ("not checked" if overall is None else "pass" if overall else "FAIL")
        css = "unknown" if overall is None else "ok" if overall else "bad"
        what = (f"{design.get('standard', '')} {design.get('edition', '')}, "
                f"{design.get('condition', '')}, {design.get('analysis', '')}")
        if dnv:
            what += f", consequence class {design.get('consequence_class')}"
        parts.append(f'<h3>{_e(label)}: {_e(what)} <span class="banner {css}">{_e(verdict)}'
                     "</span></h3>")
        rows = []
        for name, line in lines.items():
            if line.get("passed") is None:
                rows.append([name, _scaled(line.get("MBL"), scale),
                             _scaled(line.get("max_tension"), scale), None, None, None, None,
                             None, _status_cell(None, line.get("note", ""))])
                continue
            rows.append([name, _scaled(line.get("MBL"), scale),
                         _scaled(line.get("max_tension"), scale),
                         _scaled(line.get("mean_tension"), scale), line.get("utilization"),
                         line.get("safety_factor"),
                         _scaled(line.get("design_tension"), scale) if dnv
                         else line.get("required_safety_factor"),
                         line.get("design_utilization"), _status_cell(line.get("passed"))])
        parts.append(_table(["line", f"MBL [{funit}]", f"T max [{funit}]",
                             f"T mean [{funit}]", "utilization T max / MBL",
                             "safety factor MBL / T max",
                             f"design tension [{funit}]" if dnv else "required safety factor",
                             "design utilization", "check"], rows))
        notes = [f"tension: {design.get('basis', '')}",
                 f"factors: {design.get('title', '')}, {design.get('clause', '')}"]
        if not design.get("verified", True):
            notes.append("factors as commonly cited; not checked against the standard's text")
        notes += [str(design[k]) for k in ("note", "warning") if design.get(k)]
        parts.extend(_note(n) for n in notes)
    return "".join(parts)


def _dynamics_section(entries: list[tuple[str, dict]], units: str) -> str:
    if not entries:
        return _note("No dynamics analysis in this run.")
    length = _unit("length", units)
    parts = []
    for label, s in entries:
        lines = s.get("lines", {})
        parts.append(f"<h3>{_e(label)}: {_e(s.get('message', ''))}, output t = "
                     f"{_e(_num(s.get('time_start')))} to {_e(_num(s.get('time_end')))} s "
                     f"({_e(s.get('records', 0))} records, dt {_e(_num(s.get('dt')))} s)</h3>")
        stats = ("max", "min", "mean", "std")
        keys = [k for k in ("end_a", "end_b", "segment_a", "segment_b")
                if any(k in line for line in lines.values())]
        scale, funit = _force_scale([line.get(k, {}).get("max") for line in lines.values()
                                     for k in keys], units)
        rows = [[name if k == 0 else "", key.replace("_", " "),
                 *(_scaled(line.get(key, {}).get(q), scale) for q in stats)]
                for name, line in lines.items() for k, key in enumerate(keys)]
        parts.append(_table(["line", "where", *stats], rows,
                            f"Line tensions over the output records [{funit}]", text_columns=2))
        if s.get("tension_note"):
            parts.append(_note(s["tension_note"]))
        rows = [[n, p.get("kind", ""), *(v for pair in zip(p.get("min", [None] * 3),
                                                          p.get("max", [None] * 3), strict=True)
                                         for v in pair)]
                for n, p in s.get("points", {}).items()]
        parts.append(_table(["point", "kind", "x min", "x max", "y min", "y max", "z min",
                             "z max"], rows, f"Point motion extremes [{length}]",
                            text_columns=2))
        counters = s.get("counters") or {}
        if counters:
            parts.append(_note("solver counters: " + ", ".join(f"{k} {v}"
                                                               for k, v in counters.items())))
    return "".join(parts)


def _envelope_section(entries: list[tuple[str, dict]], units: str, images: list[Path]) -> str:
    parts = []
    length = _unit("length", units)
    for label, s in entries:
        envelope = s.get("envelope") or {}
        largest = envelope.get("max_element_tension")
        if largest:
            scale, funit = _force_scale([largest.get("tension")], units)
            parts.append(_table(
                ["analysis", "from t [s]", "records", f"largest element tension [{funit}]",
                 "on line", f"at arc length from end a [{length}]"],
                [[label, envelope.get("start"), envelope.get("records"),
                  _scaled(largest.get("tension"), scale), largest.get("line", ""),
                  largest.get("arc_length")]], "Tension envelope"))
    parts.extend(_figure(p) for p in images)
    return "".join(parts) or _note("No tension envelope in this run (dynamics results carry "
                                   "one).")


def _offset_section(entries: list[tuple[str, dict]], units: str) -> str:
    length = _unit("length", units)
    parts = []
    for label, s in entries:
        group = (f"body {s['body']}" if s.get("body")
                 else "points " + ", ".join(s.get("points", [])))
        parts.append(f"<h3>{_e(label)}: {_e(group)}, {_e(s.get('message', ''))}</h3>")
        for entry in s.get("headings", []):
            tensions = entry.get("fairlead_tension", {})
            scale, funit = _force_scale([*entry.get("restoring_force", []),
                                         *(v for t in tensions.values() for v in t)], units)
            rows = [[offset, _scaled(entry["restoring_force"][k], scale),
                     *(_scaled(tensions[n][k], scale) for n in tensions)]
                    for k, offset in enumerate(entry.get("offsets", []))]
            parts.append(_table([f"offset [{length}]", "restoring force",
                                 *(f"{n} fairlead" for n in tensions)], rows,
                                f"Heading {_num(entry.get('heading'))} deg: restoring force "
                                f"along the heading and fairlead tensions [{funit}]",
                                text_columns=0))
        yaw = s.get("yaw")
        if yaw:
            parts.append(_table(["yaw [deg]", f"yaw moment [{_unit('force*length', units)}]"],
                                list(zip(yaw.get("angles", []), yaw.get("yaw_moment", []),
                                         strict=False)),
                                "Yaw: restoring moment", text_columns=0))
    return "".join(parts)


def _per_line_rows(blocks: Sequence[dict], scale: float = 1.0) -> list[list[Any]]:
    """Rows (line, end, one value per block) of ``{line: {"end_a": v, "end_b": v}}`` dicts."""
    names = list(blocks[0]) if blocks else []
    return [[name if end == "a" else "", end,
             *(_scaled(b.get(name, {}).get(f"end_{end}"), scale) for b in blocks)]
            for name in names for end in ("a", "b")]


def _fatigue_section(entries: list[tuple[str, dict]], units: str) -> str:
    parts = []
    for label, s in entries:
        curves = ", ".join(f"{t}: {c}" for t, c in s.get("curves", {}).items())
        parts.append(f"<h3>{_e(label)}: {_e(s.get('source', ''))}, {_e(curves)}, "
                     f"{_e(s.get('message', ''))}</h3>")
        for method, entry in s.get("methods", {}).items():
            parts.append(_table(["line", "end", "damage", "life [years]"],
                                _per_line_rows([entry.get("damage", {}),
                                                entry.get("life_years", {})]),
                                f"{method}: damage over {_num(s.get('duration'))} s and life "
                                f"(safety factor {_num(s.get('safety_factor'))})",
                                text_columns=2))
            if entry.get("min_life_element") is not None:
                parts.append(_note(f"least life of an element ({method}): "
                                   f"{_num(entry.get('min_element_life_years'))} years "
                                   f"(element {entry['min_life_element']})"))
    return "".join(parts)


def _extremes_section(entries: list[tuple[str, dict]], units: str) -> str:
    parts = []
    for label, s in entries:
        levels = list(s.get("percentiles", {}))
        blocks = [s.get(k, {}) for k in ("mpm", "maximum", "mean", "std")]
        blocks += [s["percentiles"][q] for q in levels]
        scale, funit = _force_scale([v for b in blocks[:2] for line in b.values()
                                     for v in line.values()], units)
        parts.append(f"<h3>{_e(label)}: {_e(s.get('source', ''))}, {_e(s.get('method', ''))}, "
                     f"{_e(s.get('message', ''))}</h3>")
        parts.append(_table(["line", "end", "MPM", "max", "mean", "std",
                             *(f"p{q}" for q in levels)], _per_line_rows(blocks, scale),
                            f"Line end tensions: most probable maximum over "
                            f"{_num(s.get('duration'))} s [{funit}]", text_columns=2))
        if s.get("max_element_mpm") is not None:
            parts.append(_note(f"largest element MPM: "
                               f"{_num(_scaled(s['max_element_mpm'], scale))} {funit}"))
    return "".join(parts)


def _other_section(entries: list[tuple[str, dict]], units: str) -> str:
    """Modal, strumming, stochastic, harmonic and any other kind: modes as a table, the rest
    as name-value pairs."""
    parts = []
    for label, s in entries:
        parts.append(f"<h3>{_e(label)}: {_e(s.get('message', ''))}</h3>")
        skip = {"kind", "case", "converged", "status", "message", "design", "units"}
        modes = s.get("modes")
        if isinstance(modes, list) and modes and isinstance(modes[0], dict):
            parts.append(_table(["mode", "omega [rad/s]", "period [s]", "dominant"],
                                [[m.get("index"), m.get("omega"), m.get("period"),
                                  m.get("dominant", "")] for m in modes], "Modes"))
            skip.add("modes")
        rows = [[k, _value(v)] for k, v in s.items() if k not in skip]
        if rows:
            parts.append(_table(["quantity", "value"], rows, text_columns=2))
    return "".join(parts)


def _figure(path: Path) -> str:
    data = base64.b64encode(path.read_bytes()).decode("ascii")
    return (f'<figure><img src="data:image/png;base64,{data}" alt="{_e(path.name)}">'
            f"<figcaption>{_e(path.name)}</figcaption></figure>")


# ----------------------------------------------------------------------------- page


def _run_summary(summary: dict[str, Any]) -> dict[str, Any]:
    """A run summary (``analyses`` list) of a run or of a single statics summary."""
    if "analyses" in summary:
        return summary
    return {"case": summary.get("case", ""), "converged": summary.get("converged"),
            "units": summary.get("units", "SI"), "analyses": [{"kind": "statics", **summary}]}


def render_report(summary: dict[str, Any], files: Sequence[Path], system: Any) -> str:
    """The report page as a string.

    Parameters
    ----------
    summary
        The run summary (``moorline run``: keys ``case``, ``converged``, ``units``,
        ``analyses``) or a statics summary (``moorline statics``); an optional ``status``
        (with ``message``) overrides the status derived from the analyses (an interrupted
        run).
    files
        The files the run wrote; every existing ``.png`` among them is embedded.
    system
        The loaded case (:class:`moorline.model.System`), for the inputs.

    Returns
    -------
    str
        A complete HTML document.
    """
    summary = _run_summary(summary)
    units = str(summary.get("units") or system.units)
    analyses = summary["analyses"]
    labels = _labels([str(a.get("kind", "")) for a in analyses])
    by_kind: dict[str, list[tuple[str, dict]]] = {}
    for label, analysis in zip(labels, analyses, strict=True):
        by_kind.setdefault(str(analysis.get("kind", "")), []).append((label, analysis))
    images = [Path(f) for f in files if Path(f).suffix.lower() == ".png" and Path(f).is_file()]
    envelope_images = [p for p in images if "envelope" in p.stem]
    css, headline, details = _status(summary)

    def get(kind: str) -> list[tuple[str, dict]]:
        return by_kind.get(kind, [])

    known = ("statics", "dynamics", "offset", "fatigue", "extremes")
    other = [entry for kind, entries in by_kind.items() if kind not in known for entry in entries]
    design = list(zip(labels, analyses, strict=True))
    body = {
        "status": (f'<p><span class="banner {css}">{_e(headline)}</span> {_e(details)}</p>'
                   + _status_section(summary, labels)),
        "inputs": _inputs_section(system, units),
        "statics": _statics_section(get("statics"), units),
        "stiffness": _stiffness_section(get("statics"), get("offset"), units),
        "design": _design_section(design, units),
        "dynamics": _dynamics_section(get("dynamics"), units),
        "envelopes": _envelope_section(get("dynamics"), units, envelope_images),
    }
    optional = {"offset": _offset_section(get("offset"), units),
                "fatigue": _fatigue_section(get("fatigue"), units),
                "extremes": _extremes_section(get("extremes"), units),
                "other": _other_section(other, units)}
    body.update({k: v for k, v in optional.items() if v})
    rest = [p for p in images if p not in envelope_images]
    body["plots"] = "".join(_figure(p) for p in rest) or _note(
        "No other plots (run without --no-plots to draw them)." if not envelope_images
        else "No other plots.")
    headings = {**SECTIONS, **OPTIONAL_SECTIONS}
    order = [k for k in (*list(SECTIONS)[:-1], *OPTIONAL_SECTIONS, "plots") if k in body]
    nav = "".join(f'<a href="#{k}">{_e(headings[k])}</a>' for k in order)
    sections = "".join(f'<section id="{k}"><h2>{_e(headings[k])}</h2>{body[k]}</section>'
                       for k in order)
    title = f"moorline report: {summary.get('case') or system.name}"
    return ("<!DOCTYPE html>\n"
            f'<html lang="en"><head><meta charset="utf-8"><title>{_e(title)}</title>'
            f"<style>{_CSS}</style></head><body>"
            f'<header><h1>{_e(title)}</h1><p><span class="banner {css}">{_e(headline)}'
            f"</span> {_e(details)}</p><p>moorline {_e(__version__)}, units {_e(units)}</p>"
            f"<nav>{nav}</nav></header><main>{sections}</main></body></html>\n")


def write_report(summary: dict[str, Any], files: Sequence[Path], directory: str | Path,
                 system: Any) -> Path:
    """Write ``report.html`` into ``directory`` (see :func:`render_report`).

    Parameters
    ----------
    summary
        The run (or statics) summary.
    files
        The files the run wrote (its PNG plots are embedded).
    directory
        The case's output directory ``DIR/<case>/`` (created if needed).
    system
        The loaded case.

    Returns
    -------
    Path
        The report written.
    """
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    path = directory / REPORT_FILE
    path.write_text(render_report(summary, files, system), encoding="utf-8")
    return path
