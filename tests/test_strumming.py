"""Wake oscillator (Tuah 1982 eq. 3.2.b.1-3.2.b.8) and strumming by mode superposition."""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from moorline.errors import MoorlineError
from moorline.model import DynamicsSettings
from moorline.physics import wake
from moorline.solvers.dynamics import simulate
from moorline.solvers.statics import solve_statics
from moorline.solvers.strumming import StrummingSettings, solve_strumming
from moorline.verification import tuah_ex6

WS = 10.0
CL0 = 0.2


def free_wake(G, H, cl_start, duration, forcing=None, F=0.0):
    """Integrate the wake oscillator alone (the structure's velocity / D given by
    ``forcing(t)``)."""

    def rhs(t, y):
        u = 0.0 if forcing is None else forcing(t)
        return [y[1], float(wake.wake_acceleration(y[0], y[1], WS, G, H, F, CL0, u, 1.0))]

    t = np.linspace(0.0, duration, int(duration * 200) + 1)
    sol = solve_ivp(rhs, (0.0, duration), [cl_start, 0.0], t_eval=t, rtol=1e-10, atol=1e-12,
                    method="DOP853")
    return sol.t, sol.y[0], sol.y[1]


def frequency(t, y):
    """Mean circular frequency from upward zero crossings (linear interpolation)."""
    i = np.flatnonzero((y[:-1] < 0) & (y[1:] >= 0))
    crossings = t[i] - y[i] * (t[i + 1] - t[i]) / (y[i + 1] - y[i])
    return 2 * math.pi / np.mean(np.diff(crossings))


def test_limit_cycle_is_exact_circle():
    """E = C_L^2 + (C_L'/w_s)^2 = C_L0^2 is invariant: C_L0 cos(w_s t) for any G, H."""
    t, cl, rate = free_wake(1.65, 0.48, CL0, 20.0)
    energy = cl**2 + (rate / WS) ** 2
    assert np.abs(np.sqrt(energy) / CL0 - 1).max() < 1e-7
    assert frequency(t, cl) == pytest.approx(WS, rel=1e-6)


def test_limit_cycle_from_small_amplitude_and_logistic_growth():
    """From a small start the amplitude grows to C_L0 at w_s; for small eps = G C_L0^2 the
    averaged energy follows the van der Pol (averaging) law dE/dt = G w_s (C_L0^2 - E) E."""
    G, E0 = 0.5, (0.05 * CL0) ** 2
    t, cl, rate = free_wake(G, 0.0, math.sqrt(E0), 150.0)
    energy = cl**2 + (rate / WS) ** 2
    late = t > 120.0
    assert np.sqrt(energy[late]).max() == pytest.approx(CL0, rel=1e-5)
    assert frequency(t[late], cl[late]) == pytest.approx(WS, rel=1e-5)
    rate0 = G * WS * CL0**2
    logistic = CL0**2 / (1 + (CL0**2 / E0 - 1) * np.exp(-rate0 * t))
    half = float(np.interp(0.5 * CL0**2, energy, t))  # energy grows monotonically here
    assert half == pytest.approx(math.log(CL0**2 / E0 - 1) / rate0, rel=0.02)
    assert np.abs(energy - logistic).max() < 0.03 * CL0**2


def test_h_shifts_the_frequency():
    """At small amplitude (bracket ~ C_L0^2) the frequency is w_s sqrt(1 + H C_L0^2)."""
    t, cl, _ = free_wake(1e-4, 2.0, 1e-3 * CL0, 5.0)
    assert frequency(t, cl) == pytest.approx(WS * math.sqrt(1 + 2.0 * CL0**2), rel=1e-3)


@pytest.mark.parametrize("ratio, locked", [(0.96, True), (1.04, True), (0.7, False)])
def test_lock_in_of_the_forced_wake(ratio, locked):
    """Driven by a structure vibrating at w near w_s (U'/D = Y w cos w t), the wake locks to
    w; far from w_s it keeps shedding near w_s."""
    w = ratio * WS
    t, cl, _ = free_wake(1.65, 0.48, CL0, 80.0, forcing=lambda s: 1.0 * w * math.cos(w * s),
                         F=0.04)
    measured = frequency(t[t > 50.0], cl[t > 50.0])
    if locked:
        assert measured == pytest.approx(w, rel=2e-3)
    else:
        assert abs(measured - w) > 0.1 * w


