"""MoorDyn wave inputs (WaveKin 2, 3, 7) as a sea of explicit components, and that sea."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq

from moorline.errors import CaseError
from moorline.io.moordyn import read_moordyn_deck
from moorline.io.moordyn_waves import (
    elevation_components,
    fft_grid_components,
    read_wave_elevation,
    read_wave_frequencies,
    summed_components,
)
from moorline.model import Environment, SeaComponents, Waves
from moorline.waves import fluid_field_from_environment

DATA = Path(__file__).parent / "data" / "moordyn"
OC3 = DATA / "oc3.dat"
PUBLIC = DATA / "public" / "MoorDyn"
G = 9.80665


def _k(omega: float, depth: float) -> float:
    """Wave number of ``omega^2 = g k tanh(k h)`` (root-found here, independently)."""
    return brentq(lambda k: G * k * math.tanh(k * depth) - omega**2, 1e-9, 10.0,
                  xtol=1e-15, rtol=1e-15)


def _sea(components: SeaComponents, depth: float = 50.0, heading: float = 0.0,
         stretching: str = "none"):
    env = Environment(depth=depth, gravity=G, waves=Waves(
        kind="components", components=components, heading_deg=heading, stretching=stretching))
    return fluid_field_from_environment(env)


def _deck(tmp_path: Path, options: str, files: dict[str, str]) -> Path:
    text = OC3.read_text().replace("0.001         threshIC", f"{options}\n0.001 threshIC")
    for name, body in files.items():
        (tmp_path / name).write_text(body)
    path = tmp_path / "deck.dat"
    path.write_text(text)
    return path


# --------------------------------------------------------------------------- the sea itself


def test_components_sea_is_airy_theory() -> None:
    """Two components of different headings in 50 m of water: elevation, velocity and
    acceleration against the linear (Airy) solution written out here (Dean & Dalrymple
    1991, eqs. 4.13-4.15) with k from the dispersion relation root-found here."""
    h = 50.0
    comps = SeaComponents(omegas=(0.5, 0.9), amplitudes=(1.2, 0.4), phases_deg=(30.0, -70.0),
                          headings_deg=(0.0, 60.0))
    field = _sea(comps, depth=h)
    points = np.array([[0.0, 0.0, -3.0], [-120.0, 35.0, -20.0], [310.0, -4.0, -49.0]])
    for t in (0.0, 3.7, 41.2):
        vel, acc, eta = field.kinematics(points, t)
        e = np.zeros(3)
        u = np.zeros((3, 3))
        a = np.zeros((3, 3))
        for w, amp, phi, beta in zip(comps.omegas, comps.amplitudes, comps.phases_deg,
                                     comps.headings_deg, strict=True):
            k, b = _k(w, h), math.radians(beta)
            x, y, z = points.T
            theta = k * (x * math.cos(b) + y * math.sin(b)) - w * t + math.radians(phi)
            ch = np.cosh(k * (z + h)) / math.sinh(k * h)
            sh = np.sinh(k * (z + h)) / math.sinh(k * h)
            e += amp * np.cos(theta)
            uh, dh = amp * w * ch * np.cos(theta), amp * w * w * ch * np.sin(theta)
            u += np.column_stack([uh * math.cos(b), uh * math.sin(b),
                                  amp * w * sh * np.sin(theta)])
            a += np.column_stack([dh * math.cos(b), dh * math.sin(b),
                                  -amp * w * w * sh * np.cos(theta)])
        np.testing.assert_allclose(eta, e, rtol=0, atol=1e-12)
        np.testing.assert_allclose(vel, u, rtol=0, atol=1e-12)
        np.testing.assert_allclose(acc, a, rtol=0, atol=1e-12)


def test_components_without_headings_take_the_sea_heading() -> None:
    comps = SeaComponents(omegas=(0.6,), amplitudes=(1.0,), phases_deg=(0.0,))
    field = _sea(comps, depth=math.inf, heading=90.0)
    vel, _, eta = field.kinematics(np.array([[0.0, 10.0, -5.0]]), 2.0)
    k = 0.36 / G
    assert eta[0] == pytest.approx(math.cos(k * 10.0 - 1.2), abs=1e-12)
    assert vel[0, 0] == pytest.approx(0.0, abs=1e-12)
    assert vel[0, 1] == pytest.approx(0.6 * math.exp(-5 * k) * math.cos(k * 10 - 1.2), abs=1e-12)


# --------------------------------------------------------------------------- the file readers

FREQUENCIES = """0.0 0.0 0.0
0.3 0.5 0.0 0.0
0.5 0.0 -0.8 1.0

