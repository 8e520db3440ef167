"""Tuah (1982) Example 5, deterministic part (sec. 6.5): a floating disc on one elastic leg.

The source: "a single linearly elastic cable attached to a floating disc at the water surface.
The static loads are a wind load of 100 pounds, the buoyant force, and the cable weight. The
cable is initially stretched from the bottom of the ocean to the position (300, 2.5)." A ten
foot, three second wave, ramped in as ``5 exp(-0.005/t)``; 3 and 8 elements; the incremental/
iterative Newmark method at dt = 0.02 s against residual feedback at dt = 0.005 s (stiffness
recomputed every five steps), which "gives false results and the solution is diverging ...
because of the small resistance to horizontal motion of the cable so that the incremental
displacement is no longer small". The response period is "slightly longer than the wave
period", the 8-element surge "slightly larger" than the 3-element one, and the heave shows
high-frequency spikes "because of the sudden release of the disc when the cable slackens".

The disc and cable data were in the lost Figure 6.5-1. US units throughout (ft, slug, s,
lbf); ``g = 32.174 ft/s^2``, sea water ``rho = 1.99 slug/ft^3``.

Reconstructed data (every choice and its reason)
------------------------------------------------
Geometry
    * Depth 200 ft (chosen; the source gives none). The anchor sits on the seabed at the
      origin of the plane; the source's "(300, 2.5)" is read as the fairlead 300 ft from the
      anchor horizontally and 2.5 ft below the still water level: the disc's keel, where the
      cable is shackled, at a 2.5 ft draft.
    * The cable is "initially stretched" along that chord: its unstretched length is the
      chord, ``L = sqrt(300^2 + 197.5^2) = 359.17 ft``; statics then lets it sag and the disc
      drift in until the cable's horizontal pull equals the wind.
Cable (Tuah's own cable data, Example 2, sec. 6.2: the only complete cable of the thesis)
    * ``A0 = 0.0218 ft^2`` (a 2.0 in volume-equivalent diameter), ``E = 8.12e6 psf``
      (``EA = 177,016 lbf``: a synthetic rope's modulus, like Ex6's 8.11e6 psf), density
      3.35 slug/ft^3: mass 0.0730 slug/ft, submerged weight 0.954 lbf/ft.
    * Morison coefficients ``Cd = 1.2``, ``Cm = 2`` (``Ca = 1``), ``Ct = 0.008`` (the package
      defaults, the usual values for a circular cylinder; the source's are lost).
    * With a 100 lbf horizontal pull the closed-form catenary has ``H / w = 105 ft``: the
      fairlead settles 256 ft from the anchor, 76 ft of cable lie on the seabed and the top
      is 70 deg steep (vertical pull 270 lbf). The horizontal stiffness is ~0.6 lbf/ft: the
      "small resistance to horizontal motion". The seabed is the package default
      (stiffness 3e6 Pa/m in US units); the source had no seabed model.
Disc (a discus buoy)
    * Diameter 10 ft, hull height 4 ft, draft 2.5 ft (from the fairlead reading above).
    * Mass: ballasted to float at that draft with the cable's static vertical pull (closed-
      form catenary): ``m = (rho g A_wp T - V_top) / g = 382.3 slug`` (12,300 lbf).
    * Centre of gravity 1.5 ft above the keel (hull and ballast low in the hull): metacentric
      height ``GM = KB + BM - KG = 1.25 + 2.5 - 1.5 = 2.25 ft``. Inertia about the centre of
      gravity: a uniform solid cylinder of the hull's size, ``m (3 R^2 + h^2) / 12`` in pitch
      and roll and ``m R^2 / 2`` in yaw (the source gives none).
    * Hydrostatics: linear (``kind: matrix``): buoyancy ``rho g A_wp T`` at the centre of
      buoyancy (1.25 ft below the water line), heave stiffness ``rho g A_wp = 5,027 lbf/ft``
      and the waterplane's ``rho g I_wp = 31,430 lbf ft/rad`` in roll and pitch (the
      buoyancy and weight moments come from their point loads). Linear, like the diffraction
      theory the source used: in this ten foot wave the disc heaves more than its draft.
    * Hydrodynamic coefficients. The source used Hudspeth's (1980) axisymmetric Green's
      function results for its disc. Their modern equivalent is a linear potential-flow
      panel code: added mass, radiation damping and exciting forces of the 10 ft x 2.5 ft
      cylinder at the wave frequency ``omega = 2.094 rad/s`` (``k R = 0.68``), depth 200 ft,
      waves along +x, were computed once with Capytaine 3.0 (2,304 panels; 1,216 panels
      differ by < 1 % in every value used; not a dependency, the numbers are stored below).
      Checks against standard results: ``A33 = 415.6 slug`` lies between the high-frequency
      (``rho D^3 / 6 = 332``) and zero-frequency (baffled piston, ``rho D^3 / 3 = 663``)
      limits of a floating disc; ``B33 = 308.2 lbf s/ft`` satisfies the deep-water Haskind
      relation ``B33 = omega^3 |X3|^2 / (2 rho g^3)`` to 2 % (a row below); the Froude-Krylov
      heave force equals ``rho g A_wp e^{-kT} 2 J1(kR)/(kR)`` to 0.3 %.
    * Reference point: the exciting pitch moment about the water line is, to 1e-5, the surge
      force times 0.332 ft (``X5 / X1`` is real): the wave force acts through the point 0.332
      ft above the still water level. The body frame origin is put there, so that the force
      history at the origin (all the package can apply: a force, no moment) carries the
      exciting moment too; the coefficients are about that point. About it the pitch
      radiation damping and its coupling vanish (Haskind: ``B_ij ~ Re X_i conj(X_j)``; the
      panel code gives |B15| < 8 and B55 ~ 0), so they are set to zero.
    * No viscous drag on the disc (the source's disc had diffraction forces only).
Loads
    * Wind 100 lbf along +x (down-wave) at the body origin.
    * The disc's wave force is the linear exciting force ``Re(X_j a e^{i(k x_b - w t)})`` at
      the disc's mean position ``x_b``, given as a force table (surge and heave have
      different phases; a harmonic force history has one phase for all components).
      The cable gets Airy kinematics (Morison) from the environment's wave.
    * Ramp: ``5 exp(-0.005/t)`` reaches 95 % of the amplitude at t = 0.1 s, a thirtieth of
      a period: in effect a step. A smooth ``(1 - cos(pi t / T_r)) / 2`` ramp over three wave
      periods (9 s) is used for the cable kinematics and the disc's force alike, so that
      the start-up transient is small (the pitch mode about the force centre has no
      radiation damping).

What is checked (``run()``)
--------------------------
*Small amplitude, against an independent solution (kind "exact").* The same system is written
again, apart from moorline's solvers, in :mod:`moorline.verification.disc_linear`: its own
statics (root solve of the force balances; it lands on moorline's static state to 1e-7 ft),
tangent stiffness (central differences), lumped masses and added masses, the disc's rigid-body
equations with ``A``, ``B``, the restoring matrix and the rotating weight and buoyancy, the
legs' Morison fluid inertia in the Airy wave, the seabed's penalty spring and damper; drag
drops out (``|u| u`` has a zero derivative at rest). Its response to the ramped wave is solved
exactly from rest (exponential forcing terms plus the matrix-exponential homogeneous part), so
the start-up transient is in the reference too. moorline's nonlinear run (incremental/iterative
Newmark, dt = 0.02 s, equilibrium to 1e-9) in a wave of amplitude ``SMALL_AMPLITUDE`` = 3e-5 ft
and the linear response are fitted over the same steady window (after the ramp and two
periods): first-harmonic amplitude per foot of wave and phase of surge, heave, pitch and the top
tension, for 3 elements (and 8 in the full form).

The amplitude must be that small: the 3-element leg's middle node rests on the seabed with
5 lbf on a quadratic penalty law, 0.001 ft deep, and a leg mode at 1.94 rad/s, close to the
wave's 2.09, makes the free node move 20 times more than the disc; at ``a = 0.01`` ft the seabed
node lifts off and drag damps that node (deviations of 25-60 %). At ``a = 1e-4`` ft the
deviations are 0.41 / 1.34 / 0.12 / 0.47 % (surge, heave, pitch, tension), at 3e-5 ft 0.13 /
0.55 / 0.065 / 0.22 %: proportional to the amplitude (the nonlinearity), with a floor near
0.2 %. Tolerance 1 % on the amplitudes. The phases differ by 0.001-0.004 rad, at dt = 0.01 s by
as much with other signs: the Newmark period elongation ``(w dt)^2 / 12`` of the lightly damped
pitch transient (2.57 rad/s) accumulates ``w^3 dt^2 t / 12`` = 0.017 rad over 30 s in that part
of the signal; tolerance 0.01 rad. The 8-element mesh agrees to 0.1 %. The linear model is
itself mesh dependent (3 elements: heave 0.55 ft per ft of wave; 8 elements: 1.42), so these
rows check each mesh, not the mesh convergence.

*The source's wave (10 ft), against the source (kind "published").* The cable's top goes slack
in every period (24 slack events in 30 s; snap loads up to 3,200 lbf against a static 244 lbf),
the source's "sudden release of the disc when the cable slackens": min tension / static,
reference 0 (slack read as below 5 %). The linear model is no reference there (its top tension
amplitude would be 17,000 lbf in this wave). Not reproduced:

* "The response period is slightly longer than the wave period": no number; the surge
  up-crossing period over the window is +0.96 % and the heave's -0.2 %: the crossings of a
  disc creeping towards the anchor, not a response period other than the forcing's (a steady
  forced response has the forcing period).
* Residual feedback (``variant="residual_feedback"``: one Newton correction per step, the
  out-of-balance force carried into the next step; dt = 0.005 s, tangent refreshed at least
  every five steps as in the source) "gives false results and the solution is diverging". Here
  it does not diverge. The carried out-of-balance force is small (median 1e-4 lbf) but at the
  steps where an element snaps taut it reaches 950 lbf (3.9 times the static top tension): the
  slack cable's tangent has almost no horizontal stiffness, so the single solve predicts the
  wrong increment when the cable goes from slack to taut within the step - the source's
  explanation. But the next residual is computed from the total state, so the error is
  corrected one step later instead of accumulating. What made the source's run diverge is
  not obtained; candidates are a purely incremental state update between stiffness refreshes
  and a fixed five-step tangent (here the tangent is also refreshed when a correction removes
  less than half of the residual, with a line search).
* "The surge for the eight-element model is slightly larger": no number; in the 10 ft wave
  moorline's 8-element surge amplitude is 2.944 ft against 2.940 ft (+0.1 %), not a check.

Dropped: the response period against the forcing period, the 8/3-element surge ratio of
1 +/- 0.1, the heave against a linear RAO fed with the run's own cable force (all could not
fail).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import brentq

from ..catenary import solve_catenary
from ..io.units import default_value
from ..mesh import discretize
from ..model import (
    Body,
    DynamicsSettings,
    Environment,
    Hydrostatics,
    Line,
    LineType,
    Motion,
    Point,
    Seabed,
    StaticsSettings,
    System,
    Waves,
)
from ..results import DynamicResult, StaticResult
from ..solvers.statics import solve_statics
from ..waves.dispersion import wave_number
from . import disc_linear as dl
from .core import Row
from .signals import harmonic_fit

FloatArray = NDArray[np.float64]

CASE = "tuah-ex5"

# ----------------------------------------------------------------------------- data
GRAVITY, RHO = 32.174, 1.99  # ft/s^2, slug/ft^3
DEPTH = 200.0  # ft (chosen)
FAIRLEAD_X, FAIRLEAD_DEPTH = 300.0, 2.5  # the source's "(300, 2.5)"
WIND = 100.0  # lbf along +x
WAVE_HEIGHT, WAVE_PERIOD = 10.0, 3.0  # ft, s
OMEGA = 2.0 * math.pi / WAVE_PERIOD
AMPLITUDE = WAVE_HEIGHT / 2.0
RAMP_TIME = 3.0 * WAVE_PERIOD  # s, (1 - cos) ramp over three periods

# Tuah Example 2's cable
CABLE_AREA, CABLE_E, CABLE_DENSITY = 0.0218, 8.12e6, 3.35  # ft^2, psf, slug/ft^3
CABLE_EA = CABLE_E * CABLE_AREA
CABLE_MASS = CABLE_DENSITY * CABLE_AREA  # slug/ft
CABLE_WEIGHT = (CABLE_DENSITY - RHO) * CABLE_AREA * GRAVITY  # lbf/ft, submerged
CABLE_LENGTH = math.hypot(FAIRLEAD_X, DEPTH - FAIRLEAD_DEPTH)  # the stretched chord

# the disc
DIAMETER, HULL_HEIGHT, DRAFT = 10.0, 4.0, 2.5  # ft
KG = 1.5  # ft, centre of gravity above the keel
WATERPLANE = math.pi * DIAMETER**2 / 4.0  # ft^2
WATERPLANE_INERTIA = math.pi * DIAMETER**4 / 64.0  # ft^4
VOLUME = WATERPLANE * DRAFT  # ft^3
FORCE_CENTRE = 0.3322  # ft above the still water level: the body frame origin

# potential-flow coefficients about the force centre (Capytaine 3.0, 2,304 panels, depth
# 200 ft, omega = 2 pi / 3 rad/s; see the module docstring). Units slug, slug ft, slug ft^2;
# damping lbf s/ft, lbf s, lbf ft s.
A11, A33, A55, A15 = 235.0, 415.6, 1357.5, -118.4
B11, B33 = 144.1, 308.2
# exciting force per unit wave amplitude [lbf/ft], wave crest at the origin at t = 0, time
# factor e^{-i omega t}: F_j(t) = Re(X_j a e^{i (k x - omega t)})
X_SURGE = complex(174.69, -2015.38)
X_HEAVE = complex(2008.24, -708.91)

BODY, LEG = "disc", "leg"


def added_mass_matrix() -> FloatArray:
    """6x6 added mass of the disc about the force centre (world axes)."""
    A = np.diag([A11, A11, A33, A55, A55, 0.0])
    A[0, 4] = A[4, 0] = A15
    A[1, 3] = A[3, 1] = -A15  # sway-roll: opposite sign of surge-pitch
    return A


def damping_matrix() -> FloatArray:
    """6x6 radiation damping about the force centre (pitch terms vanish there)."""
    return np.diag([B11, B11, B33, 0.0, 0.0, 0.0])


def hydrostatic_matrix() -> FloatArray:
    """Linear restoring: heave ``rho g A_wp``, roll and pitch ``rho g I_wp`` (the moments of
    buoyancy and weight come from their point loads)."""
    K = np.zeros((6, 6))
    K[2, 2] = RHO * GRAVITY * WATERPLANE
    K[3, 3] = K[4, 4] = RHO * GRAVITY * WATERPLANE_INERTIA
    return K


def wave_number_ex5() -> float:
    """Wave number of the 3 s wave in 200 ft of water [1/ft]."""
    return float(wave_number(OMEGA, DEPTH, GRAVITY))


def cable_type() -> LineType:
    """Tuah Example 2's cable (see the module docstring)."""
    return LineType("cable", diameter=math.sqrt(4.0 * CABLE_AREA / math.pi),
                    mass_per_length=CABLE_MASS, EA=CABLE_EA, displaced_area=CABLE_AREA,
                    Cd=1.2, Ca=1.0, Ct=0.008)


