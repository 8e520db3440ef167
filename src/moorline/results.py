"""Result objects of the analyses and their datasets (:meth:`to_plain`: numpy arrays, what a run
writes; :meth:`to_xarray`: the same in xarray)."""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import numpy as np
from numpy.typing import NDArray

from .datasets import BODY_DOFS, build_plain, dynamics_dataset, group_attrs
from .envelope import line_coords, line_profile
from .mesh import Mesh
from .physics import seabed as seabed_physics
from .plain_dataset import PlainDataset, PlainResult
from .seabed_attrs import seabed_attrs
from .status import Status

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]

__all__ = ["BODY_DOFS", "DynamicResult", "HarmonicResult", "ModalResult", "StaticResult",
           "Status", "StochasticResult", "StrummingResult", "line_profile"]


def _settle_status(result: Any, ok: Status) -> None:
    """Set an empty ``status`` of a frozen result from its ``success``."""
    if not result.status:
        object.__setattr__(result, "status", str(ok if result.success else Status.FAILED))


@dataclass(frozen=True)
class StaticResult(PlainResult):
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
    status
        ``converged`` or ``failed`` (:class:`~moorline.datasets.Status`; set from ``success``
        when not given).
    settings
        The statics settings used (for the group's attributes), when known.
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
    status: str = ""
    settings: dict = field(default_factory=dict)

    def __post_init__(self) -> None:
        _settle_status(self, Status.CONVERGED)

    def body_position(self, body: str) -> FloatArray:
        """Position of a body's origin (3,)."""
        return self.body_pose[self.mesh.body_names.index(body), :3].copy()

    def body_rotation(self, body: str) -> FloatArray:
        """Rotation vector of a body [rad] (3,)."""
        return self.body_pose[self.mesh.body_names.index(body), 3:].copy()

    def pin_reaction(self, body: str) -> FloatArray:
        """Force of the pin on a pinned body (3,), world axes [force] (zeros for another
        body)."""
        reactions = self.extras.get("pin_reaction")
        if reactions is None:
            return np.zeros(3)
        return np.asarray(reactions[self.mesh.body_names.index(body)], dtype=float).copy()

    @property
    def counters(self) -> dict[str, int]:
        """``iterations``, ``load_steps``, ``n_residual``, ``n_tangent``, ``n_factorizations``."""
        return {"iterations": self.iterations, "load_steps": self.load_steps,
                "n_residual": self.n_residual, "n_tangent": self.n_tangent,
                "n_factorizations": self.n_factorizations}

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

    def max_tension(self, line: str) -> float:
        """The largest tension of a line, its end tensions included: the larger of its
        element tensions and the magnitudes of the forces on its two end points (the one
        meaning of "max tension" of the summary, the results file and the sweeps)."""
        ends = [float(np.linalg.norm(self.end_force(line, e))) for e in "ab"]
        return float(np.nanmax([*self.line_tension(line), *ends]))

    def end_force(self, line: str, end: str) -> FloatArray:
        """Force the line exerts on its end point ``end`` (``"a"`` or ``"b"``), shape (3,).

        The end element's axial force plus the share of the line's distributed loads lumped at
        the end node (half the end element's submerged weight): the nodal reaction of the
        finite element model, which converges as O(h^2) to the continuous line's end force.
        An end resting on the seabed (at or below its surface) where the line lies (pulls it
        down, not up) has the part of that force normal to the seabed (vertical on a flat
        seabed) carried by the seabed, as the
        closed-form catenary's end on the seabed
        (:class:`moorline.catenary.CatenarySolution`: ``V_a = 0`` where the line lies): the
        half element's weight and the pull of the neighbouring lying nodes, which rest a
        penalty penetration lower than an end held at the surface. With seabed friction
        (``extras["seabed_friction"]``, set by the statics) the seabed also takes up, from the
        line's horizontal pull, ``mu`` times that normal load (at most the pull), as the
        closed form's tension falls by ``mu w`` per length to the anchor.
        """
        m = self.mesh
        elements = m.line_elements[m.line_index(line)]
        if end not in ("a", "b"):
            raise ValueError(f"end must be 'a' or 'b', got {end!r}")
        e, side = (elements[0], 0) if end == "a" else (elements[-1], 1)
        force = self.element_forces[e, side].copy()
        force[2] -= 0.5 * m.weight_per_length[e] * m.length0[e]
        surface = m.seabed_surface
        node = self.positions[m.elements[e, side]][None]
        if surface is None or node[0, 2] > surface.height(node)[0]:
            return force
        unit = seabed_physics.surface_normal(node, surface)[0][0]
        along = float(force @ unit)
        if along <= 0.0:  # resting on the seabed, the line lying at it
            normal = -along
            force -= along * unit  # in the seabed's tangent plane
            pull = float(np.linalg.norm(force))
            friction = float(self.extras.get("seabed_friction", 0.0)) * normal
            if pull > 0.0 and friction > 0.0:
                force *= max(pull - friction, 0.0) / pull
        return force

    def point_position(self, point: str) -> FloatArray:
        """Position of a named point, (3,)."""
        return self.positions[self.mesh.point_node[self.mesh.point_index(point)]].copy()

    def seabed_length(self, line: str) -> float:
        """Unstretched length of the line resting on the seabed: the tributary lengths of its
        nodes, each times the share of its weight the seabed carries (:meth:`seabed_share`:
        the touchdown node counts in part). An end node held by a point (an anchor at the
        seabed surface) is carried by the point: it counts as much as its neighbour on the
        line, so a line leaving its anchor upwards has none on the seabed."""
        m = self.mesh
        k = m.line_index(line)
        nodes, elements = m.line_nodes[k], m.line_elements[k]
        if not np.isfinite(m.seabed_z):
            return 0.0
        tributary = np.zeros(len(nodes))
        tributary[:-1] += 0.5 * m.length0[elements]
        tributary[1:] += 0.5 * m.length0[elements]
        share = self.seabed_share()[nodes]
        if len(nodes) > 2:
            for end, neighbour in ((0, 1), (-1, -2)):
                if m.dof_of_node[nodes[end], 0] < 0:
                    share[end] = share[neighbour]
        return float(np.dot(tributary, share))

    def seabed_share(self) -> FloatArray:
        """Share of each node's own weight the seabed carries, (n_nodes,): 1 where the line
        lies, 0 where it hangs (computed once per result)."""
        return self._seabed_share.copy()

    @cached_property
    def _seabed_share(self) -> FloatArray:
        from .solvers.equilibrium import StaticModel

        return StaticModel(self.mesh).seabed_share(self.positions)

    def to_plain(self) -> PlainDataset:
        """The result as a dataset (dims node, element, xyz, line, end, point;
        :meth:`to_xarray`: in xarray).

        ``max_tension`` is the largest tension of each line, its end tensions included (as in
        the ``--json`` summary); the attribute ``seabed_z`` (``-inf`` without seabed) and the
        coordinate ``point_kind`` are there for the plots. Along the lines
        (:func:`moorline.envelope.line_coords`): ``line_nodes``, ``line_arc_length`` and the
        coordinates ``node_line``, ``node_arc_length``, ``element_arc_length``
        (:func:`line_profile` gives one line in order). Attributes: those of every group
        (:func:`moorline.datasets.group_attrs`), ``converged`` (= ``success``), ``method``.
        """
        m = self.mesh
        ends = np.array([[self.end_force(n, e) for e in "ab"] for n in m.line_names])
        ends = ends.reshape(len(m.line_names), 2, 3)
        end_tension = np.linalg.norm(ends, axis=2)
        max_tension = [self.max_tension(n) for n in m.line_names]
        data = {
            "position": (("node", "xyz"), self.positions),
            "tension": (("element",), self.tension),
            "end_force": (("line", "end", "xyz"), ends),
            "end_tension": (("line", "end"), end_tension),
            "max_tension": (("line",), max_tension),
            "seabed_length": (("line",), [self.seabed_length(n) for n in m.line_names]),
            "point_position": (("point", "xyz"), self.positions[m.point_node].reshape(-1, 3)),
            "residual_history": (("iteration",), self.residual_history),
            "element_nodes": (("element", "pair"), m.elements),
            "unstretched_length": (("element",), m.length0),
        }
        along, along_coords = line_coords(m)
        data.update(along)
        coords: dict[str, Any] = {
            "xyz": ["x", "y", "z"], "end": ["a", "b"], "line": list(m.line_names),
            "point": list(m.point_names), "point_kind": (("point",), list(m.point_kind)),
            "element_line": (("element",), [m.line_names[i] for i in m.element_line]),
            **along_coords,
        }
        if m.body_names:
            data["body_pose"] = (("body", "dof"), self.body_pose)
            coords.update(body=list(m.body_names), dof=list(BODY_DOFS))
        attrs = group_attrs("statics", case=self.case, units=self.units, success=self.success,
                            status=self.status, message=self.message, counters=self.counters,
                            settings=self.settings,
                            extra={"converged": int(self.success), "method": self.method,
                                   **seabed_attrs(m)})
        return build_plain("statics", data, coords, attrs)


@dataclass(frozen=True)
class DynamicResult(PlainResult):
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
    body_pose, body_velocity, body_mooring_force
        With bodies (n_t, n_bodies, 6), dofs :data:`~moorline.datasets.BODY_DOFS`.
    body_pin_force
        With bodies (n_t, n_bodies, 3): the force of the pin on each pinned body (zeros for
        the other bodies).
    status
        ``completed``, ``failed`` or ``interrupted`` (set from ``success`` when not given); a
        failed or interrupted run holds the records up to its last completed step.
    static_tension
        Element tensions of the static equilibrium the run started from (n_elements,);
        empty when it started from positions: the envelope's static value is then the
        first record's.
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
    body_pin_force: FloatArray = field(default_factory=lambda: np.zeros((0, 0, 3)))
    wave_elevation: FloatArray = field(default_factory=lambda: np.zeros(0))
    status: str = ""
    static_tension: FloatArray = field(default_factory=lambda: np.zeros(0))

    def __post_init__(self) -> None:
        _settle_status(self, Status.COMPLETED)

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

    def records(self) -> dict[str, FloatArray]:
        """The output records stacked over time, keyed as the solver's records (the input of
        :data:`moorline.datasets.DYNAMIC_VARIABLES`)."""
        n_t = len(self.time)
        elevation = (self.wave_elevation if len(self.wave_elevation) == n_t
                     else np.zeros(n_t))
        out = {"position": self.positions, "velocity": self.velocities,
               "tension": self.tension, "end_force": self.end_force,
               "wave_elevation": elevation, "body_pose": self.body_pose,
               "body_velocity": self.body_velocity,
               "body_mooring_force": self.body_mooring_force}
        if len(self.body_pin_force) == n_t:
            out["body_pin_force"] = self.body_pin_force
        return out

    def dataset_attrs(self) -> dict[str, Any]:
        """The attributes of the dynamics group (:func:`moorline.datasets.group_attrs` plus
        ``complete`` and ``seabed_z``): also what the stream closes its group with."""
        return group_attrs("dynamics", case=self.case, units=self.units, success=self.success,
                           status=self.status, message=self.message, counters=self.counters,
                           settings=self.settings,
                           extra={"complete": int(self.success),
                                  **seabed_attrs(self.mesh)})

    def to_plain(self) -> PlainDataset:
        """The histories as a dataset (dims time, node, element, xyz, line, end, point; body,
        dof with bodies; :meth:`to_xarray`: in xarray).

        The same variables, coordinates and attributes as the ``dynamics`` group that
        :class:`~moorline.io.stream.HistoryWriter` streams: both come from
        :data:`moorline.datasets.DYNAMIC_VARIABLES`, with the tension envelope
        (``tension_min``, ``tension_max``, ``tension_mean``, ``tension_std``,
        ``tension_static``; :mod:`moorline.envelope`) and the along-line coordinates.
        """
        return dynamics_dataset(self.mesh, self.time, self.records(), self.dataset_attrs(),
                                self.static_tension)


@dataclass(frozen=True)
class ModalResult(PlainResult):
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
    status
        ``converged`` or ``failed`` (set from ``success`` when not given).
    counters
        Solver counters besides ``n_dofs``.
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
    status: str = ""
    counters: dict = field(default_factory=dict)

    def __post_init__(self) -> None:
        _settle_status(self, Status.CONVERGED)

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

    def to_plain(self) -> PlainDataset:
        """The result as a dataset (dims mode, node, xyz, element, point; :meth:`to_xarray`:
        in xarray).

        The coordinate ``mode`` numbers the modes from 1; ``position`` is the static
        configuration and ``mode_shape(mode, node, xyz)`` the mass-normalized node
        displacements (for the plots: ``element_nodes`` and ``point_position`` too).
        """
        m = self.mesh
        data = {
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
            "point_position": (("point", "xyz"), self.positions[m.point_node].reshape(-1, 3)),
        }
        coords = {
            "mode": np.arange(1, self.n_modes + 1), "xyz": ["x", "y", "z"],
            "point": list(m.point_names), "point_kind": (("point",), list(m.point_kind)),
            "element_line": (("element",), [m.line_names[i] for i in m.element_line]),
        }
        attrs = group_attrs("modal", case=self.case, units=self.units, success=self.success,
                            status=self.status, message=self.message,
                            counters={"n_dofs": int(self.n_dofs), **self.counters},
                            settings=self.settings,
                            extra={"converged": int(self.success), "solver": self.solver,
                                   **seabed_attrs(m)})
        ds = build_plain("modal", data, coords, attrs)
        ds["mode_shape"].attrs["normalization"] = "phi^T M phi = 1"
        return ds


@dataclass(frozen=True)
class StrummingResult(PlainResult):
    """Histories of a strumming analysis (:func:`moorline.solvers.strumming.solve_strumming`),
    at the in-line steps.

    Attributes
    ----------
    time
        (n_t,).
    lift_coefficient, lift_rate
        ``C_L`` and ``C_L'`` per element (n_t, n_elements).
    modal_amplitude, modal_velocity
        ``z_n``, ``z_n'`` of the current modes (n_t, n_modes).
    displacement, velocity
        Strumming displacement and velocity of the nodes about the in-line state
        (n_t, n_nodes, 3), eq. 3.2.b.10.
    strouhal_frequency, normal_speed
        ``w_s`` and ``|V_NR|`` per element (n_t, n_elements), at the start of each in-line
        step (the last row repeats the one before).
    lift_direction
        Unit lift direction per element at the start (n_elements, 3).
    omega, mode_shapes, damping_ratio
        The last modes: frequencies (n_modes,), mass-normalized shapes (n_modes, n_nodes,
        3), eq. 3.2.b.8 damping ratios (n_modes,).
    omega_history, refresh_times
        Frequencies at every refresh (n_refresh, n_modes) and when.
    parameters
        Wake parameters per element at the start (:class:`~moorline.physics.wake.
        WakeParameters`).
    mesh, settings, counters
        What was solved and what it took.
    success, status, message, case, units
        How it ended (``completed``/``failed``) and for output.
    """

    time: FloatArray
    lift_coefficient: FloatArray
    lift_rate: FloatArray
    modal_amplitude: FloatArray
    modal_velocity: FloatArray
    displacement: FloatArray
    velocity: FloatArray
    strouhal_frequency: FloatArray
    normal_speed: FloatArray
    lift_direction: FloatArray
    omega: FloatArray
    mode_shapes: FloatArray
    damping_ratio: FloatArray
    omega_history: FloatArray
    refresh_times: FloatArray
    parameters: Any
    mesh: Mesh
    settings: Any
    counters: dict = field(default_factory=dict)
    success: bool = True
    status: str = ""
    message: str = ""
    case: str = ""
    units: str = "SI"

    def __post_init__(self) -> None:
        _settle_status(self, Status.COMPLETED)

    def node_displacement(self, node: int) -> FloatArray:
        """Strumming displacement history of one node (n_t, 3)."""
        return self.displacement[:, node]

    def to_plain(self) -> PlainDataset:
        """The histories as a dataset (:meth:`to_xarray`: in xarray).

        Returns
        -------
        PlainDataset
            ``lift_coefficient`` (time, element), ``modal_amplitude`` (time, mode),
            ``displacement`` (time, node, xyz: the transverse strumming displacement),
            ``strouhal_frequency`` and ``normal_speed`` (time, element), ``omega`` and
            ``damping_ratio`` (mode, numbered from 1); attributes ``CL0``, ``strouhal``.
        """
        data = {"lift_coefficient": (("time", "element"), self.lift_coefficient),
                "modal_amplitude": (("time", "mode"), self.modal_amplitude),
                "displacement": (("time", "node", "xyz"), self.displacement),
                "strouhal_frequency": (("time", "element"), self.strouhal_frequency),
                "normal_speed": (("time", "element"), self.normal_speed),
                "omega": (("mode",), self.omega),
                "damping_ratio": (("mode",), self.damping_ratio)}
        coords = {"time": self.time, "element": np.arange(self.mesh.n_elements),
                  "node": np.arange(self.mesh.n_nodes),
                  "mode": np.arange(1, len(self.omega) + 1), "xyz": ["x", "y", "z"]}
        attrs = group_attrs("strumming", case=self.case, units=self.units,
                            success=self.success, status=self.status, message=self.message,
                            counters=self.counters, settings=self.settings,
                            extra={"CL0": self.settings.CL0,
                                   "strouhal": self.settings.strouhal})
        return build_plain("strumming", data, coords, attrs)


@dataclass(frozen=True)
class StochasticResult(PlainResult):
    """Spectra, standard deviations and time series of the stochastic response
    (:func:`moorline.solvers.stochastic.solve_stochastic`).

    Attributes
    ----------
    omega, wave_spectrum, wave_amplitude
        Frequencies (n_w,), ``S(omega)`` and the realization's complex amplitudes ``A_m``.
    displacement_transfer
        Node displacement per unit wave amplitude (n_w, n_nodes, 3), complex.
    tension_transfer
        Element tension per unit wave amplitude (n_w, n_elements), complex.
    displacement_std, tension_std
        Standard deviations (n_nodes, 3) and (n_elements,).
    sigma_normal, sigma_tangential
        Converged standard deviations of the relative velocity per element.
    iterations, history
        Linearization iterations and the largest relative change of ``sigma`` per iteration.
    time, elevation, displacement, tension
        Time series over one record: (n_t,), (n_t,) at the origin, (n_t, n_nodes, 3),
        (n_t, n_elements).
    body_names, body_transfer, body_std, body_motion
        Free bodies: motion (:data:`~moorline.datasets.BODY_DOFS` about the body origin) per
        unit wave amplitude (n_w, n_bodies, 6), standard deviations (n_bodies, 6) and time
        series (n_t, n_bodies, 6).
    success, status, message, case, units
        How it ended (``converged``; ``failed`` when the linearization did not converge: the
        last iterate) and for output.
    """

    omega: FloatArray
    wave_spectrum: FloatArray
    wave_amplitude: ComplexArray
    displacement_transfer: ComplexArray
    tension_transfer: ComplexArray
    displacement_std: FloatArray
    tension_std: FloatArray
    sigma_normal: FloatArray
    sigma_tangential: FloatArray
    iterations: int
    history: list[float]
    time: FloatArray
    elevation: FloatArray
    displacement: FloatArray
    tension: FloatArray
    mesh: Mesh
    settings: Any
    d_omega: float
    body_names: tuple[str, ...] = ()
    body_transfer: ComplexArray = field(default_factory=lambda: np.zeros((0, 0, 6), complex))
    body_std: FloatArray = field(default_factory=lambda: np.zeros((0, 6)))
    body_motion: FloatArray = field(default_factory=lambda: np.zeros((0, 0, 6)))
    counters: dict = field(default_factory=dict)
    success: bool = True
    status: str = ""
    message: str = ""
    case: str = ""
    units: str = "SI"

    def __post_init__(self) -> None:
        _settle_status(self, Status.CONVERGED)

    def response_spectrum(self, transfer: ComplexArray) -> FloatArray:
        """``|H|^2 S(omega)`` of a transfer function (n_w, ...)."""
        shape = (-1,) + (1,) * (np.ndim(transfer) - 1)
        return np.abs(transfer) ** 2 * self.wave_spectrum.reshape(shape)

    def to_plain(self) -> PlainDataset:
        """Spectra (dim ``omega``), standard deviations and time series (dim ``time``)."""
        data = {"wave_spectrum": (("omega",), self.wave_spectrum),
                "displacement_spectrum": (("omega", "node", "xyz"),
                                          self.response_spectrum(self.displacement_transfer)),
                "tension_spectrum": (("omega", "element"),
                                     self.response_spectrum(self.tension_transfer)),
                "displacement_std": (("node", "xyz"), self.displacement_std),
                "tension_std": (("element",), self.tension_std),
                "sigma_normal": (("element",), self.sigma_normal),
                "sigma_tangential": (("element",), self.sigma_tangential),
                "elevation": (("time",), self.elevation),
                "displacement": (("time", "node", "xyz"), self.displacement),
                "tension": (("time", "element"), self.tension)}
        coords: dict[str, Any] = {
            "omega": self.omega, "time": self.time, "node": np.arange(self.mesh.n_nodes),
            "element": np.arange(self.mesh.n_elements), "xyz": ["x", "y", "z"]}
        if self.body_names:
            data.update(body_spectrum=(("omega", "body", "dof"),
                                       self.response_spectrum(self.body_transfer)),
                        body_std=(("body", "dof"), self.body_std),
                        body_motion=(("time", "body", "dof"), self.body_motion))
            coords.update(body=list(self.body_names), dof=list(BODY_DOFS))
        attrs = group_attrs("stochastic", case=self.case, units=self.units,
                            success=self.success, status=self.status, message=self.message,
                            counters={"iterations": self.iterations, **self.counters},
                            settings=self.settings,
                            extra={"method": self.settings.method, "d_omega": self.d_omega})
        return build_plain("stochastic", data, coords, attrs)


@dataclass(frozen=True)
class HarmonicResult(PlainResult):
    """The periodic response by harmonic balance (:func:`moorline.solvers.harmonic.
    solve_harmonic`).

    Attributes
    ----------
    period, omega
        Period and fundamental circular frequency.
    coefficients
        Node position coefficients (2 n + 1, n_nodes, 3): the mean, then ``A_k``, ``B_k``.
    time, positions, tension
        One period of the response: (n_t,), (n_t, n_nodes, 3), (n_t, n_elements).
    static_positions
        The static state linearized from (n_nodes, 3).
    iterations, residual_history
        Newton iterations and the largest harmonic residual after each.
    success, status, message, case, units
        How it ended (``converged`` or ``failed``) and for output.
    body_coefficients
        Per body (2 n + 1, n_bodies, 6): coefficients of the origin and of the rotation
        vector relative to the static orientation (``R = exp([phi x]) R_static``).
    body_pose
        One period of the bodies' poses (n_t, n_bodies, 6): origin and rotation vector.
    """

    period: float
    omega: float
    coefficients: FloatArray
    time: FloatArray
    positions: FloatArray
    tension: FloatArray
    static_positions: FloatArray
    iterations: int
    residual_history: list[float]
    mesh: Mesh
    settings: Any
    counters: dict = field(default_factory=dict)
    success: bool = True
    status: str = ""
    message: str = ""
    case: str = ""
    units: str = "SI"
    body_coefficients: FloatArray = field(default_factory=lambda: np.zeros((0, 0, 6)))
    body_pose: FloatArray = field(default_factory=lambda: np.zeros((0, 0, 6)))

    def __post_init__(self) -> None:
        _settle_status(self, Status.CONVERGED)

    def body_amplitude(self, body: str, harmonic: int = 1) -> FloatArray:
        """Amplitude ``sqrt(A_k^2 + B_k^2)`` of harmonic ``k`` of a body's six dofs."""
        b = self.mesh.body_names.index(body)
        a, c = (self.body_coefficients[2 * harmonic - 1 + i, b] for i in (0, 1))
        return np.sqrt(a * a + c * c)

    def amplitude(self, harmonic: int = 1) -> FloatArray:
        """Amplitude ``sqrt(A_k^2 + B_k^2)`` of harmonic ``k`` per node and axis."""
        a, b = self.coefficients[2 * harmonic - 1], self.coefficients[2 * harmonic]
        return np.sqrt(a * a + b * b)

    def to_plain(self) -> PlainDataset:
        """Coefficients (dim ``term``), one period of positions and tensions (dim ``time``)."""
        n = self.settings.harmonics
        terms = ["mean"] + [f"{p}{k}" for k in range(1, n + 1) for p in ("cos", "sin")]
        data = {"coefficients": (("term", "node", "xyz"), self.coefficients),
                "position": (("time", "node", "xyz"), self.positions),
                "tension": (("time", "element"), self.tension),
                "static_position": (("node", "xyz"), self.static_positions)}
        coords = {"term": terms, "time": self.time, "node": np.arange(self.mesh.n_nodes),
                  "element": np.arange(self.mesh.n_elements), "xyz": ["x", "y", "z"]}
        if self.mesh.body_names and len(self.body_pose):
            data["body_coefficients"] = (("term", "body", "dof"), self.body_coefficients)
            data["body_pose"] = (("time", "body", "dof"), self.body_pose)
            coords.update(body=list(self.mesh.body_names), dof=list(BODY_DOFS))
        attrs = group_attrs("harmonic", case=self.case, units=self.units,
                            success=self.success, status=self.status, message=self.message,
                            counters={"iterations": self.iterations, **self.counters},
                            settings=self.settings,
                            extra={"period": self.period, "harmonics": n})
        return build_plain("harmonic", data, coords, attrs)
