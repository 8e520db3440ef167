"""Rigid bodies (buoys, platforms) that lines attach to (Tuah 1982 sec. 3.2.c, 3.3; Wang, Er
and Iu, eq. 24-34). Frozen descriptions only."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Literal

from .components import Motion

Vector3 = tuple[float, float, float]
Matrix6 = tuple[tuple[float, ...], ...]
HydrostaticsKind = Literal["none", "box", "cylinder", "matrix", "rods"]
Rod = tuple[Vector3, Vector3, float]


@dataclass(frozen=True)
class Hydrostatics:
    """Buoyancy and hydrostatic restoring of a body.

    Attributes
    ----------
    kind
        ``box`` (length along body x, width along body y, height), ``cylinder`` (vertical,
        diameter, height): buoyancy from the submerged volume at the current draft, acting at
        the centre of buoyancy, and roll/pitch restoring from the waterplane inertia; the body
        frame origin is the shape's geometric centre. ``matrix``: a constant 6x6 ``stiffness``
        about the initial pose plus a constant buoyancy ``volume`` at ``center_of_buoyancy``
        (body frame). ``rods``: slender cylinders ``rods`` (end A, end B in the body frame,
        diameter) whose buoyancy is recomputed at each pose from their submerged part under
        ``z = 0``, with a piercing rod's waterplane moment
        (:mod:`moorline.physics.rod_buoyancy`), plus a constant buoyancy ``volume``
        at ``center_of_buoyancy`` (e.g. a MoorDyn body's own volume). ``none``: no
        hydrostatics.
    """

    kind: HydrostaticsKind = "none"
    length: float = 0.0
    width: float = 0.0
    height: float = 0.0
    diameter: float = 0.0
    stiffness: Matrix6 | None = None
    volume: float = 0.0
    center_of_buoyancy: Vector3 = (0.0, 0.0, 0.0)
    rods: tuple[Rod, ...] = ()


@dataclass(frozen=True)
class WaveExcitation:
    """First-order wave exciting force per unit wave amplitude, over frequency (from a
    diffraction code, e.g. ``moorline bem``), about the body origin, world axes.

    Attributes
    ----------
    omegas
        Circular frequencies [rad/s], increasing.
    amplitude
        Force (and moment) amplitude per unit wave amplitude, (n_omega, 6).
    phase_deg
        Phase of each component [deg], (n_omega, 6): the force is
        ``a |X| cos(omega t - k x_0 + phase)`` for a wave ``eta = a cos(k x - omega t)``
        passing the body origin ``x_0`` (Tuah 1982 sec. 3.2.c).
    """

    omegas: tuple[float, ...]
    amplitude: tuple[tuple[float, ...], ...]
    phase_deg: tuple[tuple[float, ...], ...]


@dataclass(frozen=True)
class RadiationTable:
    """Frequency-dependent added mass and radiation damping of a body (a hydrodynamic
    database, e.g. capytaine's), about the body origin, world axes, in the case's units
    (Tuah 1982 sec. 3.2.c: the radiation force coefficients ``f_lj(omega)``).

    In the time domain it gives the Cummins (1962) equation: the infinite-frequency added
    mass plus a convolution of the velocity history with the retardation kernels
    ``K_ij(t) = 2/pi int_0^inf B_ij(w) cos(w t) dw``; in the frequency domain ``A(w)`` and
    ``B(w)`` are interpolated at each frequency.

    Attributes
    ----------
    omegas
        Circular frequencies [rad/s], increasing, n_omega >= 2.
    added_mass, damping
        ``A_ij(w)``, ``B_ij(w)``, shape (n_omega, 6, 6), ``[i][j]`` the force in dof ``i`` per
        acceleration / velocity of dof ``j``.
    added_mass_infinite
        ``A_ij(inf)`` (6, 6) when the database gives it (capytaine's ``omega = inf``
        problem); ``None``: derived from the table (Ogilvie 1964).
    """

    omegas: tuple[float, ...]
    added_mass: tuple[Matrix6, ...]
    damping: tuple[Matrix6, ...]
    added_mass_infinite: Matrix6 | None = None


@dataclass(frozen=True)
class Body:
    """A six-degree-of-freedom rigid body.

    Attributes
    ----------
    name
        Identifier; points attach with ``kind: body`` and ``body: <name>``.
    kind
        ``free`` (solved for), ``fixed`` (held at its pose; its reaction is reported) or
        ``pinned``: its origin is a pin held at ``position`` (plus ``motion``), its rotation
        free (MoorDyn's ``Pinned``/``CoupledPinned`` rods and ``CoupledPinned`` bodies; the
        pin's reaction is reported).
    position
        Position of the body frame origin [length] (the initial guess for a free body, the
        pin of a pinned body).
    rotation
        Initial rotation vector [rad] (axis times angle).
    mass
        Mass [mass].
    center_of_gravity
        Centre of gravity in the body frame [length].
    inertia
        Inertia tensor about the centre of gravity in the body frame [mass*length^2].
    added_mass, damping
        Constant 6x6 added mass and linear (radiation) damping about the body origin, world
        axes (Tuah eq. 3.2.c.20), in SI-consistent units of the case.
    hydrostatics
        Buoyancy and restoring.
    force
        Constant external force and moment about the body origin (world axes) [force, force*
        length], e.g. a wind load.
    force_history
        Time-varying force at the body origin (world axes), e.g. Wang's ``F_x = A sin(w t)``.
    drag_area, Cd
        Quadratic drag on the relative velocity at the body origin, per world direction:
        ``1/2 rho Cd A_i |u_i| u_i`` (a small body such as a disc buoy).
    excitation
        Wave exciting forces (amplitude and phase per dof over frequency, interpolated at the
        environment's regular wave), used instead of the long-wave model.
    radiation
        Frequency-dependent added mass and damping (:class:`RadiationTable`); when given,
        ``added_mass`` and ``damping`` must be ``None`` (the table replaces them).
    motion
        A pinned body only: a displacement history of its pin (added to ``position`` in
        dynamics, as a prescribed point's ``motion``); ``None``: the pin stays put.
    pin_body
        A pinned body only: the free or fixed body its pin sits on (MoorDyn's
        ``Body<k>Pinned`` rods); ``position`` is then where the pin is at both bodies' initial
        poses, and the pin moves with that body. ``None``: the pin is held in space.
    additional_damping
        Constant 6x6 linear damping added to the radiation damping (viscous damping not in a
        potential-flow table, e.g. OC3-Hywind's additional linear damping, Jonkman 2010
        table 5-1), about the body origin, world axes; allowed with or without ``radiation``.
    wave_loads
        Long-wave (small-body) excitation from the fluid field at the body origin: the
        Froude-Krylov and added-mass force ``(rho V + A) a_fluid`` and the waterplane heave
        excitation ``rho g A_wp eta`` (box or cylinder: its waterplane; matrix hydrostatics:
        ``A_wp = K33 / (rho g)``). Diffraction coefficients (Tuah
        sec. 3.2.c) are not computed here; a BEM code can supply ``added_mass``/``damping``.
    """

    name: str
    kind: Literal["free", "fixed", "pinned"] = "free"
    position: Vector3 = (0.0, 0.0, 0.0)
    rotation: Vector3 = (0.0, 0.0, 0.0)
    mass: float = 0.0
    center_of_gravity: Vector3 = (0.0, 0.0, 0.0)
    inertia: tuple[Vector3, Vector3, Vector3] = ((0.0, 0.0, 0.0),) * 3
    added_mass: Matrix6 | None = None
    damping: Matrix6 | None = None
    hydrostatics: Hydrostatics = field(default_factory=Hydrostatics)
    force: tuple[float, float, float, float, float, float] = (0.0,) * 6
    force_history: Motion | None = None
    drag_area: Vector3 = (0.0, 0.0, 0.0)
    Cd: float = 1.0
    wave_loads: bool = False
    excitation: WaveExcitation | None = None
    radiation: RadiationTable | None = None
    additional_damping: Matrix6 | None = None
    motion: Motion | None = None
    pin_body: str | None = None

    def __post_init__(self) -> None:
        for key in ("motion", "pin_body"):
            if getattr(self, key) is not None and self.kind != "pinned":
                raise ValueError(f"body {self.name!r}: only a pinned body takes a {key}, this "
                                 f"one is {self.kind}")
        if self.motion is not None and self.pin_body is not None:
            raise ValueError(f"body {self.name!r}: a pin on a body moves with it: no motion")
        if self.radiation is not None and (self.added_mass is not None
                                           or self.damping is not None):
            raise ValueError(f"body {self.name!r}: give either a radiation table or "
                             "constant added_mass/damping, not both (the table replaces "
                             "them)")
