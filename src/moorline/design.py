"""Design checks of line tensions: utilization and safety factor of every line's largest
tension against API RP 2SK or DNV-OS-E301 (factors, clauses and editions in
``moorline/catalog/design.yaml``).

The largest tension of a line is taken, ends included, over its elements and end points
(statics), over the output records too (dynamics), or as the most probable maximum of the
stochastic tension over the storm (stochastic; element tensions only: the stochastic solver
gives no end tensions). A line type without ``MBL`` is not checked, and says so.

API RP 2SK: ``MBL / T_max >= SF`` (intact: 2.00 quasi-static, 1.67 dynamic; damaged: 1.43,
1.25); the design utilization is ``T_max SF / MBL``. DNV-OS-E301: ``gamma_mean T_mean +
gamma_dyn (T_max - T_mean) <= 0.95 MBL`` (dynamic) or ``gamma_qs T_max <= 0.95 MBL``
(quasi-static); the design utilization is the left side over the right. A line passes when its
design utilization is at most 1.
"""

from __future__ import annotations

import math
from functools import cache
from typing import Any

import numpy as np

from .model import DesignSettings
from .package_data import load_yaml

__all__ = ["DESIGN_FILE", "design_summary", "dynamics_extremes", "factors", "line_attrs",
           "line_check", "line_mbl", "most_probable_maximum", "statics_extremes",
           "stochastic_extremes"]

DESIGN_FILE = "design.yaml"
"""The data file of the design factors, in :mod:`moorline.catalog`."""


@cache
def factors() -> dict[str, Any]:
    """The design data file: ``{"storm_duration_s", "standards": {name: {...}}}``."""
    return load_yaml("moorline.catalog", DESIGN_FILE)


def _analysis(settings: DesignSettings, kind: str) -> str:
    if settings.analysis is not None:
        return settings.analysis
    return "quasi-static" if kind == "statics" else "dynamic"


def line_check(settings: DesignSettings, analysis: str, mbl: float | None, t_max: float,
               t_mean: float) -> dict[str, Any]:
    """The check of one line.

    Parameters
    ----------
    settings
        Standard, condition and consequence class.
    analysis
        ``quasi-static`` or ``dynamic``.
    mbl
        Minimum breaking load, ``None`` when unknown.
    t_max, t_mean
        Largest tension and the mean tension where it occurs (equal in statics).

    Returns
    -------
    dict
        ``{"MBL", "max_tension", "mean_tension", "utilization" (T_max / MBL),
        "safety_factor" (MBL / T_max), "design_utilization", "passed", ...}`` with the
        standard's factors; ``{"MBL": None, "passed": None, "note"}`` without an MBL.
    """
    if mbl is None:
        return {"MBL": None, "max_tension": t_max, "passed": None,
                "note": "no MBL for this line type: not checked"}
    data = factors()["standards"][settings.standard]
    entry: dict[str, Any] = {"MBL": mbl, "max_tension": t_max, "mean_tension": t_mean,
                             "utilization": t_max / mbl,
                             "safety_factor": mbl / t_max if t_max > 0 else math.inf}
    if data["method"] == "safety_factor":
        required = float(data["safety_factor"][settings.condition][analysis])
        entry["required_safety_factor"] = required
        entry["design_utilization"] = t_max * required / mbl
    else:
        gammas = data["partial_factors"][settings.condition][int(settings.consequence_class)]
        capacity = float(data["capacity_factor"]) * mbl
        if analysis == "dynamic":
            design = gammas["gamma_mean"] * t_mean + gammas["gamma_dyn"] * (t_max - t_mean)
            entry.update(gamma_mean=gammas["gamma_mean"], gamma_dyn=gammas["gamma_dyn"])
        else:
            design = gammas["gamma_qs"] * t_max
            entry["gamma_qs"] = gammas["gamma_qs"]
        entry.update(design_tension=design, capacity=capacity,
                     design_utilization=design / capacity)
    entry["passed"] = bool(entry["design_utilization"] <= 1.0)
    return entry


def line_mbl(system: Any) -> dict[str, float | None]:
    """The MBL of every line of a system (its line type's), ``None`` where unknown."""
    return {name: system.line_types[line.line_type].MBL for name, line in system.lines.items()}


def line_attrs(system: Any) -> dict[str, Any]:
    """Dataset attributes of the lines' MBL: ``line_MBL`` (one per line, in the order of the
    ``line`` coordinate, NaN where unknown)."""
    return {"line_MBL": [math.nan if v is None else float(v) for v in line_mbl(system).values()]}


