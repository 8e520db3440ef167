"""Fatigue: rainflow counting against ASTM E1049-85, the T-N curves against the standards'
constants, narrow-band and Dirlik damage against the rainflow count of simulated Gaussian
processes, and the fatigue analysis's damage and life against closed forms."""

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
from scipy.special import gamma, hyp2f1

from moorline.cli import cli
from moorline.fatigue import miner_damage, rainflow, reversals, spectral_damage
from moorline.fatigue_analysis import YEAR, solve_fatigue
from moorline.model import FatigueSettings
from moorline.spectral import spectral_moments
from moorline.tension_records import TensionRecords
from moorline.tn_curves import chain_area, curve, curves

# ASTM E1049-85 (reapproved 2011), sec. 5.4.4 (rainflow counting), the load history of its
# worked example (points A to I, in load units).
ASTM_HISTORY = [-2.0, 1.0, -3.0, 5.0, -1.0, 3.0, -4.0, 4.0, -2.0]


def _counts(ranges: np.ndarray, counts: np.ndarray) -> dict[float, float]:
    out: dict[float, float] = {}
    for r, c in zip(ranges, counts, strict=True):
        out[float(r)] = out.get(float(r), 0.0) + float(c)
    return out


def test_rainflow_astm_e1049_example() -> None:
    """The counts the standard prints for its rainflow example: range 3: 0.5 (A-B), 4: 1.5
    (B-C half, E-F full), 6: 0.5 (H-I), 8: 1.0 (C-D, G-H halves), 9: 0.5 (D-G), none of
    1, 2, 5, 7, 10 (ASTM E1049-85 sec. 5.4.4, the cycle counts of its rainflow example)."""
    ranges, means, counts = rainflow(ASTM_HISTORY)
    assert _counts(ranges, counts) == {3.0: 0.5, 4.0: 1.5, 6.0: 0.5, 8.0: 1.0, 9.0: 0.5}
    # the full cycle E-F (-1 to 3) has mean 1
    assert means[(ranges == 4.0) & (counts == 1.0)].tolist() == [1.0]


def test_rainflow_repeating_history() -> None:
    """The same history repeated (ASTM E1049-85 sec. 5.4.5, simplified rainflow counting
    for repeating histories, started at the highest peak D: D E F G H I/A B C D): one full
    cycle each of 9 (D-G), 7 (H-C), 4 (E-F) and 3 (I-B), counted by hand with its rules
    (the standard's table for this case not at hand)."""
    ranges, _, counts = rainflow(ASTM_HISTORY, residue="repeat")
    assert _counts(ranges, counts) == {3.0: 1.0, 4.0: 1.0, 7.0: 1.0, 9.0: 1.0}


def test_reversals_exact_and_plateaus() -> None:
    """Turning points are the signal's own values (no load classes), plateaus merged."""
    x = [0.0, 0.3, 0.3, 1.7, 1.2, 1.2, 1.2, 2.5, -0.4, -0.4]
    assert reversals(x).tolist() == [0.0, 1.7, 1.2, 2.5, -0.4]


# The constants as printed in the standards (N = K x^-m): API RP 2SK 3rd ed. (2005) sec. 7,
# T-N curves in tension range over reference breaking strength; DNV-OS-E301 (2010) Ch.2
# Sec.2 E, S-N curves in MPa on the nominal area. (m, K, log10 K = a + b Lm)
PRINTED = {
    "api_studlink_chain": (3.0, 1000.0, None),
    "api_studless_chain": (3.0, 316.0, None),
    "api_connecting_link": (3.0, 178.0, None),
    "api_six_strand_wire": (4.09, None, (3.20, -2.79)),
    "api_spiral_strand_wire": (5.05, None, (3.25, -3.43)),
    "api_polyester": (5.2, 25000.0, None),
    "dnv_studlink_chain": (3.0, 1.2e11, None),
    "dnv_studless_chain": (3.0, 6.0e10, None),
    "dnv_six_strand_wire": (4.0, 3.4e14, None),
    "dnv_spiral_strand_wire": (4.8, 1.7e17, None),
}