def design_catenary():
    """Closed-form elastic catenary of the leg under the wind's horizontal pull, with seabed
    contact: the fairlead's horizontal distance and vertical pull at the design draft."""
    rise = DEPTH - FAIRLEAD_DEPTH
    span = brentq(lambda x: solve_catenary(x, rise, CABLE_LENGTH, CABLE_EA,
                                           CABLE_WEIGHT).H - WIND,
                  0.2 * CABLE_LENGTH, 0.999 * CABLE_LENGTH, xtol=1e-10)
    return solve_catenary(span, rise, CABLE_LENGTH, CABLE_EA, CABLE_WEIGHT)


def disc_mass(vertical_pull: float) -> float:
    """Mass that floats the disc at its draft with ``vertical_pull`` [lbf] of mooring."""
    return (RHO * GRAVITY * VOLUME - vertical_pull) / GRAVITY


def disc(x: float, y: float = 0.0, vertical_pull: float | None = None,
         force_history: Motion | None = None) -> Body:
    """The disc with its body frame origin at the force centre above ``(x, y)``.

    Parameters
    ----------
    x, y
        Horizontal position of the disc's axis [ft].
    vertical_pull
        Static vertical mooring pull it is ballasted for [lbf]; default: the design
        catenary's.
    force_history
        Wave exciting force (see :func:`excitation`).
    """
    pull = design_catenary().V_b if vertical_pull is None else vertical_pull
    mass = disc_mass(pull)
    radius = DIAMETER / 2.0
    i_pitch = mass * (3.0 * radius**2 + HULL_HEIGHT**2) / 12.0
    i_yaw = mass * radius**2 / 2.0
    as_tuple = lambda M: tuple(tuple(float(v) for v in row) for row in M)  # noqa: E731
    return Body(
        BODY, position=(x, y, FORCE_CENTRE), mass=mass,
        center_of_gravity=(0.0, 0.0, -DRAFT + KG - FORCE_CENTRE),
        inertia=((i_pitch, 0.0, 0.0), (0.0, i_pitch, 0.0), (0.0, 0.0, i_yaw)),
        added_mass=as_tuple(added_mass_matrix()), damping=as_tuple(damping_matrix()),
        hydrostatics=Hydrostatics("matrix", stiffness=as_tuple(hydrostatic_matrix()),
                                  volume=VOLUME,
                                  center_of_buoyancy=(0.0, 0.0, -DRAFT / 2 - FORCE_CENTRE)),
        force=(WIND, 0.0, 0.0, 0.0, 0.0, 0.0), force_history=force_history)


