"""Stochastic response to random waves in the frequency domain (Tuah (1982) ch. 5).

The system vibrates about its static equilibrium ``x0`` (all nonlinearity is in the statics),
the waves are Gaussian, and the quadratic drag is replaced by a statistically equivalent
linear damping (Borgman 1972), so that the response is a linear transform of the sea
(eq. 5.1)::

    M U'' + C U' + K U = B_D V + B_I a,

``M`` structural plus added mass and ``K`` the tangent stiffness at ``x0``
(:func:`moorline.solvers.modal.modal_matrices`), ``V`` and ``a`` the fluid velocity and
acceleration at the element midpoints (:mod:`moorline.waves.transfer`, eq. 5.2.8-5.2.10).

Loads per element, the lumping of the time-domain model (:mod:`moorline.physics.hydro`: half of
the element to each node, per unstretched length ``L0``, chord tangent ``t`` at ``x0``):

- drag (eq. 5.2.1-5.2.2): ``[B_DL (I - t t^T) + B_DT t t^T] (V - U')`` with
  ``B_DL = (2/pi)^(1/2) C_D rho D sigma_n`` and ``B_DT = (2 pi)^(1/2) C_T rho D sigma_t``,
  ``sigma_n``, ``sigma_t`` the standard deviations of the normal and tangential relative
  velocity of the element (eq. 5.2.3-5.2.5; zero means). These are the quadratic laws
  ``rho C_D D / 2 |u_n| u_n`` and ``rho C_T pi D / 2 |u_t| u_t`` linearized by
  ``E[|u| u] = (8/pi)^(1/2) sigma u`` for a Gaussian ``u``;
- fluid inertia (eq. 5.2.1): ``rho A [(1 + Ca)(I - t t^T) + (1 + Cat) t t^T] a`` (as
  :func:`moorline.physics.hydro.fluid_inertia_forces`); the added mass is in ``M``.

The standard deviations are iterated (steps 5-13): start with the structure at rest, solve,
recompute ``sigma`` from the relative velocity spectra, until no ``sigma`` changes by more than
``tolerance`` (relative). The variance of a response ``x`` with transfer function ``H_x`` per
unit wave amplitude is ``sum_m |H_x(omega_m)|^2 S(omega_m) d_omega``.

Frequency response (steps 7-11), two ways:

- the full system ``(K - omega^2 M + i omega C) U = F`` at every frequency: ``direct``, and
  ``foss`` with ``n_modes`` 0 (all modes: Foss's decoupling over every mode is the same
  linear algebra, with a dense generalized eigenproblem of twice the size per linearization
  and round-off of order eps over the relative gap of the closest poles). Banded and
  compiled (:mod:`moorline.solvers.frequency_sweep`: reverse Cuthill-McKee order, a band LU
  per frequency, the residual of every frequency checked and the few above 1e-9 solved
  again with pivoting; counters ``band``, ``pivoted_frequencies``): the 3-hour OC3 sea,
  6,480 frequencies and 171 unknowns, in about 0.1 s per linearization;
- ``foss`` with ``n_modes`` > 0 (the source's, modal truncation): modes ``Phi``
  (mass-normalized, the lowest ``n_modes``, all when it exceeds the unknowns),
  modal damping ``C_u = Phi^T C Phi`` (full: drag couples the modes), decoupled by Foss's
  (1958) complex modes of the first-order form (eq. 5.3.4-5.3.28)::

      [[0, I], [I, C_u]] q' + [[-I, 0], [0, Lambda]] q = [0, Phi^T F],   q = [z', z],

  eigenvalues ``Omega_j`` and vectors ``theta_j = [Omega_j chi_j, chi_j]``,
  ``c_j = 2 Omega_j chi_j^T chi_j + chi_j^T C_u chi_j``, ``k_j = -Omega_j c_j + ...`` (eq.
  5.3.18-19), ``r_j = chi_j^T Phi^T F / (k_j + i omega c_j)``, ``U = Phi sum_j chi_j r_j``. (The
  OCR prints ``q = {Z', Z'}``; it is ``{z', z}``.)
  With all modes it reproduces the full system's solution to round-off (a test).

Time series (step 14): the inverse FFT of ``H_x A_m`` with the realization's complex
amplitudes (DSA or NSA), ``x(n dt) = 2N irfft(H_x A)[n]`` (:mod:`moorline.waves.random`).

Rigid bodies (Tuah sec. 5.2, "force spectra on large bodies ... by the procedure of sec.
3.3"): the unknowns are the free node dofs and six per free body, lines attached through the
master-slave transformation (:func:`moorline.solvers.modal.body_modal_matrices`); constant
added mass and radiation damping, or a body's frequency-dependent ``radiation`` table
(:class:`moorline.model.RadiationTable`, e.g. from capytaine): ``A(omega)`` and
``B(omega)`` interpolated linearly at each frequency, held constant beyond the table's ends
(its first and last rows; a warning when more than 1 % of the sea's variance lies outside
the table). The system at each frequency is then ``K - omega^2 (M + A(omega)) + i omega (C +
B(omega))``: ``direct`` solves it as it is; ``foss`` takes its modes from ``K`` and ``M +
A(omega_p)`` (``omega_p`` the spectral peak) and solves the coupled modal equations
``Lambda - omega^2 (I + Phi^T dA Phi) + i omega Phi^T (C + B) Phi`` at each frequency (Foss's
complex modes need constant matrices), exact with all modes. The wave loads on a body from
its exciting-force table (amplitude and unwrapped phase interpolated over frequency, zero
above the table) or the long-wave model of the time domain (``wave_loads``), and its
quadratic drag linearized the same way per direction.

Free points with their own hydrodynamics (buoys, clump weights: volume, added mass, drag
area) get the fluid inertia and the linearized drag of the time domain.

The lines' Kelvin-Voigt dashpot ``BA`` (the time domain's ``T += BA share deps/dt``, ``share``
blending it off in slack elements) linearized at rest: ``c = BA share / L0`` per element,
``c t t^T`` on its relative motion in ``C`` and ``i omega c t . (U_b - U_a)`` in the tension
transfer (tested against the time domain on a riser where it is 20 % of the tension).

Left out (the time domain has it): the superharmonics of the quadratic drag, which in the
time domain ring lightly damped modes above the wave band (``benchmarks/bench_all.py`` P3:
most of the OC3 fairlead tension's time-domain variance, a few N, at 1-3 rad/s; within the
wave band the two agree).

Current (beyond the source, which assumes zero-mean flow): with a steady current ``U(x)`` the
relative velocity is ``U + u'``, ``u'`` zero-mean Gaussian, and each quadratic drag law is
replaced by its mean plus the mean-square-optimal linear term about the mean,
``c (E[|w| w] + G w')`` with ``G = E[d(|w| w)/dw]`` (Atalik & Utku 1976; exact Gaussian
expectations, :mod:`moorline.solvers.drag_linearization`): per element the normal law on
the normal plane (mean ``(I - t t^T) U``, covariance of the normal relative velocity from its
spectra) and the tangential law in one dimension, ``2 c_t E|s| t t^T`` (``E|s|`` closed form);
points the same in three dimensions. Without current the code is Tuah's formula above,
unchanged. The mean state: the statics with the current's drag (``current_drag``), then the
linearization about it, then the statics re-solved with the excess of the mean drag over the
current's steady drag, ``E[f] - f(U)``, as node loads, repeated until the mean positions change
by less than ``tolerance`` times the largest displacement std (two statics typically;
``counters["mean_drag_offset"]``: how far the mean state moved from the current-only one,
the error of a one-way analysis). At most ``max_iterations`` statics, each with at most
``max_iterations`` linearization iterations; a linearization that does not converge ends the
mean-state loop at once (failed, the message gives the iterations and the last change).
Approximations: the tangent ``K`` about the mean state has
no drag stiffness (the change of the mean drag with the element direction). Bodies: their
drag ``1/2 rho Cd A_i |w_i| w_i`` per world direction on the relative velocity at the origin
(the time domain's law) is linearized per direction about the current ``U_i`` there,
``c_i (E[w_i|w_i|] + 2 E|w_i| w_i')`` (closed form, :func:`moorline.solvers.drag_linearization.
scalar_expectations`; without current ``2 E|w_i| = (8/pi)^(1/2) sigma_i``); the statics
carries the current's steady drag on them (:func:`moorline.solvers.statics.body_current_drag`)
and the mean state the excess of the mean drag.
"""

