"""Bad TOML scenes (issue 14): each is refused before any work with exit status 2 and one line
naming the file, the key and the reason, without a traceback (``bad_input.assert_one_line``)."""

import pytest

from bad_input import GRID_C, assert_refused, toml_case

LINE = 'segments = [{ type = "chain", length = 635.0, elements = 40 }]'
ANCHOR = "anchor = [-560.0, 0.0, -150.0]"
FAIRLEAD = "fairlead = [0.0, 0.0, 0.0]"
SEABED = 'kind = "horizontal"\ndepth = 150.0'
SOLVER = '[solver]\nintegrator = "bdf2"'
TYPE = "c = {diameter = 0.1, mass = 10.0, EA = 1e8}"


def motion(text):
    """Edits adding a [motion] table before [solver]."""
    return {"[solver]": f"[motion]\n{text}\n[solver]"}


def values(key, line, bad, reason, prefix):
    """Cases setting ``key = <bad>`` on ``line`` of the base scene, one per bad value."""
    old = line
    return [toml_case(f"{prefix}.{key}={value}", reason_of, {old: old.replace(old.split(" = ")[1], value, 1)})
            for value, reason_of in zip(bad, reason)]


SYNTAX = [
    toml_case("not-toml", "not valid TOML", text="name = \n"),
    toml_case("unclosed-table", "not valid TOML", text="[line_types.chain\n"),
    toml_case("duplicate-key", "not valid TOML", {'name = "corpus"': 'name = "corpus"\nname = "again"'}),
    toml_case("not-utf8", "not valid TOML", text=None, files={"scene.toml": b"name = \"\xff\xfe\"\n"}),
    toml_case("deep-nesting", "not valid TOML", text="x = " + "[" * 100000 + "]" * 100000 + "\n"),
    toml_case("empty", "missing required key", text=""),
    toml_case("unknown-top", "unknown key", {'name = "corpus"': 'name = "corpus"\ncolour = "red"'}),
    toml_case("typo-top", "did you mean 'seabed'", {"[seabed]": "[seabd]"}),
    toml_case("no-lines", "lines: missing required key", text=f"line_types = {{{TYPE}}}\nseabed = {{}}\n"),
    toml_case("lines-number", "lines: expected an array of tables",
              text=f"lines = 5\nline_types = {{{TYPE}}}\nseabed = {{}}\n"),
    toml_case("line-types-string", "expected a table", text='line_types = "chain"\nlines = [{}]\nseabed = {}\n'),
    toml_case("no-line-types", "must define at least one line type",
              text='line_types = {}\nlines = [{anchor = [0,0,-1], fairlead = [0,0,0], segments = []}]\n'
                   'seabed = {kind = "horizontal", depth = 10.0}\n'),
    toml_case("seabed-array", "seabed: expected a table", text=f"seabed = [1]\nline_types = {{{TYPE}}}\n"
              "lines = [{anchor = [-9.0, 0, -10], fairlead = [0, 0, 0], segments = [{type = 'c', length = 20.0, "
              "elements = 4}]}]\n"),
    toml_case("segments-empty", "must hold at least one entry", {LINE: "segments = []"}),
]

LINE_TYPE = [
    *values("diameter", "diameter = 0.3539", ["nan", "-0.3", "0.0", '"thick"', "true", "1e3", "inf"],
            ["must be finite", "must be > 0", "must be > 0", "expected a number", "expected a number",
             "beyond the sane limit of 10 m", "must be finite"], "line_types.chain"),
    *values("mass", "mass = 835.4", ["-835.4", "1e9", "[1.0]"],
            ["must be > 0", "beyond the sane limit", "expected a number"], "line_types.chain"),
    *values("EA", "EA = 3.15e9", ["1e308", "1e14", "-1.0", "0", "nan", "1.7976931348623157e308"],
            ["beyond the sane limit of 1e+13 N", "beyond the sane limit", "must be > 0", "must be > 0",
             "must be finite", "beyond the sane limit"], "line_types.chain"),
    *values("damping", "damping = 0.001", ["-1.0", "1e300"], ["must be >= 0", "beyond the sane limit"],
            "line_types.chain"),
    *values("Cd_normal", "Cd_normal = 2.5", ["1e5", "-2.5"], ["beyond the sane limit", "must be >= 0"],
            "line_types.chain"),
    toml_case("line-type-typo", "did you mean 'diameter'", {"diameter = 0.3539": "diamter = 0.3539"}),
    toml_case("line-type-missing-EA", "line_types.chain.EA: missing required key", {"EA = 3.15e9\n": ""}),
]

