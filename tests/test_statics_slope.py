"""Statics on a sloped or gridded seabed (issue 14, deliverable 3) against exact solutions
written here: a line lying along an inclined plane (closed form), a catenary hanging to an
inclined plane (an independent shooting solution of the elastic catenary ODE with scipy), and
a grid sampled from the plane giving the plane's result."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import fsolve

from moorline.io import load_case_text
from moorline.solvers.statics import solve_statics

RHO, G = 1025.0, 9.80665
D, MASS, EA = 0.1, 60.0, 5.0e8          # m, kg/m, N: a chain-like line
W = (MASS - RHO * math.pi * D**2 / 4) * G  # submerged weight per unstretched length [N/m]
DEPTH = 200.0


def _case(a, b, length, segments, seabed: str, extra_points: str = "",
          stiffness: float = 3.0e6) -> str:
    return f"""
name: slope
units: SI
environment: {{depth: {DEPTH}, water_density: {RHO}, gravity: {G},
              seabed: {{stiffness: {stiffness}, damping: 0, {seabed}}}}}
line_types:
  chain: {{diameter: {D}, mass_per_length: {MASS}, EA: {EA}, Cd: 1.2, Ca: 1.0}}
points:
  a: {{kind: fixed, position: {[float(v) for v in a]}}}
  b: {{kind: fixed, position: {[float(v) for v in b]}}}
{extra_points}
lines:
  l1: {{type: chain, length: {length}, segments: {segments}, end_a: a, end_b: b}}
