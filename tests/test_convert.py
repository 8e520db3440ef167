"""moorline convert: a MoorDyn deck becomes a case file that loads back into the same system;
and any case survives write -> load."""

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from moorline.cli import cli
from moorline.io import load_case
from moorline.io.case_writer import write_case
from moorline.io.moordyn import read_moordyn

ROOT = Path(__file__).resolve().parents[1]


def _comparable(system):
    return replace(system, source=None, analyses=())


def test_convert_moordyn_deck_round_trips(tmp_path):
    deck = ROOT / "tests" / "data" / "moordyn" / "oc3.dat"
    out = tmp_path / "oc3.yaml"
    result = CliRunner().invoke(cli, ["convert", str(deck), "--out", str(out), "--quiet"])
    assert result.exit_code == 0, result.output
    assert _comparable(load_case(out)) == _comparable(read_moordyn(deck))


@pytest.mark.parametrize("case", ["oc3_line.yaml", "oc3_dynamics.yaml", "wang_box.yaml",
                                  "tuah_ex2.yaml"])
def test_case_files_survive_write_and_load(tmp_path, case):
    system = load_case(ROOT / "cases" / case)
    again = load_case(write_case(system, tmp_path / case))
    assert _comparable(again) == _comparable(system)
    assert again.analyses == system.analyses


BAD_DECKS = ROOT / "tests" / "data" / "bad" / "moordyn"


def test_deck_with_only_free_points_is_refused(tmp_path):
    """Nothing holds the lines: refused when read (statics would be singular), exit 2."""
    deck = BAD_DECKS / "only_free_points.dat"
    out = tmp_path / "x.yaml"
    result = CliRunner().invoke(cli, ["convert", str(deck), "--out", str(out), "--quiet"])
    assert result.exit_code == 2, result.output
    assert result.stderr.startswith(f"error: {deck}: the lines joining the points 'anchor1'")
    assert "held by no fixed or prescribed point" in result.stderr
    assert len(result.stderr.strip().splitlines()) == 1 and not out.exists()


@pytest.mark.parametrize(("deck", "field", "reason"), [
    ("negative_cd", "line_types.main.Cd", "must be >= 0, got -1.6"),
    ("negative_kbot", "environment.seabed.stiffness", "must be >= 0, got -3000000.0"),
    ("negative_volume", "points.fairlead2.volume", "must be >= 0, got -1.0"),
    ("zero_depth", "environment.depth", "must be > 0, got 0.0"),
])
def test_convert_refuses_what_would_not_load(tmp_path, deck, field, reason):
    """A deck with values a case may not hold: exit 2, one line naming the deck, the key of
    the case and the reason; nothing written."""
    path = BAD_DECKS / f"{deck}.dat"
    out = tmp_path / "x.yaml"
    result = CliRunner().invoke(cli, ["convert", str(path), "--out", str(out), "--quiet"])
    assert result.exit_code == 2, result.output
    assert result.stderr.strip() == (f"error: {path}: cannot be converted, the case would not "
                                     f"load (not written): {out}: {field}: {reason}")
    assert not out.exists()


@pytest.mark.parametrize(("deck", "message"), [
    ("nan_length", "line 19, LINES: UnstrLen must be a number, got nan"),
    ("huge_segments", "lines.line1.segments: must be at most 1e+12 (MAX_COUNT)"),
])
def test_convert_refuses_bad_numbers(tmp_path, deck, message):
    path = BAD_DECKS / f"{deck}.dat"
    out = tmp_path / "x.yaml"
    result = CliRunner().invoke(cli, ["convert", str(path), "--out", str(out), "--quiet"])
    assert result.exit_code == 2, result.output
    assert result.stderr.startswith(f"error: {path}: ") and message in result.stderr
    assert not out.exists()


# --------------------------------------------------------------------------- issue 14

DECKS = ROOT / "tests" / "data" / "moordyn"


