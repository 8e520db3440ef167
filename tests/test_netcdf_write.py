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
    from moorline.io import load_case_text
    from moorline.model import ModalSettings
    from moorline.solvers.modal import solve_modes
    from moorline.solvers.statics import solve_statics

    text = (Path(__file__).parents[1] / "cases" / "oc3_line.yaml").read_text()
    # straight elements: a modal analysis refuses sag-corrected ones
    system = load_case_text(text.replace("element: sag_corrected", "element: straight"))
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


def _structure(path: Path, group: str | None = None) -> list:
    """Dimensions, variables (dtype, dimensions, attributes in order, raw values) and group
    attributes of a file or group, read with netCDF4 alone."""
    import netCDF4

    with netCDF4.Dataset(path) as root:
        g = root[group] if group else root
        dims = [(n, len(d), d.isunlimited()) for n, d in g.dimensions.items()]
        variables = []
        for name, var in g.variables.items():
            var.set_auto_maskandscale(False)
            values = np.asarray(var[...])
            attrs = [(k, repr(np.asarray(var.getncattr(k)).tolist())) for k in var.ncattrs()]
            variables.append((name, str(var.dtype), var.dimensions, attrs,
                              values.astype(str).tolist() if values.dtype.kind in "OU"
                              else values.tobytes()))
        attrs = [(k, repr(np.asarray(g.getncattr(k)).tolist())) for k in g.ncattrs()]
    return [dims, variables, attrs]


@pytest.fixture(scope="module")
def plain_results() -> dict:
    """The plain datasets of a statics, a modal analysis and 2 s of dynamics of the OC3 line."""
    import dataclasses

    from moorline.io import load_case
    from moorline.model import ModalSettings
    from moorline.solvers.dynamics import simulate
    from moorline.solvers.modal import solve_modes
    from moorline.solvers.statics import solve_statics

    system = load_case(Path(__file__).parents[1] / "cases" / "oc3_dynamics.yaml")
    static = solve_statics(system)
    settings = dataclasses.replace(system.first("dynamics"), duration=2.0)
    return {"statics": static.to_plain(),
            "modal": solve_modes(system, ModalSettings(n_modes=3), static).to_plain(),
            "dynamics": simulate(system, settings, static).to_plain()}


@pytest.mark.parametrize("kind", ["statics", "modal", "dynamics"])
def test_plain_datasets_write_the_files_of_their_xarray_twins(plain_results: dict, kind: str,
                                                              tmp_path: Path) -> None:
    """A run writes numpy containers (moorline.plain_dataset), the Python API returns xarray
    (to_xarray): the two files are the same to the byte of every value, attribute and
    dimension, in the same order; and xarray's own to_netcdf of the xarray twin reads back
    identical to the plain dataset's file."""
    plain = plain_results[kind]
    write_dataset(plain, tmp_path / "plain.nc", group=kind)
    write_dataset(plain.to_xarray(), tmp_path / "xarray.nc", group=kind)
    assert _structure(tmp_path / "plain.nc", kind) == _structure(tmp_path / "xarray.nc", kind)
    plain.to_xarray().to_netcdf(tmp_path / "theirs.nc", engine="netcdf4", group=kind)
    ours, theirs = _reread(tmp_path / "plain.nc", kind), _reread(tmp_path / "theirs.nc", kind)
    xr.testing.assert_identical(ours, theirs)
    assert list(ours.variables) == list(theirs.variables)


@pytest.mark.parametrize("kind", ["statics", "dynamics"])
def test_read_plain_gives_back_what_was_written(plain_results: dict, kind: str,
                                               tmp_path: Path) -> None:
    """netCDF4 read-back (the summary of a run that raised): the same variables, coordinates,
    values and attributes as the dataset written, and xarray reads the same dataset."""
    from moorline.io.netcdf_read import read_plain

    plain = plain_results[kind]
    write_dataset(plain, tmp_path / "r.nc", group=kind)
    back = read_plain(tmp_path / "r.nc", kind)
    assert set(back.variables) == set(plain.variables)
    assert set(back.coords) == set(plain.coords)
    assert back.sizes == plain.sizes
    for name, var in plain.variables.items():
        got = back[name]
        assert got.dims == var.dims and list(got.attrs) == list(var.attrs), name
        for key, value in var.attrs.items():
            np.testing.assert_array_equal(got.attrs[key], value, err_msg=f"{name}.{key}")
        np.testing.assert_array_equal(got.values, var.values, err_msg=name)
    assert back.attrs.keys() == plain.attrs.keys()
    xr.testing.assert_identical(back.to_xarray(), _reread(tmp_path / "r.nc", kind))
    assert list(back.to_xarray().variables) == list(_reread(tmp_path / "r.nc", kind).variables)


@pytest.mark.skipif(not (Path(__file__).parents[1] / "cases" / "oc3_dynamics.yaml").is_file(),
                    reason="no case file")
