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


__all__ = ["maxwell_operator"]