ENVIRONMENT = [
    *values("water_density", "water_density = 1025.0", ["1e300", "-1025.0"],
            ["beyond the sane limit", "must be >= 0"], "environment"),
    *values("gravity", "gravity = 9.81", ["1e10", "-9.81"], ["beyond the sane limit", "must be >= 0"],
            "environment"),
    toml_case("current-fast", "environment.current[0]: 10000 m/s is beyond the sane limit",
              {"current = [0.0, 0.0, 0.0]": "current = [1e4, 0.0, 0.0]"}),
    toml_case("current-two", "expected 3 numbers", {"current = [0.0, 0.0, 0.0]": "current = [0.0, 0.0]"}),
    toml_case("current-nan", "environment.current[1]: must be finite",
              {"current = [0.0, 0.0, 0.0]": "current = [0.0, nan, 0.0]"}),
]

LINES = [
    toml_case("elements-1e20", "expected a whole number", {"elements = 40 }": "elements = 1e20 }"}),
    toml_case("elements-1e8", "100000000 is beyond the sane limit of 1000000",
              {"elements = 40 }": "elements = 100000000 }"}),
    toml_case("elements-2e63", "beyond the sane limit", {"elements = 40 }": "elements = 9223372036854775807 }"}),
    toml_case("elements-total", "nodes in the scene",
              {"elements = 40 }": "elements = 600000 }", "order = 1": "order = 2"}),
    toml_case("elements-zero", "must be at least 1", {"elements = 40 }": "elements = 0 }"}),
    toml_case("elements-negative", "must be at least 1", {"elements = 40 }": "elements = -4 }"}),
    toml_case("order-zero", "lines[0].order: must be at least 1", {"order = 1": "order = 0"}),
    toml_case("order-1000", "lines[0].order: 1000 is beyond the sane limit of 20", {"order = 1": "order = 1000"}),
    toml_case("order-float", "expected a whole number", {"order = 1": "order = 1.5"}),
    toml_case("length-huge", "beyond the sane limit", {"length = 635.0": "length = 1e300"}),
    toml_case("length-negative", "must be > 0", {"length = 635.0": "length = -635.0"}),
    toml_case("unknown-type", "unknown line type 'chian'", {'type = "chain"': 'type = "chian"'}),
    toml_case("anchor-huge", "lines[0].anchor[0]", {ANCHOR: "anchor = [-1e300, 0.0, -150.0]"}),
    toml_case("fairlead-huge-x", "lines[0].fairlead[0]", {FAIRLEAD: "fairlead = [1e9, 0.0, 0.0]"}),
    toml_case("anchor-two", "expected 3 numbers", {ANCHOR: "anchor = [-560.0, 0.0]"}),
    toml_case("anchor-string", "no point 'origin' in [points]", {ANCHOR: 'anchor = "origin"'}),
    toml_case("anchor-inf", "must be finite", {ANCHOR: "anchor = [-560.0, 0.0, -inf]"}),
    toml_case("strain-at-rest", "absurd strain of 28.2 %", {ANCHOR: "anchor = [-800.0, 0.0, -150.0]"}),
    toml_case("duplicate-line", "duplicate line name 'line1'", {"[seabed]": '[[lines]]\nname = "line1"\n'
              'anchor = [-560.0, 1.0, -150.0]\nfairlead = [0.0, 1.0, 0.0]\n' + LINE + "\n[seabed]"}),
    toml_case("anchor-below-seabed", "the anchor lies 200 m below the seabed",
              {ANCHOR: "anchor = [-500.0, 0.0, -350.0]"}),
    toml_case("padeye-needs-soil", "needs a [soil] table", {ANCHOR: "anchor = [-500.0, 0.0, -155.0]"}),
    toml_case("fairlead-below-seabed", "lines[0].fairlead: the fairlead lies 50 m below the seabed",
              {ANCHOR: "anchor = [-400.0, 0.0, -150.0]", FAIRLEAD: "fairlead = [0.0, 0.0, -200.0]",
               "length = 635.0": "length = 450.0"}),
    toml_case("line-name-nul", "lines[0].name: must not hold control", {'name = "line1"': 'name = "a\\u0000b"'}),
    toml_case("line-name-newline", "lines[0].name: must not hold control", {'name = "line1"': 'name = "a\\nb"'}),
    toml_case("line-name-long", "lines[0].name: is 300 bytes long", {'name = "line1"': f'name = "{"x" * 300}"'}),
]