@pytest.mark.parametrize("name", sorted(PRINTED))
def test_tn_constants_as_printed(name: str) -> None:
    """Every curve of the data file carries the standard's constants and a citation."""
    m, K, log10_K = PRINTED[name]
    tn = curve(name)
    assert (tn.m, tn.K, tn.log10_K) == (m, K, log10_K)
    assert ("API" in tn.source) == name.startswith("api") and tn.source
    assert set(curves()) == set(PRINTED)


def test_tn_cycles_closed_form() -> None:
    """N = K x^-m: API studless chain at R = 0.1: 316 / 0.1^3 = 316000 cycles; six-strand
    rope at R = 0.1, Lm = 0.2: 10^(3.20 - 2.79 * 0.2) / 0.1^4.09; DNV studless chain at
    100 MPa: 6e10 / 100^3 = 6e4 cycles."""
    assert curve("api_studless_chain").cycles(0.1) == pytest.approx(316000.0, rel=1e-12)
    six = curve("api_six_strand_wire").cycles(0.1, mean_ratio=0.2)
    assert six == pytest.approx(10 ** (3.20 - 2.79 * 0.2) / 0.1**4.09, rel=1e-12)
    assert curve("dnv_studless_chain").cycles(100.0) == pytest.approx(6.0e4, rel=1e-12)


def test_tn_scale_si_and_us() -> None:
    """Scale of a DNV chain curve: nominal area 2 pi d^2 / 4 times 1 MPa, in N (SI) and in
    lbf for a diameter in ft (US: 1 lbf = 4.4482216152605 N, 1 ft = 0.3048 m)."""
    tn = curve("dnv_studless_chain")
    d = 0.1
    assert chain_area(d) == pytest.approx(2 * math.pi * d**2 / 4)
    assert tn.scale(diameter=d) == pytest.approx(chain_area(d) * 1e6, rel=1e-12)
    us = tn.scale(diameter=d / 0.3048, units="US")
    assert us == pytest.approx(chain_area(d) * 1e6 / 4.4482216152605, rel=1e-9)
    assert curve("api_studless_chain").scale(MBL=3.2e6) == 3.2e6
    with pytest.raises(ValueError, match="MBL"):
        curve("api_studless_chain").scale()


def _gaussian_bump(center: float, width: float):
    """Unit-variance one-sided Gaussian-bump spectrum (per rad/s)."""
    return lambda w: np.exp(-0.5 * ((w - center) / width) ** 2) / (math.sqrt(2 * math.pi)
                                                                   * width)


def _rainflow_damage(x: np.ndarray, m: float) -> np.ndarray:
    return np.array([miner_damage(r, c, m, 1.0) for r, _, c in map(rainflow, x)])


def test_narrow_band_damage_against_rainflow() -> None:
    """Narrow-band damage (Rayleigh ranges, nu_0 T cycles) of a narrow-band Gaussian
    process (Gaussian bump at 1 rad/s, std 0.02 rad/s, m = 3) against the rainflow damage of
    8 realizations of 1e5 s.

    Scatter, derived: the damage is sum_i S_i^m over ~nu_0 T cycles with S = 2A, A the
    envelope. For a Gaussian bump the envelope's normalized correlation is
    kappa(tau) = exp(-s^2 tau^2 / 2) and E[A(0)^m A(tau)^m] = (2 m0)^m Gamma(1 + m/2)^2
    2F1(-m/2, -m/2; 1; kappa^2) (bivariate Rayleigh moments), so
    Var D = nu_0 T nu_0 int 4^m Cov(A(0)^m, A(tau)^m) d tau (the double sum over cycles as
    an integral: the correlation time 1/s = 50 s spans ~8 periods). The mean of the 8
    rainflow damages must be within 4 of its standard deviations of the narrow-band value.
    """
    m, s, duration, seeds = 3.0, 0.02, 1.0e5, 8
    spectrum = _gaussian_bump(1.0, s)
    _, x = realize(spectrum, duration, 0.1, seeds, seed=11)
    moments = spectral_moments(*grid(spectrum))
    predicted = float(spectral_damage(moments, m, 1.0, duration, "narrow_band"))
    m0, nu0 = float(moments[0]), math.sqrt(moments[2] / moments[0]) / (2 * math.pi)
    tau = np.linspace(-12.0 / s, 12.0 / s, 24001)
    kappa2 = np.exp(-(s * tau) ** 2)
    cov = 4.0**m * (2 * m0) ** m * gamma(1 + m / 2) ** 2 * (hyp2f1(-m / 2, -m / 2, 1, kappa2)
                                                            - 1.0)
    sd_one = math.sqrt(nu0 * duration * nu0 * np.trapezoid(cov, tau))
    measured = _rainflow_damage(x, m)
    assert abs(measured.mean() - predicted) < 4.0 * sd_one / math.sqrt(seeds)
    # the derived scatter matches the observed one (within the chi-square spread of 8)
    assert 0.4 < measured.std(ddof=1) / sd_one < 1.7


