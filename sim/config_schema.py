"""Type and allowed range of every config key: the project's one validation source (bottom layer).

Each config group (``conf/<group>/``) has a dataclass below; each field's metadata holds its
check (:class:`Number`, :class:`Choice`, :class:`Text`, :class:`Flag`), the bearing type it
belongs to and whether it may be null. Nothing else in the package states a single key's
range. Two kinds of caller check against it:

- :func:`sim.api.schema.validate` checks a whole composed config (unknown keys included) at the
  start of ``python -m sim.run``, of every multirun job, of :func:`sim.simulate` and of
  :func:`sim.api.simulation.build_model`; it raises :class:`sim.errors.ConfigError`;
- the constructors that build from a config node (``Geometry.from_config``,
  ``Lubricant.from_config``, ``OperatingPoint.from_config``, ``SolverSettings.from_config``)
  call :func:`check_node` on their own node, so a caller that builds them directly gets the
  same message (key, value, allowed range) as their own error class (``GeometryError``,
  ``InputError``). They keep only the checks that combine keys (aPk + aP < Lwe, a roller that
  fits, a viscosity that falls with temperature).

This module sits with :mod:`sim.errors` at the bottom of the layers (STYLE.md "Module
boundaries"): geometry and physics import it, so it imports no project module above
:mod:`sim.errors` and no config library. Hence the names of a :class:`Choice` are written here
and the kernel code maps (``sim.geometry.TYPE_CODES``, ``sim.physics.elasticity.ELASTICITY_MODES``,
``sim.physics.ehl.FILM_FORMULAS``, ``PRESSURE_VISCOSITY_MODELS``) are tested to hold exactly
them (tests/sweeps/test_schema_single_source.py). ``sim.api.schema`` registers the dataclasses
with Hydra's ConfigStore. A new key in any ``conf/`` file must be declared here.
"""
import difflib
import math
import numbers
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, fields, is_dataclass, replace
from typing import Any

from sim.errors import ConfigError

#: omegaconf.MISSING: a structured-config default that composition must fill.
MISSING = "???"
#: Values of ``bearing.type``; the fields with ``only=`` belong to one of them.
BEARING_TYPES = ("TRB", "TSRB")


# ---------------------------------------------------------------------------- checks
def _is_number(v):
    return isinstance(v, numbers.Real) and not isinstance(v, bool)


def _is_list(v):
    return isinstance(v, Sequence) and not isinstance(v, (str, bytes))


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
        if _is_list(value):
            return self.shape != "number" and len(value) > 0 and all(self.accepts_number(v) for v in value)
        return self.shape != "list" and self.accepts_number(value)

    def accepts_number(self, v):
        """Whether one number ``v`` lies in the range (list shapes aside)."""
        if not _is_number(v) or not math.isfinite(v):
            return False
        if self.integer and float(v) != int(v):
            return False
        above = v > self.low if self.low_open else v >= self.low
        below = v < self.high if self.high_open else v <= self.high
        return above and below


@dataclass(frozen=True)
class Choice:
    """Allowed values of a string key."""

    options: tuple

    def __str__(self):
        return "one of " + ", ".join(repr(o) for o in self.options)

    def accepts(self, value):
        return isinstance(value, str) and value in self.options


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


def key(check, only=None, optional=False, note="", only_note=""):
    """A schema field: ``check`` (Number, Choice, Text, Flag) holds type and range; ``only``
    names the bearing type the key belongs to; ``optional`` lets it be null. ``note`` is added
    to a value's refusal (why the bound), ``only_note`` to the refusal of the key on the other
    bearing type."""
    default = None if (only or optional) else MISSING
    return field(default=default, metadata={"check": check, "only": only, "optional": optional, "note": note,
                                            "only_note": only_note})


#: why a bearing length lies in [LENGTH_MIN, LENGTH_MAX] mm (every key declared with :func:`mm`)
LENGTH_NOTE = ("1 um to 100 m spans every rolling bearing (the largest slewing bearings are about 10 m across); "
               "beyond it float64 geometry (sines of tiny angles, circles of huge radius) under- or overflows")
LENGTH_MIN, LENGTH_MAX = 1e-3, 1e5


