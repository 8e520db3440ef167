"""Time integration of lines and rigid bodies together (Tuah 1982 sec. 3.3 and 4.2; Wang, Er
and Iu eq. 24-34): one Newton system per step in the free node dofs and the six dofs of every
free body.

Body kinematics: position ``r``, rotation ``R``, velocity ``(v, omega)`` and acceleration
``(a, alpha)`` in world axes. Over a step the body moves by ``dq = (dr, dtheta)`` with
``R1 = exp([dtheta x]) R0`` and Newmark's relations applied to ``dq``. Attached nodes follow:
``x = r + R a``, ``v = v_r + omega x (R a)``, ``a = a_r + alpha x (R a) + omega x (omega x R a)``.
Body equation about its origin (rigid-body inertia with the centre of gravity offset ``c``):

    m (a_r + alpha x c + omega x (omega x c)) = F,
    c x m(...) + I_G alpha + omega x (I_G omega) = M,

plus constant added mass ``A`` and radiation damping ``B`` (Tuah eq. 3.2.c.20), hydrostatics,
gravity, constant and time-varying loads, and the lines' forces through the master-slave
transformation. The Newton matrix is exact for everything but the gyroscopic and centripetal
terms (second order in the angular velocity), which only slow convergence when bodies spin.
Rayleigh damping ``a0 M + a1 K0`` (``K0`` the tangent at the start) is an option.
"""

from __future__ import annotations

import logging
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from numpy.typing import NDArray

from ..mesh import rotation_matrix
from ..model import System
from .assembly import gather_free, scatter_free
from .bodies import BodyDofs, body_loads, long_wave_geometry, skew, transformation
from .dynamic_model import DynamicModel
from .excitation import motion_value

logger = logging.getLogger(__name__)
FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class BodyState:
    """Poses and motions of all bodies (world axes): ``r`` (nb, 3), ``R`` (nb, 3, 3),
    ``vel`` = (v, omega) and ``acc`` = (a, alpha), each (nb, 6)."""

    r: FloatArray
    R: FloatArray
    vel: FloatArray
    acc: FloatArray

    def pose(self) -> FloatArray:
        """(nb, 6): position and rotation vector."""
        from .bodies import rotation_vector

        return np.hstack((self.r, np.array([rotation_vector(R) for R in self.R]).reshape(-1, 3)))


