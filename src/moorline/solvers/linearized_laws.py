"""Which laws the linearized analyses (modal, strumming, stochastic, harmonic balance) can
take: the ``static_dynamic`` rope (:mod:`moorline.physics.static_dynamic`, MoorDyn's mean-load
dependent viscoelastic model) and the ``syrope`` rope (:mod:`moorline.physics.syrope`) are
modelled in statics and the time domain only, the sag-corrected element
(:mod:`moorline.physics.sag`) in those and the modal analysis. A case file refuses such an
analysis at load; this guard refuses the same call
made through the Python API, instead of silently linearizing with another law."""

from __future__ import annotations

from ..errors import CaseError
from ..model import System


def refuse_unlinearized(system: System, analysis: str) -> None:
    """Raise a :class:`~moorline.errors.CaseError` naming the ``static_dynamic`` or ``syrope``
    line types or the sag-corrected lines of ``system`` for an ``analysis`` that would
    linearize them."""
    for kind, what in (("static_dynamic", "mean-load dependent viscoelastic model"),
                       ("syrope", "Syrope rope with load-history dependent working curves")):
        names = [n for n, lt in system.line_types.items() if lt.material == kind]
        if names:
            raise CaseError(f"line type {', '.join(names)} is a {kind} rope (MoorDyn's {what}), "
                            "modelled in statics and the time domain only: no "
                            f"{analysis} analysis (not linearized)",
                            field=f"line_types.{names[0]}.material")
    sagging = [n for n, line in system.lines.items() if line.element == "sag_corrected"]
    if sagging and analysis != "modal":  # modal: the symmetric part of the tangent
        raise CaseError(sag_refusal(", ".join(sagging), analysis),
                        field=f"lines.{sagging[0]}.element")


def sag_refusal(lines: str, analysis: str) -> str:
    """The message refusing an ``analysis`` of sag-corrected ``lines``."""
    return (f"line {lines} has sag-corrected elements (element: sag_corrected), modelled in "
            f"statics, modal analysis and the time domain only: no {analysis} analysis (not "
            "linearized; use element: straight)")
