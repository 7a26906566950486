"""Scenes from TOML and MoorDyn v2 files: examples, equivalences, conversions, and one clear error per bad input."""

import glob
import math
import os

import numpy as np
import pytest

from cablefem import InputError
from cablefem.io.moordyn_input import damping_time
from cablefem.model.builtin import default_scene
from cablefem.io import load_scene
from cablefem.io.moordyn_input import read_moordyn
from cablefem.model.builtin import flume_scene

EXAMPLES = os.path.join(os.path.dirname(__file__), "..", "examples")


def example(name):
    return os.path.join(EXAMPLES, name)


def assert_same_lines(first, second, rtol=1e-12, slack_laws=None):
    """Lines equal in name order, anchor/fairlead, segments, element counts, order and type properties;
    ``slack_laws``: the two sides' ``damping_when_slack`` where they are known to differ (a MoorDyn
    file's line types carry MoorDyn-C's law, a TOML's the default)."""
    assert len(first) == len(second)
    for a, b in zip(first, second):
        np.testing.assert_array_equal(a.anchor, b.anchor)
        np.testing.assert_array_equal(a.fairlead, b.fairlead)
        assert a.order == b.order
        assert [(s.length, s.elements) for s in a.segments] == [(s.length, s.elements) for s in b.segments]
        for sa, sb in zip(a.segments, b.segments):
            assert sa.type.name == sb.type.name
            for key in ("diameter", "mass", "EA", "damping", "Cd_normal", "Cd_tangential",
                        "Ca_normal", "Ca_tangential"):
                # rtol: the MoorDyn file stores BA = beta EA and CdAx = Cd_t / pi as decimals
                assert getattr(sa.type, key) == pytest.approx(getattr(sb.type, key), rel=rtol, abs=0.0), key
            laws = (sa.type.damping_when_slack, sb.type.damping_when_slack)
            assert laws == (slack_laws or (laws[1], laws[1])), "damping_when_slack"


# ---------------------------------------------------------------- examples

EXPECTED_EXAMPLES = {  # file: (lines, unstretched length [m] of the first, segments of the first)
    "flume_flat.toml": (1, 635.0, 1),
    "flume_flat.dat": (1, 635.0, 1),
    "flume_flat_moordyn.toml": (1, 635.0, 1),
    "flume_flat_table.toml": (1, 635.0, 1),
    "chain_polyester.dat": (1, 1500.0, 2),
    "oc4_semi.dat": (3, 835.5, 1),
    "oc4_semi.toml": (3, 835.5, 1),
}


SHIPPED = sorted(os.path.basename(p) for p in glob.glob(example("*.toml")) + glob.glob(example("*.dat")))


def test_the_examples_described_here_are_shipped():
    assert set(EXPECTED_EXAMPLES) <= set(SHIPPED)


@pytest.mark.parametrize("name", SHIPPED)
def test_example_loads_with_its_lines_anchor_first(name):
    scene = load_scene(example(name))
    assert scene.lines and scene.source == os.path.abspath(example(name))
    for line in scene.lines:
        assert scene.seabed.gap_only(line.anchor[None, :])[0] == pytest.approx(0.0, abs=1e-9)  # anchor on seabed
        assert line.chord_strain() < 0.0  # every example line is slack at rest
    if name in EXPECTED_EXAMPLES:
        n_lines, length, n_segments = EXPECTED_EXAMPLES[name]
        assert len(scene.lines) == n_lines
        assert scene.lines[0].unstretched_length == pytest.approx(length, rel=1e-15)
        assert len(scene.lines[0].segments) == n_segments


@pytest.mark.parametrize("built, name", [(default_scene, "flume_steep.toml"),
                                         (lambda: flume_scene("flat"), "flume_flat.toml")])
def test_built_in_scenes_equal_their_examples(built, name):
    built, loaded = built(), load_scene(example(name))
    assert_same_lines(built.lines, loaded.lines, rtol=0.0)
    for part in ("contact", "environment", "friction", "motion", "solver", "output"):
        assert getattr(built, part) == getattr(loaded, part), part
    assert built.seabed.describe() == loaded.seabed.describe()


def test_flat_flume_scene_is_table5_line_over_100m():
    scene = flume_scene("flat")
    line = scene.lines[0]
    chain = line.segments[0].type
    assert (chain.diameter, chain.mass, chain.EA, chain.damping) == (0.3539, 835.4, 3.15e9, 0.001)
    assert (chain.Cd_normal, chain.Cd_tangential, chain.Ca_normal) == (2.5, 0.5, 3.8)
    assert line.segments[0].elements == 40 and line.order == 1
    assert scene.seabed.depth == 100.0 and scene.contact.stiffness == 3.0e5
    assert (scene.friction.model, scene.friction.mu, scene.friction.v_threshold) == ("isotropic", 0.3, 0.01)