class CoupledStepper:
    """Newmark (beta = 1/4, gamma = 1/2) steps of a system with bodies; same interface as
    :class:`~moorline.solvers.newmark.Stepper`."""

    def __init__(self, system: System, model: DynamicModel, coefficients, tolerance: float,
                 max_iterations: int, stiffness_update: int,
                 rayleigh: tuple[float, float] | None = None,
                 variant: str = "iterative") -> None:
        mesh = model.mesh
        self.model, self.mesh, self.c = model, mesh, coefficients
        self.tol, self.max_iterations = tolerance, max_iterations
        self.stiffness_update = stiffness_update
        self.free = mesh.free_nodes
        self.dof = mesh.dof_of_node
        self.bodies = [system.bodies[n] for n in mesh.body_names]
        layout = BodyDofs.of(mesh, self.bodies)
        self.n_free, self.body_dof, self.n_u = (layout.n_free, layout.body_dof,
                                                layout.n_unknowns)
        self.ext_dofs, self.pattern = layout.ext_dofs, layout.pattern
        self.added = [np.asarray(b.added_mass if b.added_mass is not None else np.zeros((6, 6)),
                                 dtype=float) for b in self.bodies]
        self.damping = [np.asarray(b.damping if b.damping is not None else np.zeros((6, 6)),
                                   dtype=float) for b in self.bodies]
        self.rayleigh = rayleigh
        self._origin0 = [np.asarray(b.position, dtype=float) for b in self.bodies]
        self._exciting: dict[int, tuple | None] = {}
        self.variant = variant  # "iterative"; otherwise one solve per step (residual feedback)
        self.C_rayleigh: sp.csr_matrix | None = None
        self.lu = None
        self.lu_h, self.lu_age = np.nan, 0
        self.counters = {"iterations": 0, "residuals": 0, "tangents": 0, "factorizations": 0}

    # ------------------------------------------------------------------ kinematics
    def _bodies(self, b0: BodyState, dq: FloatArray, h: float) -> BodyState:
        beta, gamma = self.c.beta, self.c.gamma
        acc = (dq - h * b0.vel - h * h * (0.5 - beta) * b0.acc) / (beta * h * h)
        vel = b0.vel + h * ((1 - gamma) * b0.acc + gamma * acc)
        R = np.array([rotation_matrix(d[3:]) @ R0 for d, R0 in zip(dq, b0.R, strict=True)])
        fixed = self.body_dof < 0
        acc[fixed], vel[fixed] = 0.0, 0.0
        return BodyState(b0.r + dq[:, :3], R.reshape(-1, 3, 3), vel, acc)

    def _place(self, x, v, a, bs: BodyState) -> FloatArray:
        m = self.mesh
        if not len(m.slave_node):
            return np.zeros((0, 3))
        b = m.slave_body
        arms = np.einsum("kij,kj->ki", bs.R[b], m.slave_arm)
        w, al = bs.vel[b, 3:], bs.acc[b, 3:]
        x[m.slave_node] = bs.r[b] + arms
        v[m.slave_node] = bs.vel[b, :3] + np.cross(w, arms)
        a[m.slave_node] = bs.acc[b, :3] + np.cross(al, arms) + np.cross(w, np.cross(w, arms))
        return arms

    def _state(self, s0, x1, dq, h, constrained):
        beta, gamma = self.c.beta, self.c.gamma
        a1 = (x1 - s0.x - h * s0.v - h * h * (0.5 - beta) * s0.a) / (beta * h * h)
        v1 = s0.v + h * ((1 - gamma) * s0.a + gamma * a1)
        fixed = ~self.free
        v1[fixed], a1[fixed] = constrained[1], constrained[2]
        bs = self._bodies(s0.bodies, dq, h)
        x1 = x1.copy()
        arms = self._place(x1, v1, a1, bs)
        return x1, v1, a1, bs, arms

    # ------------------------------------------------------------------ residual
    def _residual(self, s0, x1, v1, a1, bs, arms, h, forces, t1, tangent):
        ev = self.model.evaluate(x1, v1, a1, t1, s0.material, h, tangent, forces)
        self.counters["residuals"] += 1
        node = ev.nodal - self.model.node_mass[:, None] * a1
        r = np.zeros(self.n_u)
        r[: self.n_free] = gather_free(node, self.dof)
        m = self.mesh
        for b, body in enumerate(self.bodies):
            d = self.body_dof[b]
            if d < 0:
                continue
            mine = m.slave_body == b
            f = node[m.slave_node[mine]]
            gen, _ = body_loads(body, bs.r[b], bs.R[b], m.gravity, m.water_density)
            gen[:3] += f.sum(axis=0) + self._history(body, t1)
            gen[3:] += np.cross(arms[mine], f).sum(axis=0)
            gen -= self._inertia(body, bs, b) + self.added[b] @ bs.acc[b]
            gen -= self.damping[b] @ bs.vel[b]
            gen[:3] += self._fluid_loads(body, bs, b, t1)[0]
            gen += self._excitation(body, b, t1)
            r[d:d + 6] = gen
        if self.C_rayleigh is not None:
            r -= self.C_rayleigh @ self._velocity(v1, bs)
        return ev, r

    def _velocity(self, v1, bs) -> FloatArray:
        u = np.zeros(self.n_u)
        u[: self.n_free] = gather_free(v1, self.dof)
        for b in range(len(self.bodies)):
            if self.body_dof[b] >= 0:
                u[self.body_dof[b]:self.body_dof[b] + 6] = bs.vel[b]
        return u

    def _fluid_loads(self, body, bs: BodyState, b: int, t: float):
        """Drag on the relative velocity and long-wave excitation at the body origin, with the
        drag's velocity derivative (3, 3)."""
        force, dF_dv = np.zeros(3), np.zeros((3, 3))
        area = np.asarray(body.drag_area, dtype=float)
        if not body.wave_loads and not np.any(area):
            return force, dF_dv
        rho, g = self.mesh.water_density, self.mesh.gravity
        u, a, eta = self.model.fluid.kinematics(bs.r[b][None, :], t)
        if np.any(area):
            rel = u[0] - bs.vel[b, :3]
            force += 0.5 * rho * body.Cd * area * np.abs(rel) * rel
            dF_dv -= np.diag(rho * body.Cd * area * np.abs(rel))
        if body.wave_loads:
            area_wp, volume = long_wave_geometry(body, float(bs.r[b, 2]), rho, g)
            force += rho * volume * a[0] + self.added[b][:3, :3] @ a[0]
            force[2] += rho * g * area_wp * float(eta[0])
        return force, dF_dv

    def _excitation(self, body, b: int, t: float) -> FloatArray:
        """Wave exciting force of the body's table (about its origin, world axes), summed over
        the components of the wave field (a regular wave or a random sea) and ramped like the
        field: ``F_j = sum_m a_m |X_j(w_m)| cos(w_m t - k_m x_0 - phi_m + arg X_j(w_m))`` for
        ``eta = sum_m a_m cos(k_m x - w_m t + phi_m)``, ``x_0`` the body origin's position at
        the start of the run (the static pose) along each component's heading."""
        if body.excitation is None:
            return np.zeros(6)
        if b not in self._exciting:
            self._exciting[b] = _exciting_terms(body.excitation, self.model.fluid,
                                                self._origin0[b])
        terms = self._exciting[b]
        if terms is None:
            return np.zeros(6)
        a, w, shift, amp, phase, ramp_time = terms
        ramp = _ramp(t, ramp_time)
        return ramp * (a[:, None] * amp * np.cos((w * t - shift)[:, None] + phase)).sum(axis=0)

    @staticmethod
    def _history(body, t: float) -> FloatArray:
        history = getattr(body, "force_history", None)
        return motion_value(history, t)[0] if history is not None else np.zeros(3)

    def _inertia(self, body, bs: BodyState, b: int) -> FloatArray:
        """Rigid-body inertia force and moment about the origin (world axes)."""
        R = bs.R[b]
        c = R @ np.asarray(body.center_of_gravity, float)
        I_G = R @ np.asarray(body.inertia, float) @ R.T
        w, al = bs.vel[b, 3:], bs.acc[b, 3:]
        a_G = bs.acc[b, :3] + np.cross(al, c) + np.cross(w, np.cross(w, c))
        F = body.mass * a_G
        M = np.cross(c, F) + I_G @ al + np.cross(w, I_G @ w)
        return np.concatenate((F, M))

    @staticmethod
    def mass_matrix(body, R) -> FloatArray:
        """Rigid-body 6x6 mass about the origin (world axes)."""
        return rigid_mass(body, R)

    # ------------------------------------------------------------------ tangent
    def _tangent(self, ev, bs, arms, h) -> sp.csc_matrix:
        beta, gamma = self.c.beta, self.c.gamma
        ca, cv = 1.0 / (beta * h * h), gamma / (beta * h)
        blocks = ev.K + cv * ev.C + (ca * ev.Ma if ev.Ma is not None else 0.0)
        nodes = ca * self.model.node_mass[:, None, None] * np.eye(3) + ev.node_K + cv * ev.node_C
        if ev.node_M is not None:
            nodes = nodes + ca * ev.node_M
        P = transformation(self.mesh, self.ext_dofs, self.n_free, self.body_dof, arms)
        K = (P.T @ self.pattern.assemble(blocks, nodes) @ P).tolil()
        m = self.mesh
        node = ev.nodal  # the arms of these forces rotate with the body
        for b, body in enumerate(self.bodies):
            d = self.body_dof[b]
            if d < 0:
                continue
            block = body_loads(body, bs.r[b], bs.R[b], m.gravity, m.water_density)[1]
            mine = m.slave_body == b
            for f, arm in zip(node[m.slave_node[mine]], arms[mine], strict=True):
                block[3:, 3:] -= skew(f) @ skew(arm)
            block += ca * (self.mass_matrix(body, bs.R[b]) + self.added[b])
            block += cv * self.damping[b]
            block[:3, :3] -= cv * self._fluid_loads(body, bs, b, self._t)[1]
            K[d:d + 6, d:d + 6] = K[d:d + 6, d:d + 6].toarray() + block
        K = K.tocsc()
        if self.C_rayleigh is not None:
            K = K + cv * self.C_rayleigh
        return K

    def setup_rayleigh(self, s0) -> None:
        """Rayleigh damping ``a0 M + a1 K0`` from the mass and tangent at the start."""
        if self.rayleigh is None:
            return
        a0, a1 = self.rayleigh
        h = 1.0
        x, v, a = s0.x.copy(), np.zeros_like(s0.x), np.zeros_like(s0.x)
        bs = BodyState(s0.bodies.r, s0.bodies.R, np.zeros_like(s0.bodies.vel),
                       np.zeros_like(s0.bodies.acc))
        arms = self._place(x, v, a, bs)
        ev = self.model.evaluate(x, v, a, s0.t, s0.material, h, True, None)
        P = transformation(self.mesh, self.ext_dofs, self.n_free, self.body_dof, arms)
        nodes_m = self.model.node_mass[:, None, None] * np.eye(3)
        if ev.node_M is not None:
            nodes_m = nodes_m + ev.node_M
        M = P.T @ self.pattern.assemble(ev.Ma, nodes_m) @ P
        K = P.T @ self.pattern.assemble(ev.K, ev.node_K) @ P
        M, K = M.tolil(), K.tolil()
        for b, body in enumerate(self.bodies):
            d = self.body_dof[b]
            if d >= 0:
                M[d:d + 6, d:d + 6] = (M[d:d + 6, d:d + 6].toarray()
                                       + self.mass_matrix(body, bs.R[b]) + self.added[b])
                K[d:d + 6, d:d + 6] = (K[d:d + 6, d:d + 6].toarray()
                                       + body_loads(body, bs.r[b], bs.R[b], self.mesh.gravity,
                                                    self.mesh.water_density)[1])
        self.C_rayleigh = (a0 * M.tocsr() + a1 * K.tocsr()).tocsr()

    # ------------------------------------------------------------------ step
    def _apply(self, x1, dq, du):
        x1 = x1 + scatter_free(du[: self.n_free], self.dof)
        dq = dq.copy()
        for b in range(len(self.bodies)):
            d = self.body_dof[b]
            if d >= 0:
                dq[b] += du[d:d + 6]
        return x1, dq

    def step(self, s0, h: float, constrained, point_forces):
        """Advance from ``s0`` by ``h``; returns (state, converged, residual max-norm)."""
        from .newmark import StepState

        if self.C_rayleigh is None and self.rayleigh is not None:
            self.setup_rayleigh(s0)
        if not self._exciting and s0.t == 0.0:  # wave phases refer to the starting position
            self._origin0 = [np.asarray(r, dtype=float).copy() for r in s0.bodies.r]
        t1 = s0.t + h
        self._t = t1
        x1 = s0.x + h * s0.v + 0.5 * h * h * s0.a
        x1[~self.free] = constrained[0]
        dq = h * s0.bodies.vel + 0.5 * h * h * s0.bodies.acc
        refresh = self.lu is None or self.lu_h != h or self.lu_age >= self.stiffness_update
        xs, v1, a1, bs, arms = self._state(s0, x1, dq, h, constrained)
        ev, r = self._residual(s0, xs, v1, a1, bs, arms, h, point_forces, t1, refresh)
        norm = float(np.abs(r).max(initial=0.0))
        one_shot = self.variant != "iterative"
        for it in range(self.max_iterations):
            if norm <= self.tol or (one_shot and it == 1):
                self.lu_age += 1
                return StepState(t1, xs, v1, a1, ev.material, ev, bs), True, norm
            if refresh:
                if ev.K is None:
                    ev, r = self._residual(s0, xs, v1, a1, bs, arms, h, point_forces, t1, True)
                self.lu = spla.splu(self._tangent(ev, bs, arms, h))
                self.lu_h, self.lu_age, refresh = h, 0, False
                self.counters["tangents"] += 1
                self.counters["factorizations"] += 1
            du = self.lu.solve(r)
            self.counters["iterations"] += 1
            merit0, alpha = float(np.linalg.norm(r)), 1.0
            for _ls in range(5):
                x_try, dq_try = self._apply(x1, dq, alpha * du)
                xs_t, v_t, a_t, bs_t, arms_t = self._state(s0, x_try, dq_try, h, constrained)
                ev_t, r_t = self._residual(s0, xs_t, v_t, a_t, bs_t, arms_t, h, point_forces,
                                           t1, False)
                if np.linalg.norm(r_t) < merit0:
                    break
                alpha *= 0.5
            n_new = float(np.abs(r_t).max(initial=0.0))
            refresh = n_new > 0.5 * norm or np.linalg.norm(r_t) >= merit0
            x1, dq, xs, v1, a1, bs, arms, ev, r, norm = (x_try, dq_try, xs_t, v_t, a_t, bs_t,
                                                         arms_t, ev_t, r_t, n_new)
        return s0, False, norm


