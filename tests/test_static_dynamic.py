"""MoorDyn's viscoelastic static-dynamic rope (:mod:`moorline.physics.static_dynamic`) and its
deck input (:mod:`moorline.io.moordyn_visco`): exact tangent, the closed-form steady harmonic
response of the linear model, the exact statics, and OpenFAST r-test ``md_viscoelastic``
against MoorDyn-C itself."""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from moordyn_surge import moordyn_fair_tensions

from moorline.errors import CaseError
from moorline.io.moordyn import read_moordyn
from moorline.model import DynamicsSettings, Motion
from moorline.physics.static_dynamic import sls_parameters, static_dynamic_update
from moorline.solvers.dynamics import simulate
from moorline.solvers.statics import solve_statics

DECK = (Path(__file__).parent / "data/moordyn/public/OpenFAST-r-test/modules/moordyn/"
        "md_viscoelastic/moordyn.dat")
#: the deck's line type: EA = 1.424e+08|1.586e+08|0.4, BA/-zeta = 4E9|11E6
EA_S, ALPHA, BETA, C1, C2 = 1.424e8, 1.586e8, 0.4, 4.0e9, 11.0e6


@pytest.mark.parametrize("dt", [0.0, 0.01, 1.0])
def test_tangent_against_finite_differences(dt):
    """``dT/d strain_new`` of one step against central differences, taut elements under
    load, near zero load (``k2``'s kink at ``s = 0``), in compression of the static branch,
    and slack."""
    e_o = np.array([1.0, 0.5, 0.02, 1e-4, -0.01, 0.05])
    s_o = np.array([2.9e8, 1.0e8, 1.0e6, -2.0e3, -1.0e5, 4.0e6])
    e_n = e_o + np.array([0.01, -0.02, 0.003, 1e-5, 0.0, -0.1])
    args = (dt, EA_S, ALPHA, BETA, C1, C2, 1e-6)
    T, _, k = static_dynamic_update(e_n, e_o, s_o, *args)
    h = 1e-7
    Tp, _, _ = static_dynamic_update(e_n + h, e_o, s_o, *args)
    Tm, _, _ = static_dynamic_update(e_n - h, e_o, s_o, *args)
    np.testing.assert_allclose(k, (Tp - Tm) / (2 * h), rtol=1e-6)
    assert T[-1] < 0 < T[0]  # the last one is slack: the regularization, tangent 1e-6 EA_s


def _series_stiffness(omega, k1, k2, c1, c2):
    """Complex stiffness of two Kelvin-Voigt elements in series (the module's eq. 1)."""
    p = 1j * omega
    return (k1 + c1 * p) * (k2 + c2 * p) / ((k1 + k2) + (c1 + c2) * p)


@pytest.mark.parametrize("omega", [0.01, 0.3, 2.0, 50.0])
def test_constant_dynamic_stiffness_is_the_standard_linear_solid(omega):
    """:func:`sls_parameters`: the SLS plus a dashpot has the series model's complex stiffness
    at every frequency (an algebraic identity, checked to round-off)."""
    k2 = ALPHA
    k1 = k2 * EA_S / (k2 - EA_S)
    EA1, tau, eta = sls_parameters(EA_S, k2, C1, C2)
    p = 1j * omega
    sls = EA_S + eta * p + EA1 * tau * p / (1 + tau * p)
    assert abs(sls - _series_stiffness(omega, k1, k2, C1, C2)) < 1e-12 * abs(sls)


