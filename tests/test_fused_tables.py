"""Tension-strain tables and the fibre-rope dynamic stiffness in the compiled element kernel
(moorline.physics.fused) and the compiled time step (moorline.solvers.fast_newmark), against
the numpy path (moorline.physics.element.axial_tension with the same laws; the reference).

Both evaluate the same piecewise cubic (scipy's PCHIP coefficients) by the same operations, so
the tolerance is round-off: 1e-12 relative per element for the law, 1e-12 of each array's
largest entry for a whole evaluation (as tests/test_fused.py)."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from test_fused import _assert_same

from moorline.io.case import load_case
from moorline.mesh import discretize, dynamic_mesh
from moorline.model import (
    DynamicsSettings,
    Environment,
    Line,
    LineType,
    Motion,
    Point,
    System,
)
from moorline.physics import element, fused
from moorline.physics.load_strain import StrainLaws, StrainTable
from moorline.solvers import dynamics
from moorline.solvers.dynamic_model import DynamicModel
from moorline.solvers.dynamics import simulate
from moorline.solvers.statics import solve_statics
from moorline.waves import CurrentProfile

RTOL = 1e-12
POLYESTER = Path(__file__).parents[1] / "cases" / "polyester_taut.yaml"
MBL = 12.32e6  # N, the polyester case's rope


def _tables() -> tuple[StrainTable, StrainTable]:
    """A stiffening curve with uneven intervals and a softening-then-stiffening one with a flat
    stretch (PCHIP's zero-slope knots)."""
    e = np.array([0.0, 0.002, 0.005, 0.006, 0.012, 0.02, 0.04])
    stiff = StrainTable(np.c_[e, MBL * (10 * e + 250 * e**2)])
    other = StrainTable([[0.0, 0.0], [0.01, 2e5], [0.02, 3e5], [0.025, 3e5], [0.03, 4.5e5],
                         [0.05, 1.2e6]])
    return stiff, other


def _strains(table: StrainTable, smoothing: float, rng: np.random.Generator) -> np.ndarray:
    """Strains in every interval of ``table`` (interior points and the breakpoints
    themselves), beyond its last point, in the slack band and in compression."""
    knots = table.points[:, 0]
    inside = [rng.uniform(a, b, 7) for a, b in zip(knots[:-1], knots[1:], strict=True)]
    beyond = knots[-1] + rng.uniform(0.0, 0.05, 7)
    band = rng.uniform(-1.0, 1.0, 5) * smoothing
    slack = -rng.uniform(2 * smoothing + 1e-6, 0.02, 5)
    return np.concatenate(inside + [knots, beyond, band, slack])


@pytest.mark.parametrize("smoothing", [0.0, 1e-5, 2e-3])
@pytest.mark.parametrize("slack_ratio", [0.0, 1e-3])
@pytest.mark.parametrize("with_offset", [False, True])
def test_kernel_law_equals_numpy_axial_tension(smoothing, slack_ratio, with_offset):
    """Per element, elements on the x axis (so the chord length is exact in both): the
    kernel's tension equals ``element.axial_tension``'s and its tangent ``K[0, 0] = dT/dl``
    its derivative, over compression, the slack band, every table interval, every
    breakpoint and the linear extrapolation, for two tables and linear elements mixed."""
    rng = np.random.default_rng(int(1e6 * smoothing) + int(1e3 * slack_ratio) + with_offset)
    tables = _tables()
    strains, ids = [], []
    for k, table in enumerate(tables):
        for law in (k, -1):  # the same strains through the table and the linear law
            s = _strains(table, smoothing, rng)
            strains.append(s)
            ids.append(np.full(len(s), law))
    strain = np.concatenate(strains)
    ids = np.concatenate(ids).astype(np.int64)
    n = len(strain)
    laws = StrainLaws(tables, ids)
    L0 = rng.uniform(1.0, 60.0, n)
    EA = np.where(ids >= 0, np.array([t.max_slope for t in tables])[ids],
                  rng.uniform(1e6, 2e8, n))
    offset = rng.uniform(-2e-3, 2e-3, n) if with_offset else None
    length = L0 * (1.0 + strain + (0.0 if offset is None else offset))
    T, dT = element.axial_tension(length, L0, EA, slack_ratio, smoothing, laws=laws,
                                  offset=offset)
    x = np.zeros((2 * n, 3))
    x[1::2, 0] = length
    zero = np.zeros_like(x)
    r = fused.element_loads(x, zero, zero, 0.0, 0.0, np.arange(2 * n).reshape(n, 2), L0, EA,
                            slack_ratio, smoothing, 0.0, 0.1, 0.0, 0.0, 0.0, 0.0, 0.0,
                            tangent=True, with_added_mass=False, with_drag=False, laws=laws,
                            offset=offset)
    assert np.all(np.abs(r.tension - T) <= RTOL * np.abs(T))
    assert np.all(np.abs(r.K[:, 0, 0] - dT) <= RTOL * np.abs(dT))
    np.testing.assert_array_equal(r.strain, length / L0 - 1.0)  # without the offset
    # the laws differ where a table is used: the comparison is not of the linear law twice
    tabled = (ids >= 0) & (strain > 0.001)
    assert np.mean(np.abs(T - EA * strain)[tabled] > 1e-3 * np.abs(T[tabled])) > 0.9


def _mixed_system(current: float = 0.0) -> System:
    """A free junction buoy held by a polyester rope with a table, a polyester rope with the
    table and a dynamic stiffness, and a chain with a constant EA, driven from a prescribed
    fairlead by a fourth (table) rope."""
    stiff, _ = _tables()
    table = tuple(map(tuple, stiff.points.tolist()))
    rope = dict(diameter=0.16, mass_per_length=27.2, EA=stiff.max_slope, Cd=1.6, Ct=0.01,
                Ca=1.0, Cat=0.0, BA=-0.8, EA_table=table)
    types = {"poly": LineType("poly", **rope),
             "polyd": LineType("polyd", **rope, EAd=11.6 * MBL, EAd_Lm=40.0),
             "chain": LineType("chain", diameter=0.09, mass_per_length=77.7, EA=3.8e8,
                               Cd=1.6, Ct=0.05, Ca=1.0, Cat=0.1, BA=-0.8)}
    motion = Motion("harmonic", amplitude=(3.0, 1.0, 0.5), period=10.0, ramp_time=5.0)
    points = {"a1": Point("a1", "fixed", (-700.0, 0.0, -400.0)),
              "a2": Point("a2", "fixed", (350.0, 600.0, -400.0)),
              "a3": Point("a3", "fixed", (350.0, -600.0, -400.0)),
              "j": Point("j", "free", (0.0, 0.0, -60.0), volume=60.0),
              "f": Point("f", "prescribed", (0.0, 0.0, -10.0), motion=motion)}
    lines = {"l1": Line("l1", "poly", 770.0, 12, "a1", "j"),
             "l2": Line("l2", "polyd", 765.0, 10, "a2", "j"),
             "l3": Line("l3", "chain", 800.0, 10, "a3", "j"),
             "up": Line("up", "poly", 49.5, 4, "j", "f")}
    env = Environment(depth=400.0)
    if current:
        from moorline.model import Current

        env = replace(env, current=Current(speed=current, heading_deg=20.0))
    return System("mixed", environment=env, line_types=types, points=points, lines=lines)


def test_mixed_system_evaluate_numba_equals_numpy():
    """A whole ``DynamicModel.evaluate`` (tension, forces, K, C, Ma) of a system with table,
    dynamic-stiffness and linear lines about a perturbed static state, in a current."""
    system = _mixed_system()
    statics = solve_statics(system)
    assert statics.success, statics.message
    mesh = dynamic_mesh(statics.mesh, statics.positions)
    assert mesh.strain_laws.active and mesh.strain_offset is not None
    fluid = CurrentProfile.uniform(0.6, 20.0, ramp_time=10.0)
    ref = DynamicModel(mesh, fluid, kernel="numpy")
    new = DynamicModel(mesh, fluid, kernel="numba")
    assert ref.kernel == "numpy" and new.kernel == "numba"
    rng = np.random.default_rng(3)
    free = mesh.free_nodes
    for scale in (0.0, 0.5, 3.0):  # the static state, then stretched and slackened elements
        x = statics.positions.copy()
        x[free] += rng.normal(0.0, scale, (int(free.sum()), 3))
        v = rng.normal(0.0, 0.5, x.shape)
        a = rng.normal(0.0, 0.5, x.shape)
        material = ref.initial_material(x)
        for tangent in (True, False):
            args = (x, v, a, 2.0, material, 0.1, tangent)
            _assert_same(ref.evaluate(*args), new.evaluate(*args))


@pytest.mark.parametrize("current", [0.0, 0.7])
def test_mixed_system_compiled_step_equals_the_general_stepper(current):
    """The compiled Newmark step (fast_newmark) on the mixed system, step by step against
    the general stepper with the numpy kernel (same counters, same states)."""
    system = _mixed_system(current)
    start = solve_statics(system)
    settings = DynamicsSettings(duration=8.0, dt=0.05, ramp_time=5.0)
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(dynamics, "DynamicModel", _numpy_model)
        slow = simulate(system, replace(settings, fast_path=False), initial=start,
                        output_every=settings.dt)
    fast = simulate(system, replace(settings, fast_path=True), initial=start,
                    output_every=settings.dt)
    _assert_same_runs(slow, fast)


def _numpy_model(*args, **kwargs) -> DynamicModel:
    return DynamicModel(*args, **kwargs, kernel="numpy")


def _assert_same_runs(slow, fast) -> None:
    """The tolerances of tests/test_fast_newmark.py (Newton's tolerance leaves the states
    equal to far better than these; the step-by-step agreement is what is checked)."""
    assert slow.success and fast.success
    scale = float(np.abs(slow.positions).max())
    assert np.allclose(fast.positions, slow.positions, rtol=0, atol=1e-7 * scale)
    assert np.allclose(fast.tension, slow.tension, rtol=1e-6, atol=1e-6 * slow.tension.max())
    for key in ("steps", "iterations", "factorizations"):
        assert fast.counters[key] == slow.counters[key], key


def test_polyester_case_with_its_waves_numba_kernel_equals_numpy():
    """cases/polyester_taut.yaml as written (random sea: the general stepper), 40 steps, with
    the compiled element kernel and with the numpy one."""
    system = load_case(POLYESTER)
    settings = next(a for a in system.analyses if isinstance(a, DynamicsSettings))
    settings = replace(settings, duration=40 * settings.dt)
    start = solve_statics(system)
    assert start.success, start.message
    new = simulate(system, settings, initial=start, output_every=settings.dt)
    assert new.counters.get("steps") == 40
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(dynamics, "DynamicModel", _numpy_model)
        ref = simulate(system, settings, initial=start, output_every=settings.dt)
    _assert_same_runs(ref, new)


def test_table_and_dynamic_stiffness_meshes_use_the_compiled_kernel():
    """The default kernel takes the static mesh (tables) and the dynamic one (strain
    offsets), and viscoelastic lines with the exponential update; with the incremental one
    they go to numpy."""
    system = _mixed_system()
    start = solve_statics(system)
    still = CurrentProfile.uniform(0.0)
    assert DynamicModel(start.mesh, still).kernel == "numba"
    assert DynamicModel(dynamic_mesh(start.mesh, start.positions), still).kernel == "numba"
    chain = replace(system.line_types["chain"], material="viscoelastic", EA1=1e8, tau=5.0)
    sls = replace(system, line_types=dict(system.line_types, chain=chain))
    assert DynamicModel(discretize(sls), still).kernel == "numba"
    assert DynamicModel(discretize(sls), still, "incremental").kernel == "numpy"
