"""The plots of an offset analysis: restoring force against offset for every heading (and
the yaw moment against yaw), and each line's fairlead and anchor tension against offset."""

from __future__ import annotations

import numpy as np
import xarray as xr
from matplotlib.figure import Figure

from .offset_result import along
from .plot import _single_figure, _writer
from .plot_style import literal_text

__all__ = ["force_scale", "plot_offset", "plot_offset_group"]

_STYLES = ("-", "--", "-.", ":")
_MARKERS = ("o", "s", "^", "v", "D", "x")


def force_scale(values: np.ndarray, unit: str) -> tuple[float, str]:
    """A divisor and unit label for forces of this magnitude (:func:`moorline.plot_style.
    force_scale`; ``unit`` the dataset's force unit, ``N`` or ``lbf``)."""
    from .plot_style import force_scale as scale

    largest = float(np.nanmax(np.abs(values), initial=0.0))
    return scale(largest, "US" if unit == "lbf" else "SI")


@literal_text
def plot_offset(dataset: xr.Dataset) -> Figure:
    """The offset curves of an ``offset`` group: a Figure with the restoring force along each
    heading against offset (the yaw moment against yaw when the group has a yaw sweep), and
    per heading the fairlead (solid) and anchor (dashed) tension of every line."""
    headings = [float(h) for h in dataset["heading"].values]
    offsets = np.asarray(dataset["offset"].values, dtype=float)
    length = str(dataset["offset"].attrs.get("units", ""))
    force_unit = str(dataset["fairlead_tension"].attrs.get("units", ""))
    yaw = "yaw" in dataset.coords
    n_panels = 1 + yaw + len(headings)
    columns = 2 if n_panels > 1 else 1
    rows = -(-n_panels // columns)
    fig = Figure(figsize=(6.0 * columns, 3.8 * rows), layout="constrained")
    axes = [fig.add_subplot(rows, columns, k + 1) for k in range(n_panels)]
    restoring = np.asarray(dataset["restoring_force"].values, dtype=float)
    curves = np.array([along(restoring[i], h) for i, h in enumerate(headings)])
    scale, label = force_scale(curves, force_unit)
    ax = axes[0]
    for i, heading in enumerate(headings):
        ax.plot(offsets, curves[i] / scale, linestyle=_STYLES[i % len(_STYLES)],
                marker=_MARKERS[i % len(_MARKERS)], markersize=3,
                label=f"heading {heading:g} deg")
    ax.axhline(0.0, color="0.6", linewidth=0.5)
    ax.axvline(0.0, color="0.6", linewidth=0.5)
    ax.set_xlabel(f"offset along the heading [{length}]")
    ax.set_ylabel(f"restoring force [{label}]")
    ax.set_title("mooring restoring force (lines on the group, along the heading)",
                 fontsize=9)
    ax.legend(fontsize=7)
    if yaw:
        _yaw_panel(axes[1], dataset, force_unit)
    tensions = np.concatenate([np.asarray(dataset[v].values, dtype=float).ravel()
                               for v in ("fairlead_tension", "anchor_tension")])
    scale, label = force_scale(tensions, force_unit)
    lines = [str(n) for n in dataset["line"].values]
    for i, heading in enumerate(headings):
        ax = axes[1 + yaw + i]
        for j, name in enumerate(lines):
            colour = f"C{j % 10}"
            width = max(2.6 - 0.6 * j, 0.8)  # lines drawn later thinner: a curve that
            ax.plot(offsets, dataset["fairlead_tension"].values[i, :, j] / scale,  # overlaps
                    color=colour, linewidth=width, marker=_MARKERS[j % len(_MARKERS)],
                    markersize=3 + 4.0 / (1 + j), markerfacecolor="none",  # stays visible
                    label=f"{name} fairlead")
            ax.plot(offsets, dataset["anchor_tension"].values[i, :, j] / scale, color=colour,
                    linewidth=width, linestyle="--", label=f"{name} anchor")
        ax.set_xlabel(f"offset along heading {heading:g} deg [{length}]")
        ax.set_ylabel(f"tension [{label}]")
        ax.set_title(f"line tensions, heading {heading:g} deg", fontsize=9)
        ax.legend(fontsize=6, ncol=2)
    for ax in axes:
        ax.grid(True, linewidth=0.3)
    what = (f"body {dataset.attrs.get('body')}" if dataset.attrs.get("body")
            else f"points {dataset.attrs.get('points', '')}")
    fig.suptitle(f"{dataset.attrs.get('case', '')}: offset analysis of {what}", fontsize=10)
    return fig


def _yaw_panel(ax, dataset: xr.Dataset, force_unit: str) -> None:
    """Yaw restoring moment against yaw angle."""
    angles = np.asarray(dataset["yaw"].values, dtype=float)
    moment = -np.asarray(dataset["yaw_restoring_force"].values, dtype=float)[:, 5]
    length = str(dataset["offset"].attrs.get("units", ""))
    scale, label = force_scale(moment, force_unit)
    ax.plot(angles, moment / scale, marker="o", markersize=3)
    ax.axhline(0.0, color="0.6", linewidth=0.5)
    ax.set_xlabel("yaw [deg]")
    ax.set_ylabel(f"restoring yaw moment [{label}*{length}]")
    ax.set_title("mooring restoring yaw moment", fontsize=9)


plot_offset_group = _single_figure(_writer(plot_offset, "offset"), "offset", "offset")
