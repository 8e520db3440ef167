r"""A body's ``hydrodynamics:`` key: capytaine databases read into moorline's model (both
unit systems), the BEM cache, bad input, and the stochastic response of a body with
frequency-dependent added mass and damping.

References, none of them moorline's code under test:

- round trip: a dataset that capytaine itself solved and wrote (``fill_dataset``,
  ``export_dataset``), the values compared with capytaine's dataset in memory, converted to
  US units with pint in the test;
- hydrostatics of a box: capytaine's rigid-body stiffness with its default one-point panel
  quadrature holds the waterplane term :math:`\rho g \sum_p A_p y_p^2 = \rho g (L W^3/12 -
  L W h^2/12)` for ``h``-wide panel strips (the midpoint rule misses ``h^3/12`` per strip),
  so the waterplane stiffness moorline keeps once the buoyancy and weight moments are taken
  out is that, exactly;
- stochastic: surge of a body on a linear spring with tables :math:`A(\omega)`,
  :math:`B(\omega)` linear in frequency (so linear interpolation is exact) and a constant
  phase exciting force, :math:`|X(\omega)| / |K - \omega^2 (m + A(\omega)) + i\omega
  B(\omega)|` written here, the table's ends held constant.
"""

from __future__ import annotations

import logging
import math
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from moorline.errors import CaseError
from moorline.io import load_case, load_case_text
from moorline.io.hydro_database import DOFS
from moorline.solvers.stochastic import solve_stochastic

RHO, G = 1025.0, 9.80665

LINE = """
line_types:
  rope: {diameter: 0.05, mass_per_length: 5, EA: 1.0e6}
points:
  a: {kind: fixed, position: [1000, 0, -50]}
  b: {kind: fixed, position: [1100, 0, -50]}
lines:
  l: {type: rope, length: 100.5, segments: 4, end_a: a, end_b: b}
"""


def _case(body: str, *, units: str = "SI", waves: str = "{kind: random, height: 2, "
          "period: 8, record_length: 200, omega_max: 2.5}", extra: str = "") -> str:
    env = (f"environment: {{depth: 200, water_density: {RHO}, gravity: {G}, waves: {waves}}}"
           if units == "SI" else
           "environment: {depth: 656.168, water_density: 1.98877, gravity: 32.174, "
           f"waves: {waves}}}")
    return (f"name: hydro\nunits: {units}\n{env}\n{LINE}bodies:\n  hull:\n"
            + "".join(f"    {line}\n" for line in body.strip().splitlines())
            + "analyses:\n  - {kind: stochastic}\n" + extra)


# ---------------------------------------------------------------- capytaine's own files

cpt = pytest.importorskip("capytaine")

BOX = (10.0, 5.0, 2.0)  # length, width, draft [m]
PANEL = 0.5
MASS = RHO * BOX[0] * BOX[1] * BOX[2]
COG_Z = -0.5  # body origin at the water line
OMEGAS = [0.5, 1.0, 1.5]


@pytest.fixture(scope="module")
def capytaine_file(tmp_path_factory) -> tuple[Path, xr.Dataset]:
    """A box solved and written by capytaine itself: three frequencies and infinity, two
    headings, hydrostatics (default quadrature), rotation centre at the water line."""
    length, width, draft = BOX
    mesh = cpt.mesh_parallelepiped(size=(length, width, 2 * draft), center=(0, 0, 0),
                                   resolution=(int(length / PANEL), int(width / PANEL),
                                               int(2 * draft / PANEL))).immersed_part()
    body = cpt.FloatingBody(mesh=mesh, dofs=cpt.rigid_body_dofs(rotation_center=(0, 0, 0)),
                            center_of_mass=(0, 0, COG_Z), mass=MASS, name="box")
    solver = cpt.BEMSolver()
    problems = xr.Dataset(coords={"omega": OMEGAS + [np.inf], "radiating_dof": list(body.dofs),
                                  "wave_direction": [0.0, math.pi / 2], "water_depth": [200.0],
                                  "rho": [RHO], "g": [G]})
    ds = solver.fill_dataset(problems, body, progress_bar=False)
    path = tmp_path_factory.mktemp("db") / "box.nc"
    cpt.export_dataset(str(path), ds, format="netcdf")
    return path, ds


