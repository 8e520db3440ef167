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
The paper's Fig. 6 (the time histories) is lost, so W2 has no published number. Steady after
about 40 s: surge amplitude 0.4189 m (half peak-to-peak), pitch 0.02308 rad (1.32 deg),
heave 0.00628 m at twice the forcing frequency about a mean set-down of 0.012 m, maximum
element tension 473.8 kN (static 359.2 kN, at the fairleads), no sway, roll or yaw.

The forcing sits on the lines' first transverse modes (the linearized coupled model
:func:`linearize` has modes at 1.622, 1.661, 1.682 rad/s): the linear response to 1e5 N
without drag is a surge of 0.877 m (11 elements; 0.857 m with continuous lines), the
nonlinear model without line drag gives 0.553 m, with drag 0.419 m: the drag suppresses the
line resonance.

Reference (kind ``exact``): :func:`continuum_box`, a linear frequency-domain model of the box
written independently of moorline's elements and assembly: W1's exact-catenary static state,
each line's dynamic end stiffness from the continuous linearized cable
(:mod:`~moorline.verification.linear_cable`: mass, normal added mass, Rayleigh damping),
rigid-body mass, :func:`box_hydrostatics` from the box dimensions, the moment arms of the
fairlead forces. The rows:

* small amplitude (1 kN, no line drag, 120 s from rest; quick: 100 s): surge and pitch
  amplitude and surge phase of the nonlinear time-domain run (11 elements, the paper's mesh)
  against the continuum; tolerance: the 11-element discretization error measured on
  moorline's linearized FE model (+2.4 % in surge) plus 1 % (0.03 rad) for the time stepping;
* moorline's linearized FE model (frequency domain) at 11, 22, 44 elements converges to the
  continuum at second order (observed order 22 -> 44, and the 44-element value to 0.5 %);
* static surge, heave and pitch stiffness (group_stiffness + moorline's box hydrostatics vs
  exact catenary + closed-form hydrostatics), 0.5 % (11 elements' chord slack: -0.37 % in
  tension, W1);
* out-of-plane motion / surge = 0 (the system is mirror-symmetric about y = 0): a wrong
  transformation or moment arm at one corner would drive roll and yaw;
* internal cross-checks: the time domain against the linearized FE model on the same mesh
  (time stepping in the linear limit, 1 %), and (full form) the full-amplitude surge at dt
  0.1 s vs 0.05 s.

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

Every row compares with the trend the paper states in its text (kind ``published``; the
figures are lost):

* sag-to-span (Fig. 7a-c): reproduced. All three amplitudes fall as the line gets tauter
  (heave and pitch strictly; surge is flat between 1/45 and 1/50, +0.7 %, then falls by
  26 %). Spearman's rank correlation with the tautness, -1 within 0.15 (one adjacent pair
  may swap: the paper gives the trend in words).
* maximum tension vs sag-to-span (Fig. 7d): NOT reproduced. The paper's is lowest near
  1/60; here it rises monotonically with tautness because it is dominated by the static
  pretension (which grows as ``1 / (d/l)``); its dynamic part (max - static) is largest
  near 1/60 (115 kN).
* inclination (Fig. 8a-c): NOT reproduced. The paper's amplitudes fall as the lines
  steepen from 40 to 54 deg; here they rise (surge 0.12 -> 0.94 m): steeper lines are
  softer horizontally and the surge-pitch frequency falls from 2.84 to 1.80 rad/s towards
  the forcing; the independent continuous-line linear model rises as well. (An angle
  measured from the vertical, i.e. flatter lines as it grows, would give the paper's trend,
  but then W1's draft would be 0.981 m instead of the paper's 0.896 m, which 50 deg from the
  horizontal reproduces.)
* maximum tension vs inclination (Fig. 8d): reproduced, lowest at 48-50 deg (473.7 and
  473.8 kN, a tie); the row takes the vertex of the parabola through the least value and its
  neighbours (49.0 deg) against 50 deg within the study's grid step there (2 deg).

