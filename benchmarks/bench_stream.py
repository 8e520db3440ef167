"""Streaming benchmark: the cost of writing every step's record to NetCDF as the run goes.

The OC3 three-line dynamics (``cases/oc3_dynamics.yaml``: its mesh and time step, 300 s) is run
twice in the same process: without a writer and with a :class:`~moorline.io.stream.HistoryWriter`
receiving one record per time step (the densest output a run can ask for). Prints both wall
times and the streaming cost as a fraction of the stepping (target: at most 5 %), and the same
in CPU seconds of this process (less sensitive to other processes' load). The two runs are
alternated, each repeated and the fastest kept, so a busy machine inflates neither. Run with
``make bench``.
"""

from __future__ import annotations

import dataclasses
import tempfile
import time
from pathlib import Path

from moorline.io.case import load_case
from moorline.io.stream import HistoryWriter
from moorline.mesh import discretize
from moorline.solvers.dynamics import simulate
from moorline.solvers.statics import solve_statics

CASE = Path(__file__).resolve().parents[1] / "cases" / "oc3_dynamics.yaml"
REPEAT = 5


def measure(duration: float = 300.0, repeat: int = REPEAT) -> dict[str, float]:
    """Best-of-``repeat`` wall times of the run without and with the stream [s]: ``bare``,
    ``streamed``, ``open`` (creating the file), ``cost`` (fraction of the stepping); the
    same in CPU seconds: ``bare_cpu``, ``streamed_cpu``, ``cost_cpu``; ``records``, ``dt``,
    ``duration``; ``parts``: the writer's CPU seconds by part in one more run."""
    system = load_case(CASE)
    settings = system.first("dynamics")
    settings = dataclasses.replace(settings, duration=duration)
    static = solve_statics(system)
    mesh = discretize(system)
    simulate(system, settings, static, output_every=settings.dt)  # compile once

    def bare() -> tuple[float, float]:
        start, cpu = time.perf_counter(), time.process_time()
        simulate(system, settings, static, output_every=settings.dt)
        return time.perf_counter() - start, time.process_time() - cpu

    def streamed() -> tuple[float, float, float]:
        with tempfile.TemporaryDirectory() as tmp:
            start, cpu = time.perf_counter(), time.process_time()
            with HistoryWriter(Path(tmp) / "h.nc", mesh, {"case": system.name,
                                                           "units": system.units}) as writer:
                opened = time.perf_counter()
                simulate(system, settings, static, output_every=settings.dt, writer=writer)
            return (time.perf_counter() - start, time.process_time() - cpu,
                    opened - start)

    def breakdown() -> dict[str, float]:
        """CPU seconds of the writer's parts in one more streamed run (not in the minima):
        creating the file, the appends (buffering, and writing the first record at once),
        closing (the rest of the records, the envelope, the final attributes)."""
        parts = {"create": 0.0, "append": 0.0, "close": 0.0, "blocks": 0.0}

        class Timed:
            def __init__(self, writer: HistoryWriter) -> None:
                self.writer = writer

            def append_block(self, *args: object, **kwargs: object) -> None:
                cpu = time.process_time()
                self.writer.append_block(*args, **kwargs)
                parts["append"] += time.process_time() - cpu
                parts["blocks"] += 1

        with tempfile.TemporaryDirectory() as tmp:
            cpu = time.process_time()
            writer = HistoryWriter(Path(tmp) / "h.nc", mesh, {"case": system.name,
                                                              "units": system.units})
            parts["create"] = time.process_time() - cpu
            simulate(system, settings, static, output_every=settings.dt, writer=Timed(writer))
            cpu = time.process_time()
            writer.close()
            parts["close"] = time.process_time() - cpu
        return parts

    runs = [(bare(), streamed()) for _ in range(repeat)]  # alternated: same load on both
    t_bare = min(b[0] for b, _ in runs)
    c_bare = min(b[1] for b, _ in runs)
    t_stream = min(s[0] for _, s in runs)
    c_stream = min(s[1] for _, s in runs)
    t_open = min(s[2] for _, s in runs)
    return {"bare": t_bare, "streamed": t_stream, "open": t_open,
            "cost": (t_stream - t_bare) / t_bare, "bare_cpu": c_bare, "streamed_cpu": c_stream,
            "cost_cpu": (c_stream - c_bare) / c_bare, "records": round(duration / settings.dt),
            "dt": settings.dt, "duration": duration, "parts": breakdown()}


def main() -> None:
    m = measure()
    print(f"streaming: OC3 three lines, {m['duration']:g} s at dt {m['dt']:g} s, "
          f"{m['records']} records (one per step)")
    print(f"  stepping alone {m['bare']:.3f} s, with the stream {m['streamed']:.3f} s: "
          f"streaming costs {100 * m['cost']:+.1f} % of the stepping (target <= 5 %), "
          f"of which {1e3 * m['open']:.0f} ms creating the file")
    print(f"  CPU: stepping alone {m['bare_cpu']:.3f} s, with the stream "
          f"{m['streamed_cpu']:.3f} s: {100 * m['cost_cpu']:+.1f} %")
    p = m["parts"]
    print(f"  writer CPU in one more run: creating the file {1e3 * p['create']:.1f} ms, "
          f"{p['blocks']:.0f} appends {1e3 * p['append']:.1f} ms (the first record written "
          f"at once), closing {1e3 * p['close']:.1f} ms (the other records, the envelope)")


if __name__ == "__main__":
    main()
