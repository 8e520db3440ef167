"""The ``moorline`` command line: ``statics``, ``run``, ``verify`` and ``plot``.

``statics`` and ``run`` write ``DIR/<case>/``: one results file ``results.nc`` with a NetCDF
group per analysis (see :mod:`moorline.io.writers`), plots, ``summary.json``,
``summary.txt`` and ``report.html`` (one self-contained page, :mod:`moorline.report`). The
analysis kinds a case may list, with their runners, plots and summaries, are the table
:data:`moorline.analyses.KINDS`.

Exit codes: 0 success; 1 the analysis failed (a result with ``success`` False: no convergence,
a time step that failed; its message is printed and what was computed is written; a
verification row out of tolerance); 2 bad input (a case file that does not validate, a
missing or unreadable file, an unknown name); 130 interrupted (Ctrl-C), 143 terminated
(SIGTERM, e.g. from ``timeout`` or a batch scheduler): the results file keeps what was
computed, with status ``interrupted`` or ``terminated``; a second signal during the clean-up
is ignored (see :mod:`moorline.signals`). Expected errors print
``error: <file>: <key path>: <reason>`` on stderr, never a traceback; unexpected exceptions
are bugs and keep their traceback.

With ``--json`` a command prints exactly one JSON document on stdout and nothing else; logs,
progress and errors go to stderr. This is the only module that configures ``logging``.
"""

from __future__ import annotations

import json
import logging
import re
import sys
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import TYPE_CHECKING, Any, TypeVar

import click

from . import __version__
from .analyses import KINDS
from .console import _escape, _note, _status, _stdout, _stdout_is_terminal, _table
from .errors import CaseError, ConvergenceError, MoorlineError
from .runners import (
    RESULTS_FILE,
    RunContext,
    _prefix,
    _run_analyses,
    _RunInterruptedError,
)
from .signals import Terminated, handle_signals
from .threads import one_blas_thread

if TYPE_CHECKING:
    from rich.table import Table

logger = logging.getLogger(__name__)

EXIT_OK, EXIT_FAILED, EXIT_BAD_INPUT, EXIT_INTERRUPTED, EXIT_TERMINATED = 0, 1, 2, 130, 143
F = TypeVar("F", bound=Callable[..., Any])


# ----------------------------------------------------------------------------- plumbing


class _Cli(click.Group):
    """A group that turns moorline's expected errors into one-line messages and exit codes."""

    def invoke(self, ctx: click.Context) -> Any:
        with handle_signals():
            return self._invoke(ctx)

    def resolve_command(self, ctx: click.Context, args: list[str]) -> Any:
        """The command to run; OpenBLAS is set to one thread for it before anything imports
        numpy (:func:`moorline.threads.one_blas_thread`)."""
        name, command, rest = super().resolve_command(ctx, args)
        one_blas_thread(name)
        return name, command, rest

    def _invoke(self, ctx: click.Context) -> Any:
        try:
            return super().invoke(ctx)
        except CaseError as exc:
            _fail(str(exc), EXIT_BAD_INPUT)
        except ConvergenceError as exc:
            _fail(str(exc), EXIT_FAILED)
        except MoorlineError as exc:
            _fail(str(exc), EXIT_FAILED)
        except OSError as exc:
            _fail(_describe_os_error(exc), EXIT_BAD_INPUT)
        except _RunInterruptedError as exc:
            click.echo(str(exc), err=True)
            code = EXIT_TERMINATED if exc.terminated else EXIT_INTERRUPTED
            raise click.exceptions.Exit(code) from None
        except Terminated:
            click.echo("terminated", err=True)
            raise click.exceptions.Exit(EXIT_TERMINATED) from None
        except KeyboardInterrupt:
            click.echo("interrupted", err=True)
            raise click.exceptions.Exit(EXIT_INTERRUPTED) from None


def _fail(message: str, code: int) -> None:
    """Print ``error: message`` on stderr and exit with ``code``."""
    click.echo(f"error: {message}", err=True)
    raise click.exceptions.Exit(code)


def _describe_os_error(exc: OSError) -> str:
    if exc.filename is not None and exc.strerror:
        return f"{exc.filename}: {exc.strerror}"
    return str(exc) or exc.__class__.__name__


class _StderrHandler(logging.StreamHandler):
    """Writes to whatever ``sys.stderr`` is at the time of the record (test runners swap it)."""

    @property  # type: ignore[override]
    def stream(self) -> Any:
        return sys.stderr

    @stream.setter
    def stream(self, value: Any) -> None:
        pass


def _configure_logging(verbose: bool) -> None:
    """Send moorline's log records to stderr: WARNING and above, INFO too with ``--verbose``."""
    logger_ = logging.getLogger("moorline")
    for handler in [h for h in logger_.handlers if isinstance(h, _StderrHandler)]:
        logger_.removeHandler(handler)
    handler = _StderrHandler()
    handler.setFormatter(logging.Formatter("%(levelname)s: %(name)s: %(message)s"))
    handler.setLevel(logging.INFO if verbose else logging.WARNING)
    logger_.addHandler(handler)
    logger_.setLevel(logging.INFO if verbose else logging.NOTSET)


def _common_options(func: F) -> F:
    """``--quiet`` and ``--verbose``, shared by every command."""
    func = click.option("--verbose", "-v", is_flag=True,
                        help="Log progress details (INFO) to stderr.")(func)
    func = click.option("--quiet", "-q", is_flag=True,
                        help="No progress or status messages.")(func)
    return func


def _json_option(func: F) -> F:
    return click.option("--json", "as_json", is_flag=True,
                        help="Print one JSON document on stdout and nothing else.")(func)