A row is ``not reproduced`` only when moorline gives the documented opposite trend; any other
outcome is compared with the paper and can fail. No input was tuned to the paper. The
amplitudes over the last 5 periods of 80 s agree with those of 140 s runs to 0.01 %.
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
from .linear_cable import Cable, end_stiffness, transfer
from .signals import harmonic_fit
from .wang_w1 import (
    AREA,
    BOX_HEIGHT,
    BOX_LENGTH,
    BOX_MASS,
    BOX_WIDTH,
    CABLE_DENSITY,
    CORNER_SIGNS,
    EA,
    INCLINATION_DEG,
    RHO,
    SAG_TO_SPAN,
    SEGMENTS,
    WEIGHT,
    Equilibrium,
    G,
    Layout,
    catenary_draft,
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


def spearman(a: FloatArray, b: FloatArray) -> float:
    """Spearman rank correlation of two samples without ties."""
    ra = np.argsort(np.argsort(np.asarray(a, float)))
    rb = np.argsort(np.argsort(np.asarray(b, float)))
    return float(np.corrcoef(ra, rb)[0, 1])


# ----------------------------------------------------------------------------- continuum
def box_hydrostatics(draft: float) -> FloatArray:
    """6x6 hydrostatic restoring stiffness of the level box about its centre, from its
    dimensions: heave ``rho g w_a w_c``, roll and pitch ``rho g (I_wp + V z_B)`` with the
    waterplane's second moments ``w_a w_c^3 / 12`` and ``w_c w_a^3 / 12``, the displaced
    volume ``V = w_a w_c h_s`` and its centre ``z_B = h_s / 2 - w_b / 2`` below the centre
    (the centre of gravity is the centre: no ``m g z_G`` term)."""
    a, c = BOX_LENGTH, BOX_WIDTH
    volume, z_b = a * c * draft, 0.5 * draft - 0.5 * BOX_HEIGHT
    K = np.zeros((6, 6))
    K[2, 2] = RHO * G * a * c
    K[3, 3] = RHO * G * (a * c**3 / 12.0 + volume * z_b)
    K[4, 4] = RHO * G * (c * a**3 / 12.0 + volume * z_b)
    return K


def continuum_box(omega: float, rayleigh: tuple[float, float] = (0.0, 0.0),
                  sag_to_span: float = SAG_TO_SPAN, inclination_deg: float = INCLINATION_DEG,
                  steps: int = 200) -> FloatArray:
    """Dynamic stiffness (6x6, complex) of the moored box with continuous lines.

    Independent of moorline's elements and assembly: the static state is W1's exact elastic
    catenary (:func:`~moorline.verification.wang_w1.catenary_draft`: the draft and each
    line's end forces); each line's dynamic end stiffness comes from
    :mod:`~moorline.verification.linear_cable` (continuous line: mass, normal added mass
    ``Ca = 1``, no drag, Rayleigh damping); the box has its rigid-body mass (uniform solid
    box, no added mass: the paper's body equations have none), :func:`box_hydrostatics`, and
    the moment-arm stiffness ``-[f]x [r]x`` of the static fairlead forces ``f``. Rayleigh
    damping ``a0 M + a1 K`` acts on the line and body masses, the lines' stiffness and the
    hydrostatics, not on the moment-arm term (as moorline's Rayleigh stiffness).

    Returns ``Z`` with ``Z X = F`` for complex amplitudes ``X`` (surge, sway, heave, roll,
    pitch, yaw) about the box centre and a load ``F`` there.
    """
    draft, line = catenary_draft(sag_to_span, inclination_deg)
    a0, a1 = rayleigh
    Z = np.zeros((6, 6), dtype=complex)
    for sx, sy in CORNER_SIGNS:
        corner = np.array([0.5 * BOX_LENGTH * sx, 0.5 * BOX_WIDTH * sy])
        out = np.append(corner / np.linalg.norm(corner), 0.0)  # anchor side, horizontal
        arm = np.array([corner[0], corner[1], -0.5 * BOX_HEIGHT])
        up = np.array([0.0, 0.0, 1.0])
        cable = Cable(line.length, EA, tuple(-line.H_a * out + line.V_a * up), WEIGHT,
                      CABLE_DENSITY * AREA, 1.0 * RHO * AREA)
        K = end_stiffness(transfer(cable, [omega], a0=a0, a1=a1, steps=steps)[1][-1])[0]
        P = np.hstack([np.eye(3), -skew(arm)])
        Z += P.T @ K @ P
        fairlead_force = line.H * out - line.V_b * up  # on the box
        Z[3:, 3:] -= skew(fairlead_force) @ skew(arm)
    m, a, b, c = BOX_MASS, BOX_LENGTH, BOX_HEIGHT, BOX_WIDTH
    M = np.diag([m, m, m, m * (c**2 + b**2) / 12.0, m * (a**2 + b**2) / 12.0,
                 m * (a**2 + c**2) / 12.0])
    Z += (1.0 + 1j * omega * a1) * box_hydrostatics(draft)
    return Z - (omega**2 - 1j * omega * a0) * M


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


def _linear_fe(segments: int, rayleigh: tuple[float, float], force: FloatArray
               ) -> FloatArray:
    """Body amplitudes of moorline's linearized finite element model (no line drag)."""
    eq = forced_equilibrium(segments=segments, amplitude=float(force[0]), line_drag=False)
    linear = linearize(eq.system, eq.result)
    return linear.response(OMEGA, force, rayleigh)[linear.body]


def run_w2(quick: bool = False) -> list[Row]:
    """Case W2: the response of the box to ``F_x = A sin(1.6 t)`` (module docstring).

    Parameters
    ----------
    quick
        The small-amplitude run over 100 s instead of 120 s, and no full-amplitude runs
        (their rows are an internal time-step check and the documented response).
    """
    amplitude = 1.0e3
    force = np.array([amplitude, 0.0, 0.0, 0.0, 0.0, 0.0])
    small = forced_run(duration=100.0 if quick else 120.0, dt=0.05, amplitude=amplitude,
                       line_drag=False)
    rayleigh = rayleigh_coefficients(RAYLEIGH_RATIO, small.rayleigh_frequencies)
    exact = np.linalg.solve(continuum_box(OMEGA, rayleigh), force)
    fe = {n: _linear_fe(n, rayleigh, force) for n in (SEGMENTS, 2 * SEGMENTS, 4 * SEGMENTS)}
    window = steady_window(small.result.time, PERIOD, 5)
    t, pose = small.result.time[window], small.result.body_history(BODY)[window]
    surge, pitch = harmonic_fit(t, pose[:, 0], OMEGA), harmonic_fit(t, pose[:, 4], OMEGA)
    td = {"surge": surge.amplitude(), "pitch": pitch.amplitude(), "phase": surge.phase()}
    ref = {"surge": abs(exact[0]), "pitch": abs(exact[4]), "phase": float(np.angle(exact[0]))}
    lin = {"surge": abs(fe[SEGMENTS][0]), "pitch": abs(fe[SEGMENTS][4]),
           "phase": float(np.angle(fe[SEGMENTS][0]))}
    err = {n: abs(abs(X[0]) - ref["surge"]) / ref["surge"] for n, X in fe.items()}
    listing = ", ".join(f"{n}: {abs(X[0]):.5g} m ({err[n]:+.2%})" for n, X in fe.items())
    setting = (f"{amplitude:g} N at 1.6 rad/s, no line drag, {SEGMENTS} elements per line, "
               f"dt 0.05 s, {small.result.time[-1]:g} s from rest, harmonic fit over the "
               "last 5 periods")
    rows = []
    for key, unit in (("surge", "m"), ("pitch", "rad")):
        disc = abs(lin[key] - ref[key]) / ref[key]
        rows.append(Row(
            CASE_W2, f"small amplitude: {key} amplitude, nonlinear time domain vs continuous-"
            "line linear model", ref[key], td[key], disc + 0.01, unit=unit,
            note=f"{setting}; tolerance: the {SEGMENTS}-element discretization error of the "
            f"linearized model ({disc:.2%}) + 1 % for the time stepping",
            kind="exact", source="continuum_box: exact catenary, continuous lines"))
    disc = abs(lin["phase"] - ref["phase"])
    rows.append(Row(
        CASE_W2, "small amplitude: surge phase against sin(1.6 t), time domain vs "
        "continuous-line model", ref["phase"], td["phase"], disc + 0.03, relative=False,
        unit="rad", note=f"tolerance: the {SEGMENTS}-element phase error of the linearized "
        f"model ({disc:.3f} rad) + 0.03 rad for the time stepping", kind="exact",
        source="continuum_box"))
    rows.append(Row(
        CASE_W2, f"linearized FE model, surge amplitude: observed order of the error against "
        f"the continuous lines ({2 * SEGMENTS} -> {4 * SEGMENTS} elements)", 2.0,
        math.log2(err[2 * SEGMENTS] / err[4 * SEGMENTS]), 0.25, relative=False,
        note=f"{listing}; continuum {ref['surge']:.5g} m; lumped-mass straight elements: "
        "order 2", kind="exact", source="continuum_box"))
    rows.append(Row(
        CASE_W2, f"linearized FE model, {4 * SEGMENTS} elements: surge amplitude vs "
        "continuous lines", ref["surge"], abs(fe[4 * SEGMENTS][0]), 5e-3, unit="m",
        note=f"tolerance: the {SEGMENTS}-element error scaled by (1/4)^2, "
        f"{err[SEGMENTS] / 16:.2%}, times 3 for the pre-asymptotic range", kind="exact",
        source="continuum_box"))
    rows.append(Row(
        CASE_W2, "small amplitude: surge amplitude, time domain vs linearized FE model "
        f"({SEGMENTS} elements)", lin["surge"], td["surge"], 0.01, unit="m",
        note="the time stepping, body coupling and Rayleigh damping in the linear limit; "
        "tolerance: Newmark's period error (omega dt)^2/12 = 0.05 % amplified by the line "
        "modes next to 1.6 rad/s, and the transient left after 20 time constants",
        kind="internal cross-check"))
    static = continuum_box(1e-9).real
    mooring = body_stiffness(small.eq)
    for dof, name in ((0, "surge"), (2, "heave"), (4, "pitch")):
        rows.append(Row(
            CASE_W2, f"static {name} stiffness: group_stiffness + hydrostatics vs exact "
            "catenary + box hydrostatics", static[dof, dof], mooring[dof, dof], 5e-3,
            note="tolerance: the 11 straight elements' chord slack lowers the line tension by "
            "0.37 % (W1's a-priori estimate)", kind="exact",
            source="continuum_box at omega -> 0"))
    rows.append(Row(
        CASE_W2, "small amplitude: out-of-plane motion (largest of sway, roll, yaw) / surge",
        0.0, small.amplitudes["out_of_plane"] / small.amplitudes["x"], 1e-8, relative=False,
        note="the system is mirror-symmetric about y = 0 and the force lies in that plane; a "
        "wrong transformation or moment arm at one corner would drive roll and yaw",
        kind="exact", source="symmetry"))
    if not quick:
        full = forced_run(duration=80.0, dt=0.05)
        coarse = forced_run(duration=80.0, dt=0.1)
        linear = abs(np.linalg.solve(continuum_box(OMEGA, rayleigh), FORCE_AMPLITUDE * force
                                     / amplitude)[0])
        a = full.amplitudes
        rows.append(Row(
            CASE_W2, "full amplitude (1e5 N, line drag): surge amplitude, dt 0.1 s vs 0.05 s",
            a["x"], coarse.amplitudes["x"], 5e-3, unit="m",
            note=f"dt 0.05 s: surge {a['x']:.4g} m, heave {a['z']:.4g} m (twice the forcing "
            f"frequency), pitch {a['ry']:.4g} rad, max tension {full.max_tension:.5g} N "
            f"(static {float(full.eq.result.tension.max()):.5g} N); the continuous-line linear "
            f"model without drag gives a surge of {linear:.3g} m: the line drag suppresses "
            "the line resonance; tolerance: Newmark's period error at dt 0.1 s, 0.2 %, "
            "amplified by the line modes", kind="internal cross-check"))
    return rows


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


def _vertex(x: FloatArray, y: FloatArray) -> float:
    """Abscissa of the least ``y``, refined by the parabola through it and its two grid
    neighbours (the grid point itself at an end of the grid)."""
    k = int(np.argmin(y))
    if k in (0, len(x) - 1):
        return float(x[k])
    c2, c1, _ = np.polyfit(x[k - 1:k + 2], y[k - 1:k + 2], 2)
    return float(-c1 / (2.0 * c2))


W3_SOURCE = "Wang, Er & Iu, text on Figs. 7 and 8 (the figures are lost)"


def run_w3(quick: bool = False) -> list[Row]:
    """Case W3: the trends of the paper's Figs. 7 and 8 (module docstring).

    Each row compares with the paper's stated trend (kind ``published``). Where moorline
    gives the documented opposite trend (Figs. 7d, 8a-c) the row is ``not reproduced``
    with the reason; any other outcome is checked against the paper and can fail.
    """
    table = run_study(w3_study(quick))
    series = np.asarray(table["series"].values).astype(str)
    ratio = np.asarray(table["sag_to_span"].values, float)
    angle = np.asarray(table["inclination_deg"].values, float)
    value = {k: np.asarray(table[k].values, float) for k in
             ("surge", "heave", "pitch", "max_tension", "static_tension")}
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
        rows.append(Row(
            CASE_W3, f"Fig. {fig} {key} amplitude falls as the line gets tauter, {sags} "
            "(Spearman rank correlation with tautness)", -1.0, spearman(value[key][s], taut),
            0.15, relative=False, note=f"{listing(s, key)} {unit}; the paper states the trend "
            "in words ('decreases obviously'); tolerance 0.15: of five points one adjacent "
            "pair may swap (Spearman -0.9), not two (-0.8); of three, none (-0.5)",
            kind="published", source=W3_SOURCE))
    t_max, t_static = value["max_tension"], value["static_tension"]
    denominators = 1.0 / ratio[s]
    least = float(denominators[np.argmin(t_max[s])])
    dyn = ", ".join(f"{t_max[k] - t_static[k]:.3g}" for k in s)
    opposite = least == denominators.min()  # documented: lowest at the slackest line
    rows.append(Row(
        CASE_W3, "Fig. 7d sag-to-span of the least max tension, 1/n: n (paper: near 1/60)",
        60.0, least, 10.0, relative=False,
        note=f"max tension {listing(s, 'max_tension')} N at {sags}: it rises monotonically "
        "with tautness, dominated by the static pretension (which grows as 1/(d/l)); its "
        f"dynamic part (max - static: {dyn} N) is what peaks near 1/60. The paper's minimum "
        "is not obtained; tolerance: the grid step next to 1/60", kind="published",
        source=W3_SOURCE, reproduced=not opposite))
    frequencies = [surge_pitch_frequency(forced_equilibrium(ratio[k], angle[k])) for k in i]
    rayleigh = rayleigh_coefficients(RAYLEIGH_RATIO, W3_RAYLEIGH)
    force = np.array([FORCE_AMPLITUDE, 0.0, 0.0, 0.0, 0.0, 0.0])
    linear = [abs(np.linalg.solve(continuum_box(OMEGA, rayleigh, 1.0 / 60.0, angle[k]),
                                  force)[0]) for k in i]
    why = ("steeper lines are softer horizontally: the rigid-box surge-pitch frequency on the "
           f"quasi-static mooring stiffness falls ({', '.join(f'{w:.3g}' for w in frequencies)}"
           " rad/s) towards the forcing 1.6 rad/s, and the continuous-line linear model "
           f"(no drag) gives a surge of {', '.join(f'{x:.3g}' for x in linear)} m, also rising;"
           " an angle from the vertical would give the paper's trend but W1's draft 0.981 m "
           "instead of 0.896 m")
    for key, fig, unit in (("surge", "8a", "m"), ("heave", "8b", "m"), ("pitch", "8c", "rad")):
        trend = spearman(value[key][i], angle[i])
        rows.append(Row(
            CASE_W3, f"Fig. {fig} {key} amplitude falls as the inclination grows, {angles} deg "
            "(Spearman rank correlation with the angle)", -1.0, trend, 0.15, relative=False,
            note=f"{listing(i, key)} {unit}: here it rises; {why}", kind="published",
            source=W3_SOURCE, reproduced=trend < 0.85))
    grid = angle[i]
    centre = int(np.argmin(np.abs(grid - INCLINATION_DEG)))
    step = float(np.min(np.abs(np.delete(grid, centre) - grid[centre])))
    rows.append(Row(
        CASE_W3, "Fig. 8d inclination of the least max tension (paper: falls from 40 to 50 "
        "deg, rises from 50 to 54)", INCLINATION_DEG, _vertex(grid, t_max[i]), step,
        relative=False, unit="deg",
        note=f"max tension {listing(i, 'max_tension')} N at {angles} deg; computed: the vertex "
        "of the parabola through the least value and its two neighbours; tolerance: the "
        f"study's grid step at 50 deg ({step:g} deg), finer than the paper's stated points "
        "(40, 50, 54 deg)", kind="published", source=W3_SOURCE))
    return rows
