"""Verification rows and the registry of verification cases."""

from __future__ import annotations

import importlib
import math
from collections.abc import Callable
from dataclasses import asdict, dataclass


@dataclass(frozen=True)
class Row:
    """One checked quantity of a verification case.

    ``passed`` is computed: ``|computed - reference| <= tolerance`` when ``relative`` is False,
    ``|computed - reference| <= tolerance * |reference|`` when it is True.
    """

    case: str
    quantity: str
    reference: float
    computed: float
    tolerance: float
    relative: bool = True
    unit: str = ""
    note: str = ""

    @property
    def error(self) -> float:
        """Absolute error, or relative error when ``relative``."""
        diff = abs(self.computed - self.reference)
        if self.relative:
            return diff / abs(self.reference) if self.reference != 0 else math.inf
        return diff

    @property
    def passed(self) -> bool:
        """Whether the computed value lies within the tolerance of the reference."""
        return bool(math.isfinite(self.computed) and self.error <= self.tolerance)

    def to_dict(self) -> dict:
        """Plain dict for JSON output, including ``error`` and ``passed``."""
        out = asdict(self)
        out.update(error=self.error, passed=self.passed)
        return out


#: Verification cases: name -> "module:function" returning ``list[Row]``. Modules are imported
#: lazily so that one broken case does not hide the others.
CASES: dict[str, str] = {}


def register(name: str, target: str) -> None:
    """Register a case ``name`` implemented by ``"module:function"`` (module relative to here)."""
    CASES[name] = target


def case_function(name: str) -> Callable[[], list[Row]]:
    """The callable that runs case ``name``."""
    module_name, func = CASES[name].split(":")
    module = importlib.import_module(f"moorline.verification.{module_name}")
    return getattr(module, func)


def run_cases(names: list[str] | None = None) -> list[Row]:
    """Run the named cases (all when ``None``) and return all their rows."""
    rows: list[Row] = []
    for name in names or list(CASES):
        rows.extend(case_function(name)())
    return rows
