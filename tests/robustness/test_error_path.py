"""One error path (issue 15, item 3): every entry point turns the project's own errors into one
line ``error: ...`` on stderr and exit status 2, never a traceback, and creates no output folder
before the input is accepted; an unexpected exception keeps its traceback and exits 1.

The commands run as a user runs them: subprocesses of ``python -m ...`` in a scratch folder.
"""
import json

import pytest

import studies.optimize
from studies.config import StudyConfigError
from tests.robustness.common import FAST, REPO, assert_refused, run


# ---------------------------------------------------------------------------- python -m sim.run
@pytest.mark.parametrize("overrides, fragments, not_blamed", [
    (["bearing.Z=200"], ["bearing.Z = 200 is impossible", "<= 17"], None),
    (["bearing.PCR=1e30"], ["bearing.PCR = 1e+30 is outside the allowed range"], "bearing.R"),
    (["bearing.R=33"], ["bearing.R = 33.0 is impossible", "outer ring needs a section"], None),
    (["bearing.aPk=9"], ["bearing.aPk = 9.0 is impossible", "Lwe = 17.0, aP = 8.5"], None),
    (["load.Fa=-5", "bearing.kappa=2"], ["load.Fa = -5 is outside", "bearing.kappa = 2 is outside"], None),
    (["bearing=trb_32208", "bearing.roller_end_radius_ratio=0.2"], ["bearing.roller_end_radius_ratio = 0.2"], None),
    # at 1 the end sphere is centred on the bearing axis and conforms to the cone rib along e_t
    (["bearing=trb_32208", "bearing.roller_end_radius_ratio=1.0"], ["bearing.roller_end_radius_ratio = 1.0", "(0.3, 1)"],
     None),
    (["material.nu=0.7"], ["material.nu = 0.7"], None),
    (["+bearing.kapa=0.9"], ["bearing.kapa is not a config key (did you mean bearing.kappa?)"], None),
    # without "+" Hydra refused it itself, in six lines with exit status 1 (an independent check of session 31)
    (["bearing.kapa=0.9"], ["bearing.kapa is not a config key (did you mean bearing.kappa?)"], None),
    (["friction.skew.pocket_clerance=0.1"],
     ["friction.skew.pocket_clerance is not a config key (did you mean friction.skew.pocket_clearance?)"], None),
    # a config file that does not exist: Hydra refused it itself, in 11-18 lines with exit status 1 (session 33's
    # checker; a multirun already refused it in one line)
    (["bearing=tsrb_pinnion"], ["Could not find 'bearing/tsrb_pinnion'", "tsrb_pinion;"], None),
    (["load=sensitivity_scenario"], ["Could not find 'load/sensitivity_scenario'", "sensitivity_scenarios"], None),
    (["hydra/launcher=foo"], ["Could not find 'hydra/launcher/foo'", "parallel"], None),
], ids=["Z_200", "PCR_1e30", "R_33", "aPk_9", "two_bad_values", "trb_end_radius", "trb_end_sphere_conforms", "nu",
         "added_unknown_key", "unknown_key", "unknown_nested_key", "unknown_bearing_file", "unknown_load_file",
         "unknown_launcher"])
def test_single_run_refuses_in_one_line_and_makes_no_folder(tmp_path, overrides, fragments, not_blamed):
    run_dir = tmp_path / "run"
    out = run(["-m", "sim.run", *overrides, *FAST, f"hydra.run.dir={run_dir}", "output.cache_dir=null"], tmp_path)
    line = assert_refused(out, *fragments)
    assert not_blamed is None or not_blamed not in line
    assert not run_dir.exists()


