"""The thesis's pinion finding revisited (issue 18 item 6): torque by mechanism of the pinion TSRB
(thesis Table 7.4) against TRB 31313 (Table 7.3) at the pinion case of conf/study/pinion.yaml
(Fa 35 kN, Fr 0, 1100 rpm, pinion oil at 50 degC), by the quasi-static solver without and with
roller skew (friction.skew) and by the time-domain solver with skew and tilt free
(solver=dynamic), against the thesis's +367 % (TSRB torque 4.67 x TRB, thesis 7.4). Writes
beside this file pinion_breakdown.nc, pinion_breakdown.md and pinion_breakdown.png.

    python docs/figures/pinion_breakdown.py [solver.n_slices=30 ...]

Extra arguments are simulation overrides for every run (not the bearing, the load or the
lubricant: the study sets those). About 3 min on one core (the two dynamic runs).
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

from studies.verify import VARIANTS, solver_summary, variant_config, run_script  # noqa: E402

OUT = pathlib.Path(__file__).with_suffix("")
# thesis 7.4 (Fig. 7.28 discussion): the optimised TSRB's torque is 367 % above the TRB 31313's
THESIS_INCREASE = 3.67
ROLES = {"thesis_design": "TSRB (thesis Table 7.4)", "reference_trb": "TRB 31313 (Table 7.3)"}
SCALARS = {   # name -> (units, long_name)
    "torque": ("N*mm", "frictional torque on the outer ring (steady state)"),
    "loss_torque": ("N*mm", "power loss / inner-ring speed"),
    "drive_torque": ("N*mm", "torque driving the inner ring (dynamic: mean over the last window)"),
    "skew_sliding": ("N*mm", "part of 'sliding' caused by roller skew (lateral slip)"),
    "skew": ("deg", "largest |roller skew|"),
    "tilt": ("deg", "largest |roller tilt|"),
    "cage_speed": ("rpm", "cage speed"),
    "wall_time": ("s", "wall time of the run"),
}


def run(study, overrides=()):
    """Dataset (bearing, solver[, component]) of the six runs."""
    rows = {}
    for role in ROLES:
        for variant in VARIANTS:
            rows[role, variant], ds = solver_summary(variant_config(study, study[role], variant, overrides))
            r = rows[role, variant]
            print(f"{study[role]} {variant}: torque {r['torque']:.1f} N mm, loss/speed {r['loss_torque']:.1f}, "
                  f"drive {r['drive_torque']:.1f}, skew {r['skew']:.4f} deg, {r['wall_time']:.1f} s", flush=True)

    def grid(key):
        return np.array([[rows[r, v][key] for v in VARIANTS] for r in ROLES])

    data = {k: (("bearing", "solver"), grid(k), {"units": u, "long_name": n}) for k, (u, n) in SCALARS.items()}
    data["torque_component"] = (("bearing", "solver", "component"),
                                np.array([[list(rows[r, v]["component"].values()) for v in VARIANTS] for r in ROLES]),
                                {"units": "N*mm", "long_name": "torque breakdown by loss mechanism"})
    data["converged"] = (("bearing", "solver"), grid("converged").astype(bool),
                         {"long_name": "converged (dynamic: steady state found)"})
    torque = grid("torque")
    data["torque_ratio"] = ("solver", torque[0] / torque[1], {"units": "1", "long_name": "TSRB torque / TRB torque"})
    return xr.Dataset(data, coords={
        "bearing": ("bearing", [str(study[r]) for r in ROLES], {"long_name": "bearing (conf/bearing)"}),
        "solver": ("solver", list(VARIANTS), {"long_name": "solver variant"}),
        "component": ("component", ds.component.values, {"long_name": "friction loss mechanism"})},
        attrs={"title": "pinion case: torque by mechanism, TSRB (thesis Table 7.4) vs TRB 31313, by solver",
               "load_case": f"Fa {study.load.Fa:g} N, Fr {study.load.Fr:g} N, {study.load.speed:g} rpm, "
                            f"{study.lubricant} at {study.load.oil_temperature:g} degC (conf/study/pinion.yaml)",
               "thesis_torque_ratio": 1.0 + THESIS_INCREASE, "overrides": " ".join(overrides)})


def table(ds):
    """Markdown table: one row per bearing and solver variant, N mm (deg for skew and tilt)."""
    head = (["bearing", "solver", "torque", "loss/speed", "drive"] + [str(c) for c in ds.component.values]
            + ["of it skew sliding", "skew [deg]", "tilt [deg]", "wall [s]"])
    lines = ["| " + " | ".join(head) + " |", "|" + " --- |" * len(head)]
    for b in ds.bearing.values:
        for v in ds.solver.values:
            r = ds.sel(bearing=b, solver=v)
            cells = [b, VARIANTS[str(v)][0]] + [f"{float(r[k]):.1f}" for k in ("torque", "loss_torque", "drive_torque")]
            cells += [f"{x:.1f}" for x in r.torque_component.values]
            cells += [f"{float(r.skew_sliding):.1f}", f"{float(r.skew):.4f}", f"{float(r.tilt):.4f}",
                      f"{float(r.wall_time):.1f}"]
            lines.append("| " + " | ".join(cells) + " |")
    ratios = ", ".join(f"{VARIANTS[str(v)][0]} {float(x):.3f} ({100 * (float(x) - 1):+.0f} %)"
                       for v, x in zip(ds.solver.values, ds.torque_ratio.values))
    return "\n".join([f"# {ds.attrs['title']}", "", f"Load case: {ds.attrs['load_case']}. Torques in N mm.", "",
                      *lines, "", f"TSRB / TRB torque: {ratios}; thesis {ds.attrs['thesis_torque_ratio']:.2f} "
                                  f"(+{100 * THESIS_INCREASE:.0f} %).", ""])


def figure(ds):
    """Stacked bars of the breakdown per bearing and solver variant [N mm]; the figure."""
    fig, ax = plt.subplots(figsize=(8.0, 4.8))
    labels, x = [], 0
    for b in ds.bearing.values:
        for v in ds.solver.values:
            r = ds.sel(bearing=b, solver=v)
            bottom = 0.0
            for k, c in enumerate(ds.component.values):
                val = float(r.torque_component.sel(component=c))
                ax.bar(x, val, bottom=bottom, color=f"C{k}", label=c if x == 0 else None)
                if c == "sliding" and np.isfinite(float(r.skew_sliding)):   # its skew part hatched
                    ax.bar(x, float(r.skew_sliding), bottom=bottom, color="none", edgecolor="k", hatch="//",
                           lw=0, label="of it skew sliding" if x == 1 else None)
                bottom += val
            ax.plot([x - 0.4, x + 0.4], [float(r.loss_torque)] * 2, "k--", lw=1,
                    label="power loss / speed" if x == 0 else None)
            labels.append(f"{b}\n" + VARIANTS[str(v)][0].replace(", ", ",\n"))
            x += 1
    ax.set_xticks(range(x), labels, fontsize=7)
    ax.set_ylabel("torque [N mm]")
    ax.set_title(f"{ds.attrs['load_case']}\nTSRB / TRB: " + ", ".join(
        f"{float(t):.2f}" for t in ds.torque_ratio.values) + f" (thesis {ds.attrs['thesis_torque_ratio']:.2f})",
        fontsize=8)
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    return fig


if __name__ == "__main__":
    run_script(OUT, run, table, figure, sys.argv[1:])
