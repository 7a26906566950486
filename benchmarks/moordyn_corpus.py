"""MoorDyn's own test inputs in both codes: which ones MoorDyn-C loads and initialises, which of those
cablefem solves in statics and runs without refusal, and how far each line's end tensions are from
MoorDyn-C's initial condition (issue 36's targets: >= 90 % solve and run; median end-tension
difference <= 2 %), the file's as given and the file relaxed.

    python -m benchmarks.moordyn_corpus FOLDER [--only NAME ...] [--timeout 300]

FOLDER is MoorDyn's ``tests/Mooring`` (a checkout of FloatingArrayDesign/MoorDyn; links
``Mooring -> .`` in it and in 3D_seafloor/, as benchmarks/moordyn_statics.py says). MoorDyn-C runs
each file in a process of its own from the file's folder (``Create``, ``Init`` with its coupled
objects where the file puts them, and a step of 1e-4 s, without which a file with ``TmaxIC 0`` has no
tensions yet; its output on file descriptor 1 discarded) and gives each line's tension at its end
nodes (``GetLineNodeTen``, nodes 0 and N) and its imbalance: the largest net force
(``GetLineNodeForce``, ``GetPointForce``, ``GetBodyForce``, ``GetRodForce``) on its interior nodes, on
the free points it shares with other lines and on the file's free bodies and rods, over its larger end
tension; a line is at equilibrium in MoorDyn-C (``eq``) below 1 % (``BALANCED``). Where a line of the
file as given is not, MoorDyn-C runs again on a copy of the file beside it with its initial-condition
solve relaxed (``RELAXED``: TmaxIC 300 s, dtIC 1 s, threshIC 1e-3 where the file asks for less;
``relaxed_copy``): the second reference. cablefem solves the file's statics (``cablefem static``) and
runs it for two steps (``cablefem run``: a refusal shows there). Both codes' tensions are read at the
same place: MoorDyn-C's end node reports its end segment's tension (``Line::getNodeTen``), which
carries all but half a segment's weight, so cablefem's is its statics' tension at the middles of
MoorDyn-C's end segments, s = L / 2N and L - L / 2N (``cablefem_outcome``; ``LineSampler``). A line's
difference is the larger of its two ends' |T_cablefem - T_MoorDyn| / T_MoorDyn, over the ends that
are no free ends (a free point of one line: MoorDyn-C's last segment carries half a lumped node's
weight there, cablefem's exact free end nothing) and where MoorDyn-C's tension is at least 1 N and 5 % of the line's larger end tension;
lines cablefem joins (``line1+2``, two line ends at a massless point) are left out, and lines whose
MoorDyn-C tensions are not finite are shown as ``nan`` and left out of the medians.
The two codes differ in how they reach the equilibrium (MoorDyn-C relaxes for up to TmaxIC, by
default with its stationary solver, or its dynamics with CdScaleIC where a file sets ICgenDynamic;
cablefem solves the statics to its tolerance) and in their discretisation (MoorDyn-C's lumped masses
at NumSegs; cablefem's elements).

Measured on MoorDyn v2.7.1's tests/Mooring (the moordyn 2.7 wheel; 2 shared cores; 17 min):

- MoorDyn-C loads, initialises and steps 38 of the 42 files (not: body_tests/pinnedBody.txt,
  riser/riser.txt and riser_ic2.txt, and time_schemes.txt's unexpanded ``@DT@`` template).
- cablefem solves and runs 37 of those 38 (97 %; the issue's target 90 %). The one that does not:
  polyester/visco.txt, a 1 m line between points 2 m apart (a strain of 100 %, refused as absurd).
  The free rod (RodHanging) and the free bodies carrying rods (BodiesAndRods, riser/riser_ic1.txt)
  run (``cablefem.loads.rod_body``); body_tests/rotatingBody.txt and local_euler/complex_system.txt
  run: a point of a free body where several lines meet was a junction too (tests/test_body_points.py).
- Median end-tension difference against MoorDyn-C's initial condition (target <= 2 %): over its
  lines at equilibrium, 0.10 % over 26 lines of the files as given and 0.02 % over 48 lines relaxed;
  over all lines, relaxed 0.16 % over 85 lines, as given 2.27 % over 66 lines. Over all lines of the
  files as given the target is not met: 40 of those 66 lines are not at equilibrium in MoorDyn-C
  (most in files with TmaxIC 0, whose initial condition is the file's layout after one step:
  tripod.txt, the free bodies and rods below, and wavekin_2, wavekin_3 and wavekin_7 at 2.27 %,
  2.27 %, 2.16 % as given, 0.02 %, 0.02 %, 0.11 % relaxed). The free-hanging lines of 3D_seafloor/
  and wavekin_4/hanging_lines.txt (20 lines, whose ends MoorDyn-C's TmaxIC 0 leaves below 1 N as
  given) agree to 0.00-0.10 % relaxed. Not at equilibrium in MoorDyn-C however relaxed: tripod.txt
  (its lines' imbalance 0.3-6 of their tension after 300 s), body_tests/bodyDrag.txt (relaxed,
  MoorDyn-C's stationary solve stops at once with the spring at 0.006 N), RodHanging,
  BodiesAndRods, riser_ic1 and complex_system (free rods and bodies: 10 % to 9e4 % relaxed),
  wave_surface.txt (0.00-0.34 % relaxed), viv.txt (0.17 %) and the Currents 5 files (time-varying
  currents: 0.04 % relaxed). The lines over 2 % at equilibrium in MoorDyn-C:

  | file | difference | why |
  |---|---|---|
  | BeamSimplySupported.txt | 5.05 % | MoorDyn-C's 19 segments: the axial tension in the beam is 6010 N in cablefem and 6330 N in MoorDyn-C; a pinned beam under its weight whose ends cannot move apart carries H = 6012.9 N (EI w'''' - H w'' = w with H = EA / 2L int w'^2 dx, solved to 1e-6) |
  | syrope/exp_wc, quadratic_wc | 89 %, 35 % | MoorDyn-C drops owc.dat's (0, 0) row and starts its working curves at the next row (below) |

  Differences of the file as given where MoorDyn-C is not at equilibrium: tripod.txt (TmaxIC 0:
  its eleven lines 13-138 %, the file's unrelaxed layout unbalanced at its free points),
  body_tests/bodyDrag.txt (154 %: TmaxIC 0, the free body 5 m above its anchor on a 4.5 m spring; run
  on, MoorDyn-C's body falls and settles where cablefem's statics hangs it, 10.77 m down at pitch
  -90 deg, to 1e-4 m, tests/test_body_dynamics.py), RodHanging.txt (67 %, 100 %: TmaxIC 0, line
  2's fairlead at 3.5e8 N; cablefem's 8.66e5 N is MoorPy's elastic catenary over cablefem's drop to
  3e-4, tests/test_rods.py; relaxed and run on, MoorDyn-C's rod settles 4.9 mm from cablefem's and
  sways at its period to 0.16 %, benchmarks/rod_hanging_parity.py), BodiesAndRods.dat (42 %, 61 %, 61 %: MoorDyn-C's initialisation stops
  where it starts, the body at z = -0.0012 m, its rods above the water; cablefem's statics float the
  1.03e7 N body on its rods at z = -8.46 m), riser_ic1 (85-99 % and 1.8e5 %) and
  local_euler/complex_system.txt (15-2185 %: its line 1, 7 m of nylon from a fixed point to a 29.5 kg
  free body that the other lines pull, is set by the body's place; MoorDyn-C's lines that bend are
  clamped to its zero-length rods' orientation, which it solves from their bending moments, where
  cablefem pins them). BeamCantilevered.txt has no end compared (its free end, and MoorDyn-C's
  clamped end segment at 0.04 N: a cantilever carries its weight in shear, not tension).

  SYROPE: MoorDyn-C skips the first three lines of a curve file and owc.dat has two header lines,
  so MoorDyn-C drops its (0, 0) row and starts its working curves at the first row it reads (eps_0 =
  2.07e-3 in ``Line::setWorkingCurve``), where cablefem starts them at (0, 0)
  (verification/axial_laws, "MoorDyn-C and owc.dat"). MoorDyn-C's numbers follow from that by hand
  to five digits: after Init 1.5378e5 N (exp_wc) and 3.2240e5 N (quadratic_wc); held at rest for
  4500 s it settles at 3.1241e5 N and 3.6727e5 N, its working curve's tension at the file's strain.
  The linear working curve with k1 >= 1 does not use eps_0: 0.00 %.
"""