def test_toml_and_moordyn_files_of_the_flume_give_identical_lines():
    # the MoorDyn file as it meshes its line (P1 x NumSegs), not as cablefem's defaults mesh it
    toml, moordyn = load_scene(example("flume_flat.toml")), read_moordyn(example("flume_flat.dat"), defaults=False)
    assert_same_lines(toml.lines, moordyn.lines, slack_laws=(False, True))
    assert toml.environment == moordyn.environment
    assert moordyn.seabed.describe() == toml.seabed.describe()
    # cBot in the .dat is 2 sqrt(kBot m / d), the critical damping the TOML asks for
    chain = toml.lines[0].segments[0].type
    critical = 2.0 * math.sqrt(toml.contact.stiffness * chain.mass / chain.diameter)
    assert moordyn.contact.damping == pytest.approx(critical, rel=1e-12)
    assert moordyn.friction.v_threshold == pytest.approx(toml.friction.v_threshold, rel=1e-12)


def test_toml_wrapping_the_moordyn_file_rebuilds_the_default_scene():
    wrapped, built = load_scene(example("flume_flat_moordyn.toml")), flume_scene("flat")
    assert_same_lines(wrapped.lines, built.lines, slack_laws=(True, False))  # the file's line types
    assert wrapped.contact == built.contact  # damping_ratio written in the TOML overrides cBot
    assert (wrapped.motion, wrapped.solver, wrapped.environment) == (built.motion, built.solver, built.environment)
    assert wrapped.friction.v_threshold == pytest.approx(0.01, rel=1e-12)
    assert wrapped.friction.saturation_damping == pytest.approx(11439787.928722756)


def test_toml_keys_override_moordyn_values_one_by_one(tmp_path):
    (tmp_path / "mooring.dat").write_text(CHAIN_POLY)  # kBot 3e6, cBot 3e5, WtrDpth 850, no g
    (tmp_path / "s.toml").write_text('[moordyn]\nfile = "mooring.dat"\n[environment]\ngravity = 9.81\n'
                                     '[seabed]\nstiffness = 1.0e5\n[solver]\nduration = 30.0\n')
    scene = load_scene(tmp_path / "s.toml")
    assert (scene.environment.gravity, scene.environment.water_density) == (9.81, 1025.0)
    assert (scene.contact.stiffness, scene.contact.damping) == (1.0e5, 3.0e5)  # cBot kept
    assert scene.seabed.depth == 850.0 and scene.solver.duration == 30.0
    (tmp_path / "s.toml").write_text('[moordyn]\nfile = "mooring.dat"\n[seabed]\nkind = "horizontal"\n'
                                     'depth = 900.0\ndamping_ratio = 0.5\n')
    scene = load_scene(tmp_path / "s.toml")
    assert scene.seabed.depth == 900.0  # a TOML seabed kind replaces WtrDpth (850 m)
    assert (scene.contact.damping_ratio, scene.contact.damping) == (0.5, None)  # a written ratio beats cBot


def test_moordyn_wrapper_applies_element_order_and_count(tmp_path):
    (tmp_path / "s.toml").write_text(
        f'[moordyn]\nfile = "{os.path.abspath(example("chain_polyester.dat"))}"\norder = 2\nelements = 30\n')
    line = load_scene(tmp_path / "s.toml").lines[0]
    assert line.order == 2
    assert [s.elements for s in line.segments] == [10, 20]  # 30 spread by length 500 : 1000


# ------------------------------------------------------- MoorDyn mapping

with open(example("chain_polyester.dat")) as handle:
    CHAIN_POLY = handle.read()


def test_chain_and_polyester_merge_into_one_two_segment_line_anchor_first():
    line = read_moordyn(example("chain_polyester.dat"), defaults=False).lines[0]  # NumSegs per segment
    assert line.name == "line1+2"
    assert [(s.type.name, s.length, s.elements) for s in line.segments] == [
        ("chain", 500.0, 20), ("polyester", 1000.0, 40)]
    np.testing.assert_array_equal(line.anchor, [-1130.0, 0.0, -850.0])
    np.testing.assert_array_equal(line.fairlead, [-58.0, 0.0, -14.0])


