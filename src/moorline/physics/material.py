"""Three-parameter standard linear solid (SLS) in force units, vectorized over elements.

Tuah (1982) sec. 2.2.b. The constitutive law, eq. 2.2.b.2 multiplied by the area, is

    EA eps + tau (EA + EA1) deps/dt = T + tau dT/dt,                                  (1)

with ``EA = K0 A`` the long-term (quasi-static) stiffness, ``EA1 = K1 A`` the stiffness of the
spring in series with the dashpot, ``tau = N / K1`` the relaxation time of that Maxwell branch
(Tuah Fig. 2.2.b-1) and ``eps = l / L0 - 1`` the engineering strain, as in the elastic element
(:func:`moorline.physics.element.axial_tension`, which is this model's ``EA1 = 0`` limit).

Internal variable
-----------------
Split the tension into the parallel spring and the Maxwell-branch force ``Q``:

    T = EA eps + Q,        dQ/dt + Q / tau = EA1 deps/dt.                             (2)

(2) implies (1): ``T + tau dT/dt = EA eps + Q + tau EA deps/dt + tau dQ/dt
= EA eps + tau EA deps/dt + tau EA1 deps/dt``, which is (1). Conversely, given (1) define
``Q = T - EA eps``; substituting ``T = EA eps + Q`` into (1) gives ``tau (dQ/dt + Q/tau) =
tau EA1 deps/dt``, i.e. (2). The two forms are the same law; (2) makes the state explicit: ``Q``
(or, equivalently, the pair ``(eps, T)``) is everything the material remembers. Instantaneous
stiffness ``EA + EA1`` (fast loading), long-term stiffness ``EA`` (``Q -> 0`` at rest).

Here the state is always passed in and returned, never stored:

* :func:`sls_update_incremental` is the source's forward-difference form, Tuah (1982)
  eq. 2.2.b.3, with the previous tension as state (``Q_old = T_old - EA eps_old``).
* :func:`sls_update_exponential` integrates (2) exactly for a strain that varies linearly over
  the step, with ``Q`` as state. It is exact for piecewise-linear strain histories, second-order
  accurate otherwise, stable and accurate for any ``dt / tau`` (the source's form needs
  ``dt << tau``, Tuah sec. 2.2.b: "for dt << 5 seconds").

Slack (folded into :func:`sls_update_exponential`, keyword ``slack_ratio``)
----------------------------------------------------------------------------
A cable carries no compression. Rather than clipping the tension and letting ``Q`` follow the
chord strain (which, after a long slack spell with the chord much shorter than the rope, makes
``Q`` relax at the short chord and then produces a spurious tension of order ``EA1 x
shortening`` when the rope is pulled taut again), the rope *material* is given its own strain
``eps_m``: it equals the chord strain while taut; while slack the material is at zero force
(``EA eps_m + Q = 0``) and the chord is shorter than the material (``eps < eps_m``). In the slack
phase (2) then gives ``(1 + EA1/EA) dQ/dt = -Q / tau``: the dashpot keeps relaxing and the
material recovers towards its unstretched length with the retardation time
``tau (EA + EA1) / EA``. No extra state is needed: ``eps_m = max(eps, -Q / EA)``
(:func:`sls_material_strain`) holds in both phases. The transmitted force while slack is the
elastic element's tiny regularizing compression, ``slack_ratio EA (eps - eps_m)``, with tangent
``slack_ratio EA``; for ``EA1 = 0`` this is exactly the elastic element's
:func:`~moorline.physics.element.axial_tension`. Tension is continuous across the taut/slack
switch. While slack the material strain is not piecewise linear in time, so the exponential
update is second-order accurate there (not exact); for steps much longer than the retardation
time it under-predicts the recovery (``Q`` shrinks by about ``EA1 tau / (EA dt)`` per step
instead of ``exp(-dt/tc)``). The incremental form is kept as the source's linear law only (no
slack): it serves to reproduce Tuah's Example 3.

All functions take strains and return tensions and ``dT/deps``; an element's ``dT/dl`` is
``dT/deps / L0``. Arguments broadcast (per-element arrays or scalars). Imports only numpy.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

FloatArray = NDArray[np.float64]

__all__ = [
    "sls_material_strain",
    "sls_update_exponential",
    "sls_update_incremental",
]


def sls_update_incremental(
    strain_new: ArrayLike,
    strain_old: ArrayLike,
    tension_old: ArrayLike,
    dt: ArrayLike,
    EA: ArrayLike,
    EA1: ArrayLike,
    tau: ArrayLike,
) -> tuple[FloatArray, FloatArray]:
    """Tension after one step of the source's incremental SLS law.

    Tuah (1982) eq. 2.2.b.3, times the area: replacing ``deps/dt`` and ``dT/dt`` in
    eq. 2.2.b.2 by forward differences gives

        T_new = T_old + (EA eps_old - T_old) dt / tau + (EA + EA1) (eps_new - eps_old).

    This is forward Euler for the Maxwell force (``Q_new = Q_old (1 - dt/tau) + EA1 deps``):
    first-order accurate, and unstable (``|1 - dt/tau| > 1``) for ``dt > 2 tau``.

    Parameters
    ----------
    strain_new, strain_old
        Engineering strain ``l / L0 - 1`` at the end and the start of the step.
    tension_old
        Tension at the start of the step (the state of this form).
    dt
        Time step (>= 0).
    EA, EA1, tau
        Long-term stiffness ``K0 A``, Maxwell-branch stiffness ``K1 A`` (force units) and its
        relaxation time ``N / K1``.

    Returns
    -------
    tension_new, dtension_dstrain
        Tension at the end of the step and ``dT_new / d eps_new = EA + EA1``.
    """
    strain_new = np.asarray(strain_new, dtype=float)
    strain_old = np.asarray(strain_old, dtype=float)
    tension_old = np.asarray(tension_old, dtype=float)
    EA = np.asarray(EA, dtype=float)
    stiff = EA + np.asarray(EA1, dtype=float)
    tension_new = (
        tension_old
        + (EA * strain_old - tension_old) * (np.asarray(dt, dtype=float) / tau)
        + stiff * (strain_new - strain_old)
    )
    return tension_new, _full(stiff, tension_new)


def _relaxation_factors(
    dt: ArrayLike, tau: ArrayLike
) -> tuple[FloatArray, FloatArray]:
    """``exp(-h) - 1`` and ``phi = (1 - exp(-h)) / h`` with ``h = dt / tau`` (``phi(0) = 1``)."""
    minus_h = -(np.asarray(dt, dtype=float) / np.asarray(tau, dtype=float))
    a_minus_1 = np.expm1(minus_h)
    if a_minus_1.ndim == 0:
        return a_minus_1, (a_minus_1 / minus_h if minus_h < 0.0 else np.ones_like(minus_h))
    phi = np.divide(a_minus_1, minus_h, out=np.ones_like(a_minus_1), where=minus_h < 0.0)
    return a_minus_1, phi


def _full(x: FloatArray, like: FloatArray) -> FloatArray:
    """``x`` broadcast to the shape of ``like`` (a copy only when the shapes differ)."""
    return x if x.shape == like.shape else x + np.zeros_like(like)


def sls_material_strain(strain: ArrayLike, Q: ArrayLike, EA: ArrayLike) -> FloatArray:
    """Strain of the rope material, ``max(eps, -Q / EA)``.

    Equal to the chord strain ``eps`` while the element is taut (``T = EA eps + Q >= 0``) and to
    the zero-force strain ``-Q / EA`` while it is slack (``eps`` smaller than that). Only
    meaningful for states produced with slack handling on (see the module docstring).
    """
    return np.maximum(np.asarray(strain, dtype=float), -np.asarray(Q, dtype=float) / EA)


def sls_update_exponential(
    strain_new: ArrayLike,
    strain_old: ArrayLike,
    Q_old: ArrayLike,
    dt: ArrayLike,
    EA: ArrayLike,
    EA1: ArrayLike,
    tau: ArrayLike,
    slack_ratio: ArrayLike | None = None,
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Tension after one step, integrating the Maxwell branch exactly.

    With the strain linear in time over the step, ``deps/dt = (eps_new - eps_old) / dt``,
    the ODE ``dQ/dt + Q/tau = EA1 deps/dt`` (module eq. 2, equivalent to Tuah (1982)
    eq. 2.2.b.2) integrates to

        Q_new = exp(-dt/tau) Q_old + EA1 tau (1 - exp(-dt/tau)) / dt (eps_new - eps_old),
        T_new = EA eps_new + Q_new,
        dT_new/deps_new = EA + EA1 tau (1 - exp(-dt/tau)) / dt.

    ``1 - exp(-h)`` is evaluated with ``expm1``; ``dt = 0`` gives the instantaneous response
    (stiffness ``EA + EA1``), ``dt >> tau`` the relaxed one (``EA``).

    Parameters
    ----------
    strain_new, strain_old
        Engineering (chord) strain ``l / L0 - 1`` at the end and the start of the step.
    Q_old
        Maxwell-branch force at the start of the step (the state; 0 for a relaxed element).
    dt
        Time step (>= 0).
    EA, EA1, tau
        Long-term stiffness ``K0 A``, Maxwell-branch stiffness ``K1 A`` and its relaxation time.
    slack_ratio
        ``None`` (default): the linear law, compression allowed. Otherwise the element cannot
        push: when the trial tension is negative the element is slack, its material strain
        ``eps_m`` is found from ``EA eps_m + Q_new(eps_m) = 0`` (the same exponential update
        along the material strain path), ``Q_new = -EA eps_m`` and the transmitted force is
        ``slack_ratio EA (eps_new - eps_m) < 0`` with tangent ``slack_ratio EA``. The material
        strain at the start of the step is ``max(eps_old, -Q_old / EA)``. See the module
        docstring for why ``Q`` follows the material, not the chord, while slack.

    Returns
    -------
    tension_new, Q_new, dtension_dstrain
        Transmitted tension, the new state and ``dT_new / d eps_new``.
    """
    strain_new = np.asarray(strain_new, dtype=float)
    Q_old = np.asarray(Q_old, dtype=float)
    EA = np.asarray(EA, dtype=float)
    a_minus_1, phi = _relaxation_factors(dt, tau)
    c = np.asarray(EA1, dtype=float) * phi  # d Q_new / d eps_new
    if slack_ratio is None:
        start = np.asarray(strain_old, dtype=float)
    else:
        start = sls_material_strain(strain_old, Q_old, EA)
    aq = Q_old + a_minus_1 * Q_old  # exp(-dt/tau) Q_old
    Q_new = aq + c * (strain_new - start)
    tension = EA * strain_new + Q_new
    tangent = EA + c
    if slack_ratio is None or not np.any(slack := tension < 0.0):
        return tension, _full(Q_new, tension), _full(tangent, tension)
    material = (c * start - aq) / tangent  # EA eps_m + aq + c (eps_m - start) = 0
    k_slack = np.asarray(slack_ratio, dtype=float) * EA
    tension = np.where(slack, k_slack * (strain_new - material), tension)
    Q_new = np.where(slack, -EA * material, Q_new)
    tangent = np.where(slack, k_slack, tangent)
    return tension, _full(Q_new, tension), _full(tangent, tension)
