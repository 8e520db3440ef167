"""MoorDyn input files: read a MoorDyn deck into a :class:`~moorline.model.System` and write
one back.

Format (MoorDyn documentation, ``docs/inputs.rst``): sections start at header lines made of a
key phrase between dashes (``---- LINE TYPES ----``). Table sections (line types, points,
lines) begin with two header rows (column names and units) that MoorDyn does not read; every
further row is one entry. ``OPTIONS`` rows are ``value key [description]``. ``!``, ``#`` and
``%`` start comments.

Supported (v2 names first, v1 names in parentheses):

- ``LINE TYPES`` (``LINE DICTIONARY``): v2 rows ``Name Diam MassDen EA BA/-zeta EI Cd Ca CdAx
  CaAx [Cl dF cF]``; v1 rows (nine columns) ``Name Diam MassDen EA BA/-zeta Can Cat Cdn Cdt``.
  MoorDyn's ``CdAx`` is relative to the surface ``pi d l`` like moorline's ``Ct``. ``EA`` may
  be the name of a strain-tension table file (MoorDyn's non-linear EA; relative to the deck's
  folder), read as the line type's ``EA_table``; the writer writes such a file back. ``EI``
  (a constant; MoorDyn's non-linear EI table is not read) is the line type's bending stiffness
  (:mod:`moorline.physics.bending`; MoorDyn's pinned ends at points agree, its clamped ends at
  rods and bodies are not modelled) and is written back.
- ``POINTS`` (``POINT PROPERTIES``, ``CONNECTION PROPERTIES``, ``NODE PROPERTIES``): v2 rows
  ``ID Attachment X Y Z Mass Volume CdA Ca``; v1 rows (twelve columns) ``ID Type X Y Z M V FX FY
  FZ CdA Ca``. ``Fixed``/``Fix``/``Anchor`` points become ``fixed``,
  ``Coupled``/``Cpld``/``Vessel``/``Ves``/``Fairlead`` become ``prescribed`` and
  ``Free``/``Connect``/``Con``/``Point`` become ``free`` (case-insensitive, trailing digits
  ignored, as MoorDyn-C v2.7 does); ``CdA`` becomes
  ``drag_area`` with ``Cd = 1``.
- ``LINES`` (``LINE PROPERTIES``, ``LINE LIST``): v2 rows ``ID LineType AttachA AttachB
  UnstrLen NumSegs [Outputs]``; v1 rows ``ID LineType UnstrLen NumSegs NodeAnch NodeFair
  [Flags]`` (recognized by a column header ``UnstrLen``/``Length`` in third place, or by a v1
  points table). Either may end with MoorDyn-F's ``CtrlChan`` (the controller channel that
  changes the line's length in OpenFAST, e.g. OpenFAST r-test ``modules/moordyn/Node_Check_
  (N=40)/test1.dat``); a nonzero channel is a warning, the length stays ``UnstrLen``.
- MoorDyn-F v1 (FAST v8, OpenFAST before 2.x) puts a count row before a table's header rows
  (``1  NTypes - number of LineTypes``, ``NConnects``, ``NLines``); it is checked against the
  rows listed and skipped.
- ``OPTIONS`` (``SOLVER OPTIONS``): ``WtrDpth`` (alias ``depth``), ``rho`` (``WtrDnsty``,
  ``rhoW``), ``g`` (``gravity``), ``kBot`` (``kb``), ``cBot`` (``cb``), ``FrictionCoefficient``.
  MoorDyn's numerical settings (``dtM``, ``tScheme``, ``TmaxIC``, ``threshIC``, ...) do not
  describe the physics and are kept only in :attr:`MoorDynDeck.options`; unknown options are
  kept there too and logged as warnings. Option keys are case-insensitive, as in MoorDyn.

Names: MoorDyn numbers points and lines. A point or line row may end with a comment holding one
word (``1 Fixed -853.87 0 -320 0 0 0 0  # anchor1``); that word becomes its name, otherwise the
names are ``point<ID>`` and ``line<ID>``. :func:`write_moordyn` writes names that way, so that
``read_moordyn(write_moordyn(system))`` gives back the same names.

Missing ``WtrDpth``: MoorDyn-C starts from 0 and lowers the seabed to any point defined below
it; the reader does the same (with a warning). ``BODIES``, ``ROD TYPES`` and ``RODS`` become
moorline bodies and points (:mod:`moorline.io.moordyn_rigid`: free, fixed and coupled bodies,
body points ``Body<k>``, rods fixed to bodies, free, fixed and coupled rods, lines on rod ends
``R<k>A``/``R<k>B``); what cannot be represented (pinned rods, pinned coupled bodies) is one
``CaseError`` naming every such item, what is approximated a warning each. ``SeafloorFile``
(MoorDyn-C's 3-D seafloor) becomes the seabed's bathymetry grid (:mod:`moorline.io.seafloor`;
MoorDyn opens the path relative to its working directory; here the path, then its shorter
tails, are looked up in the deck's folder and its parents; a note says that moorline's
seabed pushes along its normal where MoorDyn's pushes vertically). ``WaveKin`` 2-5 and 7 with
their wave file next to the deck become a sea of explicit components, ``Currents`` 1 or 3 with
a ``current_profile.txt`` the case's current (:mod:`moorline.io.moordyn_kinematics`); other
kinematics options are warnings naming what is dropped. ``TMax``, ``dtOut`` and the
``OUTPUTS`` channels become a dynamics analysis, ``output.every`` and ``output.channels``
(:mod:`moorline.io.moordyn_outputs`). MoorDyn-F's ``EXTERNAL LOADS`` section becomes body and
point forces, body damping and drag (:mod:`moorline.io.moordyn_external`), its seabed-friction
options (``MU_KT``, ``MU_KA``, ``MC``, ``CV``; MoorDyn-C's ``FricDamp``,
``StatDynFricScale``) the seabed's friction (:mod:`moorline.io.moordyn_friction`), early
MoorDyn-F v2 17-column body rows are read (:func:`moorline.io.moordyn_rigid.legacy_body_row`),
and FAST.Farm's ``Turbine<k>`` points become prescribed points given the turbines' positions
(:func:`read_moordyn_deck`).
"""

from __future__ import annotations

import logging
import math
import re
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Literal

