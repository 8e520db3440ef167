"""Pydantic schema of case files: keys, types, dimensions and per-field bounds.

Every dimensional field is declared with :func:`quantity`, naming a key of
:data:`moorline.io.units.DIMENSIONS`; the unit system comes from the validation context
(``context={"units": "SI"}``); values come out as floats in that system. Defaults that depend
on the unit system are ``None`` here and filled in by :mod:`moorline.io.case`, which also
checks cross-references and geometry. :func:`describe_errors` turns a pydantic
``ValidationError`` into a dotted key path and a one-line message.
"""

from __future__ import annotations

import difflib
import math
import re
import types
from typing import Annotated, Any, Literal, Union, get_args, get_origin

from pydantic import (
    AfterValidator,
    BaseModel,
    ConfigDict,
    Field,
    PlainValidator,
    ValidationError,
    ValidationInfo,
    field_validator,
)
from pydantic_core import PydanticCustomError

from ..analyses import KINDS
from .units import UnitParseError, to_system

__all__ = ["MAX_COUNT", "MAX_ITERATIONS", "MAX_MAGNITUDE", "MIN_MAGNITUDE", "AnalysisSpec",
           "CaseSpec", "DesignSpec", "DynamicsSpec", "ExtremesSpec", "FatigueCurveSpec",
           "FatigueSpec", "ForceHistorySpec", "HarmonicSpec", "LineSpec", "LineTypeSpec",
           "ModalSpec", "MotionSpec", "OffsetSpec", "PointSpec", "StaticsSpec",
           "StochasticSpec", "StrummingSpec", "check_number", "describe_errors", "quantity"]

MAX_MAGNITUDE = 1.0e30
"""Largest magnitude of any number in a case file or a time table (in the case's units).

Far beyond any physical value of a mooring problem in SI or US units (a chain's EA ~1e9 N, a
hull's inertia ~1e13 kg m^2), and small enough that products and squares of such numbers in
the solvers (stiffness times displacement, residual norms) stay finite in float64 (~1.8e308).
"""

MAX_COUNT = 10**12
"""Largest positive integer of a case file (segments, iterations, harmonics, points...);
the sizes that cost memory have tighter limits in :mod:`moorline.io.limits`."""

MAX_ITERATIONS = 1_000_000
"""Largest iteration or step count (``max_iterations``, ``load_steps``, ``stiffness_update``,
``substeps``): a solver that needs more does not converge, and would run for days first."""

MIN_MAGNITUDE = 1.0e-30
"""Smallest magnitude of a nonzero number in a case file or a time table.

Tinier values (down to the denormals, 1e-308) are data errors that break the solvers: an EA
of 1e-300 makes a stiffness matrix exactly singular, a period of 1e-300 an infinite
frequency.
"""


def _show(value: Any) -> str:
    """A value as written in the file, short, for messages."""
    text = repr(value) if isinstance(value, str) and not _numeric(value) else str(value)
    return text if len(text) <= 60 else text[:57] + "..."


def _numeric(text: str) -> bool:
    """True for strings YAML 1.1 leaves unparsed but that are numbers (``1.0e8``, ``1e-8``)."""
    try:
        float(text)
    except ValueError:
        return False
    return True


def _fail(reason: str) -> PydanticCustomError:
    return PydanticCustomError("case_value", "{reason}", {"reason": reason})


def check_number(x: float, allow_inf: bool = False) -> str | None:
    """Why a number may not appear in a case file or a table, or ``None`` when it may.

    NaN is refused, infinity unless ``allow_inf``, and finite numbers beyond
    :data:`MAX_MAGNITUDE` or nonzero ones below :data:`MIN_MAGNITUDE` in magnitude.
    """
    if math.isnan(x):
        return "must be a number, got nan"
    if math.isinf(x):
        return None if allow_inf else f"must be finite, got {x}"
    if abs(x) > MAX_MAGNITUDE:
        return f"must be at most {MAX_MAGNITUDE:g} in magnitude (MAX_MAGNITUDE), got {x:g}"
    if x != 0.0 and abs(x) < MIN_MAGNITUDE:
        return (f"a nonzero number must be at least {MIN_MAGNITUDE:g} in magnitude "
                f"(MIN_MAGNITUDE), got {x:g}")
    return None


def quantity(
    dimension: str,
    *,
    gt: float | None = None,
    ge: float | None = None,
    le: float | None = None,
    allow_inf: bool = False,
) -> Any:
    """Annotated float type of a case-file field with a physical dimension and bounds.

    Parameters
    ----------
    dimension
        Key of :data:`moorline.io.units.DIMENSIONS`.
    gt, ge, le
        Bounds on the converted value (unit independent: only 0 and 1 are used).
    allow_inf
        Accept ``inf`` (e.g. an infinite depth).
    """

    def validate(value: Any, info: ValidationInfo) -> float:
        system = (info.context or {}).get("units", "SI")
        try:
            x = to_system(value, dimension, system)
        except UnitParseError as exc:
            raise _fail(str(exc)) from None
        if math.isinf(x) and not allow_inf:
            raise _fail(f"must be finite, got {_show(value)}")
        problem = check_number(x, allow_inf)
        if problem is not None:
            raise _fail(problem)
        if gt is not None and not x > gt:
            raise _fail(f"must be > {gt:g}, got {_show(value)}")
        if ge is not None and not x >= ge:
            raise _fail(f"must be >= {ge:g}, got {_show(value)}")
        if le is not None and not x <= le:
            raise _fail(f"must be <= {le:g}, got {_show(value)}")
        return x

    return Annotated[float, PlainValidator(validate)]


