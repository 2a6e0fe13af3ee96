"""Geometry feasibility is complete (issue 15, item 2): every rule of ``Geometry.RULES`` is swept
across its boundary along every key it combines.

Walks: from a base bearing, one key is moved up (or down) by growing factors (integers by growing
steps, the schema's range end included) until ``Geometry.from_config`` refuses; the first
refusal is bisected to its boundary (relative width 1e-9, or adjacent integers). Just inside
passes; just outside is refused by a feasibility rule (never a crash) whose message names the
blamed key with its value and, when another key of the rule was changed, that key with its
value; where the rule states its bound as a number, that bound is the boundary found.

Bases: the shipped bearings and wide variants (rings that do not limit), and for each rule a
*tight* copy of a base, its blamed key moved to just inside that rule's boundary, from which
every key of the rule is walked both ways. Every (rule, key) pair of ``Geometry.RULES`` must be
reached. The issue's reproducers (Z = 200, PCR = 1e30) are tested by name.
"""
import math
import re

import pytest
from omegaconf import OmegaConf

import sim
from sim.config_schema import BearingConfig, field_check
from sim.errors import GeometryError
from sim.geometry import Geometry, max_rollers

N_SLICES = 8
WIDE = {"r": 1.0, "R": 300.0, "B": 300.0}  # rings and width that limit nothing
# base name -> (bearing config, overrides)
BASES = {
    "tsrb_reference": ("tsrb_reference", {}),
    "tsrb_prototype": ("tsrb_prototype", {}),
    "tsrb_wide": ("tsrb_reference", WIDE),
    "tsrb_wide_three_rollers": ("tsrb_reference", {**WIDE, "Z": 3}),
    # a short fat roller: the crown circle's span, not its end radii, limits PCR
    "tsrb_short_roller": ("tsrb_reference", {**WIDE, "Lwe": 6.0, "aP": 2.0, "aPk": 1.0, "PCR": 20.0}),
    "trb_32208": ("trb_32208", {}),
    "trb_31313": ("trb_31313", {}),
    "trb_wide": ("trb_32208", WIDE),
    # a steep TRB with a big roller, three of them, a weak crown and a low rib contact: the
    # roller-end sphere and the rib contact height can both limit
    "trb_steep": ("trb_32208", {**WIDE, "alpha": 55.0, "Dwe": 40.0, "Lwe": 10.0, "Z": 3, "crown_coefficient": 1e-4,
                                "rib_contact_height_ratio": 0.05, "roller_end_radius_ratio": 0.9}),
    # a strong crown drops the large end below Dwe/2: the rib contact height limits
    "trb_strong_crown": ("trb_32208", {**WIDE, "crown_coefficient": 0.0099}),
    # the torus roller end (docs/roller_end_torus.md): its rib opening angle limits; on a thin
    # roller its edge radius reaches the end face's rim within the schema's 5 mm
    "trb_torus": ("trb_32208", {"roller_end": "torus"}),
    "trb_torus_thin_roller": ("trb_32208", {**WIDE, "roller_end": "torus", "Dwe": 6.0}),
}
INTEGER = {"Z"}
FACTORS = (1.001, 1.01, 1.03, 1.1, 1.3, 2.0, 4.0, 10.0, 100.0, 1e3, 1e4)


def kind_of(base):
    return "TRB" if base.startswith("trb") else "TSRB"


def base_config(name):
    config, overrides = BASES[name]
    cfg = sim.load_config([f"bearing={config}"])
    bearing = OmegaConf.to_container(cfg.bearing, resolve=True)
    bearing.update(overrides)
    return bearing, OmegaConf.to_container(cfg.material, resolve=True)


def build(bearing, material):
    return Geometry.from_config(bearing, material, N_SLICES)


def outcome(bearing, material, key, value):
    """None if the bearing with ``key = value`` builds, else its GeometryError."""
    try:
        build(dict(bearing, **{key: value}), material)
    except GeometryError as err:
        return err
    return None


def steps(key, v0, direction):
    """Values to try along ``key`` from ``v0``: growing steps, cut at the schema's range (its last
    allowed value included)."""
    check = field_check(BearingConfig, key)
    if key in INTEGER:
        values = [v0 + direction * n for n in (1, 2, 4, 8, 16, 32, 64, 128, 256, 512)]
    else:
        values = [v0 * f ** direction for f in FACTORS]
    end = check.high if direction > 0 else check.low
    if math.isfinite(end):
        open_end = check.high_open if direction > 0 else check.low_open
        last = end - direction * (1e-6 * max(abs(end), 1e-3) if open_end else 0.0)
        values = [v for v in values if (v - last) * direction < 0] + [last]
    return values


def walk(bearing, material, key, direction):
    """(inside, outside, error) at the first refusal along ``key`` in ``direction``, bisected to
    the boundary; None when nothing in the schema's range refuses."""
    inside = bearing[key]
    for v in steps(key, inside, direction):
        err = outcome(bearing, material, key, v)
        if err is None:
            inside = v
            continue
        assert getattr(err, "rule", None) in Geometry.RULES, f"{key} = {v}: refused by no feasibility rule: {err}"
        outside = v
        break
    else:
        return None
    while abs(outside - inside) > (1 if key in INTEGER else 1e-9 * abs(inside)):
        mid = (inside + outside) // 2 if key in INTEGER else 0.5 * (inside + outside)
        if outcome(bearing, material, key, mid) is None:
            inside = mid
        else:
            outside = mid
    return inside, outside, outcome(bearing, material, key, outside)


