"""Parameter studies: run a list of variations of one case and gather steady-state outputs.

A *study* (YAML file, or the same mapping in Python) names a base case, the parameters to
vary, what to run and which outputs to gather::

    name: wang-w3
    base:
      builder: moorline.verification.wang_dynamics:forced_equilibrium  # or  case: box.yaml
      parameters: {sag_to_span: 1/60, inclination_deg: 50}
    variations:                       # name -> list of values ("1/45" is read as 1/45)
      sag_to_span: [1/45, 1/50, 1/60, 1/70, 1/80]
      inclination_deg: [40, 44, 48, 50, 52, 54]
    combine: one-at-a-time            # or grid (every combination)
    statics: {tolerance: 1.0e-10}     # StaticsSettings fields (optional)
    dynamics: {duration: 80, dt: 0.05, rayleigh_ratio: 0.03, rayleigh_frequencies: [1.6, 2.07]}
    outputs:
      window: {omega: 1.6, periods: 5}  # steady state: the last 5 periods of 2 pi / 1.6
      quantities:
        surge: amplitude box.x
        max_tension: max tension

Base case
    ``case``: a case file (path relative to the study file), loaded with
    :func:`moorline.io.load_case`; its parameters are dotted paths into the
    :class:`~moorline.model.System` (``lines.C1.length``, ``environment.depth``,
    ``bodies.box.mass``). ``builder``: ``"module:function"`` called with the parameters
    as keyword arguments; it returns a :class:`~moorline.model.System`, or an object with
    ``system`` and ``result`` (a static state solved by the builder, e.g.
    :class:`~moorline.verification.wang_w1.Equilibrium`). Dotted parameters are applied to
    the built system (and the static state is then re-solved).
Statics and dynamics
    The static state is solved (:func:`~moorline.solvers.statics.solve_statics` with the
    ``statics`` settings, else the case's) unless the builder gave it; with a ``dynamics``
    mapping (:class:`~moorline.model.DynamicsSettings` fields, plus ``output_every``) the
    time-domain response from rest at the static state follows.
Quantities
    ``"<statistic> <signal>"``. Statistics over the steady window: ``amplitude`` (half the
    peak-to-peak), ``mean``, ``max``, ``min``; ``static``: the value in the static state.
    Signals: ``<body>.<dof>`` (dof ``surge sway heave roll pitch yaw``: position and
    rotation vector of a body; the older ``x y z rx ry rz`` are the same),
    ``<point>.<x|y|z>``, ``tension`` (the largest tension of all lines at each time, their
    end tensions included: the summary's ``max_tension``, :meth:`StaticResult.max_tension
    <moorline.results.StaticResult.max_tension>`), ``tension <line>`` (the same for one
    line), ``fairlead <line>`` (tension at end b).
Parameter paths
    Dotted, from the :class:`~moorline.model.System`: field names of the dataclasses
    (``environment.depth``), keys of the mappings (``lines.C1.length``), and integer
    indices into tuples, from 0 (``points.fairlead.position.2``: its z; ``-1``: the last).
Output
    :func:`run_study` returns, and ``moorline sweep`` writes (``table.csv``, ``table.nc``,
    rewritten as cases finish, at most every :data:`TABLE_WALL` seconds, and when the study
    ends or is stopped), one row per case: ``case`` (row number),
    ``series`` (the varied parameter, ``grid`` or ``base``), one column per parameter, one
    per quantity, ``status`` (``ok``, ``failed: <reason>``, or ``not run`` in a study
    stopped before the case) and ``elapsed`` (the case's wall time [s]).

The case loop is separable: :func:`study_cases` lists the parameter sets,
:func:`run_one` runs one (a pure function of the study and the parameters, returning a
dict) and :func:`run_study` maps it over the distinct sets with any ``map``-like callable.
:func:`dask_mapper` gives one that runs the cases on a Dask cluster (an existing scheduler,
or local worker processes): ``moorline sweep STUDY --workers 4`` or ``--scheduler
tcp://host:8786`` (the optional ``[dask]`` extra).
"""

from __future__ import annotations

import dataclasses
import gc
import importlib
import itertools
import logging
import math
import sys
import time
from collections.abc import Callable, Iterable, Iterator, Mapping
from dataclasses import dataclass, field
from fractions import Fraction
from functools import partial
from pathlib import Path
from typing import Any, Literal

import numpy as np
import xarray as xr
import yaml

