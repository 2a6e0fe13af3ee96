"""Surrogate-assisted design search with verification by the full simulation (issues 5 and 16).

1. Space-filling design (Sobol / Latin hypercube) of full simulations -> ``training.nc``.
2. Round r: GP surrogates fitted to every simulation so far (``surrogates/round_rrr/``): one
   regression GP per modelled output (objective and constrained quantities, calibrated
   intervals, surrogate.gp) and a GP classifier of the simulations that gave a result
   (surrogate.classifier). Constrained Bayesian optimisation (surrogate.acquisition) picks
   ``budget.verify_per_round`` = q designs: log expected improvement times the probability of
   every constraint times the probability of success, maximised over a dense candidate set
   (``study.acquisition``), a kriging-believer batch of distinct designs. They are run with the
   full simulation and added to ``training.nc``.
3. Stop when the verified best has not improved for ``budget.patience`` rounds, when the
   simulation budget is spent, or when no new candidate is left.
4. Final local stage on the full simulation (:mod:`studies.refine`, ``study.refine``): COBYLA
   under every constraint from the verified best and the next best distinct verified designs
   (``refine.starts``, screening runs of ``refine.start_simulations``), then restarted from the
   best point of all; its points stored as source ``refinement`` (round -1) and outside the
   loop's budget and rounds.

Duty cycle (``study.duty_cycle``, :mod:`studies.cycle`, issue 16 item 5): every design is
simulated at every load case (results on ``(design, case)``); the objective is the time-weighted
mean over the cases, the constraints hold at every case (:mod:`studies.constraints`), and one
set of constraint surrogates is fitted per case beside one GP of the cycle objective
(``<output>_case<k>``; benchmarks/bench_duty_layout.py measured this layout against one GP over
design x case). A one-case study is the one-case cycle, with the names and numbers it had.

Everything lives under the study's folder, so running the same command again resumes where it
stopped: a round's surrogates are loaded from their folder and its proposal is deterministic
(seeded by the study seed and the round), so a round killed while simulating proposes the same
designs again; changed result-defining settings are refused.
"""
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import xarray as xr
from omegaconf import OmegaConf

from sim.api import Geometry, GeometryError
from sim.io import write_netcdf_atomic
from studies.config import StudyConfigError, output_dir, simulation_config
from studies.constraints import FAILED, SIMULATION_MARGIN, Limits, exact_margin, margins, rank_key
from studies.cycle import DutyCycle, summary_values
from studies.evaluate import (EDGE_MARGIN, RECORDED, STATUS, STATUS_NAMES, case_values, design_matrix, evaluate_design,
                              evaluate_designs, points_dataset, simulate_point, table_from_file, table_to_file,
                              worst_status)
from studies.refine import SOURCE as REFINEMENT, distinct_starts, local_refine
from studies.search import complete_trials
from studies.space import DesignSpace
from surrogate import (CandidateSettings, Constraint, GPSettings, GPSurrogate, SuccessClassifier, load_surrogates,
                       propose, save_surrogates, saved_set)

SUCCESS = "success"      # the classifier of simulations that gave a result, in a round's surrogate set
CONSTRAINED = ("pmax", "axial_displacement", "C_eff")   # per-case outputs with a surrogate (and EDGE_MARGIN)
# study keys that do not change results: a study may be resumed with other values
RESUMABLE_KEYS = ("budget", "n_jobs", "storage", "name", "workers", "refine")
REFINEMENT_ROUND = -1    # ``round`` of the final local stage's points
# Initial-design points simulated per worker between two writes of training.nc: a kill loses at
# most this many per worker, and the per-call cost of the pool (forked workers) stays small
# against that many simulations (50-500 ms each), engineering choice.
INITIAL_CHUNK_PER_JOB = 4


