"""Tcheou (1997) sec. 5.2: periodic response of the Table 5.1 line by harmonic balance.

The line of :mod:`moorline.verification.tcheou_t1` (600 m, EA 2e5 N, steel 7000 or synthetic
2000 kg/m^3, anchor fixed, top pulled with H = 4000 N, V = 8000 N) with a harmonic force
``300 cos(omega t)`` N added at the top, horizontal (then vertical), ``T = 10 s`` (T2, "wave
frequency") and ``T = 160 s`` (T3, "slow drift"); 10, 20 and 40 elements. Tcheou gives no
drag or added-mass coefficients for the line: moorline's defaults are used (``Cd = 1.2``,
``Ca = 1`` on the 16 mm volume-equivalent diameter; Tcheou's added mass uses the displaced
area 2e-4 m^2, as here), in still water.

What the source shows and what is checked:

* "converged in elements": the first-harmonic amplitude of the top's horizontal motion at
  10, 20 and 40 elements converges at second order (observed order from the three);
* equal to the steady state of a long time-domain run: the nonlinear Newmark model
  (:func:`moorline.solvers.dynamics.simulate`, 100 steps per period, run until the
  transient has died out) over its last period against the harmonic-balance series at the
  same instants, every node (20 elements), relative to the largest dynamic amplitude;
* "the heavier cable oscillates in a hybrid second mode, while the lighter one oscillates in
  a first mode": the amplitude of the first-harmonic motion normal to the static line has an
  interior antinode for steel and none for synthetic (it grows monotonically to the top);
* a vertical top force moves the line less than a horizontal one (normal amplitude).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ..model import DynamicsSettings, Motion, System
from ..results import StaticResult
from ..solvers.dynamics import simulate
from ..solvers.harmonic import HarmonicResult, HarmonicSettings, _basis, solve_harmonic
from ..solvers.statics import solve_statics
from . import tcheou_t1 as t1
from .core import Row

CASE = "tcheou-t2"
FORCE = 300.0  # N
HARMONICS = 5
TD_HARMONICS = 9  # for the comparison with the time domain (5 give 1 %, 9 give 0.5 %)
MATERIALS = t1.MATERIALS


def forced_system(density: float, elements: int, period: float,
                  direction: str = "x") -> System:
    """The Table 5.1 line with ``300 cos(2 pi t / period)`` N at the top along ``x`` or
    ``z``."""
    system = t1.t1_system(density, elements)
    amplitude = (FORCE, 0.0, 0.0) if direction == "x" else (0.0, 0.0, FORCE)
    top = replace(system.points["top"],
                  force_history=Motion("harmonic", amplitude=amplitude, period=period,
                                       phase_deg=90.0))
    return replace(system, name=CASE, points={**system.points, "top": top})


def solve(density: float, elements: int, period: float, direction: str = "x",
          harmonics: int = HARMONICS) -> tuple[System, StaticResult, HarmonicResult]:
    """Statics and harmonic balance of one configuration."""
    system = forced_system(density, elements, period, direction)
    static = solve_statics(system, t1.SETTINGS)
    return system, static, solve_harmonic(system, HarmonicSettings(period=period,
                                                                    harmonics=harmonics),
                                          static)


def top_node(static: StaticResult) -> int:
    """Node index of the top point."""
    return int(static.mesh.point_node[static.mesh.point_index("top")])


def normal_amplitude(static: StaticResult, result: HarmonicResult) -> np.ndarray:
    """First-harmonic amplitude of the motion normal to the static line in the x-z plane,
    node by node from the anchor to the top."""
    x0 = static.positions
    anchor = static.mesh.point_node[static.mesh.point_index("anchor")]
    order = np.argsort(np.linalg.norm(x0 - x0[anchor], axis=1))
    x0 = x0[order]
    U = (result.coefficients[1] - 1j * result.coefficients[2])[order]
    t = np.gradient(x0, axis=0)
    t /= np.linalg.norm(t, axis=1)[:, None]
    normal = np.stack([-t[:, 2], np.zeros(len(t)), t[:, 0]], axis=1)
    return np.abs(np.einsum("nc,nc->n", U, normal))


def interior_antinodes(amplitude: np.ndarray, floor: float = 0.02) -> int:
    """Interior local maxima of an amplitude along the line (above ``floor`` of the
    largest)."""
    a = amplitude
    inner = (a[1:-1] > a[:-2]) & (a[1:-1] > a[2:]) & (a[1:-1] > floor * a.max())
    return int(np.sum(inner))


def time_domain_difference(system: System, static: StaticResult, result: HarmonicResult,
                           periods: int) -> tuple[float, float]:
    """Largest difference between the time-domain run's last period and the harmonic series
    at the same instants (every node and axis), relative to the largest dynamic amplitude;
    and the same for the period before (shows the transient is gone)."""
    period = result.period
    td = simulate(system, DynamicsSettings(duration=periods * period, dt=period / 100,
                                           tolerance=1e-9),
                  initial=static, output_every=period / 50)
    amp = float(np.abs(result.positions - result.coefficients[0][None]).max())
    out = []
    for last in (periods - 1, periods - 2):
        m = (td.time >= last * period - 1e-9) & (td.time < (last + 1) * period - 1e-9)
        E = _basis(td.time[m] - last * period, result.omega, result.settings.harmonics)[0]
        hb = np.einsum("tk,knc->tnc", E, result.coefficients)
        out.append(float(np.abs(td.positions[m] - hb).max()) / amp)
    return out[0], out[1]


def _order(values: list[float]) -> float:
    a, b, c = values
    return math.log2(abs(a - b) / abs(b - c))


def run(quick: bool = False) -> list[Row]:
    """The rows (see the module docstring)."""
    rows: list[Row] = []
    shapes = {}
    for name, density in MATERIALS.items():
        for label, period in (("T2", 10.0), ("T3", 160.0)):
            tops = []
            for elements in (10, 20, 40):
                system, static, result = solve(density, elements, period)
                tops.append(float(result.amplitude(1)[top_node(static), 0]))
                if elements == 40 and label == "T2":
                    shapes[name] = normal_amplitude(static, result)
            rows.append(Row(CASE, f"{label} {name}: convergence order of the top's first-"
                            "harmonic surge amplitude (10, 20, 40 elements)", 2.0,
                            _order(tops), 0.5, relative=False,
                            note="amplitudes " + ", ".join(f"{v:.4f}" for v in tops) + " m",
                            kind="internal cross-check"))
            system, static, result = solve(density, 20, period, harmonics=TD_HARMONICS)
            last, before = time_domain_difference(system, static, result,
                                                  periods=60 if label == "T2" else 40)
            rows.append(Row(CASE, f"{label} {name}: time-domain steady state vs harmonic "
                            "balance, max difference / dynamic amplitude (20 elements)", 0.0,
                            last, 0.01, relative=False,
                            note=f"{TD_HARMONICS} harmonics ({result.iterations} Newton "
                                 f"iterations); last period of the run; the period before: "
                                 f"{before:.4f} (the transient is gone)",
                                 kind="internal cross-check"))
    steel, synthetic = (interior_antinodes(shapes[n]) for n in ("steel", "synthetic"))
    rows.append(Row(CASE, "T2 steel: interior antinodes of the normal first-harmonic "
                    "amplitude (hybrid second mode: 1)", 1.0, float(steel), 0.0,
                    relative=False, kind="internal cross-check"))
    rows.append(Row(CASE, "T2 synthetic: interior antinodes (first mode: 0)", 0.0,
                    float(synthetic), 0.0, relative=False, kind="internal cross-check"))
    for name, density in MATERIALS.items():
        _, static, vertical = solve(density, 40, 10.0, "z")
        ratio = float(normal_amplitude(static, vertical).max() / shapes[name].max())
        rows.append(Row(CASE, f"T2 {name}: vertical top force moves the line less than a "
                        "horizontal one (1 = yes)", 1.0, float(ratio < 1.0), 0.0,
                        relative=False, note=f"ratio of the largest normal amplitudes "
                                             f"{ratio:.3f}", kind="internal cross-check"))
    return rows


__all__ = ["CASE", "forced_system", "interior_antinodes", "normal_amplitude", "run", "solve"]