from ..errors import CaseError
from ..model import Environment, Line, LineType, Point, Seabed, System
from ..physics.load_strain import StrainTable
from .files import MAX_CASE_BYTES, file_problem
from .moordyn_bodies import body_attachment, body_problems, body_section
from .moordyn_external import apply_external_loads, parse_external_loads
from .moordyn_friction import FRICTION_OPTIONS, deck_friction
from .moordyn_kinematics import deck_waves, water_kinematics
from .moordyn_outputs import deck_channels, output_channels, time_options, time_settings
from .moordyn_rigid import RigidParts, attach_point, parse_bodies, parse_rod_types, parse_rods
from .moordyn_syrope import apply_syrope_ic, syrope_ic_rows, syrope_line_type, write_syrope_files
from .moordyn_visco import viscoelastic_line_type
from .schema import check_number
from .seafloor import read_seafloor
from .strain_table import read_strain_table
from .tokens import is_number
from .topology import geometry_problem

logger = logging.getLogger(__name__)

Version = Literal["v1", "v2"]
MOORDYN_CURVE_POINTS = 30
"""Most points MoorDyn-C v2.7 reads from a curve file (its ``nCoef``)."""
_COMMENT = re.compile(r"[!#%]")
#: MoorDyn-F v1's count row before a table's two header rows (``1  NTypes  - number of ...``).
_COUNT_ROW = re.compile(r"^(\d+)\s+(N[A-Za-z]+)\b")
_NAME = re.compile(r"^[A-Za-z_][\w.\-]*$")
_INF_DEPTH_TAG = "moorline: no seabed"

#: Default values MoorDyn-C v2.7 uses when an option is absent.
MOORDYN_DEFAULTS: dict[str, float] = {
    "g": 9.80665, "rho": 1025.0, "WtrDpth": 0.0, "kBot": 3.0e6, "cBot": 3.0e5,
    "FrictionCoefficient": 0.0,
}
_PHYSICAL_OPTIONS = {
    "wtrdpth": "WtrDpth", "depth": "WtrDpth", "rho": "rho", "wtrdnsty": "rho", "rhow": "rho",
    "g": "g", "gravity": "g", "kbot": "kBot", "kb": "kBot", "cbot": "cBot", "cb": "cBot",
    "frictioncoefficient": "FrictionCoefficient",
}
_NUMERICAL_OPTIONS = {
    "dtm", "tmax", "wavekin", "currents", "cfl", "tscheme", "dtic", "tmaxic", "cdscaleic",
    "threshic", "icgendynamic",
    "writelog", "dtout", "writeunits", "disableoutput", "disableouttime", "fileic", "fricdamp",
    "statdynfricscale", "echo", "icdfac", "icthresh", "ictmax", "dtwave", "wavekin_rampt",
    "unifycurrentgrid", "seafloorfile", *FRICTION_OPTIONS,
}
_UNSUPPORTED_OPTIONS: dict[str, str] = {}
_DROPPED_OPTIONS = {"waterkin": "MoorDyn v1 water kinematics files (waves and current)"}
#: Point attachment words, as MoorDyn-C v2.7 reads them (``source/MoorDyn2.cpp``, the point
#: list): the leading letters of the word, upper-cased (``str::decomposeString``), one of these.
_POINT_KINDS = {"FIXED": "fixed", "FIX": "fixed", "ANCHOR": "fixed",
                "COUPLED": "prescribed", "CPLD": "prescribed", "VESSEL": "prescribed",
                "VES": "prescribed", "FAIRLEAD": "prescribed",
                "FREE": "free", "CONNECT": "free", "CON": "free", "POINT": "free"}


@dataclass(frozen=True)
class MoorDynDeck:
    """What a MoorDyn file holds beyond the :class:`System`.

    Attributes
    ----------
    system
        The cable system (``source`` is the file path).
    version
        ``v1`` or ``v2`` table layout (v1 only when every table said so).
    options
        All ``OPTIONS`` rows as written, ``{key: value}`` (keys as in the file).
    notes
        Warnings raised while reading (ignored options, defaults applied, ...).
    point_ids, line_ids
        MoorDyn's number of each point and line, by moorline name.
    outputs
        The ``OUTPUTS`` channel names, as written (``FairTen1``, ``L1N10T``, ``Con4Fx``, ...).
    line_outputs
        The line output flags of the ``LINES`` table (``p``, ``t``, ...; ``-`` for none) by
        line name (MoorDyn writes a file per line with them; moorline's results hold every
        node's position and every segment's tension anyway).
    comments
        How the deck's time settings (``dtM``, ``TMax``, ``dtOut``) were used (not warnings:
        :func:`moorline.io.moordyn_outputs.time_settings`); ``moorline convert`` writes them
        with the notes at the top of the case.
    """

    system: System
    version: Version
    options: dict[str, str] = field(default_factory=dict)
    notes: tuple[str, ...] = ()
    point_ids: dict[str, int] = field(default_factory=dict)
    line_ids: dict[str, int] = field(default_factory=dict)
    outputs: tuple[str, ...] = ()
    line_outputs: dict[str, str] = field(default_factory=dict)
    comments: tuple[str, ...] = ()


@dataclass
class _Row:
    lineno: int
    tokens: list[str]
    comment: str


@dataclass
class _Section:
    kind: str
    title: str
    lineno: int
    header: list[str] = field(default_factory=list)
    rows: list[_Row] = field(default_factory=list)
    count: tuple[int, str, int] | None = None  # a v1 count row: (number, key, line number)


@dataclass
class _Reader:
    file: str
    notes: list[str] = field(default_factory=list)

    def fail(self, reason: str, row: _Row | None = None, section: str | None = None,
             lineno: int | None = None) -> CaseError:
        where = []
        if row is not None or lineno is not None:
            where.append(f"line {row.lineno if row is not None else lineno}")
        if section:
            where.append(section)
        return CaseError(reason, file=self.file, field=", ".join(where) or None)

    def warn(self, message: str) -> None:
        self.notes.append(message)
        logger.warning("%s: %s", self.file, message)


# --------------------------------------------------------------------------- reading


def read_moordyn(path: str | Path) -> System:
    """Read a MoorDyn v2 (or v1) input file into a :class:`System`.

    Parameters
    ----------
    path
        The MoorDyn input file.

    Returns
    -------
    System
        SI units, named after the file; ``source`` is the path. The analyses: one static
        analysis (with current drag when the deck's current was read), then a dynamics
        analysis when the deck gives ``TMax``; MoorDyn's IC settings do not carry over (see
        :func:`read_moordyn_deck` for them).

    Raises
    ------
    CaseError
        Naming the file, the line number and section, and what is wrong.
    """
    return read_moordyn_deck(path).system


