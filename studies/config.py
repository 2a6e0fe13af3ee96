"""Study configuration: composing ``conf/study/`` with the simulation config, and checking it.

The study group is not in ``conf/config.yaml``'s defaults list, so ``study=NAME`` on the
command line is composed as ``+study=NAME`` (``pinion`` when none is given). The study
chooses the bearings and the load case; any other override (``solver.n_slices=30``,
``lubricant.*``) is passed on to every simulation.
"""
import importlib.util
import math
from pathlib import Path

from hydra.errors import HydraException
from omegaconf import DictConfig, OmegaConf
from omegaconf.errors import OmegaConfBaseException

import sim
from sim.api import GeometryError, InputError, not_a_key
from studies.cycle import LOAD_KEYS, DutyCycle
from studies.space import DESIGN_PARAMETERS

SAMPLERS = ("tpe", "gp", "nsga2")
DESIGN_METHODS = ("sobol", "lhs")
MATERN_NU = (0.5, 1.5, 2.5, math.inf)
PARETO_OBJECTIVES = ("power_loss", "L10", "pmax")   # objectives of studies.pareto
CASE_KEYS = (*LOAD_KEYS, "share")   # keys of a study.duty_cycle entry
# |sum of the time shares - 1| allowed: shares are written with a few digits, and the float sum of m
# of them errs by ~m 1e-16, so 1e-9 refuses every real mistake and accepts every exact cycle
SHARE_SUM_TOLERANCE = 1e-9
#: allowed values of study.verify.solver: quasi_static (the search's own full simulations only) or
#: dynamic (the reported best also by the time-domain solver with skew and tilt free)
VERIFY_SOLVERS = ("quasi_static", "dynamic")
#: solver variants of a re-simulation (studies.verify): name -> (label, simulation overrides)
VARIANTS = {
    "quasi_static": ("quasi-static", []),
    "quasi_static_skew": ("quasi-static, skew", ["friction.skew.enabled=true"]),
    "dynamic": ("dynamic, skew and tilt free", ["friction.skew.enabled=true", "solver=dynamic"]),
}
DEFAULT_STUDY = "pinion"
OUTPUT_ROOT = Path("outputs") / "studies"


class StudyConfigError(ValueError):
    """Invalid study configuration; the message names the key, its value and the allowed range."""


def _study_in_defaults():
    defaults = OmegaConf.load(sim.CONF_DIR / "config.yaml").get("defaults", [])
    return any("study" in str(key) for d in defaults for key in (d.keys() if OmegaConf.is_dict(d) else [d]))


def study_overrides(overrides):
    """The user's overrides with the study group selected (``+study=`` unless config.yaml lists it)."""
    overrides = list(overrides or [])
    plus = "" if _study_in_defaults() else "+"
    chosen = [o for o in overrides if o.lstrip("+").startswith("study=")]
    rest = [o for o in overrides if o not in chosen]
    name = chosen[-1].split("=", 1)[1] if chosen else DEFAULT_STUDY
    return [f"{plus}study={name}", *rest]


def simulation_overrides(overrides):
    """Overrides passed on to the simulations: everything but the study's own keys.

    Raises
    ------
    StudyConfigError
        For overrides of what the study sets itself: the bearings, the load case and the
        choice of lubricant (``lubricant.*`` values may be overridden).
    """
    out = []
    for o in overrides or []:
        key = o.lstrip("+~").split("=", 1)[0]
        group = key.split(".", 1)[0]
        if group == "study":
            continue
        if group in ("bearing", "load") or key == "lubricant":
            raise StudyConfigError(f"{key} = {o.split('=', 1)[-1]!r} cannot be overridden here: the study sets the "
                                   f"bearings (study.bearing, study.reference_trb, study.thesis_design), the "
                                   f"lubricant (study.lubricant) and the load case (study.load.*)")
        out.append(o)
    return out


def for_solver(overrides):
    """``overrides`` without ``solver.dynamic.*`` keys unless they select ``solver=dynamic``: those
    keys set the dynamic re-simulation of ``study.verify`` only (other configs have no such node)."""
    if VARIANTS["dynamic"][1][-1] in overrides:
        return list(overrides)
    return [o for o in overrides if not o.lstrip("+~").startswith("solver.dynamic.")]