from __future__ import annotations

import logging
import math
from dataclasses import replace

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
from numpy.typing import NDArray

from ..errors import MoorlineError
from ..mesh import Mesh, discretize, dynamic_mesh, with_loads_of
from ..model import ModalSettings, StaticsSettings, StochasticSettings, System
from ..physics import element
from ..results import StaticResult, StochasticResult
from ..waves import random_sea, wave_number
from ..waves.transfer import kinematics_transfer
from . import drag_linearization
from .bodies import long_wave_geometry
from .frequency_sweep import FrequencySweep
from .linearized_laws import refuse_unlinearized
from .modal import system_matrices
from .statics import _current_field, equilibrium_for, solve_statics

logger = logging.getLogger(__name__)

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]


def _inertia_blocks(t: FloatArray, mesh: Mesh, rho: float) -> FloatArray:
    """Per-node share of the fluid-inertia operator ``rho A L0 / 2 [(1 + Ca) (I - t t^T)
    + (1 + Cat) t t^T]`` (n_elements, 3, 3)."""
    m = 0.5 * rho * 0.25 * math.pi * mesh.diameter**2 * mesh.length0
    tt = t[:, :, None] * t[:, None, :]
    return (m * (1.0 + mesh.Ca))[:, None, None] * (np.eye(3) - tt) \
        + (m * (1.0 + mesh.Cat))[:, None, None] * tt


def _drag_blocks(t: FloatArray, mesh: Mesh, rho: float, sigma_n: FloatArray,
                 sigma_t: FloatArray) -> FloatArray:
    """Linearized drag per unit length ``B_DL (I - t t^T) + B_DT t t^T`` (eq. 5.2.1-5.2.2),
    (n_elements, 3, 3)."""
    b_n = math.sqrt(2.0 / math.pi) * mesh.Cd * rho * mesh.diameter * sigma_n
    b_t = math.sqrt(2.0 * math.pi) * mesh.Ct * rho * mesh.diameter * sigma_t
    tt = t[:, :, None] * t[:, None, :]
    return b_n[:, None, None] * (np.eye(3) - tt) + b_t[:, None, None] * tt


def _apply_blocks(blocks: FloatArray, H: ComplexArray) -> ComplexArray:
    """``blocks[e] @ H[e, :, w]`` (n_el * 3, n_w) for blocks (n_el, 3, 3) and ``H`` (n_el,
    3, n_w), frequency last."""
    return np.matmul(blocks, H).reshape(-1, H.shape[-1])


def _node_pairs(block: FloatArray) -> FloatArray:
    """(n_el, 6, 6) with ``block`` on all four node-node positions."""
    return np.tile(block, (1, 2, 2))


def _matrix6(value) -> FloatArray:
    """A body's 6x6 coefficient (``None``: zeros; six numbers: a diagonal)."""
    if value is None:
        return np.zeros((6, 6))
    m = np.asarray(value, dtype=float)
    return np.diag(m) if m.ndim == 1 else m


def _seabed_damping_blocks(mesh, positions: FloatArray, model) -> FloatArray | None:
    """Node damping blocks (n_nodes, 3, 3) of the seabed contact damper linearized about the
    static state: ``c share`` along the seabed normal of the nodes the seabed pushes, the
    same law as the time domain (:func:`moorline.physics.seabed.surface_contact` at zero
    velocity: its ``d/dv``); ``None`` without a seabed."""
    from ..physics import seabed

    surface = mesh.seabed_surface
    if surface is None:
        return None
    c = mesh.seabed_damping_per_area * mesh.node_contact_area
    contact = seabed.surface_contact(positions, np.zeros_like(positions), surface,
                                     model.node_seabed_stiffness, c, model.seabed_ramp)
    if not np.any(contact.damping):
        return None
    return -contact.damping


def _dashpot(mesh: Mesh, positions: FloatArray) -> FloatArray:
    """Per element, the axial dashpot's tension per unit rate of elongation ``BA share / L0``
    [N s/m] about the static state: the time domain's Kelvin-Voigt law
    (:class:`moorline.solvers.dynamic_model.DynamicModel`, ``T += BA share deps/dt``) at zero
    velocity, ``share`` its blending off in slack elements
    (:func:`moorline.physics.element.dashpot_share`)."""
    length, _ = element.element_geometry(positions, mesh.elements)
    share, _ = element.dashpot_share(length, mesh.length0, mesh.slack_smoothing,
                                     mesh.strain_offset)
    return mesh.BA * share / mesh.length0


