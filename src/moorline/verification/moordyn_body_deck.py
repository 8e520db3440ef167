"""A MoorDyn body deck read by ``moorline convert``'s reader, against MoorDyn on the same file
(``[compare]`` extra).

The deck (:func:`platform_deck`, MoorDyn v2): a buoyant platform, one free ``BODIES`` row
(1000 t, centre of gravity 1 m below its reference point, inertia 2e8|2e8|3e8 kg m^2, volume
1200 m^3 with MoorDyn's constant buoyancy at the centre of gravity, ``Ca`` 0.5, no drag),
reference point at z = -10 m in 150 m of water, held by six semi-taut lines (292 m of a 0.15 m
rope: 30 kg/m, EA 100 MN, BA/-zeta -0.5, Cd 1.2, Ca 1, CdAx 0.05) from ``Body1`` points at
10 m radius, 5 m below the reference point, to anchors at 270 m radius on the seabed, every 60
deg. moorline reads the file with :func:`moorline.io.moordyn.read_moordyn_deck` (the body and
its points through :mod:`moorline.io.moordyn_rigid`); MoorDyn-C 2.7.2 reads the same text.

The second deck (:func:`spar_deck`): a floating spar, a free body of 2900 t (centre of
gravity 35 m below the still water level, inertia 1e9|1e9|2e7 kg m^2, no volume of its own) with
a ``Body1`` hull rod (8 m in diameter, massless, ``Ca`` 1, from 60 m draft to 10 m freeboard,
40 segments in MoorDyn) giving the buoyancy and the waterplane, held by six catenaries (425 m
of a 60 kg/m, EA 500 MN rope from 5 m radius, 20 m draft, to anchors at 400 m radius). moorline
maps the rod to ``rods`` hydrostatics: the buoyancy of its submerged length recomputed at
every pose (:mod:`moorline.physics.rod_buoyancy`, with its cut's waterplane moment).

Equilibrium: moorline's statics. MoorDyn's own initial-condition solve does not move a free
body to equilibrium (its stationary solver stops at 0.16 m/s^2 after 300 s with the body still
at its input depth; ``ICgenDynamic`` stops on the fairlead tensions with the body rising at
6 cm/s), so MoorDyn's equilibrium is taken from its dynamics: the same deck with a large body
drag ``CdA`` 1e5 m^2 (translation) and 1e9 (rotation), which does not change the equilibrium,
run 100 s from the input pose (the body velocity is below 1 mm/s at the end); the mean of the
last 20 s is compared (it moves by < 0.5 mm over them).

Free decay: each code's body starts at its equilibrium moved 3 m in surge, the lines at rest
in their static shape for that pose (moorline: statics with the body held; MoorDyn: its
catenary line initialization, ``TmaxIC`` 0), and is released for 60 s. The surge period is
the mean over the zero crossings of the surge (about 13 half periods).

Spar: equilibrium as the platform's; the pitch free decay (2 deg, full form only) is not
reproduced: MoorDyn-C 2.7's rod waterplane moment is not the waterplane's ``rho g I_wp``
(:data:`SPAR_PITCH_NOTE`, measured from MoorDyn's force on a coupled body holding the rod alone),
so its spar is stiffer in pitch (period 24.24 s against moorline's 25.34 s at 20 segments).

Meshes and steps: 10 segments a line in both (quick; full: 20); MoorDyn ``dtM`` 2 ms (1 ms);
moorline dt 0.1 s (0.05 s). Differences, moorline minus MoorDyn, at 10 / 20 segments:
equilibrium heave -0.37 / -0.38 mm (surge 0 by symmetry in both), line 1 tensions at the
anchor and the fairlead -0.008 % / -0.008 %, surge period 8.967 / 8.964 s against 8.962 s
(+0.055 % / +0.016 %); spar (10 segments): heave +1.32 mm, tensions -0.12 % (anchor) and
-0.033 % (fairlead) (with the rods hydrostatics; +0.75 mm, -0.075 %, +0.008 % with the former
constant buoyancy; the spar pitch decay above with the rods hydrostatics and their
waterplane moment, 25.42 s with the former constant buoyancy).
Tolerances are the acceptance limits of issue 14 (1 cm, 0.5 %, 2 %);
the measured differences are far inside them.
"""

