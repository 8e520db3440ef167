"""When the compiled time step (:mod:`moorline.solvers.fast_newmark`) can run a model.

Kept apart from the compiled step so that deciding does not import numba: a model the
compiled step cannot run (bodies, viscoelastic lines, waves...) takes the general stepper
without loading it.
"""

from __future__ import annotations

import numpy as np

__all__ = ["fast_path_reason"]


def fast_path_reason(model, fluid, scheme: str, variant: str, bodies: bool = False,
                     rayleigh: bool = False) -> str | None:
    """Why the compiled step cannot run this model (None when it can)."""
    from ..waves import CurrentProfile, StillWater

    if bodies:
        return "rigid bodies"
    if rayleigh:
        return "Rayleigh damping"
    if model._fused is None:
        return "viscoelastic lines, slack_damping, drag_velocity node or the numpy kernel"
    if model.mesh.has_bending:
        return "bending stiffness (EI)"
    if scheme != "newmark" or variant != "iterative":
        return f"scheme {scheme!r} / variant {variant!r}"
    if model.has_point_hydro:
        return "points with their own drag or added mass"
    if model.friction is not None and model.friction[0] != model.friction[1]:
        return "anisotropic seabed friction"
    if model.mesh.bathymetry is not None:
        return "a sloped or gridded seabed"
    if isinstance(fluid, StillWater):
        return None
    if isinstance(fluid, CurrentProfile) and len(set(np.atleast_1d(fluid.speeds))) == 1 \
            and len(set(np.atleast_1d(fluid.headings_deg))) == 1:
        return None
    return "waves or a sheared current"
