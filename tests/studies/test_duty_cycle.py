"""Duty-cycle design study (issue 16 item 5; studies/cycle.py, conf/study/pinion_duty.yaml).

The equivalent load of ISO 281 / Harris over a cycle, the time-weighted objective against the
hand sum of per-case simulations, the one-case cycle against the single-case study, constraints
at every case, refused cycles, failed cases and resume. Simulations run for real with 10 slices
on tiny budgets (a few seconds after the numba compile).
"""
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from omegaconf import OmegaConf

import sim
from studies.config import StudyConfigError, check_simulations, compose
from studies.constraints import Limits, margins, violation
from studies.cycle import LIFE_EXPONENT, DutyCycle, cycle_life, equivalent_load, summary_values
from studies.evaluate import STATUS, points_dataset, table_from_file
from studies.loop import DesignSearch
from studies.report import write_report
from tests.helpers import assert_study_refused, killed_search_run

FAST = ["solver.n_slices=10", "study.n_jobs=1", "study.surrogate.n_restarts_optimizer=0"]
CHECKER = Path(__file__).resolve().parents[2].parent / "shared" / "tools" / "check_result.py"
TINY_DUTY = ["study=pinion_duty", *FAST, "study.initial_design.n=8", "study.budget.max_simulations=10",
             "study.budget.verify_per_round=2", "study.refine.max_simulations=0"]


def search_in(folder, *overrides):
    search = DesignSearch(compose(list(overrides)), list(overrides), out_dir=folder, log=lambda msg: None)
    search.run_references()
    return search


# ---------------------------------------------------------------------------- formulas
def test_equivalent_load_of_a_two_case_cycle_by_hand():
    """P_eq = (sum share n P^p / sum share n)^(1/p), p = 10/3 (ISO 281; Harris & Kotzalas 2007,
    mean effective load). Two cases: 10 kN at 1000 rpm for 25 % of the time, 20 kN at 500 rpm for
    75 %: weights 250 and 375, P_eq = 10 kN x ((250 + 375 x 2^(10/3)) / 625)^(3/10)
    = 17491.2098858283 N (evaluated with 40-digit decimal arithmetic). rtol 1e-12: a few float
    roundings of the powers; a wrong weight (time share alone: 18 360 N) is off by 5 %."""
    P_eq = equivalent_load([10000.0, 20000.0], [1000.0, 500.0], [0.25, 0.75])
    assert P_eq == pytest.approx(17491.2098858283, rel=1e-12)
    # Palmgren-Miner: with one rating C the cycle life is the revolution-weighted harmonic mean of the case lives
    C = 150000.0
    lives = np.array([(C / 10000.0) ** LIFE_EXPONENT, (C / 20000.0) ** LIFE_EXPONENT])
    miner = 625.0 / (250.0 / lives[0] + 375.0 / lives[1])
    assert cycle_life([C, C], [10000.0, 20000.0], [1000.0, 500.0], [0.25, 0.75]) == pytest.approx(miner, rel=1e-12)
    # the least C_eff of the cycle rates it; one case is its own equivalent load
    assert cycle_life([C, 2 * C], [1e4, 2e4], [1e3, 5e2], [0.25, 0.75]) == cycle_life([C, C], [1e4, 2e4], [1e3, 5e2],
                                                                                     [0.25, 0.75])
    assert equivalent_load([12345.678], [700.0], [1.0]) == 12345.678


