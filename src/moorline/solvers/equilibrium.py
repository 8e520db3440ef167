"""The static force balance of a mesh: residual and exact tangent.

Residual ``R(x, lam) = lam F_ext + F_cable(x) + F_seabed(x)`` at the free dofs (Tuah eq. 4.1.2:
external minus internal resisting force); tangent ``K = -dR/dx`` (Tuah eq. 3.1.8a, exact form
derived in :mod:`moorline.physics.element`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from ..mesh import Mesh
from ..physics import element, seabed
from .assembly import BlockPattern, gather_free

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class ForceState:
    """Everything a force evaluation produces at one configuration."""

    tension: FloatArray          # (n_elements,)
    element_forces: FloatArray   # (n_elements, 2, 3) force of each element on its nodes
    nodal: FloatArray            # (n_nodes, 3) sum of all forces on each node
    length: FloatArray           # (n_elements,) current chord lengths


class StaticModel:
    """Residual and tangent of a mesh's static balance, with a cached sparse pattern."""

    def __init__(self, mesh: Mesh) -> None:
        self.mesh = mesh
        self.pattern = BlockPattern(mesh.elements, mesh.dof_of_node)
        g, rho = mesh.gravity, mesh.water_density
        ext = element.lumped_weight(mesh.elements, mesh.length0, mesh.weight_per_length,
                                    mesh.n_nodes)
        ext[:, 2] += (rho * mesh.node_volume - mesh.node_mass) * g
        self.external = ext + mesh.node_force
        self.node_seabed_stiffness = mesh.seabed_stiffness_per_area * mesh.node_contact_area
        self.seabed_ramp = seabed.contact_ramp(-ext[:, 2], self.node_seabed_stiffness,
                                               float(np.max(mesh.diameter, initial=0.0)))

    def forces(self, x: FloatArray, lam: float = 1.0) -> ForceState:
        """All nodal forces at positions ``x`` (n_nodes, 3) with the loads scaled by ``lam``."""
        m = self.mesh
        length, unit = element.element_geometry(x, m.elements)
        tension, _ = element.axial_tension(length, m.length0, m.EA, m.slack_ratio,
                                                m.slack_smoothing)
        el_forces = element.nodal_forces(tension, unit)
        nodal = lam * self.external
        nodal = nodal + _sum_to_nodes(el_forces, m.elements, m.n_nodes)
        if np.isfinite(m.seabed_z):
            nodal[:, 2] += self._seabed(x)[0]
        return ForceState(tension, el_forces, nodal, length)

    def residual(self, x: FloatArray, lam: float = 1.0) -> tuple[FloatArray, ForceState]:
        """Out-of-balance force at the free dofs, and the force state."""
        state = self.forces(x, lam)
        return gather_free(state.nodal, self.mesh.dof_of_node), state

    def tangent(self, x: FloatArray, pattern: BlockPattern | None = None,
                taut_axial: bool = False) -> sp.csr_matrix:
        """Exact tangent ``-dR/dx`` assembled over ``pattern`` (default: the free dofs).

        With ``taut_axial`` every element gets the taut axial stiffness ``EA / L0`` and the
        geometric stiffness of ``max(T, 0)``, slack ones included: the stiffness against
        perturbations that do not change which elements are slack (strumming modes).
        """
        m = self.mesh
        length, unit = element.element_geometry(x, m.elements)
        tension, dT = element.axial_tension(length, m.length0, m.EA, m.slack_ratio,
                                                m.slack_smoothing)
        if taut_axial:
            tension, dT = np.maximum(tension, 0.0), m.EA / m.length0
        blocks = element.tangent_blocks(length, unit, tension, dT)
        node_blocks = None
        if np.isfinite(m.seabed_z):
            node_blocks = np.zeros((m.n_nodes, 3, 3))
            node_blocks[:, 2, 2] = -self._seabed(x)[1]
        return (pattern or self.pattern).assemble(blocks, node_blocks)

    def _seabed(self, x: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        zero = np.zeros(self.mesh.n_nodes)
        return seabed.contact_force(x[:, 2] - self.mesh.seabed_z, zero,
                                    self.node_seabed_stiffness, zero, self.seabed_ramp)

    def potential_energy(self, x: FloatArray, lam: float = 1.0) -> float:
        """Total potential energy: strain and seabed energy minus the work of the loads.

        All static forces here are conservative, so ``R = -dPi/dx``; the Newton line search
        uses ``Pi`` as its merit function.
        """
        m = self.mesh
        length, _ = element.element_geometry(x, m.elements)
        energy = float(element.strain_energy(length, m.length0, m.EA, m.slack_ratio,
                                                      m.slack_smoothing).sum())
        if np.isfinite(m.seabed_z):
            energy += seabed.contact_energy(x[:, 2] - m.seabed_z, self.node_seabed_stiffness,
                                            self.seabed_ramp)
        return energy - lam * float(np.sum(self.external * x))

    def load_scale(self) -> float:
        """Force scale for relative tolerances: the largest nodal load (or a tension scale)."""
        scale = float(np.abs(self.external).max(initial=0.0))
        return scale if scale > 0 else 1e-6 * float(np.max(self.mesh.EA, initial=1.0))

    def roundoff_floor(self, x: FloatArray) -> float:
        """Smallest out-of-balance force resolvable in double precision at positions ``x``:
        chords are differences of coordinates, so ``dT ~ EA eps |x| / L0``."""
        m = self.mesh
        if m.n_elements == 0:
            return 0.0
        reach = float(np.abs(x).max(initial=1.0))
        return 64 * np.finfo(float).eps * float(np.max(m.EA / m.length0)) * reach


def _sum_to_nodes(el_forces: FloatArray, elements: NDArray[np.int64], n_nodes: int) -> FloatArray:
    out = np.zeros((n_nodes, 3))
    for k in range(3):
        out[:, k] = (np.bincount(elements[:, 0], el_forces[:, 0, k], n_nodes)
                     + np.bincount(elements[:, 1], el_forces[:, 1, k], n_nodes))
    return out
