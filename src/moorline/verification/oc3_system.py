"""The OC3-Hywind three-line mooring system (dynamics benchmarks, the other-code cases).

Geometry and line properties: J. Jonkman (2010), NREL/TP-500-47535, table 4-1 (depth 320 m,
anchors at radius 853.87 m on the seabed at 0, 120 and 240 deg, fairleads at radius 5.2 m and
z = -70 m, 902.2 m of 0.09 m chain, 77.7066 kg/m, EA = 384.243e6 N). Hydrodynamic coefficients,
seabed contact and internal damping as in MoorDyn's OC3 example input: Cd 1.6, Ca 1.0, Ct 0.05,
Cat 0, BA = -0.8 (a damping ratio of 0.8 of each segment's axial mode), kBot 3e6 Pa/m, cBot
3e5 Pa s/m, no friction. All three fairleads surge together: 5 m amplitude, 10 s period,
smoothly ramped in over ``ramp_time``.
"""

from __future__ import annotations

import math

from ..model import Environment, Line, LineType, Motion, Point, Seabed, System
from .oc3_line import ANCHOR_R, DEPTH, DIAMETER, EA, FAIR_R, FAIR_Z, LENGTH, MASS, RHO, G

HEADINGS_DEG = (0.0, 120.0, 240.0)
AMPLITUDE, PERIOD = (5.0, 0.0, 0.0), 10.0


def chain(BA: float = -0.8) -> LineType:
    """The OC3 chain (MoorDyn's OC3 example coefficients)."""
    return LineType("chain", diameter=DIAMETER, mass_per_length=MASS, EA=EA, Cd=1.6, Ca=1.0,
                    Ct=0.05, Cat=0.0, BA=BA)


def environment() -> Environment:
    """Seawater, 320 m deep, MoorDyn's seabed contact (no friction)."""
    return Environment(depth=DEPTH, water_density=RHO, gravity=G,
                       seabed=Seabed(stiffness=3.0e6, damping=3.0e5, friction=0.0))


def surge(ramp_time: float = 10.0) -> Motion:
    """Fairlead surge: 5 m amplitude, 10 s period."""
    return Motion("harmonic", amplitude=AMPLITUDE, period=PERIOD, ramp_time=ramp_time)


def oc3_three_lines(segments: int, ramp_time: float = 10.0, BA: float = -0.8,
                    motion: Motion | None = None) -> System:
    """The three OC3 lines, ``segments`` elements each, all fairleads in harmonic surge.

    ``BA``: internal axial damping [N s], or minus a damping ratio of each segment's axial mode
    (MoorDyn's convention, the default -0.8: then the damping coefficient is proportional to
    the segment length and changes with the mesh). ``motion``: the fairleads' motion (default
    :func:`surge`).
    """
    points: dict[str, Point] = {}
    lines: dict[str, Line] = {}
    motion = surge(ramp_time) if motion is None else motion
    for k, heading in enumerate(HEADINGS_DEG, start=1):
        c, s = math.cos(math.radians(heading)), math.sin(math.radians(heading))
        anchor, fair = f"anchor{k}", f"fairlead{k}"
        points[anchor] = Point(anchor, "fixed", (ANCHOR_R * c, ANCHOR_R * s, -DEPTH))
        points[fair] = Point(fair, "prescribed", (FAIR_R * c, FAIR_R * s, FAIR_Z),
                             motion=motion)
        lines[f"line{k}"] = Line(f"line{k}", "chain", LENGTH, segments, anchor, fair)
    return System("oc3-three-lines", environment=environment(), line_types={"chain": chain(BA)},
                  points=points, lines=lines)


def oc3_one_line(segments: int, ramp_time: float = 10.0, BA: float = -0.8) -> System:
    """Line 1 of :func:`oc3_three_lines` alone (for the cost-per-step scaling)."""
    full = oc3_three_lines(segments, ramp_time, BA)
    keep = ("anchor1", "fairlead1")
    return System("oc3-one-line", environment=full.environment, line_types=full.line_types,
                  points={k: full.points[k] for k in keep},
                  lines={"line1": full.lines["line1"]})
