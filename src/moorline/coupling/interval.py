"""How the coupled dofs move within one coupling interval ``[t0, t0 + h]``.

The implicit step (:mod:`moorline.solvers.newmark`) needs the coupled points' position,
velocity and acceleration only at the end of each (sub-)step. Two rules give them:

- ``hermite`` (:meth:`Interval.hermite`, the default of :meth:`Coupling.step`): the host gives
  the state at the end of the interval; the motion is the Hermite polynomial through both
  ends' positions and velocities (a cubic), and their accelerations when the host gives the
  end acceleration (a quintic). The end of the interval is then exactly the host's state, and
  the cubic's end acceleration ``(6 (x0 - x1) / h + 2 v0 + 4 v1) / h`` is second-order
  accurate and, unlike the Newmark relation ``a1 = 2 (v1 - v0) / h - a0``, does not carry the
  previous acceleration (no step-to-step ringing).
- ``linear`` (:meth:`Interval.linear`, MoorDyn's coupling): the host gives the state at the
  start; the points move ``x + v (t - t0)`` with zero acceleration (MoorDyn-C
  ``Point::updateFairlead``), so the interval ends at ``x + v h``, not at the host's next
  position.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]

Kinematics = tuple[FloatArray, FloatArray, FloatArray]


def _hermite_matrix(order: int) -> FloatArray:
    """Rows: the value and first ``order - 1`` derivatives of ``s^k`` (k < 2 order) at
    ``s = 0`` and ``s = 1``."""
    n = 2 * order
    rows = []
    for s in (0.0, 1.0):
        for d in range(order):
            row = np.zeros(n)
            for k in range(d, n):
                row[k] = np.prod(np.arange(k - d + 1, k + 1)) * s ** (k - d)
            rows.append(row)
    return np.array(rows)


_INVERSE = {order: np.linalg.inv(_hermite_matrix(order)) for order in (2, 3)}


@dataclass(frozen=True)
class Interval:
    """Kinematics ``(x, v, a)`` of the coupled dofs at any time of an interval (flat arrays of
    the coupled dofs; a body's rotation vector is interpolated as its other dofs, which is
    exact at the interval's ends and to first order in the rotation inside)."""

    t0: float
    h: float
    coefficients: FloatArray | None  # (n_terms, n_dof) in s = (t - t0) / h
    start: Kinematics | None = None  # linear rule: position and velocity at t0

    @classmethod
    def hermite(cls, t0: float, h: float, start: Kinematics, end_x: FloatArray,
                end_v: FloatArray, end_a: FloatArray | None = None) -> Interval:
        """The Hermite motion from ``start`` (the state at ``t0``) to the host's end state
        (cubic; quintic when ``end_a`` is given)."""
        x0, v0, a0 = start
        if end_a is None:
            values = np.array([x0, h * v0, end_x, h * end_v])
            return cls(t0, h, _INVERSE[2] @ values)
        values = np.array([x0, h * v0, h * h * a0, end_x, h * end_v, h * h * end_a])
        return cls(t0, h, _INVERSE[3] @ values)

    @classmethod
    def linear(cls, t0: float, h: float, x: FloatArray, v: FloatArray) -> Interval:
        """MoorDyn's rule: ``x + v (t - t0)``, zero acceleration."""
        return cls(t0, h, None, (np.asarray(x, float), np.asarray(v, float),
                                 np.zeros_like(np.asarray(x, float))))

    def at(self, t: float) -> Kinematics:
        """Positions, velocities and accelerations at ``t``."""
        tau = t - self.t0
        if self.coefficients is None:
            x, v, a = self.start
            return x + v * tau, v.copy(), a.copy()
        s = tau / self.h
        c = self.coefficients
        k = np.arange(len(c))
        powers = s ** k
        d1 = np.concatenate(([0.0], k[1:] * s ** (k[1:] - 1)))
        d2 = np.concatenate(([0.0, 0.0], k[2:] * (k[2:] - 1) * s ** (k[2:] - 2)))
        return powers @ c, (d1 @ c) / self.h, (d2 @ c) / self.h ** 2
