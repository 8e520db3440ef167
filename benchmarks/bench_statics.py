"""Statics benchmark (P2 of bench_all.py): the OC3 three-line system with the platform 6x6,
whole processes, and one OC3 line at 20, 100 and 1000 elements, against MoorPy in the same run.

* Three lines, whole process: ``moorline statics CASE --json`` (read and check the case,
  statics, results.nc, summary and report) and ``moorline stiffness CASE --json`` (statics and
  the 6x6 about the platform) against ``moorpy_drive.py`` (import MoorPy, build its System from
  a MoorDyn-format file of the same lines, ``solveEquilibrium``, ``getCoupledStiffnessA``).
  Both sides run as the same Python with the same environment: the moorline sources compiled
  to bytecode first (as an installed package is; :func:`bench_common.python_env`) and OpenBLAS
  on one thread in both (what the moorline CLI sets for itself, :mod:`moorline.threads`; the
  MoorPy child gets ``OPENBLAS_NUM_THREADS=1`` too, so the ratio compares the codes, not
  thread-pool start-ups). Times are the smallest CPU seconds (user + system) of ``repeat``
  runs, with the smallest wall time; ratio = moorline / MoorPy.
* Three lines, in process: building from the input file + statics + 6x6, both codes' imports
  done.
* One line, in process: moorline's statics of the OC3 line from the catenary start (building
  its System and mesh inside the timed call) against MoorPy building and solving the same line
  (:func:`moorline.compare.moorpy_runner.solve_moorpy`, its System built from moorline's inside
  the timed call), at 20, 100 and 1000 elements.

Run alone with ``python benchmarks/bench_statics.py [--repeat N]``.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from bench_common import ROOT, ProcessTime, best_of, best_process, fmt, moorline_command, python_env

from moorline.solvers.statics import solve_statics
from moorline.verification.oc3_line import oc3_system

HERE = Path(__file__).resolve().parent


MOORPY_DECK = """--------------------- MoorDyn Input File ------------------------------------
OC3-Hywind three lines, the fairleads on one coupled body (moorline bench_all P2)
---------------------- LINE TYPES -----------------------------------
TypeName Diam Mass/m EA BA/-zeta EI Cd Ca CdAx CaAx
(name) (m) (kg/m) (N) (N-s/-) (N-m^2) (-) (-) (-) (-)
chain {d!r} {m!r} {ea!r} -0.8 0 1.6 1.0 0.05 0.0
---------------------- BODIES ---------------------------------------
ID Attachment X0 Y0 Z0 r0 p0 y0 Mass CG* I* Volume CdA* Ca*
(#) (word) (m) (m) (m) (deg) (deg) (deg) (kg) (m) (kg-m^2) (m^3) (m^2) (-)
1 Coupled 0 0 0 0 0 0 0 0 0 0 0 0
---------------------- POINTS ---------------------------------------
ID Attachment X Y Z Mass Volume CdA Ca
(#) (-) (m) (m) (m) (kg) (m^3) (m^2) (-)
{points}
---------------------- LINES ----------------------------------------
ID LineType AttachA AttachB UnstrLen NumSegs LineOutputs
(#) (name) (#) (#) (m) (-) (-)
{lines}
---------------------- OPTIONS --------------------------------------
{g!r} g
{rho!r} rho
{depth!r} depth
--------------------- need this line -------------------------------
"""


def write_moorpy_deck(path: Path) -> Path:
    """The OC3 three lines as a MoorDyn-format file for MoorPy, fairleads on body 1."""
    from moorline.verification.oc3_line import DEPTH, DIAMETER, EA, LENGTH, MASS, RHO, G
    from moorline.verification.oc3_system import oc3_three_lines

    system = oc3_three_lines(20)
    ids = {name: k for k, name in enumerate(system.points, start=1)}
    points = "\n".join(
        f"{ids[n]} {'Body1' if p.kind == 'prescribed' else 'Fixed'} "
        + " ".join(repr(float(c)) for c in p.position) + " 0 0 0 0"
        for n, p in system.points.items())
    lines = "\n".join(f"{k} chain {ids[ln.end_a]} {ids[ln.end_b]} {LENGTH!r} 20 -"
                      for k, ln in enumerate(system.lines.values(), start=1))
    path.write_text(MOORPY_DECK.format(d=DIAMETER, m=MASS, ea=EA, points=points, lines=lines,
                                       g=G, rho=RHO, depth=DEPTH))
    return path


def write_statics_case(path: Path) -> Path:
    """``cases/oc3_offset.yaml`` reduced to its statics (the OC3 three lines, 20 segments)."""
    import yaml

    case = yaml.safe_load((ROOT / "cases" / "oc3_offset.yaml").read_text())
    case["analyses"] = [a for a in case["analyses"] if a["kind"] == "statics"]
    case["name"] = "p2"
    path.write_text(yaml.safe_dump(case, sort_keys=False))
    return path


@dataclass
class ThreeLines:
    """P2 on the three lines: whole processes (CPU and wall seconds) and in-process times [s];
    the MoorPy members are None without MoorPy."""

    statics: ProcessTime
    stiffness: ProcessTime
    k11: float | None
    moorpy: ProcessTime | None = None
    k11_moorpy: float | None = None
    in_process: float | None = None
    in_process_moorpy: float | None = None


def have_moorpy() -> bool:
    try:
        import moorpy  # noqa: F401
    except ImportError:
        return False
    return True


def three_lines(repeat: int = 5) -> ThreeLines:
    """Time the three-line statics and 6x6 of both codes (see the module docstring)."""
    with tempfile.TemporaryDirectory(prefix="p2-") as tmp:
        folder = Path(tmp)
        case = write_statics_case(folder / "p2.yaml")
        env = python_env()
        stiff_args = moorline_command("stiffness", str(case), "--reference", "0,0,0", "--json")
        stiff = best_process(stiff_args, repeat, cwd=folder, env=env)
        statics = best_process(moorline_command("statics", str(case), "--out",
                                                str(folder / "out"), "--json"), repeat,
                               cwd=folder, env=env)
        out = ThreeLines(statics, stiff, _k11(_json_of(stiff_args, folder, env)))
        if not have_moorpy():
            return out
        deck = write_moorpy_deck(folder / "moorpy.dat")
        args = [sys.executable, str(HERE / "moorpy_drive.py"), str(deck)]
        mp_env = {**env, "OPENBLAS_NUM_THREADS": "1"}
        out.moorpy = best_process(args, repeat, cwd=folder, env=mp_env)
        out.k11_moorpy = _json_of(args, folder, mp_env).get("K11")
        out.in_process, out.in_process_moorpy = _in_process(case, deck, max(repeat, 3))
    return out


def _json_of(args: list[str], folder: Path, env: dict[str, str]) -> dict:
    done = subprocess.run(args, cwd=folder, env=env, capture_output=True, text=True)
    return json.loads(done.stdout) if done.returncode == 0 else {}


def _k11(data: dict) -> float | None:
    try:
        return float(data["stiffness"][0][0])
    except (KeyError, IndexError, TypeError):
        return None


def _in_process(case: Path, deck: Path, repeat: int) -> tuple[float, float]:
    """Build from input + statics + 6x6 in this process, both codes (imports done) [s]."""
    import moorpy

    from moorline.io import load_case
    from moorline.solvers.stiffness import group_stiffness

    def ours() -> None:
        system = load_case(case)
        fair = [n for n, p in system.points.items() if p.kind == "prescribed"]
        group_stiffness(solve_statics(system), fair, np.zeros(3))

    def theirs() -> None:
        with contextlib.redirect_stdout(io.StringIO()):
            ms = moorpy.System(file=str(deck))
            ms.initialize()
            ms.solveEquilibrium()
            ms.getCoupledStiffnessA()

    ours()
    theirs()
    return best_of(ours, repeat), best_of(theirs, repeat)


def print_three_lines(r: ThreeLines) -> None:
    """Print the three-line times and ratios."""
    print(f"  moorline stiffness --json (statics + 6x6): {r.stiffness.cpu:.2f} s CPU, "
          f"{r.stiffness.wall:.2f} s wall; K11 {fmt(r.k11, '.1f')} N/m")
    print(f"  moorline statics --json (statics, results.nc, summary): {r.statics.cpu:.2f} s "
          f"CPU, {r.statics.wall:.2f} s wall")
    if r.moorpy is None:
        print("  MoorPy is not installed: moorline only")
        return
    print(f"  MoorPy (import, build from input, solveEquilibrium, getCoupledStiffnessA): "
          f"{r.moorpy.cpu:.2f} s CPU, {r.moorpy.wall:.2f} s wall; K11 "
          f"{fmt(r.k11_moorpy, '.1f')} N/m")
    for what, run in (("stiffness", r.stiffness), ("statics", r.statics)):
        print(f"  ratio moorline {what} / MoorPy, whole process: {run.cpu / r.moorpy.cpu:.2f} "
              f"(CPU), {run.wall / r.moorpy.wall:.2f} (wall)")
    if r.in_process is not None and r.in_process_moorpy:
        print(f"  in process (build from input + statics + 6x6): moorline "
              f"{1e3 * r.in_process:.1f} ms, MoorPy {1e3 * r.in_process_moorpy:.1f} ms, ratio "
              f"{r.in_process / r.in_process_moorpy:.2f}")


def moorpy_solver(segments: int):
    """A callable building and solving the OC3 line with MoorPy (the same moorline system,
    :func:`moorline.compare.moorpy_runner.solve_moorpy`), or None without MoorPy."""
    if not have_moorpy():
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


def print_one_line(rows: list[dict]) -> None:
    """Print the one-line table."""
    print(f"  one OC3 line (in process): {'elements':>8} {'moorline [ms]':>14} "
          f"{'iterations':>10} {'MoorPy [ms]':>12} {'ratio':>7} {'T_fair moorline':>16} "
          f"{'T_fair MoorPy':>14}")
    for r in rows:
        ratio = r["moorline"] / r["moorpy"] if r["moorpy"] else None
        print(f"  {'':27}{r['elements']:8d} {1e3 * r['moorline']:14.2f} {r['iterations']:10d} "
              f"{fmt(None if r['moorpy'] is None else 1e3 * r['moorpy'], '12.2f'):>12} "
              f"{fmt(ratio, '7.2f'):>7} {r['tension']:16.1f} "
              f"{fmt(r['moorpy_tension'], '14.1f'):>14}")
    print(f"  ({NOTE})")


NOTE = ("ratio = moorline time / MoorPy time (below 1: moorline faster). MoorPy solves a "
        "line as one closed-form catenary whatever its segment count; moorline the "
        "finite-element equilibrium of all nodes")


def main(argv: list[str] | None = None) -> None:
    """Time and print."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args(argv)
    print("OC3 three lines, statics and platform 6x6 (whole processes, best of "
          f"{args.repeat}):")
    print_three_lines(three_lines(args.repeat))
    print()
    print_one_line(one_line(repeat=args.repeat))


if __name__ == "__main__":
    main()