def _out_option(func: F) -> F:
    return click.option("--out", "out", type=click.Path(file_okay=False, path_type=Path),
                        default=Path("out"), show_default=True,
                        help="Output directory; results go to DIR/<case name>/.")(func)


def _safe_name(name: str, fallback: str) -> str:
    """A directory name for a case (``/`` and other unsafe characters replaced)."""
    cleaned = re.sub(r"[^A-Za-z0-9._-]+", "_", name.strip()).strip("._")
    return cleaned or fallback


def _load(path: Path, quiet: bool = False) -> Any:
    """Load a case file; a :class:`CaseError` without a file gets this one. A MoorDyn deck
    (a file that is not a case and reads as a deck) is converted on the fly, with a note."""
    from . import io as case_io

    try:
        return case_io.load_case(path)
    except CaseError as exc:
        if not exc.file:
            exc.file = str(path)
        from .io.moordyn import is_moordyn_deck

        if not is_moordyn_deck(path):
            raise
    from .io.moordyn import read_moordyn

    system = read_moordyn(path)
    _note(f"{path} is a MoorDyn deck: converted on the fly (`moorline convert {path}` writes "
          "it as a case file)", quiet)
    return system


# ----------------------------------------------------------------------------- commands


@click.group(cls=_Cli, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="moorline")
def cli() -> None:
    """moorline: nonlinear statics and dynamics of ocean mooring cables."""


def _plots_option(func: F) -> F:
    return click.option("--plots/--no-plots", "plots", default=None,
                        help="Draw the plots (default: yes, except with --json for statics); "
                             "--no-plots writes the numbers only.")(func)


@cli.command()
@click.argument("case", type=click.Path(dir_okay=False, path_type=Path))
@_out_option
@_json_option
@_plots_option
@_common_options
def statics(case: Path, out: Path, as_json: bool, plots: bool | None, quiet: bool,
            verbose: bool) -> None:
    """Solve the static equilibrium of CASE (the method of its first statics analysis).

    Writes DIR/<case>/results.nc (group statics), summary.json, summary.txt, report.html,
    configuration_xz.png, configuration_3d.png and configuration_plan.png (the plots not
    with --json unless --plots is given, nor with --no-plots).
    """
    _configure_logging(verbose)
    system = _load(case, quiet)
    settings = system.first("statics")
    context = _context(system, case, out, quiet, plots=not as_json if plots is None else plots)
    _run_analyses(context, [settings], ["statics"])
    _finish(case, context, context.outcomes[0].summary, as_json)


@cli.command()
@click.argument("case", type=click.Path(dir_okay=False, path_type=Path))
@_out_option
@_json_option
@_plots_option
@_common_options
def run(case: Path, out: Path, as_json: bool, plots: bool | None, quiet: bool,
        verbose: bool) -> None:
    """Run every analysis CASE lists, in order, writing DIR/<case>/.

    One results file, results.nc, holds a group per analysis (statics, dynamics; numbered
    when a kind repeats); each analysis adds its plots; summary.json and summary.txt cover
    them all; report.html is one self-contained page of the inputs, tables, checks and plots.
    The run stops after an analysis that fails. Ctrl-C keeps what was computed (exit code
    130) and the report says so.
    """
    _configure_logging(verbose)
    system = _load(case, quiet)
    kinds = [str(getattr(a, "kind", type(a).__name__)) for a in system.analyses] or ["statics"]
    analyses = list(system.analyses) or [None]
    unknown = sorted({k for k in kinds if k not in KINDS})
    if unknown:
        raise CaseError(f"analysis kind {', '.join(map(repr, unknown))} is not supported by "
                        f"this version; supported: {', '.join(KINDS)}", str(case), "analyses")
    context = _context(system, case, out, quiet, plots=plots is not False)
    try:
        _run_analyses(context, analyses, kinds)
    except _RunInterruptedError as exc:  # the report says so, with what was done before
        status, _, message = str(exc).partition("; ")
        _report(context, {**_run_summary(context, kinds), "status": status,
                          "message": message}, _written(context))
        raise
    _finish(case, context, _run_summary(context, kinds), as_json)


def _run_summary(context: RunContext, kinds: list[str]) -> dict[str, Any]:
    """The summary of ``moorline run``: the case, whether every analysis succeeded, and the
    analyses' summaries in order."""
    outcomes = context.outcomes
    return {"case": context.system.name,
            "converged": len(outcomes) == len(kinds) and all(o.success for o in outcomes),
            "units": context.system.units,
            "analyses": [{"kind": o.kind, **o.summary} for o in outcomes]}


def _context(system: Any, case: Path, out: Path, quiet: bool, plots: bool = True) -> RunContext:
    directory = out / _safe_name(system.name, case.stem)
    return RunContext(system, directory, directory / RESULTS_FILE, quiet, plots=plots)


def _written(context: RunContext) -> list[Path]:
    """The results file and the plots of the analyses done so far."""
    return [context.results, *(f for o in context.outcomes for f in o.files)]


def _report(context: RunContext, summary: dict[str, Any], files: list[Path]) -> Path:
    """Write ``report.html`` (:mod:`moorline.report`) of the run into its directory."""
    from .report import write_report

    return write_report(summary, files, context.directory, context.system)


def _finish(case: Path, context: RunContext, summary: dict[str, Any], as_json: bool) -> None:
    """Write the summary and ``report.html``, print the summary, exit 1 when an analysis
    failed."""
    from .io.writers import render_summary, summary_json, summary_text, write_summary

    outcomes, quiet = context.outcomes, context.quiet
    files = [*_written(context), *write_summary(summary, context.directory)]
    files.append(_report(context, summary, files))
    if as_json:
        click.echo(summary_json(summary))
    elif _stdout_is_terminal():
        console = _stdout()
        for renderable in render_summary(summary):
            console.print(renderable)
    else:  # into a pipe or file: rich's layout at 160 columns, without rich
        click.echo(summary_text(summary, width=160), nl=False)
    _note(f"wrote {', '.join(str(f) for f in files)}", quiet)
    failed = [o for o in outcomes if not o.success]
    if failed:
        _fail(f"{case}: {failed[0].kind} failed: {failed[0].message}", EXIT_FAILED)


