"""Time-domain simulation of a cable system (Tuah 1982, sec. 4.2).

:func:`simulate` starts from a static equilibrium (solved here unless given; or, with ``start:
initial``, from the case's body poses with the lines at rest in their static shape), then advances
with :class:`~moorline.solvers.newmark.Stepper` or its compiled backend, whose steps run in
blocks inside one compiled loop (:mod:`moorline.solvers.fast_loop`; the time-dependent inputs
of a block evaluated at once, its records written into preallocated arrays). A step that fails
to converge is cut in half (recursively, ``max_step_cuts`` times) with a fresh tangent, in
Python (the compiled loop stops there and resumes after it); if that fails too, the run ends
and the result says so (``success`` False, the time and the line and node, or body dof, with
the largest residual), holding the histories computed until then. Output records are kept in
memory and, when a writer is given, streamed to NetCDF in blocks as they are produced.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Callable
from dataclasses import asdict

import numpy as np
from numpy.typing import NDArray

from ..errors import ConvergenceError
from ..mesh import Mesh, discretize, dynamic_mesh, with_loads_of
from ..model import DynamicsSettings, StaticsSettings, System
from ..results import DynamicResult, StaticResult
from .bodies import BodyState, body_mass_matrix
from .body_model import BodyModel, with_pins
from .dynamic_model import DynamicModel, MaterialState
from .equilibrium import StaticModel
from .excitation import Excitation
from .newmark import Coefficients, Stepper, StepState, accelerated
from .newton import NewtonPolicy
from .statics import describe_dof, lines_at_rest, solve_statics

FloatArray = NDArray[np.float64]
logger = logging.getLogger(__name__)

COMPILED_LOOP = True
"""Run the steps of the compiled backend in blocks (:class:`_BlockRunner`); False: one step
per call from Python (the same compiled step and results; for tests and profiling)."""


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
        Static equilibrium to start from (if None: solved with the system's statics
        settings, or with ``settings.start == "initial"`` the lines at rest with the bodies
        held at the case's poses, :func:`~moorline.solvers.statics.lines_at_rest`), or node
        positions (n_nodes, 3) to start from at rest (e.g. a displaced string).
    fluid
        Fluid kinematics (``kinematics(points, t)``); default: built from the environment.
    output_every
        Output interval [time]; default ``system.output.every`` (at least one step).
    writer
        Optional :class:`~moorline.io.stream.HistoryWriter` receiving every record.
    progress
        Called with the current time after every step.
    maxwell
        Initial Maxwell-branch force of viscoelastic elements, and static-branch force of
        static-dynamic elements (n_elements,); default relaxed at the initial positions (zero,
        and ``EA eps``).
    """
    mesh, fluid, excitation, state, stepper = start(system, settings, initial, fluid, maxwell)
    every = max(output_every or system.output.every, settings.dt)
    n_steps = int(round(settings.duration / settings.dt))
    recorder = _Recorder(mesh, writer, fluid,
                         initial.tension if isinstance(initial, StaticResult) else None,
                         _expected_records(n_steps, settings.dt, every))
    recorder.add(state)
    loop = _Loop(settings, n_steps, every)
    blocks = _BlockRunner(stepper, excitation, mesh, recorder, loop) \
        if COMPILED_LOOP and hasattr(stepper, "run_block") else None
    cuts, k = 0, 0  # step cuts, full steps done
    resume = None  # where the compiled loop stopped inside a step: (sub-step, h, norm)
    failure: StepFailedError | None = None
    while k < n_steps:
        if blocks is not None and resume is None:
            state, k, resume = blocks.run(state, k)
            if progress is not None:
                progress(state.t)
            if resume is None:
                continue
        # the next step in Python (with its step cuts), or the rest of the step the compiled
        # loop stopped in
        target = (k + 1) * settings.dt
        first, h, norm = resume if resume is not None else (
            0, (target - state.t) / 2**loop.level, None)
        resume = None
        used_cuts = 0
        try:
            for i in range(first, 2**loop.level):
                step = target - state.t if i == 2**loop.level - 1 else h
                state, used = _advance(stepper, excitation, state, step,
                                       settings.max_step_cuts - loop.level, mesh,
                                       norm if i == first else None)
                used_cuts += used
        except StepFailedError as exc:
            failure = exc
            break
        k += 1
        cuts += used_cuts
        loop.adapt(used_cuts)
        if loop.output_due(state.t, k):
            recorder.add(state)
        if progress is not None:
            progress(state.t)
    if failure is not None:
        if recorder.last_time < state.t:
            recorder.add(state)  # the last completed step
        counters = dict(stepper.counters, steps=k, step_cuts=cuts)
        logger.info("%s: %s", system.name, failure.message())
        return recorder.result(False, failure.message(), counters, system, asdict(settings))
    counters = dict(stepper.counters, steps=n_steps, step_cuts=cuts)
    return recorder.result(True, f"completed {n_steps} steps", counters, system,
                           asdict(settings))


