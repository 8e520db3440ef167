"""Rod hydrostatics (issue 14): buoyancy of slender cylinders at every pose against closed
forms, its tangent against finite differences, and a floating spar's draft and heave period."""

import numpy as np
import pytest

from moorline.model import (
    Body,
    DynamicsSettings,
    Environment,
    Hydrostatics,
    Line,
    LineType,
    Motion,
    Point,
    System,
)
from moorline.physics.rigid_body import rotation_matrix
from moorline.physics.rod_buoyancy import rod_buoyancy
from moorline.solvers.dynamics import simulate
from moorline.solvers.statics import solve_statics

RHO, G = 1025.0, 9.81


def _fd_tangent(a, b, d, r, R, h=1e-6):
    """``-d load / d(dr, dtheta)`` by central differences (left rotations)."""
    K = np.zeros((6, 6))
    for j in range(6):
        step = np.zeros(6)
        step[j] = h
        plus = rod_buoyancy(a, b, d, r + step[:3], rotation_matrix(step[3:]) @ R, RHO, G)[0]
        minus = rod_buoyancy(a, b, d, r - step[:3], rotation_matrix(-step[3:]) @ R, RHO, G)[0]
        K[:, j] = -(plus - minus) / (2 * h)
    return K


@pytest.mark.parametrize("z", [-3.0, -0.4, 0.0, 0.3, 2.5])
def test_tangent_matches_finite_differences_at_every_pose(z):
    """Rods wet, piercing (either end up), and dry; none with an end within 1e-4 of the
    surface (the kink), so central differences of 1e-6 stay on one side."""
    rng = np.random.default_rng(7)
    a, b = rng.normal(size=(5, 3)), rng.normal(size=(5, 3))
    d = rng.uniform(0.1, 0.6, 5)
    r, R = np.array([0.3, -0.1, z]), rotation_matrix([0.4, -0.3, 0.2])
    ends = np.concatenate((a, b)) @ R.T + r
    assert np.abs(ends[:, 2]).min() > 1e-4
    load, K = rod_buoyancy(a, b, d, r, R, RHO, G)
    scale = np.abs(load).max() + 1.0
    np.testing.assert_allclose(K, _fd_tangent(a, b, d, r, R), atol=1e-5 * scale)


@pytest.mark.parametrize("side", [-1e-3, 1e-3])
def test_tangent_on_both_sides_of_an_end_crossing_the_surface(side):
    """End A just under / just over z = 0: the tangent of the side it is on."""
    a, b, d = np.array([[0.0, 0.0, 0.0]]), np.array([[3.0, 0.5, -4.0]]), np.array([0.5])
    R = rotation_matrix([0.1, 0.2, 0.0])
    r = np.array([0.0, 0.0, side])
    load, K = rod_buoyancy(a, b, d, r, R, RHO, G)
    np.testing.assert_allclose(K, _fd_tangent(a, b, d, r, R), atol=1e-5 * np.abs(load).max())


def _cut_cylinder_load(h, L, d, theta):
    """Archimedes' force and moment about end A of a cylinder (end A at depth ``h``, axis
    ``t = (sin theta, 0, cos theta)``) cut by ``z = 0``, by quadrature over its cross-section,
    independent of moorline: a fibre at ``u`` along ``p = (cos theta, 0, -sin theta)`` is wet
    over ``clip(h / cos(theta) + u tan(theta), 0, L)`` of its length (the fibres across, along
    y, cancel in the moment). Gauss-Chebyshev (second kind) of 40 points: exact for the
    polynomial integrands while the cut stays on the rod's side."""
    k = np.arange(1, 41)
    x = np.cos(np.pi * k / 41)
    w = np.pi / 41 * np.sin(np.pi * k / 41) ** 2  # int f(x) sqrt(1 - x^2) dx on [-1, 1]
    r = d / 2
    u, weight = r * x, 2 * r**2 * w  # int f(u) 2 sqrt(r^2 - u^2) du
    t = np.array([np.sin(theta), 0.0, np.cos(theta)])
    p = np.array([np.cos(theta), 0.0, -np.sin(theta)])
    wet = np.clip(h / np.cos(theta) + u * np.tan(theta), 0.0, L)
    lift = RHO * G * wet * weight
    centre = 0.5 * wet[:, None] * t + u[:, None] * p
    moment = np.cross(centre, lift[:, None] * np.array([0.0, 0.0, 1.0])).sum(axis=0)
    return np.concatenate(([0.0, 0.0, lift.sum()], moment))