def test_lift_force_direction_and_magnitude():
    x = np.array([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]])
    v = np.zeros_like(x)
    flow = np.array([[0.3, 1.5, 0.0]])  # the tangential part does not count
    f = wake.lift_forces(np.array([0.25]), x, v, flow, np.array([[0, 1]]), 2.0, 0.1, 1025.0)
    expected = 0.5 * 1025.0 * 0.1 * 0.25 * 1.5**2 * 2.0 / 2
    assert f.shape == (1, 2, 3)
    assert np.allclose(f[0, 0], [0.0, 0.0, expected]) and np.allclose(f[0, 1], f[0, 0])
    # a moving element: relative velocity
    v[:] = [0.0, 0.5, 0.0]
    f = wake.lift_forces(np.array([0.25]), x, v, flow, np.array([[0, 1]]), 2.0, 0.1, 1025.0)
    assert f[0, 0, 2] == pytest.approx(expected * (1.0 / 1.5) ** 2)


def test_wake_parameters_and_damping():
    """Eq. 3.2.b.5-3.2.b.8 at the Ex6 data, against the printed formulas evaluated here."""
    ws, d, m, rho, nu, st = 17.47, 0.05, 0.0192, 2.0, 1.13e-5, 0.2
    p = wake.wake_parameters(ws, d, m, rho, nu, st)
    k_s = 45 * math.sqrt(nu / ws) / d                     # eq. 3.2.b.6, second form
    s_g = 2 * math.pi * st**2 * k_s                       # eq. 3.2.b.6
    xi = k_s * rho * d**2 / (4 * math.pi * m)             # eq. 3.2.b.6, first form
    G = 10 ** (0.25 - 0.21 * s_g)                         # eq. 3.2.b.5
    h = 10 ** (-0.24 + 0.66 * s_g) / s_g**2
    assert float(p.k_s) == pytest.approx(k_s, rel=1e-12)
    assert float(p.S_G) == pytest.approx(s_g, rel=1e-12)
    assert float(p.xi) == pytest.approx(xi, rel=1e-12)
    assert float(p.G) == pytest.approx(G, rel=1e-12)
    assert float(p.h) == pytest.approx(h, rel=1e-12)
    assert float(p.H) == pytest.approx(xi * h, rel=1e-12)
    assert float(p.F) == pytest.approx(4 * G * s_g / h, rel=1e-12)
    # eq. 3.2.b.8
    xi_n = 12 * rho * d / (math.pi * m) * math.sqrt(nu / 14.0)
    assert float(wake.modal_damping_ratio(14.0, d, m, rho, nu)) == pytest.approx(xi_n,
                                                                                 rel=1e-12)
    # eq. 3.2.b.4: 2 pi 0.2 0.695 / 0.05 = 17.4673 rad/s
    assert float(wake.strouhal_frequency(0.695, 0.05, 0.2)) == pytest.approx(17.46726,
                                                                               rel=1e-6)


def _steady(**kw):
    system = tuah_ex6.ex6_system()
    statics = solve_statics(system)
    options = {"viscosity": 1.13e-5, "strouhal": 0.18, "added_mass": False, "duration": 3.0,
               "dt": 0.001} | kw
    settings = StrummingSettings(**options)
    return solve_strumming(system, settings, statics)


def test_mode_refresh_carries_the_state():
    """Refreshing the modes at an unchanged in-line state changes nothing."""
    once, refreshed = _steady(), _steady(refresh_every=7)
    assert refreshed.counters["refreshes"] > 100
    scale = np.abs(once.displacement).max()
    assert scale > 1e-3
    assert np.abs(once.displacement - refreshed.displacement).max() < 1e-9 * scale
    assert np.allclose(once.lift_coefficient, refreshed.lift_coefficient, atol=1e-9)


def test_runge_kutta_order():
    results = [_steady(duration=1.0, substeps=n) for n in (1, 2, 4)]
    u = [r.displacement[:, 3, 2] for r in results]
    e1, e2 = np.abs(u[0] - u[2]).max(), np.abs(u[1] - u[2]).max()
    assert e1 > 0 and math.log2(e1 / e2) > 3.5  # fourth order: (1 - 1/16)/(1/4 - 1/16) ~ 5


def test_coupled_lock_in_to_the_natural_frequency():
    """With the shedding frequency near the fundamental (signed coupling) the wake and the
    string synchronize: C_L and the displacement share one frequency, pulled from w_s towards
    w_1; far from any mode the string just follows the shedding."""
    w1 = float(tuah_ex6.discrete_string_modes(added_mass=False)[0][0])  # closed form
    results = {}
    for label, target in (("near", 1.03 * w1), ("far", 1.6 * w1)):
        strouhal = target * tuah_ex6.DIAMETER / (2 * math.pi * tuah_ex6.SPEED)
        r = _steady(duration=20.0, strouhal=strouhal, n_modes=2)
        late = r.time > 12.0
        ws = float(r.strouhal_frequency[0].mean())
        results[label] = (ws, frequency(r.time[late], r.displacement[late, 3, 2]),
                          frequency(r.time[late], r.lift_coefficient[late, 1]))
    ws, f_u, f_cl = results["near"]
    # the wake sheds at the structure's frequency, not at its own (the element oscillators
    # modulate each other a little: equal within a tenth of the shift, not exactly)
    assert abs(f_cl - f_u) < 0.1 * abs(ws - f_u)
    assert abs(f_u - w1) < 0.5 * abs(ws - w1)
    ws, f_u, f_cl = results["far"]
    assert f_u == pytest.approx(ws, rel=5e-3) and f_cl == pytest.approx(ws, rel=5e-3)