def test_cycle_summary_of_a_design():
    """The one-line values of a design over a cycle (report tables, direct search): objective
    time-weighted, worst pmax and edge margin, axial displacement of largest magnitude (sign kept),
    least C_eff, P_eq and L10 over the cycle; one case returns its own values."""
    study = OmegaConf.create({"load": {"Fa": 1.0, "Fr": 0.0, "speed": 1.0, "tilt": 0.0, "oil_temperature": 50.0},
                              "duty_cycle": [{"Fa": 1e4, "Fr": 0.0, "speed": 1000.0, "share": 0.25},
                                             {"Fa": 2e4, "Fr": 0.0, "speed": 500.0, "share": 0.75}]})
    cycle = DutyCycle.from_config(study)
    values = {"power_loss": [100.0, 300.0], "pmax": [900.0, 1200.0], "axial_displacement": [0.01, -0.03],
              "C_eff": [160000.0, 150000.0], "P": [10000.0, 20000.0], "L10": [1.0, 1.0],
              "edge_stress_margin": [-0.5, -0.2]}
    out = summary_values(values, cycle, "power_loss")
    assert out["power_loss"] == 0.25 * 100.0 + 0.75 * 300.0
    assert (out["pmax"], out["axial_displacement"], out["C_eff"], out["edge_stress_margin"]) == (1200.0, -0.03, 150000.0,
                                                                                                 -0.2)
    assert out["P"] == pytest.approx(17491.2098858283, rel=1e-12)          # the hand value above
    # rtol 1e-11: the 1e-12 of P_eq raised to p = 10/3
    assert out["L10"] == pytest.approx((150000.0 / 17491.2098858283) ** LIFE_EXPONENT, rel=1e-11)
    one = DutyCycle.from_config(OmegaConf.create({"load": study.load, "duty_cycle": None}))
    single = {q: v[:1] for q, v in values.items()}
    single["L10"] = [(160000.0 / 10000.0) ** LIFE_EXPONENT]
    assert summary_values(single, one, "power_loss") == {q: v[0] for q, v in single.items()}


def limits_of_three_cases():
    """Three cases (the pinion_duty cycle), per-case pmax limits 1600/1300/1000 MPa, L10_min low enough
    that the C_eff below passes."""
    return Limits(axial_displacement_max=0.047, pmax_max=(1600.0, 1300.0, 1000.0), L10_min=10.0, edge_stress=True,
                  PCR_over_Lwe_max=10.0, Lwe=24.2, Fa=(60000.0, 35000.0, 15000.0), Fr=(0.0, 0.0, 0.0),
                  speed=(550.0, 1100.0, 1600.0), share=(0.1, 0.6, 0.3))


def test_a_constraint_violated_at_only_one_case_makes_the_design_infeasible():
    limits = limits_of_three_cases()
    bearing = {"PCR": 80.0, "ratings_alpha": 24.5}
    good = {"pmax": np.array([1500.0, 1200.0, 900.0]), "axial_displacement": np.array([0.04, -0.02, 0.01]),
            "C_eff": np.full(3, 120000.0), "edge_stress_margin": np.array([-0.5, -0.6, -0.7])}
    assert violation(margins(good, bearing, limits, 0.0)) == 0.0
    names = limits.names
    for key, k, bad_value, constraint in (("pmax", 2, 1001.0, "pmax"),            # 1001 > 1000 at case 2 only
                                          ("axial_displacement", 1, -0.05, "axial_displacement"),
                                          ("edge_stress_margin", 0, 0.01, "edge_stress")):
        values = {q: v.copy() for q, v in good.items()}
        values[key][k] = bad_value
        m = margins(values, bearing, limits, 0.0)
        assert violation(m) > 0.0
        assert [n for n, v in zip(names, m) if v > 0.0] == [constraint]
    # pmax 1500 MPa is within case 0's limit (1600) but would violate case 1's: each case has its own limit
    values = {q: v.copy() for q, v in good.items()}
    values["pmax"][1] = 1500.0
    assert margins(values, bearing, limits, 0.0)[names.index("pmax")] == pytest.approx(1500.0 / 1300.0 - 1.0)


# ---------------------------------------------------------------------------- configuration
@pytest.fixture(scope="module")
def duty_study():
    return compose(["study=pinion_duty"]).study


def test_pinion_duty_spans_the_thesis_range(duty_study):
    """conf/study/pinion_duty.yaml: thesis 7.4.2, 15-60 kN x 550-1600 rpm, shares summing to 1."""
    cycle = DutyCycle.from_config(duty_study)
    assert (cycle.column("Fa").min(), cycle.column("Fa").max()) == (15000.0, 60000.0)
    assert (cycle.column("speed").min(), cycle.column("speed").max()) == (550.0, 1600.0)
    assert math.fsum(cycle.share) == pytest.approx(1.0, abs=1e-12)
    assert duty_study.objective == "power_loss" and duty_study.bearing == "tsrb_pinion"


