"""Free-point start for statics: the points' equilibrium with every line a closed-form catenary.

A system whose free points join several lines (a buoy between two lines, a W-shaped line, a
tripod of lines on floats) gives Newton on the finite-element mesh a poor start when the
points sit at the user's guesses: each line starts on the catenary between guessed ends, the
points are far from balance, and the first steps fold the lines. Here the free points alone
are solved first, as a quasi-static model does (MoorPy's approach, Hall 2018): every line is
its elastic catenary between its end points (:func:`moorline.catenary.catenary_3d`, with
seabed contact from an end on the seabed), each point carries its weight, buoyancy and
external force, and a point that reaches the seabed rests on a stiff penalty spring. The
3 x n_points balance is solved by least squares (scipy's ``least_squares``, trust-region
reflective, finite-difference Jacobian); the finite-element lines then start on the
catenaries between the solved points (:func:`moorline.solvers.initial_shape.initial_positions`).

The catenary leaves out what the finite-element model adds (seabed contact in the middle of
a line between two points above the seabed, current drag, bending), so the result is a start
only; where no catenary exists for a trial (an over-stretched line) the line acts as a taut
elastic bar. Points attached to bodies and prescribed or fixed points stay where they are.
"""

from __future__ import annotations

import logging
import math

import numpy as np
from numpy.typing import NDArray

from ..mesh import Mesh
from ..model import System

FloatArray = NDArray[np.float64]
logger = logging.getLogger(__name__)

#: Largest number of free points solved this way (3 unknowns each, a dense Jacobian).
MAX_POINTS = 60


def _line_end_forces(pa: FloatArray, pb: FloatArray, length: float, EA: float, w: float,
                     seabed_z: float, friction: float) -> tuple[FloatArray, FloatArray]:
    """Forces the line exerts on its ends A and B: its catenary, or a taut elastic bar where
    no catenary exists. An end at or below the seabed (a point resting on the penalty
    seabed) lies on it: the catenary has seabed contact at that end's height; a line whose
    ends are both above the seabed but whose sag reaches it touches it in between
    (:func:`moorline.catenary_touching.touching_3d`); the two agree as an end comes down to
    the seabed."""
    from ..catenary import CatenaryError, catenary_3d

    tol = 1e-9 * length if math.isfinite(seabed_z) else 0.0
    flip = bool(math.isfinite(seabed_z) and pb[2] <= seabed_z + tol < pa[2])
    a, b = (pb, pa) if flip else (pa, pb)
    contact = bool(math.isfinite(seabed_z) and a[2] <= seabed_z + tol and w > 0)
    if math.isfinite(seabed_z) and w > 0 and not contact:
        from ..catenary_touching import touching_3d

        touching = touching_3d(pa, pb, length, EA, w, seabed_z)
        if touching is not None:
            return touching[0], touching[1]
    try:
        fa, fb, _ = catenary_3d(a, b, length, EA, w, seabed_contact=contact,
                                seabed_friction=friction if contact else 0.0)
    except CatenaryError:
        d = b - a
        dist = float(np.linalg.norm(d))
        unit = d / dist if dist > 0 else np.array([0.0, 0.0, 1.0])
        tension = EA * max(dist / length - 1.0, 0.0)
        half = 0.5 * w * length * np.array([0.0, 0.0, -1.0])
        fa, fb = tension * unit + half, -tension * unit + half
    return (fb, fa) if flip else (fa, fb)


def local_seabed(x: FloatArray, bottom: FloatArray, a: int, b: int) -> float:
    """The flat seabed a line's closed-form catenary assumes, given the seabed height
    ``bottom`` under every node: the height under the end nearer to the seabed (its anchor;
    ``-inf`` without a seabed). On a sloped or gridded seabed the catenary is a start only,
    which the finite elements then bring onto the real surface."""
    end = a if x[a, 2] - bottom[a] <= x[b, 2] - bottom[b] else b
    return float(bottom[end])


def presolve_free_points(system: System, mesh: Mesh, x: FloatArray) -> FloatArray | None:
    """Node positions ``x`` with the free points moved to their catenary equilibrium.

    Parameters
    ----------
    system, mesh
        The case and its mesh.
    x
        Node positions (n_nodes, 3): prescribed and fixed ends where they are, free points at
        their initial guesses.

    Returns
    -------
    ndarray or None
        A copy of ``x`` with the free points moved, or ``None`` when there is nothing to
        solve (no free point, too many, a line type without a constant ``EA``) or the solve
        did not reduce the force imbalance (the caller keeps its start).
    """
    free = [k for k, kind in enumerate(mesh.point_kind) if kind == "free"]
    if not free or len(free) > MAX_POINTS or not system.lines:
        return None
    env = system.environment
    rho, g = env.water_density, env.gravity
    nodes = np.asarray([int(mesh.point_node[k]) for k in free])
    slot = {int(n): i for i, n in enumerate(nodes)}
    lines = []
    for k, line in enumerate(system.lines.values()):
        lt = system.line_types[line.line_type]
        EA = getattr(lt, "EA", None)
        if not isinstance(EA, (int, float)) or not EA > 0:
            return None
        w = (lt.mass_per_length - rho * lt.area_displaced) * g
        ends = mesh.line_nodes[k][[0, -1]]
        if int(ends[0]) in slot or int(ends[1]) in slot:
            lines.append((int(ends[0]), int(ends[1]), float(line.length), float(EA), float(w)))
    if not lines:
        return None
    own = np.zeros((len(nodes), 3))
    own[:, 2] = (rho * mesh.node_volume[nodes] - mesh.node_mass[nodes]) * g
    own += mesh.node_force[nodes]
    seabed_z, friction = float(mesh.seabed_z), float(env.seabed.friction)
    sloped = mesh.bathymetry is not None
    scale = max(1.0, float(np.abs(own).max(initial=0.0)),
                max(abs(w) * length for _, _, length, _, w in lines))
    span = max(length for _, _, length, _, _ in lines)
    k_seabed = 1e3 * scale / span  # a point 1e-3 of the longest line deep carries `scale`

    def imbalance(q: FloatArray) -> FloatArray:
        pos = x.copy()
        pos[nodes] = q.reshape(-1, 3)
        total = own.copy()
        bottom = mesh.seabed_height(pos) if sloped else np.full(len(pos), seabed_z)
        for a, b, length, EA, w in lines:
            fa, fb = _line_end_forces(pos[a], pos[b], length, EA, w,
                                      local_seabed(pos, bottom, a, b), friction)
            if a in slot:
                total[slot[a]] += fa
            if b in slot:
                total[slot[b]] += fb
        if math.isfinite(seabed_z):
            total[:, 2] += k_seabed * np.maximum(bottom[nodes] - pos[nodes, 2], 0.0)
        return total.ravel() / scale

    from scipy.optimize import least_squares

    q0 = x[nodes].ravel()
    r0 = float(np.abs(imbalance(q0)).max())
    try:
        sol = least_squares(imbalance, q0, method="trf", x_scale=span, xtol=1e-12,
                            ftol=1e-12, gtol=1e-12, max_nfev=200 * (len(q0) + 1))
    except (ValueError, FloatingPointError) as exc:
        logger.info("free-point presolve failed (%s); keeping the initial guesses", exc)
        return None
    r1 = float(np.abs(sol.fun).max())
    if not np.all(np.isfinite(sol.x)) or not r1 < r0:
        return None
    logger.info("free points presolved on catenaries: imbalance %.3g -> %.3g of %.3g N",
                r0, r1, scale)
    out = x.copy()
    out[nodes] = sol.x.reshape(-1, 3)
    return out
