"""The ``cablefem`` command (docs/outputs.md: its commands, flags and the fields it writes).

User errors (bad scene, unreadable file, an output folder that cannot be
written) print one line naming the file, the key and the reason and exit with
status 2; a solver that does not converge prints its residual and exits with
status 3. Output files are written whole or not at all. Ctrl-C (SIGINT) and
SIGTERM stop a run the same way, leaving its outputs closed and a summary
saying "interrupted"; the exit status is then 130 or 143 (128 + the signal).
"""

import argparse
import os
import signal
import sys
import time
import traceback

from cablefem.errors import ConvergenceError, InputError


def _load(path):
    from cablefem.io import load_scene
    from cablefem.model.builtin import default_scene

    return default_scene() if path is None else load_scene(path)


def cmd_static(args):
    """``cablefem static [SCENE] [--json FILE]``."""
    from cablefem.io.output import prepare_file, write_json
    from cablefem.runs.static import network_json
    from cablefem.statics.scene import numpy_statics, static_network, warm_imports

    scene = numpy_statics(_load(args.scene))
    if args.json:
        prepare_file(args.json)  # before the work: a --json that cannot be written fails now
    warm_imports()  # start-up, not the solve (docs/outputs.md, wall_time_s)
    start = time.perf_counter()
    reports, iterations, results, network = static_network(scene)
    wall = time.perf_counter() - start
    print(f"scene {scene.name}: seabed {scene.seabed.describe()}")
    for note in scene.notes:
        print(f"  note: {note}")
    print(f"{'line':<12} {'fairlead T [N]':>15} {'anchor T [N]':>15} {'touchdown s [m]':>16} "
          f"{'iters':>6} {'residual':>9} {'step/L':>9}  strategy")
    for rep, res in zip(reports, results):
        td = "-" if rep.touchdown_s is None else f"{rep.touchdown_s:.3f}"
        print(f"{rep.name:<12} {rep.fairlead_tension:15.6e} {rep.anchor_tension:15.6e} {td:>16} "
              f"{res.iterations:6d} {res.residual:9.2e} {res.increment:9.2e}  {res.strategy}")
    fields = network_json(scene, reports, network) if scene.points or scene.bodies else {}
    for name, body in fields.get("bodies", {}).items():
        pose = body["position"] + body["rotation_deg"]
        print(f"body {name} ({body['kind']}): pose " + " ".join(f"{x:.6g}" for x in pose) + " [m, deg]; force "
              + " ".join(f"{x:.6e}" for x in body["force"]) + " [N]; moment "
              + " ".join(f"{x:.6e}" for x in body["moment"]) + " [N m]")
    if network is not None:
        print(f"network: {len(network.history) - 1} outer Newton iterations ({network.outer}) on its junctions and "
              f"free bodies, balance residual {network.residual:.2e} (its strings' iterations are in their rows)")
    for rep, res in zip(reports, results):
        if rep.soil is not None:
            mudline = rep.soil["mudline_tension"]
            print(f"{rep.name:<12} padeye T {rep.soil['padeye_tension']:.6e} N, mudline T "
                  f"{'-' if mudline is None else f'{mudline:.6e} N'}, embedded {rep.soil['embedded_length']:.3f} m")
    print(f"{iterations} Newton iterations in {wall:.3f} s")
    if args.json:
        write_json(args.json, {**fields,
            "lines": [rep.as_dict() for rep in reports],
            "newton_iterations": iterations,
            "wall_time_s": wall,
            "scene": scene.name,
            "seabed": scene.seabed.describe(),
            "notes": list(scene.notes),
            "residuals": [res.residual for res in results],
            "scale_free_residuals": [res.increment for res in results],
            "strategies": [res.strategy for res in results],
            "line_iterations": [res.iterations for res in results],
            "network_iterations": None if network is None else len(network.history) - 1,
        })
        print(f"wrote {args.json}")


def cmd_run(args):
    """``cablefem run [SCENE] [--out DIR] [--duration T] [--dt DT]``."""
    from cablefem.io.checks import check_run
    from cablefem.io.output import prepare_folder
    from cablefem.runs.run import run_scene, setting_warnings

    scene = _load(args.scene)
    for value, key in ((args.duration, "--duration"), (args.dt, "--dt")):
        if value is not None and not (value > 0 and value < float("inf")):
            raise InputError(f"must be a number > 0, got {value}", key=key)
    check_run(scene, args.duration, args.dt)
    out = args.out or scene.output.dir
    prepare_folder(out)
    print(f"scene {scene.name}: seabed {scene.seabed.describe()}; writing to {out}")
    for note in scene.notes:
        print(f"  note: {note}")
    for warning in setting_warnings(scene, args.dt):
        print(f"cablefem: warning: {warning}", file=sys.stderr)
    summary = run_scene(scene, out, duration=args.duration, dt=args.dt)
    for name, extremes in summary["tension_extremes"].items():
        print(f"{name}: fairlead tension {extremes['fairlead_tension_min']:.4e} .. "
              f"{extremes['fairlead_tension_max']:.4e} N")
    for failure in summary.get("failures", ()):
        when = "did not let go" if failure["released_at"] is None else \
            f"let go at {failure['released_at']:.6g} s, its tension {failure['tension_at_release']:.4e} N"
        print(f"{failure['line']}: {failure['end']} {when}")
    print(f"{summary['steps']} steps, {summary['newton_iterations']} Newton iterations, "
          f"{summary['simulated_time_s']:.3f} s simulated in {summary['wall_time_s']:.2f} s")


