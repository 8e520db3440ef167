"""The Newton core (moorline.solvers.newton) on small problems with known roots."""

from dataclasses import dataclass

import numpy as np
import pytest

from moorline.solvers.newton import Counters, NewtonPolicy, TangentCache, solve


@dataclass
class _Trial:
    r: np.ndarray
    has_tangent: bool = True


class _Dense:
    def __init__(self, J):
        self.J = J

    def solve(self, rhs):
        return np.linalg.solve(self.J, rhs)


class _Cubic:
    """r(u) = b - (u + u^3) componentwise: root known in closed form (Cardano), tangent
    1 + 3u^2 (a scaled tangent makes it wrong on purpose)."""

    def __init__(self, b, tangent_scale=1.0, singular=False):
        self.b, self.scale, self.singular = np.asarray(b, float), tangent_scale, singular

    def residual(self, u, tangent):
        return _Trial(self.b - (u + u**3), tangent)

    def factorize(self, u, trial):
        if self.singular:
            raise np.linalg.LinAlgError("zero pivot")
        return _Dense(np.diag(self.scale * (1 + 3 * u**2)))

    def update(self, u, du):
        return u + du


def _cardano(b):
    # real root of u^3 + u - b = 0
    d = np.sqrt(b * b / 4 + 1 / 27)
    return np.cbrt(b / 2 + d) + np.cbrt(b / 2 - d)


def test_newton_converges_quadratically_to_the_root():
    b = np.array([0.5, 3.0, -10.0])
    policy = NewtonPolicy(tolerance=1e-12, max_iterations=30, age_per="iteration")
    counters = Counters()
    out = solve(_Cubic(b), np.zeros(3), policy, TangentCache(), counters)
    assert out.converged
    assert np.allclose(out.u, _cardano(b), rtol=0, atol=1e-12)
    h = np.array(out.history)
    # quadratic convergence near the root: e_{k+1} <= C e_k^2 for the last steps
    tail = h[-4:-1]
    assert np.all(tail[1:] <= 10.0 * tail[:-1] ** 2 + 1e-12)
    assert counters.factorizations == counters.iterations  # fresh tangent every iteration


def test_modified_newton_reuses_the_factorization():
    b = np.array([0.2, -0.3])
    policy = NewtonPolicy(tolerance=1e-12, max_iterations=60, stiffness_update=1000,
                          age_per="iteration", refresh_ratio=None, stall_limit=0)
    counters = Counters()
    out = solve(_Cubic(b), np.zeros(2), policy, TangentCache(), counters)
    assert out.converged and np.allclose(out.u, _cardano(b), atol=1e-12)
    assert counters.factorizations == 1 and counters.iterations > 3


def test_cache_is_refreshed_for_a_new_key_and_kept_for_the_same():
    b = np.array([1.0])
    policy = NewtonPolicy(tolerance=1e-12, max_iterations=30, stiffness_update=5)
    cache, counters = TangentCache(), Counters()
    solve(_Cubic(b), np.zeros(1), policy, cache, counters, key=0.1)
    n = counters.factorizations
    solve(_Cubic(b * 1.0001), _cardano(b), policy, cache, counters, key=0.1)
    assert counters.factorizations == n  # reused: same key, young factorization
    solve(_Cubic(b * 1.0002), _cardano(b), policy, cache, counters, key=0.2)
    assert counters.factorizations == n + 1


def test_a_stale_tangent_whose_step_fails_is_refreshed_and_the_step_retried():
    # a factorization from an earlier call with the wrong sign makes every trial worse:
    # the core must not accept such a trial, it refactorizes at the same point
    b = np.array([2.0])
    policy = NewtonPolicy(tolerance=1e-12, max_iterations=30, stiffness_update=100)
    cache, counters = TangentCache(), Counters()
    cache.factor, cache.key = _Dense(np.array([[-1.0]])), None
    out = solve(_Cubic(b), np.zeros(1), policy, cache, counters)
    assert out.converged and np.allclose(out.u, _cardano(b), atol=1e-12)
    assert counters.factorizations >= 1


def test_stall_rule_ends_a_solve_that_does_not_progress():
    # a tangent 1000 times too stiff: each step removes 0.1 % of the residual
    policy = NewtonPolicy(tolerance=1e-12, max_iterations=50, stall_limit=3)
    out = solve(_Cubic([1.0], tangent_scale=1000.0), np.zeros(1), policy, TangentCache(),
                Counters())
    assert not out.converged and out.reason == "stalled" and out.iterations == 3


def test_iteration_limit_and_singular_tangent_are_failures_not_exceptions():
    policy = NewtonPolicy(tolerance=1e-14, max_iterations=2, stall_limit=0)
    out = solve(_Cubic([50.0]), np.zeros(1), policy, TangentCache(), Counters())
    assert not out.converged and out.reason == "iteration limit"
    out = solve(_Cubic([1.0], singular=True), np.zeros(1), policy, TangentCache(), Counters())
    assert not out.converged and "singular" in out.reason


@pytest.mark.parametrize("b", [0.0, 1e-20])
def test_converged_start_costs_no_factorization(b):
    counters = Counters()
    out = solve(_Cubic([b]), np.zeros(1), NewtonPolicy(1e-12, 10), TangentCache(), counters)
    assert out.converged and out.iterations == 0 and counters.factorizations == 0


class _LocalCubic(_Cubic):
    """:class:`_Cubic` with a local phase (``local_window``: the components above the
    threshold; ``local_step``: Newton on them alone) and a count of residual evaluations."""

    def __init__(self, b):
        super().__init__(b)
        self.calls = 0

    def residual(self, u, tangent):
        self.calls += 1
        return super().residual(u, tangent)

    def local_window(self, trial, threshold, pad, share):
        window = np.flatnonzero(np.abs(trial.r) > threshold)
        return window if 0 < len(window) <= share * len(trial.r) else None

    def local_step(self, u, trial, window):
        du = np.zeros_like(u)
        du[window] = trial.r[window] / (1 + 3 * u[window] ** 2)
        return du


def test_local_phase_line_search_counts_its_residual_evaluations():
    # two large components among 18 small ones: after one full iteration the residual sits
    # on the two, which the local phase solves; every evaluation it makes is counted
    b = np.full(20, 1e-3)
    b[[4, 11]] = [30.0, -8.0]
    problem = _LocalCubic(b)
    policy = NewtonPolicy(tolerance=1e-12, max_iterations=30, age_per="iteration",
                          local_iterations=20)
    counters = Counters()
    out = solve(problem, np.zeros(20), policy, TangentCache(), counters)
    assert out.converged and np.allclose(out.u, _cardano(b), rtol=0, atol=1e-12)
    assert counters.local_iterations > 0
    assert counters.residuals == problem.calls
