"""Dynamics benchmark: the OC3-Hywind three-line system against MoorDyn, in one run.

All three fairleads surge 5 m at 10 s (ramped in over 10 s,
:mod:`moorline.verification.oc3_system`); 300 s are simulated. The accuracy metric is the set
of fairlead-tension extremes: the largest and the smallest end-B tension of each line over
``t`` in [100, 300] s (six numbers); a run's *error* is
the largest relative difference of its six numbers from those of a converged reference run of
the same code. Tensions are sampled at every moorline step and every 0.05 s for MoorDyn (its
coupling interval; MoorDyn sub-steps within it and moves the fairleads linearly).

Printed, with wall times measured in this process:

1. converged references: moorline at 80 segments per line and dt 0.0125 s, with the change of
   its extremes when dt is halved and when the segments are doubled; MoorDyn at 160 segments
   at its largest stable step, with the changes between successive segment doublings
   (20 -> 40 -> 80 -> 160) and when its step is halved; the difference between the two
   codes' converged extremes;
2. for each code, the cheapest setting within 1 % of its own reference: moorline over
   segments (10, 20, 40, 80) x dt (0.1, 0.05, 0.025, 0.0125) s, MoorDyn over segments
   (20, 40, 80, 160) at each count's largest stable step; both times and the ratio;
3. the plain ratio at 20 segments per line: moorline at dt 0.05 s, MoorDyn at its largest
   stable step;
4. moorline's time per step on one OC3 line at 10, 100 and 1000 elements (20 s at dt 0.05 s
   after statics) and the ratio 1000/100.

Wall time of moorline is the :func:`~moorline.solvers.dynamics.simulate` call (its statics is
timed separately); wall time of MoorDyn is its ``Create`` + ``Init`` (reading the deck and its
initial-condition solve) plus its stepping loop, both printed; the summary also gives the
ratios of the stepping alone and of statics/initial condition + stepping on both sides. A
moorline run that raises :class:`~moorline.errors.ConvergenceError` is reported as a failed
candidate.

MoorDyn's largest stable step (:func:`~moorline.compare.moordyn_runner.largest_stable_dt`, a
search of 20 s trial runs that takes minutes at 160 segments) is cached in
``benchmarks/.cache/moordyn_stable_dt.json``, keyed by the segment count and the ``moordyn``
version; delete the file or pass ``--refresh`` to search again. The step used is rounded down
to ``0.05 s / n`` (a whole number of MoorDyn steps per coupling interval). A step that passed the
20 s trials but blows up later in the 300 s run is replaced by ``0.05 s / (n + 1)``, and so on;
the cache records the step that completed a full run.

Usage::

    python benchmarks/bench_dynamics.py            # full: about 10 minutes (make bench)
    python benchmarks/bench_dynamics.py --quick    # 100 s runs, extremes over [50, 100] s,
                                                   # fewer candidates, no convergence checks
    python benchmarks/bench_dynamics.py --no-moordyn
    python benchmarks/bench_dynamics.py --ba 1.56e6  # a fixed damping [N s] instead of -0.8

(``make bench BENCH_ARGS=--quick`` passes options through make.) With MoorDyn's ``BA = -0.8``
the damping coefficient of a segment is ``0.8 L_seg sqrt(EA m)``: it halves when the segments
are doubled, so the mesh limit of either code is an axially undamped line, approached slowly.

Without the ``moordyn`` package (``pip install -e .[compare]``) only moorline is run.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from moorline.compare.moordyn_runner import silenced_fd
from moorline.errors import ConvergenceError
from moorline.model import DynamicsSettings
from moorline.solvers.dynamics import simulate
from moorline.solvers.statics import solve_statics
from moorline.verification.oc3_system import oc3_one_line, oc3_three_lines

TOLERANCE = 0.01  # "within 1 %"
COUPLING = 0.05  # MoorDyn coupling and output interval [s]
CACHE = Path(__file__).resolve().parent / ".cache" / "moordyn_stable_dt.json"


@dataclass(frozen=True)
class Plan:
    """What one benchmark run does."""

    duration: float
    window: tuple[float, float]
    ml_segments: tuple[int, ...]
    ml_dts: tuple[float, ...]
    ml_reference: tuple[int, float]
    md_segments: tuple[int, ...]
    md_reference: int
    convergence_checks: bool
    ba: float = -0.8  # internal damping of the chain (negative: MoorDyn's -zeta)


FULL = Plan(300.0, (100.0, 300.0), (10, 20, 40, 80), (0.1, 0.05, 0.025, 0.0125), (80, 0.0125),
            (20, 40, 80, 160), 160, True)
QUICK = Plan(100.0, (50.0, 100.0), (10, 20, 40), (0.1, 0.05, 0.025), (80, 0.0125),
             (20, 40, 80, 160), 160, False)


@dataclass
class Run:
    """One simulation: its setting, outcome, extremes and wall times."""

    code: str
    segments: int
    dt: float
    ok: bool = False
    message: str = ""
    extremes: np.ndarray | None = None  # (n_lines, 2): max and min end-B tension [N]
    wall: float = 0.0  # moorline: simulate; MoorDyn: init + loop [s]
    prep: float = 0.0  # moorline: statics; MoorDyn: Create + Init [s]
    loop: float = 0.0  # moorline: simulate; MoorDyn: stepping loop [s]
    info: dict[str, Any] = field(default_factory=dict)

    @property
    def label(self) -> str:
        return f"{self.segments} seg, dt {self.dt:.4g} s"

    @property
    def total(self) -> float:
        """Statics / initial condition plus stepping [s]."""
        return self.prep + self.loop


# ---------------------------------------------------------------------------------------------
# metric


def extremes(time_: np.ndarray, tension: np.ndarray, window: tuple[float, float]) -> np.ndarray:
    """Max and min of each column of ``tension`` (n_t, n_lines) over ``window``: (n_lines, 2)."""
    mask = (time_ >= window[0] - 1e-9) & (time_ <= window[1] + 1e-9)
    part = tension[mask]
    return np.column_stack([part.max(axis=0), part.min(axis=0)])


def error(run: Run, reference: Run) -> float | None:
    """Largest relative difference of the six extremes from the reference's."""
    if run.extremes is None or reference.extremes is None:
        return None
    return float(np.max(np.abs(run.extremes - reference.extremes) / np.abs(reference.extremes)))