class _LinearModel:
    """``K``, ``M`` and the assembly of damping and forces over the unknowns: the free node
    dofs of the lines, then six per free body (the master-slave transformation ``P`` of
    Tuah (1982) eq. 3.3.6-3.3.10 maps them to the extended node dofs, which include the
    nodes attached to bodies)."""

    def __init__(self, system: System, statics: StaticResult,
                 settings: StochasticSettings) -> None:
        mesh = dynamic_mesh(with_loads_of(statics.mesh, system), statics.positions)
        self.mesh, self.rho = mesh, float(mesh.water_density)
        modal = ModalSettings(mass=settings.mass, added_mass=settings.added_mass)
        K, M, P, problem = system_matrices(mesh, statics.positions, statics.body_pose, modal,
                                           tabulated_added_mass=False)  # A(w) added below
        self.P, self.n_free = P, problem.n_free
        self.pattern, self.ext_map = problem.pattern, problem.ext_map
        self.bodies = [b for b, d in zip(problem.bodies, problem.body_dof, strict=True)
                       if d >= 0]
        self.body_dof = np.array([d for d in problem.body_dof if d >= 0], dtype=int)
        self.origins = np.array([statics.body_pose[i, :3] for i, d
                                 in enumerate(problem.body_dof) if d >= 0]).reshape(-1, 3)
        self.K, self.M = K, M
        self.environment = system.environment
        self.radiation = [(d, body.radiation) for body, d in zip(self.bodies, self.body_dof,
                                                                  strict=True)
                          if body.radiation is not None]
        self.seabed_blocks = _seabed_damping_blocks(mesh, statics.positions, problem.model)
        self.dashpot = _dashpot(mesh, statics.positions)
        _, t = element.element_geometry(statics.positions, mesh.elements)
        self.dashpot_blocks = element.pair_blocks(
            self.dashpot[:, None, None] * t[:, :, None] * t[:, None, :])
        held = self.ext_map.ravel() >= 0
        rows = np.flatnonzero(held)
        select = sp.csr_matrix((np.ones(len(rows)), (rows, self.ext_map.ravel()[rows])),
                               shape=(3 * mesh.n_nodes, P.shape[0]))
        #: node displacements (3 n_nodes) from the unknowns (zero rows for held nodes)
        self.nodes_of = (select @ P).tocsr()

    def midpoint_map(self) -> sp.csr_matrix:
        """``(U_a + U_b) / 2`` per element (3 n_elements rows) from the unknowns."""
        elements = self.mesh.elements
        rows = np.repeat(np.arange(3 * len(elements)), 2)
        nodes = 3 * elements[:, None, :] + np.arange(3)[None, :, None]  # (n_el, 3, 2)
        half = sp.csr_matrix((np.full(rows.size, 0.5), (rows, nodes.ravel())),
                             shape=(3 * len(elements), 3 * self.mesh.n_nodes))
        return (half @ self.nodes_of).tocsr()

    def radiation_blocks(self, omega: FloatArray) -> tuple[FloatArray, FloatArray]:
        """``A(omega)`` and ``B(omega)`` of the bodies with a radiation table, (n_w,
        n_tables, 6, 6), linear in omega, constant beyond the table's ends."""
        shape = (len(omega), len(self.radiation), 6, 6)
        added, damping = np.zeros(shape), np.zeros(shape)
        for k, (_, table) in enumerate(self.radiation):
            w = np.asarray(table.omegas, dtype=float)
            for out, values in ((added, table.added_mass), (damping, table.damping)):
                v = np.asarray(values, dtype=float).reshape(len(w), 36)
                out[:, k] = np.stack([np.interp(omega, w, v[:, j]) for j in range(36)],
                                     axis=-1).reshape(-1, 6, 6)
        return added, damping

    def body_kinematics(self, omega: FloatArray, current=None) -> _BodyWaves:
        """The wave loads on the free bodies (``current``: the steady current)."""
        return _BodyWaves(self, omega, current)

    def damping(self, element_blocks: FloatArray, gain_b: FloatArray,
                node_blocks: FloatArray | None = None) -> sp.csr_matrix:
        """Linearized line (and point) drag, the lines' axial dashpots, the seabed contact
        damper of the resting nodes, bodies' radiation damping and linearized body drag
        (``gain_b``, (n_bodies, 3): :meth:`_BodyWaves.gains`)."""
        if self.seabed_blocks is not None:
            node_blocks = (self.seabed_blocks if node_blocks is None
                           else node_blocks + self.seabed_blocks)
        element_blocks = element_blocks + self.dashpot_blocks  # the lines' axial dashpots
        C = self.pattern.assemble(element_blocks, node_blocks)
        C = (self.P.T @ C @ self.P).tolil()
        for i, (body, d) in enumerate(zip(self.bodies, self.body_dof, strict=True)):
            block = _matrix6(body.damping) + _matrix6(body.additional_damping)
            block[:3, :3] += np.diag(gain_b[i])
            C[d:d + 6, d:d + 6] = C[d:d + 6, d:d + 6].toarray() + block
        return C.tocsr()

    def forces(self, nodal: ComplexArray | None, body_forces: ComplexArray,
               out: ComplexArray) -> ComplexArray:
        """``out`` (n_u, n_w: frequency last) plus the generalized forces of node forces
        (n_w, n_nodes, 3; or ``None``) and body forces (n_w, n_bodies, 6)."""
        if nodal is not None:
            out = out + self.nodes_of.T @ nodal.reshape(len(nodal), -1).T
        for i, d in enumerate(self.body_dof):
            out[d:d + 6] += body_forces[:, i].T
        return out

    def split(self, solution: ComplexArray) -> tuple[ComplexArray, ComplexArray]:
        """Node displacements (n_w, n_nodes, 3) and body motions (n_w, n_bodies, 6)."""
        nodes = np.ascontiguousarray((self.nodes_of @ solution.T).T).reshape(
            len(solution), self.mesh.n_nodes, 3)
        bodies = np.stack([solution[:, d:d + 6] for d in self.body_dof], axis=1) \
            if len(self.body_dof) else np.zeros((solution.shape[0], 0, 6), dtype=complex)
        return nodes, bodies


def _covariance(parts: tuple[FloatArray, FloatArray], power: FloatArray) -> FloatArray:
    """``sum_w power_w Re(R_w R_w^H)`` per element, (n_el, 3, 3), of transfer functions
    ``R`` given by their real and imaginary parts, each (n_el, 3, n_w)."""
    return sum((p * power) @ p.transpose(0, 2, 1) for p in parts)


