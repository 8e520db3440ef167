"""MoorDyn's 3-D seafloor file, read into a :class:`~moorline.model.Bathymetry`.

The format, as MoorDyn-C v2.7 reads it (``source/Seafloor.cpp``, ``Seafloor::setup``; the
file its ``tests/Mooring/3D_seafloor/make_3d_seafloor.py`` writes)::

    nx ny                      # number of x and y grid lines
    x_1 x_2 ... x_nx           # the x grid lines
    y_1 y_2 ... y_ny           # the y grid lines
    x y z                      # one row per grid node: its seabed height z (z up, < 0)
    ...

Columns are separated by blanks; blank lines are skipped. MoorDyn files each ``x y z`` row
under the grid line at or below ``x`` and ``y`` and leaves nodes without a row at ``z = 0``;
here every row must sit on a grid node (within 1e-6 of the grid spacing) and every node must
have exactly one row, so that a missing or misplaced row is an error, not a pit at the
surface. Heights are in the case's length unit (metres in a MoorDyn deck).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..errors import CaseError
from ..model import Bathymetry
from .files import MAX_TABLE_BYTES, file_problem
from .schema import check_number


def read_seafloor(path: str | Path, field: str | None = None) -> Bathymetry:
    """Read a MoorDyn 3-D seafloor file.

    Parameters
    ----------
    path
        The file.
    field
        The case key that names it (for error messages).

    Raises
    ------
    CaseError
        Naming the file, the line and what is wrong.
    """
    path = Path(path)
    problem = file_problem(path, MAX_TABLE_BYTES)
    if problem is not None:
        raise CaseError(f"cannot read seafloor file {str(path)!r}: {problem}", field=field)
    try:
        text = path.read_text(encoding="utf-8", errors="replace")
    except OSError as exc:
        raise CaseError(f"cannot read seafloor file {str(path)!r}: {exc}", field=field) from None
    rows = [(k + 1, line.split()) for k, line in enumerate(text.splitlines()) if line.strip()]

    def fail(reason: str, lineno: int | None = None) -> CaseError:
        where = f", line {lineno}" if lineno is not None else ""
        return CaseError(f"seafloor file {str(path)!r}{where}: {reason}", field=field)

    def numbers(lineno: int, tokens: list[str], count: int, what: str) -> list[float]:
        if len(tokens) != count:
            raise fail(f"{what}: expected {count} values, got {len(tokens)}", lineno)
        try:
            values = [float(t) for t in tokens]
        except ValueError:
            raise fail(f"{what}: not a number in {' '.join(tokens)!r}", lineno) from None
        for v in values:
            if (bad := check_number(v)) is not None:
                raise fail(f"{what}: {bad}", lineno)
        return values

    if len(rows) < 4:
        raise fail("needs the grid sizes, the x and y grid lines and at least one 'x y z' row "
                   f"(MoorDyn's format); the file has {len(rows)} non-blank lines")
    lineno, tokens = rows[0]
    if len(tokens) != 2 or not all(t.isdigit() for t in tokens):
        raise fail(f"the first line must be two counts 'nx ny', got {' '.join(tokens)!r}", lineno)
    nx, ny = int(tokens[0]), int(tokens[1])
    x = numbers(*rows[1], nx, "x grid lines")
    y = numbers(*rows[2], ny, "y grid lines")
    z = np.full((nx, ny), np.nan)
    for lineno, tokens in rows[3:]:
        px, py, pz = numbers(lineno, tokens, 3, "a grid node 'x y z'")
        i, j = _tick(x, px), _tick(y, py)
        if i is None or j is None:
            raise fail(f"({px:g}, {py:g}) is not a node of the grid", lineno)
        if not math.isnan(z[i, j]):
            raise fail(f"node ({px:g}, {py:g}) is given twice", lineno)
        z[i, j] = pz
    problem = grid_problem(x, y, z)
    if problem is not None:
        raise fail(problem)
    return Bathymetry(x=tuple(x), y=tuple(y), z=tuple(tuple(row) for row in z.tolist()))


def _tick(ticks: list[float], value: float) -> int | None:
    """Index of the grid line ``value`` sits on, or ``None``."""
    span = (ticks[-1] - ticks[0]) if len(ticks) > 1 else 1.0
    k = int(np.argmin(np.abs(np.asarray(ticks) - value)))
    return k if abs(ticks[k] - value) <= 1e-6 * max(abs(span), 1e-300) else None


def grid_problem(x: list[float], y: list[float], z) -> str | None:
    """What is wrong with a bathymetry grid (``None`` when nothing): at least two grid lines
    each way, strictly increasing, and a height below the free surface at every node (``z``
    is (nx, ny))."""
    for name, ticks in (("x", x), ("y", y)):
        if len(ticks) < 2:
            return f"needs at least 2 {name} grid lines, got {len(ticks)}"
        if np.any(np.diff(ticks) <= 0):
            return f"the {name} grid lines must increase strictly, got {list(ticks)}"
    if len(z) != len(x) or any(len(row) != len(y) for row in z):
        return (f"needs a height at each of the {len(x)} x {len(y)} grid nodes: {len(x)} rows "
                f"z[i] (one per x grid line) of {len(y)} heights z[i][j] (one per y grid line), "
                f"got {len(z)} rows of {sorted({len(row) for row in z})} heights")
    z = np.asarray(z, dtype=float)
    missing = np.argwhere(np.isnan(z))
    if len(missing):
        i, j = missing[0]
        return (f"no height at the grid node ({x[i]:g}, {y[j]:g}) ({len(missing)} of "
                f"{z.size} nodes missing)")
    dry = np.argwhere(z >= 0.0)
    if len(dry):
        i, j = dry[0]
        return (f"the seabed must be below the free surface z = 0, got z = {z[i, j]:g} at "
                f"({x[i]:g}, {y[j]:g}) (heights z, up; a depth d is z = -d)")
    return None


def write_seafloor(bathymetry: Bathymetry, path: str | Path) -> Path:
    """Write ``bathymetry`` in MoorDyn's 3-D seafloor format (the inverse of
    :func:`read_seafloor`)."""
    path = Path(path)
    lines = [f"{len(bathymetry.x)} {len(bathymetry.y)}",
             " ".join(repr(float(v)) for v in bathymetry.x),
             " ".join(repr(float(v)) for v in bathymetry.y)]
    for i, xi in enumerate(bathymetry.x):
        for j, yj in enumerate(bathymetry.y):
            lines.append(f"{float(xi)!r} {float(yj)!r} {float(bathymetry.z[i][j])!r}")
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path