@pytest.mark.parametrize("key, value, words", [
    ("duty_cycle[1].share", 0.5, ["study.duty_cycle[*].share", "[0.1, 0.5, 0.3]", "summing to 1", "0.9"]),
    ("duty_cycle[0].share", 0.0, ["study.duty_cycle[0].share", "0.0", "(0, 1]"]),
    ("duty_cycle[2].speed", 0.0, ["study.duty_cycle[2].speed", "0.0", "> 0"]),
    ("duty_cycle[1].Fa", "heavy", ["study.duty_cycle[1].Fa", "'heavy'", "finite number"]),
    ("duty_cycle[0]", {"Fa": 1.0, "Fr": 0.0, "share": 0.1}, ["study.duty_cycle[0]", "Fa, Fr, speed, share"]),
    ("duty_cycle", [], ["study.duty_cycle", "[]", "non-empty list"]),
])
def test_bad_cycles_are_refused_naming_the_key(duty_study, key, value, words):
    assert_study_refused(duty_study, key, value, words)


def test_a_case_the_simulation_refuses_is_named_by_its_cycle_key(duty_study):
    study = duty_study.copy()
    OmegaConf.update(study, "duty_cycle[2].Fa", -5.0, merge=False)
    with pytest.raises(StudyConfigError, match=r"study\.duty_cycle\[2\]\.Fa = -5\.0"):
        check_simulations(study)


# ---------------------------------------------------------------------------- objective
def test_time_weighted_objective_is_the_hand_sum_of_per_case_simulations(tmp_path):
    """The cycle objective of two designs equals sum_i share_i P_i, P_i [W] the power loss of
    sim.simulate at each case, to rtol 1e-9 (the sums differ by float rounding only, ~1e-15; a lost
    share or case moves it by > 1 %). It also equals sum_i share_i T_i omega_i (T_i [N mm] the
    outer-ring torque, omega_i = 2 pi n_i / 60 [rad/s], / 1000 to W) to rtol 1e-5: the simulation's
    power loss (summed dissipation) equals T omega only up to its kinematic balance,
    friction.tolerance = 1e-6 of the roller and cage moments (sim/api/friction_model.py; measured
    7e-7 here)."""
    search = search_in(tmp_path, "study=pinion_duty", *FAST)
    X = search.space.sample(2, "sobol", 3)
    ds = search.simulate(X, "initial", 0)
    assert ds.sizes["case"] == 3 and np.all(ds.status.values == STATUS["ok"])
    for i, x in enumerate(X):
        hand = hand_torque = 0.0
        for case, share in zip(search.cycle.cases, search.cycle.share):
            cfg = sim.load_config(["bearing=tsrb_pinion", "lubricant=pinion_oil", *FAST[:1]])
            for key, value in {**case, **search.space.bearing_values(x)}.items():
                if value is not None:       # a per-point osculation left to follow kappa
                    (cfg.load if key in case else cfg.bearing)[key] = float(value)
            result = sim.simulate(cfg).isel(design=0, case=0)
            hand += share * float(result.power_loss)
            hand_torque += share * float(result.torque) * 2.0 * np.pi * case["speed"] / 60.0 / 1000.0
        assert search.objective_values(ds)[i] == pytest.approx(hand, rel=1e-9)
        assert search.objective_values(ds)[i] == pytest.approx(hand_torque, rel=1e-5)


def test_a_one_case_cycle_is_the_single_case_study_bit_for_bit(tmp_path):
    """study.duty_cycle with the one case of pinion.yaml's load (share 1) gives the single-case study's
    objective and margins exactly (==): the cycle reductions are identities for one case."""
    single = search_in(tmp_path / "single", *FAST)
    cycle = search_in(tmp_path / "cycle", *FAST, "study.duty_cycle=[{Fa: 35000.0, Fr: 0.0, speed: 1100.0, share: 1.0}]")
    assert single.limits == cycle.limits
    X = single.space.sample(4, "sobol", 5)
    a, b = single.simulate(X, "initial", 0), cycle.simulate(X, "initial", 0)
    np.testing.assert_array_equal(single.objective_values(a), cycle.objective_values(b))
    np.testing.assert_array_equal(single.objective_values(a), a.torque.values[:, 0])
    np.testing.assert_array_equal(single.point_margins(a), cycle.point_margins(b))


