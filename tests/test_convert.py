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
    "MoorDyn/wavekin_2/wavekin_2.txt", "MoorDyn/wavekin_2/wavekin_3.txt",
    "MoorDyn/wavekin_7/wavekin_7.txt", "MoorDyn/BeamSimplySupported.txt",
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


RTEST = "OpenFAST-r-test/"


#: Decks without a static equilibrium: free rods sinking with nothing to hold them (MoorDyn
#: runs their fall); the statics say so and the dynamics starts from the deck's pose.
NO_EQUILIBRIUM = [RTEST + "modules/moordyn/md_horizontal/moordyn.dat",
                  RTEST + "modules/moordyn/md_vertical/moordyn.dat"]


#: MoorDyn decks of OpenFAST's regression tests (origins in tests/data/moordyn/public/
#: README.md): OpenFAST-coupled platforms (their Coupled/Vessel fairleads prescribed points),
#: MoorDyn-F driver tests with bodies, rods and EI, v1 point tables with v2 line tables, the
#: CtrlChan column. Not here: the decks refused for what moorline does not model
#: (``test_rtest_decks_with_unsupported_input_are_refused``).
RTEST_DECKS = [RTEST + deck for deck in (
    "glue-codes/openfast/5MW_ITIBarge_DLL_WTurb_WavesIrr/"
    "NRELOffshrBsline5MW_ITIBarge4_MoorDyn.dat",
    "glue-codes/openfast/5MW_MRSemi_DLL_WSt_WavesIrr/MRSemi_MoorDyn.dat",
    "glue-codes/openfast/5MW_OC3Spar_DLL_WTurb_WavesIrr/NRELOffshrBsline5MW_OC3Hywind_MoorDyn.dat",
    "glue-codes/openfast/5MW_OC4Semi_MD_Linear/NRELOffshrBsline5MW_OC4DeepCwindSemi_MoorDyn.dat",
    "glue-codes/openfast/5MW_OC4Semi_WSt_WavesWN/"
    "NRELOffshrBsline5MW_OC4DeepCwindSemi_MoorDyn.dat",
    "glue-codes/openfast/5MW_TLP_DLL_WTurb_WavesIrr_WavesMulti/"
    "NRELOffshrBsline5MW_MIT_NREL_TLP_MoorDyn.dat",
    "glue-codes/openfast/MHK_RM1_Floating/MHK_RM1_Floating_MoorDyn.dat",
    "glue-codes/openfast/MHK_RM1_Floating_MR_Linear/MHK_RM1_Floating_MoorDyn.dat",
    "glue-codes/openfast/MHK_RM1_Floating_Steady_MirrorRotor/MHK_RM1_Floating_MoorDyn.dat",
    "glue-codes/openfast/MHK_RM1_Floating_Tank-scaled/FRM1Q_MoorDyn.dat",
    "glue-codes/openfast/MHK_RM1_Floating_wNacDrag/MHK_RM1_Floating_wNacDrag_MoorDyn.dat",
    "glue-codes/openfast/StC_test_OC4Semi/NRELOffshrBsline5MW_OC4DeepCwindSemi_MoorDyn.dat",
    "glue-codes/openfast/StC_test_OC4Semi_blade2/NRELOffshrBsline5MW_OC4DeepCwindSemi_MoorDyn.dat",
    "modules/moordyn/5MW_OC4/moordyn.dat",  # an early MoorDyn-F v2 body row (1coupled)
    "modules/moordyn/5MW_OC4_simple/moordyn.dat",
    "modules/moordyn/Node_Check_(N=20)/test.dat",
    "modules/moordyn/Node_Check_(N=40)/test1.dat",  # v1 points, v2 lines with CtrlChan
    "modules/moordyn/Single_Line_Quasi_Static_Test/test.dat",
    "modules/moordyn/md_5MW_OC4Semi/moordyn.dat",
    "modules/moordyn/md_BdyExtLdDmpg/moordyn.dat",
    "modules/moordyn/md_Node_Check_N20/test.dat",
    "modules/moordyn/md_Node_Check_N40/test.dat",
    "modules/moordyn/md_Single_Line_Quasi_Static_Test/moordyn.dat",
    "modules/moordyn/md_Single_Line_Quasi_Static_Test/test.dat",
    "modules/moordyn/md_VIV/moordyn.dat",
    "modules/moordyn/md_bodyDrag/moordyn.dat",
    "modules/moordyn/md_cable/moordyn.dat",
    "modules/moordyn/md_case2/moordyn.dat",
    "modules/moordyn/md_case5/moordyn.dat",
    "modules/moordyn/md_lineFail/moordyn.dat",
    "modules/moordyn/md_no_line/moordyn.dat",  # pinned rods
    "modules/moordyn/md_viscoelastic/moordyn.dat",  # EA_s|EA_Dc|EA_D_Lm, BA_s|BA_d
    # the Syrope rope (g = 0; owc.dat: MoorDyn's, see tests/data/moordyn/public/README.md)
    "modules/moordyn/md_syrope/moordyn.dat",
    "modules/moordyn/md_waterkin3/moordyn.dat",
    "modules/moordyn/py_md_5MW_OC4Semi/md_primary.inp",
)] + [
    # rods above water at the deck's pose: rod buoyancy at every pose floats the body
    RTEST + "modules/moordyn/md_BodiesAndRods/moordyn.dat",
    # a free-floating buoy (no mooring) decaying from 45 deg of pitch: surge, sway and yaw
    # have no restoring (held at the deck's pose by the statics)
    RTEST + "modules/moordyn/md_float/moordyn.dat",
] + NO_EQUILIBRIUM


