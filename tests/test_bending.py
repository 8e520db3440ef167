"""Bending stiffness (EI): the rotation-free kernel (forces and exact tangent against finite
differences), its assembly in the static and dynamic residuals, the case and MoorDyn inputs,
and beams in closed form (:mod:`moorline.verification.bending` has the rows)."""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest

from moorline.io import load_case_text
from moorline.io.moordyn import read_moordyn, read_moordyn_deck, write_moordyn
from moorline.mesh import discretize
from moorline.physics import bending
from moorline.solvers.assembly import BlockPattern, gather_free, scatter_free
from moorline.solvers.dynamic_model import DynamicModel
from moorline.solvers.equilibrium import StaticModel
from moorline.solvers.statics import solve_statics
from moorline.verification import bending as case
from moorline.verification import run_cases
from moorline.waves import StillWater

DECKS = Path(__file__).parent / "data" / "moordyn"
BEAM_DECK = DECKS / "public" / "MoorDyn" / "BeamSimplySupported.txt"


def _chain(n: int, rng: np.random.Generator, bend: float) -> np.ndarray:
    """A polyline of ``n`` nodes with turning angles of about ``bend`` rad."""
    x = np.zeros((n, 3))
    d = np.array([1.0, 0.0, 0.0])
    for i in range(1, n):
        d = d + bend * rng.normal(size=3)
        d /= np.linalg.norm(d)
        x[i] = x[i - 1] + rng.uniform(0.5, 2.0) * d
    return x


