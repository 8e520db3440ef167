"""Along-line views of a result: arc-length coordinates, nodes in order along each line, and
the tension envelope of a dynamics run (OrcaFlex-style range graphs).

Arc length ``s`` is the *unstretched* length from end A of a line: ``s = 0`` at end A,
``s = L`` (the line's length) at end B, element values at the element midpoints. Node
numbering (:mod:`moorline.mesh`) puts the named points first and the interior nodes of each
line after, so a line's nodes are not contiguous: ``line_nodes(line, line_node)`` lists them
from end A to end B (-1 past the last node of a shorter line), and :func:`line_profile` returns
one line's positions, tensions and envelope in order along it.

A point node may end several lines (a junction, a buoy, a body's fairlead shared by two lines)
or none (a free point without lines): its ``node_line`` is then ``""`` and its
``node_arc_length`` NaN, and its arc length per line is in ``line_arc_length(line,
line_node)``. A point ending exactly one line carries that line and ``0`` (end A) or ``L``
(end B).

The envelope (:class:`TensionEnvelope`) is the minimum, maximum, mean and standard deviation
(population, ``ddof = 0``) of each element's tension over the output records at
``t >= envelope_start`` (:func:`envelope_start`: the setting, default the end of the
dynamics' ramp), and the static tension: the tensions of the statics the run starts from (the
``initial`` static result given to :func:`moorline.solvers.dynamics.simulate`: the run's
statics in ``moorline run``), else those of the first record (the initial state; it differs
from the statics where a prescribed motion does not start at zero displacement). It is
accumulated record by record (running min, max, and sums of ``T - T_static`` and of its
square: the shifted-data form, which keeps the variance free of the cancellation of
``E[T^2] - E[T]^2`` at a large mean tension), so the streamed file
(:class:`moorline.io.stream.HistoryWriter`, which updates it after every block) and the
in-memory dataset (:meth:`moorline.results.DynamicResult.to_plain`) hold the same numbers
bit for bit, without reading the history back or holding it twice.
"""

from __future__ import annotations

import sys
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

if TYPE_CHECKING:
    import xarray as xr

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]

#: ``line_nodes`` entries past the last node of a line.
NO_NODE = -1

#: The envelope variables of a dynamics group, ``(name, CF cell_methods)``.
ENVELOPE_VARIABLES: tuple[tuple[str, str], ...] = (
    ("tension_min", "time: minimum"), ("tension_max", "time: maximum"),
    ("tension_mean", "time: mean"), ("tension_std", "time: standard_deviation"),
    ("tension_static", ""))

__all__ = ["ENVELOPE_VARIABLES", "NO_NODE", "TensionEnvelope", "envelope_start",
           "line_coords", "line_profile"]


# ----------------------------------------------------------------------------- arc length


def line_coords(mesh: Any) -> tuple[dict[str, Any], dict[str, Any]]:
    """The along-line variables and coordinates of a statics or dynamics group.

    Returns
    -------
    data, coords
        ``data``: ``line_nodes(line, line_node)`` (node indices from end A to end B,
        :data:`NO_NODE` past a line's end) and ``line_arc_length(line, line_node)`` (their
        unstretched arc length, NaN past the end); ``coords``: ``node_line(node)``,
        ``node_arc_length(node)`` (see the module docstring for shared end points) and
        ``element_arc_length(element)`` (at the element midpoints).
    """
    n_lines = len(mesh.line_names)
    width = max((len(nodes) for nodes in mesh.line_nodes), default=0)
    table = np.full((n_lines, width), NO_NODE, dtype=np.int64)
    along = np.full((n_lines, width), np.nan)
    node_line = [""] * mesh.n_nodes
    node_s = np.full(mesh.n_nodes, np.nan)
    ends = np.zeros(mesh.n_nodes, dtype=np.int64)  # line ends at each node
    element_s = np.full(mesh.n_elements, np.nan)
    for k, (nodes, elements) in enumerate(zip(mesh.line_nodes, mesh.line_elements,
                                              strict=True)):
        s = np.concatenate(([0.0], np.cumsum(mesh.length0[elements])))
        table[k, :len(nodes)] = nodes
        along[k, :len(nodes)] = s
        element_s[elements] = 0.5 * (s[:-1] + s[1:])
        for node, value in zip(nodes, s, strict=True):
            node_line[node], node_s[node] = mesh.line_names[k], value
        ends[nodes[0]] += 1
        ends[nodes[-1]] += 1
    shared = np.flatnonzero(ends > 1)
    for node in shared:
        node_line[node] = ""
    node_s[shared] = np.nan
    data = {"line_nodes": (("line", "line_node"), table),
            "line_arc_length": (("line", "line_node"), along)}
    coords = {"node_line": (("node",), node_line), "node_arc_length": (("node",), node_s),
              "element_arc_length": (("element",), element_s)}
    return data, coords


