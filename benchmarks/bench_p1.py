"""P1: the OC3-Hywind three-line system in 300 s of fairlead surge, whole process of three codes.

The case (issue 16): the three OC3 lines (:func:`moorline.verification.oc3_system.oc3_three_lines`),
all fairleads surging 5 m at 10 s (ramped in over 10 s by ``(1 - cos(pi t / 10)) / 2``), 300 s
simulated, a fixed axial damping of the chain ``BA = 6.2358e6 N s`` (the same in every code and
for every mesh, so that refining converges to one system), seabed ``kBot = 3e6 Pa/m``,
``cBot = 3e5 Pa s/m``, no friction. Every code writes the fairlead tension of each line every
0.05 s (CableDyn at every step, sampled here every 0.05 s); the accuracy metric is the set of
six extremes, the largest and the smallest fairlead tension of each line over t in [200, 300] s.
A run's *error* is the largest relative difference of its six extremes from those of the same
code's reference run (its finest setting).

Whole process (a subprocess, from start-up to its output on disk):

* moorline: ``python -m moorline run CASE --no-plots -q`` of a case file (statics, dynamics,
  results.nc, summary and report);
* CableDyn: its stand-alone driver ``cabledyn/bin/cabledyn DECK ROOT`` on a deck and a
  ``motionFile`` (the fairlead positions, velocities and accelerations at every ``dtM``);
* MoorDyn: ``python benchmarks/moordyn_drive.py`` (the ``moordyn`` module: ``Create``, its
  initial condition ``Init``, ``Step`` every 0.05 s with MoorDyn sub-stepping at ``dtM``, a text
  output).

The input files are written before the clock starts. The stepping alone, in CPU seconds:
moorline's ``simulate`` in this process (compiled kernels loaded, statics apart); MoorDyn's
loop of ``Step`` calls, timed by the driver script; CableDyn prints no timing of its own, so
its stepping alone is its whole process less the same deck run for two steps (start-up,
reading, statics).

Settings: each code's cheapest setting within 1 % of its own reference, found by the
documented search :func:`search`: the reference (:data:`REFERENCE`: moorline 160 segments at
dt 0.005 s, CableDyn 160 at 0.0125 s, MoorDyn 80 at its stable step, its 160-segment run being
over 10 CPU minutes), its change when the segments are halved and when the step is doubled
(printed: how converged the reference is), then the :data:`CANDIDATES` in increasing order of
nominal cost (segments / step) until one is within 1 %. The result is cached in
``benchmarks/.cache/p1_settings.json`` keyed by the code's version (``bench_all.py --search``
or ``python benchmarks/bench_p1.py [codes]`` searches again: about 15 CPU minutes in all). When
no candidate is within 1 %, the code is timed at its reference.
"""

from __future__ import annotations

import json
import math
import shutil
import sys
import tempfile
from dataclasses import asdict, dataclass, field
from importlib.metadata import PackageNotFoundError, version
from pathlib import Path
from typing import Any

import numpy as np
from bench_common import ROOT, best_process, moorline_command, python_env

DURATION = 300.0
WINDOW = (200.0, 300.0)
SAMPLE = 0.05  # output interval of every code [s]; MoorDyn's coupling interval
BA = 6.2358e6  # fixed axial damping of the chain [N s]
TOLERANCE = 0.01
CACHE = Path(__file__).resolve().parent / ".cache" / "p1_settings.json"
CASE_TEMPLATE = ROOT / "cases" / "oc3_dynamics.yaml"
DRIVER_SCRIPT = Path(__file__).resolve().parent / "moordyn_drive.py"

# The search: (segments, dt) candidates per code, and each code's reference (its finest run).
# MoorDyn is explicit: its step is set by the mesh (stable_moordyn_dt), so only the segments vary.
CANDIDATES: dict[str, list[tuple[int, float]]] = {
    "moorline": [(n, dt) for n in (10, 20, 40, 80) for dt in (0.1, 0.05, 0.025, 0.0125)],
    "CableDyn": [(n, dt) for n in (10, 20, 40, 80) for dt in (0.1, 0.05, 0.025)],
    "MoorDyn": [(n, math.nan) for n in (10, 20, 40)],
}
# MoorDyn's 160-segment run (a 0.1 ms step) takes over 10 CPU minutes: its reference is 80.
REFERENCE: dict[str, tuple[int, float]] = {
    "moorline": (160, 0.005), "CableDyn": (160, 0.0125), "MoorDyn": (80, math.nan)}


