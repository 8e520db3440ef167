"""MoorDyn's Syrope polyester-rope model (load-history dependent working curves), vectorized.

Sources: MoorDyn-C v2.7.1 (commit 319ff99) ``source/Line.cpp`` (``Line::setWorkingCurve``;
``Line::setup``, the slow strain of the original working curve; ``Line::initialize``, the
initial slow stretch; ``Line::getStateDeriv``, branch ``ELASTIC_SYROPE``), ``source/
MoorDyn2.cpp`` (``readLineProps``, ``read_syrope_working_curves``, the ``SYROPE IC``
section), ``docs/inputs.rst`` ("Syrope Model for Polyester Lines"); the model is documented
in Wei, Bingham & Shao (2026), "ESOMOOR D5.1: Extended MoorDyn solver and validation report",
DTU, doi:10.11583/DTU.31408806 (MoorDyn's ``docs/references.rst``; the report itself was not
readable here, so the equations below are those of the MoorDyn-C source, re-derived and
written down here, no code taken). The working curves follow Falkenberg, Ahjem & Yang (2017),
OTC-27761 (the "Syrope" name).

The model (per segment, strain ``e``, strain rate ``de/dt``)
-----------------------------------------------------------
* **Original working curve (OWC)**: a table ``(x_j, y_j)`` of total strain and tension (the
  first loading of a new rope), read as MoorDyn's curve files (three header lines).
* **Dynamic stiffness** ``K(T) = alpha + beta T`` (``EA_Dc|EA_D_Lm``) and the dynamic
  strain it accumulates from zero, ``g(T) = ln(1 + beta T / alpha) / beta``.
* **Slow strain** of a curve point: ``z = x - g(y)`` (``stiffZs``); it must increase along
  the curve.
* **Working curve** ``WC(Tmax)`` (``setWorkingCurve``): ``x_max = OWC^-1(Tmax)``,
  ``x_min = x_0 + k1 (x_max - x_0)`` (``LINEAR`` with ``k1 >= 1``: ``x_min = x_max -
  Tmax / k1``, ``k1`` a stiffness), and with ``xi = (x - x_min) / (x_max - x_min)``
  ``LINEAR``: ``y = Tmax xi``; ``QUADRATIC``: ``y = Tmax xi (k2 xi + 1 - k2)``; ``EXP``:
  ``y = Tmax (1 - exp(k2 xi)) / (1 - exp(k2))``; sampled at 30 equally spaced strains, with
  ``z = x - g(y)``.
* **State** per segment: the slow strain ``z`` (MoorDyn's ``dl_1 / l``) and the running
  maximum mean tension ``Tmax`` (``Tmax``); the **mean tension** ``Tm = S(z)`` is the active
  curve's ``z -> y`` (piecewise linear, clamped at both ends as MoorDyn's ``interp``) and
  ``X(Tm)`` its ``y -> x``.
* **Rate** ``(c1 + c2) dz/dt = K(Tm) (e - X(Tm)) + c2 de/dt`` with ``c1 = BA_s``,
  ``c2 = BA_d``; **tension** ``T = Tm + c1 dz/dt`` (MoorDyn: ``T = Tm`` only while the segment
  is stretched, the damping ``Td = c1 dz/dt`` always).
* **History**: where ``Tm > Tmax``, ``Tmax = Tm`` and the working curve is rebuilt.

Active curve. MoorDyn switches to the OWC when the previous mean tension equals ``Tmax``; a
state past the top of ``WC(Tmax)`` then gives ``Tm = Tmax`` (the interpolation clamps). Here
the switch is a function of the state, with no lag: ``S(z) = WC(z)`` for ``z`` below the
working curve's top ``z_top(Tmax)``, ``max(Tmax, OWC(z))`` above it. (The OWC's ``z`` is
interpolated between its table points, the working curve's top is computed exactly; ``g`` is
concave, so ``OWC_z(Tmax) >= z_top`` and the ``max`` only flattens that sliver, as MoorDyn's
clamp does: ``S`` is continuous and non-decreasing.)

One step (the midpoint rule, as :mod:`moorline.physics.static_dynamic`)
----------------------------------------------------------------------
From ``(e_o, z_o, Tmax_o)`` to ``e_n`` over ``dt`` on the curves of ``Tmax_o``:

    phi(z_n) = (c1 + c2) (z_n - z_o) - dt f(z_m, e_m) - c2 (e_n - e_o) = 0,
    f(z, e) = K(S(z)) (e - X(S(z))),   z_m = (z_o + z_n) / 2,   e_m = (e_o + e_n) / 2,

solved per segment by a bracketed Newton iteration (``phi`` is piecewise smooth and
increasing in practice; bisection where Newton leaves the bracket). Then ``Tm = S(z_n)``,
``Tmax_n = max(Tmax_o, Tm)`` and the elastic tension

    T_e = S(z_n) + c1 / (c1 + c2) f(z_n, e_n)

so that ``T = T_e + eta de/dt`` with ``eta = c1 c2 / (c1 + c2)``, moorline's Kelvin-Voigt
dashpot ``BA`` on the current strain rate (exactly ``Tm + c1 dz/dt``). ``dT_e/de_n`` is exact
(implicit function theorem on ``phi``). Slack: where the tension is not positive
(``T_e <= 0``) or the segment is shorter than unstretched (``e_n < 0``) the element
transmits the line's slack regularization ``slack_ratio EA e_n`` (MoorDyn zeroes ``Tm`` and
keeps ``Td``).

Statics and the initial state
-----------------------------
At rest ``dz/dt = 0`` gives ``e = X(Tm)``: the rope lies on its active curve, ``WC(Tmax0)``
up to ``x_max`` and the OWC beyond (:meth:`SyropeRope.relaxed_table`, the static law; between
its points the static solver uses moorline's monotone cubic table interpolation,
:mod:`moorline.physics.load_strain`). Dynamics start relaxed at the static strain
(:meth:`SyropeRope.relaxed_state`: ``z`` with ``X(S(z)) = e``, ``Tmax = max(Tmax0, Tm)``),
so there is no start-up transient. MoorDyn instead sets ``z`` from the ``SYROPE IC`` row's
``Tmean0`` on ``WC(Tmax0)`` (``Line::initialize``) whatever the geometry; its initial-
condition solver (``StationaryScheme``, ``source/Time.cpp``) then moves the nodes by their
accelerations but advances the slow strain by its own rate, so it keeps creeping (and
``Tmax`` may rise) over the pseudo-time ``TmaxIC`` (``Init_NoIC`` skips that). The two agree
when ``Tmean0`` is the working curve's tension at the deck's geometry (OpenFAST r-test
``md_syrope`` and MoorDyn's ``tests/Mooring/syrope/linear_wc``, to 5e-4 and 2e-4 of the
tension); MoorDyn's own test (``tests/syrope.cpp``) notes the large
start-up error of its quadratic and exponential decks, whose ``Tmean0`` is not.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]

__all__ = ["N_WC", "SyropeElements", "SyropeRope", "reference_stiffness", "rope_of",
           "syrope_update"]

#: points of a sampled working curve (MoorDyn-C's ``Line::nEApointsWC``)
N_WC = 30
#: where the static law's table adds points next to each knot (fraction of the segment)
RELAXED_INSET = 1e-3
FORMS = ("linear", "quadratic", "exp")


@dataclass(frozen=True, eq=False)
class SyropeRope:
    """One Syrope line type's curves (module docstring).

    Parameters
    ----------
    owc
        The original working curve, rows ``(strain, tension)`` [-, force], as MoorDyn reads
        it (strain and tension increasing).
    form, k1, k2
        Working-curve formula (``linear``, ``quadratic``, ``exp``) and its parameters.
    alpha, beta
        Dynamic stiffness ``K = alpha + beta T`` [force, -] (``EA_Dc``, ``EA_D_Lm``).
    """

    owc: FloatArray
    form: str
    k1: float
    k2: float
    alpha: float
    beta: float

    def __post_init__(self) -> None:
        owc = np.asarray(self.owc, dtype=float)
        object.__setattr__(self, "owc", owc)
        object.__setattr__(self, "owc_slow", owc[:, 0] - self.dynamic_strain(owc[:, 1]))

    def dynamic_strain(self, tension: ArrayLike) -> FloatArray:
        """``g(T) = ln(1 + beta T / alpha) / beta`` (``T / alpha`` when ``beta = 0``)."""
        T = np.asarray(tension, dtype=float)
        if self.beta == 0.0:
            return T / self.alpha
        return np.log1p(self.beta * T / self.alpha) / self.beta

    def problems(self) -> list[str]:
        """What makes the curves unusable (empty when none): MoorDyn's checks."""
        out = []
        if not np.all(np.isfinite([self.k1, self.k2, self.alpha, self.beta])) or not np.all(
                np.isfinite(self.owc)):
            return ["k1, k2, EA_Dc, EA_D_Lm and the curve must be finite numbers"]
        x, y = self.owc[:, 0], self.owc[:, 1]
        if len(x) < 2 or np.any(np.diff(x) <= 0) or np.any(np.diff(y) <= 0):
            out.append("the original working curve needs at least 2 points with strain and "
                       "tension increasing")
        elif np.any(np.diff(self.owc_slow) <= 0):
            out.append("the slow strain x - ln(1 + beta T / alpha) / beta of the original "
                       "working curve is not increasing (MoorDyn refuses it): the curve is "
                       "stiffer than the dynamic stiffness somewhere")
        if self.form not in FORMS:
            out.append(f"working curve {self.form!r} is not one of {', '.join(FORMS)}")
        elif self.form == "linear" and self.k1 < 0:
            out.append("a LINEAR working curve needs k1 >= 0")
        elif self.form == "quadratic" and not (0 <= self.k1 < 1 and 0 < self.k2 <= 1):
            out.append("a QUADRATIC working curve needs 0 <= k1 < 1 and 0 < k2 <= 1")
        elif self.form == "exp" and not (0 <= self.k1 < 1 and self.k2 > 0):
            out.append("an EXP working curve needs 0 <= k1 < 1 and k2 > 0")
        if not (self.alpha > 0 and self.beta >= 0):
            out.append("the dynamic stiffness needs EA_Dc > 0 and EA_D_Lm >= 0")
        return out

    def tmax_problem(self, Tmax: float) -> str | None:
        """Why a history starting at ``Tmax`` cannot be modelled (``None`` when it can): its
        working curve, or one of a larger ``Tmax`` it may grow to (checked at 64 values up
        to the OWC's end), has no strain range or a slow strain that does not increase (a
        curve stiffer than the dynamic stiffness; MoorDyn would interpolate it anyway)."""
        y = self.owc[:, 1]
        if not y[0] <= Tmax <= y[-1]:
            return (f"Tmax {Tmax:g} is outside the original working curve's tensions "
                    f"[{y[0]:g}, {y[-1]:g}] (MoorDyn refuses it)")
        levels = np.linspace(Tmax, y[-1], 64)
        x, _, z = self.working_curve(levels)
        bad = ~((x[:, -1] > x[:, 0]) & np.all(np.diff(z, axis=1) > 0, axis=1))
        if np.any(bad):
            at = levels[np.argmax(bad)]
            reached = "" if at == Tmax else f" (reached when the mean tension grows to {at:g})"
            return (f"the working curve of Tmax {at:g}{reached} is stiffer than the dynamic "
                    "stiffness somewhere or has no strain range: its slow strain does not "
                    "increase")
        return None

    def working_curve(self, Tmax: ArrayLike) -> tuple[FloatArray, FloatArray, FloatArray]:
        """Strain, tension and slow strain of ``WC(Tmax)`` at its 30 samples, (n, 30) each."""
        Tmax = np.asarray(Tmax, dtype=float)[:, None]
        x0 = self.owc[0, 0]
        x_max = np.interp(Tmax, self.owc[:, 1], self.owc[:, 0])
        if self.form == "linear" and self.k1 >= 1.0:
            x_min = x_max - Tmax / self.k1
        else:
            x_min = x0 + self.k1 * (x_max - x0)
        xi = np.linspace(0.0, 1.0, N_WC)[None, :]
        x = x_min + (x_max - x_min) * xi
        if self.form == "linear":
            y = Tmax * xi
        elif self.form == "quadratic":
            y = Tmax * xi * (self.k2 * xi + (1.0 - self.k2))
        else:
            y = Tmax * np.expm1(self.k2 * xi) / np.expm1(self.k2)
        y = y + 0.0 * x
        return x, y, x - self.dynamic_strain(y)

    def mean_tension(self, z: FloatArray, Tmax: FloatArray,
                     curve: tuple[FloatArray, FloatArray, FloatArray] | None = None
                     ) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
        """``Tm = S(z)``, ``X(Tm)`` and their derivatives ``dTm/dz``, ``dX/dz`` on the active
        curve of ``Tmax`` (module docstring); ``curve``: ``working_curve(Tmax)`` if known."""
        x, y, zw = self.working_curve(Tmax) if curve is None else curve
        on_wc = z < zw[:, -1]
        T, X, dT, dX = _interp_rows(zw, y, x, z)
        if np.any(~on_wc):
            o = ~on_wc
            ox, oy, oz = (np.broadcast_to(a, (int(o.sum()), len(a)))
                          for a in (self.owc[:, 0], self.owc[:, 1], self.owc_slow))
            To, Xo, dTo, dXo = _interp_rows(oz, oy, ox, z[o])
            flat = To < Tmax[o]
            T[o] = np.where(flat, Tmax[o], To)
            X[o] = np.where(flat, x[o, -1], Xo)
            dT[o] = np.where(flat, 0.0, dTo)
            dX[o] = np.where(flat, 0.0, dXo)
        return T, X, dT, dX

    def relaxed_table(self, Tmax0: float) -> tuple[float, FloatArray]:
        """The static law at rest with the running maximum ``Tmax0``: ``WC(Tmax0)`` then the OWC
        beyond ``x_max``, as ``(x_min, rows (strain - x_min, tension))``. At rest the
        dynamic law is the piecewise-linear interpolation of these points; each segment
        gets two more points at ``RELAXED_INSET`` of its length from its ends, so that
        moorline's monotone cubic through them (:mod:`moorline.physics.load_strain`) is that
        interpolation except within those insets (measured 1.1e-6 of ``Tmax0`` at most on
        MoorDyn's curves, against 6e-3 through the knots alone). Beyond the OWC's last point
        the static law goes on linearly (moorline's tables) where MoorDyn's holds the last
        tension."""
        x, y, _ = self.working_curve(np.array([Tmax0]))
        beyond = self.owc[self.owc[:, 0] > x[0, -1]]
        rows = np.vstack((np.column_stack((x[0], y[0])), beyond))
        a, b = rows[:-1], rows[1:]
        inset = np.stack((a, a + RELAXED_INSET * (b - a), b - RELAXED_INSET * (b - a)), axis=1)
        rows = np.vstack((inset.reshape(-1, 2), rows[-1:]))
        return float(x[0, 0]), np.column_stack((rows[:, 0] - x[0, 0], rows[:, 1]))

    def relaxed_state(self, strain: FloatArray, Tmax0: FloatArray
                      ) -> tuple[FloatArray, FloatArray]:
        """Slow strain ``z`` and running maximum of segments at rest at ``strain``: ``X(S(z)) =
        strain`` on ``WC(Tmax0)``, on the OWC beyond its top (``Tmax`` raised to the tension
        there); below the working curve's foot ``z = strain`` (no tension)."""
        strain = np.asarray(strain, dtype=float)
        Tmax = np.asarray(Tmax0, dtype=float).copy()
        x, y, zw = self.working_curve(Tmax)
        z = np.empty_like(strain)
        for k in range(len(strain)):
            if strain[k] <= x[k, 0]:
                z[k] = strain[k]
            elif strain[k] <= x[k, -1]:
                z[k] = np.interp(strain[k], x[k], zw[k])
            else:
                z[k] = np.interp(strain[k], self.owc[:, 0], self.owc_slow)
                Tmax[k] = max(Tmax[k], float(np.interp(strain[k], self.owc[:, 0],
                                                       self.owc[:, 1])))
        return z, Tmax