@cli.command()
@click.argument("case", type=click.Path(dir_okay=False, path_type=Path))
@click.option("--n", "n_modes", type=click.IntRange(min=1), default=None, metavar="N",
              help="Number of lowest modes (default: the case's modal analysis, else 10).")
@_out_option
@_json_option
@click.option("--plots/--no-plots", "plots", default=True,
              help="Draw mode_shapes.png (default: yes); --no-plots writes the numbers only.")
@_common_options
def modes(case: Path, n_modes: int | None, out: Path, as_json: bool, plots: bool, quiet: bool,
          verbose: bool) -> None:
    """Natural frequencies and mode shapes of CASE about its static equilibrium.

    Prints index, omega [rad/s], period [s], frequency [Hz] and dominant direction of each
    mode; adds group modal to DIR/<case>/results.nc (replacing an older modal group, keeping
    the others) and writes mode_shapes.png (not with --no-plots).
    """
    import dataclasses

    from .model import ModalSettings
    from .solvers.modal import solve_modes

    _configure_logging(verbose)
    system = _load(case)
    settings = system.first(ModalSettings)
    if n_modes is not None:
        settings = dataclasses.replace(settings, n_modes=n_modes, band=None)
    context = _context(system, case, out, quiet, plots=plots)
    modal = KINDS["modal"]
    files: list[Path] = []
    with _status(f"solving the modes of {system.name} ...", quiet) as update:
        result = solve_modes(system, settings)
        update("writing results ...")
        ds = result.to_plain()
        _replace_group(context, ds, "modal")
        if plots:
            update("plotting ...")
            files = modal.plot_group(ds.to_xarray(), context.directory)
    if as_json:
        from .io.writers import summary_json

        click.echo(summary_json(modal.summarize(result)))
    else:
        _stdout().print(_modes_table(result))
    _note(f"wrote {', '.join(str(f) for f in [context.results, *files])}", quiet)
    if not result.success:
        _fail(f"{case}: modal failed: {result.message}", EXIT_FAILED)


def _replace_group(context: RunContext, ds: Any, group: str) -> None:
    """Add ``ds`` as ``group`` to the results file, keeping its other groups; an existing
    ``group`` is replaced (NetCDF cannot delete a group: the file is rewritten, the other
    groups read back with netCDF4 alone, :func:`~moorline.io.netcdf_read.read_plain`)."""
    import netCDF4

    from .io.netcdf_read import read_plain
    from .io.writers import result_groups, start_results, write_group

    path = context.results
    if not path.exists():
        start_results(path, {"case": context.system.name, "units": context.system.units,
                             "moorline_version": __version__, "analyses": "",
                             "complete": 1, "status": "complete"})
    elif group in result_groups(path):
        groups = [name for name in result_groups(path) if name and name != group]
        keep = {name: read_plain(path, name) for name in groups}
        with netCDF4.Dataset(path, "r") as root:
            attrs = {key: root.getncattr(key) for key in root.ncattrs()}
        start_results(path, {**attrs, "analyses": ""})
        for name, other in keep.items():
            write_group(other, path, name)
    write_group(ds, path, group)


def _modes_table(result: Any) -> Table:
    table = _table(f"{result.case}: natural modes ({result.message})")
    for name in ("mode", "omega [rad/s]", "period [s]", "frequency [Hz]", "dominant",
                 "share x", "share y", "share z"):
        table.add_column(_escape(name), justify="left" if name == "dominant" else "right")
    for k in range(result.n_modes):
        table.add_row(str(k + 1), _g(result.omega[k]), _g(result.period[k]),
                      _g(result.frequency_hz[k]), _escape(str(result.dominant[k])),
                      *(f"{v:.3f}" for v in result.participation[k]))
    return table


@cli.command()
@click.option("--case", "cases", multiple=True, metavar="NAME",
              help="Run only this verification case (repeatable). Default: all.")
@click.option("--quick", is_flag=True,
              help="Shorter runs with a representative row of every check (about 2 minutes).")
@_json_option
@_common_options
def verify(cases: tuple[str, ...], quick: bool, as_json: bool, quiet: bool,
           verbose: bool) -> None:
    """Run the verification suite and compare with the reference solutions.

    Every row is pass, fail or not reproduced (the source's result is not obtained; the row
    says why). Exit code 0 when no row fails; not-reproduced rows do not count as passed.
    Cases that need another code (MoorPy, MoorDyn: the [compare] extra) are skipped, and said
    so, when it is not installed.
    """
    _configure_logging(verbose)
    import moorline.verification  # noqa: F401  (cases register themselves on import)
    from moorline.verification import core

    known = list(core.CASES)
    unknown = [c for c in cases if c not in core.CASES]
    if unknown:
        _fail(f"unknown verification case {', '.join(map(repr, unknown))}; known cases: "
              f"{', '.join(known) if known else '(none registered)'}", EXIT_BAD_INPUT)
    rows: list[dict[str, Any]] = []
    skipped: dict[str, str] = {}
    with _status("verifying ...", quiet) as update:
        for name in cases or known:
            update(f"verifying {name} ...")
            try:
                rows.extend(_verify_case(core, name, quick))
            except core.CaseSkipped as exc:
                skipped[name] = str(exc)
    if as_json:
        from .io.writers import jsonable

        click.echo(json.dumps(jsonable(rows), indent=2, allow_nan=False))
    else:
        _print_verification(rows, skipped)
    for name, reason in skipped.items():
        _note(f"skipped {name}: {reason}", quiet)
    _note(_verify_summary(rows, skipped), quiet)
    if any(r["status"] == "fail" for r in rows):
        raise click.exceptions.Exit(EXIT_FAILED)


