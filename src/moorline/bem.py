r"""Hydrodynamic coefficients of a box or vertical cylinder from a BEM code (extra ``[bem]``).

The linear potential-flow boundary element solver Capytaine (Ancellin and Dias, "Capytaine:
a Python-based linear potential flow solver", J. Open Source Softw. 4(36), 1341, 2019; based
on Nemoh, Babarit and Delhommeau 2015) computes, for the submerged part of a body's
hydrostatics shape at its draft:

- the frequency-dependent added mass :math:`A_{ij}(\omega)` and radiation damping
  :math:`B_{ij}(\omega)` (6x6),
- the wave exciting force per unit wave amplitude (Froude-Krylov plus diffraction) for one
  wave heading, as amplitude and phase per degree of freedom,
- the hydrostatic stiffness (6x6), displaced volume and waterplane area.

Conventions (those of :class:`moorline.model.Body`):

- degrees of freedom ``x, y, z, rx, ry, rz`` (capytaine's Surge, Sway, Heave, Roll, Pitch,
  Yaw) about the **body origin**, which for a ``box`` / ``cylinder`` hydrostatics shape is the
  shape's geometric centre, i.e. ``height / 2 - draft`` above the still water line (a body
  with ``matrix`` hydrostatics gives its shape and draft explicitly and its origin is at its
  position's height, e.g. Tuah Ex5's disc); world axes (the body is upright: its initial
  rotation is ignored);
- the free surface is ``z = 0``; the body's horizontal origin is ``x = y = 0``, where the
  incident wave's phase is taken;
- exciting force: moorline's waves have elevation :math:`\eta = a\cos\theta`,
  :math:`\theta = k(x\cos\beta + y\sin\beta) - \omega t + \phi` (:mod:`moorline.waves.airy`),
  which is capytaine's incident wave :math:`\mathrm{Re}(a\,e^{i(kx\cos\beta+ky\sin\beta-\omega
  t)})`; with capytaine's complex force :math:`X_i` (time factor :math:`e^{-i\omega t}`) the
  force is :math:`F_i(t) = a |X_i| \cos(\theta_0 + \arg X_i)`, :math:`\theta_0` being the wave
  phase function at the body origin. ``excitation_phase`` is :math:`\arg X_i` in degrees.
- the hydrostatic stiffness is capytaine's rigid-body formula about the body origin,
  :math:`C_{44} = \rho g (I_{xx}^{wp} + V z_b) - m g z_g` etc., with the body's mass and centre
  of gravity when given (else neutral buoyancy, centre of gravity at the origin). Mooring lines
  are not included.

Units: capytaine works in SI. For a case in US units (ft, slug, s, lbf) the inputs are
converted to SI, solved, and the results converted back with pint: an entry of a 6x6
added mass, damping or stiffness matrix between dofs ``i`` and ``j`` scales as
``mass * length**(r_i + r_j)`` (``r = 1`` for a rotation; time is the second in both systems,
and a force per length is a mass per time squared), an exciting force per unit amplitude as
``mass * length**r_i``. So added mass comes out in slug, slug ft, slug ft^2; damping in
lbf s/ft, lbf s, lbf ft s; stiffness in lbf/ft, lbf, lbf ft; excitation in lbf/ft and lbf
(per ft of wave amplitude); volume in ft^3.

Mesh: only the wetted hull is meshed (capytaine's ``mesh_parallelepiped`` /
``mesh_vertical_cylinder`` of twice the draft, centred on the water line, clipped with
``immersed_part()`` so that a row of nodes lies exactly on the water line). The cylinder's
polygon has the circle's area (its circumradius is enlarged by
:math:`\sqrt{2\pi / (n \sin(2\pi/n))}`), so volume and waterplane area are exact. Optionally a
lid on the interior free surface removes irregular frequencies (capytaine's
``generate_lid``).
"""

from __future__ import annotations

import inspect
import logging
import math
import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path
from typing import Any, Literal

import numpy as np
import xarray as xr
import yaml
from numpy.typing import ArrayLike

from .errors import CaseError, MoorlineError

__all__ = [
    "DOFS",
    "BodyTable",
    "body_coefficients",
    "comparison_rows",
    "default_panel_size",
    "write_body_table",
]

logger = logging.getLogger(__name__)

Shape = Literal["box", "cylinder"]

DOFS = ("Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw")
"""Capytaine's names of the rigid-body dofs, in moorline's order ``x y z rx ry rz``."""
_ROTATIONAL = np.array([0, 0, 0, 1, 1, 1])
_INSTALL = "install the [bem] extra: pip install moorline[bem]"

_UNIT_NAMES = {
    "SI": {"mass": "kg", "length": "m", "force": "N"},
    "US": {"mass": "slug", "length": "ft", "force": "lbf"},
}


def _capytaine() -> Any:
    """Import capytaine lazily; a :class:`MoorlineError` telling how to install it.

    Capytaine's import gives the root logger a rich handler writing to stdout when it has
    none (``capytaine.set_logging``): removed, so that its warnings go to stderr like any
    library's and a command's JSON on stdout stays JSON."""
    before = list(logging.root.handlers)
    try:
        import capytaine
    except ImportError as exc:
        raise MoorlineError(_INSTALL) from exc
    for handler in [h for h in logging.root.handlers if h not in before]:
        if type(handler).__name__ == "RichHandler":
            logging.root.removeHandler(handler)
    return capytaine


