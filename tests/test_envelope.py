"""Tension envelopes and along-line coordinates (issue 12, deliverable 4): the envelope
against numpy's statistics of the written tension history, arc lengths against the case's
line lengths, node order against the mesh's connectivity, the streamed group against the
in-memory dataset, and the range graphs.

The case: the OC3 line split at a 2 t clump into two lines (``lower``: anchor to junction,
``upper``: junction to fairlead), the fairlead surging 5 m / 10 s, 5 s of dynamics with a
1 s ramp; the junction ends both lines (a shared end point).
"""

from __future__ import annotations

import dataclasses
import json
import math
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml
from click.testing import CliRunner
from matplotlib.collections import PolyCollection

from moorline.cli import cli
from moorline.envelope import TensionEnvelope, envelope_start, line_profile
from moorline.io import load_case
from moorline.mesh import discretize
from moorline.model import StaticsSettings
from moorline.plot_envelope import force_scale, plot_tension_envelope

ROOT = Path(__file__).resolve().parents[1]
OC3_LINE = ROOT / "cases" / "oc3_line.yaml"
LENGTHS = {"lower": 500.0, "upper": 402.2}
RAMP = 1.0

pytestmark = pytest.mark.skipif(not OC3_LINE.is_file(), reason="cases/oc3_line.yaml missing")


def _case(directory: Path) -> Path:
    case = yaml.safe_load(OC3_LINE.read_text())
    case["line_types"]["chain"]["BA"] = -0.8
    case["points"]["junction"] = {"kind": "free", "position": [-500.0, 0, -300.0],
                                  "mass": 2000.0}
    case["points"]["fairlead"]["motion"] = {"kind": "harmonic", "amplitude": [5, 0, 0],
                                            "period": 10}
    case["lines"] = {
        "lower": {"type": "chain", "length": LENGTHS["lower"], "segments": 6,
                  "end_a": "anchor", "end_b": "junction"},
        "upper": {"type": "chain", "length": LENGTHS["upper"], "segments": 5,
                  "end_a": "junction", "end_b": "fairlead"}}
    case["analyses"] = [{"kind": "statics", "method": "newton"},
                        {"kind": "dynamics", "duration": 5.0, "dt": 0.05, "ramp_time": RAMP}]
    case["output"] = {"every": 0.25}
    path = directory / "two_lines.yaml"
    path.write_text(yaml.safe_dump(case))
    return path


@pytest.fixture(scope="module")
def run(tmp_path_factory: pytest.TempPathFactory) -> dict:
    """``moorline run`` of the case once: the case path, the output folder and both groups
    read back."""
    tmp = tmp_path_factory.mktemp("envelope")
    path = _case(tmp)
    result = CliRunner().invoke(cli, ["run", str(path), "--out", str(tmp / "out"), "--quiet"])
    assert result.exit_code == 0, result.output
    out = tmp / "out" / "oc3-line"
    groups = {}
    for group in ("statics", "dynamics"):
        with xr.open_dataset(out / "results.nc", group=group) as ds:
            groups[group] = ds.load()
    return {"case": path, "out": out, **groups}


def _after_start(ds: xr.Dataset) -> np.ndarray:
    """The written tension history (time, element) from the envelope's start."""
    time = ds["time"].values
    return ds["tension"].values[time >= ds.attrs["envelope_start"]]


def test_envelope_is_numpy_statistics_of_the_written_history(run: dict) -> None:
    ds = run["dynamics"]
    assert ds.attrs["envelope_start"] == RAMP  # default: after the dynamics' ramp
    history = _after_start(ds)
    assert ds.attrs["envelope_records"] == len(history) == 17  # 1, 1.25, ..., 5 s
    np.testing.assert_array_equal(ds["tension_min"], history.min(axis=0))
    np.testing.assert_array_equal(ds["tension_max"], history.max(axis=0))
    # running sums of T - T_static in order against numpy's pairwise sums: rounding only
    np.testing.assert_allclose(ds["tension_mean"], history.mean(axis=0), rtol=1e-13)
    np.testing.assert_allclose(ds["tension_std"], history.std(axis=0), rtol=1e-9)
    for name in ("tension_min", "tension_max", "tension_mean", "tension_std",
                 "tension_static"):
        assert ds[name].dims == ("element",)
        assert ds[name].attrs["units"] == "N" and ds[name].attrs["long_name"]


