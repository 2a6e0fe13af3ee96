"""The project's input errors (bottom layer: imported by every other layer, imports nothing).

Every refusal names the parameter, its value and the allowed range or bound (STYLE.md). The
ranges themselves are :mod:`sim.config_schema`'s; :func:`check_range` remains for
``sim.api.friction_model`` until it checks through the schema too.
"""
import math


class InputError(ValueError):
    """Invalid load, solver or friction input; the message names the key, its value and the allowed range."""


class GeometryError(ValueError):
    """Impossible bearing geometry; the message names the parameter, its value and the bound."""


class ConfigError(InputError):
    """Config values outside their schema (:mod:`sim.config_schema`); the message names each key,
    value and allowed range, one per line. An InputError: callers that treat bad input as a
    configuration error (``studies.evaluate.simulate_point``) treat this one alike."""


def check_range(name, value, low, high, low_open=False):
    """``float(value)`` if it lies in [low, high] (or (low, high] with ``low_open``), else InputError
    naming ``name``, the value and the interval."""
    value = float(value)
    ok = math.isfinite(value) and (value > low if low_open else value >= low) and value <= high
    if not ok:
        bracket = "(" if low_open else "["
        raise InputError(f"{name} = {value!r} is outside the allowed range {bracket}{low}, {high}]")
    return value
