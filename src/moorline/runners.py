"""The analyses a case lists, run in order by ``moorline run``: one runner per kind.

Each runner takes the analysis settings, the :class:`RunContext` (the system, the output
directory, the results file, the outcomes so far) and a label (the NetCDF group and file
prefix), runs the solver, writes its dataset and plots, and returns an :class:`Outcome`; a
failed result is written all the same and gives a failed outcome (the CLI prints its message
and exits 1). :data:`moorline.analyses.KINDS` names each kind's runner.
"""

from __future__ import annotations

import logging
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from . import __version__
from .analyses import KINDS
from .console import _note, _status
from .errors import CaseError, ConvergenceError, MoorlineError
from .signals import Terminated
from .status import Status

logger = logging.getLogger(__name__)


RESULTS_FILE = "results.nc"


@dataclass
class Outcome:
    """What one analysis of a case produced.

    Attributes
    ----------
    kind, success, message
        The analysis kind, whether it succeeded, and how it ended.
    summary
        Its part of the ``--json`` summary.
    files
        Files it wrote besides the results file (plots).
    result
        The result object (e.g. the :class:`~moorline.results.StaticResult` a following
        dynamics analysis starts from), ``None`` when there is none.
    """

    kind: str
    success: bool
    message: str
    summary: dict[str, Any]
    files: list[Path] = field(default_factory=list)
    result: Any = None


@dataclass
class RunContext:
    """What the analyses of one run share.

    Attributes
    ----------
    system
        The loaded case.
    directory
        Output directory ``DIR/<case>/``.
    results
        The run's results file (``directory/results.nc``); each analysis adds its group.
    quiet
        No progress bars or status messages.
    outcomes
        The analyses done so far, in order.
    time
        Simulated time reached by the running time-domain analysis (for the interrupt
        message), ``None`` outside one.
    plots
        Whether the analyses draw their plots (``--no-plots``: numbers only, and no
        matplotlib import).
    seed_runs
        Dynamics re-run with further wave seeds, per preceding outcome (``id``) and seed,
        shared by the fatigue and extremes analyses that list them.
    """

    system: Any
    directory: Path
    results: Path
    quiet: bool
    outcomes: list[Outcome] = field(default_factory=list)
    time: float | None = None
    plots: bool = True
    seed_runs: dict[int, dict[int, Any]] = field(default_factory=dict)

    def latest(self, kind: str) -> Outcome | None:
        """The most recent outcome of an analysis kind, if any."""
        return next((o for o in reversed(self.outcomes) if o.kind == kind), None)


class _RunInterruptedError(Exception):
    """Ctrl-C or SIGTERM during a run, with the line to print (exit code 130 or 143).

    Attributes
    ----------
    terminated
        SIGTERM (:class:`~moorline.signals.Terminated`) rather than Ctrl-C.
    """

    def __init__(self, message: str, terminated: bool = False) -> None:
        super().__init__(message)
        self.terminated = terminated


def _prefix(label: str, kind: str) -> str:
    """File-name prefix of an analysis' plots: none unless its kind repeats."""
    return "" if label == kind else f"{label}_"


def run_statics(settings: Any, context: RunContext, label: str) -> Outcome:
    """Solve statics, add group ``label`` to the results file and plot the configuration
    (written also when the solve did not converge, for diagnosis)."""
    from .solvers.statics import solve_statics

    return _solve_and_write("statics", "solving statics", lambda: solve_statics(
        context.system, settings), context, label)


