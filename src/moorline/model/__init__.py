"""Plain, frozen descriptions of a cable problem. Imports nothing else of moorline."""

from .analysis import (
    DynamicScheme,
    DynamicsSettings,
    DynamicVariant,
    ExtremesSettings,
    FatigueSettings,
    HarmonicSettings,
    ModalMass,
    ModalSettings,
    OffsetSettings,
    OutputSettings,
    StaticMethod,
    StaticsSettings,
    StochasticSettings,
    StrummingAnalysis,
    StrummingSettings,
)
from .body import Body, Hydrostatics, RadiationTable, WaveExcitation
from .components import Line, LineType, Motion, Point, PointKind
from .design import DesignSettings
from .environment import Bathymetry, Current, Environment, Seabed, SeaComponents, Waves
from .system import System, UnitSystem

__all__ = [
    "Body",
    "DesignSettings",
    "Hydrostatics",
    "DynamicScheme",
    "DynamicVariant",
    "DynamicsSettings",
    "ExtremesSettings",
    "FatigueSettings",
    "Motion",
    "Current",
    "Environment",
    "Line",
    "LineType",
    "ModalMass",
    "ModalSettings",
    "OffsetSettings",
    "OutputSettings",
    "Point",
    "PointKind",
    "SeaComponents",
    "Seabed",
    "Bathymetry",
    "StaticMethod",
    "StaticsSettings",
    "HarmonicSettings",
    "StochasticSettings",
    "StrummingAnalysis",
    "StrummingSettings",
    "System",
    "UnitSystem",
    "RadiationTable",
    "WaveExcitation",
    "Waves",
]
