r"""Read a body's hydrodynamic database (NetCDF) into moorline's model objects.

Two layouts are read:

- **capytaine's own** (``capytaine.assemble_dataset`` written by ``export_dataset`` /
  ``separate_complex_values``: complex arrays split on a ``complex`` = ``re, im`` axis), in
  SI: ``added_mass`` and ``radiation_damping`` (omega, influenced_dof, radiating_dof),
  ``excitation_force`` or ``diffraction_force`` + ``Froude_Krylov_force`` (omega,
  wave_direction [rad], influenced_dof), and optionally the hydrostatics
  ``hydrostatic_stiffness``, ``disp_mass``, ``center_of_buoyancy``, ``center_of_mass``,
  ``inertia_matrix``; coordinates ``rho``, ``g``, ``water_depth``, ``rotation_center``. The
  frequency axis may be ``omega`` or another of capytaine's (``period``, ``freq``...) with an
  ``omega`` coordinate; ``omega = inf`` gives the infinite-frequency added mass.
- **moorline's** :func:`moorline.bem.body_coefficients` layout (``excitation_amplitude`` and
  ``excitation_phase`` [deg], one heading ``attrs["heading_deg"]``, units
  ``attrs["units"]``, SI or US).

Conventions (:mod:`moorline.bem`): the coefficients are about the body origin, world axes,
dofs ``Surge .. Yaw`` = ``x .. rz``; the database's horizontal origin is the body origin
(where the wave phase is taken), so capytaine's ``rotation_center`` must be ``(0, 0, z)``
with ``z`` the body origin's height above the still water line. Exciting force: capytaine's
complex ``X_i`` (time factor ``exp(-i w t)``, incident wave ``eta = a cos(k x - w t)``) is the
force ``F_i(t) = a |X_i| cos(w t - k x_0 - arg X_i)``, so the
:class:`moorline.model.WaveExcitation` phase (``a |X| cos(w t - k x_0 + phase)``) is
``-arg X_i``; moorline's layout stores ``excitation_phase = arg X_i``
(:mod:`moorline.bem`), read the same way.

Hydrostatics: capytaine's rigid-body stiffness about the rotation centre holds the waterplane
terms and the buoyancy and weight moments :math:`\rho g V (z_b - z_c) - m g (z_g - z_c)`
(44, 55), :math:`-\rho g V (x_b - x_c) + m g (x_g - x_c)` (46) and the like (56)
(capytaine ``compute_hydrostatic_stiffness``). moorline applies buoyancy ``rho g V`` at the
centre of buoyancy and the weight at the centre of gravity as loads that turn with the body
(:mod:`moorline.solvers.bodies`), whose linearization gives those moments again, so the
``matrix`` stiffness read here is capytaine's minus them (with capytaine's own mass, from
``inertia_matrix`` or the displaced mass, and ``center_of_mass``): the waterplane terms.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import MoorlineError
from ..model import Hydrostatics, RadiationTable, WaveExcitation

__all__ = ["DOFS", "BodyHydrodynamics", "DatabaseError", "from_dataset", "read_database",
           "unit_factors"]

DOFS = ("Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw")
"""Capytaine's rigid-body dof names, moorline's ``x y z rx ry rz``."""
_ROTATIONAL = np.array([0, 0, 0, 1, 1, 1])
_HEADING_TOL = 1.0e-6  # rad: a database heading within this of the case's is taken as it
_MAX_HEADING_GAP = math.pi / 2  # widest gap between two headings interpolated across
_FREQUENCY_AXES = ("period", "freq", "wavelength", "wavenumber")


class DatabaseError(ValueError):
    """A bad database: ``key`` names the variable, coordinate or attribute at fault."""

    def __init__(self, key: str, reason: str) -> None:
        self.key, self.reason = key, reason
        super().__init__(f"{key}: {reason}")


@dataclass(frozen=True)
class BodyHydrodynamics:
    """What a database gives a body, in the case's units.

    Attributes
    ----------
    radiation
        ``A(w)``, ``B(w)`` (and ``A(inf)`` when the database has ``omega = inf``).
    excitation
        Exciting force per unit wave amplitude at the case's wave heading (``None`` when the
        database has no diffraction results).
    hydrostatics
        ``matrix`` hydrostatics (waterplane stiffness, volume, centre of buoyancy in the body
        frame), or ``None`` when the database has none.
    notes
        What was chosen (heading picked or interpolated, depth differences), for the log.
    """

    radiation: RadiationTable
    excitation: WaveExcitation | None
    hydrostatics: Hydrostatics | None
    notes: tuple[str, ...] = ()


def unit_factors(units: str) -> tuple[float, float]:
    """Factors (mass, length) from SI to ``units``: 1 kg = f_m [mass], 1 m = f_l [length]."""
    if units == "SI":
        return 1.0, 1.0
    if units != "US":
        raise MoorlineError(f"unknown unit system {units!r} (SI or US)")
    from .units import registry

    ureg = registry()
    return (float(ureg.Quantity(1.0, "kg").to("slug").magnitude),
            float(ureg.Quantity(1.0, "m").to("ft").magnitude))


def read_database(path: str | Path, **case: Any) -> BodyHydrodynamics:
    """Read a NetCDF database (either layout) for a body of a case.

    Parameters
    ----------
    path
        The NetCDF file.
    **case
        Keyword arguments of :func:`from_dataset`.

    Returns
    -------
    BodyHydrodynamics

    Raises
    ------
    DatabaseError
        The file cannot be read or lacks, or has bad, data (``key`` names what).
    """
    import xarray as xr

    try:
        with xr.open_dataset(path) as handle:
            ds = handle.load()
    except (OSError, ValueError, RuntimeError) as exc:
        raise DatabaseError("file", f"cannot read it as NetCDF: {exc}") from None
    return from_dataset(ds, **case)


def _merge_complex(ds: Any) -> Any:
    """Capytaine's ``merge_complex_values`` (complex arrays stored as re, im)."""
    if "complex" not in ds.dims:
        return ds
    labels = [str(v) for v in ds["complex"].values] if "complex" in ds.coords else ["re", "im"]
    if sorted(labels) != ["im", "re"]:
        raise DatabaseError("complex", f"must be the labels re, im, got {labels}")
    out = ds.copy()
    for name in list(ds.data_vars):
        da = ds[name]
        if "complex" in da.dims:
            out[name] = da.isel(complex=labels.index("re")) \
                + 1j * da.isel(complex=labels.index("im"))
    return out.drop_vars("complex", errors="ignore")