def test_linear_model_steady_harmonic_response():
    """``EA_D_Lm = 0``: the step (midpoint rule) driven by ``e = e0 + a sin(w t)`` reaches the
    closed-form steady response ``EA_s e0 + Im(K(iw) a e^{iwt})`` (plus the ``eta de/dt``
    dashpot the solver adds). 20 steps per period: the midpoint rule's O(dt^2) error
    (measured 1.3e-4 of the amplitude; 3.2e-5 at 40 steps) under the 1e-3 tolerance."""
    k2 = ALPHA
    k1 = k2 * EA_S / (k2 - EA_S)
    c1, c2 = 2.0e8, 5.0e7
    eta = c1 * c2 / (c1 + c2)
    e0, a, w = 0.05, 0.01, 1.0
    dt = 2 * math.pi / w / 20
    n = 20 * 40  # 40 periods: the transient (time constant (c1 + c2) / (k1 + k2)) is gone
    t = dt * np.arange(n + 1)
    e = e0 + a * np.sin(w * t)
    s = np.array([EA_S * e0])
    tension = []
    for i in range(n):
        T, s, _ = static_dynamic_update(e[i + 1:i + 2], e[i:i + 1], s, dt, EA_S, k2, 0.0,
                                        c1, c2, 1e-6)
        tension.append(T[0] + eta * a * w * math.cos(w * t[i + 1]))
    exact = EA_S * e0 + np.imag(_series_stiffness(w, k1, k2, c1, c2) * a
                                * np.exp(1j * w * t[1:]))
    last = slice(-40, None)
    amplitude = abs(_series_stiffness(w, k1, k2, c1, c2)) * a
    assert np.abs(np.array(tension)[last] - exact[last]).max() < 1e-3 * amplitude


def test_statics_is_the_static_stiffness():
    """At rest the static branch carries everything: the deck's 1 m segment stretched to 2 m
    holds ``EA_s * 1`` exactly (to the solver tolerance), whatever the dynamic stiffness."""
    system = read_moordyn(DECK)
    lt = system.line_types["rope"]
    assert (lt.material, lt.EA, lt.EAd, lt.EAd_Lm, lt.BA, lt.BA_dynamic) == (
        "static_dynamic", EA_S, ALPHA, BETA, C1, C2)
    static = solve_statics(system)
    assert static.success, static.message
    assert static.tension[0] == pytest.approx(EA_S, rel=1e-9)


def _deck(tmp_path: Path, ea: str, ba: str) -> Path:
    text = DECK.read_text(encoding="latin-1").replace("1.424e+08|1.586e+08|0.4", ea)
    path = tmp_path / "deck.dat"
    path.write_text(text.replace("4E9|11E6", ba), encoding="latin-1")
    return path


def test_constant_pair_reads_as_standard_linear_solid(tmp_path):
    """``EA_s|EA_d`` with ``BA_s|BA_d`` is moorline's standard linear solid (exact map); with
    a damping ratio ``BA_s < 0`` the static-dynamic material with a zero slope."""
    lt = read_moordyn(_deck(tmp_path, "1.424e+08|1.586e+08", "4E9|11E6")).line_types["rope"]
    EA1, tau, eta = sls_parameters(EA_S, ALPHA, C1, C2)
    assert (lt.material, lt.EA, lt.EA1, lt.tau, lt.BA) == ("viscoelastic", EA_S, EA1, tau, eta)
    lt = read_moordyn(_deck(tmp_path, "1.424e+08|1.586e+08", "-0.8|11E6")).line_types["rope"]
    assert (lt.material, lt.EAd, lt.EAd_Lm, lt.BA, lt.BA_dynamic) == (
        "static_dynamic", ALPHA, 0.0, -0.8, C2)


@pytest.mark.parametrize(("ea", "ba", "named"), [
    ("1.424e+08|1.0e+08|0.4", "4E9|11E6", "needs 0 < EA_s < EA_d"),
    ("1.424e+08|1.586e+08|0.4", "4E9|-1", "BA_d cannot be a ratio"),
    ("1.424e+08|1.586e+08|0.4", "0|0", "needs BA_s or BA_d > 0"),
    ("1.424e+08|1.586e+08|0.4|1", "4E9|11E6", "at most 3 |-separated values"),
    ("1.424e+08", "4E9|11E6", "more |-separated values than EA"),
    ("1.424e+08|table.txt", "4E9", "is not a number"),
])
def test_bad_viscoelastic_pairs_are_refused(tmp_path, ea, ba, named):
    """What MoorDyn refuses or divides by zero on: a CaseError naming the line type's row."""
    with pytest.raises(CaseError) as info:
        read_moordyn(_deck(tmp_path, ea, ba))
    assert named in str(info.value) and "line type 'rope'" in str(info.value)
    assert "line 7, LINE TYPES" in str(info.value)  # the row (after the origin line)


