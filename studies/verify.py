"""A design simulated by each solver: the quasi-static solver without and with roller skew
(``friction.skew``) and the time-domain solver with skew and tilt free (``solver=dynamic``),
reduced to its torque, the torque's breakdown by mechanism and the roller skew and tilt
(issue 18 items 6 and 7, and the ``verify.solver`` of the studies).

The quantities are those the result Dataset carries (DATA.md, ``sim.io``): ``torque`` and
``torque_component`` (the outer-ring torque split in proportion to each mechanism's power),
``skew_sliding`` (the lateral-slip part of ``sliding``), ``power_loss``, ``roller_skew`` and
``roller_tilt``; and of a dynamic run the drive torque of the inner ring over the last window
(``drive_torque_t``). At a steady state torque x inner-ring speed = power loss = drive torque x
inner-ring speed; the three are reported apart, so that a run can show where they differ.
"""
import time
from pathlib import Path

import numpy as np
from omegaconf import OmegaConf

import sim
from sim.io import (CASE_COORD_ATTRS, RPM_PER_RAD_S, W_PER_N_MM_PER_S, git_commit, model_fingerprint, package_version,
                    utc_now, write_bytes_atomic, write_figure_atomic, write_netcdf_atomic)
from studies.config import VARIANTS, compose, simulation_config
from studies.evaluate import design_config

FIGURE_DPI = 150               # 1/inch, the docs figures' resolution (docs/figures/skew_tilt_dynamic.py)


def variant_config(study, bearing, variant, overrides=(), values=None, case=None):
    """Simulation config of ``bearing`` (conf/bearing name) at the study's load case ``case``
    (default ``study.load``) with the overrides of solver ``variant`` (:data:`VARIANTS`), the
    user's ``overrides`` and the design ``values`` (parameter name -> value) if given."""
    cfg = simulation_config(study, bearing, [*VARIANTS[variant][1], *overrides], case)
    return cfg if values is None else design_config(cfg, values)


def solver_summary(cfg):
    """Simulate one case (``cfg``) and reduce it: dict of floats in output units (torque,
    loss_torque = power loss / inner-ring speed, drive_torque [N mm]; component [N mm] by
    the Dataset's components, a dict; skew_sliding [N mm], NaN without skew; skew, tilt: the
    largest |roller skew| and |roller tilt| [deg], skew NaN without skew; cage_speed [rpm];
    converged; wall_time [s]) and the Dataset. Of a dynamic run torque, loss_torque, drive_torque,
    skew and tilt are those of its last window (:func:`last_window`; the torques sample means only
    without a steady state), drive_torque a sample mean."""
    t0 = time.perf_counter()
    ds = sim.simulate(cfg)
    wall = time.perf_counter() - t0
    c = ds.isel(design=0, case=0)
    wi = float(cfg.load.speed) / RPM_PER_RAD_S
    out = {
        "torque": float(c.torque) if "torque" in c else np.nan,
        "loss_torque": float(c.power_loss) / W_PER_N_MM_PER_S / wi if "power_loss" in c else np.nan,
        "component": {str(k): float(c.torque_component.sel(component=k)) if "torque_component" in c else np.nan
                      for k in c.component.values},
        "skew_sliding": float(c.skew_sliding) if "skew_sliding" in c else np.nan,
        "skew": float(np.abs(c.roller_skew).max()) if "roller_skew" in c else np.nan,
        "tilt": float(np.abs(c.roller_tilt).max()),
        "cage_speed": float(c.cage_speed) if "cage_speed" in c else np.nan,
        "converged": bool(c.converged),
        "wall_time": wall,
    }
    out["drive_torque"] = out["torque"]
    if "time" in c.dims:
        window = last_window(c, int(cfg.solver.dynamic.samples_per_window), wi)
        if out["converged"]:    # the summary's torques are the window's exact means
            del window["torque"], window["loss_torque"]
        out.update(window)
    return out, ds


def last_window(c, samples, wi):
    """Of a dynamic run's time series ``c`` (one case), over its last window of ``samples``
    samples: the sample means of the outer-ring torque, of power loss / inner-ring speed ``wi``
    [rad/s] and of the drive torque [N mm], and the largest |mean skew| and |mean tilt| of a
    roller [deg]. At a steady state the summary holds the window's exact torques (quadrature
    states, sim.solvers.dynamic.window_means; samples at fixed instants can miss short traction
    peaks) and its per-roller skew and tilt at one instant of it (the same under a pure axial
    load); without one, where the summary has no friction outputs, these still say where the run
    ended."""
    last = c.isel(time=slice(-samples, None))
    return {"torque": float(last.torque_t.mean()),
            "loss_torque": float(last.power_loss_t.mean()) / W_PER_N_MM_PER_S / wi,
            "drive_torque": float(last.drive_torque_t.mean()),
            "skew": float(np.abs(last.roller_skew_t.mean("time")).max()),
            "tilt": float(np.abs(last.roller_tilt_t.mean("time")).max())}


# names of the scripts' tables that DATA.md gives another meaning (case tilt; per-roller skew, tilt)
NOT_DATA_NAMES = {"skew": "roller_skew_max", "tilt": "roller_tilt_max"}


