"""Tuah (1982) Example 7 with lift: strumming of the three-leg disc buoy by superposition of
the coupled (disc and legs) modes, refreshed at every in-line step."""

from __future__ import annotations

import math

import numpy as np
import pytest

from moorline.plot import plot_strumming
from moorline.verification import tuah_ex5 as ex5
from moorline.verification import tuah_ex7_lift as lift

DURATION = lift.FAST_STRUMMING_END  # s: the in-line run and the strumming


@pytest.fixture(scope="module")
def case() -> lift.Ex7LiftRun:
    return lift.run_case(DURATION, DURATION)


def test_modes_of_the_coupled_system_refreshed(case: lift.Ex7LiftRun) -> None:
    s = case.strumming
    n_unknowns = 18 + 6  # two interior nodes per leg, the disc
    assert len(s.omega) == n_unknowns  # a complete basis
    assert s.counters["refreshes"] == len(s.time) - 2
    assert s.omega_history.shape == (len(s.time) - 1, n_unknowns)
    # the frequencies move with the in-line state (legs slack and taut)
    assert np.ptp(s.omega_history[:, -1]) > 1.0
    assert case.static_modes.counters["refreshes"] == 0


def test_strumming_finite_and_lift_on_shedding_elements(case: lift.Ex7LiftRun) -> None:
    s = case.strumming
    assert np.all(np.isfinite(s.lift_coefficient))
    assert np.all(np.isfinite(s.displacement))
    # anchors held; the fairlead (disc keel) sways through the disc's modes
    assert np.allclose(s.displacement[:, 1:4], 0.0)
    assert np.abs(s.displacement[:, lift.FAIRLEAD_NODE, 1]).max() > 0
    # no shedding below Re 40: w_s zero there, and C_L above C_L0 somewhere
    re = s.normal_speed * s.mesh.diameter[None] / lift.NU
    assert np.all(s.strouhal_frequency[:-1][re[:-1] < lift.MIN_REYNOLDS] == 0.0)
    assert np.abs(s.lift_coefficient).max() > lift.CL0


def test_shedding_frequency_is_strouhal(case: lift.Ex7LiftRun) -> None:
    s = case.strumming
    on = s.strouhal_frequency > 0
    expected = 2 * math.pi * lift.STROUHAL * s.normal_speed / s.mesh.diameter[None]
    assert np.allclose(s.strouhal_frequency[on], expected[on])


def test_spectrum_tools_on_known_signals() -> None:
    t = np.arange(0.0, 21.0, 0.01)
    y = np.sin(ex5.OMEGA * t) + 0.01 * np.sin(25.0 * t)
    w, amp = lift.spectrum(t, y)
    assert lift.peak_frequency(w, amp, 0.1, lift.FAST_BAND) == pytest.approx(ex5.OMEGA,
                                                                             abs=w[1] / 2)
    assert lift.peak_frequency(w, amp, lift.FAST_BAND, w[-1]) == pytest.approx(25.0,
                                                                             abs=w[1] / 2)
    assert lift.centroid_frequency(w, amp**2, lift.FAST_BAND) == pytest.approx(25.0, abs=0.5)


def test_growth_rate_of_a_known_exponential() -> None:
    t = np.arange(0.0, 60.0, 0.01)
    y = 1e-12 * np.exp(0.4 * t) * np.sin(ex5.OMEGA * t)
    rate, start, end = lift.growth_rate(*lift.period_envelope(t, y, 0.0, ex5.WAVE_PERIOD),
                                        1e-9, 1e-2)
    assert rate == pytest.approx(0.4, rel=0.02)
    assert 1e-12 * math.exp(0.4 * start) > 1e-10 and 1e-12 * math.exp(0.4 * end) < 1e-2


def test_rows_of_the_short_run_pass(case: lift.Ex7LiftRun) -> None:
    rows = lift.rows(case, growth=False)
    assert len(rows) == 4
    failed = [r for r in rows if r.status == "fail"]
    assert not failed, "\n".join(f"{r.quantity}: {r.reference} vs {r.computed}" for r in failed)
    slow = rows[0]
    assert slow.reference == pytest.approx(2 * math.pi / 3)


def test_to_xarray_and_plot(case: lift.Ex7LiftRun, tmp_path) -> None:
    s = case.strumming
    ds = s.to_xarray()
    assert ds["lift_coefficient"].dims == ("time", "element")
    assert ds["modal_amplitude"].dims == ("time", "mode")
    assert ds["displacement"].dims == ("time", "node", "xyz")
    assert ds.sizes["mode"] == len(s.omega)
    assert ds.attrs["CL0"] == lift.CL0
    path = tmp_path / "strumming.png"
    plot_strumming(ds, path)
    assert path.stat().st_size > 0
