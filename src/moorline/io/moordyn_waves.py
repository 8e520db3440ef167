"""MoorDyn-C's wave input files as explicit linear sea components.

Formats and steps learned from MoorDyn-C v2.7.1 (``source/Waves.cpp`` ``Waves::setup``,
``source/Waves/WaveSpectrum.cpp`` ``spectrumFromFile`` and ``interpEvenlySpaced``,
``source/Waves/SpectrumKin.cpp``, ``source/Waves/WaveGrid.cpp``
``constructWaveGridSpectrumData``, ``constructWaveGridElevationData`` and ``fillWaveGrid``;
``docs/waterkinematics.rst``); the code here is moorline's own. Every result is a
:class:`moorline.model.SeaComponents` in moorline's convention
``eta = sum a cos(k l - omega t + phi)``, ``l = x cos b + y sin b``.

``wave_frequencies.txt`` (WaveKin 2 and 7): rows ``omega re im [beta]``: a frequency
[rad/s], the real and imaginary parts of a complex amplitude ``A`` [m] and an optional
direction ``beta`` [rad, within +-2 pi]; no header; the first frequency must be 0.

- WaveKin 7 (``SpectrumKin::getWaveKin``) sums the rows as they are at the nodes:
  ``eta = sum |A| sin(omega t - k l + arg A)``, i.e. ``a = |A|``, ``phi = pi/2 - arg A``.
- WaveKin 2 (the FFT grid) first interpolates the rows linearly (``re``, ``im`` and
  ``beta``) to the even step ``d_omega`` = the smallest spacing, ``n = floor(omega_last /
  d_omega) + 1`` frequencies from 0, then inverse-FFTs ``A (n - 1)`` over ``2 (n - 1)``
  samples divided by ``2 (n - 1)``: ``eta = sum Re(A e^{i(omega t - k l)})``, i.e.
  ``a = |A|``, ``phi = -arg A``, except the last (Nyquist) frequency, which the real inverse
  FFT halves (``a = |A| / 2``; equal to MoorDyn at its sample times), and the zero
  frequency, a constant level ``Re A / 2`` (dropped, warned).

``wave_elevation.txt`` (WaveKin 3): rows ``t eta`` [s, m] from ``t = 0``, no header.
MoorDyn resamples the series linearly at ``dtWave`` (``n = floor(t_last / dtWave) + 1``
samples, held constant beyond the ends), drops the last sample when ``n`` is odd, takes the
real FFT ``X_m`` and zeroes every ``m d_omega > pi`` rad/s (0.5 Hz, "to avoid FFT noise"),
``d_omega = 2 pi / (n dtWave)``, heading 0; the grid then holds
``eta = (1/n) [X_0 + 2 sum Re(X_m e^{i(omega_m t - k l)}) + Re X_{n/2} ...]``, i.e.
``a = 2 |X_m| / n`` (``|X_{n/2}| / n`` for the Nyquist frequency), ``phi = -arg X_m``; the
mean level ``X_0 / n`` is dropped (warned). The sea repeats every ``n dtWave``.

MoorDyn evaluates WaveKin 2 and 3 on the grid of ``water_grid.txt`` (linear interpolation in
x, y, z and, at the FFT's sample step, in time; points outside the grid take its edge);
moorline evaluates the same components exactly at the nodes: the two agree at grid points and
sample times and differ between them by the interpolation error.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..errors import CaseError
from ..model import SeaComponents

FREQUENCY_FILE = "wave_frequencies.txt"
ELEVATION_FILE = "wave_elevation.txt"
#: Amplitudes below this fraction of the largest are round-off (of the FFTs, of the
#: interpolation of zeros) and dropped.
NEGLIGIBLE = 1e-12
#: MoorDyn-C's cut-off of the FFT of a wave-elevation series [rad/s] (0.5 Hz).
ELEVATION_CUTOFF = 0.5 * 2.0 * math.pi


def _rows(path: Path, columns: str, least: int) -> list[tuple[int, list[float]]]:
    """Numeric rows (line number, values) of a header-less MoorDyn table; blank lines
    skipped."""
    try:
        text = path.read_text(encoding="utf-8", errors="replace")
    except OSError as exc:
        raise CaseError(f"cannot read the file: {exc.strerror or exc}", file=str(path)) from None
    rows = []
    for lineno, line in enumerate(text.splitlines(), start=1):
        tokens = line.split()
        if not tokens:
            continue
        try:
            values = [float(t) for t in tokens]
        except ValueError:
            raise CaseError(f"expected numbers '{columns}', got {line.strip()!r}",
                            file=str(path), field=f"line {lineno}") from None
        if len(values) < least or not all(map(math.isfinite, values)):
            raise CaseError(f"expected at least {least} finite numbers '{columns}', got "
                            f"{line.strip()!r}", file=str(path), field=f"line {lineno}")
        rows.append((lineno, values))
    if len(rows) < 2:
        raise CaseError(f"needs at least 2 rows '{columns}'", file=str(path))
    return rows


def read_wave_frequencies(path: Path) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``wave_frequencies.txt``: frequencies [rad/s], complex amplitudes [m] and directions
    [rad] (0 where the column is absent).

    Raises
    ------
    CaseError
        A non-numeric or short row, a direction beyond +-2 pi or a first frequency other
        than 0 (MoorDyn refuses them too), naming the file and line.
    """
    rows = _rows(path, "omega re im [beta]", 3)
    omega = np.array([r[0] for _, r in rows])
    amplitude = np.array([complex(r[1], r[2]) for _, r in rows])
    beta = np.array([r[3] if len(r) > 3 else 0.0 for _, r in rows])
    lines = [n for n, _ in rows]
    if omega[0] != 0.0:
        raise CaseError(f"the first frequency must be 0 rad/s (MoorDyn), got {omega[0]:g}",
                        file=str(path), field=f"line {lines[0]}")
    bad = np.flatnonzero(np.abs(beta) > 2.0 * math.pi)
    if bad.size:
        raise CaseError(f"the direction {beta[bad[0]]:g} must be within +-2 pi (radians)",
                        file=str(path), field=f"line {lines[bad[0]]}")
    return omega, amplitude, beta


