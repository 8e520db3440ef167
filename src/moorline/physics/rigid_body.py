"""Rigid-body kinematics and loads: pure kernels with their exact tangents.

Conventions (those of :mod:`moorline.solvers.bodies`)
-----------------------------------------------------
* The orientation of a body is a rotation matrix ``R`` (body frame to world axes). A small
  rotation ``dtheta`` (world axes) acts on the left: ``R <- exp([dtheta x]) R``. Every
  "rotation derivative" below is the derivative with respect to that ``dtheta`` at zero.
* A rotation vector ``phi`` (axis times angle) gives ``R = exp([phi x])`` (Rodrigues).
* Body velocity ``(v, omega)`` and acceleration ``(a, alpha)`` are of the body origin, world
  axes; forces and moments are about the origin, world axes (generalized 6-vectors
  ``(F, M)``).
* ``cog`` and ``inertia`` are in the body frame, ``inertia`` about the centre of gravity:
  a (3, 3) tensor or its 3 principal values (a diagonal tensor).

Every kernel broadcasts over leading axes (e.g. ``n_bodies``): vectors are (..., 3),
matrices (..., 3, 3), generalized vectors (..., 6) and tangents (..., 6, 6).

Sources: the body equation of motion with constant added mass, radiation damping,
hydrostatic restoring and exciting force is Tuah (1982) eq. 3.2.c.20 / 3.3.1, coupled to the
lines through ``x = r + R a`` (Tuah eq. 3.3.6-3.3.7; Wang, Er and Iu eq. 31-34); Wang, Er and
Iu eq. 24-30 give the box's equations with buoyancy and waterplane restoring. The
rigid-body inertia about a point off the centre of gravity (offset ``c``, gyroscopic and
centripetal terms) is the Newton-Euler form of classical mechanics.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

FloatArray = NDArray[np.float64]

_EYE = np.eye(3)
_SMALL = 1e-4  # below this angle the left Jacobian's coefficients use their series


# ---------------------------------------------------------------------- rotations
def skew(v: ArrayLike) -> FloatArray:
    """Cross-product matrix ``[v x]`` (..., 3, 3) of vectors ``v`` (..., 3): ``[v x] u = v x u``.

    Linear in ``v``: its derivative along ``dv`` is ``skew(dv)``.
    """
    v = np.asarray(v, dtype=float)
    out = np.zeros(v.shape + (3,))
    out[..., 0, 1], out[..., 0, 2] = -v[..., 2], v[..., 1]
    out[..., 1, 0], out[..., 1, 2] = v[..., 2], -v[..., 0]
    out[..., 2, 0], out[..., 2, 1] = -v[..., 1], v[..., 0]
    return out


def _angle_coefficients(phi: FloatArray) -> tuple[FloatArray, FloatArray]:
    """``(1 - cos t) / t^2`` and ``(t - sin t) / t^3`` (...) of ``t = |phi|`` (series for
    small angles)."""
    t = np.sqrt(np.einsum("...i,...i->...", phi, phi))
    small = t < _SMALL
    ts = np.where(small, 1.0, t)
    t2 = t * t
    b = np.where(small, 0.5 - t2 / 24.0, 2.0 * np.sin(0.5 * ts) ** 2 / ts**2)
    c = np.where(small, 1.0 / 6.0 - t2 / 120.0, (ts - np.sin(ts)) / ts**3)
    return b, c


def rotation_matrix(phi: ArrayLike) -> FloatArray:
    """Rotation matrix ``exp([phi x])`` (..., 3, 3) of rotation vectors ``phi`` (..., 3).

    Rodrigues' formula ``I + sin t K + (1 - cos t) K^2``, ``K = [n x]``, ``phi = t n``.
    Tangent: ``exp([(phi + dphi) x]) = exp([(J dphi) x]) exp([phi x])`` to first order,
    ``J = left_jacobian(phi)``.
    """
    phi = np.asarray(phi, dtype=float)
    angle = np.linalg.norm(phi, axis=-1)
    zero = angle < 1e-300
    K = skew(phi / np.where(zero, 1.0, angle)[..., None])
    s, c = np.sin(angle)[..., None, None], (1.0 - np.cos(angle))[..., None, None]
    return np.where(zero[..., None, None], _EYE, _EYE + s * K + c * (K @ K))


def left_jacobian(phi: ArrayLike) -> FloatArray:
    """SO(3) left Jacobian ``J(phi)`` (..., 3, 3): the derivative of the exp map as a rotation
    applied on the left, ``J = I + (1 - cos t) / t^2 P + (t - sin t) / t^3 P^2``."""
    phi = np.asarray(phi, dtype=float)
    b, c = _angle_coefficients(phi)
    P = skew(phi)
    return _EYE + b[..., None, None] * P + c[..., None, None] * (P @ P)


def rotation_vector(R: ArrayLike) -> FloatArray:
    """Rotation vector ``phi`` (..., 3), ``|phi| <= pi``, of rotation matrices ``R`` (..., 3, 3)
    (the log map, inverse of :func:`rotation_matrix`).

    ``phi = t / (2 sin t) w`` with ``w = vee(R - R^T) = 2 sin t n`` and
    ``cos t = (tr R - 1) / 2`` (``w / 2`` below 1e-8 rad); near ``t = pi``, where ``w``
    vanishes and ``arccos`` is ill-conditioned, ``t = atan2(|w| / 2, cos t)`` and the axis
    comes from the symmetric part, ``n n^T = ((R + R^T) / 2 - cos t I) / (1 - cos t)``.
    Tangent under a left rotation: ``d phi = inverse_left_jacobian(phi) dtheta``.
    """
    R = np.asarray(R, dtype=float)
    w = np.stack((R[..., 2, 1] - R[..., 1, 2], R[..., 0, 2] - R[..., 2, 0],
                  R[..., 1, 0] - R[..., 0, 1]), axis=-1)
    cos = np.clip((np.trace(R, axis1=-2, axis2=-1) - 1.0) / 2.0, -1.0, 1.0)
    angle = np.arccos(cos)
    small = angle < 1e-8
    # t / (2 sin t) w; small angles: w / 2
    scale = np.where(small, 0.5, angle / (2.0 * np.sin(np.where(small, 1.0, angle))))
    phi = scale[..., None] * w
    s2 = np.sqrt(np.einsum("...i,...i->...", w, w))  # 2 sin t
    near_pi = (cos < 0.0) & (s2 < 2e-2)
    if np.any(near_pi):  # arccos is ill-conditioned there, and w / |w| too
        t = np.arctan2(0.5 * s2, cos)
        B = (0.5 * (R + np.swapaxes(R, -1, -2)) - cos[..., None, None] * _EYE) \
            / (1.0 - cos)[..., None, None]
        diag = np.diagonal(B, axis1=-2, axis2=-1)
        i = np.argmax(diag, axis=-1)
        col = np.take_along_axis(B, i[..., None, None], axis=-1)[..., 0]
        n = col / np.sqrt(np.maximum(np.take_along_axis(diag, i[..., None], -1), 1e-300))
        sign = np.where(np.einsum("...i,...i->...", n, w) < 0.0, -1.0, 1.0)
        phi = np.where(near_pi[..., None], (sign * t)[..., None] * n, phi)
    return phi


def inverse_left_jacobian(phi: ArrayLike) -> FloatArray:
    """``d phi / d theta`` (..., 3, 3) for ``exp([phi x]) <- exp([dtheta x]) exp([phi x])``:
    how the rotation vector changes under a small rotation applied on the left (the inverse
    of :func:`left_jacobian`), ``I - P / 2 + (1 / t^2 - (1 + cos t) / (2 t sin t)) P^2``."""
    phi = np.asarray(phi, dtype=float)
    t = np.linalg.norm(phi, axis=-1)
    small = t < 1e-6
    ts = np.where(small, 1.0, t)
    c = np.where(small, 0.0,
                 1.0 / ts**2 - (1.0 + np.cos(ts)) / (2.0 * ts * np.sin(ts)))
    P = skew(phi)
    series = _EYE - 0.5 * P + P @ P / 12.0
    return np.where(small[..., None, None], series,
                    _EYE - 0.5 * P + c[..., None, None] * P @ P)


# ---------------------------------------------------------------------- inertia
def _apply(A: ArrayLike, x: ArrayLike) -> FloatArray:
    """Matrices (..., n, n) times vectors (..., n), by ``matmul``."""
    return (np.asarray(A, dtype=float) @ np.asarray(x, dtype=float)[..., None])[..., 0]


def _world_inertia(cog: ArrayLike, inertia: ArrayLike, R: FloatArray
                   ) -> tuple[FloatArray, FloatArray]:
    """World centre-of-gravity offset ``c = R cog`` and inertia ``I_G = R I R^T``."""
    R = np.asarray(R, dtype=float)
    inertia = np.asarray(inertia, dtype=float)
    if inertia.ndim == R.ndim - 1:  # principal values
        inertia = inertia[..., None, :] * _EYE
    c = _apply(R, cog)
    I_G = R @ inertia @ np.swapaxes(R, -1, -2)
    return c, I_G


def rigid_mass(mass: ArrayLike, cog: ArrayLike, inertia: ArrayLike, R: ArrayLike) -> FloatArray:
    """Rigid-body mass matrix (..., 6, 6) about the body origin, world axes.

    ``[[m I, -m [c x]], [m [c x], I_G - m [c x]^2]]`` with ``c = R cog`` and
    ``I_G = R inertia R^T`` (``inertia`` about the centre of gravity, body frame; (..., 3, 3)
    or its principal values (..., 3)).
    """
    R = np.asarray(R, dtype=float)
    c, I_G = _world_inertia(cog, inertia, R)
    m = np.asarray(mass, dtype=float)[..., None, None]
    S = skew(c)
    M = np.zeros(np.broadcast_shapes(S.shape[:-2], m.shape[:-2]) + (6, 6))
    M[..., :3, :3] = m * _EYE
    M[..., :3, 3:] = -m * S
    M[..., 3:, :3] = m * S
    M[..., 3:, 3:] = I_G - m * (S @ S)
    return M


def inertia_load(mass: ArrayLike, cog: ArrayLike, inertia: ArrayLike, R: ArrayLike,
                 vel: ArrayLike, acc: ArrayLike
                 ) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """Rigid-body inertia force and moment about the origin and their exact derivatives.

    With ``c = R cog``, ``I_G = R inertia R^T``, ``vel = (v, w)``, ``acc = (a, alpha)``::

        F = m (a + alpha x c + w x (w x c))
        M = c x F + I_G alpha + w x (I_G w)

    (the body's equation of motion is ``(F, M) = applied loads``).

    Returns
    -------
    load
        ``(F, M)`` (..., 6).
    d_acc
        ``d load / d acc`` (..., 6, 6): :func:`rigid_mass`.
    d_vel
        ``d load / d vel`` (..., 6, 6): the gyroscopic and centripetal terms (zero columns
        for ``v``).
    d_rot
        ``d load / d dtheta`` (..., 6, 6) for ``R <- exp([dtheta x]) R`` at fixed ``vel`` and
        ``acc`` (zero columns for the position).
    """
    R = np.asarray(R, dtype=float)
    vel, acc = np.asarray(vel, dtype=float), np.asarray(acc, dtype=float)
    c, I_G = _world_inertia(cog, inertia, R)
    m = np.asarray(mass, dtype=float)
    w, al = vel[..., 3:], acc[..., 3:]
    Sc, Sw, Sal = skew(c), skew(w), skew(al)
    wc = np.cross(w, c)
    F = m[..., None] * (acc[..., :3] + np.cross(al, c) + np.cross(w, wc))
    I_al, I_w = _apply(I_G, al), _apply(I_G, w)
    M = np.cross(c, F) + I_al + np.cross(w, I_w)
    load = np.concatenate((F, M), axis=-1)
    shape = load.shape[:-1] + (6, 6)
    mm = m[..., None, None]

    d_acc = rigid_mass(mass, cog, inertia, R)

    d_vel = np.zeros(shape)
    dF_dw = -mm * (skew(wc) + Sw @ Sc)
    d_vel[..., :3, 3:] = dF_dw
    d_vel[..., 3:, 3:] = Sc @ dF_dw - skew(I_w) + Sw @ I_G

    # dc = -[c x] e, dI_G = [e x] I_G - I_G [e x]
    d_rot = np.zeros(shape)
    dF_de = -mm * ((Sal + Sw @ Sw) @ Sc)
    d_rot[..., :3, 3:] = dF_de
    d_rot[..., 3:, 3:] = (skew(F) @ Sc + Sc @ dF_de - skew(I_al) + I_G @ Sal
                          - Sw @ skew(I_w) + Sw @ I_G @ Sw)
    return load, d_acc, d_vel, d_rot


# ---------------------------------------------------------------------- static loads
def point_load(force: ArrayLike, arm: ArrayLike, R: ArrayLike) -> tuple[FloatArray, FloatArray]:
    """A constant world force ``force`` (..., 3) acting at the body-frame point ``arm``
    (..., 3) of a body at rotation ``R``: the generalized load ``(f, (R arm) x f)`` (..., 6)
    and its tangent ``K = -d load / d(dr, dtheta)`` (..., 6, 6), whose only block is the
    moment change of the rotating arm, ``K_rot = -[f x][R arm x]``."""
    f = np.asarray(force, dtype=float)
    world = _apply(R, arm)
    f, world = np.broadcast_arrays(f, world)
    load = np.concatenate((f, np.cross(world, f)), axis=-1)
    K = np.zeros(load.shape[:-1] + (6, 6))
    K[..., 3:, 3:] -= skew(f) @ skew(world)
    return load, K


def gravity_load(mass: ArrayLike, cog: ArrayLike, R: ArrayLike,
                 gravity: float) -> tuple[FloatArray, FloatArray]:
    """Weight ``(0, 0, -m g)`` at the centre of gravity: :func:`point_load` (load, ``K``)."""
    m = np.asarray(mass, dtype=float)
    weight = np.zeros(m.shape + (3,))
    weight[..., 2] = -m * gravity
    return point_load(weight, cog, R)


def waterplane(kind: str, length: float = 0.0, width: float = 0.0,
               diameter: float = 0.0) -> tuple[float, tuple[float, float]]:
    """Waterplane area and its second moments about body x and y (roll, pitch) of a ``box``
    (``length`` along x, ``width`` along y) or vertical ``cylinder``; zeros otherwise."""
    if kind == "box":
        return length * width, (length * width**3 / 12.0, width * length**3 / 12.0)
    if kind == "cylinder":
        return np.pi * diameter**2 / 4.0, (np.pi * diameter**4 / 64.0,) * 2
    return 0.0, (0.0, 0.0)


def hull_draft(height: ArrayLike, z: ArrayLike) -> tuple[FloatArray, FloatArray]:
    """Draft ``clip(height / 2 - z, 0, height)`` of a wall-sided hull of ``height`` whose
    origin (its geometric centre) is at height ``z`` (still water at ``z = 0``), and
    ``d draft / dz`` (-1 while partly wet, else 0)."""
    height, z = np.asarray(height, dtype=float), np.asarray(z, dtype=float)
    depth = height / 2.0 - z
    wet = (depth > 0.0) & (depth < height)
    return np.clip(depth, 0.0, height), np.where(wet, -1.0, 0.0)


def hull_buoyancy(area: ArrayLike, height: ArrayLike, r: ArrayLike, R: ArrayLike, rho: float,
                  gravity: float) -> tuple[FloatArray, FloatArray]:
    """Buoyancy of a wall-sided hull (box or vertical cylinder of waterplane ``area`` (...)
    and ``height`` (...), origin at its centre): ``rho g A d`` with ``d`` the
    :func:`hull_draft` at the origin's height ``r_z``, acting at the centre of buoyancy, the
    body point ``(0, 0, -height / 2 + d / 2)`` (Wang, Er and Iu eq. 30's ``F_b``).

    Returns the load (..., 6) and ``K = -d load / d(dr, dtheta)`` (..., 6, 6) for ``r``
    (..., 3) and ``R`` (..., 3, 3): the rotating arm, the heave stiffness ``rho g A`` and
    the moment change of the rising centre of buoyancy.
    """
    area, height = np.asarray(area, dtype=float), np.asarray(height, dtype=float)
    r, R = np.asarray(r, dtype=float), np.asarray(R, dtype=float)
    draft, d_draft = hull_draft(height, r[..., 2])
    rg = rho * gravity
    buoyancy = np.zeros(draft.shape + (3,))
    buoyancy[..., 2] = rg * area * draft
    center = np.zeros(draft.shape + (3,))
    center[..., 2] = -height / 2.0 + draft / 2.0
    load, K = point_load(buoyancy, center, R)
    # d(buoyancy)/dz = rho g A d'(z); the centre of buoyancy moves by d'(z) / 2 R e_z
    arm = _apply(R, center)
    dB = np.zeros_like(buoyancy)
    dB[..., 2] = rg * area * d_draft
    d_arm = 0.5 * d_draft[..., None] * R[..., :, 2]
    K[..., 2, 2] -= dB[..., 2]
    K[..., 3:, 2] -= np.cross(d_arm, buoyancy) + np.cross(arm, dB)
    return load, K


def waterplane_restoring(waterplane_inertia: ArrayLike, R: ArrayLike, rho: float,
                         gravity: float) -> tuple[FloatArray, FloatArray]:
    """Roll and pitch restoring of a waterplane with second moments ``(I_x, I_y)`` (..., 2):
    the moment ``-rho g (I_x phi_x, I_y phi_y, 0)``, ``phi`` the rotation vector of ``R``
    (the small-angle restoring coefficients of Tuah eq. 3.2.c.20; Wang, Er and Iu eq. 30's
    ``F_b1, F_b2``). Returns the load (..., 6) and ``K = -d load / d(dr, dtheta)``."""
    tilt = rotation_vector(R)
    restoring = np.zeros(tilt.shape)
    restoring[..., :2] = rho * gravity * np.asarray(waterplane_inertia, dtype=float)
    load = np.zeros(tilt.shape[:-1] + (6,))
    load[..., 3:] -= restoring * tilt
    K = np.zeros(tilt.shape[:-1] + (6, 6))
    K[..., 3:, 3:] += restoring[..., :, None] * inverse_left_jacobian(tilt)
    return load, K


def matrix_restoring(stiffness: ArrayLike, r: ArrayLike, R: ArrayLike, r_ref: ArrayLike,
                     R_ref: ArrayLike) -> tuple[FloatArray, FloatArray]:
    """A constant 6x6 restoring ``stiffness`` ``S`` about the reference pose
    ``(r_ref, R_ref)`` (Tuah eq. 3.2.c.20's ``K_R``): the load ``-S q`` (..., 6),
    ``q = (r - r_ref, phi)``, ``phi`` the rotation vector of ``R R_ref^T``, and
    ``K = -d load / d(dr, dtheta) = S blockdiag(I, J^-1(phi))`` (..., 6, 6)."""
    R, R_ref = np.asarray(R, dtype=float), np.asarray(R_ref, dtype=float)
    S = np.asarray(stiffness, dtype=float)
    turn = rotation_vector(R @ np.swapaxes(R_ref, -1, -2))
    q = np.concatenate((np.asarray(r, float) - np.asarray(r_ref, float), turn), axis=-1)
    jac = np.zeros(turn.shape[:-1] + (6, 6))
    jac[..., :3, :3] = _EYE
    jac[..., 3:, 3:] = inverse_left_jacobian(turn)
    return -_apply(S, q), S @ jac


# ---------------------------------------------------------------------- fluid loads
def body_drag(rho: float, Cd: ArrayLike, area: ArrayLike, u: ArrayLike,
              v: ArrayLike) -> tuple[FloatArray, FloatArray]:
    """Quadratic drag on the relative velocity, per world axis:
    ``F_i = rho Cd A_i |u_i - v_i| (u_i - v_i) / 2`` (..., 3), and ``dF / dv`` (..., 3, 3),
    the diagonal ``-rho Cd A_i |u_i - v_i|`` (Morison drag of a small body, Tuah sec. 3.2)."""
    rel = np.asarray(u, dtype=float) - np.asarray(v, dtype=float)
    Cd, area = np.asarray(Cd, dtype=float)[..., None], np.asarray(area, dtype=float)
    force = 0.5 * rho * Cd * area * np.abs(rel) * rel
    return force, -(rho * Cd * area * np.abs(rel))[..., None] * _EYE


def long_wave_load(rho: float, gravity: float, volume: ArrayLike, area_wp: ArrayLike,
                   added_mass: ArrayLike, fluid_acc: ArrayLike, eta: ArrayLike) -> FloatArray:
    """Long-wave (small-body) force at the body origin (..., 3): Froude-Krylov and added-mass
    ``(rho V I + A) a_f`` plus the waterplane heave excitation ``rho g A_wp eta`` (``A`` the
    translational 3x3 block of the added mass; ``a_f``, ``eta`` the fluid acceleration and
    surface elevation at the origin). Linear in ``a_f`` and ``eta``; it depends on the body
    state only through them (and ``V`` through the draft, :func:`hull_draft`)."""
    a_f = np.asarray(fluid_acc, dtype=float)
    force = (rho * np.asarray(volume, dtype=float)[..., None] * a_f
             + _apply(added_mass, a_f))
    force[..., 2] += rho * gravity * np.asarray(area_wp, dtype=float) * np.asarray(eta, float)
    return force


def exciting_table(omegas: ArrayLike, amplitude: ArrayLike, phase_deg: ArrayLike,
                   w: ArrayLike) -> tuple[FloatArray, FloatArray]:
    """An exciting-force table (``amplitude``, ``phase_deg`` (n_table, 6) over ``omegas``)
    interpolated at the wave frequencies ``w`` (m,): amplitude (m, 6), zero above the table's
    last frequency, and phase [rad] (m, 6)."""
    omegas, w = np.asarray(omegas, dtype=float), np.asarray(w, dtype=float)
    amplitude, phase_deg = np.asarray(amplitude, float), np.asarray(phase_deg, float)
    amp = np.column_stack([np.interp(w, omegas, amplitude[:, j], right=0.0) for j in range(6)])
    phase = np.radians(np.column_stack([np.interp(w, omegas, phase_deg[:, j])
                                        for j in range(6)]))
    return amp, phase


def wave_shift(wave_number: ArrayLike, heading: ArrayLike, phase: ArrayLike,
               origin: ArrayLike) -> FloatArray:
    """Phase shift ``k_m x_0 + phi_m`` (m,) of the wave components (wave numbers, headings
    [rad], phases (m,)) at the reference position ``origin`` (3,), ``x_0`` its horizontal
    position along each heading."""
    heading = np.asarray(heading, dtype=float)
    along = origin[0] * np.cos(heading) + origin[1] * np.sin(heading)
    return np.asarray(wave_number, dtype=float) * along + np.asarray(phase, dtype=float)


def wave_excitation(t: float, amplitude: ArrayLike, omega: ArrayLike, shift: ArrayLike,
                    force_amplitude: ArrayLike, force_phase: ArrayLike,
                    ramp: float = 1.0) -> FloatArray:
    """Wave exciting force (6,) summed over the wave components (Tuah eq. 3.2.c.20's
    ``C_l e^{i w t}``):

        F_j = ramp sum_m a_m |X_j(w_m)| cos(w_m t - shift_m + arg X_j(w_m))

    for ``eta = sum_m a_m cos(k_m x - w_m t + phi_m)``, ``shift_m = k_m x_0 + phi_m`` (``x_0``
    the reference position along the component's heading). ``amplitude``, ``omega``,
    ``shift`` (m,) (:func:`wave_shift`); ``force_amplitude``, ``force_phase`` (m, 6)
    (:func:`exciting_table`).
    Independent of the body state (its tangent is zero).
    """
    a = np.asarray(amplitude, dtype=float)
    arg = np.asarray(omega, dtype=float) * t - np.asarray(shift, dtype=float)
    terms = a[:, None] * np.asarray(force_amplitude, float) * np.cos(
        arg[:, None] + np.asarray(force_phase, float))
    return ramp * terms.sum(axis=0)
