"""Sensitivity analysis of thesis 7.2 (Table 7.2): the figures, drawn from its sweep dataset.

One command runs the analysis and draws the figures (``conf/experiment/sensitivity.yaml``):

    python -m sim.run --multirun +experiment=sensitivity hydra/launcher=parallel

It sweeps 14 designs (TRB 32208, the reference TSRB of Table 7.1 and the one-at-a-time
variations of Table 7.2, ``conf/variant/``) over the six load scenarios at 1000, 2000 and
4000 rpm and pure axial 4.5 and 40 kN, writes ``outputs/sensitivity/<date>/<time>/sweep.nc``
and calls :func:`plot_figures`, which saves PNG files beside it. A variant that cannot be
built or solved keeps its place in the dataset with its error in the failure table; its bars
are missing and its legend entry says "no result". Redraw the figures of a finished sweep:

    python -m studies.sensitivity outputs/sensitivity/<date>/<time>/sweep.nc

A path that is not a readable sensitivity ``sweep.nc`` is refused with one line ``error: ...``
and exit status 2 (:mod:`sim.api.cli`).
"""
import argparse
import sys
from pathlib import Path

import numpy as np
import xarray as xr
from matplotlib.figure import Figure
from omegaconf import OmegaConf

from sim import CONF_DIR
from sim.api import InputError
from sim.api.cases import operating_points
from sim.api.cli import run
from sim.io import write_figure_atomic

COMPARED = ("trb_32208", "reference")  # in every figure, as the thesis's blue and green bars
FAMILIES = {  # Table 7.2; torque and pmax figures 7.7/7.8, 7.10/7.11, 7.12/7.13, 7.14/7.15, 7.16/7.17
    "PCR": ("PCR_up", "PCR_up2", "PCR_down", "PCR_down2"),
    "alpha": ("alpha_up", "alpha_down"),
    "kappa": ("kappa_up", "kappa_down"),
    "aP": ("aP_up", "aP_down"),
    "aPk": ("aPk_up", "aPk_down"),
}
AXIAL_LINES = ("trb_32208", "reference", "PCR_up", "PCR_down", "aP_up", "aPk_down")  # Fig. 7.18
PRESSURE_PANELS = ("PCR_down", "reference", "PCR_up")  # Fig. 7.9 (a), (b), (c)
SPEED = 2000.0  # rpm of the scenario figures, thesis 7.2.5
AXIS_LABELS = {"pmax": "max. contact pressure", "torque": "frictional torque", "pressure": "contact pressure",
               "axial_displacement": "roller axial displacement"}  # short forms of the long_name attributes


def scenarios():
    """The six (Fa, Fr) load scenarios [N] of ``conf/load/sensitivity_scenarios.yaml`` (Fig. 7.6)."""
    return [(op.Fa, op.Fr) for op in operating_points(OmegaConf.load(CONF_DIR / "load" / "sensitivity_scenarios.yaml"))]


def _case(ds, Fa, Fr, speed):
    """Index of the untilted case (Fa, Fr [N], speed [rpm]) in ``ds``, or None."""
    hit = np.flatnonzero((ds.Fa.values == Fa) & (ds.Fr.values == Fr) & (ds.speed.values == speed)
                         & (ds.tilt.values == 0.0))
    return int(hit[0]) if hit.size else None


def _values(ds, var, variant, cases):
    """Values of ``var`` (outer race where it has one) of one variant at case indices (NaN if absent)."""
    design = np.flatnonzero(ds.variant.values == variant)
    da = ds[var].sel(race="outer") if "race" in ds[var].dims else ds[var]
    return np.array([float(da.isel(design=design[0], case=c)) if design.size and c is not None else np.nan
                     for c in cases])


def _end_peaks(ds, variant, cases):
    """Per case index (None: no case): whether the most loaded roller's pressure peaks in an end
    slice (either race): its pmax is an edge's, not the crown's."""
    design = np.flatnonzero(ds.variant.values == variant)
    if not design.size or "pressure" not in ds:
        return np.zeros(len(cases), dtype=bool)
    p = ds.pressure.isel(design=design[0]).max("race").transpose("case", "slice").values
    last = p.shape[1] - 1
    return np.array([c is not None and np.isfinite(p[c]).any() and int(np.nanargmax(p[c])) in (0, last)
                     for c in cases])


