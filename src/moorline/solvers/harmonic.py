"""Periodic response by harmonic balance (the Fourier method of Tcheou 1997, ch. 2-4).

Tcheou writes the motion under a harmonic top force as a Fourier series in time,
``r(s, t) = sum_{k=-n}^{n} C_k(s) exp(i k omega t)`` (eq. 2.15), substitutes it in the equation
of motion (eq. 2.6: inertia with added mass, tension, drag, fluid inertia, net weight) and the
stretch condition, identifies the coefficients of each ``exp(i k omega t)`` and solves the
resulting time-independent nonlinear equations for the ``C_k`` by Newton-Raphson (sec. 4.2),
after a finite-difference discretization in ``s``.

moorline applies the same idea to its own finite-element model, so that the periodic answer
is that of the time-domain equations exactly (the steady state a long time-domain run tends
to). The free node positions are the real Fourier series

    x(t) = X_0 + sum_{k=1}^{n} (A_k cos k omega t + B_k sin k omega t),

and the residual of the dynamic equilibrium ``R(x, v, a, t) = M_s a - F(x, v, a, t)``
(:class:`moorline.solvers.dynamic_model.DynamicModel`: axial forces, drag on the relative
velocity, added mass, fluid inertia, seabed, point loads, prescribed motions) is made
orthogonal to every harmonic: ``sum_j E(t_j)^T R(t_j) = 0`` over ``N_t`` equally spaced
instants of the period (the alternating frequency-time scheme: Tcheou's identification of
exponential terms done numerically, which handles the non-polynomial ``|v| v`` drag and slack
elements; ``N_t = 4 (n + 1)`` by default, well above ``2n + 1``, keeps aliasing small). The
Jacobian is exact, ``sum_j E_j^T (K_j E_j + C_j E'_j + M_j E''_j)`` with the tangent blocks
of the time-domain model at every instant, assembled block-sparse: ordered dof by dof, it has
the sparsity of one instant's tangent with a dense (2 n + 1)^2 block per stored entry, built
from the tangents' sparse values (no dense matrix; memory linear in the number of nodes), and
factored by sparse LU. Newton (with backtracking) starts from the static state.

The excitation must be periodic with the analysis period after any ramp (harmonic forces on
free points or bodies, harmonic motions of prescribed points with a period that divides it,
regular waves and their exciting-force tables).

Rigid bodies (:mod:`moorline.solvers.harmonic_bodies`): a free body adds its origin and a
rotation vector relative to its static orientation, six Fourier series, to the unknowns; at
every instant the time-domain body model (:class:`~moorline.solvers.body_model.BodyModel`:
rigid and constant added mass, damping, hydrostatics as nonlinear as in the time domain,
drag, force histories, exciting-force tables, the lines' forces through the master-slave
transformation) gives the body residual and its tangent blocks, and the attached nodes move
with the body. The instant's tangent is chained to the generalized coordinates ``(q, q',
q'')`` (the rotation vector's kinematics exactly), so the Jacobian keeps its form
``sum_j E_j^T (K_j E_j + C_j E'_j + M_j E''_j)``, assembled over the union of the instants'
sparsity. A body's frequency-dependent radiation (``Body.radiation``) acts per harmonic,
``A(k w)`` and ``B(k w)``. Viscoelastic lines (:mod:`moorline.solvers.harmonic_material`):
the Maxwell branch's periodic state per harmonic, with its exact (non-local in time) Jacobian.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from ..errors import MoorlineError
from ..mesh import dynamic_mesh
from ..model import HarmonicSettings, System
from ..physics.element import element_geometry
from ..results import HarmonicResult, StaticResult
from .assembly import BlockPattern, factorize, gather_free, scatter_free
from .bodies import BodyState
from .dynamic_model import DynamicModel
from .excitation import Excitation
from .harmonic_bodies import BodyTerms, Collector
from .harmonic_material import maxwell_jacobian, maxwell_operator
from .linearized_laws import refuse_unlinearized
from .newton import Counters, NewtonPolicy, TangentCache
from .newton import solve as newton_solve
from .statics import equilibrium_for

FloatArray = NDArray[np.float64]


def _basis(times: FloatArray, omega: float, n: int) -> tuple[FloatArray, ...]:
    """``E``, ``E'``, ``E''`` (n_t, 2 n + 1): the mean, ``cos k w t``, ``sin k w t``."""
    k = np.arange(1, n + 1)
    arg = np.outer(times, k * omega)
    c, s = np.cos(arg), np.sin(arg)
    E = np.ones((len(times), 2 * n + 1))
    dE = np.zeros_like(E)
    ddE = np.zeros_like(E)
    E[:, 1::2], E[:, 2::2] = c, s
    dE[:, 1::2], dE[:, 2::2] = -k * omega * s, k * omega * c
    ddE[:, 1::2], ddE[:, 2::2] = -(k * omega) ** 2 * c, -(k * omega) ** 2 * s
    return E, dE, ddE


