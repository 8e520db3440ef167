"""Independent linear model of a moored rigid body: small motions about static equilibrium.

A reference for the Tuah (1982) Example 5 and 7 cases, written apart from moorline's solvers
(numpy and scipy only). The same system as the cases' moorline model, in the limit of a
vanishing wave amplitude:

* **Body** (Tuah eq. 3.2.c.20 / 3.3.1): rigid mass about the body origin, constant added mass
  ``A`` and radiation damping ``B``; weight at the centre of gravity and buoyancy
  ``rho g V`` at the centre of buoyancy as world-vertical forces at body-fixed points; a
  constant restoring matrix ``S`` about the body's reference pose (load ``-S q``, ``q`` the
  offset and the rotation vector); a constant world force (the wind) at the origin.
* **Legs**: 2-node elastic elements (tension ``EA (l / L0 - 1)``; the legs must be taut at the
  static state, there is no slack law), masses lumped half an
  element to each node (or the consistent bar mass), submerged weight lumped the same way,
  added mass ``rho A L0 / 2 [Ca (I - t t^T) + Cat t t^T]`` per node of each element and the
  Morison fluid inertia ``rho A L0 / 2 [(1 + Ca)(I - t t^T) + (1 + Cat) t t^T] a_f`` with the
  Airy acceleration at the element midpoint (Tuah eq. 3.2.a.2, 3.2.a.10). The quadratic drag
  ``|u| u`` has a zero derivative at rest: it drops out of the small-amplitude limit.
* **Seabed**: a penalty spring and damper per node, blended in over a band ``ramp`` centred
  on the surface (``k q^2 / (2 ramp)``, ``q = p + ramp / 2``, for ``|p| < ramp / 2``; ``k p``
  beyond; damping ``c min(q / ramp, 1)``; ``k``, ``c`` per unit contact area times ``D``
  times the node's tributary length;
  ``ramp = max(w L_trib / k, D / 4)``): the documented law of the case's seabed.
* **Coupling**: the fairlead node rides on the body, ``x_f = r + R a`` (Tuah eq. 3.3.6-3.3.7).

The static state is found by a root solve of these force balances (scipy), the tangent
stiffness by central differences of them, rotations as a small rotation ``dtheta`` applied on
the left of the static rotation (world axes). The response to a wave ramped in with
``(1 - cos(pi t / T_r)) / 2`` is solved exactly from rest: the forcing is a sum of complex
exponentials, so the state is their particular solutions plus the matrix-exponential
homogeneous part (no time-stepping error).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray
from scipy.linalg import expm, solve
from scipy.optimize import least_squares, root
from scipy.spatial.transform import Rotation

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]


def _skew(v: FloatArray) -> FloatArray:
    return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])


@dataclass(frozen=True)
class Leg:
    """A cable leg from a fixed anchor to a body-fixed fairlead ``arm`` (body frame)."""

    anchor: tuple[float, float, float]
    arm: tuple[float, float, float]
    length: float
    n_elements: int
    EA: float
    mass_per_length: float
    weight_per_length: float  # submerged
    diameter: float
    Ca: float
    Cat: float = 0.0
    seabed_stiffness: float = 0.0  # per unit contact area
    seabed_damping: float = 0.0


@dataclass(frozen=True)
class RigidBody:
    """The body: origin at ``reference`` (the pose of the restoring matrix, no rotation)."""

    mass: float
    cog: tuple[float, float, float]
    inertia: FloatArray  # (3, 3) about the centre of gravity, body frame
    added_mass: FloatArray  # (6, 6) about the origin
    damping: FloatArray  # (6, 6)
    restoring: FloatArray  # (6, 6)
    reference: tuple[float, float, float]
    buoyancy: float  # rho g V
    cob: tuple[float, float, float]
    force: tuple[float, float, float]  # constant world force at the origin


@dataclass(frozen=True)
class Sea:
    """Water depth, density and gravity."""

    depth: float
    rho: float
    gravity: float


@dataclass
class LinearSystem:
    """The static state and the linear matrices (unknowns: 6 body dofs, then 3 per free node).

    ``pose0``: body origin and rotation vector; ``nodes0[leg]``: node positions from the anchor
    to the fairlead (n_el + 1, 3); ``tension0[leg]``: element tensions from the anchor up.
    """

    body: RigidBody
    legs: tuple[Leg, ...]
    sea: Sea
    pose0: FloatArray
    nodes0: list[FloatArray]
    tension0: list[FloatArray]
    M: FloatArray = field(default_factory=lambda: np.zeros((0, 0)))
    C: FloatArray = field(default_factory=lambda: np.zeros((0, 0)))
    K: FloatArray = field(default_factory=lambda: np.zeros((0, 0)))

    @property
    def n(self) -> int:
        """Number of unknowns."""
        return 6 + 3 * sum(leg.n_elements - 1 for leg in self.legs)

    def free_slice(self, k: int) -> slice:
        """Unknowns of the free nodes of leg ``k`` (anchor side first)."""
        start = 6 + 3 * sum(leg.n_elements - 1 for leg in self.legs[:k])
        return slice(start, start + 3 * (self.legs[k].n_elements - 1))

    def fairlead_map(self, k: int) -> FloatArray:
        """(3, n): displacement of leg ``k``'s fairlead from the unknowns."""
        rho = self.nodes0[k][-1] - self.pose0[:3]
        P = np.zeros((3, self.n))
        P[:, :3] = np.eye(3)
        P[:, 3:6] = -_skew(rho)
        return P

    def node_map(self, k: int, i: int) -> FloatArray:
        """(3, n): displacement of node ``i`` (0 anchor .. n_el fairlead) of leg ``k``."""
        n_el = self.legs[k].n_elements
        if i == n_el:
            return self.fairlead_map(k)
        P = np.zeros((3, self.n))
        if i > 0:
            s = self.free_slice(k).start + 3 * (i - 1)
            P[:, s:s + 3] = np.eye(3)
        return P

    def top_tension_map(self, k: int) -> FloatArray:
        """(n,): tension change of leg ``k``'s top element per unit of the unknowns."""
        leg = self.legs[k]
        x = self.nodes0[k]
        d = x[-1] - x[-2]
        t = d / np.linalg.norm(d)
        L0 = leg.length / leg.n_elements
        return (leg.EA / L0) * t @ (self.node_map(k, leg.n_elements)
                                    - self.node_map(k, leg.n_elements - 1))