def _expected_records(n_steps: int, dt: float, every: float) -> int:
    """Output records of a run of ``n_steps`` steps of ``dt`` written every ``every``
    (:meth:`_Loop.output_due`): the initial state, one per ``every`` and the last step (one
    more for the roundoff of the schedule)."""
    return 3 + int(math.floor(n_steps * dt / every + 1e-9))


class _Loop:
    """The step loop's schedule: the sub-stepping level (2**level sub-steps per step while
    Newton struggles) and the output times."""

    def __init__(self, settings: DynamicsSettings, n_steps: int, every: float) -> None:
        self.dt, self.n_steps, self.every = settings.dt, n_steps, every
        self.max_cuts = settings.max_step_cuts
        self.level, self.calm = 0, 0
        self.next_output = every

    def adapt(self, used_cuts: int) -> None:
        """After a full step (:func:`_adapt`)."""
        self.level, self.calm = _adapt(self.level, self.calm, used_cuts, self.max_cuts)

    def output_due(self, t: float, k: int) -> bool:
        """Whether the state at ``t`` after full step ``k`` is an output record (and if so
        move on to the next output time)."""
        if t >= self.next_output - 1e-9 * self.dt or k == self.n_steps:
            self.next_output += self.every
            return True
        return False


class _BlockRunner:
    """Runs blocks of steps in the compiled loop (:meth:`FastStepper.run_block`): plans the
    sub-step times of a block (those the Python loop of :func:`simulate` would take without
    step cuts: the same arithmetic), evaluates the prescribed motion and point forces there
    at once, and records the block's output. A block has one sub-stepping level: at level 0
    it lasts about :data:`BLOCK_WALL` of wall time; at a finer level it ends where the level
    would change (ten calm steps). So the writer gets records at least every
    :data:`BLOCK_WALL` or so (more only when steps suddenly slow down, e.g. at a finer level),
    and a SIGKILL loses no more than its :data:`~moorline.io.stream.SYNC_WALL`."""

    BLOCK_WALL = 0.2  # wall time of a block [s] (the writer syncs every second)
    IN_PLACE = ("position", "velocity", "tension", "end_force")  # written by the compiled loop

    def __init__(self, stepper, excitation: Excitation, mesh: Mesh, recorder: _Recorder,
                 loop: _Loop) -> None:
        import time

        self.stepper, self.excitation, self.recorder, self.loop = stepper, excitation, \
            recorder, loop
        self.clock = time.perf_counter
        self.per_step_wall = 0.0
        ends = [(e, side) for elements in mesh.line_elements
                for side, e in ((0, elements[0]), (1, elements[-1]))]
        self.end_el = np.array([e for e, _ in ends], dtype=np.int64)
        self.end_side = np.array([side for _, side in ends], dtype=np.int64)
        self.end_weight = 0.5 * mesh.weight_per_length[self.end_el] * mesh.length0[self.end_el]
        self.n_lines = len(mesh.line_names)
        self.n_bodies = len(mesh.body_names)
        self.body_records = _BodyRecords(mesh, self.end_el, self.end_side)

    def _length(self, remaining: int) -> int:
        loop = self.loop
        if loop.level:
            return min(10 - loop.calm, remaining)
        if self.per_step_wall <= 0.0:  # the first block: a few steps, to time them
            return min(4, remaining)
        return int(min(max(self.BLOCK_WALL / self.per_step_wall, 1), 8192, remaining))

    def _plan(self, t: float, k: int, m: int) -> tuple[FloatArray, FloatArray, NDArray]:
        """Sub-step end times and sizes, and the output flags, of full steps k+1 .. k+m
        (schedule advanced as if they all succeed; :meth:`run` rewinds it otherwise)."""
        loop = self.loop
        per = 2**loop.level
        times, hs = np.empty(m * per), np.empty(m * per)
        record = np.zeros(m, dtype=np.bool_)
        j = 0
        for s in range(m):
            target = (k + s + 1) * loop.dt
            h = (target - t) / per
            for i in range(per):
                step = target - t if i == per - 1 else h
                t = t + step
                times[j], hs[j] = t, step
                j += 1
        return times, hs, record

    def run(self, state, k: int):
        """Advance from ``state`` after ``k`` full steps by one block; returns the state
        after it, the full steps done and, when it stopped inside a step, ``(sub-step, h,
        residual norm)`` of the sub-step Python is to cut."""
        loop = self.loop
        m = self._length(loop.n_steps - k)
        times, hs, record = self._plan(state.t, k, m)
        per = 2**loop.level
        saved_output = loop.next_output
        for s in range(m):
            record[s] = loop.output_due(float(times[(s + 1) * per - 1]), k + s + 1)
        kin = self.excitation.constrained_states(times)
        forces = (self.excitation.force_nodes, self.excitation.force_histories(times))
        n_out = int(np.count_nonzero(record))
        slots = self.recorder.slots(n_out, self.IN_PLACE)
        started = self.clock()
        block = self.stepper.run_block(
            state, times, hs, per, record, kin, forces, self.end_el, self.end_side,
            out=(slots["position"], slots["velocity"], slots["tension"],
                 slots["end_force"].reshape(n_out, 2 * self.n_lines, 3)))
        done = block.steps
        if done and not loop.level:
            self.per_step_wall = (self.clock() - started) / done
        # the schedule as far as the block went
        loop.next_output = saved_output
        for s in range(done):
            loop.output_due(float(times[(s + 1) * per - 1]), k + s + 1)
            loop.adapt(0)
        n_rec = len(block.tensions)
        if n_rec:
            rec_steps = np.flatnonzero(record[:done])
            rec_times = times[(rec_steps + 1) * per - 1]
            bodies = self.body_records.records(block)  # from the elements' end forces
            block.end_forces[:, :, 2] -= self.end_weight  # the records' end forces, in place
            self.recorder.add_block(rec_times, {
                "position": block.positions, "velocity": block.velocities,
                "tension": block.tensions,
                "end_force": block.end_forces.reshape(n_rec, self.n_lines, 2, 3),
                **bodies, "wave_elevation": self.recorder.elevations(rec_times)},
                in_place=self.IN_PLACE)
        if block.stopped < 0:
            return block.state, k + done, None
        return block.state, k + done, (block.stopped, float(hs[done * per]), block.norm)


