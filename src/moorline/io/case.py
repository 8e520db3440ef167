"""Read a YAML case file into a :class:`moorline.model.System`.

Steps: parse YAML (duplicate keys are errors), check the unit system, validate keys, types,
units and bounds with the pydantic schema (:mod:`moorline.io.schema`), cross-check references
and geometry, then build the frozen model. Every failure is a
:class:`moorline.errors.CaseError` naming the file and the dotted key path.
"""

from __future__ import annotations

import logging
import math
import os
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import yaml
from pydantic import ValidationError

from moorline.analyses import KINDS
from moorline.errors import CaseError
from moorline.model import (
    Bathymetry,
    Body,
    Current,
    DesignSettings,
    Environment,
    Hydrostatics,
    Line,
    LineType,
    Motion,
    OutputSettings,
    Point,
    Seabed,
    SeaComponents,
    System,
    WaveExcitation,
    Waves,
)
from moorline.solvers.linearized_laws import sag_refusal

from .files import MAX_CASE_BYTES, MAX_TABLE_BYTES, file_problem
from .limits import (
    MAX_MEMORY,
    MAX_SEGMENTS,
    MAX_TIME_STEPS,
    MAX_WAVE_COMPONENTS,
    analysis_memory,
    wave_components,
)
from .line_catalog import resolve_line_types
from .schema import (
    MAX_MAGNITUDE,
    MIN_MAGNITUDE,
    CaseSpec,
    LineSpec,
    MotionSpec,
    PointSpec,
    StaticsSpec,
    StochasticSpec,
    check_number,
    describe_errors,
    dotted,
)
from .seafloor import grid_problem, read_seafloor
from .topology import geometry_problem
from .units import default_value

__all__ = ["MAX_DEPTH", "MAX_STRAIN", "MAX_VALUES", "SEABED_TOLERANCE", "load_case",
           "load_case_text"]

logger = logging.getLogger(__name__)

MAX_STRAIN = 1.0
"""Largest strain a line may need to reach between two fixed/prescribed ends.

A line is rejected when the distance between its ends exceeds ``length * (1 + MAX_STRAIN)``.
100 % is far beyond the elastic range of any mooring material (steel chain and wire < 1 %,
polyester ~ 10-15 % and nylon ~ 20-30 % at break), so only data errors trip it, while an
elastic line may legitimately be shorter than its span (a pretensioned string). It is not
lower because MoorDyn's own viscoelastic test deck (MoorDyn ``tests/Mooring/polyester/
visco.txt``, OpenFAST r-test ``modules/moordyn/md_viscoelastic``) stretches a 1 m segment
between points 2 m apart.
"""

MAX_DEPTH = 32
"""Deepest nesting of mappings and lists in a case file (a case needs 6: ``bodies.hull.
added_mass[i][j]``; 10,000 levels would exhaust Python's recursion limit)."""

MAX_VALUES = 2_000_000
"""Most values (numbers, strings, mappings and lists) in a case file once its YAML aliases
are expanded: a 100,000-segment initial shape has 400,000; nine aliases of nine aliases
("billion laughs") would have 387 million numbers."""

SEABED_TOLERANCE = 1.0e-6
"""A fixed or prescribed point may lie up to ``SEABED_TOLERANCE * depth`` below the seabed."""

UNIT_SYSTEMS = ("SI", "US")


def load_case(path: str | os.PathLike[str]) -> System:
    """Read and validate a YAML case file.

    Parameters
    ----------
    path
        The case file.

    Returns
    -------
    System
        The problem, in the case's unit system; ``System.source`` is ``str(path)``.

    Raises
    ------
    CaseError
        The file cannot be read or its content is invalid (names file and key path).
    """
    file = str(path)
    problem = file_problem(path, MAX_CASE_BYTES)
    if problem is not None:
        raise CaseError(f"cannot read the case file: {problem}", file=file)
    try:
        text = Path(path).read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        reason = exc.strerror if isinstance(exc, OSError) and exc.strerror else str(exc)
        raise CaseError(f"cannot read the case file: {reason}", file=file) from None
    return _load(text, file, source=file)


def load_case_text(text: str, file: str = "<string>") -> System:
    """Read and validate a case given as YAML text.

    Parameters
    ----------
    text
        The YAML content.
    file
        Name used in error messages (and as ``System.source`` unless it is ``"<string>"``).

    Returns
    -------
    System
        The problem, in the case's unit system.

    Raises
    ------
    CaseError
        The content is invalid (names ``file`` and the key path).
    """
    return _load(text, file, source=None if file == "<string>" else file)


def _load(text: str, file: str, source: str | None) -> System:
    data = _parse_yaml(text, file)
    if not isinstance(data, dict):
        got = "an empty file" if data is None else f"a {type(data).__name__}"
        raise CaseError(
            f"the top level must be a mapping of keys (name, units, environment, line_types, "
            f"points, lines, analyses, output), got {got}",
            file=file,
        )
    units = data.get("units", "SI")
    if units not in UNIT_SYSTEMS:
        raise CaseError(
            f"unknown unit system {units!r}; allowed: {', '.join(UNIT_SYSTEMS)}",
            file=file,
            field="units",
        )
    try:
        spec = CaseSpec.model_validate(data, context={"units": units})
    except ValidationError as exc:
        field, reason = describe_errors(exc)
        raise CaseError(reason, file=file, field=field) from None
    line_types = resolve_line_types(spec.line_types, units, file, source)
    seabed = _seabed(spec, file, source)
    _cross_check(spec, file, seabed)
    system = _build(spec, source, line_types, seabed)
    logger.debug("loaded case %r from %s", system.name, file)
    return system


