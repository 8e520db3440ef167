"""Shared test helpers."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import netCDF4
import pytest

#: Attributes every analysis group of a results file carries.
GROUP_ATTRS = ("analysis", "case", "units", "moorline_version", "success", "status", "message")


def _undescribed(path: Path) -> list[str]:
    """What a results file lacks: group attributes of :data:`GROUP_ATTRS`, and ``units`` or
    ``long_name`` of any variable or coordinate, in any group (read with netCDF4, not with
    moorline)."""
    missing: list[str] = []
    with netCDF4.Dataset(path) as root:
        assert root.groups, f"{path} has no groups"
        for name, group in root.groups.items():
            missing += [f"{name}: attribute {a}" for a in GROUP_ATTRS if a not in group.ncattrs()]
            for var_name, var in group.variables.items():
                missing += [f"{name}/{var_name}: {a}" for a in ("units", "long_name")
                            if not str(getattr(var, a, "")).strip()]
    return missing


@pytest.fixture
def undescribed() -> Callable[[Path], list[str]]:
    """``undescribed(path)``: the group attributes, ``units`` and ``long_name`` a results file
    lacks (empty when complete)."""
    return _undescribed
