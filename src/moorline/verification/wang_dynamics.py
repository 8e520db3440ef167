"""Wang, Er and Iu: forced response of the moored box (W2) and its parameter study (W3).

Placeholder docstring, rewritten below once the numbers are in.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
import scipy.linalg as sla
from numpy.typing import NDArray

from ..mesh import discretize
from ..model import DynamicsSettings, Motion, System
from ..results import DynamicResult, StaticResult
from ..solvers.assembly import BlockPattern
from ..solvers.bodies import body_loads, skew, transformation
from ..solvers.dynamic_model import DynamicModel
from ..solvers.dynamics import simulate
from ..solvers.stiffness import group_stiffness
from .wang_w1 import (
    INCLINATION_DEG,
    SAG_TO_SPAN,
    SEGMENTS,
    Equilibrium,
    Layout,
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
        term; :meth:`~moorline.solvers.coupled_dynamics.CoupledStepper.setup_rayleigh`).
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
    R = np.array([_rotation(p[3:]) for p in pose])
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
    M[d, d] += _rigid_mass(body, R[0])
    if body.added_mass is not None:
        M[d, d] += np.asarray(body.added_mass, float)
    K[d, d] += body_loads(body, pose[0, :3], R[0], mesh.gravity, mesh.water_density)[1]
    K_rayleigh = K.copy()
    for f, arm in zip(ev.nodal[mesh.slave_node], arms, strict=True):
        K[n_free + 3:n_free + 6, n_free + 3:n_free + 6] -= skew(f) @ skew(arm)
    return LinearModel(M, K, K_rayleigh, d)


def _rotation(phi: FloatArray) -> FloatArray:
    from ..mesh import rotation_matrix

    return rotation_matrix(np.asarray(phi, float))


def _rigid_mass(body, R: FloatArray) -> FloatArray:
    """6x6 rigid-body mass about the body origin, world axes."""
    c = R @ np.asarray(body.center_of_gravity, float)
    S = skew(c)
    M = np.zeros((6, 6))
    M[:3, :3] = body.mass * np.eye(3)
    M[:3, 3:] = -body.mass * S
    M[3:, :3] = body.mass * S
    M[3:, 3:] = R @ np.asarray(body.inertia, float) @ R.T - body.mass * S @ S
    return M


def body_stiffness(eq: Equilibrium) -> FloatArray:
    """6x6 restoring stiffness of the moored box about its origin: the mooring
    (:func:`~moorline.solvers.stiffness.group_stiffness` of the four fairleads) plus gravity
    and hydrostatics."""
    result = eq.result
    body = eq.system.bodies[BODY]
    pose = result.body_pose[0]
    K = group_stiffness(result, list(FAIRLEADS), pose[:3])
    return K + body_loads(body, pose[:3], _rotation(pose[3:]), result.mesh.gravity,
                          result.mesh.water_density)[1]


def surge_pitch_frequency(eq: Equilibrium) -> float:
    """Lowest natural frequency [rad/s] of the rigid box in surge and pitch on its
    quasi-static mooring stiffness (:func:`body_stiffness`), line inertia ignored."""
    K = body_stiffness(eq)
    M = _rigid_mass(eq.system.bodies[BODY], _rotation(eq.result.body_pose[0, 3:]))
    idx = np.ix_([0, 4], [0, 4])
    return float(np.sqrt(sla.eigh(K[idx], M[idx], eigvals_only=True)[0]))


def rayleigh_coefficients(ratio: float, frequencies: tuple[float, float]) -> tuple[float, float]:
    """``(a0, a1)`` of ``a0 M + a1 K`` with damping ``ratio`` at both circular frequencies."""
    w1, w2 = frequencies
    return 2.0 * ratio * w1 * w2 / (w1 + w2), 2.0 * ratio / (w1 + w2)


# ----------------------------------------------------------------------------- signals
def steady_window(time: FloatArray, period: float, n_periods: int) -> NDArray[np.bool_]:
    """Mask of the last ``n_periods`` whole periods of ``time``."""
    time = np.asarray(time, float)
    return time >= time[-1] - n_periods * period - 1e-9 * period


def harmonic_fit(time: FloatArray, signal: FloatArray, omega: float) -> tuple[float, float,
                                                                             float]:
    """Least-squares ``mean + a cos(w t) + b sin(w t)``: (mean, amplitude, phase [rad]) with
    ``signal ~ mean + amplitude sin(w t + phase)``."""
    t = np.asarray(time, float)
    A = np.column_stack((np.ones_like(t), np.cos(omega * t), np.sin(omega * t)))
    c = np.linalg.lstsq(A, np.asarray(signal, float), rcond=None)[0]
    return float(c[0]), float(math.hypot(c[1], c[2])), float(math.atan2(c[1], c[2]))


def dominant_period(time: FloatArray, signal: FloatArray) -> tuple[float, float]:
    """Period of the largest spectral peak of a uniformly sampled signal (mean removed,
    Hann window, parabolic interpolation of the peak); also the bin width as a period
    uncertainty ``T^2 df``."""
    t = np.asarray(time, float)
    y = np.asarray(signal, float) - np.mean(signal)
    dt = float(np.mean(np.diff(t)))
    n = len(y)
    spec = np.abs(np.fft.rfft(y * np.hanning(n)))
    k = int(np.argmax(spec[1:])) + 1
    shift = 0.0
    if 0 < k < len(spec) - 1:
        a, b, c = np.log(spec[k - 1:k + 2] + 1e-300)
        shift = 0.5 * (a - c) / (a - 2 * b + c)
    df = 1.0 / (n * dt)
    T = 1.0 / ((k + shift) * df)
    return T, T * T * df


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
