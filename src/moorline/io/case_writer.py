"""Write a :class:`~moorline.model.System` as a YAML case file (the inverse of
:func:`moorline.io.load_case` for the fields a case file has); used by ``moorline convert``."""

from __future__ import annotations

import math
from dataclasses import asdict, fields, is_dataclass
from pathlib import Path
from typing import Any

import yaml

from ..model import Body, Line, LineType, Motion, Point, System


def system_to_dict(system: System) -> dict[str, Any]:
    """The case-file mapping of a system (values in the system's units)."""
    env = system.environment
    out: dict[str, Any] = {"name": system.name, "units": system.units}
    environment: dict[str, Any] = {"water_density": env.water_density,
                                   "gravity": env.gravity}
    if math.isfinite(env.depth):
        environment["depth"] = env.depth
    seabed = {k: v for k, v in asdict(env.seabed).items()
              if v is not None and k not in ("slope_deg", "slope_heading_deg", "bathymetry")}
    if env.seabed.slope_deg:
        seabed.update(slope=env.seabed.slope_deg, slope_heading=env.seabed.slope_heading_deg)
    if env.seabed.bathymetry is not None:
        grid = env.seabed.bathymetry
        seabed["bathymetry"] = {"x": list(grid.x), "y": list(grid.y),
                                "z": [list(row) for row in grid.z]}
    environment["seabed"] = seabed
    current = env.current
    environment["current"] = ({"z_levels": list(current.z_levels),
                               "speeds": list(current.speeds),
                               "headings": list(current.headings_deg)} if current.z_levels
                              else {"speed": current.speed, "heading": current.heading_deg})
    waves = env.waves
    environment["waves"] = ({"kind": "none"} if waves.kind == "none" else
                            {"kind": waves.kind, "height": waves.height,
                             "period": waves.period, "heading": waves.heading_deg,
                             "phase": waves.phase_deg, "stretching": waves.stretching})
    if waves.kind == "components" and waves.components is not None:
        c = waves.components
        environment["waves"] = {"kind": "components", "heading": waves.heading_deg,
                                "stretching": waves.stretching, "components": {
                                    "omegas": list(c.omegas), "amplitudes": list(c.amplitudes),
                                    "phases": list(c.phases_deg)}}
        if c.headings_deg:
            environment["waves"]["components"]["headings"] = list(c.headings_deg)
    if waves.kind == "random":
        environment["waves"].update(
            {"spectrum": waves.spectrum, "gamma": waves.gamma, "amplitudes": waves.amplitudes,
             "seed": waves.seed, "record_length": waves.record_length})
        environment["waves"].pop("phase")
        for key in ("n_frequencies", "omega_max"):
            if getattr(waves, key) is not None:
                environment["waves"][key] = getattr(waves, key)
    out["environment"] = environment
    out["line_types"] = {n: _line_type(lt) for n, lt in system.line_types.items()}
    if system.bodies:
        out["bodies"] = {n: _body(b) for n, b in system.bodies.items()}
    out["points"] = {n: _point(p) for n, p in system.points.items()}
    out["lines"] = {n: _line(line) for n, line in system.lines.items()}
    out["analyses"] = [_analysis(a) for a in system.analyses]
    out["output"] = {"every": system.output.every}
    if system.output.channels:
        out["output"]["channels"] = list(system.output.channels)
    if system.design is not None:
        out["design"] = {k: v for k, v in asdict(system.design).items() if v is not None}
    return out


def write_case(system: System, path: str | Path, header: str = "") -> Path:
    """Write ``system`` as a YAML case file, with an optional comment ``header``.

    The text is loaded back (:func:`moorline.io.load_case_text`) before it is written: a
    system that would not make a valid case (a negative drag coefficient or seabed
    stiffness from a MoorDyn deck) raises and nothing is written.

    Raises
    ------
    CaseError
        The case would not load (names ``path``, the key and the reason).
    ValueError
        A body holds a radiation table (a case file refers to its database instead).
    """
    from .case import load_case_text

    path = Path(path)
    text = yaml.safe_dump(_plain(system_to_dict(system)), sort_keys=False,
                          default_flow_style=None, width=100)
    comment = "".join(f"# {line}\n" for line in header.splitlines())
    load_case_text(comment + text, file=str(path))
    path.write_text(comment + text, encoding="utf-8")
    return path