class HarmonicBalance:
    """The harmonic-balance equations of a system: residual and sparse Jacobian.

    The unknowns are the coefficients ``X`` (2 n + 1, n_u) of the free node dofs and the six
    dofs of every free body (its origin, then its rotation vector ``phi`` relative to the
    static orientation, ``R = exp([phi x]) R_static``) (the mean, then ``A_k``, ``B_k``),
    flattened dof by dof, ``u[p (2 n + 1) + k] = X[k, p]``, so that the Jacobian is a
    block-sparse matrix with the pattern of the time-domain tangent and a dense
    (2 n + 1)^2 block per stored entry.

    Parameters
    ----------
    system
        The problem (lines, points, bodies; periodic excitation).
    settings
        Period, harmonics, samples.
    statics
        The static state linearized from (solved when not given).

    Raises
    ------
    MoorlineError
        With bad settings, or a regular wave whose period does not divide the analysis'.
    """

    def __init__(self, system: System, settings: HarmonicSettings,
                 statics: StaticResult | None = None) -> None:
        from ..waves import fluid_field_from_environment

        if not (settings.period > 0 and settings.harmonics >= 1):
            raise MoorlineError("harmonic balance needs period > 0 and harmonics >= 1")
        statics = equilibrium_for(system, statics, "harmonic balance")
        mesh = dynamic_mesh(statics.mesh, statics.positions)
        n = settings.harmonics
        n_t = settings.samples or 4 * (n + 1)
        if n_t < 2 * n + 1:
            raise MoorlineError(f"harmonic balance: samples ({n_t}) must be >= 2 n + 1 = "
                                f"{2 * n + 1}")
        _check_wave_period(system, settings.period)
        self.system, self.settings, self.statics, self.mesh = system, settings, statics, mesh
        self.system_name, self.units = system.name, system.units
        self.n_terms, self.n_t = 2 * n + 1, n_t
        self.period, self.omega = settings.period, 2.0 * math.pi / settings.period
        fluid = fluid_field_from_environment(system.environment)
        self.model = DynamicModel(mesh, fluid, "exponential", system.environment.seabed)
        self.x_static = statics.positions
        excitation = Excitation(mesh, self.x_static)
        # evaluate the excitation after its ramps, a whole number of periods on
        ramps = [p.motion.ramp_time for p in system.points.values() if p.motion is not None] + \
            [p.force_history.ramp_time for p in system.points.values()
             if p.force_history is not None] + \
            [b.force_history.ramp_time for b in system.bodies.values()
             if b.force_history is not None]
        self.shift = self.period * math.ceil(max(ramps, default=0.0) / self.period + 1e-12)
        self.times = self.period * np.arange(n_t) / n_t
        self.basis = _basis(self.times, self.omega, n)
        self.material = self.model.initial_material(self.x_static)
        self.pattern = BlockPattern(mesh.pattern_pairs, mesh.dof_of_node)
        self.node_mass = self.model.node_mass[:, None, None] * np.eye(3)
        self.constrained = [excitation.constrained_state(self.shift + t) for t in self.times]
        self.forces = [excitation.point_forces(self.shift + t, mesh.n_nodes)
                       for t in self.times]
        self.coupled = bool(mesh.body_names)
        self.bodies = (BodyTerms(mesh, fluid, statics.body_pose, self.basis, self.omega,
                                 self.model.node_mass) if self.coupled else None)
        self.n_u = self.bodies.n_u if self.coupled else mesh.n_dofs
        ve = np.flatnonzero(mesh.viscoelastic)
        self.viscoelastic = ve
        self.maxwell_map = (maxwell_operator(self.basis[0], self.omega, mesh.EA1[ve],
                                             mesh.tau[ve]) if len(ve) else None)
        E = self.basis[0]
        # the Jacobian's time weights, E_j[k] B_j[l] per instant j for B = E, E', E'' (the
        # factors of K_j, C_j, M_j), over n_t (the residual is the mean over the instants)
        self._weights = [np.einsum("jk,jl->jkl", E, B).reshape(n_t, -1) / n_t
                         for B in self.basis]
        weights = [b.mass * mesh.gravity for b in system.bodies.values()]
        self.scale = max(float(np.abs(self.model.external).max(initial=0.0)),
                         float(np.abs(statics.tension).max(initial=0.0)),
                         max(weights, default=0.0), 1e-12)

    @property
    def n_unknowns(self) -> int:
        """Number of unknowns, (2 n + 1) n_u."""
        return self.n_terms * self.n_u

    def unknowns(self, X: FloatArray) -> FloatArray:
        """Coefficients (2 n + 1, n_u) to the flat unknown vector (dof by dof)."""
        return np.ascontiguousarray(X.T).ravel()

    def coefficients_of(self, u: FloatArray) -> FloatArray:
        """The flat unknown vector back to coefficients (2 n + 1, n_u)."""
        return u.reshape(self.n_u, self.n_terms).T

    def initial(self) -> FloatArray:
        """The static state as unknowns (the mean; no harmonics)."""
        X = np.zeros((self.n_terms, self.n_u))
        X[0, :self.mesh.n_dofs] = gather_free(self.x_static, self.mesh.dof_of_node)
        if self.coupled:
            self.bodies.initial(X)
        return self.unknowns(X)

    def states(self, X: FloatArray, bodies: list[BodyState] | None = None
               ) -> list[tuple[FloatArray, FloatArray, FloatArray]]:
        """Positions, velocities, accelerations (n_nodes, 3) at every instant (the attached
        nodes on the ``bodies``' states when given)."""
        dof, free = self.mesh.dof_of_node, self.mesh.free_nodes
        nd = self.mesh.n_dofs
        xs, vs, as_ = (np.einsum("tk,kd->td", B, X[:, :nd]) for B in self.basis)
        out = []
        for j in range(self.n_t):
            x = self.x_static.copy()
            v, a = np.zeros_like(x), np.zeros_like(x)
            x[free], v[free], a[free] = (scatter_free(arr[j], dof)[free]
                                         for arr in (xs, vs, as_))
            x[~free], v[~free], a[~free] = self.constrained[j]
            if bodies is not None:
                self.bodies.model.place(x, v, a, bodies[j])
            out.append((x, v, a))
        return out

    def _maxwell(self, states) -> list[FloatArray | None]:
        """The viscoelastic elements' Maxwell-branch forces at every instant (n_el,) from
        the strains at all instants (``None`` without viscoelastic elements)."""
        if self.maxwell_map is None:
            return [None] * self.n_t
        el, ve = self.mesh.elements[self.viscoelastic], self.viscoelastic
        eps = np.array([np.linalg.norm(x[el[:, 1]] - x[el[:, 0]], axis=1)
                        / self.mesh.length0[ve] - 1.0 for x, _, _ in states])  # (n_t, n_ve)
        Q = np.einsum("eji,ie->je", self.maxwell_map, eps)
        out = []
        for j in range(self.n_t):
            q = np.zeros(self.mesh.n_elements)
            q[ve] = Q[j]
            out.append(q)
        return out

    def _instant_material(self, x: FloatArray):
        """The material state an instant of the cycle is evaluated with: the static one with
        the strain of the instant itself, so the axial dashpot's share
        (:func:`moorline.physics.element.lagged_dashpot_share`, held over a time step in the
        time domain) follows the strain through the cycle, as in the limit of small steps (a
        periodic state has no previous step). The Maxwell forces of viscoelastic elements are
        given apart; the tangent leaves out the share's slope inside the slack band (2e-5 of
        strain), which slows the iteration there but not what it converges to."""
        length, _ = element_geometry(x, self.mesh.elements)
        return replace(self.material, strain=length / self.mesh.length0 - 1.0)

    def evaluate(self, u: FloatArray, tangent: bool
                 ) -> tuple[FloatArray, sp.spmatrix | None, FloatArray]:
        """Residual, Jacobian and tensions at the unknowns ``u``.

        The residual is ``(1 / N_t) sum_j E_j^T R_j`` with ``R_j = M a_j - F(x_j, v_j, a_j,
        t_j)`` the time-domain residual at instant ``j`` (bodies: minus their generalized
        forces); its Jacobian is ``(1 / N_t) sum_j E_j^T (K_j E_j + C_j E'_j + M_j E''_j)``,
        assembled block-sparse from the sparse tangents of every instant (never a dense
        matrix), plus the non-local terms of the Maxwell branches and of frequency-dependent
        radiation.

        Returns
        -------
        residual
            (n_unknowns,), in the order of ``u``.
        jacobian
            (n_unknowns, n_unknowns) sparse matrix, or ``None`` without ``tangent``.
        tension
            Element tensions at every instant (n_t, n_elements).
        """
        mesh, model, n_t = self.mesh, self.model, self.n_t
        dof, E = mesh.dof_of_node, self.basis[0]
        X = self.coefficients_of(u)
        bodies, motion = self.bodies.motion(X) if self.coupled else (None, None)
        states = self.states(X, bodies)
        maxwell = self._maxwell(states)
        R = np.zeros((self.n_terms, self.n_u))
        tension = np.zeros((n_t, mesh.n_elements))
        collected = Collector(self.n_u) if tangent and self.coupled else None
        tangents = np.empty((3, n_t, self.pattern.nnz)) if tangent and not self.coupled \
            else None
        maps = []  # per instant: (rows map T^T, columns map P_x) for the Maxwell terms
        for j, (x, v, a) in enumerate(states):
            t = float(self.shift + self.times[j])
            ev = model.evaluate(x, v, a, t, self._instant_material(x), self.period / n_t,
                                tangent, self.forces[j], maxwell[j])
            tension[j] = ev.tension
            if not self.coupled:
                R += np.outer(E[j], gather_free(model.node_mass[:, None] * a - ev.nodal, dof))
                if tangent:
                    nodes_m = self.node_mass + (ev.node_M if ev.node_M is not None else 0.0)
                    tangents[0, j] = self.pattern.values(ev.K, ev.node_K)
                    tangents[1, j] = self.pattern.values(ev.C, ev.node_C)
                    tangents[2, j] = self.pattern.values(ev.Ma, nodes_m)
                continue
            r_j, mats, pair = self.bodies.instant(x, a, bodies[j], motion, j, t, ev, tangent)
            R += np.outer(E[j], r_j)
            if tangent:
                collected.add(j, mats)
                maps.append(pair)
        if self.coupled:
            R += self.bodies.radiation_residual(motion)
        if not tangent:
            return self.unknowns(R) / n_t, None, tension
        if self.coupled:
            indices, indptr, values = collected.values(n_t)
            J = self._jacobian(values, indices, indptr)
        else:
            J = self._jacobian(tangents, self.pattern.indices, self.pattern.indptr)
        extra = [self._maxwell_jacobian(states, maps)]
        if self.coupled:
            extra += [self.bodies.radiation_jacobian(motion), self.bodies.neutral_mean(J)]
        for part in extra:
            if part is not None:
                J = J + part
        return self.unknowns(R) / n_t, J, tension

    def _maxwell_jacobian(self, states, maps) -> sp.csr_matrix | None:
        """The viscoelastic elements' non-local Jacobian
        (:func:`~moorline.solvers.harmonic_material.maxwell_jacobian`)."""
        if self.maxwell_map is None:
            return None
        mesh = self.mesh
        extended = ((self.bodies.model.layout.ext_map, self.bodies.model.layout.ext_dofs)
                    if self.coupled else (mesh.dof_of_node, mesh.n_dofs))
        return maxwell_jacobian(mesh, self.viscoelastic, self.maxwell_map, self.basis[0],
                                self.n_u, [x for x, _, _ in states], extended,
                                maps if self.coupled else None)

    def _jacobian(self, tangents: FloatArray, indices: NDArray, indptr: NDArray
                  ) -> sp.bsr_matrix:
        """The block-sparse Jacobian from the tangent values (3, n_t, nnz) of every instant
        on the pattern ``(indices, indptr)``: the block of stored entry ``s`` is
        ``sum_j sum_b tangents[b, j, s] w_b[j]``."""
        m, nnz = self.n_terms, len(indices)
        blocks = sum(t.T @ w for t, w in zip(tangents, self._weights, strict=True))
        size = m * (len(indptr) - 1)
        return sp.bsr_matrix((blocks.reshape(nnz, m, m), indices, indptr),
                             shape=(size, size))

    def result(self, u: FloatArray, tension: FloatArray, history: list[float],
               counters: dict | None = None, success: bool = True, message: str = ""
               ) -> HarmonicResult:
        """The periodic response of the unknowns ``u`` (tensions at the instants)."""
        mesh, n, n_t = self.mesh, self.settings.harmonics, self.n_t
        X, dof, free = self.coefficients_of(u), mesh.dof_of_node, mesh.free_nodes
        t_out = self.period * np.arange(self.settings.output_points) / \
            self.settings.output_points
        E_out = _basis(t_out, self.omega, n)[0]
        # coefficients of every node (constrained and attached nodes from their motion, by
        # projection)
        coefficients = np.zeros((self.n_terms, mesh.n_nodes, 3))
        for k in range(self.n_terms):
            coefficients[k][free] = scatter_free(X[k, :mesh.n_dofs], dof)[free]
        bodies = self.bodies.motion(X)[0] if self.coupled else None
        xc = np.array([x[~free] for x, _, _ in self.states(X, bodies)])  # (n_t, n_c, 3)
        fit = np.linalg.lstsq(self.basis[0], xc.reshape(n_t, -1), rcond=None)[0]
        coefficients[:, ~free] = fit.reshape(self.n_terms, -1, 3)
        positions = np.einsum("tk,knc->tnc", E_out, coefficients)
        tension_out = _resample(tension, self.times, t_out, self.omega, n)
        body = {}
        if self.coupled:
            body = self.bodies.output(X, E_out)
        return HarmonicResult(period=self.period, omega=self.omega, coefficients=coefficients,
                              time=t_out, positions=positions, tension=tension_out,
                              static_positions=self.x_static.copy(),
                              iterations=len(history), residual_history=history, mesh=mesh,
                              settings=self.settings,
                              counters={"samples": n_t, "unknowns": self.n_unknowns,
                                        **(counters or {})},
                              success=success, status="converged" if success else "failed",
                              message=message or f"converged in {len(history)} Newton "
                                                 f"iterations ({n} harmonics)",
                              case=self.system_name, units=self.units, **body)

