"""Non-linear tension-strain laws (issue 13, item 1): the tabulated law and its tangent, a
polyester line's static end forces against an independent integration of the cable equations,
a table equal to a constant EA against the constant-EA results, the fibre-rope dynamic
stiffness, the case and MoorDyn inputs, and MoorDyn's initial condition with the same table."""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from scipy.integrate import solve_ivp
from scipy.interpolate import PchipInterpolator
from scipy.optimize import brentq, least_squares

from moorline.cli import cli
from moorline.errors import CaseError
from moorline.io.case import load_case, load_case_text
from moorline.io.case_writer import write_case
from moorline.io.moordyn import read_moordyn, write_moordyn
from moorline.mesh import dynamic_mesh
from moorline.model import DynamicsSettings, HarmonicSettings, ModalSettings
from moorline.physics import element
from moorline.physics.load_strain import StrainLaws, StrainTable
from moorline.solvers.assembly import BlockPattern, gather_free
from moorline.solvers.dynamic_model import DynamicModel
from moorline.solvers.dynamics import simulate
from moorline.solvers.harmonic import solve_harmonic
from moorline.solvers.modal import solve_modes
from moorline.solvers.statics import solve_statics
from moorline.solvers.stochastic import solve_stochastic
from moorline.waves import fluid_field_from_environment

MBL = 12.3e6  # N, a 200 mm polyester rope (MoorPy's 308e6 d^2)
RHO, G, DIAM, MASS, LENGTH = 1025.0, 9.80665, 0.158, 27.2, 1120.0
ANCHOR, FAIRLEAD = (-1000.0, 0.0, -600.0), (-20.0, 0.0, -20.0)
ROOT = Path(__file__).resolve().parents[1]
ALL_MODES = ModalSettings(n_modes=57)  # every mode of a 20-segment line


def _tangent(mesh, x) -> np.ndarray:
    """``dT/deps`` of every element of ``mesh`` at positions ``x``."""
    length, _ = element.element_geometry(x, mesh.elements)
    return element.axial_tension(length, mesh.length0, mesh.EA, mesh.slack_ratio,
                                 mesh.slack_smoothing, **mesh.axial_law)[1] * mesh.length0


def _quadratic_table(n: int = 21, end: float = 0.04) -> np.ndarray:
    """A stiffening model curve T = MBL (10 eps + 250 eps^2) sampled at ``n`` points."""
    eps = np.linspace(0.0, end, n)
    return np.column_stack((eps, MBL * (10 * eps + 250 * eps**2)))


def _case(table: np.ndarray | None, segments: int, EA: float = 0.0, extra: str = "") -> str:
    ea = (f"{{table: {[[float(e), float(t)] for e, t in table]}}}" if table is not None
          else repr(EA))
    return f"""
name: poly
units: SI
environment: {{depth: 600, water_density: {RHO}, gravity: {G}}}
line_types:
  poly: {{diameter: {DIAM}, mass_per_length: {MASS}, EA: {ea}, Cd: 2.0, Ct: 0.01{extra}}}
points:
  anchor: {{kind: fixed, position: {list(ANCHOR)}}}
  fairlead: {{kind: prescribed, position: {list(FAIRLEAD)},
              motion: {{kind: harmonic, amplitude: [4, 0, 2], period: 12, ramp_time: 12}}}}
lines:
  l1: {{type: poly, length: {LENGTH}, segments: {segments}, end_a: anchor, end_b: fairlead}}
"""


# ---- the law and its tangent (kernel level, vectorized over elements) ----

