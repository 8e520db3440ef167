"""Flat seabed contact: a penalty spring and damper on nodes at the seabed ``z = -depth``.

MoorDyn's model (kBot, cBot per unit contact area) switches both on at first contact, so the
force has a kink (spring) and a jump (damper) as a node lands. An implicit Newton iteration
cycles across such switches instead of converging. Here both blend in over a band ``ramp``
(a few millimetres: at least the static penetration of a lying line, :func:`contact_ramp`)
centred on the seabed surface: with the penetration ``p`` and ``q = p + ramp / 2``,

    spring  k q^2 / (2 ramp)   for -ramp/2 < p < ramp/2,   k p   beyond,
    damper  -c v_z min(q / ramp, 1).

The spring is C1 with a stiffness rising monotonically from 0 to ``k`` (a C1 blend that is
``k p`` beyond the band and starts at ``p = 0`` would need a stiffness above ``k`` inside it,
which harmonic balance and Newton do not like), the damper continuous. Beyond ``ramp / 2``
both are MoorDyn's, so a line lying on a soft seabed rests at MoorDyn's penetration
``w / k`` (an earlier blend over ``0 < p < ramp``, ``k p^2 / (2 ramp)`` then ``k (p - ramp /
2)``, put it ``ramp / 2`` deeper: 0.35 % in the statics of a deck with kBot = 1e5 Pa/m); on
a stiff seabed a lying node carries its weight within the band, at most ``ramp / 2`` above
the surface. Unlike MoorDyn, the total never pulls: a node lifting off faster than the
spring pushes feels no seabed force (MoorDyn's damper sucks it down; that suction also
leaves implicit steps without a solution near the seabed).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

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


def contact_ramp(weight_per_node: FloatArray, k: FloatArray, diameter: float) -> FloatArray:
    """Blend-in penetration per node: the static penetration of a lying line (its weight over
    its contact stiffness), at least a thousandth of the diameter."""
    with np.errstate(divide="ignore", invalid="ignore"):
        ramp = np.where(k > 0, np.maximum(weight_per_node, 0.0) / k, 0.0)
    return np.maximum(ramp, RAMP_DIAMETERS * max(diameter, 1e-3))


def friction_force(
    velocity: FloatArray, normal: FloatArray, axis: FloatArray, mu_axial: float,
    mu_transverse: float, slip_velocity: float,
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Regularized Coulomb friction on nodes resting on the seabed.

    The horizontal velocity is split into its part along the line (``axis``, a horizontal unit
    vector per node) and across it; each part is resisted by
    ``mu N tanh(|v| / v_s) v / |v|``, a smooth stand-in for Coulomb friction (full friction
    once sliding faster than a few ``v_s``; a viscous law near rest, so no stick-slip switch
    upsets Newton), as MoorDyn's axial and transverse seabed friction. With equal coefficients
    the law is isotropic, ``mu N tanh(|v| / v_s) v / |v|``, and independent of ``axis``; with
    different ones the force depends on the line direction, whose change with the positions
    the returned derivatives leave out.

    Parameters
    ----------
    velocity
        Node velocities (n, 3); only x and y are used.
    normal
        Seabed normal force per node (n,) (zero off the seabed).
    axis
        Horizontal unit vector along the line at each node (n, 3).
    mu_axial, mu_transverse
        Friction coefficients along and across the line.
    slip_velocity
        Regularization speed ``v_s`` [length/time].

    Returns
    -------
    force, dforce_dv, dforce_dnormal
        Friction force (n, 3), its derivative with respect to the velocity (n, 3, 3) and with
        respect to the normal force (n, 3).
    """
    horizontal = velocity.copy()
    horizontal[:, 2] = 0.0
    if mu_axial == mu_transverse:
        return _isotropic_friction(horizontal, normal, mu_axial, slip_velocity)
    n = len(normal)
    force = np.zeros((n, 3))
    d_dv = np.zeros((n, 3, 3))
    d_dn = np.zeros((n, 3))
    across = np.cross(np.array([0.0, 0.0, 1.0]), axis)
    for mu, direction in ((mu_axial, axis), (mu_transverse, across)):
        if mu == 0.0:
            continue
        speed = np.einsum("ij,ij->i", horizontal, direction)
        th = np.tanh(speed / slip_velocity)
        f = -mu * normal * th
        force += f[:, None] * direction
        d_dn += (-mu * th)[:, None] * direction
        slope = -mu * normal * (1.0 - th**2) / slip_velocity
        d_dv += slope[:, None, None] * direction[:, :, None] * direction[:, None, :]
    return force, d_dv, d_dn


