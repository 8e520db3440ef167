"""MoorDyn's viscoelastic static-dynamic rope model, vectorized over elements.

Source: MoorDyn-C v2.7.1 ``source/Line.cpp`` (``Line::getStateDeriv``, branches
``ELASTIC_VISCO_CTE`` and ``ELASTIC_VISCO_MEAN``; state ``dl_1``, rate ``ld_1``), the line-type
parser ``source/MoorDyn2.cpp`` (``readLineProps``) and ``docs/inputs.rst`` ("EA_s|EA_d" and
"EA_s|EA_Dc|EA_D_Lm" with "BA_s|BA_d"); the model is Hall, Duong & Lozon (2023), "Streamlined
loads analysis of floating wind turbines with fiber rope mooring lines", IOWTC2023-119524
(MoorDyn's ``docs/references.rst``). The equations below are re-derived here from that source
(no code taken).

The model
---------
Per segment of unstretched length ``l``, in strains (``e = dl / l``) and force units: a
*static* branch, spring ``k1`` parallel to dashpot ``c1 = BA_s``, in series with a *dynamic*
branch, spring ``k2 = EA_d`` parallel to dashpot ``c2 = BA_d``. ``e1`` is the static branch's
strain (MoorDyn's ``dl_1 / l``), ``e - e1`` the dynamic branch's. Both carry the element force

    F = k1 e1 + c1 de1/dt = k2 (e - e1) + c2 (de/dt - de1/dt),                       (1)

so ``(c1 + c2) de1/dt = k2 (e - e1) - k1 e1 + c2 de/dt`` (MoorDyn's ``ld_1``). ``k1`` is chosen
so that the two springs in series give the static stiffness ``EA_s``:
``k1 = k2 EA_s / (k2 - EA_s)`` (MoorDyn's ``EA_1``; needs ``k2 > EA_s``). MoorDyn transmits
``T = k1 e1`` plus the damping ``Td = c1 de1/dt``, i.e. ``F`` of (1) (MoorDyn's ``getNodeTen``
returns ``T + Td``).

The dynamic stiffness is ``k2 = EA_d`` (constant) or ``k2 = EA_Dc + EA_D_Lm s``
(mean-load dependent) with ``s = k1 e1`` the *static branch's spring force*: the "mean load"
of the docs is not a running mean of the tension but this low-passed force (time constant
``~ (c1 + c2) / (k1 + k2)``), clipped at 0 (``k2 = EA_Dc`` when ``dl_1 < 0``). MoorDyn solves
``k2 = EA_Dc + EA_D_Lm k1(k2) e1`` for ``k2`` in closed form (the root of a quadratic); here ``s``
is the state instead, and then everything is explicit:

    k2(s) = EA_Dc + EA_D_Lm max(s, 0),     e1(s) = s / EA_s - s / k2(s),               (2)

``de1/ds = 1 / EA_s - EA_Dc / k2^2 > 0`` (as ``k2 >= EA_Dc > EA_s``) and continuous at 0.

Statics: at rest ``de1/dt = 0`` and (1)-(2) give ``e = s / EA_s``: the static law is exactly
``EA_s e`` whatever ``k2`` (the relaxed state of a strain ``e`` is ``s = EA_s e``).

Constant ``EA_d``: a standard linear solid
------------------------------------------
With ``k2`` constant, (1) is linear with complex stiffness ``(k1 + c1 p)(k2 + c2 p) /
((k1 + k2) + (c1 + c2) p)``, which partial fractions turn into a spring ``EA_s``, a dashpot
``eta = c1 c2 / (c1 + c2)`` and a Maxwell branch (``EA1``, ``tau``) in parallel:

    tau = (c1 + c2) / (k1 + k2),    EA1 = (k1 c2 + k2 c1) / (c1 + c2) - eta / tau - EA_s,

which is moorline's standard linear solid (:mod:`moorline.physics.material`) with ``BA = eta``
(:func:`sls_parameters`). (Check: ``c2 = 0`` gives ``EA1 = EA_d - EA_s``, ``tau = c1 / (k1 +
k2)``, the Kelvin form of the SLS.)

Mean-load dependent ``EA_d``: one step
--------------------------------------
The state is ``s`` per element (carried in the step state as the element's internal force
variable). Over a step ``dt`` from ``(e_o, s_o)`` to ``e_n`` (strain linear in time) the
static-branch strain follows the midpoint rule (second order, A-stable)

    phi(s_n) = (c1 + c2) (e1(s_n) - e1(s_o)) - dt [k2(s_m) (e_m - e1(s_m)) - s_m]
               - c2 (e_n - e_o) = 0,      s_m = (s_o + s_n) / 2,  e_m = (e_o + e_n) / 2,

solved per element by Newton. The force at the end of the step is (1) with ``de1/dt`` from the
ODE at ``(s_n, e_n)``:

    F = T_e + eta de/dt,    T_e = (c2 s_n + c1 k2(s_n) (e_n - e1(s_n))) / (c1 + c2),

``eta de/dt`` being a Kelvin-Voigt dashpot on the current strain rate (moorline's line ``BA``
with ``BA = eta``). ``dT_e/de_n`` is exact: ``dT_e/de + dT_e/ds ds_n/de_n`` with
``ds_n/de_n = -(dphi/de_n) / (dphi/ds_n)``.

Slack: the rope cannot push; where ``T_e <= 0`` the element transmits the line's slack
regularization ``slack_ratio EA_s e`` (MoorDyn instead zeroes ``T`` when the segment is
shorter than its unstretched length and keeps ``Td``); the state keeps following the ODE, as in
MoorDyn.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

FloatArray = NDArray[np.float64]

__all__ = ["branch_strain", "sls_parameters", "static_dynamic_update"]


def sls_parameters(EA_s: float, EA_d: float, BA_s: float, BA_d: float
                   ) -> tuple[float, float, float]:
    """The standard linear solid equal to MoorDyn's constant-``EA_d`` model (module docstring).

    Parameters
    ----------
    EA_s, EA_d
        Static and dynamic stiffness [force], ``EA_d > EA_s > 0``.
    BA_s, BA_d
        Static- and dynamic-branch damping [force*time], ``>= 0``, not both 0.

    Returns
    -------
    EA1, tau, BA
        Maxwell-branch stiffness [force], its relaxation time [time] and the parallel dashpot
        ``eta`` [force*time] (:class:`~moorline.model.LineType` ``EA1``, ``tau``, ``BA``).
    """
    k1 = EA_d * EA_s / (EA_d - EA_s)
    c = BA_s + BA_d
    eta = BA_s * BA_d / c
    tau = c / (k1 + EA_d)
    EA1 = (k1 * BA_d + EA_d * BA_s) / c - eta / tau - EA_s
    return EA1, tau, eta


def _k2(s: FloatArray, alpha: FloatArray, beta: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Dynamic stiffness ``k2(s)`` (2) and ``dk2/ds``."""
    loaded = s > 0.0
    return alpha + beta * np.where(loaded, s, 0.0), np.where(loaded, beta, 0.0)