def test_tangent_matches_central_differences_over_all_branches():
    rng = np.random.default_rng(3)
    tables = (StrainTable(_quadratic_table(9)),
              StrainTable([[0.01, 2e5], [0.03, 9e5], [0.05, 1.2e6]]))  # (0, 0) prepended
    n = 400
    ids = rng.integers(-1, 2, n)
    laws = StrainLaws(tables, ids)
    L0 = rng.uniform(5.0, 20.0, n)
    strain = rng.uniform(-2e-4, 0.07, n)  # slack, band, inside and beyond the tables
    strain[:40] = rng.uniform(-2e-5, 2e-5, 40)  # the smoothing band
    EA = np.where(ids == 0, 1.2e8, np.where(ids == 1, 8e7, 5e7))
    ratio, s = np.full(n, 1e-3), np.full(n, 1e-5)
    length = L0 * (1 + strain)
    T, dT = element.axial_tension(length, L0, EA, ratio, s, laws=laws)
    h = 1e-9 * L0
    Tp = element.axial_tension(length + h, L0, EA, ratio, s, laws=laws)[0]
    Tm = element.axial_tension(length - h, L0, EA, ratio, s, laws=laws)[0]
    fd = (Tp - Tm) / (2 * h)
    # central differences: truncation ~ f''' h^2, round-off ~ eps |T| / h
    kink = np.isclose(np.abs(strain), 1e-5, atol=2e-9)  # the band's ends: C1, not C2
    scale = np.abs(dT) + 1e-9 * np.abs(T) / h
    assert np.all(np.abs(fd - dT)[~kink] <= 1e-5 * scale[~kink])
    # the energy is the integral of the tension (taut elements; the band is linearized)
    taut = strain > 2e-5
    E = lambda x: element.strain_energy(x, L0, EA, ratio, s, laws=laws)  # noqa: E731
    fdE = (E(length + h) - E(length - h)) / (2 * h)
    assert np.allclose(fdE[taut], T[taut], rtol=1e-6, atol=1e-3)


def test_table_law_values_monotone_and_linear_beyond_the_last_point():
    table = StrainTable(_quadratic_table(5))
    knots = table.points
    T, dT = table(knots[:, 0])
    assert np.allclose(T, knots[:, 1], rtol=1e-14, atol=1e-9)  # interpolates the points
    e = np.linspace(0.0, 0.04, 2001)
    f, df = table(e)
    assert np.all(np.diff(f) > 0) and np.all(df >= 0)  # monotone data: monotone law
    beyond = np.array([0.05, 0.08])
    fb, dfb = table(beyond)
    assert np.allclose(fb, knots[-1, 1] + table.end_slope * (beyond - knots[-1, 0]))
    assert np.allclose(dfb, table.end_slope)
    # compression-free: T = 0 at and below zero strain with the cable law (no regularization)
    laws = StrainLaws((table,), np.zeros(3, dtype=np.int64))
    T0, _ = element.axial_tension(np.array([0.9, 1.0, 1.0]), np.ones(3), np.full(3, 1e8),
                                  np.zeros(3), 0.0, laws=laws)
    assert np.all(T0 == 0.0)


@pytest.mark.parametrize("points, why", [([[0.0, 1.0], [0.1, 2.0]], "zero strain"),
                                         ([[0.0, 0.0], [0.1, 2.0], [0.1, 3.0]], "increase"),
                                         ([[0.0, 0.0], [0.1, 2.0], [0.2, 1.0]], "decrease"),
                                         ([[-0.1, 0.0], [0.1, 2.0]], ">= 0")])
def test_bad_tables_are_refused(points, why):
    with pytest.raises(ValueError, match=why):
        StrainTable(points)


@pytest.mark.parametrize("kernel", ["numpy", "numba"])
def test_dynamic_model_stiffness_of_a_table_line_matches_differences_of_its_forces(kernel):
    """The dynamic residual's K = -dF/dx with the table law (the numpy path and the compiled
    kernel) against central differences of its forces, about a state stretched beyond the
    static one (inside the curve's stiffening part)."""
    system = load_case_text(_case(_quadratic_table(), 12))
    statics = solve_statics(system)
    model = DynamicModel(statics.mesh, fluid_field_from_environment(system.environment),
                         kernel=kernel)
    assert model.kernel == kernel
    rng = np.random.default_rng(5)
    x = statics.positions + rng.normal(0.0, 0.5, statics.positions.shape)
    zero = np.zeros_like(x)
    state = model.initial_material(x)
    ev = model.evaluate(x, zero, zero, 0.0, state, 0.1, True)
    pattern = BlockPattern(statics.mesh.elements, statics.mesh.dof_of_node)
    K = pattern.assemble(ev.K, ev.node_K).toarray()
    dofs = statics.mesh.dof_of_node
    h = 1e-4
    for node, k in ((3, 0), (6, 2), (9, 1)):
        xp, xm = x.copy(), x.copy()
        xp[node, k] += h
        xm[node, k] -= h
        fp = gather_free(model.evaluate(xp, zero, zero, 0.0, state, 0.1, False).nodal, dofs)
        fm = gather_free(model.evaluate(xm, zero, zero, 0.0, state, 0.1, False).nodal, dofs)
        column = -(fp - fm) / (2 * h)
        assert np.allclose(K[:, dofs[node, k]], column, rtol=1e-6,
                           atol=1e-6 * np.abs(column).max())