def test_statics_converts_a_moordyn_deck_on_the_fly(tmp_path):
    """`moorline statics deck.dat`: not "the top level must be a mapping" but the deck read
    as `convert` reads it, with a note saying so; the same equilibrium as the converted
    case."""
    import json

    deck = DECKS / "oc3.dat"
    runner = CliRunner()
    direct = runner.invoke(cli, ["statics", str(deck), "--out", str(tmp_path / "a"), "--json"])
    assert direct.exit_code == 0, direct.output
    assert (f"{deck} is a MoorDyn deck: converted on the fly (`moorline convert {deck}` "
            "writes it as a case file)") in direct.stderr
    case = tmp_path / "oc3.yaml"
    assert runner.invoke(cli, ["convert", str(deck), "--out", str(case), "-q"]).exit_code == 0
    converted = runner.invoke(cli, ["statics", str(case), "--out", str(tmp_path / "b"),
                                    "--json"])
    assert converted.exit_code == 0, converted.output
    assert "MoorDyn deck" not in converted.stderr
    a, b = (json.loads(r.stdout)["lines"]["line1"]["end_b"]["tension"] for r in (direct,
                                                                              converted))
    assert a == pytest.approx(b, rel=1e-12)


def test_a_file_that_is_neither_case_nor_deck_keeps_the_mapping_error(tmp_path):
    path = tmp_path / "list.yaml"
    path.write_text("- a\n- b\n")
    result = CliRunner().invoke(cli, ["statics", str(path), "--out", str(tmp_path)])
    assert result.exit_code == 2
    assert "the top level must be a mapping" in result.stderr
    assert "MoorDyn" not in result.stderr


def test_a_broken_deck_given_to_statics_names_the_deck_problem(tmp_path):
    """A deck that is recognised but does not read: MoorDyn's own error (file, line,
    section), not the YAML one."""
    text = (DECKS / "oc3.dat").read_text().replace("3     main       3", "3     wire       3")
    path = tmp_path / "bad.dat"
    path.write_text(text)
    result = CliRunner().invoke(cli, ["statics", str(path), "--out", str(tmp_path)])
    assert result.exit_code == 2
    assert result.stderr.startswith(f"error: {path}: ") and "unknown line type 'wire'" in \
        result.stderr


def test_convert_keeps_time_settings_outputs_and_notes(tmp_path):
    """oc3_outputs.dat: TMax/dtOut become a dynamics analysis and output.every, OUTPUTS
    output.channels; the notes (dropped channel, time settings, line output flags) are
    comments at the top of the case."""
    out = tmp_path / "oc3_outputs.yaml"
    result = CliRunner().invoke(cli, ["convert", str(DECKS / "oc3_outputs.dat"), "--out",
                                      str(out), "--quiet"])
    assert result.exit_code == 0, result.output
    text = out.read_text()
    head = [line for line in text.splitlines() if line.startswith("#")]
    assert any("TMax = 1 s: a dynamics analysis of 1 s with dt = 0.05 s" in h for h in head)
    assert any("channel 'L1T20'" in h for h in head)
    assert any("line output flags" in h and "line1 pt" in h for h in head)
    system = load_case(out)
    assert [a.kind for a in system.analyses] == ["statics", "dynamics"]
    assert system.analyses[1].duration == 1.0 and system.output.every == 0.1
    assert system.output.channels[:3] == ("FairTen1", "AnchTen1", "L1N19T")
    assert _comparable(system) == _comparable(read_moordyn(DECKS / "oc3_outputs.dat"))


def test_convert_deck_with_point_aliases_and_wavekin(tmp_path):
    """A deck with `Fix`/`Ves` point types and WaveKin 3 converts (a warning names the
    option) and its statics converge."""
    text = (DECKS / "oc3.dat").read_text().replace("Fixed   ", "Fix     ").replace(
        "Coupled ", "Ves     ").replace("0.001         threshIC", "3  WaveKin\n0.001 threshIC")
    deck = tmp_path / "alias.dat"
    deck.write_text(text)
    out = tmp_path / "alias.yaml"
    runner = CliRunner()
    result = runner.invoke(cli, ["convert", str(deck), "--out", str(out)])
    assert result.exit_code == 0, result.output
    assert "WaveKin = 3" in result.stderr and "waves are dropped" in result.stderr
    statics = runner.invoke(cli, ["statics", str(out), "--out", str(tmp_path / "o"), "-q",
                                  "--no-plots"])
    assert statics.exit_code == 0, statics.output
    assert _comparable(load_case(out)).points == _comparable(
        read_moordyn(DECKS / "oc3.dat")).points


