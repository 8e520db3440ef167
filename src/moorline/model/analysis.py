"""Settings of each analysis a case asks for (frozen, no logic)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

StaticMethod = Literal["newton", "incremental", "relaxation"]


@dataclass(frozen=True)
class StaticsSettings:
    """Static analysis settings (Tuah 4.1).

    Attributes
    ----------
    method
        ``newton``: residual feedback with equilibrium iterations (Tuah eq. 4.1.2; one load
        step = Newton-Raphson) and a line search; ``incremental``: purely incremental loading
        (eq. 4.1.1), no equilibrium correction; ``relaxation``: viscous relaxation
        (eq. 4.1.5-4.1.8) with artificial damping ``C(t) = mu C(t - dt)``.
    load_steps
        Number of load increments (loads and prescribed displacements ramped linearly).
    tolerance
        Convergence tolerance on the residual force norm, relative to the load norm.
    max_iterations
        Iteration limit per load step (relaxation: total).
    stiffness_update
        Refresh the tangent every this many iterations (1 = full Newton).
    damping, damping_decrement, pseudo_dt
        Viscous relaxation: initial damping ``C0`` [force*time/length], ``mu`` and the pseudo
        time step [time].
    start
        Initial shape of the lines: ``catenary`` (closed form between the end positions) or
        ``straight`` (the chord).
    max_step
        Newton: largest node displacement per iteration, as a fraction of the longest line's
        unstretched length (longer steps are scaled down; a guard against slack starts).
    current_drag
        Include the drag of the environment's steady current on the lines and on points with
        a drag area (the lines at rest in the current, as MoorPy's statics with a current).
        A dynamics started from such a state keeps the current on from the start (its
        ``ramp_time`` then ramps the waves only). Not with bodies yet.
    """

    kind: Literal["statics"] = "statics"
    method: StaticMethod = "newton"
    load_steps: int = 1
    tolerance: float = 1.0e-8
    max_iterations: int = 50
    stiffness_update: int = 1
    damping: float = 1.0e5
    damping_decrement: float = 0.5
    pseudo_dt: float = 1.0
    start: Literal["catenary", "straight"] = "catenary"
    max_step: float = 0.5
    current_drag: bool = False


@dataclass(frozen=True)
class OutputSettings:
    """What to write: output interval of time histories [time]."""

    every: float = 0.1


DynamicScheme = Literal["newmark", "hht"]
DynamicVariant = Literal["iterative", "residual_feedback", "incremental"]


@dataclass(frozen=True)
class DynamicsSettings:
    """Time-domain analysis settings (Tuah 1982, sec. 4.2).

    Attributes
    ----------
    duration, dt
        Simulated time and time step [time].
    scheme
        ``newmark`` (beta = 1/4, gamma = 1/2, Tuah eq. 4.2.7) or ``hht`` (Hilber-Hughes-Taylor
        with ``alpha`` in [-1/3, 0]: numerical damping of the highest frequencies).
    alpha
        HHT parameter (ignored by ``newmark``).
    variant
        ``iterative``: equilibrium (Newton) iterations every step until the effective residual
        (eq. 4.2.10) is below tolerance; ``residual_feedback``: one solve per step, the
        residual carried into the next; ``incremental``: one solve per step, no correction.
    tolerance
        Residual tolerance relative to the force scale: the larger of the largest nodal load
        and the largest initial tension.
    max_iterations
        Newton iterations per step before the step is cut.
    stiffness_update
        Refresh the effective tangent at least every this many steps (also whenever Newton
        slows down); the factorization is reused meanwhile.
    max_step_cuts
        How many times a failing step may be halved before giving up.
    ramp_time
        Start-up ramp of waves and current [time].
    viscoelastic_update
        Standard linear solid update: ``exponential`` (exact integration of the Maxwell branch
        over a step, accurate for any dt) or ``incremental`` (Tuah eq. 2.2.b.3).
    rayleigh_ratio, rayleigh_frequencies
        Rayleigh damping ``a0 M + a1 K`` with this damping ratio at the two circular
        frequencies [rad/s] (systems with bodies; Wang, Er and Iu use 0.03).
    fast_path
        Use the compiled step (:mod:`moorline.solvers.fast_newmark`) when the model allows
        it (elastic lines, still water or uniform current, Newmark, iterative); same results.
    """

    kind: Literal["dynamics"] = "dynamics"
    duration: float = 10.0
    dt: float = 0.05
    scheme: DynamicScheme = "newmark"
    alpha: float = -0.05
    variant: DynamicVariant = "iterative"
    tolerance: float = 1.0e-6
    max_iterations: int = 20
    stiffness_update: int = 20
    max_step_cuts: int = 10
    ramp_time: float = 0.0
    viscoelastic_update: Literal["exponential", "incremental"] = "exponential"
    fast_path: bool = True
    rayleigh_ratio: float = 0.0
    rayleigh_frequencies: tuple[float, float] = (0.0, 0.0)


ModalMass = Literal["lumped", "consistent"]


@dataclass(frozen=True)
class ModalSettings:
    """Modal analysis settings: natural frequencies and modes about the static equilibrium
    (Tuah 1982, sec. 3.2.b step 4 and sec. 5.3).

    Attributes
    ----------
    n_modes
        Number of lowest modes wanted (ignored when ``band`` is given).
    band
        ``(low, high)`` circular frequencies [rad/time]: all modes in this band instead of the
        lowest ``n_modes``; ``None``: the lowest ``n_modes``.
    mass
        ``lumped`` (half of each element to each node) or ``consistent`` (Tuah eq. 3.1.12)
        structural mass.
    added_mass
        Include the hydrodynamic added mass (element normal/tangential and points).
    """

    kind: Literal["modal"] = "modal"
    n_modes: int = 10
    band: tuple[float, float] | None = None
    mass: ModalMass = "lumped"
    added_mass: bool = True


@dataclass(frozen=True)
class StrummingAnalysis:
    """Strumming (vortex-induced vibration) settings of a case (Tuah 1982 sec. 3.2.b): see
    :class:`moorline.solvers.strumming.StrummingSettings` for the meaning of each field. The
    in-line state is the run's preceding dynamics result when there is one, else its static
    state held for ``duration`` (a steady current)."""

    kind: Literal["strumming"] = "strumming"
    viscosity: float = 1.0e-6
    strouhal: float = 0.2
    CL0: float = 0.2
    n_modes: int = 6
    substeps: int = 1
    refresh_every: int = 0
    duration: float = 10.0
    dt: float = 0.001
    transverse_velocity: Literal["signed", "magnitude"] = "signed"
    min_reynolds: float = 0.0
    nonpositive_modes: Literal["error", "keep"] = "error"
    drag_damping: bool = False
    taut_axial: bool = False
    held_body_dofs: tuple[str, ...] = ()


@dataclass(frozen=True)
class StochasticSettings:
    """Frequency-domain stochastic analysis in the case's random sea (Tuah 1982 ch. 5): see
    :mod:`moorline.solvers.stochastic`.

    Attributes
    ----------
    method
        ``foss`` (mode superposition with Foss's decoupling, the source's) or ``direct``
        (the full linear system solved at every frequency).
    n_modes
        Modes superposed by ``foss``; 0: all.
    max_iterations, tolerance
        Of the statistical drag linearization: stop when no standard deviation of the
        relative velocity changes by more than ``tolerance`` (relative; the source: 0.01).
    mass, added_mass
        Mass model (Tuah: consistent) and whether the added mass is included.
    n_points
        Points of the time series over one record (the source's ``2N``); default the
        smallest power of two above four times the number of frequencies.
    """

    kind: Literal["stochastic"] = "stochastic"
    method: Literal["foss", "direct"] = "foss"
    n_modes: int = 0
    max_iterations: int = 30
    tolerance: float = 0.01
    mass: Literal["lumped", "consistent"] = "consistent"
    added_mass: bool = True
    n_points: int | None = None


@dataclass(frozen=True)
class HarmonicSettings:
    """Harmonic-balance settings: the periodic response (Tcheou 1997; see
    :mod:`moorline.solvers.harmonic`).

    Attributes
    ----------
    period
        Period of the excitation and the response [time].
    harmonics
        Number of harmonics ``n`` kept (the mean and ``n`` cosine-sine pairs).
    samples
        Instants per period of the residual evaluation (default ``4 (n + 1)``).
    tolerance
        Newton stops when the largest harmonic residual is below ``tolerance`` times the
        load scale.
    max_iterations
        Newton iteration limit.
    output_points
        Instants per period of the reconstructed histories.
    """

    kind: Literal["harmonic"] = "harmonic"
    period: float = 10.0
    harmonics: int = 5
    samples: int | None = None
    tolerance: float = 1e-8
    max_iterations: int = 50
    output_points: int = 64
