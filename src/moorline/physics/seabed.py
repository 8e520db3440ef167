"""Seabed contact: a penalty spring and damper on nodes at the seabed surface, and friction.

The surface is a :class:`~moorline.physics.bathymetry.SeabedSurface` ``z = h(x, y)`` (flat at
``z = -depth``, an inclined plane or a bilinear grid). A node's penetration is measured along
the surface's local normal, ``d = (z - h) / sqrt(1 + |grad h|^2)`` (the exact distance to a
plane, to first order in the distance for the bilinear grid), and the contact force is
``F(d) grad d``: the gradient of the contact energy ``E(d)``, so conservative, normal to a
plane and of magnitude ``F``; on a flat seabed ``d = z + depth`` and the force is vertical,
as before (:func:`surface_contact`). MoorDyn-C v2.7 (``source/Line.cpp``, "bottom contact
(stiffness and damping, vertical-only for now)") measures the penetration vertically and
pushes vertically on its 3-D seafloor too, so that a frictionless line rests anywhere on a
slope; here the seabed pushes along its normal and a frictionless line slides down.

The contact law along that normal distance:

MoorDyn's model (kBot, cBot per unit contact area) switches both on at first contact, so the
force has a kink (spring) and a jump (damper) as a node lands. An implicit Newton iteration
cycles across such switches instead of converging. Here both blend in over a band ``ramp``
(a few millimetres: at least the static penetration of a lying line, :func:`contact_ramp`)
centred on the seabed surface: with the penetration ``p`` and ``q = p + ramp / 2``,

    spring  k q^2 / (2 ramp)   for -ramp/2 < p < ramp/2,   k p   beyond,
    damper  -c v_n min(q / ramp, 1),   v_n = grad d . v  (v_z on a flat seabed).

The spring is C1 with a stiffness rising monotonically from 0 to ``k`` (a C1 blend that is
``k p`` beyond the band and starts at ``p = 0`` would need a stiffness above ``k`` inside it,
which harmonic balance and Newton do not like), the damper continuous. Beyond ``ramp / 2``
both are MoorDyn's, so a line lying on a soft seabed rests at MoorDyn's penetration
``w / k`` (an earlier blend over ``0 < p < ramp``, ``k p^2 / (2 ramp)`` then ``k (p - ramp /
2)``, put it ``ramp / 2`` deeper: 0.35 % in the statics of a deck with kBot = 1e5 Pa/m); on
a stiff seabed a lying node carries its weight within the band, at most ``ramp / 2`` above
the surface. Unlike MoorDyn, the total never pulls: a node lifting off faster than the
spring pushes feels no seabed force (MoorDyn's damper sucks it down; that suction also
leaves implicit steps without a solution near the seabed). Friction acts in the surface's
tangent plane (the horizontal plane on a flat seabed).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from .bathymetry import SeabedSurface

FloatArray = NDArray[np.float64]

#: Smallest blend-in penetration, in line diameters.
RAMP_DIAMETERS = 0.25


def contact_force(
    height: FloatArray, vz: FloatArray, k: FloatArray, c: FloatArray, ramp: FloatArray
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Upward seabed reaction on nodes at ``height`` above the seabed (negative: inside).

    Parameters
    ----------
    height
        ``z - seabed_z`` per node.
    vz
        Vertical node velocity (zeros in statics).
    k, c
        Contact stiffness [force/length] and damping [force*time/length] per node.
    ramp
        Penetration over which the contact blends in [length], > 0.

    Returns
    -------
    force, dforce_dz, dforce_dvz
        Upward force and its derivatives with respect to ``z`` and ``v_z`` (n_nodes,).
    """
    p = -height
    q = p + 0.5 * ramp
    touching = q > 0
    share = np.clip(q / ramp, 0.0, 1.0)
    full = q >= ramp
    spring = np.where(full, k * p, 0.5 * k * q * share)
    total = spring - c * share * vz
    pushing = touching & (total > 0)  # the seabed pushes, it never pulls a lifting node down
    force = np.where(pushing, total, 0.0)
    d_spring = np.where(full, k, k * share)  # d(spring)/dp
    d_damp = np.where(~full, c * vz / ramp, 0.0)  # d(c share vz)/dp
    d_dz = np.where(pushing, -d_spring + d_damp, 0.0)
    d_dv = np.where(pushing, -c * share, 0.0)
    return force, d_dz, d_dv


