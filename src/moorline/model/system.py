"""The whole cable system: environment, line types, points, lines and analyses."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Literal

from .analysis import DynamicsSettings, OutputSettings, StaticsSettings
from .body import Body
from .components import Line, LineType, Point
from .environment import Environment

UnitSystem = Literal["SI", "US"]


@dataclass(frozen=True)
class System:
    """A complete problem description. Build it in Python or load it with
    :func:`moorline.io.load_case`.

    Mappings are keyed by the string ids used in case files; their order is kept.
    """

    name: str
    units: UnitSystem = "SI"
    environment: Environment = field(default_factory=Environment)
    line_types: dict[str, LineType] = field(default_factory=dict)
    points: dict[str, Point] = field(default_factory=dict)
    lines: dict[str, Line] = field(default_factory=dict)
    bodies: dict[str, Body] = field(default_factory=dict)
    analyses: tuple[StaticsSettings | DynamicsSettings, ...] = (StaticsSettings(),)
    output: OutputSettings = field(default_factory=OutputSettings)
    source: str | None = None
