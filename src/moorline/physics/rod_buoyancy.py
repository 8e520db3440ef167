"""Buoyancy of slender cylinders ("rods") fixed in a rigid body, at any pose, with its exact
tangent (issue 14: surface-piercing and emerging rods).

Model (the submerged length of the axis under the still water level, as MoorDyn-C v2.7
``source/Rod.cpp``, ``Rod::doRHS``, ``h0``): a rod from ``a`` to ``b`` (body frame) of
diameter ``d`` has its axis submerged over the fraction ``[s0, s1]`` of its length below
``z = 0`` (one end crossing: ``s* = z_a / (z_a - z_b)``). The buoyancy is
``rho g (pi d^2 / 4) L (s1 - s0)`` upward, at the centre of the submerged part of the axis,
plus, for a rod piercing the surface, the moment of the cut's waterplane (below). This is
Archimedes' force and moment of the cylinder cut obliquely by the surface, exact while the
waterline ellipse stays on the rod's side (``h_w, h_d >= (d / 2) tan(phi)``, ``h_w`` and
``h_d`` the wet and dry axis lengths).

Waterplane moment: tilted by ``phi`` from vertical (unit axis ``t`` from the wet end up,
``cos(phi) = t_z``), the submerged volume's centroid lies off the axis (transverse offset
``tan(phi) I / (A h_w)``, axial ``tan(phi)^2 I / (2 A h_w)``, ``I = pi d^4 / 64``, by
integrating the wet length ``h_w + u tan(phi)`` over the cross-section), which adds the
couple ``M = rho g I (1 + tan(phi)^2 / 2) (t x e_z)`` to the buoyancy at the axis centre
(restoring: ``rho g I phi`` at small tilt, the metacentric ``rho g I_wp``; derived here,
checked by quadrature in tests/test_rod_buoyancy.py). Beyond the validity bound (a rod near
horizontal) ``tan(phi)`` is capped at ``2 min(h_w, h_d) / d``, where the waterline reaches an
end cap: the moment stays bounded (and continuous); the axis-length buoyancy is itself only
approximate there.

What differs from MoorDyn-C v2.7 (Rod.cpp, checked against the ``moordyn`` module on
r-test md_float, tests/test_neutral_bodies.py): MoorDyn weights its nodes by a volume-of-fluid
fraction (the same total force) and for a piercing rod adds ``rho g pi d^4 / 16 sin(phi)
cos(phi)`` ("waterplane moment", four times ``rho g I``) and, at the submerged end cap,
``-rho g I sin(phi)`` (of the opposite sign to the cap's pressure-centre moment): a pitch
stiffness of ``3 rho g I`` at small tilt instead of the exact ``rho g I`` (the MoorDyn
developers note the waterplane moment is wrong, FloatingArrayDesign/MoorDyn issue #70). Both
end-cap moments of a fully wet rod cancel (as here). The still water level only (no waves).
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
    M_wp, dM_wp = waterplane_moment(D, length, np.asarray(diameter, float), za, zb,
                                    (s1 - s0), d_s1 - d_s0, rho * gravity)
    load[3:] += M_wp.sum(axis=0)
    K = -np.concatenate((dF.sum(axis=0), (dM + dM_wp).sum(axis=0)), axis=0)
    return load, K


def waterplane_moment(D: FloatArray, length: FloatArray, diameter: FloatArray,
                      za: FloatArray, zb: FloatArray, wet: FloatArray, d_wet: FloatArray,
                      rho_g: float) -> tuple[FloatArray, FloatArray]:
    """The waterplane couple of rods piercing the surface (module docstring) and its
    derivative along ``(dr, dtheta)``.

    Parameters
    ----------
    D
        World axes ``b - a`` of the rods (n, 3) [length]; ``length`` (n,) their norms.
    za, zb
        Heights of the ends (n,) [length]: a rod crosses when they have opposite signs.
    wet, d_wet
        Wet fraction of the axis ``s1 - s0`` (n,) and its derivative (n, 6).
    rho_g
        ``rho g`` [force / length^3].

    Returns
    -------
    M, dM
        Couples (n, 3) and their derivatives ``dM / d(dr, dtheta)`` (n, 3, 6); zero for
        rods not crossing ``z = 0``.
    """
    n = len(D)
    crossing = (za < 0.0) != (zb < 0.0)
    if not crossing.any():
        return np.zeros((n, 3)), np.zeros((n, 3, 6))
    ez = np.array([0.0, 0.0, 1.0])
    up = np.where(za < 0.0, 1.0, -1.0)[:, None] * D / length[:, None]  # t: wet end up
    c = np.where(crossing, up[:, 2], 1.0)  # cos(phi) > 0 when crossing
    sin2 = np.clip(1.0 - c**2, 0.0, None)
    h_wet = wet * length
    dry_shorter = length - h_wet < h_wet
    h = np.where(dry_shorter, length - h_wet, h_wet)
    dh = np.where(dry_shorter[:, None], -1.0, 1.0) * length[:, None] * d_wet
    tan_cap = 2.0 * h / diameter
    capped = sin2 > (tan_cap * c) ** 2  # tan(phi) beyond the cap
    c_free = np.where(capped, 1.0, c)  # c only where not capped (a rod near horizontal is)
    tan2 = np.where(capped, tan_cap**2, sin2 / c_free**2)
    f = 1.0 + 0.5 * tan2
    arm = np.cross(up, ez)  # t x e_z, |.| = sin(phi)
    # df: capped: tan dtan, dtan = 2 dh / d; else f = (1 + 1/c^2) / 2, df = -dc / c^3 with
    # dc = d t_z = dtheta . (t x e_z)
    df = np.zeros((n, 6))
    df[:, 3:] = -arm / c_free[:, None] ** 3
    df = np.where(capped[:, None], (tan_cap * 2.0 / diameter)[:, None] * dh, df)
    scale = np.where(crossing, rho_g * np.pi * diameter**4 / 64.0, 0.0)
    M = (scale * f)[:, None] * arm
    # d(t x e_z) = (dtheta x t) x e_z = [e_z x][t x] dtheta
    d_arm = np.zeros((n, 3, 6))
    d_arm[:, :, 3:] = np.einsum("ij,njk->nik", skew(ez), skew(up))
    dM = scale[:, None, None] * (arm[:, :, None] * df[:, None, :] + f[:, None, None] * d_arm)
    return M, dM