def read_moordyn_deck(path: str | Path,
                      turbines: Mapping[int, tuple[float, float, float]] | None = None
                      ) -> MoorDynDeck:
    """Read a MoorDyn input file, keeping its options, IDs and reading notes.

    Parameters
    ----------
    path
        The MoorDyn input file.
    turbines
        FAST.Farm turbine reference positions [m] by turbine number (the ``WT_X WT_Y WT_Z``
        of the farm's ``.fstf``): a point attached to ``Turbine<k>`` (``T<k>``) becomes a
        prescribed point at its deck position plus turbine ``k``'s (as MoorDyn-F adds
        ``TurbineRefPos`` to the coupled point's position, OpenFAST ``MoorDyn.f90``); without
        the turbine's position the deck is refused.

    Returns
    -------
    MoorDynDeck
        The system and what else the file says.
    """
    path = Path(path)
    reader = _Reader(str(path))
    problem = file_problem(path, MAX_CASE_BYTES)
    if problem is not None:
        raise CaseError(f"cannot read MoorDyn file: {problem}", file=str(path))
    try:
        text = path.read_text(encoding="utf-8", errors="replace")
    except OSError as exc:
        raise CaseError(f"cannot read MoorDyn file: {exc.strerror or exc}", file=str(path)) from exc
    sections = _split_sections(text.splitlines(), reader)
    options = sections.get("options", _Section("options", "OPTIONS", 0))
    raw, env_values = _parse_options(options, reader)
    for kind, title in (("types", "LINE TYPES"), ("points", "POINTS"), ("lines", "LINES")):
        if kind not in sections:
            raise reader.fail(f"missing section {title} (a '--- {title} ---' header line)")
        if not sections[kind].rows:
            raise reader.fail(f"section {sections[kind].title} has no entries",
                              lineno=sections[kind].lineno, section=sections[kind].title)
    rho = env_values.get("rho", MOORDYN_DEFAULTS["rho"])
    parts = _rigid_parts(sections, rho, env_values.get("g", MOORDYN_DEFAULTS["g"]), reader)
    types, v_types = _parse_line_types(sections["types"], reader)
    points, ids, v_points = _parse_points(sections["points"], reader, parts, rho, turbines)
    points.update(parts.rod_points)
    parts.collapse_point_bodies(points, rho)
    if parts.errors:
        raise reader.fail("cannot be represented: " + "; ".join(parts.errors))
    lines, line_ids, v_lines = _parse_lines(sections["lines"], types, ids, v_points, reader,
                                            parts)
    syrope = sections.get("syrope", _Section("syrope", "SYROPE IC", 0))
    lines = apply_syrope_ic([(r.lineno, r.tokens) for r in syrope.rows], lines, line_ids, types,
                            lambda why, n: reader.fail(why, lineno=n or None,
                                                       section=syrope.title), reader.warn)
    used = {end for line in lines.values() for end in (line.end_a, line.end_b)}
    for name in parts.rod_points:
        if name not in used:
            del points[name]  # a rod end no line attaches to
    for name, rigid in parts.rigid.items():
        if rigid.kind != "pinned" and not any(p.kind == "body" and p.body == name
                                               for p in points.values()):
            parts.warnings.append(f"body {name}: no line attaches to it (statics needs "
                                  "something to hold it)")
    for message in parts.warnings:
        reader.warn(message)
    bodies = parts.bodies()
    if "external" in sections:
        sec = sections["external"]
        loads = parse_external_loads(sec.rows, lambda why, r: reader.fail(why, r, sec.title))
        errors = apply_external_loads(
            loads, bodies, points, parts.body_ids, parts.collapsed,
            {n: parts.merged.get(name, name) for n, name in ids.items()}, rho, reader.warn)
        if errors:
            raise reader.fail("cannot be represented: " + "; ".join(errors),
                              section=sec.title)
    environment = _environment(env_values, points, reader)
    waves = deck_waves(raw, path, reader.warn)
    if waves is not None:
        environment = replace(environment, waves=waves)
    environment = _seafloor(raw, path, environment, reader)
    current = water_kinematics(raw, path, reader.warn)
    if current is not None:
        environment = replace(environment, current=current)
    environment = replace(environment, seabed=deck_friction(
        raw, environment.seabed, lines, types, environment.water_density, environment.gravity,
        str(path), reader.warn))
    versions = {v_types, v_points, v_lines}
    problem = geometry_problem(points, lines, bodies)
    if problem is not None:
        raise CaseError(problem[0], file=str(path))
    outputs = output_channels(sections.get("outputs"), reader.warn)
    comments: list[str] = []
    analyses, output = time_settings(raw, outputs, current is not None, comments.append)
    system = System(name=path.stem, units="SI", environment=environment, line_types=types,
                    points=points, lines=lines, source=str(path), analyses=analyses,
                    output=output, bodies=bodies)
    flags = {name: _line_flags(sections["lines"].rows[i - 1])
             for name, i in line_ids.items()}
    return MoorDynDeck(system=system, version="v1" if versions == {"v1"} else "v2",
                       options=raw, notes=tuple(reader.notes),
                       point_ids={name: i for i, name in ids.items() if name in points},
                       line_ids=line_ids,
                       outputs=outputs, line_outputs=flags, comments=tuple(comments))


def _rigid_parts(sections: Mapping[str, _Section], rho: float, g: float,
                 reader: _Reader) -> RigidParts:
    """The ``ROD TYPES``, ``BODIES`` and ``RODS`` sections (:mod:`moorline.io.moordyn_rigid`)."""
    parts = RigidParts()

    def failer(title: str):
        return lambda reason, row: reader.fail(reason, row, title)

    rod_types = {}
    if "rodtypes" in sections:
        sec = sections["rodtypes"]
        rod_types = parse_rod_types(sec.rows, failer(sec.title))
    if "bodies" in sections:
        sec = sections["bodies"]
        parse_bodies(sec.rows, rho, failer(sec.title), parts)
    if "rods" in sections:
        sec = sections["rods"]
        parse_rods(sec.rows, rod_types, rho, g, failer(sec.title), parts)
    return parts


def _line_flags(row: _Row) -> str:
    """The output flags column of a line row (``-`` when absent)."""
    return row.tokens[6] if len(row.tokens) > 6 else "-"


def is_moordyn_deck(path: str | Path) -> bool:
    """Whether a file reads as a MoorDyn deck: dashed section headers naming at least two of
    MoorDyn's tables (line types, rod types, bodies, rods, points, lines). Never raises."""
    try:
        path = Path(path)
        if file_problem(path, MAX_CASE_BYTES) is not None:
            return False
        text = path.read_text(encoding="utf-8", errors="replace")
    except OSError:
        return False
    kinds = {_section_kind(" ".join(line.strip().strip("- \t").upper().split()))
             for line in text.splitlines() if line.strip().startswith("--")}
    return len(kinds & {"types", "rodtypes", "bodies", "rods", "points", "lines"}) >= 2


