"""Statics and stiffness against MoorPy (an independent quasi-static code, ``[compare]`` extra).

MoorPy 1.3 (NREL) solves each line as the closed-form elastic catenary on a rigid seabed and
gives analytic stiffness matrices; moorline solves the finite-element equilibrium of all nodes
on a penalty seabed (3e6 Pa/m) and condenses its exact tangent. Three systems
(:mod:`moorline.compare.moorpy_runner` builds the MoorPy models from the same moorline systems):

(a) the OC3-Hywind line (``cases/oc3_line.yaml``; Jonkman 2010, NREL/TP-500-47535, table 4-1),
    400 elements: end forces, fairlead tension, seabed length;
(b) the OC3 three-line system (:func:`~moorline.verification.oc3_system.oc3_three_lines`),
    400 elements a line: the 6x6 stiffness of the three fairleads tied to the platform's
    reference at the still water level (surge, sway, heave, pitch and yaw diagonal and the
    surge-pitch coupling), MoorPy's ``Body.getStiffnessA(lines_only=True)``;
(c) an S-line (:func:`s_line`): chain from the anchor up to a mid-water buoy, wire down to a
    clump weight and up to the fairlead: free point positions, end forces, tension, seabed
    length.

Tolerances come from the pair's converged difference (convergence study of moorline at 20 to
1600 elements; MoorPy does not depend on its segment count):

- forces: the FE forces converge (faster than O(h), oscillating as the touchdown moves
  between nodes) to 8.4e-5 (OC3) and 5-6e-5 (S-line) from MoorPy's. That converged offset
  is the penalty seabed's penetration ``delta = w / (k d)`` (2.8 mm for the OC3 chain): with a
  100 times stiffer seabed it falls to 5e-6. At the meshes used the mesh error is below 1e-5
  (OC3, 400 -> 800 elements: 1.6e-6). Tolerance 2e-4: the converged offset with a factor 2.
- positions of the free points (S-line): converged difference 9.6 mm (buoy height), 1.1 mm
  with the 100 times stiffer seabed; at the mesh used (160 chain elements) within 1 mm of the
  converged. Tolerance 0.02 m.
- seabed length: moorline counts the nodes below the seabed plane (one element of
  resolution); on the penalty seabed the line dips below the plane a distance
  ``sqrt(2 a delta)`` beyond the rigid touchdown (``a = H / w``, 2.4 m for OC3): tolerance one
  element plus that distance.
- stiffness: set by which node is nearest the touchdown (a contact state): over 300 to 1600
  elements the diagonal and coupling terms stay within 0.11 % of MoorPy's (0.41 % at 200,
  4.5 % at 50; 4e-5 at 1600); 400 elements give at most 0.09 %. Tolerance 0.2 %.
"""

from __future__ import annotations

import math

import numpy as np

from ..model import Environment, Line, LineType, Point, System
from ..solvers.statics import solve_statics
from ..solvers.stiffness import group_stiffness
from .core import CaseSkipped, Row
from .oc3_line import oc3_system
from .oc3_system import oc3_three_lines

CASE = "moorpy-statics"
SOURCE = "MoorPy 1.3 (NREL), same input"
FORCE_TOL = 2.0e-4
POSITION_TOL = 0.02  # m
STIFFNESS_TOL = 2.0e-3
OC3_SEGMENTS = 400
S_LINE_SEGMENTS = 160  # chain elements; the wires get 3/8 and 1/2 of that
FAIRLEADS = ("fairlead1", "fairlead2", "fairlead3")

#: S-line data: depth 200 m; studless chain (~100 mm: 200 kg/m, EA 854 MN, volume-equivalent
#: diameter 0.18 m) 400 m from the anchor on the seabed to a buoy (50 m^3, 12.5 t: 380 kN net
#: buoyancy); spiral-strand wire (40 kg/m, EA 600 MN, 0.08 m) 150 m down to a clump weight
#: (10 t of steel, 1.274 m^3: 85.3 kN in water) and 200 m up to the fairlead, 680 m from the
#: anchor and 20 m below the surface.
S_DEPTH, S_FAIRLEAD = 200.0, (680.0, 0.0, -20.0)


def _import() -> None:
    try:
        import moorpy  # noqa: F401
    except ImportError as exc:
        raise CaseSkipped("the [compare] extra (moorpy) is not installed") from exc


