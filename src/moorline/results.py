"""Result objects of the analyses and their conversion to xarray datasets."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from . import __version__
from .mesh import Mesh

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class StaticResult:
    """Outcome of a static analysis.

    Attributes
    ----------
    success, message
        Whether the solver converged, and how it ended.
    method
        ``newton``, ``incremental`` or ``relaxation``.
    iterations
        Total iterations (Newton iterations, load increments or relaxation steps).
    load_steps
        Number of load increments.
    residual_history
        Max-norm of the out-of-balance force after each iteration [force].
    n_residual, n_tangent, n_factorizations
        Counters of residual evaluations, tangent assemblies and sparse factorizations.
    positions
        Node positions (n_nodes, 3).
    tension
        Element tensions (n_elements,).
    element_forces
        Force of each element on its two nodes (n_elements, 2, 3).
    mesh
        The mesh solved.
    case, units
        Case name and unit system (for output).
    """

    success: bool
    message: str
    method: str
    iterations: int
    load_steps: int
    residual_history: FloatArray
    n_residual: int
    n_tangent: int
    n_factorizations: int
    positions: FloatArray
    tension: FloatArray
    element_forces: FloatArray
    mesh: Mesh
    case: str = ""
    units: str = "SI"
    extras: dict = field(default_factory=dict)
    body_pose: FloatArray = field(default_factory=lambda: np.zeros((0, 6)))
    current_drag: bool = False

    def body_position(self, body: str) -> FloatArray:
        """Position of a body's origin (3,)."""
        return self.body_pose[self.mesh.body_names.index(body), :3].copy()

    def body_rotation(self, body: str) -> FloatArray:
        """Rotation vector of a body [rad] (3,)."""
        return self.body_pose[self.mesh.body_names.index(body), 3:].copy()

    @property
    def residual(self) -> float:
        """Final max-norm of the out-of-balance force."""
        return float(self.residual_history[-1]) if len(self.residual_history) else np.nan

    def line_positions(self, line: str) -> FloatArray:
        """Node positions along a line from end A to end B, (segments + 1, 3)."""
        return self.positions[self.mesh.line_nodes[self.mesh.line_index(line)]]

    def line_tension(self, line: str) -> FloatArray:
        """Element tensions along a line from end A to end B, (segments,)."""
        return self.tension[self.mesh.line_elements[self.mesh.line_index(line)]]

    def end_force(self, line: str, end: str) -> FloatArray:
        """Force the line exerts on its end point ``end`` (``"a"`` or ``"b"``), shape (3,).

        The end element's axial force plus the share of the line's distributed loads lumped at
        the end node (half the end element's submerged weight, less the seabed's support of
        that half when the node rests on the seabed): the nodal reaction of the finite element
        model, which converges as O(h^2) to the continuous line's end force.
        """
        m = self.mesh
        elements = m.line_elements[m.line_index(line)]
        if end not in ("a", "b"):
            raise ValueError(f"end must be 'a' or 'b', got {end!r}")
        e, side = (elements[0], 0) if end == "a" else (elements[-1], 1)
        force = self.element_forces[e, side].copy()
        force[2] -= 0.5 * m.weight_per_length[e] * m.length0[e]
        penetration = m.seabed_z - self.positions[m.elements[e, side], 2]
        if np.isfinite(m.seabed_z) and penetration > 0:
            area = 0.5 * m.length0[e] * m.diameter[e]
            force[2] += m.seabed_stiffness_per_area * area * penetration
        return force

    def point_position(self, point: str) -> FloatArray:
        """Position of a named point, (3,)."""
        return self.positions[self.mesh.point_node[self.mesh.point_index(point)]].copy()

    def seabed_length(self, line: str) -> float:
        """Unstretched length of the line resting on the seabed: the tributary lengths of its
        nodes below the seabed plane (resolution: one element)."""
        m = self.mesh
        k = m.line_index(line)
        nodes, elements = m.line_nodes[k], m.line_elements[k]
        if not np.isfinite(m.seabed_z):
            return 0.0
        tributary = np.zeros(len(nodes))
        tributary[:-1] += 0.5 * m.length0[elements]
        tributary[1:] += 0.5 * m.length0[elements]
        touching = self.positions[nodes, 2] < m.seabed_z
        return float(tributary[touching].sum())

    def to_xarray(self) -> xr.Dataset:
        """The result as an :class:`xarray.Dataset` (dims node, element, xyz, line, end, point).

        ``max_tension`` is the largest tension of each line, its end tensions included (as in
        the ``--json`` summary); the attribute ``seabed_z`` (``-inf`` without seabed) and the
        coordinate ``point_kind`` are there for the plots.
        """
        m = self.mesh
        ends = np.array([[self.end_force(n, e) for e in "ab"] for n in m.line_names])
        ends = ends.reshape(len(m.line_names), 2, 3)
        end_tension = np.linalg.norm(ends, axis=2)
        max_tension = [float(np.nanmax([*self.line_tension(n), *end_tension[k]]))
                       for k, n in enumerate(m.line_names)]
        ds = xr.Dataset(
            {
                "position": (("node", "xyz"), self.positions),
                "tension": (("element",), self.tension),
                "end_force": (("line", "end", "xyz"), ends),
                "end_tension": (("line", "end"), end_tension),
                "max_tension": (("line",), max_tension),
                "seabed_length": (("line",), [self.seabed_length(n) for n in m.line_names]),
                "point_position": (("point", "xyz"),
                                   self.positions[m.point_node].reshape(-1, 3)),
                "residual_history": (("iteration",), self.residual_history),
                "element_nodes": (("element", "pair"), m.elements),
                "unstretched_length": (("element",), m.length0),
            },
            coords={
                "xyz": ["x", "y", "z"], "end": ["a", "b"], "line": list(m.line_names),
                "point": list(m.point_names),
                "point_kind": (("point",), list(m.point_kind)),
                "element_line": (("element",), [m.line_names[i] for i in m.element_line]),
            },
            attrs={
                "analysis": "statics", "case": self.case, "units": self.units,
                "seabed_z": float(m.seabed_z),
                "moorline_version": __version__, "method": self.method,
                "converged": int(self.success), "message": self.message,
                "iterations": self.iterations, "load_steps": self.load_steps,
                "n_residual": self.n_residual, "n_tangent": self.n_tangent,
                "n_factorizations": self.n_factorizations,
            },
        )
        ds["position"].attrs["units"] = "length"
        ds["tension"].attrs["units"] = "force"
        if m.body_names:
            ds["body_pose"] = (("body", "dof"), self.body_pose)
            ds = ds.assign_coords(body=list(m.body_names),
                                  dof=["x", "y", "z", "rx", "ry", "rz"])
        return ds


