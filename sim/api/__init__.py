"""The public API (edge layer): config schema, load cases, the bearing and friction models,
``simulate``, ``simulate_batch``, sweeps and the result cache. Studies and command lines import
from here and from :mod:`sim.io` only.
"""
from sim.api.bearing_model import OperatingPoint
from sim.api.cases import operating_points
from sim.api.processes import worker_pool
from sim.api.simulation import build_model, simulate, simulate_batch
from sim.api.schema import not_a_key
from sim.api.traction import TRACTION_LAWS, bearing_model_traction_law, traction_curve, twin_disc_contact
from sim.errors import ConfigError, GeometryError, InputError
from sim.geometry import Geometry
from sim.physics import ratings
from sim.physics.lubricant import Lubricant, pressure_viscosity_roelands
from sim.physics.reference_models import (SKF_TAPERED_CONSTANTS, aihara_1987_trb, aihara_rolling_moment, skf_2004_trb,
                                          torque_exponent)

__all__ = ["ConfigError", "Geometry", "GeometryError", "InputError", "Lubricant", "OperatingPoint",
           "SKF_TAPERED_CONSTANTS", "TRACTION_LAWS", "aihara_1987_trb", "aihara_rolling_moment",
           "bearing_model_traction_law", "build_model", "not_a_key", "operating_points", "pressure_viscosity_roelands", "ratings", "simulate",
           "simulate_batch", "skf_2004_trb",
           "torque_exponent", "traction_curve", "twin_disc_contact", "worker_pool"]