def _si_factors(units: str) -> tuple[float, float]:
    """Factors (mass, length) from SI to ``units``: 1 kg = f_m [mass], 1 m = f_l [length]."""
    from .io.hydro_database import unit_factors

    return unit_factors(units)


def _dimension_values(shape: str, dimensions: Mapping[str, float] | Sequence[float]
                      ) -> dict[str, float]:
    """``{"length", "width", "height"}`` of a box or ``{"diameter", "height"}`` of a cylinder,
    from a mapping or a sequence in that order."""
    keys = {"box": ("length", "width", "height"), "cylinder": ("diameter", "height")}
    if shape not in keys:
        raise MoorlineError(f"BEM meshing supports a box or a vertical cylinder, not {shape!r}")
    if isinstance(dimensions, Mapping):
        missing = [k for k in keys[shape] if k not in dimensions]
        if missing:
            raise MoorlineError(f"{shape} needs {', '.join(keys[shape])}; missing "
                                f"{', '.join(missing)}")
        values = {k: float(dimensions[k]) for k in keys[shape]}
    else:
        seq = [float(v) for v in dimensions]
        if len(seq) != len(keys[shape]):
            raise MoorlineError(f"{shape} needs {len(keys[shape])} dimensions "
                                f"({', '.join(keys[shape])}), got {len(seq)}")
        values = dict(zip(keys[shape], seq, strict=True))
    bad = [k for k, v in values.items() if not (v > 0 and math.isfinite(v))]
    if bad:
        raise MoorlineError(f"{shape} dimensions must be positive: {', '.join(bad)}")
    return values


def default_panel_size(shape: Shape, dimensions: Mapping[str, float] | Sequence[float],
                       draft: float, omega_max: float, gravity: float) -> float:
    """A panel size [length] for :func:`body_coefficients`.

    A twentieth of the smallest horizontal dimension (width of a box, diameter of a cylinder),
    and at most an eighth of the shortest (deep-water) wavelength ``2 pi g / omega_max^2``,
    so that capytaine's resolution check (wavelength above eight panel radii) passes. The
    draft gets at least two panels whatever this size.

    Parameters
    ----------
    shape, dimensions, draft
        As in :func:`body_coefficients` (any consistent length unit).
    omega_max
        Highest frequency to be solved [rad/s].
    gravity
        Acceleration of gravity in the same length unit per s^2.

    Returns
    -------
    float
        The panel size.
    """
    dims = _dimension_values(shape, dimensions)
    horizontal = min(dims["length"], dims["width"]) if shape == "box" else dims["diameter"]
    size = horizontal / 20.0
    if omega_max > 0:
        size = min(size, 2.0 * math.pi * gravity / omega_max**2 / 8.0)
    return size


def _hull_mesh(cpt: Any, shape: str, dims: dict[str, float], draft: float,
               size: float) -> Any:
    """The wetted hull (SI), water line at ``z = 0``, shape centred on the z axis."""
    height = dims["height"]
    submerged = draft >= height
    span = height if submerged else 2.0 * draft
    centre = (0.0, 0.0, height / 2.0 - draft) if submerged else (0.0, 0.0, 0.0)
    n_z = max(2, math.ceil((height if submerged else draft) / size))
    n_z_mesh = n_z if submerged else 2 * n_z
    if shape == "box":
        n_x = max(2, math.ceil(dims["length"] / size))
        n_y = max(2, math.ceil(dims["width"] / size))
        mesh = cpt.mesh_parallelepiped(size=(dims["length"], dims["width"], span),
                                       center=centre, resolution=(n_x, n_y, n_z_mesh),
                                       name="moorline_box")
    else:
        radius = dims["diameter"] / 2.0
        n_theta = max(8, 2 * math.ceil(math.pi * radius / size))
        n_r = max(1, math.ceil(radius / size))
        # equal-area polygon: area n/2 R^2 sin(2 pi/n) = pi r^2
        r_poly = radius * math.sqrt(2.0 * math.pi / (n_theta * math.sin(2.0 * math.pi / n_theta)))
        mesh = cpt.mesh_vertical_cylinder(length=span, radius=r_poly, center=centre,
                                          resolution=(n_r, n_theta, n_z_mesh),
                                          name="moorline_cylinder")
    return mesh if submerged else mesh.immersed_part()


