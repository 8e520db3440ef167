"""What the command line imports before it needs it (issue 16: a process that starts fast).

Not a timing test: it checks which heavy modules are loaded, in a fresh interpreter, by
``moorline --help`` and by reading a case in plain SI numbers (pint only when a string carries
a unit; matplotlib, xarray, netCDF4, numba, scipy and dask only when an analysis uses them).
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
HEAVY = ("pint", "xarray", "matplotlib", "numba", "scipy", "netCDF4", "dask")


def _loaded_after(code: str) -> list[str]:
    probe = (f"import sys\n{code}\n"
             f"print(' '.join(m for m in {HEAVY!r} if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True,
                         check=True, cwd=ROOT, timeout=120)
    return out.stdout.split()


def test_help_imports_no_heavy_module() -> None:
    assert _loaded_after("from moorline.cli import cli") == []


@pytest.mark.skipif(not (ROOT / "cases" / "oc3_line.yaml").is_file(), reason="no case file")
def test_reading_an_si_case_without_unit_strings_does_not_import_pint() -> None:
    loaded = _loaded_after("from moorline.io.case import load_case\n"
                           "load_case('cases/oc3_line.yaml')")
    assert "pint" not in loaded


@pytest.mark.skipif(not (ROOT / "cases" / "oc3_line.yaml").is_file(), reason="no case file")
def test_reading_a_case_does_not_import_scipy_interpolate() -> None:
    loaded = _loaded_after("from moorline.io.case import load_case\n"
                           "load_case('cases/oc3_line.yaml')\n"
                           "assert 'scipy.interpolate' not in sys.modules")
    assert "pint" not in loaded


def test_writing_results_does_not_import_dask_distributed(tmp_path: Path) -> None:
    code = ("import numpy as np, xarray as xr\n"
            "from moorline.io.writers import write_group\n"
            f"write_group(xr.Dataset({{'a': ('x', np.ones(3))}}), {str(tmp_path / 'r.nc')!r}, "
            "'statics')\n"
            "assert 'distributed' not in sys.modules")
    _loaded_after(code)


def test_a_unit_string_still_converts() -> None:
    from moorline.io.units import default_value, to_system

    assert to_system("20 ft", "length", "SI") == pytest.approx(6.096, rel=1e-12)
    assert default_value("gravity", "US") == pytest.approx(9.80665 / 0.3048, rel=1e-12)
    assert default_value("water_density", "SI") == 1025.0


def test_compiled_kernels_counts_cache_misses(monkeypatch: pytest.MonkeyPatch) -> None:
    """Reads numba's dispatcher statistics: misses are compilations in this process."""
    import types
    from collections import Counter

    from moorline import kernel_cache

    def dispatcher(misses: int, hits: int) -> types.SimpleNamespace:
        stats = types.SimpleNamespace(cache_path="/cache", cache_misses=Counter({"sig": misses}),
                                      cache_hits=Counter({"sig": hits}))
        return types.SimpleNamespace(stats=stats, py_func=lambda: None)

    fake = types.ModuleType("fake_kernels")
    fake.a, fake.b, fake.other = dispatcher(1, 0), dispatcher(0, 2), 3
    monkeypatch.setattr(kernel_cache, "KERNEL_MODULES", ("fake_kernels", "not_loaded"))
    monkeypatch.setitem(sys.modules, "fake_kernels", fake)
    assert kernel_cache.compiled_kernels() == (1, "/cache")
    fake.a = dispatcher(0, 1)
    assert kernel_cache.compiled_kernels()[0] == 0