import argparse
import contextlib
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

from benchmarks.moordyn_statics import input_files
from validation.moordyn.peer import silenced_stdout


#: the relaxed reference's options, where the file asks for less: MoorDyn-C's initial-condition solve
#: for up to 300 s, its convergence checked every 1 s (dtIC) to a relative change of 1e-3 (threshIC):
#: MoorDyn-C's own defaults for dtIC and threshIC (docs/inputs.rst), TmaxIC raised from its 120 s.
#: CdScaleIC stays the file's: MoorDyn-C's default solve (stationary) does not read it, and the files
#: that ask for its dynamic relaxation (ICgenDynamic 1) set their own
RELAXED = {"TmaxIC": (max, 300.0), "dtIC": (max, 1.0), "threshIC": (min, 1e-3)}
#: a line is at equilibrium in MoorDyn-C when the largest net force on its interior nodes, on the free
#: points it ends at and on the free bodies and rods of the file is below this fraction of its larger
#: end tension (the differences compared are percents; MoorDyn-C's own converged files leave 4e-4)
BALANCED = 1e-2
#: MoorDyn-C's names of the options in ``RELAXED`` (Options parsing in MoorDyn2.cpp)
_ALIASES = {"tmaxic": "TmaxIC", "ictmax": "TmaxIC", "dtic": "dtIC", "icdt": "dtIC", "threshic": "threshIC",
            "icthresh": "threshIC"}
