"""Run MoorDyn-C (through its ``moordyn`` Python package) on a moorline :class:`System`.

The system is written as a MoorDyn v2 deck (:func:`moorline.io.moordyn.write_moordyn`) in a
temporary directory; its prescribed points become MoorDyn ``Coupled`` points and are driven
along their :attr:`Point.motion` through the coupling interface:

- ``moordyn.Create(deck)``, ``moordyn.Init(md, x0, 0)``: MoorDyn's own initial condition (a
  stationary solve, tightened through ``threshIC`` so both codes start from equilibrium). The
  velocity passed to ``Init`` must be zero: MoorDyn moves coupled points with it during the
  initial-condition solve, which then ends far from the static state,
- ``moordyn.Step(md, x, v, t, h)`` once per coupling interval ``h``: MoorDyn sub-steps with its
  ``dtM`` and moves each coupled point linearly, ``x + v (t' - t)``, within the interval (as
  when coupled to a floating-body code); it returns the forces on the coupled points,
- ``moordyn.GetLine``, ``GetLineN``, ``GetLineNodeForce`` (net force on an end node = force
  the line exerts on its end point, the same quantity as moorline's
  :meth:`~moorline.results.StaticResult.end_force`), ``GetLineFairTen`` (MoorDyn's own
  ``FairTen``: the top segment's tension, without the end node's weight),
  ``GetPoint``/``GetPointForce``, ``moordyn.Close``,
- ``moordyn.SetLogFile``/``SetLogLevel`` around ``Init``: MoorDyn's log says how far its
  initial-condition solve got (``ic_residual``), which the API does not.

MoorDyn prints a banner on the C ``stdout`` when it is created; ``quiet=True`` sends it to
``/dev/null`` while ``Create`` and ``Init`` run.
"""

from __future__ import annotations

import contextlib
import logging
import math
import os
import re
import sys
import tempfile
import time
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import CaseError
from ..io.moordyn import unsupported_features, write_moordyn
from ..model import Motion, System
from ..solvers.excitation import motion_value

FloatArray = NDArray[np.float64]
Kinematics = Callable[[float], tuple[Any, Any]]
logger = logging.getLogger(__name__)


@dataclass
class _Coupled:
    """A coupled (prescribed) point: name, base position and how it moves."""

    name: str
    base: FloatArray
    motion: Motion | Kinematics | None

    def state(self, t: float) -> tuple[FloatArray, FloatArray]:
        if self.motion is None:
            return self.base, np.zeros(3)
        if isinstance(self.motion, Motion):
            d, v, _ = motion_value(self.motion, t)
            return self.base + d, v
        x, v = self.motion(t)
        return np.asarray(x, dtype=float), np.asarray(v, dtype=float)


def _import_moordyn() -> Any:
    try:
        import moordyn
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise ImportError("the MoorDyn comparison needs the 'moordyn' package "
                          "(pip install moorline[compare])") from exc
    return moordyn


@contextlib.contextmanager
def silenced_fd(fd: int, active: bool = True) -> Iterator[None]:
    """Send a file descriptor of the process (1: stdout, 2: stderr) to /dev/null while the
    block runs (MoorDyn writes banners and errors there from C++)."""
    stream = {1: sys.stdout, 2: sys.stderr}.get(fd)
    if not active:
        yield
        return
    try:
        if stream is not None:
            stream.flush()
        saved = os.dup(fd)
    except (OSError, ValueError, AttributeError):
        yield
        return
    devnull = os.open(os.devnull, os.O_WRONLY)
    try:
        os.dup2(devnull, fd)
        yield
    finally:
        os.dup2(saved, fd)
        os.close(saved)
        os.close(devnull)


