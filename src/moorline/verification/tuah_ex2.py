"""Tuah (1982) Example 2 (sec. 6.2): suspended two-segment cable with a buoyant load.

Segments of 500 ft (from A) and 1000 ft between A = (0, 0) and B = (1200, 500) ft, a 900 lbf
buoyant (upward) load at their junction, A0 = 0.0218 ft^2, E = 8.12e6 psf, cable density
3.35 slug/ft^3 in fluid of 2.0 slug/ft^3; 6 elements. As in the source, the solution starts
from a straight line to (1417, 500) ft and moves the support B to its place while the weight
and the buoyant load are applied, over 20 increments, by viscous relaxation; slack elements
keep a tiny modulus (``slack_stiffness_ratio``). The initial stress of 0.5 psf (strain 6e-8)
is negligible and the lengths are taken as unstretched.

Reference: the exact two-segment catenary with the point force at the junction
(:func:`~moorline.verification.references.two_segment_catenary`). Tuah compares with the
inextensible catenary; the finite elements are extensible, so the rows compare with the
elastic two-segment catenary, and a row reports how far extensibility moves the junction
(about 1.5 ft up, from the inextensible (382.98, 301.27) ft).

With 6 straight elements the lumped-load polygon cannot lie on the catenary exactly (error
O(h^2)); the 6-element rows allow 1 % of the span (3 % on H), the refined rows (60 elements)
0.01 % of the span (0.1 % on H): ten times finer, a hundred times closer.
"""

from __future__ import annotations

import math

import numpy as np

from ..model import Environment, Line, LineType, Point, StaticsSettings, System
from ..solvers.statics import solve_statics
from .core import Row
from .references import G_FT, tuah_ex2_reference

CASE = "tuah-ex2"
REFERENCE = "two-segment elastic catenary with a point load, solved independently (references)"
AREA, E, RHO_CABLE, RHO_WATER, LOAD = 0.0218, 8.12e6, 3.35, 2.0, 900.0
SPAN = math.hypot(1200.0, 500.0)


def ex2_system(elements: tuple[int, int] = (2, 4)) -> System:
    """The Example 2 cable with ``elements`` = elements on the (500 ft, 1000 ft) segments."""
    lt = LineType("cable", diameter=math.sqrt(4 * AREA / math.pi),
                  mass_per_length=RHO_CABLE * AREA, EA=E * AREA, displaced_area=AREA)
    points = {
        "A": Point("A", "fixed", (0.0, 0.0, 0.0)),
        "J": Point("J", "free", (1417.0 / 3, 0.0, 500.0 / 3), force=(0.0, 0.0, LOAD)),
        "B": Point("B", "prescribed", (1200.0, 0.0, 500.0), initial_position=(1417.0, 0.0, 500.0)),
    }
    lines = {
        "lower": Line("lower", "cable", 500.0, elements[0], "A", "J"),
        "upper": Line("upper", "cable", 1000.0, elements[1], "J", "B"),
    }
    env = Environment(water_density=RHO_WATER, gravity=G_FT)
    return System("tuah-ex2", units="US", environment=env, line_types={"cable": lt},
                  points=points, lines=lines)


RELAXATION = StaticsSettings(method="relaxation", load_steps=20, tolerance=1e-8,
                             max_iterations=2000, damping=1e5, damping_decrement=0.5,
                             stiffness_update=10, start="straight")


def run() -> list[Row]:
    """Junction position and anchor force against the elastic two-segment catenary."""
    exact = tuah_ex2_reference(EA=E * AREA)
    rigid = tuah_ex2_reference()
    rows = []
    coarse = solve_statics(ex2_system(), RELAXATION)
    fine = solve_statics(ex2_system((20, 40)), StaticsSettings(method="newton", load_steps=20,
                                                                start="straight"))
    for label, result, tol, tol_h in (("6 el., relaxation", coarse, 0.01, 0.03),
                                       ("60 el., newton", fine, 1e-4, 1e-3)):
        junction = result.point_position("J")
        note = f"{result.iterations} iterations, success={result.success}"
        rows.append(Row(CASE, f"junction x [{label}]", exact.junction[0], junction[0],
                        tol * SPAN, relative=False, unit="ft", note=note, kind="exact",
                        source=REFERENCE))
        rows.append(Row(CASE, f"junction z [{label}]", exact.junction[1], junction[2],
                        tol * SPAN, relative=False, unit="ft", note=note, kind="exact",
                        source=REFERENCE))
        H = result.end_force("lower", "a")[0]
        rows.append(Row(CASE, f"horizontal tension H [{label}]", exact.H, H, tol_h,
                        unit="lbf", kind="exact",
                        source=REFERENCE))
    shift = float(np.hypot(*(np.asarray(exact.junction) - np.asarray(rigid.junction))))
    rows.append(Row(CASE, "junction shift by extensibility, 60 el. vs inextensible", shift,
                    float(np.hypot(fine.point_position("J")[0] - rigid.junction[0],
                                   fine.point_position("J")[2] - rigid.junction[1])),
                    0.1, relative=False, unit="ft",
                    note=f"inextensible junction ({rigid.junction[0]:.2f}, "
                         f"{rigid.junction[1]:.2f}) ft, H = {rigid.H:.1f} lbf", kind="exact",
                         source=REFERENCE))
    return rows