def test_merged_line_does_not_depend_on_how_the_moordyn_lines_are_written(tmp_path):
    chain_row = "1     chain       1        2        500.0     20       -"
    poly_row = "2     polyester   3        2        1000.0    40       -"
    # both lines written fairlead-to-anchor, the polyester first
    rewritten = CHAIN_POLY.replace(chain_row + "\n" + poly_row,
                                   "2     polyester   2        3        1000.0    40       -\n"
                                   "1     chain       2        1        500.0     20       -")
    assert rewritten != CHAIN_POLY
    (tmp_path / "flipped.dat").write_text(rewritten)
    assert_same_lines(load_scene(tmp_path / "flipped.dat").lines, load_scene(example("chain_polyester.dat")).lines,
                      rtol=0.0)


def test_negative_ba_is_zeta_of_moordyn_segment_critical_damping():
    chain = load_scene(example("chain_polyester.dat")).lines[0].segments[0].type
    # MoorDyn: BA = zeta (UnstrLen / NumSegs) sqrt(EA m); beta = BA / EA
    assert chain.damping == pytest.approx(0.8 * (500.0 / 20) * math.sqrt(1.23e9 * 286.6) / 1.23e9, rel=1e-14)
    assert damping_time(3.15e6, 3.15e9, 835.4, 635.0, 40) == pytest.approx(0.001, rel=1e-15)


def test_cdax_times_pi_is_the_papers_tangential_drag_coefficient():
    chain = load_scene(example("chain_polyester.dat")).lines[0].segments[0].type
    assert chain.Cd_tangential == pytest.approx(math.pi * 0.4, rel=1e-15)


def test_moordyn_defaults_and_friction_mapping(tmp_path):
    text = CHAIN_POLY.replace("3.0e5     cBot", "3.0e5     cBot\n0.5   FrictionCoefficient\n1e6   FricDamp\n"
                              "1.5   StatDynFricScale\n25    dtIC")
    (tmp_path / "f.dat").write_text(text)
    scene = read_moordyn(str(tmp_path / "f.dat"), defaults=False)  # FricDamp scales with NumSegs
    friction, first = scene.friction, scene.lines[0].segments[0]
    # MoorDyn-C ramp mu FricDamp |v| reaches StatDynFricScale mu F_n (F_n: a resting node's weight)
    node_weight = first.type.submerged_weight(1025.0, 9.80665) * first.length / first.elements
    assert (friction.model, friction.mu, friction.static_scale) == ("isotropic", 0.5, 1.5)
    assert friction.v_threshold == pytest.approx(1.5 * node_weight / 1e6, rel=1e-14)
    assert friction.saturation_damping == 1e6
    assert scene.environment.gravity == 9.80665  # MoorDyn-C's default g, measured with the library
    assert any("dtIC" in note for note in scene.notes)  # ignored options are recorded, not dropped


def test_moordyn_file_is_detected_by_content_without_extension(tmp_path):
    (tmp_path / "mooring").write_text(CHAIN_POLY)
    assert load_scene(tmp_path / "mooring").lines[0].name == "line1+2"


# ------------------------------------------------------------ bad input

BASE_TOML = """\
name = "bad"
[environment]
water_density = 1025.0
gravity = 9.81
current = [0.0, 0.0, 0.0]
[line_types.chain]
diameter = 0.3539
mass = 835.4
EA = 3.15e9
damping = 0.001
[[lines]]
name = "line1"
anchor = [-560.0, 0.0, -150.0]
fairlead = [0.0, 0.0, 0.0]
segments = [{ type = "chain", length = 635.0, elements = 40 }]
[seabed]
kind = "horizontal"
depth = 150.0
[friction]
model = "isotropic"
[solver]
integrator = "bdf2"
"""

TWO_SEGMENTS = 'segments = [{ type = "chain", length = 640.0, elements = 40 }, ' \
               '{ type = "chain", length = -5, elements = 2 }]'