def _body_drag(body, rho: float, sigma: FloatArray, mean: FloatArray | None = None
               ) -> tuple[FloatArray, FloatArray]:
    """Linearized drag per world direction of a body (3,) and its mean drag's excess over
    the steady current's (3,): ``c_i 2 E|w_i|`` and ``c_i (E[w_i|w_i|] - U_i|U_i|)``,
    ``c_i = 1/2 rho Cd A_i``, ``w_i ~ N(U_i, sigma_i^2)``; without a mean ``c_i (8/pi)^(1/2)
    sigma_i`` and 0."""
    c = 0.5 * rho * body.Cd * np.asarray(body.drag_area, dtype=float)
    if mean is None:
        return c * math.sqrt(8.0 / math.pi) * sigma, np.zeros(3)
    e_sq, e_abs = drag_linearization.scalar_expectations(mean, sigma)
    return 2.0 * c * e_abs, c * (e_sq - np.abs(mean) * mean)


class _BodyWaves:
    """Wave loads on the free bodies per unit wave amplitude: the body's exciting-force
    table (amplitude and phase over frequency, :class:`moorline.model.body.WaveExcitation`,
    interpolated; zero above its last frequency), else with ``wave_loads`` the long-wave
    model of the time domain (Froude-Krylov and added-mass force on the fluid acceleration
    at the origin, waterplane heave force), plus the linearized drag on the fluid velocity;
    and the standard deviations of the relative velocity at the origin."""

    def __init__(self, model: _LinearModel, omega: FloatArray, current=None) -> None:
        mesh, env = model.mesh, model.environment
        self.model, self.omega = model, omega
        self.mean = (None if current is None or not model.bodies
                     else current.kinematics(model.origins, 0.0)[0])
        self.fixed = np.zeros((len(omega), len(model.bodies), 6), dtype=complex)
        self.H_v = np.zeros((len(omega), len(model.bodies), 3), dtype=complex)
        if not model.bodies:
            return
        H_v, H_a = kinematics_transfer(model.origins, omega, env.waves.heading_deg, env.depth,
                                       env.gravity)
        self.H_v = H_v
        k = np.atleast_1d(wave_number(omega, env.depth, env.gravity))
        beta = math.radians(env.waves.heading_deg)
        for i, body in enumerate(model.bodies):
            along = model.origins[i, 0] * math.cos(beta) + model.origins[i, 1] * math.sin(beta)
            shift = np.exp(-1j * k * along)
            table = body.excitation
            if table is not None:
                w_tab = np.asarray(table.omegas, dtype=float)
                amp = np.column_stack([np.interp(omega, w_tab, np.asarray(table.amplitude)[:, j],
                                                 right=0.0) for j in range(6)])
                unwrapped = np.unwrap(np.radians(np.asarray(table.phase_deg, dtype=float)),
                                      axis=0)
                phase = np.column_stack([np.interp(omega, w_tab, unwrapped[:, j])
                                         for j in range(6)])
                self.fixed[:, i] = amp * np.exp(1j * phase) * shift[:, None]
            elif body.wave_loads:
                area_wp, volume = long_wave_geometry(body, float(model.origins[i, 2]),
                                                     model.rho, mesh.gravity)
                added = _matrix6(body.added_mass)[:3, :3]
                self.fixed[:, i, :3] = H_a[:, i] @ (model.rho * volume * np.eye(3) + added).T
                self.fixed[:, i, 2] += model.rho * mesh.gravity * area_wp * shift

    def gains(self, sigma_b: FloatArray) -> tuple[FloatArray, FloatArray]:
        """Linearized drag coefficients (n_bodies, 3) at the relative-velocity standard
        deviations ``sigma_b`` (about the current's mean when there is one) and the mean
        drag's excess over the steady current's (n_bodies, 3)."""
        out = [_body_drag(body, self.model.rho, sigma_b[i],
                          None if self.mean is None else self.mean[i])
               for i, body in enumerate(self.model.bodies)]
        if not out:
            return np.zeros((0, 3)), np.zeros((0, 3))
        return np.array([g for g, _ in out]), np.array([e for _, e in out])

    def excitation(self, gain_b: FloatArray) -> ComplexArray:
        """Body forces (n_w, n_bodies, 6) with the drag coefficients ``gain_b``."""
        out = self.fixed.copy()
        for i in range(len(self.model.bodies)):
            out[:, i, :3] += self.H_v[:, i] * gain_b[i]
        return out

    def sigmas(self, X: ComplexArray, power: FloatArray) -> FloatArray:
        """Standard deviation of the relative velocity at each body origin per direction
        (n_bodies, 3)."""
        if not self.model.bodies:
            return np.zeros((0, 3))
        rel = self.H_v - 1j * self.omega[:, None, None] * X[..., :3]
        return np.sqrt(np.einsum("w,wbc->bc", power, np.abs(rel) ** 2))


