"""Small-amplitude dynamics of a continuous elastic cable, integrated along its arc length.

An independent reference for the linear limit of moorline's cable dynamics (used by the
``wang-w2``, ``tcheou-t2`` and ``stochastic-riser`` cases): none of moorline's elements,
meshes or solvers is used. The cable hangs freely (no seabed contact, no current) under a
uniform weight ``w`` per unstretched length, so its static internal force (tension times the
unit tangent, pointing to increasing ``s``) is ``F0(s) = F_a + (0, 0, w) s`` with ``s`` the
unstretched arc length from end a. With ``dr/ds = (1 + T/EA) t`` and ``F = T t``,
``dr/ds = F / T + F / EA``; perturbing about the static state (complex amplitudes,
``u(t) = Re(U e^{i omega t})``)::

    dU/ds = G(s) F' / (1 + i omega a1),   G = (I - t t^T) / T0 + I / EA,
    dF'/ds = -(omega^2 - i omega a0) M(s) U + i omega B(s) U - f(s),

with ``F'`` the force perturbation (including the Rayleigh part ``a1 K u'``), mass per
unstretched length ``M = m I + m_a (I - t t^T)`` (normal added mass, as
:func:`moorline.physics.hydro.added_mass_blocks` with ``Cat = 0``), Rayleigh damping
``a0 M + a1 K``, a linear damping ``B(s)`` per length (the statistically linearized drag) and
distributed loads ``f(s)`` per unstretched length. The system is integrated by the classical
fourth-order Runge-Kutta method, vectorized over the frequencies; a constant seventh state
carries the loads, so that one integration of the transfer matrix ``Phi`` (``y(s) = Phi(s)
y(0)``) serves every boundary condition.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]

#: ``(s, r0, t) -> (n_omega, 3)`` complex load per unstretched length at one station
Load = Callable[[float, FloatArray, FloatArray], ComplexArray]
#: ``(s, r0, t) -> (3, 3)`` linear damping per unstretched length at one station
Damping = Callable[[float, FloatArray, FloatArray], FloatArray]
#: Gauss-Legendre nodes and weights on [-1, 1] for the static position (exact for the
#: smooth integrand to round-off at these lengths)
_GAUSS = np.polynomial.legendre.leggauss(48)


@dataclass(frozen=True)
class Cable:
    """A freely hanging elastic cable in its static state.

    Attributes
    ----------
    length, EA
        Unstretched length [m] and axial stiffness [N].
    force_a
        Static internal force at ``s = 0`` (the pull of end a on the cable, reversed), 3-vector:
        ``F0(s) = force_a + (0, 0, weight) s``.
    weight
        Submerged weight per unstretched length [N/m].
    mass, added_mass
        Mass and normal added mass per unstretched length [kg/m].
    origin
        Position of end a (only the loads that depend on position use it).
    """

    length: float
    EA: float
    force_a: tuple[float, float, float]
    weight: float
    mass: float
    added_mass: float
    origin: tuple[float, float, float] = (0.0, 0.0, 0.0)

    def force(self, s: float) -> FloatArray:
        """Static internal force ``F0(s)``."""
        return np.asarray(self.force_a, float) + np.array([0.0, 0.0, self.weight]) * s

    def position(self, s: float) -> FloatArray:
        """Static position ``r0(s) = r_a + int_0^s (F0/T0 + F0/EA) ds`` (Gauss-Legendre)."""
        x, wq = _GAUSS
        q = 0.5 * s * (x + 1.0)
        F = np.asarray(self.force_a, float)[None] + np.outer(q, [0.0, 0.0, self.weight])
        T = np.linalg.norm(F, axis=1)[:, None]
        return np.asarray(self.origin, float) + 0.5 * s * np.sum(
            wq[:, None] * (F / T + F / self.EA), axis=0)


def _operator(cable: Cable, s: float, omega: FloatArray, a0: float, a1: float,
              load: Load | None, damping: Damping | None) -> ComplexArray:
    """System matrix ``A(s)`` (n_omega, 7, 7) of ``y' = A y``, ``y = (U, F', 1)``."""
    F = cable.force(s)
    T = float(np.linalg.norm(F))
    t = F / T
    P = np.eye(3) - np.outer(t, t)
    G = P / T + np.eye(3) / cable.EA
    M = cable.mass * np.eye(3) + cable.added_mass * P
    w = np.asarray(omega, complex)[:, None, None]
    A = np.zeros((len(omega), 7, 7), dtype=complex)
    A[:, :3, 3:6] = G[None] / (1.0 + 1j * w * a1)
    A[:, 3:6, :3] = -(w**2 - 1j * w * a0) * M[None]
    r0 = cable.position(s) if (load is not None or damping is not None) else None
    if damping is not None:
        A[:, 3:6, :3] += 1j * w * damping(s, r0, t)[None]
    if load is not None:
        A[:, 3:6, 6] = -load(s, r0, t)
    return A


def transfer(cable: Cable, omega: FloatArray, *, a0: float = 0.0, a1: float = 0.0,
             load: Load | None = None, damping: Damping | None = None, steps: int = 400
             ) -> tuple[FloatArray, ComplexArray]:
    """Transfer matrices ``Phi(s_k)`` from ``s = 0`` to each station, ``y(s_k) = Phi y(0)``.

    Parameters
    ----------
    cable
        The static state.
    omega
        Circular frequencies [rad/s], shape (n_omega,).
    a0, a1
        Rayleigh damping ``a0 M + a1 K``.
    load, damping
        Distributed loads and linear damping per unstretched length (module docstring).
    steps
        Runge-Kutta steps over the length.

    Returns
    -------
    (s, Phi)
        Stations (steps + 1,) and ``Phi`` (steps + 1, n_omega, 7, 7); ``y = (U, F', 1)``, the
        seventh state is the constant 1 that carries the loads.
    """
    omega = np.atleast_1d(np.asarray(omega, float))
    s = np.linspace(0.0, cable.length, steps + 1)
    h = s[1] - s[0]
    Y = np.broadcast_to(np.eye(7, dtype=complex), (len(omega), 7, 7)).copy()
    out = np.empty((steps + 1, len(omega), 7, 7), dtype=complex)
    out[0] = Y

    def A(x: float) -> ComplexArray:
        return _operator(cable, x, omega, a0, a1, load, damping)

    A_next = A(0.0)
    for k in range(steps):
        A0, Am, A1 = A_next, A(s[k] + 0.5 * h), A(s[k + 1])
        k1 = A0 @ Y
        k2 = Am @ (Y + 0.5 * h * k1)
        k3 = Am @ (Y + 0.5 * h * k2)
        k4 = A1 @ (Y + h * k3)
        Y = Y + h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
        out[k + 1] = Y
        A_next = A1
    return s, out


def end_stiffness(Phi_end: ComplexArray) -> ComplexArray:
    """Dynamic stiffness ``K`` (n_omega, 3, 3) of end b with end a fixed: ``F'(L) = K U(L)``;
    the cable's force on a body at end b is ``-K U(L)`` (unloaded cable)."""
    return Phi_end[:, 3:6, 3:6] @ np.linalg.inv(Phi_end[:, :3, 3:6])


def forced_end(Phi: ComplexArray, top_force: ComplexArray) -> ComplexArray:
    """States ``y(s)`` (stations, n_omega, 7) of a cable fixed at end a (``U(0) = 0``) whose
    end b carries the force amplitude ``top_force`` (3,) or (n_omega, 3) from outside
    (``F'(L) = top_force``), with the loads of ``Phi``."""
    end = Phi[-1]
    rhs = np.broadcast_to(np.asarray(top_force, complex), (end.shape[0], 3)) - end[:, 3:6, 6]
    F0 = np.linalg.solve(end[:, 3:6, 3:6], rhs[..., None])[..., 0]
    y0 = np.concatenate([np.zeros_like(F0), F0, np.ones((len(F0), 1))], axis=1)
    return np.einsum("kwij,wj->kwi", Phi, y0)


def fixed_ends(Phi: ComplexArray) -> ComplexArray:
    """States ``y(s)`` (stations, n_omega, 7) of a cable fixed at both ends (``U(0) = U(L)
    = 0``) under the loads of ``Phi``."""
    end = Phi[-1]
    F0 = np.linalg.solve(end[:, :3, 3:6], -end[:, :3, 6][..., None])[..., 0]
    y0 = np.concatenate([np.zeros_like(F0), F0, np.ones((len(F0), 1))], axis=1)
    return np.einsum("kwij,wj->kwi", Phi, y0)


__all__ = ["Cable", "end_stiffness", "fixed_ends", "forced_end", "transfer"]