PUBLIC = DECKS / "public"
#: Bodies- and rods-free decks of MoorPy and MoorDyn (origins in tests/data/moordyn/public/
#: README.md) that the issue-14 reader converts; statics with the case defaults.
PUBLIC_DECKS = [
    "MoorPy/tests/case1.dat", "MoorPy/tests/case2.dat", "MoorPy/tests/case3.dat",
    "MoorPy/tests/case4.dat", "MoorPy/tests/case5.dat", "MoorPy/examples/volturn_chain.dat",
    "MoorDyn/lines.txt", "MoorDyn/WD0050_Chain.txt", "MoorDyn/WD0200_Chain.txt",
    "MoorDyn/WD0600_Chain.txt", "MoorDyn/lifting.txt", "MoorDyn/pendulum.txt",
    "MoorDyn/time_schemes.txt", "MoorDyn/local_euler/hanging.txt",
    "MoorDyn/local_euler/duplicated.txt", "MoorDyn/polyester/simple.txt",
    "MoorDyn/lowe_and_langley_2006/line.txt", "MoorDyn/wavekin_4/hanging_lines.txt",
    "MoorDyn/wave_surface/wave_surface.txt", "MoorDyn/viv/viv.txt",
    "MoorDyn/wavekin_2/wavekin_2.txt", "MoorDyn/BeamSimplySupported.txt",
    "MoorPy/tests/case6.dat",  # a W-shaped line with a buoy, lines touching the seabed
    "MoorDyn/tripod.txt",  # 11 lines, 9 free points and floats
]


#: Public decks with bodies and rods (origins in tests/data/moordyn/public/README.md):
#: coupled bodies (MoorPy case7a/b, case8, case9, sample), a free rod hanging from two lines
#: (RodHanging), a free point-like body and zero-length rods among EI lines (complex_system),
#: a free body on one line (bodyDrag).
PUBLIC_BODY_DECKS = [
    "MoorPy/tests/case7a.dat", "MoorPy/tests/case7b.dat", "MoorPy/tests/case8.dat",
    "MoorPy/tests/case9.dat", "MoorPy/examples/sample.txt", "MoorDyn/RodHanging.txt",
    "MoorDyn/local_euler/complex_system.txt", "MoorDyn/body_tests/bodyDrag.txt",
]


@pytest.mark.parametrize("deck", PUBLIC_BODY_DECKS)
def test_public_body_decks_convert_solve_and_run(deck, tmp_path):
    """`moorline convert` then `moorline statics` (converged) and a short dynamics run from
    the equilibrium (2 s) of the converted case."""
    import json

    from moorline.model import DynamicsSettings
    from moorline.solvers.dynamics import simulate
    from moorline.solvers.statics import solve_statics

    out = tmp_path / "case.yaml"
    runner = CliRunner()
    result = runner.invoke(cli, ["convert", str(PUBLIC / deck), "--out", str(out), "--quiet"])
    assert result.exit_code == 0, result.output
    statics = runner.invoke(cli, ["statics", str(out), "--out", str(tmp_path / "o"),
                                  "--json", "--quiet", "--no-plots"])
    assert statics.exit_code == 0, statics.output
    summary = json.loads(statics.stdout)
    assert summary["converged"] is True
    system = load_case(out)
    if system.bodies:
        assert set(summary["bodies"]) == set(system.bodies)
    run = simulate(system, DynamicsSettings(duration=2.0, dt=0.05), initial=solve_statics(system))
    assert run.success, run.message


