"""Buoyancy of slender cylinders ("rods") fixed in a rigid body, at any pose, with its exact
tangent (issue 14: surface-piercing and emerging rods).

Model (following MoorDyn-C v2.7 ``source/Rod.cpp``, ``Rod::doRHS``: the submerged length of
the axis under the still water level, ``h0``, and the buoyancy of that length): a rod from
``a`` to ``b`` (body frame) of diameter ``d`` has its axis submerged over the fraction
``[s0, s1]`` of its length below ``z = 0`` (one end crossing: ``s* = z_a / (z_a - z_b)``).
The buoyancy is ``rho g (pi d^2 / 4) L (s1 - s0)`` upward, acting at the centre of the
submerged part of the axis. This is the exact volume of a cylinder cut obliquely by the
surface (while the cut does not reach an end cap), and MoorDyn's total force (its radial
node buoyancy plus the pressure on the submerged end caps sum to it).

What differs from MoorDyn: MoorDyn weights the nodes by a volume-of-fluid fraction and adds
two small moments, the end caps' ``pi d^4 / 64`` and the waterplane's
``pi d^4 / 16 sin(phi) cos(phi)``; here neither is included: the centre of buoyancy is on the
axis, so the metacentric radius of the cut ``I_wp / V = d^2 / (16 L_sub)`` (relative
``O(d^2 / L^2)`` for a slender rod) is neglected. The still water level only (no waves).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .rigid_body import skew

FloatArray = NDArray[np.float64]


def submerged_span(za: FloatArray, zb: FloatArray
                   ) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """Submerged fractions ``(s0, s1)`` of the axis from end A (heights ``za``, ``zb`` of the
    ends, (n,)) and their derivatives with respect to ``(za, zb)``: ``ds0``, ``ds1`` (n, 2)."""
    za, zb = np.asarray(za, dtype=float), np.asarray(zb, dtype=float)
    crossing = (za < 0.0) != (zb < 0.0)
    both_wet = (za < 0.0) & (zb < 0.0)
    diff = np.where(crossing, za - zb, 1.0)
    s = np.where(crossing, za / diff, 0.0)
    ds = np.stack((-zb / diff**2, za / diff**2), axis=-1) * crossing[:, None]
    a_wet = za < 0.0
    s0 = np.where(crossing & ~a_wet, s, 0.0)
    s1 = np.where(both_wet, 1.0, np.where(crossing, np.where(a_wet, s, 1.0), 0.0))
    ds0 = np.where((crossing & ~a_wet)[:, None], ds, 0.0)
    ds1 = np.where((crossing & a_wet)[:, None], ds, 0.0)
    return s0, s1, ds0, ds1


def rod_buoyancy(a: ArrayLike, b: ArrayLike, diameter: ArrayLike, r: ArrayLike, R: ArrayLike,
                 rho: float, gravity: float) -> tuple[FloatArray, FloatArray]:
    """Buoyancy of rods (body-frame ends ``a``, ``b`` (n, 3), ``diameter`` (n,) [length]) of
    a body at position ``r`` (3,) and rotation ``R`` (3, 3), summed (module docstring).

    Returns the load ``(F, M)`` (6,) about the body origin, world axes, and its tangent
    ``K = -d load / d(dr, dtheta)`` (6, 6) (``R <- exp([dtheta x]) R``), exact away from the
    poses where an end is exactly at ``z = 0`` (a kink: the submerged length's slope jumps).
    """
    a, b = np.atleast_2d(np.asarray(a, float)), np.atleast_2d(np.asarray(b, float))
    R, r = np.asarray(R, dtype=float), np.asarray(r, dtype=float)
    A, B = a @ R.T, b @ R.T  # world arms of the ends (n, 3)
    za, zb = r[2] + A[:, 2], r[2] + B[:, 2]
    s0, s1, ds0, ds1 = submerged_span(za, zb)
    D = B - A
    length = np.linalg.norm(D, axis=1)
    weight = rho * gravity * np.pi * np.asarray(diameter, float) ** 2 / 4.0 * length  # per s
    lift = weight * (s1 - s0)  # (n,)
    mid = 0.5 * (s0 + s1)
    arm = A + mid[:, None] * D
    F = np.zeros((len(lift), 3))
    F[:, 2] = lift
    load = np.concatenate((F.sum(axis=0), np.cross(arm, F).sum(axis=0)))
    # derivatives of the end heights: dz_end = dr_z + dtheta . (arm_end x e_z)
    ez = np.array([0.0, 0.0, 1.0])
    gz = np.zeros((len(lift), 2, 6))
    gz[:, :, 2] = 1.0
    gz[:, 0, 3:] = np.cross(A, ez)
    gz[:, 1, 3:] = np.cross(B, ez)
    d_s0 = np.einsum("nk,nkj->nj", ds0, gz)  # (n, 6)
    d_s1 = np.einsum("nk,nkj->nj", ds1, gz)
    d_lift = weight[:, None] * (d_s1 - d_s0)
    d_mid = 0.5 * (d_s0 + d_s1)
    # d arm = dtheta x arm + D d_mid;  dM = d arm x F + arm x dF
    d_arm = np.zeros((len(lift), 3, 6))
    d_arm[:, :, 3:] = -skew(arm)
    d_arm += D[:, :, None] * d_mid[:, None, :]
    dF = np.zeros((len(lift), 3, 6))
    dF[:, 2, :] = d_lift
    dM = -np.einsum("nij,njk->nik", skew(F), d_arm) + np.einsum("nij,njk->nik", skew(arm), dF)
    K = -np.concatenate((dF.sum(axis=0), dM.sum(axis=0)), axis=0)
    return load, K