@dataclass
class Run:
    """One whole-process run of a code: setting, times, extremes."""

    code: str
    segments: int
    dt: float
    ok: bool = False
    message: str = ""
    wall: float = math.nan
    cpu: float = math.nan
    extremes: list[list[float]] | None = None  # (3 lines, max/min) [N]
    stepping: float = math.nan  # the stepping alone [s] (see the module docstring)
    extra: dict[str, Any] = field(default_factory=dict)

    @property
    def label(self) -> str:
        return f"{self.segments} seg, dt {self.dt:.4g} s"


def code_version(code: str) -> str:
    """Version of a code's package (the cache key)."""
    name = {"moorline": "moorline", "CableDyn": "cabledyn", "MoorDyn": "moordyn"}[code]
    if code == "moorline":
        sys.path.insert(0, str(ROOT / "src"))
        import moorline

        return moorline.__version__
    try:
        return version(name)
    except PackageNotFoundError:
        return "missing"


def available(code: str) -> bool:
    """Whether a code can be run here."""
    if code == "CableDyn":
        return cabledyn_binary() is not None
    if code == "MoorDyn":
        try:
            import moordyn  # noqa: F401
        except ImportError:
            return False
    return True


def cabledyn_binary() -> Path | None:
    """The CableDyn stand-alone driver inside the ``cabledyn`` package (or on PATH)."""
    try:
        import cabledyn
    except ImportError:
        found = shutil.which("cabledyn")
        return Path(found) if found else None
    path = Path(cabledyn.__file__).parent / "bin" / "cabledyn"
    return path if path.is_file() else None


def stable_moordyn_dt(segments: int) -> float:
    """MoorDyn's step for an ``segments``-segment OC3 line: 0.05 s / n, n the smallest whole
    number that keeps the explicit scheme within half its two stability limits, the axial wave
    (``L_seg / sqrt(EA / m)``) and the axial damping (``m L_seg^2 / (2 BA)``: the largest
    eigenvalue of the segment dampers against the node masses is ``4 BA / (m L_seg^2)``).
    A run that still blows up is repeated at half the step (:func:`run_code`)."""
    from moorline.verification.oc3_line import EA, LENGTH, MASS

    seg = LENGTH / segments
    limit = 0.5 * min(seg / math.sqrt(EA / MASS), MASS * seg * seg / (2.0 * BA))
    return SAMPLE / math.ceil(SAMPLE / limit - 1e-9)


# ---------------------------------------------------------------------------------------------
# inputs


def system(segments: int):
    """The moorline system of the case."""
    from moorline.verification.oc3_system import oc3_three_lines

    return oc3_three_lines(segments, BA=BA)


def motion_table(segments: int, step: float, duration: float,
                 system_=None) -> dict[str, np.ndarray]:
    """Positions, velocities, accelerations of the fairleads at every ``step``:
    ``t`` (n,), ``x``, ``v``, ``a`` (n, 3 points x 3). ``system_``: another system than the
    case's (:func:`system`; e.g. one line of it, or other coefficients)."""
    from moorline.solvers.excitation import motion_value

    sys_ = system(segments) if system_ is None else system_
    fair = [p for p in sys_.points.values() if p.kind == "prescribed"]
    t = np.arange(round(duration / step) + 1) * step
    x = np.empty((len(t), 3 * len(fair)))
    v, a = np.empty_like(x), np.empty_like(x)
    for j, p in enumerate(fair):
        for k, tk in enumerate(t):
            d, dv, da = motion_value(p.motion, float(tk))
            x[k, 3 * j:3 * j + 3] = np.asarray(p.position) + d
            v[k, 3 * j:3 * j + 3], a[k, 3 * j:3 * j + 3] = dv, da
    return {"t": t, "x": x, "v": v, "a": a}