def _frequency_axis(ds: Any) -> Any:
    if "omega" in ds.dims:
        return ds
    for axis in _FREQUENCY_AXES:
        if axis in ds.dims and "omega" in ds.coords and ds["omega"].dims == (axis,):
            return ds.swap_dims({axis: "omega"})
    raise DatabaseError("omega", "no frequency axis: needs an 'omega' dimension or an "
                        "'omega' coordinate along capytaine's period/freq/wavelength axis")


def _pick(ds: Any, name: str, wanted: float, what: str, tolerance: float = 1e-3) -> Any:
    """Select the value ``wanted`` of the optional axis ``name`` (a dimension of several
    values, or a scalar coordinate that must match)."""
    if name not in ds.coords:
        return ds
    values = np.atleast_1d(np.asarray(ds[name].values, dtype=float))
    close = [i for i, v in enumerate(values)
             if (math.isinf(v) and math.isinf(wanted))
             or abs(v - wanted) <= tolerance * max(abs(wanted), 1e-300)]
    if not close:
        shown = ", ".join(f"{v:g}" for v in values)
        raise DatabaseError(name, f"computed for {what} {shown}, the case has {wanted:g}: "
                            "recompute the database or change the case")
    if name in ds.dims:
        return ds.isel({name: close[0]})
    return ds