def _verify_case(core: Any, name: str, quick: bool) -> list[dict[str, Any]]:
    """Rows of one case as dicts; a case that raises (other than a skip) gives one failed row
    naming the error."""
    try:
        return [row.to_dict() for row in core.run_case(name, quick)]
    except core.CaseSkipped:
        raise
    except Exception as exc:  # noqa: BLE001 (one broken case must not hide the others)
        reason = str(exc) if isinstance(exc, MoorlineError) else f"{type(exc).__name__}: {exc}"
        click.echo(f"error: verification case {name}: {reason}", err=True)
        return [{"case": name, "quantity": "run",
                 "reference": {"value": None, "kind": None, "source": ""}, "computed": None,
                 "tolerance": None, "relative": False, "unit": "", "error": None,
                 "status": "fail", "passed": False, "note": f"failed: {reason}"}]


def _verify_summary(rows: list[dict[str, Any]], skipped: dict[str, str]) -> str:
    """``N pass, N fail, N not reproduced``, with the internal cross-checks and skipped cases."""
    count = {status: sum(r["status"] == status for r in rows)
             for status in ("pass", "fail", "not reproduced")}
    internal = sum(r["reference"]["kind"] == "internal cross-check" for r in rows)
    other = sum(r["reference"]["kind"] == "other code" for r in rows)
    text = (f"{count['pass']} pass, {count['fail']} fail, {count['not reproduced']} not "
            f"reproduced; of {len(rows)} rows {internal} are internal cross-checks and {other} "
            "compare with another code")
    if skipped:
        text += f"; {len(skipped)} case{'s' if len(skipped) > 1 else ''} skipped"
    return text


_STATUS_STYLE = {"pass": "[green]pass[/green]", "fail": "[bold red]FAIL[/bold red]",
                 "not reproduced": "[yellow]not reproduced[/yellow]"}


def _print_verification(rows: list[dict[str, Any]], skipped: dict[str, str]) -> None:
    """The rows table, then the not-reproduced rows with their reasons, then skipped cases."""
    console = _stdout()
    console.print(_verify_table([r for r in rows if r["status"] != "not reproduced"],
                                "Verification"))
    missing = [r for r in rows if r["status"] == "not reproduced"]
    if missing:
        console.print(_verify_table(missing, "Not reproduced (the source's result is not "
                                             "obtained; see why)", reasons=True))
    if skipped:
        table = _table("Skipped cases")
        table.add_column("case")
        table.add_column("why")
        for name, reason in skipped.items():
            table.add_row(_escape(name), _escape(reason))
        console.print(table)


def _verify_table(rows: list[dict[str, Any]], title: str, reasons: bool = False) -> Table:
    table = _table(title)
    columns = ["case", "quantity", "reference", "computed", "error", "tolerance", "kind",
               "reason" if reasons else "status"]
    for name in columns:
        right = name in ("reference", "computed", "error", "tolerance")
        table.add_column(name, justify="right" if right else "left")
    for row in rows:
        unit = f" {row['unit']}" if row.get("unit") else ""
        rel = " (rel)" if row.get("relative") else unit
        ref = row["reference"]
        last = _escape(str(row.get("note", ""))) if reasons else _STATUS_STYLE[row["status"]]
        table.add_row(
            _escape(str(row["case"])), _escape(str(row["quantity"])),
            _escape(_g(ref["value"]) + unit), _escape(_g(row["computed"]) + unit),
            _escape(_g(row.get("error")) + rel), _escape(_g(row.get("tolerance")) + rel),
            _escape(str(ref["kind"] or "-")), last)
    return table


def _g(value: Any) -> str:
    return "-" if value is None else f"{float(value):.6g}"


@cli.command()
@click.argument("results", type=click.Path(dir_okay=False, path_type=Path))
@click.option("--out", "out", type=click.Path(file_okay=False, path_type=Path), default=None,
              help="Directory for the plots (default: next to RESULTS).")
@click.option("--animate", is_flag=True,
              help="Also write an animated GIF of every dynamics group (animation.gif).")
@_common_options
def plot(results: Path, out: Path | None, animate: bool, quiet: bool, verbose: bool) -> None:
    """Plot a saved RESULTS file (results.nc) again.

    Statics groups give configuration_xz.png, configuration_3d.png and
    configuration_plan.png, dynamics groups
    tension_history.png and motion_history.png (and body_motion.png, snapshots_3d.png with
    bodies; with --animate, animation.gif); modal, strumming, stochastic and harmonic groups
    their own plot (mode_shapes.png, strumming.png, stochastic.png, harmonic.png); prefixed
    with the group name when a kind repeats.
    """
    _configure_logging(verbose)
    from .io.files import file_problem
    from .io.writers import read_group, result_groups

    problem = file_problem(results, limit=1 << 62)
    if problem is not None:
        raise CaseError(f"cannot read the results file: {problem}", str(results))
    try:
        groups = result_groups(results)
        datasets = {name: read_group(results, name) for name, kind in groups.items()
                    if kind in KINDS}
    except (OSError, ValueError) as exc:
        reason = getattr(exc, "strerror", None) or str(exc)
        raise CaseError(f"cannot read as a NetCDF results file ({reason})", str(results)) from exc
    if not datasets:
        raise CaseError("not a moorline results file (no statics or dynamics group)",
                        str(results))
    directory = out if out is not None else results.parent
    files: list[Path] = []
    with _status("plotting ...", quiet):
        for name, ds in datasets.items():
            files.extend(_plot_group(ds, groups[name], name or groups[name], directory))
            if animate and groups[name] == "dynamics" and ds.sizes.get("time", 0):
                from .plot import animate_run

                files.append(directory / f"{_prefix(name or 'dynamics', 'dynamics')}"
                                         "animation.gif")
                animate_run(ds, files[-1])
    _note(f"wrote {', '.join(str(f) for f in files)}", quiet)