def run_dynamics(settings: Any, context: RunContext, label: str) -> Outcome:
    """Simulate, streaming the histories into group ``label`` of the results file.

    Starts from the preceding statics result of the run when there is one (otherwise the
    solver solves statics itself); with ``start: initial``, from the case's body poses (the
    lines at rest with the bodies held there). A failed result (``success`` False), or a
    :class:`~moorline.errors.ConvergenceError`, ends the analysis as failed: the group keeps
    the records computed so far (``success = 0``, ``status = failed``, the message). Ctrl-C
    or SIGTERM closes the group the same way (``interrupted``, ``terminated``) and raises
    :class:`_RunInterruptedError`.
    """
    from .mesh import discretize
    from .solvers.dynamics import simulate
    from .summaries import history_summary

    system = context.system
    statics = context.latest("statics")
    initial = statics.result if statics is not None and statics.success else None
    if settings.start == "initial":  # the case's poses, whatever a statics found
        initial = None
    mesh = initial.mesh if initial is not None else discretize(system)
    result, counters, attrs = None, {}, {}
    first_step: list[float] = []
    started = time.monotonic()
    try:
        with _history_writer(context, mesh, settings, label,
                             initial.tension if initial is not None else None) as writer, \
                _progress(f"{label} of {system.name}", settings.duration,
                          context.quiet) as advance:
            def progress(t: float) -> None:
                if not first_step:
                    first_step.append(time.monotonic() - started)
                context.time = t
                advance(t)

            context.time = 0.0  # a simulation starts at t = 0 (its first record)

            result = simulate(system, settings, initial=initial, writer=writer,
                              progress=progress)
            writer.close(result.dataset_attrs())
            attrs = writer.attrs
        _note_compilation(first_step[0] if first_step else time.monotonic() - started,
                          context.quiet)
        success, message, status = result.success, result.message, result.status
        counters = {k: int(v) for k, v in result.counters.items()}
    except ConvergenceError as exc:
        logger.info("dynamics of %s failed: %s", system.name, exc)
        success, message, status = False, str(exc), str(Status.FAILED)
    if not success:
        logger.info("dynamics of %s failed: %s", system.name, message)
    ds = _history(result, attrs, context, label)
    summary = history_summary(ds, settings, success, message, counters, status)
    files: list[Path] = _moordyn_channels(ds, context, label)
    summary["design"] = _design("dynamics", context, ds, summary)
    if not success:
        summary["design"]["warning"] = ("the run did not complete: the tensions are those of "
                                        "the records written")
    if context.plots:
        with _status("plotting ...", context.quiet):
            files += KINDS["dynamics"].plot_group(ds.to_xarray(), context.directory,
                                                  _prefix(label, "dynamics"))
    return Outcome("dynamics", success, message, summary, files,
                   result if success else None)


def _history(result: Any, attrs: dict[str, Any], context: RunContext, label: str) -> Any:
    """The dynamics group the summary and plots are made from: the result's records in
    memory (the same variables the stream wrote, :meth:`~moorline.results.DynamicResult.
    to_plain`) with the attributes of the group written (``attrs``), or, after a run that
    raised, the records streamed to group ``label`` (read back with netCDF4)."""
    if result is not None:
        ds = result.to_plain()
        ds.attrs.update(attrs)
        return ds
    from .io.netcdf_read import read_plain

    return read_plain(context.results, label)


def _moordyn_channels(ds: Any, context: RunContext, label: str) -> list[Path]:
    """The case's MoorDyn output channels as ``<label>_moordyn_channels.csv`` (none without
    channels), :func:`moorline.io.moordyn_outputs.write_channels`."""
    from .io.moordyn_outputs import CHANNELS_FILE, write_channels

    if not context.system.output.channels:
        return []
    context.directory.mkdir(parents=True, exist_ok=True)
    path = context.directory / f"{_prefix(label, 'dynamics')}{CHANNELS_FILE}"
    written = write_channels(ds, context.system, path)
    return [written] if written is not None else []


def _note_compilation(seconds: float, quiet: bool) -> None:
    """Say once that the numba kernels were compiled (the first run on this machine), how
    long it took and where they are cached."""
    from .kernel_cache import compiled_kernels

    compiled, where = compiled_kernels()
    if compiled:
        _note(f"compiled {compiled} numba kernels in {seconds:.1f} s (first run only: cached "
              f"in {where})", quiet)


