"""Tuah (1982) Example 7 with lift (sec. 6.7): strumming of the three-leg disc buoy mooring.

The source: "the mode-superposition and Runge-Kutta integration methods with a time increment
of 0.001 seconds were employed to treat the transverse force" on top of the in-line response
(0.005 s), the modes "recomputed every time step or every several steps of incremental
response" (sec. 3.2.b). Its Figure 6.7-6 shows the lift coefficient against the stationary
one, and Figure 6.7-7 the disc's sway "due to the transverse force": a "long period (slowly
varying) motion which can be identified with the wave frequency and a short period motion
... a high frequency fluctuation about the long period motion ... the low frequency sway
motion changes its direction suddenly as the cable slackens". The figures' values are lost;
what is checked here is that structure.

Model
-----
* In-line state: :func:`moorline.verification.tuah_ex7.run_dynamics` (the wave along +x, dt
  0.01 s, see that module). One-way coupling (sec. 3.2.b): the in-line positions and
  velocities of every in-line step give the relative normal velocity ``V_NR`` of each element
  and the state the modes are computed at.
* Strumming: :func:`moorline.solvers.strumming.solve_strumming` on the coupled system (the
  disc's six degrees of freedom with the legs' nodes; a mode moves the keel shackle rigidly
  with the disc), all modes superposed, recomputed at every in-line step (the source's step 4)
  with the strumming state carried over by mass projection (exact: the basis is complete).
  RK4 with 0.001 s (ten steps per in-line step, the source's). Modal damping eq. 3.2.b.8.
* Wake oscillator: Tuah eq. 3.2.b.3 driven by ``|U_T'|`` (the literal reading, as Example 6),
  ``S_T = 0.2``, ``C_L0 = 0.2``, the viscosity of Example 6 (``nu = 1.13e-5 ft^2/s``; the
  Example 5 data do not give one).
* Three choices the source does not make explicit, each needed for the analysis to be
  defined at all at the in-line states of this case (where the legs go slack and snap taut in
  every wave period):
  - elements below a Reynolds number of 40 shed no vortices (``min_reynolds``): where the flow
    reverses, ``w_s -> 0`` and the empirical ``k_s = 45 (nu / w_s)^(1/2) / D`` diverges;
  - the modes keep the taut axial stiffness in slack elements (``taut_axial``): the strumming
    perturbation is transverse and does not decide which elements are slack. With the exact
    tangent a slack leg has no axial stiffness, the lift drifts it along its length and every
    snap pumps that drift into ``EA / L0``: the legs' perturbation grew to 100 ft in 15 s;
  - modes of non-positive ``w^2`` are kept as they are (``nonpositive_modes: keep``): when all
    legs are slack the disc is free in surge and sway, and at tilted states the yaw's
    linearized stiffness is negative.

What the run shows
------------------
* The lift grows above the stationary one (``|C_L|`` up to about 4 ``C_L0``).
* The fairlead (disc keel) sway has its slow part at the wave frequency and its fast part
  (the acceleration spectrum above 10 rad/s) at the legs' shedding frequencies.
* The sway grows exponentially, at the rate with which the in-line run's own (round-off)
  asymmetry grows: the symmetric in-line motion of this reconstruction is unstable to a
  sway-roll-yaw motion (the disc pitches by up to 0.9 rad, its single-point mooring gives yaw
  no stiffness), and the linear strumming analysis, seeded by the lift, follows that
  instability. Two independent computations agree on the rate: the nonlinear Newmark run
  (from 1e-9 to 1e-2 ft) and the linear modal analysis. The source's six minutes of bounded
  sway therefore cannot be reproduced with these data; amplitudes beyond about 1 ft (10 % of
  the disc's diameter) are outside the linear analysis, while its frequencies and growth
  rate do not depend on the amplitude. Holding the disc's yaw in the strumming modes
  (``held_body_dofs``) keeps the sway bounded (0.3 ft over 60 s), but then the disc,
  free in sway whenever its legs are slack, drifts at its sway mode and the wave-frequency
  part is no longer dominant.
* With the modes computed once, about the static equilibrium (no refresh), the fast part
  locks in to the coupled mode nearest the shedding frequency (24.5 rad/s) and no wave-
  frequency part appears: the slow sway of the source comes from the modes changing with the
  in-line state.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..physics import wake
from ..solvers.strumming import StrummingResult, StrummingSettings, solve_strumming
from . import tuah_ex5 as ex5
from . import tuah_ex7 as ex7
from .core import Row

FloatArray = NDArray[np.float64]

CASE = "tuah-ex7-lift"
NU = 1.13e-5  # ft^2/s, Example 6's
CL0 = 0.2
STROUHAL = wake.DEFAULT_STROUHAL
SUBSTEPS = 10  # RK4 steps per in-line step: 0.001 s at dt 0.01 s (the source's)
MIN_REYNOLDS = 40.0  # no vortex shedding below
IN_LINE_DURATION = 60.0  # s: long enough for the in-line asymmetry to grow from round-off
STRUMMING_END, FAST_STRUMMING_END = 30.0, 21.0  # s
FAST_BAND = 10.0  # rad/s: the sway spectrum's fast part is sought above, the slow one below
FAIRLEAD_NODE = 0
SMALL_SWAY = 1.0  # ft: 10 % of the disc's diameter, the linear analysis' range
#: levels of the in-line run's sway between which its growth is measured: above round-off,
#: below nonlinearity [ft]
IN_LINE_LEVELS = (1e-9, 1e-2)


def strumming_settings(refresh: bool = True) -> StrummingSettings:
    """The wake-oscillator and modal settings of the case (modes refreshed at every in-line
    step, or computed once at the static equilibrium)."""
    return StrummingSettings(viscosity=NU, strouhal=STROUHAL, CL0=CL0, n_modes=0,
                             mass="consistent", added_mass=True, substeps=SUBSTEPS,
                             refresh_every=1 if refresh else 0,
                             transverse_velocity="magnitude", min_reynolds=MIN_REYNOLDS,
                             nonpositive_modes="keep", taut_axial=True)


@dataclass(frozen=True)
class Ex7LiftRun:
    """The in-line run and the strumming with refreshed and with static modes."""

    inline: ex7.Ex7Run
    strumming: StrummingResult
    static_modes: StrummingResult


def run_case(duration: float = IN_LINE_DURATION,
             strumming_end: float = STRUMMING_END) -> Ex7LiftRun:
    """In-line Ex7 run, then the strumming over its first ``strumming_end`` seconds."""
    inline = ex7.run_dynamics(duration, ex7.DT)
    system = ex7.ex7_system(inline.static.mesh.n_elements // len(ex7.AZIMUTHS_DEG))
    refreshed = solve_strumming(system, strumming_settings(True), inline.result,
                                end_time=strumming_end)
    static = solve_strumming(system, strumming_settings(False), inline.result,
                             end_time=strumming_end)
    return Ex7LiftRun(inline, refreshed, static)


def spectrum(t: FloatArray, y: FloatArray) -> tuple[FloatArray, FloatArray]:
    """One-sided amplitude spectrum of ``y`` (mean removed, Hann window) against the circular
    frequency [rad/time]."""
    dt = float(t[1] - t[0])
    y = (y - y.mean()) * np.hanning(len(y))
    amp = np.abs(np.fft.rfft(y))
    return 2.0 * math.pi * np.fft.rfftfreq(len(y), dt), amp


def peak_frequency(w: FloatArray, amp: FloatArray, lo: float, hi: float) -> float:
    """Frequency of the largest spectral amplitude in ``[lo, hi)``, refined by a parabola
    through the peak bin and its neighbours."""
    band = np.flatnonzero((w >= lo) & (w < hi))
    i = int(band[np.argmax(amp[band])])
    if 0 < i < len(amp) - 1:
        y0, y1, y2 = np.log(amp[i - 1:i + 2] + 1e-300)
        denom = y0 - 2.0 * y1 + y2
        shift = 0.5 * (y0 - y2) / denom if denom < 0 else 0.0
        return float(w[i] + shift * (w[1] - w[0]))
    return float(w[i])


def centroid_frequency(w: FloatArray, power: FloatArray, lo: float) -> float:
    """Power-weighted mean frequency of ``power`` over ``w >= lo``."""
    band = w >= lo
    return float((w[band] * power[band]).sum() / power[band].sum())


def period_envelope(t: FloatArray, y: FloatArray, start: float,
                    period: float) -> tuple[FloatArray, FloatArray]:
    """Largest ``|y|`` in each whole period from ``start``: mid-times and maxima."""
    n = int((t[-1] - start + 1e-9) // period)
    mids = start + (np.arange(n) + 0.5) * period
    peaks = np.array([np.abs(y[(t >= start + i * period) & (t < start + (i + 1) * period)])
                      .max() for i in range(n)])
    return mids, peaks


def growth_rate(mids: FloatArray, peaks: FloatArray, low: float = 0.0,
                high: float = math.inf) -> tuple[float, float, float]:
    """Exponential growth rate [1/time] of an envelope: least-squares slope of ``log``
    peaks from the first one above ``low`` to the last one before one reaches ``high``;
    and the window's first and last mid-times."""
    above = np.flatnonzero(peaks > low)
    if not above.size:
        return math.nan, math.nan, math.nan
    reach = np.flatnonzero(peaks >= high)
    i0, i1 = int(above[0]), int(reach[0]) if reach.size else len(peaks)
    if i1 - i0 < 3:
        return math.nan, math.nan, math.nan
    slope = np.polyfit(mids[i0:i1], np.log(peaks[i0:i1]), 1)[0]
    return float(slope), float(mids[i0]), float(mids[i1 - 1])


