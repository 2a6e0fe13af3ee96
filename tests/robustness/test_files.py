"""Files (issue 15, item 5): what an interrupted write leaves is removed on the next run, a full
disk or a read-only folder gives a clear message naming the path, and nothing finished is lost.

Full and read-only file systems are real: small tmpfs mounts (root only; skipped where mounting
is not allowed), so that netCDF4 fails as it does on a full disk ("NetCDF: HDF error").
"""
import errno
import json
import os
import shutil
import subprocess
import sys
import time
import uuid

import pytest
from omegaconf import OmegaConf

import sim
import sim.api.sweep as sweep
from sim.api.sweep import (CACHE_SUFFIX, CLAIM_SUFFIX, HOST_TAG, STALE_AFTER, WriteError, compute_case,
                           remove_stale_files, run_job, write_result)
from sim.api import operating_points
from tests.robustness.common import FAST, assert_refused, run

OLD = time.time() - 2 * STALE_AFTER


def dead_pid():
    """The pid of a process that has finished."""
    proc = subprocess.Popen([sys.executable, "-c", "pass"])
    proc.wait()
    return proc.pid


def touch(path, mtime=None, text=""):
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    if mtime is not None:
        os.utime(path, (mtime, mtime))
    return path


# ---------------------------------------------------------------------------- stale files
def test_only_stale_temporaries_and_claims_are_removed(tmp_path):
    """Removed: an old temporary of any writer, a fresh one of a dead pid on this host, a claim of
    a dead pid, an old claim of another host, an old set-aside claim. Kept: fresh files of live or
    unknown writers (a concurrent run), and everything that is not a temporary or a claim."""
    live = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(60)"])
    try:
        dead = dead_pid()
        shard = tmp_path / "ab"
        gone = [
            touch(tmp_path / ".result.nc.k3j_x9a2.tmp", OLD),                      # sim.io temporary, old
            touch(shard / f".abc{CACHE_SUFFIX}.{HOST_TAG}-{dead}-0a1b2c3d.tmp"),   # dead writer on this host
            touch(shard / f".abd{CACHE_SUFFIX}.ffffffff-{live.pid}-0a1b2c3d.tmp", OLD),  # another host, old
            touch(shard / f"abe{CLAIM_SUFFIX}", text=json.dumps({"host": HOST_TAG, "pid": dead})),
            touch(shard / f"abf{CLAIM_SUFFIX}", OLD, json.dumps({"host": "ffffffff", "pid": 1})),
            touch(shard / f".abg{CLAIM_SUFFIX}.1a2b3c4d.broken", OLD),
        ]
        kept = [
            touch(tmp_path / ".result.nc.k3j_x9a3.tmp"),                             # fresh, writer unknown
            touch(shard / f".abh{CACHE_SUFFIX}.{HOST_TAG}-{live.pid}-0a1b2c3d.tmp", OLD),  # live writer
            touch(shard / f".abi{CACHE_SUFFIX}.ffffffff-{dead}-0a1b2c3d.tmp"),       # another host, fresh
            touch(shard / f"abj{CLAIM_SUFFIX}", OLD, json.dumps({"host": HOST_TAG, "pid": live.pid})),
            touch(shard / f"abk{CLAIM_SUFFIX}", text=json.dumps({"host": "ffffffff", "pid": dead})),
            touch(shard / f"abl{CACHE_SUFFIX}", OLD),
            touch(tmp_path / "result.nc", OLD),
            touch(tmp_path / "notes.tmp", OLD),
        ]
        assert remove_stale_files(tmp_path) == 1            # the folder itself only
        assert remove_stale_files(tmp_path, shards=True) == len(gone) - 1
        assert not any(p.exists() for p in gone)
        assert all(p.exists() for p in kept)
    finally:
        live.kill()
        live.wait()


