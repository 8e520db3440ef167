"""Frequency-domain stochastic analysis (Tuah 1982 ch. 5): statistical drag linearization,
Foss decoupling, response spectra and time series."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
import xarray as xr
from click.testing import CliRunner

from moorline.cli import cli
from moorline.errors import MoorlineError
from moorline.io import load_case
from moorline.io.case_writer import write_case
from moorline.model import StaticsSettings, StochasticSettings, Waves
from moorline.solvers.statics import solve_statics
from moorline.solvers.stochastic import solve_stochastic
from moorline.verification.stochastic_riser import MID_NODE, riser_system


@pytest.fixture(scope="module")
def riser():
    system = riser_system()
    return system, solve_statics(system)


def test_series_variance_is_the_spectral_variance(riser):
    """DSA: over one record each component contributes exactly |H|^2 S d_omega."""
    system, static = riser
    r = solve_stochastic(system, StochasticSettings(), static)
    assert r.displacement.shape == (len(r.time), static.mesh.n_nodes, 3)
    assert np.allclose(r.displacement.std(axis=0), r.displacement_std, rtol=1e-9, atol=1e-15)
    assert np.allclose(r.tension.std(axis=0), r.tension_std, rtol=1e-9)
    assert np.allclose(r.tension.mean(axis=0), static.tension)
    assert len(r.time) == 1024 and r.time[1] == pytest.approx(0.25)  # Tuah's 2N for 200


def test_linearization_is_a_fixed_point(riser):
    """At convergence the relative-velocity sigmas recomputed from the response are those
    the drag was linearized with (within the tolerance)."""
    system, static = riser
    tight = solve_stochastic(system, StochasticSettings(tolerance=1e-10), static)
    assert tight.history[-1] <= 1e-10 and tight.iterations < 30
    loose = solve_stochastic(system, StochasticSettings(tolerance=0.01), static)
    assert np.allclose(loose.sigma_normal, tight.sigma_normal, rtol=0.02)
    # the structure moves with the water: the relative velocity is below the fluid's alone
    first = solve_stochastic(system, StochasticSettings(max_iterations=1, tolerance=1e9),
                             static)
    assert np.all(tight.sigma_normal <= first.sigma_normal * 1.0001)


def test_truncated_modes_approximate_all(riser):
    system, static = riser
    full = solve_stochastic(system, StochasticSettings(), static)
    few = solve_stochastic(system, StochasticSettings(n_modes=12), static)
    assert few.counters["modes"] == 12
    assert few.displacement_std[MID_NODE, 0] == pytest.approx(
        full.displacement_std[MID_NODE, 0], rel=0.02)


def test_default_solves_the_full_system_and_foss_over_all_modes_agrees(riser):
    """``n_modes`` 0 (all modes, the default) solves ``(K - w^2 M + i w C) U = F`` at every
    frequency (banded, :mod:`moorline.solvers.frequency_sweep`); Foss's decoupling over every
    mode is the same linear algebra (round-off: eps over the relative gap of the closest
    poles, 1e-8 here)."""
    system, static = riser
    default = solve_stochastic(system, StochasticSettings(), static)
    foss = solve_stochastic(system, StochasticSettings(n_modes=static.mesh.n_dofs), static)
    assert default.counters["modes"] == 0 and foss.counters["modes"] == static.mesh.n_dofs
    assert default.counters["pivoted_frequencies"] == 0
    scale = np.abs(default.displacement_transfer).max()
    floor = np.finfo(float).eps / foss.counters["pole_gap"]
    assert np.abs(foss.displacement_transfer - default.displacement_transfer).max() \
        <= max(1e-8, 100 * floor) * scale


def test_frequency_sweep_against_sparse_lu_and_its_pivoting_fallback():
    """The banded sweep (random order, per-frequency terms) against scipy's sparse LU at
    every frequency; a zero leading pivot (``K = [[0, 1], [1, 0]]``, no mass or damping)
    is solved again with pivoting: ``x = (F_1, F_0)``."""
    import scipy.sparse as sp
    from scipy.sparse.linalg import spsolve

    from moorline.solvers.frequency_sweep import FrequencySweep

    rng = np.random.default_rng(3)
    n = 30
    lap = sp.diags([-np.ones(n - 1), 2.5 * np.ones(n), -np.ones(n - 1)], [-1, 0, 1])
    perm = rng.permutation(n)
    K = (1e4 * lap).tocsr()[perm][:, perm]
    M = sp.diags(rng.uniform(1, 2, n)).tocsr()[perm][:, perm]
    C = (30.0 * lap).tocsr()[perm][:, perm]
    rows, cols = np.array([perm[3], perm[3], perm[4]]), np.array([perm[3], perm[4], perm[3]])
    omega = np.linspace(0.05, 300.0, 57)
    extra = rng.normal(size=(len(omega), 3)) * (1 + 1j) * 100
    F = rng.normal(size=(len(omega), n)) + 1j * rng.normal(size=(len(omega), n))
    sweep = FrequencySweep(K, M, (rows, cols))
    U = sweep.solve(C, F, omega, extra)
    assert sweep.bw <= 3  # a chain plus one extra coupling, reordered into a band
    for j, w in enumerate(omega):
        A = (K - w * w * M + 1j * w * C).tolil()
        for r, c, v in zip(rows, cols, extra[j], strict=True):
            A[r, c] += v
        ref = spsolve(A.tocsc(), F[j])
        assert np.allclose(U[j], ref, rtol=1e-10, atol=1e-12 * np.abs(ref).max())
    swap = FrequencySweep(sp.csr_matrix(np.array([[0.0, 1.0], [1.0, 0.0]])),
                          sp.csr_matrix((2, 2)))
    x = swap.solve(sp.csr_matrix((2, 2)), np.array([[1.0 + 2j, 3.0]]), np.array([1.0]))
    assert swap.refactored == 1 and np.allclose(x, [[3.0, 1.0 + 2j]], rtol=1e-15)


def test_nsa_changes_the_series_not_the_statistics(riser):
    system, static = riser
    nsa = replace(system, environment=replace(
        system.environment, waves=replace(system.environment.waves, amplitudes="nsa")))
    dsa_r = solve_stochastic(system, StochasticSettings(), static)
    nsa_r = solve_stochastic(nsa, StochasticSettings(), static)
    assert np.allclose(nsa_r.displacement_std, dsa_r.displacement_std)
    assert not np.allclose(nsa_r.displacement, dsa_r.displacement)


def test_needs_a_random_sea(riser):
    """(A current is supported: tests/test_stochastic_current.py.)"""
    system, static = riser
    calm = replace(system, environment=replace(system.environment, waves=Waves()))
    with pytest.raises(MoorlineError, match="random sea"):
        solve_stochastic(calm, StochasticSettings(), static)


def test_body_system_the_disc_follows_long_waves():
    """Tuah's Example 5 disc in the Hurricane Carla sea: body motions over the unknowns of
    the master-slave transformation; in the long-wave limit the disc heaves with the
    surface; Foss (all modes) equals the direct solve with bodies too; the keel node moves
    with the disc."""
    from moorline.verification import tuah_ex5, tuah_ex5_random

    system, static = tuah_ex5_random.random_system()
    # Foss over all modes against the direct solve, one linearization step each (the same
    # damping): converged, the two can stop an iteration apart, Foss's round-off (eps over
    # the poles' relative gap, 1e-4) making the near-zero sway sigmas noisy
    one = {"tolerance": 1e9}
    foss_1, direct_1 = (solve_stochastic(system, StochasticSettings(**kw, **one), static)
                        for kw in ({"n_modes": 10_000}, {"method": "direct"}))
    assert foss_1.counters["modes"] > 0 and direct_1.counters["modes"] == 0
    assert np.allclose(foss_1.body_transfer, direct_1.body_transfer, rtol=1e-7,
                       atol=1e-9 * np.abs(direct_1.body_transfer).max())
    foss = solve_stochastic(system, StochasticSettings(), static)  # all modes: direct solve
    assert foss.body_names == (tuah_ex5.BODY,)
    heave = np.abs(foss.body_transfer[0, 0, 2])  # 0.0245 rad/s: a very long wave
    assert heave == pytest.approx(1.0, abs=0.05)
    assert np.allclose(foss.body_motion.std(axis=0), foss.body_std, rtol=1e-9)
    # the fairlead (keel) node's heave is the disc's heave plus pitch times its arm
    keel = static.mesh.slave_node[0]
    arm = static.positions[keel] - static.body_pose[0, :3]  # world axes, at the static pose
    H = foss.body_transfer[:, 0]
    expected = H[:, 2] + np.cross(H[:, 3:], arm)[:, 2]
    assert np.allclose(foss.displacement_transfer[:, keel, 2], expected, rtol=1e-6,
                       atol=1e-9)
    ds = foss.to_xarray()
    assert ds["body_std"].dims == ("body", "dof") and list(ds["dof"].values)[4] == "pitch"


def test_stochastic_analysis_from_a_case_file(tmp_path, undescribed):
    system = replace(riser_system(), analyses=(StaticsSettings(),
                                               StochasticSettings(method="direct")))
    path = write_case(system, tmp_path / "riser.yaml")
    assert load_case(path).analyses[1] == StochasticSettings(method="direct")
    result = CliRunner().invoke(cli, ["run", str(path), "--out", str(tmp_path / "out"),
                                      "--quiet", "--json"])
    assert result.exit_code == 0, result.output
    folder = tmp_path / "out" / system.name
    assert (folder / "stochastic.png").stat().st_size > 0
    assert undescribed(folder / "results.nc") == []
    with xr.open_dataset(folder / "results.nc", group="stochastic") as ds:
        assert ds.attrs["status"] == "converged" and ds.attrs["success"] == 1
        assert ds["displacement_spectrum"].dims == ("omega", "node", "xyz")
        assert ds.attrs["method"] == "direct"
        assert float(ds["tension_std"].max()) > 0
    again = CliRunner().invoke(cli, ["plot", str(folder / "results.nc"), "--out",
                                     str(tmp_path / "again"), "--quiet"])
    assert again.exit_code == 0, again.output
    assert (tmp_path / "again" / "stochastic.png").stat().st_size > 0


def test_exciting_force_tables_in_a_random_sea_time_and_frequency_domain_agree():
    """A body's exciting-force table in a random sea: the time-domain sum over the wave
    components (coupled dynamics) equals the frequency-domain loads' series at any time."""
    from moorline.model.body import WaveExcitation
    from moorline.solvers.body_model import _exciting_terms
    from moorline.solvers.stochastic import _LinearModel
    from moorline.verification import tuah_ex5, tuah_ex5_random
    from moorline.waves import fluid_field_from_environment

    system, static = tuah_ex5_random.random_system()
    w_tab = np.linspace(0.05, 3.0, 30)
    amp = np.column_stack([4000 * np.exp(-w_tab), 0 * w_tab, 5000 / (1 + w_tab**2),
                           0 * w_tab, 300 * w_tab, 0 * w_tab])
    phase = np.column_stack([90 - 10 * w_tab, 0 * w_tab, -20 * w_tab, 0 * w_tab,
                             45 + 0 * w_tab, 0 * w_tab])
    table = WaveExcitation(tuple(w_tab), tuple(map(tuple, amp)), tuple(map(tuple, phase)))
    body = replace(system.bodies[tuah_ex5.BODY], excitation=table, wave_loads=False)
    system = replace(system, bodies={tuah_ex5.BODY: body})
    r = solve_stochastic(system, StochasticSettings(), static)
    model = _LinearModel(system, static, StochasticSettings())
    fd = model.body_kinematics(r.omega).fixed[:, 0]  # (n_w, 6) per unit amplitude
    field = fluid_field_from_environment(system.environment)
    a, w, shift, amp_i, phase_i, _ = _exciting_terms(table, field, static.body_pose[0, :3])
    for t in (0.0, 17.3, 140.9):
        td = (a[:, None] * amp_i * np.cos((w * t - shift)[:, None] + phase_i)).sum(axis=0)
        series = 2.0 * np.real((fd * (r.wave_amplitude * np.exp(1j * r.omega * t))[:, None])
                               .sum(axis=0))
        assert np.allclose(td, series, atol=1e-9 * np.abs(td).max())