def write_moorline(folder: Path, segments: int, dt: float, duration: float) -> Path:
    """``cases/oc3_dynamics.yaml`` at this mesh, step, duration, damping and output rate."""
    import yaml

    case = yaml.safe_load(CASE_TEMPLATE.read_text())
    case["name"] = "p1"
    case["line_types"]["chain"]["BA"] = BA
    for line in case["lines"].values():
        line["segments"] = segments
    case["analyses"] = [{"kind": "statics", "method": "newton"},
                        {"kind": "dynamics", "duration": duration, "dt": dt}]
    case["output"] = {"every": SAMPLE}
    path = folder / "p1.yaml"
    path.write_text(yaml.safe_dump(case, sort_keys=False))
    return path


def write_cabledyn(folder: Path, segments: int, dt: float, duration: float,
                   system_=None) -> Path:
    """A CableDyn deck of the case (cabledyn.DeckWriter) and its motion file (``system_``:
    as :func:`motion_table`)."""
    from cabledyn import DeckWriter

    from moorline.verification.oc3_line import DEPTH, DIAMETER, EA, LENGTH, MASS, RHO, G

    sys_ = system(segments) if system_ is None else system_
    lt = sys_.line_types["chain"]
    deck = DeckWriter(title="OC3-Hywind three lines, fairleads surging 5 m at 10 s (moorline P1)")
    deck.add_line_type("chain", diam=DIAMETER, mass=MASS, ea=EA, ba=lt.BA, ei=0.0, cdn=lt.Cd,
                       cdt=lt.Ct, can=lt.Ca, cat=lt.Cat)
    ids = {name: k for k, name in enumerate(sys_.points, start=1)}
    for name, p in sys_.points.items():
        deck.add_point(ids[name], "Coupled" if p.kind == "prescribed" else "Fixed", *p.position)
    for k, line in enumerate(sys_.lines.values(), start=1):
        deck.add_line(k, node_a=ids[line.end_b], node_b=ids[line.end_a])  # A: fairlead
        deck.add_section(line_id=k, line_type="chain", length=LENGTH, num_segs=segments)
    env = sys_.environment
    for value, key in ((G, "g"), (RHO, "rhoW"), (DEPTH, "WtrDpth"),
                       (env.seabed.stiffness, "kBot"), (env.seabed.damping, "cBot"),
                       (dt, "dtM"), (duration, "TMax"), ("motion.txt", "motionFile")):
        deck.set_option(value, key)
    for k in range(1, len(sys_.lines) + 1):
        deck.add_output(f"FairTen{k}")
    table = motion_table(segments, dt, duration, sys_)
    fair = [ids[n] for n, p in sys_.points.items() if p.kind == "prescribed"]
    rows = []
    for k, t in enumerate(table["t"]):
        for j, pid in enumerate(fair):
            sl = slice(3 * j, 3 * j + 3)
            values = np.concatenate([table["x"][k, sl], table["v"][k, sl], table["a"][k, sl]])
            rows.append(f"{t:.6f} {pid} " + " ".join(f"{v:.10e}" for v in values))
    (folder / "motion.txt").write_text(
        "# time id x y z vx vy vz ax ay az\n" + "\n".join(rows) + "\n")
    return deck.write(folder / "p1.dat")


def write_moordyn(folder: Path, segments: int, dt: float, duration: float,
                  system_=None, **options: Any) -> Path:
    """A MoorDyn deck of the case and the coupling table of the driver script (``system_``:
    as :func:`motion_table`; ``options``: more arguments of
    :func:`moorline.io.moordyn.write_moordyn`, e.g. ``time_scheme``)."""
    from moorline.io.moordyn import write_moordyn as write

    sys_ = system(segments) if system_ is None else system_
    table = motion_table(segments, SAMPLE, duration, sys_)
    np.savez(folder / "motion.npz", t=table["t"], x=table["x"], v=table["v"])
    return write(sys_, folder / "p1.dat", dt, **options)