from .datasets import BODY_DOFS as _BODY_DOFS
from .errors import CaseError, MoorlineError

logger = logging.getLogger(__name__)

Statistic = Literal["amplitude", "mean", "max", "min", "static"]
STATISTICS: tuple[str, ...] = ("amplitude", "mean", "max", "min", "static")
BODY_DOFS = _BODY_DOFS
#: Older names of the body dofs in study files (position and rotation-vector components).
DOF_ALIASES = dict(zip(("x", "y", "z", "rx", "ry", "rz"), _BODY_DOFS, strict=True))
TABLE_CSV, TABLE_NC, TRENDS_PNG = "table.csv", "table.nc", "trends.png"
#: Status of a case not run (yet) in a partial table.
NOT_RUN = "not run"
#: How long to wait for a Dask scheduler to answer.
SCHEDULER_TIMEOUT = "20s"
#: Wall time [s] between rewrites of a running study's table: a case that finishes sooner
#: after the last rewrite waits for the next one (or the end of the study), so a study killed
#: outright (SIGKILL) loses at most this much of finished cases, while short cases do not
#: pay a table rewrite each (about 0.1 s: xarray's dataset and two files; issue 16, P6).
TABLE_WALL = 1.0


@dataclass(frozen=True)
class Quantity:
    """One output column: ``statistic`` of a ``signal`` (see the module docstring)."""

    name: str
    statistic: Statistic
    signal: str
    target: str = ""

    @property
    def unit(self) -> str:
        """SI unit of the quantity (rad for body rotations, N for tensions, m otherwise)."""
        if self.signal in ("tension", "fairlead"):
            return "N"
        dof = self.target.rsplit(".", 1)[-1]
        return "rad" if DOF_ALIASES.get(dof, dof) in BODY_DOFS[3:] else "m"

    @property
    def long_name(self) -> str:
        """What the column holds, in words (the ``long_name`` of its table variable)."""
        what = {"amplitude": "amplitude (half the peak-to-peak) over the steady window of",
                "mean": "mean over the steady window of", "max": "largest over the steady "
                "window of", "min": "smallest over the steady window of",
                "static": "static-state value of"}[self.statistic]
        if self.signal == "tension":
            where = f"line {self.target}" if self.target else "all lines"
            signal = f"the largest tension of {where}, its end tensions included"
        elif self.signal == "fairlead":
            signal = f"the tension at end b of line {self.target} (the fairlead)"
        else:
            signal = f"{self.target}"
        return f"{what} {signal}"


@dataclass(frozen=True)
class Study:
    """A parameter study (see the module docstring for the file format).

    Attributes
    ----------
    name
        Study name (the output directory).
    case, builder
        Base case file, or ``"module:function"`` building the system (exactly one).
    base
        Base values of the parameters (builder keyword arguments or dotted paths).
    variations
        Parameter name -> values.
    combine
        ``one-at-a-time`` (each parameter varied alone, the others at their base values)
        or ``grid`` (every combination).
    statics, dynamics
        Settings fields; ``dynamics`` empty: statics only. ``output_every`` in
        ``dynamics`` is the output interval (default: the time step).
    period, periods
        Steady window: the last ``periods`` periods of length ``period`` [s].
    quantities
        The outputs.
    description
        Free text.
    """

    name: str
    case: Path | None = None
    builder: str | None = None
    base: Mapping[str, Any] = field(default_factory=dict)
    variations: Mapping[str, tuple[Any, ...]] = field(default_factory=dict)
    combine: Literal["one-at-a-time", "grid"] = "one-at-a-time"
    statics: Mapping[str, Any] = field(default_factory=dict)
    dynamics: Mapping[str, Any] = field(default_factory=dict)
    period: float = 0.0
    periods: int = 1
    quantities: tuple[Quantity, ...] = ()
    description: str = ""


# ----------------------------------------------------------------------------- reading
def load_study(path: str | Path) -> Study:
    """Read a study file.

    Raises
    ------
    CaseError
        The file cannot be read or is not a valid study (names the file and key).
    """
    from .io.files import MAX_CASE_BYTES, file_problem

    file = str(path)
    problem = file_problem(path, MAX_CASE_BYTES)
    if problem is not None:
        raise CaseError(f"cannot read the study file: {problem}", file)
    try:
        data = yaml.safe_load(Path(path).read_text(encoding="utf-8"))
    except OSError as exc:
        raise CaseError(f"cannot read the study file: {exc.strerror or exc}", file) from None
    except RecursionError:
        raise CaseError("not valid YAML: nested too deeply", file) from None
    except yaml.YAMLError as exc:
        raise CaseError(f"not valid YAML: {exc}", file) from None
    return study_from_dict(data, file=file, directory=Path(path).parent)