@pytest.mark.slow  # about 30 s: its statics rest the sunk body's lines on the seabed
def test_public_deck_with_a_rod_pinned_to_a_body_converts_solves_and_runs(tmp_path):
    """BodiesAndRods.dat: rod 2 is pinned to the free body 1 (Body1Pinned): it becomes a
    pinned body on body 1, its pin at its end A (body frame (2, 0, 2)), its axis towards end
    B; the statics converge and a short dynamics runs. The equilibrium is not MoorDyn's:
    both rods are above the water at the deck's pose, so moorline's constant rod buoyancy
    (taken there) is none, and the 1000 t body without volume sinks onto the seabed, where
    MoorDyn's rods, buoyant node by node, float it (a limitation of the rod model, not of the
    pin)."""
    from moorline.model import DynamicsSettings
    from moorline.physics.rigid_body import rotation_matrix
    from moorline.solvers.dynamics import simulate
    from moorline.solvers.statics import solve_statics

    out = tmp_path / "case.yaml"
    runner = CliRunner()
    result = runner.invoke(cli, ["convert", str(PUBLIC / "MoorDyn/BodiesAndRods.dat"),
                                 "--out", str(out), "--quiet"])
    assert result.exit_code == 0, result.output
    system = load_case(out)
    rod = system.bodies["rod2"]
    assert (rod.kind, rod.pin_body) == ("pinned", "body1")
    assert rod.position == pytest.approx((2.0, 0.0, 2.0), abs=1e-12)
    axis = rotation_matrix(np.asarray(rod.rotation)) @ np.array([1.0, 0.0, 0.0])
    assert axis == pytest.approx(np.array([3.0, 0.0, 13.0]) / math.hypot(3.0, 13.0), abs=1e-12)
    static = solve_statics(system)
    assert static.success, static.message
    assert static.pin_reaction("rod2")[2] > 0  # holding the rod up
    run = simulate(system, DynamicsSettings(duration=1.0, dt=0.05), initial=static)
    assert run.success, run.message


def test_public_coupled_pinned_body_deck_converts_solves_and_runs(tmp_path):
    """pinnedBody.txt (a CoupledPinned body carrying a rod) sets WtrDnsty 0, a vacuum, which
    moorline's cases refuse (water_density > 0): exit 2 naming the option. With water
    (WtrDnsty 1025, the only change) it converts: the body is pinned at its reference point,
    its statics converge with the rod hanging straight down and the pin holding its weight
    less its buoyancy, and a short dynamics runs."""
    import json

    from moorline.model import DynamicsSettings
    from moorline.solvers.dynamics import simulate
    from moorline.solvers.statics import solve_statics

    deck = PUBLIC / "MoorDyn/body_tests/pinnedBody.txt"
    runner = CliRunner()
    refused = runner.invoke(cli, ["convert", str(deck), "--out", str(tmp_path / "v.yaml")])
    assert refused.exit_code == 2 and "option rho must be positive, got 0" in refused.output
    wet = tmp_path / "pinnedBody.txt"
    wet.write_text(deck.read_text().replace("0.0     WtrDnsty", "1025    WtrDnsty"))
    out = tmp_path / "case.yaml"
    result = runner.invoke(cli, ["convert", str(wet), "--out", str(out), "--quiet"])
    assert result.exit_code == 0, result.output
    system = load_case(out)
    (name, body), = system.bodies.items()
    assert body.kind == "pinned" and body.position == (0.0, 0.0, -5.0)
    statics = runner.invoke(cli, ["statics", str(out), "--out", str(tmp_path / "o"),
                                  "--json", "--quiet", "--no-plots"])
    assert statics.exit_code == 0, statics.output
    summary = json.loads(statics.stdout)
    assert summary["converged"] is True
    weight = 5e3 * 10 * 9.80665 - 1025 * 9.80665 * np.pi * 10  # rod of 5 t/m, d 2 m, 10 m
    assert summary["bodies"][name]["pin_reaction"] == pytest.approx([0, 0, weight],
                                                                     rel=1e-9, abs=1e-6)
    run = simulate(system, DynamicsSettings(duration=2.0, dt=0.05), initial=solve_statics(system))
    assert run.success, run.message


def test_coupled_body_stiffness_against_moorpy(tmp_path):
    """MoorPy case 7b (one catenary line on a coupled body, its fairlead off the body's axes):
    `moorline stiffness` of the converted deck against MoorPy 1.3's 6x6 of the same file
    (``Body.getStiffnessA``, analytic, lines only). MoorPy's line is the closed-form elastic
    catenary on a rigid seabed, moorline's 80 elements on a penalty seabed: their largest
    difference (on K55) is 0.30 %, 0.08 %, 0.14 % and 0.13 % of the largest term at 80, 160,
    320 and 640 elements: the discretization (it jitters with where the touchdown falls in an
    element) down to the seabed contact's blend-in band (:mod:`moorline.physics.seabed`;
    the converged 0.13 %); the tolerance is 5e-3 of it."""
    import json

    moorpy = pytest.importorskip("moorpy")
    deck = PUBLIC / "MoorPy/tests/case7b.dat"
    out = tmp_path / "case.yaml"
    runner = CliRunner()
    assert runner.invoke(cli, ["convert", str(deck), "--out", str(out), "-q"]).exit_code == 0
    result = runner.invoke(cli, ["stiffness", str(out), "--json", "-q"])
    assert result.exit_code == 0, result.output
    ours = np.array(json.loads(result.stdout)["stiffness"])
    ms = moorpy.System(file=str(deck))
    ms.initialize()
    ms.solveEquilibrium()
    theirs = np.asarray(ms.bodyList[0].getStiffnessA(lines_only=True))
    scale = np.abs(theirs).max()
    assert np.abs(ours - theirs).max() < 5e-3 * scale


