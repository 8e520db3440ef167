"""Wang, Er and Iu cases W2 (forced response of the moored box) and W3 (its parameter study),
and the continuous-line reference model (:mod:`moorline.verification.linear_cable`)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from moorline.catenary import solve_catenary
from moorline.physics.rigid_body import rotation_matrix
from moorline.solvers.bodies import body_loads
from moorline.sweep import load_study, study_from_dict
from moorline.verification import wang_dynamics as wd
from moorline.verification import wang_w1 as w1
from moorline.verification.linear_cable import Cable, end_stiffness, forced_end, transfer
from moorline.verification.signals import harmonic_fit

ROOT = Path(__file__).resolve().parents[1]
W3_STUDY = ROOT / "cases" / "studies" / "wang_w3.yaml"


def _failed(rows):
    return [(r.quantity, r.reference, r.computed, r.error, r.tolerance) for r in rows
            if r.status == "fail"]


@pytest.fixture(scope="module")
def equilibrium():
    return wd.forced_equilibrium()


@pytest.fixture(scope="module")
def linear(equilibrium):
    return wd.linearize(equilibrium.system, equilibrium.result)


# ----------------------------------------------------------------------------- continuum
def test_continuous_taut_string_end_stiffness_is_the_closed_form():
    """A weightless taut string: transverse end stiffness ``T' k cot(k L)`` with
    ``T' = T / (1 + T/EA)`` (per unstretched length) and ``k = omega (m / T')^(1/2)``, axial
    ``EA k_a cot(k_a L)``, ``k_a = omega (m / EA)^(1/2)`` (the normal added mass acts only
    transversely)."""
    T, EA, L, m, ma, omega = 1.0e4, 1.0e7, 50.0, 10.0, 3.0, 2.0
    cable = Cable(L, EA, (T, 0.0, 0.0), 0.0, m, ma)
    K = end_stiffness(transfer(cable, [omega], steps=400)[1][-1])[0]
    Tp = T / (1.0 + T / EA)
    k = omega * math.sqrt((m + ma) / Tp)
    ka = omega * math.sqrt(m / EA)
    assert K[1, 1].real == pytest.approx(Tp * k / math.tan(k * L), rel=1e-8)
    assert K[2, 2].real == pytest.approx(Tp * k / math.tan(k * L), rel=1e-8)
    assert K[0, 0].real == pytest.approx(EA * ka / math.tan(ka * L), rel=1e-8)


def test_continuous_catenary_static_stiffness_is_the_catenary_derivative():
    """At omega -> 0 the end stiffness of a hanging line is the derivative of the closed-form
    elastic catenary's end force with respect to the end position (central differences)."""
    draft, line = w1.catenary_draft()
    X, Z = line.horizontal_span, line.vertical_span
    cable = Cable(line.length, w1.EA, (line.H_a, 0.0, line.V_a), w1.WEIGHT, 1.0, 0.0)
    K = end_stiffness(transfer(cable, [1e-9], steps=200)[1][-1])[0].real

    def force(dx: float, dz: float) -> np.ndarray:
        sol = solve_catenary(X + dx, Z + dz, line.length, w1.EA, w1.WEIGHT,
                             seabed_contact=False, tol=1e-13)
        return np.array([sol.H, sol.V_b])  # the pull from outside on the end: F(L)

    h = 1e-4
    dFdx = (force(h, 0) - force(-h, 0)) / (2 * h)
    dFdz = (force(0, h) - force(0, -h)) / (2 * h)
    assert K[np.ix_([0, 2], [0, 2])] == pytest.approx(np.column_stack([dFdx, dFdz]), rel=1e-5)


def test_continuous_forced_end_matches_the_end_stiffness():
    cable = Cable(100.0, 1e8, (2e4, 0.0, 1e4), 500.0, 60.0, 8.0)
    Phi = transfer(cable, [0.7], a0=0.05, a1=0.01, steps=200)[1]
    force = np.array([300.0, 50.0, -20.0])
    U = forced_end(Phi, force)[-1, 0, :3]
    assert end_stiffness(Phi[-1])[0] @ U == pytest.approx(force, rel=1e-10)


def test_box_hydrostatics_of_moorline_is_the_closed_form(equilibrium):
    """moorline's box hydrostatics (heave, roll, pitch) against rho g (A_wp, I_wp + V z_B)."""
    body = equilibrium.system.bodies["box"]
    pose = equilibrium.result.body_pose[0]
    K = body_loads(body, pose[:3], rotation_matrix(pose[3:]), w1.G, w1.RHO)[1]
    ref = wd.box_hydrostatics(equilibrium.draft)
    for dof in (2, 3, 4):
        assert K[dof, dof] == pytest.approx(ref[dof, dof], rel=1e-6)


# ----------------------------------------------------------------------------- model
def test_forced_equilibrium_carries_the_force(equilibrium):
    history = equilibrium.system.bodies["box"].force_history
    assert history.kind == "harmonic"
    assert history.amplitude == (1e5, 0.0, 0.0)
    assert history.period == pytest.approx(2 * math.pi / 1.6)
    assert equilibrium.draft == pytest.approx(w1.PAPER_DRAFT, rel=5e-3)  # the paper's 0.896 m


