"""Statics with the drag of a steady current (``current_drag``)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from moorline.io import load_case
from moorline.io.case_writer import write_case
from moorline.model import Current, DynamicsSettings, StaticsSettings
from moorline.solvers.assembly import scatter_free
from moorline.solvers.dynamics import simulate
from moorline.solvers.equilibrium import StaticModel
from moorline.solvers.statics import _current_field, solve_statics
from moorline.verification import steady_current


def test_tangent_with_current_drag_is_exact():
    system = steady_current.current_system(10)
    static = solve_statics(system)
    model = StaticModel(static.mesh, _current_field(system))
    rng = np.random.default_rng(0)
    x = static.positions + 0.3 * rng.standard_normal(static.positions.shape) \
        * static.mesh.free_nodes[:, None]
    K = model.tangent(x).toarray()
    n = K.shape[0]
    J = np.zeros((n, n))
    for i in range(n):
        e = np.zeros(n)
        e[i] = 1e-6
        dx = scatter_free(e, static.mesh.dof_of_node)
        J[:, i] = -(model.residual(x + dx)[0] - model.residual(x - dx)[0]) / 2e-6
    assert np.abs(K - J).max() < 1e-7 * np.abs(J).max()
    # the drag part is there (it differs from the structural tangent)
    assert np.abs(StaticModel(static.mesh).tangent(x).toarray() - J).max() > 1.0


def test_dynamics_from_the_drag_equilibrium_stays_put():
    """Started from the statics with the current's drag, the dynamics keeps the current on
    from t = 0 (no ramp of it) and the line does not move."""
    system = steady_current.current_system(20)
    static = solve_statics(system, StaticsSettings(current_drag=True, tolerance=1e-10))
    assert static.success and static.current_drag
    plain = solve_statics(system)
    assert np.abs(static.positions - plain.positions).max() > 1.0  # the current moves it
    result = simulate(system, DynamicsSettings(duration=5.0, dt=0.05, ramp_time=5.0),
                      initial=static, output_every=0.5)
    assert np.abs(result.positions - static.positions[None]).max() < 1e-3


def test_current_drag_from_a_case_file_and_refusals(tmp_path):
    system = replace(steady_current.current_system(10),
                     analyses=(StaticsSettings(current_drag=True),))
    path = write_case(system, tmp_path / "current.yaml")
    loaded = load_case(path)
    assert loaded.analyses[0].current_drag is True
    assert solve_statics(loaded).success
    calm = replace(system, environment=replace(system.environment, current=Current()))
    assert not solve_statics(calm, StaticsSettings(current_drag=True)).current_drag
    from moorline.verification import tuah_ex5

    disc, _ = tuah_ex5.static_state()
    # a body in a current: the statics carries the current's drag on it (issue 15)
    drifted = solve_statics(replace(disc, environment=replace(disc.environment,
                                                              current=Current(speed=0.5))),
                            StaticsSettings(current_drag=True))
    assert drifted.success and drifted.current_drag
