"""Rigid bodies coupled to the lines: poses, loads and the master-slave transformation.

A free body has six unknowns: the position ``r`` of its origin and a small rotation ``dtheta``
applied on the left of its rotation matrix, ``R <- exp([dtheta x]) R``. A node attached to a
body at arm ``a`` (body frame) sits at ``x = r + R a``; a small body motion moves it by
``dx = dr + dtheta x (R a) = T (dr, dtheta)`` with ``T = [I, -[R a x]]`` (Tuah 1982 eq.
3.3.6-3.3.7; Wang, Er and Iu eq. 31-34). Forces ``f`` on attached nodes act on the body as
``T^T f`` (force and moment about the origin); their tangent transforms as ``T^T K T`` plus the
change of the moment arms under fixed forces, ``-[f x][R a x]`` (see
:func:`moorline.solvers.stiffness.group_stiffness`, checked against finite differences).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from ..mesh import Mesh, rotation_matrix
from ..model import Body, System

FloatArray = NDArray[np.float64]


def skew(v: FloatArray) -> FloatArray:
    """Cross-product matrix ``[v x]``."""
    return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])


def rotation_vector(R: FloatArray) -> FloatArray:
    """Rotation vector of a rotation matrix (inverse of Rodrigues' formula)."""
    cos = np.clip((np.trace(R) - 1.0) / 2.0, -1.0, 1.0)
    angle = float(np.arccos(cos))
    w = np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]])
    if angle < 1e-8:
        return 0.5 * w
    return angle / (2.0 * np.sin(angle)) * w


@dataclass(frozen=True)
class BodyState:
    """Poses and motions of all bodies, world axes: origins ``r`` (nb, 3), rotation matrices
    ``R`` (nb, 3, 3), velocities ``vel`` = (v, omega) and accelerations ``acc`` = (a, alpha),
    each (nb, 6) (zero when not given: a static pose)."""

    r: FloatArray
    R: FloatArray
    vel: FloatArray | None = None
    acc: FloatArray | None = None

    def __post_init__(self) -> None:
        zeros = np.zeros((len(self.r), 6))
        if self.vel is None:
            object.__setattr__(self, "vel", zeros)
        if self.acc is None:
            object.__setattr__(self, "acc", zeros.copy())

    @classmethod
    def initial(cls, system: System, mesh: Mesh) -> BodyState:
        """The poses the case gives, at rest."""
        bodies = [system.bodies[n] for n in mesh.body_names]
        r = np.array([b.position for b in bodies], dtype=float).reshape(-1, 3)
        R = np.array([rotation_matrix(np.asarray(b.rotation, float)) for b in bodies])
        return cls(r, R.reshape(-1, 3, 3))

    @classmethod
    def from_pose(cls, pose: FloatArray) -> BodyState:
        """At rest at poses (nb, 6): position and rotation vector."""
        pose = np.asarray(pose, dtype=float).reshape(-1, 6)
        R = np.array([rotation_matrix(p[3:]) for p in pose]).reshape(-1, 3, 3)
        return cls(pose[:, :3].copy(), R)

    def copy(self) -> BodyState:
        """An independent copy."""
        return BodyState(self.r.copy(), self.R.copy(), self.vel.copy(), self.acc.copy())

    def moved(self, dr: FloatArray, dtheta: FloatArray) -> BodyState:
        """The poses after small motions ``dr``, ``dtheta`` (n_bodies, 3) each (motions kept)."""
        R = np.array([rotation_matrix(d) @ R0 for d, R0 in zip(dtheta, self.R, strict=True)])
        return BodyState(self.r + dr, R.reshape(-1, 3, 3), self.vel, self.acc)

    def as_array(self) -> FloatArray:
        """(n_bodies, 6): position and rotation vector."""
        rv = np.array([rotation_vector(R) for R in self.R]).reshape(-1, 3)
        return np.hstack((self.r, rv))

    pose = as_array


Poses = BodyState  # the static poses are body states at rest


def place_slaves(mesh: Mesh, poses: Poses, x: FloatArray) -> FloatArray:
    """Node positions with the attached nodes on their bodies (a new array)."""
    x = x.copy()
    if len(mesh.slave_node):
        arms = np.einsum("kij,kj->ki", poses.R[mesh.slave_body], mesh.slave_arm)
        x[mesh.slave_node] = poses.r[mesh.slave_body] + arms
    return x