def _check_wave_period(system: System, period: float) -> None:
    """A regular wave or explicit components must repeat over the analysis period (and a
    random sea never does)."""
    waves = system.environment.waves
    if waves.kind == "random":
        raise MoorlineError(f"harmonic balance of {system.name}: a random sea is not periodic "
                            "(use a stochastic or dynamics analysis)")
    if waves.kind == "components" and waves.active:
        cycles = [w * period / (2.0 * math.pi) for w in waves.components.omegas]
        if any(abs(c - round(c)) > 1e-9 * max(c, 1.0) or round(c) < 1 for c in cycles):
            raise MoorlineError(f"harmonic balance of {system.name}: every wave component "
                                f"must repeat over the analysis period ({period:g}): "
                                "omega * period / 2 pi must be whole numbers")
        return
    if waves.kind != "airy" or not waves.height:
        return
    ratio = period / waves.period
    if abs(ratio - round(ratio)) > 1e-9 * max(ratio, 1.0) or round(ratio) < 1:
        raise MoorlineError(f"harmonic balance of {system.name}: the wave period "
                            f"({waves.period:g}) must divide the analysis period ({period:g})")


@dataclass
class _BalanceTrial:
    r: FloatArray           # minus the harmonic-balance residual
    jacobian: Any
    extra: Any

    @property
    def has_tangent(self) -> bool:
        return self.jacobian is not None


