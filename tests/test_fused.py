"""The compiled element-load kernel (moorline.physics.fused) against the numpy path.

``DynamicModel(kernel="numba")`` must reproduce ``DynamicModel(kernel="numpy")`` (the
reference) in every output of ``evaluate``: both evaluate the same formulas in the same order of
operations, so they agree to round-off; the tolerance is 1e-12 of each array's largest entry.
Configurations cover taut, slack and smoothing-band elements, still water, a steady current
and a ramped current (nonzero fluid acceleration), with and without added mass and internal
damping ``BA``.
"""

from __future__ import annotations

import itertools
from dataclasses import fields

import numpy as np
import pytest

from moorline.mesh import Mesh, discretize
from moorline.model import Environment, Line, LineType, Point, System
from moorline.physics import element, fused, hydro
from moorline.solvers.dynamic_model import DynamicModel, Evaluation, MaterialState
from moorline.waves import CurrentProfile

RTOL = 1e-12
SMOOTHING = 1e-5


def _system(Ca: float = 1.0, Cat: float = 0.3, BA: float = 2.0e4, smoothing: float = SMOOTHING,
            material: str = "elastic", n: int = 12, Cd: float = 1.2, Ct: float = 0.4) -> System:
    """Two fairleads held by lines through free buoyed junctions to seabed anchors (as in
    test_stiffness), with all hydrodynamic coefficients and the damping nonzero."""
    extra = {"EA1": 1.0e6, "tau": 5.0} if material == "viscoelastic" else {}
    lt = LineType("rope", diameter=0.05, mass_per_length=8.0, EA=2.0e6, Cd=Cd, Ct=Ct, Ca=Ca,
                  Cat=Cat, BA=BA, slack_smoothing=smoothing, material=material, **extra)
    pts = {
        "A1": Point("A1", "fixed", (-300.0, -20.0, -100.0)),
        "A2": Point("A2", "fixed", (300.0, 30.0, -100.0)),
        "J1": Point("J1", "free", (-150.0, -10.0, -60.0), volume=0.05),
        "J2": Point("J2", "free", (150.0, 15.0, -60.0), force=(0.0, 0.0, 300.0)),
        "F1": Point("F1", "prescribed", (-10.0, 0.0, -5.0)),
        "F2": Point("F2", "prescribed", (10.0, 5.0, -5.0)),
    }
    lines = {
        "a1": Line("a1", "rope", 180.0, n, "A1", "J1"),
        "b1": Line("b1", "rope", 160.0, n, "J1", "F1"),
        "a2": Line("a2", "rope", 180.0, n, "A2", "J2"),
        "b2": Line("b2", "rope", 160.0, n, "J2", "F2"),
    }
    env = Environment(depth=100.0)
    return System("fused", environment=env, line_types={"rope": lt}, points=pts, lines=lines)


def _strains(mode: str, n_el: int, s: float, rng: np.random.Generator) -> np.ndarray:
    taut = rng.uniform(max(s, 1e-6) * 1.01, 1e-2, n_el)
    band = rng.uniform(-0.99, 0.99, n_el) * s
    slack = rng.uniform(-0.4, -2.0 * s - 1e-4, n_el)
    if mode == "taut":
        return taut
    if mode == "slack":
        return slack
    if mode == "band":  # without a band: tiny strains of either sign
        return band if s > 0 else rng.choice((-1.0, 1.0), n_el) * rng.uniform(3e-7, 1e-6, n_el)
    pick = rng.integers(0, 3, n_el)
    return np.choose(pick, (taut, band, slack))