@pytest.mark.parametrize("deck", PUBLIC_DECKS)
def test_public_decks_convert_and_reach_equilibrium(deck, tmp_path):
    """`moorline convert` then `moorline statics` with the defaults: exit 0 both; the
    decks with `Currents 1` (viv, wavekin_2) carry MoorDyn's steady profile."""
    import json

    path = PUBLIC / deck
    out = tmp_path / "case.yaml"
    runner = CliRunner()
    result = runner.invoke(cli, ["convert", str(path), "--out", str(out), "--quiet"])
    assert result.exit_code == 0, result.output
    system = load_case(out)
    if deck.startswith(("MoorDyn/viv", "MoorDyn/wavekin_2")):
        assert len(system.environment.current.z_levels) > 2
    statics = runner.invoke(cli, ["statics", str(out), "--out", str(tmp_path / "o"),
                                  "--json", "--quiet"])
    assert statics.exit_code == 0, statics.output
    assert json.loads(statics.stdout)["converged"] is True


def test_vessel_body_reports_the_published_oc3_mooring_stiffness(tmp_path):
    """`convert --vessel-body` on the OC3 deck holds its three Coupled fairleads by one fixed
    body at the origin: the statics summary's 6x6 of that body against the linearized mooring
    restoring of Jonkman (2010), NREL/TP-500-47535 (K11 = K22 = 41,180 N/m, K15 = -K24 =
    -2,821,000 N/rad, K33 = 11,940 N/m, K44 = K55 = 311,100,000 N m/rad, K66 = 11,560,000
    N m/rad; the delta connection's yaw spring excluded), 0.5 % (four significant figures of
    a quasi-static model of the same lines); without the flag, `moorline stiffness` takes the
    Coupled points as one group and gives the same matrix about the origin."""
    import json

    runner = CliRunner()
    out = tmp_path / "vessel.yaml"
    result = runner.invoke(cli, ["convert", str(DECKS / "oc3.dat"), "--vessel-body", "--out",
                                 str(out), "-q"])
    assert result.exit_code == 0, result.output
    system = load_case(out)
    assert system.bodies["vessel"].kind == "fixed"
    assert {p.body for p in system.points.values() if p.kind == "body"} == {"vessel"}
    statics = runner.invoke(cli, ["statics", str(out), "--out", str(tmp_path / "o"), "--json",
                                  "-q", "--no-plots"])
    assert statics.exit_code == 0, statics.output
    K = np.array(json.loads(statics.stdout)["bodies"]["vessel"]["mooring_stiffness"])
    published = {(0, 0): 41180.0, (1, 1): 41180.0, (0, 4): -2.821e6, (1, 3): 2.821e6,
                 (2, 2): 11940.0, (3, 3): 3.111e8, (4, 4): 3.111e8, (5, 5): 1.156e7}
    for (i, j), value in published.items():
        assert K[i, j] == pytest.approx(value, rel=5e-3), (i, j)
    plain = tmp_path / "plain.yaml"
    assert runner.invoke(cli, ["convert", str(DECKS / "oc3.dat"), "--out", str(plain),
                               "-q"]).exit_code == 0
    group = runner.invoke(cli, ["stiffness", str(plain), "--reference", "0,0,0", "--json",
                                "-q"])
    assert group.exit_code == 0, group.output
    np.testing.assert_allclose(json.loads(group.stdout)["stiffness"], K, rtol=1e-6,
                               atol=1e-6 * np.abs(K).max())