def fairlead_arm() -> tuple[float, float, float]:
    """The keel shackle in the body frame [ft]."""
    return (0.0, 0.0, -DRAFT - FORCE_CENTRE)


def environment(waves: bool = True, height: float = WAVE_HEIGHT) -> Environment:
    """Sea water 200 ft deep with the package's default seabed, and the 3 s wave of
    ``height`` (the source's 10 ft)."""
    seabed = Seabed(stiffness=default_value("seabed_stiffness", "US"),
                    damping=default_value("seabed_damping", "US"),
                    slip_velocity=default_value("slip_velocity", "US"))
    wave = (Waves("airy", height=height, period=WAVE_PERIOD) if waves else Waves())
    return Environment(depth=DEPTH, water_density=RHO, gravity=GRAVITY, seabed=seabed,
                       waves=wave)


def ex5_system(segments: int = 3, waves: bool = True) -> System:
    """The disc on one leg, the disc started where the closed-form catenary puts it.

    Parameters
    ----------
    segments
        Elements of the leg (the source: 3 and 8).
    waves
        Include the Airy wave (cable kinematics); the disc's exciting force is added by
        :func:`with_excitation` once the static position is known.
    """
    cat = design_catenary()
    points = {
        "anchor": Point("anchor", "fixed", (0.0, 0.0, -DEPTH)),
        "fairlead": Point("fairlead", "body", fairlead_arm(), body=BODY),
    }
    lines = {LEG: Line(LEG, "cable", CABLE_LENGTH, segments, "anchor", "fairlead")}
    return System("tuah-ex5", units="US", environment=environment(waves),
                  line_types={"cable": cable_type()}, points=points, lines=lines,
                  bodies={BODY: disc(cat.horizontal_span, vertical_pull=cat.V_b)},
                  analyses=(StaticsSettings(tolerance=1e-10),))


