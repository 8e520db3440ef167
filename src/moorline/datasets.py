"""The one dataset builder of the results, its variable table and the dynamics record list.

Every analysis group (in memory, ``to_plain()`` or ``to_xarray()``; on disk, a group of
``results.nc``) is made by :func:`build_plain` (a :class:`~moorline.plain_dataset.PlainDataset`
of numpy arrays: what a run writes, without importing xarray; :func:`build_dataset` gives it
as an :class:`xarray.Dataset`): it stamps the group with the same attributes (:func:`group_attrs`:
``analysis``, ``case``, ``units``, ``moorline_version``, ``success``, ``status``, ``message``,
the counters and the settings as ``setting_<name>``) and gives every data variable and
coordinate its ``units`` (in the case's unit system) and ``long_name`` from :data:`VARIABLES`;
a variable the table does not know is an error.

:data:`DYNAMIC_VARIABLES` lists the variables of a dynamics record (name, dimensions after
``time``, how each is derived from a record): the streamed file
(:class:`moorline.io.stream.HistoryWriter`) and the in-memory dataset
(:meth:`moorline.results.DynamicResult.to_plain`) are both made from it.

Conventions: body dofs are labelled :data:`BODY_DOFS` (``surge, sway, heave, roll, pitch,
yaw``: translations of the body origin along x, y, z, then the rotation vector's components);
modes are numbered from 1 in increasing frequency (coordinate ``mode``).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from . import __version__
from .envelope import ENVELOPE_VARIABLES, TensionEnvelope, envelope_start, line_coords
from .plain_dataset import PlainDataset

if TYPE_CHECKING:
    import xarray as xr

FloatArray = NDArray[np.float64]

#: Labels of the six rigid-body degrees of freedom, in the order of every body array.
BODY_DOFS: tuple[str, ...] = ("surge", "sway", "heave", "roll", "pitch", "yaw")


_BODY = {
    "body_pose": ("{length} (surge, sway, heave), rad (roll, pitch, yaw: rotation vector)",
                  "pose of the body origin"),
    "body_velocity": ("{velocity} (surge, sway, heave), rad/s (roll, pitch, yaw)",
                      "velocity of the body"),
    "body_mooring_force": ("{force} (surge, sway, heave), {force}*{length} (roll, pitch, "
                           "yaw; about the body origin)",
                           "force and moment of the lines on the body"),
    "body_pin_force": ("{force}", "force of the pin on a pinned body (zero for the others)"),
}

#: ``units`` (a key of :data:`moorline.io.units.DIMENSIONS`, or a unit text in which
#: ``{length}``, ``{force}``... stand for the case's units) and ``long_name`` of every variable
#: and coordinate a group may hold: ``VARIABLES[kind][name]``, ``VARIABLES["*"]`` for all kinds.
VARIABLES: dict[str, dict[str, tuple[str, str]]] = {
    "*": {
        "time": ("time", "time"),
        "node": ("1", "node index"),
        "element": ("1", "element index"),
        "xyz": ("1", "axis"),
        "line": ("1", "line"),
        "end": ("1", "line end (a: end_a, b: end_b)"),
        "point": ("1", "point"),
        "point_kind": ("1", "kind of the point"),
        "element_line": ("1", "line of the element"),
        "element_nodes": ("1", "nodes of the element (end a, end b)"),
        "point_node": ("1", "node of the point"),
        "body": ("1", "body"),
        "dof": ("1", "rigid-body degree of freedom"),
        "mode": ("1", "mode number (from 1, in increasing frequency)"),
        "position": ("length", "node position"),
        "tension": ("force", "element tension"),
        "point_position": ("length", "point position"),
        "node_line": ("1", "line of the node (empty: a point ending several lines, or none)"),
        "node_arc_length": ("length", "unstretched arc length of the node from end a of its "
                                      "line"),
        "element_arc_length": ("length", "unstretched arc length of the element midpoint "
                                         "from end a of its line"),
        "line_nodes": ("1", "nodes of the line in order from end a to end b (-1 past end b)"),
        "line_arc_length": ("length", "unstretched arc length from end a of the line's nodes "
                                      "(line_nodes; NaN past end b)"),
        **_BODY,
    },
    "statics": {
        "end_force": ("force", "force of the line on its end point"),
        "end_tension": ("force", "tension at the line end"),
        "max_tension": ("force", "largest tension of the line, its ends included"),
        "seabed_length": ("length", "unstretched length of the line on the seabed"),
        "residual_history": ("force", "max-norm of the out-of-balance force per iteration"),
        "unstretched_length": ("length", "unstretched element length"),
    },
    "dynamics": {
        "velocity": ("velocity", "node velocity"),
        "end_force": ("force", "force of the line on its end point"),
        "end_tension": ("force", "tension at the line end"),
        "fairlead_tension": ("force", "tension at end b of the line (the fairlead)"),
        "wave_elevation": ("length", "free-surface elevation at x = y = 0"),
        "tension_min": ("force", "smallest element tension over the records from "
                                 "envelope_start"),
        "tension_max": ("force", "largest element tension over the records from "
                                 "envelope_start"),
        "tension_mean": ("force", "mean element tension over the records from envelope_start"),
        "tension_std": ("force", "standard deviation of the element tension over the records "
                                 "from envelope_start"),
        "tension_static": ("force", "element tension of the state the run starts from (its "
                                    "statics)"),
    },
    "modal": {
        "omega": ("rad/s", "natural circular frequency (negative: unstable mode)"),
        "period": ("time", "natural period"),
        "frequency_hz": ("Hz", "natural frequency"),
        "dominant": ("1", "direction (or body dof) with the largest share of the mode"),
        "participation": ("1", "share of the mode on the x, y and z dofs"),
        "effective_mass": ("mass", "effective modal mass"),
        "mode_shape": ("{mass}^-1/2", "mass-normalized mode shape (node displacements)"),
    },
    "strumming": {
        "lift_coefficient": ("1", "lift coefficient C_L"),
        "modal_amplitude": ("{mass}^1/2*{length}", "modal amplitude z_n"),
        "displacement": ("length", "strumming displacement about the in-line state"),
        "strouhal_frequency": ("rad/s", "Strouhal shedding circular frequency w_s"),
        "normal_speed": ("velocity", "normal relative flow speed |V_NR|"),
        "omega": ("rad/s", "circular frequency of the mode (last modes)"),
        "damping_ratio": ("1", "modal damping ratio (Tuah eq. 3.2.b.8)"),
    },
    "stochastic": {
        "omega": ("rad/s", "wave circular frequency"),
        "wave_spectrum": ("{length}**2*s", "wave spectrum S(omega)"),
        "displacement_spectrum": ("{length}**2*s", "node displacement spectrum"),
        "tension_spectrum": ("{force}**2*s", "element tension spectrum"),
        "displacement_std": ("length", "standard deviation of the node displacement"),
        "tension_std": ("force", "standard deviation of the element tension"),
        "sigma_normal": ("velocity", "std of the normal relative velocity"),
        "sigma_tangential": ("velocity", "std of the tangential relative velocity"),
        "elevation": ("length", "wave elevation at x = y = 0"),
        "displacement": ("length", "node displacement about the static state"),
        "tension": ("force", "element tension (static plus dynamic)"),
        "body_spectrum": ("{length}**2*s (surge, sway, heave), rad**2*s (roll, pitch, yaw)",
                          "spectrum of the body motion"),
        "body_std": ("{length} (surge, sway, heave), rad (roll, pitch, yaw)",
                     "standard deviation of the body motion"),
        "body_motion": ("{length} (surge, sway, heave), rad (roll, pitch, yaw)",
                        "body motion about the static pose"),
    },
    "harmonic": {
        "term": ("1", "Fourier term: mean, cos k, sin k"),
        "coefficients": ("length", "Fourier coefficients of the node positions"),
        "position": ("length", "node position over one period"),
        "tension": ("force", "element tension over one period"),
        "static_position": ("length", "static node position"),
        "body_coefficients": ("{length} (surge, sway, heave), rad (roll, pitch, yaw: rotation "
                              "vector about the static orientation)",
                              "Fourier coefficients of the body motion"),
        "body_pose": _BODY["body_pose"][0:1] + ("pose of the body origin over one period",),
    },
    "fatigue": {
        "fatigue_method": ("1", "fatigue damage method (rainflow, narrow_band, dirlik)"),
        "damage": ("1", "Miner fatigue damage over the analysed duration at the line end"),
        "annual_damage": ("1/year", "Miner fatigue damage per year at the line end"),
        "life": ("year", "fatigue life at the line end (duration / (safety factor damage))"),
        "cycles": ("1", "tension cycles over the analysed duration at the line end"),
        "mean_tension": ("force", "mean tension at the line end"),
        "element_damage": ("1", "Miner fatigue damage over the analysed duration"),
        "element_life": ("year", "fatigue life of the element"),
        "element_cycles": ("1", "tension cycles of the element over the analysed duration"),
        "element_mean_tension": ("force", "mean element tension"),
    },
    "extremes": {
        "percentile": ("%", "percentile level"),
        "mpm": ("force", "most probable maximum tension at the line end over the exposure"),
        "maximum": ("force", "largest sampled tension at the line end"),
        "mean_tension": ("force", "mean tension at the line end"),
        "std_tension": ("force", "standard deviation of the tension at the line end"),
        "percentile_tension": ("force", "tension percentile at the line end"),
        "fit_location": ("force", "location of the fitted extreme-value distribution"),
        "fit_shape": ("1", "shape of the fitted Weibull distribution of peak excesses"),
        "fit_scale": ("force", "scale of the fitted distribution"),
        "events": ("1", "peaks or maxima fitted (time domain), expected zero-up-crossings "
                        "in the exposure (frequency domain)"),
        "element_mpm": ("force", "most probable maximum element tension over the exposure"),
        "element_maximum": ("force", "largest sampled element tension"),
    },
}


_OFFSET_STATE = {
    "displacement": ("{length} (surge, sway, heave), rad (roll, pitch, yaw: rotation vector)",
                     "imposed displacement of the group (reference point, rotation about it)"),
    "restoring_force": ("{force} (surge, sway, heave), {force}*{length} (roll, pitch, yaw; "
                        "about the moved reference point)",
                        "force and moment of the lines on the group"),
    "fairlead_tension": ("force", "tension at the line end on the group (the fairlead)"),
    "anchor_tension": ("force", "tension at the other line end (the anchor)"),
    "seabed_length": ("length", "unstretched length of the line on the seabed"),
    "suspended_length": ("length", "unstretched length of the line off the seabed"),
    "touchdown_distance": ("length", "horizontal distance from the anchor to the touchdown "
                                     "point (NaN: the line does not touch the seabed)"),
    "stiffness": ("{force}/{length} (translation rows and columns), {force}*{length}/rad "
                  "(rotation rows and columns), {force}/rad or {force}*{length}/{length} "
                  "(coupling)", "6x6 restoring stiffness of the group about the moved "
                                "reference point (mooring only)"),
    "converged": ("1", "statics converged at this offset (1) or not (0)"),
    "iterations": ("1", "statics iterations at this offset"),
}

VARIABLES["offset"] = {
    "heading": ("angle", "heading of the offset (from +x towards +y)"),
    "offset": ("length", "offset of the reference point along the heading"),
    "yaw": ("angle", "yaw angle of the group about the vertical through the reference point"),
    "dof_column": ("1", "rigid-body degree of freedom of the displacement (stiffness column)"),
    "fairlead_end": ("1", "end of the line on the group (a or b)"),
    "reference": ("length", "reference point of the group at the undisplaced state"),
    **_OFFSET_STATE,
    **{f"yaw_{k}": (u, f"{n} (yaw sweep)") for k, (u, n) in _OFFSET_STATE.items()},
}


#: CF attributes beyond ``units`` and ``long_name`` (CF conventions 1.11, sec. 4.4: the time
#: coordinate).
CF_ATTRS: dict[str, dict[str, str]] = {"time": {"standard_name": "time", "axis": "T"}}


def describe(kind: str, name: str, units: str) -> dict[str, str]:
    """``{"units", "long_name"}`` of variable ``name`` of a ``kind`` group in the unit system
    ``units`` (``SI`` or ``US``), with the :data:`CF_ATTRS` of the name.

    Raises
    ------
    KeyError
        When :data:`VARIABLES` does not know the variable.
    """
    from .io.units import DIMENSIONS

    entry = VARIABLES.get(kind, {}).get(name) or VARIABLES["*"].get(name)
    if entry is None:
        raise KeyError(f"{kind} group: variable {name!r} has no units and long_name in "
                       "moorline.datasets.VARIABLES")
    unit, long_name = entry
    system = "US" if units == "US" else "SI"
    if unit in DIMENSIONS:
        unit = DIMENSIONS[unit].unit(system)
    elif "{" in unit:
        unit = unit.format(**{k: DIMENSIONS[k].unit(system)
                              for k in ("length", "velocity", "force", "mass")})
    return {"units": unit, "long_name": long_name, **CF_ATTRS.get(name, {})}


def settings_attrs(settings: Any) -> dict[str, Any]:
    """The settings (a dataclass or a dict) as NetCDF attributes ``setting_<name>``:
    booleans as 0/1, ``None`` as ``"none"``, number sequences as arrays, string sequences
    comma-joined."""
    if dataclasses.is_dataclass(settings) and not isinstance(settings, type):
        settings = dataclasses.asdict(settings)
    out: dict[str, Any] = {}
    for key, value in dict(settings or {}).items():
        if key == "kind":
            continue
        out[f"setting_{key}"] = _attr_value(value)
    return out


def _attr_value(value: Any) -> Any:
    if isinstance(value, bool | np.bool_):
        return int(value)
    if value is None:
        return "none"
    if isinstance(value, tuple | list):
        if all(isinstance(v, str) for v in value):
            return ",".join(value)
        return np.asarray(value, dtype=float)
    return value


def group_attrs(kind: str, *, case: str, units: str, success: bool, status: str, message: str,
                counters: Mapping[str, Any] | None = None, settings: Any = None,
                extra: Mapping[str, Any] | None = None) -> dict[str, Any]:
    """The attributes of every analysis group: ``analysis``, ``case``, ``units``,
    ``moorline_version``, ``success`` (0/1), ``status``, ``message``, the counters, ``extra``
    and the settings (``setting_<name>``)."""
    attrs: dict[str, Any] = {
        "analysis": kind, "case": case, "units": units, "moorline_version": __version__,
        "success": int(bool(success)), "status": str(status), "message": str(message)}
    attrs.update({str(k): _attr_value(v) for k, v in (counters or {}).items()})
    attrs.update({str(k): _attr_value(v) for k, v in (extra or {}).items()})
    attrs.update(settings_attrs(settings))
    return attrs


def build_plain(kind: str, data_vars: Mapping[str, Any], coords: Mapping[str, Any],
                attrs: Mapping[str, Any]) -> PlainDataset:
    """An analysis group: the variables, coordinates and :func:`group_attrs`, every variable
    and coordinate with ``units`` and ``long_name``.

    Parameters
    ----------
    kind
        The analysis kind (the table of :data:`VARIABLES` to use).
    data_vars, coords
        As for :class:`xarray.Dataset`: ``name -> (dims, values)``, a dimension coordinate
        also as a 1-D sequence.
    attrs
        The group attributes (:func:`group_attrs`); ``attrs["units"]`` is the unit system.

    Raises
    ------
    KeyError
        When a variable or coordinate is not in :data:`VARIABLES`.
    """
    ds = PlainDataset(data_vars, coords, attrs)
    units = str(attrs.get("units", "SI"))
    for name, var in ds.variables.items():
        var.attrs.update(describe(kind, name, units))
    return ds


def build_dataset(kind: str, data_vars: Mapping[str, Any], coords: Mapping[str, Any],
                  attrs: Mapping[str, Any]) -> xr.Dataset:
    """:func:`build_plain` as an :class:`xarray.Dataset`."""
    return build_plain(kind, data_vars, coords, attrs).to_xarray()


def check_described(ds: xr.Dataset | PlainDataset) -> list[str]:
    """Names of the variables and coordinates of ``ds`` without ``units`` or ``long_name``."""
    return [str(n) for n in [*ds.data_vars, *ds.coords]
            if not ds[n].attrs.get("units") or not ds[n].attrs.get("long_name")]


# ----------------------------------------------------------------------------- dynamics


@dataclass(frozen=True)
class RecordVariable:
    """A variable of a dynamics record.

    Attributes
    ----------
    name
        Variable name in the dataset.
    dims
        Its dimensions after ``time``.
    derive
        The values from a record (a mapping of the solver's record arrays; with a leading
        time axis for a stack of records).
    bodies
        Only written for systems with bodies.
    """

    name: str
    dims: tuple[str, ...]
    derive: Callable[[Mapping[str, Any]], Any]
    bodies: bool = False


def _field(key: str) -> Callable[[Mapping[str, Any]], Any]:
    return lambda record: np.asarray(record[key], dtype=float)


def _end_tension(record: Mapping[str, Any]) -> FloatArray:
    """Length of ``end_force`` (``np.linalg.norm(..., axis=-1)``, the squares summed in the
    same order; five times faster than a reduction over an axis of 3)."""
    square = np.square(np.asarray(record["end_force"], dtype=float))
    return np.sqrt((square[..., 0] + square[..., 1]) + square[..., 2])


#: The variables of a dynamics record, in order: what the stream writes and the in-memory
#: dataset holds.
DYNAMIC_VARIABLES: tuple[RecordVariable, ...] = (
    RecordVariable("position", ("node", "xyz"), _field("position")),
    RecordVariable("velocity", ("node", "xyz"), _field("velocity")),
    RecordVariable("tension", ("element",), _field("tension")),
    RecordVariable("end_force", ("line", "end", "xyz"), _field("end_force")),
    RecordVariable("end_tension", ("line", "end"), _end_tension),
    RecordVariable("fairlead_tension", ("line",), lambda r: _fairlead_tension(r)),
    RecordVariable("wave_elevation", (), _field("wave_elevation")),
    RecordVariable("body_pose", ("body", "dof"), _field("body_pose"), bodies=True),
    RecordVariable("body_velocity", ("body", "dof"), _field("body_velocity"), bodies=True),
    RecordVariable("body_mooring_force", ("body", "dof"), _field("body_mooring_force"),
                   bodies=True),
    RecordVariable("body_pin_force", ("body", "xyz"), lambda r: _pin_force(r), bodies=True),
)


def _fairlead_tension(record: Mapping[str, Any]) -> FloatArray:
    """Tension at end b of each line: the record's ``end_tension`` when the caller has put
    it there (derived before, in order), else worked out."""
    ends = record["end_tension"] if "end_tension" in record else _end_tension(record)
    return np.asarray(ends)[..., 1]


def _pin_force(record: Mapping[str, Any]) -> FloatArray:
    """The pins' forces of a record (zeros when the record has none: no pinned body)."""
    if "body_pin_force" in record:
        return np.asarray(record["body_pin_force"], dtype=float)
    return np.zeros(np.shape(record["body_pose"])[:-1] + (3,))


