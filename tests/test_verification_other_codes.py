"""The other-code verification cases (``[compare]`` extra): every row of their quick forms
passes and compares with another code (MoorPy, MoorDyn); the full forms are slow."""

import pytest

from moorline.verification import core

pytestmark = pytest.mark.compare


def _check(rows: list[core.Row], not_reproduced: tuple[str, ...] = ()) -> None:
    """Every row compares with another code and passes, except the named rows the case
    declares not reproduced (with a reason)."""
    assert rows
    for row in rows:
        assert row.kind == "other code", row
        if any(name in row.quantity for name in not_reproduced):
            assert row.status == "not reproduced" and row.note, row
            continue
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
    _check(rows, not_reproduced=("pull first-harmonic phase",))
    quantities = " ".join(r.quantity for r in rows)
    for part in ("OC3 surge", "first-harmonic", "cross current", "side force",
                 "dragged on the seabed"):
        assert part in quantities


@pytest.mark.slow
def test_moordyn_dynamics_full_rows_pass():
    pytest.importorskip("moordyn")
    _check(core.run_case("moordyn-dynamics"), not_reproduced=("pull first-harmonic phase",))


def test_moordyn_body_quick_rows_pass():
    pytest.importorskip("moordyn")
    rows = core.run_case("moordyn-body", quick=True)
    _check(rows)
    quantities = " ".join(r.quantity for r in rows)
    for part in ("surge first-harmonic", "heave", "pitch", "hawser", "leg 1"):
        assert part in quantities


def test_moordyn_body_deck_quick_rows_pass():
    pytest.importorskip("moordyn")
    rows = core.run_case("moordyn-body-deck", quick=True)
    _check(rows)
    quantities = " ".join(r.quantity for r in rows)
    for part in ("platform deck (10 el.): equilibrium heave", "tension at the anchor",
                 "tension at the fairlead", "free-decay period", "spar deck (10 el.)"):
        assert part in quantities


def test_moordyn_deck_writes_the_body_and_its_points(tmp_path):
    from moorline.io.moordyn import write_moordyn
    from moorline.verification.moordyn_body import buoy_system

    text = write_moordyn(buoy_system(), tmp_path / "deck.dat", 0.0025).read_text()
    body_row = next(line for line in text.splitlines() if line.endswith("# buoy"))
    fields = body_row.split()
    # ID Attachment X0 Y0 Z0 r0 p0 y0 Mass CG I Volume CdA Ca
    assert fields[1] == "Free" and float(fields[4]) == -40.0 and float(fields[8]) == 20000.0
    assert fields[9] == "0.0|0.0|-2.0" and fields[10] == "400000.0|400000.0|200000.0"
    assert float(fields[11]) == 60.0 and float(fields[13]) == pytest.approx(0.5)
    leg = next(line for line in text.splitlines() if line.endswith("# leg1"))
    assert leg.split()[1:5] == ["Body1", "-2.0", "0.0", "-2.5"]


def test_moordyn_deck_refuses_a_body_it_cannot_express(tmp_path):
    import dataclasses

    from moorline.errors import CaseError
    from moorline.io.moordyn import write_moordyn
    from moorline.verification.moordyn_body import buoy_system

    system = buoy_system()
    body = dataclasses.replace(system.bodies["buoy"], force=(1.0, 0, 0, 0, 0, 0))
    with pytest.raises(CaseError, match="constant force"):
        write_moordyn(dataclasses.replace(system, bodies={"buoy": body}), tmp_path / "d.dat",
                      0.0025)


def test_cases_skip_without_the_extra(monkeypatch):
    import builtins

    real_import = builtins.__import__

    def no_compare(name, *args, **kwargs):
        if name.split(".")[0] in ("moorpy", "moordyn"):
            raise ImportError(name)
        return real_import(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", no_compare)
    for name in ("moorpy-statics", "moordyn-dynamics", "moordyn-body", "moordyn-body-deck"):
        with pytest.raises(core.CaseSkipped, match=r"\[compare\] extra"):
            core.run_case(name, quick=True)