0.6 0.3 0.4
"""


def test_wave_frequencies_file_and_the_summed_components(tmp_path: Path) -> None:
    """A hand-written wave_frequencies.txt (omega re im [beta rad]; a blank line skipped):
    WaveKin 7 sums ``|A| sin(omega t - k l + arg A)`` (MoorDyn-C v2.7
    source/Waves/SpectrumKin.cpp), written out here and compared with the read sea."""
    path = tmp_path / "wave_frequencies.txt"
    path.write_text(FREQUENCIES)
    omega, amplitude, beta = read_wave_frequencies(path)
    np.testing.assert_array_equal(omega, [0.0, 0.3, 0.5, 0.6])
    np.testing.assert_array_equal(amplitude, [0, 0.5, -0.8j, 0.3 + 0.4j])
    np.testing.assert_array_equal(beta, [0.0, 0.0, 1.0, 0.0])
    sea = summed_components(omega, amplitude, beta)
    assert sea.omegas == (0.3, 0.5, 0.6)
    assert sea.amplitudes == pytest.approx((0.5, 0.8, 0.5), rel=1e-15)
    assert sea.headings_deg == pytest.approx((0.0, math.degrees(1.0), 0.0), rel=1e-15)
    h = 80.0
    field = _sea(sea, depth=h)
    points = np.array([[0.0, 0.0, -10.0], [-150.0, 40.0, -30.0]])
    for t in (0.0, 5.3, 17.9):
        eta = field.kinematics(points, t)[2]
        expected = np.zeros(2)
        for w, A, b in zip(omega[1:], amplitude[1:], beta[1:], strict=True):
            ell = points[:, 0] * math.cos(b) + points[:, 1] * math.sin(b)
            expected += abs(A) * np.sin(w * t - _k(w, h) * ell + np.angle(A))
        np.testing.assert_allclose(eta, expected, rtol=0, atol=1e-12)


def test_fft_grid_components_equal_moordyns_inverse_fft(tmp_path: Path) -> None:
    """WaveKin 2 (MoorDyn-C v2.7 WaveGrid.cpp): the rows interpolated linearly to the
    smallest step (here 0.1 rad/s from 0 to 0.8), then ``irfft(A (n-1)) / (2 (n-1))`` with
    the shift ``exp(-i k l)``: done here with numpy's inverse FFT, against the components'
    elevation at the FFT's sample times at two points."""
    path = tmp_path / "wave_frequencies.txt"
    path.write_text("0 0 0\n0.2 0.4 0.1\n0.3 0 0.6\n0.5 -0.2 0\n0.8 0.3 0.3\n")
    omega, amplitude, beta = read_wave_frequencies(path)
    sea, step, mean = fft_grid_components(omega, amplitude, beta)
    assert step == pytest.approx(0.1, rel=1e-12) and mean == 0.0
    even = np.arange(9) * step
    A = np.interp(even, omega, amplitude.real) + 1j * np.interp(even, omega, amplitude.imag)
    h, n_t = 60.0, 16
    field = _sea(sea, depth=h)
    times = np.arange(n_t) * (2 * math.pi / step) / n_t
    for x in (0.0, -230.0):
        k = np.array([0.0] + [_k(w, h) for w in even[1:]])
        # kiss_fftri is unnormalized and MoorDyn divides by n_t: numpy's irfft
        series = np.fft.irfft(A * 8 * np.exp(-1j * k * x), n=n_t)
        ours = [field.kinematics(np.array([[x, 0.0, -1.0]]), t)[2][0] for t in times]
        np.testing.assert_allclose(ours, series, rtol=0, atol=1e-12)


