"""Static equilibrium of a cable system (Tuah 1982, sec. 4.1).

Three methods, as the source compares them:

- ``newton``: residual feedback (eq. 4.1.2) with equilibrium iterations in each load increment
  and a backtracking line search; with one increment it is Newton-Raphson. The tangent is
  refreshed every ``stiffness_update`` iterations (modified Newton in between).
- ``incremental``: purely incremental loading (eq. 4.1.1), ``K_n dU = dF_e``, no equilibrium
  correction; the final residual shows the drift.
- ``relaxation``: viscous relaxation (eq. 4.1.5-4.1.8), ``(C/dt + K) dU = R`` with the
  artificial damping decreasing as ``C(t) = mu C(t - dt)`` (eq. 6.1.1).

Loads (weights, buoyancy, point forces) are scaled by the load factor ``lam`` and prescribed
points move from their start to their target position linearly in ``lam``.
"""

from __future__ import annotations

import logging
from dataclasses import dataclass, field, replace

import numpy as np
from numpy.typing import NDArray

from ..mesh import Mesh, discretize, with_loads_of
from ..model import StaticsSettings, System
from ..results import StaticResult
from .assembly import BlockPattern, SparseFactor, factorize, gather_free, scatter_free, solve_sparse
from .coupled_statics import CoupledStatics, solve_coupled
from .equilibrium import ForceState, StaticModel
from .initial_shape import initial_positions
from .newton import Counters, NewtonPolicy, TangentCache
from .newton import solve as newton_solve

FloatArray = NDArray[np.float64]
logger = logging.getLogger(__name__)


@dataclass
class _Counters(Counters):
    """The Newton counters and the residual history of a static solve."""

    history: list[float] = field(default_factory=list)


def equilibrium_for(system: System, statics: StaticResult | None,
                    analysis: str) -> StaticResult:
    """The static equilibrium an ``analysis`` linearizes about: ``statics`` when given, else
    solved with the system's settings.

    Raises
    ------
    ConvergenceError
        When it did not converge (naming the analysis).
    """
    from ..errors import ConvergenceError

    if statics is None:
        statics = solve_statics(system)
    if not statics.success:
        raise ConvergenceError(f"{analysis} of {system.name}: no static equilibrium to "
                               f"linearize about ({statics.message})")
    return replace(statics, mesh=with_loads_of(statics.mesh, system))


def lines_at_rest(system: System, mesh: Mesh | None = None) -> StaticResult:
    """The lines in static equilibrium with every body held at the pose the case gives (as
    MoorDyn computes its lines' initial condition with the bodies fixed): the start of a
    dynamics analysis with ``start: initial``. ``success``: the lines' balance; the bodies'
    out-of-balance forces are what sets them moving."""
    settings = _default_settings(system)
    mesh = mesh or discretize(system)
    return _solve(system, settings, None, mesh, None, bodies_held=True)


def solve_statics(
    system: System,
    settings: StaticsSettings | None = None,
    initial: FloatArray | None = None,
    mesh: Mesh | None = None,
    body_force: FloatArray | None = None,
) -> StaticResult:
    """Find the static equilibrium of ``system``.

    Parameters
    ----------
    system
        The problem.
    settings
        Method and tolerances; default: the first statics analysis of the system, else Newton.
    initial
        Starting node positions (n_nodes, 3); default: catenary/straight start
        (:func:`~moorline.solvers.initial_shape.initial_positions`).
    mesh
        A mesh of ``system`` if already built.
    body_force
        Extra constant forces at the body origins (n_bodies, 3), world axes (the stochastic
        analysis' mean drag); with ``current_drag`` the bodies also carry the current's
        drag (:func:`body_current_drag`).

    Returns
    -------
    StaticResult
        ``success`` is False when the method did not reach the tolerance; the message says where
        the largest residual is.
    """
    settings = settings or _default_settings(system)
    mesh = mesh or discretize(system)
    current = _current_field(system) if settings.current_drag else None
    if mesh.body_names and (current is not None or body_force is not None):
        return _with_body_drag(system, settings, initial, mesh, current, body_force)
    return _solve(system, settings, initial, mesh, current)


MAX_BODY_DRAG_UPDATES = 20
"""Most statics re-solved with the current's drag on the bodies at their new origins (a
current profile; a uniform current needs none)."""