def design_summary(system: Any, kind: str, extremes: dict[str, tuple[float, float]],
                   basis: str) -> dict[str, Any]:
    """The ``design`` block of an analysis summary.

    Parameters
    ----------
    system
        The case (its line types' MBL and its ``design`` settings; none: API RP 2SK intact).
    kind
        The analysis kind (``statics``: quasi-static, otherwise dynamic, unless the settings
        say which).
    extremes
        ``{line: (T_max, T_mean)}`` (:func:`statics_extremes`, :func:`dynamics_extremes`,
        :func:`stochastic_extremes`).
    basis
        What ``T_max`` is, for the reader.

    Returns
    -------
    dict
        ``{"standard", "title", "edition", "clause", "verified", "condition", "analysis",
        "consequence_class"?, "basis", "lines": {line: line_check(...)}, "passed",
        "unchecked"}``; ``passed`` is ``None`` when no line has an MBL.
    """
    settings = system.design if system.design is not None else DesignSettings()
    analysis = _analysis(settings, kind)
    data = factors()["standards"][settings.standard]
    mbl = line_mbl(system)
    lines = {name: line_check(settings, analysis, mbl[name], t_max, t_mean)
             for name, (t_max, t_mean) in extremes.items()}
    checked = [c["passed"] for c in lines.values() if c["passed"] is not None]
    out: dict[str, Any] = {
        "standard": settings.standard, "title": data["title"], "edition": data["edition"],
        "clause": " ".join(str(data["clause"]).split()),
        "verified": bool(data.get("verified", True)), "condition": settings.condition,
        "analysis": analysis, "basis": basis, "lines": lines,
        "passed": all(checked) if checked else None,
        "unchecked": [n for n, c in lines.items() if c["passed"] is None]}
    if settings.standard == "DNV-OS-E301":
        out["consequence_class"] = int(settings.consequence_class)
    if system.design is None:
        out["note"] = "no design settings in the case: API RP 2SK, intact"
    return out


def statics_extremes(summary: dict[str, Any]) -> dict[str, tuple[float, float]]:
    """``{line: (T_max, T_max)}`` from a statics summary's ``max_tension`` (ends included)."""
    return {name: (float(line["max_tension"]), float(line["max_tension"]))
            for name, line in summary.get("lines", {}).items()}


def dynamics_extremes(ds: Any) -> dict[str, tuple[float, float]]:
    """``{line: (T_max, T_mean)}`` over the output records of a dynamics group: the largest
    tension of the line's elements and ends, and the time mean of that element's or end's
    tension (all records, the ramp included)."""
    out: dict[str, tuple[float, float]] = {}
    if ds.sizes.get("time", 0) == 0:
        return out
    tension = np.asarray(ds["tension"].values, dtype=float)
    ends = np.linalg.norm(np.asarray(ds["end_force"].values, dtype=float), axis=-1)
    owner = np.asarray([str(v) for v in ds["element_line"].values])
    for k, name in enumerate(str(v) for v in ds["line"].values):
        series = np.concatenate([tension[:, owner == name], ends[:, k, :]], axis=1)
        where = int(np.nanargmax(np.nanmax(series, axis=0)))
        out[name] = (float(np.nanmax(series[:, where])), float(np.nanmean(series[:, where])))
    return out


def extremes_extremes(result: Any) -> dict[str, tuple[float, float]]:
    """``{line: (T_MPM, T_mean)}`` of an extremes analysis
    (:class:`~moorline.extremes_analysis.ExtremesResult`): the largest most probable maximum
    of the line's ends and elements over the analysis' duration, and the mean tension of the
    end with the larger MPM (the design tension of API RP 2SK's dynamic analysis is the most
    probable maximum of the storm, not the largest sample of one record)."""
    out: dict[str, tuple[float, float]] = {}
    mpm = np.asarray(result.mpm, dtype=float)
    element_mpm = np.asarray(result.element_mpm, dtype=float)
    owner = np.asarray(result.element_line)
    mean = np.asarray(result.mean, dtype=float)
    for k, name in enumerate(result.line_names):
        candidates = np.concatenate([mpm[k], element_mpm[owner == k]])
        if not np.isfinite(candidates).any():
            continue
        end = int(np.nanargmax(mpm[k])) if np.isfinite(mpm[k]).any() else 0
        out[name] = (float(np.nanmax(candidates)), float(mean[k, end]))
    return out


def most_probable_maximum(sigma: float, m0: float, m2: float, duration: float) -> float:
    """Most probable maximum of a zero-mean narrow-banded Gaussian process over ``duration``:
    ``sigma sqrt(2 ln N)``, ``N = duration / T_z``, ``T_z = 2 pi sqrt(m0 / m2)``: the mode of
    the largest of N Rayleigh-distributed maxima (Longuet-Higgins (1952), J. Mar. Res. 11,
    for large N); 0 when ``N <= 1``."""
    if not (m0 > 0.0 and m2 > 0.0):
        return 0.0
    cycles = duration / (2.0 * math.pi * math.sqrt(m0 / m2))
    return sigma * math.sqrt(2.0 * math.log(cycles)) if cycles > 1.0 else 0.0


def stochastic_extremes(result: Any, static_tension: np.ndarray,
                        duration: float | None = None) -> dict[str, tuple[float, float]]:
    """``{line: (T_static + MPM, T_static)}`` of a stochastic result, the element with the
    largest sum per line (:func:`most_probable_maximum` of each element's tension spectrum
    ``|H_T|^2 S`` over ``duration``, default the data file's 3 hours)."""
    duration = float(duration if duration is not None else factors()["storm_duration_s"])
    spectrum = np.abs(np.asarray(result.tension_transfer)) ** 2 \
        * np.asarray(result.wave_spectrum, dtype=float)[:, None]
    omega = np.asarray(result.omega, dtype=float)[:, None]
    m0 = spectrum.sum(axis=0) * result.d_omega
    m2 = (omega**2 * spectrum).sum(axis=0) * result.d_omega
    sigma = np.asarray(result.tension_std, dtype=float)
    top = np.array([float(static_tension[e]) + most_probable_maximum(
        float(sigma[e]), float(m0[e]), float(m2[e]), duration) for e in range(len(sigma))])
    mesh = result.mesh
    out = {}
    for name, elements in zip(mesh.line_names, mesh.line_elements, strict=True):
        e = int(elements[np.argmax(top[elements])])
        out[name] = (float(top[e]), float(static_tension[e]))
    return out
