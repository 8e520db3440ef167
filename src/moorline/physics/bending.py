"""Rotation-free bending stiffness of a cable on its existing nodes (no rotational dofs).

Each interior node ``i`` of a line with bending stiffness ``EI`` carries a discrete bending
energy from the turning angle ``theta_i`` between its two adjacent segments,
``a = x_i - x_{i-1}`` and ``b = x_{i+1} - x_i`` (unit vectors ``t_a``, ``t_b``):

    U_i = EI / Lbar_i (1 - t_a . t_b) = (1/2) EI kappa_i^2 Lbar_i,
    kappa_i = 2 sin(theta_i / 2) / Lbar_i,       Lbar_i = (L_a + L_b) / 2,

with ``L_a``, ``L_b`` the unstretched segment lengths: the curvature is MoorDyn v2's
(``4 sin(theta/2) / (l_a + l_b)``, MoorDyn-C ``Misc.cpp GetCurvature``; MoorDyn takes the
stretched lengths) and the energy is the discrete-elastic-rod form of Bergou et al. (2008,
"Discrete elastic rods", ACM TOG 27(3)), ``sum EI kappa^2 Lbar / 2``, with ``2 sin(theta/2)``
for their ``2 tan(theta/2)``. For small angles ``U = EI theta^2 / (2 Lbar)``, the central
difference of ``int EI w''^2 / 2 ds`` (second order in the segment length).

The forces are ``-dU/dx`` and the tangent its exact Hessian (a 9x9 block per node triplet,
symmetric: bending is conservative). The moment at the node is
``dU/dtheta = EI sin(theta) / Lbar = EI kappa cos(theta/2)``; MoorDyn applies ``EI kappa``
with forces ``EI kappa / l`` normal to the segments and no part along them: the two agree to
``O(theta^2)`` and the segment strain.

Line ends are pinned (no moment) by default: the end nodes take part only in the triplet of
their neighbour. A clamped end holds the line's tangent there along a fixed direction ``d``
(pointing from end A towards end B): a half-segment "ghost" triplet with energy
``EI / (L_e / 2) (1 - t_e . d)`` on the end element ``e`` (MoorDyn-C's cantilevered end,
curvature ``4 sin(theta/2) / l_e``; the same as the central scheme's ghost node
``w_{-1} = w_1``). Its forces and tangent act on the end element's two nodes.
(MoorDyn clamps a line end at a rod or body, whose direction turns with it; here the direction
is fixed in space.)
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from .element import pair_blocks

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]

# d[a; b] / d[x_{i-1}; x_i; x_{i+1}]: a = x_i - x_{i-1}, b = x_{i+1} - x_i
_B = np.kron(np.array([[-1.0, 1.0, 0.0], [0.0, -1.0, 1.0]]), np.eye(3))


def bending_triplets(
    line_nodes: tuple[IntArray, ...], line_elements: tuple[IntArray, ...],
    length0: FloatArray, EI: FloatArray,
) -> tuple[IntArray, IntArray, FloatArray]:
    """The node triplets of every line with bending stiffness.

    Parameters
    ----------
    line_nodes, line_elements
        Per line, its node and element indices from end A to end B.
    length0
        Unstretched element lengths (n_elements,).
    EI
        Bending stiffness of each element [force*length^2] (0: none).

    Returns
    -------
    nodes, elements, stiffness
        Node indices ``(i-1, i, i+1)`` (n_b, 3), the two elements ``(i-1, i)`` and
        ``(i, i+1)`` (n_b, 2) and ``EI / Lbar`` [force*length] (n_b,) of each triplet.
    """
    nodes, elems = [], []
    for n, e in zip(line_nodes, line_elements, strict=True):
        if len(e) < 2 or not np.any(EI[e] > 0):
            continue
        nodes.append(np.column_stack((n[:-2], n[1:-1], n[2:])))
        elems.append(np.column_stack((e[:-1], e[1:])))
    if not nodes:
        return np.zeros((0, 3), np.int64), np.zeros((0, 2), np.int64), np.zeros(0)
    nodes_a, elems_a = np.concatenate(nodes), np.concatenate(elems)
    mean_ei = 0.5 * (EI[elems_a[:, 0]] + EI[elems_a[:, 1]])
    lbar = 0.5 * (length0[elems_a[:, 0]] + length0[elems_a[:, 1]])
    return nodes_a.astype(np.int64), elems_a.astype(np.int64), mean_ei / lbar


def _segments(positions: FloatArray, nodes: IntArray):
    a = positions[nodes[:, 1]] - positions[nodes[:, 0]]
    b = positions[nodes[:, 2]] - positions[nodes[:, 1]]
    la, lb = np.linalg.norm(a, axis=1), np.linalg.norm(b, axis=1)
    tiny = np.finfo(float).tiny
    return a / np.maximum(la, tiny)[:, None], b / np.maximum(lb, tiny)[:, None], la, lb


def turning_angle(positions: FloatArray, nodes: IntArray) -> FloatArray:
    """Angle between the two segments of each triplet [rad] (n_b,)."""
    ta, tb, _, _ = _segments(positions, nodes)
    cross = np.linalg.norm(np.cross(ta, tb), axis=1)
    return np.arctan2(cross, np.einsum("ij,ij->i", ta, tb))


def curvature(positions: FloatArray, nodes: IntArray, length0_mean: FloatArray) -> FloatArray:
    """Discrete curvature ``2 sin(theta / 2) / Lbar`` of each triplet [1/length] (n_b,)."""
    return 2.0 * np.sin(0.5 * turning_angle(positions, nodes)) / length0_mean


def bending_energy(positions: FloatArray, nodes: IntArray, stiffness: FloatArray) -> FloatArray:
    """Bending energy ``EI / Lbar (1 - t_a . t_b)`` of each triplet (n_b,)."""
    ta, tb, _, _ = _segments(positions, nodes)
    return stiffness * (1.0 - np.einsum("ij,ij->i", ta, tb))


def bending_forces(positions: FloatArray, nodes: IntArray, stiffness: FloatArray) -> FloatArray:
    """Forces of each triplet's bending on its three nodes, ``-dU/dx`` (n_b, 3, 3)."""
    ta, tb, la, lb = _segments(positions, nodes)
    s = np.einsum("ij,ij->i", ta, tb)[:, None]
    # dU/da = -c (t_b - s t_a) / |a|, dU/db = -c (t_a - s t_b) / |b|
    ga = -stiffness[:, None] * (tb - s * ta) / la[:, None]
    gb = -stiffness[:, None] * (ta - s * tb) / lb[:, None]
    return np.stack((ga, gb - ga, -gb), axis=1)