def _positive_int(value: Any, limit: int | None = None) -> int:
    """A positive integer (``20``, ``20.0`` or ``"20"``), at most ``limit`` (default
    :data:`MAX_COUNT`)."""
    n: int | None = None
    if isinstance(value, int) and not isinstance(value, bool):
        n = value
    elif isinstance(value, float) and value.is_integer():
        n = int(value)
    elif isinstance(value, str) and re.fullmatch(r"\s*\+?\d+\s*", value):
        n = int(value)
    if n is None or n < 1:
        raise _fail(f"must be a positive integer, got {_show(value)}")
    if limit is not None and n > limit:
        raise _fail(f"must be at most {limit} (MAX_ITERATIONS), got {_show(value)}")
    if n > MAX_COUNT:
        raise _fail(f"must be at most {MAX_COUNT:.0e} (MAX_COUNT), got {_show(value)}")
    return n


def _pair(values: list[float]) -> tuple[float, float]:
    if len(values) != 2:
        raise _fail(f"must be 2 numbers, got {len(values)}")
    return (values[0], values[1])


def _three(values: list[float]) -> tuple[float, float, float]:
    if len(values) != 3:
        raise _fail(f"must be 3 numbers [x, y, z], got {len(values)}")
    return (values[0], values[1], values[2])


PositiveInt = Annotated[int, PlainValidator(_positive_int)]
Iterations = Annotated[int, PlainValidator(lambda v: _positive_int(v, MAX_ITERATIONS))]
Length = quantity("length")
Vector3 = Annotated[list[Length], AfterValidator(_three)]
Force3 = Annotated[list[quantity("force")], AfterValidator(_three)]
Coefficient = quantity("dimensionless", ge=0.0)
Number = quantity("dimensionless")


def _internal_damping(value: Any, info: ValidationInfo) -> float:
    """``BA``: a damping coefficient [force*time], or a negative plain number ``-zeta`` (a
    damping ratio of each segment's axial mode, MoorDyn's convention)."""
    if isinstance(value, int | float) and not isinstance(value, bool) and value < 0:
        if value < -10:
            raise _fail(f"a negative BA is a damping ratio -zeta and must be >= -10, got {value}")
        problem = check_number(float(value))
        if problem is not None:
            raise _fail(problem)
        return float(value)
    return quantity("force*time", ge=0.0).__metadata__[0].func(value, info)


def _stiffness(value: Any, info: ValidationInfo) -> float | dict:
    """``EA``: an axial stiffness [force], or ``{table: [[strain, tension], ...]}``, a
    tension-strain law (plain numbers, tension in the case's force unit;
    :mod:`moorline.physics.load_strain` checks its shape)."""
    if value is None:
        return None
    if not isinstance(value, dict):
        return quantity("force", gt=0.0).__metadata__[0].func(value, info)
    rows = value.get("table")
    if set(value) != {"table"} or not isinstance(rows, list) or not all(
            isinstance(r, list) and len(r) == 2 for r in rows):
        raise _fail("a table EA must be {table: [[strain, tension], ...]}")
    out = []
    for row in rows:
        if not all(isinstance(x, int | float) and not isinstance(x, bool) for x in row):
            raise _fail(f"table rows must be two plain numbers, got {row!r}")
        problem = next((p for p in map(check_number, map(float, row)) if p), None)
        if problem is not None:
            raise _fail(f"table row {row!r}: {problem}")
        out.append((float(row[0]), float(row[1])))
    return {"table": out}


class _Spec(BaseModel):
    """Base of all case-file sections: unknown keys are errors."""

    model_config = ConfigDict(extra="forbid")


class BathymetrySpec(_Spec):
    """``environment.seabed.bathymetry`` given inline: seabed heights ``z[i][j]`` (z up,
    negative below the surface) at the grid nodes ``(x[i], y[j])``."""

    x: list[quantity("length")]
    y: list[quantity("length")]
    z: list[list[quantity("length")]]


class SeabedSpec(_Spec):
    """``environment.seabed``; ``None`` means the unit-system default. ``slope`` [deg] and
    ``slope_heading`` [deg]: a plane through ``(0, 0, -depth)`` going down at ``slope``
    towards ``slope_heading`` (0 = +x, 90 = +y); ``bathymetry``: a grid of heights instead,
    inline or a MoorDyn 3-D seafloor file (relative to the case file)."""

    stiffness: quantity("force/length^3", ge=0.0) | None = None
    damping: quantity("force*time/length^3", ge=0.0) | None = None
    friction: Coefficient = 0.0
    friction_axial: Coefficient | None = None
    friction_transverse: Coefficient | None = None
    slip_velocity: quantity("velocity", gt=0.0) | None = None
    slope: quantity("angle", ge=0.0) = 0.0
    slope_heading: quantity("angle") = 0.0
    bathymetry: str | BathymetrySpec | None = None


