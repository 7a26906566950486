"""One case of validation/moordyn: the reference comparison, its physics switches, its convergence
check; and the static checks of both codes."""

import functools
import tempfile
from dataclasses import replace
from pathlib import Path
from types import SimpleNamespace

import numpy as np

from cablefem.errors import ConvergenceError
from cablefem.io import load_scene
from cablefem.model.line import Line, Segment
from cablefem.model.builtin import FLUME_ANCHOR, FLUME_DEPTH, table5_chain

from validation.moordyn.comparison import compare_runs, periodicity, self_differences
from validation.moordyn.inputs import (FLUME_FILE_SEGMENTS, FLUME_LENGTH, GRAVITY, HOUSNER_CHAIN_LENGTH, WATER_DENSITY,
                                       case_file, case_title, flume_variant_file, line_type_120mm_chain)
from validation.moordyn.runners import (CONVERGENCE_CASES, WINDOW_PERIODS, point_order, refined, run_cablefem_case,
                                        run_moordyn_case, settings_for)
from validation.moordyn.switches import VerticalSeabed


def _timing(md, cf):
    return {"moordyn_wall_time_s": md["wall_time_s"], "moordyn_init_time_s": md["init_time_s"],
            "cablefem_wall_time_s": cf["wall_time_s"], "cablefem_init_time_s": cf["init_time_s"],
            "cablefem_steps": cf["steps"], "cablefem_newton_iterations": cf["newton_iterations"],
            "cablefem_rejected_steps": cf["rejected_steps"], "cablefem_dt": cf["dt"],
            "cablefem_failures": cf["failures"], "cablefem_start": cf["start"]}


def run_case(case, toml, fast, log=print):
    """Reference comparison of one case, its convergence checks (full) and its physics switches."""
    scene = load_scene(toml)
    path = Path(toml).parent / case_file(case)
    s = settings_for(case, fast)
    period = scene.motion.period
    duration = scene.motion.ramp + s["periods"] * period
    t_from = duration - min(WINDOW_PERIODS, s["periods"]) * period
    cf_scene = refined(scene, s["elements"])
    log(f"{case}: {duration:g} s, MoorDyn x{s['segments']} segments dtM {s['dtM']:g} s, "
        f"cablefem x{s['elements']} elements dt {s['dt']:g} s")
    md = run_moordyn_case(path, scene, duration, s)
    cf = run_cablefem_case(cf_scene, duration, s["dt"])
    order = point_order(scene, md["points"])
    names = [scene.lines[i].name for i in order]
    entry = {"case": case, "title": case_title(case), "file": path.name, "settings": s, "duration_s": duration, "window_s": [t_from, duration],
             "period_s": period, "lines": names, "moordyn_segments": md["segments"],
             "cablefem_elements": {line.name: [seg.elements for seg in line.segments] for line in cf_scene.lines},
             "seabed": scene.seabed.describe(), **_timing(md, cf),
             "differences": compare_runs(md, cf, order, t_from),
             "differences_point_force": compare_runs(md, cf, order, t_from, use_point_force=True)}
    if s["periods"] >= 2:
        scales = [d["reference_mean_N"] for d in entry["differences"]]
        entry["periodicity"] = {"moordyn": periodicity(md, range(len(order)), duration, period, scales),
                                "cablefem": periodicity(cf, order, duration, period, scales)}
    series = {"moordyn": md, "cablefem": cf, "order": order}
    log(f"  MoorDyn {md['wall_time_s']:.1f} s, cablefem {cf['wall_time_s']:.1f} s; "
        + "; ".join(f"{n} mean {r['mean']:+.2e} peak {r['peak']:+.2e} rms {r['rms']:.2e}"
                    for n, r in zip(names, entry["differences"])))
    if cf["failures"]:
        log(f"  cablefem reran at dt = {cf['dt']:g} s: {cf['failures']}")
    reference = SimpleNamespace(path=path, scene=scene, cf_scene=cf_scene, duration=duration, settings=s, moordyn=md,
                                cablefem=cf, order=order, names=names, t_from=t_from, log=log)
    entry["switches"] = run_switches(case, fast, reference, series)

    if not fast and case in CONVERGENCE_CASES:
        try:
            entry["convergence"], series["check"] = convergence_check(case, path, scene, s, duration, t_from,
                                                                      order, md, cf, log)
        except (ConvergenceError, RuntimeError) as error:  # recorded, and the study goes on
            entry["convergence"] = {"error": f"{type(error).__name__}: {error}"}
            log(f"  convergence check failed: {error}")
    return entry, series