def _label(ds, variant, values, cases):
    """Legend entry of one variant over the case indices ``cases``: "(no result)" where it has none;
    "(peak at a roller end in k of n)" where its pressure peaks in an end slice in k of the n cases
    with a result (:func:`_end_peaks`): there its pmax is the edge's, not the crown's (in this model
    Table 7.2's PCR = 250 mm, variant PCR_up2, carries its load on 0.10-0.16 Lwe at the large end
    in all six scenarios, PCR = 122.5 mm in the three heaviest)."""
    solved = np.isfinite(values)
    if not solved.any():
        return f"{variant} (no result)"
    k = int(np.count_nonzero(_end_peaks(ds, variant, cases)[solved]))
    return f"{variant} (peak at a roller end in {k} of {solved.sum()})" if k else variant


def _ylabel(ds, var):
    return f"{AXIS_LABELS[var]} [{ds[var].attrs.get('units', '')}]"


def _bar_figure(ds, var, series, title, path):
    """Grouped bars: x = scenario 1-6; series = list of (label, values per scenario)."""
    fig = Figure(figsize=(11, 4.5), layout="constrained")
    ax = fig.add_subplot()
    x = np.arange(1, len(scenarios()) + 1)
    width = 0.8 / len(series)
    for i, (label, values) in enumerate(series):
        ax.bar(x + (i - 0.5 * (len(series) - 1)) * width, values, width, label=label)
    ax.set_xticks(x, [f"{k}\n{Fa / 1e3:g}/{Fr / 1e3:g} kN" for k, (Fa, Fr) in zip(x, scenarios())])
    ax.set_xlabel("load scenario, Fa/Fr")
    ax.set_ylabel(_ylabel(ds, var) + (" (outer ring)" if "race" in ds[var].dims else ""))
    ax.set_title(title)
    fig.legend(loc="outside right upper", fontsize="small")
    write_figure_atomic(fig, path, 100)
    return path


def _line_figure(ds, var, variants, cases, title, path):
    """One line per variant of ``var`` over the axial load of the given pure axial cases."""
    fig = Figure(figsize=(7, 4.5), layout="constrained")
    ax = fig.add_subplot()
    Fa = ds.Fa.values[cases] / 1e3
    for variant in variants:
        values = _values(ds, var, variant, cases)
        ax.plot(Fa, values, "o-", label=_label(ds, variant, values, cases))
    ax.set_xscale("log")
    ax.minorticks_off()
    ax.set_xticks(Fa, [f"{f:g}" for f in Fa])
    ax.set_xlabel("axial load Fa [kN] (Fr = 0, 2000 rpm), log scale")
    ax.set_ylabel(_ylabel(ds, var))
    ax.set_title(title)
    ax.legend(fontsize="small")
    write_figure_atomic(fig, path, 100)
    return path


def _pressure_figure(ds, cases, path):
    """Fig. 7.9: outer-ring pressure along the roller, PCR down / reference / PCR up, Fa = 4, 7, 10 kN."""
    fig = Figure(figsize=(12, 4), layout="constrained")
    axes = fig.subplots(1, len(PRESSURE_PANELS), sharey=True)
    for ax, variant in zip(axes, PRESSURE_PANELS):
        design = np.flatnonzero(ds.variant.values == variant)
        if design.size:
            d = int(design[0])
            x = ds.x_slice.isel(design=d) if "design" in ds.x_slice.dims else ds.x_slice
            for c in cases:
                ax.plot(x, ds.pressure.sel(race="outer").isel(design=d, case=c), "o-", ms=3,
                        label=f"Fa = {ds.Fa.values[c] / 1e3:g} kN")
        ax.set_title(variant if design.size else f"{variant} (not in the sweep)")
        ax.set_xlabel("x from the large end [mm]")
        if design.size:
            ax.legend(fontsize="small")
    axes[0].set_ylabel(_ylabel(ds, "pressure") + " (outer ring)")
    write_figure_atomic(fig, path, 100)
    return path


