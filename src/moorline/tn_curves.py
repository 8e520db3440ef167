"""Fatigue design curves of mooring line components (T-N and S-N), from the package's data
file ``moorline/data/tn_curves.yaml`` (each curve with its standard and clause).

Two forms (see the data file):

- ``tension_ratio`` (API RP 2SK 3rd ed. (2005) sec. 7): ``N R^M = K`` with ``R`` the tension
  range over the reference breaking strength; ``K`` may depend on the mean-tension ratio
  ``Lm`` (wire ropes: ``log10 K = a + b Lm``).
- ``stress`` (DNV-OS-E301 (2010) Ch.2 Sec.2 E): ``n_c(s) = a_D s^-m`` with ``s`` the tension
  range over the nominal area in MPa (chain: ``2 pi d^2 / 4``).

Both are ``N = K x^-m`` in the curve's normalized range ``x``: :meth:`TNCurve.scale` gives
the tension per unit of ``x`` for a component (its reference breaking strength, or its
nominal area times 1 MPa), so that damage kernels (:mod:`moorline.fatigue`) work on
``x = tension range / scale``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .package_data import load_yaml

__all__ = ["TNCurve", "chain_area", "curve", "curves", "newtons_per"]

FloatArray = NDArray[np.float64]

#: 1 MPa in N/m^2.
MPA = 1.0e6


@dataclass(frozen=True)
class TNCurve:
    """One fatigue design curve ``N = K x^-m``.

    Attributes
    ----------
    name, description
        Key in the data file and what component it is for.
    form
        ``tension_ratio`` (``x = dT / reference breaking strength``) or ``stress``
        (``x = dT / nominal area`` in MPa).
    m
        Inverse slope (``M`` of API, ``m`` of DNV).
    K
        Intercept (``K`` of API, ``a_D`` of DNV); ``None`` when it depends on the mean load.
    log10_K
        ``(a, b)``: ``log10 K = a + b Lm``, ``Lm`` the mean tension over the reference
        breaking strength (API wire ropes); ``None`` otherwise.
    area
        ``stress`` form: ``chain`` (nominal area from the bar diameter) or ``given``.
    source, checked
        The standard and clause; the other text the values were checked against.
    """

    name: str
    description: str
    form: Literal["tension_ratio", "stress"]
    m: float
    K: float | None
    log10_K: tuple[float, float] | None
    area: str
    source: str
    checked: str

    def intercept(self, mean_ratio: ArrayLike = 0.0) -> FloatArray:
        """``K`` (per signal when it depends on the mean-tension ratio ``Lm``)."""
        if self.log10_K is None:
            return np.broadcast_to(np.asarray(self.K, dtype=float),
                                   np.shape(mean_ratio)).copy()
        a, b = self.log10_K
        return 10.0 ** (a + b * np.asarray(mean_ratio, dtype=float))

    def cycles(self, x: ArrayLike, mean_ratio: ArrayLike = 0.0) -> FloatArray:
        """Cycles to failure ``N = K x^-m`` at normalized ranges ``x``."""
        with np.errstate(divide="ignore"):
            return self.intercept(mean_ratio) * np.asarray(x, dtype=float) ** (-self.m)

    def scale(self, *, MBL: float | None = None, diameter: float | None = None,
              area: float | None = None, units: str = "SI") -> float:
        """Tension per unit of the normalized range ``x`` [force, the case's units].

        Parameters
        ----------
        MBL
            Reference breaking strength (``tension_ratio`` curves).
        diameter, area
            Nominal bar diameter of a chain (area ``2 pi d^2 / 4``) or the nominal area
            (``stress`` curves) [length, area in the case's units].
        units
            The case's unit system (``stress`` curves are in MPa).

        Raises
        ------
        ValueError
            When the quantity the curve needs is not given.
        """
        if self.form == "tension_ratio":
            if MBL is None or not MBL > 0:
                raise ValueError(f"T-N curve {self.name} needs the reference breaking "
                                 "strength MBL of the line type")
            return float(MBL)
        if area is None and diameter is not None and self.area == "chain":
            area = chain_area(diameter)
        if area is None or not area > 0:
            need = "the chain's nominal diameter or" if self.area == "chain" else ""
            raise ValueError(f"S-N curve {self.name} needs {need} the nominal area")
        newtons, square_metres = newtons_per("force", units), newtons_per("area", units)
        return float(area) * square_metres * MPA / newtons


def chain_area(diameter: float) -> float:
    """Nominal area of a chain: the two legs of a link, ``2 pi d^2 / 4`` (DNV-OS-E301
    Ch.2 Sec.2 E)."""
    return 2.0 * math.pi * diameter**2 / 4.0


def newtons_per(dimension: str, units: str) -> float:
    """The SI value of one unit of ``dimension`` (``force``: N, ``area``: m^2) in the unit
    system ``units``."""
    from .io.units import DIMENSIONS, registry

    unit = DIMENSIONS[dimension].unit("US" if units == "US" else "SI")
    target = DIMENSIONS[dimension].unit("SI")
    return float(registry().Quantity(1.0, unit).to(target).magnitude)


@lru_cache(maxsize=1)
def curves() -> dict[str, TNCurve]:
    """Every curve of the data file, by name."""
    data = load_yaml("moorline", "data/tn_curves.yaml")
    return {name: _curve(name, entry) for name, entry in data.items()}


def _curve(name: str, entry: dict[str, Any]) -> TNCurve:
    api = entry["form"] == "tension_ratio"
    log10_K = entry.get("log10_K")
    return TNCurve(name=name, description=str(entry.get("description", "")),
                   form=entry["form"], m=float(entry["M"] if api else entry["m"]),
                   K=None if log10_K else float(entry["K"] if api else entry["a_D"]),
                   log10_K=tuple(float(v) for v in log10_K) if log10_K else None,
                   area=str(entry.get("area", "")), source=str(entry["source"]),
                   checked=str(entry.get("checked", "")))


def curve(name: str) -> TNCurve:
    """The curve ``name`` of the data file.

    Raises
    ------
    KeyError
        With the known names, when there is no such curve.
    """
    table = curves()
    if name not in table:
        raise KeyError(f"unknown T-N curve {name!r}; known: {', '.join(table)}")
    return table[name]
