"""The ``moorline`` command line: ``statics``, ``run``, ``verify`` and ``plot``.

Exit codes: 0 success; 1 the analysis failed (no convergence, a verification row out of
tolerance); 2 bad input (a case file that does not validate, a missing or unreadable file, an
unknown name). Expected errors print ``error: <file>: <key path>: <reason>`` on stderr, never a
traceback; unexpected exceptions are bugs and keep their traceback.

With ``--json`` a command prints exactly one JSON document on stdout and nothing else; logs,
progress and errors go to stderr. This is the only module that configures ``logging``.
"""

from __future__ import annotations

import json
import logging
import re
import sys
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, TypeVar

import click
import numpy as np
from rich.console import Console
from rich.markup import escape
from rich.table import Table

from . import __version__
from .errors import CaseError, ConvergenceError, MoorlineError

logger = logging.getLogger(__name__)

EXIT_OK, EXIT_FAILED, EXIT_BAD_INPUT = 0, 1, 2
F = TypeVar("F", bound=Callable[..., Any])


# ----------------------------------------------------------------------------- plumbing


class _Cli(click.Group):
    """A group that turns moorline's expected errors into one-line messages and exit codes."""

    def invoke(self, ctx: click.Context) -> Any:
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


@contextmanager
def _status(message: str, quiet: bool) -> Iterator[Callable[[str], None]]:
    """A rich spinner on stderr (nothing when quiet); yields a function that updates it."""
    if quiet:
        yield lambda _msg: None
        return
    console = Console(stderr=True)
    with console.status(message) as status:
        yield lambda msg: status.update(msg)


def _note(message: str, quiet: bool) -> None:
    """A status line on stderr, unless quiet."""
    if not quiet:
        click.echo(message, err=True)


def _stdout() -> Console:
    """Console for tables on stdout: the terminal's width, or 160 columns into a pipe/file."""
    console = Console(file=sys.stdout)
    return console if console.is_terminal else Console(file=sys.stdout, width=160)


def _safe_name(name: str, fallback: str) -> str:
    """A directory name for a case (``/`` and other unsafe characters replaced)."""
    cleaned = re.sub(r"[^A-Za-z0-9._-]+", "_", name.strip()).strip("._")
    return cleaned or fallback


def _load(path: Path) -> Any:
    """Load a case file; a :class:`CaseError` without a file gets this one."""
    from . import io as case_io

    try:
        return case_io.load_case(path)
    except CaseError as exc:
        if not exc.file:
            exc.file = str(path)
        raise


# ----------------------------------------------------------------------------- statics


def statics_summary(result: Any, with_stiffness: bool = True) -> dict[str, Any]:
    """The ``--json`` object of a static result.

    Parameters
    ----------
    result
        A :class:`~moorline.results.StaticResult`.
    with_stiffness
        Add the 3x3 restoring stiffness of free and prescribed points (only computed when the
        result converged: away from equilibrium it means nothing).

    Returns
    -------
    dict
        ``{"case", "converged", "iterations", "units", "method", "message",
        "lines": {id: {"end_a": {"force", "tension"}, "end_b": ..., "max_tension",
        "seabed_length"}}, "points": {id: {"kind", "position", "stiffness"?}}}``; forces are
        those the line exerts on its end points, in the case's units.
    """
    mesh = result.mesh
    lines: dict[str, Any] = {}
    for name in mesh.line_names:
        entry: dict[str, Any] = {}
        for end in ("a", "b"):
            force = np.asarray(result.end_force(name, end), dtype=float)
            entry[f"end_{end}"] = {"force": (force + 0.0).tolist(),  # no -0.0
                                   "tension": float(np.linalg.norm(force))}
        # the largest tension is often at an end (the fairlead), not at an element midpoint
        ends = [entry["end_a"]["tension"], entry["end_b"]["tension"]]
        entry["max_tension"] = float(np.nanmax([*result.line_tension(name), *ends]))
        entry["seabed_length"] = float(result.seabed_length(name))
        lines[name] = entry
    points: dict[str, Any] = {}
    for name, kind in zip(mesh.point_names, mesh.point_kind, strict=True):
        point: dict[str, Any] = {"kind": kind,
                                 "position": np.asarray(result.point_position(name)).tolist()}
        if with_stiffness and result.success and kind in ("free", "prescribed"):
            from .solvers import stiffness

            point["stiffness"] = np.asarray(stiffness.point_stiffness(result, name)).tolist()
        points[name] = point
    return {
        "case": result.case, "converged": bool(result.success),
        "iterations": int(result.iterations), "units": result.units, "method": result.method,
        "message": result.message, "lines": lines, "points": points,
    }


