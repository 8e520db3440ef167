"""The run's record arrays (moorline.solvers.dynamics._Recorder): allocated once for the
run's output times and written in place by the compiled loop (the in-place path against the
step-by-step loop, with step cuts: tests/test_fast_loop.py)."""

import numpy as np
import pytest

from moorline.mesh import discretize
from moorline.model import DynamicsSettings
from moorline.solvers import dynamics
from moorline.solvers.dynamics import _expected_records, _Recorder, simulate
from moorline.solvers.statics import solve_statics
from moorline.verification.oc3_system import oc3_three_lines


@pytest.mark.parametrize(("duration", "dt", "every"),
                         [(2.0, 0.05, 0.05), (2.0, 0.05, 0.25), (2.0, 0.05, 0.07),
                          (1.0, 0.1, 0.3), (0.5, 0.05, 10.0)])
def test_the_records_of_a_run_fit_the_arrays_made_for_them(duration, dt, every) -> None:
    """The records a run writes (the initial state, one per output interval, the last step)
    fit the arrays allocated before it, with at most three rows to spare."""
    system = oc3_three_lines(10)
    start = solve_statics(system)
    run = simulate(system, DynamicsSettings(duration=duration, dt=dt), initial=start,
                   output_every=every)
    assert run.success, run.message
    n_steps = round(duration / dt)
    expected = _expected_records(n_steps, dt, max(every, dt))
    assert len(run.time) <= expected <= len(run.time) + 3


def test_full_arrays_grow_and_keep_what_was_handed_out() -> None:
    """More records than allocated: the arrays grow (the result holds every record in
    order) and the views a writer received keep their values."""
    mesh = discretize(oc3_three_lines(4))

    class Writer:
        def __init__(self) -> None:
            self.blocks = []

        def append_block(self, times, records, owned=False):
            self.blocks.append((times, records))

    writer = Writer()
    recorder = _Recorder(mesh, writer, capacity=2)
    rng = np.random.default_rng(5)
    given = []
    for n in (1, 3, 2):
        records = {"position": rng.random((n, mesh.n_nodes, 3)),
                   "tension": rng.random((n, mesh.n_elements))}
        times = np.arange(len(given), len(given) + n, dtype=float)
        recorder.add_block(times, records)
        given.append((times, {key: value.copy() for key, value in records.items()}))
    assert recorder.count == 6 and recorder.capacity >= 6
    for key in ("position", "tension"):
        whole = np.concatenate([records[key] for _, records in given])
        np.testing.assert_array_equal(recorder.arrays[key][:6], whole)
    for (times, records), (got_times, got) in zip(given, writer.blocks, strict=True):
        np.testing.assert_array_equal(got_times, times)
        for key in records:
            np.testing.assert_array_equal(got[key], records[key])


def test_a_failed_run_keeps_its_records(monkeypatch) -> None:
    """A run that stops early returns the records up to its last completed step, from the
    arrays allocated for the whole run."""
    system = oc3_three_lines(10, BA=6.2358e6)
    start = solve_statics(system)
    monkeypatch.setattr(dynamics, "COMPILED_LOOP", True)
    run = simulate(system, DynamicsSettings(duration=30.0, dt=0.05, max_iterations=1,
                                            max_step_cuts=0), initial=start,
                   output_every=0.05)
    assert not run.success
    assert len(run.time) == len(run.tension) == len(run.positions) >= 1
    assert np.all(np.diff(run.time) > 0)
    assert run.time[-1] < 30.0
