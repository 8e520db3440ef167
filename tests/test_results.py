"""One result convention: frozen results with success/status/message, one dataset builder
(group attributes, units and long_name of every variable), one variable list for the streamed
and the in-memory dynamics dataset, one table of analysis kinds."""

from __future__ import annotations

import dataclasses
import typing
from pathlib import Path

import netCDF4
import numpy as np
import pytest
import xarray as xr
import yaml
from click.testing import CliRunner

from moorline.analyses import KINDS, resolve
from moorline.cli import cli
from moorline.datasets import BODY_DOFS, build_dataset, group_attrs
from moorline.io import load_case
from moorline.io.schema import AnalysisSpec
from moorline.model import StaticsSettings, StochasticSettings
from moorline.results import DynamicResult, StaticResult

ROOT = Path(__file__).resolve().parents[1]
OC3_DYNAMICS = ROOT / "cases" / "oc3_dynamics.yaml"


@pytest.fixture(scope="module")
def short_oc3(tmp_path_factory) -> tuple[Path, Path]:
    """cases/oc3_dynamics.yaml with 2 s of dynamics, run through ``moorline run``."""
    if not OC3_DYNAMICS.is_file():
        pytest.skip("cases/oc3_dynamics.yaml not present")
    tmp = tmp_path_factory.mktemp("oc3")
    case = yaml.safe_load(OC3_DYNAMICS.read_text())
    dynamics = next(a for a in case["analyses"] if a["kind"] == "dynamics")
    dynamics["duration"] = 2.0
    path = tmp / "oc3_dynamics_short.yaml"
    path.write_text(yaml.safe_dump(case))
    result = CliRunner().invoke(cli, ["run", str(path), "--out", str(tmp / "out"), "--quiet"])
    assert result.exit_code == 0, result.output
    return path, tmp / "out" / "oc3-dynamics" / "results.nc"


def test_oc3_dynamics_file_has_fairlead_tension_and_describes_every_variable(
        short_oc3, undescribed) -> None:
    _, results = short_oc3
    assert undescribed(results) == []
    with netCDF4.Dataset(results) as root:
        assert list(root.groups) == ["statics", "dynamics"]
    with xr.open_dataset(results, group="dynamics") as ds:
        assert ds["fairlead_tension"].dims == ("time", "line")
        assert ds["fairlead_tension"].attrs["units"] == "N"
        # the tension at end b: the norm of the force the line exerts on its end b point
        end_b = np.linalg.norm(ds["end_force"].sel(end="b").values, axis=-1)
        np.testing.assert_allclose(ds["fairlead_tension"].values, end_b, rtol=1e-15)
        assert ds.sizes["time"] == 9  # 0, 0.25, ..., 2 s (output every 0.25 s)
        assert ds.attrs["status"] == "completed" and ds.attrs["success"] == 1


def test_streamed_group_equals_the_in_memory_dataset(short_oc3) -> None:
    from moorline.solvers.dynamics import simulate
    from moorline.solvers.statics import solve_statics

    path, results = short_oc3
    system = load_case(path)
    static = solve_statics(system, system.first(StaticsSettings))
    memory = simulate(system, system.first("dynamics"), initial=static).to_xarray()
    with xr.open_dataset(results, group="dynamics") as streamed:
        streamed = streamed.load()
    assert streamed.attrs.pop("output_every") == 0.25  # only the stream knows it
    assert len(streamed.attrs.pop("line_MBL")) == 3  # the run adds the lines' MBL
    xr.testing.assert_identical(streamed, memory)


def test_the_statics_group_equals_its_result(short_oc3) -> None:
    from moorline.solvers.statics import solve_statics

    path, results = short_oc3
    system = load_case(path)
    memory = solve_statics(system, system.first(StaticsSettings)).to_xarray()
    with xr.open_dataset(results, group="statics") as written:
        written = written.load()
        assert len(written.attrs.pop("line_MBL")) == 3  # the run adds the lines' MBL
        xr.testing.assert_identical(written, memory)


def test_the_builder_refuses_a_variable_it_cannot_describe() -> None:
    attrs = group_attrs("statics", case="c", units="SI", success=True, status="converged",
                        message="")
    with pytest.raises(KeyError, match="mystery"):
        build_dataset("statics", {"mystery": (("node",), [1.0])}, {}, attrs)
    ds = build_dataset("statics", {"tension": (("element",), [1.0])}, {}, attrs)
    assert ds["tension"].attrs == {"units": "N", "long_name": "element tension"}
    us = build_dataset("statics", {"tension": (("element",), [1.0])}, {},
                       {**attrs, "units": "US"})
    assert us["tension"].attrs["units"] == "lbf"


