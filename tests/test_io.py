"""Case-file reader: example cases, unit conversion, defaults and one test per kind of bad input."""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import pint
import pytest

from moorline.errors import CaseError
from moorline.io import MAX_STRAIN, load_case, load_case_text
from moorline.io.schema import LineSpec, LineTypeSpec, PointSpec, StaticsSpec
from moorline.io.units import to_system
from moorline.model import Line, LineType, Point, StaticsSettings

ROOT = Path(__file__).resolve().parents[1]
CASES = ROOT / "cases"
BAD = Path(__file__).resolve().parent / "data" / "bad"

# an independent registry, so the checks do not reuse the reader's conversions
U = pint.UnitRegistry()
U.define("psf = lbf / ft**2")

MINIMAL = """
name: mini
units: {units}
environment: {{depth: {depth}}}
line_types:
  chain: {{diameter: {diameter}, mass_per_length: 50, EA: {EA}}}
points:
  anchor: {{kind: fixed, position: [-300, 0, -100]}}
  fairlead: {{kind: prescribed, position: [0, 0, -10]}}
lines:
  line1: {{type: chain, length: 350, segments: 10, end_a: anchor, end_b: fairlead}}
"""


def _mini(units: str = "SI", depth: object = 100, diameter: object = 0.1, EA: object = 5e8):
    text = MINIMAL.format(units=units, depth=depth, diameter=diameter, EA=EA)
    return load_case_text(text, file="mini.yaml")


# ---- example cases ----------------------------------------------------------------------------


def test_oc3_line_loads() -> None:
    system = load_case(CASES / "oc3_line.yaml")
    assert system.name == "oc3-line" and system.units == "SI"
    assert system.source == str(CASES / "oc3_line.yaml")
    env = system.environment
    assert (env.depth, env.water_density, env.gravity) == (320.0, 1025.0, 9.80665)
    assert (env.seabed.stiffness, env.seabed.damping) == (3.0e6, 3.0e5)
    chain = system.line_types["chain"]
    assert chain.name == "chain"
    assert (chain.diameter, chain.mass_per_length, chain.EA) == (0.09, 77.7066, 384.243e6)
    assert (chain.Cd, chain.Ca, chain.Ct, chain.Cat) == (1.6, 1.0, 0.05, 0.0)
    assert system.points["anchor"].position == (-853.87, 0.0, -320.0)
    assert system.points["fairlead"].kind == "prescribed"
    line = system.lines["line1"]
    assert (line.line_type, line.length, line.segments) == ("chain", 902.2, 20)
    assert (line.end_a, line.end_b) == ("anchor", "fairlead")
    assert system.analyses == (StaticsSettings(method="newton"),)


def test_tuah_ex2_loads_in_us_units() -> None:
    system = load_case(CASES / "tuah_ex2.yaml")
    assert system.units == "US"
    env = system.environment
    assert math.isinf(env.depth) and not env.has_seabed
    assert env.water_density == 2.0
    assert env.gravity == pytest.approx(U.Quantity(1, "standard_gravity").to("ft/s**2").m, 1e-12)
    cable = system.line_types["cable"]
    assert cable.displaced_area == pytest.approx(0.0218, rel=1e-12)
    assert cable.mass_per_length == pytest.approx(3.35 * 0.0218, rel=1e-12)
    assert cable.EA == pytest.approx(8.12e6 * 0.0218, rel=1e-12)
    assert cable.diameter == pytest.approx(math.sqrt(4 * 0.0218 / math.pi), rel=1e-9)
    assert system.points["junction"].force == (0.0, 0.0, 900.0)
    assert system.points["B"].position == (1200.0, 0.0, 500.0)
    assert system.points["B"].initial_position == (1417.0, 0.0, 500.0)
    assert [line.length for line in system.lines.values()] == [500.0, 1000.0]
    assert sum(line.segments for line in system.lines.values()) == 6
    (statics,) = system.analyses
    assert (statics.method, statics.load_steps) == ("newton", 20)


# ---- units ------------------------------------------------------------------------------------


