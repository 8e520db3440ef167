"""A body's ``hydrodynamics:`` case key: a hydrodynamic database read from NetCDF, or
computed with capytaine and cached.

``hydrodynamics: {database: file.nc}`` reads a database (capytaine's own dataset format or
:func:`moorline.bem.body_coefficients`' layout, :mod:`moorline.io.hydro_database`), the path
relative to the case file. ``hydrodynamics: {bem: {...}}`` computes it
(:func:`moorline.bem.capytaine_database`) for a ``box``, ``cylinder`` or mesh file at the
case's water density, gravity, depth and wave heading, the body's mass and centre of
gravity, with the rigid-body dofs about the body origin (its ``position``; the still water
line is z = 0), and caches it as NetCDF in capytaine's format in :func:`cache_directory`,
named by the SHA-256 of every input (a mesh file by its content) and capytaine's version:
a second run with the same inputs reads the file instead of solving again, and says so.
"""

from __future__ import annotations

import hashlib
import json
import logging
import math
import os
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import CaseError, MoorlineError
from ..user_cache import CACHE_ENV, cache_root
from .files import file_problem
from .hydro_database import BodyHydrodynamics, DatabaseError, from_dataset, read_database

__all__ = ["CACHE_ENV", "MAX_DATABASE_BYTES", "body_hydrodynamics", "bem_inputs",
           "cache_directory"]

logger = logging.getLogger(__name__)

MAX_DATABASE_BYTES = 1024**3
"""Largest database file read [bytes] (1 GiB; a 6-dof body at 200 frequencies and 36
headings is about 1 MB)."""

CACHE_FORMAT = 1
"""Bumped when what moorline writes to the cache changes (part of the key)."""


def cache_directory() -> Path:
    """Where computed databases are cached: ``$MOORLINE_CACHE_DIR/bem``, else
    ``$XDG_CACHE_HOME/moorline/bem``, else ``~/.cache/moorline/bem``
    (:func:`moorline.user_cache.cache_root`)."""
    return cache_root() / "bem"


def body_hydrodynamics(name: str, body: Any, environment: Any, units: str,
                       source: str | None) -> BodyHydrodynamics:
    """Resolve ``bodies.<name>.hydrodynamics`` of a validated case.

    Parameters
    ----------
    name
        The body.
    body
        Its :class:`moorline.io.schema.BodySpec` (``hydrodynamics`` set).
    environment
        The case's :class:`moorline.model.Environment` (density, gravity, depth, waves).
    units
        The case's unit system.
    source
        The case file (paths are relative to its directory), or ``None``.

    Returns
    -------
    BodyHydrodynamics

    Raises
    ------
    CaseError
        Naming the case file, the key and the problem (a missing or bad database, a
        failed BEM computation, capytaine not installed).
    """
    spec = body.hydrodynamics
    key = f"bodies.{name}.hydrodynamics"
    base = Path(source).parent if source else Path.cwd()
    case = {"units": units, "origin_z": float(body.position[2]),
            "water_density": environment.water_density, "gravity": environment.gravity,
            "depth": environment.depth, "heading_deg": environment.waves.heading_deg}

    def note(text: str) -> None:
        logger.info("body %s: %s", name, text)

    if spec.database is not None:
        path = (base / spec.database).resolve()
        problem = file_problem(path, MAX_DATABASE_BYTES)
        if problem is not None:
            raise CaseError(f"cannot read the database {str(path)!r}: {problem}", source,
                            f"{key}.database")
        try:
            return read_database(path, **case, note=note)
        except (DatabaseError, MoorlineError) as exc:
            raise CaseError(f"database {str(path)!r}: {exc}", source,
                            f"{key}.database") from None
    inputs = bem_inputs(name, body, environment, units, base, source)
    try:
        dataset = _cached_database(inputs, name)
        return from_dataset(dataset, **case, note=note)
    except (DatabaseError, MoorlineError) as exc:
        raise CaseError(f"BEM database: {exc}", source, f"{key}.bem") from None


