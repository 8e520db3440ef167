"""Time-domain simulation of a cable system (Tuah 1982, sec. 4.2).

:func:`simulate` starts from a static equilibrium (solved here unless given), then advances
with :class:`~moorline.solvers.newmark.Stepper`. A step that fails to converge is cut in half
(recursively, ``max_step_cuts`` times) with a fresh tangent; if that fails too, a
:class:`~moorline.errors.ConvergenceError` names the time and the line and node with the
largest residual. Output records are kept in memory and, when a writer is given, streamed to
NetCDF as they are produced.
"""

from __future__ import annotations

import logging
from collections.abc import Callable
from dataclasses import asdict

import numpy as np
import scipy.sparse.linalg as spla
from numpy.typing import NDArray

from ..errors import ConvergenceError
from ..mesh import Mesh, discretize
from ..model import DynamicsSettings, StaticsSettings, System
from ..results import DynamicResult, StaticResult
from .assembly import gather_free, scatter_free
from .dynamic_model import DynamicModel, MaterialState
from .equilibrium import StaticModel
from .excitation import Excitation
from .newmark import Coefficients, Stepper, StepState
from .statics import describe_dof, solve_statics

FloatArray = NDArray[np.float64]
logger = logging.getLogger(__name__)


def simulate(
    system: System,
    settings: DynamicsSettings,
    initial: StaticResult | FloatArray | None = None,
    fluid=None,
    output_every: float | None = None,
    writer=None,
    progress: Callable[[float], None] | None = None,
    maxwell: FloatArray | None = None,
) -> DynamicResult:
    """Run a time-domain analysis.

    Parameters
    ----------
    system
        The problem.
    settings
        Time step, duration, scheme and tolerances.
    initial
        Static equilibrium to start from (solved with the system's statics settings if None),
        or node positions (n_nodes, 3) to start from at rest (e.g. a displaced string).
    fluid
        Fluid kinematics (``kinematics(points, t)``); default: built from the environment.
    output_every
        Output interval [time]; default ``system.output.every`` (at least one step).
    writer
        Optional :class:`~moorline.io.stream.HistoryWriter` receiving every record.
    progress
        Called with the current time after every step.
    maxwell
        Initial Maxwell-branch force of viscoelastic elements (n_elements,); default relaxed
        (zero) at the initial positions.
    """
    mesh = initial.mesh if isinstance(initial, StaticResult) else discretize(system)
    if initial is None:
        initial = solve_statics(system, _statics_settings(system), mesh=mesh)
        if not initial.success:
            raise ConvergenceError(f"static equilibrium before dynamics failed: "
                                   f"{initial.message}", time=0.0)
    x0 = initial.positions if isinstance(initial, StaticResult) else np.asarray(initial, float)
    fluid = fluid if fluid is not None else _fluid(
        system, settings, ramp_current=not getattr(initial, "current_drag", False))
    model = DynamicModel(mesh, fluid, settings.viscoelastic_update,
                         system.environment.seabed)
    excitation = Excitation(system, mesh, x0)
    state = _initial_state(model, excitation, x0, settings.dt, maxwell)
    if mesh.body_names:
        state = _with_bodies(state, initial)
    # force scale of the residual tolerance: the larger of the nodal loads and the tensions
    scale = max(float(np.abs(model.external).max(initial=0.0)),
                float(np.abs(state.evaluation.tension).max(initial=0.0)), 1e-12)
    tolerance = max(settings.tolerance * scale, StaticModel(mesh).roundoff_floor(x0))
    stepper = _stepper(model, fluid, settings, tolerance, system)
    every = max(output_every or system.output.every, settings.dt)
    recorder = _Recorder(mesh, writer, fluid)
    recorder.add(state)
    n_steps = int(round(settings.duration / settings.dt))
    next_output, cuts = every, 0
    level, calm = 0, 0  # sub-steps 2**level per output step while Newton struggles
    for k in range(1, n_steps + 1):
        target = k * settings.dt
        h = (target - state.t) / 2**level
        used_cuts = 0
        for i in range(2**level):
            step = target - state.t if i == 2**level - 1 else h
            state, used = _advance(stepper, excitation, state, step,
                                   settings.max_step_cuts - level, mesh)
            used_cuts += used
        cuts += used_cuts
        level, calm = _adapt(level, calm, used_cuts, settings.max_step_cuts)
        if state.t >= next_output - 1e-9 * settings.dt or k == n_steps:
            recorder.add(state)
            next_output += every
        if progress is not None:
            progress(state.t)
    counters = dict(stepper.counters, steps=n_steps, step_cuts=cuts)
    return recorder.result(True, f"completed {n_steps} steps", counters, system,
                           asdict(settings))


