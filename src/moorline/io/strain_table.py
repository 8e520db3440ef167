"""Read a tension-strain table: a CSV file or MoorDyn's EA table file.

MoorDyn v2 (docs, "Nonlinear Stiffness (EA) Inputs") reads a line type's EA as a file name
when it is not a number: three header lines, then a strain column and a tension column
separated by blanks. Here any line that is not two numbers (separated by commas or blanks)
before the first data row is a header; ``#`` starts a comment.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from .files import MAX_TABLE_BYTES, file_problem

__all__ = ["read_strain_table"]


def read_strain_table(path: str | Path) -> NDArray[np.float64]:
    """Rows ``(strain, tension)`` of a table file, shape (n, 2).

    Raises
    ------
    ValueError
        The file cannot be read, or a data row is not two numbers (the message says where).
    """
    path = Path(path)
    problem = file_problem(path.resolve(), MAX_TABLE_BYTES)
    if problem is not None:
        raise ValueError(f"cannot read strain table {str(path)!r}: {problem}")
    rows: list[list[float]] = []
    with open(path, encoding="utf-8") as handle:
        for number, line in enumerate(handle, start=1):
            fields = line.split("#")[0].replace(",", " ").split()
            if not fields:
                continue
            try:
                values = [float(x) for x in fields[:2]]
            except ValueError:
                if rows:
                    raise ValueError(f"strain table {str(path)!r}, line {number}: not two "
                                     f"numbers: {line.strip()!r}") from None
                continue  # a header line
            if len(values) < 2:
                raise ValueError(f"strain table {str(path)!r}, line {number}: two columns "
                                 "(strain, tension) needed")
            rows.append(values)
    if not rows:
        raise ValueError(f"strain table {str(path)!r}: no data rows")
    return np.asarray(rows, dtype=float)