def body_coefficients(
    shape: Shape,
    dimensions: Mapping[str, float] | Sequence[float],
    draft: float,
    omegas: ArrayLike,
    water_density: float,
    gravity: float,
    depth: float | None = None,
    *,
    units: Literal["SI", "US"] = "SI",
    heading_deg: float = 0.0,
    mass: float | None = None,
    center_of_gravity: Sequence[float] = (0.0, 0.0, 0.0),
    panel_size: float | None = None,
    lid: bool = False,
    origin_z: float | None = None,
) -> xr.Dataset:
    """Added mass, radiation damping, exciting forces and hydrostatics from capytaine.

    Meshes the wetted part of a box or vertical cylinder floating upright at ``draft``, adds
    the six rigid-body dofs about the body origin (by default the shape's centre, as in
    :class:`moorline.model.Hydrostatics`; see ``origin_z``), and solves the radiation
    problems of every dof and the diffraction problem of one wave heading at every
    frequency with capytaine's
    ``BEMSolver.fill_dataset`` (Ancellin and Dias 2019); the hydrostatics are capytaine's
    ``compute_hydrostatic_stiffness``, ``disp_volume`` and ``waterplane_area``. See the
    module docstring for the conventions and the unit conversion.

    Parameters
    ----------
    shape
        ``box`` or ``cylinder`` (vertical).
    dimensions
        ``{"length", "width", "height"}`` (box: length along x, width along y) or
        ``{"diameter", "height"}`` (cylinder), or a sequence in that order [length].
    draft
        Depth of the keel below the still water line [length]; ``>= height`` is a submerged
        body (no waterplane).
    omegas
        Wave frequencies [rad/s] (sorted, duplicates removed).
    water_density, gravity
        [mass/length^3], [length/s^2] in ``units``.
    depth
        Water depth [length]; ``None`` or ``inf`` for deep water.
    units
        Unit system of inputs and outputs, ``SI`` (kg, m, N) or ``US`` (slug, ft, lbf).
    heading_deg
        Wave propagation direction of the diffraction problem (0 = towards +x) [deg].
    mass, center_of_gravity
        Body mass and centre of gravity (body frame) for the roll/pitch/yaw hydrostatic
        stiffness; default neutral buoyancy (``rho V``) with the centre of gravity at the
        body origin.
    panel_size
        Target panel size [length]; default :func:`default_panel_size`.
    lid
        Add a lid on the interior free surface at ``z = 0`` (capytaine's ``generate_lid``,
        capytaine >= 2.1), which removes the irregular frequencies of the boundary integral
        equation (for the Wang box the first is near 3.4 rad/s, for a 10 ft disc at 2 ft draft
        near 4.5 rad/s).
    origin_z
        Height of the body origin above the still water line [length]; default the shape's
        centre, ``height / 2 - draft``.

    Returns
    -------
    xarray.Dataset
        Coordinates ``omega``, ``influenced_dof`` and ``radiating_dof`` (capytaine's names
        Surge ... Yaw = moorline's x ... rz), ``wavenumber(omega)``. Variables
        ``added_mass`` and ``radiation_damping`` (omega, influenced_dof, radiating_dof);
        ``excitation_amplitude`` [force or moment per unit wave amplitude] and
        ``excitation_phase`` [deg] (omega, influenced_dof); ``hydrostatic_stiffness``
        (influenced_dof, radiating_dof); scalars ``displaced_volume``, ``waterplane_area``.
        Attributes record the inputs, units, mesh (``n_panels``, ``panel_size``) and
        ``capytaine_version``.

    Raises
    ------
    MoorlineError
        Capytaine is not installed, or the geometry or frequencies are invalid.
    """
    ds = capytaine_database(shape, dimensions, draft, omegas, water_density, gravity, depth,
                            units=units, headings_deg=(heading_deg,), mass=mass,
                            center_of_gravity=center_of_gravity, panel_size=panel_size,
                            lid=lid, origin_z=origin_z)
    return _moorline_layout(ds, units)


def _check_inputs(omega: np.ndarray, draft: float | None, water_density: float,
                  gravity: float) -> None:
    if omega.size == 0 or not np.all(np.isfinite(omega)) or np.any(omega <= 0):
        raise MoorlineError("BEM frequencies must be positive and finite")
    if draft is not None and not (draft > 0 and math.isfinite(draft)):
        raise MoorlineError(f"draft must be positive, got {draft}")
    if not (water_density > 0 and gravity > 0):
        raise MoorlineError("water density and gravity must be positive")


def _file_mesh(cpt: Any, mesh_file: str | os.PathLike[str], f_l: float) -> Any:
    """A hull mesh file (any format capytaine reads) in the case's length unit, water line at
    ``z = 0``, in SI and clipped to its wetted part."""
    try:
        mesh = cpt.load_mesh(str(mesh_file))
    except Exception as exc:  # capytaine/meshio raise many kinds
        raise MoorlineError(f"cannot read mesh file {str(mesh_file)!r}: {exc}") from None
    if f_l != 1.0:
        mesh = cpt.Mesh(vertices=np.asarray(mesh.vertices) / f_l, faces=np.asarray(mesh.faces),
                        name=getattr(mesh, "name", None))
    wet = mesh.immersed_part()
    if wet.nb_faces == 0:
        raise MoorlineError(f"mesh file {str(mesh_file)!r} has no panel below the water line "
                            "z = 0 (coordinates in the case's length unit, z up)")
    return wet


