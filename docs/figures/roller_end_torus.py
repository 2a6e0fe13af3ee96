"""TRB 31313 at the pinion case of conf/study/pinion.yaml (Fa 35 kN, Fr 0, 1100 rpm, pinion oil at
50 degC), quasi-static with skew: roller skew, torque and its rib part against the rib opening
angle for the torus roller end (bearing.roller_end = torus) at three edge radii, against the
roller-end sphere (docs/roller_end_torus.md). Writes beside this file roller_end_torus.nc,
roller_end_torus.md and roller_end_torus.png (about 10 s on one core with a warm cache).

    python docs/figures/roller_end_torus.py [simulation overrides ...]
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

from studies.verify import run_script, solver_summary, variant_config  # noqa: E402

OUT = pathlib.Path(__file__).with_suffix("")
# mm: thesis Table A.2's 0.8 (TRB 32208) and either side of it
EDGE_RADII = [0.5, 0.8, 1.0]
# deg: the ASSUMED range of bearing.rib_opening_angle (conf/bearing/trb_31313.yaml), from just above
# the TRB 31313's single-point-contact limit (3.83 deg at r_k 0.8 mm) to where the rollers reach
# their cage pockets
OPENING_ANGLES = [4.5, 5.0, 6.0, 8.0, 10.0]
# thesis Fig. 7.28 as issue 18 reads it: roller skew of the order of 0.1-0.6 deg
THESIS_SKEW_DEG = (0.1, 0.6)
QUANTITIES = {"torque": ("N*mm", "frictional torque on the outer ring"),
              "rib": ("N*mm", "rib part of the torque (torque_component rib)"),
              "skew": ("deg", "largest |roller skew|"),
              "skew_sliding": ("N*mm", "part of 'sliding' caused by roller skew")}


def summary(study, overrides, bearing=None):
    """solver_summary of the reference TRB, quasi-static with skew; ``bearing``: keys set on its config."""
    cfg = variant_config(study, study["reference_trb"], "quasi_static_skew", list(overrides))
    for key, value in (bearing or {}).items():
        cfg.bearing[key] = value          # the study fixes its bearings; the roller end is their option
    r, _ = solver_summary(cfg)
    out = {q: r["component"]["rib"] if q == "rib" else r[q] for q in QUANTITIES}
    out["converged"] = r["converged"]
    return out


def run(study, overrides=()):
    """Dataset (edge_radius, opening_angle) of the torus sweep, and the sphere's values as scalars."""
    shape = (len(EDGE_RADII), len(OPENING_ANGLES))
    values = {q: np.full(shape, np.nan) for q in QUANTITIES}
    converged = np.zeros(shape, dtype=bool)
    for i, r_k in enumerate(EDGE_RADII):
        for k, b in enumerate(OPENING_ANGLES):
            r = summary(study, overrides, {"roller_end": "torus", "roller_end_edge_radius": r_k,
                                           "rib_opening_angle": b})
            for q in QUANTITIES:
                values[q][i, k] = r[q]
            converged[i, k] = r["converged"]
            print(f"torus r_k {r_k} mm, opening {b} deg: skew {r['skew']:.4f} deg, torque {r['torque']:.1f} N mm",
                  flush=True)
    sphere = summary(study, overrides)
    dims = ("bearing", "edge_radius", "opening_angle")   # one bearing: the study's reference TRB
    data = {q: (dims, values[q][None], {"units": u, "long_name": n}) for q, (u, n) in QUANTITIES.items()}
    data.update({f"sphere_{q}": (("bearing",), [sphere[q]], {"units": u, "long_name": f"{n}, roller-end sphere"})
                 for q, (u, n) in QUANTITIES.items()})
    data["converged"] = (dims, converged[None], {"long_name": "converged"})
    return xr.Dataset(data, coords={
        "bearing": ("bearing", [str(study["reference_trb"])], {"long_name": "bearing (conf/bearing)"}),
        "edge_radius": ("edge_radius", EDGE_RADII, {"units": "mm", "long_name": "roller end edge radius r_k"}),
        "opening_angle": ("opening_angle", OPENING_ANGLES, {"units": "deg", "long_name": "rib opening angle"})},
        attrs={"title": "TRB 31313, pinion case: torus roller end against the rib opening angle",
               "load_case": f"Fa {study.load.Fa:g} N, Fr {study.load.Fr:g} N, {study.load.speed:g} rpm, "
                            f"{study.lubricant} at {study.load.oil_temperature:g} degC (conf/study/pinion.yaml), "
                            "quasi-static with skew",
               "overrides": " ".join(overrides)})


def table(ds):
    """Markdown table: skew [deg], torque and rib torque [N mm] per edge radius and opening angle."""
    ds = ds.isel(bearing=0)
    head = ["roller end", "r_k [mm]", "opening [deg]", "skew [deg]", "torque [N mm]", "rib [N mm]",
            "skew sliding [N mm]"]
    lines = ["| " + " | ".join(head) + " |", "|" + " --- |" * len(head),
             f"| sphere | - | - | {float(ds.sphere_skew):.4f} | {float(ds.sphere_torque):.1f} | "
             f"{float(ds.sphere_rib):.1f} | {float(ds.sphere_skew_sliding):.1f} |"]
    for r_k in ds.edge_radius.values:
        for b in ds.opening_angle.values:
            r = ds.sel(edge_radius=r_k, opening_angle=b)
            lines.append(f"| torus | {r_k:g} | {b:g} | {float(r.skew):.4f} | {float(r.torque):.1f} | "
                         f"{float(r.rib):.1f} | {float(r.skew_sliding):.1f} |")
    return "\n".join([f"# {ds.attrs['title']}", "", f"Load case: {ds.attrs['load_case']}; overrides "
                      f"`{ds.attrs['overrides']}`.", "", *lines, ""])


def figure(ds):
    """Skew [deg] and torque [N mm] against the opening angle [deg]; the sphere as a horizontal line."""
    ds = ds.isel(bearing=0)
    fig, (ax_s, ax_t) = plt.subplots(1, 2, figsize=(9.0, 3.8))
    ax_s.axhspan(*THESIS_SKEW_DEG, color="0.9", label="thesis Fig. 7.28 (issue 18)")
    for i, r_k in enumerate(ds.edge_radius.values):
        r = ds.sel(edge_radius=r_k)
        ax_s.plot(ds.opening_angle, r.skew, "-o", mfc="none", color=f"C{i}", label=f"torus, r_k {r_k:g} mm")
        ax_t.plot(ds.opening_angle, r.torque, "-o", mfc="none", color=f"C{i}", label=f"torque, r_k {r_k:g} mm")
        ax_t.plot(ds.opening_angle, r.rib, "--s", mfc="none", color=f"C{i}", label=f"rib part, r_k {r_k:g} mm")
    ax_s.axhline(float(ds.sphere_skew), color="k", ls=":", label="sphere")
    ax_t.axhline(float(ds.sphere_torque), color="k", ls=":", label="sphere torque")
    ax_t.axhline(float(ds.sphere_rib), color="k", ls="-.", label="sphere rib part")
    ax_s.set_ylabel("largest roller skew [deg]")
    ax_t.set_ylabel("torque [N mm]")
    for ax in (ax_s, ax_t):
        ax.set_xlabel("rib opening angle [deg]")
        ax.legend(fontsize=6)
    fig.suptitle(ds.attrs["load_case"], fontsize=8)
    fig.tight_layout()
    return fig


if __name__ == "__main__":
    run_script(OUT, run, table, figure, sys.argv[1:])
