"""One driver written against the ``moordyn`` Python module's call pattern, run on any
module with that pattern: ``moordyn`` itself or :mod:`moorline.coupling.moordyn`
(``benchmarks/bench_coupling.py``, ``tests/test_coupling.py``).

It moves a system's prescribed points along their case motions, giving each ``Step`` the
positions and velocities at the start of the coupling interval (as MoorDyn expects), and
records every line's ``GetLineFairTen`` and ``|GetLineNodeForce(line, N)|`` after each
interval, with the wall times of ``Create`` + ``Init`` and of the stepping loop.
"""

from __future__ import annotations

import time
from types import ModuleType

import numpy as np

from ..model import System
from ..solvers.excitation import motion_value
from .moordyn_runner import silenced_fd


def fairlead_kinematics(system: System, t: float) -> tuple[list[float], list[float]]:
    """Positions and velocities of the prescribed points at ``t`` (the case's motions)."""
    x, v = [], []
    for p in system.points.values():
        if p.kind != "prescribed":
            continue
        d, dv, _ = motion_value(p.motion, t)
        x.extend((np.asarray(p.position) + d).tolist())
        v.extend(dv.tolist())
    return x, v


def drive(module: ModuleType, source: str, system: System, duration: float,
          dt: float, **options) -> dict:
    """Drive ``module`` (``moordyn`` or ``moorline.coupling.moordyn``) on ``source`` (its
    input: a MoorDyn deck, a moorline case) along ``system``'s prescribed motions for
    ``duration`` in intervals ``dt``; ``options``: the facade's extra ``Create`` options.

    Returns
    -------
    dict
        ``time`` (n,), ``fair_ten`` and ``fairlead_force`` (n, n_lines), ``wall_init``,
        ``wall_loop`` [s].
    """
    tic = time.perf_counter()
    with silenced_fd(1):
        md = module.Create(source, **options)
        x0, _ = fairlead_kinematics(system, 0.0)
        status = module.Init(md, x0, [0.0] * len(x0))
    if status:
        raise RuntimeError(f"Init failed ({status})")
    init_time = time.perf_counter() - tic
    lines = [module.GetLine(md, i) for i in range(1, len(system.lines) + 1)]
    n_seg = [module.GetLineN(line) for line in lines]
    n = int(round(duration / dt))
    fair, force, times = np.zeros((n, len(lines))), np.zeros((n, len(lines))), np.zeros(n)
    loop = 0.0
    for i in range(n):
        x, v = fairlead_kinematics(system, i * dt)
        tic = time.perf_counter()
        module.Step(md, x, v, i * dt, dt)
        loop += time.perf_counter() - tic
        times[i] = (i + 1) * dt
        for j, (line, ns) in enumerate(zip(lines, n_seg, strict=True)):
            fair[i, j] = module.GetLineFairTen(line)
            force[i, j] = np.linalg.norm(module.GetLineNodeForce(line, ns))
    module.Close(md)
    return {"time": times, "fair_ten": fair, "fairlead_force": force,
            "wall_init": init_time, "wall_loop": loop}