def _moorline_tension(deck: Path, dt: float, duration: float, x) -> tuple:
    """The deck's segment from its unstretched length (point 2 at x = 1, relaxed) with point 2
    driven along x by ``x(t)`` (a table at every step)."""
    system = read_moordyn(deck)
    times = dt * np.arange(round(duration / dt) + 1)
    motion = Motion(kind="table", times=tuple(times),
                    values=tuple((x(t) - 1.0, 0.0, 0.0) for t in times))
    p2 = replace(system.points["point2"], position=(1.0, 0.0, 0.0), motion=motion)
    system = replace(system, points={**system.points, "point2": p2})
    run = simulate(system, DynamicsSettings(duration=duration, dt=dt),
                   initial=solve_statics(system), output_every=dt)
    assert run.success, run.message
    return run.time, run.tension[:, 0]


def _moordyn_tension(deck: Path, dt: float, duration: float, x) -> np.ndarray:
    """MoorDyn-C's ``FairTen`` after each step, point 2 driven through the same positions
    (velocity the chord of each step, as MoorDyn's tests/polyester.cpp drives it)."""
    moordyn = pytest.importorskip("moordyn")
    from moorline.compare.moordyn_runner import silenced_fd

    out = []
    with silenced_fd(1):
        md = moordyn.Create(str(deck))
        moordyn.Init_NoIC(md, [x(0.0), 0.0, 0.0], [0.0, 0.0, 0.0])
        line = moordyn.GetLine(md, 1)
        for k in range(round(duration / dt)):
            t = k * dt
            moordyn.Step(md, [x(t), 0.0, 0.0], [(x(t + dt) - x(t)) / dt, 0.0, 0.0], t, dt)
            out.append(moordyn.GetLineFairTen(line))
        moordyn.Close(md)
    return np.array(out)


@pytest.mark.compare
@pytest.mark.parametrize("pair", [None, ("1.424e+08|1.586e+08", "4E9|11E6"),
                                  ("1.424e+08|1.586e+08|0.4", "-0.8|11E6")],
                         ids=["mean-load", "constant-sls", "damping-ratio"])
def test_md_viscoelastic_against_moordyn(tmp_path, pair):
    """OpenFAST r-test ``md_viscoelastic`` (MoorDyn's visco.txt: one 1 m polyester segment,
    ``EA = 1.424e8|1.586e8|0.4``, ``BA = 4e9|11e6``) and its constant-``EA_d`` variant (read
    as the standard linear solid) and a variant with a damping ratio ``BA_s = -0.8`` (resolved
    per segment, 4.5e4 N s), both codes starting from the relaxed unstretched segment
    and point 2 pulled to 10 % strain with a 2 % oscillation of period 5 s, dt = 0.01 s,
    20 s. MoorDyn-C 2.7's RK2 (``source/Time.cpp``, ``RK2Scheme::Step``) evaluates the
    tensions last at the step's midpoint, so its ``FairTen`` after a step to ``t`` is the
    tension at ``t - dt/2``: compared there (moorline's records linearly interpolated).
    Measured: 1.2e-6 (mean-load), 1.5e-6 (constant) and 1.7e-6 (ratio) of the tension;
    without the half-step shift the difference reaches 2.9e-2 early and 1.6e-3 after 5 s and
    halves with dt (MoorDyn's lag). Tolerance 1e-5 for the second-order errors of both
    schemes and of the interpolation (about 1e-6 each at 500 steps per period). The first
    0.5 s are left out: the first record pairs MoorDyn's first step with moorline's t = 0,
    and with the ratio the branch time constant (c1 + c2) / (k1 + k2) = 7 ms is below
    MoorDyn's explicit step (7.9e-4 there, 1.7e-6 from 0.5 s on)."""
    pytest.importorskip("moordyn")
    # a copy: MoorDyn writes its OUTPUTS (moordyn.out) next to the deck
    deck = _deck(tmp_path, *(pair or ("1.424e+08|1.586e+08|0.4", "4E9|11E6")))
    dt, duration, w = 0.01, 20.0, 2 * math.pi / 5.0

    def x(t: float) -> float:
        return 1.0 + t / (t + 2.0) * (0.1 + 0.02 * math.sin(w * t))

    theirs = _moordyn_tension(deck, dt, duration, x)
    t_ours, ours = _moorline_tension(deck, dt, duration, x)
    t_theirs = dt * np.arange(1, len(theirs) + 1)
    ours_mid = np.interp(t_theirs - 0.5 * dt, t_ours, ours)
    keep = t_theirs >= 0.5
    assert theirs.min() > 1e5  # taut throughout (no slack rule involved)
    np.testing.assert_allclose(ours_mid[keep], theirs[keep], rtol=1e-5)