def test_dirlik_against_rainflow_broadband() -> None:
    """Dirlik damage of a broadband bimodal process (bumps at 0.5 and 3 rad/s, irregularity
    factor 0.51, m = 3) against the mean rainflow damage of 8 realizations of 2e4 s.

    Dirlik's range density is an empirical fit to simulated rainflow counts (Dirlik 1985),
    not exact. In our simulations at m = 3 it is 5-6 % low on flat-band processes and 9-11 %
    low on this one (checked with an independent ASTM three-point count; its formula as in
    FLife's ``Dirlik``). The tolerance is 15 % for the model plus 3 standard errors of the
    rainflow mean (from the 8 realizations). The narrow-band formula, ~40 % high on this
    process, must fail the same tolerance (the test separates the two methods)."""
    m, duration, seeds = 3.0, 2.0e4, 8

    def spectrum(w: np.ndarray) -> np.ndarray:
        return _gaussian_bump(0.5, 0.05)(w) + 0.3 * _gaussian_bump(3.0, 0.3)(w)

    _, x = realize(spectrum, duration, 0.05, seeds, seed=12)
    moments = spectral_moments(*grid(spectrum))
    measured = _rainflow_damage(x, m)
    mean, se = measured.mean(), measured.std(ddof=1) / math.sqrt(seeds)
    tolerance = 0.15 * mean + 3.0 * se
    dirlik = float(spectral_damage(moments, m, 1.0, duration, "dirlik"))
    narrow = float(spectral_damage(moments, m, 1.0, duration, "narrow_band"))
    assert abs(dirlik - mean) < tolerance
    assert abs(narrow - mean) > tolerance


def _records(**kw) -> TensionRecords:
    base = dict(source="dynamics", line_names=("l1",), line_types=("chain",),
                element_line=np.array([0, 0]), end_mean=np.zeros((1, 2)),
                element_mean=np.zeros(2))
    base.update(kw)
    return TensionRecords(**base)


def test_fatigue_analysis_constant_amplitude() -> None:
    """A tension T0 + A sin(w t) at both ends and in both elements, 50 whole periods: 50
    cycles of range 2A (plus the half cycles of the start and end), damage
    50 (2A/MBL)^3 / 316 on the API studless curve, life = duration / damage."""
    T0, A, MBL, period, n = 1.0e6, 2.0e5, 5.0e6, 10.0, 50
    t = np.linspace(0.0, n * period, n * 40 + 1)
    x = T0 + A * np.sin(2 * np.pi * t / period)
    end = np.broadcast_to(x[None, :, None, None], (1, len(t), 1, 2)).copy()
    element = np.broadcast_to(x[None, :, None], (1, len(t), 2)).copy()
    records = _records(time=t, end=end, element=element, end_mean=np.full((1, 2), T0),
                       element_mean=np.full(2, T0))
    settings = FatigueSettings(curves={"chain": {"curve": "api_studless_chain", "MBL": MBL}})
    result = solve_fatigue(records, settings)
    # rainflow of sin over 50 periods from its mean: 49 full cycles of 2A and the residue
    # T0 -> T0+A -> T0-A ... -> T0: two quarter ranges A (half cycles) and one half cycle 2A
    expected = (49.5 * (2 * A / MBL) ** 3 + 2 * 0.5 * (A / MBL) ** 3) / 316.0
    assert result.damage[0] == pytest.approx(np.full((1, 2), expected), rel=1e-9)
    assert result.element_damage[0] == pytest.approx(np.full(2, expected), rel=1e-9)
    assert result.life[0, 0, 0] == pytest.approx(n * period / expected / YEAR, rel=1e-9)
    ds = result.to_xarray()
    assert all(ds[v].attrs["units"] and ds[v].attrs["long_name"]
               for v in [*ds.data_vars, *ds.coords])