def read_wave_elevation(path: Path) -> tuple[np.ndarray, np.ndarray]:
    """``wave_elevation.txt``: times [s] (increasing, from 0) and elevations [m]."""
    rows = _rows(path, "t eta", 2)
    t = np.array([r[0] for _, r in rows])
    eta = np.array([r[1] for _, r in rows])
    step = np.diff(t)
    if np.any(step <= 0.0):
        i = int(np.flatnonzero(step <= 0.0)[0]) + 1
        raise CaseError(f"times must increase: {t[i]:g} after {t[i - 1]:g}", file=str(path),
                        field=f"line {rows[i][0]}")
    return t, eta


def _sea(omega: np.ndarray, amplitude: np.ndarray, phase: np.ndarray,
         beta: np.ndarray) -> SeaComponents:
    """Components of a positive frequency and an amplitude above :data:`NEGLIGIBLE` times
    the largest (the FFTs' round-off), each with its heading [deg]."""
    keep = (amplitude > NEGLIGIBLE * np.max(amplitude, initial=0.0)) & (omega > 0.0)
    phase_deg = np.degrees(np.angle(np.exp(1j * phase[keep])))  # wrapped to (-180, 180]
    return SeaComponents(omegas=tuple(map(float, omega[keep])),
                         amplitudes=tuple(map(float, amplitude[keep])),
                         phases_deg=tuple(map(float, phase_deg)),
                         headings_deg=tuple(map(float, np.degrees(beta[keep]))))


def summed_components(omega: np.ndarray, amplitude: np.ndarray,
                      beta: np.ndarray) -> SeaComponents:
    """WaveKin 7: the rows as they are, ``eta = sum |A| sin(omega t - k l + arg A)``."""
    return _sea(omega, np.abs(amplitude), 0.5 * math.pi - np.angle(amplitude), beta)


def fft_grid_components(omega: np.ndarray, amplitude: np.ndarray, beta: np.ndarray
                        ) -> tuple[SeaComponents, float, float]:
    """WaveKin 2: the rows interpolated to an even step, as MoorDyn's inverse FFT sums them.

    Raises ``ValueError`` when the frequencies do not increase.

    Returns
    -------
    sea, d_omega, mean
        The components, the even frequency step [rad/s] and the dropped constant level [m].
    """
    d_omega = float(np.min(np.diff(omega)))
    if not d_omega > 0.0:
        raise ValueError("the frequencies must increase from row to row (MoorDyn interpolates "
                         "them to an even step)")
    n = int(math.floor(omega[-1] / d_omega)) + 1
    even = np.arange(n) * d_omega
    value = (np.interp(even, omega, amplitude.real)
             + 1j * np.interp(even, omega, amplitude.imag))
    heading = np.interp(even, omega, beta)
    size = np.abs(value)
    size[-1] *= 0.5  # the Nyquist frequency of the 2 (n - 1) samples
    return _sea(even, size, -np.angle(value), heading), d_omega, 0.5 * float(value[0].real)


def elevation_components(t: np.ndarray, eta: np.ndarray, dt_wave: float
                         ) -> tuple[SeaComponents, int, float]:
    """WaveKin 3: the FFT of the series resampled at ``dt_wave`` [s], cut at 0.5 Hz.

    Returns
    -------
    sea, n_samples, mean
        The components (heading 0), the FFT's number of samples (its period is
        ``n_samples dt_wave``) and the dropped mean level [m].
    """
    n = int(math.floor(t[-1] / dt_wave)) + 1
    n -= n % 2
    if n < 2:
        raise ValueError(f"the series lasts {t[-1]:g} s, less than two steps of dtWave = "
                         f"{dt_wave:g} s")
    samples = np.interp(np.arange(n) * dt_wave, t, eta)
    X = np.fft.rfft(samples)
    d_omega = math.pi / (dt_wave * (n // 2))
    m = np.arange(X.size)
    X[m * d_omega > ELEVATION_CUTOFF] = 0.0
    size = 2.0 * np.abs(X) / n
    size[-1] *= 0.5  # the Nyquist frequency
    return (_sea(m * d_omega, size, -np.angle(X), np.zeros(X.size)), n,
            float(X[0].real) / n)


__all__ = ["ELEVATION_CUTOFF", "ELEVATION_FILE", "FREQUENCY_FILE", "NEGLIGIBLE",
           "elevation_components", "fft_grid_components", "read_wave_elevation",
           "read_wave_frequencies", "summed_components"]
