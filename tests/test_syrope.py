"""MoorDyn's Syrope polyester rope (:mod:`moorline.physics.syrope`) and its deck input
(:mod:`moorline.io.moordyn_syrope`): exact tangent, one segment against the model's equations
integrated independently (scipy), the static law, MoorDyn's ``linear_wc`` deck against
MoorDyn-C itself, the deck round trip and the refusals."""

from __future__ import annotations

import functools
import math
import shutil
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from moordyn_surge import moordyn_fair_tensions

from moorline.errors import CaseError
from moorline.io.moordyn import read_moordyn, write_moordyn
from moorline.model import DynamicsSettings, Motion
from moorline.physics.syrope import SyropeRope, syrope_update
from moorline.solvers.dynamics import simulate
from moorline.solvers.statics import solve_statics

DATA = Path(__file__).parent / "data/moordyn/public/MoorDyn/syrope"
#: MoorDyn's owc.dat as MoorDyn-C reads it: its three header lines skipped (the (0, 0) row
#: on line 3 is one of them)
OWC = np.loadtxt(DATA / "owc.dat", skiprows=3)
#: the decks' line type: SYROPE:syrope.dat|1.53e8|23.12 with BA 5.0e10|1.0e5
ALPHA, BETA, C1, C2 = 1.53e8, 23.12, 5.0e10, 1.0e5
#: MoorDyn's three test decks' working curves (tests/Mooring/syrope/*/syrope.dat)
FORMS = {"linear": (1.25e8, 0.0), "quadratic": (0.25, 1.0), "exp": (0.20, 1.50)}
TMAX0 = 1.3886e6  # their SYROPE IC Tmax0


def _rope(form: str = "linear") -> SyropeRope:
    return SyropeRope(OWC, form, *FORMS[form], ALPHA, BETA)


# ---- the model's curves written out independently (MoorDyn-C v2.7.1 Line.cpp, the docs) ----

def _g(T):
    return np.log1p(BETA * np.asarray(T) / ALPHA) / BETA


@functools.lru_cache(maxsize=64)
def _working_curve(form: str, Tmax: float):
    k1, k2 = FORMS[form]
    x_max = np.interp(Tmax, OWC[:, 1], OWC[:, 0])
    x_min = x_max - Tmax / k1 if form == "linear" and k1 >= 1 else (
        OWC[0, 0] + k1 * (x_max - OWC[0, 0]))
    xi = np.linspace(0.0, 1.0, 30)
    if form == "linear":
        y = Tmax * xi
    elif form == "quadratic":
        y = Tmax * xi * (k2 * xi + 1 - k2)
    else:
        y = Tmax * (1 - np.exp(k2 * xi)) / (1 - np.exp(k2))
    x = x_min + (x_max - x_min) * xi
    return x, y, x - _g(y)


def _mean(form: str, z: float, Tmax: float) -> tuple[float, float]:
    """Mean tension and its curve strain: the working curve of Tmax below its top, the OWC
    (not below Tmax) above it."""
    x, y, zw = _working_curve(form, Tmax)
    if z < zw[-1]:
        T = np.interp(z, zw, y)
        return T, np.interp(T, y, x)
    T = max(Tmax, np.interp(z, OWC[:, 0] - _g(OWC[:, 1]), OWC[:, 1]))
    return T, np.interp(T, OWC[:, 1], OWC[:, 0])


@pytest.mark.parametrize("dt", [0.0, 0.05, 5.0])
@pytest.mark.parametrize("form", list(FORMS))
def test_tangent_against_finite_differences(form, dt):
    """``dT_e/d strain_new`` of one step against central differences: on the working curve
    (loading, unloading), near its foot, on the OWC beyond ``Tmax`` and slack."""
    rope = _rope(form)
    e_o = np.array([0.0148, 0.0150, 0.0125, 0.0235, 0.0300, 0.0100])
    Tmax = np.full(6, TMAX0)
    z_o, _ = rope.relaxed_state(e_o, Tmax)
    e_n = e_o + np.array([2e-4, -3e-4, -1.5e-3, 1e-3, 2e-3, -0.0101])
    T, _, _, k = syrope_update(e_n, e_o, z_o, Tmax, dt, rope, C1, C2, 1.0)
    h = 1e-8
    Tp = syrope_update(e_n + h, e_o, z_o, Tmax, dt, rope, C1, C2, 1.0)[0]
    Tm = syrope_update(e_n - h, e_o, z_o, Tmax, dt, rope, C1, C2, 1.0)[0]
    np.testing.assert_allclose(k, (Tp - Tm) / (2 * h), rtol=1e-6)
    assert T[-1] < 0 < T[:-1].min()  # the last one is slack: its regularization


