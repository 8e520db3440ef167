"""The statics start (issue 14, hard statics): the finite elements' own catenary, the U-shape
of a line touching the seabed between its ends, and the free points' catenary equilibrium."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from moorline.catenary import catenary_3d, solve_catenary
from moorline.catenary_touching import solve_touching, touching_3d
from moorline.mesh import discretize
from moorline.model import Environment, Line, LineType, Point, Seabed, System
from moorline.solvers.discrete_shape import discrete_catenary
from moorline.solvers.equilibrium import StaticModel
from moorline.solvers.initial_shape import initial_positions
from moorline.solvers.statics import solve_statics

ROOT = Path(__file__).resolve().parents[1]
W, EA = 2000.0, 5.0e8  # N/m submerged, N


def _line_system(a, b, length: float, segments: int, depth: float = 300.0,
                 kind_b: str = "fixed") -> System:
    chain = LineType("chain", diameter=0.1, mass_per_length=W / 9.80665 + 1025 * math.pi
                     * 0.0025, EA=EA)
    env = Environment(depth=depth, water_density=1025.0, gravity=9.80665,
                      seabed=Seabed(stiffness=3.0e6, damping=0.0, friction=0.0))
    points = {"a": Point("a", "fixed", tuple(a)), "b": Point("b", kind_b, tuple(b))}
    return System("start", environment=env, line_types={"chain": chain}, points=points,
                  lines={"l": Line("l", "chain", length, segments, "a", "b")})


def test_discrete_catenary_balances_every_interior_node() -> None:
    """A suspended line in 8 elements of 50 m (long against its curvature): the start is the
    finite elements' equilibrium, interior residual at round-off, while the continuous
    catenary's nodes leave out of balance forces of the order of a node's weight."""
    system = _line_system((0, 0, -300.0), (330.0, 0, -20.0), 400.0, 8, depth=1000.0)
    mesh = discretize(system)
    model = StaticModel(mesh, exact_cable=True)
    x = initial_positions(system, mesh)
    R, _ = model.residual(x)
    node_weight = W * 50.0
    assert np.abs(R).max() < 1e-7 * node_weight  # the end closes to 1e-11 of the length
    fa, fb, sol = catenary_3d((0, 0, -300.0), (330.0, 0, -20.0), 400.0, EA, W)
    from moorline.catenary import profile_3d

    smooth = x.copy()
    smooth[1:-1] = profile_3d(sol, (0, 0, -300.0), (330.0, 0, -20.0),
                              np.linspace(0, 400.0, 9))[1:-1]
    assert np.abs(model.residual(smooth)[0]).max() > 0.05 * node_weight


def test_discrete_catenary_converges_to_the_closed_form_with_refinement() -> None:
    """The force on end B (the top element's tension plus the half element's weight lumped
    on B) approaches the continuous catenary's as O(h^2)."""
    a, b, L = np.zeros(3), np.array([330.0, 0.0, 280.0]), 400.0
    _, _, sol = catenary_3d(a, b, L, EA, W)
    errors = []
    for n in (10, 20, 40):
        x = discrete_catenary(a, b, n, L, EA, W, False, sol.H, sol.V_b)
        assert x is not None and np.allclose(x[-1], b, atol=1e-9)
        d = x[-1] - x[-2]
        top = EA * (np.linalg.norm(d) / (L / n) - 1.0) * d / np.linalg.norm(d)
        reaction = math.hypot(math.hypot(top[0], top[1]), top[2] + 0.5 * W * L / n)
        errors.append(abs(reaction - sol.tension_b))
    assert errors[0] / errors[1] == pytest.approx(4.0, rel=0.1)
    assert errors[1] / errors[2] == pytest.approx(4.0, rel=0.1)


def test_touching_symmetric_is_two_contact_catenaries() -> None:
    """A U-shape with both ends 100 m above the seabed 600 m apart, 700 m long: each half is
    the seabed-contact catenary of half the line from the midpoint (solve_catenary)."""
    sol = solve_touching(600.0, 100.0, 100.0, 700.0, EA, W)
    assert sol is not None and sol.H > 0 and sol.lying_length > 0
    half = solve_catenary(300.0, 100.0, 350.0, EA, W)
    assert sol.H == pytest.approx(half.H, rel=1e-9)
    assert -sol.force_a[1] == pytest.approx(half.V_b, rel=1e-9)
    assert sol.lying_length == pytest.approx(2 * half.seabed_length, rel=1e-8)
    h, z = sol.profile(np.array([0.0, 350.0, 700.0]))
    assert h == pytest.approx([0.0, 300.0, 600.0], abs=1e-6)
    assert z == pytest.approx([0.0, -100.0, 0.0], abs=1e-6)


