"""Time histories: prescribed point motions and time-varying point forces."""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
from numpy.typing import NDArray

from ..mesh import Mesh
from ..model import Motion

FloatArray = NDArray[np.float64]


def ramp(t: float, ramp_time: float) -> tuple[float, float, float]:
    """Smooth start-up factor ``(1 - cos(pi t / T)) / 2`` and its first two time derivatives."""
    if ramp_time <= 0 or t >= ramp_time:
        return 1.0, 0.0, 0.0
    if t <= 0:
        return 0.0, 0.0, 0.0
    w = math.pi / ramp_time
    return (0.5 * (1 - math.cos(w * t)), 0.5 * w * math.sin(w * t),
            0.5 * w * w * math.cos(w * t))


def ramps(t: FloatArray, ramp_time: float) -> tuple[FloatArray, FloatArray, FloatArray]:
    """:func:`ramp` at the times ``t`` (n,): three arrays (n,)."""
    t = np.asarray(t, dtype=float)
    if ramp_time <= 0:
        return np.ones_like(t), np.zeros_like(t), np.zeros_like(t)
    w = math.pi / ramp_time
    inside = (t > 0) & (t < ramp_time)
    wt = w * t
    c, s = np.cos(wt), np.sin(wt)
    r0 = np.where(inside, 0.5 * (1 - c), np.where(t >= ramp_time, 1.0, 0.0))
    return r0, np.where(inside, 0.5 * w * s, 0.0), np.where(inside, 0.5 * w * w * c, 0.0)


def knot_derivatives(times: FloatArray, values: FloatArray) -> FloatArray:
    """Time derivatives at the knots of a table for its cubic Hermite interpolant.

    Inner knots: the derivative of the parabola through the knot and its two neighbours
    (central, second-order accurate on any spacing); the first and last knot: the one-sided
    derivative of the parabola through the first (last) three knots; two knots: the slope. A
    knot next to a constant interval gets derivative 0 (per component), so that a hold stays
    exactly held and a ramp-and-hold does not overshoot into the hold.

    Parameters
    ----------
    times
        Knot times (n,), strictly increasing.
    values
        Values at the knots (n, 3).
    """
    h = np.diff(times)[:, None]
    slope = np.diff(values, axis=0) / h
    if len(times) == 2:
        return np.vstack([slope, slope])
    d = np.empty_like(values)
    h0, h1 = h[:-1], h[1:]
    d[1:-1] = (h1 * slope[:-1] + h0 * slope[1:]) / (h0 + h1)
    d[0] = ((2 * h[0] + h[1]) * slope[0] - h[0] * slope[1]) / (h[0] + h[1])
    d[-1] = ((2 * h[-1] + h[-2]) * slope[-1] - h[-1] * slope[-2]) / (h[-1] + h[-2])
    flat = slope == 0.0
    d[:-1][flat] = 0.0
    d[1:][flat] = 0.0
    return d


def table_value(times: FloatArray, values: FloatArray, derivatives: FloatArray, t: float
                ) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Cubic Hermite interpolant of a table at ``t``: value, first and second derivative.

    The interpolant is C1 (position and velocity continuous; the acceleration is linear
    within an interval and may jump at a knot) and passes through the knots with the knot
    derivatives ``derivatives`` (:func:`knot_derivatives`). Before the first and after the
    last time the value is held: velocity and acceleration zero there. At the last time
    itself the velocity is the end derivative (the table's end is a documented stop, not a
    drop of the velocity to zero one knot early).
    """
    x, v, a = table_values(times, values, derivatives, np.array([float(t)]))
    return x[0], v[0], a[0]


def table_values(times: FloatArray, values: FloatArray, derivatives: FloatArray,
                 t: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
    """:func:`table_value` at the times ``t`` (n,): value, first and second derivative,
    (n, 3) each."""
    t = np.asarray(t, dtype=float)
    k = np.clip(np.searchsorted(times, t, side="right") - 1, 0, len(times) - 2)
    h = (times[k + 1] - times[k])[:, None]
    s = ((t - times[k]) / h[:, 0])[:, None]
    p0, p1, m0, m1 = values[k], values[k + 1], derivatives[k] * h, derivatives[k + 1] * h
    h00, h10, h01, h11 = (2 * s**3 - 3 * s**2 + 1, s**3 - 2 * s**2 + s, -2 * s**3 + 3 * s**2,
                          s**3 - s**2)
    d00, d10, d01, d11 = 6 * s**2 - 6 * s, 3 * s**2 - 4 * s + 1, -6 * s**2 + 6 * s, 3 * s**2 - 2 * s
    e00, e10, e01, e11 = 12 * s - 6, 6 * s - 4, -12 * s + 6, 6 * s - 2
    x = h00 * p0 + h10 * m0 + h01 * p1 + h11 * m1
    v = (d00 * p0 + d10 * m0 + d01 * p1 + d11 * m1) / h
    a = (e00 * p0 + e10 * m0 + e01 * p1 + e11 * m1) / (h * h)
    outside = (t < times[0]) | (t > times[-1])
    if outside.any():
        x[outside] = np.where((t[outside] < times[0])[:, None], values[0], values[-1])
        v[outside] = 0.0
        a[outside] = 0.0
    return x, v, a


def motion_value(motion: Motion, t: float) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Value of a motion at ``t`` and its first and second time derivatives (3-vectors).

    A ``table`` motion is the cubic Hermite interpolant of its knots (:func:`table_value`),
    so that the position, velocity and acceleration given to the stepper are one consistent
    trajectory (a linear interpolation has no acceleration and a velocity that jumps at
    every knot).
    """
    x, v, a = motion_values(motion, np.array([float(t)]))
    return x[0], v[0], a[0]