def contract_layout(ds, study):
    """``ds`` (dims ``bearing``, then the script's own: solver, clearance, ...; at the load case of
    ``study``) in the results contract (DATA.md): ``bearing`` becomes ``design`` (with
    ``bearing_type``), a ``case`` of one at the study's load follows it, the largest roller skew and
    tilt are named apart from DATA.md's per-roller ones, and the provenance attributes are added."""
    names = [str(b) for b in ds.bearing.values]
    out = ds.rename({k: v for k, v in NOT_DATA_NAMES.items() if k in ds}).rename(bearing="design")
    out = out.assign_coords(bearing=("design", names, {"long_name": "bearing (conf/bearing)"}),
                            bearing_type=("design", [str(simulation_config(study, b).bearing.type) for b in names],
                                          {"long_name": "bearing type"}))
    # DATA.md's leading dims first (extra ones may trail): design, case, then component where present
    out = out.expand_dims("case").transpose("design", "case", *(["component"] if "component" in out.dims else []), ...)
    out = out.assign_coords({k: ("case", [float(study.load[k])], {"units": u, "long_name": n})
                             for k, (u, n) in CASE_COORD_ATTRS.items()})
    out.attrs.update({"Conventions": "CF-1.10", "package_version": package_version(), "git_commit": git_commit(),
                      "model_fingerprint": model_fingerprint(), "config": OmegaConf.to_yaml(study),
                      "created": utc_now()})
    return out


def run_script(stem, run, table, figure, argv):
    """A docs/figures script of issue 18: compose the study of the overrides ``argv`` (study keys
    and simulation overrides, as ``python -m studies.optimize``), ``run(study, argv)`` -> its table
    Dataset, then :func:`write_results` beside ``stem``."""
    study = compose(list(argv)).study
    write_results(stem, run(study, argv), table, figure, study)


def write_results(stem, ds, table, figure, study):
    """Write ``ds`` to ``<stem>.nc`` in the results contract (:func:`contract_layout`), its markdown
    ``table(ds)`` to ``<stem>.md`` and its matplotlib ``figure(ds)`` to ``<stem>.png``, each
    atomically (a reader sees the old file or the new one); print the table (the docs/figures
    scripts of issue 18)."""
    stem = Path(stem)
    text = table(ds)
    write_netcdf_atomic(contract_layout(ds, study), stem.with_suffix(".nc"))
    write_bytes_atomic(stem.with_suffix(".md"), text.encode())
    write_figure_atomic(figure(ds), stem.with_suffix(".png"), FIGURE_DPI)
    print(text)
    print(f"wrote {stem}.nc, .md, .png")


def dynamic_verification(search, values, quasi_static):
    """``study.verify.solver = dynamic``: the reported best design (parameter ``values``) simulated
    at every load case of the study by the quasi-static solver with skew and by the dynamic solver
    with skew and tilt free, beside its ``quasi_static`` Datasets (one per case, the search's own
    full simulation, or None). Writes each dynamic Dataset to ``best_design_dynamic.nc`` (several
    cases: ``best_design_dynamic_<k>.nc``); returns the markdown section for report.md."""
    s = search.study
    several = len(search.cycle) > 1
    lines = ["## Verified best by the dynamic solver (`verify.solver: dynamic`)", "",
             "Torque [N mm] on the outer ring; power loss / speed and drive torque [N mm] of the dynamic run (at a "
             "steady state all three agree); largest |roller skew| and |roller tilt| [deg]; wall time [s].", "",
             "| case | quasi-static torque | with skew: torque | skew | dynamic: torque | power loss / speed | "
             "drive torque | skew | tilt | steady state | wall |", "|" + " --- |" * 11]
    unsteady = []
    for k, case in enumerate(search.cycle.cases):
        skew, _ = solver_summary(variant_config(s, s.bearing, "quasi_static_skew", search.overrides, values, case))
        dyn, ds = solver_summary(variant_config(s, s.bearing, "dynamic", search.overrides, values, case))
        write_netcdf_atomic(ds, search.out / (f"best_design_dynamic_{k}.nc" if several else "best_design_dynamic.nc"))
        qs = quasi_static[k]
        qs_torque = float(qs.torque.isel(design=0, case=0)) if qs is not None and "torque" in qs else np.nan
        lines.append(f"| {k} | {qs_torque:.1f} | {skew['torque']:.1f} | {skew['skew']:.4f} | {dyn['torque']:.1f} | "
                     f"{dyn['loss_torque']:.1f} | {dyn['drive_torque']:.1f} | {dyn['skew']:.4f} | {dyn['tilt']:.4f} | "
                     f"{dyn['converged']} | {dyn['wall_time']:.0f} |")
        if not dyn["converged"]:
            unsteady.append(k)
        search.log(f"verified best, case {k}, dynamic: torque {dyn['torque']:.1f} N mm (quasi-static {qs_torque:.1f}), "
                   f"skew {dyn['skew']:.4f} deg, {dyn['wall_time']:.0f} s")
    if unsteady:
        lines += ["", f"No steady state at case(s) {unsteady} within solver.dynamic.max_windows: the dynamic values "
                      "there are means over the last window (its time series in best_design_dynamic*.nc)."]
    return "\n".join(lines)
