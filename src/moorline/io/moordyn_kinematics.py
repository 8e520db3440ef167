"""MoorDyn's water-kinematics options (``WaveKin``, ``Currents``) read for moorline.

MoorDyn-C v2.7 (``source/Waves/WaveOptions.hpp``, ``source/Waves.cpp``): ``WaveKin`` 0 is still
water, 1 wave kinematics set through the coupling API, 2-7 waves from files in the deck's
folder; ``Currents`` 0 is no current (or set through the API), 1 and 3 a steady profile read
from ``current_profile.txt`` in the deck's folder (grid and node approach: the same profile),
2 and 4 a time-varying profile (``current_profile_dynamic.txt``), 5 a 4-D grid. The steady
profile file (``constructSteadyCurrentGrid`` in ``source/Waves/WaveGrid.cpp``) has three
header lines, then rows ``z ux [uy [uz]]`` [m, m/s].

MoorDyn-C 2.7.2 computes its initial condition without the current (it reads the profile
for the time stepping only, after the IC); held at their fairleads its lines settle into the
current-loaded equilibrium within about 100 s, which moorline's statics with current drag
give directly (``tests/test_moordyn_io.py``).

moorline maps the steady profile to its current profile (speed and heading at each level,
:class:`moorline.model.Current`); everything else is dropped with a warning that names it: for
statics only the steady current matters.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path

from ..errors import CaseError
from ..model import Current

CURRENT_FILE = "current_profile.txt"
_WAVE_KIN = {1: "wave kinematics set through the coupling API",
             2: "waves from a wave-elevation FFT (grid)", 3: "waves from a wave-elevation "
             "time series (grid)", 4: "waves from a wave-elevation FFT (nodes)",
             5: "waves from a wave-elevation time series (nodes)",
             6: "wave kinematics grid files", 7: "waves from wave frequency components"}
_CURRENTS = {2: "a time-varying current profile (current_profile_dynamic.txt, grid)",
             4: "a time-varying current profile (current_profile_dynamic.txt, nodes)",
             5: "a 4-D current grid (current_profile_4d.txt)"}


def water_kinematics(options: dict[str, str], deck: Path,
                     warn: Callable[[str], None]) -> Current | None:
    """The deck's steady current, or None; warnings for every dropped kinematics option.

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
    if "wavekin" in lowered:
        key, value = lowered["wavekin"]
        mode = _mode(value)
        if mode:
            what = _WAVE_KIN.get(mode, f"an unknown wave mode {value}")
            warn(f"option {key} = {value} ({what}) is not read: waves are dropped (statics "
                 "use still water; a dynamics analysis runs without waves)")
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
                     "stepping only)")
            else:
                warn(f"option {key} = {value}: no {CURRENT_FILE} next to the deck, the current "
                     "is dropped")
        elif mode:
            what = _CURRENTS.get(mode, f"an unknown current mode {value}")
            warn(f"option {key} = {value} ({what}) is not read: the current is dropped")
    return current


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
