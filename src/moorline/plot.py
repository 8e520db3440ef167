"""Plots of results (matplotlib, Agg canvas; never opens a window).

Figures are built with the object-oriented API (:class:`matplotlib.figure.Figure` on a
:class:`~matplotlib.backends.backend_agg.FigureCanvasAgg`), so importing this module changes no
global matplotlib state and works without a display.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import xarray as xr
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.cm import ScalarMappable
from matplotlib.collections import LineCollection
from matplotlib.colors import Normalize
from matplotlib.figure import Figure
from matplotlib.text import Text
from mpl_toolkits.mplot3d.art3d import Line3DCollection
from numpy.typing import NDArray

from .plot_envelope import plot_tension_envelope

__all__ = ["plot_configuration", "plot_mode_shapes", "plot_motion_history",
           "plot_tension_history"]

CMAP = "viridis"
_MARKERS = {"fixed": ("s", "black"), "prescribed": ("^", "tab:red"), "free": ("o", "tab:blue")}
_UNITS = {"SI": {"force": "N", "length": "m"}, "US": {"force": "lbf", "length": "ft"}}
_MOVING = ("free", "prescribed")


def plot_configuration(dataset: xr.Dataset, path_xz: str | Path, path_3d: str | Path) -> None:
    """Plot a static configuration: an x-z elevation and a 3D view, elements coloured by tension.

    Parameters
    ----------
    dataset
        A statics dataset (:meth:`moorline.results.StaticResult.to_xarray` or the ``statics``
        group of a ``results.nc`` read back) with variables ``position(node, xyz)``,
        ``element_nodes(element, pair)``, ``tension(element)``, optionally
        ``point_position(point, xyz)`` and the coordinates ``element_line`` and
        ``point_kind``; attributes ``units`` (``SI`` or ``US``), ``case`` and
        optionally ``seabed_z`` (drawn when finite).
    path_xz, path_3d
        PNG files to write (parent directories are created).
    """
    segments, tension = _segments(dataset)
    units = _UNITS.get(str(dataset.attrs.get("units", "SI")), _UNITS["SI"])
    norm = _norm(tension)
    _plot_xz(dataset, segments, tension, norm, units, Path(path_xz))
    _plot_3d(dataset, segments, tension, norm, units, Path(path_3d))


def _segments(dataset: xr.Dataset) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    position = np.asarray(dataset["position"].values, dtype=float)
    if position.ndim == 3:  # a time history: plot the last instant
        position = position[-1]
    connectivity = np.asarray(dataset["element_nodes"].values, dtype=int)
    tension = np.asarray(dataset["tension"].values, dtype=float)
    if tension.ndim == 2:
        tension = tension[-1]
    return position[connectivity], tension


def _norm(tension: NDArray[np.float64]) -> Normalize:
    finite = tension[np.isfinite(tension)]
    low, high = (float(finite.min()), float(finite.max())) if finite.size else (0.0, 1.0)
    if high <= low:
        pad = max(abs(high) * 0.01, 1.0)
        low, high = low - pad, high + pad
    return Normalize(vmin=low, vmax=high)


def _seabed_z(dataset: xr.Dataset) -> float | None:
    value = dataset.attrs.get("seabed_z")
    if value is None:
        return None
    z = float(np.asarray(value).ravel()[0])
    return z if math.isfinite(z) else None


def _points(dataset: xr.Dataset) -> list[tuple[str, str, NDArray[np.float64]]]:
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


def _title(dataset: xr.Dataset, view: str) -> str:
    case = str(dataset.attrs.get("case", "")).strip()
    return f"{case}: static configuration, {view}" if case else f"Static configuration, {view}"


def _save(fig: Figure, path: Path) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    FigureCanvasAgg(fig)
    for text in fig.findobj(Text):  # names are printed literally ("$x$" is not mathtext)
        text.set_parse_math(False)
    fig.savefig(path, dpi=150)


def _plot_xz(dataset: xr.Dataset, segments: NDArray[np.float64], tension: NDArray[np.float64],
             norm: Normalize, units: dict[str, str], path: Path) -> None:
    fig = Figure(figsize=(9.0, 5.0), layout="constrained")
    ax = fig.add_subplot()
    collection = LineCollection(segments[:, :, [0, 2]], cmap=CMAP, norm=norm, linewidths=2.0)
    collection.set_array(tension)
    ax.add_collection(collection)
    seabed = _seabed_z(dataset)
    if seabed is not None:
        ax.axhline(seabed, color="saddlebrown", linewidth=1.2, label="seabed")
    for name, kind, xyz in _points(dataset):
        marker, colour = _MARKERS.get(kind, ("o", "tab:gray"))
        ax.plot(xyz[0], xyz[2], marker=marker, color=colour, markersize=6, linestyle="none")
        ax.annotate(name, (xyz[0], xyz[2]), textcoords="offset points", xytext=(5, 5),
                    fontsize=8)
    _label_lines(ax, dataset, segments)
    ax.autoscale_view()
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel(f"x [{units['length']}]")
    ax.set_ylabel(f"z [{units['length']}]")
    ax.set_title(_title(dataset, "x-z elevation"))
    ax.grid(True, linewidth=0.3)
    if seabed is not None:
        ax.legend(loc="best", fontsize=8)
    fig.colorbar(ScalarMappable(norm=norm, cmap=CMAP), ax=ax,
                 label=f"tension [{units['force']}]")
    _save(fig, path)


def _label_lines(ax, dataset: xr.Dataset, segments: NDArray[np.float64]) -> None:
    """Write each line's id next to its middle element (only when there are several lines)."""
    if "element_line" not in dataset.coords:
        return
    owners = np.array([str(v) for v in dataset["element_line"].values])
    names = list(dict.fromkeys(owners))
    if len(names) < 2:
        return
    for name in names:
        elements = np.flatnonzero(owners == name)
        mid = segments[elements[len(elements) // 2]].mean(axis=0)
        ax.annotate(name, (mid[0], mid[2]), textcoords="offset points", xytext=(0, -12),
                    fontsize=7, color="dimgray", style="italic", ha="center")


def _plot_3d(dataset: xr.Dataset, segments: NDArray[np.float64], tension: NDArray[np.float64],
             norm: Normalize, units: dict[str, str], path: Path) -> None:
    fig = Figure(figsize=(8.0, 6.5), layout="constrained")
    ax = fig.add_subplot(projection="3d")
    collection = Line3DCollection(segments, cmap=CMAP, norm=norm, linewidths=2.0)
    collection.set_array(tension)
    ax.add_collection3d(collection)
    points = _points(dataset)
    for name, kind, xyz in points:
        marker, colour = _MARKERS.get(kind, ("o", "tab:gray"))
        ax.scatter(*xyz, marker=marker, color=colour, s=25, depthshade=False)
        ax.text(*xyz, f" {name}", fontsize=8)
    low, high = _bounds(segments, points)
    seabed = _seabed_z(dataset)
    if seabed is not None:
        xx, yy = np.meshgrid([low[0], high[0]], [low[1], high[1]])
        ax.plot_surface(xx, yy, np.full_like(xx, seabed), color="saddlebrown", alpha=0.15)
        low[2], high[2] = min(low[2], seabed), max(high[2], seabed)
    ax.set_xlim(low[0], high[0])
    ax.set_ylim(low[1], high[1])
    ax.set_zlim(low[2], high[2])
    ax.set_box_aspect(tuple(high - low))
    ax.view_init(elev=20.0, azim=-60.0)
    for axis, setter in zip("xyz", (ax.set_xlabel, ax.set_ylabel, ax.set_zlabel), strict=True):
        setter(f"{axis} [{units['length']}]")
    ax.set_title(_title(dataset, "3D view"))
    fig.colorbar(ScalarMappable(norm=norm, cmap=CMAP), ax=ax, shrink=0.6,
                 label=f"tension [{units['force']}]")
    _save(fig, path)


def _bounds(segments: NDArray[np.float64],
            points: list[tuple[str, str, NDArray[np.float64]]]) -> tuple[NDArray, NDArray]:
    """Padded axis limits around all nodes and points; no axis shorter than a fifth of the
    longest, so that planar configurations still get a readable box."""
    xyz = segments.reshape(-1, 3)
    if points:
        xyz = np.vstack([xyz, [p for _, _, p in points]])
    xyz = xyz[np.all(np.isfinite(xyz), axis=1)]
    if not len(xyz):
        return np.full(3, -1.0), np.full(3, 1.0)
    low, high = xyz.min(axis=0), xyz.max(axis=0)
    longest = max(float(np.max(high - low)), 1e-9)
    half = np.maximum((high - low) / 2, 0.1 * longest) + 0.05 * longest
    centre = (high + low) / 2
    return centre - half, centre + half


# ----------------------------------------------------------------------------- time histories


def plot_tension_history(dataset: xr.Dataset, path: str | Path) -> None:
    """Plot the end-B (fairlead) tension of every line against time.

    Parameters
    ----------
    dataset
        A dynamics dataset (:meth:`moorline.results.DynamicResult.to_xarray` or the
        ``dynamics`` group of a ``results.nc`` read back) with ``time`` and
        ``end_force(time, line, end, xyz)`` (or ``end_tension(time, line, end)``); attributes
        ``units`` and ``case``.
    path
        PNG file to write (parent directories are created).
    """
    units = _UNITS.get(str(dataset.attrs.get("units", "SI")), _UNITS["SI"])
    time = np.asarray(dataset["time"].values, dtype=float)
    if "end_tension" in dataset:
        tension = np.asarray(dataset["end_tension"].values, dtype=float)
    else:
        tension = np.linalg.norm(np.asarray(dataset["end_force"].values, dtype=float), axis=-1)
    fig = Figure(figsize=(9.0, 4.5), layout="constrained")
    ax = fig.add_subplot()
    for k, line in enumerate(str(n) for n in dataset["line"].values):
        ax.plot(time, tension[:, k, 1], linewidth=1.0, label=line)
    ax.set_xlabel("time [s]")
    ax.set_ylabel(f"end B tension [{units['force']}]")
    ax.set_title(_history_title(dataset, "line tension at end B"))
    ax.grid(True, linewidth=0.3)
    if len(dataset["line"]):
        fig.legend(loc="outside right upper", fontsize=8)
    _save(fig, Path(path))


def plot_motion_history(dataset: xr.Dataset, path: str | Path) -> None:
    """Plot x and z of every free and prescribed point against time (two panels).

    Parameters
    ----------
    dataset
        A dynamics dataset with ``time``, ``position(time, node, xyz)``, ``point_node(point)``
        and the coordinate ``point_kind`` (without it every point is drawn).
    path
        PNG file to write (parent directories are created).
    """
    units = _UNITS.get(str(dataset.attrs.get("units", "SI")), _UNITS["SI"])
    time = np.asarray(dataset["time"].values, dtype=float)
    position = np.asarray(dataset["position"].values, dtype=float)
    names = [str(n) for n in dataset["point"].values]
    kinds = ([str(k) for k in dataset["point_kind"].values] if "point_kind" in dataset.coords
             else [_MOVING[0]] * len(names))
    nodes = (np.asarray(dataset["point_node"].values, dtype=int) if "point_node" in dataset
             else np.arange(len(names)))
    fig = Figure(figsize=(9.0, 6.0), layout="constrained")
    axes = fig.subplots(2, 1, sharex=True)
    drawn = 0
    for name, kind, node in zip(names, kinds, nodes, strict=True):
        if kind not in _MOVING:
            continue
        for ax, component in zip(axes, (0, 2), strict=True):
            ax.plot(time, position[:, node, component], linewidth=1.0,
                    label=f"{name} ({kind})")
        drawn += 1
    for ax, axis in zip(axes, "xz", strict=True):
        ax.set_ylabel(f"{axis} [{units['length']}]")
        ax.grid(True, linewidth=0.3)
    axes[1].set_xlabel("time [s]")
    axes[0].set_title(_history_title(dataset, "motion of free and prescribed points"))
    if drawn:
        fig.legend(*axes[0].get_legend_handles_labels(), loc="outside right upper", fontsize=8)
    else:
        axes[0].text(0.5, 0.5, "no free or prescribed points", transform=axes[0].transAxes,
                     ha="center", va="center")
    _save(fig, Path(path))


def _history_title(dataset: xr.Dataset, what: str) -> str:
    case = str(dataset.attrs.get("case", "")).strip()
    return f"{case}: {what}" if case else what[:1].upper() + what[1:]


# ----------------------------------------------------------------------------- modes


def plot_mode_shapes(dataset: xr.Dataset, path: str | Path, max_modes: int = 6,
                     amplitude: float = 0.08) -> None:
    """Plot the static shape and the scaled shapes of the first modes, one panel per mode.

    Modes dominated by x or z motion are drawn in the x-z elevation, modes dominated by y
    (out of the x-z plane) in the x-y plan view. Each mode is scaled so that its largest node
    displacement is ``amplitude`` times the size of the system (mode shapes have no absolute
    amplitude).

    Parameters
    ----------
    dataset
        A modal dataset (:meth:`moorline.results.ModalResult.to_xarray` or the ``modal`` group
        of a ``results.nc`` read back): ``position(node, xyz)``, ``element_nodes``,
        ``mode_shape(mode, node, xyz)``, ``omega``, ``period``, ``dominant``; attributes
        ``units`` and ``case``.
    path
        PNG file to write (parent directories are created).
    max_modes
        Number of modes drawn (the lowest).
    amplitude
        Drawn amplitude relative to the largest extent of the static shape.
    """
    units = _UNITS.get(str(dataset.attrs.get("units", "SI")), _UNITS["SI"])
    position = np.asarray(dataset["position"].values, dtype=float)
    connectivity = np.asarray(dataset["element_nodes"].values, dtype=int)
    shapes = np.asarray(dataset["mode_shape"].values, dtype=float)[:max_modes]
    n = len(shapes)
    columns = 1 if n <= 1 else 2
    rows = max(1, math.ceil(n / columns))
    fig = Figure(figsize=(6.0 * columns, 3.2 * rows), layout="constrained")
    axes = np.atleast_1d(fig.subplots(rows, columns, squeeze=False).ravel())
    size = max(float(np.ptp(position, axis=0).max(initial=0.0)), 1e-9)
    for k, ax in enumerate(axes):
        if k >= n:
            ax.set_axis_off()
            continue
        dominant = str(dataset["dominant"].values[k])
        plane = [0, 1] if dominant == "y" else [0, 2]
        largest = max(float(np.abs(shapes[k]).max(initial=0.0)), np.finfo(float).tiny)
        moved = position + shapes[k] * (amplitude * size / largest)
        ax.add_collection(LineCollection(position[connectivity][:, :, plane], colors="0.6",
                                         linewidths=1.0, linestyles="dashed"))
        ax.add_collection(LineCollection(moved[connectivity][:, :, plane], colors="tab:blue",
                                         linewidths=1.6))
        ax.autoscale_view()
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_xlabel(f"x [{units['length']}]")
        ax.set_ylabel(f"{'xyz'[plane[1]]} [{units['length']}]")
        omega = float(dataset["omega"].values[k])
        period = float(dataset["period"].values[k])
        view = "plan" if dominant == "y" else "elevation"
        ax.set_title(f"mode {k + 1}: {omega:.4g} rad/s, T = {period:.4g} s, {dominant} ({view})",
                     fontsize=9)
        ax.grid(True, linewidth=0.3)
    case = str(dataset.attrs.get("case", "")).strip()
    fig.suptitle(f"{case}: mode shapes (dashed: static shape)" if case
                 else "Mode shapes (dashed: static shape)")
    _save(fig, Path(path))


# ----------------------------------------------------------------------------- parameter studies


def plot_sweep_trends(dataset: xr.Dataset, path: str | Path) -> None:
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
    path
        PNG file to write (parent directories are created).
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
    _save(fig, Path(path))


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


__all__ += ["plot_sweep_trends"]


def plot_body_motion(dataset: xr.Dataset, path: str | Path) -> None:
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
    _save(fig, Path(path))


def animate_run(dataset: xr.Dataset, path: str | Path, frames: int = 120,
                view: str = "xz") -> None:
    """An animated GIF of a dynamics dataset: the lines (and the points) in the x-z (or
    x-y) plane at up to ``frames`` output times (Pillow writer; no screen needed)."""
    from matplotlib.animation import FuncAnimation, PillowWriter

    pos = dataset["position"].values
    time = dataset["time"].values
    el = dataset["element_nodes"].values
    a, b = (0, 2) if view == "xz" else (0, 1)
    picks = np.unique(np.linspace(0, len(time) - 1, min(frames, len(time))).astype(int))
    fig = Figure(figsize=(8, 5), constrained_layout=True)
    ax = fig.add_subplot(1, 1, 1)
    lo, hi = pos[..., [a, b]].min(axis=(0, 1)), pos[..., [a, b]].max(axis=(0, 1))
    pad = 0.05 * float(np.max(hi - lo))
    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_aspect("equal")
    ax.set_xlabel(view[0])
    ax.set_ylabel(view[1])
    lines = [ax.plot([], [], lw=1.2, color="tab:blue")[0] for _ in range(len(el))]
    title = ax.set_title("")

    def draw(i: int):
        p = pos[picks[i]]
        for line, (n1, n2) in zip(lines, el, strict=True):
            line.set_data([p[n1, a], p[n2, a]], [p[n1, b], p[n2, b]])
        title.set_text(f"{dataset.attrs.get('case', '')}  t = {time[picks[i]]:.2f} s")
        return [*lines, title]

    animation = FuncAnimation(fig, draw, frames=len(picks), blit=False)
    animation.save(str(path), writer=PillowWriter(fps=15))


def plot_snapshots(dataset: xr.Dataset, path: str | Path, times: list[float] | None = None
                   ) -> None:
    """The system in 3D at a few times of a dynamics dataset (default: four times spread over
    the run), one panel each."""
    time = dataset["time"].values
    pos = dataset["position"].values
    el = dataset["element_nodes"].values
    picks = times if times is not None else list(np.linspace(time[0], time[-1], 4))
    fig = Figure(figsize=(12, 3.6), constrained_layout=True)
    lo, hi = pos.min(axis=(0, 1)), pos.max(axis=(0, 1))
    for k, t in enumerate(picks):
        i = int(np.argmin(np.abs(time - t)))
        ax = fig.add_subplot(1, len(picks), k + 1, projection="3d")
        p = pos[i]
        for n1, n2 in el:
            ax.plot(*zip(p[n1], p[n2], strict=True), color="tab:blue", lw=1.0)
        ax.set_xlim(lo[0], hi[0])
        ax.set_ylim(lo[1], hi[1])
        ax.set_zlim(lo[2], hi[2])
        ax.set_title(f"t = {time[i]:.2f} s", fontsize=9)
    fig.suptitle(_history_title(dataset, "snapshots"))
    _save(fig, Path(path))


# ----------------------------------------------------------------------------- strumming


def plot_strumming(dataset: xr.Dataset, path: str | Path, max_elements: int = 4,
                   max_modes: int = 6) -> None:
    """Plot the lift coefficient of a few elements and the modal amplitudes against time.

    Parameters
    ----------
    dataset
        A strumming dataset (:meth:`moorline.results.StrummingResult.to_xarray`):
        ``lift_coefficient(time, element)``, ``modal_amplitude(time, mode)`` (modes numbered
        from 1), optional ``omega(mode)`` and the attribute ``CL0`` (drawn as +-C_L0).
    path
        PNG file to write (parent directories are created).
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
    _save(fig, Path(path))


def plot_stochastic(dataset: xr.Dataset, path: str | Path, max_items: int = 3) -> None:
    """Plot the wave spectrum with the response spectra of the most responsive node
    displacements and element tensions, and their time series over one record.

    Parameters
    ----------
    dataset
        A stochastic dataset (:meth:`moorline.results.StochasticResult.to_xarray`).
    path
        PNG file to write (parent directories are created).
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
    _save(fig, Path(path))


def plot_harmonic(dataset: xr.Dataset, path: str | Path, snapshots: int = 8) -> None:
    """Plot the periodic response: snapshots of the lines over one period (x-z, the dynamic
    part magnified to be seen) and the tension range along the elements.

    Parameters
    ----------
    dataset
        A harmonic dataset (:meth:`moorline.results.HarmonicResult.to_xarray`).
    path
        PNG file to write (parent directories are created).
    snapshots
        Instants drawn, equally spaced over the period.
    """
    pos = np.asarray(dataset["position"].values, dtype=float)
    static = np.asarray(dataset["static_position"].values, dtype=float)
    tension = np.asarray(dataset["tension"].values, dtype=float)
    dyn = pos - pos.mean(axis=0)[None]
    span = float(np.ptp(static[:, [0, 2]], axis=0).max()) or 1.0
    amp = float(np.abs(dyn).max()) or 1.0
    scale = max(1.0, 0.05 * span / amp)
    fig = Figure(figsize=(10.0, 5.0), layout="constrained")
    ax, ax_t = fig.subplots(1, 2)
    order = np.argsort(static[:, 0] + 1e-9 * static[:, 2])
    mean = pos.mean(axis=0)
    for j in np.linspace(0, len(pos), snapshots, endpoint=False).astype(int):
        shape = mean + scale * dyn[j]
        ax.plot(shape[order, 0], shape[order, 2], linewidth=0.8,
                label=f"t/T = {j / len(pos):.2f}")
    ax.plot(static[order, 0], static[order, 2], "k--", linewidth=0.8, label="static")
    ax.set_xlabel("x")
    ax.set_ylabel("z")
    ax.set_title(f"one period (dynamic part x {scale:.3g})")
    ax.legend(fontsize=7)
    elements = np.arange(tension.shape[1]) + 1
    ax_t.fill_between(elements, tension.min(axis=0), tension.max(axis=0), alpha=0.3,
                      label="range over the period")
    ax_t.plot(elements, tension.mean(axis=0), "k", linewidth=0.8, label="mean")
    ax_t.set_xlabel("element")
    ax_t.set_ylabel("tension")
    ax_t.legend(fontsize=7)
    for a in (ax, ax_t):
        a.grid(True, linewidth=0.3)
    fig.suptitle(f"harmonic balance: period {float(dataset.attrs.get('period', 0)):.4g}, "
                 f"{dataset.attrs.get('harmonics', '?')} harmonics")
    _save(fig, Path(path))


# ----------------------------------------------------------------------------- per analysis group
# One function per analysis kind (the ``plot`` of :data:`moorline.analyses.KINDS`):
# ``(dataset, directory, prefix) -> files written``, used by ``moorline run`` and
# ``moorline plot`` alike; ``prefix`` (the group name and ``_`` when a kind repeats) starts
# every file name.


def plot_statics_group(dataset: xr.Dataset, directory: str | Path,
                       prefix: str = "") -> list[Path]:
    """``configuration_xz.png`` and ``configuration_3d.png`` of a statics group.

    Raises
    ------
    ValueError
        When the dataset lacks ``position``, ``element_nodes`` or ``tension``.
    """
    missing = [v for v in ("position", "element_nodes", "tension") if v not in dataset.variables]
    if missing:
        raise ValueError(f"not a statics result (missing {', '.join(missing)})")
    files = [Path(directory) / f"{prefix}configuration_xz.png",
             Path(directory) / f"{prefix}configuration_3d.png"]
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
    plot_group.__doc__ = f"``{name}.png`` of a {kind} group."
    return plot_group


plot_modal_group = _single_figure(plot_mode_shapes, "mode_shapes", "modal")
plot_strumming_group = _single_figure(plot_strumming, "strumming", "strumming")
plot_stochastic_group = _single_figure(plot_stochastic, "stochastic", "stochastic")
plot_harmonic_group = _single_figure(plot_harmonic, "harmonic", "harmonic")


__all__ += ["plot_dynamics_group", "plot_harmonic_group", "plot_modal_group",
            "plot_statics_group", "plot_stochastic_group", "plot_strumming_group"]


def plot_fatigue_group(dataset: xr.Dataset, directory: str | Path,
                       prefix: str = "") -> list[Path]:
    """``fatigue.png``: fatigue life [years] along every line (per element) for each method."""
    path = Path(directory) / f"{prefix}fatigue.png"
    fig = Figure(figsize=(8.0, 4.5), layout="constrained")
    ax = fig.add_subplot()
    lines = [str(v) for v in dataset["element_line"].values]
    for k, method in enumerate(dataset["fatigue_method"].values):
        life = dataset["element_life"].values[k]
        for name in dict.fromkeys(lines):
            mask = np.array([n == name for n in lines])
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
    _save(fig, path)
    return [path]


def plot_extremes_group(dataset: xr.Dataset, directory: str | Path,
                        prefix: str = "") -> list[Path]:
    """``extremes.png``: most probable maximum element tension along every line."""
    path = Path(directory) / f"{prefix}extremes.png"
    fig = Figure(figsize=(8.0, 4.5), layout="constrained")
    ax = fig.add_subplot()
    lines = [str(v) for v in dataset["element_line"].values]
    for name in dict.fromkeys(lines):
        mask = np.array([n == name for n in lines])
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
    _save(fig, path)
    return [path]


__all__ += ["plot_extremes_group", "plot_fatigue_group"]