# (file name, {old: new} edits of BASE_TOML or full text, expected key, expected reason)
BAD_TOML = [
    ({"diameter = 0.3539": "diamter = 0.3539"}, "line_types.chain.diamter", "did you mean 'diameter'"),
    ({"elements = 40 }]": "elemnts = 40 }]"}, "lines[0].segments[0].elemnts", "did you mean 'elements'"),
    ({'name = "bad"': 'nmae = "bad"'}, "nmae", "did you mean 'name'"),
    ({"EA = 3.15e9\n": ""}, "line_types.chain.EA", "missing required key"),
    ({"anchor = [-560.0, 0.0, -150.0]\n": ""}, "lines[0].anchor", "missing required key"),
    ({'kind = "horizontal"\n': ""}, "seabed.kind", "missing required key"),
    ({"depth = 150.0\n": ""}, "seabed.depth", "missing required key"),
    ({"mass = 835.4": 'mass = "835.4"'}, "line_types.chain.mass", "expected a number, got a string"),
    ({"anchor = [-560.0, 0.0, -150.0]": "anchor = [-560.0, 0.0]"}, "lines[0].anchor", "expected 3 numbers"),
    ({"elements = 40 }]": "elements = 40.0 }]"}, "lines[0].segments[0].elements", "expected a whole number"),
    ({"EA = 3.15e9": "EA = nan"}, "line_types.chain.EA", "must be finite"),
    ({"anchor = [-560.0, 0.0, -150.0]": "anchor = [-560.0, 0.0, -inf]"}, "lines[0].anchor[2]", "must be finite"),
    ({"current = [0.0, 0.0, 0.0]": "current = [nan, 0.0, 0.0]"}, "environment.current[0]", "must be finite"),
    ({'segments = [{ type = "chain", length = 635.0, elements = 40 }]': TWO_SEGMENTS},
     "lines[0].segments[1].length", "must be > 0, got -5"),
    ({"diameter = 0.3539": "diameter = -0.3539"}, "line_types.chain.diameter", "must be > 0"),
    ({"mass = 835.4": "mass = -835.4"}, "line_types.chain.mass", "must be > 0"),
    ({"EA = 3.15e9": "EA = -3.15e9"}, "line_types.chain.EA", "must be > 0"),
    ({"gravity = 9.81": "gravity = -9.81"}, "environment.gravity", "must be >= 0"),
    ({"elements = 40 }]": "elements = 0 }]"}, "lines[0].segments[0].elements", "must be at least 1"),
    ({'type = "chain"': 'type = "chian"'}, "lines[0].segments[0].type", "unknown line type 'chian'"),
    ({'kind = "horizontal"': 'kind = "sloped"'}, "seabed.kind", "valid: horizontal | plane | grid | mesh | points"),
    ({'model = "isotropic"': 'model = "coulomb"'}, "friction.model", "valid: none | isotropic | anisotropic"),
    ({'integrator = "bdf2"': 'integrator = "rk4"'}, "solver.integrator", "valid: bdf2 | generalized-alpha"),
    ({"[solver]": '[motion]\nkind = "sway"\n[solver]'}, "motion.kind", "valid: fixed | harmonic | circular | table"),
    ({"[solver]": '[motion]\nkind = "harmonic"\namplitude = [5.0, 0.0, 0.0]\n[solver]'},
     "motion.period", "missing required key"),
    ({"[solver]": '[motion]\nkind = "harmonic"\nradius = 1.0\n[solver]'},
     "motion.radius", "does not apply to motion kind 'harmonic'"),
    ({"depth = 150.0": "depth = 150.0\nnormal = [0.0, 0.0, 1.0]"}, "seabed.normal",
     "does not apply to seabed kind 'horizontal'"),
    ({'kind = "horizontal"\ndepth = 150.0': 'kind = "grid"\nfile = "nothere.txt"'}, "seabed.file", "file not found"),
    ({'kind = "horizontal"\ndepth = 150.0': 'kind = "plane"\npoint = [0.0, 0.0, -150.0]\nnormal = [1.0, 0.0, 0.0]'},
     "seabed.normal", "must point up"),
    ({"[solver]": '[motion]\nkind = "table"\nfile = "missing.csv"\n[solver]'}, "motion.file", "file not found"),
    ({"[solver]": '[motion]\nkind = "table"\nfile = "backwards.csv"\n[solver]'}, "motion.file",
     "backwards.csv line 4: times must strictly increase (t = 0.5 after t = 1)"),
    ({"[solver]": '[motion]\nkind = "table"\nfile = "short.csv"\n[solver]'}, "motion.file",
     "short.csv line 1: expected 4 columns t, x, y, z, got 3"),
    ({"anchor = [-560.0, 0.0, -150.0]": "anchor = [-800.0, 0.0, -150.0]"}, "lines[0]",
     "would need an absurd strain of 28.2 % to reach its fairlead"),
    ('[moordyn]\nfile = "absent.dat"\n', "moordyn.file", "file not found"),
    ('[moordyn]\nfile = "ok.dat"\nordre = 2\n', "moordyn.ordre", "did you mean 'order'"),
    ('[moordyn]\nfile = "ok.dat"\n[seabed]\ndepth = 100.0\n', "seabed.depth", "needs seabed.kind"),
    ({"[[lines]]": '[moordyn]\nfile = "ok.dat"\n[[lines]]'}, "lines", "cannot be combined with [moordyn]"),
    ({'fairlead = [0.0, 0.0, 0.0]\n': 'fairlead = [0.0, 0.0, 0.0]\norder = 0\n'}, "lines[0].order",
     "must be at least 1"),
    ({"[seabed]": '[[lines]]\nname = "line1"\nanchor = [-560.0, 1.0, -150.0]\nfairlead = [0.0, 1.0, 0.0]\n'
      'segments = [{ type = "chain", length = 635.0, elements = 4 }]\n[seabed]'},
     "lines[1].name", "duplicate line name 'line1'"),
]