@pytest.mark.parametrize("theta", [0.0, 0.2, 0.6, -0.9])
def test_tilted_piercing_rod_righting_moment(theta):
    """A rod from its lower end A at depth h, tilted by theta from vertical (about y): its
    submerged axis is h / cos(theta) long, so the buoyancy is rho g A h / cos(theta) at
    (h / (2 cos theta)) (sin theta, 0, cos theta) from A, plus the waterplane couple
    ``-rho g I sin(theta) (1 + tan(theta)^2 / 2)`` (``I = pi d^4 / 64``): the moment about A
    ``M_y = -rho g A h^2 sin(theta) / (2 cos^2 theta) - rho g I sin(theta) (1 + tan^2 / 2)``
    (closed form), equal to Archimedes' load of the obliquely cut cylinder by quadrature
    (:func:`_cut_cylinder_load`). Tolerance 1e-9 (round-off; both exact)."""
    h, L, d = 2.0, 10.0, 0.8
    area, inertia = np.pi * d**2 / 4, np.pi * d**4 / 64
    R = rotation_matrix([0.0, theta, 0.0])
    load, _ = rod_buoyancy([[0.0, 0.0, 0.0]], [[0.0, 0.0, L]], [d], [5.0, 1.0, -h], R, RHO, G)
    force = RHO * G * area * h / np.cos(theta)
    moment = (-RHO * G * area * h**2 * np.sin(theta) / (2 * np.cos(theta) ** 2)
              - RHO * G * inertia * np.sin(theta) * (1 + np.tan(theta) ** 2 / 2))
    # about the origin (5, 1, -h) = end A: the force is vertical, M_x = y F = 0 there
    np.testing.assert_allclose(load, [0, 0, force, 0, moment, 0], atol=1e-9 * force)
    np.testing.assert_allclose(load, _cut_cylinder_load(h, L, d, theta), atol=1e-9 * force)
    # the same rod upside down (end B the lower one) gives the same buoyancy
    flip, _ = rod_buoyancy([[0.0, 0.0, L]], [[0.0, 0.0, 0.0]], [d], [5.0, 1.0, -h], R, RHO, G)
    np.testing.assert_allclose(flip, load, atol=1e-9 * force)


@pytest.mark.parametrize(("h", "theta"), [(0.3, 1.2), (5.13, 1.0), (0.05, 0.3), (0.1, 1.55)],
                         ids=["wet-cap", "dry-cap", "end-near", "near-horizontal"])
def test_waterplane_moment_beyond_its_bound_is_capped_with_its_tangent(h, theta):
    """Past the bound (the waterline reaching an end cap: ``min(h_w, h_d) < (d / 2)
    tan(theta)``) ``tan(theta)`` is capped at ``2 min(h_w, h_d) / d``: the moment is that
    closed form, bounded near horizontal, and its tangent matches finite differences (both
    the wet and the dry part the shorter)."""
    L, d = 10.0, 0.8
    R = rotation_matrix([0.0, theta, 0.0])
    a, b, r = [[0.0, 0.0, 0.0]], [[0.0, 0.0, L]], np.array([0.0, 0.0, -h])
    load, K = rod_buoyancy(a, b, [d], r, R, RHO, G)
    h_w = h / np.cos(theta)
    cap = 2 * min(h_w, L - h_w) / d
    assert cap < np.tan(theta)
    area, inertia = np.pi * d**2 / 4, np.pi * d**4 / 64
    moment = (-RHO * G * area * h_w**2 * np.sin(theta) / 2
              - RHO * G * inertia * np.sin(theta) * (1 + cap**2 / 2))
    assert load[4] == pytest.approx(moment, rel=1e-12)
    np.testing.assert_allclose(K, _fd_tangent(a, b, [d], r, R), atol=1e-5 * np.abs(load).max())


def test_waterplane_moment_tangent_of_a_piercing_rod_in_3d():
    """A rod piercing the surface, tilted in x and y and spun, under the bound: the tangent
    (waterplane couple included) against finite differences, and against Archimedes' moment
    at small tilt: ``-dM_y/dtheta_y = rho g (A h^2 / 2 + I)`` about the lower end (upright)."""
    L, d, h = 6.0, 1.2, 2.5
    a, b = [[0.0, 0.0, 0.0]], [[0.0, 0.0, L]]
    R = rotation_matrix([0.25, -0.15, 0.4])
    r = np.array([1.0, -2.0, -h])
    load, K = rod_buoyancy(a, b, [d], r, R, RHO, G)
    np.testing.assert_allclose(K, _fd_tangent(a, b, [d], r, R), atol=1e-5 * np.abs(load).max())
    _, K0 = rod_buoyancy(a, b, [d], np.array([0.0, 0.0, -h]), np.eye(3), RHO, G)
    area, inertia = np.pi * d**2 / 4, np.pi * d**4 / 64
    assert K0[4, 4] == pytest.approx(RHO * G * (area * h**2 / 2 + inertia), rel=1e-12)


