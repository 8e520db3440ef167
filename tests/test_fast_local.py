"""The local (windowed) Newton phase of the time step (:mod:`moorline.solvers.newton`,
:mod:`moorline.solvers.fast_local`): the compiled step makes the same local iterations as the
general stepper, and the converged states satisfy the full residual's tolerance."""

from types import SimpleNamespace

import numpy as np
import pytest
from backends import assert_same_run, reference_run

from moorline.model import DynamicsSettings
from moorline.solvers import dynamics, newton
from moorline.solvers.dynamics import simulate
from moorline.solvers.fast_local import _window, incidence
from moorline.solvers.fast_newmark import band_ordering
from moorline.solvers.statics import solve_statics
from moorline.verification.oc3_system import oc3_one_line

BA = 6.2358e6  # the P4 benchmark's line damping (benchmarks/bench_p1.py)


@pytest.fixture(autouse=True)
def _small_models_too(monkeypatch):
    """The local phase on this module's 40-element line (below the size from which
    dynamics uses it by default)."""
    monkeypatch.setattr(dynamics, "LOCAL_MIN_FREE_NODES", 0)


def _case():
    """One OC3 line at 40 elements under the P1 fairlead motion, unramped: its first steps
    snap the line near touchdown, where the local phase works."""
    system = oc3_one_line(40, ramp_time=0.0, BA=BA)
    start = solve_statics(system)
    assert start.success, start.message
    return system, start


# slow: the first run compiles the compiled loop a second time, with the local phase in it
# (about two minutes on a 2-core machine, no line-only model of make test's is large enough to
# use it); `make verify` runs it
@pytest.mark.slow
@pytest.mark.parametrize("scheme", ["newmark", "hht"])
def test_compiled_local_phase_equals_the_general_stepper(scheme, monkeypatch):
    system, start = _case()
    settings = DynamicsSettings(duration=2.0, dt=0.05, scheme=scheme)
    fast = simulate(system, settings, initial=start, output_every=0.05)
    slow = reference_run(system, settings, start, 0.05, monkeypatch)
    assert_same_run(fast, slow)
    assert fast.counters["local_iterations"] == slow.counters["local_iterations"] > 0
    # the local phase's line search counts its residual evaluations on both
    assert fast.counters["residuals"] == slow.counters["residuals"]


def test_local_phase_changes_the_path_not_the_answer(monkeypatch):
    """Every step that used local iterations ends with the full residual (evaluated afresh at
    the returned unknowns) within the tolerance; and the run stays within the Newton
    tolerance's effect of the run without them (positions to 1e-5 of their scale)."""
    system, start = _case()
    settings = DynamicsSettings(duration=2.0, dt=0.05, fast_path=False)
    checked = []
    solve = newton.solve

    def checking(problem, u, policy, cache, counters, key=None, trial=None):
        before = counters.local_iterations
        out = solve(problem, u, policy, cache, counters, key, trial)
        if out.converged and counters.local_iterations > before:
            full = newton.max_norm(problem.residual(out.u, False).r)
            checked.append((full, out.norm, policy.tolerance))
        return out

    monkeypatch.setattr("moorline.solvers.newmark.solve", checking)
    with_local = simulate(system, settings, initial=start, output_every=0.05)
    assert checked
    for full, norm, tol in checked:
        assert full == pytest.approx(norm, rel=1e-12, abs=1e-12 * tol)
        assert full <= tol
    monkeypatch.setattr(dynamics, "LOCAL_ITERATIONS", 0)
    without = simulate(system, settings, initial=start, output_every=0.05)
    assert without.counters["local_iterations"] == 0
    scale = float(np.abs(without.positions).max())
    assert np.allclose(with_local.positions, without.positions, rtol=0, atol=1e-5 * scale)


def test_compiled_window_is_the_general_stepper_window():
    """The window of :func:`_window` (band order) and ``Stepper.local_window`` (the general
    stepper's dofs) cover the same nodes, and it is refused when too wide."""
    from moorline.solvers.newmark import Stepper

    _, start = _case()
    mesh = start.mesh
    rng = np.random.default_rng(3)
    n_nodes = mesh.n_nodes
    node_r = np.zeros((n_nodes, 3))
    node_r[mesh.free_nodes] = 1e-6 * rng.standard_normal((int(mesh.free_nodes.sum()), 3))
    node_r[[7, 8, 25]] = [1.0, -2.0, 0.5]
    band, _ = band_ordering(mesh.elements, mesh.dof_of_node)
    rvec = np.zeros(3 * int(mesh.free_nodes.sum()))
    rvec[band[mesh.free_nodes].ravel()] = node_r[mesh.free_nodes].ravel()
    ptr, inc = incidence(mesh.elements, n_nodes)
    general = Stepper.__new__(Stepper)  # the window needs the mesh only
    general.coupled, general.free, general.dof = False, mesh.free_nodes, mesh.dof_of_node
    general.model = SimpleNamespace(mesh=mesh)
    free = mesh.free_nodes
    r = np.zeros(3 * int(free.sum()))
    r[mesh.dof_of_node[free].ravel()] = node_r[free].ravel()
    trial = SimpleNamespace(r=r)
    seen = []
    for pad, share in [(2, 0.5), (3, 0.5), (3, 0.2)]:
        compiled = _window(rvec, band, free, int(free.sum()), mesh.elements, ptr, inc, 0.1,
                           pad, share, np.full(n_nodes, -1, dtype=np.int64), 0,
                           np.empty(n_nodes, dtype=np.int64), np.empty(n_nodes, dtype=np.int64))
        dofs = general.local_window(trial, 0.1, pad, share)
        seen.append(dofs is None)
        if dofs is None:
            assert len(compiled) == 0
            continue
        nodes = np.flatnonzero(np.isin(mesh.dof_of_node[:, 0], dofs))
        assert np.array_equal(compiled, nodes)
    assert seen == [False, False, True]


def test_small_models_step_without_the_local_phase(monkeypatch):
    """Below :data:`dynamics.LOCAL_MIN_FREE_NODES` free nodes the policy has no local
    iterations and the compiled step gets ``local`` None (compiled without that code)."""
    system, start = _case()
    monkeypatch.setattr(dynamics, "LOCAL_MIN_FREE_NODES", 10_000)
    run = simulate(system, DynamicsSettings(duration=0.5, dt=0.05), initial=start)
    assert run.counters["local_iterations"] == 0
    from moorline.solvers.fast_newmark import FastStepper

    made = []
    monkeypatch.setattr(FastStepper, "__init__", _recording(FastStepper.__init__, made))
    simulate(system, DynamicsSettings(duration=0.1, dt=0.05), initial=start)
    assert made and made[0].newton_args[-1] is None


def _recording(init, made):
    def wrapped(self, *args, **kwargs):
        init(self, *args, **kwargs)
        made.append(self)
    return wrapped
