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
   stiffness at the in-line positions (:func:`moorline.solvers.modal.modal_matrices`) and the
   lowest ``n_modes`` natural frequencies and mass-normalized modes; the strumming state is
   carried over by projection, ``z = Phi^T M u``, ``z' = Phi^T M u'``;
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
the drag amplification by strumming, sec. 7). ``moorline``'s statics has no current drag:
for the drag equilibrium, run the in-line dynamics until it is steady and pass that output.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Literal

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from ..errors import MoorlineError
from ..mesh import Mesh
from ..model import ModalMass, ModalSettings, System
from ..physics import wake
from ..results import DynamicResult, StaticResult
from .modal import _eigen, modal_matrices

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class StrummingSettings:
    """Settings of the strumming analysis (Tuah (1982) sec. 3.2.b).

    Attributes
    ----------
    viscosity
        Kinematic viscosity of the fluid ``nu`` [length^2/time] (eq. 3.2.b.6, 3.2.b.8).
    strouhal
        Strouhal number ``S_T`` (eq. 3.2.b.4).
    CL0
        Lift-coefficient amplitude of the stationary cylinder.
    n_modes
        Number of (lowest) modes superposed.
    mass, added_mass
        Mass model of the modal analysis (Tuah uses the consistent mass, eq. 3.1.12) and
        whether the added mass is included.
    substeps
        Runge-Kutta steps per in-line step (``delta t = Delta t / substeps``).
    refresh_every
        In-line steps between recomputations of the modes; 0: modes computed once.
    initial_CL
        Lift coefficient at the start, with ``C_L' = 0`` (default ``CL0``: the shedding of
        the still cable is established, the wake on its stationary limit cycle).
    duration, dt
        Duration and in-line step when the in-line state is steady (a static result).
    transverse_velocity
        ``signed`` (default): the wake oscillator is driven by the strumming velocity along
        the lift direction, ``U_T' = e_L . u'`` (Griffin et al. 1975; this is what
        synchronizes wake and structure). ``magnitude``: by ``|U_T'|``, the literal reading of
        Tuah's "the transverse cable velocity magnitude" (eq. 3.2.b.3), which rectifies the
        forcing and only raises ``C_L`` a little above ``C_L0``.
    """

    viscosity: float
    strouhal: float = wake.DEFAULT_STROUHAL
    CL0: float = 0.2
    n_modes: int = 6
    mass: ModalMass = "consistent"
    added_mass: bool = True
    substeps: int = 1
    refresh_every: int = 0
    initial_CL: float | None = None
    duration: float = 0.0
    dt: float = 0.001
    transverse_velocity: Literal["signed", "magnitude"] = "signed"


@dataclass
class StrummingResult:
    """Histories of a strumming analysis, at the in-line steps.

    Attributes
    ----------
    time
        (n_t,).
    lift_coefficient, lift_rate
        ``C_L`` and ``C_L'`` per element (n_t, n_elements).
    modal_amplitude, modal_velocity
        ``z_n``, ``z_n'`` of the current modes (n_t, n_modes).
    displacement, velocity
        Strumming displacement and velocity of the nodes about the in-line state
        (n_t, n_nodes, 3), eq. 3.2.b.10.
    strouhal_frequency, normal_speed
        ``w_s`` and ``|V_NR|`` per element (n_t, n_elements), at the start of each in-line
        step (the last row repeats the one before).
    lift_direction
        Unit lift direction per element at the start (n_elements, 3).
    omega, mode_shapes, damping_ratio
        The last modes: frequencies (n_modes,), mass-normalized shapes (n_modes, n_nodes,
        3), eq. 3.2.b.8 damping ratios (n_modes,).
    omega_history, refresh_times
        Frequencies at every refresh (n_refresh, n_modes) and when.
    parameters
        Wake parameters per element at the start (:class:`~moorline.physics.wake.
        WakeParameters`).
    mesh, settings
        What was solved.
    """

    time: FloatArray
    lift_coefficient: FloatArray
    lift_rate: FloatArray
    modal_amplitude: FloatArray
    modal_velocity: FloatArray
    displacement: FloatArray
    velocity: FloatArray
    strouhal_frequency: FloatArray
    normal_speed: FloatArray
    lift_direction: FloatArray
    omega: FloatArray
    mode_shapes: FloatArray
    damping_ratio: FloatArray
    omega_history: FloatArray
    refresh_times: FloatArray
    parameters: wake.WakeParameters
    mesh: Mesh
    settings: StrummingSettings
    counters: dict = field(default_factory=dict)

    def node_displacement(self, node: int) -> FloatArray:
        """Strumming displacement history of one node (n_t, 3)."""
        return self.displacement[:, node]

    def to_xarray(self) -> xr.Dataset:
        """The histories as an :class:`xarray.Dataset`.

        Returns
        -------
        xarray.Dataset
            ``lift_coefficient`` (time, element), ``modal_amplitude`` (time, mode),
            ``displacement`` (time, node, xyz: the transverse strumming displacement),
            ``strouhal_frequency`` and ``normal_speed`` (time, element), ``omega`` and
            ``damping_ratio`` (mode); attribute ``CL0``.
        """
        return xr.Dataset(
            {"lift_coefficient": (("time", "element"), self.lift_coefficient),
             "modal_amplitude": (("time", "mode"), self.modal_amplitude),
             "displacement": (("time", "node", "xyz"), self.displacement),
             "strouhal_frequency": (("time", "element"), self.strouhal_frequency),
             "normal_speed": (("time", "element"), self.normal_speed),
             "omega": (("mode",), self.omega),
             "damping_ratio": (("mode",), self.damping_ratio)},
            coords={"time": self.time, "element": np.arange(self.mesh.n_elements),
                    "node": np.arange(self.mesh.n_nodes),
                    "mode": np.arange(len(self.omega)), "xyz": ["x", "y", "z"]},
            attrs={"kind": "strumming", "CL0": self.settings.CL0,
                   "strouhal": self.settings.strouhal})