def _section_kind(title: str) -> str:
    """Classify a header line's key phrase (upper case, dashes removed)."""
    checks = (
        ("LINE TYPE", "types"), ("LINE DICTIONARY", "types"), ("ROD TYPE", "rodtypes"),
        ("ROD DICTIONARY", "rodtypes"), ("BOD", "bodies"), ("ROD", "rods"),
        ("POINT", "points"), ("CONNECTION", "points"), ("NODE", "points"),
        ("LINE", "lines"), ("OPTION", "options"), ("SOLVER OPTION", "options"),
        ("OUTPUT", "outputs"),
        ("FAIL", "ignored"), ("CONTROL", "ignored"), ("EXTERNAL", "external"),
        ("SYROPE", "syrope"),
    )
    for key, kind in checks:
        if title.startswith(key):
            return kind
    return "other"


def _split_sections(lines: list[str], reader: _Reader) -> dict[str, _Section]:
    sections: dict[str, _Section] = {}
    current: _Section | None = None
    for lineno, raw in enumerate(lines, start=1):
        stripped = raw.strip()
        if stripped.startswith("--"):
            title = " ".join(stripped.strip("- \t").upper().split())
            kind = _section_kind(title)
            current = _Section(kind, title, lineno)
            if kind in sections and kind not in ("other", "ignored", "outputs"):
                raise reader.fail(f"section {title} appears twice", lineno=lineno, section=title)
            if kind == "ignored":
                reader.warn(f"section {title} (line {lineno}) is not supported and is ignored")
            sections.setdefault(kind, current)
            continue
        if current is None or not stripped or current.kind in ("other", "ignored"):
            continue
        table = current.kind not in ("options", "outputs")
        count = _COUNT_ROW.match(stripped) if table and not current.header else None
        if count is not None and current.count is None:
            current.count = (int(count.group(1)), count.group(2), lineno)
            continue
        if table and len(current.header) < 2:
            current.header.append(stripped)
            continue
        match = _COMMENT.search(stripped)
        body, comment = (stripped[:match.start()], stripped[match.end():].strip()) if match \
            else (stripped, "")
        if body.strip():
            current.rows.append(_Row(lineno, body.split(), comment))
    for sec in sections.values():
        if sec.count is not None and sec.count[0] != len(sec.rows):
            number, key, lineno = sec.count
            raise reader.fail(f"{key} = {number} but the section lists {len(sec.rows)} "
                              "entries", lineno=lineno, section=sec.title)
    return sections


def _number(token: str, what: str, row: _Row, section: str, reader: _Reader) -> float:
    try:
        value = float(token)
    except ValueError:
        raise reader.fail(f"{what} must be a number, got {token!r}", row, section) from None
    problem = check_number(value)
    if problem is not None:
        raise reader.fail(f"{what} {problem}", row, section)
    return value


def _integer(token: str, what: str, row: _Row, section: str, reader: _Reader) -> int:
    value = _number(token, what, row, section, reader)
    if value != int(value):
        raise reader.fail(f"{what} must be an integer, got {token!r}", row, section)
    return int(value)


def _columns(row: _Row, allowed: tuple[int, ...], layout: str, section: str,
             reader: _Reader) -> None:
    if len(row.tokens) not in allowed:
        counts = " or ".join(str(n) for n in allowed)
        raise reader.fail(f"expected {counts} columns ({layout}), found {len(row.tokens)}",
                          row, section)


def _parse_line_types(sec: _Section, reader: _Reader) -> tuple[dict[str, LineType], Version]:
    types: dict[str, LineType] = {}
    version: Version = "v2" if len(sec.rows[0].tokens) != 9 else "v1"
    layout = ("v2: Name Diam MassDen EA BA/-zeta EI Cd Ca CdAx CaAx [Cl dF cF]" if version == "v2"
              else "v1: Name Diam MassDen EA BA/-zeta Can Cat Cdn Cdt")
    for row in sec.rows:
        _columns(row, (10, 11, 12, 13) if version == "v2" else (9,), layout, sec.title, reader)
        name, tok = row.tokens[0], row.tokens[1:]
        if name in types:
            raise reader.fail(f"line type {name!r} is defined twice", row, sec.title)
        def fail(why: str, n: str = name, r: _Row = row) -> CaseError:
            return reader.fail(f"line type {n!r}: {why}", r, sec.title)

        if tok[2].upper().startswith("SYROPE:"):
            visco = syrope_line_type(tok[2], tok[3], Path(reader.file).parent, fail,
                                     reader.warn)
        else:
            visco = viscoelastic_line_type(tok[2], tok[3], fail)
        if visco is not None:  # EA_s|EA_d[|...] with BA_s[|BA_d]: numbers checked there
            tok = [*tok[:2], "1", "0", *tok[4:]]
        if not is_number(tok[3]):
            raise reader.fail(f"BA/-zeta {tok[3]!r}: only a constant BA is supported (no "
                              "damping tables)", row, sec.title)
        table = None if is_number(tok[2]) else _ea_table(tok[2], row, sec.title, reader)
        values = [_number(t, f"column {i + 2}", row, sec.title, reader)
                  for i, t in enumerate(tok) if i != 2 or table is None]
        if table is not None:
            values.insert(2, table.max_slope)
        if version == "v2":
            d, m, EA, BA, EI, Cd, Ca, Ct, Cat = values[:9]
            if EI < 0:
                raise reader.fail(f"EI must not be negative, got {EI:g}", row, sec.title)
            if len(values) > 9 and values[9]:
                reader.warn(f"line type {name!r}: VIV lift coefficient Cl is ignored")
        else:
            d, m, EA, BA, Ca, Cat, Cd, Ct = values
            EI = 0.0
        for what, value in (("Diam", d), ("MassDen", m), ("EA", EA)):
            if value <= 0:
                raise reader.fail(f"{what} must be positive, got {value:g}", row, sec.title)
        points = None if table is None else tuple(map(tuple, table.points.tolist()))
        fields = {"EA": EA, "BA": BA, **(visco or {})}
        types[name] = LineType(name=name, diameter=d, mass_per_length=m, Cd=Cd, Ca=Ca, Ct=Ct,
                               Cat=Cat, EA_table=points, EI=EI, **fields)
    return types, version


def _ea_table(token: str, row: _Row, section: str, reader: _Reader) -> StrainTable:
    """MoorDyn's non-linear EA: a strain-tension table file, relative to the deck's folder
    (MoorDyn-C's convention), read by :func:`moorline.io.strain_table.read_strain_table`."""
    try:
        return StrainTable(read_strain_table(Path(reader.file).parent / token))
    except ValueError as exc:
        raise reader.fail(f"EA table {token!r}: {exc}", row, section) from None


