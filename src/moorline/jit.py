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
        with self._guard_against_spurious_io_errors():
            return self._load_overload(sig, target_context)

    load_overload._moorline_lean = True  # type: ignore[attr-defined]
    cache.load_overload = load_overload


_lean_cache_loading()