def load_sweep(path):
    """The dataset of a sensitivity ``sweep.nc``; InputError naming the path when it is none."""
    path = Path(path)
    if not path.is_file():
        raise InputError(f"{path} is not a file: give the sweep.nc of python -m sim.run --multirun "
                         "+experiment=sensitivity")
    try:
        with xr.open_dataset(path) as ds:
            ds = ds.load()
    except Exception as exc:  # truncated, empty, not NetCDF
        raise InputError(f"{path} is not a readable NetCDF file ({type(exc).__name__}: {exc})") from exc
    missing = [name for name in ("variant", "pmax", "Fa", "Fr", "speed", "tilt") if name not in ds.variables]
    if missing:
        raise InputError(f"{path} is not a sensitivity sweep: it has no {', '.join(missing)} (made by python -m "
                         "sim.run --multirun +experiment=sensitivity)")
    return ds


def plot_figures(path):
    """Draw the figures of thesis 7.2 from a sensitivity sweep dataset; PNG files beside it.

    Parameters
    ----------
    path : str or pathlib.Path
        ``sweep.nc`` of ``+experiment=sensitivity`` (needs the ``variant`` design coordinate).

    Returns
    -------
    list of pathlib.Path
        The files written: per parameter of Table 7.2 the maximum pressure (and, when the
        dataset has it, the frictional torque) per scenario and variant; both over the three
        speeds; outer-ring pressure along the roller; axial displacement, pmax and torque
        against the axial load.
    """
    path = Path(path)
    out = path.parent
    ds = load_sweep(path)
    quantities = ["pmax"] + (["torque"] if "torque" in ds else [])
    at_speed = [_case(ds, Fa, Fr, SPEED) for Fa, Fr in scenarios()]
    written = []
    for var in quantities:
        for family, variants in FAMILIES.items():
            series = [(_label(ds, v, vals, at_speed), vals) for v in COMPARED + variants
                      for vals in [_values(ds, var, v, at_speed)]]
            written.append(_bar_figure(ds, var, series, f"{var}: variation of {family} (thesis Table 7.2), 2000 rpm",
                                       out / f"{var}_{family}.png"))
        speeds = sorted({float(s) for s in ds.speed.values})
        series = [(f"{_label(ds, v, vals, cases)}, {s:g} rpm", vals) for v in COMPARED for s in speeds
                  for cases in [[_case(ds, Fa, Fr, s) for Fa, Fr in scenarios()]]
                  for vals in [_values(ds, var, v, cases)]]
        written.append(_bar_figure(ds, var, series, f"{var} at 1000, 2000, 4000 rpm (thesis Figs. 7.19, 7.20)",
                                   out / f"{var}_speed.png"))
    axial = [int(c) for c in np.argsort(ds.Fa.values)
             if ds.Fr.values[c] == 0.0 and ds.speed.values[c] == SPEED and ds.tilt.values[c] == 0.0]
    written.append(_line_figure(ds, "axial_displacement", AXIAL_LINES, axial,
                                "roller axial displacement (thesis Fig. 7.18)", out / "axial_displacement.png"))
    for var in quantities:
        written.append(_line_figure(ds, var, COMPARED + FAMILIES["PCR"], axial,
                                    f"{var} under pure axial load (thesis Figs. 7.21, 7.22)", out / f"{var}_axial.png"))
    fig_7_9 = [c for c in axial if ds.Fa.values[c] in (4000.0, 7000.0, 10000.0)]
    written.append(_pressure_figure(ds, fig_7_9, out / "pressure_PCR.png"))
    return written


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m studies.sensitivity",
                                     description="Draw the figures of thesis 7.2 beside a sensitivity sweep.nc.")
    parser.add_argument("sweep", type=Path, help="sweep.nc of python -m sim.run --multirun +experiment=sensitivity")
    for p in plot_figures(parser.parse_args(argv).sweep):
        print(p)
    return 0


if __name__ == "__main__":
    sys.exit(run(main))