def start(system: System, settings: DynamicsSettings,
          initial: StaticResult | FloatArray | None = None, fluid=None,
          maxwell: FloatArray | None = None):
    """What a time-domain run starts from (the set-up of :func:`simulate`, also used by
    :mod:`moorline.coupling`): ``(mesh, fluid, excitation, state, stepper)``; the arguments
    as :func:`simulate`'s."""
    mesh = (with_loads_of(initial.mesh, system) if isinstance(initial, StaticResult)
            else discretize(system))
    if initial is None and settings.start == "initial":
        initial = lines_at_rest(system, mesh=mesh)
        if not initial.success:
            raise ConvergenceError(f"the lines' static shape at the case's body poses "
                                   f"(start: initial) failed: {initial.message}", time=0.0)
    elif initial is None:
        initial = solve_statics(system, _statics_settings(system), mesh=mesh)
        if not initial.success:
            raise ConvergenceError(f"static equilibrium before dynamics failed: "
                                   f"{initial.message}", time=0.0)
    x0 = initial.positions if isinstance(initial, StaticResult) else np.asarray(initial, float)
    mesh = dynamic_mesh(mesh, x0)
    fluid = fluid if fluid is not None else _fluid(
        system, settings, ramp_current=not getattr(initial, "current_drag", False))
    model = DynamicModel(mesh, fluid, settings.viscoelastic_update,
                         system.environment.seabed, slack_damping=settings.slack_damping,
                         drag_velocity=settings.drag_velocity)
    excitation = Excitation(mesh, x0)
    state = _initial_state(model, excitation, x0, settings.dt, maxwell, initial)
    if settings.start == "initial" and state.bodies is not None:
        state = _bodies_released(model, state)
    # force scale of the residual tolerance: the larger of the nodal loads and the tensions
    scale = max(float(np.abs(model.external).max(initial=0.0)),
                float(np.abs(state.evaluation.tension).max(initial=0.0)), 1e-12)
    tolerance = max(settings.tolerance * scale, StaticModel(mesh).roundoff_floor(x0))
    stepper = _stepper(model, fluid, settings, tolerance, system, state)
    return mesh, fluid, excitation, state, stepper


