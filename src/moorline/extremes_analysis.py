"""The extremes analysis (``kind: extremes``): most probable maximum (MPM) tension over an
exposure ``duration`` per line end and per element, with percentiles.

Time domain (the run's preceding dynamics, and the same simulation repeated with the wave
``seeds`` the analysis lists): ``weibull`` fits the peaks over the mean (one per mean
up-crossing cycle, pooled over the realizations) and takes the characteristic largest of
the number of peaks expected in ``duration``; ``gumbel`` fits the maxima of the
realizations (each cut into ``blocks``) and takes the mode of the largest of
``duration / block length`` blocks. Frequency domain (a stochastic analysis): the Rayleigh
MPM ``mean + sqrt(2 m0 ln(nu_0 T))`` with the zero-up-crossing rate from the spectral
moments (:mod:`moorline.extremes`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from .errors import MoorlineError
from .extremes import gumbel_fit, gumbel_mpm, peaks, rayleigh_mpm, weibull_fit, weibull_mpm
from .plain_dataset import PlainDataset, PlainResult
from .spectral import spectral_moments, upcrossing_rate
from .tension_records import TensionRecords

__all__ = ["ExtremesResult", "solve_extremes"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class ExtremesResult(PlainResult):
    """Extreme tensions of one analysed state.

    Attributes
    ----------
    source, method
        ``dynamics`` (``weibull`` or ``gumbel``) or ``stochastic`` (``rayleigh``).
    line_names, element_line
        Line ids, line index of each element.
    mpm, element_mpm
        Most probable maximum over ``duration`` [force]: (n_lines, 2), (n_elements,).
    maximum, element_maximum
        Largest sampled tension over all realizations (NaN in the frequency domain).
    mean, std
        Mean and standard deviation of the line-end tensions (n_lines, 2).
    percentiles, percentile
        Levels [%] (n_q,) and the tension percentiles (n_q, n_lines, 2): sampled (time
        domain) or of the Gaussian process (frequency domain).
    fit_location, fit_shape, fit_scale
        Fit parameters per line end: Weibull of the peak excess (location the mean), Gumbel
        of the block maxima (shape NaN); frequency domain: NaN.
    events
        Peaks counted (weibull), maxima fitted (gumbel) or expected zero-up-crossings in
        ``duration`` (rayleigh), per line end.
    duration
        Exposure of the MPM [s].
    realizations, record_length
        Number of realizations (seeds) and the analysed length of each [s].
    """

    source: str
    method: str
    line_names: tuple[str, ...]
    element_line: NDArray[np.int64]
    mpm: FloatArray
    element_mpm: FloatArray
    maximum: FloatArray
    element_maximum: FloatArray
    mean: FloatArray
    std: FloatArray
    percentiles: FloatArray
    percentile: FloatArray
    fit_location: FloatArray
    fit_shape: FloatArray
    fit_scale: FloatArray
    events: FloatArray
    duration: float
    realizations: int
    record_length: float
    seeds: tuple[int, ...] = ()
    settings: Any = None
    success: bool = True
    status: str = "completed"
    message: str = ""
    case: str = ""
    units: str = "SI"
    counters: dict = field(default_factory=dict)

    def to_plain(self) -> PlainDataset:
        """Group ``extremes``: MPM, maxima, statistics, percentiles and fit parameters."""
        from .datasets import build_plain, group_attrs

        le = ("line", "end")
        data = {"mpm": (le, self.mpm), "maximum": (le, self.maximum),
                "mean_tension": (le, self.mean), "std_tension": (le, self.std),
                "percentile_tension": (("percentile", *le), self.percentile),
                "fit_location": (le, self.fit_location), "fit_shape": (le, self.fit_shape),
                "fit_scale": (le, self.fit_scale), "events": (le, self.events),
                "element_mpm": (("element",), self.element_mpm),
                "element_maximum": (("element",), self.element_maximum)}
        coords = {"line": list(self.line_names), "end": ["a", "b"],
                  "percentile": self.percentiles,
                  "element": np.arange(len(self.element_line)),
                  "element_line": (("element",),
                                   [self.line_names[int(k)] for k in self.element_line])}
        attrs = group_attrs("extremes", case=self.case, units=self.units,
                            success=self.success, status=self.status, message=self.message,
                            counters=self.counters, settings=self.settings,
                            extra={"source": self.source, "method": self.method,
                                   "duration": self.duration,
                                   "realizations": self.realizations,
                                   "record_length": self.record_length,
                                   "seeds": ",".join(map(str, self.seeds))})
        return build_plain("extremes", data, coords, attrs)


def _time_domain(signals: FloatArray, settings: Any, record: float
                 ) -> tuple[FloatArray, ...]:
    """MPM, fit parameters and event counts of each column of ``signals`` (n_real, n_t, n)."""
    n_real, n_t, n = signals.shape
    out = np.full((4, n), np.nan)  # mpm, location, shape, scale
    events = np.zeros(n)
    for j in range(n):
        series = signals[:, :, j]
        if settings.method == "gumbel":
            blocks = np.array_split(series, settings.blocks, axis=1)
            maxima = np.concatenate([b.max(axis=1) for b in blocks])
            loc, scale = gumbel_fit(maxima)
            n_blocks = settings.duration / (record / settings.blocks)
            out[:, j] = gumbel_mpm(loc, scale, n_blocks), loc, np.nan, scale
            events[j] = len(maxima)
            continue
        level = float(series.mean())
        found = np.concatenate([peaks(s, level) for s in series])
        events[j] = len(found)
        if len(found) < 2 or np.ptp(found) == 0.0:
            # no scatter to fit: the peaks are the maximum
            out[:, j] = (found.max() if len(found) else series.max()), level, np.nan, np.nan
            continue
        shape, scale = weibull_fit(found - level)
        expected = settings.duration * len(found) / (n_real * record)
        out[:, j] = weibull_mpm(level, shape, scale, expected), level, shape, scale
    return (*out, events)


def solve_extremes(records: TensionRecords, settings: Any, case: str = "",
                   units: str = "SI") -> ExtremesResult:
    """Most probable maxima, maxima, statistics and percentiles per line end and element.

    Parameters
    ----------
    records
        The tension signals (:mod:`moorline.tension_records`).
    settings
        :class:`~moorline.model.ExtremesSettings`.
    case, units
        For output.

    Raises
    ------
    MoorlineError
        When a fit is impossible (too few peaks or maxima).
    """
    q = np.asarray(settings.percentiles, dtype=float)
    n_lines, n_el = len(records.line_names), len(records.element_line)
    if records.source == "dynamics":
        n_real, n_t = records.end.shape[:2]
        record = records.duration
        ends = records.end.reshape(n_real, n_t, -1)
        try:
            mpm, loc, shape, scale, events = _time_domain(ends, settings, record)
            element_mpm = _time_domain(records.element, settings, record)[0]
        except ValueError as exc:
            raise MoorlineError(f"extremes: {exc}") from None
        pooled = ends.reshape(n_real * n_t, -1)
        shape_le = (n_lines, 2)
        return ExtremesResult(
            source="dynamics", method=settings.method, line_names=records.line_names,
            element_line=records.element_line, mpm=mpm.reshape(shape_le),
            element_mpm=element_mpm, maximum=pooled.max(axis=0).reshape(shape_le),
            element_maximum=records.element.max(axis=(0, 1)),
            mean=pooled.mean(axis=0).reshape(shape_le),
            std=pooled.std(axis=0).reshape(shape_le), percentiles=q,
            percentile=np.percentile(pooled, q, axis=0).reshape(len(q), *shape_le),
            fit_location=loc.reshape(shape_le), fit_shape=shape.reshape(shape_le),
            fit_scale=scale.reshape(shape_le), events=events.reshape(shape_le),
            duration=float(settings.duration), realizations=n_real, record_length=record,
            seeds=records.seeds, settings=settings,
            message=(f"{settings.method} MPM over {settings.duration:.6g} s from {n_real} "
                     f"realization(s) of {record:.6g} s"), case=case, units=units)
    from scipy.stats import norm

    end_m = spectral_moments(records.omega, records.end_spectrum, records.d_omega, (0, 2))
    el_m = spectral_moments(records.omega, records.element_spectrum, records.d_omega, (0, 2))
    sigma = np.sqrt(end_m[0])
    nan = np.full((n_lines, 2), np.nan)
    return ExtremesResult(
        source="stochastic", method="rayleigh", line_names=records.line_names,
        element_line=records.element_line,
        mpm=rayleigh_mpm(records.end_mean, end_m[0], end_m[1], settings.duration),
        element_mpm=rayleigh_mpm(records.element_mean, el_m[0], el_m[1], settings.duration),
        maximum=nan, element_maximum=np.full(n_el, np.nan), mean=records.end_mean,
        std=sigma, percentiles=q,
        percentile=records.end_mean + sigma * norm.ppf(q / 100.0)[:, None, None],
        fit_location=nan, fit_shape=nan, fit_scale=nan,
        events=upcrossing_rate(end_m[0], end_m[1]) * settings.duration,
        duration=float(settings.duration), realizations=1,
        record_length=2.0 * np.pi / records.d_omega, settings=settings,
        message=f"Rayleigh MPM over {settings.duration:.6g} s of the stochastic response",
        case=case, units=units)
