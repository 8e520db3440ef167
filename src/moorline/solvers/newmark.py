"""The implicit time step: Newmark (beta, gamma) or HHT-alpha, with equilibrium iterations or
the source's one-solve variants (Tuah 1982, sec. 4.2), for lines, points and rigid bodies
alike.

With ``h`` the step, the Newmark relations (Tuah eq. 4.2.7a,b; beta = 1/4, gamma = 1/2 there)

    a1 = (x1 - x0 - h v0 - h^2 (1/2 - beta) a0) / (beta h^2)
    v1 = v0 + h ((1 - gamma) a0 + gamma a1)

turn the equation of motion into a static-equivalent problem in the unknowns at the new time
whose residual is the effective residual of eq. 4.2.10,

    r = (1 + alpha) F(x1, v1, a1) - alpha F0 - M_s a1      (alpha = 0: Newmark)

(inertia, structural, added and rigid-body, always at the new time; HHT weights the other
forces) and whose tangent is the effective stiffness of eq. 4.2.9a, assembled exactly:

    K_eff = (M_s + M_a) / (beta h^2) + (1 + alpha) (gamma C / (beta h) + K).

The unknowns are the free node dofs and the six dofs of every free or pinned body (none without
bodies; a pinned body's three translations held at its pin, :func:`.bodies.hold_dofs`);
nodes on bodies are slaves through the master-slave transformation (Tuah eq. 3.3.6-3.3.10),
``P``, and the line tangent is ``P^T K P`` plus the body blocks (:mod:`.body_model`). Rayleigh
damping ``a0 M + a1 K0`` (``M`` and ``K0`` at the start) applies to all unknowns.

Variants: ``iterative`` solves each step by the Newton core (:mod:`.newton`);
``residual_feedback`` makes one solve per step from the full residual (eq. 4.2.10, the error
carried into the next step); ``incremental`` makes one solve per step from the load increment
only (the imbalance left by the previous step is not corrected).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from ..physics.rigid_body import left_jacobian as rb_left_jacobian
from .assembly import BlockPattern, SparseFactor, factorize, gather_free, scatter_free, solve_sparse
from .bodies import BodyState, hold_dofs, transformation
from .body_model import BodyModel
from .dynamic_model import DynamicModel, Evaluation, MaterialState
from .newton import Counters, NewtonPolicy, TangentCache, max_norm, solve

if TYPE_CHECKING:
    import scipy.sparse as sp

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]


@dataclass(frozen=True)
class StepState:
    """The state at the end of a completed step.

    ``body_other`` holds the bodies' non-inertial generalized forces (nb, 6) at this state
    (HHT weights them with the next step's); ``memory`` the radiation memory states of the
    bodies with a radiation table (:meth:`BodyModel.advance_memory`; None: at rest), so a
    repeated or cut step starts from them; ``pin_force`` the force of the pin on every pinned
    body (nb, 3; zeros for the others; None without pinned bodies): minus the translational
    residual of its body equation, inertia included (with HHT, of the weighted equation).
    """

    t: float
    x: FloatArray
    v: FloatArray
    a: FloatArray
    material: MaterialState
    evaluation: Evaluation
    bodies: BodyState | None = None
    body_other: FloatArray | None = None
    memory: tuple | None = None
    pin_force: FloatArray | None = None


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


@dataclass
class _Trial:
    """One evaluation of the step's residual."""

    r: FloatArray
    x: FloatArray
    v: FloatArray
    a: FloatArray
    bodies: BodyState | None
    arms: FloatArray
    ev: Evaluation
    body_other: FloatArray | None
    node_forces: FloatArray | None  # (n_nodes, 3) nodal forces as weighted in the residual,
    #                                 which attached nodes pass to their bodies (with bodies
    #                                 or HHT; else None)
    memory: tuple | None = None  # the bodies' radiation memory states at the trial
    pin_force: FloatArray | None = None  # (nb, 3) force of the pins on pinned bodies

    @property
    def has_tangent(self) -> bool:
        return self.ev.K is not None


@dataclass(frozen=True)
class _Step:
    """What one step's residual depends on besides the unknowns."""

    s0: StepState
    h: float
    constrained: tuple
    point_forces: FloatArray | None


class Stepper:
    """Performs steps, keeping the factored effective tangent between them.

    Parameters
    ----------
    model
        Forces of lines and points (:class:`~moorline.solvers.dynamic_model.DynamicModel`).
    coefficients
        Newmark/HHT parameters.
    variant
        ``iterative``, ``residual_feedback`` or ``incremental``.
    policy
        Newton constants (tolerance, iterations, refresh rule).
    bodies
        The rigid bodies (:class:`~moorline.solvers.body_model.BodyModel`); default none.
    rayleigh
        ``(a0, a1)`` of Rayleigh damping, or ``None``.
    """

    def __init__(self, model: DynamicModel, coefficients: Coefficients, variant: str,
                 policy: NewtonPolicy, bodies: BodyModel | None = None,
                 rayleigh: tuple[float, float] | None = None) -> None:
        self.model = model
        self.c = coefficients
        self.variant = variant
        self.policy = policy
        mesh = model.mesh
        self.bodies = bodies if bodies is not None else BodyModel(mesh, model.fluid)
        layout = self.bodies.layout
        self.layout = layout
        self.pattern = layout.pattern
        self.coupled = len(mesh.slave_node) > 0 or not self.bodies.empty
        # no unknowns (every node prescribed, e.g. one segment between a fixed and a coupled
        # point): nothing to factorize, each step only evaluates the forces
        self.factorizer = (None if self.coupled or layout.n_unknowns == 0
                           else SparseFactor(self.pattern))
        self.dof = mesh.dof_of_node
        self.free = mesh.free_nodes
        self.rayleigh = rayleigh
        self.C_rayleigh: sp.csr_matrix | None = None
        self.cache = TangentCache()
        self.work = Counters()
        self.carried = None  # incremental variant: imbalance left by the previous step

    @property
    def counters(self) -> dict[str, int]:
        """Iterations, residual evaluations, tangents and factorizations so far."""
        return self.work.as_dict()

    def forget_tangent(self) -> None:
        """Drop the factorization (after a step cut)."""
        self.cache.forget()

    def tangent_state(self) -> tuple:
        """The reused factorization, its age and key (and the incremental variant's carried
        imbalance): with :meth:`set_tangent_state`, a step repeated from a restored state
        (a predictor-corrector host, :mod:`moorline.coupling`) repeats the same iterations."""
        c = self.cache
        return c.factor, getattr(c.factor, "_lu", None), c.age, c.key, self.carried

    def set_tangent_state(self, saved: tuple) -> None:
        """Restore what :meth:`tangent_state` returned."""
        factor, lu, age, key, carried = saved
        if lu is not None:  # a SparseFactor refactorizes in place: put its factors back
            factor._lu = lu
        self.cache.factor, self.cache.age, self.cache.key = factor, age, key
        self.carried = carried

    # ------------------------------------------------------------------ Newton problem
    def residual(self, u: tuple[FloatArray, FloatArray], tangent: bool) -> _Trial:
        """Effective residual (eq. 4.2.10) at unknowns ``u = (x1, dq)``."""
        st = self._current
        s0, h = st.s0, st.h
        x1, dq = u
        b, g, alpha = self.c.beta, self.c.gamma, self.c.alpha
        a1 = (x1 - s0.x - h * s0.v - h * h * (0.5 - b) * s0.a) / (b * h * h)
        v1 = s0.v + h * ((1 - g) * s0.a + g * a1)
        fixed = ~self.free
        v1[fixed], a1[fixed] = st.constrained[1], st.constrained[2]
        bs, arms, memory = None, np.zeros((0, 3)), None
        if s0.bodies is not None:
            bs = self.bodies.advance(s0.bodies, dq, h, b, g, s0.t + h)
            memory = self.bodies.advance_memory(s0.memory, s0.bodies, bs, h)
            x1 = x1.copy()
            arms = self.bodies.place(x1, v1, a1, bs)
        t1 = s0.t + h
        ev = self.model.evaluate(x1, v1, a1, t1, s0.material, h, tangent, st.point_forces)
        m_s = self.model.node_mass[:, None]
        node_forces = None
        if alpha or bs is not None:  # HHT weights the non-inertial forces; bodies get both
            other = ev.nodal - ev.inertial
            inertial = ev.inertial - m_s * a1
            node_forces = (1 + alpha) * other + inertial
        if alpha:
            ev0 = s0.evaluation
            node = (1 + alpha) * other - alpha * (ev0.nodal - ev0.inertial) + inertial
        else:
            node = ev.nodal - m_s * a1
        r = np.zeros(self.layout.n_unknowns)
        r[: self.layout.n_free] = gather_free(node, self.dof)
        body_other = None
        if bs is not None:
            body_other, body_inertial = self.bodies.forces(bs, other, inertial, arms, t1,
                                                           memory)
            weighted = body_other if not alpha else ((1 + alpha) * body_other
                                                     - alpha * self._body_other(s0))
            for k, d in enumerate(self.bodies.body_dof):
                if d >= 0:
                    r[d:d + 6] = weighted[k] + body_inertial[k]
        pin_force = None
        if self.layout.held.any():  # a pinned body's translational rows: the pin's reaction
            pin_force = np.zeros((len(self.bodies.bodies), 3))
            for k in np.flatnonzero(self.layout.pinned):
                d = self.bodies.body_dof[k]
                pin_force[k] = -r[d:d + 3]
            self.layout.transfer(r, self.layout.pin_arms(bs))  # a pin on a host: onto it
        if self.C_rayleigh is not None:
            damping = self.C_rayleigh @ self._velocity(v1, bs)
            if alpha:
                damping = (1 + alpha) * damping - alpha * (self.C_rayleigh
                                                           @ self._velocity(s0.v, s0.bodies))
            r -= damping
        r[self.layout.held] = 0.0
        return _Trial(r, x1, v1, a1, bs, arms, ev, body_other, node_forces, memory,
                      pin_force)

    def factorize(self, u, trial: _Trial):
        """Factorization of the effective tangent (eq. 4.2.9a) at the trial."""
        if not self.coupled:
            return self.factorizer.factor(self._tangent_data(trial))
        return factorize(self.tangent_matrix(u, trial))

    def tangent_matrix(self, u, trial: _Trial) -> sp.csr_matrix:
        """The effective tangent ``-dr/du`` (eq. 4.2.9a) at the trial, assembled."""
        import scipy.sparse as sp

        if not self.coupled:
            p = self.pattern
            return sp.csr_matrix((self._tangent_data(trial), p.indices, p.indptr),
                                 shape=(p.n, p.n))
        h = self._current.h
        ca, cv, ck = self._factors(h)
        cv1 = cv / ck  # d vel / d u (Newmark), not HHT-weighted
        ev, arms = trial.ev, trial.arms
        K = self.pattern.assemble(_hht_stiffness(ev, ck), ev.node_K)
        C = self.pattern.assemble(ev.C, ev.node_C)
        nodes_m = self.model.node_mass[:, None, None] * np.eye(3)
        if ev.node_M is not None:
            nodes_m = nodes_m + ev.node_M
        M = self.pattern.assemble(ev.Ma, nodes_m)
        bx, bv, ba = self.bodies.kinematic_blocks(trial.bodies, arms, u[1], ca, cv1)
        Px, Pv, Pa = (self._map(arms, blocks, scale)
                      for blocks, scale in ((bx, 1.0), (bv, cv1), (ba, ca)))
        T = self._map(arms)
        parts = self.bodies.block_parts(trial.bodies, trial.node_forces, arms,
                                        self._current.s0.t + h, ck, u[1], h)
        by_rate = [T.T @ (ck * K @ Px) + self._body_matrix([p[0] for p in parts]),
                   T.T @ (ck * C @ Pv) + self._body_matrix([cv1 * p[1] for p in parts]),
                   T.T @ (M @ Pa) + self._body_matrix([ca * p[2] for p in parts])]
        if self.layout.chains:
            out = self._chained(by_rate, trial, u[1], ca, cv1)
        else:
            out = by_rate[0] + by_rate[1] + by_rate[2]
        if self.C_rayleigh is not None:
            out = out + cv * self.C_rayleigh
        if self.layout.held.any():
            out = hold_dofs(out, self.layout.held, float(np.abs(out.diagonal()).max()))
        return out.tocsr()

    def _chained(self, by_rate: list, trial: _Trial, dq: FloatArray, ca: float,
                 cv1: float) -> sp.csr_matrix:
        """The tangent with every chained pinned body's translation following its host's
        pin (Newmark: its position, velocity and acceleration by the pin's kinematic blocks
        on the host's step, columns of ``by_rate`` for position, velocity and acceleration),
        its translational force moved onto the host (``T^T``) and the host's pin arm turning
        under it (``-[F x][R_p a x] J(dq_p)``)."""
        lay = self.layout
        bs = trial.bodies
        pins = lay.pin_arms(bs)
        bx, bv, ba = self.bodies.pin_blocks(bs, dq, ca, cv1)
        maps = (lay.chain_map(pins, bx), lay.chain_map(pins, bv / cv1),
                lay.chain_map(pins, ba / ca))
        full = self._untransferred(trial)
        turning = lay.arm_turning(full, pins).tolil()
        for _, p in lay.chains:
            d = lay.body_dof[p] + 3
            block = turning[d:d + 3, d:d + 3].toarray() @ rb_left_jacobian(dq[p, 3:])
            turning[d:d + 3, d:d + 3] = block
        out = by_rate[0] @ maps[0] + by_rate[1] @ maps[1] + by_rate[2] @ maps[2]
        return (lay.chain_map(pins).T @ out + turning.tocsr()).tocsr()

    def _untransferred(self, trial: _Trial) -> FloatArray:
        """The trial's residual with the chained pinned bodies' translational forces back in
        their own rows (minus their pin forces)."""
        r = np.zeros(self.layout.n_unknowns)
        for c, _ in self.layout.chains:
            d = self.layout.body_dof[c]
            r[d:d + 3] = -trial.pin_force[c]
        return r

    def _factors(self, h: float) -> tuple[float, float, float]:
        """``(1 / (beta h^2), (1 + alpha) gamma / (beta h), 1 + alpha)``."""
        b, g, alpha = self.c.beta, self.c.gamma, self.c.alpha
        return 1.0 / (b * h * h), (1 + alpha) * g / (b * h), 1 + alpha

    def _line_blocks(self, ev: Evaluation, ca: float, cv: float, ck: float):
        blocks = ck * _hht_stiffness(ev, ck) + cv * ev.C
        if ev.Ma is not None:
            blocks = blocks + ca * ev.Ma
        nodes = ca * self.model.node_mass[:, None, None] * np.eye(3)
        nodes = nodes + ck * ev.node_K + cv * ev.node_C
        if ev.node_M is not None:
            nodes = nodes + ca * ev.node_M
        return blocks, nodes

    def _tangent_data(self, trial: _Trial) -> FloatArray:
        ca, cv, ck = self._factors(self._current.h)
        data = self.pattern.values(*self._line_blocks(trial.ev, ca, cv, ck))
        if self.C_rayleigh is not None:
            data = data + cv * self._rayleigh_data
        return data

    def update(self, u, du: FloatArray):
        """Unknowns after the step ``du``."""
        x1, dq = u
        du = np.where(self.layout.held, 0.0, du)  # a pinned body's translations follow its pin
        x1 = x1 + scatter_free(du[: self.layout.n_free], self.dof)
        if len(dq):
            dq = dq.copy()
            for k, d in enumerate(self.bodies.body_dof):
                if d >= 0:
                    dq[k] += du[d:d + 6]
        return x1, dq

    def local_window(self, trial: _Trial, threshold: float, pad: int, share: float
                     ) -> IntArray | None:
        """The unknowns of the local phase's window (:mod:`.newton`): the free nodes whose
        residual (max over their three dofs) exceeds ``threshold``, padded by ``pad`` rings
        of elements; None with bodies or slave nodes, or when the window has more than
        ``share`` of the free nodes."""
        if self.coupled:
            return None
        mesh = self.model.mesh
        el = mesh.elements
        node_r = np.zeros(mesh.n_nodes)
        node_r[self.free] = np.abs(trial.r[self.dof[self.free]]).max(axis=1)
        mark = node_r > threshold
        for _ in range(pad):
            mark[el[mark[el].any(axis=1)]] = True
        mark &= self.free
        count = int(mark.sum())
        if count == 0 or count > share * int(self.free.sum()):
            return None
        return self.dof[mark].ravel()

    def local_step(self, u, trial: _Trial, window: IntArray) -> FloatArray:
        """The step of the window's unknowns from their rows and columns of the effective
        tangent at ``trial`` (zero elsewhere)."""
        import scipy.sparse.linalg as spla

        K = self.tangent_matrix(u, trial).tocsc()[window][:, window]
        du = np.zeros(self.layout.n_unknowns)
        du[window] = spla.spsolve(K.tocsc(), trial.r[window])
        return du

    # ------------------------------------------------------------------ the step
    def step(self, s0: StepState, h: float, constrained, point_forces
             ) -> tuple[StepState, bool, float]:
        """Advance from ``s0`` by ``h``. Returns the new state (``s0`` when the step failed),
        convergence and the final residual max-norm."""
        if self.rayleigh is not None and self.C_rayleigh is None:
            self._setup_rayleigh(s0)
        self._current = _Step(s0, h, constrained, point_forces)
        u = self._predict(s0, h, constrained)
        if self.variant != "iterative":
            return self._one_shot(u, h)
        out = solve(self, u, self.policy, self.cache, self.work, key=h)
        if not out.converged:
            return s0, False, out.norm
        return self._state(out.trial), True, out.norm

    def _state(self, trial: _Trial) -> StepState:
        st = self._current
        return StepState(st.s0.t + st.h, trial.x, trial.v, trial.a, trial.ev.material,
                         trial.ev, trial.bodies, trial.body_other, trial.memory,
                         trial.pin_force)

    def _one_shot(self, u, h: float) -> tuple[StepState, bool, float]:
        """Residual feedback / purely incremental: one solve per step, no iteration."""
        refresh = self.cache.needs_refresh(self.policy, h)
        self.work.residuals += 1
        trial = self.residual(u, refresh)
        r = trial.r
        if self.variant == "incremental" and self.carried is not None:
            r = r - self.carried
        if refresh:
            if not trial.has_tangent:
                trial = self.residual(u, True)
                self.work.residuals += 1
            self.cache.factor, self.cache.age, self.cache.key = self.factorize(u, trial), 0, h
            self.work.tangents += 1
            self.work.factorizations += 1
        u = self.update(u, self.cache.factor.solve(r))
        self.work.iterations += 1
        end = self.residual(u, False)
        self.work.residuals += 1
        self.carried = end.r if self.variant == "incremental" else None
        self.cache.age += 1
        return self._state(end), True, max_norm(end.r)

    # ------------------------------------------------------------------ pieces
    def _map(self, arms: FloatArray, blocks: FloatArray | None = None,
             scale: float = 1.0) -> sp.csr_matrix:
        """Map from the unknowns to the extended node dofs (master-slave, Tuah eq. 3.3.6)."""
        lay = self.layout
        return transformation(self.model.mesh, lay.ext_dofs, lay.n_free, lay.body_dof, arms,
                              blocks, scale)

    def _transform(self, K: sp.csr_matrix, arms: FloatArray) -> sp.csr_matrix:
        """``P^T K P``: a matrix over the extended dofs onto the unknowns."""
        P = self._map(arms)
        return (P.T @ K @ P).tocsr()

    def _body_matrix(self, blocks: list[FloatArray]) -> sp.csr_matrix:
        """The body blocks as a sparse matrix over the unknowns."""
        import scipy.sparse as sp

        n = self.layout.n_unknowns
        rows, cols, vals = [], [], []
        for d, block in zip(self.bodies.body_dof, blocks, strict=True):
            if d < 0:
                continue
            i, j = np.meshgrid(np.arange(6) + d, np.arange(6) + d, indexing="ij")
            rows.append(i.ravel())
            cols.append(j.ravel())
            vals.append(block.ravel())
        if not rows:
            return sp.csr_matrix((n, n))
        return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows),
                                                    np.concatenate(cols))), shape=(n, n))

    def _velocity(self, v: FloatArray, bs: BodyState | None) -> FloatArray:
        u = np.zeros(self.layout.n_unknowns)
        u[: self.layout.n_free] = gather_free(v, self.dof)
        if bs is not None:
            for k, d in enumerate(self.bodies.body_dof):
                if d >= 0:
                    u[d:d + 6] = bs.vel[k]
        return u

    def _body_other(self, s0: StepState) -> FloatArray:
        """The bodies' non-inertial forces at a completed state (HHT)."""
        if s0.body_other is not None:
            return s0.body_other
        x, v, a = s0.x.copy(), s0.v.copy(), s0.a.copy()
        arms = self.bodies.place(x, v, a, s0.bodies)
        ev = s0.evaluation
        m_s = self.model.node_mass[:, None]
        return self.bodies.forces(s0.bodies, ev.nodal - ev.inertial, ev.inertial - m_s * a,
                                  arms, s0.t, s0.memory)[0]

    def _setup_rayleigh(self, s0: StepState) -> None:
        """Rayleigh damping ``a0 M + a1 K0`` from the mass and tangent at the start."""
        import scipy.sparse as sp

        a0, a1 = self.rayleigh
        x, v, a = s0.x.copy(), np.zeros_like(s0.x), np.zeros_like(s0.x)
        bs, arms = None, np.zeros((0, 3))
        if s0.bodies is not None:
            bs = BodyState(s0.bodies.r, s0.bodies.R)
            arms = self.bodies.place(x, v, a, bs)
        ev = self.model.evaluate(x, v, a, s0.t, s0.material, 1.0, True, None)
        nodes_m = self.model.node_mass[:, None, None] * np.eye(3)
        if ev.node_M is not None:
            nodes_m = nodes_m + ev.node_M
        if not self.coupled:
            self._rayleigh_data = (a0 * self.pattern.values(ev.Ma, nodes_m)
                                   + a1 * self.pattern.values(ev.K, ev.node_K))
            p = self.pattern
            self.C_rayleigh = sp.csr_matrix((self._rayleigh_data, p.indices, p.indptr),
                                            shape=(p.n, p.n))
            return
        M = self._transform(self.pattern.assemble(ev.Ma, nodes_m), arms)
        K = self._transform(self.pattern.assemble(ev.K, ev.node_K), arms)
        pairs = self.bodies.mass_and_stiffness(bs)
        M = M + self._body_matrix([p[0] for p in pairs])
        K = K + self._body_matrix([p[1] for p in pairs])
        keep = sp.diags((~self.layout.held).astype(float))  # a pin's translations: none
        self.C_rayleigh = (keep @ (a0 * M + a1 * K) @ keep).tocsr()

    def worst_dof(self, state: StepState, h: float, constrained, forces) -> int:
        """The unknown with the largest residual at the predicted state (for messages)."""
        self._current = _Step(state, h, constrained, forces)
        return int(np.argmax(np.abs(self.residual(self._predict(state, h, constrained),
                                                  False).r)))

    def _predict(self, s0: StepState, h: float, constrained) -> tuple[FloatArray, FloatArray]:
        """The unknowns' predictor: the nodes at ``x0 + h v0`` (constrained nodes where their
        motion puts them), the bodies' step ``dq = h v0 + h^2 a0 / 2``.

        The nodes' predictor leaves out ``h^2 a0 / 2``: under the trapezoidal rule the stiff
        axial modes of a cable, which dominate the residual, alternate the sign of their
        acceleration from step to step, so carrying ``a0`` forward predicts them on the wrong
        side (on a 1,000-element OC3 line snapping near touchdown the first residual was
        ~50 times the line's tension); the term is of order ``h^2`` for the slow motions
        (issue 16: 2.3x fewer iterations there, none more on smooth runs)."""
        x1 = s0.x + h * s0.v
        x1[~self.free] = constrained[0]
        dq = (h * s0.bodies.vel + 0.5 * h * h * s0.bodies.acc if s0.bodies is not None
              else np.zeros((0, 6)))
        return x1, dq


