"""From a composed config to a result Dataset: the bearing and friction models, solve, results.

``simulate(cfg)`` is the public entry point (re-exported as ``sim.simulate``). It validates
every input before any numerics run, solves each load case with the quasi-static solver and
hands plain arrays to :mod:`sim.io`, the only builder of Datasets. ``simulate_batch(cfgs)``
runs many designs in worker processes into one ``design`` x ``case`` Dataset.

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
import concurrent.futures as cf
import math
import os
from collections import OrderedDict

from omegaconf import OmegaConf

from sim._math.jit import clock, solver_seconds
from sim.api.bearing_model import BearingModel, SolverSettings, case_results
from sim.api import dynamic_model
from sim.api.cases import operating_points
from sim.api.friction_model import FrictionModel, coupled_solution
from sim.api.processes import worker_pool
from sim.api.schema import validate
from sim.errors import InputError, OutOfRangeError
from sim.geometry import Geometry
from sim.io import (DesignFailure, DesignResult, build_batch_dataset, build_dataset, build_dynamic_dataset,
                    failure_message, written_optional)
from sim.physics.lubricant import Lubricant

CACHE_SIZE = 128                      # configurations whose YAML and models are kept
MODEL_KEYS = ("bearing", "material", "solver", "friction", "lubricant")   # what build_model/build_friction read


def build_model(cfg):
    """Validated :class:`BearingModel` of a composed config (bearing, material, solver)."""
    validate(cfg)  # every key against its schema (sim.config_schema) before anything is built
    return _bearing_model(cfg)


def _bearing_model(cfg):
    """:class:`BearingModel` of a config that passed :func:`sim.api.schema.validate`: the
    composed config or its :func:`resolved` plain containers (the nodes are read by key)."""
    settings = SolverSettings.from_config(cfg["solver"])
    geometry = Geometry.from_config(cfg["bearing"], cfg["material"], settings.n_slices)
    if "slice_stiffness_iso16281" not in cfg["material"]:
        raise InputError("material.slice_stiffness_iso16281 is missing (ISO/TS 16281 line-contact stiffness)")
    return BearingModel(geometry, cfg["material"], settings)


def build_friction(cfg, model):
    """Validated :class:`sim.api.friction_model.FrictionModel` of a composed config (or of its
    :func:`resolved` plain containers), or None when ``friction.enabled`` is false (then no
    torque variable is written)."""
    if not bool(cfg["friction"]["enabled"]):
        return None
    if "surface" not in cfg["bearing"]:
        raise InputError("bearing.surface is missing (roughness sigma and Zhou-Hoeprich B_ZH, C_ZH, thesis (5.16))")
    return FrictionModel(model.geometry, model.E_star, model.bearing.end_drop, Lubricant.from_config(cfg["lubricant"]),
                         cfg["friction"], cfg["bearing"]["surface"], cfg["material"])


def solve_case(model, friction, op, output_cfg):
    """Load distribution, then kinematics and friction of one case; DATA.md outputs (output units).

    A case counts as converged only when both the load distribution and the traction
    kinematics converged; otherwise only its status and the load-derived P, P0 are kept.
    """
    t0 = clock()
    if friction is None:
        return case_results(model, op, model.solve(op), output_cfg)
    raw, fr = coupled_solution(model, friction, op)
    return combined_results(model, op, raw, fr, output_cfg, t0)


def combined_results(model, op, raw, fr, output_cfg, t0):
    """:func:`solve_case`'s outputs of the coupled solution (raw, fr) of
    :func:`sim.api.friction_model.coupled_solution` begun at the mark t0 (sim._math.jit.clock); its
    wall_time is the solver time since then, the numba compiling left out (jit.solver_seconds)."""
    res = case_results(model, op, raw, output_cfg)
    res["wall_time"] = solver_seconds(t0)
    if fr is None:      # no load solution, or beyond the static limit: case_results reports why
        return res
    kinematics_converged, coupling_converged = fr.pop("friction_converged"), fr.pop("coupling_converged")
    failure = fr.pop("friction_failure")
    if not (res["converged"] and kinematics_converged and coupling_converged):
        if res["converged"]:    # the load solve stands: the friction failed (else its iterations say why)
            res["status"] = failure or ("friction loads and load distribution not settled within "
                                        "friction.load_coupling_passes")
        return ({key: res[key] for key in ("iterations", "wall_time", "P", "P0", "unrested_rollers", "status") if key in res}
                | {"converged": False})
    fr.pop("roller_loads")
    fr.pop("ring_loads")
    fr.pop("kinematics")
    res.update(fr)
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
_VALID = _Cache(CACHE_SIZE)     # repr of a whole resolved config -> True once it passed the schema


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
    every solve and evaluation allocates its own state. The config is validated once per
    content of the whole config (ConfigError before anything is built)."""
    plain = resolved(cfg) if plain is None else plain
    # every key against its schema (sim.config_schema), once per content
    _VALID.get(repr({k: v for k, v in plain.items() if k != "hydra"}), lambda: validate(cfg) or True)

    def make():   # from the plain containers: read by key 5-10x faster than the config nodes
        model = _bearing_model(plain)
        return model, build_friction(plain, model)

    return _MODELS.get(repr([plain.get(key) for key in MODEL_KEYS]), make)