_DEFAULTS = {"TmaxIC": 120.0, "dtIC": 1.0, "threshIC": 1e-3}


@contextlib.contextmanager
def relaxed_copy(path):
    """A copy of the MoorDyn file ``path`` in its folder (its other files found as the file names them)
    with the ``RELAXED`` options appended to its OPTIONS section (MoorDyn-C reads the last value of an
    option); it and the files MoorDyn-C writes beside it are removed afterwards. Its name ends in
    neither .txt nor .dat, so that ``input_files`` does not list it."""
    path = Path(path)
    rows = path.read_text(errors="replace").splitlines()
    start = next(i for i, row in enumerate(rows) if row.startswith("--") and "OPTIONS" in row.upper())
    end = next((i for i in range(start + 1, len(rows)) if "---" in rows[i]), len(rows))
    own = dict(_DEFAULTS)
    for row in rows[start + 1:end]:
        entries = row.split()
        if len(entries) >= 2 and entries[1].lower() in _ALIASES:
            try:
                own[_ALIASES[entries[1].lower()]] = float(entries[0])
            except ValueError:
                pass
    rows[end:end] = [f"{pick(own[name], value)!r} {name}" for name, (pick, value) in RELAXED.items()]
    stem = f".{path.stem}-relaxed-{os.getpid()}"  # the process that removes it
    copy = path.with_name(stem + ".mdin")
    copy.write_text("\n".join(rows) + "\n")
    try:
        yield copy
    finally:
        for written in path.parent.glob(stem + "*"):
            written.unlink()