def _hull(database: str, cog: str = f"[0, 0, {COG_Z}]") -> str:
    return (f"position: [0, 0, 0]\nmass: {MASS}\ncenter_of_gravity: {cog}\n"
            f"inertia: [1.0e6, 1.0e6, 1.0e6]\nhydrodynamics: {{database: {database}}}")


def _load(tmp_path: Path, text: str, name: str = "case.yaml"):
    path = tmp_path / name
    path.write_text(text)
    return load_case(path)


def test_capytaine_file_fills_radiation_excitation_and_hydrostatics(capytaine_file, tmp_path):
    path, ds = capytaine_file
    (tmp_path / "db").mkdir()
    (tmp_path / "db" / "box.nc").write_bytes(path.read_bytes())
    system = _load(tmp_path, _case(_hull("db/box.nc")))  # relative to the case file
    body = system.bodies["hull"]
    dofs = {"influenced_dof": list(DOFS), "radiating_dof": list(DOFS)}
    assert body.radiation.omegas == tuple(OMEGAS)
    np.testing.assert_allclose(body.radiation.added_mass,
                               ds["added_mass"].sel(omega=OMEGAS, **dofs).values, rtol=1e-12)
    np.testing.assert_allclose(body.radiation.damping,
                               ds["radiation_damping"].sel(omega=OMEGAS, **dofs).values,
                               rtol=1e-12)
    np.testing.assert_allclose(body.radiation.added_mass_infinite,
                               ds["added_mass"].sel(omega=np.inf, **dofs).values, rtol=1e-12)
    X = ds["excitation_force"].sel(omega=OMEGAS, wave_direction=0.0,
                                   influenced_dof=list(DOFS)).values
    np.testing.assert_allclose(body.excitation.amplitude, np.abs(X), rtol=1e-12)
    big = np.abs(X) > 1e-6 * np.abs(X).max()
    # capytaine's X (time factor e^{-i w t}) is the force a |X| cos(w t - arg X): moorline's
    # phase (a |X| cos(w t + phase), model.WaveExcitation) is -arg X
    np.testing.assert_allclose(np.asarray(body.excitation.phase_deg)[big],
                               -np.degrees(np.angle(X))[big], atol=1e-9)
    assert body.added_mass is None and body.damping is None
    hs = body.hydrostatics
    length, width, draft = BOX
    S = np.asarray(hs.stiffness)
    assert hs.kind == "matrix"
    assert hs.volume == pytest.approx(length * width * draft, rel=1e-9)
    assert hs.center_of_buoyancy[2] == pytest.approx(-draft / 2, rel=1e-9)
    assert S[2, 2] == pytest.approx(RHO * G * length * width, rel=1e-9)
    # waterplane terms only (the buoyancy and weight moments are loads in moorline):
    # one-point quadrature of y^2 over the panel strips
    assert S[3, 3] == pytest.approx(RHO * G * (length * width**3 - length * width * PANEL**2)
                                    / 12, rel=1e-9)
    assert S[4, 4] == pytest.approx(RHO * G * (width * length**3 - length * width * PANEL**2)
                                    / 12, rel=1e-9)


def test_heading_between_two_of_the_database_is_interpolated(capytaine_file, tmp_path):
    path, ds = capytaine_file
    text = _case(_hull(str(path)), waves="{kind: random, height: 2, period: 8, heading: 45, "
                 "record_length: 200}")
    body = _load(tmp_path, text).bodies["hull"]
    X = ds["excitation_force"].sel(omega=OMEGAS, influenced_dof=list(DOFS))
    half = 0.5 * (X.sel(wave_direction=0.0).values + X.sel(wave_direction=math.pi / 2).values)
    got = np.asarray(body.excitation.amplitude) * np.exp(
        -1j * np.radians(np.asarray(body.excitation.phase_deg)))  # capytaine's sign
    np.testing.assert_allclose(got, half, rtol=1e-10, atol=1e-9 * np.abs(half).max())