def test_touching_tends_to_the_contact_catenary_as_an_end_comes_down() -> None:
    """An end 1 mm above the seabed: the U-shape's forces are the contact catenary's from
    that end (the presolve's two models meet there)."""
    pa, pb = np.array([0.0, 0.0, -299.999]), np.array([400.0, 0.0, -100.0])
    touching = touching_3d(pa, pb, 600.0, EA, W, -300.0)
    assert touching is not None
    fa, fb, _ = catenary_3d(pa, pb, 600.0, EA, W, seabed_contact=True)
    assert touching[1] == pytest.approx(fb, rel=1e-4)
    assert touching[0][0] == pytest.approx(fa[0], rel=1e-4)


def test_touching_is_none_when_the_line_clears_the_seabed() -> None:
    assert solve_touching(500.0, 200.0, 200.0, 560.0, EA, W) is None  # taut, clears
    assert solve_touching(500.0, 100.0, 100.0, 150.0, EA, W) is None  # too short to reach


def test_u_shaped_line_starts_in_balance_and_converges_fast() -> None:
    """A line between two fixed points above the seabed lying in the middle: Newton from the
    start needs only a few iterations, and the end forces converge to the closed-form
    U-shape with the mesh (the error at 70 elements under half that at 35)."""
    exact = solve_touching(600.0, 100.0, 100.0, 700.0, EA, W)
    errors = []
    for segments in (35, 70):
        result = solve_statics(_line_system((0, 0, -200.0), (600.0, 0, -200.0), 700.0,
                                            segments))
        assert result.success, result.message
        assert result.iterations <= 8
        fb = result.end_force("l", "b")
        errors.append(max(abs(-fb[0] / exact.H - 1.0),
                          abs(-fb[2] / (W * exact.hanging_b) - 1.0)))
    assert errors[1] < 0.5 * errors[0] and errors[1] < 0.01


@pytest.mark.compare
def test_case6_free_points_presolve_equals_moorpy() -> None:
    """MoorPy's W-shaped ``case6`` deck (a buoy and a connector on three lines touching the
    seabed): the catenary presolve of the free points against MoorPy's solveEquilibrium on
    the same deck (both closed-form catenaries: 1 cm), and the finite-element statics
    converges with the defaults."""
    moorpy = pytest.importorskip("moorpy")
    from moorline.io.moordyn import read_moordyn
    from moorline.solvers.point_start import presolve_free_points

    deck = ROOT / "tests" / "data" / "moordyn" / "public" / "MoorPy" / "tests" / "case6.dat"
    system = read_moordyn(deck)
    mesh = discretize(system)
    solved = presolve_free_points(system, mesh, mesh.node_prescribed_start.copy())
    assert solved is not None
    raw = deck.read_text().split("\n", 1)[1]  # the copy's first line is its origin note
    import tempfile

    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "case6.dat"
        path.write_text(raw)
        ms = moorpy.System(file=str(path))
        ms.initialize()
        ms.solveEquilibrium(tol=1e-6, maxIter=2000)
    for k, name in enumerate(mesh.point_names):
        if mesh.point_kind[k] == "free":
            number = int(name.removeprefix("point"))
            ref = next(p.r for p in ms.pointList if p.number == number)
            assert np.linalg.norm(solved[mesh.point_node[k]] - ref) < 0.01, name
    result = solve_statics(system)
    assert result.success and result.iterations <= 10, result.message


@pytest.mark.parametrize("H", [0.0, 1.0e-3, 50.0, 2.0e3, 1.0e5, 1.0e9])
def test_hanging_length_is_the_root_of_the_closed_form_height(H: float) -> None:
    """The length hanging from a touchdown to a height h (Newton from the inextensible root)
    gives back h through the closed-form elastic catenary (Irvine 1981 eq. 1.22, written
    here): z(s) = (H/w)(sqrt(1 + (w s/H)^2) - 1) + w s^2/(2 EA), z = s + w s^2/(2 EA) at H = 0."""
    from moorline.catenary_touching import _hanging_length

    w, EA = 700.0, 3.0e6  # a soft line: the elastic term matters
    for h in (0.5, 30.0, 300.0):
        s = _hanging_length(h, H, w, EA)
        b = w * s / H if H else 0.0  # (H/w)(sqrt(1 + b^2) - 1) without the cancellation:
        z = (s if H == 0.0 else H / w * b * b / (1.0 + math.sqrt(1.0 + b * b))) \
            + w * s * s / (2.0 * EA)
        assert z == pytest.approx(h, rel=1e-12), (h, H)