# ---------------------------------------------------------------------------- failed cases, resume, report
def test_a_failed_case_is_recorded_as_failed_and_fails_its_design(duty_study):
    search_cycle = DutyCycle.from_config(duty_study)

    def record(status, value):
        return {"status": status, "message": "" if status == "ok" else "diverged", "values": {"pmax": value},
                "attrs": {"pmax": {"units": "MPa", "long_name": "pmax"}}, "wall_time": 0.01}

    from studies.space import POINT_OSCULATIONS, DesignSpace
    space = DesignSpace(("PCR",), np.array([20.0]), np.array([150.0]),
                        {**{k: 1.0 for k in ("PCR", "kappa", "aP", "aPk", "alpha", "ratings_alpha")},
                         **dict.fromkeys(POINT_OSCULATIONS)})       # per-point osculations follow kappa
    records = [[record("ok", 1.0), record("ok", 2.0), record("ok", 3.0)],
               [record("ok", 1.0), record("failed", np.nan), record("ok", 3.0)]]
    ds = points_dataset(space, np.array([[50.0], [60.0]]), records, "initial", 0, {}, search_cycle)
    assert list(ds.status.values) == [STATUS["ok"], STATUS["failed"]]
    assert list(ds.case_status.values[1]) == [STATUS["ok"], STATUS["failed"], STATUS["ok"]]
    assert ds.message.values[1, 1] == "diverged" and np.isnan(ds.pmax.values[1, 1]) and ds.pmax.values[1, 2] == 3.0
    np.testing.assert_array_equal(ds.share.values, search_cycle.share)


@pytest.fixture(scope="module")
def duty_finished(tmp_path_factory):
    search = search_in(tmp_path_factory.mktemp("duty"), *TINY_DUTY)
    ds, reason = search.run()
    return search, ds, reason


def test_duty_search_resumes_its_per_case_evaluations(duty_finished, tmp_path):
    """Killed during the second chunk of the initial design (4 designs x 3 cases each), then run again:
    the per-case results of the first chunk are kept and the search ends with the uninterrupted
    run's points, bit for bit."""
    _, reference, _ = duty_finished
    search = search_in(tmp_path, *TINY_DUTY)
    calls = killed_search_run(search)
    stored = table_from_file(xr.load_dataset(tmp_path / "training.nc"))
    assert calls == [4, 4] and (stored.sizes["design"], stored.sizes["case"]) == (4, 3)
    assert np.all(np.isfinite(stored.power_loss.values[stored.status.values == STATUS["ok"]]))
    resumed, _ = search_in(tmp_path, *TINY_DUTY).run()
    for name in ("PCR", "kappa", "aP", "aPk", "alpha", "power_loss", "pmax", "status", "case_status"):
        np.testing.assert_array_equal(resumed[name].values, reference[name].values)


def test_duty_report_names_the_cycle_and_the_ratio_to_the_trb(duty_finished):
    search, ds, reason = duty_finished
    assert ds.sizes["design"] == 10 and ds.power_loss.dims == ("design", "case")
    text = write_report(search, ds, reason)
    assert "duty cycle Fa/Fr, speed, share: 60/0 kN 550 rpm 0.1; 35/0 kN 1100 rpm 0.6; 15/0 kN 1600 rpm 0.3" in text
    assert "| case | Fa [N] |" in text and text.count("| 1600 | 0.3 |") == 1
    if CHECKER.exists():   # the DATA.md checker of ../shared, as for the single-case files
        for name in ("training.nc", "verified.nc", "best_design.nc"):
            chk = subprocess.run([sys.executable, str(CHECKER), str(search.out / name)], capture_output=True, text=True)
            assert chk.returncode == 0, chk.stdout
    best = xr.load_dataset(search.out / "best_design.nc")
    assert best.sizes["case"] == 3
    trb = search.references["reference TRB"].record["values"]["power_loss"]
    mine = float(np.sum(best.power_loss.values[0] * search.cycle.share))
    r = mine / trb
    assert f"power_loss {abs(100 * (r - 1)):.1f} % {'below' if r < 1 else 'above'} the reference TRB trb_31313" in text
    assert "over the duty cycle" in text and "Rating life over the cycle" in text


def test_one_case_commands_refuse_a_cycle_before_simulating(tmp_path, monkeypatch, capsys):
    """studies.pareto runs one load case: a duty cycle is refused (exit 2, the key named) before any
    simulation, and the study folder it would have made is removed again."""
    from studies import pareto

    monkeypatch.chdir(tmp_path)
    assert pareto.main(["study=pinion_duty"]) == 2
    assert "study.duty_cycle has 3 load cases: python -m studies.pareto runs one load case" in capsys.readouterr().err
    assert not (tmp_path / "outputs").exists()
