"""The cage question of the thesis's outlook (8.2; issue 18 item 7): torque and roller skew against
the cage pocket clearance (friction.skew.pocket_clearance), pinion TSRB (thesis Table 7.4) and TRB
31313 at the pinion case of conf/study/pinion.yaml (Fa 35 kN, Fr 0, 1100 rpm, pinion oil at
50 degC), by the dynamic solver with skew and tilt free and, for comparison, the quasi-static
solver with skew. Writes beside this file pocket_clearance.nc, pocket_clearance.md and
pocket_clearance.png.

    python docs/figures/pocket_clearance.py [solver.dynamic.start=rolling ...]

Extra arguments are simulation overrides for every run. The dynamic runs start from the
quasi-static solution with skew of the same clearance (solver.dynamic.start=quasi_static; it
finds its own steady state from there, in fewer windows than from rolling): about 6 min on one core.
"""
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import xarray as xr  # noqa: E402

REPO = pathlib.Path(__file__).resolve().parents[2]
if str(REPO) not in sys.path:
    sys.path.insert(0, str(REPO))  # run from a checkout: this sim/, not an installed one

from studies.verify import solver_summary, variant_config, run_script  # noqa: E402

OUT = pathlib.Path(__file__).with_suffix("")
# mm: both ends and two inner points of the ASSUMED range 0.05-0.5 mm of friction.skew.pocket_clearance
# (conf/friction/default.yaml; 0.15 is its default)
CLEARANCES = [0.05, 0.15, 0.3, 0.5]
ROLES = ("thesis_design", "reference_trb")
# solver variants (studies.verify.VARIANTS) and their own overrides: the dynamic runs start from the
# quasi-static solution with skew (module docstring)
SOLVERS = {"quasi_static_skew": [], "dynamic": ["solver.dynamic.start=quasi_static"]}
QUANTITIES = {"torque": ("N*mm", "frictional torque on the outer ring"),
              "loss_torque": ("N*mm", "power loss / inner-ring speed"),
              "skew": ("deg", "largest |roller skew|"),
              "skew_sliding": ("N*mm", "part of 'sliding' caused by roller skew"),
              "wall_time": ("s", "wall time of the run")}


def run(study, overrides=()):
    """Dataset (bearing, solver, pocket_clearance) of the sweep."""
    shape = (len(ROLES), len(SOLVERS), len(CLEARANCES))
    values = {k: np.full(shape, np.nan) for k in QUANTITIES}
    converged = np.zeros(shape, dtype=bool)
    for i, role in enumerate(ROLES):
        for j, variant in enumerate(SOLVERS):
            for k, c in enumerate(CLEARANCES):
                cfg = variant_config(study, study[role], variant,
                                     [*SOLVERS[variant], *overrides, f"friction.skew.pocket_clearance={c}"])
                r, _ = solver_summary(cfg)
                for q in QUANTITIES:
                    values[q][i, j, k] = r[q]
                converged[i, j, k] = r["converged"]
                print(f"{study[role]} {variant} clearance {c} mm: torque {r['torque']:.1f} N mm, skew "
                      f"{r['skew']:.4f} deg, {r['wall_time']:.1f} s", flush=True)
    dims = ("bearing", "solver", "pocket_clearance")
    data = {q: (dims, values[q], {"units": u, "long_name": n}) for q, (u, n) in QUANTITIES.items()}
    data["converged"] = (dims, converged, {"long_name": "converged (dynamic: steady state found)"})
    return xr.Dataset(data, coords={
        "bearing": ("bearing", [str(study[r]) for r in ROLES], {"long_name": "bearing (conf/bearing)"}),
        "solver": ("solver", list(SOLVERS), {"long_name": "solver variant (studies.verify.VARIANTS)"}),
        "pocket_clearance": ("pocket_clearance", CLEARANCES,
                             {"units": "mm", "long_name": "circumferential cage pocket clearance"})},
        attrs={"title": "pinion case: torque and roller skew against the cage pocket clearance",
               "load_case": f"Fa {study.load.Fa:g} N, Fr {study.load.Fr:g} N, {study.load.speed:g} rpm, "
                            f"{study.lubricant} at {study.load.oil_temperature:g} degC (conf/study/pinion.yaml)",
               "overrides": " ".join(overrides)})


def table(ds):
    """Markdown table: torque [N mm] and skew [deg] per bearing, solver and clearance."""
    head = ["bearing", "solver", "clearance [mm]", "torque [N mm]", "loss/speed [N mm]", "skew [deg]",
            "skew sliding [N mm]", "steady", "wall [s]"]
    lines = ["| " + " | ".join(head) + " |", "|" + " --- |" * len(head)]
    for b in ds.bearing.values:
        for v in ds.solver.values:
            for c in ds.pocket_clearance.values:
                r = ds.sel(bearing=b, solver=v, pocket_clearance=c)
                lines.append(f"| {b} | {v} | {c:g} | {float(r.torque):.1f} | {float(r.loss_torque):.1f} | "
                             f"{float(r.skew):.4f} | {float(r.skew_sliding):.1f} | {bool(r.converged)} | "
                             f"{float(r.wall_time):.1f} |")
    return "\n".join([f"# {ds.attrs['title']}", "", f"Load case: {ds.attrs['load_case']}; overrides "
                      f"`{ds.attrs['overrides']}`.", "", *lines, ""])


def figure(ds):
    """Torque [N mm] and skew [deg] against the clearance [mm]; the figure."""
    fig, (ax_t, ax_s) = plt.subplots(1, 2, figsize=(9.0, 3.8))
    for i, b in enumerate(ds.bearing.values):
        for v, style, marker in zip(ds.solver.values, ("--", "-"), ("s", "o")):
            r = ds.sel(bearing=b, solver=v)
            for ax, q in ((ax_t, r.torque), (ax_s, r.skew)):
                ax.plot(ds.pocket_clearance, q, style, marker=marker, mfc="none", color=f"C{i}", label=f"{b}, {v}")
    ax_t.set_ylabel("torque [N mm]")
    ax_s.set_ylabel("largest roller skew [deg]")
    for ax in (ax_t, ax_s):
        ax.set_xlabel("cage pocket clearance [mm]")
    ax_t.legend(fontsize=7)
    fig.suptitle(ds.attrs["load_case"], fontsize=8)
    fig.tight_layout()
    return fig


if __name__ == "__main__":
    run_script(OUT, run, table, figure, sys.argv[1:])