# ---- statics against an independent integration of the cable equations ----

def _shooting(table: np.ndarray, mass: float = MASS, diameter: float = DIAM,
              anchor=ANCHOR, fairlead=FAIRLEAD) -> tuple[np.ndarray, np.ndarray]:
    """Anchor and fairlead forces of the continuous elastic catenary with ``T(eps)`` the same
    monotone cubic through the table: ``dx/ds = (1 + eps(T)) H / T``, ``dz/ds = (1 + eps(T))
    V / T``, ``V = V_a + w s`` (s unstretched, from the anchor), shot to the fairlead (in the
    vertical plane through both ends; forces in the anchor-to-fairlead frame, x horizontal)."""
    law = PchipInterpolator(table[:, 0], table[:, 1])
    w = (mass - RHO * math.pi * diameter**2 / 4) * G
    a, b = np.asarray(anchor, dtype=float), np.asarray(fairlead, dtype=float)
    span = np.array([np.linalg.norm((b - a)[:2]), b[2] - a[2]])

    def rhs(s, y, H, Va):
        V = Va + w * s
        T = math.hypot(H, V)
        stretch = 1 + brentq(lambda e: law(e) - T, 0.0, table[-1, 0], xtol=1e-16)
        return [stretch * H / T, stretch * V / T]

    def miss(p):
        sol = solve_ivp(rhs, (0, LENGTH), [0.0, 0.0], args=tuple(p), rtol=1e-12, atol=1e-9)
        return sol.y[:, -1] - span

    H, Va = least_squares(miss, [2e6, 1e6], x_scale=[1e6, 1e6], xtol=1e-15, ftol=1e-15).x
    return np.array([H, 0.0, Va]), -np.array([H, 0.0, Va + w * LENGTH])


def test_polyester_static_end_forces_match_the_shooting_solution():
    table = _quadratic_table()
    ref_a, ref_b = _shooting(table)
    errors = []
    for segments in (20, 40):
        r = solve_statics(load_case_text(_case(table, segments)))
        assert r.success, r.message
        assert r.tension.max() < table[-1, 1]  # inside the table
        errors.append(max(np.linalg.norm(r.end_force("l1", "a") - ref_a),
                          np.linalg.norm(r.end_force("l1", "b") - ref_b))
                      / np.linalg.norm(ref_b))
    # the lumped model converges as O(h^2) (measured 3.6e-6, 9.1e-7, 2.3e-7 at 20, 40, 80)
    assert errors[1] < 2e-6, errors
    assert 3.0 < errors[0] / errors[1] < 5.0, errors
    # the law matters: the constant EA of the table's secant at the solution is 0.1 % off
    secant = float(np.linalg.norm(ref_b))
    strain = brentq(lambda e: PchipInterpolator(table[:, 0], table[:, 1])(e) - secant, 0, 0.04)
    linear = solve_statics(load_case_text(_case(None, 40, EA=secant / strain)))
    assert np.linalg.norm(linear.end_force("l1", "a") - ref_a) > 50 * errors[1] * secant


# ---- a table equal to a constant EA reproduces the constant-EA results ----

