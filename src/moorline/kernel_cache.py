"""Whether this process compiled numba kernels (first use) or loaded them from the cache.

The compiled kernels (:mod:`moorline.physics.fused`, :mod:`moorline.solvers.fast_newmark`)
are compiled at their first call and their machine code is cached on disk (``cache=True``),
so only the first run on a machine (or after an upgrade) pays the compilation. The command
line uses :func:`compiled_kernels` to say so once, with the time it took, instead of a
progress bar that seems frozen at t = 0.
"""

from __future__ import annotations

import sys

KERNEL_MODULES = ("moorline.physics.fused", "moorline.solvers.fast_fluid",
                  "moorline.solvers.fast_rigid", "moorline.solvers.fast_bodies",
                  "moorline.solvers.fast_newmark", "moorline.solvers.fast_local",
                  "moorline.solvers.fast_loop",
                  "moorline.solvers.frequency_sweep", "moorline.fast_envelope")
"""The modules holding numba kernels."""


def compiled_kernels() -> tuple[int, str]:
    """(number of kernels this process compiled instead of loading them from the cache, the
    cache directory); ``(0, "")`` when no kernel module is loaded. Reads numba's dispatcher
    statistics; imports nothing."""
    compiled, where = 0, ""
    for name in KERNEL_MODULES:
        module = sys.modules.get(name)
        if module is None:
            continue
        for value in vars(module).values():
            stats = getattr(value, "stats", None)
            misses = getattr(stats, "cache_misses", None)
            if misses is None or not hasattr(value, "py_func"):
                continue
            compiled += sum(misses.values())
            where = where or str(getattr(stats, "cache_path", ""))
    return compiled, where
