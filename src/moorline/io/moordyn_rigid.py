"""Bodies and rods of a MoorDyn v2 deck (``BODIES``, ``ROD TYPES``, ``RODS``), for
:func:`moorline.io.moordyn.read_moordyn_deck`.

MoorDyn's formats (MoorDyn documentation ``docs/inputs.rst``; read as MoorDyn-C 2.7,
``source/MoorDyn2.cpp``, ``Body.cpp``, ``Rod.cpp``):

- body rows ``ID Attachment X0 Y0 Z0 r0 p0 y0 Mass CG I Volume CdA Ca``: ``CG`` one number (its
  z) or ``x|y|z``; ``I`` (diagonal, about the centre of gravity, body frame) one number for all
  three axes or ``Ixx|Iyy|Izz``; ``CdA`` one number (translation and rotation) or
  ``trans|rot``; ``Ca`` one number or three (translation, body axes). Orientation: Euler angles
  [deg], ``R = Rx(r0) Ry(p0) Rz(y0)``. MoorDyn applies the body's buoyancy ``rho g Volume`` at
  the centre of gravity (:mod:`moorline.io.moordyn_bodies`), its added mass ``Ca rho V`` at the
  reference point in translation only and its drag ``rho CdA |u| u / 2`` at the reference point;
  ``Fixed`` and ``Coupled`` bodies have no mass, volume, drag or added mass of their own;
- rod types ``Name Diam Mass/m Cd Ca CdEnd CaEnd``; rod rows ``ID RodType Attachment Xa Ya Za
  Xb Yb Zb NumSegs Outputs``. A rod is a rigid cylinder: mass ``Mass/m L`` at its middle, the
  inertia of a solid cylinder (MoorDyn lumps it on its nodes and corrects the transverse term
  to ``m (L^2/12 + d^2/16)``; axial ``m d^2 / 8``), buoyancy of its submerged part, transverse
  added mass ``Ca rho A`` per length and drag ``Cd d`` per length, and at each submerged end
  ``CdEnd A`` of axial drag and ``CaEnd rho (2/3) pi (d/2)^3`` of axial added mass.

The mapping to moorline (:class:`moorline.model.Body`):

- ``Free`` body -> free body; ``Fixed`` and ``Coupled``/``Vessel`` bodies -> fixed bodies (the
  pose held; their reaction and, with ``moorline stiffness`` or the statics summary, their 6x6
  mooring stiffness are reported); their own mass, volume, drag and added mass are zero, as in
  MoorDyn. ``CoupledPinned`` bodies -> pinned bodies (:class:`moorline.model.Body`, kind
  ``pinned``: the reference point held at the deck's position, the rotation free) with their
  mass, volume, drag and added mass, as MoorDyn-C 2.7 ``Body.cpp`` keeps them;
- the body's buoyancy: ``matrix`` hydrostatics with the volume at the centre of gravity and no
  stiffness (MoorDyn's constant buoyancy), its added mass ``diag(Ca rho V)`` in translation
  (world axes at the initial pose), its translational ``CdA`` as ``drag_area`` with ``Cd = 1``
  (moorline's body drag is ``rho Cd A_i |u_i| u_i / 2`` per world axis, MoorDyn's uses
  ``|u|``: a warning); its rotational ``CdA`` is dropped (a warning);
- points ``Body<k>``: body points (body frame, as in MoorDyn); their mass, volume and added mass
  ``Ca rho V`` are added to the body's (exactly: mass and centre of gravity, inertia by
  parallel axes, volume and centre of buoyancy by volume-weighted centroid, added mass as a
  6x6 at the point's arm), their ``CdA`` to the body's drag area (a warning);
- rods ``Body<k>``: rigid parts of body ``k``; their weight, inertia, buoyancy (``rods``
  hydrostatics: recomputed at every pose from each rod's submerged length,
  :mod:`moorline.physics.rod_buoyancy`, so a rod piercing or leaving the surface floats the
  body as MoorDyn's does; a piercing rod's waterplane moment is Archimedes', not MoorDyn's),
  added mass (6x6 about the body origin) and drag (lumped at the
  body origin per world axis, a warning) are added to the body; their ends ``R<k>A``/``R<k>B``
  are body points;
- ``Free`` rods -> a free body ``rod<k>`` at the rod's middle with its x axis along the rod
  (inertia diagonal there), the same contributions; ``Fixed`` rods -> fixed end points;
  ``Coupled`` rods -> prescribed end points; zero-length free rods (``NumSegs 0``, MoorDyn's
  point-like connectors, without mass) -> one free point for both ends;
- ``Pinned`` and ``CoupledPinned`` rods (MoorDyn-C 2.7 ``Rod.cpp``: end A held, the rod turning
  freely about it) -> a pinned body ``rod<k>`` (:class:`moorline.model.Body`, kind ``pinned``)
  with its origin, the pin, at end A and its x axis along the rod, the same contributions as a
  free rod; a coupled pin is held at the deck's position (as ``Coupled`` rods and bodies are).
  The rod's spin about its own axis keeps MoorDyn's inertia ``m d^2 / 8`` (a solid cylinder's;
  with axial added mass none, as MoorDyn's nodes sit on the axis) and meets no moment and no
  stiffness: the coupled statics project it out (:func:`moorline.solvers.bodies.
  spin_projection`); the rod's drag, which moorline would apply at its pin, is dropped (a
  warning);
- ``Body<k>Pinned`` rods (pinned to a body) -> pinned bodies whose pin (end A, body frame
  coordinates as MoorDyn's) sits on that body (``pin_body``); on a ``CoupledPinned`` body
  they cannot be represented (a pin on a pinned body): an error naming them;
- a deck's ``Coupled`` points and no body: ``moorline stiffness`` takes them as one rigid
  group (its default); ``moorline convert --vessel-body`` (:func:`vessel_body`) holds them by
  one fixed body at the origin instead, so that the statics summary reports its 6x6.

All errors are collected and raised at once (:attr:`RigidParts.errors`), the approximations
are warnings (:attr:`RigidParts.warnings`, the reader's notes).
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import CaseError
from ..model import Body, Hydrostatics, Point
from ..physics.rigid_body import rotation_matrix, rotation_vector, skew

FloatArray = NDArray[np.float64]
_ROD_END = re.compile(r"(?i)^r(\d+)([ab])$")
_FIXED = {"ANCHOR", "FIXED", "FIX"}
_COUPLED = {"VESSEL", "VES", "COUPLED", "CPLD"}
_PINNED_COUPLED = {"VESSELPINNED", "VESPIN", "CPLDPIN", "COUPLEDPINNED"}
_GAUSS = (0.5 - 0.5 / math.sqrt(3.0), 0.5 + 0.5 / math.sqrt(3.0))


@dataclass(frozen=True)
class RodType:
    """A MoorDyn rod type: diameter, mass per length, transverse drag and added-mass
    coefficients, end drag and end added-mass coefficients."""

    name: str
    diameter: float
    mass_per_length: float
    Cd: float
    Ca: float
    CdEnd: float
    CaEnd: float


@dataclass
class _Rigid:
    """Mass, buoyancy and fluid properties of one moorline body, summed from its parts.

    Body frame: ``mass``, ``moment`` (sum m r), ``inertia_origin`` (about the origin), ``volume``,
    ``volume_moment``. World axes at the initial pose: ``added`` (6x6 about the origin),
    ``drag`` (area per axis); ``rods`` (ends in the body frame, diameter) float it at every
    pose."""

    name: str
    kind: str
    position: FloatArray
    R: FloatArray
    mass: float = 0.0
    moment: FloatArray = field(default_factory=lambda: np.zeros(3))
    inertia_origin: FloatArray = field(default_factory=lambda: np.zeros((3, 3)))
    volume: float = 0.0
    volume_moment: FloatArray = field(default_factory=lambda: np.zeros(3))
    added: FloatArray = field(default_factory=lambda: np.zeros((6, 6)))
    drag: FloatArray = field(default_factory=lambda: np.zeros(3))
    has_rods: bool = False
    rods: list[tuple[tuple[float, float, float], tuple[float, float, float], float]] = field(
        default_factory=list)
    pin_body: str | None = None

    def add_mass(self, mass: float, at: FloatArray, inertia: FloatArray | None = None) -> None:
        """A mass at body-frame point ``at`` with its own inertia about it (body frame)."""
        at = np.asarray(at, dtype=float)
        self.mass += mass
        self.moment += mass * at
        own = np.zeros((3, 3)) if inertia is None else inertia
        self.inertia_origin += own + mass * (at @ at * np.eye(3) - np.outer(at, at))

    def add_volume(self, volume: float, at: FloatArray) -> None:
        self.volume += volume
        self.volume_moment += volume * np.asarray(at, dtype=float)

    def add_added_mass(self, A3: FloatArray, arm_world: FloatArray) -> None:
        """A translational added-mass tensor (world axes) at a world arm from the origin."""
        S = skew(np.asarray(arm_world, dtype=float))
        self.added[:3, :3] += A3
        self.added[:3, 3:] -= A3 @ S
        self.added[3:, :3] += S @ A3
        self.added[3:, 3:] -= S @ A3 @ S

    def world_arm(self, at: FloatArray) -> FloatArray:
        return self.R @ np.asarray(at, dtype=float)

    def body(self) -> Body:
        """The moorline body."""
        cg = self.moment / self.mass if self.mass > 0 else np.zeros(3)
        inertia = self.inertia_origin - self.mass * (cg @ cg * np.eye(3) - np.outer(cg, cg))
        inertia = 0.5 * (inertia + inertia.T)
        cb = self.volume_moment / self.volume if self.volume > 0 else cg
        hydro = Hydrostatics("matrix", volume=self.volume, center_of_buoyancy=_vec(cb))
        if self.volume == 0:
            hydro = Hydrostatics()
        if self.rods:
            hydro = Hydrostatics("rods", volume=self.volume, center_of_buoyancy=_vec(cb),
                                 rods=tuple(self.rods))
        added = _mat(self.added) if self.added.any() else None
        return Body(self.name, self.kind if self.kind in ("free", "pinned") else "fixed",
                    position=_vec(self.position), rotation=_vec(rotation_vector(self.R)),
                    mass=self.mass, center_of_gravity=_vec(cg),
                    inertia=tuple(_vec(r) for r in inertia), added_mass=added,
                    hydrostatics=hydro, drag_area=_vec(self.drag), Cd=1.0,
                    pin_body=self.pin_body)


def _vec(v: Any) -> tuple[float, float, float]:
    a = [float(x) for x in np.asarray(v, dtype=float).ravel()]
    return (a[0], a[1], a[2])


def _mat(m: FloatArray) -> tuple[tuple[float, ...], ...]:
    return tuple(tuple(float(x) for x in row) for row in np.asarray(m, dtype=float))


def euler_rotation(roll: float, pitch: float, yaw: float) -> FloatArray:
    """MoorDyn's orientation of Euler angles [rad]: ``Rx(roll) Ry(pitch) Rz(yaw)``
    (``Misc.hpp`` ``Euler2Quat``)."""
    return (rotation_matrix(np.array([roll, 0.0, 0.0]))
            @ rotation_matrix(np.array([0.0, pitch, 0.0]))
            @ rotation_matrix(np.array([0.0, 0.0, yaw])))


def attachment_word(token: str) -> tuple[str, str, str]:
    """MoorDyn's split of an attachment word (``str::decomposeString``): leading letters,
    digits, following letters, upper-cased (``Body1Pinned`` -> ``BODY``, ``1``, ``PINNED``)."""
    m = re.match(r"([A-Za-z]*)(\d*)([A-Za-z]*)", token)
    assert m is not None
    return m.group(1).upper(), m.group(2), m.group(3).upper()


@dataclass
class RigidParts:
    """What the ``BODIES`` and ``RODS`` sections give: moorline bodies (built by
    :meth:`bodies`), the points standing for rod ends, the body name of each MoorDyn body
    number, and the problems and warnings found."""

    rigid: dict[str, _Rigid] = field(default_factory=dict)
    body_ids: dict[int, str] = field(default_factory=dict)
    rod_points: dict[str, Point] = field(default_factory=dict)
    rod_ends: dict[tuple[int, str], str] = field(default_factory=dict)
    merged: dict[str, str] = field(default_factory=dict)
    collapsed: dict[str, str] = field(default_factory=dict)  # body -> the free point it became
    errors: list[str] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)

    def bodies(self) -> dict[str, Body]:
        return {name: r.body() for name, r in self.rigid.items()}

    def collapse_point_bodies(self, points: dict[str, Point], rho: float) -> None:
        """Free bodies without rods whose points all sit at one place, with the centres of
        gravity and buoyancy there too, have no rotational stiffness (moorline's statics
        would be singular; MoorDyn's body just spins): each becomes one free point with the
        body's mass, volume, drag area (per-axis mean) and added-mass coefficient."""
        for name, rigid in list(self.rigid.items()):
            attached = [n for n, p in points.items() if p.kind == "body" and p.body == name]
            if rigid.kind != "free" or rigid.has_rods or not attached:
                continue
            at = np.asarray(points[attached[0]].position, dtype=float)
            spots = [np.asarray(points[n].position, dtype=float) for n in attached]
            centres = ([rigid.moment / rigid.mass] if rigid.mass > 0 else []) + (
                [rigid.volume_moment / rigid.volume] if rigid.volume > 0 else [])
            if not all(np.allclose(c, at, atol=1e-9) for c in spots + centres):
                continue
            world = rigid.position + rigid.world_arm(at)
            added = float(np.trace(rigid.added[:3, :3])) / 3.0
            ca = added / (rho * rigid.volume) if rigid.volume > 0 else 0.0
            if added and not rigid.volume:
                self.warnings.append(f"body {name}: added mass without volume is dropped")
            drag = float(np.mean(rigid.drag))
            first, *others = attached
            points[first] = Point(first, "free", _vec(world), mass=rigid.mass,
                                  volume=rigid.volume, Cd=1.0 if drag else 0.0,
                                  drag_area=drag, Ca=ca)
            for other in others:
                del points[other]
            self.merged.update({other: first for other in others})
            self.collapsed[name] = first
            del self.rigid[name]
            self.warnings.append(
                f"body {name}: its lines all attach at one point at its centres of gravity "
                f"and buoyancy (no rotational stiffness): it becomes the free point {first} "
                "with its mass, volume, drag and added mass")

    def rod_end(self, token: str) -> str | None:
        """The point name of a line attachment ``R<k>A``/``R<k>B`` (None: not a rod end; a
        ``KeyError`` for an unknown rod)."""
        m = _ROD_END.match(token)
        if m is None:
            return None
        return self.rod_ends[(int(m.group(1)), m.group(2).upper())]


Fail = Callable[[str, Any], CaseError]


def _numbers(token: str, counts: tuple[int, ...], what: str, row: Any, fail: Fail
             ) -> list[float]:
    parts = token.split("|")
    if len(parts) not in counts:
        raise fail(f"{what} {token!r}: expected {' or '.join(map(str, counts))} "
                   "'|'-separated numbers", row)
    try:
        values = [float(p) for p in parts]
    except ValueError:
        raise fail(f"{what} must be numbers, got {token!r}", row) from None
    if not all(math.isfinite(v) for v in values):
        raise fail(f"{what} must be finite, got {token!r}", row)
    return values


def parse_rod_types(rows: list[Any], fail: Fail) -> dict[str, RodType]:
    """``ROD TYPES`` rows ``Name Diam Mass/m Cd Ca CdEnd CaEnd``."""
    types: dict[str, RodType] = {}
    for row in rows:
        if len(row.tokens) < 7:
            raise fail("a rod type needs 7 columns (Name Diam Mass/m Cd Ca CdEnd CaEnd), "
                       f"found {len(row.tokens)}", row)
        name = row.tokens[0]
        if name in types:
            raise fail(f"rod type {name!r} is defined twice", row)
        v = [_numbers(t, (1,), what, row, fail)[0] for t, what in
             zip(row.tokens[1:7], ("Diam", "Mass/m", "Cd", "Ca", "CdEnd", "CaEnd"), strict=True)]
        if v[0] <= 0 or min(v[1:]) < 0:
            raise fail("rod type: Diam must be positive and the other values not negative", row)
        types[name] = RodType(name, *v)
    return types


def legacy_body_row(tokens: list[str], row: Any, fail: Fail) -> list[str]:
    """An early MoorDyn-F v2 body row as today's 14 columns (other rows unchanged).

    The early row (OpenFAST ``modules/moordyn/src/MoorDyn.f90`` of 2020-2021, its "BODY
    LIST" reader of 17 values; OpenFAST r-test ``modules/moordyn/5MW_OC4/moordyn.dat``) is
    ``<ID><type> X0 Y0 Z0 r0 p0 y0 Xcg Ycg Zcg M V IX IY IZ CdA Ca``: the body type follows the
    number in the first word (``1coupled``; ``Coupled`` or ``Vessel``, else ``Free`` or
    nothing for a free body), the centre of gravity and the inertia are three columns each,
    the mass comes before the volume. It becomes ``ID Attachment X0 Y0 Z0 r0 p0 y0 M
    Xcg|Ycg|Zcg IX|IY|IZ V CdA Ca`` as :func:`parse_bodies` reads it.
    """
    match = re.match(r"^(\d+)([A-Za-z]*)$", tokens[0]) if tokens else None
    legacy = match is not None and (bool(match.group(2)) or (
        len(tokens) == 17 and re.match(r"^[-+.\d]", tokens[1]) is not None))
    if not legacy:
        return tokens
    assert match is not None
    if len(tokens) != 17:
        raise fail(f"body ID {tokens[0]!r} (an early MoorDyn-F v2 row, the type after the "
                   "number) needs 17 columns (ID+type X0 Y0 Z0 r0 p0 y0 Xcg Ycg Zcg M V IX IY "
                   f"IZ CdA Ca), found {len(tokens)}", row)
    word = match.group(2).upper()
    if word not in {"COUPLED", "VESSEL", "FREE", ""}:
        raise fail(f"body ID {tokens[0]!r}: an early MoorDyn-F v2 body type must be Coupled, "
                   "Vessel or Free (or none: free)", row)
    v = tokens[1:]
    kind = "Coupled" if word in {"COUPLED", "VESSEL"} else "Free"
    return [match.group(1), kind, *v[:6], v[9], "|".join(v[6:9]), "|".join(v[11:14]), v[10],
            v[14], v[15]]


def parse_bodies(rows: list[Any], rho: float, fail: Fail, parts: RigidParts) -> None:
    """``BODIES`` rows into ``parts`` (names from a one-word comment, else ``body<ID>``)."""
    for number, row in enumerate(rows, start=1):
        tok = row.tokens = legacy_body_row(row.tokens, row, fail)
        if len(tok) < 14:
            raise fail("a body needs 14 columns (ID Attachment X0 Y0 Z0 r0 p0 y0 Mass CG I "
                       f"Volume CdA Ca), found {len(tok)}", row)
        if _numbers(tok[0], (1,), "ID", row, fail)[0] != number:
            raise fail(f"body IDs must run 1, 2, 3, ...: expected {number}, got {tok[0]}", row)
        word = attachment_word(tok[1])[0]
        name = row.comment.strip() if re.match(r"^[A-Za-z_][\w.\-]*$", row.comment.strip()) \
            else f"body{number}"
        if name in parts.rigid:
            name = f"body{number}"
        parts.body_ids[number] = name
        pose = [_numbers(t, (1,), "X0 Y0 Z0 r0 p0 y0", row, fail)[0] for t in tok[2:8]]
        mass = _numbers(tok[8], (1,), "Mass", row, fail)[0]
        cg = _numbers(tok[9], (1, 3), "CG", row, fail)
        cg = [0.0, 0.0, cg[0]] if len(cg) == 1 else cg
        inertia = _numbers(tok[10], (1, 3), "I", row, fail)
        inertia = inertia * 3 if len(inertia) == 1 else inertia
        volume = _numbers(tok[11], (1,), "Volume", row, fail)[0]
        cda = _numbers(tok[12], (1, 2, 3, 6), "CdA", row, fail)
        ca = _numbers(tok[13], (1, 3), "Ca", row, fail)
        ca = ca * 3 if len(ca) == 1 else ca
        if mass < 0 or volume < 0 or min(inertia) < 0 or min(cda) < 0:
            raise fail("body Mass, I, Volume and CdA must not be negative", row)
        if word in _PINNED_COUPLED:
            kind = "pinned"
            parts.warnings.append(f"body {number} ({tok[1]}): a pinned body, its pin (the "
                                  "reference point) held at the deck's position (as a Coupled "
                                  "body is held), its rotation free")
        else:
            kind = "fixed" if word in _FIXED | _COUPLED else "free"
            if word not in _FIXED | _COUPLED | {"FREE", "BODY", "POINT", "CONNECT", "CON"}:
                parts.warnings.append(f"body {number}: attachment {tok[1]!r} read as Free "
                                      "(as MoorDyn-C does with an unknown word)")
        R = euler_rotation(*(math.radians(a) for a in pose[3:]))
        rigid = _Rigid(name, kind, np.array(pose[:3]), R)
        parts.rigid[name] = rigid
        if kind == "fixed":
            if mass or volume or any(cda) or any(ca):
                parts.warnings.append(f"body {number} is {tok[1]}: its mass, volume, drag and "
                                      "added mass are ignored, as MoorDyn does")
            continue
        rigid.add_mass(mass, np.array(cg), np.diag(inertia))
        rigid.add_volume(volume, np.array(cg))
        rigid.add_added_mass(R @ np.diag([c * rho * volume for c in ca]) @ R.T, np.zeros(3))
        translational = cda[0] if len(cda) in (1, 2) else max(cda[:3])
        rotational = cda[0] if len(cda) == 1 else (cda[1] if len(cda) == 2 else max(cda[3:]))
        if len(cda) in (3, 6):
            parts.warnings.append(f"body {number}: CdA {tok[12]!r} with {len(cda)} values: "
                                  "MoorDyn-C 2.7 drops the first value; taken as the largest "
                                  "translational value on all axes")
        if translational:
            rigid.drag += translational
            parts.warnings.append(f"body {number}: drag CdA {translational:g} applied per "
                                  "world axis (rho CdA |u_i| u_i / 2); MoorDyn uses "
                                  "rho CdA |u| u / 2 in body axes")
        if rotational:
            parts.warnings.append(f"body {number}: rotational drag CdA {rotational:g} is "
                                  "dropped (moorline bodies have no rotational drag)")
        if len(set(ca)) > 1:
            parts.warnings.append(f"body {number}: added mass Ca {tok[13]!r} in body axes is "
                                  "taken in world axes at the initial pose")


def attach_point(parts: RigidParts, point: Point, body: str, rho: float, number: int
                 ) -> Point:
    """Move a body point's mass, volume, added mass and drag onto its body (see the module
    docstring); the point keeps only its body-frame position."""
    rigid = parts.rigid[body]
    at = np.asarray(point.position, dtype=float)
    rigid.add_mass(point.mass, at)
    rigid.add_volume(point.volume, at)
    if point.Ca and point.volume:
        rigid.add_added_mass(point.Ca * rho * point.volume * np.eye(3), rigid.world_arm(at))
    if point.drag_area:
        rigid.drag += point.Cd * point.drag_area
        parts.warnings.append(f"point {number} on {body}: its drag CdA is lumped at the body "
                              "origin, per world axis")
    return Point(point.name, "body", point.position, body=body)


def _rod_geometry(a: FloatArray, b: FloatArray) -> tuple[float, FloatArray]:
    d = b - a
    length = float(np.linalg.norm(d))
    return length, (d / length if length > 0 else np.array([0.0, 0.0, 1.0]))


def _submerged(a_w: FloatArray, b_w: FloatArray) -> tuple[float, float]:
    """Fractions ``(s0, s1)`` of the axis from end A below the still water level z = 0."""
    za, zb = float(a_w[2]), float(b_w[2])
    if za <= 0 and zb <= 0:
        return 0.0, 1.0
    if za >= 0 and zb >= 0:
        return 0.0, 0.0
    s = za / (za - zb)
    return (0.0, s) if za < 0 else (s, 1.0)


def add_rod(rigid: _Rigid, rod: RodType, a: FloatArray, b: FloatArray, rho: float, g: float,
            label: str, warnings: list[str]) -> None:
    """Add a rigid rod from body-frame ``a`` to ``b`` to ``rigid`` (module docstring); a
    pinned body's drag is dropped (moorline's body drag acts at the origin, its pin)."""
    rigid.has_rods = True
    length, t = _rod_geometry(a, b)
    area = math.pi * rod.diameter**2 / 4.0
    mass = rod.mass_per_length * length
    own = mass * ((length**2 / 12.0 + rod.diameter**2 / 16.0) * (np.eye(3) - np.outer(t, t))
                  + rod.diameter**2 / 8.0 * np.outer(t, t))
    rigid.add_mass(mass, 0.5 * (a + b), own)
    rigid.rods.append((_vec(a), _vec(b), rod.diameter))
    a_w, b_w = rigid.position + rigid.world_arm(a), rigid.position + rigid.world_arm(b)
    s0, s1 = _submerged(a_w, b_w)
    wet = (s1 - s0) * length
    if wet <= 0:
        return
    t_w = rigid.R @ t
    transverse = np.eye(3) - np.outer(t_w, t_w)
    for gauss in _GAUSS:  # exact for the quadratic moment terms
        s = s0 + (s1 - s0) * gauss
        rigid.add_added_mass(0.5 * wet * rod.Ca * rho * area * transverse,
                             rigid.world_arm(a + s * (b - a)))
    end_mass = rod.CaEnd * rho * 2.0 / 3.0 * math.pi * (rod.diameter / 2.0) ** 3
    ends = [at for at, s in ((a, 0.0), (b, 1.0)) if s0 <= s <= s1]
    for at in ends:
        rigid.add_added_mass(end_mass * np.outer(t_w, t_w), rigid.world_arm(at))
    drag = (rod.Cd * rod.diameter * wet * np.sqrt(np.clip(1.0 - t_w**2, 0.0, None))
            + len(ends) * rod.CdEnd * area * np.abs(t_w))
    if drag.any() and rigid.kind == "pinned":
        warnings.append(f"{label}: its drag is dropped (moorline's body drag acts at the body "
                        "origin, which is the pin; MoorDyn distributes it along the rod)")
    elif drag.any():
        rigid.drag += drag
        warnings.append(f"{label}: its drag is lumped at the body origin, per world axis "
                        "(MoorDyn distributes it along the rod)")


def parse_rods(rows: list[Any], types: Mapping[str, RodType], rho: float, g: float,
               fail: Fail, parts: RigidParts) -> None:
    """``RODS`` rows into ``parts``: rod end points (``rod<k>A``/``rod<k>B``, or ``rod<k>`` for
    a zero-length free rod), bodies of free rods, parts of bodies (module docstring)."""
    on_bodies = []
    for number, row in enumerate(rows, start=1):
        tok = row.tokens
        if len(tok) < 10:
            raise fail("a rod needs 11 columns (ID RodType Attachment Xa Ya Za Xb Yb Zb "
                       f"NumSegs Outputs), found {len(tok)}", row)
        if _numbers(tok[0], (1,), "ID", row, fail)[0] != number:
            raise fail(f"rod IDs must run 1, 2, 3, ...: expected {number}, got {tok[0]}", row)
        if tok[1] not in types:
            raise fail(f"unknown rod type {tok[1]!r}; defined: {', '.join(types) or 'none'}",
                       row)
        rod = types[tok[1]]
        ends = [_numbers(t, (1,), "Xa Ya Za Xb Yb Zb", row, fail)[0] for t in tok[3:9]]
        a, b = np.array(ends[:3]), np.array(ends[3:])
        segments = int(_numbers(tok[9], (1,), "NumSegs", row, fail)[0])
        word, digits, after = attachment_word(tok[2])
        label = f"rod {number} ({tok[2]}, line {row.lineno})"
        name = f"rod{number}"
        if word == "BODY" and after in ("PINNED", "PIN"):
            host = parts.body_ids.get(int(digits)) if digits else None
            if host is None:
                raise fail(f"rod {number}: no body {tok[2]!r} (bodies: "
                           f"{', '.join(map(str, parts.body_ids)) or 'none'})", row)
            if parts.rigid[host].kind == "pinned":
                on_bodies.append(label)
                continue
            length, t = _rod_geometry(a, b)
            if length == 0:
                raise fail(f"rod {number}: a pinned rod needs a length (Xa Ya Za and Xb Yb Zb "
                           "coincide)", row)
            parent = parts.rigid[host]
            rigid = _Rigid(name, "pinned", parent.position + parent.world_arm(a),
                           parent.R @ _align_x(t), pin_body=host)
            tip = np.array([length, 0.0, 0.0])
            add_rod(rigid, rod, np.zeros(3), tip, rho, g, label, parts.warnings)
            parts.rigid[name] = rigid
            for end, at in (("A", np.zeros(3)), ("B", tip)):
                parts.rod_points[f"{name}{end}"] = Point(f"{name}{end}", "body", _vec(at),
                                                         body=name)
        elif word == "BODY":
            body = parts.body_ids.get(int(digits)) if digits else None
            if body is None:
                raise fail(f"rod {number}: no body {tok[2]!r} (bodies: "
                           f"{', '.join(map(str, parts.body_ids)) or 'none'})", row)
            add_rod(parts.rigid[body], rod, a, b, rho, g, label, parts.warnings)
            for end, at in (("A", a), ("B", b)):
                parts.rod_points[f"{name}{end}"] = Point(f"{name}{end}", "body", _vec(at),
                                                         body=body)
        elif word in _FIXED or word in _COUPLED:
            kind = "fixed" if word in _FIXED else "prescribed"
            for end, at in (("A", a), ("B", b)):
                parts.rod_points[f"{name}{end}"] = Point(f"{name}{end}", kind, _vec(at))
            if word in _COUPLED:
                parts.warnings.append(f"{label}: a coupled rod becomes two prescribed points "
                                      "at its ends (the rod's own loads are not in their "
                                      "reactions)")
        elif word in {"POINT", "CON", "FREE"} | {"PINNED", "PIN"} | _PINNED_COUPLED:
            length, t = _rod_geometry(a, b)
            pinned = word not in {"POINT", "CON", "FREE"}
            if (segments == 0 or length == 0) and not pinned:
                parts.rod_points[name] = Point(name, "free", _vec(a))
                parts.rod_ends[(number, "A")] = parts.rod_ends[(number, "B")] = name
                if np.any(a != b):
                    parts.warnings.append(f"{label}: a zero-segment rod is a point connector; "
                                          "both ends are taken at end A")
                continue
            if length == 0:
                raise fail(f"rod {number}: a pinned rod needs a length (Xa Ya Za and Xb Yb Zb "
                           "coincide)", row)
            R = _align_x(t)
            half = np.array([length / 2.0, 0.0, 0.0])
            # a pinned rod's origin is its pin (end A), a free rod's its middle
            rigid = _Rigid(name, "pinned" if pinned else "free", a if pinned else 0.5 * (a + b),
                           R)
            start, stop = (np.zeros(3), 2.0 * half) if pinned else (-half, half)
            add_rod(rigid, rod, start, stop, rho, g, label, parts.warnings)
            parts.rigid[name] = rigid
            for end, at in (("A", start), ("B", stop)):
                parts.rod_points[f"{name}{end}"] = Point(f"{name}{end}", "body", _vec(at),
                                                         body=name)
            if word in _PINNED_COUPLED:
                parts.warnings.append(f"{label}: a coupled pinned rod, its end A held at the "
                                      "deck's position (as a Coupled rod's ends are held), its "
                                      "rotation free")
        else:
            raise fail(f"rod {number}: unknown attachment {tok[2]!r} (Fixed, Pinned, Body<k>, "
                       "Body<k>Pinned, Coupled, CoupledPinned or Free)", row)
        parts.rod_ends[(number, "A")] = f"{name}A"
        parts.rod_ends[(number, "B")] = f"{name}B"
    if on_bodies:
        parts.errors.append("rods pinned to a pinned body (a CoupledPinned body) cannot be "
                            "represented (a pin on a pinned body): " + "; ".join(on_bodies))


def _align_x(t: FloatArray) -> FloatArray:
    """A rotation taking the x axis to the unit vector ``t``."""
    ex = np.array([1.0, 0.0, 0.0])
    axis = np.cross(ex, t)
    s, c = float(np.linalg.norm(axis)), float(ex @ t)
    if s < 1e-12:
        return np.eye(3) if c > 0 else rotation_matrix(np.array([0.0, 0.0, math.pi]))
    return rotation_matrix(axis / s * math.atan2(s, c))


def vessel_body(system: Any, name: str = "vessel") -> Any:
    """``system`` with its prescribed points (a deck's ``Coupled``/``Vessel`` points) turned
    into points of one fixed body ``name`` at the origin, unrotated (the platform reference
    point of MoorDyn's coupling): the statics summary then reports that body's reaction and
    6x6 mooring stiffness about the origin (``moorline convert --vessel-body``).

    Raises
    ------
    CaseError
        Without prescribed points, when a prescribed point moves (motion or initial
        position), or when ``name`` is taken.
    """
    from dataclasses import replace

    coupled = [p for p in system.points.values() if p.kind == "prescribed"]
    if not coupled:
        raise CaseError("--vessel-body: the deck has no Coupled/Vessel points",
                        file=system.source)
    moving = [p.name for p in coupled if p.motion is not None or p.initial_position is not None]
    if moving:
        raise CaseError(f"--vessel-body: points {', '.join(moving)} move", file=system.source)
    if name in system.bodies:
        raise CaseError(f"--vessel-body: a body {name!r} exists", file=system.source)
    points = {n: (Point(n, "body", p.position, body=name, mass=p.mass, volume=p.volume)
                  if p.kind == "prescribed" else p) for n, p in system.points.items()}
    bodies = {**system.bodies, name: Body(name, "fixed")}
    return replace(system, points=points, bodies=bodies)