def excitation(x: float, y: float, duration: float, ramp_time: float = RAMP_TIME,
               heading_deg: float = 0.0, step: float = 0.01,
               amplitude: float = AMPLITUDE) -> Motion:
    """The disc's linear wave exciting force at horizontal position ``(x, y)`` as a table.

    ``F(t) = r(t) Re(X a e^{i(k x_h - w t)})`` for surge (along the heading) and heave, with
    the ramp ``r`` of the table's ``ramp_time`` (the same law as the wave's); sampled every
    ``step`` s (linear interpolation error ``(w step)^2 / 8 = 5e-5``).
    """
    k = wave_number_ex5()
    beta = math.radians(heading_deg)
    xh = x * math.cos(beta) + y * math.sin(beta)
    times = np.arange(0.0, duration + 2 * step, step)
    phase = amplitude * np.exp(1j * (k * xh - OMEGA * times))
    surge = (X_SURGE * phase).real
    heave = (X_HEAVE * phase).real
    values = tuple((float(s * math.cos(beta)), float(s * math.sin(beta)), float(h))
                   for s, h in zip(surge, heave, strict=True))
    return Motion("table", times=tuple(float(t) for t in times), values=values,
                  ramp_time=ramp_time)


def with_excitation(system: System, static: StaticResult, duration: float,
                    ramp_time: float = RAMP_TIME,
                    wave_height: float = WAVE_HEIGHT) -> tuple[System, StaticResult]:
    """The system in the wave of ``wave_height`` with the disc's exciting force at its static
    position (and the static result re-meshed for it)."""
    x, y = static.body_pose[0, :2]
    body = replace(system.bodies[BODY],
                   force_history=excitation(float(x), float(y), duration, ramp_time,
                                            amplitude=wave_height / 2.0))
    env = replace(system.environment, waves=replace(system.environment.waves,
                                                    height=wave_height))
    system = replace(system, environment=env, bodies={**system.bodies, BODY: body})
    return system, replace(static, mesh=discretize(system))


