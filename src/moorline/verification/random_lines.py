"""Random feasible single-line geometries checked against the closed-form catenary.

Every geometry is one line from a fixed anchor to a fixed fairlead, drawn from one of the
categories of issue 10: ``catenary`` (touchdown on the seabed), ``taut`` (no touchdown, little
sag), ``very-slack`` (most of the line on the seabed), ``vertical-pile`` (hanging vertically or
nearly so from the fairlead, the surplus slack on the seabed; a fifth exactly vertical),
``lying`` (both ends on the seabed), ``u-shape`` (both ends in mid-water, the sag clear of the
seabed), ``buoyant`` (negative submerged weight, floating up from the anchor) and ``friction``
(a catenary with Coulomb friction on the lying part). Depth 20-3,000 m (log-uniform), chain,
wire, polyester or a buoyant line, 10-200 segments.

The reference is :func:`moorline.catenary.solve_catenary` (closed form, an independent method);
the finite elements must converge and give both end forces within a relative tolerance of it
(:func:`end_force_error`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..catenary import CatenaryError, CatenarySolution, catenary_3d, profile_3d
from ..model import Environment, Line, LineType, Point, Seabed, System

CATEGORIES = ("catenary", "taut", "very-slack", "vertical-pile", "lying", "u-shape",
              "buoyant", "friction")
RHO, G = 1025.0, 9.80665

# (mass [kg/m] per d^2 [m^2], EA [N] per d^2) of the volume-equivalent diameter d: chain and
# wire from Barltrop (1998) rules of thumb; polyester fibre of density 1,380 kg/m^3
_MATERIALS = {"chain": (19.9e3, 0.854e11), "wire": (5.0e3, 4.5e10),
              "polyester": (1380.0 * math.pi / 4.0, 2.5e9)}


@dataclass(frozen=True)
class Geometry:
    """One random line: its system and the closed-form solution it must match."""

    category: str
    material: str
    system: System
    exact: CatenarySolution
    anchor: tuple[float, float, float]
    fairlead: tuple[float, float, float]

    def exact_forces(self) -> tuple[np.ndarray, np.ndarray]:
        """Forces the line exerts on its anchor (end a) and fairlead (end b), 3-vectors."""
        lt = self.system.line_types["line"]
        line = self.system.lines["line"]
        fa, fb, _ = catenary_3d(self.anchor, self.fairlead, line.length, lt.EA,
                                self.exact.weight, seabed_friction=self.exact.seabed_friction,
                                seabed_contact=self._contact())
        return fa, fb

    def _contact(self) -> bool:
        return self.category not in ("u-shape",)


def _line_type(rng: np.random.Generator, material: str) -> LineType:
    d = float(rng.uniform(0.03, 0.2))
    area = math.pi * d * d / 4.0
    if material == "buoyant":  # a buoyant hose or synthetic line with floats
        mass, EA = float(rng.uniform(0.3, 0.8)) * RHO * area, float(rng.uniform(1e9, 5e10)) * d * d
    else:
        m, ea = _MATERIALS[material]
        mass, EA = m * d * d, ea * d * d
    return LineType("line", diameter=d, mass_per_length=mass, EA=EA)


def _sample(rng: np.random.Generator, category: str, w: float, EA: float, depth: float):
    """``(X, Z, L, anchor_height, mu)`` for a category; ``anchor_height`` above the seabed."""
    u = float(rng.uniform())
    if category in ("catenary", "friction", "very-slack"):
        Z = depth * float(rng.uniform(0.6, 1.0))
        X = Z * float(rng.uniform(0.5, 6.0))
        d = math.hypot(X, Z)
        f = float(rng.uniform(0.05, 0.95)) if category != "very-slack" else \
            float(rng.uniform(0.85, 0.98))
        mu = float(rng.uniform(0.1, 1.0)) if category == "friction" else 0.0
        return X, Z, d + f * (X + Z - d), 0.0, mu
    if category == "taut":
        Z = depth * float(rng.uniform(0.6, 1.0))
        X = Z * float(rng.uniform(0.05, 3.0))
        d = math.hypot(X, Z)
        slack = float(rng.uniform(-1.0, 1.0))  # negative: stretched
        return X, Z, d * (1.0 + (0.004 * slack if slack > 0 else 0.5 * slack * 2e-3)), 0.0, 0.0
    if category == "vertical-pile":
        Z = depth * float(rng.uniform(0.3, 1.0))
        extra = Z * float(rng.uniform(0.02, 1.0))
        X = 0.0 if u < 0.2 else extra * float(rng.uniform(0.0, 0.95))
        return X, Z, Z + extra, 0.0, 0.0
    if category == "lying":  # slack (surplus piled up) or stretched flat on the seabed
        L = depth * float(rng.uniform(0.5, 5.0))
        X = L * (float(rng.uniform(0.3, 0.999)) if u < 0.5 else 1.0 + float(rng.uniform(0, 2e-3)))
        return X, 0.0, L, 0.0, 0.0
    if category == "u-shape":
        X = depth * float(rng.uniform(0.2, 2.0))
        Z = X * float(rng.uniform(-0.3, 0.3))
        L = math.hypot(X, Z) * (1.0 + float(rng.uniform(0.01, 0.5)))
        return X, Z, L, 0.0, 0.0  # anchor height set by the caller (sag clear of the seabed)
    if category == "buoyant":
        Z = depth * float(rng.uniform(0.3, 0.9))
        X = Z * float(rng.uniform(0.05, 2.0))
        return X, Z, math.hypot(X, Z) * (1.0 + float(rng.uniform(0.001, 0.3))), 0.0, 0.0
    raise ValueError(f"unknown category {category!r}")


#: Most segments a geometry may need to be resolved (more: the geometry is drawn again).
MAX_SEGMENTS = 1000


def segments_needed(solution: CatenarySolution) -> int:
    """Elements that resolve the line: at least 20 (the lumped-weight elements' O(h^2) error
    reaches 0.5 % of the end force with about 10 on a sagging line), element length at most a
    tenth of the catenary parameter ``H / |w|`` (when ``H > 0``) and a hundredth of the
    suspended length (when part of the line lies on the seabed: the lumped-node contact
    misplaces up to half an element's weight at the touchdown), and with seabed friction at
    most ``0.01 max(H_a, 0.05 T_b) / (mu w)`` (the touchdown's misplacement moves the anchor
    tension by up to about ``mu w h / 2``)."""
    L, h = solution.length, math.inf
    hanging = L - solution.seabed_length
    if hanging <= 0.0:  # flat on the seabed: nothing to resolve
        return 1
    if solution.H > 0.0 and solution.weight != 0.0:
        h = 0.1 * solution.H / abs(solution.weight)
    if solution.seabed_length > 0.0:
        h = min(h, 0.01 * hanging)
    mu_w = solution.seabed_friction * solution.weight
    if mu_w > 0.0 and solution.seabed_length > 0.0:  # friction
        h = min(h, 0.01 * max(solution.H_a, 0.05 * solution.tension_b) / mu_w)
    return max(20, int(math.ceil(L / h)))


def random_geometry(rng: np.random.Generator, category: str, segments: int) -> Geometry:
    """One feasible random line of ``category`` with ``segments`` elements, more where the
    line needs them (:func:`segments_needed`, at most :data:`MAX_SEGMENTS`)."""
    material = "buoyant" if category == "buoyant" else str(
        rng.choice(["chain", "wire", "polyester"]))
    for _ in range(1000):
        lt = _line_type(rng, material)
        w = (lt.mass_per_length - RHO * lt.area_displaced) * G
        depth = float(np.exp(rng.uniform(np.log(20.0), np.log(3000.0))))
        X, Z, L, _, mu = _sample(rng, category, w, lt.EA, depth)
        heading = float(rng.uniform(0.0, 2.0 * math.pi))
        e = np.array([math.cos(heading), math.sin(heading), 0.0])
        contact = category != "u-shape"
        try:
            from ..catenary import solve_catenary

            sol = solve_catenary(X, Z, L, lt.EA, w, seabed_friction=mu, seabed_contact=contact)
        except CatenaryError:
            continue
        needed = segments_needed(sol)
        if needed > MAX_SEGMENTS or L / max(segments, needed) < 20.0 * lt.diameter:
            continue  # not resolved by a sane mesh: elements of at least 20 diameters
        z_a = -depth
        if category == "u-shape":  # lift both ends so that the sag clears the seabed
            sag = profile_3d(sol, (0.0, 0.0, 0.0), (X, 0.0, Z), np.linspace(0, L, 201))[:, 2]
            z_a = -depth + (-sag.min()) + 0.05 * depth + max(0.0, -Z)
            if z_a + max(Z, 0.0) > 0.0:
                continue
        anchor = np.array([0.0, 0.0, z_a])
        fair = anchor + X * e + np.array([0.0, 0.0, Z])
        if fair[2] > 1e-9:
            continue
        seabed = Seabed(friction=mu)
        env = Environment(depth=depth, water_density=RHO, gravity=G, seabed=seabed)
        points = {"anchor": Point("anchor", "fixed", tuple(anchor)),
                  "fairlead": Point("fairlead", "fixed", tuple(fair))}
        lines = {"line": Line("line", "line", L, max(segments, needed), "anchor", "fairlead")}
        system = System(f"{category}", environment=env, line_types={"line": lt},
                        points=points, lines=lines)
        return Geometry(category, material, system, sol, tuple(anchor), tuple(fair))
    raise RuntimeError(f"no feasible {category} geometry in 1000 draws")


def geometries(n: int, seed: int = 0, max_segments: int = 200) -> list[Geometry]:
    """``n`` random geometries, the categories in turn, 10 to ``max_segments`` segments."""
    rng = np.random.default_rng(seed)
    out = []
    for i in range(n):
        segments = int(rng.integers(10, max_segments + 1))
        out.append(random_geometry(rng, CATEGORIES[i % len(CATEGORIES)], segments))
    return out


def end_force_error(geometry: Geometry, result) -> float:
    """Largest relative end-force error of a static result against the closed form.

    Each end's error is ``|F_fe - F_exact|`` over the exact end force's magnitude, or over 5 %
    of the larger end force when the exact one is smaller than that (the anchor of a slack
    pile carries no force), and at least over 0.1 % of the line's weight (a line lying slack
    on the seabed has no end forces).
    """
    fa, fb = geometry.exact_forces()
    line = geometry.system.lines["line"]
    scale = max(np.linalg.norm(fa), np.linalg.norm(fb),
                1e-3 * abs(geometry.exact.weight) * line.length)
    errors = []
    for end, exact in (("a", fa), ("b", fb)):
        fe = result.end_force("line", end)
        errors.append(float(np.linalg.norm(fe - exact)) / max(np.linalg.norm(exact),
                                                               0.05 * scale))
    return max(errors)
