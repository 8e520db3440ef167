"""Random sea realizations: deterministic (DSA) and nondeterministic (NSA) spectral amplitudes.

Tuah (1982) sec. 5.1, after Borgman (1969) and Tuah and Hudspeth (1981). A record of length
``T_L`` sampled at ``2N`` points has the frequencies ``omega_m = m d_omega``,
``d_omega = 2 pi / T_L`` (eq. 5.1.2), and the linear sea at a fixed point is (eq. 5.1.1,
5.1.4-5.1.5)::

    eta(t) = sum_{m=-N}^{N} A_m exp(i omega_m t),   A_m = |A_m| exp(-i theta_m),
           = sum_{m=1}^{N} a_m cos(omega_m t - theta_m),   a_m = 2 |A_m|,

``theta_m`` uniform on ``(-pi, pi)``, ``A_{-m}`` the conjugate of ``A_m``. The magnitudes:

- DSA (eq. 5.1.3.a): ``|A_m| = (S(omega_m) d_omega / 2)^(1/2)``, so ``a_m = (2 S d_omega)^(1/2)``
  and the realization's variance ``sum a_m^2 / 2 = sum S d_omega`` is the spectrum's area
  (the "expected spectrum" of Tuah's Figure 6.5-6);
- NSA (eq. 5.1.3.b): ``|A_m| = (S d_omega / 4)^(1/2) (alpha_m^2 + beta_m^2)^(1/2)``,
  ``alpha, beta`` independent standard normal: Rayleigh-distributed amplitudes with the same
  mean square, ``E a_m^2 = 2 S d_omega`` (a "sample spectrum").

Note on the OCR'd text: eq. 5.1.3 gives the magnitude of the complex two-sided amplitude of
eq. 5.1.4; used directly as the cosine amplitude of eq. 5.1.1 it would give a quarter of the
spectrum's variance. Here the cosine amplitude is ``a_m = 2 |A_m|``, which makes the
variance equal the spectrum's area, as the source's Figure 6.5-6 requires.

The time series at a point is the inverse FFT of the complex amplitudes (the source's step
4): with ``c_m = A_m exp(-i k_m . x)`` on ``m = 1..N``, ``eta(n dt) = 2N irfft(c)[n]``,
``dt = T_L / 2N``. The same realization as a :class:`~moorline.waves.WaveComponents` gives
the wave kinematics anywhere (the transfer functions of eq. 5.2.10 are those of linear
waves) for the time-domain dynamics.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .airy import WaveComponents
from .dispersion import wave_number
from .spectra import WaveSpectrum

FloatArray = NDArray[np.float64]
AmplitudeModel = Literal["dsa", "nsa"]


@dataclass(frozen=True)
class RandomSea:
    """A random linear sea: spectrum, record and amplitude model (Tuah (1982) sec. 5.1).

    Attributes
    ----------
    spectrum
        The one-sided wave spectrum.
    record_length
        ``T_L`` [time]: the realization repeats with this period; ``d_omega = 2 pi / T_L``.
    n_frequencies
        Number of components ``m = 1 .. n_frequencies`` (Tuah's Example 5: 200 at
        0.0245 rad/s); ``None``: every ``omega_m <= omega_max``.
    omega_max
        Highest component frequency when ``n_frequencies`` is ``None`` [rad/time]; ``None``:
        six times the peak frequency.
    amplitudes
        ``dsa`` (deterministic) or ``nsa`` (nondeterministic, Rayleigh) spectral amplitudes.
    seed
        Seed of the random phases (and NSA amplitudes): the same seed, the same sea.
    heading_deg
        Direction of propagation [deg] (0 = +x).
    """

    spectrum: WaveSpectrum
    record_length: float
    n_frequencies: int | None = None
    omega_max: float | None = None
    amplitudes: AmplitudeModel = "dsa"
    seed: int = 0
    heading_deg: float = 0.0

    def __post_init__(self) -> None:
        if not (self.record_length > 0 and math.isfinite(self.record_length)):
            raise ValueError(f"record_length must be positive, got {self.record_length!r}")
        if self.n_frequencies is not None and self.n_frequencies < 1:
            raise ValueError(f"n_frequencies must be >= 1, got {self.n_frequencies!r}")
        if self.amplitudes not in ("dsa", "nsa"):
            raise ValueError(f"amplitudes must be 'dsa' or 'nsa', got {self.amplitudes!r}")
        if not (self.spectrum.hs >= 0 and self.spectrum.tp > 0):
            raise ValueError("the spectrum needs hs >= 0 and tp > 0")

    @property
    def d_omega(self) -> float:
        """Frequency step ``2 pi / T_L`` [rad/time] (eq. 5.1.2.b)."""
        return 2.0 * math.pi / self.record_length

    def n_components(self) -> int:
        """Number of components: ``n_frequencies``, or every ``m d_omega <= omega_max``."""
        if self.n_frequencies is not None:
            return self.n_frequencies
        top = self.omega_max if self.omega_max is not None else 6.0 * self.spectrum.omega_p
        return max(int(math.floor(top / self.d_omega + 1e-9)), 1)

    def frequencies(self) -> FloatArray:
        """Component frequencies ``omega_m = m d_omega``, ``m = 1, 2, ...`` [rad/time]."""
        return self.d_omega * np.arange(1, self.n_components() + 1)

    def complex_amplitudes(self) -> tuple[FloatArray, NDArray[np.complex128]]:
        """Frequencies and complex amplitudes ``A_m = |A_m| exp(-i theta_m)`` (eq. 5.1.3,
        5.1.5) of ``m = 1 .. n``."""
        w = self.frequencies()
        rng = np.random.default_rng(self.seed)
        theta = rng.uniform(-math.pi, math.pi, size=w.size)
        power = self.spectrum.density(w) * self.d_omega
        if self.amplitudes == "dsa":
            magnitude = np.sqrt(0.5 * power)
        else:
            alpha, beta = rng.standard_normal(w.size), rng.standard_normal(w.size)
            magnitude = np.sqrt(0.25 * power) * np.sqrt(alpha**2 + beta**2)
        return w, magnitude * np.exp(-1j * theta)

    def components(self, depth: float, gravity: float, ramp_time: float = 0.0,
                   stretching: str = "none") -> WaveComponents:
        """The realization as linear wave components (kinematics anywhere, any time)."""
        w, A = self.complex_amplitudes()
        keep = np.abs(A) > 0
        return WaveComponents(amplitudes=2.0 * np.abs(A[keep]), omegas=w[keep],
                              phases=-np.angle(A[keep]), headings_deg=self.heading_deg,
                              depth=depth, gravity=gravity, ramp_time=ramp_time,
                              stretching=stretching)

    def elevation_series(self, depth: float, gravity: float, n_points: int,
                         point: ArrayLike = (0.0, 0.0)) -> tuple[FloatArray, FloatArray]:
        """Surface elevation at a horizontal ``point`` over one record by inverse FFT (the
        source's step 4): times ``n T_L / n_points`` and ``eta``.

        ``n_points`` (Tuah's ``2N``) must exceed twice the number of components.
        """
        w, A = self.complex_amplitudes()
        if n_points <= 2 * w.size:
            raise ValueError(f"n_points = {n_points} must exceed 2 x {w.size} components")
        k = np.atleast_1d(wave_number(w, depth, gravity))
        beta = math.radians(self.heading_deg)
        x, y = (float(v) for v in point)
        c = np.zeros(n_points // 2 + 1, dtype=complex)
        c[1:w.size + 1] = A * np.exp(-1j * k * (x * math.cos(beta) + y * math.sin(beta)))
        eta = np.fft.irfft(c, n=n_points) * n_points
        return self.record_length * np.arange(n_points) / n_points, eta


__all__ = ["AmplitudeModel", "RandomSea"]