def mm(**options):
    """A bearing length in [1e-3, 1e5] mm (LENGTH_NOTE), with the reason as the key's note."""
    return key(Number(LENGTH_MIN, LENGTH_MAX, units="mm"), note=LENGTH_NOTE, **options)


# ---------------------------------------------------------------------------- bearing
#: why a per-point osculation (``kappa_<race>_<point>``) lies in (0, 1): eq. (2.7) and the two arcs
OSCULATION_NOTE = ("osculation of one raceway arc at its contact point, eq. (2.7) per point (thesis 8.2); null: "
                   "kappa. Below 1 as kappa: at 1 the arc would be the roller crown itself and hide the race's other arc")
#: why a composite roughness is at least 1 nm
ROUGHNESS_NOTE = ("below 1 nm a surface is atomically smooth: finished raceways and rollers have Rq of 0.02 um and "
                  "more")


#: the TRB roller end / rib contact models (sim.geometry.Geometry._rib_arrays, docs/roller_end_torus.md)
ROLLER_END_NOTE = ("sphere: a roller-end sphere (roller_end_radius_ratio) on a cone rib at "
                   "rib_contact_height_ratio; torus: the thesis's flat end face with edge radius "
                   "roller_end_edge_radius on a cone rib opened by rib_opening_angle (thesis 5.5.1)")
END_SPHERE_NOTE = ("roller-end sphere radius over the apex-to-large-end distance; at 1 the sphere is centred on the "
                   "bearing axis and conforms to the cone rib along the circumference (sim.geometry._sphere_rib)")
EDGE_RADIUS_NOTE = ("edge radius r_k of the flat roller end face, the torus's tube radius (thesis Table A.2: 0.8 mm for "
                    "the TRB 32208); above 5 mm it would be no edge of a bearing roller; sim.geometry refuses an "
                    "r_k that leaves no flat face")
OPENING_ANGLE_NOTE = ("angle between the rib's generatrix and the roller's end face in the meridian plane, opening "
                      "away from the roller with height, so that the roller touches with its edge next to the "
                      "raceway (thesis 5.5.1); 0 would be face-to-face contact, not a torus contact, and above "
                      "30 deg the rib would no longer guide the roller; sim.geometry refuses an angle at which the "
                      "roller end conforms to the cone around the circumference")


@dataclass
class SurfaceConfig:
    """Roughness and Zhou-Hoeprich mixed friction (thesis (5.16))."""

    sigma: Any = key(Number(1e-3, 10.0, units="um"), note=ROUGHNESS_NOTE)
    B_ZH: Any = key(Number(0.0, 20.0, low_open=True))
    C_ZH: Any = key(Number(0.0, 5.0, low_open=True))
    sigma_rib: Any = key(Number(1e-3, 10.0, units="um"), only="TRB", note=ROUGHNESS_NOTE)
    B_ZH_rib: Any = key(Number(0.0, 20.0, low_open=True), only="TRB")
    C_ZH_rib: Any = key(Number(0.0, 5.0, low_open=True), only="TRB")


