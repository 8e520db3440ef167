"""Rigid bodies in the time stepper: kinematics of the bodies and their attached nodes, and the
bodies' generalized forces with their exact derivatives (Tuah 1982 sec. 3.2.c and 3.3; Wang,
Er and Iu eq. 24-34).

Body kinematics: position ``r``, rotation ``R``, velocity ``(v, omega)`` and acceleration
``(a, alpha)`` in world axes. Over a step the body moves by ``dq = (dr, dtheta)`` with
``R1 = exp([dtheta x]) R0`` and Newmark's relations applied to ``dq``. Attached nodes follow:
``x = r + R a``, ``v = v_r + omega x (R a)``, ``a = a_r + alpha x (R a) + omega x (omega x R a)``.
Body equation about its origin (rigid-body inertia with the centre of gravity offset ``c``):

    m (a_r + alpha x c + omega x (omega x c)) = F,
    c x m(...) + I_G alpha + omega x (I_G omega) = M,

plus constant added mass ``A`` and radiation damping ``B`` (Tuah eq. 3.2.c.20) or, for a body
with a :class:`~moorline.model.RadiationTable`, the Cummins (1962) radiation force: the
infinite-frequency added mass ``A_inf`` and minus the memory force ``mu = int_0^t K(t - s)
v(s) ds`` (:mod:`moorline.physics.radiation`; its states advance exactly over a step for the
Newmark velocity, linear in time, and ``d mu / d dq = (gamma / (beta h)) d mu / d v1``),
hydrostatics, gravity, constant and time-varying loads, drag, long-wave loads and
exciting-force tables, and the lines' forces through the master-slave transformation. The
physics are the kernels of :mod:`moorline.physics.rigid_body`; the body blocks of the Newton
matrix are exact, the gyroscopic and centripetal terms and the rotation of the inertia
included (the long-wave loads' dependence on the draft aside).

A pinned body moves like a free one but for its origin, which follows its pin
(:meth:`BodyModel.pin_state`): its translational equations are the pin's reaction, held out of
the Newton system by the stepper (:func:`~moorline.solvers.bodies.hold_dofs`), while the
inertia of its prescribed translation enters its rotational equations (``c x m a_pin``; as
MoorDyn-C 2.7 ``Rod::getStateDeriv`` for a pinned rod).

A system without bodies has an empty :class:`BodyModel`: every method is then a no-op, so the
time stepper has one code path.
"""

from __future__ import annotations

import logging
from functools import lru_cache

import numpy as np
from numpy.typing import NDArray

from ..mesh import Mesh
from ..physics import radiation as rad
from ..physics import rigid_body as rb
from .bodies import BodyDofs, BodyState, body_loads, body_mass_matrix, long_wave_geometry, skew
from .excitation import history_value, motion_value, ramp

logger = logging.getLogger(__name__)
FloatArray = NDArray[np.float64]


