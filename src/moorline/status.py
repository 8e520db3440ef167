"""How an analysis ended: the ``status`` of a result and of its group in ``results.nc``.

A module of its own, without numpy or xarray, so the command line can use it at start-up.
"""

from __future__ import annotations

from enum import StrEnum


class Status(StrEnum):
    """How an analysis ended (the ``status`` of a result and of its group)."""

    CONVERGED = "converged"
    COMPLETED = "completed"
    FAILED = "failed"
    INTERRUPTED = "interrupted"
    TERMINATED = "terminated"
    RUNNING = "running"
