"""The analyses a case lists, run in order by ``moorline run``: one runner per kind.

Each runner takes the analysis settings, the :class:`RunContext` (the system, the output
directory, the results file, the outcomes so far) and a label (the NetCDF group and file
prefix), runs the solver, writes its dataset and plots, and returns an :class:`Outcome`.
:data:`RUNNERS` maps each analysis kind to its runner.
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from rich.console import Console
from rich.markup import escape

from . import __version__
from .console import _status
from .errors import ConvergenceError, MoorlineError
from .summaries import dynamics_summary, modal_summary, statics_summary

logger = logging.getLogger(__name__)


# ----------------------------------------------------------------------------- statics


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
    """

    system: Any
    directory: Path
    results: Path
    quiet: bool
    outcomes: list[Outcome] = field(default_factory=list)
    time: float | None = None

    def latest(self, kind: str) -> Outcome | None:
        """The most recent outcome of an analysis kind, if any."""
        return next((o for o in reversed(self.outcomes) if o.kind == kind), None)


class _RunInterruptedError(Exception):
    """Ctrl-C during a run, with the line to print (exit code 130)."""


def _prefix(label: str, kind: str) -> str:
    """File-name prefix of an analysis' plots: none unless its kind repeats."""
    return "" if label == kind else f"{label}_"


def run_statics(settings: Any, context: RunContext, label: str) -> Outcome:
    """Solve statics, add group ``label`` to the results file and plot the configuration."""
    from .io.writers import write_group
    from .plot import plot_configuration
    from .solvers.statics import solve_statics

    system, directory = context.system, context.directory
    with _status(f"solving statics of {system.name} ...", context.quiet) as update:
        result = solve_statics(system, settings)
        logger.info("statics of %s: %s", system.name, result.message)
        update("computing point stiffness ...")
        summary = statics_summary(result)
        update("writing results ...")
        ds = result.to_xarray()
        write_group(ds, context.results, label)
        prefix = _prefix(label, "statics")
        xz, view3d = (directory / f"{prefix}configuration_xz.png",
                      directory / f"{prefix}configuration_3d.png")
        update("plotting ...")
        plot_configuration(ds, xz, view3d)
    return Outcome("statics", bool(result.success), result.message, summary, [xz, view3d],
                   result)


def run_dynamics(settings: Any, context: RunContext, label: str) -> Outcome:
    """Simulate, streaming the histories into group ``label`` of the results file.

    Starts from the preceding statics result of the run when there is one (otherwise the
    solver solves statics itself). A :class:`~moorline.errors.ConvergenceError` ends the
    analysis as failed: the group keeps the records computed so far (``complete = 0``).
    Ctrl-C closes the group the same way and raises :class:`_RunInterruptedError`.
    """
    from .io.writers import read_group
    from .mesh import discretize
    from .plot import plot_motion_history, plot_tension_history
    from .solvers.dynamics import simulate

    system = context.system
    statics = context.latest("statics")
    initial = statics.result if statics is not None and statics.success else None
    mesh = initial.mesh if initial is not None else discretize(system)
    counters: dict[str, int] = {}
    try:
        with _history_writer(context, mesh, settings, label) as writer, \
                _progress(f"{label} of {system.name}", settings.duration,
                          context.quiet) as advance:
            def progress(t: float) -> None:
                context.time = t
                advance(t)

            result = simulate(system, settings, initial=initial, writer=writer,
                              progress=progress)
            counters = {k: int(v) for k, v in result.counters.items()}
            writer.close({"complete": 1, "success": 1, "message": result.message,
                          "status": f"complete: {writer.count} records", **counters})
        success, message = True, result.message
    except ConvergenceError as exc:
        logger.info("dynamics of %s failed: %s", system.name, exc)
        success, message = False, str(exc)
    ds = read_group(context.results, label)
    summary = dynamics_summary(ds, settings, success, message, counters)
    files = []
    if ds.sizes.get("time", 0):
        prefix = _prefix(label, "dynamics")
        files = [context.directory / f"{prefix}tension_history.png",
                 context.directory / f"{prefix}motion_history.png"]
        with _status("plotting ...", context.quiet):
            plot_tension_history(ds, files[0])
            plot_motion_history(ds, files[1])
            if "body_pose" in ds.variables:
                from .plot import plot_body_motion, plot_snapshots

                files.append(context.directory / f"{prefix}body_motion.png")
                plot_body_motion(ds, files[-1])
                files.append(context.directory / f"{prefix}snapshots_3d.png")
                plot_snapshots(ds, files[-1])
    return Outcome("dynamics", success, message, summary, files,
                   result if success else None)