def write_side_files(folder):
    (folder / "backwards.csv").write_text("t,x,y,z\n0,0,0,0\n1,1,0,0\n0.5,2,0,0\n")
    (folder / "short.csv").write_text("0,0,0\n1,1,0,0\n")
    (folder / "ok.dat").write_text(CHAIN_POLY)


def assert_one_clear_line(error, path, key, reason):
    message = error.value.message()
    assert "\n" not in message
    assert message.startswith(str(path)), message
    assert f": {key}: " in message, message
    assert reason in message, message


@pytest.mark.parametrize("edits, key, reason", BAD_TOML, ids=[case[1] + ":" + case[2][:24] for case in BAD_TOML])
def test_bad_toml_gives_one_line_naming_file_key_and_reason(tmp_path, edits, key, reason):
    text = BASE_TOML if isinstance(edits, dict) else edits  # a str is the whole scene
    for old, new in (edits.items() if isinstance(edits, dict) else ()):
        assert old in text, old
        text = text.replace(old, new, 1)
    write_side_files(tmp_path)
    path = tmp_path / "scene.toml"
    path.write_text(text)
    with pytest.raises(InputError) as error:
        load_scene(path)
    assert_one_clear_line(error, path, key, reason)


def test_integrators_a_scene_may_name_are_those_dynamics_implements():
    from cablefem.dynamics.registry import INTEGRATORS as implemented
    from cablefem.dynamics.registry import INTEGRATORS as accepted

    assert set(accepted) == set(implemented)


def test_base_of_the_bad_toml_table_is_valid(tmp_path):
    (tmp_path / "scene.toml").write_text(BASE_TOML)
    assert load_scene(tmp_path / "scene.toml").lines[0].segments[0].type.damping == 0.001


