"""One validation source (issue 13, item 4): every key's type and range is stated once, in
sim/config_schema.py, and enforced from there.

1. ``sim.simulate`` refuses a value just outside every bound of every numeric key (and a value
   of every choice that is none of its options) before anything runs, naming key, value and
   allowed range.
2. The constructors built from a config node (Geometry, Lubricant, OperatingPoint,
   SolverSettings) refuse the same values for their own keys: a caller that skips
   ``simulate`` gets the same message, as the constructor's error class.
3. No constructor re-states a schema bound: no ``check_range`` and no comparison of a single
   key's value with a number in sim/geometry.py, sim/physics/lubricant.py and the
   OperatingPoint / SolverSettings part of sim/api/bearing_model.py (an AST check, with a
   self-test on the checks it replaced). Checks of combinations (aPk + aP < Lwe) stay.
4. What still checks by hand (sim/api/friction_model.py, until its parameter packing is
   rewritten) checks the schema's bounds, and the kernels' code maps hold exactly the
   schema's choices.
"""
import ast
import copy
import math
import re
from dataclasses import fields, is_dataclass, replace
from pathlib import Path

import pytest
from omegaconf import OmegaConf

import sim
import sim.api.simulation
from sim.api.bearing_model import OperatingPoint, SolverSettings
from sim.config_schema import (SCHEMAS, BearingConfig, Choice, Flag, LubricantConfig, Number, SolverConfig, Text,
                               field_check)
from sim.errors import ConfigError, GeometryError, InputError
from sim.geometry import TYPE_CODES, Geometry
from sim.physics.ehl import FILM_FORMULAS, PRESSURE_VISCOSITY_MODELS
from sim.physics.friction import TRACTION_LAWS
from sim.physics.elasticity import ELASTICITY_MODES
from sim.physics.lubricant import Lubricant

REPO = Path(__file__).resolve().parents[2]
BEARING_OF_TYPE = {"TSRB": "tsrb_reference", "TRB": "trb_32208"}


def schema_fields(schema=None, path=None):
    """(dotted key, field) of every checked leaf field of the schemas."""
    items = SCHEMAS.items() if schema is None else [(path, schema)]
    for prefix, sch in items:
        for f in fields(sch):
            if is_dataclass(f.type):
                yield from schema_fields(f.type, f"{prefix}.{f.name}")
            elif f.metadata.get("check") is not None:
                yield f"{prefix}.{f.name}", f


def _outside(check):
    """Values just outside each finite bound of a Number: (label, value)."""
    def step(bound):
        return 1 if check.integer else 1e-9 * max(1.0, abs(bound))
    if not math.isinf(check.low):
        yield "below", check.low if check.low_open else check.low - step(check.low)
    if not math.isinf(check.high):
        yield "above", check.high if check.high_open else check.high + step(check.high)


def refused_values():
    """(dotted key, bearing type, bad value, check) for every bound, choice and flag of the schema."""
    cases = []
    for name, f in schema_fields():
        check = f.metadata["check"]
        kind = f.metadata.get("only") or "TSRB"
        if isinstance(check, Number):
            for label, value in _outside(check):
                cases.append(pytest.param(name, kind, [value] if check.shape == "list" else value, check,
                                          id=f"{name}-{label}"))
        elif isinstance(check, Choice):
            cases.append(pytest.param(name, kind, "nonsense", check, id=f"{name}-choice"))
        elif isinstance(check, (Text, Flag)) and f.type not in (str, bool):
            # a field typed str or bool is converted or refused by OmegaConf itself on assignment
            cases.append(pytest.param(name, kind, 12.5 if isinstance(check, Text) else "yes", check, id=f"{name}-type"))
    return cases


REFUSED = refused_values()


@pytest.fixture(scope="module")
def composed():
    return {kind: sim.load_config([f"bearing={name}"]) for kind, name in BEARING_OF_TYPE.items()}


def with_value(composed, kind, name, value):
    cfg = copy.deepcopy(composed[kind])
    OmegaConf.update(cfg, name, value, merge=False)
    return cfg


def names_key(message, name, check):
    """The refusal names the key, the value and the allowed range (the schema's own text; one
    number where one load case is built)."""
    line = next((li for li in message.splitlines() if li.startswith(f"{name} = ")), None)
    assert line is not None, message
    allowed = {str(check), str(replace(check, shape="number"))}
    assert any(f"is outside the allowed range: {a}" in line for a in allowed), message