class _BalanceProblem:
    """The harmonic-balance equations as a problem of the Newton core."""

    def __init__(self, evaluate) -> None:
        self.evaluate = evaluate

    def residual(self, u: FloatArray, tangent: bool) -> _BalanceTrial:
        R, J, extra = self.evaluate(u, tangent)
        return _BalanceTrial(-R, J, extra)

    def factorize(self, u: FloatArray, trial: _BalanceTrial):
        return factorize(trial.jacobian)

    def update(self, u: FloatArray, du: FloatArray) -> FloatArray:
        return u + du


def _newton(evaluate: Callable[[FloatArray, bool], tuple[FloatArray, sp.spmatrix | None,
                                                          Any]],
            u: FloatArray, tolerance: float, max_iterations: int, name: str,
            counters: Counters | None = None):
    """Newton-Raphson (a fresh Jacobian every iteration, the Newton core of
    :mod:`moorline.solvers.newton`) with backtracking on the largest residual.

    Parameters
    ----------
    evaluate
        ``evaluate(u, tangent) -> (residual, jacobian or None, extra)``.
    u
        Starting unknowns.
    tolerance
        Convergence when the largest residual is at most this (absolute).
    max_iterations
        Newton steps allowed.
    name
        For the messages.
    counters
        Accumulated work (a new one when not given).

    Returns
    -------
    outcome, counters, message
        The Newton core's :class:`~moorline.solvers.newton.Outcome` (``trial.extra`` holds
        the last evaluation's extra), its counters, and a message saying how it ended.
    """
    policy = NewtonPolicy(tolerance=tolerance, max_iterations=max_iterations,
                          stiffness_update=1, age_per="iteration", refresh_ratio=None,
                          stall_limit=0, max_halvings=7, merit="max")
    counters = counters if counters is not None else Counters()
    out = newton_solve(_BalanceProblem(evaluate), u, policy, TangentCache(), counters)
    if out.converged:
        return out, counters, ""
    if out.reason.startswith("singular"):
        return out, counters, f"{name}: {out.reason.replace('tangent', 'Jacobian')}"
    return out, counters, (f"{name}: Newton did not converge in {max_iterations} iterations "
                           f"(residual {out.norm:.3g}, tolerance {tolerance:.3g})")


