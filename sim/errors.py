"""The project's input errors (bottom layer: imported by every other layer, imports nothing).

Every refusal names the parameter, its value and the allowed range or bound (STYLE.md). The
ranges themselves are :mod:`sim.config_schema`'s, their one source.
"""


class InputError(ValueError):
    """Invalid load, solver or friction input; the message names the key, its value and the allowed range."""


class GeometryError(ValueError):
    """Impossible bearing geometry; the message names the parameter, its value and the bound."""


class ResolutionError(ValueError):
    """A solver resolution that does not hold for this case (it depends on the solution, so it is
    found after the solve, and may hold for other cases of the same config); the message names the
    setting, its value and the largest value allowed for the case. Not an InputError: a design
    search records the point as failed and goes on (``studies.evaluate.simulate_point``)."""


class ConfigError(InputError):
    """Config values outside their schema (:mod:`sim.config_schema`); the message names each key,
    value and allowed range, one per line. An InputError: callers that treat bad input as a
    configuration error (``studies.evaluate.simulate_point``) treat this one alike."""