SEABED_CASES = [
    toml_case("depth-zero", "seabed.depth: must be > 0", {"depth = 150.0": "depth = 0.0"}),
    toml_case("depth-negative", "seabed.depth: must be > 0", {"depth = 150.0": "depth = -150.0"}),
    toml_case("depth-huge", "seabed.depth", {"depth = 150.0": "depth = 1e300"}),
    toml_case("kind-unknown", "valid: horizontal | plane | grid | mesh | points", {'kind = "horizontal"': 'kind = "flat"'}),
    toml_case("no-kind", "seabed.kind: missing required key", {'kind = "horizontal"\n': ""}),
    toml_case("plane-above-water", "seabed.point: the seabed is 50 m above the still water surface",
              {SEABED: 'kind = "plane"\npoint = [0.0, 0.0, 50.0]\nnormal = [0.0, 0.0, 1.0]',
               ANCHOR: "anchor = [-560.0, 0.0, 0.0]"}),
    toml_case("plane-normal-down", "must point up",
              {SEABED: 'kind = "plane"\npoint = [0.0, 0.0, -150.0]\nnormal = [0.0, 0.0, -1.0]'}),
    toml_case("plane-slope-90", "must be in [0, 90)",
              {SEABED: 'kind = "plane"\npoint = [0.0, 0.0, -150.0]\nslope_deg = 90.0'}),
    toml_case("plane-anchor-buried", "lines[0].anchor: the anchor lies",
              {SEABED: 'kind = "plane"\npoint = [0.0, 0.0, -100.0]\nnormal = [0.17364817766693033, 0.0, '
               '0.984807753012208]'}),
    toml_case("grid-level-above-water", "seabed.file: the seabed is 10 m above",
              {SEABED: 'kind = "grid"\nfile = "grid.txt"'}, files={"grid.txt": GRID_C.replace("-150", "10")}),
    toml_case("grid-anchor-buried", "lines[0].anchor: the anchor lies 100 m below the seabed",
              {SEABED: 'kind = "grid"\nfile = "grid.txt"'}, files={"grid.txt": GRID_C.replace("-150", "-50")}),
    toml_case("stiffness-huge", "seabed.stiffness", {"stiffness = 3.0e5": "stiffness = 1e300"}),
    toml_case("stiffness-zero", "seabed.stiffness: must be > 0", {"stiffness = 3.0e5": "stiffness = 0.0"}),
    toml_case("depth-with-normal", "does not apply to seabed kind 'horizontal'",
              {"depth = 150.0": "depth = 150.0\nnormal = [0.0, 0.0, 1.0]"}),
    toml_case("seabed-file-missing", "seabed.file: file not found", {SEABED: 'kind = "grid"\nfile = "nothere.txt"'}),
    toml_case("seabed-file-folder", "seabed.file: not a file", {SEABED: 'kind = "mesh"\nfile = "sub"'},
              files={"sub/x": ""}),
]

