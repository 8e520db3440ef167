"""Plain, frozen descriptions of a cable problem. Imports nothing else of moorline."""

from .analysis import (
    DynamicScheme,
    DynamicsSettings,
    DynamicVariant,
    OutputSettings,
    StaticMethod,
    StaticsSettings,
)
from .components import Line, LineType, Motion, Point, PointKind
from .environment import Current, Environment, Seabed, Waves
from .system import System, UnitSystem

__all__ = [
    "DynamicScheme",
    "DynamicVariant",
    "DynamicsSettings",
    "Motion",
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