def test_submerged_and_dry_rods():
    """Fully wet: rho g A L at the middle, whatever the tilt; fully dry: nothing."""
    L, d, theta = 4.0, 0.5, 0.7
    area = np.pi * d**2 / 4
    R = rotation_matrix([theta, 0.0, 0.0])
    wet, _ = rod_buoyancy([[0, 0, 0]], [[0, 0, L]], [d], [0, 0, -10.0], R, RHO, G)
    # about x: arm (0, -sin, cos) L/2 times (0, 0, F): M_x = -F L sin(theta) / 2
    F = RHO * G * area * L
    np.testing.assert_allclose(wet, [0, 0, F, -F * L * np.sin(theta) / 2, 0, 0],
                               atol=1e-9 * F)
    dry, K = rod_buoyancy([[0, 0, 0]], [[0, 0, L]], [d], [0, 0, 0.1], R, RHO, G)
    assert not dry.any() and not K.any()


# ---------------------------------------------------------------------- a floating spar
SPAR_L, SPAR_D, SPAR_MASS, SPAR_A33 = 10.0, 2.0, 1.6e4, 2.0e3
TETHER_T = 1.0  # N: the lateral tethers' pretension, for a regular statics only


def spar(push: float) -> System:
    """A vertical rod buoy (rods hydrostatics, origin at its middle, ballasted: centre of
    gravity 3 m down) held laterally by four light horizontal tethers of tension ~1 N, pushed
    down by ``push`` in statics (released in dynamics by the opposite force history)."""
    lt = LineType("tether", diameter=0.01, mass_per_length=0.0, EA=1.0e4, displaced_area=0.0,
                  Cd=0.0, Ca=0.0, Ct=0.0)
    draft = (SPAR_MASS * G + push) / (RHO * G * np.pi * SPAR_D**2 / 4)
    z0 = draft - SPAR_L / 2  # the origin's height at the expected equilibrium
    added = np.zeros((6, 6))
    added[2, 2] = SPAR_A33
    body = Body("spar", position=(0.0, 0.0, z0 + 0.3), mass=SPAR_MASS,
                center_of_gravity=(0.0, 0.0, -3.0),
                inertia=((2e5, 0, 0), (0, 2e5, 0), (0, 0, 1e4)),
                added_mass=tuple(map(tuple, added)),
                hydrostatics=Hydrostatics("rods", rods=(((0.0, 0.0, -SPAR_L / 2),
                                                         (0.0, 0.0, SPAR_L / 2), SPAR_D),)),
                force=(0.0, 0.0, -push, 0.0, 0.0, 0.0),
                force_history=Motion("table", times=(0.0, 1e6),
                                     values=((0.0, 0.0, push), (0.0, 0.0, push))))
    points, lines = {}, {}
    span = 40.0
    for k, (x, y) in enumerate([(1, 0), (0, 1), (-1, 0), (0, -1)]):
        points[f"p{k}"] = Point(f"p{k}", "body", (x, y, 0.0), body="spar")
        points[f"a{k}"] = Point(f"a{k}", "fixed", (x * (1 + span), y * (1 + span), z0))
        lines[f"l{k}"] = Line(f"l{k}", "tether", span / (1 + TETHER_T / 1.0e4), 2,
                              f"a{k}", f"p{k}")
    env = Environment(depth=100.0, water_density=RHO, gravity=G)
    return System("spar", environment=env, line_types={"tether": lt}, points=points,
                  lines=lines, bodies={"spar": body})


