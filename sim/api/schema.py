"""Structured-config schemas of ``conf/`` (Hydra ConfigStore) and the range check at start.

``conf/config.yaml`` puts each schema below its group (``- schema/bearing@bearing`` before
``- bearing: tsrb_reference``), so composition (``sim.load_config``, ``python -m sim.run``)
merges the group's YAML onto a dataclass: a key that the schema does not declare, a typo in a
file or an override (``bearing.kapa=0.9``), fails there, naming the key (Hydra lets a key added
with ``+`` through; :func:`validate` refuses it and suggests the declared key).

Values are typed ``Any`` at composition so that they reach the physics modules exactly as
written (``bearing.alpha=0`` stays the int 0 that :mod:`sim.geometry` prints back) and so that
a load value may be a number or a list (a grid, :mod:`sim.api.cases`). Type and range live in
each field's metadata; :func:`validate` checks them for a whole composed config and raises one
:class:`ConfigError` naming every bad key, its value and the allowed range. ``python -m
sim.run`` calls it before anything runs (through :class:`sim.api.sweep.SweepCallback`), for every
point of a multirun before the first job starts.

The ranges are the bounds the physics modules enforce key by key (``sim.geometry``,
``sim.api.simulation``, ``sim.physics.friction``, ``sim.physics.lubricant``); combined feasibility (a roller that
does not fit, aPk + aP >= Lwe) stays with :mod:`sim.geometry` and fails the point, not the sweep.
A new key in any ``conf/`` file must be declared here.
"""
import difflib
import math
from dataclasses import dataclass, field, fields, is_dataclass
from typing import Any

from hydra.core.config_store import ConfigStore
from omegaconf import MISSING, DictConfig, ListConfig, OmegaConf

from sim.api.cases import operating_points
from sim.physics.elasticity import ELASTICITY_MODES
from sim.geometry import TYPE_CODES
from sim.errors import ConfigError, InputError


@dataclass(frozen=True)
class Number:
    """Allowed values of a numeric key: an interval, optionally integers only or a list of them."""

    low: float = -math.inf
    high: float = math.inf
    low_open: bool = False
    high_open: bool = False
    units: str = "1"
    integer: bool = False
    shape: str = "number"  # "number", "number or list" (a load grid) or "list" (a viscosity table)

    def __str__(self):
        one, many = ("an integer", "integers") if self.integer else ("a number", "numbers")
        if math.isinf(self.high):
            bound = f"{'>' if self.low_open else '>='} {self.low:g}"
        elif math.isinf(self.low):
            bound = f"{'<' if self.high_open else '<='} {self.high:g}"
        else:
            bound = (f"in {'(' if self.low_open else '['}{self.low:g}, {self.high:g}"
                     f"{')' if self.high_open else ']'}")
        bound += f" {self.units}" if self.units != "1" else ""
        if self.shape == "list":
            return f"a list of {many} {bound}"
        return f"{one} {bound}" + (", or a list of them" if self.shape == "number or list" else "")

    def accepts(self, value):
        if isinstance(value, (list, tuple, ListConfig)):
            return self.shape != "number" and len(value) > 0 and all(self._accepts_one(v) for v in value)
        return self.shape != "list" and self._accepts_one(value)

    def _accepts_one(self, v):
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            return False
        if self.integer and float(v) != int(v):
            return False
        above = v > self.low if self.low_open else v >= self.low
        below = v < self.high if self.high_open else v <= self.high
        return math.isfinite(v) and above and below


@dataclass(frozen=True)
class Choice:
    """Allowed values of a string key."""

    options: tuple

    def __str__(self):
        return "one of " + ", ".join(repr(o) for o in self.options)

    def accepts(self, value):
        return value in self.options


@dataclass(frozen=True)
class Text:
    """Any string (a name, a file name)."""

    def __str__(self):
        return "a string"

    def accepts(self, value):
        return isinstance(value, str)


@dataclass(frozen=True)
class Flag:
    """true or false."""

    def __str__(self):
        return "true or false"

    def accepts(self, value):
        return isinstance(value, bool)


def key(check, only=None, optional=False):
    """A schema field: ``check`` (Number, Choice, Text, Flag) holds type and range; ``only``
    names the bearing type the key belongs to; ``optional`` lets it be null."""
    default = None if (only or optional) else MISSING
    return field(default=default, metadata={"check": check, "only": only, "optional": optional})


def mm():
    """A length > 0 mm."""
    return Number(0.0, low_open=True, units="mm")


# ---------------------------------------------------------------------------- bearing
@dataclass
class SurfaceConfig:
    """Roughness and Zhou-Hoeprich mixed friction (thesis (5.16)); bounds of sim.physics.friction."""

    sigma: Any = key(Number(0.0, 10.0, low_open=True, units="um"))
    B_ZH: Any = key(Number(0.0, 20.0, low_open=True))
    C_ZH: Any = key(Number(0.0, 5.0, low_open=True))
    sigma_rib: Any = key(Number(0.0, 10.0, low_open=True, units="um"), only="TRB")
    B_ZH_rib: Any = key(Number(0.0, 20.0, low_open=True), only="TRB")
    C_ZH_rib: Any = key(Number(0.0, 5.0, low_open=True), only="TRB")


