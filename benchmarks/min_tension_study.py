"""Issue 16, deliverable 4: why moorline's fairlead-tension minimum on the P1 case is higher.

The case is line 1 of P1 (:mod:`bench_p1`): one OC3 line, its fairlead surging 5 m at 10 s
along the line, fixed axial damping ``BA = 6.2358e6 N s`` (the other two lines of P1 see the
motion at 60 deg and never approach slack; line 1 holds P1's minimum). Extremes: max and min
over the last third of the run on the 0.05 s grid (P1's :func:`bench_p1.extremes`) of the
force on the fairlead (``fair``: moorline's ``fairlead_tension``, MoorDyn's
``|GetLineNodeForce|``, CableDyn's ``FairTen1``) and of the top segment's tension (``seg``:
moorline's last element ``tension``, MoorDyn's ``|GetLineNodeTen(N)|``; the same quantity in
both, free of the end-node conventions). Runs are 150 s (periodic after ~60 s: at 80 segments
the 100-150 s and 200-300 s extremes differ by 0.3 %).

Usage: ``python benchmarks/min_tension_study.py [--quick]`` prints the table of runs
(``--quick``: the 40-segment runs, a few CPU minutes; all: about half an hour).

Findings (measured on the shared 2-core machine, kN, top-segment tension unless ``fair``)
------------------------------------------------------------------------------------------
1. **Where the minimum comes from.** At the minimum (t = 9.9 s mod 10: the fairlead moving
   towards the anchor at full speed) the whole grounded part of the line and the touchdown
   region, 30-35 of 80 elements from the anchor, are slack. The minimum is set by how that
   slack chain moves, i.e. by the slack model.
2. **Two modelling differences in slack chain, both in MoorDyn-C v2.7 source/Line.cpp:**
   (a) MoorDyn keeps the Kelvin-Voigt dashpot in slack segments (``Td = BA ldstr / l qs``
   whatever the strain, while ``T = 0``): a slack segment pushes back against shortening;
   moorline blends the dashpot off with the tension (a slack cable transmits no force).
   (b) MoorDyn evaluates the drag at each node with that node's velocity; moorline evaluates
   an element's drag at the mean of its two node velocities, which exerts no drag on the
   odd-even (zig-zag) mode of the mesh, the mode the slack chain takes. Each alone moves
   moorline's minimum by several per cent, in opposite directions; with both set as MoorDyn
   (``slack_damping: true``, ``drag_velocity: node``) moorline reproduces MoorDyn at 40, 80
   and 160 segments (min within 0.3 %, 0.2 %, 0.2 %; max within 0.05 %, 0.06 %, 0.07 %),
   while its default model stays 3.7-6 % above MoorDyn from 80 segments on:

   =========  ==================================  ====  =======  =======  =======
   code       setting                             seg   dt [s]   max      min
   =========  ==================================  ====  =======  =======  =======
   moorline   default                             40    0.005    1935.39  87.44
   moorline   slack_damping                       40    0.005    1934.24  97.17
   moorline   drag_velocity node                  40    0.005    1931.90  90.28
   moorline   both (MoorDyn's model)              40    0.005    1932.40  87.48
   MoorDyn    coupling 0.003125 s                 40    1.56e-3  1933.35  87.22
   moorline   default                             80    0.0025   1936.44  99.68
   moorline   default                             80    0.00125  (fair 1938.56 / 102.30;
                                                                 at 0.0025: 1938.61 / 102.31)
   moorline   slack_damping                       80    0.005    1934.24  102.36
   moorline   drag_velocity node                  80    0.0025   1935.23  96.06
   moorline   both (MoorDyn's model)              80    0.0025   1934.72  94.27
   MoorDyn    coupling 0.003125 s                 80    3.94e-4  1935.84  94.08
   MoorDyn    RK4, coupling 0.05 s                80    3.94e-4  1946.99  95.15
   MoorDyn    RK2, coupling 0.05 s                80    3.94e-4  1946.99  95.13
   moorline   default                             160   0.0025   1936.52  100.30
   moorline   default                             160   0.00125  1936.47  100.67
   moorline   both (MoorDyn's model)              160   0.0025   1935.99  96.88
   MoorDyn    coupling 0.003125 s                 160   9.90e-5  1937.38  96.70
   CableDyn   FairTen1 (fair)                     40    0.005    1939.16  93.26
   CableDyn   FairTen1 (fair), P1's 3-line run    80    0.005    1937.03  100.48
   =========  ==================================  ====  =======  =======  =======

   Neither code's other options close the gap alone (80 segments, moorline dt 0.0025 s /
   MoorDyn coupling 0.05 s, min): seabed damping cBot = 0: 97.50 / 94.51 (3.2 % apart instead
   of 4.8 %: MoorDyn's contact damping also pulls a lifting node down, moorline's never pulls);
   Ct = 0: 109.59 / 104.94; Ca = 0: 103.27 / 98.93; Cd = 0.8: 180.04 / 177.14. MoorDyn's
   RK2 and RK4 agree (0.02 %), moorline is converged in dt at 80 segments (0.01 %).
3. **Not the time integration.** moorline's minimum is step-size sensitive only while its
   steps are cut (160 segments, fair: dt 0.01 s 105.21, 0.005 s 100.58, 0.0025 s 101.63,
   0.00125 s 101.99 kN, 348-451 step cuts at the coarser steps): the dt-converged minimum is
   *higher*, not closer to the peers'. The remaining difference to MoorDyn is the slack model.
4. **A bias of the MoorDyn runs, P1's driver.** Within each ``Step`` call MoorDyn moves a
   coupled point at constant velocity from the position given (source/Point.cpp,
   ``updateFairlead``); with the exact velocity at the start of each 0.05 s interval the
   fairlead jumps by ``a h^2 / 2`` (up to 2.5 mm) at every call, and its velocity by
   ``a h``. That raised MoorDyn's maximum by 0.5-0.6 % and its minimum by 1.1 % at 40 and
   80 segments (seg: 1944.30 / 88.31 and 1946.99 / 95.13 against 1933.35 / 87.22 and
   1935.84 / 94.08 with a 0.003125 s coupling). P1's MoorDyn extremes (and the "maxima
   agree within 0.26 %") carry it; ``moorline.compare.moordyn_runner.run_moordyn`` has a
   ``coupling_dt`` for this.
5. Which slack model is right is a modelling choice: a chain cannot push (moorline's
   dashpot), and the midpoint drag rule converges to the same line as the nodal one but more
   slowly where the line zig-zags. moorline keeps its defaults and offers MoorDyn's choices;
   ``tests/test_min_tension_moordyn.py`` (slow) checks the 80-segment row against MoorDyn.
6. The extremes quoted in issue 16 (moorline 1836.8 / 130.6 kN at 320 segments) are not
   those of this code on P1: line 1's fair extremes are 1938.5 / 102.7 kN at 80 segments over
   200-300 s of a 300 s run (1938.6 / 102.4 over 100-150 s of 150 s), and every code here
   agrees on the maximum within 0.1 % once MoorDyn's coupling is fine.
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import sys
import tempfile
import time
from pathlib import Path

import bench_p1
import numpy as np
from bench_common import ROOT

sys.path.insert(0, str(ROOT / "src"))

BA = bench_p1.BA
DURATION = 150.0


def line_system(segments: int, **changes: float):
    """Line 1 of P1 with ``segments`` elements; ``changes``: line-type fields (``Cd``, ``Ct``,
    ``Ca``, ``BA``, ...) or ``cBot`` (seabed damping [Pa s/m])."""
    from moorline.verification.oc3_system import oc3_one_line

    system = oc3_one_line(segments, BA=BA)
    env = system.environment
    if "cBot" in changes:
        seabed = dataclasses.replace(env.seabed, damping=changes.pop("cBot"))
        system = dataclasses.replace(system, environment=dataclasses.replace(env, seabed=seabed))
    if changes:
        chain = dataclasses.replace(system.line_types["chain"], **changes)
        system = dataclasses.replace(system, line_types={"chain": chain})
    return system


def _extremes(t: np.ndarray, tension: np.ndarray, duration: float) -> tuple[float, float]:
    (high, low), = bench_p1.extremes(t, tension.reshape(len(t), -1), duration)
    return high, low


def run_moorline(system, dt: float, duration: float = DURATION, **settings) -> dict:
    """moorline's ``simulate`` on ``system`` (statics first); ``settings``: more
    :class:`~moorline.model.DynamicsSettings` fields."""
    from moorline.model import DynamicsSettings
    from moorline.solvers.dynamics import simulate

    start = time.process_time()
    result = simulate(system, DynamicsSettings(duration=duration, dt=dt, **settings),
                      output_every=bench_p1.SAMPLE)
    cpu = time.process_time() - start
    t = np.asarray(result.time)
    high, low = _extremes(t, np.asarray(result.end_tension("line1")), duration)
    top = result.mesh.line_elements[0][-1]  # the element at the fairlead (end b)
    seg_high, seg_low = _extremes(t, np.asarray(result.tension)[:, top], duration)
    return {"max": high, "min": low, "seg_max": seg_high, "seg_min": seg_low, "cpu": cpu,
            "ok": result.success and t[-1] >= duration - 1e-6,
            "cuts": result.counters.get("step_cuts", 0)}


def run_moordyn(system, dt: float, duration: float = DURATION, segment: bool = False,
                coupling: float = bench_p1.SAMPLE, secant: bool = False, **options) -> dict:
    """MoorDyn-C (the ``moordyn`` module) through P1's driver script: the end node's force
    (``max``, ``min``) or, with ``segment``, the top segment's tension (``seg_max``,
    ``seg_min``); ``options``: more arguments of :func:`moorline.io.moordyn.write_moordyn`
    (``time_scheme``).

    ``coupling``: the interval of the ``Step`` calls [s]. Within a call MoorDyn moves a
    coupled point from the position given at constant velocity, the velocity given
    (MoorDyn-C v2.7 source/Point.cpp, ``updateFairlead``: ``r = r_ves + rd_ves t``), so with
    the exact velocity at the start of the interval the fairlead jumps by ``a dt^2 / 2`` at
    every call; ``secant``: pass the interval's mean velocity ``(x[k+1] - x[k]) / dt``
    instead (a continuous, piecewise linear fairlead path)."""
    import moordyn_drive

    from moorline.compare.moordyn_runner import silenced_fd

    segments = system.lines["line1"].segments
    with tempfile.TemporaryDirectory(prefix="mintension-md-") as tmp:
        folder = Path(tmp)
        deck = bench_p1.write_moordyn(folder, segments, dt, duration, system, **options)
        if coupling != bench_p1.SAMPLE or secant:
            table = bench_p1.motion_table(segments, coupling, duration, system)
            v = table["v"]
            if secant:
                v = np.vstack([np.diff(table["x"], axis=0) / coupling, v[-1:]])
            np.savez(folder / "motion.npz", t=table["t"], x=table["x"], v=v)
        start = time.process_time()
        try:
            with silenced_fd(1), silenced_fd(2):  # MoorDyn's banner and the driver's timing
                code = moordyn_drive.main(str(deck), str(folder / "motion.npz"),
                                          str(folder / "out.txt"),
                                          "segment" if segment else "force")
        except RuntimeError:  # MoorDyn's integration failed (unstable step)
            return {"cpu": time.process_time() - start, "ok": False, "cuts": 0}
        cpu = time.process_time() - start
        data = np.loadtxt(folder / "out.txt", ndmin=2)
    ok = code == 0 and data[-1, 0] >= duration - 1e-6
    high, low = _extremes(data[:, 0], data[:, 1], duration) if ok else (math.nan, math.nan)
    prefix = "seg_" if segment else ""
    return {prefix + "max": high, prefix + "min": low, "cpu": cpu, "ok": ok, "cuts": 0}


def run_cabledyn(system, dt: float, duration: float = DURATION) -> dict:
    """CableDyn's stand-alone driver on P1's deck of ``system`` (its ``FairTen1`` only: its
    segment tensions are not written here)."""
    import subprocess

    from cabledyn import read_output

    segments = system.lines["line1"].segments
    with tempfile.TemporaryDirectory(prefix="mintension-cd-") as tmp:
        folder = Path(tmp)
        deck = bench_p1.write_cabledyn(folder, segments, dt, duration, system)
        start = time.perf_counter()
        proc = subprocess.run([str(bench_p1.cabledyn_binary()), str(deck), str(folder / "p1")],
                              cwd=folder, capture_output=True, text=True)
        wall = time.perf_counter() - start
        if proc.returncode != 0:
            return {"max": math.nan, "min": math.nan, "cpu": wall, "ok": False, "cuts": 0}
        out = read_output(folder / "p1.out")
        t = np.asarray(out.time, dtype=float)
        tension = np.asarray(out.column("FairTen1"), dtype=float)
    high, low = _extremes(t, tension, duration)
    return {"max": high, "min": low, "cpu": wall, "ok": t[-1] >= duration - 1e-6, "cuts": 0}


def stable_dt(segments: int) -> float:
    """MoorDyn's step for this mesh (:func:`bench_p1.stable_moordyn_dt`)."""
    return bench_p1.stable_moordyn_dt(segments)


