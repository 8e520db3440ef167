"""The table of analysis kinds: for each kind a case may list, its settings, case-file model,
runner, result type, plots and summary.

Everything that dispatches on a kind reads :data:`KINDS`: the case-file schema (the union of
``analyses[i]`` models, :mod:`moorline.io.schema`), the case loader (spec to settings,
:mod:`moorline.io.case`), ``moorline run`` (:mod:`moorline.runners`), ``moorline plot``,
``moorline modes`` and ``sweep``. A new kind is one row here plus its settings class, its
case-file model, its runner, result, plot and summary functions.

The settings classes are held directly (:mod:`moorline.model` imports nothing else); the other
members are ``"module:name"`` references resolved on use, so that reading a case file does not
import the solvers or matplotlib.
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass, field
from typing import Any

from .model.analysis import (
    DynamicsSettings,
    ExtremesSettings,
    FatigueSettings,
    HarmonicSettings,
    ModalSettings,
    OffsetSettings,
    StaticsSettings,
    StochasticSettings,
    StrummingSettings,
)

__all__ = ["KINDS", "AnalysisKind", "kind_of", "resolve"]


def resolve(reference: str) -> Any:
    """The object a ``"package.module:name"`` reference names."""
    module, _, name = reference.partition(":")
    return getattr(importlib.import_module(module), name)


@dataclass(frozen=True)
class AnalysisKind:
    """One analysis kind.

    Attributes
    ----------
    name
        The ``kind`` of ``analyses[i]`` in a case file, the NetCDF group name.
    settings
        Its settings class (:mod:`moorline.model.analysis`).
    spec
        Name of its case-file model in :mod:`moorline.io.schema`.
    runner
        ``(settings, context, label) -> Outcome`` of ``moorline run``
        (:mod:`moorline.runners`).
    result
        Its result class (:mod:`moorline.results`).
    plot
        ``(dataset, directory, prefix) -> list[Path]``: its plots (:mod:`moorline.plot`).
    summary
        ``(result) -> dict``: its part of the ``--json`` summary (:mod:`moorline.summaries`).
    unit_defaults
        Settings whose case-file default depends on the unit system: field -> key of
        :data:`moorline.io.units.DEFAULTS`.
    """

    name: str
    settings: type
    spec: str
    runner: str
    result: str
    plot: str
    summary: str
    unit_defaults: dict[str, str] = field(default_factory=dict)

    def spec_model(self) -> type:
        """The case-file model class."""
        return resolve(f"moorline.io.schema:{self.spec}")

    def run(self, settings: Any, context: Any, label: str) -> Any:
        """Run the analysis into a run context (see :mod:`moorline.runners`)."""
        return resolve(self.runner)(settings, context, label)

    def plot_group(self, dataset: Any, directory: Any, prefix: str = "") -> list:
        """Draw the plots of a dataset of this kind; returns the files written."""
        return resolve(self.plot)(dataset, directory, prefix)

    def summarize(self, result: Any) -> dict[str, Any]:
        """The summary of a result of this kind."""
        return resolve(self.summary)(result)

    def result_type(self) -> type:
        """The result class."""
        return resolve(self.result)


def _kind(name: str, settings: type, spec: str, result: str, **defaults: str) -> AnalysisKind:
    return AnalysisKind(name, settings, spec, runner=f"moorline.runners:run_{name}",
                        result=f"moorline.results:{result}",
                        plot=f"moorline.plot:plot_{name}_group",
                        summary=f"moorline.summaries:{name}_summary", unit_defaults=defaults)


#: Every analysis kind, in the order the documentation lists them.
KINDS: dict[str, AnalysisKind] = {k.name: k for k in (
    _kind("statics", StaticsSettings, "StaticsSpec", "StaticResult",
          damping="relaxation_damping", pseudo_dt="pseudo_dt"),
    _kind("dynamics", DynamicsSettings, "DynamicsSpec", "DynamicResult"),
    _kind("modal", ModalSettings, "ModalSpec", "ModalResult"),
    _kind("strumming", StrummingSettings, "StrummingSpec", "StrummingResult",
          viscosity="viscosity"),
    _kind("stochastic", StochasticSettings, "StochasticSpec", "StochasticResult"),
    _kind("harmonic", HarmonicSettings, "HarmonicSpec", "HarmonicResult"),
    AnalysisKind("fatigue", FatigueSettings, "FatigueSpec", runner="moorline.runners:run_fatigue",
                 result="moorline.fatigue_analysis:FatigueResult",
                 plot="moorline.plot:plot_fatigue_group",
                 summary="moorline.summaries:fatigue_summary"),
    AnalysisKind("extremes", ExtremesSettings, "ExtremesSpec",
                 runner="moorline.runners:run_extremes",
                 result="moorline.extremes_analysis:ExtremesResult",
                 plot="moorline.plot:plot_extremes_group",
                 summary="moorline.summaries:extremes_summary"),
    AnalysisKind("offset", OffsetSettings, "OffsetSpec", runner="moorline.runners:run_offset",
                 result="moorline.offset_result:OffsetResult",
                 plot="moorline.offset_plot:plot_offset_group",
                 summary="moorline.summaries:offset_summary"),
)}


def kind_of(settings: Any) -> AnalysisKind | None:
    """The kind of an analysis settings object (by its ``kind``), ``None`` if unknown."""
    return KINDS.get(str(getattr(settings, "kind", "")))
