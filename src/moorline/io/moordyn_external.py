"""MoorDyn-F's ``EXTERNAL LOADS`` section, for :func:`moorline.io.moordyn.read_moordyn_deck`.

Format (MoorDyn documentation ``docs/inputs.rst``, "External Loads"; read as OpenFAST
``modules/moordyn/src/MoorDyn.f90`` of OpenFAST 4.0 reads it): rows ``ID Object Fext Blin
Bquad CSys`` after two header rows. ``Object`` is ``Body<k>``, ``Point<k>`` (``P<k>``) or
``Rod<k>`` (``R<k>``); ``Fext`` a constant force ``Fx|Fy|Fz`` [N] (or ``0``), ``Blin`` linear
damping [N s/m] and ``Bquad`` quadratic damping [N s^2/m^2], one value for all axes or three
(two, transverse and axial, for rods); ``CSys`` ``G`` (earth axes) or ``L`` (body axes) for a
body, ``-`` otherwise. MoorDyn-F (``MoorDyn_Body.f90`` ``Body_DoRHS``, ``MoorDyn_Point.f90``
``Point_DoRHS``) adds to a body, at its reference point, ``Fext - Blin_i v_i - Bquad_i |v_i|
v_i`` per axis on the reference point's velocity (no moment), and the same to a point.

The mapping to moorline:

- a body: ``Fext`` is added to :attr:`moorline.model.Body.force` (at the body origin, which is
  MoorDyn's reference point), ``Blin`` to its ``additional_damping`` (translation), ``Bquad``
  to its ``drag_area`` as ``2 Bquad / rho`` with ``Cd = 1`` (moorline's body drag acts on the
  velocity relative to the water: the same in still water; a warning). ``L`` loads are turned
  to earth axes at the deck's pose and kept there (a warning when the body is rotated);
- a body that the reader turned into a free point (all its lines at its centre of gravity,
  :meth:`moorline.io.moordyn_rigid.RigidParts.collapse_point_bodies`), and a free point:
  ``Fext`` becomes the point's constant ``force``; ``Blin`` and ``Bquad`` are dropped with a
  warning (moorline's points have no linear damping and an isotropic ``|u| u`` drag): they
  act in dynamics only, the equilibrium is unchanged;
- a point on a body: ``Fext`` is added to the body's force with its moment about the body
  origin at the deck's pose; damping dropped (a warning);
- a fixed or coupled point: nothing moves it, its loads are dropped (a warning);
- a rod: a nonzero ``Fext`` cannot be represented (an error), damping is dropped (a warning).

A single ``Blin`` value: OpenFAST 4.0's MoorDyn.f90 reads it from the ``Bquad`` column (a
slip); here it is read from its own column, as documented.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from ..errors import CaseError
from ..model import Body, Point
from ..physics.rigid_body import rotation_matrix

Fail = Callable[[str, Any], CaseError]
_OBJECT = re.compile(r"^(BODY|POINT|P|ROD|R)(\d+)$")


@dataclass(frozen=True)
class ExternalLoad:
    """One ``EXTERNAL LOADS`` row: object kind (``body``, ``point``, ``rod``) and number,
    force [N], linear [N s/m] and quadratic [N s^2/m^2] damping per axis, body axes or not."""

    number: int
    kind: str
    target: int
    force: tuple[float, float, float]
    linear: tuple[float, ...]
    quadratic: tuple[float, ...]
    local: bool
    lineno: int


def _values(token: str, counts: tuple[int, ...], what: str, row: Any, fail: Fail
            ) -> list[float]:
    parts = token.split("|")
    try:
        values = [float(p) for p in parts]
    except ValueError:
        raise fail(f"external load: {what} must be numbers, got {token!r}", row) from None
    if len(values) not in counts or not all(np.isfinite(values)):
        raise fail(f"external load: {what} {token!r}: expected "
                   f"{' or '.join(map(str, counts))} finite '|'-separated numbers", row)
    return values


def parse_external_loads(rows: list[Any], fail: Fail) -> list[ExternalLoad]:
    """``EXTERNAL LOADS`` rows (module docstring); errors name the row and the column."""
    loads = []
    for number, row in enumerate(rows, start=1):
        tok = row.tokens
        if len(tok) != 6:
            raise fail("an external load needs 6 columns (ID Object Fext Blin Bquad CSys), "
                       f"found {len(tok)}", row)
        if tok[0] != str(number):
            raise fail(f"external load IDs must run 1, 2, 3, ...: expected {number}, got "
                       f"{tok[0]!r}", row)
        match = _OBJECT.match(tok[1].upper())
        if match is None:
            raise fail(f"external load {number}: Object {tok[1]!r} must be Body<k>, "
                       "Point<k> (P<k>) or Rod<k> (R<k>)", row)
        kind = {"BODY": "body", "POINT": "point", "P": "point"}.get(match.group(1), "rod")
        axes = (1, 2) if kind == "rod" else (1, 3)
        force = _values(tok[2], (1, 3), "Fext", row, fail)
        if len(force) == 1:
            if force[0] != 0:
                raise fail(f"external load {number}: Fext must be 0 or three numbers "
                           "Fx|Fy|Fz", row)
            force = [0.0] * 3
        linear = _values(tok[3], axes, "Blin", row, fail)
        quadratic = _values(tok[4], axes, "Bquad", row, fail)
        if min(linear + quadratic) < 0:
            raise fail(f"external load {number}: damping coefficients must not be negative",
                       row)
        csys = tok[5].upper()
        if kind == "body" and csys not in ("G", "L"):
            raise fail(f"external load {number}: CSys {tok[5]!r} of a body must be G (earth "
                       "axes) or L (body axes)", row)
        width = 3 if kind != "rod" else 2
        loads.append(ExternalLoad(
            number, kind, int(match.group(2)), (force[0], force[1], force[2]),
            tuple(linear * width if len(linear) == 1 else linear),
            tuple(quadratic * width if len(quadratic) == 1 else quadratic),
            kind == "body" and csys == "L", row.lineno))
    return loads


def apply_external_loads(loads: list[ExternalLoad], bodies: dict[str, Body],
                         points: dict[str, Point], body_ids: Mapping[int, str],
                         collapsed: Mapping[str, str], point_ids: Mapping[int, str],
                         rho: float, warn: Callable[[str], None]) -> list[str]:
    """Put ``loads`` on ``bodies`` and ``points`` (replaced in place, module docstring).

    Returns
    -------
    list of str
        What cannot be represented (the caller raises them at once).
    """
    errors = []
    for load in loads:
        label = f"external load {load.number} (line {load.lineno})"
        damped = any(load.linear) or any(load.quadratic)
        if load.kind == "rod":
            if any(load.force):
                errors.append(f"{label}: a force on rod {load.target} (moorline's rods are "
                              "bodies or end points; MoorDyn applies it at end A)")
            elif damped:
                warn(f"{label}: the damping of rod {load.target} is dropped")
            continue
        if load.kind == "body":
            name = body_ids.get(load.target)
            if name is None:
                errors.append(f"{label}: no body {load.target}")
                continue
            if name in collapsed:
                _on_point(load, label + f" on body {name}", collapsed[name], points, warn)
            else:
                bodies[name] = _on_body(load, label, bodies[name], rho, warn)
            continue
        name = point_ids.get(load.target)
        if name is None or name not in points:
            errors.append(f"{label}: no point {load.target}")
            continue
        point = points[name]
        if point.kind == "body" and point.body in bodies:
            body = bodies[point.body]
            R = rotation_matrix(np.asarray(body.rotation, dtype=float))
            arm = R @ np.asarray(point.position, dtype=float)
            moment = np.cross(arm, load.force)
            bodies[point.body] = replace(body, force=tuple(  # type: ignore[arg-type]
                float(a + b) for a, b in zip(body.force, (*load.force, *moment), strict=True)))
            if any(moment):
                warn(f"{label}: the force on point {name} is applied to body {point.body} "
                     "with its moment at the deck's pose")
            if damped:
                warn(f"{label}: the damping of point {name} on body {point.body} is dropped")
        else:
            _on_point(load, label, name, points, warn)
    return errors


def _on_point(load: ExternalLoad, label: str, name: str, points: dict[str, Point],
              warn: Callable[[str], None]) -> None:
    point = points[name]
    if point.kind != "free":
        warn(f"{label}: point {name} is {point.kind}: nothing moves it, its external load is "
             "dropped")
        return
    force = tuple(float(a + b) for a, b in zip(point.force, load.force, strict=True))
    points[name] = replace(point, force=force)  # type: ignore[arg-type]
    if any(load.linear) or any(load.quadratic):
        warn(f"{label}: the linear and quadratic damping on the free point {name} are dropped "
             "(moorline's points have no linear damping and an isotropic drag): dynamics "
             "only, the equilibrium is unchanged")


def _on_body(load: ExternalLoad, label: str, body: Body, rho: float,
             warn: Callable[[str], None]) -> Body:
    R = rotation_matrix(np.asarray(body.rotation, dtype=float)) if load.local else np.eye(3)
    if load.local and not np.allclose(R, np.eye(3)):
        warn(f"{label}: loads in body axes (CSys L) are taken in earth axes at the deck's "
             "pose (MoorDyn turns them with the body)")
    force = np.array(body.force, dtype=float)
    force[:3] += R @ np.asarray(load.force, dtype=float)
    damping = np.zeros((6, 6)) if body.additional_damping is None \
        else np.array(body.additional_damping, dtype=float)
    damping[:3, :3] += R @ np.diag(load.linear) @ R.T
    quadratic = np.diag(R @ np.diag(load.quadratic) @ R.T)
    drag = np.asarray(body.drag_area, dtype=float) * body.Cd + 2.0 * quadratic / rho
    if any(load.quadratic):
        warn(f"{label}: quadratic damping Bquad taken as body drag area 2 Bquad / rho (Cd 1) "
             "on the velocity relative to the water (MoorDyn: on the body's own velocity; "
             "the same in still water)")
    return replace(body, force=tuple(float(f) for f in force),  # type: ignore[arg-type]
                   additional_damping=tuple(tuple(float(x) for x in r) for r in damping)
                   if damping.any() else body.additional_damping,
                   drag_area=tuple(float(x) for x in drag), Cd=1.0)  # type: ignore[arg-type]