@dataclass
class BearingConfig:
    """TRB or TSRB geometry (thesis Tables 4.2, 6.1, 7.1-7.5). Bounds that combine keys (rollers
    that fit on the pitch circle with ``cage_web_ratio``, rings with a section, aPk + aP < Lwe, PCR
    spanning the roller) are :mod:`sim.geometry`'s (``Geometry.RULES``)."""

    type: str = key(Choice(BEARING_TYPES))
    alpha: Any = key(Number(0.0, 60.0, True, True, units="deg"))
    ratings_alpha: Any = key(Number(0.0, 90.0, True, True, units="deg"), only="TSRB",
                             only_note="ISO 281 rates a tapered roller bearing at its cup (outer raceway) angle "
                                  "alpha + gamma, which is derived; remove the key")
    aP: Any = mm(only="TSRB")
    aPk: Any = mm(only="TSRB")
    B: Any = mm()
    Dpw: Any = mm()
    Dwe: Any = mm()
    Lwe: Any = mm()
    PCR: Any = key(Number(0.0, 1e5, low_open=True, units="mm"), only="TSRB",
                   note="engineering choice: at 1e5 mm a 100 mm roller is straight to 13 um, and beyond it the "
                        "float64 round-off of circles centred PCR away (1e-16 PCR) grows towards the contact approach")
    kappa: Any = key(Number(0.0, 1.0, True, True), only="TSRB",
                     note="kappa = 1 gives PCR_LB = PCR: no two-point contact")
    # Osculation of each raceway arc at its own contact point (thesis 8.2 outlook: "a different
    # osculation value for the two contact points"; thesis 4.1 and Grehn [Gre19]: outer and inner
    # ring osculations may differ). Null (the default): kappa. Arc radius PCR (2 - kappa_<race>_<point>),
    # eq. (2.7) per point (sim.geometry.raceway_profile_radius).
    kappa_outer_small: Any = key(Number(0.0, 1.0, True, True), only="TSRB", optional=True, note=OSCULATION_NOTE)
    kappa_outer_large: Any = key(Number(0.0, 1.0, True, True), only="TSRB", optional=True, note=OSCULATION_NOTE)
    kappa_inner_small: Any = key(Number(0.0, 1.0, True, True), only="TSRB", optional=True, note=OSCULATION_NOTE)
    kappa_inner_large: Any = key(Number(0.0, 1.0, True, True), only="TSRB", optional=True, note=OSCULATION_NOTE)
    r: Any = mm()
    R: Any = mm()
    Z: Any = key(Number(3, integer=True))
    cage_web_ratio: Any = key(Number(0.0, 0.5, units="1"),
                              note="least cage web between neighbouring rollers at the pitch circle, in roller "
                                   "diameters; sim.geometry refuses a Z that leaves less")
    b_m: Any = key(Number(0.0, low_open=True))
    crown_coefficient: Any = key(Number(0.0, 0.01, True, True), only="TRB")
    roller_end_radius_ratio: Any = key(Number(0.3, 1.0, low_open=True, high_open=True), only="TRB",
                                       note=END_SPHERE_NOTE)
    rib_contact_height_ratio: Any = key(Number(0.0, 0.5, True, True), only="TRB")
    roller_end: Any = key(Choice(("sphere", "torus")), only="TRB", note=ROLLER_END_NOTE)
    roller_end_edge_radius: Any = key(Number(0.0, 5.0, low_open=True, units="mm"), only="TRB",
                                      note=EDGE_RADIUS_NOTE)
    rib_opening_angle: Any = key(Number(0.0, 30.0, True, True, units="deg"), only="TRB", note=OPENING_ANGLE_NOTE)
    surface: SurfaceConfig = field(default_factory=SurfaceConfig)


# ---------------------------------------------------------------------------- other groups
@dataclass
class MaterialConfig:
    """Bearing steel (thesis Table A.1) and the ISO/TS 16281 slice stiffness."""

    E: Any = key(Number(5e4, 1e6, units="N/mm^2"),
                 note="rolling-bearing materials: bearing steels 2.1e5, silicon nitride 3.1e5, tungsten carbide 6.5e5")
    nu: Any = key(Number(0.0, 0.5, high_open=True))
    density: Any = key(Number(1000.0, 20000.0, units="kg/m^3"),
                       note="rolling-bearing materials: silicon nitride 3200, steels 7850, tungsten carbide 15600")
    slice_stiffness_iso16281: Any = key(Number(0.0, low_open=True, units="N/mm^(10/9)"))
    thermal_conductivity: Any = key(Number(1.0, 500.0, units="W/(m K)"))
    specific_heat: Any = key(Number(100.0, 5000.0, units="J/(kg K)"))