def error_max_only(run: Run, reference: Run) -> float | None:
    """Largest relative difference of the three maxima alone."""
    if run.extremes is None or reference.extremes is None:
        return None
    a, b = run.extremes[:, 0], reference.extremes[:, 0]
    return float(np.max(np.abs(a - b) / np.abs(b)))


def pct(value: float | None, digits: int = 3) -> str:
    return "n/a" if value is None else f"{100 * value:.{digits}f} %"


# ---------------------------------------------------------------------------------------------
# moorline


def warm_up() -> None:
    """Load the compiled kernels once so that no timed run pays for it."""
    system = oc3_three_lines(10)
    simulate(system, DynamicsSettings(duration=0.5, dt=0.05), initial=solve_statics(system))
    single = oc3_one_line(10)
    simulate(single, DynamicsSettings(duration=0.5, dt=0.05), initial=solve_statics(single))


def run_moorline(segments: int, dt: float, plan: Plan, output_every: float | None = None
                 ) -> Run:
    """Statics, then ``plan.duration`` of dynamics, tensions at every step (or
    ``output_every``)."""
    run = Run("moorline", segments, dt)
    system = oc3_three_lines(segments, BA=plan.ba)
    tic = time.perf_counter()
    static = solve_statics(system)
    run.prep = time.perf_counter() - tic
    if not static.success:
        run.message = f"statics failed: {static.message}"
        return run
    settings = DynamicsSettings(duration=plan.duration, dt=dt)
    tic = time.perf_counter()
    try:
        result = simulate(system, settings, initial=static, output_every=output_every or dt)
    except ConvergenceError as exc:
        run.loop = run.wall = time.perf_counter() - tic
        run.message = f"ConvergenceError: {exc}"
        return run
    run.loop = run.wall = time.perf_counter() - tic
    tension = np.column_stack([result.end_tension(name, "b") for name in system.lines])
    run.ok, run.message = True, "completed"
    run.extremes = extremes(result.time, tension, plan.window)
    run.info = dict(result.counters)
    return run


# ---------------------------------------------------------------------------------------------
# MoorDyn


def moordyn_module() -> Any | None:
    try:
        import moordyn
    except ImportError:
        return None
    return moordyn


def moordyn_version() -> str:
    try:
        from importlib.metadata import version

        return version("moordyn")
    except Exception:  # pragma: no cover - metadata missing
        return "unknown"


