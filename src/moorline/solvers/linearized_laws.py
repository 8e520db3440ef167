"""Which material laws the linearized analyses (modal, strumming, stochastic, harmonic
balance) can take: the ``static_dynamic`` rope (:mod:`moorline.physics.static_dynamic`,
MoorDyn's mean-load dependent viscoelastic model) and the ``syrope`` rope
(:mod:`moorline.physics.syrope`) are modelled in statics and the time domain
only. A case file refuses such an analysis at load; this guard refuses the same call made
through the Python API, instead of silently linearizing with the static stiffness."""

from __future__ import annotations

from ..errors import CaseError
from ..model import System


def refuse_static_dynamic(system: System, analysis: str) -> None:
    """Raise a :class:`~moorline.errors.CaseError` naming the ``static_dynamic`` (or
    ``syrope``) line types of ``system`` for an ``analysis`` that would linearize them."""
    for kind, what in (("static_dynamic", "mean-load dependent viscoelastic model"),
                       ("syrope", "Syrope rope with load-history dependent working curves")):
        names = [n for n, lt in system.line_types.items() if lt.material == kind]
        if names:
            raise CaseError(f"line type {', '.join(names)} is a {kind} rope (MoorDyn's {what}), "
                            "modelled in statics and the time domain only: no "
                            f"{analysis} analysis (not linearized)",
                            field=f"line_types.{names[0]}.material")
