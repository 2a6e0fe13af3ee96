"""Multirun sweeps from the command line: merged dataset, failures, resume, refusal at start.

Issue 4, items 2-4: a sweep on all cores ends in one ``sweep.nc`` (design x case) equal point by
point to single runs; a killed sweep resumes to the same dataset; a re-run computes nothing; a
bad override stops the sweep before any job runs, naming the key and its allowed range.
"""
import json
import os
import shutil
import signal
import subprocess
import sys
import time

import numpy as np
import pytest
import xarray as xr
from hydra import initialize_config_dir
from hydra.core.global_hydra import GlobalHydra
from hydra.types import RunMode
from omegaconf import OmegaConf

import sim
import sim.api.sweep
from sim.api.simulation import simulate
from sim.api.sweep import CACHE_SUFFIX, SweepCallback, collect, run_job
from tests.sweeps.common import FAST, REPO, SWEEP, multirun

PER_RUN = {"wall_time"}  # solver time of a case: differs between two computations of the same point
WHERE = {"failed_overrides"}  # holds output.cache_dir, which differs between the test sweeps
CHECKER = REPO.parent / "shared" / "tools" / "check_result.py"


def results(ds):
    """The computed data of a sweep dataset, without run times and bookkeeping."""
    return ds.drop_vars([v for v in ds.data_vars if v in PER_RUN | WHERE]).drop_attrs()


def test_sweep_is_one_design_by_case_dataset(parallel_sweep):
    """3 PCR values x (2 Fa jobs x 2 Fr grid points) -> design 3 x case 4, parameters as coordinates."""
    ds = xr.load_dataset(parallel_sweep.nc)
    assert dict(ds.sizes)["design"] == 3 and dict(ds.sizes)["case"] == 4
    np.testing.assert_array_equal(ds.PCR, [8.0, 90.0, 110.0])
    np.testing.assert_array_equal(ds.Fa, [3000.0, 3000.0, 5000.0, 5000.0])
    np.testing.assert_array_equal(ds.Fr, [0.0, 2000.0, 0.0, 2000.0])
    assert ds.attrs["swept"] == "PCR"
    for key in ("config", "package_version", "git_commit", "created", "sweep_overrides"):
        assert ds.attrs[key], key
    assert "job 5 [" in parallel_sweep.log  # one line per run
    if CHECKER.exists():
        chk = subprocess.run([sys.executable, str(CHECKER), str(parallel_sweep.nc)], capture_output=True, text=True)
        assert chk.returncode == 0, chk.stdout


def test_merged_sweep_equals_single_runs(parallel_sweep):
    """Every computed point of sweep.nc equals sim.simulate of the same single case (bit for bit:
    the same code on the same input; NetCDF with zlib is lossless)."""
    ds = xr.load_dataset(parallel_sweep.nc)
    for d in (1, 2):
        for c in range(ds.sizes["case"]):
            cfg = sim.load_config([*FAST, f"bearing.PCR={float(ds.PCR[d])}", f"load.Fa={float(ds.Fa[c])}",
                                   f"load.Fr={float(ds.Fr[c])}", "output.cache_dir=null"])
            single = sim.simulate(cfg).isel(design=0, case=0)
            point = ds.isel(design=d, case=c)
            for name in single.data_vars:
                if name not in PER_RUN:
                    np.testing.assert_array_equal(point[name].values, single[name].values, err_msg=name)
            assert bool(point.converged)


def test_impossible_design_is_a_failed_point(parallel_sweep):
    """PCR = 8 mm fails in sim.geometry: its 4 points stay as NaN, converged False, each a row of
    the failure table with the geometry error; the sweep itself succeeded."""
    ds = xr.load_dataset(parallel_sweep.nc)
    assert not ds.converged.isel(design=0).any()
    assert ds.pmax.isel(design=0).isnull().all()
    assert ds.sizes["failure"] == 4
    assert set(ds.failed_design.values) == {0} and sorted(ds.failed_case.values) == [0, 1, 2, 3]
    assert set(ds.failed_job.values) == {0, 1}
    assert set(ds.failed_reason.values) == {"error"}
    for message in ds.failed_message.values:
        assert "GeometryError: bearing.PCR = 8.0" in message and "8.857" in message
    assert "bearing.PCR=8" in str(ds.failed_overrides.values[0])


