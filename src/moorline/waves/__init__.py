"""Fluid kinematics for cable dynamics: linear waves, currents and their combination.

Everything here implements :class:`FluidField`:
``kinematics(points (n, 3), t) -> velocity (n, 3), acceleration (n, 3), elevation (n,)``.
"""

from .airy import AiryWave, WaveComponents, ramp_factor, superpose
from .current import CurrentProfile
from .dispersion import omega_from_k, wave_number
from .field import (
    CombinedField,
    FluidField,
    StillWater,
    fluid_field_from_environment,
    random_sea,
    sea_components,
)
from .random import RandomSea
from .spectra import WaveSpectrum, jonswap, pierson_moskowitz

__all__ = [
    "AiryWave",
    "CombinedField",
    "CurrentProfile",
    "FluidField",
    "RandomSea",
    "StillWater",
    "WaveComponents",
    "WaveSpectrum",
    "fluid_field_from_environment",
    "jonswap",
    "omega_from_k",
    "pierson_moskowitz",
    "random_sea",
    "ramp_factor",
    "sea_components",
    "superpose",
    "wave_number",
]
