"""Stochastic frequency-domain response of a mid-water riser in a random sea (Tuah 1982 ch. 5).

A 46.05 m line (D 0.1 m, 20 kg/m, EA 2e7 N, Cd 1.2, Ct 0.01) is held between an anchor at
(0, 0, -50) m and a fixed top at (10, 0, -5) m, about 20 kN of pretension, in a JONSWAP sea
(Hs 3 m, Tp 8 s, gamma 3.3) from +x, DSA amplitudes, 200 frequencies over a 256 s record
(Tuah's Example 5 discretization). The frequency-domain analysis
(:func:`moorline.solvers.stochastic.solve_stochastic`) is checked against:

* exact: the statistically linearized response of the continuous riser
  (:func:`continuum_riser`: the same linearized equations on the continuous line about the
  closed-form catenary, :mod:`~moorline.verification.linear_cable`, with
  :func:`airy_kinematics` written here), both linearizations iterated to 1e-6: the
  mid-length std of x and the top element's tension std at 40 elements within the
  Richardson estimate of their discretization error, and the observed order of convergence
  (2: 20/40/80 elements 0.30 %, 0.073 %, 0.015 % off in the std of x);
* exact: the kinematics transfer functions against Airy theory written here, and the DSA
  record's variance against the discrete spectrum's area (Parseval);
* internal cross-checks (moorline against moorline): Foss's decoupling over all modes against
  the direct solution of the full linear system at every frequency (round-off); the transfer
  functions against the time-domain wave field; the nonlinear time-domain model
  (:func:`moorline.solvers.dynamics.simulate`, quadratic drag on the relative velocity,
  Newmark, dt 0.1 s) run for two records in the same DSA realization: the standard
  deviations over the second record, and the correlation of the two time series.
  Statistical linearization (Borgman) replaces ``|u| u`` by ``(8/pi)^(1/2) sigma u``, whose
  variance ``(8/pi) sigma^4`` is below the true ``3 sigma^4``, and the quadratic drag spreads
  response over sum and difference frequencies that a linear analysis does not have: the
  frequency domain comes out about 10 % low; the tolerance is 20 %; with less drag (Cd 0.3,
  inertia-dominated; full form only), the response within the wave band (from the FFT of the
  time-domain record, component by component): within 3 %.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..catenary import solve_catenary
from ..model import (
    DynamicsSettings,
    Environment,
    Line,
    LineType,
    Point,
    StochasticSettings,
    System,
    Waves,
)
from ..solvers.dynamics import simulate
from ..solvers.statics import solve_statics
from ..solvers.stochastic import solve_stochastic
from ..waves import fluid_field_from_environment
from ..waves.transfer import kinematics_transfer
from .core import Row
from .linear_cable import Cable, fixed_ends, transfer

CASE = "stochastic-riser"
DEPTH, TOP = 50.0, (10.0, 0.0, -5.0)
LENGTH, SEGMENTS = 46.05, 20
RECORD, N_FREQUENCIES = 256.0, 200
DT = 0.1
MID_NODE = 11  # node at mid-length: the points (anchor 0, top 1) come first, then the line
GRAVITY = 9.80665


def riser_system(segments: int = SEGMENTS, Cd: float = 1.2) -> System:
    """The riser in its random sea (``Cd``: its normal drag coefficient)."""
    lt = LineType("rope", diameter=0.1, mass_per_length=20.0, EA=2.0e7, Cd=Cd, Ct=0.01,
                  Ca=1.0)
    waves = Waves(kind="random", spectrum="jonswap", height=3.0, period=8.0, gamma=3.3,
                  amplitudes="dsa", seed=2, record_length=RECORD, n_frequencies=N_FREQUENCIES)
    env = Environment(depth=DEPTH, water_density=1025.0, gravity=GRAVITY, waves=waves)
    points = {"anchor": Point("anchor", "fixed", (0.0, 0.0, -DEPTH)),
              "top": Point("top", "fixed", TOP)}
    lines = {"riser": Line("riser", "rope", LENGTH, segments, "anchor", "top")}
    return System(CASE, environment=env, line_types={"rope": lt}, points=points, lines=lines)


def airy_wave_number(omega: np.ndarray, depth: float = DEPTH, g: float = GRAVITY
                     ) -> np.ndarray:
    """``k`` of ``omega^2 = g k tanh kh`` by bisection (written here, independent of
    :mod:`moorline.waves`)."""
    omega = np.asarray(omega, float)
    lo, hi = np.full_like(omega, 1e-12), omega**2 / g + 10.0 / depth
    for _ in range(100):  # g k tanh(k h) rises in k; 100 halvings reach round-off
        mid = 0.5 * (lo + hi)
        low = g * mid * np.tanh(mid * depth) < omega**2
        lo, hi = np.where(low, mid, lo), np.where(low, hi, mid)
    return 0.5 * (lo + hi)


def airy_kinematics(points: np.ndarray, omega: np.ndarray, k: np.ndarray | None = None,
                    depth: float = DEPTH) -> tuple[np.ndarray, np.ndarray]:
    """Velocity and acceleration per unit complex amplitude of a linear wave travelling along
    +x, ``eta = Re exp(i (omega t - k x))``, at ``points`` (n, 3): (n_omega, n, 3).

    Airy theory (Dean & Dalrymple 1991 eq. 4.13): ``u = omega cosh k(z+h) / sinh kh``,
    ``w = i omega sinh k(z+h) / sinh kh``; ``k`` from :func:`airy_wave_number` when not
    given."""
    omega = np.asarray(omega, float)
    k = (airy_wave_number(omega, depth) if k is None else np.asarray(k, float))[:, None]
    p = np.atleast_2d(points)
    zh = p[None, :, 2] + depth
    phase = omega[:, None] * np.exp(-1j * k * p[None, :, 0]) / np.sinh(k * depth)
    v = np.stack([np.cosh(k * zh) * phase, np.zeros_like(phase), 1j * np.sinh(k * zh) * phase],
                 axis=-1)
    return v, 1j * omega[:, None, None] * v


@dataclass(frozen=True)
class ContinuumResponse:
    """Statistically linearized response of the continuous riser (:func:`continuum_riser`)."""

    s: np.ndarray  #: stations along the unstretched length [m]
    U: np.ndarray  #: displacement transfer (stations, n_omega, 3) per unit wave amplitude
    tension: np.ndarray  #: tension transfer (stations, n_omega)
    displacement_std: np.ndarray  #: (stations, 3)
    tension_std: np.ndarray  #: (stations,)
    iterations: int


def continuum_riser(omega: np.ndarray, power: np.ndarray, Cd: float = 1.2, steps: int = 100,
                    tol: float = 1e-6, max_iter: int = 50) -> ContinuumResponse:
    """Frequency-domain response of the continuous riser with statistically linearized drag.

    The same equations as :func:`moorline.solvers.stochastic.solve_stochastic` (Tuah (1982)
    eq. 5.1-5.2: linearized normal and tangential drag ``(2/pi)^(1/2) C_D rho D sigma_n``,
    ``(2 pi)^(1/2) C_T rho D sigma_t`` on the relative velocity, fluid inertia
    ``rho A [(1 + Ca)(I - t t^T) + t t^T] a``, normal added mass), on the continuous line
    about the closed-form elastic catenary, integrated along the line
    (:mod:`~moorline.verification.linear_cable`) with :func:`airy_kinematics`; the standard
    deviations are iterated to ``tol`` (relative) from the structure at rest.

    Parameters
    ----------
    omega, power
        Frequencies of the discrete sea and the variance of each component
        (``S(omega) d_omega``).
    """
    lt = riser_system(Cd=Cd).line_types["rope"]
    rho, area = 1025.0, 0.25 * np.pi * lt.diameter**2
    weight = (lt.mass_per_length - rho * area) * GRAVITY
    line = solve_catenary(TOP[0], TOP[2] + DEPTH, LENGTH, lt.EA, weight, seabed_contact=False)
    cable = Cable(LENGTH, lt.EA, (line.H_a, 0.0, line.V_a), weight, lt.mass_per_length,
                  lt.Ca * rho * area, origin=(0.0, 0.0, -DEPTH))
    stations = np.linspace(0.0, LENGTH, steps + 1)
    r0 = np.array([cable.position(x) for x in stations])
    tangent = np.array([cable.force(x) / np.linalg.norm(cable.force(x)) for x in stations])
    k = airy_wave_number(omega)
    V = airy_kinematics(r0, omega, k)[0].transpose(1, 0, 2)  # (stations, n_omega, 3)
    sigma = np.zeros((2, len(stations)))

    def drag(x: float, t: np.ndarray) -> np.ndarray:
        n, tt = (np.interp(x, stations, sig) for sig in sigma)
        P = np.outer(t, t)
        return (np.sqrt(2.0 / np.pi) * Cd * rho * lt.diameter * n * (np.eye(3) - P)
                + np.sqrt(2.0 * np.pi) * lt.Ct * rho * lt.diameter * tt * P)

    def load(x: float, r: np.ndarray, t: np.ndarray) -> np.ndarray:
        v, a = airy_kinematics(r[None], omega, k)
        P = np.outer(t, t)
        inertia = rho * area * ((1.0 + lt.Ca) * (np.eye(3) - P) + P)
        return v[:, 0] @ drag(x, t).T + a[:, 0] @ inertia.T

    def relative(U: np.ndarray) -> np.ndarray:
        R = V - 1j * omega[None, :, None] * U
        along = np.einsum("kwc,kc->kw", R, tangent)
        normal = R - along[..., None] * tangent[:, None]
        return np.sqrt(np.array([np.einsum("w,kw->k", power, np.sum(np.abs(normal)**2, -1)),
                                 np.einsum("w,kw->k", power, np.abs(along)**2)]))

    U = np.zeros_like(V)
    sigma = relative(U)
    iterations = 0
    while iterations < max_iter:
        iterations += 1
        y = fixed_ends(transfer(cable, omega, load=load,
                                damping=lambda x, r, t: drag(x, t), steps=steps)[1])
        U = y[..., :3]
        new = relative(U)
        change = float(np.max(np.abs(new - sigma) / np.maximum(new, 1e-12 * new.max())))
        sigma = new
        if change <= tol:
            break
    tension = np.einsum("kwc,kc->kw", y[..., 3:6], tangent)
    return ContinuumResponse(stations, U, tension,
                             np.sqrt(np.einsum("w,kwc->kc", power, np.abs(U)**2)),
                             np.sqrt(np.einsum("w,kw->k", power, np.abs(tension)**2)), iterations)


def _exact_rows() -> list[Row]:
    """Frequency-domain standard deviations (20 and 40 elements) against the continuum."""
    settings = StochasticSettings(method="direct", tolerance=1e-6, max_iterations=60)
    fd = {n: solve_stochastic(riser_system(n), settings) for n in (SEGMENTS, 2 * SEGMENTS)}
    ref = fd[SEGMENTS]
    exact = continuum_riser(ref.omega, ref.wave_spectrum * ref.d_omega)
    mid = len(exact.s) // 2
    a = {n: float(r.displacement_std[r.mesh.line_nodes[0][n // 2], 0]) for n, r in fd.items()}
    ex = float(exact.displacement_std[mid, 0])
    err = {n: abs(v - ex) for n, v in a.items()}
    order = math.log2(err[SEGMENTS] / err[2 * SEGMENTS])
    estimate = abs(a[SEGMENTS] - a[2 * SEGMENTS]) / 3.0  # Richardson: the error left at 40
    listing = (f"{SEGMENTS} elements {a[SEGMENTS]:.5g} m, {2 * SEGMENTS} elements "
               f"{a[2 * SEGMENTS]:.5g} m, continuum {ex:.5g} m ({exact.iterations} "
               "linearization iterations); both linearizations iterated to 1e-6")
    # the element tension sits at the element midpoint: the continuum there
    top = float(np.interp(LENGTH * (1.0 - 0.5 / (2 * SEGMENTS)), exact.s, exact.tension_std))
    t40, t20 = float(fd[2 * SEGMENTS].tension_std[-1]), float(fd[SEGMENTS].tension_std[-1])
    return [
        Row(CASE, f"mid-length node: std of x, frequency domain ({2 * SEGMENTS} elements) vs "
            "the continuous riser (statistical linearization, exact catenary)", ex,
            a[2 * SEGMENTS], 1.5 * estimate / ex, unit="m",
            note=f"{listing}; tolerance: the Richardson estimate of the 40-element error, "
            "|a20 - a40| / 3, with 50 % margin", kind="exact",
            source="continuum_riser: linear_cable + airy_kinematics"),
        Row(CASE, "mid-length node: std of x, observed order of the error against the "
            f"continuous riser ({SEGMENTS} -> {2 * SEGMENTS} elements)", 2.0, order, 0.3,
            relative=False, note="straight elements with lumped loads: order 2",
            kind="exact", source="continuum_riser"),
        Row(CASE, f"top element: std of the tension, frequency domain ({2 * SEGMENTS} "
            "elements) vs the continuous riser at the element midpoint", top, t40,
            1.5 * abs(t20 - t40) / 3.0 / top, unit="N",
            note=f"{SEGMENTS} elements {t20:.5g} N; tolerance as for the displacement",
            kind="exact", source="continuum_riser"),
    ]


def _time_domain(system: System, static) -> tuple:
    """Two records of the nonlinear time-domain model; the mask of the second."""
    td = simulate(system, DynamicsSettings(duration=2 * RECORD, dt=DT, ramp_time=20.0),
                  initial=static, output_every=DT)
    return td, td.time >= RECORD - 1e-9


def run(quick: bool = False) -> list[Row]:
    """The rows (see the module docstring); ``quick`` leaves out the Cd 0.3 time-domain
    run."""
    system = riser_system()
    static = solve_statics(system)
    # Foss's modal sum over every mode (n_modes 0, the default, solves the full system)
    foss = solve_stochastic(system, StochasticSettings(method="foss",
                                                       n_modes=static.mesh.n_dofs), static)
    direct = solve_stochastic(system, StochasticSettings(method="direct"), static)
    scale = float(np.abs(direct.displacement_transfer).max())
    # round-off floor of Foss's modal sum: eps / (closest pair of poles, relative); near a
    # critically damped mode two poles meet and the two modal terms, each ~ 1 / gap, cancel
    gap = float(foss.counters["pole_gap"])
    floor = np.finfo(float).eps / gap
    rows = [Row(CASE, "Foss decoupling (all modes) vs direct solution: max |H_u| difference / "
                "max |H_u|", 0.0,
                float(np.abs(foss.displacement_transfer - direct.displacement_transfer).max()
                      / scale), max(1e-8, 100.0 * floor), relative=False,
                note=f"{foss.counters['modes']} modes, {len(foss.omega)} frequencies; "
                     f"{foss.iterations} linearization iterations (tolerance 0.01); closest "
                     f"poles {gap:.1e} apart (relative): round-off floor eps/gap = "
                     f"{floor:.1e}, tolerance 100 times that", kind="internal cross-check")]

    # kinematics transfer functions against the time-domain field
    mesh, x0 = static.mesh, static.positions
    mid = 0.5 * (x0[mesh.elements[:, 0]] + x0[mesh.elements[:, 1]])
    waves = system.environment.waves
    H_v, H_a = kinematics_transfer(mid, foss.omega, waves.heading_deg, DEPTH, 9.80665)
    field = fluid_field_from_environment(system.environment)
    worst = 0.0
    for t in (3.7, 101.3):
        rot = np.exp(1j * foss.omega * t) * foss.wave_amplitude
        v = 2.0 * np.real(np.einsum("w,wpc->pc", rot, H_v))
        a = 2.0 * np.real(np.einsum("w,wpc->pc", rot, H_a))
        v_td, a_td, _ = field.kinematics(mid, t)
        worst = max(worst, float(np.abs(v - v_td).max() / np.abs(v_td).max()),
                    float(np.abs(a - a_td).max() / np.abs(a_td).max()))
    rows.append(Row(CASE, "fluid velocity and acceleration transfer functions vs the time-"
                    "domain wave field (max relative difference)", 0.0, worst, 1e-10,
                    relative=False, note="eq. 5.2.8-5.2.10 at the element midpoints, two "
                                         "instants", kind="internal cross-check"))
    v_ref, a_ref = airy_kinematics(mid, foss.omega)
    airy = max(float(np.abs(H_v - v_ref).max() / np.abs(v_ref).max()),
               float(np.abs(H_a - a_ref).max() / np.abs(a_ref).max()))
    rows.append(Row(CASE, "fluid velocity and acceleration transfer functions vs Airy theory "
                    "(max relative difference)", 0.0, airy, 1e-10, relative=False,
                    note="airy_kinematics written in the case (own dispersion solve) at the "
                    "element midpoints, all frequencies", kind="exact",
                    source="Airy theory, Dean & Dalrymple (1991)"))
    discrete = float(np.sum(foss.wave_spectrum) * foss.d_omega)
    rows.append(Row(CASE, "DSA record: elevation variance vs the discrete spectrum's area",
                    discrete, float(np.var(foss.elevation)), 1e-9, unit="m^2",
                    note=f"m0 = Hs^2/16 = {3.0**2 / 16:.4f} m^2 less the tail beyond "
                         f"{foss.omega[-1]:.2f} rad/s; sinusoids at the record's Fourier "
                         "frequencies: the variance is sum a^2/2 exactly", kind="exact",
                    source="Parseval"))
    rows += _exact_rows()

    # against the nonlinear time-domain model in the same realization
    td, second = _time_domain(system, static)
    u_td = td.positions[second, MID_NODE, 0]
    top = mesh.n_elements - 1
    rows.append(Row(CASE, "mid-length node: std of x, frequency domain vs nonlinear time "
                    "domain", float(np.std(u_td)), float(foss.displacement_std[MID_NODE, 0]),
                    0.2, unit="m",
                    note="statistical drag linearization underestimates a drag-excited "
                         "response (linearized force variance 8/pi vs 3 sigma^4); second "
                         f"record of a {2 * RECORD:.0f} s run at dt {DT} s",
                         kind="internal cross-check"))
    rows.append(Row(CASE, "top element: std of the tension, frequency vs time domain",
                    float(np.std(td.tension[second, top])), float(foss.tension_std[top]), 0.2,
                    unit="N", kind="internal cross-check"))
    series = np.interp(td.time[second] - RECORD, foss.time, foss.displacement[:, MID_NODE, 0])
    corr = float(np.corrcoef(series, u_td - u_td.mean())[0, 1])
    rows.append(Row(CASE, "mid-length node x: correlation of the frequency-domain series (FFT) "
                    "with the time-domain one", 1.0, corr, 0.15, relative=False,
                    note="the same DSA realization, phases and all", kind="internal cross-check"))

    if quick:
        return rows
    # an inertia-dominated variant (Cd 0.3): within the wave band the two agree closely;
    # outside it the time domain adds the broadband content of the quadratic drag (sum and
    # difference frequencies) and the ringing of lightly damped modes
    light = riser_system(Cd=0.3)
    static = solve_statics(light)
    fd = solve_stochastic(light, StochasticSettings(), static)
    td, second = _time_domain(light, static)
    n = int(round(RECORD / DT))
    X_td = np.fft.rfft(td.positions[second, MID_NODE, 0][:n])[1:len(fd.omega) + 1] * (2.0 / n)
    X_fd = 2.0 * fd.displacement_transfer[:, MID_NODE, 0] * fd.wave_amplitude
    band = fd.wave_spectrum >= 0.05 * fd.wave_spectrum.max()
    rms_td = float(np.sqrt(0.5 * np.sum(np.abs(X_td[band]) ** 2)))
    rms_fd = float(np.sqrt(0.5 * np.sum(np.abs(X_fd[band]) ** 2)))
    lo, hi = fd.omega[band][[0, -1]]
    peak = int(np.argmax(fd.wave_spectrum))
    rows.append(Row(CASE, "Cd 0.3: mid-length node x, rms within the wave band (S >= 5 % of "
                    "its peak), frequency vs time domain", rms_td, rms_fd, 0.03, unit="m",
                    note=f"{lo:.2f}-{hi:.2f} rad/s, from the FFT of the time-domain record; "
                         f"at the spectral peak: amplitude ratio "
                         f"{abs(X_fd[peak] / X_td[peak]):.3f}, phase difference "
                         f"{float(np.angle(X_fd[peak] / X_td[peak])):.3f} rad",
                         kind="internal cross-check"))
    return rows


__all__ = ["CASE", "riser_system", "run"]