def test_killed_sweep_resumes_to_the_uninterrupted_dataset(parallel_sweep, tmp_path):
    """Kill a sequential run of the same sweep (SIGKILL, no clean-up) once it has cached a case;
    the same command again finishes it without redoing finished cases and gives the dataset of
    the uninterrupted parallel sweep."""
    cache, first = tmp_path / "cache", tmp_path / "first"
    cmd = [sys.executable, "-m", "sim.run", "--multirun", *SWEEP, *FAST, f"output.cache_dir={cache}",
           f"hydra.sweep.dir={first}"]
    proc = subprocess.Popen(cmd, cwd=REPO, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
    try:
        while proc.poll() is None and not any(cache.rglob(f"*{CACHE_SUFFIX}")):
            time.sleep(0.01)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
        proc.wait()
    assert proc.returncode == -signal.SIGKILL, "the sweep finished before it could be killed"
    assert not (first / "sweep.nc").exists()
    kept = {p: p.stat().st_mtime_ns for p in cache.rglob(f"*{CACHE_SUFFIX}")}

    resumed = multirun(SWEEP, first, cache)
    assert resumed.returncode == 0, resumed.stderr[-3000:]
    assert f"{len(kept)} already in the cache" in resumed.stdout
    assert len(list(cache.rglob(f"*{CACHE_SUFFIX}"))) == 8  # every computable point, each written once:
    assert {p: p.stat().st_mtime_ns for p in kept} == kept  # what the killed run finished is not redone
    ds = xr.load_dataset(first / "sweep.nc")
    uninterrupted = xr.load_dataset(parallel_sweep.nc)
    if ds.attrs["code_fingerprint"] != uninterrupted.attrs["code_fingerprint"]:
        pytest.skip("a source file of sim/ changed between the two sweeps: their numbers may differ")
    xr.testing.assert_identical(results(ds), results(uninterrupted))


def test_ctrl_c_ends_a_parallel_sweep_with_its_workers_and_one_line(tmp_path):
    """Ctrl-C (SIGINT to the process group, as a terminal sends it) once the parallel sweep has
    cached a case: the sweep and its workers end within seconds, exit status 130 and one line
    ``interrupted: ...`` as stderr's last, no traceback; the same command then resumes with what
    the interrupted run cached and completes the sweep. Jobs with friction on and 40 cases each
    (a few seconds of work in all) so that the signal comes while jobs run."""
    cache, sweep = tmp_path / "cache", tmp_path / "sweep"
    args = ["hydra/launcher=parallel", "bearing.PCR=70,80,90,100,110,120",
            "load.Fr=[" + ",".join(str(250 * k) for k in range(40)) + "]", "load.Fa=12000", "solver.n_slices=8"]
    cmd = [sys.executable, "-m", "sim.run", "--multirun", *args, f"output.cache_dir={cache}",
           f"hydra.sweep.dir={sweep}"]
    log = tmp_path / "stderr.txt"
    with open(log, "w") as err:
        proc = subprocess.Popen(cmd, cwd=REPO, stdout=subprocess.DEVNULL, stderr=err, start_new_session=True,
                                preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
        try:
            while proc.poll() is None and not any(cache.rglob(f"*{CACHE_SUFFIX}")):
                time.sleep(0.01)
            if proc.poll() is None:
                os.killpg(proc.pid, signal.SIGINT)
            proc.wait(timeout=30)
        finally:
            if proc.poll() is None:
                os.killpg(proc.pid, signal.SIGKILL)
                proc.wait()
    stderr = log.read_text()
    assert proc.returncode == 130, (proc.returncode, stderr[-3000:])
    assert "Traceback" not in stderr, stderr[-3000:]
    assert stderr.strip().splitlines()[-1].startswith("interrupted: every finished case is kept"), stderr[-3000:]
    time.sleep(1.0)   # the workers' exit after the parent's
    left = subprocess.run(["pgrep", "-s", str(proc.pid)], capture_output=True, text=True).stdout.split()
    assert not left, f"processes of the interrupted sweep still running: {left}"
    kept = len(list(cache.rglob(f"*{CACHE_SUFFIX}")))
    assert 0 < kept < 6 * 40
    resumed = multirun(args, sweep, cache, fast=False)
    assert resumed.returncode == 0, resumed.stderr[-3000:]
    assert f"{kept} already in the cache" in resumed.stdout + resumed.stderr
    assert bool(xr.load_dataset(sweep / "sweep.nc").converged.all())


def test_rerun_computes_nothing_but_the_failed_points(parallel_sweep, tmp_path, monkeypatch):
    """Every job of the finished sweep run again (as the launcher runs it, in a copy of the folder):
    no computed point is simulated again, only the two PCR = 8 jobs try again (and fail again),
    and the collector gives the same dataset, run times included."""
    sweep = shutil.copytree(parallel_sweep.dir, tmp_path / "sweep")
    calls = []
    monkeypatch.setattr(sim.api.sweep, "simulate",
                        lambda cfg, grid=None: calls.append(float(cfg.bearing.PCR)) or simulate(cfg, grid=grid))
    for job in json.loads((sweep / "sweep.json").read_text())["jobs"]:
        run_job(OmegaConf.create(job["config"]), sweep / str(job["job"]), job["job"], job["overrides"])
    assert calls == [8.0, 8.0]
    xr.testing.assert_identical(xr.load_dataset(collect(sweep)).drop_attrs(),
                                xr.load_dataset(parallel_sweep.nc).drop_attrs())


def test_bad_override_refuses_the_sweep_at_start(tmp_path, capsys):
    """Out-of-range and non-numeric values stop the multirun before any job (Hydra's callback,
    called here as Hydra calls it: SystemExit passes Hydra's callback guard, exit status 2),
    naming key and range for every job; no folder, no cache is made."""
    overrides = ["bearing.PCR=-5,100", "load.Fa=abc", *FAST, f"output.cache_dir={tmp_path / 'cache'}",
                 f"hydra.sweep.dir={tmp_path / 'sweep'}"]
    with initialize_config_dir(config_dir=str(sim.CONF_DIR), version_base="1.3"):
        master = GlobalHydra.instance().hydra.compose_config("config", overrides, run_mode=RunMode.MULTIRUN)
        with pytest.raises(SystemExit) as exit_:
            SweepCallback().on_multirun_start(config=master, config_name="config")
    assert exit_.value.code == 2
    err = capsys.readouterr().err
    assert "job 0 [bearing.PCR=-5 " in err and "bearing.PCR = -5 is outside the allowed range: a number in (0, 100000] mm" in err
    assert err.count("load.Fa = 'abc' is outside the allowed range: a number in (0, 1e+07] N") == 2
    assert not (tmp_path / "sweep").exists() and not (tmp_path / "cache").exists()
