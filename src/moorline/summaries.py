"""The JSON summaries of analyses (``--json`` output and ``summary.json``): plain dicts built
from result objects and datasets, in the case's units."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

__all__ = ["dynamics_summary", "extremes_summary", "fatigue_summary", "harmonic_summary",
           "offset_summary",
           "history_summary", "modal_summary", "statics_summary", "stochastic_summary",
           "strumming_summary"]


def _outcome(result: Any) -> dict[str, Any]:
    """``converged``, ``status`` and ``message`` of a result: the head of every summary."""
    return {"converged": bool(result.success), "status": str(result.status),
            "message": str(result.message)}


def statics_summary(result: Any, with_stiffness: bool = True) -> dict[str, Any]:
    """The ``--json`` object of a static result.

    Parameters
    ----------
    result
        A :class:`~moorline.results.StaticResult`.
    with_stiffness
        Add the 3x3 restoring stiffness of free and prescribed points (only computed when the
        result converged: away from equilibrium it means nothing).

    Returns
    -------
    dict
        ``{"case", "converged", "iterations", "units", "method", "message",
        "lines": {id: {"end_a": {"force", "tension"}, "end_b": ..., "max_tension",
        "seabed_length"}}, "points": {id: {"kind", "position", "stiffness"?}}}``; forces are
        those the line exerts on its end points, in the case's units.
    """
    mesh = result.mesh
    lines: dict[str, Any] = {}
    for name in mesh.line_names:
        entry: dict[str, Any] = {}
        for end in ("a", "b"):
            force = np.asarray(result.end_force(name, end), dtype=float)
            entry[f"end_{end}"] = {"force": (force + 0.0).tolist(),  # no -0.0
                                   "tension": float(np.linalg.norm(force))}
        # the largest tension is often at an end (the fairlead), not at an element midpoint
        entry["max_tension"] = result.max_tension(name)
        entry["seabed_length"] = float(result.seabed_length(name))
        lines[name] = entry
    points: dict[str, Any] = {}
    for name, kind in zip(mesh.point_names, mesh.point_kind, strict=True):
        point: dict[str, Any] = {"kind": kind,
                                 "position": np.asarray(result.point_position(name)).tolist()}
        if with_stiffness and result.success and kind in ("free", "prescribed"):
            from .solvers import stiffness

            point["stiffness"] = np.asarray(stiffness.point_stiffness(result, name)).tolist()
        points[name] = point
    summary = {
        "case": result.case, **_outcome(result),
        "iterations": int(result.iterations), "units": result.units, "method": result.method,
        "lines": lines, "points": points,
    }
    if mesh.body_names:
        summary["bodies"] = _bodies_summary(result, with_stiffness)
    return summary


def _bodies_summary(result: Any, with_stiffness: bool) -> dict[str, Any]:
    """Pose of every body (and the force of a pinned body's pin on it) and, at a converged
    equilibrium, its 6x6 mooring stiffness (lines only) about its origin."""
    from .solvers import stiffness

    mesh = result.mesh
    out: dict[str, Any] = {}
    for b, name in enumerate(mesh.body_names):
        entry: dict[str, Any] = {
            "position": result.body_position(name).tolist(),
            "rotation_deg": np.degrees(result.body_rotation(name)).tolist()}
        if mesh.bodies[b].kind == "pinned":
            entry["pin_reaction"] = result.pin_reaction(name).tolist()
        attached = [mesh.point_names[int(n)] for n, k in zip(mesh.slave_node, mesh.slave_body,
                                                              strict=True) if k == b]
        if with_stiffness and result.success and attached:
            entry["mooring_stiffness"] = np.asarray(stiffness.group_stiffness(
                result, attached, result.body_position(name))).tolist()
        out[name] = entry
    return out


def dynamics_summary(result: Any) -> dict[str, Any]:
    """The ``--json`` object of a :class:`~moorline.results.DynamicResult` (see
    :func:`history_summary`)."""
    return history_summary(result.to_plain(), result.settings, result.success,
                           result.message, result.counters, result.status)


def history_summary(ds: Any, settings: Any, success: bool, message: str,
                    counters: dict[str, int], status: str = "") -> dict[str, Any]:
    """The ``--json`` object of a dynamics analysis, from its histories.

    Parameters
    ----------
    ds
        The dynamics group (:meth:`~moorline.results.DynamicResult.to_plain` or
        ``to_xarray``, or read back):
        ``time``, ``end_force(time, line, end, xyz)``, ``position(time, node, xyz)``,
        ``point_node`` and the coordinate ``point_kind``.
    settings
        The :class:`~moorline.model.DynamicsSettings` (or its fields as a dict).
    success, message, status
        How the run ended (``status`` default: ``completed`` or ``failed``).
    counters
        Solver counters (``steps``, ``iterations``, ``factorizations``, ``step_cuts``, ...);
        empty when the run failed.

    Returns
    -------
    dict
        ``{"converged", "status", "message", "duration", "dt", "records", "time_start",
        "time_end",
        "lines": {id: {"end_a": {"max", "min", "mean", "std"}, "end_b": ..., "segment_a": ...,
        "segment_b": ...}}, "tension_note",
        "points": {id: {"kind", "min": [x, y, z], "max": [x, y, z]}}, "counters",
        "envelope": {"start", "records", "max_element_tension": {"tension", "line",
        "arc_length"}}}``; statistics over the output records, in the case's units; the
        envelope's largest element tension (from ``envelope_start``, element midpoints: the
        end tensions are in ``lines``), on which line and where (unstretched arc length from
        end a), when the group has the envelope (:mod:`moorline.envelope`).
    """
    time = np.asarray(ds["time"].values, dtype=float)
    tension = np.linalg.norm(np.asarray(ds["end_force"].values, dtype=float), axis=-1)
    lines = {str(name): {f"end_{end}": _stats(tension[:, k, j]) for j, end in enumerate("ab")}
             for k, name in enumerate(ds["line"].values)}
    _segment_stats(ds, lines)
    position = np.asarray(ds["position"].values, dtype=float)
    kinds = ds["point_kind"].values if "point_kind" in ds.coords else [""] * ds.sizes["point"]
    points = {}
    for name, kind, node in zip(ds["point"].values, kinds, ds["point_node"].values,
                                strict=True):
        path = position[:, int(node)]
        empty = np.full(3, np.nan)
        points[str(name)] = {"kind": str(kind),
                             "min": (path.min(axis=0) if len(path) else empty).tolist(),
                             "max": (path.max(axis=0) if len(path) else empty).tolist()}
    fields = settings if isinstance(settings, dict) else vars(settings)
    return {"converged": bool(success),
            "status": status or ("completed" if success else "failed"), "message": message,
            "duration": float(fields["duration"]), "dt": float(fields["dt"]),
            "records": int(len(time)),
            "time_start": float(time[0]) if len(time) else None,
            "time_end": float(time[-1]) if len(time) else None,
            "lines": lines, "points": points, "counters": counters,
            "tension_note": TENSION_NOTE, **_envelope_summary(ds)}


def _envelope_summary(ds: Any) -> dict[str, Any]:
    """``{"envelope": ...}`` of :func:`history_summary` (empty without the envelope)."""
    if "tension_max" not in ds:
        return {}
    largest = np.asarray(ds["tension_max"].values, dtype=float)
    where = None
    if np.isfinite(largest).any():
        e = int(np.nanargmax(largest))
        where = {"tension": float(largest[e]), "line": str(ds["element_line"].values[e]),
                 "arc_length": float(ds["element_arc_length"].values[e])}
    return {"envelope": {"start": float(ds.attrs.get("envelope_start", 0.0)),
                         "records": int(ds.attrs.get("envelope_records", 0)),
                         "max_element_tension": where}}


#: What ``end_*`` and ``segment_*`` of a dynamics summary are, against MoorDyn's names.
TENSION_NOTE = ("end_a/end_b: the force of the line on its end point (MoorDyn's FairTen/"
                "AnchTen output channels, the net force on the end node); segment_a/"
                "segment_b: the end segment's tension (MoorDyn's GetLineFairTen), lower by "
                "the end node's share of weight, buoyancy and seabed contact (1-2 % on chain)")


def _segment_stats(ds: Any, lines: dict[str, dict[str, Any]]) -> None:
    """Add the end segments' tension statistics (``segment_a``, ``segment_b``) per line."""
    if "element_line" not in ds or "tension" not in ds:
        return
    owner = np.asarray([str(v) for v in ds["element_line"].values])
    tension = np.asarray(ds["tension"].values, dtype=float)
    for name, entry in lines.items():
        elements = np.flatnonzero(owner == name)  # from end a to end b (moorline.mesh)
        if len(elements):
            entry["segment_a"] = _stats(tension[:, elements[0]])
            entry["segment_b"] = _stats(tension[:, elements[-1]])