def test_length_string_converted_to_us() -> None:
    system = load_case_text(
        MINIMAL.format(units="US", depth='"100 ft"', diameter='"0.03048 m"', EA=5e8)
        .replace("length: 350", 'length: "106.68 m"')
    )
    assert system.lines["line1"].length == pytest.approx(350.0, rel=1e-12)
    assert system.line_types["chain"].diameter == pytest.approx(0.1, rel=1e-12)
    text = MINIMAL.format(units="US", depth=100, diameter=0.1, EA=5e8)
    system = load_case_text(text.replace("[0, 0, -10]", '["6.096 m", 0, -10]'))
    assert system.points["fairlead"].position[0] == pytest.approx(20.0, rel=1e-12)


def test_force_string_converted_to_si() -> None:
    system = _mini(EA='"384.243 MN"')
    assert system.line_types["chain"].EA == pytest.approx(384.243e6, rel=1e-12)


def test_pressure_units_psf_and_psi() -> None:
    assert to_system("1.0e7 psf", "pressure", "US") == pytest.approx(1.0e7, rel=1e-12)
    assert to_system("1.0e7 psf", "pressure", "SI") == pytest.approx(
        U.Quantity(1.0e7, "lbf/ft**2").to("Pa").m, rel=1e-12
    )
    assert to_system("1 psi", "pressure", "US") == pytest.approx(144.0, rel=1e-12)
    # a pressure times an area is a force: E*A written as the source prints it
    assert to_system("8.12e6 psf * 0.0218 ft**2", "force", "US") == pytest.approx(177016.0)


def test_seabed_stiffness_and_heading_strings() -> None:
    text = MINIMAL.format(units="US", depth=100, diameter=0.1, EA=5e8).replace(
        "{depth: 100}",
        '{depth: 100, seabed: {stiffness: "3.0e6 Pa/m"}, current: {speed: 1, heading: "0.5 rad"}}',
    )
    env = load_case_text(text).environment
    assert env.seabed.stiffness == pytest.approx(U.Quantity(3.0e6, "Pa/m").to("lbf/ft**3").m)
    assert env.current.heading_deg == pytest.approx(math.degrees(0.5), rel=1e-12)


def test_yaml_exponent_without_dot_is_a_number() -> None:
    # YAML 1.1 reads 1e-8 and 5.0e8 as strings; the reader accepts them as numbers
    text = MINIMAL.format(units="SI", depth=100, diameter=0.1, EA="5.0e8")
    system = load_case_text(text + "analyses:\n  - {kind: statics, tolerance: 1e-8}\n")
    assert system.analyses[0].tolerance == 1e-8
    assert system.line_types["chain"].EA == 5.0e8


def test_defaults_si() -> None:
    system = _mini()
    env = system.environment
    assert (env.water_density, env.gravity) == (1025.0, 9.80665)
    assert (env.seabed.stiffness, env.seabed.damping) == (3.0e6, 3.0e5)
    assert system.analyses == (StaticsSettings(),)
    assert system.output.every == 0.1


def test_defaults_us_are_the_si_defaults_converted() -> None:
    system = _mini(units="US")
    env = system.environment
    assert env.water_density == pytest.approx(U.Quantity(1025, "kg/m**3").to("slug/ft**3").m)
    assert env.water_density == pytest.approx(1.9888, abs=1e-4)
    assert env.gravity == pytest.approx(U.Quantity(9.80665, "m/s**2").to("ft/s**2").m)
    assert env.gravity == pytest.approx(32.174, abs=1e-3)
    assert env.seabed.stiffness == pytest.approx(U.Quantity(3e6, "Pa/m").to("lbf/ft**3").m)
    assert env.seabed.damping == pytest.approx(U.Quantity(3e5, "Pa*s/m").to("lbf*s/ft**3").m)
    (statics,) = system.analyses
    assert statics.damping == pytest.approx(U.Quantity(1e5, "N*s/m").to("lbf*s/ft").m)
    assert statics.pseudo_dt == 1.0 and system.output.every == 0.1


def test_depth_omitted_means_no_seabed() -> None:
    text = MINIMAL.format(units="SI", depth=100, diameter=0.1, EA=5e8)
    system = load_case_text(text.replace("environment: {depth: 100}\n", ""))
    assert math.isinf(system.environment.depth) and not system.environment.has_seabed


