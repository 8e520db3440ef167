"""Plots an engineer trusts (issue 12, deliverable 7), checked without looking at pixels.

The case: ``cases/oc3_dynamics.yaml`` (three catenary lines at 0, 120 and 240 deg; lines 2 and
3 coincide in the x-z view and have equal tension histories), statics, 4 s of dynamics
(``dataclasses.replace`` of the case's 60 s) and six modes; ``cases/oc3_line.yaml`` for the
single-line views.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from matplotlib.collections import LineCollection
from matplotlib.figure import Figure
from matplotlib.text import Annotation
from mpl_toolkits.mplot3d import proj3d

from moorline import plot
from moorline.design import line_attrs
from moorline.io import load_case
from moorline.model import DynamicsSettings
from moorline.plot_configuration import segments
from moorline.plot_style import curve_styles, force_scale
from moorline.solvers.dynamics import simulate
from moorline.solvers.modal import solve_modes
from moorline.solvers.statics import solve_statics

ROOT = Path(__file__).resolve().parents[1]
OC3_DYNAMICS = ROOT / "cases" / "oc3_dynamics.yaml"
OC3_LINE = ROOT / "cases" / "oc3_line.yaml"

pytestmark = pytest.mark.skipif(not OC3_DYNAMICS.is_file() or not OC3_LINE.is_file(),
                                reason="OC3 cases missing")


@pytest.fixture(scope="module")
def oc3() -> dict[str, xr.Dataset]:
    """Statics, 4 s of dynamics and six modes of the three-line OC3 case, with the line
    MBL attribute the run writes (:func:`moorline.design.line_attrs`)."""
    system = load_case(OC3_DYNAMICS)
    statics = solve_statics(system)
    settings = dataclasses.replace(system.first(DynamicsSettings), duration=4.0,
                                   ramp_time=1.0)
    dynamics = simulate(system, settings, initial=statics, output_every=0.25)
    modal = solve_modes(system, statics=statics)
    groups = {"statics": statics.to_xarray(), "dynamics": dynamics.to_xarray(),
              "modal": modal.to_xarray()}
    for ds in groups.values():
        ds.attrs.update(line_attrs(system))
    return groups


@pytest.fixture(scope="module")
def single_line() -> xr.Dataset:
    return solve_statics(load_case(OC3_LINE)).to_xarray()


def _all_nodes(ds: xr.Dataset) -> np.ndarray:
    return segments(ds)[0].reshape(-1, 3)


def test_every_figure_function_returns_a_figure(oc3, single_line, tmp_path: Path) -> None:
    """(k) pure functions return Figures; the writers save the files the runs expect."""
    figures = [plot.figure_configuration_xz(oc3["statics"]),
               plot.figure_configuration_plan(oc3["statics"]),
               plot.figure_configuration_3d(oc3["statics"]),
               plot.figure_configuration_xz(single_line),
               plot.figure_tension_history(oc3["dynamics"]),
               plot.figure_motion_history(oc3["dynamics"]),
               plot.figure_mode_shapes(oc3["modal"]),
               plot.figure_snapshots(oc3["dynamics"])]
    assert all(isinstance(fig, Figure) for fig in figures)
    files = plot.plot_statics_group(oc3["statics"], tmp_path)
    assert [f.name for f in files] == ["configuration_xz.png", "configuration_3d.png",
                                       "configuration_plan.png"]
    assert all(f.stat().st_size > 0 for f in files)
    files = plot.plot_dynamics_group(oc3["dynamics"], tmp_path)
    assert {"tension_history.png", "motion_history.png"} <= {f.name for f in files}


def test_plan_view_separates_the_lines(oc3) -> None:
    """(a) the plan view shows x-y: its y limits hold the anchors at y = +-739.47 m."""
    ax = plot.figure_configuration_plan(oc3["statics"]).axes[0]
    assert ax.get_ylabel() == "y [m]"
    low, high = ax.get_ylim()
    assert low < -739.47 and high > 739.47


def test_3d_limits_hold_every_node_and_no_line_is_seen_end_on(oc3) -> None:
    """(b) limits enclose every node; each line's projected chord is at least 40 % of the
    longest one (the old fixed azimuth -60 deg looked along line 2: ~7 %)."""
    ds = oc3["statics"]
    fig = plot.figure_configuration_3d(ds)
    ax = fig.axes[0]
    nodes = _all_nodes(ds)
    for limits, column in zip((ax.get_xlim3d(), ax.get_ylim3d(), ax.get_zlim3d()),
                              nodes.T, strict=True):
        assert limits[0] <= column.min() and column.max() <= limits[1]
    assert ax.get_zlim3d()[1] >= 0.0 and ax.get_zlim3d()[0] <= -320.0  # surface and seabed
    box = np.array(ax.get_box_aspect())
    extent = np.array([np.ptp(lim) for lim in (ax.get_xlim3d(), ax.get_ylim3d(),
                                                ax.get_zlim3d())])
    np.testing.assert_allclose(box / box[0], extent / extent[0], rtol=1e-9)  # to scale
    seen = _projected_chords(fig, ds)
    assert min(seen) >= 0.4 * max(seen), seen
    ax.view_init(elev=20.0, azim=-60.0)  # the old camera looks along line 2 (120 deg)
    seen = _projected_chords(fig, ds)
    assert min(seen) < 0.1 * max(seen), seen


def _projected_chords(fig: Figure, ds: xr.Dataset) -> list[float]:
    """Screen length [px] of each line's chord (first to last node) in the 3-D view."""
    ax = fig.axes[0]
    fig.canvas.draw()
    owners = ds["element_line"].values.astype(str)
    seen = []
    for line in dict.fromkeys(owners):
        ends = segments(ds)[0][owners == line].reshape(-1, 3)[[0, -1]]
        x, y, _ = proj3d.proj_transform(*ends.T, ax.get_proj())
        pixels = ax.transData.transform(np.column_stack([x, y]))
        seen.append(float(np.hypot(*(pixels[1] - pixels[0]))))
    return seen


