"""Views of a configuration: x-z elevation, x-y plan and 3-D, elements coloured by tension.

Each ``figure_*`` function takes a dataset and returns a :class:`matplotlib.figure.Figure`
(Agg canvas, no window); :func:`moorline.plot.plot_configuration` saves them.
"""

from __future__ import annotations

import math

import numpy as np
import xarray as xr
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.cm import ScalarMappable
from matplotlib.collections import LineCollection
from matplotlib.colors import Normalize
from matplotlib.figure import Figure
from mpl_toolkits.mplot3d import proj3d
from mpl_toolkits.mplot3d.art3d import Line3DCollection
from numpy.typing import NDArray

from .plot_seabed import draw_levels_xz, draw_seabed_3d, seabed_extent
from .plot_style import (
    SURFACE_COLOUR,
    UNITS,
    force_scale,
    literal_text,
    place_labels,
)

__all__ = ["best_azimuth", "figure_configuration_3d", "figure_configuration_plan",
           "figure_configuration_xz"]

CMAP = "viridis"
MARKERS = {"fixed": ("s", "black"), "prescribed": ("^", "tab:red"), "free": ("o", "tab:blue")}
_POINT_LABEL = {"fontsize": 8}
_LINE_LABEL = {"fontsize": 7, "color": "dimgray", "style": "italic"}


def segments(dataset: xr.Dataset) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Element end coordinates ``(element, 2, xyz)`` and tensions (the last instant of a
    time history)."""
    position = np.asarray(dataset["position"].values, dtype=float)
    if position.ndim == 3:
        position = position[-1]
    connectivity = np.asarray(dataset["element_nodes"].values, dtype=int)
    tension = np.asarray(dataset["tension"].values, dtype=float)
    if tension.ndim == 2:
        tension = tension[-1]
    return position[connectivity], tension


def tension_norm(tension: NDArray[np.float64]) -> Normalize:
    """A colour scale over the finite tensions (padded when they are all equal)."""
    finite = tension[np.isfinite(tension)]
    low, high = (float(finite.min()), float(finite.max())) if finite.size else (0.0, 1.0)
    if high <= low:
        pad = max(abs(high) * 0.01, 1.0)
        low, high = low - pad, high + pad
    return Normalize(vmin=low, vmax=high)


def points(dataset: xr.Dataset) -> list[tuple[str, str, NDArray[np.float64]]]:
    """(name, kind, position) of each named point, when the dataset has them."""
    if "point_position" not in dataset:
        return []
    positions = np.asarray(dataset["point_position"].values, dtype=float)
    if positions.ndim == 3:
        positions = positions[-1]
    names = [str(n) for n in dataset["point"].values]
    kinds = ([str(k) for k in dataset["point_kind"].values] if "point_kind" in dataset.coords
             else [""] * len(names))
    return list(zip(names, kinds, positions, strict=True))


def units_of(dataset: xr.Dataset) -> dict[str, str]:
    """Force and length unit names of the dataset's unit system."""
    return UNITS.get(str(dataset.attrs.get("units", "SI")), UNITS["SI"])


def _title(dataset: xr.Dataset, view: str) -> str:
    case = str(dataset.attrs.get("case", "")).strip()
    return f"{case}: static configuration, {view}" if case else f"Static configuration, {view}"


def _line_owners(dataset: xr.Dataset) -> NDArray[np.str_] | None:
    if "element_line" not in dataset.coords:
        return None
    return np.array([str(v) for v in dataset["element_line"].values])


def _colourbar(fig: Figure, ax, norm: Normalize, dataset: xr.Dataset, **kwargs) -> None:
    """A tension colour bar in N, kN or MN by magnitude."""
    factor, unit = force_scale(max(abs(norm.vmin), abs(norm.vmax)),
                               str(dataset.attrs.get("units", "SI")))
    shown = Normalize(norm.vmin / factor, norm.vmax / factor)
    fig.colorbar(ScalarMappable(norm=shown, cmap=CMAP), ax=ax, label=f"tension [{unit}]",
                 **kwargs)


