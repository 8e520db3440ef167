"""Frequency-domain benchmark: stochastic analysis and harmonic balance against the time
domain they replace, on the same machine in the same run.

* Stochastic: the mid-water riser of ``moorline verify stochastic-riser`` in a JONSWAP sea,
  200 frequencies, 256 s record. The frequency-domain analysis (drag linearization iterated
  to 1 %, Foss decoupling over all modes) against the nonlinear time-domain run that gives
  its statistics (two records at dt 0.1 s: the first lets the start-up transient die out).
* Harmonic balance: Tcheou's line (20 elements, steel, 300 N at the top, T = 10 s, 9
  harmonics) against the time-domain run to its steady state (60 periods at T / 100).

Prints the wall times, their ratio and how close the answers are. Run with ``make bench``.
"""

from __future__ import annotations

import time

import numpy as np

from moorline.model import DynamicsSettings, StochasticSettings
from moorline.solvers.dynamics import simulate
from moorline.solvers.statics import solve_statics
from moorline.solvers.stochastic import solve_stochastic
from moorline.verification import stochastic_riser as riser
from moorline.verification import tcheou_t2


def timed(func):
    """(result, wall time [s]) of one call. The BLAS thread pool is started before (its
    one-off start-up, ~0.05 s, would otherwise be charged to whichever call is first)."""
    np.ones((256, 256)) @ np.ones((256, 256))
    start = time.perf_counter()
    out = func()
    return out, time.perf_counter() - start


def riser_runs() -> tuple:
    """The riser's frequency-domain analysis and its two-record time-domain run: (static,
    fd, fd wall time [s], td, td wall time [s], mask of the second record)."""
    system = riser.riser_system()
    static = solve_statics(system)
    fd, t_fd = timed(lambda: solve_stochastic(system, StochasticSettings(), static))
    td, t_td = timed(lambda: simulate(system, DynamicsSettings(duration=2 * riser.RECORD,
                                                                 dt=riser.DT, ramp_time=20.0),
                                      initial=static, output_every=riser.DT))
    return static, fd, t_fd, td, t_td, td.time >= riser.RECORD - 1e-9


def stochastic() -> None:
    _, fd, t_fd, td, t_td, second = riser_runs()
    std_td = float(np.std(td.positions[second, riser.MID_NODE, 0]))
    std_fd = float(fd.displacement_std[riser.MID_NODE, 0])
    print(f"stochastic riser: frequency domain {t_fd:.3f} s ({fd.iterations} iterations), "
          f"time domain {t_td:.3f} s; ratio {t_fd / t_td:.3f}; mid-node std "
          f"{std_fd:.4f} vs {std_td:.4f} m")


def harmonic() -> None:
    (system, static, hb), t_hb = timed(lambda: tcheou_t2.solve(7000.0, 20, 10.0,
                                                               harmonics=9))
    (last, _), t_td = timed(lambda: tcheou_t2.time_domain_difference(system, static, hb, 60))
    print(f"harmonic balance (Tcheou T2 steel): {t_hb:.3f} s ({hb.iterations} Newton "
          f"iterations, incl. statics), time domain to steady state {t_td:.3f} s; ratio "
          f"{t_hb / t_td:.3f}; largest difference {100 * last:.2f} % of the amplitude")


if __name__ == "__main__":
    stochastic()
    harmonic()
