"""Fluid kinematics: dispersion, Airy waves, superposition, current, combined fields.

Each check is against something independent of the implementation: the dispersion residual
and its series limits, potential-flow identities by central finite differences, the boundary
conditions, direct cosh/sinh formulas, and plain sums.
"""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from moorline.model import Current, Environment, Waves
from moorline.waves import (
    AiryWave,
    CombinedField,
    CurrentProfile,
    FluidField,
    StillWater,
    WaveComponents,
    fluid_field_from_environment,
    omega_from_k,
    ramp_factor,
    superpose,
    wave_number,
)

G = 9.80665
G_US = 32.174  # ft/s^2
RNG = np.random.default_rng(11)

# (height, period, depth): kh ~ 0.3 (shallow), ~ 2.6 (intermediate), deep water
CASES = [(1.0, 20.0, 10.0), (2.0, 8.0, 40.0), (3.0, 10.0, math.inf)]


# ---------------------------------------------------------------- dispersion


@pytest.mark.parametrize("depth, g", [(1.0, G), (50.0, G), (3000.0, G), (200.0, G_US)])
def test_dispersion_residual_over_kh_sweep(depth, g):
    kh = np.logspace(-4, 2, 601)
    k_true = kh / depth
    omega = np.sqrt(g * k_true * np.tanh(kh))
    k = wave_number(omega, depth, g)
    residual = np.abs(omega**2 - g * k * np.tanh(k * depth)) / omega**2
    assert residual.max() < 1e-14
    # d ln(omega^2) / d ln(k) is in [1, 2]: k is as well conditioned as omega^2
    np.testing.assert_allclose(k, k_true, rtol=1e-13)
    np.testing.assert_allclose(omega_from_k(k, depth, g), omega, rtol=1e-14)


def test_dispersion_matches_bracketing_root_finder():
    for omega, depth in [(0.3, 15.0), (1.1, 40.0), (2.5, 7.0), (0.05, 4000.0)]:
        ref = brentq(
            lambda k, w=omega, h=depth: G * k * math.tanh(k * h) - w * w,
            1e-12,
            100.0,
            xtol=1e-300,
            rtol=4 * np.finfo(float).eps,
        )
        assert wave_number(omega, depth, G) == pytest.approx(ref, rel=1e-14)


def test_dispersion_shallow_limit():
    # y tanh y = x  =>  y = sqrt(x) (1 + x/6 + O(x^2)), so k sqrt(g h)/omega -> 1
    omega = 0.5
    h = np.logspace(-9, -3, 13)
    x = omega**2 * h / G
    ratio = wave_number(omega, h, G) * np.sqrt(G * h) / omega
    assert np.all(np.abs(ratio - 1.0 - x / 6.0) < x**2 + 1e-15)


def test_dispersion_deep_limit_zero_and_shape():
    omega = np.array([[0.2, 0.7], [1.3, 4.0]])
    np.testing.assert_array_equal(wave_number(omega, math.inf, G), omega**2 / G)
    # kh >= 50: tanh(kh) == 1 in double precision
    np.testing.assert_allclose(wave_number(omega, 50.0 * G / 0.2**2, G), omega**2 / G, rtol=1e-15)
    assert wave_number(0.0, 30.0, G) == 0.0 and wave_number(0.0, math.inf, G) == 0.0
    np.testing.assert_array_equal(wave_number(-omega, 30.0, G), wave_number(omega, 30.0, G))
    assert wave_number(omega, 30.0, G).shape == (2, 2)
    assert np.ndim(wave_number(1.0, 30.0, G)) == 0
    assert omega_from_k(0.0, math.inf, G) == 0.0
    assert omega_from_k(0.3, math.inf, G) == pytest.approx(math.sqrt(G * 0.3), rel=1e-15)


# ---------------------------------------------------------------- Airy helpers


def _points_below_trough(n, wave, margin=0.0):
    """Random points in the water column below the lowest trough (and above the seabed)."""
    h = wave.depth
    bottom = -h + margin if math.isfinite(h) else -1.5 * wave.wavelength
    top = -wave.amplitude - margin
    xy = RNG.uniform(-wave.wavelength, wave.wavelength, (n, 2))
    return np.column_stack((xy, RNG.uniform(bottom, top, n)))


