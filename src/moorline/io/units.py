"""Units of case files: the dimension table, the unit systems and string-with-unit parsing.

A plain number in a case file is in the case's unit system (``SI``: m, kg, s, N; ``US``: ft,
slug, s, lbf). Any scalar may instead be a string with its own unit (``"20 ft"``,
``"384.243 MN"``, ``"3e6 Pa/m"``), which is converted to the case's system with pint. Angles
are in degrees (``"1.5 rad"`` is converted).

pint (about 0.6 s to import, 0.1-0.3 s to build its registry) is loaded only when a string
with a unit is read or a default is converted to the US system: a case in plain SI numbers
never imports it. The registry caches its parsed definitions (pint's ``cache_folder``).

This module is the one place that knows, for every physical dimension a case-file field may
have, its unit in each system (:data:`DIMENSIONS`), and the defaults of dimensional
quantities, stated once as physical values (:data:`DEFAULTS`). Which field has which dimension
is declared next to the field, in :mod:`moorline.io.schema`, by naming a key of
:data:`DIMENSIONS`.
"""

from __future__ import annotations

import io
import math
import re
import tokenize
from dataclasses import dataclass
from functools import cache
from typing import TYPE_CHECKING, Any, Literal

if TYPE_CHECKING:
    import pint

__all__ = [
    "DEFAULTS",
    "DIMENSIONS",
    "MAX_EXPONENT",
    "MAX_TEXT",
    "registry",
    "Dimension",
    "UnitParseError",
    "default_value",
    "to_system",
    "unit_of",
]

System = Literal["SI", "US"]



@cache
def registry() -> pint.UnitRegistry:
    """The unit registry of moorline (pint's defaults plus ``psf``; ``psi`` is built in), built
    at first use, its definitions cached on disk where the user cache directory is writable."""
    import pint

    try:
        ureg = pint.UnitRegistry(cache_folder=":auto:")
    except Exception:  # noqa: BLE001 - an unwritable or corrupt cache: build without it
        ureg = pint.UnitRegistry()
    ureg.define("pound_force_per_square_foot = force_pound / foot ** 2 = psf")
    return ureg


@dataclass(frozen=True)
class Dimension:
    """A physical dimension and its unit in each unit system.

    Attributes
    ----------
    name
        Human-readable name used in messages (``"length"``).
    si, us
        Unit expressions (pint syntax) of the dimension in the SI and US systems.
    """

    name: str
    si: str
    us: str

    def unit(self, system: System) -> str:
        """Unit expression of this dimension in ``system``."""
        return self.si if system == "SI" else self.us


DIMENSIONS: dict[str, Dimension] = {
    "dimensionless": Dimension("dimensionless number", "dimensionless", "dimensionless"),
    "angle": Dimension("angle", "degree", "degree"),
    "length": Dimension("length", "m", "ft"),
    "area": Dimension("area", "m**2", "ft**2"),
    "volume": Dimension("volume", "m**3", "ft**3"),
    "mass": Dimension("mass", "kg", "slug"),
    "mass*length^2": Dimension("moment of inertia", "kg*m**2", "slug*ft**2"),
    "force*length": Dimension("moment", "N*m", "lbf*ft"),
    "force*length^2": Dimension("bending stiffness", "N*m**2", "lbf*ft**2"),
    "time": Dimension("time", "s", "s"),
    "1/time": Dimension("circular frequency (rad/s)", "1/s", "1/s"),
    "velocity": Dimension("velocity", "m/s", "ft/s"),
    "acceleration": Dimension("acceleration", "m/s**2", "ft/s**2"),
    "force": Dimension("force", "N", "lbf"),
    "pressure": Dimension("pressure", "Pa", "psf"),
    "mass/length": Dimension("mass per length", "kg/m", "slug/ft"),
    "mass/length^3": Dimension("mass density", "kg/m**3", "slug/ft**3"),
    "force/length^3": Dimension("force per length^3", "N/m**3", "lbf/ft**3"),
    "area/time": Dimension("kinematic viscosity", "m**2/s", "ft**2/s"),
    "force*time": Dimension("force*time", "N*s", "lbf*s"),
    "force*time/length": Dimension("force*time per length", "N*s/m", "lbf*s/ft"),
    "force*time/length^3": Dimension("force*time per length^3", "N*s/m**3", "lbf*s/ft**3"),
}
"""Every dimension a case-file field may have, with its unit in each system."""