def cmd_sweep(args):
    """``cablefem sweep SWEEP.toml [--scheduler ADDRESS] [--workers N] [--out DIR] [--retry-failed]``."""
    from cablefem.sweeps import read_sweep, run
    from cablefem.sweeps.engine import check_cluster_options

    check_cluster_options(args.scheduler, args.workers)
    spec = read_sweep(args.sweep)
    out = args.out or spec.out
    where = args.scheduler or f"a local cluster of {args.workers or os.cpu_count()} worker processes"
    print(f"sweep {args.sweep}: {len(spec.cases)} cases of {spec.base}; writing to {out}; on {where}")
    table = run(spec, out=out, scheduler=args.scheduler, workers=args.workers, retry_failed=args.retry_failed)
    facts = table.attrs["sweep"]
    for row in table[table["status"] != "ok"].itertuples():
        print(f"  case {row.case} {row.status}: {row.error}")
    print(f"{facts['ran']} ran, {facts['skipped']} done before, {facts['failed']} failed, {facts['lost']} lost, "
          f"{facts['wall_time_s']:.1f} s; wrote {', '.join(facts['tables'])}")


def cmd_plot(args):
    """``cablefem plot OUT [--png FILE] [--elevation] [--y STAT --x KEY --by KEY]``: a run, or a sweep's table."""
    from cablefem.io.output import prepare_file

    if args.png:
        prepare_file(args.png)
    if os.path.isfile(os.path.join(args.out, "sweep.parquet")) or args.out.endswith((".parquet", ".csv")):
        from cablefem.sweeps.plot import plot_sweep

        path = plot_sweep(args.out, args.png, y=args.y, x=args.x, by=args.by)
    else:
        from cablefem.post import plot_tensions

        path = plot_tensions(args.out, args.png, elevation=args.elevation)
    print(f"wrote {path}")


def cmd_render(args):
    """``cablefem render OUT [--frame K ... | --every N] [--animation FILE] [--png-dir DIR] [--scalars NAME]
    [--clim LO HI] [--camera VIEW] [--size W H] [--fps N]``: pictures of a run's frames."""
    from cablefem.post import render_run

    frames = args.frame
    if args.every is not None:
        if args.every < 1 or frames:
            raise InputError("--every takes a whole number >= 1, and not with --frame", key="--every")
        from cablefem.io.vtk import read_collection
        from cablefem.post import collection

        frames = list(range(0, len(read_collection(collection(args.out))[0]), args.every))
    paths = render_run(args.out, frames=frames, png_dir=args.png_dir, animation=args.animation,
                       scalars=args.scalars, clim=args.clim, camera=args.camera, size=args.size, fps=args.fps)
    where = paths[0] if len(paths) == 1 else f"{len(paths)} pictures to {os.path.dirname(paths[0]) or '.'}"
    print(f"wrote {where}")


