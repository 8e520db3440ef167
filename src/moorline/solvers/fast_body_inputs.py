"""The arrays the compiled step with bodies takes (:mod:`moorline.solvers.fast_bodies`), built
from a :class:`~moorline.solvers.body_model.BodyModel`: the attached nodes, the bodies'
constants, their state at the start of a block, their radiation memory (modes and states), the
pinned bodies' pins and the loads that depend on time alone at its sub-steps (force histories,
:meth:`BodyModel._excitation`'s exciting-force tables)."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ..physics.rigid_body import rotation_matrix, waterplane
from .bodies import BodyState
from .excitation import history_values, ramps
from .fast_path import HULL_KINDS

FloatArray = NDArray[np.float64]


def _square(value, n: int = 6) -> FloatArray:
    """A matrix given as None (zeros), its diagonal or itself (n, n)."""
    if value is None:
        return np.zeros((n, n))
    value = np.asarray(value, dtype=float)
    return np.diag(value) if value.ndim == 1 else value


def _modes(models: list) -> tuple:
    """Every radiation-memory mode of the bodies (:class:`MemoryModel` per body, None
    without a table): its body, force dof, velocity dof, pole and coefficient."""
    parts = [(np.full(mem.n_states, k), mem.row, mem.col, mem.poles, mem.coefficients)
             for k, mem in enumerate(models) if mem is not None]
    kinds = (np.int64, np.int64, np.int64, complex, complex)
    return tuple(np.concatenate([p[i] for p in parts]).astype(t) if parts
                 else np.zeros(0, dtype=t) for i, t in enumerate(kinds))


def _rods(hydrostatics: list) -> tuple:
    """The rods of ``rods`` hydrostatics, all bodies' in one list: the first rod of each body
    (nb + 1,), then the rods' body-frame ends A and B (n, 3) and diameters (n,) [length]."""
    rods = [rod for h in hydrostatics if h.kind == "rods" for rod in h.rods]
    counts = [len(h.rods) if h.kind == "rods" else 0 for h in hydrostatics]
    first = np.concatenate(([0], np.cumsum(counts))).astype(np.int64)
    ends = np.array([(a, b) for a, b, _ in rods], dtype=np.float64).reshape(-1, 2, 3)
    return (first, ends[:, 0].copy(), ends[:, 1].copy(),
            np.array([d for *_, d in rods], dtype=np.float64))