analyses: [{{kind: statics}}]
"""


def _on_plane(slope_deg: float, heading_deg: float, x: float, y: float) -> float:
    """Height of the plane through (0, 0, -DEPTH) going down at slope_deg towards heading."""
    t = math.tan(math.radians(slope_deg))
    h = math.radians(heading_deg)
    return -DEPTH - t * (x * math.cos(h) + y * math.sin(h))


@pytest.mark.parametrize("heading, mu", [(0.0, 0.0), (120.0, 0.0), (120.0, 0.4)])
def test_a_line_lying_up_a_slope_has_the_closed_form_tension(heading, mu) -> None:
    """Both ends on a 10 deg plane along its fall line, the line 0.2 % shorter than the chord:
    the seabed carries ``w cos(a)`` per length, the tension rises up the slope by ``w sin(a)``
    per unstretched length, plus ``mu w cos(a)`` with the static friction fully mobilized
    towards the anchor (the closed-form convention, :func:`moorline.physics.seabed.
    static_friction`; the lower end ``a`` is the anchor): ``T(s) = T_A + k s``,
    ``k = w (sin(a) + mu cos(a))``, with ``D = L + (T_A L + k L^2 / 2) / EA`` (D the chord,
    L the unstretched length). The interior nodes rest 3.4 mm off the plane (within the
    contact's blend-in band, d / 4 wide, :mod:`moorline.physics.seabed`): with the ends on
    the plane that lengthens the two end elements by 1.2e-6 m and raises the tension by
    EA / L * 1.2e-6 = 1.9 N = 1.9e-6 T_B (tolerance 5e-6 T_B). With friction the kink would
    also press the nodes next to the ends by T * 3.4e-4 (~340 N, friction 136 N): there the
    seabed stiffness is chosen so that the nodes rest on the surface itself (the documented
    law ``k q^2 / (2 ramp)`` in the band with ``ramp = d / 4``: zero height at
    ``q / k = ramp / 8``, i.e. 1.6e6 Pa/m here), which makes the closed form's straight line
    the discrete one."""
    slope, L, n = 10.0, 300.0, 30
    down = np.array([math.cos(math.radians(heading)), math.sin(math.radians(heading))])
    chord = L * 1.002
    run = chord * math.cos(math.radians(slope))
    pa_xy, pb_xy = 150.0 * down, 150.0 * down - run * down  # a lower, b up the slope
    a = (*pa_xy, _on_plane(slope, heading, *pa_xy))
    b = (*pb_xy, _on_plane(slope, heading, *pb_xy))
    assert math.dist(a, b) == pytest.approx(chord)
    stiffness = 3.0e6
    if mu:  # per area: k d L_e q / (k d L_e) = d / 32 with q = w cos(a) L_e
        stiffness = 32.0 * W * math.cos(math.radians(slope)) / D**2
        assert W / (stiffness * D) < D / 4  # the band is the d / 4 minimum
    system = load_case_text(_case(a, b, L, n, f"slope: {slope}, slope_heading: {heading}, "
                                              f"friction: {mu}", stiffness=stiffness))
    result = solve_statics(system)
    assert result.success, result.message
    s_sin = W * (math.sin(math.radians(slope)) + mu * math.cos(math.radians(slope)))
    T_A = (chord - L) * EA / L - s_sin * L / 2.0
    T_B = T_A + s_sin * L
    mid = (np.arange(n) + 0.5) * L / n
    assert np.allclose(result.line_tension("l1"), T_A + s_sin * mid, rtol=0, atol=5e-6 * T_B)
    assert np.linalg.norm(result.end_force("l1", "a")) == pytest.approx(T_A, abs=5e-6 * T_B)
    if not mu:  # with friction end_force treats every end on the seabed as an anchor, whose
        # friction takes up pull: not b, where the friction of the lying line adds to it
        assert np.linalg.norm(result.end_force("l1", "b")) == pytest.approx(T_B, abs=5e-6 * T_B)
    assert result.seabed_length("l1") == pytest.approx(L, rel=1e-9)


def test_friction_holds_a_line_lying_down_a_slope_from_its_anchor() -> None:
    """The anchor up the 10 deg slope, the other end down it, mu = 0.5 > tan(10 deg): the
    friction holds the line's weight down the slope and takes up the pull, so the tension
    falls towards the anchor by ``k = w (mu cos(a) - sin(a))`` per length and reaches 0 there
    when the chord is ``D = L + k L^2 / (2 EA)``: ``T(s) = k s`` from the anchor. (Friction
    capped at the tension alone, the flat seabed's rule, cannot hold the slack end of such a
    line on a slope.) Seabed stiffness as in the test above, so that the nodes rest on the
    plane; tolerance 5e-6 of the largest tension."""
    slope, heading, L, n, mu = 10.0, 60.0, 300.0, 30, 0.5
    down = np.array([math.cos(math.radians(heading)), math.sin(math.radians(heading))])
    k = W * (mu * math.cos(math.radians(slope)) - math.sin(math.radians(slope)))
    chord = L + k * L**2 / (2.0 * EA)
    run = chord * math.cos(math.radians(slope))
    pa_xy, pb_xy = -100.0 * down, -100.0 * down + run * down  # a up, b down the slope
    a = (*pa_xy, _on_plane(slope, heading, *pa_xy))
    b = (*pb_xy, _on_plane(slope, heading, *pb_xy))
    stiffness = 32.0 * W * math.cos(math.radians(slope)) / D**2
    system = load_case_text(_case(a, b, L, n, f"slope: {slope}, slope_heading: {heading}, "
                                              f"friction: {mu}", stiffness=stiffness))
    result = solve_statics(system)
    assert result.success, result.message
    mid = (np.arange(n) + 0.5) * L / n
    assert np.allclose(result.line_tension("l1"), k * mid, rtol=0, atol=5e-6 * k * L)


def _reference_catenary(anchor: np.ndarray, fairlead: np.ndarray, L: float, slope: float,
                        up_slope: float) -> dict:
    """The elastic catenary from an anchor on a frictionless inclined seabed (2-D, x-z plane),
    solved here by shooting on the ODE, independent of moorline.

    From the anchor the line lies along the seabed (direction ``e`` at ``up_slope * slope``
    above the horizontal) for an unstretched length ``L_b`` with ``dT/ds = w sin`` of that
    angle, ``dr/ds = (1 + T/EA) e``; at the touchdown it leaves the seabed tangentially
    (no point force) and hangs: ``dT_x/ds = 0``, ``dT_z/ds = w``, ``dr/ds = (1 + T/EA) T/|T|``.
    Unknowns ``T_A`` and ``L_b`` such that the end of the line is at the fairlead."""
    angle = math.radians(slope) * up_slope
    e = np.array([math.cos(angle), math.sin(angle)])

    def shoot(p):
        T_a, L_b = p
        T_td = T_a + W * math.sin(angle) * L_b
        x_td = anchor + e * (L_b + (T_a * L_b + W * math.sin(angle) * L_b**2 / 2) / EA)

        def rhs(_, y):
            t = np.hypot(y[2], y[3])
            return [y[2] / t * (1 + t / EA), y[3] / t * (1 + t / EA), 0.0, W]

        sol = solve_ivp(rhs, (L_b, L), [*x_td, *(T_td * e)], rtol=1e-12, atol=1e-10)
        return sol.y[:2, -1], sol.y[2:, -1], T_td, x_td

    def residual(p):
        return shoot(p)[0] - fairlead

    T_a, L_b = fsolve(residual, [0.5 * W * (L - 300.0), 0.4 * L], xtol=1e-13)
    end, T_end, T_td, x_td = shoot([T_a, L_b])
    assert np.allclose(end, fairlead, atol=1e-8)
    return {"T_a": T_a, "L_b": L_b, "T_fairlead": float(np.hypot(*T_end)), "touchdown": x_td}


@pytest.mark.parametrize("up_slope", [1.0, -1.0], ids=["rising", "falling"])
def test_a_catenary_hanging_to_a_sloped_seabed_matches_a_shooting_solution(up_slope) -> None:
    """Anchor on a 3 deg plane, fairlead 150 m above the seabed 600 m away (the seabed rising
    or falling towards the fairlead), 700 m of line in 140 elements: the fairlead and anchor
    tensions within 5e-4 of the fairlead tension, the lying length within 0.25 m (5 % of an
    element). The finite elements converge to the continuous line roughly as h^2 with a
    touchdown term that changes sign (fairlead tension errors measured 8e-3, 1.3e-3, 3e-4 to
    4e-4 and 0.6e-4 to 1.2e-4 at 35, 70, 140 and 280 elements; lying length 1.4, 0.26, 0.07
    and 0.02 m); the penalty penetration (mm) is negligible."""
    slope, L = 3.0, 700.0
    heading = 180.0 if up_slope > 0 else 0.0  # the seabed goes down away from +x if rising
    ax = 0.0
    anchor = np.array([ax, _on_plane(slope, heading, ax, 0.0)])
    fx = 600.0
    fairlead = np.array([fx, _on_plane(slope, heading, fx, 0.0) + 150.0])
    ref = _reference_catenary(anchor, fairlead, L, slope, up_slope)
    assert 100.0 < ref["L_b"] < L - 150.0  # a real lying part and a real hanging part
    system = load_case_text(_case((anchor[0], 0.0, anchor[1]), (fairlead[0], 0.0, fairlead[1]),
                                  L, 140, f"slope: {slope}, slope_heading: {heading}"))
    result = solve_statics(system)
    assert result.success, result.message
    T_f = ref["T_fairlead"]
    assert np.linalg.norm(result.end_force("l1", "b")) == pytest.approx(T_f, abs=5e-4 * T_f)
    assert np.linalg.norm(result.end_force("l1", "a")) == pytest.approx(ref["T_a"],
                                                                        abs=5e-4 * T_f)
    assert result.seabed_length("l1") == pytest.approx(ref["L_b"], abs=0.25)


def test_a_grid_sampled_from_the_plane_gives_the_planes_statics() -> None:
    """The catenary of the previous test on a 4 x 3 bilinear grid of the plane's heights (an
    uneven grid, heading 30 deg): the same node positions within 1e-6 m."""
    slope, heading, L = 3.0, 210.0, 700.0
    c, s = math.cos(math.radians(30.0)), math.sin(math.radians(30.0))
    a = (0.0, 0.0, _on_plane(slope, heading, 0.0, 0.0))
    fx, fy = 600.0 * c, 600.0 * s
    b = (fx, fy, _on_plane(slope, heading, fx, fy) + 150.0)
    gx, gy = [-100.0, 140.0, 390.0, 700.0], [-200.0, 90.0, 500.0]
    gz = [[_on_plane(slope, heading, x, y) for y in gy] for x in gx]
    grid = f"bathymetry: {{x: {gx}, y: {gy}, z: {gz}}}"
    plane = solve_statics(load_case_text(_case(a, b, L, 70,
                                               f"slope: {slope}, slope_heading: {heading}")))
    gridded = solve_statics(load_case_text(_case(a, b, L, 70, grid)))
    assert plane.success and gridded.success
    assert np.allclose(gridded.positions, plane.positions, rtol=0, atol=1e-6)
    assert gridded.end_force("l1", "b") == pytest.approx(plane.end_force("l1", "b"), rel=1e-9)


def test_statics_converge_on_an_uneven_bathymetry_grid() -> None:
    """The OC3 line (40 elements) over a 50 m grid of heights -320 + 3 sin(x / 40 m)
    cos(y / 60 m) (slopes up to 4 deg, changing at every grid line): Newton converges from the
    sloped-seabed start, and no node is deeper in the seabed than a few times the penetration
    under its own weight (w / (k d) = 2.6 mm). (Much rougher grids can stall Newton and the
    relaxation fallback at the cell edges, where the bilinear surface has kinks: +-6 m random
    bumps every 50 m under 20 elements did.)"""
    import dataclasses

    from moorline.model import Bathymetry
    from moorline.verification.oc3_system import oc3_one_line

    system = oc3_one_line(40)
    gx, gy = np.arange(-100.0, 1001.0, 50.0), np.array([-200.0, -100.0, 0.0, 100.0, 200.0])
    gz = -320.0 + 3.0 * np.sin(gx / 40.0)[:, None] * np.cos(gy / 60.0)[None, :]
    grid = Bathymetry(x=tuple(gx), y=tuple(gy), z=tuple(map(tuple, gz.tolist())))
    env = system.environment
    anchor = system.points["anchor1"]
    z_anchor = float(np.interp(anchor.position[0], gx, gz[:, 2]))
    system = dataclasses.replace(
        system,
        environment=dataclasses.replace(env, seabed=dataclasses.replace(env.seabed,
                                                                        bathymetry=grid)),
        points={**system.points, "anchor1": dataclasses.replace(
            anchor, position=(anchor.position[0], 0.0, z_anchor))})
    result = solve_statics(system)
    assert result.success, result.message
    x = result.positions
    gap = x[:, 2] - result.mesh.seabed_height(x)
    assert gap.min() > -0.01
    assert result.seabed_length("line1") > 50.0  # it lies in the hollows, bridging the bumps
