"""The public API (edge layer): config schema, load cases, the bearing and friction models,
``simulate``, ``simulate_batch``, sweeps and the result cache. Studies and command lines import
from here and from :mod:`sim.io` only.
"""
from sim.api.bearing_model import OperatingPoint
from sim.api.cases import operating_points
from sim.api.simulation import build_model, simulate, simulate_batch
from sim.errors import ConfigError, GeometryError, InputError
from sim.geometry import Geometry
from sim.physics import ratings
from sim.physics.lubricant import Lubricant

__all__ = ["ConfigError", "Geometry", "GeometryError", "InputError", "Lubricant", "OperatingPoint", "build_model",
           "operating_points", "ratings", "simulate", "simulate_batch"]
