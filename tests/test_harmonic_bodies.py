"""Harmonic balance with rigid bodies and viscoelastic lines (issue 15, deliverable 4)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from click.testing import CliRunner

from moorline.cli import cli
from moorline.model import (
    Body,
    DynamicsSettings,
    Environment,
    HarmonicSettings,
    Hydrostatics,
    Line,
    LineType,
    Motion,
    Point,
    RadiationTable,
    System,
)
from moorline.physics.rigid_body import rotation_matrix
from moorline.solvers.dynamics import simulate
from moorline.solvers.harmonic import HarmonicBalance, _basis, solve_harmonic
from moorline.solvers.harmonic_bodies import angular_kinematics, interpolate_radiation
from moorline.solvers.harmonic_material import maxwell_operator
from moorline.solvers.statics import solve_statics
from moorline.verification import harmonic_body as hb

ROOT = Path(__file__).resolve().parents[1]


# ---------------------------------------------------------------------- kinematics
@pytest.mark.parametrize("scale", [1.0, 1e-2])  # 1e-2: the series branch
def test_angular_kinematics_are_those_of_the_rotation_history(scale):
    """omega and alpha of ``R(t) = exp([phi(t) x])`` against central differences of ``R``
    itself (``dR/dt R^T = [omega x]``), large and small angles (the series branch)."""
    def phi(t):
        return scale * np.array([0.3 * np.sin(t), 0.5 * np.cos(2 * t) + 0.1, 0.2 * t])

    def omega_fd(t, h=1e-5):
        W = (rotation_matrix(phi(t + h)) - rotation_matrix(phi(t - h))) / (2 * h) @ \
            rotation_matrix(phi(t)).T
        return np.array([W[2, 1], W[0, 2], W[1, 0]])

    t = 0.7
    d1 = scale * np.array([0.3 * np.cos(t), -np.sin(2 * t), 0.2])
    d2 = scale * np.array([-0.3 * np.sin(t), -2 * np.cos(2 * t), 0.0])
    w, al, J, dw, da, dd = angular_kinematics(phi(t)[None], d1[None], d2[None])
    assert np.allclose(w[0], omega_fd(t), atol=1e-9 * scale, rtol=0)
    alpha_fd = (omega_fd(t + 1e-3) - omega_fd(t - 1e-3)) / 2e-3
    assert np.allclose(al[0], alpha_fd, atol=1e-5 * scale, rtol=0)  # O(h^2) of both FDs
    # the complex-step derivatives against central differences of the kinematics
    e = 1e-6 * max(scale, 1e-3)
    for i in range(3):
        step = np.zeros(3)
        step[i] = e
        plus = angular_kinematics((phi(t) + step)[None], d1[None], d2[None])
        minus = angular_kinematics((phi(t) - step)[None], d1[None], d2[None])
        assert np.allclose(dw[0, :, i], (plus[0] - minus[0])[0] / (2 * e), atol=1e-7)
        assert np.allclose(da[0, :, i], (plus[1] - minus[1])[0] / (2 * e), atol=1e-7)
        plus = angular_kinematics(phi(t)[None], (d1 + step)[None], d2[None])
        minus = angular_kinematics(phi(t)[None], (d1 - step)[None], d2[None])
        assert np.allclose(dd[0, :, i], (plus[1] - minus[1])[0] / (2 * e), atol=1e-7)


def test_radiation_interpolation_is_linear_and_held_outside_the_table():
    a = [np.full((6, 6), v) for v in (1.0, 3.0)]
    table = RadiationTable((1.0, 2.0), tuple(tuple(map(tuple, m)) for m in a),
                           tuple(tuple(map(tuple, 2 * m)) for m in a))
    A, B = interpolate_radiation(table, np.array([0.5, 1.25, 2.0, 9.0]))
    assert np.allclose(A[:, 0, 0], [1.0, 1.5, 3.0, 3.0])
    assert np.allclose(B[:, 5, 5], [2.0, 3.0, 6.0, 6.0])


def test_maxwell_operator_gives_the_periodic_solution_of_the_branch_ode():
    """``dQ/dt + Q / tau = EA1 deps/dt`` integrated by scipy over many relaxation times for
    a strain with three harmonics: the periodic state against the operator's samples."""
    from scipy.integrate import solve_ivp

    w, tau, ea1 = 2.0, 0.4, 5.0e6
    n, n_t = 4, 20
    times = 2 * math.pi / w * np.arange(n_t) / n_t
    E = _basis(times, w, n)[0]
    coefficients = np.array([1e-3, 2e-3, -1e-3, 0.0, 5e-4, 3e-4, 0.0, 0.0, 0.0])

    def strain_rate(t):
        return _basis(np.array([t]), w, n)[1][0] @ coefficients

    periods = 40  # 40 periods of 3.1 s: 300 relaxation times, the transient is gone
    sol = solve_ivp(lambda t, q: [ea1 * strain_rate(t) - q[0] / tau],
                    (0, periods * 2 * math.pi / w), [0.0], rtol=1e-11, atol=1e-6,
                    t_eval=(periods - 1) * 2 * math.pi / w + times, dense_output=False)
    L = maxwell_operator(E, w, np.array([ea1]), np.array([tau]))[0]
    assert np.allclose(L @ (E @ coefficients), sol.y[0], rtol=0, atol=1e-6 * ea1 * 1e-3)


