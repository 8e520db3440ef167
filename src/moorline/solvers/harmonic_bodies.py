"""Rigid bodies in harmonic balance: the body motion as Fourier series and its kinematics.

A free body's six unknowns per harmonic are its origin ``r(t)`` and a rotation vector
``phi(t)`` relative to its static orientation, ``R(t) = exp([phi(t) x]) R_s``, each a real
Fourier series like the node positions (:mod:`moorline.solvers.harmonic`). The time-domain
body model (:class:`~moorline.solvers.body_model.BodyModel`) wants world angular velocity and
acceleration; for the left-acting exponential map (``d R R^T = [(J(phi) d phi) x]``, ``J`` the
left Jacobian of :func:`moorline.physics.rigid_body.left_jacobian`)

    omega = J(phi) phi',
    alpha = J(phi) phi'' + (dJ/dt) phi'
          = J phi'' + 2 (phi . phi') (b_s phi x phi' + c_s phi x (phi x phi'))
            + c phi' x (phi x phi'),

with ``J = I + b P + c P^2``, ``P = [phi x]``, ``b = (1 - cos t) / t^2``, ``c = (t - sin t) /
t^3``, ``t = |phi|``, and ``b_s``, ``c_s`` their derivatives with respect to ``s = t^2``
(the identity ``d/dt (P^2) phi' = phi' x (phi x phi')`` because ``phi' x phi' = 0``). The
derivatives of ``omega`` and ``alpha`` with respect to ``phi`` and ``phi'`` are taken by the
complex step (exact to round-off: the functions are analytic in ``s``, evaluated by series
near zero), so the harmonic-balance Jacobian stays exact.

Frequency-dependent radiation (:class:`~moorline.model.RadiationTable`) enters per harmonic:
the force of harmonic ``k`` is ``-A(k w) a_k - B(k w) v_k`` (``a_k``, ``v_k`` the harmonic-
``k`` parts of the body's generalized acceleration and velocity), which
:func:`radiation_matrices` tabulates.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ..physics.rigid_body import skew

FloatArray = NDArray[np.float64]

_SERIES = 1e-2  # |s| = |phi|^2 below this: the coefficients by their Taylor series


def _coefficients(s):
    """``b, c, db/ds, dc/ds`` of ``s = t^2`` (complex-safe; series for small ``|s|``)."""
    s = np.asarray(s)
    small = np.abs(s) < _SERIES
    ss = np.where(small, 1.0, s)
    t = np.sqrt(ss)
    one_minus_cos, t_minus_sin = 1.0 - np.cos(t), t - np.sin(t)
    b = one_minus_cos / ss
    c = t_minus_sin / (ss * t)
    db = (t * np.sin(t) - 2.0 * one_minus_cos) / (2.0 * ss * ss)
    dc = (one_minus_cos * t - 3.0 * t_minus_sin) / (2.0 * ss * ss * t)
    # Taylor series in s (truncation below 1e-15 relative for |s| < 1e-2)
    b_s = 1 / 2 - s / 24 + s**2 / 720 - s**3 / 40320 + s**4 / 3628800
    c_s = 1 / 6 - s / 120 + s**2 / 5040 - s**3 / 362880 + s**4 / 39916800
    db_s = -1 / 24 + s / 360 - s**2 / 13440 + s**3 / 907200
    dc_s = -1 / 120 + s / 2520 - s**2 / 120960 + s**3 / 9979200
    return (np.where(small, b_s, b), np.where(small, c_s, c), np.where(small, db_s, db),
            np.where(small, dc_s, dc))


def _cross(a, b):
    """Cross product of (..., 3) arrays (complex-safe)."""
    return np.stack((a[..., 1] * b[..., 2] - a[..., 2] * b[..., 1],
                     a[..., 2] * b[..., 0] - a[..., 0] * b[..., 2],
                     a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]), axis=-1)


def _omega_alpha(phi, dphi, ddphi):
    """World angular velocity and acceleration (..., 3) of ``R = exp([phi x]) R_s``."""
    s = np.einsum("...i,...i->...", phi, phi)
    b, c, db, dc = (x[..., None] for x in _coefficients(s))
    p_d = _cross(phi, dphi)
    pp_d = _cross(phi, p_d)
    omega = dphi + b * p_d + c * pp_d
    p_dd = _cross(phi, ddphi)
    jdd = ddphi + b * p_dd + c * _cross(phi, p_dd)
    rate = 2.0 * np.einsum("...i,...i->...", phi, dphi)[..., None]
    alpha = jdd + rate * (db * p_d + dc * pp_d) + c * _cross(dphi, p_d)
    return omega, alpha


def left_jacobians(phi: FloatArray) -> FloatArray:
    """``J(phi)`` (..., 3, 3) (the same series as the kinematics)."""
    s = np.einsum("...i,...i->...", phi, phi)
    b, c = (x[..., None, None] for x in _coefficients(s)[:2])
    P = skew(phi)
    return np.eye(3) + b * P + c * (P @ P)


def angular_kinematics(phi: FloatArray, dphi: FloatArray, ddphi: FloatArray
                       ) -> tuple[FloatArray, ...]:
    """Angular velocity and acceleration of rotation-vector histories, with derivatives.

    Parameters
    ----------
    phi, dphi, ddphi
        Rotation vector and its first two time derivatives at the instants (n, 3).

    Returns
    -------
    omega, alpha
        (n, 3) each.
    J
        ``d omega / d phi' = d alpha / d phi''`` = ``J(phi)`` (n, 3, 3), also the map of a
        change ``d phi`` to the left rotation it applies, ``d theta = J d phi``.
    d_omega_d_phi, d_alpha_d_phi, d_alpha_d_dphi
        (n, 3, 3) each, by the complex step.
    """
    phi, dphi, ddphi = (np.asarray(a, dtype=float) for a in (phi, dphi, ddphi))
    omega, alpha = _omega_alpha(phi, dphi, ddphi)
    h = 1e-30
    n = phi.shape[0]
    dw_dp, da_dp, da_dd = (np.zeros((n, 3, 3)) for _ in range(3))
    for i in range(3):
        e = np.zeros(3)
        e[i] = h
        w, al = _omega_alpha(phi + 1j * e, dphi, ddphi)
        dw_dp[:, :, i], da_dp[:, :, i] = w.imag / h, al.imag / h
        da_dd[:, :, i] = _omega_alpha(phi, dphi + 1j * e, ddphi)[1].imag / h
    return omega, alpha, left_jacobians(phi), dw_dp, da_dp, da_dd


def interpolate_radiation(table, omegas: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Added mass and damping of a :class:`~moorline.model.RadiationTable` at ``omegas``
    (m,): linear interpolation per coefficient, held at the table's first and last values
    outside it. Returns ``A``, ``B`` (m, 6, 6)."""
    w = np.asarray(table.omegas, dtype=float)
    A = np.asarray(table.added_mass, dtype=float).reshape(len(w), 36)
    B = np.asarray(table.damping, dtype=float).reshape(len(w), 36)
    omegas = np.asarray(omegas, dtype=float)
    out = [np.column_stack([np.interp(omegas, w, M[:, i]) for i in range(36)])
           .reshape(-1, 6, 6) for M in (A, B)]
    return out[0], out[1]


def radiation_matrices(table, omega: float, n: int) -> tuple[FloatArray, FloatArray]:
    """``A(k w)``, ``B(k w)`` per harmonic term (2 n + 1, 6, 6): the mean, then the cosine
    and the sine of every harmonic ``k`` (the same matrices for both). The mean's are zero:
    the radiation force has no mean (``B(0) = 0``, and a periodic motion's mean
    acceleration vanishes)."""
    k = np.repeat(np.arange(1, n + 1), 2)
    A, B = interpolate_radiation(table, k * omega)
    zero = np.zeros((1, 6, 6))
    return np.concatenate((zero, A)), np.concatenate((zero, B))


__all__ = ["angular_kinematics", "interpolate_radiation", "left_jacobians",
           "radiation_matrices"]
