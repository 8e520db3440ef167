"""The dynamic residual's tangents (K = -dF/dx, C = -dF/dv, M_a = -dF/da) against central
finite differences, with every load active: axial elasticity and damping, seabed contact and
friction, current drag, added mass and fluid inertia, point drag."""

import numpy as np
import pytest

from moorline.mesh import discretize
from moorline.model import Environment, Line, LineType, Point, Seabed, System
from moorline.physics import seabed
from moorline.solvers.assembly import BlockPattern
from moorline.solvers.dynamic_model import DynamicModel
from moorline.waves import CurrentProfile


def _system(friction=(0.6, 0.6)) -> System:
    lt = LineType("chain", diameter=0.09, mass_per_length=77.7, EA=3.8e8, Cd=1.6, Ct=0.05,
                  Ca=1.0, Cat=0.2, BA=-0.8)
    points = {
        "anchor": Point("anchor", "fixed", (-400.0, 0.0, -99.9)),  # off the contact kink
        "buoy": Point("buoy", "free", (-150.0, 0.0, -60.0), mass=2000.0, volume=5.0, Cd=0.8,
                      drag_area=3.0, Ca=0.5),
        "fair": Point("fair", "prescribed", (0.0, 0.0, -10.0)),
    }
    lines = {"a": Line("a", "chain", 320.0, 8, "anchor", "buoy"),
             "b": Line("b", "chain", 170.0, 6, "buoy", "fair")}
    sb = Seabed(friction_axial=friction[0], friction_transverse=friction[1], slip_velocity=0.05)
    env = Environment(depth=100.0, seabed=sb)
    return System("fd", environment=env, line_types={"chain": lt}, points=points, lines=lines)


@pytest.mark.parametrize("friction, options", [
    ((0.6, 0.6), {}), ((0.0, 0.0), {}),
    ((0.0, 0.0), {"slack_damping": True, "drag_velocity": "node"}),
    ((0.6, 0.6), {"slack_damping": True, "drag_velocity": "node", "kernel": "numpy"})])
def test_dynamic_tangents_match_central_differences(friction, options):
    system = _system(friction)
    mesh = discretize(system)
    model = DynamicModel(mesh, CurrentProfile.uniform(0.7, 25.0),
                         seabed_model=system.environment.seabed, **options)
    rng = np.random.default_rng(3)
    x = mesh.node_position.copy()
    x[mesh.line_nodes[0][1:4], 2] = -100.004  # resting on the seabed, past the blend band
    x[mesh.line_nodes[0][4], 2] = -100.001     # inside the blend band
    x += rng.normal(scale=1e-4, size=x.shape) * (x[:, 2:3] > -99.99)
    v = rng.normal(scale=0.3, size=x.shape)
    a = rng.normal(scale=0.2, size=x.shape)
    material = model.initial_material(x)
    ev = model.evaluate(x, v, a, 1.0, material, 0.05, True)
    pattern = BlockPattern(mesh.elements, np.arange(3 * mesh.n_nodes).reshape(-1, 3))
    for which, blocks, nodes in (("x", ev.K, ev.node_K), ("v", ev.C, ev.node_C),
                                 ("a", ev.Ma, ev.node_M)):
        A = pattern.assemble(blocks, nodes).toarray()
        fd = np.zeros_like(A)
        h = {"x": 1e-7, "v": 1e-7, "a": 1e-5}[which]
        for j in range(3 * mesh.n_nodes):
            d = np.zeros(3 * mesh.n_nodes)
            d[j] = h
            d = d.reshape(-1, 3)
            args = {"x": x, "v": v, "a": a}
            plus = dict(args, **{which: args[which] + d})
            minus = dict(args, **{which: args[which] - d})
            fp = model.evaluate(plus["x"], plus["v"], plus["a"], 1.0, material, 0.05, False)
            fm = model.evaluate(minus["x"], minus["v"], minus["a"], 1.0, material, 0.05, False)
            fd[:, j] = -(fp.nodal - fm.nodal).ravel() / (2 * h)
        scale = np.abs(A).max()
        bad = np.argwhere(~np.isclose(A, fd, rtol=1e-5, atol=1e-6 * scale))
        assert not len(bad), (which, bad[:6], A[tuple(bad[0])], fd[tuple(bad[0])])


def test_isotropic_friction_saturates_at_mu_n_against_the_sliding_direction():
    v = np.array([[0.3, -0.4, 0.0]])
    f = seabed.friction_force(v, np.array([1000.0]), np.array([[1.0, 0.0, 0.0]]), 0.5, 0.5,
                              1e-4)[0]
    assert np.allclose(f[0], -0.5 * 1000.0 * v[0] / 0.5, rtol=1e-12)


def test_lagged_dashpot_share_is_the_band_law_at_the_start_strain():
    """The share held over a step: 0 below ``-s``, 1 above ``s``, linear between (0.5 at
    zero strain), of the strain less its offset; a step at 0 without a band."""
    from moorline.physics.element import lagged_dashpot_share

    s = 1e-5
    strain = np.array([-1e-3, -s, -0.5 * s, 0.0, 0.5 * s, s, 1e-3])
    np.testing.assert_allclose(lagged_dashpot_share(strain, s),
                               [0.0, 0.0, 0.25, 0.5, 0.75, 1.0, 1.0], rtol=0, atol=1e-12)
    np.testing.assert_allclose(lagged_dashpot_share(strain + 2e-3, s, np.full(7, 2e-3)),
                               [0.0, 0.0, 0.25, 0.5, 0.75, 1.0, 1.0], rtol=0, atol=1e-9)
    np.testing.assert_array_equal(lagged_dashpot_share(strain, 0.0),
                                  [0, 0, 0, 0, 1, 1, 1])


@pytest.mark.parametrize("kernel", ["numpy", "numba"])
def test_dashpot_acts_by_the_strain_at_the_start_of_the_step(kernel):
    """An element stretching at a rate: its tension carries ``BA deps/dt`` when it was taut
    at the start of the step and none when it was slack then, whatever its strain now (the
    share is held over the step: element.lagged_dashpot_share)."""
    system = _system((0.0, 0.0))
    mesh = discretize(system)
    model = DynamicModel(mesh, CurrentProfile.uniform(0.0, 25.0), kernel=kernel)
    x = mesh.node_position.copy()
    e = 3
    i, j = mesh.elements[e]
    chord = x[j] - x[i]
    unit = chord / np.linalg.norm(chord)
    x[j] = x[i] + unit * mesh.length0[e] * (1 + 1e-3)  # taut now
    v = np.zeros_like(x)
    v[j] = 0.2 * unit  # stretching
    rate = 0.2 / mesh.length0[e]
    taut, slack = model.initial_material(x), model.initial_material(x)
    slack.strain[e] = -1e-3
    BA = mesh.BA[e]
    assert BA > 0
    T_taut = model.evaluate(x, v, v * 0, 0.0, taut, 0.05, False).tension[e]
    T_slack = model.evaluate(x, v, v * 0, 0.0, slack, 0.05, False).tension[e]
    np.testing.assert_allclose(T_taut - T_slack, BA * rate, rtol=1e-9)
    np.testing.assert_allclose(T_slack, mesh.EA[e] * 1e-3, rtol=1e-9)
