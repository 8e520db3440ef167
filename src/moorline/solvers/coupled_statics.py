"""Static equilibrium of lines and rigid bodies solved together (Tuah 1982 sec. 3.3; Wang, Er
and Iu eq. 31-34): one Newton system in the free node dofs and the six dofs of every free
body, through the master-slave transformation of :mod:`moorline.solvers.bodies`."""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from numpy.typing import NDArray

from ..mesh import Mesh
from ..model import StaticsSettings, System
from .assembly import gather_free, scatter_free
from .bodies import BodyDofs, Poses, body_loads, place_slaves, skew, transformation, world_arms
from .equilibrium import ForceState, StaticModel

FloatArray = NDArray[np.float64]


class CoupledStatics:
    """Residual and exact tangent of the coupled line-body statics."""

    def __init__(self, system: System, mesh: Mesh) -> None:
        self.mesh = mesh
        self.model = StaticModel(mesh)
        self.bodies = [system.bodies[n] for n in mesh.body_names]
        layout = BodyDofs.of(mesh, self.bodies)
        self.n_free, self.body_dof, self.n_unknowns = (layout.n_free, layout.body_dof,
                                                       layout.n_unknowns)
        self.ext_dofs, self.pattern, self.ext_map = layout.ext_dofs, layout.pattern, layout.ext_map

    def residual(self, x: FloatArray, poses: Poses) -> tuple[FloatArray, ForceState]:
        """Out-of-balance forces at the free node dofs, then force and moment on every free
        body (about its origin)."""
        state = self.model.forces(x)
        out = np.zeros(self.n_unknowns)
        out[: self.n_free] = gather_free(state.nodal, self.mesh.dof_of_node)
        arms = world_arms(self.mesh, poses)
        for b, body in enumerate(self.bodies):
            if self.body_dof[b] < 0:
                continue
            mine = self.mesh.slave_body == b
            f = state.nodal[self.mesh.slave_node[mine]]
            generalized, _ = body_loads(body, poses.r[b], poses.R[b], self.mesh.gravity,
                                        self.mesh.water_density)
            generalized[:3] += f.sum(axis=0)
            generalized[3:] += np.cross(arms[mine], f).sum(axis=0)
            out[self.body_dof[b]: self.body_dof[b] + 6] = generalized
        return out, state

    def tangent(self, x: FloatArray, poses: Poses, state: ForceState,
                taut_axial: bool = False):
        """Exact tangent ``-d(residual)/d(unknowns)`` (CSC); ``taut_axial``: see
        :meth:`moorline.solvers.equilibrium.StaticModel.tangent`."""
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
        # a body free to turn about an axis with nothing resisting it (yaw of a buoy on one
        # line) is a mechanism of the statics: a vanishing regularization of the body
        # diagonal keeps the Newton matrix solvable without changing the equilibrium
        body = np.flatnonzero(np.arange(self.n_unknowns) >= self.n_free)
        if body.size:
            scale = 1e-9 * float(np.abs(K.diagonal()).max(initial=1.0))
            K = K + sp.csc_matrix((np.full(body.size, scale), (body, body)), shape=K.shape)
        return K

    def update(self, x: FloatArray, poses: Poses, du: FloatArray) -> tuple[FloatArray, Poses]:
        """Apply a step of the unknowns."""
        x = x + scatter_free(du[: self.n_free], self.mesh.dof_of_node)
        nb = len(self.bodies)
        dr, dtheta = np.zeros((nb, 3)), np.zeros((nb, 3))
        for b in range(nb):
            d = self.body_dof[b]
            if d >= 0:
                dr[b], dtheta[b] = du[d:d + 3], du[d + 3:d + 6]
        poses = poses.moved(dr, dtheta)
        return place_slaves(self.mesh, poses, x), poses


