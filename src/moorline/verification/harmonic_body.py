"""Harmonic balance with bodies and viscoelastic lines against closed forms (issue 15).

Two systems whose periodic response is known exactly, so that the harmonic-balance solver
(:mod:`moorline.solvers.harmonic`) is checked against algebra, not against itself:

* **a body on linear springs** (:func:`spring_body`): a 6-dof body with a constant heave
  hydrostatic stiffness (``kind: matrix``), added mass and linear damping, held by four
  vertical weightless taut lines (axial springs ``EA / L`` for heave: vertical lines stay
  vertical in pure heave, so the spring is exactly linear while taut), under a harmonic
  heave force ``F sin(w t)``. Steady state ``z = Im(F e^{i w t} / (k - (m + A) w^2 + i B w))``
  with ``k = K33 + 4 EA / L``. The frequency-dependent variant gives the body a
  :class:`~moorline.model.RadiationTable` whose ``A(w)``, ``B(w)`` differ at every tabulated
  frequency and are tabulated at the forcing frequency itself (the reference reads the table
  there, no interpolation enters it);
* **the body in a regular wave** (:func:`wave_body`): the same body without the force,
  excited by an exciting-force table (``F = a |X| cos(w t + phase)`` at its origin, the
  lines weightless and without drag, so the table is the only wave load):
  ``z = Re(a |X| e^{i phase} e^{i w t} / (k - (m + A) w^2 + i B w))``;
* **a mass on a viscoelastic bar** (:func:`sls_oscillator`): a point mass at the end of one
  weightless standard-linear-solid element in air, pretensioned by a constant force along the
  element and forced harmonically along it. The strain is linear in the motion, so the
  equation is exactly ``m u'' + (EA + EA1 i w tau / (1 + i w tau)) / L0 u = F sin(w t)``
  (Tuah 1982 eq. 2.2.b.2 as a complex modulus) at any amplitude that keeps the bar taut.

Every row is ``exact``: first-harmonic amplitude and phase of the solver against the closed
form. Tolerance 1e-6 relative: the solver's Newton tolerance is 1e-8 of the load scale and the
systems are linear (the higher harmonics vanish), so round-off and the Newton stop are the
only differences (a wrong mass, damping, radiation or Maxwell term changes the numbers by
percent).
"""

from __future__ import annotations

import cmath
import math
from dataclasses import replace

import numpy as np

from ..model import (
    Body,
    Environment,
    HarmonicSettings,
    Hydrostatics,
    Line,
    LineType,
    Motion,
    Point,
    RadiationTable,
    System,
    WaveExcitation,
    Waves,
)
from ..solvers.harmonic import solve_harmonic
from .core import Row

CASE = "harmonic-body"

# the body on springs (SI)
MASS, ADDED, DAMPING, K_HEAVE = 2.0e4, 5.0e3, 3.0e4, 4.0e5  # kg, kg, N s/m, N/m
EA, LENGTH, STRETCH = 2.0e6, 50.0, 1e-3  # N, m, pretension strain of the four lines
FORCE = 5.0e3  # N: heave amplitude below 0.02 m, the lines' 0.05 m pretension stretch
# the mass on a viscoelastic bar (SI)
BAR_MASS, BAR_EA, BAR_EA1, BAR_TAU, BAR_L0 = 50.0, 2.0e6, 3.0e6, 0.05, 2.0
BAR_PRELOAD, BAR_FORCE = 2.0e4, 5.0e3  # N: strain 1e-2 static, 2.5e-3 dynamic (taut)


def heave_stiffness() -> float:
    """``K33 + 4 EA / L`` [N/m]."""
    return K_HEAVE + 4 * EA / LENGTH


def radiation_table(omega: float) -> RadiationTable:
    """A heave radiation table with ``A(w)``, ``B(w)`` different at each of its frequencies
    ``(0.25, 0.5, 1, 2, 4) w`` (the forcing frequency ``w`` is one of them)."""
    omegas = tuple(omega * f for f in (0.25, 0.5, 1.0, 2.0, 4.0))
    added, damping = [], []
    for i in range(len(omegas)):
        a, b = np.zeros((6, 6)), np.zeros((6, 6))
        a[2, 2], b[2, 2] = ADDED * (0.6 + 0.3 * i), DAMPING * (1.5 - 0.2 * i)
        added.append(tuple(map(tuple, a)))
        damping.append(tuple(map(tuple, b)))
    return RadiationTable(omegas, tuple(added), tuple(damping))