@pytest.mark.parametrize("bend", [1e-4, 0.1, 1.0])
def test_forces_are_minus_the_energy_gradient_and_the_tangent_its_hessian(bend: float) -> None:
    """Central differences of the energy (forces) and of the forces (9x9 tangent), from a
    nearly straight line to turning angles of tens of degrees."""
    rng = np.random.default_rng(3)
    x = _chain(6, rng, bend)
    nodes = np.array([[0, 1, 2], [1, 2, 3], [2, 3, 4], [3, 4, 5]])
    c = rng.uniform(1.0, 3.0, size=4)
    forces = bending.bending_forces(x, nodes, c)
    K = bending.bending_tangent(x, nodes, c)
    h = 1e-6
    for t in range(len(nodes)):
        grad = np.zeros(9)
        dforce = np.zeros((9, 9))
        for j in range(9):
            node, k = nodes[t, j // 3], j % 3
            xp, xm = x.copy(), x.copy()
            xp[node, k] += h
            xm[node, k] -= h
            one = slice(t, t + 1)
            grad[j] = (bending.bending_energy(xp, nodes[one], c[one])[0]
                       - bending.bending_energy(xm, nodes[one], c[one])[0]) / (2 * h)
            dforce[:, j] = -(bending.bending_forces(xp, nodes[one], c[one])[0].ravel()
                             - bending.bending_forces(xm, nodes[one], c[one])[0].ravel()) / (2 * h)
        scale = np.abs(K[t]).max()
        np.testing.assert_allclose(forces[t].ravel(), -grad, atol=1e-7 * max(scale, 1.0))
        np.testing.assert_allclose(K[t], dforce, atol=1e-6 * scale)
        np.testing.assert_allclose(K[t], K[t].T, atol=1e-12 * scale)
        np.testing.assert_allclose(forces[t].sum(axis=0), 0.0, atol=1e-12 * scale)


def test_curvature_of_a_circle_and_the_small_angle_energy() -> None:
    """Nodes on a circle of radius R with chords of unstretched length: curvature
    ``2 sin(theta/2) / Lbar = 1 / R``; energy ``EI / (2 R^2) Lbar`` per node at small angles."""
    R, n = 20.0, 50
    phi = np.linspace(0.0, 0.5, n)
    x = np.column_stack((R * np.cos(phi), R * np.sin(phi), np.zeros(n)))
    chord = 2 * R * math.sin(0.5 * (phi[1] - phi[0]))
    nodes = np.column_stack((np.arange(n - 2), np.arange(1, n - 1), np.arange(2, n)))
    kappa = bending.curvature(x, nodes, np.full(n - 2, chord))
    np.testing.assert_allclose(kappa, 1.0 / R, rtol=1e-10)
    EI = 3.0
    energy = bending.bending_energy(x, nodes, np.full(n - 2, EI / chord))
    np.testing.assert_allclose(energy, 0.5 * EI / R**2 * chord, rtol=1e-4)


def _bent_system(EI: float = 2.0e8):
    """A slack riser-like line with bending stiffness, between a fixed and a free point
    (the free point carries a weight), so the tangent couples free and held nodes."""
    system = case.riser_system(EI, segments=6)
    top = dataclasses.replace(system.points["top"], kind="free", mass=100.0)
    return dataclasses.replace(system, points={**system.points, "top": top})


def test_assembled_static_tangent_matches_finite_differences() -> None:
    """The bending blocks through the pattern's extra (i-1, i+1) pairs: the whole assembled
    tangent ``-dR/dx`` against central differences of the residual."""
    system = _bent_system()
    mesh = discretize(system)
    assert mesh.has_bending and len(mesh.bend_nodes) == 5
    assert len(mesh.pattern_pairs) == mesh.n_elements + 5
    rng = np.random.default_rng(0)
    x = mesh.node_position + rng.normal(scale=0.5, size=mesh.node_position.shape)
    x[mesh.point_node[0]] = mesh.node_position[mesh.point_node[0]]
    x[:, 1] += 0.2 * rng.normal(size=mesh.n_nodes)
    model = StaticModel(mesh)
    K = model.tangent(x).toarray()
    h = 1e-5
    fd = np.zeros_like(K)
    for j in range(mesh.n_dofs):
        d = np.zeros(mesh.n_dofs)
        d[j] = h
        step = scatter_free(d, mesh.dof_of_node)
        fd[:, j] = -(model.residual(x + step)[0] - model.residual(x - step)[0]) / (2 * h)
    np.testing.assert_allclose(K, fd, atol=1e-6 * np.abs(K).max())
    without = StaticModel(discretize(_bent_system(0.0))).tangent(x).toarray()
    assert np.abs(K - without).max() > 1e-3 * np.abs(K).max()  # bending is in it


@pytest.mark.parametrize("kernel", ["numpy", "numba"])
def test_dynamic_residual_carries_bending_and_its_tangent(kernel: str) -> None:
    """Both element kernels: the dynamic nodal forces equal the static ones at rest, the
    element forces include the bending shear, and ``K`` matches finite differences."""
    mesh = discretize(_bent_system())
    rng = np.random.default_rng(1)
    x = mesh.node_position + rng.normal(scale=0.3, size=mesh.node_position.shape)
    zero = np.zeros_like(x)
    model = DynamicModel(mesh, StillWater(), kernel=kernel)
    state = model.initial_material(x)
    ev = model.evaluate(x, zero, zero, 0.0, state, 0.1, tangent=True)
    static = StaticModel(mesh).forces(x)
    np.testing.assert_allclose(ev.nodal, static.nodal, atol=1e-8 * np.abs(static.nodal).max())
    np.testing.assert_allclose(ev.element_forces, static.element_forces, rtol=1e-12,
                               atol=1e-9 * np.abs(static.element_forces).max())
    assert ev.K.shape == ev.C.shape == (len(mesh.pattern_pairs), 6, 6)
    pattern = BlockPattern(mesh.pattern_pairs, mesh.dof_of_node)
    K = pattern.assemble(ev.K, ev.node_K).toarray()
    h = 1e-5
    fd = np.zeros_like(K)
    for j in range(mesh.n_dofs):
        d = np.zeros(mesh.n_dofs)
        d[j] = h
        step = scatter_free(d, mesh.dof_of_node)
        fp = model.evaluate(x + step, zero, zero, 0.0, state, 0.1, tangent=False).nodal
        fm = model.evaluate(x - step, zero, zero, 0.0, state, 0.1, tangent=False).nodal
        dof = mesh.dof_of_node
        fd[:, j] = -(gather_free(fp, dof) - gather_free(fm, dof)) / (2 * h)
    np.testing.assert_allclose(K, fd, atol=1e-6 * np.abs(K).max())


def test_compiled_time_step_refuses_bending() -> None:
    from moorline.solvers.fast_path import fast_path_reason

    model = DynamicModel(discretize(_bent_system()), StillWater(), kernel="numba")
    assert fast_path_reason(model, StillWater(), "newmark", "iterative") == \
        "bending stiffness (EI)"
    plain = DynamicModel(discretize(_bent_system(0.0)), StillWater(), kernel="numba")
    assert fast_path_reason(plain, StillWater(), "newmark", "iterative") is None


def test_no_bending_leaves_the_mesh_and_pattern_as_before() -> None:
    mesh = discretize(_bent_system(0.0))
    assert not mesh.has_bending and mesh.pattern_pairs is mesh.elements


def test_beam_string_deflection_against_the_closed_form() -> None:
    """(a) of the verification case: midspan deflection at 40 elements within 1e-3 of the
    sinh/cosh beam-string solution, converging at second order; the same line without EI
    would sag twice as much (so the check sees the bending)."""
    rows = case.static_rows()
    assert all(r.passed for r in rows), [(r.quantity, r.error) for r in rows]
    assert rows[0].computed < 0.6 * LOAD_STRING_SAG


LOAD_STRING_SAG = case.LOAD * case.SPAN**2 / (8 * case.TENSION)


def test_pinned_end_reaction_includes_the_bending_shear() -> None:
    """By symmetry each pinned end carries half the beam's weight: the end force (end
    element's force plus half its weight) holds only with the bending shear in the element
    forces (the axial force alone gives ``T sin(slope)``)."""
    system = case.beam_system(20, mass=case.LOAD / case.GRAVITY, gravity=case.GRAVITY)
    result = solve_statics(system)
    half = 0.5 * case.LOAD * system.lines["beam"].length
    for end in ("a", "b"):
        assert result.end_force("beam", end)[2] == pytest.approx(-half, rel=1e-9)
    e = result.mesh.line_elements[0][0]
    axial_only = -result.tension[e] * (result.positions[result.mesh.elements[e, 1], 2]
                                       - result.positions[result.mesh.elements[e, 0], 2]) \
        / result.mesh.length0[e] - 0.5 * case.LOAD * result.mesh.length0[e]
    assert abs(axial_only + half) > 0.1 * half


def test_beam_frequencies_against_the_closed_form() -> None:
    rows = case.modal_rows(quick=True)
    assert len(rows) == 4 and all(r.passed for r in rows), [(r.quantity, r.error) for r in rows]


def test_moordyn_simply_supported_beam_deck() -> None:
    """MoorDyn's own bending test deck (tests/Mooring/BeamSimplySupported.txt): EI is read (no
    warning), the statics match Euler-Bernoulli ``w = q x (L^3 - 2 L x^2 + x^3) / 24 EI``
    with moorline's load, the submerged weight (the deck's line lies above MoorDyn's water
    surface, where MoorDyn weighs it dry; moorline's statics take every line as submerged),
    within 0.2 % of the largest deflection (the stretch of the sagging pinned beam adds a
    tension of 1.5 kN: ``T L^2 / (pi^2 EI) = 0.15 %``; measured 0.07 %)."""
    deck = read_moordyn_deck(BEAM_DECK)
    assert deck.notes == ()
    system = deck.system
    assert system.line_types["beam"].EI == 1.0e7
    result = solve_statics(system)
    assert result.success
    x = result.positions[result.mesh.line_nodes[0]]
    q, EI, L = result.mesh.weight_per_length[0], 1.0e7, 10.0
    assert q == pytest.approx((100.0 - 1025.0 * math.pi * 0.25**2 / 4) * 9.80665, rel=1e-12)
    s = x[:, 0]
    w = -q * s * (L**3 - 2 * L * s**2 + s**3) / (24 * EI)
    np.testing.assert_allclose(x[:, 2] - 10.0, w, atol=2e-3 * np.abs(w).max())


def test_moordyn_writer_writes_ei_and_reads_it_back(tmp_path: Path) -> None:
    system = case.riser_system()
    deck = write_moordyn(system, tmp_path / "riser.dat", 0.005)
    assert read_moordyn(deck).line_types["riser"].EI == case.RISER_EI
    row = [r for r in deck.read_text().splitlines() if r.startswith("riser ")][0]
    assert row.split()[5] == "50000000.0"


def test_negative_ei_in_a_deck_is_refused(tmp_path: Path) -> None:
    from moorline.errors import CaseError

    text = BEAM_DECK.read_text().replace("-1.0        1e7", "-1.0        -1e7")
    path = tmp_path / "beam.txt"
    path.write_text(text)
    with pytest.raises(CaseError, match="EI must not be negative"):
        read_moordyn(path)


CASE_TEXT = """
name: beam
units: SI
line_types:
  b: {{diameter: 0.1 m, mass_per_length: 10 kg/m, EA: 1e8 N, EI: {EI}}}
points:
  a: {{kind: fixed, position: [0, 0, 0]}}
  c: {{kind: fixed, position: [100, 0, 0]}}
lines:
  l: {{type: b, length: 99.9, segments: 10, end_a: a, end_b: c}}
"""


def test_case_file_ei_with_units() -> None:
    system = load_case_text(CASE_TEXT.format(EI="2.5 kN*m**2"))
    assert system.line_types["b"].EI == pytest.approx(2500.0, rel=1e-12)
    assert load_case_text(CASE_TEXT.format(EI="3e4")).line_types["b"].EI == 3e4
    assert load_case_text(CASE_TEXT.format(EI="0")).line_types["b"].EI == 0.0
    from moorline.errors import CaseError

    with pytest.raises(CaseError, match="EI"):
        load_case_text(CASE_TEXT.format(EI="-1"))
    with pytest.raises(CaseError, match="EI"):
        load_case_text(CASE_TEXT.format(EI="5 N*m"))


def test_case_writer_keeps_ei(tmp_path: Path) -> None:
    from moorline.io import load_case
    from moorline.io.case_writer import write_case

    system = load_case_text(CASE_TEXT.format(EI="2.5e3"))
    path = write_case(system, tmp_path / "beam.yaml")
    assert load_case(path).line_types["b"].EI == 2.5e3
    plain = write_case(load_case_text(CASE_TEXT.format(EI="0")), tmp_path / "plain.yaml")
    assert "EI" not in plain.read_text()


def test_bending_verification_rows_pass() -> None:
    rows = run_cases(["bending"], quick=True)
    assert rows and all(r.status == "pass" for r in rows), \
        [(r.quantity, r.error) for r in rows if r.status != "pass"]


def test_bending_moordyn_rows_pass() -> None:
    pytest.importorskip("moordyn")
    rows = run_cases(["bending-moordyn"], quick=True)
    assert len(rows) == 3 and all(r.status == "pass" for r in rows), \
        [(r.quantity, r.reference, r.computed) for r in rows]


def test_harmonic_balance_of_the_end_driven_beam() -> None:
    """(d) of the verification case: the harmonic-balance midspan amplitude of the end-driven
    beam-string against its closed-form steady state (the string alone responds with 0.50 mm
    instead of 0.78 mm: the check sees the bending)."""
    row, = case.harmonic_rows()
    assert row.passed, (row.reference, row.computed)
    from moorline.verification.bending import driven_amplitude

    string = _string_drive()
    assert abs(row.reference - string) > 0.3 * abs(string)
    assert driven_amplitude(case.DRIVE_PERIOD, 1.0) == pytest.approx(
        row.reference / case.DRIVE, rel=1e-12)


def _string_drive() -> float:
    """The taut string's midspan amplitude for the same drive, ``Y sin(k L/2) / sin(k L)``,
    ``k = omega sqrt(m / T)``."""
    w = 2 * math.pi / case.DRIVE_PERIOD
    k = w * math.sqrt(case.MASS / (1 + case.EPS) / case.TENSION)
    return case.DRIVE * math.sin(k * case.SPAN / 2) / math.sin(k * case.SPAN)


def test_stochastic_analysis_carries_bending() -> None:
    """The frequency-domain analysis runs over the extended pattern: its two methods (FOSS
    and direct) agree with EI as without, and EI changes the response."""
    from moorline.model import StochasticSettings
    from moorline.solvers.stochastic import solve_stochastic
    from moorline.verification import stochastic_riser

    base = stochastic_riser.riser_system(20)
    stds = {}
    for ei in (0.0, 1.0e8):
        types = {k: dataclasses.replace(v, EI=ei) for k, v in base.line_types.items()}
        system = dataclasses.replace(base, line_types=types)
        # Foss's modal sum over every mode (n_modes >= the dofs; n_modes 0 solves the
        # full system directly) against the direct solution
        foss, direct = (solve_stochastic(system, StochasticSettings(method=m, n_modes=n))
                        for m, n in (("foss", 10_000), ("direct", 0)))
        assert foss.counters["modes"] > 0 and direct.counters["modes"] == 0
        assert foss.success and direct.success
        np.testing.assert_allclose(foss.tension_std, direct.tension_std, rtol=1e-6)
        stds[ei] = foss.displacement_std
    assert np.abs(stds[1.0e8] - stds[0.0]).max() > 0.05 * np.abs(stds[0.0]).max()


def test_clamp_forces_and_tangent_against_finite_differences() -> None:
    rng = np.random.default_rng(5)
    x = rng.normal(size=(4, 3))
    elements = np.array([[0, 1], [2, 3]])
    which = np.array([0, 1])
    direction = rng.normal(size=(2, 3))
    direction /= np.linalg.norm(direction, axis=1)[:, None]
    c = np.array([2.0, 5.0])
    args = (elements, which, direction, c)
    f = bending.clamp_forces(x, *args)
    K = bending.clamp_tangent(x, *args)
    h = 1e-6
    for k in range(2):
        for j in range(6):
            node, axis = elements[k, j // 3], j % 3
            xp, xm = x.copy(), x.copy()
            xp[node, axis] += h
            xm[node, axis] -= h
            energy = bending.clamp_energy(xp, *args)[k] - bending.clamp_energy(xm, *args)[k]
            grad = energy / (2 * h)
            assert f[k].ravel()[j] == pytest.approx(-grad, abs=1e-7)
            dforce = -(bending.clamp_forces(xp, *args)[k] - bending.clamp_forces(xm, *args)[k])
            np.testing.assert_allclose(K[k][:, j], dforce.ravel() / (2 * h), atol=1e-6)


def test_cantilever_tip_deflection_and_clamped_tangent() -> None:
    """(e) of the verification case: ``P L^3 / 3 EI`` at second order; the assembled tangent
    with the clamp matches finite differences; the root carries the tip load."""
    rows = case.cantilever_rows()
    assert all(r.passed for r in rows), [(r.quantity, r.error) for r in rows]
    system = case.cantilever_system(6)
    mesh = discretize(system)
    assert list(mesh.clamp_elements) == [mesh.line_elements[0][0]]
    assert mesh.clamp_stiffness[0] == pytest.approx(case.CANTILEVER_EI / (0.5 * 10.0 / 6))
    rng = np.random.default_rng(2)
    x = mesh.node_position + 0.05 * rng.normal(size=mesh.node_position.shape)
    x[mesh.point_node[0]] = mesh.node_position[mesh.point_node[0]]
    model = StaticModel(mesh)
    K = model.tangent(x).toarray()
    h = 1e-6
    fd = np.zeros_like(K)
    for j in range(mesh.n_dofs):
        d = np.zeros(mesh.n_dofs)
        d[j] = h
        step = scatter_free(d, mesh.dof_of_node)
        fd[:, j] = -(model.residual(x + step)[0] - model.residual(x - step)[0]) / (2 * h)
    np.testing.assert_allclose(K, fd, atol=1e-6 * np.abs(K).max())
    result = solve_statics(case.cantilever_system(20))
    np.testing.assert_allclose(result.end_force("beam", "a"), (0.0, 0.0, -case.TIP_LOAD),
                               atol=1e-6 * case.TIP_LOAD)


CLAMPED = """
name: cantilever
units: SI
line_types:
  b: {{diameter: 0.1 m, mass_per_length: 1 kg/m, EA: 1e9 N, EI: {EI}}}
points:
  root: {{kind: {root}, position: [0, 0, 0]}}
  tip: {{kind: free, position: [10, 0, 0], mass: 1, force: [0, 0, -100]}}
lines:
  l: {{type: b, length: 10, segments: 10, end_a: root, end_b: tip, clamp_a: {clamp}}}
"""


def test_clamped_end_from_a_case_file(tmp_path: Path) -> None:
    from moorline.errors import CaseError
    from moorline.io import load_case
    from moorline.io.case_writer import write_case

    system = load_case_text(CLAMPED.format(EI="1e6", root="fixed", clamp="[2, 0, 0]"))
    assert system.lines["l"].clamp_a == (2.0, 0.0, 0.0) and system.lines["l"].clamp_b is None
    assert discretize(system).clamp_direction.tolist() == [[1.0, 0.0, 0.0]]
    again = load_case(write_case(system, tmp_path / "c.yaml"))
    assert again.lines["l"].clamp_a == (2.0, 0.0, 0.0)
    for EI, root, clamp, match in (("0", "fixed", "[1, 0, 0]", "needs bending stiffness"),
                                   ("1e6", "free", "[1, 0, 0]", "fixed or prescribed"),
                                   ("1e6", "fixed", "[0, 0, 0]", "nonzero direction")):
        with pytest.raises(CaseError, match=match):
            load_case_text(CLAMPED.format(EI=EI, root=root, clamp=clamp))
    with pytest.raises(CaseError, match="clamped end"):
        write_moordyn(system, tmp_path / "c.dat", 0.001)


def test_body_with_bending_lines_statics_modes_and_hht() -> None:
    """Lines with EI on a free body: the body's balance with the lines' end forces (which
    carry the bending shear at the fairleads) still holds, and the modal and HHT dynamic
    analyses run over the body pattern."""
    from test_bodies import RHO, G, box_system

    from moorline.model import DynamicsSettings, ModalSettings
    from moorline.solvers.dynamics import simulate
    from moorline.solvers.modal import solve_modes

    base = box_system()
    types = {k: dataclasses.replace(v, EI=5.0e6) for k, v in base.line_types.items()}
    system = dataclasses.replace(base, line_types=types)
    result = solve_statics(system)
    assert result.success, result.message
    body = system.bodies["box"]
    lines = sum(result.end_force(f"l{k}", "b") for k in range(4))
    for i in range(2):
        assert lines[i] + body.force[i] == pytest.approx(0.0, abs=1e-6 * body.mass * G)
    plain = solve_statics(base)
    assert np.abs(result.body_position("box") - plain.body_position("box")).max() > 1e-5
    draft = 2.5 - result.body_position("box")[2]
    assert lines[2] + RHO * G * 26 * 10 * draft - body.mass * G == pytest.approx(
        0.0, abs=1e-3 * body.mass * G)
    modes = solve_modes(system, ModalSettings(n_modes=6), result)
    assert modes.success and np.all(modes.omega > 0)
    run = simulate(system, DynamicsSettings(duration=1.0, dt=0.05, scheme="hht", alpha=-0.05),
                   initial=result)
    assert run.success, run.message
    np.testing.assert_allclose(np.asarray(run.positions)[-1], result.positions, atol=1e-3)


def test_bending_moordyn_is_skipped_without_moordyn(monkeypatch) -> None:
    import builtins

    from moorline.verification import core

    real_import = builtins.__import__

    def no_moordyn(name, *args, **kwargs):
        if name.split(".")[0] == "moordyn":
            raise ImportError(name)
        return real_import(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", no_moordyn)
    with pytest.raises(core.CaseSkipped, match=r"\[compare\] extra"):
        core.run_case("bending-moordyn", quick=True)


def test_riser_in_a_current_against_the_closed_form() -> None:
    """(g): the vertical, neutrally buoyant riser in a uniform current (statics with the
    current's drag) offsets as the beam-string under a uniform load; the string alone would
    offset twice as far."""
    row, = case.current_riser_rows()
    assert row.passed, (row.reference, row.computed)
    load = 0.5 * case.WATER * case.RISER_CD * case.RISER_D * case.SPEED**2
    assert row.computed < 0.6 * load * case.SPAN**2 / (8 * case.TENSION)
