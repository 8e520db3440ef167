"""The source's incremental scheme of Tuah Example 3 (moorline.verification.tuah_ex3).

Checked against the closed-form creep (viscoelastic_reference.creep_strain, itself checked
against scipy's ODE solution in test_material) and against the step-size limit of the scheme,
an ODE integrated here by scipy.
"""

from __future__ import annotations

import numpy as np
import pytest
import scipy.integrate

from moorline.verification import viscoelastic_reference as ref
from moorline.verification.tuah_ex3 import source_scheme

# the SLS fitted to Table 6.3-1 (EA = 1); any positive values would do for these checks
T1, EA1, TAU = ref.TUAH_EX3_FINAL_STRAIN, 7.4641, 4.9209
K = EA1 + 1.0


def _grid(dt: float) -> np.ndarray:
    return np.linspace(0.0, 3.0, round(3.0 / dt) + 1)


def _exact_3s() -> float:
    return float(ref.creep_strain(3.0, T1, 1.0, 1.0, EA1, TAU))


@pytest.mark.parametrize("terms", [0, 1, 2])
def test_residual_feedback_converges_to_the_closed_form_at_first_order(terms):
    """Whatever the tangent, feeding the residual back drives the stress to the applied force:
    the strain at 3 s tends to the closed form, the error halving with dt (ratio 2 +- 0.15:
    eq. 2.2.b.3 is explicit in its delay term and the strain increment is linearized)."""
    errors = [abs(source_scheme(_grid(dt), T1, 1.0, 1.0, EA1, TAU, residual_feedback=True,
                                initial_stress_terms=terms)[-1] - _exact_3s())
              for dt in (0.1, 0.05, 0.025)]
    assert errors[0] < 1e-2 * _exact_3s()
    assert np.all(np.abs(np.array(errors[:-1]) / errors[1:] - 2.0) < 0.15), errors


def _continuous_limit(terms: int) -> float:
    """dt -> 0 of the purely incremental scheme: with lam and sig as states,
    d lam/dt = (dT/dt - (eps - sig) / tau) / k,  k = terms sig / lam + K lam,
    d sig/dt = (eps - sig) / tau + K lam d lam/dt,  eps = (lam^2 - 1) / 2 (EA = 1)."""
    def rhs(t, y, rate):
        lam, sig = y
        delay = (0.5 * (lam * lam - 1.0) - sig) / TAU
        dlam = (rate - delay) / (terms * sig / lam + K * lam)
        return [dlam, delay + K * lam * dlam]

    opts = {"rtol": 1e-11, "atol": 1e-13, "method": "DOP853"}
    ramp = scipy.integrate.solve_ivp(rhs, (0.0, 1.0), [1.0, 0.0], args=(T1,), **opts)
    hold = scipy.integrate.solve_ivp(rhs, (1.0, 3.0), ramp.y[:, -1], args=(0.0,), **opts)
    lam = hold.y[0, -1]
    return 0.5 * (lam * lam - 1.0)


@pytest.mark.parametrize("terms", [0, 1, 2])
def test_purely_incremental_tends_to_its_continuous_limit(terms):
    """Without the residual the scheme tends, at first order in dt, to the solution of its
    own continuous limit (the ODE above), not to the closed form: with the consistent axial
    tangent (no initial-stress term) that limit is the closed form itself (no drift); with
    the initial-stress term of eq. 2.2.b.8 it lies below it by more than 5e-3 at 3 s (a lag
    of the stress that no step size removes)."""
    limit = _continuous_limit(terms)
    errors = [abs(source_scheme(_grid(dt), T1, 1.0, 1.0, EA1, TAU,
                                initial_stress_terms=terms)[-1] - limit)
              for dt in (0.05, 0.025, 0.0125)]
    assert np.all(np.abs(np.array(errors[:-1]) / errors[1:] - 2.0) < 0.15), errors
    if terms == 0:
        assert limit == pytest.approx(_exact_3s(), rel=1e-9)
    else:
        assert limit < _exact_3s() - 5e-3


def test_first_steps_from_rest_agree():
    """From rest the stress is zero, so the first step has the consistent tangent and leaves
    no residual: both variants agree exactly after two steps."""
    grid = _grid(0.1)
    pure = source_scheme(grid, T1, 1.0, 1.0, EA1, TAU)
    feedback = source_scheme(grid, T1, 1.0, 1.0, EA1, TAU, residual_feedback=True)
    assert pure[1] == feedback[1] and pure[2] == feedback[2]
    assert pure[3] != feedback[3]