class StableSteps:
    """MoorDyn's largest stable step per segment count, cached in a JSON file."""

    def __init__(self, path: Path, refresh: bool, ba: float) -> None:
        self.path = path
        self.ba = ba
        self.version = moordyn_version()
        self.data: dict[str, Any] = {}
        if path.is_file() and not refresh:
            try:
                self.data = json.loads(path.read_text())
            except (OSError, ValueError):
                self.data = {}

    def key(self, segments: int) -> str:
        return f"oc3_three_lines/segments={segments}/BA={self.ba:g}/moordyn={self.version}"

    def save(self) -> None:
        self.path.parent.mkdir(parents=True, exist_ok=True)
        ignore = self.path.parent / ".gitignore"
        if not ignore.exists():
            ignore.write_text("*\n")
        stored = {k: {f: v for f, v in e.items() if f != "from_cache"}
                  for k, e in self.data.items()}
        self.path.write_text(json.dumps(stored, indent=2, sort_keys=True) + "\n")

    def entry(self, segments: int) -> dict[str, Any]:
        """The cached entry, searching (and caching) when missing."""
        key = self.key(segments)
        if key in self.data:
            self.data[key]["from_cache"] = True
            return self.data[key]
        from moorline.compare.moordyn_runner import largest_stable_dt

        print(f"  searching MoorDyn's largest stable step at {segments} segments "
              "(cached afterwards) ...", flush=True)
        tic = time.perf_counter()
        with silenced_fd(2):  # the unstable trials make MoorDyn print NaN errors
            found = largest_stable_dt(oc3_three_lines(segments, BA=self.ba))
        seconds = time.perf_counter() - tic
        dt = found["dt"]
        self.data[key] = {
            "segments": segments, "search_dt": dt, "unstable_dt": found["unstable_dt"],
            "trials": len(found["trials"]), "search_seconds": seconds,
            "criterion": found["criterion"],
            "divisor": None if dt is None else math.ceil(COUPLING / dt - 1e-9),
            "verified_duration": 0.0, "failed_divisors": [],
        }
        self.save()
        self.data[key]["from_cache"] = False
        return self.data[key]


def run_moordyn_once(segments: int, dt: float, plan: Plan) -> Run:
    from moorline.compare.moordyn_runner import run_moordyn

    run = Run("MoorDyn", segments, dt)
    out = run_moordyn(oc3_three_lines(segments, BA=plan.ba), plan.duration, dt, COUPLING)
    run.prep, run.loop = out["wall_time_init"], out["wall_time_loop"]
    run.wall = run.prep + run.loop
    run.ok, run.message = bool(out["success"]), out["message"].splitlines()[0]
    run.info = {"ic_residual": out["ic_residual"], "ic_time": out["ic_time"],
                "n_steps": out["n_steps"]}
    if run.ok:
        run.extremes = extremes(out["time"], out["fairlead_tension"], plan.window)
    return run


def run_moordyn_stable(segments: int, plan: Plan, steps: StableSteps, retries: int = 3) -> Run:
    """MoorDyn at its largest stable step; a smaller one when the full run blows up."""
    entry = steps.entry(segments)
    if entry["divisor"] is None:
        return Run("MoorDyn", segments, math.nan, message="no stable step found")
    for _ in range(retries + 1):
        dt = COUPLING / entry["divisor"]
        run = run_moordyn_once(segments, dt, plan)
        run.info["search_dt"] = entry["search_dt"]
        if run.ok:
            if plan.duration > entry["verified_duration"]:
                entry["verified_duration"] = plan.duration
            steps.save()
            return run
        print(f"  MoorDyn {run.label}: {run.message}; trying a smaller step", flush=True)
        entry["failed_divisors"].append(entry["divisor"])
        entry["divisor"] += 1
        entry["verified_duration"] = 0.0
        steps.save()
    return run


# ---------------------------------------------------------------------------------------------
# scaling


