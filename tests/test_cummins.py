"""The Cummins (1962) equation for bodies with a radiation table: the retardation kernel against
closed-form cosine transforms, A_inf from Ogilvie's relation, the state-space memory against
direct convolution, the step's tangent against finite differences, the constant-damping
limit, and regular-wave steady states against the frequency-domain RAO solved here."""

from dataclasses import replace

import numpy as np
import pytest
from scipy.integrate import quad

from moorline.model import (
    DynamicsSettings,
    RadiationTable,
    System,
    WaveExcitation,
    Waves,
)
from moorline.physics import radiation as rad
from moorline.solvers.dynamics import simulate
from moorline.solvers.statics import solve_statics
from moorline.verification.cummins import (
    A_INF,
    DAMPED,
    EA,
    K0,
    K_HYDRO,
    LENGTH,
    MASS,
    WAVE,
    X3,
    heave_rao,
    heave_steady_state,
    heave_table,
    known_kernel,
    known_table,
    known_transfer,
    moored_body,
    nested,
)

# The known kernels, the moored body and its RAO are the verification case's
# (moorline.verification.cummins): K(t) = k0 e^{-a t} (cos b t - a/b sin b t), whose transform
# K^(w) = k0 i w / ((i w + a)^2 + b^2) has K^(0) = 0 (no damping at zero frequency).


# ---------------------------------------------------------------------- kernels
def test_kernel_is_the_cosine_transform_of_a_gaussian_damping():
    """B(w) = b (w / w0)^2 exp(-(w / w0)^2) has the closed-form transform
    K(t) = b w0 / sqrt(pi) exp(-(w0 t / 2)^2) (1/2 - (w0 t)^2 / 4); the table (0.02-6 rad/s,
    300 points) transformed exactly as piecewise linear is within 2e-4 of K(0) (the
    interpolation error, O(dw^2 B'')), and so is the fitted state-space kernel within 2e-3
    (its fit tolerance)."""
    b, w0 = 2.0, 1.0
    w = np.linspace(0.02, 6.0, 300)
    B = b * (w / w0) ** 2 * np.exp(-((w / w0) ** 2))
    t = np.linspace(0.0, 20.0, 401)
    exact = b * w0 / np.sqrt(np.pi) * np.exp(-((w0 * t / 2) ** 2)) * (0.5 - (w0 * t) ** 2 / 4)
    K = rad.retardation_kernel(w, B, t)
    assert np.abs(K - exact).max() < 2e-4 * exact[0]
    # the added mass of this damping by Ogilvie's relation, A_inf = 0: the fit of K^(w)
    A = rad.added_mass_offset(w, B, w)
    six = np.zeros((len(w), 6, 6))
    A6, B6 = six.copy(), six.copy()
    A6[:, 2, 2], B6[:, 2, 2] = A, B
    model = rad.fit_memory(w, A6, B6, np.zeros((6, 6)))
    assert np.abs(model.kernel(t)[:, 2, 2] - exact).max() < 2e-3 * exact[0]


def test_infinite_frequency_added_mass_and_kernel_of_a_known_kernel():
    """A table built from K(t) = k0 e^{-a t} (cos b t - a/b sin b t): B = Re K^, A = A_inf +
    Im K^ / w. Ogilvie's A_inf is recovered within 2e-4 of the largest |A(w) - A_inf| (measured
    1.1e-4 with 160 and 0.9e-4 with 640 frequencies: not the interpolation but the w^-3 tail
    assumed beyond 8 rad/s, where the true B decays as w^-2), the kernel within 3 % of K(0)
    (that tail: the missing 2/pi int_8^inf (B - B_tail) dw is 2.4 % of K(0)), and the
    fitted model's transfer within 2e-3 of the largest |K^| over the table."""
    table = known_table()
    w = np.array(table.omegas)
    A, B = np.array(table.added_mass)[:, 2, 2], np.array(table.damping)[:, 2, 2]
    A_inf = rad.infinite_frequency_added_mass(w, A, B)
    spread = np.abs(A - A_INF).max()
    assert abs(A_inf - A_INF) < 2e-4 * spread
    t = np.linspace(0.0, 30.0, 301)
    assert np.abs(rad.retardation_kernel(w, B, t) - known_kernel(t)).max() < 0.03 * K0
    model = rad.fit_memory(w, np.array(table.added_mass), np.array(table.damping))
    assert model.added_mass_infinite[2, 2] == pytest.approx(A_inf, rel=1e-12)
    fit = model.transfer(w)[:, 2, 2]
    Kh = known_transfer(w)
    assert np.abs(fit - Kh).max() < 2e-3 * np.abs(Kh).max()
    assert np.all(model.poles.real < 0)


