"""Drive moorline's mooring lines from an external solver, step by step.

A host (a floating-body code, a vessel simulator, a control loop) owns the motion of some
points or rigid bodies ("coupled"); moorline integrates the lines between them with its one
implicit time stepper (:class:`~moorline.solvers.newmark.Stepper` or its compiled backend,
set up as :func:`~moorline.solvers.dynamics.simulate` sets them up) and returns the mooring
forces on the coupled dofs::

    from moorline.coupling import Coupling

    c = Coupling("cases/oc3_dynamics.yaml")         # the case's prescribed points
    f = c.init(x0)                                  # statics with the points at x0 (9,)
    for k in range(n):
        f = c.step(x(t + dt), v(t + dt), t, dt)     # the host's state at t + dt
        K = c.stiffness()                           # d(-f)/dx, condensed (9, 9)
        t += dt
    c.close()

Coupled dofs, in this order (as MoorDyn's): six per coupled body (origin position and rotation
vector, world axes; velocities: origin velocity and angular velocity), then three per coupled
point. The force on a coupled point is the dynamic residual of the lines at its node: the line
end forces, the node's lumped share of weight, buoyancy, drag and added mass, minus its lumped
structural inertia (what the mooring applies to the host there); a body gets the sum over its
points with the moments about its origin.

Kinematics within an interval: :mod:`moorline.coupling.interval` (the Hermite rule of
:meth:`Coupling.step`, the end state exactly the host's; MoorDyn's linear rule in
:meth:`Coupling.step_linear`, used by the facade :mod:`moorline.coupling.moordyn`).
"""

from __future__ import annotations

import math
import os
from collections.abc import Sequence
from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import CaseError, ConvergenceError
from ..mesh import world_position
from ..model import DynamicsSettings, Point, StaticsSettings, System
from ..physics.rigid_body import rotation_matrix
from ..results import StaticResult
from ..solvers import dynamics as dyn
from ..solvers.equilibrium import StaticModel
from ..solvers.newmark import StepState
from ..solvers.statics import solve_statics
from ..solvers.stiffness import (
    arm_rotation_stiffness,
    condense,
    condensed_tangent,
    full_pattern,
    rigid_map,
)
from .interval import Interval, Kinematics

