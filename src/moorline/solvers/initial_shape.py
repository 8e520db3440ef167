"""Starting configuration for statics: catenary profiles where the ends are known."""

from __future__ import annotations

import logging
from typing import Literal

import numpy as np
from numpy.typing import NDArray

from ..mesh import Mesh
from ..model import System
from .point_start import local_seabed

FloatArray = NDArray[np.float64]
logger = logging.getLogger(__name__)


def initial_positions(system: System, mesh: Mesh,
                      start: Literal["catenary", "straight"] = "catenary") -> FloatArray:
    """Node positions to start a static solution from, (n_nodes, 3).

    Lines with a user-given ``initial_shape`` take it. With ``start='catenary'`` every other
    line starts on the closed-form elastic catenary between its end positions (free points
    first moved to their equilibrium with every line a catenary,
    :func:`~moorline.solvers.point_start.presolve_free_points`), with seabed contact when an
    end lies on the seabed; where no catenary exists (or with ``start='straight'``) the line
    starts on its straight chord, as in Tuah (1982) Ex. 2. Free nodes the start puts on (or
    under) the seabed are lowered to the
    penetration at which the penalty seabed carries them
    (:meth:`~moorline.solvers.equilibrium.StaticModel.resting_penetration`), so that a lying
    line starts in vertical balance, not on the contact's kink.

    On a sloped or gridded seabed each line's catenary assumes a flat seabed at the height
    under its end nearer to the seabed (:func:`~moorline.solvers.point_start.local_seabed`,
    its anchor), and the free nodes it lays on that plane, or that end up below the real
    surface, are moved vertically onto the surface (the same resting penetration); Newton
    takes it from there.
    """
    x = mesh.node_prescribed_start.copy()
    if start == "catenary":
        from .point_start import presolve_free_points

        solved = presolve_free_points(system, mesh, x)
        if solved is not None:
            x = solved
    sink = np.zeros(mesh.n_nodes)
    reference = np.full(mesh.n_nodes, mesh.seabed_z)  # the flat seabed each line assumes
    if np.isfinite(mesh.seabed_z):
        from .equilibrium import StaticModel

        sink = StaticModel(mesh).resting_penetration()
    for k, line in enumerate(system.lines.values()):
        nodes = mesh.line_nodes[k]
        a, b = x[nodes[0]], x[nodes[-1]]
        if line.initial_shape is not None:
            x[nodes[1:-1]] = np.asarray(line.initial_shape, dtype=float)[1:-1]
            continue
        s = np.linspace(0.0, line.length, line.segments + 1)
        depth = float(sink[nodes[1:-1]].max(initial=0.0))
        shape = None
        if mesh.bathymetry is not None and start == "catenary":
            reference[nodes] = local_seabed(x, mesh.seabed_height(x), nodes[0], nodes[-1])
            shape = _sloped_shape(system, mesh, line, a, b, s)
            if shape is not None:
                reference[nodes] = -np.inf  # its lying nodes are on the surface itself
        if shape is None and start == "catenary":
            shape = _catenary_shape(system, line.line_type, line.length, a, b, s,
                                    float(reference[nodes[0]]), depth)
        if shape is not None:
            x[nodes[1:-1]] = shape[1:-1]
        else:
            x[nodes[1:-1]] = a + (s[1:-1, None] / line.length) * (b - a)
    if not np.isfinite(mesh.seabed_z):
        return x
    tol = 1e-9 * max(1.0, abs(mesh.seabed_z))
    bottom = mesh.seabed_height(x) if mesh.bathymetry is not None else reference
    lying = mesh.free_nodes & ((x[:, 2] <= reference + tol) | (x[:, 2] < bottom + tol))
    x[lying, 2] = bottom[lying] - sink[lying]
    return x


def _sloped_shape(system: System, mesh: Mesh, line, a: FloatArray, b: FloatArray,
                  s: FloatArray) -> FloatArray | None:
    """:func:`~moorline.solvers.sloped_start.sloped_catenary_shape` from the end of the line
    on the seabed (``None``: neither end on it, or no lying part)."""
    from .sloped_start import sloped_catenary_shape

    lt = system.line_types[line.line_type]
    env = system.environment
    EA = getattr(lt, "EA", None)
    if lt.EA_table is not None or not isinstance(EA, (int, float)):
        return None
    w = (lt.mass_per_length - env.water_density * lt.area_displaced) * env.gravity
    tol = 1e-6 * max(1.0, abs(mesh.seabed_z))
    bottom = mesh.seabed_height(np.array([a, b]))
    if a[2] <= bottom[0] + tol:
        return sloped_catenary_shape(mesh.bathymetry, a, b, s, line.length, EA, w)
    if b[2] <= bottom[1] + tol:
        shape = sloped_catenary_shape(mesh.bathymetry, b, a, line.length - s[::-1],
                                      line.length, EA, w)
        return None if shape is None else shape[::-1]
    return None