FRICTION_SOLVER = [
    toml_case("friction-model", "valid: none | isotropic | anisotropic", {'model = "isotropic"': 'model = "coulomb"'}),
    toml_case("mu-huge", "friction.mu", {"mu = 0.3": "mu = 1e9"}),
    toml_case("mu-negative", "friction.mu: must be >= 0", {"mu = 0.3": "mu = -0.3"}),
    toml_case("integrator", "valid: bdf2 | generalized-alpha", {'integrator = "bdf2"': 'integrator = "rk4"'}),
    toml_case("adaptive-string", "expected true or false", {'integrator = "bdf2"': 'adaptive = "yes"'}),
    toml_case("dt-zero", "solver.dt: must be > 0", {"dt = 0.01": "dt = 0.0"}),
    toml_case("dt-tiny", "solver.dt", {"dt = 0.01": "dt = 1e-300"}),
    toml_case("duration-huge", "solver.duration: 1e+300 s in steps", {"duration = 10.0": "duration = 1e300"}),
    toml_case("rho-inf", "solver.rho_inf: must be between 0 and 1", {'integrator = "bdf2"': "rho_inf = 2.0"}),
    toml_case("max-iterations", "solver.max_iterations", {'integrator = "bdf2"': "max_iterations = 1000000000"}),
    toml_case("newton", "valid: auto | full | modified", {'integrator = "bdf2"': 'newton = "quasi"'}),
    toml_case("every-zero", "output.every: must be > 0", {"every = 0.1": "every = 0.0"}),
    toml_case("frames", "output.every", {"every = 0.1": "every = 1e-9", 'integrator = "bdf2"': "adaptive = true"}),
    toml_case("output-dir-nul", "output.dir: must not hold control", {"every = 0.1": 'dir = "a\\u0000b"'}),
    toml_case("output-dir-empty", "output.dir: must not be empty", {"every = 0.1": 'dir = ""'}),
]

MOTION = [
    toml_case("motion-kind", "valid: fixed | harmonic | circular | table", motion('kind = "sway"')),
    toml_case("motion-no-kind", "motion.kind: missing required key", motion("period = 6.0")),
    toml_case("motion-no-period", "motion.period: missing required key",
              motion('kind = "harmonic"\namplitude = [5.0, 0.0, 0.0]')),
    toml_case("motion-radius-harmonic", "does not apply to motion kind 'harmonic'",
              motion('kind = "harmonic"\namplitude = [5.0, 0.0, 0.0]\nperiod = 6.0\nradius = 1.0')),
    toml_case("harmonic-strain-45", "motion.amplitude: moves the fairlead of line 'line1'",
              motion('kind = "harmonic"\namplitude = [250.0, 0.0, 0.0]\nperiod = 60.0')),
    toml_case("harmonic-offset-strain", "absurd strain", motion(
        'kind = "harmonic"\namplitude = [1.0, 0.0, 0.0]\noffset = [300.0, 0.0, 0.0]\nperiod = 60.0\nramp = 60.0')),
    toml_case("harmonic-amplitude-huge", "beyond the sane limit",
              motion('kind = "harmonic"\namplitude = [1e300, 0.0, 0.0]\nperiod = 6.0')),
    toml_case("harmonic-period-tiny", "motion.period: the fairlead's peak speed would reach",
              motion('kind = "harmonic"\namplitude = [1.0, 0.0, 0.0]\nperiod = 1e-300')),
    toml_case("harmonic-acceleration", "motion.period: the fairlead's peak acceleration",
              motion('kind = "harmonic"\namplitude = [1e-6, 0.0, 0.0]\nperiod = 1e-6')),
    toml_case("harmonic-ramp-tiny", "motion.ramp: the fairlead's peak",
              motion('kind = "harmonic"\namplitude = [1.0, 0.0, 0.0]\noffset = [5.0, 0.0, 0.0]\n'
                     'period = 6.0\nramp = 1e-6')),
    toml_case("circular-radius", "motion.radius: moves the fairlead",
              motion('kind = "circular"\nradius = 200.0\nperiod = 60.0\nplane = "xz"')),
    toml_case("circular-plane", "valid: xy | xz | yz", motion('kind = "circular"\nradius = 1.0\nperiod = 6.0\nplane = "ab"')),
    toml_case("circular-radius-negative", "motion.radius: must be > 0",
              motion('kind = "circular"\nradius = -1.0\nperiod = 6.0')),
    toml_case("period-negative", "motion.period: must be > 0",
              motion('kind = "harmonic"\namplitude = [1.0, 0.0, 0.0]\nperiod = -6.0')),
]