def _row_name(row: _Row, default: str, taken: Mapping[str, object], section: str,
              reader: _Reader) -> str:
    name = row.comment.strip()
    if not _NAME.match(name):
        name = default
    if name in taken:
        raise reader.fail(f"name {name!r} is used twice (names come from a one-word comment "
                          "at the end of the row, else from the ID)", row, section)
    return name


def _check_id(row: _Row, expected: int, section: str, reader: _Reader) -> None:
    got = _integer(row.tokens[0], "ID", row, section, reader)
    if got != expected:
        raise reader.fail(f"IDs must run 1, 2, 3, ...: expected {expected}, got {got}",
                          row, section)


def point_word(attachment: str) -> str:
    """The leading letters of a point attachment word, upper-cased, as MoorDyn compares them
    (``Fixed``, ``fix2`` and ``FIX`` all give ``FIX``/``FIXED``)."""
    match = re.match(r"[A-Za-z]*", attachment)
    return match.group(0).upper() if match else ""


def _parse_points(sec: _Section, reader: _Reader, parts: RigidParts | None = None,
                  rho: float = MOORDYN_DEFAULTS["rho"],
                  turbines: Mapping[int, tuple[float, float, float]] | None = None
                  ) -> tuple[dict[str, Point], dict[int, str], Version]:
    version: Version = "v1" if len(sec.rows[0].tokens) == 12 else "v2"
    layout = ("v2: ID Attachment X Y Z Mass Volume CdA Ca" if version == "v2"
              else "v1: ID Type X Y Z M V FX FY FZ CdA Ca")
    points: dict[str, Point] = {}
    ids: dict[int, str] = {}
    for number, row in enumerate(sec.rows, start=1):
        _columns(row, (9,) if version == "v2" else (12,), layout, sec.title, reader)
        _check_id(row, number, sec.title, reader)
        attachment = row.tokens[1]
        kind = _POINT_KINDS.get(point_word(attachment))
        body = _point_body(attachment, parts)
        if body is not None:
            kind = "body"
        turbine = re.match(r"(?i)^(?:turbine|t)(\d+)$", attachment)
        offset = (0.0, 0.0, 0.0)
        if turbine is not None and int(turbine.group(1)) in (turbines or {}):
            kind, offset = "prescribed", (turbines or {})[int(turbine.group(1))]
        if kind is None:
            given = ", ".join(map(str, sorted(turbines or {}))) or "none"
            what = ("no such body" if point_word(attachment) == "BODY" else
                    f"a FAST.Farm turbine: give its reference position (WT_X WT_Y WT_Z of the "
                    f"farm's .fstf) with `moorline convert --turbine {turbine.group(1)} X Y Z` "
                    f"(turbines given: {given})" if turbine is not None else
                    "expected Fixed (Fix, Anchor), Coupled (Vessel, Ves, Cpld, Fairlead) "
                    "or Free (Connect, Con, Point)")
            raise reader.fail(f"unknown point attachment {attachment!r}: {what}", row, sec.title)
        v = [_number(t, f"column {i + 3}", row, sec.title, reader)
             for i, t in enumerate(row.tokens[2:])]
        force = (v[5], v[6], v[7]) if version == "v1" else (0.0, 0.0, 0.0)
        cda, ca = (v[-2], v[-1])
        if v[3] < 0:
            raise reader.fail(f"Mass must not be negative, got {v[3]:g}", row, sec.title)
        name = _row_name(row, f"point{number}", points, sec.title, reader)
        position = (v[0] + offset[0], v[1] + offset[1], v[2] + offset[2])
        points[name] = Point(name=name, kind=kind, position=position, mass=v[3],
                             volume=v[4], force=force, Cd=1.0 if cda else 0.0, drag_area=cda,
                             Ca=ca)
        if body is not None and parts is not None:
            points[name] = attach_point(parts, points[name], body, rho, number)
        ids[number] = name
    return points, ids, version


def _point_body(attachment: str, parts: RigidParts | None) -> str | None:
    """The body name of a ``Body<k>`` point attachment (None: not one, or no such body)."""
    match = re.match(r"(?i)^body(\d+)$", attachment)
    if match is None or parts is None:
        return None
    return parts.body_ids.get(int(match.group(1)))


def _lines_layout(sec: _Section, points_version: Version) -> Version:
    """v1 line rows put UnstrLen third; decide from the column-name row, else the points."""
    names = sec.header[0].split() if sec.header else []
    if len(names) > 2 and re.match(r"(?i)(unstr|len)", names[2]):
        return "v1"
    if len(names) > 2 and re.match(r"(?i)(attach|end|node|con|point|anch)", names[2]):
        return "v2"
    return points_version


def _parse_lines(sec: _Section, types: Mapping[str, LineType], ids: Mapping[int, str],
                 points_version: Version, reader: _Reader, parts: RigidParts | None = None
                 ) -> tuple[dict[str, Line], dict[str, int], Version]:
    version = _lines_layout(sec, points_version)
    layout = ("v2: ID LineType AttachA AttachB UnstrLen NumSegs [Outputs [CtrlChan]]"
              if version == "v2"
              else "v1: ID LineType UnstrLen NumSegs NodeAnch NodeFair [Flags [CtrlChan]]")
    lines: dict[str, Line] = {}
    line_ids: dict[str, int] = {}
    for number, row in enumerate(sec.rows, start=1):
        _columns(row, (6, 7, 8), layout, sec.title, reader)
        _check_id(row, number, sec.title, reader)
        tok = row.tokens
        if len(tok) == 8 and _integer(tok[7], "CtrlChan", row, sec.title, reader) != 0:
            reader.warn(f"line {number} (line {row.lineno}): CtrlChan {tok[7]} (length "
                        "control by a turbine controller channel) is not modelled; the "
                        "line keeps its UnstrLen")
        type_name = tok[1]
        if type_name not in types:
            raise reader.fail(f"unknown line type {type_name!r}; defined: "
                              f"{', '.join(types)}", row, sec.title)
        a, b, length, segs = ((tok[2], tok[3], tok[4], tok[5]) if version == "v2"
                              else (tok[4], tok[5], tok[2], tok[3]))
        ends = [_attachment(t, which, ids, row, sec.title, reader, parts)
                for t, which in ((a, "AttachA"), (b, "AttachB"))]
        length_value = _number(length, "UnstrLen", row, sec.title, reader)
        n = _integer(segs, "NumSegs", row, sec.title, reader)
        if length_value <= 0 or n < 1:
            raise reader.fail("UnstrLen must be positive and NumSegs at least 1", row, sec.title)
        if ends[0] == ends[1]:
            raise reader.fail(f"both ends attach to point {a}", row, sec.title)
        name = _row_name(row, f"line{number}", lines, sec.title, reader)
        lines[name] = Line(name=name, line_type=type_name, length=length_value, segments=n,
                           end_a=ends[0], end_b=ends[1])
        line_ids[name] = number
    return lines, line_ids, version


