"""Compiled rigid-body kernels for the compiled time step with bodies
(:mod:`moorline.solvers.fast_bodies`): the rotation maps, the rigid-body inertia and the
static loads of one body with their exact tangents.

They are the formulas of :mod:`moorline.physics.rigid_body` (and of
:func:`moorline.solvers.bodies.body_loads`, which combines them) written for one body at a
time in numba, with the same conventions: ``R <- exp([dtheta x]) R``, tangents
``K = -d load / d(dr, dtheta)``, loads about the body origin in world axes. Sources as
there: Tuah (1982) eq. 3.2.c.20 / 3.3.1 (constant added mass, damping, hydrostatic
restoring), Wang, Er and Iu eq. 24-30 (the box's buoyancy and waterplane restoring), and the
Newton-Euler rigid-body equations about a point off the centre of gravity; the rods'
buoyancy is :func:`moorline.physics.rod_buoyancy.rod_buoyancy` (MoorDyn-C v2.7
``source/Rod.cpp``, ``Rod::doRHS``, ``h0``, for the submerged length; the waterplane couple
derived and sourced there); the drag of a body is
:func:`moorline.physics.rigid_body.body_drag` (Morison drag of a small body, Tuah sec. 3.2).
"""

from __future__ import annotations

import math

import numpy as np

from ..jit import numba
from ..physics.rigid_body import _SMALL  # below it the left Jacobian's series

_JIT = {"cache": True, "fastmath": False, "error_model": "numpy"}


@numba.njit(**_JIT)
def skew(v):
    """``[v x]`` (3, 3)."""
    out = np.zeros((3, 3))
    out[0, 1], out[0, 2] = -v[2], v[1]
    out[1, 0], out[1, 2] = v[2], -v[0]
    out[2, 0], out[2, 1] = -v[1], v[0]
    return out


@numba.njit(**_JIT)
def mm(A, B):
    """``A @ B`` of small matrices."""
    out = np.zeros((A.shape[0], B.shape[1]))
    for i in range(A.shape[0]):
        for k in range(A.shape[1]):
            a = A[i, k]
            if a != 0.0:
                for j in range(B.shape[1]):
                    out[i, j] += a * B[k, j]
    return out


@numba.njit(**_JIT)
def mv(A, x):
    """``A @ x`` of a small matrix."""
    out = np.zeros(A.shape[0])
    for i in range(A.shape[0]):
        s = 0.0
        for k in range(A.shape[1]):
            s += A[i, k] * x[k]
        out[i] = s
    return out


@numba.njit(**_JIT)
def cross(a, b):
    """``a x b``."""
    return np.array([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                     a[0] * b[1] - a[1] * b[0]])


@numba.njit(**_JIT)
def _quadratic(P, b, c):
    """``I + b P + c P^2``."""
    P2 = mm(P, P)
    out = np.eye(3)
    for i in range(3):
        for j in range(3):
            out[i, j] += b * P[i, j] + c * P2[i, j]
    return out


@numba.njit(**_JIT)
def rotation_matrix(phi):
    """``exp([phi x])`` (Rodrigues; :func:`moorline.physics.rigid_body.rotation_matrix`)."""
    angle = math.sqrt(phi[0] * phi[0] + phi[1] * phi[1] + phi[2] * phi[2])
    if angle < 1e-300:
        return np.eye(3)
    return _quadratic(skew(phi / angle), math.sin(angle), 1.0 - math.cos(angle))


@numba.njit(**_JIT)
def left_jacobian(phi):
    """SO(3) left Jacobian ``I + (1 - cos t) / t^2 P + (t - sin t) / t^3 P^2``, series below
    1e-4 rad (:func:`moorline.physics.rigid_body.left_jacobian`)."""
    t2 = phi[0] * phi[0] + phi[1] * phi[1] + phi[2] * phi[2]
    t = math.sqrt(t2)
    if t < _SMALL:
        b, c = 0.5 - t2 / 24.0, 1.0 / 6.0 - t2 / 120.0
    else:
        b = 2.0 * math.sin(0.5 * t) ** 2 / t2
        c = (t - math.sin(t)) / (t2 * t)
    return _quadratic(skew(phi), b, c)


@numba.njit(**_JIT)
def inverse_left_jacobian(phi):
    """``I - P / 2 + (1 / t^2 - (1 + cos t) / (2 t sin t)) P^2``, series below 1e-6 rad
    (:func:`moorline.physics.rigid_body.inverse_left_jacobian`)."""
    t = math.sqrt(phi[0] * phi[0] + phi[1] * phi[1] + phi[2] * phi[2])
    c = 1.0 / 12.0 if t < 1e-6 else \
        1.0 / (t * t) - (1.0 + math.cos(t)) / (2.0 * t * math.sin(t))
    return _quadratic(skew(phi), -0.5, c)