def time_per_step(elements: int, ba: float, duration: float = 20.0, dt: float = 0.05
                  ) -> dict[str, Any]:
    """One OC3 line, ``elements`` elements: statics, then ``duration`` of a 1 m surge at 10 s.

    The motion is kept mild (no slack snaps) so that every mesh does the same work per step:
    this measures how the cost of a step grows with the number of elements. The cost of snap
    events (sub-steps after step cuts) is in the main comparison.

    When the run fails (ConvergenceError), it is repeated up to one second before the failure
    and the time per step is that of the repeat (so that the step cuts of the failing step
    are not counted).
    """
    system = oc3_one_line(elements, BA=ba)
    mild = dataclasses.replace(system.points["fairlead1"].motion, amplitude=(1.0, 0.0, 0.0))
    points = dict(system.points)
    points["fairlead1"] = dataclasses.replace(points["fairlead1"], motion=mild)
    system = dataclasses.replace(system, points=points)
    static = solve_statics(system)
    out: dict[str, Any] = {"elements": elements, "duration": duration, "failed_at": None}
    while True:
        settings = DynamicsSettings(duration=duration, dt=dt)
        tic = time.perf_counter()
        try:
            result = simulate(system, settings, initial=static, output_every=1.0)
        except ConvergenceError as exc:
            failed = exc.time if exc.time is not None else 0.0
            out["failed_at"], out["message"] = failed, str(exc)
            duration = dt * math.floor((failed - 1.0) / dt)
            if duration < 10 * dt:
                out.update(ok=False, per_step=math.nan, steps=0, duration=0.0)
                return out
            continue
        wall = time.perf_counter() - tic
        steps = result.counters["steps"]
        out.update(ok=True, wall=wall, steps=steps, per_step=wall / steps, duration=duration,
                   counters=dict(result.counters))
        return out


def scaling(ba: float, repeat: int = 5) -> list[dict[str, Any]]:
    """Best-of-``repeat`` time per step at 10, 100 and 1000 elements, over the same simulated
    time for all three (shortened to what every mesh completes)."""
    sizes = (10, 100, 1000)
    first = {n: time_per_step(n, ba) for n in sizes}
    common = min(r["duration"] for r in first.values())
    rows = []
    for n in sizes:
        runs = [first[n]] if first[n]["duration"] == common else []
        runs += [time_per_step(n, ba, duration=common) for _ in range(repeat - len(runs))]
        best = min(runs, key=lambda r: r["per_step"] if r["ok"] else math.inf)
        best["failed_at"], best["message"] = first[n]["failed_at"], first[n].get("message")
        rows.append(best)
    return rows


# ---------------------------------------------------------------------------------------------
# printing


HEADER = (f"{'code':<9}{'segments':>9}{'dt [s]':>10}{'error':>11}{'err(max)':>11}"
          f"{'wall [s]':>10}{'statics/init':>13}{'stepping':>10}  notes")


def row(run: Run, reference: Run | None, note: str = "") -> str:
    err = error(run, reference) if reference is not None else None
    errm = error_max_only(run, reference) if reference is not None else None
    if not run.ok:
        note = (note + " FAILED: " + run.message).strip()
    elif run.code == "moorline" and run.info:
        c = run.info
        note = (f"{c.get('iterations', 0)} it, {c.get('factorizations', 0)} fact, "
                f"{c.get('step_cuts', 0)} cuts " + note).strip()
    elif run.code == "MoorDyn" and run.info:
        note = (f"IC residual {run.info.get('ic_residual', math.nan):.2g} m/s2 " + note).strip()
    return (f"{run.code:<9}{run.segments:>9d}{run.dt:>10.5f}{pct(err):>11}{pct(errm):>11}"
            f"{run.wall:>10.2f}{run.prep:>13.2f}{run.loop:>10.2f}  {note}")


def print_extremes(title: str, runs: list[Run]) -> None:
    print(f"\n{title}")
    names = "".join(f"{f'line{k} max':>13}{f'line{k} min':>13}" for k in (1, 2, 3))
    print(f"{'run':<28}{names}  [kN]")
    for run in runs:
        if run.extremes is None:
            print(f"{run.code + ' ' + run.label:<28}  failed")
            continue
        values = "".join(f"{v / 1e3:13.2f}" for v in run.extremes.ravel())
        print(f"{run.code + ' ' + run.label:<28}{values}")


def cheapest(runs: list[Run], reference: Run, metric=error) -> Run | None:
    """The fastest completed run within the tolerance of the reference (by ``metric``)."""
    passing = [r for r in runs if r.ok and (metric(r, reference) or 0.0) <= TOLERANCE]
    return min(passing, key=lambda r: r.wall) if passing else None


# ---------------------------------------------------------------------------------------------


