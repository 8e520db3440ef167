"""Bending stiffness (EI): a tensioned beam in closed form, and a riser against MoorDyn-C.

The formulation is :mod:`moorline.physics.bending` (rotation-free, on the cable's nodes; line
ends pinned). Its bending moment is ``EI`` times the curvature per unstretched length (the
extensible rod's material curvature), so on the stretched line of strain ``eps = T / EA`` the
beam has ``EI (1 + eps)``, and the mass and weight per stretched length are the unstretched
ones over ``1 + eps``; the closed forms below carry those factors (``eps = 1e-3``).

(a) Beam-string statics: a horizontal line pinned at both ends, span ``L = 100 m``, tension
    ``T = 1e5 N`` set by the pretension (``EA = 1e8 N``), ``EI = 1e8 N m^2`` (so
    ``lambda L = L sqrt(T / EI) = 3.16``: bending and tension both carry the load), under its
    own weight ``q = 0.8 N/m`` (in air). ``EI w'''' - T w'' = q``, ``w = w'' = 0`` at the ends:

        w(x) = q EI / T^2 [cosh(lambda (x - L/2)) / cosh(lambda L / 2) - 1] + q x (L - x) / (2 T).

    Midspan deflection 5.15 mm (the string alone, ``q L^2 / 8 T``: 10 mm). The load is small
    (``w / L = 5e-5``) so the sag's extra tension is 1e-5 relative. Rows: the midspan
    deflection at 40 elements (its discretization error, O(h^2), is 2.3e-4 there; tolerance
    1e-3) and the observed order of the error from 10 to 20 to 40 elements (2 +- 0.1).
(b) Vibration of the same line without weight, ``m = 10 kg/m``: pinned-pinned beam-string
    ``omega_n^2 = k_n^2 (T + EI k_n^2) / m``, ``k_n = n pi / L``, n = 1..3 (80 elements: the
    O(h^2) error is 1.1e-3 at n = 3; tolerance 2e-3), and the beam (pretension 1 N, i.e.
    ``T / EI k_1^2 = 1e-5``, with no slack smoothing band so that the elements stay taut:
    ``omega_n -> k_n^2 sqrt(EI / m)``, the same formula with its T; tolerance 2e-3).
(c) Dynamics: the tensioned beam released from rest in its first mode shape (5 mm at
    midspan), 40 elements, Newmark (average acceleration) with 100 steps per period: the
    period of the midspan motion over three periods against ``2 pi / omega_1`` (tolerance
    1e-3: the mesh error 4e-4 and the step's period elongation ``(omega h)^2 / 12 = 3.3e-4``).
(d) Harmonic balance: the same line without weight, end B driven across by 1 mm at a
    1 s period (between the first two modes), one harmonic, 80 elements: the midspan
    amplitude against the closed-form steady state (:func:`driven_amplitude`); errors
    8.1e-3 and 2.0e-3 at 20 and 40 elements (O(h^2)); tolerance 2e-3.
(e) Cantilever (clamped end): 10 m, ``EI = 1e6 N m^2``, clamped along +x at a fixed root,
    a free tip point loaded by 100 N downwards (no weight; the tip tension ``P sin(theta)``
    stays 0.5 N, so the slack band is off): the tip deflection ``P L^3 / (3 EI)`` = 33.3 mm
    at 40 elements (error 3.0e-4, O(h^2): 5.0e-3 and 1.2e-3 at 10 and 20; tolerance 1e-3),
    and the observed order.
(f) Case ``bending-moordyn``: MoorDyn-C 2.7 (``[compare]`` extra; other code, same input
    through :func:`moorline.io.moordyn.write_moordyn`): a steel riser (diameter 0.3 m,
    150 kg/m, ``EA = 3e8 N``, ``EI = 5e7 N m^2``, length 118 m) pinned at an anchor point
    100 m below the surface and a top point 60 m away (chord 116.6 m), in water (depth 300 m,
    no seabed contact), 10 segments in both codes; the tension is positive everywhere (2e4 N
    at least: neither code's cable carries compression). MoorDyn's static state is its
    initial-condition solve (stationary scheme, 4000 s of pseudo-time, dtM 5 ms); MoorDyn's
    line ends at points are pinned too. Bending changes the anchor force by -58 % and the top
    force by -29 % (from ``EI = 0``); the codes differ by +0.012 % (anchor) and -0.032 %
    (top), the node positions by 0.46 mm; without EI the same pair differs by -0.007 %,
    -0.030 % and 0.46 mm. Model differences: MoorDyn's moment is ``EI kappa`` with ``kappa``
    on the stretched segments (moorline's ``EI kappa cos(theta / 2)`` per unstretched
    length), relative ``theta^2 / 8 + eps`` = 0.09 % here (turning angle up to 0.068 rad,
    strain up to 3e-4). Tolerances: 0.1 % on the end forces (that bound), 5 mm on the node
    positions (ten times the difference without EI).
(g) A riser in a current: the line of (a) stood vertical (foot 100 m below the top), in water
    (``rho = 1025``), neutrally buoyant (no weight, so the tension is uniform), diameter 0.3 m,
    ``Cd = 1.2``, no tangential drag, in a uniform 0.15 m/s current: the statics with the
    current's drag (``q = rho Cd D U^2 / 2 = 4.15 N/m``, normal to the riser to second order
    in its slope) against the same closed form; 40 elements (error 1.4e-4: the O(h^2) error
    and, the other way, the deflection's stretch, +1.8e-4 in tension; tolerance 1e-3).
"""

