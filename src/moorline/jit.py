"""numba for moorline's kernel modules: imported only after its cache directory was chosen
(:func:`moorline.numba_cache.use_source_keyed_cache`, which must run before numba reads
``NUMBA_CACHE_DIR`` at its import). The kernel modules (:data:`moorline.kernel_cache.
KERNEL_MODULES`) take ``numba`` from here, never ``import numba`` themselves.
"""

from __future__ import annotations

from .numba_cache import use_source_keyed_cache

use_source_keyed_cache()

import numba  # noqa: E402  (after the cache directory is set)

__all__ = ["numba"]