def build_parser():
    """The argument parser of the ``cablefem`` command."""
    from cablefem import __version__

    parser = _Parser(prog="cablefem", description=__doc__.splitlines()[0])
    parser.add_argument("--version", action="version", version=f"cablefem {__version__}")
    commands = parser.add_subparsers(dest="command", required=True)
    static = commands.add_parser("static", help="static equilibrium of a scene")
    static.add_argument("scene", nargs="?", help="TOML scene or MoorDyn v2 input file (default: built-in scene)")
    static.add_argument("--json", metavar="FILE", help="write the results as JSON")
    static.set_defaults(func=cmd_static)
    run = commands.add_parser("run", help="time-domain simulation of a scene")
    run.add_argument("scene", nargs="?", help="TOML scene or MoorDyn v2 input file (default: built-in scene)")
    run.add_argument("--out", metavar="DIR", help="output folder (default: the scene's [output] dir)")
    run.add_argument("--duration", type=float, metavar="T", help="simulated time [s]")
    run.add_argument("--dt", type=float, metavar="DT", help="time step [s]")
    run.set_defaults(func=cmd_run)
    plot = commands.add_parser("plot", help="tension against time of a run, or a statistic of a sweep")
    plot.add_argument("out", metavar="OUT", help="output folder of a run or of a sweep (or a sweep's table)")
    plot.add_argument("--png", metavar="FILE", help="image to write (default: OUT/tensions.png, OUT/sweep.png)")
    plot.add_argument("--elevation", action="store_true", help="a run in waves: the elevation at the origin "
                      "above the tensions")
    plot.add_argument("--y", metavar="STAT", help="sweep: the column to draw (default: the first line's "
                      "fairlead_tension_max, or fairlead_tension for static cases)")
    plot.add_argument("--x", metavar="KEY", help="sweep: the parameter along x (default: the first varied one)")
    plot.add_argument("--by", metavar="KEY", help="sweep: one curve per value of this parameter "
                      "(default: the second varied one)")
    plot.set_defaults(func=cmd_plot)
    render = commands.add_parser("render", help="pictures of a run's frames: PNGs or an animation")
    render.add_argument("out", metavar="OUT", help="output folder of a run")
    render.add_argument("--frame", type=int, action="append", metavar="K",
                        help="only frame K (repeat for more; negative from the end; default: every frame)")
    render.add_argument("--every", type=int, metavar="N", help="every N-th frame (0, N, 2N, ...)")
    render.add_argument("--animation", metavar="FILE", help="one animation instead of PNGs: .gif "
                        "(or .mp4 with imageio-ffmpeg installed)")
    render.add_argument("--png-dir", metavar="DIR", help="folder of the PNGs (default: OUT)")
    render.add_argument("--scalars", default="tension", metavar="NAME", help="the frames' array that colours "
                        "the line (default: tension; docs/outputs.md lists them)")
    render.add_argument("--clim", type=float, nargs=2, metavar=("LO", "HI"), help="colour range in the array's "
                        "SI unit (default: its range over the whole run)")
    render.add_argument("--camera", default="side", choices=("side", "top", "iso"), help="view (default: side)")
    render.add_argument("--size", type=int, nargs=2, metavar=("W", "H"), help="picture size in pixels "
                        "(default: 1600 wide, as tall as the scene needs)")
    render.add_argument("--fps", type=float, default=10.0, help="animation: frames a second (default 10)")
    render.set_defaults(func=cmd_render)
    sweep = commands.add_parser("sweep", help="many runs of a scene on Dask (docs/sweep.md)")
    sweep.add_argument("sweep", metavar="SWEEP", help="sweep file (TOML): base scene, axes, run kind")
    sweep.add_argument("--scheduler", metavar="ADDRESS", help="an existing Dask cluster's scheduler, "
                       "e.g. tcp://host:8786 (default: a local cluster)")
    sweep.add_argument("--workers", type=int, metavar="N", help="local cluster: worker processes "
                       "(default: one per core)")
    sweep.add_argument("--out", metavar="DIR", help="output folder (default: the sweep file's out)")
    sweep.add_argument("--retry-failed", action="store_true", help="run again the cases that failed "
                       "(cases done before are skipped)")
    sweep.set_defaults(func=cmd_sweep)
    return parser


def main(argv=None):
    """Entry point: parse arguments, run the command, turn every failure into one line on stderr
    and an exit status: 2 bad input or output location, 3 no convergence, 128 + the signal
    for SIGINT / SIGTERM, 1 a fault of cablefem itself (its traceback with CABLEFEM_DEBUG=1)."""
    from cablefem.io.output import raise_on_sigterm

    args = build_parser().parse_args(argv)
    previous = raise_on_sigterm()
    try:
        args.func(args)
    except InputError as error:
        return _fail(f"error: {error.message()}", 2)
    except ConvergenceError as error:
        return _fail(" ".join(str(error).split()), 3)
    except KeyboardInterrupt as error:
        signum = getattr(error, "signum", signal.SIGINT)
        return _fail(f"interrupted ({signal.Signals(signum).name})", 128 + signum)
    except OSError as error:  # an input or output file the checks could not foresee
        where = f"{error.filename}: " if error.filename else ""
        return _fail(f"error: {where}{error.strerror or error}", 2)
    except Exception as error:  # noqa: BLE001 - a bug: one line, the traceback on request
        if os.environ.get("CABLEFEM_DEBUG"):
            traceback.print_exc()
        return _fail(f"internal error: {type(error).__name__}: {' '.join(str(error).split())} "
                     "(CABLEFEM_DEBUG=1 shows the traceback; please report it)", 1)
    finally:
        if previous is not None:
            signal.signal(signal.SIGTERM, previous)
    return 0


def _fail(message, status):
    """Print ``cablefem: message`` on one line of stderr (control characters escaped, as in
    ``'\\n'``); return the exit status."""
    message = "".join(c if c.isprintable() else repr(c)[1:-1] for c in message)
    print(f"cablefem: {message}", file=sys.stderr)
    return status


class _Parser(argparse.ArgumentParser):
    """argparse with its usage errors on one line, exit status 2."""

    def error(self, message):
        self.exit(2, f"cablefem: error: {' '.join(message.split())} (see {self.prog} --help)\n")


if __name__ == "__main__":
    sys.exit(main())