def rigid_mass(body, R: FloatArray) -> FloatArray:
    """Rigid-body 6x6 mass matrix about the body origin, world axes, for rotation ``R``:
    ``[[m I, -m [c x]], [m [c x], I_G - m [c x]^2]]`` with ``c = R c_body`` the centre of
    gravity offset."""
    c = R @ np.asarray(body.center_of_gravity, float)
    I_G = R @ np.asarray(body.inertia, float) @ R.T
    S = skew(c)
    M = np.zeros((6, 6))
    M[:3, :3] = body.mass * np.eye(3)
    M[:3, 3:] = -body.mass * S
    M[3:, :3] = body.mass * S
    M[3:, 3:] = I_G - body.mass * S @ S
    return M


def _exciting_terms(table, fluid, origin: FloatArray) -> tuple | None:
    """Per wave component: amplitude, frequency, phase shift ``k x_0 + phi``, and the
    table's force amplitude and phase interpolated at its frequency (zero above the table's
    last frequency); ``None`` without waves."""
    wave = getattr(fluid, "wave", fluid)
    if hasattr(wave, "omegas"):
        a, w, phi = wave.amplitudes, wave.omegas, wave.phases
        k, heading = wave.wave_numbers, np.radians(wave.headings_deg)
    elif getattr(wave, "omega", None) is not None:
        a, w, phi = (np.array([wave.amplitude]), np.array([wave.omega]),
                     np.array([float(getattr(wave, "phase", 0.0))]))
        k = np.array([float(wave.wave_number)])
        heading = np.radians(np.array([float(getattr(wave, "heading_deg", 0.0))]))
    else:
        return None
    omegas = np.asarray(table.omegas, dtype=float)
    beyond = (w > omegas[-1]) & (a > 1e-3 * a.max(initial=0.0))
    if np.any(beyond):
        logger.warning("wave components above the exciting-force table's last frequency "
                       "(%.4g rad/s) get no exciting force", omegas[-1])
    amp = np.column_stack([np.interp(w, omegas, np.asarray(table.amplitude)[:, j], right=0.0)
                           for j in range(6)])
    phase = np.radians(np.column_stack([np.interp(w, omegas, np.asarray(table.phase_deg)[:, j])
                                        for j in range(6)]))
    along = origin[0] * np.cos(heading) + origin[1] * np.sin(heading)
    return (np.asarray(a, float), np.asarray(w, float), k * along + phi, amp, phase,
            float(getattr(wave, "ramp_time", 0.0)))


def _ramp(t: float, ramp_time: float) -> float:
    from .excitation import ramp

    return ramp(t, ramp_time)[0]
