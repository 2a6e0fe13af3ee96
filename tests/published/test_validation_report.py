"""The validation report of issue 14 item 8 (``python -m studies.validation``), run on its reduced set.

``--quick`` runs TRB 32208 at 4.5 and 40 kN, the prototype at 4.5 kN, the Fig. 6.9 grid at
Fr = 0 and 2 kN, the pinion pair and a coarse traction curve (~15 s with a warm numba cache).
Checked: the files the report names exist, every plotted number is in the NetCDF with units,
and the pass/fail table agrees with the numbers it is computed from (recomputed here).
"""
import math
import re

import numpy as np
import pytest
import xarray as xr

from studies import validation

FIGURES = ("trb_32208_torque_vs_Fa.png", "prototype_vs_trb.png", "torque_breakdown.png", "traction_curve.png")


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    out = tmp_path_factory.mktemp("validation")
    assert validation.main(["--quick", "--out", str(out)]) == 0
    with xr.open_dataset(out / "validation.nc") as ds:
        ds.load()
    return out, ds, (out / "report.md").read_text()


def test_files_exist_and_the_report_links_each_figure(report):
    out, _, text = report
    linked = re.findall(r"!\[[^\]]*\]\(([^)]+)\)", text)
    assert sorted(linked) == sorted(FIGURES)
    for name in FIGURES:
        assert (out / name).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n", name
    assert "Timken" in text and "not available" in text


@pytest.mark.smoke
def test_netcdf_holds_the_plotted_variables_with_units(report):
    _, ds, _ = report
    plotted = ("torque_trb_32208", "torque_component_trb_32208", "torque_skf", "torque_aihara_rolling",
               "torque_aihara_rib", "torque_thesis", "band_low", "band_high", "torque_exponent", "torque_trb_rig",
               "torque_prototype_rig", "ratio_rig", "torque_trb_fig69", "torque_prototype_fig69", "ratio_fig69",
               "breakdown", "torque_case", "ratio_pinion", "traction_coefficient", "target_value", "target_pass")
    for name in plotted:
        assert name in ds, name
    for name, var in {**ds.data_vars, **ds.coords}.items():
        assert var.attrs.get("long_name"), name
        if var.dtype.kind in "fiu":
            assert var.attrs.get("units"), name
    assert ds.torque_trb_32208.attrs["units"] == "N*mm"
    assert list(ds.component.values) == ["rolling", "hysteresis", "sliding", "drilling", "rib", "cage", "drag"]


def test_pass_fail_table_agrees_with_the_numbers(report):
    _, ds, text = report
    values = dict(zip(ds.target.values, ds.target_value.values))
    # every row: pass <=> value within its band (NaN fails)
    for k in range(ds.sizes["target"]):
        v, lo, hi = (float(ds[n][k]) for n in ("target_value", "target_low", "target_high"))
        assert bool(ds.target_pass[k]) == (math.isfinite(v) and lo <= v <= hi), str(ds.target.values[k])
    # one ratio recomputed from the torques it divides
    ratio = float(ds.torque_prototype_rig.sel(Fa_rig=4500.0) / ds.torque_trb_rig.sel(Fa_rig=4500.0))
    assert values["prototype / TRB 32208 at Fa 4.5 kN (Fig. 6.8)"] == pytest.approx(ratio, rel=1e-12)
    # the exponent of the two quick loads is the log-log slope between them
    M = ds.torque_trb_32208.sel(Fa_sweep=[4500.0, 40000.0]).values
    assert values["TRB 32208 exponent n, 4.5-40 kN"] == pytest.approx(math.log(M[1] / M[0]) / math.log(40 / 4.5),
                                                                      rel=1e-9)
    # the 4.5 kN band: 0.6 x thesis to 1.2 x SKF 2004 (issue 14 item 5)
    k = list(ds.target.values).index("TRB 32208 torque at 4.5 kN")
    assert float(ds.target_low[k]) == pytest.approx(0.6 * 650.0)
    assert float(ds.target_high[k]) == pytest.approx(1.2 * float(ds.torque_skf.sel(Fa_sweep=4500.0)))
    assert values["pinion TSRB (Table 7.4) / TRB 31313"] == pytest.approx(
        float(ds.torque_case[3] / ds.torque_case[2]), rel=1e-12)
    # the markdown table says what the dataset says, row by row
    for name, passed in zip(ds.target.values, ds.target_pass.values):
        row = next(line for line in text.splitlines() if line.startswith(f"| {name} |"))
        assert row.rstrip().endswith("| PASS |" if passed else "| FAIL |"), row


def test_breakdown_sums_to_the_torque(report):
    """DATA.md: torque_component sums to torque (a cross-check of the case bookkeeping of the report)."""
    _, ds, _ = report
    np.testing.assert_allclose(ds.breakdown_total, ds.torque_case, rtol=1e-6)


def test_traction_curve_is_zero_without_slip_and_rises_with_it(report):
    _, ds, _ = report
    mu = ds.traction_coefficient
    assert np.all(mu.sel(srr_disc=0.0) == 0.0)
    assert np.all(mu.diff("srr_disc") > 0.0)
    assert np.all(mu < 0.2)   # bounded by tau_L/p of a mineral oil (c = 0.06 plus tau_L0/p), far below 0.2


def test_sensitivity_base_row_is_the_reported_model_and_the_rib_height_acts_on_the_trb_only(report):
    """Section e: the base setting reproduces the section a/b numbers (same model, same inputs:
    1e-9); a higher rib contact (a longer lever of the rib friction about the roller axis and the
    bearing axis) raises the TRB's torque at 40 kN, where the rib carries a third of it; the
    prototype has no rib, so its torque is unchanged and the ratio falls."""
    _, ds, text = report
    base = ds.sensitivity.sel(setting="base")
    outs = list(ds.sensitivity_output.values)
    for prm in ds.parameter.values:
        assert float(base.sel(parameter=prm).isel(sensitivity_output=0)) == pytest.approx(
            float(ds.torque_trb_32208.sel(Fa_sweep=4500.0)), rel=1e-9)
        assert float(base.sel(parameter=prm).isel(sensitivity_output=1)) == pytest.approx(
            float(ds.torque_trb_32208.sel(Fa_sweep=40000.0)), rel=1e-9)
    rib = ds.sensitivity.sel(parameter="bearing.rib_contact_height_ratio")
    low, high = rib.sel(setting="low"), rib.sel(setting="high")
    assert float(high.isel(sensitivity_output=1)) > float(low.isel(sensitivity_output=1))
    ratio = outs.index("prototype / TRB at the largest Fig. 6.8 load")
    assert float(high.isel(sensitivity_output=ratio)) < float(low.isel(sensitivity_output=ratio))
    assert "## e. Sensitivity to the assumed parameters" in text
