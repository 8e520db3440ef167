"""The one Newton iteration of moorline: statics, the implicit time step and harmonic balance
all solve their nonlinear equations here.

A problem supplies the residual, a factored tangent, and how a step changes its unknowns;
this module owns everything else, once: the modified-Newton refresh policy (a factorization is
reused until it gets old, convergence slows, or a line search along it fails), the backtracking
line search, the stall rule, and the counters. The compiled time step
(:mod:`moorline.solvers.fast_newmark`) runs the same algorithm and reads its constants from the
same :class:`NewtonPolicy`.

The rules (one set, for every analysis):

- converged when the residual max-norm is at or below ``tolerance``;
- the tangent is refreshed when there is none, when it is ``stiffness_update`` uses old (uses
  are counted per iteration or per solve, :attr:`NewtonPolicy.age_per`), when the problem asks
  for it (a changed time step), and after an iteration that reduced the max-norm by less than
  ``refresh_ratio``;
- line search: the step is halved until the problem accepts the trial (default: the residual
  2-norm decreases), at most ``max_halvings`` times; when no trial is accepted and the tangent
  was factored before this solve (stale), the iteration is retried from the same point with a
  fresh tangent, otherwise the last trial is taken;
- stall: ``stall_limit`` iterations in a row each reducing the max-norm by less than
  ``stall_ratio`` end the solve as failed (the caller cuts the step);
- at most ``max_iterations`` solves; the final iterate is checked once more;
- local phase (``local_iterations > 0``, problems with ``local_window``): after an accepted
  iteration that did not converge, while the residual sits on a few nodes, Newton on a window
  of nodes around them (the rest frozen): the nodes whose residual (max over their dofs)
  exceeds ``max(local_fraction * norm, tolerance)``, padded by ``local_pad`` rings of
  elements; a fresh tangent of the window, the full iterations' line search (the policy's
  merit; its residual evaluations counted like theirs); it stops when the window covers
  more than ``local_max_share`` of the free nodes, when the line search fails, when an
  iteration reduces the max-norm by less than ``stall_ratio``, when the largest residual
  left is outside the window (a window's step moves residual onto its frozen edge, which
  more local iterations only push outwards), at convergence, or after
  ``local_iterations``. The next full iteration keeps the factorization (the refresh rules
  above apply): what the local phase leaves is the smooth part a stale tangent handles.
  This is nonlinear elimination (Lanzkron, Rose and Wilkes 1996, "An analysis of approximate
  nonlinear elimination", SIAM J. Sci. Comput. 17(2):538-559), a restricted nonlinear
  Schwarz correction on the strongly nonlinear subdomain (Cai and Li 2011, "Inexact Newton
  methods with restricted additive Schwarz based nonlinear elimination for problems with
  high local nonlinearity", SIAM J. Sci. Comput. 33(2):746-762). The convergence test is the
  full residual's: only the path changes.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Literal, Protocol

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class NewtonPolicy:
    """Constants of the Newton iteration.

    Attributes
    ----------
    tolerance
        Convergence threshold on the residual max-norm [force].
    max_iterations
        Linear solves per call of :func:`solve`.
    stiffness_update
        Age (in ``age_per`` units) at which a reused factorization is refreshed.
    age_per
        ``iteration``: the age counts iterations (statics); ``solve``: it counts completed
        solves, i.e. time steps (a step usually converges on a tangent from earlier steps).
    refresh_ratio
        Refresh the tangent after an iteration whose max-norm is above this fraction of the
        previous one (``None``: never for this reason).
    stall_ratio, stall_limit
        ``stall_limit`` iterations in a row above ``stall_ratio`` of the previous max-norm end
        the solve (``stall_limit = 0``: never).
    max_halvings
        Line-search halvings of a step (``max_halvings + 1`` trials).
    merit
        What the line search asks to decrease: the residual's 2-norm or its max-norm.
    local_iterations
        Local (windowed) iterations after a full one (0: no local phase; see the module).
    local_fraction, local_pad, local_max_share
        The window: nodes above ``local_fraction`` of the max-norm, padded by ``local_pad``
        element rings, at most ``local_max_share`` of the free nodes.
        (``local_pad`` 6: one OC3 line under the P1 motion at 1,000 elements, 30 tolerances
        0.65e-6 ... 1.5e-6, P4 12.8x with 8, 12.1x with 6, 12.2-13.0 with 4, 7, 12.)
    """

    tolerance: float
    max_iterations: int
    stiffness_update: int = 1
    age_per: Literal["iteration", "solve"] = "solve"
    refresh_ratio: float | None = 0.5
    stall_ratio: float = 0.9
    stall_limit: int = 3
    max_halvings: int = 4
    merit: Literal["l2", "max"] = "l2"
    local_iterations: int = 0
    local_fraction: float = 1e-2
    local_pad: int = 6
    local_max_share: float = 0.3


@dataclass
class Counters:
    """Work done (accumulated over calls)."""

    iterations: int = 0
    residuals: int = 0
    tangents: int = 0
    factorizations: int = 0
    local_iterations: int = 0

    def as_dict(self) -> dict[str, int]:
        """The counters as a plain dict."""
        return {"iterations": self.iterations, "residuals": self.residuals,
                "tangents": self.tangents, "factorizations": self.factorizations,
                "local_iterations": self.local_iterations}


@dataclass
class TangentCache:
    """The factored tangent a modified Newton iteration reuses, and its age."""

    factor: Any = None
    age: int = 0
    key: Any = None  # what the factorization depends on besides the state (e.g. the step)

    def forget(self) -> None:
        """Drop the factorization (the next iteration refactorizes)."""
        self.factor, self.age, self.key = None, 0, None

    def needs_refresh(self, policy: NewtonPolicy, key: Any = None) -> bool:
        """Whether the cached factorization may not be reused."""
        return self.factor is None or self.key != key or self.age >= policy.stiffness_update


class Trial(Protocol):
    """What a residual evaluation returns: at least the residual vector ``r``; a trial with
    an attribute ``u`` replaces the unknowns it was evaluated at by ``u`` (a residual that
    first projects them, e.g. re-equilibrates the lines of a body problem)."""

    r: FloatArray


class Problem(Protocol):
    """A nonlinear system ``r(u) = 0`` for :func:`solve`.

    ``u`` is whatever the problem uses as its unknowns (node positions, body poses...);
    :func:`solve` only handles residual and step vectors.
    """

    def residual(self, u: Any, tangent: bool) -> Trial:
        """The residual at ``u`` (and the tangent's ingredients when ``tangent``)."""

    def factorize(self, u: Any, trial: Trial) -> Any:
        """A factorization (``solve(rhs)``) of the tangent ``-dr/du`` at ``u``; ``trial`` is
        the residual evaluation at ``u`` (it carries the tangent's ingredients when it was
        evaluated with ``tangent=True``)."""

    def update(self, u: Any, du: FloatArray) -> Any:
        """The unknowns after the step ``du``."""


@dataclass
class Outcome:
    """How a call of :func:`solve` ended."""

    converged: bool
    u: Any
    trial: Any
    norm: float
    iterations: int
    reason: str = ""
    history: list[float] = field(default_factory=list)


def max_norm(r: FloatArray) -> float:
    """Max-norm of a residual vector (0 for an empty one)."""
    return float(np.abs(r).max(initial=0.0))


def solve(problem: Problem, u: Any, policy: NewtonPolicy, cache: TangentCache,
          counters: Counters, key: Any = None, trial: Trial | None = None) -> Outcome:
    """Newton iterations with line search from ``u`` until the residual is below tolerance.

    Parameters
    ----------
    problem
        Residual, tangent factorization and update of the unknowns.
    u
        Starting unknowns.
    policy
        Tolerance and the refresh, line-search and stall constants.
    cache
        The factorization reused between iterations and calls; updated in place.
    counters
        Accumulated work; updated in place.
    key
        A value the factorization depends on (the time step): a different key refreshes it.
    trial
        The residual evaluation at ``u`` if the caller already has it.
    """
    refresh = cache.needs_refresh(policy, key)
    if trial is None:
        trial = _evaluate(problem, u, refresh, counters)
    u = getattr(trial, "u", u)
    norm = max_norm(trial.r)
    history = [norm]
    fresh_here = False  # a factorization made during this call
    stalled = 0
    for it in range(policy.max_iterations):
        if norm <= policy.tolerance:
            return _done(cache, policy, Outcome(True, u, trial, norm, it, "converged", history))
        if refresh:
            try:
                trial = _factorize(problem, u, trial, cache, key, counters)
            except np.linalg.LinAlgError as exc:
                cache.forget()
                return Outcome(False, u, trial, norm, it, f"singular tangent: {exc}", history)
            refresh, fresh_here = False, True
        du = cache.factor.solve(trial.r)
        if hasattr(problem, "limit"):
            du = problem.limit(u, du)
        counters.iterations += 1
        if policy.age_per == "iteration":
            cache.age += 1
        u_new, trial_new, better = _line_search(problem, u, du, trial, policy, counters)
        if not better and not fresh_here:
            refresh = True  # a stale tangent: refresh it and retry from the same point
            continue
        norm_new = max_norm(trial_new.r)
        if policy.refresh_ratio is not None and norm_new > policy.refresh_ratio * norm:
            refresh = True
        elif cache.age >= policy.stiffness_update:
            refresh = True
        stalled = stalled + 1 if norm_new > policy.stall_ratio * norm else 0
        u, trial, norm = getattr(trial_new, "u", u_new), trial_new, norm_new
        if policy.local_iterations and norm > policy.tolerance \
                and hasattr(problem, "local_window"):
            u, trial, norm, worked = _local_phase(problem, u, trial, norm, policy, counters)
            if worked:  # the factorization stays (refreshed by the usual rules)
                stalled = 0
        history.append(norm)
        if policy.stall_limit and stalled >= policy.stall_limit:
            return Outcome(False, u, trial, norm, it + 1, "stalled", history)
    if norm <= policy.tolerance:
        return _done(cache, policy, Outcome(True, u, trial, norm, policy.max_iterations,
                                            "converged", history))
    return Outcome(False, u, trial, norm, policy.max_iterations, "iteration limit", history)


def _done(cache: TangentCache, policy: NewtonPolicy, outcome: Outcome) -> Outcome:
    if policy.age_per == "solve":
        cache.age += 1
    return outcome


def _evaluate(problem: Problem, u: Any, tangent: bool, counters: Counters) -> Trial:
    counters.residuals += 1
    return problem.residual(u, tangent)


def _factorize(problem: Problem, u: Any, trial: Trial, cache: TangentCache, key: Any,
               counters: Counters) -> Trial:
    """Factorize the tangent at ``u`` (re-evaluating there when ``trial`` has no tangent)."""
    if not getattr(trial, "has_tangent", True):
        trial = _evaluate(problem, u, True, counters)
    counters.tangents += 1
    counters.factorizations += 1
    cache.factor, cache.age, cache.key = problem.factorize(u, trial), 0, key
    return trial


def _line_search(problem: Problem, u: Any, du: FloatArray, trial0: Trial,
                 policy: NewtonPolicy, counters: Counters) -> tuple[Any, Trial, bool]:
    """Halve the step until the merit (``policy.merit`` of the residual) falls below the
    merit at ``trial0`` or the problem accepts the trial (its optional ``accept`` and
    ``search_context``); every trial counts as a residual evaluation. The one line search of
    the full and the local iterations. Returns the last trial's unknowns, the trial and
    whether it was accepted."""
    accept = getattr(problem, "accept", None)
    measure = max_norm if policy.merit == "max" else np.linalg.norm
    merit0 = float(measure(trial0.r))
    context = problem.search_context(u, du, trial0) if hasattr(problem, "search_context") \
        else None
    alpha = 1.0
    for _ in range(policy.max_halvings + 1):
        u_try = problem.update(u, alpha * du)
        trial = _evaluate(problem, u_try, False, counters)
        if float(measure(trial.r)) < merit0:
            return u_try, trial, True
        if accept is not None and accept(u, u_try, trial, alpha, du, trial0, context):
            return u_try, trial, True
        alpha *= 0.5
    return u_try, trial, False


def _local_phase(problem: Problem, u: Any, trial: Trial, norm: float, policy: NewtonPolicy,
                 counters: Counters) -> tuple[Any, Trial, float, bool]:
    """Newton on a window of nodes around the residual, the rest frozen (nonlinear
    elimination, see the module). The problem supplies ``local_window(trial, threshold, pad,
    share)`` (the window's unknowns, or None) and ``local_step(u, trial, window)`` (the
    step of the window's unknowns with the window's rows and columns of the tangent at
    ``trial``, evaluated with it). Returns the iterate, its trial, max-norm and whether a
    local step was solved."""
    worked = False
    for _ in range(policy.local_iterations):
        window = problem.local_window(trial, max(policy.local_fraction * norm,
                                                 policy.tolerance),
                                      policy.local_pad, policy.local_max_share)
        if window is None:
            break
        here = _evaluate(problem, u, True, counters)
        du = problem.local_step(u, here, window)
        counters.local_iterations += 1
        worked = True
        u_try, t_try, accepted = _line_search(problem, u, du, here, policy, counters)
        if not accepted:
            break
        u, trial = u_try, t_try
        new = max_norm(trial.r)
        ratio, norm = new / norm, new
        # the largest residual left outside the window: its frozen edge, not Newton, limits
        # the local iterations; a full iteration follows
        if norm <= policy.tolerance or ratio > policy.stall_ratio \
                or max_norm(trial.r[window]) < new:
            break
    return u, trial, norm, worked