def test_output_file_outside_the_run_folder_must_be_in_an_existing_folder(tmp_path):
    """``output.file=/nonexistent_dir/x.nc`` created /nonexistent_dir; now refused naming output.file."""
    absent = tmp_path / "nonexistent_dir" / "x.nc"
    run_dir = tmp_path / "run"
    out = run(["-m", "sim.run", *FAST, f"output.file={absent}", f"hydra.run.dir={run_dir}", "output.cache_dir=null"],
              tmp_path)
    assert_refused(out, f"output.file = '{absent}'", "does not exist")
    assert not absent.parent.exists() and not run_dir.exists()
    escaping = run(["-m", "sim.run", *FAST, "output.file=../../nowhere/x.nc", f"hydra.run.dir={run_dir}",
                    "output.cache_dir=null"], tmp_path)
    assert_refused(escaping, "output.file = '../../nowhere/x.nc'")
    # an existing folder outside the run folder, and a new subfolder inside it, are fine
    (tmp_path / "elsewhere").mkdir()
    ok = run(["-m", "sim.run", *FAST, f"output.file={tmp_path / 'elsewhere' / 'x.nc'}", f"hydra.run.dir={run_dir}",
              "output.cache_dir=null"], tmp_path)
    assert ok.returncode == 0, ok.stderr[-3000:]
    assert (tmp_path / "elsewhere" / "x.nc").is_file()
    inside = run(["-m", "sim.run", *FAST, "output.file=sub/x.nc", f"hydra.run.dir={tmp_path / 'run2'}",
                  "output.cache_dir=null"], tmp_path)
    assert inside.returncode == 0, inside.stderr[-3000:]
    assert (tmp_path / "run2" / "sub" / "x.nc").is_file()


def test_multirun_refuses_in_one_line_and_makes_no_folder(tmp_path):
    sweep = tmp_path / "sweep"
    out = run(["-m", "sim.run", "--multirun", "bearing.PCR=-5,100", *FAST, f"hydra.sweep.dir={sweep}",
               f"output.cache_dir={tmp_path / 'cache'}"], tmp_path)
    assert_refused(out, "job 0 [bearing.PCR=-5", "bearing.PCR = -5 is outside the allowed range")
    assert not sweep.exists() and not (tmp_path / "cache").exists()
    shared = run(["-m", "sim.run", "--multirun", "bearing.PCR=90,100", *FAST, f"output.file={tmp_path / 'x.nc'}",
                  f"hydra.sweep.dir={sweep}", "output.cache_dir=null"], tmp_path)
    assert_refused(shared, "is outside the job folder")
    assert not sweep.exists()


def test_unexpected_exception_keeps_its_traceback_and_exits_1(tmp_path):
    """A bug is not an input error: traceback, exit status 1 (Hydra's report), nothing hidden."""
    code = ("import sys, runpy, sim.api.sweep as s\n"
            "def boom(cfg, grid=None):\n    raise RuntimeError('a bug')\n"
            "s.simulate = boom\n"
            f"sys.argv = ['sim.run', *{FAST!r}, 'hydra.run.dir={tmp_path / 'run'}', 'output.cache_dir=null']\n"
            "runpy.run_module('sim.run', run_name='__main__')\n")
    out = run(["-c", code], tmp_path, env={"HYDRA_FULL_ERROR": "1"})
    assert out.returncode == 1
    assert "Traceback" in out.stderr and "RuntimeError: a bug" in out.stderr


# ---------------------------------------------------------------------------- python -m sim.api.sweep collect
def test_collect_refuses_a_folder_that_is_not_a_sweep(tmp_path):
    assert_refused(run(["-m", "sim.api.sweep", "collect", str(tmp_path)], tmp_path), "no sweep.json")
    assert_refused(run(["-m", "sim.api.sweep", "collect", str(tmp_path / "absent")], tmp_path), "no sweep.json")
    (tmp_path / "sweep.json").write_text("{not json")
    assert_refused(run(["-m", "sim.api.sweep", "collect", str(tmp_path)], tmp_path), "sweep.json unreadable")
    (tmp_path / "sweep.json").write_text(json.dumps({"jobs": 3}))
    assert_refused(run(["-m", "sim.api.sweep", "collect", str(tmp_path)], tmp_path), "sweep.json unreadable")
    assert not (tmp_path / "sweep.nc").exists()


# ---------------------------------------------------------------------------- python -m studies.optimize
@pytest.mark.parametrize("overrides, fragments", [
    (["study.load.Fa=-5"], ["study.load.Fa = -5.0 is outside the allowed range"]),
    (["study.sampler=simplex"], ["study.sampler = 'simplex'"]),
    (["study.foo=1"], ["study.foo"]),
    (["bearing.PCR=90"], ["bearing.PCR = '90' cannot be overridden here"]),
    (["solver.n_slices=1"], ["solver.n_slices = 1 is outside the allowed range"]),
    (["study.bearing=nothing"], ["study.bearing = 'nothing'"]),
    # Hydra's own message had no hint, and with "+" (its advice) the study ran without the key (session 32)
    (["study.refine.maxsims=3"], ["study.refine.maxsims is not a config key (did you mean study.refine.max_simulations?)"]),
    (["+study.refine.maxsims=3"], ["study.refine.maxsims is not a config key (did you mean study.refine.max_simulations?)"]),
], ids=["Fa_negative", "sampler", "unknown_key", "bearing_override", "solver_range", "unknown_bearing",
         "unknown_nested_key", "added_unknown_nested_key"])
