"""Wang, Er and Iu: static draft of the moored floating box (case W1).

Data (the paper's Tables 1 and 2): box ``w_a x w_b x w_c = 26 x 5 x 10`` m (length, height,
width), mass ``M = 1.2e5`` kg; four steel lines ``E = 2e11`` Pa, ``D = 0.1`` m, density
8000 kg/m^3; depth ``h = 100`` m; inclination ``theta = 50`` deg; sag-to-span ``d/l = 1/60``;
sea water ``rho_s = 1025`` kg/m^3. The paper reports the submerged height (draft)
``h_s = 0.896`` m from its eq. (1),

    F_f + F_A2 + F_B2 + F_C2 + F_D2 = M g,    F_f = rho_s g h_s w_a w_c,

where ``F_X2`` is the vertical (paper: y) component of the line pretension at node X. The
paper's y axis is vertical; here z is up, x runs along the 26 m length and y across the 10 m
width. ``g`` cancels from eq. (1) (every term is a weight), so ``g = 9.81`` is immaterial.

Geometry (stated here because the paper gives it only in its lost Figs. 1-3)
----------------------------------------------------------------------------
* The body frame origin is the box centre (the paper's centroid O); the centre of gravity is
  taken at O and the inertia is that of a uniform solid box (the paper gives neither; they do
  not enter the static draft).
* Fairleads A, B, C, D at the four keel corners, body frame ``(+-13, +-5, -2.5)`` m, i.e. at
  depth ``h_s`` below the still water level when the box floats level.
* Each line's chord runs from its fairlead down to the seabed at ``theta`` to the horizontal,
  across the remaining depth ``h - h_s``: chord ``l = (h - h_s) / sin(theta)``, horizontal
  span ``(h - h_s) / tan(theta)``. The anchors are placed where the chord meets the seabed, so
  they depend on the draft.
* Azimuth (``layout``). The paper: "C1, C2 and C3, C4 are symmetric about the y-axis in the
  plane x1Oy and x2Oy", and "w_l is the distance between the nodes A and B". Both planes pass
  through O and w_l is a separate parameter from w_a, so the default ``layout="diagonal"``
  puts each line in the vertical plane through O and its corner (C1, C2 along one diagonal,
  C3, C4 along the other; w_l = 27.86 m). ``layout="parallel"`` runs all four lines along
  +-x in the vertical planes y = +-5 m through the long keel edges (C1, C2 in y = +5 m,
  C3, C4 in y = -5 m). The draft does not depend on the azimuth (only vertical forces enter
  eq. (1)); the W2/W3 surge response does, mildly.
* Sag-to-span ``d/l``: ``d`` is measured at mid-chord, perpendicular to the chord, and ``l``
  is the chord ("inclined length").

Three references for the draft
------------------------------
1. *Paper formula* (:func:`parabolic_draft`): small-sag (parabolic) cable under its submerged
   weight ``w`` per length. The transverse load ``w cos(theta)`` per chord length gives the
   chord tension ``T = w cos(theta) l^2 / (8 d)``; with ``H = T cos(theta)`` the moment of
   the line about its anchor gives the top vertical force ``V = T sin(theta) + w l / 2``.
   Since ``l = (h - h_s) / sin(theta)`` and ``d = l (d/l)``, eq. (1) is linear in ``h_s``::

       h_s = (M + 4 k w h / (g sin(theta))) / (rho_s w_a w_c + 4 k w / (g sin(theta))),
       k = cos(theta) sin(theta) / (8 d/l) + 1/2,

   0.89631 m (+0.03 % from 0.896): this reading reproduces the paper. Other readings
   (:func:`parabolic_draft` keywords): dry weight 616.4 N/m instead of the submerged
   537.4 N/m gives 0.962 m (+7 %); sag measured vertically (``d_v = l/60``, i.e. a tauter
   line) gives 1.113 m (+24 %); chord across the full depth (fairlead at the water level)
   gives 0.900 m (+0.48 %); chord from the box centre (rise ``h - h_s + w_b/2``) gives
   0.908 m (+1.3 %). Only the keel-corner, perpendicular-sag, submerged-weight reading lands
   within 0.1 %.
2. *Exact elastic catenary* (:func:`catenary_line`, :func:`catenary_draft`): the closed-form
   elastic catenary (:func:`moorline.catenary.solve_catenary`, no seabed contact) through the
   fairlead and the anchor, with the unstretched length ``L`` solved so that the
   perpendicular distance from the chord midpoint to the cable is ``l/60``; eq. (1) with its
   top vertical force: 0.89739 m (+0.16 %; L = 129.438 m on a 129.369 m chord).
3. *Finite elements* (:func:`wang_equilibrium`): the box as a free :class:`~moorline.model.Body`
   with box hydrostatics on four lines of 11 straight elements, solved with the lines in one
   Newton system (:func:`~moorline.solvers.statics.solve_statics`). The anchors and the ``L``
   of item 2 depend on the draft, so the draft is found as a fixed point: draft guess -> anchors and
   ``L`` -> coupled statics -> new draft, with secant updates (converged to 1e-9 m in four
   statics solves; plain substitution contracts only by ~0.57 per pass because the taut
   lines stretch when the body settles): 0.89595 m (-0.006 % from 0.896).

The finite element draft differs from the catenary's by the discretization error of the
straight elements, which is predicted a priori (:func:`discretization_estimate`): the
polygon of ``n`` chords inscribed in the cable is shorter than the arc by
``L (h kappa)^2 / 24`` (``h = L/n``, curvature ``kappa = w cos(theta) / T``), so the elements
carry that much slack the continuous line does not; the line's compliance
``L/EA + (w cos(theta))^2 l^3 / (12 T^3)`` turns it into a tension loss (0.37 % at 11
elements), which lowers the top vertical force by ``dT sin(theta)`` and the draft by
``4 dV / (rho_s g w_a w_c)`` (-0.16 %; measured -0.160 %, and -0.040 % with 22 elements:
order 2.0). The FE-vs-catenary draft tolerance, 0.3 %, is about twice this estimate at
11 elements; the estimate itself is checked to 20 %.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np
from scipy.optimize import brentq

from ..catenary import CatenarySolution, solve_catenary
from ..model import Body, Environment, Hydrostatics, Line, LineType, Point, StaticsSettings, System
from ..results import StaticResult
from ..solvers.statics import solve_statics
from .core import Row

CASE = "wang-w1"
PAPER = "Wang, Er & Iu: the static draft h_s = 0.896 m"
EXACT = "closed-form elastic catenary of each line + eq. (1)"
PAPER_DRAFT = 0.896  # m, the paper's h_s from eq. (1)

# Table 2 (body) and Table 1 (lines); sea water
BOX_LENGTH, BOX_HEIGHT, BOX_WIDTH, BOX_MASS = 26.0, 5.0, 10.0, 1.2e5  # w_a, w_b, w_c, M
YOUNG, DIAMETER, CABLE_DENSITY = 2.0e11, 0.1, 8000.0
DEPTH, INCLINATION_DEG, SAG_TO_SPAN = 100.0, 50.0, 1.0 / 60.0
RHO, G = 1025.0, 9.81

AREA = math.pi * DIAMETER**2 / 4.0
EA = YOUNG * AREA
DRY_WEIGHT = CABLE_DENSITY * AREA * G  # N/m
WEIGHT = (CABLE_DENSITY - RHO) * AREA * G  # submerged weight per length, N/m
WATERPLANE = BOX_LENGTH * BOX_WIDTH
#: keel corners in the body frame (origin at the box centre), order A, B, C, D = C1..C4
CORNER_SIGNS = ((1.0, 1.0), (-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0))
SEGMENTS = 11
STATICS = StaticsSettings(method="newton", tolerance=1e-10, max_iterations=50)

Layout = Literal["diagonal", "parallel"]


# ----------------------------------------------------------------------------- paper formula
def parabolic_top_force(chord: float, inclination_deg: float, sag_to_span: float,
                        weight: float) -> tuple[float, float, float]:
    """End forces of a small-sag (parabolic) inclined cable, as the paper uses them.

    Parameters
    ----------
    chord
        Chord length ``l`` (the paper's inclined length) [m].
    inclination_deg
        Chord inclination ``theta`` to the horizontal [deg].
    sag_to_span
        ``d/l``, sag ``d`` measured at mid-chord perpendicular to the chord.
    weight
        Weight per length ``w`` (vertical) [N/m].

    Returns
    -------
    (T, H, V)
        Chord-direction tension ``T = w cos(theta) l^2 / (8 d)`` (transverse load
        ``w cos(theta)`` on a string of chord ``l``), its horizontal component
        ``H = T cos(theta)`` and the vertical force at the upper end
        ``V = H tan(theta) + w l / 2`` (moment of the whole line about the lower end).
    """
    th = math.radians(inclination_deg)
    T = weight * math.cos(th) * chord / (8.0 * sag_to_span)
    H = T * math.cos(th)
    return T, H, H * math.tan(th) + 0.5 * weight * chord


def parabolic_draft(sag_to_span: float = SAG_TO_SPAN, inclination_deg: float = INCLINATION_DEG,
                    *, weight: float = WEIGHT, sag: Literal["perpendicular", "vertical"] =
                    "perpendicular", fairlead_depth: Literal["keel", "centre", "surface"] =
                    "keel") -> float:
    """Draft ``h_s`` from the paper's eq. (1) with the parabolic line forces.

    ``rho_s g h_s w_a w_c = M g + 4 V(h_s)`` with ``V`` of :func:`parabolic_top_force` on the
    chord from the fairlead to the seabed at ``theta``. ``V`` is linear in the chord, which is
    linear in ``h_s``, so the solution is closed-form.

    Parameters
    ----------
    sag_to_span, inclination_deg
        ``d/l`` and ``theta`` [deg].
    weight
        Line weight per length [N/m]; the default (submerged) reproduces 0.896 m,
        :data:`DRY_WEIGHT` is the alternative reading.
    sag
        ``perpendicular``: ``d`` normal to the chord (reproduces the paper); ``vertical``:
        ``d`` is the vertical sag, ``d_perp = d cos(theta)``.
    fairlead_depth
        Where the chord starts: ``keel`` (depth ``h_s``, the paper's number), ``centre``
        (box centre, depth ``h_s - w_b/2``) or ``surface`` (depth 0, chord over the full
        depth).

    Returns
    -------
    float
        ``h_s`` [m].
    """
    th = math.radians(inclination_deg)
    ratio = sag_to_span * (math.cos(th) if sag == "vertical" else 1.0)
    _, _, v_per_chord = parabolic_top_force(1.0, inclination_deg, ratio, weight)
    # chord = (depth - a * h_s + b) / sin(theta); V = v_per_chord * chord
    a, b = {"keel": (1.0, 0.0), "centre": (1.0, 0.5 * BOX_HEIGHT), "surface": (0.0, 0.0)}[
        fairlead_depth]
    k = 4.0 * v_per_chord / math.sin(th)
    return (BOX_MASS * G + k * (DEPTH + b)) / (RHO * G * WATERPLANE + a * k)


# ----------------------------------------------------------------------------- exact catenary
def chord_geometry(draft: float, inclination_deg: float = INCLINATION_DEG
                   ) -> tuple[float, float, float]:
    """Horizontal span ``X``, rise ``Z = h - h_s`` and chord ``l`` from anchor to keel fairlead."""
    th = math.radians(inclination_deg)
    Z = DEPTH - draft
    return Z / math.tan(th), Z, Z / math.sin(th)


def mid_chord_sag(solution: CatenarySolution) -> float:
    """Sag at mid-chord: distance, perpendicular to the chord, from the chord's midpoint to
    the cable (the cable point whose projection on the chord is half the chord)."""
    X, Z, L = solution.horizontal_span, solution.vertical_span, solution.length
    chord = math.hypot(X, Z)
    e = np.array([X, Z]) / chord

    def along(s: float) -> float:
        h, z = solution.profile(np.array([s]))
        return float(h[0] * e[0] + z[0] * e[1]) - 0.5 * chord

    s = brentq(along, 0.0, L, xtol=1e-12 * L)
    h, z = solution.profile(np.array([s]))
    return float(h[0] * e[1] - z[0] * e[0])  # below the chord is positive


def catenary_line(draft: float, sag_to_span: float = SAG_TO_SPAN,
                  inclination_deg: float = INCLINATION_DEG) -> CatenarySolution:
    """Exact elastic catenary from the anchor to the keel fairlead whose mid-chord
    perpendicular sag is ``sag_to_span`` times the chord; the unstretched length is solved
    for (Brent, bracketed around the parabolic arc length ``l (1 + 8/3 (d/l)^2)``)."""
    X, Z, chord = chord_geometry(draft, inclination_deg)

    def line(L: float) -> CatenarySolution:
        return solve_catenary(X, Z, L, EA, WEIGHT, seabed_contact=False)

    def excess(L: float) -> float:
        return mid_chord_sag(line(L)) / chord - sag_to_span

    L0 = chord * (1.0 + 8.0 / 3.0 * sag_to_span**2)
    L = brentq(excess, L0 * (1.0 - 2e-3), L0 * (1.0 + 2e-2), xtol=1e-13 * L0, rtol=1e-14)
    return line(L)


def catenary_draft(sag_to_span: float = SAG_TO_SPAN, inclination_deg: float = INCLINATION_DEG
                   ) -> tuple[float, CatenarySolution]:
    """Draft from eq. (1) with the exact catenary's top vertical force ``V_b`` (Brent on
    ``h_s``; the line geometry moves with the draft). Returns the draft and the line."""

    def residual(hs: float) -> float:
        return RHO * G * hs * WATERPLANE - BOX_MASS * G - 4.0 * catenary_line(
            hs, sag_to_span, inclination_deg).V_b

    guess = parabolic_draft(sag_to_span, inclination_deg)
    hs = brentq(residual, 0.8 * guess, 1.2 * guess, xtol=1e-13)
    return hs, catenary_line(hs, sag_to_span, inclination_deg)


# ----------------------------------------------------------------------------- finite elements
def wang_system(sag_to_span: float = SAG_TO_SPAN, inclination_deg: float = INCLINATION_DEG,
                segments: int = SEGMENTS, draft: float | None = None,
                layout: Layout = "diagonal") -> System:
    """The moored box of Wang, Er and Iu as a moorline :class:`~moorline.model.System`.

    Parameters
    ----------
    sag_to_span, inclination_deg
        ``d/l`` and ``theta`` of the static state (the W3 study varies them).
    segments
        Elements per line (the paper: 11).
    draft
        Draft ``h_s`` for which the anchors are placed and the unstretched length chosen
        (:func:`catenary_line`); ``None``: the exact-catenary draft of eq. (1)
        (:func:`catenary_draft`). The body starts level at this draft. For the draft at
        which the finite elements are in equilibrium with these anchors use
        :func:`wang_equilibrium`.
    layout
        Line azimuths: ``diagonal`` (each line in the vertical plane through the box centre
        and its corner, the paper's planes x1Oy, x2Oy) or ``parallel`` (along +-x in the
        planes y = +-5 m). See the module docstring.

    Returns
    -------
    System
        Body ``box`` (free; mass at the centre; uniform-box inertia; box hydrostatics;
        no added mass or damping: dynamics cases add theirs with ``dataclasses.replace``),
        points ``A``-``D`` on the body and anchors ``anchorA``-``anchorD``, lines ``C1``-``C4``
        from anchor (end a) to fairlead (end b); depth 100 m, sea water 1025 kg/m^3.
    """
    if draft is None:
        draft = catenary_draft(sag_to_span, inclination_deg)[0]
    length = catenary_line(draft, sag_to_span, inclination_deg).length
    X = chord_geometry(draft, inclination_deg)[0]
    lt = LineType("steel", diameter=DIAMETER, mass_per_length=CABLE_DENSITY * AREA, EA=EA,
                  Cd=1.2)
    m = BOX_MASS
    inertia = ((m * (BOX_WIDTH**2 + BOX_HEIGHT**2) / 12.0, 0.0, 0.0),
               (0.0, m * (BOX_LENGTH**2 + BOX_HEIGHT**2) / 12.0, 0.0),
               (0.0, 0.0, m * (BOX_LENGTH**2 + BOX_WIDTH**2) / 12.0))
    body = Body("box", kind="free", position=(0.0, 0.0, 0.5 * BOX_HEIGHT - draft), mass=m,
                inertia=inertia,
                hydrostatics=Hydrostatics("box", length=BOX_LENGTH, width=BOX_WIDTH,
                                          height=BOX_HEIGHT))
    points, lines = {}, {}
    for k, (sx, sy) in enumerate(CORNER_SIGNS):
        name = "ABCD"[k]
        corner = np.array([0.5 * BOX_LENGTH * sx, 0.5 * BOX_WIDTH * sy])
        out = corner / np.linalg.norm(corner) if layout == "diagonal" else np.array([sx, 0.0])
        anchor = corner + X * out
        points[name] = Point(name, "body", (float(corner[0]), float(corner[1]),
                                             -0.5 * BOX_HEIGHT), body="box")
        points[f"anchor{name}"] = Point(f"anchor{name}", "fixed",
                                        (float(anchor[0]), float(anchor[1]), -DEPTH))
        lines[f"C{k + 1}"] = Line(f"C{k + 1}", "steel", length, segments, f"anchor{name}", name)
    env = Environment(depth=DEPTH, water_density=RHO, gravity=G)
    return System(CASE, environment=env, line_types={"steel": lt}, points=points, lines=lines,
                  bodies={"box": body}, analyses=(STATICS,))


@dataclass(frozen=True)
class Equilibrium:
    """Finite element static state of the moored box at the fixed-point draft.

    Attributes
    ----------
    system
        The system whose anchors and line length belong to ``draft``.
    result
        Its coupled static solution.
    draft
        Draft of the solved body, equal to the draft the geometry was built for.
    history
        Drafts tried by the fixed-point iteration (guess, then one per statics solve).
    """

    system: System
    result: StaticResult
    draft: float
    history: tuple[float, ...]


def _fe_draft(result: StaticResult) -> float:
    return 0.5 * BOX_HEIGHT - float(result.body_position("box")[2])


def wang_equilibrium(sag_to_span: float = SAG_TO_SPAN, inclination_deg: float = INCLINATION_DEG,
                     segments: int = SEGMENTS, layout: Layout = "diagonal", *,
                     tol: float = 1e-9, max_iter: int = 20) -> Equilibrium:
    """Coupled body-line statics at the draft that is its own fixed point.

    ``g(d) = draft_FE(wang_system(draft=d)) - d`` is driven to zero by the secant method,
    starting from the exact-catenary draft and the first finite element draft (plain
    substitution would contract by only ~0.57 per solve).

    Raises
    ------
    RuntimeError
        A statics solve failed or the iteration did not reach ``tol`` [m].
    """

    def solve(d: float) -> tuple[System, StaticResult, float]:
        system = wang_system(sag_to_span, inclination_deg, segments, d, layout)
        result = solve_statics(system, STATICS)
        if not result.success:
            raise RuntimeError(f"wang-w1 statics failed at draft {d}: {result.message}")
        return system, result, _fe_draft(result)

    d0 = catenary_draft(sag_to_span, inclination_deg)[0]
    system, result, d1 = solve(d0)
    history = [d0, d1]
    g0 = d1 - d0
    d_prev, d = d0, d1
    for _ in range(max_iter):
        system, result, d_new = solve(d)
        history.append(d_new)
        g = d_new - d
        if abs(g) <= tol:
            return Equilibrium(system, result, d_new, tuple(history))
        d_prev, d, g0 = d, d - g * (d - d_prev) / (g - g0), g
    raise RuntimeError(f"wang-w1 draft fixed point not reached: {history}")


def discretization_estimate(line: CatenarySolution, segments: int,
                            inclination_deg: float = INCLINATION_DEG) -> tuple[float, float]:
    """A-priori error of ``segments`` straight elements against the continuous line.

    The chords of ``n`` elements inscribed in a curve of curvature ``kappa`` are shorter than
    the arc by ``L (h kappa)^2 / 24`` (``h = L/n``). With the same unstretched length the
    elements thus carry that much slack; the line's compliance
    ``dL/dT = L/EA + (w cos(theta))^2 l^3 / (12 T^3)`` (elastic plus parabolic arc excess
    ``(w cos(theta))^2 l^3 / (24 T^2)``) turns it into a tension change ``dT``. The top
    vertical force changes by ``dT sin(theta)`` and, by eq. (1), the draft by
    ``4 dT sin(theta) / (rho_s g w_a w_c)``.

    Returns
    -------
    (relative tension change, draft change [m])
        Both negative: the elements hang slacker.
    """
    th = math.radians(inclination_deg)
    L = line.length
    chord = math.hypot(line.horizontal_span, line.vertical_span)
    T = line.H / math.cos(th)
    q = WEIGHT * math.cos(th)
    kappa = q / T
    deficit = L * (L / segments * kappa) ** 2 / 24.0
    compliance = L / EA + q**2 * chord**3 / (12.0 * T**3)
    dT = -deficit / compliance
    return dT / T, 4.0 * dT * math.sin(th) / (RHO * G * WATERPLANE)


# ----------------------------------------------------------------------------- case
def run() -> list[Row]:
    """Draft by the paper's formula, the exact catenary and the finite elements."""
    paper = parabolic_draft()
    exact, line = catenary_draft()
    chord = math.hypot(line.horizontal_span, line.vertical_span)
    eq = wang_equilibrium()
    fe = eq.draft
    same = catenary_line(fe)  # exact line with the finite elements' geometry
    rel_t, d_draft = discretization_estimate(same, SEGMENTS)
    fair = eq.result.end_force("C1", "b")
    t_fe = float(np.linalg.norm(fair))
    fine = wang_equilibrium(segments=2 * SEGMENTS).draft
    order = math.log2(abs(fe - exact) / abs(fine - exact))
    solves = len(eq.history) - 1
    geometry = ("keel-corner fairleads, chord at 50 deg across h - h_s, sag l/60 at mid-chord "
                "perpendicular to the chord")
    return [
        Row(CASE, "draft h_s, paper's parabolic formulas + eq. (1)", PAPER_DRAFT, paper, 5e-3,
            unit="m", note=f"{geometry}; submerged weight {WEIGHT:.1f} N/m (dry weight: "
            f"{parabolic_draft(weight=DRY_WEIGHT):.3f} m)", kind="published", source=PAPER),
        Row(CASE, "draft h_s, exact elastic catenary + eq. (1)", PAPER_DRAFT, exact, 5e-3,
            unit="m", note=f"L = {line.length:.4f} m, chord {chord:.4f} m, "
            f"V_top = {line.V_b:.0f} N", kind="published", source=PAPER),
        Row(CASE, f"draft h_s, finite elements ({SEGMENTS} per line), coupled statics",
            PAPER_DRAFT, fe, 5e-3, unit="m",
            note=f"fixed point draft -> anchors, L -> statics: {solves} solves",
            kind="published", source=PAPER),
        Row(CASE, f"draft, finite elements ({SEGMENTS}) vs exact catenary", exact, fe, 3e-3,
            unit="m", note=f"a-priori O(h^2) estimate {d_draft / exact:+.2%}; "
            f"{2 * SEGMENTS} elements: {(fine - exact) / exact:+.3%}", kind="exact", source=EXACT),
        Row(CASE, "draft error of the elements / a-priori estimate", 1.0,
            (fe - exact) / d_draft, 0.2,
            note="inscribed-polygon slack L (h kappa)^2/24 through the line compliance",
            kind="exact", source=EXACT),
        Row(CASE, f"observed order of the draft error ({SEGMENTS} -> {2 * SEGMENTS} elements)",
            2.0, order, 0.2, relative=False, kind="exact", source=EXACT),
        Row(CASE, "fairlead tension, finite elements vs exact catenary (same geometry)",
            same.tension_b, t_fe, 6e-3, unit="N",
            note=f"a-priori estimate {rel_t:+.2%}", kind="exact", source=EXACT),
    ]


__all__ = ["CASE", "Equilibrium", "PAPER_DRAFT", "catenary_draft", "catenary_line",
           "chord_geometry", "discretization_estimate", "mid_chord_sag", "parabolic_draft",
           "parabolic_top_force", "run", "wang_equilibrium", "wang_system"]
