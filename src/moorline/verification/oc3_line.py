"""OC3-Hywind mooring line in still water against the closed-form elastic catenary.

Jonkman (2010), NREL/TP-500-47535, table 4-1: depth 320 m, anchor at 853.87 m radius on the
seabed, fairlead at 5.2 m radius and 70 m depth, 902.2 m of 0.09 m chain, 77.7066 kg/m,
EA = 384.243e6 N; seawater 1025 kg/m^3. Part of the line rests on the seabed (no friction).
The finite elements (100, from the catenary start) must converge in at most 8 Newton
iterations and give the end forces of the closed form
(:func:`moorline.catenary.solve_catenary`) within 0.1 %. The seabed is a penalty spring
(3e6 Pa/m) in the finite elements and rigid in the closed form; the difference (a few mm of
penetration) is far below the tolerance. The seabed length is resolved to one element.
"""

from __future__ import annotations

from functools import partial

import numpy as np

from ..catenary import solve_catenary
from ..model import Environment, Line, LineType, Point, StaticsSettings, System
from ..solvers.statics import solve_statics
from .core import Row

CASE = "oc3-line"
REFERENCE = "closed-form elastic catenary with seabed contact (catenary.solve_catenary)"
DEPTH, ANCHOR_R, FAIR_R, FAIR_Z = 320.0, 853.87, 5.2, -70.0
LENGTH, DIAMETER, MASS, EA, RHO, G = 902.2, 0.09, 77.7066, 384.243e6, 1025.0, 9.80665


#: submerged weight per unstretched length [N/m]
SUBMERGED_WEIGHT = (MASS - RHO * np.pi * DIAMETER**2 / 4) * G


def oc3_system(segments: int = 100) -> System:
    """One OC3-Hywind line from its anchor to its fairlead (prescribed)."""
    lt = LineType("chain", diameter=DIAMETER, mass_per_length=MASS, EA=EA, Cd=1.6, Ca=1.0,
                  Ct=0.05)
    points = {
        "anchor": Point("anchor", "fixed", (-ANCHOR_R, 0.0, -DEPTH)),
        "fairlead": Point("fairlead", "prescribed", (-FAIR_R, 0.0, FAIR_Z)),
    }
    lines = {"line1": Line("line1", "chain", LENGTH, segments, "anchor", "fairlead")}
    env = Environment(depth=DEPTH, water_density=RHO, gravity=G)
    return System("oc3-line", environment=env, line_types={"chain": lt}, points=points,
                  lines=lines)


def closed_form():
    """The closed-form catenary of the OC3 line."""
    return solve_catenary(ANCHOR_R - FAIR_R, FAIR_Z + DEPTH, LENGTH, EA, SUBMERGED_WEIGHT,
                          seabed_contact=True)


def run() -> list[Row]:
    """End forces, seabed length and Newton iterations against the closed form."""
    exact = closed_form()
    segments = 100
    result = solve_statics(oc3_system(segments), StaticsSettings(method="newton"))
    fair = result.end_force("line1", "b")
    anchor = result.end_force("line1", "a")
    note = f"{result.iterations} Newton iterations, {result.n_factorizations} factorizations"
    exact_row = partial(Row, CASE, kind="exact", source=REFERENCE)
    return [
        Row(CASE, "Newton iterations from the catenary start (at most 8)", 0.0,
            float(result.iterations), 8.0, relative=False, note=note,
            kind="internal cross-check", source="convergence requirement of the case"),
        exact_row("fairlead horizontal force", exact.H, -fair[0], 1e-3, unit="N"),
        exact_row("fairlead vertical force", exact.V_b, -fair[2], 1e-3, unit="N"),
        exact_row("fairlead tension", exact.tension_b, float(np.linalg.norm(fair)), 1e-3,
                  unit="N"),
        exact_row("anchor horizontal force", exact.force_a[0], anchor[0], 1e-3, unit="N"),
        exact_row("anchor vertical force (the line is tangent to the seabed)",
                  float(exact.force_a[1]), anchor[2], 1e-3 * exact.tension_a, relative=False,
                  unit="N", note="tolerance 0.1 % of the anchor tension"),
        exact_row("seabed length", exact.seabed_length, result.seabed_length("line1"),
                  LENGTH / segments, relative=False, unit="m"),
    ]