@dataclass
class BearingConfig:
    """TRB or TSRB geometry (thesis Tables 4.2, 6.1, 7.1-7.5); single-key bounds of sim.geometry."""

    type: str = key(Choice(tuple(sorted(TYPE_CODES))))
    alpha: Any = key(Number(0.0, 60.0, True, True, units="deg"))
    ratings_alpha: Any = key(Number(0.0, 90.0, True, True, units="deg"), only="TSRB")  # TRB: derived cup angle
    aP: Any = key(mm(), only="TSRB")
    aPk: Any = key(mm(), only="TSRB")
    B: Any = key(mm())
    Dpw: Any = key(mm())
    Dwe: Any = key(mm())
    Lwe: Any = key(mm())
    PCR: Any = key(mm(), only="TSRB")
    kappa: Any = key(Number(0.0, 1.0, True, True), only="TSRB")
    r: Any = key(mm())
    R: Any = key(mm())
    Z: Any = key(Number(3, integer=True))
    b_m: Any = key(Number(0.0, low_open=True))
    crown_coefficient: Any = key(Number(0.0, 0.01, True, True), only="TRB")
    roller_end_radius_ratio: Any = key(Number(0.3, 1.0, low_open=True), only="TRB")
    rib_contact_height_ratio: Any = key(Number(0.0, 0.5, True, True), only="TRB")
    surface: SurfaceConfig = field(default_factory=SurfaceConfig)


# ---------------------------------------------------------------------------- other groups
@dataclass
class MaterialConfig:
    """Bearing steel (thesis Table A.1) and the ISO/TS 16281 slice stiffness."""

    E: Any = key(Number(0.0, low_open=True, units="N/mm^2"))
    nu: Any = key(Number(0.0, 0.5, high_open=True))
    density: Any = key(Number(0.0, low_open=True, units="kg/m^3"))
    slice_stiffness_iso16281: Any = key(Number(0.0, low_open=True, units="N/mm^(10/9)"))
    thermal_conductivity: Any = key(Number(1.0, 500.0, units="W/(m K)"))
    specific_heat: Any = key(Number(100.0, 5000.0, units="J/(kg K)"))


@dataclass
class LubricantConfig:
    """Oil data (thesis Tables A.1, A.4); bounds of sim.physics.lubricant."""

    name: str = key(Text())
    temperature: Any = key(Number(-40.0, 200.0, units="degC", shape="list"))
    viscosity: Any = key(Number(0.0, low_open=True, units="mm^2/s", shape="list"))
    walther_slope: Any = key(Number(1.0, 6.0), optional=True)
    density_temperature: Any = key(Number(-40.0, 200.0, units="degC"))
    density: Any = key(Number(500.0, 1500.0, units="kg/m^3"))
    density_slope: Any = key(Number(-10.0, 0.0, units="kg/(m^3 K)"))
    pressure_viscosity: Any = key(Number(0.0, 0.1, units="1/MPa"))
    pressure_viscosity_model: str = key(Choice(("barus", "roelands")))
    limiting_shear_coefficient: Any = key(Number(0.0, 0.5, low_open=True))
    limiting_shear_stress_0: Any = key(Number(0.0, 100.0, units="MPa"))
    shear_modulus: Any = key(Number(10.0, 1e5, units="MPa"))
    thermal_conductivity: Any = key(Number(0.01, 1.0, units="W/(m K)"))
    eyring_stress: Any = key(Number(0.0, 100.0, low_open=True, units="MPa"))


@dataclass
class DragConfig:
    """Roller drag in the oil (Harris & Kotzalas 2007); bounds of sim.physics.friction."""

    model: str = key(Choice(("none", "roller_drag")))
    drag_coefficient: Any = key(Number(0.0, 10.0))
    oil_volume_fraction: Any = key(Number(0.0, 1.0))


@dataclass
class FrictionConfig:
    """EHL mixed friction (thesis 5.4); bounds of sim.physics.friction."""

    enabled: bool = key(Flag())
    solid_friction_coefficient: Any = key(Number(0.0, 1.0))
    solid_slip_velocity: Any = key(Number(0.0, 1.0, low_open=True, units="m/s"))
    hysteresis_loss_factor: Any = key(Number(0.0, 0.5))
    cage_friction_coefficient: Any = key(Number(0.0, 1.0))
    film_thickness: str = key(Choice(("dowson_higginson", "pan_hamrock")))
    width_points: Any = key(Number(2, 64, integer=True))
    thermal: bool = key(Flag())
    temperature_tolerance: Any = key(Number(0.0, 10.0, low_open=True, units="K"))
    kinematics: str = key(Choice(("rolling", "traction")))
    max_iterations: Any = key(Number(1, 10000, integer=True))
    tolerance: Any = key(Number(1e-14, 1e-2, low_open=True))
    seed_tolerance_factor: Any = key(Number(1.0, 1e4))
    drag: DragConfig = field(default_factory=DragConfig)


