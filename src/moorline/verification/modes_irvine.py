"""Free vibrations of a shallow sagging cable: Irvine and Caughey (1974).

Reference: H. M. Irvine and T. K. Caughey (1974), "The linear theory of free vibrations of a
suspended cable", Proc. R. Soc. Lond. A 341, 299-315. For a cable hanging between supports at
the same level, span ``L``, static horizontal tension ``H``, mass ``m`` per unit length:

- out-of-plane (swinging) modes: ``omega_n = n pi / L sqrt(H / m)``;
- in-plane antisymmetric modes (no additional tension to first order):
  ``omega_n = 2 n pi / L sqrt(H / m)``;
- in-plane symmetric modes: ``omega = beta / L sqrt(H / m)`` with ``beta`` the roots of
  ``tan(beta / 2) = beta / 2 - (4 / lambda^2) (beta / 2)^3``,

with the cable parameter ``lambda^2 = (m g L / H)^2 L / (H L_e / EA_t)``, where
``L_e = integral_0^L (ds/dx)^3 dx ~ L (1 + 8 (d / L)^2)`` (``d = m g L^2 / (8 H)`` the sag of
the parabolic profile). At ``lambda^2 = 4 pi^2`` the first symmetric frequency crosses the
first antisymmetric one (``beta = 2 pi``); below it the first in-plane mode is symmetric,
above it antisymmetric.

Model: span 100 m, mass 1 kg/m per unstretched length, in air (``water_density = 0``),
``H = m0 g L^2 / (8 d)`` for a sag of 1/50 of the span, EA chosen (a root search) so that
``lambda^2`` is 1, ``4 pi^2`` (the crossover) and 100, unstretched length from the closed-form
elastic catenary between level supports,

    ``L = (2 H / w0) asinh(w0 L0 / (2 H)) + H L0 / EA``  (``w0 = m0 g``),

80 elements, lumped mass. The reference uses the exact quantities of that static state:
``m = m0 L0 / S`` per stretched length (``S`` the stretched arc length) and ``EA_t = EA + H``:
the model's law ``T = EA (l / L0 - 1)`` has ``dT / (dl / l) = EA l / L0 = EA + T``, the axial
stiffness with respect to strain on the current length that Irvine's ``EA`` stands for (the
same for small static strain; here the static strain is 2.5 % at ``lambda^2 = 1``).

Remaining modelling difference: the theory neglects the longitudinal inertia of in-plane
motion and treats the profile as a flat parabola (``ds ~ dx``); the finite element model does
neither. For the in-plane antisymmetric mode the horizontal motion carries about 0.6 % of the
kinetic energy at sag/span 1/50, which lowers its frequency by about 0.3 %, i.e.
``O((d / L)^2)`` (at sag/span 1/20 it is -1.6 %). Out-of-plane and symmetric modes differ by
< 0.1 %. The lumped-mass discretization error is ``-(k pi / N)^2 / 24`` for ``k``
half-waves: 0.03 % for the antisymmetric mode at N = 80.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

from ..model import Environment, Line, LineType, ModalSettings, Point, System
from ..results import ModalResult
from ..solvers.modal import solve_modes
from .core import Row

CASE = "modes-irvine"
REFERENCE = "Irvine & Caughey (1974), Proc. R. Soc. Lond. A 341"
SPAN, MASS, DIAMETER, GRAVITY = 100.0, 1.0, 0.012, 9.80665
SAG_RATIO = 1.0 / 50.0
ELEMENTS = 80
LAMBDA2 = (1.0, 4.0 * math.pi**2, 100.0)
TOLERANCE = 5e-3


def horizontal_tension() -> float:
    """``H = m0 g L^2 / (8 d)`` for the design sag ``d = L / 50``."""
    return MASS * GRAVITY * SPAN / (8.0 * SAG_RATIO)


def unstretched_length(H: float, EA: float) -> float:
    """Unstretched length of the elastic catenary with horizontal tension ``H`` over the span
    (supports level)."""
    w0 = MASS * GRAVITY

    def span(L0: float) -> float:
        return (2 * H / w0) * math.asinh(w0 * L0 / (2 * H)) + H * L0 / EA - SPAN

    return brentq(span, 0.5 * SPAN, 2.0 * SPAN, xtol=1e-14, rtol=4 * np.finfo(float).eps)


def stretched_length(H: float, EA: float, L0: float) -> float:
    """Arc length ``S = L0 + (1/EA) integral T ds0`` with ``T = sqrt(H^2 + (w0 u)^2)``."""
    w0, a = MASS * GRAVITY, 0.5 * L0
    integral = a * math.sqrt(H * H + (w0 * a) ** 2) + H * H / w0 * math.asinh(w0 * a / H)
    return L0 + integral / EA


def irvine_parameters(H: float, EA: float) -> dict[str, float]:
    """``lambda^2``, mass per stretched length, unstretched length and parabolic sag."""
    L0 = unstretched_length(H, EA)
    m = MASS * L0 / stretched_length(H, EA, L0)
    sag = m * GRAVITY * SPAN**2 / (8 * H)
    Le = SPAN * (1 + 8 * (sag / SPAN) ** 2)
    lambda2 = (m * GRAVITY * SPAN / H) ** 2 * SPAN / (H * Le / (EA + H))
    return {"lambda2": lambda2, "m": m, "L0": L0, "sag": sag}


def axial_stiffness_for(lambda2: float, H: float) -> float:
    """The EA that gives the cable parameter ``lambda2``."""
    return brentq(lambda EA: irvine_parameters(H, EA)["lambda2"] - lambda2, 1.0001 * H,
                  1e7 * H, rtol=1e-13)


def symmetric_beta(lambda2: float, n: int = 1) -> float:
    """n-th positive root of ``tan(beta/2) = beta/2 - (4/lambda^2)(beta/2)^3`` (Irvine and
    Caughey 1974): one root per branch of the tangent, ``beta/2`` in
    ``((2n - 1) pi/2, (2n + 1) pi/2)``."""

    def f(y: float) -> float:
        return math.tan(y) - y + 4.0 / lambda2 * y**3

    eps = 1e-12
    return 2.0 * brentq(f, (2 * n - 1) * math.pi / 2 + eps, (2 * n + 1) * math.pi / 2 - eps,
                        xtol=1e-15)


def theory(lambda2: float, H: float, m: float) -> dict[str, float]:
    """First out-of-plane, in-plane antisymmetric and in-plane symmetric frequencies."""
    base = math.sqrt(H / m) / SPAN
    return {"out-of-plane": math.pi * base, "in-plane antisymmetric": 2 * math.pi * base,
            "in-plane symmetric": symmetric_beta(lambda2) * base}


def cable_system(EA: float, L0: float, elements: int = ELEMENTS) -> System:
    """The cable in air between level fixed supports."""
    lt = LineType("cable", diameter=DIAMETER, mass_per_length=MASS, EA=EA)
    points = {"left": Point("left", "fixed", (0.0, 0.0, 0.0)),
              "right": Point("right", "fixed", (SPAN, 0.0, 0.0))}
    return System(CASE, environment=Environment(water_density=0.0, gravity=GRAVITY),
                  line_types={"cable": lt}, points=points,
                  lines={"cable": Line("cable", "cable", L0, elements, "left", "right")})


def classify(result: ModalResult) -> dict[str, int]:
    """Index of the first out-of-plane (y-dominated), in-plane antisymmetric and in-plane
    symmetric mode; in-plane symmetry from the vertical motion mirrored about midspan."""
    nodes = result.mesh.line_nodes[0]
    found: dict[str, int] = {}
    for k, direction in enumerate(result.dominant):
        if direction == "y":
            found.setdefault("out-of-plane", k)
            continue
        uz = result.mode_shapes[k, nodes, 2]
        symmetric = np.sum((uz + uz[::-1]) ** 2) / (4 * np.sum(uz**2))
        found.setdefault("in-plane symmetric" if symmetric > 0.5
                         else "in-plane antisymmetric", k)
    return found


def run() -> list[Row]:
    """FE frequencies vs Irvine-Caughey for lambda^2 = 1, 4 pi^2, 100, and the crossover."""
    rows = []
    H = horizontal_tension()
    for lambda2 in LAMBDA2:
        EA = axial_stiffness_for(lambda2, H)
        p = irvine_parameters(H, EA)
        result = solve_modes(cable_system(EA, p["L0"]), ModalSettings(n_modes=8))
        modes = classify(result)
        ref = theory(p["lambda2"], H, p["m"])
        label = "4 pi^2" if abs(lambda2 - 4 * math.pi**2) < 1e-9 else f"{lambda2:g}"
        for name, k in modes.items():
            share = result.participation[k]
            rows.append(Row(
                CASE, f"lambda^2 = {label}: first {name} omega", ref[name],
                float(result.omega[k]), TOLERANCE, unit="rad/s",
                note=f"mode {k + 1}; EA/H = {EA / H:.4g}, sag/span = {p['sag'] / SPAN:.4f}, "
                     f"{ELEMENTS} elements; x-share of kinetic energy {share[0]:.4f}",
                     kind="published", source=REFERENCE))
        if label == "4 pi^2":
            ratio = (result.omega[modes["in-plane symmetric"]]
                     / result.omega[modes["in-plane antisymmetric"]])
            rows.append(Row(CASE, "crossover at lambda^2 = 4 pi^2: omega_sym / omega_anti",
                            1.0, float(ratio), TOLERANCE,
                            note="equal in the theory; the FE antisymmetric mode is lowered "
                                 "by the longitudinal inertia the theory neglects",
                                 kind="published", source=REFERENCE))
    return rows