# --------------------------------------------------------------------------------------------
# YAML


class _Loader(getattr(yaml, "CSafeLoader", yaml.SafeLoader)):  # type: ignore[misc]
    """Safe loader that rejects duplicate keys (YAML would silently keep the last one); on
    libyaml's parser where PyYAML has it (``CSafeLoader``: the P1 case parses in 3 ms instead
    of 29).

    Merge keys work as YAML defines them (https://yaml.org/type/merge.html): ``<<: *base``
    inserts the keys of ``base`` that the mapping does not give itself; only keys written
    twice in the mapping itself are duplicates."""


def _construct_mapping(loader: _Loader, node: yaml.MappingNode, deep: bool = False) -> Any:
    seen: set[Any] = set()
    own = [k for k, _ in node.value if k.tag != "tag:yaml.org,2002:merge"]
    for key_node in own:
        key = loader.construct_object(key_node, deep=deep)
        try:
            duplicate = key in seen
        except TypeError:
            continue  # unhashable key: construct_mapping reports it
        if duplicate:
            raise yaml.constructor.ConstructorError(
                None, None, f"duplicate key {key!r}", key_node.start_mark
            )
        seen.add(key)
    return loader.construct_mapping(node, deep=deep)  # flattens the merge keys


_Loader.add_constructor(yaml.resolver.BaseResolver.DEFAULT_MAPPING_TAG, _construct_mapping)


def _parse_yaml(text: str, file: str) -> Any:
    too_deep = (f"nested too deeply for the parser (a case needs at most MAX_DEPTH = "
                f"{MAX_DEPTH} levels of mappings and lists)")
    try:
        data = yaml.load(text, Loader=_Loader)  # noqa: S506 - a SafeLoader subclass
    except RecursionError:  # PyYAML's Python parser
        raise CaseError(f"malformed YAML: {too_deep}", file=file) from None
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        problem = getattr(exc, "problem", None) or str(exc).splitlines()[0]
        if "maximum nesting depth" in problem:  # libyaml's parser
            problem = too_deep
        where = f" at line {mark.line + 1}, column {mark.column + 1}" if mark else ""
        raise CaseError(f"malformed YAML{where}: {problem}", file=file) from None
    path = _too_deep(data)
    if path is not None:
        raise CaseError(f"nested more than MAX_DEPTH = {MAX_DEPTH} levels of mappings and "
                        f"lists (no case key is that deep)", file=file, field=path)
    count = _size(data, {})
    if count > MAX_VALUES:
        raise CaseError(f"holds {count:.3g} values once its aliases (*name) are expanded, more "
                        f"than MAX_VALUES = {MAX_VALUES}", file=file)
    return data


def _children(value: Any) -> Any:
    if isinstance(value, dict):
        return value.items()
    return enumerate(value) if isinstance(value, list) else ()


def _too_deep(data: Any) -> str | None:
    """Key path of the first value nested deeper than :data:`MAX_DEPTH`, else ``None``.

    Aliases make the data a graph (even a cyclic one): a mapping or list is walked again
    only when it is reached deeper than before, so at most ``MAX_DEPTH`` times.
    """
    stack: list[tuple[Any, list[str | int]]] = [(data, [])]
    reached: dict[int, int] = {}
    while stack:
        value, parts = stack.pop()
        if not isinstance(value, dict | list):
            continue
        if len(parts) > MAX_DEPTH:
            return dotted(parts[:MAX_DEPTH + 1])
        if reached.get(id(value), -1) >= len(parts):
            continue
        reached[id(value)] = len(parts)
        stack.extend((v, [*parts, k if isinstance(k, int) else str(k)])
                     for k, v in _children(value))
    return None


def _size(value: Any, memo: dict[int, int]) -> int:
    """Number of values with aliases expanded (the data is acyclic and at most
    :data:`MAX_DEPTH` deep: checked first)."""
    if not isinstance(value, dict | list):
        return 1
    if id(value) not in memo:
        memo[id(value)] = 1 + sum(_size(v, memo) for _, v in _children(value))
    return memo[id(value)]


# --------------------------------------------------------------------------------------------
# cross-checks


