"""Free rigid bodies in the compiled time step (:func:`moorline.solvers.fast_newmark.newmark_step`):
the same unknowns, residual and exact tangent as :class:`moorline.solvers.newmark.Stepper` with
a :class:`~moorline.solvers.body_model.BodyModel`, for the loads of
:data:`moorline.solvers.fast_path.HULL_KINDS` (see
:func:`~moorline.solvers.fast_path.body_refusal` for what keeps the general stepper).

A body's unknowns are its step ``dq = (dr, phi)`` (``R1 = exp([phi x]) R0``, Newmark's
relations on ``dq``; predictor ``h v0 + h^2 a0 / 2``); the nodes attached to it follow
(``x = r + R a``, Tuah 1982 eq. 3.3.6-3.3.7) and pass it their forces through ``T^T``,
``T = [I, -[R a x]]``. The lines' effective tangent keeps its band (free nodes, reverse
Cuthill-McKee order); the ``6 nb`` body unknowns border it:

    [A  B] [dx]   [r_l]
    [C  D] [dq] = [r_b]

``B`` (the free rows' coupling to the attached nodes, through the kinematic blocks of
:meth:`BodyModel.kinematic_blocks`), ``C`` (the attached rows, through ``T^T``), ``D`` (the
body blocks of :meth:`BodyModel.block_parts` and the attached nodes' own terms). A
factorization is the banded LU of ``A``, ``A^-1 B`` (``6 nb`` band solves) and the inverse of
the Schur complement ``S = D - C A^-1 B`` (``6 nb`` square); a solve is one band solve, and
``dq = S^-1 (r_b - C y)``, ``dx = y - A^-1 B dq``. The cost stays that of the band.

``bodies`` = ``(links, loads, state, forces, work, memory, pins)``: the attached nodes
(node, body, body-frame arm, the attached index of every node or -1); the bodies' constants
(:func:`moorline.solvers.fast_rigid.static_load`); the state (start of the step ``r0, R0,
vel0, acc0``, the step ``dq`` and its line-search trial, the evaluated state ``r1, R1, vel1,
acc1``, the attached nodes' world arms and weighted forces, the non-inertial generalized
forces at the start of the step and at the evaluated state for HHT); the loads that depend
on time alone per sub-step (force histories, exciting-force tables; ``(n_sub, nb, 6)``) and
the current at the body origins for their drag (``(n_sub, nb, 3)`` more); the
factorization (``(A^-1 B)^T``, ``C``, ``D``, ``S^-1``); the radiation memory of the bodies
with a radiation table (Cummins 1962, :class:`moorline.physics.radiation.MemoryModel`: every
mode's body, force and velocity dof, pole and coefficient; the complex states at the start of
the step and at the evaluated state, and the step weight ``h phi_2(p h)`` of the mode's end
velocity, :func:`advance_memory`; no modes without a table); the pinned bodies (which, the
position, velocity and acceleration of every pin per sub-step (n_sub, nb, 3, 3), the sub-step,
the pins' forces at the evaluated state and at the start of the step). A pinned body's origin
follows its pin (:meth:`BodyModel.advance`): its translational rows are the pin's force, held
out of the system (:func:`moorline.solvers.bodies.hold_dofs`). Without bodies ``bodies`` is None:
every function here returns at once, and numba prunes the rest, so a model without bodies
does not compile the bodies' code.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from ..jit import numba
from ..physics.fused import hht_stiffness
from .fast_rigid import (
    cross,
    drag_load,
    inertia_load,
    left_jacobian,
    mm,
    mv,
    rigid_mass,
    rotation_matrix,
    skew,
    static_load,
)

FloatArray = NDArray[np.float64]
_JIT = {"cache": True, "fastmath": False, "error_model": "numpy"}


@numba.njit(**_JIT)
def predict(bodies, h, j):
    """The bodies' predictor ``dq = h v0 + h^2 a0 / 2`` (:meth:`Stepper._predict`) for
    sub-step ``j``."""
    if bodies is None:  # no bodies: not compiled in
        return
    bodies[6][2][0] = j
    state = bodies[2]
    vel0, acc0, dq = state[2], state[3], state[4]
    for b in range(dq.shape[0]):
        for i in range(6):
            dq[b, i] = h * vel0[b, i] + 0.5 * h * h * acc0[b, i]


@numba.njit(**_JIT)
def place(bodies, trial, h, beta, gamma, x, v, a):
    """The bodies after the step (``trial``: its line-search trial) and their attached
    nodes on them (in ``x, v, a``) (:meth:`BodyModel.advance`, :meth:`BodyModel.place`)."""
    if bodies is None:  # no bodies: not compiled in
        return
    slave_node, slave_body, slave_arm = bodies[0][0], bodies[0][1], bodies[0][2]
    r0, R0, vel0, acc0, dq_now, dq_try, r1, R1, vel1, acc1, arms = bodies[2][:11]
    dq = dq_try if trial else dq_now
    for b in range(dq.shape[0]):
        for i in range(6):
            acc = (dq[b, i] - h * vel0[b, i] - h * h * (0.5 - beta) * acc0[b, i]) \
                / (beta * h * h)
            acc1[b, i] = acc
            vel1[b, i] = vel0[b, i] + h * ((1.0 - gamma) * acc0[b, i] + gamma * acc)
            if i < 3:
                r1[b, i] = r0[b, i] + dq[b, i]
        R1[b] = mm(rotation_matrix(dq[b, 3:].copy()), R0[b])
    pinned, pin, j = bodies[6][0], bodies[6][1], bodies[6][2][0]
    for b in range(dq.shape[0]):
        if pinned[b]:  # the origin where its pin is
            for i in range(3):
                r1[b, i] = r0[b, i] + (pin[j, b, 0, i] - r0[b, i])
                vel1[b, i] = pin[j, b, 1, i]
                acc1[b, i] = pin[j, b, 2, i]
    advance_memory(bodies[5], h, vel0, vel1)
    for s in range(slave_node.shape[0]):
        b, n = slave_body[s], slave_node[s]
        arm = mv(R1[b], slave_arm[s])
        arms[s] = arm
        w, al = vel1[b, 3:].copy(), acc1[b, 3:].copy()
        wa = cross(w, arm)
        turn = cross(al, arm) + cross(w, wa)
        for c in range(3):
            x[n, c] = r1[b, c] + arm[c]
            v[n, c] = vel1[b, c] + wa[c]
            a[n, c] = acc1[b, c] + turn[c]


@numba.njit(**_JIT)
def advance_memory(memory, h, vel0, vel1):
    """The radiation memory states at the end of the step ``h`` for the body velocities
    going linearly from ``vel0`` to ``vel1`` (nb, 6): ``z1 = e^{p h} z0 + h phi_1 v0 + h
    phi_2 (v1 - v0)`` (:meth:`MemoryModel.step_weights` and :meth:`~MemoryModel.advance`,
    exact; the weight ``h phi_2`` of ``v1`` kept for the tangent)."""
    body, col, poles, z0, z1, w_end = memory[0], memory[2], memory[3], memory[5], memory[6], \
        memory[7]
    for m in range(poles.shape[0]):
        x = poles[m] * h
        e = np.exp(x)
        if abs(x) < 1e-3:
            phi1 = 1.0 + x / 2.0 + x * x / 6.0
            phi2 = 0.5 + x / 6.0 + x * x / 24.0
        else:
            phi1 = (e - 1.0) / x
            phi2 = (e - 1.0 - x) / (x * x)
        a, w = h * phi1, h * phi2
        w_end[m] = w
        v0, v1 = vel0[body[m], col[m]], vel1[body[m], col[m]]
        z1[m] = e * z0[m] + a * v0 + w * (v1 - v0)


@numba.njit(**_JIT)
def memory_forces(memory, nb):
    """The memory forces ``mu = Re sum c z1`` (nb, 6) of the evaluated states (the bodies
    feel ``-mu``; :meth:`MemoryModel.force`)."""
    body, row, coef, z1 = memory[0], memory[1], memory[4], memory[6]
    mu = np.zeros((nb, 6))
    for m in range(coef.shape[0]):
        mu[body[m], row[m]] += (coef[m] * z1[m]).real
    return mu


@numba.njit(**_JIT)
def add_memory_damping(memory, b, damp):
    """Adds ``d mu / d v1`` of body ``b`` (:meth:`MemoryModel.velocity_derivative` over the
    step of the last :func:`advance_memory`) to its damping block ``damp`` (6, 6)."""
    body, row, col, coef, w_end = memory[0], memory[1], memory[2], memory[4], memory[7]
    for m in range(coef.shape[0]):
        if body[m] == b:
            damp[row[m], col[m]] += (coef[m] * w_end[m]).real


@numba.njit(**_JIT)
def fluid_at(forces, j, b, r):
    """The fluid velocity at body ``b``'s origin ``r`` at sub-step ``j``: the current of
    ``forces`` where the origin is wet (``z <= 0``), zero above the still water level (as
    :meth:`moorline.waves.CurrentProfile.kinematics`)."""
    return forces[j, b, 6:].copy() if r[2] <= 0.0 else np.zeros(3)


@numba.njit(**_JIT)
def residual(bodies, j, buf, rvec, alpha, node_mass, a, norm):
    """The bodies' rows of the step's residual (after the ``n`` band rows of ``rvec``): the
    weighted non-inertial forces plus the inertial ones, ``(1 + alpha) F - alpha F0 + F_i``
    (:meth:`Stepper.residual`, :meth:`BodyModel.forces`), with the attached nodes' forces
    of ``buf`` through ``T^T``; a pinned body's translational rows are minus its pin's
    force (kept in ``bodies``) and held at zero; returns the max-norm of the whole residual
    (``norm``: that of the band rows; ``inf`` for a NaN)."""
    if bodies is None:  # no bodies: not compiled in
        return norm
    slave_node, slave_body = bodies[0][0], bodies[0][1]
    loads = bodies[1]
    (_, _, _, _, _, _, r1, R1, vel1, acc1, arms, other0, other1, node_w) = bodies[2]
    forces = bodies[3]
    mass, cog, inertia, added, damping = loads[0], loads[1], loads[2], loads[3], loads[4]
    nb = r1.shape[0]
    n_line = rvec.shape[0] - 6 * nb
    resid, f_am = buf[11], buf[10]
    K = np.empty((6, 6))
    d_vel = np.empty((6, 6))
    d_rot = np.empty((6, 6))
    inertial = np.zeros((nb, 6))
    mu = memory_forces(bodies[5], nb)
    for b in range(nb):
        gen = static_load(b, loads, r1[b], R1[b], K) - (mv(damping[b], vel1[b]) + mu[b])
        gen += forces[j, b, :6]
        drag_load(loads[-1][b], fluid_at(forces, j, b, r1[b]), vel1[b], gen, K)  # K: scratch
        other1[b] = gen
        inertial[b] = -(inertia_load(mass[b], cog[b], inertia[b], R1[b], vel1[b], acc1[b],
                                     d_vel, d_rot) + mv(added[b], acc1[b]))
    for s in range(slave_node.shape[0]):
        b, n = slave_body[s], slave_node[s]
        f_o = np.empty(3)
        f_i = np.empty(3)
        for c in range(3):
            f_o[c] = resid[n, c] + node_mass[n] * a[n, c] - f_am[n, c]
            f_i[c] = f_am[n, c] - node_mass[n] * a[n, c]
            node_w[s, c] = (1.0 + alpha) * f_o[c] + f_i[c]
        m_o, m_i = cross(arms[s], f_o), cross(arms[s], f_i)
        for c in range(3):
            other1[b, c] += f_o[c]
            other1[b, 3 + c] += m_o[c]
            inertial[b, c] += f_i[c]
            inertial[b, 3 + c] += m_i[c]
    pinned, pin_force = bodies[6][0], bodies[6][3]
    for b in range(nb):
        for i in range(6):
            row = other1[b, i] + inertial[b, i] if alpha == 0.0 else \
                (1.0 + alpha) * other1[b, i] - alpha * other0[b, i] + inertial[b, i]
            if pinned[b] and i < 3:
                pin_force[b, i] = -row
                row = 0.0
            rvec[n_line + 6 * b + i] = row
            r = abs(row)
            if not (r <= norm):
                norm = r if r == r else math.inf
    return norm


@numba.njit(**_JIT)
def kinematic_blocks(bodies, ca, cv1):
    """How every attached node's position, velocity and acceleration change with its body's
    step: (n_slaves, 3, 6) each (:meth:`BodyModel.kinematic_blocks`, exact)."""
    slave_body = bodies[0][1]
    state = bodies[2]
    dq, vel1, acc1, arms = state[4], state[8], state[9], state[10]
    ns = slave_body.shape[0]
    bx, bv, ba = np.zeros((ns, 3, 6)), np.zeros((ns, 3, 6)), np.zeros((ns, 3, 6))
    for s in range(ns):
        b = slave_body[s]
        A = skew(arms[s])
        W, Al = skew(vel1[b, 3:].copy()), skew(acc1[b, 3:].copy())
        d_arm = -mm(A, left_jacobian(dq[b, 3:].copy()))
        wa = skew(cross(vel1[b, 3:].copy(), arms[s]))
        rot_v = -cv1 * A + mm(W, d_arm)
        rot_a = -ca * A + mm(Al, d_arm) - cv1 * (wa + mm(W, A)) + mm(mm(W, W), d_arm)
        for c in range(3):
            bx[s, c, c], bv[s, c, c], ba[s, c, c] = 1.0, cv1, ca
            for k in range(3):
                bx[s, c, 3 + k] = d_arm[c, k]
                bv[s, c, 3 + k] = rot_v[c, k]
                ba[s, c, 3 + k] = rot_a[c, k]
    return bx, bv, ba


@numba.njit(**_JIT)
def _transposed_maps(arms):
    """``T^T = [I; [arm x]]`` (n_slaves, 6, 3) of ``T = [I, -[arm x]]``."""
    out = np.zeros((arms.shape[0], 6, 3))
    for s in range(arms.shape[0]):
        A = skew(arms[s])
        for c in range(3):
            out[s, c, c] = 1.0
            for k in range(3):
                out[s, 3 + c, k] = A[c, k]
    return out


@numba.njit(**_JIT)
def couplings(bodies, band, elements, buf, with_added_mass, node_mass, ca, cv, ck, seabed_on):
    """The border of the effective tangent ``-dr/du`` (:meth:`Stepper.tangent_matrix`):
    ``B^T`` (6 nb, n), ``C`` (6 nb, n) and ``D`` (6 nb, 6 nb) into ``bodies``' work arrays:
    the element blocks ``ck K + cv C + ca M_a`` (the added-mass forces' part of ``K`` weighted
    1, :func:`~moorline.physics.fused.hht_stiffness`) on an attached node's columns through its
    kinematic blocks, on its rows through ``T^T``; its node mass and seabed terms; and every
    body's block (:meth:`BodyModel.block_parts`: hydrostatics and weight, the attached
    nodes' arms turning under their forces, damping with the radiation memory's ``d mu / d
    v1``, added mass and the exact rigid-body inertia; rotation columns chained by the left
    Jacobian of the step)."""
    if bodies is None:  # no bodies: not compiled in
        return
    slave_node, slave_body, slave_of_node = bodies[0][0], bodies[0][1], bodies[0][3]
    loads = bodies[1]
    (_, _, _, _, dq, _, r1, R1, vel1, acc1, arms, _, _, node_w) = bodies[2]
    BT, Cr, D = bodies[4][0], bodies[4][1], bodies[4][2]
    nb = r1.shape[0]
    if nb == 0:
        return
    K, C, Ma, Ka = buf[6], buf[7], buf[8], buf[19]
    kzz, czz, fric_c, fric_kz, fric_cz = buf[12], buf[13], buf[14], buf[15], buf[16]
    BT[:, :] = 0.0
    Cr[:, :] = 0.0
    D[:, :] = 0.0
    cv1 = cv / ck
    bx, bv, ba = kinematic_blocks(bodies, ca, cv1)
    TT = _transposed_maps(arms)
    for e in range(elements.shape[0]):
        if slave_of_node[elements[e, 0]] < 0 and slave_of_node[elements[e, 1]] < 0:
            continue
        for p in range(6):
            n_p, c_p = elements[e, p // 3], p % 3
            row, s_r = band[n_p, c_p], slave_of_node[n_p]
            if row < 0 and s_r < 0:
                continue
            for q in range(6):
                n_q, c_q = elements[e, q // 3], q % 3
                col, s_c = band[n_q, c_q], slave_of_node[n_q]
                if col >= 0:
                    if s_r < 0:
                        continue
                    val = hht_stiffness(K, Ka, with_added_mass, ck, e, p, q) + cv * C[e, p, q]
                    if with_added_mass:
                        val += ca * Ma[e, p, q]
                    for i in range(6):
                        Cr[6 * slave_body[s_r] + i, col] += TT[s_r, i, c_p] * val
                    continue
                if s_c < 0:
                    continue
                mapped = np.empty(6)
                k_pq = hht_stiffness(K, Ka, with_added_mass, ck, e, p, q)
                for k in range(6):
                    mapped[k] = k_pq * bx[s_c, c_q, k] + ck * C[e, p, q] * bv[s_c, c_q, k]
                    if with_added_mass:
                        mapped[k] += Ma[e, p, q] * ba[s_c, c_q, k]
                d_c = 6 * slave_body[s_c]
                if s_r < 0:
                    for k in range(6):
                        BT[d_c + k, row] += mapped[k]
                else:
                    for i in range(6):
                        t = TT[s_r, i, c_p]
                        if t != 0.0:
                            for k in range(6):
                                D[6 * slave_body[s_r] + i, d_c + k] += t * mapped[k]
    for s in range(slave_node.shape[0]):  # the attached nodes' own mass and seabed terms
        n, d = slave_node[s], 6 * slave_body[s]
        node_k, node_c = np.zeros((3, 3)), np.zeros((3, 3))
        if seabed_on:
            node_k[2, 2], node_c[2, 2] = kzz[n], czz[n]
            for r in range(2):
                node_k[r, 2], node_c[r, 2] = fric_kz[n, r], fric_cz[n, r]
                for c in range(2):
                    node_c[r, c] = fric_c[n, r, c]
        mapped = node_mass[n] * ba[s] + ck * (mm(node_k, bx[s]) + mm(node_c, bv[s]))
        D[d:d + 6, d:d + 6] += mm(TT[s], mapped)
    mass, cog, inertia, added, damping = loads[0], loads[1], loads[2], loads[3], loads[4]
    stiff = np.empty((6, 6))
    d_vel = np.empty((6, 6))
    d_rot = np.empty((6, 6))
    for b in range(nb):
        static_load(b, loads, r1[b], R1[b], stiff)
        inertia_load(mass[b], cog[b], inertia[b], R1[b], vel1[b], acc1[b], d_vel, d_rot)
        turned = ck * stiff + d_rot
        for s in range(slave_node.shape[0]):
            if slave_body[s] == b:
                turned[3:, 3:] -= mm(skew(node_w[s]), skew(arms[s]))
        turned[:, 3:] = mm(turned[:, 3:].copy(), left_jacobian(dq[b, 3:].copy()))
        damp = damping[b].copy()
        add_memory_damping(bodies[5], b, damp)
        drag_load(loads[-1][b], fluid_at(bodies[3], bodies[6][2][0], b, r1[b]), vel1[b],
                  np.zeros(6), damp)
        block = turned + cv1 * (ck * damp + d_vel) \
            + ca * (rigid_mass(mass[b], cog[b], inertia[b], R1[b]) + added[b])
        D[6 * b:6 * b + 6, 6 * b:6 * b + 6] += block
    _hold_pins(bodies[6][0], BT, Cr, D)


@numba.njit(**_JIT)
def _hold_pins(pinned, BT, Cr, D):
    """The pinned bodies' translations held: their rows and columns of the border zero,
    their diagonal the largest of ``D``'s (:func:`moorline.solvers.bodies.hold_dofs`)."""
    scale = 0.0
    for k in range(D.shape[0]):
        scale = max(scale, abs(D[k, k]))
    for b in range(pinned.shape[0]):
        if not pinned[b]:
            continue
        for i in range(3):
            d = 6 * b + i
            BT[d, :] = 0.0
            Cr[d, :] = 0.0
            D[d, :] = 0.0
            D[:, d] = 0.0
            D[d, d] = scale