def _isotropic_friction(horizontal: FloatArray, normal: FloatArray, mu: float,
                        slip_velocity: float) -> tuple[FloatArray, FloatArray, FloatArray]:
    speed = np.linalg.norm(horizontal, axis=1)
    th = np.tanh(speed / slip_velocity)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(speed > 0, th / speed, 1.0 / slip_velocity)  # tanh(s/vs)/s, s -> 0
        unit = np.where(speed[:, None] > 0, horizontal / speed[:, None], 0.0)
    force = (-mu * normal * ratio)[:, None] * horizontal
    eye = np.diag([1.0, 1.0, 0.0])
    uu = unit[:, :, None] * unit[:, None, :]
    d_dv = (-mu * normal)[:, None, None] * (ratio[:, None, None] * (eye - uu)
                                            + ((1 - th**2) / slip_velocity)[:, None, None] * uu)
    d_dn = (-mu * ratio)[:, None] * horizontal
    return force, d_dv, d_dn


def static_friction(
    normal: FloatArray, dnormal_dz: FloatArray, tension: FloatArray, dtension_dl: FloatArray,
    direction: FloatArray, length: FloatArray, mu: float,
) -> tuple[FloatArray, FloatArray]:
    """Coulomb friction of a lying line in statics, fully mobilized towards its anchor.

    The closed-form convention (Jonkman 2007, MAP manual): on the lying part the tension
    falls towards the anchor by ``mu w`` per unit length and stays at zero once it is taken
    up. On a node resting on the seabed with the normal force ``N`` and the element on its
    fairlead side (tension ``T``, unit vector ``direction`` from the node towards the
    fairlead, chord ``length``) the friction is ``-min(mu N, T) P direction`` with
    ``P = diag(1, 1, 0)``: it takes up ``mu N`` of the tension, or all of it.

    Parameters
    ----------
    normal, dnormal_dz
        Seabed normal force on each node and its derivative with respect to the node's z (n,).
    tension, dtension_dl
        Tension of each node's fairlead-side element and its derivative with respect to the
        chord length (n,).
    direction
        Unit vector of that element from the node towards the fairlead (n, 3).
    length
        Its chord length (n,).
    mu
        Friction coefficient.

    Returns
    -------
    force, dforce
        Friction force on each node (n, 3) and its derivative (n, 3, 6) with respect to the
        node's position (columns 0-2) and the far node of the element (columns 3-5).
    """
    n = len(normal)
    flat = direction * np.array([1.0, 1.0, 0.0])
    capped = mu * normal < tension  # friction mu N; else it takes up all of T
    phi = np.where(capped, mu * normal, np.maximum(tension, 0.0))
    force = -phi[:, None] * flat
    dphi = np.zeros((n, 6))
    dphi[:, 2] = np.where(capped, mu * dnormal_dz, 0.0)
    dT = np.where(capped, 0.0, dtension_dl)[:, None] * direction  # dT/d(far node)
    dphi[:, 3:] += dT
    dphi[:, :3] -= dT
    dunit = (np.eye(3) - direction[:, :, None] * direction[:, None, :]) \
        / np.maximum(length, np.finfo(float).tiny)[:, None, None]  # d direction / d(far)
    dforce = -flat[:, :, None] * dphi[:, None, :]
    dflat = dunit * np.array([1.0, 1.0, 0.0])[None, :, None]
    dforce[:, :, 3:] -= phi[:, None, None] * dflat
    dforce[:, :, :3] += phi[:, None, None] * dflat
    return force, dforce