def test_elevation_series_becomes_its_fourier_components(tmp_path: Path) -> None:
    """WaveKin 3 (MoorDyn-C v2.7 WaveGrid.cpp): a hand-written 40 s series of a mean level
    0.1 m, 0.5 cos(2 pi 3 t / 40) + 0.2 sin(2 pi 5 t / 40) and a 0.05 m ripple at 0.75 Hz,
    sampled every 0.1 s and resampled at dtWave = 0.2 s: the FFT's components at 3 and 5
    cycles per record with those amplitudes and phases; the ripple (above MoorDyn's 0.5 Hz
    cut-off) and the mean level are dropped; the last sample (an odd count) too."""
    T = 40.0
    t = np.arange(401) * 0.1
    eta = (0.1 + 0.5 * np.cos(2 * math.pi * 3 * t / T) + 0.2 * np.sin(2 * math.pi * 5 * t / T)
           + 0.05 * np.cos(2 * math.pi * 0.75 * t))
    path = tmp_path / "wave_elevation.txt"
    path.write_text("".join(f"{a:.17g} {b:.17g}\n" for a, b in zip(t, eta, strict=True)))
    times, values = read_wave_elevation(path)
    np.testing.assert_array_equal(times, t)
    sea, n, mean = elevation_components(times, values, 0.2)
    assert n == 200 and mean == pytest.approx(0.1, abs=1e-12)
    assert sea.omegas == pytest.approx((2 * math.pi * 3 / T, 2 * math.pi * 5 / T), rel=1e-12)
    assert sea.amplitudes == pytest.approx((0.5, 0.2), abs=1e-12)
    # 0.5 cos(w t) = 0.5 cos(k x - w t + 0); 0.2 sin(w t) = 0.2 cos(k x - w t + 90 deg)
    assert sea.phases_deg == pytest.approx((0.0, 90.0), abs=1e-9)


@pytest.mark.parametrize(("text", "where", "what"), [
    ("0.1 0 0\n0.2 1 0\n", "line 1", "first frequency must be 0"),
    ("0 0 0\n0.2 1\n", "line 2", "at least 3 finite numbers"),
    ("0 0 0\n0.2 one 0\n", "line 2", "expected numbers"),
    ("0 0 0\n0.2 1 0 7.0\n", "line 2", "within +-2 pi"),
    ("0 0 0\n", None, "at least 2 rows"),
])
def test_bad_wave_frequencies_name_file_and_line(tmp_path: Path, text: str, where: str | None,
                                                 what: str) -> None:
    path = _deck(tmp_path, "7  WaveKin", {"wave_frequencies.txt": text})
    with pytest.raises(CaseError) as info:
        read_moordyn_deck(path)
    assert info.value.file.endswith("wave_frequencies.txt")
    assert what in info.value.reason
    if where:
        assert info.value.field == where


def test_bad_elevation_series_and_dtwave(tmp_path: Path) -> None:
    path = _deck(tmp_path, "3  WaveKin", {"wave_elevation.txt": "0 0\n1 0.2\n1 0.3\n"})
    with pytest.raises(CaseError, match="times must increase") as info:
        read_moordyn_deck(path)
    assert info.value.field == "line 3"
    path = _deck(tmp_path, "3  WaveKin\n-0.5  dtWave", {"wave_elevation.txt": "0 0\n9 1\n"})
    with pytest.raises(CaseError, match="positive time step") as info:
        read_moordyn_deck(path)
    assert info.value.field == "OPTIONS dtWave"


def test_unsupported_items_are_all_warned_at_once(tmp_path: Path) -> None:
    """WaveKin 6 (grid files) and Currents 2 (time-varying profile) in one deck: a warning
    each, the deck still read (still water, no current)."""
    path = _deck(tmp_path, "6  WaveKin\n2  Currents", {})
    deck = read_moordyn_deck(path)
    notes = " | ".join(deck.notes)
    assert "WaveKin = 6 (wave kinematics grid files) is not read" in notes
    assert "Currents = 2 (a time-varying current profile" in notes
    assert deck.system.environment.waves.kind == "none"


def test_node_modes_read_like_grid_modes_with_a_warning(tmp_path: Path) -> None:
    """WaveKin 5 reads wave_elevation.txt as WaveKin 3 does, warning that MoorDyn-C 2.7
    builds no kinematics for it."""
    series = "".join(f"{0.5 * k} {math.sin(2 * math.pi * 0.5 * k / 20)}\n" for k in range(41))
    deck = read_moordyn_deck(_deck(tmp_path, "5  WaveKin\n0.5  dtWave",
                                   {"wave_elevation.txt": series}))
    waves = deck.system.environment.waves
    assert waves.kind == "components" and waves.stretching == "wheeler"
    assert waves.components.omegas == pytest.approx((2 * math.pi / 20,), rel=1e-12)
    assert any("builds no kinematics for WaveKin 5" in n for n in deck.notes)