def test_optimize_refuses_in_one_line_and_makes_no_folder(tmp_path, overrides, fragments):
    out = run(["-m", "studies.optimize", *overrides], tmp_path)
    assert_refused(out, *fragments)
    assert not (tmp_path / "outputs").exists()


def test_optimize_refused_after_the_references_removes_the_folder_it_made(tmp_path, monkeypatch, capsys):
    """A refusal that needs the reference simulations (here: a StudyConfigError from them, as when
    the reference TRB gives no result at study.load) comes after DesignSearch made the study folder:
    the empty folder and the parents it made are removed, exit 2, one line."""
    monkeypatch.chdir(tmp_path)

    def refused(self):
        raise StudyConfigError("study.constraints.pmax_max = 'trb' but the reference TRB has no pmax")

    monkeypatch.setattr(studies.optimize.DesignSearch, "run_references", refused)
    assert studies.optimize.main(["study.name=refused"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error: study.constraints.pmax_max")
    assert not (tmp_path / "outputs").exists()


# ---------------------------------------------------------------------------- python -m studies.workers
@pytest.mark.parametrize("args, fragments", [
    (["run", "-n", "0"], ["-n/--workers = 0 is outside the allowed range", ">= 1"]),
    (["create", "study.load.Fa=-5"], ["study.load.Fa = -5.0 is outside the allowed range"]),
    (["work", "study.workers.max_retry=-1"], ["study.workers.max_retry = -1"]),
    (["report", "study.sampler=simplex"], ["study.sampler = 'simplex'"]),
], ids=["no_workers", "Fa_negative", "max_retry", "sampler"])
def test_workers_refuse_in_one_line_and_make_no_folder(tmp_path, args, fragments):
    out = run(["-m", "studies.workers", *args], tmp_path)
    assert_refused(out, *fragments)
    assert not (tmp_path / "outputs").exists()


# ---------------------------------------------------------------------------- python -m studies.pareto
@pytest.mark.parametrize("overrides, fragments", [
    (["study.pareto.fronts=[[power_loss,torque]]"], ["study.pareto.fronts", "torque"]),
    (["study.pareto.trials=0"], ["study.pareto.trials = 0", ">= 1"]),
    (["study.load.Fa=-5"], ["study.load.Fa = -5.0 is outside the allowed range"]),
], ids=["unknown_objective", "no_trials", "Fa_negative"])
def test_pareto_refuses_in_one_line_and_makes_no_folder(tmp_path, overrides, fragments):
    out = run(["-m", "studies.pareto", *overrides], tmp_path)
    assert_refused(out, *fragments)
    assert not (tmp_path / "outputs").exists()


# ---------------------------------------------------------------------------- python -m studies.reference_optimum
@pytest.mark.parametrize("args, fragments", [
    (["--sobol", "1"], ["--sobol = 1", ">= 2"]),
    (["study.load.Fa=-5"], ["study.load.Fa = -5.0 is outside the allowed range"]),
], ids=["sample_too_small", "Fa_negative"])
def test_reference_optimum_refuses_in_one_line_and_makes_no_folder(tmp_path, args, fragments):
    out = run(["-m", "studies.reference_optimum", *args], tmp_path)
    assert_refused(out, *fragments)
    assert not (tmp_path / "outputs").exists()


# ---------------------------------------------------------------------------- python -m studies.validation
def test_validation_refuses_an_output_path_that_is_a_file(tmp_path):
    target = tmp_path / "report"
    target.write_text("not a folder")
    assert_refused(run(["-m", "studies.validation", "--out", str(target)], tmp_path), "--out", "is a file")


# ---------------------------------------------------------------------------- python -m studies.sensitivity
def test_sensitivity_refuses_what_is_not_a_sensitivity_sweep(tmp_path):
    assert_refused(run(["-m", "studies.sensitivity", str(tmp_path / "absent.nc")], tmp_path), "is not a file")
    garbage = tmp_path / "garbage.nc"
    garbage.write_bytes(b"\x89HDF\r\n\x1a\n" + b"rubbish" * 10)
    assert_refused(run(["-m", "studies.sensitivity", str(garbage)], tmp_path), "is not a readable NetCDF file")
    single = tmp_path / "single.nc"
    made = run(["-m", "sim.run", *FAST, f"output.file={single}", f"hydra.run.dir={tmp_path / 'run'}",
                "output.cache_dir=null"], tmp_path)
    assert made.returncode == 0, made.stderr[-3000:]
    assert_refused(run(["-m", "studies.sensitivity", str(single)], tmp_path), "is not a sensitivity sweep",
                   "no variant")


def test_every_entry_point_is_covered():
    """The entry points of the issue, each with its refusal tests above (benchmarks are exempt)."""
    mains = {p.relative_to(REPO).as_posix() for p in list((REPO / "sim").rglob("*.py"))
             + list((REPO / "studies").rglob("*.py")) if 'if __name__ == "__main__":' in p.read_text()}
    assert mains == {"sim/run.py", "sim/api/sweep.py", "studies/optimize.py", "studies/pareto.py",
                     "studies/reference_optimum.py", "studies/sensitivity.py", "studies/validation.py",
                     "studies/workers.py"}


def test_a_run_with_long_full_precision_overrides_makes_its_folder(tmp_path):
    """A design report's re-simulation command (full-precision values, 11 overrides) named its run
    folder after all of them, 271 bytes against Linux's 255, and failed with a traceback (session 32,
    an independent check). The folder's name now keeps the overrides' first bytes and a hash of
    all of them (sim.api.schema.run_folder_name): the run succeeds, every name stays within 255
    bytes, and two commands that differ only in the last digits of a late value get two folders."""
    base = ["bearing=tsrb_reference", "lubricant=fva3", "bearing.PCR=41.99541028259611", "bearing.kappa=0.9713367221216711",
            "bearing.aP=4.0", "bearing.aPk=8.5", "bearing.alpha=18.0", "bearing.ratings_alpha=18.0", "load.Fa=6500.0",
            "load.Fr=0.0", "load.speed=1500.0", "load.tilt=0.0"]
    for temperature in ("55.000000000001", "55.000000000002"):
        out = run(["-m", "sim.run", *base, f"load.oil_temperature={temperature}", *FAST, "output.cache_dir=null"],
                  tmp_path)
        assert out.returncode == 0, out.stderr[-3000:]
    folders = [p for p in (tmp_path / "outputs" / "runs").glob("*/*") if p.is_dir()]
    assert len(folders) == 2 and all((f / "result.nc").is_file() for f in folders)
    assert all(len(f.name.encode()) <= 255 for f in folders)
    assert len({f.name.split("_", 1)[1] for f in folders}) == 2


def test_a_study_removes_the_temporary_a_killed_write_left(tmp_path, monkeypatch):
    """kill -9 during a write of training.nc left its temporary (.training.nc.<host>-<pid>-<hex>.tmp)
    beside it, and the resumed study finished with it still there (session 32, an independent
    check). A study's start removes the temporaries of dead writers in its folder (and in its
    pareto folder), as a run does in its own (sim.api.sweep.remove_stale_files); here the start is
    stopped right after, before any simulation."""
    import subprocess
    import sys

    from sim.io import HOST_TAG
    from studies.config import compose, output_dir

    monkeypatch.chdir(tmp_path)
    proc = subprocess.Popen([sys.executable, "-c", "pass"])
    proc.wait()
    folder = output_dir(compose(["study.name=killed"]).study)
    stale = [folder / f".training.nc.{HOST_TAG}-{proc.pid}-0a1b2c3d.tmp",
             folder / "pareto" / f".local_points.nc.{HOST_TAG}-{proc.pid}-0a1b2c3d.tmp"]
    for path in stale:
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_bytes(b"partial")

    def stop(*args, **kwargs):
        raise StudyConfigError("stopped after the start's clean-up")
    monkeypatch.setattr(studies.optimize, "DesignSearch", stop)
    assert studies.optimize.main(["study.name=killed"]) == 2
    assert not any(p.exists() for p in stale)
