"""Flat seabed contact: a penalty spring on nodes below ``z = -depth`` (as MoorDyn's kBot)."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]


def contact_forces(
    positions: FloatArray, seabed_z: float, stiffness: FloatArray
) -> tuple[FloatArray, FloatArray]:
    """Vertical seabed reaction on nodes and its tangent.

    Parameters
    ----------
    positions
        Node positions (n_nodes, 3).
    seabed_z
        Height of the seabed (``-depth``).
    stiffness
        Contact spring per node [force/length]: the seabed stiffness per area times the node's
        contact area (diameter times tributary length), shape (n_nodes,).

    Returns
    -------
    force, tangent
        Upward reaction (n_nodes, 3) and ``-d(force_z)/dz`` per node (n_nodes,): the stiffness
        the seabed adds to the resisting force of the z degree of freedom.
    """
    penetration = seabed_z - positions[:, 2]
    touching = penetration > 0.0
    force = np.zeros_like(positions)
    force[:, 2] = np.where(touching, stiffness * penetration, 0.0)
    return force, np.where(touching, stiffness, 0.0)


def contact_energy(positions: FloatArray, seabed_z: float, stiffness: FloatArray) -> float:
    """Energy stored in the seabed springs, ``sum k p^2 / 2`` over penetrating nodes."""
    penetration = np.maximum(seabed_z - positions[:, 2], 0.0)
    return float(0.5 * np.sum(stiffness * penetration**2))