def clear_caches():
    """Forget the cached YAML and models (they are rebuilt on the next call)."""
    _YAML.clear()
    _MODELS.clear()
    _VALID.clear()


def optional_outputs(friction, dynamic=False):
    """The optional variables (sim.io.written_optional) of a configuration whose friction model
    is ``friction`` (None: friction disabled)."""
    return written_optional(friction is not None, friction is not None and friction.par.skew, dynamic)


# the raw state of a case refused before any solve (case_results: its outputs without a solution)
_NOT_SOLVED = {"converged": False, "iterations": 0, "wall_time": 0.0, "solver_info": {"unrested_rollers": 0}}


def _out_of_range(model, ops, output_cfg, grid):
    """The model's validity limits (:meth:`BearingModel.check_limits`) of every case, before
    anything is solved: {case index: its results without a solution (``converged`` False, the
    refusal its reason)} of the cases beyond them. OutOfRangeError instead when ``grid`` is False
    (a run's only case is refused input)."""
    refused = {}
    for i, op in enumerate(ops):
        try:
            model.check_limits(op)
        except OutOfRangeError as exc:
            if not grid:
                raise
            refused[i] = case_results(model, op, _NOT_SOLVED | {"status": f"refused before the solve: {exc}"},
                                      output_cfg)
    return refused


def _is_grid(ops, grid):
    """:func:`simulate`'s ``grid``: as given, or whether there is more than one case."""
    return len(ops) > 1 if grid is None else bool(grid)


def _solve_design(cfg, case_slice=slice(None), plain=None, grid=None):
    """Everything :func:`simulate` does but the Dataset: (model, ops, results, plain config,
    optional variables)."""
    plain = resolved(cfg) if plain is None else plain
    model, friction = build_models(cfg, plain)   # validates first
    ops = operating_points(plain["load"])
    output = plain["output"]
    refused = _out_of_range(model, ops, output, _is_grid(ops, grid))
    results = [refused[i] if i in refused else solve_case(model, friction, op, output)
               for i, op in list(enumerate(ops))[case_slice]]
    return model, ops, results, plain, optional_outputs(friction)


def simulate(cfg, grid=None):
    """Run the configured bearing through every load case of ``cfg.load``.

    Parameters
    ----------
    cfg : omegaconf.DictConfig
        Composed config (``sim.load_config``): bearing, material, lubricant, friction, load, solver, output.
    grid : bool, optional
        Whether the cases belong to a grid: then a case beyond the model's validity limits
        (:meth:`BearingModel.check_limits`: speed, static load, the single row's axial share) is a
        case without a result (``converged`` False, the refusal its reason) and the others are
        solved, as a multirun records such a job; else it is refused input (OutOfRangeError, an
        InputError) before anything is solved. None: a grid when ``cfg.load`` has more than one
        case (:func:`sim.api.sweep.run_cases` passes True for each single case it runs of a grid).

    Returns
    -------
    xarray.Dataset
        The result following DATA.md, dims ``design`` (1) and ``case``.
    """
    plain = resolved(cfg)
    if plain["solver"]["name"] == "dynamic":
        return _simulate_dynamic(cfg, plain, grid)
    model, ops, results, plain, optional = _solve_design(cfg, plain=plain, grid=grid)
    return build_dataset(model.geometry, ops, results, config_yaml(cfg, plain), model.settings, optional)


