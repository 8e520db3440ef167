"""The other-code verification cases (``[compare]`` extra): every row of their quick forms
passes and compares with another code (MoorPy, MoorDyn); the full forms are slow."""

import pytest

from moorline.verification import core

pytestmark = pytest.mark.compare


def _check(rows: list[core.Row]) -> None:
    assert rows
    for row in rows:
        assert row.kind == "other code", row
        assert row.status == "pass", (row.quantity, row.reference, row.computed, row.error,
                                      row.tolerance)


def test_moorpy_statics_rows_pass():
    pytest.importorskip("moorpy")
    rows = core.run_case("moorpy-statics", quick=True)
    _check(rows)
    quantities = " ".join(r.quantity for r in rows)
    for part in ("OC3 line", "OC3 three lines", "K15 surge-pitch", "S-line: buoy z",
                 "S-line: clump x"):
        assert part in quantities


def test_moordyn_dynamics_quick_rows_pass():
    pytest.importorskip("moordyn")
    rows = core.run_case("moordyn-dynamics", quick=True)
    _check(rows)
    quantities = " ".join(r.quantity for r in rows)
    for part in ("OC3 surge", "first-harmonic", "cross current", "side force"):
        assert part in quantities


@pytest.mark.slow
def test_moordyn_dynamics_full_rows_pass():
    pytest.importorskip("moordyn")
    _check(core.run_case("moordyn-dynamics"))


def test_cases_skip_without_the_extra(monkeypatch):
    import builtins

    real_import = builtins.__import__

    def no_compare(name, *args, **kwargs):
        if name.split(".")[0] in ("moorpy", "moordyn"):
            raise ImportError(name)
        return real_import(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", no_compare)
    for name in ("moorpy-statics", "moordyn-dynamics"):
        with pytest.raises(core.CaseSkipped, match=r"\[compare\] extra"):
            core.run_case(name, quick=True)