def test_us_case_gets_us_units(capytaine_file, tmp_path):
    """Conversions checked with pint here: kg -> slug, N s/m -> lbf s/ft, N m s -> lbf ft s,
    N/m (force per metre of wave) -> lbf/ft, N m / m -> lbf, N/m -> lbf/ft."""
    import pint

    u = pint.UnitRegistry()
    path, ds = capytaine_file
    m_ft = u.Quantity(1.0, "m").to("ft").magnitude
    mass_us = u.Quantity(MASS, "kg").to("slug").magnitude
    text = _case(f"position: [0, 0, 0]\nmass: {mass_us}\ncenter_of_gravity: "
                 f"[0, 0, {COG_Z * m_ft}]\ninertia: [1.0e6, 1.0e6, 1.0e6]\n"
                 f"hydrodynamics: {{database: {path}}}", units="US",
                 waves="{kind: random, height: 6, period: 8, record_length: 200}")
    # the case's density and gravity are the SI ones in US units (0.1 % check)
    body = _load(tmp_path, text.replace("1.98877", str(u.Quantity(RHO, "kg/m^3").to(
        "slug/ft^3").magnitude)).replace("32.174", str(G * m_ft))).bodies["hull"]
    at = {"omega": 1.0}
    A = ds["added_mass"].sel(**at)
    B = ds["radiation_damping"].sel(**at)
    X = ds["excitation_force"].sel(**at, wave_direction=0.0)
    j = OMEGAS.index(1.0)

    def conv(value, src, dst):
        return u.Quantity(float(value), src).to(dst).magnitude

    assert body.radiation.added_mass[j][0][0] == pytest.approx(
        conv(A.sel(influenced_dof="Surge", radiating_dof="Surge"), "kg", "slug"), rel=1e-9)
    assert body.radiation.added_mass[j][4][4] == pytest.approx(
        conv(A.sel(influenced_dof="Pitch", radiating_dof="Pitch"), "kg m^2", "slug ft^2"),
        rel=1e-9)
    assert body.radiation.damping[j][2][2] == pytest.approx(
        conv(B.sel(influenced_dof="Heave", radiating_dof="Heave"), "N s/m", "lbf s/ft"),
        rel=1e-9)
    assert body.radiation.damping[j][0][4] == pytest.approx(
        conv(B.sel(influenced_dof="Surge", radiating_dof="Pitch"), "N s", "lbf s"), rel=1e-9)
    assert body.excitation.amplitude[j][0] == pytest.approx(
        conv(abs(X.sel(influenced_dof="Surge").values), "N/m", "lbf/ft"), rel=1e-9)
    assert body.excitation.amplitude[j][4] == pytest.approx(
        conv(abs(X.sel(influenced_dof="Pitch").values), "N", "lbf"), rel=1e-9)
    length, width, draft = BOX
    hs = body.hydrostatics
    assert hs.volume == pytest.approx(conv(length * width * draft, "m^3", "ft^3"), rel=1e-9)
    assert hs.stiffness[2][2] == pytest.approx(conv(RHO * G * length * width, "N/m",
                                                    "lbf/ft"), rel=1e-9)


def test_moorline_layout_database_is_read(tmp_path):
    """``moorline.bem.body_coefficients``' own layout, written to NetCDF."""
    from moorline.bem import body_coefficients

    ds = body_coefficients("cylinder", {"diameter": 4.0, "height": 8.0}, 4.0, [0.6, 1.2], RHO,
                           G, 200.0, panel_size=1.0, origin_z=0.0, mass=RHO * math.pi * 16,
                           center_of_gravity=(0, 0, -1.0))
    ds.to_netcdf(tmp_path / "own.nc")
    body = _load(tmp_path, _case(_hull("own.nc", "[0, 0, -1.0]").replace(
        f"mass: {MASS}", f"mass: {RHO * math.pi * 16}"))).bodies["hull"]
    np.testing.assert_allclose(body.radiation.added_mass, ds["added_mass"].values, rtol=1e-12)
    np.testing.assert_allclose(body.excitation.amplitude, ds["excitation_amplitude"].values,
                               rtol=1e-12)
    hs = body.hydrostatics
    assert hs.volume == pytest.approx(math.pi * 4.0 * 4.0, rel=1e-9)  # equal-area polygon
    assert hs.center_of_buoyancy[2] == pytest.approx(-2.0)
    assert hs.stiffness[2][2] == pytest.approx(RHO * G * math.pi * 4.0, rel=1e-9)