def _interp_rows(zp: FloatArray, yp: FloatArray, xp: FloatArray, z: FloatArray
                 ) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """Row-wise piecewise-linear ``y(z)``, ``x(z)`` and slopes, clamped outside the knots
    (MoorDyn's ``interp``: the end values, slope 0)."""
    n, m = zp.shape
    j = np.clip((zp <= z[:, None]).sum(axis=1), 1, m - 1)
    rows = np.arange(n)
    z0, z1 = zp[rows, j - 1], zp[rows, j]
    f = (z - z0) / (z1 - z0)
    inside = (z > zp[:, 0]) & (z < zp[:, -1])
    f = np.clip(f, 0.0, 1.0)
    dy, dx = yp[rows, j] - yp[rows, j - 1], xp[rows, j] - xp[rows, j - 1]
    slope = np.where(inside, 1.0 / (z1 - z0), 0.0)
    return yp[rows, j - 1] + f * dy, xp[rows, j - 1] + f * dx, dy * slope, dx * slope


def _rate(rope: SyropeRope, z, e, Tmax, curve):
    """``f(z, e) = K(Tm) (e - X(Tm))``, ``df/dz``, ``df/de`` and ``Tm``, ``dTm/dz``."""
    T, X, dT, dX = rope.mean_tension(z, Tmax, curve)
    K = rope.alpha + rope.beta * T
    f = K * (e - X)
    return f, rope.beta * dT * (e - X) - K * dX, K, T, dT


