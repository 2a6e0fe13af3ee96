"""Reference optima of the design studies (studies/reference_optimum.py, issue 16 item 3).

The stored optima (benchmarks/reference_optima/*.yaml) are what the search benchmark measures
every method against; these tests hold them to the current physics and to their claim of being
local optima."""
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from omegaconf import OmegaConf

from studies.config import compose
from studies.constraints import rank_key, violation
from studies.evaluate import STATUS, table_from_file
from studies.loop import DesignSearch
from studies.reference_optimum import main

STORED = sorted((Path(__file__).resolve().parents[2] / "benchmarks" / "reference_optima").glob("*.yaml"))
# The simulation is deterministic; re-run on another machine its loads agree to the solver
# tolerance (1e-9 relative, solver.tolerance) and the torque to ~1e-9 (the kinematics' own
# tolerance): 1e-6 leaves room for other BLAS builds and still catches any physics change,
# which moves the pinion torque by far more (the last friction change moved it by 1e-2).
REPRODUCE_RTOL = 1e-6
# Coordinate step of the local-optimality probe, unit scale (0.2 % of each search range): 20x
# COBYLA's final trust radius (refine.final_step 1e-4), so the probe looks past where the local run
# stopped, yet close enough that the objective is locally smooth there (the torque is continuous
# in the design since the contact ends lie between slice centres; pmax, a maximum over slices, has kinks).
PROBE_STEP = 2e-3
# An optimum is reported as within 0.1 % of the best (issue 16 item 4's tightest target): a
# feasible probe better than that would make the stored value no reference at that precision.
PROBE_IMPROVEMENT = 1e-3


def stored_search(path, tmp_path):
    ref = OmegaConf.to_container(OmegaConf.load(path))
    overrides = list(ref["simulation_overrides"])
    search = DesignSearch(compose(overrides), overrides, out_dir=tmp_path, log=lambda msg: None)
    search.run_references()
    return ref, search


def judge(search, x):
    """(objective, margins) of the design at x (free parameters in space order), by the study's
    own evaluation (every case of its duty cycle)."""
    part = search.simulate(np.asarray(x, dtype=float)[None, :], "probe", 0)
    ok = int(part.status.values[0]) == STATUS["ok"]
    return (float(search.objective_values(part)[0]) if ok else np.nan), search.point_margins(part)[0]


def test_reference_optima_are_stored_for_both_shipped_studies():
    assert {p.stem for p in STORED} >= {"pinion", "size_32208"}


@pytest.mark.parametrize("path", STORED, ids=[p.stem for p in STORED])
def test_stored_reference_optimum_reproduces_is_feasible_and_locally_optimal(path, tmp_path):
    """The stored design re-simulates to its stored objective (else: the physics changed, run the
    command in the file again), meets every constraint, and no feasible design one probe step away
    along any free parameter is better by more than 0.1 %."""
    ref, search = stored_search(path, tmp_path)
    x = np.array([ref["design"][n] for n in search.space.names])
    f, m = judge(search, x)
    assert f == pytest.approx(ref["value"], rel=REPRODUCE_RTOL), \
        f"{path.name}: re-simulated {f} != stored {ref['value']}: physics changed, rerun `{ref['command']}`"
    assert ref["feasible"] and violation(m) == 0.0
    u0 = search.space.unit(x)[0]
    span = search.space.high - search.space.low
    for i in range(len(u0)):
        for sign in (-1.0, 1.0):
            u = u0.copy()
            u[i] = np.clip(u[i] + sign * PROBE_STEP, 0.0, 1.0)
            if u[i] == u0[i]:
                continue                                   # on a bound: that side is outside the box
            fp, mp = judge(search, search.space.low + u * span)
            if violation(mp) == 0.0 and np.isfinite(fp):
                assert fp >= f * (1.0 - PROBE_IMPROVEMENT), \
                    f"{path.name}: {search.space.names[i]} {sign:+.0f} step gives feasible {fp} < {f}"


def test_reference_run_takes_the_best_point_and_resumes_without_simulating(tmp_path, monkeypatch):
    """A tiny run (8 sample points, one start from the sample and one from the template, then the
    polish rounds, at most 8 simulations each): the reported optimum is the best point of
    everything it simulated by the study's own ranking (checked from points.nc), and a second run
    simulates nothing and reports the same optimum."""
    monkeypatch.chdir(tmp_path)
    args = ["study=size_32208", "study.name=reference_test", "--sobol", "8", "--starts", "1",
            "--max-per-start", "8", "--out", "first.yaml"]
    main(args)
    points = tmp_path / "outputs" / "studies" / "reference_test" / "reference" / "points.nc"
    n_first = xr.load_dataset(points).sizes["design"]
    polish = int(compose(args[:2]).study.refine.restarts)
    assert 8 < n_first <= 8 + (1 + 1 + polish) * 8            # sample, two starts and the polish runs
    first = OmegaConf.to_container(OmegaConf.load("first.yaml"))
    mtime = points.stat().st_mtime_ns
    main(args[:-1] + ["second.yaml"])
    second = OmegaConf.to_container(OmegaConf.load("second.yaml"))
    assert points.stat().st_mtime_ns == mtime                    # nothing simulated, nothing rewritten
    assert second["design"] == first["design"] and second["value"] == first["value"]
    assert second["simulations"] == n_first
    overrides = args[:2]
    search = DesignSearch(compose(overrides), overrides, out_dir=tmp_path / "judge", log=lambda msg: None)
    search.run_references()
    table = table_from_file(xr.load_dataset(points))
    M = search.point_margins(table)
    f = np.where(table.status.values == STATUS["ok"], search.objective_values(table), np.nan)
    best = min(range(len(f)), key=lambda i: rank_key(f[i], M[i]))
    assert first["design"] == {n: float(table[n].values[best]) for n in search.space.names}


@pytest.mark.parametrize("flag, value", [("--sobol", "1"), ("--max-per-start", "3"), ("--starts", "-1")])
def test_bad_reference_settings_are_refused_naming_the_flag(flag, value, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main([flag, value]) == 2
    err = capsys.readouterr().err
    assert flag in err and value in err and ">=" in err
    assert not (tmp_path / "outputs").exists()


def test_a_stored_optimum_starts_a_rerun_and_another_studys_file_is_refused(tmp_path):
    """``--from-reference`` (a rerun after a physics change starts from the old optimum as well): the
    stored pinion design comes back in the search's parameter order; the pinion file offered to the
    size_32208 study is refused naming the file and both studies, before anything runs."""
    from sim.api import InputError
    from studies.reference_optimum import stored_optimum

    path = next(p for p in STORED if p.stem == "pinion")
    ref = OmegaConf.to_container(OmegaConf.load(path))
    pinion = DesignSearch(compose([]), [], out_dir=tmp_path / "p", log=lambda msg: None)
    label, x = stored_optimum(path, pinion)
    assert "pinion.yaml" in label and str(ref["git_commit"])[:7] in label
    np.testing.assert_array_equal(x, [ref["design"][n] for n in pinion.space.names])
    other = DesignSearch(compose(["study=size_32208"]), ["study=size_32208"], out_dir=tmp_path / "s", log=lambda msg: None)
    with pytest.raises(InputError, match=r"--from-reference .*pinion.yaml: the optimum of study 'pinion', not of 'size_32208'"):
        stored_optimum(path, other)
