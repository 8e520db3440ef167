"""Tuah (1982) Example 7 with lift: strumming of the three-leg disc buoy by superposition of
the coupled (disc and legs) modes, refreshed at every in-line step."""

from __future__ import annotations

import math

import numpy as np
import pytest

from moorline.model import ModalSettings
from moorline.plot import plot_strumming
from moorline.solvers.modal import solve_modes
from moorline.verification import tuah_ex5 as ex5
from moorline.verification import tuah_ex7 as ex7
from moorline.verification import tuah_ex7_lift as lift
from moorline.waves import fluid_field_from_environment

DURATION = lift.FAST_STRUMMING_END  # s: the in-line run and the strumming


@pytest.fixture(scope="module")
def case() -> lift.Ex7LiftRun:
    return lift.run_case(DURATION, DURATION)


def test_modes_of_the_coupled_system_refreshed(case: lift.Ex7LiftRun) -> None:
    """A complete basis, refreshed at every in-line step; at the first step (the static
    equilibrium, all legs taut) the frequencies of a separate modal analysis."""
    s = case.strumming
    n_unknowns = 18 + 6  # two interior nodes per leg, the disc
    assert len(s.omega) == n_unknowns
    assert s.counters["refreshes"] == len(s.time) - 2
    assert s.omega_history.shape == (len(s.time) - 1, n_unknowns)
    system = ex7.ex7_system(case.inline.static.mesh.n_elements // len(ex7.AZIMUTHS_DEG))
    modal = solve_modes(system, ModalSettings(n_modes=n_unknowns, mass="consistent",
                                              added_mass=True), case.inline.static)
    fast = modal.omega > 1.0  # the slow ones carry the statics' regularization of the yaw
    assert np.allclose(s.omega_history[0][fast], modal.omega[fast], rtol=1e-8)


def test_shedding_frequency_from_the_in_line_state(case: lift.Ex7LiftRun) -> None:
    """w_s = 2 pi S_T |V_NR| / D (eq. 3.2.b.4) with V_NR (eq. 3.2.a.3) computed here from the
    in-line positions and velocities and the wave field, zero below Re = 40; anchors still."""
    s, inline = case.strumming, case.inline.result
    system = ex7.ex7_system(case.inline.static.mesh.n_elements // len(ex7.AZIMUTHS_DEG))
    fluid = fluid_field_from_environment(system.environment, ramp_time=ex5.RAMP_TIME)
    mesh = inline.mesh
    assert np.allclose(s.time, inline.time[:len(s.time)])
    for k in (0, 500, 1000, len(s.time) - 2):
        x, v = inline.positions[k], inline.velocities[k]
        for e, (a, b) in enumerate(mesh.elements):
            chord = x[b] - x[a]
            t = chord / math.sqrt(chord @ chord)
            mid = 0.5 * (x[a] + x[b])
            u = fluid.kinematics(mid[None], float(inline.time[k]))[0][0] - 0.5 * (v[a] + v[b])
            normal = u - (u @ t) * t
            speed = math.sqrt(normal @ normal)
            d = mesh.diameter[e]
            expected = 2 * math.pi * lift.STROUHAL * speed / d if speed * d / lift.NU >= 40 \
                else 0.0
            assert s.strouhal_frequency[k, e] == pytest.approx(expected, rel=1e-10, abs=1e-12)
    assert np.allclose(s.displacement[:, 1:4], 0.0)  # the anchors


def test_spectrum_tools_on_known_signals() -> None:
    t = np.arange(0.0, 21.0, 0.01)
    y = np.sin(ex5.OMEGA * t) + 0.01 * np.sin(25.0 * t)
    w, amp = lift.spectrum(t, y)
    assert lift.peak_frequency(w, amp, 0.1, lift.FAST_BAND) == pytest.approx(ex5.OMEGA,
                                                                             abs=w[1] / 2)
    assert lift.peak_frequency(w, amp, lift.FAST_BAND, w[-1]) == pytest.approx(25.0,
                                                                             abs=w[1] / 2)
    assert lift.centroid_frequency(w, amp**2, lift.FAST_BAND) == pytest.approx(25.0, abs=0.5)
    # zero crossings: pi per crossing, one crossing of resolution over the window
    assert lift.mean_frequency(t, np.sin(17.0 * t + 0.3)) == pytest.approx(
        17.0, abs=math.pi / 21.0)


def test_growth_rate_of_a_known_exponential() -> None:
    t = np.arange(0.0, 60.0, 0.01)
    y = 1e-12 * np.exp(0.4 * t) * np.sin(ex5.OMEGA * t)
    rate, start, end = lift.growth_rate(*lift.period_envelope(t, y, 0.0, ex5.WAVE_PERIOD),
                                        1e-9, 1e-2)
    assert rate == pytest.approx(0.4, rel=0.02)
    assert 1e-12 * math.exp(0.4 * start) > 1e-10 and 1e-12 * math.exp(0.4 * end) < 1e-2


def test_rows(case: lift.Ex7LiftRun) -> None:
    """No fail; the published rows cite the source; a not-reproduced row says why."""
    rows = lift.rows(case)
    assert len(rows) == 3
    failed = [r for r in rows if r.status == "fail"]
    assert not failed, "\n".join(f"{r.quantity}: {r.reference} vs {r.computed}" for r in failed)
    published = [r for r in rows if r.kind == "published"]
    assert len(published) == 2 and all(r.source.startswith("Tuah (1982)") for r in published)
    assert all("not reproduced:" in r.note for r in rows if not r.reproduced)


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