REFRESH_RATIO = 0.05
"""A time step's reused factorization is refreshed after an iteration that reduced the residual
max-norm by less than 20 times (statics: 2 times). A banded factorization costs about one
residual evaluation, so a modified-Newton iteration converging linearly (ratios 0.3-0.5 near
slack snaps) is dearer than a fresh tangent (issue 16, one OC3 line under the P1 motion: 1,000
elements 5,166 -> 4,140 iterations and 1.21 -> 1.08 s from ratio 0.2; 100 elements and the
P1 three-line run likewise faster)."""


LOCAL_ITERATIONS = 20
"""Local (windowed) Newton iterations after a full one in a time step of a line-only model
(:mod:`moorline.solvers.newton`: nonlinear elimination). The hard slack-snap steps converge
slowly because after one or two full iterations the residual sits on a few small groups of
nodes near touchdown where Newton creeps (~0.9 per iteration); a window around them converges
cheaply (issue 16, P4)."""

LOCAL_MIN_FREE_NODES = 300
"""Free nodes a line-only model needs for the local phase. It pays where a window is a small
part of the line: one OC3 line under the P1 motion at 1,000 elements steps 1.65x faster with
it (4.24 -> 2.56 ms a step), at 100 elements no faster (0.16 ms either way: the full iteration
is cheap there), and on the P1 three-line run at 20 segments the stepping is unchanged while
loading the compiled step with the local phase in it costs 0.2-0.3 s more of the process. A
model below this size gets the compiled step without the local code
(:func:`moorline.solvers.fast_newmark.newmark_step` with ``local`` None)."""


def _local_iterations(model: DynamicModel) -> int:
    """The local iterations of the model's Newton policy: :data:`LOCAL_ITERATIONS` for a
    line-only model of at least :data:`LOCAL_MIN_FREE_NODES` free nodes, else 0."""
    if model.mesh.body_names or int(np.count_nonzero(model.mesh.free_nodes)) < LOCAL_MIN_FREE_NODES:
        return 0
    return LOCAL_ITERATIONS