@dataclass(frozen=True)
class DynamicResult:
    """Outcome of a time-domain analysis.

    Attributes
    ----------
    success, message
        Whether the run reached its end, and how it ended.
    time
        Output times (n_t,).
    positions, velocities
        Node positions and velocities (n_t, n_nodes, 3).
    tension
        Element tensions (n_t, n_elements).
    end_force
        Force each line exerts on its end points (n_t, n_lines, 2, 3).
    counters
        ``steps``, ``iterations``, ``residuals``, ``tangents``, ``factorizations``,
        ``step_cuts``.
    mesh, case, units, settings
        What was solved, for output.
    """

    success: bool
    message: str
    time: FloatArray
    positions: FloatArray
    velocities: FloatArray
    tension: FloatArray
    end_force: FloatArray
    counters: dict
    mesh: Mesh
    case: str = ""
    units: str = "SI"
    settings: dict = field(default_factory=dict)
    body_pose: FloatArray = field(default_factory=lambda: np.zeros((0, 0, 6)))
    body_velocity: FloatArray = field(default_factory=lambda: np.zeros((0, 0, 6)))
    body_mooring_force: FloatArray = field(default_factory=lambda: np.zeros((0, 0, 6)))
    wave_elevation: FloatArray = field(default_factory=lambda: np.zeros(0))

    def body_history(self, body: str) -> FloatArray:
        """Pose history of a body (n_t, 6): position and rotation vector."""
        return self.body_pose[:, self.mesh.body_names.index(body)]

    def end_tension(self, line: str, end: str = "b") -> FloatArray:
        """Tension history at one end of a line (n_t,)."""
        k = self.mesh.line_index(line)
        return np.linalg.norm(self.end_force[:, k, "ab".index(end)], axis=-1)

    def point_history(self, point: str) -> FloatArray:
        """Position history of a named point (n_t, 3)."""
        return self.positions[:, self.mesh.point_node[self.mesh.point_index(point)]]

    def to_xarray(self) -> xr.Dataset:
        """The histories as an :class:`xarray.Dataset` (dims time, node, element, xyz, line,
        end, point).

        The same variables, coordinates and attributes as the ``dynamics`` group that
        :class:`~moorline.io.stream.HistoryWriter` streams, plus ``end_tension`` and
        ``fairlead_tension`` (end B).
        """
        m = self.mesh
        end_tension = np.linalg.norm(self.end_force, axis=-1)
        ds = xr.Dataset(
            {
                "position": (("time", "node", "xyz"), self.positions),
                "velocity": (("time", "node", "xyz"), self.velocities),
                "tension": (("time", "element"), self.tension),
                "end_force": (("time", "line", "end", "xyz"), self.end_force),
                "end_tension": (("time", "line", "end"), end_tension),
                "fairlead_tension": (("time", "line"), end_tension[:, :, 1]),
                "wave_elevation": (("time",), self.wave_elevation if len(self.wave_elevation)
                                   == len(self.time) else np.zeros(len(self.time))),
                "element_nodes": (("element", "pair"), m.elements),
                "point_node": (("point",), np.asarray(m.point_node, dtype=np.int64)),
            },
            coords={
                "time": self.time, "xyz": ["x", "y", "z"], "end": ["a", "b"],
                "line": list(m.line_names), "point": list(m.point_names),
                "point_kind": (("point",), list(m.point_kind)),
                "element_line": (("element",), [m.line_names[i] for i in m.element_line]),
            },
            attrs={
                "analysis": "dynamics", "case": self.case, "units": self.units,
                "moorline_version": __version__, "success": int(self.success),
                "complete": int(self.success), "message": self.message,
                "seabed_z": float(m.seabed_z),
                **{k: v for k, v in self.counters.items()},
                **{f"setting_{k}": v for k, v in self.settings.items()},
            },
        )
        if m.body_names:
            ds["body_pose"] = (("time", "body", "dof"), self.body_pose)
            ds["body_velocity"] = (("time", "body", "dof"), self.body_velocity)
            ds["body_mooring_force"] = (("time", "body", "dof"), self.body_mooring_force)
            ds = ds.assign_coords(body=list(m.body_names),
                                  dof=["x", "y", "z", "rx", "ry", "rz"])
        return ds