EA = "EA = 3.15e9"
DAMPING = "damping = 0.001"
CHAIN_SEGMENT = '{ type = "chain", length = 635.0, elements = 40 }'
OWC = "EA = { strain = [0.0, 0.01, 0.02, 0.04], tension = [0.0, 1e6, 2.2e6, 5e6] }"
SYROPE = OWC + "\nEA_dynamic = 1.5e8\nEA_dynamic_slope = 20.0\nBA = 5e10\nsyrope = { working_curve = \"linear\", k1 = 1.25e8, k2 = 0.0 }"
IC = '{ type = "chain", length = 635.0, elements = 40, syrope = { Tmax = 2e6, Tmean = 1e6 } }'


def law(name, reason, line_type, segment=None):
    """A case whose chain line type has ``line_type`` instead of EA and damping (its segment ``segment``)."""
    edits = {EA: line_type, DAMPING: ""}
    if segment is not None:
        edits[CHAIN_SEGMENT] = segment
    return toml_case(name, reason, edits)


AXIAL = [
    law("table-strain-not-increasing", "line_types.chain.EA.strain: not monotonic: strain must strictly increase",
        "EA = { strain = [0.0, 0.02, 0.01], tension = [0.0, 1e6, 2e6] }"),
    law("table-tension-falling", "line_types.chain.EA.tension: not monotonic: tension must strictly increase, but "
        "row 2 has 500000 after 1e+06", "EA = { strain = [0.0, 0.01, 0.02], tension = [0.0, 1e6, 5e5] }"),
    law("table-tension-flat", "not monotonic", "EA = { strain = [0.0, 0.01, 0.02], tension = [0.0, 1e6, 1e6] }"),
    law("table-one-row", "line_types.chain.EA: a table needs at least 2 rows, got 1",
        "EA = { strain = [0.01], tension = [1e6] }"),
    law("table-lengths", "3 strain values but 2 tension values", "EA = { strain = [0.0, 0.01, 0.02], tension = [0.0, 1e6] }"),
    law("table-negative-strain", "EA.strain: strain must be >= 0", "EA = { strain = [-0.01, 0.01], tension = [0.0, 1e6] }"),
    law("table-pull-at-zero", "EA.tension: the tension at zero strain must be 0",
        "EA = { strain = [0.0, 0.01], tension = [1e5, 1e6] }"),
    law("table-too-long", "at most 32 rows", "EA = { strain = [" + ", ".join(str(0.001 * i) for i in range(40))
        + "], tension = [" + ", ".join(str(1e5 * i) for i in range(40)) + "] }"),
    law("table-nan", "EA.tension[1]: must be finite", "EA = { strain = [0.0, 0.01], tension = [0.0, nan] }"),
    law("table-unknown-key", "line_types.chain.EA.stress: unknown key", "EA = { strain = [0.0, 0.01], stress = [0.0, 1e6] }"),
    law("ba-and-damping", "line_types.chain.BA: give the internal damping once", "EA = 3.15e9\nBA = 1e6\ndamping = 0.1"),
    law("ba-table-at-zero", "BA.tension: the tension at zero strain_rate must be 0",
        "EA = 3.15e9\nBA = { strain_rate = [-0.1, -0.05, 0.1], tension = [-1e4, 5e3, 2e4] }"),
    law("dynamic-below-static", "line_types.chain.EA_dynamic: the dynamic stiffness must exceed the static EA",
        "EA = 3.15e9\nEA_dynamic = 3.0e9\nBA = 1e9"),
    law("dynamic-slope-alone", "line_types.chain.EA_dynamic_slope: belongs to a viscoelastic rope",
        "EA = 3.15e9\nEA_dynamic_slope = 0.4"),
    law("viscoelastic-table", "a viscoelastic rope takes EA as its static stiffness, a number",
        OWC + "\nEA_dynamic = 1.5e8\nBA = 1e9"),
    law("viscoelastic-without-damper", "line_types.chain.BA: a viscoelastic rope needs BA > 0 or BA_dynamic > 0",
        "EA = 3.15e9\nEA_dynamic = 4e9"),
    law("syrope-without-table", "line_types.chain.EA: a SYROPE rope needs EA as its original working curve",
        "EA = 3.15e9\nEA_dynamic = 1.5e8\nBA = 5e10\nsyrope = { working_curve = \"linear\", k1 = 1.25e8, k2 = 0.0 }",
        IC),
    law("syrope-without-dynamic", "line_types.chain.EA_dynamic: a SYROPE rope needs EA_dynamic",
        OWC + "\nBA = 5e10\nsyrope = { working_curve = \"linear\", k1 = 1.25e8, k2 = 0.0 }", IC),
    law("syrope-form", "line_types.chain.syrope.working_curve: unknown value 'cubic'",
        SYROPE.replace('"linear"', '"cubic"'), IC),
    law("syrope-quadratic-k1", "line_types.chain.syrope.k1: a quadratic working curve needs 0 <= k1 < 1",
        SYROPE.replace('"linear"', '"quadratic"'), IC),
    law("syrope-without-ic", "lines[0].segments[0].syrope: line type 'chain' is a SYROPE rope: its segment needs its "
        "initial condition", SYROPE),
    law("syrope-tmax-beyond", "lines[0].segments[0].syrope.Tmax: Tmax = 9e+06 N is outside the original working curve",
        SYROPE, IC.replace("Tmax = 2e6", "Tmax = 9e6")),
    law("syrope-tmean-above", "lines[0].segments[0].syrope.Tmean: must lie in [0, Tmax = 2e+06] N",
        SYROPE, IC.replace("Tmean = 1e6", "Tmean = 3e6")),
    law("ic-not-syrope", "lines[0].segments[0].syrope: line type 'chain' is not a SYROPE rope", EA, IC),
    toml_case("force-on-fixed-point", "points.a.force: a force acts on a free point or a point of a free body",
              {"[[lines]]": '[points.a]\nkind = "fixed"\nposition = [-560.0, 0.0, -150.0]\nforce = [1.0, 0.0, 0.0]'
               "\n[[lines]]", "anchor = [-560.0, 0.0, -150.0]": 'anchor = "a"'}),
]

CASES = SYNTAX + LINE_TYPE + ENVIRONMENT + LINES + SEABED_CASES + FRICTION_SOLVER + MOTION + AXIAL


@pytest.mark.parametrize("case", CASES, ids=str)
def test_bad_toml_scene_is_refused_in_one_line(case, tmp_path, capsys):
    assert_refused(case, tmp_path, capsys)


def test_the_corpus_base_scene_is_valid(tmp_path):
    from cablefem.io import load_scene

    from bad_input import BASE_TOML

    (tmp_path / "scene.toml").write_text(BASE_TOML)
    scene = load_scene(tmp_path / "scene.toml")
    assert scene.name == "corpus" and scene.lines[0].segments[0].elements == 40