def test_floating_spar_draft_and_heave_period():
    """Draft ``T = (m g + push) / (rho g A)`` (Archimedes) and the heave free-decay period
    ``2 pi sqrt((m + A33) / (rho g A))`` (a wall-sided hull: the buoyancy is linear in heave
    while it pierces the surface). Tolerances: the statics residual (1e-6 on the draft); the
    tethers' vertical stiffness 4 T / L ~ 0.1 N/m against rho g A = 3.2e4 N/m, and Newmark's
    period elongation at 100 steps per period (~0.03 %): 5e-3 on the period."""
    area = np.pi * SPAR_D**2 / 4
    push = RHO * G * area * 0.1  # 0.1 m of heave
    system = spar(push)
    start = solve_statics(system)
    assert start.success, start.message
    z = float(start.body_position("spar")[2])
    draft = (SPAR_MASS * G + push) / (RHO * G * area)
    assert SPAR_L / 2 - z == pytest.approx(draft, rel=1e-6)
    period = 2 * np.pi * np.sqrt((SPAR_MASS + SPAR_A33) / (RHO * G * area))
    dt = period / 100
    result = simulate(system, DynamicsSettings(duration=5 * period, dt=dt, tolerance=1e-9),
                      initial=start, output_every=dt)
    zt = result.body_history("spar")[:, 2]
    zt = zt - zt.mean()
    i = np.flatnonzero((zt[:-1] < 0) & (zt[1:] >= 0))
    crossings = result.time[i] - zt[i] * dt / (zt[i + 1] - zt[i])
    assert float(np.mean(np.diff(crossings))) == pytest.approx(period, rel=5e-3)
    assert np.abs(zt).max() == pytest.approx(0.1, rel=2e-2)


def test_md_float_converted_buoy_balances_at_archimedes_draft():
    """OpenFAST r-test md_float (deck origin in tests/data/moordyn/public/README.md): a buoy of
    two coaxial rods on a free body, released at 45 deg of pitch. Its converted body (rods
    hydrostatics) is in heave and pitch balance upright at the origin's height
    ``z = 1 - (m - rho V_w) / (rho A_can)`` (Archimedes: the 4 m weight rod, 1 m long, fully
    wet; the 2 m can, from 1 m below the origin, wet over the rest), whatever the deck's pose
    of 45 deg: a Newton on the body's loads and their tangent from that pose. Tolerance 1e-9 m
    (the Newton's residual). MoorDyn-C released there stays there (tests/test_neutral_bodies.py
    ``test_float_equilibrium_against_moordyn``)."""
    from pathlib import Path

    from moorline.io.moordyn import read_moordyn_deck
    from moorline.solvers.bodies import body_loads

    deck = Path(__file__).parent / ("data/moordyn/public/OpenFAST-r-test/modules/moordyn/"
                                    "md_float/moordyn.dat")
    system = read_moordyn_deck(deck).system
    body, env = system.bodies["body1"], system.environment
    rho, g = env.water_density, env.gravity
    q = np.array([body.position[2], body.rotation[1]])
    assert q[1] == pytest.approx(np.pi / 4)
    for _ in range(30):
        load, K = body_loads(body, np.array([0.0, 0.0, q[0]]),
                             rotation_matrix([0.0, q[1], 0.0]), g, rho)
        q = q + np.linalg.solve(K[np.ix_([2, 4], [2, 4])], load[[2, 4]])
    mass = 1.0e2 * 5.0 + 2.15e4 * 1.0  # the deck's rods: Mass/m times length
    heave = 1.0 - (mass - rho * np.pi * 2.0**2 * 1.0) / (rho * np.pi * 1.0**2)
    assert body.mass == pytest.approx(mass)
    assert q[0] == pytest.approx(heave, abs=1e-9) and q[1] == pytest.approx(0.0, abs=1e-9)


def test_rods_hydrostatics_round_trip_through_a_case_file_and_bad_input(tmp_path):
    """The spar's rods hydrostatics written to a case file and read back are the same; a
    ``rods`` kind without rods, or a rod of zero diameter, is refused naming the key."""
    from dataclasses import replace

    from moorline.errors import CaseError
    from moorline.io.case import load_case, load_case_text
    from moorline.io.case_writer import write_case

    system = spar(0.0)
    tether = replace(system.line_types["tether"], mass_per_length=1.0, displaced_area=1e-4)
    system = replace(system, analyses=(), line_types={"tether": tether})
    path = write_case(system, tmp_path / "spar.yaml")
    back = load_case(path).bodies["spar"].hydrostatics
    assert back == system.bodies["spar"].hydrostatics
    text = path.read_text()
    for bad, key in ((text.replace("diameter: 2.0", "diameter: 0.0"), "diameter"),):
        with pytest.raises(CaseError, match=key):
            load_case_text(bad, "bad.yaml")
    import yaml

    data = yaml.safe_load(text)
    data["bodies"]["spar"]["hydrostatics"]["rods"] = []
    with pytest.raises(CaseError, match="hydrostatics.rods"):
        load_case_text(yaml.safe_dump(data), "bad.yaml")