def changed_keys(stored, wanted, prefix=""):
    """`` (changed: study.seed 7 -> 8; ...)`` between two YAML configs (``config_attrs``, both written by
    OmegaConf), dotted keys with ``prefix``; "" when they hold the same values."""
    def flat(node, path=""):
        if isinstance(node, dict):
            out = {}
            for k, v in node.items():
                out.update(flat(v, f"{path}{k}."))
            return out
        return {path[:-1]: node}

    old, new = (flat(OmegaConf.to_container(OmegaConf.create(t or ""))) for t in (stored, wanted))
    diff = [f"{prefix}{k} {old.get(k, '(none)')} -> {new.get(k, '(none)')}" for k in sorted(set(old) | set(new))
            if old.get(k) != new.get(k)]
    return f" (changed: {'; '.join(diff)})" if diff else ""


@dataclass
class Reference:
    """A reference bearing simulated at every load case of the study's duty cycle."""

    label: str
    bearing: str
    cfgs: list       # the composed simulation config of each case
    datasets: list   # the full result of each case (None where it failed)
    records: list    # studies.evaluate.simulate_point's record of each case
    record: dict     # the cycle's record: status, message, wall_time and summary values (DesignSearch.summary)

    @property
    def cfg(self):
        """The config of the first case (bearing, lubricant, solver: the same at every case)."""
        return self.cfgs[0]

    @property
    def ds(self):
        """The full result of the first case."""
        return self.datasets[0]


def round_seed(seed, *indices):
    """Independent integer seed for (round, trial) from the study seed (numpy SeedSequence)."""
    return int(np.random.SeedSequence([seed, *indices]).generate_state(1)[0])


def improved(before, after, min_improvement):
    """Whether rank key ``after`` improves on ``before`` by more than the relative ``min_improvement``."""
    if before is None:
        return after is not None
    if after[0] != before[0]:
        return after[0] < before[0]
    return after[1] < before[1] - min_improvement * abs(before[1])