def test_static_value_is_the_runs_statics_not_the_first_record(run: dict) -> None:
    ds, statics = run["dynamics"], run["statics"]
    np.testing.assert_array_equal(ds["tension_static"], statics["tension"])
    # the harmonic fairlead motion starts displaced (cos), so the first record differs from
    # the statics at the fairlead element: the check above tells the two apart
    assert not np.allclose(ds["tension"].values[0], statics["tension"].values, rtol=1e-3)


def test_envelope_start_setting(run: dict) -> None:
    assert envelope_start({"ramp_time": 2.0, "envelope_start": None}) == 2.0
    assert envelope_start({"ramp_time": 2.0, "envelope_start": 3.5}) == 3.5
    assert envelope_start({"setting_ramp_time": 0.0, "setting_envelope_start": "none"}) == 0.0
    assert envelope_start({}) == 0.0
    text = yaml.safe_load(run["case"].read_text())
    text["analyses"][1]["envelope_start"] = "2.5 s"
    path = run["case"].with_name("with_start.yaml")
    path.write_text(yaml.safe_dump(text))
    assert load_case(path).first("dynamics").envelope_start == 2.5


def test_the_envelope_of_a_later_start_in_memory(run: dict) -> None:
    from moorline.solvers.dynamics import simulate
    from moorline.solvers.statics import solve_statics

    system = load_case(run["case"])
    static = solve_statics(system, system.first(StaticsSettings))
    result = simulate(system, system.first("dynamics"), initial=static)
    later = dataclasses.replace(result, settings={**result.settings, "envelope_start": 3.0})
    ds = later.to_xarray()
    history = result.tension[result.time >= 3.0]
    assert ds.attrs["envelope_records"] == len(history) == 9
    np.testing.assert_array_equal(ds["tension_max"], history.max(axis=0))
    np.testing.assert_allclose(ds["tension_std"], history.std(axis=0), rtol=1e-9)
    # the streamed group and to_xarray agree (same records, same accumulation)
    memory = result.to_xarray()
    for name in ("tension_min", "tension_max", "tension_mean", "tension_std",
                 "tension_static", "line_nodes", "line_arc_length", "node_line",
                 "node_arc_length", "element_arc_length"):
        xr.testing.assert_identical(run["dynamics"][name], memory[name])
    for key in ("envelope_start", "envelope_records"):
        assert run["dynamics"].attrs[key] == memory.attrs[key]


def test_variance_keeps_its_digits_at_a_large_mean() -> None:
    """Shifted sums: a 10 MN tension varying by 1 N keeps its std (E[T^2] - E[T]^2 would
    lose it all)."""
    rng = np.random.default_rng(3)
    tension = 1.0e7 + rng.normal(0.0, 1.0, (400, 3))
    envelope = TensionEnvelope(3)
    envelope.add_records(np.arange(400.0), tension)
    np.testing.assert_allclose(envelope.values()["tension_std"], tension.std(axis=0),
                               rtol=1e-6)


@pytest.mark.parametrize("group", ["statics", "dynamics"])
def test_arc_length_runs_from_zero_to_the_line_length(run: dict, group: str) -> None:
    ds, statics = run[group], run["statics"]
    for k, line in enumerate(str(n) for n in ds["line"].values):
        elements = np.flatnonzero(ds["element_line"].values == line)
        s = ds["line_arc_length"].values[k]
        s = s[ds["line_nodes"].values[k] >= 0]
        unstretched = statics["unstretched_length"].values[elements]
        assert s[0] == 0.0
        assert s[-1] == pytest.approx(math.fsum(unstretched), rel=1e-15)
        assert s[-1] == pytest.approx(LENGTHS[line], rel=1e-14)
        np.testing.assert_allclose(np.diff(s), unstretched, rtol=1e-12)
        np.testing.assert_allclose(ds["element_arc_length"].values[elements],
                                   0.5 * (s[:-1] + s[1:]), rtol=1e-15)
    # the nodes: interior ones and the points ending one line carry it; the junction ends
    # both lines: no single line, no single arc length
    mesh = discretize(load_case(run["case"]))
    point_node = {p: mesh.point_node[mesh.point_index(p)] for p in mesh.point_names}
    node_line, node_s = ds["node_line"].values, ds["node_arc_length"].values
    assert (node_line[point_node["anchor"]], node_s[point_node["anchor"]]) == ("lower", 0.0)
    assert node_line[point_node["fairlead"]] == "upper"
    assert node_s[point_node["fairlead"]] == pytest.approx(LENGTHS["upper"], rel=1e-14)
    assert node_line[point_node["junction"]] == ""
    assert np.isnan(node_s[point_node["junction"]])


