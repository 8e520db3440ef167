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


def test_large_motion_stiffens_the_string():
    """At larger amplitude the string's geometric stiffening appears: a third harmonic and a
    first harmonic below the linear one (below resonance the response is smaller)."""
    k = 2 * TENSION / HALF
    w = 0.5 * math.sqrt(k / MASS)
    big = 400.0
    system = string_mass(2 * math.pi / w, force=big)
    result = solve_harmonic(system, HarmonicSettings(period=2 * math.pi / w, harmonics=5))
    node = result.mesh.point_node[result.mesh.point_index("m")]
    linear = big / (k - MASS * w * w)
    b1, b3 = result.coefficients[2, node, 2], result.coefficients[6, node, 2]
    assert 0.0 < b1 < 0.999 * linear
    assert abs(b3) > 1e-3 * abs(b1)


def test_unforced_system_stays_static():
    system = string_mass(1.0, force=0.0)
    static = solve_statics(system)
    result = solve_harmonic(system, HarmonicSettings(period=1.0, harmonics=2), static)
    assert result.iterations == 0
    assert np.allclose(result.positions, static.positions[None], atol=1e-12)


def test_refuses_bodies_viscoelastic_and_bad_settings():
    system = string_mass(1.0)
    with pytest.raises(MoorlineError):
        solve_harmonic(system, HarmonicSettings(period=0.0))
    visco = replace(system, line_types={"s": replace(system.line_types["s"],
                                                     material="viscoelastic", EA1=1e6,
                                                     tau=1.0)})
    with pytest.raises(MoorlineError, match="elastic lines only"):
        solve_harmonic(visco, HarmonicSettings(period=1.0))
    from moorline.verification import tuah_ex5

    disc, static = tuah_ex5.static_state()
    with pytest.raises(MoorlineError, match="bodies"):
        solve_harmonic(disc, HarmonicSettings(period=3.0), static)


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
        amp = np.hypot(ds["coefficients"].values[1, top, 0], ds["coefficients"].values[2, top, 0])
        # the case file is the tcheou-t2 model (checked there against the time domain)
        from moorline.verification import tcheou_t2

        _, static, expected = tcheou_t2.solve(7000.0, 20, 10.0)
        node = tcheou_t2.top_node(static)
        assert amp == pytest.approx(float(expected.amplitude(1)[node, 0]), rel=1e-6)
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
