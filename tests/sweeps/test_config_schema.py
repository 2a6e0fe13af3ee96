"""Config schemas (sim/config_schema.py, validated by sim.api.schema): every shipped config composes and passes; a typo or an
out-of-range value is refused naming the key and what is allowed; every value has its source."""
import re

import pytest
from hydra import compose, initialize_config_dir
from omegaconf import OmegaConf

import sim
from sim.api.schema import ConfigError, validate
from sim.api.sweep import sweep_jobs

CONF = sim.CONF_DIR
OPTIONS = [(group, p.stem) for group in ("bearing", "material", "lubricant", "friction", "load", "solver", "output")
           for p in sorted((CONF / group).glob("*.yaml"))]
VARIANTS = sorted(p.stem for p in (CONF / "variant").glob("*.yaml"))
OURS = ["load", "output", "hydra/launcher", "variant", "experiment"]  # files whose every value cites a source


@pytest.mark.parametrize("group, option", OPTIONS)
def test_every_group_option_composes_and_passes(group, option):
    """Each conf/<group>/*.yaml holds exactly schema keys and values in range."""
    validate(sim.load_config([f"{group}={option}"]))


def test_sensitivity_experiment_defines_28_valid_jobs():
    """+experiment=sensitivity: 14 designs (TRB 32208, the reference, the 12 variations of Table 7.2)
    x 2 load grids; every variant composes and passes, aP variations keep aPk = (Lwe - aP)/2."""
    with initialize_config_dir(config_dir=str(CONF), version_base="1.3"):
        jobs = sweep_jobs(compose("config", overrides=["+experiment=sensitivity"], return_hydra_config=True))
        configs = {v: compose("config", overrides=[f"+variant={v}", "load=sensitivity_speeds"]) for v in VARIANTS}
        validate(compose("config", overrides=["load=high_axial_load"]))
    assert len(jobs) == 28 and len(VARIANTS) == 14
    assert {job[0].split("=")[1] for job in jobs} == set(VARIANTS)
    for cfg in configs.values():
        validate(cfg)
    for v in ("aP_up", "aP_down"):
        assert configs[v].bearing.aPk == pytest.approx((configs[v].bearing.Lwe - configs[v].bearing.aP) / 2)
    assert configs["trb_32208"].bearing.type == "TRB" and configs["PCR_down2"].bearing.PCR == 28.0


@pytest.mark.parametrize("overrides, message", [
    (["bearing.aP=-5"], "bearing.aP = -5 is outside the allowed range: a number in [0.001, 100000] mm"),
    (["load.Fa=abc"], "load.Fa = 'abc' is outside the allowed range: a number in (0, 1e+07] N, or a list of them"),
    (["bearing.kappa=1.0"], "bearing.kappa = 1.0 is outside the allowed range: a number in (0, 1)"),
    (["bearing.Z=3.5"], "bearing.Z = 3.5 is outside the allowed range: an integer >= 3"),
    (["solver.elasticity=rigid"], "solver.elasticity = 'rigid' is outside the allowed range: one of 'coupled', 'independent'"),
    (["bearing=trb_32208", "bearing.PCR=100"], "bearing.PCR = 100 does not apply to a TRB (a TSRB parameter)"),
    (["lubricant.viscosity=[57.0,-1.0]"], "lubricant.viscosity = [57.0, -1.0] is outside the allowed range: a list of numbers > 0 mm^2/s"),
    (["load.Fa=[1000,2000]", "load.Fr=[0,1,2]", "load.zip=[[Fa,Fr]]"], "zipped lists need equal lengths"),
])
def test_bad_value_is_refused_naming_key_and_range(overrides, message):
    with pytest.raises(ConfigError) as err:
        validate(sim.load_config(overrides))
    assert message in str(err.value)


def test_all_bad_values_are_reported_at_once():
    with pytest.raises(ConfigError) as err:
        validate(sim.load_config(["bearing.PCR=-5", "load.speed=-1", "material.nu=0.7"]))
    assert [line.split(" = ")[0] for line in str(err.value).splitlines()] == ["bearing.PCR", "material.nu", "load.speed"]


@pytest.mark.parametrize("override", ["bearing.kapa=0.9", "load.Fx=1"])
def test_unknown_key_fails_composition_naming_it(override):
    """A typo fails while composing (files and overrides), naming the key and its schema."""
    key = override.split("=")[0].split(".")[1]
    with pytest.raises(ConfigError, match="Could not") as err:
        sim.load_config([override])
    assert f"Key '{key}' not in" in str(err.value)


def test_unknown_key_added_with_plus_is_refused():
    """Hydra adds '+' keys even to a schema node; the range check refuses them, suggesting the key."""
    with pytest.raises(ConfigError, match=r"bearing\.kapa is not a config key \(did you mean bearing\.kappa\?\)"):
        validate(sim.load_config(["+bearing.kapa=0.9"]))


@pytest.mark.parametrize("path", [p for d in OURS for p in sorted((CONF / d).glob("*.yaml"))], ids=str)
def test_every_value_cites_its_source(path):
    """STYLE.md: each number has its unit and source (thesis table/figure, ASSUMED or engineering
    choice) in a trailing comment; a value spread over a list carries it on its first line."""
    for line in path.read_text().splitlines():
        code = line.split("#")[0]
        if re.match(r"\s*[\w+]+:\s*\S", code) and not code.strip().startswith("-"):
            assert "#" in line, f"{path.name}: {line!r} has no source comment"


def test_schema_defaults_show_in_composed_config():
    """The schema adds only load.zip (empty: no pairs) and output.cache_dir to what the files hold."""
    cfg = sim.load_config([])
    assert OmegaConf.to_container(cfg.load)["zip"] == []
    assert cfg.output.cache_dir == "outputs/cache"