def _stats(values: np.ndarray) -> dict[str, float]:
    if not len(values):
        return dict.fromkeys(("max", "min", "mean", "std"), math.nan)
    return {"max": float(values.max()), "min": float(values.min()),
            "mean": float(values.mean()), "std": float(values.std())}


def modal_summary(result: Any) -> dict[str, Any]:
    """The ``--json`` object of a modal result (:class:`~moorline.results.ModalResult`):
    ``{"case", "converged", "status", "message", "modes": [{"index", "omega", "period",
    "dominant"}]}``, ``index`` numbering the modes from 1 in increasing frequency (as the
    ``mode`` coordinate of the dataset), ``omega`` in rad/s, ``period`` in s."""
    modes = [{"index": k + 1, "omega": float(result.omega[k]),
              "period": float(result.period[k]), "dominant": str(result.dominant[k])}
             for k in range(result.n_modes)]
    return {"case": result.case, **_outcome(result), "modes": modes}


def strumming_summary(result: Any) -> dict[str, Any]:
    """The ``--json`` object of a :class:`~moorline.results.StrummingResult`: largest lift
    coefficient and strumming displacement, the last modes' frequencies [rad/s]."""
    return {**_outcome(result),
            "max_lift_coefficient": float(np.abs(result.lift_coefficient).max(initial=0.0)),
            "max_displacement": float(np.abs(result.displacement).max(initial=0.0)),
            "modes": [float(w) for w in result.omega]}


