"""Compile moorline's numba kernels into the kernel cache ahead of their first use.

The compiled time step is specialized on the kind of model (:mod:`moorline.solvers.
fast_newmark`): lines only; lines only with the local Newton phase (models of at least
:data:`~moorline.solvers.dynamics.LOCAL_MIN_FREE_NODES` free nodes); lines with bodies or rods.
Each kind costs 0.5-2 minutes of compilation the first time a case of that kind runs on a
machine (then the machine code loads from the cache, :mod:`moorline.numba_cache`).
:func:`precompile` runs one tiny case of each kind, in parallel processes, so that the cost is
paid once, at install (``make`` does it) or when building a container image, instead of by the
first real run or by every worker of a sweep at the same time.
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass
from multiprocessing import get_context
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from .model import System

KINDS = ("bodies", "lines", "lines-local")
"""The model kinds :func:`precompile` compiles, the longest first."""


@dataclass(frozen=True)
class Compiled:
    """What compiling one kind did."""

    kind: str
    kernels: int
    """Kernels compiled (0: all loaded from the cache)."""
    seconds: float
    """Wall time of the kind's case, compilation included [s]."""
    cache: str
    """The kernel cache directory."""


def _bodies_case() -> System:
    """A body on a heave spring (hydrostatic matrix) held by four taut vertical ropes."""
    from .model import Body, Environment, Hydrostatics, Line, LineType, Point, System

    mass, ea, length = 2.0e4, 2.0e6, 50.0
    rope = LineType("rope", diameter=0.05, mass_per_length=1.0, EA=ea)
    stiffness = [[0.0] * 6 for _ in range(6)]
    for i, k in enumerate((1e5, 1e5, 4e5, 1e7, 1e7, 1e7)):
        stiffness[i][i] = k
    pretension = 4 * ea * 1e-3
    body = Body("b", position=(0.0, 0.0, 0.0), mass=mass,
                inertia=((1e5, 0, 0), (0, 1e5, 0), (0, 0, 1e5)),
                hydrostatics=Hydrostatics("matrix", stiffness=tuple(map(tuple, stiffness)),
                                          volume=(mass * 9.81 + pretension) / (1025 * 9.81)))
    points, lines = {}, {}
    for k, (x, y) in enumerate([(2, 2), (-2, 2), (-2, -2), (2, -2)]):
        points[f"p{k}"] = Point(f"p{k}", "body", (x, y, 0.0), body="b")
        points[f"a{k}"] = Point(f"a{k}", "fixed", (x, y, -length * 1.001))
        lines[f"l{k}"] = Line(f"l{k}", "rope", length, 4, f"a{k}", f"p{k}")
    return System("precompile-bodies", environment=Environment(), line_types={"rope": rope},
                  points=points, lines=lines, bodies={"b": body})


def _case(kind: str) -> System:
    if kind == "bodies":
        return _bodies_case()
    from .verification.oc3_system import oc3_three_lines

    # lines-local: 3 x 110 segments = 327 free nodes, above LOCAL_MIN_FREE_NODES (300)
    return oc3_three_lines(110 if kind == "lines-local" else 10)


def compile_kind(kind: str) -> Compiled:
    """Statics and two time steps of the tiny case of ``kind`` (one of :data:`KINDS`) on the
    compiled path; returns what this process compiled."""
    from .kernel_cache import compiled_kernels
    from .model import DynamicsSettings
    from .solvers.dynamics import simulate
    from .solvers.statics import solve_statics

    start = time.perf_counter()
    system = _case(kind)
    initial = solve_statics(system)
    if not initial.success:
        raise RuntimeError(f"precompile {kind}: statics failed: {initial.message}")
    run = simulate(system, DynamicsSettings(duration=0.1, dt=0.05), initial=initial,
                   output_every=0.05)
    if not run.success:
        raise RuntimeError(f"precompile {kind}: dynamics failed: {run.message}")
    if kind == "lines":  # the tension envelope's pass (results of every dynamics run)
        from .envelope import TensionEnvelope

        TensionEnvelope(1).add_records(run.time, run.tension[:, :1])
    kernels, where = compiled_kernels()
    # where: numba's directory of one kernel module, inside moorline's numba-<hash> directory
    return Compiled(kind, kernels, time.perf_counter() - start, os.path.dirname(where))


def precompile(kinds: tuple[str, ...] = KINDS, jobs: int | None = None,
               done: Callable[[Compiled], None] | None = None) -> list[Compiled]:
    """Compile the kernels of ``kinds`` into the cache, ``jobs`` processes at a time (default:
    the CPUs available, at most one per kind); ``done`` is called as each kind finishes."""
    unknown = [k for k in kinds if k not in KINDS]
    if unknown:
        raise ValueError(f"unknown kind {unknown[0]!r}; expected one of {', '.join(KINDS)}")
    if jobs is None:
        jobs = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") \
            else (os.cpu_count() or 1)
    jobs = max(1, min(jobs, len(kinds)))
    results: list[Compiled] = []
    if jobs == 1:
        for kind in kinds:
            results.append(compile_kind(kind))
            if done is not None:
                done(results[-1])
        return results
    # spawn: a clean interpreter per worker (numba and BLAS threads do not survive a fork well)
    with ProcessPoolExecutor(max_workers=jobs, mp_context=get_context("spawn")) as pool:
        futures = [pool.submit(compile_kind, kind) for kind in kinds]
        for future in futures:
            results.append(future.result())
            if done is not None:
                done(results[-1])
    return results
