"""Every verification case passes (each row: computed vs reference within its stated
tolerance). Long cases run in `make verify` (marker ``slow``); their quick versions are tested
in their own test modules."""

import pytest

from moorline.verification import CASES

SLOW = {"wang-w2", "wang-w3", "tuah-ex5", "tuah-ex7", "tuah-ex6", "tuah-ex7-lift",
        # other codes ([compare] extra): quick forms in test_verification_other_codes.py
        "moorpy-statics", "moordyn-dynamics", "moordyn-body", "moordyn-body-deck"}


@pytest.mark.parametrize(
    "case", [pytest.param(c, marks=pytest.mark.slow) if c in SLOW else c for c in sorted(CASES)])
def test_verification_case_passes(case):
    from moorline.verification.core import CaseSkipped, run_case

    try:
        rows = run_case(case)
    except CaseSkipped as exc:  # an optional extra is missing (make verify installs them)
        pytest.skip(f"{case}: {exc}")
    assert rows, f"{case} produced no rows"
    failed = [r for r in rows if r.status == "fail"]
    assert not failed, "\n".join(
        f"{r.quantity}: reference {r.reference:.6g}, computed {r.computed:.6g}, "
        f"error {r.error:.3g} > {r.tolerance:.3g}" for r in failed)


def test_foundation_cases_are_registered():
    assert {"tuah-ex1", "tuah-ex2", "tcheou-t1", "oc3-line"} <= set(CASES)


def _row(computed, **kw):
    from moorline.verification.core import Row

    return Row("fake", kw.pop("quantity", "q"), 1.0, computed, 0.1, kind=kw.pop("kind", "exact"),
               **kw)


def test_row_status_is_pass_fail_or_not_reproduced():
    assert _row(1.05).status == "pass"
    assert _row(1.2).status == "fail"
    assert _row(float("nan")).status == "fail"
    missing = _row(1.05, reproduced=False, note="lost figure")
    assert missing.status == "not reproduced" and not missing.passed
    assert missing.to_dict()["reference"] == {"value": 1.0, "kind": "exact", "source": ""}


def test_row_needs_a_known_kind_and_a_reason_when_not_reproduced():
    with pytest.raises(ValueError, match="kind"):
        _row(1.0, kind="")
    with pytest.raises(ValueError, match="must say why"):
        _row(1.0, reproduced=False)


def _fake_cases(monkeypatch, rows_by_case):
    from moorline.verification import core

    def function(name):
        def run():
            rows = rows_by_case[name]
            if isinstance(rows, Exception):
                raise rows
            return rows
        return run

    monkeypatch.setattr(core, "CASES", {n: core.Case(n, "x:y") for n in rows_by_case})
    monkeypatch.setattr(core, "case_function", function)


def test_verify_exit_code_counts_only_failures(monkeypatch):
    import json

    from click.testing import CliRunner

    from moorline.cli import cli
    from moorline.verification.core import CaseSkipped

    cases = {"a": [_row(1.0), _row(1.05, reproduced=False, note="lost data")],
             "b": CaseSkipped("the [compare] extra is not installed")}
    _fake_cases(monkeypatch, cases)
    result = CliRunner().invoke(cli, ["verify"])
    assert result.exit_code == 0, result.output
    assert "1 pass, 0 fail, 1 not reproduced" in result.stderr
    assert "skipped b: the [compare] extra is not installed" in result.stderr
    assert "lost data" in result.stdout  # the reason is printed in its own section
    result = CliRunner().invoke(cli, ["verify", "--json", "--quiet"])
    assert [r["status"] for r in json.loads(result.stdout)] == ["pass", "not reproduced"]
    _fake_cases(monkeypatch, {"a": [_row(1.0), _row(2.0)]})
    result = CliRunner().invoke(cli, ["verify"])
    assert result.exit_code == 1
    assert "1 pass, 1 fail, 0 not reproduced" in result.stderr
