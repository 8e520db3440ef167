"""A free rigid body against MoorDyn v2's body (``[compare]`` extra).

The system (:func:`buoy_system`): a submerged buoy, a free six-degree-of-freedom body (60 m^3,
20 t, centre of gravity 2 m below its reference point, inertia 4e5, 4e5, 2e5 kg m^2 about it,
added mass ``0.5 rho V`` in translation), 40 m below the surface in 150 m of water, held by two
wire legs (182 m each, from body points (-+2, 0, -2.5) m to anchors at x = -+150 m on the
seabed) and pulled by a wire hawser (203 m, from the body point (2, 0, 0) m to a vessel
fairlead at (200, 0, -10) m). Wire: 0.08 m, 40 kg/m, EA 600 MN, fixed internal damping
BA = 1e6 N s, Cd 1.2, Ca 1, Ct 0.008. The vessel fairlead surges 2 m at 15 s (ramped over
15 s): the hawser drives the buoy in surge, heave and pitch. MoorDyn's body is written by
:func:`moorline.io.moordyn.write_moordyn` (:mod:`moorline.io.moordyn_bodies`). MoorDyn applies
a body's buoyancy at its centre of gravity, so the buoy's centre of buoyancy is put there in
both codes (the buoy's pitch is then restored by its lines alone).

MoorDyn's initial-condition solve stalls with a free body (residual 0.5 m/s^2): it is first
run with the vessel still (60 s; quick 30 s) and its time is shifted by that; moorline starts
from its static equilibrium. Checked over t in [45, 90] s (three periods): the body's mean
surge, heave and pitch, the amplitudes of their first harmonics (15 s) and the phase of the
surge; the first-harmonic amplitude and the max of the hawser tension at the vessel; the
first-harmonic amplitude of leg 1's tension at its anchor.

Meshes and steps: 20 segments a line in both; moorline dt 0.05 s (quick 0.1 s: the rows
change by < 0.05 %), MoorDyn dtM 0.05/20 s. Differences, moorline minus MoorDyn, at 20 / 40
segments (MoorDyn 0.05/160 s at 40; moorline's dt 0.025 s changes nothing at 20): body
amplitudes surge -0.54 / -0.17 %, heave -0.60 / -0.21 %, pitch -0.65 / +0.01 %; surge phase
0.07 / 0.01 deg; means: surge 2e-4 / 6e-5 m, heave 4e-4 / 2e-4 m, pitch 2e-5 / 3e-5 rad;
hawser tension at the vessel: amplitude -1.70 / -1.64 %, max -0.55 / -0.55 %; leg 1 at the
anchor: amplitude -0.3 %. Tolerances: body amplitudes 1 %, phase 1 deg, means 5 mm and
1 mrad (3 % of the amplitudes), tensions 3 % (the converged 1.64 % of the hawser, as the
converged 1 % of the OC3 first harmonic in ``moordyn-dynamics``: a line-model difference).

Not compared: the hawser tension at the body. There the codes differ by 3.8 % in amplitude
and 2.6 deg in phase at 20 and 40 segments alike, while the body motions agree to 0.6 %.
MoorDyn's reported end-node forces at the body (``GetLineNodeForce``) do not balance its
own body motion: their sum on the body has a surge amplitude of 4.65 kN where the body's
inertia needs about 1.5 kN (moorline's sum, 1.40 kN, equals its body's mooring force); so the
reported force at a body-attached end is doubted, not moorline's.
"""

from __future__ import annotations

import logging
import math

import numpy as np

from ..model import (
    Body,
    DynamicsSettings,
    Environment,
    Hydrostatics,
    Line,
    LineType,
    Motion,
    Point,
    System,
)
from ..solvers.dynamics import simulate
from ..solvers.excitation import motion_value
from ..solvers.statics import solve_statics
from .core import CaseSkipped, Row
from .moordyn_dynamics import first_harmonic

