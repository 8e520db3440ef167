"""Line types, points and lines: the parts a cable system is made of (frozen, no logic)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

Vector3 = tuple[float, float, float]
PointKind = Literal["fixed", "free", "prescribed", "body"]
MaterialKind = Literal["elastic", "viscoelastic", "static_dynamic", "syrope"]


@dataclass(frozen=True)
class LineType:
    """Cross-section properties shared by lines of one kind.

    Attributes
    ----------
    name
        Identifier used by lines.
    diameter
        Hydrodynamic (volume-equivalent) diameter [length].
    mass_per_length
        Dry mass per unstretched length [mass/length].
    EA
        Axial stiffness [force]. For a viscoelastic line, the long-term (quasi-static) K0*A.
    displaced_area
        Displaced cross-section [length^2]; ``None`` means ``pi d^2 / 4``.
    Cd, Ca, Ct, Cat
        Normal drag, normal added mass, tangential drag and tangential added-mass coefficients.
    material
        ``elastic`` (no compression), ``viscoelastic`` (standard linear solid, Tuah 2.2.b) or
        ``static_dynamic`` (MoorDyn's viscoelastic rope with a mean-load dependent dynamic
        stiffness, :mod:`moorline.physics.static_dynamic`: static stiffness ``EA``, dynamic
        stiffness ``EAd + EAd_Lm s``, static-branch damping ``BA`` and dynamic-branch damping
        ``BA_dynamic``) or ``syrope`` (MoorDyn's Syrope polyester rope with load-history
        dependent working curves, :mod:`moorline.physics.syrope`: ``owc``, ``working_curve``,
        ``wc_k1``, ``wc_k2``, dynamic stiffness ``EAd + EAd_Lm T``, dampings ``BA`` and
        ``BA_dynamic`` as ``static_dynamic``; ``EA`` is a reference stiffness, the OWC's
        largest tangent).
    EA1
        Viscoelastic: extra instantaneous stiffness K1*A [force]; instantaneous is EA + EA1.
    tau
        Viscoelastic characteristic time [time].
    slack_stiffness_ratio
        Fraction of EA a slack element keeps in compression, so the tangent stays usable
        (Tuah 6.2: "the modulus E for the slack element is set to a very small value").
    MBL
        Minimum breaking load [force]; ``None``: unknown (no design check).
    EA_dynamic
        Dynamic axial stiffness of a fibre rope [force], stored for reference (the solvers
        use ``EA``); ``None``: not given.
    catalog, nominal_diameter
        The line catalogue entry and nominal diameter [length] the properties came from
        (:mod:`moorline.catalog`), ``None`` for a line type given by hand.
    EA_table
        Tension-strain law as ``(strain, tension)`` points [-, force]
        (:mod:`moorline.physics.load_strain`); ``None``: the linear law ``EA eps``. With a
        table, ``EA`` is a reference stiffness (the table's largest tangent, for scales and
        the slack regularization).
    EAd, EAd_Lm
        Fibre-rope dynamic stiffness ``EA_d = EAd + EAd_Lm T_mean`` [force, -] used about the
        static state in dynamic analyses (Del Vecchio 1992; MoorPy's ``EAd``/``EAd_Lm``);
        ``None``: the static law in dynamics too. For the ``static_dynamic`` material, the
        dynamic branch's stiffness at zero load and its slope with the static branch's force.
    BA_dynamic
        ``static_dynamic`` material: damping of the dynamic branch [force*time] (MoorDyn's
        ``BA_d``); ``BA`` is then the static branch's (``BA_s``).
    EI
        Bending stiffness [force*length^2] (0: a cable without bending stiffness;
        :mod:`moorline.physics.bending`, pinned line ends).
    owc
        ``syrope`` material: the original working curve, ``(strain, tension)`` rows [-, force].
    working_curve, wc_k1, wc_k2
        ``syrope`` material: the working-curve formula (``linear``, ``quadratic``, ``exp``)
        and its two parameters (MoorDyn's ``WCType``, ``k1``, ``k2``).
    """

    name: str
    diameter: float
    mass_per_length: float
    EA: float
    displaced_area: float | None = None
    Cd: float = 1.2
    Ca: float = 1.0
    Ct: float = 0.008
    Cat: float = 0.0
    material: MaterialKind = "elastic"
    EA1: float = 0.0
    tau: float = 0.0
    slack_stiffness_ratio: float = 1.0e-6
    slack_smoothing: float = 1.0e-5
    BA: float = 0.0
    MBL: float | None = None
    EA_dynamic: float | None = None
    catalog: str | None = None
    nominal_diameter: float | None = None
    EA_table: tuple[tuple[float, float], ...] | None = None
    EAd: float | None = None
    EAd_Lm: float = 0.0
    EI: float = 0.0
    BA_dynamic: float = 0.0
    owc: tuple[tuple[float, float], ...] | None = None
    working_curve: str = "linear"
    wc_k1: float = 0.0
    wc_k2: float = 0.0

    @property
    def area_displaced(self) -> float:
        """Displaced area per unit length [length^2]."""
        if self.displaced_area is not None:
            return self.displaced_area
        return math.pi * self.diameter**2 / 4.0


MotionKind = Literal["harmonic", "table"]


@dataclass(frozen=True)
class Motion:
    """A time history added to a point's position (prescribed points) or force (free points).

    Attributes
    ----------
    kind
        ``harmonic``: ``amplitude * sin(2 pi t / period + phase)``; ``table``: ``values``
        at ``times``, held constant outside; a motion follows the C1 cubic Hermite
        interpolant with central knot derivatives (its velocity and acceleration are that
        curve's, :func:`moorline.solvers.excitation.motion_value`), a force history the
        linear interpolation.
    amplitude, period, phase_deg
        Harmonic amplitude per direction [length or force], period [time], phase [deg].
    times, values
        Time table [time] and the 3-vectors at those times.
    ramp_time
        Smooth start-up: the history is multiplied by ``(1 - cos(pi t / ramp_time)) / 2`` for
        ``t < ramp_time``.
    """

    kind: MotionKind
    amplitude: Vector3 = (0.0, 0.0, 0.0)
    period: float = 0.0
    phase_deg: float = 0.0
    times: tuple[float, ...] = ()
    values: tuple[Vector3, ...] = ()
    ramp_time: float = 0.0


@dataclass(frozen=True)
class Point:
    """A node that lines can end at.

    Attributes
    ----------
    name
        Identifier used by lines.
    kind
        ``fixed`` (never moves), ``free`` (solved for), ``prescribed`` (position imposed; its
        reaction is reported) or ``body`` (rigidly attached to the body ``body``).
    position
        Position [length]; for a free point the initial guess; for a body point its position
        in the body frame (relative to the body origin).
    mass
        Lumped mass [mass] (free points).
    volume
        Displaced volume [length^3]; buoyancy is ``rho g volume`` upward.
    force
        Constant external force [force] (e.g. a buoyant load ``(0, 0, +P)``).
    initial_position
        Prescribed points only: where a load-stepped static solution starts the point from
        (it moves to ``position`` over the load steps, as the support of Tuah Ex2).
    motion
        Prescribed points: displacement history added to ``position`` in dynamics.
    force_history
        Free points: force history added to ``force`` in dynamics.
    Cd, drag_area, Ca
        Free points: drag coefficient and area (``0.5 rho Cd A |u| u``) and added-mass
        coefficient on the displaced volume.
    body
        Body points: the body's name.
    """

    name: str
    kind: PointKind
    position: Vector3
    mass: float = 0.0
    volume: float = 0.0
    force: Vector3 = (0.0, 0.0, 0.0)
    initial_position: Vector3 | None = None
    motion: Motion | None = None
    force_history: Motion | None = None
    Cd: float = 0.0
    drag_area: float = 0.0
    Ca: float = 0.0
    body: str | None = None


@dataclass(frozen=True)
class Line:
    """A cable between two points, discretized into ``segments`` straight 2-node elements.

    Attributes
    ----------
    name
        Identifier.
    line_type
        Name of its :class:`LineType`.
    length
        Unstretched length [length].
    segments
        Number of elements.
    end_a, end_b
        Names of the end points.
    initial_shape
        Optional initial node positions, shape ``(segments + 1, 3)``; otherwise the solver
        chooses (catenary or straight line).
    clamp_a, clamp_b
        A clamped end (its line type needs ``EI > 0``; the end point fixed or prescribed): the
        direction the line's tangent is held along there, pointing from end A towards end B
        (normalized; :mod:`moorline.physics.bending`). ``None``: a pinned end.
    element
        ``straight``: the chord carries the stretched length (the classical element);
        ``sag_corrected``: the chord is shortened by the element's own sag
        (:mod:`moorline.physics.sag`).
    syrope_ic
        Lines of a ``syrope`` line type: ``(Tmax0, Tmean0)`` [force], the highest mean tension
        the rope has seen and its mean tension (MoorDyn's ``SYROPE IC``; statics use the
        working curve of ``Tmax0``, :mod:`moorline.physics.syrope`).
    """

    name: str
    line_type: str
    length: float
    segments: int
    end_a: str
    end_b: str
    initial_shape: tuple[Vector3, ...] | None = None
    clamp_a: Vector3 | None = None
    clamp_b: Vector3 | None = None
    element: Literal["straight", "sag_corrected"] = "straight"
    syrope_ic: tuple[float, float] | None = None