@pytest.mark.parametrize(("change", "field", "words"), [
    (lambda ds: ds.drop_vars("added_mass"), "database", "added_mass: missing"),
    (lambda ds: ds.assign_coords(rho=1000.0), "database", "rho: computed for a water density"),
    (lambda ds: ds.assign_coords(rotation_center=("space_coordinate", [0.0, 0.0, -1.0])),
     "database", "rotation_center"),
    (lambda ds: ds.drop_vars(["excitation_force", "diffraction_force"]), "database",
     "diffraction_force: missing"),
    (lambda ds: ds.isel(omega=[0]), "database", "at least two finite frequencies"),
], ids=["no-added-mass", "other-density", "rotation-centre", "half-excitation",
        "one-frequency"])
def test_bad_database_names_file_key_and_problem(capytaine_file, tmp_path, change, field,
                                                 words):
    path, _ = capytaine_file
    with xr.open_dataset(path) as handle:
        bad = change(handle.load())
    bad.to_netcdf(tmp_path / "bad.nc")
    with pytest.raises(CaseError) as info:
        _load(tmp_path, _case(_hull("bad.nc")))
    err = info.value
    assert err.field == f"bodies.hull.hydrodynamics.{field}"
    assert err.file.endswith("case.yaml") and "bad.nc" in err.reason and words in err.reason


def test_heading_the_database_lacks_is_refused(capytaine_file, tmp_path):
    path, _ = capytaine_file
    with xr.open_dataset(path) as handle:
        one = handle.load().isel(wave_direction=[0])
    one.to_netcdf(tmp_path / "one.nc")
    text = _case(_hull("one.nc"), waves="{kind: random, height: 2, period: 8, heading: 30, "
                 "record_length: 200}")
    with pytest.raises(CaseError, match="wave_direction: has the heading 0 deg only"):
        _load(tmp_path, text)


def test_missing_file_and_conflicting_keys(tmp_path, capytaine_file):
    with pytest.raises(CaseError, match="cannot read the database") as info:
        _load(tmp_path, _case(_hull("nowhere.nc")))
    assert info.value.field == "bodies.hull.hydrodynamics.database"
    path, _ = capytaine_file
    both = _hull(str(path)) + "\nadded_mass: [1, 1, 1, 1, 1, 1]"
    with pytest.raises(CaseError, match="remove added_mass") as info:
        load_case_text(_case(both))
    assert info.value.field == "bodies.hull.added_mass"
    with pytest.raises(CaseError, match="exactly one of database"):
        load_case_text(_case(_hull(str(path)).replace(
            f"{{database: {path}}}", "{}")))
    not_nc = tmp_path / "text.nc"
    not_nc.write_text("not netcdf")
    with pytest.raises(CaseError, match="cannot read it as NetCDF"):
        _load(tmp_path, _case(_hull("text.nc")))


# ---------------------------------------------------------------- computed and cached

BEM_BODY = """
position: [0, 0, 0]
mass: {mass}
center_of_gravity: [0, 0, -1.5]
inertia: [1.0e6, 1.0e6, 1.0e6]
hydrodynamics:
  bem: {{shape: cylinder, dimensions: {{diameter: 4, height: 8}}, draft: 4,
        omega: {{min: 0.4, max: 1.6, n: 4}}, panel_size: {panel}}}
"""


