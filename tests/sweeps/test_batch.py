"""Designs combined into one design x case Dataset (sim.io.combine_designs)."""
from omegaconf import OmegaConf

import sim
from sim import io
from sim.api.cases import operating_points
from sim.api.simulation import simulate
from tests.sweeps.common import FAST


def configs(*designs):
    return [sim.load_config(list(d)) for d in designs]


def per_design(cfg):
    """What a sweep holds for one design: its simulate result, or the placeholder of a failure."""
    try:
        return simulate(cfg)
    except Exception as exc:
        return io.failed_dataset(cfg.bearing, operating_points(cfg.load), OmegaConf.to_yaml(cfg, resolve=True),
                                 f"{type(exc).__name__}: {exc}")


def test_unlike_designs_with_a_failure_combine():
    """combine_designs of a TRB, a TSRB (x_slice per design) and a failed design: NaN slices there
    (the concat refused the failed design's missing x_slice)."""
    cfgs = configs([*FAST, "bearing=trb_31313", "load.Fa=3000", "load.Fr=0"], [*FAST, "load.Fa=3000", "load.Fr=0"],
                   [*FAST, "bearing.PCR=8", "load.Fa=3000", "load.Fr=0"])
    ds = io.combine_designs([per_design(cfg) for cfg in cfgs], {})
    assert ds.x_slice.dims == ("design", "slice") and ds.x_slice.isel(design=2).isnull().all()
    assert ds.slice.dtype.kind == "i" and ds.sizes["slice"] == 8
    assert ds.converged.values.tolist() == [[True], [True], [False]]
