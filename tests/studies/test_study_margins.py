"""Constraint margins (studies/constraints.py), edge-stress margin and design space (studies/evaluate.py,
studies/space.py): exact values on constructed inputs; the edge margin of simulated designs."""
from dataclasses import replace

import numpy as np
import pytest
from omegaconf import OmegaConf

from sim import CONF_DIR
from sim.physics import ratings
from studies.config import compose, simulation_config
from studies.constraints import FAILED, Limits, margins, rank_key, violation
from studies.evaluate import EDGE_MARGIN, design_config, simulate_point
from studies.space import DesignSpace

LIMITS = Limits(axial_displacement_max=0.047, pmax_max=1300.0, L10_min=150.0, edge_stress=True,
                PCR_over_Lwe_max=10.0, Lwe=24.2, Fa=35000.0, Fr=0.0)
BEARING = {"PCR": 121.0, "ratings_alpha": 24.5}


def values(**kw):
    v = {"pmax": 1300.0, "axial_displacement": -0.047, "C_eff": 1.0e5, "edge_stress_margin": -0.2}
    v.update(kw)
    return v


def test_margins_are_exact_normalised_excesses():
    """pmax at its limit and |axial displacement| at its limit give 0; L10 from (2.12), (2.15)."""
    m = dict(zip(LIMITS.names, margins(values(), BEARING, LIMITS, 0.0)))
    P = ratings.equivalent_dynamic_load(0.0, 35000.0, 24.5)
    assert m["simulation"] == 0.0
    assert m["axial_displacement"] == pytest.approx(0.0, abs=1e-15)  # sign ignored: |-0.047| / 0.047 - 1
    assert m["pmax"] == pytest.approx(0.0, abs=1e-15)
    assert m["L10"] == pytest.approx(1.0 - (1.0e5 / P) ** (10.0 / 3.0) / 150.0, rel=1e-12)
    assert m["edge_stress"] == -0.2
    assert m["PCR_over_Lwe"] == pytest.approx(121.0 / 242.0 - 1.0, rel=1e-12)
    m2 = dict(zip(LIMITS.names, margins(values(pmax=1430.0), BEARING, LIMITS, 0.0)))
    assert m2["pmax"] == pytest.approx(0.1, rel=1e-12)


def test_a_point_without_result_is_infeasible_not_dropped():
    """NaN results: the simulation margin alone (1) marks it; the others are 0, the geometric one exact."""
    nan = values(pmax=np.nan, axial_displacement=np.nan, C_eff=np.nan, edge_stress_margin=np.nan)
    m = margins(nan, BEARING, LIMITS, FAILED)
    assert m[0] == FAILED > 0.0
    assert np.all(m[1:-1] == 0.0)
    assert violation(m) == FAILED
    assert rank_key(np.nan, m) == (2, FAILED)  # behind every point with a result, however infeasible
    assert rank_key(5000.0, [0.0, 3.0]) < rank_key(np.nan, m)


def test_edge_stress_switch_and_rank_order():
    no_edge = replace(LIMITS, edge_stress=False)
    assert "edge_stress" not in no_edge.names
    assert len(margins(values(), BEARING, no_edge, 0.0)) == len(no_edge.names)
    assert sorted([(1, 0.5), (0, 900.0), (0, 800.0)]) == [(0, 800.0), (0, 900.0), (1, 0.5)]
    assert rank_key(800.0, [-1.0, -0.1]) == (0, 800.0)


@pytest.mark.parametrize("PCR, flagged", [(51.0, True), (25.0, False)])
def test_edge_stress_margin_has_the_sign_of_the_simulation_flag(PCR, flagged):
    """The study's edge margin is the simulation's edge_interference (max over the races) and is
    > 0 exactly when the simulation flags edge stress: the pinion template at its study load with
    a flatter crown (the contact runs onto the large end) and a more crowned one (it ends inside)."""
    study = compose([]).study
    ds, record = simulate_point(design_config(simulation_config(study, study.bearing), {"PCR": PCR}), ("pmax",))
    margin = record["values"][EDGE_MARGIN]
    assert margin == pytest.approx(float(ds.edge_interference.max()), rel=0, abs=0)
    assert (margin > 0.0) == bool(ds.edge_stress) == flagged


def test_a_numerical_failure_is_recorded_as_failed_and_an_input_error_stops_the_search(monkeypatch):
    """simulate_point's error path: an exception of the simulation that is not an InputError (a
    numerical failure that depends on the design) is a result of that point, recorded as failed with
    its type and message, and the search goes on; an InputError (the same for every point) is a
    configuration error and propagates. The simulation is replaced by one that raises, since no
    shipped design fails numerically on purpose."""
    import studies.evaluate as evaluate
    from sim.errors import InputError

    study = compose([]).study
    cfg = design_config(simulation_config(study, study.bearing), {"PCR": 25.0})

    def diverges(cfg):
        raise FloatingPointError("roller 3 did not converge")

    monkeypatch.setattr(evaluate, "simulate", diverges)
    ds, record = simulate_point(cfg, ("pmax",))
    assert ds is None and record["status"] == "failed"
    assert record["message"] == "FloatingPointError: roller 3 did not converge"
    assert np.isnan(record["values"]["pmax"])

    def refuses(cfg):
        raise InputError("load.Fa = -1 is outside the allowed range [0, inf)")

    monkeypatch.setattr(evaluate, "simulate", refuses)
    with pytest.raises(InputError, match="load.Fa = -1"):
        simulate_point(cfg, ("pmax",))


@pytest.fixture(scope="module")
def space():
    cfg = compose([])
    return DesignSpace.from_config(cfg.study, OmegaConf.load(CONF_DIR / "bearing" / f"{cfg.study.bearing}.yaml"))


@pytest.mark.parametrize("method", ["sobol", "lhs"])
def test_space_filling_design_stays_in_bounds_and_fills_them(space, method):
    """64 points (scipy.stats.qmc): inside the box, and each parameter's range is covered to within 1/64
    at both ends for LHS (one point per stratum) and 5 % for scrambled Sobol."""
    X = space.sample(64, method, seed=0)
    assert X.shape == (64, len(space.names))
    U = space.unit(X)
    assert np.all((U >= 0.0) & (U <= 1.0))
    assert np.all(U.min(axis=0) < 0.05) and np.all(U.max(axis=0) > 0.95)
    np.testing.assert_array_equal(X, space.sample(64, method, seed=0))  # reproducible


def test_ratings_alpha_follows_a_free_alpha(space):
    x = (space.low + space.high) / 2.0
    b = space.bearing_values(x)
    assert b["ratings_alpha"] == b["alpha"] == pytest.approx(25.0)
    fixed = DesignSpace(("PCR",), np.array([30.0]), np.array([150.0]), space.template)
    b = fixed.bearing_values([60.0])
    assert (b["PCR"], b["alpha"], b["ratings_alpha"]) == (60.0, 24.5, 24.5)  # template tsrb_pinion
