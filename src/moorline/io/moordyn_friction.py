"""A MoorDyn deck's seabed-friction options as moorline's seabed friction, for
:func:`moorline.io.moordyn.read_moordyn_deck`.

MoorDyn's law, per seabed node (MoorDyn-F: OpenFAST ``modules/moordyn/src/MoorDyn_Line.f90``,
options ``MU_KT``, ``MU_KA``, ``MC``, ``CV`` (alias ``FricDamp``), defaults 0, 0, 1, 200;
MoorDyn-C v2.7 ``source/Line.cpp``, options ``FrictionCoefficient`` for both directions,
``FricDamp``, ``StatDynFricScale``, defaults 0, 200, 1): on the node's velocity ``v`` along
(axial) and across (transverse) the line, ``F = -mu CV v`` while ``mu CV |v| <= MC mu N``,
else ``-mu N v / |v|`` (``N`` the node's seabed contact force). moorline's law
(:func:`moorline.physics.seabed.friction_force`) is ``mu N tanh(|v| / v_s)``, the same
kinetic level ``mu N`` and, with ``v_s = N / CV``, the same slope at rest. ``N`` differs from
node to node; the slip velocity taken is that of a resting node, ``v_s = w l_seg / CV`` (``w``
the line's wet weight per length, ``l_seg`` its segment length), the median over the deck's
lines (a warning gives the range when they differ by more than 10 %).

Mapping: ``MU_KT`` -> ``seabed.friction_transverse``, ``MU_KA`` -> ``seabed.friction_axial``
and ``seabed.friction`` (the statics' and the closed-form catenary's friction of a lying
line, which is axial) unless ``FrictionCoefficient`` gives it; ``CV``/``FricDamp`` ->
``seabed.slip_velocity`` as above (only when the deck gives it: with MoorDyn's default 200
N s/m the linear branch reaches ``mu N`` only at ``N / 200`` m/s, tens of m/s on chain, so
MoorDyn's friction is then viscous; moorline keeps its 0.01 m/s). ``MC``/``StatDynFricScale``
other than 1 (a static peak above the kinetic level) has no counterpart: a warning.
"""

from __future__ import annotations

import math
import statistics
from collections.abc import Callable, Mapping
from dataclasses import replace

from ..errors import CaseError
from ..model import Line, LineType, Seabed

FRICTION_OPTIONS = {"mu_kt", "mu_ka", "mc", "cv", "fricdamp", "statdynfricscale"}


def _option(raw: Mapping[str, str], names: tuple[str, ...], file: str) -> float | None:
    for key, value in raw.items():
        if key.lower() in names:
            try:
                number = float(value)
            except ValueError:
                raise CaseError(f"option {key} must be a number, got {value!r}", file=file,
                                field="OPTIONS") from None
            if not math.isfinite(number) or number < 0:
                raise CaseError(f"option {key} must be a finite number >= 0, got {value!r}",
                                file=file, field="OPTIONS")
            return number
    return None


def deck_friction(raw: Mapping[str, str], seabed: Seabed, lines: Mapping[str, Line],
                  types: Mapping[str, LineType], rho: float, g: float, file: str,
                  warn: Callable[[str], None]) -> Seabed:
    """``seabed`` with the deck's friction options (module docstring); unchanged without
    them."""
    mu_t = _option(raw, ("mu_kt",), file)
    mu_a = _option(raw, ("mu_ka",), file)
    cv = _option(raw, ("cv", "fricdamp"), file)
    mc = _option(raw, ("mc", "statdynfricscale"), file)
    given = "frictioncoefficient" in {k.lower() for k in raw}
    if mu_t is not None:
        seabed = replace(seabed, friction_transverse=mu_t)
    if mu_a is not None:
        seabed = replace(seabed, friction_axial=mu_a,
                         **({} if given else {"friction": mu_a}))
    mus = [m for m in (seabed.friction, seabed.friction_axial, seabed.friction_transverse)
           if m]
    if not mus:
        return seabed
    if mc is not None and mc != 1.0:
        warn(f"seabed friction: static/kinetic ratio MC (StatDynFricScale) = {mc:g} has no "
             "counterpart (moorline's friction has no static peak): kinetic coefficients used")
    if cv is not None:
        if cv == 0:
            raise CaseError("option CV (FricDamp) = 0: the friction law's slope must be "
                            "positive", file=file, field="OPTIONS")
        slips = []
        for line in lines.values():
            lt = types[line.line_type]
            w = (lt.mass_per_length - rho * math.pi * lt.diameter**2 / 4.0) * g
            if w > 0:
                slips.append(w * line.length / line.segments / cv)
        if slips:
            slip = statistics.median(slips)
            seabed = replace(seabed, slip_velocity=slip)
            note = (f" (the lines' resting nodes give {min(slips):.3g} to {max(slips):.3g})"
                    if max(slips) > 1.1 * min(slips) else "")
            warn(f"seabed friction: CV (FricDamp) = {cv:g} N s/m taken as the slip velocity "
                 f"{slip:.3g} m/s, a resting node's weight over CV{note}")
    return seabed
