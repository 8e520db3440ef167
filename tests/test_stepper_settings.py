"""The one time stepper honours every setting, with and without bodies: HHT's dissipation
against the spectral radius of its amplification matrix, Rayleigh damping against the damping
ratio it is set to, and every combination of scheme x variant x bodies x Rayleigh x waves x
viscoelastic lines with a measurable effect of each setting."""

import itertools
from dataclasses import replace

import numpy as np
import pytest
from test_body_dynamics import ADDED, EA, F0, K_HYDRO, LENGTH, MASS, spring_body

from moorline.model import (
    DynamicsSettings,
    Environment,
    Line,
    LineType,
    Motion,
    Point,
    System,
    Waves,
)
from moorline.solvers.dynamics import simulate
from moorline.solvers.statics import solve_statics


def _decay_per_step(z: np.ndarray) -> float:
    """|lambda| of a sampled damped oscillation about a constant: least squares of
    z[n+1] = c1 z[n] + c2 z[n-1] + c0 gives c2 = -|lambda|^2."""
    A = np.column_stack((z[1:-1], z[:-2], np.ones(len(z) - 2)))
    c1, c2, c0 = np.linalg.lstsq(A, z[2:], rcond=None)[0]
    return float(np.sqrt(-c2))


def _hht_spectral_radius(alpha: float, omega_dt: float) -> float:
    """Modulus of the oscillatory eigenvalues of HHT-alpha's amplification matrix for the
    undamped oscillator ``a + w^2 x = 0`` (Hilber, Hughes and Taylor 1977), built here from
    the scheme's three equations (state x, h v, h^2 a)."""
    beta, gamma = (1 - alpha) ** 2 / 4, 0.5 - alpha
    w2 = omega_dt**2  # with h = 1
    # unknowns (x1, v1, a1) from (x0, v0, a0):
    #   a1 + (1 + alpha) w2 x1 - alpha w2 x0 = 0
    #   x1 = x0 + v0 + (1/2 - beta) a0 + beta a1
    #   v1 = v0 + (1 - gamma) a0 + gamma a1
    lhs = np.array([[(1 + alpha) * w2, 0.0, 1.0], [1.0, 0.0, -beta], [0.0, 1.0, -gamma]])
    rhs = np.array([[alpha * w2, 0.0, 0.0], [1.0, 1.0, 0.5 - beta], [0.0, 1.0, 1 - gamma]])
    eig = np.linalg.eigvals(np.linalg.solve(lhs, rhs))
    return float(np.abs(eig[np.abs(eig.imag) > 1e-12]).max())


@pytest.mark.parametrize("scheme,alpha", [("newmark", 0.0), ("hht", -0.1), ("hht", -0.3)])
def test_a_body_with_hht_is_damped_by_the_scheme_spectral_radius(scheme, alpha):
    system = spring_body(F0)
    start = solve_statics(system)
    omega = np.sqrt((K_HYDRO + 4 * EA / LENGTH) / (MASS + ADDED))
    dt = 1.2 / omega  # a large step: omega dt = 1.2
    settings = DynamicsSettings(duration=40 * dt, dt=dt, scheme=scheme, alpha=alpha,
                                tolerance=1e-11, max_step_cuts=0)
    result = simulate(system, settings, initial=start, output_every=dt)
    assert result.success, result.message
    z = result.body_history("b")[5:, 2]
    measured = _decay_per_step(z)
    expected = _hht_spectral_radius(alpha, omega * dt) if scheme == "hht" else 1.0
    assert measured == pytest.approx(expected, abs=2e-4)
    if scheme == "hht":
        assert measured < 0.999  # the dissipation is there