class DesignSearch:
    """One design search: references, training data, rounds, verified results.

    Parameters
    ----------
    root_cfg : omegaconf.DictConfig
        Composed config with the ``study`` node (:func:`studies.config.compose`).
    overrides : sequence of str
        The command-line overrides (passed on to every simulation config).
    out_dir : path, optional
        Study folder; default ``outputs/studies/<name>``.
    log : callable
        Progress printer (one line per stage).
    """

    def __init__(self, root_cfg, overrides=(), out_dir=None, log=print):
        self.study = s = root_cfg.study
        self.overrides = list(overrides)
        self.out = Path(out_dir) if out_dir is not None else output_dir(s)
        self.log = log
        self.cycle = DutyCycle.from_config(s)
        # the template design at each case of the duty cycle; the first holds what all share (bearing, solver, ...)
        self.case_cfgs = [simulation_config(s, s.bearing, self.overrides, case) for case in self.cycle.cases]
        self.base_cfg = self.case_cfgs[0]
        self.space = DesignSpace.from_config(s, self.base_cfg.bearing)
        self.objective = str(s.objective)
        self.quantities = tuple(dict.fromkeys((self.objective, *RECORDED)))
        self.settings = GPSettings.from_config(s.surrogate, s.seed)
        self.references = {}
        self.limits = None
        # plain copies for the geometry check of every surrogate trial (an OmegaConf copy costs 16 ms)
        self._bearing = OmegaConf.to_container(self.base_cfg.bearing, resolve=True)
        self._material = OmegaConf.to_container(self.base_cfg.material, resolve=True)
        self._n_slices = int(self.base_cfg.solver.n_slices)
        self.local = None        # studies.refine.LocalResult of the final local stage, once run
        self._refined = None     # the local stage's points, kept apart from the loop's (training.nc holds both)

    def require_one_case(self, command):
        """Refuse a duty cycle of several cases in a command that runs one load case.

        Raises
        ------
        StudyConfigError
            Naming study.duty_cycle and the command that takes it (studies.optimize).
        """
        if len(self.cycle) > 1:
            raise StudyConfigError(f"study.duty_cycle has {len(self.cycle)} load cases: {command} runs one load case "
                                   f"(study.load, study.duty_cycle null); a duty cycle runs with python -m studies.optimize")

    # ------------------------------------------------------------------ references and limits
    def run_references(self):
        """Simulate the reference TRB and the thesis design at every case; set the constraint limits."""
        for label, name in (("reference TRB", self.study.reference_trb), ("thesis design", self.study.thesis_design)):
            cfgs = [simulation_config(self.study, name, self.overrides, case) for case in self.cycle.cases]
            try:
                runs = [simulate_point(cfg, self.quantities) for cfg in cfgs]
            except KeyError as err:
                raise StudyConfigError(f"study.objective = {self.objective!r} (or a constraint quantity) is not a "
                                       f"result of the simulation: {err.args[0]}") from err
            records = [r for _, r in runs]
            self.references[label] = Reference(label, str(name), cfgs, [d for d, _ in runs], records,
                                               self.summary(records))
        trb = self.references["reference TRB"].records
        self.limits = Limits.from_config(self.study, [r["values"] for r in trb], float(self.base_cfg.bearing.Lwe),
                                         self.cycle)
        return self.references

    def summary(self, records):
        """One record for a design's per-case ``records``: status (studies.evaluate.worst_status),
        the messages of the cases without result (named by case when the cycle has several), the
        total wall time, the first case's attrs and the cycle's values (studies.cycle.summary_values)."""
        several = len(records) > 1
        message = "; ".join(f"{self.cycle.label(k)}: {r['message']}" if several else r["message"]
                            for k, r in enumerate(records) if r["message"])
        return {"status": worst_status([r["status"] for r in records]), "message": message,
                "values": summary_values(case_values(records), self.cycle, self.objective),
                "attrs": next((r["attrs"] for r in records if r["attrs"]), {}),
                "wall_time": float(sum(r["wall_time"] for r in records))}

    # ------------------------------------------------------------------ training data
    def config_attrs(self):
        """The result-defining configuration: ``study_config`` (without RESUMABLE_KEYS) and
        ``simulation_config``, as YAML text."""
        study = {k: v for k, v in OmegaConf.to_container(self.study, resolve=True).items() if k not in RESUMABLE_KEYS}
        return {"study_config": OmegaConf.to_yaml(OmegaConf.create(study)),
                "simulation_config": OmegaConf.to_yaml(self.base_cfg, resolve=True)}

    def attrs(self):
        """Dataset attributes: provenance of the simulation and the result-defining study config."""
        ref = next(iter(self.references.values())).ds
        prov = {k: ref.attrs[k] for k in ("package_version", "git_commit", "model_fingerprint", "solver",
                                          "solver_settings", "sources")
                if ref is not None and k in ref.attrs}
        return {"Conventions": "CF-1.10", "title": f"design search {self.study.name}: full simulations",
                **prov, **self.config_attrs()}

    @property
    def training_path(self):
        return self.out / "training.nc"

    def load_training(self):
        """The training data on disk (None if none); refuses data of another configuration."""
        if not self.training_path.exists():
            return None
        return self.own_points(self.training_path, "use another study.name or delete")

    def own_points(self, path, advice):
        """The per-point table stored at ``path``; refuses one made with another result-defining
        configuration or by another version of the simulation code (the SHA-256 of ``sim/``,
        ``model_fingerprint``: its points would mix with new ones computed by other physics)
        (``advice``: what to do, followed by the folder to delete)."""
        ds = table_from_file(xr.load_dataset(path))
        want = self.attrs()
        for key in ("study_config", "simulation_config", "model_fingerprint"):
            if ds.attrs.get(key) != want.get(key):
                what = ("version of the simulation code (sim/ sources)" if key == "model_fingerprint"
                        else key.replace("_", " ") + changed_keys(ds.attrs.get(key), want.get(key),
                                                                  "study." if key == "study_config" else ""))
                raise StudyConfigError(f"{path} was made with another {what}; {advice} {Path(path).parent} to start "
                                       "afresh")
        return ds

    def save_training(self, ds):
        """Write the loop's points ``ds`` and the local stage's (:meth:`refine`) to training.nc."""
        if self._refined is not None and self._refined.sizes["design"]:
            ds = xr.concat([ds, self._refined], dim="design", combine_attrs="override", data_vars="all")
        write_netcdf_atomic(table_to_file(ds), self.training_path)

    def simulate(self, X, source, round_index):
        """Full simulations of the rows of X at every case of the duty cycle -> points dataset."""
        points = [self.space.bearing_values(x) for x in X]
        records = evaluate_designs(self.case_cfgs, points, self.quantities, int(self.study.n_jobs))
        return points_dataset(self.space, X, records, source, round_index, self.attrs(), self.cycle)

    def initial_points(self):
        """The initial design: the designs of ``initial_design.include`` (known ones, e.g. an optimum
        to start from), then the space-filling sequence of ``initial_design.n`` points."""
        d = self.study.initial_design
        sample = self.space.sample(int(d.n), str(d.method), int(self.study.seed))
        return np.vstack([self.space.include(d.get("include", [])), sample])

    def initial_design(self):
        """Load the training data, or simulate the space-filling design and save it.

        The design is simulated in chunks of :data:`INITIAL_CHUNK_PER_JOB` points per worker and
        training.nc is rewritten after each chunk, so a killed run loses at most one chunk; a
        rerun continues with the rest of the same (seeded) sequence (issue 16 item 8).
        """
        ds = self.load_training()
        X = self.initial_points()
        if ds is not None:
            self.log(f"resuming from {self.training_path}: {ds.sizes['design']} simulations")
            local = ds.source.values == REFINEMENT
            self._refined = ds.isel(design=np.flatnonzero(local))
            ds = ds.isel(design=np.flatnonzero(~local))
            done = int(np.sum(ds.source.values == "initial"))
            if done >= len(X):
                return ds
            if not np.array_equal(design_matrix(ds.isel(design=slice(0, done)), self.space), X[:done]):
                raise StudyConfigError(f"{self.training_path} holds an initial design that is not this study's "
                                       f"sequence; use another study.name or delete {self.out} to start afresh")
        else:
            done = 0
        t0 = time.perf_counter()
        chunk = INITIAL_CHUNK_PER_JOB * int(self.study.n_jobs)
        for start in range(done, len(X), chunk):
            part = self.simulate(X[start:start + chunk], "initial", 0)
            ds = part if ds is None else xr.concat([ds, part], dim="design", combine_attrs="override", data_vars="all")
            self.save_training(ds)
            self.log(f"initial design: {ds.sizes['design']} of {len(X)} simulated")
        counts = {k: int((ds.status == v).sum()) for k, v in STATUS.items()}
        self.log(f"initial design: {self.count(len(X) - done, str(self.study.initial_design.method))} in "
                 f"{time.perf_counter() - t0:.1f} s {counts}")
        return ds

    def count(self, n, kind=""):
        """'n [kind] simulations', or in a duty cycle 'n [kind] designs x m cases' (for the log)."""
        kind = f"{kind} " if kind else ""
        return f"{n} {kind}simulations" if len(self.cycle) == 1 else f"{n} {kind}designs x {len(self.cycle)} cases"

    # ------------------------------------------------------------------ judging simulated points
    def objective_values(self, ds):
        """The cycle objective (n,) of simulated points: the time-weighted mean of the per-case
        objective (studies.cycle.DutyCycle.weighted; one case: its value); NaN without result."""
        return self.cycle.weighted(ds[self.objective].transpose("design", "case").values)

    def point_margins(self, ds):
        """Constraint margins (n, m) of simulated points, from their results at every case."""
        out = []
        for i in range(ds.sizes["design"]):
            p = ds.isel(design=i)
            values = {k: p[k].values for k in ("pmax", "axial_displacement", "C_eff", EDGE_MARGIN)}
            bearing = {k: float(p[k]) for k in ("PCR", "ratings_alpha")}
            out.append(margins(values, bearing, self.limits, 0.0 if int(p.status) == STATUS["ok"] else FAILED))
        return np.array(out).reshape(len(out), len(self.limits.names))

    def ranked(self, ds):
        """Indices of the simulated points, best first (:func:`studies.constraints.rank_key`), and their keys."""
        keys = [rank_key(v, m) for v, m in zip(self.objective_values(ds), self.point_margins(ds))]
        return sorted(range(len(keys)), key=keys.__getitem__), keys

    def best(self, ds):
        """Index and rank key of the best simulated point (None, None for no points)."""
        if ds.sizes["design"] == 0:
            return None, None
        order, keys = self.ranked(ds)
        return order[0], keys[order[0]]

    # ------------------------------------------------------------------ surrogates
    def model_name(self, quantity, k):
        """Name of the surrogate of ``quantity`` at case k: the quantity itself for a one-case study,
        ``<quantity>_case<k>`` in a duty cycle (one set of constraint surrogates per case)."""
        return quantity if len(self.cycle) == 1 else f"{quantity}_case{k}"

    def constrained(self):
        """Per-case outputs whose surrogates carry constraints."""
        return (*CONSTRAINED, *((EDGE_MARGIN,) if self.limits.edge_stress else ()))

    def training_sets(self, ds):
        """(X, y, log, units) per modelled output, from the points with results: the cycle objective
        (key: the objective's name) and each constrained output at each case (:meth:`model_name`)."""
        X = design_matrix(ds, self.space)
        ok = ds.status.values == STATUS["ok"]
        log_outputs = set(self.study.surrogate.log_outputs)

        def units(q):
            return ds[q].attrs.get("units", "1")

        sets = {self.objective: (X[ok], self.objective_values(ds)[ok], self.objective in log_outputs,
                                 units(self.objective))}
        for k in range(len(self.cycle)):
            for q in self.constrained():
                sets.setdefault(self.model_name(q, k), (X[ok], ds[q].transpose("design", "case").values[ok, k],
                                                        q in log_outputs, units(q)))
        return sets

    def success_set(self, ds):
        """(X, success) of the points that were simulated: impossible geometries are known without a
        simulation (:meth:`admissible`), so they are no failure of the simulation to learn."""
        ran = ds.status.values != STATUS["geometry_error"]
        return design_matrix(ds, self.space)[ran], ds.status.values[ran] == STATUS["ok"]

    def fit(self, ds):
        """Regression surrogates of every modelled output and the success classifier (key
        :data:`SUCCESS`) fitted to ``ds``."""
        n_ok = int((ds.status == STATUS["ok"]).sum())
        if n_ok < 2:
            raise StudyConfigError(f"only {n_ok} of {ds.sizes['design']} simulations converged: the surrogates need "
                                   f"at least 2; check study.bounds")
        models = {q: GPSurrogate(self.space.bounds, log, self.settings, q, units).fit(X, y)
                  for q, (X, y, log, units) in self.training_sets(ds).items()}
        models[SUCCESS] = SuccessClassifier(self.space.bounds, self.settings, SUCCESS).fit(*self.success_set(ds))
        return models

    def surrogates(self, folder, ds):
        """Surrogates saved in ``folder``, or fitted to ``ds`` and saved there.

        Loading checks each file's SHA-256 and the scikit-learn version recorded at save time
        (surrogate.store); a set that fails is refused with the reason and how to refit.
        """
        if saved_set(folder) is not None:
            return load_surrogates(folder)
        models = self.fit(ds)
        save_surrogates(models, folder)
        return models

    # ------------------------------------------------------------------ one round
    def geometry_error(self, bearing):
        """Message of an impossible geometry ('' if possible): sim.geometry's check, no numerics."""
        try:
            Geometry.from_config({**self._bearing, **bearing}, self._material, self._n_slices)
        except GeometryError as err:
            return str(err)
        return ""

    def constraint_set(self):
        """The constraints of :func:`studies.constraints.margins` on the modelled outputs, as limits
        for the acquisition (the simulation margin is the classifier's, PCR_over_Lwe is exact:
        :meth:`admissible`)."""
        L = self.limits
        out = []
        for k in range(len(self.cycle)):
            out += [Constraint(self.model_name("axial_displacement", k), -L.axial_displacement_max,
                               L.axial_displacement_max),
                    Constraint(self.model_name("pmax", k), high=L.pmax_max[k]),
                    Constraint(self.model_name("C_eff", k), low=lambda X: L.C_eff_min(self.space.ratings_alpha(X)))]
            if L.edge_stress:
                out.append(Constraint(self.model_name(EDGE_MARGIN, k), high=0.0))
        return out

    def admissible(self, x):
        """Whether design x can be built and meets the exact constraints (no simulation needed)."""
        bearing = self.space.bearing_values(x)
        return exact_margin(bearing, self.limits) <= 0.0 and self.geometry_error(bearing) == ""

    def propose(self, ds, models, q, seed, pending=None):
        """q new designs (k, d), k <= q, by constrained Bayesian optimisation on ``models`` fitted to
        ``ds`` (surrogate.acquisition), each at least ``budget.dedup_distance`` (max-norm, unit
        cube) from every simulated and every ``pending`` design (being simulated elsewhere, fantasised
        by the kriging believer)."""
        ok = ds.isel(design=np.flatnonzero(ds.status.values == STATUS["ok"]))
        i, key = self.best(ok)
        incumbent = centre = None
        if i is not None:
            centre = design_matrix(ok, self.space)[i]
            if key[0] == 0:
                value = float(self.objective_values(ok)[i])
                incumbent = np.log(value) if models[self.objective].log else value
        regression = {k: m for k, m in models.items() if k != SUCCESS}
        X, _ = propose(regression, self.objective, self.constraint_set(), models[SUCCESS], incumbent, centre,
                       self.space.bounds, design_matrix(ds, self.space), q,
                       CandidateSettings.from_config(self.study.acquisition), self.admissible,
                       float(self.study.budget.dedup_distance), seed, pending)
        return X

    def simulation_trial(self, trial):
        """Evaluate an Optuna trial with the full simulation: (objective, margins, user attrs).

        For direct searches (benchmarks/bench_design_search.py). A point without result is
        told with a positive ``simulation`` margin, so the sampler learns from it, and the
        worst objective seen so far (at least the references'), so it is never a gap.
        """
        x = self.space.suggest(trial)
        bearing = self.space.bearing_values(x)
        records = [evaluate_design(cfg, bearing, self.quantities) for cfg in self.case_cfgs]
        record = self.summary(records)
        ok = record["status"] == "ok"
        value = record["values"][self.objective]
        if not ok:
            seen = [t.value for t in complete_trials(trial.study)] + \
                [r.record["values"][self.objective] for r in self.references.values()]
            value = float(np.nanmax(seen))
        return value, margins(case_values(records), bearing, self.limits, 0.0 if ok else FAILED), \
            {"status": record["status"], "message": record["message"], "values": record["values"],
             "wall_time": record["wall_time"]}

    # ------------------------------------------------------------------ final local stage
    def refine(self, ds):
        """Local stage on the full simulation from the best distinct verified designs of ``ds`` (the
        loop's points): returns all points (loop and local stage) and sets :attr:`local`.

        Each point is looked up among the stored ones before it is simulated (a resumed stage
        replays COBYLA's sequence from the same start), and training.nc is rewritten after each.
        """
        r = self.study.refine
        n_max = int(r.max_simulations)
        if self._refined is None:
            self._refined = ds.isel(design=[])
        if n_max == 0:
            return ds
        span = self.space.high - self.space.low

        def stored(x):
            for part in (ds, self._refined):
                hit = np.flatnonzero(np.all(design_matrix(part, self.space) == x, axis=1))
                if hit.size:
                    return part.isel(design=[int(hit[0])])
            return None

        seen = set()    # this stage's points (the starts included), as local_refine counts them against n_max;
        # stored refinement points of an earlier stage from other starts (a resume with a larger budget) do not count

        def evaluate(u):
            x = self.space.low + u * span
            seen.add(x.tobytes())
            p = stored(x)
            if p is None:
                p = self.simulate(x[None, :], REFINEMENT, REFINEMENT_ROUND)
                self._refined = xr.concat([self._refined, p], dim="design", combine_attrs="override", data_vars="all")
                self.save_training(ds)
                self.log(f"local stage: point {len(seen)} of at most {n_max} (the starts included): "
                         f"{self.objective} {float(self.objective_values(p)[0]):.6g} ({STATUS_NAMES[int(p.status.values[0])]})")
            ok = int(p.status.values[0]) == STATUS["ok"]
            return (float(self.objective_values(p)[0]) if ok else np.nan), self.point_margins(p)[0]

        order, _ = self.ranked(ds)
        starts = distinct_starts(self.space.unit(design_matrix(ds, self.space)[order]), int(r.starts),
                                 float(r.start_distance))
        self.log(f"local stage: {len(starts)} start(s), the verified best and the next best designs at least "
                 f"{float(r.start_distance):g} apart (unit scale)")
        # the back-off tightens every constraint but the simulation's own margin (0 or 1: a result or none)
        backoff = [0.0 if n == SIMULATION_MARGIN else float(r.constraint_backoff) for n in self.limits.names]
        self.local = local_refine(evaluate, starts, self.limits.names, n_max, float(r.initial_step), float(r.final_step),
                                  float(r.active_tolerance), int(r.restarts), float(r.restart_shrink),
                                  int(r.start_simulations), backoff)
        # the simulation's own margin (0 whenever it gave a result) is no constraint to report
        self.local.active_constraints = [c for c in self.local.active_constraints if c != SIMULATION_MARGIN]
        return xr.concat([ds, self._refined], dim="design", combine_attrs="override", data_vars="all")

    # ------------------------------------------------------------------ the loop
    def run(self):
        """Run (or resume) the whole search; returns the training dataset and the stop reason."""
        s = self.study
        b = s.budget
        if self.limits is None:
            self.run_references()
        ds = self.initial_design()
        stale, r = 0, 1
        while True:
            if ds.sizes["design"] >= int(b.max_simulations):
                reason = f"simulation budget spent ({ds.sizes['design']} of {b.max_simulations})"
                break
            t0 = time.perf_counter()
            models = self.surrogates(self.out / "surrogates" / f"round_{r:03d}", ds)
            if not np.any(ds["round"].values == r):
                q = min(int(b.verify_per_round), int(b.max_simulations) - ds.sizes["design"])
                X = self.propose(ds, models, q, round_seed(s.seed, r))
                self.log(f"round {r}: fits and acquisition {time.perf_counter() - t0:.1f} s, {len(X)} designs proposed")
                if len(X) == 0:
                    reason = f"round {r}: no new candidate (all within budget.dedup_distance of simulated points)"
                    break
                ds = xr.concat([ds, self.simulate(X, "verification", r)], dim="design",
                               combine_attrs="override", data_vars="all")
                self.save_training(ds)
            _, before = self.best(ds.isel(design=np.flatnonzero(ds["round"].values < r)))
            i, after = self.best(ds)
            stale = 0 if improved(before, after, float(b.min_improvement)) else stale + 1
            state = "feasible" if after[0] == 0 else "infeasible, violation"
            self.log(f"round {r}: {self.count(ds.sizes['design'])}; best #{i} ({state} {after[1]:.6g})")
            if stale >= int(b.patience):
                reason = f"verified best not improved for {stale} rounds"
                break
            r += 1
        self.log(f"stopped: {reason}")
        ds = self.refine(ds)
        if self.local is not None:
            L = self.local
            self.log(f"local stage: {L.evaluations} points, {self.objective} {L.start_value:.6g} -> {L.value:.6g} "
                     f"({'feasible' if L.feasible else 'infeasible'}); active constraints: "
                     f"{', '.join(L.active_constraints) or 'none'}; active bounds: "
                     f"{', '.join(f'{self.space.names[k]} {side}' for k, side in L.active_bounds) or 'none'}")
        return ds, reason