def _attachment(token: str, which: str, ids: Mapping[int, str], row: _Row, section: str,
                reader: _Reader, parts: RigidParts | None = None) -> str:
    if re.match(r"(?i)^r\d+[ab]$", token):
        try:
            name = parts.rod_end(token) if parts is not None else None
        except KeyError:
            name = None
        if name is None:
            raise reader.fail(f"{which} {token!r}: no such rod end (or the rod is pinned, "
                              "which is not supported)", row, section)
        return name
    try:
        number = int(token)
    except ValueError:
        number = None
    if number is None or number not in ids:
        raise reader.fail(f"unknown attachment {which} {token!r}: no point with that ID "
                          f"(points are 1..{len(ids)})", row, section)
    name = ids[number]
    return parts.merged.get(name, name) if parts is not None else name


def _parse_options(sec: _Section, reader: _Reader) -> tuple[dict[str, str], dict[str, float]]:
    raw: dict[str, str] = {}
    physical: dict[str, float] = {}
    for row in sec.rows:
        if len(row.tokens) < 2:
            raise reader.fail("an option row needs a value and a key ('value key')", row,
                              sec.title)
        value, key = row.tokens[0], row.tokens[1]
        raw[key] = value
        low = key.lower()
        if low in _UNSUPPORTED_OPTIONS:
            if not (is_number(value) and float(value) == 0):
                raise reader.fail(f"option {key} = {value}: {_UNSUPPORTED_OPTIONS[low]} are not "
                                  "supported", row, sec.title)
        elif low in _DROPPED_OPTIONS:
            if not (is_number(value) and float(value) == 0):
                reader.warn(f"option {key} = {value} (line {row.lineno}): "
                            f"{_DROPPED_OPTIONS[low]} are not read and are dropped")
        elif low in _PHYSICAL_OPTIONS:
            canonical = _PHYSICAL_OPTIONS[low]
            if canonical == "WtrDpth" and row.comment.strip().lower() == _INF_DEPTH_TAG:
                physical[canonical] = math.inf
                continue
            physical[canonical] = _number(value, f"option {key}", row, sec.title, reader)
        elif low not in _NUMERICAL_OPTIONS:
            reader.warn(f"unknown option {key!r} (line {row.lineno}) ignored")
    return raw, physical


def _environment(values: Mapping[str, float], points: Mapping[str, Point],
                 reader: _Reader) -> Environment:
    get = {**MOORDYN_DEFAULTS, **values}
    depth = get["WtrDpth"]
    deepest = max((-p.position[2] for p in points.values() if p.kind != "body"), default=0.0)
    if deepest > depth:
        reader.warn(f"water depth set to {deepest:g} (the deepest point), as MoorDyn does: "
                    f"WtrDpth {'is missing' if 'WtrDpth' not in values else f'= {depth:g}'}")
        depth = deepest
    if get["rho"] <= 0 or get["g"] < 0:
        key = "rho" if get["rho"] <= 0 else "g"
        raise reader.fail(f"option {key} must be {'positive' if key == 'rho' else '>= 0'}, "
                          f"got {get[key]:g}", section="OPTIONS")
    return Environment(depth=depth, water_density=get["rho"], gravity=get["g"],
                       seabed=Seabed(stiffness=get["kBot"], damping=get["cBot"],
                                     friction=get["FrictionCoefficient"]))


def _seafloor(raw: Mapping[str, str], path: Path, environment: Environment,
              reader: _Reader) -> Environment:
    """The deck's ``SeafloorFile`` as the seabed's bathymetry (unchanged without one)."""
    value = next((v for k, v in raw.items() if k.lower() == "seafloorfile"), None)
    if value is None or (is_number(value) and float(value) == 0):
        return environment
    folder = path.resolve().parent
    parts = Path(value).parts
    tails = [Path(*parts[k:]) for k in range(len(parts))]  # the path, then shorter tails
    candidates = [Path(value)] if Path(value).is_absolute() else \
        [base / tail for tail in tails for base in (folder, *folder.parents)]
    found = next((c for c in candidates if c.is_file()), None)
    if found is None:
        raise reader.fail(f"option SeafloorFile = {value}: no such file in the deck's folder "
                          f"{str(folder)!r} or its parents (MoorDyn opens it relative to its "
                          "working directory)", section="OPTIONS")
    try:
        grid = read_seafloor(found, field="SeafloorFile")
    except CaseError as exc:
        raise CaseError(exc.reason, file=str(path), field="OPTIONS.SeafloorFile") from None
    reader.warn(f"SeafloorFile {value}: the seabed is the bilinear grid of {found}; moorline's "
                "seabed pushes along its normal (a lying line slides down a slope), MoorDyn-C's "
                "vertically")
    # MoorDyn-C v2.7 MoorDyn2.cpp (setup of the runtime water kinematics) and Seafloor.cpp:
    # the waves see the mean of the grid's heights as the water depth, not WtrDpth
    heights = [h for row in grid.z for h in row]
    mean_depth = -math.fsum(heights) / len(heights)
    if not mean_depth > 0.0:
        raise reader.fail(f"option SeafloorFile = {value}: the grid's mean height "
                          f"{-mean_depth:g} is not below the free surface (MoorDyn-C takes "
                          "the mean as the water depth of the waves)", section="OPTIONS")
    if not math.isclose(mean_depth, environment.depth, rel_tol=1e-12):
        reader.warn(f"SeafloorFile {value}: the water depth of the waves is the grid's mean "
                    f"depth {mean_depth:g}, not WtrDpth {environment.depth:g} (as MoorDyn-C)")
    return replace(environment, depth=mean_depth,
                   seabed=replace(environment.seabed, bathymetry=grid))


# --------------------------------------------------------------------------- writing