def _texts_overlap(fig: Figure) -> list[tuple[str, str]]:
    renderer = fig.canvas.get_renderer()
    labels = [t for t in fig.axes[0].texts if isinstance(t, Annotation) and t.get_visible()]
    boxes = [t.get_window_extent(renderer) for t in labels]
    return [(labels[i].get_text(), labels[j].get_text())
            for i in range(len(boxes)) for j in range(i + 1, len(boxes))
            if boxes[i].overlaps(boxes[j])]


def test_no_label_overprints_another(oc3) -> None:
    """(c) the three-line x-z view: no two label boxes overlap; coincident fairleads 2 and 3
    (and lines 2 and 3) share one label; every point name is written."""
    for make in (plot.figure_configuration_xz, plot.figure_configuration_plan,
                 plot.figure_configuration_3d):
        fig = make(oc3["statics"])
        fig.canvas.draw()
        assert _texts_overlap(fig) == []
        written = " ".join(t.get_text() for t in fig.axes[0].texts)
        for name in oc3["statics"]["point"].values:
            assert str(name) in written
    texts = [t.get_text() for t in plot.figure_configuration_xz(oc3["statics"]).axes[0].texts]
    assert any("fairlead2" in t and "fairlead3" in t for t in texts)
    assert any("line2" in t and "line3" in t for t in texts)


def test_labels_do_not_cover_the_lines(oc3) -> None:
    """(c) in the OC3 elevation and plan no label box covers a node of a drawn line."""
    nodes = _all_nodes(oc3["statics"])
    for make, plane in ((plot.figure_configuration_xz, [0, 2]),
                        (plot.figure_configuration_plan, [0, 1])):
        fig = make(oc3["statics"])
        fig.canvas.draw()
        ax = fig.axes[0]
        pixels = ax.transData.transform(nodes[:, plane])
        for text in ax.texts:
            box = text.get_window_extent(fig.canvas.get_renderer())
            inside = ((pixels[:, 0] >= box.x0) & (pixels[:, 0] <= box.x1)
                      & (pixels[:, 1] >= box.y0) & (pixels[:, 1] <= box.y1))
            assert not inside.any(), text.get_text()


