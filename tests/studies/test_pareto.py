"""Pareto fronts of a design study (studies/pareto.py, issue 16 item 6)."""
import numpy as np
import pytest
from omegaconf import OmegaConf

from studies.config import StudyConfigError, compose, validate
from studies.pareto import OBJECTIVES, non_dominated


def _brute_force_front(F, signs):
    """Pareto set by definition: i is kept unless some j is no worse in both and better in one."""
    G = F * signs
    return [i for i in range(len(G))
            if not any(np.all(G[j] <= G[i]) and np.any(G[j] < G[i]) for j in range(len(G)) if j != i)]


@pytest.mark.parametrize("directions", [("minimize", "minimize"), ("minimize", "maximize")])
def test_non_dominated_is_the_definition_of_the_pareto_set(directions):
    """Random clouds with ties: the vectorised filter keeps exactly the definition's set; on the
    circle arc x^2 + y^2 = 1 (x, y >= 0, both minimised) every point is non-dominated."""
    rng = np.random.default_rng(7)
    signs = np.array([1.0 if d == "minimize" else -1.0 for d in directions])
    for _ in range(20):
        F = np.round(rng.random((40, 2)), 1)          # coarse grid: many ties and duplicates
        assert non_dominated(F, directions).tolist() == _brute_force_front(F, signs)
    t = np.linspace(0.0, np.pi / 2, 25)
    arc = np.column_stack([np.cos(t), np.sin(t)])
    assert non_dominated(arc, ("minimize", "minimize")).tolist() == list(range(25))
    inner = np.vstack([arc, 0.5 * arc])               # the inner arc dominates the outer one
    assert non_dominated(inner, ("minimize", "minimize")).tolist() == list(range(25, 50))


def test_shipped_fronts_pair_known_objectives():
    study = compose([]).study
    for pair in study.pareto.fronts:
        assert set(pair) <= set(OBJECTIVES) and pair[0] != pair[1]


@pytest.mark.parametrize("key, value, words", [
    ("pareto.trials", 0, ["study.pareto.trials", "0", ">= 1"]),
    ("pareto.fronts", [["power_loss", "torque"]], ["study.pareto.fronts", "torque", "power_loss", "L10", "pmax"]),
    ("pareto.fronts", [["pmax", "pmax"]], ["study.pareto.fronts", "distinct"]),
])
def test_bad_pareto_settings_fail_at_start(key, value, words):
    study = compose([]).study.copy()
    OmegaConf.update(study, key, value, merge=False)
    with pytest.raises(StudyConfigError) as err:
        validate(study)
    for w in words:
        assert w in str(err.value)


def test_fronts_are_feasible_non_dominated_verified_and_resume_without_simulating(tmp_path, monkeypatch, capsys):
    """A small pinion run (10 NSGA-II trials per front, one epsilon level, COBYLA runs of at most
    50 simulations: none of the 10 trials of the power loss / L10 front is feasible, and the COBYLA
    run from its best needs 31-35 simulations to reach the pinion's thin feasible sliver, measured
    on session 14's physics; 25 had sufficed before by the path's luck): every front point meets the front's constraints and no feasible simulated
    point dominates it (checked here by the definition, independently of studies.pareto); the
    re-simulated fronts (the command raises if they differ from the trials by more than 1e-9), the
    points files and the local stage's resume store pass the DATA.md checker (the last two had no
    attributes before session 31); a second run simulates nothing and writes the same fronts."""
    import subprocess
    import sys
    from pathlib import Path

    import xarray as xr

    from studies.pareto import main

    monkeypatch.chdir(tmp_path)
    args = ["study.name=pareto_test", "study.pareto.trials=10", "study.sampler_settings.population_size=10",
            "study.pareto.levels=1", "study.refine.max_simulations=50"]
    assert main(args) == 0
    out = tmp_path / "outputs" / "studies" / "pareto_test" / "pareto"
    first = {}
    for pair in compose([]).study.pareto.fronts:
        name = f"{pair[0]}_{pair[1]}"
        ds = xr.load_dataset(out / f"points_{name}.nc")
        first[name] = ds
        # the file's form (studies.pareto.points_to_file): designs at the study's one case, pmax as pmax_any_race
        F = np.column_stack([ds[{"pmax": "pmax_any_race"}.get(p, p)].isel(case=0).values for p in pair])
        signs = np.array([1.0 if OBJECTIVES[p][0] == "minimize" else -1.0 for p in pair])
        feasible = np.flatnonzero(ds.feasible.values)
        assert np.all((ds.margin.values[feasible] <= 0.0))
        on = np.flatnonzero(ds.on_front.values)
        assert on.size >= 1 and set(on) <= set(feasible)
        assert sorted(feasible[_brute_force_front(F[feasible], signs)]) == sorted(on)
        assert (out / f"front_{name}.png").stat().st_size > 0
        checker = Path(__file__).resolve().parents[2].parent / "shared" / "tools" / "check_result.py"
        if checker.is_file():
            for nc in (f"front_{name}.nc", f"points_{name}.nc", "local_points.nc"):
                run = subprocess.run([sys.executable, str(checker), str(out / nc)], capture_output=True, text=True)
                assert run.returncode == 0 and "0 finding(s)" in run.stdout, run.stdout + run.stderr
    n_local = xr.load_dataset(out / "local_points.nc").sizes["point"]
    capsys.readouterr()
    assert main(args) == 0
    assert xr.load_dataset(out / "local_points.nc").sizes["point"] == n_local
    assert "10 of 10 simulations already" in capsys.readouterr().out
    for name, ds in first.items():      # the same points; only the time the file was written differs
        again = xr.load_dataset(out / f"points_{name}.nc")
        assert again.attrs.pop("created") >= ds.attrs.pop("created")
        xr.testing.assert_identical(again, ds)


def test_a_study_without_a_feasible_design_has_no_front_and_exits_1(tmp_path, monkeypatch, capsys):
    """The pinion study at 40 kN with 4 trials per front and no local stage: no simulated design
    meets the constraints (the feasible region is a thin sliver even at 35 kN, 0.03 % of a Sobol
    sample). The command exited 0 and each section said "0 on the front, each re-simulated"
    (session 32, an independent check); as studies.optimize without a feasible design, it now
    exits 1 naming the fronts, and pareto.md says there is no front."""
    from studies.pareto import main

    monkeypatch.chdir(tmp_path)
    args = ["study.name=pareto_empty", "study.load.Fa=40000", "study.pareto.trials=4",
            "study.sampler_settings.population_size=4", "study.refine.max_simulations=0"]
    assert main(args) == 1
    err = capsys.readouterr().err
    assert "no feasible design, so no front: " in err
    text = (tmp_path / "outputs" / "studies" / "pareto_empty" / "pareto" / "pareto.md").read_text()
    assert "no feasible design, so no front" in text and "each re-simulated" not in text
