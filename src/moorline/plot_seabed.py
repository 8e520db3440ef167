"""The seabed in the plots: flat (one level), sloped or gridded (drawn under the lines).

A flat seabed is the horizontal line of :func:`moorline.plot_style.draw_water_levels`; a sloped
or gridded one (:mod:`moorline.seabed_attrs`) is drawn in the x-z views as its height under each
element (sampled along the element's plan footprint), and in the 3-D views as a surface.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from matplotlib.axes import Axes
from matplotlib.collections import LineCollection
from numpy.typing import NDArray

from .physics.bathymetry import SeabedSurface
from .plot_style import SEABED_COLOUR, draw_water_levels
from .seabed_attrs import seabed_from_attrs

#: points sampled along each element's footprint to draw a non-flat seabed under it
SAMPLES_PER_ELEMENT = 9


def seabed_surface(dataset: Any) -> SeabedSurface | None:
    """The seabed of a results dataset (``None`` without one)."""
    return seabed_from_attrs(dataset.attrs)


def seabed_under(dataset: Any, xyz: NDArray[np.float64]) -> NDArray[np.float64] | None:
    """Seabed height under points ``xyz`` (n, 3) (``None`` without a seabed)."""
    surface = seabed_surface(dataset)
    return None if surface is None else surface.height(np.asarray(xyz, dtype=float))


def draw_levels_xz(ax: Axes, dataset: Any, segments: NDArray[np.float64]) -> None:
    """The free surface and the seabed in an x-z view: a flat seabed as a level, a sloped or
    gridded one as its height under the elements ``segments`` (element, 2, xyz)."""
    surface = seabed_surface(dataset)
    if surface is None or surface.is_flat:
        draw_water_levels(ax, None if surface is None else surface.z0)
        return
    draw_water_levels(ax, None)
    s = np.linspace(0.0, 1.0, SAMPLES_PER_ELEMENT)[None, :, None]
    along = segments[:, :1, :] + s * (segments[:, 1:, :] - segments[:, :1, :])
    height = surface.height(along.reshape(-1, 3)).reshape(along.shape[:2])
    ax.add_collection(LineCollection(np.stack([along[..., 0], height], axis=-1),
                                     colors=SEABED_COLOUR, linewidths=1.4))
    ax.plot([], [], color=SEABED_COLOUR, linewidth=1.4, label="seabed (under the lines)")


def seabed_extent(dataset: Any, low: NDArray[np.float64], high: NDArray[np.float64]
                  ) -> NDArray[np.float64]:
    """Points (n, 3) spanning the seabed's height range over the plan box ``low``-``high``
    (x, y), to include in a 3-D view's limits (empty without a seabed)."""
    surface = seabed_surface(dataset)
    if surface is None:
        return np.zeros((0, 3))
    xx, yy, zz = _grid(surface, low, high)
    return np.column_stack([xx.ravel(), yy.ravel(), zz.ravel()])


def draw_seabed_3d(ax: Any, dataset: Any, low: NDArray[np.float64],
                   high: NDArray[np.float64]) -> None:
    """The seabed as a surface over the plan box ``low``-``high`` of a 3-D view."""
    surface = seabed_surface(dataset)
    if surface is not None:
        ax.plot_surface(*_grid(surface, low, high), color=SEABED_COLOUR, alpha=0.15)


def _grid(surface: SeabedSurface, low: NDArray[np.float64], high: NDArray[np.float64]
          ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    n = 2 if surface.is_flat else 25
    xx, yy = np.meshgrid(np.linspace(low[0], high[0], n), np.linspace(low[1], high[1], n))
    zz = surface.height(np.column_stack([xx.ravel(), yy.ravel()])).reshape(xx.shape)
    return xx, yy, zz
