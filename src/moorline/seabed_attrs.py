"""The seabed as results-file attributes, and back.

Every analysis group carries ``seabed_z`` (the flat seabed's height, or the reference height of
a sloped or gridded one: a plane's height at the origin); a sloped seabed adds
``seabed_gradient`` (``dh/dx, dh/dy`` [-]) and a gridded one ``seabed_grid_x``,
``seabed_grid_y`` [length] and ``seabed_grid_z`` [length] (the heights, row-major, shape
``(len(seabed_grid_x), len(seabed_grid_y))``) so that the plots draw the seabed the contact
acted on (:class:`moorline.physics.bathymetry.SeabedSurface`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from .physics.bathymetry import SeabedSurface


def seabed_attrs(mesh: Any) -> dict[str, Any]:
    """The attributes describing ``mesh``'s seabed (``seabed_z`` always)."""
    out: dict[str, Any] = {"seabed_z": float(mesh.seabed_z)}
    surface = getattr(mesh, "bathymetry", None)
    if surface is None or surface.is_flat:
        return out
    if surface.grid_z is None:
        out["seabed_gradient"] = np.asarray(surface.gradient, dtype=float)
    else:
        out["seabed_grid_x"] = np.asarray(surface.grid_x, dtype=float)
        out["seabed_grid_y"] = np.asarray(surface.grid_y, dtype=float)
        out["seabed_grid_z"] = np.asarray(surface.grid_z, dtype=float).ravel()
    return out


def seabed_from_attrs(attrs: Mapping[str, Any]) -> SeabedSurface | None:
    """The seabed :func:`seabed_attrs` describes (``None`` without a finite seabed)."""
    value = attrs.get("seabed_z")
    if value is None:
        return None
    z0 = float(np.asarray(value, dtype=float).ravel()[0])
    if not math.isfinite(z0):
        return None
    if "seabed_grid_z" in attrs:
        gx = np.atleast_1d(np.asarray(attrs["seabed_grid_x"], dtype=float))
        gy = np.atleast_1d(np.asarray(attrs["seabed_grid_y"], dtype=float))
        gz = np.asarray(attrs["seabed_grid_z"], dtype=float).reshape(len(gx), len(gy))
        return SeabedSurface(z0=z0, grid_x=gx, grid_y=gy, grid_z=gz)
    if "seabed_gradient" in attrs:
        g = np.asarray(attrs["seabed_gradient"], dtype=float).ravel()
        return SeabedSurface(z0=z0, gradient=(float(g[0]), float(g[1])))
    return SeabedSurface(z0=z0)