class BodyModel:
    """The bodies of a mesh (in mesh order) and their loads.

    ``start``: the bodies' state at the start of the run (the static poses); the wave phases
    of exciting-force tables refer to its positions (default: the case's body positions).
    ``radiation_memory``: a body's radiation table as the Cummins equation (its
    infinite-frequency added mass and the memory force); ``False`` leaves both out, for a
    frequency-domain caller that applies ``A(w)`` and ``B(w)`` itself (harmonic balance).
    """

    def __init__(self, mesh: Mesh, fluid, start: BodyState | None = None,
                 radiation_memory: bool = True) -> None:
        self.mesh = mesh
        self.fluid = fluid
        self.bodies = list(mesh.bodies)
        self.layout = BodyDofs.of(mesh, self.bodies)
        self.body_dof = self.layout.body_dof
        self.pinned = self.layout.pinned
        self.memory = [memory_model(b) if radiation_memory else None for b in self.bodies]
        self.added = [_matrix(b.added_mass) if mem is None else mem.added_mass_infinite
                      for b, mem in zip(self.bodies, self.memory, strict=True)]
        # without the memory, a tabulated body has no constant added mass (its caller adds
        # A(w)); Body refuses a table next to constant coefficients, so _matrix gives zeros
        self.damping = [_matrix(b.damping) + _matrix(getattr(b, "additional_damping", None))
                        for b in self.bodies]
        self.origin0 = [np.asarray(b.position, dtype=float) for b in self.bodies]
        self._exciting: dict[int, tuple | None] = {}
        if start is not None:
            self.set_origins(start)

    @property
    def empty(self) -> bool:
        """No bodies."""
        return not self.bodies

    def set_origins(self, state: BodyState) -> None:
        """Wave phases of exciting-force tables refer to the bodies' starting positions."""
        self.origin0 = [np.asarray(r, dtype=float).copy() for r in state.r]
        self._exciting.clear()

    # ------------------------------------------------------------------ kinematics
    def advance(self, b0: BodyState, dq: FloatArray, h: float, beta: float,
                gamma: float, t1: float = 0.0) -> BodyState:
        """Body state after the motion ``dq`` (nb, 6) over a step ``h`` (Newmark) ending at
        ``t1``; a pinned body's origin where its pin is at ``t1`` (whatever ``dq`` says)."""
        pinned = self.pinned
        if pinned.any():
            r, v, a = self.pin_state(t1)
            dq = dq.copy()
            dq[pinned, :3] = r[pinned] - b0.r[pinned]
        acc = (dq - h * b0.vel - h * h * (0.5 - beta) * b0.acc) / (beta * h * h)
        vel = b0.vel + h * ((1 - gamma) * b0.acc + gamma * acc)
        held = self.body_dof < 0
        acc[held], vel[held] = 0.0, 0.0
        if pinned.any():
            vel[pinned, :3], acc[pinned, :3] = v[pinned], a[pinned]
        moved = b0.moved(dq[:, :3], dq[:, 3:])
        return self.layout.place_pins(BodyState(moved.r, moved.R, vel, acc))

    def pin_state(self, t: float) -> tuple[FloatArray, FloatArray, FloatArray]:
        """Position, velocity and acceleration of every pinned body's pin at ``t``
        (:func:`pin_state`)."""
        return pin_state(self.bodies, t)

    def place(self, x: FloatArray, v: FloatArray, a: FloatArray, bs: BodyState) -> FloatArray:
        """Put the attached nodes on their bodies (in place); returns their world arms."""
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

    def kinematic_blocks(self, bs: BodyState, arms: FloatArray, dq: FloatArray, ca: float,
                         cv: float) -> tuple[FloatArray, FloatArray, FloatArray]:
        """How the attached nodes' position, velocity and acceleration change with the step's
        body motion ``dq`` = (dr, phi), ``R = exp([phi x]) R0``, for Newmark's ``d acc / d dq =
        ca``, ``d vel / d dq = cv``: three (n_slaves, 3, 6) blocks, exact (with ``arm = R a``,
        ``d arm = -[arm x] J(phi) d phi``, ``J`` the left Jacobian of the exp map):

            dx = dr + d arm
            dv = cv dr + cv d omega x arm + omega x d arm
            da = ca dr + ca d alpha x arm + alpha x d arm + d omega x (omega x arm)
                 + omega x (d omega x arm) + omega x (omega x d arm)
        """
        return _kinematic_blocks(bs, self.mesh.slave_body, arms, dq, ca, cv)

    def pin_blocks(self, bs: BodyState, dq: FloatArray, ca: float, cv: float
                   ) -> tuple[FloatArray, FloatArray, FloatArray]:
        """:meth:`kinematic_blocks` of every chained pinned body's pin on its host (nb, 3, 6)
        each, zeros for the other bodies: how the pinned body's origin moves with its
        host's step."""
        nb = len(self.bodies)
        out = [np.zeros((nb, 3, 6)) for _ in range(3)]
        chains = self.layout.chains
        if chains:
            child = np.array([c for c, _ in chains])
            host = np.array([p for _, p in chains])
            arms = self.layout.pin_arms(bs)[child]
            for whole, part in zip(out, _kinematic_blocks(bs, host, arms, dq, ca, cv),
                                   strict=True):
                whole[child] = part
        return out[0], out[1], out[2]

    # ------------------------------------------------------------------ radiation memory
    def advance_memory(self, memory: tuple | None, b0: BodyState, b1: BodyState,
                       h: float) -> tuple | None:
        """The radiation memory states (one complex array per body, None for a body without
        a table) after a step ``h`` from ``b0`` to ``b1`` (velocity linear over the step);
        ``memory`` None: at rest. None when no body has a table."""
        if all(mem is None for mem in self.memory):
            return None
        old = memory if memory is not None else (None,) * len(self.memory)
        return tuple(None if mem is None else mem.advance(z, b0.vel[b], b1.vel[b], h)
                     for b, (mem, z) in enumerate(zip(self.memory, old, strict=True)))

    def memory_forces(self, memory: tuple | None) -> FloatArray:
        """The memory forces ``mu`` (nb, 6) of the states (the bodies feel ``-mu``)."""
        out = np.zeros((len(self.bodies), 6))
        if memory is not None:
            for b, (mem, z) in enumerate(zip(self.memory, memory, strict=True)):
                if mem is not None:
                    out[b] = mem.force(z)
        return out

    # ------------------------------------------------------------------ forces
    def forces(self, bs: BodyState, node_other: FloatArray, node_inertial: FloatArray,
               arms: FloatArray, t: float, memory: tuple | None = None
               ) -> tuple[FloatArray, FloatArray]:
        """Generalized forces on the free bodies about their origins, (nb, 6) each: the
        non-inertial part (loads, damping, radiation memory of the states ``memory``, fluid,
        excitation, the attached nodes' forces through ``T^T``) and the inertial part (minus
        rigid-body inertia and added mass, and the attached nodes' inertial forces)."""
        mu = self.memory_forces(memory)
        nb = len(self.bodies)
        other, inertial = np.zeros((nb, 6)), np.zeros((nb, 6))
        m = self.mesh
        for b, body in enumerate(self.bodies):
            if self.body_dof[b] < 0:
                continue
            mine = m.slave_body == b
            arm = arms[mine]
            f_o, f_i = node_other[m.slave_node[mine]], node_inertial[m.slave_node[mine]]
            gen, _ = body_loads(body, bs.r[b], bs.R[b], m.gravity, m.water_density)
            gen[:3] += f_o.sum(axis=0) + _history(body, t)
            gen[3:] += np.cross(arm, f_o).sum(axis=0)
            gen -= self.damping[b] @ bs.vel[b] + mu[b]
            gen[:3] += self._fluid_loads(body, bs, b, t)[0]
            gen += self._excitation(body, b, t)
            other[b] = gen
            ine = -(self._inertia(body, bs, b)[0] + self.added[b] @ bs.acc[b])
            ine[:3] += f_i.sum(axis=0)
            ine[3:] += np.cross(arm, f_i).sum(axis=0)
            inertial[b] = ine
        return other, inertial

    def blocks(self, bs: BodyState, node_forces: FloatArray, arms: FloatArray, t: float,
               ca: float, cv: float, ck: float, dq: FloatArray | None = None,
               h: float | None = None) -> list[FloatArray]:
        """The body blocks (6, 6) of the effective tangent (:meth:`block_parts` combined:
        ``ca J_a + (cv / ck) J_v + J_x``)."""
        return [ca * a + (cv / ck) * v + x for x, v, a in
                self.block_parts(bs, node_forces, arms, t, ck, dq, h)]

    def block_parts(self, bs: BodyState, node_forces: FloatArray, arms: FloatArray,
                    t: float, ck: float, dq: FloatArray | None = None,
                    h: float | None = None) -> list[tuple[FloatArray, FloatArray, FloatArray]]:
        """Per body, the parts ``(J_x, J_v, J_a)`` of its block (6, 6) of the effective
        tangent ``ca M + cv C + ck K`` by what they multiply (the step's change of position,
        of velocity over ``d vel / d dq``, of acceleration over ``d acc / d dq``): rigid mass
        and added mass, damping (with the radiation memory's ``d mu / d v1`` over the step
        ``h``) and drag, hydrostatics, the rotation of the attached nodes' moment arms under
        their forces ``node_forces`` (as weighted in the residual), and the exact derivative
        of the rigid-body inertia (never HHT-weighted): ``ca d_acc + (cv / ck) d_vel +
        d_rot``. Derivatives with respect to a rotation are
        taken for ``R <- exp([e x]) R`` and chained to the step's rotation vector ``dq`` by the
        left Jacobian ``J(dq)``."""
        out = []
        m = self.mesh
        for b, body in enumerate(self.bodies):
            if self.body_dof[b] < 0:
                out.append((np.zeros((6, 6)),) * 3)
                continue
            stiff = body_loads(body, bs.r[b], bs.R[b], m.gravity, m.water_density)[1]
            mine = m.slave_body == b
            arm_terms = np.zeros((6, 6))
            for f, arm in zip(node_forces[m.slave_node[mine]], arms[mine], strict=True):
                arm_terms[3:, 3:] -= skew(f) @ skew(arm)
            damp = self.damping[b].copy()
            if self.memory[b] is not None:
                if h is None:
                    raise ValueError("the radiation memory's tangent needs the step h")
                damp += self.memory[b].velocity_derivative(h)
            damp[:3, :3] -= self._fluid_loads(body, bs, b, t)[1]
            _, d_acc, d_vel, d_rot = self._inertia(body, bs, b)
            turned = ck * stiff + arm_terms + d_rot  # derivatives for R <- exp([e x]) R
            if dq is not None:
                turned[:, 3:] = turned[:, 3:] @ rb.left_jacobian(dq[b, 3:])
            out.append((turned, ck * damp + d_vel, d_acc + self.added[b]))
        return out

    def mass_and_stiffness(self, bs: BodyState) -> list[tuple[FloatArray, FloatArray]]:
        """Per free body: the mass (rigid plus added) and the hydrostatic stiffness at ``bs``
        (for Rayleigh damping)."""
        m = self.mesh
        return [(body_mass_matrix(body, bs.R[b]) + self.added[b],
                 body_loads(body, bs.r[b], bs.R[b], m.gravity, m.water_density)[1])
                for b, body in enumerate(self.bodies)]

    def _inertia(self, body, bs: BodyState, b: int):
        """Rigid-body inertia force and moment about the origin (world axes) and their
        derivatives with respect to acceleration, velocity and rotation
        (:func:`moorline.physics.rigid_body.inertia_load`)."""
        return rb.inertia_load(body.mass, body.center_of_gravity, body.inertia, bs.R[b],
                               bs.vel[b], bs.acc[b])

    def _fluid_loads(self, body, bs: BodyState, b: int, t: float):
        """Drag on the relative velocity and long-wave excitation at the body origin, with the
        drag's velocity derivative (3, 3)."""
        force, dF_dv = np.zeros(3), np.zeros((3, 3))
        area = np.asarray(body.drag_area, dtype=float)
        if not body.wave_loads and not np.any(area):
            return force, dF_dv
        rho, g = self.mesh.water_density, self.mesh.gravity
        u, a, eta = self.fluid.kinematics(bs.r[b][None, :], t)
        if np.any(area):
            drag, dF_dv = rb.body_drag(rho, body.Cd, area, u[0], bs.vel[b, :3])
            force = force + drag
        if body.wave_loads:
            area_wp, volume = long_wave_geometry(body, float(bs.r[b, 2]), rho, g)
            force = force + rb.long_wave_load(rho, g, volume, area_wp, self.added[b][:3, :3],
                                              a[0], float(eta[0]))
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
            self._exciting[b] = _exciting_terms(body.excitation, self.fluid, self.origin0[b])
        terms = self._exciting[b]
        if terms is None:
            return np.zeros(6)
        a, w, shift, amp, phase, ramp_time = terms
        return rb.wave_excitation(t, a, w, shift, amp, phase, ramp(t, ramp_time)[0])