def _analytic(wave, points, t, z_eval=None):
    """Direct textbook formulas (Dean & Dalrymple 1991, ch. 4) with numpy cosh/sinh."""
    a, w, k, h = wave.amplitude, wave.omega, wave.wave_number, wave.depth
    beta = math.radians(wave.heading_deg)
    xh = points[:, 0] * math.cos(beta) + points[:, 1] * math.sin(beta)
    th = k * xh - w * t + wave.phase
    z = points[:, 2] if z_eval is None else z_eval
    if math.isfinite(h):
        cf = np.cosh(k * (z + h)) / math.sinh(k * h)
        sf = np.sinh(k * (z + h)) / math.sinh(k * h)
    else:
        cf = sf = np.exp(k * z)
    uh, uz = a * w * cf * np.cos(th), a * w * sf * np.sin(th)
    ah, az = a * w * w * cf * np.sin(th), -a * w * w * sf * np.cos(th)
    vel = np.column_stack((uh * math.cos(beta), uh * math.sin(beta), uz))
    acc = np.column_stack((ah * math.cos(beta), ah * math.sin(beta), az))
    return vel, acc, a * np.cos(th)


# ---------------------------------------------------------------- Airy wave


@pytest.mark.parametrize("H, T, depth", CASES)
def test_airy_matches_direct_formulas(H, T, depth):
    wave = AiryWave(H, T, 30.0, depth, G, phase=0.4)
    p = _points_below_trough(500, wave)
    vel, acc, eta = wave.kinematics(p, 3.7)
    v_ref, a_ref, eta_ref = _analytic(wave, p, 3.7)
    scale = wave.amplitude * wave.omega / math.tanh(wave.wave_number * depth)
    np.testing.assert_allclose(vel, v_ref, rtol=0, atol=1e-13 * scale)
    np.testing.assert_allclose(acc, a_ref, rtol=0, atol=1e-13 * scale * wave.omega)
    np.testing.assert_allclose(eta, eta_ref, rtol=0, atol=1e-14 * H)


@pytest.mark.parametrize("H, T, depth", CASES)
def test_airy_velocity_is_divergence_free_and_irrotational(H, T, depth):
    wave = AiryWave(H, T, 30.0, depth, G, phase=1.0)
    k = wave.wave_number
    d = 1e-4 / k
    p = _points_below_trough(200, wave, margin=2 * d)
    t = 2.3
    grad = np.empty((p.shape[0], 3, 3))  # grad[:, i, j] = d u_i / d x_j
    for j in range(3):
        e = np.zeros(3)
        e[j] = d
        grad[:, :, j] = (wave.kinematics(p + e, t)[0] - wave.kinematics(p - e, t)[0]) / (2 * d)
    div = grad[:, 0, 0] + grad[:, 1, 1] + grad[:, 2, 2]
    curl = np.column_stack(
        (
            grad[:, 2, 1] - grad[:, 1, 2],
            grad[:, 0, 2] - grad[:, 2, 0],
            grad[:, 1, 0] - grad[:, 0, 1],
        )
    )
    # velocity gradients are O(k a omega coth kh); central differences err by (k d)^2/6 ~ 2e-9
    # of that (truncation) plus eps/(k d) ~ 2e-12 (round-off)
    scale = k * wave.amplitude * wave.omega / math.tanh(k * depth)
    assert np.abs(grad).max() > 0.1 * scale  # the check is not vacuous
    assert np.abs(div).max() < 1e-7 * scale
    assert np.abs(curl).max() < 1e-7 * scale