@dataclass
class _Modes:
    omega: FloatArray        # (n_modes,)
    phi: FloatArray          # free dofs (n_dofs, n_modes)
    shapes: FloatArray       # (n_modes, n_nodes, 3)
    M: object                # mass matrix over the free dofs
    xi: FloatArray           # (n_modes,) eq. 3.2.b.8


@dataclass(frozen=True)
class _Coupling:
    """Coefficients of the coupled modal and wake equations, frozen over one in-line step.

    ``U_T' = B z'`` (element strumming velocity along its lift direction) and the modal lift
    ``B^T (c C_L)`` with ``c = 1/2 rho D |V_NR|^2 L0`` (Tuah (1982) eq. 3.2.b.1, 3.2.b.9,
    3.2.b.10.b)."""

    B: FloatArray            # (n_elements, n_modes)
    c: FloatArray            # (n_elements,)
    two_xi_w: FloatArray     # (n_modes,)
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
        zdd = self.B.T @ (self.c * cl) - self.two_xi_w * zd - self.w2 * z
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
                    start_time: float) -> tuple[FloatArray, FloatArray, FloatArray]:
    """In-line step times (n_t,), positions and velocities (n_t, n_nodes, 3)."""
    if isinstance(inline, DynamicResult):
        keep = inline.time >= start_time - 1e-9 * max(1.0, abs(start_time))
        t = inline.time[keep]
        if len(t) < 2:
            raise MoorlineError("strumming: the in-line history has fewer than two steps "
                                f"after t = {start_time}")
        return t, inline.positions[keep], inline.velocities[keep]
    if settings.duration <= 0 or settings.dt <= 0:
        raise MoorlineError("strumming about a steady in-line state needs duration > 0 and "
                            "dt > 0")
    n = int(round(settings.duration / settings.dt))
    t = start_time + settings.dt * np.arange(n + 1)
    x = np.broadcast_to(inline.positions, (n + 1, *inline.positions.shape))
    return t, x, np.zeros_like(x)


def _element_mass(mesh: Mesh, rho: float) -> FloatArray:
    """Structural plus added mass per unstretched length ``m`` of every element."""
    return mesh.mass_per_length + rho * mesh.Ca * math.pi * mesh.diameter**2 / 4.0


def _modes(mesh: Mesh, x: FloatArray, settings: StrummingSettings, rho: float) -> _Modes:
    """Steps 3-4: modes at the in-line positions ``x``, with eq. 3.2.b.8 damping."""
    modal = ModalSettings(n_modes=settings.n_modes, mass=settings.mass,
                          added_mass=settings.added_mass)
    K, M = modal_matrices(mesh, x, modal)
    lam, phi, _ = _eigen(K, M, modal)
    lam, phi = lam[: settings.n_modes], phi[:, : settings.n_modes]
    if np.any(lam <= 0):
        raise MoorlineError("strumming: non-positive eigenvalue at the in-line state (a "
                            "slack or unstable line); strumming needs a taut line")
    omega = np.sqrt(lam)
    shapes = np.zeros((phi.shape[1], mesh.n_nodes, 3))
    mask = mesh.dof_of_node >= 0
    shapes[:, mask] = phi[mesh.dof_of_node[mask]].T
    # eq. 3.2.b.8 with rho D / m weighted by the mode's kinetic energy per element
    m = _element_mass(mesh, rho)
    a, b = mesh.elements[:, 0], mesh.elements[:, 1]
    energy = (mesh.length0 * m)[None] * ((shapes[:, a] ** 2).sum(-1) + (shapes[:, b] ** 2)
                                         .sum(-1))
    energy /= np.maximum(energy.sum(axis=1, keepdims=True), np.finfo(float).tiny)
    coefficient = energy @ (mesh.diameter / m)
    xi = wake.modal_damping_ratio(omega, coefficient, 1.0, rho, settings.viscosity)
    return _Modes(omega, phi, shapes, M, xi)