class CurrentSpec(_Spec):
    """``environment.current``: uniform current towards ``heading`` [deg], or a profile:
    ``speeds`` and ``headings`` at heights ``z_levels`` (linear in z)."""

    speed: quantity("velocity", ge=0.0) = 0.0
    heading: quantity("angle") = 0.0
    z_levels: list[quantity("length")] | None = None
    speeds: list[quantity("velocity", ge=0.0)] | None = None
    headings: list[quantity("angle")] | None = None


class WaveComponentsSpec(_Spec):
    """``environment.waves.components``: an explicit linear sea, one entry per component:
    ``eta = sum a cos(k (x cos b + y sin b) - omega t + phi)`` with ``omegas`` [rad/s],
    ``amplitudes`` a [length], ``phases`` phi [angle] and optional ``headings`` b [angle]
    (default: ``waves.heading``)."""

    omegas: list[quantity("1/time", gt=0.0)]
    amplitudes: list[quantity("length", ge=0.0)]
    phases: list[quantity("angle")]
    headings: list[quantity("angle")] | None = None


class WavesSpec(_Spec):
    """``environment.waves``: ``kind: none``, a regular ``airy`` wave (``height``,
    ``period``), a ``random`` sea (``height`` = Hs, ``period`` = Tp, ``spectrum``,
    ``gamma``, ``amplitudes``, ``seed``, ``record_length``, ``n_frequencies`` or
    ``omega_max``), or explicit ``components`` (:class:`WaveComponentsSpec`)."""

    kind: Literal["none", "airy", "random", "components"] = "none"
    height: quantity("length", ge=0.0) = 0.0
    period: quantity("time", ge=0.0) = 0.0
    heading: quantity("angle") = 0.0
    phase: quantity("angle") = 0.0
    stretching: Literal["none", "wheeler"] = "none"
    spectrum: Literal["pierson-moskowitz", "jonswap"] = "jonswap"
    gamma: quantity("dimensionless", ge=1.0) = 3.3
    amplitudes: Literal["dsa", "nsa"] = "dsa"
    seed: Annotated[int, Field(ge=0)] = 0
    record_length: quantity("time", gt=0.0) = 1800.0
    n_frequencies: PositiveInt | None = None
    omega_max: quantity("1/time", gt=0.0) | None = None
    components: WaveComponentsSpec | None = None


class EnvironmentSpec(_Spec):
    """``environment``; an omitted ``depth`` means deep water without a seabed."""

    depth: quantity("length", gt=0.0, allow_inf=True) | None = None
    water_density: quantity("mass/length^3", gt=0.0) | None = None
    gravity: quantity("acceleration", gt=0.0) | None = None
    seabed: SeabedSpec = Field(default_factory=SeabedSpec)
    current: CurrentSpec = Field(default_factory=CurrentSpec)
    waves: WavesSpec = Field(default_factory=WavesSpec)


class LineTypeSpec(_Spec):
    """``line_types.<name>``: cross-section properties.

    ``catalog`` and ``nominal_diameter`` take ``diameter``, ``mass_per_length``, ``EA``,
    ``EA_dynamic``, ``MBL`` and the hydrodynamic coefficients from the line catalogue
    (:mod:`moorline.catalog`); a key given here overrides the catalogue's value. Without a
    catalogue ``diameter``, ``mass_per_length`` and ``EA`` are required (checked by
    :mod:`moorline.io.case`). ``MBL`` (minimum breaking load) enables the design checks;
    ``EA_dynamic`` (fibre ropes) is stored, the solvers use ``EA``.
    ``EA`` may be a tension-strain table (``{table: [[strain, tension], ...]}``) or
    ``EA_table`` a table file (CSV or MoorDyn's EA table file, relative to the case file);
    ``EAd`` and ``EAd_Lm`` give the fibre-rope dynamic stiffness ``EA_d = EAd + EAd_Lm T_mean``
    used about the static state in dynamic analyses. ``material: static_dynamic`` is MoorDyn's
    viscoelastic rope (:mod:`moorline.physics.static_dynamic`): ``EA`` static, ``EAd`` +
    ``EAd_Lm`` the dynamic branch's stiffness, ``BA`` and ``BA_dynamic`` the two dampings.
    ``EI`` is the bending stiffness [force*length^2] (:mod:`moorline.physics.bending`; line
    ends pinned), 0 for a cable.
    """

    catalog: str | None = None
    nominal_diameter: quantity("length", gt=0.0) | None = None
    diameter: quantity("length", gt=0.0) | None = None
    mass_per_length: quantity("mass/length", gt=0.0) | None = None
    EA: Annotated[Any, PlainValidator(_stiffness)] = None
    EA_table: str | None = None
    EAd: quantity("force", gt=0.0) | None = None
    EAd_Lm: quantity("dimensionless", ge=0.0) = 0.0
    EA_dynamic: quantity("force", gt=0.0) | None = None
    MBL: quantity("force", gt=0.0) | None = None
    displaced_area: quantity("area", gt=0.0) | None = None
    Cd: Coefficient = 1.2
    Ca: Coefficient = 1.0
    Ct: Coefficient = 0.008
    Cat: Coefficient = 0.0
    material: Literal["elastic", "viscoelastic", "static_dynamic"] = "elastic"
    EA1: quantity("force", ge=0.0) = 0.0
    tau: quantity("time", ge=0.0) = 0.0
    slack_stiffness_ratio: quantity("dimensionless", gt=0.0, le=1.0) = 1.0e-6
    slack_smoothing: quantity("dimensionless", ge=0.0, le=0.01) = 1.0e-5
    BA: Annotated[float, PlainValidator(_internal_damping)] = 0.0
    EI: quantity("force*length^2", ge=0.0) = 0.0
    BA_dynamic: quantity("force*time", ge=0.0) = 0.0