def _strain(t: float) -> float:
    """Smooth loading past Tmax0, a hold, unloading and an oscillation (strain)."""
    ramp = 0.5 * (1 - math.cos(math.pi * min(t / 10.0, 1.0)))
    down = 0.5 * (1 - math.cos(math.pi * min(max(t - 25.0, 0.0) / 10.0, 1.0)))
    return 0.0148657 + 0.015 * ramp - 0.010 * down + 1e-3 * math.sin(2 * math.pi * t / 7.0)


def _strain_rate(t: float, h: float = 1e-6) -> float:
    return (_strain(t + h) - _strain(t - h)) / (2 * h)


MAX_STEP = 0.1


def _reference(form: str, c1: float, times: np.ndarray) -> np.ndarray:
    """Tension ``Tm + c1 dz/dt`` from scipy's DOP853 on the slow-strain ODE, the running
    maximum handled by events: on the working curve of ``Tmax`` until the state reaches its
    top; above it (the OWC, ``Tm`` raising the maximum) until the slow strain stops growing,
    where ``Tmax`` becomes the ``Tm`` reached; and so on."""
    from scipy.integrate import solve_ivp

    def rate(t, z, Tmax):
        T, X = _mean(form, z[0], Tmax)
        return [((ALPHA + BETA * T) * (_strain(t) - X) + C2 * _strain_rate(t)) / (c1 + C2)]

    def top(t, z, Tmax):
        return z[0] - _working_curve(form, Tmax)[2][-1]

    def peak(t, z, Tmax):
        return rate(t, z, Tmax)[0]

    top.terminal, top.direction = True, 1
    peak.terminal, peak.direction = True, -1
    x, _, zw = _working_curve(form, TMAX0)
    z0, t0, Tmax = np.interp(_strain(0.0), x, zw), 0.0, TMAX0  # at rest on the curve
    pieces, on_owc = [], False
    while t0 < times[-1]:
        sol = solve_ivp(rate, (t0, times[-1]), [z0], args=(Tmax,), method="DOP853",
                        rtol=1e-11, atol=1e-15, max_step=MAX_STEP, dense_output=True,
                        events=peak if on_owc else top)
        pieces.append((t0, sol.t[-1], Tmax, sol.sol, on_owc))
        t0, z0 = sol.t[-1], sol.y[0, -1]
        if on_owc:
            Tmax = max(Tmax, float(_mean(form, z0, Tmax)[0]))
        on_owc = not on_owc
    assert any(p[4] for p in pieces)  # the history was exercised
    out = []
    for t in times:
        _, _, Tmax, sol, _ = next(p for p in pieces if p[0] <= t <= p[1])
        z = sol(t)
        out.append(_mean(form, z[0], Tmax)[0] + c1 * rate(t, z, Tmax)[0])
    return np.array(out)


def _stepped(form: str, c1: float, dt: float, duration: float) -> tuple[np.ndarray, ...]:
    """moorline's step (:func:`syrope_update`) driven through the same strain history, with
    the ``eta de/dt`` dashpot the solver adds."""
    rope = _rope(form)
    times = dt * np.arange(round(duration / dt) + 1)
    e = np.array([_strain(t) for t in times])
    z, Tmax = rope.relaxed_state(e[:1], np.array([TMAX0]))
    out = []
    for i in range(len(times) - 1):
        T, z, Tmax, _ = syrope_update(e[i + 1:i + 2], e[i:i + 1], z, Tmax, dt, rope, c1, C2,
                                      1.0)
        out.append(T[0] + c1 * C2 / (c1 + C2) * _strain_rate(times[i + 1]))
    return times[1:], np.array(out), Tmax


