"""The tension signals a post-processing analysis (fatigue, extremes) works on: histories
(a dynamics result, one or several realizations) or spectra (a stochastic result), at the
line ends and in every element.

Line-end tensions: a dynamics result gives them exactly (the norm of the force of the line
on its end point); a stochastic result gives element tensions only, and the end value is
that of the line's end element.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from .errors import MoorlineError

__all__ = ["TensionRecords", "from_dynamics", "from_stochastic", "preceding", "realizations"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class TensionRecords:
    """Tension signals of one analysed state.

    Attributes
    ----------
    source
        ``dynamics`` (histories) or ``stochastic`` (spectra).
    line_names, line_types
        Line ids and their line-type names.
    element_line
        Line index of each element (n_elements,).
    time, end, element
        Histories: times (n_t,), line-end tensions (n_real, n_t, n_lines, 2) and element
        tensions (n_real, n_t, n_elements), one row per realization (seed).
    seeds
        Wave seed of each realization (``-1`` when the sea is not random).
    omega, d_omega, end_spectrum, element_spectrum
        Spectra: frequencies (n_w,) [rad/s], step, one-sided tension spectra at the line ends
        (n_w, n_lines, 2) and per element (n_w, n_elements).
    end_mean, element_mean
        Mean tensions (n_lines, 2) and (n_elements,).
    """

    source: str
    line_names: tuple[str, ...]
    line_types: tuple[str, ...]
    element_line: NDArray[np.int64]
    end_mean: FloatArray
    element_mean: FloatArray
    time: FloatArray = field(default_factory=lambda: np.zeros(0))
    end: FloatArray = field(default_factory=lambda: np.zeros((0, 0, 0, 2)))
    element: FloatArray = field(default_factory=lambda: np.zeros((0, 0, 0)))
    seeds: tuple[int, ...] = ()
    omega: FloatArray = field(default_factory=lambda: np.zeros(0))
    d_omega: float = 0.0
    end_spectrum: FloatArray = field(default_factory=lambda: np.zeros((0, 0, 2)))
    element_spectrum: FloatArray = field(default_factory=lambda: np.zeros((0, 0)))

    @property
    def duration(self) -> float:
        """Length of one realization [s] (time domain)."""
        return float(self.time[-1] - self.time[0]) if len(self.time) > 1 else 0.0

    @property
    def element_types(self) -> tuple[str, ...]:
        """Line-type name of each element."""
        return tuple(self.line_types[int(k)] for k in self.element_line)


def _line_types(system: Any, mesh: Any) -> tuple[str, ...]:
    return tuple(system.lines[name].line_type for name in mesh.line_names)


def realizations(system: Any, outcome: Any, seeds: Sequence[int], initial: Any = None,
                 cache: dict[int, Any] | None = None, label: str = "realizations"
                 ) -> tuple[list[Any], list[int]]:
    """The preceding dynamics result and the same simulation with each of the wave
    ``seeds`` (a seed equal to the case's is not run again).

    Parameters
    ----------
    system, outcome
        The case and the preceding dynamics analysis (its result and settings).
    seeds
        Wave seeds of the further realizations.
    initial
        The static state the dynamics starts from.
    cache
        Results of seeds already simulated for this outcome (seed -> result), filled here:
        a fatigue and an extremes analysis with the same seeds share the runs.
    label
        The analysis named in error messages.

    Raises
    ------
    MoorlineError
        When seeds are given but the case's sea is not random, or a run fails.
    """
    import dataclasses

    from .model import DynamicsSettings
    from .solvers.dynamics import simulate

    dynamics = outcome.result.settings
    if isinstance(dynamics, dict):
        dynamics = DynamicsSettings(**dynamics)
    waves = system.environment.waves
    if not seeds:
        return [outcome.result], [int(waves.seed) if waves.kind == "random" else -1]
    if waves.kind != "random":
        raise MoorlineError(f"{label}: seeds need a random sea (environment.waves.kind: "
                            "random)")
    cache = {} if cache is None else cache
    results, used = [outcome.result], [int(waves.seed)]
    for seed in map(int, seeds):
        if seed in used:
            continue
        if seed not in cache:
            other = dataclasses.replace(system, environment=dataclasses.replace(
                system.environment, waves=dataclasses.replace(waves, seed=seed)))
            result = simulate(other, dynamics, initial=initial)
            if not result.success:
                raise MoorlineError(f"{label}: the dynamics with seed {seed} failed: "
                                    f"{result.message}")
            cache[seed] = result
        results.append(cache[seed])
        used.append(seed)
    return results, used


def from_dynamics(system: Any, results: Sequence[Any], skip: float,
                  seeds: Sequence[int] = ()) -> TensionRecords:
    """The histories of dynamics results (realizations of the same case) after ``skip``
    seconds of start-up.

    Raises
    ------
    MoorlineError
        When fewer than three records remain after ``skip``.
    """
    first = results[0]
    keep = first.time >= first.time[0] + skip - 1e-9
    if keep.sum() < 3:
        raise MoorlineError(f"fewer than three output records after the first {skip:g} s "
                            "of the dynamics (skip)")
    n_t = int(keep.sum())
    end = np.stack([np.linalg.norm(r.end_force[keep][:n_t], axis=-1) for r in results])
    element = np.stack([np.asarray(r.tension, dtype=float)[keep][:n_t] for r in results])
    mesh = first.mesh
    return TensionRecords(
        source="dynamics", line_names=tuple(mesh.line_names),
        line_types=_line_types(system, mesh),
        element_line=np.asarray(mesh.element_line, dtype=np.int64),
        end_mean=end.mean(axis=(0, 1)), element_mean=element.mean(axis=(0, 1)),
        time=np.asarray(first.time[keep], dtype=float), end=end, element=element,
        seeds=tuple(int(s) for s in seeds) or (-1,) * len(results))


def from_stochastic(system: Any, result: Any) -> TensionRecords:
    """The tension spectra of a stochastic result, ends from the lines' end elements; means
    from its tension series over one record (the static tension plus a zero-mean sum of
    whole periods)."""
    mesh = result.mesh
    spectrum = result.response_spectrum(result.tension_transfer)  # (n_w, n_elements)
    ends = np.array([[e[0], e[-1]] for e in mesh.line_elements], dtype=np.int64)
    element_mean = np.asarray(result.tension, dtype=float).mean(axis=0)
    return TensionRecords(
        source="stochastic", line_names=tuple(mesh.line_names),
        line_types=_line_types(system, mesh),
        element_line=np.asarray(mesh.element_line, dtype=np.int64),
        end_mean=element_mean[ends], element_mean=element_mean,
        omega=np.asarray(result.omega, dtype=float), d_omega=float(result.d_omega),
        end_spectrum=spectrum[:, ends], element_spectrum=spectrum)


def preceding(context: Any, source: str) -> Any:
    """The outcome a post-processing analysis uses: the run's latest successful
    ``dynamics`` or ``stochastic`` analysis (``source='auto'``: whichever came last).

    Raises
    ------
    MoorlineError
        When the run has no such analysis before this one.
    """
    kinds = ("dynamics", "stochastic") if source == "auto" else (source,)
    for outcome in reversed(context.outcomes):
        if outcome.kind in kinds and outcome.success and outcome.result is not None:
            return outcome
    raise MoorlineError(f"needs a successful {' or '.join(kinds)} analysis listed before it "
                        "in the case's analyses")
