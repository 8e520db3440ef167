"""Periodic response by harmonic balance (the Fourier method of Tcheou 1997)."""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from click.testing import CliRunner

from moorline.cli import cli
from moorline.errors import MoorlineError
from moorline.io import load_case
from moorline.model import (
    Environment,
    HarmonicSettings,
    Line,
    LineType,
    Motion,
    Point,
    StaticsSettings,
    System,
)
from moorline.solvers.harmonic import solve_harmonic
from moorline.solvers.statics import solve_statics

MASS, TENSION, HALF, F = 10.0, 1000.0, 5.0, 0.05  # kg, N, m, N


EA = 1.0e7  # N


def string_mass(period: float, force: float = F) -> System:
    """A point mass between two taut weightless strings in air, forced across the strings:
    for small motion the oscillator ``m u'' + (2 T / l) u = F sin(w t)``."""
    ea = EA
    stretch = TENSION / ea
    lt = LineType("s", diameter=0.01, mass_per_length=1e-9, EA=ea, Cd=0.0, Ca=0.0)
    points = {"a": Point("a", "fixed", (-HALF * (1 + stretch), 0.0, 0.0)),
              "b": Point("b", "fixed", (HALF * (1 + stretch), 0.0, 0.0)),
              "m": Point("m", "free", (0.0, 0.0, 0.0), mass=MASS,
                         force_history=Motion("harmonic", amplitude=(0.0, 0.0, force),
                                              period=period))}
    lines = {"left": Line("left", "s", HALF, 1, "a", "m"),
             "right": Line("right", "s", HALF, 1, "m", "b")}
    env = Environment(water_density=0.0, gravity=0.0)
    return System("string-mass", environment=env, line_types={"s": lt}, points=points,
                  lines=lines)


@pytest.mark.parametrize("ratio", [0.5, 2.0])
def test_linear_oscillator_amplitude_and_phase(ratio):
    """Small motion below and above resonance: the first harmonic is F / (k - m w^2) in
    phase (below) or in opposition (above), ``k = 2 T / l`` with ``l`` the stretched length;
    the higher harmonics vanish."""
    k = 2 * TENSION / (HALF * (1 + TENSION / EA))
    w = ratio * math.sqrt(k / MASS)
    system = string_mass(2 * math.pi / w)
    result = solve_harmonic(system, HarmonicSettings(period=2 * math.pi / w, harmonics=3))
    node = result.mesh.point_node[result.mesh.point_index("m")]
    exact = F / (k - MASS * w * w)
    # sin(w t) forcing: the response is exact * sin(w t), the B_1 coefficient
    assert result.coefficients[2, node, 2] == pytest.approx(exact, rel=1e-4)
    assert abs(result.coefficients[1, node, 2]) < 1e-8 * abs(exact)
    assert np.abs(result.coefficients[3:, node, 2]).max() < 1e-3 * abs(exact)
    assert result.iterations <= 3


def _shooting_coefficients(period: float, force: float) -> tuple[float, float]:
    """Sine coefficients ``b1``, ``b3`` of the periodic response of the exact string-mass
    ODE ``m u'' + 2 T(u) u / l(u) = F sin(w t)``, ``l = (a^2 + u^2)^(1/2)``,
    ``T = EA (l - l0) / l0`` (``a`` the stretched half span, ``l0`` the unstretched half):
    an independent solution by shooting (scipy). The response is odd in time and symmetric
    about its quarter period, so ``u(0) = 0`` and ``u'(T/4) = 0`` fix it."""
    from scipy.integrate import solve_ivp
    from scipy.optimize import brentq

    a = HALF * (1 + TENSION / EA)
    w = 2 * math.pi / period

    def rhs(t, y):
        length = math.hypot(a, y[0])
        tension = EA * (length - HALF) / HALF
        return [y[1], (force * math.sin(w * t) - 2 * tension * y[0] / length) / MASS]

    def quarter(v0):
        sol = solve_ivp(rhs, (0, period / 4), [0.0, v0], rtol=1e-12, atol=1e-14)
        return sol.y[1, -1]

    k = 2 * TENSION / HALF
    v_lin = w * force / (k - MASS * w * w)
    scan = np.linspace(0.02, 1.5, 38) * v_lin  # the first sign change: the small branch
    q = [quarter(v) for v in scan]
    j = next(i for i in range(len(q) - 1) if q[i] * q[i + 1] < 0)
    v0 = brentq(quarter, scan[j], scan[j + 1], xtol=1e-14)
    t = np.linspace(0, period, 4001)
    sol = solve_ivp(rhs, (0, period), [0.0, v0], t_eval=t, rtol=1e-12, atol=1e-14)
    u = sol.y[0]
    weights = np.full(len(t), period / (len(t) - 1))
    weights[[0, -1]] *= 0.5  # trapezoid: spectrally accurate for a periodic integrand
    return tuple(2 / period * float(np.sum(weights * u * np.sin(n * w * t))) for n in (1, 3))