def _configuration(mesh: Mesh, mode: str, seed: int, quantize: bool = True
                   ) -> tuple[np.ndarray, ...]:
    """Positions whose elements have prescribed strains (walking each line from end A along
    random directions), and random velocities and accelerations.

    With ``quantize`` the chord components are multiples of 2^-20 (below 16 in magnitude):
    their squares and sums are exact, so every implementation gets the same chord length to
    the last bit. That length is the ill-conditioned input: the strain ``l / L0 - 1`` loses
    ``log10(1 / |strain|)`` digits and the slope of the slack band is ``EA / (2 s)``, so one
    ulp of length (numpy's einsum may use fused multiply-adds, a loop may not) moves the
    band tangent by ~1e-11 of ``EA / L0`` (see test_unquantized_inputs).
    """
    rng = np.random.default_rng(seed)
    s = float(mesh.slack_smoothing[0])
    strain = _strains(mode, mesh.n_elements, s, rng)
    x = mesh.node_position.copy()
    placed = np.zeros(mesh.n_nodes, dtype=bool)
    placed[[mesh.point_index(p) for p in ("A1", "A2")]] = True
    for nodes, elems in zip(mesh.line_nodes, mesh.line_elements, strict=True):
        assert placed[nodes[0]]
        for node, e in zip(nodes[1:], elems, strict=True):
            direction = rng.normal(size=3) + np.array([1.0, 0.0, 0.3])
            direction /= np.linalg.norm(direction)
            prev = mesh.elements[e, 0]
            chord = mesh.length0[e] * (1.0 + strain[e]) * direction
            if quantize:
                chord = np.round(chord * 2.0**20) / 2.0**20
            x[node] = x[prev] + chord
            placed[node] = True
    length, _ = element.element_geometry(x, mesh.elements)
    np.testing.assert_allclose(length / mesh.length0 - 1.0, strain, atol=1e-7)
    v = rng.normal(0.0, 0.5, x.shape)
    a = rng.normal(0.0, 0.5, x.shape)
    return x, v, a


def _assert_same(ref: Evaluation, new: Evaluation, floor: dict[str, float] | None = None
                 ) -> None:
    """Every array of ``new`` within RTOL of the largest entry of ``ref``'s (or of
    ``floor[name]`` if larger)."""
    floor = floor or {}
    for f in fields(Evaluation):
        A, B = getattr(ref, f.name), getattr(new, f.name)
        if f.name == "material":
            np.testing.assert_array_equal(A.maxwell, B.maxwell)
            A, B = A.strain, B.strain
        if A is None or B is None:
            assert A is None and B is None, f.name
            continue
        assert A.shape == B.shape, f.name
        scale = max(float(np.abs(A).max(initial=0.0)), floor.get(f.name, 0.0),
                    np.finfo(float).tiny)
        err = float(np.abs(A - B).max(initial=0.0))
        assert err <= RTOL * scale, f"{f.name}: {err:.3e} > {RTOL:g} * {scale:.3e}"


FLUIDS = {
    "still": CurrentProfile.uniform(0.0),
    "current": CurrentProfile.uniform(0.5, 30.0),
    "ramped": CurrentProfile.uniform(0.5, 30.0, ramp_time=10.0),  # a_f != 0 at t = 2
}
CASES = list(itertools.product(("taut", "slack", "band", "mixed"), FLUIDS,
                               ((1.0, 0.3), (0.0, 0.0)), (2.0e4, 0.0)))


@pytest.mark.parametrize(("mode", "fluid", "added", "BA"), CASES)
def test_numba_evaluate_equals_numpy(mode, fluid, added, BA):
    mesh = discretize(_system(Ca=added[0], Cat=added[1], BA=BA))
    ref = DynamicModel(mesh, FLUIDS[fluid], kernel="numpy")
    new = DynamicModel(mesh, FLUIDS[fluid], kernel="numba")
    assert ref.kernel == "numpy" and new.kernel == "numba"
    assert new.has_added_mass == (added != (0.0, 0.0))
    seed = CASES.index((mode, fluid, added, BA))
    x, v, a = _configuration(mesh, mode, seed)
    material = ref.initial_material(x)
    forces = np.random.default_rng(seed).normal(size=x.shape)
    for tangent in (True, False):
        for point_forces in (None, forces):
            args = (x, v, a, 2.0, material, 0.1, tangent, point_forces)
            _assert_same(ref.evaluate(*args), new.evaluate(*args))


@pytest.mark.parametrize("smoothing", [0.0, 1e-3])
@pytest.mark.parametrize("mode", ["mixed", "band"])
def test_other_slack_bands(smoothing, mode):
    """No smoothing (sharp slack law) and a wide band."""
    mesh = discretize(_system(smoothing=smoothing))
    fluid = FLUIDS["ramped"]
    ref = DynamicModel(mesh, fluid, kernel="numpy")
    new = DynamicModel(mesh, fluid, kernel="numba")
    x, v, a = _configuration(mesh, mode, 7)
    material = ref.initial_material(x)
    for tangent in (True, False):
        args = (x, v, a, 3.0, material, 0.1, tangent)
        _assert_same(ref.evaluate(*args), new.evaluate(*args))