@dataclasses.dataclass
class Case:
    """One run of the study: code, mesh, step, line-type/seabed changes, code options."""

    code: str
    segments: int
    dt: float = math.nan  # NaN: MoorDyn's stable step
    changes: dict = dataclasses.field(default_factory=dict)
    options: dict = dataclasses.field(default_factory=dict)

    def run(self, duration: float = DURATION) -> dict:
        system = line_system(self.segments, **self.changes)
        if self.code == "moorline":
            return run_moorline(system, self.dt, duration, **self.options)
        if self.code == "MoorDyn":
            dt = self.dt if math.isfinite(self.dt) else stable_dt(self.segments)
            return run_moordyn(system, dt, duration, segment=True, **self.options)
        return run_cabledyn(system, self.dt, duration)


#: moorline set to MoorDyn's model: the dashpot in slack elements, the drag at the nodes.
MOORDYN_MODEL = {"slack_damping": True, "drag_velocity": "node"}


def cases(quick: bool) -> list[Case]:
    """The key runs (``quick``: only those at 40 segments, about a minute of CPU)."""
    fine = {"coupling": 0.003125}
    out = [Case("moorline", 40, 0.005), Case("moorline", 40, 0.0025),
           Case("MoorDyn", 40), Case("MoorDyn", 40, options={"secant": True}),
           Case("MoorDyn", 40, options=fine),
           Case("moorline", 40, 0.005, options={"slack_damping": True}),
           Case("moorline", 40, 0.005, options={"drag_velocity": "node"}),
           Case("moorline", 40, 0.005, options=MOORDYN_MODEL),
           Case("CableDyn", 40, 0.005)]
    if quick:
        return out
    out += [Case("moorline", 80, 0.0025), Case("moorline", 80, 0.00125),
            Case("MoorDyn", 80), Case("MoorDyn", 80, options=fine),
            Case("MoorDyn", 80, options={"time_scheme": "RK4"})]
    for change in ({"cBot": 0.0}, {"Ct": 0.0}, {"Ca": 0.0}, {"Cd": 0.8}):
        out += [Case("moorline", 80, 0.0025, change), Case("MoorDyn", 80, changes=change)]
    out += [Case("moorline", 80, 0.0025, options={"slack_damping": True}),
            Case("moorline", 80, 0.0025, options={"drag_velocity": "node"}),
            Case("moorline", 80, 0.0025, options=MOORDYN_MODEL),
            Case("moorline", 160, 0.005), Case("moorline", 160, 0.0025),
            Case("moorline", 160, 0.00125), Case("moorline", 160, 0.0025, options=MOORDYN_MODEL),
            Case("MoorDyn", 160, options=fine)]
    return out


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="only the runs at 40 segments")
    parser.add_argument("--duration", type=float, default=DURATION, help="simulated time [s]")
    args = parser.parse_args(argv)
    print(f"{'code':9s} {'segments':>8s} {'dt [s]':>9s}  {'setting':40s} {'fair max':>9s} "
          f"{'fair min':>9s} {'seg max':>9s} {'seg min':>9s}  [kN]")
    for case in cases(args.quick):
        r = case.run(args.duration)
        dt = case.dt if math.isfinite(case.dt) else stable_dt(case.segments)
        setting = " ".join(f"{k}={v}" for k, v in {**case.changes, **case.options}.items())
        values = " ".join(f"{r.get(k, math.nan) / 1e3:9.2f}"
                          for k in ("max", "min", "seg_max", "seg_min"))
        flag = "" if r["ok"] else "  FAILED"
        print(f"{case.code:9s} {case.segments:8d} {dt:9.5g}  {setting or 'default':40s} {values}"
              f"{flag}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