def _cross_check(spec: CaseSpec, file: str, seabed: Seabed) -> None:
    """References, geometry and combinations that single fields cannot check."""

    def fail(reason: str, field: str) -> None:
        raise CaseError(reason, file=file, field=field)

    env = spec.environment
    levels = env.current.z_levels
    if levels is not None or env.current.speeds is not None:
        n = len(levels or [])
        if n < 1 or len(env.current.speeds or []) != n:
            fail(f"a current profile needs as many speeds as z_levels ({n}), got "
                 f"{len(env.current.speeds or [])}", "environment.current.speeds")
        if env.current.headings is not None and len(env.current.headings) != n:
            fail(f"headings must have {n} entries like z_levels", "environment.current.headings")
    for k, analysis in enumerate(spec.analyses or ()):
        if analysis.kind == "offset":
            from ..offset_group import OffsetGroupError, resolve_group

            try:
                resolve_group(spec.points, spec.bodies, analysis.body, analysis.points or ())
            except OffsetGroupError as exc:
                fail(str(exc), f"analyses[{k}].{exc.key}")
        if isinstance(analysis, StochasticSpec):
            if env.waves.kind != "random":
                why = (" (explicit components have no spectrum: use a dynamics analysis)"
                       if env.waves.kind == "components" else "")
                fail("a stochastic analysis needs a random sea (environment.waves kind: "
                     f"random), not {env.waves.kind!r}{why}", f"analyses[{k}].kind")
    if env.gravity == 0.0 and env.waves.kind != "none":
        fail("waves need gravity > 0 (the dispersion relation)", "environment.gravity")
    if env.waves.kind in ("airy", "random"):
        what = "an airy wave" if env.waves.kind == "airy" else "a random sea (Hs, Tp)"
        for key in ("height", "period"):
            if getattr(env.waves, key) <= 0.0:
                fail(f"{what} needs {key} > 0", f"environment.waves.{key}")
    _check_components(env.waves, fail)
    headings = env.waves.components.headings if env.waves.components is not None else None
    tables = [n for n, b in (spec.bodies or {}).items()
              if b.excitation is not None or b.hydrodynamics is not None]
    if tables and headings and any(h != env.waves.heading for h in headings):
        fail(f"body {tables[0]}'s exciting forces are for one heading (waves.heading = "
             f"{env.waves.heading:g} deg): components of other headings would get them too; "
             "give every component that heading", "environment.waves.components.headings")
    for name, lt in spec.line_types.items():
        if lt.material == "viscoelastic" and lt.tau <= 0.0:
            fail(f"a viscoelastic material needs tau > 0, got {lt.tau:g}", f"line_types.{name}.tau")
        if lt.material in ("static_dynamic", "syrope"):
            if lt.material == "static_dynamic":
                _check_static_dynamic(name, lt, fail)
            else:
                check_syrope(name, lt, spec.lines, fail)
            what = ("mean-load dependent viscoelastic model" if lt.material == "static_dynamic"
                    else "Syrope rope with load-history dependent working curves")
            for k, analysis in enumerate(spec.analyses or ()):
                if analysis.kind in ("modal", "strumming", "stochastic", "harmonic"):
                    fail(f"line type {name} is a {lt.material} rope (MoorDyn's {what}), "
                         f"modelled in statics and the time domain only: no "
                         f"{analysis.kind} analysis (not linearized)", f"analyses[{k}].kind")
    for name, line in spec.lines.items():
        if line.syrope_ic is not None and (line.type not in spec.line_types or
                                           spec.line_types[line.type].material != "syrope"):
            fail("syrope_ic is for lines of a syrope line type", f"lines.{name}.syrope_ic")
    _check_sag(spec, fail)
    depth = env.depth if env.depth is not None else math.inf
    bodies = spec.bodies or {}
    surface = _surface(depth, seabed)
    for name, point in spec.points.items():
        local = depth if surface is None else -float(surface.height(
            np.asarray([point.position[:2]], dtype=float))[0])
        _check_point(name, point, local, fail)
        if point.kind == "body" and point.body not in bodies:
            fail(f"unknown body {point.body!r}; known bodies: {_known(list(bodies))}",
                 f"points.{name}.body")
        if point.kind != "body" and point.body is not None:
            fail(f"only body points take 'body'; this point is {point.kind}",
                 f"points.{name}.body")
    for name, body in bodies.items():
        if body.pin_body is not None:
            parent = bodies.get(body.pin_body)
            if body.kind != "pinned" or body.motion is not None:
                fail("only a pinned body without a motion takes a pin_body",
                     f"bodies.{name}.pin_body")
            if parent is None or body.pin_body == name or parent.kind == "pinned":
                fail(f"pin_body {body.pin_body!r} must be another body, free or fixed "
                     f"(bodies: {', '.join(bodies)})", f"bodies.{name}.pin_body")
        if body.motion is not None:
            if body.kind != "pinned":
                fail(f"only pinned bodies take a motion (of their pin); this body is "
                     f"{body.kind}", f"bodies.{name}.motion")
            _check_history(body.motion, f"bodies.{name}.motion", fail)
        hydro = body.hydrodynamics
        if hydro is not None:
            if (hydro.database is None) == (hydro.bem is None):
                fail("give exactly one of database (a NetCDF file) and bem (computed)",
                     f"bodies.{name}.hydrodynamics")
            given = [k for k in ("added_mass", "damping", "excitation")
                     if getattr(body, k) is not None]
            if given:
                fail(f"a body with hydrodynamics takes its radiation and wave loads from "
                     f"the database: remove {' and '.join(given)} (or hydrodynamics)",
                     f"bodies.{name}.{given[0]}")
        ex = body.excitation
        if ex is not None:
            n = len(ex.omegas)
            rows_ok = all(len(r) == 6 for r in ex.amplitude + ex.phase)
            if n < 1 or len(ex.amplitude) != n or len(ex.phase) != n or not rows_ok:
                fail(f"needs one row of 6 amplitudes and 6 phases per frequency ({n})",
                     f"bodies.{name}.excitation")
            if any(b <= a for a, b in zip(ex.omegas, ex.omegas[1:], strict=False)):
                fail("omegas must increase strictly", f"bodies.{name}.excitation.omegas")
        hs = body.hydrostatics
        need = {"box": ("length", "width", "height"), "cylinder": ("diameter", "height"),
                "matrix": ()}.get(hs.kind, ())
        if hs.kind == "rods" and not hs.rods:
            fail("rods hydrostatics needs at least one rod", f"bodies.{name}.hydrostatics.rods")
        for key in need:
            if getattr(hs, key) <= 0:
                fail(f"a {hs.kind} needs {key} > 0", f"bodies.{name}.hydrostatics.{key}")
    for name, line in spec.lines.items():
        _check_line(spec, name, line, fail)
    attached = {p for line in spec.lines.values() for p in (line.end_a, line.end_b)}
    for name, point in spec.points.items():
        if point.kind == "free" and name not in attached:
            fail(f"free point {name!r} is not attached to any line", f"points.{name}")
    problem = geometry_problem(spec.points, spec.lines, spec.bodies)
    if problem is not None:
        fail(*problem)
    _check_sizes(spec, fail)


