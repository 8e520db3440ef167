"""Dynamics against MoorDyn-C 2.7 (an independent lumped-mass code, ``[compare]`` extra).

Both codes run the same moorline :class:`~moorline.model.System`
(:func:`moorline.compare.moordyn_runner.run_moordyn` writes it as a MoorDyn v2 deck and drives
its prescribed points through MoorDyn's coupling interface) from the still-water static
equilibrium. The chain is the OC3-Hywind chain (Jonkman 2010, NREL/TP-500-47535, table 4-1;
MoorDyn's OC3 example coefficients, :mod:`moorline.verification.oc3_system`) with the same
fixed internal damping ``BA = 1.56e6 N s`` in both codes (MoorDyn's ratio 0.8 at 80 segments;
a ratio would change the system with the mesh). Fairleads surge 5 m at 10 s, ramped over
10 s; statistics over t in [50, 100] s of the fairlead tension ``|end force|`` (moorline: its
end force; MoorDyn: the net force on the end node).

(a) ``oc3-surge``: the three OC3 lines, all fairleads surging: max, min and mean tension of
    lines 1 (in the surge plane) and 2 (at 120 deg), and the amplitude and phase of the
    tension's first harmonic (10 s) over the window.
(b) ``current``: line 1 with a uniform 1 m/s current across its plane (+y), switched on at
    t = 0 (MoorDyn applies its current after its still-water initial condition; moorline
    starts from the still-water statics without a current ramp), fairlead surging: max and
    mean tension, mean and max side force ``F_y`` on the fairlead.

Converged differences, moorline minus MoorDyn (three lines; moorline at 160 elements and dt
0.003125 s, MoorDyn at 160 segments and dtM = 0.05/64 s):

- surge, line 1 / line 2: max -0.67 / -0.31 %, min +0.96 / +0.42 %, mean -0.04 / -0.03 %,
  first-harmonic amplitude -0.98 / -0.61 %, phase +0.62 / +0.91 deg. At the full form's
  mesh (80 elements, dt 0.00625 s; MoorDyn 0.05/16 s) the same to within 0.05 % and 0.02 deg
  except line 1's min tension (+2.85 %). The min of line 1 is a near-slack trough that neither
  code has converged: moorline's spans 1.027e5 to 1.062e5 N over 40-160 elements and dt
  0.0125-0.003125 s (+-1.7 %), MoorDyn's 1.028e5 to 1.038e5 N over 40-160 segments. The
  amplitude and phase differences are converged in both codes (80 -> 160 elements: 0.04 % and
  0.01 deg in moorline, 0.02 % and 0.01 deg in MoorDyn); they come from the models (MoorDyn's
  node-based drag and added mass with node-averaged tangents vs moorline's element-based ones)
  and are not explained further.
- current (one line): max -0.78 %, mean +0.02 %, mean F_y -0.38 %, max F_y -0.34 % (80
  elements: -0.36, +0.05, -0.81, -0.19 %); the min tension is not converged in either code
  (moorline 1.03e5 to 1.10e5 N, MoorDyn 0.89e5 to 0.92e5 N from 80 to 160 elements) and is
  not checked.

Tolerances (the converged difference, rounded up, plus the non-converged spread where there
is one): max tension 1 %, min 4 % (1 % converged + 1.7 % moorline spread + 1 % MoorDyn
spread), mean 0.2 %, first-harmonic amplitude 1.5 %, phase 1.5 deg, side force 1 %.
Meshes: full 80 elements (current: 160), quick 40 (current: 80); MoorDyn at its largest
stable step rounded to the 0.05 s coupling interval (0.05/10, /16, /64 s at 40, 80, 160).

Seabed friction is not compared (no rows). MoorDyn-C 2.7 supports it (options
``FrictionCoefficient``, ``FricDamp``, ``StatDynFricScale``): per seabed node a saturated
viscous law, ``min(mu FricDamp |v_h|, mu N)`` against the horizontal node velocity, with
``FricDamp`` [N s/m] independent of the node's normal force N (default 200: for an OC3 node at
80 segments, N = 7.9 kN, it saturates only above 40 m/s, i.e. it is plain viscous damping).
moorline's law is ``mu N tanh(|v| / v_s)``. Matching the small-velocity slopes needs
``FricDamp = w l_seg / v_s`` (mesh-dependent). Tried on line 1 in surge with mu = 1: with
v_s = 0.01 m/s (80 elements) friction changes the max fairlead tension by -13.2 kN in moorline
and -24.8 kN in MoorDyn, the mean by +0.3 and -0.5 kN, the first-harmonic amplitude by -3.5 and
-1.0 kN; with v_s = 0.002 m/s (40 elements, MoorDyn at dtM = 0.05/128 s) -15.7 / -25.9 kN,
+0.3 / -0.5 kN, -3.4 / -0.9 kN. The effect is about 1 % of the max tension and the two laws
disagree on it by a factor of 1.6 to 4: no tolerance would be honest without a case where
friction dominates and a study of v_s -> 0 in both codes (left to do).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from ..model import Current, DynamicsSettings, System
from ..solvers.dynamics import simulate
from ..solvers.statics import solve_statics
from .core import CaseSkipped, Row
from .oc3_system import PERIOD, oc3_one_line, oc3_three_lines

CASE = "moordyn-dynamics"
SOURCE = "MoorDyn-C 2.7.2, same input"
BA = 1.56e6  # N s, both codes
DURATION, WINDOW, COUPLING = 100.0, (50.0, 100.0), 0.05
#: MoorDyn's step per segment count: its largest stable step (benchmarks/bench_dynamics.py
#: search, cached) rounded down to a whole number of steps per coupling interval.
MOORDYN_DIVISOR = {40: 10, 80: 16, 160: 64}
#: moorline's step per element count (converged: halving it changes the extremes < 0.5 %).
MOORLINE_DT = {40: 0.0125, 80: 0.00625, 160: 0.00625}
TOL = {"max": 0.01, "min": 0.04, "mean": 0.002, "amplitude": 0.015, "phase": 1.5,
       "side": 0.01}
CURRENT = Current(speed=1.0, heading_deg=90.0)


@dataclass
class _Pair:
    """Fairlead end forces of both codes: time (n,) and forces (n, n_lines, 3)."""

    ml_time: np.ndarray
    ml_force: np.ndarray
    md_time: np.ndarray
    md_force: np.ndarray


def _import() -> None:
    try:
        import moordyn  # noqa: F401
    except ImportError as exc:
        raise CaseSkipped("the [compare] extra (moordyn) is not installed") from exc


def _run_pair(system: System, segments: int) -> _Pair:
    from ..compare.moordyn_runner import run_moordyn

    dt = MOORLINE_DT[segments]
    ml = simulate(system, DynamicsSettings(duration=DURATION, dt=dt),
                  initial=solve_statics(system), output_every=COUPLING)
    if not ml.success:
        raise RuntimeError(f"moorline run failed: {ml.message}")
    md = run_moordyn(system, DURATION, COUPLING / MOORDYN_DIVISOR[segments], COUPLING)
    if not md["success"]:
        raise RuntimeError(f"MoorDyn run failed: {md['message']}")
    return _Pair(np.asarray(ml.time), np.asarray(ml.records()["end_force"])[:, :, 1],
                 np.asarray(md["time"]), np.asarray(md["end_force"])[:, :, 1])


def _window(time: np.ndarray, values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    inside = (time >= WINDOW[0] - 1e-9) & (time < WINDOW[1] - 1e-9)
    return time[inside], values[inside]


def first_harmonic(time: np.ndarray, values: np.ndarray, period: float) -> tuple[float, float]:
    """Amplitude and phase [deg] of the ``period`` harmonic of ``values`` over whole periods
    of uniform samples: ``values ~ A cos(w t + phase)``."""
    omega = 2.0 * math.pi / period
    c = 2.0 / len(time) * np.sum(values * np.exp(-1j * omega * time))
    return float(abs(c)), float(math.degrees(np.angle(c)))


def _row(label: str, quantity: str, ref: float, got: float, tol_key: str, unit: str = "N",
         relative: bool = True, note: str = "") -> Row:
    return Row(CASE, f"{label}: {quantity}", ref, got, TOL[tol_key], relative=relative,
               unit=unit, kind="other code", source=SOURCE, note=note)


def surge_rows(quick: bool = False) -> list[Row]:
    """(a) The OC3 three lines in surge: tension statistics of lines 1 and 2."""
    segments = 40 if quick else 80
    pair = _run_pair(oc3_three_lines(segments, BA=BA), segments)
    rows = []
    for k, name in ((0, "line1"), (1, "line2")):
        t_ml, T_ml = _window(pair.ml_time, np.linalg.norm(pair.ml_force[:, k], axis=-1))
        t_md, T_md = _window(pair.md_time, np.linalg.norm(pair.md_force[:, k], axis=-1))
        label = f"OC3 surge ({segments} el.) {name}"
        rows += [_row(label, "max fairlead tension", T_md.max(), T_ml.max(), "max"),
                 _row(label, "min fairlead tension", T_md.min(), T_ml.min(), "min")]
        if quick and k == 1:
            continue
        a_ml, p_ml = first_harmonic(t_ml, T_ml, PERIOD)
        a_md, p_md = first_harmonic(t_md, T_md, PERIOD)
        rows += [_row(label, "mean fairlead tension", T_md.mean(), T_ml.mean(), "mean"),
                 _row(label, "first-harmonic tension amplitude", a_md, a_ml, "amplitude"),
                 _row(label, "first-harmonic tension phase", p_md, p_ml, "phase", unit="deg",
                      relative=False)]
    return rows


def current_rows(quick: bool = False) -> list[Row]:
    """(b) OC3 line 1 in a 1 m/s cross current, fairlead surging."""
    segments = 80 if quick else 160
    base = oc3_one_line(segments, BA=BA)
    system = dataclasses.replace(
        base, environment=dataclasses.replace(base.environment, current=CURRENT))
    pair = _run_pair(system, segments)
    _, F_ml = _window(pair.ml_time, pair.ml_force[:, 0])
    _, F_md = _window(pair.md_time, pair.md_force[:, 0])
    T_ml, T_md = np.linalg.norm(F_ml, axis=-1), np.linalg.norm(F_md, axis=-1)
    label = f"OC3 line, 1 m/s cross current ({segments} el.)"
    return [_row(label, "max fairlead tension", T_md.max(), T_ml.max(), "max"),
            _row(label, "mean fairlead tension", T_md.mean(), T_ml.mean(), "mean"),
            _row(label, "mean fairlead side force F_y", abs(F_md[:, 1].mean()),
                 abs(F_ml[:, 1].mean()), "side"),
            _row(label, "max fairlead side force F_y", abs(F_md[:, 1]).max(),
                 abs(F_ml[:, 1]).max(), "side")]


def run(quick: bool = False) -> list[Row]:
    """Surge of the three OC3 lines and a line in current, against MoorDyn."""
    _import()
    return surge_rows(quick) + current_rows(quick)