def _stepper(model: DynamicModel, fluid, settings: DynamicsSettings, tolerance: float,
             system: System | None = None):
    """The coupled stepper for systems with bodies; else the compiled stepper when the model
    allows it, else the general one."""
    from .fast_newmark import FastStepper, fast_path_reason

    coefficients = Coefficients.for_scheme(settings.scheme, settings.alpha)
    if model.mesh.body_names:
        from .coupled_dynamics import CoupledStepper

        return CoupledStepper(system, model, Coefficients.for_scheme("newmark", 0.0), tolerance,
                              settings.max_iterations, settings.stiffness_update,
                              _rayleigh(settings), settings.variant)
    reason = fast_path_reason(model, fluid, settings.scheme, settings.variant)
    if reason is None and settings.fast_path:
        return FastStepper(model, coefficients, tolerance, settings.max_iterations,
                           settings.stiffness_update)
    logger.info("general stepper (compiled step not used: %s)", reason or "disabled")
    return Stepper(model, coefficients, settings.variant, tolerance, settings.max_iterations,
                   settings.stiffness_update)


def _adapt(level: int, calm: int, used_cuts: int, max_cuts: int) -> tuple[int, int]:
    """Sub-step level for the next step: one level finer after a step that needed cuts (slack
    snaps and touchdowns last several steps; retrying the full step each time wastes the
    failed iterations), one level coarser after ten calm steps."""
    if used_cuts:
        return min(level + 1, max(max_cuts - 1, 0)), 0
    calm += 1
    if level and calm >= 10:
        return level - 1, 0
    return level, calm


def _rayleigh(settings: DynamicsSettings) -> tuple[float, float] | None:
    """(a0, a1) of Rayleigh damping with the settings' ratio at its two frequencies."""
    zeta = settings.rayleigh_ratio
    w1, w2 = settings.rayleigh_frequencies
    if zeta <= 0 or w1 <= 0 or w2 <= 0:
        return None
    return 2 * zeta * w1 * w2 / (w1 + w2), 2 * zeta / (w1 + w2)


def _statics_settings(system: System) -> StaticsSettings:
    return system.first(StaticsSettings)


def _fluid(system: System, settings: DynamicsSettings, ramp_current: bool = True):
    from ..waves import fluid_field_from_environment

    return fluid_field_from_environment(system.environment, ramp_time=settings.ramp_time,
                                        ramp_current=ramp_current)


def _initial_state(model: DynamicModel, excitation: Excitation, x0: FloatArray,
                   dt: float, maxwell: FloatArray | None = None) -> StepState:
    """Start at rest at the static state, with the acceleration the loads give at t = 0."""
    mesh = model.mesh
    x = x0.copy()
    x_c, v_c, a_c = excitation.constrained_state(0.0)
    x[~mesh.free_nodes] = x_c
    v = np.zeros_like(x)
    v[~mesh.free_nodes] = v_c
    a = np.zeros_like(x)
    a[~mesh.free_nodes] = a_c
    material = model.initial_material(x)
    if maxwell is not None:
        material = MaterialState(material.strain, np.asarray(maxwell, dtype=float).copy())
    forces = excitation.point_forces(0.0, mesh.n_nodes)
    ev = model.evaluate(x, v, a, 0.0, material, dt, True, forces)
    mass = ev.node_M if ev.node_M is not None else np.zeros((mesh.n_nodes, 3, 3))
    mass = mass + model.node_mass[:, None, None] * np.eye(3)
    if mesh.n_dofs and not mesh.body_names:  # with bodies: start at rest (static state)
        from .assembly import BlockPattern

        M = BlockPattern(mesh.elements, mesh.dof_of_node).assemble(ev.Ma, mass).tocsc()
        massive = M.diagonal() > 0  # massless nodes (weightless strings) start at a = 0
        if np.any(massive):
            rhs = gather_free(ev.nodal, mesh.dof_of_node)
            a_free = np.zeros(len(rhs))
            a_free[massive] = spla.splu(M[massive][:, massive].tocsc()).solve(rhs[massive])
            a = a + scatter_free(a_free, mesh.dof_of_node)
            ev = model.evaluate(x, v, a, 0.0, material, dt, False, forces)
    return StepState(0.0, x, v, a, ev.material, ev)


def _with_bodies(state: StepState, initial) -> StepState:
    """Bodies at their static poses, at rest."""
    from dataclasses import replace as dc_replace

    from ..mesh import rotation_matrix
    from .coupled_dynamics import BodyState

    pose = initial.body_pose if isinstance(initial, StaticResult) else None
    if pose is None or not len(pose):
        raise ConvergenceError("dynamics of a system with bodies needs its static state")
    R = np.array([rotation_matrix(p[3:]) for p in pose])
    zeros = np.zeros((len(pose), 6))
    return dc_replace(state, a=np.zeros_like(state.a),
                      bodies=BodyState(pose[:, :3].copy(), R, zeros, zeros.copy()))