def study_from_dict(data: Any, file: str | None = None, directory: Path | None = None
                    ) -> Study:
    """Validate a study given as a mapping (the content of a study file).

    Parameters
    ----------
    data
        The mapping.
    file
        File name for error messages.
    directory
        Directory that a relative ``base.case`` path is relative to.
    """

    def fail(reason: str, key: str | None = None) -> CaseError:
        return CaseError(reason, file, key)

    if not isinstance(data, Mapping):
        raise fail("a study must be a mapping")
    unknown = set(data) - {"name", "description", "base", "variations", "combine", "statics",
                           "dynamics", "outputs"}
    if unknown:
        raise fail(f"unknown key(s) {', '.join(sorted(map(str, unknown)))}")
    name = data.get("name")
    if not isinstance(name, str) or not name.strip():
        raise fail("needs a non-empty string", "name")
    base = data.get("base")
    if not isinstance(base, Mapping):
        raise fail("needs a mapping with 'case' or 'builder'", "base")
    if ("case" in base) == ("builder" in base):
        raise fail("give exactly one of 'case' and 'builder'", "base")
    case = builder = None
    if "case" in base:
        case = Path(str(base["case"]))
        if not case.is_absolute() and directory is not None:
            case = directory / case
    else:
        builder = str(base["builder"])
        if ":" not in builder:
            raise fail("must be 'module:function'", "base.builder")
    params = base.get("parameters") or {}
    if not isinstance(params, Mapping):
        raise fail("must be a mapping", "base.parameters")
    base_values = {str(k): _value(v, fail, f"base.parameters.{k}") for k, v in params.items()}
    variations_in = data.get("variations") or {}
    if not isinstance(variations_in, Mapping):
        raise fail("must be a mapping name -> list of values", "variations")
    variations: dict[str, tuple[Any, ...]] = {}
    for key, values in variations_in.items():
        if not isinstance(values, list) or not values:
            raise fail("must be a non-empty list", f"variations.{key}")
        variations[str(key)] = tuple(_value(v, fail, f"variations.{key}") for v in values)
    combine = data.get("combine", "one-at-a-time")
    if combine not in ("one-at-a-time", "grid"):
        raise fail("must be 'one-at-a-time' or 'grid'", "combine")
    statics = dict(data.get("statics") or {})
    dynamics = {k: (tuple(v) if isinstance(v, list) else v)
                for k, v in dict(data.get("dynamics") or {}).items()}
    _check_fields(statics, "statics", fail)
    _check_fields({k: v for k, v in dynamics.items() if k != "output_every"}, "dynamics", fail)
    outputs = data.get("outputs") or {}
    if not isinstance(outputs, Mapping):
        raise fail("must be a mapping", "outputs")
    window = outputs.get("window") or {}
    period = float(window.get("period", 0.0))
    if "omega" in window:
        period = 2.0 * math.pi / float(window["omega"])
    periods = int(window.get("periods", 1))
    specs = outputs.get("quantities") or {}
    if not isinstance(specs, Mapping) or not specs:
        raise fail("needs a mapping name -> '<statistic> <signal>'", "outputs.quantities")
    quantities = tuple(parse_quantity(str(k), str(v), fail) for k, v in specs.items())
    if dynamics and period <= 0:
        raise fail("dynamics outputs need 'period' or 'omega' > 0", "outputs.window")
    if not dynamics and any(q.statistic != "static" for q in quantities):
        raise fail("without 'dynamics' only 'static' quantities exist", "outputs.quantities")
    return Study(name.strip(), case, builder, base_values, variations, combine, statics,
                 dynamics, period, periods, quantities, str(data.get("description", "")))


def _value(value: Any, fail: Callable[..., CaseError], key: str) -> Any:
    """Numbers stay numbers; ``"a/b"`` becomes ``a/b``; other strings and booleans stay."""
    if isinstance(value, str) and "/" in value:
        try:
            return float(Fraction(value.replace(" ", "")))
        except (ValueError, ZeroDivisionError):
            raise fail(f"{value!r} is not a number or fraction", key) from None
    if isinstance(value, bool | str):
        return value
    if isinstance(value, int | float):
        return float(value) if isinstance(value, float) else value
    raise fail(f"{value!r}: values must be numbers, fractions 'a/b' or strings", key)