def test_schema_covers_every_model_field() -> None:
    """A field added to the model must get a case-file key too."""
    pairs = [(LineType, LineTypeSpec), (Point, PointSpec), (StaticsSettings, StaticsSpec)]
    for model, spec in pairs:
        names = {f.name for f in dataclasses.fields(model)} - {"name"}
        assert names <= set(spec.model_fields), (model.__name__, names - set(spec.model_fields))
    line_keys = {f.name for f in dataclasses.fields(Line)} - {"name", "line_type"} | {"type"}
    assert line_keys <= set(LineSpec.model_fields)


def test_slightly_short_pretensioned_line_is_accepted() -> None:
    text = MINIMAL.format(units="SI", depth=100, diameter=0.1, EA=5e8)
    span = math.dist((-300, 0, -100), (0, 0, -10))
    system = load_case_text(text.replace("length: 350", f"length: {0.99 * span}"))
    assert system.lines["line1"].length < span < system.lines["line1"].length * (1 + MAX_STRAIN)


# ---- bad input --------------------------------------------------------------------------------

# (file in tests/data/bad, expected dotted key path (None: no field), text the message contains)
BAD_CASES = [
    ("malformed_yaml", None, "malformed YAML at line 8, column"),
    ("top_level_list", None, "top level must be a mapping"),
    ("empty_file", None, "got an empty file"),
    ("duplicate_line", None, "duplicate key 'line1'"),
    ("missing_name", "name", "missing required key 'name'"),
    ("missing_lines", "lines", "missing required key 'lines'"),
    ("missing_diameter", "line_types.chain.diameter", "missing required key"),
    ("missing_line_end", "lines.line1.end_b", "missing required key"),
    ("missing_point_kind", "points.anchor.kind", "missing required key"),
    ("unknown_key_typo", "lines.line1.lenght", "did you mean 'length'?"),
    ("unknown_top_key", "enviroment", "did you mean 'environment'?"),
    ("unknown_statics_key", "analyses[0].methd", "did you mean 'method'?"),
    ("wrong_type_text", "line_types.chain.EA", "expected a number, got 'abc'"),
    ("wrong_type_name", "name", "expected a string"),
    ("negative_length", "lines.line1.length", "must be > 0, got -5"),
    ("zero_diameter", "line_types.chain.diameter", "must be > 0, got 0"),
    ("zero_EA", "line_types.chain.EA", "must be > 0"),
    ("negative_mass", "line_types.chain.mass_per_length", "must be > 0, got -50"),
    ("zero_segments", "lines.line1.segments", "must be a positive integer, got 0"),
    ("fractional_segments", "lines.line1.segments", "must be a positive integer, got 2.5"),
    ("negative_depth", "environment.depth", "must be > 0"),
    ("zero_water_density", "environment.water_density", "must be > 0"),
    ("negative_gravity", "environment.gravity", "must be >= 0"),
    ("negative_drag", "line_types.chain.Cd", "must be >= 0, got -1.2"),
    ("negative_seabed_stiffness", "environment.seabed.stiffness", "must be >= 0"),
    ("negative_EA1", "line_types.chain.EA1", "must be >= 0, got -1.0e8"),
    ("position_two_numbers", "points.anchor.position", "must be 3 numbers"),
    ("position_component_text", "points.anchor.position[2]", "expected a number, got 'deep'"),
    ("unknown_point_kind", "points.anchor.kind", "'fixed', 'free', 'prescribed' or 'body'"),
    ("unknown_line_type", "lines.line1.type", "known line types: chain"),
    ("unknown_end_point", "lines.line1.end_b", "known points: anchor, fairlead"),
    ("same_ends", "lines.line1.end_b", "both ends are the point 'anchor'"),
    ("anchor_below_seabed", "points.anchor.position[2]", "below the seabed"),
    ("prescribed_start_below_seabed", "points.fairlead.initial_position[2]", "below the seabed"),
    ("line_too_short", "lines.line1.length", "too short to span its ends"),
    ("unknown_units_system", "units", "unknown unit system 'metric'; allowed: SI, US"),
    ("viscoelastic_without_tau", "line_types.chain.tau", "viscoelastic material needs tau > 0"),
    ("initial_shape_rows", "lines.line1.initial_shape", "segments + 1 = 3 rows, got 2"),
    ("initial_shape_wrong_end", "lines.line1.initial_shape[2]", "must be at end_b 'fairlead'"),
    ("wrong_dimension", "lines.line1.length", "expected a length, got '350 kg' (a mass)"),
    ("unknown_unit", "lines.line1.length", "unknown unit 'blorps'"),
    ("unknown_analysis_kind", "analyses[0].kind", "allowed kinds: 'statics', 'dynamics'"),
    ("unknown_statics_method", "analyses[0].method", "got 'magic'"),
    ("unattached_free_point", "points.buoy", "not attached to any line"),
    ("initial_position_fixed", "points.anchor.initial_position", "only prescribed points"),
    ("airy_without_period", "environment.waves.period", "needs period > 0"),
    ("random_without_period", "environment.waves.period", "needs period > 0"),
    ("random_unknown_spectrum", "environment.waves.spectrum", "bretschneider"),
    ("random_gamma_below_one", "environment.waves.gamma", "must be >= 1"),
    ("random_record_length_zero", "environment.waves.record_length", "must be > 0"),
    ("stochastic_without_random_sea", "analyses[1].kind", "needs a random sea"),
    ("motion_period_below_two_steps", "points.fairlead.motion.period",
     "shorter than two time steps"),
    ("body_point_unknown_body", "points.fairlead.body", "unknown body 'hull'"),
    # non-finite and out-of-range numbers (MAX_MAGNITUDE, MIN_MAGNITUDE)
    ("nan_EA", "line_types.chain.EA", "expected a number, got nan"),
    ("inf_length", "lines.line1.length", "must be finite, got inf"),
    ("huge_mass", "line_types.chain.mass_per_length", "at most 1e+30 in magnitude"),
    ("denormal_EA", "line_types.chain.EA", "at least 1e-30 in magnitude"),
    ("tiny_period", "points.fairlead.motion.period", "at least 1e-30 in magnitude"),
    ("inf_in_inline_table", "points.fairlead.motion.values[1][0]", "must be finite, got inf"),
    ("empty_inline_table", "points.fairlead.motion.times", "needs >= 2 rows, got 0"),
    ("nan_in_motion_table", "points.fairlead.motion.file", "data row 2, column 2: must be a "
                                                           "number, got nan"),
    ("inf_in_motion_table", "points.fairlead.motion.file", "data row 2, column 2: must be "
                                                           "finite, got inf"),
    ("huge_in_motion_table", "points.fairlead.motion.file", "data row 2, column 4: must be at "
                                                            "most 1e+30"),
    ("nan_added_mass", "bodies.spar.added_mass", "entry [2][2] must be a number, got nan"),
    # sizes (moorline.io.limits)
    ("segments_1e30", "lines.line1.segments", "must be at most 1e+12 (MAX_COUNT), got 1e+30"),
    ("segments_1e7", "lines.line1.segments", "1e+07 segments are more than MAX_SEGMENTS"),
    ("random_record_length_huge", "environment.waves.record_length",
     "6e+08 components, more than MAX_WAVE_COMPONENTS"),
    ("random_n_frequencies_huge", "environment.waves.n_frequencies",
     "1e+09 components, more than MAX_WAVE_COMPONENTS"),
    ("stochastic_memory", "environment.waves.record_length", "more than MAX_MEMORY = 4 GiB"),
    ("stochastic_n_points_huge", "analyses[1].n_points", "10000000000 time points"),
    ("dynamics_duration_huge", "analyses[1].duration", "1e+09 output records"),
    ("harmonic_harmonics_huge", "analyses[1].harmonics", "10000 harmonics"),
    ("dynamics_dt_tiny", "analyses[1].dt", "1e+21 time steps, more than MAX_TIME_STEPS"),
    ("statics_iterations_huge", "analyses[0].max_iterations",
     "must be at most 1000000 (MAX_ITERATIONS)"),
    # degenerate geometry (moorline.io.topology)
    ("coincident_fixed_ends", "lines.line1", "both ends ('anchor', 'fairlead') are at the "
                                             "same place"),
    ("line_between_free_points", "points.anchor", "points 'anchor', 'fairlead' are held by "
                                                  "no fixed or prescribed point"),
    ("free_island", "points.b1", "points 'b1', 'b2' are held by no fixed"),
    # files, nesting, unit expressions
    ("devzero_motion_table", "points.fairlead.motion.file",
     "'/dev/zero': not a regular file (a character device)"),
    ("deep_nesting", None, "nested too deeply for the parser"),
    ("deep_nesting_200", "points" + ".a" * 32, "nested more than MAX_DEPTH = 32 levels"),
    ("unit_power_tower", "lines.line1.length", "'10**10**10 m': chained powers"),
    ("unit_nested_power", "lines.line1.length", "a power of an expression that holds a power"),
    ("depth_1e300", "environment.depth", "must be at most 1e+30 in magnitude"),
    ("negative_inertia", "bodies.spar.inertia[0]", "must be >= 0, got -1.0e9"),
    ("billion_laughs", None, "holds 4.9e+08 values once its aliases (*name) are expanded"),
    ("recursive_alias", "a" + "[1]" * 32, "nested more than MAX_DEPTH = 32 levels"),
]