@dataclass(frozen=True)
class Contact:
    """Seabed contact on every node (:func:`surface_contact`); derivatives (n, 3, 3) are
    ``d row / d column``."""

    force: FloatArray         # (n, 3) contact force on each node
    normal: FloatArray        # (n,) its magnitude along grad d, F (friction's normal force)
    dnormal_dx: FloatArray    # (n, 3)
    dnormal_dv: FloatArray    # (n, 3)
    stiffness: FloatArray     # (n, 3, 3) d force / d x
    damping: FloatArray       # (n, 3, 3) d force / d v
    unit_normal: FloatArray   # (n, 3) upward unit normal of the surface under each node
    dunit_dx: FloatArray      # (n, 3, 3) its derivative with respect to the position


def normal_distance(x: FloatArray, surface: SeabedSurface
                    ) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Signed distance ``d = (z - h) / s`` of points ``x`` (n, 3) above the seabed along its
    normal, ``s = sqrt(1 + h_x^2 + h_y^2)``, with its gradient (n, 3) and Hessian (n, 3, 3).

    Exact for a plane; for the bilinear grid (Hessian ``H`` of ``h`` constant in a cell, third
    derivatives zero) the derivatives are those of this ``d``:
    ``d_z = 1/s``, ``d_u = -G/s - g s_u/s^2``, ``d_zu = -s_u/s^2``,
    ``d_uu = -H/s + (G s_u^T + s_u G^T)/s^2 - g s_uu/s^2 + 2 g s_u s_u^T/s^3`` with ``g = z - h``,
    ``G = grad h``, ``s_u = H G / s`` and ``s_uu = (H H - s_u s_u^T) / s``.
    """
    if surface.is_flat:
        grad = np.zeros((len(x), 3))
        grad[:, 2] = 1.0
        return x[:, 2] - surface.z0, grad, np.zeros((len(x), 3, 3))
    h, G, H = surface.evaluate(x)
    g = x[:, 2] - h
    s = np.sqrt(1.0 + np.einsum("ij,ij->i", G, G))
    su = np.einsum("nij,nj->ni", H, G) / s[:, None]
    suu = (np.einsum("nik,nkj->nij", H, H) - su[:, :, None] * su[:, None, :]) / s[:, None, None]
    d = g / s
    grad = np.empty((len(x), 3))
    grad[:, :2] = -G / s[:, None] - (g / s**2)[:, None] * su
    grad[:, 2] = 1.0 / s
    hess = np.zeros((len(x), 3, 3))
    outer = G[:, :, None] * su[:, None, :]
    hess[:, :2, :2] = (-H / s[:, None, None] + (outer + outer.transpose(0, 2, 1))
                       / (s**2)[:, None, None] - (g / s**2)[:, None, None] * suu
                       + (2.0 * g / s**3)[:, None, None] * su[:, :, None] * su[:, None, :])
    hess[:, 2, :2] = hess[:, :2, 2] = -su / (s**2)[:, None]
    return d, grad, hess


def surface_normal(x: FloatArray, surface: SeabedSurface) -> tuple[FloatArray, FloatArray]:
    """Upward unit normal ``n = (-G, 1) / s`` of the surface under points ``x`` (n, 3) and its
    derivative with respect to the position (n, 3, 3): ``dn/du_j = (-H_j, 0)/s - n s_j/s``."""
    if surface.is_flat:
        n = np.zeros((len(x), 3))
        n[:, 2] = 1.0
        return n, np.zeros((len(x), 3, 3))
    _, G, H = surface.evaluate(x)
    s = np.sqrt(1.0 + np.einsum("ij,ij->i", G, G))
    n = np.empty((len(x), 3))
    n[:, :2] = -G / s[:, None]
    n[:, 2] = 1.0 / s
    su = np.einsum("nij,nj->ni", H, G) / s[:, None]
    dn = np.zeros((len(x), 3, 3))
    dn[:, :2, :2] = -H / s[:, None, None]
    dn[:, :, :2] -= n[:, :, None] * (su / s[:, None])[:, None, :]
    return n, dn


def surface_contact(x: FloatArray, v: FloatArray, surface: SeabedSurface, k: FloatArray,
                    c: FloatArray, ramp: FloatArray) -> Contact:
    """Contact of nodes at ``x`` moving at ``v`` (n, 3) with the seabed ``surface``: the law
    of :func:`contact_force` on the normal distance ``d`` and its rate ``v_n = grad d . v``,
    pushing along ``grad d`` (module docstring). ``k``, ``c``, ``ramp`` as in
    :func:`contact_force`."""
    if surface.is_flat:  # the same numbers, without the products with 0 and 1
        return _flat_contact(x, v, surface.z0, k, c, ramp)
    d, grad, hess = normal_distance(x, surface)
    vn = np.einsum("ij,ij->i", grad, v)
    F, F_d, F_v = contact_force(d, vn, k, c, ramp)
    hv = np.einsum("nij,nj->ni", hess, v)  # d(v_n)/dx
    dN_dx = F_d[:, None] * grad + F_v[:, None] * hv
    dN_dv = F_v[:, None] * grad
    unit, dunit = surface_normal(x, surface)
    return Contact(
        force=F[:, None] * grad, normal=F, dnormal_dx=dN_dx, dnormal_dv=dN_dv,
        stiffness=grad[:, :, None] * dN_dx[:, None, :] + F[:, None, None] * hess,
        damping=grad[:, :, None] * dN_dv[:, None, :], unit_normal=unit, dunit_dx=dunit)


def _flat_contact(x: FloatArray, v: FloatArray, z0: float, k: FloatArray, c: FloatArray,
                  ramp: FloatArray) -> Contact:
    n = len(x)
    F, F_d, F_v = contact_force(x[:, 2] - z0, v[:, 2], k, c, ramp)
    force, dN_dx, dN_dv, unit = (np.zeros((n, 3)) for _ in range(4))
    stiffness, damping = np.zeros((n, 3, 3)), np.zeros((n, 3, 3))
    force[:, 2], dN_dx[:, 2], dN_dv[:, 2], unit[:, 2] = F, F_d, F_v, 1.0
    stiffness[:, 2, 2], damping[:, 2, 2] = F_d, F_v
    return Contact(force=force, normal=F, dnormal_dx=dN_dx, dnormal_dv=dN_dv,
                   stiffness=stiffness, damping=damping, unit_normal=unit,
                   dunit_dx=np.zeros((n, 3, 3)))


def surface_energy(x: FloatArray, surface: SeabedSurface, k: FloatArray,
                   ramp: FloatArray) -> float:
    """Energy stored in the seabed springs at positions ``x`` (:func:`contact_energy` of the
    normal distance), the potential of :func:`surface_contact` without damping."""
    return contact_energy(normal_distance(x, surface)[0], k, ramp)


def contact_energy(height: FloatArray, k: FloatArray, ramp: FloatArray) -> float:
    """Energy stored in the seabed springs (the potential of :func:`contact_force` with
    ``c = 0``): ``k q^3 / (6 ramp)`` within the band, ``k (p^2 / 2 + ramp^2 / 24)`` beyond."""
    p = -height
    q = np.maximum(p + 0.5 * ramp, 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        partial = k * q**3 / (6.0 * ramp)
    energy = np.where(q >= ramp, k * (0.5 * p**2 + ramp**2 / 24.0), partial)
    return float(np.sum(np.where(q > 0, energy, 0.0)))


def resting_penetration(load: FloatArray, k: FloatArray, ramp: FloatArray) -> FloatArray:
    """Penetration at which the spring of :func:`contact_force` carries ``load``: ``load / k``
    from ``k ramp / 2`` on, below it ``sqrt(2 ramp load / k) - ramp / 2`` (negative: the
    node rests within the band above the surface); 0 where ``k`` or the load is not
    positive."""
    load = np.maximum(np.asarray(load, dtype=float), 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        p = np.where(load >= 0.5 * k * ramp, load / k,
                     np.sqrt(2.0 * ramp * load / k) - 0.5 * ramp)
    return np.where((k > 0) & (load > 0), p, 0.0)


def carried_share(height: FloatArray, k: FloatArray, ramp: FloatArray, load: FloatArray
                  ) -> tuple[FloatArray, FloatArray]:
    """How fully the seabed carries each node, (n,), and its derivative with respect to the
    height, for the sag correction (:mod:`moorline.physics.sag`).

    ``u = S(height) / (load / 2)``, ``S`` the spring of :func:`contact_force` (``c = 0``), and
    the share ``3 u^2 - 2 u^3`` of ``u`` clipped to [0, 1]: 0 above the contact band, 1 once
    the spring carries half the node's own load or more (a lying node carries all of it, so
    it sits well inside), C1 in the height. 0 where ``load <= 0`` (a buoyant node).
    """
    spring, d_spring, _ = contact_force(height, np.zeros_like(height), k,
                                        np.zeros_like(height), ramp)
    half = 0.5 * np.asarray(load, dtype=float)
    safe = np.where(half > 0, half, 1.0)
    u = np.where(half > 0, spring / safe, 0.0)
    inside = (u > 0) & (u < 1)
    uc = np.clip(u, 0.0, 1.0)
    share = uc * uc * (3.0 - 2.0 * uc)
    slope = np.where(inside, 6.0 * uc * (1.0 - uc) * d_spring / safe, 0.0)
    return share, slope


def contact_ramp(weight_per_node: FloatArray, k: FloatArray, diameter: float) -> FloatArray:
    """Blend-in penetration per node: the static penetration of a lying line (its weight over
    its contact stiffness), at least a thousandth of the diameter."""
    with np.errstate(divide="ignore", invalid="ignore"):
        ramp = np.where(k > 0, np.maximum(weight_per_node, 0.0) / k, 0.0)
    return np.maximum(ramp, RAMP_DIAMETERS * max(diameter, 1e-3))


def friction_force(
    velocity: FloatArray, normal: FloatArray, axis: FloatArray, mu_axial: float,
    mu_transverse: float, slip_velocity: float, unit_normal: FloatArray | None = None,
    dunit_dx: FloatArray | None = None,
) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """Regularized Coulomb friction on nodes resting on the seabed.

    The velocity's part in the seabed's tangent plane (the horizontal plane without
    ``unit_normal``) is split into its part along the line (``axis``, a unit vector in that
    plane per node) and across it; each part is resisted by ``mu N tanh(|v| / v_s) v / |v|``,
    a smooth stand-in for Coulomb friction (full friction once sliding faster than a few
    ``v_s``; a viscous law near rest, so no stick-slip switch upsets Newton), as MoorDyn's
    axial and transverse seabed friction. With equal coefficients the law is isotropic and
    independent of ``axis``; with different ones the force depends on the line direction,
    whose change with the positions the returned derivatives leave out.

    Parameters
    ----------
    velocity
        Node velocities (n, 3).
    normal
        Seabed normal force per node (n,) (zero off the seabed).
    axis
        Unit vector along the line at each node, in the tangent plane (n, 3).
    mu_axial, mu_transverse
        Friction coefficients along and across the line.
    slip_velocity
        Regularization speed ``v_s`` [length/time].
    unit_normal, dunit_dx
        Upward unit normal of the seabed under each node (n, 3) and its position derivative
        (n, 3, 3) (:func:`surface_normal`); ``None``: a flat seabed.

    Returns
    -------
    force, dforce_dv, dforce_dnormal, dforce_dx
        Friction force (n, 3), its derivative with respect to the velocity (n, 3, 3), to the
        normal force (n, 3) and to the position through the seabed normal (n, 3, 3).
    """
    n = len(normal)
    if unit_normal is None:  # flat: the horizontal plane
        unit_normal = np.tile([0.0, 0.0, 1.0], (n, 1))
        tangential = velocity.copy()
        tangential[:, 2] = 0.0
        projector, dvt_dx = np.diag([1.0, 1.0, 0.0]), None
    else:
        along = np.einsum("ij,ij->i", unit_normal, velocity)
        tangential = velocity - unit_normal * along[:, None]
        projector = np.eye(3) - unit_normal[:, :, None] * unit_normal[:, None, :]
        # d(tangential)/dx through the normal: -(dn (n . v) + n (v . dn))
        dvt_dx = -(dunit_dx * along[:, None, None] + unit_normal[:, :, None]
                   * np.einsum("nb,nbj->nj", velocity, dunit_dx)[:, None])
    if mu_axial == mu_transverse:
        return _isotropic_friction(tangential, normal, mu_axial, slip_velocity, projector,
                                   dvt_dx)
    force = np.zeros((n, 3))
    d_dv = np.zeros((n, 3, 3))
    d_dn = np.zeros((n, 3))
    across = np.cross(unit_normal, axis)
    for mu, direction in ((mu_axial, axis), (mu_transverse, across)):
        if mu == 0.0:
            continue
        speed = np.einsum("ij,ij->i", tangential, direction)
        th = np.tanh(speed / slip_velocity)
        f = -mu * normal * th
        force += f[:, None] * direction
        d_dn += (-mu * th)[:, None] * direction
        slope = -mu * normal * (1.0 - th**2) / slip_velocity
        d_dv += slope[:, None, None] * direction[:, :, None] * direction[:, None, :]
    return force, d_dv, d_dn, np.zeros((n, 3, 3))


def _isotropic_friction(tangential: FloatArray, normal: FloatArray, mu: float,
                        slip_velocity: float, projector: FloatArray,
                        dvt_dx: FloatArray | None
                        ) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    speed = np.linalg.norm(tangential, axis=1)
    th = np.tanh(speed / slip_velocity)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(speed > 0, th / speed, 1.0 / slip_velocity)  # tanh(s/vs)/s, s -> 0
        unit = np.where(speed[:, None] > 0, tangential / speed[:, None], 0.0)
    force = (-mu * normal * ratio)[:, None] * tangential
    uu = unit[:, :, None] * unit[:, None, :]
    d_dn = (-mu * ratio)[:, None] * tangential
    slope = ((1 - th**2) / slip_velocity)[:, None, None] * uu
    if dvt_dx is None:  # flat: J P = -mu N (ratio (P - u u) + slope u u), u in the plane
        d_dv = (-mu * normal)[:, None, None] * (ratio[:, None, None] * (projector - uu) + slope)
        return force, d_dv, d_dn, np.zeros_like(d_dv)
    # d force / d tangential, then through the projection onto the tangent plane
    J = (-mu * normal)[:, None, None] * (ratio[:, None, None] * (np.eye(3) - uu) + slope)
    d_dv = np.einsum("nij,njk->nik", J, projector)
    d_dx = np.einsum("nij,njk->nik", J, dvt_dx)
    return force, d_dv, d_dn, d_dx


def static_friction(
    normal: FloatArray, dnormal_dx: FloatArray, tension: FloatArray, dtension_dl: FloatArray,
    direction: FloatArray, length: FloatArray, mu: float,
    unit_normal: FloatArray | None = None, dunit_dx: FloatArray | None = None,
    load: FloatArray | None = None, dtension_dx: FloatArray | None = None,
) -> tuple[FloatArray, FloatArray]:
    """Coulomb friction of a lying line in statics, fully mobilized towards its anchor.

    The closed-form convention (Jonkman 2007, MAP manual): on the lying part the tension
    falls towards the anchor by ``mu w`` per unit length and stays at zero once it is taken
    up. On a node resting on the seabed with the normal force ``N`` and the element on its
    fairlead side (tension ``T``, unit vector ``direction`` from the node towards the
    fairlead, chord ``length``) the friction is ``-phi P direction`` with ``P`` the
    projection on the seabed's tangent plane (``diag(1, 1, 0)`` on a flat seabed) and
    ``phi = clip(T + g, -mu N, mu N)``, ``g = load . P direction`` the node's own load down a
    slope towards the fairlead (0 on a flat seabed, where ``phi = min(mu N, T)``): it takes
    up ``mu N`` of the pull, or all of it, so that a slack stretch on a slope is held where
    ``mu > tan(slope)``.

    Parameters
    ----------
    normal, dnormal_dx
        Seabed normal force on each node (n,) and its derivative with respect to the node's
        position (n, 3).
    tension, dtension_dl
        Tension of each node's fairlead-side element and its derivative with respect to the
        chord length (n,).
    direction
        Unit vector of that element from the node towards the fairlead (n, 3).
    length
        Its chord length (n,).
    mu
        Friction coefficient.
    unit_normal, dunit_dx
        Seabed unit normal under each node (n, 3) and its position derivative (n, 3, 3)
        (:func:`surface_normal`); ``None``: flat.
    load
        The constant load on each node (n, 3) (its weight); ``None``: left out (on a flat
        seabed it has no part along the seabed).
    dtension_dx
        The tension's whole derivative with respect to the node (columns 0-2) and the far
        node (3-5), (n, 6), where it is not ``dtension_dl`` along the element (the
        sag-corrected element); ``None``: ``dtension_dl`` along ``direction``.

    Returns
    -------
    force, dforce
        Friction force on each node (n, 3) and its derivative (n, 3, 6) with respect to the
        node's position (columns 0-2) and the far node of the element (columns 3-5).
    """
    n = len(normal)
    if unit_normal is None:
        unit_normal = np.tile([0.0, 0.0, 1.0], (n, 1))
        dunit_dx = np.zeros((n, 3, 3))
    projector = np.eye(3) - unit_normal[:, :, None] * unit_normal[:, None, :]
    along = np.einsum("ij,ij->i", unit_normal, direction)
    flat = direction - unit_normal * along[:, None]
    dunit = (np.eye(3) - direction[:, :, None] * direction[:, None, :]) \
        / np.maximum(length, np.finfo(float).tiny)[:, None, None]  # d direction / d(far)
    dflat = np.einsum("nij,njk->nik", projector, dunit)
    # the tangent plane turns with the node's position (a bilinear grid's twist)
    dflat_dn = -(dunit_dx * along[:, None, None] + unit_normal[:, :, None]
                 * np.einsum("nb,nbj->nj", direction, dunit_dx)[:, None])
    pull = np.maximum(tension, 0.0)
    dpull = np.zeros((n, 6))
    dT = dtension_dl[:, None] * direction  # dT/d(far node)
    dpull[:, 3:], dpull[:, :3] = dT, -dT
    if dtension_dx is not None:
        dpull[:] = dtension_dx
    if load is not None:  # the node's own load down the slope, towards the fairlead
        pull = pull + np.einsum("ij,ij->i", load, flat)
        dg = np.einsum("ni,nij->nj", load, dflat)
        dpull[:, 3:] += dg
        dpull[:, :3] += np.einsum("ni,nij->nj", load, dflat_dn) - dg
    high, low = mu * normal < pull, pull < -mu * normal  # friction +-mu N; else all the pull
    phi = np.where(high, mu * normal, np.where(low, -mu * normal, pull))
    force = -phi[:, None] * flat
    dN = np.zeros((n, 6))
    dN[:, :3] = mu * dnormal_dx
    dphi = np.where(high[:, None], dN, np.where(low[:, None], -dN, dpull))
    dforce = -flat[:, :, None] * dphi[:, None, :]
    dforce[:, :, 3:] -= phi[:, None, None] * dflat
    dforce[:, :, :3] += phi[:, None, None] * dflat
    dforce[:, :, :3] -= phi[:, None, None] * dflat_dn
    return force, dforce