def _stepper(model: DynamicModel, fluid, settings: DynamicsSettings, tolerance: float,
             system: System | None = None, start: StepState | None = None):
    """The time stepper of the settings: the compiled backend when the model allows it, else
    the general one (the same algorithm; lines, points and bodies). ``start``: the state the
    run starts from (the bodies' exciting-force phases refer to it)."""
    from .fast_path import fast_path_reason

    coefficients = Coefficients.for_scheme(settings.scheme, settings.alpha)
    policy = NewtonPolicy(tolerance=tolerance, max_iterations=settings.max_iterations,
                          stiffness_update=settings.stiffness_update, age_per="solve",
                          refresh_ratio=REFRESH_RATIO,
                          local_iterations=_local_iterations(model))
    rayleigh = _rayleigh(settings)
    has_bodies = bool(model.mesh.body_names)
    reason = fast_path_reason(model, fluid, settings.scheme, settings.variant, has_bodies,
                              rayleigh is not None)
    bodies = BodyModel(model.mesh, fluid, start.bodies if start is not None else None) \
        if has_bodies else None
    if reason is None and settings.fast_path:
        from .fast_newmark import FastStepper  # imports numba: only when it runs

        return FastStepper(model, coefficients, policy, bodies)
    logger.info("general stepper (compiled step not used: %s)", reason or "disabled")
    return Stepper(model, coefficients, settings.variant, policy, bodies, rayleigh)


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
                   dt: float, maxwell: FloatArray | None = None,
                   initial: StaticResult | None = None) -> StepState:
    """Start at rest at the static state (bodies at their static poses, from ``initial``),
    with the accelerations the loads give at t = 0 (:func:`~.newmark.accelerated`; bodies
    at rest)."""
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
        material = MaterialState(material.strain, np.asarray(maxwell, dtype=float).copy(),
                                 material.peak)
    forces = excitation.point_forces(0.0, mesh.n_nodes)
    ev = model.evaluate(x, v, a, 0.0, material, dt, False, forces)
    bodies = with_pins(mesh.bodies, _static_poses(initial), 0.0) if mesh.body_names else None
    state = StepState(0.0, x, v, a, ev.material, ev, bodies)
    return accelerated(model, state, material, forces, dt)


def _bodies_released(model: DynamicModel, state: StepState) -> StepState:
    """``state`` with the free bodies' accelerations the loads give them at the start,
    ``(M + A) a = F`` per body (rigid-body mass and added mass about its origin; the forces
    of :meth:`BodyModel.forces` at rest: weight, hydrostatics, the lines' pull): a body
    released away from equilibrium (a decay test, a free fall, ``start: initial``) starts
    with its true acceleration, not at ``a = 0``, which would lag its velocity by ``a h / 2``
    for the whole run. The attached line nodes' mass is not in ``M`` (the first step
    corrects it)."""
    bm = BodyModel(model.mesh, model.fluid, state.bodies)
    x, v, a = state.x.copy(), state.v.copy(), state.a.copy()
    bs = state.bodies
    arms = bm.place(x, v, a, bs)
    ev = state.evaluation
    m_s = model.node_mass[:, None]
    other = bm.forces(bs, ev.nodal - ev.inertial, ev.inertial - m_s * a, arms, state.t)[0]
    acc = bs.acc.copy()
    for b, body in enumerate(bm.bodies):
        if bm.body_dof[b] >= 0 and body.kind == "free":
            acc[b] = np.linalg.solve(body_mass_matrix(body, bs.R[b]) + bm.added[b], other[b])
    released = BodyState(bs.r, bs.R, bs.vel, acc)
    bm.place(x, v, a, released)
    return StepState(state.t, state.x, state.v, a, state.material, state.evaluation, released)


def _static_poses(initial) -> BodyState:
    """The bodies at their static poses, at rest."""
    pose = initial.body_pose if isinstance(initial, StaticResult) else None
    if pose is None or not len(pose):
        raise ConvergenceError("dynamics of a system with bodies needs its static state")
    return BodyState.from_pose(pose)


class StepFailedError(Exception):
    """A step that did not converge after all its cuts (internal to :func:`simulate`)."""

    def __init__(self, time: float, where: str | None, residual: float) -> None:
        super().__init__(time, where, residual)
        self.time, self.where, self.residual = time, where, residual

    def message(self) -> str:
        at = f" at {self.where}" if self.where else ""
        return (f"Newton iterations did not converge at t = {self.time:.6g}{at} "
                f"(residual {self.residual:.3e}) after all step cuts")


def _advance(stepper, excitation: Excitation, state: StepState, h: float,
             cuts_left: int, mesh: Mesh, failed: float | None = None) -> tuple[StepState, int]:
    """One step of size ``h``, halving it recursively when Newton fails (``failed``: the
    residual norm of an attempt already made, which failed: go straight to the cut)."""
    t1 = state.t + h
    constrained = excitation.constrained_state(t1)
    forces = excitation.point_forces(t1, mesh.n_nodes)
    if failed is None:
        new, ok, norm = stepper.step(state, h, constrained, forces)
        if ok and math.isfinite(norm):
            return new, 0
    else:
        norm = failed
    if cuts_left == 0:
        raise StepFailedError(t1, _worst(stepper, state, h, constrained, forces), norm)
    stepper.forget_tangent()
    half, used1 = _advance(stepper, excitation, state, h / 2, cuts_left - 1, mesh)
    full, used2 = _advance(stepper, excitation, half, h / 2, cuts_left - 1, mesh)
    stepper.forget_tangent()
    return full, 1 + used1 + used2