def test_every_numeric_key_has_its_bounds_tested():
    """The parametrisation covers every numeric key of every group (70 keys at the time of writing)."""
    numeric = {name for name, f in schema_fields() if isinstance(f.metadata["check"], Number)}
    tested = {p.values[0] for p in REFUSED if isinstance(p.values[3], Number)}
    assert tested == numeric and len(numeric) >= 60
    assert {n.split(".")[0] for n in numeric} == set(SCHEMAS)


@pytest.mark.parametrize("name, kind, value, check", REFUSED)
def test_simulate_refuses_every_bound_before_anything_runs(composed, monkeypatch, name, kind, value, check):
    """sim.simulate: a value just outside a bound (a closed bound minus 1e-9 of it, an open one
    itself, an integer one step off), or no allowed choice, is a ConfigError naming key and
    range; no model is built."""
    def not_reached(*args, **kwargs):
        raise AssertionError("a model was built from an invalid config")

    monkeypatch.setattr(sim.api.simulation.SolverSettings, "from_config", not_reached)
    monkeypatch.setattr(sim.api.simulation.Geometry, "from_config", not_reached)
    with pytest.raises(ConfigError) as err:
        sim.simulate(with_value(composed, kind, name, value))
    if isinstance(check, Number):
        names_key(str(err.value), name, check)
    else:
        assert f"{name} = {value!r} is outside the allowed range: {check}" in str(err.value)


def test_simulate_and_build_model_pass_a_valid_config_on(composed, monkeypatch):
    """The shipped default passes the check and reaches the model (the validation is no stub)."""
    reached = []
    sim.api.simulation.clear_caches()    # models of earlier tests with the same config are kept per content
    monkeypatch.setattr(sim.api.simulation.SolverSettings, "from_config", lambda cfg: reached.append(cfg) or 1 / 0)
    for call in (sim.simulate, sim.api.simulation.build_model):
        with pytest.raises(ZeroDivisionError):
            call(composed["TSRB"])
    assert len(reached) == 2
    with pytest.raises(ConfigError, match=r"^bearing\.kappa = 1\.5 is outside"):
        sim.api.simulation.build_model(with_value(composed, "TSRB", "bearing.kappa", 1.5))


def _constructor(group, name):
    """(build(cfg), error class) of the constructor that checks key ``name``, or None."""
    key = name.split(".", 1)[1]
    if group == "bearing" and not key.startswith("surface."):
        return lambda c: Geometry.from_config(c.bearing, c.material, c.solver.n_slices), GeometryError
    if group == "material" and key in ("E", "nu", "density"):
        return lambda c: Geometry.from_config(c.bearing, c.material, c.solver.n_slices), GeometryError
    if group == "lubricant":
        return lambda c: Lubricant.from_config(OmegaConf.to_container(c.lubricant)), InputError
    if group == "load":
        return lambda c: OperatingPoint.from_config(OmegaConf.to_container(c.load)), InputError
    if group == "solver":
        return lambda c: SolverSettings.from_config(c.solver), InputError
    return None


CONSTRUCTED = [p for p in REFUSED if _constructor(p.values[0].split(".")[0], p.values[0])]


@pytest.mark.parametrize("name, kind, value, check", CONSTRUCTED)
def test_constructors_refuse_every_bound_of_their_keys(composed, name, kind, value, check):
    """Geometry / Lubricant / OperatingPoint / SolverSettings.from_config check their node
    against the schema: the same refusal as sim.simulate, as their own error class."""
    build, error = _constructor(name.split(".")[0], name)
    with pytest.raises(error) as err:
        build(with_value(composed, kind, name, value))
    if isinstance(check, Number):
        names_key(str(err.value), name, check)
    else:
        assert f"{name} = {value!r} is outside the allowed range: {check}" in str(err.value)


def test_geometry_checks_n_slices_it_is_given(composed):
    cfg = composed["TSRB"]
    with pytest.raises(GeometryError) as err:
        Geometry.from_config(cfg.bearing, cfg.material, 1)
    assert str(err.value) == "solver.n_slices = 1 is outside the allowed range: an integer in [2, 400]"


def test_lubricant_fitted_walther_slope_uses_the_schema_range():
    """Two viscosity points whose fitted slope leaves walther_slope's range: refused, quoting it."""
    cfg = OmegaConf.to_container(sim.load_config([]).lubricant)
    cfg.update(viscosity=[57.01, 56.9])   # nearly flat: B far below 1
    with pytest.raises(InputError, match=re.escape(f"it must be {field_check(LubricantConfig, 'walther_slope')}")):
        Lubricant.from_config(cfg)