# --------------------------------------------------------------------------- public decks

#: MoorDyn's own wave decks (tests/Mooring/<path> of MoorDyn v2.7.1, origins in
#: tests/data/moordyn/public/README.md), their wave files next to them.
WAVE_DECKS = ["wavekin_2/wavekin_2.txt", "wavekin_2/wavekin_3.txt", "wavekin_7/wavekin_7.txt",
              "wave_surface/wave_surface.txt"]


@pytest.mark.parametrize("deck", WAVE_DECKS)
def test_public_wave_decks_convert_solve_and_run(deck: str, tmp_path: Path) -> None:
    """`moorline convert` writes the components into the case (read back exactly), the
    statics (still water) converge, and a 2 s dynamics runs in the waves (the recorded
    elevation at the origin is the sea's)."""
    from click.testing import CliRunner

    from moorline.cli import cli
    from moorline.io import load_case
    from moorline.model import DynamicsSettings
    from moorline.solvers.dynamics import simulate
    from moorline.solvers.statics import solve_statics

    out = tmp_path / "case.yaml"
    result = CliRunner().invoke(cli, ["convert", str(PUBLIC / deck), "--out", str(out), "-q"])
    assert result.exit_code == 0, result.output
    system = load_case(out)
    waves = system.environment.waves
    assert waves == read_moordyn_deck(PUBLIC / deck).system.environment.waves
    assert waves.kind == "components" and waves.active
    static = solve_statics(system)
    assert static.success, static.message
    run = simulate(system, DynamicsSettings(duration=2.0, dt=0.05), initial=static)
    assert run.success, run.message
    field = fluid_field_from_environment(system.environment)
    expected = [field.kinematics(np.zeros((1, 3)), t)[2][0] for t in run.time]
    np.testing.assert_allclose(run.wave_elevation, expected, rtol=0, atol=1e-12)
    assert np.abs(expected).max() > 0.05


def _moordyn_copy(tmp_path: Path, deck: str, files: tuple[str, ...], edits=(),
                  drop: tuple[str, ...] = ()) -> Path:
    """The deck (its rows starting with one of ``drop`` left out) and its files in
    ``tmp_path`` (MoorDyn writes its logs next to the deck)."""
    source = PUBLIC / deck
    rows = source.read_text().splitlines(keepends=True)
    text = "".join(r for r in rows if not r.startswith(drop)) if drop else "".join(rows)
    for old, new in edits:
        assert old in text
        text = text.replace(old, new)
    path = tmp_path / source.name
    path.write_text(text)
    for name in files:
        (tmp_path / name).write_bytes((source.parent / name).read_bytes())
    return path