class MotionSpec(_Spec):
    """``points.<name>.motion``: displacement history of a prescribed point.

    ``harmonic``: ``amplitude sin(2 pi t / period + phase)``; ``table``: ``times`` and
    ``values`` (3-vectors) or a CSV ``file`` with columns t, x, y, z (relative to the case
    file), linearly interpolated.
    """

    kind: Literal["harmonic", "table"]
    amplitude: Vector3 = (0.0, 0.0, 0.0)
    period: quantity("time", gt=0.0) | None = None
    phase: quantity("angle") = 0.0
    times: list[quantity("time")] | None = None
    values: list[Vector3] | None = None
    file: str | None = None
    ramp_time: quantity("time", ge=0.0) = 0.0


class ForceHistorySpec(MotionSpec):
    """``points.<name>.force_history``: force history added to a free point's force."""

    amplitude: Force3 = (0.0, 0.0, 0.0)
    values: list[Force3] | None = None


def _matrix6(value: Any) -> tuple[tuple[float, ...], ...]:
    """A 6x6 matrix of plain numbers (the case's units), given as 6 rows of 6, or 6 numbers
    for a diagonal."""
    rows = value
    if isinstance(value, list) and len(value) == 6 and all(
            isinstance(v, int | float) for v in value):
        rows = [[value[i] if i == j else 0.0 for j in range(6)] for i in range(6)]
    ok = (isinstance(rows, list) and len(rows) == 6
          and all(isinstance(r, list) and len(r) == 6 for r in rows))
    if not ok:
        raise _fail("must be a 6x6 matrix (6 rows of 6 numbers) or 6 diagonal numbers")
    try:
        matrix = tuple(tuple(float(x) for x in r) for r in rows)
    except (TypeError, ValueError, OverflowError):
        raise _fail("must contain numbers only") from None
    for i, row in enumerate(matrix):
        for j, x in enumerate(row):
            problem = check_number(x)
            if problem is not None:
                raise _fail(f"entry [{i}][{j}] {problem}")
    return matrix


Matrix6 = Annotated[Any, PlainValidator(_matrix6)]


class HydrostaticsSpec(_Spec):
    """``bodies.<name>.hydrostatics``: ``box`` (length, width, height), ``cylinder`` (diameter,
    height), ``matrix`` (stiffness 6x6, volume, center_of_buoyancy) or ``none``."""

    kind: Literal["none", "box", "cylinder", "matrix"] = "none"
    length: quantity("length", ge=0.0) = 0.0
    width: quantity("length", ge=0.0) = 0.0
    height: quantity("length", ge=0.0) = 0.0
    diameter: quantity("length", ge=0.0) = 0.0
    stiffness: Matrix6 | None = None
    volume: quantity("volume", ge=0.0) = 0.0
    center_of_buoyancy: Vector3 = (0.0, 0.0, 0.0)


class ExcitationSpec(_Spec):
    """``bodies.<name>.excitation``: wave exciting force per unit wave amplitude over
    frequency: ``omegas`` [rad/s], ``amplitude`` and ``phase`` [deg], one row of 6 per
    frequency (plain numbers in the case's units)."""

    omegas: list[Number]
    amplitude: list[list[Number]]
    phase: list[list[Number]]


class BemOmegaSpec(_Spec):
    """``bodies.<name>.hydrodynamics.bem.omega``: ``n`` frequencies evenly spaced from
    ``min`` to ``max`` [rad/s]."""

    min: quantity("1/time", gt=0.0)
    max: quantity("1/time", gt=0.0)
    n: PositiveInt


class BemDimensionsSpec(_Spec):
    """``bodies.<name>.hydrodynamics.bem.dimensions``: ``length``, ``width``, ``height`` of a
    box, ``diameter``, ``height`` of a vertical cylinder."""

    length: quantity("length", gt=0.0) | None = None
    width: quantity("length", gt=0.0) | None = None
    height: quantity("length", gt=0.0) | None = None
    diameter: quantity("length", gt=0.0) | None = None


