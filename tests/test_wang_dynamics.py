"""Wang, Er and Iu cases W2 (forced response of the moored box) and W3 (its parameter study):
quick versions of the verification rows, the linearized reference model and the helpers."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from moorline.sweep import load_study, study_from_dict
from moorline.verification import wang_dynamics as wd
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


# ----------------------------------------------------------------------------- model
def test_forced_equilibrium_carries_the_force(equilibrium):
    history = equilibrium.system.bodies["box"].force_history
    assert history.kind == "harmonic"
    assert history.amplitude == (1e5, 0.0, 0.0)
    assert history.period == pytest.approx(2 * math.pi / 1.6)
    assert equilibrium.draft == pytest.approx(0.896, rel=5e-3)


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


def test_forcing_sits_on_the_first_line_modes(linear):
    """The documented finding: the lines' first transverse modes are near 1.6 rad/s."""
    freqs = linear.frequencies()
    assert np.all(freqs > 0.5)
    assert np.min(np.abs(freqs - 1.6)) < 0.05


def test_surge_pitch_frequency_and_rayleigh(equilibrium):
    w = wd.surge_pitch_frequency(equilibrium)
    assert w == pytest.approx(2.0678, abs=1e-3)
    a0, a1 = wd.rayleigh_coefficients(0.03, (1.6, w))
    for omega in (1.6, w):  # ratio a0 / (2 w) + a1 w / 2 at both frequencies
        assert a0 / (2 * omega) + a1 * omega / 2 == pytest.approx(0.03)


def test_quasi_static_response_at_zero_frequency(equilibrium):
    X = wd.quasi_static_response(equilibrium, (0.0, 0.0), amplitude=1e5, omega=0.0)
    expected = np.linalg.solve(wd.body_stiffness(equilibrium), [1e5, 0, 0, 0, 0, 0])
    assert np.allclose(X.real, expected, rtol=1e-10, atol=1e-14)


# ----------------------------------------------------------------------------- helpers
def test_signal_helpers():
    t = np.arange(0.0, 40 * math.pi / 1.6, 0.01)
    y = 0.3 + 0.5 * np.sin(1.6 * t + 0.4) + 0.05 * np.sin(3.2 * t)
    fit = harmonic_fit(t, y, 1.6)
    assert (fit.mean, fit.amplitude(), fit.phase()) == pytest.approx((0.3, 0.5, 0.4), abs=1e-3)
    assert wd.crossing_period(t, y) == pytest.approx(2 * math.pi / 1.6, rel=1e-5)
    period, resolution = wd.dominant_period(t, np.sin(3.2 * t))
    assert abs(period - math.pi / 1.6) <= resolution
    assert wd.spearman([1, 3, 2, 5], [10, 30, 20, 50]) == pytest.approx(1.0)
    assert wd.spearman([5, 4, 3, 1, 2], [1, 2, 3, 4, 5]) == pytest.approx(-0.9)


def test_line_mass_share(equilibrium):
    assert wd.line_mass_share(equilibrium) == pytest.approx(0.306, abs=2e-3)


# ----------------------------------------------------------------------------- cases
def test_w2_quick_rows_pass():
    rows = wd.run_w2(quick=True)
    assert len(rows) >= 9
    assert all(r.case == "wang-w2" for r in rows)
    assert not _failed(rows), _failed(rows)


def test_w3_quick_rows_pass():
    rows = wd.run_w3(quick=True)
    assert len(rows) >= 9
    assert all(r.case == "wang-w3" for r in rows)
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
    assert len(rows) == 9
    assert not _failed(rows), _failed(rows)