def check_crossing(bearing, material, key, found):
    """Just inside builds; just outside names the blamed key and value, the changed key and value,
    and (where stated) the bound found."""
    inside, outside, err = found
    assert outcome(bearing, material, key, inside) is None
    blamed, keys = Geometry.RULES[err.rule]
    assert key in keys, f"rule {err.rule} refused a change of {key}, which it does not list: {err}"
    message = str(err)
    assert message.startswith(f"bearing.{blamed} = ") and err.key == f"bearing.{blamed}", message
    shown = outside if key in INTEGER else float(outside)
    if key == blamed:
        assert f"bearing.{key} = {shown!r} is impossible" in message, message
        if err.limit is not None:
            assert err.limit == pytest.approx(inside if key in INTEGER else 0.5 * (inside + outside), rel=1e-6)
    else:  # alpha goes through radians and back: equal to round-off
        named = [float(v) for v in re.findall(rf"\b{key} = ([-+]?[\d.]+(?:e[-+]?\d+)?)", message)]
        assert any(v == pytest.approx(shown, rel=1e-12) for v in named), message


def rule_keys(kind):
    """Keys of the rules that a bearing type has (the other type's keys are not in its config)."""
    own = {n for n, f in BearingConfig.__dataclass_fields__.items() if f.metadata.get("only") in (None, kind)}
    return sorted({k for _, keys in Geometry.RULES.values() for k in keys} & own)


def tight(base, rule):
    """``base`` with the blamed key of ``rule`` just inside that rule's boundary, or None if the
    rule does not limit that key from this base."""
    bearing, material = base_config(base)
    blamed = Geometry.RULES[rule][0]
    if blamed not in rule_keys(kind_of(base)):
        return None
    for direction in (-1, 1):
        found = walk(bearing, material, blamed, direction)
        if found and found[2].rule == rule:
            return dict(bearing, **{blamed: found[0]}), material
    return None


WALKS = [(b, k, d) for b in BASES for k in rule_keys(kind_of(b)) for d in (-1, 1)]


@pytest.fixture(scope="module")
def reached():
    """(rule, key) pairs reached by the walks of the tests below (filled as they run)."""
    return set()


def test_every_base_builds():
    for base in BASES:
        build(*base_config(base))


@pytest.mark.parametrize("base", sorted(BASES))
def test_walks_from_each_base(base, reached):
    """Every key of every rule, up and down from a base: a named refusal at the boundary."""
    bearing, material = base_config(base)
    for key in rule_keys(kind_of(base)):
        for direction in (-1, 1):
            found = walk(bearing, material, key, direction)
            if found:
                check_crossing(bearing, material, key, found)
                reached.add((found[2].rule, key))


@pytest.mark.parametrize("rule", sorted(Geometry.RULES))
def test_walks_from_a_base_tight_on_each_rule(rule, reached):
    """From each base with the rule's blamed key just inside the rule, every key of the rule both
    ways: a named refusal at the boundary."""
    bases = [tight(b, rule) for b in BASES]
    bases = [b for b in bases if b is not None]
    assert bases, f"no base reaches rule {rule} along its blamed key"
    for bearing, material in bases:
        for key in Geometry.RULES[rule][1]:
            if bearing.get(key) is None:  # a key of the other bearing type
                continue
            for direction in (-1, 1):
                found = walk(bearing, material, key, direction)
                if found:
                    check_crossing(bearing, material, key, found)
                    reached.add((found[2].rule, key))


def test_every_rule_is_reached_along_every_key_it_names(reached):
    """Coverage of the walks above (run in this module's order): each (rule, key) of Geometry.RULES
    was the first refusal of some walk."""
    wanted = {(rule, key) for rule, (_, keys) in Geometry.RULES.items() for key in keys}
    assert sorted(wanted - reached) == []


# ---------------------------------------------------------------------------- the reproducers
def compose_bearing(*overrides):
    cfg = sim.load_config(list(overrides))
    return cfg.bearing, cfg.material


def test_z_200_is_refused_naming_z_and_the_most_that_fit():
    with pytest.raises(GeometryError) as err:
        build(*compose_bearing("bearing=tsrb_reference", "bearing.Z=200"))
    assert str(err.value).startswith("bearing.Z = 200 is impossible: it must be <= 17, the most that fit")
    assert max_rollers(60.0, 10.0, 0.05) == 17


def test_pcr_1e30_blames_pcr():
    with pytest.raises(GeometryError) as err:
        build(*compose_bearing("bearing=tsrb_reference", "bearing.PCR=1e30"))
    assert str(err.value).startswith("bearing.PCR = 1e+30 is outside the allowed range")


@pytest.mark.parametrize("Dpw, Dwe, web", [(60.0, 10.0, 0.05), (102.5, 18.0, 0.05), (58.0, 8.4, 0.05), (60, 10, 0.0),
                                           (100.0, 1.0, 0.3), (10.0, 8.6, 0.0), (10.0, 9.0, 0.0)])
def test_max_rollers_is_the_largest_z_with_room_for_the_web(Dpw, Dwe, web):
    z = max_rollers(Dpw, Dwe, web)
    need = (1 + web) * Dwe
    if z:
        assert Dpw * math.sin(math.pi / z) >= need
    assert Dpw * math.sin(math.pi / (z + 1)) < need


def test_cage_web_ratio_range_is_the_schemas():
    assert str(field_check(BearingConfig, "cage_web_ratio")) == "a number in [0, 0.5]"
    bearing, material = compose_bearing("bearing=tsrb_reference", "bearing.cage_web_ratio=0.6")
    with pytest.raises(GeometryError, match=r"bearing\.cage_web_ratio = 0\.6 is outside the allowed range"):
        build(bearing, material)