@contextmanager
def _history_writer(context: RunContext, mesh: Any, settings: Any,
                    label: str) -> Iterator[Any]:
    """A :class:`~moorline.io.stream.HistoryWriter` on group ``label`` of the results file."""
    from dataclasses import asdict

    from .io.stream import HistoryWriter
    from .io.units import DIMENSIONS
    from .io.writers import add_analysis

    system = context.system
    units = {key: DIMENSIONS[key].unit(system.units)
             for key in ("length", "velocity", "force", "time")}
    attrs = {"analysis": "dynamics", "case": system.name, "units": system.units,
             "moorline_version": __version__, "seabed_z": float(mesh.seabed_z),
             "output_every": float(max(system.output.every, settings.dt)),
             **{f"setting_{k}": v for k, v in asdict(settings).items()}}
    add_analysis(context.results, label)
    with HistoryWriter(context.results, mesh, attrs, units, group=label) as writer:
        yield writer


@contextmanager
def _progress(description: str, total: float, quiet: bool) -> Iterator[Callable[[float], None]]:
    """A rich progress bar of simulated time on stderr (nothing when quiet); yields a
    function that moves it to time ``t``."""
    if quiet:
        yield lambda _t: None
        return
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
        task = bar.add_task(escape(description), total=total)
        yield lambda t: bar.update(task, completed=t)


def run_modal(settings: Any, context: RunContext, label: str) -> Outcome:
    """Natural modes about the preceding statics result of the run (solved here when there
    is none): group ``label`` of the results file and a plot of the mode shapes."""
    from .plot import plot_mode_shapes
    from .solvers.modal import solve_modes

    def describe(result) -> tuple[str, dict]:
        return result.message, modal_summary(result)

    return _about_statics("modal", "solving the modes", solve_modes, plot_mode_shapes,
                          describe, settings, context, label, filename="mode_shapes.png",
                          failed={"modes": []})


def run_strumming(settings: Any, context: RunContext, label: str) -> Outcome:
    """Strumming by wake oscillators and mode superposition on the run's preceding dynamics
    (or static) state: group ``label`` of the results file and ``strumming.png``."""
    from .io.writers import write_group
    from .plot import plot_strumming
    from .solvers.statics import solve_statics
    from .solvers.strumming import solve_strumming

    system = context.system
    previous = context.latest("dynamics") or context.latest("statics")
    inline = previous.result if previous is not None and previous.success else None
    if inline is None:
        inline = solve_statics(system)
    path = context.directory / f"{_prefix(label, 'strumming')}strumming.png"
    with _status(f"strumming of {system.name} ...", context.quiet) as update:
        try:
            result = solve_strumming(system, settings, inline)
        except MoorlineError as exc:
            return Outcome("strumming", False, str(exc), {"converged": False,
                                                          "message": str(exc)})
        update("writing results ...")
        ds = result.to_xarray()
        write_group(ds, context.results, label)
        plot_strumming(ds, path)
    summary = {"converged": True, "message": f"{len(result.time)} steps",
               "max_lift_coefficient": float(abs(result.lift_coefficient).max()),
               "max_displacement": float(abs(result.displacement).max()),
               "modes": [float(w) for w in result.omega]}
    return Outcome("strumming", True, summary["message"], summary, [path], result)


def _about_statics(kind: str, what: str, solve: Callable, plot: Callable,
                   describe: Callable, settings: Any, context: RunContext, label: str,
                   filename: str | None = None, failed: dict | None = None) -> Outcome:
    """Run an analysis that linearizes about (or starts from) the preceding statics result
    of the run (solved by ``solve`` when there is none): its dataset in group ``label`` of
    the results file, its plot (``filename``, default ``<kind>.png``), its summary from
    ``describe(result)`` (a message and a dict; ``failed`` adds to the summary of a run that
    did not converge)."""
    from .io.writers import write_group

    system = context.system
    statics = context.latest("statics")
    initial = statics.result if statics is not None and statics.success else None
    path = context.directory / f"{_prefix(label, kind)}{filename or kind + '.png'}"
    with _status(f"{what} of {system.name} ...", context.quiet) as update:
        try:
            result = solve(system, settings, initial)
        except ConvergenceError as exc:
            return Outcome(kind, False, str(exc), {"converged": False, "message": str(exc),
                                                   **(failed or {})})
        update("writing results ...")
        ds = result.to_xarray()
        ds.attrs["case"] = system.name
        write_group(ds, context.results, label)
        update("plotting ...")
        plot(ds, path)
    message, details = describe(result)
    return Outcome(kind, True, message, {"converged": True, "message": message, **details},
                   [path], result)