def capytaine_database(
    shape: Shape | Literal["mesh"],
    dimensions: Mapping[str, float] | Sequence[float] | None,
    draft: float | None,
    omegas: ArrayLike,
    water_density: float,
    gravity: float,
    depth: float | None = None,
    *,
    units: Literal["SI", "US"] = "SI",
    headings_deg: Sequence[float] = (0.0,),
    mass: float | None = None,
    center_of_gravity: Sequence[float] = (0.0, 0.0, 0.0),
    panel_size: float | None = None,
    lid: bool = False,
    origin_z: float | None = None,
    mesh_file: str | os.PathLike[str] | None = None,
    infinite_frequency: bool = False,
) -> xr.Dataset:
    """The hydrodynamic database of a hull in capytaine's own dataset format (SI units).

    Meshes the wetted part of a box or vertical cylinder floating upright at ``draft`` (or
    reads a mesh file), adds the six rigid-body dofs about the body origin, and solves the
    radiation problems of every dof and the diffraction problems of every heading at every
    frequency with capytaine's ``BEMSolver.fill_dataset`` (Ancellin and Dias 2019), whose
    ``assemble_dataset`` output is returned unchanged but for ``hydrostatic_stiffness``,
    recomputed with a 2x2 Gauss-Legendre panel quadrature (exact waterplane moments of flat
    panels). With ``infinite_frequency`` the radiation problems at ``omega = inf`` are solved
    too (capytaine >= 2.0) and appended to the ``omega`` axis (their damping is 0, their
    exciting forces NaN).

    Parameters
    ----------
    shape
        ``box``, ``cylinder`` or ``mesh`` (then ``mesh_file``).
    dimensions, draft
        As in :func:`body_coefficients` (ignored for a mesh file).
    omegas, water_density, gravity, depth, units, mass, center_of_gravity, panel_size, lid
        As in :func:`body_coefficients` (inputs in ``units``; the dataset is SI, capytaine's).
    headings_deg
        Wave propagation directions of the diffraction problems [deg].
    origin_z
        Height of the body origin above the still water line [length]; default the shape's
        centre, ``height / 2 - draft`` (a mesh file: 0).
    mesh_file
        A hull mesh in a format capytaine reads (``cpt.load_mesh``), coordinates in the case's
        length unit, z up, the still water line at ``z = 0``, the body origin on the z axis;
        only its part below ``z = 0`` is kept. ``panel_size`` does not apply.
    infinite_frequency
        Also solve ``omega = inf`` (the added mass ``A(inf)`` of the Cummins equation).

    Returns
    -------
    xarray.Dataset
        Capytaine's dataset (complex exciting forces; write it with
        :func:`write_capytaine_netcdf`); ``attrs`` also record moorline's inputs
        (``moorline_*``).

    Raises
    ------
    MoorlineError
        Capytaine is not installed, the mesh file cannot be read, or the geometry or
        frequencies are invalid.
    """
    cpt = _capytaine()
    omega = np.unique(np.asarray(omegas, dtype=float).ravel())
    _check_inputs(omega, None if shape == "mesh" else draft, water_density, gravity)
    f_m, f_l = _si_factors(units)
    rho_si = water_density * f_l**3 / f_m
    g_si = gravity / f_l
    depth_si = math.inf if depth is None or not math.isfinite(depth) else depth / f_l
    if shape == "mesh":
        if mesh_file is None:
            raise MoorlineError("a mesh hull needs its mesh file")
        hull = _file_mesh(cpt, mesh_file, f_l)
        draft_si = float(-np.min(np.asarray(hull.vertices)[:, 2]))
        size_si = float("nan")
        origin = np.array([0.0, 0.0, 0.0 if origin_z is None else origin_z / f_l])
        submerged = bool(np.max(np.asarray(hull.vertices)[:, 2]) < -1e-9 * max(draft_si, 1.0))
        dims: dict[str, float] = {}
    else:
        assert draft is not None
        dims = _dimension_values(shape, dimensions or {})
        dims_si = {k: v / f_l for k, v in dims.items()}
        draft_si = draft / f_l
        if panel_size is None:
            size_si = default_panel_size(shape, dims_si, draft_si, float(omega.max()), g_si)
        elif panel_size > 0:
            size_si = panel_size / f_l
        else:
            raise MoorlineError(f"panel size must be positive, got {panel_size}")
        hull = _hull_mesh(cpt, shape, dims_si, draft_si, size_si)
        origin = np.array([0.0, 0.0, dims_si["height"] / 2.0 - draft_si if origin_z is None
                           else origin_z / f_l])
        submerged = draft_si >= dims_si["height"]
    if depth_si <= draft_si:
        raise MoorlineError(f"water depth {depth} must exceed the draft {draft_si * f_l:g}")
    cog = origin + np.asarray(center_of_gravity, dtype=float) / f_l
    lid_mesh = hull.generate_lid(z=0.0) if lid and not submerged else None
    body = cpt.FloatingBody(mesh=hull, lid_mesh=lid_mesh,
                            dofs=cpt.rigid_body_dofs(rotation_center=origin),
                            center_of_mass=cog,
                            mass=None if mass is None else mass / f_m,
                            name=f"moorline_{shape}")
    # hydrostatics with capytaine's 2x2 Gauss-Legendre panel quadrature: exact for the
    # quadratic waterplane moments of flat quadrilaterals (the default one-point rule
    # misses h^2/12 per panel of size h in I_wp)
    exact = (hull.with_quadrature("Gauss-Legendre 2") if hasattr(hull, "with_quadrature")
             else hull)
    statics = cpt.FloatingBody(mesh=exact, dofs=cpt.rigid_body_dofs(rotation_center=origin),
                               center_of_mass=cog, mass=body.mass, name=body.name)
    stiffness = statics.compute_hydrostatic_stiffness(rho=rho_si, g=g_si)

    common = {"radiating_dof": list(DOFS), "water_depth": [depth_si], "rho": [rho_si],
              "g": [g_si]}
    solver = cpt.BEMSolver()
    quiet = ({"progress_bar": False}
             if "progress_bar" in inspect.signature(solver.fill_dataset).parameters else {})
    headings = np.unique(np.radians(np.asarray(headings_deg, dtype=float).ravel()))
    solved = solver.fill_dataset(xr.Dataset(coords={
        "omega": omega, "wave_direction": headings, **common}), body, **quiet)
    if infinite_frequency:
        high = solver.fill_dataset(xr.Dataset(coords={"omega": [np.inf], **common}), body,
                                   **quiet)
        solved = xr.concat([solved, high[["added_mass", "radiation_damping"]]], dim="omega",
                           data_vars="minimal", coords="minimal", compat="override",
                           join="outer")
    solved["hydrostatic_stiffness"] = (
        ("influenced_dof", "radiating_dof"),
        np.asarray(stiffness.sel(influenced_dof=list(DOFS), radiating_dof=list(DOFS)).values,
                   dtype=float))
    solved.attrs.update({
        "moorline_source": "moorline.bem.capytaine_database",
        "moorline_units_of_inputs": units, "moorline_shape": shape,
        **{f"moorline_dimension_{k}": v for k, v in dims.items()},
        "moorline_draft": float(draft_si * f_l),
        "moorline_mesh_file": "" if mesh_file is None else str(mesh_file),
        "moorline_mass": float("nan") if mass is None else float(mass),
        "moorline_center_of_gravity": [float(c) for c in center_of_gravity],
        "moorline_n_panels": int(hull.nb_faces),
        "moorline_n_lid_panels": 0 if lid_mesh is None else int(lid_mesh.nb_faces),
        "moorline_panel_size": size_si * f_l,
        "moorline_origin_z": float(origin[2] * f_l),
        "moorline_waterplane_area": float(body.waterplane_area) if not submerged else 0.0,
    })
    return solved


