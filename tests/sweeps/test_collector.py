"""The collector (sim.api.sweep.collect, sim.io.combine_designs): whatever variables the run files hold
are merged point by point; a job that never finished is reported; unlike designs still combine."""
import shutil
import subprocess
import sys

import numpy as np
import xarray as xr

import sim
from sim import io
from sim.physics.friction import COMPONENTS
from sim.api.sweep import collect, main
from tests.sweeps.common import FAST, REPO

CHECKER = REPO.parent / "shared" / "tools" / "check_result.py"


def copy_of(sweep, tmp_path):
    return shutil.copytree(sweep.dir, tmp_path / "sweep")


def test_collect_command_rebuilds_the_same_dataset(parallel_sweep, tmp_path, capsys):
    """python -m sim.api.sweep collect DIR gives the dataset the multirun wrote."""
    main(["collect", str(copy_of(parallel_sweep, tmp_path))])
    assert capsys.readouterr().out.strip().endswith("sweep.nc")
    rebuilt = xr.load_dataset(tmp_path / "sweep" / "sweep.nc")
    original = xr.load_dataset(parallel_sweep.nc)
    xr.testing.assert_identical(rebuilt.drop_attrs(), original.drop_attrs())


def test_friction_variables_in_run_files_are_merged(parallel_sweep, tmp_path):
    """Torque and film outputs of "Simulation core II" (DATA.md names and dims), put into the run
    files, land in sweep.nc at their design and case; the failed design holds NaN."""
    sweep = copy_of(parallel_sweep, tmp_path)
    for result in sweep.glob("*/result.nc"):
        ds = xr.load_dataset(result)
        tag = ds.PCR.values[:, None] * 10.0 + ds.Fa.values[None, :] / 1e3 + ds.Fr.values[None, :] / 1e6
        parts = tag[..., None] * np.arange(1, len(COMPONENTS) + 1) / 28.0
        ds["torque_component"] = (("design", "case", "component"), parts, {"units": "N*mm", "long_name": "breakdown"})
        ds["torque"] = (("design", "case"), parts.sum(axis=-1), {"units": "N*mm", "long_name": "torque"})
        ds["power_loss"] = (("design", "case"), tag / 100, {"units": "W", "long_name": "power loss"})
        ds["srr"] = (("design", "case", "race", "slice"), np.broadcast_to(tag[..., None, None], ds.pressure.shape).copy(),
                     {"units": "1", "long_name": "slide-to-roll ratio"})
        ds["lambda_ratio"] = (("design", "case", "race"), np.broadcast_to(tag[..., None], ds.pmax.shape).copy(),
                              {"units": "1", "long_name": "specific film thickness"})
        io.write_netcdf_atomic(ds, result)
    merged = xr.load_dataset(collect(sweep))
    expected = merged.PCR.values[:, None] * 10.0 + merged.Fa.values[None, :] / 1e3 + merged.Fr.values[None, :] / 1e6
    np.testing.assert_allclose(merged.torque.isel(design=slice(1, None)), expected[1:], rtol=1e-12)
    assert merged.torque.dims == ("design", "case") and merged.srr.dims == ("design", "case", "race", "slice")
    assert merged.torque_component.dims == ("design", "case", "component")
    np.testing.assert_allclose(merged.srr.isel(design=2, race=0, slice=3), expected[2], rtol=1e-12)
    assert merged.torque.isel(design=0).isnull().all()  # PCR = 8: no result
    if CHECKER.exists():
        chk = subprocess.run([sys.executable, str(CHECKER), str(sweep / "sweep.nc")], capture_output=True, text=True)
        assert chk.returncode == 0, chk.stdout


def test_job_that_never_finished_is_reported_missing(parallel_sweep, tmp_path):
    """Job 3 (PCR 90, Fa 5 kN) without its result: its 2 points NaN, rows 'missing' in the table."""
    sweep = copy_of(parallel_sweep, tmp_path)
    (sweep / "3" / "result.nc").unlink()
    ds = xr.load_dataset(collect(sweep))
    missing = ds.failed_reason.values == "missing"
    assert missing.sum() == 2 and set(ds.failed_job.values[missing]) == {3}
    assert set(ds.failed_design.values[missing]) == {1} and set(ds.failed_case.values[missing]) == {2, 3}
    assert ds.pmax.isel(design=1, case=[2, 3]).isnull().all() and ds.pmax.isel(design=1, case=[0, 1]).notnull().all()


def test_unlike_designs_combine(tmp_path):
    """TRB 31313 (Z 13, Lwe 24.2) and the reference TSRB (Z 17, Lwe 17) with different load cases:
    the case union, NaN where a design lacks a case, roller, PCR and x_slice per design."""
    trb = sim.simulate(sim.load_config([*FAST, "bearing=trb_31313", "load.Fa=[3000,5000]", "load.Fr=0"]))
    tsrb = sim.simulate(sim.load_config([*FAST, "load.Fa=[5000,7000]", "load.Fr=0"]))
    ds = io.combine_designs([trb, tsrb], {"bearing": (np.array(["trb_31313", "tsrb_reference"]), {"long_name": "x"})})
    np.testing.assert_array_equal(ds.Fa, [3000.0, 5000.0, 7000.0])
    np.testing.assert_array_equal(ds.converged, [[True, True, False], [False, True, True]])
    assert ds.pmax.isel(design=0, case=2).isnull().all() and ds.pmax.isel(design=1, case=0).isnull().all()
    assert ds.sizes["roller"] == 17 and ds.Q.isel(design=0, case=0, roller=slice(13, None)).isnull().all()
    assert np.isnan(ds.PCR.values[0]) and ds.PCR.values[1] == 100.0
    assert ds.x_slice.dims == ("slice", "design")     # DATA.md's x_slice (slice), design trailing
    np.testing.assert_array_equal(ds.pressure.isel(design=1, case=1), tsrb.pressure.isel(design=0, case=0))
    if CHECKER.exists():    # (design, slice) failed the contract (session 33's checker: a sweep over Lwe or n_slices)
        path = tmp_path / "unlike.nc"
        ds.to_netcdf(path)
        chk = subprocess.run([sys.executable, str(CHECKER), str(path)], capture_output=True, text=True)
        assert chk.returncode == 0, chk.stdout + chk.stderr