def _composed(overrides):
    """``sim.load_config(overrides)``; a composition error (unknown key, bad override syntax, missing
    config) is a StudyConfigError with Hydra's message on one line."""
    try:
        return sim.load_config(overrides)
    except (HydraException, OmegaConfBaseException) as err:
        cause = f" ({' '.join(str(err.__cause__).split())})" if err.__cause__ else ""
        raise StudyConfigError(" ".join(str(err).split()) + cause) from err


def compose(overrides=None):
    """Root config (simulation groups + ``study``) from command-line style overrides; validated,
    the simulations of the study's bearings at its load case included (:func:`check_simulations`),
    before anything is written."""
    simulation_overrides(overrides)
    _check_study_keys(overrides)
    cfg = _composed(for_solver(study_overrides(overrides)))
    validate(cfg.study)
    check_simulations(cfg.study, overrides)
    return cfg


def _check_study_keys(overrides):
    """Each ``study.*`` key set or added (``+``) on the command line must be a key of the selected
    study config: Hydra refused an unknown one in its own words, and with ``+``, as its message
    advised, the study ran with the key ignored (``+study.refine.maxsims=3``: session 32, an
    independent check). ``study.bounds.<name>`` is a mapping of design parameters that
    :func:`validate` checks; below a list (``duty_cycle[0].Fa``) DutyCycle checks the keys.

    Raises
    ------
    StudyConfigError
        ``study.refine.maxsims is not a config key (did you mean study.refine.max_simulations?)``.
    """
    keys = [o.lstrip("+").split("=", 1)[0] for o in overrides or []
            if "=" in o and o.lstrip("+").startswith("study.")]
    if not keys:
        return
    base = _composed(for_solver(study_overrides([o for o in overrides if not o.lstrip("+").startswith("study.")])))
    for key in keys:
        node, path = base.study, "study"
        for part in key.split(".")[1:]:
            name = part.split("[", 1)[0]
            if path == "study.bounds" or not isinstance(node, DictConfig):
                break
            if name not in node:
                raise StudyConfigError(not_a_key(path, name, list(node.keys())))
            node, path = node[name], f"{path}.{name}"
            if name != part:      # an item of a list
                break


def simulation_arguments(study, bearing, overrides=None, settings=()):
    """The command-line arguments of the study's simulations of ``bearing`` (a conf/bearing name): the
    bearing, the study's lubricant, ``settings`` (e.g. a design's values and a load case) and the
    overrides passed on to simulations (``solver.dynamic.*`` only with ``solver=dynamic``)."""
    return [f"bearing={bearing}", f"lubricant={study.lubricant}", *settings,
            *for_solver(simulation_overrides(overrides))]


def simulation_config(study, bearing, overrides=None, case=None):
    """Composed simulation config of ``bearing`` (a conf/bearing name) at the load case ``case``
    (a dict of LOAD_KEYS, a case of studies.cycle.DutyCycle; default: ``study.load``), from
    :func:`simulation_arguments`."""
    cfg = _composed(simulation_arguments(study, bearing, overrides))
    for key in LOAD_KEYS:
        cfg.load[key] = float((study.load if case is None else case)[key])
    return cfg


def load_key(study, k, key):
    """The study key that sets load quantity ``key`` of case k: ``duty_cycle[k].key`` where the
    cycle's entry sets it, else ``load.key``."""
    cycle = study.get("duty_cycle")
    return f"duty_cycle[{k}].{key}" if cycle and key in cycle[k] else f"load.{key}"


def check_simulations(study, overrides=None):
    """Check the simulation of each bearing of the study (its design template, the reference TRB,
    the thesis design) at each load case of its duty cycle as a run checks its input, without
    computing (:func:`sim.api.sweep.preflight`: schema ranges, geometry, friction inputs).

    Raises
    ------
    StudyConfigError
        Naming each problem; a load value is named as the study key that sets it
        (``study.load.Fa = -5.0 is outside the allowed range: ...``, or
        ``study.duty_cycle[2].Fa = ...``).
    """
    from sim.api.sweep import preflight

    dynamic = study.verify.solver == "dynamic"
    for k, case in enumerate(DutyCycle.from_config(study).cases):
        for role in dict.fromkeys(("bearing", "reference_trb", "thesis_design")):
            name = study[role]
            try:
                preflight(simulation_config(study, name, overrides, case))
                if dynamic and role == "bearing":   # the best design's dynamic re-simulation (studies.verify)
                    cfg = simulation_config(study, name, [*VARIANTS["dynamic"][1], *(overrides or [])], case)
                    _require(bool(cfg.friction.enabled), "verify.solver", study.verify.solver,
                             "quasi_static when friction.enabled = false: the dynamic solver's rollers and cage are "
                             "driven by the raceway traction")
                    preflight(cfg)
            except (InputError, GeometryError) as err:
                lines = [_named_load_line(study, k, line) if line.startswith("load.")
                         else f"{line} (in the simulation of study.{role} = {name!r})"
                         for line in str(err).splitlines() if line.strip()]
                raise StudyConfigError("\n".join(lines)) from err
    _check_bounds_in_schema(study, overrides)