@dataclass
class LubricantConfig:
    """Oil data (thesis Tables A.1, A.4). The Walther slope fitted through two viscosity points
    must lie in ``walther_slope``'s range (:mod:`sim.physics.lubricant`)."""

    name: str = key(Text())
    temperature: Any = key(Number(-40.0, 200.0, units="degC", shape="list"))
    viscosity: Any = key(Number(0.0, low_open=True, units="mm^2/s", shape="list"))
    walther_slope: Any = key(Number(1.0, 6.0), optional=True, note="that of mineral and synthetic oils")
    density_temperature: Any = key(Number(-40.0, 200.0, units="degC"))
    density: Any = key(Number(500.0, 1500.0, units="kg/m^3"))
    density_slope: Any = key(Number(-5.0, 0.0, units="kg/(m^3 K)"))
    pressure_viscosity: Any = key(Number(0.0, 0.05, units="1/MPa"),
                                  note="mineral and synthetic oils 0.01-0.035, traction fluids to about 0.04 1/MPa")
    pressure_viscosity_temperature: Any = key(Number(-40.0, 200.0, units="degC"))
    pressure_viscosity_temperature_law: str = key(Choice(("constant", "roelands")))
    pressure_viscosity_model: str = key(Choice(("barus", "roelands")))
    limiting_shear_coefficient: Any = key(Number(0.0, 0.5, low_open=True))
    limiting_shear_stress_0: Any = key(Number(0.0, 100.0, units="MPa"))
    shear_modulus: Any = key(Number(10.0, 1e5, units="MPa"))
    thermal_conductivity: Any = key(Number(0.01, 1.0, units="W/(m K)"))
    eyring_stress: Any = key(Number(0.1, 100.0, units="MPa"),
                             note="lubricants' Eyring stresses are 1-20 MPa (Johnson & Tevaarwerk 1977; Evans & "
                                  "Johnson 1986)")
    eyring_stress_temperature_law: str = key(Choice(("constant", "bair_winer")))


@dataclass
class DragConfig:
    """Roller drag in the oil (Harris & Kotzalas 2007)."""

    model: str = key(Choice(("none", "roller_drag")))
    drag_coefficient: Any = key(Number(0.0, 10.0))
    oil_volume_fraction: Any = key(Number(0.0, 1.0))


@dataclass
class SkewConfig:
    """Roller skew as an unknown of the kinematics, held by the cage pocket (sim.physics.friction)."""

    enabled: bool = key(Flag())
    pocket_clearance: Any = key(Number(0.0, 5.0, low_open=True, units="mm"))
    pocket_stiffness: Any = key(Number(0.0, 1e9, low_open=True, units="N/mm"))
    pocket_transition: Any = key(Number(0.0, 1.0, low_open=True, units="mm"))


@dataclass
class FrictionConfig:
    """EHL mixed friction (thesis 5.4)."""

    enabled: bool = key(Flag())
    solid_friction_coefficient: Any = key(Number(0.0, 1.0))
    solid_slip_velocity: Any = key(Number(0.0, 1.0, low_open=True, units="m/s"))
    solid_slip_ratio: Any = key(Number(0.0, 1.0, low_open=True))
    hysteresis_loss_factor: Any = key(Number(0.0, 0.5))
    cage_friction_coefficient: Any = key(Number(0.0, 1.0))
    film_thickness: str = key(Choice(("dowson_higginson", "pan_hamrock")))
    width_points: Any = key(Number(2, 64, integer=True))
    thermal: bool = key(Flag())
    traction_law: str = key(Choice(("eyring", "newton_limited")))
    inlet_shear_heating: bool = key(Flag())
    temperature_tolerance: Any = key(Number(0.0, 10.0, low_open=True, units="K"))
    inner_ring_temperature_rise: Any = key(Number(-50.0, 50.0, units="K"))
    kinematics: str = key(Choice(("rolling", "traction")))
    cage_guidance: str = key(Choice(("free", "rigid")))
    max_iterations: Any = key(Number(1, 10000, integer=True))
    tolerance: Any = key(Number(1e-14, 1e-2, low_open=True))
    seed_tolerance_factor: Any = key(Number(1.0, 1e4))
    load_coupling_tolerance: Any = key(Number(0.0, 1e-2, low_open=True))
    load_coupling_passes: Any = key(Number(1, 100, integer=True))
    load_coupling_depth: Any = key(Number(1, 10, integer=True))
    drag: DragConfig = field(default_factory=DragConfig)
    skew: SkewConfig = field(default_factory=SkewConfig)


@dataclass
class LoadConfig:
    """One operating point or a grid of them (:mod:`sim.api.cases`).

    ``zip`` lists groups of keys whose lists pair up element by element; all other lists
    combine as a full factorial. One case (``OperatingPoint``) takes one number per key.
    """

    Fa: Any = key(Number(0.0, 1e7, low_open=True, units="N", shape="number or list"),
                  note="per bearing, the equivalent static load P0 is bounded by solver.max_static_load_ratio x C0")
    Fr: Any = key(Number(0.0, 1e7, units="N", shape="number or list"),
                  note="per bearing, the equivalent static load P0 is bounded by solver.max_static_load_ratio x C0")
    speed: Any = key(Number(0.0, 1e5, units="rpm", shape="number or list"),
                     note="0 is the static case (friction: the breakaway torque); per bearing, speed x Dpw is "
                          "bounded by solver.max_speed_dm")
    tilt: Any = key(Number(-2.0, 2.0, units="deg", shape="number or list"))
    oil_temperature: Any = key(Number(-40.0, 200.0, units="degC", shape="number or list"))
    zip: Any = field(default_factory=list, metadata={"check": None})


