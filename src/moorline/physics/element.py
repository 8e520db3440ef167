"""Two-node straight cable element, evaluated over all elements at once.

Tuah (1982) sec. 3.1, eq. 3.1.8a-3.1.12. The element carries an axial force only. Its strain is
the engineering strain of the chord, ``eps = l / L0 - 1``, with ``L0`` the unstretched length
(Tuah's pseudo-Hookean material, eq. 2.2.a.1: the traction per unstrained area grows by
``E d(ds)/d(Is)``, i.e. the tension is linear in the stretch ratio ``lambda = l / L0``).
An initial stress sigma0 in a reference configuration of length ``l_ref`` is represented by
``L0 = l_ref / (1 + sigma0 / E)``.

The tangent stiffness is the exact derivative of the nodal forces,

    k = (dT/dl) n n^T + (T / l) (I - n n^T),      K_e = [[k, -k], [-k, k]],

the material part plus the initial-stress (geometric) part. Tuah's printed form, eq. 3.1.8a with
eq. 3.1.9-3.1.11, reads ``(A sigma / l) I + (A sigma + E A lambda) / l^3 d d^T`` (with
``d = x2 - x1``); its second term carries ``+T n n^T / l`` where the exact derivative has
``-T n n^T / l``: the OCR'd form, or the thesis's incremental linearization, does not give the
consistent tangent, so we derive it here and check it against finite differences in the tests.

Slack elements (eps < 0) keep ``slack_ratio * EA`` in compression, so the tangent stays usable
(Tuah sec. 6.2: "the modulus E for the slack element is set to a very small value").

Non-linear laws: elements with a tabulated tension-strain law (``laws``,
:mod:`moorline.physics.load_strain`) take ``T = f(g(eps))``, ``dT/deps = f'(g) g'`` with
``g`` the slack-regularized strain of the linear law (``T = EA g``: ``g = eps`` when taut,
``(eps + s)^2 / (4 s)`` in the band, ``slack_ratio (eps + s)`` when slack); ``f`` is linear
(``EA``) for ``g < 0``. A strain ``offset`` (the dynamic stiffness of fibre ropes) shifts the
strain of any law: ``eps = l / L0 - 1 - offset``.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from .load_strain import StrainLaws

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]


def element_geometry(
    positions: FloatArray, elements: IntArray
) -> tuple[FloatArray, FloatArray]:
    """Chord length and unit tangent of every element.

    Parameters
    ----------
    positions
        Node positions, shape (n_nodes, 3).
    elements
        Node indices of each element, shape (n_elements, 2).

    Returns
    -------
    length, unit
        Current chord length (n_elements,) and unit vector from node 1 to node 2 (n_elements, 3).
    """
    chord = positions[elements[:, 1]] - positions[elements[:, 0]]
    length = np.sqrt(np.einsum("ij,ij->i", chord, chord))
    unit = chord / np.maximum(length, np.finfo(float).tiny)[:, None]
    return length, unit


def axial_tension(
    length: FloatArray, length0: FloatArray, EA: FloatArray, slack_ratio: FloatArray,
    smoothing: FloatArray | float = 0.0, laws: StrainLaws | None = None,
    offset: FloatArray | None = None,
) -> tuple[FloatArray, FloatArray]:
    """Tension of an elastic element that carries (almost) no compression.

    ``T = EA eps`` for ``eps >= s``; in the band ``|eps| < s`` (``s = smoothing``) the law
    blends smoothly (C1) into the slack branch, ``T = EA (eps + s)^2 / (4 s)``; below
    ``-s`` a slack element keeps ``slack_ratio EA (eps + s)``. With ``s = 0`` it is the
    plain no-compression law. The band exists for Newton's sake: an element that switches
    between slack and taut inside an iteration makes the residual kink, and implicit steps
    then cycle instead of converging (seen on chain lying on the seabed being pushed).
    ``laws`` and ``offset``: a tabulated law per element and a strain offset (module
    docstring).

    Returns
    -------
    tension, dtension_dlength
        Tension and its derivative with respect to the current length.
    """
    strain = _strain(length, length0, offset)
    s = np.broadcast_to(np.asarray(smoothing, dtype=float), strain.shape)
    taut = strain >= s
    band = ~taut & (strain > -s)
    safe_s = np.where(s > 0, s, 1.0)
    shifted = strain + s
    tension = np.where(taut, EA * strain,
                       np.where(band, EA * shifted**2 / (4 * safe_s), slack_ratio * EA * shifted))
    slope = np.where(taut, EA, np.where(band, EA * shifted / (2 * safe_s), slack_ratio * EA))
    if laws is not None and laws.active:
        ratio = np.broadcast_to(np.asarray(slack_ratio, dtype=float), strain.shape)
        g = np.where(taut, strain, np.where(band, shifted**2 / (4 * safe_s), ratio * shifted))
        dg = np.where(taut, 1.0, np.where(band, shifted / (2 * safe_s), ratio))
        f, df = laws.evaluate(g, np.broadcast_to(EA, strain.shape))
        table = laws.ids >= 0
        tension, slope = np.where(table, f, tension), np.where(table, df * dg, slope)
    return tension, slope / length0


def _strain(length: FloatArray, length0: FloatArray, offset: FloatArray | None) -> FloatArray:
    strain = length / length0 - 1.0
    return strain if offset is None else strain - offset


def dashpot_share(
    length: FloatArray, length0: FloatArray, smoothing: FloatArray | float = 0.0,
    offset: FloatArray | None = None,
) -> tuple[FloatArray, FloatArray]:
    """Fraction of an element's Kelvin-Voigt dashpot that acts, and its derivative with
    respect to the strain.

    A slack cable transmits no damping force either. Switching the dashpot on at a strain
    threshold would make the tension jump by ``BA deps/dt`` (an implicit Newton iteration
    cannot converge across a jump), so it blends in linearly over the same band as the
    tension law of :func:`axial_tension`: 0 below ``-s``, 1 above ``s`` (of the strain less
    ``offset``).
    """
    strain = _strain(length, length0, offset)
    s = np.broadcast_to(np.asarray(smoothing, dtype=float), strain.shape)
    safe_s = np.where(s > 0, s, 1.0)
    slope = np.where((s > 0) & (np.abs(strain) < s), 1.0 / (2 * safe_s), 0.0)
    return _share_of_strain(strain, s), slope


def lagged_dashpot_share(
    strain_before: FloatArray, smoothing: FloatArray | float = 0.0,
    offset: FloatArray | None = None,
) -> FloatArray:
    """Fraction of each element's dashpot that acts over a time step: the share of
    :func:`dashpot_share` at the strain the element had at the start of the step
    (``strain_before``, ``l / L0 - 1`` without the offset), held over the step.

    Why lagged: blended in over the slack band of width ``2 s`` (``s ~ 1e-5``), the damping
    force ``BA share(eps) deps/dt`` of an element snapping slack or taut has a slope
    ``BA (deps/dt) / (2 s)`` thousands of times ``EA``: the step's residual is all but
    discontinuous there, and Newton cycles or the step is cut many times over (issue 16: a
    1,000-element OC3 line under the P1 motion took 176 iterations a step). Held at its
    value at the start of the step, the share switches the dashpot on or off one step late
    (an error of order ``dt`` in the timing of the switch alone, converging with the step)
    and the residual of the step keeps only the C1 elastic band. A step that is cut starts
    again from the same state, so the share does not depend on the iteration path.
    """
    strain = np.asarray(strain_before, dtype=float)
    if offset is not None:
        strain = strain - offset
    s = np.broadcast_to(np.asarray(smoothing, dtype=float), strain.shape)
    return _share_of_strain(strain, s)


def _share_of_strain(strain: FloatArray, s: FloatArray) -> FloatArray:
    """The dashpot share law of :func:`dashpot_share` at the strain less its offset."""
    safe_s = np.where(s > 0, s, 1.0)
    return np.where(s > 0, np.clip((strain + s) / (2 * safe_s), 0.0, 1.0),
                    (strain > 0).astype(float))


def strain_energy(
    length: FloatArray, length0: FloatArray, EA: FloatArray, slack_ratio: FloatArray,
    smoothing: FloatArray | float = 0.0, laws: StrainLaws | None = None,
    offset: FloatArray | None = None,
) -> FloatArray:
    """Elastic energy stored in each element, ``L0 * integral of T d(eps)`` for the law of
    :func:`axial_tension` (its derivative with respect to ``l`` is the tension).

    For a tabulated law the taut part is exact, ``F(eps) - F(s) + E_band``; inside the band
    (width ``s`` ~ 1e-5) ``f`` is replaced by its linear part ``EA g`` (energy error of order
    ``f'' s^3``, the merit of the static line search only)."""
    strain = _strain(length, length0, offset)
    s = np.broadcast_to(np.asarray(smoothing, dtype=float), strain.shape)
    safe_s = np.where(s > 0, s, 1.0)
    shifted = strain + s
    energy = np.where(
        strain >= s, EA * (strain**2 / 2 + s**2 / 6),
        np.where(strain > -s, EA * shifted**3 / (12 * safe_s),
                 0.5 * slack_ratio * EA * shifted**2))
    if laws is not None and laws.active:
        EA = np.broadcast_to(EA, strain.shape)
        taut = laws.energy(np.maximum(strain, s), EA) - laws.energy(s, EA) + EA * s**2 * 2 / 3
        energy = np.where((laws.ids >= 0) & (strain >= s), taut, energy)
    return energy * length0


def nodal_forces(tension: FloatArray, unit: FloatArray) -> FloatArray:
    """Forces each element exerts on its two nodes, shape (n_elements, 2, 3).

    A tensioned element pulls node 1 towards node 2 and node 2 towards node 1.
    """
    f1 = tension[:, None] * unit
    return np.stack((f1, -f1), axis=1)


def tangent_blocks(
    length: FloatArray, unit: FloatArray, tension: FloatArray, dtension_dlength: FloatArray
) -> FloatArray:
    """Exact tangent of the elements' resisting forces, shape (n_elements, 6, 6).

    The resisting force is minus :func:`nodal_forces`; its derivative with respect to the
    nodal positions ``(x1, x2)`` is ``[[k, -k], [-k, k]]`` with
    ``k = dT/dl n n^T + T/l (I - n n^T)``.
    """
    nn = unit[:, :, None] * unit[:, None, :]
    geometric = (tension / length)[:, None, None]
    return pair_blocks(dtension_dlength[:, None, None] * nn + geometric * (np.eye(3) - nn))


def pair_blocks(k: FloatArray) -> FloatArray:
    """Element blocks ``[[k, -k], [-k, k]]`` (n_elements, 6, 6) of a 3x3 block per element: the
    pattern of anything acting on the relative motion of an element's two nodes."""
    blocks = np.empty((len(k), 6, 6))
    blocks[:, :3, :3] = k
    blocks[:, 3:, 3:] = k
    blocks[:, :3, 3:] = -k
    blocks[:, 3:, :3] = -k
    return blocks