def _check_components(waves: Any, fail: Callable[[str, str], None]) -> None:
    """``kind: components`` needs ``components`` (lists of one length), no other kind
    takes them."""
    given = waves.components
    if waves.kind != "components":
        if given is not None:
            fail(f"components are read only with kind: components, not {waves.kind!r}",
                 "environment.waves.components")
        return
    if given is None:
        fail("kind: components needs components: {omegas, amplitudes, phases}",
             "environment.waves.components")
    n = len(given.omegas)
    if n < 1:
        fail("needs at least one component", "environment.waves.components.omegas")
    for key in ("amplitudes", "phases", "headings"):
        values = getattr(given, key)
        if values is not None and len(values) != n:
            fail(f"{len(values)} {key} for {n} omegas (one per component)",
                 f"environment.waves.components.{key}")


def _check_sizes(spec: CaseSpec, fail: Callable[[str, str], None]) -> None:
    """Segments, random-sea components and each analysis' memory within
    :mod:`moorline.io.limits`."""
    total = 0
    for name, line in spec.lines.items():
        total += line.segments
        if total > MAX_SEGMENTS:
            before = " (with the lines before)" if total > line.segments else ""
            fail(f"{line.segments:.6g} segments{before} are more than MAX_SEGMENTS = "
                 f"{MAX_SEGMENTS} for the whole case", f"lines.{name}.segments")
    waves = spec.environment.waves
    components = 0
    if waves.kind in ("random", "components"):
        components = wave_components(_waves(waves))
        if components > MAX_WAVE_COMPONENTS:
            key = ("components.omegas" if waves.kind == "components" else "n_frequencies"
                   if waves.n_frequencies is not None else "record_length")
            fail(f"the random sea would have {components:.3g} components, more than "
                 f"MAX_WAVE_COMPONENTS = {MAX_WAVE_COMPONENTS} (components: n_frequencies, or "
                 f"omega_max * record_length / 2 pi)", f"environment.waves.{key}")
    n_nodes = total + len(spec.lines)
    every = spec.output.every or default_value("output_every", spec.units)
    for k, analysis in enumerate(spec.analyses or ()):
        if analysis.kind in ("dynamics", "strumming"):
            steps = analysis.duration / analysis.dt * getattr(analysis, "substeps", 1)
            if steps > MAX_TIME_STEPS:
                fail(f"duration / dt (x substeps) = {steps:.3g} time steps, more than "
                     f"MAX_TIME_STEPS = {MAX_TIME_STEPS:.0e}", f"analyses[{k}].dt")
        if analysis.kind == "dynamics":
            _check_resolved_periods(spec, analysis.dt, f"analyses[{k}].dt", fail)
        need, what, key = analysis_memory(analysis.kind, analysis, n_nodes, components, every)
        if need > MAX_MEMORY:
            field = f"analyses[{k}].{key}" if key else "environment.waves.record_length"
            fail(f"{analysis.kind} would need about {need / 1024**3:.3g} GiB ({what}, "
                 f"{n_nodes} nodes), more than MAX_MEMORY = {MAX_MEMORY / 1024**3:g} GiB",
                 field)


def _check_resolved_periods(spec: CaseSpec, dt: float, field: str,
                            fail: Callable[[str, str], None]) -> None:
    """Harmonic motions and force histories must last at least two time steps a period: a
    step cannot resolve a faster one (the run would alias it and look fine)."""
    histories = []
    for name, point in spec.points.items():
        histories += [(f"points.{name}.motion", point.motion),
                      (f"points.{name}.force_history", point.force_history)]
    for name, body in (spec.bodies or {}).items():
        histories += [(f"bodies.{name}.force_history", body.force_history),
                      (f"bodies.{name}.motion", body.motion)]
    for key, history in histories:
        if history is not None and history.kind == "harmonic" and history.period is not None \
                and history.period < 2.0 * dt:
            fail(f"period {history.period:g} is shorter than two time steps of the dynamics "
                 f"({field} = {dt:g}): the step cannot resolve it", f"{key}.period")


