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