def test_point_buoy_loads_against_the_time_domain(monkeypatch):
    """A buoy (free point with volume, added mass and drag) at mid-depth of the riser: its
    fluid inertia and linearized drag enter the frequency domain as in the time domain; its
    in-band motion agrees with the nonlinear time-domain run in the same sea."""
    from moorline.model import DynamicsSettings, Line, Point
    from moorline.solvers.dynamics import simulate
    from moorline.verification import stochastic_riser as sr

    base = sr.riser_system(Cd=0.3)
    buoy = Point("buoy", "free", (5.0, 0.0, -27.5), mass=50.0, volume=0.4, Ca=0.5, Cd=0.6,
                 drag_area=0.5)
    lines = {"lower": Line("lower", "rope", sr.LENGTH / 2, 10, "anchor", "buoy"),
             "upper": Line("upper", "rope", sr.LENGTH / 2, 10, "buoy", "top")}
    system = replace(base, points={**base.points, "buoy": buoy}, lines=lines)
    static = solve_statics(system)
    fd = solve_stochastic(system, StochasticSettings(), static)
    node = static.mesh.point_node[static.mesh.point_index("buoy")]
    td = simulate(system, DynamicsSettings(duration=2 * sr.RECORD, dt=sr.DT, ramp_time=20.0),
                  initial=static, output_every=sr.DT)
    second = td.time >= sr.RECORD - 1e-9
    n = int(round(sr.RECORD / sr.DT))
    X_td = np.fft.rfft(td.positions[second, node, 0][:n])[1:len(fd.omega) + 1] * (2.0 / n)
    X_fd = 2.0 * fd.displacement_transfer[:, node, 0] * fd.wave_amplitude
    band = fd.wave_spectrum >= 0.05 * fd.wave_spectrum.max()
    rms_td = np.sqrt(0.5 * np.sum(np.abs(X_td[band]) ** 2))
    rms_fd = np.sqrt(0.5 * np.sum(np.abs(X_fd[band]) ** 2))
    assert rms_fd == pytest.approx(rms_td, rel=0.05)
    # without the buoy's wave loads (inertia and drag) the answer is off: they matter
    import moorline.solvers.stochastic as stochastic

    class NoPointLoads(stochastic._PointWaves):
        def __init__(self, mesh, *args):
            super().__init__(mesh, *args)
            self.nodes = np.zeros(0, dtype=int)

    monkeypatch.setattr(stochastic, "_PointWaves", NoPointLoads)
    bare = solve_stochastic(system, StochasticSettings(), static)
    X_bare = 2.0 * bare.displacement_transfer[:, node, 0] * bare.wave_amplitude
    rms_bare = np.sqrt(0.5 * np.sum(np.abs(X_bare[band]) ** 2))
    assert abs(rms_bare / rms_td - 1) > 2 * abs(rms_fd / rms_td - 1)


