"""Compare two moorline results files group by group, variable by variable.

Usage: ``python benchmarks/compare_results.py BEFORE.nc AFTER.nc [--rtol R]``.

Read with netCDF4 alone (no decoding: masks and scaling off), the two files must have the
same groups, the same dimensions (names, sizes, unlimited or not) in the same order, the same
variables in the same order with the same dtype, dimensions, chunking and attributes (names,
order, values), the same group attributes, and equal values: bit for bit by default (NaN equal
to NaN), or within ``--rtol`` relative to the largest magnitude of the variable (for runs whose
floating-point sums may be ordered differently). Prints every difference and a one-line
verdict; exit code 0 when the files match, 1 otherwise. Used to check that a change of the
writer (issue 16: NetCDF written from plain numpy containers instead of xarray) leaves the
files' content as it was.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

import netCDF4
import numpy as np


def _same(a: Any, b: Any, rtol: float) -> bool:
    a, b = np.asarray(a), np.asarray(b)
    if a.shape != b.shape or a.dtype.kind != b.dtype.kind:
        return False
    if a.dtype.kind != "f":
        return bool(np.array_equal(a, b))
    nan = np.isnan(a)
    if not np.array_equal(nan, np.isnan(b)):
        return False
    if rtol == 0.0:
        return bool(np.array_equal(a[~nan], b[~nan]))
    scale = float(np.abs(a[~nan]).max(initial=0.0))
    return bool(np.all(np.abs(a[~nan] - b[~nan]) <= rtol * scale))


def _attrs(obj: Any) -> list[tuple[str, Any]]:
    return [(name, obj.getncattr(name)) for name in obj.ncattrs()]


def _compare_attrs(where: str, a: Any, b: Any, rtol: float, out: list[str]) -> None:
    left, right = _attrs(a), _attrs(b)
    if [k for k, _ in left] != [k for k, _ in right]:
        out.append(f"{where}: attributes {[k for k, _ in left]} != {[k for k, _ in right]}")
        return
    for (key, u), (_, v) in zip(left, right, strict=True):
        if not _same(u, v, rtol):
            out.append(f"{where}: attribute {key}: {u!r} != {v!r}")


def compare_groups(a: Any, b: Any, where: str, rtol: float, out: list[str]) -> None:
    """Append the differences of NetCDF groups ``a`` and ``b`` (recursively) to ``out``."""
    _compare_attrs(where or "/", a, b, rtol, out)
    dims_a = [(n, len(d), d.isunlimited()) for n, d in a.dimensions.items()]
    dims_b = [(n, len(d), d.isunlimited()) for n, d in b.dimensions.items()]
    if dims_a != dims_b:
        out.append(f"{where or '/'}: dimensions {dims_a} != {dims_b}")
    if list(a.variables) != list(b.variables):
        out.append(f"{where or '/'}: variables {list(a.variables)} != {list(b.variables)}")
    for name in a.variables:
        if name not in b.variables:
            continue
        u, v = a.variables[name], b.variables[name]
        label = f"{where}/{name}"
        for what, x, y in (("dtype", u.dtype, v.dtype), ("dimensions", u.dimensions,
                                                           v.dimensions),
                           ("chunking", u.chunking(), v.chunking())):
            if x != y:
                out.append(f"{label}: {what} {x} != {y}")
        _compare_attrs(label, u, v, rtol, out)
        u.set_auto_maskandscale(False)
        v.set_auto_maskandscale(False)
        if not _same(u[...], v[...], rtol):
            out.append(f"{label}: values differ")
    if list(a.groups) != list(b.groups):
        out.append(f"{where or '/'}: groups {list(a.groups)} != {list(b.groups)}")
    for name in a.groups:
        if name in b.groups:
            compare_groups(a.groups[name], b.groups[name], f"{where}/{name}", rtol, out)


def compare_files(before: Path, after: Path, rtol: float = 0.0) -> list[str]:
    """The differences between two NetCDF files (empty: they match)."""
    out: list[str] = []
    with netCDF4.Dataset(before) as a, netCDF4.Dataset(after) as b:
        compare_groups(a, b, "", rtol, out)
    return out


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("before", type=Path)
    parser.add_argument("after", type=Path)
    parser.add_argument("--rtol", type=float, default=0.0,
                        help="relative tolerance on values (default 0: bit for bit)")
    args = parser.parse_args(argv)
    differences = compare_files(args.before, args.after, args.rtol)
    for line in differences:
        print(line)
    verdict = "differ" if differences else "match"
    print(f"{args.before} and {args.after}: {verdict} ({len(differences)} differences, "
          f"values {'bit for bit' if args.rtol == 0 else f'within rtol {args.rtol:g}'})")
    return 1 if differences else 0


if __name__ == "__main__":
    sys.exit(main())