def motion_values(motion: Motion, t: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
    """:func:`motion_value` at the times ``t`` (n,): three arrays (n, 3)."""
    t = np.asarray(t, dtype=float)
    if motion.kind == "harmonic":
        amp = np.asarray(motion.amplitude, dtype=float)
        w = 2 * np.pi / motion.period
        phase = (w * t + np.radians(motion.phase_deg))[:, None]
        sin, cos = np.sin(phase), np.cos(phase)
        f = (amp * sin, amp * w * cos, -amp * w * w * sin)
    else:
        f = table_values(*_table(motion), t)
    r, dr, ddr = (q[:, None] for q in ramps(t, motion.ramp_time))
    return r * f[0], r * f[1] + dr * f[0], r * f[2] + 2 * dr * f[1] + ddr * f[0]


@lru_cache(maxsize=256)
def _table(motion: Motion) -> tuple[FloatArray, FloatArray, FloatArray]:
    """A table motion's times, values and :func:`knot_derivatives` (once per motion)."""
    times = np.asarray(motion.times, dtype=float)
    values = np.asarray(motion.values, dtype=float).reshape(-1, 3)
    return times, values, knot_derivatives(times, values)


def history_value(history: Motion, t: float) -> FloatArray:
    """A force history at ``t`` (3-vector): harmonic, or a ``table`` interpolated linearly
    (a force needs no derivative; steps and ramps stay exactly as tabulated)."""
    return history_values(history, np.array([float(t)]))[0]


def history_values(history: Motion, t: FloatArray) -> FloatArray:
    """:func:`history_value` at the times ``t`` (n,): (n, 3)."""
    t = np.asarray(t, dtype=float)
    if history.kind == "harmonic":
        return motion_values(history, t)[0]
    times = np.asarray(history.times, dtype=float)
    values = np.asarray(history.values, dtype=float).reshape(-1, 3)
    f0 = np.column_stack([np.interp(t, times, values[:, k]) for k in range(3)])
    return ramps(t, history.ramp_time)[0][:, None] * f0


class Excitation:
    """Prescribed node kinematics and point force histories of a system, at one time or
    vectorized over many (the compiled time loop takes a block of steps at once; one time is
    the same computation on one element, so both give the same numbers)."""

    def __init__(self, mesh: Mesh, base_positions: FloatArray) -> None:
        self.constrained = np.flatnonzero(~mesh.free_nodes)
        self.base = base_positions[self.constrained].copy()
        row = {int(n): i for i, n in enumerate(self.constrained)}
        self._moving = [(row[int(mesh.point_node[i])], mo)
                        for i, mo in enumerate(mesh.point_motion) if mo is not None]
        self._forces = [(int(mesh.point_node[i]), f)
                        for i, f in enumerate(mesh.point_force_history) if f is not None]
        self.force_nodes = np.array([node for node, _ in self._forces], dtype=np.int64)

    def constrained_state(self, t: float) -> tuple[FloatArray, FloatArray, FloatArray]:
        """Positions, velocities and accelerations of all fixed and prescribed nodes at ``t``."""
        x, v, a = self.constrained_states(np.array([float(t)]))
        return x[0], v[0], a[0]

    def constrained_states(self, t: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        """:meth:`constrained_state` at the times ``t`` (n,): three arrays (n, n_fixed, 3)."""
        t = np.asarray(t, dtype=float)
        x = np.repeat(self.base[None], len(t), axis=0)
        v, a = np.zeros_like(x), np.zeros_like(x)
        values: dict[Motion, tuple] = {}  # points moving alike (fairleads of one platform)
        for row, motion in self._moving:
            if motion not in values:
                values[motion] = motion_values(motion, t)
            d, dv, da = values[motion]
            x[:, row] += d
            v[:, row] = dv
            a[:, row] = da
        return x, v, a

    def point_forces(self, t: float, n_nodes: int) -> FloatArray | None:
        """Time-varying forces on free points at ``t`` (n_nodes, 3), or None if there are none."""
        if not self._forces:
            return None
        out = np.zeros((n_nodes, 3))
        for node, f in zip(self.force_nodes, self.force_histories(np.array([float(t)]))[0],
                           strict=True):
            out[node] += f
        return out

    def force_histories(self, t: FloatArray) -> FloatArray:
        """Each point force history (on node :attr:`force_nodes`) at the times ``t`` (n,):
        (n, n_forces, 3)."""
        out = np.zeros((len(t), len(self._forces), 3))
        for k, (_, history) in enumerate(self._forces):
            out[:, k] = history_values(history, t)
        return out
