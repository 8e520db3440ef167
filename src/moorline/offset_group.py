"""What an offset analysis moves: a body, or a rigid group of prescribed points.

One rule, used by the case loader (to refuse a bad ``analyses[i]`` with the key at fault) and
by the solver (:mod:`moorline.solvers.offset`) and ``moorline stiffness``: it reads only the
``kind`` and ``body`` of the points, so it works on case-file specs and on the model alike.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

__all__ = ["OffsetGroup", "OffsetGroupError", "resolve_group"]


class OffsetGroupError(ValueError):
    """A group that cannot be moved; ``key`` is the setting at fault (``body``, ``points``)."""

    def __init__(self, reason: str, key: str) -> None:
        super().__init__(reason)
        self.key = key


@dataclass(frozen=True)
class OffsetGroup:
    """The moved group.

    Attributes
    ----------
    body
        The body moved, or ``None`` for a group of prescribed points.
    points
        The points moved rigidly: the prescribed points of the group, or the points attached
        to the body.
    """

    body: str | None
    points: tuple[str, ...]


def resolve_group(points: Mapping[str, Any], bodies: Mapping[str, Any] | None,
                  body: str | None = None, names: Sequence[str] | None = ()) -> OffsetGroup:
    """The group of a body name or point names (both empty: every prescribed point, else the
    only body).

    Raises
    ------
    OffsetGroupError
        For an unknown body, a body without attached points, both a body and points, an
        unknown or non-prescribed point, or nothing to move.
    """
    bodies = bodies or {}
    if body is not None and names:
        raise OffsetGroupError("give a body or points, not both", "points")
    if body is None and not names:
        names = [n for n, p in points.items() if p.kind == "prescribed"]
        if not names and len(bodies) == 1:
            body = next(iter(bodies))
        elif not names:
            raise OffsetGroupError("nothing to move: the case has no prescribed point and "
                                   f"{len(bodies)} bodies; name a body or points", "points")
    if body is not None:
        if body not in bodies:
            known = ", ".join(bodies) or "none"
            raise OffsetGroupError(f"unknown body {body!r}; known bodies: {known}", "body")
        attached = tuple(n for n, p in points.items()
                         if p.kind == "body" and getattr(p, "body", None) == body)
        if not attached:
            raise OffsetGroupError(f"body {body!r} has no points: no line to offset", "body")
        return OffsetGroup(body, attached)
    for name in names:
        if name not in points:
            raise OffsetGroupError(f"unknown point {name!r}; known points: "
                                   f"{', '.join(points)}", "points")
        if points[name].kind != "prescribed":
            raise OffsetGroupError(f"point {name!r} is {points[name].kind}: only prescribed "
                                   "points are moved (a body's points: give the body)",
                                   "points")
    if len(set(names)) != len(names):
        raise OffsetGroupError("a point is listed twice", "points")
    return OffsetGroup(None, tuple(names))