def _kinematic_blocks(bs: BodyState, body: NDArray[np.int64], arms: FloatArray,
                      dq: FloatArray, ca: float, cv: float
                      ) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Position, velocity and acceleration blocks (n, 3, 6) of points at world ``arms`` on
    the bodies ``body`` (:meth:`BodyModel.kinematic_blocks`)."""
    n = len(body)
    bx, bv, ba = (np.zeros((n, 3, 6)) for _ in range(3))
    eye = np.eye(3)
    for k in range(n):
        b = body[k]
        A = skew(arms[k])
        W, Al = skew(bs.vel[b, 3:]), skew(bs.acc[b, 3:])
        d_arm = -A @ rb.left_jacobian(dq[b, 3:])
        bx[k] = np.hstack((eye, d_arm))
        bv[k] = np.hstack((cv * eye, -cv * A + W @ d_arm))
        wa = skew(np.cross(bs.vel[b, 3:], arms[k]))
        ba[k] = np.hstack((ca * eye, -ca * A + Al @ d_arm - cv * (wa + W @ A)
                           + W @ W @ d_arm))
    return bx, bv, ba


def pin_state(bodies, t: float) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Position, velocity and acceleration of every pinned body's pin at ``t`` (nb, 3)
    each: its ``position`` plus its ``motion`` (zeros for the other bodies)."""
    nb = len(bodies)
    r, v, a = np.zeros((nb, 3)), np.zeros((nb, 3)), np.zeros((nb, 3))
    for b, body in enumerate(bodies):
        if body.kind != "pinned":
            continue
        r[b] = body.position
        if body.motion is not None:
            d, dv, da = motion_value(body.motion, t)
            r[b] += d
            v[b], a[b] = dv, da
    return r, v, a


