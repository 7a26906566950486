"""The closed-form cases of the axial laws (``cablefem.model.axial``, ``cablefem.loads.rope``), each a
TOML scene written to a folder and run through ``cablefem.io.load_scene`` as a user would:

- ``table_free_end``: a rope with a strain-tension table from a fixed anchor to a free point pulled
  by a steady force F (g = 0): its end lies at L (1 + e) with e the table's inverse at F;
- ``viscoelastic_harmonic``: a straight rope of constant dynamic stiffness (EA_s|EA_d, BA_D = 0)
  stretched harmonically from rest: the tension against the exact solution of its linear equation,
  and the observed order of backward Euler's error in the step;
- ``syrope_cycle``: a SYROPE rope loaded slowly past its initial highest mean tension Tmax0, unloaded
  and reloaded: below the new Tmax the tension follows the working curve of the new Tmax
  (``AxialLaw.working_curve``), above it the original working curve.
"""

import tempfile
import textwrap
from pathlib import Path

import numpy as np

from cablefem.io import load_scene
from cablefem.model.axial import AxialLaw, Curve, Syrope
from cablefem.statics.scene import static_lines
from cablefem.study import start_line, tensions

TABLE = {"strain": [0.0, 0.004, 0.011, 0.031, 0.05], "tension": [0.0, 3.0e5, 1.0e6, 3.6e6, 7.0e6]}
HEAD = """
[environment]
gravity = 0.0
water_density = 0.0
[seabed]
kind = "horizontal"
depth = 100.0
"""


def _scene(text, folder):
    path = Path(folder) / "scene.toml"
    path.write_text(textwrap.dedent(text) + HEAD)
    return load_scene(path)


def table_free_end(forces=(2.0e5, 2.0e6, 5.0e6, 8.0e6), elements=10, order=2):
    """End position error [m] of the free end under each force (the last beyond the table: its last
    slope carried on), against L (1 + Curve.inverse(F))."""
    curve = Curve.from_rows(TABLE["strain"], TABLE["tension"], "EA")
    rows = []
    with tempfile.TemporaryDirectory() as folder:
        for force in forces:
            scene = _scene(f"""
                name = "table-free-end"
                [line_types.poly]
                diameter = 0.2
                mass = 40.0
                EA = {{ strain = {TABLE['strain']}, tension = {TABLE['tension']} }}
                [points.end]
                kind = "free"
                position = [100.0, 0.0, -50.0]
                force = [{force}, 0.0, 0.0]
                [[lines]]
                anchor = [0.0, 0.0, -50.0]
                fairlead = "end"
                segments = [{{ type = "poly", length = 100.0, elements = {elements} }}]
                order = {order}
                """, folder)
            systems, results, _, _ = static_lines(scene)
            end = results[0].X[systems[0].fem.fairlead_dof]
            exact = 100.0 * (1.0 + float(curve.inverse(force)))
            rows.append({"force": force, "end_x": float(end[0]), "exact": exact, "error": abs(float(end[0]) - exact)})
    return rows


def _viscoelastic_exact(t, e0, amplitude, omega, EA_s, EA_d, BA):
    """Tension [N] of the rope EA_s|EA_d with BA_D = 0 under e = e0 + a sin(w t), relaxed at t = 0:
    e_1' + e_1 / tau = (EA_d / BA) e, T = EA_d (e - e_1), tau = BA / (EA_1 + EA_d)."""
    EA_1 = EA_d * EA_s / (EA_d - EA_s)
    tau = BA / (EA_1 + EA_d)
    k = EA_d / BA
    A = k * amplitude * tau / (1.0 + (omega * tau) ** 2)
    B = -omega * tau * A
    e1 = EA_d * e0 / (EA_1 + EA_d) + A * np.sin(omega * t) + B * np.cos(omega * t) - B * np.exp(-t / tau)
    return EA_d * (e0 + amplitude * np.sin(omega * t) - e1)


def viscoelastic_harmonic(steps=(20, 40, 80), period=10.0, duration=20.0):
    """The fairlead tension of a 4-element rope (EA_s 1.2e8 N, EA_d 1.6e8 N, BA 4e8 N s: tau = 0.55 s),
    its fairlead moved 0.05 m (0.05 % strain) at ``period`` about 1 % strain, against the exact
    solution: the RMS error relative to the tension's amplitude for ``steps`` per period."""
    EA_s, EA_d, BA, length = 1.2e8, 1.6e8, 4.0e8, 100.0
    e0, stroke = 0.01, 0.05
    omega = 2.0 * np.pi / period
    rows = []
    with tempfile.TemporaryDirectory() as folder:
        scene = _scene(f"""
            name = "viscoelastic"
            [line_types.poly]
            diameter = 0.2
            mass = 1.0
            EA = {EA_s}
            EA_dynamic = {EA_d}
            BA = {BA}
            Cd_normal = 0.0
            Ca_normal = 0.0
            [[lines]]
            anchor = [0.0, 0.0, -50.0]
            fairlead = [{length * (1 + e0)}, 0.0, -50.0]
            segments = [{{ type = "poly", length = {length}, elements = 4 }}]
            [motion]
            kind = "harmonic"
            amplitude = [{stroke}, 0.0, 0.0]
            period = {period}
            """, folder)
        for n in steps:
            dt = period / n
            integ = start_line(scene, dt=dt)
            times = np.arange(1, int(round(duration / dt)) + 1) * dt
            fairlead, _ = tensions(integ, times)
            exact = _viscoelastic_exact(times, e0, stroke / length, omega, EA_s, EA_d, BA)
            swing = 0.5 * (exact.max() - exact.min())
            rows.append({"steps_per_period": n, "dt": dt,
                         "rms_error_of_amplitude": float(np.sqrt(np.mean((fairlead - exact) ** 2)) / swing),
                         "static_EA_tension": EA_s * e0, "dynamic_amplitude": swing,
                         "static_amplitude": EA_s * stroke / length})
    errors = [r["rms_error_of_amplitude"] for r in rows]
    order = float(np.polyfit(np.log(steps), np.log(errors), 1)[0]) * -1.0
    return {"rows": rows, "observed_order": order}