def _coupled_points(system: System, prescribed: Mapping[str, Motion | Kinematics] | None
                    ) -> list[_Coupled]:
    prescribed = dict(prescribed or {})
    unknown = [n for n in prescribed
               if n not in system.points or system.points[n].kind != "prescribed"]
    if unknown:
        raise CaseError(f"prescribed motion given for {', '.join(unknown)}, which are not "
                        "prescribed points", file=system.source, field="points")
    return [_Coupled(p.name, np.asarray(p.position, dtype=float),
                     prescribed.get(p.name, p.motion))
            for p in system.points.values() if p.kind == "prescribed"]


def _check_system(system: System) -> None:
    errors, omissions = unsupported_features(system)
    dynamic = [o for o in omissions if o == "waves" or "force_history" in o]
    if errors or dynamic:
        raise CaseError("MoorDyn comparison cannot represent: " + "; ".join(errors + dynamic),
                        file=system.source)


def current_profile_rows(system: System) -> list[tuple[float, float, float]] | None:
    """The system's current as MoorDyn's steady profile rows ``(z, ux, uy)``, or None.

    A uniform current gives two rows (seabed and surface); a profile its own levels (MoorDyn
    interpolates linearly in ``z`` between rows, as moorline does)."""
    cur = system.environment.current
    if cur.speeds:
        return [(float(z), s * math.cos(math.radians(h)), s * math.sin(math.radians(h)))
                for z, s, h in zip(cur.z_levels, cur.speeds, cur.headings_deg, strict=True)]
    if not cur.speed:
        return None
    ux = cur.speed * math.cos(math.radians(cur.heading_deg))
    uy = cur.speed * math.sin(math.radians(cur.heading_deg))
    depth = system.environment.depth
    bottom = -depth if math.isfinite(depth) else -1.0e4
    return [(bottom, ux, uy), (0.0, ux, uy)]


def _write_current(system: System, folder: Path) -> dict[str, object]:
    """Write ``current_profile.txt`` next to the deck (MoorDyn option ``Currents 1``: a
    steady profile read from the deck's folder) and return the options that select it.
    MoorDyn applies the current after its initial-condition solve: the run starts from the
    still-water equilibrium with the current switched on at t = 0."""
    rows = current_profile_rows(system)
    if rows is None:
        return {}
    text = ["--- MoorDyn steady currents file (written by moorline) ---",
            "Tabulated water current components",
            "z (m), ux (m/s), uy (m/s), uz (m/s)"]
    text += [f"{z!r} {ux!r} {uy!r} 0.0" for z, ux, uy in sorted(rows)]
    (folder / "current_profile.txt").write_text("\n".join(text) + "\n", encoding="utf-8")
    return {"WaveKin": 0, "Currents": 1}


def _steps(duration: float, step: float, what: str) -> int:
    n = int(round(duration / step))
    if n < 1 or abs(n * step - duration) > 1e-6 * step:
        raise ValueError(f"{what} ({duration:g}) must be a positive multiple of the coupling "
                         f"interval ({step:g})")
    return n


class _Recorder:
    """Collects end forces of every line and the forces on the coupled points."""

    def __init__(self, md: Any, moordyn: Any, system: System, coupled: list[_Coupled],
                 capacity: int) -> None:
        self._md = moordyn
        self.lines = [moordyn.GetLine(md, i) for i in range(1, len(system.lines) + 1)]
        self.n_seg = [moordyn.GetLineN(line) for line in self.lines]
        ids = {name: i for i, name in enumerate(system.points, start=1)}
        self.points = [moordyn.GetPoint(md, ids[c.name]) for c in coupled]
        self.time = np.full(capacity, np.nan)
        self.end_force = np.full((capacity, len(self.lines), 2, 3), np.nan)
        self.fair_ten = np.full((capacity, len(self.lines)), np.nan)
        self.point_force = np.full((capacity, len(coupled), 3), np.nan)
        self.bodies = [moordyn.GetBody(md, i) for i in range(1, len(system.bodies) + 1)]
        self.body_state = np.full((capacity, len(self.bodies), 6), np.nan)
        self.count = 0

    def record(self, t: float, point_forces: Any | None = None) -> bool:
        """Store one sample; False when a value is not finite."""
        md, k = self._md, self.count
        self.time[k] = t
        for j, (line, n) in enumerate(zip(self.lines, self.n_seg, strict=True)):
            self.end_force[k, j, 0] = md.GetLineNodeForce(line, 0)
            self.end_force[k, j, 1] = md.GetLineNodeForce(line, n)
            self.fair_ten[k, j] = md.GetLineFairTen(line)
        if point_forces is None:
            point_forces = [c for p in self.points for c in md.GetPointForce(p)]
        self.point_force[k] = np.asarray(point_forces, dtype=float).reshape(-1, 3)
        for j, body in enumerate(self.bodies):
            self.body_state[k, j] = md.GetBodyState(body)[0]
        self.count += 1
        return bool(np.isfinite(self.end_force[k]).all() and np.isfinite(self.point_force[k]).all())