def unsupported_features(system: System) -> tuple[list[str], list[str]]:
    """What of ``system`` a MoorDyn deck cannot express.

    Returns
    -------
    errors, omissions
        ``errors``: features that make a deck wrong (non-elastic materials, horizontal point
        forces); ``omissions``: features left out of the deck but harmless for statics
        (current, waves, point force histories, a displaced area other than ``pi d^2 / 4``,
        initial line shapes). Point ``motion`` is neither: it is the coupling input (see
        :func:`moorline.compare.moordyn_runner.run_moordyn`).
    """
    errors, omissions = [], []
    env = system.environment
    if env.current.speed:
        omissions.append("current")
    if env.waves.active:
        omissions.append("waves")
    if not env.seabed.is_flat:
        omissions.append("the push of the sloped or gridded seabed along its normal "
                         "(MoorDyn-C's seafloor pushes vertically)")
    for lt in system.line_types.values():
        if lt.material not in ("elastic", "static_dynamic", "syrope"):
            errors.append(f"line type {lt.name}: {lt.material} material")
        if lt.EA_table is not None and len(lt.EA_table) > MOORDYN_CURVE_POINTS:
            errors.append(f"line type {lt.name}: an EA table of {len(lt.EA_table)} points "
                          f"(MoorDyn-C reads at most {MOORDYN_CURVE_POINTS})")
        if lt.EAd is not None and lt.material not in ("static_dynamic", "syrope"):
            omissions.append(f"line type {lt.name}: dynamic stiffness EAd (MoorDyn's EA_s|EA_Dc|"
                             "EA_D_Lm is another, viscoelastic, model)")
        if lt.displaced_area is not None and not math.isclose(
                lt.displaced_area, math.pi * lt.diameter**2 / 4.0):
            omissions.append(f"line type {lt.name}: displaced_area (MoorDyn uses pi d^2 / 4)")
    for p in system.points.values():
        if p.force[0] or p.force[1]:
            errors.append(f"point {p.name}: horizontal force")
        if p.force_history is not None:
            omissions.append(f"point {p.name}: force_history")
    for ln in system.lines.values():
        if ln.initial_shape is not None:
            omissions.append(f"line {ln.name}: initial_shape")
        if ln.clamp_a is not None or ln.clamp_b is not None:
            errors.append(f"line {ln.name}: a clamped end (MoorDyn clamps lines only at rods "
                          "and bodies)")
    errors += body_problems(system)
    return errors, omissions


def _fmt(value: float) -> str:
    return repr(float(value))


def _point_rows(system: System) -> list[str]:
    kinds = {"fixed": "Fixed", "prescribed": "Coupled", "free": "Free"}
    rho_g = system.environment.water_density * system.environment.gravity
    rows = []
    for i, p in enumerate(system.points.values(), start=1):
        volume = p.volume
        if p.force[2]:
            volume += p.force[2] / rho_g
            logger.warning("point %s: vertical force %g written as %g of extra volume (MoorDyn "
                           "points have no force input)", p.name, p.force[2], volume - p.volume)
        cda = p.Cd * p.drag_area
        values = [*p.position, p.mass, volume, cda, p.Ca]
        kind = body_attachment(system, p.body) if p.kind == "body" else kinds[p.kind]
        rows.append(f"{i:<4d} {kind:<8s} " + " ".join(_fmt(v) for v in values)
                    + f"   # {p.name}")
    return rows


def _line_type_rows(system: System, path: Path) -> list[str]:
    rows = []
    for lt in system.line_types.values():
        values = [lt.diameter, lt.mass_per_length, lt.EA, lt.BA, lt.EI, lt.Cd, lt.Ca, lt.Ct,
                  lt.Cat]
        cells = [_fmt(v) for v in values]
        if lt.EA_table is not None:
            cells[2] = _write_ea_table(lt, path.with_name(f"{path.stem}_{lt.name}_EA.dat"))
        if lt.material == "static_dynamic":  # MoorDyn's EA_s|EA_Dc|EA_D_Lm and BA_s|BA_d
            cells[2] = "|".join(_fmt(v) for v in (lt.EA, lt.EAd, lt.EAd_Lm))
            cells[3] = "|".join(_fmt(v) for v in (lt.BA, lt.BA_dynamic))
        if lt.material == "syrope":  # SYROPE:settings|EA_Dc|EA_D_Lm and BA_s|BA_d
            cells[2] = write_syrope_files(lt, path)
            cells[3] = "|".join(_fmt(v) for v in (lt.BA, lt.BA_dynamic))
        rows.append(f"{lt.name:<10s} " + " ".join(cells))
    return rows


def _write_ea_table(lt: LineType, path: Path) -> str:
    """Write a line type's tension-strain table as MoorDyn's EA file (three header lines, then
    ``strain tension`` rows; no final newline: MoorDyn-C v2.7 reads an empty last line as a
    bad curve point). MoorDyn interpolates the table linearly and holds the last tension beyond
    it, moorline's law is the monotone cubic through the same points (extrapolated linearly):
    write tables dense enough for the two to agree. Returns the file name."""
    rows = [f"---- {lt.name} tension-strain table (moorline) ----", "Strain Tension", "(-) (N)"]
    rows += [f"{_fmt(e)} {_fmt(t)}" for e, t in lt.EA_table]
    path.write_text("\n".join(rows), encoding="utf-8")
    return path.name


def _line_rows(system: System) -> list[str]:
    ids = {name: i for i, name in enumerate(system.points, start=1)}
    rows = []
    for i, ln in enumerate(system.lines.values(), start=1):
        rows.append(f"{i:<4d} {ln.line_type:<10s} {ids[ln.end_a]:<4d} {ids[ln.end_b]:<4d} "
                    f"{_fmt(ln.length)} {ln.segments:d} -   # {ln.name}")
    return rows


def _option_rows(system: System, dt: float, settings: Mapping[str, object]) -> list[str]:
    env = system.environment
    depth = env.depth
    deepest = max((-p.position[2] for p in system.points.values()), default=0.0)
    rows = [f"{_fmt(dt):<14s} dtM", f"{_fmt(env.gravity):<14s} g",
            f"{_fmt(env.water_density):<14s} rho"]
    if math.isfinite(depth):
        rows.append(f"{_fmt(depth):<14s} WtrDpth")
    else:  # no seabed: one far below everything, tagged so that the reader restores inf
        rows.append(f"{_fmt(max(1.0e4, 10.0 * deepest)):<14s} WtrDpth   # {_INF_DEPTH_TAG}")
    rows += [f"{_fmt(env.seabed.stiffness):<14s} kBot", f"{_fmt(env.seabed.damping):<14s} cBot"]
    if env.seabed.friction:
        rows.append(f"{_fmt(env.seabed.friction):<14s} FrictionCoefficient")
    for key, value in settings.items():
        text = _fmt(value) if isinstance(value, float) else str(value)
        rows.append(f"{text:<14s} {key}")
    return rows


