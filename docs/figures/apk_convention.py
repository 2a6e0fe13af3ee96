"""Evidence for the aPk convention (issue 14 item 6): writes docs/figures/apk_convention.png and
prints the tables of docs/aPk_convention.md.

    python docs/figures/apk_convention.py            # ~3 min (numba compile), then seconds

Two conventions for the distance aPk "from contact point to the edge" (thesis Fig. 4.11, missing):
  small: aPk from the SMALL end face (sim.geometry today, MODEL.md 2 and 4),
  large: aPk from the LARGE end face.
For one roller both give the same pair of points when aPk_large = Lwe - aP - aPk_small, so the
"large" convention is run here through that override; no code is changed.

Panels: (a) prototype (thesis Table 6.1): unloaded gap between roller and outer raceway along the
roller for both conventions, with Fig. 7.1's peak slices 4 and 16 for 20 and 30 slices;
(b) the model's outer-ring pressure of the most loaded roller at Fa 4.5 kN, Fr 0/2/4 kN, both
conventions (thesis Fig. 7.1). Units: mm, um, MPa.
"""
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import sim  # noqa: E402
from sim.io import write_figure_atomic  # noqa: E402
from sim.geometry import Geometry  # noqa: E402

OUT = pathlib.Path(__file__).with_name("apk_convention.png")


def geometry(*overrides):
    cfg = sim.load_config(list(overrides))
    return Geometry.from_config(cfg.bearing, cfg.material, cfg.solver.n_slices)


def flipped(g):
    """aPk that puts the points where the large-end convention would put them [mm]."""
    return g.Lwe - g.aP - g.aPk


def outer_gap(g, x):
    """Unloaded gap between the roller and the outer lens raceway [mm] at roller-frame x (from mid).

    Each raceway arc (radius PCR_LB, MODEL.md 2) is internally tangent to the roller circle at one
    contact point; the gap to an arc is PCR_LB - |p - c_k| for a roller point p, the raceway's gap
    the smaller of the two (the "two intersected tori")."""
    xc, yc = g.crown_centre
    y = g.roller_radius(x)
    gaps = []
    for xk in g.contact_points_x:
        yk = float(g.roller_radius(xk))
        nx, ny = (xk - xc) / g.PCR, (yk - yc) / g.PCR
        cx, cy = xk - g.PCR_LB * nx, yk - g.PCR_LB * ny
        gaps.append(g.PCR_LB - np.hypot(x - cx, y - cy))
    return np.min(gaps, axis=0)


def case(*overrides):
    ds = sim.simulate(sim.load_config(list(overrides)))
    return ds.isel(design=0, case=0)