class _PointWaves:
    """Wave loads on free points with their own hydrodynamics (buoys, clump weights), as in
    the time domain (:meth:`moorline.solvers.dynamic_model.DynamicModel`): fluid inertia
    ``rho V (1 + Ca) a`` (the added mass ``rho Ca V`` is in ``M``) and the isotropic drag
    ``1/2 rho Cd A |u| u`` on the relative velocity, linearized like the lines' normal drag:
    without current ``1/2 rho Cd A (8/pi)^(1/2) sigma u``, ``sigma`` the standard deviation
    of the relative velocity vector; with a current ``U`` at the point
    ``1/2 rho Cd A (E[|u| u] + G u')`` with the exact Gaussian expectations about the mean
    (:func:`moorline.solvers.drag_linearization.vector_expectations`)."""

    def __init__(self, mesh: Mesh, x0: FloatArray, omega: FloatArray, env, rho: float,
                 current=None) -> None:
        self.omega = omega
        self.drag = 0.5 * rho * mesh.node_Cd * mesh.node_drag_area
        self.mass = rho * mesh.node_volume * (1.0 + mesh.node_Ca)
        self.nodes = np.flatnonzero(((self.drag > 0) | (self.mass > 0)) & mesh.free_nodes)
        self.n_nodes = mesh.n_nodes
        self.mean = None
        if self.nodes.size:
            self.H_v, H_a = kinematics_transfer(x0[self.nodes], omega, env.waves.heading_deg,
                                                env.depth, env.gravity)
            self.inertia = self.mass[self.nodes][None, :, None] * H_a
            self.coefficient = self.drag[self.nodes] * math.sqrt(8.0 / math.pi)
            if current is not None:
                self.mean = current.kinematics(x0[self.nodes], 0.0)[0]

    def _relative(self, U: ComplexArray) -> ComplexArray:
        return self.H_v - 1j * self.omega[:, None, None] * U[:, self.nodes]

    def sigmas(self, U: ComplexArray, power: FloatArray) -> FloatArray:
        """Standard deviation of each point's relative velocity (vector magnitude)."""
        if not self.nodes.size:
            return np.zeros(0)
        return np.sqrt(np.einsum("w,wpc->p", power, np.abs(self._relative(U)) ** 2))

    def gains(self, U: ComplexArray, power: FloatArray, sigma: FloatArray
              ) -> tuple[FloatArray, FloatArray]:
        """Linearized drag matrices (n_points, 3, 3) and the mean drag minus the steady
        current's drag (n_points, 3) about the response ``U``."""
        k = self.nodes.size
        if not k:
            return np.zeros((0, 3, 3)), np.zeros((0, 3))
        if self.mean is None:
            return (self.coefficient * sigma)[:, None, None] * np.eye(3), np.zeros((k, 3))
        R = self._relative(U)
        cov = np.einsum("w,wpi,wpj->pij", power, R, R.conj()).real
        e_f, gain = drag_linearization.vector_expectations(self.mean, cov,
                                                           np.broadcast_to(np.eye(3), cov.shape))
        c = self.drag[self.nodes]
        steady = np.linalg.norm(self.mean, axis=1)[:, None] * self.mean
        return c[:, None, None] * gain, c[:, None] * (e_f - steady)

    def forces(self, gain: FloatArray) -> ComplexArray | None:
        """Node forces (n_w, n_nodes, 3) of the points' fluid inertia and linearized drag
        excitation (``None`` without such points)."""
        if not self.nodes.size:
            return None
        nodal = np.zeros((len(self.omega), self.n_nodes, 3), dtype=complex)
        nodal[:, self.nodes] = self.inertia + np.einsum("pij,wpj->wpi", gain, self.H_v)
        return nodal

    def damping_blocks(self, gain: FloatArray) -> FloatArray | None:
        """Node damping blocks (n_nodes, 3, 3) of the linearized point drag."""
        if not self.nodes.size:
            return None
        blocks = np.zeros((self.n_nodes, 3, 3))
        blocks[self.nodes] = gain
        return blocks


class _Response:
    """Frequency response of ``M U'' + C U' + K U = F`` over the free dofs, plus the
    frequency-dependent body terms ``(-omega^2 dA(omega) + i omega B(omega))`` of the
    radiation tables (module docstring)."""

    def __init__(self, K: sp.csr_matrix, M: sp.csr_matrix, settings: StochasticSettings,
                 omega: FloatArray | None = None, model: _LinearModel | None = None,
                 omega_ref: float = 0.0) -> None:
        self.K, self.settings = K, settings
        self.frequency_terms = None
        if model is not None and model.radiation and omega is not None:
            added, damping = model.radiation_blocks(np.append(omega, omega_ref))
            # the modal basis needs a symmetric mass (a BEM table is symmetric only to its
            # discretization); the per-frequency terms carry the exact A(w) - A_ref
            added[-1] = 0.5 * (added[-1] + np.swapaxes(added[-1], -1, -2))
            dofs = [d for d, _ in model.radiation]
            M = M.tolil()
            for k, d in enumerate(dofs):
                M[d:d + 6, d:d + 6] = M[d:d + 6, d:d + 6].toarray() + added[-1, k]
            M = M.tocsr()
            # -w^2 (A(w) - A(w_ref)) + i w B(w), on the bodies' 6x6 blocks
            terms = (-(omega**2)[:, None, None, None] * (added[:-1] - added[-1:])
                     + 1j * omega[:, None, None, None] * damping[:-1])
            self.frequency_terms = (dofs, terms)
        self.M = M
        self.modal = settings.method == "foss" and settings.n_modes > 0
        if self.modal:
            lam, phi = sla.eigh(K.toarray(), M.toarray())
            self.lam, self.phi = lam[: settings.n_modes], phi[:, : settings.n_modes]
        else:
            self.sweep = FrequencySweep(K, M, self._extra_positions())

    def _extra_positions(self) -> tuple[NDArray[np.int64], NDArray[np.int64]] | None:
        """Rows and columns of the frequency-dependent body terms (the bodies' 6x6 blocks)."""
        if self.frequency_terms is None:
            return None
        base = np.arange(6)
        dofs = self.frequency_terms[0]
        return (np.concatenate([np.repeat(base + d, 6) for d in dofs]),
                np.concatenate([np.tile(base + d, 6) for d in dofs]))

    def solve(self, C: sp.csr_matrix, F: ComplexArray, omega: FloatArray) -> ComplexArray:
        """``U`` (n_w, n_dofs) for the forces ``F`` (n_w, n_dofs)."""
        if not self.modal:
            terms = None if self.frequency_terms is None else \
                self.frequency_terms[1].reshape(len(omega), -1)
            return self.sweep.solve(C, F, omega, terms)
        if self.frequency_terms is not None:
            return self._modal(C, F, omega)
        return self._foss(C, F, omega)

    def _modal(self, C: sp.csr_matrix, F: ComplexArray, omega: FloatArray) -> ComplexArray:
        """The coupled modal equations solved at each frequency (with radiation tables)."""
        phi, lam = self.phi, self.lam
        Cu = phi.T @ (C @ phi)
        dofs, terms = self.frequency_terms
        rows = [phi[d:d + 6] for d in dofs]  # (6, n_modes) each
        modal_force = F @ phi
        out = np.empty((len(omega), phi.shape[1]), dtype=complex)
        self.pole_gap = np.inf
        for j, w in enumerate(omega):
            Z = np.diag(lam - w * w).astype(complex) + 1j * w * Cu
            for k, row in enumerate(rows):
                Z += row.T @ terms[j, k] @ row
            out[j] = np.linalg.solve(Z, modal_force[j])
        return out @ phi.T

    def _foss(self, C: sp.csr_matrix, F: ComplexArray, omega: FloatArray) -> ComplexArray:
        """Tuah (1982) eq. 5.3.4-5.3.29: Foss's decoupling of the modal equations."""
        phi, lam = self.phi, self.lam
        n = len(lam)
        Cu = phi.T @ (C @ phi)
        eye, zero = np.eye(n), np.zeros((n, n))
        Cq = np.block([[zero, eye], [eye, Cu]])
        Kq = np.block([[-eye, zero], [zero, np.diag(lam)]])
        Omega, theta = sla.eig(Kq, -Cq)  # Omega Cq theta + Kq theta = 0
        # the closest pair of poles (relative): near a critically damped mode two poles
        # meet, the modal terms grow as 1 / gap and cancel, and Foss's sum carries round-off
        # of order eps / gap
        gaps = np.abs(Omega[:, None] - Omega[None, :]) + np.diag(np.full(2 * n, np.inf))
        self.pole_gap = float(gaps.min(initial=np.inf) / max(np.abs(Omega).max(initial=0.0),
                                                             np.finfo(float).tiny))
        chi = theta[n:]
        c_q = np.einsum("ij,ik,kj->j", theta, Cq, theta)
        k_q = np.einsum("ij,ik,kj->j", theta, Kq, theta)
        modal_force = F @ phi  # (n_w, n): Phi^T F per frequency
        r = (modal_force @ chi) / (k_q[None, :] + 1j * omega[:, None] * c_q[None, :])
        return (r @ chi.T) @ phi.T


