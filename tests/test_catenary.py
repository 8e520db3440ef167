"""Tests of :mod:`moorline.catenary` against independent references.

References used:

* direct numerical integration (scipy ``solve_ivp``, DOP853, rtol 1e-12) of the elastic
  catenary equations ``dx/ds = (H/T)(1 + T/EA)``, ``dz/ds = (V/T)(1 + T/EA)`` with
  ``V(s) = V_b - w (L - s)``, started at A (or at touchdown, after the lying part whose
  stretch is the area under its linear friction tension profile); it must land on B to
  ``1e-8 L``;
* Tcheou (1997) eqs. 3.24 / 3.27 coded literally (``ln(x + sqrt(1 + x^2))``) and the
  Table 5.1 basis case;
* the OC3-Hywind mooring line: MoorPy 1.3.0 ``catenary()`` numbers and the system values
  published in Jonkman (2010), NREL/TP-500-47535;
* closed forms derived by hand for vertical, slack, flat and weightless lines.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from moorline.catenary import (
    CatenaryError,
    catenary_3d,
    hanging_from_forces,
    profile_3d,
    solve_catenary,
)
from moorline.errors import MoorlineError

LAND_TOL = 1e-8  # ODE landing tolerance, relative to the line length
OC3_W = (77.7066 - 1025.0 * math.pi * 0.09**2 / 4.0) * 9.80665
OC3 = dict(horizontal_span=853.87 - 5.2, vertical_span=320.0 - 70.0, length=902.2,
           EA=384.243e6, weight=OC3_W)


# ----------------------------------------------------------------------------- helpers
def _inv(EA):
    return 0.0 if math.isinf(EA) else 1.0 / EA


def _lying_end(sol):
    """Horizontal extent of the lying part: L_B + (area under T(s)) / EA, T linear."""
    lb, H, Ha, mu, w = (sol.seabed_length, sol.H, sol.H_a, sol.seabed_friction, sol.weight)
    if lb == 0.0:
        return 0.0
    if H == 0.0:  # slack: the surplus length piles up on the seabed under A..B
        assert lb >= sol.horizontal_span
        return sol.horizontal_span
    assert Ha == pytest.approx(max(H - mu * w * lb, 0.0), rel=1e-12, abs=1e-12 * H)
    area = 0.5 * lb * (H + Ha) if (Ha > 0.0 or mu == 0.0) else H * H / (2.0 * mu * w)
    return lb + area * _inv(sol.EA)


def _integrate(sol, sigma=(1.0,)):
    """Integrate the suspended part; positions at fractions ``sigma`` of it, shape (2, n)."""
    L, lb, H, w = sol.length, sol.seabed_length, sol.H, sol.weight
    ls, inv = L - lb, _inv(sol.EA)
    v0 = sol.V_b - w * ls

    def rhs(s, y):
        v = v0 + w * s
        if H == 0.0:  # vertical: dz/ds = sign(V) (1 + |V| / EA)
            return [0.0, (math.copysign(1.0, w) if v == 0.0 else np.sign(v)) / L + v * inv / L]
        f = 1.0 / math.hypot(H, v) + inv
        return [H * f / L, v * f / L]

    # split where V changes sign (a fold), where dx/ds peaks sharply when H is small
    brk = sorted({0.0, ls, *([-v0 / w] if w != 0.0 and 0.0 < -v0 / w < ls else [])})
    y, out, targets = [_lying_end(sol) / L, 0.0], {}, [ls * f for f in sigma]
    for s0, s1 in zip(brk[:-1], brk[1:], strict=True):
        ev = sorted({s1, *(t for t in targets if s0 <= t <= s1)})
        r = solve_ivp(rhs, (s0, s1), y, method="DOP853", rtol=1e-12, atol=1e-15, t_eval=ev)
        assert r.success, r.message
        out.update({t: r.y[:, i] * L for i, t in enumerate(ev)})
        y = r.y[:, -1]
    return np.array([out[t] for t in targets]).T


def _assert_lands(sol):
    X, Z, L = sol.horizontal_span, sol.vertical_span, sol.length
    sig = np.linspace(0.0, 1.0, 6)
    ref = _integrate(sol, sig)
    assert ref[0, -1] == pytest.approx(X, abs=LAND_TOL * L)
    assert ref[1, -1] == pytest.approx(Z, abs=LAND_TOL * L)
    h, z = sol.profile(sol.seabed_length + sig * (L - sol.seabed_length))
    np.testing.assert_allclose(h, ref[0], rtol=0, atol=LAND_TOL * L)
    np.testing.assert_allclose(z, ref[1], rtol=0, atol=LAND_TOL * L)
    s = sol.seabed_length + sig * (L - sol.seabed_length)
    v = sol.V_b - sol.weight * (L - s)
    np.testing.assert_allclose(sol.tension(s), np.hypot(sol.H, v), rtol=1e-12,
                               atol=1e-12 * max(sol.tension_b, abs(sol.V_a)))
    # equilibrium of the whole line: end forces, weight, seabed normal force and friction
    (fah, faz), (fbh, fbz) = sol.force_a, sol.force_b
    w, lb = sol.weight, sol.seabed_length
    scale = max(sol.tension_a, sol.tension_b, abs(w) * L)
    assert -fah - fbh - (sol.H - sol.H_a) == pytest.approx(0.0, abs=1e-12 * scale)
    assert -faz - fbz - w * (L - lb) == pytest.approx(0.0, abs=1e-9 * scale)
    assert sol.H >= 0.0 and sol.H_a >= 0.0 and sol.seabed_length >= 0.0


def _random_geometries(n, seed):
    rng = np.random.default_rng(seed)
    cases = []
    for _ in range(n):
        L = 10 ** rng.uniform(0.5, 3.3)
        w = (-1.0 if rng.random() < 0.2 else 1.0) * 10 ** rng.uniform(0.0, 3.0)
        EA = math.inf if rng.random() < 0.1 else abs(w) * L * 10 ** rng.uniform(1.0, 7.0)
        u = rng.random()
        if u < 0.2:
            r = 1.0 - 10 ** rng.uniform(-6.0, -2.0)  # nearly taut
        elif u < 0.3 and not math.isinf(EA):
            r = 1.0 + 10 ** rng.uniform(-6.0, -2.0)  # stretched
        else:
            r = rng.uniform(0.2, 0.999)
        th = rng.uniform(-0.5 * math.pi + 0.05, 0.5 * math.pi - 0.05)
        mu = 0.0 if rng.random() < 0.4 else rng.uniform(0.0, 1.5)
        cases.append((r * L * math.cos(th), r * L * math.sin(th), L, EA, w, mu,
                       bool(rng.random() < 0.7)))
    return cases


# ----------------------------------------------------------------------------- ODE checks
@pytest.mark.parametrize("seed", [1, 2, 3])
def test_random_geometries_land_on_b(seed):
    """~250 random feasible geometries: the integrated line lands on B to 1e-8 L."""
    for X, Z, L, EA, w, mu, contact in _random_geometries(80, seed):
        sol = solve_catenary(X, Z, L, EA, w, seabed_friction=mu, seabed_contact=contact)
        _assert_lands(sol)


HARD = {
    "nearly_taut_inextensible": (600.0, 300.0, math.hypot(600, 300) * (1 + 1e-9), math.inf,
                                 100.0, 0.0, True),
    "nearly_taut_elastic": (600.0, 300.0, math.hypot(600, 300) * (1 + 1e-9), 1e9, 100.0,
                            0.0, True),
    "stretched": (990.0, 141.0, 990.0, 1e8, 300.0, 0.0, True),
    "stretched_near_vertical": (1.0, 100.0, 99.0, 1e7, 50.0, 0.0, True),
    "very_slack_on_seabed": (100.0, 50.0, 1000.0, 1e9, 500.0, 0.0, True),
    "just_off_slack_on_seabed": (50.0 * (1 + 1e-6), 50.0, 100.0, math.inf, 10.0, 0.3, True),
    "friction_anchor_loaded": (848.67, 250.0, 902.2, 384.243e6, OC3_W, 0.5, True),
    "friction_anchor_slack": (700.0, 250.0, 902.2, 384.243e6, OC3_W, 1.0, True),
    "b_below_a": (400.0, -200.0, 500.0, 1e8, 100.0, 0.8, True),
    "buoyant_up": (300.0, 200.0, 450.0, 1e7, -50.0, 0.0, True),
    "buoyant_down": (300.0, -200.0, 450.0, 1e7, -50.0, 0.0, True),
    "hanging_fold_no_seabed": (1e-3, 10.0, 100.0, 1e6, 20.0, 0.0, False),
    "sagging_below_a_no_seabed": (100.0, 10.0, 300.0, math.inf, 20.0, 0.0, False),
    "weightless_taut": (3.0, 4.0, 4.9, 100.0, 0.0, 0.0, True),
    "tiny_weight": (80.0, 20.0, 100.0, 1e5, 1e-6, 0.0, True),
    "heavy_stiff": (500.0, 300.0, 700.0, 1e12, 5000.0, 0.2, True),
    "nearly_vertical_slack": (1e-4, 300.0, 302.0, 1e9, 100.0, 0.0, False),
    "slack_piled_on_seabed": (10.0, 300.0, 400.0, 1e9, 100.0, 0.5, True),
}


@pytest.mark.parametrize("case", HARD.values(), ids=HARD.keys())
def test_hard_geometries_land_on_b(case):
    X, Z, L, EA, w, mu, contact = case
    _assert_lands(solve_catenary(X, Z, L, EA, w, seabed_friction=mu, seabed_contact=contact))


@pytest.mark.parametrize("case", HARD.values(), ids=HARD.keys())
def test_bracketed_fallback_agrees(case):
    """max_iter=0 forces the bracketed fallback; it must give the same line."""
    X, Z, L, EA, w, mu, contact = case
    kw = dict(seabed_friction=mu, seabed_contact=contact)
    ref = solve_catenary(X, Z, L, EA, w, **kw)
    sol = solve_catenary(X, Z, L, EA, w, max_iter=0, **kw)
    _assert_lands(sol)
    scale = max(ref.tension_b, abs(w) * L)
    assert sol.H == pytest.approx(ref.H, abs=1e-8 * scale)
    assert sol.V_b == pytest.approx(ref.V_b, abs=1e-8 * scale)


# ----------------------------------------------------------------------------- Tcheou 1997
def _tcheou_327(H, V, L, EA, w):
    """Tcheou (1997) eq. 3.27 at s = L, written as printed (ln(x + sqrt(1 + x^2)))."""
    def asinh_(x):
        return math.log(x + math.sqrt(1.0 + x * x))

    lo, hi = (V - w * L) / H, V / H
    x = H / w * (asinh_(hi) - asinh_(lo)) + H * L / EA
    z = H / w * (math.sqrt(1 + hi * hi) - math.sqrt(1 + lo * lo)) + (V * L - w * L * L / 2) / EA
    return x, z


@pytest.mark.parametrize("rho_s", [7000.0, 2000.0], ids=["steel", "synthetic"])
def test_tcheou_table_5_1_round_trip(rho_s):
    """Tcheou Table 5.1 basis case: forward eq. 3.27, then the inverse returns (H, V)."""
    H, V, L, E, A_s, rho_f, A_f, g = 4000.0, 8000.0, 600.0, 1e9, 2e-4, 1000.0, 2e-4, 9.81
    w, EA = (rho_s * A_s - rho_f * A_f) * g, E * A_s  # eq. 3.26
    X, Z = hanging_from_forces(H, V, L, EA, w)
    xr, zr = _tcheou_327(H, V, L, EA, w)
    assert X == pytest.approx(xr, rel=1e-12) and Z == pytest.approx(zr, rel=1e-12)
    sol = solve_catenary(X, Z, L, EA, w, seabed_contact=False)
    assert sol.H == pytest.approx(H, rel=1e-9)
    assert sol.V_b == pytest.approx(V, rel=1e-9)
    assert sol.V_a == pytest.approx(V - w * L, rel=1e-9)
    _assert_lands(sol)
    # tension along the line, Tcheou eq. 3.25
    s = np.linspace(0.0, L, 7)
    np.testing.assert_allclose(sol.tension(s), np.hypot(H, V - w * (L - s)), rtol=1e-9)


def test_tcheou_inelastic_eq_3_24():
    """EA = inf reduces to eq. 3.24 (its OCR drops brackets inside the roots; fixed here)."""
    X, Z = hanging_from_forces(4000.0, 8000.0, 600.0, math.inf, 11.772)
    xr, zr = _tcheou_327(4000.0, 8000.0, 600.0, math.inf, 11.772)
    assert X == pytest.approx(xr, rel=1e-12) and Z == pytest.approx(zr, rel=1e-12)


# ----------------------------------------------------------------------------- OC3-Hywind
def test_oc3_hywind_line():
    """OC3-Hywind line vs MoorPy 1.3.0 and the published system values (Jonkman 2010)."""
    sol = solve_catenary(**OC3)
    # MoorPy 1.3.0 catenary(848.67, 250, 902.2, 384.243e6, w, CB=0, Tol=1e-12)
    assert sol.H == pytest.approx(736938.8513934169, rel=1e-9)
    assert sol.V_b == pytest.approx(535727.8495310353, rel=1e-9)
    assert sol.seabed_length == pytest.approx(134.7855293206834, rel=1e-8)
    assert sol.tension_b == pytest.approx(9.11e5, rel=0.01)
    # NREL/TP-500-47535: total vertical mooring preload 1,607 kN (3 lines), linearized
    # mooring stiffness K11 = 41,180 N/m and K33 = 11,940 N/m
    assert 3.0 * sol.V_b == pytest.approx(1.607e6, rel=1e-3)
    e, X, Z = 1e-3, OC3["horizontal_span"], OC3["vertical_span"]
    kw = {k: v for k, v in OC3.items() if k not in ("horizontal_span", "vertical_span")}
    dhdx = (solve_catenary(X + e, Z, **kw).H - solve_catenary(X - e, Z, **kw).H) / (2 * e)
    dvdz = (solve_catenary(X, Z + e, **kw).V_b - solve_catenary(X, Z - e, **kw).V_b) / (2 * e)
    assert 1.5 * (dhdx + sol.H / X) == pytest.approx(41180.0, rel=1e-3)
    assert 3.0 * dvdz == pytest.approx(11940.0, rel=1e-3)
    h, z = sol.profile(np.array([0.0, sol.seabed_length, OC3["length"]]))
    assert z[1] == 0.0 and h[2] == pytest.approx(X, abs=1e-8) and z[2] == pytest.approx(Z)
    _assert_lands(sol)


@pytest.mark.compare
@pytest.mark.parametrize("X, Z, mu", [(848.67, 250.0, 0.0), (848.67, 250.0, 0.5),
                                      (700.0, 250.0, 1.0), (880.0, 250.0, 0.0)])
def test_against_moorpy(X, Z, mu):
    cat = pytest.importorskip("moorpy.Catenary")
    fah, fav, fbh, fbv, info = cat.catenary(X, Z, 902.2, 384.243e6, OC3_W, CB=mu, Tol=1e-12,
                                            MaxIter=200)
    sol = solve_catenary(X, Z, 902.2, 384.243e6, OC3_W, seabed_friction=mu)
    tol = 1e-7 * sol.tension_b
    assert sol.force_a == pytest.approx((fah, fav), abs=tol)
    assert sol.force_b == pytest.approx((fbh, fbv), abs=tol)
    assert sol.seabed_length == pytest.approx(info["LBot"], abs=1e-6)


# ----------------------------------------------------------------------------- closed forms
def test_vertical_taut_line():
    # Z = L + (V_a L + w L^2 / 2) / EA  ->  V_a = 9500
    sol = solve_catenary(0.0, 110.0, 100.0, 1e5, 10.0, seabed_contact=False)
    assert (sol.H, sol.V_a, sol.V_b) == pytest.approx((0.0, 9500.0, 10500.0), rel=1e-12)
    assert sol.profile(np.array([100.0]))[1][0] == pytest.approx(110.0, rel=1e-12)


def test_vertical_folded_line():
    # inextensible, ends on one vertical: goes down 25 and up 75
    sol = solve_catenary(0.0, 50.0, 100.0, math.inf, 10.0, seabed_contact=False)
    assert (sol.H, sol.V_a, sol.V_b) == pytest.approx((0.0, -250.0, 750.0), rel=1e-12)
    h, z = sol.profile(np.array([0.0, 25.0, 100.0]))
    np.testing.assert_allclose(z, [0.0, -25.0, 50.0], atol=1e-12)
    np.testing.assert_allclose(h, 0.0, atol=0.0)
    near = solve_catenary(1e-9, 50.0, 100.0, math.inf, 10.0, seabed_contact=False)
    assert near.V_b == pytest.approx(750.0, rel=1e-6)


@pytest.mark.parametrize("X", [0.0, 20.0, 50.0])
def test_slack_line_on_seabed(X):
    # hangs vertically over 50, the rest (50) lies on the seabed with zero tension
    sol = solve_catenary(X, 50.0, 100.0, math.inf, 10.0, seabed_friction=0.4)
    assert (sol.H, sol.H_a, sol.V_a, sol.V_b) == pytest.approx((0.0, 0.0, 0.0, 500.0))
    assert sol.seabed_length == pytest.approx(50.0, rel=1e-12)
    h, z = sol.profile(np.array([0.0, 50.0, 75.0, 100.0]))
    np.testing.assert_allclose(h, [0.0, X, X, X], atol=1e-12)
    np.testing.assert_allclose(z, [0.0, 0.0, 25.0, 50.0], atol=1e-12)
    np.testing.assert_allclose(sol.tension(np.array([10.0, 75.0])), [0.0, 250.0])


@pytest.mark.parametrize("mu, H, Ha", [(0.0, 100.0, 100.0), (0.5, math.sqrt(1e5), 0.0),
                                       (0.01, (1e4 + 0.5 * 0.01 * 10 * 1e4) / 100, 95.0)])
def test_flat_line_stretched_on_seabed(mu, H, Ha):
    # X - L = (area under T) / EA with T rising from H_a to H
    sol = solve_catenary(100.1, 0.0, 100.0, 1e5, 10.0, seabed_friction=mu)
    assert (sol.H, sol.H_a, sol.V_b, sol.seabed_length) == pytest.approx((H, Ha, 0.0, 100.0))
    assert sol.profile(np.array([100.0]))[0][0] == pytest.approx(100.1, rel=1e-12)


def test_weightless_lines():
    sol = solve_catenary(3.0, 4.0, 4.9, 100.0, 0.0)
    t = 100.0 * (5.0 / 4.9 - 1.0)
    assert (sol.H, sol.V_a, sol.V_b) == pytest.approx((0.6 * t, 0.8 * t, 0.8 * t))
    slack = solve_catenary(3.0, 4.0, 6.0, 100.0, 0.0)
    assert (slack.H, slack.V_b, slack.tension_a) == (0.0, 0.0, 0.0)
    np.testing.assert_allclose(np.stack(slack.profile(np.array([6.0]))).ravel(), [3.0, 4.0])


def test_buoyant_line_mirrors_heavy_line():
    up = solve_catenary(300.0, 200.0, 450.0, 1e7, -50.0)
    down = solve_catenary(300.0, -200.0, 450.0, 1e7, 50.0)
    assert (up.H, up.V_a, up.V_b) == pytest.approx((down.H, -down.V_a, -down.V_b), rel=1e-12)
    assert up.seabed_length == 0.0


# ----------------------------------------------------------------------------- 3-D
def test_catenary_3d_and_profile():
    pa, ang = np.array([10.0, 20.0, -320.0]), math.radians(30.0)
    pb = pa + np.array([848.67 * math.cos(ang), 848.67 * math.sin(ang), 250.0])
    fa, fb, sol = catenary_3d(pa, pb, 902.2, 384.243e6, OC3_W, seabed_friction=0.5)
    e = np.array([math.cos(ang), math.sin(ang)])
    np.testing.assert_allclose(fb, [*(-sol.H * e), -sol.V_b], rtol=1e-14)
    np.testing.assert_allclose(fa, [*(sol.H_a * e), sol.V_a], rtol=1e-14)
    pts = profile_3d(sol, pa, pb, np.linspace(0.0, 902.2, 11))
    assert pts.shape == (11, 3)
    np.testing.assert_allclose(pts[0], pa, atol=1e-12)
    np.testing.assert_allclose(pts[-1], pb, atol=1e-8)


def test_catenary_3d_vertical():
    fa, fb, sol = catenary_3d([1.0, 2.0, -100.0], [1.0, 2.0, 10.0], 100.0, 1e5, 10.0,
                              seabed_contact=False)
    assert np.all(np.isfinite(fa)) and np.all(np.isfinite(fb))
    np.testing.assert_allclose(fb, [0.0, 0.0, -10500.0], rtol=1e-12)
    np.testing.assert_allclose(profile_3d(sol, [1, 2, -100], [1, 2, 10], [100.0]),
                               [[1.0, 2.0, 10.0]], atol=1e-10)


# ----------------------------------------------------------------------------- errors
@pytest.mark.parametrize("args, words", [
    ((500.0, 0.0, 100.0, 1e9, 10.0), ["500", "100", "0.5"]),
    ((100.0, 0.0, 100.0, math.inf, 10.0), ["inf", "100"]),
    ((10.0, 0.0, 0.0, 1e9, 10.0), ["length", "0"]),
    ((10.0, 0.0, -3.0, 1e9, 10.0), ["-3"]),
    ((10.0, 0.0, 20.0, -5.0, 10.0), ["EA", "-5"]),
    ((-1.0, 0.0, 20.0, 1e9, 10.0), ["-1"]),
    ((0.0, 100.0, 100.0, 1e5, 1e4), ["strain", "100"]),
])
def test_infeasible_input_raises_with_numbers(args, words):
    with pytest.raises(CatenaryError) as err:
        solve_catenary(*args)
    assert isinstance(err.value, MoorlineError)
    for word in words:
        assert word in str(err.value)


def test_hanging_from_forces_rejects_bad_input():
    with pytest.raises(CatenaryError, match="-1"):
        hanging_from_forces(-1.0, 10.0, 100.0, 1e6, 1.0)