@pytest.mark.parametrize("kind", list(KINDS))
def test_every_kind_returns_a_frozen_result_with_the_convention(kind: str) -> None:
    cls = KINDS[kind].result_type()
    assert cls.__dataclass_params__.frozen
    names = {f.name for f in dataclasses.fields(cls)} | set(dir(cls))
    assert {"success", "status", "message", "counters", "case", "units", "settings",
            "to_xarray"} <= names


def test_dynamic_result_keeps_its_positional_constructor_and_says_its_status() -> None:
    from moorline.mesh import discretize

    mesh = discretize(load_case(ROOT / "cases" / "oc3_line.yaml"))
    empty = np.zeros((0, mesh.n_nodes, 3))
    args = (np.zeros(0), empty, empty, np.zeros((0, mesh.n_elements)),
            np.zeros((0, len(mesh.line_names), 2, 3)), {}, mesh)
    assert DynamicResult(True, "done", *args).status == "completed"
    failed = DynamicResult(False, "t = 1 s, line1 element 3: no convergence", *args)
    assert failed.status == "failed" and not failed.to_xarray().attrs["success"]
    with pytest.raises(dataclasses.FrozenInstanceError):
        failed.success = True  # type: ignore[misc]


def test_the_table_of_kinds_is_what_the_schema_and_loader_read() -> None:
    union = typing.get_args(typing.get_args(AnalysisSpec)[0])
    tags = [typing.get_args(m.model_fields["kind"].annotation)[0] for m in union]
    assert tags == list(KINDS)
    for name, kind in KINDS.items():
        assert kind.settings().kind == name
        assert kind.spec_model() in union
        for ref in (kind.runner, kind.plot, kind.summary, kind.result):
            assert callable(resolve(ref)), ref
        # every settings field is a case-file key of its kind, with the same name
        spec_keys = set(kind.spec_model().model_fields)
        assert {f.name for f in dataclasses.fields(kind.settings)} == spec_keys


def test_a_body_dof_is_labelled_the_same_in_statics_dynamics_and_stochastic() -> None:
    assert BODY_DOFS == ("surge", "sway", "heave", "roll", "pitch", "yaw")
    system = load_case(ROOT / "cases" / "wang_box.yaml")
    from moorline.solvers.statics import solve_statics

    static: StaticResult = solve_statics(system)
    assert list(static.to_xarray()["dof"].values) == list(BODY_DOFS)


def test_a_stochastic_linearization_that_does_not_converge_is_returned_failed(
        tmp_path: Path, undescribed) -> None:
    from moorline.io.case_writer import write_case
    from moorline.verification.stochastic_riser import riser_system

    system = dataclasses.replace(riser_system(), analyses=(
        StaticsSettings(), StochasticSettings(method="direct", max_iterations=1,
                                              tolerance=1e-12)))
    path = write_case(system, tmp_path / "riser.yaml")
    result = CliRunner().invoke(cli, ["run", str(path), "--out", str(tmp_path / "out"),
                                      "--quiet"])
    assert result.exit_code == 1
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and "stochastic failed: " in lines[0]
    assert "did not converge in 1 iterations" in lines[0]
    results = tmp_path / "out" / system.name / "results.nc"
    assert undescribed(results) == []
    with xr.open_dataset(results, group="stochastic") as ds:  # what was computed is kept
        assert ds.attrs["success"] == 0 and ds.attrs["status"] == "failed"
        assert ds.attrs["iterations"] == 1


def test_seabed_length_of_a_taut_line_is_zero_and_of_a_lying_line_the_closed_forms() -> None:
    """An anchor held at the seabed surface is carried by the anchor: a taut line leaving it
    upwards has no length on the seabed (the closed form: 0; it counted half an element),
    while the OC3 line's seabed length stays the closed form's within one element."""
    from moorline.catenary import catenary_3d
    from moorline.solvers.statics import solve_statics

    root = Path(__file__).resolve().parents[1]
    taut = load_case(root / "cases" / "polyester_taut.yaml")
    result = solve_statics(taut)
    assert result.success
    for name in taut.lines:
        assert result.seabed_length(name) == 0.0, name
    oc3 = load_case(root / "cases" / "oc3_line.yaml")
    line, lt, env = oc3.lines["line1"], oc3.line_types["chain"], oc3.environment
    w = (lt.mass_per_length - env.water_density * np.pi * lt.diameter**2 / 4) * env.gravity
    exact = catenary_3d(oc3.points["anchor"].position, oc3.points["fairlead"].position,
                        line.length, lt.EA, w)[2].seabed_length
    got = solve_statics(oc3).seabed_length("line1")
    assert abs(got - exact) < line.length / line.segments