def body_current_drag(mesh: Mesh, current, origins: FloatArray) -> FloatArray:
    """The steady current's drag on each body (n_bodies, 3) at its origin ``origins``
    (n_bodies, 3): ``1/2 rho Cd A_i |U_i| U_i`` per world direction, the time domain's law
    (:class:`moorline.model.Body` ``drag_area``, ``Cd``) with the body at rest."""
    if current is None or not len(mesh.bodies):
        return np.zeros((len(mesh.bodies), 3))
    U = current.kinematics(np.asarray(origins, dtype=float).reshape(-1, 3), 0.0)[0]
    area = np.array([b.drag_area for b in mesh.bodies], dtype=float)
    cd = np.array([b.Cd for b in mesh.bodies], dtype=float)[:, None]
    return 0.5 * float(mesh.water_density) * cd * area * np.abs(U) * U


def _with_body_drag(system: System, settings: StaticsSettings, initial: FloatArray | None,
                    mesh: Mesh, current, extra: FloatArray | None = None) -> StaticResult:
    """Statics with the current's drag on the lines and, as a constant force at each body
    origin, on the bodies (:func:`body_current_drag`), re-evaluated at the solved origins
    until it no longer changes (1e-9 relative), plus ``extra`` body forces (n_bodies, 3)."""
    bodies = mesh.bodies
    origins = np.array([b.position for b in bodies], dtype=float)
    extra = np.zeros((len(bodies), 3)) if extra is None else extra
    result = None
    for _ in range(MAX_BODY_DRAG_UPDATES):
        drag = body_current_drag(mesh, current, origins)
        loaded = tuple(replace(b, force=(*(np.asarray(b.force[:3]) + d + e), *b.force[3:]))
                       for b, d, e in zip(bodies, drag, extra, strict=True))
        result = _solve(system, settings, initial, replace(mesh, bodies=loaded), current)
        origins, initial = result.body_pose[:, :3], result.positions
        new = body_current_drag(mesh, current, origins)
        if not result.success or np.all(np.abs(new - drag)
                                        <= 1e-9 * max(float(np.abs(drag).max()), 1e-300)):
            break
    return replace(result, mesh=replace(result.mesh, bodies=bodies))


def _solve(system: System, settings: StaticsSettings, initial: FloatArray | None, mesh: Mesh,
           current, bodies_held: bool = False) -> StaticResult:
    model = StaticModel(mesh, current, exact_cable=True,
                        friction=system.environment.seabed.friction)
    x = (initial_positions(system, mesh, settings.start) if initial is None
         else np.array(initial, dtype=float))
    target = mesh.node_position[~mesh.free_nodes]
    solver = {"newton": _newton, "incremental": _incremental, "relaxation": _relaxation}
    counters = _Counters()
    fixed_rows = ~np.isin(np.flatnonzero(~mesh.free_nodes), mesh.slave_node)

    def hold(x_held: FloatArray):
        """The lines in equilibrium with the body nodes held where ``x_held`` has them; the
        fixed and prescribed points moved from where they are to their targets."""
        held = x_held[~mesh.free_nodes]
        goal = held.copy()
        goal[fixed_rows] = target[fixed_rows]
        tol = _tolerance(model, x_held, settings)
        if not mesh.free_nodes.any():  # every line node is held: nothing to solve here
            x_new = x_held.copy()
            _move_supports(model, x_new, held, goal, 1.0)
            return _checked(model, tol, counters, True, "no free line nodes", 0,
                            _residual(model, x_new, 1.0, counters)[1], x_new)
        out = solver[settings.method](model, x_held.copy(), held, goal, settings, counters)
        if not out[0] and settings.method == "newton":
            out = _regularized_fallback(model, x_held, held, goal, settings, counters, out)
        if not out[0] and settings.method == "newton":
            out = _relaxation_fallback(model, x_held, held, goal, settings, counters, out)
        return _checked(model, tol, counters, *out)

    # bodies by Newton on their six dofs, the lines re-equilibrated (robust line statics)
    # with the bodies held at every trial pose; without bodies, the line statics alone
    ok, message, iterations, state, x, poses = solve_coupled(mesh, x, settings, counters, hold,
                                                             model.current, bodies_held)
    pose = poses.as_array()
    extras: dict = {"seabed_friction": model.friction} if model.friction > 0 else {}
    if any(b.kind == "pinned" for b in mesh.bodies):
        problem = CoupledStatics(mesh, exact_cable=True, current=model.current)
        extras["pin_reaction"] = -problem.body_forces(state, poses)[:, :3]
    return StaticResult(
        success=ok, message=message, method=settings.method, iterations=iterations,
        load_steps=settings.load_steps, residual_history=np.array(counters.history),
        n_residual=counters.residuals, n_tangent=counters.tangents,
        n_factorizations=counters.factorizations, positions=x, tension=state.tension,
        element_forces=state.element_forces, mesh=mesh, case=system.name, units=system.units,
        body_pose=pose, current_drag=current is not None, extras=extras)


