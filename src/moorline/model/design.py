"""Settings of the design checks of line tensions (``design`` in a case file)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

Standard = Literal["API-RP-2SK", "DNV-OS-E301"]
Condition = Literal["intact", "damaged"]


@dataclass(frozen=True)
class DesignSettings:
    """The standard and condition of the design checks (:mod:`moorline.design`).

    Attributes
    ----------
    standard
        ``API-RP-2SK`` (safety factors) or ``DNV-OS-E301`` (partial safety factors).
    condition
        ``intact`` (DNV: ULS) or ``damaged`` (one line failed; DNV: ALS).
    analysis
        ``quasi-static`` or ``dynamic``; ``None``: quasi-static for statics, dynamic for
        dynamics and stochastic results.
    consequence_class
        DNV-OS-E301 consequence class (1 or 2).
    storm_duration
        Duration of the most probable maximum of stochastic results [time]; ``None``: the
        data file's 3 hours.
    """

    standard: Standard = "API-RP-2SK"
    condition: Condition = "intact"
    analysis: Literal["quasi-static", "dynamic"] | None = None
    consequence_class: int = 1
    storm_duration: float | None = None
