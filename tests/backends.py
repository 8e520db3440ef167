"""The compiled backend against the general stepper on the numpy element kernel (the reference
path: its own residual, HHT weighting, assembly, sparse LU and fluid kinematics), for the
tests of the compiled step and loop."""

import numpy as np

from moorline.model import DynamicsSettings
from moorline.solvers import dynamics
from moorline.solvers.dynamic_model import DynamicModel
from moorline.solvers.dynamics import simulate


def reference_run(system, settings: DynamicsSettings, start, every: float, monkeypatch):
    """``simulate`` on the general stepper with the numpy element kernel."""
    from dataclasses import replace

    monkeypatch.setattr(dynamics, "DynamicModel",
                        lambda *args, **kw: DynamicModel(*args, **kw, kernel="numpy"))
    return simulate(system, replace(settings, fast_path=False), initial=start,
                    output_every=every)


def assert_same_run(fast, slow) -> None:
    """The same states to the Newton tolerance's round-off (positions to 1e-7 of their
    largest, tensions to 1e-6) and the same work (iterations, factorizations, local
    iterations)."""
    assert fast.success and slow.success
    scale = float(np.abs(slow.positions).max())
    assert np.allclose(fast.positions, slow.positions, rtol=0, atol=1e-7 * scale)
    assert np.allclose(fast.tension, slow.tension, rtol=1e-6, atol=1e-6 * slow.tension.max())
    assert fast.counters["iterations"] == slow.counters["iterations"]
    assert fast.counters["factorizations"] == slow.counters["factorizations"]
    assert fast.counters["local_iterations"] == slow.counters["local_iterations"]


def assert_same_bodies(fast, slow, size: float) -> None:
    """The same body poses (within 1e-9 of the body's ``size`` [m]), velocities, lines'
    forces on the bodies and line end forces (to the Newton tolerance's round-off of their
    largest)."""
    assert np.allclose(fast.body_pose, slow.body_pose, rtol=0, atol=1e-9 * size)
    assert np.allclose(fast.body_velocity, slow.body_velocity, rtol=0,
                       atol=1e-8 * np.abs(slow.body_velocity).max())
    scale = np.abs(slow.body_mooring_force).max()
    assert np.allclose(fast.body_mooring_force, slow.body_mooring_force, rtol=0,
                       atol=1e-7 * scale)
    ends = np.abs(slow.end_force).max()
    assert np.allclose(fast.end_force, slow.end_force, rtol=0, atol=1e-7 * ends)