@pytest.mark.parametrize("H, T, depth", CASES)
def test_airy_kinematic_surface_and_seabed_conditions(H, T, depth):
    wave = AiryWave(H, T, -45.0, depth, G, phase=0.2)
    xy = RNG.uniform(-wave.wavelength, wave.wavelength, (400, 2))
    t, dt = 5.1, 1e-4 * T
    surface = np.column_stack((xy, np.zeros(len(xy))))
    deta_dt = (wave.elevation(xy, t + dt) - wave.elevation(xy, t - dt)) / (2 * dt)
    vel, _, eta = wave.kinematics(surface, t)
    wet = eta >= 0.0  # z = 0 is wet only under crests
    assert wet.sum() > 100
    # linearized kinematic condition d(eta)/dt = w(z = 0); time truncation (omega dt)^2/6 ~ 7e-8
    np.testing.assert_allclose(
        vel[wet, 2], deta_dt[wet], rtol=0, atol=1e-6 * wave.amplitude * wave.omega
    )
    if math.isfinite(depth):
        for zb in (-depth, -depth - 3.0):  # at and below the seabed
            vb, ab, _ = wave.kinematics(np.column_stack((xy, np.full(len(xy), zb))), t)
            assert np.abs(vb[:, 2]).max() <= 1e-15 * wave.amplitude * wave.omega
            assert np.abs(ab[:, 2]).max() <= 1e-15 * wave.amplitude * wave.omega**2
        v_at = wave.kinematics(np.column_stack((xy, np.full(len(xy), -depth))), t)[0]
        v_below = wave.kinematics(np.column_stack((xy, np.full(len(xy), -depth - 3.0))), t)[0]
        np.testing.assert_array_equal(v_below, v_at)


@pytest.mark.parametrize("t", [0.7, 9.0, 21.5, 33.0])  # in the ramp (T_r = 24) and after it
@pytest.mark.parametrize("H, T, depth", CASES)
def test_acceleration_is_time_derivative_of_velocity(H, T, depth, t):
    wave = AiryWave(H, T, 120.0, depth, G, phase=2.0, ramp_time=24.0)
    p = _points_below_trough(300, wave)
    dt = 1e-4 * T
    dv = (wave.kinematics(p, t + dt)[0] - wave.kinematics(p, t - dt)[0]) / (2 * dt)
    acc = wave.kinematics(p, t)[1]
    # central difference truncation ~ (omega dt)^2 / 6 ~ 7e-8 of a omega^2 coth kh
    scale = wave.amplitude * wave.omega**2 / math.tanh(wave.wave_number * depth)
    np.testing.assert_allclose(acc, dv, rtol=0, atol=1e-6 * scale)


def test_ramp_factor_and_ramped_field():
    assert ramp_factor(-1.0, 10.0) == (0.0, 0.0)
    assert ramp_factor(0.0, 10.0) == (0.0, 0.0)
    assert ramp_factor(10.0, 10.0) == (1.0, 0.0)
    assert ramp_factor(3.0, 0.0) == (1.0, 0.0)
    r, dr = ramp_factor(2.5, 10.0)
    assert r == pytest.approx(0.5 * (1 - math.cos(math.pi / 4)), rel=1e-15)
    assert dr == pytest.approx(0.5 * math.pi / 10 * math.sin(math.pi / 4), rel=1e-15)
    ramped = AiryWave(2.0, 8.0, 0.0, 40.0, G, ramp_time=10.0)
    plain = AiryWave(2.0, 8.0, 0.0, 40.0, G)
    p = _points_below_trough(50, plain)
    v0, a0, e0 = ramped.kinematics(p, 0.0)
    assert not v0.any() and not a0.any() and not e0.any()
    v, _, e = ramped.kinematics(p, 2.5)
    vp, _, ep = plain.kinematics(p, 2.5)
    np.testing.assert_allclose(v, r * vp, rtol=1e-14, atol=0)
    np.testing.assert_allclose(e, r * ep, rtol=1e-14, atol=0)