def _current_field(system: System):
    """The environment's steady current as a fluid field (``None`` without one)."""
    from ..waves.current import CurrentProfile

    c = system.environment.current
    if c.z_levels:
        return CurrentProfile(tuple(c.z_levels), tuple(c.speeds), tuple(c.headings_deg))
    if c.speed != 0.0 and np.isfinite(c.speed):
        speed, heading = (c.speed, c.heading_deg) if c.speed > 0 else (-c.speed,
                                                                         c.heading_deg + 180)
        return CurrentProfile.uniform(speed, heading)
    return None


def _default_settings(system: System) -> StaticsSettings:
    return system.first(StaticsSettings)


def _tolerance(model: StaticModel, x: FloatArray, settings: StaticsSettings) -> float:
    """The out-of-balance force every method must end below: ``tolerance`` times the load
    scale, at least the round-off floor at ``x``."""
    return max(settings.tolerance * model.load_scale(), model.roundoff_floor(x))


def _checked(model: StaticModel, tol: float, counters: _Counters, ok: bool, message: str,
             iterations: int, state: ForceState, x: FloatArray):
    """The one residual check every method ends with: the full loads, the supports at their
    targets, the largest out-of-balance force finite and at most the tolerance the methods
    use (:func:`_tolerance` at the start, or at the end if larger)."""
    R, state = _residual(model, x, 1.0, counters)
    norm = float(np.abs(R).max(initial=0.0))
    if ok and not norm <= max(tol, model.roundoff_floor(x)):
        where = describe_dof(model.mesh, int(np.argmax(np.nan_to_num(np.abs(R), nan=np.inf)))) \
            if R.size else "-"
        ok, message = False, (f"{message}, but the final out-of-balance force {norm:.3e} at "
                              f"{where} is above the tolerance")
    return ok, message, iterations, state, x


def _move_supports(model: StaticModel, x: FloatArray, start: FloatArray, target: FloatArray,
                   lam: float) -> None:
    x[~model.mesh.free_nodes] = start + lam * (target - start)


def _residual(model: StaticModel, x: FloatArray, lam: float,
              counters: _Counters) -> tuple[FloatArray, ForceState]:
    counters.residuals += 1
    return model.residual(x, lam)


@dataclass
class _StaticTrial:
    r: FloatArray
    state: ForceState


class _NewtonStatics:
    """One load increment of the static balance as a problem of the Newton core: the exact
    tangent, a step limited to ``max_step``, and a line search that also accepts a step
    lowering the potential energy enough (Armijo; the loads are conservative but a current's
    drag, held at its value at the start of the search, its work added to the energy; with
    sag-corrected elements, which have no potential, the residual norm alone)."""

    def __init__(self, model: StaticModel, lam: float, max_step: float) -> None:
        self.model, self.lam, self.max_step = model, lam, max_step
        self.dof = model.mesh.dof_of_node
        self.factorizer = SparseFactor.for_few_solves(model.pattern)
        self.shift = _shift(model)

    def residual(self, x: FloatArray, tangent: bool) -> _StaticTrial:
        return _StaticTrial(*self.model.residual(x, self.lam))

    def factorize(self, x: FloatArray, trial: _StaticTrial) -> SparseFactor:
        if not self.model.friction:  # friction's stuck zone is near-singular: always shift
            try:
                return self.factorizer.factor(self.model.tangent_values(x))
            except np.linalg.LinAlgError:  # a pile free to slide: the shifted matrix
                pass
        return self.factorizer.factor(self.model.tangent_values(x, shift=self.shift))

    def update(self, x: FloatArray, du: FloatArray) -> FloatArray:
        return x + scatter_free(du, self.dof)

    def limit(self, x: FloatArray, du: FloatArray) -> FloatArray:
        return gather_free(_limit_step(scatter_free(du, self.dof), self.max_step), self.dof)

    def search_context(self, x: FloatArray, du: FloatArray, trial0: _StaticTrial):
        if self.model.sag is not None:
            return None
        frozen = self.model.drag_loads(x, self.lam)
        slope = -float(np.sum(du * trial0.r))
        return frozen, self.model.potential_energy(x, self.lam, frozen), slope

    def accept(self, x, x_try, trial, alpha, du, trial0, context) -> bool:
        if context is None:  # sag-corrected elements have no potential: the residual's norm
            return False
        frozen, energy0, slope = context
        return slope < 0 and (self.model.potential_energy(x_try, self.lam, frozen)
                              <= energy0 + 1e-4 * alpha * slope)