@dataclass(frozen=True)
class ModalResult:
    """Natural frequencies and mode shapes about a static equilibrium
    (:func:`moorline.solvers.modal.solve_modes`).

    Attributes
    ----------
    success, message
        Whether the eigensolver succeeded, and what it found.
    omega
        Circular natural frequencies [rad/time] (n_modes,), ascending. A negative value marks
        a negative eigenvalue ``-omega^2`` (an unstable equilibrium).
    mode_shapes
        Node displacements of each mode (n_modes, n_nodes, 3), zero at fixed and prescribed
        nodes; mass-normalized: ``phi^T M phi = 1`` over the free dofs.
    participation
        Share of ``sum_i m_i phi_i^2`` (``m_i`` the diagonal of the mass matrix) on the x, y
        and z dofs (n_modes, 3); rows sum to 1.
    effective_mass
        Effective modal mass along x, y, z, ``(phi^T M r_d)^2`` [mass] (n_modes, 3).
    dominant
        Direction (``"x"``, ``"y"`` or ``"z"``) with the largest participation share, per mode.
    positions, tension
        The static equilibrium linearized about: node positions (n_nodes, 3) and element
        tensions (n_elements,).
    mesh, case, units
        What was solved, for output.
    solver
        ``dense`` (LAPACK, all eigenvalues) or ``shift-invert`` (ARPACK).
    n_dofs
        Number of free degrees of freedom.
    settings
        The modal settings used (``n_modes``, ``band``, ``mass``, ``added_mass``).
    """

    success: bool
    message: str
    omega: FloatArray
    mode_shapes: FloatArray
    participation: FloatArray
    effective_mass: FloatArray
    dominant: tuple[str, ...]
    positions: FloatArray
    tension: FloatArray
    mesh: Mesh
    case: str = ""
    units: str = "SI"
    solver: str = ""
    n_dofs: int = 0
    settings: dict = field(default_factory=dict)

    @property
    def n_modes(self) -> int:
        """Number of modes."""
        return len(self.omega)

    @property
    def period(self) -> FloatArray:
        """Natural periods ``2 pi / omega`` [time] (``inf`` for ``omega <= 0``)."""
        with np.errstate(divide="ignore"):
            return np.where(self.omega > 0, 2 * np.pi / np.abs(self.omega), np.inf)

    @property
    def frequency_hz(self) -> FloatArray:
        """Natural frequencies ``omega / (2 pi)`` [1/time]."""
        return self.omega / (2 * np.pi)

    def modes_of(self, direction: str) -> NDArray[np.int64]:
        """Indices (0-based, ascending frequency) of the modes dominated by ``direction``."""
        return np.array([i for i, d in enumerate(self.dominant) if d == direction],
                        dtype=np.int64)

    def to_xarray(self) -> xr.Dataset:
        """The result as an :class:`xarray.Dataset` (dims mode, node, xyz, element, point).

        The coordinate ``mode`` numbers the modes from 1; ``position`` is the static
        configuration and ``mode_shape(mode, node, xyz)`` the mass-normalized node
        displacements (for the plots: ``element_nodes`` and ``point_position`` too).
        """
        m = self.mesh
        settings = {f"setting_{k}": (v if v is not None else "none") if not isinstance(v, bool)
                    else int(v) for k, v in self.settings.items() if k != "band"}
        band = self.settings.get("band")
        if band is not None:
            settings.update(setting_band_low=float(band[0]), setting_band_high=float(band[1]))
        ds = xr.Dataset(
            {
                "omega": (("mode",), self.omega),
                "period": (("mode",), self.period),
                "frequency_hz": (("mode",), self.frequency_hz),
                "dominant": (("mode",), np.array(self.dominant, dtype=str)),
                "participation": (("mode", "xyz"), self.participation),
                "effective_mass": (("mode", "xyz"), self.effective_mass),
                "mode_shape": (("mode", "node", "xyz"), self.mode_shapes),
                "position": (("node", "xyz"), self.positions),
                "tension": (("element",), self.tension),
                "element_nodes": (("element", "pair"), m.elements),
                "point_position": (("point", "xyz"),
                                   self.positions[m.point_node].reshape(-1, 3)),
            },
            coords={
                "mode": np.arange(1, self.n_modes + 1), "xyz": ["x", "y", "z"],
                "point": list(m.point_names), "point_kind": (("point",), list(m.point_kind)),
                "element_line": (("element",), [m.line_names[i] for i in m.element_line]),
            },
            attrs={
                "analysis": "modal", "case": self.case, "units": self.units,
                "moorline_version": __version__, "seabed_z": float(m.seabed_z),
                "converged": int(self.success), "message": self.message,
                "solver": self.solver, "n_dofs": int(self.n_dofs), **settings,
            },
        )
        ds["omega"].attrs["units"] = "rad/time"
        ds["period"].attrs["units"] = "time"
        ds["frequency_hz"].attrs["units"] = "1/time"
        ds["effective_mass"].attrs["units"] = "mass"
        ds["mode_shape"].attrs["normalization"] = "phi^T M phi = 1"
        return ds
