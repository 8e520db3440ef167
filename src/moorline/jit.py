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


_loading_kernel = [False]
"""True while one of moorline's kernels loads from the cache (:func:`_lean_cache_loading`)."""


def _lean_cache_loading() -> None:
    """Load moorline's cached kernels without numba's compiler-context refresh (see the
    module docstring); nothing changes when numba's cache lacks the expected methods."""
    from numba.core import caching
    from numba.core.runtime import rtsys

    from .kernel_cache import KERNEL_MODULES

    cache = caching.Cache
    full = cache.load_overload
    if getattr(full, "_moorline_lean", False) or not hasattr(cache, "_load_overload") \
            or not _TESTED_NUMBA[0] <= _version(numba.__version__) < _TESTED_NUMBA[1]:
        return
    kernels = frozenset(KERNEL_MODULES)

    def load_overload(self, sig, target_context):  # noqa: ANN001, ANN202 (numba's signature)
        if getattr(getattr(self, "_py_func", None), "__module__", None) not in kernels:
            return full(self, sig, target_context)
        rtsys.initialize(target_context)  # the runtime, as refresh() would set it up
        _loading_kernel[0] = True
        try:
            with self._guard_against_spurious_io_errors():
                return self._load_overload(sig, target_context)
        finally:
            _loading_kernel[0] = False

    load_overload._moorline_lean = True  # type: ignore[attr-defined]
    cache.load_overload = load_overload
    _lean_environments()


def _lean_environments() -> None:
    """Rebuild the environments of numba's own helpers without importing their modules.

    Loading a cached kernel unpickles an environment (:class:`numba.core.environment.
    Environment`: the defining module's globals and the function's constants) for every
    function compiled into it, importing the module to get its globals. The array
    allocations in moorline's compiled step bring numba's helpers for the allocation's
    error message (``numba.np.arrayobj``, ``numba.cpython.unicode``, ``charseq``): importing
    those cost ~50 ms of every run (issue 16, P1). Their environments hold no constants, and
    a function compiled in nopython mode reads no globals from its environment, so while one
    of moorline's kernels loads they get an environment of their own module name only;
    environments with constants, of modules already imported, and of any other function
    are rebuilt as numba does."""
    from numba.core import environment

    full = environment._rebuild_env
    if getattr(full, "_moorline_lean", False):
        return

    def rebuild(modname, consts, env_name):  # noqa: ANN001, ANN202 (numba's signature)
        if not _loading_kernel[0] or consts or not str(modname).startswith("numba.") \
                or modname in sys.modules or environment.lookup_environment(env_name):
            return full(modname, consts, env_name)
        env = environment.Environment({"__name__": modname})
        env.env_name = env_name
        environment.Environment._memo[env_name] = env
        return env

    rebuild._moorline_lean = True  # type: ignore[attr-defined]
    environment._rebuild_env = rebuild


_lean_cache_loading()