def solve_harmonic(system: System, settings: HarmonicSettings,
                   statics: StaticResult | None = None) -> HarmonicResult:
    """Periodic response of a line system by harmonic balance.

    Parameters
    ----------
    system
        The problem (lines, points, bodies; periodic excitation).
    settings
        Period, harmonics, samples, tolerance.
    statics
        The static state to start from (solved when not given).

    Returns
    -------
    HarmonicResult
        ``success`` False (the last iterate, the message saying why) when Newton did not
        converge.

    Raises
    ------
    MoorlineError
        With bad settings.
    ConvergenceError
        When the static state it starts from did not converge.
    """
    refuse_unlinearized(system, "harmonic")
    balance = HarmonicBalance(system, settings, statics)
    name = f"harmonic balance of {system.name}"
    tolerance = settings.tolerance * balance.scale
    out, counters, message = _newton(balance.evaluate, balance.initial(), tolerance,
                                     settings.max_iterations, name)
    return balance.result(out.u, out.trial.extra, out.history[1:], counters.as_dict(),
                          out.converged, message)


def _resample(values: FloatArray, times: FloatArray, t_out: FloatArray, omega: float,
              n: int) -> FloatArray:
    """Trigonometric interpolation (the ``n`` harmonics) of samples over one period."""
    E = _basis(times, omega, n)[0]
    coef = np.linalg.lstsq(E, values, rcond=None)[0]
    return _basis(t_out, omega, n)[0] @ coef


__all__ = ["HarmonicBalance", "HarmonicResult", "HarmonicSettings", "solve_harmonic"]
