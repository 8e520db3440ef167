"""Range graphs of a dynamics run: element tension against arc length along each line.

As OrcaFlex draws them: the static tension, the mean, the minimum and the maximum over the
records of the envelope (:mod:`moorline.envelope`), and the band mean +- one standard
deviation shaded; one panel per line, arc length from end A (unstretched).
"""

from __future__ import annotations

import math

import numpy as np
import xarray as xr
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from .plot_style import force_scale, literal_text

__all__ = ["force_scale", "plot_tension_envelope"]

_LENGTH = {"SI": "m", "US": "ft"}


@literal_text
def plot_tension_envelope(dataset: xr.Dataset) -> Figure:
    """The tension range graph of every line of a dynamics dataset.

    Parameters
    ----------
    dataset
        A dynamics group (:meth:`moorline.results.DynamicResult.to_xarray` or read back from
        ``results.nc``) with ``tension_min``, ``tension_max``, ``tension_mean``,
        ``tension_std``, ``tension_static``, ``element_line`` and ``element_arc_length``.

    Returns
    -------
    matplotlib.figure.Figure
        One panel per line (titled with the line id): static (dashed), mean, min and max
        against arc length, mean +- std shaded; forces in N, kN or MN by magnitude.
    """
    units = str(dataset.attrs.get("units", "SI"))
    lines = [str(n) for n in dataset["line"].values]
    element_line = np.asarray(dataset["element_line"].values).astype(str)
    s = np.asarray(dataset["element_arc_length"].values, dtype=float)
    v = {k: np.asarray(dataset[f"tension_{k}"].values, dtype=float)
         for k in ("min", "max", "mean", "std", "static")}
    peak = float(np.nanmax(np.abs(np.concatenate([v["max"], v["static"]])), initial=0.0))
    factor, force_unit = force_scale(peak, units)
    cols = 1 if len(lines) <= 3 else 2
    rows = max(1, math.ceil(len(lines) / cols))
    fig = Figure(figsize=(6.5 * cols, 1.0 + 2.6 * rows), layout="constrained")
    FigureCanvasAgg(fig)
    axes = fig.subplots(rows, cols, squeeze=False).ravel()
    for ax in axes[len(lines):]:
        ax.set_visible(False)
    for ax, line in zip(axes, lines, strict=False):
        order = np.flatnonzero(element_line == line)
        order = order[np.argsort(s[order], kind="stable")]
        x = s[order]
        y = {k: a[order] / factor for k, a in v.items()}
        ax.fill_between(x, y["mean"] - y["std"], y["mean"] + y["std"], color="tab:blue",
                        alpha=0.25, linewidth=0, label="mean \u00b1 std")
        ax.plot(x, y["max"], color="tab:red", linewidth=1.2, label="max")
        ax.plot(x, y["mean"], color="tab:blue", linewidth=1.2, label="mean")
        ax.plot(x, y["min"], color="tab:green", linewidth=1.2, label="min")
        ax.plot(x, y["static"], color="black", linestyle="--", linewidth=1.0, label="static")
        ax.set_title(line, fontsize=10)
        ax.set_xlabel(f"arc length from end A [{_LENGTH.get(units, 'm')}]")
        ax.set_ylabel(f"tension [{force_unit}]")
        ax.grid(True, linewidth=0.3)
    if lines:  # one legend below the panels, where it hides no curve
        fig.legend(*axes[0].get_legend_handles_labels(), loc="outside lower center",
                   ncols=5, fontsize=8, frameon=False)
    start = float(dataset.attrs.get("envelope_start", 0.0))
    count = int(dataset.attrs.get("envelope_records", 0))
    case = str(dataset.attrs.get("case", "")).strip()
    title = f"tension envelope, {count} records from t = {start:g} s"
    fig.suptitle(f"{case}: {title}" if case else title[0].upper() + title[1:], fontsize=11)
    return fig
