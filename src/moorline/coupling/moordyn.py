"""The call pattern of the ``moordyn`` Python module (MoorDyn-C 2.x) on moorline's implicit
solver: a driver written for MoorDyn switches by changing its import::

    import moorline.coupling.moordyn as moordyn     # instead of: import moordyn

    md = moordyn.Create("cases/oc3_dynamics.yaml")  # a moorline case or a MoorDyn deck
    moordyn.Init(md, x0, [0.0] * len(x0))
    for i in range(n):
        forces = moordyn.Step(md, x, xd, i * dt, dt)  # x, xd at t = i dt, as MoorDyn
    line = moordyn.GetLine(md, 1)
    moordyn.GetLineFairTen(line)
    moordyn.Close(md)

The coupled dofs are the case's prescribed points (a MoorDyn deck's ``Coupled``/``Vessel``
points), three per point in the case's order. ``Step`` moves them as MoorDyn does,
``x + xd (t' - t)`` over the interval (:meth:`~moorline.coupling.Coupling.step_linear`), and
returns the forces on them at ``t + dt``. Differences: one implicit step per call (no
``dtM`` sub-steps unless ``Create(file, substep=...)``), the
forces on a point include its node's lumped inertia, and MoorDyn's bodies and rods are not
read from decks. ``GetStiffness`` (not in MoorDyn) gives the coupled dofs' tangent.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from . import Coupling

LEVEL_DBG, LEVEL_MSG, LEVEL_WRN, LEVEL_ERR, LEVEL_NONE = 0, 1, 3, 4, 4096


@dataclass(frozen=True)
class _Point:
    system: Coupling
    index: int  # 0-based, case order


@dataclass(frozen=True)
class _Line:
    system: Coupling
    index: int


def Create(filepath: str | os.PathLike = "", **options) -> Coupling:
    """Read a moorline case (``.yaml``, ``.yml``, ``.json``) or a MoorDyn deck; ``options``
    (not in MoorDyn) go to :class:`Coupling` (``substep``, ``dynamics``, ...)."""
    path = Path(filepath or "Mooring/lines.txt")
    if path.suffix.lower() in (".yaml", ".yml", ".json"):
        return Coupling(path, **options)
    from ..io.moordyn import read_moordyn

    return Coupling(read_moordyn(path), **options)


def NCoupledDOF(instance: Coupling) -> int:
    """Number of coupled dofs."""
    return instance.n_dof


def Init(instance: Coupling, x, v) -> int:
    """Statics with the coupled points at ``x``; ``v``: their velocities (the lines start at
    rest). Returns 0 (raises on failure, unlike MoorDyn's error code)."""
    instance.init(x, v)
    return 0


def Step(instance: Coupling, x, v, t: float, dt: float) -> list[float]:
    """Advance from ``t`` to ``t + dt`` with the coupled points at ``x`` moving with ``v``;
    the forces on them at ``t + dt``."""
    return instance.step_linear(x, v, t, dt).tolist()


def Close(instance: Coupling) -> int:
    """Release the system."""
    instance.close()
    return 0


def SetVerbosity(instance: Coupling, verbosity: int) -> int:
    """Accepted for compatibility (moorline logs through :mod:`logging`)."""
    return 0


def SetLogFile(instance: Coupling, path: str) -> int:
    """Accepted for compatibility."""
    return 0


def SetLogLevel(instance: Coupling, level: int) -> int:
    """Accepted for compatibility."""
    return 0


def GetNumberLines(instance: Coupling) -> int:
    """Number of lines."""
    return len(instance.system.lines)


def GetNumberPoints(instance: Coupling) -> int:
    """Number of points."""
    return len(instance.system.points)


def GetNumberBodies(instance: Coupling) -> int:
    """Number of bodies moorline solves (coupled bodies are the host's)."""
    return len(instance.system.bodies) - len(instance.body_names)


def GetPoint(instance: Coupling, point: int) -> _Point:
    """Point ``point`` (1-based, case order)."""
    if not 1 <= point <= len(instance.system.points):
        raise IndexError(f"no point {point}")
    return _Point(instance, point - 1)


def _point_name(p: _Point) -> str:
    return list(p.system.system.points)[p.index]


def GetPointForce(instance: _Point) -> tuple[float, float, float]:
    """Force on the point (:meth:`Coupling.point_force`)."""
    return tuple(float(f) for f in instance.system.point_force(_point_name(instance)))


def GetPointPos(instance: _Point) -> tuple[float, float, float]:
    """Position of the point."""
    node = instance.system.mesh.point_index(_point_name(instance))
    return tuple(float(c) for c in instance.system.positions[node])


def GetPointVel(instance: _Point) -> tuple[float, float, float]:
    """Velocity of the point."""
    node = instance.system.mesh.point_index(_point_name(instance))
    return tuple(float(c) for c in instance.system._state.v[node])


def GetLine(instance: Coupling, line: int) -> _Line:
    """Line ``line`` (1-based, case order)."""
    if not 1 <= line <= len(instance.system.lines):
        raise IndexError(f"no line {line}")
    return _Line(instance, line - 1)


def GetLineN(instance: _Line) -> int:
    """Number of segments."""
    return len(instance.system.mesh.line_elements[instance.index])


def GetLineFairTen(instance: _Line) -> float:
    """Tension of the segment at end B (MoorDyn's ``FairTen``)."""
    last = instance.system.mesh.line_elements[instance.index][-1]
    return float(instance.system.tensions()[last])


def GetLineNodeTen(instance: _Line, i: int) -> float:
    """Tension at node ``i`` (0..N): its segment's at the ends, the mean of its two
    segments' inside (as MoorDyn)."""
    elements = instance.system.mesh.line_elements[instance.index]
    T = instance.system.tensions()[elements]
    if i <= 0:
        return float(T[0])
    if i >= len(T):
        return float(T[-1])
    return float(0.5 * (T[i - 1] + T[i]))


def GetLineNodePos(instance: _Line, i: int) -> tuple[float, float, float]:
    """Position of node ``i`` (0: end A)."""
    node = instance.system.mesh.line_nodes[instance.index][i]
    return tuple(float(c) for c in instance.system.positions[node])


def GetLineNodeForce(instance: _Line, i: int) -> tuple[float, float, float]:
    """Force the line exerts on its end point (``i`` = 0: end A, ``i`` = N: end B), as
    :meth:`Coupling.end_forces`; interior nodes are not available."""
    n = GetLineN(instance)
    if i not in (0, n):
        raise ValueError("GetLineNodeForce: only the end nodes (0 and N) are available")
    f = instance.system.end_forces()[instance.index, 0 if i == 0 else 1]
    return tuple(float(c) for c in f)


def GetFASTtens(instance: Coupling, n_lines: int):
    """Horizontal and vertical fairlead (end B) and anchor (end A) tensions of the first
    ``n_lines`` lines (MoorDyn's ``GetFASTtens``)."""
    f = instance.end_forces()[:n_lines]
    horizontal = np.linalg.norm(f[..., :2], axis=-1)
    vertical = np.abs(f[..., 2])
    return (horizontal[:, 1].tolist(), vertical[:, 1].tolist(), horizontal[:, 0].tolist(),
            vertical[:, 0].tolist())


def GetStiffness(instance: Coupling) -> np.ndarray:
    """The coupled dofs' tangent (:meth:`Coupling.stiffness`; MoorDyn has none)."""
    return instance.stiffness()
