"""The OC3 line against MoorPy (optional [compare] extra): an independent code."""

import numpy as np
import pytest

from moorline.solvers.statics import solve_statics
from moorline.verification.oc3_line import (
    ANCHOR_R,
    DEPTH,
    DIAMETER,
    EA,
    FAIR_R,
    FAIR_Z,
    LENGTH,
    MASS,
    RHO,
    G,
    oc3_system,
)

pytestmark = pytest.mark.compare


def test_oc3_line_end_forces_match_moorpy_catenary():
    catenary = pytest.importorskip("moorpy.Catenary").catenary
    w = (MASS - RHO * np.pi * DIAMETER**2 / 4) * G
    fAH, fAV, fBH, fBV, _ = catenary(ANCHOR_R - FAIR_R, FAIR_Z + DEPTH, LENGTH, EA, w, CB=0,
                                     Tol=1e-10, MaxIter=200)
    result = solve_statics(oc3_system(200))
    fair = result.end_force("line1", "b")
    # MoorPy returns the forces on the line's ends; the line pulls the fairlead by the opposite
    assert -fair[0] == pytest.approx(-fBH, rel=5e-4)
    assert -fair[2] == pytest.approx(-fBV, rel=5e-4)