# ---------------------------------------------------------------------------- no restated bound
SCHEMA_KEYS = {group: {n.split(".")[-1] for n, _ in schema_fields() if n.split(".")[0] == group} for group in SCHEMAS}
GUARDED = {  # module -> (schema groups of the keys it builds from, top-level names checked; None: all)
    "sim/geometry.py": (("bearing", "material", "solver"), None),
    "sim/physics/lubricant.py": (("lubricant",), None),
    "sim/api/bearing_model.py": (("load", "solver"), ("OperatingPoint", "SolverSettings")),
}


def test_friction_model_trusts_the_validated_config():
    """FrictionModel is only built by sim.api.simulation after the schema check: it re-checks no
    key (no range call, no refusal of its own); the data-flow check above is too coarse for its
    kinematic code (comparisons of derived speeds and loads with 0)."""
    source = (REPO / "sim/api/friction_model.py").read_text()
    for forbidden in ("check_range", "InputError", "raise "):
        assert forbidden not in source


def _is_number_literal(node):
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
        node = node.operand
    return isinstance(node, ast.Constant) and isinstance(node.value, (int, float)) and not isinstance(node.value, bool)


def _targets(target):
    return [n.id for n in ast.walk(target) if isinstance(n, ast.Name)]


class _Sources:
    """Which schema keys an expression depends on, in one function: string constants,
    attributes and names that are keys, and local names through their latest assignment or
    loop at or above the use (a loop over a literal list of key names gives one key at a
    time); ``len(...)`` counts, not values."""

    def __init__(self, unit, keys):
        self.keys = keys
        self.assigned = []  # (line, name, value expression or a set of keys)
        for node in ast.walk(unit):
            if isinstance(node, (ast.Assign, ast.AnnAssign)) and node.value is not None:
                for t in (node.targets if isinstance(node, ast.Assign) else [node.target]):
                    if isinstance(t, ast.Tuple) and isinstance(node.value, ast.Tuple) \
                            and len(t.elts) == len(node.value.elts):
                        self.assigned += [(node.lineno, n, v) for e, v in zip(t.elts, node.value.elts)
                                          for n in _targets(e)]
                    else:
                        self.assigned += [(node.lineno, n, node.value) for n in _targets(t)]
            elif isinstance(node, (ast.For, ast.comprehension)):
                elts = getattr(node.iter, "elts", None)
                value = node.iter
                if elts and all(isinstance(e, ast.Constant) and e.value in keys for e in elts):
                    value = {"one of " + ", ".join(sorted(e.value for e in elts))}
                line = getattr(node, "lineno", None) or node.iter.lineno
                self.assigned += [(line, n, value) for n in _targets(node.target)]

    def of(self, node, line, seen=frozenset()):
        """Keys that ``node``, used at ``line``, depends on."""
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == "len":
            return set()
        found = set()
        if isinstance(node, ast.Constant) and isinstance(node.value, str) and node.value in self.keys:
            found.add(node.value)
        elif isinstance(node, ast.Attribute) and node.attr in self.keys:
            found.add(node.attr)
        elif isinstance(node, ast.Name):
            found |= {node.id} & self.keys
            before = [(ln, v) for ln, n, v in self.assigned if n == node.id and ln <= line and (n, ln) not in seen]
            if before:
                ln, value = max(before, key=lambda item: item[0])
                found |= value if isinstance(value, set) else self.of(value, ln, seen | {(node.id, ln)})
        for child in ast.iter_child_nodes(node):
            found |= self.of(child, line, seen)
        return found


def _called(call):
    return getattr(call.func, "id", None) or getattr(call.func, "attr", "")


