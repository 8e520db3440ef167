"""numba's cache directory, named by a hash of the compiled kernels' sources (issue 16).

numba's ``cache=True`` checks a cached function against its own file's time stamp only, but
the kernels compile in code and constants of other files:
:func:`moorline.solvers.fast_loop.advance_block` inlines
:func:`moorline.solvers.fast_newmark.newmark_step` and :mod:`moorline.physics.fused`'s kernel,
and those compile in the constants of :mod:`moorline.physics.sag`. After a change to one of
them alone (an edit, a ``git checkout``) the stale machine code of the others was loaded: old
arithmetic, or a crash (``free(): invalid pointer``). So numba caches moorline's kernels in
``<cache root>/numba-<key>`` (:func:`moorline.user_cache.cache_root`), ``key`` a hash of all
:data:`KERNEL_SOURCES` and of numba's version: a change to any of them starts a new cache.
:func:`use_source_keyed_cache` sets it before moorline imports numba
(:mod:`moorline.jit`), unless the user chose numba's cache (``NUMBA_CACHE_DIR``); when the
directory cannot be created (a read-only home) numba keeps its default (``__pycache__``).
A new directory removes the other ``numba-*`` directories but the newest :data:`KEEP`, those
not used for :data:`UNUSED_S`.
"""

from __future__ import annotations

import hashlib
import importlib.util
import os
import sys
import time
from collections.abc import Iterable
from pathlib import Path

from .kernel_cache import KERNEL_MODULES
from .user_cache import cache_root

__all__ = ["KEEP", "KERNEL_SOURCES", "UNUSED_S", "cache_directory", "kernel_files", "prune",
           "source_key", "use_source_keyed_cache"]

KERNEL_SOURCES = (*KERNEL_MODULES, "moorline.physics.sag", "moorline.jit")
"""The modules whose source the compiled kernels depend on: the kernel modules,
:mod:`moorline.physics.sag` (whose constants :mod:`moorline.physics.fused` compiles in) and
:mod:`moorline.jit` (how the cached kernels are loaded and what their pickles name)."""

KEEP = 3
"""Cache directories of other sources kept (the most recently used)."""

UNUSED_S = 86400.0
"""A cache directory used within this time [s] is never removed (a running process may be
writing to it)."""

PREFIX = "numba-"
"""Name prefix of the cache directories, followed by :func:`source_key`."""

_chosen: list[str | None] = []
"""The directory :func:`use_source_keyed_cache` chose (once per process)."""


def kernel_files() -> list[Path]:
    """The source files of :data:`KERNEL_SOURCES` (found next to this module: nothing is
    imported)."""
    package = Path(__file__).resolve().parent
    return [package.joinpath(*name.split(".")[1:]).with_suffix(".py") for name in KERNEL_SOURCES]


def _numba_stamp() -> bytes:
    """numba's version file (its ``_version.py``) and location, found without importing
    numba."""
    spec = importlib.util.find_spec("numba")
    origin = (spec.origin or "") if spec is not None else ""
    try:
        return origin.encode() + Path(origin).with_name("_version.py").read_bytes()
    except OSError:
        return origin.encode()


def source_key(files: Iterable[Path]) -> str:
    """16 hex digits of a BLAKE2b hash of the files' contents (in order) and of numba's
    version. Raises :class:`OSError` when a file cannot be read."""
    digest = hashlib.blake2b(_numba_stamp(), digest_size=8)
    for path in files:
        content = Path(path).read_bytes()
        digest.update(len(content).to_bytes(8, "little"))
        digest.update(content)
    return digest.hexdigest()


def cache_directory(files: Iterable[Path] | None = None) -> Path:
    """``<cache root>/numba-<source_key(files)>``, ``files`` by default :func:`kernel_files`.
    Not created here."""
    return cache_root() / f"{PREFIX}{source_key(kernel_files() if files is None else files)}"


def prune(root: Path, current: Path, keep: int = KEEP, unused_s: float = UNUSED_S,
          now: float | None = None) -> list[Path]:
    """Remove the ``numba-*`` directories of ``root`` other than ``current`` beyond the
    ``keep`` most recently used (modification time) that were not used for ``unused_s``
    seconds before ``now`` (default: the clock's time, seconds since the epoch); returns those
    removed. Errors are ignored (another process pruning too)."""
    import shutil

    now = time.time() if now is None else now
    try:
        others = [p for p in root.iterdir()
                  if p.name.startswith(PREFIX) and p.is_dir() and p != current]
        stamped = sorted(((p.stat().st_mtime, p) for p in others), reverse=True)
    except OSError:
        return []
    removed = []
    for mtime, path in stamped[keep:]:
        if now - mtime > unused_s:
            shutil.rmtree(path, ignore_errors=True)
            removed.append(path)
    return removed


def _prepare(directory: Path) -> bool:
    """Create ``directory`` (pruning the older ones when it is new) or mark it used; whether
    it is a writable directory."""
    try:
        if directory.is_dir():
            os.utime(directory)
        else:
            directory.mkdir(parents=True, exist_ok=True)
            prune(directory.parent, directory)
    except OSError:
        return False
    return os.access(directory, os.W_OK | os.X_OK)


def use_source_keyed_cache() -> str | None:
    """Point numba's cache at :func:`cache_directory` (once per process); returns it, or
    ``None`` when numba's own setting is kept.

    Kept: ``NUMBA_CACHE_DIR`` set by the user (or numba's ``config.CACHE_DIR`` set after
    numba was imported), or a directory that cannot be created or written. Before numba is
    imported this sets ``NUMBA_CACHE_DIR`` (inherited by child processes, whose kernels are
    the same); after, ``numba.config.CACHE_DIR`` (kernel modules imported after it use it).
    Either way the user's own cached numba functions of this process go there too.
    """
    if _chosen:
        return _chosen[0]
    chosen = None
    numba = sys.modules.get("numba")
    config = getattr(numba, "config", None)
    user_set = os.environ.get("NUMBA_CACHE_DIR") or getattr(config, "CACHE_DIR", "")
    if not user_set and (numba is None or config is not None):
        try:
            directory = cache_directory()
        except OSError:  # a kernel source is unreadable: numba's own per-file check
            directory = None
        if directory is not None and _prepare(directory):
            chosen = str(directory)
            if config is None:
                os.environ["NUMBA_CACHE_DIR"] = chosen
            else:
                config.CACHE_DIR = chosen
    _chosen.append(chosen)
    return chosen