def write_capytaine_netcdf(dataset: xr.Dataset, path: str | os.PathLike[str]) -> Path:
    """Write a :func:`capytaine_database` dataset as NetCDF in capytaine's format (complex
    arrays split on a ``complex`` = re, im axis: capytaine's ``export_dataset``)."""
    cpt = _capytaine()
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    cpt.export_dataset(str(path), dataset, format="netcdf")
    return path


def _moorline_layout(solved: xr.Dataset, units: str) -> xr.Dataset:
    """:func:`body_coefficients`' layout (case units) of a one-heading
    :func:`capytaine_database`."""
    a = solved.attrs
    f_m, f_l = _si_factors(units)
    finite = np.isfinite(solved["omega"].values)
    solved = solved.isel(omega=np.flatnonzero(finite))
    omega = solved["omega"].values
    pick = {"omega": omega, "influenced_dof": list(DOFS)}
    added = solved["added_mass"].sel(**pick, radiating_dof=list(DOFS)).values
    damping = solved["radiation_damping"].sel(**pick, radiating_dof=list(DOFS)).values
    excitation = solved["excitation_force"].isel(wave_direction=0).sel(**pick).values
    wavenumber = np.asarray(solved["wavenumber"].sel(omega=omega).values, dtype=float)
    stiffness = solved["hydrostatic_stiffness"].values
    rho_si = float(solved["rho"])
    volume = float(solved["disp_mass"]) / rho_si
    waterplane = float(a["moorline_waterplane_area"])
    shape = str(a["moorline_shape"])
    dims = {k[len("moorline_dimension_"):]: v for k, v in a.items()
            if k.startswith("moorline_dimension_")}
    depth_si = float(solved["water_depth"])
    mass = float(a["moorline_mass"])
    heading_deg = math.degrees(float(solved["wave_direction"].values[0]))

    r = _ROTATIONAL
    matrix_factor = f_m * f_l ** (r[:, None] + r[None, :])
    force_factor = f_m * f_l**r
    names = _UNIT_NAMES[units]
    ds = xr.Dataset(
        {
            "added_mass": (("omega", "influenced_dof", "radiating_dof"),
                           np.asarray(added, float) * matrix_factor),
            "radiation_damping": (("omega", "influenced_dof", "radiating_dof"),
                                  np.asarray(damping, float) * matrix_factor),
            "excitation_amplitude": (("omega", "influenced_dof"),
                                     np.abs(excitation) * force_factor),
            "excitation_phase": (("omega", "influenced_dof"),
                                 np.degrees(np.angle(excitation))),
            "hydrostatic_stiffness": (("influenced_dof", "radiating_dof"),
                                      stiffness * matrix_factor),
            "displaced_volume": ((), volume * f_l**3),
            "waterplane_area": ((), waterplane * f_l**2),
        },
        coords={"omega": omega, "influenced_dof": list(DOFS), "radiating_dof": list(DOFS),
                "wavenumber": ("omega", wavenumber / f_l)},
    )
    m, length, force = names["mass"], names["length"], names["force"]
    ds["omega"].attrs["units"] = "rad/s"
    ds["wavenumber"].attrs["units"] = f"1/{length}"
    ds["added_mass"].attrs["units"] = f"{m}, {m} {length}, {m} {length}^2 (6x6 blocks)"
    ds["radiation_damping"].attrs["units"] = (f"{force} s/{length}, {force} s, "
                                              f"{force} {length} s (6x6 blocks)")
    ds["hydrostatic_stiffness"].attrs["units"] = (f"{force}/{length}, {force}, "
                                                  f"{force} {length} (6x6 blocks)")
    ds["excitation_amplitude"].attrs["units"] = (f"{force}/{length}, {force} per {length} "
                                                 "of wave amplitude")
    ds["excitation_phase"].attrs["units"] = "deg"
    ds["excitation_phase"].attrs["convention"] = (
        "F(t) = a |X| cos(theta_0 + phase), theta_0 = k (x cos b + y sin b) - w t + phi at "
        "the body origin (moorline.waves.airy); capytaine's arg X, time factor exp(-i w t)")
    ds["displaced_volume"].attrs["units"] = f"{length}^3"
    ds["waterplane_area"].attrs["units"] = f"{length}^2"
    ds.attrs.update({
        "source": "capytaine (Ancellin and Dias 2019), linear potential flow BEM",
        "capytaine_version": str(a.get("capytaine_version", "unknown")),
        "green_function": str(a.get("green_function", "")),
        "method": str(a.get("method", "")),
        "units": units, "shape": shape,
        **{f"dimension_{k}": v for k, v in dims.items()},
        "draft": float(a["moorline_draft"]), "water_density": rho_si * f_m / f_l**3,
        "gravity": float(solved["g"]) * f_l,
        "depth": depth_si * f_l,
        "heading_deg": float(heading_deg),
        "mass": mass,
        "center_of_gravity": [float(c) for c in a["moorline_center_of_gravity"]],
        "n_panels": int(a["moorline_n_panels"]),
        "n_lid_panels": int(a["moorline_n_lid_panels"]),
        "panel_size": float(a["moorline_panel_size"]),
        "origin_z": float(a["moorline_origin_z"]),
        "reference_point": "body origin, world axes",
    })
    return ds