def test_unquantized_inputs():
    """General positions: the chord length may differ in its last bit between numpy and the
    kernel, and the ill-conditioned quantities inherit that. The strain (``l / L0 - 1``) has
    an absolute error ~eps, the tension ~``EA eps``, the band tangent ~``EA eps / (s L0)``:
    the comparison scales are at least these (times 1e12, the error allowed is still round-off
    of the conditioning)."""
    mesh = discretize(_system())
    EA, s = float(mesh.EA.max()), float(mesh.slack_smoothing.min())
    K_band = EA / (s * float(mesh.length0.min())) * 1e-3  # a few ulps of strain / RTOL
    # the dashpot share blends in over the band too: C inherits the same conditioning
    C_band = float(mesh.BA.max()) / (s * float(mesh.length0.min())) * 1e-3
    floor = {"material": 1.0, "tension": EA, "element_forces": EA, "nodal": EA, "K": K_band,
             "C": C_band}
    fluid = FLUIDS["ramped"]
    ref = DynamicModel(mesh, fluid, kernel="numpy")
    new = DynamicModel(mesh, fluid, kernel="numba")
    for seed, mode in enumerate(("band", "mixed", "taut", "slack")):
        x, v, a = _configuration(mesh, mode, 100 + seed, quantize=False)
        material = ref.initial_material(x)
        for tangent in (True, False):
            args = (x, v, a, 3.0, material, 0.1, tangent)
            _assert_same(ref.evaluate(*args), new.evaluate(*args), floor)


def test_no_drag_and_dry():
    """Drag switched off (Cd = Ct = 0), then no fluid at all (rho = 0)."""
    mesh = discretize(_system(Cd=0.0, Ct=0.0))
    for m in (mesh, _replace_density(mesh, 0.0)):
        ref = DynamicModel(m, FLUIDS["ramped"], kernel="numpy")
        new = DynamicModel(m, FLUIDS["ramped"], kernel="numba")
        assert not new.has_drag
        x, v, a = _configuration(m, "mixed", 3)
        material = ref.initial_material(x)
        for tangent in (True, False):
            args = (x, v, a, 3.0, material, 0.1, tangent)
            _assert_same(ref.evaluate(*args), new.evaluate(*args))


def _replace_density(mesh: Mesh, rho: float) -> Mesh:
    from dataclasses import replace

    return replace(mesh, water_density=rho)


def _half_viscoelastic() -> System:
    """:func:`_system` with its lines from the anchors viscoelastic (standard linear solid),
    the others elastic."""
    from dataclasses import replace

    system = _system()
    ve = replace(system.line_types["rope"], name="sls", material="viscoelastic", EA1=1.0e6,
                 tau=5.0)
    lines = {k: replace(line, line_type="sls") if k.startswith("a") else line
             for k, line in system.lines.items()}
    return replace(system, line_types={**system.line_types, "sls": ve}, lines=lines)


@pytest.mark.parametrize("dt", [0.0, 0.1, 50.0])
@pytest.mark.parametrize("mode", ["taut", "slack", "band", "mixed"])
def test_viscoelastic_evaluate_numba_equals_numpy(mode, dt):
    """Standard-linear-solid elements (exponential update, with its slack rule) beside elastic
    ones: the compiled kernel gives the numpy path's loads, tangents and new Maxwell-branch
    forces, from a start-of-step state with strains off the current ones and Maxwell forces
    of either sign; steps of none, a fiftieth and ten relaxation times."""
    mesh = discretize(_half_viscoelastic())
    ve = mesh.viscoelastic
    assert 0 < ve.sum() < mesh.n_elements
    ref = DynamicModel(mesh, FLUIDS["ramped"], kernel="numpy")
    new = DynamicModel(mesh, FLUIDS["ramped"], kernel="numba")
    assert new.kernel == "numba"
    seed = 100 + ["taut", "slack", "band", "mixed"].index(mode)
    x, v, a = _configuration(mesh, mode, seed)
    rng = np.random.default_rng(seed)
    now = ref.initial_material(x)
    previous = MaterialState(now.strain + rng.normal(0.0, 2e-3, now.strain.shape),
                             rng.normal(0.0, 3e3, now.strain.shape))
    for tangent in (True, False):
        args = (x, v, a, 2.0, previous, dt, tangent)
        _assert_same(ref.evaluate(*args), new.evaluate(*args))
    if mode == "mixed":  # both branches of the slack rule
        trial = mesh.EA * now.strain + previous.maxwell  # dt = 0: Q_new - Q_old = EA1 deps
        trial = trial + mesh.EA1 * (now.strain - np.maximum(previous.strain,
                                                            -previous.maxwell / mesh.EA))
        assert np.any(trial[ve] < 0) and np.any(trial[ve] > 0)


