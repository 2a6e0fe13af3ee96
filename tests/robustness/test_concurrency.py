"""Concurrency (issue 15, item 6): runs sharing a result cache compute no case twice.

A run claims a case in the cache (``<key>.claim``, O_CREAT | O_EXCL, with host, pid and a token)
while it computes it; another run computes other cases first, then waits for the claimed ones
and loads them. A claim whose process is gone is broken. Tested on the claim functions, on
``run_cases`` with a claim held by another (live) process, and with two real sweeps at once.
"""
import collections
import json
import os
import re
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import sim
import sim.api.sweep as sweep
from sim.api import operating_points
from sim.api.sweep import CACHE_SUFFIX, CLAIM_SUFFIX, HOST_TAG, cache_file, compute_case, encode_case, run_cases
from tests.robustness.common import FAST, REPO

GRID = ["load.Fa=[3000,4000]", "load.Fr=[0,1000]"]


@pytest.fixture
def other():
    """A live process that is not this one (its pid holds claims 'of another run')."""
    proc = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(120)"])
    yield proc.pid
    proc.kill()
    proc.wait()


@pytest.fixture
def cfg(tmp_path):
    cfg = sim.load_config([*FAST, *GRID])
    cfg.output.cache_dir = str(tmp_path / "cache")
    return cfg


@pytest.fixture
def counted(monkeypatch):
    """The cases simulated in this process, in order (Fa, Fr)."""
    calls = []
    real = sweep.simulate

    def counting(cfg, grid=None):
        calls.append((float(cfg.load.Fa), float(cfg.load.Fr)))
        return real(cfg, grid=grid)

    monkeypatch.setattr(sweep, "simulate", counting)
    return calls


def hold(path, pid):
    """A claim of the case at ``path`` by process ``pid`` on this host."""
    claim = sweep._claim_file(path)
    claim.parent.mkdir(parents=True, exist_ok=True)
    claim.write_text(json.dumps({"host": HOST_TAG, "pid": pid, "token": "other", "time": time.time()}))
    return claim


def test_a_claim_is_exclusive_and_released(cfg):
    op = operating_points(cfg.load)[0]
    path = cache_file(cfg, op)
    state, token = sweep._claim(path)
    assert state == "mine" and sweep._claim_file(path).exists()
    assert sweep._claim(path) == ("theirs", None)      # a second claim, even from this process, waits
    info = json.loads(sweep._claim_file(path).read_text())
    assert info["host"] == HOST_TAG and info["token"] == token
    sweep._release(path, token)
    assert not sweep._claim_file(path).exists()
    assert sweep._claim(path)[0] == "mine"


def test_release_leaves_a_claim_another_run_took(cfg, other):
    op = operating_points(cfg.load)[0]
    path = cache_file(cfg, op)
    _, token = sweep._claim(path)
    hold(path, other)   # ours was broken (as stale) and the case claimed anew
    sweep._release(path, token)
    assert sweep._claim_file(path).exists()


def test_claim_of_a_dead_process_is_broken(cfg, counted):
    op = operating_points(cfg.load)[0]
    path = cache_file(cfg, op)
    dead = subprocess.Popen([sys.executable, "-c", "pass"])
    dead.wait()
    hold(path, dead.pid)
    ds, hit = compute_case(cfg.copy(), op, path)
    assert not hit and bool(ds.converged.all()) and counted == [(op.Fa, op.Fr)]
    assert path.exists() and not sweep._claim_file(path).exists()
    assert not list(path.parent.glob("*.broken"))


def test_claim_of_a_live_process_is_waited_for_and_its_result_loaded(cfg, counted, other):
    """Cases 1..4, the second claimed by another live run: the others are computed first, then the
    second is taken from the cache once that run has written it and released the claim."""
    ops = operating_points(cfg.load)
    path = cache_file(cfg, ops[1])
    claim = hold(path, other)
    done = sim.simulate(sim.load_config([*FAST, f"load.Fa={ops[1].Fa}", f"load.Fr={ops[1].Fr}",
                                         "output.cache_dir=null"]))

    def finish_later():
        while len(counted) < 3:   # the other run finishes while this one has done the other cases
            time.sleep(0.02)
        time.sleep(0.3)
        sweep.io.write_bytes_atomic(path, encode_case(done))
        claim.unlink()

    worker = threading.Thread(target=finish_later)
    worker.start()
    ds, n = run_cases(cfg, progress=False)
    worker.join()
    assert counted == [(o.Fa, o.Fr) for i, o in enumerate(ops) if i != 1]
    assert n["cached"] == 1 and n["computed"] == 3
    np.testing.assert_array_equal(ds.pmax.values[0, 1], done.pmax.values[0, 0])
    assert not list(Path(cfg.output.cache_dir).rglob(f"*{CLAIM_SUFFIX}"))


def test_claim_released_without_a_result_is_computed_here(cfg, counted, other):
    """The other run's case did not converge (nothing cached): this run computes it after it."""
    op = operating_points(cfg.load)[0]
    path = cache_file(cfg, op)
    claim = hold(path, other)
    assert compute_case(cfg.copy(), op, path, wait=False) == (None, False)
    threading.Timer(0.3, claim.unlink).start()
    ds, hit = compute_case(cfg.copy(), op, path)
    assert not hit and counted == [(op.Fa, op.Fr)] and bool(ds.converged.all())


# ---------------------------------------------------------------------------- two real sweeps at once
SWEEP = ["bearing.PCR=90,100,110", "load.Fa=1000,2000", "load.Fr=[0,400,800,1200]"]
SLOW = ["friction.enabled=false", "solver.n_slices=200"]   # 0.1-0.2 s a case: the two sweeps overlap


def test_two_identical_sweeps_at_once_compute_each_case_once(tmp_path):
    """Two processes run the same sweep (24 cases) into one cache at the same time: every case is
    computed by exactly one of them, both finish with the same sweep.nc, the cache holds 24 valid
    entries and no claim or temporary is left."""
    cache = tmp_path / "cache"
    procs = []
    for name in ("a", "b"):
        args = ["-m", "sim.run", "--multirun", *SWEEP, *SLOW, f"output.cache_dir={cache}",
                f"hydra.sweep.dir={tmp_path / name}", "hydra.verbose=[sim.api.sweep]"]
        procs.append(subprocess.Popen([sys.executable, *args], cwd=tmp_path, stdout=subprocess.PIPE,
                                      stderr=subprocess.STDOUT, text=True,
                                      env=dict(os.environ, PYTHONPATH=str(REPO))))
    logs = [p.communicate(timeout=900)[0] for p in procs]
    assert [p.returncode for p in procs] == [0, 0], "\n".join(log[-3000:] for log in logs)
    computed = [re.findall(r"computed case ([0-9a-f]{64}) ", log) for log in logs]
    counts = collections.Counter(key for keys in computed for key in keys)
    assert len(counts) == 24 and max(counts.values()) == 1, counts.most_common(3)
    assert all(computed), f"one sweep computed nothing ({[len(c) for c in computed]}): they did not overlap"
    entries = sorted(p.name[: -len(CACHE_SUFFIX)] for p in cache.rglob(f"*{CACHE_SUFFIX}"))
    assert entries == sorted(counts)
    assert not list(cache.rglob(f"*{CLAIM_SUFFIX}")) and not list(cache.rglob("*.tmp"))
    a, b = (xr.load_dataset(tmp_path / name / "sweep.nc") for name in ("a", "b"))
    for var in ("converged", "pmax", "Q", "axial_displacement"):
        np.testing.assert_array_equal(a[var].values, b[var].values, err_msg=var)
    assert a.converged.all()