def _simulate_dynamic(cfg, plain, grid):
    """:func:`simulate` with ``solver=dynamic``: one load case through the time-domain solver
    (:mod:`sim.api.dynamic_model`), its time series and steady state (sim.io.build_dynamic_dataset)."""
    model, friction = build_models(cfg, plain)   # validates first
    ops = operating_points(plain["load"])
    if len(ops) != 1:
        raise InputError(f"solver=dynamic runs one load case per call, the load gives {len(ops)}: use --multirun "
                         "over the load values")
    if friction is None or ops[0].speed_rpm == 0.0:
        raise InputError("solver=dynamic needs friction.enabled = true and load.speed > 0 (the rollers and the "
                         "cage are driven by the traction)")
    op = ops[0]
    refused = _out_of_range(model, ops, plain["output"], _is_grid(ops, grid))
    t0 = clock()
    dyn = plain["solver"]["dynamic"]
    series = None
    if refused:   # a grid's case beyond the validity limits: no run
        summary = refused[0]
    else:
        try:
            dcase = dynamic_model.prepare(model, friction, op, dyn)
        except dynamic_model.NoQuasiStaticStart as exc:
            # no start, no run: a case without a result (converged False, its reason in the dataset's
            # failed_cases) and an empty time series, as a quasi-static run reports the same case
            summary = combined_results(model, op, exc.raw, exc.fr, plain["output"], t0)
            summary["status"] = f"{exc}: {failure_message(summary)}"
        else:
            integ = dynamic_model.run(dcase)
            summary, series = dynamic_model.outputs(model, op, dcase, integ, solver_seconds(t0), plain["output"])
    return build_dynamic_dataset(model.geometry, op, summary, series, config_yaml(cfg, plain), model.settings, dyn,
                                 optional_outputs(friction, dynamic=True))


# ------------------------------------------------------------------ many designs in worker processes
def _run(cfg, plain, start, stop, with_yaml):
    """Cases ``start:stop`` of one design (``plain``: its :func:`resolved` config): ("ok",
    (geometry, settings, results, YAML or None, optional variables)), or ("error", message): an
    exception fails the design, as it fails :func:`simulate`."""
    try:
        model, _, results, plain, optional = _solve_design(cfg, slice(start, stop), plain)
        return "ok", (model.geometry, model.settings, results, config_yaml(cfg, plain) if with_yaml else None, optional)
    except Exception as exc:
        return "error", f"{type(exc).__name__}: {exc}"


_WORKER_CFGS = ()   # the configs of the batch and their resolved forms, in a worker process


def _init_worker(cfgs, plains):
    global _WORKER_CFGS
    _WORKER_CFGS = tuple(zip(cfgs, plains))


def _run_in_worker(design, start, stop, with_yaml):
    return _run(*_WORKER_CFGS[design], start, stop, with_yaml)


def _kind(plain):
    """Designs of one kind run the same numba kernels: all but the bearing's numbers and the load."""
    rest = {k: v for k, v in plain.items() if k not in ("bearing", "load", "hydra")}
    return repr([(plain.get("bearing") or {}).get("type"), rest])


_WARM = set()   # kinds whose kernels ran in this process (compiled, or loaded from numba's cache)


def _warm_up(cfgs, plains, kinds):
    """Run the first case of designs of each kind not yet warm here, until one converges (at
    most 3 per kind), before the workers start.

    A converged case runs every kernel of its kind (the friction kernels only run after the
    load distribution converged), so they are compiled, or loaded from numba's on-disk cache,
    once, here: forked workers inherit them, spawned ones load them from the cache, and no two
    processes compile the same kernel at once.
    """
    tried = {}
    for cfg, plain, kind in zip(cfgs, plains, kinds):
        if kind is None or kind in _WARM or tried.get(kind, 0) >= 3:
            continue
        tried[kind] = tried.get(kind, 0) + 1
        status, out = _run(cfg, plain, 0, 1, False)
        if status == "ok" and all(res["converged"] for res in out[2]):
            _WARM.add(kind)


def _chunks(n_cases, workers, n_designs):
    """Case ranges of one design's tasks: whole designs when there are at least two per worker
    (fewest tasks, one model build each), else designs cut so that each worker gets about 4."""
    pieces = 1 if n_designs >= 2 * workers else min(n_cases, math.ceil(4 * workers / n_designs))
    size = max(1, math.ceil(n_cases / max(pieces, 1)))
    return [(a, min(a + size, n_cases)) for a in range(0, n_cases, size)] or [(0, 0)]