def syrope_update(
    strain_new: ArrayLike,
    strain_old: ArrayLike,
    z_old: ArrayLike,
    Tmax_old: ArrayLike,
    dt: float,
    rope: SyropeRope,
    c1: ArrayLike,
    c2: ArrayLike,
    slack_stiffness: ArrayLike,
    *,
    tol: float = 1e-13,
    max_iter: int = 100,
) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """Elastic part of the force after one step, the new state and the exact tangent.

    Parameters
    ----------
    strain_new, strain_old
        Segment strain ``l / L0 - 1`` at the end and the start of the step.
    z_old, Tmax_old
        The state at the start of the step: slow strain [-] and running maximum mean
        tension [force].
    dt
        Time step [time] (>= 0).
    rope
        The line type's curves.
    c1, c2
        Static- and dynamic-branch damping [force*time] (``c1 + c2 > 0``).
    slack_stiffness
        ``slack_ratio EA`` [force], the slack regularization's stiffness.

    Returns
    -------
    tension, z_new, Tmax_new, dtension_dstrain
        ``T_e`` (without the ``eta de/dt`` dashpot), the new state and ``dT_e/d strain_new``.
    """
    e_n = np.asarray(strain_new, dtype=float)
    e_o = np.asarray(strain_old, dtype=float)
    z_o = np.asarray(z_old, dtype=float)
    Tmax = np.asarray(Tmax_old, dtype=float)
    c1, c2 = np.broadcast_to(c1, e_n.shape), np.broadcast_to(c2, e_n.shape)
    c = c1 + c2
    e_m = 0.5 * (e_o + e_n)
    de = e_n - e_o
    curve = rope.working_curve(Tmax)

    def residual(z):
        f, f_z, _, _, _ = _rate(rope, 0.5 * (z_o + z), e_m, Tmax, curve)
        return c * (z - z_o) - dt * f - c2 * de, c - 0.5 * dt * f_z

    z = z_o + c2 * de / c
    lo = np.full_like(z, -np.inf)
    hi = np.full_like(z, np.inf)
    for _ in range(max_iter):
        phi, dphi = residual(z)
        lo = np.where(phi < 0, np.maximum(lo, z), lo)
        hi = np.where(phi > 0, np.minimum(hi, z), hi)
        step = phi / dphi
        trial = z - step
        done = (phi == 0) | (np.abs(step) <= tol * np.maximum(np.abs(z), 1e-3))
        bisect = ~(done | ((trial > lo) & (trial < hi))) & np.isfinite(lo) & np.isfinite(hi)
        mid = 0.5 * (np.where(bisect, lo, 0.0) + np.where(bisect, hi, 0.0))
        z = np.where(bisect, mid, np.where(phi == 0, z, trial))
        if np.all(done):
            break
    else:
        raise FloatingPointError("Syrope rope update did not converge")
    _, dphi = residual(z)
    _, _, K_m, _, _ = _rate(rope, 0.5 * (z_o + z), e_m, Tmax, curve)
    dz_de = (0.5 * dt * K_m + c2) / dphi
    f, f_z, K, T_mean, dT = _rate(rope, z, e_n, Tmax, curve)
    share = c1 / c
    tension = T_mean + share * f
    tangent = share * K + (dT + share * f_z) * dz_de
    slack = (tension <= 0.0) | (e_n < 0.0)
    if np.any(slack):
        k_slack = np.broadcast_to(np.asarray(slack_stiffness, dtype=float), e_n.shape)
        tension = np.where(slack, k_slack * e_n, tension)
        tangent = np.where(slack, k_slack, tangent)
    return tension, z, np.maximum(Tmax, T_mean), tangent