@pytest.mark.parametrize("H, T, depth", CASES)
def test_wheeler_at_surface_equals_unstretched_at_still_water_level(H, T, depth):
    wave = AiryWave(H, T, 60.0, depth, G, phase=0.5, stretching="wheeler")
    xy = RNG.uniform(-wave.wavelength, wave.wavelength, (300, 2))
    t = 4.2
    eta = wave.elevation(xy, t)
    assert (eta > 0).any() and (eta < 0).any()
    p = np.column_stack((xy, eta))
    vel, acc, eta_out = wave.kinematics(p, t)
    v_ref, a_ref, _ = _analytic(wave, p, t, z_eval=np.zeros(len(p)))
    scale = wave.amplitude * wave.omega / math.tanh(wave.wave_number * depth)
    np.testing.assert_allclose(vel, v_ref, rtol=0, atol=1e-13 * scale)
    np.testing.assert_allclose(acc, a_ref, rtol=0, atol=1e-13 * scale * wave.omega)
    np.testing.assert_array_equal(eta_out, eta)
    if math.isfinite(depth):  # the seabed stays the seabed
        pb = np.column_stack((xy, np.full(len(xy), -depth)))
        v_ref, _, _ = _analytic(wave, pb, t)
        np.testing.assert_allclose(wave.kinematics(pb, t)[0], v_ref, rtol=0, atol=1e-13 * scale)


@pytest.mark.parametrize("stretching", ["none", "wheeler"])
def test_zero_kinematics_above_the_surface(stretching):
    wave = AiryWave(3.0, 9.0, 10.0, 30.0, G, stretching=stretching, ramp_time=5.0)
    xy = RNG.uniform(-100, 100, (400, 2))
    t = 3.0
    eta = wave.elevation(xy, t)
    for dz in (1e-9, 0.5, 40.0):
        vel, acc, eta_out = wave.kinematics(np.column_stack((xy, eta + dz)), t)
        assert not vel.any() and not acc.any()
        np.testing.assert_array_equal(eta_out, eta)


def test_unstretched_between_still_level_and_crest_holds_surface_values():
    wave = AiryWave(3.0, 9.0, 10.0, 30.0, G)
    xy = RNG.uniform(-100, 100, (400, 2))
    eta = wave.elevation(xy, 1.0)
    crest = eta > 0.05
    p = np.column_stack((xy, 0.5 * eta))[crest]
    v_ref, a_ref, _ = _analytic(wave, p, 1.0, z_eval=np.zeros(len(p)))
    vel, acc, _ = wave.kinematics(p, 1.0)
    np.testing.assert_allclose(vel, v_ref, rtol=0, atol=1e-14)
    np.testing.assert_allclose(acc, a_ref, rtol=0, atol=1e-14)


def test_no_overflow_for_very_large_kh():
    # T = 2 s in 1000 m: k h ~ 1000, cosh/sinh would overflow; the field is the deep-water one
    finite = AiryWave(0.5, 2.0, 0.0, 1000.0, G)
    deep = AiryWave(0.5, 2.0, 0.0, math.inf, G)
    p = np.column_stack((RNG.uniform(-5, 5, (200, 2)), RNG.uniform(-1200.0, -0.25, 200)))
    with np.errstate(over="raise", invalid="raise", divide="raise"):
        got = finite.kinematics(p, 1.3)
        ref = deep.kinematics(p, 1.3)
    for g_, r_ in zip(got, ref, strict=True):
        np.testing.assert_allclose(g_, r_, rtol=1e-12, atol=1e-300)
    with np.errstate(over="raise", invalid="raise", divide="raise"):  # far below, deep water
        assert not deep.kinematics(np.array([[0.0, 0.0, -1e6]]), 0.0)[0].any()


def test_superposition_equals_sum_of_single_waves():
    depth = 35.0
    w1 = AiryWave(2.0, 8.0, 30.0, depth, G, phase=0.3, ramp_time=12.0)
    w2 = AiryWave(1.2, 13.0, -60.0, depth, G, phase=1.1, ramp_time=12.0)
    both = superpose(w1, w2)
    direct = WaveComponents(
        [1.0, 0.6],
        [2 * math.pi / 8.0, 2 * math.pi / 13.0],
        [0.3, 1.1],
        [30.0, -60.0],
        depth,
        G,
        ramp_time=12.0,
    )
    p = np.column_stack((RNG.uniform(-200, 200, (500, 2)), RNG.uniform(-depth, -1.7, 500)))
    for t in (4.0, 30.0):
        s1, s2 = w1.kinematics(p, t), w2.kinematics(p, t)
        for got in (both.kinematics(p, t), direct.kinematics(p, t)):
            for g_, a_, b_ in zip(got, s1, s2, strict=True):
                np.testing.assert_allclose(g_, a_ + b_, rtol=0, atol=1e-14)
    assert both.n_components == 2
    with pytest.raises(ValueError):
        superpose(w1, AiryWave(1.0, 5.0, 0.0, depth + 1.0, G))


