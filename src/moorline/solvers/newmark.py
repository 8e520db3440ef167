"""One implicit time step: Newmark (beta = 1/4, gamma = 1/2) or HHT-alpha, with equilibrium
iterations (Tuah 1982, sec. 4.2).

With ``h`` the step, the Newmark relations (Tuah eq. 4.2.7a,b for beta = 1/4, gamma = 1/2)

    a1 = (x1 - x0 - h v0 - h^2 (1/2 - beta) a0) / (beta h^2)
    v1 = v0 + h ((1 - gamma) a0 + gamma a1)

turn the equation of motion into a static-equivalent problem in ``x1`` whose residual is the
effective residual of eq. 4.2.10,

    r = (1 + alpha) F(x1, v1, a1) - alpha F0 - M_s a1      (alpha = 0: Newmark)

(inertia, structural and added, always at the new time; HHT weights the other forces) and
whose tangent is the effective stiffness of eq. 4.2.9a, assembled exactly:

    K_eff = (M_s + M_a) / (beta h^2) + (1 + alpha) (gamma C / (beta h) + K).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from .assembly import BlockPattern, SparseFactor, gather_free, scatter_free
from .dynamic_model import DynamicModel, Evaluation, MaterialState

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class StepState:
    """The state at the end of a completed step."""

    t: float
    x: FloatArray
    v: FloatArray
    a: FloatArray
    material: MaterialState
    evaluation: Evaluation
    bodies: object = None  # coupled_dynamics.BodyState when the system has bodies


@dataclass(frozen=True)
class Coefficients:
    """Newmark/HHT parameters."""

    beta: float
    gamma: float
    alpha: float

    @classmethod
    def for_scheme(cls, scheme: str, alpha: float) -> Coefficients:
        """Average acceleration (``newmark``) or HHT with ``alpha`` in [-1/3, 0]."""
        if scheme == "newmark":
            return cls(0.25, 0.5, 0.0)
        return cls((1 - alpha) ** 2 / 4, 0.5 - alpha, alpha)


class Stepper:
    """Performs steps, keeping the factorized effective tangent between them."""

    def __init__(self, model: DynamicModel, coefficients: Coefficients, variant: str,
                 tolerance: float, max_iterations: int, stiffness_update: int) -> None:
        self.model = model
        self.c = coefficients
        self.variant = variant
        self.tol = tolerance
        self.max_iterations = max_iterations
        self.stiffness_update = stiffness_update
        mesh = model.mesh
        self.pattern = BlockPattern(mesh.elements, mesh.dof_of_node)
        self.factorizer = SparseFactor(self.pattern)
        self.dof = mesh.dof_of_node
        self.free = mesh.free_nodes
        self.lu: SparseFactor | None = None
        self.lu_h = np.nan
        self.lu_age = 0
        self.carried = None  # incremental variant: imbalance left by the previous step
        self.counters = {"iterations": 0, "residuals": 0, "tangents": 0, "factorizations": 0}

    def _kinematics(self, s0: StepState, x1: FloatArray, h: float):
        b, g = self.c.beta, self.c.gamma
        a1 = (x1 - s0.x - h * s0.v - h * h * (0.5 - b) * s0.a) / (b * h * h)
        v1 = s0.v + h * ((1 - g) * s0.a + g * a1)
        return v1, a1

    def _residual(self, s0: StepState, ev: Evaluation, a1: FloatArray) -> FloatArray:
        alpha = self.c.alpha
        m_s = self.model.node_mass[:, None]
        if alpha:
            ev0 = s0.evaluation
            other1 = ev.nodal - ev.inertial
            other0 = ev0.nodal - ev0.inertial
            total = (1 + alpha) * other1 - alpha * other0 + ev.inertial - m_s * a1
        else:
            total = ev.nodal - m_s * a1
        return gather_free(total, self.dof)

    def _factorize(self, ev: Evaluation, h: float) -> None:
        b, g, alpha = self.c.beta, self.c.gamma, self.c.alpha
        ca, cv, ck = 1.0 / (b * h * h), (1 + alpha) * g / (b * h), 1 + alpha
        blocks = ck * ev.K + cv * ev.C
        if ev.Ma is not None:
            blocks = blocks + ca * ev.Ma
        nodes = ca * self.model.node_mass[:, None, None] * np.eye(3)
        nodes = nodes + ck * ev.node_K + cv * ev.node_C
        if ev.node_M is not None:
            nodes = nodes + ca * ev.node_M
        self.lu = self.factorizer.factor(self.pattern.values(blocks, nodes))
        self.lu_h, self.lu_age = h, 0
        self.counters["tangents"] += 1
        self.counters["factorizations"] += 1

    def _trial(self, s0, x1, h, constrained, point_forces, tangent):
        v1, a1 = self._kinematics(s0, x1, h)
        v1[~self.free], a1[~self.free] = constrained[1], constrained[2]
        ev = self.model.evaluate(x1, v1, a1, s0.t + h, s0.material, h, tangent, point_forces)
        self.counters["residuals"] += 1
        r = self._residual(s0, ev, a1)
        return ev, r, float(np.abs(r).max(initial=0.0)), a1

    def _search(self, s0, x1, dx, norm, h, constrained, point_forces, max_halvings=4):
        """Backtrack along ``dx`` until the residual decreases (slack/taut and seabed
        contact switches make the residual non-smooth; a full step can cycle)."""
        alpha, merit0 = 1.0, norm
        for _ in range(max_halvings + 1):
            trial = x1 + alpha * dx
            ev, r, n, a1 = self._trial(s0, trial, h, constrained, point_forces, False)
            merit = float(np.linalg.norm(r))
            if merit < merit0:
                break
            alpha *= 0.5
        return trial, ev, r, n, a1, merit < merit0

    def step(self, s0: StepState, h: float, constrained, point_forces) -> tuple[StepState, bool,
                                                                                 float]:
        """Advance from ``s0`` by ``h``. Returns the new state, convergence and the final
        residual max-norm."""
        x1 = s0.x + h * s0.v + 0.5 * h * h * s0.a
        x1[~self.free] = constrained[0]
        refresh = self.lu is None or self.lu_h != h or self.lu_age >= self.stiffness_update
        ev, r, norm, a1 = self._trial(s0, x1, h, constrained, point_forces, refresh)
        if self.variant == "incremental" and self.carried is not None:
            r = r - self.carried
        if self.variant != "iterative":
            return self._one_shot(s0, x1, h, constrained, point_forces, ev, r, refresh)
        stalled = 0
        for _ in range(self.max_iterations):
            if norm <= self.tol:
                self.lu_age += 1
                return StepState(s0.t + h, x1, *self._kinematics_c(s0, x1, h, constrained),
                                 ev.material, ev), True, norm
            if refresh:
                self._factorize(ev if ev.K is not None else self._trial(
                    s0, x1, h, constrained, point_forces, True)[0], h)
                refresh = False
            dx = scatter_free(self.lu.solve(r), self.dof)
            self.counters["iterations"] += 1
            x_new, ev_new, r_new, n_new, a1, better = self._search(
                s0, x1, dx, float(np.linalg.norm(r)), h, constrained, point_forces)
            if not better and self.lu_age > 0:
                refresh = True  # stale tangent: refresh and retry from the same point
                self.lu_age = 0
                continue
            refresh = refresh or n_new > 0.5 * norm
            stalled = stalled + 1 if n_new > 0.9 * norm else 0
            x1, ev, r, norm = x_new, ev_new, r_new, n_new
            if stalled >= 3:
                break  # not converging (e.g. slack/taut switching): cut the step early
        return s0, False, norm

    def _kinematics_c(self, s0, x1, h, constrained):
        v1, a1 = self._kinematics(s0, x1, h)
        v1[~self.free], a1[~self.free] = constrained[1], constrained[2]
        return v1, a1

    def _one_shot(self, s0, x1, h, constrained, point_forces, ev, r, refresh):
        """Residual feedback / purely incremental: one solve per step, no iteration."""
        if refresh or self.lu is None:
            self._factorize(ev, h)
        x1 = x1 + scatter_free(self.lu.solve(r), self.dof)
        self.counters["iterations"] += 1
        ev, end, norm, _ = self._trial(s0, x1, h, constrained, point_forces, False)
        self.carried = end if self.variant == "incremental" else None
        self.lu_age += 1
        return StepState(s0.t + h, x1, *self._kinematics_c(s0, x1, h, constrained),
                         ev.material, ev), True, norm
