"""SIGINT and SIGTERM in the command line: both stop a run the same way, keeping its results.

SIGINT (Ctrl-C) raises :class:`KeyboardInterrupt`, SIGTERM (``timeout``, batch schedulers,
``docker stop``) :class:`Terminated`, a subclass, so that every clean-up written for Ctrl-C
(closing the results file with what was computed) runs for both; the command line exits 130
or 143 (128 + the signal number). After the first signal a second one does not interrupt the
clean-up: it is noted and ignored, and the exit code stays the first signal's.
:func:`signals_deferred` holds both signals back while a record is written, so a record is
never left half-written.
"""

from __future__ import annotations

import signal
import threading
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from types import FrameType
from typing import Any

__all__ = ["Terminated", "handle_signals", "signals_deferred"]

_SIGNALS = (signal.SIGINT, signal.SIGTERM)


class Terminated(KeyboardInterrupt):  # noqa: N818 - named like KeyboardInterrupt
    """SIGTERM received: stop like Ctrl-C, report "terminated" (exit code 143)."""


def _main_thread() -> bool:
    return threading.current_thread() is threading.main_thread()


@contextmanager
def handle_signals() -> Iterator[None]:
    """In the block, SIGINT raises :class:`KeyboardInterrupt` and SIGTERM :class:`Terminated`,
    once: the first signal switches both to being ignored, so that the clean-up it starts
    runs to its end. The previous handlers are restored on leaving the block when no signal
    came (a no-op outside the main thread)."""
    if not _main_thread():
        yield
        return
    previous = {s: signal.getsignal(s) for s in _SIGNALS}
    received: list[int] = []

    def later(signum: int, _frame: FrameType | None) -> None:
        received.append(signum)

    def first(signum: int, _frame: FrameType | None) -> None:
        received.append(signum)
        for s in _SIGNALS:
            signal.signal(s, later)
        raise Terminated() if signum == signal.SIGTERM else KeyboardInterrupt()

    for s in _SIGNALS:
        signal.signal(s, first)
    try:
        yield
    finally:
        if not received:
            for s, handler in previous.items():
                signal.signal(s, handler)


@contextmanager
def signals_deferred() -> Iterator[None]:
    """Hold back SIGINT and SIGTERM in the block and deliver them right after (to the handler
    that was in place). Only in the main thread and for signals Python handles; otherwise a
    no-op."""
    if not _main_thread():
        yield
        return
    previous: dict[int, Callable[..., Any]] = {
        s: h for s in _SIGNALS if callable(h := signal.getsignal(s))}
    received: list[tuple[int, FrameType | None]] = []
    for s in previous:
        signal.signal(s, lambda signum, frame: received.append((signum, frame)))
    try:
        yield
    finally:
        for s, handler in previous.items():
            signal.signal(s, handler)
        if received:
            signum, frame = received[0]
            previous[signum](signum, frame)
