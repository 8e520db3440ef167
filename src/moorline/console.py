"""Console output of the command line: spinners, status lines, tables on stdout.

rich is imported when something is shown with it (not by ``--help`` nor a quiet spinner).
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import TYPE_CHECKING

import click

if TYPE_CHECKING:
    from rich.console import Console
    from rich.table import Table


@contextmanager
def _status(message: str, quiet: bool) -> Iterator[Callable[[str], None]]:
    """A rich spinner on stderr (nothing when quiet); yields a function that updates it.

    Messages are printed literally (``Text``, not markup: a case may be named ``[/]``)."""
    if quiet:
        yield lambda _msg: None
        return
    from rich.console import Console
    from rich.text import Text

    console = Console(stderr=True)
    with console.status(Text(message)) as status:
        yield lambda msg: status.update(Text(msg))


def _note(message: str, quiet: bool) -> None:
    """A status line on stderr, unless quiet."""
    if not quiet:
        click.echo(message, err=True)


def _stdout_is_terminal() -> bool:
    """Whether rich would treat stdout as a terminal (its rule: ``TTY_COMPATIBLE`` 0 or 1,
    else a non-empty ``FORCE_COLOR``, else ``isatty``); decided without importing rich."""
    import os

    compatible = os.environ.get("TTY_COMPATIBLE", "")
    if compatible in ("0", "1"):
        return compatible == "1"
    force = os.environ.get("FORCE_COLOR")
    if force is not None:
        return force != ""
    isatty = getattr(sys.stdout, "isatty", None)
    try:
        return bool(isatty is not None and isatty())
    except ValueError:  # a closed stream
        return False


def _stdout() -> Console:
    """Console for tables on stdout: the terminal's width, or 160 columns into a pipe/file."""
    from rich.console import Console

    console = Console(file=sys.stdout)
    return console if console.is_terminal else Console(file=sys.stdout, width=160)


def _escape(text: str) -> str:
    """``text`` with rich markup escaped (printed literally)."""
    from rich.markup import escape

    return escape(text)


def _table(title: str) -> Table:
    """An empty rich table titled ``title`` (printed literally)."""
    from rich.table import Table

    return Table(title=_escape(title))
