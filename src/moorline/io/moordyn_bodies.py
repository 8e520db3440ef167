"""Rigid bodies in a MoorDyn v2 deck (``BODIES`` section), for :func:`write_moordyn`.

MoorDyn v2 body (MoorDyn documentation, ``docs/inputs.rst``, "Bodies list"): ``ID Attachment
X0 Y0 Z0 r0 p0 y0 Mass CG I Volume CdA Ca``: mass at the centre of gravity ``CG`` (body
frame), inertia diagonal ``I`` about the centre of gravity, added mass ``Ca rho Volume`` in
translation only, drag ``CdA``. Points attached to body ``k`` have attachment ``Body<k>`` and
body-frame coordinates. MoorDyn-C 2.7 applies the body's buoyancy ``rho g Volume`` at its
centre of gravity, not at its reference point (the documentation does not say; found from its
net body moment, :func:`moorline.compare.moordyn_runner.run_moordyn`'s body state against a
hand moment balance: a pitched body with ``CG = (0, 0, -2)`` was 1.43e5 N m out of balance
with the buoyancy at the reference point, 4e3 N m with it at the centre of gravity).

A moorline body is written only when MoorDyn can express it: no initial rotation, a diagonal
inertia, no hydrostatic stiffness (buoyancy: a constant ``volume``), added
mass ``a I3`` in translation with ``a = Ca rho V`` and none in rotation, the centre of
buoyancy at the centre of gravity (MoorDyn's model, above), no radiation damping,
drag, external force, force history or wave loads. Anything else is an error listed by
:func:`body_problems`.
"""

from __future__ import annotations

import math

import numpy as np

from ..model import Body, System

_KINDS = {"free": "Free", "fixed": "Fixed"}


def _volume(body: Body) -> float:
    hs = body.hydrostatics
    return float(hs.volume) if hs.kind == "matrix" else 0.0


def _added_mass_ca(body: Body, rho: float) -> float:
    """MoorDyn's ``Ca`` of the body (0 without added mass); NaN when not expressible."""
    if body.added_mass is None:
        return 0.0
    A = np.asarray(body.added_mass, dtype=float)
    a = A[0, 0]
    expected = np.diag([a, a, a, 0.0, 0.0, 0.0])
    if not np.allclose(A, expected, rtol=1e-12, atol=1e-12 * max(abs(a), 1.0)):
        return math.nan
    volume = _volume(body)
    if a == 0.0:
        return 0.0
    return a / (rho * volume) if volume > 0 else math.nan


def body_problems(system: System) -> list[str]:
    """What of the system's bodies a MoorDyn deck cannot express (empty: all can)."""
    rho = system.environment.water_density
    problems = []
    for body in system.bodies.values():
        name = f"body {body.name}"
        hs = body.hydrostatics
        inertia = np.asarray(body.inertia, dtype=float)
        checks = [
            (body.kind not in _KINDS, f"kind {body.kind}"),
            (any(body.rotation), "an initial rotation"),
            (np.count_nonzero(inertia - np.diag(np.diag(inertia))) > 0,
             "off-diagonal inertia"),
            (hs.kind not in ("none", "matrix"), f"{hs.kind} hydrostatics"),
            (hs.kind == "matrix" and hs.stiffness is not None
             and bool(np.any(np.asarray(hs.stiffness, dtype=float))),
             "hydrostatic stiffness"),
            (hs.kind == "matrix" and hs.volume != 0.0
             and tuple(hs.center_of_buoyancy) != tuple(body.center_of_gravity),
             "a centre of buoyancy away from the centre of gravity (MoorDyn applies the "
             "body's buoyancy there)"),
            (math.isnan(_added_mass_ca(body, rho)),
             "added mass other than Ca rho V in translation"),
            (body.damping is not None and bool(np.any(np.asarray(body.damping))),
             "radiation damping"),
            (any(body.drag_area), "drag"),
            (any(body.force), "a constant force"),
            (body.force_history is not None, "a force history"),
            (body.wave_loads or body.excitation is not None, "wave loads"),
        ]
        problems += [f"{name}: {what}" for bad, what in checks if bad]
    return problems


def body_section(system: System) -> list[str]:
    """The ``BODIES`` header and rows (empty without bodies)."""
    if not system.bodies:
        return []
    rho = system.environment.water_density
    rows = ["ID  Attachment  X0  Y0  Z0  r0  p0  y0  Mass  CG*  I*  Volume  CdA*  Ca*",
            "(#)  (word)  (m)  (m)  (m)  (deg)  (deg)  (deg)  (kg)  (m)  (kg-m^2)  (m^3)  "
            "(m^2)  (-)"]
    for i, body in enumerate(system.bodies.values(), start=1):
        cg = "|".join(repr(float(c)) for c in body.center_of_gravity)
        inertia = "|".join(repr(float(v)) for v in np.diag(np.asarray(body.inertia, float)))
        values = [*map(float, body.position), 0.0, 0.0, 0.0, float(body.mass)]
        rows.append(f"{i:<4d} {_KINDS[body.kind]:<6s} " + " ".join(repr(v) for v in values)
                    + f" {cg} {inertia} {_volume(body)!r} 0.0 {float(_added_mass_ca(body, rho))!r}"
                    + f"   # {body.name}")
    return rows


def body_attachment(system: System, body: str) -> str:
    """MoorDyn attachment word of a point on ``body`` (``Body<k>``)."""
    return f"Body{list(system.bodies).index(body) + 1}"