def test_many_components_are_evaluated_in_blocks():
    m = 600
    omegas = np.linspace(0.3, 1.5, m)
    comps = WaveComponents(np.full(m, 0.01), omegas, RNG.uniform(0, 2 * np.pi, m), 20.0, 80.0, G)
    p = np.column_stack((RNG.uniform(-50, 50, (5000, 2)), RNG.uniform(-80, -7, 5000)))
    vel, acc, eta = comps.kinematics(p, 2.0)
    vel2, acc2, eta2 = comps.kinematics(p[::-1], 2.0)  # order independent
    np.testing.assert_allclose(vel, vel2[::-1], rtol=1e-13, atol=1e-15)
    one = comps.kinematics(p[:1], 2.0)
    np.testing.assert_allclose(vel[:1], one[0], rtol=1e-13, atol=1e-15)


def test_invalid_wave_arguments():
    with pytest.raises(ValueError):
        AiryWave(1.0, 0.0, 0.0, 10.0, G)
    with pytest.raises(ValueError):
        AiryWave(1.0, 5.0, 0.0, -10.0, G)
    with pytest.raises(ValueError):
        AiryWave(1.0, 5.0, 0.0, 10.0, G, stretching="linear")  # type: ignore[arg-type]
    with pytest.raises(ValueError):
        AiryWave(1.0, 5.0, 0.0, 10.0, G).kinematics(np.zeros((4, 2)), 0.0)


# ---------------------------------------------------------------- current


def test_current_profile_interpolation():
    ascending = CurrentProfile((-100.0, -50.0, 0.0), (0.2, 0.5, 1.0), (350.0, 10.0, 30.0))
    descending = CurrentProfile((0.0, -50.0, -100.0), (1.0, 0.5, 0.2), (30.0, 10.0, 350.0))
    z = np.array([-300.0, -100.0, -75.0, -50.0, -25.0, 0.0])
    speed = np.array([0.2, 0.2, 0.35, 0.5, 0.75, 1.0])
    heading = np.radians([350.0, 350.0, 0.0, 10.0, 20.0, 30.0])  # 350 -> 10 turns through 0
    ref = np.column_stack((speed * np.cos(heading), speed * np.sin(heading), np.zeros(6)))
    for prof in (ascending, descending):
        np.testing.assert_allclose(prof.velocity(z), ref, rtol=0, atol=1e-15)
        p = np.column_stack((np.zeros((6, 2)), z))
        vel, acc, eta = prof.kinematics(p, 7.0)
        np.testing.assert_allclose(vel, ref, rtol=0, atol=1e-15)
        assert not acc.any() and not eta.any()
    above = ascending.kinematics(np.array([[0.0, 0.0, 0.1]]), 0.0)[0]
    assert not above.any()
    with pytest.raises(ValueError):
        CurrentProfile((0.0, -50.0, -20.0), (1.0, 0.5, 0.2), (0.0, 0.0, 0.0))
    with pytest.raises(ValueError):
        CurrentProfile((0.0, -50.0), (1.0,), (0.0, 0.0))


def test_uniform_current():
    cur = CurrentProfile.uniform(0.8, 90.0)
    vel = cur.velocity(np.array([-1e4, -3.0, 0.0]))
    np.testing.assert_allclose(vel, [[0.0, 0.8, 0.0]] * 3, rtol=0, atol=1e-15)
    assert cur == CurrentProfile.uniform(0.8, 90.0)
    assert cur != CurrentProfile.uniform(0.8, 90.0, ramp_time=3.0)
    assert CurrentProfile.from_levels([-10, 0], [0.1, 0.2], 45.0).headings_deg == (45.0, 45.0)