# ----------------------------------------------------------------------------- case files


@dataclass(frozen=True)
class BodyTable:
    """What :func:`write_body_table` computed and wrote.

    Attributes
    ----------
    coefficients
        The :func:`body_coefficients` dataset at the reference frequency.
    rows
        :func:`comparison_rows`: ``(quantity, unit, case value or None, BEM value)``.
    added_mass, damping
        The symmetrized 6x6 matrices written (case units).
    path
        The file written.
    text
        Its content.
    """

    coefficients: xr.Dataset
    rows: list[tuple[str, str, float | None, float | None]]
    added_mass: np.ndarray
    damping: np.ndarray
    path: Path
    text: str


def _shape_of(body: Any) -> tuple[Shape, dict[str, float]] | None:
    hs = body.hydrostatics
    if hs.kind == "box":
        return "box", {"length": hs.length, "width": hs.width, "height": hs.height}
    if hs.kind == "cylinder":
        return "cylinder", {"diameter": hs.diameter, "height": hs.height}
    return None


def _case_hydrostatics(body: Any, draft: float, rho: float, g: float
                       ) -> tuple[float, float, float, float]:
    """moorline's own small-motion hydrostatics of a body (about its origin): heave stiffness,
    displaced volume and the roll and pitch restoring its buoyancy, weight and restoring
    terms give (:func:`moorline.solvers.bodies.body_loads`). Box/cylinder at ``draft``:
    ``rho g A_wp``, ``A_wp d`` and ``rho g (I_wp + V z_b) - m g z_g``; ``matrix``: ``S_33``,
    the given volume and ``S_44 + rho g V z_b - m g z_g``."""
    hs = body.hydrostatics
    z_g = float(body.center_of_gravity[2])
    if hs.kind in ("matrix", "none"):
        S = np.zeros((6, 6)) if hs.stiffness is None else np.asarray(hs.stiffness, float)
        volume = hs.volume if hs.kind == "matrix" else 0.0
        z_b = float(hs.center_of_buoyancy[2])
        roll, pitch = (S[i, i] + rho * g * volume * z_b - body.mass * g * z_g for i in (3, 4))
        return float(S[2, 2]), volume, roll, pitch
    from .solvers.bodies import waterplane

    area, inertia = waterplane(hs)
    wet = min(max(draft, 0.0), hs.height)
    volume = area * wet
    z_b = -hs.height / 2.0 + wet / 2.0
    waterplane = 1.0 if draft < hs.height else 0.0
    roll, pitch = (rho * g * (waterplane * i + volume * z_b) - body.mass * g * z_g
                   for i in inertia)
    return rho * g * area * waterplane, volume, roll, pitch


def comparison_rows(system: Any, body_name: str, coefficients: xr.Dataset,
                    omega: float | None = None
                    ) -> list[tuple[str, str, float | None, float | None]]:
    """The case's constants next to the BEM values at one frequency.

    Parameters
    ----------
    system
        The loaded case (:class:`moorline.model.System`).
    body_name
        The body.
    coefficients
        :func:`body_coefficients` of that body.
    omega
        Frequency to report (default: the first of ``coefficients``).

    Returns
    -------
    list of tuple
        ``(quantity, unit, case value or None, BEM value)``: the diagonal added mass
        ``A11 .. A66`` and damping ``B11 .. B66`` (case value 0 when the case has none),
        heave stiffness ``C33``, roll and pitch stiffness ``C44``, ``C55`` and displaced
        volume (case: see :func:`_case_hydrostatics`), and the exciting force amplitude and
        phase per dof (case: heave ``C33``, i.e. ``rho g A_wp``, the long-wave limit that
        moorline's ``wave_loads`` use; others none).
    """
    body = system.bodies[body_name]
    env = system.environment
    units = _UNIT_NAMES[system.units]
    m, length, force = units["mass"], units["length"], units["force"]
    at = coefficients.sel(omega=float(coefficients.omega[0]) if omega is None else omega,
                          method="nearest")
    draft = float(coefficients.attrs["draft"])
    c33, volume, c44, c55 = _case_hydrostatics(body, draft, env.water_density, env.gravity)
    added = np.zeros((6, 6)) if body.added_mass is None else np.asarray(body.added_mass)
    damp = np.zeros((6, 6)) if body.damping is None else np.asarray(body.damping)
    mass_units = [m] * 3 + [f"{m} {length}^2"] * 3
    damp_units = [f"{force} s/{length}"] * 3 + [f"{force} {length} s"] * 3
    rows: list[tuple[str, str, float | None, float | None]] = []
    for i in range(6):
        rows.append((f"A{i + 1}{i + 1}", mass_units[i], float(added[i, i]),
                     float(at["added_mass"].values[i, i])))
    for i in range(6):
        rows.append((f"B{i + 1}{i + 1}", damp_units[i], float(damp[i, i]),
                     float(at["radiation_damping"].values[i, i])))
    C = at["hydrostatic_stiffness"].values
    rows += [("C33", f"{force}/{length}", c33, float(C[2, 2])),
             ("C44", f"{force} {length}", c44, float(C[3, 3])),
             ("C55", f"{force} {length}", c55, float(C[4, 4])),
             ("volume", f"{length}^3", volume, float(at["displaced_volume"]))]
    amp = np.array(at["excitation_amplitude"].values, dtype=float)
    # the phase of a case's ``excitation:`` table (:class:`moorline.model.WaveExcitation`,
    # ``a |X| cos(w t - k x_0 + phase)``) is ``-arg X``: printed in that convention so that
    # the table can be copied into a case
    phase: list[float | None] = [-float(v) for v in at["excitation_phase"].values]
    for block in (slice(0, 3), slice(3, 6)):  # numerically zero forces have no phase
        noise = amp[block] <= 1.0e-6 * max(float(np.max(amp[block])), 1e-300)
        amp[block][noise] = 0.0
        for i in np.flatnonzero(noise) + block.start:
            phase[i] = None
    for i, dof in enumerate(("x", "y", "z", "rx", "ry", "rz")):
        unit = f"{force}/{length}" if i < 3 else force
        rows.append((f"|X_{dof}|", unit, c33 if i == 2 else None, float(amp[i])))
        rows.append((f"phase X_{dof}", "deg", 0.0 if i == 2 else None, phase[i]))
    return rows