def _plot_group(ds: Any, kind: str, label: str, directory: Path) -> list[Path]:
    """The plots of one analysis group (its kind's plot in :data:`moorline.analyses.KINDS`);
    returns the files written."""
    try:
        return KINDS[kind].plot_group(ds, directory, _prefix(label, kind))
    except (KeyError, ValueError) as exc:
        raise CaseError(f"group {label}: {exc}") from None


@cli.command()
@click.argument("study", type=click.Path(dir_okay=False, path_type=Path))
@click.option("--out", "out", type=click.Path(file_okay=False, path_type=Path),
              default=Path("out"), show_default=True,
              help="Output directory; results go to DIR/<study name>/.")
@click.option("--workers", "workers", type=click.IntRange(min=1), default=None,
              help="Run the cases on a local Dask cluster of N worker processes.")
@click.option("--scheduler", "scheduler", metavar="ADDRESS", default=None,
              help="Run the cases on the Dask cluster of this scheduler "
                   "(tcp://host:8786; its workers need moorline).")
@_json_option
@_common_options
def sweep(study: Path, out: Path, workers: int | None, scheduler: str | None, as_json: bool,
          quiet: bool, verbose: bool) -> None:
    """Run the parameter study STUDY (see moorline.sweep) and gather its outputs.

    Writes DIR/<study>/table.csv, table.nc (one row per case: parameters, steady-state
    outputs, status) and trends.png (each output against the varied parameter). The table
    is rewritten as cases finish (at most every second) and when stopped, so a study
    stopped mid-way keeps what finished (status "not run" for the rest); the progress line
    shows the cases done and the time
    left (from the mean case time). The cases run one after the other, or in parallel on
    Dask with --workers or --scheduler (the optional [dask] extra). Exit code 1 when a case
    failed.
    """
    _configure_logging(verbose)
    from .sweep import (
        dask_mapper,
        eta_text,
        load_study,
        run_study,
        study_cases,
        warm_up,
        write_study,
    )

    spec = load_study(study)
    directory = out / _safe_name(spec.name, study.stem)
    n_cases = len(study_cases(spec))
    with _status(f"study {spec.name}: {n_cases} cases ...", quiet) as update:
        done = {"text": ""}

        def progress(finished: int, total: int, elapsed: float) -> None:
            done["text"] = eta_text(finished, total, elapsed)
            update(f"study {spec.name}: {done['text']}")
            logger.info("study %s: %s", spec.name, done["text"])

        def counted(function: Callable[..., Any], cases: list[Any]) -> Iterator[Any]:
            for k, params in enumerate(cases):
                update(f"study {spec.name}: case {k + 1} of {len(cases)} ({params})"
                       + (f"; {done['text']}" if done["text"] else "") + " ...")
                yield function(params)

        close = None
        mapper: Callable[..., Any] = counted
        if workers is not None or scheduler is not None:
            try:
                mapper, close = dask_mapper(scheduler, workers,
                                            warm=lambda: warm_up(spec))
            except MoorlineError as exc:
                _fail(f"{study}: {exc}", EXIT_BAD_INPUT)
        try:
            table = run_study(spec, mapper=mapper, directory=directory, progress=progress)
        finally:
            if close is not None:
                close()
        files = write_study(table, directory)
    rows = table.to_dataframe().reset_index()
    failed = [str(s) for s in table["status"].values if str(s) != "ok"]
    if as_json:
        from .io.writers import jsonable

        click.echo(json.dumps(jsonable({"study": spec.name, "cases": rows.to_dict("records"),
                                        "files": [str(f) for f in files]}),
                              indent=2, allow_nan=False))
    else:
        result = _table(f"{spec.name}: {len(rows)} cases")
        for column in rows.columns:
            result.add_column(_escape(str(column)))
        for record in rows.itertuples(index=False):
            result.add_row(*(_escape(_g(v) if isinstance(v, float) else str(v))
                             for v in record))
        _stdout().print(result)
    _note(f"wrote {', '.join(str(f) for f in files)}", quiet)
    if failed:
        _fail(f"{study}: {len(failed)} case(s) failed: {failed[0]}", EXIT_FAILED)


@cli.command()
@click.argument("case", type=click.Path(dir_okay=False, path_type=Path))
@click.option("--body", "body", required=True, metavar="NAME", help="The body (box or cylinder).")
@click.option("--omega", "omega", required=True, type=click.FloatRange(min=0.0, min_open=True),
              metavar="W", help="Reference frequency [rad/s] (e.g. the wave or forcing one).")
@click.option("--out", "out", type=click.Path(dir_okay=False, path_type=Path), default=None,
              help="File to write (default: <case>_<body>_bem.yaml here).")
@click.option("--panel", "panel", type=click.FloatRange(min=0.0, min_open=True), default=None,
              help="Panel size [case length] (default: a twentieth of the width/diameter).")
@click.option("--whole-case", is_flag=True,
              help="Write the whole case with added_mass and damping replaced (no comments).")
@click.option("--shape", type=click.Choice(["box", "cylinder"]), default=None,
              help="Hull to mesh for a body with matrix hydrostatics (with --size, --draft).")