def test_axial_dashpot_against_the_time_domain():
    """The lines' Kelvin-Voigt dashpot ``BA`` in the damping and the tension transfer: the
    inertia-dominated riser (Cd 0.3) with BA = 2e7 N s, where the dashpot's tension
    ``omega BA / EA`` is of the order of the elastic part in the wave band (the frequency
    domain without it is 18 % low), against the nonlinear time domain in the same DSA
    realization: the top element's tension within the wave band, from the FFT of the second
    of two records. Tolerance 3 %: the in-band agreement of this riser without a dashpot
    (``moorline verify stochastic-riser``, Cd 0.3 row; 1.1 % here at BA 0)."""
    from moorline.model import DynamicsSettings
    from moorline.solvers.dynamics import simulate
    from moorline.verification import stochastic_riser as riser

    base = riser_system(Cd=0.3)
    system = replace(base, line_types={"rope": replace(base.line_types["rope"], BA=2.0e7)})
    static = solve_statics(system)
    fd = solve_stochastic(system, StochasticSettings(), static)
    td = simulate(system, DynamicsSettings(duration=2 * riser.RECORD, dt=riser.DT,
                                           ramp_time=20.0), initial=static, output_every=riser.DT)
    second = td.time >= riser.RECORD - 1e-9
    top, n = static.mesh.n_elements - 1, int(round(riser.RECORD / riser.DT))
    T_td = np.fft.rfft(td.tension[second, top][:n])[1:len(fd.omega) + 1] * (2.0 / n)
    T_fd = 2.0 * fd.tension_transfer[:, top] * fd.wave_amplitude
    band = fd.wave_spectrum >= 0.05 * fd.wave_spectrum.max()
    rms_td = np.sqrt(0.5 * np.sum(np.abs(T_td[band]) ** 2))
    rms_fd = np.sqrt(0.5 * np.sum(np.abs(T_fd[band]) ** 2))
    assert rms_fd == pytest.approx(rms_td, rel=0.03)
