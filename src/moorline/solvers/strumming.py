"""Cable strumming: transverse response to vortex-shedding lift by mode superposition.

Tuah (1982) sec. 3.2.b, steps 1-11 and eq. 3.2.b.1-3.2.b.10. The strumming motion is small
and fast compared with the in-line motion, so it is computed separately, as a fluctuation
about the in-line state:

1. the strumming step is ``delta t = Delta t / substeps``, ``Delta t`` the in-line step;
2. at the start ``t1`` of every in-line step, from the in-line state (node positions and
   velocities) and the fluid velocity at the element midpoints: the relative normal velocity
   ``V_NR`` (eq. 3.2.a.3), the shedding frequency ``w_s = 2 pi S_T |V_NR| / D`` (eq.
   3.2.b.4), the wake parameters ``G, H, F`` (eq. 3.2.b.5-6), the lift direction
   ``theta x V_NR`` (eq. 3.2.b.1) -- all held over the in-line step;
3. and 4. every ``refresh_every`` in-line steps (only once when 0): mass and tangent
   stiffness at the in-line state (:func:`moorline.solvers.modal.modal_matrices`; with bodies
   those of lines and bodies together, :func:`moorline.solvers.modal.body_modal_matrices`)
   and the lowest ``n_modes`` natural frequencies and mass-normalized modes (all when 0); the
   strumming state is carried over by projection, ``z = Phi^T M u``, ``z' = Phi^T M u'``
   (exact with all modes);
5. to 8. the wake oscillators (one per element, eq. 3.2.b.3) and the modal equations
   ``z_n'' + 2 xi_n w_n z_n' + w_n^2 z_n = phi_n . F_L`` (eq. 3.2.b.7, 3.2.b.9 with
   ``phi^T M phi = 1``) are integrated together by the classical fourth-order Runge-Kutta
   method with the step ``delta t``; the strumming velocity of an element along its lift
   direction, ``U_T' = e_L . (u_1' + u_2') / 2`` with ``u' = Phi z'`` (eq. 3.2.b.10.b), drives
   its wake oscillator, and the lift ``1/2 rho D C_L |V_NR|^2 L0 e_L``, half to each node,
   drives the modes;
9. to 11. until the end of the in-line step, then the next in-line step.

The modal damping is the viscous fluid damping of eq. 3.2.b.8,
``xi_n = 12 rho D / (pi m) (nu / w_n)^(1/2)``, ``m`` the structural plus added mass per length
(for lines of several types, ``rho D / m`` averaged with the weights of the mode's kinetic
energy per element). Lock-in to the natural frequency nearest the shedding frequency is not
imposed: it arises from the coupled equations, the mode nearest ``w_s`` responding most.

Coupling to the in-line dynamics (one way, as in the source): the in-line state is either
the output of :func:`moorline.solvers.dynamics.simulate` (each output interval is an in-line
step, its positions and velocities give ``V_NR``), or a steady state (a
:class:`~moorline.results.StaticResult`: positions held, velocity zero) for a taut line in
steady flow. The strumming does not feed back into the in-line motion (Tuah neither includes
the drag amplification by strumming, sec. 7). For a line in a steady current, the drag
equilibrium is the statics with ``current_drag`` (or the steady end of an in-line dynamics).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from dataclasses import replace as dataclass_replace

import numpy as np
from numpy.typing import NDArray

from ..errors import MoorlineError
from ..mesh import Mesh, with_loads_of
from ..model import ModalSettings, StrummingSettings, System
from ..physics import hydro, wake
from ..results import DynamicResult, StaticResult, StrummingResult
from .assembly import BlockPattern
from .linearized_laws import refuse_unlinearized
from .modal import BODY_DOFS, _eigen, body_mode_shapes, system_matrices

FloatArray = NDArray[np.float64]


@dataclass
class _Modes:
    lam: FloatArray          # (n_modes,) w_n^2, signed
    omega: FloatArray        # (n_modes,) sign(w_n^2) |w_n|
    phi: FloatArray          # over the unknowns (n_unknowns, n_modes)
    shapes: FloatArray       # (n_modes, n_nodes, 3)
    M: object                # mass matrix over the unknowns
    xi: FloatArray           # (n_modes,) eq. 3.2.b.8 at |w_n|
    two_xi_w: FloatArray     # (n_modes,) 2 xi_n |w_n|


@dataclass(frozen=True)
class _Coupling:
    """Coefficients of the coupled modal and wake equations, frozen over one in-line step.

    ``U_T' = B z'`` (element strumming velocity along its lift direction) and the modal lift
    ``B^T (c C_L)`` with ``c = 1/2 rho D |V_NR|^2 L0`` (Tuah (1982) eq. 3.2.b.1, 3.2.b.9,
    3.2.b.10.b)."""

    B: FloatArray            # (n_elements, n_modes)
    c: FloatArray            # (n_elements,)
    two_xi_w: FloatArray     # (n_modes,) or a full modal damping matrix (n_modes, n_modes)
    w2: FloatArray           # (n_modes,)
    ws: FloatArray           # (n_elements,), 1 where inactive
    G: FloatArray
    H: FloatArray
    F: FloatArray
    CL0: float
    D: FloatArray
    active: NDArray[np.bool_]
    rectify: bool = False

    def rhs(self, state: tuple[FloatArray, ...]) -> tuple[FloatArray, ...]:
        """Time derivative of ``(z, z', C_L, C_L')`` (eq. 3.2.b.3 and 3.2.b.7)."""
        z, zd, cl, cld = state
        damping = (self.two_xi_w @ zd if self.two_xi_w.ndim == 2 else self.two_xi_w * zd)
        zdd = self.B.T @ (self.c * cl) - damping - self.w2 * z
        u_t = self.B @ zd
        cldd = wake.wake_acceleration(cl, cld, self.ws, self.G, self.H, self.F, self.CL0,
                                      np.abs(u_t) if self.rectify else u_t, self.D)
        return zd, zdd, cld, np.where(self.active, cldd, 0.0)

    def rk4(self, state: tuple[FloatArray, ...], h: float) -> tuple[FloatArray, ...]:
        """One classical fourth-order Runge-Kutta step of length ``h``."""
        k1 = self.rhs(state)
        k2 = self.rhs(tuple(s + 0.5 * h * d for s, d in zip(state, k1, strict=True)))
        k3 = self.rhs(tuple(s + 0.5 * h * d for s, d in zip(state, k2, strict=True)))
        k4 = self.rhs(tuple(s + h * d for s, d in zip(state, k3, strict=True)))
        return tuple(s + h / 6.0 * (d1 + 2.0 * d2 + 2.0 * d3 + d4)
                     for s, d1, d2, d3, d4 in zip(state, k1, k2, k3, k4, strict=True))


def _in_line_states(inline: StaticResult | DynamicResult, settings: StrummingSettings,
                    start_time: float) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """In-line step times (n_t,), positions and velocities (n_t, n_nodes, 3), body poses
    (n_t, n_bodies, 6)."""
    if isinstance(inline, DynamicResult):
        keep = inline.time >= start_time - 1e-9 * max(1.0, abs(start_time))
        t = inline.time[keep]
        if len(t) < 2:
            raise MoorlineError("strumming: the in-line history has fewer than two steps "
                                f"after t = {start_time}")
        pose = inline.body_pose[keep] if inline.body_pose.size else \
            np.zeros((len(t), 0, 6))
        return t, inline.positions[keep], inline.velocities[keep], pose
    if settings.duration <= 0 or settings.dt <= 0:
        raise MoorlineError("strumming about a steady in-line state needs duration > 0 and "
                            "dt > 0")
    n = int(round(settings.duration / settings.dt))
    t = start_time + settings.dt * np.arange(n + 1)
    x = np.broadcast_to(inline.positions, (n + 1, *inline.positions.shape))
    pose = np.asarray(inline.body_pose, float).reshape(-1, 6)
    return t, x, np.zeros_like(x), np.broadcast_to(pose, (n + 1, *pose.shape))


def _element_mass(mesh: Mesh, rho: float) -> FloatArray:
    """Structural plus added mass per unstretched length ``m`` of every element."""
    return mesh.mass_per_length + rho * mesh.Ca * math.pi * mesh.diameter**2 / 4.0


class _ModeSource:
    """Steps 3-4 of Tuah (1982) sec. 3.2.b: mass, tangent stiffness, natural frequencies and
    mass-normalized modes at an in-line state, of the lines alone
    (:func:`moorline.solvers.modal.modal_matrices`) or of lines and rigid bodies together
    (:func:`moorline.solvers.modal.body_modal_matrices`: a body's modal displacement moves
    its fairlead nodes rigidly), with the damping of eq. 3.2.b.8."""

    def __init__(self, system: System, mesh: Mesh, settings: StrummingSettings,
                 rho: float) -> None:
        from .coupled_statics import CoupledStatics

        self.system, self.mesh, self.settings, self.rho = system, mesh, settings, rho
        self.problem = CoupledStatics(mesh)
        self.modal = ModalSettings(n_modes=max(settings.n_modes, 1), mass=settings.mass,
                                   added_mass=settings.added_mass)
        # eq. 3.2.b.8 with rho D / m averaged over the elements, weighted per mode by its
        # kinetic energy per element
        self.m = _element_mass(mesh, rho)
        self.a, self.b = mesh.elements[:, 0], mesh.elements[:, 1]
        self.pattern = BlockPattern(mesh.pattern_pairs, mesh.dof_of_node)
        self.P = None
        self.keep = None
        if settings.held_body_dofs:
            unknown = {name: i for i, name in enumerate(BODY_DOFS)}
            bad = [d for d in settings.held_body_dofs if d not in unknown]
            if bad:
                raise MoorlineError(f"strumming: held_body_dofs {bad} not among {BODY_DOFS}")
            held = [int(d0) + unknown[d] for d0 in self.problem.body_dof if d0 >= 0
                    for d in settings.held_body_dofs]
            self.keep = np.setdiff1d(np.arange(self.problem.n_unknowns), held)

    def at(self, x: FloatArray, pose: FloatArray, time: float) -> _Modes:
        """Modes at node positions ``x`` and body poses ``pose`` (in-line time ``time``)."""
        mesh, settings = self.mesh, self.settings
        K, M, P, _ = system_matrices(mesh, x, pose, self.modal, self.problem,
                                     settings.taut_axial)
        if self.keep is not None:
            K, M, P = K[self.keep][:, self.keep], M[self.keep][:, self.keep], P[:, self.keep]
        self.P = P
        n = K.shape[0]
        k = n if settings.n_modes <= 0 else min(settings.n_modes, n)
        lam, phi, _ = _eigen(K, M, dataclass_replace(self.modal, n_modes=k))
        lam, phi = lam[:k], phi[:, :k]
        if np.any(lam <= 0) and settings.nonpositive_modes == "error":
            raise MoorlineError(
                f"strumming: {int(np.sum(lam <= 0))} non-positive eigenvalue(s) at the "
                f"in-line state of t = {time:g} (lowest w^2 = {lam.min():.4g}: a slack line, "
                "a mechanism or an unstable state); set nonpositive_modes: keep to integrate "
                "such modes as they are")
        shapes = body_mode_shapes(phi, P, self.problem, mesh)
        w_abs = np.maximum(np.sqrt(np.abs(lam)), 1e-12)
        a, b, m = self.a, self.b, self.m
        energy = (mesh.length0 * m)[None] * ((shapes[:, a] ** 2).sum(-1)
                                             + (shapes[:, b] ** 2).sum(-1))
        energy /= np.maximum(energy.sum(axis=1, keepdims=True), np.finfo(float).tiny)
        xi = wake.modal_damping_ratio(w_abs, energy @ (mesh.diameter / m), 1.0, self.rho,
                                      settings.viscosity)
        return _Modes(lam, np.sign(lam) * np.sqrt(np.abs(lam)), phi, shapes, M, xi,
                      2.0 * xi * w_abs)

    def drag_damping(self, x: FloatArray, v: FloatArray, fluid_mid: FloatArray,
                     phi: FloatArray) -> FloatArray:
        """Modal drag damping ``phi^T C phi`` (n_modes, n_modes), ``C = -dF_drag/dv`` at the
        in-line state (Tuah (1982) eq. 3.2.a.6, exact), through the body transformation of
        the last :meth:`at` when there are bodies."""
        mesh = self.mesh
        _, dF_dv, _ = hydro.drag_forces(x, v, fluid_mid, mesh.elements, mesh.length0,
                                        mesh.diameter, mesh.Cd, mesh.Ct, self.rho)
        C = self.P.T @ (self.problem.pattern.assemble(-dF_dv) @ self.P)
        return phi.T @ (C @ phi)


def solve_strumming(system: System, settings: StrummingSettings,
                    inline: StaticResult | DynamicResult, fluid=None,
                    start_time: float | None = None,
                    end_time: float | None = None) -> StrummingResult:
    """Transverse strumming response by mode superposition with wake oscillators.

    Tuah (1982) sec. 3.2.b, steps 1-11 (see the module docstring). Lines alone, or lines with
    rigid bodies (the modes are then those of the coupled system, Tuah sec. 6.7).

    Parameters
    ----------
    system
        The problem (its environment gives the fluid density and, by default, the current).
    settings
        Strouhal number, ``C_L0``, viscosity, modes, Runge-Kutta substeps, refresh interval.
    inline
        The in-line state: the output of :func:`~moorline.solvers.dynamics.simulate` (its
        output interval is the in-line step), or a steady state.
    fluid
        Fluid kinematics (``kinematics(points, t)``); default from the environment (with the
        in-line run's current and wave ramp).
    start_time, end_time
        Start and end of the strumming analysis (default: the in-line history's; 0 and the
        settings' ``duration`` when steady).

    Returns
    -------
    StrummingResult
        Lift coefficients, modal amplitudes and strumming displacements at the in-line
        steps.

    Raises
    ------
    MoorlineError
        Without fluid, without an in-line history, or at a slack state (unless
        ``nonpositive_modes`` is ``keep``).
    """
    refuse_unlinearized(system, "strumming")
    from ..waves import fluid_field_from_environment

    mesh = with_loads_of(inline.mesh, system)
    rho = float(mesh.water_density)
    if rho <= 0:
        raise MoorlineError("strumming needs a fluid (water_density > 0)")
    if settings.substeps < 1 or settings.n_modes < 0 or settings.viscosity <= 0:
        raise MoorlineError("strumming: substeps must be >= 1, n_modes >= 0 (0: all), "
                            "viscosity > 0")
    if settings.transverse_velocity not in ("signed", "magnitude"):
        raise MoorlineError("strumming: transverse_velocity must be 'signed' or 'magnitude', "
                            f"not {settings.transverse_velocity!r}")
    if settings.nonpositive_modes not in ("error", "keep"):
        raise MoorlineError("strumming: nonpositive_modes must be 'error' or 'keep', not "
                            f"{settings.nonpositive_modes!r}")
    if fluid is None:
        ramp = inline.settings.get("ramp_time", 0.0) if isinstance(inline, DynamicResult) \
            else 0.0
        fluid = fluid_field_from_environment(system.environment, ramp_time=ramp)
    if start_time is None:
        start_time = float(inline.time[0]) if isinstance(inline, DynamicResult) else 0.0
    times, X, Vel, poses = _in_line_states(inline, settings, start_time)
    if end_time is not None:
        n_t = max(int(np.searchsorted(times, end_time + 1e-9 * max(1.0, abs(end_time)),
                                      side="right")), 2)
        times, X, Vel, poses = times[:n_t], X[:n_t], Vel[:n_t], poses[:n_t]
    n_t, n_el = len(times), mesh.n_elements
    elements, L0, D = mesh.elements, mesh.length0, mesh.diameter
    a, b = elements[:, 0], elements[:, 1]
    D_safe = np.where(D > 0, D, 1.0)
    m_el = _element_mass(mesh, rho)
    CL0 = settings.CL0

    source = _ModeSource(system, mesh, settings, rho)
    modes = source.at(X[0], poses[0], float(times[0]))
    n_modes = len(modes.omega)
    z, zd = np.zeros(n_modes), np.zeros(n_modes)
    cl = np.full(n_el, settings.initial_CL if settings.initial_CL is not None else CL0)
    cld = np.zeros(n_el)

    out = {k: np.zeros((n_t, n_el)) for k in ("cl", "cld", "ws", "speed")}
    out_z, out_zd = np.zeros((n_t, n_modes)), np.zeros((n_t, n_modes))
    disp, vel = np.zeros((n_t, mesh.n_nodes, 3)), np.zeros((n_t, mesh.n_nodes, 3))
    omega_history, refresh_times = [modes.omega.copy()], [times[0]]
    first_params = first_dir = None

    def record(k: int) -> None:
        out["cl"][k], out["cld"][k] = cl, cld
        out_z[k], out_zd[k] = z, zd
        disp[k] = np.einsum("m,mnc->nc", z, modes.shapes)
        vel[k] = np.einsum("m,mnc->nc", zd, modes.shapes)

    record(0)
    evaluations = 0
    for k in range(n_t - 1):
        # step 2: relative velocities, shedding frequencies, wake parameters, lift direction
        mid = 0.5 * (X[k][a] + X[k][b])
        u_fluid = fluid.kinematics(mid, float(times[k]))[0]
        v_nr, tangent = wake.relative_normal_velocity(X[k], Vel[k], u_fluid, elements)
        speed = np.linalg.norm(v_nr, axis=1)
        ws = wake.strouhal_frequency(speed, D, settings.strouhal)
        active = (ws > 0) & (wake.reynolds_number(speed, D, settings.viscosity)
                             >= settings.min_reynolds)
        w_safe = np.where(active, ws, 1.0)
        params = wake.wake_parameters(w_safe, D_safe, m_el, rho, settings.viscosity,
                                      settings.strouhal)
        e_lift = wake.lift_direction(tangent, v_nr)
        if first_params is None:
            first_params, first_dir = params, e_lift
        out["ws"][k], out["speed"][k] = np.where(active, ws, 0.0), speed
        # steps 3-4: modes refreshed every k in-line steps (state carried by projection)
        if settings.refresh_every and k > 0 and k % settings.refresh_every == 0:
            u, ud = modes.phi @ z, modes.phi @ zd
            modes = source.at(X[k], poses[k], float(times[k]))
            z = modes.phi.T @ (modes.M @ u)
            zd = modes.phi.T @ (modes.M @ ud)
            omega_history.append(modes.omega.copy())
            refresh_times.append(times[k])
        # coupling matrix: U_T'(element) = B z',  modal lift = B^T (c C_L)
        Bc = 0.5 * np.einsum("mec,ec->em", modes.shapes[:, a] + modes.shapes[:, b], e_lift)
        c = np.where(active, wake.lift_force_per_length(1.0, speed, D, rho) * L0, 0.0)
        damping = modes.two_xi_w
        if settings.drag_damping:
            damping = np.diag(damping) + source.drag_damping(X[k], Vel[k], u_fluid, modes.phi)
        coefficients = _Coupling(Bc, c, damping, modes.lam, w_safe, params.G,
                                 params.H, params.F, CL0, D_safe, active,
                                 settings.transverse_velocity == "magnitude")
        # steps 5-10: RK4 with delta t inside the in-line step
        h = (times[k + 1] - times[k]) / settings.substeps
        for _ in range(settings.substeps):
            z, zd, cl, cld = coefficients.rk4((z, zd, cl, cld), h)
            evaluations += 4
        record(k + 1)
    out["ws"][-1], out["speed"][-1] = out["ws"][-2], out["speed"][-2]
    return StrummingResult(
        time=np.asarray(times, float), lift_coefficient=out["cl"], lift_rate=out["cld"],
        modal_amplitude=out_z, modal_velocity=out_zd, displacement=disp, velocity=vel,
        strouhal_frequency=out["ws"], normal_speed=out["speed"], lift_direction=first_dir,
        omega=modes.omega, mode_shapes=modes.shapes, damping_ratio=modes.xi,
        omega_history=np.array(omega_history), refresh_times=np.array(refresh_times),
        parameters=first_params, mesh=mesh, settings=settings,
        counters={"in_line_steps": n_t - 1, "rk4_steps": (n_t - 1) * settings.substeps,
                  "evaluations": evaluations, "refreshes": len(refresh_times) - 1},
        message=f"{n_t - 1} in-line steps", case=system.name, units=system.units)
