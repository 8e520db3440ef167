"""Tuah (1982) Example 1 (sec. 6.1): point load at midspan of a pretensioned horizontal string.

Data (US units): E = 1.0e7 psf, A0 = 0.1 ft^2, initial stress 500 psf; the span is not printed,
20 ft is assumed as in Example 4, which uses "the same material". No weight. The reference is
the exact large-deflection equilibrium of the pin-jointed string
(:func:`~moorline.verification.references.pin_jointed_string_deflection`).

The source solves it by viscous relaxation (C0 = 1e5, mu = 0.5, dt = 1 s, TOL 0.001,
stiffness updated every 10 steps: 44 iterations) and quotes Webster (1974): 100 load steps
purely incremental, 55 modified Newton-Raphson iterations. All three methods are run here and
their iteration counts reported in the notes. The purely incremental method drifts (no
equilibrium correction, and the straight string starts with almost no transverse stiffness):
with Webster's 100 increments its deflection is ~26 % high; its error falls roughly as 1/N,
and a row checks it reaches 0.1 % with 1600 increments.
"""

from __future__ import annotations

from ..model import Environment, Line, LineType, Point, StaticsSettings, System
from ..solvers.statics import solve_statics
from .core import Row
from .references import G_FT, pin_jointed_string_deflection

CASE = "tuah-ex1"
REFERENCE = "exact equilibrium of the pin-jointed string (references.pin_jointed_string_deflection)"
E, AREA, STRESS0, SPAN = 1.0e7, 0.1, 500.0, 20.0
LOADS = (50.0, 200.0, 500.0, 1000.0, 2000.0)  # lbf


def string_system(load: float, elements_per_half: int = 2) -> System:
    """The pretensioned string with a downward midspan load ``load`` [lbf]."""
    EA = E * AREA
    unstretched = SPAN / (1.0 + STRESS0 / E)
    lt = LineType("string", diameter=0.0, mass_per_length=0.0, EA=EA, displaced_area=0.0)
    points = {
        "left": Point("left", "fixed", (0.0, 0.0, 0.0)),
        "mid": Point("mid", "free", (SPAN / 2, 0.0, 0.0), force=(0.0, 0.0, -load)),
        "right": Point("right", "fixed", (SPAN, 0.0, 0.0)),
    }
    lines = {
        "left_half": Line("left_half", "string", unstretched / 2, elements_per_half, "left",
                          "mid"),
        "right_half": Line("right_half", "string", unstretched / 2, elements_per_half, "mid",
                           "right"),
    }
    env = Environment(water_density=2.0, gravity=G_FT)
    return System("tuah-ex1", units="US", environment=env, line_types={"string": lt},
                  points=points, lines=lines)


def _deflection(load: float, settings: StaticsSettings) -> tuple[float, int, bool]:
    result = solve_statics(string_system(load), settings)
    return -float(result.point_position("mid")[2]), result.iterations, result.success


def run() -> list[Row]:
    """Deflection vs load with Newton; all three methods at 1000 lbf."""
    rows = []
    exact = {p: pin_jointed_string_deflection(p, SPAN, E * AREA, STRESS0 * AREA) for p in LOADS}
    newton = StaticsSettings(method="newton", tolerance=1e-10, start="straight")
    for p in LOADS:
        d, its, ok = _deflection(p, newton)
        rows.append(Row(CASE, f"midspan deflection, P = {p:g} lbf, newton", exact[p], d, 1e-3,
                        unit="ft", note=f"{its} Newton iterations" + ("" if ok else ", FAILED"),
                        kind="exact",
                        source=REFERENCE))
    relax = StaticsSettings(method="relaxation", tolerance=1e-6, max_iterations=400,
                            damping=1e5, damping_decrement=0.5, pseudo_dt=1.0,
                            stiffness_update=10, start="straight")
    d, its, ok = _deflection(1000.0, relax)
    rows.append(Row(CASE, "midspan deflection, P = 1000 lbf, viscous relaxation", exact[1000.0],
                    d, 1e-3, unit="ft",
                    note=f"{its} relaxation steps (Tuah: 44); C0=1e5, mu=0.5, K every 10",
                    kind="exact",
                    source=REFERENCE))
    d100, _, _ = _deflection(1000.0, StaticsSettings(method="incremental", load_steps=100,
                                                     start="straight"))
    d, its, _ = _deflection(1000.0, StaticsSettings(method="incremental", load_steps=1600,
                                                    start="straight"))
    drift = (d100 - exact[1000.0]) / exact[1000.0]
    rows.append(Row(CASE, "midspan deflection, P = 1000 lbf, purely incremental x1600",
                    exact[1000.0], d, 1e-3, unit="ft",
                    note=f"{its} increments; with Webster's 100 the drift is {drift:+.1%}",
                    kind="exact",
                    source=REFERENCE))
    return rows