def write_moordyn(system: System, path: str | Path, dt: float, *, tmax_ic: float = 1000.0,
                  thresh_ic: float = 1.0e-5, dt_ic: float = 1.0,
                  time_scheme: str | None = None,
                  extra_options: Mapping[str, object] | None = None) -> Path:
    """Write ``system`` as a MoorDyn v2 input file.

    Fixed points become ``Fixed``, prescribed points ``Coupled`` (driven through MoorDyn's
    coupling interface) and free points ``Free`` (``CdA = Cd * drag_area``). A vertical
    constant point force becomes extra ``Volume`` (MoorDyn points have no force column).
    Bodies that MoorDyn can express (:mod:`moorline.io.moordyn_bodies`) become ``BODIES``
    rows and their points ``Body<k>`` points (read back by :func:`read_moordyn_deck`).
    The case's ``output.channels`` become the ``OUTPUTS`` section (those moorline can compute,
    :func:`~moorline.io.moordyn_outputs.deck_channels`); its first dynamics analysis gives
    ``TMax`` (its duration) and ``dtOut`` (``output.every``, also written without dynamics
    when it is not the default), as :func:`~moorline.io.moordyn_outputs.time_settings`
    reads them back. ``dtM`` is the ``dt`` argument, not the analysis's implicit step.

    Parameters
    ----------
    system
        The problem; its units are used as they are (``g`` and ``rho`` are always written).
    path
        Output file.
    dt
        MoorDyn's internal time step ``dtM`` [time]. No ``CFL`` option is written, so MoorDyn
        uses ``dtM`` as given.
    tmax_ic, thresh_ic, dt_ic
        Initial-condition options ``TmaxIC``, ``threshIC``, ``dtIC``. MoorDyn-C v2.7 finds
        its initial condition with a stationary (static) solver that stops when the largest
        residual node acceleration falls below ``threshIC`` [m/s^2] or after ``TmaxIC``
        pseudo-seconds. Its default ``threshIC = 1e-3`` leaves the OC3 fairlead tension about
        0.01 % short of equilibrium; ``1e-5`` (default here) agrees with moorline's static
        solution to within 1e-6 at a cost of about 0.5 s for 20 segments. ``TmaxIC`` is only
        a cap.
    time_scheme
        MoorDyn ``tScheme`` (``RK2`` when omitted, MoorDyn's default).
    extra_options
        More ``{key: value}`` option rows (written after the others, so they win).

    Returns
    -------
    Path
        ``path``.

    Raises
    ------
    CaseError
        If the system holds something MoorDyn cannot express (the ``errors`` of
        :func:`unsupported_features`; its ``omissions`` are only logged).
    """
    errors, omissions = unsupported_features(system)
    if errors:
        raise CaseError("cannot be written as a MoorDyn deck: " + "; ".join(errors),
                        file=str(path))
    for omission in omissions:
        if omission == "current" and "Currents" in (extra_options or {}):
            continue  # written by the caller as a current file (moordyn_runner)
        logger.warning("MoorDyn deck %s: %s not written", path, omission)
    settings: dict[str, object] = {"dtIC": float(dt_ic), "TmaxIC": float(tmax_ic),
                                   "threshIC": float(thresh_ic), "writeLog": 0,
                                   "disableOutTime": 1, **time_options(system)}
    if time_scheme:
        settings["tScheme"] = time_scheme
    if not system.environment.seabed.is_flat and math.isfinite(system.environment.depth):
        settings["SeafloorFile"] = str(_write_seafloor_grid(system, Path(path)))
    settings.update(extra_options or {})
    head = ["Diam", "MassDen", "EA", "BA/-zeta", "EI", "Cd", "Ca", "CdAx", "CaAx"]
    units = ["(m)", "(kg/m)", "(N)", "(N-s/-)", "(N-m^2)", "(-)", "(-)", "(-)", "(-)"]
    text = [
        _rule("MoorDyn v2 input file"),
        f"written by moorline for case {system.name!r} ({system.units} units)",
        _rule("LINE TYPES"), "TypeName   " + " ".join(head), "(name)     " + " ".join(units),
        *_line_type_rows(system, Path(path)),
        *([_rule("BODIES"), *body_section(system)] if system.bodies else []),
        _rule("POINTS"), "ID   Attachment  X  Y  Z  Mass  Volume  CdA  Ca",
        "(#)  (-)  (m)  (m)  (m)  (kg)  (m^3)  (m^2)  (-)", *_point_rows(system),
        _rule("LINES"), "ID  LineType  AttachA  AttachB  UnstrLen  NumSegs  LineOutputs",
        "(#)  (name)  (#)  (#)  (m)  (-)  (-)", *_line_rows(system),
        *([_rule("SYROPE IC"), "Line(s)  Tmax0  Tmean0", "(-)  (N)  (N)", *ic]
          if (ic := syrope_ic_rows(system)) else []),
        _rule("OPTIONS"), *_option_rows(system, dt, settings),
        _rule("OUTPUTS"), *deck_channels(system), *(["END"] if system.output.channels else []),
        _rule("need this line"),
    ]
    path = Path(path)
    path.write_text("\n".join(text) + "\n", encoding="utf-8")
    return path


def _write_seafloor_grid(system: System, path: Path) -> Path:
    """Write the system's sloped or gridded seabed next to the deck as MoorDyn's 3-D seafloor
    file (``<deck>_seafloor.txt``; a plane as a 2 x 2 grid reaching a longest line beyond
    every point, bilinear interpolation being exact on a plane) and return its absolute
    path (MoorDyn opens it relative to its working directory)."""
    from ..mesh import sloped_seabed
    from ..model import Bathymetry
    from .seafloor import write_seafloor

    env = system.environment
    grid = env.seabed.bathymetry
    if grid is None:
        xyz = [p.position for p in system.points.values()]
        reach = max((line.length for line in system.lines.values()), default=1.0)
        x = (min(q[0] for q in xyz) - reach, max(q[0] for q in xyz) + reach)
        y = (min(q[1] for q in xyz) - reach, max(q[1] for q in xyz) + reach)
        corners = [[xi, yj, 0.0] for xi in x for yj in y]
        z = sloped_seabed(env).height(corners).reshape(2, 2)
        grid = Bathymetry(x=x, y=y, z=tuple(tuple(row) for row in z.tolist()))
    out = path.with_name(path.stem + "_seafloor.txt").resolve()
    return write_seafloor(grid, out)


def _rule(title: str) -> str:
    return f"{'-' * 22} {title} {'-' * max(4, 50 - len(title))}"