@numba.njit(**_JIT)
def rotation_vector(R):
    """The log map, ``|phi| <= pi`` (:func:`moorline.physics.rigid_body.rotation_vector`:
    ``t / (2 sin t) w``; near ``t = pi`` the axis from the symmetric part)."""
    w = np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]])
    cos = min(max((R[0, 0] + R[1, 1] + R[2, 2] - 1.0) / 2.0, -1.0), 1.0)
    angle = math.acos(cos)
    scale = 0.5 if angle < 1e-8 else angle / (2.0 * math.sin(angle))
    s2 = math.sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2])
    if not (cos < 0.0 and s2 < 2e-2):
        return scale * w
    t = math.atan2(0.5 * s2, cos)
    B = np.empty((3, 3))
    for i in range(3):
        for j in range(3):
            B[i, j] = (0.5 * (R[i, j] + R[j, i]) - (cos if i == j else 0.0)) / (1.0 - cos)
    i = 0
    for k in range(1, 3):
        if B[k, k] > B[i, i]:
            i = k
    n = B[:, i] / math.sqrt(max(B[i, i], 1e-300))
    sign = -1.0 if n[0] * w[0] + n[1] * w[1] + n[2] * w[2] < 0.0 else 1.0
    return (sign * t) * n


@numba.njit(**_JIT)
def rigid_mass(m, cog, inertia, R):
    """Rigid-body mass matrix about the origin, world axes
    (:func:`moorline.physics.rigid_body.rigid_mass`); ``inertia`` (3, 3) body frame about
    the centre of gravity."""
    c = mv(R, cog)
    I_G = mm(mm(R, inertia), R.T.copy())
    S = skew(c)
    S2 = mm(S, S)
    M = np.zeros((6, 6))
    for i in range(3):
        M[i, i] = m
        for j in range(3):
            M[i, 3 + j] = -m * S[i, j]
            M[3 + i, j] = m * S[i, j]
            M[3 + i, 3 + j] = I_G[i, j] - m * S2[i, j]
    return M


@numba.njit(**_JIT)
def inertia_load(m, cog, inertia, R, vel, acc, d_vel, d_rot):
    """Rigid-body inertia ``(F, M)`` about the origin (6,)
    (:func:`moorline.physics.rigid_body.inertia_load`: ``F = m (a + alpha x c + w x (w x
    c))``, ``M = c x F + I_G alpha + w x (I_G w)``); fills its exact derivatives with respect
    to velocity ``d_vel`` and rotation ``d_rot`` (6, 6) (``d / d acc`` is
    :func:`rigid_mass`)."""
    c = mv(R, cog)
    I_G = mm(mm(R, inertia), R.T.copy())
    w, al = vel[3:].copy(), acc[3:].copy()
    Sc, Sw, Sal = skew(c), skew(w), skew(al)
    wc = cross(w, c)
    F = m * (acc[:3] + cross(al, c) + cross(w, wc))
    I_al, I_w = mv(I_G, al), mv(I_G, w)
    M = cross(c, F) + I_al + cross(w, I_w)
    load = np.empty(6)
    load[:3], load[3:] = F, M
    dF_dw = -m * (skew(wc) + mm(Sw, Sc))
    dM_dw = mm(Sc, dF_dw) - skew(I_w) + mm(Sw, I_G)
    dF_de = -m * mm(Sal + mm(Sw, Sw), Sc)
    dM_de = (mm(skew(F), Sc) + mm(Sc, dF_de) - skew(I_al) + mm(I_G, Sal)
             - mm(Sw, skew(I_w)) + mm(mm(Sw, I_G), Sw))
    d_vel[:, :] = 0.0
    d_rot[:, :] = 0.0
    d_vel[:3, 3:] = dF_dw
    d_vel[3:, 3:] = dM_dw
    d_rot[:3, 3:] = dF_de
    d_rot[3:, 3:] = dM_de
    return load


@numba.njit(**_JIT)
def _point_load(force, arm, R, load, K):
    """Adds a constant world ``force`` at the body point ``arm``
    (:func:`moorline.physics.rigid_body.point_load`): ``(f, (R arm) x f)``, and
    ``K_rot = -[f x][R arm x]``."""
    world = mv(R, arm)
    load[:3] += force
    load[3:] += cross(world, force)
    K[3:, 3:] -= mm(skew(force), skew(world))