def run_switches(case, fast, reference, series):
    """The physics switches of ``case`` (``_switch``); {name: entry}."""
    scene, cf_scene, s, md = reference.scene, reference.cf_scene, reference.settings, reference.moordyn
    switches = {}
    both = functools.partial(_switch, reference, switches, series)
    flume = case.startswith("flume")
    if not case.endswith("flat") and not flume:
        both("vertical_contact", cf_scene_variant=replace(cf_scene, seabed=VerticalSeabed(cf_scene.seabed)))
    if not fast and flume:
        both("no_seabed_damping", md_options={"cBot": 0.0},
             cf_scene_variant=replace(cf_scene, contact=replace(cf_scene.contact, damping=0.0)))
        both("no_friction", md_options={"FrictionCoefficient": 0.0},
             cf_scene_variant=replace(cf_scene, friction=replace(cf_scene.friction, model="none")))
        both("hydrodynamics_per_unstretched_length", hydro_per_unstretched=True)
        both("cdax_not_converted", cf_scene_variant=_unconverted_cdax(cf_scene))
        if case == "flume-dynamic":
            both("lumped_mass", lumped=True)  # MoorDyn's nodes carry lumped masses
        if case == "flume-quasi-static":
            with tempfile.TemporaryDirectory(prefix="moordyn-variant-") as folder:
                variant = flume_variant_file(folder, "flume_flat_kbot_default.dat", kbot=None)
                default_scene = replace(load_scene(variant), motion=scene.motion)
                md_default = both("kbot_default", md_path=variant, md_scene=default_scene,
                                  cf_scene_variant=refined(default_scene, s["elements"]))
                both("cablefem_kbot_3e5_moordyn_default", md_result=md_default)
    if not fast and case == "housner-flat":
        both("hydrodynamics_per_unstretched_length", hydro_per_unstretched=True)
        both("cdax_not_converted", cf_scene_variant=_unconverted_cdax(cf_scene))
    if not fast and case == "housner-upslope":
        mu = 0.5
        chain = line_type_120mm_chain()
        weight = (chain["MassDen"] - WATER_DENSITY * np.pi / 4 * chain["Diam"] ** 2) * GRAVITY
        fric_damp = weight * HOUSNER_CHAIN_LENGTH / 20 / 0.01  # a resting chain node saturates at 0.01 m/s
        from cablefem.model.scene import Friction
        friction = Friction(model="isotropic", mu=mu, v_threshold=0.01, saturation_damping=fric_damp)
        md_friction = {"FrictionCoefficient": mu, "FricDamp": fric_damp / s["segments"]}
        # both codes start from the frictionless equilibrium (cablefem's statics have no friction;
        # MoorDyn loads the reference run's initial state): a relaxation under friction stops
        # wherever friction arrests the chain, which the last variant shows
        md_with_friction = both("friction", md_options=md_friction, md_initial_state=md["initial_state"],
                                cf_scene_variant=replace(cf_scene, friction=friction))
        cf_vertical_friction = replace(cf_scene, friction=friction, seabed=VerticalSeabed(cf_scene.seabed))
        if md_with_friction is not None:
            both("friction_vertical_contact", md_result=md_with_friction, cf_scene_variant=cf_vertical_friction)
        if "friction_vertical_contact" in series:
            # a resting node's friction damping, mu FricDamp / node mass ~ 430 1/s, makes MoorDyn's explicit
            # relaxation unstable at a 4e-3 s initial-condition step (NaN at t = 206 s): 1e-3 s
            both("friction_vertical_contact_moordyn_relaxed", md_options=md_friction,
                 md_settings=dict(s, ic_dtM=min(s["ic_dtM"], 1e-3)),
                 cf_result=series["friction_vertical_contact"]["cablefem"])
    return switches


