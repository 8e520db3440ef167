"""Input files are regular files of a sane size: checked with ``stat`` before reading, so that
``/dev/zero`` (endless), a FIFO (blocks until a writer comes) or a directory is refused at once
with a message instead of hanging or exhausting the memory."""

from __future__ import annotations

import os
import stat

__all__ = ["MAX_CASE_BYTES", "MAX_TABLE_BYTES", "file_problem"]

MAX_CASE_BYTES = 16 * 1024**2
"""Largest case file or MoorDyn deck [bytes] (16 MiB; the example cases are a few kB, a case
with a 100,000-node initial shape ~5 MB)."""

MAX_TABLE_BYTES = 256 * 1024**2
"""Largest CSV time table [bytes] (256 MiB, ~5 million rows of t, x, y, z)."""

_KINDS = ((stat.S_ISDIR, "a directory"), (stat.S_ISCHR, "a character device"),
          (stat.S_ISBLK, "a block device"), (stat.S_ISFIFO, "a named pipe"),
          (stat.S_ISSOCK, "a socket"))


def file_problem(path: str | os.PathLike[str], limit: int) -> str | None:
    """Why ``path`` may not be read as an input file, or ``None`` when it may.

    Parameters
    ----------
    path
        The file (symbolic links are followed).
    limit
        Largest size [bytes].

    Returns
    -------
    str or None
        The OS error (no such file, permission denied), not a regular file (naming what it
        is), or larger than ``limit``.
    """
    try:
        info = os.stat(path)
    except OSError as exc:
        return exc.strerror or str(exc)
    if not stat.S_ISREG(info.st_mode):
        kind = next((name for test, name in _KINDS if test(info.st_mode)), "not a file")
        return f"not a regular file ({kind})"
    if info.st_size > limit:
        return f"{info.st_size} bytes, more than the limit of {limit} bytes"
    return None