@numba.njit(**_JIT)
def _submerged_span(za, zb):
    """Submerged fractions ``(s0, s1)`` of a rod's axis from end A (heights ``za``, ``zb``
    of its ends [length]) and their derivatives with respect to ``(za, zb)`` (2,) each
    (:func:`moorline.physics.rod_buoyancy.submerged_span`)."""
    ds0, ds1 = np.zeros(2), np.zeros(2)
    a_wet, b_wet = za < 0.0, zb < 0.0
    if a_wet == b_wet:
        return 0.0, (1.0 if a_wet else 0.0), ds0, ds1
    diff = za - zb
    s = za / diff
    if a_wet:
        ds1[0], ds1[1] = -zb / diff**2, za / diff**2
        return 0.0, s, ds0, ds1
    ds0[0], ds0[1] = -zb / diff**2, za / diff**2
    return s, 1.0, ds0, ds1


@numba.njit(**_JIT)
def _waterplane_moment(D, length, diameter, up_sign, wet, d_wet, rho_g, load, K):
    """Adds the waterplane couple of a rod piercing the surface (world axis ``D`` (3,) of
    norm ``length``, ``up_sign`` 1 when end A is wet, else -1; wet fraction ``wet`` and its
    derivative ``d_wet`` (6,)) to ``load`` and its tangent to ``K``
    (:func:`moorline.physics.rod_buoyancy.waterplane_moment`)."""
    up = (up_sign / length) * D  # t: from the wet end up
    c = up[2]
    sin2 = max(1.0 - c * c, 0.0)
    h_wet = wet * length
    dry_shorter = length - h_wet < h_wet
    h = length - h_wet if dry_shorter else h_wet
    dh = ((-1.0 if dry_shorter else 1.0) * length) * d_wet
    tan_cap = 2.0 * h / diameter
    capped = sin2 > (tan_cap * c) ** 2  # tan(phi) beyond the cap
    c_free = 1.0 if capped else c
    f = 1.0 + 0.5 * (tan_cap * tan_cap if capped else sin2 / (c_free * c_free))
    arm = np.array([up[1], -up[0], 0.0])  # t x e_z
    if capped:  # df = tan dtan, dtan = 2 dh / d
        df = (tan_cap * 2.0 / diameter) * dh
    else:  # f = (1 + 1 / c^2) / 2, df = -dc / c^3, dc = dtheta . (t x e_z)
        df = np.zeros(6)
        df[3:] = -arm / c_free**3
    scale = rho_g * math.pi * diameter**4 / 64.0
    # d(t x e_z) = [e_z x][t x] dtheta
    turn = mm(skew(np.array([0.0, 0.0, 1.0])), skew(up))
    for i in range(3):
        load[3 + i] += scale * f * arm[i]
        for j in range(6):
            K[3 + i, j] -= scale * arm[i] * df[j]
        for j in range(3):
            K[3 + i, 3 + j] -= scale * f * turn[i, j]


@numba.njit(**_JIT)
def rods_load(first, last, rod_a, rod_b, rod_d, r, R, rho_g, load, K):
    """Adds the buoyancy of rods ``first:last`` (body-frame ends ``rod_a``, ``rod_b`` (n, 3),
    diameters ``rod_d`` (n,) [length]) of a body at ``r``, ``R`` to ``load`` (6,) and its
    exact tangent to ``K`` (6, 6) (:func:`moorline.physics.rod_buoyancy.rod_buoyancy`)."""
    for k in range(first, last):
        A, B = mv(R, rod_a[k]), mv(R, rod_b[k])
        za, zb = r[2] + A[2], r[2] + B[2]
        s0, s1, ds0, ds1 = _submerged_span(za, zb)
        D = B - A
        length = math.sqrt(D[0] * D[0] + D[1] * D[1] + D[2] * D[2])
        weight = rho_g * math.pi * rod_d[k] ** 2 / 4.0 * length  # per unit fraction
        lift = weight * (s1 - s0)
        arm = A + (0.5 * (s0 + s1)) * D
        load[2] += lift
        load[3] += arm[1] * lift
        load[4] -= arm[0] * lift
        # dz_end = dr_z + dtheta . (arm_end x e_z)
        gz_a = np.array([0.0, 0.0, 1.0, A[1], -A[0], 0.0])
        gz_b = np.array([0.0, 0.0, 1.0, B[1], -B[0], 0.0])
        d_s0 = ds0[0] * gz_a + ds0[1] * gz_b
        d_s1 = ds1[0] * gz_a + ds1[1] * gz_b
        d_wet = d_s1 - d_s0
        d_mid = 0.5 * (d_s0 + d_s1)
        # d arm = dtheta x arm + D d_mid;  dM = d arm x F + arm x dF, F = lift e_z
        d_arm = np.zeros((3, 6))
        d_arm[:, 3:] = -skew(arm)
        for i in range(3):
            for j in range(6):
                d_arm[i, j] += D[i] * d_mid[j]
        for j in range(6):
            d_lift = weight * d_wet[j]
            K[2, j] -= d_lift
            K[3, j] -= lift * d_arm[1, j] + arm[1] * d_lift
            K[4, j] -= -lift * d_arm[0, j] - arm[0] * d_lift
        if (za < 0.0) != (zb < 0.0):
            _waterplane_moment(D, length, rod_d[k], 1.0 if za < 0.0 else -1.0, s1 - s0,
                               d_wet, rho_g, load, K)


