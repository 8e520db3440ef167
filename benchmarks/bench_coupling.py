"""Coupling benchmark: one MoorDyn-style driver, run on ``moordyn`` itself and on moorline's
facade :mod:`moorline.coupling.moordyn`.

The driver (:func:`moorline.compare.moordyn_driver.drive`) is written against the
``moordyn`` module's call pattern (``Create``, ``Init``, ``Step``, ``GetLine``,
``GetLineFairTen``, ``GetLineNodeForce``, ``Close``) and takes the module as an argument:
the only difference between the two runs is the module (and the input: a moorline case for
the facade, the same system written as a MoorDyn deck by
:func:`~moorline.io.moordyn.write_moordyn` for MoorDyn). It moves the OC3
fairleads of ``cases/oc3_dynamics.yaml`` along the case's motion (5 m surge at 10 s, ramped
over 10 s), giving position and velocity at the start of each 0.05 s coupling interval as
MoorDyn expects; MoorDyn sub-steps with its explicit ``dtM`` (default 0.05 / 16 s), moorline
makes one implicit step per interval.

Printed: for each line, the statistics (mean, std, max, min) over ``t`` in [20, 60] s of the
fairlead tension ``GetLineFairTen`` (top segment) and of ``|GetLineNodeForce(line, N)|`` (the
force on the fairlead) side by side, their relative differences, and the wall times of
``Create`` + ``Init`` and of the stepping loop.

Usage::

    python benchmarks/bench_coupling.py              # 60 s, dtM = 0.05 / 16 s
    python benchmarks/bench_coupling.py --dtm 0.001 --duration 120
    python benchmarks/bench_coupling.py --substep 0.0125   # moorline's steps within 0.05 s
    python benchmarks/bench_coupling.py --no-moordyn
"""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path

import numpy as np

from moorline.compare.moordyn_driver import drive
from moorline.io import load_case
from moorline.io.moordyn import write_moordyn

CASE = Path(__file__).resolve().parents[1] / "cases" / "oc3_dynamics.yaml"
COUPLING_DT = 0.05


def _stats(series: np.ndarray) -> np.ndarray:
    return np.array([series.mean(), series.std(), series.max(), series.min()])


def report(runs: dict[str, dict], start: float, names: list[str]) -> None:
    labels = list(runs)
    for key, title in (("fair_ten", "GetLineFairTen (top segment) [kN]"),
                       ("fairlead_force", "|GetLineNodeForce(line, N)| [kN]")):
        print(f"\n{title}, t in [{start:g}, end] s")
        head = "".join(f"{f'{lab} {s}':>18}" for s in ("mean", "std", "max", "min")
                       for lab in labels)
        print(f"{'line':8}{head}")
        for j, name in enumerate(names):
            row, stats = [], {}
            for lab in labels:
                r = runs[lab]
                keep = r["time"] >= start - 1e-9
                stats[lab] = _stats(r[key][keep, j]) / 1e3
            for k in range(4):
                row.extend(stats[lab][k] for lab in labels)
            print(f"{name:8}" + "".join(f"{v:18.3f}" for v in row))
            if len(labels) == 2:
                a, b = stats[labels[0]], stats[labels[1]]
                rel = (a - b) / np.where(b != 0, np.abs(b), 1.0)
                print(f"{'  diff':8}" + "  ".join(
                    f"{s} {v:+.2%}" for s, v in zip(("mean", "std", "max", "min"), rel,
                                                    strict=True)))
    print("\nwall time [s]")
    for lab in labels:
        r = runs[lab]
        print(f"  {lab:10} Create+Init {r['wall_init']:8.3f}   stepping {r['wall_loop']:8.3f}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--duration", type=float, default=60.0)
    parser.add_argument("--start", type=float, default=20.0,
                        help="statistics from this time on [s]")
    parser.add_argument("--dtm", type=float, default=COUPLING_DT / 16,
                        help="MoorDyn's internal step dtM [s]")
    parser.add_argument("--substep", type=float, default=None,
                        help="moorline's largest internal step [s] (default: one implicit "
                             "step per coupling interval)")
    parser.add_argument("--no-moordyn", action="store_true")
    args = parser.parse_args()
    system = load_case(CASE)
    import moorline.coupling.moordyn as facade

    # a first short run compiles the numba kernels (not timed below)
    drive(facade, str(CASE), system, 4 * COUPLING_DT, COUPLING_DT)
    runs = {"moorline": drive(facade, str(CASE), system, args.duration, COUPLING_DT,
                              substep=args.substep)}
    if not args.no_moordyn:
        import moordyn

        with tempfile.TemporaryDirectory() as folder:
            deck = write_moordyn(system, Path(folder) / "oc3.dat", args.dtm)
            runs["moordyn"] = drive(moordyn, str(deck), system, args.duration, COUPLING_DT)
    print(f"OC3 fairleads, {CASE.name}: {args.duration:g} s, coupling interval "
          f"{COUPLING_DT:g} s; moorline "
          + (f"implicit steps of {args.substep:g} s" if args.substep
             else "one implicit step per interval")
          + ("" if args.no_moordyn else f", MoorDyn dtM = {args.dtm:g} s"))
    report(runs, args.start, list(system.lines))


if __name__ == "__main__":
    main()
