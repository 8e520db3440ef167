"""Modal analysis: verification rows, M-orthonormal modes, counts and ordering, band search,
the ``moorline modes --json`` contract and ``kind: modal`` through ``moorline run``."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml
from click.testing import CliRunner

from moorline.cli import cli
from moorline.io import load_case
from moorline.model import ModalSettings
from moorline.solvers import modal
from moorline.solvers.assembly import gather_free
from moorline.solvers.modal import modal_matrices, solve_modes
from moorline.solvers.statics import solve_statics
from moorline.verification import CASES, run_cases
from moorline.verification.modes_string import exact_frequency, string_system

ROOT = Path(__file__).resolve().parents[1]
OC3 = ROOT / "cases" / "oc3_line.yaml"
needs_oc3 = pytest.mark.skipif(not OC3.is_file(), reason="cases/oc3_line.yaml not present")


@pytest.mark.parametrize("case", ["modes-string", "modes-irvine"])
def test_verification_rows_pass(case: str) -> None:
    assert case in CASES
    rows = run_cases([case])
    assert rows
    failed = [r for r in rows if r.status == "fail"]
    assert not failed, "\n".join(f"{r.quantity}: ref {r.reference:.6g}, got {r.computed:.6g}"
                                 for r in failed)


def _modal_vectors(result, mesh) -> np.ndarray:
    return np.stack([gather_free(s, mesh.dof_of_node) for s in result.mode_shapes], axis=1)


@pytest.fixture(scope="module")
def oc3_statics():
    if not OC3.is_file():
        pytest.skip("cases/oc3_line.yaml not present")
    system = load_case(OC3)
    return system, solve_statics(system)


@needs_oc3
@pytest.mark.parametrize("mass", ["lumped", "consistent"])
@pytest.mark.parametrize("sparse", [False, True])
def test_modes_are_mass_orthonormal(oc3_statics, monkeypatch, mass: str, sparse: bool) -> None:
    """phi^T M phi = I and phi^T K phi = diag(omega^2), with added mass and seabed contact;
    dense (LAPACK) and shift-invert (ARPACK) paths."""
    system, statics = oc3_statics
    if sparse:
        monkeypatch.setattr(modal, "DENSE_LIMIT", 0)
    settings = ModalSettings(n_modes=8, mass=mass)  # type: ignore[arg-type]
    result = solve_modes(system, settings, statics)
    assert result.solver == ("shift-invert" if sparse else "dense")
    K, M = modal_matrices(statics.mesh, statics.positions, settings)
    phi = _modal_vectors(result, statics.mesh)
    np.testing.assert_allclose(phi.T @ (M @ phi), np.eye(8), atol=1e-9)
    stiffness = phi.T @ (K @ phi)
    scale = result.omega[-1] ** 2
    np.testing.assert_allclose(stiffness, np.diag(result.omega**2), atol=1e-8 * scale)


@needs_oc3
def test_an_eigensolver_that_does_not_converge_is_a_returned_failure(oc3_statics,
                                                                     monkeypatch) -> None:
    """ARPACK giving up is a result with success False and ARPACK's reason, not an
    exception out of the solver."""
    import scipy.sparse.linalg as spla

    system, statics = oc3_statics
    monkeypatch.setattr(modal, "DENSE_LIMIT", 0)

    def no_convergence(*args, **kwargs):
        raise spla.ArpackNoConvergence("no convergence (maxiter)", np.zeros(0),
                                       np.zeros((0, 0)))

    monkeypatch.setattr(spla, "eigsh", no_convergence)
    result = solve_modes(system, ModalSettings(n_modes=4), statics)
    assert not result.success and result.status == "failed"
    assert "ARPACK did not converge" in result.message and result.n_modes == 0


@needs_oc3
def test_sparse_and_dense_agree(oc3_statics, monkeypatch) -> None:
    system, statics = oc3_statics
    dense = solve_modes(system, ModalSettings(n_modes=10), statics)
    monkeypatch.setattr(modal, "DENSE_LIMIT", 0)
    sparse = solve_modes(system, ModalSettings(n_modes=10), statics)
    np.testing.assert_allclose(sparse.omega, dense.omega, rtol=1e-9)
    assert sparse.dominant == dense.dominant


def test_mode_count_and_ordering() -> None:
    system = string_system(elements=12)
    result = solve_modes(system, ModalSettings(n_modes=7))
    assert result.n_modes == 7
    assert result.mode_shapes.shape == (7, result.mesh.n_nodes, 3)
    assert np.all(np.diff(result.omega) >= 0)
    np.testing.assert_allclose(result.period, 2 * np.pi / result.omega)
    np.testing.assert_allclose(result.frequency_hz, result.omega / (2 * np.pi))
    # repeated frequencies (two polarizations) come out separated by direction
    assert result.dominant[:4] == ("y", "z", "y", "z")
    np.testing.assert_allclose(result.participation.sum(axis=1), 1.0)
    # fixed ends do not move
    assert np.all(result.mode_shapes[:, result.mesh.point_node] == 0.0)


@pytest.mark.parametrize("sparse", [False, True])
def test_band_returns_every_mode_in_band(monkeypatch, sparse: bool) -> None:
    system = string_system(elements=40)
    everything = solve_modes(system, ModalSettings(n_modes=30))
    low, high = 5.0, 13.0
    expected = everything.omega[(everything.omega >= low) & (everything.omega <= high)]
    if sparse:
        monkeypatch.setattr(modal, "DENSE_LIMIT", 0)
    band = solve_modes(system, ModalSettings(band=(low, high)))
    assert band.solver == ("shift-invert" if sparse else "dense")
    np.testing.assert_allclose(band.omega, expected, rtol=1e-9)
    assert len(expected) == 6  # omega_2, omega_3 and omega_4 of the string, two each


def test_effective_masses_sum_to_the_total_mass() -> None:
    """With all modes, sum_k (phi_k^T M r_d)^2 = r_d^T M r_d (mass completeness)."""
    system = string_system(elements=10)
    n_dofs = 3 * 9
    result = solve_modes(system, ModalSettings(n_modes=n_dofs, added_mass=False))
    assert result.n_modes == n_dofs
    free_mass = 9 * (result.mesh.length0[0] * 10.0)
    np.testing.assert_allclose(result.effective_mass.sum(axis=0), free_mass, rtol=1e-9)


def test_added_mass_lowers_transverse_frequencies() -> None:
    air = solve_modes(string_system(elements=20), ModalSettings(n_modes=2))
    water = solve_modes(string_system(elements=20, water_density=1025.0),
                        ModalSettings(n_modes=2))
    ratio = water.omega[0] / air.omega[0]
    assert ratio == pytest.approx(exact_frequency(1, 1025.0) / exact_frequency(1), rel=1e-9)
    no_added = solve_modes(string_system(elements=20, water_density=1025.0),
                           ModalSettings(n_modes=2, added_mass=False))
    np.testing.assert_allclose(no_added.omega, air.omega, rtol=1e-12)


def test_to_xarray() -> None:
    result = solve_modes(string_system(elements=8), ModalSettings(n_modes=3))
    ds = result.to_xarray()
    assert ds["mode_shape"].dims == ("mode", "node", "xyz")
    assert list(ds["mode"].values) == [1, 2, 3]
    assert ds.attrs["analysis"] == "modal"
    assert ds.attrs["case"] == "modes-string"
    assert ds.attrs["units"] == "SI"
    assert "moorline_version" in ds.attrs
    assert ds["omega"].attrs["units"] == "rad/s"
    assert list(ds["dominant"].values) == list(result.dominant)


# ----------------------------------------------------------------------------- command line


def _invoke(*args: object):
    return CliRunner().invoke(cli, [str(a) for a in args])


@needs_oc3
def test_modes_json_contract(tmp_path: Path) -> None:
    result = _invoke("modes", OC3, "--n", 6, "--out", tmp_path, "--json", "--quiet")
    assert result.exit_code == 0, result.output
    data = json.loads(result.stdout)
    assert set(data) == {"case", "converged", "status", "message", "modes"}
    assert data["case"] == "oc3-line" and data["converged"] and data["status"] == "converged"
    modes = data["modes"]
    assert [m["index"] for m in modes] == [1, 2, 3, 4, 5, 6]
    for mode in modes:
        assert set(mode) == {"index", "omega", "period", "dominant"}
        assert mode["dominant"] in ("x", "y", "z")
        assert mode["period"] == pytest.approx(2 * math.pi / mode["omega"])
    omegas = [m["omega"] for m in modes]
    assert omegas == sorted(omegas) and omegas[0] > 0
    directory = tmp_path / "oc3-line"
    assert (directory / "mode_shapes.png").stat().st_size > 0
    with xr.open_dataset(directory / "results.nc", group="modal") as ds:
        np.testing.assert_allclose(ds["omega"].values, omegas)
        assert list(ds["mode"].values) == [m["index"] for m in modes]  # one numbering
    # a second run replaces the modal group and keeps the others
    assert _invoke("statics", OC3, "--out", tmp_path, "--quiet").exit_code == 0
    again = _invoke("modes", OC3, "--n", 3, "--out", tmp_path, "--quiet")
    assert again.exit_code == 0, again.output
    assert "omega [rad/s]" in again.stdout
    with xr.open_dataset(directory / "results.nc", group="modal") as ds:
        assert ds.sizes["mode"] == 3
    with xr.open_dataset(directory / "results.nc", group="statics") as ds:
        assert ds.sizes["element"] == 20


@needs_oc3
def test_modal_case_runs(tmp_path: Path, undescribed) -> None:
    case = yaml.safe_load(OC3.read_text())
    case["analyses"] = [{"kind": "statics"},
                        {"kind": "modal", "n_modes": 5, "mass": "consistent"},
                        {"kind": "modal", "band": [0.5, 1.2], "added_mass": False}]
    path = tmp_path / "oc3_modal.yaml"
    path.write_text(yaml.safe_dump(case))
    system = load_case(path)
    settings = system.analyses[1]
    assert isinstance(settings, ModalSettings)
    assert (settings.n_modes, settings.mass, settings.added_mass) == (5, "consistent", True)
    assert system.analyses[2].band == (0.5, 1.2)
    result = _invoke("run", path, "--out", tmp_path, "--json", "--quiet")
    assert result.exit_code == 0, result.output
    data = json.loads(result.stdout)
    assert [a["kind"] for a in data["analyses"]] == ["statics", "modal", "modal"]
    assert len(data["analyses"][1]["modes"]) == 5
    assert all(0.5 <= m["omega"] <= 1.2 for m in data["analyses"][2]["modes"])
    directory = tmp_path / "oc3-line"
    assert (directory / "modal1_mode_shapes.png").is_file()
    assert undescribed(directory / "results.nc") == []
    with xr.open_dataset(directory / "results.nc", group="modal2") as ds:
        assert ds.attrs["setting_added_mass"] == 0
        assert list(ds.attrs["setting_band"]) == [0.5, 1.2]


def test_modes_of_a_moored_body_include_its_six_rigid_body_modes():
    """The Wang box on its four lines: each of the body's six dofs dominates a mode; the heave
    mode lies between the quasi-static estimate (lines with their sag compliance, the
    condensed 6x6 mooring stiffness) and the estimate with the sag frozen (axial EA/L only):
    above the lines' own transverse frequencies their sag cannot follow the body, so the
    lines stiffen dynamically towards EA/L."""
    import numpy as np

    from moorline.io import load_case
    from moorline.model import ModalSettings
    from moorline.solvers.modal import solve_modes
    from moorline.solvers.statics import solve_statics
    from moorline.solvers.stiffness import group_stiffness

    system = load_case("cases/wang_box.yaml")
    statics = solve_statics(system)
    result = solve_modes(system, ModalSettings(n_modes=120), statics)  # all: dense solver
    labels = set(result.dominant)
    for dof in ("surge", "sway", "heave", "roll", "pitch", "yaw"):
        assert f"box {dof}" in labels, (dof, result.dominant)
    heave = result.omega[result.dominant.index("box heave")]
    mesh = statics.mesh
    attached = [mesh.point_names[int(n)] for n in mesh.slave_node]
    k_lines = group_stiffness(statics, attached, statics.body_position("box"))[2, 2]
    body = system.bodies["box"]
    hs = body.hydrostatics
    k_hydro = 1025 * 9.81 * hs.length * hs.width
    lt = system.line_types["steel"] if "steel" in system.line_types else next(
        iter(system.line_types.values()))
    k_axial = 0.0
    for line in system.lines.values():
        a = statics.point_position(line.end_a)
        b = statics.point_position(line.end_b)
        chord = b - a
        sin2 = (chord[2] / np.linalg.norm(chord)) ** 2
        k_axial += lt.EA / line.length * sin2
    low = np.sqrt((k_hydro + k_lines) / body.mass)
    high = np.sqrt((k_hydro + k_axial) / body.mass)
    # line inertia above the lines' own resonances pushes it a little further: 10 % margin
    assert low < heave < 1.1 * high
