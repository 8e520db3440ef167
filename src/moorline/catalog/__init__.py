"""The line catalogue: properties of mooring chain, wire and fibre rope from the nominal
diameter, computed from published formulas (the data file ``lines.yaml`` next to this module
names the source of every coefficient).

A catalogue name is a family, and for chain its grade: ``chain_studless_r3``,
``chain_studlink_r4s``, ``wire_six_strand``, ``wire_spiral_strand``, ``polyester``, ``nylon``,
``hmpe``. :func:`line_properties` gives the SI properties of a name at a nominal diameter;
:func:`in_units` converts them to a case's unit system. In a case file
``line_types.<name>: {catalog: ..., nominal_diameter: "120 mm"}`` fills in the line type;
any key given next to them overrides the catalogue's value.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cache
from typing import Any

from ..package_data import load_yaml

__all__ = ["CATALOG_FILE", "PROPERTIES", "CatalogError", "LineProperties", "catalog_names",
           "families", "in_units", "line_properties"]

CATALOG_FILE = "lines.yaml"
"""The data file of the catalogue, in this package."""

PROPERTIES: dict[str, str] = {
    "diameter": "length", "mass_per_length": "mass/length", "EA": "force",
    "EA_dynamic": "force", "MBL": "force", "Cd": "dimensionless", "Ct": "dimensionless",
    "Ca": "dimensionless", "Cat": "dimensionless"}
"""The properties the catalogue gives (line-type keys) and their dimension
(:data:`moorline.io.units.DIMENSIONS`)."""


class CatalogError(ValueError):
    """An unknown catalogue name or a nominal diameter outside a family's range.

    Attributes
    ----------
    key
        ``"catalog"`` or ``"nominal_diameter"``: the line-type key at fault.
    """

    def __init__(self, message: str, key: str) -> None:
        super().__init__(message)
        self.key = key


@dataclass(frozen=True)
class LineProperties:
    """Catalogue properties of one line type, in SI units.

    Attributes
    ----------
    name, family, grade
        The catalogue name, its family and (chain) grade, ``""`` otherwise.
    nominal_diameter
        Nominal diameter [m] (chain bar diameter, rope diameter).
    values
        ``{key: value}`` for the keys of :data:`PROPERTIES` the family has (``diameter`` is the
        volume-equivalent diameter [m]; ``EA_dynamic`` only for fibre ropes, at
        ``mean_load_percent``).
    sources
        ``{key: source}``: where each value comes from.
    verified
        ``{key: bool}``: False where the primary source could not be read (see the data file).
    mean_load_percent
        Mean load [% MBL] of ``EA_dynamic`` (fibre ropes).
    """

    name: str
    family: str
    grade: str
    nominal_diameter: float
    values: dict[str, float]
    sources: dict[str, str] = field(default_factory=dict)
    verified: dict[str, bool] = field(default_factory=dict)
    mean_load_percent: float = 0.0


@cache
def _data() -> dict[str, Any]:
    return load_yaml(__name__, CATALOG_FILE)


def families() -> dict[str, dict[str, Any]]:
    """The families of the catalogue: ``{family: {"description", "grades",
    "diameter_range_mm"}}``."""
    return {name: {"description": f["description"], "grades": list(f.get("grades", [])),
                   "diameter_range_mm": list(f["diameter_range_mm"])}
            for name, f in _data()["families"].items()}


def catalog_names() -> list[str]:
    """Every catalogue name: ``<family>`` or, for chain, ``<family>_<grade>`` (lower case)."""
    names = []
    for family, entry in families().items():
        grades = entry["grades"]
        names += [f"{family}_{g.lower()}" for g in grades] if grades else [family]
    return names


def _split(name: str) -> tuple[str, str]:
    """(family, grade) of a catalogue name; raises :class:`CatalogError` if unknown."""
    key = str(name).strip().lower()
    for family, entry in families().items():
        if key == family and not entry["grades"]:
            return family, ""
        for grade in entry["grades"]:
            if key == f"{family}_{grade.lower()}":
                return family, grade
    import difflib

    known = catalog_names()
    close = difflib.get_close_matches(key, known, n=1, cutoff=0.6)
    hint = f" (did you mean {close[0]!r}?)" if close else ""
    raise CatalogError(f"unknown catalogue line {name!r}{hint}; known: {', '.join(known)}",
                       "catalog")


def _evaluate(spec: dict[str, Any], d: float, grade: str, mbl: float | None,
              mean_load: float) -> float:
    """One property from its formula (``kind`` in the data file) at nominal diameter ``d``
    [m]."""
    kind = spec["kind"]
    if kind == "power":
        return float(sum(c * d**k for k, c in enumerate(spec["coefficients"])))
    if kind == "chain_mbl":
        d_mm = d * 1e3
        return float(spec["grade_factor"][grade] * d_mm**2 * (44.0 - 0.08 * d_mm) * 1e3)
    if kind == "ratio":
        return float(spec["factor"] * d)
    if kind == "of_mbl":
        return float(spec["factor"] * mbl)
    if kind == "of_mbl_load":
        return float((spec["alpha"] + spec["beta"] * mean_load) * mbl)
    if kind == "value":
        return float(spec["value"])
    raise ValueError(f"unknown formula kind {kind!r} in {CATALOG_FILE}")  # pragma: no cover


def line_properties(name: str, nominal_diameter: float) -> LineProperties:
    """The catalogue properties of ``name`` at a nominal diameter.

    Parameters
    ----------
    name
        A catalogue name (:func:`catalog_names`), case-insensitive.
    nominal_diameter
        Nominal diameter [m].

    Returns
    -------
    LineProperties
        SI values with their sources.

    Raises
    ------
    CatalogError
        Unknown name, or a diameter outside the family's ``diameter_range_mm``.
    """
    family, grade = _split(name)
    entry = _data()["families"][family]
    low, high = entry["diameter_range_mm"]
    d_mm = nominal_diameter * 1e3
    if not (math.isfinite(d_mm) and low <= d_mm <= high):
        raise CatalogError(f"nominal diameter {d_mm:.6g} mm is outside the range of "
                           f"{family} in the catalogue, {low:g} to {high:g} mm "
                           f"({CATALOG_FILE})", "nominal_diameter")
    mean_load = float(_data()["mean_load_percent"])
    values: dict[str, float] = {}
    sources: dict[str, str] = {}
    verified: dict[str, bool] = {}
    # MBL first: the stiffness of fibre ropes is given per breaking load
    for key in sorted(PROPERTIES, key=lambda k: k != "MBL"):
        if key in entry:
            values[key] = _evaluate(entry[key], nominal_diameter, grade, values.get("MBL"),
                                    mean_load)
            sources[key] = " ".join(str(entry[key]["source"]).split())
            verified[key] = bool(entry[key].get("verified", True))
    ordered = {k: values[k] for k in PROPERTIES if k in values}
    return LineProperties(name=f"{family}_{grade.lower()}" if grade else family, family=family,
                          grade=grade, nominal_diameter=nominal_diameter, values=ordered,
                          sources=sources, verified=verified,
                          mean_load_percent=mean_load if "EA_dynamic" in values else 0.0)


def in_units(values: dict[str, float], system: str) -> dict[str, float]:
    """SI catalogue values (keys of :data:`PROPERTIES`) in ``system``'s units (``SI``: the
    same; ``US``: ft, slug/ft, lbf)."""
    if system == "SI":
        return dict(values)
    from ..io.units import registry, unit_of

    ureg = registry()
    out = {}
    for key, value in values.items():
        dimension = PROPERTIES[key]
        out[key] = float(ureg.Quantity(value, unit_of(dimension, "SI"))
                         .to(unit_of(dimension, system)).magnitude)
    return out