def _switch(reference, switches, series, name, md_options=None, cf_scene_variant=None, md_path=None, md_scene=None,
            md_result=None, md_settings=None, md_initial_state=None, cf_result=None, **cf_flags):
    """Switch ``name`` of a case: MoorDyn's and/or cablefem's run replaced by a variant (another file,
    scene, OPTIONS, flags, or a run already made), compared as the references are; records it in
    ``switches`` and its runs in ``series``, returns MoorDyn's run (None if a run failed)."""
    path, scene, duration, s = reference.path, reference.scene, reference.duration, reference.settings
    md, cf, cf_scene, order = reference.moordyn, reference.cablefem, reference.cf_scene, reference.order
    t_from, names, log = reference.t_from, reference.names, reference.log
    try:
        md_v = md_result if md_result is not None else md if md_options is None and md_path is None else \
            run_moordyn_case(md_path or path, md_scene or scene, duration, md_settings or s, md_options,
                             initial_state=md_initial_state)
        cf_v = cf_result if cf_result is not None else cf if cf_scene_variant is None and not cf_flags else \
            run_cablefem_case(cf_scene_variant if cf_scene_variant is not None else cf_scene, duration, s["dt"],
                              **cf_flags)
    except (ConvergenceError, RuntimeError) as error:  # recorded, and the study goes on
        switches[name] = {"error": f"{type(error).__name__}: {error}"}
        log(f"  switch {name} failed: {error}")
        return None
    rows = compare_runs(md_v, cf_v, order, t_from)
    switches[name] = {"differences": rows,
                      "moordyn_change": self_differences(md, md_v, t_from) if md_v is not md else None,
                      "cablefem_change": [self_differences(cf, cf_v, t_from)[i] for i in order]
                      if cf_v is not cf else None,
                      "moordyn_wall_time_s": md_v["wall_time_s"], "cablefem_wall_time_s": cf_v["wall_time_s"],
                      "cablefem_dt": cf_v["dt"], "cablefem_failures": cf_v["failures"],
                      "cablefem_start": cf_v["start"]}
    series[name] = {"moordyn": md_v, "cablefem": cf_v}
    log(f"  switch {name}: " + "; ".join(f"{n} mean {r['mean']:+.2e} peak {r['peak']:+.2e} rms {r['rms']:.2e}"
                                         for n, r in zip(names, rows)))
    if cf_v.get("failures"):
        log(f"  cablefem reran {name} at dt = {cf_v['dt']:g} s: {cf_v['failures']}")
    return md_v


def convergence_check(case, path, scene, s, duration, t_from, order, md, cf, log=print):
    """Both codes rerun at the ``s["check"]`` resolution ("coarse": half the segments/elements,
    twice the steps; "fine": the reverse): the change of each line's tension statistics from the
    reference, and the two codes compared at that resolution. Returns (entry, series)."""
    factor = 0.5 if s["check"] == "coarse" else 2.0
    other = dict(s, segments=s["segments"] * factor, dtM=s["dtM"] / factor)
    # MoorDyn's initial-condition step: stable for the reference, so for a coarser run; a finer
    # one needs 1 / factor^2 of it where BA dominates
    other["ic_dtM"] = s["ic_dtM"] if factor < 1 else s["ic_dtM"] / factor**2
    elements, dt = s["elements"] * factor, s["dt"] / factor
    log(f"  convergence ({s['check']}): MoorDyn x{other['segments']:g} segments dtM {other['dtM']:g} s; "
        f"cablefem x{elements:g} elements dt {dt:g} s")
    md_other = run_moordyn_case(path, scene, duration, other)
    cf_other = run_cablefem_case(refined(scene, elements), duration, dt)
    entry = {
        "check": s["check"],
        "moordyn": {"settings": other, "segments": md_other["segments"], "wall_time_s": md_other["wall_time_s"],
                    "change": self_differences(md, md_other, t_from)},
        "cablefem": {"elements_factor": elements, "dt": cf_other["dt"], "wall_time_s": cf_other["wall_time_s"],
                     "failures": cf_other["failures"],
                     "change": [self_differences(cf, cf_other, t_from)[i] for i in order]},
        "differences": compare_runs(md_other, cf_other, order, t_from)}
    for code in ("moordyn", "cablefem"):
        rows = entry[code]["change"]
        log(f"  {code} change: " + "; ".join(f"mean {r['mean']:+.2e} peak {r['peak']:+.2e} rms {r['rms']:.2e}"
                                             for r in rows))
    log("  both at that resolution: " + "; ".join(f"mean {r['mean']:+.2e} peak {r['peak']:+.2e} rms {r['rms']:.2e}"
                                                  for r in entry["differences"]))
    return entry, {"moordyn": md_other, "cablefem": cf_other}


