"""The fluid-field interface the dynamics solver calls, still water, wave + current, builder."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Protocol, runtime_checkable

import numpy as np
from numpy.typing import NDArray

from .airy import AiryWave, WaveComponents
from .current import CurrentProfile
from .random import RandomSea
from .spectra import WaveSpectrum

if TYPE_CHECKING:
    from moorline.model import Environment, Waves

FloatArray = NDArray[np.float64]


@runtime_checkable
class FluidField(Protocol):
    """Anything that gives fluid kinematics at points and times."""

    def kinematics(self, points: np.ndarray, t: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """points (n, 3) -> fluid velocity (n, 3), fluid acceleration (n, 3), free-surface
        elevation (n,) at the points' horizontal positions, at time t."""
        ...


@dataclass(frozen=True)
class StillWater:
    """No waves, no current: all kinematics and the elevation are zero."""

    def kinematics(self, points: np.ndarray, t: float) -> tuple[FloatArray, FloatArray, FloatArray]:
        """Zeros of shapes (n, 3), (n, 3), (n,)."""
        p = np.asarray(points, dtype=float)
        if p.ndim != 2 or p.shape[1] != 3:
            raise ValueError(f"points must have shape (n, 3), got {p.shape}")
        return np.zeros_like(p), np.zeros_like(p), np.zeros(p.shape[0])


@dataclass(frozen=True)
class CombinedField:
    """Waves plus a steady current.

    The velocity is the wave velocity plus the current velocity ``U(z)``; the current is
    evaluated at the point's actual ``z`` (held at its top-level value up to the crest) and is
    zero above the wave's instantaneous free surface. The acceleration is the wave's plus the
    current's (non-zero only during the current's start-up ramp); the elevation is the wave's.
    Wave-current interaction (e.g. the Doppler shift of the wave frequency) is not modelled.

    Parameters
    ----------
    wave
        Any fluid field that supplies the elevation (e.g. :class:`~moorline.waves.AiryWave`).
    current
        The current profile.
    """

    wave: FluidField
    current: CurrentProfile

    def kinematics(self, points: np.ndarray, t: float) -> tuple[FloatArray, FloatArray, FloatArray]:
        """Velocity (n, 3), acceleration (n, 3), elevation (n,) at time ``t``."""
        p = np.asarray(points, dtype=float)
        vel, acc, eta = self.wave.kinematics(p, t)
        cur_v, cur_a = self.current.ramped(p[:, 2], t)
        dry = p[:, 2] > eta
        cur_v[dry] = 0.0
        cur_a[dry] = 0.0
        return vel + cur_v, acc + cur_a, eta


def random_sea(waves: Waves) -> RandomSea:
    """The :class:`~moorline.waves.random.RandomSea` of a ``kind: random`` wave description."""
    return RandomSea(WaveSpectrum(waves.spectrum, waves.height, waves.period, waves.gamma),
                     record_length=waves.record_length, n_frequencies=waves.n_frequencies,
                     omega_max=waves.omega_max, amplitudes=waves.amplitudes, seed=waves.seed,
                     heading_deg=waves.heading_deg)


def sea_components(waves: Waves, depth: float, gravity: float, ramp_time: float = 0.0
                   ) -> WaveComponents | None:
    """The linear components of a ``random`` or ``components`` sea (one code path: a random
    sea's realization is itself a set of components), ``None`` for a still one.

    Parameters
    ----------
    waves
        ``kind: random`` (its realization, :meth:`RandomSea.components`) or ``kind:
        components`` (:class:`moorline.model.SeaComponents`; a component without heading
        takes ``waves.heading_deg``).
    depth, gravity
        Water depth (``inf``: deep) [length] and gravitational acceleration.
    ramp_time
        Start-up ramp [time].
    """
    if not waves.active:
        return None
    if waves.kind == "random":
        return random_sea(waves).components(depth, gravity, ramp_time=ramp_time,
                                            stretching=waves.stretching)
    if waves.kind != "components" or waves.components is None:
        raise ValueError(f"waves of kind {waves.kind!r} are not a set of components")
    c = waves.components
    headings = c.headings_deg if c.headings_deg else waves.heading_deg
    return WaveComponents(amplitudes=np.asarray(c.amplitudes, float),
                          omegas=np.asarray(c.omegas, float),
                          phases=np.radians(np.asarray(c.phases_deg, float)),
                          headings_deg=np.asarray(headings, float), depth=depth,
                          gravity=gravity, ramp_time=ramp_time, stretching=waves.stretching)


def fluid_field_from_environment(env: Environment, ramp_time: float = 0.0,
                                 ramp_current: bool = True) -> FluidField:
    """Fluid field described by a :class:`moorline.model.Environment`.

    ``waves.kind == 'airy'`` with a positive height gives an :class:`~moorline.waves.AiryWave`
    (heading, depth and gravity from the environment, phase 0, no stretching), ``random``
    and ``components`` their :class:`~moorline.waves.WaveComponents` (:func:`sea_components`);
    a non-zero
    ``current.speed`` gives a uniform :class:`~moorline.waves.CurrentProfile`. Both are ramped
    over ``ramp_time`` (``DynamicsSettings.ramp_time`` ramps "waves and current": the
    dynamics starts from a static state computed without current drag). Both give a
    :class:`CombinedField`, neither gives :class:`StillWater`.

    Parameters
    ----------
    env
        The environment.
    ramp_time
        Start-up ramp of the waves and the current [time]; 0 for none.
    ramp_current
        Ramp the current too (``False``: it flows from the start, e.g. after a statics that
        included its drag).

    Returns
    -------
    FluidField
    """
    waves = env.waves
    wave: AiryWave | WaveComponents | None = None
    if waves.kind == "airy":
        if waves.height > 0.0:
            wave = AiryWave(
                height=waves.height,
                period=waves.period,
                heading_deg=waves.heading_deg,
                depth=env.depth,
                gravity=env.gravity,
                phase=math.radians(waves.phase_deg),
                ramp_time=ramp_time,
                stretching=waves.stretching,
            )
    elif waves.kind in ("random", "components"):
        wave = sea_components(waves, env.depth, env.gravity, ramp_time)
    elif waves.kind != "none":
        raise ValueError(f"unknown wave kind {waves.kind!r}")
    current = None
    current_ramp = ramp_time if ramp_current else 0.0
    if env.current.z_levels:
        c = env.current
        current = CurrentProfile(tuple(c.z_levels), tuple(c.speeds), tuple(c.headings_deg),
                                 ramp_time=current_ramp)
    elif env.current.speed != 0.0 and math.isfinite(env.current.speed):
        speed, heading = env.current.speed, env.current.heading_deg
        if speed < 0.0:  # a negative speed flows the other way
            speed, heading = -speed, heading + 180.0
        current = CurrentProfile.uniform(speed, heading, ramp_time=current_ramp)
    if wave is not None and current is not None:
        return CombinedField(wave, current)
    if wave is not None:
        return wave
    if current is not None:
        return current
    return StillWater()
