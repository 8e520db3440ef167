"""Dynamics on an inclined seabed (issue 14, deliverable 3): a free line lying along the fall
line of a 10 deg plane slides down it. Without friction every node accelerates at
``w sin(a) / m`` along the slope (the seabed's push is normal to the plane; no drag, no axial
added mass), ``s = a t^2 / 2``, which the average-acceleration Newmark step integrates
exactly. With the regularized Coulomb friction ``mu N tanh(v / v_s)`` and ``mu > tan(a)``
the line creeps at the speed where friction balances the slope, ``v = v_s atanh(tan(a) /
mu)`` (N = w cos(a) per length), reached within milliseconds (time constant
``m v_s / (mu N)``)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from moorline.io import load_case_text
from moorline.mesh import discretize
from moorline.model.analysis import DynamicsSettings
from moorline.solvers.dynamics import simulate

RHO, G, D, MASS = 1025.0, 9.80665, 0.1, 60.0
W = (MASS - RHO * math.pi * D**2 / 4) * G
SLOPE, HEADING, DEPTH, L = 10.0, 45.0, 100.0, 50.0


def _system(friction: float):
    t, h = math.tan(math.radians(SLOPE)), math.radians(HEADING)
    down = np.array([math.cos(h), math.sin(h)])
    ends = [np.array([*(r * down), -DEPTH - t * r]) for r in (0.0, L * math.cos(math.radians(
        SLOPE)))]
    text = f"""
name: sliding
units: SI
environment: {{depth: {DEPTH}, water_density: {RHO}, gravity: {G},
              seabed: {{stiffness: 3.0e6, damping: 3.0e5, friction: {friction},
                        slip_velocity: 0.01, slope: {SLOPE}, slope_heading: {HEADING}}}}}
line_types:
  rope: {{diameter: {D}, mass_per_length: {MASS}, EA: 1.0e8, Cd: 0, Ct: 0, Ca: 0, Cat: 0}}
points:
  a: {{kind: fixed, position: {ends[0].tolist()}}}
  b: {{kind: fixed, position: {ends[1].tolist()}}}
lines:
  l1: {{type: rope, length: {L}, segments: 10, end_a: a, end_b: b}}
analyses: [{{kind: statics}}]
"""
    system = load_case_text(text)
    # both ends free: a case file refuses a system without a held point (statics would be
    # singular); the dynamics of a free line is well posed
    system = dataclasses.replace(system, points={
        name: dataclasses.replace(p, kind="free") for name, p in system.points.items()})
    mesh = discretize(system)
    x0 = mesh.node_position.copy()
    fall = np.array([math.cos(math.radians(SLOPE)) * down[0],
                     math.cos(math.radians(SLOPE)) * down[1], -math.sin(math.radians(SLOPE))])
    return system, x0, fall


def _mean(values: np.ndarray) -> np.ndarray:
    """Mass-weighted mean over the nodes (last axis): the line's centre of mass, which the
    line's own tension does not move (the elastic law's smoothing band pulls a line at zero
    strain with ``EA s / 4``, so the nodes oscillate about it)."""
    tributary = np.full(values.shape[-1], L / 10)
    tributary[:2] = L / 20  # the two end points
    return values @ tributary / tributary.sum()


def test_a_frictionless_line_slides_down_the_slope_at_w_sin_over_m() -> None:
    system, x0, fall = _system(0.0)
    result = simulate(system, DynamicsSettings(duration=2.0, dt=0.02, tolerance=1e-9),
                      initial=x0)
    assert result.success, result.message
    a = W * math.sin(math.radians(SLOPE)) / MASS
    t = result.time
    moved = _mean(np.einsum("tnk,k->tn", result.positions - x0, fall))
    assert np.allclose(moved, 0.5 * a * t**2, rtol=0, atol=1e-6 * 0.5 * a * t[-1]**2)
    speed = _mean(np.einsum("tnk,k->tn", result.velocities, fall))
    assert np.allclose(speed, a * t, rtol=0, atol=1e-6 * a * t[-1])


def test_friction_above_the_slope_leaves_the_regularized_creep_speed() -> None:
    mu = 0.5
    system, x0, fall = _system(mu)
    result = simulate(system, DynamicsSettings(duration=1.0, dt=0.01, tolerance=1e-10),
                      initial=x0)
    assert result.success, result.message
    creep = 0.01 * math.atanh(math.tan(math.radians(SLOPE)) / mu)
    velocity = _mean(result.velocities[-1].T)  # (3,)
    assert velocity @ fall == pytest.approx(creep, rel=1e-4)
    # along the fall line (what is left, 3e-4 of it, is the nodes still settling into the
    # seabed across it: they start on the surface, not at their resting penetration)
    assert np.allclose(velocity - (velocity @ fall) * fall, 0.0, atol=1e-3 * creep)