@dataclass(frozen=True, eq=False)
class SyropeElements:
    """The Syrope elements of a mesh (:attr:`moorline.mesh.Mesh.syrope`).

    Attributes
    ----------
    index
        Their element indices (n,).
    ropes, group
        The distinct line types' curves and, per element, the index of its own (n,).
    c1, c2
        Static- and dynamic-branch damping [force*time] (n,).
    Tmax0
        The running maximum mean tension before the start [force] (n,) (``SYROPE IC``).
    """

    index: IntArray
    ropes: tuple[SyropeRope, ...]
    group: IntArray
    c1: FloatArray
    c2: FloatArray
    Tmax0: FloatArray


def reference_stiffness(owc: ArrayLike) -> float:
    """A Syrope line type's ``EA`` [force]: the original working curve's largest secant
    slope (the slack regularization's scale, as a tabulated law's ``EA``)."""
    owc = np.asarray(owc, dtype=float)
    return float(np.max(np.diff(owc[:, 1]) / np.diff(owc[:, 0])))


def rope_of(line_type) -> SyropeRope:
    """The curves of a ``syrope`` :class:`~moorline.model.LineType`."""
    return SyropeRope(np.asarray(line_type.owc, dtype=float), line_type.working_curve,
                      line_type.wc_k1, line_type.wc_k2, float(line_type.EAd),
                      float(line_type.EAd_Lm))
