"""Kernel speed benchmark: the speed-ups the tests used to assert, measured and printed.

The unit tests check that each vectorized or compiled kernel gives the right numbers; how
fast they are depends on the machine and its load, so it is measured here (``make bench``)
and never asserted. Each line prints the best-of-``repeat`` wall time of the fast path, of a
slow path computing the same thing, and their ratio (the speed-up). The former test bounds
are printed for comparison ("target"), not enforced:

* fused element loads (numba) vs the numpy path on 60 elements: element loads >= 10x, the
  whole ``DynamicModel.evaluate`` >= 5x (was tests/test_fused.py); the same with a
  tension-strain table on every line (PCHIP law evaluated in the kernel), and a time-domain run
  of ``cases/polyester_taut.yaml`` in still water (table statics, fibre-rope dynamic stiffness)
  by the compiled step against the general stepper on the numpy kernel (no target);
* hydrodynamic kernels on 1e5 elements (was tests/test_hydro.py: each < 0.1 s), against a
  Python loop over single-element calls (timed on a sample, scaled);
* standard-linear-solid updates on 1e5 elements (was tests/test_material.py: < 10 ms),
  against single-element calls;
* Airy kinematics at 1e5 points (was tests/test_waves.py: < 50 ms), against single points;
* 1000 elastic-catenary solves (was tests/test_catenary.py: < 2 s), against MoorPy's
  ``catenary`` on the same geometries when the ``[compare]`` extra is installed.

Run: ``python benchmarks/bench_kernels.py [--quick]``.
"""

from __future__ import annotations

import argparse
import math
import time
from collections.abc import Callable

import numpy as np

from moorline.catenary import solve_catenary
from moorline.mesh import discretize
from moorline.model import Environment, Line, LineType, Point, System
from moorline.physics import element, fused, hydro
from moorline.physics.material import sls_update_exponential, sls_update_incremental
from moorline.solvers.dynamic_model import DynamicModel
from moorline.waves import AiryWave, CurrentProfile

RNG = np.random.default_rng(11)
RHO, G = 1025.0, 9.81


def best_of(fun: Callable[[], object], number: int = 1, repeat: int = 5) -> float:
    """Smallest mean wall time of ``number`` calls over ``repeat`` tries, after a warm-up."""
    fun()
    best = math.inf
    for _ in range(repeat):
        start = time.perf_counter()
        for _ in range(number):
            fun()
        best = min(best, (time.perf_counter() - start) / number)
    return best


def report(name: str, fast: float, slow: float, target: str) -> None:
    """One line: fast and slow times, their ratio and the former test's bound."""
    print(f"  {name:<34s} {fast * 1e3:10.3f} ms {slow * 1e3:11.3f} ms {slow / fast:9.1f}x"
          f"   {target}")


def _four_lines(n: int, table: bool = False) -> System:
    """Four taut-ish ropes from seabed anchors to prescribed fairleads, all hydrodynamic
    coefficients and the internal damping nonzero (the kernels' full path); ``table``: their
    law a stiffening tension-strain table (tangent 2e6 at the origin) instead of ``EA``."""
    law = {}
    if table:
        eps = np.linspace(0.0, 0.05, 11)
        law = {"EA_table": tuple(zip(eps.tolist(), (2.0e6 * eps * (1 + 20 * eps)).tolist(),
                                     strict=True))}
    lt = LineType("rope", diameter=0.05, mass_per_length=8.0, EA=2.0e6, Cd=1.2, Ct=0.4,
                  Ca=1.0, Cat=0.3, BA=2.0e4, **law)
    pts, lines = {}, {}
    for k, ang in enumerate(np.deg2rad([0.0, 90.0, 180.0, 270.0])):
        c, s = math.cos(ang), math.sin(ang)
        pts[f"A{k}"] = Point(f"A{k}", "fixed", (300.0 * c, 300.0 * s, -100.0))
        pts[f"F{k}"] = Point(f"F{k}", "prescribed", (10.0 * c, 10.0 * s, -5.0))
        lines[f"l{k}"] = Line(f"l{k}", "rope", 310.0, n, f"A{k}", f"F{k}")
    return System("bench", environment=Environment(depth=100.0), line_types={"rope": lt},
                  points=pts, lines=lines)