#: the SYROPE rope of the cycle: MoorDyn's owc.dat (every other row), its EA_Dc and EA_D_Lm, a slow
#: part's damper BA = 5e8 N s (tau ~ 3 s, so that a 2000 s cycle is slow) and the linear working curve
OWC = {"strain": [0.0, 4.13793e-03, 8.27586e-03, 1.24138e-02, 1.65517e-02, 2.06897e-02, 2.48276e-02,
                  2.89655e-02, 3.31034e-02, 3.72414e-02, 4.13793e-02],
       "tension": [0.0, 3.30952e+05, 6.16510e+05, 8.66556e+05, 1.09097e+06, 1.29964e+06, 1.50245e+06,
                   1.70927e+06, 1.93000e+06, 2.17450e+06, 2.45267e+06]}


def syrope_cycle(peak_strain=0.026, low_strain=0.012, period=4000.0, dt=2.0):
    """A one-element SYROPE rope (1 m) whose strain goes in straight ramps from that of Tmean0 =
    Tmax0 = 1e6 N to ``peak_strain`` (beyond Tmax0: on the original curve), down to ``low_strain``
    and back up, over ``period``: the largest tension error, relative to the new Tmax, against the
    original working curve on the way up and against the working curve of the new Tmax
    (``AxialLaw.working_curve``) on the way down and back up, away from the turns (the slow strain
    lags by its relaxation time, ~3 s here)."""
    law = AxialLaw("syrope", Curve.from_rows(OWC["strain"], OWC["tension"], "EA"), dynamic_EA=1.53e8,
                   dynamic_slope=23.12, damping=5.0e8, dynamic_damping=1.0e5, syrope=Syrope("linear", 1.25e8, 0.0))
    peak0 = 1.0e6
    e_start = float(law.curve.inverse(peak0))
    corners = np.array([[0.0, e_start], [period / 4, peak_strain], [3 * period / 4, low_strain], [period, peak_strain]])
    with tempfile.TemporaryDirectory() as folder:
        motion = Path(folder) / "motion.csv"
        np.savetxt(motion, np.column_stack([corners[:, 0], corners[:, 1] - e_start, 0 * corners[:, 0],
                                            0 * corners[:, 0]]), delimiter=",", header="t,x,y,z", comments="")
        scene = _scene(f"""
            name = "syrope-cycle"
            [line_types.poly]
            diameter = 0.2
            mass = 1.0
            EA = {{ strain = {OWC['strain']}, tension = {OWC['tension']} }}
            EA_dynamic = 1.53e8
            EA_dynamic_slope = 23.12
            BA = 5.0e8
            BA_dynamic = 1.0e5
            syrope = {{ working_curve = "linear", k1 = 1.25e8, k2 = 0.0 }}
            Cd_normal = 0.0
            Ca_normal = 0.0
            [[lines]]
            anchor = [0.0, 0.0, -50.0]
            fairlead = [{1.0 + e_start}, 0.0, -50.0]
            segments = [{{ type = "poly", length = 1.0, elements = 1, syrope = {{ Tmax = {peak0}, Tmean = {peak0} }} }}]
            [motion]
            kind = "table"
            file = "{motion}"
            interpolation = "linear"
            """, folder)
        integ = start_line(scene, dt=dt)
        times = np.arange(1, int(round(period / dt)) + 1) * dt
        fairlead, _ = tensions(integ, times)
    strain = np.interp(times, corners[:, 0], corners[:, 1])
    new_peak = float(law.curve.at(peak_strain))
    x, y, _ = law.working_curve(new_peak)
    settle = 20.0  # s after each turn: seven relaxation times
    loading = (times > settle) & (times < period / 4)
    cycling = times > period / 4 + settle
    turns = np.abs(times[:, None] - corners[1:3, 0][None, :]).min(axis=1) > settle
    return {"period": period, "new_peak": new_peak, "peak_reached": float(fairlead.max()),
            "original_curve_error": float(np.max(np.abs(fairlead[loading] - law.curve.at(strain[loading])))
                                          / new_peak),
            "working_curve_error": float(np.max(np.abs(fairlead[cycling & turns] - np.interp(strain, x, y)[cycling & turns]))
                                         / new_peak)}