def run_moordyn(system: System, duration: float, dt: float, output_every: float,
                prescribed: Mapping[str, Motion | Kinematics] | None = None, *,
                coupling_dt: float | None = None, tmax_ic: float = 1000.0,
                thresh_ic: float = 1.0e-5, time_scheme: str | None = None,
                extra_options: Mapping[str, object] | None = None,
                workdir: str | Path | None = None, quiet: bool = True) -> dict[str, Any]:
    """Simulate ``system`` with MoorDyn from its static equilibrium.

    Parameters
    ----------
    system
        The problem (fixed, free and prescribed points, lines; a steady current, no waves).
        The current is written as MoorDyn's steady profile (:func:`current_profile_rows`);
        MoorDyn switches it on at t = 0 after its still-water initial condition, so compare
        with a moorline run started from the still-water statics with no current ramp.
    duration
        Simulated time [s]; a multiple of the coupling interval.
    dt
        MoorDyn's internal time step ``dtM`` [s] (explicit ``RK2`` unless ``time_scheme``).
    output_every
        Sampling interval of the returned histories [s]; a multiple of the coupling interval.
    prescribed
        Optional motions overriding :attr:`Point.motion` of named prescribed points: a
        :class:`~moorline.model.Motion` (displacement added to the point's position, evaluated
        with :func:`moorline.solvers.excitation.motion_value`) or a callable ``t -> (position,
        velocity)`` (absolute). Points with neither stay still.
    coupling_dt
        Interval between ``moordyn.Step`` calls [s]; default ``output_every``. Within it MoorDyn
        moves the coupled points with constant velocity (error ``a h^2 / 2``: 2.5 mm for 5 m at
        10 s and ``h = 0.05``). ``coupling_dt = dt`` gives exact kinematics every step at the
        price of one Python call per step (about 10 us). Make it a multiple of ``dt``: MoorDyn
        ends an interval that is not with one shorter step, and near the stability limit
        that alone made an 80-segment OC3 run blow up at 11 s.
    tmax_ic, thresh_ic
        MoorDyn initial-condition options (see :func:`~moorline.io.moordyn.write_moordyn`).
    time_scheme
        MoorDyn ``tScheme`` (default ``RK2``).
    extra_options
        More MoorDyn option rows (e.g. ``FricDamp``), see
        :func:`~moorline.io.moordyn.write_moordyn`.
    workdir
        Directory to write the deck (and MoorDyn's outputs) into and keep; default: a
        temporary directory, removed afterwards.
    quiet
        Silence MoorDyn's console output.

    Returns
    -------
    dict
        ``time`` (n_t,); ``end_force`` (n_t, n_lines, 2, 3): force each line exerts on its end
        points A and B; ``fairlead_tension`` (n_t, n_lines): ``|end_force[..., 1, :]|`` (as
        moorline's ``fairlead_tension``); ``fairlead_tension_segment`` (n_t, n_lines):
        MoorDyn's ``FairTen`` (top segment); ``point_force``: ``{name: (n_t, 3)}`` force on
        each coupled point; ``body_state``: ``{name: (n_t, 6)}`` MoorDyn's body position and
        orientation (its Euler angles [rad]); ``lines``, ``coupled_points``: names in order;
        ``success``,
        ``message``; ``wall_time_loop`` (the stepping loop only), ``wall_time_init``
        (``Create`` + ``Init``: reading and the static solve), ``wall_time_total`` (deck
        writing to ``Close``); ``dtM``, ``coupling_dt``, ``n_steps`` (MoorDyn steps),
        ``deck`` (path, or None when the directory was temporary); ``ic_time``,
        ``ic_residual``: pseudo-time and largest residual node acceleration [m/s^2] of
        MoorDyn's initial-condition solve, from its log (a warning is logged when the
        residual exceeds ``10 * thresh_ic``: MoorDyn's stationary solver stops on stagnation
        too, e.g. at 1.3 m/s^2 for a system with a free buoy).
    """
    moordyn = _import_moordyn()
    _check_system(system)
    coupling_dt = float(output_every if coupling_dt is None else coupling_dt)
    n_couple = _steps(duration, coupling_dt, "duration")
    stride = _steps(output_every, coupling_dt, "output_every")
    coupled = _coupled_points(system, prescribed)
    ratio = coupling_dt / dt
    if ratio > 1 and abs(ratio - round(ratio)) > 1e-6 * ratio:
        logger.warning("coupling interval %g s is not a multiple of dtM = %g s: MoorDyn ends "
                       "each interval with a shorter step, which can destabilize it near its "
                       "stability limit", coupling_dt, dt)
    start = time.perf_counter()
    with contextlib.ExitStack() as stack:
        folder = Path(workdir) if workdir is not None else Path(
            stack.enter_context(tempfile.TemporaryDirectory(prefix="moorline-moordyn-")))
        folder.mkdir(parents=True, exist_ok=True)
        deck = write_moordyn(system, folder / "moorline.dat", dt, tmax_ic=tmax_ic,
                             thresh_ic=thresh_ic, time_scheme=time_scheme,
                             extra_options={**_write_current(system, folder),
                                            **dict(extra_options or {})})
        result = _simulate(moordyn, system, deck, coupled, n_couple, stride, coupling_dt, quiet)
    if result["ic_residual"] > 10.0 * thresh_ic:
        logger.warning("MoorDyn's initial condition did not converge: residual %.3g m/s^2 "
                       "after %.4g s (threshIC %.3g); its run does not start from equilibrium",
                       result["ic_residual"], result["ic_time"], thresh_ic)
    result.update(dtM=float(dt), coupling_dt=coupling_dt,
                  n_steps=n_couple * max(1, math.ceil(coupling_dt / dt - 1e-9)),
                  wall_time_total=time.perf_counter() - start,
                  deck=str(deck) if workdir is not None else None)
    return result