# ---------------------------------------------------------------------- closed forms
@pytest.mark.parametrize("radiation", [False, True])
@pytest.mark.parametrize("ratio", [0.7, 1.4])
def test_body_on_springs_matches_the_closed_form(radiation, ratio):
    """A body on a linear heave spring (matrix hydrostatics and four vertical taut lines)
    under a harmonic heave force: ``z = F / (k - (m + A) w^2 + i B w)``, with ``A(w)``,
    ``B(w)`` of a radiation table in the frequency-dependent variant; no harmonics above
    the first, no mean shift, no motion in the other dofs (exact, linear system)."""
    omega = ratio * math.sqrt(hb.heave_stiffness() / (hb.MASS + hb.ADDED))
    system = hb.spring_body(omega, radiation)
    static = solve_statics(system)
    result = solve_harmonic(system, HarmonicSettings(period=2 * math.pi / omega,
                                                     harmonics=3), static)
    assert result.success, result.message
    z = hb.first_harmonic(result.body_coefficients[:, 0, 2]) / hb.FORCE
    exact = hb.heave_response(omega, radiation)
    assert abs(z - exact) < 1e-7 * abs(exact)
    # the other variant's coefficients differ by percent: the test can tell them apart
    assert abs(hb.heave_response(omega, not radiation) - exact) > 1e-2 * abs(exact)
    c = result.body_coefficients[:, 0]
    assert abs(c[0, 2] - static.body_pose[0, 2]) < 1e-9 * hb.FORCE * abs(exact)
    assert np.abs(c[3:, 2]).max() < 1e-9 * hb.FORCE * abs(exact)
    assert np.abs(c[1:, [0, 1, 3, 4, 5]]).max() < 1e-12


def test_body_in_a_regular_wave_matches_the_closed_form():
    """The body on springs excited by its exciting-force table in a regular wave (the table
    read at the wave frequency, other values around it): the exact linear heave."""
    omega = 0.8 * math.sqrt(hb.heave_stiffness() / (hb.MASS + hb.ADDED))
    result = solve_harmonic(hb.wave_body(omega), HarmonicSettings(period=2 * math.pi / omega,
                                                                  harmonics=3))
    assert result.success, result.message
    z, exact = hb.first_harmonic(result.body_coefficients[:, 0, 2]), hb.wave_heave(omega)
    assert abs(z - exact) < 1e-7 * abs(exact)