def bench_fused(repeat: int, table: bool = False) -> None:
    mesh = discretize(_four_lines(15, table))
    assert table == (mesh.strain_laws is not None)
    fluid = CurrentProfile.uniform(0.5, 30.0)
    ref = DynamicModel(mesh, fluid, kernel="numpy")
    new = DynamicModel(mesh, fluid, kernel="numba")
    if new.kernel != "numba":
        print("  fused: numba kernel not available, skipped")
        return
    x = mesh.node_position + RNG.normal(0.0, 0.05, mesh.node_position.shape)
    v = RNG.normal(0.0, 0.5, x.shape)
    a = RNG.normal(0.0, 0.5, x.shape)
    material = ref.initial_material(x)
    args = (x, v, a, 1.0, material, 0.1, True)
    mid = fused.midpoints(x, mesh.elements)
    uf, af, _ = fluid.kinematics(mid, 1.0)

    def numpy_element_loads() -> None:  # the element part of evaluate on the numpy path
        el = mesh.elements
        length, unit = element.element_geometry(x, el)
        dv = v[el[:, 1]] - v[el[:, 0]]
        T, dT_dl, _, share, _ = ref._axial_tension(x, length, unit, dv, material, 0.1)
        forces = element.nodal_forces(T, unit).copy()
        out = {"K": ref._axial_tangent(length, unit, dv, T, dT_dl, share),
               "C": np.zeros((len(T), 6, 6))}
        forces, out = ref._morison(x, v, a, uf, af, forces, out, True)
        hydro.sum_to_nodes(out.pop("f_am"), el, mesh.n_nodes)
        hydro.sum_to_nodes(forces, el, mesh.n_nodes)

    law = "tension-strain table" if table else "constant EA"
    print(f"fused element kernel, {mesh.n_elements} elements ({law}), tangent on:")
    targets = ("(no target)",) * 2 if table else ("target >= 10x", "target >= 5x")
    report("element loads (numba vs numpy)",
           best_of(lambda: new._fused(x, v, a, uf, af, True), 1000, repeat),
           best_of(numpy_element_loads, 100, repeat), targets[0])
    report("DynamicModel.evaluate",
           best_of(lambda: new.evaluate(*args), 1000, repeat),
           best_of(lambda: ref.evaluate(*args), 100, repeat), targets[1])


def bench_polyester_run(quick: bool) -> None:
    """cases/polyester_taut.yaml without its waves (the compiled step takes still water), a
    few seconds of its dynamics: the compiled step against the general stepper on the numpy
    kernel (the reference path of tables and strain offsets before the kernel took them)."""
    from dataclasses import replace
    from pathlib import Path

    from moorline.io.case import load_case
    from moorline.model import DynamicsSettings, Waves
    from moorline.solvers import dynamics
    from moorline.solvers.statics import solve_statics

    path = Path(__file__).parents[1] / "cases" / "polyester_taut.yaml"
    system = load_case(path)
    system = replace(system, environment=replace(system.environment, waves=Waves()))
    settings = next(a for a in system.analyses if isinstance(a, DynamicsSettings))
    settings = replace(settings, duration=2.0 if quick else 10.0)
    start = solve_statics(system)
    compiled = replace(settings, fast_path=True)
    fast = best_of(lambda: dynamics.simulate(system, compiled, initial=start), 1, 2)

    def numpy_run() -> None:
        model = dynamics.DynamicModel
        dynamics.DynamicModel = lambda *a, **k: model(*a, **k, kernel="numpy")
        try:
            dynamics.simulate(system, replace(settings, fast_path=False), initial=start)
        finally:
            dynamics.DynamicModel = model

    n_steps = round(settings.duration / settings.dt)
    print(f"polyester_taut in still water, {n_steps} steps of dt = {settings.dt:g} s:")
    report("compiled step vs numpy stepper", fast, best_of(numpy_run, 1, 2), "(no target)")


def _loop_time(single: Callable[[int], object], n_total: int, sample: int,
               repeat: int) -> float:
    """Time of ``n_total`` single-element calls, measured on ``sample`` of them and scaled."""
    def run() -> None:
        for i in range(sample):
            single(i)
    return best_of(run, 1, repeat) * n_total / sample


def bench_hydro(n_el: int, sample: int, repeat: int) -> None:
    x = np.cumsum(RNG.normal(size=(n_el + 1, 3)), axis=0)
    elements = np.column_stack((np.arange(n_el), np.arange(1, n_el + 1)))
    v = RNG.normal(size=x.shape)
    uf = RNG.normal(size=(n_el, 3))
    L0 = np.ones(n_el)
    D, CD, CT = 0.08, 1.2, 0.4
    one = np.array([[0, 1]])
    calls = {
        "drag": (lambda: hydro.drag_forces(x, v, uf, elements, L0, D, CD, CT, RHO),
                 lambda i: hydro.drag_forces(x[i:i + 2], v[i:i + 2], uf[i:i + 1], one,
                                             L0[:1], D, CD, CT, RHO)),
        "added_mass": (lambda: hydro.added_mass_blocks(x, elements, L0, D, 1.0, 0.1, RHO),
                       lambda i: hydro.added_mass_blocks(x[i:i + 2], one, L0[:1], D, 1.0,
                                                         0.1, RHO)),
        "added_mass_dx": (lambda: hydro.added_mass_position_derivative(
            x, v, elements, L0, D, 1.0, 0.1, RHO),
            lambda i: hydro.added_mass_position_derivative(x[i:i + 2], v[i:i + 2], one,
                                                           L0[:1], D, 1.0, 0.1, RHO)),
        "inertia": (lambda: hydro.fluid_inertia_forces(x, uf, elements, L0, D, 1.0, 0.1, RHO),
                    lambda i: hydro.fluid_inertia_forces(x[i:i + 2], uf[i:i + 1], one, L0[:1],
                                                         D, 1.0, 0.1, RHO)),
    }
    print(f"hydrodynamic kernels, {n_el} elements (vectorized vs single-element calls):")
    for name, (vec, single) in calls.items():
        report(name, best_of(vec, 1, repeat), _loop_time(single, n_el, sample, repeat),
               "target < 100 ms")