def static_state(segments: int = 3) -> tuple[System, StaticResult]:
    """Coupled statics of the disc and its leg."""
    system = ex5_system(segments)
    static = solve_statics(system)
    if not static.success:
        raise RuntimeError(f"Ex5 statics failed: {static.message}")
    return system, static


# ----------------------------------------------------------------------------- linear model
def linear_body(vertical_pull: float, reference: tuple[float, float]) -> dl.RigidBody:
    """The disc of :func:`disc` for the independent linear model (restoring about
    ``(reference, FORCE_CENTRE)``, the body's given position)."""
    mass = disc_mass(vertical_pull)
    radius = DIAMETER / 2.0
    i_pitch = mass * (3.0 * radius**2 + HULL_HEIGHT**2) / 12.0
    return dl.RigidBody(
        mass=mass, cog=(0.0, 0.0, -DRAFT + KG - FORCE_CENTRE),
        inertia=np.diag([i_pitch, i_pitch, mass * radius**2 / 2.0]),
        added_mass=added_mass_matrix(), damping=damping_matrix(),
        restoring=hydrostatic_matrix(), reference=(reference[0], reference[1], FORCE_CENTRE),
        buoyancy=RHO * GRAVITY * VOLUME, cob=(0.0, 0.0, -DRAFT / 2 - FORCE_CENTRE),
        force=(WIND, 0.0, 0.0))


def linear_leg(anchor: tuple[float, float, float], segments: int) -> dl.Leg:
    """The leg of :func:`cable_type` from ``anchor`` to the keel shackle."""
    return dl.Leg(anchor=anchor, arm=fairlead_arm(), length=CABLE_LENGTH, n_elements=segments,
                  EA=CABLE_EA, mass_per_length=CABLE_MASS, weight_per_length=CABLE_WEIGHT,
                  diameter=math.sqrt(4.0 * CABLE_AREA / math.pi), Ca=1.0, Cat=0.0,
                  seabed_stiffness=default_value("seabed_stiffness", "US"),
                  seabed_damping=default_value("seabed_damping", "US"))


def catenary_guess(anchor: FloatArray, fairlead: FloatArray, segments: int) -> FloatArray:
    """Interior node positions (segments - 1, 3) on the inextensible catenary with the design
    horizontal pull, the part beyond the anchor on the seabed: a starting point for the linear
    model's statics."""
    a = WIND / CABLE_WEIGHT
    rise = fairlead[2] - anchor[2]
    hang = a * math.sinh(math.acosh(1.0 + rise / a))  # suspended length
    grounded = CABLE_LENGTH - hang
    direction = (fairlead - anchor)[:2] / np.linalg.norm((fairlead - anchor)[:2])
    out = []
    for i in range(1, segments):
        s = i * CABLE_LENGTH / segments
        if s <= grounded:
            x, z = s, -0.25 * math.sqrt(4.0 * CABLE_AREA / math.pi)  # pressed into the seabed
        else:
            u = s - grounded
            x, z = grounded + a * math.asinh(u / a), a * (math.sqrt(1.0 + (u / a) ** 2) - 1.0)
        out.append((anchor[0] + x * direction[0], anchor[1] + x * direction[1], anchor[2] + z))
    return np.array(out)


def linear_model(anchors: list[tuple[float, float, float]], segments: int,
                 vertical_pull: float, reference: tuple[float, float],
                 mass: str = "lumped") -> dl.LinearSystem:
    """Independent linear model (:mod:`moorline.verification.disc_linear`) of the disc on legs
    from ``anchors``, ballasted for ``vertical_pull``, about its own static state."""
    body = linear_body(vertical_pull, reference)
    legs = tuple(linear_leg(a, segments) for a in anchors)
    origin = np.array([reference[0], reference[1], FORCE_CENTRE])
    fairlead = origin + np.array(fairlead_arm())
    guesses = [catenary_guess(np.array(a), fairlead, segments) for a in anchors]
    pose = np.concatenate((origin, np.zeros(3)))
    sea = dl.Sea(DEPTH, RHO, GRAVITY)
    return dl.equilibrium(body, legs, sea, pose, guesses, mass)


def linear_loads(model: dl.LinearSystem, amplitude: float,
                 heading_deg: float = 0.0) -> tuple[NDArray[np.complex128],
                                                    NDArray[np.complex128]]:
    """The disc's exciting force at its static position (the case's force table) and the
    legs' fluid-inertia operator, for the wave of ``amplitude``."""
    k = wave_number_ex5()
    beta = math.radians(heading_deg)
    x0 = model.pose0[:2]
    shift = amplitude * np.exp(1j * k * (x0[0] * math.cos(beta) + x0[1] * math.sin(beta)))
    force = np.array([X_SURGE * shift * math.cos(beta), X_SURGE * shift * math.sin(beta),
                      X_HEAVE * shift])
    return (dl.body_load(model, force),
            dl.cable_inertia_operator(model, OMEGA, k, amplitude, heading_deg))


