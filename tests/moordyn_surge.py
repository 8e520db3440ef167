"""MoorDyn-C (the ``moordyn`` module) driving one coupled point along x: the fairlead tension
of line 1 after each step, for the tests that compare moorline's rope laws with MoorDyn's."""

from __future__ import annotations

from collections.abc import Callable, Iterable
from pathlib import Path

import numpy as np


def moordyn_fair_tensions(deck: Path, x: Callable[[float], float], z: float,
                          times: Iterable[float], dt: float) -> np.ndarray:
    """``FairTen`` of line 1 after a step of ``dt`` from each of ``times``, the coupled point
    at ``(x(t), 0, z)`` moving at the step's mean velocity (``Init_NoIC`` at the first time)."""
    import moordyn

    from moorline.compare.moordyn_runner import silenced_fd

    times = list(times)
    out = []
    with silenced_fd(1):
        md = moordyn.Create(str(deck))
        moordyn.Init_NoIC(md, [x(times[0]), 0.0, z], [0.0, 0.0, 0.0])
        line = moordyn.GetLine(md, 1)
        for t in times:
            moordyn.Step(md, [x(t), 0.0, z], [(x(t + dt) - x(t)) / dt, 0.0, 0.0], t, dt)
            out.append(moordyn.GetLineFairTen(line))
        moordyn.Close(md)
    return np.array(out)