def _unconverted_cdax(scene):
    """The scene with Cd_tangential = MoorDyn's CdAx copied, not multiplied by pi (the mistake the
    reader avoids), to show what the conversion is worth."""
    types = {}
    lines = []
    for line in scene.lines:
        segments = []
        for seg in line.segments:
            kind = types.setdefault(seg.type.name, replace(seg.type, Cd_tangential=seg.type.Cd_tangential / np.pi))
            segments.append(Segment(kind, seg.length, seg.elements))
        lines.append(Line(line.name, line.anchor, line.fairlead, segments, line.order))
    return replace(scene, lines=lines)


def static_checks(inputs_folder, fast, log=print):
    """Static pretension of the flat flume line: MoorDyn (peer), held 5 s to show it is MoorDyn's own
    equilibrium, MoorPy's catenary (rigid seabed), cablefem; and, in full, the surface-piercing
    fairlead (z = 0 against z = -1 m) and a stiff seabed."""
    from moorpy.Catenary import catenary

    from cablefem.model.scene import Contact

    chain = table5_chain()
    weight = chain.submerged_weight(WATER_DENSITY, GRAVITY)
    path = Path(inputs_folder) / "flume_flat.dat"
    factor = 1 if fast else 4
    settings = {"segments": factor, "dtM": 4e-4, "ic_dtM": 4e-4}
    scene = load_scene(path)
    held = run_moordyn_case(path, scene, 5.0, settings)
    moordyn_static = float(held["tensions"][0, 0])
    hold_change = float(np.max(np.abs(held["tensions"][:, 0] - moordyn_static)) / moordyn_static)

    def moorpy(height):
        fAH, fAV, fBH, fBV, _ = catenary(-FLUME_ANCHOR[0], height, FLUME_LENGTH, chain.EA, weight, CB=0.0,
                                         Tol=1e-12, MaxIter=500)
        return float(np.hypot(fBH, fBV))

    def cablefem_static(scene, elements_factor):
        cf = run_cablefem_case(refined(scene, elements_factor), 0.0, 1.0)
        return float(cf["tensions"][0, 0])

    result = {"moordyn_segments": FLUME_FILE_SEGMENTS * factor, "moordyn_N": moordyn_static,
              "moordyn_hold_5s_change": hold_change, "moorpy_N": moorpy(FLUME_DEPTH),
              "cablefem_N": cablefem_static(scene, factor), "cablefem_elements": FLUME_FILE_SEGMENTS * factor}
    result["moordyn_vs_moorpy"] = result["moordyn_N"] / result["moorpy_N"] - 1
    result["cablefem_vs_moorpy"] = result["cablefem_N"] / result["moorpy_N"] - 1
    result["moordyn_vs_cablefem"] = result["moordyn_N"] / result["cablefem_N"] - 1
    if not fast:
        converged = cablefem_static(scene, 16)
        stiff = cablefem_static(replace(scene, contact=Contact(stiffness=3e9, damping=0.0)), 16)
        with tempfile.TemporaryDirectory(prefix="moordyn-variant-") as folder:
            below = flume_variant_file(folder, "flume_flat_fairlead_1m_below.dat", fairlead_z=-1.0)
            below_scene = load_scene(below)
            md_below = run_moordyn_case(below, below_scene, 0.0, settings)
        result.update({
            "cablefem_640_elements_N": converged, "cablefem_stiff_seabed_N": stiff,
            "seabed_elasticity": converged / stiff - 1,
            "moorpy_vs_cablefem_stiff_seabed": result["moorpy_N"] / stiff - 1,
            "fairlead_1m_below": {"moordyn_N": float(md_below["tensions"][0, 0]),
                                  "cablefem_N": cablefem_static(below_scene, factor)}})
        below_row = result["fairlead_1m_below"]
        below_row["moordyn_vs_cablefem"] = below_row["moordyn_N"] / below_row["cablefem_N"] - 1
    log(f"statics: MoorDyn {moordyn_static:.1f} N (held 5 s: {hold_change:.1e}), MoorPy {result['moorpy_N']:.1f} N "
        f"({result['moordyn_vs_moorpy']:+.2e}), cablefem {result['cablefem_N']:.1f} N")
    return result