def test_line_nodes_follow_the_mesh_connectivity(run: dict) -> None:
    ds = run["statics"]
    mesh = discretize(load_case(run["case"]))
    for k, line in enumerate(mesh.line_names):
        row = ds["line_nodes"].sel(line=line).values
        nodes = row[row >= 0]
        assert (row[len(nodes):] == -1).all()
        elements = mesh.elements[mesh.element_line == k]
        pairs = np.column_stack((nodes[:-1], nodes[1:]))
        np.testing.assert_array_equal(pairs, elements)  # each pair is the next element
        ends = load_case(run["case"]).lines[line]
        assert nodes[0] == mesh.point_node[mesh.point_index(ends.end_a)]
        assert nodes[-1] == mesh.point_node[mesh.point_index(ends.end_b)]
        interior = nodes[1:-1]
        assert (ds["node_line"].values[interior] == line).all()


def test_line_profile_is_the_line_in_order(run: dict) -> None:
    ds = run["dynamics"]
    profile = line_profile(ds, "upper")
    k = list(ds["line"].values).index("upper")
    nodes = ds["line_nodes"].values[k]
    nodes = nodes[nodes >= 0]
    np.testing.assert_array_equal(profile["position"].values,
                                  ds["position"].values[:, nodes])
    np.testing.assert_array_equal(profile["arc_length"].values,
                                  ds["line_arc_length"].values[k, :len(nodes)])
    assert profile.sizes["element"] == 5
    assert (np.diff(profile["element_arc_length"].values) > 0).all()
    np.testing.assert_array_equal(profile["tension_max"].values,
                                  ds["tension_max"].values[ds["element_line"] == "upper"])


def test_summary_names_the_largest_element_tension(run: dict) -> None:
    summary = json.loads((run["out"] / "summary.json").read_text())
    envelope = next(a for a in summary["analyses"] if a["kind"] == "dynamics")["envelope"]
    ds = run["dynamics"]
    history = _after_start(ds)
    e = int(np.argmax(history.max(axis=0)))
    assert envelope["records"] == len(history)
    assert envelope["max_element_tension"] == {
        "tension": float(history.max()), "line": str(ds["element_line"].values[e]),
        "arc_length": float(ds["element_arc_length"].values[e])}


def test_range_graph_per_line(run: dict) -> None:
    ds = run["dynamics"]
    assert (run["out"] / "tension_envelope.png").stat().st_size > 0
    fig = plot_tension_envelope(ds)
    panels = [ax for ax in fig.axes if ax.get_visible()]
    assert [ax.get_title() for ax in panels] == ["lower", "upper"]
    factor, unit = force_scale(float(ds["tension_max"].max()))
    for ax in panels:
        assert sum(isinstance(c, PolyCollection) for c in ax.collections) == 1  # mean +- std
        assert len(ax.get_lines()) == 4  # static, mean, min, max
        assert ax.get_ylabel() == f"tension [{unit}]"
    top = max(max(line.get_ydata().max() for line in ax.get_lines()) for ax in panels)
    assert top == pytest.approx(float(ds["tension_max"].max()) / factor, rel=1e-12)


def test_force_units_by_magnitude() -> None:
    assert force_scale(12.0) == (1.0, "N")
    assert force_scale(9.5e5) == (1.0e3, "kN")
    assert force_scale(1.2e6) == (1.0e6, "MN")
    assert force_scale(4.0e3, "US") == (1.0e3, "kip")
    assert force_scale(math.nan) == (1.0, "N")


