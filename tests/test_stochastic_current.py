"""Stochastic analysis with a steady current (issue 15, deliverable 3): the Gaussian
expectations of the quadratic drag about a non-zero mean flow
(:mod:`moorline.solvers.drag_linearization`) and the frequency-domain response of a riser in
waves and current against the nonlinear time domain in the same sea and current."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
import xarray as xr
from click.testing import CliRunner

from moorline.cli import cli
from moorline.io import load_case
from moorline.io.case_writer import write_case
from moorline.model import Current, DynamicsSettings, StaticsSettings, StochasticSettings
from moorline.solvers import drag_linearization as dl
from moorline.solvers.dynamics import simulate
from moorline.solvers.statics import solve_statics
from moorline.solvers.stochastic import solve_stochastic
from moorline.verification import stochastic_riser as sr

PLANE = np.diag([1.0, 1.0, 0.0])


def _mc(mean: np.ndarray, chol: np.ndarray, n: int, seed: int):
    """Monte Carlo samples of ``|w| w`` and of the Jacobian terms, with their means and
    standard errors."""
    rng = np.random.default_rng(seed)
    w = mean + rng.standard_normal((n, chol.shape[1])) @ chol.T
    norm = np.linalg.norm(w, axis=1)
    f = norm[:, None] * w
    outer = (w[:, :, None] * w[:, None, :]) / norm[:, None, None]
    se = lambda x: x.std(axis=0) / math.sqrt(n)  # noqa: E731
    return (f.mean(0), se(f)), (norm.mean(), se(norm)), (outer.mean(0), se(outer))


def _grid(mean: np.ndarray, chol: np.ndarray, n: int):
    """``E[|w| w]`` and ``E[|w| I + w w^T / |w|]`` of ``w = mean + chol xi`` (two axes) by
    the trapezoidal rule on an ``n^2`` grid of ``xi`` over [-9, 9]^2."""
    xi = np.linspace(-9, 9, n)
    X1, X2 = np.meshgrid(xi, xi, indexing="ij")
    wt = np.exp(-0.5 * (X1**2 + X2**2))
    wt /= wt.sum()
    w = mean + np.stack([X1, X2], -1) @ chol.T
    norm = np.linalg.norm(w, axis=-1)
    return (np.einsum("ij,ij,ijk->k", wt, norm, w),
            (wt * norm).sum() * np.eye(2) + np.einsum("ij,ijk,ijl->kl", wt / norm, w, w))


@pytest.mark.parametrize("U,sigma", [(0.0, 1.0), (0.4, 1.0), (-1.3, 0.7), (3.0, 1.0)])
def test_scalar_expectations_against_monte_carlo(U, sigma):
    """Closed forms against 10^6 samples: within 4 standard errors of the sample mean."""
    e_sq, e_abs = dl.scalar_expectations(np.array(U), np.array(sigma))
    rng = np.random.default_rng(7)
    x = U + sigma * rng.standard_normal(1_000_000)
    for value, sample in ((e_sq, x * np.abs(x)), (e_abs, np.abs(x))):
        assert abs(float(value) - sample.mean()) <= 4 * sample.std() / math.sqrt(x.size)


def test_zero_current_limit_is_borgman():
    """U = 0: E|X| = (2/pi)^(1/2) sigma, so the gain 2 E|X| is Borgman's (8/pi)^(1/2) sigma,
    and E[X|X|] = 0 (exact); the planar (collinear) vector case reduces to it."""
    sigma = np.array([0.3, 1.0, 2.5])
    e_sq, e_abs = dl.scalar_expectations(np.zeros(3), sigma)
    assert np.allclose(2 * e_abs, math.sqrt(8 / math.pi) * sigma, rtol=1e-15, atol=0)
    assert np.all(e_sq == 0)
    f, g = dl.vector_expectations(np.zeros((1, 3)), np.diag([0.49, 0, 0])[None], PLANE[None])
    assert g[0, 0, 0] == pytest.approx(math.sqrt(8 / math.pi) * 0.7, rel=1e-15)
    # an isotropic plane (Rayleigh): E|w| = sigma (pi/2)^(1/2), E[w w^T/|w|] = E|w| I / 2
    f, g = dl.vector_expectations(np.zeros((1, 3)), 0.49 * PLANE[None], PLANE[None])
    assert np.allclose(g[0], 1.5 * 0.7 * math.sqrt(math.pi / 2) * PLANE, rtol=1e-12,
                       atol=1e-15)
    assert np.allclose(f, 0, atol=1e-15)


def test_large_current_limit_and_the_mean_derivative():
    """U >> sigma: the gain 2 E|X| -> 2|U| and E[X|X|] -> U|U| (1 + sigma^2/U^2) (exact at
    U = 40 sigma in double precision); dE[X|X|]/dU = 2 E|X| (central difference)."""
    e_sq, e_abs = dl.scalar_expectations(np.array([40.0, -40.0]), np.array([1.0, 1.0]))
    assert np.allclose(2 * e_abs, [80.0, 80.0], rtol=1e-15)
    assert np.allclose(e_sq, [1601.0, -1601.0], rtol=1e-15)
    U, h = np.array([-0.8, 0.1, 0.9]), 1e-5
    plus, _ = dl.scalar_expectations(U + h, np.ones(3))
    minus, _ = dl.scalar_expectations(U - h, np.ones(3))
    assert np.allclose((plus - minus) / (2 * h), 2 * dl.scalar_expectations(U, np.ones(3))[1],
                       rtol=1e-8)


def test_normal_plane_expectations_against_a_fine_grid_and_monte_carlo():
    """A correlated Gaussian over a cable's normal plane with a mean off its axes (the
    polar rule) against a 3601^2 trapezoidal grid over the Gaussian (relative 1e-6) and
    against 10^6 samples (4 standard errors); and a one-axis fluctuation with the mean off
    the axis (the dense line rule)."""
    chol = np.array([[0.8, 0.0], [0.5, 0.4]])
    W = np.array([0.3, -0.2, 0.0])
    cov = np.zeros((3, 3))
    cov[:2, :2] = chol @ chol.T
    f, g = dl.vector_expectations(W[None], cov[None], PLANE[None])
    grid_f, grid_g = _grid(W[:2], chol, 3601)
    assert np.allclose(f[0, :2], grid_f, rtol=1e-6)
    assert np.allclose(g[0, :2, :2], grid_g, rtol=1e-6)
    (mf, sf), (ma, sa), (mo, so) = _mc(W[:2], chol, 1_000_000, 11)
    assert np.all(np.abs(f[0, :2] - mf) <= 4 * sf)
    assert np.all(np.abs(g[0, :2, :2] - (ma * np.eye(2) + mo)) <= 4 * (sa + so))
    # one axis (x), the mean partly across it
    f1, g1 = dl.vector_expectations(W[None], np.diag([0.36, 0, 0])[None], PLANE[None])
    (mf, sf), (ma, sa), (mo, so) = _mc(W[:2], np.array([[0.6], [0.0]]), 1_000_000, 12)
    assert np.all(np.abs(f1[0, :2] - mf) <= 4 * sf + 1e-12)
    assert np.all(np.abs(g1[0, :2, :2] - (ma * np.eye(2) + mo)) <= 4 * (sa + so) + 1e-12)


@pytest.mark.parametrize("W,chol", [
    # a line in a current: the fluctuation a thousandth of the mean flow (the OC3 lines on
    # the seabed in a 1 m/s current); the old polar rule about the origin sampled the
    # needle-shaped peak every 0.025 rad for a width of 0.001 rad and gave zero drag
    ((0.8, -0.6), ((2e-3, 0.0), (1e-3, 5e-4))),
    ((0.05, 0.02), ((2e-3, 0.0), (1e-3, 5e-4))),  # 20 standard deviations out
    ((1.0, 0.0), ((1e-2, 0.0), (0.0, 1e-5))),  # elongated: axis ratio 1000
])
def test_normal_plane_expectations_with_a_strong_mean_flow(W, chol):
    """The mean flow far outside the fluctuation (Mahalanobis distance 20 to 10^6): against
    an 801^2 trapezoidal grid over the Gaussian (the integrand is smooth there: relative
    1e-8) and 2 x 10^5 samples (4 standard errors)."""
    W3, chol = np.array([*W, 0.0]), np.array(chol)
    cov = np.zeros((3, 3))
    cov[:2, :2] = chol @ chol.T
    f, g = dl.vector_expectations(W3[None], cov[None], PLANE[None])
    grid_f, grid_g = _grid(W3[:2], chol, 801)
    assert np.allclose(f[0, :2], grid_f, rtol=1e-8, atol=1e-8 * np.abs(grid_f).max())
    assert np.allclose(g[0, :2, :2], grid_g, rtol=1e-8, atol=1e-8 * np.abs(grid_g).max())
    (mf, sf), (ma, sa), (mo, so) = _mc(W3[:2], chol, 200_000, 14)
    assert np.all(np.abs(f[0, :2] - mf) <= 4 * sf + 1e-14)
    assert np.all(np.abs(g[0, :2, :2] - (ma * np.eye(2) + mo)) <= 4 * (sa + so) + 1e-14)


def test_point_expectations_against_monte_carlo():
    """Three axes (a buoy): Gauss-Hermite against 2x10^6 samples, within 4 standard errors
    plus the quadrature's own error at the kink (1.5e-3 relative: at zero mean against the
    exact Maxwell value, E|w| = 2 (2/pi)^(1/2) sigma, G = 4/3 E|w| I)."""
    f, g = dl.vector_expectations(np.zeros((1, 3)), np.eye(3)[None], np.eye(3)[None])
    exact = 4 / 3 * 2 * math.sqrt(2 / math.pi)
    quad = abs(g[0, 0, 0] / exact - 1)
    assert quad < 1.5e-3
    W = np.array([1.0, 0.3, -0.2])
    chol = np.array([[0.9, 0, 0], [0.2, 0.5, 0], [0.1, -0.1, 0.3]])
    f, g = dl.vector_expectations(W[None], (chol @ chol.T)[None], np.eye(3)[None])
    (mf, sf), (ma, sa), (mo, so) = _mc(W, chol, 2_000_000, 13)
    assert np.all(np.abs(f[0] - mf) <= 4 * sf + 1.5e-3 * np.abs(f[0]))
    J = ma * np.eye(3) + mo
    assert np.all(np.abs(g[0] - J) <= 4 * (sa + so) + 1.5e-3 * np.abs(g[0]).max())


# --- the riser in waves and a 1 m/s current: frequency domain against the time domain ---
# Tolerance 5 % on standard deviations: with DSA amplitudes the time-domain record has the
# spectral variance of its linear part exactly (Parseval; no sampling scatter of the sea),
# so the difference is the drag's non-linearity the linearization leaves out. For zero
# current it is about 10 % low at Cd 1.2 (stochastic-riser); with U / sigma between about 1.5
# (top) and 8 (bottom) the drag is close to linear in the fluctuation, its neglected
# (non-Gaussian, sum-frequency) part of order (sigma / U)^2 smaller: 5 %.

def _current_riser(heading: float = 0.0, speed: float = 1.0):
    base = sr.riser_system()
    return replace(base, environment=replace(base.environment,
                                             current=Current(speed=speed,
                                                             heading_deg=heading)))


def _time_domain(system):
    start = solve_statics(system, StaticsSettings(current_drag=True))
    td = simulate(system, DynamicsSettings(duration=2 * sr.RECORD, dt=sr.DT, ramp_time=20.0),
                  initial=start, output_every=sr.DT)
    second = td.time >= sr.RECORD - 1e-9
    return start, td.positions[second], td.tension[second], td


@pytest.fixture(scope="module")
def in_current():
    system = _current_riser()
    fd = solve_stochastic(system, StochasticSettings())
    return system, fd, _time_domain(system)


def test_riser_in_current_against_the_time_domain(in_current):
    system, fd, (_, x, T, _) = in_current
    assert fd.success and fd.counters["mean_state_iterations"] >= 1
    for td_std, fd_std in ((x[:, sr.MID_NODE, 0].std(), fd.displacement_std[sr.MID_NODE, 0]),
                           (x[:, sr.MID_NODE, 2].std(), fd.displacement_std[sr.MID_NODE, 2]),
                           (T[:, -1].std(), fd.tension_std[-1]),
                           (T[:, 0].std(), fd.tension_std[0])):
        assert fd_std == pytest.approx(td_std, rel=0.05)
    # the current matters: the zero-current response is less than half of it
    still = solve_stochastic(sr.riser_system(), StochasticSettings())
    assert still.displacement_std[sr.MID_NODE, 0] < 0.5 * x[:, sr.MID_NODE, 0].std()


def test_the_waves_mean_drag_against_the_time_domain(in_current):
    """The mean drag of waves plus current exceeds the current's steady drag,
    E[(U + u')|U + u'|] > U|U|: the time average of the drag on the line over the
    time-domain record (the quadratic law on the simulated relative velocity) exceeds the
    steady drag at the current-only static state by the excess the analysis loads its mean
    state with (its node loads ``E[f] - f(U)``), within 5 % (a second-order quantity; the
    standard deviations agree within 0.5 %); a one-way current-only analysis has no excess
    (100 % off). (The mean tension is not compared: the time domain's has second-order
    geometric terms a linear analysis has not, 18 N at zero current.)"""
    import moorline.solvers.stochastic as stochastic
    from moorline.physics import hydro
    from moorline.waves import fluid_field_from_environment

    system, fd, (start, _, _, td) = in_current
    m, el = start.mesh, start.mesh.elements
    field = fluid_field_from_environment(system.environment)

    def line_drag(x, v, t):
        u = field.kinematics(0.5 * (x[el[:, 0]] + x[el[:, 1]]), t)[0]
        f = hydro.drag_forces(x, v, u, el, m.length0, m.diameter, m.Cd, m.Ct,
                              m.water_density)[0]
        return f.sum(axis=(0, 1))

    steps = np.flatnonzero(td.time >= sr.RECORD - 1e-9)[:-1]  # one record
    mean_td = np.mean([line_drag(td.positions[k], td.velocities[k], td.time[k])
                       for k in steps], axis=0)
    current = stochastic._current_field(system)
    u0 = current.kinematics(0.5 * (start.positions[el[:, 0]] + start.positions[el[:, 1]]),
                            0.0)[0]
    steady = hydro.drag_forces(start.positions, 0 * start.positions, u0, el, m.length0,
                               m.diameter, m.Cd, m.Ct, m.water_density)[0].sum(axis=(0, 1))
    lin, _, _ = stochastic._mean_state(system, StochasticSettings(), None, current)
    excess_fd = lin.increment.sum(axis=0)
    assert excess_fd[0] > 0.02 * steady[0]  # the waves add 3 % to the current's drag
    assert excess_fd[0] == pytest.approx(mean_td[0] - steady[0], rel=0.05)


def test_a_linearization_that_does_not_converge_ends_the_mean_state_loop():
    """Fail fast: the linearization about the current-only state stops at its cap (2
    iterations for a tolerance of 1e-12) and no further statics are solved."""
    r = solve_stochastic(_current_riser(), StochasticSettings(max_iterations=2,
                                                              tolerance=1e-12))
    assert not r.success and r.iterations == 2
    assert r.counters["mean_state_iterations"] == 0
    assert "did not converge in 2 iterations" in r.message and "statics 0" in r.message


def test_zero_mean_formula_about_the_current_state_fails(in_current, monkeypatch):
    """Borgman's zero-mean gain used about the current's static state (the current ignored
    in the linearization) misses the time domain by far more than the tolerance."""
    system, _, (_, x, _, _) = in_current
    scalar, vector = dl.scalar_expectations, dl.vector_expectations
    monkeypatch.setattr(dl, "scalar_expectations", lambda U, s: scalar(0 * U, s))
    monkeypatch.setattr(dl, "vector_expectations",
                        lambda W, c, p, *a: vector(0 * W, c, p, *a))
    wrong = solve_stochastic(system, StochasticSettings())
    assert abs(wrong.displacement_std[sr.MID_NODE, 0] / x[:, sr.MID_NODE, 0].std() - 1) > 0.2


@pytest.mark.slow
def test_oblique_current_against_the_time_domain():
    """A 0.5 m/s current at 60 degrees to the waves: the normal relative velocity has two
    components (the polar rule over the normal plane), the riser moves out of its plane."""
    system = _current_riser(heading=60.0, speed=0.5)
    fd = solve_stochastic(system, StochasticSettings())
    _, x, T, _ = _time_domain(system)
    for k in range(3):
        assert fd.displacement_std[sr.MID_NODE, k] == pytest.approx(
            x[:, sr.MID_NODE, k].std(), rel=0.05)
    assert fd.tension_std[-1] == pytest.approx(T[:, -1].std(), rel=0.05)


def test_stochastic_with_current_from_a_case_file(tmp_path):
    """The read-time refusal is gone: ``moorline run`` on a case with a 1 m/s current and a
    stochastic analysis converges and writes the analysis' standard deviations."""
    system = replace(_current_riser(), analyses=(StaticsSettings(current_drag=True),
                                                 StochasticSettings()))
    path = write_case(system, tmp_path / "riser_current.yaml")
    result = CliRunner().invoke(cli, ["run", str(path), "--out", str(tmp_path / "out"),
                                      "--quiet", "--json"])
    assert result.exit_code == 0, result.output
    with xr.open_dataset(tmp_path / "out" / system.name / "results.nc",
                         group="stochastic") as ds:
        assert ds.attrs["status"] == "converged"
        direct = solve_stochastic(system, StochasticSettings())
        assert np.allclose(ds["tension_std"].values, direct.tension_std, rtol=1e-9)


def test_bodies_in_a_current_run_from_a_case_file(tmp_path):
    """Tuah's disc buoy in its random sea with a 1 m/s current (the case is in US units),
    written as a case file, read back and run: the linearization about the current converges
    (issue 15: the statics carries the current's drag on bodies, and the bodies feel the
    drag on their lines' end elements). The exact check of a body's drag about a current is
    tests/test_hydrodynamics.py."""
    from moorline.verification import tuah_ex5_random

    system, _ = tuah_ex5_random.random_system()
    assert system.units == "US"
    system = replace(system, environment=replace(system.environment,
                                                 current=Current(speed=1.0 / 0.3048)),
                     analyses=(StaticsSettings(), StochasticSettings()))
    loaded = load_case(write_case(system, tmp_path / "disc.yaml"))
    r = solve_stochastic(loaded, StochasticSettings())
    assert r.success, r.message
    assert r.counters["mean_state_iterations"] >= 1 and np.all(np.isfinite(r.body_std))


@pytest.mark.slow
def test_buoy_in_current_against_the_time_domain():
    """A buoy (free point with volume, added mass and drag area) at mid-depth of the riser
    (Cd 0.3) in waves and a 1 m/s current at 30 degrees: its three-dimensional drag
    linearized about the current (Gauss-Hermite over the three axes); the buoy's motion and
    the end tensions against the time domain, within 5 %."""
    from moorline.model import Line, Point

    base = sr.riser_system(Cd=0.3)
    buoy = Point("buoy", "free", (5.0, 0.0, -27.5), mass=50.0, volume=0.4, Ca=0.5, Cd=0.6,
                 drag_area=0.5)
    lines = {"lower": Line("lower", "rope", sr.LENGTH / 2, 10, "anchor", "buoy"),
             "upper": Line("upper", "rope", sr.LENGTH / 2, 10, "buoy", "top")}
    system = replace(base, points={**base.points, "buoy": buoy}, lines=lines,
                     environment=replace(base.environment,
                                         current=Current(speed=1.0, heading_deg=30.0)))
    fd = solve_stochastic(system, StochasticSettings())
    start, x, T, _ = _time_domain(system)
    node = start.mesh.point_node[start.mesh.point_index("buoy")]
    assert np.allclose(fd.displacement_std[node], x[:, node].std(axis=0), rtol=0.05)
    assert np.allclose(fd.tension_std[[0, -1]], T[:, [0, -1]].std(axis=0), rtol=0.05)