def test_large_motion_matches_the_exact_nonlinear_oscillator():
    """At larger amplitude the string's geometric stiffening appears (a third harmonic, a
    first harmonic below the linear one): the harmonic-balance coefficients against the
    periodic solution of the exact ODE found by shooting."""
    k = 2 * TENSION / HALF
    w = 0.5 * math.sqrt(k / MASS)
    period, big = 2 * math.pi / w, 10.0  # N: 14 % below the linear amplitude
    system = string_mass(period, force=big)
    result = solve_harmonic(system, HarmonicSettings(period=period, harmonics=7))
    node = result.mesh.point_node[result.mesh.point_index("m")]
    b1, b3 = _shooting_coefficients(period, big)
    linear = big / (k - MASS * w * w)
    assert b1 < 0.9 * linear and abs(b3) > 2e-2 * abs(b1)  # the reference is nonlinear
    # 7 harmonics: the truncated ones are below 1e-6 of b1 here
    assert result.coefficients[2, node, 2] == pytest.approx(b1, rel=1e-6)
    assert result.coefficients[6, node, 2] == pytest.approx(b3, rel=1e-4)


def test_unforced_system_stays_static():
    system = string_mass(1.0, force=0.0)
    static = solve_statics(system)
    result = solve_harmonic(system, HarmonicSettings(period=1.0, harmonics=2), static)
    assert result.iterations == 0
    assert np.allclose(result.positions, static.positions[None], atol=1e-12)


def test_refuses_bad_settings_and_a_wave_period_that_does_not_divide():
    system = string_mass(1.0)
    with pytest.raises(MoorlineError):
        solve_harmonic(system, HarmonicSettings(period=0.0))
    from moorline.model import Waves

    wavy = replace(system, environment=replace(system.environment, water_density=1025.0,
                                               gravity=9.81, depth=50.0,
                                               waves=Waves("airy", height=1.0, period=3.0)))
    with pytest.raises(MoorlineError, match="wave period"):
        solve_harmonic(wavy, HarmonicSettings(period=4.0))