@contextmanager
def _history_writer(context: RunContext, mesh: Any, settings: Any, label: str,
                    static_tension: Any = None) -> Iterator[Any]:
    """A :class:`~moorline.io.stream.HistoryWriter` on group ``label`` of the results file
    (``static_tension``: the envelope's static tensions, those of the run's statics)."""
    from .datasets import group_attrs
    from .design import line_attrs
    from .io.stream import HistoryWriter
    from .io.writers import add_analysis
    from .seabed_attrs import seabed_attrs

    system = context.system
    attrs = group_attrs("dynamics", case=system.name, units=system.units, success=False,
                        status=Status.RUNNING, message="", settings=settings,
                        extra={"complete": 0, **seabed_attrs(mesh),
                               "output_every": float(max(system.output.every, settings.dt)),
                               **line_attrs(system)})
    add_analysis(context.results, label)
    with HistoryWriter(context.results, mesh, attrs, group=label,
                       static_tension=static_tension) as writer:
        yield writer


@contextmanager
def _progress(description: str, total: float, quiet: bool) -> Iterator[Callable[[float], None]]:
    """A rich progress bar of simulated time on stderr (nothing when quiet); yields a
    function that moves it to time ``t``."""
    if quiet:
        yield lambda _t: None
        return
    from rich.console import Console
    from rich.markup import escape
    from rich.progress import (
        BarColumn,
        Progress,
        TextColumn,
        TimeElapsedColumn,
        TimeRemainingColumn,
    )

    columns = (TextColumn("{task.description}"), BarColumn(),
               TextColumn("t = {task.completed:.2f} / {task.total:g} s"),
               TimeElapsedColumn(), TimeRemainingColumn())
    with Progress(*columns, console=Console(stderr=True)) as bar:
        task = bar.add_task(escape(f"{description} (starting: the first run compiles the "
                                   "kernels)"), total=total)

        def advance(t: float) -> None:
            if t > 0 and not started:
                started.append(True)
                bar.update(task, description=escape(description))
            bar.update(task, completed=t)

        started: list[bool] = []
        yield advance


def _statics_of(context: RunContext) -> Any:
    """The run's preceding statics result when it converged, else ``None``."""
    statics = context.latest("statics")
    return statics.result if statics is not None and statics.success else None


def run_modal(settings: Any, context: RunContext, label: str) -> Outcome:
    """Natural modes about the preceding statics result of the run (solved here when there
    is none): group ``label`` of the results file and a plot of the mode shapes."""
    from .solvers.modal import solve_modes

    return _solve_and_write("modal", "solving the modes", lambda: solve_modes(
        context.system, settings, _statics_of(context)), context, label)


def run_strumming(settings: Any, context: RunContext, label: str) -> Outcome:
    """Strumming by wake oscillators and mode superposition on the run's preceding dynamics
    (or static) state: group ``label`` of the results file and ``strumming.png``."""
    from .solvers.statics import solve_statics
    from .solvers.strumming import solve_strumming

    def solve() -> Any:
        previous = context.latest("dynamics") or context.latest("statics")
        inline = previous.result if previous is not None and previous.success else None
        if inline is None:
            inline = solve_statics(context.system)
        return solve_strumming(context.system, settings, inline)

    return _solve_and_write("strumming", "strumming", solve, context, label)


def run_stochastic(settings: Any, context: RunContext, label: str) -> Outcome:
    """Frequency-domain stochastic response to the case's random sea about the preceding
    statics result: group ``label`` of the results file and ``stochastic.png``."""
    from .solvers.stochastic import solve_stochastic

    def solve() -> Any:
        started = time.monotonic()
        result = solve_stochastic(context.system, settings, _statics_of(context))
        _note_compilation(time.monotonic() - started, context.quiet)  # the banded sweep
        return result

    return _solve_and_write("stochastic", "stochastic response", solve, context, label)


