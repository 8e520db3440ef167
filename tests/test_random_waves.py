"""Wave spectra and random sea realizations (Tuah 1982 sec. 5.1: DSA and NSA by FFT)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import quad

from moorline.io import load_case
from moorline.io.case_writer import write_case
from moorline.model import Current, Waves
from moorline.waves import (
    RandomSea,
    WaveComponents,
    WaveSpectrum,
    fluid_field_from_environment,
    jonswap,
    pierson_moskowitz,
)

G_FT = 32.174
DEPTH = 200.0
CARLA = WaveSpectrum.from_moment("pierson-moskowitz", 28.0, 0.5)  # Tuah's Example 5 sea


def _area(f, lo: float = 0.0) -> float:
    return quad(lambda w: float(f(np.array([w]))[0]), lo, np.inf, limit=400,
                epsrel=1e-11)[0]


def test_pierson_moskowitz_moments_and_peak():
    m0, wp = 28.0, 0.5
    assert _area(lambda w: pierson_moskowitz(w, m0, wp)) == pytest.approx(m0, rel=1e-9)
    w = np.linspace(0.2, 2.0, 20001)
    assert w[np.argmax(pierson_moskowitz(w, m0, wp))] == pytest.approx(wp, abs=1e-4)
    # the textbook form 5/16 Hs^2 wp^4 w^-5 exp(-5/4 (wp/w)^4) with Hs = 4 sqrt(m0)
    hs = 4 * math.sqrt(m0)
    textbook = 5 / 16 * hs**2 * wp**4 * w**-5 * np.exp(-1.25 * (wp / w) ** 4)
    assert np.allclose(pierson_moskowitz(w, m0, wp), textbook, rtol=1e-12)
    assert CARLA.hs == pytest.approx(hs) and CARLA.omega_p == pytest.approx(wp)


@pytest.mark.parametrize("gamma", [1.0, 2.0, 3.3, 7.0])
def test_jonswap_normalized_and_close_to_dnv(gamma):
    hs, tp = 6.0, 10.0
    assert _area(lambda w: jonswap(w, hs, tp, gamma)) == pytest.approx(hs**2 / 16, rel=1e-8)
    wp = 2 * math.pi / tp
    w = np.linspace(0.1, 3.0, 3001)
    # DNV-RP-C205 3.5.5: A_gamma = 1 - 0.287 ln(gamma) times the PM shape and the peak factor
    dnv = (1 - 0.287 * math.log(gamma)) * pierson_moskowitz(w, hs**2 / 16, wp) * gamma ** np.exp(
        -((w - wp) ** 2) / (2 * np.where(w <= wp, 0.07, 0.09) ** 2 * wp**2))
    assert np.allclose(jonswap(w, hs, tp, gamma), dnv, rtol=0.02)
    if gamma == 1.0:
        assert np.allclose(jonswap(w, hs, tp, 1.0), pierson_moskowitz(w, hs**2 / 16, wp))


def test_dsa_realization_variance_is_the_spectrum_area():
    """Tuah's Example 5 sea: 200 frequencies at 0.0245 rad/s, 256 s at 0.25 s (1024 points).
    The DSA record's variance is exactly the discrete spectrum's area, which is m0 up to the
    truncated tail."""
    sea = RandomSea(CARLA, record_length=256.0, n_frequencies=200)
    assert sea.d_omega == pytest.approx(0.0245, abs=1e-4)
    t, eta = sea.elevation_series(DEPTH, G_FT, 1024)
    assert t[1] == pytest.approx(0.25)
    discrete = float(np.sum(CARLA.density(sea.frequencies()) * sea.d_omega))
    assert eta.var() == pytest.approx(discrete, rel=1e-10)
    tail = _area(CARLA.density, lo=200.5 * sea.d_omega)
    assert discrete == pytest.approx(28.0 - tail, rel=2e-3)
    # the sample spectrum of a DSA record is the spectrum itself at every frequency
    amp = np.abs(np.fft.rfft(eta))[1:201] * 2 / 1024
    assert np.allclose(amp, np.sqrt(2 * CARLA.density(sea.frequencies()) * sea.d_omega))


def test_nsa_amplitudes_are_rayleigh_with_the_same_mean_square():
    sea = RandomSea(CARLA, record_length=256.0, n_frequencies=200, amplitudes="nsa")
    w, _ = sea.complex_amplitudes()
    target = 0.5 * CARLA.density(w) * sea.d_omega  # E |A_m|^2
    on = target > 1e-12 * target.max()
    target = target[on]
    samples = np.array([np.abs(RandomSea(CARLA, 256.0, 200, amplitudes="nsa", seed=s)
                               .complex_amplitudes()[1][on]) ** 2 for s in range(400)])
    ratio = samples / target
    assert ratio.mean() == pytest.approx(1.0, abs=0.02)
    # |A|^2 / E|A|^2 of a Rayleigh amplitude is exponential: variance 1
    assert ratio.var() == pytest.approx(1.0, abs=0.05)
    # a DSA realization has the expected value exactly
    dsa = np.abs(RandomSea(CARLA, 256.0, 200).complex_amplitudes()[1][on]) ** 2
    assert np.allclose(dsa, target)


def test_phases_uniform_and_seeded():
    a = RandomSea(CARLA, 256.0, 200, seed=3).complex_amplitudes()[1]
    b = RandomSea(CARLA, 256.0, 200, seed=3).complex_amplitudes()[1]
    c = RandomSea(CARLA, 256.0, 200, seed=4).complex_amplitudes()[1]
    assert np.array_equal(a, b) and not np.allclose(a, c)
    phases = np.concatenate([np.angle(RandomSea(CARLA, 256.0, 200, seed=s)
                                      .complex_amplitudes()[1][20:]) for s in range(50)])
    counts, _ = np.histogram(phases, bins=8, range=(-math.pi, math.pi))
    assert counts.min() > 0.9 * counts.mean() and counts.max() < 1.1 * counts.mean()


@pytest.mark.parametrize("point", [(0.0, 0.0), (37.0, -12.0)])
def test_fft_record_equals_the_component_sum(point):
    """The inverse FFT of the complex amplitudes (eq. 5.1.4) and the direct sum of the
    components used by the time-domain dynamics give the same sea, at any point."""
    sea = RandomSea(CARLA, 256.0, 200, heading_deg=30.0, seed=7)
    t, eta = sea.elevation_series(DEPTH, G_FT, 1024, point=point)
    waves = sea.components(DEPTH, G_FT)
    # components of zero amplitude (the spectrum underflows far below its peak) are dropped
    assert isinstance(waves, WaveComponents) and 150 < waves.n_components <= 200
    p = np.array([[point[0], point[1], 0.0]])
    direct = np.array([waves.elevation(p, float(s))[0] for s in t[::37]])
    assert np.allclose(direct, eta[::37], atol=1e-10 * np.abs(eta).max())


def test_default_frequencies_reach_six_peak_frequencies():
    sea = RandomSea(WaveSpectrum("jonswap", 6.0, 10.0), record_length=1800.0)
    w = sea.frequencies()
    assert w[0] == pytest.approx(2 * math.pi / 1800) and w[-1] <= 6 * sea.spectrum.omega_p
    assert w[-1] > 6 * sea.spectrum.omega_p - sea.d_omega
    with pytest.raises(ValueError, match="n_points"):
        RandomSea(CARLA, 256.0, 200).elevation_series(DEPTH, G_FT, 400)


def test_random_waves_from_a_case_file(tmp_path):
    from dataclasses import replace

    from moorline.verification.tuah_ex6 import ex6_system

    system = ex6_system(gravity=G_FT)
    waves = Waves(kind="random", height=4 * math.sqrt(28.0), period=4 * math.pi,
                  spectrum="pierson-moskowitz", amplitudes="nsa", seed=5, record_length=256.0,
                  n_frequencies=200)
    system = replace(system, environment=replace(system.environment, waves=waves,
                                                 depth=DEPTH, current=Current()))
    path = write_case(system, tmp_path / "random.yaml")
    loaded = load_case(path)
    assert loaded.environment.waves == waves
    field = fluid_field_from_environment(loaded.environment)
    expected = RandomSea(CARLA, 256.0, 200, amplitudes="nsa", seed=5).components(DEPTH, G_FT)
    p = np.array([[3.0, 1.0, -5.0]])
    for t in (0.0, 11.3):
        got, want = field.kinematics(p, t), expected.kinematics(p, t)
        for a, b in zip(got, want, strict=True):
            assert np.allclose(a, b)


def test_dynamics_in_a_random_sea_from_the_example_case():
    """cases/oc3_random_sea.yaml: the lines feel the random sea (tensions differ from still
    water once the ramp is under way)."""
    from dataclasses import replace
    from pathlib import Path

    from moorline.model import DynamicsSettings
    from moorline.solvers.dynamics import simulate
    from moorline.solvers.statics import solve_statics

    path = Path(__file__).resolve().parents[1] / "cases" / "oc3_random_sea.yaml"
    if not path.is_file():
        pytest.skip("cases/oc3_random_sea.yaml not present")
    system = load_case(path)
    assert system.environment.waves.kind == "random"
    still = replace(system, environment=replace(system.environment, waves=Waves()))
    settings = DynamicsSettings(duration=6.0, dt=0.05, ramp_time=2.0)
    static = solve_statics(system)
    sea = simulate(system, settings, initial=static, output_every=0.5)
    calm = simulate(still, settings, initial=static, output_every=0.5)
    assert sea.success and np.all(np.isfinite(sea.tension))
    assert np.abs(sea.tension[-1] - calm.tension[-1]).max() > 1.0  # N


def test_dynamic_results_carry_the_wave_elevation(tmp_path):
    """The wave elevation at the origin is recorded with the histories (in memory and in the
    streamed NetCDF group) and equals the sea's."""
    from dataclasses import replace

    import xarray as xr
    from click.testing import CliRunner

    from moorline.cli import cli
    from moorline.model import DynamicsSettings

    path = Path(__file__).resolve().parents[1] / "cases" / "oc3_random_sea.yaml"
    if not path.is_file():
        pytest.skip("cases/oc3_random_sea.yaml not present")
    system = load_case(path)
    system = replace(system, analyses=(system.analyses[0],
                                       DynamicsSettings(duration=2.0, dt=0.05)))
    case = write_case(system, tmp_path / "sea.yaml")
    result = CliRunner().invoke(cli, ["run", str(case), "--out", str(tmp_path / "out"),
                                      "--quiet"])
    assert result.exit_code == 0, result.output
    with xr.open_dataset(tmp_path / "out" / system.name / "results.nc",
                         group="dynamics") as ds:
        eta = ds["wave_elevation"].values
        t = ds["time"].values
    sea = fluid_field_from_environment(system.environment)
    expected = [sea.kinematics(np.zeros((1, 3)), float(s))[2][0] for s in t]
    assert np.allclose(eta, expected) and np.abs(eta).max() > 0.1