def test_deck_round_trip(tmp_path):
    """:func:`~moorline.io.moordyn.write_moordyn` writes the static-dynamic line type back as
    MoorDyn's ``EA_s|EA_Dc|EA_D_Lm`` and ``BA_s|BA_d``: read again, the same line type."""
    from moorline.io.moordyn import write_moordyn

    system = read_moordyn(DECK)
    path = tmp_path / "back.dat"
    write_moordyn(system, path, 0.01)
    assert read_moordyn(path).line_types["rope"] == system.line_types["rope"]


CASE = """
name: rope
units: SI
environment: {{depth: 100}}
line_types:
  rope: {{diameter: 0.14, mass_per_length: 22.4, EA: 1.424e8, material: static_dynamic,
         {extra}}}
points:
  anchor: {{kind: fixed, position: [0, 0, -100]}}
  top: {{kind: prescribed, position: [0, 0, -1]}}
lines:
  l1: {{type: rope, length: 98, segments: 4, end_a: anchor, end_b: top}}
analyses:
  - {{kind: {kind}}}
"""


@pytest.mark.parametrize(("extra", "kind", "field", "named"), [
    ("BA: 4.0e9", "statics", "line_types.rope.EAd", "needs EAd"),
    ("EAd: 1.0e8, BA: 4.0e9", "statics", "line_types.rope.EAd", "needs EAd > EA"),
    ("EAd: 1.586e8, EAd_Lm: 0.4", "statics", "line_types.rope.BA", "damping in a branch"),
    ("EAd: 1.586e8, BA: 4.0e9", "modal", "analyses[0].kind", "no modal analysis"),
])
def test_bad_static_dynamic_cases_are_refused(extra, kind, field, named):
    """A case's static_dynamic line type without what the law needs, or with an analysis
    that would linearize it: a CaseError naming the key."""
    from moorline.io import load_case_text

    with pytest.raises(CaseError) as info:
        load_case_text(CASE.format(extra=extra, kind=kind), file="rope.yaml")
    assert info.value.field == field and named in info.value.reason


def test_good_static_dynamic_case_loads():
    """The same case with EAd above EA and a damping: loads, the law's parameters kept."""
    from moorline.io import load_case_text

    system = load_case_text(CASE.format(extra="EAd: 1.586e8, EAd_Lm: 0.4, BA: 4.0e9, "
                                        "BA_dynamic: 1.1e7", kind="statics"))
    lt = system.line_types["rope"]
    assert (lt.EAd, lt.EAd_Lm, lt.BA, lt.BA_dynamic) == (ALPHA, BETA, C1, C2)


