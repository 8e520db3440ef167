"""Dynamics features: time tables from CSV files in case files, HHT numerical damping,
force histories on free points."""

import textwrap

import numpy as np
import pytest

from moorline.io import load_case
from moorline.model import DynamicsSettings
from moorline.solvers.dynamics import simulate
from moorline.solvers.excitation import motion_value
from moorline.verification.tuah_ex4 import EA, L_HALF, MASS, ex4_system, start_positions

CASE = """
name: table
units: SI
environment: {{depth: 100}}
line_types:
  rope: {{diameter: 0.05, mass_per_length: 5, EA: 1.0e7, Cd: 1.2, BA: -0.5}}
points:
  anchor: {{kind: fixed, position: [-150, 0, -100]}}
  top: {{kind: prescribed, position: [0, 0, -10], motion: {{kind: table, file: {file}}}}}
  buoy: {{kind: free, position: [-75, 0, -60], volume: 0.5,
          force_history: {{kind: harmonic, amplitude: [0, 0, 200], period: 5}}}}
lines:
  a: {{type: rope, length: 100, segments: 8, end_a: anchor, end_b: buoy}}
  b: {{type: rope, length: 90, segments: 8, end_a: buoy, end_b: top}}
analyses:
  - {{kind: statics}}
  - {{kind: dynamics, duration: 4, dt: 0.05}}
"""


def test_csv_time_table_drives_a_prescribed_point(tmp_path):
    table = tmp_path / "surge.csv"
    table.write_text("t,x,y,z\n0,0,0,0\n2,1.0,0,0\n4,1.0,0.5,0\n", encoding="utf-8")
    path = tmp_path / "case.yaml"
    path.write_text(textwrap.dedent(CASE.format(file="surge.csv")), encoding="utf-8")
    system = load_case(path)
    motion = system.points["top"].motion
    assert motion.times == (0.0, 2.0, 4.0)
    # The cubic Hermite interpolant (issue 14), by hand: y has knot derivatives 0 (next to
    # the constant interval) and (3 * 0.25 - 0) / 2 = 0.375 at the end; at t = 3 (s = 1/2)
    # y = 0.5 h01 + 2 * 0.375 h11 = 0.25 - 0.09375, y' = (1.5 * 0.5 - 0.25 * 0.75) / 2.
    # x: derivatives 0.75 and 0 on [0, 2]; held (1, derivative 0) on [2, 4].
    d, v, _ = motion_value(motion, 3.0)
    assert np.allclose(d, [1.0, 0.15625, 0.0]) and np.allclose(v, [0.0, 0.28125, 0.0])
    result = simulate(system, system.analyses[1], output_every=0.5)
    top = result.point_history("top")
    assert np.allclose(top[-1], np.array([0.0, 0.0, -10.0]) + [1.0, 0.5, 0.0], atol=1e-12)
    # t = 1 (s = 1/2): x = 2 * 0.75 h10 + h01 = 0.1875 + 0.5
    assert np.allclose(top[result.time == 1.0][0], [0.6875, 0.0, -10.0], atol=1e-12)


def test_bad_csv_table_is_a_case_error(tmp_path):
    from moorline.errors import CaseError

    (tmp_path / "bad.csv").write_text("0,0,0\n1,2,3\n", encoding="utf-8")
    path = tmp_path / "case.yaml"
    path.write_text(textwrap.dedent(CASE.format(file="bad.csv")), encoding="utf-8")
    with pytest.raises(CaseError, match="points.top.motion.file"):
        load_case(path)


def _string_energy(result):
    node = result.mesh.point_node[result.mesh.point_index("mass")]
    v = result.velocities[:, node]
    return 0.5 * MASS * (v**2).sum(axis=1) + (0.5 * EA * (result.tension / EA) ** 2
                                              * L_HALF).sum(axis=1)


def test_hht_dissipates_where_newmark_conserves():
    """HHT-alpha damps: the string of Tuah Ex4 (omega dt = 0.24) loses energy with
    alpha = -0.2, the average-acceleration Newmark rule keeps it."""
    system = ex4_system()
    x0 = start_positions(system)
    common = dict(duration=2.0, dt=0.01, tolerance=1e-10, max_iterations=30)
    newmark = simulate(system, DynamicsSettings(**common), initial=x0, output_every=0.01)
    hht = simulate(system, DynamicsSettings(**common, scheme="hht", alpha=-0.2), initial=x0,
                   output_every=0.01)
    e_newmark, e_hht = _string_energy(newmark), _string_energy(hht)
    assert abs(e_newmark[-1] / e_newmark[0] - 1) < 1e-3  # measured 4e-5
    assert e_hht[-1] / e_hht[0] < 0.97  # measured 0.945 after 7.5 periods
    assert e_hht[-1] < e_newmark[-1] - 0.03 * e_newmark[0]


def test_force_history_on_a_free_point_moves_it_at_the_forcing_period(tmp_path):
    table = tmp_path / "still.csv"
    table.write_text("0,0,0,0\n1,0,0,0\n", encoding="utf-8")
    path = tmp_path / "case.yaml"
    text = CASE.format(file="still.csv").replace("duration: 4", "duration: 20")
    path.write_text(textwrap.dedent(text), encoding="utf-8")
    system = load_case(path)
    result = simulate(system, system.analyses[1], output_every=0.05)
    z = result.point_history("buoy")[:, 2]
    late = result.time > 10.0
    spectrum = np.abs(np.fft.rfft(z[late] - z[late].mean()))
    freqs = np.fft.rfftfreq(late.sum(), 0.05)
    assert freqs[np.argmax(spectrum)] == pytest.approx(1 / 5.0, abs=1 / (late.sum() * 0.05))
    assert np.isfinite(z).all()