@pytest.mark.parametrize("ratio", [0.7, 1.4])
def test_viscoelastic_bar_matches_the_complex_modulus(ratio):
    """A mass on one standard-linear-solid element, forced along it: the exact linear
    response ``1 / ((EA + EA1 i w tau / (1 + i w tau)) / L0 - m w^2)`` (the strain is linear
    in the motion: exact at this 25 % of the static stretch too)."""
    omega = ratio * math.sqrt((hb.BAR_EA + hb.BAR_EA1) / hb.BAR_L0 / hb.BAR_MASS)
    system = hb.sls_oscillator(omega)
    result = solve_harmonic(system, HarmonicSettings(period=2 * math.pi / omega,
                                                     harmonics=3))
    assert result.success, result.message
    node = result.mesh.point_node[result.mesh.point_index("mass")]
    u = hb.first_harmonic(result.coefficients[:, node, 0]) / hb.BAR_FORCE
    exact = hb.sls_response(omega)
    assert abs(u - exact) < 1e-7 * abs(exact)
    for stiffness in (hb.BAR_EA, hb.BAR_EA + hb.BAR_EA1):  # relaxed and instantaneous
        elastic = 1.0 / (stiffness / hb.BAR_L0 - hb.BAR_MASS * omega**2)
        assert abs(elastic - exact) > 1e-2 * abs(exact)  # the Maxwell branch matters here


def test_a_fixed_body_holds_its_points_like_fixed_points():
    """A free point between two taut strings, one held by a fixed body (attached 1 m from
    the body origin, the body turned), forced harmonically: the same periodic response as
    with a fixed point at the attachment (to round-off), and the body stays at its pose."""
    half, tension, ea, mass = 5.0, 1000.0, 1.0e7, 10.0
    string = LineType("s", diameter=0.01, mass_per_length=1e-9, EA=ea, Cd=0.0, Ca=0.0)
    end = half * (1 + tension / ea)
    history = Motion("harmonic", amplitude=(0.0, 0.0, 0.5), period=1.0)
    held = Body("held", kind="fixed", position=(end, 0.0, -1.0), rotation=(0.3, 0.0, 0.0))
    arm = (0.0, float(np.sin(0.3)), float(np.cos(0.3)))  # body frame: the origin + 1 m up
    points = {"a": Point("a", "fixed", (-end, 0.0, 0.0)),
              "m": Point("m", "free", (0.0, 0.0, 0.0), mass=mass, force_history=history),
              "b": Point("b", "body", arm, body="held")}
    lines = {"left": Line("left", "s", half, 2, "a", "m"),
             "right": Line("right", "s", half, 2, "m", "b")}
    env = Environment(water_density=0.0, gravity=0.0)
    with_body = System("held", environment=env, line_types={"s": string}, points=points,
                       lines=lines, bodies={"held": held})
    plain = System("plain", environment=env, line_types={"s": string},
                   points={**points, "b": Point("b", "fixed", (end, 0.0, 0.0))}, lines=lines)
    settings = HarmonicSettings(period=1.0, harmonics=3)
    one, two = solve_harmonic(with_body, settings), solve_harmonic(plain, settings)
    assert one.success and two.success, (one.message, two.message)
    assert np.abs(two.coefficients[1:]).max() > 1e-4  # it moves
    assert np.allclose(one.coefficients, two.coefficients, rtol=0, atol=1e-10)
    assert np.allclose(one.body_pose[:, 0, :3], [end, 0.0, -1.0], rtol=0, atol=1e-12)
    assert np.allclose(one.body_pose[:, 0, 3:], [0.3, 0.0, 0.0], rtol=0, atol=1e-12)


