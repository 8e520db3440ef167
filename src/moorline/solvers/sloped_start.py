"""Starting shape of a line with its anchor on a sloped or gridded seabed.

The closed-form catenary (:mod:`moorline.catenary`) has a flat seabed. Laying its horizontal
lying part vertically onto a slope stretches it by ``1 / cos(slope)`` (0.14 % at 3 deg: some
700 kN in a chain) and leaves Newton without a usable start. Here the line is split instead
at a touchdown point ``P`` reached after an unstretched length ``L_b`` lying along the seabed
from the anchor, in the vertical plane through the anchor and the other end; the rest
hangs from ``P`` as the free elastic catenary of length ``L - L_b`` to the other end.
``L_b`` is the root of

    f(L_b) = V_P / H_P - dh/dr (P),

the hanging part leaving ``P`` tangent to the seabed (no point force at the touchdown, as in
the closed form): a slack line (``f(0) < 0``: it would leave the anchor into the seabed) lays
more of itself down until it does. The lying part's stretch and the change of its tension
along a slope are left to Newton, which starts from nodes on the seabed and a hanging part
in its own balance. A taut line (``f(0) >= 0``, no lying part) gets ``None``: the caller's
catenary without contact applies.
"""

from __future__ import annotations

import logging

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import brentq

from ..catenary import CatenaryError, catenary_3d, profile_3d
from ..physics.bathymetry import SeabedSurface

FloatArray = NDArray[np.float64]
logger = logging.getLogger(__name__)

#: Samples of the seabed profile between the anchor and the other end.
PROFILE_SAMPLES = 801


def sloped_catenary_shape(surface: SeabedSurface, anchor: FloatArray, end: FloatArray,
                          s: FloatArray, length: float, EA: float, w: float
                          ) -> FloatArray | None:
    """Node positions (len(s), 3) at unstretched arc lengths ``s`` from ``anchor`` (on the
    seabed) of a line of ``length`` ending at ``end`` (module docstring); ``None`` when the
    line has no lying part or no such shape exists."""
    d = end[:2] - anchor[:2]
    span = float(np.hypot(*d))
    if span <= 1e-9 * length or w <= 0:
        return None
    u = d / span
    r = np.linspace(0.0, span, PROFILE_SAMPLES)
    path = anchor[:2] + r[:, None] * u
    z = surface.height(path)
    arc = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(r), np.diff(z)))])

    def touchdown(lying: float) -> tuple[FloatArray, float]:
        rr = float(np.interp(lying, arc, r))
        xy = anchor[:2] + rr * u
        point = np.array([*xy, surface.height(xy[None])[0]])
        gradient = surface.evaluate(xy[None])[1][0]
        return point, float(gradient @ u)

    def mismatch(lying: float) -> float:
        point, slope = touchdown(lying)
        try:
            fa, _, _ = catenary_3d(point, end, length - lying, EA, w, seabed_contact=False)
        except CatenaryError:
            return np.inf  # too short to reach: taut
        horizontal = float(np.hypot(fa[0], fa[1]))
        if horizontal <= 1e-12 * abs(fa[2]):  # hanging vertically from P
            return float(np.copysign(np.inf, fa[2]))
        return float(fa[2]) / horizontal - slope

    if mismatch(0.0) >= 0.0:
        return None
    top = min(length, float(arc[-1]))
    trials = np.linspace(0.0, top, 65)[1:]
    values = [mismatch(t) for t in trials]
    above = next((k for k, v in enumerate(values) if v >= 0.0), None)
    if above is None:
        logger.info("sloped seabed start: no touchdown found along the seabed")
        return None
    low = 0.0 if above == 0 else float(trials[above - 1])
    high = float(trials[above])
    lying = brentq(lambda t: min(mismatch(t), 1e6), low, high, xtol=1e-9 * length) \
        if np.isfinite(values[above]) else high
    point, _ = touchdown(lying)
    try:
        _, _, sol = catenary_3d(point, end, length - lying, EA, w, seabed_contact=False)
    except CatenaryError:
        return None
    shape = np.empty((len(s), 3))
    on = s <= lying
    rr = np.interp(s[on], arc, r)
    shape[on, :2] = anchor[:2] + rr[:, None] * u
    shape[on, 2] = surface.height(shape[on])
    shape[~on] = profile_3d(sol, point, end, s[~on] - lying)
    return shape
