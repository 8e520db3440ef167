"""A dataset of plain numpy arrays: what a run writes to NetCDF without importing xarray.

:class:`PlainDataset` holds named variables (dimensions, a numpy array, attributes), which of
them are coordinates, and the group attributes: the part of :class:`xarray.Dataset` that
:func:`moorline.io.netcdf_write.write_dataset` and the summaries read (``ds[name].values``,
``.dims``, ``.attrs``, ``ds.sizes``, ``ds.coords``, ``ds.data_vars``, ``name in ds``).
:meth:`PlainDataset.to_xarray` gives the same dataset in xarray (imported there), with the
variables in the same order: data variables first, then coordinates, each in the order given
(xarray's own order for ``xr.Dataset(data_vars, coords=coords)``), so a group written from
either holds the same variables, dimensions, attributes and values.

Variables are given as xarray takes them: ``(dims, values)`` tuples, or for a dimension
coordinate a 1-D sequence (its dimension is its own name).
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    import xarray as xr

__all__ = ["PlainDataset", "PlainResult", "PlainVariable"]


class PlainVariable:
    """One variable: ``dims`` (names), ``values`` (a numpy array of that many axes) and
    ``attrs`` (a dict; ``units`` and ``long_name`` in a results group)."""

    __slots__ = ("attrs", "dims", "values")

    def __init__(self, dims: tuple[str, ...], values: Any,
                 attrs: Mapping[str, Any] | None = None) -> None:
        self.dims = tuple(str(d) for d in dims)
        self.values = np.asarray(values)
        self.attrs = dict(attrs or {})
        if self.values.ndim != len(self.dims):
            raise ValueError(f"dimensions {self.dims} do not match values of shape "
                             f"{self.values.shape}")

    @property
    def shape(self) -> tuple[int, ...]:
        return self.values.shape

    @property
    def dtype(self) -> np.dtype:
        return self.values.dtype

    def __len__(self) -> int:
        return len(self.values)


def _variable(name: str, spec: Any, coordinate: bool) -> PlainVariable:
    """A :class:`PlainVariable` from ``(dims, values[, attrs])``, a variable, or (for a
    coordinate) a 1-D sequence on the dimension ``name``."""
    if isinstance(spec, PlainVariable):
        return PlainVariable(spec.dims, spec.values, spec.attrs)
    if isinstance(spec, tuple) and len(spec) in (2, 3):
        dims = (spec[0],) if isinstance(spec[0], str) else tuple(spec[0])
        return PlainVariable(dims, spec[1], spec[2] if len(spec) == 3 else None)
    if coordinate:
        return PlainVariable((name,), spec)
    raise TypeError(f"variable {name!r}: give (dims, values), not {type(spec).__name__}")


class PlainDataset:
    """Variables, coordinate names and attributes of one results group.

    Parameters
    ----------
    data_vars, coords
        As for :class:`xarray.Dataset`: ``name -> (dims, values)``; a coordinate may be a
        1-D sequence (a dimension coordinate).
    attrs
        Group attributes.

    Raises
    ------
    ValueError
        When two variables give a dimension different sizes, or a name is both a data
        variable and a coordinate.
    """

    def __init__(self, data_vars: Mapping[str, Any] | None = None,
                 coords: Mapping[str, Any] | None = None,
                 attrs: Mapping[str, Any] | None = None) -> None:
        data_vars, coords = dict(data_vars or {}), dict(coords or {})
        both = set(data_vars) & set(coords)
        if both:
            raise ValueError(f"{sorted(both)} are both data variables and coordinates")
        self.variables: dict[str, PlainVariable] = {
            **{str(k): _variable(str(k), v, False) for k, v in data_vars.items()},
            **{str(k): _variable(str(k), v, True) for k, v in coords.items()}}
        self._coord_names = [str(k) for k in coords]
        self.attrs: dict[str, Any] = dict(attrs or {})
        self.sizes  # noqa: B018  (checks the dimension sizes agree)

    @property
    def sizes(self) -> dict[str, int]:
        """Dimension sizes, in order of first appearance over the variables."""
        sizes: dict[str, int] = {}
        for name, var in self.variables.items():
            for dim, n in zip(var.dims, var.shape, strict=True):
                if sizes.setdefault(dim, n) != n:
                    raise ValueError(f"variable {name!r}: dimension {dim!r} has size {n}, "
                                     f"elsewhere {sizes[dim]}")
        return sizes

    @property
    def dims(self) -> dict[str, int]:
        """The dimension sizes (as :attr:`sizes`)."""
        return self.sizes

    @property
    def coords(self) -> dict[str, PlainVariable]:
        """The coordinates, in the order given."""
        return {k: self.variables[k] for k in self._coord_names}

    @property
    def data_vars(self) -> dict[str, PlainVariable]:
        """The data variables (not coordinates), in the order given."""
        coords = set(self._coord_names)
        return {k: v for k, v in self.variables.items() if k not in coords}

    def __getitem__(self, name: str) -> PlainVariable:
        return self.variables[name]

    def __contains__(self, name: object) -> bool:
        return name in self.variables

    def __iter__(self) -> Iterator[str]:
        return iter(self.data_vars)

    def __len__(self) -> int:
        return len(self.data_vars)

    def to_xarray(self) -> xr.Dataset:
        """The same dataset as an :class:`xarray.Dataset` (variables, coordinates, attributes
        and order)."""
        import xarray as xr

        def spec(var: PlainVariable) -> xr.Variable:
            return xr.Variable(var.dims, var.values, dict(var.attrs))

        return xr.Dataset({k: spec(v) for k, v in self.data_vars.items()},
                          coords={k: spec(v) for k, v in self.coords.items()},
                          attrs=dict(self.attrs))


class PlainResult:
    """Mixin of the result classes: :meth:`to_xarray` from their :meth:`to_plain`."""

    def to_plain(self) -> PlainDataset:  # pragma: no cover - every result defines it
        raise NotImplementedError

    def to_xarray(self) -> xr.Dataset:
        """The result's dataset (:meth:`to_plain`) as an :class:`xarray.Dataset`."""
        return self.to_plain().to_xarray()
