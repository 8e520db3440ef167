"""Flat seabed contact: a penalty spring and damper on nodes below ``z = -depth``.

MoorDyn's model (kBot, cBot per unit contact area) switches both on at first contact, so the
force has a kink (spring) and a jump (damper) as a node lands. An implicit Newton iteration
cycles across such switches instead of converging. Here both blend in over the first
``ramp`` of penetration (a few millimetres: the static penetration of a lying line):

    spring  k p^2 / (2 ramp)           for p < ramp,   k (p - ramp / 2)   beyond,
    damper  -c v_z min(p / ramp, 1).

The spring is C1 and the damper continuous; away from touchdown they are MoorDyn's, with the
equilibrium penetration deeper by ``ramp / 2``.
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
    touching = p > 0
    share = np.clip(p / ramp, 0.0, 1.0)
    full = p >= ramp
    spring = np.where(full, k * (p - 0.5 * ramp), k * p * share * 0.5)
    force = np.where(touching, spring - c * share * vz, 0.0)
    d_spring = np.where(full, k, k * share)  # d(spring)/dp
    d_damp = np.where(touching & ~full, c * vz / ramp, 0.0)  # d(c share vz)/dp
    d_dz = np.where(touching, -d_spring + d_damp, 0.0)
    d_dv = np.where(touching, -c * share, 0.0)
    return force, d_dz, d_dv


def contact_energy(height: FloatArray, k: FloatArray, ramp: FloatArray) -> float:
    """Energy stored in the seabed springs (the potential of :func:`contact_force` with
    ``c = 0``)."""
    p = np.maximum(-height, 0.0)
    full = p >= ramp
    energy = np.where(full, k * (0.5 * p**2 - 0.5 * ramp * p + ramp**2 / 6),
                      k * p**3 / (6 * ramp))
    return float(np.sum(energy))


def contact_ramp(weight_per_node: FloatArray, k: FloatArray, diameter: float) -> FloatArray:
    """Blend-in penetration per node: the static penetration of a lying line (its weight over
    its contact stiffness), at least a thousandth of the diameter."""
    with np.errstate(divide="ignore", invalid="ignore"):
        ramp = np.where(k > 0, np.maximum(weight_per_node, 0.0) / k, 0.0)
    return np.maximum(ramp, RAMP_DIAMETERS * max(diameter, 1e-3))