def _oscillator(waves: bool = False, viscoelastic: bool = False, bodies: bool = False,
                across: bool = True) -> System:
    """A 2 t neutrally buoyant point mass between two taut lines along z, released from a
    force step across and along them; or the body of :func:`spring_body` pushed in surge
    (the lines' geometric stiffness makes both nonlinear: the variants differ)."""
    if bodies:
        system = spring_body(F0)
        body = system.bodies["b"]
        sway = Motion("table", times=(0.0, 1e6), values=((2e4, 0.0, F0), (2e4, 0.0, F0)))
        system = replace(system, bodies={"b": replace(body, force_history=sway)})
        lt = system.line_types["rope"]
    else:
        push_x = 2.0e3 if across else 0.0
        lt = LineType("rope", diameter=0.05, mass_per_length=0.0, EA=2.0e6,
                      displaced_area=0.0, Cd=0.0, Ca=0.0, Ct=0.0)
        push = Motion("table", times=(0.0, 1e-9, 1e6),
                      values=((0.0, 0.0, 0.0), (push_x, 0.0, 2.0e3), (push_x, 0.0, 2.0e3)))
        points = {"top": Point("top", "fixed", (0.0, 0.0, -1.0)),
                  "m": Point("m", "free", (0.0, 0.0, -21.0), mass=2000.0,
                             volume=2000.0 / 1025.0, force_history=push),
                  "bottom": Point("bottom", "fixed", (0.0, 0.0, -41.0))}
        lines = {"up": Line("up", "rope", 19.98, 4, "m", "top"),
                 "down": Line("down", "rope", 19.98, 4, "bottom", "m")}
        system = System("osc", environment=Environment(water_density=1025.0, gravity=9.81),
                        line_types={"rope": lt}, points=points, lines=lines)
    lt = replace(lt, Cd=1.2 if waves else 0.0, mass_per_length=1.0,
                 material="viscoelastic" if viscoelastic else "elastic",
                 EA1=3.0 * lt.EA if viscoelastic else 0.0, tau=0.5 if viscoelastic else 0.0)
    env = system.environment
    if waves:
        env = replace(env, depth=200.0, waves=Waves(kind="airy", height=2.0, period=3.0))
    return replace(system, line_types={"rope": lt}, environment=env)


def test_rayleigh_damps_a_system_without_bodies_at_the_ratio_set():
    system = _oscillator(across=False)
    system = replace(system, line_types={"rope": replace(system.line_types["rope"],
                                                         mass_per_length=0.0)})
    omega = np.sqrt(2 * 2.0e6 / 19.98 / 2000.0)
    dt = 0.02 / omega * 2 * np.pi  # 50 steps per period
    zeta = 0.02
    settings = DynamicsSettings(duration=6 * 2 * np.pi / omega, dt=dt, tolerance=1e-11,
                                rayleigh_ratio=zeta, rayleigh_frequencies=(omega, omega))
    start = solve_statics(system)
    damped = simulate(system, settings, initial=start, output_every=dt)
    plain = simulate(system, replace(settings, rayleigh_ratio=0.0), initial=start,
                     output_every=dt)
    assert damped.success and plain.success
    z_d = damped.point_history("m")[3:, 2]
    z_p = plain.point_history("m")[3:, 2]
    # damping ratio from the decay per step, lambda = exp(-zeta omega dt): trapezoidal
    # integration keeps it to O((omega dt)^2) = 1.6 %
    assert -np.log(_decay_per_step(z_d)) / (omega * dt) == pytest.approx(zeta, rel=3e-2)
    assert _decay_per_step(z_p) == pytest.approx(1.0, abs=1e-6)


_SETTINGS = list(itertools.product(("newmark", "hht"),
                                   ("iterative", "residual_feedback", "incremental"),
                                   (0.0, 0.05)))


def _histories(bodies: bool, waves: bool, viscoelastic: bool) -> dict:
    system = _oscillator(waves, viscoelastic, bodies)
    start = solve_statics(system)
    assert start.success, start.message
    out = {}
    for scheme, variant, zeta in _SETTINGS:
        settings = DynamicsSettings(duration=1.0, dt=0.05, scheme=scheme, alpha=-0.2,
                                    variant=variant, rayleigh_ratio=zeta,
                                    rayleigh_frequencies=(2.0, 20.0), tolerance=1e-10)
        result = simulate(system, settings, initial=start, output_every=0.05)
        assert result.success, (scheme, variant, zeta, result.message)
        free = result.mesh.free_nodes
        out[scheme, variant, zeta] = result.positions[:, free].copy()
    return out


@pytest.mark.parametrize("bodies", [False, True])
def test_every_setting_has_an_effect_in_every_combination(bodies):
    runs = {(w, v): _histories(bodies, w, v) for w in (False, True) for v in (False, True)}

    def differ(a, b) -> bool:
        return float(np.abs(a - b).max()) > 1e-9 * float(np.abs(a).max())

    for (waves, visco), hist in runs.items():
        for scheme, variant, zeta in _SETTINGS:
            here = hist[scheme, variant, zeta]
            other_scheme = "hht" if scheme == "newmark" else "newmark"
            assert differ(here, hist[other_scheme, variant, zeta]), ("scheme", waves, visco)
            assert differ(here, hist[scheme, variant, 0.05 - zeta]), ("rayleigh", waves, visco)
            for other in ("iterative", "residual_feedback", "incremental"):
                if other != variant:
                    assert differ(here, hist[scheme, other, zeta]), ("variant", variant, other)
            assert differ(here, runs[not waves, visco][scheme, variant, zeta]), "waves"
            assert differ(here, runs[waves, not visco][scheme, variant, zeta]), "viscoelastic"