def _clean(matrix: np.ndarray, relative: float = 1.0e-6) -> tuple[np.ndarray, float]:
    """Symmetrize a 6x6 coefficient matrix and zero its numerically null entries.

    ``M_ij`` is zeroed when below ``relative * sqrt(s_i s_j)``, with the dof scale ``s_i =
    max(|M_ii|, 1e-9 max_k |M_kk|)`` over the dofs ``k`` of the same kind (translation or
    rotation), so that the comparison is scale-aware across blocks and a null diagonal (the
    yaw of an axisymmetric body) does not keep its round-off couplings. Returns the matrix
    and its relative asymmetry ``max|M - M^T| / max|M|``."""
    M = np.asarray(matrix, dtype=float)
    biggest = float(np.max(np.abs(M))) or 1.0
    asym = float(np.max(np.abs(M - M.T))) / biggest
    S = 0.5 * (M + M.T)
    diag = np.abs(np.diag(S))
    scale = np.empty(6)
    for block in (slice(0, 3), slice(3, 6)):
        top = float(np.max(diag[block])) or 1e-9 * biggest
        scale[block] = np.maximum(diag[block], 1e-9 * top)
    S[np.abs(S) <= relative * np.sqrt(np.outer(scale, scale))] = 0.0
    return S, asym


def _fmt(value: float | None) -> str:
    return "-" if value is None else f"{value:.6g}"


def _yaml_matrix(name: str, matrix: np.ndarray, indent: str) -> list[str]:
    lines = [f"{indent}{name}:"]
    for row in matrix:
        lines.append(f"{indent}  - [{', '.join(f'{v:.6g}' for v in row)}]")
    return lines