@click.option("--size", default=None, metavar="A,B[,C]",
              help="Box length,width,height or cylinder diameter,height [case length].")
@click.option("--draft", type=click.FloatRange(min=0.0, min_open=True), default=None,
              help="Draft [case length] (default: from a box/cylinder body's position).")
@_common_options
def bem(case: Path, body: str, omega: float, out: Path | None, panel: float | None,
        whole_case: bool, shape: str | None, size: str | None, draft: float | None,
        quiet: bool, verbose: bool) -> None:
    """Added mass, damping, hydrostatics and exciting forces of a body from capytaine.

    Needs the [bem] extra. Prints the case's constants next to the BEM values at W and
    writes a YAML snippet (bodies.NAME.added_mass and damping) to merge into CASE; see
    moorline.bem. A body with matrix hydrostatics needs --shape, --size and --draft (its
    origin stays at its position's height).
    """
    _configure_logging(verbose)
    from .bem import write_body_table

    _load(case)
    out = out if out is not None else Path(f"{case.stem}_{_safe_name(body, 'body')}_bem.yaml")
    try:
        dims = None if size is None else [float(v) for v in size.split(",")]
    except ValueError:
        raise click.BadParameter(f"{size!r} is not comma-separated numbers",
                                 param_hint="--size") from None
    with _status(f"solving BEM problems of {body} at {omega:g} rad/s ...", quiet):
        table = write_body_table(case, body, omega, out, panel_size=panel, draft=draft,
                                 shape=shape, dimensions=dims, whole_case=whole_case)
    a = table.coefficients.attrs
    result = _table(f"{case.name}: body {body}, omega {omega:g} rad/s, capytaine "
                    f"{a['capytaine_version']}, {a['n_panels']} panels")
    for name in ("quantity", "unit", "case", "BEM"):
        result.add_column(name, justify="left" if name in ("quantity", "unit") else "right")
    for quantity, unit, value, computed in table.rows:
        result.add_row(_escape(quantity), _escape(unit), _g(value), _g(computed))
    _stdout().print(result)
    _note(f"wrote {table.path}", quiet)


# ----------------------------------------------------------------------------- compile


@cli.command(name="compile")
@click.argument("kinds", nargs=-1)
@click.option("--jobs", "-j", type=click.IntRange(min=1), default=None,
              help="Processes compiling at once (default: the CPUs, at most one per kind).")
@_json_option
@_common_options
def compile_kernels(kinds: tuple[str, ...], jobs: int | None, as_json: bool, quiet: bool,
                    verbose: bool) -> None:
    """Compile the numba kernels into the kernel cache now.

    The compiled time step is built for each kind of model (bodies, lines, lines-local: lines
    of at least 300 free nodes, with the local Newton phase) at the first run of a case of that
    kind on a machine (0.5-2 minutes each). This runs a tiny case of each KIND (default: all)
    in parallel so that no later run pays it: after install (make does it), in a container
    build, or before a sweep whose workers would otherwise all compile at once.
    """
    _configure_logging(verbose)
    from .precompile import KINDS, Compiled, precompile

    def done(result: Compiled) -> None:
        what = (f"compiled {result.kernels} kernels" if result.kernels
                else "already in the cache")
        _note(f"{result.kind}: {what} ({result.seconds:.1f} s)", quiet or as_json)

    try:
        results = precompile(kinds or KINDS, jobs, done)
    except ValueError as exc:  # an unknown kind, refused before anything runs
        _fail(f"compile: {exc}", EXIT_BAD_INPUT)
    if as_json:
        from dataclasses import asdict

        click.echo(json.dumps([asdict(r) for r in results], indent=2))
    else:
        _note(f"kernel cache: {results[0].cache}", quiet)


def main() -> None:
    """Entry point of the ``moorline`` console script."""
    cli(prog_name="moorline")


if __name__ == "__main__":  # pragma: no cover
    main()


@cli.command()
@click.argument("deck", type=click.Path(dir_okay=False, path_type=Path))
@click.option("--out", "out", type=click.Path(dir_okay=False, path_type=Path), default=None,
              help="Case file to write (default: the deck's name with .yaml).")
@click.option("--vessel-body", "vessel", is_flag=True,
              help="Hold the Coupled/Vessel points by one fixed body 'vessel' at the origin "
                   "(the statics summary then reports its reaction and 6x6 stiffness).")
@click.option("--turbine", "turbines", type=(int, float, float, float), multiple=True,
              metavar="K X Y Z",
              help="Reference position [m] of turbine K of a FAST.Farm farm-level deck "
                   "(WT_X WT_Y WT_Z of the .fstf): its Turbine<K> points become prescribed "
                   "points at the deck position plus X Y Z. Repeatable.")