def line_profile(ds: Any, line: str) -> xr.Dataset:
    """One line of a statics or dynamics dataset in order from end A to end B.

    Parameters
    ----------
    ds
        A statics or dynamics group (``to_xarray()``, ``to_plain()`` or read back from
        ``results.nc``) with ``line_nodes`` and ``line_arc_length``.
    line
        The line id.

    Returns
    -------
    xarray.Dataset
        ``position(..., line_node, xyz)`` with coordinate ``arc_length(line_node)`` (nodes,
        ends included); every element variable of ``ds`` (``tension`` and, in a dynamics
        group, the envelope ``tension_min`` ... ``tension_static``) on dimension
        ``element`` restricted to the line, in order, with ``element_arc_length``.
    """
    if not hasattr(ds, "isel"):  # a PlainDataset
        ds = ds.to_xarray()
    k = [str(n) for n in ds["line"].values].index(line)
    table = np.asarray(ds["line_nodes"].values[k])
    nodes = table[table != NO_NODE]
    elements = np.flatnonzero(np.asarray(ds["element_line"].values).astype(str) == line)
    elements = elements[np.argsort(np.asarray(ds["element_arc_length"].values)[elements],
                                   kind="stable")]
    out = ds[[v for v in ds.data_vars if ds[v].dims and "element" in ds[v].dims
              and v != "element_nodes"]].isel(element=elements)
    position = ds["position"].isel(node=nodes).rename(node="line_node")
    out["position"] = position.drop_vars([c for c in position.coords
                                          if "line_node" in position[c].dims])
    out = out.assign_coords(arc_length=("line_node", ds["line_arc_length"].values[k][:len(
        nodes)]))
    out["arc_length"].attrs.update(ds["node_arc_length"].attrs)
    out.attrs.update(ds.attrs, line=line)
    return out


# ----------------------------------------------------------------------------- envelope


def envelope_start(settings: Mapping[str, Any] | Any) -> float:
    """The time the envelope starts at [time]: ``envelope_start`` of the dynamics settings
    (a :class:`~moorline.model.DynamicsSettings`, its fields as a dict, or a group's
    attributes ``setting_<name>``), default its ``ramp_time`` (0 without ramp)."""
    if not isinstance(settings, Mapping):
        settings = vars(settings)
    fields = {k.removeprefix("setting_"): v for k, v in settings.items()}
    for key in ("envelope_start", "ramp_time"):
        value = fields.get(key)
        if value is not None and not (isinstance(value, str) and value == "none"):
            return float(value)
    return 0.0