CASE = "moordyn-body"
SOURCE = "MoorDyn-C 2.7.2 free body, same input"
RHO, G, DEPTH = 1025.0, 9.80665, 150.0
VOLUME, MASS, CG_Z, CA = 60.0, 20000.0, -2.0, 0.5
PERIOD = 15.0
MOTION = Motion("harmonic", amplitude=(2.0, 0.0, 0.0), period=PERIOD, ramp_time=15.0)
VESSEL = (200.0, 0.0, -10.0)
SEGMENTS, MD_DIVISOR, COUPLING = 20, 20, 0.05
DURATION, WINDOW = 90.0, (45.0, 90.0)
#: (moorline dt [s], MoorDyn still phase [s]): full and quick (dt 0.1 s changes the rows by
#: < 0.05 %; 30 s of still phase leave MoorDyn's body within 0.1 % of the 60 s one).
FULL, QUICK = (0.05, 60.0), (0.1, 30.0)
#: Tolerances: relative for amplitudes and tensions, absolute [m, rad, deg] for means/phase.
TOL = {"mean x": 0.005, "mean z": 0.005, "mean pitch": 0.001, "amplitude": 0.01,
       "phase": 1.0, "tension": 0.03}


def _import() -> None:
    try:
        import moordyn  # noqa: F401
    except ImportError as exc:
        raise CaseSkipped("the [compare] extra (moordyn) is not installed") from exc


def buoy_system(segments: int = SEGMENTS) -> System:
    """The moored submerged buoy (data in the module docstring)."""
    added = RHO * VOLUME * CA
    body = Body("buoy", "free", position=(0.0, 0.0, -40.0), mass=MASS,
                center_of_gravity=(0.0, 0.0, CG_Z),
                inertia=((4.0e5, 0.0, 0.0), (0.0, 4.0e5, 0.0), (0.0, 0.0, 2.0e5)),
                added_mass=tuple(map(tuple, np.diag([added, added, added, 0.0, 0.0, 0.0]))),
                hydrostatics=Hydrostatics("matrix", volume=VOLUME,
                                          center_of_buoyancy=(0.0, 0.0, CG_Z),
                                          stiffness=tuple(map(tuple, np.zeros((6, 6))))))
    wire = LineType("wire", diameter=0.08, mass_per_length=40.0, EA=600.0e6, Cd=1.2, Ca=1.0,
                    Ct=0.008, BA=1.0e6)
    points = {
        "anchor1": Point("anchor1", "fixed", (-150.0, 0.0, -DEPTH)),
        "anchor2": Point("anchor2", "fixed", (150.0, 0.0, -DEPTH)),
        "leg1": Point("leg1", "body", (-2.0, 0.0, -2.5), body="buoy"),
        "leg2": Point("leg2", "body", (2.0, 0.0, -2.5), body="buoy"),
        "hawser": Point("hawser", "body", (2.0, 0.0, 0.0), body="buoy"),
        "vessel": Point("vessel", "prescribed", VESSEL, motion=MOTION),
    }
    lines = {"leg1": Line("leg1", "wire", 182.0, segments, "anchor1", "leg1"),
             "leg2": Line("leg2", "wire", 182.0, segments, "anchor2", "leg2"),
             "hawser": Line("hawser", "wire", 203.0, segments, "hawser", "vessel")}
    env = Environment(depth=DEPTH, water_density=RHO, gravity=G)
    return System("moored-buoy", environment=env, line_types={"wire": wire}, points=points,
                  lines=lines, bodies={"buoy": body})


def delayed_vessel(settle: float):
    """The vessel fairlead held still for ``settle`` s, then moving as :data:`MOTION`:
    ``t -> (position, velocity)``."""
    base = np.asarray(VESSEL, dtype=float)

    def state(t: float) -> tuple[np.ndarray, np.ndarray]:
        if t < settle:
            return base, np.zeros(3)
        d, v, _ = motion_value(MOTION, t - settle)
        return base + d, v

    return state