@_common_options
def convert(deck: Path, out: Path | None, vessel: bool,
            turbines: tuple[tuple[int, float, float, float], ...], quiet: bool,
            verbose: bool) -> None:
    """Convert a MoorDyn input file DECK into a moorline case file (YAML).

    The case is validated before it is written: a deck whose values a case may not hold
    (negative coefficients, volumes, seabed stiffness) exits 2 and writes nothing. The
    reading notes (dropped options and channels), how TMax/dtM/dtOut were used and the line
    output flags are comments at the top of the case; the OUTPUTS channels are
    output.channels (a dynamics run writes them as moordyn_channels.csv). `statics` and
    `run` also take a deck directly and convert it on the fly (with a note). Bodies and rods
    become moorline bodies and points (moorline.io.moordyn_rigid). Without --vessel-body,
    `moorline stiffness` takes every Coupled point as one rigid group (about their centroid).
    FAST.Farm's farm-level decks attach points to turbines (Turbine<K>): give each turbine's
    reference position with --turbine K X Y Z (MoorDyn-F adds it to the point's deck position).
    """
    _configure_logging(verbose)
    from .io.case_writer import write_case
    from .io.moordyn import read_moordyn_deck

    positions: dict[int, tuple[float, float, float]] = {}
    for k, *xyz in turbines:
        if k in positions:
            raise CaseError(f"--turbine {k} is given twice", str(deck))
        positions[k] = (xyz[0], xyz[1], xyz[2])
    read = read_moordyn_deck(deck, turbines=positions)
    system = read.system
    if vessel:
        from .io.moordyn_rigid import vessel_body

        system = vessel_body(system)
    target = out if out is not None else deck.with_suffix(".yaml")
    flags = {n: f for n, f in read.line_outputs.items() if f not in ("-", "0")}
    header = "\n".join([
        f"converted by moorline from the MoorDyn deck {deck}",
        *(f"note: {n}" for n in (*read.notes, *read.comments)),
        *([f"line output flags (MoorDyn's per-line files; moorline's results hold every node): "
           f"{', '.join(f'{n} {f}' for n, f in flags.items())}"] if flags else []),
        *(["OUTPUTS: output.channels, written by a dynamics run as <case>/"
           "moordyn_channels.csv"] if read.outputs else [])])
    try:
        write_case(system, target, header=header)
    except CaseError as exc:
        raise CaseError(f"cannot be converted, the case would not load (not written): {exc}",
                        str(deck)) from None
    _note(f"wrote {target}", quiet)


# ----------------------------------------------------------------------------- catalog


@cli.command()
@click.argument("name", required=False)
@click.argument("diameter", required=False)
@click.option("--units", "units", type=click.Choice(["SI", "US"]), default="SI",
              show_default=True, help="Unit system of the printed properties.")
@_json_option
@_common_options
def catalog(name: str | None, diameter: str | None, units: str, as_json: bool, quiet: bool,
            verbose: bool) -> None:
    """The line catalogue: its entries, or the properties of entry NAME at nominal DIAMETER.

    DIAMETER is a number in mm or a number with a unit ("120 mm", "4.75 in"). The
    properties are what a case's line type gets from
    `{catalog: NAME, nominal_diameter: DIAMETER}`, each with its source (see
    moorline/catalog/lines.yaml); EA_dynamic (fibre ropes) is stored, the solvers use EA.
    Exit 2 for an unknown entry or a diameter outside its range.
    """
    _configure_logging(verbose)
    from .catalog import PROPERTIES, CatalogError, families, in_units, line_properties
    from .io.units import UnitParseError, to_system, unit_of
    from .io.writers import jsonable

    if name is None:
        entries = families()
        if as_json:
            click.echo(json.dumps(jsonable(entries), indent=2, allow_nan=False))
            return
        table = _table("Line catalogue (moorline catalog NAME DIAMETER for properties)")
        for column in ("entry", "grades", "nominal diameter [mm]", "description"):
            table.add_column(column)
        for family, entry in entries.items():
            grades = ", ".join(f"{family}_{g.lower()}" for g in entry["grades"]) or family
            low, high = entry["diameter_range_mm"]
            table.add_row(_escape(family), _escape(grades), f"{low:g} to {high:g}",
                          _escape(entry["description"]))
        _stdout().print(table)
        return
    if diameter is None:
        _fail(f"catalog {name}: give a nominal diameter (e.g. moorline catalog {name} "
              "'120 mm')", EXIT_BAD_INPUT)
    try:
        metres = (float(diameter) / 1e3 if re.fullmatch(r"\s*[-+]?[\d.]+([eE][-+]?\d+)?\s*",
                                                        diameter)
                  else to_system(diameter, "length", "SI"))
        props = line_properties(name, metres)
    except (CatalogError, UnitParseError, ValueError) as exc:
        _fail(f"catalog {name} {diameter}: {exc}", EXIT_BAD_INPUT)
    values = in_units(props.values, units)
    if as_json:
        click.echo(json.dumps(jsonable({
            "catalog": props.name, "nominal_diameter_m": props.nominal_diameter,
            "units": units, "values": values,
            "units_of": {k: unit_of(PROPERTIES[k], units) for k in values},
            "sources": props.sources, "verified": props.verified,
            "mean_load_percent": props.mean_load_percent}), indent=2, allow_nan=False))
        return
    table = _table(f"{props.name}, nominal diameter {props.nominal_diameter * 1e3:g}"
                   f" mm ({units})")
    for column in ("key", "value", "unit", "source"):
        table.add_column(column, justify="right" if column == "value" else "left")
    for key, value in values.items():
        unit = unit_of(PROPERTIES[key], units).replace("dimensionless", "-")
        source = props.sources[key] + ("" if props.verified[key] else " [not verified]")
        table.add_row(key, f"{value:.6g}", _escape(unit), _escape(source))
    _stdout().print(table)
    if props.mean_load_percent:
        _note(f"EA_dynamic at a mean load of {props.mean_load_percent:g} % MBL; the solvers "
              "use EA", quiet)


# ----------------------------------------------------------------------------- stiffness


@cli.command()
@click.argument("case", type=click.Path(dir_okay=False, path_type=Path))
@click.option("--body", "body", default=None, metavar="NAME",
              help="The body whose mooring stiffness is printed (about its origin).")
@click.option("--points", "points", default=None, metavar="A,B,C",
              help="Prescribed points taken as one rigid group (default: every prescribed "
                   "point, or the only body), about their centroid.")
@click.option("--reference", "reference", default=None, metavar="X,Y,Z",
              help="Reference point of the moments and rotations, in the case's length unit.")