def bench_material(n: int, sample: int, repeat: int) -> None:
    EA = RNG.uniform(1e3, 1e5, n)
    old = RNG.uniform(0.0, 0.05, n)
    kw = {"dt": RNG.uniform(1e-3, 10.0, n), "EA": EA, "EA1": EA * RNG.uniform(0.5, 10.0, n),
          "tau": RNG.uniform(0.1, 20.0, n)}
    Q = kw["EA1"] * RNG.uniform(-0.01, 0.01, n)
    new = old + RNG.uniform(-0.02, 0.02, n)

    def exp_one(i: int) -> object:
        return sls_update_exponential(new[i], old[i], Q[i], *(kw[k][i] for k in kw),
                                      slack_ratio=1e-6)

    def inc_one(i: int) -> object:
        return sls_update_incremental(new[i], old[i], Q[i], *(kw[k][i] for k in kw))

    print(f"standard linear solid updates, {n} elements (vectorized vs single-element calls):")
    report("exponential, slack on",
           best_of(lambda: sls_update_exponential(new, old, Q, **kw, slack_ratio=1e-6), 1,
                   repeat), _loop_time(exp_one, n, sample, repeat), "target < 10 ms")
    report("incremental (Tuah eq. 2.2.b.3)",
           best_of(lambda: sls_update_incremental(new, old, Q, **kw), 1, repeat),
           _loop_time(inc_one, n, sample, repeat), "target < 10 ms")


def bench_waves(n: int, sample: int, repeat: int) -> None:
    p = np.column_stack((RNG.uniform(-500, 500, (n, 2)), RNG.uniform(-45, 2, n)))
    print(f"Airy kinematics, {n} points (vectorized vs single points):")
    for stretching in ("none", "wheeler"):
        wave = AiryWave(2.0, 8.0, 30.0, 40.0, G, ramp_time=10.0, stretching=stretching)
        report(f"stretching {stretching}", best_of(lambda w=wave: w.kinematics(p, 1.0), 1, repeat),
               _loop_time(lambda i, w=wave: w.kinematics(p[i:i + 1], 1.0), n, sample, repeat),
               "target < 50 ms")


def _geometries(n: int) -> list[tuple[float, float, float, float, float]]:
    """Suspended or grounded elastic lines: (X, Z, L, EA, w), Z > 0, slack 0.5-0.99 L."""
    out = []
    for _ in range(n):
        L = 10 ** RNG.uniform(1.0, 3.0)
        w = 10 ** RNG.uniform(0.0, 3.0)
        EA = w * L * 10 ** RNG.uniform(2.0, 6.0)
        r, th = RNG.uniform(0.5, 0.99), RNG.uniform(0.05, 0.5 * math.pi - 0.05)
        out.append((r * L * math.cos(th), r * L * math.sin(th), L, EA, w))
    return out


def bench_catenary(n: int, repeat: int) -> None:
    cases = _geometries(n)

    def ours() -> None:
        for X, Z, L, EA, w in cases:
            solve_catenary(X, Z, L, EA, w)

    fast = best_of(ours, 1, repeat)
    print(f"elastic catenary, {n} solves (moorline vs MoorPy's catenary):")
    try:
        from moorpy.Catenary import catenary
    except ImportError:
        print(f"  {'moorline':<34s} {fast * 1e3:10.3f} ms   (MoorPy not installed)"
              "   target < 2000 ms")
        return

    def theirs() -> None:
        for X, Z, L, EA, w in cases:
            catenary(X, Z, L, EA, w, CB=0.0)

    report("solve_catenary vs moorpy", fast, best_of(theirs, 1, repeat), "target < 2000 ms")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer repeats and elements")
    args = parser.parse_args()
    repeat = 2 if args.quick else 5
    n = 20_000 if args.quick else 100_000
    sample = 200 if args.quick else 1000
    print(f"{'':38s}{'fast':>10s}{'slow':>15s}{'speed-up':>10s}")
    bench_fused(repeat)
    bench_fused(repeat, table=True)
    bench_polyester_run(args.quick)
    bench_hydro(n, sample, repeat)
    bench_material(n, sample, repeat)
    bench_waves(n, sample, repeat)
    bench_catenary(200 if args.quick else 1000, repeat)


if __name__ == "__main__":
    main()
