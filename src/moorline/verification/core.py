"""Verification rows and the registry of verification cases.

A row checks one quantity against a reference of a named kind and has one of three outcomes:
``pass``, ``fail`` or ``not reproduced``. A row is ``not reproduced`` when the case declares
that the source's result is not obtained (lost data, a doubt about the source, a model
difference); its note says why, it never counts as passed and it does not fail the suite.
"""

from __future__ import annotations

import importlib
import inspect
import math
from collections.abc import Callable
from dataclasses import dataclass

#: Kinds of reference a row may compare with.
#: ``exact``: a closed-form or independently integrated solution of the same equations;
#: ``published``: a number printed in a source (cite it in ``source``);
#: ``other code``: MoorPy, MoorDyn or another independent program run on the same input;
#: ``internal cross-check``: moorline against moorline by another path (another method,
#: another mesh or analysis); counted and printed apart, since it cannot show a shared error.
REFERENCE_KINDS = ("exact", "published", "other code", "internal cross-check")

#: Row outcomes.
STATUSES = ("pass", "fail", "not reproduced")


class CaseSkipped(Exception):  # noqa: N818 (a skip, not an error)
    """Raised by a case that cannot run here (an optional extra is missing); says why."""


@dataclass(frozen=True)
class Row:
    """One checked quantity of a verification case.

    Parameters
    ----------
    case, quantity
        The case name and what is checked.
    reference, computed
        The reference value and moorline's value.
    tolerance
        Allowed error: ``|computed - reference| <= tolerance`` when ``relative`` is False,
        ``<= tolerance * |reference|`` when True.
    kind
        The reference's kind, one of :data:`REFERENCE_KINDS` (required).
    source
        Where the reference comes from ("Tuah (1982) Table 6.3", "MoorPy 1.1", "eq. 4.2.9").
    reproduced
        False when the case declares the source's result not reproduced; ``note`` says why.
    """

    case: str
    quantity: str
    reference: float
    computed: float
    tolerance: float
    relative: bool = True
    unit: str = ""
    note: str = ""
    kind: str = ""
    source: str = ""
    reproduced: bool = True

    def __post_init__(self) -> None:
        if self.kind not in REFERENCE_KINDS:
            raise ValueError(f"verification row {self.case!r} / {self.quantity!r}: kind "
                             f"{self.kind!r} is not one of {', '.join(REFERENCE_KINDS)}")
        if not self.reproduced and not self.note:
            raise ValueError(f"verification row {self.case!r} / {self.quantity!r}: a row "
                             "declared not reproduced must say why in its note")

    @property
    def error(self) -> float:
        """Absolute error, or relative error when ``relative``."""
        diff = abs(self.computed - self.reference)
        if self.relative:
            return diff / abs(self.reference) if self.reference != 0 else math.inf
        return diff

    @property
    def within_tolerance(self) -> bool:
        """Whether the computed value lies within the tolerance of the reference."""
        return bool(math.isfinite(self.computed) and self.error <= self.tolerance)

    @property
    def status(self) -> str:
        """``pass``, ``fail`` or ``not reproduced`` (see the module docstring)."""
        if not self.reproduced:
            return "not reproduced"
        return "pass" if self.within_tolerance else "fail"

    @property
    def passed(self) -> bool:
        """Whether the row passed (a not-reproduced row never counts as passed)."""
        return self.status == "pass"

    def to_dict(self) -> dict:
        """Plain dict for JSON output: ``reference`` is ``{value, kind, source}``."""
        return {
            "case": self.case, "quantity": self.quantity,
            "reference": {"value": self.reference, "kind": self.kind, "source": self.source},
            "computed": self.computed, "tolerance": self.tolerance, "relative": self.relative,
            "unit": self.unit, "error": self.error, "status": self.status,
            "passed": self.passed, "note": self.note,
        }


@dataclass(frozen=True)
class Case:
    """A registered verification case: its name and ``"module:function"``."""

    name: str
    target: str


#: Verification cases by name. Modules are imported lazily so that one broken case does not
#: hide the others.
CASES: dict[str, Case] = {}


def register(name: str, target: str) -> None:
    """Register a case ``name`` implemented by ``"module:function"`` (module relative to here).

    The function returns ``list[Row]``; it may take a keyword ``quick`` (a shorter run with a
    representative row of each check) and may raise :class:`CaseSkipped`.
    """
    CASES[name] = Case(name, target)


def case_function(name: str) -> Callable[..., list[Row]]:
    """The callable that runs case ``name``."""
    module_name, func = CASES[name].target.split(":")
    module = importlib.import_module(f"moorline.verification.{module_name}")
    return getattr(module, func)


def run_case(name: str, quick: bool = False) -> list[Row]:
    """Run case ``name`` (``quick`` when the case has a quick form) and return its rows."""
    func = case_function(name)
    if quick and "quick" in inspect.signature(func).parameters:
        return func(quick=True)
    return func()


def run_cases(names: list[str] | None = None, quick: bool = False) -> list[Row]:
    """Run the named cases (all when ``None``) and return all their rows; skipped cases give
    no rows."""
    rows: list[Row] = []
    for name in names or list(CASES):
        try:
            rows.extend(run_case(name, quick))
        except CaseSkipped:
            continue
    return rows