@numba.njit(**_JIT)
def static_load(b, model, r, R, K):
    """Weight, constant load and hydrostatics of body ``b`` (6,) and their tangent ``K``
    (6, 6, filled) (:func:`moorline.solvers.bodies.body_loads` for the kinds of
    :data:`moorline.solvers.fast_path.HULL_KINDS`:
    :func:`~moorline.physics.rigid_body.gravity_load`,
    :func:`~moorline.physics.rigid_body.hull_buoyancy` and
    :func:`~moorline.physics.rigid_body.waterplane_restoring` of a box or cylinder,
    :func:`~moorline.physics.rigid_body.matrix_restoring` with a constant buoyancy, the rods'
    buoyancy (:func:`rods_load`) with a constant buoyancy)."""
    (mass, cog, inertia, added, damping, force, kind, area, height, wp_inertia, volume,
     cob, stiffness, ref_r, ref_R, gravity, rho, rod_first, rod_a, rod_b, rod_d, _) = model
    K[:, :] = 0.0
    load = force[b].copy()
    _point_load(np.array([0.0, 0.0, -mass[b] * gravity]), cog[b], R, load, K)
    rg = rho * gravity
    if kind[b] == 1:  # wall-sided hull: buoyancy of the draft, waterplane restoring
        h = height[b]
        depth = h / 2.0 - r[2]
        draft = min(max(depth, 0.0), h)
        d_draft = -1.0 if 0.0 < depth < h else 0.0
        lift = rg * area[b] * draft
        center = np.array([0.0, 0.0, -h / 2.0 + draft / 2.0])
        _point_load(np.array([0.0, 0.0, lift]), center, R, load, K)
        arm = mv(R, center)
        d_lift = rg * area[b] * d_draft
        K[2, 2] -= d_lift
        # the rising centre of buoyancy: d_arm x B + arm x dB
        d_arm = 0.5 * d_draft * R[:, 2].copy()
        turn = cross(d_arm, np.array([0.0, 0.0, lift])) \
            + cross(arm, np.array([0.0, 0.0, d_lift]))
        for i in range(3):
            K[3 + i, 2] -= turn[i]
        tilt = rotation_vector(R)
        J_inv = inverse_left_jacobian(tilt)
        for i in range(2):
            restoring = rg * wp_inertia[b, i]
            load[3 + i] -= restoring * tilt[i]
            for j in range(3):
                K[3 + i, 3 + j] += restoring * J_inv[i, j]
    elif kind[b] >= 2:  # constant buoyancy at the centre of buoyancy
        _point_load(np.array([0.0, 0.0, rg * volume[b]]), cob[b], R, load, K)
    if kind[b] == 3:  # and the rods' buoyancy at this pose
        rods_load(rod_first[b], rod_first[b + 1], rod_a, rod_b, rod_d, r, R, rg, load, K)
    elif kind[b] == 2:  # and a constant stiffness
        turn = rotation_vector(mm(R, ref_R[b].T.copy()))
        q = np.empty(6)
        q[:3], q[3:] = r - ref_r[b], turn
        load -= mv(stiffness[b], q)
        jac = np.eye(6)
        jac[3:, 3:] = inverse_left_jacobian(turn)
        K += mm(stiffness[b], jac)
    return load


@numba.njit(**_JIT)
def drag_load(coef, u, v, load, damp):
    """Adds the quadratic drag ``F_i = coef_i |u_i - v_i| (u_i - v_i) / 2`` per world axis
    (``coef = rho Cd A`` (3,) [mass / length], fluid velocity ``u``, body velocity ``v``
    (3,) [length / time]) to ``load`` (6,) and its damping ``-dF / dv``, the diagonal
    ``coef_i |u_i - v_i|``, to ``damp`` (6, 6)
    (:func:`moorline.physics.rigid_body.body_drag`)."""
    for i in range(3):
        rel = u[i] - v[i]
        load[i] += 0.5 * coef[i] * abs(rel) * rel
        damp[i, i] += coef[i] * abs(rel)