def solve_stochastic(system: System, settings: StochasticSettings | None = None,
                     statics: StaticResult | None = None) -> StochasticResult:
    """Stochastic response of lines (and bodies) to the random sea of its environment.

    Tuah (1982) sec. 5.2-5.3, steps 1-14 (see the module docstring); with a steady current,
    the linearization about the mean flow and the mean state with the mean drag (module
    docstring, "Current").

    Parameters
    ----------
    system
        The problem; ``environment.waves`` must be ``kind: random``.
    settings
        Method, modes, linearization tolerance, mass model, time-series length.
    statics
        The equilibrium to linearize about (solved when not given); with a current, the
        start of the mean-state iteration (re-solved with the current's drag).

    Returns
    -------
    StochasticResult
        ``success`` False (status ``failed``, the last iterate) when the drag linearization
        (or, with a current, the mean-state iteration) does not converge in
        ``settings.max_iterations``.

    Raises
    ------
    MoorlineError
        Without a random sea.
    ConvergenceError
        When the statics fails.
    """
    refuse_unlinearized(system, "stochastic")
    settings = settings or StochasticSettings()
    env = system.environment
    if env.waves.kind != "random" or env.waves.height <= 0:
        raise MoorlineError(f"stochastic analysis of {system.name} needs a random sea "
                            "(environment.waves: {kind: random, height: Hs, period: Tp})")
    if settings.method not in ("foss", "direct"):
        raise MoorlineError(f"stochastic method must be 'foss' or 'direct', not "
                            f"{settings.method!r}")
    current = _current_field(system)
    if current is None:
        statics = equilibrium_for(system, statics, "stochastic analysis")
        lin = _linearize(system, settings, statics, None)
        outer: dict = {}
    else:
        lin, statics, outer = _mean_state(system, settings, statics, current)
    return _result(system, settings, statics, lin, outer)


class _Linearized:
    """The converged (or last) statistical linearization about one static state."""

    def __init__(self, **kw) -> None:
        self.__dict__.update(kw)


