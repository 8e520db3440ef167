"""The sag-corrected chord: a straight element whose chord is shortened by its own sag.

A straight two-node element puts its stretched arc length on the chord. A uniformly loaded
cable segment of stretched length ``s`` under the chord force ``T`` sags, and its chord is
shorter,

    c = s (1 - W_p^2 / (24 T^2)) + O(W_p^4 / T^4),

with ``W_p`` the segment's weight perpendicular to the chord (Irvine 1981, "Cable
Structures", ch. 2-3: the parabolic approximation of the sagging cable; the same ratio gives
Ernst's equivalent modulus). Here ``s = L0 (1 + eps(T))`` is the stretched length of the
element's tension-strain law (any law: linear, a table, a strain offset, the slack
regularization) and ``W_p^2 = (w L0)^2 (1 - n_z^2)`` (``w`` the submerged weight per
unstretched length, ``n`` the chord's unit vector, z up). The lumped weights stay at the
nodes: the end reactions of a uniformly loaded sagging segment are its chord force plus
``W/2`` at each end, so only the chord force changes.

Saturation. The correction ``r = W_p^2 / (24 T^2)`` grows without bound as the element goes
slack. It is replaced by

    c = s g(T),   g = 1 - phi W_p^2 / (24 T_+^2 + W^2 / rho),   T_+ = max(T, 0),

``W = |w| L0`` the element's whole weight: ``g = 1 - r + r^2 / rho + ...`` for ``T >> W``;
``rho = 10/27`` makes that second-order term the exact one of a horizontal chord (the
catenary between level supports, ``c / s = x / sinh x`` with ``x = w c / (2 H)``, gives
``1 - r + 2.7 r^2``). ``g`` rises monotonically from ``1 - phi rho (1 - n_z^2)`` at
``T <= 0`` to 1 and is C1 (in ``T``, smooth in ``n`` and ``phi``): a slack element is at most
``rho`` shorter, never infinitely.

Seabed. ``phi`` in [0, 1] switches the correction off where the seabed carries the
element's weight (it then lies straight): ``phi = 1 - s_1 s_2`` with ``s_k`` the share of node
``k``'s own load carried by the seabed spring (:func:`moorline.physics.seabed.carried_share`,
a C1 function of the node's height); 1 in the water, 0 when both nodes lie.

Dynamics. The same law acts in the time domain: the sag is that of the element's weight, as
if it hung at rest; its own inertia, drag and added mass (lumped at the nodes like its weight)
do not enter it. A chain falling slack in a snap trough therefore keeps the tension of a
hanging segment (see the README for the measured effect on the OC3 surge).

The law. Given the chord ``c``, the tension solves ``T = A(c / g(T))`` with ``A(l)`` the
straight element's law (:func:`moorline.physics.element.axial_tension` at the length ``l``).
``F(T) = T - A(c / g(T))`` has ``F' = 1 + A' c g_T / g^2 >= 1`` (``A' >= 0``, ``g_T >= 0``),
so the root is unique; it lies in ``[A(c), A(c / g_min)]`` and is found by Newton's method
safeguarded by bisection (Press et al., Numerical Recipes, "rtsafe"), until the residual is
at its round-off. The exact derivatives follow from the implicit function theorem,

    dT/dc = A' / (g D),   dT/dq = -A' c g_q / (g^2 D)   (q = W_p^2, phi),   D = F'(T),

and ``W_p^2`` depends on the chord direction, ``phi`` on the two node heights: the element
tangent is not symmetric (:func:`sag_blocks`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from numpy.typing import NDArray

from .bathymetry import SeabedSurface
from .element import axial_tension
from .load_strain import StrainLaws
from .seabed import carried_share, normal_distance

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]

#: Largest relative shortening of a slack element (and the second-order coefficient 1/rho of
#: the saturated correction; module docstring).
SATURATION = 10.0 / 27.0

#: Newton iterations of the tension at most (bisection steps included).
MAX_ITERATIONS = 100

#: The tension's residual ``T - A(c / g)`` counts as zero below this times ``|T| + A' c / g``
#: (the round-off of the strain ``l / L0 - 1`` times the stiffness, and of ``T``).
NOISE = 16 * np.finfo(float).eps


class SagTension(NamedTuple):
    """Tension of sag-corrected elements and its derivatives (all (n_el,) but ``dT_dx2``).

    Attributes
    ----------
    tension
        Chord force ``T``.
    dT_dl
        ``dT/dc`` at fixed direction and ``phi``.
    dT_dx2
        ``dT/dx2`` through the direction (``W_p^2``) only, (n_el, 3); ``dT/dx1`` is minus it.
    dT_dphi
        ``dT/dphi``.
    factor
        The chord factor ``g = c / s``.
    """

    tension: FloatArray
    dT_dl: FloatArray
    dT_dx2: FloatArray
    dT_dphi: FloatArray
    factor: FloatArray


def chord_factor(tension: FloatArray, weight2: FloatArray, perp2: FloatArray,
                 phi: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """The chord factor ``g`` and its derivatives ``g_T``, ``g_q`` (``q = W_p^2``) and
    ``g_phi``.

    Parameters
    ----------
    tension
        Chord force ``T`` [force].
    weight2, perp2
        ``W^2 = (w L0)^2`` and ``W_p^2 = W^2 (1 - n_z^2)`` [force^2].
    phi
        Share of the correction (0 to 1).
    """
    tp = np.maximum(tension, 0.0)
    q = 24.0 * tp * tp + weight2 / SATURATION
    safe = np.where(q > 0, q, 1.0)
    g = np.where(q > 0, 1.0 - phi * perp2 / safe, 1.0)
    g_T = np.where(q > 0, phi * perp2 * 48.0 * tp / (safe * safe), 0.0)
    g_q = np.where(q > 0, -phi / safe, 0.0)
    g_phi = np.where(q > 0, -perp2 / safe, 0.0)
    return g, g_T, g_q, g_phi


def sag_tension(
    length: FloatArray, unit: FloatArray, length0: FloatArray, EA: FloatArray,
    slack_ratio: FloatArray, smoothing: FloatArray | float, weight_per_length: FloatArray,
    phi: FloatArray, laws: StrainLaws | None = None, offset: FloatArray | None = None,
) -> SagTension:
    """Chord force of sag-corrected elements (module docstring) and its exact derivatives.

    Parameters
    ----------
    length, unit
        Chord length (n_el,) and unit vector from node 1 to node 2 (n_el, 3).
    length0, EA, slack_ratio, smoothing, laws, offset
        The straight element's law (:func:`moorline.physics.element.axial_tension`).
    weight_per_length
        Submerged weight per unstretched length ``w`` [force/length] (negative: buoyant).
    phi
        Share of the correction per element (0: a straight element).
    """
    weight2 = (weight_per_length * length0) ** 2
    nz = unit[:, 2]
    perp2 = weight2 * (1.0 - nz * nz)

    def law(chord_factor_g: FloatArray) -> tuple[FloatArray, FloatArray]:
        return axial_tension(length / chord_factor_g, length0, EA, slack_ratio, smoothing,
                             laws, offset)

    g_min = chord_factor(np.zeros_like(length), weight2, perp2, phi)[0]
    lo = law(np.ones_like(length))[0]
    hi = law(g_min)[0]
    T = np.clip(_sag_start(length, length0, weight2, perp2, phi, offset), lo, hi)
    step_old = step = hi - lo
    for _ in range(MAX_ITERATIONS):
        g, g_T, _, _ = chord_factor(T, weight2, perp2, phi)
        A, dA = law(g)
        F = T - A
        dF = 1.0 + dA * length * g_T / (g * g)
        lo = np.where(F < 0, T, lo)
        hi = np.where(F > 0, T, hi)
        # Newton, or bisection where Newton leaves the bracket or does not halve the step
        # (Press et al., Numerical Recipes, "rtsafe")
        bisect = (((T - hi) * dF - F) * ((T - lo) * dF - F) > 0) \
            | (np.abs(2.0 * F) > np.abs(step_old * dF))
        step_old = step
        step = np.where(bisect, T - 0.5 * (lo + hi), F / dF)
        # converged: F at its round-off (the strain l / L0 - 1 is known to ~eps), or no step
        settled = np.abs(F) <= NOISE * (np.abs(T) + dA * length / g)
        step = np.where(settled, 0.0, step)
        T = T - step
        if np.all(np.abs(step) <= 1e-15 * np.abs(T)):
            break
    g, g_T, g_q, g_phi = chord_factor(T, weight2, perp2, phi)
    _, dA = law(g)
    scale = dA / (g * (1.0 + dA * length * g_T / (g * g)))   # A' / (g D)
    dT_dl = scale
    # dq/dx2 = -2 W^2 n_z (e_z - n_z n) / c
    dq_dx2 = (-2.0 * weight2 * nz / length)[:, None] * (np.array([0.0, 0.0, 1.0])
                                                        - nz[:, None] * unit)
    dT_dq = -scale * length * g_q / g
    return SagTension(T, dT_dl, dT_dq[:, None] * dq_dx2, -scale * length * g_phi / g, g)


def _sag_start(length: FloatArray, length0: FloatArray, weight2: FloatArray,
               perp2: FloatArray, phi: FloatArray, offset: FloatArray | None) -> FloatArray:
    """A start for the tension: the inextensible sag law ``c = s_0 g(T)`` solved for ``T``
    (``s_0`` the length at zero strain); 0 where the chord is not shorter than ``s_0`` (the
    caller's lower bound, the straight element's tension, is then the start)."""
    s0 = length0 if offset is None else length0 * (1.0 + offset)
    short = 1.0 - length / s0
    safe = np.where(short > 0, short, 1.0)
    tp2 = (phi * perp2 / safe - weight2 / SATURATION) / 24.0
    return np.where(short > 0, np.sqrt(np.maximum(tp2, 0.0)), 0.0)


def sag_blocks(length: FloatArray, unit: FloatArray, sag: SagTension,
               dphi_dx: FloatArray) -> FloatArray:
    """Exact tangent of the resisting forces of sag-corrected elements, (n_el, 6, 6).

    The force on node 1 is ``T n`` (on node 2 ``-T n``); with ``k = dT/dc n n^T + T/c (I - n
    n^T) + n (dT/dx2)^T`` (the part that depends on ``x2 - x1``) and ``a_k = dT/dphi
    dphi/dx_k`` the blocks are ``[[k - n a_1, -k - n a_2], [-k + n a_1, k + n a_2]]``.

    Parameters
    ----------
    length, unit, sag
        Chord length, unit vector and :func:`sag_tension` of each element.
    dphi_dx
        ``dphi/dx_1`` and ``dphi/dx_2`` per element, (n_el, 2, 3).
    """
    n = unit
    nn = n[:, :, None] * n[:, None, :]
    k = (sag.dT_dl[:, None, None] * nn + (sag.tension / length)[:, None, None]
         * (np.eye(3) - nn) + n[:, :, None] * sag.dT_dx2[:, None, :])
    a = sag.dT_dphi[:, None, None] * dphi_dx                       # (n_el, 2, 3)
    n_a1 = n[:, :, None] * a[:, None, 0, :]
    n_a2 = n[:, :, None] * a[:, None, 1, :]
    blocks = np.empty((len(length), 6, 6))
    blocks[:, :3, :3] = k - n_a1
    blocks[:, :3, 3:] = -k - n_a2
    blocks[:, 3:, :3] = -k + n_a1
    blocks[:, 3:, 3:] = k + n_a2
    return blocks


@dataclass(frozen=True)
class SagCorrection:
    """What the sag correction of a mesh needs besides the element law.

    Attributes
    ----------
    active
        1 on sag-corrected elements, 0 on straight ones (n_el,).
    elements
        Node indices of each element (n_el, 2).
    node_load
        Each node's own load into the seabed [force] (its lumped submerged weight) (n_nodes,).
    node_stiffness, node_ramp
        The seabed contact's spring [force/length] and blend-in band [length] per node
        (:func:`moorline.physics.seabed.contact_force`).
    surface
        The seabed (``None``: no seabed, ``phi = active``).
    """

    active: FloatArray
    elements: IntArray
    node_load: FloatArray
    node_stiffness: FloatArray
    node_ramp: FloatArray
    surface: SeabedSurface | None

    def share(self, x: FloatArray) -> tuple[FloatArray, FloatArray]:
        """``phi`` per element at node positions ``x`` (n_nodes, 3), and ``dphi/dx`` of its
        two nodes (n_el, 2, 3)."""
        n_el = len(self.elements)
        if self.surface is None:
            return self.active.copy(), np.zeros((n_el, 2, 3))
        d, grad, _ = normal_distance(x, self.surface)
        s, ds = carried_share(d, self.node_stiffness, self.node_ramp, self.node_load)
        i, j = self.elements[:, 0], self.elements[:, 1]
        phi = self.active * (1.0 - s[i] * s[j])
        dphi = np.empty((n_el, 2, 3))
        dphi[:, 0] = (-self.active * s[j] * ds[i])[:, None] * grad[i]
        dphi[:, 1] = (-self.active * s[i] * ds[j])[:, None] * grad[j]
        return phi, dphi
