"""Rigid bodies coupled to the lines: poses, loads and the master-slave transformation.

A free body has six unknowns: the position ``r`` of its origin and a small rotation ``dtheta``
applied on the left of its rotation matrix, ``R <- exp([dtheta x]) R``. A node attached to a
body at arm ``a`` (body frame) sits at ``x = r + R a``; a small body motion moves it by
``dx = dr + dtheta x (R a) = T (dr, dtheta)`` with ``T = [I, -[R a x]]`` (Tuah 1982 eq.
3.3.6-3.3.7; Wang, Er and Iu eq. 31-34). Forces ``f`` on attached nodes act on the body as
``T^T f`` (force and moment about the origin); their tangent transforms as ``T^T K T`` plus the
change of the moment arms under fixed forces, ``-[f x][R a x]`` (see
:func:`moorline.solvers.stiffness.group_stiffness`, checked against finite differences).
The rotation maps and the body loads are the kernels of :mod:`moorline.physics.rigid_body`;
this module unpacks the model's :class:`~moorline.model.Body` for them.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from ..mesh import Mesh
from ..model import Body
from ..physics import rigid_body as rb
from ..physics.rigid_body import inverse_left_jacobian, rotation_matrix, rotation_vector, skew

__all__ = ["BodyDofs", "BodyState", "body_loads", "body_mass_matrix", "hold_dofs",
           "inverse_left_jacobian", "long_wave_geometry", "place_slaves", "rotation_vector",
           "skew", "transformation", "waterplane", "world_arms"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class BodyState:
    """BodyState and motions of all bodies, world axes: origins ``r`` (nb, 3), rotation matrices
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
    def initial(cls, mesh: Mesh) -> BodyState:
        """The poses the case gives, at rest."""
        bodies = mesh.bodies
        r = np.array([b.position for b in bodies], dtype=float).reshape(-1, 3)
        R = rotation_matrix(np.array([b.rotation for b in bodies], dtype=float).reshape(-1, 3))
        return cls(r, R)

    @classmethod
    def from_pose(cls, pose: FloatArray) -> BodyState:
        """At rest at poses (nb, 6): position and rotation vector."""
        pose = np.asarray(pose, dtype=float).reshape(-1, 6)
        return cls(pose[:, :3].copy(), rotation_matrix(pose[:, 3:]))

    def copy(self) -> BodyState:
        """An independent copy."""
        return BodyState(self.r.copy(), self.R.copy(), self.vel.copy(), self.acc.copy())

    def moved(self, dr: FloatArray, dtheta: FloatArray) -> BodyState:
        """The poses after small motions ``dr``, ``dtheta`` (n_bodies, 3) each (motions kept)."""
        R = rotation_matrix(np.asarray(dtheta, float)) @ self.R
        return BodyState(self.r + dr, R, self.vel, self.acc)

    def as_array(self) -> FloatArray:
        """(n_bodies, 6): position and rotation vector."""
        return np.hstack((self.r, rotation_vector(self.R).reshape(-1, 3)))

    pose = as_array


def place_slaves(mesh: Mesh, poses: BodyState, x: FloatArray) -> FloatArray:
    """Node positions with the attached nodes on their bodies (a new array)."""
    x = x.copy()
    if len(mesh.slave_node):
        arms = np.einsum("kij,kj->ki", poses.R[mesh.slave_body], mesh.slave_arm)
        x[mesh.slave_node] = poses.r[mesh.slave_body] + arms
    return x


def world_arms(mesh: Mesh, poses: BodyState) -> FloatArray:
    """Arms ``R a`` of the attached nodes in world axes (n_slaves, 3)."""
    return np.einsum("kij,kj->ki", poses.R[mesh.slave_body], mesh.slave_arm)


def transformation(mesh: Mesh, ext_dofs: int, n_free: int, body_dof: NDArray[np.int64],
                   arms: FloatArray, blocks: FloatArray | None = None,
                   free_scale: float = 1.0) -> sp.csr_matrix:
    """The sparse map ``P`` from the unknowns (free node dofs, free body dofs) to the extended
    node dofs (free nodes, then attached nodes), ``dx_ext = P du``: identity (times
    ``free_scale``) on the free node dofs and, for every attached node, ``T = [I, -[R a x]]``
    or its own (3, 6) block of ``blocks`` (n_slaves, 3, 6)."""
    rows, cols = [np.arange(n_free)], [np.arange(n_free)]
    vals = [np.full(n_free, float(free_scale))]
    for k, (b, arm) in enumerate(zip(mesh.slave_body, arms, strict=True)):
        if body_dof[b] < 0:
            continue
        T = np.hstack((np.eye(3), -skew(arm))) if blocks is None else blocks[k]
        r = n_free + 3 * k + np.repeat(np.arange(3), 6)
        c = body_dof[b] + np.tile(np.arange(6), 3)
        rows.append(r)
        cols.append(c)
        vals.append(np.asarray(T).ravel())
    n_u = n_free + 6 * int(np.sum(body_dof >= 0))
    return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                         shape=(ext_dofs, n_u))