def _worst(stepper, state: StepState, h: float, constrained, forces) -> str:
    """Where the residual of the predicted state is largest (for the error message)."""
    general = stepper if isinstance(stepper, Stepper) else getattr(
        stepper, "general", None) or Stepper(stepper.model, stepper.c, "iterative",
                                             stepper.policy)
    dof = general.worst_dof(state, h, constrained, forces)
    return describe_unknown(stepper.model.mesh, general.bodies.body_dof, dof)


def describe_unknown(mesh: Mesh, body_dof: NDArray[np.int64], dof: int) -> str:
    """A node dof (point, or line, node and elements) or a body dof, in words."""
    if dof < mesh.n_dofs:
        return describe_dof(mesh, dof)
    for b, first in enumerate(body_dof):
        if 0 <= first <= dof < first + 6:
            label = ("surge", "sway", "heave", "roll", "pitch", "yaw")[dof - first]
            return f"body {mesh.body_names[b]} ({label})"
    return f"unknown {dof}"


class _Recorder:
    """Collects output records (and streams them when a writer is given).

    The records go into one array per variable, allocated at the first record for
    ``capacity`` records (the run's output times: :func:`_expected_records`; grown should a
    run give more), so the result holds views of them, not a concatenation of blocks (half
    the peak memory of a long run, and no copy at its end), and the compiled loop writes its
    records straight into them (:meth:`slots`)."""

    def __init__(self, mesh: Mesh, writer, fluid=None,
                 static_tension: FloatArray | None = None, capacity: int = 1) -> None:
        self.mesh = mesh
        self.writer = writer
        self.fluid = fluid
        self.static_tension = (np.zeros(0) if static_tension is None
                               else np.array(static_tension, dtype=float))
        self.capacity = max(int(capacity), 1)
        self.arrays: dict[str, FloatArray] = {}
        self.count = 0
        self.last_time = -math.inf

    def add(self, state: StepState) -> None:
        """One record: the state."""
        record = {"position": state.x, "velocity": state.v,
                  "tension": state.evaluation.tension,
                  "end_force": _end_forces(self.mesh, state),
                  "body_pose": (state.bodies.pose() if state.bodies is not None
                                else np.zeros((0, 6))),
                  "body_velocity": (state.bodies.vel if state.bodies is not None
                                    else np.zeros((0, 6))),
                  "body_mooring_force": _mooring_forces(self.mesh, state),
                  "body_pin_force": (state.pin_force if state.pin_force is not None
                                     else np.zeros((len(self.mesh.body_names), 3))),
                  "wave_elevation": self._elevation(state.t)}
        self.add_block(np.array([state.t]),
                       {key: np.asarray(value)[None] for key, value in record.items()})

    def slots(self, n: int, keys: tuple[str, ...]) -> dict[str, FloatArray]:
        """Views of the next ``n`` rows of the record arrays ``keys`` (made by the first
        record), for a block to write its records into in place before :meth:`add_block`
        takes them (``in_place``)."""
        self._reserve(n, {})
        return {key: self.arrays[key][self.count:self.count + n] for key in keys}

    def add_block(self, times: FloatArray, records: dict[str, FloatArray],
                  in_place: tuple[str, ...] = ()) -> None:
        """Records at ``times`` (n,), each key stacked along a first axis of length n; the
        keys of ``in_place`` were written into :meth:`slots` already. The writer gets views
        of the record arrays (never changed afterwards)."""
        n = len(times)
        self._reserve(n, {key: np.shape(value)[1:] for key, value in records.items()})
        rows = slice(self.count, self.count + n)
        self.arrays["time"][rows] = times
        for key, value in records.items():
            if key not in in_place:
                self.arrays[key][rows] = value
        self.count += n
        self.last_time = float(times[-1])
        if self.writer is not None:
            self.writer.append_block(self.arrays["time"][rows],
                                     {key: self.arrays[key][rows] for key in records},
                                     owned=True)

    def _reserve(self, n: int, shapes: dict[str, tuple[int, ...]]) -> None:
        """Room for ``n`` more records (the arrays made at the first record, with its
        per-record ``shapes``; doubled when full)."""
        if not self.arrays:
            self.capacity = max(self.capacity, n)
            self.arrays = {"time": np.empty(self.capacity)}
            self.arrays.update({key: np.empty((self.capacity, *shape))
                                for key, shape in shapes.items()})
        elif self.count + n > self.capacity:
            self.capacity = max(2 * self.capacity, self.count + n)
            grown = {}
            for key, old in self.arrays.items():
                grown[key] = np.empty((self.capacity, *old.shape[1:]))
                grown[key][:self.count] = old[:self.count]
            self.arrays = grown  # views handed out before keep the old arrays alive

    def _elevation(self, t: float) -> float:
        """Free-surface elevation at the origin (x = y = 0) [length]."""
        if self.fluid is None:
            return 0.0
        return float(self.fluid.kinematics(np.zeros((1, 3)), t)[2][0])

    def elevations(self, times: FloatArray) -> FloatArray:
        """:meth:`_elevation` at ``times`` (zeros in still water or a current)."""
        from ..waves import CurrentProfile, StillWater

        if self.fluid is None or isinstance(self.fluid, StillWater | CurrentProfile):
            return np.zeros(len(times))
        return np.array([self._elevation(float(t)) for t in times])

    def result(self, ok: bool, message: str, counters: dict, system: System,
               settings: dict) -> DynamicResult:
        arrays = {key: value[:self.count] for key, value in self.arrays.items()}
        return DynamicResult(ok, message, arrays["time"], arrays["position"],
                             arrays["velocity"], arrays["tension"], arrays["end_force"],
                             counters, self.mesh, system.name, system.units, settings,
                             body_pose=arrays["body_pose"],
                             body_velocity=arrays["body_velocity"],
                             body_mooring_force=arrays["body_mooring_force"],
                             body_pin_force=arrays["body_pin_force"],
                             wave_elevation=arrays["wave_elevation"],
                             static_tension=self.static_tension)


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