# ---------------------------------------------------------------------- time domain
def buoy(material: str = "elastic", segments: int = 6, force=(1500.0, 0.0, 800.0),
         period: float = 6.0, radiation: bool = False, lines: int = 3) -> System:
    """A floating cylinder (nonlinear wall-sided hydrostatics, centre of gravity below the
    origin, quadratic drag, constant added mass and damping or a radiation table) on
    catenary chains hanging clear of the seabed, forced by a harmonic force at its origin."""
    viscous = material != "elastic"
    chain = LineType("chain", diameter=0.05, mass_per_length=20.0, EA=5e7, Cd=1.2, Ca=1.0,
                     Ct=0.01, material=material, EA1=3e7 if viscous else 0.0,
                     tau=0.7 if viscous else 0.0)
    added = np.diag([800.0, 800.0, 1500.0, 300.0, 300.0, 50.0])
    damping = np.diag([500.0, 500.0, 2000.0, 100.0, 100.0, 10.0])
    if radiation:
        w = (0.2, 1.0, 2.0, 4.0)
        hydro = {"radiation": RadiationTable(
            w, tuple(tuple(map(tuple, added * (1 + 0.2 * i))) for i in range(4)),
            tuple(tuple(map(tuple, damping * (0.5 + i))) for i in range(4)))}
    else:
        hydro = {"added_mass": tuple(map(tuple, added)),
                 "damping": tuple(map(tuple, damping))}
    body = Body("buoy", mass=3000.0, center_of_gravity=(0.0, 0.0, -0.3),
                inertia=((2000.0, 0, 0), (0, 2000.0, 0), (0, 0, 1500.0)),
                hydrostatics=Hydrostatics("cylinder", diameter=2.0, height=2.0),
                drag_area=(2.0, 2.0, 3.0), Cd=1.0,
                force_history=Motion("harmonic", amplitude=force, period=period), **hydro)
    points, legs = {}, {}
    for k in range(lines):
        a = 2 * math.pi * k / 3 + (0.3 if lines == 1 else 0.0)
        points[f"f{k}"] = Point(f"f{k}", "body", (math.cos(a), math.sin(a), -1.0), body="buoy")
        points[f"a{k}"] = Point(f"a{k}", "fixed", (60 * math.cos(a), 60 * math.sin(a), -40.0))
        legs[f"l{k}"] = Line(f"l{k}", "chain", 80.0, segments, f"a{k}", f"f{k}")
    return System("buoy", environment=Environment(depth=60.0, water_density=1025.0,
                                                  gravity=9.81),
                  line_types={"chain": chain}, points=points, lines=legs,
                  bodies={"buoy": body})


@pytest.mark.parametrize("material", ["elastic", "viscoelastic"])
def test_moored_buoy_equals_the_time_domain_steady_state(material):
    """The buoy on three chains in surge-heave forcing (0.28 m surge, 0.1 m heave, 0.7 deg
    pitch: geometric, drag and hydrostatic nonlinearity; elastic, then viscoelastic chains
    at large strain amplitude): the harmonic-balance series against the last period of a
    Newmark run started from the static state, all six body dofs.

    Tolerance (internal cross-check, moorline against moorline): the time domain's own
    error. Elastic chains, relative to each dof's amplitude: at dt = T/100 the two differ
    by 6e-4 (surge), 9e-4 (heave), 5.4e-3 (pitch); at dt = T/200 by 3e-4, 3e-4, 1.7e-3,
    which is the transient left after 15 periods (the last two periods differ by 3e-4,
    2e-4, 2.6e-3); 5 against 8 harmonics changes the body series by 1e-5 m. Bound: 1 % of
    each dof's amplitude (twice the largest difference seen)."""
    period, n = 6.0, 5
    system = buoy(material)
    static = solve_statics(system)
    result = solve_harmonic(system, HarmonicSettings(period=period, harmonics=n), static)
    assert result.success, result.message
    periods = 15
    td = simulate(system, DynamicsSettings(duration=periods * period, dt=period / 100,
                                           tolerance=1e-9), initial=static,
                  output_every=period / 25)
    assert td.success, td.message
    last = (td.time >= (periods - 1) * period - 1e-9) & (td.time < periods * period - 1e-9)
    E = _basis(td.time[last] - (periods - 1) * period, 2 * math.pi / period, n)[0]
    hb_pose = E @ result.body_coefficients[:, 0]
    td_pose = td.body_pose[last, 0]
    amplitude = 0.5 * np.ptp(hb_pose, axis=0)
    assert amplitude[0] > 0.2 and amplitude[2] > 0.05 and amplitude[4] > 5e-3  # it moves
    for k in (0, 2, 4):  # surge, heave, pitch (sway, roll, yaw vanish by symmetry)
        assert np.abs(td_pose[:, k] - hb_pose[:, k]).max() < 0.01 * amplitude[k]
    # the fairlead tension of each chain (the lines' side of the coupling): the series of
    # the solver's tensions over one period against the time domain, relative to the range
    fairleads = [elements[-1] for elements in result.mesh.line_elements]
    fit = np.linalg.lstsq(_basis(result.time, 2 * math.pi / period, n)[0],
                          result.tension[:, fairleads], rcond=None)[0]
    hb_tension, td_tension = E @ fit, td.tension[last][:, fairleads]
    assert np.abs(hb_tension - td_tension).max() < 0.01 * np.ptp(hb_tension, axis=0).max()


