"""Line types of a case file from the line catalogue (``catalog`` and ``nominal_diameter``)
or by hand, as :class:`~moorline.model.LineType` objects in the case's units."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from moorline.catalog import CatalogError, in_units, line_properties
from moorline.errors import CaseError
from moorline.model import LineType
from moorline.physics.load_strain import StrainTable
from moorline.physics.syrope import reference_stiffness

from .strain_table import read_strain_table

__all__ = ["FOOT", "REQUIRED", "resolve_line_types"]

REQUIRED = ("diameter", "mass_per_length", "EA")
"""The keys a line type needs when it names no catalogue entry."""

FOOT = 0.3048
"""One foot in metres (exact, by the international yard of 1959)."""


def resolve_line_types(specs: dict[str, Any], units: str, file: str,
                       source: str | None = None) -> dict[str, LineType]:
    """The line types of a validated case, catalogue values filled in.

    Parameters
    ----------
    specs
        ``line_types`` of the case (:class:`~moorline.io.schema.LineTypeSpec` by name).
    units
        The case's unit system (``SI`` or ``US``): catalogue values are converted to it.
    file
        The case file, for messages.
    source
        The case file's path (``EA_table`` files are relative to it; ``None``: the working
        directory).

    Returns
    -------
    dict
        :class:`~moorline.model.LineType` by name; keys written in the case override the
        catalogue's values.

    Raises
    ------
    CaseError
        An unknown catalogue name or a diameter outside its range (names
        ``line_types.<name>.catalog`` or ``.nominal_diameter``), a catalogue without a
        nominal diameter or the reverse, a hand-made line type without a required key.
    """
    out = {}
    for name, spec in specs.items():
        where = f"line_types.{name}"
        values = spec.model_dump()
        given = spec.model_fields_set
        if spec.catalog is not None:
            if spec.nominal_diameter is None:
                raise CaseError(f"a catalogue line type needs nominal_diameter (the catalogue "
                                f"entry {spec.catalog!r} is scaled by it)", file=file,
                                field=f"{where}.nominal_diameter")
            metres = spec.nominal_diameter * (FOOT if units == "US" else 1.0)
            try:
                props = line_properties(spec.catalog, metres)
            except CatalogError as exc:
                raise CaseError(str(exc), file=file, field=f"{where}.{exc.key}") from None
            values["catalog"] = props.name
            for key, value in in_units(props.values, units).items():
                if key not in given:
                    values[key] = value
        elif spec.nominal_diameter is not None:
            raise CaseError("nominal_diameter needs a catalog entry (moorline catalog lists "
                            "them); without one give diameter, mass_per_length and EA",
                            file=file, field=f"{where}.nominal_diameter")
        _strain_law(values, spec, source, file, where)
        if values["owc"] is not None:
            values["owc"] = tuple((float(e), float(t)) for e, t in values["owc"])
            if values["EA"] is None and len(values["owc"]) > 1:
                values["EA"] = reference_stiffness(values["owc"])
        for key in REQUIRED:
            if values[key] is None:
                raise CaseError(f"missing required key {key!r} (or give catalog and "
                                f"nominal_diameter)", file=file, field=f"{where}.{key}")
        out[name] = LineType(name=name, **values)
    return out


def _strain_law(values: dict, spec: Any, source: str | None, file: str, where: str) -> None:
    """Resolve ``EA: {table: ...}`` or ``EA_table: file`` into ``EA_table`` points and the
    reference ``EA`` (the table's largest tangent), in place."""
    points = None
    if isinstance(values["EA"], dict):
        if spec.EA_table is not None:
            raise CaseError("give EA as a table or EA_table, not both", file=file,
                            field=f"{where}.EA_table")
        points, field = values["EA"]["table"], f"{where}.EA"
    elif spec.EA_table is not None:
        if "EA" in spec.model_fields_set:
            raise CaseError("give EA or EA_table, not both", file=file,
                            field=f"{where}.EA_table")
        base = Path(source).parent if source else Path.cwd()
        field = f"{where}.EA_table"
        try:
            points = read_strain_table(base / spec.EA_table)
        except ValueError as exc:
            raise CaseError(str(exc), file=file, field=field) from None
    if points is None:
        values["EA_table"] = None
        return
    try:
        table = StrainTable(points)
    except ValueError as exc:
        raise CaseError(str(exc), file=file, field=field) from None
    values["EA_table"] = tuple((float(e), float(t)) for e, t in table.points)
    values["EA"] = table.max_slope
