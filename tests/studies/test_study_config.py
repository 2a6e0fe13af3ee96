"""Study configuration (conf/study/, studies/config.py): composition and refusal at start.

Issue 5: bad values (unknown sampler, bounds reversed, budget < 1) fail at start with a
message naming the key, the value and the allowed range.
"""
import pytest
from omegaconf import OmegaConf

from studies.config import StudyConfigError, compose, simulation_config, validate
from studies.optimize import main
from tests.helpers import assert_study_refused


@pytest.fixture(scope="module")
def pinion():
    return compose([]).study


def test_default_is_pinion_and_size_32208_inherits_it(pinion):
    """pinion.yaml is the default; size_32208.yaml overrides only its own keys (thesis 7.4 vs 7.2.5)."""
    size = compose(["study=size_32208"]).study
    assert (pinion.name, pinion.bearing, pinion.reference_trb, pinion.load.Fa) == ("pinion", "tsrb_pinion",
                                                                                   "trb_31313", 35000.0)
    assert pinion.constraints.axial_displacement_max == 0.047  # thesis Annex A.2.1
    assert (size.name, size.bearing, size.reference_trb, size.load.Fa) == ("size_32208", "tsrb_reference",
                                                                           "trb_32208", 4500.0)
    assert size.surrogate == pinion.surrogate  # inherited
    assert compose(["study.sampler=nsga2"]).study.sampler == "nsga2"


def test_simulation_config_carries_the_study_load_case(pinion):
    cfg = simulation_config(pinion, "trb_31313", ["solver.n_slices=12"])
    assert (cfg.bearing.type, cfg.load.Fa, cfg.load.Fr, cfg.load.speed, cfg.solver.n_slices) == \
        ("TRB", 35000.0, 0.0, 1100.0, 12)


@pytest.mark.parametrize("key, value, words", [
    ("sampler", "simplex", ["study.sampler", "'simplex'", "tpe", "gp", "nsga2"]),
    ("bounds.PCR", [150.0, 30.0], ["study.bounds.PCR", "[150.0, 30.0]", "low < high"]),
    ("budget.max_simulations", 0, ["study.budget.max_simulations", "0", ">= initial_design.n"]),
    ("budget.verify_per_round", 0, ["study.budget.verify_per_round", "0", ">= 1"]),
    ("free", ["PCR", "gamma"], ["study.free", "gamma", "PCR", "kappa"]),
    ("initial_design.method", "grid", ["study.initial_design.method", "'grid'", "sobol", "lhs"]),
    ("constraints.pmax_max", -1, ["study.constraints.pmax_max", "-1", "'trb'"]),
    ("surrogate.interval", 1.5, ["study.surrogate.interval", "1.5", "(0, 1)"]),
    ("storage", "outputs/x.db", ["study.storage", "outputs/x.db", "journal:"]),
    ("workers.grace_period", 5, ["study.workers.grace_period", "5", "> workers.heartbeat_interval = 10"]),
    ("workers.heartbeat_interval", 0.5, ["study.workers.heartbeat_interval", "0.5", "integer >= 1"]),
    ("bearing", "tsrb_missing", ["study.bearing", "tsrb_missing", "tsrb_pinion"]),
    ("refine.max_simulations", -1, ["study.refine.max_simulations", "-1", "0 (no local stage)", ">= 7"]),
    ("refine.max_simulations", 6, ["study.refine.max_simulations", "6", ">= 7", "first simplex of 6 points"]),
    ("refine.max_simulations", False, ["study.refine.max_simulations", "False", ">= 7"]),
    ("refine.initial_step", 0.0, ["study.refine.initial_step", "0.0", "(0, 1]"]),
    ("refine.final_step", 0.5, ["study.refine.final_step", "0.5", "<= refine.initial_step"]),
    ("refine.restarts", -1, ["study.refine.restarts", "-1", ">= 0"]),
    ("refine.restart_shrink", 1.5, ["study.refine.restart_shrink", "1.5", "(0, 1]"]),
    ("refine.constraint_backoff", -0.001, ["study.refine.constraint_backoff", "-0.001", "[0, 0.1)"]),
    ("refine.starts", 0, ["study.refine.starts", "0", ">= 1"]),
    ("refine.start_distance", 2.0, ["study.refine.start_distance", "2.0", "[0, 1]"]),
    ("refine.start_simulations", 0, ["study.refine.start_simulations", "0", ">= 1"]),
    ("acquisition.n_global", 0, ["study.acquisition.n_global", "0", ">= 1"]),
    ("acquisition.n_local", -5, ["study.acquisition.n_local", "-5", ">= 0"]),
    ("acquisition.local_scales", [0.1, 0.0], ["study.acquisition.local_scales", "[0.1, 0.0]", "(0, 1]"]),
    ("acquisition.local_scales", [], ["study.acquisition.local_scales", "[]", "non-empty"]),
    ("acquisition.n_centres", 0, ["study.acquisition.n_centres", "0", ">= 1"]),
    ("acquisition.n_polish", -1, ["study.acquisition.n_polish", "-1", ">= 0"]),
    ("acquisition.n_polish", 2.5, ["study.acquisition.n_polish", "2.5", "integer"]),
    ("acquisition.polish_iterations", 0, ["study.acquisition.polish_iterations", "0", ">= 1"]),
    ("acquisition.batch_distance", 1.0, ["study.acquisition.batch_distance", "1.0", "[0, 1)"]),
    ("acquisition.n_diverse", -1, ["study.acquisition.n_diverse", "-1", "null", ">= 0"]),
    ("surrogate.calibrate", "yes", ["study.surrogate.calibrate", "'yes'", "true or false"]),
    ("verify.solver", "adams", ["study.verify.solver", "'adams'", "quasi_static", "dynamic"]),
])
def test_bad_values_fail_at_start_naming_key_value_and_range(pinion, key, value, words):
    assert_study_refused(pinion, key, value, words)