def test_tension_history_styles_units_and_mbl(oc3) -> None:
    """(d, e, g) distinct (linestyle, colour, marker) per line; MN (peak ~1 MN, MBL
    3.397 MN) with no offset text; the MBL line at the catalogue value."""
    ds = oc3["dynamics"]
    fig = plot.figure_tension_history(ds)
    ax = fig.axes[0]
    curves = [c for c in ax.get_lines() if c.get_label().startswith("line")]
    assert len(curves) == 3
    styles = {(c.get_linestyle(), c.get_color(), c.get_marker()) for c in curves}
    assert len(styles) == 3
    factor, unit = force_scale(float(np.nanmax(ds.attrs["line_MBL"])))
    assert (factor, unit) == (1e6, "MN")
    assert ax.get_ylabel().endswith("[MN]")
    fig.canvas.draw()
    assert ax.yaxis.get_offset_text().get_text() == ""
    fairlead = ds["end_tension"].values[:, :, 1]
    np.testing.assert_allclose(curves[0].get_ydata(), fairlead[:, 0] / 1e6)
    mbl = [c for c in ax.get_lines() if c.get_label().startswith("MBL")]
    assert len(mbl) == 1  # the three lines share one MBL: one line, one label
    # R3 studless chain, d = 62.5 mm: MBL = 0.0223 d^2 (44 - 0.08 d) kN (DNV-OS-E302)
    np.testing.assert_allclose(mbl[0].get_ydata(), 0.0223 * 62.5**2 * (44 - 0.08 * 62.5) / 1e3,
                               rtol=1e-6)
    ds_unknown = ds.copy()
    ds_unknown.attrs["line_MBL"] = np.full(3, np.nan)
    lines = plot.figure_tension_history(ds_unknown).axes[0].get_lines()
    assert not [c for c in lines if c.get_label().startswith("MBL")]
    assert plot.figure_tension_history(ds_unknown).axes[0].get_ylabel().endswith("[kN]")
    ds_unknown.attrs["units"] = "US"  # the same numbers read as lbf: kip
    assert plot.figure_tension_history(ds_unknown).axes[0].get_ylabel().endswith("[kip]")


def test_force_scale_steps() -> None:
    assert force_scale(950.0) == (1.0, "N")
    assert force_scale(9.5e5) == (1e3, "kN")
    assert force_scale(3.4e6) == (1e6, "MN")
    assert force_scale(2.0e3, "US") == (1e3, "kip")
    assert len({(s["color"], s["linestyle"], s["marker"]) for s in curve_styles(8)}) == 8


def _horizontal_levels(ax) -> set[float]:
    return {float(c.get_ydata()[0]) for c in ax.get_lines()
            if len(set(np.atleast_1d(c.get_ydata()))) == 1}


def test_free_surface_and_seabed_drawn(oc3, single_line) -> None:
    """(f) horizontal lines at z = 0 and at the seabed (-320 m) in the elevation and in
    every elevation panel of the mode shapes."""
    for ds in (oc3["statics"], single_line):
        assert {0.0, -320.0} <= _horizontal_levels(plot.figure_configuration_xz(ds).axes[0])
    fig = plot.figure_mode_shapes(oc3["modal"])
    elevations = [ax for ax in fig.axes if ax.get_ylabel() == "z [m]"]
    assert elevations
    for ax in elevations:
        assert {0.0, -320.0} <= _horizontal_levels(ax)


def test_motion_history_draws_only_what_moves(oc3) -> None:
    """(h) OC3 fairleads surge in x only: one panel (x), three curves, none flat; each
    curve is the displacement from t = 0 of its point."""
    ds = oc3["dynamics"]
    fig = plot.figure_motion_history(ds)
    panels = [ax for ax in fig.axes if ax.get_lines()]
    assert [ax.get_ylabel() for ax in panels] == ["x - x(0) [m]"]
    curves = panels[0].get_lines()
    assert len(curves) == 3
    assert all(np.ptp(c.get_ydata()) > 1.0 for c in curves)
    node = int(ds["point_node"].values[list(ds["point"].values).index("fairlead1")])
    x = ds["position"].values[:, node, 0]
    np.testing.assert_allclose(curves[0].get_ydata(), x - x[0])