def _check_fields(values: Mapping[str, Any], key: str, fail: Callable[..., CaseError]) -> None:
    from .analyses import KINDS

    names = {f.name for f in dataclasses.fields(KINDS[key].settings)} - {"kind"}
    unknown = set(values) - names
    if unknown:
        raise fail(f"unknown setting(s) {', '.join(sorted(unknown))}", key)


def parse_quantity(name: str, spec: str, fail: Callable[..., CaseError] | None = None
                   ) -> Quantity:
    """A :class:`Quantity` from ``"<statistic> <signal>"`` (see the module docstring)."""
    fail = fail or (lambda reason, key=None: CaseError(reason, None, key))
    words = spec.split()
    key = f"outputs.quantities.{name}"
    if len(words) not in (2, 3) or words[0] not in STATISTICS:
        raise fail(f"{spec!r}: expected '<{'|'.join(STATISTICS)}> <signal>'", key)
    statistic, signal = words[0], words[1]
    if signal in ("tension", "fairlead"):
        if signal == "fairlead" and len(words) != 3:
            raise fail(f"{spec!r}: 'fairlead' needs a line name", key)
        return Quantity(name, statistic, signal, words[2] if len(words) == 3 else "")  # type: ignore[arg-type]
    if len(words) != 2 or "." not in signal:
        raise fail(f"{spec!r}: signals are '<body>.<dof>', '<point>.<x|y|z>', "
                   f"'tension [<line>]' or 'fairlead <line>'", key)
    return Quantity(name, statistic, "pose", signal)  # type: ignore[arg-type]


# ----------------------------------------------------------------------------- cases
def study_cases(study: Study) -> list[tuple[str, dict[str, Any]]]:
    """The parameter sets of a study as ``(series, parameters)``: ``series`` is the varied
    parameter (one-at-a-time; the base set appears in every series it belongs to) or
    ``grid``. A study without variations has the single case ``("base", base)``."""
    base = dict(study.base)
    if not study.variations:
        return [("base", base)]
    if study.combine == "grid":
        names = list(study.variations)
        return [("grid", {**base, **dict(zip(names, combo, strict=True))})
                for combo in itertools.product(*study.variations.values())]
    return [(name, {**base, name: value}) for name, values in study.variations.items()
            for value in values]


def _key(params: Mapping[str, Any]) -> tuple:
    """Identity of a parameter set (``50`` and ``50.0`` are the same value)."""

    def norm(v: Any) -> str:
        numeric = isinstance(v, int | float) and not isinstance(v, bool)
        return repr(float(v)) if numeric else repr(v)

    return tuple(sorted((k, norm(v)) for k, v in params.items()))


def run_one(study: Study, params: Mapping[str, Any]) -> dict[str, Any]:
    """Run one parameter set: build, static state, dynamics, quantities.

    A failure of the analysis (a :class:`~moorline.errors.MoorlineError` other than bad
    input, or a ``RuntimeError`` from a builder) does not raise: the quantities are NaN and
    ``status`` says what happened.

    Returns
    -------
    dict
        The parameters, every quantity by name, ``status`` (``"ok"`` or the error) and
        ``elapsed`` [s].
    """
    start = time.perf_counter()
    row: dict[str, Any] = dict(params)
    try:
        row.update(_evaluate(study, params))
        row["status"] = "ok"
    except CaseError:
        raise
    except (MoorlineError, RuntimeError) as exc:
        logger.warning("study %s, case %s failed: %s", study.name, dict(params), exc)
        row.update({q.name: math.nan for q in study.quantities})
        row["status"] = f"failed: {exc}"
    row["elapsed"] = time.perf_counter() - start
    return row


def _evaluate(study: Study, params: Mapping[str, Any]) -> dict[str, float]:
    from .model import DynamicsSettings, StaticsSettings
    from .solvers.dynamics import simulate
    from .solvers.statics import solve_statics

    system, static = build(study, params)
    if static is None:
        settings = dataclasses.replace(system.first(StaticsSettings), **study.statics)
        static = solve_statics(system, settings)
        if not static.success:
            raise MoorlineError(f"statics did not converge: {static.message}")
    result = None
    if study.dynamics:
        fields = {k: v for k, v in study.dynamics.items() if k != "output_every"}
        settings_d = DynamicsSettings(**fields)
        every = float(study.dynamics.get("output_every", settings_d.dt))
        result = simulate(system, settings_d, initial=static, output_every=every)
        if not result.success:
            raise MoorlineError(f"dynamics failed: {result.message}")
    return {q.name: gather(q, static, result, study.period, study.periods)
            for q in study.quantities}