def statics_dataset(result: Any) -> Any:
    """``result.to_xarray()`` plus what the plots need: ``seabed_z`` and ``point_kind``."""
    ds = result.to_xarray()
    mesh = result.mesh
    if "seabed_z" not in ds.attrs:
        ds.attrs["seabed_z"] = float(mesh.seabed_z)
    if "point_kind" not in ds.coords and "point" in ds.dims:
        ds = ds.assign_coords(point_kind=("point", list(mesh.point_kind)))
    return ds


@dataclass
class Outcome:
    """What one analysis of a case produced."""

    kind: str
    success: bool
    message: str
    summary: dict[str, Any]
    files: list[Path] = field(default_factory=list)


def run_statics(system: Any, settings: Any, directory: Path, label: str,
                quiet: bool) -> Outcome:
    """Solve statics, write ``<label>.nc`` and the configuration plots into ``directory``."""
    from .io.writers import write_netcdf
    from .plot import plot_configuration
    from .solvers.statics import solve_statics

    with _status(f"solving statics of {system.name} ...", quiet) as update:
        result = solve_statics(system, settings)
        logger.info("statics of %s: %s", system.name, result.message)
        update("computing point stiffness ...")
        summary = statics_summary(result)
        update("writing results ...")
        ds = statics_dataset(result)
        prefix = "" if label == "statics" else f"{label}_"
        nc = write_netcdf(ds, directory / f"{label}.nc")
        xz, view3d = (directory / f"{prefix}configuration_xz.png",
                      directory / f"{prefix}configuration_3d.png")
        update("plotting ...")
        plot_configuration(ds, xz, view3d)
    return Outcome("statics", bool(result.success), result.message, summary, [nc, xz, view3d])


#: Runner of each analysis kind a case may list: (system, settings, dir, label, quiet).
RUNNERS: dict[str, Callable[[Any, Any, Path, str, bool], Outcome]] = {
    "statics": run_statics,
}


def _labels(kinds: list[str]) -> list[str]:
    """File labels: the kind, numbered when a kind appears more than once."""
    seen: dict[str, int] = {}
    labels = []
    for kind in kinds:
        seen[kind] = seen.get(kind, 0) + 1
        labels.append(kind if kinds.count(kind) == 1 else f"{kind}{seen[kind]}")
    return labels


def _analysis_kind(analysis: Any) -> str:
    return str(getattr(analysis, "kind", type(analysis).__name__))


# ----------------------------------------------------------------------------- commands


@click.group(cls=_Cli, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="moorline")
def cli() -> None:
    """moorline: nonlinear statics and dynamics of ocean mooring cables."""


@cli.command()
@click.argument("case", type=click.Path(dir_okay=False, path_type=Path))
@_out_option
@_json_option
@_common_options
def statics(case: Path, out: Path, as_json: bool, quiet: bool, verbose: bool) -> None:
    """Solve the static equilibrium of CASE (the method of its first statics analysis).

    Writes DIR/<case>/statics.nc, summary.json, summary.txt, configuration_xz.png and
    configuration_3d.png.
    """
    _configure_logging(verbose)
    system = _load(case)
    settings = next((a for a in system.analyses if _analysis_kind(a) == "statics"), None)
    directory = out / _safe_name(system.name, case.stem)
    outcome = run_statics(system, settings, directory, "statics", quiet)
    _finish(case, directory, outcome.summary, [outcome], as_json, quiet)


@cli.command()
@click.argument("case", type=click.Path(dir_okay=False, path_type=Path))
@_out_option
@_json_option
@_common_options
def run(case: Path, out: Path, as_json: bool, quiet: bool, verbose: bool) -> None:
    """Run every analysis CASE lists, in order, writing DIR/<case>/.

    Each analysis writes <kind>.nc (numbered when a kind repeats) and its plots; summary.json
    and summary.txt cover them all.
    """
    _configure_logging(verbose)
    system = _load(case)
    kinds = [_analysis_kind(a) for a in system.analyses] or ["statics"]
    analyses = list(system.analyses) or [None]
    unknown = sorted({k for k in kinds if k not in RUNNERS})
    if unknown:
        raise CaseError(f"analysis kind {', '.join(map(repr, unknown))} is not supported by "
                        f"this version; supported: {', '.join(RUNNERS)}", str(case), "analyses")
    directory = out / _safe_name(system.name, case.stem)
    outcomes = [RUNNERS[kind](system, analysis, directory, label, quiet)
                for kind, analysis, label in zip(kinds, analyses, _labels(kinds), strict=True)]
    summary = {"case": system.name, "converged": all(o.success for o in outcomes),
               "units": system.units,
               "analyses": [{"kind": o.kind, **o.summary} for o in outcomes]}
    _finish(case, directory, summary, outcomes, as_json, quiet)