def run_stochastic(settings: Any, context: RunContext, label: str) -> Outcome:
    """Frequency-domain stochastic response to the case's random sea about the preceding
    statics result: group ``label`` of the results file and ``stochastic.png``."""
    from .plot import plot_stochastic
    from .solvers.stochastic import solve_stochastic

    def describe(result) -> tuple[str, dict]:
        return (f"{result.iterations} linearization iterations, {len(result.omega)} "
                f"frequencies ({settings.method})",
                {"iterations": result.iterations,
                 "max_displacement_std": float(result.displacement_std.max(initial=0.0)),
                 "max_tension_std": float(result.tension_std.max(initial=0.0)),
                 "tension_std": [float(v) for v in result.tension_std]})

    return _about_statics("stochastic", "stochastic response", solve_stochastic,
                          plot_stochastic, describe, settings, context, label)


def run_harmonic(settings: Any, context: RunContext, label: str) -> Outcome:
    """Periodic response by harmonic balance from the preceding statics result: group
    ``label`` of the results file and ``harmonic.png``."""
    from .plot import plot_harmonic
    from .solvers.harmonic import solve_harmonic

    def describe(result) -> tuple[str, dict]:
        return (f"converged in {result.iterations} Newton iterations "
                f"({settings.harmonics} harmonics)",
                {"iterations": result.iterations,
                 "max_first_harmonic_amplitude": float(result.amplitude(1).max(initial=0.0)),
                 "tension_min": [float(v) for v in result.tension.min(axis=0)],
                 "tension_max": [float(v) for v in result.tension.max(axis=0)]})

    return _about_statics("harmonic", "harmonic balance", solve_harmonic, plot_harmonic,
                          describe, settings, context, label)


#: Runner of each analysis kind a case may list: (settings, context, label) -> Outcome.
RUNNERS: dict[str, Callable[[Any, RunContext, str], Outcome]] = {
    "statics": run_statics,
    "dynamics": run_dynamics,
    "modal": run_modal,
    "strumming": run_strumming,
    "stochastic": run_stochastic,
    "harmonic": run_harmonic,
}


def _labels(kinds: list[str]) -> list[str]:
    """Group and file labels: the kind, numbered when a kind appears more than once."""
    seen: dict[str, int] = {}
    labels = []
    for kind in kinds:
        seen[kind] = seen.get(kind, 0) + 1
        labels.append(kind if kinds.count(kind) == 1 else f"{kind}{seen[kind]}")
    return labels


def _analysis_kind(analysis: Any) -> str:
    return str(getattr(analysis, "kind", type(analysis).__name__))


def _run_analyses(context: RunContext, analyses: list[Any], kinds: list[str]) -> None:
    """Run the analyses in order into ``context`` (stopping after one that fails), then mark
    the results file complete or not; Ctrl-C becomes :class:`_RunInterruptedError`."""
    from .io.writers import start_results, update_results

    system = context.system
    start_results(context.results, {"case": system.name, "units": system.units,
                                    "moorline_version": __version__, "analyses": ""})
    label = ""
    try:
        for kind, analysis, label in zip(kinds, analyses, _labels(kinds), strict=True):
            context.time = None
            outcome = RUNNERS[kind](analysis, context, label)
            context.outcomes.append(outcome)
            if not outcome.success:
                break
    except KeyboardInterrupt:
        when = f"at t = {context.time:.6g} s" if context.time is not None else f"in {label}"
        update_results(context.results, {"complete": 0, "status": f"interrupted {when}"})
        raise _RunInterruptedError(f"interrupted {when}; results so far in "
                           f"{context.results}") from None
    failed = [o for o in context.outcomes if not o.success]
    status = f"{failed[0].kind} failed: {failed[0].message}" if failed else "complete"
    update_results(context.results, {"complete": int(not failed), "status": status})
