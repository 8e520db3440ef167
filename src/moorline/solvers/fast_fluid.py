"""Fluid kinematics at the element midpoints for the compiled step (numba): linear wave
components and a uniform current, the formulas of :class:`moorline.waves.WaveComponents`
(:mod:`moorline.waves.airy`: Airy kinematics, ``cosh k(z + h) / sinh kh`` written with
``expm1`` for large ``kh``, no or Wheeler stretching) and
:class:`moorline.waves.CombinedField`, one midpoint at a time. The time-dependent parts (the
phases ``phi - w t``, the ramps) are computed per sub-step in Python
(:meth:`moorline.solvers.fast_newmark.FastStepper.run_block`)."""

from __future__ import annotations

import math

import numpy as np

from ..jit import numba

_JIT = {"cache": True, "fastmath": False, "error_model": "numpy"}

DEEP = -36.0
"""``k z`` below which a wave component's depth factor ``exp(k z)`` (< 2.4e-16) is skipped."""

NEGLIGIBLE = math.exp(DEEP)
"""The depth factor of :data:`DEEP`."""


@numba.njit(**_JIT)
def fluid_at_midpoints(x, elements, j, fluid, uf, af):
    """Fluid velocity and acceleration at the element midpoints at sub-step ``j``: linear
    (Airy) wave components and a uniform current, as
    :meth:`moorline.waves.WaveComponents.kinematics` (no stretching: the values at
    ``min(z, 0)``, or Wheeler stretching; zero above the instantaneous surface ``eta``; below
    the seabed those at the seabed) plus :meth:`moorline.waves.CurrentProfile.ramped` (zero
    above ``eta``, as :class:`moorline.waves.CombinedField`; ``eta = 0`` without waves).

    ``fluid = (waves_on, coef, depth, wheeler, offset, wave_ramp, current_on, current,
    current_ramp)``: ``coef`` rows ``k, kx, ky, a, a w cos b, a w sin b, a w, a w^2 cos b,
    a w^2 sin b, a w^2, 1 - exp(-2 k h)`` per component (those of ``WaveComponents``),
    ``offset[j]`` the phases ``phi - w t`` at the sub-step's time, ``wave_ramp[j]`` and
    ``current_ramp[j]`` the ramp factors and their rates, ``current`` a uniform current's
    velocity, ``profile`` a sheared one's levels (rows: heights ascending, speeds, unwrapped
    headings [rad]; one column for a uniform current), evaluated at the midpoint's ``z`` as
    :meth:`moorline.waves.CurrentProfile.velocity`.

    Each component's phase and its cosine are computed once per midpoint (the elevation and
    the kinematics share them). A component whose depth factor ``exp(k z)`` is below
    :data:`NEGLIGIBLE` (``k z < -36``: a short wave at a deep midpoint) adds nothing at
    double precision relative to the surface values and is skipped; where ``2 k (z + h) >
    40`` the finite-depth factor ``expm1(-2 k (z + h))`` is -1 to double precision and is not
    evaluated (on the OC3 lines in a 319-component sea most midpoints are deep: the
    kinematics took ~95 % of the step).
    """
    (waves_on, coef, depth, wheeler, offset, wave_ramp, current_on, current,
     current_ramp, profile) = fluid
    sheared = profile.shape[1] > 1
    finite = math.isfinite(depth)
    r, dr = wave_ramp[j, 0], wave_ramp[j, 1]
    rc, drc = current_ramp[j, 0], current_ramp[j, 1]
    n_comp = coef.shape[1] if waves_on else 0
    phase = np.empty(n_comp)
    cosine = np.empty(n_comp)
    for e in range(elements.shape[0]):
        mx = 0.5 * (x[elements[e, 0], 0] + x[elements[e, 1], 0])
        my = 0.5 * (x[elements[e, 0], 1] + x[elements[e, 1], 1])
        z = 0.5 * (x[elements[e, 0], 2] + x[elements[e, 1], 2])
        u0 = u1 = u2 = a0 = a1 = a2 = 0.0
        eta = 0.0
        if waves_on:
            s = 0.0
            for i in range(n_comp):
                theta = mx * coef[1, i] + my * coef[2, i] + offset[j, i]
                phase[i] = theta
                cosine[i] = math.cos(theta)
                s += cosine[i] * coef[3, i]
            eta = r * s
            zc = max(z, -depth)
            if wheeler:
                ze = depth * (zc - eta) / (depth + eta) if finite else zc - eta
            else:
                ze = zc
            ze = min(ze, 0.0)
            for i in range(n_comp):
                k = coef[0, i]
                if ze * k < DEEP:
                    continue
                ct, st = cosine[i], math.sin(phase[i])
                ekz = math.exp(ze * k)
                if finite:
                    reach = -2.0 * k * (ze + depth)
                    em = math.expm1(reach) if reach > -40.0 else -1.0
                    cfac = ekz * (2.0 + em) / coef[10, i]
                    sfac = -ekz * em / coef[10, i]
                else:
                    cfac = sfac = ekz
                u0 += cfac * ct * coef[4, i]
                u1 += cfac * ct * coef[5, i]
                u2 += sfac * st * coef[6, i]
                a0 += cfac * st * coef[7, i]
                a1 += cfac * st * coef[8, i]
                a2 -= sfac * ct * coef[9, i]
            if dr != 0.0:
                a0, a1, a2 = r * a0 + dr * u0, r * a1 + dr * u1, r * a2 + dr * u2
            else:
                a0, a1, a2 = r * a0, r * a1, r * a2
            u0, u1, u2 = r * u0, r * u1, r * u2
        wet = z <= eta
        if current_on and wet:
            if sheared:
                c0, c1, c2 = _profile_velocity(profile, z)
            else:
                c0, c1, c2 = current[0], current[1], current[2]
            u0 += rc * c0
            u1 += rc * c1
            u2 += rc * c2
            a0 += drc * c0
            a1 += drc * c1
            a2 += drc * c2
        uf[e, 0] = u0 if wet else 0.0
        uf[e, 1] = u1 if wet else 0.0
        uf[e, 2] = u2 if wet else 0.0
        af[e, 0] = a0 if wet else 0.0
        af[e, 1] = a1 if wet else 0.0
        af[e, 2] = a2 if wet else 0.0


@numba.njit(**_JIT)
def _profile_velocity(profile, z):
    """A current profile's velocity at height ``z``: speed and heading interpolated linearly
    between the levels and held beyond the end ones (``numpy.interp``, the arithmetic of
    :meth:`moorline.waves.CurrentProfile.velocity`)."""
    zp = profile[0]
    n = zp.shape[0]
    if z <= zp[0]:
        speed, heading = profile[1, 0], profile[2, 0]
    elif z >= zp[n - 1]:
        speed, heading = profile[1, n - 1], profile[2, n - 1]
    else:
        i = 0
        while zp[i + 1] <= z:
            i += 1
        dz = zp[i + 1] - zp[i]
        speed = (profile[1, i + 1] - profile[1, i]) / dz * (z - zp[i]) + profile[1, i]
        heading = (profile[2, i + 1] - profile[2, i]) / dz * (z - zp[i]) + profile[2, i]
    return speed * math.cos(heading), speed * math.sin(heading), 0.0
