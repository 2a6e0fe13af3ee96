"""The per-configuration caches of sim.simulate (sim.api.simulation): the provenance YAML is
OmegaConf.to_yaml's, block by block; equal content reuses the YAML and the models, changed
content (in the same object) never does; the result file keeps its DATA.md form."""
import subprocess
import sys

import numpy as np
import pytest
import xarray as xr
from omegaconf import OmegaConf

import sim
from sim import io
from sim.api.simulation import _MODELS, _YAML, config_yaml, simulate, simulate_batch
from tests.sweeps.common import FAST, REPO

CHECKER = REPO.parent / "shared" / "tools" / "check_result.py"


@pytest.mark.parametrize("overrides", [
    [], ["bearing=trb_32208"], ["load=sensitivity_scenarios"], ["load=sensitivity_speeds"], FAST,
    ["bearing=tsrb_pinion", "lubricant=pinion_oil", "load=pinion_duty"], ["+variant=PCR_down", "load.tilt=0.25"],
    ["load.Fa=[3000,4500]", "load.Fr=[0,2000]", "bearing.PCR=120.5", "bearing.Z=15"],
])
def test_config_yaml_is_omegaconf_to_yaml(overrides):
    cfg = sim.load_config(overrides)
    assert config_yaml(cfg) == config_yaml(cfg) == OmegaConf.to_yaml(cfg, resolve=True)


def test_caches_follow_the_config_content():
    """A repeated call builds and serialises nothing new and gives the same result; a changed
    load or geometry in the same object gives its own YAML, model and results."""
    cfg = sim.load_config(["load.Fa=4500", "load.Fr=2000", *FAST])
    first = simulate(cfg)
    sizes = len(_YAML.data), len(_MODELS.data)
    again = simulate(sim.load_config(["load.Fa=4500", "load.Fr=2000", *FAST]))   # a new object, same content
    assert (len(_YAML.data), len(_MODELS.data)) == sizes
    assert first.attrs["config"] == again.attrs["config"] == OmegaConf.to_yaml(cfg, resolve=True)
    xr.testing.assert_identical(first.drop_vars("wall_time").drop_attrs(), again.drop_vars("wall_time").drop_attrs())
    cfg.load.Fa = 6000.0
    assert simulate(cfg).attrs["config"] == OmegaConf.to_yaml(cfg, resolve=True)
    assert len(_MODELS.data) == sizes[1]   # the load is no model input
    cfg.bearing.PCR = 120.0
    changed = simulate(cfg)
    assert changed.attrs["config"] == OmegaConf.to_yaml(cfg, resolve=True) != first.attrs["config"]
    fresh = sim.simulate(sim.load_config(["load.Fa=6000", "load.Fr=2000", "bearing.PCR=120", *FAST]))
    assert changed.Fa.values.tolist() == [6000.0] and changed.PCR.values.tolist() == [120.0]
    np.testing.assert_array_equal(changed.Q.values, fresh.Q.values)


def test_result_file_keeps_its_form(tmp_path):
    """Friction on, a load grid: the written file passes the DATA.md checker and reads back equal."""
    cfg = sim.load_config(["load.Fa=[3000,4500]", "load.Fr=[0,2000]"])
    ds = simulate(cfg)
    path = io.write_netcdf_atomic(ds, tmp_path / "result.nc")
    xr.testing.assert_identical(xr.load_dataset(path), ds)
    assert ds.attrs["config"] == OmegaConf.to_yaml(cfg, resolve=True)
    if CHECKER.exists():
        out = subprocess.run([sys.executable, str(CHECKER), str(path)], capture_output=True, text=True)
        assert out.returncode == 0, out.stdout


def _structure(ds):
    """Everything of a Dataset that its construction decides: variables in order with their type,
    dims, dtype and attrs, the dims in order, the coordinate names, the indexes, the attributes."""
    variables = [(name, type(var).__name__, var.dims, var.dtype, var.attrs) for name, var in ds.variables.items()]
    indexes = {k: (type(i).__name__, list(i.index)) for k, i in ds.xindexes.items()}
    return variables, list(ds.sizes.items()), sorted(ds.coords), indexes, {k: v for k, v in ds.attrs.items()
                                                                           if k != "created"}


@pytest.mark.parametrize("overrides", [
    ["load.Fa=[3000,4500]", "load.Fr=[0,2000]"], ["bearing=trb_32208", "load.Fr=0"], FAST,
    ["load.Fa=4500", "load.Fr=2000", "solver.max_iterations=1", "solver.continuation_steps=0"],
])
def test_direct_construction_equals_the_public_constructor(overrides, monkeypatch):
    """sim.io builds its Datasets with xarray's private Dataset._construct_direct where it exists;
    the public constructor gives the same Dataset (the single-design result and a batch)."""
    if not io.DIRECT_CONSTRUCTION:
        pytest.skip("this xarray has no Dataset._construct_direct: the public constructor is used")
    cfgs = [sim.load_config(overrides), sim.load_config([*overrides, "bearing.Z=15"])]
    for build in (lambda: simulate(cfgs[0]), lambda: simulate_batch(cfgs, workers=1)):
        direct = build()
        monkeypatch.setattr(io, "DIRECT_CONSTRUCTION", False)
        public = build()
        monkeypatch.setattr(io, "DIRECT_CONSTRUCTION", True)
        for ds in (direct, public):
            ds["wall_time"].values[:] = 0.0
        xr.testing.assert_identical(direct, public.assign_attrs(created=direct.attrs["created"]))
        assert _structure(direct) == _structure(public)
        assert direct.sel(race="inner").pmax.dims == ("design", "case")   # the indexes work
