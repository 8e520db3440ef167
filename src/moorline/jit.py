"""numba for moorline's kernel modules: imported only after its cache directory was chosen
(:func:`moorline.numba_cache.use_source_keyed_cache`, which must run before numba reads
``NUMBA_CACHE_DIR`` at its import). The kernel modules (:data:`moorline.kernel_cache.
KERNEL_MODULES`) take ``numba`` from here, never ``import numba`` themselves.

Loading a cached kernel: numba refreshes its whole compiler context first (imports and
installs every typing and lowering registry: ``numba.np.arrayobj``, ``linalg``, the typed
containers..., about 0.2 s of CPU at a process' first kernel), which only compiling needs:
machine code loaded from the cache needs the runtime (NRT) and the C helpers, which numba
sets up anyway. :func:`_lean_cache_loading` skips the refresh for moorline's own kernels
(those of :data:`~moorline.kernel_cache.KERNEL_MODULES`: numeric loops, no hashing, no typed
containers); a cache miss compiles as before, and compiling refreshes the context itself.
Other numba functions in the process load as numba does.
"""

from __future__ import annotations

import sys

from .numba_cache import use_source_keyed_cache

use_source_keyed_cache()

import numba  # noqa: E402  (after the cache directory is set)

__all__ = ["numba"]


_TESTED_NUMBA = ((0, 59), (0, 69))
"""numba versions whose ``Cache.load_overload`` is the refresh, then ``_load_overload``
that :func:`_lean_cache_loading` replaces (outside them numba loads as it does)."""


def _version(text: str) -> tuple[int, int]:
    """``(major, minor)`` of a version string (``(0, 0)`` when it does not start so)."""
    parts = text.split(".")
    try:
        return int(parts[0]), int(parts[1])
    except (IndexError, ValueError):
        return 0, 0


_NUMBA_REBUILD_ENV: list = []
"""numba's ``numba.core.environment._rebuild_env`` (set by :func:`_lean_cache_loading`)."""


def _lean_cache_loading() -> None:
    """Load moorline's cached kernels without numba's compiler-context refresh (see the
    module docstring); nothing changes when numba's cache lacks the expected methods."""
    from numba.core import caching, environment
    from numba.core.runtime import rtsys

    from .kernel_cache import KERNEL_MODULES

    cache = caching.Cache
    full = cache.load_overload
    if getattr(full, "_moorline_lean", False) or not hasattr(cache, "_load_overload") \
            or not _TESTED_NUMBA[0] <= _version(numba.__version__) < _TESTED_NUMBA[1]:
        return
    kernels = frozenset(KERNEL_MODULES)
    _NUMBA_REBUILD_ENV.append(environment._rebuild_env)

    def load_overload(self, sig, target_context):  # noqa: ANN001, ANN202 (numba's signature)
        if getattr(getattr(self, "_py_func", None), "__module__", None) not in kernels:
            return full(self, sig, target_context)
        rtsys.initialize(target_context)  # the runtime, as refresh() would set it up
        # lean environments while loading only (see _lean_rebuild_env)
        environment._rebuild_env = _lean_rebuild_env
        try:
            with self._guard_against_spurious_io_errors():
                return self._load_overload(sig, target_context)
        finally:
            environment._rebuild_env = _NUMBA_REBUILD_ENV[0]

    load_overload._moorline_lean = True  # type: ignore[attr-defined]
    cache.load_overload = load_overload


def _lean_rebuild_env(modname, consts, env_name):  # noqa: ANN001, ANN202 (numba's signature)
    """Rebuild the environment of a function compiled into a kernel being loaded, without
    importing the module of numba's own helpers.

    Loading a cached kernel unpickles an environment (:class:`numba.core.environment.
    Environment`: the defining module's globals and the function's constants) for every
    function compiled into it, importing the module to get its globals. The array
    allocations in moorline's compiled step bring numba's helpers for the allocation's
    error message (``numba.np.arrayobj``, ``numba.cpython.unicode``, ``charseq``): importing
    those cost ~50 ms of every run (issue 16, P1). Their environments hold no constants, and
    a function compiled in nopython mode reads no globals from its environment, so they get
    an environment of their own module name only; environments with constants, and those
    of modules already imported, are rebuilt by numba. In place only while one of moorline's
    kernels loads (:func:`_lean_cache_loading`): an environment pickled while a kernel is
    compiled names numba's own function (a cache written with this one in place would pickle
    it, by value)."""
    from numba.core.environment import Environment, lookup_environment

    if consts or not str(modname).startswith("numba.") or modname in sys.modules \
            or lookup_environment(env_name) is not None:
        return _NUMBA_REBUILD_ENV[0](modname, consts, env_name)
    env = Environment({"__name__": modname})
    env.env_name = env_name
    Environment._memo[env_name] = env
    return env


_lean_cache_loading()