def test_bem_database_is_cached_and_reused(tmp_path, monkeypatch, caplog):
    monkeypatch.setenv("MOORLINE_CACHE_DIR", str(tmp_path / "cache"))
    mass = RHO * math.pi * 4 * 4
    text = _case(BEM_BODY.format(mass=mass, panel=1.0))
    with caplog.at_level(logging.INFO, logger="moorline"):
        first = _load(tmp_path, text).bodies["hull"]
    assert "computing its BEM database" in caplog.text
    files = list((tmp_path / "cache" / "bem").glob("bem-*.nc"))
    assert len(files) == 1
    with xr.open_dataset(files[0]) as handle:  # capytaine's format, readable by capytaine
        stored = cpt.io.xarray.merge_complex_values(handle.load())
    assert {"added_mass", "radiation_damping", "excitation_force", "diffraction_force",
            "Froude_Krylov_force", "hydrostatic_stiffness"} <= set(stored.data_vars)
    assert np.isinf(stored["omega"].values).any()  # A(inf)
    assert first.radiation.added_mass_infinite is not None
    np.testing.assert_allclose(first.radiation.omegas, np.linspace(0.4, 1.6, 4))
    assert first.hydrostatics.stiffness[2][2] == pytest.approx(RHO * G * math.pi * 4,
                                                               rel=1e-9)

    import moorline.bem

    def no_solve(*args, **kwargs):
        raise AssertionError("solved again instead of using the cache")

    monkeypatch.setattr(moorline.bem, "capytaine_database", no_solve)
    caplog.clear()
    with caplog.at_level(logging.INFO, logger="moorline"):
        second = _load(tmp_path, text).bodies["hull"]
    assert "using the cached BEM database" in caplog.text
    assert second.radiation == first.radiation and second.excitation == first.excitation
    # another input is another database
    with pytest.raises(AssertionError, match="solved again"):
        _load(tmp_path, _case(BEM_BODY.format(mass=mass, panel=0.9)))


def test_bem_inputs_are_checked(tmp_path):
    body = BEM_BODY.format(mass=1e5, panel=1.0)
    with pytest.raises(CaseError, match="needs dimensions diameter, height; missing height"):
        load_case_text(_case(body.replace("diameter: 4, height: 8", "diameter: 4")))
    with pytest.raises(CaseError, match="cannot read the mesh file") as info:
        load_case_text(_case(body.replace("shape: cylinder", "shape: hull.stl")))
    assert info.value.field == "bodies.hull.hydrodynamics.bem.shape"
    with pytest.raises(CaseError, match="n >= 2"):
        load_case_text(_case(body.replace("n: 4", "n: 1")))


# ---------------------------------------------------------------- frequency domain

W_TABLE = np.array([0.1, 0.4, 0.8, 1.3, 2.0])
M_BODY, K_SURGE = 2.0e5, 4.0e4
A0, A1 = 1.5e5, -6.0e4  # A11(w) = A0 + A1 w
B0, B1 = 1.0e3, 2.0e4   # B11(w) = B0 + B1 w
X0, X1, PHASE = 2.0e4, 6.0e4, 0.7  # X1(w) = (X0 + X1 w) exp(i PHASE)


def _table_database(path: Path, excited: bool = True) -> None:
    """A database in capytaine's layout written by xarray: surge tables linear in omega, the
    other dofs' diagonal constant (they are not excited); ``excited`` False: no exciting
    force."""
    n = len(W_TABLE)
    A = np.zeros((n, 6, 6))
    B = np.zeros((n, 6, 6))
    for i in range(6):
        A[:, i, i] = 1.0e5
        B[:, i, i] = 1.0e4
    A[:, 0, 0] = A0 + A1 * W_TABLE
    B[:, 0, 0] = B0 + B1 * W_TABLE
    X = np.zeros((n, 1, 6), dtype=complex)
    X[:, 0, 0] = (X0 + X1 * W_TABLE) * np.exp(1j * PHASE) if excited else 0.0
    ds = xr.Dataset(
        {"added_mass": (("omega", "influenced_dof", "radiating_dof"), A),
         "radiation_damping": (("omega", "influenced_dof", "radiating_dof"), B),
         "excitation_force": (("complex", "omega", "wave_direction", "influenced_dof"),
                              np.stack([X.real, X.imag]))},
        coords={"omega": W_TABLE, "influenced_dof": list(DOFS), "radiating_dof": list(DOFS),
                "wave_direction": [0.0], "complex": ["re", "im"], "rho": RHO, "g": G,
                "water_depth": 200.0, "rotation_center": ("space_coordinate", [0.0, 0, 0])})
    ds.to_netcdf(path)