def build(study: Study, params: Mapping[str, Any]) -> tuple[Any, Any]:
    """The system of one parameter set and, when the builder solved it, its static state."""
    dotted = {k: v for k, v in params.items() if "." in k}
    plain = {k: v for k, v in params.items() if "." not in k}
    static = None
    if study.case is not None:
        from .io import load_case

        if plain:
            raise CaseError(f"parameters of a case file are dotted paths into the system, "
                            f"got {', '.join(sorted(plain))}", None, "variations")
        system = load_case(study.case)
    else:
        module_name, func_name = str(study.builder).split(":")
        try:
            func = getattr(importlib.import_module(module_name), func_name)
        except (ImportError, AttributeError) as exc:
            raise CaseError(f"cannot import {study.builder}: {exc}", None,
                            "base.builder") from None
        built = func(**plain)
        if hasattr(built, "system") and hasattr(built, "result"):
            system, static = built.system, built.result
        else:
            system = built
    if dotted:
        for path, value in dotted.items():
            system = set_path(system, path, value)
        static = None
    return system, static


def set_path(obj: Any, path: str, value: Any) -> Any:
    """A copy of a tree of frozen dataclasses, mappings and tuples with the item at the dotted
    ``path`` replaced (mapping keys and field names by name, tuple items by index).

    Raises
    ------
    CaseError
        A step of the path does not exist.
    """
    head, _, rest = path.partition(".")
    if dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        if head not in {f.name for f in dataclasses.fields(obj)}:
            raise CaseError(f"no field {head!r} in {type(obj).__name__}", None, path)
        child = getattr(obj, head)
        new = set_path(child, rest, value) if rest else _like(child, value)
        return dataclasses.replace(obj, **{head: new})
    if isinstance(obj, Mapping):
        if head not in obj:
            raise CaseError(f"no entry {head!r} (have {', '.join(map(str, obj))})", None, path)
        new = set_path(obj[head], rest, value) if rest else _like(obj[head], value)
        return {**obj, head: new}
    if isinstance(obj, tuple) and head.lstrip("-").isdigit() and \
            -len(obj) <= int(head) < len(obj):
        items = list(obj)
        k = int(head)
        items[k] = set_path(items[k], rest, value) if rest else _like(items[k], value)
        return tuple(items)
    raise CaseError(f"cannot step into {type(obj).__name__} with {head!r}", None, path)


def _like(old: Any, value: Any) -> Any:
    """``value`` converted to the kind of ``old`` (floats stay floats, lists become tuples)."""
    if isinstance(old, float) and isinstance(value, int | float) and not isinstance(value, bool):
        return float(value)
    if isinstance(old, tuple) and isinstance(value, list):
        return tuple(value)
    return value


# ----------------------------------------------------------------------------- outputs
def steady_window(time: np.ndarray, period: float, periods: int) -> np.ndarray:
    """Mask of the last ``periods`` periods of ``time`` (all of it when shorter)."""
    time = np.asarray(time, dtype=float)
    return time >= time[-1] - periods * period - 1e-9 * max(period, 1.0)


def statistic(values: np.ndarray, which: str) -> float:
    """``amplitude`` (half the peak-to-peak), ``mean``, ``max`` or ``min`` of a history."""
    values = np.asarray(values, dtype=float)
    if which == "amplitude":
        return 0.5 * float(np.ptp(values))
    return float({"mean": np.mean, "max": np.max, "min": np.min}[which](values))


def gather(q: Quantity, static: Any, result: Any, period: float, periods: int) -> float:
    """Value of one quantity from the static state and the dynamic result."""
    if q.statistic == "static":
        return _static_value(q, static)
    window = steady_window(result.time, period, periods)
    return statistic(_history(q, result)[window], q.statistic)


def _history(q: Quantity, result: Any) -> np.ndarray:
    mesh = result.mesh
    if q.signal == "fairlead":
        return result.end_tension(q.target, "b")
    if q.signal == "tension":
        lines = [q.target] if q.target else list(mesh.line_names)
        tension = result.tension[:, np.isin(mesh.element_line,
                                            [mesh.line_index(n) for n in lines])]
        ends = [result.end_tension(n, e) for n in lines for e in "ab"]
        return np.nanmax(np.column_stack([tension, *ends]), axis=1)
    owner, dof = q.target.rsplit(".", 1)
    if owner in mesh.body_names:
        return result.body_history(owner)[:, _dof(q, dof, BODY_DOFS)]
    _known_point(q, mesh, owner)
    return result.point_history(owner)[:, _dof(q, dof, ("x", "y", "z"))]


