"""moorline's per-user cache directory (BEM databases, compiled kernels).

Read from the environment only (no import beyond :mod:`os` and :mod:`pathlib`), so that the
start of a command does not pay for it.
"""

from __future__ import annotations

import os
from pathlib import Path

__all__ = ["CACHE_ENV", "cache_root"]

CACHE_ENV = "MOORLINE_CACHE_DIR"
"""Environment variable naming moorline's cache directory."""


def cache_root() -> Path:
    """moorline's cache directory: ``$MOORLINE_CACHE_DIR``, else
    ``$XDG_CACHE_HOME/moorline``, else ``~/.cache/moorline``. Not created here."""
    root = os.environ.get(CACHE_ENV)
    if root:
        return Path(root)
    xdg = os.environ.get("XDG_CACHE_HOME")
    return (Path(xdg) if xdg else Path.home() / ".cache") / "moorline"
