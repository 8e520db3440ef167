"""The summary laid out without rich (:mod:`moorline.io.plain_tables`) against rich itself.

rich is the reference: the same blocks rendered by rich's console (what ``summary.txt`` and
stdout held before) and by the plain layout must be the same text, character for character,
or the plain layout must decline (``None``) and leave them to rich.
"""

from __future__ import annotations

import random

from moorline.io.plain_tables import plain_text
from moorline.io.summary_render import Grid, Para, summary_blocks
from moorline.io.writers import _NullFile, _rich, summary_text


def _by_rich(blocks: list, width: int) -> str:
    from rich.console import Console

    console = Console(width=width, record=True, file=_NullFile(), color_system=None)
    for renderable in _rich(blocks):
        console.print(renderable)
    return console.export_text()


_WORDS = ("line1", "a", "b", "tension", "1.80334e+06", "-735759", "(factors", "as",
          "commonly", "cited;", "not", "checked)", "x", "[N]", "Stationkeeping",
          "averyveryverylongwordwithoutanyspacesatallthatmustbefoldedsomewhere", "-", "")


def _text(rng: random.Random, words: int, long: bool = True) -> str:
    """Random words; ``long``: the very long word among them (folded in paragraphs)."""
    sep = rng.choice((" ", " ", "  ", ", "))
    pool = _WORDS if long else [w for w in _WORDS if len(w) < 20]
    return sep.join(rng.choice(pool) for _ in range(words))


def _grid(rng: random.Random) -> Grid:
    grid = Grid(_text(rng, rng.randint(0, 25)))
    n = rng.randint(1, 8)
    for _ in range(n):
        grid.add_column(_text(rng, rng.randint(0, 2), False), rng.choice(("left", "right")))
    for _ in range(rng.randint(0, 6)):
        cells = [_text(rng, rng.randint(0, 2), False) for _ in range(n)]
        if rng.random() < 0.2:  # a cell of several lines (the stiffness matrices)
            cells[rng.randrange(n)] = "\n".join(
                "  ".join(f"{rng.uniform(-1e5, 1e5):>11.4g}" for _ in range(3))
                for _ in range(3))
        grid.add_row(*cells)
    return grid


def test_random_blocks_match_rich() -> None:
    laid_out = tried = 0
    for seed in range(60):
        rng = random.Random(seed)
        blocks = [_grid(rng) if rng.random() < 0.6 else Para(_text(rng, rng.randint(0, 40)),
                                                             bold=rng.random() < 0.5)
                  for _ in range(rng.randint(1, 5))]
        for width in (30, 80, 110, 160):
            plain = plain_text(blocks, width)
            tried += 1
            if plain is not None:  # None: a table wider than the width, left to rich
                assert plain == _by_rich(blocks, width), (seed, width)
                laid_out += 1
    assert laid_out > tried / 2  # most were laid out without rich, not left to it


def test_a_table_too_wide_or_unusual_text_is_left_to_rich() -> None:
    wide = Grid("t")
    for k in range(12):
        wide.add_column(f"column {k}", "right")
    assert plain_text([wide], 80) is None
    assert plain_text([Para("a :warning: sign")], 80) is None  # rich makes it an emoji
    assert plain_text([Para("naïve")], 80) is None  # not ASCII: rich measures cells
    named = Grid("t")
    named.add_column("line")
    named.add_row("mooring – 1")
    assert plain_text([named], 80) is None
    assert summary_text({"kind": "statics", "lines": {"ligne été": {}}}) == \
        _by_rich(summary_blocks({"kind": "statics", "lines": {"ligne été": {}}}), 110)


def _statics_summary() -> dict:
    row = [1.5e4, -2.25e3, 7.1e2]
    return {"case": "oc3 [x]", "kind": "statics", "method": "newton", "converged": True,
            "iterations": 4, "units": "SI",
            "lines": {"line1": {"end_a": {"force": [-735759.0, 0.0, 0.0], "tension": 735759.0},
                                "end_b": {"force": [735759.0, 0.0, -535296.0],
                                          "tension": 909881.0},
                                "max_tension": 909881.0, "seabed_length": 135.405}},
            "points": {"anchor1": {"kind": "fixed", "position": [853.87, 0.0, -320.0],
                                   "stiffness": None},
                       "fairlead1": {"kind": "prescribed", "position": [5.2, 0.0, -70.0],
                                     "stiffness": [row, row, [None, 1.0, 2.0]]}},
            "design": {"standard": "API-RP-2SK", "edition": "3rd edition", "condition": "intact",
                       "analysis": "quasi-static", "basis": "largest tension of each line",
                       "title": "API RP 2SK, Design and Analysis of Stationkeeping Systems for "
                                "Floating Structures", "clause": "Section 6.4, Table 2",
                       "verified": False,
                       "lines": {"line1": {"passed": True, "MBL": 3.39727e6,
                                           "max_tension": 909881.0, "utilization": 0.2678,
                                           "safety_factor": 3.734,
                                           "required_safety_factor": 2.0,
                                           "design_utilization": 0.5357},
                                 "line2": {"passed": None, "max_tension": 1.0}}}}


def test_summaries_match_rich() -> None:
    """A run summary with statics (a design table, a stiffness matrix), dynamics and an
    offset analysis: the file's text and stdout's (160 columns) are rich's."""
    dynamics = {"kind": "dynamics", "message": "completed 6000 steps", "time_start": 0.0,
                "time_end": 300.0, "records": 6001,
                "lines": {"line1": {"end_a": {"max": 1.8e6, "min": 1.5e4, "mean": 7.7e5,
                                              "std": 6.7e5},
                                    "end_b": {"max": 1.9e6, "min": None}}},
                "points": {"fairlead1": {"kind": "prescribed", "min": [0.2, 0.0, -70.0],
                                         "max": [10.2, 0.0, -70.0]}},
                "envelope": {"start": 0.0, "records": 6001,
                             "max_element_tension": {"tension": 1.93e6, "line": "line1",
                                                     "arc_length": 879.6}},
                "counters": {"iterations": 18460, "steps": 6000}}
    offset = {"kind": "offset", "converged": True, "message": "done", "points": ["f1", "f2"],
              "stiffness": [[1.0] * 6] * 6, "reference": [0.0, 0.0, 0.0],
              "headings": [{"heading": 0.0, "offsets": [0.0, 5.0],
                            "restoring_force": [0.0, -1e5],
                            "fairlead_tension": {"line1": [1e6, 1.1e6]}}]}
    summary = {"case": "p1", "converged": True, "units": "SI",
               "analyses": [_statics_summary(), dynamics, offset,
                            {"kind": "modal", "converged": False, "message": "x"}]}
    for width in (110, 160):
        assert summary_text(summary, width) == _by_rich(summary_blocks(summary), width)
    assert plain_text(summary_blocks(summary), 110) is not None  # laid out without rich
