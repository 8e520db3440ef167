"""A sloped or gridded seabed in the results file and the plots (issue 14): the attributes
give back the seabed the contact acted on, and the x-z and 3-D views draw it where it is (the
plane's height written here from its slope, not from moorline)."""

from __future__ import annotations

import math

import netCDF4
import numpy as np
import pytest
from matplotlib.collections import LineCollection

from moorline import plot
from moorline.io import load_case_text
from moorline.io.netcdf_write import write_dataset
from moorline.plot_style import SEABED_COLOUR
from moorline.seabed_attrs import seabed_from_attrs
from moorline.solvers.statics import solve_statics

DEPTH, SLOPE = 200.0, 5.0  # m, deg (falling towards +x)

CASE = """
name: slope-plot
units: SI
environment: {{depth: {depth}, seabed: {{stiffness: 3.0e6, damping: 0, {seabed}}}}}
line_types:
  chain: {{diameter: 0.1, mass_per_length: 60.0, EA: 5.0e8, Cd: 1.2, Ca: 1.0}}
points:
  a: {{kind: fixed, position: [0.0, 0.0, {za}]}}
  b: {{kind: fixed, position: [-500.0, 0.0, -20.0]}}
lines:
  l1: {{type: chain, length: 600.0, segments: 40, end_a: a, end_b: b}}
analyses: [{{kind: statics}}]
"""


def _plane(x: np.ndarray) -> np.ndarray:
    return -DEPTH - math.tan(math.radians(SLOPE)) * x


def _statics(seabed: str):
    result = solve_statics(load_case_text(CASE.format(depth=DEPTH, seabed=seabed,
                                                      za=-DEPTH)))
    assert result.success, result.message
    return result.to_xarray()


@pytest.fixture(scope="module")
def sloped():
    return _statics(f"slope: {SLOPE}, slope_heading: 0")


def _seabed_collections(ax) -> list[np.ndarray]:
    return [np.concatenate(c.get_segments()) for c in ax.collections
            if isinstance(c, LineCollection)
            and np.allclose(c.get_colors()[0][:3], _rgb(SEABED_COLOUR))]


def _rgb(name: str) -> np.ndarray:
    from matplotlib.colors import to_rgb
    return np.array(to_rgb(name))


def test_the_results_file_gives_back_a_plane_and_a_grid(sloped, tmp_path) -> None:
    """Written to NetCDF and read back, the attributes rebuild the seabed: the plane's height
    at scattered points to 1e-9 m; a grid's heights at its nodes exactly."""
    path = tmp_path / "r.nc"
    write_dataset(sloped, path, group="statics")
    with netCDF4.Dataset(path) as nc:
        attrs = {k: nc["statics"].getncattr(k) for k in nc["statics"].ncattrs()}
    surface = seabed_from_attrs(attrs)
    xy = np.random.default_rng(3).uniform(-600, 100, (20, 2))
    assert np.allclose(surface.height(xy), _plane(xy[:, 0]), rtol=0, atol=1e-9)
    gx, gy = [-700.0, -200.0, 200.0], [-50.0, 60.0]
    gz = [[_plane(np.array(x)).item() - 5.0 * (x == -200.0) for _ in gy] for x in gx]
    gridded = _statics(f"bathymetry: {{x: {gx}, y: {gy}, z: {gz}}}")
    surface = seabed_from_attrs(gridded.attrs)
    nodes = np.array([[x, y] for x in gx for y in gy])
    assert np.array_equal(surface.height(nodes), np.ravel(gz))


def test_the_elevation_draws_the_slope_under_the_line(sloped) -> None:
    """Every drawn seabed point lies on the plane (heading 0: the height depends on x only);
    no horizontal seabed level is drawn; the drawing spans the line's plan extent."""
    ax = plot.figure_configuration_xz(sloped).axes[0]
    drawn = _seabed_collections(ax)
    assert len(drawn) == 1
    xz = drawn[0]
    assert np.allclose(xz[:, 1], _plane(xz[:, 0]), rtol=0, atol=1e-9)
    x = sloped["position"].values[:, 0]
    assert xz[:, 0].min() == pytest.approx(x.min()) and xz[:, 0].max() == pytest.approx(x.max())
    levels = {float(c.get_ydata()[0]) for c in ax.get_lines()
              if len(np.atleast_1d(c.get_ydata())) > 1
              and len(set(np.atleast_1d(c.get_ydata()))) == 1}
    assert levels == {0.0}  # the free surface only


def test_the_3d_view_holds_the_slope(sloped) -> None:
    """The 3-D view's z limits reach the plane's lowest height over the drawn box."""
    ax = plot.figure_configuration_3d(sloped).axes[0]
    (x0, x1), (z0, _) = ax.get_xlim(), ax.get_zlim()
    assert z0 <= min(_plane(np.array([x0, x1]))) + 1e-9


def test_mode_shape_scale_uses_the_height_under_each_node() -> None:
    """Node 1 is 1 m above the seabed under it, node 2 5 m (the seabed 10 m lower there); a
    shape moving node 1 down and node 2 up is drawn with the sign that moves node 2 down, at
    most 5 m: target 2 -> -2, target 8 -> -5 (above a quarter of 8). A flat seabed at node 1's
    level would leave node 2 no room (it is 5 m below that level) and give +1 instead."""
    position = np.array([[0.0, 0.0, -99.0], [10.0, 0.0, -105.0]])
    shape = np.array([[0.0, 0.0, -1.0], [0.0, 0.0, 1.0]])
    heights = np.array([-100.0, -110.0])
    assert plot.display_scale(position, shape, 2.0, heights) == (-2.0, False)
    assert plot.display_scale(position, shape, 8.0, heights) == (-5.0, False)
    assert plot.display_scale(position, shape, 2.0, -100.0) == (1.0, False)