def _squeeze(ds: Any, name: str) -> Any:
    if name in ds.dims:
        if ds.sizes[name] != 1:
            raise DatabaseError(name, f"has {ds.sizes[name]} values; moorline reads one")
        return ds.isel({name: 0})
    return ds


def _matrix(ds: Any, name: str) -> np.ndarray:
    if name not in ds:
        raise DatabaseError(name, "missing (needed)")
    da = ds[name]
    try:
        da = da.sel(influenced_dof=list(DOFS), radiating_dof=list(DOFS))
    except (KeyError, ValueError):
        have = [str(v) for v in ds.coords.get("radiating_dof", ds.coords.get(
            "influenced_dof", [])).values] if "radiating_dof" in ds.coords else []
        raise DatabaseError(name, f"needs the six rigid-body dofs {', '.join(DOFS)} on "
                            f"influenced_dof and radiating_dof; has {have}") from None
    return np.asarray(da.transpose(..., "influenced_dof", "radiating_dof").values)


def _heading(force: Any, heading_deg: float) -> tuple[np.ndarray, str]:
    """The exciting force (n_omega, 6) at ``heading_deg``: a database heading equal to it
    (mod 360 deg), else linear interpolation of the complex force between the two
    neighbouring headings (periodic), at most 90 deg apart."""
    if "wave_direction" not in force.dims:
        direction = float(force["wave_direction"]) if "wave_direction" in force.coords else 0.0
        force = force.expand_dims(wave_direction=[direction])
    force = force.transpose("omega", "wave_direction", "influenced_dof")
    directions = np.mod(np.asarray(force["wave_direction"].values, dtype=float), 2 * math.pi)
    beta = math.radians(heading_deg) % (2 * math.pi)
    gap = np.abs((directions - beta + math.pi) % (2 * math.pi) - math.pi)
    values = np.asarray(force.values)
    if gap.min() <= _HEADING_TOL:
        j = int(np.argmin(gap))
        return values[:, j], f"heading {heading_deg:g} deg: the database's"
    shown = ", ".join(f"{math.degrees(d):g}" for d in sorted(directions))
    if len(directions) < 2:
        raise DatabaseError("wave_direction", f"has the heading {shown} deg only; the case's "
                            f"waves go towards {heading_deg:g} deg (recompute the database "
                            "for that heading)")
    ahead = (directions - beta) % (2 * math.pi)
    after, before = int(np.argmin(ahead)), int(np.argmax(ahead))
    span = ahead[after] + (2 * math.pi - ahead[before])
    if span > _MAX_HEADING_GAP:
        raise DatabaseError("wave_direction", f"headings {shown} deg do not bracket the "
                            f"case's {heading_deg:g} deg within 90 deg: cannot interpolate")
    w = (2 * math.pi - ahead[before]) / span
    note = (f"heading {heading_deg:g} deg: interpolated between the database's "
            f"{math.degrees(directions[before]):g} and {math.degrees(directions[after]):g} deg")
    return (1.0 - w) * values[:, before] + w * values[:, after], note


def _table(rows: np.ndarray) -> tuple[tuple[float, ...], ...]:
    return tuple(tuple(float(x) for x in r) for r in rows)