def test_compiled_kernel_refusals():
    """The incremental update of the standard linear solid stays on numpy; given Maxwell
    forces (harmonic balance) are evaluated by numpy; unknown kernels are refused."""
    mesh = discretize(_half_viscoelastic())
    model = DynamicModel(mesh, FLUIDS["current"], "incremental", kernel="numba")
    assert model.kernel == "numpy" and "incremental" in model.compiled_refusal
    ref = DynamicModel(mesh, FLUIDS["current"], kernel="numpy")
    new = DynamicModel(mesh, FLUIDS["current"], kernel="numba")
    x, v, a = _configuration(mesh, "taut", 7)
    material = ref.initial_material(x)
    given = np.random.default_rng(7).normal(0.0, 1e3, mesh.n_elements)
    args = (x, v, a, 1.0, material, 0.1, True, None, given)
    _assert_same(ref.evaluate(*args), new.evaluate(*args))
    with pytest.raises(ValueError, match="kernel"):
        DynamicModel(mesh, FLUIDS["current"], kernel="fortran")


def test_outputs_are_fresh_arrays():
    """An evaluation kept (e.g. as the accepted step's) is not overwritten by the next."""
    mesh = discretize(_system())
    model = DynamicModel(mesh, FLUIDS["current"], kernel="numba")
    x, v, a = _configuration(mesh, "mixed", 1)
    material = model.initial_material(x)
    first = model.evaluate(x, v, a, 1.0, material, 0.1, True)
    kept = {f.name: np.copy(getattr(first, f.name)) for f in fields(Evaluation)
            if isinstance(getattr(first, f.name), np.ndarray)}
    x2, v2, a2 = _configuration(mesh, "taut", 2)
    model.evaluate(x2, v2, a2, 1.0, material, 0.1, True)
    model.evaluate(x2, v2, a2, 1.0, material, 0.1, False)
    for name, value in kept.items():
        np.testing.assert_array_equal(getattr(first, name), value, err_msg=name)


def test_element_subset_and_functional_form():
    """The functional form on a subset of the elements (how a caller with viscoelastic
    elements would use it) equals the full evaluation restricted to that subset; the
    compiled midpoints equal the numpy ones."""
    mesh = discretize(_system())
    x, v, a = _configuration(mesh, "mixed", 5)
    rng = np.random.default_rng(5)
    uf = rng.normal(size=(mesh.n_elements, 3))
    af = rng.normal(size=(mesh.n_elements, 3))
    props = (mesh.length0, mesh.EA, mesh.slack_ratio, mesh.slack_smoothing, mesh.BA,
             mesh.diameter, mesh.Cd, mesh.Ct, mesh.Ca, mesh.Cat, mesh.water_density)
    full = fused.element_loads(x, v, a, uf, af, mesh.elements, *props, tangent=True,
                               with_added_mass=True)
    keep = rng.random(mesh.n_elements) < 0.5
    sub = fused.element_loads(x, v, a, uf[keep], af[keep], mesh.elements[keep],
                              *(np.broadcast_to(p, keep.shape)[keep] for p in props),
                              tangent=True, with_added_mass=True)
    for name in ("element_forces", "total_forces", "added_mass_force", "tension", "strain",
                 "taut", "K", "C", "Ma"):
        np.testing.assert_array_equal(getattr(sub, name), getattr(full, name)[keep], name)
    np.testing.assert_array_equal(full.nodal, hydro.sum_to_nodes(full.total_forces,
                                                                 mesh.elements, mesh.n_nodes))
    np.testing.assert_array_equal(fused.midpoints(x, mesh.elements),
                                  0.5 * (x[mesh.elements[:, 0]] + x[mesh.elements[:, 1]]))
    # drag alone against hydro.drag_forces (the model stores C = -dF/dv)
    drag = fused.element_loads(x, v, a, uf, af, mesh.elements, *props[:4], 0.0, *props[5:],
                               tangent=True, with_added_mass=False)
    f, dF_dv, _ = hydro.drag_forces(x, v, uf, mesh.elements, mesh.length0, mesh.diameter,
                                    mesh.Cd, mesh.Ct, mesh.water_density)
    np.testing.assert_allclose(drag.total_forces - drag.element_forces, f, rtol=0,
                               atol=RTOL * np.abs(f).max())
    axial_c = np.zeros_like(dF_dv)  # BA = 0: no dashpot
    np.testing.assert_allclose(drag.C, axial_c - dF_dv, rtol=0, atol=RTOL * np.abs(dF_dv).max())


