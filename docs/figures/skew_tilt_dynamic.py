"""Roller skew and tilt over time, pinion TSRB (thesis Table 7.4) against TRB 31313 (Table 7.3) at
35 kN axial, 1100 rpm, pinion oil at 50 degC, skew free (friction.skew.enabled): the dynamic
solver's counterpart of thesis Fig. 7.28 (issue 18 item 7). Writes docs/figures/skew_tilt_dynamic.png.

    python docs/figures/skew_tilt_dynamic.py [--revolutions 3]

Panels: (a) skew of roller 0 [deg] over time [ms]; (b) its tilt [deg]; both bearings, from
rolling kinematics without skew (the start transient is part of the plot).
"""
import argparse
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

REPO = pathlib.Path(__file__).resolve().parents[2]
if str(REPO) not in sys.path:
    sys.path.insert(0, str(REPO))  # run from a checkout: this sim/, not an installed one

import sim  # noqa: E402
from sim.io import write_figure_atomic  # noqa: E402

OUT = pathlib.Path(__file__).with_name("skew_tilt_dynamic.png")
CASE = ["lubricant=pinion_oil", "load.Fa=35000", "load.Fr=0", "load.speed=1100", "load.oil_temperature=50",
        "friction.skew.enabled=true", "solver=dynamic", "solver.dynamic.start=rolling"]
BEARINGS = {"TSRB (thesis Table 7.4)": "tsrb_pinion", "TRB 31313": "trb_31313"}
MS_PER_S = 1e3


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--revolutions", type=int, default=3, help="inner-ring revolutions at most (one per window)")
    args = ap.parse_args()
    fig, (ax_s, ax_t) = plt.subplots(2, 1, figsize=(7.0, 6.0), sharex=True)
    for label, bearing in BEARINGS.items():
        ds = sim.simulate(sim.load_config([f"bearing={bearing}", f"solver.dynamic.max_windows={args.revolutions}"]
                                          + CASE))
        t = ds.time.values * MS_PER_S
        ax_s.plot(t, ds.roller_skew_t.isel(design=0, case=0, roller=0), label=label)
        ax_t.plot(t, ds.roller_tilt_t.isel(design=0, case=0, roller=0), label=label)
        print(f"{label}: steady {bool(ds.converged.values.all())}, skew roller 0 at the end "
              f"{float(ds.roller_skew_t.values[0, 0, -1, 0]):.3f} deg, tilt "
              f"{float(ds.roller_tilt_t.values[0, 0, -1, 0]):.4f} deg, torque {float(ds.torque_t.values[0, 0, -1]):.0f} N mm")
    ax_s.set_ylabel("skew of roller 0 [deg]")
    ax_t.set_ylabel("tilt of roller 0 [deg]")
    ax_t.set_xlabel("time [ms]")
    ax_s.legend()
    ax_s.set_title("35 kN axial, 1100 rpm, pinion oil 50 degC, skew free, from rolling and no skew", fontsize=10)
    fig.tight_layout()
    write_figure_atomic(fig, OUT, 150)
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