def main():
    base = ("bearing=tsrb_prototype",)
    g = geometry(*base)
    conv = {"small": base, "large": base + (f"bearing.aPk={flipped(g):.6g}",)}
    fig, ax = plt.subplots(2, 1, figsize=(8, 8), sharex=True)
    xs = np.linspace(-0.5 * g.Lwe * 0.999, 0.5 * g.Lwe * 0.999, 801)
    for name, ov in conv.items():
        gi = geometry(*ov)
        ax[0].plot(0.5 * g.Lwe - xs, 1e3 * outer_gap(gi, xs), label=f"aPk from the {name} end")
        for xk in gi.contact_points_x:
            ax[0].axvline(0.5 * g.Lwe - xk, ls=":", color="C0" if name == "small" else "C1")
    for n, ls in ((20, "--"), (30, "-.")):
        for k in (4, 16):
            ax[0].axvline((k - 0.5) * g.Lwe / n, color="k", ls=ls, lw=0.8,
                          label=f"Fig. 7.1 peak slice {k}, {n} slices" if k == 4 else None)
    ax[0].set_ylim(0, 40)
    ax[0].set_ylabel("unloaded gap, outer race [um]")
    ax[0].legend(fontsize=7)
    ax[0].set_title("Prototype (Table 6.1: Lwe 20, aP 8, aPk 9.5); x from the LARGE end (Fig. 7.1: slice 1)")
    rows = []
    for name, ov in conv.items():
        for Fr, ls in ((0, "-"), (2000, "--"), (4000, ":")):
            c = case(*ov, "load.Fa=4500", f"load.Fr={Fr}", "solver.n_slices=30", "friction.enabled=false")
            p = c.pressure.sel(race="outer").values
            x = c.x_slice.values
            ax[1].plot(x, p, ls=ls, color="C0" if name == "small" else "C1", label=f"{name}, Fr {Fr / 1e3:g} kN")
            # local maxima of the loaded pressure, as slice numbers counted from 1 at the large end
            peaks = [i + 1 for i in range(1, len(p) - 1) if p[i] >= p[i - 1] and p[i] > p[i + 1] and p[i] > 0]
            if p[0] > p[1]:
                peaks.insert(0, 1)
            if p[-1] > p[-2]:
                peaks.append(len(p))
            rows.append((name, Fr, peaks, float(p.max()), float(c.axial_displacement)))
    ax[1].set_xlabel("x from the large end [mm]")
    ax[1].set_ylabel("outer-ring pressure, most loaded roller [MPa]")
    ax[1].legend(fontsize=7, ncol=2)
    ax[1].set_title("Model, Fa 4.5 kN (Fig. 7.1 load), 30 slices")
    fig.tight_layout()
    write_figure_atomic(fig, OUT, 120)
    print(f"wrote {OUT}")
    print("\n| convention | Fr [kN] | pressure peaks (slice from large end, of 30) | pmax [MPa] | axial disp. [mm] |")
    print("| --- | --- | --- | --- | --- |")
    for name, Fr, peaks, pm, ad in rows:
        print(f"| {name} | {Fr / 1e3:g} | {peaks} | {pm:.0f} | {ad:.4f} |")

    # Tables A.6-A.8: aPk steps at the pinion load (35 kN, 1100 rpm), both conventions
    tables = [
        ("A.6 #4 -> #5", ("bearing=tsrb_pinion", "bearing.PCR=90", "bearing.kappa=0.99"), 6.05, 8.0, (0.047, 0.024), (17.95, 22.64)),
        ("A.7 #23 -> #24", ("bearing=tsrb_pinion_long", "bearing.PCR=120", "bearing.kappa=0.99"), 7.5, 9.5, (0.052, 0.032), (21.29, 26.13)),
        ("A.8 #34 -> #35", ("bearing=tsrb_pinion_alpha", "bearing.PCR=90", "bearing.kappa=0.99"), 6.05, 8.0, (0.038, 0.033), (17.17, 18.74)),
    ]
    print("\n| step | thesis axial disp. [mm] | small-end | large-end | thesis loaded length [mm] | small-end L_eff | large-end L_eff |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for label, ov, a0, a1, disp, leff in tables:
        gi = geometry(*ov)
        res = {}
        for name in ("small", "large"):
            vals = []
            for a in (a0, a1):
                aa = a if name == "small" else gi.Lwe - gi.aP - a
                c = case(*ov, f"bearing.aPk={aa:.6g}", "load.Fa=35000", "load.Fr=0", "load.speed=1100",
                         "friction.enabled=false")
                vals.append((float(c.axial_displacement), float(c.L_eff)))
            res[name] = vals
        f = lambda v, k: f"{v[0][k]:.3f} -> {v[1][k]:.3f}"  # noqa: E731
        print(f"| {label} (aPk {a0} -> {a1}) | {disp[0]} -> {disp[1]} | {f(res['small'], 0)} | {f(res['large'], 0)} "
              f"| {leff[0]} -> {leff[1]} | {f(res['small'], 1)} | {f(res['large'], 1)} |")
    sys.stdout.flush()


if __name__ == "__main__":
    main()
