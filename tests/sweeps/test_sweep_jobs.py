"""The job list of a multirun (sim.api.sweep.sweep_jobs) from Hydra's public override parser.

The collector numbers jobs as the launcher does, so the list must be the basic sweeper's:
the Cartesian product of one column per key, the last key fastest, ``hydra.sweeper.params``
before the command line and a later override of a key replacing the earlier one.
"""
import pytest
from omegaconf import OmegaConf

import sim
import sim._math.jit
from sim.api.sweep import sweep_jobs

CASES = [
    ([], ["a=1,2", "b=x,y"]),
    ([], ["bearing.PCR=8,90,110", "load.Fa=3000,5000", "load.Fr=[0,2000]"]),
    ([], ["+variant=PCR_up,PCR_down", "solver.n_slices=8", "x=range(1,4)"]),
    ([], ["a=1,2", "b=3", "a=5,6,7"]),
    ({"a": "1,2", "c": "z"}, ["b=x,y"]),
    ({"a": "1,2"}, ["a=9"]),
    ([], ["a=choice(p,q)", "b=[1,2],[3,4]", "~c", "d='s,t'"]),
]


def master(params, task):
    return OmegaConf.create({"hydra": {"sweeper": {"params": dict(params) or None}, "overrides": {"task": task}}})


def test_order_is_the_documented_basic_sweeper_order():
    """Hydra docs (tutorials/basic/running_your_app/multi-run): ``a=1,2 b=x,y`` runs 4 jobs, b fastest."""
    assert sweep_jobs(master([], ["a=1,2", "b=x,y"])) == [["a=1", "b=x"], ["a=1", "b=y"], ["a=2", "b=x"],
                                                          ["a=2", "b=y"]]
    assert sweep_jobs(master({"a": "1,2", "c": "z"}, ["b=x,y", "a=3"])) == [["a=3", "c=z", "b=x"],
                                                                            ["a=3", "c=z", "b=y"]]
    assert sweep_jobs(master([], [])) == [[]]


@pytest.mark.parametrize("params, task", CASES)
def test_jobs_equal_hydras_basic_sweeper(params, task):
    """Same lists as the basic sweeper itself (private module, imported only here to compare)."""
    basic = pytest.importorskip("hydra._internal.core_plugins.basic_sweeper")
    from hydra.core.override_parser.overrides_parser import OverridesParser

    arguments = [f"{k}={v}" for k, v in dict(params).items()] + task
    expected = basic.BasicSweeper.split_arguments(OverridesParser.create().parse_overrides(arguments), None)[0]
    assert sweep_jobs(master(params, task)) == expected


def test_range_sweep_is_refused():
    with pytest.raises(ValueError, match="does not support sweep type"):
        sweep_jobs(master([], ["a=interval(0,1)"]))


def test_sim_uses_no_private_hydra_module():
    """Issue 13 item 5: nothing in sim/ imports or names ``hydra._internal``."""
    for path in sim._math.jit.sim_sources():
        assert "hydra._internal" not in path.read_text(), path