def bending_tangent(positions: FloatArray, nodes: IntArray, stiffness: FloatArray) -> FloatArray:
    """Exact tangent of the resisting bending forces, ``d^2 U / dx^2`` (n_b, 9, 9), over the
    node triplet ``(x_{i-1}, x_i, x_{i+1})``.

    With ``P_a = I - t_a t_a^T`` and ``s = t_a . t_b``:
    ``U_aa = c (t_a t_b^T + t_b t_a^T + s I - 3 s t_a t_a^T) / |a|^2``,
    ``U_ab = -c P_a P_b / (|a| |b|)`` (and ``a <-> b``); then ``B^T U B`` with ``B`` the map
    from the node positions to ``(a, b)``.
    """
    ta, tb, la, lb = _segments(positions, nodes)
    c = stiffness[:, None, None]
    s = np.einsum("ij,ij->i", ta, tb)[:, None, None]
    eye = np.eye(3)
    Pa, Pb = eye - _outer(ta, ta), eye - _outer(tb, tb)
    cross = -c * (Pa @ Pb) / (la * lb)[:, None, None]
    H = np.empty((len(nodes), 6, 6))
    H[:, :3, :3] = _direction_hessian(ta, tb, la, c, s)
    H[:, 3:, 3:] = _direction_hessian(tb, ta, lb, c, s)
    H[:, :3, 3:] = cross
    H[:, 3:, :3] = np.transpose(cross, (0, 2, 1))
    return _B.T @ H @ _B


def _direction_hessian(t: FloatArray, u: FloatArray, length: FloatArray, c: FloatArray,
                       s: FloatArray) -> FloatArray:
    """``d^2 / da^2`` of ``c (1 - t . u)`` with ``t = a / |a|`` and ``u`` held:
    ``c (t u^T + u t^T + s I - 3 s t t^T) / |a|^2``, ``s = t . u``."""
    sym = _outer(t, u) + _outer(u, t) + s * np.eye(3) - 3.0 * s * _outer(t, t)
    return c * sym / (length**2)[:, None, None]


def _element_direction(positions: FloatArray, elements: IntArray, element: IntArray):
    chord = positions[elements[element, 1]] - positions[elements[element, 0]]
    length = np.linalg.norm(chord, axis=1)
    return chord / np.maximum(length, np.finfo(float).tiny)[:, None], length


