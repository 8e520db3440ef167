"""Statics benchmark: one OC3-Hywind line at 20, 100 and 1000 elements.

Prints wall time and Newton iterations of moorline's statics from the catenary start and, if
MoorPy is installed (``pip install -e .[compare]``), the time of MoorPy's solve of the same
line in the same run, with the ratio. Run with ``make bench``.
"""

from __future__ import annotations

import time

import numpy as np

from moorline.solvers.statics import solve_statics
from moorline.verification.oc3_line import oc3_system


def best_of(func, repeat: int = 5) -> float:
    """Smallest wall time of ``repeat`` calls [s]."""
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        func()
        times.append(time.perf_counter() - start)
    return min(times)


def moorpy_solver(segments: int):
    """A callable building and solving the OC3 line with MoorPy (the same moorline system,
    :func:`moorline.compare.moorpy_runner.solve_moorpy`), or None without MoorPy."""
    try:
        import moorpy  # noqa: F401
    except ImportError:
        return None
    from moorline.compare.moorpy_runner import solve_moorpy

    system = oc3_system(segments)

    def solve():
        return solve_moorpy(system).lineList[0].TB

    return solve


def main() -> None:
    """Time and print."""
    print(f"{'elements':>8} {'moorline [ms]':>14} {'iterations':>10} {'MoorPy [ms]':>12} "
          f"{'ratio':>8} {'T_fair moorline':>16} {'T_fair MoorPy':>14}")
    for n in (20, 100, 1000):
        system = oc3_system(n)
        result = solve_statics(system)
        t_ml = best_of(lambda system=system: solve_statics(system))
        tension = float(np.linalg.norm(result.end_force("line1", "b")))
        mp_solve = moorpy_solver(n)
        if mp_solve is None:
            print(f"{n:8d} {1e3 * t_ml:14.2f} {result.iterations:10d} {'n/a':>12}")
            continue
        t_mp = best_of(mp_solve)
        t_mp_fair = float(mp_solve())
        print(f"{n:8d} {1e3 * t_ml:14.2f} {result.iterations:10d} {1e3 * t_mp:12.2f} "
              f"{t_ml / t_mp:8.2f} {tension:16.1f} {t_mp_fair:14.1f}")
    print("ratio = moorline time / MoorPy time (below 1: moorline faster). MoorPy solves the "
          "line as one closed-form catenary whatever its segment count; moorline solves the "
          "finite-element equilibrium of all nodes.")


if __name__ == "__main__":
    main()