class BemSpec(_Spec):
    """``bodies.<name>.hydrodynamics.bem``: compute the database with capytaine
    (:mod:`moorline.io.hydrodynamics`). ``shape``: ``box``, ``cylinder`` or a mesh file
    (relative to the case file, case length unit, water line at z = 0)."""

    shape: str
    dimensions: BemDimensionsSpec | None = None
    draft: quantity("length", gt=0.0) | None = None
    omega: BemOmegaSpec
    heading_deg: quantity("angle") | list[quantity("angle")] | None = None
    panel_size: quantity("length", gt=0.0) | None = None
    lid: bool = False
    infinite_frequency: bool = True


class HydrodynamicsSpec(_Spec):
    """``bodies.<name>.hydrodynamics``: a capytaine ``database`` (NetCDF file, relative to
    the case file) or a ``bem`` computation (cached), exactly one."""

    database: str | None = None
    bem: BemSpec | None = None


class BodySpec(_Spec):
    """``bodies.<name>``: a rigid body (see :class:`moorline.model.Body`). Matrices (inertia,
    added mass, damping, hydrostatic stiffness) are plain numbers in the case's units.
    ``inertia`` holds the diagonal ``Ixx, Iyy, Izz`` about the centre of gravity (body frame),
    ``products_of_inertia`` the tensor's off-diagonal entries ``I[0][1], I[0][2], I[1][2]``."""

    kind: Literal["free", "fixed", "pinned"] = "free"
    position: Vector3
    motion: MotionSpec | None = None
    pin_body: str | None = None
    rotation: Annotated[list[quantity("angle")], AfterValidator(_three)] = (0.0, 0.0, 0.0)
    mass: quantity("mass", ge=0.0)
    center_of_gravity: Vector3 = (0.0, 0.0, 0.0)
    inertia: Annotated[list[quantity("mass*length^2", ge=0.0)],
                       AfterValidator(_three)] = (0.0,) * 3
    products_of_inertia: Annotated[list[quantity("mass*length^2")],
                                   AfterValidator(_three)] = (0.0,) * 3
    added_mass: Matrix6 | None = None
    damping: Matrix6 | None = None
    additional_damping: Matrix6 | None = None
    hydrostatics: HydrostaticsSpec = Field(default_factory=HydrostaticsSpec)
    force: Force3 = (0.0, 0.0, 0.0)
    moment: Annotated[list[quantity("force*length")], AfterValidator(_three)] = (0.0,) * 3
    force_history: ForceHistorySpec | None = None
    drag_area: Annotated[list[quantity("area", ge=0.0)], AfterValidator(_three)] = (0.0,) * 3
    Cd: Coefficient = 1.0
    wave_loads: bool = False
    excitation: ExcitationSpec | None = None
    hydrodynamics: HydrodynamicsSpec | None = None


class PointSpec(_Spec):
    """``points.<name>``: a fixed, free or prescribed node.

    ``initial_position`` (prescribed points only): where load-stepped statics starts the point
    from; it moves to ``position`` over the load steps.
    """

    kind: Literal["fixed", "free", "prescribed", "body"]
    position: Vector3
    body: str | None = None
    mass: quantity("mass", ge=0.0) = 0.0
    volume: quantity("volume", ge=0.0) = 0.0
    force: Force3 = (0.0, 0.0, 0.0)
    initial_position: Vector3 | None = None
    motion: MotionSpec | None = None
    force_history: ForceHistorySpec | None = None
    Cd: Coefficient = 0.0
    drag_area: quantity("area", ge=0.0) = 0.0
    Ca: Coefficient = 0.0


class LineSpec(_Spec):
    """``lines.<name>``: a cable between two points. ``clamp_a``/``clamp_b``: a clamped end
    (line type with ``EI > 0``, a fixed or prescribed point), the direction its tangent is
    held along (from end A towards end B); omitted: pinned."""

    type: str
    length: quantity("length", gt=0.0)
    segments: PositiveInt
    end_a: str
    end_b: str
    initial_shape: list[Vector3] | None = None
    clamp_a: Annotated[list[float], AfterValidator(_three)] | None = None
    clamp_b: Annotated[list[float], AfterValidator(_three)] | None = None


class StaticsSpec(_Spec):
    """``analyses[i]`` with ``kind: statics`` (see :class:`moorline.model.StaticsSettings`)."""

    kind: Literal["statics"]
    method: Literal["newton", "incremental", "relaxation"] = "newton"
    load_steps: Iterations = 1
    tolerance: quantity("dimensionless", gt=0.0) = 1.0e-8
    max_iterations: Iterations = 50
    stiffness_update: Iterations = 1
    damping: quantity("force*time/length", ge=0.0) | None = None
    damping_decrement: quantity("dimensionless", gt=0.0, le=1.0) = 0.5
    pseudo_dt: quantity("time", gt=0.0) | None = None
    start: Literal["catenary", "straight"] = "catenary"
    max_step: quantity("dimensionless", gt=0.0) = 0.5
    current_drag: bool = False


