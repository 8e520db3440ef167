"""Build and solve a MoorPy model of a moorline :class:`System` (quasi-static catenaries).

MoorPy (NREL, ``pip install moorline[compare]``) represents each line by the closed-form
elastic catenary (with seabed contact when end A lies on the seabed) and solves for the
free points' equilibrium; its stiffness matrices are the analytic gradients of those
catenaries. The translation:

- line types: ``mass``, ``d_vol = diameter``, ``EA`` (MoorPy's wet weight is then
  ``(m - rho pi d^2 / 4) g``, moorline's with the default displaced area),
- points: ``fixed`` and ``prescribed`` -> MoorPy fixed points (type 1), ``free`` -> free
  points (type 0) with the same mass, volume and constant external force; or, for the points
  named in ``body_points``, points of one MoorPy coupled body (type -1) whose reference is
  ``body_reference`` (for the 6x6 stiffness of a floater's mooring),
- lines: the same ends and unstretched length, no seabed friction (MoorPy 1.3 resets its
  friction coefficient to 0 for a line whose end A lies on the seabed).

MoorPy has no elastic seabed: its seabed is rigid, moorline's a penalty spring.
"""

from __future__ import annotations

import contextlib
import io
from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import CaseError
from ..model import System

FloatArray = NDArray[np.float64]


def import_moorpy() -> Any:
    """The ``moorpy`` package; ImportError with the install hint when it is missing."""
    try:
        import moorpy
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise ImportError("the MoorPy comparison needs the 'moorpy' package "
                          "(pip install moorline[compare])") from exc
    return moorpy


def moorpy_system(system: System, body_points: Sequence[str] = (),
                  body_reference: Sequence[float] = (0.0, 0.0, 0.0)) -> Any:
    """A MoorPy ``System`` of ``system`` (initialized, not yet solved).

    Parameters
    ----------
    system
        Fixed, prescribed and free points and elastic lines (no current, waves or bodies).
    body_points
        Points (fixed or prescribed in ``system``) to attach to one coupled MoorPy body.
    body_reference
        The body's reference point [m] (its rotations are about it).

    Returns
    -------
    moorpy.System
        Points numbered in the order of ``system.points``, lines in that of ``system.lines``.
    """
    mp = import_moorpy()
    env = system.environment
    if system.bodies:
        raise CaseError("the MoorPy translation does not handle moorline bodies",
                        file=system.source)
    if env.current.speed or env.current.speeds:
        raise CaseError("the MoorPy translation does not handle current", file=system.source)
    ms = mp.System(depth=env.depth, rho=env.water_density, g=env.gravity)
    for lt in system.line_types.values():
        if lt.material != "elastic" or lt.EA_table is not None:
            raise CaseError(f"line type {lt.name}: the MoorPy translation needs an elastic "
                            "material with a constant EA", file=system.source)
        ms.setLineType(dnommm=lt.diameter * 1000.0, name=lt.name, mass=lt.mass_per_length,
                       d_vol=lt.diameter, EA=lt.EA)
    body = 0
    reference = np.asarray(body_reference, dtype=float)
    if body_points:
        ms.addBody(-1, [*reference, 0.0, 0.0, 0.0])
        body = 1
    number: dict[str, int] = {}
    for name, p in system.points.items():
        if name in body_points:
            if p.kind == "free":
                raise CaseError(f"point {name}: a body point must be fixed or prescribed",
                                file=system.source)
            ms.addPoint(1, np.asarray(p.position, dtype=float) - reference, body=body)
        elif p.kind in ("fixed", "prescribed"):
            ms.addPoint(1, list(p.position))
        elif p.kind == "free":
            ms.addPoint(0, list(p.position), m=p.mass, v=p.volume, fExt=np.asarray(p.force))
        else:
            raise CaseError(f"point {name}: kind {p.kind!r} has no MoorPy translation",
                            file=system.source)
        number[name] = len(ms.pointList)
    for line in system.lines.values():
        ms.addLine(line.length, line.line_type, nSegs=line.segments,
                   pointA=number[line.end_a], pointB=number[line.end_b])
    ms.initialize()
    return ms


def solve_moorpy(system: System, tol: float = 1.0e-6, **options: Any) -> Any:
    """:func:`moorpy_system` solved for the equilibrium of its free points.

    ``tol`` is MoorPy's absolute position tolerance [m] (its default, 0.05 m, is far too
    loose for a comparison); ``options`` go to :func:`moorpy_system`.
    """
    ms = moorpy_system(system, **options)
    with contextlib.redirect_stdout(io.StringIO()):  # MoorPy prints its solver's progress
        ms.solveEquilibrium(tol=tol, maxIter=1000)
    return ms


def end_forces(ms: Any, index: int) -> tuple[FloatArray, FloatArray]:
    """Forces MoorPy line ``index`` (0-based) exerts on its end points A and B [N]: MoorPy's
    ``fA``, ``fB``, the same quantity as moorline's
    :meth:`~moorline.results.StaticResult.end_force`."""
    line = ms.lineList[index]
    return np.asarray(line.fA, dtype=float), np.asarray(line.fB, dtype=float)