def from_dataset(ds: Any, *, units: str, origin_z: float, water_density: float,
                 gravity: float, depth: float, heading_deg: float,
                 note: Callable[[str], None] | None = None) -> BodyHydrodynamics:
    """A database (either layout, see the module docstring) for a body of a case.

    Parameters
    ----------
    ds
        The dataset (as read from NetCDF: complex values split or not).
    units
        The case's unit system (``SI`` or ``US``).
    origin_z
        Height of the body origin above the still water line [case length]: must be the
        database's rotation centre.
    water_density, gravity, depth
        The case's (``inf`` for deep water) [case units]; a database computed for another
        density or gravity (0.1 %) is refused, another depth is noted.
    heading_deg
        The case's wave heading.
    note
        Called with what was chosen (heading, depth).

    Returns
    -------
    BodyHydrodynamics

    Raises
    ------
    DatabaseError
    """
    notes: list[str] = []
    f_m, f_l = unit_factors(units)
    if "excitation_amplitude" in ds or "excitation_phase" in ds:
        db_units = str(ds.attrs.get("units", "SI"))
        d_m, d_l = unit_factors(db_units)
        f_m, f_l = f_m / d_m, f_l / d_l  # database units -> case units
        ds = _frequency_axis(ds)
        si = (d_m, d_l)
        for key in ("water_density", "gravity", "origin_z"):
            if key not in ds.attrs:
                raise DatabaseError(key, "missing attribute (moorline's layout)")
        rho_db = float(ds.attrs["water_density"]) * d_l**3 / d_m
        g_db = float(ds.attrs["gravity"]) / d_l
        depth_db = float(ds.attrs.get("depth", math.inf)) / d_l
        center = np.array([0.0, 0.0, float(ds.attrs["origin_z"]) / d_l])
    else:
        si = (1.0, 1.0)
        ds = _frequency_axis(_merge_complex(ds))
        ds = _squeeze(_pick(ds, "forward_speed", 0.0, "forward speed", 0.0), "forward_speed")
        ds = _squeeze(ds, "body")
        rho_db = g_db = depth_db = math.nan
        center = None
        if "rotation_center" in ds.coords:
            center = np.asarray(ds["rotation_center"].values, dtype=float).ravel()
            if center.shape != (3,):
                raise DatabaseError("rotation_center", "must be one point (x, y, z)")
    c_m, c_l = unit_factors(units)  # the case's values in SI
    rho_case, g_case = water_density * c_l**3 / c_m, gravity / c_l
    depth_case = depth / c_l if math.isfinite(depth) else math.inf
    if math.isnan(rho_db):  # capytaine's layout: rho, g, water_depth coordinates
        ds = _pick(ds, "rho", rho_case, "a water density [kg/m^3]")
        ds = _pick(ds, "g", g_case, "a gravity [m/s^2]")
        if "water_depth" in ds.coords:
            depths = np.atleast_1d(np.asarray(ds["water_depth"].values, dtype=float))
            j = int(np.argmin([0.0 if (math.isinf(d) and math.isinf(depth_case))
                               else abs(d - depth_case) for d in depths]))
            if "water_depth" in ds.dims:
                ds = ds.isel(water_depth=j)
            depth_db = float(depths[j])
        for axis in ("rho", "g"):
            ds = _squeeze(ds, axis)
        rho_db = float(ds["rho"]) if "rho" in ds.coords else rho_case
        g_db = float(ds["g"]) if "g" in ds.coords else g_case
    else:
        for value, case_value, what in ((rho_db, rho_case, "water_density"),
                                        (g_db, g_case, "gravity")):
            if not abs(value - case_value) <= 1e-3 * case_value:
                raise DatabaseError(what, f"computed for {value:g} (SI), the case has "
                                    f"{case_value:g}: recompute the database or change the "
                                    "case")
    if not math.isnan(depth_db) and not (
            (math.isinf(depth_db) and math.isinf(depth_case))
            or abs(depth_db - depth_case) <= 1e-3 * depth_case):
        notes.append(f"database computed for water depth {depth_db:g} m, the case's is "
                     f"{depth_case:g} m")

    origin_si = origin_z / c_l
    if center is not None:
        scale = max(1.0, abs(origin_si))
        if abs(center[0]) > 1e-6 * scale or abs(center[1]) > 1e-6 * scale \
                or abs(center[2] - origin_si) > 1e-6 * scale:
            raise DatabaseError("rotation_center", f"is ({', '.join(f'{c:g}' for c in center)})"
                                f" m; the body origin is (0, 0, {origin_si:g}) m in the "
                                "database frame (the coefficients must be about it)")
    else:
        notes.append("the database has no rotation_center: taken to be the body origin")

    omega_all = np.asarray(ds["omega"].values, dtype=float)
    if np.any(np.isnan(omega_all)) or np.any(omega_all < 0):
        raise DatabaseError("omega", "frequencies must be >= 0")
    order = np.argsort(omega_all)
    ds = ds.isel(omega=order)
    omega_all = omega_all[order]
    finite = np.isfinite(omega_all)
    if np.any(np.diff(omega_all[finite]) <= 0):
        raise DatabaseError("omega", "frequencies must be distinct")
    if finite.sum() < 2:
        raise DatabaseError("omega", f"needs at least two finite frequencies, has "
                            f"{int(finite.sum())}")

    r = _ROTATIONAL
    matrix_factor = f_m * f_l ** (r[:, None] + r[None, :])
    force_factor = f_m * f_l**r
    A_all = _matrix(ds, "added_mass") * matrix_factor
    B_all = _matrix(ds, "radiation_damping") * matrix_factor
    for name, values in (("added_mass", A_all), ("radiation_damping", B_all)):
        if not np.all(np.isfinite(values[finite])):
            raise DatabaseError(name, "has non-finite values at finite frequencies")
    infinite = None
    if (~finite).any():
        A_inf = A_all[~finite][0]
        if np.all(np.isfinite(A_inf)):
            infinite = _table(A_inf)
    radiation = RadiationTable(tuple(float(w) for w in omega_all[finite]),
                               tuple(_table(m) for m in A_all[finite]),
                               tuple(_table(m) for m in B_all[finite]), infinite)

    force = _excitation_force(ds, heading_deg, notes)  # capytaine's complex X
    excitation = None
    if force is not None:
        force = force * force_factor
        keep = finite & (omega_all > 0) & np.all(np.isfinite(force), axis=1)
        if keep.sum() < 1:
            raise DatabaseError("excitation_force", "has no finite value at a frequency > 0")
        excitation = WaveExcitation(tuple(float(w) for w in omega_all[keep]),
                                    _table(np.abs(force[keep])),
                                    _table(-np.degrees(np.angle(force[keep]))))
    hydrostatics = _hydrostatics(ds, si, (f_m, f_l), rho_db, g_db, center)
    for text in notes:
        if note is not None:
            note(text)
    return BodyHydrodynamics(radiation, excitation, hydrostatics, tuple(notes))


