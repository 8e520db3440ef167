"""Tuah Examples 5 and 7 (deterministic, no strumming) and Example 5's random sea: the moored
disc buoy and its independent linear model (:mod:`moorline.verification.disc_linear`).

The linear model is tested against closed forms (a free floating disc) and a numerical ODE
integration; moorline's statics and modes against the linear model; the verification rows'
full runs are marked slow."""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from moorline.io import load_case
from moorline.model import ModalSettings
from moorline.solvers.modal import solve_modes
from moorline.solvers.statics import solve_statics
from moorline.verification import disc_linear as dl
from moorline.verification import tuah_ex5, tuah_ex5_random, tuah_ex7
from moorline.verification.signals import harmonic_fit

CASES = Path(__file__).resolve().parents[1] / "cases"


def _failed(rows):
    return [f"{r.quantity}: ref {r.reference:.4g} got {r.computed:.4g} ({r.note})"
            for r in rows if r.status == "fail"]


def test_disc_data_are_consistent():
    """Haskind's relation for the stored heave damping; the ballast floats the disc at its
    draft; the excitation table reproduces the complex amplitudes."""
    assert tuah_ex5.haskind_heave_damping() == pytest.approx(tuah_ex5.B33, rel=0.03)
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


def _free_disc() -> dl.LinearSystem:
    body = replace(tuah_ex5.linear_body(tuah_ex5.design_catenary().V_b, (0.0, 0.0)),
                   force=(0.0, 0.0, 0.0))
    sea = dl.Sea(tuah_ex5.DEPTH, tuah_ex5.RHO, tuah_ex5.GRAVITY)
    return dl.equilibrium(body, (), sea, np.array([0, 0, tuah_ex5.FORCE_CENTRE, 0, 0, 0.0]),
                          [])


def test_linear_model_of_a_free_disc_matches_closed_forms():
    """Without legs: the disc rises by the missing pull / K33; heave at
    sqrt(K33 / (m + A33)); surge-pitch from the 2x2 problem with the pitch stiffness
    rho g I_wp + rho g V z_B - m g z_G (weight and buoyancy rho g V on their body-fixed arms,
    the heave restoring at the origin); the heave response
    X3 / (K33 - w^2 (m + A33) - i w B33)."""
    e = tuah_ex5
    model = _free_disc()
    m = e.disc_mass(e.design_catenary().V_b)
    k33 = e.RHO * e.GRAVITY * e.WATERPLANE
    buoyancy = e.RHO * e.GRAVITY * e.VOLUME
    assert model.pose0[2] - e.FORCE_CENTRE == pytest.approx((buoyancy - m * e.GRAVITY) / k33,
                                                            rel=1e-9)
    z_b, z_g = -e.DRAFT / 2 - e.FORCE_CENTRE, -e.DRAFT + e.KG - e.FORCE_CENTRE
    k55 = e.RHO * e.GRAVITY * e.WATERPLANE_INERTIA + buoyancy * z_b - m * e.GRAVITY * z_g
    i_g = m * (3 * (e.DIAMETER / 2) ** 2 + e.HULL_HEIGHT**2) / 12
    M = np.array([[m + e.A11, m * z_g + e.A15], [m * z_g + e.A15, i_g + m * z_g**2 + e.A55]])
    pitch = math.sqrt(k55 * M[0, 0] / np.linalg.det(M))
    w, _ = dl.natural_frequencies(model)
    assert w[0] == pytest.approx(math.sqrt(k33 / (m + e.A33)), rel=1e-7)
    assert sorted(w[1:]) == pytest.approx([pitch, pitch], rel=1e-6)  # pitch and roll
    load = dl.body_load(model, np.array([0.0, 0.0, e.X_HEAVE]))
    q = dl.frequency_response(model, e.OMEGA, load)
    assert q[2] == pytest.approx(e.X_HEAVE / (k33 - e.OMEGA**2 * (m + e.A33)
                                              - 1j * e.OMEGA * e.B33), rel=1e-7)


def test_ramped_history_is_the_solution_of_the_linear_equations():
    """The exact ramped response of the 3-element model against a numerical integration of
    the same ODE (Radau, tight tolerances)."""
    model = tuah_ex5.linear_ex5(3)
    table, inertia = tuah_ex5.linear_loads(model, 1.0)
    hist = dl.ramped_history(model, tuah_ex5.OMEGA, table, inertia, tuah_ex5.RAMP_TIME,
                             0.05, 12.0)
    n = model.n
    Minv = np.linalg.inv(model.M)
    W = math.pi / tuah_ex5.RAMP_TIME

    def rhs(t, y):
        r, dr = ((0.5 * (1 - math.cos(W * t)), 0.5 * W * math.sin(W * t))
                 if t < tuah_ex5.RAMP_TIME else (1.0, 0.0))
        e = np.exp(-1j * tuah_ex5.OMEGA * t)
        f = np.real(r * table * e + (dr - 1j * tuah_ex5.OMEGA * r) * inertia * e)
        return np.concatenate((y[n:], Minv @ (f - model.C @ y[n:] - model.K @ y[:n])))

    sol = solve_ivp(rhs, (0.0, 12.0), np.zeros(2 * n), method="Radau", t_eval=hist.time,
                    rtol=1e-10, atol=1e-12)
    scale = np.abs(hist.q).max(axis=0)
    for j in (0, 2, 4):
        assert np.abs(sol.y[j] - hist.q[:, j]).max() < 1e-5 * scale[j]