def stochastic_summary(result: Any) -> dict[str, Any]:
    """The ``--json`` object of a :class:`~moorline.results.StochasticResult`: linearization
    iterations, largest standard deviations, the tension standard deviation per element."""
    return {**_outcome(result), "iterations": int(result.iterations),
            "max_displacement_std": float(result.displacement_std.max(initial=0.0)),
            "max_tension_std": float(result.tension_std.max(initial=0.0)),
            "tension_std": [float(v) for v in result.tension_std]}


def harmonic_summary(result: Any) -> dict[str, Any]:
    """The ``--json`` object of a :class:`~moorline.results.HarmonicResult`: Newton
    iterations, largest first-harmonic amplitude, tension range per element and, with bodies,
    each body's first-harmonic amplitude per dof."""
    out = {**_outcome(result), "iterations": int(result.iterations),
           "max_first_harmonic_amplitude": float(result.amplitude(1).max(initial=0.0)),
           "tension_min": [float(v) for v in result.tension.min(axis=0)],
           "tension_max": [float(v) for v in result.tension.max(axis=0)]}
    if len(getattr(result, "body_pose", ())):
        out["bodies"] = {name: {"first_harmonic_amplitude": [
            float(v) for v in result.body_amplitude(name, 1)]}
            for name in result.mesh.body_names}
    return out


def _per_line(values: Any, names: Any) -> dict[str, dict[str, float]]:
    """``{line: {"end_a": v, "end_b": v}}`` of an (n_lines, 2) array (NaN as ``None``)."""
    return {str(n): {f"end_{e}": _number(values[k, j]) for j, e in enumerate("ab")}
            for k, n in enumerate(names)}


def _number(value: Any) -> float | None:
    value = float(value)
    return None if math.isnan(value) else value