def moordyn_tensions(path):
    """{line number: (tension at node 0, tension at node N, imbalance, (free end at node 0, at node N),
    segments N)} [N, N, -, -, -] after MoorDyn-C's Init of ``path``, its coupled objects where the file puts them; run
    from the file's folder. The imbalance is the largest net force on the line's interior nodes, the
    free points it ends at with other lines and the file's free bodies and rods (MoorDyn's API does not
    say which lines end on a body), over the line's larger end tension: 0 at an equilibrium. A free end
    is a free point that no other line shares."""
    import moordyn

    cwd = os.getcwd()
    try:
        with silenced_stdout():
            os.chdir(os.path.dirname(path))
            system = moordyn.Create(os.path.basename(path))
            x, free = [], [0.0]
            for i in range(1, moordyn.GetNumberBodies(system) + 1):
                body = moordyn.GetBody(system, i)
                kind = moordyn.GetBodyType(body)
                if kind == -1:
                    x += list(moordyn.GetBodyState(body)[0])
                elif kind == 2:
                    x += list(moordyn.GetBodyState(body)[0][:3])
            for i in range(1, moordyn.GetNumberRods(system) + 1):
                rod = moordyn.GetRod(system, i)
                kind = moordyn.GetRodType(rod)
                if kind in (-2, -1):
                    n = moordyn.GetRodN(rod)
                    a, b = np.array(moordyn.GetRodNodePos(rod, 0)), np.array(moordyn.GetRodNodePos(rod, n))
                    axis = (b - a) / max(np.linalg.norm(b - a), 1e-12)
                    x += list(a) + (list(axis) if kind == -2 else [])
            for i in range(1, moordyn.GetNumberPoints(system) + 1):
                point = moordyn.GetPoint(system, i)
                if moordyn.GetPointType(point) == -1:
                    x += list(moordyn.GetPointPos(point))
            if len(x) != moordyn.NCoupledDOF(system):
                raise RuntimeError(f"{len(x)} coupled positions for {moordyn.NCoupledDOF(system)} degrees of freedom")
            moordyn.Init(system, x, [0.0] * len(x))
            moordyn.Step(system, x, [0.0] * len(x), 0.0, 1e-4)  # with TmaxIC 0 its tensions are set by a step
            for i in range(1, moordyn.GetNumberBodies(system) + 1):
                body = moordyn.GetBody(system, i)
                if moordyn.GetBodyType(body) == moordyn.BODY_TYPE_FREE:
                    free.append(float(np.linalg.norm(moordyn.GetBodyForce(body)[:3])))
            for i in range(1, moordyn.GetNumberRods(system) + 1):
                rod = moordyn.GetRod(system, i)
                if moordyn.GetRodType(rod) == moordyn.ROD_TYPE_FREE:
                    free.append(float(np.linalg.norm(moordyn.GetRodForce(rod)[:3])))
            at_points, free_ends = {}, set()  # line id: the largest net force on a free point it ends at
            for i in range(1, moordyn.GetNumberPoints(system) + 1):
                point = moordyn.GetPoint(system, i)
                if moordyn.GetPointType(point) == moordyn.POINT_TYPE_FREE:
                    force = float(np.linalg.norm(moordyn.GetPointForce(point)))
                    count = moordyn.GetPointNAttached(point)
                    for k in range(count):
                        line, end = moordyn.GetPointAttached(point, k)
                        line_id = moordyn.GetLineID(line)
                        if count == 1:
                            free_ends.add((line_id, int(end)))
                        else:
                            at_points[line_id] = max(at_points.get(line_id, 0.0), force)
            out = {}
            for i in range(1, moordyn.GetNumberLines(system) + 1):
                line = moordyn.GetLine(system, i)
                n = moordyn.GetLineN(line)
                ends = [float(np.linalg.norm(moordyn.GetLineNodeTen(line, k))) for k in (0, n)]
                nodes = [float(np.linalg.norm(moordyn.GetLineNodeForce(line, k))) for k in range(1, n)]
                net = max(nodes + [at_points.get(moordyn.GetLineID(line), 0.0)] + free)  # a free end's own: 0
                line_id = moordyn.GetLineID(line)
                out[i] = ends + [net / max(ends) if max(ends) > 0.0 else float("inf"),
                                 [(line_id, e) in free_ends for e in (0, 1)], n]
            moordyn.Close(system)
    finally:
        os.chdir(cwd)
    return out


def cablefem_outcome(path, segments):
    """(outcome, {line name: (tension, tension)}): 'solved and ran', or why not. The tensions are
    where MoorDyn-C's node 0 and node N tensions are, the middles of its end segments (s = L / 2N
    and L - L / 2N for the N segments of line K in ``segments``: {K: N}); MoorDyn-C's end node
    reports its end segment's tension, which carries all but half a segment of the line's weight."""
    from cablefem.errors import ConvergenceError, InputError
    from cablefem.io import load_scene
    from cablefem.runs.results import LineSampler
    from cablefem.runs.run import run_scene
    from cablefem.statics.scene import numpy_statics, static_lines

    try:
        scene = load_scene(str(path))
        systems, results, _, _ = static_lines(numpy_statics(scene))
    except (InputError, ConvergenceError) as error:
        return f"statics: {str(error).replace(str(path) + ': ', '')[:100]}", {}
    tensions = {}
    for system, result in zip(systems, results):
        name = system.line.name
        if name.startswith("line") and name[4:].isdigit() and int(name[4:]) in segments:
            length = system.line.unstretched_length
            half = length / (2 * segments[int(name[4:])])
            tensions[name] = tuple(LineSampler(system, [half, length - half]).tension(result.X))
    with tempfile.TemporaryDirectory() as out:
        try:
            run_scene(scene, out, duration=2 * scene.solver.dt, dt=scene.solver.dt)
        except (InputError, ConvergenceError) as error:
            return f"run: {str(error).replace(str(path) + ': ', '')[:100]}", tensions
    return "solved and ran", tensions


def compare(theirs, ours):
    """Per line cablefem names ``lineK``: the larger relative difference of its ends that are no free
    ends and where MoorDyn-C's tension is 1 N or more and 5 % of the line's larger end tension or more
    (None: no such end; NaN: MoorDyn-C's tensions are not finite)."""
    out = {}
    for name, (anchor, fairlead) in ours.items():
        if not (name.startswith("line") and name[4:].isdigit()) or int(name[4:]) not in theirs:
            continue
        pair, free = theirs[int(name[4:])][:2], theirs[int(name[4:])][3]
        if not np.all(np.isfinite(pair)):
            out[name] = float("nan")
            continue
        ends = [abs(t - m) / m for t, m, loose in zip((anchor, fairlead), pair, free)
                if not loose and m >= max(1.0, 0.05 * max(pair))]
        out[name] = max(ends) if ends else None
    return out