def run_harmonic(settings: Any, context: RunContext, label: str) -> Outcome:
    """Periodic response by harmonic balance from the preceding statics result: group
    ``label`` of the results file and ``harmonic.png``."""
    from .solvers.harmonic import solve_harmonic

    return _solve_and_write("harmonic", "harmonic balance", lambda: solve_harmonic(
        context.system, settings, _statics_of(context)), context, label)


def run_offset(settings: Any, context: RunContext, label: str) -> Outcome:
    """Offset curves of a body or a rigid group of prescribed points from the preceding
    statics result (:mod:`moorline.solvers.offset`): group ``label`` of the results file and
    ``offset.png``."""
    from .solvers.offset import solve_offset

    return _solve_and_write("offset", "offset analysis", lambda: solve_offset(
        context.system, settings, _statics_of(context)), context, label)


def _solve_and_write(kind: str, what: str, solve: Callable[[], Any], context: RunContext,
                     label: str) -> Outcome:
    """Run ``solve()``, add its dataset as group ``label`` of the results file, draw the
    kind's plots and summarize it (:data:`moorline.analyses.KINDS`).

    A result that did not succeed is written and plotted all the same (what was computed)
    and gives a failed outcome; a :class:`~moorline.errors.MoorlineError` raised by the
    solver (other than bad input) gives a failed outcome without a group.
    """
    from .io.writers import write_group

    entry = KINDS[kind]
    with _status(f"{what} of {context.system.name} ...", context.quiet) as update:
        try:
            result = solve()
        except CaseError:
            raise
        except MoorlineError as exc:
            logger.info("%s of %s failed: %s", kind, context.system.name, exc)
            return Outcome(kind, False, str(exc), {"converged": False,
                                                   "status": str(Status.FAILED),
                                                   "message": str(exc)})
        logger.info("%s of %s: %s", kind, context.system.name, result.message)
        update("writing results ...")
        ds = result.to_plain()
        if kind in _DESIGN_KINDS:
            from .design import line_attrs

            ds.attrs.update(line_attrs(context.system))
        write_group(ds, context.results, label)
        files: list[Path] = []
        if context.plots:
            update("plotting ...")
            files = entry.plot_group(ds.to_xarray(), context.directory, _prefix(label, kind))
        summary = entry.summarize(result)
        if kind in _DESIGN_KINDS:
            summary["design"] = _design(kind, context, result, summary)
            if not result.success:
                summary["design"]["warning"] = ("the analysis did not succeed: the tensions "
                                                "are those of its last state")
    return Outcome(kind, bool(result.success), result.message, summary, files, result)


_DESIGN_KINDS = ("statics", "dynamics", "stochastic", "extremes")
"""The analysis kinds whose summary has the design checks (:mod:`moorline.design`)."""


def _design(kind: str, context: RunContext, result: Any, summary: dict[str, Any]) -> Any:
    """The ``design`` block of a summary: the lines' largest tensions (from the statics
    summary, the dynamics group ``result``, or the stochastic result about the run's statics)
    checked against the case's standard."""
    from .design import (
        design_summary,
        dynamics_extremes,
        extremes_extremes,
        statics_extremes,
        stochastic_extremes,
    )

    system = context.system
    if kind == "extremes":
        return design_summary(system, kind, extremes_extremes(result),
                              f"most probable maximum over {result.duration:g} s "
                              f"({result.method}, {result.source}), largest of each line's "
                              "ends and elements; mean: at the end with the larger MPM")
    if kind == "statics":
        return design_summary(system, kind, statics_extremes(summary),
                              "largest tension of each line, its ends included")
    if kind == "dynamics":
        return design_summary(system, kind, dynamics_extremes(result),
                              "largest tension of each line over the output records, its "
                              "ends included; mean: the time mean there")
    statics = _statics_of(context)
    static = statics.tension if statics is not None else result.tension.mean(axis=0)
    duration = system.design.storm_duration if system.design is not None else None
    extremes = stochastic_extremes(result, static, duration)
    return design_summary(system, kind, extremes,
                          "static tension plus the most probable maximum of the stochastic "
                          "tension over the storm, largest element of each line (end "
                          "tensions are not computed)")