def _linearize(system: System, settings: StochasticSettings, statics: StaticResult,
               current) -> _Linearized:
    """Steps 5-13: iterate the drag linearization about ``statics`` (``current``: the
    steady current as a fluid field, or ``None``)."""
    env = system.environment
    mesh = dynamic_mesh(statics.mesh, statics.positions)
    if mesh.n_dofs == 0 and not mesh.body_names:
        raise MoorlineError(f"stochastic analysis of {system.name}: no free node")
    rho = float(mesh.water_density)
    sea = random_sea(env.waves)
    omega, amplitude = sea.complex_amplitudes()
    spectrum = sea.spectrum.density(omega)
    power = spectrum * sea.d_omega  # variance per component

    x0 = statics.positions
    model = _LinearModel(system, statics, settings)
    length, t = element.element_geometry(x0, mesh.elements)
    a, b = mesh.elements[:, 0], mesh.elements[:, 1]
    mid = 0.5 * (x0[a] + x0[b])
    H_v, H_a = kinematics_transfer(mid, omega, env.waves.heading_deg, env.depth, env.gravity)
    n_w = len(omega)
    mid_of = model.midpoint_map()  # element midpoint displacements from the unknowns
    load_of = (2.0 * mid_of.T).tocsr()  # half of an element's load to each of its nodes
    H_v_last = np.ascontiguousarray(H_v.transpose(1, 2, 0))  # (n_el, 3, n_w)
    inertia = load_of @ _apply_blocks(_inertia_blocks(t, mesh, rho),
                                      np.ascontiguousarray(H_a.transpose(1, 2, 0)))
    bodies = model.body_kinematics(omega, current)
    points = _PointWaves(mesh, x0, omega, env, rho, current)
    response = _Response(model.K, model.M, settings, omega, model, sea.spectrum.omega_p)
    _check_table_range(system, model, omega, power)
    lines = _LineDrag(mesh, t, rho, None if current is None
                      else current.kinematics(mid, 0.0)[0])
    plane = np.eye(3) - t[:, :, None] * t[:, None, :]

    def forces(drag: FloatArray, gain_p: FloatArray, gain_b: FloatArray) -> ComplexArray:
        """Generalized forces (n_w, n_u), the transpose of a frequency-last array."""
        per_node = _apply_blocks(drag * (0.5 * mesh.length0)[:, None, None], H_v_last)
        return model.forces(points.forces(gain_p), bodies.excitation(gain_b),
                            inertia + load_of @ per_node).T

    v_re, v_im = H_v_last.real.copy(), H_v_last.imag.copy()

    def relative(solution: ComplexArray | None) -> FloatArray:
        """Covariance of the relative velocity ``V - i omega U_mid`` at the midpoints,
        (n_el, 3, 3)."""
        if solution is None:
            return _covariance((v_re, v_im), power)
        u = (mid_of @ solution.T).reshape(-1, 3, n_w) * omega  # omega U_mid
        return _covariance((v_re + u.imag, v_im - u.real), power)

    def sigmas(cov: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        """The normal plane's covariance and the normal and tangential sigmas."""
        cov_n = plane @ cov @ plane
        var_t = np.einsum("ei,eij,ej->e", t, cov, t)
        return (cov_n, np.sqrt(np.maximum(np.trace(cov_n, axis1=1, axis2=2), 0.0)),
                np.sqrt(np.maximum(var_t, 0.0)))

    U = np.zeros((n_w, mesh.n_nodes, 3), dtype=complex)
    X = np.zeros((n_w, len(model.body_dof), 6), dtype=complex)
    cov_n, sigma_n, sigma_t = sigmas(relative(None))  # step 5: the structure at rest
    sigma_b = bodies.sigmas(X, power)
    sigma_p = points.sigmas(U, power)
    history: list[float] = []
    converged = False
    for _ in range(settings.max_iterations):
        drag, _ = lines.linearize(cov_n, sigma_n, sigma_t)
        gain_p, _ = points.gains(U, power, sigma_p)
        gain_b, _ = bodies.gains(sigma_b)
        C = model.damping(_node_pairs(drag * (0.25 * mesh.length0)[:, None, None]), gain_b,
                          points.damping_blocks(gain_p))
        solution = response.solve(C, forces(drag, gain_p, gain_b), omega)
        if points.nodes.size or len(model.body_dof):
            U, X = model.split(solution)
        cov_n, new_n, new_t = sigmas(relative(solution))
        new_b, new_p = bodies.sigmas(X, power), points.sigmas(U, power)
        change = max(_relative_change(new_n, sigma_n), _relative_change(new_t, sigma_t),
                     _relative_change(new_b, sigma_b), _relative_change(new_p, sigma_p))
        history.append(change)
        sigma_n, sigma_t, sigma_b, sigma_p = new_n, new_t, new_b, new_p
        if change <= settings.tolerance:
            converged = True
            break
    if history:
        U, X = model.split(solution)
    increment = np.zeros((mesh.n_nodes, 3))
    body_increment = np.zeros((len(mesh.body_names), 3))
    if current is not None:  # the mean drag minus the current's steady drag, at the nodes
        _, per_length = lines.linearize(cov_n, sigma_n, sigma_t)
        share = per_length * (0.5 * mesh.length0)[:, None]
        np.add.at(increment, a, share)
        np.add.at(increment, b, share)
        if points.nodes.size:
            increment[points.nodes] += points.gains(U, power, sigma_p)[1]
        free = [mesh.body_names.index(b.name) for b in model.bodies]
        body_increment[free] = bodies.gains(sigma_b)[1]
    return _Linearized(mesh=mesh, sea=sea, omega=omega, amplitude=amplitude,
                       spectrum=spectrum, power=power, model=model, response=response,
                       length=length, t=t, U=U, X=X, sigma_n=sigma_n, sigma_t=sigma_t,
                       history=history, converged=converged, increment=increment,
                       body_increment=body_increment)


class _LineDrag:
    """Linearized line drag per unit length (n_elements, 3, 3): without current Tuah's
    ``B_DL (I - t t^T) + B_DT t t^T`` (eq. 5.2.1-5.2.2); with the current's mean relative
    velocity ``W`` (normal) and ``s_bar`` (tangential) at the midpoints,
    ``c_n G_n + 2 c_t E|s| t t^T`` and the mean drag ``c_n E[|w| w] + c_t E[s|s|] t``
    (:mod:`moorline.solvers.drag_linearization`), ``c_n = rho C_D D / 2``,
    ``c_t = rho C_T pi D / 2``."""

    def __init__(self, mesh: Mesh, t: FloatArray, rho: float,
                 current_mid: FloatArray | None) -> None:
        self.mesh, self.t, self.rho = mesh, t, rho
        self.mean = current_mid
        if current_mid is not None:
            self.c_n = 0.5 * rho * mesh.Cd * mesh.diameter
            self.c_t = 0.5 * rho * mesh.Ct * math.pi * mesh.diameter
            self.s_bar = np.einsum("ei,ei->e", current_mid, t)
            self.W = current_mid - self.s_bar[:, None] * t
            self.plane = np.eye(3) - t[:, :, None] * t[:, None, :]

    def linearize(self, cov: FloatArray, sigma_n: FloatArray,
                  sigma_t: FloatArray) -> tuple[FloatArray, FloatArray]:
        """Drag blocks (n_el, 3, 3) and the mean drag minus the steady current's drag per
        unit length (n_el, 3) (zeros without current), from the covariance of the normal
        relative velocity ``cov`` (n_el, 3, 3) and the normal and tangential sigmas."""
        t = self.t
        if self.mean is None:
            return _drag_blocks(t, self.mesh, self.rho, sigma_n, sigma_t), np.zeros_like(t)
        e_f, gain = drag_linearization.vector_expectations(self.W, cov, self.plane)
        e_s, e_abs = drag_linearization.scalar_expectations(self.s_bar, sigma_t)
        tt = t[:, :, None] * t[:, None, :]
        blocks = self.c_n[:, None, None] * gain + (2.0 * self.c_t * e_abs)[:, None, None] * tt
        steady_n = np.linalg.norm(self.W, axis=1)[:, None] * self.W
        steady_t = np.abs(self.s_bar) * self.s_bar
        mean = self.c_n[:, None] * (e_f - steady_n) + (self.c_t * (e_s - steady_t))[:, None] * t
        return blocks, mean


def _mean_state(system: System, settings: StochasticSettings, statics: StaticResult | None,
                current) -> tuple[_Linearized, StaticResult, dict]:
    """With a current: the static state with the current's drag, the linearization about
    it, and the statics re-solved with the mean drag's excess over the current's steady
    drag as node loads, until the mean positions change by less than ``tolerance`` times
    the largest displacement standard deviation (module docstring, "Current")."""
    static_settings = replace(system.first(StaticsSettings), current_drag=True)
    mesh0 = statics.mesh if statics is not None else discretize(system)
    base = mesh0.node_force

    def solve(extra: FloatArray, extra_bodies: FloatArray | None,
              start: FloatArray | None) -> StaticResult:
        mesh = replace(mesh0, node_force=base + extra)
        st = equilibrium_for(system, solve_statics(system, static_settings, start, mesh,
                                                   extra_bodies), "stochastic analysis")
        return st

    start = None if statics is None else statics.positions
    state = solve(np.zeros_like(base), None, start)
    current_only = state.positions
    lin = _linearize(system, settings, state, current)
    iterations, change, ok = 0, math.inf, False
    while lin.converged and iterations < settings.max_iterations:
        iterations += 1
        new = solve(lin.increment, lin.body_increment if len(mesh0.body_names) else None,
                    state.positions)
        std = np.sqrt(np.einsum("w,wnc->nc", lin.power, np.abs(lin.U) ** 2))
        body_std = np.sqrt(np.einsum("w,wbc->bc", lin.power, np.abs(lin.X[..., :3]) ** 2))
        scale = max(float(std.max(initial=0.0)), float(body_std.max(initial=0.0)), 1e-12)
        moved = np.abs(new.body_pose[:, :3] - state.body_pose[:, :3]).max(initial=0.0) \
            if len(mesh0.body_names) else 0.0
        change = max(float(np.abs(new.positions - state.positions).max(initial=0.0)),
                     float(moved)) / scale
        state = new
        lin = _linearize(system, settings, state, current)
        if not lin.converged:  # no consistent linearization about this state: stop
            break
        if change <= settings.tolerance:
            ok = True
            break
    state = replace(state, mesh=replace(state.mesh, node_force=base))
    lin.mesh = replace(lin.mesh, node_force=base)
    offset = float(np.abs(state.positions - current_only).max(initial=0.0))
    return lin, state, {"mean_state_iterations": iterations, "mean_state_converged": ok,
                        "mean_state_change": change, "mean_drag_offset": offset}


def _result(system: System, settings: StochasticSettings, statics: StaticResult,
            lin: _Linearized, outer: dict) -> StochasticResult:
    """Step 14 and the result: standard deviations, tension transfer and time series."""
    mesh, omega, power, U, X = lin.mesh, lin.omega, lin.power, lin.U, lin.X
    history, response, model, sea = lin.history, lin.response, lin.model, lin.sea
    converged = lin.converged and outer.get("mean_state_converged", True)
    message = (f"{len(history)} linearization iterations, {len(omega)} frequencies "
               f"({settings.method})")
    if outer:
        message += (f"; mean state with the current's and the waves' mean drag: "
                    f"{outer['mean_state_iterations']} statics")
    if not lin.converged:
        message = (f"stochastic analysis of {system.name}: the drag linearization did not "
                   f"converge in {settings.max_iterations} iterations (last change "
                   f"{history[-1]:.3g})"
                   + (f" about the mean state of statics {outer['mean_state_iterations']}"
                      if outer else "") + "; the last iterate is returned")
    elif not converged:
        message = (f"stochastic analysis of {system.name}: the mean state with the mean drag "
                   f"did not converge in {settings.max_iterations} statics (last change "
                   f"{outer['mean_state_change']:.3g} of the response std)")
    a, b = mesh.elements[:, 0], mesh.elements[:, 1]
    _, dT = element.axial_tension(lin.length, mesh.length0, mesh.EA, mesh.slack_ratio,
                                  mesh.slack_smoothing, **mesh.axial_law)
    # the elastic and the dashpot's tension per elongation (i omega BA share / L0)
    H_T = (dT[None] + 1j * omega[:, None] * model.dashpot[None]) \
        * np.einsum("wei,ei->we", U[:, b] - U[:, a], lin.t)
    u_std = np.sqrt(np.einsum("w,wnc->nc", power, np.abs(U) ** 2))
    T_std = np.sqrt(np.einsum("w,we->e", power, np.abs(H_T) ** 2))

    n_points = settings.n_points or 1 << int(math.ceil(math.log2(4 * len(omega) + 1)))
    if n_points <= 2 * len(omega):
        raise MoorlineError(f"stochastic analysis: n_points = {n_points} must exceed twice the "
                            f"{len(omega)} frequencies")

    def series(H: ComplexArray) -> FloatArray:
        c = np.zeros((n_points // 2 + 1,) + H.shape[1:], dtype=complex)
        c[1:len(omega) + 1] = H * lin.amplitude.reshape((-1,) + (1,) * (H.ndim - 1))
        return np.fft.irfft(c, n=n_points, axis=0) * n_points

    time = sea.record_length * np.arange(n_points) / n_points
    counters = {"frequencies": len(omega), "dofs": model.K.shape[0],
                "modes": len(response.lam) if response.modal else 0,
                **({"pole_gap": getattr(response, "pole_gap", np.inf)} if response.modal
                   else {"band": response.sweep.bw,
                         "pivoted_frequencies": response.sweep.refactored})}
    if outer:
        counters.update(mean_state_iterations=outer["mean_state_iterations"],
                        mean_drag_offset=outer["mean_drag_offset"])
    return StochasticResult(
        omega=omega, wave_spectrum=lin.spectrum, wave_amplitude=lin.amplitude,
        displacement_transfer=U, tension_transfer=H_T, displacement_std=u_std,
        tension_std=T_std, sigma_normal=lin.sigma_n, sigma_tangential=lin.sigma_t,
        iterations=len(history), history=history, time=time,
        elevation=series(np.ones(len(omega), dtype=complex)),
        displacement=series(U), tension=np.asarray(statics.tension, float)[None] + series(H_T),
        mesh=mesh, settings=settings, d_omega=sea.d_omega,
        body_names=tuple(b.name for b in model.bodies), body_transfer=X,
        body_std=np.sqrt(np.einsum("w,wbc->bc", power, np.abs(X) ** 2)),
        body_motion=series(X), counters=counters,
        success=converged, message=message, case=system.name, units=system.units)


def _check_table_range(system: System, model: _LinearModel, omega: FloatArray,
                       power: FloatArray) -> None:
    """Warn when more than 1 % of the sea's variance lies outside a body's radiation table
    (where ``A`` and ``B`` are held at the table's end values)."""
    total = float(power.sum()) or 1.0
    for d, table in model.radiation:
        outside = (omega < table.omegas[0]) | (omega > table.omegas[-1])
        share = float(power[outside].sum()) / total
        if share > 0.01:
            name = next(b.name for b, dof in zip(model.bodies, model.body_dof, strict=True)
                        if dof == d)
            logger.warning("stochastic analysis of %s: %.1f %% of the sea's variance is outside "
                           "body %s's radiation table (%.3g to %.3g rad/s), where its added "
                           "mass and damping are held at the table's end values", system.name,
                           100 * share, name, table.omegas[0], table.omegas[-1])


def _relative_change(new: FloatArray, old: FloatArray) -> float:
    """Largest ``|new - old| / new`` (entries below 1e-9 of the largest are compared with
    that floor)."""
    floor = 1e-9 * float(np.max(new, initial=0.0)) or 1e-300
    return float(np.max(np.abs(new - old) / np.maximum(new, floor), initial=0.0))


__all__ = ["StochasticResult", "StochasticSettings", "solve_stochastic"]
