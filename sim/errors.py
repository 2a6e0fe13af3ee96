"""The project's input errors (bottom layer: imported by every other layer, imports nothing).

Every refusal names the parameter, its value and the allowed range or bound (STYLE.md). The
ranges themselves are :mod:`sim.config_schema`'s, their one source.
"""


class InputError(ValueError):
    """Invalid load, solver or friction input; the message names the key, its value and the allowed range."""


class OutOfRangeError(InputError):
    """A load case beyond the model's validity for this bearing
    (:meth:`sim.api.bearing_model.BearingModel.check_limits`): refused input when it is a run's only
    case; in a grid of cases, a case without a result (``converged`` False, this message its
    reason), as a multirun records a job of that case."""


class GeometryError(ValueError):
    """Impossible bearing geometry; the message names the parameter, its value and the bound."""


class ConfigError(InputError):
    """Config values outside their schema (:mod:`sim.config_schema`); the message names each key,
    value and allowed range, one per line. An InputError: callers that treat bad input as a
    configuration error (``studies.evaluate.simulate_point``) treat this one alike."""
