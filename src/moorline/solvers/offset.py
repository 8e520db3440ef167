"""Offset analysis: a body, or a rigid group of prescribed points, moved through horizontal
offsets along headings (and optionally turned in yaw), the lines in static equilibrium at
every offset; the restoring force and moment, line tensions, touchdown and stiffness along
the way (the offset and tension-offset curves of a mooring study, API RP 2SK sec. 6).

The group moves rigidly: a displacement ``q = (t, phi)`` (translation of the reference
point, small-or-not rotation vector about it) takes a point at ``x`` to
``ref + t + R(phi) (x - ref)``. A body is held at each pose (all six dofs prescribed, its
hydrostatics and weight play no part: the restoring force is the mooring's alone); prescribed
points are moved to their new positions. Each offset is solved by
:func:`moorline.solvers.statics.solve_statics` from the previous one's node positions (a
warm start), outwards from the undisplaced state in both directions. The stiffness at each
offset is :func:`moorline.solvers.stiffness.group_stiffness` about the moved reference point.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import NDArray

from ..errors import CaseError
from ..mesh import Mesh
from ..model import OffsetSettings, StaticsSettings, System
from ..offset_group import OffsetGroup, OffsetGroupError, resolve_group
from ..offset_result import OffsetResult
from ..physics.rigid_body import rotation_matrix, rotation_vector
from ..results import StaticResult
from .equilibrium import StaticModel
from .statics import equilibrium_for, solve_statics
from .stiffness import group_stiffness, rigid_map

FloatArray = NDArray[np.float64]

__all__ = ["OffsetGroupState", "Sweep", "group_of", "group_reference", "moved_mesh",
           "solve_offset", "sweep"]


def group_of(system: System, settings: OffsetSettings) -> OffsetGroup:
    """The group ``settings`` moves (:func:`moorline.offset_group.resolve_group`).

    Raises
    ------
    CaseError
        Naming the setting at fault.
    """
    try:
        return resolve_group(system.points, system.bodies, settings.body, settings.points)
    except OffsetGroupError as exc:
        raise CaseError(str(exc), field=f"offset.{exc.key}") from None


def group_reference(result: StaticResult, group: OffsetGroup,
                    reference: tuple[float, float, float] | None = None) -> FloatArray:
    """The reference point of a group at a static state: ``reference`` when given, else the
    body origin or the centroid of the points."""
    if reference is not None:
        return np.asarray(reference, dtype=float)
    if group.body is not None:
        return result.body_position(group.body)
    return np.mean([result.point_position(p) for p in group.points], axis=0)


@dataclass(frozen=True)
class OffsetGroupState:
    """The group at its undisplaced static state: what every offset moves from.

    Attributes
    ----------
    group
        The body or points moved.
    nodes
        Node of each of the group's points.
    positions
        Their positions at the undisplaced state (n, 3).
    reference
        The reference point there (3,).
    body_pose
        The body's pose there (position, rotation vector), ``None`` for points.
    """

    group: OffsetGroup
    nodes: tuple[int, ...]
    positions: FloatArray
    reference: FloatArray
    body_pose: FloatArray | None

    @classmethod
    def of(cls, result: StaticResult, group: OffsetGroup,
           reference: tuple[float, float, float] | None = None) -> OffsetGroupState:
        """The group at the static state ``result``."""
        mesh = result.mesh
        nodes = tuple(int(mesh.point_node[mesh.point_index(p)]) for p in group.points)
        pose = (None if group.body is None
                else result.body_pose[mesh.body_names.index(group.body)].copy())
        return cls(group, nodes, result.positions[list(nodes)].copy(),
                   group_reference(result, group, reference), pose)


def moved_mesh(mesh: Mesh, state: OffsetGroupState, q: FloatArray) -> tuple[Mesh, FloatArray]:
    """The mesh with the group displaced by ``q = (t, phi)`` and the moved reference point.

    A body becomes ``fixed`` at its displaced pose; prescribed points get their displaced
    positions as targets.
    """
    t, R = np.asarray(q[:3], dtype=float), rotation_matrix(np.asarray(q[3:], dtype=float))
    ref = state.reference

    def move(x: FloatArray) -> FloatArray:
        return ref + t + (np.asarray(x, dtype=float) - ref) @ R.T

    if state.body_pose is None:
        position = mesh.node_position.copy()
        position[list(state.nodes)] = move(state.positions)
        return replace(mesh, node_position=position), ref + t
    b = mesh.body_names.index(state.group.body)
    origin = move(state.body_pose[:3])
    rotation = rotation_vector(R @ rotation_matrix(state.body_pose[3:]))
    bodies = list(mesh.bodies)
    bodies[b] = replace(bodies[b], kind="fixed", position=tuple(float(v) for v in origin),
                        rotation=tuple(float(v) for v in rotation))
    return replace(mesh, bodies=tuple(bodies)), ref + t


@dataclass
class Sweep:
    """The states of one sweep of displacements (``n`` of them).

    Attributes
    ----------
    displacement
        The imposed displacements ``(t, phi)`` (n, 6) [length, rad].
    restoring_force
        Force and moment of the lines on the group about the moved reference point (n, 6):
        the nodal forces on the group's points (lines, seabed and the points' own loads).
    fairlead_tension, anchor_tension
        Tension at each line's fairlead (the end on the group; end b for a line not on it)
        and at its other end (n, n_lines).
    seabed_length, suspended_length
        Unstretched length of each line on the seabed and off it (n, n_lines).
    touchdown_distance
        Horizontal distance from the anchor to the touchdown point (the lying node farthest
        along the line from the anchor; one element's resolution), NaN where the line does
        not touch the seabed (n, n_lines).
    stiffness
        The 6x6 stiffness at each state (n, 6, 6), NaN where not computed.
    converged, iterations
        Per state; a failed state ends its side of the sweep (the states beyond it NaN).
    """

    displacement: FloatArray
    restoring_force: FloatArray
    fairlead_tension: FloatArray
    anchor_tension: FloatArray
    seabed_length: FloatArray
    suspended_length: FloatArray
    touchdown_distance: FloatArray
    stiffness: FloatArray
    converged: NDArray[np.bool_]
    iterations: NDArray[np.int64]
    messages: list[str]

    @classmethod
    def empty(cls, displacement: FloatArray, n_lines: int) -> Sweep:
        """A sweep of the given displacements, nothing solved yet."""
        n = len(displacement)

        def nan(*shape: int) -> FloatArray:
            return np.full((n, *shape), np.nan)

        return cls(np.asarray(displacement, dtype=float), nan(6), nan(n_lines), nan(n_lines),
                   nan(n_lines), nan(n_lines), nan(n_lines), nan(6, 6),
                   np.zeros(n, dtype=bool), np.zeros(n, dtype=np.int64), [""] * n)


def fairlead_ends(mesh: Mesh, nodes: tuple[int, ...]) -> tuple[str, ...]:
    """Per line, the end (``"a"`` or ``"b"``) on the group: the fairlead (end b when the line
    is not on the group)."""
    on = set(nodes)
    return tuple("a" if int(ln[0]) in on and int(ln[-1]) not in on else "b"
                 for ln in mesh.line_nodes)


def _record(out: Sweep, k: int, result: StaticResult, state: OffsetGroupState,
            reference: FloatArray, ends: tuple[str, ...], with_stiffness: bool) -> None:
    """Store the state ``result`` as state ``k`` of the sweep."""
    mesh = result.mesh
    nodes = list(state.nodes)
    forces = StaticModel(mesh, exact_cable=True).forces(result.positions).nodal[nodes]
    arms = result.positions[nodes] - reference
    out.restoring_force[k] = rigid_map(arms).T @ forces.ravel()
    for j, (name, end) in enumerate(zip(mesh.line_names, ends, strict=True)):
        other = "a" if end == "b" else "b"
        out.fairlead_tension[k, j] = np.linalg.norm(result.end_force(name, end))
        out.anchor_tension[k, j] = np.linalg.norm(result.end_force(name, other))
        on_seabed = result.seabed_length(name)
        out.seabed_length[k, j] = on_seabed
        out.suspended_length[k, j] = float(mesh.length0[mesh.line_elements[j]].sum()) - on_seabed
        out.touchdown_distance[k, j] = _touchdown(result, j, other)
    if with_stiffness:
        out.stiffness[k] = group_stiffness(result, list(state.group.points), reference)


def _touchdown(result: StaticResult, line: int, anchor_end: str) -> float:
    """Horizontal distance from the anchor end of a line to its lying node farthest along
    the line from it (the seabed carrying at least half its weight; NaN when none)."""
    mesh = result.mesh
    nodes = mesh.line_nodes[line]
    if anchor_end == "b":
        nodes = nodes[::-1]
    x = result.positions[nodes]
    lying = np.flatnonzero(result.seabed_share()[nodes] >= 0.5)
    if not lying.size:
        return float("nan")
    return float(np.hypot(*(x[lying[-1], :2] - x[0, :2])))


def sweep(system: System, base: StaticResult, state: OffsetGroupState, displacement: FloatArray,
          statics: StaticsSettings, with_stiffness: bool = True) -> Sweep:
    """Statics at each displacement of a sweep whose middle one is zero, walking outwards
    from it in both directions, each state from the previous one's node positions.

    Parameters
    ----------
    system
        The case.
    base
        The undisplaced static state (its node positions start the walk).
    state
        The group at ``base``.
    displacement
        (n, 6) displacements, ``n`` odd, ``displacement[n // 2] == 0``.
    statics
        The statics settings of every solve.
    with_stiffness
        Compute the 6x6 stiffness at each converged state.
    """
    mesh = base.mesh
    ends = fairlead_ends(mesh, state.nodes)
    out = Sweep.empty(displacement, len(mesh.line_names))
    middle = len(displacement) // 2
    for side in (range(middle, len(displacement)), range(middle - 1, -1, -1)):
        x = base.positions
        for k in side:
            moved, reference = moved_mesh(mesh, state, out.displacement[k])
            result = solve_statics(system, statics, initial=x, mesh=moved)
            out.converged[k], out.iterations[k] = result.success, result.iterations
            out.messages[k] = result.message
            if not result.success:
                break
            _record(out, k, result, state, reference, ends, with_stiffness)
            x = result.positions
    return out


def solve_offset(system: System, settings: OffsetSettings,
                 statics: StaticResult | None = None) -> OffsetResult:
    """The offset analysis of ``system`` (see the module docstring).

    Parameters
    ----------
    system
        The case.
    settings
        Headings, offsets, yaw, the group and its reference point.
    statics
        The undisplaced static state (the run's statics); solved here when ``None``.

    Raises
    ------
    CaseError
        When the group cannot be moved (unknown body or point, a point not prescribed).
    ConvergenceError
        When the undisplaced statics does not converge.
    """
    group = group_of(system, settings)
    base = equilibrium_for(system, statics, "offset analysis")
    state = OffsetGroupState.of(base, group, settings.reference)
    solve = replace(system.first(StaticsSettings), load_steps=1)
    offsets = np.linspace(-settings.max_offset, settings.max_offset, settings.steps)
    sweeps = []
    for heading in settings.headings:
        q = np.zeros((settings.steps, 6))
        h = np.radians(heading)
        q[:, 0], q[:, 1] = offsets * np.cos(h), offsets * np.sin(h)
        sweeps.append(sweep(system, base, state, q, solve, settings.stiffness))
    yaw = None
    if settings.yaw:
        q = np.zeros((settings.steps, 6))
        q[:, 5] = np.radians(np.linspace(-settings.max_yaw, settings.max_yaw, settings.steps))
        yaw = sweep(system, base, state, q, solve, settings.stiffness)
    every = [*sweeps, *([yaw] if yaw else [])]
    unsolved = sum(int((~s.converged).sum()) for s in every)
    failed = [(s, k) for s in every for k in np.flatnonzero(~s.converged) if s.messages[k]]
    if unsolved:
        s, k = failed[0]
        message = (f"{unsolved} of {sum(len(s.converged) for s in every)} offsets not solved "
                   "(a failed offset ends its side of the sweep); failed at displacement "
                   f"{np.round(s.displacement[k], 6).tolist()}: {s.messages[k]}")
    else:
        solved = sum(len(s.converged) for s in every)
        message = f"{solved} offsets solved"
    return OffsetResult(
        success=not unsolved, message=message, group=group, reference=state.reference,
        headings=tuple(float(h) for h in settings.headings), offsets=offsets, sweeps=sweeps,
        yaw_angles=np.linspace(-settings.max_yaw, settings.max_yaw, settings.steps)
        if yaw else np.zeros(0), yaw=yaw, line_names=base.mesh.line_names,
        fairlead_end=fairlead_ends(base.mesh, state.nodes), case=system.name,
        units=system.units, settings=settings)
