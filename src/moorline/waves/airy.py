r"""Linear (Airy) wave kinematics, single regular waves and sums of linear components.

For one component of amplitude ``a``, angular frequency ``omega``, wave number ``k`` (from
the dispersion relation, :func:`moorline.waves.dispersion.wave_number`), heading ``beta``
(direction of propagation, 0 = +x, 90 deg = +y) and phase ``phi``, with the phase function

.. math:: \theta = k (x\cos\beta + y\sin\beta) - \omega t + \phi,

the first-order potential-flow solution (Dean & Dalrymple 1991, ch. 3-4, eqs. 4.13-4.15;
the linear wave theory Tuah (1982) sec. 5.1 uses for cable dynamics) is

.. math::

    \eta &= a \cos\theta, \\
    u_h &= a\omega\,\frac{\cosh k(z+h)}{\sinh kh}\cos\theta, \qquad
    w = a\omega\,\frac{\sinh k(z+h)}{\sinh kh}\sin\theta, \\
    \partial_t u_h &= a\omega^2\,\frac{\cosh k(z+h)}{\sinh kh}\sin\theta, \qquad
    \partial_t w = -a\omega^2\,\frac{\sinh k(z+h)}{\sinh kh}\cos\theta,

with ``u_h`` along the heading. The depth factors are evaluated overflow-free for every
``k h`` (including ``h = inf``) as

.. math::

    \frac{\cosh k(z+h)}{\sinh kh} = e^{kz}\,\frac{1 + e^{-2k(z+h)}}{1 - e^{-2kh}}, \qquad
    \frac{\sinh k(z+h)}{\sinh kh} = e^{kz}\,\frac{1 - e^{-2k(z+h)}}{1 - e^{-2kh}},

(using ``expm1`` for the small differences), which tends to the deep-water ``e^{kz}`` when
``k h`` is large or ``h = inf``; no switch between "deep" and "finite" forms is needed.

Vertical positions (documented convention)
------------------------------------------
* Points with ``z`` above the instantaneous (ramped, summed) free surface ``eta`` get zero
  velocity and acceleration; their ``eta`` is still returned.
* ``stretching="none"``: a wet point is evaluated at ``min(z, 0)``, i.e. between ``z = 0``
  and a crest the ``z = 0`` values are held constant (constant extrapolation).
* ``stretching="wheeler"`` (Wheeler 1970): a wet point is evaluated at the stretched
  ``z' = h (z - eta) / (h + eta)`` (deep water: ``z' = z - eta``), which maps the water
  column ``[-h, eta]`` onto ``[-h, 0]``. The acceleration is the linear local acceleration at
  ``z'`` (the time derivative of the stretching coordinate is not added, as is usual).
* Points below the seabed (``z < -h``) are treated as being at the seabed.

The accelerations are the local (linear) ``du/dt``; convective terms are of second order
and are not included.

Ramp
----
With ``ramp_time = T_r > 0`` all kinematics (velocity, acceleration and elevation) are
multiplied by ``r(t) = (1 - cos(pi t / T_r)) / 2`` for ``0 <= t < T_r`` (``r = 0`` for
``t <= 0``, ``r = 1`` for ``t >= T_r``), and the acceleration gets the extra term
``r'(t) u`` so that it is exactly the time derivative of the ramped velocity.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .dispersion import wave_number

FloatArray = NDArray[np.float64]
Stretching = Literal["none", "wheeler"]

_STRETCHINGS = ("none", "wheeler")
#: Largest (points x components) block evaluated at once (bounds temporary memory).
_BLOCK = 1 << 16


def ramp_factor(t: float, ramp_time: float) -> tuple[float, float]:
    """Smooth start-up ramp ``r(t) = (1 - cos(pi t / T_r)) / 2`` and its derivative ``r'(t)``.

    Parameters
    ----------
    t
        Time [time].
    ramp_time
        Ramp duration ``T_r`` [time]; ``0`` means no ramp (``r = 1``, ``r' = 0``).

    Returns
    -------
    r, dr
        Ramp factor (0 for ``t <= 0``, 1 for ``t >= T_r``) and its time derivative.
    """
    if ramp_time <= 0.0 or t >= ramp_time:
        return 1.0, 0.0
    if t <= 0.0:
        return 0.0, 0.0
    arg = math.pi * t / ramp_time
    return 0.5 * (1.0 - math.cos(arg)), 0.5 * math.pi / ramp_time * math.sin(arg)


def _check_points(points: ArrayLike) -> FloatArray:
    p = np.asarray(points, dtype=float)
    if p.ndim != 2 or p.shape[1] != 3:
        raise ValueError(f"points must have shape (n, 3), got {p.shape}")
    return p


@dataclass(frozen=True, eq=False)
class WaveComponents:
    r"""Sum of linear (Airy) wave components; a :class:`~moorline.waves.field.FluidField`.

    All per-component arguments are broadcast to one common 1-d length ``m`` (a scalar heading
    or phase applies to all components). The kinematics are the sums over components of the
    single-component formulas of this module (linear superposition), evaluated as
    (n_points x n_components) arrays; the surface clipping and the Wheeler stretching use the
    *total* elevation.

    Parameters
    ----------
    amplitudes
        Component amplitudes ``a`` [length] (half the wave height), ``>= 0``.
    omegas
        Angular frequencies [rad/time], ``> 0``.
    phases
        Phases ``phi`` [rad]; ``eta = sum a cos(k x_h - omega t + phi)``.
    headings_deg
        Directions of propagation [deg] (0 = +x, 90 = +y).
    depth
        Water depth ``h`` [length]; ``inf`` for deep water.
    gravity
        Gravitational acceleration [length/time^2].
    ramp_time
        Duration of the start-up ramp [time]; 0 (default) for none.
    stretching
        ``"none"`` (evaluate at ``min(z, 0)``) or ``"wheeler"``.

    Attributes
    ----------
    wave_numbers
        ``k`` of each component from the dispersion relation [rad/length].
    """

    amplitudes: FloatArray
    omegas: FloatArray
    phases: FloatArray
    headings_deg: FloatArray
    depth: float
    gravity: float
    ramp_time: float = 0.0
    stretching: Stretching = "none"
    wave_numbers: FloatArray = field(init=False, repr=False)
    _coef: dict[str, FloatArray] = field(init=False, repr=False)

    def __post_init__(self) -> None:
        arrays = np.broadcast_arrays(
            *(
                np.atleast_1d(np.asarray(v, dtype=float))
                for v in (self.amplitudes, self.omegas, self.phases, self.headings_deg)
            )
        )
        if arrays[0].ndim != 1:
            raise ValueError("wave component arguments must be scalars or 1-d")
        a, w, phi, beta_deg = (np.array(v, dtype=float) for v in arrays)
        if not (np.all(np.isfinite(a)) and np.all(a >= 0.0)):
            raise ValueError("amplitudes must be finite and non-negative")
        if not (np.all(np.isfinite(w)) and np.all(w > 0.0)):
            raise ValueError("omegas must be finite and positive")
        if not (np.all(np.isfinite(phi)) and np.all(np.isfinite(beta_deg))):
            raise ValueError("phases and headings must be finite")
        if not self.depth > 0.0:
            raise ValueError(f"depth must be positive (inf for deep water), got {self.depth!r}")
        if not (self.gravity > 0.0 and math.isfinite(self.gravity)):
            raise ValueError(f"gravity must be positive, got {self.gravity!r}")
        if not (self.ramp_time >= 0.0 and math.isfinite(self.ramp_time)):
            raise ValueError(f"ramp_time must be >= 0, got {self.ramp_time!r}")
        if self.stretching not in _STRETCHINGS:
            raise ValueError(f"stretching must be one of {_STRETCHINGS}, got {self.stretching!r}")
        k = np.asarray(wave_number(w, float(self.depth), float(self.gravity)), dtype=float)
        k = np.atleast_1d(k)
        beta = np.radians(beta_deg)
        cb, sb = np.cos(beta), np.sin(beta)
        denom = -np.expm1(-2.0 * k * self.depth) if math.isfinite(self.depth) else np.ones_like(k)
        coef = {
            "a": a,
            "k": k,
            "w": w,
            "phi": phi,
            "kx": k * cb,
            "ky": k * sb,
            "aw_c": a * w * cb,
            "aw_s": a * w * sb,
            "aw": a * w,
            "aw2_c": a * w * w * cb,
            "aw2_s": a * w * w * sb,
            "aw2": a * w * w,
            "denom": denom,
        }
        for name, arr in (
            ("amplitudes", a),
            ("omegas", w),
            ("phases", phi),
            ("headings_deg", beta_deg),
            ("wave_numbers", k),
        ):
            arr.setflags(write=False)
            object.__setattr__(self, name, arr)
        for arr in coef.values():
            arr.setflags(write=False)
        object.__setattr__(self, "depth", float(self.depth))
        object.__setattr__(self, "gravity", float(self.gravity))
        object.__setattr__(self, "ramp_time", float(self.ramp_time))
        object.__setattr__(self, "_coef", coef)

    @property
    def n_components(self) -> int:
        """Number of linear components ``m``."""
        return int(self.omegas.size)

    def _phase(
        self, x: FloatArray, y: FloatArray, t: float, c: dict[str, FloatArray]
    ) -> FloatArray:
        return x[:, None] * c["kx"] + y[:, None] * c["ky"] + (c["phi"] - c["w"] * t)

    def elevation(self, points: ArrayLike, t: float) -> FloatArray:
        """Free-surface elevation ``eta`` (ramped) at the horizontal positions of ``points``.

        Parameters
        ----------
        points
            (n, 2) or (n, 3) positions; only x and y are used.
        t
            Time.

        Returns
        -------
        numpy.ndarray
            ``eta`` (n,), ``r(t) sum_j a_j cos(theta_j)``.
        """
        p = np.asarray(points, dtype=float)
        if p.ndim != 2 or p.shape[1] not in (2, 3):
            raise ValueError(f"points must have shape (n, 2) or (n, 3), got {p.shape}")
        r, _ = ramp_factor(t, self.ramp_time)
        c = self._coef
        out = np.empty(p.shape[0])
        step = max(1, _BLOCK // max(self.n_components, 1))
        for i in range(0, p.shape[0], step):
            sl = slice(i, i + step)
            out[sl] = np.cos(self._phase(p[sl, 0], p[sl, 1], t, c)) @ c["a"]
        return r * out

    def kinematics(self, points: ArrayLike, t: float) -> tuple[FloatArray, FloatArray, FloatArray]:
        """Fluid velocity, acceleration and free-surface elevation at ``points`` at time ``t``.

        Parameters
        ----------
        points
            Positions (n, 3), ``z`` up with the still water level at ``z = 0``.
        t
            Time.

        Returns
        -------
        velocity, acceleration, elevation
            (n, 3), (n, 3) and (n,) arrays; zero velocity and acceleration above ``eta``.
            See the module docstring for the formulas and the vertical-position convention.
        """
        p = _check_points(points)
        n = p.shape[0]
        vel = np.empty((n, 3))
        acc = np.empty((n, 3))
        eta = np.empty(n)
        r, dr = ramp_factor(t, self.ramp_time)
        step = max(1, _BLOCK // max(self.n_components, 1))
        for i in range(0, n, step):  # blocks of points, only to bound memory
            sl = slice(i, i + step)
            vel[sl], acc[sl], eta[sl] = self._block(p[sl], t, r, dr)
        return vel, acc, eta

    def _block(
        self, p: FloatArray, t: float, r: float, dr: float
    ) -> tuple[FloatArray, FloatArray, FloatArray]:
        c = self._coef
        h = self.depth
        theta = self._phase(p[:, 0], p[:, 1], t, c)
        cos_t = np.cos(theta)
        sin_t = np.sin(theta)
        eta = r * (cos_t @ c["a"])
        z = p[:, 2]
        wet = z <= eta
        zc = np.maximum(z, -h)  # below the seabed -> at the seabed
        if self.stretching == "wheeler":
            ze = h * (zc - eta) / (h + eta) if math.isfinite(h) else zc - eta
        else:
            ze = zc
        ze = np.minimum(ze, 0.0)  # 'none': hold the z = 0 values up to the crest
        ekz = np.exp(ze[:, None] * c["k"])
        if math.isfinite(h):
            em = np.expm1(-2.0 * c["k"] * (ze[:, None] + h))  # e^{-2k(z+h)} - 1, in [-1, 0]
            cfac = ekz * (2.0 + em) / c["denom"]  # cosh k(z+h) / sinh kh
            sfac = -ekz * em / c["denom"]  # sinh k(z+h) / sinh kh
        else:
            cfac = sfac = ekz
        cc = cfac * cos_t
        sc = sfac * sin_t
        cs = cfac * sin_t
        ss = sfac * cos_t
        u = np.column_stack((cc @ c["aw_c"], cc @ c["aw_s"], sc @ c["aw"]))
        a = np.column_stack((cs @ c["aw2_c"], cs @ c["aw2_s"], -(ss @ c["aw2"])))
        a = r * a + dr * u if dr != 0.0 else r * a
        u = r * u
        dry = ~wet
        u[dry] = 0.0
        a[dry] = 0.0
        return u, a, eta


@dataclass(frozen=True)
class AiryWave:
    """Regular linear (Airy) wave; a one-component :class:`WaveComponents`.

    ``eta = (H/2) cos(k x_h - omega t + phase)`` with ``omega = 2 pi / T``, ``x_h`` the
    horizontal coordinate along the heading and ``k`` from the dispersion relation.

    Parameters
    ----------
    height
        Wave height ``H`` [length] (crest to trough).
    period
        Wave period ``T`` [time].
    heading_deg
        Direction of propagation [deg] (0 = +x, 90 = +y).
    depth
        Water depth [length]; ``inf`` for deep water.
    gravity
        Gravitational acceleration [length/time^2].
    phase
        Phase ``phi`` [rad].
    ramp_time
        Start-up ramp duration [time]; 0 for none.
    stretching
        ``"none"`` or ``"wheeler"`` (see :mod:`moorline.waves.airy`).
    """

    height: float
    period: float
    heading_deg: float
    depth: float
    gravity: float
    phase: float = 0.0
    ramp_time: float = 0.0
    stretching: Stretching = "none"
    components: WaveComponents = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        if not (self.period > 0.0 and math.isfinite(self.period)):
            raise ValueError(f"period must be positive, got {self.period!r}")
        if not (self.height >= 0.0 and math.isfinite(self.height)):
            raise ValueError(f"height must be >= 0, got {self.height!r}")
        comp = WaveComponents(
            amplitudes=np.array([0.5 * self.height]),
            omegas=np.array([2.0 * math.pi / self.period]),
            phases=np.array([self.phase]),
            headings_deg=np.array([self.heading_deg]),
            depth=self.depth,
            gravity=self.gravity,
            ramp_time=self.ramp_time,
            stretching=self.stretching,
        )
        object.__setattr__(self, "components", comp)

    @property
    def amplitude(self) -> float:
        """``H / 2``."""
        return 0.5 * self.height

    @property
    def omega(self) -> float:
        """Angular frequency ``2 pi / T``."""
        return 2.0 * math.pi / self.period

    @property
    def wave_number(self) -> float:
        """``k`` from the dispersion relation."""
        return float(self.components.wave_numbers[0])

    @property
    def wavelength(self) -> float:
        """``2 pi / k``."""
        return 2.0 * math.pi / self.wave_number

    def elevation(self, points: ArrayLike, t: float) -> FloatArray:
        """Free-surface elevation at (n, 2) or (n, 3) points (:meth:`WaveComponents.elevation`)."""
        return self.components.elevation(points, t)

    def kinematics(self, points: ArrayLike, t: float) -> tuple[FloatArray, FloatArray, FloatArray]:
        """Velocity (n, 3), acceleration (n, 3), elevation (n,); see :class:`WaveComponents`."""
        return self.components.kinematics(points, t)


def superpose(*waves: AiryWave | WaveComponents) -> WaveComponents:
    """Linear superposition of waves into one :class:`WaveComponents`.

    All waves must share ``depth``, ``gravity``, ``ramp_time`` and ``stretching``. Below the
    lowest trough and without stretching the result equals the sum of the separate fields;
    near the surface it differs, since clipping and stretching use the total elevation.

    Parameters
    ----------
    *waves
        At least one :class:`AiryWave` or :class:`WaveComponents`.

    Returns
    -------
    WaveComponents
        All components concatenated.
    """
    if not waves:
        raise ValueError("superpose needs at least one wave")
    comps = [w.components if isinstance(w, AiryWave) else w for w in waves]
    first = comps[0]
    for c in comps[1:]:
        same = (
            c.depth == first.depth
            and c.gravity == first.gravity
            and c.ramp_time == first.ramp_time
            and c.stretching == first.stretching
        )
        if not same:
            raise ValueError("superposed waves must share depth, gravity, ramp_time, stretching")
    return WaveComponents(
        amplitudes=np.concatenate([c.amplitudes for c in comps]),
        omegas=np.concatenate([c.omegas for c in comps]),
        phases=np.concatenate([c.phases for c in comps]),
        headings_deg=np.concatenate([c.headings_deg for c in comps]),
        depth=first.depth,
        gravity=first.gravity,
        ramp_time=first.ramp_time,
        stretching=first.stretching,
    )