# ---------------------------------------------------------------------- the Jacobian
@pytest.mark.parametrize("material,radiation", [("elastic", False), ("viscoelastic", True)])
def test_jacobian_equals_finite_differences(material, radiation):
    """The exact Jacobian of the coupled harmonic balance (body kinematics chained through
    the rotation vector, attached nodes, Maxwell branch, radiation per harmonic) against
    central differences of the residual, at a state with large rotations and harmonics of
    every unknown. Tolerance: the differences' truncation and round-off, 1e-6 of the
    largest entry (a missing term is of order one)."""
    system = buoy(material, segments=2, radiation=radiation, lines=1,
                  force=(3000.0, 500.0, 1000.0))
    static = solve_statics(system)
    balance = HarmonicBalance(system, HarmonicSettings(period=6.0, harmonics=2, samples=6),
                              static)
    rng = np.random.default_rng(1)
    X = balance.coefficients_of(balance.initial()).copy()
    X[1:] += 0.2 * rng.standard_normal(X[1:].shape)
    X[0] += 0.05 * rng.standard_normal(X[0].shape)
    u = balance.unknowns(X)
    J = balance.evaluate(u, True)[1].toarray()
    h = 1e-6
    numeric = np.empty_like(J)
    for i in range(len(u)):
        e = np.zeros(len(u))
        e[i] = h
        numeric[:, i] = (balance.evaluate(u + e, False)[0]
                         - balance.evaluate(u - e, False)[0]) / (2 * h)
    assert np.abs(J - numeric).max() < 1e-6 * np.abs(J).max()
    body = balance.bodies.model.body_dof[0] * balance.n_terms  # the body's rows alone
    rows = slice(body, body + 6 * balance.n_terms)
    assert np.abs(J[rows] - numeric[rows]).max() < 1e-6 * np.abs(J[rows]).max()


def test_viscoelastic_jacobian_without_bodies_equals_finite_differences():
    """The Maxwell branch's non-local Jacobian on a line system without bodies (the
    block-sparse path)."""
    omega = 30.0
    system = hb.sls_oscillator(omega)
    balance = HarmonicBalance(system, HarmonicSettings(period=2 * math.pi / omega,
                                                       harmonics=2))
    rng = np.random.default_rng(2)
    X = balance.coefficients_of(balance.initial()).copy()
    X[1:] += 1e-3 * rng.standard_normal(X[1:].shape)
    u = balance.unknowns(X)
    J = balance.evaluate(u, True)[1].toarray()
    h = 1e-8
    numeric = np.column_stack([(balance.evaluate(u + h * e, False)[0]
                                - balance.evaluate(u - h * e, False)[0]) / (2 * h)
                               for e in np.eye(len(u))])
    assert np.abs(J - numeric).max() < 1e-6 * np.abs(J).max()


# ---------------------------------------------------------------------- the case file
def test_harmonic_body_case_runs_from_the_cli(tmp_path, undescribed):
    """cases/harmonic_body.yaml (the Tuah Ex5 disc on its leg in a regular wave with its
    exciting-force table): the CLI solves it, writes the body's series and poses in the
    harmonic group, and plots them; the disc moves in surge, heave and pitch only."""
    path = ROOT / "cases" / "harmonic_body.yaml"
    result = CliRunner().invoke(cli, ["run", str(path), "--out", str(tmp_path), "--quiet"])
    assert result.exit_code == 0, result.output
    folder = tmp_path / "harmonic-body"
    assert (folder / "harmonic.png").stat().st_size > 0
    assert undescribed(folder / "results.nc") == []
    with xr.open_dataset(folder / "results.nc", group="harmonic") as ds:
        assert ds.attrs["status"] == "converged"
        assert ds["body_coefficients"].dims == ("term", "body", "dof")
        pose = ds["body_pose"].values[:, 0]
    motion = np.ptp(pose, axis=0)
    assert motion[0] > 0.1 and motion[2] > 0.5 and motion[4] > 0.05  # ft, ft, rad
    assert np.abs(motion[[1, 3, 5]]).max() < 1e-9
