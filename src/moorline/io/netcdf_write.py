"""Write an in-memory dataset to a NetCDF-4 file or group with netCDF4 directly.

The dataset is a :class:`moorline.plain_dataset.PlainDataset` (numpy arrays: what a run
writes, without importing xarray) or an :class:`xarray.Dataset`; both give the same file.

xarray's own ``to_netcdf`` asks dask for the active scheduler to pick a write lock, which
imports dask and dask.distributed when they are installed (about 0.5 s of a ``moorline run``
that uses neither). Results here are plain in-memory datasets, so the part of xarray's CF
encoding they need is small and is written out below; files read back with
``xarray.open_dataset`` give the same dataset (tested against ``to_netcdf`` in
``tests/test_netcdf_write.py``):

- float variables get ``_FillValue = NaN`` (xarray's default);
- booleans are stored as ``int8`` with the attribute ``dtype = "bool"`` (xarray decodes them);
- strings as NetCDF-4 variable-length strings;
- non-dimension coordinates are listed in each data variable's ``coordinates`` attribute
  (those whose dimensions it has), the rest in the global ``coordinates`` attribute;
- attributes: ``bool`` as ``int``, ``None`` as ``""``.

Dates, times as ``datetime64`` and complex numbers are refused (results carry none).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any, Literal

import numpy as np

__all__ = ["nc_attrs", "put_rows", "write_dataset", "write_into"]


def nc_attrs(attrs: Mapping[str, Any]) -> dict[str, Any]:
    """Attributes NetCDF can store: ``bool`` as ``int``, ``None`` as ``""``."""
    return {str(k): int(v) if isinstance(v, (bool, np.bool_)) else ("" if v is None else v)
            for k, v in attrs.items()}


def write_dataset(ds: Any, path: str | Path, *, group: str | None = None,
                  mode: Literal["w", "a"] = "w", unlimited_dims: Iterable[str] = (),
                  chunksizes: Mapping[str, tuple[int, ...]] | None = None) -> None:
    """Write ``ds`` to ``path`` (``mode="w"``: a new file; ``"a"``: add to an existing one).

    Parameters
    ----------
    ds
        An in-memory :class:`~moorline.plain_dataset.PlainDataset` or
        :class:`xarray.Dataset`.
    path
        The NetCDF-4 file.
    group
        Group to create (``None``: the root group); it must not exist yet.
    mode
        ``"w"`` replaces the file, ``"a"`` appends (the file is created when missing).
    unlimited_dims
        Dimensions created unlimited (e.g. ``time`` of a streamed history).
    chunksizes
        Chunk shape per variable name.

    Raises
    ------
    ValueError
        When ``group`` already exists, or a variable has a type this writer does not encode.
    """
    import netCDF4

    path = Path(path)
    mode = "a" if mode == "a" and path.exists() else "w"
    with netCDF4.Dataset(path, mode, format="NETCDF4") as root:
        write_into(root, ds, group=group, unlimited_dims=unlimited_dims, chunksizes=chunksizes)


def write_into(root: Any, ds: Any, *, group: str | None = None,
               unlimited_dims: Iterable[str] = (),
               chunksizes: Mapping[str, tuple[int, ...]] | None = None,
               unfilled: Iterable[str] = (),
               chunk_cache: Mapping[str, int] | None = None) -> Any:
    """Write ``ds`` into an open :class:`netCDF4.Dataset` ``root`` (as :func:`write_dataset`,
    which opens and closes the file around it); returns the group written (``root`` itself
    when ``group`` is ``None``).

    ``unfilled`` (variables of which the caller writes every value, the histories of a
    stream) are defined in netCDF's no-fill mode: HDF5 does not fill their new chunks before
    they are written (with their ``_FillValue`` attribute as the others: readers see the same
    dataset), so a chunk written whole is written once, straight from the caller's array,
    when it does not fit the variable's chunk cache. One difference remains: read past its
    own length (shorter than its unlimited dimension, which a stream's variables never are
    but after a SIGKILL in the middle of a sync), such a variable gives netCDF's default
    fill (9.97e36) where a filled one gives its ``_FillValue``. ``chunk_cache``: that cache's size
    [bytes] per variable name, set at definition (later, netCDF reopens the dataset).

    Raises
    ------
    ValueError
        When ``group`` already exists, or a variable has a type this writer does not encode.
    """
    unlimited, unfilled = set(unlimited_dims), set(unfilled)
    chunks, caches = dict(chunksizes or {}), dict(chunk_cache or {})
    if group is None:
        target = root
    elif group in root.groups:
        raise ValueError(f"{root.filepath()} already has a group {group!r}")
    else:
        target = root.createGroup(group)
    for dim, size in ds.sizes.items():
        target.createDimension(str(dim), None if dim in unlimited else int(size))
    coordinates = _coordinates(ds)
    # everything is defined before any value is written: netCDF-4 leaves define mode at a
    # write and re-enters it at the next definition, each switch writing the metadata of the
    # whole file (interleaved, the skeleton of a dynamics group took 9 ms instead of 5)
    defined = []
    for name, var in ds.variables.items():
        key = str(name)
        if key in unfilled:
            target.set_fill_off()  # the default of the variables defined from here
        nc_var, values = _define_variable(target, key, var, chunks.get(key),
                                          coordinates.get(key))
        if key in unfilled:
            target.set_fill_on()
        defined.append((nc_var, values))
    attrs = nc_attrs(ds.attrs)
    if coordinates.get(None):
        attrs["coordinates"] = coordinates[None]
    target.setncatts(attrs)
    for nc_var, values in defined:
        if not values.size:
            continue
        if values.ndim:
            put_rows(nc_var, values)
        else:
            nc_var[...] = values.item() if values.dtype == object else values
    for name, size in caches.items():  # once the datasets exist (netCDF sizes it before)
        target[name].set_var_chunk_cache(size=int(size))
    return target


def put_rows(variable: Any, values: np.ndarray, first: int = 0) -> None:
    """Write ``values`` into the open netCDF4 ``variable`` from index ``first`` of its first
    dimension (whole along the others; an unlimited first dimension grows as needed).

    ``variable[first:first + len(values)] = values`` does the same, but netCDF4's slicing
    (``_StartCountStride``: a dozen numpy calls) costs about 0.14 ms a call, fifteen times
    the write of a small array; ``Variable._put`` (netCDF4's own writer under the slicing:
    the C ``nc_put_vara`` with a start and count, string variables encoded as there) is
    called directly when the values already have the variable's shape. Falls back to the
    slicing otherwise or when that method is missing.
    """
    values = np.asarray(values)
    put = getattr(variable, "_put", None)
    if (put is None or values.ndim == 0 or values.ndim != variable.ndim
            or values.shape[1:] != _trailing_shape(variable)):
        variable[first:first + len(values)] = values
        return
    if values.dtype != variable.dtype and values.dtype != object:
        values = values.astype(variable.dtype)
    put(np.ascontiguousarray(values), [int(first), *(0 for _ in values.shape[1:])],
        list(values.shape), [1] * values.ndim)


def _trailing_shape(variable: Any) -> tuple[int, ...]:
    """The sizes of ``variable``'s dimensions after the first (``variable.shape`` asks the
    length of an unlimited first dimension, which netCDF-4 finds by querying every
    variable of the group: ~17 us a call)."""
    get_dims = getattr(variable, "get_dims", None)
    if get_dims is None:
        return tuple(variable.shape[1:])
    return tuple(len(dim) for dim in get_dims()[1:])


def _coordinates(ds: Any) -> dict[str | None, str]:
    """The ``coordinates`` attribute per data variable, and the global one under ``None``
    (xarray's ``conventions._encode_coordinates`` rule)."""
    dims = set(ds.dims)  # once: a PlainDataset works its sizes out at every call
    non_dim = [str(c) for c in ds.coords if c not in dims]
    attached: dict[str | None, set[str]] = {}
    used: set[str] = set()
    for coord in non_dim:
        coord_dims = set(ds[coord].dims)
        for name, var in ds.data_vars.items():
            if coord_dims <= set(var.dims):
                attached.setdefault(str(name), set()).add(coord)
                used.add(coord)
    out: dict[str | None, str] = {k: " ".join(sorted(v)) for k, v in attached.items()}
    rest = sorted(set(non_dim) - used)
    if rest:
        out[None] = " ".join(rest)
    return out


def _define_variable(target: Any, name: str, var: Any, chunks: tuple[int, ...] | None,
                     coordinates: str | None) -> tuple[Any, np.ndarray]:
    """Create variable ``name`` with its attributes; returns it and the values to write
    (encoded: booleans as ``int8``, strings as objects)."""
    values = np.asarray(var.values)
    attrs = nc_attrs(var.attrs)
    kind = values.dtype.kind
    options: dict[str, Any] = {}
    if chunks is not None:
        options["chunksizes"] = tuple(int(c) for c in chunks)
    if kind == "f":
        dtype: Any = values.dtype
        options["fill_value"] = np.nan
    elif kind in "iu":
        dtype = values.dtype
    elif kind == "b":
        dtype, values = np.int8, values.astype(np.int8)
        attrs["dtype"] = "bool"
    elif kind in "USO":
        dtype = str
        values = np.asarray(values, dtype=object)
        if not all(isinstance(v, str) for v in values.flat):
            raise ValueError(f"variable {name!r}: only strings may be stored as objects")
    else:
        raise ValueError(f"variable {name!r}: dtype {values.dtype} is not written by "
                         "moorline.io.netcdf_write")
    nc_var = target.createVariable(name, dtype, tuple(str(d) for d in var.dims), **options)
    if coordinates:
        attrs["coordinates"] = coordinates
    nc_var.setncatts(attrs)
    return nc_var, values