def _spring_body(database: str, drag: str = "") -> str:
    diag = [K_SURGE, 1e5, 1e5, 1e5, 1e5, 1e5]
    rows = ", ".join("[" + ", ".join(str(diag[i] if i == j else 0) for j in range(6)) + "]"
                     for i in range(6))
    return (f"position: [0, 0, 0]\nmass: {M_BODY}\ninertia: [1.0e6, 1.0e6, 1.0e6]\n"
            f"hydrostatics: {{kind: matrix, stiffness: [{rows}], volume: {M_BODY / RHO}}}\n"
            f"hydrodynamics: {{database: {database}}}\n{drag}")


@pytest.mark.parametrize("method", ["direct", "foss"])
def test_surge_transfer_function_is_the_exact_one(tmp_path, method):
    """H = conj(X(w)) / (K - w^2 (m + A(w)) + i w B(w)) at every component (time factor
    e^{i w t}; capytaine's X is for e^{-i w t}), A, B and |X| held
    at the table's first row below 0.1 rad/s (the sea starts at 2 pi / 200 s)."""
    _table_database(tmp_path / "table.nc")
    text = _case(_spring_body("table.nc"), waves="{kind: random, height: 2, period: 14, "
                 "record_length: 200, omega_max: 2.0}").replace("{kind: stochastic}",
                                                   f"{{kind: stochastic, method: {method}}}")
    system = _load(tmp_path, text)
    r = solve_stochastic(system, system.first("stochastic"))
    w = r.omega
    assert w[0] < W_TABLE[0] and w[-1] <= W_TABLE[-1]
    wc = np.clip(w, W_TABLE[0], W_TABLE[-1])
    # moorline's time factor is e^{i w t}: capytaine's X e^{-i w t} is conj(X) e^{i w t}
    exact = (X0 + X1 * wc) * np.exp(-1j * PHASE) / (
        K_SURGE - w**2 * (M_BODY + A0 + A1 * wc) + 1j * w * (B0 + B1 * wc))
    H = r.body_transfer[:, 0, 0]
    # tolerance: the coupled statics' tangent regularizes each body dof by 1e-9 of its
    # largest diagonal entry (moorline.solvers.coupled_statics; ~1e-4 N/m here), 2.5e-9 of
    # the surge stiffness, amplified ~20 times at resonance
    np.testing.assert_allclose(np.abs(H), np.abs(exact), rtol=1e-7)
    np.testing.assert_allclose(H, exact, rtol=1e-7, atol=1e-9 * np.abs(exact).max())
    std = math.sqrt(float(np.sum(np.abs(exact) ** 2 * r.wave_spectrum * r.d_omega)))
    assert r.body_std[0, 0] == pytest.approx(std, rel=1e-7)
    # the frequency dependence matters: a constant table at the peak gives another answer
    peak = 2 * math.pi / 14
    const = (X0 + X1 * wc) / np.abs(K_SURGE - w**2 * (M_BODY + A0 + A1 * peak)
                                    + 1j * w * (B0 + B1 * peak))
    assert abs(math.sqrt(float(np.sum(const**2 * r.wave_spectrum * r.d_omega))) / std - 1) > 0.02


def _wave_number(w: float, depth: float) -> float:
    from scipy.optimize import brentq

    return brentq(lambda k: G * k * math.tanh(k * depth) - w * w, 1e-12, 10 * w * w / G + 1)


