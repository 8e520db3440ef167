"""numba's cache directory named by the kernels' sources (issue 16: a stale compiled loop
after a change to a kernel of another file)."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from moorline import numba_cache

ROOT = Path(__file__).resolve().parents[1]
SRC = ROOT / "src"


def _copies(tmp_path: Path) -> list[Path]:
    """Copies of the kernel sources in ``tmp_path``."""
    copies = []
    for i, path in enumerate(numba_cache.kernel_files()):
        copies.append(tmp_path / f"{i}_{path.name}")
        shutil.copyfile(path, copies[-1])
    return copies


def test_every_kernel_source_exists() -> None:
    files = numba_cache.kernel_files()
    assert len(files) == len(numba_cache.KERNEL_SOURCES)
    assert all(path.is_file() for path in files)
    assert SRC / "moorline" / "physics" / "sag.py" in [p.resolve() for p in files]


def test_the_directory_changes_with_any_kernel_source(tmp_path: Path,
                                                      monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("MOORLINE_CACHE_DIR", str(tmp_path / "cache"))
    copies = _copies(tmp_path)
    first = numba_cache.cache_directory(copies)
    assert first.parent == tmp_path / "cache"
    assert re.fullmatch(r"numba-[0-9a-f]{16}", first.name)
    assert numba_cache.cache_directory(copies) == first
    assert numba_cache.cache_directory(numba_cache.kernel_files()) == first  # same contents
    seen = {first}
    for path in copies:  # an edit of any one file alone gives a new directory
        original = path.read_bytes()
        path.write_bytes(original + b"\n# edited\n")
        seen.add(numba_cache.cache_directory(copies))
        path.write_bytes(original)
    assert len(seen) == len(copies) + 1
    assert numba_cache.cache_directory(copies) == first


def test_prune_keeps_the_newest_and_the_recently_used(tmp_path: Path) -> None:
    now = 1.7e9  # a fixed "now" [s since the epoch]: the ages are set from it, not the clock
    ages = {"numba-a": 5, "numba-b": 4, "numba-c": 3, "numba-d": 2, "numba-e": 1}  # days
    for name, days in ages.items():
        (tmp_path / name / "solvers_x").mkdir(parents=True)
        os.utime(tmp_path / name, (now - days * 86400, now - days * 86400))
    (tmp_path / "bem").mkdir()
    os.utime(tmp_path / "bem", (now - 9 * 86400, now - 9 * 86400))
    current = tmp_path / "numba-new"
    current.mkdir()
    assert numba_cache.prune(tmp_path, current, keep=3, unused_s=10 * 86400, now=now) == []
    removed = numba_cache.prune(tmp_path, current, keep=3, unused_s=1.5 * 86400, now=now)
    assert sorted(p.name for p in removed) == ["numba-a", "numba-b"]
    left = sorted(p.name for p in tmp_path.iterdir())
    assert left == ["bem", "numba-c", "numba-d", "numba-e", "numba-new"]


def _numba_cache_of(env: dict[str, str], code: str = "import moorline.physics.fused") -> str:
    """``numba.config.CACHE_DIR`` and the cache path of a compiled kernel after ``code`` in a
    fresh interpreter with ``env`` (nothing is compiled)."""
    probe = (f"{code}\nimport numba\nfrom moorline.physics import fused\n"
             "print('CACHE', numba.config.CACHE_DIR, fused.maxwell_forces.stats.cache_path)")
    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True,
                         env=env, cwd=ROOT, timeout=120)
    assert out.returncode == 0, out.stderr
    return out.stdout.rsplit("CACHE", 1)[1].strip()


def _env(**values: str) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items()
           if k not in ("NUMBA_CACHE_DIR", "MOORLINE_CACHE_DIR")}
    env["PYTHONPATH"] = os.pathsep.join([str(SRC), env.get("PYTHONPATH", "")])
    return {**env, **values}


def test_kernels_are_cached_in_the_source_keyed_directory(tmp_path: Path) -> None:
    root = tmp_path / "cache"
    config, path = _numba_cache_of(_env(MOORLINE_CACHE_DIR=str(root))).split()
    expected = root / f"numba-{numba_cache.source_key(numba_cache.kernel_files())}"
    assert Path(config) == expected
    assert Path(path).parent == expected
    assert expected.is_dir()


def test_numba_imported_first_gets_the_directory_too(tmp_path: Path) -> None:
    root = tmp_path / "cache"
    config, path = _numba_cache_of(_env(MOORLINE_CACHE_DIR=str(root)),
                                   "import numba\nimport moorline.physics.fused").split()
    assert Path(config).parent == root
    assert Path(path).parent == Path(config)


def test_the_users_numba_cache_dir_is_kept(tmp_path: Path) -> None:
    mine = tmp_path / "mine"
    config, path = _numba_cache_of(_env(NUMBA_CACHE_DIR=str(mine),
                                        MOORLINE_CACHE_DIR=str(tmp_path / "cache"))).split()
    assert Path(config) == mine
    assert Path(path).parent == mine
    assert not (tmp_path / "cache").exists()


@pytest.mark.skipif(os.geteuid() == 0 if hasattr(os, "geteuid") else True,
                    reason="root writes anywhere")
def test_an_unwritable_cache_root_leaves_numbas_default(tmp_path: Path) -> None:
    locked = tmp_path / "locked"
    locked.mkdir(mode=0o500)
    config = _numba_cache_of(_env(MOORLINE_CACHE_DIR=str(locked / "cache"))).split()
    assert len(config) == 1  # CACHE_DIR empty: numba's __pycache__ next to the sources
    assert "__pycache__" in config[0]


def test_a_cache_root_that_is_a_file_leaves_numbas_default(tmp_path: Path) -> None:
    blocker = tmp_path / "file"
    blocker.write_text("not a directory", encoding="utf-8")
    config = _numba_cache_of(_env(MOORLINE_CACHE_DIR=str(blocker / "cache"))).split()
    assert len(config) == 1
    assert "__pycache__" in config[0]


def test_only_moorline_jit_imports_numba() -> None:
    """Every kernel module takes numba from :mod:`moorline.jit`, which chooses the cache
    directory first: a direct ``import numba`` would read ``NUMBA_CACHE_DIR`` too early."""
    direct = re.compile(r"^\s*(import numba\b|from numba\b)", re.MULTILINE)
    offenders = [str(path.relative_to(SRC)) for path in (SRC / "moorline").rglob("*.py")
                 if path.name != "jit.py" and direct.search(path.read_text(encoding="utf-8"))]
    assert offenders == []
