"""MoorDyn-C (PyPI ``moordyn``) on its own SYROPE and polyester test inputs (its repository's
``tests/Mooring/syrope``, ``tests/Mooring/polyester/visco.txt``; copies in tests/data/moordyn/laws),
against cablefem on the same files: the tension after MoorDyn's initial condition against
``cablefem static``, and a short run with the fairlead moved harmonically along the line.

A copy of each case is written to a temporary folder (MoorDyn writes its outputs beside its input).
``owc_header``: give owc.dat a third header line. MoorDyn-C skips three lines of a curve file, and its
own owc.dat has two, so both codes drop its (0, 0) row; cablefem's table then runs from (0, 0) to
the next row, where MoorDyn-C takes that next row's strain (2.07e-3) as the working curves' zero-
tension offset eps_0: the quadratic and exponential working curves (eps_min = eps_0 + k1 (eps_max -
eps_0)) differ by that. With the third line both keep the row.
"""

import math
import shutil
import tempfile
import textwrap
from pathlib import Path

import numpy as np

from cablefem.io import load_scene
from cablefem.statics.scene import static_lines
from cablefem.study import start_line, tensions

HERE = Path(__file__).resolve().parents[2] / "tests" / "data" / "moordyn" / "laws"
SYROPE_CASES = ("linear_wc", "quadratic_wc", "exp_wc")


def case_folder(case, folder, owc_header=False):
    """A copy of a SYROPE case (its line.txt, syrope.dat and ../owc.dat) or of visco.txt in ``folder``;
    the input file's path."""
    folder = Path(folder)
    if case == "visco":
        (folder / "case").mkdir()
        target = folder / "case" / "visco.txt"
        # the file's fairlead sits at x = 2 m, a 100 % strain of its 1 m line, which cablefem refuses
        # (docs/scene.md, Limits); at 1.02 m it is a 2 % strain
        target.write_text((HERE / "polyester" / "visco.txt").read_text().replace(
            "2    Coupled      2     0.0   0.0", "2    Coupled      1.02  0.0   0.0"))
        return target
    (folder / "case").mkdir()
    for name in ("line.txt", "syrope.dat"):
        shutil.copy(HERE / "syrope" / case / name, folder / "case" / name)
    rows = (HERE / "syrope" / "owc.dat").read_text().splitlines()
    (folder / "owc.dat").write_text("\n".join((["--- OWC (a third header line) ---"] if owc_header else []) + rows))
    return folder / "case" / "line.txt"


def moordyn_run(path, stroke, period, duration, dt):
    """MoorDyn-C's fairlead tension [N] after its initial condition (t = 0) and every ``dt`` of a run
    with the coupled point 2 at x0 + stroke sin(2 pi t / period), and the times."""
    import moordyn

    from validation.moordyn.peer import silenced_stdout

    with silenced_stdout():
        system = moordyn.Create(str(path))
        point = moordyn.GetPoint(system, 2)
        x0 = np.array(moordyn.GetPointPos(point))
        moordyn.Init(system, list(x0), [0.0, 0.0, 0.0])
        times = np.arange(0, int(round(duration / dt)) + 1) * dt
        out = [abs(moordyn.GetPointForce(point)[0])]
        omega = 2.0 * math.pi / period
        for t in times[1:]:
            x = x0 + [stroke * math.sin(omega * t), 0.0, 0.0]
            before = x0 + [stroke * math.sin(omega * (t - dt)), 0.0, 0.0]
            moordyn.Step(system, list(before), list((x - before) / dt), t - dt, dt)
            out.append(abs(moordyn.GetPointForce(point)[0]))
        moordyn.Close(system)
    return times, np.array(out)


def cablefem_run(path, stroke, period, duration, dt):
    """cablefem's fairlead tension: ``cablefem static`` (t = 0) and a run with the fairlead moved as
    ``moordyn_run`` moves it (a TOML that wraps the file with a harmonic [motion])."""
    wrapper = Path(path).with_name("run.toml")
    wrapper.write_text(textwrap.dedent(f"""
        [moordyn]
        file = "{Path(path).name}"
        [motion]
        kind = "harmonic"
        amplitude = [{stroke}, 0.0, 0.0]
        period = {period}
        [solver]
        dt = {dt}
        """))
    scene = load_scene(wrapper)
    systems, results, _, _ = static_lines(scene)
    static = float(np.linalg.norm(systems[0].residual(results[0].X)[systems[0].fem.fairlead_dof]))
    integ = start_line(scene, dt=dt)
    times = np.arange(1, int(round(duration / dt)) + 1) * dt
    fairlead, _ = tensions(integ, times)
    return static, np.concatenate([[static], fairlead])


def compare(case, owc_header=False, stroke=0.002, period=20.0, duration=40.0, dt=0.05, skip=0.0):
    """Both codes on one case: the initial tensions, their relative difference, and the run's RMS
    difference from ``skip`` [s] on, relative to the tension's swing and to its mean."""
    with tempfile.TemporaryDirectory() as folder:
        path = case_folder(case, folder, owc_header)
        times, peer = moordyn_run(path, stroke, period, duration, dt)
        static, ours = cablefem_run(path, stroke, period, duration, dt)
    keep, initial = times >= skip, peer[0]
    times, peer, ours = times[keep], peer[keep], ours[keep]
    swing = 0.5 * (peer.max() - peer.min())
    return {"case": case, "owc_header": owc_header, "moordyn_initial": float(initial), "cablefem_static": static,
            "initial_difference": static / float(initial) - 1.0, "from_s": skip,
            "run_rms_over_swing": float(np.sqrt(np.mean((ours - peer) ** 2)) / swing),
            "run_rms_over_mean": float(np.sqrt(np.mean((ours - peer) ** 2)) / np.mean(peer)),
            "swing": swing, "mean": float(np.mean(peer))}
