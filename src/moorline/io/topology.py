"""Checks of a system's geometry that make its static problem well posed, shared by the case
reader and the MoorDyn reader: every group of connected lines is held by a fixed or
prescribed point (or a fixed body), and no line starts with its two ends at one place.

Without them statics meets a singular stiffness matrix (a group of free points can drift as
a rigid body) or a zero-length element (no direction), and fails with a message about the
solver instead of the input. The functions take the points, lines and bodies of either the
case-file specs or the model (the same attribute names: ``kind``, ``position``, ``body``,
``end_a``, ``end_b``, ``length``).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

__all__ = ["COINCIDENT_TOLERANCE", "geometry_problem"]

COINCIDENT_TOLERANCE = 1.0e-9
"""Two ends of a line closer than ``COINCIDENT_TOLERANCE * length`` coincide."""

_HOLDING = ("fixed", "prescribed")


def geometry_problem(points: Mapping[str, Any], lines: Mapping[str, Any],
                     bodies: Mapping[str, Any] | None = None) -> tuple[str, str] | None:
    """The first geometric defect of a system as ``(reason, key path)``, or ``None``.

    Parameters
    ----------
    points, lines, bodies
        By name; lines must name existing points and body points existing bodies.

    Returns
    -------
    tuple of str or None
        A line whose two (non-body) ends start at the same place (``lines.<name>``), or a
        group of lines with no fixed or prescribed point and no fixed body, naming its points
        (``points.<first point of the group>``).
    """
    bodies = bodies or {}
    for name, line in lines.items():
        a, b = points[line.end_a], points[line.end_b]
        if "body" in (a.kind, b.kind):
            continue  # body points are given in the body's frame
        if math.dist(a.position, b.position) <= COINCIDENT_TOLERANCE * line.length:
            return (f"both ends ({line.end_a!r}, {line.end_b!r}) are at the same place "
                    f"{tuple(a.position)}; a line needs ends apart", f"lines.{name}")
    parent: dict[str, str] = {}

    def root(node: str) -> str:
        parent.setdefault(node, node)
        while parent[node] != node:
            parent[node] = parent[parent[node]]
            node = parent[node]
        return node

    def node_of(point: str) -> str:
        p = points[point]
        return f"body {p.body}" if p.kind == "body" else f"point {point}"

    for line in lines.values():
        parent[root(node_of(line.end_a))] = root(node_of(line.end_b))
    held: set[str] = set()
    members: dict[str, list[str]] = {}
    for name, p in points.items():
        if p.kind == "body" and p.body not in bodies:
            continue
        group = root(node_of(name))
        members.setdefault(group, []).append(name)
        if p.kind in _HOLDING or (p.kind == "body" and _held(bodies, p.body)):
            held.add(group)
    for group, names in members.items():
        connected = any(node_of(n) in parent for n in names)
        if connected and group not in held:
            shown = ", ".join(repr(n) for n in names[:6]) + (", ..." if len(names) > 6 else "")
            return (f"the lines joining the points {shown} are held by no fixed or prescribed "
                    f"point and no fixed or pinned body: statics would be singular (they can drift "
                    f"as a rigid body)", f"points.{names[0]}")
    return None


def _held(bodies: Mapping[str, Any], name: str) -> bool:
    """A fixed body, or a pinned one whose pin is held (in space or on a fixed body)."""
    body = bodies[name]
    parent = getattr(body, "pin_body", None)
    return body.kind == "fixed" or (body.kind == "pinned" and (
        parent is None or parent not in bodies or bodies[parent].kind == "fixed"))
