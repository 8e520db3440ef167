"""Morison hydrodynamic loads on straight two-node cable elements and on point bodies.

Tuah (1982) sec. 3.2.a, eq. 3.2.a.1-3.2.a.10, evaluated over all elements at once.

Conventions
-----------
* Every element quantity is evaluated once, at the element: the structural velocity is the mean
  of the two node velocities, the fluid velocity/acceleration is the one at the element midpoint
  (given by the caller), and the unit tangent ``t`` is the chord direction ``(x2 - x1) / l``.
* ``u = u_fluid - v_struct`` is the relative flow velocity (Tuah eq. 3.2.a.3 and 3.2.a.5; the
  OCR'd eq. 3.2.a.3 reads ``V_Ni - U_Ni``, the dot on the structural velocity was lost).
  ``u_t = (u . t) t`` and ``u_n = u - u_t``.
* Loads are per *unstretched* length ``L0``, with the diameter ``D`` unchanged by stretch, and
  the element total is lumped half to each node. Tuah eq. 3.2.a.9-3.2.a.10 lumps a linearly
  varying load given by its nodal values (``F^1 = L (3 F_N^1 + F_N^2) / 8``, nodal tangents
  ``theta`` at the nodes); with one evaluation at the element (chord tangent) the load is uniform
  over the element and that lumping reduces to one half per node. Using ``L0`` instead of the
  current length underestimates the drag by a factor ``1 + strain`` (a few per mille for a
  mooring line) and keeps the added mass a constant per unstretched length.
* Coefficients, diameters and ``rho`` are scalars or per-element arrays (broadcast).

Drag (Tuah eq. 3.2.a.2 and 3.2.a.4), per unit length::

    f = B_D |u_n| u_n + B_T |u_t| u_t,   B_D = rho Cd D / 2,   B_T = rho Ct pi D / 2.

The tangential (skin) drag acts on the wetted perimeter ``pi D`` (the area of a flat plate with
the same surface, Tuah sec. 3.2); this is also MoorDyn's convention for ``Cdt``. The OCR'd
eq. 3.2.a.7 prints ``B_D = (1/2) rho C_D D / 2``, which is inconsistent with eq. 3.2.a.1 and
with the linearization eq. 3.2.a.6 (whose velocity Jacobian
``B_D u_n u_n^T / |u_n| + B_D |u_n| I + (2 B_T |u_t| - B_D |u_n|) t t^T`` is exactly the one
derived below with ``B_D = rho Cd D / 2``); we use ``B_D = rho Cd D / 2``.

Derivative of ``|w| w`` at ``w = 0``: ``d(|w| w)/dw = |w| I + w w^T / |w|`` is continuous with
the exact limit ``0`` at ``w = 0`` (the map is C^1). We use that exact limit (no regularization,
the force is unchanged): the term ``w w^T / |w|`` is set to zero where ``|w| = 0``.

Position derivatives (``dF_dx``) are taken through the change of ``t`` only. Tuah keeps them as
the "incremental stiffness" ``S_ij`` of eq. 3.2.a.6 and neglects them; we give them exactly. The
derivative of the fluid kinematics with respect to position (e.g. a velocity gradient of a
sheared current or of waves) is neglected: the fluid velocity and acceleration at the midpoint
are held fixed.

Inertia (Tuah eq. 3.2.a.2): ``rho A [C_M a_N - (C_M - 1) \\ddot U_N]`` with ``A = pi D^2 / 4``,
i.e. an added mass ``Ca = C_M - 1`` on the normal structural acceleration and a fluid inertia
(Froude-Krylov plus added mass) ``C_M = 1 + Ca`` on the normal fluid acceleration. Tuah has no
tangential inertia terms; we add a tangential added-mass coefficient ``Cat`` (``Cat = 0``
recovers Tuah's added mass) and apply ``1 + Cat`` to the tangential fluid acceleration, because
the Froude-Krylov part ``rho A a_f`` (the pressure gradient of the undisturbed flow acting on the
displaced volume) acts in every direction. Tuah's fluid inertia (none along ``t``) together
with Tuah's added mass is therefore not reproducible with one ``Cat``; the difference is the
tangential ``rho A L0 (1 + Cat) a_f,t``, small for a slender line.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]

_EYE = np.eye(3)


def sum_to_nodes(element_node_forces: FloatArray, elements: IntArray, n_nodes: int) -> FloatArray:
    """Add the forces each element exerts on its nodes into a nodal array.

    Parameters
    ----------
    element_node_forces
        Forces on the two nodes of every element, shape (n_elements, 2, 3).
    elements
        Node indices of each element, shape (n_elements, 2).
    n_nodes
        Number of nodes.

    Returns
    -------
    FloatArray
        Nodal forces, shape (n_nodes, 3).
    """
    idx = (3 * np.asarray(elements)[:, :, None] + np.arange(3)).ravel()
    flat = np.bincount(idx, np.asarray(element_node_forces, float).ravel(), 3 * n_nodes)
    return flat.reshape(n_nodes, 3)


def _tangent(x: FloatArray, elements: IntArray) -> tuple[FloatArray, FloatArray]:
    """Current chord length (n_el,) and unit tangent (n_el, 3)."""
    chord = x[elements[:, 1]] - x[elements[:, 0]]
    length = np.sqrt(np.einsum("ij,ij->i", chord, chord))
    length = np.maximum(length, np.finfo(float).tiny)
    return length, chord / length[:, None]


def _outer(a: FloatArray, b: FloatArray) -> FloatArray:
    return np.einsum("ni,nj->nij", a, b)


def _per_element(value: ArrayLike, n_el: int) -> FloatArray:
    return np.broadcast_to(np.asarray(value, dtype=float), (n_el,))


def _node_blocks(block: FloatArray) -> FloatArray:
    """(n_el, 6, 6) with the same 3x3 ``block`` on all four node-node positions."""
    n = block.shape[0]
    row = np.empty((n, 3, 2, 3))
    row[:, :, 0] = block
    row[:, :, 1] = block
    return np.broadcast_to(row[:, None], (n, 2, 3, 2, 3)).reshape(n, 6, 6)


def _position_blocks(g: FloatArray) -> FloatArray:
    """Blocks of ``d(node force)/d(x1, x2)`` for a node force, the same on both nodes, that
    depends on position only through ``t``. ``g = (dF/dt) (I - t t^T) / l`` is the derivative
    with respect to ``x2`` (``dt/dx2 = -dt/dx1 = (I - t t^T) / l``)."""
    n = g.shape[0]
    row = np.empty((n, 3, 2, 3))
    np.negative(g, out=row[:, :, 0])
    row[:, :, 1] = g
    return np.broadcast_to(row[:, None], (n, 2, 3, 2, 3)).reshape(n, 6, 6)


def _projector_terms(alpha: FloatArray, t: FloatArray, p: FloatArray) -> FloatArray:
    """``alpha (I - t t^T) + t p^T`` per element, shape (n_el, 3, 3)."""
    out = _outer(t, p - alpha[:, None] * t)
    out[:, (0, 1, 2), (0, 1, 2)] += alpha[:, None]
    return out


def drag_forces(
    x: FloatArray,
    v: FloatArray,
    fluid_velocity_mid: FloatArray,
    elements: IntArray,
    length0: ArrayLike,
    diameter: ArrayLike,
    Cd: ArrayLike,
    Ct: ArrayLike,
    rho: ArrayLike,
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Normal and tangential Morison drag on every element, lumped to its nodes.

    Tuah (1982) eq. 3.2.a.2-3.2.a.5 with relative velocities, linearization eq. 3.2.a.6, lumping
    eq. 3.2.a.10 (see the module docstring for the conventions and the corrected ``B_D``).
    Per unit unstretched length ``f = (rho Cd D / 2) |u_n| u_n + (rho Ct pi D / 2) |u_t| u_t``,
    ``u = u_fluid(mid) - (v1 + v2) / 2``; each node receives ``f L0 / 2``.

    Parameters
    ----------
    x, v
        Node positions and velocities, shape (n_nodes, 3).
    fluid_velocity_mid
        Fluid velocity at each element midpoint, shape (n_elements, 3) (or (3,), broadcast).
    elements
        Node indices of each element, shape (n_elements, 2).
    length0, diameter, Cd, Ct, rho
        Unstretched length, hydrodynamic diameter, normal and tangential drag coefficients and
        fluid density: scalars or arrays of shape (n_elements,).

    Returns
    -------
    node_forces
        Drag on the two nodes of every element, shape (n_elements, 2, 3).
    dF_dv
        Exact derivative of the 6 node-force components with respect to the 6 node-velocity
        components ``(v1, v2)``, shape (n_elements, 6, 6); the damping matrix is ``-dF_dv``.
    dF_dx
        Exact derivative with respect to the node positions ``(x1, x2)`` through the change of
        ``t``, fluid velocity held fixed, shape (n_elements, 6, 6).
    """
    elements = np.asarray(elements)
    n_el = elements.shape[0]
    u = np.broadcast_to(fluid_velocity_mid, (n_el, 3)) - 0.5 * (v[elements[:, 0]]
                                                                 + v[elements[:, 1]])
    f, df_dv, g = _drag_share(x, u, -0.5, elements, length0, diameter, Cd, Ct, rho)
    return np.stack((f, f), axis=1), _node_blocks(df_dv), _position_blocks(g)