@pytest.mark.parametrize("form", list(FORMS))
def test_single_segment_against_independent_integration(form):
    """One segment driven through a strain history that loads it past ``Tmax0`` (onto the
    OWC), holds, unloads onto a new working curve and oscillates (period 7 s), the static
    damping reduced to 2e9 N s (slow-strain time constant about 10 s instead of 300 s, so
    that 45 s see all of it): moorline's midpoint step (dt = 0.05 s) against scipy's DOP853
    (rtol 1e-11; 1e-9 of the tension from a 5x smaller max_step) on the equations written
    out here. Measured: 5.2e-6 (linear), 1.2e-5 (quadratic), 4.1e-6 (exp) of the largest
    tension; the step is second order: at dt = 0.025 s the linear case's difference is 5.1
    times smaller (the quadratic's only 1.6: its working curve, sampled at 30 points as
    MoorDyn does, has stronger kinks, where the midpoint rule loses order). Tolerances 3e-5,
    and a ratio above 3 (linear)."""
    c1, duration = 2.0e9, 45.0
    times, ours, Tmax = _stepped(form, c1, 0.05, duration)
    ref = _reference(form, c1, times)
    error = np.max(np.abs(ours - ref)) / np.max(np.abs(ref))
    assert Tmax[0] > 1.1 * TMAX0  # the running maximum rose
    assert error < 3e-5, error
    if form == "linear":
        times, ours, _ = _stepped(form, c1, 0.025, duration)
        finer = np.max(np.abs(ours - _reference(form, c1, times))) / np.max(np.abs(ref))
        assert error / finer > 3.0, (error, finer)


def test_static_law_is_the_working_curve_of_tmax0():
    """The statics of MoorDyn's linear_wc deck (one 1 m segment between a fixed and a
    coupled point): the tension of the linear working curve of Tmax0 at the deck's strain,
    ``k1 (e - x_max + Tmax0 / k1)`` with ``x_max`` the OWC's strain at Tmax0 (exact to the
    solver's round-off). The deck's Tmean0 = 4.339e5 N (4 digits) agrees to 1.9e-4."""
    system = read_moordyn(DATA / "linear_wc/line.txt")
    lt, line = system.line_types["poly"], system.lines["line1"]
    assert (lt.material, lt.working_curve, lt.wc_k1, lt.EAd, lt.EAd_Lm, lt.BA, lt.BA_dynamic
            ) == ("syrope", "linear", 1.25e8, ALPHA, BETA, C1, C2)
    assert line.syrope_ic == (TMAX0, 4.339e5) and len(lt.owc) == 29
    statics = solve_statics(system)
    assert statics.success, statics.message
    k1 = FORMS["linear"][0]
    x_max = np.interp(TMAX0, OWC[:, 1], OWC[:, 0])
    exact = k1 * (0.0148657 - x_max + TMAX0 / k1)
    assert statics.tension[0] == pytest.approx(exact, rel=1e-12)
    assert statics.tension[0] == pytest.approx(4.339e5, rel=2e-4)


def _copy_deck(tmp_path: Path, form: str = "linear") -> Path:
    """A copy of MoorDyn's deck with its settings file and ../owc.dat (MoorDyn writes its
    line output files next to the deck)."""
    folder = tmp_path / f"{form}_wc"
    shutil.copytree(DATA / f"{form}_wc", folder)
    shutil.copy(DATA / "owc.dat", tmp_path / "owc.dat")
    return folder / "line.txt"


RTEST = (Path(__file__).parent / "data/moordyn/public/OpenFAST-r-test/modules/moordyn/"
         "md_syrope")


def _motion(x0: float):
    """Point 2 from ``x0``: pulled 2 cm in 10 s, held, released by 1.2 cm at 150-160 s, with
    a 2 mm oscillation of period 8 s (smooth)."""

    def x(t: float) -> float:
        ramp = 0.5 * (1 - math.cos(math.pi * min(t / 10.0, 1.0)))
        down = 0.5 * (1 - math.cos(math.pi * min(max(t - 150.0, 0.0) / 10.0, 1.0)))
        return x0 + 0.02 * ramp - 0.012 * down + 0.002 * math.sin(2 * math.pi * t / 8.0)

    return x


@pytest.mark.compare
@pytest.mark.parametrize(("case", "x0", "z", "lag"), [
    ("linear_wc", 1.0148657, -5.0, 0.025), ("md_syrope", 1.0137912, 0.0, 0.0)])