@dataclass
class LoadConfig:
    """One operating point or a grid of them (:mod:`sim.api.cases`); bounds of sim.api.simulation.

    ``zip`` lists groups of keys whose lists pair up element by element; all other lists
    combine as a full factorial.
    """

    Fa: Any = key(Number(0.0, 1e7, low_open=True, units="N", shape="number or list"))
    Fr: Any = key(Number(0.0, 1e7, units="N", shape="number or list"))
    speed: Any = key(Number(0.0, 1e5, units="rpm", shape="number or list"))
    tilt: Any = key(Number(-2.0, 2.0, units="deg", shape="number or list"))
    oil_temperature: Any = key(Number(-40.0, 200.0, units="degC", shape="number or list"))
    zip: Any = field(default_factory=list, metadata={"check": None})


@dataclass
class SolverConfig:
    """Quasi-static solver settings (MODEL.md 4); bounds of sim.api.simulation.SolverSettings."""

    name: str = key(Choice(("quasi_static",)))
    n_slices: Any = key(Number(2, 400, integer=True))
    elasticity: str = key(Choice(tuple(sorted(ELASTICITY_MODES))))
    tolerance: Any = key(Number(1e-14, 1e-3, low_open=True))
    max_iterations: Any = key(Number(1, 10000, integer=True))
    roller_max_iterations: Any = key(Number(1, 10000, integer=True))
    centrifugal: bool = key(Flag())
    gyroscopic: bool = key(Flag())
    roller_tolerance_ratio: Any = key(Number(0.0, 1.0, low_open=True))
    forcing: Any = key(Number(0.0, 1.0))
    roller_step_interference: Any = key(Number(0.0, 10.0, low_open=True))
    roller_step_length: Any = key(Number(0.0, 1.0, low_open=True))
    line_search_halvings: Any = key(Number(0, 60, integer=True))
    ring_step_fraction: Any = key(Number(0.0, 10.0, low_open=True))
    continuation_steps: Any = key(Number(0, 1000, integer=True))


@dataclass
class OutputConfig:
    """What is written, where results are cached (:mod:`sim.api.sweep`), how edge stress is judged."""

    file: str = key(Text())
    cache_dir: Any = key(Text(), optional=True)
    edge_stress_ratio: Any = key(Number(0.0, low_open=True))
    contact_pressure_threshold: Any = key(Number(0.0, low_open=True, units="MPa"))


SCHEMAS = {"bearing": BearingConfig, "material": MaterialConfig, "lubricant": LubricantConfig,
           "friction": FrictionConfig, "load": LoadConfig, "solver": SolverConfig, "output": OutputConfig}

for _group, _node in SCHEMAS.items():
    ConfigStore.instance().store(group="schema", name=_group, node=_node)


# ---------------------------------------------------------------------------- validation
def _problems(schema, node, path, bearing_type):
    """Messages for the values of one config node (``path``) that its schema does not allow."""
    node = node if isinstance(node, DictConfig) else DictConfig({})
    names = [f.name for f in fields(schema)]
    for extra in (k for k in node if k not in names):  # added with "+group.key=..."
        close = difflib.get_close_matches(str(extra), names, n=1)
        yield f"{path}.{extra} is not a config key" + (f" (did you mean {path}.{close[0]}?)" if close else "")
    for f in fields(schema):
        name = f"{path}.{f.name}"
        value = None if f.name not in node or OmegaConf.is_missing(node, f.name) else node[f.name]
        if is_dataclass(f.type):
            yield from _problems(f.type, value, name, bearing_type)
            continue
        check, only = f.metadata.get("check"), f.metadata.get("only")
        if check is None:
            continue
        if only and bearing_type in TYPE_CODES and only != bearing_type:
            if value is not None:
                yield f"{name} = {value!r} does not apply to a {bearing_type} (a {only} parameter)"
            continue
        if value is None and f.metadata.get("optional"):
            continue
        if value is None:
            yield f"{name} is missing: allowed {check}"
        elif not check.accepts(value):
            shown = OmegaConf.to_container(value) if isinstance(value, ListConfig) else value
            yield f"{name} = {shown!r} is outside the allowed range: {check}"


def validate(cfg):
    """Check every value of a composed config against its schema (type, range, bearing type).

    Parameters
    ----------
    cfg : omegaconf.DictConfig
        Composed config (the ``hydra`` node, if present, is ignored).

    Raises
    ------
    ConfigError
        Listing every offending key as ``group.key = value is outside the allowed range: ...``,
        and a load grid that cannot be formed (:func:`sim.api.cases.operating_points`).
    """
    bearing_type = OmegaConf.select(cfg, "bearing.type")
    problems = [p for group, schema in SCHEMAS.items()
                for p in _problems(schema, cfg.get(group), group, bearing_type)]
    if not any(p.startswith("load.") for p in problems):
        try:
            operating_points(cfg.load)  # zipped lengths, repeated cases
        except InputError as exc:
            problems.append(str(exc))
    if problems:
        raise ConfigError("\n".join(problems))
