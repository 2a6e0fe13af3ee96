"""The result cache of sim.api.sweep: a re-run computes nothing, an interrupted run resumes, a damaged
or unconverged entry is recomputed, and the key follows what is computed, not where it is written.
"""
import logging

import pytest
import xarray as xr
from omegaconf import OmegaConf

import sim
import sim.api.sweep
from sim.api.cases import operating_points
from sim.api.sweep import _key_base, cache_file, case_key, run_cases
from tests.sweeps.common import FAST

GRID = ["load.Fa=[3000,5000]", "load.Fr=[0,2000]"]  # 4 cases in one run


@pytest.fixture
def calls(monkeypatch):
    """Counts sim.simulate calls made by sim.api.sweep; ``calls.fail_at = n`` interrupts the n-th call."""

    class Counter:
        n = 0
        fail_at = None

    def counting(cfg):
        Counter.n += 1
        if Counter.n == Counter.fail_at:
            raise KeyboardInterrupt  # what a killed process leaves: no result for this case
        return real(cfg)

    real = sim.api.sweep.simulate
    monkeypatch.setattr(sim.api.sweep, "simulate", counting)
    return Counter


def config(cache, *extra):
    return sim.load_config([*FAST, *GRID, f"output.cache_dir={cache}", *extra])


def without_run_times(ds):
    return ds.drop_vars("wall_time").drop_attrs()


def test_second_run_computes_nothing(tmp_path, calls):
    """The same config again: every case from the cache, no simulate call, the identical Dataset."""
    first, n1 = run_cases(config(tmp_path), progress=False)
    assert calls.n == 4 and n1["computed"] == 4
    second, n2 = run_cases(config(tmp_path), progress=False)
    assert calls.n == 4 and n2 == {"cases": 4, "cached": 4, "computed": 0, "not_converged": 0}
    xr.testing.assert_identical(first.drop_attrs(), second.drop_attrs())


def test_interrupted_run_resumes_to_the_same_result(tmp_path, calls):
    """Interrupted in its third case, a run keeps the two finished ones; the re-run computes only
    the other two and gives what an uninterrupted run (own cache) gives."""
    calls.fail_at = 3
    with pytest.raises(KeyboardInterrupt):
        run_cases(config(tmp_path / "a"), progress=False)
    assert len(list((tmp_path / "a").rglob("*.pkl"))) == 2
    calls.n, calls.fail_at = 0, None
    resumed, n = run_cases(config(tmp_path / "a"), progress=False)
    assert calls.n == 2 and n["cached"] == 2
    whole, _ = run_cases(config(tmp_path / "b"), progress=False)
    xr.testing.assert_identical(without_run_times(resumed), without_run_times(whole))


def test_damaged_entry_is_recomputed(tmp_path, calls, caplog):
    """A cache entry that cannot be read is reported, deleted and recomputed, never trusted."""
    first, _ = run_cases(config(tmp_path), progress=False)
    entry = sorted(tmp_path.rglob("*.pkl"))[0]
    entry.write_bytes(entry.read_bytes()[:100])
    with caplog.at_level(logging.WARNING, logger="sim.api.sweep"):
        again, n = run_cases(config(tmp_path), progress=False)
    assert n["computed"] == 1 and calls.n == 5
    assert "unreadable" in caplog.text
    xr.testing.assert_identical(without_run_times(first), without_run_times(again))


def test_unconverged_cases_are_recomputed(tmp_path, calls):
    """With one ring iteration the combined-load cases cannot converge: they are written with
    converged False but not cached, so a re-run computes exactly them again (issue 4: failed
    points are recomputed); the converged pure axial cases come from the cache."""
    ds, n = run_cases(config(tmp_path, "solver.max_iterations=1"), progress=False)
    unconverged = int((~ds.converged).sum())
    assert unconverged == n["not_converged"] >= 2
    assert len(list(tmp_path.rglob("*.pkl"))) == 4 - unconverged
    run_cases(config(tmp_path, "solver.max_iterations=1"), progress=False)
    assert calls.n == 4 + unconverged


def test_key_follows_what_is_computed():
    """Where results go does not change the key, nor 17 vs 17.0; a parameter or a case does."""
    base = sim.load_config([*FAST, *GRID])
    op = operating_points(base.load)

    def key(case=0, **changes):
        cfg = base.copy()
        for path, value in changes.items():
            OmegaConf.update(cfg, path.replace("__", "."), value)
        return case_key(_key_base(cfg), op[case])

    assert key() == key(output__file="other.nc", output__cache_dir="/elsewhere") == key(bearing__Z=17.0)
    assert key() != key(bearing__PCR=101.0) and key() != key(case=1) and key() != key(solver__n_slices=9)
    base.output.cache_dir = None
    assert cache_file(base, op[0]) is None  # no cache: always computed


def test_grid_run_equals_simulate(tmp_path):
    """Case by case through the cache or all at once with sim.simulate: the same Dataset."""
    cfg = config(tmp_path)
    cached, _ = run_cases(cfg, progress=False)
    direct = sim.simulate(cfg)
    xr.testing.assert_identical(without_run_times(cached), without_run_times(direct))


def test_code_fingerprint_covers_every_layer_of_sim():
    """A change to any kernel (physics, solvers, numerics) must invalidate the cache."""
    names = {str(path.relative_to(sim.api.sweep.SIM_ROOT)) for path in sim.api.sweep.fingerprint_sources()}
    for required in ("physics/friction.py", "solvers/quasi_static.py", "_math/jit.py", "geometry.py", "api/simulation.py"):
        assert required in names