@pytest.mark.parametrize(("name", "field", "fragment"), BAD_CASES, ids=[c[0] for c in BAD_CASES])
def test_bad_case_file(name: str, field: str | None, fragment: str) -> None:
    path = BAD / f"{name}.yaml"
    with pytest.raises(CaseError) as info:
        load_case(path)
    err = info.value
    message = str(err)
    assert "\n" not in message
    assert message.startswith(f"{path}: ")
    assert err.file == str(path)
    assert err.field == field
    if field is not None:
        assert f": {field}: " in message
    assert fragment in message


def test_every_bad_file_is_tested() -> None:
    on_disk = {p.stem for p in BAD.glob("*.yaml")}
    assert on_disk == {c[0] for c in BAD_CASES}


def test_missing_file_is_a_case_error() -> None:
    with pytest.raises(CaseError, match="cannot read the case file"):
        load_case(BAD / "does_not_exist.yaml")


def test_text_errors_name_the_given_file() -> None:
    with pytest.raises(CaseError) as info:
        _mini(diameter=-1)
    assert str(info.value) == "mini.yaml: line_types.chain.diameter: must be > 0, got -1"


def test_size_limits_match_the_solvers_counts() -> None:
    """The component count of the limit check is the random sea's own (a 3-hour JONSWAP sea
    to 6 omega_p: 6 x 10800 / 12 = 5400 components)."""
    from moorline.io.limits import wave_components
    from moorline.model import Waves

    waves = Waves(kind="random", height=6.0, period=12.0, record_length=10800.0)
    assert wave_components(waves) == 6 * 10800 // 12
    capped = Waves(kind="random", height=6.0, period=12.0, omega_max=1.0)
    assert wave_components(capped) == math.floor(1.0 * 1800.0 / (2 * math.pi))


