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
import scipy.sparse.linalg as spla
from numpy.typing import NDArray

from .assembly import BlockPattern, gather_free, scatter_free
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
        self.dof = mesh.dof_of_node
        self.free = mesh.free_nodes
        self.lu: spla.SuperLU | None = None
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
        K = self.pattern.assemble(blocks, nodes)
        self.lu = spla.splu(K.tocsc())
        self.lu_h, self.lu_age = h, 0
        self.counters["tangents"] += 1
        self.counters["factorizations"] += 1

    def step(self, s0: StepState, h: float, constrained, point_forces) -> tuple[StepState, bool,
                                                                                 float]:
        """Advance from ``s0`` by ``h``. Returns the new state, convergence and the final
        residual max-norm."""
        t1 = s0.t + h
        x1 = s0.x + h * s0.v + 0.5 * h * h * s0.a
        x1[~self.free], v_c, a_c = constrained
        v1, a1 = self._kinematics(s0, x1, h)
        v1[~self.free], a1[~self.free] = v_c, a_c
        refresh = self.lu is None or self.lu_h != h or self.lu_age >= self.stiffness_update
        one_shot = self.variant != "iterative"
        norm, previous_norm = np.inf, np.inf
        for it in range(self.max_iterations + 1):
            need_tangent = refresh
            ev = self.model.evaluate(x1, v1, a1, t1, s0.material, h, need_tangent, point_forces)
            self.counters["residuals"] += 1
            r = self._residual(s0, ev, a1)
            if self.variant == "incremental" and it == 0 and self.carried is not None:
                r = r - self.carried
            norm = float(np.abs(r).max(initial=0.0))
            if not one_shot and norm <= self.tol:
                break
            if one_shot and it == 1:
                break
            if it == self.max_iterations:
                return s0, False, norm
            if refresh or norm > 0.5 * previous_norm:
                if not need_tangent:
                    ev = self.model.evaluate(x1, v1, a1, t1, s0.material, h, True, point_forces)
                self._factorize(ev, h)
                refresh = False
            previous_norm = norm
            dx = scatter_free(self.lu.solve(r), self.dof)
            x1 = x1 + dx
            v1, a1 = self._kinematics(s0, x1, h)
            v1[~self.free], a1[~self.free] = v_c, a_c
            self.counters["iterations"] += 1
        self.lu_age += 1
        if one_shot:
            end = self._residual(s0, ev, a1)
            self.carried = end if self.variant == "incremental" else None
            norm = float(np.abs(end).max(initial=0.0))
        return StepState(t1, x1, v1, a1, ev.material, ev), True, norm