MOORDYN_OPTIONS = {"slack_damping": {"slack_damping": True},
                   "node_drag": {"drag_velocity": "node"},
                   "both": {"slack_damping": True, "drag_velocity": "node"}}


@pytest.mark.parametrize("options", MOORDYN_OPTIONS)
@pytest.mark.parametrize("mode", ["mixed", "slack", "band"])
def test_moordyn_options_equal_numpy(mode, options):
    """MoorDyn's choices in the compiled kernel against the numpy path, with damping, added
    mass and a ramped current: ``slack_damping`` (the dashpot kept whole in slack elements)
    and ``drag_velocity: node`` (each node's drag share at its own velocity); each changes
    the loads (not the default's)."""
    mesh = discretize(_system())
    fluid = FLUIDS["ramped"]
    kw = MOORDYN_OPTIONS[options]
    ref = DynamicModel(mesh, fluid, kernel="numpy", **kw)
    new = DynamicModel(mesh, fluid, kernel="numba", **kw)
    default = DynamicModel(mesh, fluid, kernel="numba")
    assert new.kernel == "numba"
    x, v, a = _configuration(mesh, mode, 11)
    material = ref.initial_material(x)
    for tangent in (True, False):
        args = (x, v, a, 3.0, material, 0.1, tangent)
        _assert_same(ref.evaluate(*args), new.evaluate(*args))
    assert not np.allclose(default.evaluate(*args).nodal, new.evaluate(*args).nodal)


def test_added_mass_part_of_the_tangent_is_the_derivative_of_the_added_mass_forces():
    """``Ka`` (the added-mass forces' part of ``K``, weighted 1 by HHT, the rest of ``K``
    ``1 + alpha``) is ``-d(-M_a(x) a)/dx`` of the nodal added-mass forces (``inertial``):
    against central differences in every node coordinate, within 1e-7 of the largest; and
    a part of ``K`` (Cat != Ca: ``M_a`` turns with the element)."""
    mesh = discretize(_system(Ca=1.0, Cat=0.3))
    model = DynamicModel(mesh, FLUIDS["still"], kernel="numba")
    x, v, a = _configuration(mesh, "taut", 0)
    a = 1e3 * a  # a visible derivative next to the axial stiffness
    material = model.initial_material(x)

    def inertial(xx):
        return model.evaluate(xx, v, a, 2.0, material, 0.1, False).inertial.ravel()

    ev = model.evaluate(x, v, a, 2.0, material, 0.1, True)
    n = 3 * mesh.n_nodes
    Ka = np.zeros((n, n))
    for e, (i, j) in enumerate(mesh.elements):
        dofs = np.r_[3 * i:3 * i + 3, 3 * j:3 * j + 3]
        Ka[np.ix_(dofs, dofs)] += ev.Ka[e]
    fd = np.zeros((n, n))
    for k in range(n):
        step = np.zeros(n)
        step[k] = 1e-6
        fd[:, k] = -(inertial(x + step.reshape(x.shape))
                     - inertial(x - step.reshape(x.shape))) / 2e-6
    assert np.abs(fd).max() > 1.0
    assert np.allclose(Ka, fd, rtol=0, atol=1e-7 * np.abs(fd).max())
