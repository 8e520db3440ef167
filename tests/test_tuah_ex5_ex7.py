"""Tuah Examples 5 and 7 (deterministic, no strumming): the moored disc buoy.

Fast versions of the verification rows (short runs), the data's internal consistency and the
case files' statics; the full runs are marked slow."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from moorline.io import load_case
from moorline.solvers.statics import solve_statics
from moorline.verification import tuah_ex5, tuah_ex7
from moorline.verification.signals import harmonic_fit

CASES = Path(__file__).resolve().parents[1] / "cases"


def _failed(rows):
    return [f"{r.quantity}: ref {r.reference:.4g} got {r.computed:.4g} ({r.note})"
            for r in rows if r.status == "fail"]


def test_disc_data_are_consistent():
    """Haskind's relation for the stored heave damping; the ballast floats the disc at its
    draft; the excitation table reproduces the complex amplitudes."""
    assert tuah_ex5.haskind_heave_damping() == pytest.approx(tuah_ex5.B33, rel=0.05)
    cat = tuah_ex5.design_catenary()
    assert cat.H == pytest.approx(tuah_ex5.WIND, rel=1e-9)
    mass = tuah_ex5.disc_mass(cat.V_b)
    buoyancy = tuah_ex5.RHO * tuah_ex5.GRAVITY * tuah_ex5.VOLUME
    assert mass * tuah_ex5.GRAVITY + cat.V_b == pytest.approx(buoyancy, rel=1e-12)
    table = tuah_ex5.excitation(0.0, 0.0, 6.0, ramp_time=0.0)
    t = np.asarray(table.times)
    values = np.asarray(table.values)
    fit = harmonic_fit(t, values[:, 2], tuah_ex5.OMEGA, 2, trend=True).phasor()
    assert fit == pytest.approx(tuah_ex5.X_HEAVE * tuah_ex5.AMPLITUDE, rel=1e-6)


@pytest.mark.parametrize("name, module", [("tuah_ex5.yaml", tuah_ex5),
                                          ("tuah_ex7.yaml", tuah_ex7)])
def test_case_files_load_and_match_the_python_statics(name, module):
    system = load_case(CASES / name)
    static = solve_statics(system)
    assert static.success, static.message
    _, reference = module.static_state()
    np.testing.assert_allclose(static.body_pose, reference.body_pose, atol=1e-6)
    np.testing.assert_allclose(static.tension, reference.tension, rtol=1e-6)


def test_ex5_statics_settles_the_disc_near_the_catenary():
    """The disc moves in from the source's 300 ft to where the cable's pull equals the wind:
    the closed-form catenary's 256.3 ft, less the 3-element polygon's shortfall."""
    _, static = tuah_ex5.static_state(8)
    assert static.body_pose[0, 0] == pytest.approx(tuah_ex5.design_catenary().horizontal_span,
                                                   abs=1.0)
    assert static.body_pose[0, 2] == pytest.approx(tuah_ex5.FORCE_CENTRE, abs=0.01)


def test_ex5_fast_rows_pass():
    rows = tuah_ex5.run(quick=True)
    assert len(rows) == 9
    assert not _failed(rows), _failed(rows)


def test_ex7_leeward_leg_goes_slack_in_a_short_run():
    """12 s (the ramp and a period): the leeward top element (the source's element 7) is
    slack at some instant, and the run stays symmetric about the wave direction."""
    run = tuah_ex7.run_dynamics(12.0, 0.02)
    tension = tuah_ex7.leeward_tension(run)
    assert tension[0] > 50.0
    assert tension.min() <= 0.0
    assert np.abs(run.result.body_history("disc")[:, 1]).max() < 1e-6


@pytest.mark.slow
def test_ex7_fast_rows_pass():
    rows = tuah_ex7.run(quick=True)
    assert not _failed(rows), _failed(rows)


@pytest.mark.slow
def test_ex5_and_ex7_full_rows_pass():
    rows = tuah_ex5.run() + tuah_ex7.run()
    assert not _failed(rows), _failed(rows)