def test_a_stream_holds_the_envelope_of_the_records_it_holds(run: dict, tmp_path: Path) -> None:
    """Block by block (what a killed run leaves): the file's envelope is numpy's over the
    records on disk; without a static tension given, the static value is the first record."""
    import netCDF4

    from moorline.io.stream import HistoryWriter

    mesh = discretize(load_case(run["case"]))
    n, m = mesh.n_nodes, mesh.n_elements
    rng = np.random.default_rng(7)
    tensions = 8.0e5 + 1.0e5 * rng.standard_normal((21, m))
    times = 0.25 * np.arange(21)
    attrs = {"case": "x", "units": "SI", "setting_ramp_time": 1.0,
             "setting_envelope_start": "none"}
    with HistoryWriter(tmp_path / "h.nc", mesh, attrs, block_records=4) as writer:
        for k, t in enumerate(times):
            writer.append(float(t), {
                "position": np.zeros((n, 3)), "velocity": np.zeros((n, 3)),
                "tension": tensions[k], "end_force": np.zeros((len(mesh.line_names), 2, 3)),
                "body_pose": np.zeros((0, 6)), "body_velocity": np.zeros((0, 6)),
                "body_mooring_force": np.zeros((0, 6)), "wave_elevation": 0.0})
            if k == 12:
                with netCDF4.Dataset(tmp_path / "h.nc") as mid:
                    kept = len(mid["time"][:])
                    on_disk = tensions[:kept][times[:kept] >= 1.0]
                    assert 0 < kept < len(times) and mid.envelope_records == len(on_disk)
                    np.testing.assert_array_equal(mid["tension_max"][:], on_disk.max(axis=0))
    with xr.open_dataset(tmp_path / "h.nc") as ds:
        after = tensions[times >= 1.0]
        np.testing.assert_array_equal(ds["tension_min"], after.min(axis=0))
        np.testing.assert_allclose(ds["tension_std"], after.std(axis=0), rtol=1e-9)
        np.testing.assert_array_equal(ds["tension_static"], tensions[0])


@pytest.mark.parametrize("n_elements", [1, 2, 7, 60, 1000])
def test_blocks_give_the_record_by_record_envelope_bit_for_bit(n_elements: int) -> None:
    """The stream adds records a block at a time, the in-memory dataset all at once: both
    must equal the record-by-record sums to the last bit (same mean and std in the file as
    in ``to_xarray()``), at any number of elements (numpy sums one column pairwise)."""
    from moorline.envelope import TensionEnvelope

    rng = np.random.default_rng(n_elements)
    tensions = 8.0e5 + 1.0e5 * rng.standard_normal((2000, n_elements))
    times = 0.05 * np.arange(2000)
    one = TensionEnvelope(n_elements, 10.0)
    for t, tension in zip(times, tensions, strict=True):
        one.add(float(t), tension)
    blocks = TensionEnvelope(n_elements, 10.0)
    for i in range(0, 2000, 333):
        blocks.add_records(times[i:i + 333], tensions[i:i + 333])
    whole = TensionEnvelope(n_elements, 10.0)
    whole.add_records(times, tensions)
    assert one.count == blocks.count == whole.count == int(np.sum(times >= 10.0))
    for name, value in one.values().items():
        np.testing.assert_array_equal(blocks.values()[name], value, err_msg=name)
        np.testing.assert_array_equal(whole.values()[name], value, err_msg=name)


@pytest.mark.parametrize("compiled", [True, False])
def test_both_passes_equal_numpy_record_by_record(compiled: bool) -> None:
    """The compiled envelope pass (:func:`moorline.fast_envelope.accumulate`, runs on the
    compiled path) and the numpy one (runs that do not load numba) against numpy's own
    operations record by record (``np.minimum``, ``np.maximum``, shifted sums added in
    order): equal to the last bit; a NaN tension makes the minimum and maximum NaN, as numpy
    does."""
    from moorline.envelope import TensionEnvelope

    rng = np.random.default_rng(11)
    tensions = 8.0e5 + 1.0e5 * rng.standard_normal((500, 9))
    tensions[200, 4] = np.nan
    static = tensions[0].copy()
    low, high = np.full(9, np.inf), np.full(9, -np.inf)
    total, square = np.zeros(9), np.zeros(9)
    for row in tensions:
        np.minimum(low, row, out=low)
        np.maximum(high, row, out=high)
        shifted = row - static
        total += shifted
        square += shifted * shifted
    envelope = TensionEnvelope(9, 0.0, static)
    for first in range(0, 500, 137):  # blocks, as a stream gives them
        envelope._accumulate(tensions[first:first + 137], compiled=compiled)
    got = envelope.values()
    np.testing.assert_array_equal(got["tension_min"], low)
    np.testing.assert_array_equal(got["tension_max"], high)
    np.testing.assert_array_equal(got["tension_mean"], static + total / 500)
    variance = np.maximum(square / 500 - (total / 500) ** 2, 0.0)
    np.testing.assert_array_equal(got["tension_std"], np.sqrt(variance))
    assert np.isnan(got["tension_min"][4]) and np.isnan(got["tension_max"][4])