def record_variables(mesh: Any) -> tuple[RecordVariable, ...]:
    """The :data:`DYNAMIC_VARIABLES` of a mesh (the body ones only with bodies)."""
    with_bodies = bool(mesh.body_names)
    return tuple(v for v in DYNAMIC_VARIABLES if with_bodies or not v.bodies)


def mesh_coords(mesh: Any) -> tuple[dict[str, Any], dict[str, Any]]:
    """The time-independent variables (``element_nodes``, ``point_node``, ``line_nodes``,
    ``line_arc_length``) and coordinates (``xyz``, ``end``, ``line``, ``point``,
    ``point_kind``, ``element_line``, ``node_line``, ``node_arc_length``,
    ``element_arc_length``; ``body``, ``dof`` with bodies) of a dynamics group (the
    along-line ones: :func:`moorline.envelope.line_coords`)."""
    along, along_coords = line_coords(mesh)
    data = {"element_nodes": (("element", "pair"), np.asarray(mesh.elements, dtype=np.int64)),
            "point_node": (("point",), np.asarray(mesh.point_node, dtype=np.int64)), **along}
    coords: dict[str, Any] = {
        "xyz": ["x", "y", "z"], "end": ["a", "b"], "line": list(mesh.line_names),
        "point": list(mesh.point_names), "point_kind": (("point",), list(mesh.point_kind)),
        "element_line": (("element",), [mesh.line_names[i] for i in mesh.element_line]),
        **along_coords}
    if mesh.body_names:
        coords.update(body=list(mesh.body_names), dof=list(BODY_DOFS))
    return data, coords


