"""Central differences of a residual, for the tangent tests."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np


def central_tangent(residual: Callable[[np.ndarray], np.ndarray], u: np.ndarray,
                    relative: float = 1e-6) -> np.ndarray:
    """``-d residual / d u`` by central differences, column by column, each with the step
    ``relative * max(1, |u_k|)``."""
    columns = []
    for k in range(len(u)):
        eps = relative * max(1.0, abs(u[k]))
        up, um = u.copy(), u.copy()
        up[k] += eps
        um[k] -= eps
        columns.append(-(residual(up) - residual(um)) / (2 * eps))
    return np.stack(columns, axis=1)