@pytest.mark.compare
@pytest.mark.parametrize(("deck", "files", "step", "tol_eta", "tol_kin"), [
    ("wavekin_7/wavekin_7.txt", ("wave_frequencies.txt",), 1.7, 1e-8, 1e-8),
    ("wavekin_2/wavekin_3.txt", ("wave_elevation.txt", "water_grid.txt"), 7 * 0.15, 1e-6,
     2e-4),
    pytest.param("wavekin_2/wavekin_2.txt", ("wave_frequencies.txt", "water_grid.txt"),
                 math.pi / 6, 1e-8, 2e-4, marks=pytest.mark.slow),  # MoorDyn's grid: ~10 s
])
def test_wave_kinematics_match_moordyn(deck: str, files: tuple[str, ...], step: float,
                                       tol_eta: float, tol_kin: float,
                                       tmp_path: Path) -> None:
    """MoorDyn-C 2.7.2 (the `moordyn` module, ``GetWavesKin``) on the same deck against the
    read components, at 24 submerged points at 3 times (the current switched off in both:
    MoorDyn adds it to its grid at unstretched heights).

    - WaveKin 7: both sum the same closed-form components with Wheeler stretching; measured
      4.6e-10 m (elevation), 2.1e-10 m/s, 7.8e-11 m/s^2 (MoorDyn's approximate wave number,
      ``WaveNumber``): tolerance 1e-8.
    - WaveKin 3 and 2 (grid): times on the FFT's samples (0.15 s, pi/6 s) and points on
      water_grid.txt's x, y: the elevation agrees to 2.9e-7 m (WaveKin 3: MoorDyn stores
      dtWave in single precision) and 6.7e-10 m; velocity and acceleration to 3.5e-5 (m/s,
      m/s^2), MoorDyn interpolating linearly between its 1 m z levels at the stretched
      height: bounded by ``dz^2 k^2 / 8 |u|`` = 2e-4 (k = 0.045 rad/m, |u| < 0.9 m/s), the
      tolerance."""
    moordyn = pytest.importorskip("moordyn")
    path = _moordyn_copy(tmp_path, deck, files,
                         [("1             Currents", "0             Currents")]
                         if "wavekin_2" in deck else [])
    system = read_moordyn_deck(path).system
    field = fluid_field_from_environment(system.environment)
    points = np.array([(x, y, z) for x in (-300.0, -100.0, -37.0, 0.0) for y in (0.0, 1.0)
                       for z in (-5.0, -20.0, -45.0)])
    fairleads = [p.position for p in system.points.values() if p.kind == "prescribed"]
    x = np.concatenate(fairleads) if fairleads else np.zeros(0)
    md = moordyn.Create(str(path))
    try:
        moordyn.Init(md, x, np.zeros_like(x))
        waves = moordyn.GetWaves(md)
        t = 0.0
        for _ in range(3):
            moordyn.Step(md, x, np.zeros_like(x), t, step)
            t += step
            theirs = [moordyn.GetWavesKin(waves, *p) for p in points]
            vel, acc, eta = field.kinematics(points, t)
            np.testing.assert_allclose(eta, [r[2] for r in theirs], rtol=0, atol=tol_eta)
            np.testing.assert_allclose(vel, [r[0] for r in theirs], rtol=0, atol=tol_kin)
            np.testing.assert_allclose(acc, [r[1] for r in theirs], rtol=0, atol=tol_kin)
    finally:
        moordyn.Close(md)


@pytest.mark.compare
def test_wave_surface_line_tension_matches_moordyn(tmp_path: Path) -> None:
    """MoorDyn's wave_surface deck (WaveKin 7: one 5 m, 0.4 rad/s component in 30 m of
    water), its line 1 (a 50 m chain hung between two fixed points 40 m apart at z = -10 m,
    always submerged; the deck's other lines, independent of it and crossing the surface,
    removed): the top segment's tension over 10.5 s from the still-water equilibrium,
    moorline (dt 5 ms) against MoorDyn-C 2.7.2 (``GetLineNodeTen``, dtM 0.1 ms). The waves
    swing it between 430 and 770 N; measured difference at most 2.1 N (0.28 % of the peak),
    a constant offset (MoorDyn's initial condition stops at threshIC = 1e-3); tolerance 1 %
    of the peak. Afterwards the line goes slack (near 0 N at 11-13 s) and the two snap back
    differently (up to 7 %), so the comparison stops before."""
    moordyn = pytest.importorskip("moordyn")
    from moorline.model import DynamicsSettings
    from moorline.solvers.dynamics import simulate
    from moorline.solvers.statics import solve_statics

    path = _moordyn_copy(tmp_path, "wave_surface/wave_surface.txt", ("wave_frequencies.txt",),
                         drop=tuple(f"{k}     chain " for k in (2, 3, 4, 5)))
    system = read_moordyn_deck(path).system
    assert list(system.lines) == ["line1"]
    dt_out, n = 0.1, 105
    md = moordyn.Create(str(path))
    try:
        moordyn.Init(md, np.zeros(0), np.zeros(0))
        line = moordyn.GetLine(md, 1)
        top = moordyn.GetLineN(line)
        theirs = []
        for k in range(n):
            moordyn.Step(md, np.zeros(0), np.zeros(0), k * dt_out, dt_out)
            theirs.append(np.linalg.norm(moordyn.GetLineNodeTen(line, top)))
    finally:
        moordyn.Close(md)
    run = simulate(system, DynamicsSettings(duration=n * dt_out, dt=0.005),
                   initial=solve_statics(system))
    assert run.success, run.message
    element = run.mesh.line_elements[run.mesh.line_index("line1")][-1]
    times = dt_out * np.arange(1, n + 1)
    ours = np.interp(times, run.time, run.tension[:, element])
    theirs = np.array(theirs)
    assert theirs.max() - theirs.min() > 300.0  # the waves drive it
    assert np.abs(ours - theirs).max() < 0.01 * theirs.max()