@pytest.mark.parametrize("name", [p.stem for p in sorted(CASES.glob("*.yaml"))])
def test_example_cases_are_within_the_size_limits(name: str) -> None:
    path = CASES / f"{name}.yaml"
    if "bem:" in path.read_text(encoding="utf-8"):
        pytest.importorskip("capytaine", reason="the case computes a BEM database ([bem])")
    load_case(path)


MERGED = """
name: merged
environment: {depth: 100}
line_types:
  chain: &chain {diameter: 0.1, mass_per_length: 50, EA: 5.0e8, Cd: 1.2}
  heavy:
    <<: *chain
    mass_per_length: 80
points:
  anchor: {kind: fixed, position: [-300, 0, -100]}
  fairlead: {kind: prescribed, position: [0, 0, -10]}
lines:
  line1: {type: heavy, length: 350, segments: 10, end_a: anchor, end_b: fairlead}
"""


def test_yaml_merge_key_overrides_as_yaml_defines() -> None:
    """``<<: *base`` then one key overridden (https://yaml.org/type/merge.html): the
    mapping's own key wins, the others come from the base."""
    types = load_case_text(MERGED).line_types
    assert types["heavy"].mass_per_length == 80.0
    assert (types["heavy"].diameter, types["heavy"].EA, types["heavy"].Cd) == (0.1, 5.0e8, 1.2)
    assert types["chain"].mass_per_length == 50.0


def test_a_key_written_twice_beside_a_merge_key_is_still_a_duplicate() -> None:
    text = MERGED.replace("    mass_per_length: 80",
                          "    mass_per_length: 80\n    EA: 1\n    EA: 2")
    with pytest.raises(CaseError, match="duplicate key 'EA'"):
        load_case_text(text)