def lumped_weight(
    elements: IntArray, length0: FloatArray, weight_per_length: FloatArray, n_nodes: int
) -> FloatArray:
    """Submerged weight lumped to the nodes, shape (n_nodes, 3) (z is up).

    For a uniform load on a 2-node element the consistent load vector equals the lumped one:
    half of ``w L0`` to each node (Tuah eq. 2.1.b.10 with eq. 3.1.1).
    """
    half = 0.5 * weight_per_length * length0
    fz = np.bincount(elements[:, 0], half, n_nodes) + np.bincount(elements[:, 1], half, n_nodes)
    out = np.zeros((n_nodes, 3))
    out[:, 2] = -fz
    return out


def lumped_mass(
    elements: IntArray, length0: FloatArray, mass_per_length: FloatArray, n_nodes: int
) -> FloatArray:
    """Lumped (diagonal) mass per node, shape (n_nodes,): half of each element to each node."""
    half = 0.5 * mass_per_length * length0
    return np.bincount(elements[:, 0], half, n_nodes) + np.bincount(elements[:, 1], half, n_nodes)


def consistent_mass_blocks(length0: FloatArray, mass_per_length: FloatArray) -> FloatArray:
    """Consistent element mass matrices, shape (n_elements, 6, 6).

    Tuah (1982) eq. 3.1.12: ``m L0 [[I/3, I/6], [I/6, I/3]]`` (mass per unstretched length, so
    the ``rho A / lambda`` factor of eq. 3.1.8a times the current length is ``m L0``).
    """
    m = (mass_per_length * length0)[:, None, None]
    eye = np.eye(3)
    blocks = np.empty((len(length0), 6, 6))
    blocks[:, :3, :3] = m * eye / 3.0
    blocks[:, 3:, 3:] = m * eye / 3.0
    blocks[:, :3, 3:] = m * eye / 6.0
    blocks[:, 3:, :3] = m * eye / 6.0
    return blocks
