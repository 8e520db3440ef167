"""A cable in a steady uniform current reaches the static drag configuration.

A 100 m line hangs between two fixed points, A = (0, 0, -60) m and B = (70, 0, 0) m, in deep
water, with a uniform current of 1 m/s along +x switched on over 5 s. The dynamic run
(Morison drag on the relative velocity, Tuah 1982 sec. 3.2.a) settles to a steady shape; the
reference is the static equilibrium of the continuous elastic cable under its submerged
weight and the drag of the steady current, solved independently by shooting on the cable
equations (arc length ``s`` unstretched, tangent angle ``phi`` from horizontal):

    dT/ds = -f . t,   T dphi/ds = -f . n,   dx/ds = (1 + T/EA) cos(phi),
    dz/ds = (1 + T/EA) sin(phi),

with ``t = (cos phi, sin phi)``, ``n = (-sin phi, cos phi)`` and the load per unstretched
length ``f = (0, -w) + 1/2 rho Cd D |u_n| u_n + 1/2 rho Ct pi D |u_t| u_t`` for the flow
``u = (U, 0)`` split into its normal and tangential parts. The unknown tension and angle at A
are found so the integration lands on B. The rows compare the node positions of the finite
elements (40 elements) with the shooting solution at the same arc length, and the end
tensions.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import least_squares

from ..model import (
    Current,
    DynamicsSettings,
    Environment,
    Line,
    LineType,
    Point,
    StaticsSettings,
    System,
)
from ..solvers.dynamics import simulate
from ..solvers.statics import solve_statics
from .core import Row

CASE = "steady-current"
REFERENCE = "shooting solution of the elastic cable equations with current drag (scipy)"
A, B = np.array([0.0, 0.0, -60.0]), np.array([70.0, 0.0, 0.0])
LENGTH, DIAMETER, MASS, EA, CD, CT = 100.0, 0.05, 3.0, 1.0e7, 1.2, 0.01
RHO, G, U = 1025.0, 9.81, 1.0


def current_system(segments: int = 40) -> System:
    """The line between A and B in a 1 m/s current along +x."""
    lt = LineType("rope", diameter=DIAMETER, mass_per_length=MASS, EA=EA, Cd=CD, Ct=CT, Ca=1.0,
                  BA=-0.5)
    points = {"A": Point("A", "fixed", tuple(A)), "B": Point("B", "fixed", tuple(B))}
    lines = {"rope": Line("rope", "rope", LENGTH, segments, "A", "B")}
    env = Environment(water_density=RHO, gravity=G, current=Current(speed=U, heading_deg=0.0))
    return System("steady-current", environment=env, line_types={"rope": lt}, points=points,
                  lines=lines)


def _loads(phi: float) -> tuple[float, float]:
    """Tangential and normal components of the load per unstretched length at angle phi."""
    w = (MASS - RHO * math.pi * DIAMETER**2 / 4) * G
    t = np.array([math.cos(phi), math.sin(phi)])
    n = np.array([-math.sin(phi), math.cos(phi)])
    u = np.array([U, 0.0])
    u_t = (u @ t) * t
    u_n = u - u_t
    drag = (0.5 * RHO * CD * DIAMETER * np.linalg.norm(u_n) * u_n
            + 0.5 * RHO * CT * math.pi * DIAMETER * np.linalg.norm(u_t) * u_t)
    f = drag + np.array([0.0, -w])
    return float(f @ t), float(f @ n)


def _rhs(s, y):
    T, phi, _, _ = y
    ft, fn = _loads(phi)
    stretch = 1 + T / EA
    return [-ft, -fn / T, stretch * math.cos(phi), stretch * math.sin(phi)]


def shooting_solution(s_eval: np.ndarray) -> tuple[np.ndarray, float, float]:
    """Positions (x, z) at ``s_eval`` and the tensions at A and B of the continuous cable."""
    span = B[[0, 2]] - A[[0, 2]]

    def miss(p):
        sol = solve_ivp(_rhs, (0, LENGTH), [p[0], p[1], 0.0, 0.0], rtol=1e-11, atol=1e-10)
        return sol.y[2:, -1] - span

    guess = [2000.0, math.atan2(span[1], span[0]) - 0.3]
    p = least_squares(miss, guess, x_scale=[1000.0, 1.0], xtol=1e-14, ftol=1e-14).x
    sol = solve_ivp(_rhs, (0, LENGTH), [p[0], p[1], 0.0, 0.0], t_eval=s_eval, rtol=1e-11,
                    atol=1e-10)
    xz = sol.y[2:].T + A[[0, 2]]
    return xz, float(p[0]), float(sol.y[0, -1])


def run() -> list[Row]:
    """Steady positions and end tensions against the shooting solution."""
    segments = 40
    system = current_system(segments)
    settings = DynamicsSettings(duration=120.0, dt=0.1, ramp_time=5.0)
    result = simulate(system, settings, output_every=1.0)
    nodes = result.positions[-1][result.mesh.line_nodes[0]]
    s = np.linspace(0.0, LENGTH, segments + 1)
    xz, T_a, T_b = shooting_solution(s)
    error = float(np.max(np.hypot(nodes[:, 0] - xz[:, 0], nodes[:, 2] - xz[:, 1])))
    motion = float(np.abs(result.positions[-1] - result.positions[-11]).max())
    end = result.end_force[-1, 0]
    return [
        Row(CASE, "largest node distance from the shooting solution", 0.0, error,
            1e-3 * LENGTH, relative=False, unit="m",
            note=f"40 elements; motion over the last 10 s {motion:.1e} m (steady)",
            kind="exact", source=REFERENCE),
        Row(CASE, "tension at A", T_a, float(np.linalg.norm(end[0])), 5e-3, unit="N",
            kind="exact", source=REFERENCE),
        Row(CASE, "tension at B", T_b, float(np.linalg.norm(end[1])), 5e-3, unit="N",
            kind="exact", source=REFERENCE),
        Row(CASE, "steady: largest node motion over the last 10 s", 0.0, motion, 1e-4,
            relative=False, unit="m", kind="exact", source=REFERENCE),
        *static_rows(system, s, xz, T_a, result),
    ]


def static_rows(system, s, xz, T_a, dynamic) -> list[Row]:
    """The same equilibrium by the statics with the current's drag (``current_drag``)."""
    static = solve_statics(system, StaticsSettings(current_drag=True, tolerance=1e-10))
    nodes = static.positions[static.mesh.line_nodes[0]]
    error = float(np.max(np.hypot(nodes[:, 0] - xz[:, 0], nodes[:, 2] - xz[:, 1])))
    to_dynamic = float(np.abs(static.positions - dynamic.positions[-1]).max())
    end = static.end_force("rope", "a")
    return [
        Row(CASE, "statics with current drag: largest node distance from the shooting "
            "solution", 0.0, error, 1e-3 * LENGTH, relative=False, unit="m",
            note=f"{static.iterations} Newton iterations; from the steady dynamic state: "
                 f"{to_dynamic:.1e} m", kind="exact", source=REFERENCE),
        Row(CASE, "statics with current drag: tension at A", T_a,
            float(np.linalg.norm(end)), 5e-3, unit="N", kind="exact", source=REFERENCE),
    ]