def _excitation_force(ds: Any, heading_deg: float, notes: list[str]) -> np.ndarray | None:
    """The complex exciting force (n_omega, 6) at the case's heading in the database's
    units, ``None`` without diffraction results."""
    if "excitation_amplitude" in ds:
        amp = np.asarray(ds["excitation_amplitude"].sel(influenced_dof=list(DOFS)).values)
        phase = np.radians(np.asarray(ds["excitation_phase"].sel(
            influenced_dof=list(DOFS)).values))
        db_heading = float(ds.attrs.get("heading_deg", 0.0))
        gap = abs((db_heading - heading_deg + 180.0) % 360.0 - 180.0)
        if gap > math.degrees(_HEADING_TOL):
            raise DatabaseError("heading_deg", f"the database is for waves towards "
                                f"{db_heading:g} deg, the case's go towards "
                                f"{heading_deg:g} deg")
        notes.append(f"heading {heading_deg:g} deg: the database's")
        return amp * np.exp(1j * phase)
    if "excitation_force" in ds:
        total = ds["excitation_force"]
    elif "diffraction_force" in ds or "Froude_Krylov_force" in ds:
        missing = next((n for n in ("diffraction_force", "Froude_Krylov_force")
                        if n not in ds), None)
        if missing is not None:
            raise DatabaseError(missing, "missing: the exciting force is diffraction_force + "
                                "Froude_Krylov_force (or give excitation_force)")
        total = ds["diffraction_force"] + ds["Froude_Krylov_force"]
    else:
        notes.append("the database has no exciting force (no diffraction results)")
        return None
    try:
        total = total.sel(influenced_dof=list(DOFS))
    except (KeyError, ValueError):
        raise DatabaseError("excitation_force", "needs the six rigid-body dofs "
                            f"{', '.join(DOFS)} on influenced_dof") from None
    force, chosen = _heading(total, heading_deg)
    notes.append(chosen)
    return force