def test_memory_states_convolve_a_velocity_linear_over_each_step():
    """The states advanced step by step give mu(t) = int_0^t K(t - s) v(s) ds of the fitted
    kernel for a piecewise-linear velocity, against adaptive quadrature of the convolution."""
    model = rad.fit_memory(*_arrays(known_table()), np.diag([0, 0, A_INF, 0, 0, 0]))
    h, n = 0.4, 20
    times = h * np.arange(n + 1)
    v_nodes = np.sin(0.7 * times) + 0.3 * times
    z = None
    for k in range(n):
        v0, v1 = np.zeros(6), np.zeros(6)
        v0[2], v1[2] = v_nodes[k], v_nodes[k + 1]
        z = model.advance(z, v0, v1, h)
    T = times[-1]

    def integrand(s):
        return model.kernel([T - s])[0, 2, 2] * np.interp(s, times, v_nodes)

    exact = sum(quad(integrand, a, b, limit=200)[0]
                for a, b in zip(times[:-1], times[1:], strict=True))
    assert model.force(z)[2] == pytest.approx(exact, rel=1e-9, abs=1e-9 * K0)


def _arrays(table: RadiationTable):
    return np.array(table.omegas), np.array(table.added_mass), np.array(table.damping)


# ---------------------------------------------------------------------- the stepper
@pytest.mark.parametrize("scheme", ["newmark", "hht"])
def test_the_step_tangent_with_radiation_memory_equals_finite_differences(scheme):
    """The effective tangent of a step of a spinning body with a radiation table and memory
    states against central differences of the step's residual in every unknown (the memory
    enters through the Newmark velocity, d mu / d dq = gamma / (beta h) d mu / d v1)."""
    from moorline.solvers.bodies import BodyState
    from moorline.solvers.dynamic_model import DynamicModel
    from moorline.solvers.dynamics import _fluid, _initial_state, _stepper
    from moorline.solvers.excitation import Excitation
    from moorline.solvers.newmark import _Step

    # off-diagonal entries too: surge-pitch coupling of the known kernel
    table = known_table()
    w, A, B = _arrays(table)
    for (i, j), f in {(0, 0): 0.5, (4, 4): 30.0, (0, 4): 2.0, (4, 0): 2.0}.items():
        A[:, i, j], B[:, i, j] = f * A[:, 2, 2], f * B[:, 2, 2]
    system = moored_body(RadiationTable(tuple(w), nested(A), nested(B)))
    start = solve_statics(system)
    settings = DynamicsSettings(dt=0.05, scheme=scheme, alpha=-0.2, fast_path=False)
    fluid = _fluid(system, settings)
    model = DynamicModel(start.mesh, fluid)
    exc = Excitation(start.mesh, start.positions)
    state = _initial_state(model, exc, start.positions, settings.dt, initial=start)
    spin = np.array([[0.1, -0.05, 0.02, 0.3, -0.2, 0.4]])
    state = replace(state, bodies=BodyState(state.bodies.r, state.bodies.R, spin, 0.5 * spin))
    stepper = _stepper(model, fluid, settings, 1e-6, system)
    mem = stepper.bodies.memory[0]
    rng = np.random.default_rng(1)
    z0 = 0.1 * (rng.normal(size=mem.n_states) + 1j * rng.normal(size=mem.n_states))
    state = replace(state, memory=(z0,))
    h = settings.dt
    stepper._current = _Step(state, h, exc.constrained_state(h), None)
    u = (state.x + h * state.v, np.array([[0.02, -0.01, 0.03, 0.04, -0.03, 0.05]]))
    trial = stepper.residual(u, True)
    assert np.abs(trial.body_other[0] - stepper.bodies.forces(
        trial.bodies, np.zeros_like(trial.x), np.zeros_like(trial.x), trial.arms, h)[0][0]
    ).max() > 1.0  # the memory force is there
    K = stepper.tangent_matrix(u, trial).toarray()
    n = K.shape[0]
    fd = np.empty_like(K)
    eps = 1e-6
    for j in range(n):
        e = np.zeros(n)
        e[j] = eps
        plus = stepper.residual(stepper.update(u, e), False).r
        minus = stepper.residual(stepper.update(u, -e), False).r
        fd[:, j] = -(plus - minus) / (2 * eps)
    memory_block = stepper.bodies.memory[0].velocity_derivative(h)
    assert np.abs(memory_block).max() > 1e-3 * np.abs(K[-6:, -6:]).max() * settings.dt
    assert np.allclose(K, fd, rtol=1e-5, atol=1e-6 * np.abs(K).max())


