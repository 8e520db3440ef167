"""MoorDyn line types with a viscoelastic ``EA``: ``EA_s|EA_d`` or ``EA_s|EA_Dc|EA_D_Lm`` with
``BA_s[|BA_d]`` (MoorDyn-C v2.7.1 ``source/MoorDyn2.cpp`` ``readLineProps``; ``docs/inputs.rst``,
"Line Types"); the Syrope model's ``SYROPE:file|EA_Dc|EA_D_Lm`` is
:mod:`moorline.io.moordyn_syrope`.

* ``EA_s|EA_d`` (constant dynamic stiffness) is a standard linear solid plus a dashpot
  (:func:`moorline.physics.static_dynamic.sls_parameters`): ``material: viscoelastic`` with
  ``EA = EA_s`` and the exact ``EA1``, ``tau`` and ``BA``. With a damping ratio ``BA_s < 0``
  (which MoorDyn turns into a coefficient per line from its segment length) it is the
  ``static_dynamic`` material with ``EAd_Lm = 0`` instead, which resolves the ratio per element.
* ``EA_s|EA_Dc|EA_D_Lm`` is ``material: static_dynamic`` (:mod:`moorline.physics.static_dynamic`)
  with ``EA = EA_s``, ``EAd = EA_Dc``, ``EAd_Lm = EA_D_Lm``, ``BA = BA_s``, ``BA_dynamic = BA_d``.
* ``BA_d`` missing is 0, as in MoorDyn; a negative ``BA_d`` is refused, as MoorDyn does.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from ..physics.static_dynamic import sls_parameters


def viscoelastic_line_type(ea: str, ba: str, fail: Callable[[str], Exception]
                           ) -> dict[str, Any] | None:
    """The :class:`~moorline.model.LineType` fields of a viscoelastic ``EA``/``BA`` pair, or
    ``None`` when ``ea`` has no ``|`` (an elastic line type).

    Parameters
    ----------
    ea, ba
        The deck's ``EA`` and ``BA/-zeta`` tokens.
    fail
        Builds the error to raise from a reason (the reader's, naming file, line and section).
    """
    if "|" not in ea:
        if "|" in ba:
            raise fail(f"BA/-zeta {ba!r} has more |-separated values than EA {ea!r} "
                       "(MoorDyn refuses it too)")
        return None
    parts = ea.split("|")
    if len(parts) > 3:
        raise fail(f"EA {ea!r}: at most 3 |-separated values (EA_s|EA_d or "
                   "EA_s|EA_Dc|EA_D_Lm)")
    values = [_number(p, f"EA {ea!r}", fail) for p in parts]
    damping = ba.split("|")
    if len(damping) > 2:
        raise fail(f"BA/-zeta {ba!r}: at most 2 |-separated values (BA_s|BA_d)")
    BA_s, BA_d = (_number(d, f"BA/-zeta {ba!r}", fail) for d in (*damping, "0")[:2])
    EA_s, EA_d = values[0], values[1]
    if EA_s <= 0 or EA_d <= EA_s:
        raise fail(f"EA {ea!r}: the viscoelastic model needs 0 < EA_s < EA_d (the dynamic "
                   f"stiffness {'at zero load ' if len(values) == 3 else ''}above the static)")
    if BA_d < 0:
        raise fail(f"BA/-zeta {ba!r}: the dynamic damping BA_d cannot be a ratio (< 0)")
    if BA_s == 0 and BA_d == 0:
        raise fail(f"BA/-zeta {ba!r}: the viscoelastic model needs BA_s or BA_d > 0 "
                   "(MoorDyn divides by BA_s + BA_d)")
    slope = values[2] if len(values) == 3 else 0.0
    if slope < 0:
        raise fail(f"EA {ea!r}: the slope EA_D_Lm must not be negative")
    if len(values) == 2 and BA_s >= 0:
        EA1, tau, eta = sls_parameters(EA_s, EA_d, BA_s, BA_d)
        return {"EA": EA_s, "material": "viscoelastic", "EA1": EA1, "tau": tau, "BA": eta}
    return {"EA": EA_s, "material": "static_dynamic", "EAd": EA_d, "EAd_Lm": slope, "BA": BA_s,
            "BA_dynamic": BA_d}


def _number(token: str, what: str, fail: Callable[[str], Exception]) -> float:
    try:
        value = float(token)
    except ValueError:
        raise fail(f"{what}: {token!r} is not a number (tables are not supported in "
                   "viscoelastic pairs)") from None
    if value != value or value in (float("inf"), float("-inf")):
        raise fail(f"{what}: {token!r} is not a finite number")
    return value