def _hydrostatics(ds: Any, si: tuple[float, float], factors: tuple[float, float],
                  rho: float, g: float, center: np.ndarray | None) -> Hydrostatics | None:
    """The ``matrix`` hydrostatics of a database (module docstring), case units; ``None``
    without ``hydrostatic_stiffness``."""
    if "hydrostatic_stiffness" not in ds:
        return None
    f_m, f_l = factors
    d_m, d_l = si
    r = _ROTATIONAL
    C = _matrix(ds, "hydrostatic_stiffness").astype(float)
    C = C / (d_m * d_l ** (r[:, None] + r[None, :]))  # to SI
    c = np.zeros(3) if center is None else center
    if "displaced_volume" in ds:  # moorline's layout (database units)
        volume = float(ds["displaced_volume"]) / d_l**3
        mass = float(ds.attrs.get("mass", math.nan)) / d_m
        mass = rho * volume if math.isnan(mass) else mass
        cog = c + np.asarray(ds.attrs.get("center_of_gravity", [0.0, 0.0, 0.0]),
                             dtype=float) / d_l
        cob = c + _moorline_center_of_buoyancy(ds) / d_l
    else:
        for name in ("disp_mass", "center_of_buoyancy"):
            if name not in ds:
                raise DatabaseError(name, "missing: needed with hydrostatic_stiffness (the "
                                    "buoyancy's point and size)")
        if "center_of_mass" not in ds.coords and "center_of_mass" not in ds:
            raise DatabaseError("center_of_mass", "missing: needed to take the weight's "
                                "moments out of hydrostatic_stiffness")
        volume = float(ds["disp_mass"]) / rho
        mass = float(ds["inertia_matrix"].sel(influenced_dof="Surge", radiating_dof="Surge")) \
            if "inertia_matrix" in ds else float(ds["disp_mass"])
        cog = np.asarray(ds["center_of_mass"].values, dtype=float).ravel()
        cob = np.asarray(ds["center_of_buoyancy"].values, dtype=float).ravel()
    zb, zg = cob - c, cog - c
    buoyancy, weight = rho * g * volume, mass * g
    S = C.copy()
    S[3, 3] -= buoyancy * zb[2] - weight * zg[2]
    S[4, 4] -= buoyancy * zb[2] - weight * zg[2]
    S[3, 5] -= -buoyancy * zb[0] + weight * zg[0]
    S[4, 5] -= -buoyancy * zb[1] + weight * zg[1]
    S = S * (f_m * d_m) * (f_l * d_l) ** (r[:, None] + r[None, :])
    S[np.abs(S) <= 1e-9 * np.max(np.abs(S), initial=0.0)] = 0.0
    return Hydrostatics(kind="matrix", stiffness=_table(S),
                        volume=volume * (f_l * d_l) ** 3,
                        center_of_buoyancy=tuple(float(x) for x in zb * (f_l * d_l)))


def _moorline_center_of_buoyancy(ds: Any) -> np.ndarray:
    """Centre of buoyancy relative to the body origin of a box or cylinder in moorline's
    layout (database units): the wetted prism's centroid."""
    a = ds.attrs
    if "center_of_buoyancy" in ds:
        return np.asarray(ds["center_of_buoyancy"].values, dtype=float)
    shape, draft = a.get("shape"), float(a.get("draft", math.nan))
    if shape not in ("box", "cylinder") or math.isnan(draft):
        raise DatabaseError("center_of_buoyancy", "missing (needed with "
                            "hydrostatic_stiffness for a hull other than a box or cylinder)")
    height = float(a["dimension_height"])
    z_b = -draft / 2.0 if draft < height else height / 2.0 - draft
    return np.array([0.0, 0.0, z_b - float(a["origin_z"])])
