"""studies/sensitivity.py: the figures of thesis 7.2 from a sensitivity dataset (issue 4, item 6).

The dataset is made the way the experiment makes it (one run per variant over the six scenarios,
combined with the ``variant`` coordinate), with a variant that failed; torque figures appear
exactly when the data has torque.
"""
from pathlib import Path

import numpy as np
import xarray as xr

import sim
from sim import io
from sim.api.cases import operating_points
from sim.api.sweep import run_cases
from studies import sensitivity
from studies.sensitivity import FAMILIES, plot_figures
from tests.sweeps.common import FAST

VARIANTS = ["trb_32208", "reference", "PCR_up"]


def sensitivity_dataset(path, cache):
    runs = [run_cases(sim.load_config([*FAST, f"+variant={v}", "load=sensitivity_scenarios",
                                       f"output.cache_dir={cache}"]), progress=False)[0] for v in VARIANTS]
    cfg = sim.load_config([*FAST, "+variant=PCR_down2", "load=sensitivity_scenarios"])
    failed = io.failed_dataset(cfg.bearing, operating_points(cfg.load), "", "GeometryError: as an impossible variant")
    ds = io.combine_designs(runs + [failed], {"variant": (np.array(VARIANTS + ["PCR_down2"]), {"long_name": "variant"})})
    io.write_netcdf_atomic(ds, path)
    return ds


def test_figures_of_7_2(tmp_path, monkeypatch):
    ds = sensitivity_dataset(tmp_path / "sweep.nc", tmp_path / "cache")
    ds["torque"] = ds.P * 0.01  # a stand-in torque variable (N*mm) until friction lands in every run
    ds.torque.attrs.update(units="N*mm", long_name="frictional torque")
    io.write_netcdf_atomic(ds, tmp_path / "with_torque" / "sweep.nc")
    written = plot_figures(tmp_path / "with_torque" / "sweep.nc")
    pmax_only = {f"pmax_{f}.png" for f in FAMILIES} | {"pmax_speed.png", "pmax_axial.png",
                                                       "axial_displacement.png", "pressure_PCR.png"}
    torque = {f"torque_{f}.png" for f in FAMILIES} | {"torque_speed.png", "torque_axial.png"}
    assert {p.name for p in written} == pmax_only | torque
    assert all(p.stat().st_size > 10_000 for p in written)  # drawn, not empty canvases

    monkeypatch.setattr(sensitivity, "write_figure_atomic", lambda fig, path, dpi: Path(path).touch())  # names only
    assert {p.name for p in plot_figures(tmp_path / "sweep.nc")} == pmax_only  # no torque in the data
    assert xr.load_dataset(tmp_path / "sweep.nc").variant.values.tolist()[-1] == "PCR_down2"


def test_legend_marks_designs_whose_pressure_peaks_at_a_roller_end(tmp_path):
    """Table 7.2's PCR = 250 mm (variant PCR_up2) crowns the roller so little that its contact sits on the
    large end (0.10-0.16 Lwe loaded, pmax 2.4-3.4 GPa against the reference's 1.0-1.4 GPa at 20 slices):
    its legend entry says so in every scenario, while the reference, whose pressure peaks at its
    contact points inside the roller (thesis 7.1, Fig. 7.1), carries no mark."""
    runs = [run_cases(sim.load_config([*FAST, f"+variant={v}", "load=sensitivity_scenarios",
                                       f"output.cache_dir={tmp_path}"]), progress=False)[0]
            for v in ("reference", "PCR_up2")]
    ds = io.combine_designs(runs, {"variant": (np.array(["reference", "PCR_up2"]), {"long_name": "variant"})})
    cases = list(range(ds.sizes["case"]))
    up2 = sensitivity._values(ds, "pmax", "PCR_up2", cases)
    ref = sensitivity._values(ds, "pmax", "reference", cases)
    assert np.all(up2 > 1.5 * ref)     # the edge's pressure, not the crown's
    assert np.all(ds.contact_length_ratio.sel(race="outer").isel(design=1).values < 0.25)
    assert sensitivity._label(ds, "PCR_up2", up2, cases) == f"PCR_up2 (peak at a roller end in {len(cases)} of {len(cases)})"
    assert sensitivity._label(ds, "reference", ref, cases) == "reference"
    # a case without a result is left out of the count
    assert sensitivity._label(ds, "PCR_up2", np.where(np.arange(len(cases)) == 0, np.nan, up2), cases) \
        == f"PCR_up2 (peak at a roller end in {len(cases) - 1} of {len(cases) - 1})"
