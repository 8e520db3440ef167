"""MoorDyn's water-kinematics options (``WaveKin``, ``Currents``) read for moorline.

MoorDyn-C v2.7 (``source/Waves/WaveOptions.hpp``, ``source/Waves.cpp``): ``WaveKin`` 0 is still
water, 1 wave kinematics set through the coupling API, 2 a wave spectrum
(``wave_frequencies.txt``) inverse-FFT'd on a grid, 3 a wave-elevation time series
(``wave_elevation.txt``) FFT'd onto a grid, 4 and 5 the same at the nodes (not implemented by
MoorDyn-C 2.7: it builds no kinematics for them), 6 grid files (not implemented), 7 the
spectrum's components summed at the nodes; ``Currents`` 0 is no current (or set through the
API), 1 and 3 a steady profile read from ``current_profile.txt`` in the deck's folder (grid
and node approach: the same profile; MoorDyn-C 2.7 builds nothing for 3, a warning says so),
2 and 4 a time-varying profile
(``current_profile_dynamic.txt``), 5 a 4-D grid. The steady profile file
(``constructSteadyCurrentGrid`` in ``source/Waves/WaveGrid.cpp``) has three header lines,
then rows ``z ux [uy [uz]]`` [m, m/s].

MoorDyn-C 2.7.2 computes its initial condition without the current (it reads the profile
for the time stepping only, after the IC); held at their fairleads its lines settle into the
current-loaded equilibrium within about 100 s, which moorline's statics with current drag
give directly (``tests/test_moordyn_io.py``).

moorline maps the steady profile to its current profile (speed and heading at each level,
:class:`moorline.model.Current`) and WaveKin 2, 3, 7 (and 4, 5 as 2, 3) to a sea of explicit
components (``Waves(kind="components")``, :mod:`moorline.io.moordyn_waves`; Wheeler
stretching, as MoorDyn's kinematics stretch z to the instantaneous surface); everything else
is dropped with a warning that names it. Statics use still water and the steady current (as
MoorDyn's initial condition has no waves). The time-varying current (Currents 2 and 4) is
not read: moorline's current is a steady profile (ramped at the start), and a time table of
profiles would need its own field in the environment, the case file and every analysis that
linearizes about the current.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import replace
from pathlib import Path

from ..errors import CaseError
from ..model import Current, Waves
from .moordyn_waves import (
    ELEVATION_FILE,
    FREQUENCY_FILE,
    NEGLIGIBLE,
    elevation_components,
    fft_grid_components,
    read_wave_elevation,
    read_wave_frequencies,
    summed_components,
)

CURRENT_FILE = "current_profile.txt"
_WAVE_KIN = {1: "wave kinematics set through the coupling API",
             2: "waves from a wave spectrum, FFT grid", 3: "waves from a wave-elevation "
             "time series, grid", 4: "waves from a wave spectrum, FFT at the nodes",
             5: "waves from a wave-elevation time series at the nodes",
             6: "wave kinematics grid files", 7: "waves from wave frequency components"}
_CURRENTS = {2: "a time-varying current profile (current_profile_dynamic.txt, grid)",
             4: "a time-varying current profile (current_profile_dynamic.txt, nodes)",
             5: "a 4-D current grid (current_profile_4d.txt)"}
#: Default of MoorDyn-C's ``dtWave`` option [s] (``WaterKinOptions``).
DT_WAVE = 0.25


def water_kinematics(options: dict[str, str], deck: Path,
                     warn: Callable[[str], None]) -> Current | None:
    """The deck's steady current, or None; warnings for every dropped current option (the
    waves: :func:`deck_waves`).

    Parameters
    ----------
    options
        The deck's ``OPTIONS`` rows ``{key: value}`` (keys as written).
    deck
        The deck's path (MoorDyn reads its kinematics files from the deck's folder).
    warn
        Called with each warning.
    """
    lowered = {k.lower(): (k, v) for k, v in options.items()}
    current = None
    if "currents" in lowered:
        key, value = lowered["currents"]
        mode = _mode(value)
        if mode in (1, 3):
            path = deck.parent / CURRENT_FILE
            if path.is_file():
                current = read_current_profile(path, warn)
                warn(f"option {key} = {value}: the steady current profile {path} is read as "
                     "the case's current (statics with current drag; MoorDyn-C 2.7 finds its "
                     "initial condition without the current and applies it in the time "
                     "stepping only)" + ("; MoorDyn-C 2.7 builds no current for Currents 3 "
                                         "(not implemented): its runs of this deck have none"
                                         if mode == 3 else ""))
            else:
                warn(f"option {key} = {value}: no {CURRENT_FILE} next to the deck, the current "
                     "is dropped")
        elif mode:
            what = _CURRENTS.get(mode, f"an unknown current mode {value}")
            warn(f"option {key} = {value} ({what}) is not read: the current is dropped "
                 "(moorline's current is a steady profile)")
    return current


def deck_waves(options: dict[str, str], deck: Path, warn: Callable[[str], None]) -> Waves | None:
    """The deck's waves (``WaveKin`` 2-5, 7) as explicit components, or None; a warning
    saying what was read, or what is dropped and why.

    Parameters
    ----------
    options
        The deck's ``OPTIONS`` rows ``{key: value}`` (keys as written).
    deck
        The deck's path (MoorDyn reads its wave files from the deck's folder).
    warn
        Called with each warning.

    Raises
    ------
    CaseError
        A wave file MoorDyn would refuse, or a ``dtWave`` that is not a positive number.
    """
    lowered = {k.lower(): (k, v) for k, v in options.items()}
    if "wavekin" not in lowered:
        return None
    key, value = lowered["wavekin"]
    mode = _mode(value)
    if not mode:
        return None
    what = _WAVE_KIN.get(mode, f"an unknown wave mode {value}")
    option = f"option {key} = {value} ({what})"
    if mode not in (2, 3, 4, 5, 7):
        warn(f"{option} is not read: waves are dropped (statics use still water; a "
             "dynamics analysis runs without waves)")
        return None
    name = ELEVATION_FILE if mode in (3, 5) else FREQUENCY_FILE
    path = deck.parent / name
    if not path.is_file():
        warn(f"{option}: no {name} next to the deck, waves are dropped")
        return None
    if mode in (3, 5):
        dt_key, dt_value = lowered.get("dtwave", ("dtWave", str(DT_WAVE)))
        try:
            dt_wave = float(dt_value)
        except ValueError:
            dt_wave = math.nan
        if not (dt_wave > 0.0 and math.isfinite(dt_wave)):
            raise CaseError(f"must be a positive time step [s], got {dt_value!r}",
                            file=str(deck), field=f"OPTIONS {dt_key}")
        t, eta = read_wave_elevation(path)
        try:
            sea, n, mean = elevation_components(t, eta, dt_wave)
        except ValueError as exc:
            raise CaseError(str(exc), file=str(path)) from None
        how = (f"{t.size} samples resampled at dtWave = {dt_wave:g} s, the FFT of {n} "
               f"(repeating every {n * dt_wave:g} s) cut at 0.5 Hz")
    else:
        omega, amplitude, beta = read_wave_frequencies(path)
        if mode == 7:
            sea, mean = summed_components(omega, amplitude, beta), 0.0
            how = f"{omega.size} rows summed at the nodes, as MoorDyn does"
        else:
            try:
                sea, step, mean = fft_grid_components(omega, amplitude, beta)
            except ValueError as exc:
                raise CaseError(str(exc), file=str(path)) from None
            how = (f"interpolated to MoorDyn's even step of {step:g} rad/s, the last "
                   "frequency halved as its inverse FFT does")
    count = len(sea.omegas)
    notes = [f"{option}: {path} is read as {count} wave component{'s' * (count != 1)} ({how}); "
             "statics use still water"]
    if mode != 7:
        notes.append("moorline evaluates them exactly at the nodes, MoorDyn interpolates them "
                     "on the grid of water_grid.txt and in time")
    if mode in (4, 5):
        notes.append(f"MoorDyn-C 2.7 builds no kinematics for WaveKin {mode} (not "
                     "implemented): its runs of this deck are in still water")
    if abs(mean) > NEGLIGIBLE * max(sea.amplitudes, default=0.0):
        notes.append(f"the constant level {mean:.6g} m (zero frequency) is dropped")
    warn("; ".join(notes))
    headings = sea.headings_deg
    heading = headings[0] if headings else 0.0
    if all(h == heading for h in headings):  # one direction: the sea's heading
        sea = replace(sea, headings_deg=())
    return Waves(kind="components", components=sea, heading_deg=heading,
                 stretching="wheeler")


def _mode(value: str) -> int:
    try:
        return int(float(value))
    except ValueError:
        return -1


def read_current_profile(path: Path, warn: Callable[[str], None]) -> Current:
    """A MoorDyn ``current_profile.txt`` as a :class:`Current` profile.

    moorline's profile holds a horizontal speed and heading per level and interpolates them
    linearly in z; MoorDyn interpolates the velocity components. The two agree where the
    heading is the same at neighbouring levels (a warning otherwise); a vertical component
    ``uz`` is dropped (warning). A level of zero speed takes the heading of its neighbours.
    """
    rows = []
    for lineno, text in enumerate(path.read_text(encoding="utf-8", errors="replace")
                                  .splitlines(), start=1):
        if lineno <= 3 or not text.strip():
            continue
        tokens = text.split()
        try:
            values = [float(t) for t in tokens[:4]]
        except ValueError:
            raise CaseError(f"expected numbers 'z ux [uy [uz]]', got {text.strip()!r}",
                            file=str(path), field=f"line {lineno}") from None
        if len(values) < 2 or not all(map(math.isfinite, values)):
            raise CaseError("expected finite numbers 'z ux [uy [uz]]'", file=str(path),
                            field=f"line {lineno}")
        rows.append((values + [0.0, 0.0])[:4])
    if not rows:
        raise CaseError("no current levels (three header lines, then 'z ux [uy [uz]]')",
                        file=str(path))
    if any(r[3] for r in rows):
        warn(f"{path}: the vertical current component uz is dropped")
    speeds = [math.hypot(r[1], r[2]) for r in rows]
    headings = [math.degrees(math.atan2(r[2], r[1])) if s else math.nan
                for r, s in zip(rows, speeds, strict=True)]
    known = [h for h in headings if not math.isnan(h)]
    fill = known[0] if known else 0.0
    for i, h in enumerate(headings):  # zero-speed levels: the last known heading (or the first)
        if math.isnan(h):
            headings[i] = fill
        else:
            fill = h
    turning = any(not math.isclose(a, b, abs_tol=1e-9) and sa and sb for a, b, sa, sb in
                  zip(headings, headings[1:], speeds, speeds[1:], strict=False))
    if turning:
        warn(f"{path}: the current turns with depth; moorline interpolates speed and heading "
             "between levels, MoorDyn the velocity components (they differ between levels)")
    return Current(z_levels=tuple(r[0] for r in rows), speeds=tuple(speeds),
                   headings_deg=tuple(headings))
