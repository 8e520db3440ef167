"""The compiled pass of the tension envelope (numba): :meth:`moorline.envelope.
TensionEnvelope.add_records` in one pass over a block of records.

numpy needed six passes for it (minimum, maximum, the shifted tensions, their squares and the
two sums in record order), each over the whole block: 2 ms of the 20 ms of streaming a
300-second OC3 run at one record per step, and a pass over every record of a long history per
statistic. The loop adds the records in order, element by element, with the operations of
:meth:`~moorline.envelope.TensionEnvelope.add`: the same numbers to the last bit (no fused
multiply-add: ``fastmath`` off).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from .jit import numba

FloatArray = NDArray[np.float64]


@numba.njit(cache=True, fastmath=False, error_model="numpy")
def accumulate(rows: FloatArray, static: FloatArray, low: FloatArray, high: FloatArray,
               total: FloatArray, square: FloatArray) -> None:  # pragma: no cover (compiled)
    """Add ``rows`` (n_records, n_elements) in order: running minimum ``low`` and maximum
    ``high`` (a NaN tension makes them NaN, as ``np.minimum`` and ``np.maximum`` do), and
    the sums of ``d = T - static`` into ``total`` and of ``d * d`` into ``square``."""
    for i in range(rows.shape[0]):
        for j in range(rows.shape[1]):
            t = rows[i, j]
            if t < low[j] or t != t:
                low[j] = t
            if t > high[j] or t != t:
                high[j] = t
            d = t - static[j]
            total[j] += d
            square[j] += d * d
