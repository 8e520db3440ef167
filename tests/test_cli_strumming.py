"""`kind: strumming` in a case file runs through `moorline run` after the in-line dynamics:
the results file gets a strumming group (lift coefficients, modal amplitudes) and a plot."""

import math
from dataclasses import replace

import numpy as np
import xarray as xr
from click.testing import CliRunner

from moorline.cli import cli
from moorline.io import load_case
from moorline.io.case_writer import write_case
from moorline.model import DynamicsSettings, OutputSettings, StaticsSettings, StrummingAnalysis
from moorline.verification.tuah_ex6 import (
    AREA,
    CA,
    DIAMETER,
    RHO,
    SPEED,
    discrete_string_modes,
    ex6_system,
)


def test_strumming_analysis_runs_from_a_case_file(tmp_path, undescribed):
    """The Ex6 string made neutrally buoyant (straight under gravity: closed-form modes): the
    file's modes, damping, shedding frequencies and initial lift against the closed form and
    the printed formulas."""
    system = ex6_system(gravity=32.174)
    neutral = replace(system.line_types["string"], mass_per_length=RHO * AREA)
    system = replace(system, line_types={"string": neutral})
    analyses = (StaticsSettings(start="straight"),
                DynamicsSettings(duration=2.0, dt=0.005, tolerance=1e-8),
                StrummingAnalysis(viscosity=1.13e-5, strouhal=0.18, n_modes=4))
    system = replace(system, analyses=analyses, output=OutputSettings(every=0.005))
    path = write_case(system, tmp_path / "ex6.yaml")
    assert load_case(path).analyses[2] == analyses[2]
    result = CliRunner().invoke(cli, ["run", str(path), "--out", str(tmp_path / "out"),
                                      "--quiet"])
    assert result.exit_code == 0, result.output
    folder = tmp_path / "out" / system.name
    assert (folder / "strumming.png").is_file()
    # moorline plot draws the strumming group again
    again = CliRunner().invoke(cli, ["plot", str(folder / "results.nc"), "--out",
                                     str(tmp_path / "again"), "--quiet"])
    assert again.exit_code == 0, again.output
    assert (tmp_path / "again" / "strumming.png").stat().st_size > 0
    assert undescribed(folder / "results.nc") == []
    with xr.open_dataset(folder / "results.nc", group="strumming") as ds:
        assert list(ds["mode"].values) == [1, 2, 3, 4]  # modes numbered from 1
        assert ds.attrs["status"] == "completed" and ds.attrs["success"] == 1
        # modes once, at the straight string at rest: the two polarizations of the first
        # two discrete string modes (closed form, added mass C_a = 1)
        closed, _ = discrete_string_modes(added_mass=True, structural_mass=RHO * AREA)
        assert np.allclose(ds["omega"].values, np.repeat(closed[:2], 2), rtol=1e-9)
        # eq. 3.2.b.8 with m = structural + added mass
        m = (RHO + RHO * CA) * AREA
        xi = 12 * RHO * DIAMETER / (math.pi * m) * np.sqrt(1.13e-5 / ds["omega"].values)
        assert np.allclose(ds["damping_ratio"].values, xi, rtol=1e-12)
        # at rest, straight, flow normal: |V_NR| = V; then w_s = 2 pi S_T |V_NR| / D
        speed = ds["normal_speed"].values
        assert np.allclose(speed[0], SPEED, rtol=1e-12)
        assert np.allclose(ds["strouhal_frequency"].values,
                           2 * math.pi * 0.18 * speed / DIAMETER, rtol=1e-12)
        cl = ds["lift_coefficient"].values
        assert cl.shape[1] == 4 and np.allclose(cl[0], 0.2)  # the limit cycle's C_L0
        # the wake stays near its limit cycle: |C_L| <= C_L0 + the forced part (< 10 %)
        assert np.isfinite(cl).all() and np.abs(cl).max() < 0.22


def test_strumming_options_round_trip_through_a_case_file(tmp_path):
    system = ex6_system(gravity=32.174)
    strumming = StrummingAnalysis(viscosity=1.13e-5, n_modes=0, refresh_every=1,
                                  min_reynolds=40.0, nonpositive_modes="keep",
                                  drag_damping=True, taut_axial=True,
                                  held_body_dofs=("yaw", "roll"))
    system = replace(system, analyses=(StaticsSettings(start="straight"), strumming))
    path = write_case(system, tmp_path / "ex6.yaml")
    assert load_case(path).analyses[1] == strumming


def test_bad_held_body_dof_names_the_field(tmp_path):
    path = tmp_path / "bad.yaml"
    strumming = StrummingAnalysis(viscosity=1e-5, held_body_dofs=("yaw",))
    system = replace(ex6_system(gravity=32.174), analyses=(StaticsSettings(), strumming))
    text = write_case(system, path).read_text()
    assert text.count("yaw") == 1
    path.write_text(text.replace("yaw", "twist"))
    result = CliRunner().invoke(cli, ["statics", str(path), "--out", str(tmp_path / "o")])
    assert result.exit_code == 2
    assert "held_body_dofs" in result.output and "bad.yaml" in result.output
