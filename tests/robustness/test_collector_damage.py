"""The collector never sinks a sweep (issue 15, item 4).

One small sweep (2 designs x 2 load jobs, each job a grid of 2 cases) is run once; each test
copies it, damages one job's files the way a crash, a full disk or a hand edit would, and
collects again: the damaged job is a failure-table row per case with reason ``damaged`` and a
message naming the file and what is wrong; every other job is merged unchanged; the command
line exits 1 with a one-line summary; sweep.nc passes the contract checker.
"""
import json
import shutil
import subprocess
import sys

import numpy as np
import pytest
import xarray as xr

from sim.api.sweep import DAMAGED, collect_jobs
from tests.robustness.common import FAST, REPO, run

SWEEP = ["bearing.PCR=90,110", "load.Fa=3000,5000", "load.Fr=[0,2000]"]
CHECKER = REPO.parent / "shared" / "tools" / "check_result.py"
DAMAGED_JOB = 1   # PCR = 90, Fa = 5000: design 0, cases 2 and 3


@pytest.fixture(scope="module")
def sweep(tmp_path_factory):
    root = tmp_path_factory.mktemp("sweep")
    out = run(["-m", "sim.run", "--multirun", *SWEEP, *FAST, f"output.cache_dir={root / 'cache'}",
               f"hydra.sweep.dir={root / 'sweep'}"], root)
    assert out.returncode == 0, out.stderr[-3000:]
    return root / "sweep"


def damaged_copy(sweep, tmp_path, damage):
    """A copy of the sweep with ``damage(job_dir)`` applied to the damaged job; its sweep.nc removed."""
    copy = shutil.copytree(sweep, tmp_path / "sweep")
    (copy / "sweep.nc").unlink()
    damage(copy / str(DAMAGED_JOB))
    return copy


def without(name):
    def damage(job_dir):
        ds = xr.load_dataset(job_dir / "result.nc").drop_vars(name)
        (job_dir / "result.nc").unlink()
        ds.to_netcdf(job_dir / "result.nc")
    return damage


def nan_pmax(job_dir):
    ds = xr.load_dataset(job_dir / "result.nc")
    ds["pmax"][0, 0, 0] = np.nan
    (job_dir / "result.nc").unlink()
    ds.to_netcdf(job_dir / "result.nc")


def foreign(job_dir):
    """The result of another job (other load cases) in this job's folder."""
    shutil.copy(job_dir.parent / "0" / "result.nc", job_dir / "result.nc")


