"""Tuah (1982) Example 4 (sec. 6.4): a point mass at midspan of a horizontal string, released.

Data: 5 slug at midspan of a 20 ft string fixed at both ends, Ex1 material (E = 1e7 psf,
A = 0.1 ft^2, initial stress 500 psf) or the Ex3 viscoelastic material, released from 2 ft,
dt = 0.001 s, two elements. No gravity, no fluid (the source gives none).

The reference is the exact equation of motion of the pin-jointed string, integrated
independently with scipy (rtol 1e-11):

    m d'' = -2 T sin(theta),  sin(theta) = d / l,  l = sqrt(a^2 + d^2),  a = span / 2,

with ``T = EA (l / l0 - 1)`` (elastic, no compression) or the standard linear solid
``T = EA eps + Q``, ``Q' = -Q / tau + EA1 eps'`` while taut; while slack (trial tension < 0)
the rope carries nothing and its Maxwell branch recovers with the creep time
``tau (EA + EA1) / EA`` (the slack model of :mod:`moorline.physics.material`).

The source prints a period of 0.65 s. The stated data do not give it: the exact equation
above has a period of about 0.265 s (the string is very stiff: EA = 1e6 lbf against 5 slug).
We report the discrepancy and do not tune inputs. The Ex3 material's absolute modulus was in a
lost figure: we take the long-term stiffness K0 A equal to Ex1's EA, with EA1/EA and tau of
our Ex3 fit (EA1/EA = 7.464, tau = 4.92 s). The string is relaxed (Q = 0) straight at its
pretension and displaced suddenly ("initially displaced two feet and suddenly released"), so
at release its Maxwell branch carries ``EA1 (eps(2 ft) - eps0)``: it starts with the
instantaneous modulus, and the period lengthens as it relaxes towards K0. Over 40 s the
reference shows what the source describes: the period grows from 0.091 s to 0.21 s, the slack
fraction of each second from 0.14 to 0.70, and the amplitude, after growing 4 % while the
modulus softens, decays (1.92 ft at 40 s). The rows check the first 3 s against it.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
from scipy.integrate import solve_ivp

from ..mesh import discretize
from ..model import DynamicsSettings, Environment, Line, LineType, Point, System
from ..solvers.dynamics import simulate
from .core import Row

CASE = "tuah-ex4"
REFERENCE = ("exact equation of motion of the pin-jointed string, integrated with scipy "
             "(rtol 1e-11)")
SOURCE_PERIOD = 0.65  # s, Tuah (1982) sec. 6.4
E, AREA, STRESS0, SPAN, MASS, D0 = 1.0e7, 0.1, 500.0, 20.0, 5.0, 2.0
EA = E * AREA
EA1_RATIO, TAU = 7.4641, 4.9209  # our Ex3 fit (viscoelastic_reference.fit_tuah_ex3)
L_HALF = (SPAN / 2) / (1 + STRESS0 / E)  # unstretched length of each half


def ex4_system(viscoelastic: bool = False, elements_per_half: int = 1) -> System:
    """The string with the point mass (displaced start positions: :func:`start_positions`)."""
    lt = LineType("string", diameter=0.0, mass_per_length=0.0, EA=EA, displaced_area=0.0,
                  Cd=0.0, Ca=0.0, Ct=0.0,
                  material="viscoelastic" if viscoelastic else "elastic",
                  EA1=EA1_RATIO * EA if viscoelastic else 0.0, tau=TAU if viscoelastic else 0.0)
    points = {
        "left": Point("left", "fixed", (0.0, 0.0, 0.0)),
        "mass": Point("mass", "free", (SPAN / 2, 0.0, 0.0), mass=MASS),
        "right": Point("right", "fixed", (SPAN, 0.0, 0.0)),
    }
    lines = {"left": Line("left", "string", L_HALF, elements_per_half, "left", "mass"),
             "right": Line("right", "string", L_HALF, elements_per_half, "mass", "right")}
    env = Environment(water_density=0.0, gravity=0.0)
    return System("tuah-ex4", units="US", environment=env, line_types={"string": lt},
                  points=points, lines=lines)


def start_positions(system: System) -> np.ndarray:
    """Nodes on the two straight halves with the mass displaced by 2 ft (downwards)."""
    mesh = discretize(system)
    x = mesh.node_position.copy()
    mass = mesh.point_node[mesh.point_index("mass")]
    x[mass, 2] = -D0
    for nodes in mesh.line_nodes:
        a, b = x[nodes[0]], x[nodes[-1]]
        s = np.linspace(0.0, 1.0, len(nodes))[:, None]
        x[nodes] = a + s * (b - a)
    return x


def reference(duration: float, viscoelastic: bool) -> tuple[np.ndarray, ...]:
    """Exact midpoint deflection history (times, d, trial tension) on a fine output grid."""
    a = SPAN / 2

    def rhs(t, y):
        d, v, q = y
        length = math.hypot(a, d)
        strain = length / L_HALF - 1
        rate = d * v / (length * L_HALF)
        if not viscoelastic:
            tension, dq = max(EA * strain, 0.0), 0.0
        elif EA * strain + q >= 0:
            tension, dq = EA * strain + q, -q / TAU + EA1_RATIO * EA * rate
        else:
            tension, dq = 0.0, -q / (TAU * (1 + EA1_RATIO))
        return [v, -2 * tension * d / length / MASS, dq]

    t = np.linspace(0.0, duration, int(duration / 1e-4) + 1)
    q0 = initial_maxwell() if viscoelastic else 0.0
    sol = solve_ivp(rhs, (0.0, duration), [-D0, 0.0, q0], t_eval=t, rtol=1e-11, atol=1e-9,
                    method="DOP853", max_step=2e-4)
    length = np.hypot(a, sol.y[0])
    tension = EA * (length / L_HALF - 1) + sol.y[2]
    return sol.t, sol.y[0], tension


def initial_maxwell() -> float:
    """Maxwell-branch force after the sudden 2 ft displacement from the relaxed string."""
    strain0 = (SPAN / 2) / L_HALF - 1
    return EA1_RATIO * EA * (math.hypot(SPAN / 2, D0) / L_HALF - 1 - strain0)


def periods(t: np.ndarray, d: np.ndarray) -> np.ndarray:
    """Times between successive upward zero crossings (linear interpolation)."""
    i = np.flatnonzero((d[:-1] < 0) & (d[1:] >= 0))
    crossings = t[i] - d[i] * (t[i + 1] - t[i]) / (d[i + 1] - d[i])
    return np.diff(crossings)


def peaks(t: np.ndarray, d: np.ndarray) -> np.ndarray:
    """Local maxima of ``d`` (upward swings), as values."""
    i = np.flatnonzero((d[1:-1] > d[:-2]) & (d[1:-1] >= d[2:])) + 1
    return d[i]


def _run(viscoelastic: bool, dt: float, duration: float, variant: str = "iterative"):
    system = ex4_system(viscoelastic)
    settings = DynamicsSettings(duration=duration, dt=dt, tolerance=1e-10, variant=variant,
                                max_iterations=30)
    maxwell = np.full(discretize(system).n_elements, initial_maxwell()) if viscoelastic else None
    result = simulate(system, settings, initial=start_positions(system), output_every=dt,
                      maxwell=maxwell)
    return result, result.time, result.point_history("mass")[:, 2]


def _energy(result) -> np.ndarray:
    """Kinetic plus strain energy of the elastic string at every output time."""
    v = result.velocities[:, result.mesh.point_node[result.mesh.point_index("mass")]]
    strain = result.tension / EA
    return 0.5 * MASS * (v**2).sum(axis=1) + (0.5 * EA * strain**2 * L_HALF).sum(axis=1)


def run() -> list[Row]:
    """Elastic period, Newmark order, energy, viscoelastic decay and slack."""
    rows = []
    t_ref, d_ref, _ = reference(3.0, False)
    period_exact = float(np.mean(periods(t_ref, d_ref)))
    result, t, d = _run(False, 0.001, 3.0)
    period = float(np.mean(periods(t, d)))
    rows.append(Row(CASE, "elastic period, dt = 0.001 s, 2 elements", period_exact, period,
                    5e-3, unit="s", note="source prints 0.65 s; its stated data give "
                    f"{period_exact:.4f} s (exact ODE)", kind="exact",
                    source=REFERENCE))
    rows.append(Row(CASE, "elastic period, the source's printed value", SOURCE_PERIOD, period,
                    0.05, unit="s", kind="published", source="Tuah (1982) sec. 6.4",
                    reproduced=False,
                    note="the stated data (EA = 1e6 lbf, 5 slug, 20 ft) give "
                    f"{period_exact:.4f} s by the exact equation of motion; 0.65 s would need "
                    f"EA {(period_exact / SOURCE_PERIOD) ** 2:.3f} times smaller (a lost or "
                    "misprinted datum); the inputs are not tuned"))
    energy = _energy(result)
    rows.append(Row(CASE, "elastic: energy error over ~11 periods (undamped, iterative)", 0.0,
                    float(np.abs(energy / energy[0] - 1).max()), 1e-3, relative=False,
                    note="average acceleration conserves energy exactly only for linear "
                    "springs; for this stiffening string the error is O(dt^2), bounded",
                    kind="exact",
                    source=REFERENCE))
    errors = [abs(float(np.mean(periods(*_run(False, h, 3.0)[1:]))) - period_exact)
              for h in (0.004, 0.002)]
    rows.append(Row(CASE, "Newmark order in dt (period error, dt 0.004 -> 0.002 s)", 2.0,
                    math.log2(errors[0] / errors[1]), 0.2, relative=False,
                    note=f"period errors {errors[0]:.3g} s, {errors[1]:.3g} s", kind="exact",
                    source="Newmark average acceleration: second order in dt"))
    _, _, d_pure = _run(False, 0.001, 3.0, "incremental")
    rows[0] = replace(rows[0], note=rows[0].note + "; purely incremental: final amplitude "
                      f"{abs(peaks(t, d_pure)[-1]):.3f} ft vs {D0} ft (drifts)")
    rows += _viscoelastic_rows()
    return rows


def _viscoelastic_rows() -> list[Row]:
    duration = 3.0
    t_ref, d_ref, trial_ref = reference(duration, True)
    result, t, d = _run(True, 0.001, duration)
    p_ref, p = periods(t_ref, d_ref), periods(t, d)
    a_ref, a = peaks(t_ref, d_ref), peaks(t, d)
    n = min(len(p_ref), len(p)) - 1
    m = min(len(a_ref), len(a)) - 1
    slack_ref = _slack_fraction(t_ref, trial_ref <= 0)
    slack = _slack_fraction(t, result.tension[:, 0] <= 0)
    return [
        Row(CASE, "viscoelastic: last period in 3 s (lengthens)", float(p_ref[n]), float(p[n]),
            5e-3, unit="s", note=f"first period {p_ref[0]:.4f} s", kind="exact",
            source=REFERENCE),
        Row(CASE, "viscoelastic: last upward peak in 3 s", float(a_ref[m]), float(a[m]), 1e-3,
            unit="ft", note=f"release from {D0} ft; the amplitude first grows as the modulus "
            "relaxes, then decays (reference: 2.08 ft at ~10 s, 1.92 ft at 40 s)", kind="exact",
            source=REFERENCE),
        Row(CASE, "viscoelastic: slack time fraction in the last second", slack_ref[1], slack[1],
            0.02, relative=False, note=f"first second: {slack_ref[0]:.3f} (reference)",
            kind="exact",
            source=REFERENCE),
    ]


def _slack_fraction(t: np.ndarray, slack: np.ndarray) -> tuple[float, float]:
    """Fraction of time the string is slack (carries no tension) in the first and last
    second."""
    first, last = t <= 1.0, t >= t[-1] - 1.0
    return float(slack[first].mean()), float(slack[last].mean())
