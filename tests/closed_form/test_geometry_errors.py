"""Impossible bearing geometry is refused before any numerics run (MODEL.md 2).

``Geometry.from_config`` raises ``sim.geometry.GeometryError`` (a ValueError) whose message
names the parameter (``bearing.<name>``), the value given and the bound it breaks: a single
key's range comes from the schema (sim/config_schema.py, the value printed as written), a
combination of keys from sim.geometry (the value as a float). Every shipped config in
conf/bearing must build. The bounds quoted below follow from the
reference TSRB (Table 7.1: Lwe 17, aP 8.5, Dpw 60, Dwe 10, r 20, R 40, B 24.75).
"""
import re
from pathlib import Path

import pytest
from omegaconf import OmegaConf

import sim
from sim.geometry import Geometry, GeometryError

BEARING_DIR = Path(sim.CONF_DIR) / "bearing"
BEARINGS = sorted(p.stem for p in BEARING_DIR.glob("*.yaml"))
TRBS = [name for name in BEARINGS if name.startswith("trb_")]


def compose(*overrides):
    return sim.load_config(list(overrides))


def build_cfg(cfg):
    return Geometry.from_config(cfg.bearing, cfg.material, cfg.solver.n_slices)


def build(*overrides):
    return build_cfg(compose(*overrides))


def test_geometry_error_is_value_error():
    """Callers that catch ValueError also catch refused geometry."""
    assert issubclass(GeometryError, ValueError)


# (override on tsrb_reference, parameter named, value as printed, text of the bound)
REFUSED = [
    pytest.param("bearing.kappa=1.0", "kappa", "1.0", "(0, 1)", id="kappa_1_no_two_point_contact"),
    pytest.param("bearing.kappa=0", "kappa", "0", "(0, 1)", id="kappa_0"),
    pytest.param("bearing.kappa=1.2", "kappa", "1.2", "(0, 1)", id="kappa_1.2_PCR_LB_below_PCR"),
    pytest.param("bearing.aPk=9", "aPk", "9.0", "Lwe - aP = 8.5", id="aPk_plus_aP_beyond_Lwe"),
    pytest.param("bearing.aPk=8.5", "aPk", "8.5", "Lwe - aP = 8.5", id="aPk_plus_aP_equal_Lwe"),
    pytest.param("bearing.aPk=0", "aPk", "0", "[0.001, 100000] mm", id="aPk_zero"),
    pytest.param("bearing.aP=0", "aP", "0", "[0.001, 100000] mm", id="aP_zero"),
    pytest.param("bearing.aP=-1", "aP", "-1", "[0.001, 100000] mm", id="aP_negative"),
    pytest.param("bearing.PCR=8", "PCR", "8.0", "Lwe/(2 (1 - sin(gamma))) = 8.857", id="PCR_below_half_Lwe"),
    pytest.param("bearing.PCR=8.8", "PCR", "8.8", "Lwe/(2 (1 - sin(gamma))) = 8.857", id="PCR_below_crown_bound"),
    pytest.param("bearing.Dwe=60", "Dwe", "60.0", "Dpw = 60.0", id="Dwe_equal_Dpw"),
    pytest.param("bearing.Dwe=70", "Dwe", "70.0", "Dpw = 60.0", id="Dwe_above_Dpw"),
    pytest.param("bearing.R=33", "R", "33.0", "> 36.890 mm", id="R_too_small"),
    pytest.param("bearing.r=27", "r", "27.0", "< 23.778 mm", id="r_too_large"),
    pytest.param("bearing.B=10", "B", "10.0", "> 18.914 mm", id="B_too_small"),
    pytest.param("bearing.alpha=0", "alpha", "0", "(0, 60)", id="alpha_zero"),
    pytest.param("bearing.alpha=-5", "alpha", "-5", "(0, 60)", id="alpha_negative"),
    pytest.param("bearing.alpha=70", "alpha", "70", "(0, 60)", id="alpha_70"),
    pytest.param("bearing.Z=2", "Z", "2", ">= 3", id="Z_2"),
    pytest.param("bearing.Z=3.5", "Z", "3.5", "integer", id="Z_not_integer"),
    pytest.param("bearing.Lwe=-17", "Lwe", "-17", "[0.001, 100000] mm", id="Lwe_negative"),
]


@pytest.mark.parametrize("override, name, value, bound", REFUSED)
def test_impossible_tsrb_is_refused(override, name, value, bound):
    """MODEL.md 2: impossible geometry -> GeometryError naming parameter, value and bound."""
    with pytest.raises(GeometryError, match=rf"\bbearing\.{re.escape(name)} = ") as err:
        build("bearing=tsrb_reference", override)
    message = str(err.value)
    assert f"bearing.{name} = {value} " in message, message
    assert bound in message, message


def test_unknown_type_is_refused():
    """bearing.type must be TRB or TSRB; the message names the value and the allowed ones."""
    with pytest.raises(GeometryError, match=r"bearing\.type") as err:
        build("bearing=tsrb_reference", "bearing.type=XYZ")
    assert "'XYZ'" in str(err.value)
    assert "TRB" in str(err.value) and "TSRB" in str(err.value)


def _without(cfg, key):
    """Plain-dict copy of cfg.bearing without ``key`` (the composed config is left intact)."""
    bearing = OmegaConf.to_container(cfg.bearing, resolve=True)
    del bearing[key]
    return bearing


@pytest.mark.parametrize("name, key", [
    ("trb_32208", "Lwe"),
    ("trb_32208", "Z"),
    ("tsrb_reference", "PCR"),
    ("tsrb_reference", "kappa"),
    ("tsrb_reference", "aPk"),
])
def test_missing_key_is_refused(name, key):
    """A missing parameter is named in the error (MODEL.md 2: refuse before any numerics)."""
    cfg = compose(f"bearing={name}")
    with pytest.raises(GeometryError, match=rf"bearing\.{key} is missing"):
        Geometry.from_config(_without(cfg, key), cfg.material, cfg.solver.n_slices)
    assert key in cfg.bearing  # the copy was edited, not the composed config


@pytest.mark.parametrize("name", TRBS)
def test_trb_refuses_missing_crown_coefficient(name):
    """The TRB needs the log-crown coefficient of eq. (2.5); it has no default."""
    cfg = compose(f"bearing={name}")
    with pytest.raises(GeometryError, match=r"bearing\.crown_coefficient is missing"):
        Geometry.from_config(_without(cfg, "crown_coefficient"), cfg.material, cfg.solver.n_slices)


def test_bearing_configs_found():
    """The parametrisation below really covers the shipped configs (7 at the time of writing)."""
    assert len(BEARINGS) >= 7
    assert {"tsrb_reference", "tsrb_prototype", "trb_32208", "trb_31313"} <= set(BEARINGS)
    assert TRBS


@pytest.mark.parametrize("name", BEARINGS)
def test_every_bearing_config_builds(name):
    """Every conf/bearing/*.yaml is a possible bearing and builds without error."""
    g = build(f"bearing={name}")
    assert g.type in ("TRB", "TSRB")
    cfg = compose(f"bearing={name}")
    assert g.type == cfg.bearing.type