def _figure_2d(dataset: xr.Dataset, plane: tuple[int, int], view: str) -> Figure:
    """An elevation (x-z) or plan (x-y) view with labelled points and lines."""
    seg, tension = segments(dataset)
    norm = tension_norm(tension)
    units = units_of(dataset)
    fig = Figure(figsize=(9.0, 5.0 if plane[1] == 2 else 7.0), layout="constrained")
    FigureCanvasAgg(fig)
    ax = fig.add_subplot()
    collection = LineCollection(seg[:, :, list(plane)], cmap=CMAP, norm=norm, linewidths=2.0)
    collection.set_array(tension)
    ax.add_collection(collection)
    if plane[1] == 2:
        draw_levels_xz(ax, dataset, seg)
    labels = []
    for name, kind, xyz in points(dataset):
        marker, colour = MARKERS.get(kind, ("o", "tab:gray"))
        ax.plot(xyz[plane[0]], xyz[plane[1]], marker=marker, color=colour, markersize=6,
                linestyle="none")
        labels.append((name, xyz[plane[0]], xyz[plane[1]], _POINT_LABEL))
    owners = _line_owners(dataset)
    names = list(dict.fromkeys(owners)) if owners is not None else []
    if len(names) > 1:  # each line's id at its middle element
        for name in names:
            elements = np.flatnonzero(owners == name)
            mid = seg[elements[len(elements) // 2]].mean(axis=0)
            labels.append((name, mid[plane[0]], mid[plane[1]], _LINE_LABEL))
    ax.autoscale_view()  # the free surface (axhline) included
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel(f"x [{units['length']}]")
    ax.set_ylabel(f"{'xyz'[plane[1]]} [{units['length']}]")
    ax.set_title(_title(dataset, view))
    ax.grid(True, linewidth=0.3)
    if plane[1] == 2:
        ax.legend(loc="lower right", fontsize=8)
    _colourbar(fig, ax, norm, dataset)
    along = seg[:, 0, None, :] + np.linspace(0.0, 1.0, 6)[None, :, None] * (
        seg[:, 1, None, :] - seg[:, 0, None, :])
    place_labels(ax, labels, avoid=along[..., list(plane)].reshape(-1, 2))
    return fig


@literal_text
def figure_configuration_xz(dataset: xr.Dataset) -> Figure:
    """The x-z elevation of a statics dataset: elements coloured by tension (N, kN or MN),
    points marked by kind, the free surface (z = 0) and the seabed (attribute ``seabed_z``,
    when finite) drawn; coincident points and lines labelled once, no label over another."""
    return _figure_2d(dataset, (0, 2), "x-z elevation")


@literal_text
def figure_configuration_plan(dataset: xr.Dataset) -> Figure:
    """The x-y plan view of a statics dataset (as :func:`figure_configuration_xz`)."""
    return _figure_2d(dataset, (0, 1), "x-y plan")


def best_azimuth(seg: NDArray[np.float64], owners: NDArray[np.str_] | None,
                 elevation: float = 20.0, preferred: float = -60.0) -> float:
    """The camera azimuth [deg] at which the most foreshortened line is seen longest.

    A line's horizontal chord (first to last node) of direction ``theta`` is seen at
    azimuth ``a`` and elevation ``e`` with the factor ``sqrt(sin^2(theta - a) + sin^2 e
    cos^2(theta - a))``; the azimuth maximises the smallest factor over the lines (ties:
    the one nearest ``preferred``).
    """
    chords = []
    groups = ([np.flatnonzero(owners == n) for n in dict.fromkeys(owners)]
              if owners is not None else [np.arange(len(seg))])
    for elements in groups:
        if not len(elements):
            continue
        nodes = seg[elements].reshape(-1, 3)
        span = nodes[:, :2].max(axis=0) - nodes[:, :2].min(axis=0)
        chord = nodes[-1, :2] - nodes[0, :2]
        if np.hypot(*chord) > 1e-9 * max(float(np.hypot(*span)), 1.0):
            chords.append(math.atan2(chord[1], chord[0]))
    if not chords:
        return preferred
    candidates = np.arange(-180.0, 180.0, 1.0)
    a = np.radians(candidates)[:, None]
    theta = np.asarray(chords)[None, :]
    sin_e = math.sin(math.radians(elevation))
    factor = np.sqrt(np.sin(theta - a) ** 2 + (sin_e * np.cos(theta - a)) ** 2).min(axis=1)
    best = factor >= factor.max() - 1e-9
    distance = np.abs((candidates - preferred + 180.0) % 360.0 - 180.0)
    return float(candidates[best][np.argmin(distance[best])])


def bounds(xyz: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Padded axis limits around all finite points ``(n, 3)``; no axis shorter than a fifth
    of the longest, so that planar configurations still get a readable box."""
    xyz = xyz[np.all(np.isfinite(xyz), axis=1)]
    if not len(xyz):
        return np.full(3, -1.0), np.full(3, 1.0)
    low, high = xyz.min(axis=0), xyz.max(axis=0)
    longest = max(float(np.max(high - low)), 1e-9)
    half = np.maximum((high - low) / 2, 0.1 * longest) + 0.05 * longest
    centre = (high + low) / 2
    return centre - half, centre + half


@literal_text
def figure_configuration_3d(dataset: xr.Dataset, elevation: float = 20.0) -> Figure:
    """The 3-D view of a statics dataset: the limits enclose every node, point, the seabed
    and the free surface, the box is to scale (equal aspect) and the camera azimuth is
    :func:`best_azimuth` (no line seen end-on)."""
    seg, tension = segments(dataset)
    norm = tension_norm(tension)
    units = units_of(dataset)
    fig = Figure(figsize=(8.0, 6.5), layout="constrained")
    FigureCanvasAgg(fig)
    ax = fig.add_subplot(projection="3d")
    collection = Line3DCollection(seg, cmap=CMAP, norm=norm, linewidths=2.0)
    collection.set_array(tension)
    ax.add_collection3d(collection)
    named = points(dataset)
    for _, kind, xyz in named:
        marker, colour = MARKERS.get(kind, ("o", "tab:gray"))
        ax.scatter(*xyz, marker=marker, color=colour, s=25, depthshade=False)
    xyz = seg.reshape(-1, 3)
    if named:
        xyz = np.vstack([xyz, [p for _, _, p in named]])
    xyz = np.vstack([xyz, [[xyz[0, 0], xyz[0, 1], 0.0]]])
    low, high = bounds(xyz)
    low, high = bounds(np.vstack([xyz, seabed_extent(dataset, low, high)]))
    xx, yy = np.meshgrid([low[0], high[0]], [low[1], high[1]])
    draw_seabed_3d(ax, dataset, low, high)
    ax.plot_surface(xx, yy, np.zeros_like(xx), color=SURFACE_COLOUR, alpha=0.08)
    ax.set_xlim(low[0], high[0])
    ax.set_ylim(low[1], high[1])
    ax.set_zlim(low[2], high[2])
    ax.set_box_aspect(tuple(high - low))
    ax.view_init(elev=elevation, azim=best_azimuth(seg, _line_owners(dataset), elevation))
    for axis, setter in zip("xyz", (ax.set_xlabel, ax.set_ylabel, ax.set_zlabel), strict=True):
        setter(f"{axis} [{units['length']}]")
    ax.set_title(_title(dataset, "3D view to scale"))
    _colourbar(fig, ax, norm, dataset, shrink=0.6)
    if named:  # labels placed on the projected view, as in the 2-D views
        fig.canvas.draw()
        xs, ys, _ = proj3d.proj_transform(*np.array([p for _, _, p in named]).T, ax.get_proj())
        place_labels(ax, [(name, x, y, _POINT_LABEL)
                          for (name, _, _), x, y in zip(named, xs, ys, strict=True)])
    return fig
