"""Seabed surfaces ``z = h(x, y)``: a plane (flat or inclined) or a bilinear grid of heights.

The grid is MoorDyn-C v2.7's 3-D seafloor (``source/Seafloor.cpp``, ``getDepthAt``): heights
``z[i, j]`` at ``(x[i], y[j])``, bilinear inside each cell, and beyond the grid the height at
its edge (the interpolation factor is clamped to 0 or 1, as ``Util/Interp.hpp``
``interp_factor`` does). Inside a cell ``h = a + b x + c y + e x y``: the Hessian is
``[[0, e], [e, 0]]`` and the third derivatives vanish, which the contact kernel
(:func:`moorline.physics.seabed.normal_distance`) relies on. Across cell edges the slope
jumps (the surface is only C0); a point on an interior grid line takes the cell above it
(the last cell on the grid's last line).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class SeabedSurface:
    """A seabed ``z = h(x, y)``.

    Attributes
    ----------
    z0, gradient
        Plane: height at the origin [length] and slope ``(dh/dx, dh/dy)`` (used when ``grid_z``
        is ``None``).
    grid_x, grid_y, grid_z
        Grid: strictly increasing coordinates (n_x,), (n_y,) and heights (n_x, n_y) [length].
    """

    z0: float = 0.0
    gradient: tuple[float, float] = (0.0, 0.0)
    grid_x: FloatArray | None = None
    grid_y: FloatArray | None = None
    grid_z: FloatArray | None = None

    @property
    def is_flat(self) -> bool:
        """True for a horizontal plane (the closed-form catenary's seabed)."""
        return self.grid_z is None and self.gradient == (0.0, 0.0)

    def height(self, x: FloatArray) -> FloatArray:
        """Seabed height under points ``x`` (n, 2 or 3) (n,)."""
        return self.evaluate(x)[0]

    def evaluate(self, x: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        """Height ``h`` (n,), gradient ``(h_x, h_y)`` (n, 2) and Hessian (n, 2, 2) under
        points ``x`` (n, 2 or 3)."""
        x = np.asarray(x, dtype=float)
        n = len(x)
        if self.grid_z is None:
            gx, gy = self.gradient
            h = self.z0 + gx * x[:, 0] + gy * x[:, 1] if (gx or gy) \
                else np.full(n, self.z0)
            return h, np.tile(np.array([gx, gy], dtype=float), (n, 1)), np.zeros((n, 2, 2))
        return _bilinear(self.grid_x, self.grid_y, self.grid_z, x[:, 0], x[:, 1])


def _cell(ticks: FloatArray, u: FloatArray) -> tuple[NDArray[np.int64], FloatArray,
                                                     FloatArray, NDArray[np.bool_]]:
    """Cell index, interpolation factor, cell width and inside-mask along one axis."""
    i = np.clip(np.searchsorted(ticks, u, side="right") - 1, 0, len(ticks) - 2)
    width = ticks[i + 1] - ticks[i]
    inside = (u >= ticks[0]) & (u <= ticks[-1])
    f = np.clip((u - ticks[i]) / width, 0.0, 1.0)
    return i, f, width, inside


def _bilinear(gx: FloatArray, gy: FloatArray, z: FloatArray, x: FloatArray, y: FloatArray
              ) -> tuple[FloatArray, FloatArray, FloatArray]:
    i, fx, wx, in_x = _cell(gx, x)
    j, fy, wy, in_y = _cell(gy, y)
    z00, z10, z01, z11 = z[i, j], z[i + 1, j], z[i, j + 1], z[i + 1, j + 1]
    h = (z00 * (1 - fx) * (1 - fy) + z10 * fx * (1 - fy) + z01 * (1 - fx) * fy
         + z11 * fx * fy)
    twist = z11 - z10 - z01 + z00
    dx = np.where(in_x, ((z10 - z00) + twist * fy) / wx, 0.0)
    dy = np.where(in_y, ((z01 - z00) + twist * fx) / wy, 0.0)
    hxy = np.where(in_x & in_y, twist / (wx * wy), 0.0)
    hess = np.zeros((len(x), 2, 2))
    hess[:, 0, 1] = hess[:, 1, 0] = hxy
    return h, np.stack([dx, dy], axis=1), hess


def plane(depth: float, slope_deg: float, heading_deg: float) -> SeabedSurface:
    """The plane through ``(0, 0, -depth)`` going down at ``slope_deg`` towards the horizontal
    direction ``heading_deg`` (0 = +x, 90 = +y)."""
    t = np.tan(np.radians(slope_deg))
    a = np.radians(heading_deg)
    gradient = (0.0, 0.0) if t == 0.0 else (float(-t * np.cos(a)), float(-t * np.sin(a)))
    return SeabedSurface(z0=-float(depth), gradient=gradient)


def grid(x: FloatArray, y: FloatArray, z: FloatArray) -> SeabedSurface:
    """A bilinear grid of seabed heights ``z[i, j]`` at ``(x[i], y[j])``."""
    return SeabedSurface(grid_x=np.asarray(x, dtype=float), grid_y=np.asarray(y, dtype=float),
                         grid_z=np.asarray(z, dtype=float))