# --------------------------------------------------------------------------- the case file

CASE = """
name: components
units: SI
environment:
  depth: 100
  waves: {waves}
line_types:
  chain: {{diameter: 0.1, mass_per_length: 50, EA: 5.0e8}}
points:
  anchor: {{kind: fixed, position: [-300, 0, -100]}}
  fairlead: {{kind: prescribed, position: [0, 0, -10]}}
lines:
  line1: {{type: chain, length: 350, segments: 10, end_a: anchor, end_b: fairlead}}
"""
SEA = ("{kind: components, heading: 30, stretching: wheeler, components: {omegas: [0.5, 1.25], "
       "amplitudes: [1.0, '20 cm'], phases: [10, '0.5 rad']}}")


def _case(waves: str = SEA, extra: str = ""):
    from moorline.io import load_case_text

    return load_case_text(CASE.format(waves=waves) + extra, file="sea.yaml")


def test_case_file_components_sea_and_round_trip(tmp_path: Path) -> None:
    """``kind: components`` with units (cm, rad converted: angles in degrees); written by the
    case writer and read back identical."""
    from moorline.io import load_case
    from moorline.io.case_writer import write_case

    system = _case()
    waves = system.environment.waves
    assert waves.kind == "components" and waves.heading_deg == 30.0
    assert waves.components == SeaComponents(omegas=(0.5, 1.25), amplitudes=(1.0, 0.2),
                                             phases_deg=(10.0, math.degrees(0.5)))
    assert waves.active
    back = load_case(write_case(system, tmp_path / "sea.yaml"))
    assert back.environment.waves == waves


@pytest.mark.parametrize(("waves", "field", "what"), [
    ("{kind: components, components: {omegas: [0.5, 1], amplitudes: [1], phases: [0, 0]}}",
     "environment.waves.components.amplitudes", "1 amplitudes for 2 omegas"),
    ("{kind: components, components: {omegas: [0.5], amplitudes: [1], phases: [0], "
     "headings: [0, 9]}}", "environment.waves.components.headings", "2 headings for 1"),
    ("{kind: components}", "environment.waves.components", "needs components"),
    ("{kind: random, height: 2, period: 8, components: {omegas: [1], amplitudes: [1], "
     "phases: [0]}}", "environment.waves.components", "only with kind: components"),
    ("{kind: components, components: {omegas: [-0.5], amplitudes: [1], phases: [0]}}",
     "environment.waves.components.omegas", "must be > 0"),
])
def test_bad_components_name_the_key(waves: str, field: str, what: str) -> None:
    with pytest.raises(CaseError) as info:
        _case(waves)
    assert info.value.file == "sea.yaml"
    assert info.value.field.startswith(field) and what in info.value.reason


def test_stochastic_refuses_a_components_sea_clearly() -> None:
    with pytest.raises(CaseError, match="explicit components have no spectrum") as info:
        _case(extra="analyses: [{kind: stochastic}]\n")
    assert info.value.field == "analyses[0].kind"


def test_harmonic_balance_needs_components_that_repeat() -> None:
    """Components at 1 and 3 times 2 pi / 20 s repeat over 20 s (and 40 s), not over 30 s."""
    from moorline.errors import MoorlineError
    from moorline.solvers.harmonic import _check_wave_period

    w = 2 * math.pi / 20
    system = _case(f"{{kind: components, components: {{omegas: [{w!r}, {3 * w!r}], "
                   "amplitudes: [1, 0.5], phases: [0, 0]}}")
    _check_wave_period(system, 20.0)
    _check_wave_period(system, 40.0)
    with pytest.raises(MoorlineError, match="every wave component must repeat"):
        _check_wave_period(system, 30.0)