class DynamicsSpec(_Spec):
    """``analyses[i]`` with ``kind: dynamics`` (see :class:`moorline.model.DynamicsSettings`)."""

    kind: Literal["dynamics"]
    duration: quantity("time", gt=0.0)
    dt: quantity("time", gt=0.0)
    scheme: Literal["newmark", "hht"] = "newmark"
    alpha: quantity("dimensionless", ge=-1.0 / 3.0, le=0.0) = -0.05
    variant: Literal["iterative", "residual_feedback", "incremental"] = "iterative"
    tolerance: quantity("dimensionless", gt=0.0) = 1.0e-6
    max_iterations: Iterations = 20
    stiffness_update: Iterations = 20
    max_step_cuts: Annotated[int, Field(ge=0, le=20)] = 10
    ramp_time: quantity("time", ge=0.0) = 0.0
    viscoelastic_update: Literal["exponential", "incremental"] = "exponential"
    fast_path: bool = True
    rayleigh_ratio: quantity("dimensionless", ge=0.0) = 0.0
    rayleigh_frequencies: Annotated[list[quantity("dimensionless", ge=0.0)],
                                    AfterValidator(lambda v: _pair(v))] = Field(
        default_factory=lambda: [0.0, 0.0])
    envelope_start: quantity("time", ge=0.0) | None = None
    slack_damping: bool = False
    drag_velocity: Literal["element", "node"] = "element"
    start: Literal["statics", "initial"] = "statics"


def _band(values: list[float]) -> list[float]:
    if len(values) != 2 or not values[0] < values[1]:
        raise _fail(f"must be [low, high] with low < high (rad/s), got {list(values)}")
    return values


class ModalSpec(_Spec):
    """``analyses[i]`` with ``kind: modal`` (see :class:`moorline.model.ModalSettings`);
    ``band`` in rad/s (plain numbers, the same in both unit systems)."""

    kind: Literal["modal"]
    n_modes: PositiveInt = 10
    band: Annotated[list[quantity("dimensionless", ge=0.0)], AfterValidator(_band)] | None = None
    mass: Literal["lumped", "consistent"] = "lumped"
    added_mass: bool = True


class StrummingSpec(_Spec):
    """``analyses[i]`` with ``kind: strumming`` (see :class:`moorline.model.StrummingSettings`)."""

    kind: Literal["strumming"]
    viscosity: quantity("area/time", gt=0.0) | None = None
    strouhal: quantity("dimensionless", gt=0.0) = 0.2
    CL0: quantity("dimensionless", gt=0.0) = 0.2
    n_modes: Annotated[int, Field(ge=0, le=MAX_COUNT)] = 6
    substeps: Iterations = 1
    refresh_every: Annotated[int, Field(ge=0, le=MAX_COUNT)] = 0
    duration: quantity("time", gt=0.0) = 10.0
    dt: quantity("time", gt=0.0) = 0.001
    transverse_velocity: Literal["signed", "magnitude"] = "signed"
    min_reynolds: quantity("dimensionless", ge=0.0) = 0.0
    nonpositive_modes: Literal["error", "keep"] = "error"
    drag_damping: bool = False
    taut_axial: bool = False
    held_body_dofs: list[Literal["surge", "sway", "heave", "roll", "pitch", "yaw"]] = []
    mass: Literal["lumped", "consistent"] = "consistent"
    added_mass: bool = True
    initial_CL: quantity("dimensionless") | None = None


class StochasticSpec(_Spec):
    """``analyses[i]`` with ``kind: stochastic`` (see :class:`moorline.model.StochasticSettings`);
    needs ``environment.waves: {kind: random, ...}``."""

    kind: Literal["stochastic"]
    method: Literal["foss", "direct"] = "foss"
    n_modes: Annotated[int, Field(ge=0, le=MAX_COUNT)] = 0
    max_iterations: Iterations = 30
    tolerance: quantity("dimensionless", gt=0.0) = 0.01
    mass: Literal["lumped", "consistent"] = "consistent"
    added_mass: bool = True
    n_points: PositiveInt | None = None


class HarmonicSpec(_Spec):
    """``analyses[i]`` with ``kind: harmonic`` (see :class:`moorline.model.HarmonicSettings`):
    the periodic response by harmonic balance."""

    kind: Literal["harmonic"]
    period: quantity("time", gt=0.0)
    harmonics: PositiveInt = 5
    samples: PositiveInt | None = None
    tolerance: quantity("dimensionless", gt=0.0) = 1e-8
    max_iterations: Iterations = 50
    output_points: PositiveInt = 64


class FatigueCurveSpec(_Spec):
    """``analyses[i].curves.<line type>`` of a fatigue analysis: a curve of
    ``moorline/data/tn_curves.yaml`` and what it needs: ``MBL`` (API T-N curves, the
    reference breaking strength) or ``diameter`` (chain) / ``area`` (DNV S-N curves)."""

    curve: str
    MBL: quantity("force", gt=0.0) | None = None
    diameter: quantity("length", gt=0.0) | None = None
    area: quantity("area", gt=0.0) | None = None

    @field_validator("curve")
    @classmethod
    def _known_curve(cls, value: str) -> str:
        from ..tn_curves import curves

        if value not in curves():
            raise _fail(f"unknown T-N curve {value!r}; known: {', '.join(curves())}")
        return value