def moorline_part(plan: Plan) -> tuple[Run, list[Run], list[Run]]:
    """Reference, convergence checks and candidate scan of moorline."""
    seg_ref, dt_ref = plan.ml_reference
    print(f"\n== moorline: reference {seg_ref} segments, dt {dt_ref} s ==", flush=True)
    reference = run_moorline(seg_ref, dt_ref, plan)
    print(HEADER)
    print(row(reference, reference, "(reference)"), flush=True)
    if not reference.ok:
        raise SystemExit("moorline's reference run failed: " + reference.message)
    checks: list[Run] = []
    if plan.convergence_checks:
        # half the step sampled on the reference's grid, so that only the step differs
        checks.append(run_moorline(seg_ref, dt_ref / 2, plan, output_every=dt_ref))
        print(row(checks[-1], reference, "(dt halved)"), flush=True)
        checks.append(run_moorline(2 * seg_ref, dt_ref, plan))
        print(row(checks[-1], reference, "(segments doubled)"), flush=True)
    print(f"\n== moorline: candidates (error vs the reference; within {TOLERANCE:.0%} passes) ==")
    print(HEADER)
    candidates = sorted(((n, dt) for n in plan.ml_segments for dt in plan.ml_dts),
                        key=lambda c: (c[0] / c[1], c[0]))
    runs = []
    for n, dt in candidates:
        if (n, dt) == plan.ml_reference:
            runs.append(reference)
            print(row(reference, reference, "(= reference)"), flush=True)
            continue
        runs.append(run_moorline(n, dt, plan))
        print(row(runs[-1], reference), flush=True)
    return reference, checks, runs


def moordyn_part(plan: Plan, refresh: bool) -> tuple[Run, list[Run], list[Run]]:
    steps = StableSteps(CACHE, refresh, plan.ba)
    print(f"\n== MoorDyn {steps.version}: largest stable steps (cache {CACHE}) ==", flush=True)
    for n in plan.md_segments:
        e = steps.entry(n)
        src = "cached" if e.get("from_cache") else f"searched in {e['search_seconds']:.0f} s"
        print(f"  {n:4d} segments: stable {e['search_dt']:.5g} s, unstable "
              f"{e['unstable_dt']:.5g} s ({src}); used 0.05/{e['divisor']} = "
              f"{COUPLING / e['divisor']:.5g} s", flush=True)
    print(f"\n== MoorDyn: reference {plan.md_reference} segments and candidates ==", flush=True)
    print(HEADER)
    reference = run_moordyn_stable(plan.md_reference, plan, steps)
    print(row(reference, reference, "(reference)"), flush=True)
    if not reference.ok:
        raise SystemExit("MoorDyn's reference run failed: " + reference.message)
    runs: list[Run] = []
    for n in plan.md_segments:
        if n == plan.md_reference:
            runs.append(reference)
            continue
        runs.append(run_moordyn_stable(n, plan, steps))
        print(row(runs[-1], reference), flush=True)
    checks: list[Run] = []
    if plan.convergence_checks:
        checks.append(run_moordyn_once(plan.md_reference, reference.dt / 2, plan))
        print(row(checks[-1], reference, "(dt halved)"), flush=True)
    return reference, checks, runs


def same_mesh(ml_runs: list[Run], md_runs: list[Run]) -> None:
    """MoorDyn against moorline's finest-step run at the same segment count."""
    print("Same mesh (moorline at its finest step there; with a negative BA both codes then "
          "have the same damping):")
    for md in sorted((r for r in md_runs if r.ok), key=lambda r: r.segments):
        ml = [r for r in ml_runs if r.ok and r.segments == md.segments]
        if not ml:
            continue
        ml_run = min(ml, key=lambda r: r.dt)
        diff = (md.extremes - ml_run.extremes) / ml_run.extremes
        print(f"  {md.segments:4d} segments (moorline dt {ml_run.dt:g} s): largest |difference| "
              f"{pct(float(np.abs(diff).max()), 2)}, maxima alone "
              f"{pct(float(np.abs(diff[:, 0]).max()), 2)} (line1 max {100 * diff[0, 0]:+.2f} %)")