BAD_MOORDYN = [
    ({"---------------------- LINES": "---------------------- RODS ------\nID RodType\n(#) (name)\n"
      "1 rod 0 0 0 1 1 1 10 -\n---------------------- LINES"}, "line 17: RODS",
     "expected 11 columns"),
    ({"---------------------- POINTS": "---------------------- BODIES ------\n1 free 0 0 0 0 0 0 1000 0 0 0 0 0"
      "\n---------------------- POINTS"}, "line 9: BODIES.1", "three moments of inertia > 0"),
    ({"---------------------- POINTS": "---------------------- BODIES ------\n1 free 0 0 0 0 0 0 1000 0 1e6 0 0 0"
      "\n---------------------- POINTS", "3      Coupled": "3      Body2  "}, "line 15: POINTS.3.Attachment",
     "no body 2 in BODIES (Body1)"),
    ({"---------------------- POINTS": "---------------------- BODIES ------\n1 floating 0 0 0 0 0 0 1 0 1 0 0 0"
      "\n---------------------- POINTS"}, "line 9: BODIES.1.Attachment", "unknown attachment 'floating'"),
    ({"---------------------- POINTS": "---------------------- BODIES ------\n1 free 0 0 0 0 0 0 1 1|2 1 0 0 0"
      "\n---------------------- POINTS"}, "line 9: BODIES.1.CG", "expected 1 or 3 numbers"),
    ({"-14.0    0      0        0     0\n": "-14.0    0      0        0     0\n4      Free   0 0 -10 0 0 0 0\n"},
     "line 14: POINTS.4",
     "no line uses this point"),
    ({"1.23e9": "-1.23e9"}, "line 6: LINE TYPES.chain.EA", "must be > 0"),
    ({"0.216 ": "nan   "}, "line 6: LINE TYPES.chain.Diam", "must be finite"),
    ({"1.23e9    -0.8 ": "1.23e9|5e8 -0.8 "}, "line 6: LINE TYPES.chain.EA",
     "the dynamic stiffness must exceed the static EA = 1.23e+09 N"),
    ({"1.23e9    -0.8 ": "1.2e9|1.3e9|0.4|9 -0.8 "}, "line 6: LINE TYPES.chain.EA",
     "at most 3 values separated by '|'"),
    ({"1.23e9    -0.8 ": "stiff.txt -0.8 "}, "line 6: LINE TYPES.chain.EA", "file not found"),
    ({"1        2        500.0     20": "1        2        -500.0    20"}, "line 17: LINES.1.UnstrLen", "must be > 0"),
    ({"1        2        500.0     20": "1        2        500.0     0 "}, "line 17: LINES.1.NumSegs", "at least 1"),
    ({"1     chain       1": "1     chian       1"}, "line 17: LINES.1.LineType", "unknown line type 'chian'"),
    ({"1     chain       1        2": "1     chain       1        7"}, "line 17: LINES.1.AttachB", "no point '7'"),
    ({"1     chain       1        2": "1     chain       R1A      2"}, "line 17: LINES.1.AttachA",
     "no rod 1 in RODS for 'R1A' (none defined)"),
    ({"1     chain       1        2": "1     chain       P1       Q2"}, "line 17: LINES.1.AttachB", "no point 'Q2'"),
    ({"3      Coupled": "3      Floating"}, "line 13: POINTS.3.Attachment", "unknown attachment 'Floating'"),
    ({"3      Coupled": "3      Body1  "}, "line 13: POINTS.3.Attachment", "no body 1 in BODIES (none defined)"),
    ({"3      Coupled": "3      Turbine1"}, "line 13: POINTS.3.Attachment", "FAST.Farm turbine"),
    ({"-14.0    0      0        0     0": "-14.0    0      0   nan 0 5e3  0     0"}, "line 13: POINTS.3.FX",
     "must be finite"),
    ({"850.0     WtrDpth": "850.0     WtrDpth\n4   WaveKin"}, "line 22: OPTIONS.WaveKin", "give the waves as [waves]"),
    ({"850.0     WtrDpth": "850.0     WtrDpth\n3   Currents"}, "line 22: OPTIONS.Currents",
     "node approach to currents (Currents 3 and 4, for which MoorDyn-C 2.7 builds no current): Currents 3 is not "
     "supported"),
    ({"850.0     WtrDpth": "850.0     WtrDpth\n2   Currents"}, "line 22: OPTIONS.Currents (current_profile_dynamic.txt)",
     "file not found"),
    ({"850.0     WtrDpth": "850.0     WtrDpth\n1   Currents"}, "line 22: OPTIONS.Currents (current_profile.txt)",
     "file not found"),
    ({"850.0     WtrDpth": "bathy.txt SeafloorFile"}, "line 21: OPTIONS.SeafloorFile", "file not found"),
    ({"850.0     WtrDpth\n": ""}, "OPTIONS.WtrDpth", "missing"),
    ({"3.0e6     kBot": "-3.0e6    kBot"}, "line 22: OPTIONS.kBot", "must be > 0"),
    ({"-1130.0": "-2000.0"}, "line 17: LINES.1+2", "would need an absurd strain of"),
    ({"1        2        500.0     20       -": "1        2        500.0"}, "line 17: LINES",
     "expected 6 columns"),
    ({"ID    LineType    AttachA  AttachB  UnstrLen  NumSegs  Outputs":
      "Line  LineType    UnstrLen NumSegs  NodeAnch  NodeFair Outputs"},
     "line 17: LINES.1.AttachA", "no point '500.0' in POINTS"),  # v1 columns: the v2 row's UnstrLen is NodeAnch
    ({"--------------------------- OUTPUTS": "--- CURRENT PROFILE ---\n0.0 0.5 0.0\n--- OUTPUTS"},
     "line 24: CURRENT PROFILE", "unrecognised section"),
]


@pytest.mark.parametrize("edits, key, reason", BAD_MOORDYN, ids=[case[1] + ":" + case[2][:24] for case in BAD_MOORDYN])
def test_bad_moordyn_file_gives_one_line_naming_file_key_and_reason(tmp_path, edits, key, reason):
    text = CHAIN_POLY
    for old, new in edits.items():
        assert old in text, old
        text = text.replace(old, new, 1)
    path = tmp_path / "mooring.dat"
    path.write_text(text)
    with pytest.raises(InputError) as error:
        load_scene(path)
    assert_one_clear_line(error, path, key, reason)


def test_bad_moordyn_file_behind_a_toml_is_reported_in_the_moordyn_file(tmp_path):
    (tmp_path / "mooring.dat").write_text(CHAIN_POLY.replace("1.23e9", "-1.23e9"))
    (tmp_path / "scene.toml").write_text('[moordyn]\nfile = "mooring.dat"\n')
    with pytest.raises(InputError) as error:
        load_scene(tmp_path / "scene.toml")
    assert_one_clear_line(error, tmp_path / "mooring.dat", "line 6: LINE TYPES.chain.EA", "must be > 0")