@dataclass
class DynamicConfig:
    """Time-domain solver settings (sim/solvers/dynamic.py); reasons and sources in conf/solver/dynamic.yaml."""

    start: str = key(Choice(("rolling", "quasi_static")))
    method: str = key(Choice(("BDF", "Radau")))
    rtol: Any = key(Number(1e-12, 1e-2, low_open=True))
    contact_damping_ratio: Any = key(Number(0.0, 2.0))
    pocket_damping_ratio: Any = key(Number(0.0, 2.0))
    inner_ring_mass: Any = key(Number(0.0, 1e4, low_open=True, units="kg"))
    cage_inertia: Any = key(Number(0.0, 1e3, low_open=True, units="kg m^2"))
    window_revolutions: Any = key(Number(0.0, 1e3, low_open=True))
    samples_per_window: Any = key(Number(2, 10000, integer=True))
    max_windows: Any = key(Number(2, 10000, integer=True))
    steady_tolerance_speed: Any = key(Number(0.0, 1.0, low_open=True))
    steady_tolerance_torque: Any = key(Number(0.0, 1.0, low_open=True))
    steady_tolerance_load: Any = key(Number(0.0, 1.0, low_open=True))
    steady_tolerance_skew: Any = key(Number(0.0, 1.0, low_open=True))
    steady_tolerance_power: Any = key(Number(0.0, 1.0, low_open=True))
    fluctuation_windows: Any = key(Number(4, 1000, integer=True))


@dataclass
class SolverConfig:
    """Quasi-static solver settings (MODEL.md 4); the Newton limits' reasons are in
    conf/solver/quasi_static.yaml."""

    name: str = key(Choice(("quasi_static", "dynamic")))
    n_slices: Any = key(Number(2, 400, integer=True))
    elasticity: str = key(Choice(("coupled", "independent")))
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
    max_static_load_ratio: Any = key(Number(0.0, 4.0, low_open=True),
                                     note="at 4 C0 the Hertz pressure is twice ISO 76's 4000 MPa and the steel "
                                          "has long yielded")
    max_speed_dm: Any = key(Number(0.0, 2e6, low_open=True, units="mm/min"),
                            note="DN 2e6 is beyond every rolling bearing of this kind in service")
    dynamic: Any = field(default=None, metadata={"check": None, "schema": DynamicConfig})


@dataclass
class OutputConfig:
    """What is written, where results are cached (:mod:`sim.api.sweep`), when a slice counts as loaded."""

    file: str = key(Text())
    cache_dir: Any = key(Text(), optional=True)
    contact_pressure_threshold: Any = key(Number(0.0, low_open=True, units="MPa"))


SCHEMAS = {"bearing": BearingConfig, "material": MaterialConfig, "lubricant": LubricantConfig,
           "friction": FrictionConfig, "load": LoadConfig, "solver": SolverConfig, "output": OutputConfig}


# ---------------------------------------------------------------------------- node checks
def undeclared_key(dotted):
    """Why a dotted config key of a schema group (``bearing.kapa``, ``friction.skew.pocket_clerance``) is
    no declared key, or "" when it is one (or names no schema group: Hydra's own keys, groups without a
    schema). The check of command-line overrides before Hydra composes them (sim.run), which would
    refuse such a key with its own multi-line message and exit status 1."""
    group, *path = str(dotted).split(".")
    schema = SCHEMAS.get(group)
    prefix = group
    for part in path:
        if schema is None:
            return ""
        found = {f.name: f for f in fields(schema)}
        if part not in found:
            return not_a_key(prefix, part, list(found))
        f = found[part]
        schema = f.metadata.get("schema") or (f.type if is_dataclass(f.type) else None)
        prefix = f"{prefix}.{part}"
    return ""