def truncate(job_dir):
    data = (job_dir / "result.nc").read_bytes()
    (job_dir / "result.nc").write_bytes(data[: len(data) // 2])


def corrupt_failed(job_dir):
    (job_dir / "result.nc").unlink()
    (job_dir / "failed.json").write_text('{"job": 1, "error": ')


DAMAGES = {
    "truncated_result": (truncate, "result.nc unreadable"),
    "empty_result": (lambda d: (d / "result.nc").write_bytes(b""), "result.nc unreadable"),
    "garbage_result": (lambda d: (d / "result.nc").write_bytes(b"\x89HDF\r\n\x1a\n" + bytes(range(256)) * 8),
                       "result.nc unreadable"),
    "text_result": (lambda d: (d / "result.nc").write_text("not a netcdf file\n"), "result.nc unreadable"),
    "result_without_pmax": (without("pmax"), "result.nc incomplete: no variable pmax"),
    "result_without_converged": (without("converged"), "result.nc incomplete: no variable converged"),
    "result_without_C": (without("C"), "result.nc incomplete: no variable C"),
    "converged_with_nan_pmax": (nan_pmax, "pmax is not finite for a case marked converged"),
    "result_of_another_job": (foreign, "cases that are not the job's"),
    "corrupt_failed_json": (corrupt_failed, "failed.json unreadable"),
    "failed_json_not_an_object": (lambda d: ((d / "result.nc").unlink(), (d / "failed.json").write_text("[1, 2]")),
                                  "failed.json unreadable"),
    "corrupt_overrides": (lambda d: (d / ".hydra" / "overrides.yaml").write_text("- a: [\n"),
                          "overrides.yaml unreadable"),
}


@pytest.mark.parametrize("name", sorted(DAMAGES))
def test_damaged_job_is_a_failure_and_the_others_are_merged(sweep, tmp_path, name):
    damage, text = DAMAGES[name]
    copy = damaged_copy(sweep, tmp_path, damage)
    path, incomplete = collect_jobs(copy)
    assert [(job, reason) for job, reason, _ in incomplete] == [(DAMAGED_JOB, DAMAGED)]
    assert text in incomplete[0][2]
    ds, whole = xr.load_dataset(path), xr.load_dataset(sweep / "sweep.nc")
    rows = ds.failed_reason.values == DAMAGED
    assert rows.sum() == 2 and set(ds.failed_job.values[rows]) == {DAMAGED_JOB}
    assert all(text in m for m in ds.failed_message.values[rows])
    hit = [(int(d), int(c)) for d, c in zip(ds.failed_design.values[rows], ds.failed_case.values[rows])]
    assert sorted(hit) == [(0, 2), (0, 3)]
    assert not ds.converged.values[0, 2:].any() and np.isnan(ds.pmax.values[0, 2:]).all()
    # every other point is the undamaged sweep's, bit for bit
    keep = np.ones(ds.converged.shape, dtype=bool)
    keep[0, 2:] = False
    for var in ("converged", "pmax", "axial_displacement", "Q", "iterations"):
        np.testing.assert_array_equal(ds[var].values[keep], whole[var].values[keep], err_msg=var)
    assert ds.converged.values[keep].all()
    if CHECKER.exists():
        chk = subprocess.run([sys.executable, str(CHECKER), str(path)], capture_output=True, text=True)
        assert chk.returncode == 0, chk.stdout


def test_command_line_exits_1_with_a_summary_and_writes_sweep_nc(sweep, tmp_path):
    copy = damaged_copy(sweep, tmp_path, truncate)
    out = run(["-m", "sim.api.sweep", "collect", str(copy)], tmp_path)
    assert out.returncode == 1, out.stderr[-3000:]
    assert "Traceback" not in out.stderr
    lines = [line for line in out.stderr.splitlines() if line.startswith("error: ")]
    assert len(lines) == 1 and "1 job(s) left no readable result (1 damaged)" in lines[0]
    assert f"job {DAMAGED_JOB} damaged" in lines[0] and "result.nc unreadable" in lines[0]
    assert (copy / "sweep.nc").is_file()


def test_missing_job_exits_1_and_a_whole_sweep_exits_0(sweep, tmp_path):
    whole = run(["-m", "sim.api.sweep", "collect", str(shutil.copytree(sweep, tmp_path / "whole"))], tmp_path)
    assert whole.returncode == 0, whole.stderr[-3000:]
    copy = damaged_copy(sweep, tmp_path, lambda d: shutil.rmtree(d))
    out = run(["-m", "sim.api.sweep", "collect", str(copy)], tmp_path)
    assert out.returncode == 1 and "(1 missing)" in out.stderr and "Traceback" not in out.stderr


def test_rerun_of_the_sweep_repairs_a_damaged_job(sweep, tmp_path):
    """The same command again rewrites the damaged job from the cache (nothing computed) and the
    sweep is whole again."""
    copy = damaged_copy(sweep, tmp_path, truncate)
    manifest = json.loads((copy / "sweep.json").read_text())
    cache = manifest["jobs"][0]["config"]["output"]["cache_dir"]
    out = run(["-m", "sim.run", "--multirun", *SWEEP, *FAST, f"output.cache_dir={cache}", f"hydra.sweep.dir={copy}"],
              tmp_path)
    assert out.returncode == 0, out.stderr[-3000:]
    assert "8 already in the cache" in out.stdout + out.stderr
    ds = xr.load_dataset(copy / "sweep.nc")
    assert ds.converged.all() and ds.sizes["failure"] == 0