def test_next_run_of_the_same_sweep_removes_what_a_killed_one_left(tmp_path):
    """Temporaries as a kill -9 leaves them (old sim.io NetCDF ones in the sweep and a job folder,
    a cache temporary and a claim of a dead process): the same sweep again removes them and
    completes; a fresh temporary of a possibly live writer is left alone."""
    cache, folder = tmp_path / "cache", tmp_path / "sweep"
    args = ["-m", "sim.run", "--multirun", "bearing.PCR=90,100", "load.Fa=3000", *FAST, f"output.cache_dir={cache}",
            f"hydra.sweep.dir={folder}"]
    first = run(args, tmp_path)
    assert first.returncode == 0, first.stderr[-3000:]
    dead = dead_pid()
    shard = next(p for p in cache.iterdir() if p.is_dir())
    left = [touch(folder / ".sweep.nc.a1b2c3d4.tmp", OLD), touch(folder / "0" / ".result.nc.a1b2c3d4.tmp", OLD),
            touch(shard / f".{'0' * 64}{CACHE_SUFFIX}.{HOST_TAG}-{dead}-0a1b2c3d.tmp"),
            touch(shard / f"{'0' * 64}{CLAIM_SUFFIX}", text=json.dumps({"host": HOST_TAG, "pid": dead}))]
    fresh = touch(folder / "1" / ".result.nc.z9y8x7w6.tmp")
    again = run(args, tmp_path)
    assert again.returncode == 0, again.stderr[-3000:]
    assert not any(p.exists() for p in left)
    assert fresh.exists()
    single = touch(tmp_path / "run" / ".result.nc.a1b2c3d4.tmp", OLD)
    one = run(["-m", "sim.run", *FAST, f"hydra.run.dir={tmp_path / 'run'}", f"output.cache_dir={cache}"], tmp_path)
    assert one.returncode == 0, one.stderr[-3000:]
    assert not single.exists()


# ---------------------------------------------------------------------------- failed writes, in process
@pytest.fixture(scope="module")
def cfg():
    return sim.load_config(FAST)


def test_unwritable_result_names_the_file_and_the_cache(cfg, tmp_path, monkeypatch):
    def full(ds, path):
        raise RuntimeError("NetCDF: HDF error")

    monkeypatch.setattr(sweep.io, "write_netcdf_atomic", full)
    with pytest.raises(WriteError) as err:
        write_result(None, tmp_path / "result.nc", cfg)
    message = str(err.value)
    assert f"cannot write {tmp_path / 'result.nc'}: RuntimeError: NetCDF: HDF error" in message
    assert "free there; is the disk full or the folder read-only?" in message
    assert f"in the result cache {cfg.output.cache_dir}" in message


def test_multirun_job_that_cannot_write_its_result_is_a_failed_job(cfg, tmp_path, monkeypatch):
    def full(ds, path):
        raise OSError(errno.ENOSPC, "No space left on device")

    job = OmegaConf.merge(cfg, {"output": {"cache_dir": None}})
    monkeypatch.setattr(sweep.io, "write_netcdf_atomic", full)
    run_job(job, tmp_path, 0, ["x=1"])
    error = json.loads((tmp_path / "failed.json").read_text())["error"]
    assert error.startswith(f"WriteError: cannot write {tmp_path / 'result.nc'}") and "No space left" in error


@pytest.mark.parametrize("code", [errno.ENOSPC, errno.EROFS, errno.EACCES])
def test_cache_that_cannot_be_written_warns_once_and_the_case_is_kept(cfg, tmp_path, monkeypatch, caplog, code):
    def refuse(path, data):
        raise OSError(code, os.strerror(code), str(path))

    monkeypatch.setattr(sweep.io, "write_bytes_atomic", refuse)
    monkeypatch.setattr(sweep, "_warned", set())
    one = cfg.copy()
    one.output.cache_dir = str(tmp_path / "cache")
    ops = operating_points(one.load)
    for op in ops * 2:
        ds, hit = compute_case(one.copy(), op, sweep.cache_file(one, op))
        assert not hit and bool(ds.converged.all())
    warnings = [r for r in caplog.records if "cannot be written" in r.getMessage()]
    assert len(warnings) == 1 and str(tmp_path / "cache") in warnings[0].getMessage()
    assert not list((tmp_path / "cache").rglob(f"*{CLAIM_SUFFIX}"))


# ---------------------------------------------------------------------------- real full and read-only folders
@pytest.fixture
def mount(tmp_path):
    """mount(folder, options): a tmpfs at ``folder`` (unmounted afterwards); skips where not allowed."""
    mounted = []

    def make(folder, options):
        if os.geteuid() != 0 or shutil.which("mount") is None:
            pytest.skip("mounting a tmpfs needs root")
        folder.mkdir(parents=True, exist_ok=True)
        out = subprocess.run(["mount", "-t", "tmpfs", "-o", options, f"tmpfs-{uuid.uuid4().hex[:8]}", str(folder)],
                             capture_output=True, text=True)
        if out.returncode != 0:
            pytest.skip(f"cannot mount a tmpfs here: {out.stderr.strip()}")
        mounted.append(folder)
        return folder

    yield make
    for folder in reversed(mounted):
        subprocess.run(["umount", "-l", str(folder)], capture_output=True)