from __future__ import annotations

import logging
import math
import tempfile
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np

from ..model import DynamicsSettings
from .core import CaseSkipped, Row

CASE = "moordyn-body-deck"
SOURCE = "MoorDyn-C 2.7.2 on the same deck"
#: (segments, MoorDyn dtM [s], moorline dt [s]): quick and full.
QUICK, FULL = (10, 0.002, 0.1), (20, 0.001, 0.05)
SETTLE, SETTLE_MEAN, DECAY, OFFSET, SAMPLE = 100.0, 20.0, 60.0, 3.0, 0.05
SETTLE_DRAG = "1e5|1e9"
SPAR_ROD_SEGMENTS, SPAR_PITCH = 40, 2.0
TOL = {"position": 0.01, "tension": 0.005, "period": 0.02}
SPAR_PITCH_NOTE = (
    "not reproduced: the codes' pitch restoring differs. MoorDyn-C 2.7's rod waterplane moment "
    "is not rho g I_wp: the hull rod alone on a coupled body at the equilibrium draft, pitched "
    "+-0.01 rad, has in MoorDyn a pitch stiffness 4.05e6 N m/rad above rho g (I_wp + V z_B) "
    "(3.0 rho g I_wp instead of Archimedes' 1.0, which moorline's rods have; Rod.cpp adds "
    "pi d^4/16 rho g sin(phi) cos(phi), four times pi d^4/64, and an end-cap moment of the "
    "opposite sign; MoorDyn issue #70 calls its waterplane moment incorrect). That explains "
    "0.43 s of the 1.10 s (4.5 %) period difference (moorline with 3 rho g I_wp: 24.90 s); "
    "the rest is not explained here")


def _table(title: str, head: str, units: str, rows: list[str]) -> list[str]:
    return [f"---------------------- {title} ----------------------", head, units, *rows]


def _deck(title: str, sections: list[str], segments: int, dt: float, anchor_radius: float,
          fairlead: tuple[float, float], length: float, rope: str) -> str:
    """A MoorDyn v2 deck with six lines every 60 deg from seabed anchors at
    ``anchor_radius`` to ``Body1`` points at ``fairlead = (radius, z)`` (body frame)."""
    points, lines = [], []
    for k in range(6):
        a = math.radians(60.0 * k)
        points.append(f"{2 * k + 1} Fixed {anchor_radius * math.cos(a)!r} "
                      f"{anchor_radius * math.sin(a)!r} -150.0 0 0 0 0")
        points.append(f"{2 * k + 2} Body1 {fairlead[0] * math.cos(a)!r} "
                      f"{fairlead[0] * math.sin(a)!r} {fairlead[1]!r} 0 0 0 0")
        lines.append(f"{k + 1} rope {2 * k + 1} {2 * k + 2} {length!r} {segments} -")
    return "\n".join([
        f"MoorDyn v2 deck: {title} on six lines (moorline verification)",
        *_table("LINE TYPES", "TypeName Diam Mass/m EA BA/-zeta EI Cd Ca CdAx CaAx",
                "(name) (m) (kg/m) (N) (N-s/-) (N-m^2) (-) (-) (-) (-)", [rope]),
        *sections,
        *_table("POINTS", "ID Attachment X Y Z Mass Volume CdA Ca",
                "(#) (-) (m) (m) (m) (kg) (m^3) (m^2) (-)", points),
        *_table("LINES", "ID LineType AttachA AttachB UnstrLen NumSegs LineOutputs",
                "(#) (name) (#) (#) (m) (-) (-)", lines),
        "---------------------- OPTIONS ----------------------",
        f"{dt!r} dtM", "9.80665 g", "1025.0 rho", "150.0 WtrDpth", "0 TmaxIC",
        "0 writeLog", "1 disableOutTime",
        "---------------------- OUTPUTS ----------------------",
        "---------------------- need this line ----------------------"]) + "\n"