def test_a_body_with_a_radiation_table_and_constant_coefficients_is_rejected():
    with pytest.raises(ValueError, match="'b'"):
        moored_body(known_table(), added=1.0e3)
    with pytest.raises(ValueError, match="'b'"):
        moored_body(known_table(), damping=1.0e3)


def _heave(system: System, duration: float, dt: float, ramp: float = 0.0):
    start = solve_statics(system)
    assert start.success, start.message
    result = simulate(system, DynamicsSettings(duration=duration, dt=dt, ramp_time=ramp),
                      initial=start, output_every=dt)
    assert result.success, result.message
    return result.time, result.body_history("b")[:, 2]


def test_free_decay_with_a_flat_damping_table_is_the_constant_damping_body():
    """The limit K(t) = 2 B0 delta(t): a table with constant B0 from 0.01 to 1000 rad/s
    (B(0) = 0 and the w^-3 tail at the ends) and the added mass its causality demands,
    A(w) = A0 + Ogilvie's offset (given A_inf = A0; the offset is ~2 B0 / (pi w_N) = 13 kg at
    the body's 7.3 rad/s, 0.05 % of its mass), has a kernel of width ~1/1000 s; the body's
    free decay equals that of the same body with constant added mass A0 and damping B0
    within 0.3 % of the initial offset (the added-mass offset, the fit's 0.2 %)."""
    B0, A0, push = 2.0e4, 5.0e3, 2.0e4
    w = np.geomspace(0.01, 1000.0, 150)
    B = np.full(len(w), B0)
    table = heave_table(w, A0 + rad.added_mass_offset(w, B, w), B, A_inf=A0)
    k = K_HYDRO + 4 * EA / LENGTH
    period = 2 * np.pi / np.sqrt(k / (MASS + A0))
    t1, z1 = _heave(moored_body(table, push=push), 4 * period, period / 100)
    t2, z2 = _heave(moored_body(added=A0, damping=B0, push=push), 4 * period, period / 100)
    offset = z1[0] - z1[-1]
    assert abs(offset) > 0.5 * push / k  # it decays from the pushed pose
    assert np.abs(z1 - z2).max() < 3e-3 * abs(offset)
    # and not the undamped body: the damping matters at this level
    t3, z3 = _heave(moored_body(added=A0, push=push), 4 * period, period / 100)
    assert np.abs(z3 - z2).max() > 0.1 * abs(offset)


@pytest.mark.parametrize("omega", [1.5, 3.0])
def test_regular_wave_steady_state_matches_the_rao(omega):
    """The Cummins run in a regular wave (exciting-force table X3 per metre, A_inf from
    Ogilvie) settles to the amplitude of the RAO (solved in the frequency domain with the
    kernel's closed-form A(w), B(w)) within 1 % (Newmark's period error at 60 steps per period
    ~0.1 %, the fit 0.05 %). The heave mode (4.9 rad/s, B = 4.9e3 there: decay time 9.5 s) is
    barely started by a 10 s ramp and has decayed after 40 s."""
    assert heave_steady_state(omega, 60) == pytest.approx(abs(heave_rao(omega)), rel=1e-2)
    # the constant-coefficient body with A and B at another frequency would not pass
    assert abs(abs(heave_rao(omega)) - abs(heave_rao(1.2 * omega))) > 0.03 * abs(heave_rao(omega))


