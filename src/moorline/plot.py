"""Plots of results (matplotlib, Agg canvas; never opens a window).

Figures are built with the object-oriented API (:class:`matplotlib.figure.Figure` on a
:class:`~matplotlib.backends.backend_agg.FigureCanvasAgg`), so importing this module changes no
global matplotlib state and works without a display. Every ``figure_*`` function takes a
dataset and returns the Figure (for notebooks); the ``plot_*`` functions also save it, and the
``plot_*_group(dataset, directory, prefix)`` functions write the files of ``moorline run``.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import xarray as xr
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.cm import ScalarMappable
from matplotlib.collections import LineCollection
from matplotlib.figure import Figure
from matplotlib.text import Text
from mpl_toolkits.mplot3d.art3d import Line3DCollection
from numpy.typing import NDArray

from .datasets import BODY_DOFS
from .plot_configuration import (
    CMAP,
    best_azimuth,
    bounds,
    figure_configuration_3d,
    figure_configuration_plan,
    figure_configuration_xz,
    tension_norm,
    units_of,
)
from .plot_envelope import plot_tension_envelope
from .plot_seabed import draw_levels_xz, seabed_extent, seabed_under
from .plot_style import curve_styles, force_scale, literal_text

__all__ = ["figure_configuration_3d", "figure_configuration_plan", "figure_configuration_xz",
           "figure_mode_shapes", "figure_motion_history", "figure_tension_history",
           "plot_configuration", "plot_mode_shapes", "plot_motion_history",
           "plot_tension_history"]

_MOVING = ("free", "prescribed")


def plot_configuration(dataset: xr.Dataset, path_xz: str | Path, path_3d: str | Path,
                       path_plan: str | Path | None = None) -> list[Figure]:
    """Save the x-z elevation, the 3-D view and (with ``path_plan``) the x-y plan of a
    static configuration (:mod:`moorline.plot_configuration`).

    Parameters
    ----------
    dataset
        A statics dataset (:meth:`moorline.results.StaticResult.to_xarray` or the ``statics``
        group of a ``results.nc`` read back) with variables ``position(node, xyz)``,
        ``element_nodes(element, pair)``, ``tension(element)``, optionally
        ``point_position(point, xyz)`` and the coordinates ``element_line`` and
        ``point_kind``; attributes ``units`` (``SI`` or ``US``), ``case`` and
        optionally ``seabed_z`` (drawn when finite) and the attributes of a sloped or
        gridded seabed (:mod:`moorline.seabed_attrs`).
    path_xz, path_3d, path_plan
        PNG files to write (parent directories are created).

    Returns
    -------
    list of Figure
        The figures saved, in the order of the paths.
    """
    figures = [figure_configuration_xz(dataset), figure_configuration_3d(dataset)]
    paths = [path_xz, path_3d]
    if path_plan is not None:
        figures.append(figure_configuration_plan(dataset))
        paths.append(path_plan)
    for fig, path in zip(figures, paths, strict=True):
        _save(fig, Path(path))
    return figures


def _save(fig: Figure, path: Path) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    if not isinstance(fig.canvas, FigureCanvasAgg):
        FigureCanvasAgg(fig)
    for text in fig.findobj(Text):  # names are printed literally ("$x$" is not mathtext)
        text.set_parse_math(False)
    fig.savefig(path, dpi=150)


def _writer(figure, name: str):
    """``plot_<name>(dataset, path, *args, **kwargs) -> Figure``: ``figure`` saved to
    ``path`` (PNG; parent directories are created)."""

    def write(dataset: xr.Dataset, path: str | Path, *args, **kwargs) -> Figure:
        fig = figure(dataset, *args, **kwargs)
        _save(fig, Path(path))
        return fig

    write.__name__ = write.__qualname__ = f"plot_{name}"
    write.__doc__ = (f"Save :func:`figure_{name}` of ``dataset`` to ``path`` (PNG; parent "
                     "directories are created) and return the Figure.")
    return write


# ----------------------------------------------------------------------------- time histories


def _history_title(dataset: xr.Dataset, what: str) -> str:
    case = str(dataset.attrs.get("case", "")).strip()
    return f"{case}: {what}" if case else what[:1].upper() + what[1:]


def _line_mbl(dataset: xr.Dataset) -> NDArray[np.float64]:
    """The ``line_MBL`` attribute (one per line, NaN where unknown), all NaN without it."""
    n = dataset.sizes.get("line", 0)
    value = dataset.attrs.get("line_MBL")
    mbl = np.full(n, np.nan) if value is None else np.atleast_1d(np.asarray(value, dtype=float))
    return mbl if mbl.shape == (n,) else np.full(n, np.nan)


@literal_text
def figure_tension_history(dataset: xr.Dataset) -> Figure:
    """The end-B (fairlead) tension of every line against time.

    Parameters
    ----------
    dataset
        A dynamics dataset (:meth:`moorline.results.DynamicResult.to_xarray` or the
        ``dynamics`` group of a ``results.nc`` read back) with ``time`` and
        ``end_force(time, line, end, xyz)`` (or ``end_tension(time, line, end)``); attributes
        ``units``, ``case`` and optionally ``line_MBL`` (drawn as horizontal lines where
        finite).

    Returns
    -------
    Figure
        Forces in N, kN or MN (lbf or kip) by magnitude; each line its own (colour,
        linestyle, marker) so that equal histories stay distinguishable.
    """
    units = str(dataset.attrs.get("units", "SI"))
    time = np.asarray(dataset["time"].values, dtype=float)
    if "end_tension" in dataset:
        tension = np.asarray(dataset["end_tension"].values, dtype=float)[:, :, 1]
    else:
        tension = np.linalg.norm(np.asarray(dataset["end_force"].values, dtype=float),
                                 axis=-1)[:, :, 1]
    lines = [str(n) for n in dataset["line"].values]
    mbl = _line_mbl(dataset)
    peak = float(np.nanmax(np.abs(np.concatenate([tension.ravel(), mbl])), initial=0.0))
    factor, unit = force_scale(peak, units)
    fig = Figure(figsize=(9.0, 4.5), layout="constrained")
    ax = fig.add_subplot()
    styles = curve_styles(len(lines))
    for k, line in enumerate(lines):
        ax.plot(time, tension[:, k] / factor, label=line, **styles[k])
    finite = sorted({float(v) for v in mbl[np.isfinite(mbl)]})
    for value in finite:
        owners = [n for n, v in zip(lines, mbl, strict=True) if v == value]
        colour = "tab:red" if len(finite) == 1 else styles[lines.index(owners[0])]["color"]
        ax.axhline(value / factor, color=colour, linestyle=(0, (8, 3)), linewidth=1.4,
                   label=f"MBL {', '.join(owners)} ({value / factor:.4g} {unit})")
    ax.ticklabel_format(axis="y", style="plain", useOffset=False)
    ax.set_xlabel("time [s]")
    ax.set_ylabel(f"end B tension [{unit}]")
    ax.set_title(_history_title(dataset, "line tension at end B"))
    ax.grid(True, linewidth=0.3)
    if lines:
        fig.legend(loc="outside right upper", fontsize=8)
    return fig


plot_tension_history = _writer(figure_tension_history, "tension_history")


@literal_text
def figure_motion_history(dataset: xr.Dataset) -> Figure:
    """The displacement from the first record of every free and prescribed point against
    time, one panel per moving component (x, y, z), each scaled to its own range; a
    component in which no point moves is not drawn, nor a point that does not move in it.

    Parameters
    ----------
    dataset
        A dynamics dataset with ``time``, ``position(time, node, xyz)``, ``point_node(point)``
        and the coordinate ``point_kind`` (without it every point is drawn).
    """
    length = units_of(dataset)["length"]
    time = np.asarray(dataset["time"].values, dtype=float)
    position = np.asarray(dataset["position"].values, dtype=float)
    names = [str(n) for n in dataset["point"].values]
    kinds = ([str(k) for k in dataset["point_kind"].values] if "point_kind" in dataset.coords
             else [_MOVING[0]] * len(names))
    nodes = (np.asarray(dataset["point_node"].values, dtype=int) if "point_node" in dataset
             else np.arange(len(names)))
    chosen = [(n, k, node) for n, k, node in zip(names, kinds, nodes, strict=True)
              if k in _MOVING]
    moved = (np.stack([position[:, node] - position[:1, node] for _, _, node in chosen], axis=1)
             if chosen and len(time) else np.zeros((len(time), 0, 3)))
    size = max(float(np.ptp(position[0], axis=0).max(initial=0.0)), 1.0) if len(time) else 1.0
    moving = np.ptp(moved, axis=0) > 1e-9 * size if len(time) else np.zeros((0, 3), bool)
    components = [c for c in range(3) if moving[:, c].any()]
    fig = Figure(figsize=(9.0, 2.2 + 1.9 * max(len(components), 1)), layout="constrained")
    axes = np.atleast_1d(fig.subplots(max(len(components), 1), 1, sharex=True, squeeze=False)
                         .ravel())
    styles = curve_styles(len(chosen))
    for ax, c in zip(axes, components, strict=False):
        for j, (name, kind, _) in enumerate(chosen):
            if moving[j, c]:
                ax.plot(time, moved[:, j, c], label=f"{name} ({kind})", **styles[j])
        ax.set_ylabel(f"{'xyz'[c]} - {'xyz'[c]}(0) [{length}]")
        ax.grid(True, linewidth=0.3)
    axes[-1].set_xlabel("time [s]")
    axes[0].set_title(_history_title(dataset, "displacement of the moving points from t = 0"))
    if components:
        handles = {}
        for ax in axes:
            for h, label in zip(*ax.get_legend_handles_labels(), strict=True):
                handles.setdefault(label, h)
        fig.legend(list(handles.values()), list(handles), loc="outside right upper",
                   fontsize=8)
    else:
        axes[0].text(0.5, 0.5, "no free or prescribed point moves",
                     transform=axes[0].transAxes, ha="center", va="center")
    return fig


plot_motion_history = _writer(figure_motion_history, "motion_history")


# ----------------------------------------------------------------------------- modes


def display_scale(position: NDArray[np.float64], shape: NDArray[np.float64], target: float,
                  seabed: float | NDArray[np.float64] | None, tolerance: float = 0.0
                  ) -> tuple[float, bool]:
    """The signed factor a mode shape is drawn with, and whether the drawing must still be
    clipped at the seabed.

    A mode's sign and amplitude are arbitrary: the sign is the one that lets the nodes move
    farthest before one goes ``tolerance`` below the seabed (nodes resting on it count from
    it), and the factor ``target`` is reduced to keep every node above that, unless that
    would shrink it under a quarter (then the drawing is clipped at the seabed instead).
    ``seabed``: its height, or its height under each node (n,) for a sloped or gridded one.
    """
    if seabed is None:
        return target, False
    height = np.maximum(position[:, 2] - seabed, 0.0) + tolerance
    best, room = 1.0, -1.0
    for sign in (1.0, -1.0):
        down = sign * shape[:, 2] < 0
        limit = float(np.min(height[down] / -(sign * shape[down, 2]), initial=np.inf))
        if limit > room:
            best, room = sign, limit
    if room >= target:
        return best * target, False
    if room >= 0.25 * target:
        return best * room, False
    return best * target, True


@literal_text
def figure_mode_shapes(dataset: xr.Dataset, max_modes: int = 6,
                       amplitude: float = 0.08) -> Figure:
    """The static shape and the shapes of the first modes, one panel per mode.

    Modes dominated by x or z motion are drawn in the x-z elevation (with the free surface
    and the seabed), modes dominated by y in the x-y plan view. A mode shape has no
    absolute amplitude (the figure says so): each is drawn with its largest node
    displacement ``amplitude`` times the size of the system, reduced (or, when it would
    vanish, clipped) so that no node is drawn below the seabed (:func:`display_scale`, with
    0.2 % of the system's size, under a line width, as tolerance; the drawing is then
    clipped at the seabed).

    Parameters
    ----------
    dataset
        A modal dataset (:meth:`moorline.results.ModalResult.to_xarray` or the ``modal`` group
        of a ``results.nc`` read back): ``position(node, xyz)``, ``element_nodes``,
        ``mode_shape(mode, node, xyz)``, ``omega``, ``period``, ``dominant``; attributes
        ``units``, ``case`` and optionally ``seabed_z``.
    max_modes
        Number of modes drawn (the lowest).
    amplitude
        Drawn amplitude relative to the largest extent of the static shape.
    """
    units = units_of(dataset)
    position = np.asarray(dataset["position"].values, dtype=float)
    connectivity = np.asarray(dataset["element_nodes"].values, dtype=int)
    shapes = np.asarray(dataset["mode_shape"].values, dtype=float)[:max_modes]
    seabed = seabed_under(dataset, position)
    n = len(shapes)
    columns = 1 if n <= 1 else 2
    rows = max(1, math.ceil(n / columns))
    fig = Figure(figsize=(6.0 * columns, 3.4 * rows), layout="constrained")
    axes = np.atleast_1d(fig.subplots(rows, columns, squeeze=False).ravel())
    size = max(float(np.ptp(position, axis=0).max(initial=0.0)), 1e-9)
    for k, ax in enumerate(axes):
        if k >= n:
            ax.set_axis_off()
            continue
        dominant = str(dataset["dominant"].values[k])
        plane = [0, 1] if dominant == "y" else [0, 2]
        largest = max(float(np.abs(shapes[k]).max(initial=0.0)), np.finfo(float).tiny)
        scale, clip = display_scale(position, shapes[k], amplitude * size / largest,
                                    seabed if plane[1] == 2 else None, 2e-3 * size)
        moved = position + shapes[k] * scale
        if seabed is not None and plane[1] == 2:
            moved[:, 2] = np.maximum(moved[:, 2], seabed)
        ax.add_collection(LineCollection(position[connectivity][:, :, plane], colors="0.6",
                                         linewidths=1.0, linestyles="dashed"))
        ax.add_collection(LineCollection(moved[connectivity][:, :, plane], colors="tab:blue",
                                         linewidths=1.6, gid="mode shape"))
        if plane[1] == 2:
            draw_levels_xz(ax, dataset, position[connectivity])
        ax.autoscale_view()
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_xlabel(f"x [{units['length']}]")
        ax.set_ylabel(f"{'xyz'[plane[1]]} [{units['length']}]")
        omega = float(dataset["omega"].values[k])
        period = float(dataset["period"].values[k])
        view = "plan" if dominant == "y" else "elevation"
        note = ", clipped at the seabed" if clip else ""
        ax.set_title(f"mode {k + 1}: {omega:.4g} rad/s, T = {period:.4g} s, {dominant} ({view})"
                     f"\namplitude arbitrary{note}", fontsize=9)
        ax.grid(True, linewidth=0.3)
    case = str(dataset.attrs.get("case", "")).strip()
    what = "mode shapes, amplitude arbitrary (scaled for display; dashed: static shape)"
    fig.suptitle(f"{case}: {what}" if case else what[:1].upper() + what[1:])
    return fig


plot_mode_shapes = _writer(figure_mode_shapes, "mode_shapes")


# ----------------------------------------------------------------------------- parameter studies


@literal_text
def figure_sweep_trends(dataset: xr.Dataset) -> Figure:
    """Plot every output of a parameter study against the varied parameter.

    One panel per output (rows) and varied parameter (columns). One-at-a-time studies draw
    each series (the cases where that parameter was varied) against its parameter; ``grid``
    studies draw the outputs against the first varied parameter, one line per combination of
    the others. Failed cases (NaN) leave gaps.

    Parameters
    ----------
    dataset
        The table of :func:`moorline.sweep.run_study`: dimension ``case``, coordinate
        ``series`` and one per parameter, one variable per output (attribute ``units``);
        attributes ``study``, ``variations`` and ``quantities`` (comma-separated names).
    """
    outputs = [q for q in str(dataset.attrs.get("quantities", "")).split(",") if q]
    varied = [v for v in str(dataset.attrs.get("variations", "")).split(",") if v]
    series = [str(s) for s in dataset["series"].values]
    grid = "grid" in series
    columns = varied[:1] if grid else (varied or ["case"])
    rows = max(1, len(outputs))
    fig = Figure(figsize=(4.2 * len(columns), 2.6 * rows), layout="constrained")
    axes = fig.subplots(rows, len(columns), squeeze=False)
    for i, name in enumerate(outputs):
        values = np.asarray(dataset[name].values, dtype=float)
        unit = str(dataset[name].attrs.get("units", ""))
        for j, parameter in enumerate(columns):
            ax = axes[i, j]
            x = (np.asarray(dataset[parameter].values, dtype=float) if parameter in dataset.coords
                 else np.arange(len(values), dtype=float))
            for label, mask in _sweep_groups(dataset, parameter, varied, series, grid):
                order = np.argsort(x[mask])
                ax.plot(x[mask][order], values[mask][order], marker="o", markersize=4,
                        linewidth=1.2, label=label)
            ax.set_ylabel(f"{name} [{unit}]" if unit else name, fontsize=9)
            ax.grid(True, linewidth=0.3)
            if i == rows - 1:
                ax.set_xlabel(parameter)
            if grid and i == 0 and len(varied) > 1:
                ax.legend(fontsize=7)
    study = str(dataset.attrs.get("study", "")).strip()
    fig.suptitle(f"{study}: steady-state outputs" if study else "Parameter study")
    return fig


def _sweep_groups(dataset: xr.Dataset, parameter: str, varied: list[str], series: list[str],
                  grid: bool) -> list[tuple[str, NDArray[np.bool_]]]:
    """Cases drawn as one line: the series of ``parameter``, or (grid) each combination of
    the other varied parameters."""
    n = len(series)
    if not grid:
        mask = np.array([s == parameter for s in series]) if parameter in series else np.ones(
            n, dtype=bool)
        return [(parameter, mask)]
    others = [v for v in varied if v != parameter]
    if not others:
        return [(parameter, np.ones(n, dtype=bool))]
    keys = [tuple(dataset[o].values[k].item() for o in others) for k in range(n)]
    groups = []
    for key in dict.fromkeys(keys):
        label = ", ".join(f"{o} = {v:.4g}" if isinstance(v, float) else f"{o} = {v}"
                          for o, v in zip(others, key, strict=True))
        groups.append((label, np.array([k == key for k in keys])))
    return groups




@literal_text
def figure_body_motion(dataset: xr.Dataset) -> Figure:
    """Six panels per run: body surge, sway, heave (positions of the origin) and roll, pitch,
    yaw (the rotation vector, degrees) vs time, one line per body, from a dynamics dataset
    with ``body_pose(time, body, dof)``."""
    pose = dataset["body_pose"].values
    time = dataset["time"].values
    names = [str(b) for b in dataset["body"].values]
    fig = Figure(figsize=(11, 7), constrained_layout=True)
    labels = ("surge", "sway", "heave", "roll", "pitch", "yaw")
    for k in range(6):
        ax = fig.add_subplot(2, 3, k + 1)
        scale = 1.0 if k < 3 else 180.0 / np.pi
        for b, name in enumerate(names):
            ax.plot(time, pose[:, b, k] * scale, label=name)
        unit = "deg" if k >= 3 else ("ft" if dataset.attrs.get("units") == "US" else "m")
        ax.set_title(f"{labels[k]} [{unit}]")
        ax.set_xlabel("time [s]")
        ax.grid(True, lw=0.4)
    fig.axes[0].legend(fontsize=8)
    fig.suptitle(_history_title(dataset, "body motion"))
    return fig


@literal_text
def animate_run(dataset: xr.Dataset, path: str | Path, frames: int = 120,
                view: str = "xz") -> Figure:
    """An animated GIF of a dynamics dataset (Pillow writer; no screen needed).

    The lines in the x-z (or x-y) plane at up to ``frames`` output times, elements coloured
    by tension (one colour scale over the run, colour bar in N, kN or MN), the free surface
    and the seabed drawn in the x-z view, axes in the case's units.

    Returns
    -------
    Figure
        The animation's figure (its last frame).
    """
    from matplotlib.animation import FuncAnimation, PillowWriter

    pos = np.asarray(dataset["position"].values, dtype=float)
    time = np.asarray(dataset["time"].values, dtype=float)
    el = np.asarray(dataset["element_nodes"].values, dtype=int)
    tension = np.asarray(dataset["tension"].values, dtype=float)
    length = units_of(dataset)["length"]
    a, b = (0, 2) if view == "xz" else (0, 1)
    picks = np.unique(np.linspace(0, len(time) - 1, min(frames, len(time))).astype(int))
    fig = Figure(figsize=(9.0, 4.5), layout="constrained")
    FigureCanvasAgg(fig)
    ax = fig.add_subplot(1, 1, 1)
    lo, hi = pos[..., [a, b]].min(axis=(0, 1)), pos[..., [a, b]].max(axis=(0, 1))
    seabed = seabed_under(dataset, pos.reshape(-1, 3))
    if b == 2:
        draw_levels_xz(ax, dataset, pos[0][el])
        lo[1] = min(lo[1], float(seabed.min()) if seabed is not None else lo[1])
        hi[1] = max(hi[1], 0.0)
    pad = 0.05 * float(np.max(hi - lo))
    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_aspect("equal")
    ax.set_xlabel(f"{'xyz'[a]} [{length}]")
    ax.set_ylabel(f"{'xyz'[b]} [{length}]")
    norm = tension_norm(tension[picks].ravel())
    factor, unit = force_scale(max(abs(norm.vmin), abs(norm.vmax)),
                               str(dataset.attrs.get("units", "SI")))
    collection = LineCollection(pos[picks[0]][el][:, :, [a, b]], cmap=CMAP, norm=norm,
                                linewidths=2.0)
    collection.set_array(tension[picks[0]])
    ax.add_collection(collection)
    fig.colorbar(ScalarMappable(norm=type(norm)(norm.vmin / factor, norm.vmax / factor),
                                cmap=CMAP), ax=ax, shrink=0.8, label=f"tension [{unit}]")
    if b == 2:  # below the axes, where it hides no line
        fig.legend(loc="outside lower center", ncols=2, fontsize=8, frameon=False)
    title = ax.set_title("")

    def draw(i: int):
        collection.set_segments(pos[picks[i]][el][:, :, [a, b]])
        collection.set_array(tension[picks[i]])
        title.set_text(f"{dataset.attrs.get('case', '')}  t = {time[picks[i]]:.2f} s")
        return [collection, title]

    animation = FuncAnimation(fig, draw, frames=len(picks), blit=False)
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    animation.save(str(path), writer=PillowWriter(fps=15))
    return fig


@literal_text
def figure_snapshots(dataset: xr.Dataset, times: list[float] | None = None) -> Figure:
    """The system in 3D at a few times of a dynamics dataset (default: four times spread over
    the run), one panel each: elements coloured by tension (one scale), the same to-scale box
    holding every node of the run and the seabed, the camera of
    :func:`moorline.plot_configuration.best_azimuth`."""
    time = np.asarray(dataset["time"].values, dtype=float)
    pos = np.asarray(dataset["position"].values, dtype=float)
    el = np.asarray(dataset["element_nodes"].values, dtype=int)
    tension = np.asarray(dataset["tension"].values, dtype=float)
    picks = times if times is not None else list(np.linspace(time[0], time[-1], 4))
    fig = Figure(figsize=(12, 3.8), layout="constrained")
    extent = pos.reshape(-1, 3)
    low, high = bounds(extent)
    low, high = bounds(np.vstack([extent, seabed_extent(dataset, low, high)]))
    owners = (np.asarray(dataset["element_line"].values).astype(str)
              if "element_line" in dataset.coords else None)
    azimuth = best_azimuth(pos[0][el], owners)
    norm = tension_norm(tension.ravel())
    length = units_of(dataset)["length"]
    axes = []
    for k, t in enumerate(picks):
        i = int(np.argmin(np.abs(time - t)))
        ax = fig.add_subplot(1, len(picks), k + 1, projection="3d")
        collection = Line3DCollection(pos[i][el], cmap=CMAP, norm=norm, linewidths=1.2)
        collection.set_array(tension[i])
        ax.add_collection3d(collection)
        ax.set_xlim(low[0], high[0])
        ax.set_ylim(low[1], high[1])
        ax.set_zlim(low[2], high[2])
        ax.set_box_aspect(tuple(high - low))
        ax.view_init(elev=20.0, azim=azimuth)
        ax.set_xlabel(f"x [{length}]", fontsize=7)
        ax.set_ylabel(f"y [{length}]", fontsize=7)
        ax.set_zlabel(f"z [{length}]", fontsize=7)
        ax.set_title(f"t = {time[i]:.2f} s", fontsize=9)
        axes.append(ax)
    factor, unit = force_scale(max(abs(norm.vmin), abs(norm.vmax)),
                               str(dataset.attrs.get("units", "SI")))
    fig.colorbar(ScalarMappable(norm=type(norm)(norm.vmin / factor, norm.vmax / factor),
                                cmap=CMAP), ax=axes, shrink=0.7, label=f"tension [{unit}]")
    fig.suptitle(_history_title(dataset, "snapshots"))
    return fig


# ----------------------------------------------------------------------------- strumming


@literal_text
def figure_strumming(dataset: xr.Dataset, max_elements: int = 4,
                   max_modes: int = 6) -> Figure:
    """Plot the lift coefficient of a few elements and the modal amplitudes against time.

    Parameters
    ----------
    dataset
        A strumming dataset (:meth:`moorline.results.StrummingResult.to_xarray`):
        ``lift_coefficient(time, element)``, ``modal_amplitude(time, mode)`` (modes numbered
        from 1), optional ``omega(mode)`` and the attribute ``CL0`` (drawn as +-C_L0).
    max_elements
        Elements drawn: those with the largest peak ``|C_L|``.
    max_modes
        Modes drawn: those with the largest peak amplitude.
    """
    time = np.asarray(dataset["time"].values, dtype=float)
    cl = np.asarray(dataset["lift_coefficient"].values, dtype=float)
    z = np.asarray(dataset["modal_amplitude"].values, dtype=float)
    omega = (np.asarray(dataset["omega"].values, dtype=float) if "omega" in dataset
             else np.full(z.shape[1], np.nan))
    fig = Figure(figsize=(9.0, 6.0), layout="constrained")
    axes = fig.subplots(2, 1, sharex=True)
    for e in np.argsort(-np.abs(cl).max(axis=0))[:max_elements]:
        axes[0].plot(time, cl[:, e], linewidth=0.8, label=f"element {int(e) + 1}")
    if "CL0" in dataset.attrs:
        cl0 = float(dataset.attrs["CL0"])
        for sign in (1.0, -1.0):
            axes[0].axhline(sign * cl0, color="k", linestyle="--", linewidth=0.8,
                            label="stationary C_L0" if sign > 0 else None)
    axes[0].set_ylabel("lift coefficient C_L")
    numbers = (dataset["mode"].values if "mode" in dataset.coords
               else np.arange(1, z.shape[1] + 1))
    for m in np.sort(np.argsort(-np.abs(z).max(axis=0))[:max_modes]):
        axes[1].plot(time, z[:, m], linewidth=0.8,
                     label=f"mode {int(numbers[m])} ({omega[m]:.3g} rad/s)")
    axes[1].set_ylabel("modal amplitude z_n")
    axes[1].set_xlabel("time [s]")
    for ax in axes:
        ax.grid(True, linewidth=0.3)
        ax.legend(fontsize=7, loc="upper right")
    axes[0].set_title(_history_title(dataset, "strumming: lift coefficient and modal "
                                              "amplitudes"))
    return fig


@literal_text
def figure_stochastic(dataset: xr.Dataset, max_items: int = 3) -> Figure:
    """Plot the wave spectrum with the response spectra of the most responsive node
    displacements and element tensions, and their time series over one record.

    Parameters
    ----------
    dataset
        A stochastic dataset (:meth:`moorline.results.StochasticResult.to_xarray`).
    max_items
        Nodes and elements drawn: those with the largest standard deviation.
    """
    omega = np.asarray(dataset["omega"].values, dtype=float)
    time = np.asarray(dataset["time"].values, dtype=float)
    u_std = np.asarray(dataset["displacement_std"].values, dtype=float)
    t_std = np.asarray(dataset["tension_std"].values, dtype=float)
    u_spec = np.asarray(dataset["displacement_spectrum"].values, dtype=float)
    t_spec = np.asarray(dataset["tension_spectrum"].values, dtype=float)
    fig = Figure(figsize=(10.0, 8.0), layout="constrained")
    axes = fig.subplots(3, 2)
    axes[0, 0].plot(omega, dataset["wave_spectrum"].values, "k", linewidth=1.0)
    axes[0, 0].set_ylabel("wave spectrum S(w)")
    axes[0, 1].plot(time, dataset["elevation"].values, "k", linewidth=0.6)
    axes[0, 1].set_ylabel("elevation at x = 0")
    flat = np.argsort(-u_std, axis=None)[:max_items]
    for node, c in zip(*np.unravel_index(flat, u_std.shape), strict=True):
        label = f"node {int(node) + 1} {'xyz'[int(c)]} (std {u_std[node, c]:.3g})"
        axes[1, 0].plot(omega, u_spec[:, node, c], linewidth=0.9, label=label)
        axes[1, 1].plot(time, dataset["displacement"].values[:, node, c], linewidth=0.6,
                        label=label)
    axes[1, 0].set_ylabel("displacement spectrum")
    axes[1, 1].set_ylabel("displacement")
    for e in np.argsort(-t_std)[:max_items]:
        label = f"element {int(e) + 1} (std {t_std[e]:.3g})"
        axes[2, 0].plot(omega, t_spec[:, e], linewidth=0.9, label=label)
        axes[2, 1].plot(time, dataset["tension"].values[:, e], linewidth=0.6, label=label)
    axes[2, 0].set_ylabel("tension spectrum")
    axes[2, 1].set_ylabel("tension")
    axes[2, 0].set_xlabel("w [rad/s]")
    axes[2, 1].set_xlabel("time [s]")
    for ax in axes.flat:
        ax.grid(True, linewidth=0.3)
    for ax in axes[1:].flat:
        ax.legend(fontsize=7, loc="upper right")
    fig.suptitle(f"stochastic response ({dataset.attrs.get('method', '')}, "
                 f"{dataset.attrs.get('iterations', '?')} linearization iterations)")
    return fig


@literal_text
def figure_harmonic(dataset: xr.Dataset, snapshots: int = 8) -> Figure:
    """Plot the periodic response: snapshots of the lines over one period (x-z, the dynamic
    part magnified to be seen) and the tension range along the elements.

    Parameters
    ----------
    dataset
        A harmonic dataset (:meth:`moorline.results.HarmonicResult.to_xarray`).
    snapshots
        Instants drawn, equally spaced over the period.
    """
    pos = np.asarray(dataset["position"].values, dtype=float)
    static = np.asarray(dataset["static_position"].values, dtype=float)
    factor, unit = force_scale(float(np.nanmax(np.abs(dataset["tension"].values), initial=0.0)),
                               str(dataset.attrs.get("units", "SI")))
    tension = np.asarray(dataset["tension"].values, dtype=float) / factor
    dyn = pos - pos.mean(axis=0)[None]
    span = float(np.ptp(static[:, [0, 2]], axis=0).max()) or 1.0
    amp = float(np.abs(dyn).max()) or 1.0
    scale = max(1.0, 0.05 * span / amp)
    bodies = "body_pose" in dataset
    fig = Figure(figsize=(15.0 if bodies else 10.0, 5.0), layout="constrained")
    ax, ax_t, *ax_b = fig.subplots(1, 3 if bodies else 2)
    order = np.argsort(static[:, 0] + 1e-9 * static[:, 2])
    mean = pos.mean(axis=0)
    for j in np.linspace(0, len(pos), snapshots, endpoint=False).astype(int):
        shape = mean + scale * dyn[j]
        ax.plot(shape[order, 0], shape[order, 2], linewidth=0.8,
                label=f"t/T = {j / len(pos):.2f}")
    ax.plot(static[order, 0], static[order, 2], "k--", linewidth=0.8, label="static")
    length = units_of(dataset)["length"]
    ax.set_xlabel(f"x [{length}]")
    ax.set_ylabel(f"z [{length}]")
    ax.set_title(f"one period (dynamic part x {scale:.3g})")
    ax.legend(fontsize=7)
    elements = np.arange(tension.shape[1]) + 1
    ax_t.fill_between(elements, tension.min(axis=0), tension.max(axis=0), alpha=0.3,
                      label="range over the period")
    ax_t.plot(elements, tension.mean(axis=0), "k", linewidth=0.8, label="mean")
    ax_t.set_xlabel("element")
    ax_t.set_ylabel(f"tension [{unit}]")
    ax_t.legend(fontsize=7)
    if bodies:
        _harmonic_bodies(ax_b[0], dataset, length)
    for a in (ax, ax_t, *ax_b):
        a.grid(True, linewidth=0.3)
    fig.suptitle(f"harmonic balance: period {float(dataset.attrs.get('period', 0)):.4g}, "
                 f"{dataset.attrs.get('harmonics', '?')} harmonics")
    return fig


def _harmonic_bodies(ax, dataset: xr.Dataset, length: str) -> None:
    """The bodies' motion about their mean over one period: translations (solid, left axis)
    and rotations in degrees (dashed, right axis)."""
    pose = np.asarray(dataset["body_pose"].values, dtype=float)  # (time, body, dof)
    phase = np.arange(len(pose)) / max(len(pose), 1)
    turn = ax.twinx()
    for b, name in enumerate(dataset["body"].values):
        motion = pose[:, b] - pose[:, b].mean(axis=0)
        for k, dof in enumerate(BODY_DOFS):
            if np.ptp(motion[:, k]) <= 1e-12 * (1.0 + np.abs(pose[:, b, k]).max()):
                continue
            if k < 3:
                ax.plot(phase, motion[:, k], linewidth=0.9, label=f"{name} {dof}")
            else:
                turn.plot(phase, np.degrees(motion[:, k]), "--", linewidth=0.9,
                          label=f"{name} {dof}")
    ax.set_xlabel("t / T")
    ax.set_ylabel(f"translation about the mean [{length}]")
    turn.set_ylabel("rotation about the mean [deg]")
    ax.set_title("bodies over one period")
    lines = ax.get_legend_handles_labels()
    more = turn.get_legend_handles_labels()
    if lines[0] or more[0]:
        ax.legend(lines[0] + more[0], lines[1] + more[1], fontsize=7)


plot_sweep_trends = _writer(figure_sweep_trends, "sweep_trends")
plot_body_motion = _writer(figure_body_motion, "body_motion")
plot_snapshots = _writer(figure_snapshots, "snapshots")
plot_strumming = _writer(figure_strumming, "strumming")
plot_stochastic = _writer(figure_stochastic, "stochastic")
plot_harmonic = _writer(figure_harmonic, "harmonic")
__all__ += ["figure_body_motion", "figure_harmonic", "figure_snapshots", "figure_stochastic",
            "figure_strumming", "figure_sweep_trends", "plot_body_motion", "plot_harmonic",
            "plot_snapshots", "plot_stochastic", "plot_strumming", "plot_sweep_trends"]


# ----------------------------------------------------------------------------- per analysis group
# One function per analysis kind (the ``plot`` of :data:`moorline.analyses.KINDS`):
# ``(dataset, directory, prefix) -> files written``, used by ``moorline run`` and
# ``moorline plot`` alike; ``prefix`` (the group name and ``_`` when a kind repeats) starts
# every file name.


def plot_statics_group(dataset: xr.Dataset, directory: str | Path,
                       prefix: str = "") -> list[Path]:
    """``configuration_xz.png``, ``configuration_3d.png`` and ``configuration_plan.png``
    of a statics group.

    Raises
    ------
    ValueError
        When the dataset lacks ``position``, ``element_nodes`` or ``tension``.
    """
    missing = [v for v in ("position", "element_nodes", "tension") if v not in dataset.variables]
    if missing:
        raise ValueError(f"not a statics result (missing {', '.join(missing)})")
    files = [Path(directory) / f"{prefix}configuration_xz.png",
             Path(directory) / f"{prefix}configuration_3d.png",
             Path(directory) / f"{prefix}configuration_plan.png"]
    plot_configuration(dataset, *files)
    return files


def plot_dynamics_group(dataset: xr.Dataset, directory: str | Path,
                        prefix: str = "") -> list[Path]:
    """``tension_history.png``, ``motion_history.png``, ``tension_envelope.png`` (with the
    envelope variables: :func:`moorline.plot_envelope.plot_tension_envelope`) and, with
    bodies, ``body_motion.png`` and ``snapshots_3d.png`` of a dynamics group (nothing without
    records)."""
    if not dataset.sizes.get("time", 0):
        return []
    directory = Path(directory)
    files = [directory / f"{prefix}tension_history.png",
             directory / f"{prefix}motion_history.png"]
    plot_tension_history(dataset, files[0])
    plot_motion_history(dataset, files[1])
    if "tension_max" in dataset.variables:
        files.append(directory / f"{prefix}tension_envelope.png")
        _save(plot_tension_envelope(dataset), files[-1])
    if "body_pose" in dataset.variables:
        files += [directory / f"{prefix}body_motion.png", directory / f"{prefix}snapshots_3d.png"]
        plot_body_motion(dataset, files[-2])
        plot_snapshots(dataset, files[-1])
    return files


def _single_figure(plotter, name: str, kind: str):
    """A group plotter drawing one figure ``{prefix}{name}.png`` with ``plotter``."""

    def plot_group(dataset: xr.Dataset, directory: str | Path, prefix: str = "") -> list[Path]:
        path = Path(directory) / f"{prefix}{name}.png"
        plotter(dataset, path)
        return [path]

    plot_group.__name__ = plot_group.__qualname__ = f"plot_{kind}_group"
    plot_group.__doc__ = f"``{name}.png`` of the {kind} group."
    return plot_group


plot_modal_group = _single_figure(plot_mode_shapes, "mode_shapes", "modal")
plot_strumming_group = _single_figure(plot_strumming, "strumming", "strumming")
plot_stochastic_group = _single_figure(plot_stochastic, "stochastic", "stochastic")
plot_harmonic_group = _single_figure(plot_harmonic, "harmonic", "harmonic")


__all__ += ["plot_dynamics_group", "plot_harmonic_group", "plot_modal_group",
            "plot_statics_group", "plot_stochastic_group", "plot_strumming_group"]


def _elements_by_line(dataset: xr.Dataset) -> list[tuple[str, np.ndarray]]:
    """(line, mask of its elements) for every line, in the order of ``element_line``."""
    lines = np.asarray([str(v) for v in dataset["element_line"].values])
    return [(name, lines == name) for name in dict.fromkeys(lines)]


@literal_text
def figure_fatigue(dataset: xr.Dataset) -> Figure:
    """The fatigue life [years] along every line (per element) for each method."""
    fig = Figure(figsize=(8.0, 4.5), layout="constrained")
    ax = fig.add_subplot()
    for k, method in enumerate(dataset["fatigue_method"].values):
        life = dataset["element_life"].values[k]
        for name, mask in _elements_by_line(dataset):
            ax.semilogy(np.arange(mask.sum()), life[mask], marker=".",
                        label=f"{name} ({method})")
    from matplotlib.ticker import FuncFormatter, NullFormatter

    # plain tick labels: the figure's texts are not parsed as mathtext (see _save)
    ax.yaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:.3g}"))
    ax.yaxis.set_minor_formatter(NullFormatter())
    ax.set_xlabel("element along the line (from end a)")
    ax.set_ylabel("fatigue life [years]")
    ax.grid(True, which="both", linewidth=0.3)
    ax.legend(fontsize=7)
    fig.suptitle(f"fatigue ({dataset.attrs.get('source', '')}): "
                 f"{dataset.attrs.get('curves', '')}", fontsize=9)
    return fig


@literal_text
def figure_extremes(dataset: xr.Dataset) -> Figure:
    """The most probable maximum element tension along every line."""
    fig = Figure(figsize=(8.0, 4.5), layout="constrained")
    ax = fig.add_subplot()
    for name, mask in _elements_by_line(dataset):
        ax.plot(np.arange(mask.sum()), dataset["element_mpm"].values[mask], marker=".",
                label=f"{name} MPM")
        maximum = dataset["element_maximum"].values[mask]
        if np.isfinite(maximum).any():
            ax.plot(np.arange(mask.sum()), maximum, linestyle=":", label=f"{name} max")
    ax.set_xlabel("element along the line (from end a)")
    ax.set_ylabel(f"tension [{dataset['element_mpm'].attrs.get('units', '')}]")
    ax.grid(True, linewidth=0.3)
    ax.legend(fontsize=7)
    fig.suptitle(f"extremes ({dataset.attrs.get('method', '')}) over "
                 f"{float(dataset.attrs.get('duration', 0)):.6g} s", fontsize=9)
    return fig


plot_fatigue_group = _single_figure(_writer(figure_fatigue, "fatigue"), "fatigue", "fatigue")
plot_extremes_group = _single_figure(_writer(figure_extremes, "extremes"), "extremes",
                                     "extremes")


__all__ += ["figure_extremes", "figure_fatigue", "plot_extremes_group",
            "plot_fatigue_group"]