def spring_body(omega: float, radiation: bool = False, force: float = FORCE) -> System:
    """The body on four vertical taut lines and a heave hydrostatic spring, forced in heave
    at ``omega`` (constant ``A``, ``B``, or a :func:`radiation_table`)."""
    rope = LineType("rope", diameter=0.05, mass_per_length=0.0, EA=EA, displaced_area=0.0,
                    Cd=0.0, Ca=0.0, Ct=0.0)
    stiffness = np.diag([1e5, 1e5, K_HEAVE, 1e7, 1e7, 1e7])
    hydro = {}
    if radiation:
        hydro["radiation"] = radiation_table(omega)
    else:
        added, damping = np.zeros((6, 6)), np.zeros((6, 6))
        added[2, 2], damping[2, 2] = ADDED, DAMPING
        hydro = {"added_mass": tuple(map(tuple, added)),
                 "damping": tuple(map(tuple, damping))}
    pretension = 4 * EA * STRETCH
    body = Body("b", mass=MASS, inertia=((1e5, 0, 0), (0, 1e5, 0), (0, 0, 1e5)),
                hydrostatics=Hydrostatics("matrix", stiffness=tuple(map(tuple, stiffness)),
                                          volume=(MASS * 9.81 + pretension) / (1025 * 9.81)),
                force_history=Motion("harmonic", amplitude=(0.0, 0.0, force),
                                     period=2 * math.pi / omega), **hydro)
    points, lines = {}, {}
    for k, (x, y) in enumerate([(2, 2), (-2, 2), (-2, -2), (2, -2)]):
        points[f"p{k}"] = Point(f"p{k}", "body", (x, y, 0.0), body="b")
        points[f"a{k}"] = Point(f"a{k}", "fixed", (x, y, -LENGTH * (1 + STRETCH)))
        lines[f"l{k}"] = Line(f"l{k}", "rope", LENGTH, 2, f"a{k}", f"p{k}")
    return System("harmonic-spring-body", environment=Environment(water_density=1025.0,
                                                                  gravity=9.81),
                  line_types={"rope": rope}, points=points, lines=lines, bodies={"b": body})


def heave_response(omega: float, radiation: bool = False) -> complex:
    """``z / F`` of the body: ``1 / (k - (m + A) w^2 + i B w)`` (``A``, ``B`` read off the
    radiation table at ``w`` in the frequency-dependent variant)."""
    if radiation:
        table = radiation_table(omega)
        added, damping = table.added_mass[2][2][2], table.damping[2][2][2]
    else:
        added, damping = ADDED, DAMPING
    return 1.0 / (heave_stiffness() - (MASS + added) * omega**2 + 1j * damping * omega)


EXCITING, EXCITING_PHASE, WAVE_AMPLITUDE = 3.0e4, 40.0, 0.2  # N/m, deg, m


def wave_body(omega: float) -> System:
    """:func:`spring_body` in a regular Airy wave of amplitude ``WAVE_AMPLITUDE`` (100 m of
    water), excited by a heave exciting-force table tabulated at ``(0.5, 1, 2) w`` (other
    values off the forcing frequency) instead of the force history."""
    system = spring_body(omega, force=0.0)
    table = WaveExcitation(
        (0.5 * omega, omega, 2.0 * omega),
        ((0, 0, 1e4, 0, 0, 0), (0, 0, EXCITING, 0, 0, 0), (0, 0, 5e4, 0, 0, 0)),
        ((0,) * 6, (0, 0, EXCITING_PHASE, 0, 0, 0), (0, 0, -20.0, 0, 0, 0)))
    body = replace(system.bodies["b"], excitation=table, force_history=None)
    env = replace(system.environment, depth=100.0,
                  waves=Waves("airy", height=2 * WAVE_AMPLITUDE, period=2 * math.pi / omega))
    return replace(system, name="harmonic-wave-body", environment=env, bodies={"b": body})


def wave_heave(omega: float) -> complex:
    """The complex amplitude ``c`` of ``Im(c e^{i w t})`` of the body's heave in
    :func:`wave_body`: ``Re(C e^{i w t}) = Im(i C e^{i w t})``, ``C = a |X| e^{i phase}
    / (k - (m + A) w^2 + i B w)``."""
    C = WAVE_AMPLITUDE * EXCITING * cmath.exp(1j * math.radians(EXCITING_PHASE)) * \
        heave_response(omega)
    return 1j * C