def test_memory_states_are_saved_and_restored_by_the_coupling():
    """A coupled run repeated from a snapshot (Coupling.state/restore) gives the same forces
    and body motion: the memory states travel with the step state."""
    from moorline.coupling import Coupling

    excitation = WaveExcitation(omegas=(0.05, 8.0), amplitude=((0, 0, X3, 0, 0, 0),) * 2,
                                phase_deg=((0.0,) * 6,) * 2)
    system = moored_body(known_table(), excitation=excitation,
                         waves=Waves(kind="airy", height=2 * WAVE, period=4.0))
    a0 = replace(system.points["a0"], kind="prescribed")
    system = replace(system, points={**system.points, "a0": a0})
    c = Coupling(system, points=["a0"])
    q = np.array(a0.position, dtype=float)
    c.init(q)
    for k in range(20):
        c.step(q, np.zeros(3), 0.1 * k, 0.1)
    saved = c.state()
    assert saved.step.memory is not None and np.abs(saved.step.memory[0]).max() > 0
    first = [c.step(q, np.zeros(3), 2.0 + 0.1 * k, 0.1) for k in range(10)]
    z_first = c._state.bodies.r.copy()
    c.restore(saved)
    again = [c.step(q, np.zeros(3), 2.0 + 0.1 * k, 0.1) for k in range(10)]
    np.testing.assert_array_equal(np.array(first), np.array(again))
    np.testing.assert_array_equal(z_first, c._state.bodies.r)


def test_random_sea_response_variance_is_the_sum_over_the_components():
    """JONSWAP sea (Hs 4 cm, Tp 3 s, components up to 3.5 rad/s, below the heave mode, on the
    60 s record's frequency grid): after the start-up the Cummins run's heave variance over
    one whole record equals sum_m a_m^2 |H(w_m)|^2 / 2 with the frequency-domain RAO H solved
    in the case (the cross terms vanish exactly over a record), within 2 % in the standard
    deviation (Newmark's period error at the highest components, dt = 0.04 s: ~0.3 %; the
    start-up transient left after 40 s: < 1 %)."""
    from moorline.waves import fluid_field_from_environment

    excitation = WaveExcitation(omegas=(0.05, 20.0), amplitude=((0, 0, X3, 0, 0, 0),) * 2,
                                phase_deg=((0.0,) * 6,) * 2)
    waves = Waves(kind="random", height=0.04, period=3.0, record_length=60.0, omega_max=3.5,
                  seed=3)
    system = moored_body(known_table(shape=DAMPED, w_max=20.0, n=200), excitation=excitation,
                         waves=waves)
    sea = fluid_field_from_environment(system.environment)
    expected = np.sqrt(0.5 * np.sum(sea.amplitudes**2
                                    * np.abs([heave_rao(w) for w in sea.omegas]) ** 2))
    dt = 0.04
    t, z = _heave(system, 100.0, dt, ramp=10.0)
    window = (t >= 40.0 - 1e-9) & (t < 100.0 - 1e-9)
    assert np.std(z[window]) == pytest.approx(expected, rel=0.02)
    assert len(sea.omegas) > 20


def test_additional_damping_adds_to_the_radiation_damping():
    """``additional_damping`` (viscous damping outside the potential-flow table, OC3's
    additional linear damping): a body with the flat table of B0 / 2 and an additional B0 / 2
    decays as the body with the table of B0 (the memory and the constant damping add up),
    and without a table additional damping is the same as constant damping."""
    B0, A0, push = 2.0e4, 5.0e3, 2.0e4
    w = np.geomspace(0.01, 1000.0, 150)

    def table(b):
        B = np.full(len(w), b)
        return heave_table(w, A0 + rad.added_mass_offset(w, B, w), B, A_inf=A0)

    extra = nested(np.diag([0, 0, 0.5 * B0, 0, 0, 0])[None])[0]
    k = K_HYDRO + 4 * EA / LENGTH
    period = 2 * np.pi / np.sqrt(k / (MASS + A0))
    half = moored_body(table(0.5 * B0), push=push)
    half = replace(half, bodies={"b": replace(half.bodies["b"], additional_damping=extra)})
    _, z1 = _heave(half, 3 * period, period / 100)
    _, z2 = _heave(moored_body(table(B0), push=push), 3 * period, period / 100)
    offset = z2[0] - z2[-1]
    assert np.abs(z1 - z2).max() < 3e-3 * abs(offset)
    plain = moored_body(added=A0, push=push)
    plain = replace(plain, bodies={"b": replace(plain.bodies["b"],
                                                additional_damping=nested(np.diag(
                                                    [0, 0, B0, 0, 0, 0])[None])[0])})
    _, z3 = _heave(plain, 3 * period, period / 100)
    _, z4 = _heave(moored_body(added=A0, damping=B0, push=push), 3 * period, period / 100)
    assert np.allclose(z3, z4, rtol=0, atol=1e-12 * abs(offset))
