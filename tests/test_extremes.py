"""Extremes: the Rayleigh most probable maximum of a simulated Gaussian process against its
sampled maxima over many seeds, the Gumbel fit recovering known parameters, peaks and the
Weibull MPM against closed forms, and the extremes analysis on records."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml
from click.testing import CliRunner
from gaussian_process import grid, realize
from scipy.stats import gumbel_r

from moorline.cli import cli
from moorline.extremes import gumbel_fit, gumbel_mpm, peaks, rayleigh_mpm, weibull_fit, weibull_mpm
from moorline.extremes_analysis import solve_extremes
from moorline.model import ExtremesSettings
from moorline.spectral import spectral_moments, upcrossing_rate
from moorline.tension_records import TensionRecords


def _bump(w: np.ndarray) -> np.ndarray:
    """Unit-variance Gaussian-bump spectrum at 1 rad/s, std 0.25 rad/s (a moderately narrow
    sea-like band, spectral width delta = sqrt(1 - m1^2 / (m0 m2)) ~ 0.24)."""
    return np.exp(-0.5 * ((w - 1.0) / 0.25) ** 2) / (math.sqrt(2 * math.pi) * 0.25)


def test_rayleigh_mpm_against_sampled_maxima() -> None:
    """Rayleigh MPM sqrt(2 m0 ln(nu_0 T)) over 3 h against the maxima of 300 independent
    3-h realizations of the process (sampled every 0.2 s, ~30 samples per period).

    Under the model (Poisson up-crossings of high levels, Rice's rate nu_0 e^(-x^2/2m0)) the
    maximum is distributed as exp(-nu_0 T e^(-x^2/2m0)) ~ Gumbel with mode the MPM and scale
    sqrt(m0 / (2 ln(nu_0 T))), so:

    - the fraction of maxima below the MPM is e^-1 = 0.368, within 4 binomial standard
      errors sqrt(p (1 - p) / 300) = 0.028;
    - the Gumbel location fitted to the 300 maxima (maximum likelihood) is the MPM within 4
      of its asymptotic standard errors sqrt(1.1087 / n) scale (Gumbel MLE) ~ 0.017 sigma;
      the model's own finite-n term (its mode sits ~m0 / (2 MPM ln(nu_0 T)) ~ 0.017 sigma
      above sqrt(2 m0 ln n)) is inside that.
    """
    duration, n = 10800.0, 300
    maxima = np.concatenate([realize(_bump, duration, 0.2, 50, seed=100 + b)[1].max(axis=1)
                             for b in range(n // 50)])
    moments = spectral_moments(*grid(_bump), orders=(0, 2))
    mpm = float(rayleigh_mpm(0.0, moments[0], moments[1], duration))
    p = math.exp(-1.0)
    assert abs((maxima < mpm).mean() - p) < 4.0 * math.sqrt(p * (1 - p) / n)
    loc, scale = gumbel_fit(maxima)
    assert abs(loc - mpm) < 4.0 * math.sqrt(1.1087 / n) * scale
    # the model's Gumbel scale sqrt(m0 / (2 ln n)), within 4 standard errors of the fit
    expected_scale = math.sqrt(moments[0] / (2 * math.log(upcrossing_rate(*moments)
                                                          * duration)))
    assert abs(scale - expected_scale) < 4.0 * math.sqrt(0.6079 / n) * scale


def test_gumbel_fit_recovers_parameters() -> None:
    """2000 samples of Gumbel(loc 10, scale 2): the MLE within 4 asymptotic standard errors,
    Var(loc) = 1.1087 scale^2 / n and Var(scale) = 0.6079 scale^2 / n (the inverse Fisher
    information of the Gumbel distribution: 1 + 6 (1 - gamma_E)^2 / pi^2 and 6 / pi^2)."""
    n, loc, scale = 2000, 10.0, 2.0
    sample = gumbel_r.rvs(loc=loc, scale=scale, size=n, random_state=np.random.default_rng(5))
    fit_loc, fit_scale = gumbel_fit(sample)
    assert abs(fit_loc - loc) < 4 * scale * math.sqrt(1.1087 / n)
    assert abs(fit_scale - scale) < 4 * scale * math.sqrt(0.6079 / n)
    # the largest of k blocks: Gumbel(loc + scale ln k, scale)
    assert gumbel_mpm(loc, scale, 20.0) == pytest.approx(loc + scale * math.log(20.0))


def test_weibull_mpm_is_rayleigh_for_shape_two() -> None:
    """Rayleigh peaks are Weibull of shape 2 and scale sqrt(2 m0): the characteristic
    largest of n is sqrt(2 m0 ln n), the Rayleigh MPM."""
    m0, n = 4.0, 1000.0
    assert weibull_mpm(0.0, 2.0, math.sqrt(2 * m0), n) == pytest.approx(
        math.sqrt(2 * m0 * math.log(n)), rel=1e-12)


def test_weibull_fit_of_rayleigh_peaks() -> None:
    """Peaks (one per mean up-crossing cycle) of a narrow-band Gaussian process are Rayleigh:
    the Weibull fit of 20000 s of a bump of std 0.02 rad/s gives shape 2 within 10 % (the
    peaks of the ~3000 cycles are correlated over ~8 cycles: ~400 independent ones, a
    shape standard error ~ 0.78 * 2 / sqrt(400) ~ 4 %)."""
    spectrum = lambda w: np.exp(-0.5 * ((w - 1.0) / 0.02) ** 2) / (  # noqa: E731
        math.sqrt(2 * math.pi) * 0.02)
    _, x = realize(spectrum, 2.0e4, 0.1, 1, seed=3)
    found = peaks(x[0], 0.0)
    assert abs(len(found) - 2.0e4 / (2 * math.pi)) < 0.05 * 2.0e4 / (2 * math.pi)
    shape, scale = weibull_fit(found)
    assert shape == pytest.approx(2.0, rel=0.10)
    assert scale == pytest.approx(math.sqrt(2.0), rel=0.10)


def test_peaks_between_upcrossings() -> None:
    """One peak per complete up-crossing cycle, the incomplete ends dropped."""
    x = np.array([0.5, -1.0, 2.0, 1.0, 3.0, -1.0, 1.5, -2.0, 4.0, 0.0])
    assert peaks(x, 0.0).tolist() == [3.0, 1.5]


def _records(**kw) -> TensionRecords:
    base = dict(source="dynamics", line_names=("l1",), line_types=("chain",),
                element_line=np.array([0]), end_mean=np.zeros((1, 2)),
                element_mean=np.zeros(1))
    base.update(kw)
    return TensionRecords(**base)


def test_extremes_analysis_stochastic_records() -> None:
    """Frequency domain: MPM = mean + sqrt(2 m0 ln(nu_0 T)), percentile 90 = mean + 1.2816
    sigma, for a single-frequency spectrum (nu_0 = w / 2 pi)."""
    w, d_omega, sigma, mean = 0.6, 0.01, 3.0e4, 1.0e6
    spectrum = np.full((1, 1, 2), sigma**2 / d_omega)
    records = _records(source="stochastic", omega=np.array([w]), d_omega=d_omega,
                       end_spectrum=spectrum, element_spectrum=spectrum[:, 0, :1],
                       end_mean=np.full((1, 2), mean), element_mean=np.full(1, mean))
    result = solve_extremes(records, ExtremesSettings(duration=10800.0, percentiles=(90.0,)))
    n = w / (2 * math.pi) * 10800.0
    assert result.mpm == pytest.approx(np.full((1, 2), mean + sigma * math.sqrt(2 * math.log(
        n))), rel=1e-12)
    assert result.percentile[0] == pytest.approx(np.full((1, 2), mean + 1.2815516 * sigma),
                                                 rel=1e-7)
    ds = result.to_xarray()
    assert all(ds[v].attrs["units"] and ds[v].attrs["long_name"]
               for v in [*ds.data_vars, *ds.coords])


def test_extremes_analysis_gumbel_over_seeds() -> None:
    """Time domain, gumbel: the maxima of the realizations are fitted; the MPM over k record
    lengths is loc + scale ln k (k = duration / record length)."""
    rng = np.random.default_rng(8)
    n_real, n_t = 12, 400
    t = np.arange(n_t) * 0.5
    end = 1e6 + 1e5 * rng.standard_normal((n_real, n_t, 1, 2))
    records = _records(time=t, end=end, element=end[:, :, 0, :1], seeds=tuple(range(n_real)))
    settings = ExtremesSettings(duration=10 * t[-1], method="gumbel")
    result = solve_extremes(records, settings)
    loc, scale = gumbel_fit(end[:, :, 0, 0].max(axis=1))
    assert result.mpm[0, 0] == pytest.approx(loc + scale * math.log(10.0), rel=1e-9)
    assert result.maximum[0, 0] == end[:, :, 0, 0].max()
    assert result.realizations == n_real


ROOT = Path(__file__).resolve().parents[1]
OC3_LINE = ROOT / "cases" / "oc3_line.yaml"


@pytest.mark.skipif(not OC3_LINE.is_file(), reason="cases/oc3_line.yaml missing")
def test_run_extremes_over_seeds(tmp_path: Path) -> None:
    """``seeds`` runs the preceding dynamics again with each wave seed: three realizations
    of a random sea (seeds 1, 2, 3), Gumbel fit of their three maxima; the realizations
    differ (the sea changes with the seed)."""
    case = yaml.safe_load(OC3_LINE.read_text())
    case["lines"]["line1"]["segments"] = 8
    case["environment"]["waves"] = {"kind": "random", "spectrum": "jonswap", "height": 6,
                                    "period": 10, "seed": 1, "record_length": 200}
    case["analyses"] = [{"kind": "statics"},
                        {"kind": "dynamics", "duration": 8.0, "dt": 0.1, "ramp_time": 2.0},
                        {"kind": "extremes", "method": "gumbel", "seeds": [2, 3, 1],
                         "duration": "1 h"}]
    case["output"] = {"every": 0.25}
    path = tmp_path / "seeds.yaml"
    path.write_text(yaml.safe_dump(case))
    out = tmp_path / "out"
    result = CliRunner().invoke(cli, ["run", str(path), "--out", str(out), "--json",
                                      "--no-plots"])
    assert result.exit_code == 0, result.output
    extremes = json.loads(result.stdout)["analyses"][2]
    assert extremes["realizations"] == 3
    group = xr.open_dataset(out / "oc3-line" / "results.nc", group="extremes")
    assert group.attrs["seeds"] == "1,2,3"
    assert np.isfinite(group["fit_scale"].values).all() and (group["fit_scale"] > 0).all()
