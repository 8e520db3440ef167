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

Meshes and steps: 10 segments a line in both (quick; full: 20); MoorDyn ``dtM`` 2 ms (1 ms);
moorline dt 0.1 s (0.05 s). Differences, moorline minus MoorDyn, at 10 / 20 segments:
equilibrium heave -0.37 / -0.38 mm (surge 0 by symmetry in both), line 1 tensions at the
anchor and the fairlead -0.008 % / -0.008 %, surge period 8.967 / 8.964 s against 8.962 s
(+0.055 % / +0.016 %). Tolerances are the acceptance limits of issue 14 (1 cm, 0.5 %, 2 %);
the measured differences are far inside them.
"""

from __future__ import annotations

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
TOL = {"position": 0.01, "tension": 0.005, "period": 0.02}


def platform_deck(segments: int, dt: float, *, x0: float = 0.0, z0: float = -10.0,
                  cda: str = "0.0", tmax_ic: float = 0.0) -> str:
    """The MoorDyn v2 deck of the moored platform (module docstring); the body's reference
    point at ``(x0, 0, z0)``, body drag ``cda`` (MoorDyn's CdA column)."""
    points, lines = [], []
    for k in range(6):
        a = math.radians(60.0 * k)
        points.append(f"{2 * k + 1} Fixed {270 * math.cos(a)!r} {270 * math.sin(a)!r} -150.0 "
                      "0 0 0 0")
        points.append(f"{2 * k + 2} Body1 {10 * math.cos(a)!r} {10 * math.sin(a)!r} -5.0 "
                      "0 0 0 0")
        lines.append(f"{k + 1} rope {2 * k + 1} {2 * k + 2} 292.0 {segments} -")
    return "\n".join([
        "MoorDyn v2 deck: a buoyant platform on six lines (moorline verification)",
        "---------------------- LINE TYPES ----------------------",
        "TypeName Diam Mass/m EA BA/-zeta EI Cd Ca CdAx CaAx",
        "(name) (m) (kg/m) (N) (N-s/-) (N-m^2) (-) (-) (-) (-)",
        "rope 0.15 30.0 1.0e8 -0.5 0.0 1.2 1.0 0.05 0.0",
        "---------------------- BODIES ----------------------",
        "ID Attachment X0 Y0 Z0 r0 p0 y0 Mass CG* I* Volume CdA* Ca*",
        "(#) (-) (m) (m) (m) (deg) (deg) (deg) (kg) (m) (kg-m^2) (m^3) (m^2) (-)",
        f"1 Free {x0!r} 0.0 {z0!r} 0 0 0 1.0e6 -1.0 2.0e8|2.0e8|3.0e8 1200.0 {cda} 0.5",
        "---------------------- POINTS ----------------------",
        "ID Attachment X Y Z Mass Volume CdA Ca",
        "(#) (-) (m) (m) (m) (kg) (m^3) (m^2) (-)",
        *points,
        "---------------------- LINES ----------------------",
        "ID LineType AttachA AttachB UnstrLen NumSegs LineOutputs",
        "(#) (name) (#) (#) (m) (-) (-)",
        *lines,
        "---------------------- OPTIONS ----------------------",
        f"{dt!r} dtM", "9.80665 g", "1025.0 rho", "150.0 WtrDpth", f"{tmax_ic!r} TmaxIC",
        "0 writeLog", "1 disableOutTime",
        "---------------------- OUTPUTS ----------------------",
        "---------------------- need this line ----------------------"]) + "\n"


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


def surge_period(time: np.ndarray, x: np.ndarray) -> float:
    """Mean period of ``x`` about zero from its zero crossings (linear interpolation)."""
    s = np.sign(x)
    i = np.nonzero(s[:-1] * s[1:] < 0)[0]
    crossing = time[i] - x[i] * (time[i + 1] - time[i]) / (x[i + 1] - x[i])
    if len(crossing) < 3:
        return math.nan
    return float(2.0 * (crossing[-1] - crossing[0]) / (len(crossing) - 1))


def _moorline(deck: Path, dt: float) -> dict[str, Any]:
    """moorline's equilibrium (pose, line end tensions) and free decay of the deck."""
    from ..io.moordyn import read_moordyn_deck
    from ..solvers.dynamics import simulate
    from ..solvers.statics import solve_statics

    system = read_moordyn_deck(deck).system
    (name, body), = system.bodies.items()
    static = solve_statics(system)
    if not static.success:
        raise RuntimeError(f"moorline statics failed: {static.message}")
    pose = np.asarray(static.body_pose[0], dtype=float)
    tension = np.array([[np.linalg.norm(static.end_force(line, end)) for end in ("a", "b")]
                        for line in system.lines])
    start = (float(pose[0] + OFFSET), float(pose[1]), float(pose[2]))
    held = replace(system, bodies={name: replace(body, kind="fixed", position=start)})
    released = replace(system, bodies={name: replace(body, position=start)})
    initial = solve_statics(held)
    if not initial.success:
        raise RuntimeError(f"moorline statics of the offset body failed: {initial.message}")
    run = simulate(released, DynamicsSettings(duration=DECAY, dt=dt), initial=initial,
                   output_every=SAMPLE)
    if not run.success:
        raise RuntimeError(f"moorline decay failed: {run.message}")
    surge = np.asarray(run.body_history(name), dtype=float)[:, 0] - pose[0]
    return {"pose": pose, "tension": tension,
            "period": surge_period(np.asarray(run.time, dtype=float), surge)}


def _row(quantity: str, ref: float, got: float, tol: str, unit: str, relative: bool = True,
         note: str = "") -> Row:
    return Row(CASE, quantity, ref, got, TOL[tol], relative=relative, unit=unit,
               kind="other code", source=SOURCE, note=note)


def run(quick: bool = False) -> list[Row]:
    """Equilibrium, line tensions and free-decay period of the platform deck against
    MoorDyn."""
    try:
        import moordyn  # noqa: F401
    except ImportError as exc:
        raise CaseSkipped("the [compare] extra (moordyn) is not installed") from exc
    segments, dtm, dt = QUICK if quick else FULL
    with tempfile.TemporaryDirectory(prefix="moorline-deck-") as folder:
        deck = Path(folder) / "platform.dat"
        deck.write_text(platform_deck(segments, dtm), encoding="utf-8")
        ml = _moorline(deck, dt)
        settle = Path(folder) / "settle.dat"
        settle.write_text(platform_deck(segments, dtm, cda=SETTLE_DRAG), encoding="utf-8")
        md = _moordyn(settle, SETTLE)
        last = md["time"] > SETTLE - SETTLE_MEAN - 1e-9
        md_pose = md["pose"][last].mean(axis=0)
        md_tension = md["tension"][last].mean(axis=0)
        speed = float(np.linalg.norm(md["velocity"][:3]))
        decay = Path(folder) / "decay.dat"
        decay.write_text(platform_deck(segments, dtm, x0=float(md_pose[0] + OFFSET),
                                       z0=float(md_pose[2])), encoding="utf-8")
        md_decay = _moordyn(decay, DECAY)
    md_period = surge_period(md_decay["time"], md_decay["pose"][:, 0] - md_pose[0])
    label = f"platform deck ({segments} el.)"
    settle_note = (f"MoorDyn: mean of the last {SETTLE_MEAN:g} s of a {SETTLE:g} s damped run "
                   f"(body speed {speed:.2g} m/s at its end)")
    rows = [_row(f"{label}: equilibrium surge", float(md_pose[0]), float(ml["pose"][0]),
                 "position", "m", relative=False, note=settle_note),
            _row(f"{label}: equilibrium heave", float(md_pose[2]), float(ml["pose"][2]),
                 "position", "m", relative=False, note=settle_note)]
    for k, end in ((0, "anchor"), (1, "fairlead")):  # the six lines agree by symmetry
        rows.append(_row(f"{label}: line 1 tension at the {end}", float(md_tension[0, k]),
                         float(ml["tension"][0, k]), "tension", "N"))
    rows.append(_row(f"{label}: surge free-decay period ({DECAY:g} s, {OFFSET:g} m)",
                     md_period, ml["period"], "period", "s"))
    assert all(math.isfinite(r.computed) and math.isfinite(r.reference) for r in rows)
    return rows