def _advance(stepper: Stepper, excitation: Excitation, state: StepState, h: float,
             cuts_left: int, mesh: Mesh) -> tuple[StepState, int]:
    """One step of size ``h``, halving it recursively when Newton fails."""
    t1 = state.t + h
    constrained = excitation.constrained_state(t1)
    forces = excitation.point_forces(t1, mesh.n_nodes)
    new, ok, norm = stepper.step(state, h, constrained, forces)
    if ok:
        return new, 0
    if cuts_left == 0:
        where = (None if state.bodies is not None
                 else _worst(stepper, state, h, constrained, forces))
        raise ConvergenceError("Newton iterations did not converge", time=t1, where=where,
                               residual=norm)
    _forget_tangent(stepper)
    half, used1 = _advance(stepper, excitation, state, h / 2, cuts_left - 1, mesh)
    full, used2 = _advance(stepper, excitation, half, h / 2, cuts_left - 1, mesh)
    _forget_tangent(stepper)
    return full, 1 + used1 + used2


def _forget_tangent(stepper) -> None:
    if hasattr(stepper, "lu_valid"):
        stepper.lu_valid = False
    else:
        stepper.lu = None


def _worst(stepper, state: StepState, h: float, constrained, forces) -> str:
    """Where the residual of the predicted state is largest (for the error message)."""
    model = stepper.model
    general = Stepper(model, stepper.c, "iterative", 0.0, 0, 1)
    x1 = state.x + h * state.v + 0.5 * h * h * state.a
    x1[~general.free] = constrained[0]
    v1, a1 = general._kinematics(state, x1, h)
    ev = model.evaluate(x1, v1, a1, state.t + h, state.material, h, False, forces)
    r = general._residual(state, ev, a1)
    return describe_dof(model.mesh, int(np.argmax(np.abs(r))))


class _Recorder:
    """Collects output records (and streams them when a writer is given)."""

    def __init__(self, mesh: Mesh, writer, fluid=None) -> None:
        self.mesh = mesh
        self.writer = writer
        self.fluid = fluid
        self.records: dict[str, list] = {k: [] for k in
                                         ("time", "position", "velocity", "tension",
                                          "end_force", "body_pose", "body_velocity",
                                          "body_mooring_force", "wave_elevation")}

    def add(self, state: StepState) -> None:
        record = {"position": state.x.copy(), "velocity": state.v.copy(),
                  "tension": state.evaluation.tension.copy(),
                  "end_force": _end_forces(self.mesh, state),
                  "body_pose": (state.bodies.pose() if state.bodies is not None
                                else np.zeros((0, 6))),
                  "body_velocity": (state.bodies.vel.copy() if state.bodies is not None
                                    else np.zeros((0, 6))),
                  "body_mooring_force": _mooring_forces(self.mesh, state),
                  "wave_elevation": self._elevation(state.t)}
        self.records["time"].append(state.t)
        for key, value in record.items():
            self.records[key].append(value)
        if self.writer is not None:
            self.writer.append(state.t, record)

    def _elevation(self, t: float) -> float:
        """Free-surface elevation at the origin (x = y = 0) [length]."""
        if self.fluid is None:
            return 0.0
        return float(self.fluid.kinematics(np.zeros((1, 3)), t)[2][0])

    def result(self, ok: bool, message: str, counters: dict, system: System,
               settings: dict) -> DynamicResult:
        arrays = {k: np.array(v) for k, v in self.records.items()}
        return DynamicResult(ok, message, arrays["time"], arrays["position"],
                             arrays["velocity"], arrays["tension"], arrays["end_force"],
                             counters, self.mesh, system.name, system.units, settings,
                             body_pose=arrays["body_pose"],
                             body_velocity=arrays["body_velocity"],
                             body_mooring_force=arrays["body_mooring_force"],
                             wave_elevation=arrays["wave_elevation"])


def _mooring_forces(mesh: Mesh, state: StepState) -> FloatArray:
    """Force and moment (about each body's origin, world axes) the lines exert on every body
    through its attached nodes (n_bodies, 6)."""
    if state.bodies is None:
        return np.zeros((0, 6))
    out = np.zeros((len(mesh.body_names), 6))
    el = mesh.elements
    f = state.evaluation.element_forces
    for k, node in enumerate(mesh.slave_node):
        b = mesh.slave_body[k]
        force = f[el[:, 0] == node, 0].sum(axis=0) + f[el[:, 1] == node, 1].sum(axis=0)
        arm = state.x[node] - state.bodies.r[b]
        out[b, :3] += force
        out[b, 3:] += np.cross(arm, force)
    return out


def _end_forces(mesh: Mesh, state: StepState) -> FloatArray:
    """Force each line exerts on its two end points: the end element's axial force plus half
    its submerged weight (as :meth:`StaticResult.end_force`)."""
    forces = state.evaluation.element_forces
    out = np.empty((len(mesh.line_names), 2, 3))
    for k, elements in enumerate(mesh.line_elements):
        for side, e in ((0, elements[0]), (1, elements[-1])):
            out[k, side] = forces[e, side]
            out[k, side, 2] -= 0.5 * mesh.weight_per_length[e] * mesh.length0[e]
    return out
