"""The least-squares harmonic fit of a time history."""

from __future__ import annotations

import math

import numpy as np
import pytest

from moorline.verification.signals import harmonic_fit


def test_recovers_mean_trend_and_harmonics_exactly():
    """A signal made of exactly the fitted functions is recovered to round-off."""
    w = 1.3
    t = np.linspace(2.0, 40.0, 900)
    y = (0.7 + 0.02 * (t - t.mean()) + 0.5 * np.cos(w * t) - 0.2 * np.sin(w * t)
         + 0.1 * np.cos(2 * w * t) + 0.05 * np.sin(2 * w * t))
    fit = harmonic_fit(t, y, w, harmonics=2, trend=True)
    assert fit.mean == pytest.approx(0.7, abs=1e-12)
    assert fit.slope == pytest.approx(0.02, abs=1e-12)
    assert np.allclose(fit.cos, [0.5, 0.1], atol=1e-12)
    assert np.allclose(fit.sin, [-0.2, 0.05], atol=1e-12)
    assert fit.phasor() == pytest.approx(complex(0.5, -0.2), abs=1e-12)
    # Re(Y e^{-i w t}) is the first harmonic
    assert np.allclose((fit.phasor() * np.exp(-1j * w * t)).real,
                       0.5 * np.cos(w * t) - 0.2 * np.sin(w * t), atol=1e-12)


def test_amplitude_and_phase_of_a_sine():
    """``a sin(w t + phase)``: amplitude and phase; no trend fitted gives slope 0."""
    w, a, phase = 0.8, 2.5, -2.0
    t = np.linspace(0.0, 6 * math.pi / w, 400, endpoint=False)
    fit = harmonic_fit(t, 1.5 + a * np.sin(w * t + phase), w)
    assert fit.slope == 0.0 and fit.cos.shape == (1,)
    assert (fit.mean, fit.amplitude(), fit.phase()) == pytest.approx((1.5, a, phase),
                                                                     abs=1e-12)
