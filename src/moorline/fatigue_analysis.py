"""The fatigue analysis (``kind: fatigue``): Miner damage and fatigue life per line end and
per element from the run's preceding dynamics (rainflow counting of the tension histories)
or stochastic analysis (narrow-band and Dirlik damage from the tension spectra).

The curve of each line type comes from the analysis's ``curves`` (a curve of
:mod:`moorline.tn_curves` and the reference breaking strength ``MBL`` or the nominal
``diameter`` / ``area`` it needs). The damage is that of the analysed duration: the
simulated time after ``skip`` (time domain) or the stochastic analysis's record length
``2 pi / d_omega`` (frequency domain); the life is that duration over the damage (times the
design fatigue factor ``safety_factor``), in years of 365.25 days.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from .errors import MoorlineError
from .fatigue import miner_damage, rainflow, spectral_damage
from .plain_dataset import PlainDataset, PlainResult
from .spectral import spectral_moments, upcrossing_rate
from .tension_records import TensionRecords
from .tn_curves import TNCurve, curve

__all__ = ["YEAR", "FatigueResult", "line_type_curves", "solve_fatigue"]

FloatArray = NDArray[np.float64]

#: One year [s] (365.25 days).
YEAR = 365.25 * 86400.0


@dataclass(frozen=True)
class FatigueResult(PlainResult):
    """Fatigue damage and life of one analysed state.

    Attributes
    ----------
    source
        ``dynamics`` or ``stochastic``.
    methods
        ``rainflow`` (time domain), ``narrow_band`` and/or ``dirlik`` (frequency domain).
    line_names, element_line
        Line ids, line index of each element.
    damage, element_damage
        Miner damage over ``duration`` per method: (n_methods, n_lines, 2) at the line ends
        (a, b) and (n_methods, n_elements); NaN where the line type has no curve.
    cycles, element_cycles
        Cycles over ``duration``: rainflow counts (time domain) or expected zero-up-crossings
        ``nu_0 T`` (frequency domain).
    end_mean, element_mean
        Mean tensions [force].
    duration
        Analysed duration [s] (of one realization: the damage is the mean over them).
    realizations, seeds
        Number of time-domain realizations averaged and their wave seeds (-1: not a random
        sea); 1 and ``()`` in the frequency domain.
    safety_factor
        Design fatigue factor applied to the life.
    curves
        Line type -> ``(curve, scale)``: the curve and the tension per unit of its normalized
        range [force].
    """

    source: str
    methods: tuple[str, ...]
    line_names: tuple[str, ...]
    element_line: NDArray[np.int64]
    damage: FloatArray
    element_damage: FloatArray
    cycles: FloatArray
    element_cycles: FloatArray
    end_mean: FloatArray
    element_mean: FloatArray
    duration: float
    safety_factor: float
    curves: dict[str, tuple[TNCurve, float]]
    realizations: int = 1
    seeds: tuple[int, ...] = ()
    settings: Any = None
    success: bool = True
    status: str = "completed"
    message: str = ""
    case: str = ""
    units: str = "SI"
    counters: dict = field(default_factory=dict)

    @property
    def life(self) -> FloatArray:
        """Fatigue life at the line ends [years]: ``duration / (safety_factor damage)``."""
        return _life(self.damage, self.duration, self.safety_factor)

    @property
    def element_life(self) -> FloatArray:
        """Fatigue life per element [years]."""
        return _life(self.element_damage, self.duration, self.safety_factor)

    def to_plain(self) -> PlainDataset:
        """Group ``fatigue``: damage, annual damage, life and cycles per method at the line
        ends and per element, mean tensions."""
        from .datasets import build_plain, group_attrs

        annual = YEAR / self.duration
        data = {
            "damage": (("fatigue_method", "line", "end"), self.damage),
            "annual_damage": (("fatigue_method", "line", "end"), self.damage * annual),
            "life": (("fatigue_method", "line", "end"), self.life),
            "cycles": (("line", "end"), self.cycles),
            "mean_tension": (("line", "end"), self.end_mean),
            "element_damage": (("fatigue_method", "element"), self.element_damage),
            "element_life": (("fatigue_method", "element"), self.element_life),
            "element_cycles": (("element",), self.element_cycles),
            "element_mean_tension": (("element",), self.element_mean)}
        coords = {"fatigue_method": list(self.methods), "line": list(self.line_names),
                  "end": ["a", "b"], "element": np.arange(len(self.element_line)),
                  "element_line": (("element",),
                                   [self.line_names[int(k)] for k in self.element_line])}
        curves = "; ".join(f"{t}: {c.name} (scale {s:.6g})" for t, (c, s) in
                           self.curves.items())
        sources = "; ".join(f"{c.name}: {c.source}" for c, _ in self.curves.values())
        attrs = group_attrs("fatigue", case=self.case, units=self.units, success=self.success,
                            status=self.status, message=self.message, counters=self.counters,
                            extra={"source": self.source, "duration": self.duration,
                                   "realizations": self.realizations,
                                   "seeds": ",".join(map(str, self.seeds)),
                                   "safety_factor": self.safety_factor, "curves": curves,
                                   "curve_sources": sources})
        attrs.update(_settings_attrs(self.settings))
        return build_plain("fatigue", data, coords, attrs)


def _life(damage: FloatArray, duration: float, factor: float) -> FloatArray:
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(damage > 0, duration / (factor * damage) / YEAR, np.inf) \
            * np.where(np.isnan(damage), np.nan, 1.0)


def _settings_attrs(settings: Any) -> dict[str, Any]:
    """The settings as group attributes, the per-type curves flattened to text."""
    from .datasets import settings_attrs

    if settings is None:
        return {}
    fields = {k: v for k, v in vars(settings).items() if k != "curves"}
    out = settings_attrs(fields)
    out["setting_curves"] = "; ".join(
        f"{t}: " + ", ".join(f"{k} {v}" for k, v in dict(c).items() if v is not None)
        for t, c in (settings.curves or {}).items())
    return out


def line_type_curves(choices: Mapping[str, Mapping[str, Any]], types: set[str],
                     units: str, line_types: Mapping[str, Any] | None = None
                     ) -> dict[str, tuple[TNCurve, float]]:
    """The curve and scale of each line type from the analysis's ``curves`` entries
    (``{type: {curve, MBL, diameter, area}}``); without an ``MBL`` there, the line type's
    own ``MBL`` attribute when it has one (``line_types``: the system's line types).

    Raises
    ------
    MoorlineError
        For an unknown curve or line type, or a curve without the strength or area it needs.
    """
    out: dict[str, tuple[TNCurve, float]] = {}
    for name, choice in choices.items():
        if name not in types:
            raise MoorlineError(f"fatigue curves: no line of type {name!r} "
                                f"(line types: {', '.join(sorted(types))})")
        strength = choice.get("MBL")
        if strength is None and line_types is not None and name in line_types:
            strength = getattr(line_types[name], "MBL", None)
        try:
            tn = curve(str(choice["curve"]))
            scale = tn.scale(MBL=strength, diameter=choice.get("diameter"),
                             area=choice.get("area"), units=units)
        except (KeyError, ValueError) as exc:
            raise MoorlineError(f"fatigue curves.{name}: {exc.args[0]}") from None
        out[name] = (tn, scale)
    return out


def _rainflow_damage(signals: FloatArray, means: FloatArray, tn: TNCurve, scale: float,
                     residue: str) -> tuple[FloatArray, FloatArray]:
    """Damage and cycles of each column of ``signals`` (n_real, n_t, n) averaged over
    realizations."""
    n_real, _, n = signals.shape
    damage, cycles = np.zeros(n), np.zeros(n)
    K = tn.intercept(means / scale)
    for j in range(n):
        for r in range(n_real):
            ranges, _, counts = rainflow(signals[r, :, j], residue=residue)  # type: ignore[arg-type]
            damage[j] += miner_damage(ranges / scale, counts, tn.m, float(K[j])) / n_real
            cycles[j] += counts.sum() / n_real
    return damage, cycles


def solve_fatigue(records: TensionRecords, settings: Any, case: str = "",
                  units: str = "SI", line_types: Mapping[str, Any] | None = None
                  ) -> FatigueResult:
    """Miner damage and life per line end and element.

    Parameters
    ----------
    records
        The tension signals (:mod:`moorline.tension_records`).
    settings
        :class:`~moorline.model.FatigueSettings`.
    case, units
        For output.
    line_types
        The system's line types (their ``MBL`` when a curve entry gives none).
    """
    curves = line_type_curves(settings.curves or {}, set(records.line_types), units,
                              line_types)
    if not curves:
        raise MoorlineError("fatigue: give a curve for at least one line type "
                            "(curves: {type: {curve: ..., MBL: ...}})")
    time_domain = records.source == "dynamics"
    methods = ("rainflow",) if time_domain else tuple(settings.spectral)
    n_lines, n_el = len(records.line_names), len(records.element_line)
    damage = np.full((len(methods), n_lines, 2), np.nan)
    element_damage = np.full((len(methods), n_el), np.nan)
    cycles, element_cycles = np.full((n_lines, 2), np.nan), np.full(n_el, np.nan)
    duration = records.duration if time_domain else 2.0 * np.pi / records.d_omega
    line_types = np.asarray(records.line_types)
    element_types = np.asarray(records.element_types)
    for name, (tn, scale) in curves.items():
        lines, elements = np.flatnonzero(line_types == name), np.flatnonzero(element_types == name)
        if time_domain:
            d, c = _rainflow_damage(records.end[:, :, lines].reshape(
                records.end.shape[0], records.end.shape[1], -1),
                records.end_mean[lines].ravel(), tn, scale, settings.residue)
            damage[0, lines], cycles[lines] = d.reshape(-1, 2), c.reshape(-1, 2)
            d, c = _rainflow_damage(records.element[:, :, elements],
                                    records.element_mean[elements], tn, scale,
                                    settings.residue)
            element_damage[0, elements], element_cycles[elements] = d, c
            continue
        for target, spectrum, mean, where, count in (
                (damage, records.end_spectrum[:, lines], records.end_mean[lines], lines,
                 cycles),
                (element_damage, records.element_spectrum[:, elements],
                 records.element_mean[elements], elements, element_cycles)):
            moments = spectral_moments(records.omega, spectrum / scale**2, records.d_omega)
            K = tn.intercept(mean / scale)
            for k, method in enumerate(methods):
                target[k, where] = spectral_damage(moments, tn.m, K, duration, method)
            count[where] = upcrossing_rate(moments[0], moments[2]) * duration
    missing = sorted(set(records.line_types) - set(curves))
    n_real = int(records.end.shape[0]) if time_domain else 1
    message = (f"{'rainflow' if time_domain else ', '.join(methods)} damage over "
               f"{duration:.6g} s of the {records.source} analysis")
    if n_real > 1:
        message += f" (mean of {n_real} realizations, seeds {', '.join(map(str, records.seeds))})"
    if missing:
        message += f"; no curve for line type(s) {', '.join(missing)} (NaN)"
    return FatigueResult(
        source=records.source, methods=methods, line_names=records.line_names,
        element_line=records.element_line, damage=damage, element_damage=element_damage,
        cycles=cycles, element_cycles=element_cycles, end_mean=records.end_mean,
        element_mean=records.element_mean, duration=float(duration),
        safety_factor=float(settings.safety_factor), curves=curves, realizations=n_real,
        seeds=tuple(records.seeds) if time_domain else (), settings=settings,
        message=message, case=case, units=units)