__all__ = ["Coupling", "CouplingState", "Interval"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class CouplingState:
    """A snapshot for :meth:`Coupling.restore` (opaque to the host): the stepper's state, the
    coupled dofs' kinematics and forces at that time, and the reused factorization."""

    step: StepState
    kinematics: Kinematics
    forces: FloatArray
    tangent: tuple
    level: tuple[int, int] = (0, 0)
    previous: tuple = (None, None)  # the state before the last step and its size


class _HostMotion:
    """The excitation of one interval (duck type of
    :class:`~moorline.solvers.excitation.Excitation` for
    :func:`~moorline.solvers.dynamics._advance`): the case's fixed and prescribed points, the
    coupled nodes where the host's interval puts them."""

    def __init__(self, coupling: Coupling, interval: Interval) -> None:
        self.c, self.interval = coupling, interval

    def constrained_state(self, t: float) -> Kinematics:
        x, v, a = self.c._excitation.constrained_state(t)
        nx, nv, na = self.c._node_kinematics(*self.interval.at(t))
        rows = self.c._rows
        x[rows], v[rows], a[rows] = nx, nv, na
        return x, v, a

    def point_forces(self, t: float, n_nodes: int) -> FloatArray | None:
        return self.c._excitation.point_forces(t, n_nodes)


class Coupling:
    """Mooring lines driven by an external solver (see the module docstring).

    Parameters
    ----------
    source
        A :class:`~moorline.model.System` or a case file.
    points
        The coupled points (``prescribed`` points of the case); default: all its prescribed
        points not on a coupled body. Prescribed points not coupled follow their case motion.
    bodies
        Bodies of the case to couple: the host moves them; their points move rigidly with
        them (their hydrodynamics, mass and loads are the host's business).
    dynamics, statics
        Settings; default: the case's first dynamics and statics analyses (scheme,
        tolerance, Newton constants, wave ramp...).
    substep
        Largest internal step [time]: a host interval longer than it is split into equal
        steps, the coupled dofs following the interval's rule. Default: one implicit step per
        host step (the scheme has no stability limit).
    """

    def __init__(self, source: System | str | os.PathLike, points: Sequence[str] | None = None,
                 bodies: Sequence[str] = (), *, dynamics: DynamicsSettings | None = None,
                 statics: StaticsSettings | None = None, substep: float | None = None) -> None:
        if not isinstance(source, System):
            from ..io import load_case

            source = load_case(source)
        self.system = source
        self.body_names = tuple(bodies)
        for name in self.body_names:
            if name not in source.bodies:
                raise CaseError(f"no body {name!r} to couple", file=source.source,
                                field="bodies")
        on_bodies = {p.name for p in source.points.values() if p.body in self.body_names}
        if points is None:
            points = [p.name for p in source.points.values()
                      if p.kind == "prescribed" and p.name not in on_bodies]
        self.point_names = tuple(points)
        wrong = [n for n in self.point_names
                 if n not in source.points or source.points[n].kind != "prescribed"]
        if wrong:
            raise CaseError(f"coupled points must be prescribed points: {', '.join(wrong)}",
                            file=source.source, field="points")
        self.body_points = tuple(tuple(p.name for p in source.points.values()
                                       if p.kind == "body" and p.body == b)
                                 for b in self.body_names)
        self.dynamics = dynamics or source.first(DynamicsSettings)
        self.statics = statics or source.first(StaticsSettings)
        self.substep = substep
        self.n_dof = 6 * len(self.body_names) + 3 * len(self.point_names)
        self.dof_names = tuple(
            [f"{b}.{d}" for b in self.body_names for d in ("x", "y", "z", "rx", "ry", "rz")]
            + [f"{p}.{d}" for p in self.point_names for d in "xyz"])
        self._static: StaticResult | None = None
        self._state: StepState | None = None
        self._closed = False

    # ------------------------------------------------------------------ set-up
    def case_positions(self) -> FloatArray:
        """The coupled dofs where the case puts them (n_dof,)."""
        out = [np.concatenate((self.system.bodies[b].position, self.system.bodies[b].rotation))
               for b in self.body_names]
        out += [np.asarray(self.system.points[p].position, float) for p in self.point_names]
        return np.concatenate(out).astype(float) if out else np.zeros(0)

    def _derived(self, positions: FloatArray) -> System:
        """The case with the coupled points at ``positions`` (their case motion dropped) and
        the coupled bodies' points turned into prescribed points where the bodies put them."""
        system = self.system
        points = dict(system.points)
        poses = self._split(positions)[0]
        for b, name in enumerate(self.body_names):
            body = replace(system.bodies[name], position=tuple(poses[b, :3]),
                           rotation=tuple(poses[b, 3:]))
            posed = replace(system, bodies={**system.bodies, name: body})
            for p in self.body_points[b]:
                point = system.points[p]
                points[p] = Point(p, "prescribed", tuple(world_position(posed, point)),
                                  mass=point.mass, volume=point.volume, force=point.force)
        for k, p in enumerate(self._split(positions)[1]):
            name = self.point_names[k]
            points[name] = replace(system.points[name], position=tuple(p), motion=None,
                                   initial_position=None)
        bodies = {k: v for k, v in system.bodies.items() if k not in self.body_names}
        return replace(system, points=points, bodies=bodies)

    def _split(self, q: ArrayLike) -> tuple[FloatArray, FloatArray]:
        """Body dofs (nb, 6) and point dofs (np, 3) of a flat coupled vector."""
        q = np.asarray(q, dtype=float).ravel()
        if q.size != self.n_dof:
            raise ValueError(f"expected {self.n_dof} coupled dofs, got {q.size}")
        nb = 6 * len(self.body_names)
        return q[:nb].reshape(-1, 6), q[nb:].reshape(-1, 3)

    def init(self, positions: ArrayLike | None = None, velocities: ArrayLike | None = None,
             time: float = 0.0) -> FloatArray:
        """Solve the statics with the coupled dofs at ``positions`` (default: the case's) and
        start the time integration there, at rest, at ``time``.

        ``velocities`` (optional) are the coupled dofs' velocities at ``time``: the start of
        the first interval's Hermite motion; the free nodes start at rest with the
        accelerations their loads give then (as :func:`~moorline.solvers.dynamics.simulate`
        starts a prescribed point that moves at t = 0). Returns the static forces on the
        coupled dofs (n_dof,).

        Raises
        ------
        ConvergenceError
            When the statics do not converge.
        """
        self._check_open()
        q = self.case_positions() if positions is None else np.asarray(positions, float).ravel()
        self._split(q)
        derived = self._derived(q)
        guess = self._guess(derived, q)
        static = solve_statics(derived, self.statics, initial=guess)
        if not static.success:
            raise ConvergenceError(f"coupling init of {self.system.name}: statics did not "
                                   f"converge ({static.message})")
        self._static = static
        mesh, fluid, excitation, state, stepper = dyn.start(derived, self.dynamics, static)
        self._mesh, self._excitation, self._stepper = mesh, excitation, stepper
        self._nodes, self._arms_body, self._node_body = self._coupled_nodes(derived, mesh)
        constrained = np.flatnonzero(~mesh.free_nodes)
        row = {int(n): i for i, n in enumerate(constrained)}
        self._rows = np.array([row[int(n)] for n in self._nodes], dtype=np.int64)
        v = np.zeros(self.n_dof) if velocities is None else np.asarray(velocities, float).ravel()
        kin = (q.copy(), v.copy(), np.zeros(self.n_dof))
        if velocities is not None:  # the start as simulate's: the loads' accelerations
            motion = _HostMotion(self, Interval.linear(0.0, 1.0, q, v))
            state = dyn._initial_state(stepper.model, motion, static.positions,
                                       self.dynamics.dt, None, static)
        self._offset = float(time)
        self._state, self._kin = state, kin
        nodal = StaticModel(mesh, exact_cable=True).forces(static.positions).nodal
        self._forces = self._generalized(static.positions, nodal[self._nodes], q)
        self.counters = {"steps": 0, "step_cuts": 0}
        self._level, self._calm = 0, 0
        self._previous, self._step_size = state, None
        return self._forces.copy()

    def _guess(self, derived: System, q: FloatArray) -> FloatArray | None:
        """The last equilibrium as the start of a new static solve of the same system (the
        coupled nodes moved to ``q``), else None (the case's start shape)."""
        if self._static is None:
            return None
        x = self._static.positions.copy()
        x[self._nodes] = self._node_kinematics(q, np.zeros_like(q), np.zeros_like(q))[0]
        return x

    def _coupled_nodes(self, derived: System, mesh):
        """Node of every coupled point (bodies' points first), its arm in its body's frame and
        its body (-1: a coupled point)."""
        nodes, arms, owner = [], [], []
        for b, names in enumerate(self.body_points):
            for p in names:
                nodes.append(mesh.point_index(p))
                arms.append(self.system.points[p].position)
                owner.append(b)
        for p in self.point_names:
            nodes.append(mesh.point_index(p))
            arms.append((0.0, 0.0, 0.0))
            owner.append(-1)
        return (np.array(nodes, dtype=np.int64), np.array(arms, float).reshape(-1, 3),
                np.array(owner, dtype=np.int64))

    # ------------------------------------------------------------------ kinematics, forces
    def _node_kinematics(self, x: FloatArray, v: FloatArray, a: FloatArray) -> Kinematics:
        """Positions, velocities and accelerations of the coupled nodes (n, 3) from those of
        the coupled dofs: a body's point at arm ``b`` sits at ``r + R b`` and moves with
        ``v + w x Rb`` and ``a + alpha x Rb + w x (w x Rb)``."""
        bx, px = self._split(x)
        bv, pv = self._split(v)
        ba, pa = self._split(a)
        n = len(self._node_body)
        out = [np.zeros((n, 3)) for _ in range(3)]
        point = self._node_body < 0
        out[0][point], out[1][point], out[2][point] = px, pv, pa
        for b in range(len(self.body_names)):
            mine = self._node_body == b
            arm = self._arms_body[mine] @ rotation_matrix(bx[b, 3:]).T
            w, alpha = bv[b, 3:], ba[b, 3:]
            out[0][mine] = bx[b, :3] + arm
            out[1][mine] = bv[b, :3] + np.cross(w, arm)
            out[2][mine] = ba[b, :3] + np.cross(alpha, arm) + np.cross(w, np.cross(w, arm))
        return out[0], out[1], out[2]

    def _generalized(self, x: FloatArray, node_forces: FloatArray, q: FloatArray) -> FloatArray:
        """Forces on the coupled dofs from the forces on their nodes: a body's force and its
        moment about its origin (world axes), then each point's force."""
        bq, _ = self._split(q)
        out = []
        for b in range(len(self.body_names)):
            mine = self._node_body == b
            f = node_forces[mine]
            arms = x[self._nodes[mine]] - bq[b, :3]
            out.append(np.concatenate((f.sum(axis=0), np.cross(arms, f).sum(axis=0))))
        out.append(node_forces[self._node_body < 0].ravel())
        return np.concatenate(out)

    def _dynamic_forces(self, state: StepState) -> FloatArray:
        ev = state.evaluation
        nodes = self._nodes
        f = ev.nodal[nodes] - self._stepper.model.node_mass[nodes, None] * state.a[nodes]
        return self._generalized(state.x, f, self._kin[0])

    # ------------------------------------------------------------------ stepping
    def step(self, positions: ArrayLike, velocities: ArrayLike, t: float, dt: float,
             accelerations: ArrayLike | None = None) -> FloatArray:
        """Advance from ``t`` to ``t + dt`` with the coupled dofs ending at ``positions`` and
        ``velocities`` (the host's state at ``t + dt``; ``accelerations`` too when known),
        moving in between along the Hermite polynomial through both ends
        (:meth:`Interval.hermite`). Returns the forces on the coupled dofs at ``t + dt``.

        Raises
        ------
        ConvergenceError
            When a step does not converge after all its cuts (the state is left at ``t``).
        """
        self._check_started(t)
        x1, v1 = (np.asarray(a, float).ravel() for a in (positions, velocities))
        a1 = None if accelerations is None else np.asarray(accelerations, float).ravel()
        interval = Interval.hermite(self._state.t, dt, self._kin, x1, v1, a1)
        return self._advance(interval, dt)

    def step_linear(self, positions: ArrayLike, velocities: ArrayLike, t: float,
                    dt: float) -> FloatArray:
        """MoorDyn's coupling step: ``positions`` and ``velocities`` are the host's state at
        ``t``; the coupled dofs move ``x + v (t' - t)`` through the interval, zero
        acceleration (:meth:`Interval.linear`). Returns the forces at ``t + dt``."""
        self._check_started(t)
        interval = Interval.linear(self._state.t, dt, np.asarray(positions, float).ravel(),
                                   np.asarray(velocities, float).ravel())
        return self._advance(interval, dt)

    def _advance(self, interval: Interval, dt: float) -> FloatArray:
        if not dt > 0:
            raise ValueError(f"the coupling interval must be positive, got {dt}")
        n = 1 if self.substep is None else max(1, math.ceil(dt / self.substep - 1e-9))
        # as simulate: 2**level sub-steps per step while Newton struggles (dynamics._adapt)
        level, max_cuts = self._level, self.dynamics.max_step_cuts
        m = n * 2**level
        motion = _HostMotion(self, interval)
        state, cuts = self._state, 0
        end = interval.t0 + dt
        try:
            for _ in range(m):
                state, used = dyn._advance(self._stepper, motion, state, dt / m,
                                           max_cuts - level, self._mesh)
                cuts += used
        except dyn.StepFailedError as exc:
            raise ConvergenceError(f"coupling step of {self.system.name}: {exc.message()}",
                                   time=exc.time + self._offset) from None
        self._level, self._calm = dyn._adapt(level, self._calm, cuts, max_cuts)
        self._previous, self._step_size = self._state, dt / m
        self._state, self._kin = state, interval.at(end)
        self.counters["steps"] += m
        self.counters["step_cuts"] += cuts
        self._forces = self._dynamic_forces(state)
        return self._forces.copy()

    # ------------------------------------------------------------------ tangent
    def stiffness(self, dynamic: bool = False) -> FloatArray:
        """The current tangent of the lines at the coupled dofs, ``K = -d f / d q``
        (n_dof, n_dof), every free dof condensed out, ``K_cc - K_cf K_ff^-1 K_fc``
        (:func:`~moorline.solvers.stiffness.condense`); held dofs are the fixed points and
        the prescribed points not coupled.

        ``dynamic=False``: the static tangent of the one solver core
        (:class:`~moorline.solvers.equilibrium.StaticModel`) at the current node positions
        (:func:`~moorline.solvers.stiffness.condensed_tangent`; at an equilibrium,
        :func:`~moorline.solvers.stiffness.point_stiffness`).

        ``dynamic=True``: the tangent of the last :meth:`step`'s forces with respect to the
        end positions when the velocities and accelerations follow them by the Newmark
        relations (``dv/dx = gamma / (beta h)``, ``da/dx = 1 / (beta h^2)``): the condensed
        effective tangent ``(M_s + M_a) / (beta h^2) + gamma C / (beta h) + K`` (Tuah (1982)
        eq. 4.2.9a) of the dynamic model at the current state, the Jacobian a Newmark host
        iterating on its own equations needs (with HHT the ``(1 + alpha)`` weights of the
        residual; for bodies the rigid map of positions serves for the velocities and
        accelerations too, leaving out their angular-velocity terms).

        A body's block maps the point tangent through its points' rigid motion, ``T^T K T``,
        less the turning of the arms under the current forces (as
        :func:`~moorline.solvers.stiffness.group_stiffness`)."""
        self._check_open()
        if self._state is None:
            raise RuntimeError("call init() first")
        x = self._state.x
        if dynamic:
            Kc = condense(self._effective_tangent(), self._mesh, list(self._nodes))
            ev = self._state.evaluation
            forces = (ev.nodal[self._nodes]
                      - self._stepper.model.node_mass[self._nodes, None]
                      * self._state.a[self._nodes])
        else:
            Kc = condensed_tangent(self._mesh, x, list(self._nodes))
            forces = StaticModel(self._mesh).forces(x).nodal[self._nodes]
        T = np.zeros((3 * len(self._nodes), self.n_dof))
        bq, _ = self._split(self._kin[0])
        geometric = []
        col = 0
        for b in range(len(self.body_names)):
            mine = np.flatnonzero(self._node_body == b)
            arms = x[self._nodes[mine]] - bq[b, :3]
            rows = (3 * mine[:, None] + np.arange(3)).ravel()
            T[rows, col:col + 6] = rigid_map(arms)
            geometric.append((col + 3, arm_rotation_stiffness(forces[mine], arms)))
            col += 6
        for k in np.flatnonzero(self._node_body < 0):
            T[3 * k:3 * k + 3, col:col + 3] = np.eye(3)
            col += 3
        K = T.T @ Kc @ T
        for c, block in geometric:
            K[c:c + 3, c:c + 3] -= block
        return K

    def _effective_tangent(self):
        """``-dr/dx1`` of the last step over every node dof (Tuah eq. 4.2.9a)."""
        if self._step_size is None:
            raise RuntimeError("stiffness(dynamic=True) needs a step first")
        st, h = self._state, self._step_size
        c = self._stepper.c
        ca, cv, ck = 1 / (c.beta * h * h), (1 + c.alpha) * c.gamma / (c.beta * h), 1 + c.alpha
        model = self._stepper.model
        forces = self._excitation.point_forces(st.t, self._mesh.n_nodes)
        ev = model.evaluate(st.x, st.v, st.a, st.t, self._previous.material, h, True, forces)
        pattern = full_pattern(self._mesh)
        mass = model.node_mass[:, None, None] * np.eye(3)
        if ev.node_M is not None:
            mass = mass + ev.node_M
        return (ck * pattern.assemble(ev.K, ev.node_K) + cv * pattern.assemble(ev.C, ev.node_C)
                + ca * pattern.assemble(ev.Ma, mass))

    # ------------------------------------------------------------------ state
    def state(self) -> CouplingState:
        """A snapshot of the integration (for a predictor-corrector host)."""
        self._check_open()
        return CouplingState(self._state, tuple(k.copy() for k in self._kin),
                             self._forces.copy(), self._stepper.tangent_state(),
                             (self._level, self._calm), (self._previous, self._step_size))

    def restore(self, saved: CouplingState) -> None:
        """Go back to a snapshot: the next :meth:`step` from it repeats the same iterations
        (the same forces for the same motion)."""
        self._check_open()
        self._state, self._kin = saved.step, tuple(k.copy() for k in saved.kinematics)
        self._forces = saved.forces.copy()
        self._stepper.set_tangent_state(saved.tangent)
        self._level, self._calm = saved.level
        self._previous, self._step_size = saved.previous

    def close(self) -> None:
        """Release the integration (further calls raise)."""
        self._state = self._stepper = self._excitation = None
        self._closed = True

    # ------------------------------------------------------------------ getters
    @property
    def time(self) -> float:
        """The host time of the current state."""
        return self._state.t + self._offset

    @property
    def forces(self) -> FloatArray:
        """The forces on the coupled dofs at the current state (n_dof,)."""
        return self._forces.copy()

    @property
    def positions(self) -> FloatArray:
        """All node positions (n_nodes, 3) at the current state."""
        return self._state.x.copy()

    @property
    def mesh(self):
        """The mesh of the coupled system (points first, in case order)."""
        return self._mesh

    @property
    def static(self) -> StaticResult:
        """The static equilibrium of the last :meth:`init`."""
        return self._static

    def point_force(self, name: str) -> FloatArray:
        """Force (3,) on any point of the case at the current state: the lines' residual at
        its node (as the coupled points' forces; at a fixed point, minus its reaction)."""
        node = self._mesh.point_index(name)
        st = self._state
        return st.evaluation.nodal[node] - self._stepper.model.node_mass[node] * st.a[node]

    def tensions(self) -> FloatArray:
        """Element tensions (n_elements,) at the current state."""
        return self._state.evaluation.tension.copy()

    def end_forces(self) -> FloatArray:
        """Force each line exerts on its ends A and B (n_lines, 2, 3), as the end forces of
        :func:`~moorline.solvers.dynamics.simulate`'s records."""
        return dyn._end_forces(self._mesh, self._state)

    def fairlead_tensions(self) -> FloatArray:
        """``|end force at end B|`` of every line (n_lines,)."""
        return np.linalg.norm(self.end_forces()[:, 1], axis=-1)

    def _check_open(self) -> None:
        if self._closed:
            raise RuntimeError("the coupling is closed")

    def _check_started(self, t: float) -> None:
        self._check_open()
        if self._state is None:
            raise RuntimeError("call init() before step()")
        now = self.time
        if abs(t - now) > 1e-9 * max(1.0, abs(now)):
            raise ValueError(f"step from t = {t:.9g}, but the coupling is at t = {now:.9g} "
                             "(restore() a state to repeat a step)")
