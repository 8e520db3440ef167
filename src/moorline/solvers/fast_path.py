"""When the compiled time step (:mod:`moorline.solvers.fast_newmark`) can run a model.

Kept apart from the compiled step so that deciding does not import numba: a model the
compiled step cannot run (fixed bodies, pins on bodies, MoorDyn's viscoelastic ropes,
bending...) takes the general stepper without loading it.
"""

from __future__ import annotations

import numpy as np

__all__ = ["HULL_KINDS", "body_refusal", "fast_path_reason", "fluid_parts"]

HULL_KINDS = {"none": 0, "box": 1, "cylinder": 1, "matrix": 2, "rods": 3}
"""Hydrostatics the compiled step takes (:func:`moorline.solvers.fast_rigid.static_load`),
by its code there: 0 none, 1 a wall-sided hull (box or vertical cylinder), 2 a constant
stiffness matrix with a constant buoyancy, 3 rods (buoyancy of slender cylinders at each pose,
:func:`moorline.solvers.fast_rigid.rods_load`) with a constant buoyancy."""


def fast_path_reason(model, fluid, scheme: str, variant: str, bodies: bool = False,
                     rayleigh: bool = False) -> str | None:
    """Why the compiled step cannot run this model (None when it can). ``bodies``: the
    model's mesh has rigid bodies (:func:`body_refusal`)."""
    if bodies and (reason := body_refusal(model.mesh)) is not None:
        return reason
    parts = fluid_parts(fluid) if bodies else None
    if parts is not None and (parts[0] is not None or _sheared(parts[1])):
        # the compiled bodies' drag takes a fluid velocity that depends on time alone
        for body in model.mesh.bodies:
            if np.any(np.asarray(body.drag_area, dtype=float)):
                where = "waves" if parts[0] is not None else "a sheared current"
                return f"drag on body {body.name} in {where}"
    if rayleigh:
        return "Rayleigh damping"
    if model._fused is None:  # the numpy kernel, the incremental SLS update, MoorDyn's ropes
        return model.compiled_refusal
    if model.mesh.has_bending:
        return "bending stiffness (EI)"
    if scheme not in ("newmark", "hht") or variant != "iterative":
        return f"scheme {scheme!r} / variant {variant!r}"
    if model.has_point_hydro:
        return "points with their own drag or added mass"
    if model.mesh.bathymetry is not None:
        return "a sloped or gridded seabed"
    if fluid_parts(fluid) is None:
        return "a fluid field other than Airy waves and a current profile"
    return None


def _sheared(current) -> bool:
    """Whether a current profile's velocity changes over depth."""
    return current is not None and (len(set(current.speeds)) > 1
                                    or len(set(current.headings_deg)) > 1)


def fluid_parts(fluid):
    """``(waves, current)`` of a fluid field the compiled step takes (linear wave components
    and a current profile, uniform or sheared, each or both or neither), or None when it takes
    no such field."""
    from ..waves import AiryWave, CombinedField, CurrentProfile, StillWater, WaveComponents

    waves, current = fluid, None
    if isinstance(fluid, StillWater):
        return None, None
    if isinstance(fluid, CurrentProfile):
        waves, current = None, fluid
    elif isinstance(fluid, CombinedField):
        waves, current = fluid.wave, fluid.current
    if isinstance(waves, AiryWave):
        waves = waves.components
    if waves is not None and not isinstance(waves, WaveComponents):
        return None
    if current is not None and not isinstance(current, CurrentProfile):
        return None
    return waves, current


def body_refusal(mesh) -> str | None:
    """Why the compiled step cannot run the bodies of ``mesh`` (None when it can): it takes
    free bodies and bodies pinned in space with weight, constant loads and force histories,
    constant added mass and damping or a radiation table (Cummins memory), hydrostatics of
    :data:`HULL_KINDS`, exciting-force tables and drag (in still water or a uniform current:
    :func:`fast_path_reason` refuses it in waves) (:mod:`moorline.solvers.fast_bodies`)."""
    for body in mesh.bodies:
        name = body.name
        if body.kind not in ("free", "pinned"):
            return f"a {body.kind} body ({name})"
        if getattr(body, "pin_body", None) is not None:
            return f"a pinned body on another body ({name})"
        if body.hydrostatics.kind not in HULL_KINDS:
            return f"{body.hydrostatics.kind} hydrostatics on body {name}"
        if body.wave_loads:
            return f"long-wave loads on body {name}"
    return None