def write_body_table(
    case_path: str | os.PathLike[str],
    body_name: str,
    omega_ref: float,
    out_path: str | os.PathLike[str],
    *,
    panel_size: float | None = None,
    draft: float | None = None,
    shape: Shape | None = None,
    dimensions: Mapping[str, float] | Sequence[float] | None = None,
    lid: bool = False,
    whole_case: bool = False,
) -> BodyTable:
    """Compute a body's coefficients at one frequency and write them for the case file.

    The added mass and radiation damping at ``omega_ref`` (e.g. the wave or forcing
    frequency; symmetrized, negligible entries zeroed) are written as a YAML snippet
    ``bodies: {<body>: {added_mass: 6x6, damping: 6x6}}`` to merge into the case, or with
    ``whole_case`` as the whole case with those two entries replaced (the case's comments
    are not kept). A comment header records the source (capytaine version, mesh, frequency,
    depth, units), the case's constants next to the BEM values (:func:`comparison_rows`),
    and the exciting forces, which have no case-file entry yet.

    Parameters
    ----------
    case_path
        The case file.
    body_name
        A body with ``box`` or ``cylinder`` hydrostatics, or any body with ``shape``,
        ``dimensions`` and ``draft`` given.
    omega_ref
        Reference frequency [rad/s].
    out_path
        File to write.
    panel_size
        Panel size [case length]; default :func:`default_panel_size`.
    draft
        Draft [case length]; default from the body's position ``height / 2 - z`` (box and
        cylinder hydrostatics; required otherwise).
    shape, dimensions
        Hull to mesh (see :func:`body_coefficients`) for a body whose hydrostatics are a
        ``matrix``; its origin is then at the height of its ``position`` above the water
        line. Default: the body's box or cylinder.
    lid
        Irregular-frequency lid (see :func:`body_coefficients`).
    whole_case
        Write the whole case instead of a snippet.

    Returns
    -------
    BodyTable
        The coefficients, comparison rows, matrices, path and text written.

    Raises
    ------
    CaseError
        The case does not load, has no such body, or the body has no meshable shape.
    MoorlineError
        Capytaine is missing or the computation fails.
    """
    from . import __version__
    from .io import load_case

    case_path = Path(case_path)
    out_path = Path(out_path)
    system = load_case(case_path)
    if body_name not in system.bodies:
        known = ", ".join(system.bodies) or "(none)"
        raise CaseError(f"no body {body_name!r}; bodies: {known}", str(case_path), "bodies")
    body = system.bodies[body_name]
    own = _shape_of(body)
    origin_z: float | None = None
    if shape is not None or dimensions is not None:
        if shape is None or dimensions is None:
            raise MoorlineError("give both the shape and its dimensions")
        dims = _dimension_values(shape, dimensions)
    elif own is not None:
        shape, dims = own
    else:
        raise CaseError(f"body {body_name!r} has {body.hydrostatics.kind!r} hydrostatics: "
                        "give the hull to mesh and its draft (--shape, --size, --draft)",
                        str(case_path), f"bodies.{body_name}.hydrostatics.kind")
    if own is None:  # origin where the body is, not at a shape centre
        if draft is None:
            raise CaseError(f"body {body_name!r} has {body.hydrostatics.kind!r} "
                            "hydrostatics: give its draft (--draft)", str(case_path),
                            f"bodies.{body_name}.hydrostatics.kind")
        origin_z = float(body.position[2])
    if draft is None:
        draft = dims["height"] / 2.0 - float(body.position[2])
    if any(abs(a) > 1e-9 for a in body.rotation):
        logger.warning("body %s: initial rotation ignored; the BEM body is upright", body_name)
    if not 0.0 < draft:
        raise CaseError(f"body {body_name!r} is out of the water (draft {draft:g})",
                        str(case_path), f"bodies.{body_name}.position")
    env = system.environment
    coefficients = body_coefficients(
        shape, dims, draft, [omega_ref], env.water_density, env.gravity, env.depth,
        units=system.units, mass=body.mass, center_of_gravity=body.center_of_gravity,
        panel_size=panel_size, lid=lid, origin_z=origin_z)
    rows = comparison_rows(system, body_name, coefficients)
    at = coefficients.isel(omega=0)
    added, asym_a = _clean(at["added_mass"].values)
    damping, asym_b = _clean(at["radiation_damping"].values)

    a = coefficients.attrs
    units = _UNIT_NAMES[system.units]
    length = units["length"]
    depth_text = "infinite" if not math.isfinite(a["depth"]) else f"{a['depth']:g} {length}"
    size = ", ".join(f"{k} {v:g}" for k, v in dims.items())
    k = float(at["wavenumber"])
    header = [
        f"moorline bem: added mass and radiation damping of body {body_name!r} of case "
        f"{system.name!r} ({case_path})",
        f"source: capytaine {a['capytaine_version']} (linear potential flow BEM, "
        f"{a['green_function']} Green function, {a['method']} method), via moorline "
        f"{__version__}, {datetime.now(UTC).isoformat(timespec='seconds')}",
        f"mesh: {shape} ({size} {length}) at draft {draft:.6g} {length}, "
        f"{a['n_panels']} panels of about {a['panel_size']:.3g} {length}"
        + (f", lid {a['n_lid_panels']} panels" if a["n_lid_panels"] else ", no lid"),
        f"frequency: omega = {omega_ref:g} rad/s (period {2 * math.pi / omega_ref:.4g} s, "
        f"wavenumber {k:.4g} 1/{length}); water depth {depth_text}; "
        f"rho = {env.water_density:g}, g = {env.gravity:g}",
        f"units: {system.units} ({units['mass']}, {length}, s, {units['force']}); 6x6 about "
        f"the body origin ({a['origin_z']:.6g} {length} above the water line"
        + (", the shape centre" if own is not None else "")
        + "), world axes, dofs x y z rx ry rz",
        f"matrices symmetrized (relative asymmetry: added mass {asym_a:.1e}, damping "
        f"{asym_b:.1e}); entries below 1e-6 sqrt(|M_ii M_jj|) set to 0",
        "",
        f"{'quantity':<12} {'unit':<14} {'case':>14} {'BEM':>14}",
        *(f"{q:<12} {u:<14} {_fmt(c):>14} {_fmt(b):>14}" for q, u, c, b in rows),
        "",
        "exciting force per unit wave amplitude, heading 0 deg: F_i(t) = a |X_i| cos(w t - "
        "k x_0 + phase_i)",
        "for the wave eta = a cos(k x - w t) (the convention of a case's excitation: table, "
        "moorline.model.WaveExcitation;",
        "phase_i = -arg X_i of capytaine's complex force, time factor exp(-i w t)); the case "
        "column of |X_z| and its phase",
        "is moorline's long-wave heave excitation rho g A_wp.",
    ]
    comment = "\n".join(f"# {line}".rstrip() for line in header) + "\n"
    if whole_case:
        data = yaml.safe_load(case_path.read_text())
        entry = data["bodies"][body_name]
        entry["added_mass"] = [[float(f"{v:.6g}") for v in row] for row in added]
        entry["damping"] = [[float(f"{v:.6g}") for v in row] for row in damping]
        body_text = yaml.safe_dump(data, sort_keys=False, default_flow_style=None, width=100)
        text = comment + body_text
    else:
        lines = ["bodies:", f"  {body_name}:",
                 *_yaml_matrix("added_mass", added, "    "),
                 *_yaml_matrix("damping", damping, "    ")]
        text = comment + "\n".join(lines) + "\n"
    out_path.parent.mkdir(parents=True, exist_ok=True)
    out_path.write_text(text)
    return BodyTable(coefficients, rows, added, damping, out_path, text)
