"""Time histories: prescribed point motions and time-varying point forces."""

from __future__ import annotations

import math

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


def motion_value(motion: Motion, t: float) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Value of a history at ``t`` and its first and second time derivatives (3-vectors)."""
    if motion.kind == "harmonic":
        amp = np.asarray(motion.amplitude, dtype=float)
        w = 2 * np.pi / motion.period
        phase = w * t + np.radians(motion.phase_deg)
        f = (amp * np.sin(phase), amp * w * np.cos(phase), -amp * w * w * np.sin(phase))
    else:
        times = np.asarray(motion.times, dtype=float)
        values = np.asarray(motion.values, dtype=float).reshape(-1, 3)
        f0 = np.array([np.interp(t, times, values[:, k]) for k in range(3)])
        k = int(np.clip(np.searchsorted(times, t, side="right") - 1, 0, len(times) - 2))
        inside = times[0] <= t < times[-1]
        slope = (values[k + 1] - values[k]) / (times[k + 1] - times[k]) if inside else 0 * f0
        f = (f0, slope, np.zeros(3))
    r, dr, ddr = ramp(t, motion.ramp_time)
    return r * f[0], r * f[1] + dr * f[0], r * f[2] + 2 * dr * f[1] + ddr * f[0]


class Excitation:
    """Prescribed node kinematics and point force histories of a system.

    Harmonic motions of all prescribed points are evaluated together (one vectorized call per
    time); tables one by one.
    """

    def __init__(self, mesh: Mesh, base_positions: FloatArray) -> None:
        self.constrained = np.flatnonzero(~mesh.free_nodes)
        self.base = base_positions[self.constrained].copy()
        row = {int(n): i for i, n in enumerate(self.constrained)}
        moving = [(row[int(mesh.point_node[i])], mo) for i, mo in enumerate(mesh.point_motion)
                  if mo is not None]
        harmonic = [(r, mo) for r, mo in moving if mo.kind == "harmonic"]
        self._tables = [(r, mo) for r, mo in moving if mo.kind != "harmonic"]
        self._rows = [r for r, _ in harmonic]
        self._amp = np.array([mo.amplitude for _, mo in harmonic], dtype=float).reshape(-1, 3)
        self._omega = np.array([2 * np.pi / mo.period for _, mo in harmonic])
        self._phase = np.radians([mo.phase_deg for _, mo in harmonic])
        self._ramp = np.array([mo.ramp_time for _, mo in harmonic])
        self._forces = [(int(mesh.point_node[i]), f)
                        for i, f in enumerate(mesh.point_force_history) if f is not None]

    def constrained_state(self, t: float) -> tuple[FloatArray, FloatArray, FloatArray]:
        """Positions, velocities and accelerations of all fixed and prescribed nodes at ``t``."""
        x, v, a = self.base.copy(), np.zeros_like(self.base), np.zeros_like(self.base)
        for k, row in enumerate(self._rows):  # a few points: scalar math beats numpy calls
            w = self._omega[k]
            arg = w * t + self._phase[k]
            s, c = math.sin(arg), math.cos(arg)
            r0, r1, r2 = ramp(t, self._ramp[k])
            for j in range(3):
                amp = self._amp[k, j]
                if amp == 0.0:
                    continue
                d, dv, da = amp * s, amp * w * c, -amp * w * w * s
                x[row, j] += r0 * d
                v[row, j] = r0 * dv + r1 * d
                a[row, j] = r0 * da + 2 * r1 * dv + r2 * d
        for row, motion in self._tables:
            d, dv, da = motion_value(motion, t)
            x[row] += d
            v[row] = dv
            a[row] = da
        return x, v, a

    def point_forces(self, t: float, n_nodes: int) -> FloatArray | None:
        """Time-varying forces on free points at ``t`` (n_nodes, 3), or None if there are none."""
        if not self._forces:
            return None
        out = np.zeros((n_nodes, 3))
        for node, history in self._forces:
            out[node] += motion_value(history, t)[0]
        return out