from __future__ import annotations

import dataclasses
import math
import tempfile
from pathlib import Path

import numpy as np

from ..model import (
    Current,
    DynamicsSettings,
    Environment,
    HarmonicSettings,
    Line,
    LineType,
    ModalSettings,
    Motion,
    Point,
    StaticsSettings,
    System,
)
from ..physics import bending
from ..solvers.dynamics import simulate
from ..solvers.harmonic import solve_harmonic
from ..solvers.modal import solve_modes
from ..solvers.statics import solve_statics
from .core import CaseSkipped, Row

CASE = "bending"
CASE_MOORDYN = "bending-moordyn"
BEAM = "pinned-pinned beam-string, closed form"
SPAN, TENSION, EA, EI, LOAD, MASS = 100.0, 1.0e5, 1.0e8, 1.0e8, 0.8, 10.0
EPS = TENSION / EA
#: the "untensioned" beam's pretension [N]: T / (EI k_1^2) = 1e-5, taut (no slack band)
BEAM_TENSION = 1.0
GRAVITY = 9.80665
STATIC_ELEMENTS, MODAL_ELEMENTS, DYNAMIC_ELEMENTS = 40, 80, 40
STEPS_PER_PERIOD = 200
HARMONIC_ELEMENTS, DRIVE, DRIVE_PERIOD, TOL_HARMONIC = 80, 1.0e-3, 1.0, 2e-3
CANTILEVER_LENGTH, CANTILEVER_EI, TIP_LOAD, CANTILEVER_ELEMENTS = 10.0, 1.0e6, 100.0, 40
WATER, RISER_D, RISER_CD, SPEED = 1025.0, 0.3, 1.2, 0.15
TOL_STATIC, TOL_ORDER, TOL_MODAL, TOL_PERIOD = 1e-3, 0.1, 2e-3, 1e-3
MOORDYN = "MoorDyn-C 2.7.2, same input"
RISER_SEGMENTS, RISER_EI, RISER_LENGTH, MOORDYN_DT = 10, 5.0e7, 118.0, 5.0e-3
TOL_FORCE, TOL_SHAPE = 1e-3, 5e-3


def beam_system(elements: int, EI_: float = EI, tension: float = TENSION, mass: float = MASS,
                gravity: float = 0.0) -> System:
    """The horizontal line pinned at both ends with pretension ``tension`` (in air)."""
    smoothing = 1.0e-5 if tension > BEAM_TENSION else 0.0
    lt = LineType("beam", diameter=0.1, mass_per_length=mass, EA=EA, Cd=0.0, Ca=0.0, Ct=0.0,
                  Cat=0.0, EI=EI_, slack_smoothing=smoothing)
    points = {"left": Point("left", "fixed", (0.0, 0.0, 0.0)),
              "right": Point("right", "fixed", (SPAN, 0.0, 0.0))}
    line = Line("beam", "beam", SPAN / (1.0 + tension / EA), elements, "left", "right")
    env = Environment(water_density=0.0, gravity=gravity)
    return System(CASE, environment=env, line_types={"beam": lt}, points=points,
                  lines={"beam": line}, analyses=(StaticsSettings(start="straight"),))