def with_pins(bodies, state: BodyState, t: float) -> BodyState:
    """``state`` with every pinned body's origin, velocity and acceleration those of its
    pin at ``t`` (the start of a run)."""
    pinned = np.array([b.kind == "pinned" for b in bodies], dtype=bool)
    if not pinned.any():
        return state
    r, v, a = pin_state(bodies, t)
    out = state.copy()
    out.r[pinned], out.vel[pinned, :3], out.acc[pinned, :3] = r[pinned], v[pinned], a[pinned]
    return out


def memory_model(body) -> rad.MemoryModel | None:
    """The radiation memory of a body's :class:`~moorline.model.RadiationTable` (None
    without one), fitted once per table (:func:`moorline.physics.radiation.fit_memory`)."""
    table = getattr(body, "radiation", None)
    if table is None:
        return None
    return _fitted(table)  # Body refuses a table with constant added mass or damping


@lru_cache(maxsize=16)
def _fitted(table) -> rad.MemoryModel:
    mem = rad.fit_memory(table.omegas, table.added_mass, table.damping,
                         table.added_mass_infinite)
    worst = float(mem.error.max(initial=0.0))
    if worst > 1e-2:
        logger.warning("radiation memory fit within %.2g %% only (largest entry error over "
                       "the table, MemoryModel.error)", 100 * worst)
    return mem


def _matrix(value) -> FloatArray:
    return np.asarray(value if value is not None else np.zeros((6, 6)), dtype=float)


def _history(body, t: float) -> FloatArray:
    history = getattr(body, "force_history", None)
    return history_value(history, t) if history is not None else np.zeros(3)


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
    amp, phase = rb.exciting_table(omegas, table.amplitude, table.phase_deg, w)
    return (np.asarray(a, float), np.asarray(w, float), rb.wave_shift(k, heading, phi, origin),
            amp, phase, float(getattr(wave, "ramp_time", 0.0)))