def _labels(kinds: list[str]) -> list[str]:
    """Group and file labels: the kind, numbered when a kind appears more than once."""
    seen: dict[str, int] = {}
    labels = []
    for kind in kinds:
        seen[kind] = seen.get(kind, 0) + 1
        labels.append(kind if kinds.count(kind) == 1 else f"{kind}{seen[kind]}")
    return labels


def _run_analyses(context: RunContext, analyses: list[Any], kinds: list[str]) -> None:
    """Run the analyses in order into ``context`` (stopping after one that fails), then mark
    the results file complete or not; Ctrl-C or SIGTERM becomes :class:`_RunInterruptedError`
    (the results file's status ``interrupted`` or ``terminated``)."""
    from .io.writers import start_results, update_results

    system = context.system
    start_results(context.results, {"case": system.name, "units": system.units,
                                    "moorline_version": __version__, "analyses": "",
                                    "moordyn_channels": " ".join(system.output.channels)})
    label = ""
    try:
        for kind, analysis, label in zip(kinds, analyses, _labels(kinds), strict=True):
            context.time = None
            outcome = KINDS[kind].run(analysis, context, label)
            context.outcomes.append(outcome)
            if not outcome.success:
                break
    except KeyboardInterrupt as exc:
        terminated = isinstance(exc, Terminated)
        word = str(Status.TERMINATED if terminated else Status.INTERRUPTED)
        when = f"at t = {context.time:.6g} s" if context.time is not None else f"in {label}"
        update_results(context.results, {"complete": 0, "status": f"{word} {when}"})
        raise _RunInterruptedError(f"{word} {when}; results so far in {context.results}",
                                   terminated) from None
    failed = [o for o in context.outcomes if not o.success]
    status = f"{failed[0].kind} failed: {failed[0].message}" if failed else "complete"
    update_results(context.results, {"complete": int(not failed), "status": status})


def _records(context: RunContext, settings: Any) -> Any:
    """The tension signals of the run's preceding dynamics or stochastic analysis
    (:mod:`moorline.tension_records`); time domain: after ``settings.skip`` (default the
    dynamics' ramp time), with the realizations of the further wave ``settings.seeds``."""
    from .tension_records import from_dynamics, from_stochastic, preceding, realizations

    outcome = preceding(context, settings.source)
    if outcome.kind == "stochastic":
        return from_stochastic(context.system, outcome.result)
    dynamics = outcome.result.settings
    ramp = dynamics.get("ramp_time", 0.0) if isinstance(dynamics, dict) else getattr(
        dynamics, "ramp_time", 0.0)
    skip = settings.skip if settings.skip is not None else float(ramp)
    cache = context.seed_runs.setdefault(id(outcome), {})
    results, used = realizations(context.system, outcome, tuple(settings.seeds),
                                 _statics_of(context), cache, settings.kind)
    return from_dynamics(context.system, results, skip, used)


def run_fatigue(settings: Any, context: RunContext, label: str) -> Outcome:
    """Miner damage and fatigue life per line end and element from the run's preceding
    dynamics (rainflow, averaged over the realizations of the listed wave seeds) or
    stochastic (narrow band, Dirlik) analysis: group ``label`` of the results file."""
    from .fatigue_analysis import solve_fatigue

    system = context.system
    return _solve_and_write("fatigue", "fatigue", lambda: solve_fatigue(
        _records(context, settings), settings, system.name, system.units,
        system.line_types), context, label)


def run_extremes(settings: Any, context: RunContext, label: str) -> Outcome:
    """Most probable maximum tensions, maxima and percentiles per line end and element from
    the run's preceding dynamics (repeated with the listed wave seeds) or stochastic
    analysis: group ``label`` of the results file."""
    from .extremes_analysis import solve_extremes

    system = context.system
    return _solve_and_write("extremes", "extremes", lambda: solve_extremes(
        _records(context, settings), settings, system.name,
        system.units), context, label)