#: MoorDyn-F v1 decks of OpenFAST's in-tree regression tests (before r-test): count rows
#: (``1 NTypes``) before the table headers, no WtrDpth.
OPENFAST_V1 = "OpenFAST/reg_tests/5MW_Baseline/NRELOffshrBsline5MW_"
OPENFAST_V1_DECKS = [OPENFAST_V1 + name + "_MoorDyn.dat" for name in (
    "ITIBarge4", "MIT_NREL_TLP", "OC3Hywind", "OC4DeepCwindSemi")]


def _deck_id(deck: str) -> str:
    """A short test id: an r-test deck by its case folder (long ids become ``deckN``)."""
    if deck.startswith(OPENFAST_V1):
        return "openfast-v1:" + deck[len(OPENFAST_V1):-len("_MoorDyn.dat")]
    for prefix in (RTEST + "glue-codes/openfast/", RTEST + "modules/moordyn/", RTEST):
        if deck.startswith(prefix):
            folder, _, name = deck[len(prefix):].rpartition("/")
            return f"r-test:{folder}" if name.endswith("MoorDyn.dat") else f"r-test:{folder}/{name}"
    return deck


@pytest.mark.parametrize("deck", PUBLIC_BODY_DECKS + RTEST_DECKS + OPENFAST_V1_DECKS,
                         ids=_deck_id)
def test_public_body_decks_convert_solve_and_run(deck, tmp_path):
    """`moorline convert` then `moorline statics` (converged) and a short dynamics run from
    the equilibrium (2 s) of the converted case: the body decks of MoorPy and MoorDyn and
    the OpenFAST regression-test decks. A deck without a static equilibrium
    (:data:`NO_EQUILIBRIUM`): the statics say so (exit 1) and the dynamics starts from the
    deck's pose (``start: initial``)."""
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
    summary = json.loads(statics.stdout)
    system = load_case(out)
    if deck in NO_EQUILIBRIUM:
        assert statics.exit_code == 1, statics.output
        assert summary["converged"] is False
        assert summary["message"].startswith("no static equilibrium"), summary["message"]
        run = simulate(system, DynamicsSettings(duration=2.0, dt=0.05, start="initial"))
        assert run.success, run.message
        return
    assert statics.exit_code == 0, statics.output
    assert summary["converged"] is True
    if system.bodies:
        assert set(summary["bodies"]) == set(system.bodies)
    run = simulate(system, DynamicsSettings(duration=2.0, dt=0.05), initial=solve_statics(system))
    assert run.success, run.message


@pytest.mark.slow  # about 15 s (convert, statics and 1 s of dynamics of 6 lines)
def test_public_deck_with_a_rod_pinned_to_a_body_converts_solves_and_runs(tmp_path):
    """BodiesAndRods.dat: rod 2 is pinned to the free body 1 (Body1Pinned): it becomes a
    pinned body on body 1, its pin at its end A (body frame (2, 0, 2)), its axis towards end
    B; the statics converge and a short dynamics runs. The rod (10 m in diameter, 1 t/m) is
    buoyant (rods hydrostatics): it stands straight up from its pin (its buoyancy and weight
    then both act on the vertical through the pin), and the pin holds it down with its
    buoyancy less its weight, ``rho g A L_wet - m g``, ``L_wet`` the depth of the pin."""
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
    pose = static.body_pose[static.mesh.body_names.index("rod2")]
    axis = rotation_matrix(pose[3:]) @ np.array([1.0, 0.0, 0.0])
    assert axis == pytest.approx([0.0, 0.0, 1.0], abs=1e-6)
    env = system.environment
    length, area = math.hypot(3.0, 13.0), math.pi * 10.0**2 / 4
    assert -pose[2] < length  # piercing the surface
    held = (1.0e3 * length - env.water_density * area * -pose[2]) * env.gravity
    assert static.pin_reaction("rod2") == pytest.approx([0.0, 0.0, held], abs=1e-6 * abs(held))
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


