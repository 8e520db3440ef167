"""Tests of the exact reference solutions in :mod:`moorline.verification.references`.

Each reference is checked against something derived independently of it: asymptotic
closed forms, the classical single-catenary relation, and direct numerical integration
of the equilibrium ODE.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.integrate
import scipy.optimize

from moorline.verification.references import (
    G_FT,
    TwoSegmentSolution,
    pin_jointed_string_deflection,
    pin_jointed_string_load,
    pin_jointed_string_tension,
    tuah_ex2_reference,
    two_segment_catenary,
)

# Tuah (1982) sec. 6.1 data: E = 1e7 psf, A0 = 0.1 ft^2, sigma0 = 500 psf; span 20 ft assumed.
EA1 = 1.0e7 * 0.1
T01 = 500.0 * 0.1
SPAN1 = 20.0
A1 = SPAN1 / 2.0

# Tuah (1982) sec. 6.2 data.
W2 = (3.35 - 2.0) * 0.0218 * G_FT
EA2 = 8.12e6 * 0.0218


# ---------------------------------------------------------------------------
# pin-jointed string (Example 1)
# ---------------------------------------------------------------------------


def test_string_small_load_matches_linear_taut_string() -> None:
    # P = 2 T0 u + EA u^3 + O(EA u^5): with u_lin = P/(2 T0) the first correction to
    # d = P a/(2 T0) is -EA u_lin^2/(2 T0) relative, 2.5e-5 at P/T0 = 1e-4 with the Tuah
    # data. The linear formula must hold to 3x that, and the computed relative deviation
    # must equal the predicted correction to 0.1 % of itself (the next term is about
    # 3 * correction = 7.5e-5 relative to it).
    P = 1e-4 * T01
    d = pin_jointed_string_deflection(P, SPAN1, EA1, T01)
    d_lin = P * A1 / (2.0 * T01)
    u_lin = d_lin / A1
    correction = EA1 * u_lin**2 / (2.0 * T01)
    assert correction == pytest.approx(2.5e-5, rel=1e-12)
    assert d == pytest.approx(d_lin, rel=3.0 * correction)
    assert (d_lin - d) / d_lin == pytest.approx(correction, rel=1e-3)


def test_string_zero_pretension_matches_cubic_law() -> None:
    # T0 = 0: P = 2 u EA (1 - 1/sqrt(1+u^2)) = EA u^3 (1 - 3u^2/4 + O(u^4)), so
    # d = a (P/EA)^(1/3) (1 + u^2/4 + O(u^4)). At P/EA = 1e-9 (u ~ 1e-3) the cubic law holds
    # to 2.5e-7 relative. Carrying the expansion one order further (P/EA = u^3 (1 - 3u^2/4
    # + 5u^4/8 - ...)) gives d/d_cubic = 1 + u^2/4 + u^4/24 + O(u^6), which the exact
    # solution must match to O(u^6) plus round-off (1e-13).
    for p_over_ea in (1e-9, 1e-6):
        P = p_over_ea * EA1
        d = pin_jointed_string_deflection(P, SPAN1, EA1, 0.0)
        d_cubic = A1 * p_over_ea ** (1.0 / 3.0)
        u = d_cubic / A1
        assert d / d_cubic - 1.0 == pytest.approx(u**2 / 4.0 + u**4 / 24.0, abs=u**6 + 1e-13)


def test_string_small_strain_cubic_form() -> None:
    # Small-strain form 2 T0 u + EA u^3 = P (both terms of the same order here), solved
    # by numpy's polynomial roots; the exact answer differs by O(u^2) relative.
    for P in (0.05, 0.5, 5.0):
        d = pin_jointed_string_deflection(P, SPAN1, EA1, T01)
        roots = np.roots([EA1, 0.0, 2.0 * T01, -P])
        u_ss = float(next(r.real for r in roots if abs(r.imag) < 1e-12 and r.real > 0))
        assert d / A1 == pytest.approx(u_ss, rel=2.0 * u_ss**2)


@pytest.mark.parametrize("pretension", [0.0, 1e-3, T01, 1e5])
@pytest.mark.parametrize("load", [1e-8, 1e-3, 1.0, 50.0, 1e3, 1e6, 1e9])
def test_string_round_trip(load: float, pretension: float) -> None:
    d = pin_jointed_string_deflection(load, SPAN1, EA1, pretension)
    assert pin_jointed_string_load(d, SPAN1, EA1, pretension) == pytest.approx(load, rel=1e-12)
    assert pin_jointed_string_deflection(
        pin_jointed_string_load(d, SPAN1, EA1, pretension), SPAN1, EA1, pretension
    ) == pytest.approx(d, rel=1e-12)
    # odd in the load
    assert pin_jointed_string_deflection(-load, SPAN1, EA1, pretension) == -d


def test_string_tension_and_equilibrium() -> None:
    # Direct check of the two-bar geometry for one state: T from the stretched length
    # of an unstretched half L0/2, and P = 2 T d / l.
    d = 2.0
    L0 = SPAN1 / (1.0 + T01 / EA1)
    ell = math.hypot(A1, d)
    T = EA1 * (ell / (L0 / 2.0) - 1.0)
    assert pin_jointed_string_tension(d, SPAN1, EA1, T01) == pytest.approx(T, rel=1e-12)
    assert pin_jointed_string_load(d, SPAN1, EA1, T01) == pytest.approx(2 * T * d / ell, rel=1e-12)
    assert pin_jointed_string_tension(0.0, SPAN1, EA1, T01) == T01


def test_string_slack_limit() -> None:
    # T0 = 0, P = 0: straight, just taut; unique answer d = 0 (zero tangent stiffness).
    assert pin_jointed_string_deflection(0.0, SPAN1, EA1, 0.0) == 0.0
    assert pin_jointed_string_load(0.0, SPAN1, EA1, 0.0) == 0.0
    with pytest.raises(ValueError):
        pin_jointed_string_deflection(1.0, SPAN1, EA1, -1.0)


# ---------------------------------------------------------------------------
# two-segment catenary (Example 2)
# ---------------------------------------------------------------------------


def _single_catenary(X: float, Z: float, L: float, w: float) -> tuple[float, float]:
    """Classical inextensible catenary: (H, V_a) from sqrt(L^2-Z^2) = 2 (H/w) sinh(wX/(2H)).

    With y = w X/(2H) the relation is sinh(y)/y = sqrt(L^2 - Z^2)/X, solved by brentq; then
    with m = atanh(Z/L) the parameter at A is m - y and V_a = H sinh(m - y).
    """
    ratio = math.sqrt(L * L - Z * Z) / X
    y = scipy.optimize.brentq(lambda t: math.sinh(t) / t - ratio, 1e-8, 700.0, xtol=1e-15)
    H = w * X / (2.0 * y)
    return H, H * math.sinh(math.atanh(Z / L) - y)


@pytest.mark.parametrize(
    ("point_b", "lengths"),
    [
        ((1200.0, 500.0), (500.0, 1000.0)),  # Tuah geometry without the buoy
        ((1200.0, 500.0), (1000.0, 500.0)),
        ((300.0, -200.0), (150.0, 350.0)),  # B below A, deep sag
        ((99.0, 1.0), (60.0, 40.0)),  # nearly taut
    ],
)
def test_zero_junction_force_is_single_catenary(
    point_b: tuple[float, float], lengths: tuple[float, float]
) -> None:
    sol = two_segment_catenary((0.0, 0.0), point_b, lengths, W2, 0.0)
    H, Va = _single_catenary(point_b[0], point_b[1], sum(lengths), W2)
    assert sol.H == pytest.approx(H, rel=1e-10)
    assert sol.V_a == pytest.approx(Va, rel=1e-10, abs=1e-10 * H)


def _rhs_two_segment(s: float, y: np.ndarray, H: float, V0: float, s0: float, w: float,
                     EA: float) -> list[float]:
    """Elastic cable equilibrium: dx/ds = (1+T/EA) H/T, dz/ds = (1+T/EA) V/T, V = V0 + w(s-s0)."""
    V = V0 + w * (s - s0)
    T = math.hypot(H, V)
    stretch = 1.0 + T / EA
    return [stretch * H / T, stretch * V / T]


def _integrate(sol: TwoSegmentSolution) -> tuple[np.ndarray, np.ndarray, list]:
    """Integrate dx/ds = (1+T/EA) H/T, dz/ds = (1+T/EA) V/T from A, segment by segment."""
    H, w, EA, P = sol.H, sol.weight, sol.EA, sol.junction_force
    L1, L2 = sol.lengths
    pieces = []

    y0 = np.array(sol.point_a, dtype=float)
    out = []
    for s0, s1, V0 in ((0.0, L1, sol.V_a), (L1, L1 + L2, sol.V_a + w * L1 - P)):
        r = scipy.integrate.solve_ivp(
            _rhs_two_segment,
            (s0, s1),
            y0,
            method="DOP853",
            rtol=1e-13,
            atol=1e-12,
            args=(H, V0, s0, w, EA),
            dense_output=True,
        )
        assert r.success
        y0 = r.y[:, -1]
        out.append(y0.copy())
        pieces.append(r)
    return out[0], out[1], pieces


@pytest.mark.parametrize(
    ("point_b", "lengths", "P", "EA"),
    [
        ((1200.0, 500.0), (500.0, 1000.0), 900.0, math.inf),  # Tuah Ex2
        ((1200.0, 500.0), (500.0, 1000.0), 900.0, EA2),  # Tuah Ex2, elastic
        ((1200.0, 500.0), (500.0, 1000.0), 2500.0, math.inf),  # buoy lifts more than the weight
        ((1200.0, -300.0), (900.0, 600.0), 2500.0, EA2),  # B below A, buoy > weight
        ((800.0, 100.0), (700.0, 500.0), -400.0, math.inf),  # clump weight, sag in both
        ((1000.0, 0.0), (500.0, 500.0), 0.0, 2.0e3),  # very soft: large stretch
    ],
)
def test_shape_reaches_b_by_ode_integration(
    point_b: tuple[float, float], lengths: tuple[float, float], P: float, EA: float
) -> None:
    sol = two_segment_catenary((0.0, 0.0), point_b, lengths, W2, P, EA=EA)
    junction, end, pieces = _integrate(sol)
    # DOP853 at rtol 1e-13 reaches B to ~1e-14 of the chord for the exact (H, V_a); a
    # relative error of 1e-9 in H already misses by 3e-10, so 1e-10 is a sharp test.
    chord = math.hypot(*point_b)
    assert np.hypot(*(end - np.array(point_b))) < 1e-10 * chord
    assert np.hypot(*(junction - np.array(sol.junction))) < 1e-10 * chord
    # interior points of the closed-form profile against the dense ODE output
    L1, L2 = lengths
    s = np.linspace(0.0, L1 + L2, 301)
    x, z = sol.position(s)
    for s_i, x_i, z_i in zip(s, x, z, strict=True):
        r = pieces[0] if s_i <= L1 else pieces[1]
        xi, zi = r.sol(s_i)
        assert math.hypot(xi - x_i, zi - z_i) < 1e-10 * chord


def test_extensible_tends_to_inextensible() -> None:
    # The elastic solution differs from the inextensible one by O(T/EA): the distance
    # between the junctions times EA tends to a constant (2.786e5 lbf ft here), with an
    # O(1/EA) relative drift (T/EA ~ 1e-5 at EA = 1e8). Check the scaled distance agrees to
    # 1e-4 across EA = 1e8, 1e9, 1e10, and that EA = 1e14 reproduces the inextensible H,
    # V_a and junction to 1e-9.
    ref = tuah_ex2_reference()
    scaled = []
    for EA in (1e8, 1e9, 1e10):
        sol = tuah_ex2_reference(EA=EA)
        scaled.append(math.dist(sol.junction, ref.junction) * EA)
    assert scaled[2] == pytest.approx(scaled[1], rel=1e-4)
    assert scaled[1] == pytest.approx(scaled[0], rel=1e-4)
    stiff = tuah_ex2_reference(EA=1e14)
    assert stiff.H == pytest.approx(ref.H, rel=1e-9)
    assert stiff.V_a == pytest.approx(ref.V_a, rel=1e-9)
    assert math.dist(stiff.junction, ref.junction) < 1e-9 * 1300.0


def _end_slope(sol: TwoSegmentSolution, s: float, direction: float, h: float = 1e-2) -> float:
    """dz/dx at arc length s by a second-order one-sided difference of the exact position."""
    ss = s + direction * np.array([0.0, h, 2.0 * h])
    x, z = sol.position(ss)
    dx = -3.0 * x[0] + 4.0 * x[1] - x[2]
    dz = -3.0 * z[0] + 4.0 * z[1] - z[2]
    return float(dz / dx)


@pytest.mark.parametrize("EA", [math.inf, EA2])
def test_tuah_ex2_balance(EA: float) -> None:
    sol = tuah_ex2_reference(EA=EA)
    L = sum(sol.lengths)
    print(
        f"\nTuah Ex2 (EA={EA}): w={sol.weight:.6f} lbf/ft, H={sol.H:.6f} lbf, "
        f"V_a={sol.V_a:.6f} lbf, V_b={sol.V_b:.6f} lbf, T_a={sol.tension_a:.6f}, "
        f"T_b={sol.tension_b:.6f}, junction=({sol.junction[0]:.6f}, {sol.junction[1]:.6f}) ft"
    )
    assert sol.weight == pytest.approx(0.946882, rel=1e-6)
    # vertical balance of the whole cable with the sign convention of the module
    assert sol.V_b - sol.V_a == pytest.approx(sol.weight * L - 900.0, abs=1e-10 * sol.weight * L)
    # the end forces agree with the shape: slope at A is V_a/H, slope at B is V_b/H
    # (independent of the stored V_b: taken from the computed profile; the one-sided
    # difference with h = 0.01 ft errs by O(h^2 z''') ~ 1e-9 relative, so 1e-8)
    assert _end_slope(sol, 0.0, +1.0) == pytest.approx(sol.V_a / sol.H, rel=1e-8)
    assert _end_slope(sol, L, -1.0) == pytest.approx(sol.V_b / sol.H, rel=1e-8)
    # the kink at the junction carries the buoy: slope jump times H equals -P
    L1 = sol.lengths[0]
    below = _end_slope(sol, L1, -1.0)
    above = _end_slope(sol, L1, +1.0)
    assert sol.H * (above - below) == pytest.approx(-900.0, rel=1e-8)


def _shoot_ex2(EA: float) -> dict[str, float]:
    """Tuah Ex2 solved without :mod:`references`: shooting on the equilibrium ODE.

    Unknowns (H, V_a); the cable is integrated from A by DOP853 (``_rhs_two_segment``) with
    the 900 lbf buoy as a jump of -900 lbf in V at s = 500 ft, and scipy's ``root`` drives the
    end to B = (1200, 500) ft from a rough start (the chord's H ~ w L, V_a = 0), never from
    the closed form. Returns H, V_a, V_b = V_a + w L - P and the junction."""
    w, P, (L1, L2), B = W2, 900.0, (500.0, 1000.0), np.array([1200.0, 500.0])

    def ends(p: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        H, Va = p
        y, out = np.zeros(2), []
        for s0, s1, V0 in ((0.0, L1, Va), (L1, L1 + L2, Va + w * L1 - P)):
            r = scipy.integrate.solve_ivp(_rhs_two_segment, (s0, s1), y, method="DOP853",
                                          rtol=1e-13, atol=1e-12, args=(H, V0, s0, w, EA))
            y = r.y[:, -1]
            out.append(y)
        return out[0], out[1]

    sol = scipy.optimize.root(lambda p: ends(p)[1] - B, x0=[w * (L1 + L2), 0.0],
                              method="hybr", options={"xtol": 1e-13})
    assert sol.success, sol.message
    H, Va = (float(v) for v in sol.x)
    junction = ends(sol.x)[0]
    return {"H": H, "V_a": Va, "V_b": Va + w * (L1 + L2) - P,
            "x_j": float(junction[0]), "z_j": float(junction[1])}


@pytest.mark.parametrize(
    ("EA", "printed"),
    [  # the table of tuah_ex2_reference's docstring: H, V_a, V_b, junction (x, z)
        (math.inf, (363.6406, 72.6578, 592.9812, 382.978, 301.268)),
        (EA2, (359.3659, 70.7856, 591.1090, 383.200, 302.807)),
    ],
)
def test_tuah_ex2_against_shooting(EA: float, printed: tuple[float, ...]) -> None:
    """The closed form and the numbers its docstring quotes, against shooting on the ODE.

    The shooting solution reaches B to ~1e-12 of the chord; its (H, V_a) then carry a
    relative error of ~1e-11 (the end position's sensitivity to H is of order L / H), so
    the closed form must agree to 1e-9 and each printed number to half a unit of its last
    printed digit (plus 1e-9 of slack for the shooting error)."""
    shot = _shoot_ex2(EA)
    sol = tuah_ex2_reference(EA=EA)
    computed = {"H": sol.H, "V_a": sol.V_a, "V_b": sol.V_b,
                "x_j": sol.junction[0], "z_j": sol.junction[1]}
    for key, value in computed.items():
        assert value == pytest.approx(shot[key], rel=1e-9, abs=1e-9), key
    for key, quoted, half_digit in zip(shot, printed, (5e-5,) * 3 + (5e-4,) * 2, strict=True):
        assert abs(quoted - shot[key]) <= half_digit + 1e-9, (key, quoted, shot[key])


def test_profile_includes_junction_and_ends() -> None:
    sol = tuah_ex2_reference()
    x, z = sol.profile(31)
    assert x.shape == z.shape == (31,)
    n1 = max(2, min(30, round(31 * 500.0 / 1500.0)))
    assert (x[0], z[0]) == (0.0, 0.0)
    assert (x[n1 - 1], z[n1 - 1]) == pytest.approx(sol.junction, abs=1e-12)
    assert (x[-1], z[-1]) == pytest.approx((1200.0, 500.0), abs=1e-9)


def test_infeasible_inextensible_raises() -> None:
    with pytest.raises(ValueError):
        two_segment_catenary((0.0, 0.0), (1417.0, 500.0), (500.0, 1000.0), W2, 900.0)