def test_single_segment_decks_against_moordyn(tmp_path, case, x0, z, lag):
    """MoorDyn's tests/Mooring/syrope/linear_wc deck and OpenFAST r-test md_syrope (one 1 m
    segment of the same rope, Tmax0 1.3886e6 and 1.302e6 N) with point 2 driven by
    :func:`_motion` for 170 s: the tension rises past Tmax0 onto the OWC (to 2.9 Tmax0) while
    the slow strain creeps (time constant about 300 s), then unloads onto a new working
    curve. MoorDyn-C (RK2 at the deck's dtM, 0.05 and 0.01 s, driven every 0.1 s,
    ``Init_NoIC``: its slow strain set from the deck's Tmean0) against moorline (read from
    the same deck, implicit midpoint step of 0.1 s, started at rest at the static state).
    MoorDyn's RK2 (``source/Time.cpp``) evaluates the tension last at the midpoint of its
    last internal step, so its ``FairTen`` after a step to ``t`` is the tension at ``t -
    lag``: ``dtM / 2`` = 0.025 s for linear_wc (as tests/test_static_dynamic.py; without it
    the difference is 1.5 %), but 0 for md_syrope: MoorDyn-C's ``Step`` (``MoorDyn2.cpp``)
    takes internal steps while ``t_target -= dt_step`` stays positive, and 0.1 less ten
    times 0.01 leaves 1.0e-17 s, an eleventh, vanishing step (with 0.005 s the difference is
    2.9e-3). Measured: 5.7e-5 and 1.6e-4 of the tension at most (the two time
    discretizations, and the start: the decks' Tmean0 are 1.9e-4 and 5.2e-4 off the working
    curve's tension at their geometry, which the dynamic branch turns into 5e-5 and 1.6e-4 of
    the tension, decaying with the creep); tolerance 3e-4."""
    pytest.importorskip("moordyn")

    if case == "md_syrope":
        shutil.copytree(RTEST, tmp_path / case)
        deck = tmp_path / case / "moordyn.dat"
    else:
        deck = _copy_deck(tmp_path)
    x = _motion(x0)
    dt, duration = 0.1, 170.0
    n = round(duration / dt)
    theirs = moordyn_fair_tensions(deck, x, z, dt * np.arange(n), dt)
    system = read_moordyn(deck)
    times = dt * np.arange(n + 1)
    motion = Motion(kind="table", times=tuple(times),
                    values=tuple((x(t) - x0, 0.0, 0.0) for t in times))
    p2 = replace(system.points["point2"], motion=motion)
    system = replace(system, points={**system.points, "point2": p2})
    run = simulate(system, DynamicsSettings(duration=duration, dt=dt),
                   initial=solve_statics(system), output_every=dt)
    assert run.success, run.message
    t_theirs = times[1:]
    ours = np.interp(t_theirs - lag, run.time, run.tension[:, 0])
    assert theirs.max() > 1.5 * TMAX0  # far past the history's maximum
    np.testing.assert_allclose(ours, theirs, rtol=3e-4)


@pytest.mark.compare
def test_written_taut_line_with_mass_against_moordyn(tmp_path):
    """The deck's rope (static damping 2e9 N s) as a 50 m line of 5 segments with its mass
    (no gravity, no fluid: both codes start on the straight line at the deck's strain, its
    Tmean0 set to the working curve's tension there), written by :func:`write_moordyn` (its
    settings and OWC files, ``SYROPE IC``) and run by MoorDyn-C at 1e-4 s (explicit RK2),
    against moorline's implicit step of 0.01 s, the end pulled 1 % further with a 0.1 %
    oscillation of period 3 s. The top segment's tension (``FairTen``, half a MoorDyn step
    back) after 5 s: measured 4.4e-5 of the tension (the axial modes, period about 0.1 s,
    that the start excites are resolved by MoorDyn and filtered by moorline's step: 0.9 % in
    the first second); tolerance 3e-4."""
    pytest.importorskip("moordyn")
    from moorline.model import Line, Point, System
    from moorline.physics.syrope import rope_of

    deck = read_moordyn(DATA / "linear_wc/line.txt")
    rope = replace(deck.line_types["poly"], BA=2.0e9)
    length, n_seg, dt, duration, strain = 50.0, 5, 0.01, 10.0, 0.0148657
    x0 = length * (1.0 + strain)

    def x(t: float) -> float:
        ramp = 0.5 * (1 - math.cos(math.pi * min(t / 5.0, 1.0)))
        return x0 + length * (0.01 * ramp + 0.001 * math.sin(2 * math.pi * t / 3.0))

    curves = rope_of(rope)
    z, peak = curves.relaxed_state(np.array([strain]), np.array([TMAX0]))
    tmean0 = float(curves.mean_tension(z, peak)[0][0])
    times = dt * np.arange(round(duration / dt) + 1)
    motion = Motion(kind="table", times=tuple(times),
                    values=tuple((x(t) - x0, 0.0, 0.0) for t in times))
    points = {"a": Point("a", "fixed", (0.0, 0.0, -50.0)),
              "b": Point("b", "prescribed", (x0, 0.0, -50.0), motion=motion)}
    system = System("taut", environment=deck.environment, line_types={"poly": rope},
                    points=points, lines={"l": Line("l", "poly", length, n_seg, "a", "b",
                                                    syrope_ic=(TMAX0, tmean0))})
    run = simulate(system, DynamicsSettings(duration=duration, dt=dt),
                   initial=solve_statics(system), output_every=dt)
    assert run.success, run.message
    path = write_moordyn(system, tmp_path / "taut.dat", 1.0e-4)
    theirs = moordyn_fair_tensions(path, x, -50.0, times[:-1], dt)
    t_theirs = times[1:]
    ours = np.interp(t_theirs - 0.5e-4, run.time, run.tension[:, -1])
    keep = t_theirs >= 5.0
    np.testing.assert_allclose(ours[keep], np.array(theirs)[keep], rtol=3e-4)


