"""The sag-corrected chord (moorline.physics.sag, issue 10): exact tangents on every branch,
the catenary convergence it buys against the closed form (moorline.catenary, independent of
the finite elements), and the compiled paths equal to the numpy one."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from scipy.optimize import brentq

from moorline.catenary import solve_catenary
from moorline.mesh import discretize
from moorline.model import Environment, Line, LineType, Point, System
from moorline.physics import element, sag, seabed
from moorline.physics.load_strain import StrainTable, strain_laws
from moorline.solvers.equilibrium import StaticModel
from moorline.solvers.statics import solve_statics
from moorline.solvers.stiffness import full_pattern
from moorline.verification.oc3_line import (
    ANCHOR_R,
    EA,
    FAIR_R,
    FAIR_Z,
    SUBMERGED_WEIGHT,
    closed_form,
    oc3_system,
)

W = SUBMERGED_WEIGHT
X = ANCHOR_R - FAIR_R


def _sagging(system: System) -> System:
    return dataclasses.replace(system, lines={
        k: dataclasses.replace(line, element="sag_corrected")
        for k, line in system.lines.items()})


# ---- exact tangents ----------------------------------------------------------------------

def _chain(offset_table: bool = False) -> System:
    """Three free points and an anchor joined by 10 m sag-corrected elements on a 50 m deep
    seabed (positions are set by the tests)."""
    lt = LineType("c", diameter=0.1, mass_per_length=60.0, EA=5.0e7,
                  EA_table=((0.0, 0.0), (0.01, 4.0e5), (0.03, 1.6e6)) if offset_table
                  else None)
    pts = {"p0": Point("p0", "fixed", (0.0, 0.0, -50.0))}
    pts.update({f"p{i}": Point(f"p{i}", "free", (10.0 * i, 0.0, -40.0)) for i in (1, 2, 3)})
    lines = {f"l{i}": Line(f"l{i}", "c", 10.0, 1, f"p{i}", f"p{i + 1}",
                           element="sag_corrected") for i in range(3)}
    return System("chain", environment=Environment(depth=50.0), line_types={"c": lt},
                  points=pts, lines=lines)


def _height_for(model: StaticModel, node: int, carried: float, depth: float = 50.0) -> float:
    """The height at which the contact spring carries ``carried`` of the node's own load
    (inside the share's band for 0 < carried < 1/2)."""
    load = -model.external[node, 2]
    p = seabed.resting_penetration(np.array([carried * load]),
                                   model.node_seabed_stiffness[node:node + 1],
                                   model.seabed_ramp[node:node + 1])[0]
    return -depth - p


def _branch(name: str, model: StaticModel) -> np.ndarray:
    """Node positions (4, 3) putting the middle element (p1-p2) on a branch of the law."""
    x = np.array([[0.0, 0.0, -50.0], [9.0, 1.0, -49.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]])
    if name == "taut":            # chord 10.05 m, inclined
        x[2] = x[1] + 10.05 * np.array([0.8, 0.1, 0.59]) / np.linalg.norm([0.8, 0.1, 0.59])
    elif name == "near-slack":    # chord 9.97 m: held by its sag, T of the order of W
        x[2] = x[1] + 9.97 * np.array([0.9, 0.2, 0.3]) / np.linalg.norm([0.9, 0.2, 0.3])
    elif name == "touchdown":     # node 1 lying, node 2 lifting off (partly carried)
        x[1, 2] = _height_for(model, 1, 1.0)
        x[2] = x[1] + [10.0, 0.3, 0.0]
        x[2, 2] = _height_for(model, 2, 0.2)
    elif name == "band":          # both nodes partly carried
        x[1, 2] = _height_for(model, 1, 0.4)
        x[2] = x[1] + [9.995, 0.1, 0.0]
        x[2, 2] = _height_for(model, 2, 0.35)
    elif name == "lying":         # both nodes carried: phi = 0, the straight element
        x[1, 2] = _height_for(model, 1, 1.0)
        x[2] = x[1] + [10.002, 0.1, 0.0]
        x[2, 2] = _height_for(model, 2, 0.9)
    elif name == "vertical":      # W_p = 0: the straight element, its direction derivative 0
        x[1] = [9.0, 1.0, -45.0]
        x[2] = x[1] + [0.0, 0.0, 10.03]
    x[3] = x[2] + [9.0, -1.0, 3.0]
    return x


@pytest.mark.parametrize("table", [False, True], ids=["linear", "table+offset"])
@pytest.mark.parametrize("name", ["taut", "near-slack", "touchdown", "band", "lying",
                                  "vertical"])
def test_sag_tangent_matches_central_differences(name: str, table: bool) -> None:
    """``-d(nodal forces)/dx`` of the regularized law by central differences on every branch;
    the tangent is not symmetric where the correction acts (direction and node heights)."""
    mesh = discretize(_chain(table))
    if table:
        mesh = dataclasses.replace(mesh, strain_offset=np.full(mesh.n_elements, -2e-4))
        assert mesh.strain_laws is not None and mesh.strain_laws.active
    model = StaticModel(mesh)
    x = _branch(name, model)
    K = model.tangent(x, full_pattern(mesh)).toarray()
    h = 1e-6
    fd = np.empty_like(K)
    for k in range(K.shape[1]):
        xp, xm = x.copy(), x.copy()
        xp.flat[k] += h
        xm.flat[k] -= h
        fd[:, k] = -(model.forces(xp).nodal - model.forces(xm).nodal).ravel() / (2 * h)
    tolerance = 1e-6 * np.abs(K).max()
    assert np.abs(K - fd).max() <= tolerance
    phi, dphi = model.sag.share(x)
    phi = phi[1]
    T = model.forces(x).tension[1]
    weight = float(mesh.weight_per_length[1] * mesh.length0[1])
    if name == "near-slack":
        assert 0.2 * weight < T < 5 * weight  # really on the sag branch
    if name in ("touchdown", "band"):  # the node-height term is far above the tolerance
        length, unit = element.element_geometry(x, mesh.elements)
        law = model.sag_tension(x, length, unit, mesh.slack_ratio, mesh.slack_smoothing)[0]
        assert 0.0 < phi < 1.0
        assert abs(law.dT_dphi[1]) * np.abs(dphi[1]).max() > 100 * tolerance
    if name == "lying":
        assert phi == 0.0
    if name in ("taut", "near-slack", "touchdown", "band"):
        assert np.abs(K - K.T).max() > 1e-6 * np.abs(K).max()


def test_sag_law_saturates_and_is_monotone_when_slack() -> None:
    """As the chord shortens the tension falls monotonically to 0 (no 1/T^2 blow-up): the
    chord factor stays at or above 1 - SATURATION, and a chord shorter than that is slack."""
    L0, w = 10.0, 600.0
    chord = np.linspace(0.5, 10.02, 400) * L0 / 10.0
    unit = np.tile([1.0, 0.0, 0.0], (len(chord), 1))
    one = np.ones_like(chord)
    law = sag.sag_tension(chord, unit, L0 * one, 5e7 * one, 0 * one, 0.0, w * one, one)
    assert np.all(np.isfinite(law.tension)) and np.all(np.diff(law.tension) >= 0)
    assert np.all(law.factor >= 1 - sag.SATURATION - 1e-12)
    assert np.all(law.tension[chord < (1 - sag.SATURATION) * L0] == 0.0)
    assert law.tension[-1] > 5e7 * 0.002  # taut: more than the straight element's EA eps


def test_no_correction_is_the_straight_law_bit_for_bit() -> None:
    """``phi = 0`` (a straight element, or one lying on the seabed) gives the straight
    element's tension and slope exactly."""
    rng = np.random.default_rng(1)
    n = 50
    length = 10.0 * (1 + rng.uniform(-0.3, 0.01, n))
    unit = rng.normal(size=(n, 3))
    unit /= np.linalg.norm(unit, axis=1)[:, None]
    args = (np.full(n, 10.0), np.full(n, 5e7), np.full(n, 1e-3), 1e-5)
    T, dT = element.axial_tension(length, *args)
    law = sag.sag_tension(length, unit, *args, np.full(n, 500.0), np.zeros(n))
    assert np.array_equal(law.tension, T) and np.array_equal(law.dT_dl, dT)
    assert not np.any(law.dT_dx2)


# ---- against the closed form ---------------------------------------------------------------

def _suspended(segments: int, element_kind: str) -> System:
    """The OC3 line with its anchor raised to 250 m depth: fully suspended."""
    system = oc3_system(segments)
    points = dict(system.points)
    points["anchor"] = dataclasses.replace(points["anchor"], position=(-ANCHOR_R, 0.0, -250.0))
    line = dataclasses.replace(system.lines["line1"], element=element_kind)
    return dataclasses.replace(system, points=points, lines={"line1": line})


def _horizontal_error(segments: int, element_kind: str) -> float:
    exact = solve_catenary(X, FAIR_Z + 250.0, 902.2, EA, W, seabed_contact=False)
    result = solve_statics(_suspended(segments, element_kind))
    assert result.success, result.message
    return abs(result.end_force("line1", "a")[0]) / exact.H - 1.0


def test_suspended_catenary_converges_faster_with_the_sag_correction() -> None:
    """Suspended OC3 line, horizontal tension against the closed form at 10/20/40 elements:
    the error stays second order (ratio ~4 per halving: the lumped weights and the end
    reactions ``chord force + W/2`` keep an O(h^2) term) but its constant falls about six
    times (-0.109 % -> +0.019 % at 20 elements); 20 elements within 0.03 %."""
    straight = {n: _horizontal_error(n, "straight") for n in (20, 40)}
    corrected = {n: _horizontal_error(n, "sag_corrected") for n in (10, 20, 40)}
    assert abs(corrected[20]) <= 3e-4
    ratio = corrected[20] / corrected[40]
    assert 3.5 < ratio < 4.5  # second order
    assert corrected[10] / corrected[20] > 3.5
    for n in (20, 40):
        assert abs(corrected[n]) < abs(straight[n]) / 4


def test_oc3_line_end_forces_within_a_thousandth_at_twenty_elements() -> None:
    """cases/oc3_line.yaml's mesh (20 elements) with the sag correction: anchor and fairlead
    forces within 0.1 % of the closed form (straight elements: -0.160 %)."""
    exact = closed_form()
    result = solve_statics(_sagging(oc3_system(20)))
    assert result.success, result.message
    anchor, fair = result.end_force("line1", "a"), result.end_force("line1", "b")
    assert np.linalg.norm(anchor - [exact.H_a, 0.0, 0.0]) <= 1e-3 * exact.tension_a
    tension_b = np.hypot(exact.H, exact.V_b)
    assert abs(np.linalg.norm(fair) / tension_b - 1.0) <= 1e-3


@pytest.mark.parametrize("segments", [20, 100])
def test_line_tangent_to_the_seabed_at_its_anchor_with_the_sag_correction(segments) -> None:
    """The OC3 geometry with the length whose touchdown is at the anchor: anchor Fz within
    0.1 % of the anchor tension, H within 0.1 %."""
    length = brentq(lambda L: solve_catenary(X, FAIR_Z + 320.0, L, EA, W,
                                             seabed_contact=False).V_a,
                    np.hypot(X, FAIR_Z + 320.0) * 1.0001, 902.2, xtol=1e-9)
    exact = solve_catenary(X, FAIR_Z + 320.0, length, EA, W)
    system = oc3_system(segments)
    system = _sagging(dataclasses.replace(system, lines={
        "line1": dataclasses.replace(system.lines["line1"], length=length)}))
    anchor = solve_statics(system).end_force("line1", "a")
    assert abs(anchor[2]) <= 1e-3 * exact.tension_a
    assert abs(anchor[0] - exact.H_a) <= 1e-3 * exact.tension_a


# ---- compiled paths ------------------------------------------------------------------------

def _touching_state(mesh, model):
    """A perturbed state of a sag-corrected two-line system with nodes in the seabed's share
    band (so ``dphi`` is not zero) and random velocities and accelerations."""
    rng = np.random.default_rng(7)
    start = solve_statics(_fused_system()).positions
    x = start + rng.normal(0.0, 0.05, start.shape) * mesh.free_nodes[:, None]
    lying = np.flatnonzero(mesh.free_nodes & (start[:, 2] < -149.9))
    for k, node in enumerate(lying[:4]):
        x[node, 2] = _height_for(model, node, 0.1 + 0.1 * k, 150.0)  # u = 0.2 to 0.8
    return x, rng.normal(0.0, 0.3, x.shape), rng.normal(0.0, 0.3, x.shape)


def _fused_system() -> System:
    """tests/test_fast_newmark.py's two chains (seabed contact, friction 0.5, a 0.8 m/s
    current, a surging fairlead), sag-corrected."""
    from test_fast_newmark import _system

    return _sagging(_system(0.5, 0.8))


def test_compiled_element_loads_equal_numpy_with_the_sag_correction() -> None:
    """DynamicModel.evaluate, numba kernel against numpy, every output within 1e-12 of its
    largest entry (as tests/test_fused.py), at a state with nodes in the share band."""
    from test_fused import _assert_same

    from moorline.solvers.dynamic_model import DynamicModel
    from moorline.waves import CurrentProfile

    mesh = discretize(_fused_system())
    fluid = CurrentProfile.uniform(0.8, 30.0)
    ref = DynamicModel(mesh, fluid, kernel="numpy")
    new = DynamicModel(mesh, fluid, kernel="numba")
    assert new.kernel == "numba"
    x, v, a = _touching_state(mesh, StaticModel(mesh))
    phi = ref.sag.share(x)[0]
    assert np.any((phi > 0.01) & (phi < 0.99))
    prev = ref.initial_material(x)
    _assert_same(ref.evaluate(x, v, a, 2.0, prev, 0.05, True),
                 new.evaluate(x, v, a, 2.0, prev, 0.05, True))


def test_compiled_step_equals_the_general_stepper_with_the_sag_correction() -> None:
    """The compiled Newmark step (fast_newmark) against the general stepper on sag-corrected
    lines with seabed contact, friction and a current (as tests/test_fast_newmark.py)."""
    from test_fast_newmark import assert_fast_equals_slow

    assert_fast_equals_slow(_fused_system(), duration=8.0)


def test_straight_lines_in_a_mixed_system_keep_the_straight_law() -> None:
    """Only the lines that ask for it are corrected: a straight line's element tensions are
    those of the all-straight model at the same positions, bit for bit."""
    system = _fused_system()
    mixed = dataclasses.replace(system, lines={
        "l1": system.lines["l1"], "l2": dataclasses.replace(system.lines["l2"],
                                                            element="straight")})
    straight = dataclasses.replace(system, lines={
        k: dataclasses.replace(line, element="straight") for k, line in system.lines.items()})
    x = solve_statics(mixed).positions
    t_mixed = StaticModel(discretize(mixed)).forces(x).tension
    t_straight = StaticModel(discretize(straight)).forces(x).tension
    l2 = discretize(mixed).line_elements[1]
    l1 = discretize(mixed).line_elements[0]
    assert np.array_equal(t_mixed[l2], t_straight[l2])
    assert not np.array_equal(t_mixed[l1], t_straight[l1])


def test_strain_table_mesh_is_accepted() -> None:
    """A tabulated law with the sag correction converges (statics of a table line)."""
    system = _sagging(oc3_system(20))
    lt = dataclasses.replace(system.line_types["chain"],
                             EA_table=tuple((e, EA * e * (1 + 20 * e)) for e in
                                            np.linspace(0.0, 0.02, 9)))
    system = dataclasses.replace(system, line_types={"chain": lt})
    assert strain_laws([StrainTable(lt.EA_table)], np.zeros(1, dtype=np.int64)) is not None
    result = solve_statics(system)
    assert result.success, result.message


# ---- case files ----------------------------------------------------------------------------

CASE = """
name: sag
units: SI
environment: {depth: 320}
line_types:
  chain: {diameter: 0.09, mass_per_length: 77.7066, EA: 384.243e6%s}
points:
  anchor: {kind: fixed, position: [-853.87, 0, -320]}
  fairlead: {kind: prescribed, position: [-5.2, 0, -70]}
lines:
  line1: {type: chain, length: 902.2, segments: 20, end_a: anchor, end_b: fairlead,
          element: sag_corrected}
analyses:
  - {kind: statics}%s
"""


def test_case_file_option_round_trips(tmp_path) -> None:
    """``element: sag_corrected`` is read into the model and written back by the case
    writer; the default is ``straight``."""
    from moorline.io.case import load_case, load_case_text
    from moorline.io.case_writer import write_case

    system = load_case_text(CASE % ("", ""))
    assert system.lines["line1"].element == "sag_corrected"
    again = load_case(write_case(system, tmp_path / "sag.yaml"))
    assert again.lines["line1"].element == "sag_corrected"
    assert load_case_text((CASE % ("", "")).replace("element: sag_corrected", "")
                          ).lines["line1"].element == "straight"


@pytest.mark.parametrize(("extra_type", "analysis", "field"), [
    ("", "\n  - {kind: strumming}", "analyses[1].kind"),
    ("", "\n  - {kind: harmonic, period: 10}", "analyses[1].kind"),
    (", material: viscoelastic, EA1: 1.0e8, tau: 5.0", "", "lines.line1.element"),
    (", EAd: 5.0e8", "", "lines.line1.element"),
])
def test_case_file_refuses_what_the_option_cannot_take(extra_type, analysis, field) -> None:
    """Linearized analyses and non-elastic line types are refused naming the key."""
    from moorline.errors import CaseError
    from moorline.io.case import load_case_text

    with pytest.raises(CaseError) as info:
        load_case_text(CASE % (extra_type, analysis))
    assert field in str(info.value)
    assert "sag-corrected" in str(info.value) or "sag_corrected" in str(info.value)


def test_api_refuses_a_harmonic_analysis_of_sag_corrected_lines() -> None:
    """The same refusal through the Python API (moorline.solvers.linearized_laws)."""
    from moorline.errors import CaseError
    from moorline.solvers.linearized_laws import refuse_unlinearized

    with pytest.raises(CaseError, match="sag_corrected"):
        refuse_unlinearized(_sagging(oc3_system(20)), "harmonic")


def test_modal_frequencies_of_sag_corrected_lines_move_towards_the_converged_ones() -> None:
    """The OC3 line's three lowest natural frequencies at 20 elements, sag-corrected, are
    closer to the straight elements' converged values (160 elements, within 0.03 % of 320
    elements' on the first mode) than straight elements at 20 are: the modal analysis takes
    the symmetric part of their tangent (moorline.solvers.modal)."""
    from moorline.model import ModalSettings
    from moorline.solvers.modal import solve_modes

    def omegas(system):
        return np.asarray(solve_modes(system, ModalSettings(n_modes=3),
                                      solve_statics(system)).omega)

    converged = omegas(oc3_system(160))
    straight = np.abs(omegas(oc3_system(20)) / converged - 1)
    corrected = np.abs(omegas(_sagging(oc3_system(20))) / converged - 1)
    assert np.all(corrected < straight), (corrected, straight)