# ---------------------------------------------------------------------------------------------
# runs


def extremes(t: np.ndarray, tension: np.ndarray, duration: float) -> list[list[float]]:
    """Max and min of each column over the last third of the run (:data:`WINDOW` for 300 s),
    on the 0.05 s grid (a history sampled more often, CableDyn's at every step, is taken at
    the samples nearest the grid)."""
    step = float(np.median(np.diff(t)))
    keep = (t >= 2.0 * duration / 3.0 - 1e-9) & (t <= duration + 1e-9)
    if step < 0.99 * SAMPLE:
        keep &= np.abs(t - SAMPLE * np.round(t / SAMPLE)) < 0.5 * step
    part = tension[keep]
    return np.column_stack([part.max(axis=0), part.min(axis=0)]).tolist()


def error(run: Run, reference: Run) -> float | None:
    """Largest relative difference of the six extremes from the reference's."""
    if run.extremes is None or reference.extremes is None:
        return None
    a, b = np.asarray(run.extremes), np.asarray(reference.extremes)
    return float(np.max(np.abs(a - b) / np.abs(b)))


def run_code(code: str, segments: int, dt: float, duration: float = DURATION,
             repeat: int = 1) -> Run:
    """Whole process of one code on the case (best of ``repeat``), with its extremes.

    MoorDyn with ``dt`` NaN: at :func:`stable_moordyn_dt`, halved (up to three times) while
    the run blows up."""
    if code == "MoorDyn" and not math.isfinite(dt):
        dt = stable_moordyn_dt(segments)
        for _ in range(3):
            run = _run_once(code, segments, dt, duration, repeat)
            if run.ok:
                return run
            dt /= 2.0
    return _run_once(code, segments, dt, duration, repeat)


def _run_once(code: str, segments: int, dt: float, duration: float, repeat: int) -> Run:
    run = Run(code, segments, dt)
    with tempfile.TemporaryDirectory(prefix=f"p1-{code}-") as tmp:
        folder = Path(tmp)
        if code == "moorline":
            case = write_moorline(folder, segments, dt, duration)
            args = moorline_command("run", str(case), "--out", str(folder / "out"),
                                    "--no-plots", "-q")
        elif code == "CableDyn":
            deck = write_cabledyn(folder, segments, dt, duration)
            args = [str(cabledyn_binary()), str(deck), str(folder / "p1")]
        else:
            deck = write_moordyn(folder, segments, dt, duration)
            args = [sys.executable, str(DRIVER_SCRIPT), str(deck), str(folder / "motion.npz"),
                    str(folder / "out.txt")]
        proc = best_process(args, repeat, cwd=folder, env=python_env())
        run.wall, run.cpu = proc.wall, proc.cpu
        if proc.returncode != 0:
            run.message = f"exit {proc.returncode}: " + (proc.stderr.strip().splitlines()
                                                         or [""])[-1][:200]
            return run
        t, tension = read_tension(code, folder)
        if code == "MoorDyn":
            run.stepping = float(proc.stderr.split("loop")[-1].split()[0]) if "loop" in \
                proc.stderr else math.nan
    if t[-1] < duration - 1e-6:
        run.message = f"output ends at t = {t[-1]:g} s"
        return run
    run.ok, run.message = True, "completed"
    run.extremes = extremes(t, tension, duration)
    return run


def read_tension(code: str, folder: Path) -> tuple[np.ndarray, np.ndarray]:
    """Time and fairlead tensions (n, 3) [N] from a finished run's output."""
    if code == "moorline":
        import netCDF4

        with netCDF4.Dataset(folder / "out" / "p1" / "results.nc") as ds:
            g = ds["dynamics"]
            return np.asarray(g["time"][:]), np.asarray(g["fairlead_tension"][:])
    if code == "CableDyn":
        from cabledyn import read_output

        out = read_output(folder / "p1.out")
        return (np.asarray(out.time, dtype=float),
                np.column_stack([np.asarray(out.column(f"FairTen{k}"), dtype=float)
                                 for k in (1, 2, 3)]))
    data = np.loadtxt(folder / "out.txt", ndmin=2)
    return data[:, 0], data[:, 1:]