def test_random_sea_and_its_components_are_the_same_sea() -> None:
    """One code path: a JONSWAP realization written out as ``kind: components`` gives the
    same kinematics as the ``kind: random`` description it came from."""
    from moorline.waves import random_sea

    random = Waves(kind="random", height=3.0, period=9.0, record_length=200.0, seed=4,
                   heading_deg=20.0, stretching="wheeler")
    sea = random_sea(random).components(80.0, G)
    explicit = Waves(kind="components", heading_deg=20.0, stretching="wheeler",
                     components=SeaComponents(omegas=tuple(sea.omegas),
                                              amplitudes=tuple(sea.amplitudes),
                                              phases_deg=tuple(np.degrees(sea.phases))))
    points = np.array([[0.0, 0.0, -2.0], [40.0, -10.0, -30.0], [-5.0, 3.0, 0.5]])
    fields = [fluid_field_from_environment(Environment(depth=80.0, gravity=G, waves=w),
                                           ramp_time=5.0) for w in (random, explicit)]
    for t in (1.0, 7.5, 33.0):
        a, b = (f.kinematics(points, t) for f in fields)
        for x, y in zip(a, b, strict=True):
            np.testing.assert_allclose(x, y, rtol=1e-12, atol=1e-12)


def test_body_wave_loads_take_components_like_the_regular_wave() -> None:
    """cases/harmonic_body.yaml (a floating disc with an exciting-force table on one cable)
    with its 1 ft, 3 s airy wave written as one component (amplitude 0.5 ft, omega 2 pi / 3,
    phase 0: the same sea): 3 s of dynamics give the same body motion and tensions."""
    from moorline.io import load_case_text
    from moorline.model import DynamicsSettings
    from moorline.solvers.dynamics import simulate
    from moorline.solvers.statics import solve_statics

    text = (Path(__file__).resolve().parents[1] / "cases" / "harmonic_body.yaml").read_text()
    airy = "waves: {kind: airy, height: 1, period: 3}"
    assert airy in text
    component = (f"waves: {{kind: components, components: {{omegas: [{2 * math.pi / 3!r}], "
                 "amplitudes: [0.5], phases: [0]}}")
    runs = []
    for case in (text, text.replace(airy, component)):
        system = load_case_text(case, file="h.yaml")
        runs.append(simulate(system, DynamicsSettings(duration=3.0, dt=0.05),
                             initial=solve_statics(system)))
    a, b = runs
    assert a.success and b.success
    assert np.ptp(a.body_pose[:, 0, 2]) > 0.1  # the wave heaves the disc
    np.testing.assert_allclose(b.body_pose, a.body_pose, rtol=0, atol=1e-9)
    np.testing.assert_allclose(b.tension, a.tension, rtol=1e-9)


def test_steady_node_current_is_read_with_moordyns_gap_named(tmp_path: Path) -> None:
    """Currents 3 reads current_profile.txt like Currents 1; MoorDyn-C 2.7 does not implement
    it (docs/waterkinematics.rst, no branch in Waves::setup): a warning says so."""
    profile = "header\nheader\nz ux uy uz\n-320 0.2 0 0\n0 0.6 0 0\n"
    deck = read_moordyn_deck(_deck(tmp_path, "3  Currents", {"current_profile.txt": profile}))
    assert deck.system.environment.current.speeds == (0.2, 0.6)
    assert any("builds no current for Currents 3" in n for n in deck.notes)


def test_exciting_force_tables_need_one_heading() -> None:
    """A body's exciting-force table is for the sea's heading: components going elsewhere
    are refused (and accepted when they all go that way)."""
    from moorline.io import load_case_text

    text = (Path(__file__).resolve().parents[1] / "cases" / "harmonic_body.yaml").read_text()
    airy = "waves: {kind: airy, height: 1, period: 3}"
    sea = ("waves: {{kind: components, heading: 10, components: {{omegas: [2, 2.5], "
           "amplitudes: [0.5, 0.2], phases: [0, 0], headings: [10, {}]}}}}")
    load_case_text(text.replace(airy, sea.format(10)), file="h.yaml")
    with pytest.raises(CaseError, match="body disc's exciting forces are for one heading") as e:
        load_case_text(text.replace(airy, sea.format(40)), file="h.yaml")
    assert e.value.field == "environment.waves.components.headings"
