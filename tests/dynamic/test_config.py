"""solver=dynamic input checks: refused before any numerics, naming the key, value and range."""
import pytest

import sim
from sim.errors import ConfigError, InputError


def test_a_dynamic_key_out_of_range_is_refused_by_name():
    cfg = sim.load_config(["solver=dynamic", "solver.dynamic.rtol=5"])
    with pytest.raises(ConfigError, match=r"solver\.dynamic\.rtol = 5 is outside the allowed range"):
        sim.simulate(cfg)


def test_a_missing_dynamic_key_is_refused_by_name():
    cfg = sim.load_config(["solver=dynamic", "~solver.dynamic.max_windows"])
    with pytest.raises(ConfigError, match=r"solver\.dynamic\.max_windows is missing"):
        sim.simulate(cfg)


def test_the_quasi_static_config_has_no_dynamic_node_to_check():
    from sim.api.schema import validate
    validate(sim.load_config([]))   # solver.dynamic is null there: nothing to check, no error


def test_a_load_grid_is_refused_with_the_way_to_run_it():
    cfg = sim.load_config(["solver=dynamic", "load.Fa=[3000,4500]"])
    with pytest.raises(InputError, match="--multirun"):
        sim.simulate(cfg)


@pytest.mark.parametrize("tilt", ["0.05", "[0,0.1]"])
def test_an_imposed_tilt_is_refused_as_the_time_domain_model_has_none(tilt):
    """The time-domain inner ring translates but does not tilt (sim.solvers.dynamic): a tilted case
    ran as if untilted, its result labelled with the tilt (TRB 32208 at 9 / 3 kN, 3000 rpm, tilt
    0.05 deg gave the untilted 1096.9 N mm against the quasi-static 1070.8 N mm; an independent
    check of session 31). Refused before anything is built, as any out-of-range key; the
    quasi-static solver takes it."""
    cfg = sim.load_config(["solver=dynamic", f"load.tilt={tilt}"])
    with pytest.raises(ConfigError, match=r"load\.tilt = .* solver=dynamic: 0 .*solver=quasi_static"):
        sim.simulate(cfg)
    from sim.api.schema import validate
    validate(sim.load_config([f"load.tilt={tilt}"]))   # quasi-static: allowed