# ----------------------------------------------------------------------------- forces
def _seabed(leg: Leg, sea: Sea, z: FloatArray, vz: FloatArray | None = None) -> FloatArray:
    """Upward seabed force on interior nodes at heights ``z``."""
    if leg.seabed_stiffness <= 0:
        return np.zeros_like(z)
    L0 = leg.length / leg.n_elements
    k = leg.seabed_stiffness * leg.diameter * L0
    ramp = max(leg.weight_per_length * L0 / k, 0.25 * leg.diameter)
    p = -(z + sea.depth)
    q = np.clip(p + 0.5 * ramp, 0, None)
    spring = np.where(q >= ramp, k * p, k * q**2 / (2 * ramp))
    if vz is not None:
        spring = spring - leg.seabed_damping * leg.diameter * L0 * np.clip(q / ramp, 0, 1) * vz
    return np.where(q > 0, spring, 0.0)


def _leg_forces(leg: Leg, sea: Sea, x: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Forces on the interior nodes (n_el - 1, 3), the force on the fairlead node (with its
    lumped weight) and the element tensions, for node positions ``x`` (n_el + 1, 3)."""
    L0 = leg.length / leg.n_elements
    d = np.diff(x, axis=0)
    length = np.linalg.norm(d, axis=1)
    t = d / length[:, None]
    tension = leg.EA * (length / L0 - 1.0)
    f = np.zeros_like(x)
    f[:-1] += tension[:, None] * t
    f[1:] -= tension[:, None] * t
    f[:, 2] -= leg.weight_per_length * L0 * np.r_[0.5, np.ones(len(x) - 2), 0.5]
    inner = f[1:-1]
    inner[:, 2] += _seabed(leg, sea, x[1:-1, 2])
    return inner, f[-1], tension


def _body_force(body: RigidBody, sea: Sea, r: FloatArray, R: FloatArray,
                fairlead: list[tuple[FloatArray, FloatArray]]) -> FloatArray:
    """Generalized force (6,) about the origin at ``r``, rotation ``R``: the constant force,
    weight, buoyancy, the restoring ``-S q`` and the fairlead forces ``(world arm, force)``."""
    out = np.zeros(6)
    out[:3] += body.force
    loads = [(R @ np.asarray(body.cog), np.array([0.0, 0.0, -body.mass * sea.gravity])),
             (R @ np.asarray(body.cob), np.array([0.0, 0.0, body.buoyancy])), *fairlead]
    for arm, f in loads:
        out[:3] += f
        out[3:] += np.cross(arm, f)
    q = np.concatenate((r - np.asarray(body.reference), Rotation.from_matrix(R).as_rotvec()))
    return out - np.asarray(body.restoring) @ q


def _forces(body: RigidBody, legs: tuple[Leg, ...], sea: Sea, r: FloatArray, R: FloatArray,
            inner: list[FloatArray]) -> tuple[FloatArray, list[FloatArray]]:
    """All static forces: on the body (6,) and on the free nodes (concatenated); and the
    element tensions of every leg."""
    fairlead, node_f, tensions = [], [], []
    for leg, xi in zip(legs, inner, strict=True):
        arm = R @ np.asarray(leg.arm)
        x = np.vstack((leg.anchor, xi, r + arm))
        f_in, f_top, tension = _leg_forces(leg, sea, x)
        fairlead.append((arm, f_top))
        node_f.append(f_in.ravel())
        tensions.append(tension)
    return np.concatenate([_body_force(body, sea, r, R, fairlead), *node_f]), tensions


def _split(legs: tuple[Leg, ...], values: FloatArray) -> list[FloatArray]:
    out, k = [], 0
    for leg in legs:
        n = 3 * (leg.n_elements - 1)
        out.append(values[k:k + n].reshape(-1, 3))
        k += n
    return out


# ----------------------------------------------------------------------------- statics
def equilibrium(body: RigidBody, legs: tuple[Leg, ...], sea: Sea, pose_guess: FloatArray,
                nodes_guess: list[FloatArray], mass: str = "lumped") -> LinearSystem:
    """Static equilibrium (root solve of the force balances; yaw held, it has no stiffness
    about a fairlead on the axis) and the linear matrices about it.

    Parameters
    ----------
    pose_guess
        Body origin and rotation vector (6,).
    nodes_guess
        Per leg, the interior node positions (n_el - 1, 3).
    mass
        ``lumped`` or ``consistent`` structural mass of the legs (added mass lumped).
    """
    def unpack(z: FloatArray) -> tuple[FloatArray, FloatArray, list[FloatArray]]:
        R = Rotation.from_rotvec([z[3], z[4], 0.0]).as_matrix()
        return z[:3], R, _split(legs, z[5:])

    def residual(z: FloatArray) -> FloatArray:
        r, R, inner = unpack(z)
        f, _ = _forces(body, legs, sea, r, R, inner)
        return np.delete(f, 5) / scale

    scale = max(body.mass * sea.gravity, 1.0)
    z0 = np.concatenate((pose_guess[:5], *[np.asarray(n, float).ravel() for n in nodes_guess]))
    sol = root(residual, z0, method="hybr", options={"xtol": 1e-13})
    if not sol.success:  # from a poor guess: trust region first, then polish
        rough = least_squares(residual, z0, xtol=1e-12, ftol=1e-12, gtol=1e-12)
        sol = root(residual, rough.x, method="hybr", options={"xtol": 1e-13})
    if not sol.success or np.max(np.abs(residual(sol.x))) > 1e-9:
        raise RuntimeError(f"linear model statics did not converge: {sol.message}")
    r, R, inner = unpack(sol.x)
    _, tensions = _forces(body, legs, sea, r, R, inner)
    pose = np.concatenate((r, Rotation.from_matrix(R).as_rotvec()))
    nodes = [np.vstack((leg.anchor, xi, r + R @ np.asarray(leg.arm)))
             for leg, xi in zip(legs, inner, strict=True)]
    system = LinearSystem(body, legs, sea, pose, nodes, tensions)
    _matrices(system, R, inner, mass)
    return system


def _matrices(s: LinearSystem, R0: FloatArray, inner0: list[FloatArray], mass: str) -> None:
    """Tangent stiffness (central differences), damping and mass about the static state."""
    n = s.n
    r0 = s.pose0[:3]

    def forces(u: FloatArray) -> FloatArray:
        R = Rotation.from_rotvec(u[3:6]).as_matrix() @ R0
        inner = [x + d for x, d in zip(inner0, _split(s.legs, u[6:]), strict=True)]
        return _forces(s.body, s.legs, s.sea, r0 + u[:3], R, inner)[0]

    K = np.zeros((n, n))
    for j in range(n):
        h = 1e-7 if 3 <= j < 6 else 1e-5
        e = np.zeros(n)
        e[j] = h
        K[:, j] = -(forces(e) - forces(-e)) / (2 * h)
    C = np.zeros((n, n))
    C[:6, :6] = s.body.damping
    M = np.zeros((n, n))
    b = s.body
    c = R0 @ np.asarray(b.cog)
    Sc = _skew(c)
    M[:3, :3] = b.mass * np.eye(3)
    M[:3, 3:6] = -b.mass * Sc
    M[3:6, :3] = b.mass * Sc
    M[3:6, 3:6] = R0 @ np.asarray(b.inertia) @ R0.T - b.mass * Sc @ Sc
    M[:6, :6] += b.added_mass
    for k, leg in enumerate(s.legs):
        L0 = leg.length / leg.n_elements
        x = s.nodes0[k]
        area = 0.25 * math.pi * leg.diameter**2
        maps = [s.node_map(k, i) for i in range(leg.n_elements + 1)]
        for e in range(leg.n_elements):
            d = x[e + 1] - x[e]
            t = d / np.linalg.norm(d)
            tt = np.outer(t, t)
            added = 0.5 * s.sea.rho * area * L0 * (leg.Ca * (np.eye(3) - tt) + leg.Cat * tt)
            ms = leg.mass_per_length * L0
            P1, P2 = maps[e], maps[e + 1]
            if mass == "consistent":
                M += ms / 3 * (P1.T @ P1 + P2.T @ P2) + ms / 6 * (P1.T @ P2 + P2.T @ P1)
            else:
                M += ms / 2 * (P1.T @ P1 + P2.T @ P2)
            M += P1.T @ added @ P1 + P2.T @ added @ P2
        if leg.seabed_damping > 0:
            p = -(x[1:-1, 2] + s.sea.depth)
            kk = leg.seabed_stiffness * leg.diameter * L0
            ramp = max(leg.weight_per_length * L0 / kk, 0.25 * leg.diameter)
            share = np.clip((p + 0.5 * ramp) / ramp, 0, 1)
            for i, sh in enumerate(share, start=1):
                P = maps[i][2]
                C += leg.seabed_damping * leg.diameter * L0 * sh * np.outer(P, P)
    s.M, s.C, s.K = M, C, K


# ----------------------------------------------------------------------------- wave loads
def airy_velocity(omega: float, k: float, depth: float, amplitude: float, x: FloatArray,
                  heading_deg: float = 0.0) -> ComplexArray:
    """Complex Airy velocity (..., 3) at points ``x`` (..., 3): ``u = Re(U e^{-i w t})`` for
    ``eta = a cos(k x_h - w t)`` (finite depth; points above the still water level take the
    ``z = 0`` values, below the seabed the seabed's)."""
    x = np.asarray(x, float)
    beta = math.radians(heading_deg)
    z = np.clip(x[..., 2], -depth, 0.0)
    ch = np.cosh(k * (z + depth)) / np.sinh(k * depth)
    sh = np.sinh(k * (z + depth)) / np.sinh(k * depth)
    phase = amplitude * omega * np.exp(1j * k * (x[..., 0] * math.cos(beta)
                                                 + x[..., 1] * math.sin(beta)))
    return np.stack((ch * math.cos(beta) * phase, ch * math.sin(beta) * phase,
                     -1j * sh * phase), axis=-1)


def cable_inertia_operator(s: LinearSystem, omega: float, k: float, amplitude: float,
                           heading_deg: float = 0.0) -> ComplexArray:
    """(n,) the legs' Morison fluid-inertia operator ``G``: for the fluid velocity
    ``Re(U e^{s t})`` (Airy, wave of ``amplitude``) the load is ``Re(s G e^{s t})`` (``s =
    -i w`` in steady waves); lumped half to each node, the fairlead's half onto the body."""
    G = np.zeros(s.n, dtype=complex)
    for kk, leg in enumerate(s.legs):
        L0 = leg.length / leg.n_elements
        x = s.nodes0[kk]
        area = 0.25 * math.pi * leg.diameter**2
        for e in range(leg.n_elements):
            d = x[e + 1] - x[e]
            t = d / np.linalg.norm(d)
            tt = np.outer(t, t)
            U = airy_velocity(omega, k, s.sea.depth, amplitude, 0.5 * (x[e] + x[e + 1]),
                              heading_deg)
            f = 0.5 * s.sea.rho * area * L0 * ((1 + leg.Ca) * (np.eye(3) - tt)
                                                + (1 + leg.Cat) * tt) @ U
            G += s.node_map(kk, e).T @ f + s.node_map(kk, e + 1).T @ f
    return G


def body_load(s: LinearSystem, force: ComplexArray) -> ComplexArray:
    """(n,) a complex force (3,) or generalized force (6,) on the body origin."""
    out = np.zeros(s.n, dtype=complex)
    out[:len(force)] = force
    return out


# ----------------------------------------------------------------------------- responses
def frequency_response(s: LinearSystem, omega: float, load: ComplexArray) -> ComplexArray:
    """Steady response ``Re(Q e^{-i w t})`` to the load ``Re(F e^{-i w t})``:
    ``(K - w^2 M - i w C) Q = F``."""
    return solve(s.K - omega**2 * s.M - 1j * omega * s.C, load)


def steady_response(s: LinearSystem, omega: float, table: ComplexArray,
                    inertia: ComplexArray) -> ComplexArray:
    """Steady response to the body's exciting force ``table`` (n,) and the legs' fluid
    inertia ``inertia`` (n,, per :func:`cable_inertia_operator`)."""
    return frequency_response(s, omega, table - 1j * omega * inertia)


@dataclass(frozen=True)
class History:
    """Response from rest: times (n_t,), unknowns (n_t, n), top tension changes per leg."""

    time: FloatArray
    q: FloatArray
    top_tension: FloatArray  # (n_t, n_legs)


def ramped_history(s: LinearSystem, omega: float, table: ComplexArray, inertia: ComplexArray,
                   ramp_time: float, dt: float, duration: float) -> History:
    """Exact response from rest at the static state to the loads of a wave ramped in with
    ``r(t) = (1 - cos(pi t / T_r)) / 2`` over ``ramp_time`` (the body force ``r Re(F e^{-iwt})``,
    the legs' fluid inertia on ``d/dt (r u)``), at ``t = 0, dt, ..., duration``.

    The forcing is a sum of exponentials ``e^{s_j t}`` (``r e^{-iwt} = e^{-iwt} / 2 -
    e^{-i(w - W)t} / 4 - e^{-i(w + W)t} / 4``, ``W = pi / T_r``); each has the particular
    solution ``(s_j I - A)^{-1} b_j e^{s_j t}`` of ``y' = A y + b(t)``; the homogeneous part
    ``e^{A t} y_h(0)`` matches the initial state and is restarted at ``T_r``.
    """
    n = s.n
    Minv = np.linalg.inv(s.M)
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ s.K, -Minv @ s.C]])
    W = math.pi / ramp_time
    terms = [(0.5, -1j * omega), (-0.25, -1j * (omega - W)), (-0.25, -1j * (omega + W))]

    def particular(coef: float, sj: complex) -> ComplexArray:
        b = np.concatenate((np.zeros(n), Minv @ (coef * (table + sj * inertia))))
        return solve(sj * np.eye(2 * n) - A, b)

    ramp_parts = [(particular(c, sj), sj) for c, sj in terms]
    steady = particular(1.0, -1j * omega)
    times = np.arange(0.0, duration + 0.5 * dt, dt)
    E = expm(A * dt)
    y = np.zeros((len(times), 2 * n))
    yh = -np.real(sum(p for p, _ in ramp_parts))
    k_ramp = int(round(ramp_time / dt))
    for i, t in enumerate(times):
        if i == k_ramp:  # restart the homogeneous part for the steady forcing
            y_end = np.real(sum(p * np.exp(sj * t) for p, sj in ramp_parts)) + yh
            yh = y_end - np.real(steady * np.exp(-1j * omega * t))
        if i < k_ramp:
            y[i] = np.real(sum(p * np.exp(sj * t) for p, sj in ramp_parts)) + yh
        else:
            y[i] = np.real(steady * np.exp(-1j * omega * t)) + yh
        yh = E @ yh
    q = y[:, :n]
    tension = np.column_stack([q @ s.top_tension_map(k) for k in range(len(s.legs))])
    return History(times, q, tension)


def natural_frequencies(s: LinearSystem) -> tuple[FloatArray, FloatArray]:
    """Undamped natural frequencies [rad/s] (ascending, zero-stiffness modes dropped) and the
    mode shapes (n, n_modes) of ``K phi = w^2 M phi``."""
    from scipy.linalg import eigh

    Ks = 0.5 * (s.K + s.K.T)
    w2, phi = eigh(Ks, s.M)
    keep = w2 > 1e-9 * np.max(np.abs(w2))
    return np.sqrt(w2[keep]), phi[:, keep]


__all__ = ["History", "Leg", "LinearSystem", "RigidBody", "Sea", "airy_velocity",
           "body_load", "cable_inertia_operator", "equilibrium", "frequency_response",
           "natural_frequencies", "ramped_history", "steady_response"]
