"""The whole cable system: environment, line types, points, lines and analyses."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Literal, TypeVar, overload

from .analysis import DynamicsSettings, OutputSettings, StaticsSettings
from .body import Body
from .components import Line, LineType, Point
from .design import DesignSettings
from .environment import Environment

UnitSystem = Literal["SI", "US"]
S = TypeVar("S")


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
    design: DesignSettings | None = None

    @overload
    def first(self, kind: type[S]) -> S: ...

    @overload
    def first(self, kind: str) -> Any | None: ...

    def first(self, kind: type[S] | str) -> S | Any | None:
        """The first analysis of a kind in :attr:`analyses`.

        Parameters
        ----------
        kind
            A settings class (e.g. :class:`~moorline.model.StaticsSettings`) or a kind name
            (``"statics"``).

        Returns
        -------
        The first matching settings; when there is none, the class's defaults (``kind()``)
        for a class, ``None`` for a name.
        """
        if isinstance(kind, str):
            return next((a for a in self.analyses if getattr(a, "kind", None) == kind), None)
        return next((a for a in self.analyses if isinstance(a, kind)), None) or kind()