def _static_value(q: Quantity, static: Any) -> float:
    mesh = static.mesh
    if q.signal == "fairlead":
        return float(np.linalg.norm(static.end_force(q.target, "b")))
    if q.signal == "tension":
        return max(static.max_tension(n) for n in ([q.target] if q.target
                                                   else mesh.line_names))
    owner, dof = q.target.rsplit(".", 1)
    if owner in mesh.body_names:
        pose = static.body_pose[mesh.body_names.index(owner)]
        return float(pose[_dof(q, dof, BODY_DOFS)])
    _known_point(q, mesh, owner)
    return float(static.point_position(owner)[_dof(q, dof, ("x", "y", "z"))])


def _dof(q: Quantity, dof: str, allowed: tuple[str, ...]) -> int:
    if allowed == BODY_DOFS:
        dof = DOF_ALIASES.get(dof, dof)
    if dof not in allowed:
        raise CaseError(f"{q.target!r}: component {dof!r} not one of {', '.join(allowed)}",
                        None, f"outputs.quantities.{q.name}")
    return allowed.index(dof)


def _known_point(q: Quantity, mesh: Any, owner: str) -> None:
    if owner not in mesh.point_names:
        raise CaseError(f"{q.target!r}: no body or point {owner!r}", None,
                        f"outputs.quantities.{q.name}")


# ----------------------------------------------------------------------------- study
def run_study(study: Study | Mapping[str, Any] | str | Path,
              mapper: Callable[[Callable, Iterable], Iterable] = map,
              directory: str | Path | None = None,
              progress: Callable[[int, int, float], None] | None = None) -> xr.Dataset:
    """Run every distinct parameter set of a study and gather the table.

    Parameters
    ----------
    study
        A :class:`Study`, its mapping, or a study file.
    mapper
        ``map``-like: ``mapper(function, parameter_sets)`` -> the results (each a
        :func:`run_one` row), in order or in the order they finish (rows are matched to
        their parameter set).
    directory
        When given, ``table.csv`` and ``table.nc`` are rewritten there as cases finish (at
        most every :data:`TABLE_WALL` seconds) and when the loop ends, normally or by an
        exception (:func:`write_table`): a study stopped mid-way keeps the cases that
        finished (the others have status ``not run``; attribute ``complete`` is 0).
    progress
        Called after every finished case with (cases finished, distinct cases, seconds
        since the start); :func:`eta_text` makes it a progress line.

    Returns
    -------
    xarray.Dataset
        Dimension ``case`` (one row per series and value; a parameter set shared by several
        series is run once); coordinates ``series`` and one per parameter; a variable per
        quantity (attributes ``units``, ``long_name``, ``spec``), ``status`` and
        ``elapsed``. Attributes: study name, description, ``combine``, ``variations``
        (names), ``quantities`` (names), ``finished`` and ``complete``, and the settings.
    """
    if isinstance(study, str | Path):
        study = load_study(study)
    elif not isinstance(study, Study):
        study = study_from_dict(study)
    cases = study_cases(study)
    distinct: dict[tuple, dict[str, Any]] = {}
    for _, params in cases:
        distinct.setdefault(_key(params), params)
    outputs: dict[tuple, dict[str, Any]] = {}
    start = written = time.perf_counter()
    unwritten = directory is not None
    try:
        for row in mapper(partial(run_one, study), list(distinct.values())):
            outputs[_match(row, distinct, outputs)] = row
            unwritten = directory is not None
            if unwritten and time.perf_counter() - written >= TABLE_WALL:
                write_table(_table(study, cases, outputs), directory)
                written, unwritten = time.perf_counter(), False
            if progress is not None:
                progress(len(outputs), len(distinct), time.perf_counter() - start)
    finally:
        if unwritten:  # what finished since the last rewrite, also when stopped
            write_table(_table(study, cases, outputs), directory)
    return _table(study, cases, outputs)