def moordyn_child(path, timeout, relaxed=False):
    """MoorDyn-C's ``moordyn_tensions`` of ``path`` (relaxed: of its ``relaxed_copy``, made and removed
    here, so that a child killed at the timeout leaves nothing behind) in a process of its own (a file
    MoorDyn-C cannot read may abort it); None if it fails or takes over ``timeout`` [s]."""
    if relaxed:
        with relaxed_copy(path) as copy:
            return moordyn_child(copy, timeout)
    env = dict(os.environ, PYTHONBREAKPOINT="0")
    try:
        child = subprocess.run([sys.executable, "-m", "benchmarks.moordyn_corpus", ".", "--moordyn-one", str(path)],
                               capture_output=True, text=True, timeout=timeout, env=env,
                               cwd=Path(__file__).resolve().parents[1])
        theirs = json.loads(child.stderr.strip().splitlines()[-1]) if child.returncode == 0 else None
    except (subprocess.TimeoutExpired, ValueError, IndexError):
        return None
    return None if theirs is None else {int(k): v for k, v in theirs.items()}


def _percent(value):
    return "-" if value is None else "nan" if not np.isfinite(value) else f"{100 * value:.2f} %"


def _median(values):
    values = [v for v in values if v is not None and np.isfinite(v)]
    return (100 * float(np.median(values)) if values else float("nan")), len(values)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("folder", help="MoorDyn's tests/Mooring")
    parser.add_argument("--only", nargs="*", default=(), help="files whose path contains one of these")
    parser.add_argument("--timeout", type=float, default=300.0, help="MoorDyn-C's seconds per file and reference")
    parser.add_argument("--moordyn-one", help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.moordyn_one:  # the child process: MoorDyn-C's tensions as JSON on the last line of stderr
        print(json.dumps(moordyn_tensions(os.path.abspath(args.moordyn_one))), file=sys.stderr)
        return 0
    folder = Path(args.folder)
    files = [p for p in input_files(folder) if not args.only or any(o in str(p) for o in args.only)]
    loaded, both, given, given_balanced, relaxed, balanced = 0, 0, [], [], [], []
    print(f"{'file':<36} {'cablefem':<34} {'line':<8} {'as given':>10} {'eq':>3} {'relaxed':>10} {'eq':>3}")
    for path in files:
        name = str(path.relative_to(folder))
        theirs = moordyn_child(path, args.timeout)
        if theirs is None:
            print(f"{name:<36} MoorDyn-C does not load or initialise it", flush=True)
            continue
        loaded += 1
        # the relaxed reference where the file's own leaves a line out of balance (else the same)
        settled = theirs if all(v[2] < BALANCED for v in theirs.values()) else moordyn_child(path, args.timeout, True)
        outcome, ours = cablefem_outcome(path, {k: v[4] for k, v in theirs.items()})
        both += outcome == "solved and ran"
        lines = compare(theirs, ours)
        again = compare(settled, ours) if settled is not None else dict.fromkeys(lines)
        if not lines:
            print(f"{name:<36} {outcome[:34]:<34}", flush=True)
        for k, (line, difference) in enumerate(lines.items()):
            number = int(line[4:])
            at_rest = settled is not None and settled[number][2] < BALANCED
            given.append(difference)
            if theirs[number][2] < BALANCED:
                given_balanced.append(difference)
            relaxed.append(again[line])
            if at_rest:
                balanced.append(again[line])
            print(f"{name if k == 0 else '':<36} {outcome[:34] if k == 0 else '':<34} {line:<8} "
                  f"{_percent(difference):>10} {'yes' if theirs[number][2] < BALANCED else 'no':>3} "
                  f"{_percent(again[line]) if settled is not None else 'failed':>10} {'yes' if at_rest else 'no':>3}",
                  flush=True)
    print(f"\nMoorDyn-C loads and initialises {loaded} of {len(files)}; cablefem solves and runs {both} of them "
          f"({100 * both / max(loaded, 1):.0f} %)")
    for label, values in (("against MoorDyn-C's initial condition of the file as given", given),
                          ("against MoorDyn-C's initial condition of the file as given, its lines at equilibrium there",
                           given_balanced),
                          ("against MoorDyn-C relaxed (TmaxIC 300 s)", relaxed),
                          ("against MoorDyn-C relaxed, its lines at equilibrium there", balanced)):
        median, count = _median(values)
        print(f"median end-tension difference {label}: {median:.2f} % over {count} lines")


if __name__ == "__main__":
    sys.exit(main())
