"""Steady horizontal current: uniform or a piecewise-linear profile over depth."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .airy import ramp_factor

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class CurrentProfile:
    """Horizontal current varying with height; a :class:`~moorline.waves.field.FluidField`.

    Speed and heading are interpolated linearly in ``z`` between the levels and held constant
    beyond the first and last level. Headings are unwrapped first, so between two levels the
    direction turns the shorter way (e.g. 350 deg -> 10 deg passes through 0 deg) and the speed
    is interpolated on its own (it does not dip where the direction turns, as it would if the
    velocity components were interpolated; for equal headings the two agree).

    Parameters
    ----------
    z_levels
        Heights of the levels [length] (z up, still water at 0), strictly ascending or strictly
        descending.
    speeds
        Current speed at each level [length/time].
    headings_deg
        Direction the current flows towards at each level [deg] (0 = +x, 90 = +y).
    ramp_time
        Start-up ramp [time]; 0 (default) for a current that is there from the start. With
        ``T_r > 0`` the velocity is ``r(t) U(z)`` and the acceleration ``r'(t) U(z)`` with the
        same ``r(t) = (1 - cos(pi t / T_r)) / 2`` as the waves
        (:func:`moorline.waves.airy.ramp_factor`); otherwise the acceleration is zero.
    """

    z_levels: tuple[float, ...]
    speeds: tuple[float, ...]
    headings_deg: tuple[float, ...]
    ramp_time: float = 0.0
    _z: FloatArray = field(init=False, repr=False, compare=False)
    _speed: FloatArray = field(init=False, repr=False, compare=False)
    _heading: FloatArray = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        z = np.atleast_1d(np.asarray(self.z_levels, dtype=float))
        s = np.atleast_1d(np.asarray(self.speeds, dtype=float))
        b = np.atleast_1d(np.asarray(self.headings_deg, dtype=float))
        if z.ndim != 1 or z.shape != s.shape or z.shape != b.shape or z.size == 0:
            raise ValueError("z_levels, speeds and headings_deg must be 1-d of equal length >= 1")
        if not (np.all(np.isfinite(z)) and np.all(np.isfinite(s)) and np.all(np.isfinite(b))):
            raise ValueError("current profile values must be finite")
        if np.any(s < 0.0):
            raise ValueError("current speeds must be >= 0 (use the heading for the direction)")
        dz = np.diff(z)
        if z.size > 1 and not (np.all(dz > 0.0) or np.all(dz < 0.0)):
            raise ValueError("z_levels must be strictly ascending or strictly descending")
        if not (self.ramp_time >= 0.0 and np.isfinite(self.ramp_time)):
            raise ValueError(f"ramp_time must be >= 0, got {self.ramp_time!r}")
        object.__setattr__(self, "ramp_time", float(self.ramp_time))
        order = np.argsort(z)
        beta = np.unwrap(np.radians(b[order]))
        for name, v in (("z_levels", z), ("speeds", s), ("headings_deg", b)):
            object.__setattr__(self, name, tuple(float(x) for x in v))
        for name, v in (("_z", z[order]), ("_speed", s[order]), ("_heading", beta)):
            v.setflags(write=False)
            object.__setattr__(self, name, v)

    @classmethod
    def uniform(
        cls, speed: float, heading_deg: float = 0.0, ramp_time: float = 0.0
    ) -> CurrentProfile:
        """The same current ``speed`` towards ``heading_deg`` at every depth."""
        return cls((0.0,), (float(speed),), (float(heading_deg),), ramp_time)

    @classmethod
    def from_levels(
        cls,
        z_levels: Sequence[float] | ArrayLike,
        speeds: Sequence[float] | ArrayLike,
        headings_deg: Sequence[float] | ArrayLike | float,
        ramp_time: float = 0.0,
    ) -> CurrentProfile:
        """Profile from array-likes; a scalar ``headings_deg`` applies to all levels."""
        z = np.atleast_1d(np.asarray(z_levels, dtype=float))
        b = np.broadcast_to(np.asarray(headings_deg, dtype=float), z.shape)
        s = np.atleast_1d(np.asarray(speeds, dtype=float))
        return cls(tuple(z), tuple(s), tuple(b), ramp_time)

    def velocity(self, z: ArrayLike) -> FloatArray:
        """Steady (unramped) current velocity (n, 3) at heights ``z`` (n,), no surface clipping.

        ``U(z) = s(z) (cos b(z), sin b(z), 0)`` with ``s`` and ``b`` interpolated linearly
        (``numpy.interp``; constant beyond the end levels).
        """
        zz = np.asarray(z, dtype=float).reshape(-1)
        s = np.interp(zz, self._z, self._speed)
        b = np.interp(zz, self._z, self._heading)
        return np.column_stack((s * np.cos(b), s * np.sin(b), np.zeros_like(s)))

    def ramped(self, z: ArrayLike, t: float) -> tuple[FloatArray, FloatArray]:
        """Ramped velocity ``r(t) U(z)`` and acceleration ``r'(t) U(z)``, (n, 3) each, at
        heights ``z`` and time ``t``, without free-surface clipping."""
        u = self.velocity(z)
        r, dr = ramp_factor(t, self.ramp_time)
        return r * u, dr * u

    def kinematics(self, points: ArrayLike, t: float) -> tuple[FloatArray, FloatArray, FloatArray]:
        """Velocity and acceleration (n, 3) (zero above ``z = 0``), zero elevation (n,).

        Parameters
        ----------
        points
            Positions (n, 3).
        t
            Time (the current is steady apart from the optional start-up ramp).
        """
        p = np.asarray(points, dtype=float)
        if p.ndim != 2 or p.shape[1] != 3:
            raise ValueError(f"points must have shape (n, 3), got {p.shape}")
        vel, acc = self.ramped(p[:, 2], t)
        dry = p[:, 2] > 0.0
        vel[dry] = 0.0
        acc[dry] = 0.0
        return vel, acc, np.zeros(p.shape[0])
