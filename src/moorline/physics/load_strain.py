"""Non-linear tension-strain laws of fibre ropes, vectorized over elements.

A line type may give its tension as a table of ``(strain, tension)`` points (a quasi-static
load-strain curve, or MoorDyn's EA table file). The table is interpolated by the monotone
piecewise-cubic Hermite interpolant of Fritsch & Carlson (1980) with the knot slopes of
:class:`scipy.interpolate.PchipInterpolator`: monotone data give a monotone law with a
continuous derivative, which Newton needs. The law is

* ``f(eps)`` of the table for ``0 <= eps <= eps_last``;
* ``f(eps_last) + f'(eps_last) (eps - eps_last)`` beyond the last point: extrapolated linearly
  with the interpolant's slope there (so ``f`` stays C1); MoorDyn instead holds the last
  tension constant beyond its table;
* ``EA eps`` for ``eps < 0`` (``EA``: the line type's reference stiffness). The element law
  (:func:`moorline.physics.element.axial_tension`) evaluates ``f`` at the slack-regularized
  strain, so a compression-free line (``slack_ratio = 0``) carries no tension for
  ``eps <= 0``, and a regularized one keeps ``slack_ratio EA`` in compression, as an elastic
  line.

The first point must be ``(0, 0)`` (a table without it gets it prepended); strains must
increase and tensions must not decrease.

Fibre-rope dynamic stiffness
----------------------------
Polyester is stiffer under wave-frequency cycling than in slow loading. The static-dynamic
model of Del Vecchio (1992, PhD thesis, University of Reading; the form used by the
classification rules, e.g. DNV-RP-E305, not checked against their text here) gives the
dynamic stiffness as a linear function of the mean load, ``K_rd = alpha + beta L_m``. In force
units it is MoorPy's line-type convention (``EAd``, ``EAd_Lm``: ``EA_d = EAd + EAd_Lm
T_mean``, moorpy ``line.py``, ``activateDynamicStiffness``) and MoorDyn's ``EA_Dc|EA_D_Lm``
(docs/inputs.rst). :func:`dynamic_strain_law` linearizes each such element about its static
state ``(eps_s, T_s)`` (the quasi-static law): in dynamic analyses (time domain, modal,
stochastic, harmonic balance; :func:`moorline.mesh.dynamic_mesh`) its tension is ``T = T_s +
EA_d (eps - eps_s)`` with ``EA_d = EAd + EAd_Lm T_s`` (per element; MoorPy uses the line's
mean end tension), i.e. the elastic law with ``EA_d`` and a strain offset ``eps_0 = eps_s -
T_s / EA_d`` (compression-free below
``eps_0``); the static equilibrium is unchanged and the tangent about it is ``EA_d``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]


class StrainTable:
    """One tabulated law ``T = f(eps)`` (see the module docstring).

    Parameters
    ----------
    points
        ``(strain, tension)`` pairs, strain increasing from 0, tension non-decreasing.
    """

    def __init__(self, points: ArrayLike) -> None:
        pts = np.asarray(points, dtype=float)
        if pts.ndim != 2 or pts.shape[1] != 2 or len(pts) < 1:
            raise ValueError("a strain table needs rows of (strain, tension)")
        if not np.all(np.isfinite(pts)):
            raise ValueError("a strain table must contain finite numbers only")
        if pts[0, 0] < 0:
            raise ValueError("strain table: strains must be >= 0 (no compression)")
        if pts[0, 0] > 0:
            pts = np.vstack(([0.0, 0.0], pts))
        elif pts[0, 1] != 0:
            raise ValueError("strain table: the tension at zero strain must be 0")
        if len(pts) < 2 or np.any(np.diff(pts[:, 0]) <= 0):
            raise ValueError("strain table: strains must increase (at least one point > 0)")
        if np.any(np.diff(pts[:, 1]) < 0):
            raise ValueError("strain table: tensions must not decrease (a monotone law)")
        from scipy.interpolate import PchipInterpolator  # 0.4 s to import: only for tables

        self.points = pts
        self._f = PchipInterpolator(pts[:, 0], pts[:, 1], extrapolate=False)
        self._df = self._f.derivative()
        self._F = self._f.antiderivative()
        self.end_strain, self.end_tension = float(pts[-1, 0]), float(pts[-1, 1])
        self.end_slope = float(self._df(self.end_strain))
        self.end_energy = float(self._F(self.end_strain))

    @property
    def max_slope(self) -> float:
        """Largest tangent ``dT/deps`` of the law (its stiffest point) [force]."""
        knots = np.asarray(self._df(self.points[:, 0]), dtype=float)
        return float(max(knots.max(), np.max(np.diff(self.points[:, 1])
                                             / np.diff(self.points[:, 0]))))

    def __call__(self, strain: FloatArray) -> tuple[FloatArray, FloatArray]:
        """Tension and ``dT/deps`` at strains ``>= 0`` (linear beyond the last point)."""
        inside = np.minimum(strain, self.end_strain)
        beyond = np.maximum(strain - self.end_strain, 0.0)
        return self._f(inside) + self.end_slope * beyond, self._df(inside)

    def energy(self, strain: FloatArray) -> FloatArray:
        """``integral_0^eps f`` at strains ``>= 0``."""
        inside = np.minimum(strain, self.end_strain)
        beyond = np.maximum(strain - self.end_strain, 0.0)
        return (self._F(inside) + self.end_tension * beyond
                + 0.5 * self.end_slope * beyond**2)


@dataclass(frozen=True)
class StrainLaws:
    """The tabulated laws of a mesh: ``tables`` and, per element, the index of its table
    (``-1``: the linear law ``EA eps`` of :func:`moorline.physics.element.axial_tension`)."""

    tables: tuple[StrainTable, ...]
    ids: IntArray

    @property
    def active(self) -> bool:
        """Whether any element follows a table."""
        return bool(np.any(self.ids >= 0))

    def take(self, index: ArrayLike) -> StrainLaws:
        """The laws of a subset of the elements."""
        return StrainLaws(self.tables, self.ids[index])

    def evaluate(self, g: FloatArray, EA: FloatArray) -> tuple[FloatArray, FloatArray]:
        """``f(g)`` and ``f'(g)`` per element at regularized strains ``g`` (``EA g`` and ``EA``
        for ``g < 0`` and for elements without a table)."""
        T, dT = EA * g, np.array(EA, dtype=float, copy=True)
        for k, table in enumerate(self.tables):
            sel = np.flatnonzero((self.ids == k) & (g >= 0))
            if sel.size:
                T[sel], dT[sel] = table(g[sel])
        return T, dT

    def energy(self, g: FloatArray, EA: FloatArray) -> FloatArray:
        """``integral_0^g f`` per element (``EA g^2 / 2`` for ``g < 0``)."""
        out = 0.5 * EA * g**2
        for k, table in enumerate(self.tables):
            sel = np.flatnonzero((self.ids == k) & (g >= 0))
            if sel.size:
                out[sel] = table.energy(g[sel])
        return out


def strain_laws(tables: list[StrainTable | None], line_of_element: IntArray) -> StrainLaws | None:
    """Per-element laws from one optional table per line (``None`` when no line has one)."""
    distinct: list[StrainTable] = []
    index = []
    for table in tables:
        if table is None:
            index.append(-1)
            continue
        if table not in distinct:
            distinct.append(table)
        index.append(distinct.index(table))
    if not distinct:
        return None
    return StrainLaws(tuple(distinct), np.asarray(index, dtype=np.int64)[line_of_element])


def dynamic_strain_law(
    static_strain: FloatArray, static_tension: FloatArray, EAd: FloatArray, EAd_Lm: FloatArray
) -> tuple[FloatArray, FloatArray]:
    """Dynamic stiffness about the mean state (module docstring): ``EA_d = EAd + EAd_Lm T_s``
    (``T_s`` clipped at 0) and the strain offset ``eps_0 = eps_s - T_s / EA_d`` of the linear law
    ``T = EA_d (eps - eps_0)``."""
    mean = np.maximum(static_tension, 0.0)
    EA_d = EAd + EAd_Lm * mean
    return EA_d, static_strain - mean / EA_d