def test_linear_table_reproduces_constant_ea_in_every_analysis():
    EA = 3.7e8
    table = np.array([[0.0, 0.0], [0.01, 0.01 * EA], [0.05, 0.05 * EA]])
    constant = load_case_text(_case(None, 20, EA=EA))
    tabulated = load_case_text(_case(table, 20))
    assert tabulated.line_types["poly"].EA == pytest.approx(EA, rel=1e-12)
    s_c, s_t = solve_statics(constant), solve_statics(tabulated)
    assert np.allclose(s_t.positions, s_c.positions, rtol=0, atol=1e-10 * LENGTH)
    assert np.allclose(s_t.tension, s_c.tension, rtol=1e-10)
    settings = DynamicsSettings(duration=6.0, dt=0.1)
    d_c = simulate(constant, settings, initial=s_c)
    d_t = simulate(tabulated, settings, initial=s_t)
    T_c, T_t = d_c.end_tension("l1", "b"), d_t.end_tension("l1", "b")
    assert np.ptp(T_c) > 1e3  # the fairlead moves
    assert np.allclose(T_t, T_c, rtol=1e-10)
    f_c = solve_modes(constant, ALL_MODES, statics=s_c).omega
    f_t = solve_modes(tabulated, ALL_MODES, statics=s_t).omega
    assert np.allclose(f_t, f_c, rtol=1e-10)
    hb = HarmonicSettings(period=12.0, harmonics=3)
    h_c = solve_harmonic(constant, hb, statics=s_c)
    h_t = solve_harmonic(tabulated, hb, statics=s_t)
    assert np.ptp(h_c.tension) > 1e3
    assert np.allclose(h_t.tension, h_c.tension, rtol=1e-10)
    sea = "waves: {kind: random, height: 6, period: 10, record_length: 600}"
    at_sea = [load_case_text(c.replace("gravity: 9.80665}", f"gravity: 9.80665, {sea}}}"))
              for c in (_case(None, 20, EA=EA), _case(table, 20))]
    r_c, r_t = (solve_stochastic(c, statics=st) for c, st in zip(at_sea, (s_c, s_t), strict=True))
    assert r_c.tension_std.max() > 10.0
    assert np.allclose(r_t.tension_std, r_c.tension_std, rtol=1e-10)


# ---- fibre-rope dynamic stiffness about the mean tension ----

@pytest.mark.parametrize("kernel", ["numpy", "numba"])
def test_dynamic_stiffness_about_the_static_state(kernel):
    EAd, Lm = 11.6 * MBL, 40.0  # MoorPy's polyester: EA_d = 11.6 MBL + 40 T_mean
    system = load_case_text(_case(_quadratic_table(), 20, extra=f", EAd: {EAd}, EAd_Lm: {Lm}"))
    statics = solve_statics(system)
    mesh = dynamic_mesh(statics.mesh, statics.positions)
    model = DynamicModel(mesh, fluid_field_from_environment(system.environment),
                         kernel=kernel)
    assert model.kernel == kernel
    x = statics.positions
    zero = np.zeros_like(x)
    ev = model.evaluate(x, zero, zero, 0.0, model.initial_material(x), 0.1, False)
    assert np.allclose(ev.tension, statics.tension, rtol=1e-12)  # same equilibrium
    assert np.allclose(_tangent(mesh, x), EAd + Lm * statics.tension, rtol=1e-12)
    # the static tangent is the table's, which is softer here: the axial modes stiffen
    quasi_static = replace(system, line_types={"poly": replace(system.line_types["poly"],
                                                               EAd=None)})
    w_static = solve_modes(quasi_static, ALL_MODES).omega
    w_dynamic = solve_modes(system, ALL_MODES, statics=statics).omega
    # the highest (axial) mode scales with sqrt(EA): sqrt(EA_d / EA_t) at the mean tension
    T = statics.tension
    ratio = math.sqrt(float(np.mean(EAd + Lm * T))
                      / float(np.mean(_tangent(statics.mesh, statics.positions))))
    assert w_dynamic.max() / w_static.max() == pytest.approx(ratio, rel=0.05)


# ---- inputs: case tables, table files, MoorDyn decks ----

def test_table_file_and_moordyn_deck_give_the_same_line_type(tmp_path: Path):
    table = _quadratic_table(6)
    (tmp_path / "poly.dat").write_text(
        "----Polyester----\nStrain    Tension\n(-)       (N)\n"
        + "\n".join(f"{e!r} {t!r}" for e, t in table.tolist()), encoding="utf-8")
    case = tmp_path / "case.yaml"
    case.write_text(_case(None, 10, EA=1.0).replace("EA: 1.0", "EA_table: poly.dat"),
                    encoding="utf-8")
    from_file = load_case(case).line_types["poly"]
    inline = load_case_text(_case(table, 10)).line_types["poly"]
    assert from_file.EA_table == inline.EA_table and from_file.EA == inline.EA
    deck = write_moordyn(load_case(case), tmp_path / "deck.dat", 1e-3)
    back = read_moordyn(deck).line_types["poly"]
    assert np.allclose(back.EA_table, from_file.EA_table, rtol=1e-15)


