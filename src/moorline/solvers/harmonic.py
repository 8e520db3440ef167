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
free points or harmonic motions of prescribed points with a period that divides it, regular
waves); elastic lines only (the standard linear solid carries history).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from ..errors import MoorlineError
from ..mesh import dynamic_mesh
from ..model import HarmonicSettings, System
from ..results import HarmonicResult, StaticResult
from .assembly import BlockPattern, factorize, gather_free, scatter_free
from .dynamic_model import DynamicModel
from .excitation import Excitation
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

    The unknowns are the coefficients ``X`` (2 n + 1, n_dofs) of the free dofs (the mean,
    then ``A_k``, ``B_k``), flattened dof by dof, ``u[p (2 n + 1) + k] = X[k, p]``, so that
    the Jacobian is a block-sparse matrix with the pattern of the time-domain tangent
    (:class:`~moorline.solvers.assembly.BlockPattern`) and a dense (2 n + 1)^2 block per
    stored entry.

    Parameters
    ----------
    system
        The problem (elastic lines and points; periodic excitation).
    settings
        Period, harmonics, samples.
    statics
        The static state linearized from (solved when not given).

    Raises
    ------
    MoorlineError
        With bodies, viscoelastic lines or bad settings.
    """

    def __init__(self, system: System, settings: HarmonicSettings,
                 statics: StaticResult | None = None) -> None:
        from ..waves import fluid_field_from_environment

        if not (settings.period > 0 and settings.harmonics >= 1):
            raise MoorlineError("harmonic balance needs period > 0 and harmonics >= 1")
        statics = equilibrium_for(system, statics, "harmonic balance")
        mesh = dynamic_mesh(statics.mesh, statics.positions)
        if mesh.body_names:
            raise MoorlineError(f"harmonic balance of {system.name}: systems with bodies are "
                                "not supported")
        if any(system.line_types[line.line_type].material != "elastic"
               for line in system.lines.values()):
            raise MoorlineError(f"harmonic balance of {system.name}: elastic lines only (a "
                                "viscoelastic line carries history)")
        n = settings.harmonics
        n_t = settings.samples or 4 * (n + 1)
        if n_t < 2 * n + 1:
            raise MoorlineError(f"harmonic balance: samples ({n_t}) must be >= 2 n + 1 = "
                                f"{2 * n + 1}")
        self.system, self.settings, self.statics, self.mesh = system, settings, statics, mesh
        self.system_name, self.units = system.name, system.units
        self.n_terms, self.n_t = 2 * n + 1, n_t
        self.period, self.omega = settings.period, 2.0 * math.pi / settings.period
        self.model = DynamicModel(mesh, fluid_field_from_environment(system.environment),
                                  "exponential", system.environment.seabed)
        self.x_static = statics.positions
        excitation = Excitation(mesh, self.x_static)
        # evaluate the excitation after its ramps, a whole number of periods on
        ramps = [p.motion.ramp_time for p in system.points.values() if p.motion is not None] + \
            [p.force_history.ramp_time for p in system.points.values()
             if p.force_history is not None]
        self.shift = self.period * math.ceil(max(ramps, default=0.0) / self.period + 1e-12)
        self.times = self.period * np.arange(n_t) / n_t
        self.basis = _basis(self.times, self.omega, n)
        self.material = self.model.initial_material(self.x_static)
        self.pattern = BlockPattern(mesh.pattern_pairs, mesh.dof_of_node)
        self.node_mass = self.model.node_mass[:, None, None] * np.eye(3)
        self.constrained = [excitation.constrained_state(self.shift + t) for t in self.times]
        self.forces = [excitation.point_forces(self.shift + t, mesh.n_nodes)
                       for t in self.times]
        E = self.basis[0]
        # the Jacobian's time weights, E_j[k] B_j[l] per instant j for B = E, E', E'' (the
        # factors of K_j, C_j, M_j), over n_t (the residual is the mean over the instants)
        self._weights = [np.einsum("jk,jl->jkl", E, B).reshape(n_t, -1) / n_t
                         for B in self.basis]
        self.scale = max(float(np.abs(self.model.external).max(initial=0.0)),
                         float(np.abs(statics.tension).max(initial=0.0)), 1e-12)

    @property
    def n_unknowns(self) -> int:
        """Number of unknowns, (2 n + 1) n_dofs."""
        return self.n_terms * self.mesh.n_dofs

    def unknowns(self, X: FloatArray) -> FloatArray:
        """Coefficients (2 n + 1, n_dofs) to the flat unknown vector (dof by dof)."""
        return np.ascontiguousarray(X.T).ravel()

    def coefficients_of(self, u: FloatArray) -> FloatArray:
        """The flat unknown vector back to coefficients (2 n + 1, n_dofs)."""
        return u.reshape(self.mesh.n_dofs, self.n_terms).T

    def initial(self) -> FloatArray:
        """The static state as unknowns (the mean; no harmonics)."""
        X = np.zeros((self.n_terms, self.mesh.n_dofs))
        X[0] = gather_free(self.x_static, self.mesh.dof_of_node)
        return self.unknowns(X)

    def states(self, X: FloatArray) -> list[tuple[FloatArray, FloatArray, FloatArray]]:
        """Positions, velocities, accelerations (n_nodes, 3) at every instant."""
        dof, free = self.mesh.dof_of_node, self.mesh.free_nodes
        xs, vs, as_ = (np.einsum("tk,kd->td", B, X) for B in self.basis)
        out = []
        for j in range(self.n_t):
            x = self.x_static.copy()
            v, a = np.zeros_like(x), np.zeros_like(x)
            x[free], v[free], a[free] = (scatter_free(arr[j], dof)[free]
                                         for arr in (xs, vs, as_))
            x[~free], v[~free], a[~free] = self.constrained[j]
            out.append((x, v, a))
        return out

    def evaluate(self, u: FloatArray, tangent: bool
                 ) -> tuple[FloatArray, sp.bsr_matrix | None, FloatArray]:
        """Residual, Jacobian and tensions at the unknowns ``u``.

        The residual is ``(1 / N_t) sum_j E_j^T R_j`` with ``R_j = M a_j - F(x_j, v_j, a_j,
        t_j)`` the time-domain residual at instant ``j``; its Jacobian is
        ``(1 / N_t) sum_j E_j^T (K_j E_j + C_j E'_j + M_j E''_j)``, assembled block-sparse
        from the sparse tangents of every instant (never a dense matrix).

        Returns
        -------
        residual
            (n_unknowns,), in the order of ``u``.
        jacobian
            (n_unknowns, n_unknowns) block-sparse matrix, or ``None`` without ``tangent``.
        tension
            Element tensions at every instant (n_t, n_elements).
        """
        mesh, model, pattern, n_t = self.mesh, self.model, self.pattern, self.n_t
        dof, E = mesh.dof_of_node, self.basis[0]
        R = np.zeros((self.n_terms, mesh.n_dofs))
        tangents = np.empty((3, n_t, pattern.nnz)) if tangent else None
        tension = np.zeros((n_t, mesh.n_elements))
        for j, (x, v, a) in enumerate(self.states(self.coefficients_of(u))):
            ev = model.evaluate(x, v, a, float(self.shift + self.times[j]), self.material,
                                self.period / n_t, tangent, self.forces[j])
            R += np.outer(E[j], gather_free(model.node_mass[:, None] * a - ev.nodal, dof))
            tension[j] = ev.tension
            if tangent:
                nodes_m = self.node_mass + (ev.node_M if ev.node_M is not None else 0.0)
                tangents[0, j] = pattern.values(ev.K, ev.node_K)
                tangents[1, j] = pattern.values(ev.C, ev.node_C)
                tangents[2, j] = pattern.values(ev.Ma, nodes_m)
        J = self._jacobian(tangents) if tangent else None
        return self.unknowns(R) / n_t, J, tension

    def _jacobian(self, tangents: FloatArray) -> sp.bsr_matrix:
        """The block-sparse Jacobian from the tangent values (3, n_t, nnz) of every instant:
        the block of stored entry ``s`` is ``sum_j sum_b tangents[b, j, s] w_b[j]``."""
        m, p = self.n_terms, self.pattern
        blocks = sum(t.T @ w for t, w in zip(tangents, self._weights, strict=True))
        size = m * p.n
        return sp.bsr_matrix((blocks.reshape(p.nnz, m, m), p.indices, p.indptr),
                             shape=(size, size))

    def result(self, u: FloatArray, tension: FloatArray, history: list[float],
               counters: dict | None = None, success: bool = True, message: str = ""
               ) -> HarmonicResult:
        """The periodic response of the unknowns ``u`` (tensions at the instants)."""
        mesh, n, n_t = self.mesh, self.settings.harmonics, self.n_t
        X, dof, free = self.coefficients_of(u), mesh.dof_of_node, mesh.free_nodes
        # coefficients of every node (constrained nodes from their motion, by projection)
        coefficients = np.zeros((self.n_terms, mesh.n_nodes, 3))
        for k in range(self.n_terms):
            coefficients[k][free] = scatter_free(X[k], dof)[free]
        xc = np.array([c[0] for c in self.constrained])  # (n_t, n_constrained, 3)
        fit = np.linalg.lstsq(self.basis[0], xc.reshape(n_t, -1), rcond=None)[0]
        coefficients[:, ~free] = fit.reshape(self.n_terms, -1, 3)
        t_out = self.period * np.arange(self.settings.output_points) / \
            self.settings.output_points
        E_out = _basis(t_out, self.omega, n)[0]
        positions = np.einsum("tk,knc->tnc", E_out, coefficients)
        tension_out = _resample(tension, self.times, t_out, self.omega, n)
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
                              case=self.system_name, units=self.units)


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
            u: FloatArray, tolerance: float, max_iterations: int, name: str):
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

    Returns
    -------
    outcome, counters, message
        The Newton core's :class:`~moorline.solvers.newton.Outcome` (``trial.extra`` holds
        the last evaluation's extra), its counters, and a message saying how it ended.
    """
    policy = NewtonPolicy(tolerance=tolerance, max_iterations=max_iterations,
                          stiffness_update=1, age_per="iteration", refresh_ratio=None,
                          stall_limit=0, max_halvings=7, merit="max")
    counters = Counters()
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
        The problem (elastic lines and points; periodic excitation).
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
        With bodies, viscoelastic lines or bad settings.
    ConvergenceError
        When the static state it starts from did not converge.
    """
    balance = HarmonicBalance(system, settings, statics)
    out, counters, message = _newton(balance.evaluate, balance.initial(),
                                     settings.tolerance * balance.scale,
                                     settings.max_iterations,
                                     f"harmonic balance of {system.name}")
    return balance.result(out.u, out.trial.extra, out.history[1:], counters.as_dict(),
                          out.converged, message)


def _resample(values: FloatArray, times: FloatArray, t_out: FloatArray, omega: float,
              n: int) -> FloatArray:
    """Trigonometric interpolation (the ``n`` harmonics) of samples over one period."""
    E = _basis(times, omega, n)[0]
    coef = np.linalg.lstsq(E, values, rcond=None)[0]
    return _basis(t_out, omega, n)[0] @ coef


__all__ = ["HarmonicBalance", "HarmonicResult", "HarmonicSettings", "solve_harmonic"]
