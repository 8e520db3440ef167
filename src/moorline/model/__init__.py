"""Plain, frozen descriptions of a cable problem. Imports nothing else of moorline."""

from .analysis import OutputSettings, StaticMethod, StaticsSettings
from .components import Line, LineType, Point, PointKind
from .environment import Current, Environment, Seabed, Waves
from .system import System, UnitSystem

__all__ = [
    "Current",
    "Environment",
    "Line",
    "LineType",
    "OutputSettings",
    "Point",
    "PointKind",
    "Seabed",
    "StaticMethod",
    "StaticsSettings",
    "System",
    "UnitSystem",
    "Waves",
]