def _histories(quick: bool) -> tuple[dict, dict]:
    """Body pose and line end tensions of both codes over the window: ``{quantity: (t, y)}``."""
    from ..compare.moordyn_runner import run_moordyn

    dt, settle = QUICK if quick else FULL
    system = buoy_system()
    ml = simulate(system, DynamicsSettings(duration=DURATION, dt=dt),
                  initial=solve_statics(system), output_every=COUPLING)
    if not ml.success:
        raise RuntimeError(f"moorline run failed: {ml.message}")
    # MoorDyn's stationary solve stalls near 0.5 m/s^2 with the free body (the runner warns);
    # the still phase brings it to equilibrium
    runner_log = logging.getLogger("moorline.compare.moordyn_runner")
    level = runner_log.level
    runner_log.setLevel(logging.ERROR)
    try:
        md = run_moordyn(system, settle + DURATION, COUPLING / MD_DIVISOR, COUPLING,
                         prescribed={"vessel": delayed_vessel(settle)})
    finally:
        runner_log.setLevel(level)
    if not md["success"]:
        raise RuntimeError(f"MoorDyn run failed: {md['message']}")
    lines = list(system.lines)

    def pick(time, pose, end_force):
        inside = (time >= WINDOW[0] - 1e-9) & (time < WINDOW[1] - 1e-9)
        tension = np.linalg.norm(end_force, axis=-1)
        # the ends away from the body (see the module docstring): the vessel's, the anchor's
        hawser = tension[:, lines.index("hawser"), 1]
        leg1 = tension[:, lines.index("leg1"), 0]
        return {"x": pose[:, 0], "z": pose[:, 2], "pitch": pose[:, 4], "hawser": hawser,
                "leg1": leg1, "time": time, "inside": inside}

    ml_h = pick(np.asarray(ml.time), ml.body_history("buoy"), np.asarray(ml.end_force))
    md_h = pick(np.asarray(md["time"]) - settle, np.asarray(md["body_state"]["buoy"]),
                np.asarray(md["end_force"]))
    return ml_h, md_h


def _stats(h: dict, key: str) -> tuple[float, float, float, float]:
    """Mean, first-harmonic amplitude and phase [deg], max of ``key`` over the window."""
    inside = h["inside"]
    y, t = h[key][inside], h["time"][inside]
    amplitude, phase = first_harmonic(t, y, PERIOD)
    return float(y.mean()), amplitude, phase, float(y.max())


def _row(quantity: str, ref: float, got: float, tol: str, unit: str,
         relative: bool = True) -> Row:
    return Row(CASE, quantity, ref, got, TOL[tol], relative=relative, unit=unit,
               kind="other code", source=SOURCE)


def run(quick: bool = False) -> list[Row]:
    """Body motion and line tensions of the moored buoy against MoorDyn."""
    _import()
    ml, md = _histories(quick)
    label = f"buoy ({SEGMENTS} el.)"
    rows = []
    for key, name, unit in (("x", "surge", "m"), ("z", "heave", "m"), ("pitch", "pitch", "rad")):
        m_ml, a_ml, p_ml, _ = _stats(ml, key)
        m_md, a_md, p_md, _ = _stats(md, key)
        rows.append(_row(f"{label}: mean {name}", m_md, m_ml, f"mean {key}", unit,
                         relative=False))
        rows.append(_row(f"{label}: {name} first-harmonic amplitude", a_md, a_ml, "amplitude",
                         unit))
        if key == "x":
            rows.append(_row(f"{label}: surge first-harmonic phase", p_md, p_ml, "phase",
                             "deg", relative=False))
    _, a_ml, _, max_ml = _stats(ml, "hawser")
    _, a_md, _, max_md = _stats(md, "hawser")
    rows += [_row(f"{label}: hawser tension at the vessel, first-harmonic amplitude", a_md,
                  a_ml, "tension", "N"),
             _row(f"{label}: max hawser tension at the vessel", max_md, max_ml, "tension",
                  "N")]
    _, a_ml, _, _ = _stats(ml, "leg1")
    _, a_md, _, _ = _stats(md, "leg1")
    rows.append(_row(f"{label}: leg 1 tension at the anchor, first-harmonic amplitude", a_md,
                     a_ml, "tension", "N"))
    assert all(math.isfinite(r.computed) for r in rows)
    return rows
