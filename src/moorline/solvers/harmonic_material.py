"""The standard linear solid in harmonic balance: the Maxwell branch's periodic state.

The viscoelastic element's tension is ``T = EA eps + Q`` with the Maxwell-branch force
``dQ/dt + Q / tau = EA1 deps/dt`` (Tuah 1982 eq. 2.2.b.2; :mod:`moorline.physics.material`,
module eq. 2). In a periodic steady state this linear ODE is solved harmonic by harmonic:
for ``eps = Re(e_k exp(i k w t))``,

    Q_k = EA1 H_k e_k,    H_k = i k w tau / (1 + i k w tau),    Q_0 = 0,

(a complex modulus: the spring ``EA1`` in series with the dashpot ``EA1 tau``). In cosine-sine
coefficients, ``eps = a cos + b sin``: ``Q = EA1 ((h_r a + h_i b) cos + (h_r b - h_i a) sin)``
with ``h_r = (k w tau)^2 / (1 + (k w tau)^2)``, ``h_i = k w tau / (1 + (k w tau)^2)``.

The harmonic-balance residual samples the strains at the instants, projects them on the
harmonics, applies ``H_k`` and synthesizes ``Q`` back at the instants: one linear map per
element, ``Q_j = sum_i L_ji eps_i`` (:func:`maxwell_operator`), whose matrix also gives the
exact Jacobian (the tension at an instant depends on the strain at every instant).
The law is the taut one (no slack of the rope material, unlike the time domain's
:func:`~moorline.physics.material.sls_update_exponential`).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]


def maxwell_operator(E: FloatArray, omega: float, EA1: FloatArray, tau: FloatArray
                     ) -> FloatArray:
    """The map from strain samples to Maxwell-branch force samples over one period.

    Parameters
    ----------
    E
        The basis at the instants (n_t, 2 n + 1): the mean, ``cos k w t``, ``sin k w t``.
    omega
        Fundamental circular frequency.
    EA1, tau
        Maxwell-branch stiffness and relaxation time per element (n_e,).

    Returns
    -------
    L
        (n_e, n_t, n_t): ``Q_j = sum_i L[e, j, i] eps_i`` for element ``e``.
    """
    n_terms = E.shape[1]
    n = (n_terms - 1) // 2
    project = np.linalg.pinv(E)  # (2 n + 1, n_t): samples to coefficients
    k = np.arange(1, n + 1)
    x = np.outer(np.asarray(tau, dtype=float), k * omega)  # (n_e, n): k w tau
    hr, hi = x * x / (1 + x * x), x / (1 + x * x)
    D = np.zeros((len(x), n_terms, n_terms))
    cos, sin = 2 * k - 1, 2 * k
    D[:, cos, cos], D[:, cos, sin] = hr, hi
    D[:, sin, cos], D[:, sin, sin] = -hi, hr
    return np.asarray(EA1, dtype=float)[:, None, None] * np.einsum(
        "jk,ekl,li->eji", E, D, project)


def maxwell_jacobian(mesh, ve: NDArray[np.int64], L: FloatArray, E: FloatArray, n_u: int,
                     positions: list[FloatArray], extended: tuple[NDArray[np.int64], int],
                     maps: list | None = None) -> sp.csr_matrix:
    """The non-local part of the viscoelastic elements' harmonic-balance Jacobian: the
    tension at instant ``j`` depends through ``Q_j = sum_i L_ji eps_i`` on the strain at every
    instant ``i``: ``(1 / N_t) sum_ji E_j^T g_j L_ji h_i^T E_i``, with ``g_j = d R_j / d T``
    (minus the element's nodal forces per unit tension, mapped to the unknowns by ``T^T``)
    and ``h_i = d eps_i / d u`` (through the master-slave map ``P_x``).

    Parameters
    ----------
    mesh
        The mesh.
    ve, L
        The viscoelastic elements and their :func:`maxwell_operator` (n_ve, n_t, n_t).
    E
        The basis at the instants (n_t, 2 n + 1).
    n_u
        Unknowns per term (node dofs and body dofs).
    positions
        Node positions at every instant (n_nodes, 3).
    extended
        The extended dof of every node (n_nodes, 3; -1: held) and their number: the free
        dofs, or with bodies the free and the attached nodes' dofs.
    maps
        With bodies, per instant ``(T^T, P_x)`` from the extended dofs to the unknowns and
        back; ``None``: the extended dofs are the unknowns.

    Returns
    -------
    The (n_u (2 n + 1))^2 sparse matrix, in the unknowns' order (dof by dof).
    """
    n_t, m = E.shape
    el = mesh.elements[ve]
    ext, n_ext = extended
    G = np.zeros((n_t, n_u, len(ve)))
    H = np.zeros((n_t, len(ve), n_u))
    for j, x in enumerate(positions):
        chord = x[el[:, 1]] - x[el[:, 0]]
        unit = chord / np.linalg.norm(chord, axis=1)[:, None]
        g_ext, h_ext = np.zeros((n_ext, len(ve))), np.zeros((len(ve), n_ext))
        for side, sign in ((0, -1.0), (1, 1.0)):
            d = ext[el[:, side]]  # (n_ve, 3)
            for c in range(3):
                ok = d[:, c] >= 0
                e_ok = np.flatnonzero(ok)
                g_ext[d[ok, c], e_ok] += sign * unit[ok, c]
                h_ext[e_ok, d[ok, c]] += sign * unit[ok, c] / mesh.length0[ve][ok]
        if maps:
            Tt, Px = maps[j]
            G[j], H[j] = Tt @ g_ext, (Px.T @ h_ext.T).T
        else:
            G[j], H[j] = g_ext, h_ext
    rows, cols, vals = [], [], []
    for e in range(len(ve)):
        r = np.flatnonzero(np.abs(G[:, :, e]).max(axis=0) > 0)
        c = np.flatnonzero(np.abs(H[:, e, :]).max(axis=0) > 0)
        block = np.einsum("jr,jk,ji,ic,il->rkcl", G[:, r, e], E, L[e],
                          H[:, e, c], E) / n_t
        ri = (r[:, None] * m + np.arange(m)).reshape(len(r), m, 1, 1)
        ci = (c[:, None] * m + np.arange(m)).reshape(1, 1, len(c), m)
        rows.append(np.broadcast_to(ri, block.shape).ravel())
        cols.append(np.broadcast_to(ci, block.shape).ravel())
        vals.append(block.ravel())
    size = m * n_u
    return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows),
                                                np.concatenate(cols))),
                         shape=(size, size))


__all__ = ["maxwell_jacobian", "maxwell_operator"]