def test_fatigue_analysis_spectral_single_frequency() -> None:
    """A tension spectrum with one component (variance sigma^2 at w): narrow-band damage
    over the record 2 pi / d_omega is nu_0 T (2 sqrt(2) sigma / MBL)^3 Gamma(2.5) / K with
    nu_0 = w / 2 pi; Dirlik reduces to it for a single frequency (gamma = 1)."""
    w, d_omega, sigma, MBL = 0.8, 0.01, 1.0e5, 4.0e6
    omega = np.array([w])
    spectrum = np.full((1, 1, 2), sigma**2 / d_omega)
    records = _records(source="stochastic", omega=omega, d_omega=d_omega,
                       end_spectrum=spectrum, element_spectrum=spectrum[:, 0, :],
                       end_mean=np.full((1, 2), 1e6), element_mean=np.full(2, 1e6))
    settings = FatigueSettings(curves={"chain": {"curve": "api_studless_chain", "MBL": MBL}})
    result = solve_fatigue(records, settings)
    duration = 2 * math.pi / d_omega
    expected = (w / (2 * math.pi) * duration * (2 * math.sqrt(2) * sigma / MBL) ** 3
                * gamma(2.5) / 316.0)
    assert result.methods == ("narrow_band", "dirlik")
    assert result.damage[0] == pytest.approx(np.full((1, 2), expected), rel=1e-9)
    assert result.damage[1] == pytest.approx(np.full((1, 2), expected), rel=1e-6)


ROOT = Path(__file__).resolve().parents[1]
OC3_LINE = ROOT / "cases" / "oc3_line.yaml"


def _case(directory: Path, analyses: list[dict]) -> Path:
    """The OC3 line, 10 segments, fairlead surging 5 m / 10 s, with ``analyses``."""
    case = yaml.safe_load(OC3_LINE.read_text())
    case["line_types"]["chain"]["BA"] = -0.8
    case["lines"]["line1"]["segments"] = 10
    case["points"]["fairlead"]["motion"] = {"kind": "harmonic", "amplitude": [5, 0, 0],
                                            "period": 10}
    case["analyses"] = analyses
    case["output"] = {"every": 0.25}
    path = directory / "fatigue_case.yaml"
    path.write_text(yaml.safe_dump(case))
    return path


CURVES = {"chain": {"curve": "api_studless_chain", "MBL": "3.21 MN"}}


