r"""RAOs of a floating vertical cylinder: moorline's frequency domain against capytaine's.

A vertical cylinder, 10 m diameter, 20 m draft, floating freely (its neutral buoyancy mass
``rho V``, centre of gravity 14 m below the water line, radii of gyration 8 m in roll and
pitch and 5 m in yaw), 200 m of water, waves towards +x. Capytaine (Ancellin and Dias 2019)
solves its radiation and diffraction problems (coarse mesh, about 2 m panels) and writes
the dataset in its own NetCDF format; moorline reads it through a case file's
``hydrodynamics: {database: ...}`` (A(w), B(w), X(w) and the hydrostatics) and computes the
body's transfer functions with its stochastic analysis (``direct``; no drag anywhere, so the
response is linear; a line far from the body, unattached, is there because a case needs one).
The reference is capytaine's own ``post_pro.rao``: ``X / (-w^2 (M + A) - i w B + C)`` with
the dataset's rigid-body inertia matrix and hydrostatic stiffness (time factor
``exp(-i w t)``; moorline's ``exp(+i w t)``: its transfer function is the conjugate).

What is independent: capytaine assembles its 6x6 equation of motion from its inertia matrix
(given here from the cylinder's mass, centre of gravity and radii of gyration) and its
rigid-body hydrostatic stiffness; moorline from its body model (mass matrix about the
origin, the weight and buoyancy as turning loads, the waterplane stiffness it keeps from
the database), the database's unit and layout handling, and its sparse solve. Shared: the
hydrodynamic coefficients themselves (computed once). The sea's frequencies are multiples
of 0.02 rad/s and the table's are too, so the interpolation is exact at the compared
frequencies.

Tolerance 1e-5 (relative; phases 1e-5 rad): the statics tangent's regularization of the
body dofs (1e-9 of the largest diagonal stiffness, :mod:`moorline.solvers.coupled_statics`)
gives the free surge a stiffness capytaine's has not; observed agreement 3e-6 at 0.2 rad/s
(where the inertia ``w^2 M`` is smallest), 1e-7 above. A wrong sign of the exciting force's
phase (capytaine's ``exp(-i w t)`` against moorline's ``exp(i w t)``) fails the phase rows by
``2 arg X`` and the coupled surge/pitch amplitudes by up to 1e-5.
"""

from __future__ import annotations

import math
import tempfile
from pathlib import Path

import numpy as np

from .core import CaseSkipped, Row

CASE = "bem-rao"
RHO, G, DEPTH = 1025.0, 9.80665, 200.0
RADIUS, DRAFT, ZG = 5.0, 20.0, -14.0
GYRATION = (8.0, 8.0, 5.0)
D_OMEGA = 0.02
SOURCE = "capytaine 'post_pro.rao' on the same database (Ancellin and Dias 2019)"


def _mass_matrix(mass: float, zg: float, radii: tuple[float, float, float]) -> np.ndarray:
    """Rigid-body 6x6 mass matrix about the origin (0, 0, 0), centre of gravity (0, 0, zg),
    inertia ``m r_i^2`` about the centre of gravity: ``[[m I, -m [c x]], [m [c x], I_c - m
    [c x]^2]]``."""
    c = np.array([0.0, 0.0, zg])
    cx = np.array([[0, -c[2], c[1]], [c[2], 0, -c[0]], [-c[1], c[0], 0]])
    M = np.zeros((6, 6))
    M[:3, :3] = mass * np.eye(3)
    M[:3, 3:] = -mass * cx
    M[3:, :3] = mass * cx
    M[3:, 3:] = np.diag([mass * r * r for r in radii]) - mass * cx @ cx
    return M