def test_in_line_velocity_enters_the_relative_velocity():
    """Coupling to the in-line dynamics: w_s at every in-line step is built from the fluid
    velocity minus the in-line velocity of the simulate output."""
    system = tuah_ex6.ex6_system()
    inline = simulate(system, DynamicsSettings(duration=0.2, dt=0.001, tolerance=1e-8),
                      initial=solve_statics(system), output_every=0.001)
    r = solve_strumming(system, StrummingSettings(viscosity=1.13e-5, strouhal=0.18,
                                                  added_mass=False), inline)
    k = 150
    x, v = inline.positions[k], inline.velocities[k]
    flow = np.array([0.0, tuah_ex6.SPEED, 0.0])
    expected = []
    for a, b in inline.mesh.elements:  # eq. 3.2.a.3 and 3.2.b.4 by hand
        chord = x[b] - x[a]
        t = chord / math.sqrt(chord @ chord)
        u = flow - 0.5 * (v[a] + v[b])
        normal = u - (u @ t) * t
        expected.append(2 * math.pi * 0.18 * math.sqrt(normal @ normal) / tuah_ex6.DIAMETER)
    assert np.allclose(r.strouhal_frequency[k], expected, rtol=1e-12)
    assert np.abs(v[:, 1]).max() > 0.01  # the in-line motion is not negligible here
    assert r.strouhal_frequency[k].max() < r.strouhal_frequency[0].max() * 0.999


def test_needs_water():
    system = tuah_ex6.ex6_system()
    from dataclasses import replace

    dry = replace(system, environment=replace(system.environment, water_density=0.0))
    with pytest.raises(MoorlineError):
        solve_strumming(dry, StrummingSettings(viscosity=1e-5, duration=0.01),
                        solve_statics(dry))


def test_tuah_ex6_rows():
    """The quick rows: no fail, the exact references pass, every published row says why
    when it is not reproduced."""
    rows = tuah_ex6.run(quick=True)
    failed = [r for r in rows if r.status == "fail"]
    assert not failed, "\n".join(f"{r.quantity}: {r.reference} vs {r.computed}" for r in failed)
    exact = [r for r in rows if r.kind == "exact"]
    assert len(exact) == 5 and all(r.status == "pass" for r in exact)
    published = [r for r in rows if r.kind == "published"]
    assert len(published) == 5 and all(r.source for r in published)
    assert all("not reproduced:" in r.note for r in published if not r.reproduced)


def test_discrete_string_modes_are_the_eigenpairs():
    """The closed form of the four-element string against a numerical eigensolution of the
    mass and stiffness matrices assembled here (consistent structural mass [2 1; 1 2] m l0 / 6
    per element, node-lumped added mass, geometric stiffness T / h [1 -1; -1 1])."""
    from scipy.linalg import eigh

    n = tuah_ex6.ELEMENTS
    tension = tuah_ex6.STRESS0 * tuah_ex6.AREA
    h, l0 = tuah_ex6.SPAN / n, tuah_ex6.UNSTRETCHED / n
    m_s = tuah_ex6.DENSITY * tuah_ex6.AREA
    m_a = tuah_ex6.RHO * tuah_ex6.CA * tuah_ex6.AREA
    K, M = np.zeros((n + 1, n + 1)), np.zeros((n + 1, n + 1))
    for e in range(n):
        i = [e, e + 1]
        K[np.ix_(i, i)] += tension / h * np.array([[1, -1], [-1, 1]])
        M[np.ix_(i, i)] += m_s * l0 / 6 * np.array([[2, 1], [1, 2]]) + m_a * l0 / 2 * np.eye(2)
    lam, vec = eigh(K[1:-1, 1:-1], M[1:-1, 1:-1])
    omega, phi = tuah_ex6.discrete_string_modes(added_mass=True)
    assert np.allclose(omega, np.sqrt(lam), rtol=1e-12)
    assert np.allclose(np.abs(phi[1:-1]), np.abs(vec), rtol=1e-10)
    assert np.allclose(phi[1:-1].T @ M[1:-1, 1:-1] @ phi[1:-1], np.eye(n - 1), atol=1e-12)
    assert np.allclose(phi[[0, -1]], 0.0)


