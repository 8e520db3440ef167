"""Shared conventions of the plots: force units by magnitude, distinct curve styles, the
free surface and the seabed, and point labels placed so that none overprints another.
"""

from __future__ import annotations

import functools
import itertools
import math
from collections.abc import Callable, Sequence
from typing import Any

import matplotlib
import numpy as np
from matplotlib.axes import Axes
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.text import Annotation

__all__ = ["UNITS", "curve_styles", "draw_water_levels", "force_scale", "length_unit",
           "literal_text", "place_labels"]

UNITS = {"SI": {"force": "N", "length": "m"}, "US": {"force": "lbf", "length": "ft"}}
_FORCE_STEPS = {"SI": ((1.0e6, "MN"), (1.0e3, "kN"), (1.0, "N")),
                "US": ((1.0e3, "kip"), (1.0, "lbf"))}
_LINESTYLES = ("-", "--", "-.", ":")
_MARKERS = ("o", "s", "^", "v", "D", "x", "P", "*")
SEABED_COLOUR = "saddlebrown"
SURFACE_COLOUR = "tab:cyan"


def literal_text(figure_function: Callable[..., Any]) -> Callable[..., Any]:
    """Decorate a function that builds a figure: every text it creates is shown literally
    (names from case files such as ``$x$`` or ``$\\frac{`` are not matplotlib mathtext, which
    would fail to parse or change them), without touching the caller's matplotlib settings."""

    @functools.wraps(figure_function)
    def build(*args: Any, **kwargs: Any) -> Any:
        with matplotlib.rc_context({"text.parse_math": False}):
            return figure_function(*args, **kwargs)

    return build


def force_scale(peak: float, units: str = "SI") -> tuple[float, str]:
    """The divisor and unit to show forces up to ``peak`` with.

    MN from 1 MN, kN from 1 kN, else N (US: kip from 1000 lbf, else lbf); a non-finite peak
    gives the base unit.
    """
    steps = _FORCE_STEPS.get(units, _FORCE_STEPS["SI"])
    for factor, name in steps:
        if math.isfinite(peak) and abs(peak) >= factor:
            return factor, name
    return steps[-1]


def length_unit(units: str) -> str:
    """``m`` or ``ft`` for a case's unit system (``SI`` or ``US``)."""
    return UNITS.get(units, UNITS["SI"])["length"]


def curve_styles(count: int) -> list[dict[str, Any]]:
    """``count`` keyword sets for :meth:`Axes.plot` with distinct (colour, linestyle,
    marker), widths decreasing so that a curve drawn on top of an equal one leaves the
    first visible around it; markers are sparse (``markevery``) and hollow."""
    styles = []
    for k in range(count):
        styles.append({"color": f"C{k % 10}", "linestyle": _LINESTYLES[k % len(_LINESTYLES)],
                       "marker": _MARKERS[k % len(_MARKERS)], "linewidth": max(2.4 - 0.5 * k, 0.9),
                       "markersize": max(7.0 - 1.2 * k, 3.5), "markerfacecolor": "none",
                       "markevery": (0.02 * k, 0.1)})
    return styles


def draw_water_levels(ax: Axes, seabed: float | None, surface: float = 0.0) -> None:
    """Horizontal lines at the free surface (z = ``surface``) and at the seabed (when
    given), labelled for the legend."""
    ax.axhline(surface, color=SURFACE_COLOUR, linewidth=1.0, linestyle="--",
               label="free surface")
    if seabed is not None:
        ax.axhline(seabed, color=SEABED_COLOUR, linewidth=1.4, label="seabed")


def _offsets() -> list[tuple[float, float]]:
    """Candidate label offsets [points]: eight directions at growing distances."""
    directions = [(1, 1), (-1, 1), (1, -1), (-1, -1), (0, 1), (0, -1), (1, 0), (-1, 0)]
    return [(r * dx, r * dy) for r, (dx, dy) in itertools.product((6, 14, 24, 36, 50),
                                                                   directions)]


def place_labels(ax: Axes, labels: Sequence[tuple[str, float, float, dict[str, Any]]],
                 merge_pixels: float = 6.0,
                 avoid: np.ndarray | None = None) -> list[Annotation]:
    """Annotate points so that no two labels overlap.

    Labels whose anchors fall within ``merge_pixels`` of each other on screen (points that
    coincide in this view) are written once, their texts joined by commas. Each label then
    takes the first offset (eight directions, growing distances) at which its box overlaps
    no label already placed, stays inside the axes and covers none of the ``avoid`` points
    (the drawn lines; when no offset clears them, the first that meets the other two). The
    figure is drawn once first and its layout then frozen, so the boxes measured are those
    saved.

    Parameters
    ----------
    ax
        A 2-D axes with its data drawn and limits set.
    labels
        ``(text, x, y, text keywords)`` in data coordinates.
    merge_pixels
        Screen distance under which anchors are merged.
    avoid
        Data points ``(n, 2)`` no label should cover (points along the drawn lines).

    Returns
    -------
    list of Annotation
        The labels drawn.
    """
    fig = ax.get_figure()
    if not isinstance(fig.canvas, FigureCanvasAgg):
        FigureCanvasAgg(fig)
    fig.canvas.draw()
    fig.set_layout_engine("none")
    renderer = fig.canvas.get_renderer()
    merged: list[list[Any]] = []
    for text, x, y, style in labels:
        pixel = ax.transData.transform((x, y))
        for group in merged:
            if np.hypot(*(group[3] - pixel)) <= merge_pixels and group[4] == style:
                group[0].append(text)
                break
        else:
            merged.append([[text], x, y, pixel, style])
    frame = ax.get_window_extent(renderer)
    obstacles = (ax.transData.transform(np.asarray(avoid, dtype=float)) if avoid is not None
                 else np.zeros((0, 2)))
    placed: list[Annotation] = []
    boxes = []
    for texts, x, y, _, style in merged:
        fallback = None
        for dx, dy in _offsets():
            annotation = ax.annotate(", ".join(texts), (x, y), xytext=(dx, dy),
                                     textcoords="offset points",
                                     ha="left" if dx > 0 else "right" if dx < 0 else "center",
                                     va="bottom" if dy > 0 else "top" if dy < 0 else "center",
                                     annotation_clip=False, **style)
            annotation.set_parse_math(False)
            box = annotation.get_window_extent(renderer).expanded(1.05, 1.1)
            inside = (box.x0 >= frame.x0 and box.x1 <= frame.x1 and box.y0 >= frame.y0
                      and box.y1 <= frame.y1)
            if not inside or any(box.overlaps(other) for other in boxes):
                annotation.remove()
                continue
            covered = np.any((obstacles[:, 0] >= box.x0) & (obstacles[:, 0] <= box.x1)
                             & (obstacles[:, 1] >= box.y0) & (obstacles[:, 1] <= box.y1))
            if not covered:
                if fallback is not None:
                    fallback.remove()
                fallback = annotation
                break
            if fallback is None:
                fallback = annotation
            else:
                annotation.remove()
        if fallback is None:  # nowhere free: the first offset
            dx, dy = _offsets()[0]
            fallback = ax.annotate(", ".join(texts), (x, y), xytext=(dx, dy),
                                   textcoords="offset points", annotation_clip=False, **style)
            fallback.set_parse_math(False)
        boxes.append(fallback.get_window_extent(renderer))
        placed.append(fallback)
    return placed
