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
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from ..mesh import Mesh
from ..model import Body
from ..physics import rigid_body as rb
from ..physics.rigid_body import inverse_left_jacobian, rotation_matrix, rotation_vector, skew
from ..physics.rod_buoyancy import rod_buoyancy

if TYPE_CHECKING:
    import scipy.sparse as sp

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
    import scipy.sparse as sp

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
    kernels of :mod:`moorline.physics.rigid_body` (``rods`` hydrostatics:
    :mod:`moorline.physics.rod_buoyancy`)."""
    force, K = rb.gravity_load(body.mass, body.center_of_gravity, R, gravity)
    force = np.asarray(body.force, dtype=float) + force
    hs = body.hydrostatics
    parts = []
    if hs.kind in ("box", "cylinder"):
        area, inertia = waterplane(hs)
        parts = [rb.hull_buoyancy(area, hs.height, r, R, rho, gravity),
                 rb.waterplane_restoring(inertia, R, rho, gravity)]
    elif hs.kind in ("matrix", "rods"):  # a constant buoyancy at the centre of buoyancy
        parts = [rb.point_load([0.0, 0.0, rho * gravity * hs.volume], hs.center_of_buoyancy,
                               R)]
    if hs.kind == "matrix":
        stiffness = hs.stiffness if hs.stiffness is not None else np.zeros((6, 6))
        parts.append(rb.matrix_restoring(stiffness, r, R, body.position,
                                         rotation_matrix(body.rotation)))
    elif hs.kind == "rods" and hs.rods:
        ends = np.array([(a, b) for a, b, _ in hs.rods], dtype=float)
        parts.append(rod_buoyancy(ends[:, 0], ends[:, 1], [d for *_, d in hs.rods], r, R,
                                  rho, gravity))
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
    leaves them where the pin puts them. A pin on a free body (``pin_parent``, the pin at
    ``pin_arm`` in that body's frame) moves with it: the pinned body's translation is a
    slave of its host's six dofs (:meth:`chain_map`, the master-slave relation of Tuah 1982
    eq. 3.3.6 applied to the pin), its translational force moves onto the host
    (:meth:`transfer`). ``spin``: pinned rods whose spin about their own axis is a mechanism
    (:func:`spin_projection`)."""

    n_free: int
    body_dof: NDArray[np.int64]
    n_unknowns: int
    ext_dofs: int
    pattern: object
    ext_map: NDArray[np.int64]  # (n_nodes, 3) extended dof of every node (-1: held)
    held: NDArray[np.bool_] = field(default_factory=lambda: np.zeros(0, dtype=bool))
    pinned: NDArray[np.bool_] = field(default_factory=lambda: np.zeros(0, dtype=bool))
    pin_parent: NDArray[np.int64] = field(default_factory=lambda: np.zeros(0, dtype=np.int64))
    pin_arm: FloatArray = field(default_factory=lambda: np.zeros((0, 3)))
    spin: NDArray[np.bool_] = field(default_factory=lambda: np.zeros(0, dtype=bool))

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
        names = [b.name for b in bodies]
        parent = np.full(len(bodies), -1, dtype=np.int64)
        arm = np.zeros((len(bodies), 3))
        for k, body in enumerate(bodies):
            host = getattr(body, "pin_body", None)
            if host is None or bodies[names.index(host)].kind != "free":
                continue  # a pin in space or on a fixed body stays where it is
            p = names.index(host)
            parent[k] = p
            R0 = rotation_matrix(np.asarray(bodies[p].rotation, dtype=float))
            arm[k] = R0.T @ (np.asarray(body.position, float) - np.asarray(bodies[p].position,
                                                                            float))
        spin = np.array([k == "pinned" and _axisymmetric(mesh, bodies, i)
                         for i, k in enumerate(b.kind for b in bodies)], dtype=bool)
        return cls(n_free, body_dof, n_unknowns, n_free + 3 * len(mesh.slave_node),
                   BlockPattern(mesh.pattern_pairs, ext), ext, held, pinned, parent, arm,
                   spin)

    @property
    def chains(self) -> list[tuple[int, int]]:
        """(pinned body, body its pin moves with) pairs."""
        return [(int(c), int(p)) for c, p in enumerate(self.pin_parent) if p >= 0]

    def pin_arms(self, poses: BodyState) -> FloatArray:
        """World arms ``R_p a`` from each chained body's host origin to its pin (nb, 3)."""
        out = np.zeros((len(self.pin_parent), 3))
        for c, p in self.chains:
            out[c] = poses.R[p] @ self.pin_arm[c]
        return out

    def place_pins(self, poses: BodyState) -> BodyState:
        """``poses`` with every chained pinned body's origin (and its velocity and
        acceleration) those of its pin on its host: ``r_p + R_p a``, ``v_p + w_p x R_p a``,
        ``a_p + alpha_p x R_p a + w_p x (w_p x R_p a)``."""
        if not self.chains:
            return poses
        out = poses.copy()
        arms = self.pin_arms(poses)
        for c, p in self.chains:
            w, al = poses.vel[p, 3:], poses.acc[p, 3:]
            out.r[c] = poses.r[p] + arms[c]
            out.vel[c, :3] = poses.vel[p, :3] + np.cross(w, arms[c])
            out.acc[c, :3] = (poses.acc[p, :3] + np.cross(al, arms[c])
                              + np.cross(w, np.cross(w, arms[c])))
        return out

    def chain_map(self, arms: FloatArray, blocks: FloatArray | None = None) -> sp.csr_matrix:
        """``Q`` (n_unknowns square): the unknowns with every chained pinned body's
        translation following its host, ``du = Q du~``: the identity, but a chained body's
        translation columns replaced by ``T = [I, -[R_p a x]]`` (or its (3, 6) block of
        ``blocks``, per body) in its host's columns."""
        import scipy.sparse as sp

        n = self.n_unknowns
        diag = np.ones(n)
        rows, cols, vals = [np.arange(n)], [np.arange(n)], [diag]
        for c, p in self.chains:
            dc, dp = self.body_dof[c], self.body_dof[p]
            diag[dc:dc + 3] = 0.0
            T = np.hstack((np.eye(3), -skew(arms[c]))) if blocks is None else blocks[c]
            rows.append(dc + np.repeat(np.arange(3), 6))
            cols.append(dp + np.tile(np.arange(6), 3))
            vals.append(np.asarray(T).ravel())
        return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows),
                                                     np.concatenate(cols))), shape=(n, n))

    def transfer(self, r: FloatArray, arms: FloatArray) -> FloatArray:
        """Residual ``Q^T r``: a chained body's translational force moves onto its host
        (force, and moment ``R_p a x F`` about the host's origin); its own rows then held
        at zero by the caller."""
        for c, p in self.chains:
            dc, dp = self.body_dof[c], self.body_dof[p]
            F = r[dc:dc + 3].copy()
            r[dp:dp + 3] += F
            r[dp + 3:dp + 6] += np.cross(arms[c], F)
        return r

    def arm_turning(self, r: FloatArray, arms: FloatArray) -> sp.csr_matrix:
        """The host's tangent from its pin arm turning under the chained body's force ``F``
        (its translational residual in ``r``, before the transfer): ``-[F x][R_p a x]`` on
        the host's rotation block (for ``R <- exp([e x]) R``)."""
        import scipy.sparse as sp

        n = self.n_unknowns
        out = sp.lil_matrix((n, n))
        for c, p in self.chains:
            dc, dp = self.body_dof[c], self.body_dof[p]
            out[dp + 3:dp + 6, dp + 3:dp + 6] = -skew(r[dc:dc + 3]) @ skew(arms[c])
        return out.tocsr()