DEFAULTS: dict[str, tuple[float, str]] = {
    "water_density": (1025.0, "mass/length^3"),
    "gravity": (9.80665, "acceleration"),
    "seabed_stiffness": (3.0e6, "force/length^3"),
    "seabed_damping": (3.0e5, "force*time/length^3"),
    "relaxation_damping": (1.0e5, "force*time/length"),
    "pseudo_dt": (1.0, "time"),
    "output_every": (0.1, "time"),
    "slip_velocity": (0.01, "velocity"),
    "viscosity": (1.0e-6, "area/time"),
}
"""Defaults of dimensional quantities: (value in the SI unit of the dimension, key of
:data:`DIMENSIONS`); converted to the case's system."""

_NUMBER_START = re.compile(r"^\s*[-+]?(\d|\.\d)")

MAX_TEXT = 200
"""Longest string with a unit a case file may hold (characters)."""

MAX_EXPONENT = 30
"""Largest exponent magnitude in a string with a unit (``"m**2"``, ``"s^-1"``, ``"10**6 N"``).

An exponent must be a plain number at most this large, and powers may be neither chained
(``10**10**10``) nor applied to an expression holding a power (``(10**99)**99``): pint
evaluates integer powers exactly, and such towers would run for hours.
"""


class UnitParseError(ValueError):
    """A value could not be read as a quantity of the expected dimension."""


def unit_of(dimension: str, system: System) -> str:
    """Unit expression of ``dimension`` (a key of :data:`DIMENSIONS`) in ``system``."""
    return DIMENSIONS[dimension].unit(system)


def default_value(key: str, system: System) -> float:
    """Default of a dimensional quantity (a key of :data:`DEFAULTS`) in ``system``'s units."""
    value, dimension = DEFAULTS[key]
    if system == "SI":
        return value
    ureg = registry()
    return float(ureg.Quantity(value, unit_of(dimension, "SI")).to(unit_of(dimension, system))
                 .magnitude)


def _dimension_named(quantity: pint.Quantity) -> str | None:
    """Key of :data:`DIMENSIONS` whose dimensionality matches ``quantity`` (angle excluded)."""
    for key, dim in DIMENSIONS.items():
        if key == "angle":
            continue
        if registry().Quantity(1.0, dim.si).dimensionality == quantity.dimensionality:
            return key
    return None


def _describe(quantity: pint.Quantity) -> str:
    """The dimension of ``quantity`` for messages: ``"a mass"``, ``"dimension [length] ** 5"``."""
    key = _dimension_named(quantity)
    return _a(DIMENSIONS[key].name) if key else f"dimension {quantity.dimensionality}"


def _a(noun: str) -> str:
    """``"length"`` -> ``"a length"``, ``"area"`` -> ``"an area"``."""
    return ("an " if noun[:1] in "aeiou" else "a ") + noun


def _show(value: Any) -> str:
    """A value as written in the file, for messages."""
    return repr(value) if isinstance(value, str) else str(value)


def to_system(value: Any, dimension: str, system: System) -> float:
    """Convert a case-file value to a float in ``system``'s unit of ``dimension``.

    Parameters
    ----------
    value
        A number (already in the case's system; angles in degrees) or a string: a number, or a
        number with a unit (``"20 ft"``, pint syntax, arithmetic allowed).
    dimension
        Key of :data:`DIMENSIONS`.
    system
        ``"SI"`` or ``"US"``.

    Returns
    -------
    float
        The magnitude in the system's unit (may be ``inf``; NaN is rejected).

    Raises
    ------
    UnitParseError
        Not a number, unknown unit, unreadable text or wrong dimension (the message names
        the expected and the given dimension).
    """
    if isinstance(value, bool) or not isinstance(value, int | float | str):
        raise UnitParseError(f"expected a number, got {_show(value)}")
    if isinstance(value, str):
        magnitude = _parse_text(value, dimension, system)
    else:
        try:
            magnitude = float(value)
        except OverflowError:
            raise UnitParseError(f"too large a number: {str(value)[:20]}... "
                                 f"({len(str(value))} digits)") from None
    if math.isnan(magnitude):
        raise UnitParseError(f"expected a number, got {_show(value)}")
    return magnitude