def fatigue_summary(result: Any) -> dict[str, Any]:
    """The ``--json`` object of a :class:`~moorline.fatigue_analysis.FatigueResult`: per
    method, damage over the analysed duration and life [years] at both ends of every line,
    and the element of least life."""
    methods = {}
    for k, method in enumerate(result.methods):
        life = result.element_life[k]
        worst = int(np.nanargmin(life)) if np.isfinite(life).any() else None
        methods[method] = {
            "damage": _per_line(result.damage[k], result.line_names),
            "life_years": _per_line(result.life[k], result.line_names),
            "min_element_life_years": None if worst is None else float(life[worst]),
            "min_life_element": worst}
    return {**_outcome(result), "source": result.source, "duration": result.duration,
            "safety_factor": result.safety_factor,
            "curves": {t: c.name for t, (c, _) in result.curves.items()},
            "methods": methods}


def extremes_summary(result: Any) -> dict[str, Any]:
    """The ``--json`` object of an :class:`~moorline.extremes_analysis.ExtremesResult`: the
    most probable maximum, the sampled maximum, mean, standard deviation and percentiles at
    both ends of every line, in the case's units."""
    names = result.line_names
    return {**_outcome(result), "source": result.source, "method": result.method,
            "duration": result.duration, "realizations": result.realizations,
            "record_length": result.record_length,
            "mpm": _per_line(result.mpm, names), "maximum": _per_line(result.maximum, names),
            "mean": _per_line(result.mean, names), "std": _per_line(result.std, names),
            "percentiles": {f"{q:g}": _per_line(result.percentile[i], names)
                            for i, q in enumerate(result.percentiles)},
            "max_element_mpm": float(np.nanmax(result.element_mpm))}


def offset_summary(result: Any) -> dict[str, Any]:
    """The ``--json`` object of an :class:`~moorline.offset_result.OffsetResult`.

    Returns
    -------
    dict
        ``{"case", "converged", "status", "message", "body", "points", "reference",
        "stiffness" (6x6 at the undisplaced state, ``None`` when not computed),
        "headings": [{"heading", "offsets", "restoring_force" (along the heading, positive
        pulling back), "fairlead_tension": {line: [...]}, "anchor_tension": {line: [...]},
        "max_fairlead_tension": {line: v}}], "yaw"?: {"angles", "yaw_moment",
        "max_fairlead_tension"}}``, in the case's units (angles in degrees; NaN as ``None``
        in JSON).
    """
    from .offset_result import along

    names = list(result.line_names)

    def per_line(values: np.ndarray) -> dict[str, list[float]]:
        return {n: [float(v) for v in values[:, j]] for j, n in enumerate(names)}

    def largest(values: np.ndarray) -> dict[str, float | None]:
        return {n: (float(np.nanmax(values[:, j])) if np.isfinite(values[:, j]).any()
                    else None) for j, n in enumerate(names)}

    headings = []
    for heading, sweep in zip(result.headings, result.sweeps, strict=True):
        headings.append({
            "heading": heading, "offsets": [float(v) for v in result.offsets],
            "restoring_force": [float(v) for v in along(sweep.restoring_force, heading)],
            "fairlead_tension": per_line(sweep.fairlead_tension),
            "anchor_tension": per_line(sweep.anchor_tension),
            "max_fairlead_tension": largest(sweep.fairlead_tension)})
    stiffness = result.stiffness_at_rest()
    summary: dict[str, Any] = {
        "case": result.case, **_outcome(result), "body": result.group.body,
        "points": list(result.group.points),
        "reference": [float(v) for v in result.reference],
        "stiffness": stiffness.tolist() if np.isfinite(stiffness).all() else None,
        "headings": headings}
    if result.yaw is not None:
        summary["yaw"] = {"angles": [float(v) for v in result.yaw_angles],
                          "yaw_moment": [float(-v) for v in result.yaw.restoring_force[:, 5]],
                          "max_fairlead_tension": largest(result.yaw.fairlead_tension)}
    return summary