def _line_type(lt: LineType) -> dict[str, Any]:
    data = asdict(lt)
    data.pop("name")
    for key in ("displaced_area", "MBL", "EA_dynamic", "catalog", "nominal_diameter", "EAd"):
        if data[key] is None:
            data.pop(key)
    table = data.pop("EA_table")
    if table is not None:  # the table is the law; EA (its largest tangent) follows from it
        data["EA"] = {"table": [list(row) for row in table]}
    if "EAd" not in data:
        data.pop("EAd_Lm")
    for key in ("EI", "BA_dynamic"):
        if not data[key]:
            data.pop(key)
    owc = data.pop("owc")
    if owc is None:
        for key in ("working_curve", "wc_k1", "wc_k2"):
            data.pop(key)
    else:
        data["owc"] = [list(row) for row in owc]
    return data


def _point(p: Point) -> dict[str, Any]:
    data: dict[str, Any] = {"kind": p.kind, "position": list(p.position)}
    for key in ("mass", "volume", "Cd", "drag_area", "Ca"):
        if getattr(p, key):
            data[key] = getattr(p, key)
    if any(p.force):
        data["force"] = list(p.force)
    if p.initial_position is not None:
        data["initial_position"] = list(p.initial_position)
    if p.body is not None:
        data["body"] = p.body
    for key in ("motion", "force_history"):
        if getattr(p, key) is not None:
            data[key] = _motion(getattr(p, key))
    return data


def _motion(m: Motion) -> dict[str, Any]:
    if m.kind == "harmonic":
        return {"kind": "harmonic", "amplitude": list(m.amplitude), "period": m.period,
                "phase": m.phase_deg, "ramp_time": m.ramp_time}
    return {"kind": "table", "times": list(m.times), "values": [list(v) for v in m.values],
            "ramp_time": m.ramp_time}


def _line(line: Line) -> dict[str, Any]:
    data = {"type": line.line_type, "length": line.length, "segments": line.segments,
            "end_a": line.end_a, "end_b": line.end_b}
    if line.initial_shape is not None:
        data["initial_shape"] = [list(r) for r in line.initial_shape]
    for key in ("clamp_a", "clamp_b", "syrope_ic"):
        if getattr(line, key) is not None:
            data[key] = list(getattr(line, key))
    if line.element != "straight":
        data["element"] = line.element
    return data


def _body(b: Body) -> dict[str, Any]:
    hs = {k: v for k, v in asdict(b.hydrostatics).items() if v not in (None, 0.0, ())}
    if "rods" in hs:
        hs["rods"] = [{"end_a": list(a), "end_b": list(e), "diameter": d}
                      for a, e, d in b.hydrostatics.rods]
    data: dict[str, Any] = {
        "kind": b.kind, "position": list(b.position),
        "rotation": [math.degrees(a) for a in b.rotation], "mass": b.mass,
        "center_of_gravity": list(b.center_of_gravity),
        "inertia": [b.inertia[i][i] for i in range(3)], "hydrostatics": hs,
        "force": list(b.force[:3]), "moment": list(b.force[3:])}
    products = [b.inertia[0][1], b.inertia[0][2], b.inertia[1][2]]
    if any(products):
        data["products_of_inertia"] = products
    if any(b.drag_area):
        data.update(drag_area=list(b.drag_area), Cd=b.Cd)
    for key in ("added_mass", "damping", "additional_damping"):
        if getattr(b, key) is not None:
            data[key] = [list(r) for r in getattr(b, key)]
    if b.force_history is not None:
        data["force_history"] = _motion(b.force_history)
    if b.motion is not None:
        data["motion"] = _motion(b.motion)
    if b.pin_body is not None:
        data["pin_body"] = b.pin_body
    if b.wave_loads:
        data["wave_loads"] = True
    if b.excitation is not None:
        data["excitation"] = {"omegas": list(b.excitation.omegas),
                              "amplitude": [list(r) for r in b.excitation.amplitude],
                              "phase": [list(r) for r in b.excitation.phase_deg]}
    if b.radiation is not None:  # a case file gives a table only through a database file
        raise ValueError(f"body {b.name!r} has a frequency-dependent radiation table (from a "
                         "hydrodynamic database): a case file refers to the database "
                         "(bodies.<name>.hydrodynamics.database) and cannot hold the table "
                         "inline")
    return data


def _analysis(a: Any) -> dict[str, Any]:
    return {f.name: getattr(a, f.name) for f in fields(a)}


def _plain(value: Any) -> Any:
    """Tuples to lists, numpy scalars to floats, dataclasses to dicts (YAML-safe)."""
    if is_dataclass(value):
        value = asdict(value)
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_plain(v) for v in value]
    if hasattr(value, "item"):
        return value.item()
    return value