def clamp_energy(positions: FloatArray, elements: IntArray, element: IntArray,
                 direction: FloatArray, stiffness: FloatArray) -> FloatArray:
    """Energy ``c (1 - t_e . d)`` of each clamped end (n_c,): ``element`` the end elements,
    ``direction`` the held unit tangents (n_c, 3), ``stiffness`` ``c = EI / (L_e / 2)``."""
    t, _ = _element_direction(positions, elements, element)
    return stiffness * (1.0 - np.einsum("ij,ij->i", t, direction))


def clamp_forces(positions: FloatArray, elements: IntArray, element: IntArray,
                 direction: FloatArray, stiffness: FloatArray) -> FloatArray:
    """Forces of each clamp on its end element's two nodes, ``-dU/dx`` (n_c, 2, 3)."""
    t, length = _element_direction(positions, elements, element)
    s = np.einsum("ij,ij->i", t, direction)[:, None]
    f2 = stiffness[:, None] * (direction - s * t) / length[:, None]
    return np.stack((-f2, f2), axis=1)


def clamp_tangent(positions: FloatArray, elements: IntArray, element: IntArray,
                  direction: FloatArray, stiffness: FloatArray) -> FloatArray:
    """Exact tangent of the clamps' resisting forces over their end elements' nodes
    (n_c, 6, 6): ``[[H, -H], [-H, H]]`` with ``H`` the Hessian in the chord."""
    t, length = _element_direction(positions, elements, element)
    s = np.einsum("ij,ij->i", t, direction)[:, None, None]
    return pair_blocks(_direction_hessian(t, direction, length, stiffness[:, None, None], s))


def _outer(u: FloatArray, v: FloatArray) -> FloatArray:
    return u[:, :, None] * v[:, None, :]


def to_pair_blocks(K: FloatArray, elements: IntArray, n_elements: int,
                   element_blocks: FloatArray | None = None) -> FloatArray:
    """Triplet blocks (n_b, 9, 9) as blocks over the node pairs of a
    :class:`~moorline.solvers.assembly.BlockPattern` built on ``elements`` followed by the
    triplets' outer pairs ``(i-1, i+1)`` (:attr:`moorline.mesh.Mesh.pattern_pairs`): shape
    (n_elements + n_b, 6, 6), ``element_blocks`` (n_elements, 6, 6) added in front.

    The node ``i`` diagonal block is split half to each element; the ``(i-1, i+1)`` coupling
    goes to the outer pair's off-diagonal blocks.
    """
    n_b = len(K)
    out = np.zeros((n_elements + n_b, 6, 6))
    if element_blocks is not None:
        out[: len(element_blocks)] = element_blocks
    first, second = elements[:, 0], elements[:, 1]
    half = 0.5 * K[:, 3:6, 3:6]
    # each element is the first element of at most one triplet, and the second of at most one
    out[first, :3, :3] += K[:, :3, :3]
    out[first, :3, 3:] += K[:, :3, 3:6]
    out[first, 3:, :3] += K[:, 3:6, :3]
    out[first, 3:, 3:] += half
    out[second, :3, :3] += half
    out[second, :3, 3:] += K[:, 3:6, 6:]
    out[second, 3:, :3] += K[:, 6:, 3:6]
    out[second, 3:, 3:] += K[:, 6:, 6:]
    out[n_elements:, :3, 3:] = K[:, :3, 6:]
    out[n_elements:, 3:, :3] = K[:, 6:, :3]
    return out


def element_shear(forces: FloatArray, elements: IntArray, n_elements: int) -> FloatArray:
    """Triplet node forces (n_b, 3, 3) as forces of the elements on their nodes
    (n_elements, 2, 3), the pattern of :func:`moorline.physics.element.nodal_forces`.

    The force ``f_{i-1}`` on the outer node ``i-1`` is carried by the element ``(i-1, i)``
    (``f_{i-1}`` on its first node, ``-f_{i-1}`` on ``i``), ``f_{i+1}`` by ``(i, i+1)``; with
    ``f_{i-1} + f_i + f_{i+1} = 0`` their sum on the nodes is the triplet's forces. So the
    end element of a line carries the bending shear at a pinned end, and every force summed
    from the element forces (end forces, forces on bodies) includes it.
    """
    out = np.zeros((n_elements, 2, 3))
    first, second = elements[:, 0], elements[:, 1]
    out[first, 0] += forces[:, 0]
    out[first, 1] -= forces[:, 0]
    out[second, 1] += forces[:, 2]
    out[second, 0] -= forces[:, 2]
    return out