def _axisymmetric(mesh: Mesh, bodies: list[Body], b: int) -> bool:
    """Whether every load of body ``b`` acts on its x axis (a rod: its attached points, centres
    of gravity and buoyancy there, no hydrostatic stiffness, moment, drag or wave loads), so
    that its spin about that axis meets no moment and no stiffness."""
    body = bodies[b]
    hs = body.hydrostatics
    if hs.kind not in ("none", "matrix", "rods") or (hs.stiffness is not None
                                             and np.any(np.asarray(hs.stiffness, float))):
        return False
    if any(body.force[3:]) or any(body.drag_area) or body.wave_loads or \
            body.excitation is not None or body.radiation is not None:
        return False
    spots = [np.asarray(body.center_of_gravity, float), np.asarray(hs.center_of_buoyancy, float),
             *np.asarray([end for a, b, _ in hs.rods for end in (a, b)], float).reshape(-1, 3),
             *np.asarray(mesh.slave_arm, float).reshape(-1, 3)[mesh.slave_body == b]]
    scale = 1.0 + max(float(np.abs(p).max()) for p in spots)
    return all(abs(p[1]) <= 1e-9 * scale and abs(p[2]) <= 1e-9 * scale for p in spots)


def spin_projection(layout: BodyDofs, poses: BodyState) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    """For the statics of rods pinned at one end (:attr:`BodyDofs.spin`), whose spin about
    their own axis ``n = R e_x`` meets no moment and no stiffness (a mechanism; MoorDyn's rods
    carry every load on their axis): ``S``, the identity with each such body's rotation block
    ``I - n n^T`` (the spin projected out of residual, tangent and step), and ``N``, its
    ``n n^T`` (scaled by the caller into the tangent so that it stays regular)."""
    import scipy.sparse as sp

    n_u = layout.n_unknowns
    rows, cols, vals = [np.arange(n_u)], [np.arange(n_u)], [np.ones(n_u)]
    n_rows, n_cols, n_vals = [], [], []
    for b in np.flatnonzero(layout.spin):
        d = layout.body_dof[b] + 3
        axis = poses.R[b][:, 0]
        block = np.eye(3) - np.outer(axis, axis)
        i, j = np.meshgrid(np.arange(3) + d, np.arange(3) + d, indexing="ij")
        rows.append(i.ravel())
        cols.append(j.ravel())
        vals.append((block - np.eye(3)).ravel())
        n_rows.append(i.ravel())
        n_cols.append(j.ravel())
        n_vals.append(np.outer(axis, axis).ravel())
    S = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                      shape=(n_u, n_u))
    if not n_rows:
        return S, sp.csr_matrix((n_u, n_u))
    N = sp.csr_matrix((np.concatenate(n_vals), (np.concatenate(n_rows),
                                                np.concatenate(n_cols))), shape=(n_u, n_u))
    return S, N


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
    import scipy.sparse as sp

    if not held.any():
        return sp.csc_matrix(K)
    keep = sp.diags((~held).astype(float))
    return (keep @ sp.csr_matrix(K) @ keep + sp.diags(scale * held.astype(float))).tocsc()
