"""Many designs in one call (sim.api.simulate_batch) and their combination (sim.io.combine_designs).

The batch must hold what the per-design ``simulate`` results give when combined as a sweep
combines them (sim.io.combine_designs), record a failing design instead of raising, and be the
same on one process and on several. combine_designs takes a failed design among unlike ones.
"""
import subprocess
import sys

import numpy as np
import pytest
import xarray as xr
from omegaconf import OmegaConf

import sim
from sim import io
from sim.api import simulate_batch
from sim.api.cases import operating_points
from sim.api import processes
from sim.api.simulation import simulate
from tests.sweeps.common import FAST, REPO

CHECKER = REPO.parent / "shared" / "tools" / "check_result.py"
# friction on (the default): two TSRB designs over 2 combined cases, one case that cannot
# converge in one ring iteration; a TRB with the fast settings and other cases
DESIGNS = [
    ["bearing.PCR=90", "load.Fa=[3000,5000]", "load.Fr=2000"],
    ["bearing.PCR=120", "bearing.kappa=0.97", "load.Fa=[3000,5000]", "load.Fr=2000"],
    [*FAST, "bearing=trb_31313", "load.Fa=[3000,7000]", "load.Fr=0"],
    ["bearing.PCR=110", "load.Fa=4500", "load.Fr=2000", "solver.max_iterations=1", "solver.continuation_steps=0"],
]
IMPOSSIBLE = ["bearing.PCR=8", "load.Fa=[3000,5000]", "load.Fr=2000"]  # PCR > 8.857 mm (sim.geometry)
OUTSIDE = ["bearing.PCR=100", "load.Fa=-5", "load.Fr=2000"]            # load.Fa outside (0, 1e7]
UNRESOLVED = [*FAST, "bearing.PCR=${oops}"]                             # no such key


def configs(*designs):
    return [sim.load_config(list(d)) for d in designs]


def per_design(cfg):
    """What a sweep holds for one design: its simulate result, or the placeholder of a failure."""
    try:
        return simulate(cfg)
    except Exception as exc:
        return io.failed_dataset(cfg.bearing, operating_points(cfg.load), OmegaConf.to_yaml(cfg, resolve=True),
                                 f"{type(exc).__name__}: {exc}")


def assert_same_results(batch, expected):
    """Same variables, coordinates, dims and attributes; every number equal to 1e-12 (the solver
    wall time is a measurement, left out)."""
    batch = batch.drop_vars([v for v in batch.variables if v.startswith("failed_")] + ["design_config", "wall_time"])
    expected = expected.drop_vars("wall_time")
    assert set(batch.variables) == set(expected.variables)
    assert dict(batch.sizes) == dict(expected.sizes)
    for name, var in expected.variables.items():
        got = batch[name].variable
        assert got.dims == var.dims and got.dtype == var.dtype and got.attrs == var.attrs, name
        if var.dtype.kind == "f":
            np.testing.assert_allclose(got.values, var.values, rtol=1e-12, atol=0.0, equal_nan=True, err_msg=name)
        else:
            np.testing.assert_array_equal(got.values, var.values, err_msg=name)


@pytest.fixture(scope="module")
def batch():
    cfgs = configs(*DESIGNS, IMPOSSIBLE)
    return cfgs, simulate_batch(cfgs, workers=2)


def test_batch_equals_per_design_simulate(batch):
    """Two worker processes give, design by design and case by case, what simulate gives, in the
    layout combine_designs gives a sweep (case union, TRB without PCR, its own x_slice)."""
    cfgs, ds = batch
    expected = io.combine_designs([per_design(cfg) for cfg in cfgs], {})
    assert_same_results(ds, expected)
    assert ds.sizes["design"] == 5 and ds.x_slice.dims == ("slice", "design")
    np.testing.assert_array_equal(ds.Fa, [3000.0, 5000.0, 3000.0, 7000.0, 4500.0])
    for d, cfg in enumerate(cfgs):
        assert str(ds.design_config.values[d]) == OmegaConf.to_yaml(cfg, resolve=True)


