"""Wake oscillator for the lift coefficient of vortex shedding (cable strumming).

Tuah (1982) sec. 3.2.b, eq. 3.2.b.1-3.2.b.8, after Griffin, Skop and Ramberg (1975) and Skop
and Griffin (1973). Pure functions, vectorized over elements (every argument a scalar or an
array of shape (n_elements,), broadcast).

The OCR'd source is partly garbled; what is used here, and why:

Lift force (eq. 3.2.b.1-3.2.b.2). Printed ``F_Li = 1/2 rho_f D C_L eps_ikl theta_k V_NRi
V_NRl``; the repeated free index ``i`` cannot be right. With ``theta`` the unit tangent and
``V_NR`` the relative normal velocity (eq. 3.2.a.3) the permutation symbol builds the cross
product, and the force has the dimensions of ``1/2 rho D C_L |V_NR|^2``, so per unit length::

    F_L = 1/2 rho_f D C_L |V_NR| (theta x V_NR),

of magnitude ``1/2 rho_f D C_L |V_NR|^2``, perpendicular to the element and to the relative
velocity (the sign is immaterial: ``C_L`` oscillates about zero).

Wake oscillator (eq. 3.2.b.3), with the bracket's first term squared::

    C_L'' + w_s^2 C_L - [C_L0^2 - C_L^2 - (C_L' / w_s)^2] (w_s G C_L' - w_s^2 H C_L)
        = w_s F U_T' / D.

The OCR prints ``C_L0`` unsquared; only ``C_L0^2`` is dimensionally consistent with
``C_L^2`` and gives the fixed cylinder (``U_T' = 0``) its stationary lift amplitude ``C_L0``
(below). ``U_T'`` is the transverse (strumming) velocity of the element along the lift
direction, signed (Griffin et al. 1975). The source calls it "the transverse cable velocity
magnitude"; read literally (``|U_T'|``) the forcing is rectified: it shifts ``C_L`` upwards
and cannot synchronize the wake with the structure. The strumming solver offers both
(:class:`moorline.model.StrummingSettings` ``transverse_velocity``); the verification of
Tuah's Examples 6 and 7 uses the signed one (:mod:`moorline.verification.tuah_ex6`).

Free limit cycle (derivation, used by the tests). With ``E = C_L^2 + (C_L' / w_s)^2``::

    dE/dt = (2 C_L' / w_s^2) (C_L'' + w_s^2 C_L)
          = 2 (C_L0^2 - E) (G C_L'^2 / w_s - H C_L C_L').

So ``E = C_L0^2`` is invariant, and on it ``C_L'' + w_s^2 C_L = 0``: the limit cycle is
exactly ``C_L = C_L0 cos(w_s t + phi)`` -- amplitude ``C_L0``, frequency ``w_s``, for any
``G > 0`` and ``H`` (it is stable: inside it the ``G`` term is a negative damping, outside a
positive one). Averaged over a cycle (``<C_L'^2> = w_s^2 E / 2``, ``<C_L C_L'> = 0``), for small
``eps = G C_L0^2`` (the van der Pol limit), the energy obeys the logistic law
``d<E>/dt = G w_s (C_L0^2 - <E>) <E>``, growth rate ``G w_s C_L0^2`` from small amplitudes;
meanwhile the ``H`` term shifts the frequency to ``w_s sqrt(1 + H (C_L0^2 - E))``.

Shedding frequency (eq. 3.2.b.4): ``w_s = 2 pi S_T |V_NR| / D``.

Empirical parameters (eq. 3.2.b.5-3.2.b.6), from the Skop-Griffin response parameter
``S_G = 2 pi S_T^2 k_s`` with the reduced damping ``k_s = 4 pi m xi / (rho_f D^2)``, which
the source evaluates from the fluid's viscous damping as ``k_s = 45 (nu / w_s)^(1/2) / D``::

    log10 G = 0.25 - 0.21 S_G,
    log10 (h S_G^2) = -0.24 + 0.66 S_G,      (h a dummy variable)
    H = xi h,
    F = 4 G S_G / h,

with ``xi = k_s rho_f D^2 / (4 pi m)`` the damping ratio that ``k_s`` stands for and ``m``
the structural plus added mass per unit length. These are the printed formulas; we could not
check them against Skop and Griffin's papers (not available here). Note that with them
``F H / G = 4 S_G xi``: the ``H`` term has little effect for small damping.

Modal damping (eq. 3.2.b.8): ``xi_n = 12 rho_f D / (pi m) (nu / w_n)^(1/2)``, the viscous
damping of a cylinder oscillating in still fluid (consistent with ``k_s`` above:
``4 pi m xi_n / (rho_f D^2) = 48 (nu / w_n)^(1/2) / D``, against the 45 of eq. 3.2.b.6).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

FloatArray = NDArray[np.float64]

#: The Strouhal number the brief's default (a stationary cylinder, subcritical Reynolds
#: numbers; Tuah 1982 does not print the value it used).
DEFAULT_STROUHAL = 0.2


def reynolds_number(speed: ArrayLike, diameter: ArrayLike, viscosity: float) -> FloatArray:
    """``Re = |V| D / nu``.

    Parameters
    ----------
    speed
        Relative normal flow speed [length/time].
    diameter
        Cable diameter [length].
    viscosity
        Kinematic viscosity ``nu`` [length^2/time].
    """
    return np.abs(np.asarray(speed, float)) * np.asarray(diameter, float) / viscosity


def strouhal_frequency(normal_speed: ArrayLike, diameter: ArrayLike,
                       strouhal: float = DEFAULT_STROUHAL) -> FloatArray:
    """Shedding (Strouhal) circular frequency ``w_s = 2 pi S_T |V_NR| / D``.

    Tuah (1982) eq. 3.2.b.4.

    Parameters
    ----------
    normal_speed
        Magnitude of the relative normal fluid velocity ``|V_NR|`` (eq. 3.2.a.3) [length/time].
    diameter
        Cable diameter [length].
    strouhal
        Strouhal number ``S_T``.

    Returns
    -------
    FloatArray
        ``w_s`` [rad/time]; zero where the diameter is zero.
    """
    d = np.asarray(diameter, float)
    speed = np.abs(np.asarray(normal_speed, float))
    return np.divide(2.0 * math.pi * strouhal * speed, d, out=np.zeros(np.broadcast(speed, d)
                                                                      .shape), where=d > 0)


def reduced_damping(omega_s: ArrayLike, diameter: ArrayLike, viscosity: float) -> FloatArray:
    """Reduced damping ``k_s = 45 (nu / w_s)^(1/2) / D`` of the viscous fluid damping.

    Tuah (1982) eq. 3.2.b.6 (second equality).
    """
    w = np.asarray(omega_s, float)
    return 45.0 * np.sqrt(viscosity / w) / np.asarray(diameter, float)


def skop_griffin_parameter(strouhal: float, k_s: ArrayLike) -> FloatArray:
    """Skop-Griffin response parameter ``S_G = 2 pi S_T^2 k_s``.

    Tuah (1982) eq. 3.2.b.6.
    """
    return 2.0 * math.pi * strouhal**2 * np.asarray(k_s, float)


@dataclass(frozen=True)
class WakeParameters:
    """Empirical wake-oscillator parameters per element (Tuah (1982) eq. 3.2.b.5-3.2.b.6).

    Attributes
    ----------
    G, H, F
        Negative-damping, frequency-shift and coupling parameters of eq. 3.2.b.3.
    S_G
        Skop-Griffin response parameter ``2 pi S_T^2 k_s``.
    k_s
        Reduced damping ``45 (nu / w_s)^(1/2) / D``.
    xi
        Damping ratio ``k_s rho D^2 / (4 pi m)``.
    h
        The source's dummy variable, ``10^(-0.24 + 0.66 S_G) / S_G^2``.
    """

    G: FloatArray
    H: FloatArray
    F: FloatArray
    S_G: FloatArray
    k_s: FloatArray
    xi: FloatArray
    h: FloatArray


def wake_parameters(omega_s: ArrayLike, diameter: ArrayLike, mass_per_length: ArrayLike,
                    rho: float, viscosity: float,
                    strouhal: float = DEFAULT_STROUHAL) -> WakeParameters:
    """``G``, ``H``, ``F`` from the Skop-Griffin parameter.

    Tuah (1982) eq. 3.2.b.5-3.2.b.6 (see the module docstring for the reading of the OCR)::

        k_s = 45 (nu / w_s)^(1/2) / D,   S_G = 2 pi S_T^2 k_s,   xi = k_s rho D^2 / (4 pi m),
        log10 G = 0.25 - 0.21 S_G,   log10 (h S_G^2) = -0.24 + 0.66 S_G,
        H = xi h,   F = 4 G S_G / h.

    Parameters
    ----------
    omega_s
        Shedding frequency per element [rad/time] (positive).
    diameter
        Diameter per element [length].
    mass_per_length
        Structural plus added mass per unit length ``m`` [mass/length].
    rho
        Fluid density [mass/length^3].
    viscosity
        Kinematic viscosity ``nu`` [length^2/time].
    strouhal
        Strouhal number ``S_T``.
    """
    d = np.asarray(diameter, float)
    k_s = reduced_damping(omega_s, d, viscosity)
    s_g = skop_griffin_parameter(strouhal, k_s)
    xi = k_s * rho * d**2 / (4.0 * math.pi * np.asarray(mass_per_length, float))
    G = 10.0 ** (0.25 - 0.21 * s_g)
    h = 10.0 ** (-0.24 + 0.66 * s_g) / s_g**2
    return WakeParameters(G=G, H=xi * h, F=4.0 * G * s_g / h, S_G=s_g, k_s=k_s, xi=xi, h=h)


def modal_damping_ratio(omega_n: ArrayLike, diameter: ArrayLike, mass_per_length: ArrayLike,
                        rho: float, viscosity: float) -> FloatArray:
    """Viscous fluid damping ratio of a mode, ``xi_n = 12 rho D / (pi m) (nu / w_n)^(1/2)``.

    Tuah (1982) eq. 3.2.b.8; ``m`` is the structural plus added mass per unit length.

    Parameters
    ----------
    omega_n
        Natural frequency [rad/time] (positive).
    diameter, mass_per_length
        ``D`` and ``m`` (scalars or broadcastable).
    rho, viscosity
        Fluid density and kinematic viscosity.
    """
    return (12.0 * rho * np.asarray(diameter, float)
            / (math.pi * np.asarray(mass_per_length, float))
            * np.sqrt(viscosity / np.asarray(omega_n, float)))


def wake_acceleration(CL: ArrayLike, CL_rate: ArrayLike, omega_s: ArrayLike, G: ArrayLike,
                      H: ArrayLike, F: ArrayLike, CL0: float, transverse_velocity: ArrayLike,
                      diameter: ArrayLike) -> FloatArray:
    """``C_L''`` from the wake oscillator.

    Tuah (1982) eq. 3.2.b.3 (with ``C_L0^2`` in the bracket)::

        C_L'' = -w_s^2 C_L + [C_L0^2 - C_L^2 - (C_L'/w_s)^2] (w_s G C_L' - w_s^2 H C_L)
                + w_s F U_T' / D.

    Parameters
    ----------
    CL, CL_rate
        Lift coefficient and its time derivative per element.
    omega_s
        Shedding frequency per element (positive where the oscillator is active).
    G, H, F
        Wake parameters (:func:`wake_parameters`).
    CL0
        Stationary-cylinder lift amplitude.
    transverse_velocity
        Strumming velocity of the element along its lift direction [length/time].
    diameter
        Diameter [length].
    """
    CL = np.asarray(CL, float)
    rate = np.asarray(CL_rate, float)
    w = np.asarray(omega_s, float)
    bracket = CL0**2 - CL**2 - (rate / w) ** 2
    return (-w**2 * CL + bracket * (w * G * rate - w**2 * H * CL)
            + w * F * np.asarray(transverse_velocity, float) / np.asarray(diameter, float))


def relative_normal_velocity(x: FloatArray, v: FloatArray, fluid_velocity_mid: ArrayLike,
                             elements: NDArray[np.int64]) -> tuple[FloatArray, FloatArray]:
    """Relative normal fluid velocity ``V_NR`` and unit tangent ``theta`` of every element.

    Tuah (1982) eq. 3.2.a.3: ``u = u_fluid(mid) - (v1 + v2) / 2``, ``V_NR = u - (u . t) t``
    with ``t`` the chord direction.

    Returns
    -------
    V_NR, tangent
        Both (n_elements, 3).
    """
    elements = np.asarray(elements)
    chord = x[elements[:, 1]] - x[elements[:, 0]]
    length = np.maximum(np.linalg.norm(chord, axis=1), np.finfo(float).tiny)
    t = chord / length[:, None]
    u = (np.broadcast_to(np.asarray(fluid_velocity_mid, float), (len(elements), 3))
         - 0.5 * (v[elements[:, 0]] + v[elements[:, 1]]))
    return u - np.einsum("ij,ij->i", u, t)[:, None] * t, t


def lift_direction(tangent: FloatArray, normal_velocity: FloatArray) -> FloatArray:
    """Unit lift direction ``theta x V_NR / |V_NR|`` per element (zero where ``V_NR = 0``).

    Tuah (1982) eq. 3.2.b.1-3.2.b.2: perpendicular to the element and to the relative
    velocity.
    """
    cross = np.cross(tangent, normal_velocity)
    norm = np.linalg.norm(cross, axis=1)
    return np.divide(cross, norm[:, None], out=np.zeros_like(cross), where=norm[:, None] > 0)


def lift_force_per_length(CL: ArrayLike, normal_speed: ArrayLike, diameter: ArrayLike,
                          rho: float) -> FloatArray:
    """Signed lift force per unit length along the lift direction,
    ``1/2 rho D C_L |V_NR|^2``.

    Tuah (1982) eq. 3.2.b.1.
    """
    speed = np.asarray(normal_speed, float)
    return 0.5 * rho * np.asarray(diameter, float) * np.asarray(CL, float) * speed**2


def lift_forces(CL: ArrayLike, x: FloatArray, v: FloatArray, fluid_velocity_mid: ArrayLike,
                elements: NDArray[np.int64], length0: ArrayLike, diameter: ArrayLike,
                rho: float) -> FloatArray:
    """Lift on the two nodes of every element, half of the element's total to each.

    Tuah (1982) eq. 3.2.b.1: per unit (unstretched, as the Morison loads of
    :mod:`moorline.physics.hydro`) length ``1/2 rho D C_L |V_NR| (theta x V_NR)``.

    Returns
    -------
    FloatArray
        (n_elements, 2, 3).
    """
    v_nr, t = relative_normal_velocity(x, v, fluid_velocity_mid, elements)
    speed = np.linalg.norm(v_nr, axis=1)
    total = lift_force_per_length(CL, speed, diameter, rho) * np.asarray(length0, float)
    f = 0.5 * total[:, None] * lift_direction(t, v_nr)
    return np.stack((f, f), axis=1)
