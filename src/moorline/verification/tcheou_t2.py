"""Tcheou (1997) sec. 5.2: periodic response of the Table 5.1 line by harmonic balance.

The line of :mod:`moorline.verification.tcheou_t1` (600 m, EA 2e5 N, steel 7000 or synthetic
2000 kg/m^3, anchor fixed, top pulled with H = 4000 N, V = 8000 N) with a harmonic force
``300 cos(omega t)`` N added at the top, horizontal (then vertical), ``T = 10 s`` (T2, "wave
frequency") and ``T = 160 s`` (T3, "slow drift"); 10, 20 and 40 elements. Tcheou gives no
drag or added-mass coefficients for the line: moorline's defaults are used (``Cd = 1.2``,
``Ca = 1`` on the 16 mm volume-equivalent diameter; Tcheou's added mass uses the displaced
area 2e-4 m^2, as here), in still water.

Tcheou prints no number for the dynamic response (his Figs. 5-5 to 5-14 are lost); his text
states the mode shapes. What is checked:

* exact (the small-amplitude limit): 1 N at the top, no drag, harmonic balance at 20 and 40
  elements against the continuous line linearized about the closed-form catenary
  (:func:`continuum_top`, :mod:`~moorline.verification.linear_cable`), T = 10 and 160 s,
  steel and synthetic: the 40-element top surge amplitude within the Richardson estimate of
  its error (``|a20 - a40| / 3``, 50 % margin), and the observed order of the error, 2
  within 0.25 (T2 steel: 9.6 % at 20 elements, 2.4 % at 40: the 10 s period sits near the
  steel line's second mode);
* published (text on Figs. 5-7 to 5-10): "the heavier cable oscillates in a hybrid second
  mode, while the lighter one oscillates in a first mode": the amplitude of the first-harmonic
  motion normal to the static line (40 elements, drag on) has one interior antinode for steel
  and none for synthetic; under a vertical force the synthetic line keeps its mode, the steel
  line "a third hybrid mode" (two interior antinodes: NOT reproduced, one here), and both
  move less than under a horizontal force. The antinode count is our reading of "mode";
* internal cross-checks (moorline against moorline): the element convergence of the forced
  response (10, 20, 40 elements, observed order) and the time-domain steady state (Newmark,
  100 steps per period, run until the transient has died out) against the harmonic-balance
  series over the last period, every node (20 elements), relative to the largest dynamic
  amplitude, 1 %.
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
from .linear_cable import Cable, forced_end, transfer

CASE = "tcheou-t2"
FORCE = 300.0  # N
HARMONICS = 5
TD_HARMONICS = 9  # for the comparison with the time domain (5 give 1 %, 9 give 0.5 %)
MATERIALS = t1.MATERIALS
SMALL_FORCE = 1.0  # N: the small-amplitude limit (top motion ~4 mm at T = 10 s)


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


def small_amplitude_top(density: float, elements: int, period: float) -> complex:
    """First-harmonic complex amplitude ``U`` (``x = Re U e^{i w t}``) of the top's surge
    under ``SMALL_FORCE cos(w t)`` without drag: harmonic balance, 3 harmonics."""
    system = forced_system(density, elements, period)
    top = replace(system.points["top"], force_history=replace(
        system.points["top"].force_history, amplitude=(SMALL_FORCE, 0.0, 0.0)))
    types = {k: replace(v, Cd=0.0, Ct=0.0) for k, v in system.line_types.items()}
    system = replace(system, points={**system.points, "top": top}, line_types=types)
    static = solve_statics(system, t1.SETTINGS)
    result = solve_harmonic(system, HarmonicSettings(period=period, harmonics=3), static)
    c = result.coefficients[:, top_node(static), 0]
    return complex(c[1] - 1j * c[2])


def continuum_top(density: float, period: float, steps: int = 600) -> complex:
    """The same amplitude from the continuous line linearized about the closed-form catenary
    (:mod:`~moorline.verification.linear_cable`: mass ``rho_c A``, normal added mass
    ``rho_w A``, no drag), per ``SMALL_FORCE``."""
    w = (density - t1.RHO_WATER) * t1.AREA * t1.G
    cable = Cable(t1.LENGTH, t1.E * t1.AREA, (t1.H, 0.0, t1.V - w * t1.LENGTH), w,
                  density * t1.AREA, t1.RHO_WATER * t1.AREA)
    Phi = transfer(cable, [2.0 * math.pi / period], steps=steps)[1]
    return complex(forced_end(Phi, [SMALL_FORCE, 0.0, 0.0])[-1, 0, 0])


TCHEOU_SOURCE = "Tcheou (1997) sec. 5.2.1, text on Figs. 5-7 to 5-10 (the figures are lost)"


def _exact_rows(name: str, density: float, label: str, period: float) -> list[Row]:
    exact = continuum_top(density, period)
    fe = {n: small_amplitude_top(density, n, period) for n in (20, 40)}
    err = {n: abs(v - exact) for n, v in fe.items()}
    estimate = abs(fe[20] - fe[40]) / 3.0  # Richardson: the O(h^2) error left at 40
    note = (f"{SMALL_FORCE:g} N cos(w t), no drag, 3 harmonics; continuum {exact.real:.6g} m; "
            + ", ".join(f"{n} elements {v.real:.6g} m" for n, v in fe.items()))
    return [
        Row(CASE, f"{label} {name} small amplitude: top surge amplitude, 40 elements vs the "
            "continuous line", abs(exact), abs(fe[40]), 1.5 * estimate / abs(exact), unit="m",
            note=f"{note}; tolerance: the Richardson estimate of the 40-element error "
            f"|a20 - a40| / 3 ({estimate / abs(exact):.2%}) with 50 % margin", kind="exact",
            source="linear_cable: closed-form catenary, continuous line"),
        Row(CASE, f"{label} {name} small amplitude: observed order of the error against the "
            "continuous line (20 -> 40 elements)", 2.0, math.log2(err[20] / err[40]), 0.25,
            relative=False, note="lumped-mass straight elements: order 2", kind="exact",
            source="linear_cable"),
    ]


def run(quick: bool = False) -> list[Row]:
    """The rows (see the module docstring).

    ``quick``: the element convergence and the time-domain comparison for the steel line at
    T = 10 s only; every exact and published row.
    """
    rows: list[Row] = []
    for name, density in MATERIALS.items():
        for label, period in (("T2", 10.0), ("T3", 160.0)):
            rows += _exact_rows(name, density, label, period)
    shapes = {}
    for name, density in MATERIALS.items():
        for label, period in (("T2", 10.0), ("T3", 160.0)):
            if quick and (name, label) != ("steel", "T2"):
                continue
            tops = []
            for elements in (10, 20, 40):
                system, static, result = solve(density, elements, period)
                tops.append(float(result.amplitude(1)[top_node(static), 0]))
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
                            note=f"moorline against moorline (Newmark vs harmonic balance); "
                                 f"{TD_HARMONICS} harmonics ({result.iterations} Newton "
                                 f"iterations); last period of the run; the period before: "
                                 f"{before:.4f} (the transient is gone)",
                            kind="internal cross-check"))
    for name, density in MATERIALS.items():
        for direction in ("x", "z"):
            _, static, result = solve(density, 40, 10.0, direction)
            shapes[name, direction] = normal_amplitude(static, result)
    counts = {key: interior_antinodes(a) for key, a in shapes.items()}
    # (material, direction): the source's mode, its interior antinodes, and what moorline
    # gives when it differs (documented; any other count is checked and can fail)
    for (name, direction), expected, what, documented in (
            (("steel", "x"), 1, "hybrid second mode", None),
            (("synthetic", "x"), 0, "first mode", None),
            (("steel", "z"), 2, "third hybrid mode", 1),
            (("synthetic", "z"), 0, "the same (first) mode as under a horizontal force", None)):
        force = "horizontal" if direction == "x" else "vertical"
        count = counts[name, direction]
        note = ("40 elements, drag on; an antinode is an interior local maximum above 2 % of "
                "the largest (our reading of the source's 'mode', its figures being lost)")
        if documented is not None and count == documented:
            note += ("; here one interior antinode, the shape of the horizontal case with a "
                     "smaller amplitude (the next row): the source's third hybrid mode is not "
                     "obtained. The undamped continuous line has two under either force, so "
                     "the count depends on the drag near the second mode; Tcheou gives no drag "
                     "coefficient")
        rows.append(Row(CASE, f"T2 {name}, {force} top force: interior antinodes of the "
                        f"normal first-harmonic amplitude ({what}: {expected})",
                        float(expected), float(count), 0.0, relative=False, note=note,
                        kind="published", source=TCHEOU_SOURCE,
                        reproduced=documented is None or count != documented))
    for name in MATERIALS:
        ratio = float(shapes[name, "z"].max() / shapes[name, "x"].max())
        rows.append(Row(CASE, f"T2 {name}: a vertical top force moves the line less than a "
                        "horizontal one (1 = yes)", 1.0, float(ratio < 1.0), 0.0,
                        relative=False, note=f"ratio of the largest normal amplitudes "
                                             f"{ratio:.3f}", kind="published",
                        source=TCHEOU_SOURCE))
    return rows


__all__ = ["CASE", "continuum_top", "forced_system", "interior_antinodes", "normal_amplitude",
           "run", "small_amplitude_top", "solve"]