@pytest.mark.parametrize("name, text, reason", [
    ("absent.toml", None, "file not found"),
    ("broken.toml", "name = \n", "not valid TOML"),
    ("binary.dat", b"\xff\xfe\x00\x01", "not a MoorDyn input file"),
    ("empty.dat", "", "not a MoorDyn v2 input file"),
])
def test_unreadable_scene_file_gives_one_line_with_the_file(tmp_path, name, text, reason):
    path = tmp_path / name
    if isinstance(text, bytes):
        path.write_bytes(text)
    elif text is not None:
        path.write_text(text)
    with pytest.raises(InputError) as error:
        load_scene(path)
    message = error.value.message()
    assert "\n" not in message and message.startswith(str(path)) and reason in message, message


def test_grid_seabed_goes_through_read_seabed_or_says_it_is_not_available(tmp_path):
    (tmp_path / "bathy.txt").write_text("not a grid\n")
    text = BASE_TOML.replace('kind = "horizontal"\ndepth = 150.0', 'kind = "grid"\nfile = "bathy.txt"')
    (tmp_path / "scene.toml").write_text(text)
    with pytest.raises(InputError) as error:
        load_scene(tmp_path / "scene.toml")
    message = error.value.message()
    assert message.startswith(str(tmp_path / "scene.toml")), message
    assert (": seabed.kind: seabed kind 'grid' is not available yet" in message
            or (": seabed.file: " in message and "bathy.txt" in message)), message


def test_plane_seabed_from_slope_and_azimuth(tmp_path):
    text = BASE_TOML.replace('kind = "horizontal"\ndepth = 150.0',
                             'kind = "plane"\npoint = [-560.0, 0.0, -150.0]\nslope_deg = 4.0\nazimuth_deg = 0.0')
    (tmp_path / "scene.toml").write_text(text)
    seabed = load_scene(tmp_path / "scene.toml").seabed
    # rises towards +x by tan(4 deg) per metre
    assert seabed.elevation(np.array([[-460.0, 0.0]]))[0] == pytest.approx(-150.0 + 100 * math.tan(math.radians(4)))


# ------------------------------------- the conversions, checked against MoorDyn itself

PROBE = """\
--------------------- MoorDyn Input File ---------------------
cablefem conversion probe: 100 m, two coupled ends
----------------------- LINE TYPES ---------------------------
Name   Diam  MassDen  EA    BA/-zeta  EI  Cd   Ca   CdAx  CaAx
(-)    (m)   (kg/m)   (N)   (N-s/-)   (-) (-)  (-)  (-)   (-)
probe  0.1   100.0    {EA}  {BA}      0   0.0  0.0  {CdAx} 0.0
---------------------- POINTS ---------------------------------
ID  Attachment  X      Y    Z     M  V  CdA  CA
(-) (-)         (m)    (m)  (m)   (kg) (m^3) (m^2) (-)
1   Coupled     0.0    0.0  -50.0 0  0  0    0
2   Coupled     {X2}   0.0  -50.0 0  0  0    0
---------------------- LINES ----------------------------------
ID  LineType  AttachA  AttachB  UnstrLen  NumSegs  Outputs
(-) (-)       (-)      (-)      (m)       (-)      (-)
1   probe     1        2        100.0     10       -
---------------------- OPTIONS --------------------------------
0.0005  dtM
50.0    WtrDpth
{G}     g
0.5     FrictionCoefficient
1e6     FricDamp
1.0     StatDynFricScale
--------------------- need this line (MoorDyn 2.7 crashes on a file ending in OPTIONS) -------
"""


def run_moordyn_probe(folder, velocity, duration, *, EA="1e8", BA="0", CdAx="0.0", X2="100.0", G="9.81"):
    """Drive both ends of PROBE at ``velocity`` [m/s], (3,) or one row per end (2, 3), ramped in over a
    quarter of ``duration`` [s]; returns per node: velocity, drag, seabed force, tension (3,) each."""
    moordyn = pytest.importorskip("moordyn")
    path = folder / f"probe{len(list(folder.iterdir()))}.dat"
    path.write_text(PROBE.format(EA=EA, BA=BA, CdAx=CdAx, X2=X2, G=G))
    saved = os.dup(1)
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, 1)  # MoorDyn prints a line per step to fd 1
    try:
        system = moordyn.Create(str(path))
        x = np.array([0.0, 0.0, -50.0, float(X2), 0.0, -50.0])
        moordyn.Init_NoIC(system, x, np.zeros(6))
        t, dt = 0.0, 0.0005
        for _ in range(int(round(duration / dt))):
            v = np.broadcast_to(velocity, (2, 3)).ravel() * min(1.0, t / (0.25 * duration))
            x = x + v * dt
            moordyn.Step(system, x, v, t, dt)
            t += dt
        line = moordyn.GetLine(system, 1)
        nodes = [(np.array(moordyn.GetLineNodeVel(line, i)), np.array(moordyn.GetLineNodeDrag(line, i)),
                  np.array(moordyn.GetLineNodeSeabedForce(line, i)), np.array(moordyn.GetLineNodeTen(line, i)))
                 for i in range(11)]
        moordyn.Close(system)
    finally:
        os.dup2(saved, 1)
        os.close(saved)
        os.close(devnull)
    return nodes


