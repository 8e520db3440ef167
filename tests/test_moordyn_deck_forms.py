"""MoorDyn deck forms of OpenFAST's r-test decks (issue 14): early MoorDyn-F v2 body rows,
``EXTERNAL LOADS``, MoorDyn-F's seabed-friction options and FAST.Farm turbine attachments."""

from __future__ import annotations

import numpy as np
import pytest

from moorline.io.moordyn import read_moordyn, read_moordyn_deck

LEGACY_BODY_DECK = """\
--------------------- MoorDyn Input File ------------------------------------
an early MoorDyn-F v2 body row (OpenFAST r-test modules/moordyn/5MW_OC4 layout)
----------------------- LINE TYPES ------------------------------------------
LineType  Diam     MassDen    EA      BA/-zeta   EI   Cd   Ca   CdAx  CaAx
(-)       (m)      (kg/m)     (N)     (N-s/-)   (Nm^2) (-) (-)   (-)   (-)
main      0.0766   113.35     7.536E8  -1.0      0    2.0  0.8  0.4   0.25
----------------------------- BODIES ---------------------------------------
BodyID  X0  Y0  Z0  r0  p0  y0  Xcg  Ycg  Zcg  M     V    IX  IY  IZ  CdA  Ca
(-)     (m) (m) (m) (deg) (deg) (deg) (m) (m) (m) (kg) (m^3) (kg-m^2) (kg-m^2) (kg-m^2) (m^2) (-)
{body}
---------------------- POINTS --------------------------------
ID  Attachment  X  Y  Z  Mass  Volume  CdA  Ca
(-)  (-)  (m)  (m)  (m)  (kg)  (m^3)  (m^2)  (-)
1   Fixed   400   0    -200  0  0  0  0
2   Fixed  -400   0    -200  0  0  0  0
3   Body1   20    0    0     0  0  0  0
4   Body1  -20    0    0     0  0  0  0
---------------------- LINES --------------------------------------
ID  LineType  AttachA  AttachB  UnstrLen  NumSegs  Outputs
(-)  (-)  (-)  (-)  (m)  (-)  (-)
1   main   1   3   420   10   -
2   main   2   4   420   10   -
---------------------- SOLVER OPTIONS ---------------------------------------
200      WtrDpth
------------------------- need this line --------------------------------------
"""


@pytest.mark.parametrize(("row", "kind"), [
    ("1free  1 2 -10  0 0 0  0.1 0.2 -0.5  1000  2  10 20 30  0  0", "free"),
    ("1      1 2 -10  0 0 0  0.1 0.2 -0.5  1000  2  10 20 30  0  0", "free"),
    ("1Coupled 1 2 -10  0 0 0  0.1 0.2 -0.5  1000  2  10 20 30  0  0", "fixed"),
])
def test_early_moordyn_f_body_row(row, kind, tmp_path):
    """The 17-column body row of early MoorDyn-F v2 (OpenFAST MoorDyn.f90's "BODY LIST"
    reader: ``<ID><type> X0 Y0 Z0 r0 p0 y0 Xcg Ycg Zcg M V IX IY IZ CdA Ca``): each column lands
    where the deck puts it (a coupled body, held, keeps none of its own mass, as MoorDyn)."""
    deck = tmp_path / "legacy.dat"
    deck.write_text(LEGACY_BODY_DECK.format(body=row))
    (body,) = read_moordyn(deck).bodies.values()
    assert body.kind == kind
    assert body.position == (1.0, 2.0, -10.0)
    if kind == "free":
        assert body.mass == 1000.0
        assert body.center_of_gravity == pytest.approx((0.1, 0.2, -0.5), abs=1e-12)
        assert np.diag(np.array(body.inertia)) == pytest.approx([10.0, 20.0, 30.0], abs=1e-9)
        assert body.hydrostatics.volume == 2.0
    else:
        assert body.mass == 0.0


def test_early_body_row_with_missing_columns_is_refused(tmp_path):
    from moorline.errors import CaseError

    deck = tmp_path / "legacy.dat"
    deck.write_text(LEGACY_BODY_DECK.format(body="1free 1 2 -10 0 0 0 0.1 0.2 -0.5 1000 2"))
    with pytest.raises(CaseError, match="needs 17 columns"):
        read_moordyn_deck(deck)
