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
        Include the drag of the environment's steady current on the lines, on points with
        a drag area and on bodies with a drag area (at their origin,
        :func:`moorline.solvers.statics.body_current_drag`) (the system at rest in the
        current, as MoorPy's statics with a current). A dynamics started from such a state
        keeps the current on from the start (its ``ramp_time`` then ramps the waves only).
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
    """What to write: output interval of time histories [time]; ``channels``: MoorDyn output
    channel names (``FairTen1``, ``L1N10T``, ...) a dynamics run also writes as a CSV table
    (:mod:`moorline.io.moordyn_outputs`)."""

    every: float = 0.1
    channels: tuple[str, ...] = ()


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
        Rayleigh damping ``a0 M + a1 K`` (``M`` and ``K`` at the start of the run, over all
        unknowns: lines, points and bodies) with this damping ratio at the two circular
        frequencies [rad/s] (Wang, Er and Iu use 0.03).
    fast_path
        Use the compiled step (:mod:`moorline.solvers.fast_newmark`) when the model allows
        it (elastic lines; still water, a uniform current, linear waves; Newmark or HHT,
        iterative); same results.
    envelope_start
        Time from which the output records enter the tension envelope (min, max, mean, std
        per element, :mod:`moorline.envelope`); ``None``: ``ramp_time`` (after the ramp).
    slack_damping, drag_velocity
        MoorDyn's choices where moorline's differ (:class:`~moorline.solvers.dynamic_model.
        DynamicModel`; both run in the compiled kernel and loop): ``slack_damping`` keeps
        the axial dashpot ``BA`` in slack elements; ``drag_velocity: node`` evaluates each
        node's share of an element's drag at the node's own velocity instead of the
        element's mean velocity (``element``). They change the slack, grounded part of a
        line most (issue 16, the OC3 minimum tension: ``benchmarks/min_tension_study.py``).
    start
        What the run starts from: ``statics`` (the static equilibrium, solved unless a
        preceding statics analysis gives it) or ``initial``: the bodies at rest at the poses
        the case gives and the lines at rest in their static shape with the bodies held
        there (MoorDyn's line initial condition with its bodies fixed;
        :func:`moorline.solvers.statics.lines_at_rest`): decay tests and free falls of
        bodies without a static equilibrium.
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
    envelope_start: float | None = None
    slack_damping: bool = False
    drag_velocity: Literal["element", "node"] = "element"
    start: Literal["statics", "initial"] = "statics"


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
class StrummingSettings:
    """Settings of the strumming analysis (Tuah (1982) sec. 3.2.b; see
    :mod:`moorline.solvers.strumming`), ``kind: strumming`` in a case file. The in-line state
    is the run's preceding dynamics result when there is one, else its static state held for
    ``duration`` (a steady current).

    Attributes
    ----------
    viscosity
        Kinematic viscosity of the fluid ``nu`` [length^2/time] (eq. 3.2.b.6, 3.2.b.8).
    strouhal
        Strouhal number ``S_T`` (eq. 3.2.b.4).
    CL0
        Lift-coefficient amplitude of the stationary cylinder.
    n_modes
        Number of (lowest) modes superposed; 0: all of them (a complete basis: the state is
        carried over exactly when the modes are refreshed).
    mass, added_mass
        Mass model of the modal analysis (Tuah uses the consistent mass, eq. 3.1.12) and
        whether the added mass is included.
    substeps
        Runge-Kutta steps per in-line step (``delta t = Delta t / substeps``).
    refresh_every
        In-line steps between recomputations of the modes; 0: modes computed once.
    initial_CL
        Lift coefficient at the start, with ``C_L' = 0`` (default ``CL0``: the shedding of
        the still cable is established, the wake on its stationary limit cycle).
    duration, dt
        Duration and in-line step when the in-line state is steady (a static result).
    min_reynolds
        Elements whose Reynolds number ``|V_NR| D / nu`` is below this shed no vortices:
        their wake oscillator is held (``C_L`` frozen) and they carry no lift. Needed in
        waves, where the flow at every element reverses twice per period and ``w_s -> 0``
        makes the empirical ``k_s`` (eq. 3.2.b.6) diverge; a cylinder sheds no vortices below
        ``Re ~ 40``. Default 0: every element with ``|V_NR| > 0`` sheds.
    nonpositive_modes
        What to do with modes of non-positive ``w^2`` at an in-line state (a slack line, a
        mechanism such as a single-point-moored body's yaw, a linearization about a
        non-equilibrium state that is momentarily unstable): ``error`` (default) stops;
        ``keep`` integrates their modal equations with ``w_n^2`` as it is (``<= 0``) and the
        damping of eq. 3.2.b.8 at ``|w_n|``.
    drag_damping
        Add to the modal damping of eq. 3.2.b.8 the Morison drag linearized about the
        in-line relative velocity (the exact Jacobian ``-dF_drag/dv`` of
        :func:`moorline.physics.hydro.drag_forces` at each in-line step, projected on the
        modes: a full modal damping matrix). Not in the source, whose modal equations carry
        only the viscous damping of eq. 3.2.b.8; without it a slack part of a line (no
        stiffness) has neither restoring nor damping against the lift. Default ``False``.
    taut_axial
        Modes with the taut axial stiffness ``EA / L0`` in every element, slack ones
        included (and the geometric stiffness of ``max(T, 0)``). The strumming perturbation
        is transverse ("the transverse motion is assumed to fluctuate about the inline
        motion", sec. 3.2.b): it does not decide which elements are slack, the in-line
        motion does. Without it a slack element has no axial stiffness, the lift drifts the
        slack legs along their length and every snap of the in-line motion pumps that drift
        into the tangent's ``EA / L0``: the linearized perturbation grows without bound
        (Tuah's Example 7 with modes refreshed). Default ``False`` (the exact tangent).
    held_body_dofs
        Rigid-body degrees of freedom (``surge``, ``sway``, ``heave``, ``roll``, ``pitch``,
        ``yaw``) held fixed in the strumming modes of every body. A mechanism whose
        linearized stiffness turns negative at the in-line states (the yaw of a disc moored
        at one keel point: none at rest, negative when the disc is tilted and the keel swings
        off its axis) makes the linear perturbation grow exponentially: an instability of the
        in-line motion, not strumming; holding it keeps the analysis to the lines'
        transverse vibration.
    transverse_velocity
        ``signed`` (default): the wake oscillator is driven by the strumming velocity along
        the lift direction, ``U_T' = e_L . u'`` (Griffin et al. 1975; this is what
        synchronizes wake and structure). ``magnitude``: by ``|U_T'|``, the literal reading of
        Tuah's "the transverse cable velocity magnitude" (eq. 3.2.b.3), which rectifies the
        forcing and only raises ``C_L`` a little above ``C_L0``.
    """

    kind: Literal["strumming"] = "strumming"
    viscosity: float = 1.0e-6
    strouhal: float = 0.2
    CL0: float = 0.2
    n_modes: int = 6
    mass: ModalMass = "consistent"
    added_mass: bool = True
    substeps: int = 1
    refresh_every: int = 0
    initial_CL: float | None = None
    duration: float = 10.0
    dt: float = 0.001
    transverse_velocity: Literal["signed", "magnitude"] = "signed"
    min_reynolds: float = 0.0
    nonpositive_modes: Literal["error", "keep"] = "error"
    drag_damping: bool = False
    taut_axial: bool = False
    held_body_dofs: tuple[str, ...] = ()


#: The name case files and older code use for :class:`StrummingSettings`.
StrummingAnalysis = StrummingSettings


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
        Modes superposed by ``foss``; 0: all, by solving the full system at every frequency
        (the same result as Foss's sum over every mode, :mod:`moorline.solvers.stochastic`).
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


@dataclass(frozen=True)
class FatigueSettings:
    """Fatigue analysis settings (``kind: fatigue``; see :mod:`moorline.fatigue_analysis`):
    Miner damage and life from the run's preceding dynamics or stochastic analysis.

    Attributes
    ----------
    source
        ``auto`` (the latest of the two), ``dynamics`` or ``stochastic``.
    curves
        Per line type: ``{"curve": name, "MBL": ..., "diameter": ..., "area": ...}``; the
        curve a key of ``moorline/data/tn_curves.yaml``; ``MBL`` the reference breaking
        strength of API T-N curves [force] (default: the line type's ``MBL`` where line
        types have one); ``diameter`` (chain, nominal area
        ``2 pi d^2 / 4``) or ``area`` for DNV S-N curves [length, area]. Line types not
        listed get no damage (NaN).
    spectral
        Frequency-domain methods: ``narrow_band`` and/or ``dirlik``.
    residue
        Rainflow residue: ``half`` cycles (ASTM E1049-85) or ``repeat`` (closed).
    skip
        Start-up time discarded from the histories [time]; ``None``: the dynamics'
        ``ramp_time``.
    safety_factor
        Design fatigue factor: the life is the duration over ``safety_factor * damage``.
    seeds
        Wave seeds of further realizations (time domain): the preceding dynamics is run again
        with each and the damage is the mean over the realizations (the case's own seed is
        the first); runs shared with an extremes analysis listing the same seeds.
    """

    kind: Literal["fatigue"] = "fatigue"
    source: Literal["auto", "dynamics", "stochastic"] = "auto"
    curves: dict | None = None
    spectral: tuple[str, ...] = ("narrow_band", "dirlik")
    residue: Literal["half", "repeat"] = "half"
    skip: float | None = None
    safety_factor: float = 1.0
    seeds: tuple[int, ...] = ()


@dataclass(frozen=True)
class ExtremesSettings:
    """Extremes analysis settings (``kind: extremes``; see :mod:`moorline.extremes_analysis`):
    most probable maximum tensions from the run's preceding dynamics or stochastic analysis.

    Attributes
    ----------
    source
        ``auto`` (the latest of the two), ``dynamics`` or ``stochastic``.
    duration
        Exposure of the most probable maximum [time] (default 3 h).
    method
        Time domain: ``weibull`` (fit of the peaks over the mean) or ``gumbel`` (fit of the
        maxima of the realizations, each cut into ``blocks``).
    percentiles
        Tension percentiles reported [%].
    seeds
        Wave seeds of further realizations: the preceding dynamics is run again with each
        (time domain; the case's own seed is the first realization).
    blocks
        Gumbel: blocks each realization is cut into.
    skip
        Start-up time discarded from the histories [time]; ``None``: the dynamics'
        ``ramp_time``.
    """

    kind: Literal["extremes"] = "extremes"
    source: Literal["auto", "dynamics", "stochastic"] = "auto"
    duration: float = 10800.0
    method: Literal["weibull", "gumbel"] = "weibull"
    percentiles: tuple[float, ...] = (50.0, 90.0, 99.0)
    seeds: tuple[int, ...] = ()
    blocks: int = 1
    skip: float | None = None


@dataclass(frozen=True)
class OffsetSettings:
    """Offset analysis settings (``kind: offset``; see :mod:`moorline.solvers.offset`): a
    body, or a rigid group of points, moved through horizontal offsets along headings (and
    optionally turned in yaw), the lines in static equilibrium at each offset.

    Attributes
    ----------
    headings
        Directions of the offsets in the horizontal plane [deg], from +x towards +y.
    max_offset
        Largest offset [length]; the offsets run from ``-max_offset`` to ``+max_offset``.
    steps
        Offsets per heading, an odd number (the middle one is the undisplaced state).
    yaw
        Also turn the group about the vertical axis through the reference point, from
        ``-max_yaw`` to ``+max_yaw`` in ``steps`` steps.
    max_yaw
        Largest yaw angle [deg].
    body
        The body moved (held at each offset pose: all six dofs prescribed); ``None``: the
        ``points``.
    points
        Prescribed points moved rigidly together (like fairleads on a vessel); empty: every
        prescribed point of the case (or its only body when it has one and no prescribed
        point).
    reference
        Reference point of the moments and of the yaw [length]; ``None``: the body origin, or
        the centroid of the points.
    stiffness
        Store the 6x6 stiffness (:func:`moorline.solvers.stiffness.group_stiffness`) at
        every offset.
    """

    kind: Literal["offset"] = "offset"
    headings: tuple[float, ...] = (0.0,)
    max_offset: float = 10.0
    steps: int = 21
    yaw: bool = False
    max_yaw: float = 10.0
    body: str | None = None
    points: tuple[str, ...] = ()
    reference: tuple[float, float, float] | None = None
    stiffness: bool = True