@pytest.mark.skipif(not OC3_LINE.is_file(), reason="cases/oc3_line.yaml missing")
def test_run_writes_fatigue_and_extremes(tmp_path: Path) -> None:
    """``moorline run`` with fatigue and extremes after a 25 s dynamics: both groups in
    results.nc, every variable described, damage / life / MPM per line in the summary, and
    the damage at the fairlead is the rainflow damage of the written end-tension history
    after the 5 s skip on T / 3.21 MN (API studless K = 316, m = 3), the extremes' maximum
    that history's largest value (the wiring of skip, end and strength)."""
    path = _case(tmp_path, [{"kind": "statics"},
                            {"kind": "dynamics", "duration": 25.0, "dt": 0.1},
                            {"kind": "fatigue", "curves": CURVES, "skip": "5 s"},
                            {"kind": "extremes", "duration": "3 h", "skip": 5.0}])
    out = tmp_path / "out"
    result = CliRunner().invoke(cli, ["run", str(path), "--out", str(out), "--json",
                                      "--no-plots"])
    assert result.exit_code == 0, result.output
    summary = json.loads(result.stdout)
    fatigue, extremes = summary["analyses"][2], summary["analyses"][3]
    assert fatigue["kind"] == "fatigue" and extremes["kind"] == "extremes"
    results = out / "oc3-line" / "results.nc"
    dynamics = xr.open_dataset(results, group="dynamics")
    group = xr.open_dataset(results, group="fatigue")
    for ds in (group, xr.open_dataset(results, group="extremes")):
        assert all(ds[v].attrs.get("units") and ds[v].attrs.get("long_name")
                   for v in [*ds.data_vars, *ds.coords])
    keep = dynamics["time"].values >= 5.0 - 1e-9
    history = dynamics["end_tension"].values[keep, 0, 1]
    ranges, _, counts = rainflow(history)
    expected = miner_damage(ranges / 3.21e6, counts, 3.0, 316.0)
    assert float(group["damage"].values[0, 0, 1]) == pytest.approx(expected, rel=1e-9)
    life = fatigue["methods"]["rainflow"]["life_years"]["line1"]["end_b"]
    assert life == pytest.approx(20.0 / expected / YEAR, rel=1e-9)
    assert extremes["maximum"]["line1"]["end_b"] == pytest.approx(history.max(), rel=1e-12)
    assert extremes["mpm"]["line1"]["end_b"] > extremes["mean"]["line1"]["end_b"]


@pytest.mark.skipif(not OC3_LINE.is_file(), reason="cases/oc3_line.yaml missing")
def test_fatigue_without_dynamics_fails(tmp_path: Path) -> None:
    """A fatigue analysis with no dynamics or stochastic analysis before it fails with a
    message (exit code 1); an unknown curve is a case error naming the key."""
    path = _case(tmp_path, [{"kind": "statics"}, {"kind": "fatigue", "curves": CURVES}])
    result = CliRunner().invoke(cli, ["run", str(path), "--out", str(tmp_path / "o"),
                                      "--no-plots", "-q"])
    assert result.exit_code == 1
    assert "dynamics or stochastic analysis listed before it" in result.output
    bad = _case(tmp_path, [{"kind": "statics"}, {"kind": "dynamics", "duration": 1.0,
                                                  "dt": 0.1},
                           {"kind": "fatigue", "curves": {"chain": {"curve": "nope"}}}])
    result = CliRunner().invoke(cli, ["run", str(bad), "--out", str(tmp_path / "o"), "-q"])
    assert result.exit_code != 0
    assert "analyses[2].curves.chain.curve" in result.output and "unknown T-N curve" in \
        result.output


def test_curve_strength_from_line_type() -> None:
    """Without an MBL in the curve entry, the line type's own MBL is the reference strength
    (and its absence is an error naming the line type)."""
    from types import SimpleNamespace

    from moorline.errors import MoorlineError
    from moorline.fatigue_analysis import line_type_curves

    choice = {"chain": {"curve": "api_studless_chain"}}
    found = line_type_curves(choice, {"chain"}, "SI", {"chain": SimpleNamespace(MBL=7.0e6)})
    assert found["chain"][1] == 7.0e6
    with pytest.raises(MoorlineError, match="curves.chain"):
        line_type_curves(choice, {"chain"}, "SI", {"chain": SimpleNamespace()})