def test_study_owned_groups_are_refused():
    with pytest.raises(StudyConfigError, match="load.Fa"):
        compose(["load.Fa=1000"])
    with pytest.raises(StudyConfigError, match="study.bearing"):
        compose(["bearing=trb_32208"])


def test_command_line_exits_2_with_the_message(capsys):
    """The overrides of the command line reach the check (``python -m studies.optimize study.sampler=...``)."""
    assert main(["study.sampler=simplex"]) == 2
    assert "study.sampler = 'simplex'" in capsys.readouterr().err
    assert main(["study.bounds.kappa=[0.99,0.9]"]) == 2
    assert "study.bounds.kappa = [0.99, 0.9]" in capsys.readouterr().err


def test_pinion_asym_searches_the_point_osculations_from_the_included_design():
    """conf/study/pinion_asym.yaml (issue 16 item 7): pinion's load case, constraints and bounds, the
    four per-point osculations free instead of kappa, and the included symmetric design simulated
    first, its per-point osculations all equal to its kappa; the names are the schema's keys."""
    from sim.config_schema import BearingConfig
    from sim.geometry import OSCULATION_KEYS
    from studies.space import POINT_OSCULATIONS
    from studies.space import DesignSpace

    assert list(POINT_OSCULATIONS) == [k for pair in OSCULATION_KEYS for k in pair]
    assert set(POINT_OSCULATIONS) <= set(BearingConfig.__dataclass_fields__)
    cfg = compose(["study=pinion_asym"])
    s = cfg.study
    validate(s)
    pinion = compose([]).study
    assert (s.load, s.constraints, s.bounds.PCR, s.bounds.aP) == (pinion.load, pinion.constraints, pinion.bounds.PCR,
                                                                  pinion.bounds.aP)
    assert set(POINT_OSCULATIONS) <= set(s.free) and "kappa" not in s.free
    space = DesignSpace.from_config(s, simulation_config(s, s.bearing, []).bearing)
    start = space.include(s.initial_design.include)[0]
    point = s.initial_design.include[0]
    assert [start[space.names.index(k)] for k in POINT_OSCULATIONS] == [point.kappa] * 4


def test_point_osculations_left_null_follow_kappa_in_a_study(pinion):
    """A symmetric study leaves the per-point keys null (no coordinate, no override: the geometry
    takes kappa); a free one starts at the template's kappa."""
    from studies.space import DesignSpace

    bearing = simulation_config(pinion, pinion.bearing, []).bearing
    space = DesignSpace.from_config(pinion, bearing)
    assert space.template["kappa_outer_small"] is None
    assert space.bearing_values(space.low)["kappa_outer_small"] is None
    study = OmegaConf.create(OmegaConf.to_container(pinion))
    study.free = ["PCR", "kappa_outer_small"]
    study.bounds.kappa_outer_small = [0.9, 0.99]
    assert DesignSpace.from_config(study, bearing).template["kappa_outer_small"] == bearing.kappa


@pytest.mark.parametrize("include, words", [
    ([{"PCR": 50.0}], ["study.initial_design.include[0]", "every free parameter"]),
    ([{"PCR": 500.0, "kappa": 0.95, "aP": 8.0, "aPk": 6.0, "alpha": 25.0}],
     ["study.initial_design.include[0].PCR", "500.0", "study.bounds.PCR = [20.0, 150.0]"]),
])
def test_bad_included_designs_fail_at_start(pinion, include, words):
    study = OmegaConf.create(OmegaConf.to_container(pinion))
    study.initial_design.include = include
    with pytest.raises(StudyConfigError) as err:
        validate(study)
    for w in words:
        assert w in str(err.value)


@pytest.mark.parametrize("override, words", [
    ("study.bounds.kappa=[0.9,1.003]", ["study.bounds.kappa = [0.9, 1.003]", "upper end", "bearing.kappa = 1.003",
                                        "(0, 1)"]),
    ("study.bounds.alpha=[10,95]", ["study.bounds.alpha = [10.0, 95.0]", "upper end", "bearing.alpha = 95.0",
                                    "(0, 60)"]),
    ("study.bounds.PCR=[-5,100]", ["study.bounds.PCR = [-5.0, 100.0]", "lower end", "bearing.PCR = -5.0"]),
    ("+study.bounds.kapa=[0.9,0.99]", ["study.bounds.kapa = [0.9, 0.99]", "design parameters", "'kappa'"]),
])
def test_a_bound_outside_the_bearing_schema_is_refused_before_any_simulation(override, words):
    """A search bound the bearing schema does not allow (kappa < 1, alpha <= 60 deg, PCR > 0), or of a
    name that is no design parameter (a typo, which bounded nothing), is refused at start, naming the study key, which end and the schema's range; before, the study simulated
    its references and initial designs and then stopped at the first design beyond the bound,
    naming that design's value (an independent check of session 31)."""
    with pytest.raises(StudyConfigError) as err:
        compose(["study=size_32208", override])
    for w in words:
        assert w in str(err.value)