def _check_sag(spec: CaseSpec, fail: Callable[[str, str], None]) -> None:
    """Sag-corrected lines (:mod:`moorline.physics.sag`): elastic line types without a
    fibre-rope dynamic stiffness, and no linearized analysis but the modal one."""
    for name, line in spec.lines.items():
        if line.element != "sag_corrected":
            continue
        lt = spec.line_types.get(line.type)
        if lt is not None and (lt.material != "elastic" or lt.EAd is not None):
            what = f"material {lt.material!r}" if lt.material != "elastic" else "EAd"
            fail(f"sag-corrected elements need an elastic line type without EAd; line type "
                 f"{line.type!r} has {what}", f"lines.{name}.element")
        for k, analysis in enumerate(spec.analyses or ()):
            if analysis.kind in ("strumming", "stochastic", "harmonic"):
                fail(sag_refusal(name, analysis.kind), f"analyses[{k}].kind")
            if analysis.kind == "dynamics":
                # measured on the OC3 10 s surge (README): the sag of the weight alone moves
                # a near-slack minimum by +60 to +117 % from the converged straight elements
                logger.warning("line %s: sag-corrected elements in dynamics carry the sag of "
                               "their weight only (not of their inertia or drag): right for "
                               "slow motions, wrong near slack (use element: straight for "
                               "dynamics with slack phases)", name)
def check_syrope(name: str, lt, lines: dict, fail) -> None:
    """A ``syrope`` line type (:mod:`moorline.physics.syrope`): its curves, dynamic stiffness
    and dampings, and each of its lines' ``syrope_ic``."""
    from ..physics.syrope import SyropeRope

    where = f"line_types.{name}"
    if lt.owc is None:
        fail("a syrope material needs owc (the original working curve)", f"{where}.owc")
    if lt.EAd is None:
        fail("a syrope material needs EAd (the dynamic stiffness at zero load)",
             f"{where}.EAd")
    if not isinstance(lt.BA, int | float) or lt.BA < 0 or lt.BA + lt.BA_dynamic <= 0:
        fail("a syrope material needs BA >= 0 (no damping ratio) and BA + BA_dynamic > 0",
             f"{where}.BA")
    rope = SyropeRope(np.asarray(lt.owc, dtype=float), lt.working_curve, lt.wc_k1, lt.wc_k2,
                      float(lt.EAd), float(lt.EAd_Lm))
    problems = rope.problems()
    if problems:
        fail("; ".join(problems), f"{where}.owc")
    for line_name, line in lines.items():
        if line.type != name:
            continue
        if line.syrope_ic is None:
            fail(f"a line of the syrope line type {name} needs syrope_ic: [Tmax0, Tmean0]",
                 f"lines.{line_name}.syrope_ic")
        problem = rope.tmax_problem(line.syrope_ic[0])
        if problem is not None:
            fail(problem, f"lines.{line_name}.syrope_ic")


def _check_static_dynamic(name: str, lt, fail) -> None:
    """A ``static_dynamic`` line type (:mod:`moorline.physics.static_dynamic`): a constant
    static ``EA``, a dynamic stiffness ``EAd`` above it, and some damping in a branch."""
    where = f"line_types.{name}"
    if lt.EA_table is not None or isinstance(lt.EA, dict):
        fail("a static_dynamic material needs a constant static EA (no table)", f"{where}.EA")
    if lt.EAd is None:
        fail("a static_dynamic material needs EAd (the dynamic stiffness at zero load)",
             f"{where}.EAd")
    elif isinstance(lt.EA, int | float) and not lt.EAd > lt.EA:
        fail(f"a static_dynamic material needs EAd > EA (the static stiffness), got EAd "
             f"{lt.EAd:g} and EA {lt.EA:g}", f"{where}.EAd")
    if lt.BA == 0.0 and lt.BA_dynamic == 0.0:
        fail("a static_dynamic material needs damping in a branch (BA or BA_dynamic > 0)",
             f"{where}.BA")


def _check_point(
    name: str, point: PointSpec, depth: float, fail: Callable[[str, str], None]
) -> None:
    if point.initial_position is not None and point.kind != "prescribed":
        fail(
            f"only prescribed points take an initial_position; this point is {point.kind}",
            f"points.{name}.initial_position",
        )
    for key, kind in (("motion", "prescribed"), ("force_history", "free")):
        history = getattr(point, key)
        if history is not None and point.kind != kind:
            fail(f"only {kind} points take a {key}; this point is {point.kind}",
                 f"points.{name}.{key}")
        if history is not None:
            _check_history(history, f"points.{name}.{key}", fail)
    if point.kind in ("free", "body") or not math.isfinite(depth):
        return
    for key in ("position", "initial_position"):
        xyz = getattr(point, key)
        if xyz is not None and xyz[2] < -depth * (1 + SEABED_TOLERANCE):
            fail(
                f"{point.kind} point is below the seabed: z = {xyz[2]:g} < {-depth:g}",
                f"points.{name}.{key}[2]",
            )