def nodal_drag_forces(
    x: FloatArray,
    v: FloatArray,
    fluid_velocity_mid: FloatArray,
    elements: IntArray,
    length0: ArrayLike,
    diameter: ArrayLike,
    Cd: ArrayLike,
    Ct: ArrayLike,
    rho: ArrayLike,
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """The drag of :func:`drag_forces` with each node's half of an element evaluated with that
    node's own velocity, ``u_a = u_fluid(mid) - v_a`` (the trapezoidal rule over the element
    instead of the midpoint rule; MoorDyn-C v2.7 source/Line.cpp evaluates its drag at the
    nodes with the node velocities). The two rules converge to the same line; the midpoint
    rule exerts no drag on the odd-even (zig-zag) velocity mode of a mesh, which the
    trapezoidal rule damps. Arguments and returns as :func:`drag_forces`; ``dF_dv`` couples
    each node with itself only.
    """
    elements = np.asarray(elements)
    n_el = elements.shape[0]
    forces = np.empty((n_el, 2, 3))
    dF_dv = np.zeros((n_el, 6, 6))
    dF_dx = np.empty((n_el, 6, 6))
    for side in (0, 1):
        u = np.broadcast_to(fluid_velocity_mid, (n_el, 3)) - v[elements[:, side]]
        f, df_dv, g = _drag_share(x, u, -1.0, elements, length0, diameter, Cd, Ct, rho)
        rows = slice(3 * side, 3 * side + 3)
        forces[:, side] = f
        dF_dv[:, rows, rows] = df_dv
        dF_dx[:, rows] = _position_blocks(g)[:, rows]
    return forces, dF_dv, dF_dx


def _drag_share(x: FloatArray, u: FloatArray, du_dv: float, elements: IntArray,
                length0: ArrayLike, diameter: ArrayLike, Cd: ArrayLike, Ct: ArrayLike,
                rho: ArrayLike) -> tuple[FloatArray, FloatArray, FloatArray]:
    """One node's share of each element's drag at relative velocity ``u`` (n_el, 3), its
    derivative with respect to a node velocity of which ``u`` changes by ``du_dv`` times
    (3x3 per element) and ``g``, its derivative with respect to ``x2`` through ``t``
    (:func:`_position_blocks`)."""
    n_el = elements.shape[0]
    length, t = _tangent(x, elements)
    s = np.einsum("ij,ij->i", u, t)
    u_n = u - s[:, None] * t
    un = np.sqrt(np.einsum("ij,ij->i", u_n, u_n))
    abs_s = np.abs(s)

    diameter = _per_element(diameter, n_el)
    half = 0.25 * _per_element(rho, n_el) * _per_element(length0, n_el) * diameter
    cn = half * _per_element(Cd, n_el)  # B_D L0 / 2: per-node share of the normal drag
    ct = half * np.pi * _per_element(Ct, n_el)  # B_T L0 / 2
    # f: force on each node (half the element total)
    f = (cn * un)[:, None] * u_n + (ct * abs_s * s)[:, None] * t

    # velocity (Tuah eq. 3.2.a.6): with w = u_n, d(|w| w)/dw = |w| I + w w^T / |w| (exact limit
    # 0 at w = 0) and w^T t = 0,
    #   df/du = cn |w| I + (2 ct |s| - cn |w|) t t^T + cn w w^T / |w|,   du/dv = du_dv I.
    inv = np.divide(1.0, un, out=np.zeros_like(un), where=un > 0.0)
    cnw = cn * un
    beta = 2.0 * ct * abs_s - cnw
    df_du = _outer(t, (du_dv * beta)[:, None] * t)  # times du/dv up front
    df_du += _outer(u_n, (du_dv * cn * inv)[:, None] * u_n)
    df_du[:, (0, 1, 2), (0, 1, 2)] += du_dv * cnw[:, None]

    # position through t (u fixed): d u_n/dt = -(t u^T + s I),
    # d(|s| s t)/dt = |s| s I + 2 |s| t u^T, so
    #   df/dt = -cn (|w| t u^T + s |w| I + s w w^T / |w|) + ct (|s| s I + 2 |s| t u^T); times
    # dt/dx2 = (I - t t^T) / l, using u^T (I - t t^T) = w^T:
    #   df/dx2 = [s (ct |s| - cn |w|) (I - t t^T) + beta t w^T - cn s w w^T / |w|] / l.
    inv_l = 1.0 / length
    g = _projector_terms(s * (ct * abs_s - cnw) * inv_l, t, (beta * inv_l)[:, None] * u_n)
    g += _outer(u_n, (-cn * s * inv * inv_l)[:, None] * u_n)
    return f, df_du, g


def _mass_scale(elements: IntArray, length0: ArrayLike, diameter: ArrayLike,
                rho: ArrayLike) -> FloatArray:
    """Per-node share of the displaced mass, ``rho (pi D^2 / 4) L0 / 2``."""
    n_el = np.asarray(elements).shape[0]
    d = _per_element(diameter, n_el)
    return 0.5 * _per_element(rho, n_el) * 0.25 * np.pi * d * d * _per_element(length0, n_el)


def added_mass_blocks(
    x: FloatArray,
    elements: IntArray,
    length0: ArrayLike,
    diameter: ArrayLike,
    Ca: ArrayLike,
    Cat: ArrayLike,
    rho: ArrayLike,
) -> FloatArray:
    """Node-lumped added mass of every element, shape (n_elements, 6, 6).

    Tuah (1982) eq. 3.2.a.2 (added mass ``(C_M - 1) rho A`` on the normal structural
    acceleration) with a tangential coefficient ``Cat`` added: each node's diagonal 3x3 block
    is ``rho A L0 [Ca (I - t t^T) + Cat t t^T] / 2``, ``A = pi D^2 / 4``; the node-node blocks
    are zero (lumped, eq. 3.2.a.10). Add these to the mass matrix.
    """
    elements = np.asarray(elements)
    n_el = elements.shape[0]
    _, t = _tangent(x, elements)
    m = _mass_scale(elements, length0, diameter, rho)
    ca = _per_element(Ca, n_el)
    cat = _per_element(Cat, n_el)
    block = (m * ca)[:, None, None] * _EYE + (m * (cat - ca))[:, None, None] * _outer(t, t)
    out = np.zeros((n_el, 6, 6))
    out[:, :3, :3] = block
    out[:, 3:, 3:] = block
    return out


def added_mass_position_derivative(
    x: FloatArray,
    a: FloatArray,
    elements: IntArray,
    length0: ArrayLike,
    diameter: ArrayLike,
    Ca: ArrayLike,
    Cat: ArrayLike,
    rho: ArrayLike,
) -> FloatArray:
    """Derivative of the added-mass force ``-M_a(x) a`` with respect to the node positions.

    With ``M_a = m [Ca I + (Cat - Ca) t t^T]`` per node (:func:`added_mass_blocks`),
    ``d(-M_a a_k)/dt = -m (Cat - Ca) (t a_k^T + (t . a_k) I)`` for node ``k``, times
    ``dt/dx2 = -dt/dx1 = (I - t t^T) / l``. Tuah (1982) neglects this term (part of ``S_ij``
    in eq. 3.2.a.6); it is given here for an exact Newton tangent.

    Parameters
    ----------
    x, a
        Node positions and accelerations, shape (n_nodes, 3).

    Returns
    -------
    FloatArray
        ``d(force on (node1, node2))/d(x1, x2)``, shape (n_elements, 6, 6).
    """
    elements = np.asarray(elements)
    n_el = elements.shape[0]
    length, t = _tangent(x, elements)
    m = _mass_scale(elements, length0, diameter, rho)
    c = -m * (_per_element(Cat, n_el) - _per_element(Ca, n_el)) / length
    out = np.empty((n_el, 2, 3, 2, 3))
    for k in range(2):  # the two nodes of every element (not a loop over elements)
        ak = a[elements[:, k]]
        s = np.einsum("ij,ij->i", t, ak)
        # c (t a_k^T + (t.a_k) I) (I - t t^T) = c [(t.a_k) (I - t t^T) + t (a_k - (t.a_k) t)^T]
        g = _projector_terms(c * s, t, c[:, None] * (ak - s[:, None] * t))
        np.negative(g, out=out[:, k, :, 0, :])
        out[:, k, :, 1, :] = g
    return out.reshape(n_el, 6, 6)


def fluid_inertia_forces(
    x: FloatArray,
    fluid_acceleration_mid: FloatArray,
    elements: IntArray,
    length0: ArrayLike,
    diameter: ArrayLike,
    Ca: ArrayLike,
    Cat: ArrayLike,
    rho: ArrayLike,
) -> tuple[FloatArray, FloatArray]:
    """Froude-Krylov plus added-mass force of the fluid acceleration, lumped to the nodes.

    Tuah (1982) eq. 3.2.a.2: ``C_M rho A a_N`` with ``C_M = 1 + Ca`` on the normal fluid
    acceleration; we also apply ``1 + Cat`` to the tangential part (Tuah has none; see the
    module docstring). Element total ``rho A L0 [(1 + Ca)(I - t t^T) + (1 + Cat) t t^T] a_f``,
    half to each node.

    Parameters
    ----------
    x
        Node positions, shape (n_nodes, 3).
    fluid_acceleration_mid
        Fluid acceleration at each element midpoint, shape (n_elements, 3) (or (3,)).

    Returns
    -------
    node_forces
        Shape (n_elements, 2, 3).
    dF_dx
        Derivative with respect to ``(x1, x2)`` through ``t`` (fluid acceleration held fixed),
        shape (n_elements, 6, 6).
    """
    elements = np.asarray(elements)
    n_el = elements.shape[0]
    length, t = _tangent(x, elements)
    af = np.broadcast_to(fluid_acceleration_mid, (n_el, 3))
    m = _mass_scale(elements, length0, diameter, rho)
    ca = _per_element(Ca, n_el)
    dc = m * (_per_element(Cat, n_el) - ca)
    s = np.einsum("ij,ij->i", t, af)
    f = (m * (1.0 + ca))[:, None] * af + (dc * s)[:, None] * t
    c = dc / length
    g = _projector_terms(c * s, t, c[:, None] * (af - s[:, None] * t))
    return np.stack((f, f), axis=1), _position_blocks(g)


def point_drag(
    v_rel: FloatArray, area: ArrayLike, Cd: ArrayLike, rho: ArrayLike
) -> tuple[FloatArray, FloatArray]:
    """Isotropic quadratic drag on point bodies (buoys, clump weights).

    ``F = 0.5 rho Cd A |u| u`` with ``u = v_rel`` the relative flow velocity (fluid minus body),
    the same coefficient in every direction (Tuah 1982 eq. 3.2.a.1 applied to the full
    relative velocity).

    Parameters
    ----------
    v_rel
        Relative flow velocity, shape (..., 3).
    area, Cd, rho
        Drag area, coefficient and fluid density, broadcast against ``v_rel[..., 0]``.

    Returns
    -------
    force
        Shape (..., 3).
    dF_dv_rel
        ``0.5 rho Cd A (|u| I + u u^T / |u|)`` (exact limit 0 at ``u = 0``), shape (..., 3, 3).
        The derivative with respect to the body velocity is ``-dF_dv_rel``.
    """
    u = np.asarray(v_rel, dtype=float)
    c = 0.5 * np.asarray(rho, float) * np.asarray(Cd, float) * np.asarray(area, float)
    c = np.broadcast_to(c, u.shape[:-1])
    norm = np.sqrt(np.sum(u * u, axis=-1))
    inv = np.divide(1.0, norm, out=np.zeros_like(norm), where=norm > 0.0)
    force = (c * norm)[..., None] * u
    jac = (c * norm)[..., None, None] * _EYE + c[..., None, None] * (
        (u * inv[..., None])[..., :, None] * u[..., None, :])
    return force, jac


def point_added_mass(volume: ArrayLike, Ca: ArrayLike, rho: ArrayLike) -> FloatArray:
    """Isotropic added mass ``rho Ca V I`` of point bodies, shape (..., 3, 3)."""
    m = np.asarray(rho, float) * np.asarray(Ca, float) * np.asarray(volume, float)
    return m[..., None, None] * _EYE