_BODY_HEAD = ("ID Attachment X0 Y0 Z0 r0 p0 y0 Mass CG* I* Volume CdA* Ca*",
              "(#) (-) (m) (m) (m) (deg) (deg) (deg) (kg) (m) (kg-m^2) (m^3) (m^2) (-)")


def platform_deck(segments: int, dt: float, *, x0: float = 0.0, z0: float = -10.0,
                  p0: float = 0.0, cda: str = "0.0") -> str:
    """The MoorDyn v2 deck of the moored buoyant platform (module docstring); the body's
    reference point at ``(x0, 0, z0)``, pitched ``p0`` [deg], body drag ``cda`` (MoorDyn's
    CdA column)."""
    body = (f"1 Free {x0!r} 0.0 {z0!r} 0 {p0!r} 0 1.0e6 -1.0 2.0e8|2.0e8|3.0e8 1200.0 {cda} "
            "0.5")
    return _deck("a buoyant platform", _table("BODIES", *_BODY_HEAD, [body]), segments, dt,
                 270.0, (10.0, -5.0), 292.0, "rope 0.15 30.0 1.0e8 -0.5 0.0 1.2 1.0 0.05 0.0")


def spar_deck(segments: int, dt: float, *, x0: float = 0.0, z0: float = 0.0,
              p0: float = 0.0, cda: str = "0.0") -> str:
    """The MoorDyn v2 deck of the moored spar (module docstring), as :func:`platform_deck`."""
    body = (f"1 Free {x0!r} 0.0 {z0!r} 0 {p0!r} 0 2.9e6 -35.0 1.0e9|1.0e9|2.0e7 0.0 {cda} "
            "0.0")
    sections = [*_table("ROD TYPES", "TypeName Diam Mass/m Cd Ca CdEnd CaEnd",
                        "(name) (m) (kg/m) (-) (-) (-) (-)", ["hull 8.0 0.0 0.0 1.0 0.0 0.0"]),
                *_table("BODIES", *_BODY_HEAD, [body]),
                *_table("RODS", "ID RodType Attachment Xa Ya Za Xb Yb Zb NumSegs RodOutputs",
                        "(#) (name) (#/key) (m) (m) (m) (m) (m) (m) (-) (-)",
                        [f"1 hull Body1 0 0 -60 0 0 10 {SPAR_ROD_SEGMENTS} -"])]
    return _deck("a spar", sections, segments, dt, 400.0, (5.0, -20.0), 425.0,
                 "rope 0.15 60.0 5.0e8 -0.5 0.0 1.2 1.0 0.05 0.0")


def _moordyn(deck: Path, duration: float) -> dict[str, Any]:
    """Run MoorDyn on a deck file without coupling: body pose (n, 6) and velocity at the
    end, line end tensions (n, 6, 2), every ``SAMPLE`` s."""
    import moordyn

    from ..compare.moordyn_runner import silenced_fd

    with silenced_fd(1):
        md = moordyn.Create(str(deck))
        moordyn.SetVerbosity(md, moordyn.LEVEL_ERR)
        status = moordyn.Init(md, [], [])
    try:
        if status:
            raise RuntimeError(f"moordyn.Init failed with error code {status}")
        body = moordyn.GetBody(md, 1)
        lines = [moordyn.GetLine(md, i) for i in range(1, 7)]
        ends = [(line, moordyn.GetLineN(line)) for line in lines]
        n = int(round(duration / SAMPLE))
        pose, tension = np.zeros((n, 6)), np.zeros((n, 6, 2))
        for i in range(n):
            moordyn.Step(md, [], [], i * SAMPLE, SAMPLE)
            pose[i] = moordyn.GetBodyState(body)[0]
            for j, (line, last) in enumerate(ends):
                tension[i, j] = [np.linalg.norm(moordyn.GetLineNodeForce(line, k))
                                 for k in (0, last)]
        velocity = np.asarray(moordyn.GetBodyState(body)[1], dtype=float)
    finally:
        moordyn.Close(md)
    time = SAMPLE * np.arange(1, n + 1)
    return {"time": time, "pose": pose, "tension": tension, "velocity": velocity}