def test_the_alpha_coordinate_is_the_value_given():
    """A design's alpha coordinate is the configured angle itself: it was degrees(radians(alpha)), so a
    sweep stored 15 as 14.999999999999998 and 24 as 24.000000000000004 (session 33's checker), which split
    an unstacked sweep into spurious levels and made .sel(alpha=24) fail."""
    for bearing, alpha in (("tsrb_prototype", 15), ("trb_31313", 24), ("tsrb_reference", 30)):
        ds = sim.simulate(sim.load_config([*FAST, f"bearing={bearing}", f"bearing.alpha={alpha}", "load.Fr=0",
                                           "load.Fa=5000"]))
        assert ds.alpha.values[0] == alpha
        assert ds.sel(design=ds.alpha == alpha).sizes["design"] == 1


def test_sweep_with_friction_collects_its_converged_jobs_and_reports_the_refused_one(friction_sweep):
    """A multirun as the README runs it, friction on (the default; the other sweep tests switch it
    off): every converged job's file holds what sim.io writes for its config, so the collector
    merges it (before, it called every such job "damaged": it required the skew outputs, which only
    friction.skew writes). A case beyond the static limit after the solve (tsrb_reference at 80 kN:
    past ISO 76's 4000 MPa, tests/published/test_static_capacity.py) is a point without a result,
    with its torque variables NaN (DATA.md) and its reason in the failure table."""
    sweep = friction_sweep.dir
    ds = xr.load_dataset(sweep / "sweep.nc")
    assert list(ds.Fa.values) == [3000.0, 80000.0] and list(ds.bearing.values) == ["tsrb_reference", "trb_32208"]
    assert ds.converged.values.tolist() == [[True, False], [True, True]]
    assert np.isfinite(ds.torque.values[0, 0]) and np.isnan(ds.torque.values[0, 1])
    assert np.isfinite(ds.torque_component.values[0, 0]).all() and np.isnan(ds.power_loss.values[0, 1])
    # the TRB's rows: its rib carries load and friction, the TSRB has none (DATA.md: Q_rib 0 for a TSRB)
    rib = list(ds.component.values).index("rib")
    assert (ds.Q_rib.values[1] > 0.0).any(axis=-1).all() and (ds.torque_component.values[1, :, rib] > 0.0).all()
    assert (ds.Q_rib.values[0, 0] == 0.0).all() and ds.torque_component.values[0, 0, rib] == 0.0
    np.testing.assert_allclose(ds.torque_component.values[1].sum(axis=-1), ds.torque.values[1], rtol=1e-9)
    assert "roller_skew" not in ds            # friction.skew off: no skew outputs, no placeholders
    assert list(ds.failed_reason.values) == ["not converged"] and list(ds.failed_case.values) == [1]
    # exit 0 (every job left its result), the points without one counted in the last line on stderr
    assert friction_sweep.stderr.strip().splitlines()[-1].endswith(
        "1 of 4 cases without a result (1 not converged; listed in its failed_* variables); exit status 0: every "
        "job left its result")
    assert "static safety" in str(ds.failed_message.values[0])
    if CHECKER.exists():
        chk = subprocess.run([sys.executable, str(CHECKER), str(sweep / "sweep.nc")], capture_output=True, text=True)
        assert chk.returncode == 0, chk.stdout


def test_a_case_without_result_keeps_the_variables_of_its_config_and_says_why():
    """sim.simulate of one case that has no result, friction on: the friction outputs are there,
    NaN (DATA.md: "its data variables NaN"; they were left out, so ``ds.torque`` raised), and the
    reason is in the attribute failed_cases."""
    ds = sim.simulate(sim.load_config(["bearing=tsrb_reference", "load.Fa=[3000,80000]", "load.Fr=0",
                                       "solver.n_slices=8"]))
    assert list(ds.converged.values[0]) == [True, False]
    for name in io.FRICTION_VARIABLES:    # srr and film_thickness are NaN on unloaded slices (between the contacts)
        values = ds[name].values[0]
        assert np.isfinite(values[0]).any() and np.isnan(values[1]).all(), name
    assert np.isfinite(ds.torque_component.values[0, 0]).all() and np.isfinite(ds.lambda_ratio.values[0, 0]).all()
    assert ds.attrs["failed_cases"].startswith("Fa = 80000.0, Fr = 0.0, speed = 2000.0, tilt = 0.0, oil_temperature = 55.0: pmax = ") and "static safety" in ds.attrs["failed_cases"]
    assert "failed_cases" not in sim.simulate(sim.load_config(["bearing=tsrb_reference", "load.Fa=3000", "load.Fr=0",
                                                               "solver.n_slices=8"])).attrs
