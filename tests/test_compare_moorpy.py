"""The OC3 line against MoorPy (optional [compare] extra): an independent code, the MoorPy
model built from the same moorline system (:mod:`moorline.compare.moorpy_runner`)."""

import numpy as np
import pytest

from moorline.solvers.statics import solve_statics
from moorline.verification.oc3_line import oc3_system

pytestmark = pytest.mark.compare


def test_oc3_line_end_forces_match_moorpy_catenary():
    pytest.importorskip("moorpy")
    from moorline.compare.moorpy_runner import end_forces, solve_moorpy

    _, ref_b = end_forces(solve_moorpy(oc3_system(20)), 0)
    fair = solve_statics(oc3_system(200)).end_force("line1", "b")
    # converged FE forces differ from the rigid-seabed catenary by 8e-5 (penalty seabed)
    assert fair[0] == pytest.approx(ref_b[0], rel=5e-4)
    assert fair[2] == pytest.approx(ref_b[2], rel=5e-4)
    assert np.linalg.norm(fair) == pytest.approx(np.linalg.norm(ref_b), rel=5e-4)
