"""moorline's own NetCDF writer against xarray's ``to_netcdf``: the files read back with
``xarray.open_dataset`` must be identical datasets (values, dtypes, coordinates, attributes)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from moorline.io.netcdf_write import write_dataset


def _reread(path: Path, group: str | None = None) -> xr.Dataset:
    with xr.open_dataset(path, group=group, engine="netcdf4") as opened:
        return opened.load()


def _assert_same(ds: xr.Dataset, tmp_path: Path, group: str | None = None) -> None:
    theirs, ours = tmp_path / "xarray.nc", tmp_path / "moorline.nc"
    ds.to_netcdf(theirs, engine="netcdf4", group=group)
    write_dataset(ds, ours, group=group)
    a, b = _reread(theirs, group), _reread(ours, group)
    xr.testing.assert_identical(a, b)
    assert list(a.variables) == list(b.variables)
    for name in a.variables:
        assert a[name].dtype == b[name].dtype, name


def test_every_kind_of_variable(tmp_path: Path) -> None:
    ds = xr.Dataset(
        {"tension": (("time", "element"), np.array([[1.0, np.nan], [3.0, 4.0]]),
                     {"units": "N", "long_name": "tension"}),
         "count": ((), np.int64(7), {"units": "1"}),
         "flag": (("element",), np.array([True, False])),
         "slack": ((), np.bool_(True)),
         "label": (("element",), np.array(["a", "bb"])),
         "scalar": ((), 2.5)},
        coords={"time": ("time", [0.0, 0.5], {"units": "s"}),
                "element": ("element", [0, 1]),
                "line": ("element", np.array(["L1", "L1"])),
                "arc": (("element",), [0.5, 1.5], {"units": "m"}),
                "depth": ((), 200.0),
                "node": ("node", [0, 1, 2]),
                "node_line": ("node", ["L1", "L1", "L1"])},
        attrs={"case": "x", "success": 1, "values": [1.0, 2.0], "count": 3})
    _assert_same(ds, tmp_path)
    (tmp_path / "g").mkdir()
    _assert_same(ds, tmp_path / "g", group="statics")


def test_results_of_the_analyses(tmp_path: Path) -> None:
    from moorline.io import load_case
    from moorline.model import ModalSettings
    from moorline.solvers.modal import solve_modes
    from moorline.solvers.statics import solve_statics

    system = load_case(Path(__file__).parents[1] / "cases" / "oc3_line.yaml")
    static = solve_statics(system)
    assert static.success
    _assert_same(static.to_xarray(), tmp_path)
    modes = solve_modes(system, ModalSettings(n_modes=3), static)
    (tmp_path / "m").mkdir()
    _assert_same(modes.to_xarray(), tmp_path / "m", group="modal")


def test_attributes_netcdf_cannot_hold(tmp_path: Path) -> None:
    path = tmp_path / "a.nc"
    write_dataset(xr.Dataset(attrs={"success": True, "note": None}), path)
    assert _reread(path).attrs == {"success": 1, "note": ""}


def test_existing_group_is_refused(tmp_path: Path) -> None:
    ds = xr.Dataset({"a": ("x", [1.0])})
    path = tmp_path / "f.nc"
    write_dataset(ds, path, group="g")
    write_dataset(ds, path, group="h", mode="a")
    with pytest.raises(ValueError, match="already has a group"):
        write_dataset(ds, path, group="g", mode="a")


def test_unsupported_dtype_is_refused(tmp_path: Path) -> None:
    ds = xr.Dataset({"z": ("x", np.array([1 + 2j]))})
    with pytest.raises(ValueError, match="not written"):
        write_dataset(ds, tmp_path / "c.nc")