def _check_bounds_in_schema(study, overrides):
    """Each end of each free parameter's ``study.bounds`` set in the template bearing and checked
    against the bearing schema (:func:`sim.api.schema.validate`: kappa in (0, 1), alpha in (0, 60)
    deg, ...): a bound outside it would otherwise stop the study at the first sampled design beyond
    it, after simulations ran. Combined feasibility (a roller that does not fit) stays a failed
    design, as for any point (:mod:`sim.geometry`)."""
    from sim.api.schema import validate as validate_simulation

    template = simulation_config(study, study.bearing, overrides)
    for name in study.free:
        bounds = [float(b) for b in study.bounds[name]]
        for end, value in zip(("lower", "upper"), bounds):
            cfg = template.copy()
            cfg.bearing[name] = value
            try:
                validate_simulation(cfg)
            except InputError as err:
                lines = [line for line in str(err).splitlines() if line.startswith(f"bearing.{name} ")]
                raise StudyConfigError(f"study.bounds.{name} = {bounds}: its {end} end "
                                       + (lines[0] if lines else str(err))) from err


def _named_load_line(study, k, line):
    """A simulation's message on ``load.KEY ...`` with the study key of case k that sets KEY."""
    key, space, rest = line[len("load."):].partition(" ")
    return f"study.{load_key(study, k, key)}{space}{rest}"


def output_dir(study):
    """Folder of a study's files: ``outputs/studies/<name>/`` (relative to the working directory)."""
    return OUTPUT_ROOT / str(study.name)


def storage_spec(study, out_dir):
    """Storage of the Optuna studies: ``study.storage`` or ``sqlite:///<out_dir>/study.db``."""
    return str(study.storage) if study.storage is not None else f"sqlite:///{Path(out_dir) / 'study.db'}"


# ---------------------------------------------------------------------------- validation
def _require(ok, key, value, allowed):
    if not ok:
        raise StudyConfigError(f"study.{key} = {value!r} is outside the allowed range: {allowed}")


def _is_number(v):
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def _is_int(v, low):
    return isinstance(v, int) and not isinstance(v, bool) and v >= low