def _catenary_shape(system: System, type_name: str, length: float, a: FloatArray,
                    b: FloatArray, s: FloatArray, seabed_z: float,
                    sink: float = 0.0) -> FloatArray | None:
    """The closed-form profile at arc lengths ``s``; with an end on the seabed, solved with
    that end and the seabed ``sink`` lower (the penetration at which the lying nodes rest),
    so that lying and hanging nodes start in balance with each other; with both ends above
    the seabed and a sag that reaches it, the U-shape of
    :func:`moorline.catenary_touching.touching_3d` (unless it piles up)."""
    from ..catenary import CatenaryError, catenary_3d, profile_3d
    from .discrete_shape import discrete_catenary

    lt = system.line_types[type_name]
    env = system.environment
    w = (lt.mass_per_length - env.water_density * lt.area_displaced) * env.gravity
    tol = 1e-6 * max(1.0, abs(seabed_z)) if np.isfinite(seabed_z) else 0.0
    if np.isfinite(seabed_z) and min(a[2], b[2]) > seabed_z + tol and w > 0:
        from ..catenary_touching import touching_3d, touching_profile_3d

        touching = touching_3d(a, b, length, lt.EA, w, seabed_z - sink)
        if touching is not None and touching[2].H > 0.0:
            profile = touching_profile_3d(touching[2], a, b, s)
            if lt.EA_table is None:
                split = _discrete_touching(touching[2], profile, a, b, s, lt.EA, w)
                if split is not None:
                    return split
            return profile
    flip = bool(np.isfinite(seabed_z) and b[2] <= seabed_z + tol < a[2])
    pa, pb = (b, a) if flip else (a, b)
    on_seabed = bool(np.isfinite(seabed_z) and pa[2] <= seabed_z + tol)
    if on_seabed:
        pa = pa - np.array([0.0, 0.0, sink])
    try:
        _, _, sol = catenary_3d(pa, pb, length, lt.EA, w, seabed_contact=on_seabed,
                                seabed_friction=env.seabed.friction)
        sigma = length - s[::-1] if flip else s
        shape = profile_3d(sol, pa, pb, sigma)
        if sol.H == 0.0 and sol.seabed_length > 0.0:
            shape = _coil_pile(shape, sol, pa, sigma)
        elif lt.EA_table is None and env.seabed.friction == 0.0:
            exact = discrete_catenary(pa, pb, len(s) - 1, length, lt.EA, w, on_seabed and w > 0,
                                      sol.H, sol.V_b)
            if exact is not None:
                shape = exact
    except CatenaryError as err:
        logger.info("catenary start not available (%s); starting straight", err)
        return None
    return shape[::-1] if flip else shape


def _discrete_touching(sol, profile: FloatArray, a: FloatArray, b: FloatArray,
                       s: FloatArray, EA: float, w: float) -> FloatArray | None:
    """The finite elements' own equilibrium of a U-shaped line (:func:`discrete_catenary`
    on each side of a node in the middle of the lying stretch, each side resting on the
    seabed at that node), or ``None`` when no node lies inside the lying stretch."""
    from .discrete_shape import discrete_catenary

    inside = np.flatnonzero((s > sol.hanging_a) & (s < sol.length - sol.hanging_b))
    if len(inside) == 0:
        return None
    k = int(inside[len(inside) // 2])
    n = len(s) - 1
    side_a = discrete_catenary(profile[k], a, k, float(s[k]), EA, w, True, sol.H,
                               w * sol.hanging_a)
    side_b = discrete_catenary(profile[k], b, n - k, float(s[-1] - s[k]), EA, w, True,
                               sol.H, w * sol.hanging_b)
    if side_a is None or side_b is None:
        return None
    return np.vstack([side_a[::-1], side_b[1:]])


def _coil_pile(shape: FloatArray, sol, pa: FloatArray, sigma: FloatArray) -> FloatArray:
    """A slack pile laid out on the seabed so that none of its elements has zero length.

    The closed form draws the surplus length ``L_B`` of a slack line (``H = 0``) compressed
    uniformly over the horizontal span ``X``; when ``X < 0.4 L_B`` (a line hanging vertically
    over its anchor has ``X = 0``) the finite elements would start with (nearly) zero-length
    elements. Here the lying part ``0 <= sigma <= L_B`` goes once around a loop from the
    anchor to the touchdown, ``p(t) = A + t X e + rho (sin(2 pi t) e + (1 - cos(2 pi t)) n)``
    with ``t = sigma / L_B`` and ``2 pi rho = L_B / 2``: every element between 0.1 and 0.9 of
    its unstretched length, so slack, and all of them carry no force, as in the closed form.
    """
    lb, X = sol.seabed_length, sol.horizontal_span
    if X >= 0.4 * lb:
        return shape
    touchdown = shape[np.argmin(np.abs(sigma - lb))]
    d = touchdown[:2] - pa[:2]
    e = d / np.hypot(*d) if np.hypot(*d) > 0 else np.array([1.0, 0.0])
    n = np.array([-e[1], e[0]])
    lying = sigma <= lb
    t = sigma[lying] / lb
    rho = lb / (4.0 * np.pi)
    h = (t * X)[:, None] * e + rho * (np.sin(2 * np.pi * t)[:, None] * e
                                      + (1.0 - np.cos(2 * np.pi * t))[:, None] * n)
    out = shape.copy()
    out[lying, :2] = pa[:2] + h
    out[lying, 2] = pa[2]
    return out