def test_modes_rewrites_the_other_groups_as_xarray_did(tmp_path: Path) -> None:
    """``moorline modes`` replacing the modal group of a run's results rewrites the file: the
    other groups (a statics and a streamed dynamics group) are read back with netCDF4 alone
    (read_plain) and written again, giving the groups that xarray's read-back written by the
    same writer gives (the former path), variable order included."""
    import re
    import shutil

    from click.testing import CliRunner

    from moorline.cli import cli
    from moorline.io.writers import write_group

    text = (Path(__file__).parents[1] / "cases" / "oc3_dynamics.yaml").read_text("utf-8")
    case = tmp_path / "short.yaml"
    case.write_text(re.sub(r"duration: *[0-9.]+", "duration: 0.5", text), encoding="utf-8")
    out = tmp_path / "out"
    args = [str(case), "--out", str(out), "-q"]
    assert CliRunner().invoke(cli, ["run", *args, "--no-plots"]).exit_code == 0
    results = out / "oc3-dynamics" / "results.nc"
    shutil.copy(results, tmp_path / "run.nc")
    for n in ("3", "2"):  # the second replaces the first's modal group
        done = CliRunner().invoke(cli, ["modes", *args, "--n", n, "--no-plots", "--json"])
        assert done.exit_code == 0, done.output
    assert not list((out / "oc3-dynamics").glob("*.png"))
    for group in ("statics", "dynamics"):
        expected = tmp_path / f"{group}.nc"
        write_group(_reread(tmp_path / "run.nc", group), expected, group)
        assert _structure(results, group) == _structure(expected, group)
    assert _reread(results, "modal").sizes["mode"] == 2


class _Sliced:
    """A netCDF4 variable seen through its slicing alone (no ``_put``): :func:`put_rows`'
    fallback."""

    def __init__(self, variable) -> None:
        self.variable, self.shape, self.dtype = variable, variable.shape, variable.dtype

    def __setitem__(self, key, values) -> None:
        self.variable[key] = values


def test_put_rows_writes_what_slicing_writes(tmp_path: Path) -> None:
    """Rows appended in pieces along an unlimited dimension (floats, integers, strings), and
    whole fixed variables, by netCDF4's ``_put`` and by its slicing: the same values bit for
    bit, the same lengths."""
    import netCDF4

    from moorline.io.netcdf_write import put_rows

    rng = np.random.default_rng(5)
    floats, ints = rng.normal(size=(9, 4, 3)), rng.integers(-9, 9, size=(9, 4))
    words = np.array([f"w{k}" * (k % 3 + 1) for k in range(9)], dtype=object)
    path = tmp_path / "rows.nc"
    with netCDF4.Dataset(path, "w") as root:
        root.createDimension("time", None)
        root.createDimension("n", 4)
        root.createDimension("xyz", 3)
        for way in ("put", "sliced"):
            targets = (root.createVariable(f"f_{way}", "f8", ("time", "n", "xyz"),
                                           fill_value=np.nan, chunksizes=(2, 4, 3)),
                       root.createVariable(f"i_{way}", "i8", ("time", "n")),
                       root.createVariable(f"s_{way}", str, ("time",)))
            fixed = root.createVariable(f"fixed_{way}", "f8", ("n",))
            if way == "sliced":
                targets = tuple(_Sliced(v) for v in targets)
                fixed = _Sliced(fixed)
            for first, last in ((0, 1), (1, 5), (5, 9)):
                for target, values in zip(targets, (floats, ints, words), strict=True):
                    put_rows(target, values[first:last], first)
            put_rows(fixed, floats[0, :, 1])
    with netCDF4.Dataset(path) as root:
        for name in ("f", "i", "s", "fixed"):
            put, sliced = root[f"{name}_put"][...], root[f"{name}_sliced"][...]
            assert put.shape == sliced.shape
            assert put.dtype == sliced.dtype and np.all(put == sliced), name
        assert root["f_put"][...].tobytes() == floats.tobytes()
        assert list(root["s_put"][...]) == list(words)


def test_unfilled_variables_keep_their_fill_value_attribute(tmp_path: Path) -> None:
    """``unfilled``: no HDF5 fill (netCDF's no-fill mode) for the named variables only; their
    ``_FillValue`` attribute is there as for the others, so xarray reads the same dataset."""
    import netCDF4

    from moorline.io.netcdf_write import write_into

    ds = xr.Dataset({"a": (("time", "n"), np.arange(6.0).reshape(3, 2)),
                     "b": (("time", "n"), -np.arange(6.0).reshape(3, 2))},
                    coords={"time": [0.0, 1.0, 2.0]})
    paths = tmp_path / "filled.nc", tmp_path / "unfilled.nc"
    for path, unfilled in zip(paths, ((), ("a", "time")), strict=True):
        with netCDF4.Dataset(path, "w") as root:
            write_into(root, ds, unlimited_dims=["time"], unfilled=unfilled,
                       chunk_cache={"a": 0})
    with netCDF4.Dataset(paths[1]) as root:
        assert root["a"].get_fill_value() is None and root["time"].get_fill_value() is None
        assert np.isnan(root["b"].get_fill_value())
        assert all(np.isnan(root[name].getncattr("_FillValue")) for name in ("a", "b", "time"))
    xr.testing.assert_identical(_reread(paths[0]), _reread(paths[1]))
