"""Runs of other codes on moorline systems, for comparisons and benchmarks.

The reference codes are optional (``pip install moorline[compare]``); each runner imports its
code only when called.
"""

from .moordyn_runner import largest_stable_dt, run_moordyn

__all__ = ["largest_stable_dt", "run_moordyn"]