def s_line(chain_segments: int = S_LINE_SEGMENTS) -> System:
    """The S-line with a mid-water buoy and a clump weight (data: :data:`S_DEPTH` comment)."""
    types = {"chain": LineType("chain", diameter=0.18, mass_per_length=200.0, EA=854.0e6),
             "wire": LineType("wire", diameter=0.08, mass_per_length=40.0, EA=600.0e6)}
    points = {
        "anchor": Point("anchor", "fixed", (0.0, 0.0, -S_DEPTH)),
        "buoy": Point("buoy", "free", (360.0, 0.0, -100.0), mass=12500.0, volume=50.0),
        "clump": Point("clump", "free", (500.0, 0.0, -120.0), mass=10000.0,
                       volume=10000.0 / 7850.0),
        "fairlead": Point("fairlead", "prescribed", S_FAIRLEAD),
    }
    n = chain_segments
    lines = {"chain": Line("chain", "chain", 400.0, n, "anchor", "buoy"),
             "lower": Line("lower", "wire", 150.0, max(2, 3 * n // 8), "buoy", "clump"),
             "upper": Line("upper", "wire", 200.0, max(2, n // 2), "clump", "fairlead")}
    env = Environment(depth=S_DEPTH, water_density=1025.0, gravity=9.80665)
    return System("s-line", environment=env, line_types=types, points=points, lines=lines)


def _touchdown_spread(system: System, line: str, horizontal: float) -> float:
    """``sqrt(2 a delta)``: how far past the rigid touchdown a line on the penalty seabed dips
    below the seabed plane (``a = H / w``, ``delta = w / (k d)`` its penetration)."""
    lt = system.line_types[system.lines[line].line_type]
    env = system.environment
    w = (lt.mass_per_length - env.water_density * lt.area_displaced) * env.gravity
    delta = w / (env.seabed.stiffness * lt.diameter)
    return math.sqrt(2.0 * horizontal / w * delta)


def _force_rows(label: str, quantity: str, ref: np.ndarray, got: np.ndarray) -> list[Row]:
    """Horizontal, vertical and total end force rows (magnitudes)."""
    return [
        Row(CASE, f"{label}: {quantity} horizontal force", float(np.hypot(*ref[:2])),
            float(np.hypot(*got[:2])), FORCE_TOL, unit="N", kind="other code", source=SOURCE),
        Row(CASE, f"{label}: {quantity} vertical force", float(abs(ref[2])), float(abs(got[2])),
            FORCE_TOL, unit="N", kind="other code", source=SOURCE),
        Row(CASE, f"{label}: {quantity} tension", float(np.linalg.norm(ref)),
            float(np.linalg.norm(got)), FORCE_TOL, unit="N", kind="other code", source=SOURCE),
    ]


def _seabed_row(label: str, system: System, result, line: str, reference: float,
                horizontal: float) -> Row:
    element = system.lines[line].length / system.lines[line].segments
    spread = _touchdown_spread(system, line, horizontal)
    return Row(CASE, f"{label}: seabed length of {line}", reference,
               result.seabed_length(line), element + spread, relative=False, unit="m",
               kind="other code", source=SOURCE,
               note=f"tolerance: one element ({element:.2f} m) + penetration spread "
                    f"{spread:.2f} m")


def oc3_line_rows() -> list[Row]:
    """(a) The OC3 line: fairlead and anchor forces, tension, seabed length."""
    from ..compare.moorpy_runner import end_forces, solve_moorpy

    system = oc3_system(OC3_SEGMENTS)
    ms = solve_moorpy(system)
    ref_a, ref_b = end_forces(ms, 0)
    result = solve_statics(system)
    label = f"OC3 line ({OC3_SEGMENTS} el.)"
    rows = _force_rows(label, "fairlead", ref_b, result.end_force("line1", "b"))
    rows.append(Row(CASE, f"{label}: anchor horizontal force", float(ref_a[0]),
                    float(result.end_force("line1", "a")[0]), FORCE_TOL, unit="N",
                    kind="other code", source=SOURCE))
    rows.append(_seabed_row(label, system, result, "line1", float(ms.lineList[0].LBot),
                            float(ref_a[0])))
    return rows


def oc3_stiffness_rows() -> list[Row]:
    """(b) The OC3 three-line system: stiffness about its equilibrium at the platform's
    reference point (0, 0, 0)."""
    from ..compare.moorpy_runner import solve_moorpy

    system = oc3_three_lines(OC3_SEGMENTS)
    ms = solve_moorpy(system, body_points=FAIRLEADS)
    reference = ms.bodyList[0].getStiffnessA(lines_only=True)
    K = group_stiffness(solve_statics(system), list(FAIRLEADS), np.zeros(3))
    label = f"OC3 three lines ({OC3_SEGMENTS} el.)"
    entries = (("K11 surge", 0, 0, "N/m"), ("K22 sway", 1, 1, "N/m"),
               ("K33 heave", 2, 2, "N/m"), ("K55 pitch", 4, 4, "N m/rad"),
               ("K66 yaw", 5, 5, "N m/rad"), ("K15 surge-pitch", 0, 4, "N/rad"))
    return [Row(CASE, f"{label}: stiffness {name}", float(reference[i, j]), float(K[i, j]),
                STIFFNESS_TOL, unit=unit, kind="other code",
                source=SOURCE + " Body.getStiffnessA")
            for name, i, j, unit in entries]


def s_line_rows() -> list[Row]:
    """(c) The S-line: free point positions, fairlead and anchor forces, seabed length."""
    from ..compare.moorpy_runner import end_forces, solve_moorpy

    system = s_line()
    ms = solve_moorpy(system)
    result = solve_statics(system)
    names = list(system.points)
    label = "S-line"
    rows = []
    for point in ("buoy", "clump"):
        ref = ms.pointList[names.index(point)].r
        got = result.point_position(point)
        for axis, k in (("x", 0), ("z", 2)):
            rows.append(Row(CASE, f"{label}: {point} {axis}", float(ref[k]), float(got[k]),
                            POSITION_TOL, relative=False, unit="m", kind="other code",
                            source=SOURCE))
    lines = list(system.lines)
    _, ref_b = end_forces(ms, lines.index("upper"))
    ref_a, _ = end_forces(ms, lines.index("chain"))
    rows += _force_rows(label, "fairlead", ref_b, result.end_force("upper", "b"))
    rows.append(Row(CASE, f"{label}: anchor horizontal force", float(ref_a[0]),
                    float(result.end_force("chain", "a")[0]), FORCE_TOL, unit="N",
                    kind="other code", source=SOURCE))
    rows.append(_seabed_row(label, system, result, "chain",
                            float(ms.lineList[lines.index("chain")].LBot), float(ref_a[0])))
    return rows


def run(quick: bool = False) -> list[Row]:
    """All rows (statics is fast: the quick form is the full case)."""
    _import()
    return oc3_line_rows() + oc3_stiffness_rows() + s_line_rows()