def _match(row: Mapping[str, Any], distinct: Mapping[tuple, Mapping[str, Any]],
           done: Mapping[tuple, Any]) -> tuple:
    """The key of the parameter set a result row belongs to (rows may come in any order)."""
    for key, params in distinct.items():
        if key not in done and all(n in row for n in params) and \
                _key({n: row[n] for n in params}) == key:
            return key
    raise MoorlineError(f"a study result matches no parameter set: {dict(row)}")


def eta_text(done: int, total: int, elapsed: float) -> str:
    """``"3 of 10 cases done, 12.5 s per case, about 1 min 28 s left"``: the estimate is the
    mean wall time per finished case so far (with parallel workers, the elapsed time over
    the cases done) times the cases left."""
    if done <= 0:
        return f"0 of {total} cases done"
    mean = elapsed / done
    left = mean * (total - done)
    text = f"{done} of {total} cases done, {_duration(mean)} per case"
    return text + (f", about {_duration(left)} left" if done < total else "")


def _duration(seconds: float) -> str:
    if seconds < 60:
        return f"{seconds:.3g} s"
    minutes, rest = divmod(round(seconds), 60)
    if minutes < 60:
        return f"{minutes} min {rest} s"
    hours, minutes = divmod(minutes, 60)
    return f"{hours} h {minutes} min"