class BodyInputs:
    """The compiled step's ``bodies`` argument for the free bodies of ``body_model`` (None:
    no bodies, every array empty) on a band of ``n_band`` rows."""

    def __init__(self, body_model, mesh, n_band: int) -> None:
        from .body_model import _exciting_terms

        self.model = body_model
        bodies = [] if body_model is None else body_model.bodies
        nb = len(bodies)
        self.nb = nb
        node = np.asarray(mesh.slave_node if nb else np.zeros(0), dtype=np.int64)
        slave_of_node = np.full(mesh.n_nodes, -1, dtype=np.int64)
        slave_of_node[node] = np.arange(len(node))
        self.links = (node, np.asarray(mesh.slave_body if nb else np.zeros(0), dtype=np.int64),
                      np.asarray(mesh.slave_arm if nb else np.zeros((0, 3)),
                                 dtype=float).reshape(-1, 3), slave_of_node)
        hs = [b.hydrostatics for b in bodies]
        planes = [waterplane(h.kind, h.length, h.width, h.diameter) for h in hs]
        f8 = np.float64
        self.loads = (
            np.array([b.mass for b in bodies], dtype=f8),
            np.array([b.center_of_gravity for b in bodies], dtype=f8).reshape(nb, 3),
            np.array([_square(b.inertia, 3) for b in bodies], dtype=f8).reshape(nb, 3, 3),
            np.array(body_model.added if nb else [], dtype=f8).reshape(nb, 6, 6),
            np.array(body_model.damping if nb else [], dtype=f8).reshape(nb, 6, 6),
            np.array([b.force for b in bodies], dtype=f8).reshape(nb, 6),
            np.array([HULL_KINDS[h.kind] for h in hs], dtype=np.int64),
            np.array([p[0] for p in planes], dtype=f8),
            np.array([h.height for h in hs], dtype=f8),
            np.array([p[1] for p in planes], dtype=f8).reshape(nb, 2),
            np.array([h.volume for h in hs], dtype=f8),
            np.array([h.center_of_buoyancy for h in hs], dtype=f8).reshape(nb, 3),
            np.array([_square(h.stiffness) for h in hs], dtype=f8).reshape(nb, 6, 6),
            np.array([b.position for b in bodies], dtype=f8).reshape(nb, 3),
            rotation_matrix(np.array([b.rotation for b in bodies], dtype=f8).reshape(nb, 3)),
            float(mesh.gravity), float(mesh.water_density), *_rods(hs),
            np.array([float(mesh.water_density) * np.asarray(b.Cd, dtype=f8)
                      * np.asarray(b.drag_area, dtype=f8) for b in bodies],
                     dtype=f8).reshape(nb, 3))
        self.exciting = [None if b.excitation is None else
                         _exciting_terms(b.excitation, body_model.fluid, body_model.origin0[k])
                         for k, b in enumerate(bodies)]
        self.modes = _modes(body_model.memory if nb else [])
        m = 6 * nb
        self.work = (np.zeros((m, n_band)), np.zeros((m, n_band)), np.zeros((m, m)),
                     np.zeros((m, m)))

    def state(self, bs: BodyState | None, other0: FloatArray | None) -> tuple:
        """The state arrays at the start of a block: the bodies ``bs`` and their
        non-inertial generalized forces ``other0`` (HHT; None: zeros)."""
        nb = self.nb
        z6 = np.zeros((nb, 6))
        if nb == 0:
            r, R, vel, acc = np.zeros((0, 3)), np.zeros((0, 3, 3)), z6, z6.copy()
        else:
            r, R, vel, acc = (np.array(q, dtype=float) for q in (bs.r, bs.R, bs.vel, bs.acc))
        ns = len(self.links[0])
        return (r, R, vel, acc, z6.copy(), z6.copy(), r.copy(), R.copy(), vel.copy(),
                acc.copy(), np.zeros((ns, 3)),
                z6.copy() if other0 is None else np.array(other0, dtype=float), z6.copy(),
                np.zeros((ns, 3)))

    def memory(self, states: tuple | None) -> tuple:
        """The compiled memory (:mod:`moorline.solvers.fast_bodies`) at the start of a
        block: the modes and the states ``states`` (one complex array per body, None for a
        body without a table; None: at rest)."""
        n = len(self.modes[0])
        z0 = np.zeros(n, dtype=complex)
        if states is not None:
            for k, z in enumerate(states):
                if z is not None:
                    z0[self.modes[0] == k] = z
        return (*self.modes, z0, z0.copy(), np.zeros(n, dtype=complex))

    def pins(self, times: FloatArray, pin_force: FloatArray | None) -> tuple:
        """The compiled pins (:mod:`moorline.solvers.fast_bodies`) of a block of sub-steps
        ending at ``times``: which bodies are pinned, their pins' position, velocity and
        acceleration (:func:`~moorline.solvers.body_model.pin_state`) per sub-step, the
        sub-step, and the pins' forces (``pin_force`` at the start: None, zeros)."""
        from .body_model import pin_state

        bodies = self.model.bodies if self.nb else []
        pinned = np.array([b.kind == "pinned" for b in bodies], dtype=np.bool_)
        kin = np.zeros((len(times), self.nb, 3, 3))
        if pinned.any():
            for k, t in enumerate(times):
                kin[k] = np.stack(pin_state(bodies, float(t)), axis=1)
        force0 = np.zeros((self.nb, 3)) if pin_force is None else \
            np.array(pin_force, dtype=float)
        return pinned, kin, np.zeros(1, dtype=np.int64), force0.copy(), force0

    def memory_states(self, memory: tuple) -> tuple | None:
        """The states at the start of the step in :meth:`memory`'s tuple as
        :attr:`StepState.memory` (None when no body has a table)."""
        models = self.model.memory if self.nb else []
        if all(mem is None for mem in models):
            return None
        body, z0 = memory[0], memory[5]
        return tuple(None if mem is None else z0[body == k].copy()
                     for k, mem in enumerate(models))

    def forces(self, times: FloatArray) -> FloatArray:
        """Loads on the bodies that depend on time alone at ``times`` (n,), (n, nb, 9):
        :meth:`BodyModel.forces`'s force histories and exciting forces ``[..., :6]``, then
        the fluid velocity at a wet body origin ``[..., 6:]`` (a uniform current, ramped; the
        compiled step takes body drag without waves only)."""
        times = np.asarray(times, dtype=float)
        out = np.zeros((len(times), self.nb, 9))
        if self.nb and self.loads[-1].any():  # the current for the bodies' drag
            for i, t in enumerate(times):
                out[i, :, 6:] = self.model.fluid.kinematics(np.zeros((1, 3)), float(t))[0][0]
        for k in range(self.nb):
            body = self.model.bodies[k]
            if body.force_history is not None:
                out[:, k, :3] += history_values(body.force_history, times)
            terms = self.exciting[k]
            if terms is not None:  # rigid_body.wave_excitation at every time
                a, w, shift, amp, phase, ramp_time = terms
                arg = w[None, :] * times[:, None] - shift[None, :]  # cos(arg + phase) split
                scaled = a[:, None] * amp
                load = np.cos(arg) @ (scaled * np.cos(phase)) \
                    - np.sin(arg) @ (scaled * np.sin(phase))
                out[:, k, :6] += ramps(times, ramp_time)[0][:, None] * load
        return out

    def records(self, n: int) -> tuple:
        """Record buffers (origins, rotations, velocities, pin forces) for ``n``
        records."""
        return (np.empty((n, self.nb, 3)), np.empty((n, self.nb, 3, 3)),
                np.empty((n, self.nb, 6)), np.empty((n, self.nb, 3)))

    def tangent_state(self) -> tuple:
        """Copies of the factorization's border."""
        return tuple(w.copy() for w in self.work)

    def set_tangent_state(self, saved: tuple) -> None:
        """Restore what :meth:`tangent_state` returned."""
        for w, s in zip(self.work, saved, strict=True):
            w[...] = s