def dynamics_dataset(mesh: Any, time: FloatArray, records: Mapping[str, Any],
                     attrs: Mapping[str, Any],
                     static_tension: FloatArray | None = None) -> PlainDataset:
    """The dynamics group from stacked records (leading axis ``time``; ``records`` may be
    empty with ``time`` of length 0: the group a stream starts from).

    With the tension envelope (:class:`moorline.envelope.TensionEnvelope`, from
    ``envelope_start`` of the settings in ``attrs``): ``tension_min``, ``tension_max``,
    ``tension_mean``, ``tension_std``, ``tension_static`` (element; the static value:
    ``static_tension``, default the first record's) with CF ``cell_methods``, and the group
    attributes ``envelope_start`` and ``envelope_records``.
    """
    data, coords = mesh_coords(mesh)
    n_t = len(time)
    for var in record_variables(mesh):
        if n_t:
            values = var.derive(records)
        else:
            values = np.zeros((0, *(_size(mesh, d) for d in var.dims)))
        data[var.name] = (("time", *var.dims), values)
    coords["time"] = np.asarray(time, dtype=float)
    envelope = TensionEnvelope(mesh.n_elements, envelope_start(attrs), static_tension)
    if n_t:
        envelope.add_records(coords["time"], np.asarray(records["tension"], dtype=float))
    data.update({k: (("element",), v) for k, v in envelope.values().items()})
    ds = build_plain("dynamics", data, coords,
                     {**attrs, "envelope_start": envelope.start,
                      "envelope_records": envelope.count})
    for name, method in ENVELOPE_VARIABLES:
        if method:
            ds[name].attrs["cell_methods"] = method
    return ds


def _size(mesh: Any, dim: str) -> int:
    return {"node": mesh.n_nodes, "element": mesh.n_elements, "xyz": 3,
            "line": len(mesh.line_names), "end": 2, "body": len(mesh.body_names),
            "dof": 6}[dim]