def world_arms(mesh: Mesh, poses: Poses) -> FloatArray:
    """Arms ``R a`` of the attached nodes in world axes (n_slaves, 3)."""
    return np.einsum("kij,kj->ki", poses.R[mesh.slave_body], mesh.slave_arm)


def transformation(mesh: Mesh, ext_dofs: int, n_free: int, body_dof: NDArray[np.int64],
                   arms: FloatArray) -> sp.csr_matrix:
    """The sparse map ``P`` from the unknowns (free node dofs, free body dofs) to the extended
    node dofs (free nodes, then attached nodes), ``dx_ext = P du``."""
    rows, cols, vals = [np.arange(n_free)], [np.arange(n_free)], [np.ones(n_free)]
    for k, (b, arm) in enumerate(zip(mesh.slave_body, arms, strict=True)):
        if body_dof[b] < 0:
            continue
        T = np.hstack((np.eye(3), -skew(arm)))
        r = n_free + 3 * k + np.repeat(np.arange(3), 6)
        c = body_dof[b] + np.tile(np.arange(6), 3)
        rows.append(r)
        cols.append(c)
        vals.append(T.ravel())
    n_u = n_free + 6 * int(np.sum(body_dof >= 0))
    return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                         shape=(ext_dofs, n_u))


def waterplane(hs) -> tuple[float, tuple[float, float]]:
    """Waterplane area and its second moments about x and y (roll, pitch) of a box or
    vertical cylinder hull; zeros for other hydrostatics."""
    if hs.kind == "box":
        return hs.length * hs.width, (hs.length * hs.width**3 / 12.0,
                                      hs.width * hs.length**3 / 12.0)
    if hs.kind == "cylinder":
        return np.pi * hs.diameter**2 / 4.0, (np.pi * hs.diameter**4 / 64.0,) * 2
    return 0.0, (0.0, 0.0)


def long_wave_geometry(body: Body, z: float, rho: float = 0.0,
                       gravity: float = 0.0) -> tuple[float, float]:
    """Waterplane area and submerged volume of the long-wave (small-body) load model at the
    body origin's height ``z``: a box or cylinder hull gives both from its draft; a matrix
    hydrostatics gives its ``volume`` and the waterplane of its heave stiffness,
    ``A_wp = K33 / (rho g)`` (with ``rho`` and ``gravity`` given; else none)."""
    hs = body.hydrostatics
    area_wp = waterplane(hs)[0]
    if hs.kind == "matrix" and rho > 0 and gravity > 0 and hs.stiffness is not None:
        k = np.asarray(hs.stiffness, dtype=float)
        k33 = float(k[2, 2] if k.ndim == 2 else k[2])
        return max(k33, 0.0) / (rho * gravity), hs.volume
    draft = float(np.clip(hs.height / 2 - z, 0.0, hs.height)) \
        if hs.kind in ("box", "cylinder") else 0.0
    return area_wp, (area_wp * draft if area_wp else hs.volume)


def body_loads(body: Body, r: FloatArray, R: FloatArray, gravity: float,
               rho: float) -> tuple[FloatArray, FloatArray]:
    """Gravity, hydrostatics and constant loads on a body: generalized force (6,) about its
    origin and its tangent ``K = -d(force)/d(dr, dtheta)`` (6, 6)."""
    force = np.asarray(body.force, dtype=float).copy()
    K = np.zeros((6, 6))
    weight = np.array([0.0, 0.0, -body.mass * gravity])
    _point_load(force, K, weight, R @ np.asarray(body.center_of_gravity, float))
    hs = body.hydrostatics
    if hs.kind in ("box", "cylinder"):
        _shape_hydrostatics(hs, r, R, gravity, rho, force, K)
    elif hs.kind == "matrix":
        buoyancy = np.array([0.0, 0.0, rho * gravity * hs.volume])
        _point_load(force, K, buoyancy, R @ np.asarray(hs.center_of_buoyancy, float))
        stiffness = np.asarray(hs.stiffness if hs.stiffness is not None else np.zeros((6, 6)))
        turn = rotation_vector(R @ rotation_matrix(np.asarray(body.rotation, float)).T)
        q = np.concatenate((r - np.asarray(body.position, float), turn))
        force -= stiffness @ q
        jac = np.eye(6)
        jac[3:, 3:] = inverse_left_jacobian(turn)
        K += stiffness @ jac
    return force, K