def _hht_stiffness(ev: Evaluation, ck: float) -> FloatArray:
    """The element blocks ``K`` with HHT's weights as ``ck K`` will apply them: the
    added-mass forces' part ``Ka`` (inertial, weighted 1 in the residual) scaled by
    ``1 / ck`` (``ck = 1 + alpha``), the rest left (weighted ``1 + alpha``)."""
    if ck == 1.0 or ev.Ka is None:
        return ev.K
    return ev.K - (1.0 - 1.0 / ck) * ev.Ka


def accelerated(model: DynamicModel, state: StepState, material: MaterialState,
                point_forces: FloatArray | None, dt: float) -> StepState:
    """``state`` with the accelerations its loads give: ``M a = F`` over the free node dofs
    (Tuah (1982) eq. 4.2.1 at the start of a run; unknowns without mass, weightless strings,
    start at ``a = 0``); ``material``: the elements' state before the start.

    Systems with bodies start at rest (``a = 0``, as the source's examples, which start from
    the static equilibrium with ramped loads): there, the static solve's residue (its
    tolerance) would otherwise seed motions that some of the verification rows measure (the
    round-off growth of Ex7's sway).
    """
    mesh = model.mesh
    x, v, a = state.x.copy(), state.v.copy(), state.a.copy()
    bs = state.bodies
    if bs is not None:
        return StepState(state.t, x, v, np.zeros_like(a), state.material, state.evaluation, bs)
    ev = model.evaluate(x, v, a, state.t, material, dt, True, point_forces)
    nodes_m = model.node_mass[:, None, None] * np.eye(3)
    if ev.node_M is not None:
        nodes_m = nodes_m + ev.node_M
    pattern = BlockPattern(mesh.pattern_pairs, mesh.dof_of_node)
    values = pattern.values(ev.Ma, nodes_m)
    massive = pattern.diagonal(values) > 0
    if not np.any(massive):
        return StepState(state.t, x, v, a, ev.material, ev)
    rhs = gather_free(ev.nodal, mesh.dof_of_node)
    acc = np.zeros(mesh.n_dofs)
    if massive.all():  # factored once: in Python when small (band_lu), no scipy
        acc = SparseFactor.for_few_solves(pattern).factor(values).solve(rhs)
    else:
        M = pattern.csr(values).tocsc()
        acc[massive] = solve_sparse(M[massive][:, massive], rhs[massive])
    a = a + scatter_free(acc, mesh.dof_of_node)
    ev = model.evaluate(x, v, a, state.t, material, dt, False, point_forces)
    return StepState(state.t, x, v, a, ev.material, ev, bs)

