"""Tuah (1982) Example 7 with lift (sec. 6.7): strumming of the three-leg disc buoy mooring.

The source: "the mode-superposition and Runge-Kutta integration methods with a time increment
of 0.001 seconds were employed to treat the transverse force" on top of the in-line response
(0.005 s). Its Figure 6.7-6 shows the lift coefficient against the stationary one (the
nonstationary lift's period is longer: "the tendency of the nonstationary lift frequency to
remain constant when the Strouhal frequency is in the vicinity of a structural natural
frequency"), and Figure 6.7-7 the disc's sway "due to the transverse force": a "long period
(slowly varying) motion which can be identified with the wave frequency and a short period
motion ... a high frequency fluctuation about the long period motion". The figures' values
are lost; what is checked here is that structure.

Model
-----
* In-line state: :func:`moorline.verification.tuah_ex7.run_dynamics` (the wave along +x, dt
  0.01 s, see that module), a short run (30 s; 21 s in the quick version) instead of six
  minutes. The coupling is one way (sec. 3.2.b): the in-line positions and velocities of every
  in-line step give the relative normal velocity ``V_NR`` of each element.
* Modes: those of the coupled system, the disc's six degrees of freedom with the legs
  (:func:`moorline.solvers.modal.solve_modes`, consistent mass with added mass), about the
  static equilibrium, computed once (the source's step 4 without refresh: at the in-line
  states of the wave the legs go slack in every period, where the tangent has negative
  eigenvalues). All modes of positive frequency are superposed (the disc's yaw has no
  stiffness and is dropped; a horizontal force at the keel shackle does not yaw the disc).
  :func:`moorline.solvers.strumming.solve_strumming` refuses systems with bodies, so the
  mode-superposition loop is repeated here with its pieces
  (:class:`moorline.solvers.strumming._Coupling`, :mod:`moorline.physics.wake`): the
  generalized lift ``phi_n . F_L`` sums over the nodes, the disc's keel node included (its
  motion in a mode is the disc's rigid motion), which is the virtual work of the lift on the
  coupled modes.
* Wake oscillator: Tuah eq. 3.2.b.3 with the signed transverse velocity (moorline's default;
  see :mod:`moorline.physics.wake`), ``S_T = 0.2``, ``C_L0 = 0.2``, the viscosity of Example 6
  (``nu = 1.13e-5 ft^2/s``; the Example 5 data do not give one), RK4 with 0.001 s (ten steps
  per in-line step, the source's). Modal damping eq. 3.2.b.8.
* Where the flow reverses (twice per wave period at every element) ``|V_NR|`` passes through
  zero. There ``w_s -> 0`` and the empirical ``k_s = 45 (nu / w_s)^(1/2) / D`` diverges, the
  wake parameter ``H`` overflows and the explicit integration blows up (it does, with
  :func:`~moorline.solvers.strumming.solve_strumming`'s ``w_s > 0`` rule). Below a Reynolds
  number of 40 a cylinder sheds no vortices: such elements are held inactive (``C_L`` frozen,
  no lift) until the flow picks up again. This is the only addition to the source's model.

What is checked
---------------
* The fairlead sway (the disc's keel, y, normal to the wave) from the strumming has a slow
  part at the wave frequency and a fast part near the shedding frequency: the two dominant
  peaks of its spectrum (after the wave's ramp), against ``2 pi / 3`` rad/s and against the
  force-weighted mean of ``2 pi S_T |V_NR| / D`` over the elements and the window (``V_NR``
  from the in-line velocities), each within the spectral resolution (plus, for the fast one,
  the spread of the shedding frequency over the wave cycle, stated).
* The lift coefficient against the stationary-cylinder ``C_L0``: the largest ``|C_L|`` of
  the shedding elements over ``C_L0`` (the source: it grows above the stationary one), and
  the rms ``C_L`` over ``C_L0 / sqrt(2)``.

Results (30 s run, window 9-30 s, resolution 0.30 rad/s)
--------------------------------------------------------
* Fast part: the fairlead sway's fast peak is at 24.3 rad/s, at the coupled mode of
  24.5 rad/s (lock-in), against the weighted shedding frequency 25.5 rad/s (which sweeps with
  a standard deviation of 9.3 rad/s over the wave cycle). With the signed ``U_T'`` the fast
  peak is at 14.2 rad/s (the 14.3 rad/s modes), outside that band.
* Slow part: NOT reproduced. The strumming sway of the fairlead (up to 0.32 ft) is dominated
  by the coupled system's slow modes (the disc's sway at 0.079 rad/s, the legs' pendulum modes
  at 0.24-0.71 rad/s), excited by the slow content of the lift while ``w_s`` sweeps through
  zero at the flow reversals; the spectrum has no peak at the wave frequency. That row fails.
* Lift: ``|C_L|`` reaches 4.0 ``C_L0`` (rms 1.5 times the stationary rms): above the
  stationary lift, as the source says.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from dataclasses import replace as dataclass_replace

import numpy as np
from numpy.typing import NDArray

from ..model import ModalSettings
from ..physics import wake
from ..results import DynamicResult, ModalResult
from ..solvers.modal import solve_modes
from ..solvers.strumming import (
    StrummingResult,
    StrummingSettings,
    _Coupling,
    _element_mass,
)
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
DURATION, FAST_DURATION = 30.0, 21.0  # s
FAST_BAND = 10.0  # rad/s: the sway spectrum's fast peak is sought above, the slow one below
FAIRLEAD_NODE = 0


def strumming_settings() -> StrummingSettings:
    """The wake-oscillator and modal settings of the case."""
    return StrummingSettings(viscosity=NU, strouhal=STROUHAL, CL0=CL0, n_modes=0,
                             mass="consistent", added_mass=True, substeps=SUBSTEPS,
                             transverse_velocity="magnitude")


def coupled_modes(run: ex7.Ex7Run) -> ModalResult:
    """All modes of the disc and its legs about the static equilibrium."""
    system = ex7.ex7_system(run.static.mesh.n_elements // len(ex7.AZIMUTHS_DEG))
    n = int(np.sum(run.static.mesh.dof_of_node >= 0)) + 6
    return solve_modes(system, ModalSettings(n_modes=n, mass="consistent", added_mass=True),
                       statics=run.static)


def _damping(shapes: FloatArray, omega: FloatArray, inline: DynamicResult,
             rho: float) -> FloatArray:
    """Eq. 3.2.b.8 damping ratios, ``rho D / m`` weighted by the legs' modal kinetic energy
    per element (as :func:`moorline.solvers.strumming.solve_strumming`)."""
    mesh = inline.mesh
    m = _element_mass(mesh, rho)
    a, b = mesh.elements[:, 0], mesh.elements[:, 1]
    energy = (mesh.length0 * m)[None] * ((shapes[:, a] ** 2).sum(-1)
                                         + (shapes[:, b] ** 2).sum(-1))
    energy /= np.maximum(energy.sum(axis=1, keepdims=True), np.finfo(float).tiny)
    return wake.modal_damping_ratio(omega, energy @ (mesh.diameter / m), 1.0, rho, NU)


def coupled_strumming(inline: DynamicResult, modal: ModalResult,
                      settings: StrummingSettings | None = None,
                      min_reynolds: float = MIN_REYNOLDS) -> StrummingResult:
    """Strumming by superposition of the coupled (disc and legs) modes.

    Tuah (1982) sec. 3.2.b, steps 1-11, as :func:`moorline.solvers.strumming.solve_strumming`
    (one-way coupling, the in-line output interval as the in-line step, RK4 substeps), with
    the modes of a body system given and elements below ``min_reynolds`` not shedding.

    Parameters
    ----------
    inline
        The Ex7 in-line run (:func:`moorline.verification.tuah_ex7.run_dynamics`).
    modal
        Modes of the coupled system (:func:`coupled_modes`); those of non-positive frequency
        are dropped.
    settings
        Wake-oscillator settings (default :func:`strumming_settings`; ``n_modes`` ignored).
    min_reynolds
        Elements with ``|V_NR| D / nu`` below this shed no vortices.

    Returns
    -------
    StrummingResult
        Lift coefficients, modal amplitudes, strumming displacements at the in-line steps.
    """
    from ..waves import fluid_field_from_environment

    settings = settings or strumming_settings()
    mesh = inline.mesh
    rho = float(mesh.water_density)
    keep = modal.omega > 0
    omega, shapes = modal.omega[keep], modal.mode_shapes[keep]
    xi = _damping(shapes, omega, inline, rho)
    system = ex7.ex7_system(mesh.n_elements // len(ex7.AZIMUTHS_DEG))
    fluid = fluid_field_from_environment(system.environment,
                                         ramp_time=inline.settings.get("ramp_time", 0.0))
    times, X, V = inline.time, inline.positions, inline.velocities
    n_t, n_el, n_modes = len(times), mesh.n_elements, len(omega)
    a, b, D, L0 = mesh.elements[:, 0], mesh.elements[:, 1], mesh.diameter, mesh.length0
    m_el = _element_mass(mesh, rho)
    z, zd = np.zeros(n_modes), np.zeros(n_modes)
    cl = np.full(n_el, settings.initial_CL if settings.initial_CL is not None else CL0)
    cld = np.zeros(n_el)
    out = {k: np.zeros((n_t, n_el)) for k in ("cl", "cld", "ws", "speed")}
    out_z, out_zd = np.zeros((n_t, n_modes)), np.zeros((n_t, n_modes))
    first: tuple | None = None

    def record(k: int) -> None:
        out["cl"][k], out["cld"][k] = cl, cld
        out_z[k], out_zd[k] = z, zd

    record(0)
    for k in range(n_t - 1):
        mid = 0.5 * (X[k][a] + X[k][b])
        u_fluid = fluid.kinematics(mid, float(times[k]))[0]
        v_nr, tangent = wake.relative_normal_velocity(X[k], V[k], u_fluid, mesh.elements)
        speed = np.linalg.norm(v_nr, axis=1)
        ws = wake.strouhal_frequency(speed, D, settings.strouhal)
        active = wake.reynolds_number(speed, D, settings.viscosity) >= min_reynolds
        w_safe = np.where(active, ws, 1.0)
        params = wake.wake_parameters(w_safe, D, m_el, rho, settings.viscosity,
                                      settings.strouhal)
        e_lift = wake.lift_direction(tangent, v_nr)
        if first is None:
            first = (params, e_lift)
        out["ws"][k], out["speed"][k] = np.where(active, ws, 0.0), speed
        B = 0.5 * np.einsum("mec,ec->em", shapes[:, a] + shapes[:, b], e_lift)
        c = np.where(active, wake.lift_force_per_length(1.0, speed, D, rho) * L0, 0.0)
        coupling = _Coupling(B, c, 2.0 * xi * omega, omega**2, w_safe, params.G, params.H,
                             params.F, settings.CL0, D, active,
                             settings.transverse_velocity == "magnitude")
        h = (times[k + 1] - times[k]) / settings.substeps
        for _ in range(settings.substeps):
            z, zd, cl, cld = coupling.rk4((z, zd, cl, cld), h)
        record(k + 1)
    out["ws"][-1], out["speed"][-1] = out["ws"][-2], out["speed"][-2]
    assert first is not None
    return StrummingResult(
        time=np.asarray(times, float), lift_coefficient=out["cl"], lift_rate=out["cld"],
        modal_amplitude=out_z, modal_velocity=out_zd,
        displacement=np.einsum("tm,mnc->tnc", out_z, shapes),
        velocity=np.einsum("tm,mnc->tnc", out_zd, shapes),
        strouhal_frequency=out["ws"], normal_speed=out["speed"], lift_direction=first[1],
        omega=omega, mode_shapes=shapes, damping_ratio=xi, omega_history=omega[None],
        refresh_times=np.asarray(times[:1], float), parameters=first[0], mesh=mesh,
        settings=settings,
        counters={"in_line_steps": n_t - 1, "rk4_steps": (n_t - 1) * settings.substeps,
                  "refreshes": 0})


@dataclass(frozen=True)
class Ex7LiftRun:
    """The in-line run, the coupled modes and the strumming."""

    inline: ex7.Ex7Run
    modal: ModalResult
    strumming: StrummingResult


def run_case(duration: float = DURATION) -> Ex7LiftRun:
    """In-line Ex7 run, coupled modes, strumming."""
    inline = ex7.run_dynamics(duration, ex7.DT)
    modal = coupled_modes(inline)
    return Ex7LiftRun(inline, modal, coupled_strumming(inline.result, modal))


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


def _weighted_shedding(result: StrummingResult, mask: NDArray[np.bool_]) -> tuple[float, float]:
    """Mean and standard deviation of ``w_s = 2 pi S_T |V_NR| / D`` over the shedding elements
    and the samples of ``mask``, weighted by the lift force scale ``|V_NR|^2 L0``."""
    ws = result.strouhal_frequency[mask]
    weight = result.normal_speed[mask] ** 2 * result.mesh.length0[None] * (ws > 0)
    mean = float((ws * weight).sum() / weight.sum())
    return mean, float(np.sqrt(((ws - mean) ** 2 * weight).sum() / weight.sum()))


def run(fast: bool = False) -> list[Row]:
    """Ex7-with-lift rows: the sway spectrum's slow and fast peaks, the lift coefficient.

    Parameters
    ----------
    fast
        Shorter in-line run (the tests): 21 s instead of 30 s.
    """
    inline = ex7.run_dynamics(FAST_DURATION if fast else DURATION, ex7.DT)
    modal = coupled_modes(inline)
    literal = coupled_strumming(inline.result, modal)
    signed = coupled_strumming(inline.result, modal, dataclass_replace(
        strumming_settings(), transverse_velocity="signed"))
    t = literal.time
    mask = t >= ex5.RAMP_TIME - 1e-9
    w, amp = spectrum(t[mask], literal.displacement[mask, FAIRLEAD_NODE, 1])
    resolution = float(w[1])
    slow = peak_frequency(w, amp, resolution / 2, FAST_BAND)
    fast_peak = peak_frequency(w, amp, FAST_BAND, float(w[-1]))
    w_s, spread = _weighted_shedding(literal, mask)
    ws_, amp_s = spectrum(t[mask], signed.displacement[mask, FAIRLEAD_NODE, 1])
    fast_signed = peak_frequency(ws_, amp_s, FAST_BAND, float(ws_[-1]))
    sway = literal.displacement[mask, FAIRLEAD_NODE, 1]
    sway_modes = ", ".join(f"{o:.3f}" for o, d in zip(modal.omega, modal.dominant,
                                                       strict=True)
                           if 0 < o < FAST_BAND and d in ("disc sway", "y"))
    near = float(literal.omega[np.argmin(np.abs(literal.omega - w_s))])
    rows = [
        Row(CASE, f"fairlead sway spectrum: dominant slow frequency (< {FAST_BAND} rad/s) vs "
            "the wave's", ex5.OMEGA, slow, resolution, relative=False, unit="rad/s",
            note=f"NOT reproduced: the source's slow sway follows the wave; here it is at the "
                 f"coupled system's sway modes ({sway_modes} rad/s: the disc's sway and the "
                 f"legs' pendulum modes), excited by the slow content of the lift while w_s "
                 f"sweeps through zero at the flow reversals; spectral resolution "
                 f"{resolution:.3f} rad/s over {t[mask][-1] - t[mask][0]:.1f} s; sway range "
                 f"{sway.min():+.3f} to {sway.max():+.3f} ft (in-line sway ~0 by symmetry)"),
        Row(CASE, "fairlead sway spectrum: dominant fast frequency vs 2 pi S_T |V_NR| / D",
            w_s, fast_peak, resolution + spread, relative=False, unit="rad/s",
            note=f"w_s from the in-line velocities, mean over elements and time weighted by "
                 f"|V_NR|^2 L0, std {spread:.2f} rad/s (it sweeps with the wave: tolerance = "
                 f"resolution + std); nearest natural frequency {near:.2f} rad/s (lock-in); "
                 f"wake driven by |U_T'| (literal, as Ex6); signed U_T': {fast_signed:.2f}"),
    ]
    cl = literal.lift_coefficient[mask]
    shedding = literal.strouhal_frequency[mask] > 0
    ratio = float(np.abs(cl[shedding]).max() / CL0)
    rms = float(np.sqrt(np.mean(cl[shedding] ** 2)) / (CL0 / math.sqrt(2.0)))
    signed_ratio = float(np.abs(signed.lift_coefficient[mask][shedding]).max() / CL0)
    rows.append(Row(CASE, "max |C_L| of the shedding elements above C_L0 (1 = yes)", 1.0,
                    float(ratio > 1.0), 0.0, relative=False,
                    note=f"max |C_L| / C_L0 = {ratio:.2f}, rms C_L / (C_L0 / sqrt 2) = "
                         f"{rms:.2f} (source: the lift grows above the stationary one); "
                         f"signed U_T': max ratio {signed_ratio:.2f}"))
    return rows


__all__ = ["CASE", "Ex7LiftRun", "coupled_modes", "coupled_strumming", "peak_frequency",
           "run", "run_case", "spectrum", "strumming_settings"]
