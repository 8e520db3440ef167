"""Statics benchmark: one OC3-Hywind line at 20, 100 and 1000 elements.

Prints wall time and Newton iterations of moorline's statics from the catenary start and, if
MoorPy is installed (``pip install -e .[compare]``), the time of MoorPy's solve of the same
line in the same run, with the ratio. Both timings include building the model from the same
description (moorline's System and mesh; MoorPy's System built from it). bench_all.py (P2)
prints the same table; run alone with ``python benchmarks/bench_statics.py``.
"""

from __future__ import annotations

import numpy as np
from bench_common import best_of

from moorline.solvers.statics import solve_statics
from moorline.verification.oc3_line import oc3_system


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


def one_line(sizes: tuple[int, ...] = (20, 100, 1000), repeat: int = 5) -> list[dict]:
    """Per mesh: moorline's statics time [s], iterations and fairlead tension, MoorPy's time
    and tension (None without MoorPy), best of ``repeat``."""
    rows = []
    for n in sizes:
        system = oc3_system(n)
        result = solve_statics(system)
        # both sides build their model from the same description inside the timed call:
        # moorline the System (oc3_system) and its mesh, MoorPy its System from it
        row = {"elements": n, "moorline": best_of(lambda n=n: solve_statics(oc3_system(n)),
                                                  repeat),
               "iterations": result.iterations,
               "tension": float(np.linalg.norm(result.end_force("line1", "b"))),
               "moorpy": None, "moorpy_tension": None}
        mp_solve = moorpy_solver(n)
        if mp_solve is not None:
            row["moorpy"] = best_of(mp_solve, repeat)
            row["moorpy_tension"] = float(mp_solve())
        rows.append(row)
    return rows


def main() -> None:
    """Time and print."""
    print(f"{'elements':>8} {'moorline [ms]':>14} {'iterations':>10} {'MoorPy [ms]':>12} "
          f"{'ratio':>8} {'T_fair moorline':>16} {'T_fair MoorPy':>14}")
    for r in one_line():
        if r["moorpy"] is None:
            print(f"{r['elements']:8d} {1e3 * r['moorline']:14.2f} {r['iterations']:10d} "
                  f"{'n/a':>12}")
            continue
        print(f"{r['elements']:8d} {1e3 * r['moorline']:14.2f} {r['iterations']:10d} "
              f"{1e3 * r['moorpy']:12.2f} {r['moorline'] / r['moorpy']:8.2f} "
              f"{r['tension']:16.1f} {r['moorpy_tension']:14.1f}")
    print(NOTE)


NOTE = ("ratio = moorline time / MoorPy time (below 1: moorline faster). MoorPy solves the "
        "line as one closed-form catenary whatever its segment count; moorline solves the "
        "finite-element equilibrium of all nodes.")


if __name__ == "__main__":
    main()