def default_workers():
    """Cores this process may use."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:
        return os.cpu_count() or 1


def _run_pool(cfgs, plains, tasks, workers):
    """Outcomes of ``tasks`` (design, start, stop, with_yaml) on ``workers`` processes, in order.

    The pool is :func:`sim.api.processes.worker_pool` (its workers die with this process). On
    Linux the workers are forked (they start with the kernels warmed here and the configs,
    nothing pickled); elsewhere spawned (fork is unsafe on macOS, absent on Windows: they load
    the kernels from numba's on-disk cache, and the configs are pickled once per worker). A
    worker that dies fails the designs of its unfinished tasks.
    """
    outcomes = [None] * len(tasks)
    with worker_pool(workers, _init_worker, (cfgs, plains)) as pool:
        futures = {pool.submit(_run_in_worker, *task): i for i, task in enumerate(tasks)}
        for future in cf.as_completed(futures):
            try:
                outcomes[futures[future]] = future.result()
            except Exception as exc:   # BrokenProcessPool
                outcomes[futures[future]] = ("error", f"{type(exc).__name__}: {exc}")
    return outcomes


def _provenance_text(cfg, plain):
    """The YAML of a design that failed: resolved if it resolves, else as written."""
    return config_yaml(cfg, plain) if plain is not None else OmegaConf.to_yaml(cfg)


def simulate_batch(cfgs, workers=None):
    """Simulate many designs, each over the load cases of its own config, into one Dataset.

    Parameters
    ----------
    cfgs : sequence of omegaconf.DictConfig
        One composed config per design (``sim.load_config``); they may differ in any key
        (bearing, load grid, friction, solver, ...).
    workers : int, optional
        Processes; None: one per core this process may use; 1: everything in this process.
        Never more than there are tasks (whole designs, or parts of their load grids when
        there are fewer than two designs per worker). Before the workers start, one case of
        each kind of design runs here (:func:`_warm_up`), once per process.

    Returns
    -------
    xarray.Dataset
        dims ``design`` x ``case`` (DATA.md), laid out as :func:`sim.io.combine_designs`
        lays out the per-design :func:`simulate` results (:func:`sim.io.build_batch_dataset`:
        cases the union in order of first appearance, NaN and ``converged = False`` where a
        design lacks one), the resolved config of each design in ``design_config`` and every
        point without a valid result a row of the ``failed_*`` table (reason ``error`` or
        ``not converged``). A design that raises (impossible geometry, bad input, a worker
        that died) is recorded, not raised: its slot holds its config's geometry inputs, NaN
        and ``converged = False``.

    Notes
    -----
    Processes, not threads or numba ``prange``: the kernels release the GIL, but about 15 %
    of a combined case (continuation, the friction fixed point, the outputs) and all of a
    design's setup (config, models, YAML) is Python under the GIL, which caps two threads at
    about 1.7x; a ``prange`` over designs would need the whole case inside one kernel.
    """
    cfgs = list(cfgs)
    if not cfgs:
        raise InputError("simulate_batch needs at least one config")
    n = len(cfgs)
    plains, ops, failed = [None] * n, [[] for _ in range(n)], {}
    for d, cfg in enumerate(cfgs):
        try:
            plains[d] = resolved(cfg)
            ops[d] = operating_points(plains[d]["load"])
        except Exception as exc:
            failed[d] = f"{type(exc).__name__}: {exc}"
    workers = default_workers() if workers is None else max(1, int(workers))
    tasks = [(d, a, b, a == 0) for d in range(n) if d not in failed for a, b in _chunks(len(ops[d]), workers, n)]
    workers = min(workers, len(tasks))
    if workers <= 1:
        outcomes = [_run(cfgs[d], plains[d], a, b, with_yaml) for d, a, b, with_yaml in tasks]
    else:
        _warm_up(cfgs, plains, [None if d in failed else _kind(plains[d]) for d in range(n)])
        outcomes = _run_pool(cfgs, plains, tasks, workers)
    parts = {}
    for (d, *_), (status, out) in zip(tasks, outcomes):
        if status == "error":
            failed.setdefault(d, out)
        else:
            parts.setdefault(d, []).append(out)
    designs = []
    for d, cfg in enumerate(cfgs):
        if d in failed:
            bearing = (plains[d] or {}).get("bearing") or {}
            designs.append(DesignFailure(bearing, ops[d], _provenance_text(cfg, plains[d]), failed[d]))
        else:
            geometry, settings, _, text, optional = parts[d][0]
            designs.append(DesignResult(geometry, ops[d], [res for part in parts[d] for res in part[2]], text,
                                        settings, optional))
    return build_batch_dataset(designs)
