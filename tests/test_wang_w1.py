"""Wang, Er and Iu case W1: static draft of the moored box by the paper's parabolic formulas,
the exact catenary and the coupled finite elements; the builders reused by W2/W3."""

import math

import numpy as np
import pytest

from moorline.catenary import solve_catenary
from moorline.verification import wang_w1 as w1


@pytest.fixture(scope="module")
def rows():
    return w1.run()


def test_rows_pass(rows):
    assert len(rows) >= 6
    failed = [(r.quantity, r.reference, r.computed, r.error, r.tolerance) for r in rows
              if r.status == "fail"]
    assert not failed, failed


def test_paper_formula_reproduces_printed_draft():
    assert w1.parabolic_draft() == pytest.approx(0.896, abs=5e-4)
    # the readings that do not reproduce it (documented in the module)
    assert w1.parabolic_draft(weight=w1.DRY_WEIGHT) == pytest.approx(0.962, abs=1e-3)
    assert w1.parabolic_draft(sag="vertical") > 1.0


def test_parabolic_draft_solves_eq_1():
    """The closed form satisfies eq. (1) with the line forces on its own chord."""
    for ratio, angle in [(1 / 60, 50.0), (1 / 45, 40.0), (1 / 80, 54.0)]:
        hs = w1.parabolic_draft(ratio, angle)
        chord = (w1.DEPTH - hs) / math.sin(math.radians(angle))
        V = w1.parabolic_top_force(chord, angle, ratio, w1.WEIGHT)[2]
        buoyancy = w1.RHO * w1.G * hs * w1.WATERPLANE
        assert buoyancy - w1.BOX_MASS * w1.G - 4 * V == pytest.approx(0.0, abs=1e-6 * buoyancy)


def test_parabolic_forces_match_inextensible_catenary_in_small_sag_limit():
    """Independent check: an inextensible catenary through the same ends, its sag measured
    at mid-chord perpendicular to the chord; the parabolic H and top V agree to O((d/l)^2)."""
    X, Z, chord = w1.chord_geometry(0.9)
    errors = []
    for excess in (1e-3, 1e-4, 1e-5):
        line = solve_catenary(X, Z, chord * (1 + excess), math.inf, w1.WEIGHT,
                              seabed_contact=False)
        ratio = w1.mid_chord_sag(line) / chord
        _, H, V = w1.parabolic_top_force(chord, 50.0, ratio, w1.WEIGHT)
        eh, ev = H / line.H - 1, V / line.V_b - 1
        assert abs(eh) < 3 * ratio**2 and abs(ev) < 15 * ratio**2, (ratio, eh, ev)
        errors.append((ratio, abs(ev)))
    (r0, e0), (r1, e1) = errors[0], errors[-1]
    assert math.log(e0 / e1) / math.log(r0 / r1) == pytest.approx(2.0, abs=0.15)


@pytest.mark.parametrize("ratio,angle", [(1 / 45, 50.0), (1 / 80, 50.0), (1 / 60, 40.0),
                                         (1 / 60, 54.0)])
def test_catenary_line_has_requested_sag(ratio, angle):
    line = w1.catenary_line(0.9, ratio, angle)
    X, Z, chord = w1.chord_geometry(0.9, angle)
    assert (line.horizontal_span, line.vertical_span) == pytest.approx((X, Z))
    assert w1.mid_chord_sag(line) == pytest.approx(ratio * chord, rel=1e-9)
    assert line.V_a > 0  # hangs free of the seabed


def test_system_geometry():
    draft = 0.9
    system = w1.wang_system(draft=draft)
    body = system.bodies["box"]
    assert body.position == pytest.approx((0.0, 0.0, 2.5 - draft))
    length = w1.catenary_line(draft).length
    for k, name in enumerate("ABCD"):
        fair = np.array(system.points[name].position)
        anchor = np.array(system.points[f"anchor{name}"].position)
        assert abs(fair[0]) == 13.0 and abs(fair[1]) == 5.0 and fair[2] == -2.5
        world = fair + np.array(body.position)
        d = world - anchor
        assert anchor[2] == -100.0
        assert math.degrees(math.atan2(d[2], math.hypot(d[0], d[1]))) == pytest.approx(50.0)
        # diagonal layout: the line lies in the vertical plane through the centre and corner
        assert d[0] * fair[1] - d[1] * fair[0] == pytest.approx(0.0, abs=1e-9)
        assert system.lines[f"C{k + 1}"].length == pytest.approx(length)
        assert system.lines[f"C{k + 1}"].segments == 11


def test_equilibrium_is_a_fixed_point_and_layout_independent():
    eq = w1.wang_equilibrium()
    res = eq.result
    assert 2.5 - res.body_position("box")[2] == pytest.approx(eq.draft, abs=1e-8)
    assert np.abs(res.body_rotation("box")).max() < 1e-10
    assert np.abs(res.body_position("box")[:2]).max() < 1e-8
    # the anchors of the returned system belong to the solved draft
    anchor = np.array(eq.system.points["anchorA"].position)
    fair = res.point_position("A")
    assert fair[2] == pytest.approx(-eq.draft, abs=1e-8)
    d = fair - anchor
    assert math.degrees(math.atan2(d[2], math.hypot(d[0], d[1]))) == pytest.approx(50.0)
    par = w1.wang_equilibrium(layout="parallel")
    assert par.draft == pytest.approx(eq.draft, abs=1e-8)
    assert np.abs(par.result.body_rotation("box")).max() < 1e-10


@pytest.mark.parametrize("ratio,angle", [(1 / 45, 50.0), (1 / 80, 50.0), (1 / 60, 40.0),
                                         (1 / 60, 54.0)])
def test_w3_range_equilibria(ratio, angle):
    """The builders work over the W3 study; the FE draft stays within its O(h^2) estimate of
    the exact catenary's."""
    eq = w1.wang_equilibrium(ratio, angle)
    exact, _ = w1.catenary_draft(ratio, angle)
    predicted = w1.discretization_estimate(w1.catenary_line(eq.draft, ratio, angle), 11, angle)[1]
    assert eq.draft - exact == pytest.approx(predicted, rel=0.25)


def test_case_file_is_the_equilibrium_system():
    """cases/wang_box.yaml holds the finite element fixed point; it solves to the same draft."""
    from pathlib import Path

    from moorline.io import load_case
    from moorline.solvers.statics import solve_statics

    path = Path(__file__).resolve().parents[1] / "cases" / "wang_box.yaml"
    system = load_case(path)
    eq = w1.wang_equilibrium()
    for name, point in eq.system.points.items():
        assert system.points[name].kind == point.kind
        assert system.points[name].position == pytest.approx(point.position, abs=1e-9)
    for name, line in eq.system.lines.items():
        assert system.lines[name].length == pytest.approx(line.length, rel=1e-12)
    assert system.bodies["box"].position == pytest.approx(eq.system.bodies["box"].position)
    result = solve_statics(system)
    assert result.success
    assert 2.5 - result.body_position("box")[2] == pytest.approx(eq.draft, abs=1e-8)