def test_full_disk_names_the_file_and_loses_nothing_finished(tmp_path, mount):
    """The run folder on a full file system (64 kB: Hydra's own files fit, result.nc does not):
    one line naming result.nc, exit 1; the case is in the cache, so the run into a folder with
    room computes nothing."""
    full = mount(tmp_path / "full", "size=64k")
    cache = tmp_path / "cache"
    out = run(["-m", "sim.run", *FAST, f"hydra.run.dir={full / 'run'}", f"output.cache_dir={cache}"], tmp_path)
    assert_refused(out, f"cannot write {full / 'run' / 'result.nc'}", "is the disk full",
                   f"in the result cache {cache}", status=1)
    assert not list((full / "run").glob(".*.tmp"))
    again = run(["-m", "sim.run", *FAST, f"hydra.run.dir={tmp_path / 'room'}", f"output.cache_dir={cache}"], tmp_path)
    assert again.returncode == 0 and "(1 cases, 1 from the cache)" in again.stdout


def test_full_cache_warns_and_the_result_is_written(tmp_path, mount):
    cache = mount(tmp_path / "cache", "size=8k")
    out = run(["-m", "sim.run", *FAST, f"hydra.run.dir={tmp_path / 'run'}", f"output.cache_dir={cache}"], tmp_path)
    assert out.returncode == 0, out.stderr[-3000:]
    assert f"the result cache {cache} cannot be written" in out.stdout + out.stderr
    assert (tmp_path / "run" / "result.nc").is_file()
    assert not list(cache.rglob(f"*{CLAIM_SUFFIX}")) and not list(cache.rglob("*.tmp"))


def test_read_only_cache_warns_and_the_result_is_written(tmp_path, mount):
    cache = mount(tmp_path / "cache", "ro,size=64k")
    out = run(["-m", "sim.run", *FAST, f"hydra.run.dir={tmp_path / 'run'}", f"output.cache_dir={cache}"], tmp_path)
    assert out.returncode == 0, out.stderr[-3000:]
    assert f"the result cache {cache} cannot be written" in out.stdout + out.stderr
    assert (tmp_path / "run" / "result.nc").is_file()


def test_read_only_sweep_collect_names_sweep_nc(tmp_path, mount):
    """A finished sweep copied onto a read-only file system: collect exits 1 naming sweep.nc."""
    folder = tmp_path / "sweep"
    made = run(["-m", "sim.run", "--multirun", "bearing.PCR=90,100", *FAST, "output.cache_dir=null",
                f"hydra.sweep.dir={folder}"], tmp_path)
    assert made.returncode == 0, made.stderr[-3000:]
    (folder / "sweep.nc").unlink()
    ro = mount(tmp_path / "ro", "size=1m")
    shutil.copytree(folder, ro / "sweep")
    subprocess.run(["mount", "-o", "remount,ro", str(ro)], check=True)
    out = run(["-m", "sim.api.sweep", "collect", str(ro / "sweep")], tmp_path)
    assert_refused(out, f"cannot write {ro / 'sweep' / 'sweep.nc'}", "read-only", status=1)


@pytest.mark.parametrize("umask, mode", [(0o022, 0o644), (0o077, 0o600), (0o002, 0o664)])
def test_result_files_get_the_users_umask(tmp_path, umask, mode):
    """write_netcdf_atomic creates result files like any other file (0666 minus the umask), not
    with the 0600 of a mkstemp temporary."""
    import xarray as xr

    from sim.io import write_netcdf_atomic

    old = os.umask(umask)
    try:
        path = write_netcdf_atomic(xr.Dataset({"a": ("x", [1.0])}), tmp_path / "result.nc")
    finally:
        os.umask(old)
    assert os.stat(path).st_mode & 0o777 == mode
    assert [p.name for p in tmp_path.iterdir()] == ["result.nc"]      # no temporary left


def test_reports_and_figures_replace_the_old_file_whole_or_not_at_all(tmp_path):
    """write_bytes_atomic / write_figure_atomic (reports, summaries, plots): a new version replaces
    the old file whole; a figure that fails while it is drawn leaves the old file as it was and no
    temporary beside it."""
    from matplotlib.figure import Figure

    from sim.io import write_bytes_atomic, write_figure_atomic

    report = write_bytes_atomic(tmp_path / "report.md", b"old\n")
    write_bytes_atomic(report, b"new\n")
    assert report.read_text() == "new\n"
    fig = Figure()
    fig.add_subplot().plot([0, 1], [0, 1])
    png = write_figure_atomic(fig, tmp_path / "plot.png", 50)
    before = png.read_bytes()
    assert before.startswith(b"\x89PNG")
    fig.axes[0].text(0.5, 0.5, r"$\notacommand$")            # mathtext error while drawing
    with pytest.raises(ValueError):
        write_figure_atomic(fig, png, 50)
    assert png.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["plot.png", "report.md"]