def sls_oscillator(omega: float, force: float = BAR_FORCE) -> System:
    """A point mass on one weightless viscoelastic element along ``x`` in air, pretensioned
    by ``BAR_PRELOAD`` and forced by ``force sin(w t)`` along the element."""
    bar = LineType("bar", diameter=0.01, mass_per_length=0.0, EA=BAR_EA, displaced_area=0.0,
                   Cd=0.0, Ca=0.0, Ct=0.0, material="viscoelastic", EA1=BAR_EA1, tau=BAR_TAU)
    stretched = BAR_L0 * (1 + BAR_PRELOAD / BAR_EA)
    points = {"wall": Point("wall", "fixed", (0.0, 0.0, 0.0)),
              "mass": Point("mass", "free", (stretched, 0.0, 0.0), mass=BAR_MASS,
                            force=(BAR_PRELOAD, 0.0, 0.0),
                            force_history=Motion("harmonic", amplitude=(force, 0.0, 0.0),
                                                 period=2 * math.pi / omega))}
    return System("harmonic-sls-bar", environment=Environment(water_density=0.0, gravity=0.0),
                  line_types={"bar": bar}, points=points,
                  lines={"bar": Line("bar", "bar", BAR_L0, 1, "wall", "mass")})


def sls_response(omega: float) -> complex:
    """``u / F`` of the mass on the bar: ``1 / (k(w) - m w^2)``, ``k(w) = (EA + EA1 i w tau
    / (1 + i w tau)) / L0`` (Tuah 1982 eq. 2.2.b.2 for ``eps = Re(e exp(i w t))``)."""
    s = 1j * omega * BAR_TAU
    return 1.0 / ((BAR_EA + BAR_EA1 * s / (1 + s)) / BAR_L0 - BAR_MASS * omega**2)


def first_harmonic(coefficients: np.ndarray) -> complex:
    """The complex amplitude ``c`` of ``Im(c e^{i w t})`` from the cosine and sine
    coefficients ``(mean, a1, b1, ...)``: ``a cos + b sin = Im((b + i a) e^{i w t})``."""
    return complex(coefficients[2], coefficients[1])


def _rows(name: str, computed: complex, exact: complex, unit: str, note: str) -> list[Row]:
    phase = math.degrees(cmath.phase(computed) - cmath.phase(exact))
    phase = (phase + 180.0) % 360.0 - 180.0
    return [Row(CASE, f"{name}: first-harmonic amplitude", abs(exact), abs(computed), 1e-6,
                unit=unit, kind="exact", note=note),
            Row(CASE, f"{name}: phase error", 0.0, phase, 1e-4, relative=False, unit="deg",
                kind="exact", note=note)]


def run(quick: bool = False) -> list[Row]:
    """Rows: body heave (constant and frequency-dependent radiation) and the viscoelastic
    bar, below and above resonance (quick: one frequency each)."""
    rows: list[Row] = []
    w_body = math.sqrt(heave_stiffness() / (MASS + ADDED))
    ratios = (0.7,) if quick else (0.7, 1.4)
    for radiation in (False, True):
        for ratio in ratios:
            omega = ratio * w_body
            result = solve_harmonic(spring_body(omega, radiation),
                                    HarmonicSettings(period=2 * math.pi / omega, harmonics=3))
            z = first_harmonic(result.body_coefficients[:, 0, 2]) / FORCE
            label = "radiation table" if radiation else "constant A, B"
            rows += _rows(f"body heave, {label}, w/w_n {ratio}", z,
                          heave_response(omega, radiation), "m/N",
                          "closed form 1 / (k - (m + A) w^2 + i B w)")
    omega = 0.8 * w_body
    result = solve_harmonic(wave_body(omega), HarmonicSettings(period=2 * math.pi / omega,
                                                               harmonics=3))
    rows += _rows("body heave in a regular wave, exciting-force table, w/w_n 0.8",
                  first_harmonic(result.body_coefficients[:, 0, 2]), wave_heave(omega), "m",
                  "closed form a |X| e^{i phase} / (k - (m + A) w^2 + i B w)")
    w_bar = math.sqrt((BAR_EA + BAR_EA1) / BAR_L0 / BAR_MASS)
    for ratio in ratios:
        omega = ratio * w_bar
        system = sls_oscillator(omega)
        result = solve_harmonic(system, HarmonicSettings(period=2 * math.pi / omega,
                                                         harmonics=3))
        node = result.mesh.point_node[result.mesh.point_index("mass")]
        u = first_harmonic(result.coefficients[:, node, 0]) / BAR_FORCE
        rows += _rows(f"viscoelastic bar, w/w_0 {ratio}", u, sls_response(omega), "m/N",
                      "complex modulus EA + EA1 i w tau / (1 + i w tau)")
    return rows