def validate(study):
    """Check every study key at start; raise :class:`StudyConfigError` naming key, value and range."""
    s = OmegaConf.to_container(study, resolve=True)
    _require(isinstance(s.get("name"), str) and s["name"].strip() != "" and "/" not in s["name"],
             "name", s.get("name"), "a non-empty folder name")
    _require(isinstance(s.get("objective"), str) and s["objective"] != "", "objective", s.get("objective"),
             "a result variable name (DATA.md), e.g. torque or pmax")
    _require(s.get("sampler") in SAMPLERS, "sampler", s.get("sampler"), f"one of {list(SAMPLERS)}")
    if s["sampler"] == "gp":
        _require(importlib.util.find_spec("torch") is not None, "sampler", s["sampler"],
                 "gp needs PyTorch (pip install torch==2.13.0, the CPU build on this machine's disk); "
                 "or use tpe / nsga2")
    free = s.get("free")
    _require(isinstance(free, list) and len(free) > 0 and len(set(free)) == len(free)
             and set(free) <= set(DESIGN_PARAMETERS), "free", free,
             f"a non-empty list of distinct names from {list(DESIGN_PARAMETERS)}")
    for name, b in s.get("bounds", {}).items():
        _require(name in DESIGN_PARAMETERS, f"bounds.{name}", b,
                 f"bounds of the design parameters {list(DESIGN_PARAMETERS)} only (a typo would bound nothing)")
    for name in free:
        b = s.get("bounds", {}).get(name)
        _require(isinstance(b, list) and len(b) == 2 and all(map(_is_number, b)) and b[0] < b[1],
                 f"bounds.{name}", b, "[low, high], finite numbers with low < high")
    _require(_is_int(s.get("seed"), 0), "seed", s.get("seed"), "an integer >= 0")
    _require(s.get("storage") is None or (isinstance(s["storage"], str) and
                                          ("://" in s["storage"] or s["storage"].startswith("journal:"))),
             "storage", s.get("storage"), "null (SQLite under outputs/), an RDB URL or journal:<path>")
    _require(_is_int(s.get("n_jobs"), 1), "n_jobs", s.get("n_jobs"), "an integer >= 1")
    w = s.get("workers", {})
    _require(_is_int(w.get("heartbeat_interval"), 1), "workers.heartbeat_interval", w.get("heartbeat_interval"),
             "an integer >= 1 [s] (Optuna's RDBStorage takes whole seconds)")
    _require(_is_int(w.get("grace_period"), 1) and w["grace_period"] > w["heartbeat_interval"],
             "workers.grace_period", w.get("grace_period"),
             f"an integer > workers.heartbeat_interval = {w['heartbeat_interval']} [s]")
    _require(_is_int(w.get("max_retry"), 0), "workers.max_retry", w.get("max_retry"), "an integer >= 0")
    _require(_is_number(w.get("poll_interval")) and w["poll_interval"] > 0, "workers.poll_interval",
             w.get("poll_interval"), "a number > 0 [s]")
    ss = s.get("sampler_settings", {})
    _require(_is_int(ss.get("n_startup_trials"), 0), "sampler_settings.n_startup_trials",
             ss.get("n_startup_trials"), "an integer >= 0")
    _require(_is_int(ss.get("population_size"), 2), "sampler_settings.population_size",
             ss.get("population_size"), "an integer >= 2")
    d = s.get("initial_design", {})
    _require(d.get("method") in DESIGN_METHODS, "initial_design.method", d.get("method"), f"one of {list(DESIGN_METHODS)}")
    sur = s.get("surrogate", {})
    _require(_is_int(sur.get("cv_folds"), 2), "surrogate.cv_folds", sur.get("cv_folds"), "an integer >= 2")
    _require(_is_int(d.get("n"), max(2, sur["cv_folds"])), "initial_design.n", d.get("n"),
             f"an integer >= {max(2, sur['cv_folds'])} (at least surrogate.cv_folds points)")
    include = d.get("include", [])
    _require(isinstance(include, list), "initial_design.include", include, "a list of designs (name: value mappings)")
    for k, point in enumerate(include):
        _require(isinstance(point, dict) and set(free) <= set(point) and set(point) <= set(DESIGN_PARAMETERS),
                 f"initial_design.include[{k}]", point,
                 f"a mapping with a value for every free parameter {free} (others of {list(DESIGN_PARAMETERS)} "
                 "are allowed and ignored, so one design serves several free sets)")
        for name in free:
            lo, hi = s["bounds"][name]
            _require(_is_number(point[name]) and lo <= point[name] <= hi, f"initial_design.include[{k}].{name}",
                     point[name], f"a number in study.bounds.{name} = [{lo}, {hi}]")
    b = s.get("budget", {})
    _require(_is_int(b.get("max_simulations"), d["n"]), "budget.max_simulations", b.get("max_simulations"),
             f"an integer >= initial_design.n = {d['n']}")
    for key in ("verify_per_round", "patience"):
        _require(_is_int(b.get(key), 1), f"budget.{key}", b.get(key), "an integer >= 1")
    _require(_is_number(b.get("min_improvement")) and b["min_improvement"] >= 0.0, "budget.min_improvement",
             b.get("min_improvement"), "a number >= 0")
    _require(_is_number(b.get("dedup_distance")) and 0.0 <= b["dedup_distance"] < 1.0, "budget.dedup_distance",
             b.get("dedup_distance"), "a number in [0, 1)")
    a = s.get("acquisition", {})
    _require(_is_int(a.get("n_global"), 1), "acquisition.n_global", a.get("n_global"), "an integer >= 1")
    _require(_is_int(a.get("n_local"), 0), "acquisition.n_local", a.get("n_local"), "an integer >= 0")
    scales = a.get("local_scales")
    _require(isinstance(scales, list) and len(scales) > 0 and all(_is_number(v) and 0.0 < v <= 1.0 for v in scales),
             "acquisition.local_scales", scales, "a non-empty list of numbers in (0, 1] (unit-cube coordinates)")
    _require(_is_int(a.get("n_centres"), 1), "acquisition.n_centres", a.get("n_centres"), "an integer >= 1")
    _require(_is_int(a.get("n_polish"), 0), "acquisition.n_polish", a.get("n_polish"), "an integer >= 0 (0: no polish)")
    _require(_is_int(a.get("polish_iterations"), 1), "acquisition.polish_iterations", a.get("polish_iterations"),
             "an integer >= 1")
    _require(_is_number(a.get("batch_distance")) and 0.0 <= a["batch_distance"] < 1.0, "acquisition.batch_distance",
             a.get("batch_distance"), "a number in [0, 1) (unit-cube coordinates; 0: none)")
    _require(a.get("n_diverse") is None or _is_int(a.get("n_diverse"), 0), "acquisition.n_diverse", a.get("n_diverse"),
             "null (every design of a batch) or an integer >= 0")
    rf = s.get("refine", {})
    # COBYLA (scipy) builds its first linear models on a simplex of d + 1 points and takes at least one step
    # from it: a smaller budget would be overrun by that floor (studies.refine.local_refine, n_min)
    _require(_is_int(rf.get("max_simulations"), 0) and (rf["max_simulations"] == 0 or rf["max_simulations"] >= len(free) + 2),
             "refine.max_simulations", rf.get("max_simulations"),
             f"0 (no local stage) or an integer >= {len(free) + 2} (len(free) + 2: COBYLA's first simplex of "
             f"{len(free) + 1} points and one step)")
    for key in ("initial_step", "final_step"):
        _require(_is_number(rf.get(key)) and 0.0 < rf[key] <= 1.0, f"refine.{key}", rf.get(key),
                 "a number in (0, 1] (unit-cube coordinates)")
    _require(rf["final_step"] <= rf["initial_step"], "refine.final_step", rf["final_step"],
             f"<= refine.initial_step = {rf['initial_step']}")
    _require(_is_number(rf.get("active_tolerance")) and 0.0 <= rf["active_tolerance"] < 0.5,
             "refine.active_tolerance", rf.get("active_tolerance"), "a number in [0, 0.5)")
    _require(_is_int(rf.get("restarts"), 0), "refine.restarts", rf.get("restarts"), "an integer >= 0")
    _require(_is_int(rf.get("starts"), 1), "refine.starts", rf.get("starts"), "an integer >= 1")
    _require(_is_number(rf.get("start_distance")) and 0.0 <= rf["start_distance"] <= 1.0, "refine.start_distance",
             rf.get("start_distance"), "a number in [0, 1] (unit-cube coordinates)")
    _require(_is_int(rf.get("start_simulations"), 1), "refine.start_simulations", rf.get("start_simulations"),
             "an integer >= 1")
    _require(_is_number(rf.get("restart_shrink")) and 0.0 < rf["restart_shrink"] <= 1.0, "refine.restart_shrink",
             rf.get("restart_shrink"), "a number in (0, 1]")
    _require(_is_number(rf.get("constraint_backoff")) and 0.0 <= rf["constraint_backoff"] < 0.1,
             "refine.constraint_backoff", rf.get("constraint_backoff"), "a number in [0, 0.1) (normalised margin)")
    c = s.get("constraints", {})
    _require(_is_number(c.get("axial_displacement_max")) and c["axial_displacement_max"] > 0.0,
             "constraints.axial_displacement_max", c.get("axial_displacement_max"), "a number > 0 [mm]")
    for key, unit in (("pmax_max", "MPa"), ("L10_min", "1e6 rev")):
        v = c.get(key)
        _require(v == "trb" or (_is_number(v) and v > 0.0), f"constraints.{key}", v,
                 f"'trb' (the reference TRB at the same load) or a number > 0 [{unit}]")
    _require(isinstance(c.get("edge_stress"), bool), "constraints.edge_stress", c.get("edge_stress"), "true or false")
    _require(_is_number(c.get("PCR_over_Lwe_max")) and c["PCR_over_Lwe_max"] > 0.0,
             "constraints.PCR_over_Lwe_max", c.get("PCR_over_Lwe_max"), "a number > 0")
    _require(sur.get("nu") in MATERN_NU, "surrogate.nu", sur.get("nu"), f"one of {list(MATERN_NU)}")
    for key in ("length_scale_bounds", "constant_value_bounds", "noise_level_bounds"):
        v = sur.get(key)
        _require(isinstance(v, list) and len(v) == 2 and all(map(_is_number, v)) and 0.0 < v[0] < v[1],
                 f"surrogate.{key}", v, "[low, high] with 0 < low < high")
    _require(_is_int(sur.get("n_restarts_optimizer"), 0), "surrogate.n_restarts_optimizer",
             sur.get("n_restarts_optimizer"), "an integer >= 0")
    _require(isinstance(sur.get("calibrate"), bool), "surrogate.calibrate", sur.get("calibrate"), "true or false")
    _require(_is_number(sur.get("interval")) and 0.0 < sur["interval"] < 1.0, "surrogate.interval",
             sur.get("interval"), "a probability in (0, 1)")
    _require(isinstance(sur.get("log_outputs"), list), "surrogate.log_outputs", sur.get("log_outputs"),
             "a list of result names modelled as ln(y)")
    pa = s.get("pareto", {})
    _require(_is_int(pa.get("trials"), 1), "pareto.trials", pa.get("trials"), "an integer >= 1")
    _require(_is_int(pa.get("levels"), 0), "pareto.levels", pa.get("levels"), "an integer >= 0")
    fronts = pa.get("fronts")
    _require(isinstance(fronts, list) and len(fronts) > 0 and all(
        isinstance(f, list) and len(f) == 2 and f[0] != f[1] and set(f) <= set(PARETO_OBJECTIVES) for f in fronts),
        "pareto.fronts", fronts, f"a non-empty list of pairs of distinct names from {list(PARETO_OBJECTIVES)}")
    load = s.get("load", {})
    for key in LOAD_KEYS:
        _require(_is_number(load.get(key)), f"load.{key}", load.get(key), "a finite number (checked by the simulation)")
    _validate_duty_cycle(s.get("duty_cycle"))
    verify = s.get("verify") or {}
    _require(verify.get("solver") in VERIFY_SOLVERS, "verify.solver", verify.get("solver"),
             f"one of {list(VERIFY_SOLVERS)} (dynamic: the reported best also by the time-domain solver)")
    for key, group in (("bearing", "bearing"), ("reference_trb", "bearing"), ("thesis_design", "bearing"),
                       ("lubricant", "lubricant")):
        v = s.get(key)
        _require(isinstance(v, str) and (sim.CONF_DIR / group / f"{v}.yaml").is_file(), key, v,
                 f"a config of conf/{group}/: {sorted(p.stem for p in (sim.CONF_DIR / group).glob('*.yaml'))}")
    return study