def dask_mapper(scheduler: str | None = None, workers: int | None = None,
                progress: Callable[[int, int], None] | None = None,
                warm: Callable[[], None] | None = None):
    """A ``map``-like callable that runs the cases on Dask, and a function that closes the
    client (and the local cluster).

    Parameters
    ----------
    scheduler
        Address of a running Dask scheduler (``tcp://host:8786``): the cases run on its
        workers, which need moorline installed. ``None``: a local cluster of ``workers``
        processes (one thread each: the solvers are single-threaded numpy).
    workers
        Local worker processes (default: the machine's cores).
    progress
        Called with (cases done, cases) as results arrive.
    warm
        Called in this process before a local cluster starts (e.g. :func:`warm_up`: the
        solver modules imported and the compiled kernels loaded). On Linux the local workers
        are forked from this process (``distributed.worker.multiprocessing-method: fork``),
        so they start with all of that instead of importing moorline and loading numba's
        kernels each (seconds per worker, the bulk of the Dask overhead of a small study).

    Returns
    -------
    mapper, close
        ``mapper(function, items)`` yields the results as they finish (in any order: each
        :func:`run_one` row names its parameters); the items go to the workers in batches
        (about four per worker), each returning its list of rows; call ``close()`` when
        done.

    Raises
    ------
    MoorlineError
        When Dask's distributed scheduler is not installed or the scheduler cannot be
        reached.
    """
    try:
        import dask
        from dask.distributed import Client, LocalCluster, as_completed
    except ImportError:
        raise MoorlineError("running a study on Dask needs dask.distributed: install "
                            "moorline[dask]") from None
    cluster = None
    try:
        if scheduler:
            client = Client(scheduler, timeout=SCHEDULER_TIMEOUT)
        else:
            if warm is not None:
                warm()
            method = "fork" if sys.platform.startswith("linux") else "spawn"
            # forked workers share this process's memory copy-on-write; the garbage
            # collector's first pass in a worker would write to every tracked object (and
            # so copy every page holding one: +0.6 s on the first case of each worker of the
            # issue-16 P6 study); frozen objects are left out of the workers' collections
            gc.freeze()
            try:
                with dask.config.set({"distributed.worker.multiprocessing-method": method}):
                    cluster = LocalCluster(n_workers=workers, threads_per_worker=1,
                                           processes=True, dashboard_address=None)
            finally:
                gc.unfreeze()
            client = Client(cluster)
    except (OSError, TimeoutError) as exc:
        raise MoorlineError(f"cannot reach the Dask scheduler {scheduler!r}: {exc}") from None

    def mapper(function: Callable, items: Iterable) -> Iterator[Any]:
        items = list(items)
        n_workers = max(len(client.scheduler_info().get("workers", {})), 1)
        size = max(1, len(items) // (4 * n_workers))
        batches = [items[k:k + size] for k in range(0, len(items), size)]
        futures = client.map(partial(_run_batch, function), batches, pure=False)
        done = 0
        for future in as_completed(futures):
            for row in future.result():
                done += 1
                if progress is not None:
                    progress(done, len(items))
                yield row

    def close() -> None:
        client.close()
        if cluster is not None:
            cluster.close()

    return mapper, close


def _run_batch(function: Callable, items: list) -> list:
    """``function`` over a batch of items on one worker."""
    return [function(item) for item in items]


def warm_up(study: Study) -> None:
    """Import the solvers and load their compiled kernels by running the study's first case
    for two time steps (its result is discarded); a failure is left to the case itself."""
    from .model import DynamicsSettings, StaticsSettings
    from .solvers.dynamics import simulate
    from .solvers.statics import solve_statics

    cases = study_cases(study)
    if not cases:
        return
    try:
        system, static = build(study, cases[0][1])
        if static is None:
            static = solve_statics(system, dataclasses.replace(system.first(StaticsSettings),
                                                               **study.statics))
        if study.dynamics and static.success:
            fields = {k: v for k, v in study.dynamics.items() if k != "output_every"}
            settings = DynamicsSettings(**fields)
            simulate(system, dataclasses.replace(settings, duration=2 * settings.dt),
                     initial=static)
    except (MoorlineError, RuntimeError, ValueError) as exc:
        logger.info("study %s: warm-up case failed (%s); the workers start cold", study.name,
                    exc)


def _table(study: Study, cases: list[tuple[str, dict[str, Any]]],
           outputs: Mapping[tuple, dict[str, Any]]) -> xr.Dataset:
    pending = {**{q.name: math.nan for q in study.quantities}, "status": NOT_RUN,
               "elapsed": math.nan}
    rows = [outputs.get(_key(params), pending) for _, params in cases]
    names = list(dict.fromkeys(k for _, params in cases for k in params))
    coords: dict[str, Any] = {"case": np.arange(len(cases)),
                              "series": ("case", [s for s, _ in cases])}
    for name in names:
        values = [params.get(name) for _, params in cases]
        coords[name] = ("case", np.asarray(values))
    data: dict[str, Any] = {}
    for q in study.quantities:
        data[q.name] = ("case", np.array([float(r[q.name]) for r in rows]),
                        {"units": q.unit, "long_name": q.long_name,
                         "spec": f"{q.statistic} {q.signal}"
                         + (f" {q.target}" if q.target else "")})
    data["status"] = ("case", np.array([str(r["status"]) for r in rows], dtype=object))
    data["elapsed"] = ("case", np.array([float(r["elapsed"]) for r in rows]), {"units": "s"})
    attrs = {"study": study.name, "description": study.description, "combine": study.combine,
             "variations": ",".join(study.variations), "parameters": ",".join(names),
             "quantities": ",".join(q.name for q in study.quantities),
             "base": str(study.case or study.builder),
             "window_period": study.period, "window_periods": study.periods,
             "finished": len(outputs),
             "complete": int(all(_key(p) in outputs for _, p in cases)),
             **{f"statics_{k}": _attr(v) for k, v in study.statics.items()},
             **{f"dynamics_{k}": _attr(v) for k, v in study.dynamics.items()}}
    return xr.Dataset(data, coords=coords, attrs=attrs)


def _attr(value: Any) -> Any:
    """NetCDF-friendly attribute value."""
    if isinstance(value, bool):
        return int(value)
    if isinstance(value, tuple | list):
        return np.asarray(value, dtype=float)
    return value


def write_table(table: xr.Dataset, directory: str | Path) -> list[Path]:
    """Write ``table.csv`` and ``table.nc`` into ``directory`` (each written to a temporary
    file and renamed, so a study stopped while writing keeps the previous table)."""
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    csv, nc = directory / TABLE_CSV, directory / TABLE_NC
    out = table.copy()
    out["status"] = out["status"].astype(str)
    out["series"] = out["series"].astype(str)
    for path, write in ((csv, lambda p: table.to_dataframe().to_csv(p)),
                        (nc, out.to_netcdf)):
        partial_path = path.with_name(path.name + ".part")
        write(partial_path)
        partial_path.replace(path)
    return [csv, nc]


def write_study(table: xr.Dataset, directory: str | Path) -> list[Path]:
    """Write ``table.csv``, ``table.nc`` (:func:`write_table`) and ``trends.png`` into
    ``directory``."""
    from .plot import plot_sweep_trends

    files = write_table(table, directory)
    png = Path(directory) / TRENDS_PNG
    plot_sweep_trends(table, png)
    return [*files, png]


__all__ = ["Quantity", "Study", "build", "eta_text", "gather", "load_study", "parse_quantity",
           "run_one", "run_study", "set_path", "statistic", "steady_window", "study_cases",
           "study_from_dict", "warm_up", "write_study", "write_table"]
