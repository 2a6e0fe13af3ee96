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


def test_a_tilted_grid_is_refused_for_its_grid_not_its_tilt():
    """The time-domain solver takes an imposed tilt since session 36 (tests/dynamic/test_imposed_tilt.py;
    refused before, when its inner ring did not tilt); a grid of tilts is refused as any grid, with
    the way to run it."""
    from sim.api.schema import validate
    validate(sim.load_config(["solver=dynamic", "load.tilt=0.05"]))
    with pytest.raises(InputError, match="--multirun"):
        sim.simulate(sim.load_config(["solver=dynamic", "load.tilt=[0,0.1]"]))