class _BodyRecords:
    """The bodies' records of a block of the compiled loop (:attr:`Block.bodies`): poses,
    velocities and the lines' forces on them as :func:`_mooring_forces` (the attached nodes
    are line ends: their element forces are the block's end forces ``(end_elements,
    end_sides)``)."""

    def __init__(self, mesh: Mesh, end_elements: NDArray, end_sides: NDArray) -> None:
        self.n_bodies = len(mesh.body_names)
        ends = mesh.elements[end_elements, end_sides]
        self.pairs = [(np.flatnonzero(ends == node), int(mesh.slave_body[k]), int(node))
                      for k, node in enumerate(mesh.slave_node)]

    def records(self, block) -> dict[str, FloatArray]:
        """``body_pose``, ``body_velocity``, ``body_mooring_force`` (n_rec, nb, 6) and
        ``body_pin_force`` (n_rec, nb, 3)."""
        n_rec = len(block.tensions)
        if not self.n_bodies:
            return {"body_pose": np.zeros((n_rec, 0, 6)), "body_velocity": np.zeros((n_rec, 0, 6)),
                    "body_mooring_force": np.zeros((n_rec, 0, 6)),
                    "body_pin_force": np.zeros((n_rec, 0, 3))}
        from ..physics.rigid_body import rotation_vector

        r, R, vel, pin_force = block.bodies
        mooring = np.zeros((n_rec, self.n_bodies, 6))
        for ends, b, node in self.pairs:
            force = block.end_forces[:, ends].sum(axis=1)
            mooring[:, b, :3] += force
            mooring[:, b, 3:] += np.cross(block.positions[:, node] - r[:, b], force)
        return {"body_pose": np.concatenate((r, rotation_vector(R)), axis=-1),
                "body_velocity": vel.copy(), "body_mooring_force": mooring,
                "body_pin_force": pin_force.copy()}


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