def doubling_report(runs: list[Run]) -> None:
    """Changes of the extremes between successive segment doublings (MoorDyn)."""
    ok = [r for r in sorted(runs, key=lambda r: r.segments) if r.ok]
    changes = []
    for a, b in zip(ok, ok[1:], strict=False):
        changes.append(error(a, b))
        print(f"  {a.segments:4d} -> {b.segments:4d} segments: extremes change by up to "
              f"{pct(changes[-1])} (maxima alone {pct(error_max_only(a, b))})")
    if len(changes) >= 2 and changes[-1] and changes[-2] and changes[-1] < changes[-2]:
        q = changes[-1] / changes[-2]
        print(f"  ratio of the last two changes {q:.2f}: if it holds, the finest run is within "
              f"about {pct(changes[-1] * q / (1 - q))} of the mesh limit")


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--quick", action="store_true",
                        help="100 s runs (extremes over [50, 100] s), moorline candidates up "
                             "to 40 segments and dt 0.025 s, no convergence checks")
    parser.add_argument("--no-moordyn", action="store_true", help="moorline only")
    parser.add_argument("--ba", type=float, default=1.56e6,
                        help="internal axial damping of the chain [N s] (default 1.56e6: what "
                             "MoorDyn's OC3 example's -0.8 gives at 80 segments, held fixed so "
                             "that mesh refinement converges to one system); negative: minus a "
                             "damping ratio of each segment's axial mode (-0.8 is MoorDyn's "
                             "OC3 example), which changes with the mesh")
    parser.add_argument("--refresh", action="store_true",
                        help="search MoorDyn's largest stable steps again (ignore the cache)")
    args = parser.parse_args(argv)
    plan = dataclasses.replace(QUICK if args.quick else FULL, ba=args.ba)
    start = time.perf_counter()
    moordyn = None if args.no_moordyn else moordyn_module()
    print(f"OC3-Hywind, three lines, fairleads surging 5 m / 10 s (ramp 10 s), {plan.duration:g} s "
          f"simulated; extremes of the fairlead tension over t in [{plan.window[0]:g}, "
          f"{plan.window[1]:g}] s.\nerror: largest relative difference of the 6 extremes "
          "(max and min per line) from the code's own reference; err(max): of the 3 maxima "
          "alone.\nwall: moorline = simulate (statics apart); MoorDyn = Create + Init (initial "
          f"condition) + stepping loop. Chain BA = {plan.ba:g}"
          + (" (damping ratio of each segment's axial mode)." if plan.ba < 0 else " N s."))
    if moordyn is None and not args.no_moordyn:
        print("moordyn is not importable: moorline numbers only (pip install -e .[compare])")
    warm_up()

    ml_ref, ml_checks, ml_runs = moorline_part(plan)
    if ml_checks:
        print("\nmoorline convergence of the reference (should be well below 1 %):")
        for run, what in zip(ml_checks, ("dt halved", "segments doubled"), strict=False):
            print(f"  {what:<17}: extremes change by {pct(error(run, ml_ref))} "
                  f"(maxima alone {pct(error_max_only(run, ml_ref))})"
                  + ("" if run.ok else f"  FAILED: {run.message}"))
    print(f"moorline segment doublings at dt {ml_ref.dt:g} s:")
    doubling_report([r for r in ml_runs + ml_checks if r.dt == ml_ref.dt])

    md_ref = None
    md_runs: list[Run] = []
    if moordyn is not None:
        md_ref, md_checks, md_runs = moordyn_part(plan, args.refresh)
        print("\nMoorDyn convergence evidence:")
        doubling_report(md_runs)
        for run in md_checks:
            print(f"  dt halved at {run.segments} segments: extremes change by "
                  f"{pct(error(run, md_ref))} (maxima alone {pct(error_max_only(run, md_ref))})"
                  + ("" if run.ok else f"  FAILED: {run.message}"))

    shown = [ml_ref] + ([md_ref] if md_ref is not None else [])
    print_extremes("Converged extremes:", shown)
    if md_ref is not None:
        diff = (md_ref.extremes - ml_ref.extremes) / ml_ref.extremes
        print("MoorDyn vs moorline: " + ", ".join(
            f"line{k + 1} max {100 * diff[k, 0]:+.2f} % min {100 * diff[k, 1]:+.2f} %"
            for k in range(diff.shape[0])))
        print(f"largest |difference| {pct(float(np.abs(diff).max()), 2)} "
              f"(maxima alone {pct(float(np.abs(diff[:, 0]).max()), 2)})")
        same_mesh(ml_runs + ml_checks, md_runs)

    print("\n== moorline: time per step, one OC3 line, 1 m surge (no snaps), 20 s at dt 0.05 s ==",
          flush=True)
    scale = scaling(plan.ba)
    for r in scale:
        c = r.get("counters", {})
        note = ""
        if r["ok"]:
            per_it = 1e3 * r["wall"] / max(c.get("iterations", 1), 1)
            note = (f"{c.get('iterations', 0)} it ({per_it:.3f} ms/it), "
                    f"{c.get('factorizations', 0)} fact, {c.get('step_cuts', 0)} cuts")
        if r["failed_at"] is not None:
            note += (f"; its 20 s run FAILED at t = {r['failed_at']:.4g} s "
                     f"({r['message']})")
        print(f"  {r['elements']:5d} elements: {1e3 * r['per_step']:8.3f} ms/step over "
              f"{r['steps']} steps ({r['duration']:g} s)  {note}")
    growth = scale[2]["per_step"] / scale[1]["per_step"]

    # ---- summary
    ml_best = cheapest(ml_runs, ml_ref)
    md_best = cheapest(md_runs, md_ref) if md_ref is not None else None
    ml_best_max = cheapest(ml_runs, ml_ref, error_max_only)
    md_best_max = cheapest(md_runs, md_ref, error_max_only) if md_ref is not None else None
    ml_20 = next((r for r in ml_runs if (r.segments, r.dt) == (20, 0.05)), None)
    md_20 = next((r for r in md_runs if r.segments == 20), None)
    print("\n" + "=" * 100)
    print(f"SUMMARY ({'quick' if args.quick else 'full'}; {plan.duration:g} s simulated; "
          f"bench took {time.perf_counter() - start:.0f} s)")
    print(f"{'':<28}{'moorline':<34}{'MoorDyn':<34}")

    def cell(run: Run | None, ref: Run | None, metric=error) -> str:
        if run is None:
            return "none"
        if not run.ok:
            return f"{run.label}: failed"
        if ref is not None and run is ref:
            return f"{run.label} = reference only"
        return f"{run.label}, err {pct(metric(run, ref), 2) if ref else 'n/a'}"

    def times(run: Run | None) -> str:
        if run is None or not run.ok:
            return ""
        return f"{run.wall:.2f} s ({run.prep:.2f}+{run.loop:.2f})"

    def ratios(a: Run | None, b: Run | None) -> str:
        if a is None or b is None or not (a.ok and b.ok):
            return ""
        return (f"moorline/MoorDyn: {a.wall / b.wall:.3g} (as defined), stepping alone "
                f"{a.loop / b.loop:.3g}, with statics/IC {a.total / b.total:.3g}")

    print(f"{'reference':<28}{cell(ml_ref, None):<34}{cell(md_ref, None):<34}")
    print(f"{'cheapest within 1 %':<28}{cell(ml_best, ml_ref):<34}{cell(md_best, md_ref):<34}")
    print(f"{'  wall (statics/IC+step)':<28}{times(ml_best):<34}{times(md_best):<34}")
    print(f"{'  ratio':<28}{ratios(ml_best, md_best)}")
    print(f"{'(maxima alone within 1 %)':<28}{cell(ml_best_max, ml_ref, error_max_only):<34}"
          f"{cell(md_best_max, md_ref, error_max_only):<34}")
    print(f"{'  wall (statics/IC+step)':<28}{times(ml_best_max):<34}{times(md_best_max):<34}")
    print(f"{'  ratio':<28}{ratios(ml_best_max, md_best_max)}")
    print(f"{'20 segments, plain':<28}{cell(ml_20, ml_ref):<34}{cell(md_20, md_ref):<34}")
    print(f"{'  wall (statics/IC+step)':<28}{times(ml_20):<34}{times(md_20):<34}")
    print(f"{'  ratio':<28}{ratios(ml_20, md_20)}")
    if md_ref is not None:
        diff = np.abs(md_ref.extremes - ml_ref.extremes) / ml_ref.extremes
        print(f"{'references differ by':<28}up to {pct(float(diff.max()), 2)} "
              f"(maxima {pct(float(diff[:, 0].max()), 2)})")
    per = ", ".join(f"{r['elements']}: {1e3 * r['per_step']:.3f} ms" for r in scale)
    if scale[0]["duration"] < 20.0:
        per += f" (first {scale[0]['duration']:g} s: a 20 s run failed)"
    print(f"{'time per step':<28}{per}; 1000/100 = {growth:.2f} (required < 12)")
    print("=" * 100)


if __name__ == "__main__":
    main()