def test_deck_round_trip(tmp_path):
    """:func:`write_moordyn` writes the Syrope line type back as ``SYROPE:<settings>|EA_Dc|
    EA_D_Lm`` with its settings and OWC files and the ``SYROPE IC`` section: read again, the
    same line type and line history."""
    system = read_moordyn(DATA / "exp_wc/line.txt")
    path = write_moordyn(system, tmp_path / "back.dat", 0.05)
    back = read_moordyn(path)
    assert back.line_types["poly"] == system.line_types["poly"]
    assert back.lines["line1"].syrope_ic == system.lines["line1"].syrope_ic


@pytest.mark.parametrize(("old", "new", "named"), [
    ("SYROPE:syrope.dat|1.53e8|23.12", "SYROPE:syrope.dat|1.53e8",
     "needs 3 |-separated values"),
    ("SYROPE:syrope.dat|1.53e8|23.12", "SYROPE:missing.dat|1.53e8|23.12",
     "cannot read the Syrope settings file"),
    ("5.0e10|1.0e5", "-0.8|1.0e5", "no damping ratio"),
    ("SYROPE:syrope.dat|1.53e8|23.12", "SYROPE:syrope.dat|1.0e7|23.12",
     "slow strain"),
    ("1       1.3886e6  4.339e5", "1       9.0e6  4.339e5", "outside the original working"),
    ("1       1.3886e6  4.339e5", "2       1.3886e6  4.339e5", "there is no line 2"),
])
def test_bad_syrope_decks_are_refused(tmp_path, old, new, named):
    """What MoorDyn refuses (or reads past its arrays on): a CaseError naming the file and
    the row."""
    deck = _copy_deck(tmp_path)
    text = deck.read_text()
    assert old in text
    deck.write_text(text.replace(old, new))
    with pytest.raises(CaseError) as info:
        read_moordyn(deck)
    assert named in str(info.value) and str(deck) in str(info.value)


def test_bad_settings_file_is_refused(tmp_path):
    """A settings file with an unknown working curve: the error names the file and line."""
    deck = _copy_deck(tmp_path, "quadratic")
    settings = deck.with_name("syrope.dat")
    settings.write_text(settings.read_text().replace("QUADRATIC", "CUBIC"))
    with pytest.raises(CaseError) as info:
        read_moordyn(deck)
    assert "syrope.dat, line 2: WCType 'CUBIC'" in str(info.value)


CASE = """
name: rope
units: SI
environment: {{depth: 100, gravity: 0}}
line_types:
  poly: {{diameter: 0.203, mass_per_length: 40, material: syrope, EAd: 1.53e8,
         EAd_Lm: 23.12, BA: 5.0e10, BA_dynamic: 1.0e5, working_curve: linear, wc_k1: 1.25e8,
         owc: {owc}}}
points:
  a: {{kind: fixed, position: [0, 0, -5]}}
  b: {{kind: prescribed, position: [1.0148657, 0, -5]}}
lines:
  l1: {{type: poly, length: 1.0, segments: 1, end_a: b, end_b: a{ic}}}
analyses:
  - {{kind: {kind}}}
"""