def test_body_in_a_one_metre_per_second_current(tmp_path):
    """Statics: the surge offset is the steady drag over the spring, 1/2 rho Cd A U^2 / K.
    Stochastic in waves far smaller than the current (sigma_u / U ~ 1e-3): the drag
    linearizes to its derivative at the current, rho Cd A U (the exact Gaussian E|w| differs
    from U by exp(-U^2 / 2 sigma^2)), and the only surge load is that drag on the wave
    velocity at the origin, omega coth(k h) per unit amplitude (Airy), so
    H = rho Cd A U omega coth(k h) / (K - omega^2 (m + A) + i omega (B + rho Cd A U)),
    phased for where the current holds the body."""
    _table_database(tmp_path / "table.nc", excited=False)
    area, cd, speed, depth = 40.0, 1.2, 1.0, 200.0
    text = _case(_spring_body("table.nc", f"drag_area: [{area}, 0, 0]\nCd: {cd}"),
                 waves="{kind: random, height: 0.004, period: 8, record_length: 200, "
                 "omega_max: 2.0}, current: {speed: 1.0, heading: 0}")
    system = _load(tmp_path, text)
    r = solve_stochastic(system, system.first("stochastic"))
    assert r.success, r.message
    drag = 0.5 * RHO * cd * area * speed**2
    from moorline.model import StaticsSettings
    from moorline.solvers.statics import solve_statics

    st = solve_statics(system, StaticsSettings(current_drag=True))
    # rel: the statics tangent's regularization, 1e-9 of its largest diagonal (above)
    assert st.body_pose[0, 0] == pytest.approx(drag / K_SURGE, rel=1e-7)
    w = r.omega
    wc = np.clip(w, W_TABLE[0], W_TABLE[-1])
    c = RHO * cd * area * speed
    k = np.array([_wave_number(x, depth) for x in w])
    # the current holds the body at x0 = drag / K: the wave reaches it e^{-i k x0} later
    # (time factor e^{i w t}, as moorline's series x(t) = Re sum H A e^{i w t})
    coth = np.exp(-1j * k * drag / K_SURGE) / np.tanh(k * depth)
    exact = c * w * coth / (K_SURGE - w**2 * (M_BODY + A0 + A1 * wc)
                            + 1j * w * (B0 + B1 * wc + c))
    # tolerance: the statics tangent's 1e-9 regularization (see above) and E|w| - U
    np.testing.assert_allclose(r.body_transfer[:, 0, 0], exact, rtol=1e-6,
                               atol=1e-9 * np.abs(exact).max())


def _write_gdf(mesh, path: Path) -> None:
    """A WAMIT GDF file (quadrilateral panels, no symmetry) of a capytaine mesh."""
    vertices = np.asarray(mesh.vertices)
    faces = np.asarray(mesh.faces)
    lines = ["moorline test hull", f"1.0 {G}", "0 0", str(len(faces))]
    lines += [" ".join(repr(float(c)) for c in vertices[i]) for face in faces for i in face]
    path.write_text("\n".join(lines) + "\n")


def test_mesh_file_hull_gives_the_box_database(tmp_path, monkeypatch):
    """A box written as a GDF mesh (the panels moorline meshes for ``shape: box``) gives the
    same database through ``shape: <mesh file>`` (relative to the case file)."""
    monkeypatch.setenv("MOORLINE_CACHE_DIR", str(tmp_path / "cache"))
    length, width, draft, panel = 4.0, 2.0, 1.0, 0.5
    mesh = cpt.mesh_parallelepiped(size=(length, width, 2 * draft), center=(0, 0, 0),
                                   resolution=(8, 4, 4)).immersed_part()
    _write_gdf(mesh, tmp_path / "box.gdf")
    common = (f"position: [0, 0, 0]\nmass: {RHO * length * width * draft}\n"
              "center_of_gravity: [0, 0, -0.2]\ninertia: [1.0e4, 1.0e4, 1.0e4]\n")
    omega = "omega: {min: 0.8, max: 2.0, n: 3}"
    box = _load(tmp_path, _case(common + "hydrodynamics: {bem: {shape: box, dimensions: "
                                f"{{length: {length}, width: {width}, height: 3}}, draft: "
                                f"{draft}, panel_size: {panel}, {omega}}}}}"), "box.yaml")
    gdf = _load(tmp_path, _case(common + f"hydrodynamics: {{bem: {{shape: box.gdf, {omega}}}}}"),
                "gdf.yaml")
    a, b = box.bodies["hull"], gdf.bodies["hull"]
    # rtol: capytaine's own scatter between two solves of one mesh in finite depth (observed
    # 2e-6 on the heave added mass, from run to run)
    scale = np.abs(a.radiation.added_mass).max()
    np.testing.assert_allclose(b.radiation.added_mass, a.radiation.added_mass, rtol=1e-5,
                               atol=1e-10 * scale)
    np.testing.assert_allclose(b.excitation.amplitude, a.excitation.amplitude, rtol=1e-5,
                               atol=1e-10 * np.abs(a.excitation.amplitude).max())
    assert b.hydrostatics.volume == pytest.approx(length * width * draft, rel=1e-9)
