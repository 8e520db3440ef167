"""Linearized restoring stiffness of the moored system at points, by static condensation.

At a static equilibrium the tangent ``K`` (exact, :mod:`moorline.solvers.equilibrium`) relates
small displacements to out-of-balance forces. Keeping the dofs ``r`` of the chosen point(s),
holding the other fixed and prescribed nodes still and letting every other free dof
re-equilibrate gives ``K_r = K_rr - K_rc K_cc^-1 K_cr``: the force needed to hold the point(s)
displaced, per unit displacement. MoorDyn gives no such matrix; MoorPy estimates it by finite
differences. Here it is exact, and tests check it against finite differences of re-solved
equilibria.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ..mesh import Mesh
from ..physics.rigid_body import skew
from ..results import StaticResult
from .assembly import BlockPattern, factorize
from .band_lu import MAX_SMALL, small_band_solver
from .equilibrium import StaticModel

FloatArray = NDArray[np.float64]


def condensed_stiffness(result: StaticResult, nodes: list[int]) -> FloatArray:
    """Stiffness (3n x 3n) at the given nodes, all other free dofs condensed out.

    Parameters
    ----------
    result
        A converged static result.
    nodes
        Node indices to keep (free or prescribed; fixed nodes are allowed but rarely useful).
    """
    return condensed_tangent(result.mesh, result.positions, nodes)


def condensed_tangent(mesh: Mesh, positions: FloatArray, nodes: list[int]) -> FloatArray:
    """The condensed tangent of :func:`condensed_stiffness` at any node positions (not only
    an equilibrium: the current tangent of a time-domain state, :mod:`moorline.coupling`)."""
    pattern = full_pattern(mesh)
    values = StaticModel(mesh).tangent_values(positions, pattern)
    small = pattern.n < MAX_SMALL  # solved in Python (band_lu) when narrow: no scipy
    return condense(pattern.dense(values) if small else pattern.csr(values), mesh, nodes)


def full_pattern(mesh: Mesh) -> BlockPattern:
    """The block pattern over every node dof (fixed and prescribed ones included)."""
    return BlockPattern(mesh.pattern_pairs, np.arange(3 * mesh.n_nodes).reshape(-1, 3))


def condense(K, mesh: Mesh, nodes: list[int]) -> FloatArray:
    """``K_rr - K_rc K_cc^-1 K_cr`` of a matrix over every node dof (:func:`full_pattern`):
    the dofs of ``nodes`` kept, every free dof condensed out, the other held. ``K``: a
    sparse matrix, or a numpy array (solved dense)."""
    kept = (3 * np.asarray(nodes)[:, None] + np.arange(3)).ravel()
    free = mesh.dof_of_node >= 0
    free_flat = np.flatnonzero(free.ravel())
    condensed = np.setdiff1d(free_flat, kept)
    if isinstance(K, np.ndarray):
        K_rr = K[np.ix_(kept, kept)]
        if condensed.size == 0:
            return K_rr
        K_cr = K[np.ix_(condensed, kept)]  # not K_rc^T: drag and damping tangents are not
        solve = small_band_solver(K[np.ix_(condensed, condensed)])  # symmetric
        if solve is not None:
            return K_rr - K[np.ix_(kept, condensed)] @ solve(K_cr)
        from scipy.sparse import csr_matrix

        K = csr_matrix(K)
    K = K.tocsr()
    K_rr = K[kept][:, kept].toarray()
    if condensed.size == 0:
        return K_rr
    K_rc = K[kept][:, condensed].toarray()
    K_cr = K[condensed][:, kept].toarray()  # not K_rc^T: drag and damping tangents are not
    lu = factorize(K[condensed][:, condensed])  # symmetric
    return K_rr - K_rc @ lu.solve(np.ascontiguousarray(K_cr))


def point_stiffness(result: StaticResult, point: str) -> FloatArray:
    """3x3 restoring stiffness of the moored system at a free or prescribed point.

    ``K[i, j]`` is the extra force in direction ``i`` needed to hold the point displaced by a
    unit amount in direction ``j`` while the rest of the system re-equilibrates.
    """
    mesh = result.mesh
    return condensed_stiffness(result, [int(mesh.point_node[mesh.point_index(point)])])


def group_stiffness(result: StaticResult, points: list[str], reference: FloatArray) -> FloatArray:
    """6x6 stiffness of a group of points rigidly tied to a reference point.

    Generalized displacement ``q = (dx, dy, dz, rx, ry, rz)`` of the rigid group (small rotation
    vector about ``reference``); generalized force: the total force and moment about the
    reference needed to hold the group displaced. With arms ``a_i = x_i - reference``,
    ``T_i = [I, -[a_i x]]`` and ``f_i`` the total force on point ``i`` from its lines, the
    seabed and its own loads:

        K6 = sum_ij T_i^T K_ij T_j - blockdiag(0, sum_i [f_i x][a_i x])

    the second term being the moment change from rotating the arms under fixed forces.
    """
    mesh = result.mesh
    nodes = [int(mesh.point_node[mesh.point_index(p)]) for p in points]
    Kc = condensed_stiffness(result, nodes)
    arms = result.positions[nodes] - np.asarray(reference, dtype=float)
    T = rigid_map(arms)
    K6 = T.T @ Kc @ T
    forces = StaticModel(mesh).forces(result.positions).nodal[nodes]
    K6[3:, 3:] -= arm_rotation_stiffness(forces, arms)
    return K6


def rigid_map(arms: FloatArray) -> FloatArray:
    """``T`` (3n x 6): the displacements of points at world ``arms`` from a rigid group's
    small motion ``(dx, dy, dz, rx, ry, rz)``, rows ``[I, -[a_i x]]``."""
    return np.vstack([np.hstack((np.eye(3), -skew(a))) for a in np.reshape(arms, (-1, 3))])


def arm_rotation_stiffness(forces: FloatArray, arms: FloatArray) -> FloatArray:
    """``sum_i [f_i x][a_i x]`` (3 x 3): the change of the moment ``sum a_i x f_i`` when the
    arms turn under fixed forces, per unit rotation (subtracted in :func:`group_stiffness`)."""
    return sum((skew(f) @ skew(a) for f, a in zip(np.reshape(forces, (-1, 3)),
                                                  np.reshape(arms, (-1, 3)), strict=True)),
               np.zeros((3, 3)))