# ---------------------------------------------------------------------------------------------
# settings: search and cache


def load_cache() -> dict[str, Any]:
    try:
        return json.loads(CACHE.read_text())
    except (OSError, ValueError):
        return {}


def save_cache(data: dict[str, Any]) -> None:
    CACHE.parent.mkdir(parents=True, exist_ok=True)
    ignore = CACHE.parent / ".gitignore"
    if not ignore.exists():
        ignore.write_text("*\n")
    CACHE.write_text(json.dumps(data, indent=2, sort_keys=True) + "\n")


def cache_key(code: str) -> str:
    return (f"{code}={code_version(code)}/oc3_three_lines/BA={BA:g}/T={DURATION:g}/"
            f"window={WINDOW[0]:g}-{WINDOW[1]:g}")


def search(code: str, log=print) -> dict[str, Any]:
    """The cheapest setting of ``code`` within 1 % of its reference (see the module docstring).

    The reference is run first, then the convergence of the reference is shown by the runs one
    step coarser in each direction (half the segments; twice the step), then the candidates in
    increasing order of ``segments / dt`` until one is within 1 %.
    """
    ref_n, ref_dt = REFERENCE[code]
    step = f"dt {ref_dt:g} s" if math.isfinite(ref_dt) else "dt at its stable step"
    log(f"  {code}: reference {ref_n} segments, {step} ...")
    done: dict[tuple[int, float], Run] = {}

    def run_code(code: str, n: int, dt: float) -> Run:  # each setting once
        key = (n, round(dt, 12) if math.isfinite(dt) else -1.0)
        if key not in done:
            done[key] = globals()["run_code"](code, n, dt)
        return done[key]

    ref = run_code(code, ref_n, ref_dt)
    log(f"    {ref.label}: {ref.message}, {ref.cpu:.1f} s CPU")
    if not ref.ok:
        return {"reference": asdict(ref), "found": None}
    checks = []
    coarser = [(ref_n // 2, ref_dt)] + ([(ref_n, 2 * ref_dt)] if math.isfinite(ref_dt) else [])
    for n, dt in coarser:
        run = run_code(code, n, dt)
        checks.append({"setting": [n, run.dt], "error": error(run, ref), "ok": run.ok})
        log(f"    convergence: {run.label}: {run.message}, change "
            f"{100 * (error(run, ref) or math.nan):.2f} %")
    tried, found = [], None
    for n, dt in sorted(CANDIDATES[code], key=lambda c: (c[0] / (c[1] if math.isfinite(c[1])
                                                                   else 1.0 / c[0] ** 2), c[0])):
        run = run_code(code, n, dt)
        err = error(run, ref)
        tried.append({"setting": [n, run.dt], "error": err, "ok": run.ok, "cpu": run.cpu,
                      "message": run.message})
        log(f"    candidate {run.label}: {run.message}, error "
            f"{'n/a' if err is None else f'{100 * err:.2f} %'}, {run.cpu:.1f} s CPU")
        if run.ok and err is not None and err <= TOLERANCE:
            found = {"segments": n, "dt": run.dt, "error": err}
            break
    return {"reference": asdict(ref), "checks": checks, "tried": tried, "found": found}


def settings(code: str, research: bool, log=print) -> dict[str, Any]:
    """The cached search result of ``code`` (searching when missing or ``research``)."""
    data = load_cache()
    key = cache_key(code)
    if research or key not in data:
        found = search(code, log)
        data = load_cache()  # another search may have written it meanwhile
        data[key] = found
        save_cache(data)
    return data[key]


if __name__ == "__main__":  # the search alone: python benchmarks/bench_p1.py [codes...]
    for name in sys.argv[1:] or ("moorline", "CableDyn", "MoorDyn"):
        if available(name):
            print(name, json.dumps(settings(name, True)["found"]), flush=True)