class FatigueSpec(_Spec):
    """``analyses[i]`` with ``kind: fatigue`` (see :class:`moorline.model.FatigueSettings`):
    after a dynamics or stochastic analysis."""

    kind: Literal["fatigue"]
    source: Literal["auto", "dynamics", "stochastic"] = "auto"
    curves: dict[str, FatigueCurveSpec]
    spectral: Annotated[list[Literal["narrow_band", "dirlik"]], Field(min_length=1)] = [
        "narrow_band", "dirlik"]
    residue: Literal["half", "repeat"] = "half"
    skip: quantity("time", ge=0.0) | None = None
    safety_factor: quantity("dimensionless", gt=0.0) = 1.0
    seeds: list[Annotated[int, Field(ge=0)]] = []


class ExtremesSpec(_Spec):
    """``analyses[i]`` with ``kind: extremes`` (see :class:`moorline.model.ExtremesSettings`):
    after a dynamics or stochastic analysis."""

    kind: Literal["extremes"]
    source: Literal["auto", "dynamics", "stochastic"] = "auto"
    duration: quantity("time", gt=0.0) = 10800.0
    method: Literal["weibull", "gumbel"] = "weibull"
    percentiles: list[quantity("dimensionless", ge=0.0, le=100.0)] = [50.0, 90.0, 99.0]
    seeds: list[Annotated[int, Field(ge=0)]] = []
    blocks: PositiveInt = 1
    skip: quantity("time", ge=0.0) | None = None


MAX_OFFSET_STEPS = 1001
"""Largest number of offsets per heading of an offset analysis (each one a static solve)."""


def _odd_steps(value: Any) -> int:
    """``steps`` of an offset analysis: an odd integer from 3 to :data:`MAX_OFFSET_STEPS` (the
    middle offset is the undisplaced state)."""
    n = _positive_int(value, MAX_OFFSET_STEPS)
    if n < 3 or n % 2 == 0:
        raise _fail(f"must be an odd integer >= 3 (the middle offset is zero), got {_show(value)}")
    return n


class OffsetSpec(_Spec):
    """``analyses[i]`` with ``kind: offset`` (see :class:`moorline.model.OffsetSettings`): a
    body or a rigid group of prescribed points moved through offsets along headings [deg]
    from ``-max_offset`` to ``+max_offset`` in ``steps`` (odd) steps."""

    kind: Literal["offset"]
    headings: Annotated[list[quantity("angle")], Field(min_length=1)] = [0.0]
    max_offset: quantity("length", gt=0.0)
    steps: Annotated[int, PlainValidator(_odd_steps)] = 21
    yaw: bool = False
    max_yaw: quantity("angle", gt=0.0, le=180.0) = 10.0
    body: str | None = None
    points: Annotated[list[str], Field(min_length=1)] | None = None
    reference: Vector3 | None = None
    stiffness: bool = True

    @field_validator("headings")
    @classmethod
    def _distinct(cls, value: list[float]) -> list[float]:
        if len(set(value)) != len(value):
            raise _fail(f"headings must be distinct, got {value}")
        return value


# ``analyses[i]``: one model per row of the table of analysis kinds (moorline.analyses.KINDS,
# which names each kind's model in this module).
AnalysisSpec = Annotated[Union[tuple(globals()[k.spec] for k in KINDS.values())],  # noqa: UP007
                         Field(discriminator="kind")]


class DesignSpec(_Spec):
    """``design``: the standard and condition of the line tension checks
    (:mod:`moorline.design`); ``analysis`` ``None``: quasi-static for statics, dynamic for
    dynamics and stochastic results; ``storm_duration`` (``None``: 3 hours) sets the most
    probable maximum of stochastic results."""

    standard: Literal["API-RP-2SK", "DNV-OS-E301"] = "API-RP-2SK"
    condition: Literal["intact", "damaged"] = "intact"
    analysis: Literal["quasi-static", "dynamic"] | None = None
    consequence_class: Literal[1, 2] = 1
    storm_duration: quantity("time", gt=0.0) | None = None


class OutputSpec(_Spec):
    """``output``: interval of written time histories (``None``: unit-system default) and
    MoorDyn output channels written by a dynamics run (``channels``)."""

    every: quantity("time", gt=0.0) | None = None
    channels: list[str] = Field(default_factory=list)


class CaseSpec(_Spec):
    """A whole case file."""

    name: str
    units: Literal["SI", "US"] = "SI"
    environment: EnvironmentSpec = Field(default_factory=EnvironmentSpec)
    line_types: dict[str, LineTypeSpec]
    points: dict[str, PointSpec]
    lines: dict[str, LineSpec]
    bodies: dict[str, BodySpec] | None = None
    analyses: list[AnalysisSpec] | None = None
    output: OutputSpec = Field(default_factory=OutputSpec)
    design: DesignSpec | None = None

    @field_validator("name")
    @classmethod
    def _name_not_empty(cls, value: str) -> str:
        if not value.strip():
            raise _fail("must not be empty")
        return value

    @field_validator("lines")
    @classmethod
    def _some_lines(cls, value: dict[str, LineSpec]) -> dict[str, LineSpec]:
        if not value:
            raise _fail("must define at least one line")
        return value



