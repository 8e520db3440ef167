"""Environment: water depth, fluid, gravity, seabed, current and waves (frozen, no logic)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Literal


@dataclass(frozen=True)
class Bathymetry:
    """Seabed heights on a grid (MoorDyn-C's 3-D seafloor file): ``z[i][j]`` [length, z up,
    negative below the surface] at ``(x[i], y[j])``, bilinear in between and constant beyond
    the grid's edges; ``x`` and ``y`` strictly increasing, at least two of each."""

    x: tuple[float, ...]
    y: tuple[float, ...]
    z: tuple[tuple[float, ...], ...]


@dataclass(frozen=True)
class Seabed:
    """Seabed: flat at ``z = -depth``, an inclined plane, or a bathymetry grid.

    Attributes
    ----------
    stiffness
        Contact stiffness per unit of contact area [force/length^3] (MoorDyn ``kBot``, Pa/m).
    damping
        Contact damping per unit of contact area [force*time/length^3] (MoorDyn ``cBot``).
    friction
        Coulomb friction coefficient of the lying part (the closed-form catenary, and the
        default of both dynamic coefficients).
    friction_axial, friction_transverse
        Dynamics: friction coefficients along and across the line (``None``: ``friction``).
    slip_velocity
        Dynamics: regularization speed of the friction law [length/time].
    slope_deg, slope_heading_deg
        An inclined plane through ``(0, 0, -depth)`` going down at ``slope_deg`` towards the
        horizontal direction ``slope_heading_deg`` (0 = +x, 90 = +y); 0: flat.
    bathymetry
        A grid of seabed heights instead of the plane (``None``: the plane).
    """

    stiffness: float = 3.0e6
    damping: float = 3.0e5
    friction: float = 0.0
    friction_axial: float | None = None
    friction_transverse: float | None = None
    slip_velocity: float = 0.01
    slope_deg: float = 0.0
    slope_heading_deg: float = 0.0
    bathymetry: Bathymetry | None = None

    @property
    def is_flat(self) -> bool:
        """True for the horizontal seabed ``z = -depth``."""
        return self.bathymetry is None and self.slope_deg == 0.0


@dataclass(frozen=True)
class Current:
    """Current: uniform ``speed`` [length/time] towards ``heading_deg`` (0 = +x, 90 = +y), or a
    profile over depth: ``speeds`` and ``headings_deg`` at heights ``z_levels`` (linear in z,
    constant beyond the ends; then ``speed`` is ignored)."""

    speed: float = 0.0
    heading_deg: float = 0.0
    z_levels: tuple[float, ...] = ()
    speeds: tuple[float, ...] = ()
    headings_deg: tuple[float, ...] = ()


@dataclass(frozen=True)
class SeaComponents:
    """An explicit linear sea: components ``eta = sum a_j cos(k_j (x cos b_j + y sin b_j) -
    omega_j t + phi_j)`` (:class:`moorline.waves.WaveComponents`, ``k_j`` from the
    dispersion relation).

    Attributes
    ----------
    omegas
        Angular frequencies ``omega_j`` [rad/time], ``> 0``.
    amplitudes
        Amplitudes ``a_j`` [length] (half the component's height), ``>= 0``.
    phases_deg
        Phases ``phi_j`` [deg].
    headings_deg
        Directions of propagation ``b_j`` [deg] (0 = +x); empty: the ``Waves.heading_deg``
        of every component.
    """

    omegas: tuple[float, ...]
    amplitudes: tuple[float, ...]
    phases_deg: tuple[float, ...]
    headings_deg: tuple[float, ...] = ()


@dataclass(frozen=True)
class Waves:
    """Waves: ``kind='none'`` for still water, ``airy`` for a regular wave of ``height`` and
    ``period``, ``random`` for a random sea (:class:`moorline.waves.RandomSea`) of significant
    height ``height`` (``Hs``) and peak period ``period`` (``Tp``) with the ``spectrum``
    (``pierson-moskowitz`` or ``jonswap`` with ``gamma``), ``amplitudes`` ``dsa`` or ``nsa``,
    ``seed``, ``record_length`` (the realization's period) and ``n_frequencies`` (or all up
    to ``omega_max``, default six times the peak frequency), ``components`` for the explicit
    sea ``components`` (:class:`SeaComponents`, e.g. read from a MoorDyn deck's wave file).
    ``stretching='wheeler'`` evaluates the kinematics at Wheeler-stretched heights."""

    kind: Literal["none", "airy", "random", "components"] = "none"
    height: float = 0.0
    period: float = 0.0
    heading_deg: float = 0.0
    phase_deg: float = 0.0
    stretching: Literal["none", "wheeler"] = "none"
    spectrum: Literal["pierson-moskowitz", "jonswap"] = "jonswap"
    gamma: float = 3.3
    amplitudes: Literal["dsa", "nsa"] = "dsa"
    seed: int = 0
    record_length: float = 1800.0
    n_frequencies: int | None = None
    omega_max: float | None = None
    components: SeaComponents | None = None

    @property
    def active(self) -> bool:
        """True when the water surface moves: a positive ``height`` (``airy``, ``random``)
        or a non-zero component amplitude (``components``)."""
        if self.kind == "components":
            return self.components is not None and any(a > 0 for a in self.components.amplitudes)
        return self.kind != "none" and self.height > 0


@dataclass(frozen=True)
class Environment:
    """Everything around the cables.

    Attributes
    ----------
    depth
        Water depth [length]; the seabed is at ``z = -depth``. ``inf`` means no seabed.
    water_density
        Fluid mass density [mass/length^3].
    gravity
        Gravitational acceleration [length/time^2].
    """

    depth: float = float("inf")
    water_density: float = 1025.0
    gravity: float = 9.80665
    seabed: Seabed = field(default_factory=Seabed)
    current: Current = field(default_factory=Current)
    waves: Waves = field(default_factory=Waves)

    @property
    def has_seabed(self) -> bool:
        """True when the water has finite depth (a seabed exists)."""
        return bool(self.depth < float("inf"))