@_json_option
@_common_options
def stiffness(case: Path, body: str | None, points: str | None, reference: str | None,
              as_json: bool, quiet: bool, verbose: bool) -> None:
    """The 6x6 mooring stiffness of a body or of a rigid group of points of CASE.

    Solves statics (the case's first statics settings), then condenses the exact tangent on
    the group (moorline.solvers.stiffness.group_stiffness): rows and columns surge, sway,
    heave (translations of the reference point) and roll, pitch, yaw (rotations about it);
    the lines only (no hydrostatics). Exit 1 when the statics does not converge, 2 for an
    unknown body or point or both --body and --points.
    """
    _configure_logging(verbose)
    import numpy as np

    from .datasets import BODY_DOFS
    from .io.writers import jsonable
    from .offset_group import OffsetGroupError, resolve_group
    from .solvers.offset import group_reference
    from .solvers.statics import solve_statics
    from .solvers.stiffness import group_stiffness

    system = _load(case)
    names = tuple(n.strip() for n in points.split(",") if n.strip()) if points else ()
    try:
        group = resolve_group(system.points, system.bodies, body, names)
    except OffsetGroupError as exc:
        raise CaseError(str(exc), str(case), f"--{exc.key}") from None
    ref = None
    if reference is not None:
        try:
            ref = tuple(float(v) for v in reference.split(","))
        except ValueError:
            ref = ()
        if len(ref) != 3:
            raise CaseError(f"--reference must be three numbers X,Y,Z, got {reference!r}",
                            str(case), "--reference")
    with _status(f"solving statics of {system.name} ...", quiet):
        result = solve_statics(system)
    if not result.success:
        _fail(f"{case}: statics failed: {result.message}", EXIT_FAILED)
    about = group_reference(result, group, ref)
    K = group_stiffness(result, list(group.points), about)
    units = {"SI": ("N", "m"), "US": ("lbf", "ft")}.get(system.units, ("N", "m"))
    if as_json:
        click.echo(json.dumps(jsonable({
            "case": system.name, "units": system.units, "body": group.body,
            "points": list(group.points), "reference": about, "dofs": list(BODY_DOFS),
            "stiffness": np.asarray(K)}), indent=2, allow_nan=False))
        return
    what = f"body {group.body}" if group.body else "points " + ", ".join(group.points)
    force, length = units
    table = _table(f"{system.name}: mooring stiffness of {what} about "
                   f"({', '.join(f'{v:g}' for v in about)}) {length} "
                   f"[{force}/{length}, {force}/rad, {force}*{length}/rad]")
    table.add_column("")
    for dof in BODY_DOFS:
        table.add_column(dof, justify="right")
    for dof, row in zip(BODY_DOFS, K, strict=True):
        table.add_row(dof, *(f"{v:.6g}" for v in row))
    _stdout().print(table)


# ----------------------------------------------------------------------------- export
@cli.command()
@click.argument("results", type=click.Path(dir_okay=False, path_type=Path))
@click.option("--csv", "as_csv", is_flag=True, help="CSV files (the default).")
@click.option("--text", "as_text", is_flag=True, help="Fixed-width text tables (.txt).")
@click.option("--moordyn", "as_moordyn", is_flag=True,
              help="MoorDyn's main output file <case>.out of each dynamics group (the case's "
                   "OUTPUTS channels; FairTen/AnchTen of every line without).")
@click.option("--line-outputs", "line_flags", default="", metavar="FLAGS",
              help="With --moordyn: MoorDyn's per-line files <case>_Line<n>.out of every line "
                   "for these LineOutputs flags (p positions, v velocities, t segment "
                   "tensions, s strains).")
@click.option("--out", "out", type=click.Path(file_okay=False, path_type=Path), default=None,
              help="Output directory (default: the results file's directory).")
@_common_options
def export(results: Path, as_csv: bool, as_text: bool, as_moordyn: bool, line_flags: str,
           out: Path | None, quiet: bool, verbose: bool) -> None:
    """Write the tables of RESULTS (a results.nc): time series and per-line tables.

    One file per table (see moorline.io.export): dynamics groups give Time, FairTen<n>,
    AnchTen<n> (MoorDyn's channel names) and Body<m>Surge...; statics a table per line
    (node, arc length, x, y, z, tension) and the end forces; the other groups their
    natural tables (spectra against omega, offset curves per heading). The first line
    holds the column names, the second their units. --moordyn writes instead MoorDyn's
    main output file of each dynamics group, in MoorDyn-C 2.7's layout
    (moorline.io.moordyn_out): <case>.out (<group>.out with several), its channels those
    of the case's output.channels (a deck's OUTPUTS); --line-outputs FLAGS adds MoorDyn's
    per-line files <case>_Line<n>.out of every line.
    """
    _configure_logging(verbose)
    from .io.export import export_results
    from .io.moordyn_out import export_moordyn

    if as_csv + as_text + as_moordyn > 1:
        _fail("--csv, --text and --moordyn: choose one", EXIT_BAD_INPUT)
    if line_flags and not as_moordyn:
        _fail("--line-outputs goes with --moordyn", EXIT_BAD_INPUT)
    if not results.is_file():
        _fail(f"{results}: no such file", EXIT_BAD_INPUT)
    directory = out if out is not None else results.parent
    try:
        files = export_moordyn(results, directory, line_flags) if as_moordyn else \
            export_results(results, directory, text=as_text)
    except (KeyError, ValueError) as exc:
        raise CaseError(f"{results}: cannot export: {exc}") from None
    if as_moordyn and not files:
        _fail(f"{results}: no dynamics analysis to export as a MoorDyn .out file",
              EXIT_BAD_INPUT)
    _note(f"wrote {', '.join(str(f) for f in files)}", quiet)
