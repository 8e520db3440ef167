"""The result of an offset analysis (:func:`moorline.solvers.offset.solve_offset`) and its
``offset`` group of ``results.nc``.

Layout: the heading sweeps on dimensions ``(heading, offset, ...)``; the yaw sweep (when
asked for) on ``(yaw, ...)`` with the same variables prefixed ``yaw_``. Forces and moments are
those of the lines on the group about the reference point moved with it (body dofs
:data:`moorline.datasets.BODY_DOFS`); the stiffness is ``K[dof, dof_column]``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from .datasets import BODY_DOFS, build_plain, group_attrs
from .offset_group import OffsetGroup
from .plain_dataset import PlainDataset, PlainResult
from .results import _settle_status
from .status import Status

FloatArray = NDArray[np.float64]

__all__ = ["SWEEP_VARIABLES", "OffsetResult", "along"]

#: The per-state variables of a sweep: name -> (attribute of
#: :class:`moorline.solvers.offset.Sweep`, dimensions after the sweep's own).
SWEEP_VARIABLES: dict[str, tuple[str, tuple[str, ...]]] = {
    "displacement": ("displacement", ("dof",)),
    "restoring_force": ("restoring_force", ("dof",)),
    "fairlead_tension": ("fairlead_tension", ("line",)),
    "anchor_tension": ("anchor_tension", ("line",)),
    "seabed_length": ("seabed_length", ("line",)),
    "suspended_length": ("suspended_length", ("line",)),
    "touchdown_distance": ("touchdown_distance", ("line",)),
    "stiffness": ("stiffness", ("dof", "dof_column")),
    "converged": ("converged", ()),
    "iterations": ("iterations", ()),
}


@dataclass(frozen=True)
class OffsetResult(PlainResult):
    """Outcome of an offset analysis.

    Attributes
    ----------
    success, message, status
        Whether every offset was solved, and how it ended.
    group
        The body or points moved.
    reference
        The reference point at the undisplaced state [length] (3,).
    headings, offsets
        Headings [deg] and offsets [length] of the heading sweeps.
    sweeps
        One :class:`~moorline.solvers.offset.Sweep` per heading.
    yaw_angles, yaw
        Yaw angles [deg] and the yaw sweep (empty and ``None`` without one).
    line_names, fairlead_end
        Line ids, and the end of each line on the group.
    case, units, settings
        For output.
    """

    success: bool
    message: str
    group: OffsetGroup
    reference: FloatArray
    headings: tuple[float, ...]
    offsets: FloatArray
    sweeps: list[Any]
    yaw_angles: FloatArray
    yaw: Any
    line_names: tuple[str, ...]
    fairlead_end: tuple[str, ...]
    case: str = ""
    units: str = "SI"
    settings: Any = None
    status: str = ""
    counters: dict = field(default_factory=dict)

    def __post_init__(self) -> None:
        _settle_status(self, Status.COMPLETED)

    def heading_index(self, heading: float) -> int:
        """Index of a heading [deg]."""
        return self.headings.index(float(heading))

    def stiffness_at_rest(self) -> FloatArray:
        """The 6x6 stiffness at the undisplaced state (the middle offset of the first
        heading)."""
        return self.sweeps[0].stiffness[len(self.offsets) // 2]

    def to_plain(self) -> PlainDataset:
        """Group ``offset`` (see the module docstring)."""
        data: dict[str, Any] = {"reference": (("xyz",), np.asarray(self.reference, float))}
        for name, (attr, dims) in SWEEP_VARIABLES.items():
            data[name] = (("heading", "offset", *dims),
                          _as_stored(np.stack([getattr(s, attr) for s in self.sweeps])))
            if self.yaw is not None:
                data[f"yaw_{name}"] = (("yaw", *dims), _as_stored(getattr(self.yaw, attr)))
        coords: dict[str, Any] = {
            "heading": list(self.headings), "offset": np.asarray(self.offsets, float),
            "dof": list(BODY_DOFS), "dof_column": list(BODY_DOFS), "xyz": ["x", "y", "z"],
            "line": list(self.line_names), "fairlead_end": (("line",), list(self.fairlead_end))}
        if self.yaw is not None:
            coords["yaw"] = np.asarray(self.yaw_angles, float)
        attrs = group_attrs("offset", case=self.case, units=self.units, success=self.success,
                            status=self.status, message=self.message, settings=self.settings,
                            extra={"body": self.group.body or "",
                                   "points": ",".join(self.group.points)})
        return build_plain("offset", data, coords, attrs)


def _as_stored(values: Any) -> Any:
    """Booleans as 0/1 integers (NetCDF has no boolean)."""
    values = np.asarray(values)
    return values.astype(np.int8) if values.dtype == bool else values


def along(force: FloatArray, heading: float) -> FloatArray:
    """The restoring force along a heading: ``-(F_x cos h + F_y sin h)`` of force rows
    ``(..., 6)`` (positive when the lines pull the group back towards where it came from)."""
    h = np.radians(heading)
    return -(force[..., 0] * np.cos(h) + force[..., 1] * np.sin(h))