#: Levenberg-Marquardt shift of a singular static Newton matrix, relative to the stiffest
#: element.
SHIFT = 1e-9


def _shift(model: StaticModel) -> float:
    """A vanishing diagonal shift for a singular Newton matrix: a straight slack pile on the
    seabed (no force in its elements, none across the seabed) is free to move sideways,
    which leaves the tangent singular; the shift makes those modes stand still (their
    residual is zero) and changes the step elsewhere by a relative ``SHIFT``, not the
    equilibrium. Used only when the unshifted matrix does not factorize."""
    m = model.mesh
    return SHIFT * float(np.max(m.EA / m.length0, initial=0.0))


def _limit_step(dx: FloatArray, max_step: float) -> FloatArray:
    """Scale a displacement step so that no node moves farther than ``max_step`` (the node
    norms taken relative to the largest component: a near-singular solve's huge step does
    not overflow)."""
    peak = float(np.abs(dx).max(initial=0.0))
    if not 0.0 < peak < np.inf:
        return dx
    unit = dx / peak
    largest = peak * float(np.sqrt((unit * unit).sum(axis=1)).max())
    return dx * (max_step / largest) if largest > max_step else dx


def _newton(model, x, start, target, settings, counters):
    """Residual feedback with equilibrium iterations per load increment (Tuah eq. 4.1.2),
    each increment solved by the Newton core."""
    tol = _tolerance(model, x, settings)
    max_step = settings.max_step * model.mesh.longest_line
    policy = NewtonPolicy(tolerance=tol, max_iterations=settings.max_iterations,
                          stiffness_update=settings.stiffness_update, age_per="iteration",
                          refresh_ratio=None, stall_limit=0, max_halvings=11)
    total, state = 0, None
    for step in range(1, settings.load_steps + 1):
        lam = step / settings.load_steps
        _move_supports(model, x, start, target, lam)
        out = newton_solve(_NewtonStatics(model, lam, max_step), x, policy, TangentCache(),
                           counters)
        counters.history.extend(out.history)
        x, state, total = out.u, out.trial.state, total + out.iterations
        if not out.converged:
            return False, _failure(model, out.trial.r, state, step, settings, out.reason), \
                total, state, x
    return True, f"converged in {total} iterations", total, state, x


def _incremental(model, x, start, target, settings, counters):
    """Purely incremental loading, Tuah eq. 4.1.1: no equilibrium correction."""
    mesh = model.mesh
    pattern_all = BlockPattern(mesh.pattern_pairs, np.arange(mesh.n_nodes * 3).reshape(-1, 3))
    free = (mesh.dof_of_node >= 0).ravel()
    n = settings.load_steps
    for step in range(1, n + 1):
        K = model.tangent(x, pattern_all).tocsr()
        counters.tangents += 1
        d_prescribed = np.zeros((mesh.n_nodes, 3))
        d_prescribed[~mesh.free_nodes] = (target - start) / n
        rhs = (model.external / n).ravel()[free] - K[free][:, ~free] @ d_prescribed.ravel()[~free]
        counters.factorizations += 1
        du = solve_sparse(K[free][:, free], rhs)
        x = x + d_prescribed + scatter_free(du, mesh.dof_of_node)
        R, state = _residual(model, x, step / n, counters)
        counters.history.append(float(np.abs(R).max(initial=0.0)))
    ok = counters.history[-1] <= _tolerance(model, x, settings)
    msg = (f"{n} load increments; final out-of-balance force {counters.history[-1]:.3e} "
           "(purely incremental: no equilibrium correction)")
    return ok, msg, n, state, x


