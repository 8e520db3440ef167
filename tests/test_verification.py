"""Every verification case passes (each row: computed vs reference within its stated
tolerance). Long cases run in `make verify` (marker ``slow``); their quick versions are tested
in their own test modules."""

import pytest

from moorline.verification import CASES, run_cases

SLOW = {"wang-w2", "wang-w3", "tuah-ex5", "tuah-ex7", "tuah-ex6", "tuah-ex7-lift"}


@pytest.mark.parametrize(
    "case", [pytest.param(c, marks=pytest.mark.slow) if c in SLOW else c for c in sorted(CASES)])
def test_verification_case_passes(case):
    rows = run_cases([case])
    assert rows, f"{case} produced no rows"
    failed = [r for r in rows if not r.passed]
    assert not failed, "\n".join(
        f"{r.quantity}: reference {r.reference:.6g}, computed {r.computed:.6g}, "
        f"error {r.error:.3g} > {r.tolerance:.3g}" for r in failed)


def test_foundation_cases_are_registered():
    assert {"tuah-ex1", "tuah-ex2", "tcheou-t1", "oc3-line"} <= set(CASES)