def _weighted_shedding(result: StrummingResult, mask: NDArray[np.bool_]) -> tuple[float, float]:
    """Mean and standard deviation of ``w_s = 2 pi S_T |V_NR| / D`` over the shedding elements
    and the samples of ``mask``, weighted by the lift force scale ``|V_NR|^2 L0``."""
    ws = result.strouhal_frequency[mask]
    weight = result.normal_speed[mask] ** 2 * result.mesh.length0[None] * (ws > 0)
    mean = float((ws * weight).sum() / weight.sum())
    return mean, float(np.sqrt(((ws - mean) ** 2 * weight).sum() / weight.sum()))


def run(quick: bool = False) -> list[Row]:
    """Ex7-with-lift rows: the sway's slow and fast parts, the lift coefficient, the growth
    rate against the in-line run's, the lock-in with static modes.

    Parameters
    ----------
    quick
        Shorter runs (the tests): in-line and strumming 21 s, no growth-rate row.
    """
    end = FAST_STRUMMING_END if quick else STRUMMING_END
    return rows(run_case(end if quick else IN_LINE_DURATION, end), growth=not quick)


def rows(case: Ex7LiftRun, growth: bool = True) -> list[Row]:
    """The rows of a run (:func:`run_case`); ``growth``: with the growth-rate row (needs an
    in-line run long enough for its asymmetry to grow from round-off, 60 s)."""
    s, static = case.strumming, case.static_modes
    t = s.time
    # the window: from the end of the wave's ramp while the sway is small (the linear
    # analysis' range; later the growing instability dominates the spectrum)
    after = t >= ex5.RAMP_TIME - 1e-9
    exceeds = np.flatnonzero(after & (np.abs(s.displacement[:, FAIRLEAD_NODE, 1])
                                      > SMALL_SWAY))
    small_until = float(t[exceeds[0]]) if exceeds.size else float(t[-1])
    mask = after & (t <= small_until)
    sway = s.displacement[mask, FAIRLEAD_NODE, 1]
    w, amp = spectrum(t[mask], sway)
    resolution = float(w[1])
    slow = peak_frequency(w, amp, resolution / 2, FAST_BAND)
    fast_part = centroid_frequency(w, (amp * w**2) ** 2, FAST_BAND)
    w_s, spread = _weighted_shedding(s, mask)
    window = (f"window {t[mask][0]:.1f}-{t[mask][-1]:.1f} s (from the ramp's end until "
              f"|sway| first exceeds {SMALL_SWAY:g} ft, 10 % of the diameter)")
    out = [
        Row(CASE, f"fairlead sway, slow part: dominant frequency below {FAST_BAND:g} rad/s "
            "vs the wave's", ex5.OMEGA, slow, resolution, relative=False, unit="rad/s",
            note=f"modes refreshed every in-line step; {window}; resolution "
                 f"{resolution:.2f} rad/s", kind="internal cross-check"),
        Row(CASE, "fairlead sway, fast part: centroid of the acceleration power above "
            f"{FAST_BAND:g} rad/s vs 2 pi S_T |V_NR| / D", w_s, fast_part, spread,
            relative=False, unit="rad/s",
            note=f"same window; w_s from the in-line velocities, mean over the shedding "
                 f"elements and time weighted by |V_NR|^2 L0; tolerance: its standard "
                 f"deviation over the wave cycle ({spread:.1f} rad/s)",
                 kind="internal cross-check"),
    ]
    shedding = s.strouhal_frequency[mask] > 0
    cl = s.lift_coefficient[mask]
    ratio = float(np.abs(cl[shedding]).max() / CL0)
    rms = float(np.sqrt(np.mean(cl[shedding] ** 2)) / (CL0 / math.sqrt(2.0)))
    out.append(Row(CASE, "max |C_L| of the shedding elements above C_L0 (1 = yes)", 1.0,
                    float(ratio > 1.0), 0.0, relative=False,
                    note=f"max |C_L| / C_L0 = {ratio:.2f}, rms C_L / (C_L0 / sqrt 2) = "
                         f"{rms:.2f} (source: the lift grows above the stationary one)",
                         kind="internal cross-check"))
    if growth:
        inline = case.inline.result
        rate_inline, a0, a1 = growth_rate(*period_envelope(
            inline.time, inline.positions[:, FAIRLEAD_NODE, 1], 0.0, ex5.WAVE_PERIOD),
            *IN_LINE_LEVELS)
        rate_lift, b0, b1 = growth_rate(*period_envelope(
            t, s.displacement[:, FAIRLEAD_NODE, 1], ex5.RAMP_TIME, ex5.WAVE_PERIOD))
        out.append(Row(
            CASE, "growth rate of the strumming sway vs that of the in-line run's own "
            "asymmetry", rate_inline, rate_lift, 0.15, unit="1/s",
            note=f"in-line (nonlinear Newmark, sway from round-off, {IN_LINE_LEVELS[0]:g} to "
                 f"{IN_LINE_LEVELS[1]:g} ft, t = {a0:.1f}-{a1:.1f} s) vs strumming (linear, "
                 f"modal, t = {b0:.1f}-{b1:.1f} s): the symmetric in-line motion is unstable "
                 f"to sway-roll-yaw and the lift seeds it; per-period maxima, log-linear fit",
                 kind="internal cross-check"))
    ws_, amp_s = spectrum(t[after], static.displacement[after, FAIRLEAD_NODE, 1])
    lock = peak_frequency(ws_, amp_s, FAST_BAND, float(ws_[-1]))
    band = static.omega[np.abs(static.omega - w_s) <= spread]
    near = float(band[np.argmin(np.abs(band - lock))]) if band.size else math.nan
    out.append(Row(
        CASE, "static modes: fast sway peak vs the nearest natural frequency in the shedding "
        "band (lock-in)", near, lock, float(ws_[1]), relative=False, unit="rad/s",
        note=f"modes computed once at the static equilibrium (the sway stays bounded); window "
             f"{t[after][0]:.0f}-{t[after][-1]:.0f} s; natural frequencies within w_s = "
             f"{w_s:.1f} +- {spread:.1f} rad/s: "
             + ", ".join(f"{o:.2f}" for o in band) + "; tolerance: the spectral resolution",
             kind="internal cross-check"))
    return out


__all__ = ["CASE", "Ex7LiftRun", "centroid_frequency", "growth_rate", "peak_frequency",
           "period_envelope", "rows", "run", "run_case", "spectrum", "strumming_settings"]
