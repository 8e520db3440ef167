"""Wang, Er and Iu: forced response of the moored box (W2) and its parameter study (W3).

The box of W1 (:mod:`moorline.verification.wang_w1`: 11 elements per line, lines in the
vertical planes through the box centre and the keel corners, the static state at the draft
that is its own fixed point) under ``F_x = 1e5 sin(1.6 t)`` N at the box centre along its
26 m length, from rest at the static state (the force is zero at ``t = 0``). The paper's y is
vertical: its "displacement along y" is the heave z here and its "rotational angle in xOy"
the pitch ``ry`` (rotation vector component about y).

Model choices (the paper leaves them open)
------------------------------------------
* Rayleigh damping ``a0 M + a1 K`` (``K`` the tangent at the static state) with ratio 0.03
  at 1.6 rad/s, the forcing, and 2.0678 rad/s, the lowest natural frequency of the rigid box
  in surge and pitch on its quasi-static mooring stiffness (:func:`surge_pitch_frequency`:
  :func:`~moorline.solvers.stiffness.group_stiffness` of the fairleads plus hydrostatics,
  box mass and inertia; surge and pitch are strongly coupled, ``K_x,ry = 3.08e7`` N, so the
  surge stiffness with pitch free is 5.99e5 N/m, not ``K_xx = 2.20e6``). The ratio is then
  0.03 at both frequencies and below 0.03 between them: ``a0 = 0.05412`` 1/s,
  ``a1 = 0.01636`` s. W3 keeps these two frequencies for every geometry.
* The box has no added mass or radiation damping (the paper's body equations have none);
  the lines keep their Morison drag (``Cd = 1.2``) and added mass (``Ca = 1``) from
  :func:`~moorline.verification.wang_w1.wang_system`. Lines plus their added mass weigh
  31 % of the box.

W2: response (80 s, dt 0.05 s; steady state = the last 5 periods)
------------------------------------------------------------------
Steady after about 40 s. Surge amplitude 0.4189 m (half peak-to-peak), pitch 0.02308 rad
(1.32 deg), heave 0.00628 m at twice the forcing frequency about a mean set-down of
0.012 m, maximum element tension 473.8 kN (static 359.2 kN, at the fairleads), no sway,
roll or yaw. Refining dt to 0.025 s changes the surge by 0.07 %.

The forcing sits on the lines' first transverse modes: the linearized coupled model
(:func:`linearize`) has modes at 1.622, 1.661, 1.682 rad/s, and its frequency response to
1e5 N gives a surge of 0.877 m. The nonlinear model without line drag gives 0.553 m, with
drag 0.419 m: the drag (and the tension modulation) suppress the line resonance, and the
response is then close to the quasi-static estimate of the rigid box on its mooring
stiffness, 0.411 m (pitch 0.0221 rad). The rows check what can be checked independently:

* steady surge period (up-crossings) = 2 pi / 1.6 to 0.2 %;
* heave at twice the forcing frequency (linear heave vanishes by symmetry), to half an FFT
  bin of the window;
* zero mean surge (symmetric mooring, zero-mean force), to 1 % of the amplitude, and no
  out-of-plane motion (1e-6);
* surge amplitude vs the quasi-static surge-pitch estimate, 25 % (the estimate ignores the
  line inertia, 31 % of the box mass, the drag and the nonlinear stiffening);
* small amplitude (1 kN, no line drag, 120 s): surge and pitch amplitude and surge phase
  vs the linearized model solved in the frequency domain (2 %, 0.05 rad; measured 0.27 %,
  0.19 %, 0.014 rad): the time stepping, the body coupling and the Rayleigh damping in
  the linear limit; the linearized model's zero-frequency compliance vs the mooring
  stiffness (1e-6);
* time-step convergence: dt 0.05 s vs 0.025 s, 0.5 %.

W3: parameter study (:mod:`moorline.sweep`, ``cases/studies/wang_w3.yaml``)
-----------------------------------------------------------------------------
=========  =====  =========  =========  ==========  ===========  ===========
d/l        theta  surge [m]  heave [m]  pitch       max tension  static max
                                        [rad]       [kN]         [kN]
=========  =====  =========  =========  ==========  ===========  ===========
1/45       50     0.4403     0.01118    0.02514     380.7        276.3
1/50       50     0.4436     0.00953    0.02496     417.2        303.9
1/60       50     0.4189     0.00628    0.02308     473.8        359.2
1/70       50     0.3734     0.00378    0.02103     517.6        414.5
1/80       50     0.3288     0.00214    0.01977     561.8        469.8
1/60       40     0.1208     0.00273    0.00860     550.4        499.3
1/60       44     0.1851     0.00348    0.01190     501.7        437.2
1/60       48     0.3074     0.00490    0.01788     473.7        383.5
1/60       52     0.6065     0.00902    0.03150     494.2        336.2
1/60       54     0.9408     0.01569    0.04578     554.6        314.4
=========  =====  =========  =========  ==========  ===========  ===========

Against the paper's Figs. 7 and 8:

* sag-to-span (Fig. 7a-c): reproduced. All three amplitudes fall as the line gets tauter
  (heave and pitch strictly; surge is flat between 1/45 and 1/50, +0.7 %, then falls by
  26 %). The rows take Spearman's rank correlation with the tautness, -1 within 0.15 (one
  adjacent pair may swap).
* maximum tension vs sag-to-span (Fig. 7d): NOT reproduced. The paper's is lowest near
  1/60; here it rises monotonically with tautness because it is dominated by the static
  pretension (which grows as ``1 / (d/l)``); its dynamic part (max - static) is largest
  near 1/60 (115 kN). The row checks that the max tension ranks follow the paper's own
  parabolic pretension ``w cos(theta) l / (8 d/l)``.
* inclination (Fig. 8a-c): NOT reproduced. The paper's amplitudes fall as the lines
  steepen from 40 to 54 deg; here they rise (surge 0.12 -> 0.94 m): steeper lines are
  softer horizontally and the surge-pitch frequency falls from 2.84 to 1.80 rad/s towards
  the forcing. (An angle measured from the vertical, i.e. flatter lines as it grows, would
  give the paper's trend, but then W1's draft would be 0.981 m instead of the paper's
  0.896 m, which 50 deg from the horizontal reproduces.) The rows check that the amplitudes
  follow the quasi-static surge-pitch estimate (Spearman 1 within 0.15), as does the surge
  over all ten cases (0.95).
* maximum tension vs inclination (Fig. 8d): reproduced, lowest at 48-50 deg (473.7 and
  473.8 kN, a tie); the row accepts one grid step.

No input was tuned to the paper. The amplitudes over the last 5 periods of 80 s agree with
those of 140 s runs to 0.01 %.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
import scipy.linalg as sla
from numpy.typing import NDArray

from ..mesh import discretize
from ..model import DynamicsSettings, Motion, System
from ..physics.rigid_body import rotation_matrix, skew
from ..results import DynamicResult, StaticResult
from ..solvers.assembly import BlockPattern
from ..solvers.bodies import body_loads, body_mass_matrix, transformation
from ..solvers.dynamic_model import DynamicModel
from ..solvers.dynamics import simulate
from ..solvers.stiffness import group_stiffness
from ..sweep import run_study, steady_window
from .core import Row
from .signals import harmonic_fit
from .wang_w1 import (
    DEPTH,
    INCLINATION_DEG,
    SAG_TO_SPAN,
    SEGMENTS,
    WEIGHT,
    Equilibrium,
    Layout,
    parabolic_top_force,
    wang_equilibrium,
)

FloatArray = NDArray[np.float64]

CASE_W2, CASE_W3 = "wang-w2", "wang-w3"
FORCE_AMPLITUDE = 1.0e5  # N, F_x = A sin(w t)
OMEGA = 1.6  # rad/s
PERIOD = 2.0 * math.pi / OMEGA
RAYLEIGH_RATIO = 0.03
BODY = "box"
FAIRLEADS = ("A", "B", "C", "D")


# ----------------------------------------------------------------------------- model
def forced_equilibrium(sag_to_span: float = SAG_TO_SPAN, inclination_deg: float = INCLINATION_DEG,
                       segments: int = SEGMENTS, layout: Layout = "diagonal",
                       amplitude: float = FORCE_AMPLITUDE, omega: float = OMEGA,
                       line_drag: bool = True) -> Equilibrium:
    """The W1 static state with the paper's force ``F_x = amplitude sin(omega t)`` on the box.

    Parameters
    ----------
    sag_to_span, inclination_deg, segments, layout
        As :func:`~moorline.verification.wang_w1.wang_equilibrium`.
    amplitude, omega
        Force amplitude [N] and circular frequency [rad/s], at the body origin along x.
    line_drag
        Keep the lines' Morison drag (``Cd = 1.2``, ``Ct = 0.008``); ``False`` zeroes it
        (the small-amplitude comparison with the linearized model).

    Returns
    -------
    Equilibrium
        Its ``system`` carries the force history; ``result`` is the static state (the force
        is zero at ``t = 0``, so the static state is that of W1).
    """
    eq = wang_equilibrium(sag_to_span, inclination_deg, segments, layout)
    system = eq.system
    body = replace(system.bodies[BODY], force_history=Motion(
        "harmonic", amplitude=(amplitude, 0.0, 0.0), period=2.0 * math.pi / omega))
    types = system.line_types
    if not line_drag:
        types = {k: replace(v, Cd=0.0, Ct=0.0) for k, v in types.items()}
    system = replace(system, bodies={**system.bodies, BODY: body}, line_types=types)
    # the dynamics take the mesh (with its drag coefficients) from the static result
    return replace(eq, system=system, result=replace(eq.result, mesh=discretize(system)))


@dataclass(frozen=True)
class LinearModel:
    """The coupled lines and body linearized about a static state.

    Unknowns: the free node dofs, then the six dofs of the body (``body``: their slice).

    Attributes
    ----------
    M
        Mass: lumped line mass, the lines' added mass and the rigid body's 6x6 mass.
    K
        Tangent stiffness: line elements and seabed, the master-slave transformation with the
        moment-arm term of the fairlead forces, gravity and hydrostatics of the body.
    K_rayleigh
        The stiffness the dynamics' Rayleigh damping uses (``K`` without the moment-arm
        term; :meth:`~moorline.solvers.newmark.Stepper._setup_rayleigh`).
    body
        Slice of the body dofs.
    """

    M: FloatArray
    K: FloatArray
    K_rayleigh: FloatArray
    body: slice

    def response(self, omega: float, force: FloatArray, rayleigh: tuple[float, float]
                 ) -> FloatArray:
        """Complex amplitudes of all dofs under the body load ``force`` (6,) ``e^{i w t}``,
        with damping ``a0 M + a1 K_rayleigh``."""
        a0, a1 = rayleigh
        C = a0 * self.M + a1 * self.K_rayleigh
        rhs = np.zeros(len(self.M), dtype=complex)
        rhs[self.body] = force
        return np.linalg.solve(self.K - omega**2 * self.M + 1j * omega * C, rhs)

    def frequencies(self) -> FloatArray:
        """Undamped natural circular frequencies, ascending [rad/s]."""
        return np.sqrt(np.abs(sla.eigh(self.K, self.M, eigvals_only=True)))


def linearize(system: System, static: StaticResult) -> LinearModel:
    """Mass and stiffness of the coupled system about its static state (one body, free).

    Built from the same element tangents as the time integration
    (:meth:`~moorline.solvers.dynamic_model.DynamicModel.evaluate`) but solved in the
    frequency domain, so it checks the nonlinear time stepping, the coupling and the Rayleigh
    damping in the small-amplitude limit.
    """
    from ..waves import fluid_field_from_environment

    mesh = static.mesh
    model = DynamicModel(mesh, fluid_field_from_environment(system.environment),
                         seabed_model=system.environment.seabed)
    x = static.positions.copy()
    zero = np.zeros_like(x)
    ev = model.evaluate(x, zero, zero, 0.0, model.initial_material(x), 1.0, True, None)
    n_free = mesh.n_dofs
    ext = mesh.dof_of_node.copy()
    for k, node in enumerate(mesh.slave_node):
        ext[node] = n_free + 3 * k + np.arange(3)
    pattern = BlockPattern(mesh.elements, ext)
    pose = static.body_pose
    R = rotation_matrix(pose[:, 3:])
    arms = np.einsum("kij,kj->ki", R[mesh.slave_body], mesh.slave_arm)
    body_dof = np.array([n_free])
    P = transformation(mesh, n_free + 3 * len(mesh.slave_node), n_free, body_dof, arms)
    node_m = model.node_mass[:, None, None] * np.eye(3)
    if ev.node_M is not None:
        node_m = node_m + ev.node_M
    Ma = ev.Ma if ev.Ma is not None else np.zeros_like(ev.K)
    M = (P.T @ pattern.assemble(Ma, node_m) @ P).toarray()
    K = (P.T @ pattern.assemble(ev.K, ev.node_K) @ P).toarray()
    body = system.bodies[mesh.body_names[0]]
    d = slice(n_free, n_free + 6)
    M[d, d] += body_mass_matrix(body, R[0])
    if body.added_mass is not None:
        M[d, d] += np.asarray(body.added_mass, float)
    K[d, d] += body_loads(body, pose[0, :3], R[0], mesh.gravity, mesh.water_density)[1]
    K_rayleigh = K.copy()
    for f, arm in zip(ev.nodal[mesh.slave_node], arms, strict=True):
        K[n_free + 3:n_free + 6, n_free + 3:n_free + 6] -= skew(f) @ skew(arm)
    return LinearModel(M, K, K_rayleigh, d)


def body_stiffness(eq: Equilibrium) -> FloatArray:
    """6x6 restoring stiffness of the moored box about its origin: the mooring
    (:func:`~moorline.solvers.stiffness.group_stiffness` of the four fairleads) plus gravity
    and hydrostatics."""
    result = eq.result
    body = eq.system.bodies[BODY]
    pose = result.body_pose[0]
    K = group_stiffness(result, list(FAIRLEADS), pose[:3])
    return K + body_loads(body, pose[:3], rotation_matrix(pose[3:]), result.mesh.gravity,
                          result.mesh.water_density)[1]


def surge_pitch_frequency(eq: Equilibrium) -> float:
    """Lowest natural frequency [rad/s] of the rigid box in surge and pitch on its
    quasi-static mooring stiffness (:func:`body_stiffness`), line inertia ignored."""
    K = body_stiffness(eq)
    M = body_mass_matrix(eq.system.bodies[BODY], rotation_matrix(eq.result.body_pose[0, 3:]))
    idx = np.ix_([0, 4], [0, 4])
    return float(np.sqrt(sla.eigh(K[idx], M[idx], eigvals_only=True)[0]))


def rayleigh_coefficients(ratio: float, frequencies: tuple[float, float]) -> tuple[float, float]:
    """``(a0, a1)`` of ``a0 M + a1 K`` with damping ``ratio`` at both circular frequencies."""
    w1, w2 = frequencies
    return 2.0 * ratio * w1 * w2 / (w1 + w2), 2.0 * ratio / (w1 + w2)


# ----------------------------------------------------------------------------- signals
def crossing_period(time: FloatArray, signal: FloatArray) -> float:
    """Mean period between up-crossings of the mean (linear interpolation of the crossing
    times): (last crossing - first crossing) / (number of crossings - 1)."""
    t = np.asarray(time, float)
    y = np.asarray(signal, float) - np.mean(signal)
    k = np.flatnonzero((y[:-1] < 0.0) & (y[1:] >= 0.0))
    if len(k) < 2:
        return math.nan
    crossings = t[k] - y[k] * (t[k + 1] - t[k]) / (y[k + 1] - y[k])
    return float((crossings[-1] - crossings[0]) / (len(crossings) - 1))


def dominant_period(time: FloatArray, signal: FloatArray) -> tuple[float, float]:
    """Period of the largest spectral peak of a uniformly sampled signal (mean removed), and
    half the bin width expressed as a period, ``T^2 df / 2`` (the resolution)."""
    t = np.asarray(time, float)
    y = np.asarray(signal, float) - np.mean(signal)
    n = len(y)
    df = 1.0 / (n * float(np.mean(np.diff(t))))
    k = int(np.argmax(np.abs(np.fft.rfft(y))[1:])) + 1
    T = 1.0 / (k * df)
    return T, 0.5 * T * T * df


def spearman(a: FloatArray, b: FloatArray) -> float:
    """Spearman rank correlation of two samples without ties."""
    ra = np.argsort(np.argsort(np.asarray(a, float)))
    rb = np.argsort(np.argsort(np.asarray(b, float)))
    return float(np.corrcoef(ra, rb)[0, 1])


# ----------------------------------------------------------------------------- W2
@dataclass(frozen=True)
class ForcedRun:
    """A forced-response run of the box and its steady-state summary.

    Attributes
    ----------
    eq
        Forced system and static state.
    result
        The time histories.
    rayleigh_frequencies
        The two frequencies of the Rayleigh damping [rad/s].
    amplitudes
        Half the peak-to-peak over the steady window: surge ``x``, heave ``z``, pitch ``ry``
        (rotation in the paper's vertical x-y plane) [m, m, rad], and the largest of sway,
        roll and yaw (out-of-plane) [m or rad].
    max_tension
        Largest element tension in the steady window [N].
    """

    eq: Equilibrium
    result: DynamicResult
    rayleigh_frequencies: tuple[float, float]
    amplitudes: dict[str, float]
    max_tension: float


def forced_run(sag_to_span: float = SAG_TO_SPAN, inclination_deg: float = INCLINATION_DEG, *,
               duration: float = 80.0, dt: float = 0.05, n_periods: int = 5,
               amplitude: float = FORCE_AMPLITUDE, line_drag: bool = True,
               rayleigh_frequencies: tuple[float, float] | None = None) -> ForcedRun:
    """Static state, then the forced response from rest.

    ``rayleigh_frequencies=None``: the forcing frequency and :func:`surge_pitch_frequency`
    of this geometry.
    """
    eq = forced_equilibrium(sag_to_span, inclination_deg, amplitude=amplitude,
                            line_drag=line_drag)
    if rayleigh_frequencies is None:
        rayleigh_frequencies = (OMEGA, surge_pitch_frequency(eq))
    settings = DynamicsSettings(duration=duration, dt=dt, rayleigh_ratio=RAYLEIGH_RATIO,
                                rayleigh_frequencies=rayleigh_frequencies)
    result = simulate(eq.system, settings, initial=eq.result, output_every=dt)
    window = steady_window(result.time, PERIOD, n_periods)
    pose = result.body_history(BODY)[window]
    half = 0.5 * np.ptp(pose, axis=0)
    amplitudes = {"x": float(half[0]), "z": float(half[2]), "ry": float(half[4]),
                  "out_of_plane": float(max(half[1], half[3], half[5]))}
    return ForcedRun(eq, result, rayleigh_frequencies, amplitudes,
                     float(result.tension[window].max()))


def quasi_static_response(eq: Equilibrium, rayleigh: tuple[float, float],
                          amplitude: float = FORCE_AMPLITUDE, omega: float = OMEGA
                          ) -> FloatArray:
    """Complex 6-dof amplitudes of the rigid box on its quasi-static mooring stiffness.

    ``(K - w^2 M + i w (a0 M + a1 K)) X = (amplitude, 0, ...)`` with ``K`` of
    :func:`body_stiffness` and ``M`` the rigid box: the lines act as springs without inertia
    or drag.
    """
    K = body_stiffness(eq)
    M = body_mass_matrix(eq.system.bodies[BODY], rotation_matrix(eq.result.body_pose[0, 3:]))
    force = np.zeros(6)
    force[0] = amplitude
    C = rayleigh[0] * M + rayleigh[1] * K
    return np.linalg.solve(K - omega**2 * M + 1j * omega * C, force)


def line_mass_share(eq: Equilibrium) -> float:
    """Mass plus normal added mass of all lines over the box mass."""
    system = eq.system
    total = 0.0
    for line in system.lines.values():
        lt = system.line_types[line.line_type]
        added = lt.Ca * system.environment.water_density * math.pi * lt.diameter**2 / 4.0
        total += (lt.mass_per_length + added) * line.length
    return total / system.bodies[BODY].mass


def run_w2(quick: bool = False) -> list[Row]:
    """Case W2: the response of the box to ``F_x = 1e5 sin(1.6 t)`` N (module docstring).

    Parameters
    ----------
    quick
        Shorter runs (60 s at dt 0.1 s; the small amplitude 100 s at dt 0.05 s) and no
        time-step refinement, for the fast tests.
    """
    duration, dt, small_duration = (60.0, 0.1, 100.0) if quick else (80.0, 0.05, 120.0)
    run = forced_run(duration=duration, dt=dt)
    rayleigh = rayleigh_coefficients(RAYLEIGH_RATIO, run.rayleigh_frequencies)
    result, amp = run.result, run.amplitudes
    window = steady_window(result.time, PERIOD, 5)
    t, pose = result.time[window], result.body_history(BODY)[window]
    surge_mean = harmonic_fit(t, pose[:, 0], OMEGA).mean
    heave_period, heave_resolution = dominant_period(t, pose[:, 2])
    qs = quasi_static_response(run.eq, rayleigh)
    static_tension = float(run.eq.result.tension.max())
    rows = [
        Row(CASE_W2, "steady surge period (up-crossings) vs forcing period 2 pi / 1.6",
            PERIOD, crossing_period(t, pose[:, 0]), 2e-3, unit="s",
            note=f"last 5 periods of {duration:g} s, dt {dt:g} s", kind="internal cross-check"),
        Row(CASE_W2, "steady heave period: second order, half the forcing period", PERIOD / 2,
            heave_period, heave_resolution / (PERIOD / 2), unit="s",
            note="linear heave vanishes by the x -> -x symmetry; tolerance: half an FFT bin "
            f"of the window; heave amplitude {amp['z']:.4g} m, mean set-down "
            f"{float(np.mean(pose[:, 2]) - run.eq.result.body_pose[0, 2]):.3g} m",
            kind="internal cross-check"),
        Row(CASE_W2, "mean surge in the steady state (symmetric mooring, zero-mean force)",
            0.0, surge_mean, 0.01 * amp["x"], relative=False, unit="m",
            note="tolerance 1 % of the surge amplitude", kind="internal cross-check"),
        Row(CASE_W2, "out-of-plane motion (sway, roll, yaw) under in-plane forcing", 0.0,
            amp["out_of_plane"], 1e-6, relative=False,
            note="largest half peak-to-peak of y [m], rx, rz [rad]", kind="internal cross-check"),
        Row(CASE_W2, "steady surge amplitude vs quasi-static surge-pitch estimate",
            float(abs(qs[0])), amp["x"], 0.25, unit="m",
            note=f"rigid box on group_stiffness + hydrostatics, Rayleigh damping, no line "
            f"inertia or drag (line mass + added mass = {line_mass_share(run.eq):.0%} of the "
            f"box); pitch "
            f"{amp['ry']:.4g} rad vs {abs(qs[4]):.4g}; max tension {run.max_tension:.4g} N "
            f"(static {static_tension:.4g} N)", kind="internal cross-check"),
    ]
    # near the line modes the phase is sensitive to Newmark's period error: dt 0.05 s
    rows += _small_amplitude_rows(small_duration, 0.05)
    if not quick:
        fine = forced_run(duration=duration, dt=dt / 2)
        rows.append(Row(CASE_W2, f"surge amplitude, dt {dt:g} s vs {dt / 2:g} s",
                        fine.amplitudes["x"], amp["x"], 5e-3, unit="m",
                        note=f"pitch {amp['ry']:.5g} vs {fine.amplitudes['ry']:.5g} rad, max "
                        f"tension {run.max_tension:.6g} vs {fine.max_tension:.6g} N",
                        kind="internal cross-check"))
    return rows


def _small_amplitude_rows(duration: float, dt: float) -> list[Row]:
    """1 kN without line drag against the linearized model in the frequency domain."""
    amplitude = 1.0e3
    run = forced_run(duration=duration, dt=dt, amplitude=amplitude, line_drag=False)
    linear = linearize(run.eq.system, run.eq.result)
    rayleigh = rayleigh_coefficients(RAYLEIGH_RATIO, run.rayleigh_frequencies)
    force = np.array([amplitude, 0.0, 0.0, 0.0, 0.0, 0.0])
    X = linear.response(OMEGA, force, rayleigh)[linear.body]
    window = steady_window(run.result.time, PERIOD, 5)
    t, pose = run.result.time[window], run.result.body_history(BODY)[window]
    surge = harmonic_fit(t, pose[:, 0], OMEGA)
    ax, phx = surge.amplitude(), surge.phase()
    ary = harmonic_fit(t, pose[:, 4], OMEGA).amplitude()
    static = np.linalg.solve(body_stiffness(run.eq), force)[0]
    zero = float(abs(linear.response(0.0, force, (0.0, 0.0))[linear.body][0]))
    freqs = linear.frequencies()
    near = freqs[np.argsort(np.abs(freqs - OMEGA))[:3]]
    note = (f"1 kN, no line drag, {duration:g} s; linearized frequencies nearest 1.6 rad/s: "
            f"{', '.join(f'{w:.3f}' for w in sorted(near))}")
    return [
        Row(CASE_W2, "small amplitude: surge amplitude vs linearized model", float(abs(X[0])),
            ax, 0.02, unit="m", note=note, kind="internal cross-check"),
        Row(CASE_W2, "small amplitude: pitch amplitude vs linearized model", float(abs(X[4])),
            ary, 0.02, unit="rad", kind="internal cross-check"),
        Row(CASE_W2, "small amplitude: surge phase vs linearized model",
            float(np.angle(X[0])), phx, 0.05, relative=False, unit="rad",
            note="phase of x against sin(1.6 t)", kind="internal cross-check"),
        Row(CASE_W2, "linearized model at zero frequency vs mooring stiffness (surge)",
            float(static), zero, 1e-6, unit="m",
            note="static compliance of the assembled model vs group_stiffness + hydrostatics",
            kind="internal cross-check"),
    ]


# ----------------------------------------------------------------------------- W3
W3_SAG_TO_SPAN = ("1/45", "1/50", "1/60", "1/70", "1/80")
W3_INCLINATION = (40, 44, 48, 50, 52, 54)
#: Rayleigh frequencies of every W3 case: the forcing and the base case's
#: :func:`surge_pitch_frequency` (2.0678 rad/s)
W3_RAYLEIGH = (1.6, 2.0678)


def w3_study(quick: bool = False) -> dict:
    """The W3 study as a :mod:`moorline.sweep` mapping (``cases/studies/wang_w3.yaml``).

    ``quick``: three values per series (1/45, 1/60, 1/80; 44, 50, 54 deg) and 40 s at
    dt 0.1 s (the amplitudes are then within ~3 % of their steady values).
    """
    sag = W3_SAG_TO_SPAN[::2] if quick else W3_SAG_TO_SPAN
    inclination = (44, 50, 54) if quick else W3_INCLINATION
    duration, dt = (40.0, 0.1) if quick else (80.0, 0.05)
    return {
        "name": CASE_W3,
        "description": "Wang, Er and Iu W3, steady-state response vs sag-to-span and "
                       "inclination",
        "base": {"builder": "moorline.verification.wang_dynamics:forced_equilibrium",
                 "parameters": {"sag_to_span": "1/60", "inclination_deg": 50}},
        "variations": {"sag_to_span": list(sag), "inclination_deg": list(inclination)},
        "combine": "one-at-a-time",
        "dynamics": {"duration": duration, "dt": dt, "rayleigh_ratio": RAYLEIGH_RATIO,
                     "rayleigh_frequencies": list(W3_RAYLEIGH), "output_every": dt},
        "outputs": {"window": {"omega": OMEGA, "periods": 5},
                    "quantities": {"surge": "amplitude box.x", "heave": "amplitude box.z",
                                   "pitch": "amplitude box.ry",
                                   "max_tension": "max tension",
                                   "static_tension": "static tension"}},
    }


def run_w3(quick: bool = False) -> list[Row]:
    """Case W3: the trends of the paper's Figs. 7 and 8 (module docstring)."""
    table = run_study(w3_study(quick))
    series = np.asarray(table["series"].values).astype(str)
    ratio = np.asarray(table["sag_to_span"].values, float)
    angle = np.asarray(table["inclination_deg"].values, float)
    value = {k: np.asarray(table[k].values, float) for k in
             ("surge", "heave", "pitch", "max_tension", "static_tension")}
    rayleigh = rayleigh_coefficients(RAYLEIGH_RATIO, W3_RAYLEIGH)
    estimate = np.empty((len(ratio), 2))
    pretension = np.empty(len(ratio))
    for k, (r, a) in enumerate(zip(ratio, angle, strict=True)):
        eq = forced_equilibrium(float(r), float(a))
        X = quasi_static_response(eq, rayleigh)
        estimate[k] = abs(X[0]), abs(X[4])
        chord = (DEPTH - eq.draft) / math.sin(math.radians(a))
        pretension[k] = parabolic_top_force(chord, float(a), float(r), WEIGHT)[0]
    s, i = series == "sag_to_span", series == "inclination_deg"
    s = np.flatnonzero(s)[np.argsort(-ratio[s])]  # 1/45 first: tauter along the series
    i = np.flatnonzero(i)[np.argsort(angle[i])]
    taut = np.arange(len(s), dtype=float)

    def listing(idx: NDArray[np.int64], key: str, fmt: str = ".4g") -> str:
        return ", ".join(f"{value[key][k]:{fmt}}" for k in idx)

    sags = ", ".join(f"1/{1 / ratio[k]:.0f}" for k in s)
    angles = ", ".join(f"{angle[k]:g}" for k in i)
    rows = []
    for key, fig, unit in (("surge", "7a", "m"), ("heave", "7b", "m"), ("pitch", "7c", "rad")):
        rows.append(Row(CASE_W3, f"Fig. {fig} {key} amplitude falls as the line gets tauter, "
                        f"{sags} (Spearman)", -1.0, spearman(value[key][s], taut), 0.15,
                        relative=False, note=f"{listing(s, key)} {unit}; tolerance: one "
                        "adjacent pair may swap", kind="internal cross-check"))
    t_max, t_static = value["max_tension"], value["static_tension"]
    lowest = 1.0 / ratio[s][np.argmin(t_max[s])]
    rows.append(Row(
        CASE_W3, f"Fig. 7d max tension vs d/l: paper lowest near 1/60, here lowest at "
        f"1/{lowest:.0f}; check: it follows the parabolic pretension (Spearman)", 1.0,
        spearman(t_max[s], pretension[s]), 0.15, relative=False,
        note=f"max tension {listing(s, 'max_tension')} N at {sags}; pretension "
        f"w cos(theta) l / (8 d/l) {', '.join(f'{pretension[k]:.3g}' for k in s)} N; "
        f"dynamic part max - static {', '.join(f'{t_max[k] - t_static[k]:.3g}' for k in s)} N",
        kind="internal cross-check"))
    trend = spearman(value["surge"][i], angle[i])
    frequencies = ", ".join(f"{surge_pitch_frequency(forced_equilibrium(ratio[k], angle[k])):.3g}"
                            for k in i)
    for key, col, fig in (("surge", 0, "8a"), ("pitch", 1, "8c")):
        rows.append(Row(
            CASE_W3, f"Fig. {fig} {key} vs inclination: paper falls, here rises (Spearman "
            f"{spearman(value[key][i], angle[i]):+.2f}); check: it follows the quasi-static "
            "surge-pitch estimate (Spearman)", 1.0, spearman(value[key][i], estimate[i, col]),
            0.15, relative=False,
            note=f"{listing(i, key)} at {angles} deg vs estimate "
            f"{', '.join(f'{estimate[k, col]:.4g}' for k in i)}; surge-pitch frequency "
            f"{frequencies} rad/s: steeper lines are softer horizontally, the frequency "
            "approaches the forcing 1.6 rad/s", kind="internal cross-check"))
    rows.append(Row(
        CASE_W3, f"Fig. 8b heave vs inclination: paper falls, here rises (Spearman "
        f"{spearman(value['heave'][i], angle[i]):+.2f}); check: this second-order response "
        "follows the quasi-static surge estimate (Spearman)", 1.0,
        spearman(value["heave"][i], estimate[i, 0]), 0.15, relative=False,
        note=f"{listing(i, 'heave')} m at {angles} deg; surge trend {trend:+.2f}",
        kind="internal cross-check"))
    grid = np.sort(angle[i])
    centre = int(np.argmin(np.abs(grid - INCLINATION_DEG)))
    step = float(np.min(np.abs(np.delete(grid, centre) - grid[centre])))
    rows.append(Row(
        CASE_W3, "Fig. 8d inclination of the least max tension (paper: near 50 deg)",
        INCLINATION_DEG, float(angle[i][np.argmin(t_max[i])]), step, relative=False,
        unit="deg", note=f"max tension {listing(i, 'max_tension')} N at {angles} deg; "
        "tolerance: one grid step", kind="internal cross-check"))
    everything = np.unique(np.column_stack((ratio, angle)), axis=0, return_index=True)[1]
    rows.append(Row(
        CASE_W3, "surge amplitude across all cases follows the quasi-static surge-pitch "
        "estimate (Spearman)", 1.0, spearman(value["surge"][everything],
                                             estimate[everything, 0]), 0.15, relative=False,
        note="rigid box on the mooring stiffness at 1.6 rad/s, Rayleigh damping",
        kind="internal cross-check"))
    return rows
