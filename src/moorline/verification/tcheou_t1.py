"""Tcheou (1997) sec. 5.1, Table 5.1: the static line under a given top force.

Anchor fixed; at the top the outside pulls with H = 4000 N, V = 8000 N; L = 600 m,
E = 1e9 Pa, A = 2e-4 m^2, fluid 1000 kg/m^3, displaced area 2e-4 m^2, g = 9.81; steel
7000 kg/m^3 and synthetic 2000 kg/m^3. The line hangs freely (V exceeds its submerged weight,
7063 N steel, 1177 N synthetic). The reference is the closed-form elastic catenary
(Tcheou eq. 3.27 for the position, eq. 3.25 for the tension), through
:func:`moorline.catenary.hanging_from_forces`.

Tcheou's own finite elements carry an approximation (his eq. 3.36) and converge to a curve
slightly off the closed form; ours need not: straight 2-node elements with lumped weight
converge to the closed form at second order in the element length. Rows: the top position
with 5, 10 and 150 elements, the observed order between 5 and 10 elements, and the anchor
tension.
"""

from __future__ import annotations

import math

import numpy as np

from ..catenary import hanging_from_forces, solve_catenary
from ..model import Environment, Line, LineType, Point, StaticsSettings, System
from ..solvers.statics import solve_statics
from .core import Row

CASE = "tcheou-t1"
REFERENCE = "closed-form elastic catenary, Tcheou (1997) eqs. 3.25, 3.27"
H, V, LENGTH, E, AREA, RHO_WATER, G = 4000.0, 8000.0, 600.0, 1.0e9, 2.0e-4, 1000.0, 9.81
MATERIALS = {"steel": 7000.0, "synthetic": 2000.0}
SETTINGS = StaticsSettings(method="newton", tolerance=1e-10, max_iterations=100)


def t1_system(density: float, elements: int) -> System:
    """The Table 5.1 line of cable density ``density`` with ``elements`` elements."""
    lt = LineType("cable", diameter=math.sqrt(4 * AREA / math.pi), mass_per_length=density * AREA,
                  EA=E * AREA, displaced_area=AREA)
    points = {
        "anchor": Point("anchor", "fixed", (0.0, 0.0, 0.0)),
        # initial guess only: a point up and across, not the answer
        "top": Point("top", "free", (0.5 * LENGTH, 0.0, 0.7 * LENGTH), force=(H, 0.0, V)),
    }
    lines = {"line": Line("line", "cable", LENGTH, elements, "anchor", "top")}
    env = Environment(water_density=RHO_WATER, gravity=G)
    return System("tcheou-t1", environment=env, line_types={"cable": lt}, points=points,
                  lines=lines)


def _top_error(density: float, elements: int, exact: np.ndarray) -> tuple[np.ndarray, object]:
    result = solve_statics(t1_system(density, elements), SETTINGS)
    top = result.point_position("top")
    return np.array([top[0], top[2]]), result


def run() -> list[Row]:
    """Top position convergence and anchor tension, steel and synthetic."""
    rows = []
    for name, density in MATERIALS.items():
        w = (density - RHO_WATER) * AREA * G
        X, Z = hanging_from_forces(H, V, LENGTH, E * AREA, w)
        exact = np.array([X, Z])
        errors = {}
        for n in (5, 10, 150):
            top, result = _top_error(density, n, exact)
            errors[n] = float(np.linalg.norm(top - exact))
            note = f"{result.iterations} Newton iterations"
            tol = {5: 5e-3, 10: 1.5e-3, 150: 1e-5}[n]  # O(h^2): ~4x per halving
            rows.append(Row(CASE, f"{name}: top x, {n} elements", X, top[0], tol, unit="m",
                            note=note, kind="exact",
                            source=REFERENCE))
            rows.append(Row(CASE, f"{name}: top z, {n} elements", Z, top[1], tol, unit="m",
                            note=note, kind="exact",
                            source=REFERENCE))
        order = math.log2(errors[5] / errors[10])
        rows.append(Row(CASE, f"{name}: convergence order, 5 -> 10 elements", 2.0, order, 0.15,
                        relative=False, note=f"errors {errors[5]:.3g} m, {errors[10]:.3g} m, "
                                              f"{errors[150]:.3g} m (150 el.)", kind="exact",
                        source="2-node elements with lumped weight: second order"))
        sol = solve_catenary(X, Z, LENGTH, E * AREA, w, seabed_contact=False)
        anchor = float(np.linalg.norm(result.end_force("line", "a")))
        rows.append(Row(CASE, f"{name}: anchor tension, 150 elements (eq. 3.25)",
                        sol.tension_a, anchor, 1e-4, unit="N", kind="exact",
                        source=REFERENCE))
    return rows