def not_a_key(path, name, names):
    """``path.name is not a config key``, with the closest of the declared ``names`` as a hint."""
    close = difflib.get_close_matches(str(name), names, n=1)
    return f"{path}.{name} is not a config key" + (f" (did you mean {path}.{close[0]}?)" if close else "")


def field_check(schema, name):
    """The check (Number, Choice, ...) of field ``name`` of a group dataclass ``schema``."""
    return next(f for f in fields(schema) if f.name == name).metadata["check"]


def _shown(value):
    """A value as the config wrote it (numpy scalars as plain numbers, sequences as lists)."""
    if _is_list(value):
        return [_shown(v) for v in value]
    if isinstance(value, numbers.Integral) and not isinstance(value, (bool, int)):
        return int(value)
    if _is_number(value) and not isinstance(value, (int, float)):
        return float(value)
    return value


def _is_missing(node, name):
    if name not in node:
        return True
    try:
        value = node[name]
    except Exception as exc:  # a DictConfig's "???" (this layer imports no config library)
        if type(exc).__name__ == "MissingMandatoryValue":
            return True
        raise
    return value is None or (isinstance(value, str) and value == MISSING)


def node_problems(schema, node, path, *, bearing_type=None, keys=None, strict=False, scalar=False):
    """Messages for the values of one config node that its schema does not allow.

    Parameters
    ----------
    schema : dataclass type
        The group's schema (a value of :data:`SCHEMAS`, or a nested one such as SurfaceConfig).
    node : mapping or None
        The config node (dict or DictConfig); missing values are absent, None or ``"???"``.
    path : str
        Its dotted name in the config (``"bearing"``, ``"friction.drag"``): messages name
        ``path.key``.
    bearing_type : str, optional
        'TRB' or 'TSRB': a key of the other type must be absent, one of this type present.
        None (or an unknown type): type-specific keys are checked when given, not required.
    keys : iterable of str, optional
        Check only these fields (default: all, nested groups included).
    strict : bool
        Also refuse keys that the schema does not declare (suggesting the closest one).
    scalar : bool
        One value per key, even where the schema allows a list (one load case).

    Returns
    -------
    list of str
        ``path.key = value is outside the allowed range: <range>``, ``path.key is missing: ...``,
        ``path.key = value does not apply to a TRB ...``, ``path.key is not a config key ...``.
    """
    node = node if isinstance(node, Mapping) else {}
    names = [f.name for f in fields(schema)]
    problems = []
    if strict:
        for extra in (k for k in node if k not in names):  # added with "+group.key=..."
            problems.append(not_a_key(path, extra, names))
    wanted = None if keys is None else set(keys)
    for f in fields(schema):
        if wanted is not None and f.name not in wanted:
            continue
        name = f"{path}.{f.name}"
        missing = _is_missing(node, f.name)
        value = None if missing else node[f.name]
        if is_dataclass(f.type):
            problems += node_problems(f.type, value, name, bearing_type=bearing_type, strict=strict, scalar=scalar)
            continue
        if f.metadata.get("schema") is not None:
            # a node only some configs have (solver.dynamic with solver=dynamic): checked where present
            if value is not None:
                problems += node_problems(f.metadata["schema"], value, name, bearing_type=bearing_type,
                                          strict=strict, scalar=scalar)
            continue
        check, only, note = f.metadata.get("check"), f.metadata.get("only"), f.metadata.get("note")
        if check is None:
            continue
        why = f" ({note})" if note else ""
        if only and only != bearing_type:
            if bearing_type in BEARING_TYPES and not missing:
                only_note = f.metadata.get("only_note")
                problems.append(f"{name} = {_shown(value)!r} does not apply to a {bearing_type} (a {only} parameter"
                                + (f"; {only_note})" if only_note else ")"))
            if bearing_type in BEARING_TYPES or missing:
                continue
        if missing and f.metadata.get("optional"):
            continue
        if scalar and isinstance(check, Number):
            check = replace(check, shape="number")
        if missing:
            problems.append(f"{name} is missing: allowed {check}")
        elif not check.accepts(value):
            problems.append(f"{name} = {_shown(value)!r} is outside the allowed range: {check}{why}")
    return problems


def check_node(schema, node, path, *, error=ConfigError, **options):
    """Raise ``error`` listing every problem of :func:`node_problems` (one per line), if any."""
    problems = node_problems(schema, node, path, **options)
    if problems:
        raise error("\n".join(problems))