def _short(text: str) -> str:
    return text if len(text) <= 60 else text[:57] + "..."


def _power_problem(text: str) -> str | None:
    """Why the powers of a unit expression cannot be evaluated quickly, or ``None``
    (:data:`MAX_EXPONENT`)."""
    try:
        tokens = [t for t in tokenize.generate_tokens(io.StringIO(text).readline)
                  if t.type in (tokenize.OP, tokenize.NUMBER, tokenize.NAME)]
    except (tokenize.TokenError, SyntaxError):
        return None  # pint reports malformed text
    opened: list[int] = []  # indices of the open parentheses
    powered: list[bool] = [False]  # whether each open group holds a power
    for i, tok in enumerate(tokens):
        if tok.string == "(":
            opened.append(i)
            powered.append(False)
        elif tok.string == ")" and opened:
            opened.pop()
            inner = powered.pop()
            powered[-1] = powered[-1] or inner
            if inner and i + 1 < len(tokens) and tokens[i + 1].string in ("**", "^"):
                return "a power of an expression that holds a power (too slow to evaluate)"
        elif tok.string in ("**", "^"):
            powered[-1] = True
            rest = [t.string for t in tokens[i + 1:i + 5]]
            while rest and rest[0] in ("(", "-", "+"):
                rest.pop(0)
            try:
                exponent = float(rest[0]) if rest else math.nan
            except ValueError:
                exponent = math.nan
            if not abs(exponent) <= MAX_EXPONENT:
                return (f"an exponent must be a number of magnitude at most {MAX_EXPONENT} "
                        f"(MAX_EXPONENT)")
            if rest[1:2] in (["**"], ["^"]):
                return "chained powers (a ** b ** c) are too slow to evaluate"
    return None


def _parse_text(text: str, dimension: str, system: System) -> float:
    """Read a string: a bare number (case's system) or a number with a unit."""
    try:
        return float(text)
    except ValueError:
        pass
    if not _NUMBER_START.match(text):
        raise UnitParseError(f"expected a number, got {text!r}")
    if len(text) > MAX_TEXT:
        raise UnitParseError(f"a number with a unit must be at most {MAX_TEXT} characters "
                             f"(MAX_TEXT), got {len(text)}")
    problem = _power_problem(text)
    if problem is not None:
        raise UnitParseError(f"cannot read {_short(text)!r}: {problem}")
    import pint

    ureg = registry()
    try:
        quantity = ureg.Quantity(text)
    except pint.UndefinedUnitError as exc:
        names = ", ".join(repr(n) for n in exc.unit_names) or "?"
        raise UnitParseError(f"unknown unit {names} in {text!r}") from None
    except Exception:  # noqa: BLE001 - pint raises many kinds on malformed text
        raise UnitParseError(f"cannot read {text!r} as a number with a unit") from None
    if not isinstance(quantity, pint.Quantity):  # pragma: no cover - pint returns Quantity
        return float(quantity)
    expected = DIMENSIONS[dimension]
    target = ureg.Quantity(1.0, expected.unit(system))
    if quantity.dimensionality != target.dimensionality:
        raise UnitParseError(
            f"expected {_a(expected.name)}, got {text!r} ({_describe(quantity)})"
        )
    try:
        return float(quantity.to(target.units).magnitude)
    except Exception:  # noqa: BLE001 - e.g. offset units
        raise UnitParseError(f"cannot convert {text!r} to {expected.unit(system)}") from None