def waterplane(hs) -> tuple[float, tuple[float, float]]:
    """Waterplane area and its second moments about x and y (roll, pitch) of a box or
    vertical cylinder hull; zeros for other hydrostatics (:func:`rigid_body.waterplane`)."""
    return rb.waterplane(hs.kind, hs.length, hs.width, hs.diameter)


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
    draft = float(rb.hull_draft(hs.height, z)[0]) if hs.kind in ("box", "cylinder") else 0.0
    return area_wp, (area_wp * draft if area_wp else hs.volume)


def body_loads(body: Body, r: FloatArray, R: FloatArray, gravity: float,
               rho: float) -> tuple[FloatArray, FloatArray]:
    """Gravity, hydrostatics and constant loads on a body: generalized force (6,) about its
    origin and its tangent ``K = -d(force)/d(dr, dtheta)`` (6, 6). Unpacks ``body`` for the
    kernels of :mod:`moorline.physics.rigid_body`."""
    force, K = rb.gravity_load(body.mass, body.center_of_gravity, R, gravity)
    force = np.asarray(body.force, dtype=float) + force
    hs = body.hydrostatics
    parts = []
    if hs.kind in ("box", "cylinder"):
        area, inertia = waterplane(hs)
        parts = [rb.hull_buoyancy(area, hs.height, r, R, rho, gravity),
                 rb.waterplane_restoring(inertia, R, rho, gravity)]
    elif hs.kind == "matrix":
        stiffness = hs.stiffness if hs.stiffness is not None else np.zeros((6, 6))
        parts = [rb.point_load([0.0, 0.0, rho * gravity * hs.volume], hs.center_of_buoyancy,
                               R),
                 rb.matrix_restoring(stiffness, r, R, body.position,
                                     rotation_matrix(body.rotation))]
    for load, dK in parts:
        force, K = force + load, K + dK
    return force, K


def body_mass_matrix(body: Body, R: FloatArray) -> FloatArray:
    """Rigid-body 6x6 mass matrix of ``body`` about its origin, world axes, at rotation ``R``
    (:func:`moorline.physics.rigid_body.rigid_mass`)."""
    return rb.rigid_mass(body.mass, body.center_of_gravity, body.inertia, R)


@dataclass(frozen=True)
class BodyDofs:
    """Layout of the coupled unknowns: the free node dofs, then six per free or pinned body;
    and the extended node dofs (free nodes, then the attached nodes) the line tangent is
    assembled over before the master-slave transformation.

    A pinned body keeps its six unknowns, but its three translations are held (``held``):
    they follow the pin, their residual rows (the pin's reaction) are set to zero and their
    rows and columns of the tangent to the identity (:func:`hold_dofs`), so a Newton step
    leaves them where the pin puts them."""

    n_free: int
    body_dof: NDArray[np.int64]
    n_unknowns: int
    ext_dofs: int
    pattern: object
    ext_map: NDArray[np.int64]  # (n_nodes, 3) extended dof of every node (-1: held)
    held: NDArray[np.bool_] = field(default_factory=lambda: np.zeros(0, dtype=bool))
    pinned: NDArray[np.bool_] = field(default_factory=lambda: np.zeros(0, dtype=bool))

    @classmethod
    def of(cls, mesh: Mesh, bodies: list[Body]) -> BodyDofs:
        """The layout of ``mesh`` with ``bodies`` (in mesh order)."""
        from .assembly import BlockPattern

        n_free = mesh.n_dofs
        pinned = np.array([b.kind == "pinned" for b in bodies], dtype=bool)
        free = np.array([b.kind in ("free", "pinned") for b in bodies], dtype=bool)
        body_dof = np.where(free, n_free + 6 * (np.cumsum(free) - 1), -1).astype(np.int64)
        ext = mesh.dof_of_node.copy()
        for k, node in enumerate(mesh.slave_node):
            ext[node] = n_free + 3 * k + np.arange(3)
        n_unknowns = n_free + 6 * int(free.sum())
        held = np.zeros(n_unknowns, dtype=bool)
        for d in body_dof[pinned]:
            held[d:d + 3] = True
        return cls(n_free, body_dof, n_unknowns, n_free + 3 * len(mesh.slave_node),
                   BlockPattern(mesh.pattern_pairs, ext), ext, held, pinned)


def refuse_pinned(mesh: Mesh, analysis: str) -> None:
    """A :class:`~moorline.errors.CaseError` naming the pinned bodies of ``mesh`` for an
    ``analysis`` that has no held body dofs (modal, stochastic, strumming, harmonic)."""
    from ..errors import CaseError

    pinned = [b.name for b in mesh.bodies if b.kind == "pinned"]
    if pinned:
        raise CaseError(f"{analysis} analyses do not support pinned bodies ("
                        f"{', '.join(pinned)}): use statics or dynamics",
                        field=f"bodies.{pinned[0]}.kind")


def hold_dofs(K: sp.spmatrix, held: NDArray[np.bool_], scale: float = 1.0) -> sp.csc_matrix:
    """``K`` with the ``held`` unknowns' rows and columns replaced by ``scale`` times the
    identity (a pinned body's translations): with a zero residual there, a solve leaves
    them unchanged and the other unknowns see the constrained system."""
    if not held.any():
        return sp.csc_matrix(K)
    keep = sp.diags((~held).astype(float))
    return (keep @ sp.csr_matrix(K) @ keep + sp.diags(scale * held.astype(float))).tocsc()