def _check_history(history: MotionSpec, field: str, fail: Callable[[str, str], None]) -> None:
    if history.kind == "harmonic" and history.period is None:
        fail("a harmonic history needs a period > 0", f"{field}.period")
    if history.kind == "table":
        given = (history.times is not None, history.values is not None)
        if history.file is None and not all(given):
            fail("a table history needs 'times' and 'values', or a CSV 'file'", field)
        if history.file is None and len(history.times) != len(history.values):
            fail(f"'times' has {len(history.times)} entries but 'values' has "
                 f"{len(history.values)}", f"{field}.values")
        if history.file is None and len(history.times) < 2:
            fail(f"a table history needs >= 2 rows, got {len(history.times)}", f"{field}.times")
        if history.times is not None and any(
                b <= a for a, b in zip(history.times, history.times[1:], strict=False)):
            fail("'times' must increase strictly", f"{field}.times")


def _start(point: PointSpec) -> Sequence[float]:
    """Where statics starts a point from."""
    return point.initial_position if point.initial_position is not None else point.position


def _known(names: Sequence[str]) -> str:
    return ", ".join(names) if names else "(none)"


def _check_line(
    spec: CaseSpec, name: str, line: LineSpec, fail: Callable[[str, str], None]
) -> None:
    where = f"lines.{name}"
    if line.type not in spec.line_types:
        fail(
            f"unknown line type {line.type!r}; known line types: {_known(list(spec.line_types))}",
            f"{where}.type",
        )
    for end in ("end_a", "end_b"):
        point = getattr(line, end)
        if point not in spec.points:
            fail(
                f"unknown point {point!r}; known points: {_known(list(spec.points))}",
                f"{where}.{end}",
            )
    if line.end_a == line.end_b:
        fail(
            f"both ends are the point {line.end_a!r}; a line needs two different points",
            f"{where}.end_b",
        )
    a, b = spec.points[line.end_a], spec.points[line.end_b]
    for key, point in (("clamp_a", a), ("clamp_b", b)):
        direction = getattr(line, key)
        if direction is None:
            continue
        if not any(direction):
            fail("a clamped end needs a nonzero direction", f"{where}.{key}")
        if point.kind not in ("fixed", "prescribed"):
            fail(f"a clamped end needs a fixed or prescribed point, not {point.kind!r} (the "
                 "direction is held fixed in space)", f"{where}.{key}")
        if line.type in spec.line_types and not spec.line_types[line.type].EI > 0:
            fail(f"a clamped end needs bending stiffness: line type {line.type!r} has no EI",
                 f"{where}.{key}")
    span = math.dist(a.position, b.position)
    if a.kind in ("fixed", "prescribed") and b.kind in ("fixed", "prescribed") \
            and span > line.length * (1 + MAX_STRAIN):
        fail(
            f"too short to span its ends: {line.end_a!r} and {line.end_b!r} are {span:.6g} "
            f"apart, more than length*(1 + MAX_STRAIN) = {line.length * (1 + MAX_STRAIN):.6g} "
            f"(length {line.length:g}, MAX_STRAIN = {MAX_STRAIN})",
            f"{where}.length",
        )
    if line.initial_shape is not None:
        _check_shape(line, _start(a), _start(b), where, fail)


def _check_shape(
    line: LineSpec,
    start: Sequence[float],
    end: Sequence[float],
    where: str,
    fail: Callable[[str, str], None],
) -> None:
    shape = line.initial_shape or []
    rows = line.segments + 1
    if len(shape) != rows:
        fail(
            f"must have segments + 1 = {rows} rows, got {len(shape)}",
            f"{where}.initial_shape",
        )
    tolerance = 1.0e-6 * max(line.length, 1.0)
    for index, point, end_key in ((0, start, "end_a"), (rows - 1, end, "end_b")):
        if math.dist(shape[index], point) > tolerance:
            fail(
                f"must be at {end_key} {getattr(line, end_key)!r} {_xyz(point)}, "
                f"got {_xyz(shape[index])}",
                f"{where}.initial_shape[{index}]",
            )


def _xyz(v: Sequence[float]) -> str:
    return "(" + ", ".join(f"{c:g}" for c in v) + ")"


# --------------------------------------------------------------------------------------------
# spec -> model