def _astm_three_point(x: np.ndarray) -> list[tuple[float, float]]:
    """ASTM E1049-85 sec. 5.4.4 as written (the three-point rule on a stack of reversals: a
    range Y not larger than the next X is counted, as a half cycle when it holds the
    starting point, which is then discarded; what is left counts as half cycles), written
    here independently of fatpack's four-point algorithm."""
    stack: list[float] = []
    out: list[tuple[float, float]] = []
    for point in reversals(x):
        stack.append(float(point))
        while len(stack) >= 3:
            X, Y = abs(stack[-1] - stack[-2]), abs(stack[-2] - stack[-3])
            if X < Y:
                break
            if len(stack) == 3:
                out.append((Y, 0.5))
                stack.pop(0)
            else:
                out.append((Y, 1.0))
                del stack[-3:-1]
    out += [(abs(b - a), 0.5) for a, b in zip(stack[:-1], stack[1:], strict=True)]
    return out


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_rainflow_equals_astm_three_point(seed: int) -> None:
    """Four-point counting with the residue as half cycles gives the same cycles as the
    standard's three-point procedure (McInnes & Meehan 2008, Int. J. Fatigue 30: 547), on
    random histories of 2000 points."""
    x = np.random.default_rng(seed).standard_normal(2000).cumsum()
    ranges, _, counts = rainflow(x)
    ours = sorted(zip(np.round(ranges, 12), counts, strict=True))
    theirs = sorted((round(r, 12), c) for r, c in _astm_three_point(x))
    assert ours == theirs


@pytest.mark.skipif(not OC3_LINE.is_file(), reason="cases/oc3_line.yaml missing")
def test_fatigue_over_seeds_is_the_mean_and_shares_runs(tmp_path: Path,
                                                        monkeypatch: pytest.MonkeyPatch) -> None:
    """Fatigue with ``seeds: [2]`` after a random-sea dynamics (seed 1) is the mean of the
    rainflow damages of the seed-1 history and of the history of a separate run of the same
    case with seed 2; an extremes analysis listing the same seed reuses that realization
    (one extra simulation, not two)."""
    import moorline.solvers.dynamics as dynamics_module

    waves = {"kind": "random", "spectrum": "jonswap", "height": 6, "period": 10,
             "gamma": 3.3, "seed": 1, "record_length": 100}
    analyses = [{"kind": "statics"}, {"kind": "dynamics", "duration": 20.0, "dt": 0.1}]
    path = _case(tmp_path, [*analyses,
                            {"kind": "fatigue", "curves": CURVES, "skip": 5.0, "seeds": [2]},
                            {"kind": "extremes", "skip": 5.0, "seeds": [2]}])
    case = yaml.safe_load(path.read_text())
    case["points"]["fairlead"].pop("motion")
    case["environment"]["waves"] = waves
    path.write_text(yaml.safe_dump(case))
    single = tmp_path / "seed2.yaml"
    case["environment"]["waves"] = {**waves, "seed": 2}
    case["analyses"] = analyses
    single.write_text(yaml.safe_dump(case))

    seeds_run: list[int] = []
    simulate = dynamics_module.simulate

    def counting(system, *args, **kwargs):
        seeds_run.append(int(system.environment.waves.seed))
        return simulate(system, *args, **kwargs)

    monkeypatch.setattr(dynamics_module, "simulate", counting)
    out = tmp_path / "out"
    result = CliRunner().invoke(cli, ["run", str(path), "--out", str(out), "-q",
                                      "--no-plots"])
    assert result.exit_code == 0, result.output
    assert seeds_run.count(2) == 1
    monkeypatch.setattr(dynamics_module, "simulate", simulate)
    other = tmp_path / "other"
    result = CliRunner().invoke(cli, ["run", str(single), "--out", str(other), "-q",
                                      "--no-plots"])
    assert result.exit_code == 0, result.output

    def damage_of(results: Path) -> float:
        dyn = xr.open_dataset(results, group="dynamics")
        keep = dyn["time"].values >= 5.0 - 1e-9
        ranges, _, counts = rainflow(dyn["end_tension"].values[keep, 0, 1])
        return miner_damage(ranges / 3.21e6, counts, 3.0, 316.0)

    expected = 0.5 * (damage_of(out / "oc3-line" / "results.nc")
                      + damage_of(other / "oc3-line" / "results.nc"))
    group = xr.open_dataset(out / "oc3-line" / "results.nc", group="fatigue")
    assert group.attrs["realizations"] == 2 and group.attrs["seeds"] == "1,2"
    assert float(group["damage"].values[0, 0, 1]) == pytest.approx(expected, rel=1e-9)
