"""BLAS threads of a ``moorline`` command (issue 16: start-up).

numpy and scipy each load their own OpenBLAS, and OpenBLAS starts a pool of threads (one per
core) when it is loaded: on a 2-core machine that costs about 35 ms of CPU and wall time at
``import numpy`` and 20 ms more at ``import scipy.linalg`` (measured: ``import numpy`` 0.10 s
CPU with the pool, 0.05 s with ``OPENBLAS_NUM_THREADS=1``). The solves of a cable mesh are
banded LU factorizations of bandwidth ~10 (LAPACK ``gbtrf``/``gbtrs``), which threads do not
speed up. So a command asks OpenBLAS for one thread before numpy is imported, unless the user
chose a thread count (any of :data:`THREAD_VARIABLES` set) or the command solves dense BEM
systems (:data:`THREADED_COMMANDS`).
"""

from __future__ import annotations

import os
import sys

__all__ = ["THREADED_COMMANDS", "THREAD_VARIABLES", "one_blas_thread"]

THREAD_VARIABLES = ("OPENBLAS_NUM_THREADS", "GOTO_NUM_THREADS", "OMP_NUM_THREADS")
"""The variables OpenBLAS reads for its thread count, in its order of precedence."""

THREADED_COMMANDS = frozenset({"bem"})
"""Commands that keep OpenBLAS's default threads (dense panel-method systems)."""


def one_blas_thread(command: str | None) -> bool:
    """Ask OpenBLAS for one thread (``OPENBLAS_NUM_THREADS=1`` in this process's environment,
    inherited by its children) for ``command``; returns whether it did.

    Nothing is changed when numpy is already imported (OpenBLAS read its settings then: a
    test runner, a Python session calling the CLI), when the user set any of
    :data:`THREAD_VARIABLES`, or for a command of :data:`THREADED_COMMANDS`.
    """
    if command in THREADED_COMMANDS or "numpy" in sys.modules:
        return False
    if any(name in os.environ for name in THREAD_VARIABLES):
        return False
    os.environ["OPENBLAS_NUM_THREADS"] = "1"
    return True