def test_line_drag_switch_reaches_the_mesh():
    """The dynamics take the mesh from the static result: its drag must follow the switch."""
    eq = wd.forced_equilibrium(line_drag=False)
    assert np.all(eq.result.mesh.Cd == 0.0) and np.all(eq.result.mesh.Ct == 0.0)
    assert np.all(eq.result.mesh.Ca == 1.0)


def test_linearized_model_condenses_to_the_mooring_stiffness(equilibrium, linear):
    """Condensing the line dofs out of the assembled tangent gives the body stiffness of
    group_stiffness + hydrostatics (an independent condensation of the static tangent)."""
    K, b = linear.K, linear.body
    lines = np.setdiff1d(np.arange(len(K)), np.arange(b.start, b.stop))
    condensed = K[b, b] - K[b][:, lines] @ np.linalg.solve(K[np.ix_(lines, lines)],
                                                          K[lines][:, b])
    reference = wd.body_stiffness(equilibrium)
    assert np.allclose(condensed, reference, rtol=1e-6, atol=1e-6 * np.abs(reference).max())
    assert np.allclose(linear.M, linear.M.T)
    assert np.all(np.linalg.eigvalsh(linear.M) > 0)


def test_mooring_stiffness_against_the_continuous_lines(equilibrium):
    """Surge-pitch block of group_stiffness + hydrostatics (11 elements) against the exact
    catenary's: within the 11 elements' 0.37 % tension deficit (W1's a-priori estimate)."""
    exact = wd.continuum_box(1e-9).real
    K = wd.body_stiffness(equilibrium)
    idx = np.ix_([0, 2, 4], [0, 2, 4])
    assert K[idx] == pytest.approx(exact[idx], rel=5e-3, abs=1e-6 * np.abs(exact).max())


def test_rayleigh_coefficients_give_the_ratio_at_both_frequencies():
    a0, a1 = wd.rayleigh_coefficients(0.03, (1.6, 2.1))
    for omega in (1.6, 2.1):  # ratio a0 / (2 w) + a1 w / 2
        assert a0 / (2 * omega) + a1 * omega / 2 == pytest.approx(0.03)
    assert a0 / (2 * 1.8) + a1 * 1.8 / 2 < 0.03  # below the ratio between them


def test_linearized_response_converges_to_the_continuous_lines():
    """moorline's linearized FE model of the box at 1.6 rad/s (no line drag) converges at
    second order in the element length to the continuous-line model."""
    rayleigh = wd.rayleigh_coefficients(0.03, (1.6, 2.07))
    force = np.array([1e3, 0.0, 0.0, 0.0, 0.0, 0.0])
    exact = abs(np.linalg.solve(wd.continuum_box(1.6, rayleigh), force)[0])
    err = [abs(abs(wd._linear_fe(n, rayleigh, force)[0]) - exact) for n in (22, 44)]
    assert math.log2(err[0] / err[1]) == pytest.approx(2.0, abs=0.25)


# ----------------------------------------------------------------------------- helpers
def test_signal_helpers():
    t = np.arange(0.0, 40 * math.pi / 1.6, 0.01)
    y = 0.3 + 0.5 * np.sin(1.6 * t + 0.4) + 0.05 * np.sin(3.2 * t)
    fit = harmonic_fit(t, y, 1.6)
    assert (fit.mean, fit.amplitude(), fit.phase()) == pytest.approx((0.3, 0.5, 0.4), abs=1e-3)
    assert wd.spearman([1, 3, 2, 5], [10, 30, 20, 50]) == pytest.approx(1.0)
    assert wd.spearman([5, 4, 3, 1, 2], [1, 2, 3, 4, 5]) == pytest.approx(-0.9)


def test_vertex_of_the_least_value():
    x = np.array([40.0, 44.0, 48.0, 50.0, 52.0, 54.0])
    assert wd._vertex(x, (x - 49.3) ** 2 + 7.0) == pytest.approx(49.3)
    assert wd._vertex(x, x) == 40.0  # at an end of the grid: the grid point


# ----------------------------------------------------------------------------- cases
def test_w2_quick_rows_pass():
    rows = wd.run_w2(quick=True)
    assert all(r.case == "wang-w2" for r in rows)
    assert {r.kind for r in rows} >= {"exact", "internal cross-check"}
    assert not _failed(rows), _failed(rows)


@pytest.mark.slow
def test_w3_quick_rows_pass():
    rows = wd.run_w3(quick=True)
    assert all(r.case == "wang-w3" and r.kind == "published" for r in rows)
    assert not _failed(rows), _failed(rows)


def test_w3_study_file_matches_the_case():
    """``cases/studies/wang_w3.yaml`` is the study run_w3 runs."""
    assert load_study(W3_STUDY) == study_from_dict(wd.w3_study())


@pytest.mark.slow
def test_w2_rows_pass():
    rows = wd.run_w2()
    assert not _failed(rows), _failed(rows)


@pytest.mark.slow
def test_w3_rows_pass():
    rows = wd.run_w3()
    assert len(rows) == 8
    assert not _failed(rows), _failed(rows)