def restated_bounds(source, keys, names=None):
    """(line, text) of every single-key range check in ``source``: a comparison of a number
    with an expression of exactly one schema key, a ``check_range`` call, or a table mapping a
    key to numbers (NEWTON_LIMITS style). ``names``: the only top-level functions and classes
    to look into (module-level statements are always looked into)."""
    tree = ast.parse(source)
    defs = (ast.FunctionDef, ast.ClassDef)
    top = [n for n in tree.body if not isinstance(n, defs) or names is None or n.name in names]
    units = [f for n in top for f in ast.walk(n) if isinstance(f, ast.FunctionDef)]
    units += [n for n in top if not isinstance(n, defs)]
    found = []
    for unit in units:
        sources = _Sources(unit, keys)
        for node in ast.walk(unit):
            if isinstance(node, ast.Compare):
                operands = [node.left, *node.comparators]
                others = set().union(*(sources.of(o, node.lineno) for o in operands if not _is_number_literal(o)))
                if any(map(_is_number_literal, operands)) and len(others) == 1:
                    found.append((node.lineno, ast.unparse(node)))
            elif isinstance(node, ast.Call) and _called(node) == "check_range":
                found.append((node.lineno, ast.unparse(node)))
            elif isinstance(node, ast.Dict):
                for k, v in zip(node.keys, node.values):
                    if isinstance(k, ast.Constant) and k.value in keys and isinstance(v, ast.Tuple) \
                            and any(map(_is_number_literal, v.elts)):
                        found.append((node.lineno, ast.unparse(k) + ": " + ast.unparse(v)))
    return sorted(set(found))


@pytest.mark.parametrize("module", sorted(GUARDED))
def test_no_constructor_restates_a_schema_bound(module):
    groups, names = GUARDED[module]
    keys = set().union(*(SCHEMA_KEYS[g] for g in groups))
    found = restated_bounds((REPO / module).read_text(), keys, names)
    assert not found, f"{module} re-states schema bounds (sim/config_schema.py is their one source):\n" + \
        "\n".join(f"  line {line}: {text}" for line, text in found)


def test_restated_bound_finder_finds_the_checks_it_replaced():
    """The finder flags the forms of the removed checks and passes combinations and counts."""
    old = '''
def from_config(cls, lub, b, material, n_slices, solver):
    alpha_p = float(lub["pressure_viscosity"])
    if not 0.0 <= alpha_p <= 0.1:
        raise InputError("")
    for temp in [float(t) for t in lub["temperature"]]:
        if not -40.0 <= temp <= 200.0:
            raise InputError("")
    for key in ("Dpw", "Dwe"):
        _require(float(b[key]) > 0.0, key, b[key], "> 0")
    E = float(material["E"])
    _require(E > 0.0, "material.E", E, "> 0")
    _require(2 <= n_slices <= 400, "solver.n_slices", n_slices, "")
    x = check_range("solver.tolerance", solver["tolerance"], 1e-14, 1e-3, low_open=True)
    LIMITS = {"forcing": (0.0, 1.0, False, float)}
'''
    ok = '''
def from_config(cls, lub, T, nu, self):
    if len(T) != len(nu) or not 1 <= len(T) <= 2:
        raise InputError("")
    if (nu[0] - nu[1]) * (T[1] - T[0]) <= 0.0:
        raise InputError("")
    _require(self.aPk + self.aP < self.Lwe, "aPk", self.aPk, "")
    _require(rho_ends.min() > 0.1 * self.Dwe, "PCR", self.PCR, "")
'''
    keys = {"pressure_viscosity", "temperature", "viscosity", "Dpw", "Dwe", "E", "n_slices", "tolerance", "forcing",
            "aPk", "aP", "Lwe", "PCR"}
    assert len(restated_bounds(old, keys)) == 7
    assert restated_bounds(ok, keys) == []


# ---------------------------------------------------------------------------- what still checks by hand
def _schema_check(dotted):
    group, *path = dotted.split(".")
    schema = SCHEMAS[group]
    for part in path[:-1]:
        schema = next(f.type for f in fields(schema) if f.name == part)
    return field_check(schema, path[-1])


@pytest.mark.parametrize("schema, key, codes", [
    (BearingConfig, "type", TYPE_CODES),
    (SolverConfig, "elasticity", ELASTICITY_MODES),
    (SCHEMAS["friction"], "film_thickness", FILM_FORMULAS),
    (LubricantConfig, "pressure_viscosity_model", PRESSURE_VISCOSITY_MODELS),
    (SCHEMAS["friction"], "traction_law", TRACTION_LAWS),
], ids=["type", "elasticity", "film_thickness", "pressure_viscosity_model", "traction_law"])
def test_kernel_code_maps_hold_exactly_the_schema_choices(schema, key, codes):
    """The bottom-layer schema writes its choices out; each kernel's name -> code map has them all."""
    assert sorted(field_check(schema, key).options) == sorted(codes)

