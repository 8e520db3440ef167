"""Success rate of finite-element statics on 2,000 random feasible single lines (issue 10).

Each line (:mod:`moorline.verification.random_lines`: eight categories, depth 20-3,000 m,
chain, wire, polyester and buoyant lines) is solved with the default statics settings and
compared with the closed-form catenary. Prints, per category, how many converged and how many
have both end forces within 0.5 % of the closed form. Run with ``make bench``.
"""

from __future__ import annotations

import argparse
import time
from collections import Counter

import numpy as np

from moorline.solvers.statics import solve_statics
from moorline.verification.random_lines import CATEGORIES, end_force_error, geometries

TOLERANCE = 5e-3


def main() -> None:
    """Solve, compare and print."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=2000, help="number of lines")
    parser.add_argument("--seed", type=int, default=7)
    args = parser.parse_args()
    total, converged, accurate, crashed = Counter(), Counter(), Counter(), Counter()
    start = time.perf_counter()
    for g in geometries(args.n, seed=args.seed):
        total[g.category] += 1
        try:
            with np.errstate(all="ignore"):
                result = solve_statics(g.system)
        except Exception:  # noqa: BLE001 - an uncaught error is what this counts
            crashed[g.category] += 1
            continue
        if result.success:
            converged[g.category] += 1
            accurate[g.category] += end_force_error(g, result) <= TOLERANCE
    print(f"{'category':>14} {'lines':>6} {'converged':>16} {'within 0.5 %':>16} {'errors':>7}")
    for c in (*CATEGORIES, "all"):
        pick = (lambda d, c=c: sum(d.values())) if c == "all" else (lambda d, c=c: d[c])
        n = pick(total)
        ok, good = pick(converged), pick(accurate)
        print(f"{c:>14} {n:6d} {ok:7d} ({100 * ok / n:6.2f}%) {good:7d} ({100 * good / n:6.2f}%) "
              f"{pick(crashed):7d}")
    print(f"{args.n} lines in {time.perf_counter() - start:.1f} s (seed {args.seed}); reference: "
          "moorline.catenary.solve_catenary (closed form)")


if __name__ == "__main__":
    main()
