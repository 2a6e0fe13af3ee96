"""From a composed config to a result Dataset: the bearing and friction models, solve, results.

``simulate(cfg)`` is the public entry point (re-exported as ``sim.simulate``). It validates
every input before any numerics run, solves each load case with the quasi-static solver and
hands plain arrays to :mod:`sim.io`, the only builder of Datasets.

Per-call overhead. A warm ``simulate`` of one combined case costs the physics (the load
distribution twice and the traction kinematics) plus what surrounds it; that part is kept
small by doing once per configuration what does not depend on the case:

- the resolved config is read once per call (``OmegaConf.to_container``); its content
  (``repr``) keys the caches (:data:`CACHE_SIZE` entries each), so equal content, in the same
  object or a new one, reuses them and changed content (a new load, a mutated node) never does;
- the provenance YAML (``OmegaConf.to_yaml``: the slow pure-Python YAML emitter) is kept per
  top-level node: a call whose load alone changed (each case of a sweep) serialises its
  ``load`` node only;
- the bearing and friction models are kept per content of the nodes they read;
- :func:`sim.io.build_dataset` creates the Dataset once from numpy arrays.
"""
import time
from collections import OrderedDict

from omegaconf import OmegaConf

from sim.api.bearing_model import BearingModel, SolverSettings, case_results
from sim.api.cases import operating_points
from sim.api.friction_model import FrictionModel
from sim.errors import InputError
from sim.geometry import Geometry
from sim.io import build_dataset
from sim.physics.lubricant import Lubricant

CACHE_SIZE = 128                      # configurations whose YAML and models are kept
MODEL_KEYS = ("bearing", "material", "solver", "friction", "lubricant")   # what build_model/build_friction read


def build_model(cfg):
    """Validated :class:`BearingModel` of a composed config (bearing, material, solver)."""
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


# ------------------------------------------------------------------ per-configuration caches
class _Cache:
    """Least-recently-used mapping of at most ``size`` entries (one per configuration content)."""

    def __init__(self, size):
        self.size, self.data = size, OrderedDict()

    def get(self, key, make):
        if key in self.data:
            self.data.move_to_end(key)
            return self.data[key]
        value = make()                 # an exception caches nothing
        self.data[key] = value
        if len(self.data) > self.size:
            self.data.popitem(last=False)
        return value

    def clear(self):
        self.data.clear()


_YAML = _Cache(8 * CACHE_SIZE)  # repr of (top-level key, resolved node) -> its block of the YAML
_MODELS = _Cache(CACHE_SIZE)    # repr of its MODEL_KEYS nodes -> (BearingModel, FrictionModel or None)


def resolved(cfg):
    """The resolved config as plain containers, as ``OmegaConf.to_yaml`` sees it."""
    return OmegaConf.to_container(cfg, resolve=True, enum_to_str=True)


def _yaml_block(key, value):
    return OmegaConf.to_yaml(OmegaConf.create({key: value}))


def config_yaml(cfg, plain=None):
    """``OmegaConf.to_yaml(cfg, resolve=True)``, each top-level node serialised once per content.

    ``plain``: :func:`resolved` of ``cfg`` when the caller has it. ``to_yaml`` dumps exactly
    that container, a block-style mapping whose top-level entries follow each other, each a
    block of its own that depends on its key and node only; a block is serialised on the first
    call with its content (``repr`` tells apart every difference in value, type, 17 and 17.0,
    and key order) and reused after.
    """
    plain = resolved(cfg) if plain is None else plain
    if not isinstance(plain, dict) or not plain:
        return OmegaConf.to_yaml(cfg, resolve=True)
    return "".join(_YAML.get(repr((key, value)), lambda: _yaml_block(key, value)) for key, value in plain.items())


def build_models(cfg, plain=None):
    """(:func:`build_model`, :func:`build_friction`) of ``cfg``, built once per content of the
    config nodes they read (:data:`MODEL_KEYS`) and shared: both hold parameters only, and
    every solve and evaluation allocates its own state."""
    plain = resolved(cfg) if plain is None else plain

    def make():
        model = build_model(cfg)
        return model, build_friction(cfg, model)

    return _MODELS.get(repr([plain.get(key) for key in MODEL_KEYS]), make)


def clear_caches():
    """Forget the cached YAML and models (they are rebuilt on the next call)."""
    _YAML.clear()
    _MODELS.clear()


def _solve_design(cfg, case_slice=slice(None)):
    """Everything :func:`simulate` does but the Dataset: (model, ops, results, plain config)."""
    plain = resolved(cfg)
    model, friction = build_models(cfg, plain)
    ops = operating_points(cfg.load)
    output = plain["output"]
    results = [solve_case(model, friction, op, output) for op in ops[case_slice]]
    return model, ops, results, plain


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
    model, ops, results, plain = _solve_design(cfg)
    return build_dataset(model.geometry, ops, results, config_yaml(cfg, plain), model.settings)
