"""Turn a :class:`~moorline.model.System` into arrays: nodes, elements, properties, dofs.

Node numbering: the named points first (in case order), then the interior nodes of each line
from end A to end B. Every array is 0-based. Fixed and prescribed nodes have no degrees of
freedom; ``dof_of_node[i, k] == -1`` marks them.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np
from numpy.typing import NDArray

from .model import System
from .physics import bending, element
from .physics.bathymetry import SeabedSurface, grid, plane
from .physics.load_strain import StrainLaws, StrainTable, dynamic_strain_law, strain_laws
from .physics.rigid_body import rotation_matrix
from .physics.syrope import SyropeElements, rope_of

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]
BoolArray = NDArray[np.bool_]


@dataclass(frozen=True)
class Mesh:
    """A discretized cable system. Plain arrays; nothing here changes after construction.

    Attributes
    ----------
    node_position
        Reference node positions (n_nodes, 3): points at their positions, line interior nodes
        on the straight chord (solvers replace them with a better initial shape).
    elements
        Node indices (n_elements, 2), from end A towards end B of each line.
    length0
        Unstretched element lengths (n_elements,).
    EA, EA1, tau, slack_ratio, slack_smoothing
        Axial stiffness [force] (of an element with a tension-strain table: its reference
        stiffness, see :class:`~moorline.model.LineType`), viscoelastic extra stiffness and
        time, slack stiffness ratio and the strain band of the smooth slack transition.
    BA
        Internal axial damping [force*time] (a negative line-type value, a damping ratio, is
        resolved here: ``BA = zeta L0 sqrt(EA m)``).
    viscoelastic
        Mask of elements made of the standard linear solid (n_elements,).
    mass_per_length, weight_per_length
        Dry mass per length and submerged weight per length (weight minus buoyancy, z down).
    diameter, Cd, Ca, Ct, Cat
        Hydrodynamic diameter and coefficients per element.
    element_line
        Line index of each element.
    line_names, line_nodes, line_elements
        Line ids and, per line, its node and element indices from end A to end B.
    point_names, point_kind, point_node
        Point ids, kinds and node index.
    node_mass, node_volume, node_force
        Lumped point mass [mass], displaced volume and constant external force per node.
    node_drag_area, node_Cd, node_Ca
        Point drag area, drag and added-mass coefficients per node (0 on line nodes).
    node_prescribed_start
        Where each node starts in a load-stepped statics (prescribed points may start elsewhere).
    dof_of_node
        Global dof number of each node's x, y, z, or -1 for fixed/prescribed nodes.
    seabed_z
        Seabed height (``-depth``; ``-inf`` without seabed); with ``bathymetry`` the reference
        height of the sloped or gridded seabed (its height at the origin for a plane).
    seabed_stiffness_per_area, seabed_damping_per_area
        Contact stiffness [force/length^3] and damping [force*time/length^3] per area.
    node_contact_area
        Diameter times tributary unstretched length of each node (n_nodes,).
    gravity, water_density
        Environment constants.
    body_names
        Body ids (their 6 dofs follow the node dofs in coupled solvers).
    slave_node, slave_body, slave_arm
        Nodes rigidly attached to bodies: node index, body index and position in the body
        frame (the master-slave transformation of Tuah 1982 eq. 3.3.6-3.3.7).
    bodies
        The rigid bodies (:class:`~moorline.model.Body`), in ``body_names`` order.
    bathymetry
        A sloped or gridded seabed (:class:`~moorline.physics.bathymetry.SeabedSurface`);
        ``None``: flat at ``seabed_z`` (see :attr:`seabed_surface`).
    point_motion, point_force_history
        Per point: its prescribed motion and its force history (``None`` when it has none).
    strain_laws
        Tabulated tension-strain laws per element (:mod:`moorline.physics.load_strain`);
        ``None``: every element is linear (``EA``).
    strain_offset
        Strain offset of each element's law (:func:`dynamic_mesh`); ``None``: zero.
    EAd, EAd_Lm
        Fibre-rope dynamic stiffness per element (``EAd`` NaN where none).
    static_dynamic
        Elements of MoorDyn's viscoelastic rope (:mod:`moorline.physics.static_dynamic`):
        ``(alpha, beta, c1, c2)`` per element (n_elements, 4), NaN on other elements (their
        ``BA`` holds ``c1 c2 / (c1 + c2)``); ``None``: no such element.
    syrope
        Elements of MoorDyn's Syrope rope (:mod:`moorline.physics.syrope`; their ``BA`` holds
        ``c1 c2 / (c1 + c2)``, their table and strain offset the static law at ``Tmax0``);
        ``None``: no such element.
    bend_nodes, bend_elements, bend_stiffness
        Bending stiffness (:mod:`moorline.physics.bending`): the node triplets
        ``(i-1, i, i+1)`` of the interior nodes of lines with ``EI > 0`` (n_b, 3), their two
        elements (n_b, 2) and ``EI / Lbar`` [force*length] (n_b,); empty without bending.
    clamp_elements, clamp_direction, clamp_stiffness
        Clamped line ends: the end element (n_c,), the held unit tangent (n_c, 3) and
        ``EI / (L_e / 2)`` (n_c,); empty when every end is pinned.
    sag_corrected
        Elements of lines with ``element: sag_corrected`` (:mod:`moorline.physics.sag`)
        (n_elements,); ``None`` when every element is straight.
    """

    node_position: FloatArray
    elements: IntArray
    length0: FloatArray
    EA: FloatArray
    EA1: FloatArray
    tau: FloatArray
    slack_ratio: FloatArray
    slack_smoothing: FloatArray
    BA: FloatArray
    viscoelastic: BoolArray
    mass_per_length: FloatArray
    weight_per_length: FloatArray
    diameter: FloatArray
    Cd: FloatArray
    Ca: FloatArray
    Ct: FloatArray
    Cat: FloatArray
    element_line: IntArray
    line_names: tuple[str, ...]
    line_nodes: tuple[IntArray, ...]
    line_elements: tuple[IntArray, ...]
    point_names: tuple[str, ...]
    point_kind: tuple[str, ...]
    point_node: IntArray
    node_mass: FloatArray
    node_volume: FloatArray
    node_force: FloatArray
    node_drag_area: FloatArray
    node_Cd: FloatArray
    node_Ca: FloatArray
    node_prescribed_start: FloatArray
    dof_of_node: IntArray
    seabed_z: float
    seabed_stiffness_per_area: float
    seabed_damping_per_area: float
    node_contact_area: FloatArray
    gravity: float
    water_density: float
    body_names: tuple[str, ...] = ()
    slave_node: IntArray = field(default_factory=lambda: np.zeros(0, dtype=np.int64))
    slave_body: IntArray = field(default_factory=lambda: np.zeros(0, dtype=np.int64))
    slave_arm: FloatArray = field(default_factory=lambda: np.zeros((0, 3)))
    bodies: tuple = ()
    bathymetry: SeabedSurface | None = None
    point_motion: tuple = ()
    point_force_history: tuple = ()
    strain_laws: StrainLaws | None = None
    strain_offset: FloatArray | None = None
    EAd: FloatArray | None = None
    EAd_Lm: FloatArray | None = None
    static_dynamic: FloatArray | None = None
    syrope: SyropeElements | None = None
    bend_nodes: IntArray = field(default_factory=lambda: np.zeros((0, 3), dtype=np.int64))
    bend_elements: IntArray = field(default_factory=lambda: np.zeros((0, 2), dtype=np.int64))
    bend_stiffness: FloatArray = field(default_factory=lambda: np.zeros(0))
    clamp_elements: IntArray = field(default_factory=lambda: np.zeros(0, dtype=np.int64))
    clamp_direction: FloatArray = field(default_factory=lambda: np.zeros((0, 3)))
    clamp_stiffness: FloatArray = field(default_factory=lambda: np.zeros(0))
    sag_corrected: BoolArray | None = None

    @property
    def seabed_surface(self) -> SeabedSurface | None:
        """The seabed ``z = h(x, y)`` the contact acts on (``None`` without a seabed)."""
        if self.bathymetry is not None:
            return self.bathymetry
        return SeabedSurface(z0=float(self.seabed_z)) if np.isfinite(self.seabed_z) else None

    def seabed_height(self, x: FloatArray) -> FloatArray:
        """Seabed height under points ``x`` (n, 3) (n,) (``-inf`` without a seabed)."""
        surface = self.seabed_surface
        return surface.height(x) if surface is not None else np.full(len(x), -np.inf)

    @property
    def has_bending(self) -> bool:
        """Whether any line has bending stiffness (interior nodes or clamped ends)."""
        return len(self.bend_nodes) > 0 or len(self.clamp_elements) > 0

    @property
    def pattern_pairs(self) -> IntArray:
        """The node pairs a tangent couples (n_elements + n_b, 2): the elements, then the
        outer nodes ``(i-1, i+1)`` of every bending triplet (the pattern of
        :class:`~moorline.solvers.assembly.BlockPattern`)."""
        if not self.has_bending:
            return self.elements
        return np.concatenate((self.elements, self.bend_nodes[:, [0, 2]]))

    @property
    def axial_law(self) -> dict:
        """Keyword arguments of the non-linear element law
        (:func:`moorline.physics.element.axial_tension`): ``laws`` and ``offset``."""
        return {"laws": self.strain_laws, "offset": self.strain_offset}

    def axial_law_of(self, index: IntArray) -> dict:
        """:attr:`axial_law` of the elements ``index``."""
        laws, offset = self.strain_laws, self.strain_offset
        return {"laws": None if laws is None else laws.take(index),
                "offset": None if offset is None else offset[index]}

    @property
    def linear_axial(self) -> bool:
        """Whether every element follows ``EA eps`` (no table, no strain offset)."""
        return ((self.strain_laws is None or not self.strain_laws.active)
                and self.strain_offset is None)

    @property
    def n_nodes(self) -> int:
        """Number of nodes."""
        return len(self.node_position)

    @property
    def n_elements(self) -> int:
        """Number of elements."""
        return len(self.elements)

    @property
    def n_dofs(self) -> int:
        """Number of free degrees of freedom."""
        return int(self.dof_of_node.max(initial=-1)) + 1

    @property
    def longest_line(self) -> float:
        """Unstretched length of the longest line [length] (1 without lines)."""
        return max((float(self.length0[e].sum()) for e in self.line_elements), default=1.0)

    @property
    def free_nodes(self) -> BoolArray:
        """Mask of nodes that move freely (n_nodes,)."""
        return self.dof_of_node[:, 0] >= 0

    def point_index(self, name: str) -> int:
        """Index of a named point."""
        return self.point_names.index(name)

    def line_index(self, name: str) -> int:
        """Index of a named line."""
        return self.line_names.index(name)


def _element_properties(system: System, line_of_element: IntArray) -> dict[str, FloatArray]:
    env = system.environment
    lines = list(system.lines.values())
    props: dict[str, list[float]] = {k: [] for k in (
        "EA", "EA1", "tau", "slack_ratio", "slack_smoothing", "BA", "viscoelastic",
        "mass_per_length", "weight_per_length", "diameter", "Cd", "Ca", "Ct", "Cat", "EI")}
    for line in lines:
        lt = system.line_types[line.line_type]
        weight = (lt.mass_per_length - env.water_density * lt.area_displaced) * env.gravity
        values = {"EA": lt.EA, "EA1": lt.EA1, "tau": lt.tau,
                  "slack_ratio": lt.slack_stiffness_ratio,
                  "slack_smoothing": lt.slack_smoothing, "BA": lt.BA,
                  "viscoelastic": float(lt.material == "viscoelastic"),
                  "mass_per_length": lt.mass_per_length, "weight_per_length": weight,
                  "diameter": lt.diameter, "Cd": lt.Cd, "Ca": lt.Ca, "Ct": lt.Ct, "Cat": lt.Cat,
                  "EI": lt.EI}
        for key, value in values.items():
            props[key].append(value)
    out = {k: np.asarray(v, dtype=float)[line_of_element] for k, v in props.items()}
    out["viscoelastic"] = out["viscoelastic"] > 0.5
    types = [system.line_types[line.line_type] for line in lines]
    tables = {lt.name: StrainTable(lt.EA_table) for lt in types if lt.EA_table is not None}
    per_line = [tables.get(lt.name) for lt in types]
    syrope = _syrope_lines(lines, types, per_line, line_of_element)
    if syrope is not None:
        out["strain_offset"], out["syrope"] = syrope
    out["strain_laws"] = strain_laws(per_line, line_of_element)
    series = [lt.material in ("static_dynamic", "syrope") for lt in types]
    if any(lt.EAd is not None and not sd for lt, sd in zip(types, series, strict=True)):
        out["EAd"] = np.array([np.nan if lt.EAd is None or sd else lt.EAd
                               for lt, sd in zip(types, series, strict=True)])[line_of_element]
        out["EAd_Lm"] = np.array([lt.EAd_Lm for lt in types], dtype=float)[line_of_element]
    if any(lt.material == "static_dynamic" for lt in types):
        out["static_dynamic"] = np.array(
            [(lt.EAd, lt.EAd_Lm, 0.0, lt.BA_dynamic) if lt.material == "static_dynamic"
             else (np.nan,) * 4
             for lt in types], dtype=float)[line_of_element]
    return out


def _syrope_lines(lines, types, per_line, line_of_element):
    """The Syrope lines' static laws put in ``per_line`` (the working curve of each line's
    ``Tmax0``, :meth:`~moorline.physics.syrope.SyropeRope.relaxed_table`) and their strain
    offsets (n_elements,) and :class:`~moorline.physics.syrope.SyropeElements` (``c1``
    filled in by :func:`_assemble_mesh`); ``None`` without Syrope lines."""
    if not any(lt.material == "syrope" for lt in types):
        return None
    ropes, offset = {}, np.zeros(len(types))
    group, tmax = np.full(len(types), -1), np.zeros(len(types))
    c2 = np.zeros(len(types))
    for k, (line, lt) in enumerate(zip(lines, types, strict=True)):
        if lt.material != "syrope":
            continue
        if line.syrope_ic is None:
            raise ValueError(f"line {line.name}: a Syrope line needs its history (Tmax0, "
                             "Tmean0), MoorDyn's SYROPE IC")
        rope = ropes.setdefault(lt.name, rope_of(lt))
        offset[k], table = rope.relaxed_table(line.syrope_ic[0])
        per_line[k] = StrainTable(table)
        group[k], tmax[k], c2[k] = list(ropes).index(lt.name), line.syrope_ic[0], lt.BA_dynamic
    index = np.flatnonzero(group[line_of_element] >= 0)
    on = line_of_element[index]
    return offset[line_of_element], SyropeElements(
        index, tuple(ropes.values()), group[on], np.zeros(len(index)), c2[on], tmax[on])


def world_position(system: System, point) -> FloatArray:
    """Position of a point in the world frame (body points: through their body's pose)."""
    if point.kind != "body":
        return np.asarray(point.position, dtype=float)
    body = system.bodies[point.body]
    R = rotation_matrix(np.asarray(body.rotation, dtype=float))
    return np.asarray(body.position, dtype=float) + R @ np.asarray(point.position, dtype=float)


def discretize(system: System) -> Mesh:
    """Build the :class:`Mesh` of a system (no solving; interior nodes on straight chords)."""
    point_names = tuple(system.points)
    point_index = {name: i for i, name in enumerate(point_names)}
    positions = [world_position(system, p) for p in system.points.values()]
    elements: list[IntArray] = []
    line_nodes: list[IntArray] = []
    length0: list[FloatArray] = []
    line_of_element: list[IntArray] = []
    next_node = len(point_names)
    for k, line in enumerate(system.lines.values()):
        a, b = point_index[line.end_a], point_index[line.end_b]
        n_seg = line.segments
        s = np.linspace(0.0, 1.0, n_seg + 1)[1:-1, None]
        positions.extend(positions[a] + s * (positions[b] - positions[a]))
        nodes = np.concatenate(([a], np.arange(next_node, next_node + n_seg - 1), [b]))
        next_node += n_seg - 1
        line_nodes.append(nodes.astype(np.int64))
        elements.append(np.column_stack((nodes[:-1], nodes[1:])).astype(np.int64))
        length0.append(np.full(n_seg, line.length / n_seg))
        line_of_element.append(np.full(n_seg, k, dtype=np.int64))
    return _assemble_mesh(system, point_names, np.array(positions).reshape(-1, 3),
                          elements, line_nodes, length0, line_of_element)


def _assemble_mesh(system, point_names, node_position, elements, line_nodes, length0,
                   line_of_element) -> Mesh:
    n_nodes = len(node_position)
    elems = np.concatenate(elements) if elements else np.zeros((0, 2), np.int64)
    L0 = np.concatenate(length0) if length0 else np.zeros(0)
    el_line = np.concatenate(line_of_element) if line_of_element else np.zeros(0, np.int64)
    offsets = np.cumsum([0] + [len(e) for e in elements])
    line_elements = tuple(np.arange(offsets[i], offsets[i + 1]) for i in range(len(elements)))
    props = _element_properties(system, el_line)
    EI = props.pop("EI")
    bend = bending.bending_triplets(line_nodes, line_elements, L0, EI)
    ratio = props["BA"] < 0  # MoorDyn's -zeta: a damping ratio of each segment's axial mode
    props["BA"] = np.where(ratio, -props["BA"] * L0 * np.sqrt(props["EA"]
                                                              * props["mass_per_length"]),
                           props["BA"])
    if props.get("static_dynamic") is not None:  # BA is the static branch's: c1
        sd = props["static_dynamic"]
        series = np.isfinite(sd[:, 0])
        sd[series, 2] = props["BA"][series]
        c1, c2 = sd[series, 2], sd[series, 3]
        props["BA"][series] = c1 * c2 / (c1 + c2)  # the dashpot on the strain rate
    if props.get("syrope") is not None:  # the same two branches
        sy = props["syrope"]
        sy = replace(sy, c1=props["BA"][sy.index].copy())
        props["syrope"] = sy
        props["BA"][sy.index] = sy.c1 * sy.c2 / (sy.c1 + sy.c2)

    points = list(system.points.values())
    n_points = len(points)
    node_mass = np.zeros(n_nodes)
    node_volume = np.zeros(n_nodes)
    node_force = np.zeros((n_nodes, 3))
    node_hydro = np.zeros((3, n_nodes))
    start = node_position.copy()
    constrained = np.zeros(n_nodes, dtype=bool)
    for i, p in enumerate(points):
        node_mass[i], node_volume[i] = p.mass, p.volume
        node_force[i] = p.force
        node_hydro[:, i] = (p.drag_area, p.Cd, p.Ca)
        constrained[i] = p.kind != "free"
        if p.kind == "prescribed" and p.initial_position is not None:
            start[i] = p.initial_position
    dof = np.full((n_nodes, 3), -1, dtype=np.int64)
    free = np.flatnonzero(~constrained)
    dof[free] = np.arange(3 * len(free)).reshape(-1, 3)

    tributary = 0.5 * (np.bincount(elems[:, 0], L0 * props["diameter"], n_nodes)
                       + np.bincount(elems[:, 1], L0 * props["diameter"], n_nodes))
    env = system.environment
    return Mesh(
        node_position=node_position, elements=elems, length0=L0,
        element_line=el_line, line_names=tuple(system.lines), line_nodes=tuple(line_nodes),
        line_elements=line_elements, point_names=tuple(point_names),
        point_kind=tuple(p.kind for p in points),
        point_node=np.arange(n_points, dtype=np.int64), node_mass=node_mass,
        node_volume=node_volume, node_force=node_force, node_drag_area=node_hydro[0],
        node_Cd=node_hydro[1], node_Ca=node_hydro[2], node_prescribed_start=start,
        dof_of_node=dof, seabed_z=-env.depth if env.has_seabed else -np.inf,
        seabed_stiffness_per_area=env.seabed.stiffness,
        seabed_damping_per_area=env.seabed.damping, node_contact_area=tributary,
        gravity=env.gravity, water_density=env.water_density, **props,
        bend_nodes=bend[0], bend_elements=bend[1], bend_stiffness=bend[2],
        **_clamps(system, line_elements, L0, EI),
        **_body_arrays(system, points), bathymetry=sloped_seabed(env),
        sag_corrected=_sag_mask(system, el_line))


def _sag_mask(system: System, line_of_element: IntArray) -> BoolArray | None:
    """:attr:`Mesh.sag_corrected` (``None`` when no line asks for it)."""
    sag = np.array([line.element == "sag_corrected" for line in system.lines.values()],
                   dtype=bool)
    return sag[line_of_element] if sag.any() else None


def sloped_seabed(env) -> SeabedSurface | None:
    """The sloped or gridded seabed of an :class:`~moorline.model.Environment` (``None``:
    flat or no seabed)."""
    sb = env.seabed
    if not env.has_seabed or sb.is_flat:
        return None
    if sb.bathymetry is not None:
        return grid(sb.bathymetry.x, sb.bathymetry.y, sb.bathymetry.z)
    return plane(env.depth, sb.slope_deg, sb.slope_heading_deg)


def _clamps(system: System, line_elements: tuple[IntArray, ...], length0: FloatArray,
            EI: FloatArray) -> dict[str, FloatArray]:
    """The clamped line ends (:attr:`Mesh.clamp_elements` and the rest)."""
    elements, directions, stiffness = [], [], []
    for line, els in zip(system.lines.values(), line_elements, strict=True):
        for end, direction, e in ((line.end_a, line.clamp_a, els[0]),
                                  (line.end_b, line.clamp_b, els[-1])):
            if direction is None:
                continue
            d = np.asarray(direction, dtype=float)
            kind = system.points[end].kind
            if kind not in ("fixed", "prescribed") or not EI[e] > 0 or not np.any(d):
                raise ValueError(f"line {line.name}: a clamped end needs EI > 0, a nonzero "
                                 f"direction and a fixed or prescribed point ({end!r} is "
                                 f"{kind})")
            elements.append(e)
            directions.append(d / np.linalg.norm(d))
            stiffness.append(EI[e] / (0.5 * length0[e]))
    return {"clamp_elements": np.array(elements, dtype=np.int64),
            "clamp_direction": np.array(directions, dtype=float).reshape(-1, 3),
            "clamp_stiffness": np.array(stiffness, dtype=float)}


def with_loads_of(mesh: Mesh, system: System) -> Mesh:
    """``mesh`` (of a system with the same points, lines and bodies) carrying the bodies and
    the point motion and force histories of ``system``: a static state solved once serves
    systems that differ from it only in what moves them (waves, force histories, body
    hydrodynamics).

    Raises
    ------
    ValueError
        When ``system`` has other points, lines or bodies than the mesh.
    """
    if (tuple(system.points) != mesh.point_names or tuple(system.lines) != mesh.line_names
            or tuple(system.bodies) != mesh.body_names):
        raise ValueError(f"{system.name}: its points, lines or bodies differ from the mesh's")
    arrays = _body_arrays(system, list(system.points.values()))
    return replace(mesh, bodies=arrays["bodies"], point_motion=arrays["point_motion"],
                   point_force_history=arrays["point_force_history"])


def dynamic_mesh(mesh: Mesh, positions: FloatArray) -> Mesh:
    """``mesh`` for a dynamic analysis about the static state ``positions``: elements of fibre
    ropes with a dynamic stiffness (``EAd``) take the linear law ``EA_d (eps - eps_0)`` about
    their static tension (:func:`moorline.physics.load_strain.dynamic_strain_law`); other
    elements, and meshes without ``EAd``, are returned unchanged."""
    if mesh.EAd is None:
        return mesh
    fibre = np.isfinite(mesh.EAd)
    if mesh.sag_corrected is not None and np.any(fibre & mesh.sag_corrected):
        raise ValueError("sag-corrected elements (element: sag_corrected) take no fibre-rope "
                         "dynamic stiffness (EAd): use straight elements for that line")
    length, _ = element.element_geometry(positions, mesh.elements)
    tension, _ = element.axial_tension(length, mesh.length0, mesh.EA, mesh.slack_ratio,
                                       mesh.slack_smoothing, **mesh.axial_law)
    strain = length / mesh.length0 - 1.0
    if mesh.strain_offset is not None:
        strain = strain - mesh.strain_offset
    EA_d, eps0 = dynamic_strain_law(strain, tension, np.where(fibre, mesh.EAd, 1.0),
                                    mesh.EAd_Lm)
    laws = mesh.strain_laws
    if laws is not None:
        laws = StrainLaws(laws.tables, np.where(fibre, -1, laws.ids))
    base = np.zeros(mesh.n_elements) if mesh.strain_offset is None else mesh.strain_offset
    return replace(mesh, EA=np.where(fibre, EA_d, mesh.EA), strain_laws=laws,
                   strain_offset=np.where(fibre, base + eps0, base), EAd=None, EAd_Lm=None)


def _body_arrays(system: System, points: list) -> dict:
    names = tuple(system.bodies)
    slaves = [(i, names.index(p.body), p.position) for i, p in enumerate(points)
              if p.kind == "body"]
    return {
        "body_names": names,
        "bodies": tuple(system.bodies.values()),
        "point_motion": tuple(p.motion if p.kind == "prescribed" else None for p in points),
        "point_force_history": tuple(p.force_history if p.kind == "free" else None
                                     for p in points),
        "slave_node": np.array([s[0] for s in slaves], dtype=np.int64),
        "slave_body": np.array([s[1] for s in slaves], dtype=np.int64),
        "slave_arm": np.array([s[2] for s in slaves], dtype=float).reshape(-1, 3),
    }