def solve_coupled(system: System, mesh: Mesh, x: FloatArray, settings: StaticsSettings,
                  counters, hold=None) -> tuple[bool, str, int, ForceState, FloatArray, Poses]:
    """Newton on the bodies' six dofs with the lines kept in equilibrium (partitioned).

    Every iteration first equilibrates the lines with the bodies held (``hold``: the robust
    line statics, energy line search), then takes a Newton step on the bodies with the exact
    reduced tangent (the coupled tangent with the line dofs condensed out: the Schur
    complement ``K_bb - K_bl K_ll^-1 K_lb``), backtracking on the bodies' out-of-balance
    force. A slack line gives a body almost no stiffness; a monolithic Newton step then
    throws the line through the seabed, where the partitioned one cannot.
    """
    problem = CoupledStatics(system, mesh)
    poses = Poses.initial(system, mesh)
    x = place_slaves(mesh, poses, x)
    scale = max(problem.model.load_scale(),
                max((b.mass * mesh.gravity for b in problem.bodies), default=0.0))
    tol = max(settings.tolerance * scale, problem.model.roundoff_floor(x))
    n = problem.n_free
    x, R, state = _equilibrate(problem, x, poses, hold, counters)
    for it in range(settings.max_iterations + 1):
        norm = float(np.abs(R).max(initial=0.0))
        counters.history.append(norm)
        if norm <= tol:
            return True, f"converged in {it} body iterations", it, state, x, poses
        if it == settings.max_iterations:
            break
        K = problem.tangent(x, poses, state)
        counters.tangents += 1
        counters.factorizations += 1
        dq = _reduced_step(K, R, n)
        dq = _limit(np.concatenate((np.zeros(n), dq)), problem, settings)[n:]
        merit0, alpha = float(np.linalg.norm(R[n:])), 1.0
        for _ in range(8):
            x_try, p_try = problem.update(x, poses, np.concatenate((np.zeros(n), alpha * dq)))
            x_try, R_try, s_try = _equilibrate(problem, x_try, p_try, hold, counters)
            if np.linalg.norm(R_try[n:]) < merit0:
                break
            alpha *= 0.5
        x, poses, R, state = x_try, p_try, R_try, s_try
    return (False, f"coupled statics did not converge in {settings.max_iterations} body "
            f"iterations: largest out-of-balance force {counters.history[-1]:.3e}",
            settings.max_iterations, state, x, poses)


def _equilibrate(problem: CoupledStatics, x: FloatArray, poses: Poses, hold, counters):
    """Lines in equilibrium with the bodies held at ``poses``; the coupled residual there."""
    x = place_slaves(problem.mesh, poses, x)
    if hold is not None:
        x = hold(x)
    R, state = problem.residual(x, poses)
    counters.residuals += 1
    return x, R, state


def _reduced_step(K, R: FloatArray, n: int) -> FloatArray:
    """Body step from the coupled tangent with the line dofs condensed out."""
    K = K.tocsc()
    K_bb = K[n:, n:].toarray()
    if n == 0:
        return np.linalg.solve(K_bb, R[n:])
    K_bl, K_lb = K[n:, :n].toarray(), K[:n, n:].toarray()
    lu = spla.splu(K[:n, :n].tocsc())
    schur = K_bb - K_bl @ lu.solve(K_lb)
    rhs = R[n:] - K_bl @ lu.solve(R[:n])
    return np.linalg.solve(schur, rhs)


def _limit(du: FloatArray, problem: CoupledStatics, settings: StaticsSettings) -> FloatArray:
    """Scale a Newton step so no node or body origin moves more than ``max_step`` times the
    longest line (slack lines give a body almost no stiffness in some direction, and a full
    step would throw it far away), and clip each body's rotation to 0.2 rad on its own (a
    body nearly free to turn, such as the yaw of a buoy on one line, would otherwise hold the
    whole step back)."""
    mesh = problem.mesh
    longest = max((float(mesh.length0[e].sum()) for e in mesh.line_elements), default=1.0)
    reach = settings.max_step * longest
    du = du.copy()
    moves = [np.abs(du[: problem.n_free]).max(initial=0.0) / reach]
    for d in problem.body_dof[problem.body_dof >= 0]:
        moves.append(np.linalg.norm(du[d:d + 3]) / reach)
        turn = np.linalg.norm(du[d + 3:d + 6])
        if turn > 0.2:
            du[d + 3:d + 6] *= 0.2 / turn
    largest = max(moves)
    return du / largest if largest > 1.0 else du