def test_failing_design_is_recorded_not_raised(batch):
    """The impossible geometry keeps its slot: its config's inputs, NaN, converged False, and one
    failure row per case with the GeometryError; the unconverged case is a row of its own."""
    _, ds = batch
    failed = ds.isel(design=4)
    assert not failed.converged.any() and failed.pmax.isnull().all() and failed.PCR == 8.0
    rows = ds.failed_design.values == 4
    assert rows.sum() == 2 and set(ds.failed_reason.values[rows]) == {"error"}
    assert all(m.startswith("GeometryError: bearing.PCR") for m in ds.failed_message.values[rows])
    np.testing.assert_array_equal(ds.failed_case.values[rows], [0, 1])
    others = ~rows
    assert list(ds.failed_reason.values[others]) == ["not converged"] and ds.failed_design.values[others] == [3]
    assert ds.converged.sum() == 6   # 2 + 2 + 2 of the first three designs
    assert ds.attrs["config"] == OmegaConf.to_yaml(batch[0][0], resolve=True)


def test_batch_file_passes_the_result_checker(tmp_path):
    """Like designs (one x_slice, friction on) and a failed one, written and checked (DATA.md)."""
    ds = simulate_batch(configs(DESIGNS[0], DESIGNS[1], IMPOSSIBLE), workers=2)
    path = io.write_netcdf_atomic(ds, tmp_path / "batch.nc")
    xr.testing.assert_identical(xr.load_dataset(path), ds)
    if CHECKER.exists():
        out = subprocess.run([sys.executable, str(CHECKER), str(path)], capture_output=True, text=True)
        assert out.returncode == 0, out.stdout


def test_one_process_and_two_agree():
    """workers=1 (all here) and 2 processes give the same dataset; a load outside its range and a
    config that does not resolve fail their designs (no case: one row with case -1) without
    stopping the others."""
    cfgs = configs(DESIGNS[0], OUTSIDE, DESIGNS[2], UNRESOLVED)
    one, two = (simulate_batch(cfgs, workers=w) for w in (1, 2))
    xr.testing.assert_identical(one.drop_vars("wall_time").drop_attrs(), two.drop_vars("wall_time").drop_attrs())
    assert one.failed_design.values.tolist() == [1, 3] and one.failed_case.values.tolist() == [-1, -1]
    assert one.failed_message.values[0].startswith("InputError: load.Fa")
    assert one.failed_message.values[1].startswith("InterpolationKeyError")
    assert one.converged.sum() == 4 and one.sizes["case"] == 4


def test_unlike_designs_with_a_failure_combine():
    """combine_designs of a TRB, a TSRB (x_slice per design) and a failed design: NaN slices there
    (the concat refused the failed design's missing x_slice)."""
    cfgs = configs([*FAST, "bearing=trb_31313", "load.Fa=3000", "load.Fr=0"], [*FAST, "load.Fa=3000", "load.Fr=0"],
                   [*FAST, "bearing.PCR=8", "load.Fa=3000", "load.Fr=0"])
    ds = io.combine_designs([per_design(cfg) for cfg in cfgs], {})
    assert ds.x_slice.dims == ("slice", "design") and ds.x_slice.isel(design=2).isnull().all()
    assert ds.slice.dtype.kind == "i" and ds.sizes["slice"] == 8
    assert ds.converged.values.tolist() == [[True], [True], [False]]


def test_spawned_workers_agree(monkeypatch):
    """Where the workers cannot be forked (macOS, Windows) they are spawned: the configs reach
    them pickled and the kernels come from numba's cache; the result is the same."""
    cfgs = configs([*FAST, "load.Fa=[3000,5000]", "load.Fr=0"], [*FAST, "bearing.PCR=8", "load.Fa=3000", "load.Fr=0"])
    monkeypatch.setattr(processes, "START_METHOD", "spawn")
    spawned = simulate_batch(cfgs, workers=2)
    here = simulate_batch(cfgs, workers=1)
    xr.testing.assert_identical(spawned.drop_vars("wall_time").drop_attrs(), here.drop_vars("wall_time").drop_attrs())
    assert spawned.converged.values.tolist() == [[True, True], [False, False]]
