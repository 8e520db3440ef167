"""Tuah (1982) Example 7 with lift: coupled-mode strumming of the three-leg disc buoy."""

from __future__ import annotations

import math

import numpy as np
import pytest

from moorline.plot import plot_strumming
from moorline.verification import tuah_ex5 as ex5
from moorline.verification import tuah_ex7_lift as lift

DURATION = 12.0  # s: a short in-line run (the ramp and one period after it)


@pytest.fixture(scope="module")
def case() -> lift.Ex7LiftRun:
    return lift.run_case(DURATION)


def test_coupled_modes_include_the_disc(case: lift.Ex7LiftRun) -> None:
    modal = case.modal
    assert modal.n_modes == 18 + 6
    assert any(d == "disc sway" for d in modal.dominant)
    # the strumming keeps the modes of positive frequency only, mass-normalized shapes
    s = case.strumming
    assert np.all(s.omega > 0)
    assert s.mode_shapes.shape == (len(s.omega), s.mesh.n_nodes, 3)
    assert np.all((s.damping_ratio > 0) & (s.damping_ratio < 1))


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


def test_spectrum_peak_of_known_signal() -> None:
    t = np.arange(0.0, 21.0, 0.01)
    y = np.sin(ex5.OMEGA * t) + 0.01 * np.sin(25.0 * t)
    w, amp = lift.spectrum(t, y)
    assert lift.peak_frequency(w, amp, 0.1, lift.FAST_BAND) == pytest.approx(ex5.OMEGA,
                                                                             abs=w[1] / 2)
    assert lift.peak_frequency(w, amp, lift.FAST_BAND, w[-1]) == pytest.approx(25.0,
                                                                             abs=w[1] / 2)


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


def test_run_rows_quick() -> None:
    rows = {r.quantity: r for r in lift.run(fast=True)}
    assert len(rows) == 3
    for r in rows.values():
        assert r.case == lift.CASE and math.isfinite(r.computed)
    slow = next(r for q, r in rows.items() if "slow" in q)
    fast = next(r for q, r in rows.items() if "fast" in q)
    assert 0 < slow.computed < lift.FAST_BAND <= fast.computed
    assert slow.reference == pytest.approx(2 * math.pi / 3)
    assert next(r for q, r in rows.items() if "C_L0" in q).passed