def period(time: np.ndarray, x: np.ndarray) -> float:
    """Mean period of ``x`` about zero from its zero crossings (linear interpolation)."""
    s = np.sign(x)
    i = np.nonzero(s[:-1] * s[1:] < 0)[0]
    crossing = time[i] - x[i] * (time[i + 1] - time[i]) / (x[i + 1] - x[i])
    if len(crossing) < 3:
        return math.nan
    return float(2.0 * (crossing[-1] - crossing[0]) / (len(crossing) - 1))


def _moorline_static(deck: Path) -> dict[str, Any]:
    """moorline's reading and equilibrium of a deck: system, body name, pose, line end
    tensions (6, 2)."""
    from ..io.moordyn import read_moordyn_deck
    from ..solvers.statics import solve_statics

    log = logging.getLogger("moorline.io.moordyn")
    level = log.level
    log.setLevel(logging.ERROR)  # the reader's notes (the rod's approximations) are known
    try:
        system = read_moordyn_deck(deck).system
    finally:
        log.setLevel(level)
    (name, _), = system.bodies.items()
    static = solve_statics(system)
    if not static.success:
        raise RuntimeError(f"moorline statics failed: {static.message}")
    tension = np.array([[np.linalg.norm(static.end_force(line, end)) for end in ("a", "b")]
                        for line in system.lines])
    return {"system": system, "name": name, "tension": tension,
            "pose": np.asarray(static.body_pose[0], dtype=float)}


def _moorline_decay(eq: dict[str, Any], dx: float, pitch: float, dt: float) -> dict[str, Any]:
    """moorline's free decay from the equilibrium moved ``dx`` in surge and pitched ``pitch``
    [rad]: the body held there for the lines' statics, then released; surge (from
    equilibrium) and pitch histories."""
    from ..solvers.dynamics import simulate
    from ..solvers.statics import solve_statics

    system, name, pose = eq["system"], eq["name"], eq["pose"]
    body = system.bodies[name]
    held = replace(system, bodies={name: replace(
        body, kind="fixed", position=(float(pose[0] + dx), float(pose[1]), float(pose[2])),
        rotation=(0.0, pitch, 0.0))})
    initial = solve_statics(held)
    if not initial.success:
        raise RuntimeError(f"moorline statics of the offset body failed: {initial.message}")
    run = simulate(system, DynamicsSettings(duration=DECAY, dt=dt), initial=initial,
                   output_every=SAMPLE)
    if not run.success:
        raise RuntimeError(f"moorline decay failed: {run.message}")
    history = np.asarray(run.body_history(name), dtype=float)
    return {"time": np.asarray(run.time, dtype=float), "surge": history[:, 0] - pose[0],
            "pitch": history[:, 4]}


def _moordyn_equilibrium(folder: Path, deck: Any, segments: int, dtm: float
                         ) -> dict[str, Any]:
    """MoorDyn's equilibrium from its damped dynamics (module docstring): pose, line end
    tensions (6, 2), body speed at the end."""
    path = folder / "settle.dat"
    path.write_text(deck(segments, dtm, cda=SETTLE_DRAG), encoding="utf-8")
    md = _moordyn(path, SETTLE)
    last = md["time"] > SETTLE - SETTLE_MEAN - 1e-9
    return {"pose": md["pose"][last].mean(axis=0), "tension": md["tension"][last].mean(axis=0),
            "speed": float(np.linalg.norm(md["velocity"][:3]))}