def beam_deflection(x: np.ndarray | float, tension: float = TENSION,
                    load: float = LOAD) -> np.ndarray | float:
    """Exact deflection of the pinned beam-string of span ``SPAN`` under a uniform ``load`` per
    unstretched length (module docstring), with the model's stretched-line factors."""
    eps = tension / EA
    ei, q = EI * (1.0 + eps), load / (1.0 + eps)
    lam = math.sqrt(tension / ei)
    return (q * ei / tension**2 * (np.cosh(lam * (x - SPAN / 2)) / math.cosh(lam * SPAN / 2)
                                   - 1.0) + q * x * (SPAN - x) / (2.0 * tension))


def beam_frequency(n: int, tension: float = TENSION) -> float:
    """Exact ``omega_n`` of the pinned beam-string (module docstring) [rad/s]."""
    eps = tension / EA
    k = n * math.pi / SPAN
    return k * math.sqrt((tension + EI * (1.0 + eps) * k * k) * (1.0 + eps) / MASS)


def _midspan_error(elements: int) -> tuple[float, float]:
    result = solve_statics(beam_system(elements, mass=LOAD / GRAVITY, gravity=GRAVITY))
    if not result.success:
        raise RuntimeError(f"beam statics failed: {result.message}")
    node = result.mesh.line_nodes[0][elements // 2]
    x = result.positions[node]
    return -float(x[2]), float(beam_deflection(x[0]))


def static_rows() -> list[Row]:
    """(a): midspan deflection and the observed convergence order."""
    got, exact = _midspan_error(STATIC_ELEMENTS)
    rows = [Row(CASE, f"midspan deflection under weight, {STATIC_ELEMENTS} elements", exact,
                got, TOL_STATIC, unit="m", kind="exact", source=BEAM,
                note=f"string alone {LOAD * SPAN**2 / (8 * TENSION):.4g} m; lambda L = "
                f"{SPAN * math.sqrt(TENSION / EI):.3g}")]
    counts = (10, 20, STATIC_ELEMENTS)
    errors = []
    for n in counts:
        g, e = _midspan_error(n)
        errors.append(abs(g - e) / e)
    order = math.log(errors[-2] / errors[-1]) / math.log(counts[-1] / counts[-2])
    rows.append(Row(CASE, f"observed order of the deflection error (N = {counts[1]} -> "
                    f"{counts[2]})", 2.0, order, TOL_ORDER, relative=False, kind="exact",
                    source=BEAM, note="errors at N = " + ", ".join(
                        f"{n}: {e:.2e}" for n, e in zip(counts, errors, strict=True))))
    return rows


def modal_rows(quick: bool = False) -> list[Row]:
    """(b): the first transverse frequencies, tensioned and untensioned."""
    rows = []
    n_modes = 2 if quick else 3
    for tension, label in ((TENSION, "T = 1e5 N"), (BEAM_TENSION, "beam, T = 1 N")):
        result = solve_modes(beam_system(MODAL_ELEMENTS, tension=tension),
                             ModalSettings(n_modes=2 * n_modes + 2, added_mass=False))
        if not result.success:
            raise RuntimeError(f"beam modes failed: {result.message}")
        omega = result.omega[result.modes_of("y")]
        for n in range(1, n_modes + 1):
            rows.append(Row(CASE, f"omega_{n} transverse, {label}, {MODAL_ELEMENTS} elements",
                            beam_frequency(n, tension), float(omega[n - 1]), TOL_MODAL,
                            unit="rad/s", kind="exact", source=BEAM))
    return rows


def dynamic_rows() -> list[Row]:
    """(c): the period of the first mode released from rest."""
    system = beam_system(DYNAMIC_ELEMENTS)
    statics = solve_statics(system)
    mesh = statics.mesh
    nodes = mesh.line_nodes[0]
    x0 = statics.positions.copy()
    s = x0[nodes, 0] / SPAN
    x0[nodes, 1] += 5e-3 * np.sin(math.pi * s)
    period = 2 * math.pi / beam_frequency(1)
    dt = period / STEPS_PER_PERIOD
    result = simulate(system, DynamicsSettings(duration=3.3 * period, dt=dt), initial=x0,
                      output_every=dt)
    if not result.success:
        raise RuntimeError(f"beam dynamics failed: {result.message}")
    y = np.asarray(result.positions)[:, nodes[DYNAMIC_ELEMENTS // 2], 1]
    t = np.asarray(result.time)
    crossings = _downward_crossings(t, y)
    got = float(np.mean(np.diff(crossings)))
    return [Row(CASE, f"first-mode period in dynamics, {DYNAMIC_ELEMENTS} elements", period,
                got, TOL_PERIOD, unit="s", kind="exact", source=BEAM,
                note=f"{len(crossings) - 1} periods, dt = T / {STEPS_PER_PERIOD} (Newmark)")]


def current_riser_system(elements: int) -> System:
    """The vertical riser of (g): neutrally buoyant, pinned at both ends, in a uniform
    current along +x."""
    lt = LineType("riser", diameter=RISER_D, mass_per_length=WATER * math.pi * RISER_D**2 / 4,
                  EA=EA, Cd=RISER_CD, Ca=1.0, Ct=0.0, Cat=0.0, EI=EI)
    points = {"foot": Point("foot", "fixed", (0.0, 0.0, -SPAN)),
              "top": Point("top", "fixed", (0.0, 0.0, 0.0))}
    line = Line("riser", "riser", SPAN / (1.0 + EPS), elements, "foot", "top")
    env = Environment(depth=2 * SPAN, water_density=WATER, current=Current(speed=SPEED))
    return System(CASE, environment=env, line_types={"riser": lt}, points=points,
                  lines={"riser": line},
                  analyses=(StaticsSettings(start="straight", current_drag=True),))


def current_riser_rows() -> list[Row]:
    """(g): midspan offset of the riser in the current."""
    result = solve_statics(current_riser_system(STATIC_ELEMENTS))
    if not result.success:
        raise RuntimeError(f"riser statics failed: {result.message}")
    x = result.positions[result.mesh.line_nodes[0][STATIC_ELEMENTS // 2]]
    load = 0.5 * WATER * RISER_CD * RISER_D * SPEED**2
    exact = float(beam_deflection(x[2] + SPAN, load=load))
    return [Row(CASE, f"riser in a {SPEED:g} m/s current: midspan offset, {STATIC_ELEMENTS} "
                "elements", exact, float(x[0]), TOL_STATIC, unit="m", kind="exact",
                source=BEAM, note=f"drag {load:.4g} N/m; string alone "
                f"{load * SPAN**2 / (8 * TENSION):.4g} m")]


def cantilever_system(elements: int) -> System:
    """The cantilever of (e): clamped at the root along +x, a free tip point loaded down."""
    lt = LineType("beam", diameter=0.1, mass_per_length=1.0, EA=1.0e9, Cd=0.0, Ca=0.0,
                  Ct=0.0, Cat=0.0, EI=CANTILEVER_EI, slack_smoothing=0.0)
    points = {"root": Point("root", "fixed", (0.0, 0.0, 0.0)),
              "tip": Point("tip", "free", (CANTILEVER_LENGTH, 0.0, 0.0),
                           force=(0.0, 0.0, -TIP_LOAD))}
    line = Line("beam", "beam", CANTILEVER_LENGTH, elements, "root", "tip",
                clamp_a=(1.0, 0.0, 0.0))
    env = Environment(water_density=0.0, gravity=0.0)
    return System(CASE, environment=env, line_types={"beam": lt}, points=points,
                  lines={"beam": line}, analyses=(StaticsSettings(start="straight"),))


def _tip_error(elements: int) -> tuple[float, float]:
    result = solve_statics(cantilever_system(elements))
    if not result.success:
        raise RuntimeError(f"cantilever statics failed: {result.message}")
    exact = TIP_LOAD * CANTILEVER_LENGTH**3 / (3.0 * CANTILEVER_EI)
    return -float(result.positions[result.mesh.point_index("tip"), 2]), exact


def cantilever_rows() -> list[Row]:
    """(e): tip deflection of the clamped cantilever and its convergence order."""
    counts = (10, 20, CANTILEVER_ELEMENTS)
    pairs = [_tip_error(n) for n in counts]
    errors = [abs(g - e) / e for g, e in pairs]
    order = math.log(errors[-2] / errors[-1]) / math.log(counts[-1] / counts[-2])
    source = "cantilever, P L^3 / (3 EI)"
    return [Row(CASE, f"cantilever tip deflection, clamped root, {CANTILEVER_ELEMENTS} "
                "elements", pairs[-1][1], pairs[-1][0], TOL_STATIC, unit="m", kind="exact",
                source=source),
            Row(CASE, f"observed order of the tip deflection error (N = {counts[1]} -> "
                f"{counts[2]})", 2.0, order, TOL_ORDER, relative=False, kind="exact",
                source=source, note="errors at N = " + ", ".join(
                    f"{n}: {e:.2e}" for n, e in zip(counts, errors, strict=True)))]


def driven_amplitude(period: float, amplitude: float = 1.0e-3) -> float:
    """Exact midspan amplitude of the weightless beam-string whose end B is driven across by
    ``amplitude sin(2 pi t / period)``, both ends pinned: ``EI w'''' - T w'' - m omega^2 w =
    0`` with ``w(0) = w''(0) = w''(L) = 0``, ``w(L) = Y`` gives
    ``w = Y [b^2 sinh(a x) / sinh(a L) + a^2 sin(b x) / sin(b L)] / (a^2 + b^2)``,
    ``a^2, -b^2 = (T +- sqrt(T^2 + 4 EI m omega^2)) / (2 EI)``."""
    ei, m = EI * (1.0 + EPS), MASS / (1.0 + EPS)
    w = 2 * math.pi / period
    root = math.sqrt(TENSION**2 + 4 * ei * m * w * w)
    a, b = math.sqrt((TENSION + root) / (2 * ei)), math.sqrt((root - TENSION) / (2 * ei))
    x = SPAN / 2
    return amplitude * (b * b * math.sinh(a * x) / math.sinh(a * SPAN)
                        + a * a * math.sin(b * x) / math.sin(b * SPAN)) / (a * a + b * b)


def harmonic_rows() -> list[Row]:
    """(d): the harmonic-balance steady state of the end-driven beam-string."""
    system = beam_system(HARMONIC_ELEMENTS)
    drive = Motion("harmonic", amplitude=(0.0, DRIVE, 0.0), period=DRIVE_PERIOD)
    right = dataclasses.replace(system.points["right"], kind="prescribed", motion=drive)
    system = dataclasses.replace(system, points={**system.points, "right": right})
    result = solve_harmonic(system, HarmonicSettings(period=DRIVE_PERIOD, harmonics=1))
    if not result.success:
        raise RuntimeError(f"beam harmonic balance failed: {result.message}")
    node = result.mesh.line_nodes[0][HARMONIC_ELEMENTS // 2]
    got = float(result.coefficients[2, node, 1])  # the sin(omega t) coefficient of y
    return [Row(CASE, f"harmonic balance: midspan amplitude, end driven {DRIVE * 1e3:g} mm at "
                f"{DRIVE_PERIOD:g} s, {HARMONIC_ELEMENTS} elements",
                driven_amplitude(DRIVE_PERIOD, DRIVE), got, TOL_HARMONIC, unit="m",
                kind="exact", source=BEAM,
                note="in opposition to the drive (between modes 1 and 2)")]


def _downward_crossings(t: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Times where ``y`` crosses zero downwards, linearly interpolated."""
    i = np.flatnonzero((y[:-1] > 0) & (y[1:] <= 0))
    return t[i] + (t[i + 1] - t[i]) * y[i] / (y[i] - y[i + 1])


def riser_system(EI_: float = RISER_EI, segments: int = RISER_SEGMENTS) -> System:
    """The riser of (f) (module docstring)."""
    lt = LineType("riser", diameter=0.3, mass_per_length=150.0, EA=3.0e8, Cd=1.0, Ca=1.0,
                  Ct=0.0, Cat=0.0, EI=EI_)
    points = {"anchor": Point("anchor", "fixed", (0.0, 0.0, -100.0)),
              "top": Point("top", "fixed", (60.0, 0.0, 0.0))}
    line = Line("riser", "riser", RISER_LENGTH, segments, "anchor", "top")
    return System("riser", environment=Environment(depth=300.0), line_types={"riser": lt},
                  points=points, lines={"riser": line},
                  analyses=(StaticsSettings(max_iterations=200),))


def moordyn_statics(system: System, dt: float = MOORDYN_DT, tmax_ic: float = 4000.0,
                    dt_ic: float = 2.0) -> dict:
    """MoorDyn's initial-condition (static) state of a system of fixed points and one line:
    ``positions`` of its nodes (n + 1, 3) and the ``end_force`` (2, 3) on its end nodes."""
    import moordyn

    from ..compare.moordyn_runner import silenced_fd
    from ..io.moordyn import write_moordyn

    with tempfile.TemporaryDirectory(prefix="moorline-bending-") as folder:
        deck = write_moordyn(system, Path(folder) / "riser.dat", dt, tmax_ic=tmax_ic,
                             thresh_ic=1e-7, extra_options={"dtIC": dt_ic})
        with silenced_fd(1):
            md = moordyn.Create(str(deck))
            try:
                moordyn.SetVerbosity(md, moordyn.LEVEL_ERR)
                status = moordyn.Init(md, [], [])
                if status:
                    raise RuntimeError(f"moordyn.Init failed with error code {status}")
                line = moordyn.GetLine(md, 1)
                n = moordyn.GetLineN(line)
                positions = np.array([moordyn.GetLineNodePos(line, i) for i in range(n + 1)])
                ends = np.array([moordyn.GetLineNodeForce(line, i) for i in (0, n)])
            finally:
                moordyn.Close(md)
    return {"positions": positions, "end_force": ends}


def moordyn_rows() -> list[Row]:
    """(f): the riser's end forces and shape against MoorDyn."""
    try:
        import moordyn  # noqa: F401
    except ImportError as exc:
        raise CaseSkipped("the [compare] extra (moordyn) is not installed") from exc
    system = riser_system()
    ml = solve_statics(system)
    if not ml.success:
        raise RuntimeError(f"riser statics failed: {ml.message}")
    md = moordyn_statics(system)
    nodes = ml.mesh.line_nodes[0]
    theta = float(bending.turning_angle(ml.positions, ml.mesh.bend_nodes).max())
    shape = float(np.linalg.norm(ml.positions[nodes] - md["positions"], axis=1).max())
    note = (f"{RISER_SEGMENTS} segments; largest turning angle {theta:.3f} rad; smallest "
            f"tension {float(ml.tension.min()):.4g} N; {ml.message}")
    rows = []
    for side, (end, label) in enumerate((("a", "anchor"), ("b", "top"))):
        ref = float(np.linalg.norm(md["end_force"][side]))
        got = float(np.linalg.norm(ml.end_force("riser", end)))
        rows.append(Row(CASE_MOORDYN, f"riser {label} force with EI", ref, got, TOL_FORCE, unit="N",
                        kind="other code", source=MOORDYN, note=note))
    rows.append(Row(CASE_MOORDYN, "riser node positions with EI, largest difference", 0.0, shape,
                    TOL_SHAPE, relative=False, unit="m", kind="other code", source=MOORDYN,
                    note=note))
    return rows


def run(quick: bool = False) -> list[Row]:
    """Case ``bending``: rows (a)-(e) and (g) of the module docstring; ``quick`` drops the third
    frequencies."""
    return (static_rows() + modal_rows(quick) + dynamic_rows() + harmonic_rows()
            + cantilever_rows() + current_riser_rows())


def run_moordyn(quick: bool = False) -> list[Row]:
    """Case ``bending-moordyn``: rows (f) (the same in the quick form: one MoorDyn run of a
    few seconds)."""
    return moordyn_rows()