def test_taut_axial_tangent_of_a_slack_element():
    """``taut_axial``: a slack element keeps EA / L0 along its axis and no geometric part; a
    taut one is unchanged."""
    from moorline.physics import element
    from moorline.solvers.equilibrium import StaticModel

    system = tuah_ex6.ex6_system()
    statics = solve_statics(system)
    mesh = statics.mesh
    x = statics.positions.copy()
    model = StaticModel(mesh)
    assert np.allclose(model.tangent(x, taut_axial=True).toarray(),
                       model.tangent(x).toarray())  # all taut at the pretension
    # shorten the string: every element slack
    x_slack = x[0] + 0.9 * (x - x[0])
    length, unit = element.element_geometry(x_slack, mesh.elements)
    expected = element.tangent_blocks(length, unit, np.zeros(mesh.n_elements),
                                      mesh.EA / mesh.length0)
    K = model.tangent(x_slack, pattern=None, taut_axial=True).toarray()
    assert np.allclose(K, model.pattern.assemble(expected).toarray())
    assert np.abs(model.tangent(x_slack).toarray()).max() < 1e-4 * np.abs(K).max()


def test_slack_state_needs_nonpositive_modes_keep():
    system = tuah_ex6.ex6_system()
    statics = solve_statics(system)
    from dataclasses import replace

    x = statics.positions[0] + 0.9 * (statics.positions - statics.positions[0])
    slack = replace(statics, positions=x)
    settings = StrummingSettings(viscosity=1.13e-5, strouhal=0.18, duration=0.05, dt=0.001)
    with pytest.raises(MoorlineError, match="nonpositive_modes"):
        solve_strumming(system, settings, slack)
    r = solve_strumming(system, replace(settings, nonpositive_modes="keep", n_modes=0), slack)
    assert np.all(np.isfinite(r.displacement)) and np.any(r.omega <= 0)


def test_modal_drag_damping_is_the_drag_jacobian():
    """``drag_damping``: phi^T (-dF_drag/dv) phi against central differences of the Morison
    drag along the modes; it adds damping to the strumming."""
    from moorline.physics import hydro
    from moorline.solvers.strumming import _ModeSource

    system = tuah_ex6.ex6_system()
    statics = solve_statics(system)
    mesh, x = statics.mesh, statics.positions
    settings = StrummingSettings(viscosity=1.13e-5, strouhal=0.18, n_modes=4)
    source = _ModeSource(system, mesh, settings, float(mesh.water_density))
    modes = source.at(x, np.zeros((0, 6)), 0.0)
    rng = np.random.default_rng(1)
    v = 0.01 * rng.standard_normal(x.shape)
    v[~mesh.free_nodes] = 0.0
    flow = np.array([0.0, tuah_ex6.SPEED, 0.0])
    C = source.drag_damping(x, v, flow, modes.phi)

    def modal_force(q):
        u = v + np.einsum("m,mnc->nc", q, modes.shapes)
        f, _, _ = hydro.drag_forces(x, u, flow, mesh.elements, mesh.length0, mesh.diameter,
                                    mesh.Cd, mesh.Ct, float(mesh.water_density))
        nodal = hydro.sum_to_nodes(f, mesh.elements, mesh.n_nodes)
        return np.einsum("mnc,nc->m", modes.shapes, nodal)

    h = 1e-6
    fd = np.column_stack([-(modal_force(h * e) - modal_force(-h * e)) / (2 * h)
                          for e in np.eye(len(modes.omega))])
    assert np.allclose(C, fd, rtol=1e-6, atol=1e-8 * np.abs(fd).max())
    plain = _steady(duration=2.0)
    damped = _steady(duration=2.0, drag_damping=True)
    assert np.abs(damped.displacement).max() < 0.9 * np.abs(plain.displacement).max()


def test_held_body_dofs():
    from moorline.verification import tuah_ex7

    system, static = tuah_ex7.static_state()
    settings = StrummingSettings(viscosity=1.13e-5, n_modes=0, duration=0.02, dt=0.01,
                                 nonpositive_modes="keep", min_reynolds=40.0)
    from dataclasses import replace

    free = solve_strumming(system, settings, static)
    held = solve_strumming(system, replace(settings, held_body_dofs=("yaw",)), static)
    assert len(free.omega) == 24 and len(held.omega) == 23
    # the yaw mode (no stiffness but the statics regularization: the legs meet on the
    # disc's axis) is the one removed
    assert np.sum(np.abs(free.omega) < 0.05) == 1 and np.all(np.abs(held.omega) > 0.05)
    with pytest.raises(MoorlineError, match="held_body_dofs"):
        solve_strumming(system, replace(settings, held_body_dofs=("twist",)), static)