def _build(spec: CaseSpec, source: str | None, line_types: dict[str, LineType],
           seabed: Seabed) -> System:
    units = spec.units

    def default(value: float | None, key: str) -> float:
        return value if value is not None else default_value(key, units)

    env = spec.environment
    environment = Environment(
        depth=env.depth if env.depth is not None else math.inf,
        water_density=default(env.water_density, "water_density"),
        gravity=default(env.gravity, "gravity"),
        seabed=seabed,
        current=_current(env.current),
        waves=_waves(env.waves),
    )
    points = {
        name: Point(
            name=name,
            kind=p.kind,
            position=tuple(p.position),
            mass=p.mass,
            volume=p.volume,
            force=tuple(p.force),
            initial_position=None if p.initial_position is None else tuple(p.initial_position),
            motion=_motion(p.motion, source, f"points.{name}.motion"),
            force_history=_motion(p.force_history, source, f"points.{name}.force_history"),
            Cd=p.Cd,
            drag_area=p.drag_area,
            Ca=p.Ca,
            body=p.body,
        )
        for name, p in spec.points.items()
    }
    lines = {name: _line(name, line) for name, line in spec.lines.items()}
    bodies = {name: _body(name, b, source, environment, units)
              for name, b in (spec.bodies or {}).items()}
    if spec.analyses is None:
        analyses: tuple[Any, ...] = (_settings(StaticsSpec(kind="statics"), units),)
    else:
        analyses = tuple(_settings(a, units) for a in spec.analyses)
    return System(
        name=spec.name,
        units=units,
        environment=environment,
        line_types=line_types,
        points=points,
        lines=lines,
        bodies=bodies,
        analyses=analyses,
        output=OutputSettings(every=default(spec.output.every, "output_every"),
                              channels=tuple(spec.output.channels)),
        source=source,
        design=None if spec.design is None else DesignSettings(**spec.design.model_dump()),
    )


def _body(name: str, spec: Any, source: str | None, environment: Environment,
          units: str) -> Body:
    hs = spec.hydrostatics
    off = {(0, 1): 0, (0, 2): 1, (1, 2): 2}
    inertia = tuple(tuple(spec.inertia[i] if i == j else
                          spec.products_of_inertia[off[(min(i, j), max(i, j))]]
                          for j in range(3)) for i in range(3))
    hydrostatics = Hydrostatics(kind=hs.kind, length=hs.length, width=hs.width,
                                height=hs.height, diameter=hs.diameter,
                                stiffness=hs.stiffness, volume=hs.volume,
                                center_of_buoyancy=tuple(hs.center_of_buoyancy),
                                rods=tuple((tuple(r.end_a), tuple(r.end_b), r.diameter)
                                           for r in hs.rods))
    excitation, radiation = _excitation(spec.excitation), None
    if spec.hydrodynamics is not None:
        from .hydrodynamics import body_hydrodynamics

        hydro = body_hydrodynamics(name, spec, environment, units, source)
        excitation, radiation = hydro.excitation, hydro.radiation
        if hs.kind == "none" and hydro.hydrostatics is not None:
            hydrostatics = hydro.hydrostatics
    return Body(
        name=name, kind=spec.kind, position=tuple(spec.position),
        rotation=tuple(math.radians(a) for a in spec.rotation), mass=spec.mass,
        center_of_gravity=tuple(spec.center_of_gravity), inertia=inertia,
        added_mass=spec.added_mass, damping=spec.damping,
        additional_damping=spec.additional_damping, hydrostatics=hydrostatics,
        force=(*spec.force, *spec.moment),
        force_history=_motion(spec.force_history, source, f"bodies.{name}.force_history"),
        drag_area=tuple(spec.drag_area), Cd=spec.Cd, wave_loads=spec.wave_loads,
        excitation=excitation, radiation=radiation,
        motion=_motion(spec.motion, source, f"bodies.{name}.motion"), pin_body=spec.pin_body)


def _seabed(spec: CaseSpec, file: str, source: str | None) -> Seabed:
    """``environment.seabed`` as a :class:`Seabed`: defaults of the unit system, and a slope
    or a bathymetry grid (inline or a MoorDyn seafloor file relative to the case file)."""
    sb, units, field = spec.environment.seabed, spec.units, "environment.seabed"

    def default(value: float | None, key: str) -> float:
        return value if value is not None else default_value(key, units)

    def fail(reason: str, key: str) -> CaseError:
        return CaseError(reason, file=file, field=f"{field}.{key}")

    if not sb.slope < 90.0:
        raise fail(f"must be below 90 degrees, got {sb.slope:g}", "slope")
    bathymetry = None
    if sb.bathymetry is not None:
        if sb.slope:
            raise fail("give either a slope or a bathymetry grid, not both", "bathymetry")
        depth = spec.environment.depth
        if depth is None or not math.isfinite(depth):
            raise fail("a bathymetry grid needs a finite environment.depth (the water depth "
                       "of the waves and the reference of the plots)", "bathymetry")
        if isinstance(sb.bathymetry, str):
            base = Path(source).parent if source else Path.cwd()
            try:
                bathymetry = read_seafloor(base / sb.bathymetry, field=f"{field}.bathymetry")
            except CaseError as exc:
                raise CaseError(exc.reason, file=file, field=exc.field) from None
        else:
            grid = sb.bathymetry
            problem = grid_problem(grid.x, grid.y, grid.z)
            if problem is not None:
                raise fail(problem, "bathymetry")
            bathymetry = Bathymetry(x=tuple(grid.x), y=tuple(grid.y),
                                    z=tuple(tuple(r) for r in grid.z))
    return Seabed(
        stiffness=default(sb.stiffness, "seabed_stiffness"),
        damping=default(sb.damping, "seabed_damping"),
        friction=sb.friction, friction_axial=sb.friction_axial,
        friction_transverse=sb.friction_transverse,
        slip_velocity=default(sb.slip_velocity, "slip_velocity"),
        slope_deg=sb.slope, slope_heading_deg=sb.slope_heading, bathymetry=bathymetry)