# ----------------------------------------------------------------------------- dynamics
@dataclass(frozen=True)
class Run:
    """One time-domain run: times, disc pose (n_t, 6), element tensions (n_t, n_el), the
    fairlead's force on the disc (n_t, 3) and, for residual feedback, the out-of-balance
    force carried out of each step (n_t,) [lbf]; ``diverged_at`` is the time the state went
    non-finite (None if it did not)."""

    time: FloatArray
    pose: FloatArray
    tension: FloatArray
    fairlead_force: FloatArray
    residual: FloatArray | None = None
    diverged_at: float | None = None


def run_dynamics(segments: int, dt: float, variant: str = "iterative",
                 duration: float = 30.0, stiffness_update: int = 5,
                 wave_height: float = WAVE_HEIGHT, tolerance: float = 1e-6) -> Run:
    """Run Ex5 from its static state.

    Parameters
    ----------
    segments
        Elements of the leg.
    dt
        Time step [s].
    variant
        ``iterative`` (Newton to the tolerance every step) or ``residual_feedback`` (one
        correction per step, the out-of-balance force carried forward).
    duration
        Simulated time [s].
    stiffness_update
        Tangent refreshed every this many steps (the source: five).
    wave_height, tolerance
        Wave height [ft] (the source: 10) and the equilibrium tolerance (relative).
    """
    system, static = static_state(segments)
    system, static = with_excitation(system, static, duration, wave_height=wave_height)
    settings = DynamicsSettings(duration=duration, dt=dt, variant=variant,
                                ramp_time=RAMP_TIME, stiffness_update=stiffness_update,
                                tolerance=tolerance)
    if variant == "iterative":
        from ..solvers.dynamics import simulate

        result = simulate(system, settings, initial=static, output_every=dt)
        return _from_result(result)
    return _one_shot(system, static, settings)


def _fairlead_force(result: DynamicResult) -> FloatArray:
    return result.end_force[:, result.mesh.line_index(LEG), 1]


def _from_result(result: DynamicResult) -> Run:
    return Run(result.time, result.body_history(BODY), result.tension, _fairlead_force(result))


def _one_shot(system: System, static: StaticResult, settings: DynamicsSettings) -> Run:
    """Residual feedback, recording the out-of-balance force each step leaves behind (the
    same set-up as :func:`~moorline.solvers.dynamics.simulate`, stepped here so that the
    carried residual can be recorded; one correction per step never cuts a step)."""
    from ..solvers import dynamics as dyn
    from ..solvers.dynamic_model import DynamicModel
    from ..solvers.equilibrium import StaticModel
    from ..solvers.excitation import Excitation

    mesh = static.mesh
    x0 = static.positions
    fluid = dyn._fluid(system, settings)
    model = DynamicModel(mesh, fluid, settings.viscoelastic_update, system.environment.seabed)
    exc = Excitation(mesh, x0)
    state = dyn._initial_state(model, exc, x0, settings.dt, initial=static)
    scale = max(float(np.abs(model.external).max(initial=0.0)),
                float(np.abs(state.evaluation.tension).max(initial=0.0)), 1e-12)
    tolerance = max(settings.tolerance * scale, StaticModel(mesh).roundoff_floor(x0))
    stepper = dyn._stepper(model, fluid, settings, tolerance, system, state)
    line = mesh.line_elements[mesh.line_index(LEG)]
    times, poses, tensions, forces, residuals = [0.0], [state.bodies.pose()[0]], \
        [state.evaluation.tension.copy()], [state.evaluation.element_forces[line[-1], 1]], [0.0]
    n_steps = int(round(settings.duration / settings.dt))
    diverged = None
    with np.errstate(all="ignore"):
        for k in range(1, n_steps + 1):
            t1 = k * settings.dt
            constrained = exc.constrained_state(t1)
            try:
                state, _, norm = stepper.step(state, t1 - state.t, constrained,
                                              exc.point_forces(t1, mesh.n_nodes))
            except (ValueError, RuntimeError, np.linalg.LinAlgError, ArithmeticError):
                diverged = t1
                break
            pose = state.bodies.pose()[0]
            if not (np.all(np.isfinite(pose)) and math.isfinite(norm)):
                diverged = t1
                break
            times.append(state.t)
            poses.append(pose)
            tensions.append(state.evaluation.tension.copy())
            forces.append(state.evaluation.element_forces[line[-1], 1])
            residuals.append(norm)
    force = np.array(forces)
    force[:, 2] -= 0.5 * mesh.weight_per_length[line[-1]] * mesh.length0[line[-1]]
    return Run(np.array(times), np.array(poses), np.array(tensions), force,
               np.array(residuals), diverged)


# ----------------------------------------------------------------------------- analysis
def up_crossing_period(t: FloatArray, y: FloatArray, period_guess: float) -> float:
    """Mean interval between up-crossings of ``y`` minus its linear trend, crossings closer
    than half ``period_guess`` merged (the snap spikes can add extra crossings)."""
    trend = np.polyval(np.polyfit(t, y, 1), t)
    z = y - trend
    idx = np.flatnonzero((z[:-1] < 0.0) & (z[1:] >= 0.0))
    crossings = t[idx] - z[idx] * (t[idx + 1] - t[idx]) / (z[idx + 1] - z[idx])
    kept: list[float] = []
    for c in crossings:
        if not kept or c - kept[-1] > 0.5 * period_guess:
            kept.append(float(c))
    if len(kept) < 2:
        return math.nan
    return float((kept[-1] - kept[0]) / (len(kept) - 1))