def _simulate(moordyn: Any, system: System, deck: Path, coupled: list[_Coupled],
              n_couple: int, stride: int, h: float, quiet: bool) -> dict[str, Any]:
    start = time.perf_counter()
    with silenced_fd(1, quiet):
        md = moordyn.Create(str(deck))
        try:
            if quiet:
                moordyn.SetVerbosity(md, moordyn.LEVEL_ERR)
            expected = 3 * len(coupled)
            if moordyn.NCoupledDOF(md) != expected:
                raise RuntimeError(f"MoorDyn expects {moordyn.NCoupledDOF(md)} coupled degrees "
                                   f"of freedom, moorline has {expected}")
            # zero velocity: MoorDyn moves coupled points with it during its IC solve
            x0, _ = _coupled_state(coupled, 0.0)
            log = deck.with_suffix(".ic.log")
            moordyn.SetLogFile(md, str(log))
            moordyn.SetLogLevel(md, moordyn.LEVEL_MSG)
            status = moordyn.Init(md, x0, [0.0] * len(x0))
            moordyn.SetLogLevel(md, moordyn.LEVEL_ERR)
        except BaseException:
            moordyn.Close(md)
            raise
    try:
        if status:
            raise RuntimeError(f"moordyn.Init failed with error code {status}")
        init_time = time.perf_counter() - start
        recorder = _Recorder(md, moordyn, system, coupled, n_couple // stride + 1)
        ok = recorder.record(0.0)
        message, loop_time = "completed", 0.0
        if not ok:
            message = "non-finite forces after the initial condition"
        else:
            message, loop_time = _loop(moordyn, md, recorder, coupled, n_couple, stride, h)
    finally:
        moordyn.Close(md)
    result = _collect(system, coupled, recorder, message, init_time, loop_time)
    result.update(_ic_report(log))
    return result


def _ic_report(log: Path) -> dict[str, float]:
    """MoorDyn's own account of its initial-condition solve, read from its log file:
    ``ic_time`` (pseudo-time spent) and ``ic_residual`` (largest node acceleration left,
    m/s^2); NaN when the log does not say."""
    try:
        text = log.read_text(errors="replace")
    except OSError:
        text = ""
    found = re.findall(r"Remaining error after\s+(\S+)\s+s\s*=\s*(\S+)", text)
    if not found:
        return {"ic_time": math.nan, "ic_residual": math.nan}
    return {"ic_time": float(found[-1][0]), "ic_residual": float(found[-1][1])}


def _coupled_state(coupled: list[_Coupled], t: float) -> tuple[list[float], list[float]]:
    x, v = [], []
    for c in coupled:
        xi, vi = c.state(t)
        x.extend(float(a) for a in xi)
        v.extend(float(a) for a in vi)
    return x, v


def _loop(moordyn: Any, md: Any, recorder: _Recorder, coupled: list[_Coupled], n_couple: int,
          stride: int, h: float, chunk: int = 2048) -> tuple[str, float]:
    """Step MoorDyn; kinematics are evaluated in chunks outside the timed region."""
    loop_time = 0.0
    for first in range(0, n_couple, chunk):
        states = [_coupled_state(coupled, i * h) for i in range(first, min(first + chunk,
                                                                            n_couple))]
        tic = time.perf_counter()
        for offset, (x, v) in enumerate(states):
            i = first + offset
            try:
                forces = moordyn.Step(md, x, v, i * h, h)
            except Exception as exc:  # MoorDyn raises on NaN / integration failure
                loop_time += time.perf_counter() - tic
                return f"MoorDyn failed at t = {i * h:.6g} s: {exc}", loop_time
            if (i + 1) % stride == 0 and not recorder.record((i + 1) * h, forces):
                loop_time += time.perf_counter() - tic
                return f"non-finite forces at t = {(i + 1) * h:.6g} s", loop_time
        loop_time += time.perf_counter() - tic
    return "completed", loop_time


def _collect(system: System, coupled: list[_Coupled], recorder: _Recorder, message: str,
             init_time: float, loop_time: float) -> dict[str, Any]:
    k = recorder.count
    end_force = recorder.end_force[:k]
    return {
        "time": recorder.time[:k],
        "end_force": end_force,
        "fairlead_tension": np.linalg.norm(end_force[:, :, 1], axis=-1),
        "fairlead_tension_segment": recorder.fair_ten[:k],
        "point_force": {c.name: recorder.point_force[:k, i] for i, c in enumerate(coupled)},
        "body_state": {name: recorder.body_state[:k, i]
                       for i, name in enumerate(system.bodies)},
        "lines": list(system.lines),
        "coupled_points": [c.name for c in coupled],
        "success": message == "completed",
        "message": message,
        "wall_time_init": init_time,
        "wall_time_loop": loop_time,
    }


def _axial_time(system: System) -> float:
    """Shortest axial wave transit time of a segment, ``min L_seg / sqrt(EA / m)`` [s]."""
    times = []
    for line in system.lines.values():
        lt = system.line_types[line.line_type]
        times.append(line.length / line.segments / math.sqrt(lt.EA / lt.mass_per_length))
    return min(times)


def largest_stable_dt(system: System, duration: float = 20.0, *, growth_limit: float = 10.0,
                      rel_tol: float = 0.05, dt_start: float | None = None,
                      dt_min: float = 1.0e-6, dt_max: float = 1.0,
                      thresh_ic: float = 1.0e-4, **run_options: Any) -> dict[str, Any]:
    """Largest MoorDyn time step ``dtM`` that runs ``system`` without blowing up.

    Criterion: a trial ``dtM`` is *stable* when :func:`run_moordyn` completes ``duration``
    seconds of the system's prescribed motion without MoorDyn raising an error, every sampled
    end force is finite, and the largest sampled fairlead tension stays below ``growth_limit``
    times the largest static (t = 0, after MoorDyn's initial condition) fairlead tension.
    Samples are taken at every coupling interval, ``h = dtM * max(1, floor(0.05 / dtM))``.

    Search: from ``dt_start`` (default: the shortest axial wave transit time of a segment,
    ``L_seg / sqrt(EA / m)``) the step is doubled until unstable or halved until stable, then
    the bracket is bisected geometrically until ``unstable / stable <= 1 + rel_tol``. Stability
    of an explicit scheme is not strictly monotone in ``dt``; the result is the largest step
    seen to be stable next to one seen to be unstable.

    Parameters
    ----------
    system
        The problem, with the motions to apply.
    duration
        Length of each trial run [s].
    growth_limit
        Blow-up threshold on the fairlead tension, relative to its static value.
    rel_tol
        Relative width of the final bracket.
    dt_start, dt_min, dt_max
        First trial and search limits [s].
    thresh_ic
        ``threshIC`` of the trials (the initial condition only sets the reference tension).
    **run_options
        Passed to :func:`run_moordyn` (``time_scheme``, ``prescribed``, ...).

    Returns
    -------
    dict
        ``dt`` (largest stable step), ``unstable_dt`` (smallest unstable one), ``trials``
        (list of ``{"dt", "stable", "peak_ratio", "message"}``), ``criterion`` (text).
    """
    trials: list[dict[str, Any]] = []

    def stable(dt: float) -> bool:
        k = max(1, math.floor(0.05 / dt))
        h = dt * k
        span = h * max(1, math.ceil(duration / h - 1e-9))
        run = run_moordyn(system, span, dt, h, coupling_dt=h, thresh_ic=thresh_ic,
                          **run_options)
        tension = run["fairlead_tension"]
        static = float(np.nanmax(tension[0])) if len(tension) else float("nan")
        peak = float(np.nanmax(tension)) / static if static > 0 else float("inf")
        ok = bool(run["success"] and np.isfinite(peak) and peak <= growth_limit)
        trials.append({"dt": dt, "stable": ok, "peak_ratio": peak, "message": run["message"]})
        logger.info("dtM = %.4g s: %s (peak/static %.3g)", dt, "stable" if ok else "unstable",
                    peak)
        return ok

    lo, hi = _bracket(stable, dt_start or _axial_time(system), dt_min, dt_max)
    while hi is not None and lo is not None and hi / lo > 1.0 + rel_tol:
        mid = math.sqrt(lo * hi)
        lo, hi = (mid, hi) if stable(mid) else (lo, mid)
    return {"dt": lo, "unstable_dt": hi, "trials": trials,
            "criterion": (f"completes {duration:g} s, finite forces, fairlead tension <= "
                          f"{growth_limit:g} x static")}


def _bracket(stable: Callable[[float], bool], dt: float, dt_min: float, dt_max: float
             ) -> tuple[float | None, float | None]:
    """A stable and an unstable step a factor of 2 apart (None where a limit was reached)."""
    dt = min(max(dt, dt_min), dt_max)
    if stable(dt):
        while dt * 2 <= dt_max:
            if not stable(dt * 2):
                return dt, dt * 2
            dt *= 2
        return dt, None
    while dt / 2 >= dt_min:
        if stable(dt / 2):
            return dt / 2, dt
        dt /= 2
    return None, dt