def branch_strain(s: ArrayLike, EA_s: ArrayLike, alpha: ArrayLike, beta: ArrayLike
                  ) -> tuple[FloatArray, FloatArray]:
    """Static-branch strain ``e1(s)`` of (2) and ``de1/ds`` for a static-branch force ``s``."""
    s = np.asarray(s, dtype=float)
    k2, _ = _k2(s, np.asarray(alpha, dtype=float), np.asarray(beta, dtype=float))
    return s / EA_s - s / k2, 1.0 / np.asarray(EA_s, dtype=float) - alpha / k2**2


def static_dynamic_update(
    strain_new: ArrayLike,
    strain_old: ArrayLike,
    s_old: ArrayLike,
    dt: float,
    EA_s: ArrayLike,
    alpha: ArrayLike,
    beta: ArrayLike,
    c1: ArrayLike,
    c2: ArrayLike,
    slack_ratio: ArrayLike,
    *,
    tol: float = 1e-13,
    max_iter: int = 50,
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Elastic part of the force after one step, the new state and the exact tangent.

    Parameters
    ----------
    strain_new, strain_old
        Element strain ``l / L0 - 1`` at the end and the start of the step.
    s_old
        Static-branch spring force at the start of the step [force] (the state).
    dt
        Time step [time] (>= 0).
    EA_s, alpha, beta
        Static stiffness, ``EA_Dc`` [force] and ``EA_D_Lm`` [-] (``k2 = alpha + beta s``).
    c1, c2
        Static- and dynamic-branch damping [force*time] (``c1 + c2 > 0``).
    slack_ratio
        Stiffness ratio of the slack regularization (where ``T_e <= 0``).

    Returns
    -------
    tension, s_new, dtension_dstrain
        ``T_e`` (without the ``eta de/dt`` dashpot, see the module docstring), the new state
        and ``dT_e / d strain_new``.
    """
    e_n = np.asarray(strain_new, dtype=float)
    e_o = np.asarray(strain_old, dtype=float)
    s_o = np.asarray(s_old, dtype=float)
    EA_s, alpha, beta, c1, c2 = (np.asarray(a, dtype=float) for a in (EA_s, alpha, beta, c1, c2))
    c = c1 + c2
    e_m = 0.5 * (e_o + e_n)
    g_o, _ = branch_strain(s_o, EA_s, alpha, beta)
    s = s_o.copy() + np.zeros_like(e_n)
    scale = np.maximum(np.abs(s_o), EA_s * np.maximum(np.abs(e_n), 1e-6))
    for _ in range(max_iter):
        phi, dphi = _midpoint_residual(s, s_o, g_o, e_m, e_n - e_o, dt, EA_s, alpha, beta, c, c2)
        step = phi / dphi
        s = s - step
        if np.all(np.abs(step) <= tol * scale):
            break
    else:
        raise FloatingPointError("static-dynamic rope update did not converge")
    _, dphi = _midpoint_residual(s, s_o, g_o, e_m, e_n - e_o, dt, EA_s, alpha, beta, c, c2)
    s_m = 0.5 * (s_o + s)
    k2_m, _ = _k2(s_m, alpha, beta)
    ds_de = (0.5 * dt * k2_m + c2) / dphi          # -(dphi/de_n) / (dphi/ds_n)
    k2, dk2 = _k2(s, alpha, beta)
    g, dg = branch_strain(s, EA_s, alpha, beta)
    tension = (c2 * s + c1 * k2 * (e_n - g)) / c
    dT_ds = (c2 + c1 * (dk2 * (e_n - g) - k2 * dg)) / c
    tangent = c1 * k2 / c + dT_ds * ds_de
    slack = tension <= 0.0
    if np.any(slack):
        k_slack = np.asarray(slack_ratio, dtype=float) * EA_s
        tension = np.where(slack, k_slack * e_n, tension)
        tangent = np.where(slack, k_slack + 0.0 * tangent, tangent)
    return tension, s, tangent


def _midpoint_residual(s, s_o, g_o, e_m, de, dt, EA_s, alpha, beta, c, c2):
    """``phi(s_n)`` of the module docstring and ``dphi/ds_n``."""
    g, dg = branch_strain(s, EA_s, alpha, beta)
    s_m = 0.5 * (s_o + s)
    g_m, dg_m = branch_strain(s_m, EA_s, alpha, beta)
    k2_m, dk2_m = _k2(s_m, alpha, beta)
    rate = k2_m * (e_m - g_m) - s_m
    drate = 0.5 * (dk2_m * (e_m - g_m) - k2_m * dg_m - 1.0)
    return c * (g - g_o) - dt * rate - c2 * de, c * dg - dt * drate