def test_ramped_current_acceleration_is_time_derivative_of_velocity():
    cur = CurrentProfile((-80.0, -10.0), (0.3, 1.2), (0.0, 40.0), ramp_time=20.0)
    p = np.column_stack((np.zeros((50, 2)), np.linspace(-100.0, 0.0, 50)))
    steady = cur.velocity(p[:, 2])
    for t in (0.5, 3.0, 10.0, 19.9, 25.0):  # not at the C1 kinks t = 0, T_r
        dt = 1e-4
        dv = (cur.kinematics(p, t + dt)[0] - cur.kinematics(p, t - dt)[0]) / (2 * dt)
        vel, acc, _ = cur.kinematics(p, t)
        r, _ = ramp_factor(t, 20.0)
        np.testing.assert_allclose(vel, r * steady, rtol=1e-15, atol=0)
        # truncation (pi dt / T_r)^2 / 6 of pi / (2 T_r) * 1.2 plus round-off eps / dt
        np.testing.assert_allclose(acc, dv, rtol=0, atol=1e-10)


# ---------------------------------------------------------------- fields


def test_still_water_and_environment_builder():
    p = RNG.uniform(-10, 0, (7, 3))
    still = fluid_field_from_environment(Environment())
    assert isinstance(still, StillWater)
    for arr, shape in zip(still.kinematics(p, 1.0), [(7, 3), (7, 3), (7,)], strict=True):
        assert arr.shape == shape and not arr.any()

    waves = Waves(kind="airy", height=2.0, period=9.0, heading_deg=15.0)
    env = Environment(depth=60.0, gravity=G_US, waves=waves)
    wave = fluid_field_from_environment(env, ramp_time=20.0)
    assert wave == AiryWave(2.0, 9.0, 15.0, 60.0, G_US, ramp_time=20.0)

    cur = fluid_field_from_environment(Environment(current=Current(0.5, 200.0)))
    assert cur == CurrentProfile.uniform(0.5, 200.0)
    cur = fluid_field_from_environment(Environment(current=Current(-0.5, 20.0)), ramp_time=4.0)
    assert cur == CurrentProfile.uniform(0.5, 200.0, ramp_time=4.0)

    both = fluid_field_from_environment(
        Environment(depth=60.0, waves=waves, current=Current(0.5, 200.0))
    )
    assert isinstance(both, CombinedField)
    assert both.current.ramp_time == 0.0 and both.wave.ramp_time == 0.0
    for f in (still, wave, cur, both):
        assert isinstance(f, FluidField)


def test_combined_field_adds_current_below_surface_only():
    wave = AiryWave(2.0, 9.0, 15.0, 60.0, G)
    cur = CurrentProfile((-60.0, 0.0), (0.1, 0.6), (200.0, 200.0))
    field = CombinedField(wave, cur)
    xy = RNG.uniform(-100, 100, (300, 2))
    eta = wave.elevation(xy, 2.0)
    p = np.column_stack((xy, RNG.uniform(-70.0, 0.0, 300)))
    p[:100, 2] = eta[:100] + 0.01  # dry
    vel, acc, e = field.kinematics(p, 2.0)
    vw, aw, ew = wave.kinematics(p, 2.0)
    wet = p[:, 2] <= eta
    np.testing.assert_array_equal(acc, aw)
    np.testing.assert_array_equal(e, ew)
    np.testing.assert_allclose(vel[wet], vw[wet] + cur.velocity(p[wet, 2]), rtol=0, atol=1e-15)
    assert not vel[~wet].any()
    # ramped: the current's r'(t) U adds to the acceleration below the surface
    field = CombinedField(
        AiryWave(2.0, 9.0, 15.0, 60.0, G, ramp_time=10.0),
        CurrentProfile.uniform(0.5, 30.0, ramp_time=10.0),
    )
    q = np.column_stack((xy, np.full(300, -5.0)))
    dt = 1e-4
    dv = (field.kinematics(q, 4.0 + dt)[0] - field.kinematics(q, 4.0 - dt)[0]) / (2 * dt)
    np.testing.assert_allclose(field.kinematics(q, 4.0)[1], dv, rtol=0, atol=1e-7)