def _moordyn_decay(folder: Path, deck: Any, segments: int, dtm: float, pose: np.ndarray,
                   dx: float, pitch_deg: float) -> dict[str, Any]:
    path = folder / "decay.dat"
    path.write_text(deck(segments, dtm, x0=float(pose[0] + dx), z0=float(pose[2]),
                         p0=pitch_deg), encoding="utf-8")
    md = _moordyn(path, DECAY)
    return {"time": md["time"], "surge": md["pose"][:, 0] - pose[0], "pitch": md["pose"][:, 4]}


def _row(quantity: str, ref: float, got: float, tol: str, unit: str, relative: bool = True,
         note: str = "") -> Row:
    return Row(CASE, quantity, ref, got, TOL[tol], relative=relative, unit=unit,
               kind="other code", source=SOURCE, note=note)


def _equilibrium_rows(label: str, ml: dict[str, Any], md: dict[str, Any]) -> list[Row]:
    note = (f"MoorDyn: mean of the last {SETTLE_MEAN:g} s of a {SETTLE:g} s damped run "
            f"(body speed {md['speed']:.2g} m/s at its end)")
    rows = [_row(f"{label}: equilibrium surge", float(md["pose"][0]), float(ml["pose"][0]),
                 "position", "m", relative=False, note=note),
            _row(f"{label}: equilibrium heave", float(md["pose"][2]), float(ml["pose"][2]),
                 "position", "m", relative=False, note=note)]
    for k, end in ((0, "anchor"), (1, "fairlead")):  # the six lines agree by symmetry
        rows.append(_row(f"{label}: line 1 tension at the {end}", float(md["tension"][0, k]),
                         float(ml["tension"][0, k]), "tension", "N"))
    return rows


def run(quick: bool = False) -> list[Row]:
    """Equilibria, line tensions and free-decay periods of the platform and spar decks
    against MoorDyn."""
    try:
        import moordyn  # noqa: F401
    except ImportError as exc:
        raise CaseSkipped("the [compare] extra (moordyn) is not installed") from exc
    segments, dtm, dt = QUICK if quick else FULL
    rows = []
    with tempfile.TemporaryDirectory(prefix="moorline-deck-") as name:
        folder = Path(name)
        deck = folder / "platform.dat"
        deck.write_text(platform_deck(segments, dtm), encoding="utf-8")
        ml = _moorline_static(deck)
        md = _moordyn_equilibrium(folder, platform_deck, segments, dtm)
        label = f"platform deck ({segments} el.)"
        rows += _equilibrium_rows(label, ml, md)
        ml_decay = _moorline_decay(ml, OFFSET, 0.0, dt)
        md_decay = _moordyn_decay(folder, platform_deck, segments, dtm, md["pose"], OFFSET, 0.0)
        rows.append(_row(f"{label}: surge free-decay period ({DECAY:g} s, {OFFSET:g} m)",
                         period(md_decay["time"], md_decay["surge"]),
                         period(ml_decay["time"], ml_decay["surge"]), "period", "s"))
        deck = folder / "spar.dat"
        deck.write_text(spar_deck(segments, dtm), encoding="utf-8")
        ml = _moorline_static(deck)
        md = _moordyn_equilibrium(folder, spar_deck, segments, dtm)
        label = f"spar deck ({segments} el.)"
        rows += _equilibrium_rows(label, ml, md)
        if not quick:
            ml_decay = _moorline_decay(ml, 0.0, math.radians(SPAR_PITCH), dt)
            md_decay = _moordyn_decay(folder, spar_deck, segments, dtm, md["pose"], 0.0,
                                      SPAR_PITCH)
            rows.append(Row(
                CASE, f"{label}: pitch free-decay period ({DECAY:g} s, {SPAR_PITCH:g} deg)",
                period(md_decay["time"], md_decay["pitch"]),
                period(ml_decay["time"], ml_decay["pitch"]), TOL["period"], unit="s",
                kind="other code", source=SOURCE, reproduced=False, note=SPAR_PITCH_NOTE))
    assert all(math.isfinite(r.computed) and math.isfinite(r.reference) for r in rows)
    return rows
