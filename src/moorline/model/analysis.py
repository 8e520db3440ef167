"""Settings of each analysis a case asks for (frozen, no logic)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

StaticMethod = Literal["newton", "incremental", "relaxation"]


@dataclass(frozen=True)
class StaticsSettings:
    """Static analysis settings (Tuah 4.1).

    Attributes
    ----------
    method
        ``newton``: residual feedback with equilibrium iterations (Tuah eq. 4.1.2; one load
        step = Newton-Raphson) and a line search; ``incremental``: purely incremental loading
        (eq. 4.1.1), no equilibrium correction; ``relaxation``: viscous relaxation
        (eq. 4.1.5-4.1.8) with artificial damping ``C(t) = mu C(t - dt)``.
    load_steps
        Number of load increments (loads and prescribed displacements ramped linearly).
    tolerance
        Convergence tolerance on the residual force norm, relative to the load norm.
    max_iterations
        Iteration limit per load step (relaxation: total).
    stiffness_update
        Refresh the tangent every this many iterations (1 = full Newton).
    damping, damping_decrement, pseudo_dt
        Viscous relaxation: initial damping ``C0`` [force*time/length], ``mu`` and the pseudo
        time step [time].
    start
        Initial shape of the lines: ``catenary`` (closed form between the end positions) or
        ``straight`` (the chord).
    max_step
        Newton: largest node displacement per iteration, as a fraction of the longest line's
        unstretched length (longer steps are scaled down; a guard against slack starts).
    """

    kind: Literal["statics"] = "statics"
    method: StaticMethod = "newton"
    load_steps: int = 1
    tolerance: float = 1.0e-8
    max_iterations: int = 50
    stiffness_update: int = 1
    damping: float = 1.0e5
    damping_decrement: float = 0.5
    pseudo_dt: float = 1.0
    start: Literal["catenary", "straight"] = "catenary"
    max_step: float = 0.5


@dataclass(frozen=True)
class OutputSettings:
    """What to write: output interval of time histories [time]."""

    every: float = 0.1