def bem_inputs(name: str, body: Any, environment: Any, units: str, base: Path,
               source: str | None) -> dict[str, Any]:
    """Every input of a body's BEM computation (the cache key), checked."""
    bem = body.hydrodynamics.bem
    key = f"bodies.{name}.hydrodynamics.bem"
    omega = bem.omega
    if omega.n < 2 or omega.max <= omega.min:
        raise CaseError(f"needs n >= 2 frequencies and max > min, got n = {omega.n}, "
                        f"min = {omega.min:g}, max = {omega.max:g}", source, f"{key}.omega")
    headings = bem.heading_deg
    if headings is None:
        headings = [environment.waves.heading_deg]
    elif not isinstance(headings, list):
        headings = [headings]
    inputs: dict[str, Any] = {
        "format": CACHE_FORMAT, "units": units,
        "omegas": [float(w) for w in np.linspace(omega.min, omega.max, omega.n)],
        "headings_deg": sorted(float(h) for h in headings),
        "water_density": environment.water_density, "gravity": environment.gravity,
        "depth": environment.depth if math.isfinite(environment.depth) else "inf",
        "mass": body.mass, "center_of_gravity": [float(c) for c in body.center_of_gravity],
        "origin_z": float(body.position[2]), "panel_size": bem.panel_size, "lid": bem.lid,
        "infinite_frequency": bem.infinite_frequency,
    }
    if bem.shape in ("box", "cylinder"):
        need = ("length", "width", "height") if bem.shape == "box" else ("diameter", "height")
        dims = bem.dimensions
        missing = [k for k in need if dims is None or getattr(dims, k) is None]
        if missing:
            raise CaseError(f"a {bem.shape} needs dimensions {', '.join(need)}; missing "
                            f"{', '.join(missing)}", source, f"{key}.dimensions")
        extra = [k for k in ("length", "width", "height", "diameter")
                 if k not in need and getattr(dims, k) is not None]
        if extra:
            raise CaseError(f"a {bem.shape} takes {', '.join(need)}, not {', '.join(extra)}",
                            source, f"{key}.dimensions")
        if bem.draft is None:
            raise CaseError(f"a {bem.shape} needs its draft", source, f"{key}.draft")
        inputs.update(shape=bem.shape, dimensions={k: getattr(dims, k) for k in need},
                      draft=bem.draft)
    else:
        path = (base / bem.shape).resolve()
        problem = file_problem(path, MAX_DATABASE_BYTES)
        if problem is not None:
            raise CaseError(f"shape is box, cylinder or a mesh file; cannot read the mesh "
                            f"file {str(path)!r}: {problem}", source, f"{key}.shape")
        if bem.dimensions is not None or bem.draft is not None:
            raise CaseError("a mesh file hull takes no dimensions or draft (the mesh is "
                            "placed with the water line at z = 0)", source, f"{key}.shape")
        inputs.update(shape="mesh", mesh_file=str(path),
                      mesh_sha256=hashlib.sha256(path.read_bytes()).hexdigest())
    return inputs


def _cache_key(inputs: dict[str, Any], capytaine_version: str) -> str:
    keyed = {k: v for k, v in inputs.items() if k != "mesh_file"}
    keyed["capytaine_version"] = capytaine_version
    text = json.dumps(keyed, sort_keys=True, default=repr)
    return hashlib.sha256(text.encode()).hexdigest()[:24]


def _cached_database(inputs: dict[str, Any], name: str) -> Any:
    """The capytaine dataset of ``inputs``: read from the cache, or computed and cached."""
    import xarray as xr

    from ..bem import _capytaine, write_capytaine_netcdf

    cpt = _capytaine()
    version = str(getattr(cpt, "__version__", "unknown"))
    directory = cache_directory()
    path = directory / f"bem-{_cache_key(inputs, version)}.nc"
    if path.is_file():
        try:
            with xr.open_dataset(path) as handle:
                dataset = handle.load()
        except (OSError, ValueError, RuntimeError) as exc:
            logger.warning("body %s: cached BEM database %s is unreadable (%s): recomputing",
                           name, path, exc)
        else:
            logger.warning("body %s: using the cached BEM database %s", name, path)
            return dataset
    logger.warning("body %s: computing its BEM database with capytaine %s (%d frequencies, "
                   "%d headings); it will be cached in %s", name, version,
                   len(inputs["omegas"]), len(inputs["headings_deg"]), path)
    depth = inputs["depth"]
    try:
        dataset = _solve(inputs, depth)
    except (ValueError, RuntimeError, NotImplementedError, np.linalg.LinAlgError) as exc:
        raise MoorlineError(f"capytaine failed: {exc}") from None
    dataset.attrs["moorline_cache_inputs"] = json.dumps(inputs, sort_keys=True, default=repr)
    partial = path.with_name(f"{path.name}.{os.getpid()}.part")
    try:
        write_capytaine_netcdf(dataset, partial)
        os.replace(partial, path)
    except OSError as exc:
        logger.warning("body %s: could not cache the BEM database in %s (%s)", name, path,
                       exc)
        partial.unlink(missing_ok=True)
        return dataset
    with xr.open_dataset(path) as handle:  # what a second run reads
        return handle.load()


def _solve(inputs: dict[str, Any], depth: Any) -> Any:
    from .. import bem

    return bem.capytaine_database(
        inputs["shape"], inputs.get("dimensions"), inputs.get("draft"), inputs["omegas"],
        inputs["water_density"], inputs["gravity"],
        None if depth == "inf" else float(depth), units=inputs["units"],
        headings_deg=inputs["headings_deg"], mass=inputs["mass"],
        center_of_gravity=inputs["center_of_gravity"], panel_size=inputs["panel_size"],
        lid=inputs["lid"], origin_z=inputs["origin_z"], mesh_file=inputs.get("mesh_file"),
        infinite_frequency=inputs["infinite_frequency"])