def _point_load(force: FloatArray, K: FloatArray, f: FloatArray, arm: FloatArray) -> None:
    """Add a constant force ``f`` acting at world arm ``arm``; its moment changes as the arm
    rotates: ``K_rot -= [f x][arm x]``."""
    force[:3] += f
    force[3:] += np.cross(arm, f)
    K[3:, 3:] -= skew(f) @ skew(arm)


def _shape_hydrostatics(hs, r, R, gravity, rho, force, K) -> None:
    """Buoyancy of a box or vertical cylinder at its draft (origin at the shape's centre),
    acting at the centre of buoyancy, and the waterplane restoring ``rho g I_wp`` in roll and
    pitch (small-angle, Tuah eq. 3.2.c.20's restoring coefficients)."""
    area, inertia = waterplane(hs)
    draft = float(np.clip(hs.height / 2.0 - r[2], 0.0, hs.height))
    wet = 0.0 < hs.height / 2.0 - r[2] < hs.height
    buoyancy = np.array([0.0, 0.0, rho * gravity * area * draft])
    center = np.array([0.0, 0.0, -hs.height / 2.0 + draft / 2.0])
    arm = R @ center
    _point_load(force, K, buoyancy, arm)
    if wet:
        K[2, 2] += rho * gravity * area  # d(buoyancy)/dz = -rho g A
        # the centre of buoyancy rises by half the draft change: d(arm)/dz = -R e_z / 2
        d_arm = -0.5 * R[:, 2]
        K[3:, 2] -= np.cross(d_arm, buoyancy) + np.cross(arm, [0.0, 0.0, -rho * gravity * area])
    tilt = rotation_vector(R)
    restoring = rho * gravity * np.array([inertia[0], inertia[1], 0.0])
    force[3:] -= restoring * tilt
    K[3:, 3:] += np.diag(restoring) @ inverse_left_jacobian(tilt)


def inverse_left_jacobian(phi: FloatArray) -> FloatArray:
    """``d phi / d theta`` for ``R(phi) <- exp([dtheta x]) R(phi)``: how the rotation vector
    changes under a small rotation applied on the left (SO(3) inverse left Jacobian)."""
    angle = float(np.linalg.norm(phi))
    P = skew(phi)
    if angle < 1e-6:
        return np.eye(3) - 0.5 * P + P @ P / 12.0
    c = 1.0 / angle**2 - (1.0 + np.cos(angle)) / (2.0 * angle * np.sin(angle))
    return np.eye(3) - 0.5 * P + c * P @ P


@dataclass(frozen=True)
class BodyDofs:
    """Layout of the coupled unknowns: the free node dofs, then six per free body; and the
    extended node dofs (free nodes, then the attached nodes) the line tangent is assembled
    over before the master-slave transformation."""

    n_free: int
    body_dof: NDArray[np.int64]
    n_unknowns: int
    ext_dofs: int
    pattern: object
    ext_map: NDArray[np.int64]  # (n_nodes, 3) extended dof of every node (-1: held)

    @classmethod
    def of(cls, mesh: Mesh, bodies: list[Body]) -> BodyDofs:
        """The layout of ``mesh`` with ``bodies`` (in mesh order)."""
        from .assembly import BlockPattern

        n_free = mesh.n_dofs
        free = np.array([b.kind == "free" for b in bodies], dtype=bool)
        body_dof = np.where(free, n_free + 6 * (np.cumsum(free) - 1), -1).astype(np.int64)
        ext = mesh.dof_of_node.copy()
        for k, node in enumerate(mesh.slave_node):
            ext[node] = n_free + 3 * k + np.arange(3)
        return cls(n_free, body_dof, n_free + 6 * int(free.sum()),
                   n_free + 3 * len(mesh.slave_node), BlockPattern(mesh.elements, ext), ext)
