"""Load cases of a ``load`` config node: one operating point or a grid of them.

A ``load`` node (``conf/load/``) holds Fa [N], Fr [N], speed [rpm], tilt [deg] and
oil_temperature [degC], each a number or a list of numbers. Lists combine as a full factorial
in the order Fa, Fr, speed, tilt, oil_temperature (the last varies fastest), except the keys
grouped in ``zip``: those pair up element by element (lists of equal length; a number is
repeated) and vary together as one factor, in the place of their first key::

    Fa: [3000, 4500]  Fr: [0, 2000, 4000]                         -> 6 cases
    Fa: [4000, 4000, 7000]  Fr: [0, 2000, 0]  zip: [[Fa, Fr]]     -> 3 cases
    the same with speed: [1000, 2000, 4000]                       -> 9 cases, speed fastest

A grid runs inside one process and its cases fill the ``case`` dimension (DATA.md).
"""
import itertools

from omegaconf import ListConfig

from sim.api.bearing_model import OperatingPoint
from sim.errors import InputError

LOAD_KEYS = ("Fa", "Fr", "speed", "tilt", "oil_temperature")


def _values(load_cfg, key):
    value = load_cfg[key]
    values = list(value) if isinstance(value, (list, tuple, ListConfig)) else [value]
    if not values:
        raise InputError(f"load.{key} is an empty list")
    for v in values:
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            raise InputError(f"load.{key} = {v!r} is not a number")
    return values, isinstance(value, (list, tuple, ListConfig))


def _zip_groups(load_cfg):
    groups = [list(g) for g in (load_cfg.get("zip") or [])]
    named = [k for g in groups for k in g]
    for k in named:
        if k not in LOAD_KEYS:
            raise InputError(f"load.zip names {k!r}, which is not one of {list(LOAD_KEYS)}")
        if named.count(k) > 1:
            raise InputError(f"load.zip names {k!r} more than once")
    return groups


def _zipped(load_cfg, group):
    """Value tuples of one zipped group, in the group's key order."""
    columns = {k: _values(load_cfg, k) for k in group}
    lengths = {k: len(v) for k, (v, is_list) in columns.items() if is_list}
    if len(set(lengths.values())) > 1:
        raise InputError(f"load.zip {group}: zipped lists need equal lengths, got {lengths}")
    n = max(lengths.values(), default=1)
    return [tuple(v[i] if is_list else v[0] for v, is_list in columns.values()) for i in range(n)]


def operating_points(load_cfg):
    """The load cases of a ``load`` config node, in grid order.

    Parameters
    ----------
    load_cfg : mapping
        ``Fa``, ``Fr`` [N], ``speed`` [rpm], ``tilt`` [deg], ``oil_temperature`` [degC]: each a
        number or a list; optional ``zip``: groups of keys whose lists pair up.

    Returns
    -------
    list of sim.api.simulation.OperatingPoint

    Raises
    ------
    sim.api.simulation.InputError
        Naming the key: a value that is no number or outside its range, zipped lists of
        unequal length, or a case that the grid holds twice.
    """
    groups = _zip_groups(load_cfg)
    factors = []  # (keys, list of value tuples)
    for key in LOAD_KEYS:
        group = next((g for g in groups if key in g), [key])
        if key == min(group, key=LOAD_KEYS.index):
            factors.append((group, _zipped(load_cfg, group)))
    ops = {}  # insertion-ordered set
    for combination in itertools.product(*(values for _, values in factors)):
        case = {k: v for (keys, _), row in zip(factors, combination) for k, v in zip(keys, row)}
        op = OperatingPoint.from_config(case)
        if op in ops:
            raise InputError(f"load: the grid holds the case {op} more than once")
        ops[op] = None
    return list(ops)