@numba.njit(**_JIT)
def schur(bodies):
    """With ``B^T`` replaced by ``(A^-1 B)^T`` (the band solves of
    :func:`moorline.solvers.fast_newmark._factor_border`): the inverse of
    ``S = D - C A^-1 B`` (Gauss-Jordan with partial pivoting); False when ``S`` is
    singular."""
    if bodies is None:  # no bodies: not compiled in
        return True
    BT, Cr, D, S_inv = bodies[4]
    m = D.shape[0]
    if m == 0:
        return True
    S = D.copy()
    for i in range(m):
        for k in range(m):
            s = 0.0
            for q in range(BT.shape[1]):
                s += Cr[i, q] * BT[k, q]
            S[i, k] -= s
    return _invert(S, S_inv)


@numba.njit(**_JIT)
def _invert(S, out):
    """``out = S^-1`` by Gauss-Jordan elimination with partial pivoting (``S`` destroyed);
    False when a pivot vanishes."""
    m = S.shape[0]
    out[:, :] = 0.0
    for i in range(m):
        out[i, i] = 1.0
    for k in range(m):
        p = k
        for i in range(k + 1, m):
            if abs(S[i, k]) > abs(S[p, k]):
                p = i
        if S[p, k] == 0.0 or not math.isfinite(S[p, k]):
            return False
        if p != k:
            for j in range(m):
                S[k, j], S[p, j] = S[p, j], S[k, j]
                out[k, j], out[p, j] = out[p, j], out[k, j]
        f = 1.0 / S[k, k]
        for j in range(m):
            S[k, j] *= f
            out[k, j] *= f
        for i in range(m):
            if i != k and S[i, k] != 0.0:
                g = S[i, k]
                for j in range(m):
                    S[i, j] -= g * S[k, j]
                    out[i, j] -= g * out[k, j]
    return True