def test_moordyn_negative_ba_damps_exactly_as_our_beta(tmp_path):
    # a line stretched at a constant rate (ends pulled apart), g = 0: tension = EA e + BA de/dt
    ea, zeta = 1e6, 0.5
    ba = damping_time(-zeta, ea, 100.0, 100.0, 10) * ea  # back to MoorDyn's N s
    common = dict(EA="1e6", G="0", X2="100.0")
    stretched = [run_moordyn_probe(tmp_path, [(-0.05, 0.0, 0.0), (0.05, 0.0, 0.0)], 2.0, BA=b, **common)[5][3]
                 for b in (f"{-zeta}", repr(ba), "0")]
    assert np.linalg.norm(stretched[0]) == pytest.approx(np.linalg.norm(stretched[1]), rel=1e-12)
    assert np.linalg.norm(stretched[0]) != pytest.approx(np.linalg.norm(stretched[2]), rel=1e-6)


def test_moordyn_axial_drag_is_pi_cdax_on_the_papers_reference_area(tmp_path):
    nodes = run_moordyn_probe(tmp_path, (1.0, 0.0, 0.0), 1.0, EA="1e9", BA="-1.0", CdAx="1.0", G="0")
    cd_tangential = math.pi * 1.0  # our conversion
    for velocity, drag, _, _ in nodes[1:-1]:
        # desire2023 Eq. 3 per unit length times the 10 m a node stands for; BA damps the axial ringing
        # so the nodes move steadily (rel 1e-6); a d-area convention would be off by a factor pi
        expected = -0.5 * cd_tangential * 0.1 * 1025.0 * abs(velocity[0]) * velocity[0] * 10.0
        assert drag[0] == pytest.approx(expected, rel=1e-6)


@pytest.mark.parametrize("direction", [(0.004, 0.0, 0.0), (0.0, 0.004, 0.0)], ids=["axial", "transverse"])
def test_moordyn_c_friction_is_isotropic_saturated_damping(tmp_path, direction):
    # a line pretensioned to 2 % on the seabed, dragged along or across itself, with mu = 0.5, FricDamp = 1e6
    nodes = run_moordyn_probe(tmp_path, direction, 2.0, X2="102.0", BA="-1.0")
    axis = int(np.argmax(direction))
    moving = [(v, f) for v, _, f, _ in nodes[1:-1] if abs(v[axis]) > 1e-5]
    assert len(moving) >= 2
    for velocity, seabed in moving:
        # below saturation F = -mu FricDamp v along either direction; rel 1e-3: sideways the nodes still
        # accelerate, and MoorDyn reports the force of its last RK2 stage with the velocity at the step end
        assert seabed[axis] == pytest.approx(-0.5 * 1e6 * velocity[axis], rel=1e-3)
    fast = run_moordyn_probe(tmp_path, (0.1, 0.0, 0.0), 1.0, X2="100.5")
    for _, _, seabed, _ in fast[2:-2]:
        assert abs(seabed[0]) == pytest.approx(0.5 * seabed[2], rel=1e-9)  # saturated at mu |F_n|


def test_moordyn_seafloor_file_becomes_a_grid_seabed(tmp_path):
    try:
        from cablefem.geometry import read_seabed  # noqa: F401
    except ImportError:
        pytest.importorskip("cablefem.geometry.readers")
    rows = ["3 2", "-1200 -600 0", "-100 100"]  # MoorDyn-C layout: nx ny, x ticks, y ticks, x y z rows
    rows += [f"{x} {y} {-850 + 0.05 * x}" for y in (-100, 100) for x in (-1200, -600, 0)]
    (tmp_path / "bathy.txt").write_text("\n".join(rows) + "\n")
    (tmp_path / "m.dat").write_text(CHAIN_POLY.replace("850.0     WtrDpth", "bathy.txt SeafloorFile"))
    seabed = load_scene(tmp_path / "m.dat").seabed
    # the grid's elevation, not WtrDpth (there is none): z = -850 + 0.05 x, exact at the nodes
    assert seabed.elevation(np.array([[-1200.0, 0.0], [0.0, 0.0]])) == pytest.approx([-910.0, -850.0], abs=1e-9)
