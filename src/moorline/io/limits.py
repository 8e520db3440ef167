"""Size limits of a case: the number of segments, of random-sea components, and a memory
estimate of each analysis, checked when the case is read so that a typo (``segments: 1e7``,
``record_length: 1e9``) is refused at once instead of exhausting the memory later.

The limits are module constants; the estimates are rough upper bounds of the largest arrays
an analysis holds (documented next to each), not a measurement.
"""

from __future__ import annotations

from ..model import Waves

__all__ = ["MAX_MEMORY", "MAX_SEGMENTS", "MAX_TIME_STEPS", "MAX_WAVE_COMPONENTS", "analysis_memory",
           "wave_components"]

MAX_SEGMENTS = 100_000
"""Most segments of all lines of a case together: 1,000 times the mesh a mooring study needs
(20-200 per line); statics and dynamics of that many take minutes and ~100 MB."""

MAX_WAVE_COMPONENTS = 100_000
"""Most components of a random sea (Tuah 1982, Example 5, uses 200; a 3-hour record to
6 omega_p needs a few thousand)."""

MAX_TIME_STEPS = 1_000_000_000
"""Most time steps ``duration / dt`` of a dynamics or strumming analysis (a 3-hour storm at
dt = 1e-4 s is 1.1e8; 1e9 steps take days)."""

MAX_MEMORY = 4 * 1024**3
"""Largest memory estimate of one analysis [bytes] (4 GiB; a 3-hour run of a 60-node system
recorded at 50 Hz needs ~6 GiB)."""

_FLOAT, _COMPLEX = 8, 16
_RECORD_OVERHEAD = 4096  # bytes per dynamics record beyond its numbers (the OC3 run, 63 nodes:
#                          11.6 kB measured per record, 11.2 kB estimated)


def wave_components(waves: Waves) -> int:
    """Number of components of a ``kind: random`` sea, as
    :meth:`moorline.waves.RandomSea.n_components` counts them (no arrays made), or of a
    ``kind: components`` one."""
    if waves.kind == "components":
        return len(waves.components.omegas) if waves.components is not None else 0
    from ..waves.field import random_sea

    return random_sea(waves).n_components()


def analysis_memory(kind: str, settings: object, n_nodes: int, n_components: int,
                    output_every: float) -> tuple[float, str, str]:
    """Rough memory [bytes] an analysis needs, what drives it (for the message) and the key
    of its settings that sets it (``""``: the sea's size).

    - ``dynamics``: the output records kept in memory, ``duration / max(every, dt)`` of
      positions, velocities (3 per node) and tensions (one per segment), twice (the lists of
      records and the arrays made of them at the end), plus ~4 kB per record for the array
      objects of each and the solver's end-of-run copies.
    - ``strumming``: its time histories, ``duration / dt`` steps of 3 numbers per node.
    - ``stochastic``: transfer functions (``n_components`` complex per degree of freedom) and
      the time series of one record (``n_points``, default ~4-8 ``n_components``, per degree
      of freedom).
    - ``harmonic``: the block-sparse Jacobian, ``(2 harmonics + 1)^2`` blocks of the tangent
      (27 entries per node row) and the sampled tangents, four times (its assembly and LU
      factors; measured 322 MB for 40 harmonics of a 21-node line, estimated 366 MB).
    - ``stochastic`` measured 105 MB for 7,200 components of a 21-node line, estimated
      116 MB.
    - other kinds: nothing beyond the mesh.
    """
    dofs = 3 * n_nodes

    def get(key: str) -> float:
        return getattr(settings, key)

    if kind == "dynamics":
        records = get("duration") / max(output_every, get("dt"))
        per_record = 2 * (2 * dofs + n_nodes) * _FLOAT + _RECORD_OVERHEAD
        return records * per_record, f"{records:.3g} output records", "duration"
    if kind == "strumming":
        steps = get("duration") / get("dt")
        return steps * dofs * _FLOAT, f"{steps:.3g} time steps", "duration"
    if kind == "stochastic":
        n_points = get("n_points") or 8 * n_components
        return (n_components * dofs * 4 * _COMPLEX + n_points * dofs * 3 * _FLOAT,
                f"{n_components} wave components and {n_points:.0f} time points",
                "n_points" if get("n_points") else "")
    if kind == "harmonic":
        terms = 2 * get("harmonics") + 1
        samples = get("samples") or 4 * (get("harmonics") + 1)
        return ((terms**2 + samples) * 27 * dofs * _FLOAT * 4,
                f"{get('harmonics'):.0f} harmonics and {samples:.0f} samples", "harmonics")
    return 0.0, "", ""
