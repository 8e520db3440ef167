"""MoorDyn's Syrope line types (``SYROPE:file|EA_Dc|EA_D_Lm``) and ``SYROPE IC`` section.

Sources: MoorDyn-C v2.7.1 ``source/MoorDyn2.cpp`` (``readLineProps``,
``read_syrope_working_curves``, ``read_curve``, the ``SYROPE IC`` section of ``load``) and
``docs/inputs.rst`` ("Syrope Model for Polyester Lines"). The settings file holds ``value
name`` rows: ``OWC`` (the original working curve's file, relative to the deck's folder, as
MoorDyn-C opens it), ``WCType`` (``LINEAR``, ``QUADRATIC``, ``EXP``), ``k1``, ``k2``. The
curve file is read as MoorDyn's ``read_curve`` reads it: the first three lines are headers,
every later line is a ``strain tension`` point. (MoorDyn's own ``tests/Mooring/syrope/owc.dat``
has two header lines, so MoorDyn skips its ``(0, 0)`` point; so does this reader, with a note.)
The ``SYROPE IC`` rows are ``Line(s) Tmax0 Tmean0``, the line IDs comma separated.
The model: :mod:`moorline.physics.syrope`.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np

from ..model import Line, LineType, System
from ..physics.syrope import FORMS, SyropeRope, reference_stiffness, rope_of
from .files import MAX_TABLE_BYTES, file_problem
from .tokens import is_number

_HEADER_LINES = 3  # MoorDyn-C read_curve skips the first three lines of a curve file


def syrope_line_type(ea: str, ba: str, folder: Path, fail: Callable[[str], Exception],
                     warn: Callable[[str], None]) -> dict[str, Any]:
    """The :class:`~moorline.model.LineType` fields of a ``SYROPE:file|EA_Dc|EA_D_Lm`` EA
    with ``BA_s[|BA_d]``; ``fail`` builds the error naming the deck row."""
    parts = ea.split("|")
    if len(parts) != 3:
        raise fail(f"EA {ea!r}: the Syrope model needs 3 |-separated values "
                   "(SYROPE:file|EA_Dc|EA_D_Lm), as MoorDyn")
    alpha, beta = (_number(p, f"EA {ea!r}", fail) for p in parts[1:])
    damping = ba.split("|")
    if len(damping) > 2:
        raise fail(f"BA/-zeta {ba!r}: at most 2 |-separated values (BA_s|BA_d)")
    c1, c2 = (_number(d, f"BA/-zeta {ba!r}", fail) for d in (*damping, "0")[:2])
    if c1 < 0 or c2 < 0 or c1 + c2 <= 0:
        raise fail(f"BA/-zeta {ba!r}: the Syrope model needs BA_s, BA_d >= 0 (no damping "
                   "ratio) and BA_s + BA_d > 0 (MoorDyn divides by it)")
    settings_file = folder / parts[0][len("SYROPE:"):]
    settings = read_syrope_settings(settings_file, fail)
    owc_file = folder / settings["owc"]
    owc = read_moordyn_curve(owc_file, fail, warn)
    rope = SyropeRope(owc, settings["wctype"], settings["k1"], settings["k2"], alpha, beta)
    problems = rope.problems()
    if problems:
        raise fail(f"EA {ea!r} ({settings_file.name}, {owc_file.name}): " + "; ".join(problems))
    return {"EA": reference_stiffness(owc), "material": "syrope",
            "owc": tuple(map(tuple, owc.tolist())), "working_curve": settings["wctype"],
            "wc_k1": settings["k1"], "wc_k2": settings["k2"], "EAd": alpha, "EAd_Lm": beta,
            "BA": c1, "BA_dynamic": c2}


def read_syrope_settings(path: Path, fail: Callable[[str], Exception]) -> dict[str, Any]:
    """``OWC``, ``WCType``, ``k1``, ``k2`` of a Syrope settings file (``value name`` rows)."""
    problem = file_problem(path.resolve(), MAX_TABLE_BYTES)
    if problem is not None:
        raise fail(f"cannot read the Syrope settings file {str(path)!r}: {problem}")
    text = path.read_text(encoding="utf-8", errors="replace")
    found: dict[str, Any] = {}
    for number, line in enumerate(text.splitlines(), start=1):
        tokens = line.split()
        if len(tokens) < 2:
            continue
        value, name = tokens[0], tokens[1].lower()
        if name in ("k1", "k2"):
            found[name] = _number(value, f"{path.name}, line {number}: {tokens[1]}", fail)
        elif name == "wctype":
            if value.lower() not in FORMS:
                raise fail(f"{path.name}, line {number}: WCType {value!r} is not LINEAR, "
                           "QUADRATIC or EXP")
            found[name] = value.lower()
        elif name == "owc":
            found[name] = value
    missing = [key for key in ("owc", "wctype", "k1", "k2") if key not in found]
    if missing:
        raise fail(f"Syrope settings file {path.name}: missing "
                   f"{', '.join(k.upper() if k == 'owc' else k for k in missing)}")
    return found


def read_moordyn_curve(path: Path, fail: Callable[[str], Exception],
                       warn: Callable[[str], None]) -> np.ndarray:
    """Rows ``(strain, tension)`` of a MoorDyn curve file as MoorDyn-C reads it (three header
    lines skipped, then two numbers per line)."""
    problem = file_problem(path.resolve(), MAX_TABLE_BYTES)
    if problem is not None:
        raise fail(f"cannot read the curve file {str(path)!r}: {problem}")
    lines = path.read_text(encoding="utf-8", errors="replace").splitlines()
    skipped = lines[_HEADER_LINES - 1].split() if len(lines) >= _HEADER_LINES else []
    if len(skipped) >= 2 and all(is_number(t) for t in skipped[:2]):
        warn(f"curve file {path.name}: line {_HEADER_LINES} ({lines[_HEADER_LINES - 1].strip()!r})"
             f" is skipped as a header, as MoorDyn-C reads curve files (three header lines)")
    rows = []
    for number, line in enumerate(lines[_HEADER_LINES:], start=_HEADER_LINES + 1):
        tokens = line.split()
        if not tokens:
            continue
        if len(tokens) < 2 or not all(is_number(t) for t in tokens[:2]):
            raise fail(f"curve file {path.name}, line {number}: not a strain and a tension: "
                       f"{line.strip()!r}")
        rows.append([float(tokens[0]), float(tokens[1])])
    if len(rows) < 2:
        raise fail(f"curve file {path.name}: fewer than 2 points after its 3 header lines")
    return np.asarray(rows, dtype=float)


def apply_syrope_ic(rows: list[tuple[int, list[str]]], lines: dict[str, Line],
                    line_ids: Mapping[str, int], types: Mapping[str, LineType],
                    fail: Callable[[str, int], Exception], warn: Callable[[str], None]
                    ) -> dict[str, Line]:
    """``lines`` with the ``SYROPE IC`` rows' ``(Tmax0, Tmean0)`` (``rows``: line number and
    tokens); every Syrope line needs one (MoorDyn reads past its arrays without)."""
    by_id = {number: name for name, number in line_ids.items()}
    out = dict(lines)
    for lineno, tokens in rows:
        if len(tokens) < 3:
            raise fail(f"3 fields needed (Line(s) Tmax0 Tmean0), found {len(tokens)}", lineno)
        def row_fail(why: str, n: int = lineno) -> Exception:
            return fail(why, n)

        Tmax0, Tmean0 = (_number(t, what, row_fail)
                         for t, what in ((tokens[-2], "Tmax0"), (tokens[-1], "Tmean0")))
        for token in "".join(tokens[:-2]).split(","):
            number = int(_number(token, "Line(s)", row_fail))
            if number not in by_id:
                raise fail(f"there is no line {number}", lineno)
            line = out[by_id[number]]
            lt = types[line.line_type]
            if lt.material != "syrope":
                warn(f"SYROPE IC (line {lineno}): line {number} is not a Syrope line; ignored "
                     "(as MoorDyn)")
                continue
            problem = rope_of(lt).tmax_problem(Tmax0)
            if problem is not None or Tmean0 < 0:
                raise fail(f"line {number}: {problem or f'Tmean0 {Tmean0:g} is negative'}",
                           lineno)
            out[line.name] = replace(line, syrope_ic=(Tmax0, Tmean0))
    missing = [n for n, ln in out.items()
               if types[ln.line_type].material == "syrope" and ln.syrope_ic is None]
    if missing:
        raise fail(f"Syrope line(s) {', '.join(missing)} without a SYROPE IC row (Tmax0 "
                   "Tmean0): MoorDyn needs one for every Syrope line", 0)
    return out


def write_syrope_files(lt: LineType, deck: Path) -> str:
    """Write a Syrope line type's settings and OWC files next to ``deck``; return its EA cell
    ``SYROPE:<settings>|EA_Dc|EA_D_Lm``."""
    owc = deck.with_name(f"{deck.stem}_{lt.name}_owc.dat")
    rows = [f"---- {lt.name} original working curve (moorline) ----", "Strain Tension",
            "(-) (N)", *(f"{e!r} {t!r}" for e, t in lt.owc)]
    owc.write_text("\n".join(rows), encoding="utf-8")  # no final newline (MoorDyn-C)
    settings = deck.with_name(f"{deck.stem}_{lt.name}_syrope.dat")
    settings.write_text(f"{owc.name} OWC\n{lt.working_curve.upper()} WCType\n"
                        f"{float(lt.wc_k1)!r} k1\n{float(lt.wc_k2)!r} k2\n", encoding="utf-8")
    return f"SYROPE:{settings.name}|{float(lt.EAd)!r}|{float(lt.EAd_Lm)!r}"


def syrope_ic_rows(system: System) -> list[str]:
    """The ``SYROPE IC`` rows of the Syrope lines (numbered in the system's line order)."""
    return [f"{i:<4d} {ln.syrope_ic[0]!r} {ln.syrope_ic[1]!r}"
            for i, ln in enumerate(system.lines.values(), start=1)
            if ln.syrope_ic is not None and system.line_types[ln.line_type].material == "syrope"]


def _number(token: str, what: str, fail: Callable[[str], Exception]) -> float:
    try:
        value = float(token)
    except ValueError:
        raise fail(f"{what}: {token!r} is not a number") from None
    if not np.isfinite(value):
        raise fail(f"{what}: {token!r} is not a finite number")
    return value