@pytest.mark.parametrize(("deck", "named"), [
    # a rod of a type the deck never defines (MoorDyn-C 2.7.2 refuses it too: "Unrecognized
    # rod type Can")
    ("modules/moordyn/md_waterkin2/moordyn.dat", "RODS: unknown rod type 'Can'"),
    # FAST.Farm's farm-level mooring without the turbines' positions (`convert --turbine`)
    ("glue-codes/fast-farm/MD_Shared/SharedMooring2.dat",
     "unknown point attachment 'Turbine1': a FAST.Farm turbine: give its reference position "
     "(WT_X WT_Y WT_Z of the farm's .fstf) with `moorline convert --turbine 1 X Y Z`"),
], ids=lambda value: value.rpartition("/")[0].rpartition("/")[2] if "/" in value else "")
def test_rtest_decks_with_unsupported_input_are_refused(deck, named, tmp_path):
    """OpenFAST r-test decks using what moorline does not model: exit 2, an error naming the
    file, the row and the item, nothing written."""
    path = PUBLIC / RTEST / deck
    out = tmp_path / "c.yaml"
    result = CliRunner().invoke(cli, ["convert", str(path), "--out", str(out), "--quiet"])
    assert result.exit_code == 2
    error = result.stderr.strip().splitlines()[-1]  # after warnings of what is dropped
    assert error.startswith(f"error: {path}: ") and named in error
    assert not out.exists()


def test_v1_count_row_must_match_the_rows(tmp_path):
    """MoorDyn-F v1's ``NTypes`` row declares how many rows follow (MoorDyn-F reads that many):
    a deck listing another number is refused naming the key, the section and its line."""
    text = (PUBLIC / OPENFAST_V1_DECKS[3]).read_text().replace("1        NTypes",
                                                               "2        NTypes")
    deck = tmp_path / "count.dat"
    deck.write_text(text)
    result = CliRunner().invoke(cli, ["convert", str(deck), "--out", str(tmp_path / "c.yaml"),
                                      "--quiet"])
    assert result.exit_code == 2
    assert f"error: {deck}: line 6, LINE TYPES: NTypes = 2 but the section lists 1 entries" \
        in result.stderr


@pytest.mark.compare
def test_rtest_oc4_semi_fairlead_tensions_against_moordyn():
    """OpenFAST r-test ``modules/moordyn/md_5MW_OC4Semi/moordyn.dat`` (the OC4-DeepCwind semi:
    three 835.35 m chains, 20 segments, 200 m deep, kBot 3e6 Pa/m) read by moorline and, as
    written back, by MoorDyn-C 2.7.2 (its initial-condition solve, threshIC 1e-6, 300 s):
    the fairlead tensions (end force on the Vessel points) agree to 5.1e-5 of MoorDyn's
    (moorline 1103.73 kN, MoorDyn 1103.79 kN), the same mesh and the same lumped-mass model
    on both sides. Tolerance 2e-4: issue 14's 1e-4 agreement on the OC3/OC4/IEA-15 chain
    systems with a factor 2 for MoorDyn's stationary solve stopping at its threshold."""
    pytest.importorskip("moordyn")
    from moorline.compare.moordyn_runner import run_moordyn
    from moorline.solvers.statics import solve_statics

    system = read_moordyn(PUBLIC / RTEST / "modules/moordyn/md_5MW_OC4Semi/moordyn.dat")
    static = solve_statics(system)
    assert static.success, static.message
    md = run_moordyn(system, 0.05, 1.0e-3, 0.05, tmax_ic=300.0, thresh_ic=1.0e-6)
    assert md["success"], md["message"]
    theirs = np.linalg.norm(np.asarray(md["end_force"])[0, :, 1], axis=1)
    ours = [np.linalg.norm(static.end_force(name, "b")) for name in md["lines"]]
    np.testing.assert_allclose(ours, theirs, rtol=2.0e-4)


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
    decks with `Currents 1` (viv, wavekin_2) carry MoorDyn's steady profile, those with
    `WaveKin` 2, 3 and 7 (wavekin_2, wavekin_7) their wave components."""
    import json

    path = PUBLIC / deck
    out = tmp_path / "case.yaml"
    runner = CliRunner()
    result = runner.invoke(cli, ["convert", str(path), "--out", str(out), "--quiet"])
    assert result.exit_code == 0, result.output
    system = load_case(out)
    if deck.startswith(("MoorDyn/viv", "MoorDyn/wavekin_2")):
        assert len(system.environment.current.z_levels) > 2
    if deck.startswith(("MoorDyn/wavekin_2", "MoorDyn/wavekin_7")):
        assert system.environment.waves.kind == "components"
        assert system.environment.waves.active
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


def test_write_case_keeps_a_bodys_exciting_force_table_and_wave_loads(tmp_path):
    """A body's exciting-force table and its long-wave loads survive write_case and reload
    (cases/harmonic_body.yaml: Tuah Ex5's disc with an excitation table); a body holding a
    radiation table from a database is refused with a message, not written without it."""
    import dataclasses

    from moorline.model import RadiationTable

    system = load_case(ROOT / "cases" / "harmonic_body.yaml")
    name, body = next(iter(system.bodies.items()))
    assert body.excitation is not None
    again = load_case(write_case(system, tmp_path / "c.yaml"))
    assert again.bodies[name].excitation == body.excitation
    assert again.bodies[name].wave_loads == body.wave_loads
    eye = tuple(tuple(float(i == j) for j in range(6)) for i in range(6))
    table = RadiationTable((0.5, 1.0), (eye, eye), (eye, eye))
    held = dataclasses.replace(body, added_mass=None, damping=None, radiation=table)
    with pytest.raises(ValueError, match="radiation table"):
        write_case(dataclasses.replace(system, bodies={name: held}), tmp_path / "r.yaml")