@pytest.mark.parametrize("segments", [3, 8])
def test_moorline_statics_matches_the_independent_model(segments):
    """moorline's coupled statics (Newton, seabed contact) against the linear model's own
    root solve of the same force balances."""
    _, static = tuah_ex5.static_state(segments)
    model = tuah_ex5.linear_ex5(segments)
    np.testing.assert_allclose(static.body_pose[0, [0, 2, 4]], model.pose0[[0, 2, 4]],
                               rtol=1e-7, atol=1e-8)
    np.testing.assert_allclose(static.tension, model.tension0[0], rtol=1e-6)


def test_ex7_statics_matches_the_independent_model():
    _, static = tuah_ex7.static_state()
    model = tuah_ex7.linear_ex7()
    np.testing.assert_allclose(static.body_pose[0, :3], model.pose0[:3], atol=1e-7)
    for k, name in enumerate(tuah_ex7.AZIMUTHS_DEG):
        top = tuah_ex7.top_element(static, name)
        assert static.tension[top] == pytest.approx(model.tension0[k][-1], rel=1e-6)


def test_moorline_modes_match_the_independent_model():
    """moorline's modal solver (lumped mass) on the Ex5 system against the linear model's
    eigenvalues: the same K and M assembled independently."""
    system, static = tuah_ex5.static_state(3)
    modes = solve_modes(system, ModalSettings(n_modes=10, mass="lumped"), static)
    w, _ = dl.natural_frequencies(tuah_ex5.linear_ex5(3))
    np.testing.assert_allclose(np.sort(modes.omega), w[:10], rtol=1e-6, atol=1e-6)


def test_the_small_amplitude_rows_would_see_a_wrong_leg_model():
    """The rows' 1 % tolerance is tight enough to see a plausible modelling error: the legs'
    added mass left out moves the 3-element response by tens of per cent (the leg's mode at
    1.94 rad/s lies close to the wave's 2.09)."""
    e = tuah_ex5
    model = e.linear_ex5(3)
    legs = tuple(replace(leg, Ca=0.0) for leg in model.legs)
    bare = dl.equilibrium(model.body, legs, model.sea, model.pose0,
                          [n[1:-1] for n in model.nodes0])
    responses = [dl.steady_response(m, e.OMEGA, *e.linear_loads(m, 1.0)) for m in (model, bare)]
    ratio = np.abs(responses[1][[0, 2]]) / np.abs(responses[0][[0, 2]])
    assert np.all(np.abs(ratio - 1) > 10 * e.AMPLITUDE_TOLERANCE), ratio


def test_ex5_quick_rows():
    """The small-amplitude moorline run against the linear model and the slack in the
    source's wave."""
    rows = tuah_ex5.run(quick=True)
    assert not _failed(rows), _failed(rows)
    kinds = {r.kind for r in rows}
    assert kinds == {"exact", "published"}
    assert sum(r.kind == "exact" for r in rows) == 9


def test_ex7_leeward_leg_goes_slack_in_a_short_run():
    """12 s (the ramp and a period): the leeward top element (the source's element 7) is
    slack at some instant, and the run stays symmetric about the wave direction."""
    run = tuah_ex7.run_dynamics(12.0, 0.02)
    tension = tuah_ex7.leeward_tension(run)
    assert tension[0] > 50.0
    assert tension.min() <= 0.0
    assert np.abs(run.result.body_history("disc")[:, 1]).max() < 1e-6


def test_ex5_random_rows():
    """moorline's frequency-domain transfer functions (no drag) against the linear model;
    the pitch peak at its pitch-dominated mode; the source's 4.6 rad/s not reproduced."""
    rows = tuah_ex5_random.run()
    assert not _failed(rows), _failed(rows)
    assert [r.status for r in rows].count("not reproduced") == 1


@pytest.mark.slow
def test_ex7_quick_rows_pass():
    rows = tuah_ex7.run(quick=True)
    assert not _failed(rows), _failed(rows)


@pytest.mark.slow
def test_ex5_and_ex7_full_rows_pass():
    rows = tuah_ex5.run() + tuah_ex7.run()
    assert not _failed(rows), _failed(rows)