def test_mode_shapes_say_arbitrary_and_stay_above_the_seabed(oc3) -> None:
    """(j) every panel says the amplitude is arbitrary; no drawn node of an elevation
    panel is below the seabed. OC3 single line, eight modes: scaled as before (largest
    displacement 8 % of the system), modes 5 and 7 reach ~30 m into the seabed."""
    fig = plot.figure_mode_shapes(oc3["modal"])
    assert "arbitrary" in fig.get_suptitle()
    panels = [ax for ax in fig.axes if ax.get_title()]
    assert len(panels) == 6
    assert all("amplitude arbitrary" in ax.get_title() for ax in panels)
    ds = solve_modes(load_case(OC3_LINE)).to_xarray()
    position, shapes = ds["position"].values, ds["mode_shape"].values[:8]
    size = np.ptp(position, axis=0).max()
    old = [(position + s * (0.08 * size / np.abs(s).max()))[:, 2].min() for s in shapes]
    assert min(old) < -340.0  # the old drawing went through the seabed
    fig = plot.figure_mode_shapes(ds, max_modes=8)
    elevations = [ax for ax in fig.axes if ax.get_ylabel() == "z [m]"]
    assert len(elevations) >= 4
    for ax in elevations:
        (shape,) = [c for c in ax.collections
                    if isinstance(c, LineCollection) and c.get_gid() == "mode shape"]
        drawn = np.array(shape.get_segments())
        assert drawn[..., 1].min() >= -320.0
        static = position[ds["element_nodes"].values][..., [0, 2]]
        assert np.abs(drawn - static).max() > 0.01 * size  # still visible, not scaled away


def test_animation_has_units_seabed_and_tension_colours(oc3, tmp_path: Path) -> None:
    """(i) a GIF is written; the figure has a tension colour bar, axis units, the seabed
    and the free surface, elements coloured by tension."""
    path = tmp_path / "anim" / "animation.gif"
    fig = plot.animate_run(oc3["dynamics"], path, frames=4)
    assert path.read_bytes()[:3] == b"GIF"
    colourbars = [ax for ax in fig.axes if ax.get_label() == "<colorbar>"]
    assert len(colourbars) == 1 and "kN" in colourbars[0].get_ylabel()
    ax = fig.axes[0]
    assert ax.get_xlabel() == "x [m]" and ax.get_ylabel() == "z [m]"
    assert {0.0, -320.0} <= _horizontal_levels(ax)
    (coloured,) = [c for c in ax.collections if isinstance(c, LineCollection)
                   and c.get_array() is not None]
    np.testing.assert_allclose(coloured.get_array(), oc3["dynamics"]["tension"].values[-1])


def test_display_scale_by_hand() -> None:
    """(j) two nodes 10 and 15 m above a seabed at -20 m: the sign and factor worked out by
    hand (a mode's sign is free; the factor shrinks until a node touches the seabed, and
    the drawing is clipped when it would shrink under a quarter)."""
    position = np.array([[0.0, 0.0, -10.0], [1.0, 0.0, -5.0]])
    down_only = np.array([[0.0, 0.0, -1.0], [0.0, 0.0, 0.0]])
    assert plot.display_scale(position, down_only, 5.0, -20.0) == (-5.0, False)
    both = np.array([[0.0, 0.0, -1.0], [0.0, 0.0, 1.0]])  # room 10 (sign +), 15 (sign -)
    assert plot.display_scale(position, both, 20.0, -20.0) == (-15.0, False)
    assert plot.display_scale(position, both, 100.0, -20.0) == (-100.0, True)
    assert plot.display_scale(position, both, 100.0, None) == (100.0, False)