# ---- pydantic errors -> (dotted key path, one-line message) -------------------------------

def _strip(tp: Any) -> Any:
    """Remove ``Annotated`` and ``| None`` wrappers from a type."""
    while True:
        origin = get_origin(tp)
        if origin is Annotated:
            tp = get_args(tp)[0]
        elif origin in (Union, types.UnionType):
            members = [a for a in get_args(tp) if a is not type(None)]
            if len(members) != 1:
                return tp
            tp = members[0]
        else:
            return tp


def _tagged(tp: Any) -> dict[str, type[BaseModel]]:
    """Members of a discriminated union ``Annotated[A | B, Field(discriminator=...)]`` by tag."""
    if get_origin(tp) is not Annotated:
        return {}
    inner, *metadata = get_args(tp)
    if not any(getattr(m, "discriminator", None) for m in metadata):
        return {}
    members = get_args(inner) if get_origin(inner) in (Union, types.UnionType) else (inner,)
    tags: dict[str, type[BaseModel]] = {}
    for member in members:
        if _is_model(member) and "kind" in member.model_fields:
            for tag in get_args(member.model_fields["kind"].annotation):
                tags[tag] = member
    return tags


def _is_model(tp: Any) -> bool:
    return isinstance(tp, type) and issubclass(tp, BaseModel)


def _locate(loc: tuple[Any, ...]) -> tuple[list[str | int], type[BaseModel] | None]:
    """Follow a pydantic ``loc`` through the schema.

    Returns the key path without union tags and the spec class holding its last key.
    """
    tp: Any = CaseSpec
    parts: list[str | int] = []
    parent: type[BaseModel] | None = None
    for item in loc:
        tags = _tagged(tp)
        tp = _strip(tp)
        if item == "[key]":
            continue
        if isinstance(item, str) and item in tags:
            tp = tags[item]
            continue
        parts.append(item)
        parent = None
        if _is_model(tp):
            parent = tp
            field = tp.model_fields.get(item) if isinstance(item, str) else None
            tp = field.annotation if field is not None else None
        elif get_origin(tp) is dict:
            tp = get_args(tp)[1]
        elif get_origin(tp) in (list, tuple):
            tp = get_args(tp)[0]
        else:
            tp = None
    return parts, parent


def dotted(parts: list[str | int]) -> str:
    """``["points", "a", "position", 2]`` -> ``points.a.position[2]``."""
    out = ""
    for part in parts:
        if isinstance(part, int):
            out += f"[{part}]"
        else:
            out += f".{part}" if out else str(part)
    return out


def _unknown_key(key: Any, parent: type[BaseModel] | None) -> str:
    valid = list(parent.model_fields) if parent is not None else []
    close = difflib.get_close_matches(str(key), valid, n=1, cutoff=0.6)
    if close:
        return f"unknown key {str(key)!r} (did you mean {close[0]!r}?)"
    return f"unknown key {str(key)!r}; valid keys: {', '.join(valid)}"


def _message(err: Any, parts: list[str | int], parent: type[BaseModel] | None) -> str:
    kind, value, ctx = err["type"], err.get("input"), err.get("ctx") or {}
    last = parts[-1] if parts else ""
    if kind == "case_value":
        return str(ctx.get("reason", err["msg"]))
    if kind == "missing":
        return f"missing required key {str(last)!r}"
    if kind == "extra_forbidden":
        return _unknown_key(last, parent)
    if kind == "string_type":
        return f"expected a string, got {_show(value)}"
    if kind in ("model_type", "model_attributes_type", "dict_type"):
        return f"expected a mapping of keys, got {_show(value)}"
    if kind in ("list_type", "tuple_type"):
        return f"expected a list, got {_show(value)}"
    if kind == "literal_error":
        return f"must be one of {ctx.get('expected')}, got {_show(value)}"
    if kind == "union_tag_invalid":
        allowed = ctx.get("expected_tags")
        return f"unknown kind {ctx.get('tag')!r}; allowed kinds: {allowed}"
    if kind == "union_tag_not_found":
        return "missing required key 'kind'"
    return str(err["msg"])


def describe_errors(exc: ValidationError, limit: int = 4) -> tuple[str, str]:
    """Turn a pydantic ``ValidationError`` into ``(field, reason)`` on one line.

    The first error (unknown keys first) gives the field; up to ``limit - 1`` further errors
    are appended to the reason as ``also: <field>: <reason>``.
    """
    described: list[tuple[str, str]] = []
    # an unknown key first: a misspelt key also makes the right one "missing"
    errors = sorted(exc.errors(), key=lambda e: e["type"] != "extra_forbidden")
    for err in errors:
        parts, parent = _locate(tuple(err["loc"]))
        if err["type"] in ("union_tag_invalid", "union_tag_not_found"):
            parts = [*parts, "kind"]
        described.append((dotted(parts), _message(err, parts, parent)))
    field, reason = described[0]
    extra = [f"{f}: {r}" for f, r in described[1:limit]]
    if len(described) > limit:
        extra.append(f"and {len(described) - limit} more")
    if extra:
        reason += " (also: " + "; ".join(extra) + ")"
    return field, reason