def _validate_duty_cycle(cycle):
    """``study.duty_cycle``: null, or a non-empty list of cases {Fa, Fr, speed, share} (tilt and
    oil_temperature optional) with shares in (0, 1] summing to 1 and speeds > 0 (the cycle's
    equivalent load weighs each case by its revolutions, studies.cycle.equivalent_load); the
    load values' own ranges are checked by the simulation (:func:`check_simulations`)."""
    if cycle is None:
        return
    _require(isinstance(cycle, list) and len(cycle) > 0, "duty_cycle", cycle,
             "null (one case: study.load) or a non-empty list of {Fa, Fr, speed, share}")
    for k, entry in enumerate(cycle):
        _require(isinstance(entry, dict) and {"Fa", "Fr", "speed", "share"} <= set(entry) and set(entry) <= set(CASE_KEYS),
                 f"duty_cycle[{k}]", entry, f"a mapping with Fa, Fr, speed, share and optionally tilt, oil_temperature "
                                            f"(keys from {list(CASE_KEYS)})")
        for key in entry:
            _require(_is_number(entry[key]), f"duty_cycle[{k}].{key}", entry[key], "a finite number")
        _require(entry["speed"] > 0.0, f"duty_cycle[{k}].speed", entry["speed"],
                 "a number > 0 [rpm] (the cycle's equivalent load weighs cases by revolutions)")
        _require(0.0 < entry["share"] <= 1.0, f"duty_cycle[{k}].share", entry["share"], "a time share in (0, 1]")
    total = math.fsum(e["share"] for e in cycle)
    _require(abs(total - 1.0) <= SHARE_SUM_TOLERANCE, "duty_cycle[*].share", [e["share"] for e in cycle],
             f"time shares summing to 1 (+- {SHARE_SUM_TOLERANCE:g}); they sum to {total!r}")