def _slack_periods(t: FloatArray, tension: FloatArray, start: float, end: float) -> float:
    """Fraction of the wave periods in ``[start, end]`` during which ``tension`` is ``<= 0``
    at least once."""
    n = max(int(round((end - start) / WAVE_PERIOD)), 1)
    hits = 0
    for k in range(n):
        mask = (t >= start + k * WAVE_PERIOD) & (t < start + (k + 1) * WAVE_PERIOD)
        hits += bool(np.any(tension[mask] <= 0.0))
    return hits / n


def slack_events(t: FloatArray, tension: FloatArray) -> int:
    """How many times ``tension`` falls from positive to ``<= 0``."""
    taut = tension > 0.0
    return int(np.count_nonzero(taut[:-1] & ~taut[1:]))


def heave_denominator() -> complex:
    """``K33 - (m + A33) w^2 + i B33 w`` of the disc alone [lbf/ft]."""
    mass = disc_mass(design_catenary().V_b)
    return complex(RHO * GRAVITY * WATERPLANE - (mass + A33) * OMEGA**2, B33 * OMEGA)


def haskind_heave_damping() -> float:
    """Deep-water Haskind relation ``B33 = w^3 |X3|^2 / (2 rho g^3)`` [lbf s/ft]."""
    return OMEGA**3 * abs(X_HEAVE) ** 2 / (2.0 * RHO * GRAVITY**3)


def window(run: Run, start: float) -> NDArray[np.bool_]:
    """Samples from ``start`` to the end, a whole number of wave periods."""
    end = run.time[-1]
    n = math.floor((end - start) / WAVE_PERIOD + 1e-9)
    return (run.time >= end - n * WAVE_PERIOD - 1e-9) & (run.time <= end + 1e-9)


# ----------------------------------------------------------------------------- rows
#: Wave amplitude of the small-amplitude runs [ft]: small enough that the legs' quadratic drag
#: and the seabed contact (a node resting with 5 lbf on a quadratic penalty law, 0.001 ft
#: deep) stay linear. The deviations from the linear model scale with it (module docstring).
SMALL_AMPLITUDE = 3e-5
#: Tolerances of the small-amplitude rows: amplitude (relative) and phase [rad], from the
#: amplitude study in the module docstring (deviations at 3e-5 ft at most 0.55 % and
#: 0.005 rad, at 1e-4 ft 1.3 % and 0.003 rad: proportional to the amplitude, floor 0.2 %).
AMPLITUDE_TOLERANCE, PHASE_TOLERANCE = 0.01, 0.01
SOURCE = "Tuah (1982) sec. 6.5"


def linear_ex5(segments: int) -> dl.LinearSystem:
    """The independent linear model of Example 5 (one leg, anchor at the origin)."""
    cat = design_catenary()
    return linear_model([(0.0, 0.0, -DEPTH)], segments, cat.V_b,
                        (cat.horizontal_span, 0.0))


def linear_rows(case: str, label: str, model: dl.LinearSystem, time: FloatArray,
                pose: FloatArray, tensions: dict[str, tuple[FloatArray, int]],
                amplitude: float, start: float) -> list[Row]:
    """Rows comparing a small-amplitude moorline run with the linear model's exact response
    to the same ramped wave, both fitted over the same steady window of whole periods:
    amplitude and phase of surge, heave, pitch and the top tensions.

    Parameters
    ----------
    time, pose
        moorline's output times and the disc pose (n_t, 6).
    tensions
        Per label, moorline's top-element tension history and the index of that leg in
        ``model.legs``.
    """
    dt = float(time[1] - time[0])
    table, inertia = linear_loads(model, amplitude)
    hist = dl.ramped_history(model, OMEGA, table, inertia, RAMP_TIME, dt, float(time[-1]))
    if len(hist.time) != len(time) or np.max(np.abs(hist.time - time)) > 1e-9:
        raise RuntimeError("linear history and moorline run on different time grids")
    n = math.floor((time[-1] - start) / WAVE_PERIOD + 1e-9)
    w = time >= time[-1] - n * WAVE_PERIOD - 1e-9
    t = time[w]
    steady = dl.steady_response(model, OMEGA, table, inertia)
    signals = [(name, pose[w, j], hist.q[w, j], "ft" if j < 3 else "rad", steady[j])
               for name, j in (("surge", 0), ("heave", 2), ("pitch", 4))]
    signals += [(f"{name} top tension", series[w], hist.top_tension[w, k], "lbf",
                 model.top_tension_map(k) @ steady) for name, (series, k) in tensions.items()]
    rows = []
    for name, moor, lin, unit, q in signals:
        fm = harmonic_fit(t, moor, OMEGA, 1).phasor()
        fl = harmonic_fit(t, lin, OMEGA, 1).phasor()
        note = (f"a = {amplitude:g} ft, {n} periods before t = {time[-1]:.0f} s, both with "
                f"the ramp's transient; linear steady amplitude {abs(q) / amplitude:.4g} "
                f"{unit}/ft")
        rows.append(Row(case, f"{label}: {name} amplitude / wave amplitude vs linear model",
                        abs(fl) / amplitude, abs(fm) / amplitude, AMPLITUDE_TOLERANCE,
                        unit=f"{unit}/ft", note=note, kind="exact",
                        source="disc_linear: independent linear model, exact ramped response"))
        rows.append(Row(case, f"{label}: {name} phase vs linear model", float(np.angle(fl)),
                        float(np.angle(fl) + np.angle(fm / fl)), PHASE_TOLERANCE,
                        relative=False, unit="rad", note="phase of Re(Y e^{-i w t})",
                        kind="exact", source="disc_linear"))
    return rows


