"""MoorDyn ``BODIES`` and ``RODS`` read into moorline bodies (io/moordyn_rigid.py): each value
against the deck's numbers worked by hand (MoorDyn's conventions: docs/inputs.rst, Body.cpp,
Rod.cpp of MoorDyn-C 2.7)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from moorline.errors import CaseError
from moorline.io.moordyn import read_moordyn_deck
from moorline.mesh import world_position
from moorline.solvers.bodies import body_loads

RHO, G = 1025.0, 9.80665
LINE_TYPE = ["---------------------- LINE TYPES ----------------------",
             "TypeName Diam Mass/m EA BA/-zeta EI Cd Ca CdAx CaAx",
             "(name) (m) (kg/m) (N) (N-s/-) (N-m^2) (-) (-) (-) (-)",
             "rope 0.1 20.0 1.0e8 -0.5 0.0 1.2 1.0 0.05 0.0"]
ROD_TYPE = ["---------------------- ROD TYPES ----------------------",
            "TypeName Diam Mass/m Cd Ca CdEnd CaEnd", "(name) (m) (kg/m) (-) (-) (-) (-)",
            "can 2.0 500.0 0.8 1.0 0.6 0.5"]


def _deck(tmp_path: Path, bodies: list[str], points: list[str], lines: list[str],
          rods: list[str] = ()) -> Path:
    text = [*LINE_TYPE, *ROD_TYPE]
    if bodies:
        text += ["---------------------- BODIES ----------------------",
                 "ID Attachment X0 Y0 Z0 r0 p0 y0 Mass CG* I* Volume CdA* Ca*",
                 "(#) (-) (m) (m) (m) (deg) (deg) (deg) (kg) (m) (kg-m^2) (m^3) (m^2) (-)",
                 *bodies]
    if rods:
        text += ["---------------------- RODS ----------------------",
                 "ID RodType Attachment Xa Ya Za Xb Yb Zb NumSegs RodOutputs",
                 "(#) (name) (#/key) (m) (m) (m) (m) (m) (m) (-) (-)", *rods]
    text += ["---------------------- POINTS ----------------------",
             "ID Attachment X Y Z Mass Volume CdA Ca", "(#) (-) (m) (m) (m) (kg) (m^3) (m^2) (-)",
             *points,
             "---------------------- LINES ----------------------",
             "ID LineType AttachA AttachB UnstrLen NumSegs LineOutputs",
             "(#) (name) (#) (#) (m) (-) (-)", *lines,
             "---------------------- OPTIONS ----------------------",
             "100.0 WtrDpth", "1025.0 rho", "9.80665 g",
             "---------------------- need this line ----------------------"]
    path = tmp_path / "deck.dat"
    path.write_text("\n".join(text) + "\n")
    return path


ANCHORS = ["1 Fixed 200 0 -100 0 0 0 0", "2 Fixed -200 0 -100 0 0 0 0"]


def test_free_body_mass_buoyancy_added_mass_and_drag(tmp_path):
    """Mass, CG (x|y|z), diagonal inertia about the CG, buoyancy at the CG (MoorDyn's model),
    added mass Ca rho V in translation, CdA as per-axis drag area; Body1 points in the body
    frame."""
    path = _deck(tmp_path, ["1 Free 0 0 -10 0 0 0 5e4 0.5|0|-1 1e6|2e6|3e6 80.0 12.0|0 0.6"],
                 [*ANCHORS, "3 Body1 3 0 -2 0 0 0 0", "4 Body1 -3 0 -2 0 0 0 0"],
                 ["1 rope 1 3 205 10 -", "2 rope 2 4 205 10 -"])
    deck = read_moordyn_deck(path)
    body = deck.system.bodies["body1"]
    assert body.kind == "free" and body.position == (0.0, 0.0, -10.0)
    assert body.mass == 5e4 and body.center_of_gravity == pytest.approx((0.5, 0.0, -1.0))
    np.testing.assert_allclose(body.inertia, np.diag([1e6, 2e6, 3e6]), atol=1e-6)
    hs = body.hydrostatics
    assert hs.kind == "matrix" and hs.volume == 80.0
    assert hs.center_of_buoyancy == pytest.approx((0.5, 0.0, -1.0))
    assert not np.any(hs.stiffness)
    np.testing.assert_allclose(body.added_mass, np.diag([0.6 * RHO * 80.0] * 3 + [0.0] * 3))
    assert body.drag_area == (12.0, 12.0, 12.0) and body.Cd == 1.0
    assert any("drag CdA 12" in n for n in deck.notes)
    point = deck.system.points["point3"]
    assert point.kind == "body" and point.body == "body1" and point.position == (3.0, 0.0, -2.0)
    assert deck.system.lines["line1"].end_b == "point3"


def test_euler_angles_orient_the_body(tmp_path):
    """MoorDyn's R = Rx(r0) Ry(p0) Rz(y0): a pitch of 90 deg turns the body's x axis to
    -z (a right-handed rotation about y)."""
    path = _deck(tmp_path, ["1 Free 0 0 -10 0 90 0 5e4 0 1e6 80.0 0 0"],
                 [*ANCHORS, "3 Body1 3 0 0 0 0 0 0", "4 Body1 0 3 0 0 0 0 0"],
                 ["1 rope 1 3 205 10 -", "2 rope 2 4 205 10 -"])
    system = read_moordyn_deck(path).system
    np.testing.assert_allclose(world_position(system, system.points["point3"]),
                               [0.0, 0.0, -13.0], atol=1e-12)
    np.testing.assert_allclose(world_position(system, system.points["point4"]),
                               [0.0, 3.0, -10.0], atol=1e-12)


def test_body_point_mass_and_volume_join_the_body(tmp_path):
    """A body point's mass and volume move onto the body: total mass, mass-weighted CG,
    inertia about the new CG by parallel axes, volume-weighted centre of buoyancy."""
    path = _deck(tmp_path, ["1 Free 0 0 -10 0 0 0 100 0 10 2.0 0 0"],
                 [*ANCHORS, "3 Body1 4 0 0 300 6.0 0 0", "4 Body1 -4 0 0 0 0 0 0"],
                 ["1 rope 1 3 205 10 -", "2 rope 2 4 205 10 -"])
    system = read_moordyn_deck(path).system
    body = system.bodies["body1"]
    assert body.mass == 400.0
    assert body.center_of_gravity == pytest.approx((3.0, 0.0, 0.0))  # (300 * 4) / 400
    # about the CG: 10 + 100 * 3^2 (body) + 300 * 1^2 (point) about y and z; 10 about x
    np.testing.assert_allclose(np.diag(body.inertia), [10.0, 1210.0, 1210.0])
    assert body.hydrostatics.volume == 8.0
    assert body.hydrostatics.center_of_buoyancy == pytest.approx((3.0, 0.0, 0.0))  # 6*4/8
    point = system.points["point3"]
    assert point.mass == 0.0 and point.volume == 0.0


def test_body_attached_rod_adds_a_cylinder(tmp_path):
    """A vertical rod fixed to a body, fully submerged: weight w L at its middle, a solid
    cylinder's inertia, its volume, transverse added mass Ca rho A L with the arm moments and
    the ends' axial added mass CaEnd rho (2/3) pi r^3 each; lines on R1A/R1B attach to body
    points at the rod's ends."""
    path = _deck(tmp_path, ["1 Free 0 0 -20 0 0 0 0 0 0 0 0 0"], ANCHORS,
                 ["1 rope 1 R1A 205 10 -", "2 rope 2 R1B 205 10 -"],
                 rods=["1 can Body1 0 0 -1 0 0 -5 4 -"])
    deck = read_moordyn_deck(path)
    body = deck.system.bodies["body1"]
    L, d, w = 4.0, 2.0, 500.0
    m, area = w * L, math.pi * d**2 / 4
    assert body.mass == pytest.approx(m)
    assert body.center_of_gravity == pytest.approx((0.0, 0.0, -3.0))
    transverse = m * (L**2 / 12 + d**2 / 16)
    np.testing.assert_allclose(np.diag(body.inertia), [transverse, transverse, m * d**2 / 8])
    hs = body.hydrostatics
    assert hs.kind == "rods" and hs.volume == 0.0
    assert hs.rods == (((0.0, 0.0, -1.0), (0.0, 0.0, -5.0), d),)
    # its buoyancy at the deck pose: rho g A L at the rod's middle
    load, _ = body_loads(body, np.array(body.position), np.eye(3), G, RHO)
    np.testing.assert_allclose(load, [0, 0, RHO * G * area * L - m * G, 0, 0, 0],
                               atol=1e-9 * m * G)
    A = np.asarray(body.added_mass)
    side = 1.0 * RHO * area * L
    ends = 2 * 0.5 * RHO * 2 / 3 * math.pi * (d / 2) ** 3
    assert A[0, 0] == pytest.approx(side) and A[2, 2] == pytest.approx(ends)
    # roll: int Ca rho A z^2 dz over z in [-5, -1]; surge-pitch coupling: int Ca rho A z dz
    assert A[3, 3] == pytest.approx(RHO * area * (5**3 - 1) / 3)
    assert A[0, 4] == pytest.approx(RHO * area * (-(5**2 - 1) / 2))
    assert body.drag_area[0] == pytest.approx(0.8 * d * L)  # transverse Cd d L
    assert body.drag_area[2] == pytest.approx(2 * 0.6 * area)  # both ends, CdEnd A
    lines = deck.system.lines
    assert deck.system.points[lines["line1"].end_b].position == (0.0, 0.0, -1.0)
    assert deck.system.points[lines["line2"].end_b].position == (0.0, 0.0, -5.0)


def test_surface_piercing_rod_floats_at_its_submerged_length(tmp_path):
    """A vertical rod through the surface (rods hydrostatics, issue 14): buoyancy rho g A 6 at
    the submerged part's centre (0, 0, -3), heave stiffness K33 = rho g A, and, the body origin
    on the surface (the submerged length unchanged by a tilt about it), roll and pitch
    stiffness ``-rho g V 3`` of the centre of buoyancy 3 below the origin plus the waterplane
    inertia's ``rho g pi d^4 / 64`` (Archimedes' metacentric term of the piercing can)."""
    path = _deck(tmp_path, ["1 Free 0 0 0 0 0 0 0 0 0 0 0 0"], ANCHORS,
                 ["1 rope 1 R1A 230 10 -", "2 rope 2 R1A 230 10 -"],
                 rods=["1 can Body1 0 0 -6 0 0 2 8 -"])
    deck = read_moordyn_deck(path)
    body = deck.system.bodies["body1"]
    area = math.pi
    assert body.hydrostatics.kind == "rods"
    load, K = body_loads(body, np.zeros(3), np.eye(3), G, RHO)
    buoyancy = RHO * G * area * 6
    assert load[2] + body.mass * G == pytest.approx(buoyancy)
    assert K[2, 2] == pytest.approx(RHO * G * area)
    weight_arm = -body.mass * G * body.center_of_gravity[2]  # the rod's weight below the origin
    waterplane = RHO * G * math.pi * 2.0**4 / 64  # the can's diameter: 2 m
    assert K[3, 3] == pytest.approx(-buoyancy * 3 + weight_arm + waterplane)
    assert K[4, 4] == pytest.approx(K[3, 3])
    assert K[2, 4] == pytest.approx(0.0, abs=1e-9 * buoyancy)


def test_free_rod_becomes_a_body_along_its_axis(tmp_path):
    """A free rod: a body at its middle, body x along the rod, inertia diagonal there, its
    ends (R1A, R1B) body points at -+L/2 whose world positions are the deck's ends."""
    path = _deck(tmp_path, [], ANCHORS, ["1 rope 1 R1B 195 10 -", "2 rope 2 R1A 195 10 -"],
                 rods=["1 can Free -3 0 -50 3 0 -58 5 -"])
    system = read_moordyn_deck(path).system
    body = system.bodies["rod1"]
    L = 10.0
    m = 500.0 * L
    assert body.position == pytest.approx((0.0, 0.0, -54.0)) and body.mass == pytest.approx(m)
    np.testing.assert_allclose(np.diag(body.inertia),
                               [m * 4 / 8, m * (L**2 / 12 + 4 / 16), m * (L**2 / 12 + 4 / 16)])
    np.testing.assert_allclose(world_position(system, system.points["rod1A"]), [-3, 0, -50],
                               atol=1e-12)
    np.testing.assert_allclose(world_position(system, system.points["rod1B"]), [3, 0, -58],
                               atol=1e-12)


def test_zero_length_rod_is_a_point_and_coupled_body_is_fixed(tmp_path):
    """A free rod with no segments is one free point for both ends; a Coupled body is a fixed
    body whose own mass and volume are dropped (as in MoorDyn), with a note."""
    path = _deck(tmp_path, ["1 Coupled 0 0 -5 0 0 0 1e5 0 1e6 100 0 0"],
                 [*ANCHORS, "3 Body1 5 0 0 0 0 0 0"],
                 ["1 rope 1 R1A 120 10 -", "2 rope 3 R1B 90 10 -", "3 rope 2 3 200 10 -"],
                 rods=["1 can Free 100 0 -60 100 0 -60 0 -"])
    deck = read_moordyn_deck(path)
    system = deck.system
    assert system.lines["line1"].end_b == system.lines["line2"].end_b == "rod1"
    assert system.points["rod1"].kind == "free"
    body = system.bodies["body1"]
    assert body.kind == "fixed" and body.mass == 0.0 and body.hydrostatics.volume == 0.0
    assert any("ignored, as MoorDyn does" in n for n in deck.notes)


def test_point_like_body_becomes_a_free_point(tmp_path):
    """A free body whose lines all meet at one point at its CG and centre of buoyancy has no
    rotational stiffness: it becomes that free point with the body's mass, volume and
    Ca = added mass / (rho V)."""
    path = _deck(tmp_path, ["1 Free 0 0 -40 0 0 0 200 0 5 0.5 0 1.0"],
                 [*ANCHORS, "3 Body1 0 0 0 0 0 0 0", "4 Body1 0 0 0 0 0 0 0"],
                 ["1 rope 1 3 205 10 -", "2 rope 2 4 205 10 -"])
    system = read_moordyn_deck(path).system
    assert not system.bodies and "point4" not in system.points
    point = system.points["point3"]
    assert point.kind == "free" and point.position == (0.0, 0.0, -40.0)
    assert point.mass == 200.0 and point.volume == 0.5 and point.Ca == pytest.approx(1.0)
    assert system.lines["line2"].end_b == "point3"


def test_unknown_rod_end_and_body_are_errors(tmp_path):
    path = _deck(tmp_path, [], ANCHORS, ["1 rope 1 R2A 195 10 -"],
                 rods=["1 can Free -3 0 -50 3 0 -58 5 -"])
    with pytest.raises(CaseError, match="R2A"):
        read_moordyn_deck(path)
    path = _deck(tmp_path, [], [*ANCHORS, "3 Body1 0 0 0 0 0 0 0"], ["1 rope 1 3 195 10 -"])
    with pytest.raises(CaseError, match="unknown point attachment 'Body1'"):
        read_moordyn_deck(path)


def test_converted_case_keeps_products_of_inertia_and_drag(tmp_path):
    """A body with a rod off its axes has products of inertia; the case file written by
    `convert` holds them and the drag area, and loads back the same body."""
    from moorline.io import load_case
    from moorline.io.case_writer import write_case

    path = _deck(tmp_path, ["1 Free 0 0 -20 0 0 0 1e4 0 1e5 20 2.0 0.5"], ANCHORS,
                 ["1 rope 1 R1A 205 10 -", "2 rope 2 R1B 205 10 -"],
                 rods=["1 can Body1 2 0 -1 2 0 -5 4 -"])
    system = read_moordyn_deck(path).system
    body = system.bodies["body1"]
    assert body.inertia[0][2] != 0.0  # the rod sits off the CG in x and z
    out = write_case(system, tmp_path / "case.yaml")
    back = load_case(out).bodies["body1"]
    np.testing.assert_allclose(back.inertia, body.inertia, rtol=1e-12)
    assert back.drag_area == pytest.approx(body.drag_area)
    np.testing.assert_allclose(back.added_mass, body.added_mass, rtol=1e-12, atol=1e-9)
    assert back.hydrostatics.center_of_buoyancy == pytest.approx(
        body.hydrostatics.center_of_buoyancy)


def test_written_body_deck_reads_back(tmp_path):
    """write_moordyn's BODIES row and Body<k> points read back as the same body: mass, CG,
    inertia, buoyancy at the CG, added mass Ca rho V, the points' body-frame positions."""
    from moorline.io.moordyn import write_moordyn
    from moorline.verification.moordyn_body import buoy_system

    system = buoy_system()
    back = read_moordyn_deck(write_moordyn(system, tmp_path / "deck.dat", 0.0025)).system
    ours, theirs = system.bodies["buoy"], back.bodies["buoy"]
    assert theirs.kind == "free" and theirs.position == ours.position
    assert theirs.mass == ours.mass
    assert theirs.center_of_gravity == pytest.approx(ours.center_of_gravity)
    np.testing.assert_allclose(theirs.inertia, ours.inertia)
    assert theirs.hydrostatics.volume == ours.hydrostatics.volume
    assert theirs.hydrostatics.center_of_buoyancy == pytest.approx(
        ours.hydrostatics.center_of_buoyancy)
    np.testing.assert_allclose(theirs.added_mass, ours.added_mass, rtol=1e-12)
    for name in ("leg1", "leg2", "hawser"):
        assert back.points[name].kind == "body" and back.points[name].body == "buoy"
        assert back.points[name].position == system.points[name].position


def test_free_rod_hanging_against_moordyn(tmp_path):
    """MoorDyn's RodHanging deck (a 20 m free rod hanging from two 450 m ropes): the rod's
    equilibrium depth and the rope tensions of the converted deck against MoorDyn-C 2.7 on
    the same file. MoorDyn's initial condition is off for this deck (TmaxIC 0), so its
    equilibrium is the mean of 50-90 s of its own dynamics (the rope drag damps the swing to
    mm); measured differences 0.2 mm and 0.002 %; tolerances 1 cm and 0.5 % (issue 14's)."""
    moordyn = pytest.importorskip("moordyn")
    from moorline.compare.moordyn_runner import silenced_fd
    from moorline.solvers.statics import solve_statics

    source = Path(__file__).parent / "data/moordyn/public/MoorDyn/RodHanging.txt"
    deck = tmp_path / "rod.txt"
    deck.write_text(source.read_text().replace("2             writeLog", "0 writeLog"))
    system = read_moordyn_deck(deck).system
    static = solve_statics(system)
    assert static.success
    with silenced_fd(1):
        md = moordyn.Create(str(deck))
        moordyn.Init(md, [], [])
    try:
        rod = moordyn.GetRod(md, 1)
        line = moordyn.GetLine(md, 1)
        depth, tension = [], []
        for i in range(900):
            moordyn.Step(md, [], [], i * 0.1, 0.1)
            if i >= 500:
                ends = [moordyn.GetRodNodePos(rod, k) for k in (0, moordyn.GetRodN(rod))]
                depth.append(0.5 * (ends[0][2] + ends[1][2]))
                tension.append(np.linalg.norm(moordyn.GetLineNodeForce(line, 0)))
    finally:
        moordyn.Close(md)
    assert abs(static.body_position("rod1")[2] - np.mean(depth)) < 0.01
    ours = np.linalg.norm(static.end_force("line1", "a"))
    assert ours == pytest.approx(np.mean(tension), rel=5e-3)


def test_fixed_and_coupled_rods_become_end_points(tmp_path):
    """A Fixed rod's ends are fixed points, a Coupled rod's prescribed points (named
    rod<k>A/B, at the deck's coordinates); ends no line uses are left out."""
    path = _deck(tmp_path, [], ANCHORS, ["1 rope 1 R1B 195 10 -", "2 rope 2 R2A 195 10 -"],
                 rods=["1 can Fixed 0 0 -100 0 0 -98 2 -", "2 can Coupled -10 0 -5 -10 0 5 2 -"])
    deck = read_moordyn_deck(path)
    points = deck.system.points
    assert points["rod1B"].kind == "fixed" and points["rod1B"].position == (0.0, 0.0, -98.0)
    assert points["rod2A"].kind == "prescribed" and points["rod2A"].position == (-10.0, 0.0, -5.0)
    assert "rod1A" not in points and "rod2B" not in points
    assert any("coupled rod" in n for n in deck.notes)