def test_example_case_runs_from_the_cli(tmp_path, undescribed):
    path = Path(__file__).resolve().parents[1] / "cases" / "tcheou_t2.yaml"
    if not path.is_file():
        pytest.skip("cases/tcheou_t2.yaml not present")
    system = load_case(path)
    assert isinstance(system.analyses[1], HarmonicSettings)
    assert system.analyses[0] == replace(system.analyses[0]) and \
        isinstance(system.analyses[0], StaticsSettings)
    result = CliRunner().invoke(cli, ["run", str(path), "--out", str(tmp_path), "--quiet",
                                      "--json"])
    assert result.exit_code == 0, result.output
    folder = tmp_path / system.name
    assert (folder / "harmonic.png").stat().st_size > 0
    assert undescribed(folder / "results.nc") == []
    with xr.open_dataset(folder / "results.nc", group="harmonic") as ds:
        assert ds.attrs["status"] == "converged" and ds.attrs["success"] == 1
        assert ds["coefficients"].dims == ("term", "node", "xyz")
        assert ds.attrs["period"] == 10.0
        top = int(np.argmax(ds["static_position"].values[:, 2]))
        coefficients = ds["coefficients"].values
    # an independent computation of the same model: the time-domain steady state (Newmark,
    # 60 periods, transient gone) against the harmonic series written by the CLI, at the top
    from moorline.model import DynamicsSettings
    from moorline.solvers.dynamics import simulate
    from moorline.solvers.harmonic import _basis

    period = 10.0
    static = solve_statics(system)
    td = simulate(system, DynamicsSettings(duration=60 * period, dt=period / 100,
                                           tolerance=1e-9), initial=static,
                  output_every=period / 50)
    last = (td.time >= 59 * period - 1e-9) & (td.time < 60 * period - 1e-9)
    E = _basis(td.time[last] - 59 * period, 2 * math.pi / period, 5)[0]
    hb = E @ coefficients[:, top, 0]
    x_td = td.positions[last, top, 0]
    amplitude = 0.5 * np.ptp(hb)
    assert amplitude > 0.1  # m: the 300 N force moves the top
    # 5 harmonics against the time domain: 1 % of the dynamic amplitude (tcheou-t2)
    assert np.abs(x_td - hb).max() < 0.015 * amplitude
    again = CliRunner().invoke(cli, ["plot", str(folder / "results.nc"), "--out",
                                     str(tmp_path / "again"), "--quiet"])
    assert again.exit_code == 0, again.output
    assert (tmp_path / "again" / "harmonic.png").stat().st_size > 0


def test_regular_waves_on_a_riser_equal_the_time_domain_steady_state():
    """A riser in a regular Airy wave (drag on the relative velocity, fluid inertia): the
    harmonic-balance series against the last periods of a long time-domain run."""
    from moorline.model import DynamicsSettings, Waves
    from moorline.solvers.dynamics import simulate
    from moorline.solvers.harmonic import _basis
    from moorline.verification import stochastic_riser

    system = stochastic_riser.riser_system()
    system = replace(system, environment=replace(system.environment,
                                                 waves=Waves("airy", height=3.0, period=8.0)))
    static = solve_statics(system)
    result = solve_harmonic(system, HarmonicSettings(period=8.0, harmonics=7), static)
    td = simulate(system, DynamicsSettings(duration=30 * 8.0, dt=0.04, tolerance=1e-10),
                  initial=static, output_every=0.08)
    last = (td.time >= 29 * 8.0 - 1e-9) & (td.time < 30 * 8.0 - 1e-9)
    E = _basis(td.time[last] - 29 * 8.0, result.omega, 7)[0]
    series = np.einsum("tk,knc->tnc", E, result.coefficients)
    amplitude = np.abs(result.positions - result.coefficients[0][None]).max()
    assert amplitude > 0.05  # m: the wave moves the riser
    assert np.abs(td.positions[last] - series).max() < 0.01 * amplitude


def test_sparse_jacobian_equals_finite_differences_of_the_residual():
    """The block-sparse Jacobian of the harmonic-balance residual against its central finite
    differences, at a state with every harmonic present: the Tcheou line in still water (4
    elements: tension, drag, added mass, weight; 3 harmonics)."""
    from moorline.solvers.harmonic import HarmonicBalance
    from moorline.verification import tcheou_t1, tcheou_t2

    system = tcheou_t2.forced_system(7000.0, 4, 10.0)
    static = solve_statics(system, tcheou_t1.SETTINGS)
    balance = HarmonicBalance(system, HarmonicSettings(period=10.0, harmonics=3), static)
    u = balance.initial() + np.random.default_rng(1).normal(0.0, 0.5, balance.n_unknowns)
    _, J, _ = balance.evaluate(u, True)
    assert J.shape == (balance.n_unknowns, balance.n_unknowns)
    h = 1e-4  # m
    fd = np.empty(J.shape)
    for i in range(len(u)):
        e = np.zeros_like(u)
        e[i] = h
        fd[:, i] = (balance.evaluate(u + e, False)[0] - balance.evaluate(u - e, False)[0]) / (2 * h)
    dense = J.toarray()
    assert np.abs(dense - fd).max() < 1e-7 * np.abs(fd).max()