def _finish(case: Path, directory: Path, summary: dict[str, Any], outcomes: list[Outcome],
            as_json: bool, quiet: bool) -> None:
    """Write the summary, report on stdout, exit 1 when an analysis failed."""
    from .io.writers import render_summary, summary_json, write_summary

    files = [f for o in outcomes for f in o.files] + list(write_summary(summary, directory))
    if as_json:
        click.echo(summary_json(summary))
    else:
        console = _stdout()
        for renderable in render_summary(summary):
            console.print(renderable)
    _note(f"wrote {', '.join(str(f) for f in files)}", quiet)
    failed = [o for o in outcomes if not o.success]
    if failed:
        _fail(f"{case}: {failed[0].kind} failed: {failed[0].message}", EXIT_FAILED)


@cli.command()
@click.option("--case", "cases", multiple=True, metavar="NAME",
              help="Run only this verification case (repeatable). Default: all.")
@_json_option
@_common_options
def verify(cases: tuple[str, ...], as_json: bool, quiet: bool, verbose: bool) -> None:
    """Run the verification suite and compare with the reference solutions.

    Exit code 0 only when every row passes.
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
    with _status("verifying ...", quiet) as update:
        for name in cases or known:
            update(f"verifying {name} ...")
            rows.extend(_verify_case(core, name))
    if as_json:
        from .io.writers import jsonable

        click.echo(json.dumps(jsonable(rows), indent=2, allow_nan=False))
    else:
        _stdout().print(_verify_table(rows))
    failed = [r for r in rows if not r["passed"]]
    _note(f"{len(rows) - len(failed)} of {len(rows)} checks passed", quiet)
    if failed:
        raise click.exceptions.Exit(EXIT_FAILED)


def _verify_case(core: Any, name: str) -> list[dict[str, Any]]:
    """Rows of one case as dicts; a case that raises a moorline error gives one failed row."""
    try:
        return [row.to_dict() for row in core.run_cases([name])]
    except MoorlineError as exc:
        click.echo(f"error: verification case {name}: {exc}", err=True)
        return [{"case": name, "quantity": "run", "reference": None, "computed": None,
                 "tolerance": None, "passed": False, "error": None, "unit": "",
                 "note": f"failed: {exc}"}]


def _verify_table(rows: list[dict[str, Any]]) -> Table:
    table = Table(title="Verification")
    for name in ("case", "quantity", "reference", "computed", "error", "tolerance", "pass"):
        right = name in ("reference", "computed", "error", "tolerance")
        table.add_column(name, justify="right" if right else "left")
    for row in rows:
        unit = f" {row['unit']}" if row.get("unit") else ""
        kind = " (rel)" if row.get("relative") else unit
        table.add_row(
            escape(str(row["case"])), escape(str(row["quantity"])),
            escape(_g(row["reference"]) + unit), escape(_g(row["computed"]) + unit),
            escape(_g(row.get("error")) + kind), escape(_g(row.get("tolerance")) + kind),
            "[green]pass[/green]" if row["passed"] else "[bold red]FAIL[/bold red]")
    return table


def _g(value: Any) -> str:
    return "-" if value is None else f"{float(value):.6g}"


@cli.command()
@click.argument("results", type=click.Path(dir_okay=False, path_type=Path))
@click.option("--out", "out", type=click.Path(file_okay=False, path_type=Path), default=None,
              help="Directory for the plots (default: next to RESULTS).")
@_common_options
def plot(results: Path, out: Path | None, quiet: bool, verbose: bool) -> None:
    """Plot the configuration saved in a statics RESULTS file (statics.nc)."""
    _configure_logging(verbose)
    import xarray as xr

    from .plot import plot_configuration

    if not results.is_file():
        raise CaseError("no such file", str(results))
    try:
        with xr.open_dataset(results, engine="netcdf4") as opened:
            ds = opened.load()
    except (OSError, ValueError) as exc:
        reason = getattr(exc, "strerror", None) or str(exc)
        raise CaseError(f"cannot read as a NetCDF results file ({reason})", str(results)) from exc
    missing = [v for v in ("position", "element_nodes", "tension") if v not in ds.variables]
    if missing or ds.attrs.get("analysis", "statics") != "statics":
        raise CaseError(f"not a statics result (missing {', '.join(missing) or 'statics'})",
                        str(results))
    directory = out if out is not None else results.parent
    xz, view3d = directory / "configuration_xz.png", directory / "configuration_3d.png"
    with _status("plotting ...", quiet):
        plot_configuration(ds, xz, view3d)
    _note(f"wrote {xz}, {view3d}", quiet)


def main() -> None:
    """Entry point of the ``moorline`` console script."""
    cli(prog_name="moorline")


if __name__ == "__main__":  # pragma: no cover
    main()
