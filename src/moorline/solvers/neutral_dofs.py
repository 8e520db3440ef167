"""Body dofs nothing resists in a static solve: a free-floating buoy's surge, sway and yaw, or
every dof of a rod with no line on it.

A dof is *neutral* when its row of the reduced body stiffness (the lines condensed out,
:func:`moorline.solvers.coupled_statics.reduced_stiffness`, without regularization) is zero:
no small motion of any body changes the force there. With no force there either, the dof is
held where the case puts it and the others are balanced (OrcaFlex reports such dofs as free
of stiffness; a Newton step with them held is the minimum-norm step of the singular
system). With a force there, the system has no static equilibrium: the body would move
without bound (a rod sinking with nothing to hold it) and the statics says so, naming the
body, the dof and the force, instead of iterating.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]

DOF_NAMES = ("surge", "sway", "heave", "roll", "pitch", "yaw")

#: A stiffness row is zero when every entry is at most this fraction of the largest entry of
#: the reduced body stiffness (round-off of the condensation; a real stiffness is far larger).
RELATIVE_ZERO = 1e-9


@dataclass(frozen=True)
class NeutralDofs:
    """The neutral dofs of a coupled statics.

    Attributes
    ----------
    held
        Mask over the unknowns (lines, then six per body): the neutral dofs without force.
    names
        ``"<body> <dof>"`` of each held dof.
    unbalanced
        ``(body, dof, force)`` of each neutral dof with an out-of-balance force above the
        tolerance (force or moment in the case's units).
    """

    held: NDArray[np.bool_]
    names: list[str] = field(default_factory=list)
    unbalanced: list[tuple[str, str, float]] = field(default_factory=list)

    def held_note(self) -> str:
        """The message part naming the held dofs ("" when none)."""
        if not self.names:
            return ""
        return (f"; held at the case's pose (no restoring and no force): "
                f"{', '.join(self.names)}")

    def no_equilibrium(self) -> str:
        """The message of a system without static equilibrium ("" when it may have one)."""
        if not self.unbalanced:
            return ""
        parts = [f"body {b} has no restoring in {d} and an out-of-balance "
                 f"{'force' if DOF_NAMES.index(d) < 3 else 'moment'} of {f:.4g} there"
                 for b, d, f in self.unbalanced]
        return ("no static equilibrium: " + "; ".join(parts)
                + " (it would move without bound; a dynamics analysis with start: initial "
                  "runs from the case's pose)")


def find_neutral(stiffness: FloatArray, residual: FloatArray, body_dof: NDArray[np.int64],
                 n_free: int, free: list[bool], names: list[str],
                 tolerance: float) -> NeutralDofs:
    """The neutral dofs of the free bodies.

    Parameters
    ----------
    stiffness
        Reduced body stiffness (n_body_unknowns square), unregularized.
    residual
        Out-of-balance forces of the body unknowns (n_body_unknowns,).
    body_dof
        First unknown of every body (-1: not solved for); ``n_free`` line unknowns before.
    free
        Per body: whether its six dofs are all solved for (a free body).
    names
        Body names.
    tolerance
        Out-of-balance force below which a neutral dof counts as balanced.
    """
    largest = float(np.abs(stiffness).max(initial=0.0))
    zero_row = np.abs(stiffness).max(axis=1, initial=0.0) <= RELATIVE_ZERO * largest
    held = np.zeros(n_free + len(residual), dtype=bool)
    held_names: list[str] = []
    unbalanced: list[tuple[str, str, float]] = []
    for b, first in enumerate(body_dof):
        if first < 0 or not free[b]:
            continue
        for k in range(6):
            j = first - n_free + k
            if not zero_row[j]:
                continue
            if abs(residual[j]) > tolerance:
                unbalanced.append((names[b], DOF_NAMES[k], float(residual[j])))
            else:
                held[first + k] = True
                held_names.append(f"{names[b]} {DOF_NAMES[k]}")
    return NeutralDofs(held, held_names, unbalanced)