@pytest.mark.compare
def test_taut_line_with_mass_against_moordyn(tmp_path):
    """The deck's rope as a 50 m line of 5 segments with its mass (no gravity, no fluid, so
    both codes start relaxed on the straight unstretched line), its end pulled to 10 % strain
    with a 2 % oscillation of period 5 s: the top segment's tension (MoorDyn's ``FairTen``,
    half a MoorDyn step, 5e-5 s, back as in :func:`test_md_viscoelastic_against_moordyn`)
    with moorline's implicit step of 0.01 s against MoorDyn's explicit RK2 at 1e-4 s (its
    stability limit with the dashpots is about 4e-4 s; at 5e-4 s it diverges). After 5 s
    they differ by 1.9e-4 of the tension (7.6e-5 with moorline at 0.0025 s): the axial modes
    (period about 0.04 s) that the start excites are resolved by MoorDyn and filtered by
    moorline's step; tolerance 5e-4."""
    pytest.importorskip("moordyn")
    from moorline.io.moordyn import write_moordyn
    from moorline.model import Line, Point, System

    deck = read_moordyn(DECK)
    rope = replace(deck.line_types["rope"], Cd=0.0, Ca=0.0, Ct=0.0, Cat=0.0)
    length, n_seg, dt, duration, w = 50.0, 5, 0.01, 20.0, 2 * math.pi / 5.0

    def x(t: float) -> float:
        return length + t / (t + 2.0) * (5.0 + 1.0 * math.sin(w * t))

    times = dt * np.arange(round(duration / dt) + 1)
    motion = Motion(kind="table", times=tuple(times),
                    values=tuple((x(t) - length, 0.0, 0.0) for t in times))
    points = {"a": Point("a", "fixed", (0.0, 0.0, -50.0)),
              "b": Point("b", "prescribed", (length, 0.0, -50.0), motion=motion)}
    system = System("taut", environment=replace(deck.environment, gravity=0.0),
                    line_types={"rope": rope}, points=points,
                    lines={"l": Line("l", "rope", length, n_seg, "a", "b")})
    start = np.array([[0.0, 0.0, -50.0], [length, 0.0, -50.0]]
                     + [[length * i / n_seg, 0.0, -50.0] for i in range(1, n_seg)])
    run = simulate(system, DynamicsSettings(duration=duration, dt=dt), initial=start,
                   output_every=dt)
    assert run.success, run.message
    path = write_moordyn(system, tmp_path / "taut.dat", 1.0e-4)
    theirs = moordyn_fair_tensions(path, x, -50.0, times[:-1], dt)
    t_theirs = times[1:]
    ours = np.interp(t_theirs - 0.5e-4, run.time, run.tension[:, -1])
    keep = t_theirs >= 5.0
    np.testing.assert_allclose(ours[keep], np.array(theirs)[keep], rtol=5e-4)


@pytest.mark.parametrize("analysis", ["modal", "stochastic", "strumming", "harmonic"])
def test_linearized_analyses_refuse_the_law_through_the_api(analysis):
    """The Python API refuses a linearized analysis of a static_dynamic rope as the case file
    does (it used to linearize with the static stiffness without a word)."""
    from moorline.io import load_case_text
    from moorline.model import HarmonicSettings, ModalSettings, StrummingSettings
    from moorline.solvers.harmonic import solve_harmonic
    from moorline.solvers.modal import solve_modes
    from moorline.solvers.stochastic import solve_stochastic
    from moorline.solvers.strumming import solve_strumming

    system = load_case_text(CASE.format(extra="EAd: 1.586e8, EAd_Lm: 0.4, BA: 4.0e9",
                                        kind="statics"))
    call = {"modal": lambda: solve_modes(system, ModalSettings()),
            "stochastic": lambda: solve_stochastic(system),
            "strumming": lambda: solve_strumming(system, StrummingSettings(), None),
            "harmonic": lambda: solve_harmonic(system, HarmonicSettings(period=10.0))}
    with pytest.raises(CaseError) as info:
        call[analysis]()
    assert info.value.field == "line_types.rope.material"
    assert f"no {analysis} analysis" in info.value.reason
