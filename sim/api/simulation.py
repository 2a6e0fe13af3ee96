"""From a composed config to a result Dataset: the bearing and friction models, solve, results.

``simulate(cfg)`` is the public entry point (re-exported as ``sim.simulate``). It validates
every input before any numerics run, solves each load case with the quasi-static solver and
hands plain arrays to :mod:`sim.io`, the only builder of Datasets.
"""
import time

from omegaconf import OmegaConf

from sim.api.bearing_model import BearingModel, SolverSettings, case_results
from sim.api.cases import operating_points
from sim.api.friction_model import FrictionModel
from sim.api.schema import validate
from sim.errors import InputError
from sim.geometry import Geometry
from sim.io import build_dataset
from sim.physics.lubricant import Lubricant


def build_model(cfg):
    """Validated :class:`BearingModel` of a composed config (bearing, material, solver)."""
    validate(cfg)  # every key against its schema (sim.config_schema) before anything is built
    settings = SolverSettings.from_config(cfg.solver)
    geometry = Geometry.from_config(cfg.bearing, cfg.material, settings.n_slices)
    if "slice_stiffness_iso16281" not in cfg.material:
        raise InputError("material.slice_stiffness_iso16281 is missing (ISO/TS 16281 line-contact stiffness)")
    return BearingModel(geometry, cfg.material, settings)


def build_friction(cfg, model):
    """Validated :class:`sim.api.friction_model.FrictionModel` of a composed config, or None when
    ``friction.enabled`` is false (then no torque variable is written)."""
    if not bool(cfg.friction.enabled):
        return None
    if "surface" not in cfg.bearing:
        raise InputError("bearing.surface is missing (roughness sigma and Zhou-Hoeprich B_ZH, C_ZH, thesis (5.16))")
    return FrictionModel(model.geometry, model.E_star, Lubricant.from_config(cfg.lubricant), cfg.friction,
                         cfg.bearing.surface, cfg.material)


def solve_case(model, friction, op, output_cfg):
    """Load distribution, then kinematics and friction of one case; DATA.md outputs (output units).

    A case counts as converged only when both the load distribution and the traction
    kinematics converged; otherwise only its status and the load-derived P, P0 are kept.
    """
    t0 = time.perf_counter()
    raw = model.solve(op)
    if friction is None or not raw["converged"]:
        return case_results(model, op, raw, output_cfg)
    fr = friction.evaluate(op, raw)
    if fr["friction_converged"]:
        # friction loads on the rollers (cage pocket) enter the load distribution; one
        # fixed-point pass: they are 1e-3 of the contact loads, so a second pass changes the
        # result below the solver tolerance
        raw = model.solve(op, roller_loads=fr["roller_loads"])
        fr = friction.evaluate(op, raw, start=fr["kinematics"]) if raw["converged"] else {"friction_converged": False}
    res = case_results(model, op, raw, output_cfg)
    if not (res["converged"] and fr.pop("friction_converged")):
        return {key: res[key] for key in ("iterations", "wall_time", "P", "P0")} | {"converged": False}
    fr.pop("roller_loads")
    fr.pop("kinematics")
    res.update(fr)
    res["wall_time"] = time.perf_counter() - t0
    return res


def simulate(cfg):
    """Run the configured bearing through every load case of ``cfg.load``.

    Parameters
    ----------
    cfg : omegaconf.DictConfig
        Composed config (``sim.load_config``): bearing, material, lubricant, friction, load, solver, output.

    Returns
    -------
    xarray.Dataset
        The result following DATA.md, dims ``design`` (1) and ``case``.
    """
    validate(cfg)  # every key against its schema (sim.config_schema): ConfigError before anything runs
    model = build_model(cfg)
    friction = build_friction(cfg, model)
    ops = operating_points(cfg.load)
    results = [solve_case(model, friction, op, cfg.output) for op in ops]
    return build_dataset(model.geometry, ops, results, OmegaConf.to_yaml(cfg, resolve=True), model.settings)