def run(quick: bool = False) -> list[Row]:
    """Ex5 rows (see the module docstring).

    Parameters
    ----------
    quick
        The 3-element small-amplitude run over 21 s (two steady periods) and 15 s in the
        source's wave (the slack row); the full form: 3 and 8 elements over 30 s, 30 s in
        the source's wave (adds the not-reproduced response period) and 12 s of residual
        feedback (not reproduced: no divergence).
    """
    duration = 21.0 if quick else 30.0
    start = RAMP_TIME + 2 * WAVE_PERIOD
    rows: list[Row] = [Row(CASE, "disc B33 vs Haskind from |X3|", haskind_heave_damping(),
                           B33, 0.03, unit="lbf s/ft",
                           note="data consistency of the stored potential-flow numbers (deep "
                                "water, e^{-2kh} = 1e-12); tolerance: two panel meshes differ "
                                "by < 1 % per value, |X3|^2 doubles it", kind="exact",
                           source="Haskind relation (Newman 1977)")]
    for segments in ((3,) if quick else (3, 8)):
        small = run_dynamics(segments, 0.02, duration=duration,
                             wave_height=2 * SMALL_AMPLITUDE, tolerance=1e-9)
        rows += linear_rows(CASE, f"{segments} el", linear_ex5(segments), small.time,
                            small.pose, {"leg": (small.tension[:, -1], 0)}, SMALL_AMPLITUDE,
                            start)

    big = run_dynamics(3, 0.02, duration=15.0 if quick else duration)
    rows.append(_slack_row(big, CASE, "cable top element", SOURCE + " (heave spikes 'when "
                           "the cable slackens', Fig. 6.5-4, 6.5-5)"))
    if not quick:
        rows.append(_period_row(big, start))
        feedback = run_dynamics(3, 0.005, "residual_feedback", duration=12.0)
        rows.append(_feedback_row(feedback, float(big.tension[0, -1])))
    return rows


def _slack_row(run: Run, case: str, what: str, source: str) -> Row:
    """Published: in the source's wave the top element goes slack (min tension 0)."""
    top = run.tension[:, -1]
    mask = run.time >= RAMP_TIME
    return Row(case, f"10 ft wave: min tension of the {what} / static", 0.0,
               float(top[mask].min() / top[0]), 0.05, relative=False,
               note=f"static {top[0]:.0f} lbf, peak {top.max():.0f} lbf, "
                    f"{slack_events(run.time, top)} slack events after {run.time[-1]:.0f} s; "
                    "tolerance: 'slack' read as below 5 % of the static tension",
               kind="published", source=source)


def _period_row(run: Run, start: float) -> Row:
    """Not reproduced: the source's 'slightly longer' response period."""
    w = window(run, start)
    period = up_crossing_period(run.time[w], run.pose[w, 0], WAVE_PERIOD)
    heave = up_crossing_period(run.time[w], run.pose[w, 2], WAVE_PERIOD)
    return Row(CASE, "10 ft wave: surge response period (3 el)", WAVE_PERIOD, period, 0.0,
               unit="s", kind="published", source=SOURCE + " ('slightly longer than the wave "
               "period'; no number, Fig. 6.5-2 to 6.5-5 lost)", reproduced=False,
               note=f"surge up-crossings {100 * (period / WAVE_PERIOD - 1):+.2f} %, heave "
                    f"{100 * (heave / WAVE_PERIOD - 1):+.2f} % from the wave's period: the "
                    "crossings of a creeping disc; a steady forced response has the forcing "
                    "period, a longer one is not obtained (the source's step-like ramp "
                    "5 exp(-0.005/t) or its diverging residual-feedback curve may show one)")


def _feedback_row(feedback: Run, static_top: float) -> Row:
    """Not reproduced unless it diverges: the source's residual feedback at dt 0.005 s."""
    residual = feedback.residual if feedback.residual is not None else np.zeros(1)
    diverged = feedback.diverged_at is not None
    end = feedback.diverged_at if diverged else float(feedback.time[-1])
    note = (f"carried out-of-balance force up to {residual.max():.0f} lbf "
            f"({residual.max() / static_top:.1f} x the static top tension, at the snaps), "
            f"median {np.median(residual):.2g} lbf")
    if diverged:
        return Row(CASE, "residual feedback dt 0.005 (10 ft wave): diverges", 1.0, 1.0, 0.0,
                   relative=False, kind="published", source=SOURCE + " ('gives false "
                   "results and the solution is diverging')",
                   note=f"diverged at t = {end:.2f} s; " + note)
    return Row(CASE, "residual feedback dt 0.005 (10 ft wave): diverges", 1.0, 0.0, 0.0,
               relative=False, kind="published", source=SOURCE + " ('gives false results "
               "and the solution is diverging')", reproduced=False,
               note=f"no divergence over {end:.0f} s: {note}; each step's residual is "
                    "computed from the total state, so a step's error is corrected in the "
                    "next instead of accumulating (module docstring)")
