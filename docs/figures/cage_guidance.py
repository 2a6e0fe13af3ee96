"""How the cage's guidance changes the losses (thesis outlook 8.2; issue 18 item 7): torque and
cage pocket friction against the radial load, TRB 32208 at Fa 19.5 kN, 1201 rpm, FVA 3 at 108 degC
(the case of 200 random ones where the two quasi-static guidances part most, README "Radial
loads"), by the quasi-static solver with the cage rigid (friction.cage_guidance=rigid: every roller
held at the cage speed, the pocket carrying its net traction) and with the rollers free in their
pockets (the default), and by the dynamic solver. Writes beside this file cage_guidance.nc,
cage_guidance.md and cage_guidance.png.

    python docs/figures/cage_guidance.py [bearing=tsrb_reference load.Fa=... ...]

Extra arguments are simulation overrides for every run (after the case above); about 3 min on one
core.
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

import sim  # noqa: E402

OUT = pathlib.Path(__file__).with_suffix("")
CASE = ["bearing=trb_32208", "load.Fa=19484", "load.speed=1201", "load.oil_temperature=108"]
RADIAL_LOADS = [0.0, 6500.0, 13000.0, 19500.0, 26690.0]     # N, Fr / Fa 0 to 1.37
SOLVERS = {"rigid cage": ["friction.cage_guidance=rigid"], "free rollers": ["friction.cage_guidance=free"],
           "dynamic": ["solver=dynamic"]}


def run(overrides=()):
    """Dataset (solver, Fr) of torque and cage pocket friction [N mm] and whether each run converged
    (the dynamic one: found its steady state)."""
    shape = (len(SOLVERS), len(RADIAL_LOADS))
    torque, cage = np.full(shape, np.nan), np.full(shape, np.nan)
    converged = np.zeros(shape, dtype=bool)
    for i, (name, extra) in enumerate(SOLVERS.items()):
        for k, Fr in enumerate(RADIAL_LOADS):
            ds = sim.simulate(sim.load_config([*CASE, *overrides, f"load.Fr={Fr}", *extra])).isel(design=0, case=0)
            converged[i, k] = bool(ds.converged)
            if converged[i, k]:
                torque[i, k] = float(ds.torque)
                cage[i, k] = float(ds.torque_component.sel(component="cage"))
            print(f"{name}, Fr {Fr:g} N: torque {torque[i, k]:.1f} N mm, cage {cage[i, k]:.2f} N mm", flush=True)
    coords = {"solver": list(SOLVERS), "Fr": ("Fr", RADIAL_LOADS, {"units": "N", "long_name": "radial load"})}
    return xr.Dataset(
        {"torque": (("solver", "Fr"), torque, {"units": "N*mm", "long_name": "frictional torque"}),
         "cage": (("solver", "Fr"), cage, {"units": "N*mm", "long_name": "cage pocket friction (torque share)"}),
         "converged": (("solver", "Fr"), converged, {"units": "1", "long_name": "converged or steady state found"})},
        coords=coords, attrs={"title": "cage guidance: torque against the radial load",
                              "case": " ".join([*CASE, *overrides])})


def table(ds):
    rows = [f"# {ds.attrs['title']}", "", f"Case: `{ds.attrs['case']}`, Fr varied. Torques in N mm "
            "(cage pocket friction in brackets); - : not converged / no steady state.", "",
            "| Fr [N] | " + " | ".join(ds.solver.values) + " |", "| --- |" + " --- |" * ds.solver.size]
    for k, Fr in enumerate(ds.Fr.values):
        cells = [f"{ds.torque.values[i, k]:.1f} ({ds.cage.values[i, k]:.1f})" if ds.converged.values[i, k] else "-"
                 for i in range(ds.solver.size)]
        rows.append(f"| {Fr:g} | " + " | ".join(cells) + " |")
    return "\n".join(rows) + "\n"


def figure(ds):
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.6))
    for i, name in enumerate(ds.solver.values):
        axes[0].plot(ds.Fr / 1e3, ds.torque[i], "o-", label=name)
        axes[1].plot(ds.Fr / 1e3, ds.cage[i], "o-", label=name)
    axes[0].set(xlabel="radial load Fr [kN]", ylabel="torque [N mm]")
    axes[1].set(xlabel="radial load Fr [kN]", ylabel="cage pocket friction [N mm]")
    axes[0].legend(fontsize=8)
    fig.suptitle(ds.attrs["case"], fontsize=8)
    fig.tight_layout()
    return fig


if __name__ == "__main__":
    result = run(sys.argv[1:])
    result.to_netcdf(OUT.with_suffix(".nc.tmp"))
    OUT.with_suffix(".nc.tmp").replace(OUT.with_suffix(".nc"))
    OUT.with_suffix(".md").write_text(table(result))
    figure(result).savefig(OUT.with_suffix(".png"), dpi=120)
    print(f"wrote {OUT.with_suffix('.nc')}, .md, .png")
