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
of the time-domain model at every instant, and Newton (with backtracking) starts from the
static state.

The excitation must be periodic with the analysis period after any ramp (harmonic forces on
free points or harmonic motions of prescribed points with a period that divides it, regular
waves); elastic lines only (the standard linear solid carries history).
"""

from __future__ import annotations

import math

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from numpy.typing import NDArray

from ..errors import ConvergenceError, MoorlineError
from ..model import HarmonicSettings, System
from ..results import HarmonicResult, StaticResult
from .assembly import BlockPattern, gather_free, scatter_free
from .dynamic_model import DynamicModel
from .excitation import Excitation
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

    Raises
    ------
    MoorlineError
        With bodies, viscoelastic lines or bad settings.
    ConvergenceError
        When Newton does not converge.
    """
    from ..waves import fluid_field_from_environment

    if not (settings.period > 0 and settings.harmonics >= 1):
        raise MoorlineError("harmonic balance needs period > 0 and harmonics >= 1")
    statics = equilibrium_for(system, statics, "harmonic balance")
    mesh = statics.mesh
    if getattr(mesh, "body_names", ()):
        raise MoorlineError(f"harmonic balance of {system.name}: systems with bodies are not "
                            "supported")
    if any(system.line_types[line.line_type].material != "elastic"
           for line in system.lines.values()):
        raise MoorlineError(f"harmonic balance of {system.name}: elastic lines only (a "
                            "viscoelastic line carries history)")
    n = settings.harmonics
    n_t = settings.samples or 4 * (n + 1)
    if n_t < 2 * n + 1:
        raise MoorlineError(f"harmonic balance: samples ({n_t}) must be >= 2 n + 1 = {2 * n + 1}")
    period, omega = settings.period, 2.0 * math.pi / settings.period
    fluid = fluid_field_from_environment(system.environment)
    model = DynamicModel(mesh, fluid, "exponential", system.environment.seabed)
    x_static = statics.positions
    excitation = Excitation(system, mesh, x_static)
    # evaluate the excitation after its ramps, a whole number of periods on
    ramps = [p.motion.ramp_time for p in system.points.values() if p.motion is not None] + \
        [p.force_history.ramp_time for p in system.points.values()
         if p.force_history is not None]
    shift = period * math.ceil(max(ramps, default=0.0) / period + 1e-12)
    times = period * np.arange(n_t) / n_t
    E, dE, ddE = _basis(times, omega, n)
    dof, free = mesh.dof_of_node, mesh.free_nodes
    n_dof = mesh.n_dofs
    material = model.initial_material(x_static)
    pattern = BlockPattern(mesh.elements, dof)
    node_mass = model.node_mass[:, None, None] * np.eye(3)
    constrained = [excitation.constrained_state(shift + t) for t in times]
    forces = [excitation.point_forces(shift + t, mesh.n_nodes) for t in times]
    scale = max(float(np.abs(model.external).max(initial=0.0)),
                float(np.abs(statics.tension).max(initial=0.0)), 1e-12)

    def states(X: FloatArray):
        """Positions, velocities, accelerations (n_t, n_nodes, 3) of coefficients X."""
        xs, vs, as_ = (np.einsum("tk,kd->td", B, X) for B in (E, dE, ddE))
        out = []
        for j in range(n_t):
            x = x_static.copy()
            v, a = np.zeros_like(x), np.zeros_like(x)
            x[free], v[free], a[free] = (scatter_free(arr[j], dof)[free]
                                         for arr in (xs, vs, as_))
            x[~free], v[~free], a[~free] = constrained[j]
            out.append((x, v, a))
        return out

    # the Jacobian's time weights: J = sum_j E_j^T (K_j E_j + C_j E'_j + M_j E''_j), with
    # the products of basis functions per sample precomputed ((2n+1)^2 per instant)
    weights = [np.einsum("jk,jl->jkl", E, B).reshape(n_t, -1) for B in (E, dE, ddE)]

    def residual(X: FloatArray, tangent: bool):
        R = np.zeros((2 * n + 1, n_dof))
        mats = np.zeros((3, n_t, n_dof, n_dof)) if tangent else None
        tension = np.zeros((n_t, mesh.n_elements))
        for j, (x, v, a) in enumerate(states(X)):
            ev = model.evaluate(x, v, a, float(shift + times[j]), material, period / n_t,
                                tangent, forces[j])
            r = gather_free(model.node_mass[:, None] * a - ev.nodal, dof)
            R += np.outer(E[j], r)
            tension[j] = ev.tension
            if tangent:
                Ma = ev.Ma if ev.Ma is not None else np.zeros_like(ev.K)
                nodes_m = node_mass + (ev.node_M if ev.node_M is not None else 0.0)
                mats[0, j] = pattern.assemble(ev.K, ev.node_K).toarray()
                mats[1, j] = pattern.assemble(ev.C, ev.node_C).toarray()
                mats[2, j] = pattern.assemble(Ma, nodes_m).toarray()
        J = None
        if tangent:
            size = 2 * n + 1
            flat = sum(w.T @ m.reshape(n_t, -1) for w, m in zip(weights, mats, strict=True))
            J = flat.reshape(size, size, n_dof, n_dof).transpose(0, 2, 1, 3)
        return R, J, tension

    X = np.zeros((2 * n + 1, n_dof))
    X[0] = gather_free(x_static, dof)
    history: list[float] = []
    R, J, tension = residual(X, True)
    norm = float(np.abs(R).max(initial=0.0)) / n_t
    for _ in range(settings.max_iterations):
        if norm <= settings.tolerance * scale:
            break
        size = (2 * n + 1) * n_dof
        try:
            # the Jacobian couples neighbouring nodes only (through all harmonics): sparse LU
            step = spla.splu(sp.csc_matrix(J.reshape(size, size))).solve(
                -R.reshape(size)).reshape(X.shape)
        except (RuntimeError, ValueError) as exc:
            raise ConvergenceError(f"harmonic balance of {system.name}: singular Jacobian "
                                   f"({exc})") from None
        alpha = 1.0
        for _ in range(8):  # backtracking on the residual
            trial = X + alpha * step
            R_t, _, _ = residual(trial, False)
            norm_t = float(np.abs(R_t).max(initial=0.0)) / n_t
            if norm_t < norm or alpha < 1e-2:
                break
            alpha *= 0.5
        X = trial
        R, J, tension = residual(X, True)
        norm = float(np.abs(R).max(initial=0.0)) / n_t
        history.append(norm)
    if norm > settings.tolerance * scale:
        raise ConvergenceError(f"harmonic balance of {system.name}: Newton did not converge in "
                               f"{settings.max_iterations} iterations (residual {norm:.3g}, "
                               f"scale {scale:.3g})")
    # coefficients of every node (constrained nodes from their motion, by projection)
    coefficients = np.zeros((2 * n + 1, mesh.n_nodes, 3))
    for k in range(2 * n + 1):
        coefficients[k][free] = scatter_free(X[k], dof)[free]
    xc = np.array([c[0] for c in constrained])  # (n_t, n_constrained, 3)
    fit = np.linalg.lstsq(E, xc.reshape(n_t, -1), rcond=None)[0]
    coefficients[:, ~free] = fit.reshape(2 * n + 1, -1, 3)
    t_out = period * np.arange(settings.output_points) / settings.output_points
    E_out = _basis(t_out, omega, n)[0]
    positions = np.einsum("tk,knc->tnc", E_out, coefficients)
    tension_out = _resample(tension, times, t_out, omega, n)
    return HarmonicResult(period=period, omega=omega, coefficients=coefficients, time=t_out,
                          positions=positions, tension=tension_out,
                          static_positions=x_static.copy(), iterations=len(history),
                          residual_history=history, mesh=mesh, settings=settings,
                          counters={"samples": n_t, "unknowns": (2 * n + 1) * n_dof},
                          message=f"converged in {len(history)} Newton iterations "
                                  f"({n} harmonics)", case=system.name, units=system.units)


def _resample(values: FloatArray, times: FloatArray, t_out: FloatArray, omega: float,
              n: int) -> FloatArray:
    """Trigonometric interpolation (the ``n`` harmonics) of samples over one period."""
    E = _basis(times, omega, n)[0]
    coef = np.linalg.lstsq(E, values, rcond=None)[0]
    return _basis(t_out, omega, n)[0] @ coef


__all__ = ["HarmonicResult", "HarmonicSettings", "solve_harmonic"]