@numba.njit(**_JIT)
def solve(bodies, dx):
    """Completes a solve whose band rows ``dx[:n]`` hold ``y = A^-1 r_l``: the bodies' step
    ``dq = S^-1 (r_b - C y)`` into ``dx[n:]`` and ``dx[:n] = y - A^-1 B dq``."""
    if bodies is None:  # no bodies: not compiled in
        return
    BT, Cr, _, S_inv = bodies[4]
    m = S_inv.shape[0]
    if m == 0:
        return
    n = Cr.shape[1]
    z = np.empty(m)
    for i in range(m):
        s = dx[n + i]
        for q in range(n):
            s -= Cr[i, q] * dx[q]
        z[i] = s
    step = mv(S_inv, z)
    for k in range(m):
        dx[n + k] = step[k]
        for q in range(n):
            dx[q] -= BT[k, q] * step[k]


@numba.njit(**_JIT)
def try_step(bodies, step, dx):
    """The line-search trial of the bodies: ``dq + step dx[n:]``."""
    if bodies is None:  # no bodies: not compiled in
        return
    dq, dq_try = bodies[2][4], bodies[2][5]
    n = dx.shape[0] - 6 * dq.shape[0]
    for b in range(dq.shape[0]):
        for i in range(6):
            dq_try[b, i] = dq[b, i] + step * dx[n + 6 * b + i]


@numba.njit(**_JIT)
def take_trial(bodies):
    """The trial becomes the iterate."""
    if bodies is None:  # no bodies: not compiled in
        return
    bodies[2][4][:, :] = bodies[2][5]


@numba.njit(**_JIT)
def commit(bodies):
    """A converged sub-step: its end state becomes the start of the next."""
    if bodies is None:  # no bodies: not compiled in
        return
    state = bodies[2]
    state[0][:, :] = state[6]
    state[1][:, :, :] = state[7]
    state[2][:, :] = state[8]
    state[3][:, :] = state[9]
    state[11][:, :] = state[12]
    bodies[5][5][:] = bodies[5][6]
    bodies[6][4][:, :] = bodies[6][3]


@numba.njit(**_JIT)
def record(bodies, r, out):
    """The bodies' state into record ``r`` of ``out = (origins, rotations, velocities,
    pin forces)``."""
    if bodies is None:  # no bodies: not compiled in
        return
    state = bodies[2]
    out[0][r] = state[0]
    out[1][r] = state[1]
    out[2][r] = state[2]
    out[3][r] = bodies[6][4]