@pytest.mark.parametrize("scheme,zeta", [("newmark", 0.0), ("hht", 0.05)])
def test_the_stepper_tangent_with_a_spinning_body_equals_finite_differences(scheme, zeta):
    """The effective tangent of a step (lines, a body with an offset centre of gravity that
    spins and accelerates, added mass, drag, Rayleigh damping) against central differences
    of the step's residual in every unknown, node and body dofs."""
    from moorline.solvers.bodies import BodyState
    from moorline.solvers.dynamic_model import DynamicModel
    from moorline.solvers.dynamics import _fluid, _initial_state, _stepper
    from moorline.solvers.excitation import Excitation
    from moorline.solvers.newmark import _Step

    system = spring_body(F0)
    body = replace(system.bodies["b"], center_of_gravity=(0.3, -0.2, -0.5),
                   inertia=((1e5, 2e3, 0), (2e3, 8e4, 1e3), (0, 1e3, 6e4)),
                   drag_area=(4.0, 3.0, 2.0), Cd=1.0)
    system = replace(system, bodies={"b": body})
    start = solve_statics(system)
    # the general stepper's tangent (a body with drag in still water also runs compiled)
    settings = DynamicsSettings(dt=0.05, scheme=scheme, alpha=-0.2, rayleigh_ratio=zeta,
                                rayleigh_frequencies=(1.0, 10.0), fast_path=False)
    fluid = _fluid(system, settings)
    model = DynamicModel(start.mesh, fluid)
    exc = Excitation(start.mesh, start.positions)
    state = _initial_state(model, exc, start.positions, settings.dt, initial=start)
    spin = np.array([[0.1, -0.05, 0.02, 0.3, -0.2, 0.4]])
    state = replace(state, bodies=BodyState(state.bodies.r, state.bodies.R, spin, 0.5 * spin))
    stepper = _stepper(model, fluid, settings, 1e-6, system)
    stepper._setup_rayleigh(state) if zeta else None
    h = settings.dt
    stepper._current = _Step(state, h, exc.constrained_state(h), None)
    x1 = state.x + h * state.v
    dq = np.array([[0.02, -0.01, 0.03, 0.04, -0.03, 0.05]])
    u = (x1, dq)
    K = stepper.tangent_matrix(u, stepper.residual(u, True)).toarray()
    n = K.shape[0]
    fd = np.empty_like(K)
    eps = 1e-6
    for j in range(n):
        e = np.zeros(n)
        e[j] = eps
        plus = stepper.residual(stepper.update(u, e), False).r
        minus = stepper.residual(stepper.update(u, -e), False).r
        fd[:, j] = -(plus - minus) / (2 * eps)
    assert np.allclose(K, fd, rtol=1e-5, atol=1e-6 * np.abs(K).max())


@pytest.mark.parametrize("fast_path", [True, False])
def test_a_state_that_turns_nan_is_a_failure_with_time_and_place_not_converged(fast_path):
    """A prescribed motion that becomes NaN at t = 0.5 s (through the Python API, which the
    case-file validation does not guard): the run stops there with success False and says
    when and where, keeping the records before."""
    system = _oscillator(across=False)
    nan_motion = Motion("table", times=(0.0, 0.5, 1e6),
                        values=((0.0, 0.0, 0.0), (0.0, 0.0, 0.0), (np.nan, 0.0, 0.0)))
    top = replace(system.points["top"], kind="prescribed", motion=nan_motion)
    system = replace(system, points={**system.points, "top": top})
    start = solve_statics(system)
    result = simulate(system, DynamicsSettings(duration=2.0, dt=0.1, max_step_cuts=2,
                                               fast_path=fast_path),
                      initial=start, output_every=0.1)
    assert not result.success and result.status == "failed"
    assert "did not converge at t = " in result.message and "line" in result.message
    assert np.all(np.isfinite(result.positions)) and result.time[-1] <= 0.5 + 1e-9
