"""What the command line imports before it needs it (issue 16: a process that starts fast).

Not a timing test: it checks which heavy modules are loaded, in a fresh interpreter, by
``moorline --help``, by reading a case in plain SI numbers (pint only when a string carries
a unit; matplotlib, xarray, netCDF4, numba, scipy and dask only when an analysis uses them), by
``moorline statics --json`` and by ``moorline run --no-plots`` (results written from numpy
with netCDF4, summaries from the results in memory: no xarray, pandas or dask; numba only for
the compiled time step; matplotlib only when plotting; rich only when something is shown).
"""

from __future__ import annotations

import os
import re
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


def _loaded_by_cli(*args: str, names: tuple[str, ...] = (*HEAVY, "pandas")) -> set[str]:
    """The modules of ``names`` (by default :data:`HEAVY` and pandas) loaded after ``moorline
    ARGS`` ran in a fresh interpreter (exit code 0 required)."""
    code = (f"import sys\nsys.argv = ['moorline', *{list(args)!r}]\n"
            "from moorline.cli import main\n"
            "try:\n    main()\nexcept SystemExit as exc:\n    assert not exc.code, exc.code\n"
            f"print('LOADED', *(m for m in {names!r} if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         cwd=ROOT, timeout=900)
    assert out.returncode == 0, out.stderr
    return set(out.stdout.rsplit("LOADED", 1)[1].split())


def test_help_command_imports_no_heavy_module() -> None:
    assert _loaded_by_cli("--help") == set()


def test_help_imports_neither_rich_nor_pydantic() -> None:
    """rich only when something is shown with it (a table, a spinner, a progress bar);
    pydantic only to read a case."""
    assert _loaded_by_cli("--help", names=("rich", "pydantic", "yaml", "numpy")) == set()


@pytest.mark.skipif(not (ROOT / "cases" / "oc3_line.yaml").is_file(), reason="no case file")
def test_statics_json_writes_results_without_xarray_or_plots(tmp_path: Path) -> None:
    """netCDF4 (results.nc), nothing else heavy: no plots with --json; no scipy (a small
    system's Newton steps and condensed stiffness solved dense by numpy)."""
    loaded = _loaded_by_cli("statics", "cases/oc3_line.yaml", "--json", "-q",
                            "--out", str(tmp_path))
    assert loaded == {"netCDF4"}
    assert (tmp_path / "oc3-line" / "results.nc").is_file()
    assert not list((tmp_path / "oc3-line").glob("*.png"))


@pytest.mark.skipif(not (ROOT / "cases" / "oc3_dynamics.yaml").is_file(), reason="no case file")
def test_run_without_plots_needs_neither_xarray_nor_matplotlib(tmp_path: Path) -> None:
    """Statics and 1 s of dynamics of the OC3 three lines: numba (the compiled step) and
    netCDF4, scipy's bare package only (numba imports it to check its version: no
    ``scipy.sparse``, ``scipy.linalg``: the statics of so small a system is solved dense by
    numpy, the band ordering is moorline's); with plots (here of a statics), matplotlib too
    (and xarray, which the plots read)."""
    case = tmp_path / "short.yaml"
    text = (ROOT / "cases" / "oc3_dynamics.yaml").read_text(encoding="utf-8")
    case.write_text(re.sub(r"duration: *[0-9.]+", "duration: 1", text), encoding="utf-8")
    loaded = _loaded_by_cli("run", str(case), "--no-plots", "-q", "--out", str(tmp_path),
                            names=(*HEAVY, "pandas", "scipy.sparse", "scipy.linalg", "rich"))
    assert loaded == {"scipy", "netCDF4", "numba"}
    assert not list((tmp_path / "oc3-dynamics").glob("*.png"))
    plotted = _loaded_by_cli("statics", "cases/oc3_line.yaml", "-q", "--out",
                             str(tmp_path / "plots"))
    assert {"matplotlib", "xarray"} <= plotted
    assert list((tmp_path / "plots" / "oc3-line").glob("*.png"))


@pytest.mark.skipif(not (ROOT / "cases" / "oc3_dynamics.yaml").is_file(), reason="no case file")
def test_cached_kernels_load_without_numba_compiler_registries(tmp_path: Path) -> None:
    """A second run loads the compiled kernels from numba's cache without refreshing numba's
    compiler context (moorline.jit): its lowering registries (``numba.np.linalg``...)
    stay unimported, and so do the modules of numba's helpers compiled into the kernels
    (``numba.np.arrayobj``, ``numba.cpython.unicode``: their environments are rebuilt
    without them); the first run may have compiled them (a cold cache) and needed them.
    Both runs write the same summary."""
    case = tmp_path / "short.yaml"
    text = (ROOT / "cases" / "oc3_dynamics.yaml").read_text(encoding="utf-8")
    case.write_text(re.sub(r"duration: *[0-9.]+", "duration: 1", text), encoding="utf-8")
    names = ("numba", "numba.np.linalg", "numba.typed.typeddict", "numba.misc.gdb_hook",
             "numba.np.arrayobj", "numba.cpython.unicode", "numba.cpython.charseq")
    summaries = []
    for k in range(2):
        out = tmp_path / f"out{k}"
        loaded = _loaded_by_cli("run", str(case), "--no-plots", "-q", "--json", "--out",
                                str(out), names=names)
        summaries.append((out / "oc3-dynamics" / "summary.json").read_text(encoding="utf-8"))
    assert loaded == {"numba"}
    assert summaries[0] == summaries[1]


@pytest.mark.skipif(not (ROOT / "cases" / "oc3_dynamics.yaml").is_file(), reason="no case file")
def test_a_run_the_compiled_step_cannot_take_does_not_import_numba(tmp_path: Path) -> None:
    """Viscoelastic lines with the source's incremental update: the general stepper with the
    numpy kernels; deciding so does not load numba (moorline.solvers.fast_path)."""
    case = tmp_path / "visco.yaml"
    text = (ROOT / "cases" / "oc3_dynamics.yaml").read_text(encoding="utf-8")
    text = re.sub(r"duration: *[0-9.]+", "duration: 0.5, viscoelastic_update: incremental",
                  text)
    case.write_text(text.replace("    material: elastic",
                                 "    material: viscoelastic\n    EA1: 2.0e8\n    tau: 1.0"),
                    encoding="utf-8")
    loaded = _loaded_by_cli("run", str(case), "--no-plots", "-q", "--out", str(tmp_path))
    assert loaded == {"scipy", "netCDF4"}
    assert "viscoelastic" in case.read_text(encoding="utf-8")


@pytest.mark.skipif(not (ROOT / "cases" / "oc3_line.yaml").is_file(), reason="no case file")
def test_modes_writes_its_group_without_xarray(tmp_path: Path) -> None:
    """``modes --no-plots``: the modal group written from numpy with netCDF4 (scipy for the
    eigenvalues), no xarray, pandas or matplotlib."""
    loaded = _loaded_by_cli("modes", "cases/oc3_line.yaml", "--n", "3", "--no-plots", "--json",
                            "-q", "--out", str(tmp_path))
    assert loaded == {"scipy", "netCDF4"}
    assert (tmp_path / "oc3-line" / "results.nc").is_file()
    assert not list((tmp_path / "oc3-line").glob("*.png"))


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


def _threads_after(args: list[str], env: dict[str, str]) -> tuple[str, int]:
    """``OPENBLAS_NUM_THREADS`` and the number of threads of a fresh process after ``moorline
    ARGS`` ran in it (Linux: /proc/self/status)."""
    code = (f"import os, sys\nsys.argv = ['moorline', *{args!r}]\n"
            "from moorline.cli import main\n"
            "try:\n    main()\nexcept SystemExit as exc:\n    assert not exc.code, exc.code\n"
            "threads = [int(t.split()[1]) for t in open('/proc/self/status')"
            " if t.startswith('Threads:')][0]\n"
            "print('BLAS', os.environ.get('OPENBLAS_NUM_THREADS'), threads)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         cwd=ROOT, timeout=300, env=env)
    assert out.returncode == 0, out.stderr
    value, threads = out.stdout.rsplit("BLAS", 1)[1].split()
    return value, int(threads)


@pytest.mark.skipif(not Path("/proc/self/status").is_file(), reason="needs Linux /proc")
@pytest.mark.skipif(not (ROOT / "cases" / "oc3_line.yaml").is_file(), reason="no case file")
def test_a_command_runs_openblas_on_one_thread_unless_told(tmp_path: Path) -> None:
    """The statics process has one thread (no OpenBLAS pool started by numpy or scipy); a
    thread count the user set is kept."""
    from moorline.threads import THREAD_VARIABLES

    env = {k: v for k, v in os.environ.items() if k not in THREAD_VARIABLES}
    args = ["statics", "cases/oc3_line.yaml", "--json", "-q", "--out", str(tmp_path)]
    assert _threads_after(args, env) == ("1", 1)
    assert _threads_after(args, {**env, "OPENBLAS_NUM_THREADS": "2"})[0] == "2"


def test_one_blas_thread_leaves_an_imported_numpy_and_bem_alone(
        monkeypatch: pytest.MonkeyPatch) -> None:
    from moorline.threads import THREAD_VARIABLES, one_blas_thread

    for name in THREAD_VARIABLES:  # set, then removed: restored as they were afterwards
        monkeypatch.setenv(name, "0")
        monkeypatch.delenv(name)
    assert "numpy" in sys.modules  # pytest imported it: OpenBLAS is loaded already
    assert not one_blas_thread("statics")
    monkeypatch.delitem(sys.modules, "numpy")
    assert not one_blas_thread("bem")
    assert "OPENBLAS_NUM_THREADS" not in os.environ
    assert one_blas_thread("statics")
    assert os.environ["OPENBLAS_NUM_THREADS"] == "1"


def test_lean_loading_only_on_tested_numba_versions():
    """The cache-loading shortcut keys on numba's (major, minor); a version string it cannot
    read falls outside the tested range (numba then loads as it always does)."""
    from moorline import jit

    assert jit._version("0.68.1") == (0, 68)
    assert jit._version("0.59.0rc1") == (0, 59)
    assert jit._version("dev") == (0, 0)
    low, high = jit._TESTED_NUMBA
    assert low <= jit._version("0.68.1") < high
    assert not low <= jit._version("dev") < high