def solve_strumming(system: System, settings: StrummingSettings,
                    inline: StaticResult | DynamicResult, fluid=None,
                    start_time: float | None = None) -> StrummingResult:
    """Transverse strumming response by mode superposition with wake oscillators.

    Tuah (1982) sec. 3.2.b, steps 1-11 (see the module docstring).

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
        in-line run's current ramp).
    start_time
        Start of the strumming analysis (default: the first in-line time; 0 when steady).

    Returns
    -------
    StrummingResult
        Lift coefficients, modal amplitudes and strumming displacements at the in-line
        steps.

    Raises
    ------
    MoorlineError
        Without fluid, with bodies, without an in-line history, or at a slack state.
    """
    from ..waves import fluid_field_from_environment

    mesh = inline.mesh
    rho = float(mesh.water_density)
    if rho <= 0:
        raise MoorlineError("strumming needs a fluid (water_density > 0)")
    if getattr(mesh, "body_names", ()):
        raise MoorlineError("strumming of systems with bodies is not supported")
    if settings.substeps < 1 or settings.n_modes < 1 or settings.viscosity <= 0:
        raise MoorlineError("strumming: substeps and n_modes must be >= 1, viscosity > 0")
    if settings.transverse_velocity not in ("signed", "magnitude"):
        raise MoorlineError("strumming: transverse_velocity must be 'signed' or 'magnitude', "
                            f"not {settings.transverse_velocity!r}")
    if fluid is None:
        ramp = inline.settings.get("ramp_time", 0.0) if isinstance(inline, DynamicResult) \
            else 0.0
        fluid = fluid_field_from_environment(system.environment, ramp_time=ramp)
    if start_time is None:
        start_time = float(inline.time[0]) if isinstance(inline, DynamicResult) else 0.0
    times, X, Vel = _in_line_states(inline, settings, start_time)
    n_t, n_el = len(times), mesh.n_elements
    elements, L0, D = mesh.elements, mesh.length0, mesh.diameter
    a, b = elements[:, 0], elements[:, 1]
    m_el = _element_mass(mesh, rho)
    CL0 = settings.CL0

    modes = _modes(mesh, X[0], settings, rho)
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
        active = ws > 0
        w_safe = np.where(active, ws, 1.0)
        params = wake.wake_parameters(w_safe, np.where(D > 0, D, 1.0), m_el, rho,
                                      settings.viscosity, settings.strouhal)
        e_lift = wake.lift_direction(tangent, v_nr)
        if first_params is None:
            first_params, first_dir = params, e_lift
        out["ws"][k], out["speed"][k] = ws, speed
        # steps 3-4: modes refreshed every k in-line steps (state carried by projection)
        if settings.refresh_every and k > 0 and k % settings.refresh_every == 0:
            u = modes.phi @ z
            ud = modes.phi @ zd
            modes = _modes(mesh, X[k], settings, rho)
            z = modes.phi.T @ (modes.M @ u)
            zd = modes.phi.T @ (modes.M @ ud)
            omega_history.append(modes.omega.copy())
            refresh_times.append(times[k])
        # coupling matrix: U_T'(element) = B z',  modal lift = B^T (c C_L)
        Bc = 0.5 * np.einsum("mec,ec->em", modes.shapes[:, a] + modes.shapes[:, b], e_lift)
        c = np.where(active, wake.lift_force_per_length(1.0, speed, D, rho) * L0, 0.0)
        D_safe = np.where(D > 0, D, 1.0)
        coefficients = _Coupling(Bc, c, 2.0 * modes.xi * modes.omega, modes.omega**2, w_safe,
                                 params.G, params.H, params.F, CL0, D_safe, active,
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
                  "evaluations": evaluations, "refreshes": len(refresh_times) - 1})