class TensionEnvelope:
    """Running envelope of element tensions over output records (see the module docstring).

    Parameters
    ----------
    n_elements
        Number of elements.
    start
        Records at ``t >= start`` enter the statistics.
    static
        The static tensions (n_elements,): those of the statics the run starts from; ``None``
        or empty: the first record's, whatever its time.
    """

    def __init__(self, n_elements: int, start: float = 0.0,
                 static: FloatArray | None = None) -> None:
        self.start = float(start)
        self.count = 0
        given = static is not None and np.size(static) > 0
        self.static = (np.array(static, dtype=float) if given
                       else np.full(n_elements, np.nan))
        self._seen = given
        self._min = np.full(n_elements, np.inf)
        self._max = np.full(n_elements, -np.inf)
        self._sum = np.zeros(n_elements)
        self._square = np.zeros(n_elements)

    def add(self, t: float, tension: FloatArray) -> None:
        """Add one record (element tensions at time ``t``)."""
        tension = np.asarray(tension, dtype=float)
        if not self._seen:
            self.static, self._seen = tension.copy(), True
        if t < self.start:
            return
        self._accumulate(tension[None])

    def add_records(self, times: FloatArray, tensions: FloatArray) -> None:
        """Add records in order: ``tensions`` (n_t, n_elements) at ``times`` (n_t,)
        (increasing). The same numbers, bit for bit, as :meth:`add` record by record: the
        records are added in order, whatever the blocks."""
        times = np.asarray(times, dtype=float)
        tensions = np.asarray(tensions, dtype=float).reshape(len(times), -1)
        if not len(times):
            return
        if not self._seen:
            self.static, self._seen = tensions[0].copy(), True
        kept = tensions if times[0] >= self.start else tensions[times >= self.start]
        if len(kept):
            self._accumulate(kept)

    def _accumulate(self, rows: FloatArray, compiled: bool | None = None) -> None:
        """Add ``rows`` (n, n_elements) in order: in one compiled pass
        (:func:`moorline.fast_envelope.accumulate`) when numba is loaded already (a run on
        the compiled path), else with numpy in passes that stay in the cache (a run on the
        general path does not import numba for it); the same numbers to the last bit
        (tested). ``compiled``: force one or the other."""
        if compiled is None:
            compiled = "moorline.jit" in sys.modules
        if compiled:
            from .fast_envelope import accumulate

            accumulate(np.ascontiguousarray(rows, dtype=float), self.static, self._min,
                       self._max, self._sum, self._square)
        else:
            per_pass = max(1, _PASS_BYTES // (8 * max(1, rows.shape[1])))
            for first in range(0, len(rows), per_pass):
                block = rows[first:first + per_pass]
                np.minimum(self._min, block.min(axis=0), out=self._min)
                np.maximum(self._max, block.max(axis=0), out=self._max)
                shifted = block - self.static
                square = shifted * shifted
                self._sum = _in_order(self._sum, shifted)
                self._square = _in_order(self._square, square)
        self.count += len(rows)

    def values(self) -> dict[str, FloatArray]:
        """``tension_min``, ``tension_max``, ``tension_mean``, ``tension_std``,
        ``tension_static`` (NaN while no record counts)."""
        n = self.static.shape[0]
        if not self.count:
            nan = np.full(n, np.nan)
            return {"tension_min": nan, "tension_max": nan.copy(), "tension_mean": nan.copy(),
                    "tension_std": nan.copy(), "tension_static": self.static.copy()}
        mean_shift = self._sum / self.count
        variance = np.maximum(self._square / self.count - mean_shift * mean_shift, 0.0)
        return {"tension_min": self._min.copy(), "tension_max": self._max.copy(),
                "tension_mean": self.static + mean_shift, "tension_std": np.sqrt(variance),
                "tension_static": self.static.copy()}


_PASS_BYTES = 1 << 18
"""Size of the records [bytes] :meth:`TensionEnvelope.add_records` takes per pass (a long
block in passes: the same sums, twice as fast as one pass over 6000 records of 60
elements)."""


def _in_order(total: FloatArray, rows: FloatArray) -> FloatArray:
    """``total + rows[0] + rows[1] + ...`` added in that order, element by element (the
    rounding of a record-by-record sum, whatever the blocks): numpy reduces a C-ordered
    (n, m) array over axis 0 row after row when m > 1 (checked bit for bit in
    ``tests/test_envelope.py``); a single column would be summed pairwise, so it is
    accumulated instead. ``rows`` (a temporary of the caller) is overwritten: ``total`` is
    added to its first row in place (no stacked copy)."""
    rows[0] += total
    if rows.shape[1] > 1:
        return np.add.reduce(rows, axis=0)
    return np.add.accumulate(rows, axis=0)[-1]
