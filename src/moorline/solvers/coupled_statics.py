"""Static equilibrium of lines and rigid bodies solved together (Tuah 1982 sec. 3.3; Wang, Er
and Iu eq. 31-34): one Newton system in the free node dofs and the six dofs of every free
body, through the master-slave transformation of :mod:`moorline.solvers.bodies`. A pinned
body's three rotations are solved for (its rotational balance about the pin) and its
translations held at the pin (:func:`~moorline.solvers.bodies.hold_dofs`); its reduced
stiffness is the Schur complement with those rows and columns eliminated."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..mesh import Mesh
from ..model import StaticsSettings
from .assembly import factorize, gather_free, scatter_free
from .bodies import (
    BodyDofs,
    BodyState,
    body_loads,
    hold_dofs,
    place_slaves,
    skew,
    spin_projection,
    transformation,
    world_arms,
)
from .equilibrium import ForceState, StaticModel
from .neutral_dofs import NeutralDofs, find_neutral
from .newton import Counters, NewtonPolicy, TangentCache
from .newton import solve as newton_solve

FloatArray = NDArray[np.float64]


class CoupledStatics:
    """Residual and exact tangent of the coupled line-body statics (``exact_cable``,
    ``current``: see :class:`~moorline.solvers.equilibrium.StaticModel`)."""

    def __init__(self, mesh: Mesh, exact_cable: bool = False, current=None) -> None:
        self.mesh = mesh
        self.model = StaticModel(mesh, current, exact_cable=exact_cable)
        self.bodies = list(mesh.bodies)
        layout = BodyDofs.of(mesh, self.bodies)
        self.n_free, self.body_dof, self.n_unknowns = (layout.n_free, layout.body_dof,
                                                       layout.n_unknowns)
        self.ext_dofs, self.pattern, self.ext_map = layout.ext_dofs, layout.pattern, layout.ext_map
        self.held = layout.held
        self.layout = layout

    def residual(self, x: FloatArray, poses: BodyState) -> tuple[FloatArray, ForceState]:
        """Out-of-balance forces at the free node dofs, then force and moment on every free
        or pinned body (about its origin; zero on a pinned body's held translations)."""
        state = self.model.forces(x)
        out = np.zeros(self.n_unknowns)
        out[: self.n_free] = gather_free(state.nodal, self.mesh.dof_of_node)
        for b, generalized in enumerate(self.body_forces(state, poses)):
            if self.body_dof[b] >= 0:
                out[self.body_dof[b]: self.body_dof[b] + 6] = generalized
        self.layout.transfer(out, self.layout.pin_arms(poses))
        out[self.held] = 0.0
        if self.layout.spin.any():
            out = spin_projection(self.layout, poses)[0] @ out
        return out, state

    def body_forces(self, state: ForceState, poses: BodyState) -> FloatArray:
        """Force and moment about its origin (world axes) of the loads and the attached
        lines on every body (n_bodies, 6): the out-of-balance force of a free body; minus the
        reaction of a pinned body's pin (translation) or of a fixed body's support."""
        arms = world_arms(self.mesh, poses)
        out = np.zeros((len(self.bodies), 6))
        for b, body in enumerate(self.bodies):
            mine = self.mesh.slave_body == b
            f = state.nodal[self.mesh.slave_node[mine]]
            generalized, _ = body_loads(body, poses.r[b], poses.R[b], self.mesh.gravity,
                                        self.mesh.water_density)
            generalized[:3] += f.sum(axis=0)
            generalized[3:] += np.cross(arms[mine], f).sum(axis=0)
            out[b] = generalized
        return out

    def tangent(self, x: FloatArray, poses: BodyState, state: ForceState,
                taut_axial: bool = False, regularize: bool = True):
        """Exact tangent ``-d(residual)/d(unknowns)`` (CSC); ``taut_axial``: see
        :meth:`moorline.solvers.equilibrium.StaticModel.tangent`; ``regularize``: add the
        vanishing diagonal of the body dofs and hold the held ones (``False``: the bare
        tangent, to find the directions nothing resists)."""
        import scipy.sparse as sp

        arms = world_arms(self.mesh, poses)
        P = transformation(self.mesh, self.ext_dofs, self.n_free, self.body_dof, arms)
        K = (P.T @ self.model.tangent(x, self.pattern, taut_axial) @ P).tolil()
        for b, body in enumerate(self.bodies):
            d = self.body_dof[b]
            if d < 0:
                continue
            mine = self.mesh.slave_body == b
            block = body_loads(body, poses.r[b], poses.R[b], self.mesh.gravity,
                               self.mesh.water_density)[1]
            for f, arm in zip(state.nodal[self.mesh.slave_node[mine]], arms[mine], strict=True):
                block[3:, 3:] -= skew(f) @ skew(arm)
            K[d:d + 6, d:d + 6] = K[d:d + 6, d:d + 6].toarray() + block
        K = K.tocsc()
        if self.layout.chains:  # pins on free bodies: their translations follow the hosts
            full = np.zeros(self.n_unknowns)
            for b, generalized in enumerate(self.body_forces(state, poses)):
                if self.body_dof[b] >= 0:
                    full[self.body_dof[b]: self.body_dof[b] + 6] = generalized
            pins = self.layout.pin_arms(poses)
            Q = self.layout.chain_map(pins)
            K = (Q.T @ K @ Q + self.layout.arm_turning(full, pins)).tocsc()
        # a body free to turn about an axis with nothing resisting it (yaw of a buoy on one
        # line) is a mechanism of the statics: a vanishing regularization of the body
        # diagonal keeps the Newton matrix solvable without changing the equilibrium
        # (the spin of a slender pinned rod about its axis, too)
        body = np.flatnonzero(np.arange(self.n_unknowns) >= self.n_free)
        if body.size and regularize:
            largest = float(np.abs(K.diagonal()).max(initial=1.0))
            K = K + sp.csc_matrix((np.full(body.size, 1e-9 * largest), (body, body)),
                                  shape=K.shape)
            K = hold_dofs(K, self.held, largest)  # a pinned body's translations
            if self.layout.spin.any():  # a pinned rod's spin about its axis
                S, N = spin_projection(self.layout, poses)
                K = (S @ K @ S + largest * N).tocsc()
        return K

    def update(self, x: FloatArray, poses: BodyState,
               du: FloatArray) -> tuple[FloatArray, BodyState]:
        """Apply a step of the unknowns (a pinned body's translations stay)."""
        du = np.where(self.held, 0.0, du)
        if self.layout.spin.any():
            du = spin_projection(self.layout, poses)[0] @ du
        x = x + scatter_free(du[: self.n_free], self.mesh.dof_of_node)
        nb = len(self.bodies)
        dr, dtheta = np.zeros((nb, 3)), np.zeros((nb, 3))
        for b in range(nb):
            d = self.body_dof[b]
            if d >= 0:
                dr[b], dtheta[b] = du[d:d + 3], du[d + 3:d + 6]
        poses = self.layout.place_pins(poses.moved(dr, dtheta))
        return place_slaves(self.mesh, poses, x), poses


@dataclass
class _CoupledTrial:
    r: FloatArray            # the bodies' out-of-balance forces (the lines are in balance)
    full: FloatArray         # the whole coupled residual
    x: FloatArray
    state: ForceState
    u: tuple  # the unknowns with the lines equilibrated


class _BodyNewton:
    """The bodies' balance as a problem of the Newton core: every residual evaluation first
    equilibrates the lines with the bodies held (``hold``), the tangent is the coupled tangent
    with the line dofs condensed out (Schur complement)."""

    def __init__(self, problem: CoupledStatics, hold, counters, settings) -> None:
        self.problem, self.hold, self.counters, self.settings = problem, hold, counters, settings
        self.n = problem.n_free

    def residual(self, u, tangent: bool) -> _CoupledTrial:
        x, poses = u
        x, R, state = _equilibrate(self.problem, x, poses, self.hold, self.counters)
        self.counters.residuals -= 1  # counted by the Newton core
        return _CoupledTrial(R[self.n:], R, x, state, (x, poses))

    def factorize(self, u, trial: _CoupledTrial) -> _SchurStep:
        return _SchurStep(self.problem.tangent(trial.x, u[1], trial.state), trial.full, self.n)

    def update(self, u, du: FloatArray):
        x, poses = u
        return self.problem.update(x, poses, np.concatenate((np.zeros(self.n), du)))

    def limit(self, u, du: FloatArray) -> FloatArray:
        return _limit(np.concatenate((np.zeros(self.n), du)), self.problem,
                      self.settings)[self.n:]


class _SchurStep:
    """Body step ``S^-1 (R_b - K_bl K_ll^-1 R_l)`` from the coupled tangent ``K`` with the
    line dofs condensed out (``S = K_bb - K_bl K_ll^-1 K_lb``); the line residual ``R_l`` is
    the one at the factorization point."""

    def __init__(self, K, R: FloatArray, n: int) -> None:
        import scipy.linalg

        schur, self.correction = reduced_stiffness(K, n, R)
        self.lu = scipy.linalg.lu_factor(schur)

    def solve(self, r_bodies: FloatArray) -> FloatArray:
        import scipy.linalg

        return scipy.linalg.lu_solve(self.lu, r_bodies - self.correction)


def reduced_stiffness(K, n: int, R: FloatArray | None = None
                      ) -> tuple[FloatArray, FloatArray]:
    """The body dofs' stiffness with the ``n`` line dofs condensed out (the Schur complement
    ``K_bb - K_bl K_ll^-1 K_lb``, dense) and the correction ``K_bl K_ll^-1 R_l`` of a line
    residual ``R`` (zeros without one)."""
    K = K.tocsc()
    schur = K[n:, n:].toarray()
    correction = np.zeros(K.shape[0] - n)
    if n:
        K_bl, K_lb = K[n:, :n].toarray(), K[:n, n:].toarray()
        lines = factorize(K[:n, :n])
        schur = schur - K_bl @ lines.solve(K_lb)
        if R is not None:
            correction = K_bl @ lines.solve(R[:n])
    return schur, correction


def solve_coupled(mesh: Mesh, x: FloatArray, settings: StaticsSettings, counters, hold,
                  current=None, bodies_held: bool = False
                  ) -> tuple[bool, str, int, ForceState, FloatArray, BodyState]:
    """Static equilibrium of lines and bodies: Newton on the bodies' six dofs with the lines
    kept in equilibrium (partitioned); without free bodies, the lines' own solve.

    Every iteration first equilibrates the lines with the bodies held (``hold(x)``: the
    line statics, energy line search; returns ``(ok, message, iterations, state, x)``), then
    takes a Newton step on the bodies with the exact reduced tangent (the coupled tangent
    with the line dofs condensed out: the Schur complement ``K_bb - K_bl K_ll^-1 K_lb``),
    backtracking on the bodies' out-of-balance force. A slack line gives a body almost no
    stiffness; a monolithic Newton step then throws the line through the seabed, where the
    partitioned one cannot. ``current``: the steady current whose drag the lines carry (the
    one ``hold`` solves with), so that the bodies feel the drag on their nodes' elements.
    ``bodies_held``: only the lines, the bodies held at the case's poses (the start of a
    dynamics from the initial pose).

    Body dofs nothing resists (:mod:`.neutral_dofs`) are held where the case puts them when
    they carry no force (the message names them); with a force there, the result is "no
    static equilibrium", naming the body, the dof and the force.
    """
    problem = CoupledStatics(mesh, exact_cable=True, current=current)  # the lines' law
    poses = BodyState.initial(mesh)
    x = place_slaves(mesh, poses, x)
    if bodies_held or problem.n_unknowns == problem.n_free:  # the lines' solve is the answer
        ok, message, iterations, state, x = hold(x)
        return ok, message, iterations, state, x, poses
    scale = max(problem.model.load_scale(),
                max((b.mass * mesh.gravity for b in problem.bodies), default=0.0))
    tol = max(settings.tolerance * scale, problem.model.roundoff_floor(x))
    policy = NewtonPolicy(tolerance=tol, max_iterations=settings.max_iterations,
                          stiffness_update=1, age_per="iteration", refresh_ratio=None,
                          stall_limit=0, max_halvings=7)
    x, R, state = _equilibrate(problem, x, poses, hold, counters)
    neutral = _neutral(problem, x, poses, state, R, tol)
    if neutral.unbalanced:
        return False, neutral.no_equilibrium(), 0, state, x, poses
    problem.held = problem.held | neutral.held
    R = np.where(problem.held, 0.0, R)
    body_counters = Counters()
    out = newton_solve(_BodyNewton(problem, hold, counters, settings), (x, poses), policy,
                       TangentCache(), body_counters,
                       trial=_CoupledTrial(R[problem.n_free:], R, x, state, (x, poses)))
    counters.residuals += body_counters.residuals
    counters.tangents += body_counters.tangents
    counters.factorizations += body_counters.factorizations
    counters.history.extend(out.history)
    x, poses = out.trial.x, out.u[1]
    if out.converged:
        drift = _held_drift(problem, neutral, out.trial.state, poses, tol)
        if drift:
            return False, f"converged in {out.iterations} body iterations, but {drift}", \
                out.iterations, out.trial.state, x, poses
        return True, (f"converged in {out.iterations} body iterations"
                      f"{neutral.held_note()}"), out.iterations, out.trial.state, x, poses
    return (False, f"coupled statics did not converge in {settings.max_iterations} body "
            f"iterations ({out.reason}): largest out-of-balance force {out.norm:.3e}",
            out.iterations, out.trial.state, x, poses)


def _neutral(problem: CoupledStatics, x: FloatArray, poses: BodyState, state: ForceState,
             R: FloatArray, tol: float) -> NeutralDofs:
    """The free bodies' dofs nothing resists at the start (:mod:`.neutral_dofs`); none when
    the lines' own tangent is singular (the regularized Newton then does what it can)."""
    K = problem.tangent(x, poses, state, regularize=False)
    try:
        S = reduced_stiffness(K, problem.n_free)[0]
    except (np.linalg.LinAlgError, RuntimeError, ValueError):
        return NeutralDofs(np.zeros(problem.n_unknowns, dtype=bool))
    return find_neutral(S, R[problem.n_free:], problem.body_dof, problem.n_free,
                        [b.kind == "free" for b in problem.bodies],
                        [b.name for b in problem.bodies], tol)


def _held_drift(problem: CoupledStatics, neutral: NeutralDofs, state: ForceState,
                poses: BodyState, tol: float) -> str:
    """What is wrong with the held neutral dofs at the solution: the out-of-balance force
    that appeared there while the others were balanced ("" when none)."""
    if not neutral.names:
        return ""
    forces = problem.body_forces(state, poses).ravel()
    first = problem.n_free
    bad = [(name, forces[j - first]) for name, j in
           zip(neutral.names, np.flatnonzero(neutral.held), strict=True)
           if abs(forces[j - first]) > tol]
    return ", ".join(f"{name}, held for having no restoring, carries {f:.4g}"
                     for name, f in bad)


def _equilibrate(problem: CoupledStatics, x: FloatArray, poses: BodyState, hold, counters):
    """Lines in equilibrium with the bodies held at ``poses``; the coupled residual there."""
    x = place_slaves(problem.mesh, poses, x)
    if hold is not None:
        x = hold(x)[4]
    R, state = problem.residual(x, poses)
    counters.residuals += 1
    return x, R, state


def _limit(du: FloatArray, problem: CoupledStatics, settings: StaticsSettings) -> FloatArray:
    """Scale a Newton step so no node or body origin moves more than ``max_step`` times the
    longest line (slack lines give a body almost no stiffness in some direction, and a full
    step would throw it far away), and clip each body's rotation to 0.2 rad on its own (a
    body nearly free to turn, such as the yaw of a buoy on one line, would otherwise hold the
    whole step back), its translation scaled with it: the body's step keeps the Newton
    direction (clipping the rotation alone turns it, and a buoy whose heave and pitch are
    coupled by its waterplane then finds no descent)."""
    mesh = problem.mesh
    reach = settings.max_step * mesh.longest_line
    du = du.copy()
    moves = [np.abs(du[: problem.n_free]).max(initial=0.0) / reach]
    for d in problem.body_dof[problem.body_dof >= 0]:
        turn = np.linalg.norm(du[d + 3:d + 6])
        if turn > 0.2:
            du[d:d + 6] *= 0.2 / turn
        moves.append(np.linalg.norm(du[d:d + 3]) / reach)
    largest = max(moves)
    return du / largest if largest > 1.0 else du