def _relaxation(model, x, start, target, settings, counters):
    """Viscous relaxation, Tuah eq. 4.1.5-4.1.8, damping C(t) = mu C(t - dt) (eq. 6.1.1).

    Tuah (sec. 4.1) leaves the damping schedule to judgement ("adjustment of the damping
    constant is recommended"). Our rule: a step that raises the out-of-balance force by more
    than half is rejected, the damping goes back up by 1/mu^2 and the stiffness is refreshed;
    otherwise the damping decays by ``mu`` each step and the stiffness is refreshed every
    ``stiffness_update`` steps.
    """
    import scipy.sparse as sp

    tol = _tolerance(model, x, settings)
    dof = model.mesh.dof_of_node
    damping, K, K_age = settings.damping, None, 0
    lam = min(1.0, 1.0 / settings.load_steps)
    _move_supports(model, x, start, target, lam)
    R, state = _residual(model, x, lam, counters)
    counters.history.append(float(np.abs(R).max(initial=0.0)))
    for it in range(1, settings.max_iterations + 1):
        if K is None or K_age >= settings.stiffness_update:
            K, K_age = model.tangent(x), 0
            counters.tangents += 1
        shift = sp.identity(K.shape[0], format="csr") * (damping / settings.pseudo_dt)
        counters.factorizations += 1
        try:
            step = factorize(K + shift).solve(R)
        except np.linalg.LinAlgError as exc:
            return False, _failure(model, R, state, None, settings, f"singular matrix: {exc}"), \
                it, state, x
        x_trial = x + scatter_free(step, dof)
        K_age += 1
        lam = min(1.0, (it + 1) / settings.load_steps)
        _move_supports(model, x_trial, start, target, lam)
        R_trial, state_trial = _residual(model, x_trial, lam, counters)
        norm = float(np.abs(R_trial).max(initial=0.0))
        if lam >= 1.0 and norm > 1.5 * counters.history[-1]:
            damping, K = damping / settings.damping_decrement**2, None
            counters.history.append(counters.history[-1])
            continue
        x, R, state = x_trial, R_trial, state_trial
        counters.history.append(norm)
        if lam >= 1.0 and norm <= tol:
            return True, f"converged in {it} relaxation steps", it, state, x
        damping *= settings.damping_decrement
    return False, _failure(model, R, state, None, settings), settings.max_iterations, state, x


def _regularized_fallback(model, x, start, target, settings, counters, failed):
    """Newton's failure on the exact cable law retried as a continuation: Newton on the
    regularized law (slack elements with ``slack_ratio EA``, the smoothing band; its tangent
    is the exact derivative of its residual, which guides a step that throws elements slack
    better), then Newton on the exact law from there. The exact law's result when it
    converges, else the first failure."""
    regularized = StaticModel(model.mesh, model.current, friction=model.friction)
    ok, _, iterations, _, x = _newton(regularized, x.copy(), start, target, settings, counters)
    if not ok:
        return failed
    polish = replace(settings, load_steps=1)
    ok, message, more, state, x = _newton(model, x, target, target, polish, counters)
    if not ok:
        return failed
    return (True, f"{message} on the exact cable law from the regularized law's equilibrium "
            f"after Newton did not ({failed[1]})", failed[2] + iterations + more, state, x)


def _relaxation_fallback(model, x, start, target, settings, counters, failed):
    """Newton's failure retried by viscous relaxation (Tuah eq. 4.1.5-4.1.8) from the same
    start, with 20 times Newton's iteration limit: its damping steadies what a Newton step
    cannot, such as a long lying stretch that seabed friction leaves without tension (no
    stiffness, and a friction force with no potential for the line search) or a buoyant
    line folded over its fairlead with almost no horizontal tension. Its result when it
    converges (the same residual check follows), else Newton's failure."""
    relax = replace(settings, method="relaxation", max_iterations=20 * settings.max_iterations)
    ok, message, iterations, state, x = _relaxation(model, x.copy(), start, target, relax,
                                                    counters)
    if not ok:
        return failed
    return (True, f"relaxation {message} after Newton did not ({failed[1]})",
            failed[2] + iterations, state, x)


def _failure(model: StaticModel, R: FloatArray, state: ForceState, step: int | None,
             settings: StaticsSettings, reason: str = "") -> str:
    where = describe_dof(model.mesh, int(np.argmax(np.abs(R)))) if R.size else "-"
    at = f" in load step {step}/{settings.load_steps}" if step else ""
    why = f" ({reason})" if reason and reason != "iteration limit" else ""
    return (f"{settings.method} did not converge{at} within {settings.max_iterations} "
            f"iterations{why}: largest out-of-balance force {np.abs(R).max(initial=0.0):.3e} "
            f"at {where}")


def describe_dof(mesh: Mesh, dof: int) -> str:
    """Human description of a global dof: the point or the line and node it belongs to."""
    node, comp = np.argwhere(mesh.dof_of_node == dof)[0]
    axis = "xyz"[comp]
    if node < len(mesh.point_names):
        return f"point {mesh.point_names[node]} ({axis})"
    for k, nodes in enumerate(mesh.line_nodes):
        hit = np.flatnonzero(nodes == node)
        if hit.size:
            i = int(hit[0])
            return (f"line {mesh.line_names[k]}, node {i} ({axis}), between elements {i - 1} "
                    f"and {i}")
    return f"node {node} ({axis})"