def _convert(deck: Path, out: Path):
    """``moorline convert`` of a deck, loaded back."""
    result = CliRunner().invoke(cli, ["convert", str(deck), "--out", str(out), "--quiet"])
    assert result.exit_code == 0, result.output
    return load_case(out)


def test_convert_reads_a_moordyn_deck_with_an_ea_table(tmp_path: Path):
    system = load_case_text(_case(_quadratic_table(8), 10))
    deck = write_moordyn(system, tmp_path / "deck.dat", 1e-3)
    assert "deck_poly_EA.dat" in deck.read_text()
    converted = _convert(deck, tmp_path / "deck.yaml")
    assert converted.line_types["poly"].EA_table == system.line_types["poly"].EA_table
    r0, r1 = solve_statics(system), solve_statics(converted)
    assert np.allclose(r1.tension, r0.tension, rtol=1e-12)


def test_moordyn_tables_longer_than_moordyn_reads_are_refused(tmp_path: Path):
    with pytest.raises(CaseError, match="at most 30"):
        write_moordyn(load_case_text(_case(_quadratic_table(31), 10)), tmp_path / "d.dat", 1e-3)


@pytest.mark.compare
def test_initial_condition_tensions_agree_with_moordyn_with_a_table(tmp_path: Path):
    """MoorDyn interpolates its table linearly, moorline by the monotone cubic: with 30
    points (MoorDyn's most) to 2.5 % strain the laws differ by at most 250 MBL h^2 / 4 =
    570 N (0.02 % of the 2.9 MN fairlead tension), well inside the 0.5 % asked. moorline
    solves the case converted from the deck MoorDyn read (``moorline convert``). MoorDyn's
    stationary initial-condition solver stops at TmaxIC = 300 s with a residual of about
    0.09 m/s^2; measured difference 1e-4 (6e-5 at TmaxIC = 1000 s)."""
    pytest.importorskip("moordyn")
    from moorline.compare.moordyn_runner import run_moordyn

    system = load_case_text(_case(_quadratic_table(30, 0.025), 20))
    md = run_moordyn(system, 0.1, 1e-4, 0.1, tmax_ic=300.0, workdir=tmp_path)
    assert md["success"], md["message"]
    r = solve_statics(_convert(Path(md["deck"]), tmp_path / "converted.yaml"))
    md_force = np.asarray(md["end_force"])[0, 0]
    for k, end in enumerate("ab"):
        ml = np.linalg.norm(r.end_force("l1", end))
        assert np.linalg.norm(md_force[k]) == pytest.approx(ml, rel=0.005)


# ---- the polyester case file ----

def test_polyester_case_statics_dynamics_and_stochastic(tmp_path: Path):
    """cases/polyester_taut.yaml: each line's static end forces against the shooting
    solution with the case's own curve (MoorDyn's Syrope test curve) and rope: the lumped
    model's O(h^2) error, measured 7.3e-6, 1.8e-6, 4.4e-7 of the end tension at 20, 40, 80
    segments; a short dynamics and the stochastic analysis run with the dynamic stiffness;
    the case survives write -> load with its table."""
    system = load_case(ROOT / "cases" / "polyester_taut.yaml")
    lt = system.line_types["polyester"]
    table = np.asarray(lt.EA_table)
    statics = solve_statics(system)
    assert statics.success, statics.message
    for name, line in system.lines.items():
        a, b = system.points[line.end_a].position, system.points[line.end_b].position
        ref_a, ref_b = _shooting(table, lt.mass_per_length, lt.diameter, a, b)
        horizontal = np.append((np.asarray(b) - np.asarray(a))[:2], 0.0)
        horizontal /= np.linalg.norm(horizontal)
        for end, ref in (("a", ref_a), ("b", ref_b)):
            f = statics.end_force(name, end)
            across = np.array([-horizontal[1], horizontal[0], 0.0])
            plane = np.array([f @ horizontal, f @ across, f[2]])
            assert np.allclose(plane, ref, rtol=0, atol=1e-5 * np.linalg.norm(ref))
    dynamics = simulate(system, DynamicsSettings(duration=5.0, dt=0.05), initial=statics)
    assert dynamics.success, dynamics.message
    stochastic = solve_stochastic(system, statics=statics)
    assert stochastic.success and stochastic.tension_std.max() > 0
    again = load_case(write_case(system, tmp_path / "polyester.yaml"))
    assert again.line_types == system.line_types
