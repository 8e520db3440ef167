"""Natural frequencies of a taut string: transverse modes ``omega_n = n pi / L sqrt(T / m)``.

A weightless (gravity 0) horizontal string between two fixed points, span ``L = 100 m``,
tension ``T = 1e5 N`` set by the pretension (unstretched length ``L / (1 + T / EA)``),
``EA = 1e8 N``, mass ``m0 = 10 kg/m`` per unstretched length, diameter 0.1 m. The string's
mass per stretched length is ``m = m0 / (1 + T / EA)``; in water (``rho = 1025``,
``Ca = 1``) the transverse modes carry the added mass too, ``m -> (m0 + rho Ca pi d^2 / 4) /
(1 + T / EA)`` (the model's added mass is per unstretched length, like its structural mass).
Each ``omega_n`` is a pair of modes (polarizations y and z); the axial modes are far higher
(``pi / L sqrt(EA / m)`` = 31 times the first transverse one). Modes are picked by their
dominant direction.

With lumped mass and N elements the discrete string has exactly
``omega_n = (2 N / L) sqrt(T / m) sin(n pi / (2 N))``: an error ``-(n pi / N)^2 / 24``,
``O(h^2)``, which the convergence row measures (observed order from N = 40 to 80). The
consistent mass (Tuah 1982 eq. 3.1.12) errs by as much, from above (shown too).
"""

from __future__ import annotations

import math

import numpy as np

from ..model import Environment, Line, LineType, ModalSettings, Point, StaticsSettings, System
from ..results import ModalResult
from ..solvers.modal import solve_modes
from .core import Row

CASE = "modes-string"
REFERENCE = "taut string omega_n = n pi / L sqrt(T / m)"
SPAN, TENSION, EA, MASS, DIAMETER, CA, RHO = 100.0, 1.0e5, 1.0e8, 10.0, 0.1, 1.0, 1025.0
ELEMENTS = 50
N_MODES = 4
TOLERANCE = 5e-3


def string_system(elements: int = ELEMENTS, water_density: float = 0.0) -> System:
    """The pretensioned weightless string, in air (``water_density = 0``) or in water."""
    lt = LineType("string", diameter=DIAMETER, mass_per_length=MASS, EA=EA, Ca=CA, Cat=0.0,
                  Cd=0.0, Ct=0.0)
    points = {"left": Point("left", "fixed", (0.0, 0.0, 0.0)),
              "right": Point("right", "fixed", (SPAN, 0.0, 0.0))}
    line = Line("string", "string", SPAN / (1.0 + TENSION / EA), elements, "left", "right")
    env = Environment(water_density=water_density, gravity=0.0)
    return System(CASE, environment=env, line_types={"string": lt}, points=points,
                  lines={"string": line}, analyses=(StaticsSettings(start="straight"),))


def exact_frequency(n: int, water_density: float = 0.0) -> float:
    """``n pi / L sqrt(T / m)`` with ``m`` the (structural + added) mass per stretched length."""
    added = water_density * CA * math.pi * DIAMETER**2 / 4
    m = (MASS + added) / (1.0 + TENSION / EA)
    return n * math.pi / SPAN * math.sqrt(TENSION / m)


def transverse(result: ModalResult, direction: str, count: int) -> np.ndarray:
    """The lowest ``count`` frequencies of the modes dominated by ``direction``."""
    return result.omega[result.modes_of(direction)][:count]


def _modes(elements: int, water_density: float = 0.0, mass: str = "lumped") -> ModalResult:
    settings = ModalSettings(n_modes=2 * N_MODES + 2, mass=mass)  # type: ignore[arg-type]
    return solve_modes(string_system(elements, water_density), settings)


def _frequency_rows(label: str, result: ModalResult, water_density: float) -> list[Row]:
    rows = []
    y, z = transverse(result, "y", N_MODES), transverse(result, "z", N_MODES)
    for n in range(1, N_MODES + 1):
        exact = exact_frequency(n, water_density)
        pair = (float(y[n - 1]), float(z[n - 1]))
        worst = max(pair, key=lambda w: abs(w - exact))
        rows.append(Row(CASE, f"omega_{n} transverse, {label}", exact, worst, TOLERANCE,
                        unit="rad/s", note=f"y {pair[0]:.6g}, z {pair[1]:.6g} (worse shown); "
                        f"{ELEMENTS} elements", kind="exact", source=REFERENCE))
    return rows


def convergence_order(counts: tuple[int, ...] = (10, 20, 40, 80)) -> tuple[float, list[float]]:
    """Observed order of the first frequency's error between the two finest meshes, and the
    relative errors on all meshes (lumped mass, in air)."""
    exact = exact_frequency(1)
    errors = [abs(float(transverse(_modes(n), "y", 1)[0]) - exact) / exact for n in counts]
    order = math.log(errors[-2] / errors[-1]) / math.log(counts[-1] / counts[-2])
    return order, errors


def run() -> list[Row]:
    """Frequencies in air and in water (lumped mass), in air with consistent mass, and the
    mesh-convergence order of the first frequency."""
    rows = _frequency_rows("in air", _modes(ELEMENTS), 0.0)
    rows += _frequency_rows(f"in water (Ca = {CA:g})", _modes(ELEMENTS, RHO), RHO)
    rows += _frequency_rows("in air, consistent mass", _modes(ELEMENTS, mass="consistent"),
                            0.0)
    order, errors = convergence_order()
    rows.append(Row(CASE, "observed order of omega_1 error (lumped mass, N = 40 -> 80)", 2.0,
                    order, 0.05, relative=False,
                    note="errors at N = 10, 20, 40, 80: "
                    + ", ".join(f"{e:.2e}" for e in errors), kind="exact", source=REFERENCE))
    return rows
