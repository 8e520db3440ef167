"""Tabulated motions: the cubic Hermite interpolant with central knot derivatives
(moorline.solvers.excitation), against analytic motions sampled into tables."""

from __future__ import annotations

import numpy as np
import pytest

from moorline.model import Motion
from moorline.solvers.excitation import history_value, knot_derivatives, motion_value

A, W = 3.0, 2 * np.pi / 10.0  # 3 m surge at a 10 s period


def _sampled(times: np.ndarray) -> Motion:
    return Motion("table", times=tuple(map(float, times)),
                  values=tuple((A * np.sin(W * t), 0.0, 0.5 * A * np.cos(W * t)) for t in times))


def _exact(t: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    s, c = np.sin(W * t), np.cos(W * t)
    return (np.array([A * s, 0.0, 0.5 * A * c]), np.array([A * W * c, 0.0, -0.5 * A * W * s]),
            np.array([-A * W * W * s, 0.0, -0.5 * A * W * W * c]))


def _errors(step: float, uneven: bool = False) -> np.ndarray:
    """Largest position, velocity and acceleration errors over 0..20 s, knots every
    ``step`` (``uneven``: steps alternating 0.6 and 1.4 times ``step``)."""
    times = np.arange(0.0, 20.0 + step / 2, step)
    if uneven:
        times[1:-1:2] -= 0.4 * step
    motion = _sampled(times)
    errors = np.zeros(3)
    for t in np.linspace(0.0, 20.0, 1201):
        got, want = motion_value(motion, float(t)), _exact(float(t))
        errors = np.maximum(errors, [np.abs(g - w).max() for g, w in zip(got, want,
                                                                           strict=True)])
    return errors


@pytest.mark.parametrize("uneven", [False, True])
def test_interpolation_error_orders(uneven: bool) -> None:
    """A C1 Hermite interpolant with second-order knot derivatives: position error O(h^3),
    velocity O(h^2), acceleration O(h) (halving h divides them by ~8, ~4, ~2). The linear
    interpolation it replaces had a velocity error O(h) (the next interval's slope) and no
    acceleration at all (error A w^2 = 1.18 m/s^2)."""
    coarse, fine = _errors(0.5, uneven), _errors(0.25, uneven)
    orders = np.log2(coarse / fine)
    assert orders[0] > 2.6 and orders[1] > 1.7 and orders[2] > 0.8, orders
    # Sizes (h: the largest step, 0.25 or 0.35 s): the knot derivative's truncation error,
    # largest at the one-sided ends, is h^2/3 |d3x/dt3| (A w^3 = 0.74 m/s^3); the velocity
    # error is at most that, and it makes an acceleration error of at most 6 / h times it,
    # 2 h |d3x/dt3| (inner knots: h |d3x/dt3|).
    h = 0.25 * (1.4 if uneven else 1.0)
    assert fine[1] < 1.02 * h**2 / 3 * A * W**3, fine
    assert fine[2] < 2 * h * A * W**3, fine


def test_no_jump_at_the_last_knot() -> None:
    """The velocity at the table's last time is the one-sided end derivative (close to the
    motion's), continuous from the left; the old code dropped it to zero there."""
    times = np.arange(0.0, 20.0 + 1e-9, 0.25)
    motion = _sampled(times)
    end = float(times[-1])
    _, v_end, _ = motion_value(motion, end)
    _, v_before, _ = motion_value(motion, end - 1e-6)
    _, v_exact, _ = _exact(end)
    np.testing.assert_allclose(v_end, v_before, atol=1e-5)
    np.testing.assert_allclose(v_end, v_exact, atol=0.01 * A * W)
    assert abs(v_end[0]) > 0.9 * A * W  # sin(w 20 s) = sin(4 pi): the surge speed is A w
    held, v_after, a_after = motion_value(motion, end + 0.1)  # held after the table
    np.testing.assert_array_equal(held, motion.values[-1])
    assert not v_after.any() and not a_after.any()


def test_position_velocity_acceleration_are_one_trajectory() -> None:
    """The velocity is the position's derivative and the acceleration the velocity's
    (central differences of the interpolant itself, inside intervals and across knots)."""
    motion = _sampled(np.array([0.0, 0.7, 1.1, 2.0, 2.4, 3.5, 4.0]))
    eps = 1e-6
    for t in np.linspace(0.05, 3.95, 40):
        x_m, v_m, _ = motion_value(motion, t - eps)
        x_p, v_p, _ = motion_value(motion, t + eps)
        _, v, a = motion_value(motion, t)
        np.testing.assert_allclose((x_p - x_m) / (2 * eps), v, atol=1e-6)
        if not np.isclose(np.asarray(motion.times), t, atol=2 * eps).any():
            np.testing.assert_allclose((v_p - v_m) / (2 * eps), a, atol=1e-4)
    for t, value in zip(motion.times, motion.values, strict=True):  # through the knots
        np.testing.assert_allclose(motion_value(motion, t)[0], value, atol=1e-12)


def test_ramp_and_hold_stays_held_without_overshoot() -> None:
    """0 -> 2 m in 1 s, held 1 s, back in 1 s (a knot next to a constant interval gets a
    zero derivative): exactly held in the hold, never beyond 0..2 m."""
    motion = Motion("table", times=(0.0, 1.0, 2.0, 3.0),
                    values=((0.0, 0, 0), (2.0, 0, 0), (2.0, 0, 0), (0.0, 0, 0)))
    samples = [motion_value(motion, t) for t in np.linspace(0.0, 3.0, 601)]
    x = np.array([s[0][0] for s in samples])
    assert x.min() >= -1e-12 and x.max() <= 2.0 + 1e-12
    for t in np.linspace(1.0, 2.0, 11):
        x_t, v_t, a_t = motion_value(motion, t)
        assert x_t[0] == pytest.approx(2.0, abs=1e-12) and v_t[0] == pytest.approx(0.0, abs=1e-12)


def test_knot_derivatives_are_exact_for_a_parabola() -> None:
    """Three-point derivatives reproduce a quadratic exactly on any spacing (inner and end
    knots), and a straight line stays straight (two knots: the slope)."""
    times = np.array([0.0, 0.3, 1.0, 1.2, 2.5])
    values = np.column_stack([times**2 - times, 2 * times, np.full(5, 4.0)])
    d = knot_derivatives(times, values)
    np.testing.assert_allclose(d[:, 0], 2 * times - 1, atol=1e-12)
    np.testing.assert_allclose(d[:, 1], 2.0, atol=1e-12)
    np.testing.assert_array_equal(d[:, 2], 0.0)
    line = Motion("table", times=(0.0, 4.0), values=((0.0, 0, 0), (8.0, 0, 0)))
    x, v, a = motion_value(line, 1.0)
    assert (x[0], v[0], a[0]) == pytest.approx((2.0, 2.0, 0.0), abs=1e-12)


def test_force_histories_stay_linear() -> None:
    """A force table (a step load, a ramp) keeps its linear interpolation: steps and ramps
    exactly as tabulated."""
    ramp = Motion("table", times=(0.0, 1.0, 1.0e6),
                  values=((0.0, 0.0, 0.0), (0.0, 0.0, -10.0), (0.0, 0.0, -10.0)))
    assert history_value(ramp, 0.25)[2] == pytest.approx(-2.5, abs=1e-12)
    assert history_value(ramp, 5.0)[2] == -10.0


def test_tabulated_fairlead_motion_follows_the_harmonic_to_the_last_record() -> None:
    """The OC3 line with its fairlead surging 5 m at 10 s, once as the harmonic motion and
    once as that motion sampled every 0.1 s into a table ending at the run's end (20 s):
    fairlead tensions agree over the run (measured 0.45 % of the peak, 1.0 % with 0.25 s
    knots: first order, from the acceleration) and at the last record (measured 0.025 %);
    the old linear table set the velocity to zero at its last time (3.1 m/s too low here),
    a false final tension jump of the kind issue 14 reports (1113 to 939 kN)."""
    import dataclasses
    from pathlib import Path

    from moorline.io.moordyn import read_moordyn
    from moorline.model import DynamicsSettings
    from moorline.solvers.dynamics import simulate

    base = read_moordyn(Path(__file__).parent / "data" / "moordyn" / "oc3.dat")

    def single(motion: Motion):
        fair = dataclasses.replace(base.points["fairlead1"], motion=motion)
        return dataclasses.replace(base, points={"anchor1": base.points["anchor1"],
                                                 "fairlead1": fair},
                                   lines={"line1": base.lines["line1"]})

    period, amplitude, duration = 10.0, 5.0, 20.0
    knots = np.arange(0.0, duration + 1e-9, 0.1)
    table = Motion("table", times=tuple(map(float, knots)),
                   values=tuple((amplitude * np.sin(2 * np.pi * t / period), 0.0, 0.0)
                                for t in knots))
    harmonic = Motion("harmonic", amplitude=(amplitude, 0.0, 0.0), period=period)
    settings = DynamicsSettings(duration=duration, dt=0.05)
    runs = [simulate(single(m), settings) for m in (harmonic, table)]
    assert all(r.success for r in runs)
    ref, got = (r.end_tension("line1", "b") for r in runs)
    assert runs[1].time[-1] == pytest.approx(duration)
    assert np.abs(got - ref).max() < 0.01 * ref.max()
    assert abs(got[-1] - ref[-1]) < 1e-3 * ref.max()