def _surface(depth: float, seabed: Seabed):
    """The sloped or gridded seabed surface (``None``: flat or no seabed)."""
    from ..mesh import sloped_seabed

    return sloped_seabed(Environment(depth=depth, seabed=seabed))


def _waves(spec: Any) -> Waves:
    given = spec.components
    components = None if given is None else SeaComponents(
        omegas=tuple(given.omegas), amplitudes=tuple(given.amplitudes),
        phases_deg=tuple(given.phases), headings_deg=tuple(given.headings or ()))
    return Waves(heading_deg=spec.heading, phase_deg=spec.phase, components=components,
                 **spec.model_dump(exclude={"heading", "phase", "components"}))


def _excitation(spec: Any) -> WaveExcitation | None:
    if spec is None:
        return None
    return WaveExcitation(tuple(spec.omegas), tuple(tuple(r) for r in spec.amplitude),
                          tuple(tuple(r) for r in spec.phase))


def _current(spec: Any) -> Current:
    if not spec.z_levels:
        return Current(speed=spec.speed, heading_deg=spec.heading)
    headings = spec.headings if spec.headings else [spec.heading] * len(spec.z_levels)
    return Current(speed=spec.speed, heading_deg=spec.heading, z_levels=tuple(spec.z_levels),
                   speeds=tuple(spec.speeds), headings_deg=tuple(headings))


def _line(name: str, line: LineSpec) -> Line:
    shape = None
    if line.initial_shape is not None:
        shape = tuple(tuple(row) for row in line.initial_shape)
    return Line(
        name=name,
        line_type=line.type,
        length=line.length,
        segments=line.segments,
        end_a=line.end_a,
        end_b=line.end_b,
        initial_shape=shape,
        clamp_a=None if line.clamp_a is None else tuple(line.clamp_a),
        clamp_b=None if line.clamp_b is None else tuple(line.clamp_b),
        element=line.element,
        syrope_ic=None if line.syrope_ic is None else tuple(line.syrope_ic),
    )


def _settings(spec: Any, units: str) -> Any:
    """The settings object of an ``analyses[i]`` spec (:data:`moorline.analyses.KINDS`):
    unit-dependent defaults filled in, lists as tuples."""
    kind = KINDS[spec.kind]
    values = spec.model_dump(warnings=False)
    for key, default in kind.unit_defaults.items():
        if values[key] is None:
            values[key] = default_value(default, units)  # type: ignore[arg-type]
    return kind.settings(**{k: tuple(v) if isinstance(v, list) else v
                            for k, v in values.items()})


def _motion(spec: MotionSpec | None, source: str | None, field: str) -> Motion | None:
    """A history spec as a :class:`Motion`, reading a CSV table relative to the case file."""
    if spec is None:
        return None
    times, values = spec.times or [], spec.values or []
    if spec.file is not None:
        times, values = _read_table(spec.file, source, field)
    return Motion(kind=spec.kind, amplitude=tuple(spec.amplitude), period=spec.period or 0.0,
                  phase_deg=spec.phase, times=tuple(times),
                  values=tuple(tuple(v) for v in values), ramp_time=spec.ramp_time)


def _read_table(name: str, source: str | None, field: str) -> tuple[list, list]:
    """Read ``t, x, y, z`` rows from a CSV file (``#`` comments and a header row allowed)."""
    import numpy as np

    base = Path(source).parent if source else Path.cwd()
    path = (base / name).resolve()
    problem = file_problem(path, MAX_TABLE_BYTES)
    if problem is not None:
        raise CaseError(f"cannot read time table {str(path)!r}: {problem}", file=source,
                        field=f"{field}.file")
    try:
        data = np.loadtxt(path, delimiter=",", comments="#", ndmin=2,
                          skiprows=_header_rows(path))
    except (OSError, ValueError) as exc:
        raise CaseError(f"cannot read time table {str(path)!r}: {exc}", file=source,
                        field=f"{field}.file") from None
    if data.shape[1] != 4 or len(data) < 2:
        raise CaseError(f"time table {str(path)!r} must have >= 2 rows of 4 columns t, x, y, z",
                        file=source, field=f"{field}.file")
    size = np.abs(data)
    bad = np.argwhere(~np.isfinite(data) | (size > MAX_MAGNITUDE)
                      | ((data != 0.0) & (size < MIN_MAGNITUDE)))
    if len(bad):
        row, column = bad[0]
        raise CaseError(f"time table {str(path)!r}, data row {row + 1}, column {column + 1}: "
                        f"{check_number(float(data[row, column]))}", file=source,
                        field=f"{field}.file")
    if np.any(np.diff(data[:, 0]) <= 0):
        raise CaseError(f"time table {str(path)!r}: times must increase strictly", file=source,
                        field=f"{field}.file")
    return data[:, 0].tolist(), data[:, 1:].tolist()


def _header_rows(path: Path) -> int:
    """1 if the first non-comment line of a CSV file is not numeric, else 0."""
    with open(path, encoding="utf-8") as handle:
        for line in handle:
            if line.strip() and not line.lstrip().startswith("#"):
                try:
                    [float(x) for x in line.split(",")]
                except ValueError:
                    return 1
                return 0
    return 0