@pytest.mark.parametrize(("ic", "kind", "field", "named"), [
    ("", "statics", "lines.l1.syrope_ic", "needs syrope_ic"),
    (", syrope_ic: [9.0e6, 1.0e5]", "statics", "lines.l1.syrope_ic", "outside the original"),
    (", syrope_ic: [1.3886e6, 4.339e5]", "modal", "analyses[0].kind", "no modal analysis"),
])
def test_bad_syrope_cases_are_refused(ic, kind, field, named):
    """A case's syrope line type without a line history, with one off its curve, or with a
    linearized analysis: a CaseError naming the key."""
    from moorline.io import load_case_text

    owc = [list(row) for row in OWC.tolist()]
    with pytest.raises(CaseError) as info:
        load_case_text(CASE.format(owc=owc, ic=ic, kind=kind), file="rope.yaml")
    assert info.value.field == field and named in info.value.reason


def test_linearized_analyses_refuse_the_rope_through_the_api():
    """The Python API refuses a linearized analysis of a Syrope rope as the case does."""
    from moorline.io import load_case_text
    from moorline.model import ModalSettings
    from moorline.solvers.modal import solve_modes

    owc = [list(row) for row in OWC.tolist()]
    system = load_case_text(CASE.format(owc=owc, ic=", syrope_ic: [1.3886e6, 4.339e5]",
                                        kind="statics"))
    assert solve_statics(system).tension[0] == pytest.approx(433982.9, rel=1e-6)
    with pytest.raises(CaseError) as info:
        solve_modes(system, ModalSettings())
    assert info.value.field == "line_types.poly.material"
    assert "syrope rope" in info.value.reason and "no modal analysis" in info.value.reason


def test_case_file_round_trip(tmp_path):
    """The deck's system written as a case file and loaded again: the same line type and
    line history, and the same static tension."""
    from moorline.io import load_case
    from moorline.io.case_writer import write_case

    system = read_moordyn(DATA / "quadratic_wc/line.txt")
    back = load_case(write_case(system, tmp_path / "rope.yaml"))
    assert back.line_types["poly"] == system.line_types["poly"]
    assert back.lines["line1"].syrope_ic == system.lines["line1"].syrope_ic
    assert solve_statics(back).tension[0] == solve_statics(system).tension[0]


def test_dynamics_start_at_rest_from_the_statics():
    """Two 20 m lines of the quadratic_wc deck's rope, 10 segments each, in water under
    gravity between fixed points: one on the working curve of Tmax0, one stretched past it
    onto the OWC (its running maximum raised). The statics (the table of the relaxed law)
    and the dynamics' relaxed start agree, so 5 s of dynamics stay at the static tensions:
    measured 5e-7 of the tension (the 1.1e-6 between the static table's cubic and the
    piecewise-linear curves, see ``SyropeRope.relaxed_table``); tolerance 1e-5. Without the
    table's insets the start is off by up to 6e-3."""
    from moorline.model import Point

    deck = read_moordyn(DATA / "quadratic_wc/line.txt")
    rope = replace(deck.line_types["poly"], Cd=1.2, Ca=1.0)
    line = replace(deck.lines["line1"], length=20.0, segments=10)
    points = {"a": Point("a", "fixed", (0.0, 0.0, -50.0)),
              "b": Point("b", "fixed", (20.0, 3.0, -50.0)),
              "c": Point("c", "fixed", (0.0, 10.0, -50.0)),
              "d": Point("d", "fixed", (20.3, 10.0, -45.0))}
    system = replace(deck, environment=replace(deck.environment, gravity=9.80665, depth=100.0),
                     line_types={"poly": rope}, points=points,
                     lines={"wc": replace(line, name="wc", end_a="a", end_b="b"),
                            "owc": replace(line, name="owc", end_a="c", end_b="d")})
    statics = solve_statics(system)
    assert statics.success, statics.message
    tension = statics.tension
    assert tension[:10].max() < TMAX0 < tension[10:].min()
    run = simulate(system, DynamicsSettings(duration=5.0, dt=0.05), initial=statics,
                   output_every=0.05)
    assert run.success, run.message
    assert np.abs(run.tension - tension).max() < 1e-5 * tension.max()