def _database(omegas: np.ndarray, path: Path):
    """Solve the cylinder with capytaine and write its dataset (capytaine's format)."""
    import xarray as xr

    from ..bem import _capytaine
    from ..errors import MoorlineError

    try:
        cpt = _capytaine()
    except MoorlineError as exc:
        raise CaseSkipped("needs capytaine (the [bem] extra)") from exc

    mesh = cpt.mesh_vertical_cylinder(length=2 * DRAFT, radius=RADIUS, center=(0, 0, 0),
                                      resolution=(2, 16, 20)).immersed_part()
    body = cpt.FloatingBody(mesh=mesh, dofs=cpt.rigid_body_dofs(rotation_center=(0, 0, 0)),
                            center_of_mass=(0, 0, ZG), name="cylinder")
    mass = float(body.disp_mass(rho=RHO))
    body.mass = mass
    body.inertia_matrix = body.add_dofs_labels_to_matrix(_mass_matrix(mass, ZG, GYRATION))
    problems = xr.Dataset(coords={"omega": omegas, "wave_direction": [0.0],
                                  "radiating_dof": list(body.dofs), "water_depth": [DEPTH],
                                  "rho": [RHO], "g": [G]})
    ds = cpt.BEMSolver().fill_dataset(problems, body, progress_bar=False)
    cpt.export_dataset(str(path), ds, format="netcdf")
    rao = cpt.post_pro.rao(ds, wave_direction=0.0)
    return ds, rao, mass


def _case_text(database: Path, mass: float, omega_max: float) -> str:
    inertia = [mass * r * r for r in GYRATION]
    return f"""
name: {CASE}
environment: {{depth: {DEPTH}, water_density: {RHO}, gravity: {G},
              waves: {{kind: random, height: 1, period: 9, record_length: {2 * math.pi / D_OMEGA},
                      omega_max: {omega_max}}}}}
line_types:
  rope: {{diameter: 0.05, mass_per_length: 5, EA: 1.0e6}}
points:
  a: {{kind: fixed, position: [1000, 0, -50]}}
  b: {{kind: fixed, position: [1100, 0, -50]}}
lines:
  l: {{type: rope, length: 100.5, segments: 4, end_a: a, end_b: b}}
bodies:
  cylinder:
    position: [0, 0, 0]
    mass: {mass!r}
    center_of_gravity: [0, 0, {ZG}]
    inertia: {inertia!r}
    hydrodynamics: {{database: {database}}}
analyses:
  - {{kind: stochastic, method: direct}}
"""


def _at(rao, omega: float, dof: str) -> complex:
    """Capytaine's RAO of ``dof`` at the tabulated frequency nearest ``omega``."""
    j = int(np.argmin(np.abs(rao["omega"].values - omega)))
    dofs = [str(d) for d in rao["radiating_dof"].values]
    return complex(rao.isel(omega=j).values[dofs.index(dof)])


def run(quick: bool = False) -> list[Row]:
    """Surge, heave and pitch RAO amplitudes (and phases at one frequency) against
    capytaine's."""
    from ..io import load_case_text
    from ..solvers.stochastic import solve_stochastic

    steps = [20, 40, 60] if quick else [10, 20, 30, 40, 50, 60, 70]
    # the database's frequencies: every 0.1 rad/s from 0.1 to 1.5 (quick: 0.2 .. 1.2)
    table = D_OMEGA * (np.arange(10, 61, 10) if quick else np.arange(5, 80, 5))
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "cylinder.nc"
        _, rao, mass = _database(table, path)
        system = load_case_text(_case_text(path, mass, float(table[-1])))
    result = solve_stochastic(system, system.first("stochastic"))
    rows: list[Row] = []
    for dof, index, unit in (("Surge", 0, "m/m"), ("Heave", 2, "m/m"), ("Pitch", 4, "rad/m")):
        for step in steps:
            w = D_OMEGA * step
            j = int(np.argmin(np.abs(result.omega - w)))
            ref = _at(rao, w, dof)
            got = complex(result.body_transfer[j, 0, index])
            rows.append(Row(CASE, f"|{dof} RAO| at {w:.2f} rad/s", abs(ref), abs(got), 1e-5,
                            unit=unit, kind="other code", source=SOURCE))
        w = D_OMEGA * steps[len(steps) // 2]
        j = int(np.argmin(np.abs(result.omega - w)))
        ref = _at(rao, w, dof)
        got = complex(result.body_transfer[j, 0, index])
        phase_error = abs(np.angle(got * ref))  # moorline's H is capytaine's conjugate
        rows.append(Row(CASE, f"{dof} RAO phase at {w:.2f} rad/s (vs conjugate)", 0.0,
                        float(phase_error), 1e-5, relative=False, unit="rad",
                        kind="other code", source=SOURCE))
    return rows
