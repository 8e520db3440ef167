"""End forces of lines on the seabed against the closed-form catenary (issue 10): the finite
elements report the closed form's anchor force (``V_a = 0`` where the line lies), and lying
nodes start where the penalty seabed carries them."""

from __future__ import annotations

import dataclasses

import numpy as np
from scipy.optimize import brentq

from moorline.catenary import solve_catenary
from moorline.physics import seabed
from moorline.solvers.statics import solve_statics
from moorline.verification.oc3_line import (
    ANCHOR_R,
    DEPTH,
    EA,
    FAIR_R,
    FAIR_Z,
    SUBMERGED_WEIGHT,
    closed_form,
    oc3_system,
)

W = SUBMERGED_WEIGHT
X, Z = ANCHOR_R - FAIR_R, FAIR_Z + DEPTH


def test_oc3_anchor_force_is_the_closed_forms_within_a_thousandth() -> None:
    """OC3 line, 100 elements: the anchor force (H_a, 0, 0) of the closed form, the vertical
    part included (it was -15.8 kN: the half element's weight and the pull of the sunk lying
    nodes, which the seabed carries)."""
    exact = closed_form()
    anchor = solve_statics(oc3_system(100)).end_force("line1", "a")
    assert np.linalg.norm(anchor - [exact.H_a, 0.0, 0.0]) <= 1e-3 * exact.tension_a


def test_a_line_tangent_to_the_seabed_at_its_anchor_does_not_pull_it_down_or_up() -> None:
    """The OC3 geometry with the length at which the touchdown reaches the anchor (V_a = 0 of
    the closed form without contact): anchor Fz within 0.1 % of the anchor tension."""
    length = brentq(lambda L: solve_catenary(X, Z, L, EA, W, seabed_contact=False).V_a,
                    np.hypot(X, Z) * 1.0001, 902.2, xtol=1e-9)
    exact = solve_catenary(X, Z, length, EA, W)
    system = oc3_system(100)
    system = dataclasses.replace(system, lines={
        "line1": dataclasses.replace(system.lines["line1"], length=length)})
    anchor = solve_statics(system).end_force("line1", "a")
    assert abs(anchor[2]) <= 1e-3 * exact.tension_a
    assert abs(anchor[0] - exact.H_a) <= 1e-3 * exact.tension_a


def test_resting_penetration_inverts_the_contact_spring() -> None:
    """contact_force at the resting penetration carries the load, on both branches of the
    spring (below and beyond the blend-in ramp)."""
    k = np.array([1e4, 1e4, 3e6, 0.0])
    ramp = np.array([0.02, 0.02, 0.01, 0.01])
    load = np.array([10.0, 500.0, 2e3, 5.0])  # 10 N: inside the band (k ramp / 2 = 100 N)
    p = seabed.resting_penetration(load, k, ramp)
    zero = np.zeros(4)
    force = seabed.contact_force(-p, zero, k, zero, ramp)[0]
    assert np.allclose(force[:3], load[:3], rtol=1e-12)
    assert p[0] < ramp[0] / 2 < p[1] and p[3] == 0.0
