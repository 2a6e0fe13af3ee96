"""Several worker processes on one design search (issue 17): ``python -m studies.workers``.

::

    python -m studies.workers run -n 4 [overrides ...]   # create, start 4 workers here, wait, report
    python -m studies.workers create [overrides ...]     # once, before any worker starts
    python -m studies.workers work [overrides ...]       # one worker: start as many as wanted, anywhere
    python -m studies.workers report [overrides ...]     # the report, built from the storage alone

The surrogate-assisted search of :mod:`studies.loop`, run asynchronously by N processes on one
Optuna study ``<name>-verified`` in ``study.storage`` (PostgreSQL for several machines; a
journal file or SQLite on one). Every full simulation is one trial of that study; its record
(studies.evaluate: status, message, values, units, wall time) is the trial's user attribute
``record``, its constraint margins the trial's constraints.

- ``create`` simulates the references (the constraint limits they set are stored as study user
  attributes), creates the study and enqueues the space-filling design as WAITING trials.
  Workers only load the study: no creation race. An existing study is resumed when its
  result-defining configuration is the same, refused otherwise.
- A worker simulates a queued design if there is one. Otherwise, once no design of the initial
  design is queued or running, it proposes one: it fits the surrogates to every COMPLETE trial
  in the storage and takes the design of highest constrained acquisition (surrogate.acquisition,
  seeded by the study seed, the number of trials and the worker index) at least
  ``budget.dedup_distance`` from every stored point, those queued or being simulated elsewhere
  included (fantasised by the kriging believer).
- Before it simulates, a trial claims its design and one of ``budget.max_simulations`` slots in
  a claims table (name unique per study: a table beside Optuna's in the same database, or, for
  a journal, files created atomically beside it). A design claimed by another trial is PRUNED as
  a duplicate; a design that finds no free slot is PRUNED as over budget. So no design is
  simulated twice and the number of simulated designs is exact, whatever the timing.
- RDB storage has Optuna's heartbeat on (``study.workers``): the trial of a worker killed with
  SIGKILL is marked FAIL after ``grace_period`` and enqueued again (RetryHeartbeatStaleTrialCallback),
  and the retry keeps the design's claim and slot. The journal storage has no heartbeat: its
  trials left RUNNING are failed and retried when ``create`` runs again (never while workers run).
- ``budget.patience`` of the sequential search does not apply: the workers stop when every slot
  is taken (or no new candidate is left).
"""
import argparse
import hashlib
import os
import shutil
import socket
import subprocess
import sys
import tempfile
import time
import warnings
from dataclasses import asdict
from pathlib import Path

import numpy as np
import optuna
import sqlalchemy as sa
from optuna.samplers import PartialFixedSampler, RandomSampler
from optuna.storages import RDBStorage, RetryHeartbeatStaleTrialCallback
from optuna.trial import TrialState

from sim.api.cli import PROJECT_ERRORS, refused
from studies.config import StudyConfigError, compose, storage_spec
from studies.constraints import FAILED, Limits, margins
from studies.evaluate import evaluate_design, points_dataset
from studies.loop import DesignSearch, round_seed
from studies.report import write_report
from studies.search import make_storage

STUDY_ERRORS = PROJECT_ERRORS + (StudyConfigError,)
CREATED_ATTR = "created"      # study user attribute: the study and its initial design are complete
CLAIMS_TABLE = "tsrb_claims"  # table of claimed names beside Optuna's tables


def study_name(study):
    """Name of the Optuna study of the workers: ``<study.name>-verified``."""
    return f"{study.name}-verified"


def design_key(params, names):
    """Text key of a design: its free parameters at full float precision (``repr`` round-trips)."""
    return ";".join(f"{n}={float(params[n])!r}" for n in names)


# ---------------------------------------------------------------------------- claims
class RDBClaims:
    """Names claimed once per study, with an integer value: rows of a table in the study's database
    (primary key (study, name), so a second insert of a name fails in the database itself)."""

    def __init__(self, engine, study):
        self.engine, self.study = engine, study
        meta = sa.MetaData()
        self.table = sa.Table(CLAIMS_TABLE, meta, sa.Column("study", sa.String(512), primary_key=True),
                              sa.Column("name", sa.String(512), primary_key=True),
                              sa.Column("value", sa.Integer, nullable=False))
        self._meta = meta

    def create_table(self):
        self._meta.create_all(self.engine)

    def add(self, name, value):
        """Claim ``name`` with ``value``; False if it was claimed before."""
        try:
            with self.engine.begin() as con:
                con.execute(self.table.insert().values(study=self.study, name=name, value=int(value)))
        except sa.exc.IntegrityError:
            return False
        return True

    def get(self, name):
        """Value of a claimed name, None if unclaimed."""
        t = self.table
        with self.engine.connect() as con:
            return con.execute(sa.select(t.c.value).where(t.c.study == self.study, t.c.name == name)).scalar()

    def count(self, prefix):
        t = self.table
        with self.engine.connect() as con:
            return con.execute(sa.select(sa.func.count()).where(t.c.study == self.study,
                                                                t.c.name.startswith(prefix))).scalar()

    def clear(self):
        with self.engine.begin() as con:
            con.execute(self.table.delete().where(self.table.c.study == self.study))


class FileClaims:
    """The same for a journal storage: one file per name in a folder beside the journal, created
    with ``os.link`` of a written temporary file (atomic, fails if the name exists)."""

    def __init__(self, folder):
        self.folder = Path(folder)

    def create_table(self):
        self.folder.mkdir(parents=True, exist_ok=True)

    def add(self, name, value):
        fd, tmp = tempfile.mkstemp(prefix=f".{name}.", dir=self.folder)
        with os.fdopen(fd, "w") as f:
            f.write(str(int(value)))
        tmp = Path(tmp)
        try:
            os.link(tmp, self.folder / name)
        except FileExistsError:
            return False
        finally:
            tmp.unlink()
        return True

    def get(self, name):
        try:
            return int((self.folder / name).read_text())
        except FileNotFoundError:
            return None

    def count(self, prefix):
        return sum(1 for _ in self.folder.glob(f"{prefix}*"))

    def clear(self):
        shutil.rmtree(self.folder, ignore_errors=True)
        self.folder.mkdir(parents=True)


def claim(claims, key, root, budget):
    """Claim a design for the chain of trials ``root`` (a trial and its retries): (slot, '') or
    (None, reason).

    The design's name holds the chain that owns it; a slot ``slot-k`` (k < budget) holds the
    chain it belongs to, so a retry finds its design and slot again.
    """
    name = "design-" + hashlib.sha256(key.encode()).hexdigest()[:40]
    if not claims.add(name, root) and claims.get(name) != root:
        return None, f"duplicate of the design of trial #{claims.get(name)}"
    for k in range(budget):
        if claims.add(f"slot-{k}", root) or claims.get(f"slot-{k}") == root:
            return k, ""
    return None, f"all budget.max_simulations = {budget} slots taken"


# ---------------------------------------------------------------------------- results from the storage
def known_design(trial, names):
    """x of a trial's design (parameters, or the fixed parameters of a queued trial); None if unknown yet.

    Another worker's RUNNING trial may be read while it is still being suggested, one parameter at
    a time (seen under load: a KeyError on the second name): until it holds every name its design
    is unknown (the design claim still keeps it from being simulated twice)."""
    params = trial.params or trial.system_attrs.get("fixed_params")
    if not params or any(n not in params for n in names):
        return None
    return np.array([float(params[n]) for n in names])


def verified_points(search, trials, attrs=None):
    """Points dataset (studies.evaluate.points_dataset) of the COMPLETE trials, in slot order:
    ``source`` and ``round`` (0 initial design, k the k-th proposal) from the trial."""
    done = sorted((t for t in trials if t.state == TrialState.COMPLETE), key=lambda t: t.user_attrs["slot"])
    names = search.space.names
    X = np.array([search.space.from_params(t.params) for t in done]).reshape(len(done), len(names))
    ds = points_dataset(search.space, X, [[t.user_attrs["record"]] for t in done], "initial", 0, attrs or {}, search.cycle)
    n0 = len(search.initial_points())
    source = [t.user_attrs.get("source", "verification") for t in done]
    rounds = np.array([0 if s == "initial" else t.user_attrs["slot"] - n0 + 1 for s, t in zip(source, done)],
                      dtype=np.int32)
    return ds.assign_coords(source=("design", source, ds.source.attrs), round=("design", rounds, ds["round"].attrs))


class Skipped(optuna.TrialPruned):
    """A trial that simulates nothing: its design is a duplicate, over budget, or was taken by
    another worker (the reason is the trial's user attribute ``skipped``)."""


# ---------------------------------------------------------------------------- the workers
class Workers:
    """Create, work on and report one study shared by worker processes.

    Parameters
    ----------
    root_cfg : omegaconf.DictConfig
        Composed config (studies.config.compose).
    overrides : sequence of str
    index : int
        This worker's index (decorrelates the seeds of concurrent proposals).
    out_dir : path, optional
        Study folder (report files; the SQLite default storage); default outputs/studies/<name>.
    log : callable
    """

    def __init__(self, root_cfg, overrides=(), index=0, out_dir=None, log=print):
        self.search = DesignSearch(root_cfg, overrides, out_dir=out_dir, log=log)
        self.search.require_one_case("python -m studies.workers")
        self.study = root_cfg.study
        self.index = int(index)
        self.log = log
        self.spec = storage_spec(self.study, self.search.out)
        self.storage = make_storage(self.spec, heartbeat=self.study.workers)
        self.heartbeat = isinstance(self.storage, RDBStorage)
        self.name = study_name(self.study)
        self.claims = (RDBClaims(self.storage.engine, self.name) if self.heartbeat else
                       FileClaims(f"{self.spec[len('journal:'):]}.claims/{self.name}"))
        self.worker_id = f"{socket.gethostname()}:{os.getpid()}"
        self.candidate = None

    # ------------------------------------------------------------------ create, open
    def _load(self):
        try:
            return optuna.load_study(study_name=self.name, storage=self.storage, sampler=RandomSampler())
        except KeyError:
            return None

    def _check_config(self, study):
        for key, value in self.search.config_attrs().items():
            if study.user_attrs.get(key) != value:
                raise StudyConfigError(f"the study {self.name!r} in {self.spec} was made with another "
                                       f"{key.replace('_', ' ')}; use another study.name or storage")

    def create(self):
        """Create the study and queue the initial design (or check and resume an existing one)."""
        search, s = self.search, self.study
        search.run_references()
        study = self._load()
        if study is not None and not study.user_attrs.get(CREATED_ATTR):
            optuna.delete_study(study_name=self.name, storage=self.storage)  # half made: made again
            study = None
        self.claims.create_table()
        if study is None:
            self.claims.clear()
            study = optuna.create_study(storage=self.storage, study_name=self.name, direction="minimize")
            for key, value in {**search.config_attrs(), "limits": asdict(search.limits)}.items():
                study.set_user_attr(key, value)
            X = search.initial_points()
            for x in X:
                study.enqueue_trial(dict(zip(search.space.names, map(float, x))), user_attrs={"source": "initial"})
            study.set_user_attr(CREATED_ATTR, True)
            self.log(f"created {self.name} in {self.spec}: {len(X)} initial designs queued")
            return study
        self._check_config(study)
        if self.heartbeat:
            optuna.storages.fail_stale_trials(study)
        else:  # no heartbeat: a RUNNING trial here is one of a dead worker (create runs before the workers)
            retry = RetryHeartbeatStaleTrialCallback(max_retry=int(s.workers.max_retry))
            for t in study.get_trials(deepcopy=False, states=(TrialState.RUNNING,)):
                study.tell(t.number, state=TrialState.FAIL)
                retry(study, next(f for f in study.get_trials(deepcopy=False) if f.number == t.number))
        counts = {st.name: n for st in TrialState
                  if (n := len(study.get_trials(deepcopy=False, states=(st,))))}
        self.log(f"resuming {self.name} in {self.spec}: {counts}")
        return study

    def open(self):
        """The created study (workers and report only load it); sets the stored constraint limits."""
        study = self._load()
        if study is None or not study.user_attrs.get(CREATED_ATTR):
            raise StudyConfigError(f"no study {self.name!r} in {self.spec}: run `python -m studies.workers create` "
                                   f"with the same overrides before the workers")
        self._check_config(study)
        self.search.limits = Limits(**study.user_attrs["limits"])
        return study

    # ------------------------------------------------------------------ one worker
    def propose(self, trials):
        """A new design from surrogates fitted to the COMPLETE trials: {name: value}, or None."""
        search, s = self.search, self.study
        ds = verified_points(search, trials)
        models = search.fit(ds)
        pending = [x for t in trials if t.state in (TrialState.RUNNING, TrialState.WAITING)
                   and (x := known_design(t, search.space.names)) is not None]
        X = search.propose(ds, models, 1, round_seed(s.seed, len(trials), self.index),
                           np.array(pending).reshape(len(pending), len(search.space.names)))
        return dict(zip(search.space.names, map(float, X[0]))) if len(X) else None

    def _skip(self, trial, reason):
        trial.set_user_attr("skipped", reason)
        raise Skipped(reason)

    def objective(self, trial):
        """Simulate the trial's design once it is claimed; the objective (+inf without result)."""
        search = self.search
        names = search.space.names
        system_attrs = next(t for t in trial.study.get_trials(deepcopy=False) if t.number == trial.number).system_attrs
        queued = bool(trial.params) or "fixed_params" in system_attrs
        if not queued and self.candidate is None:
            self._skip(trial, "the queued design was taken by another worker")
        x = search.space.suggest(trial)
        root = system_attrs.get("failed_trial", trial.number)  # a retry keeps its chain's claims
        slot, reason = claim(self.claims, design_key(trial.params, names), root, int(self.study.budget.max_simulations))
        if slot is None:
            self._skip(trial, reason)
        trial.set_user_attr("slot", slot)
        trial.set_user_attr("worker", self.worker_id)
        if "source" not in trial.user_attrs:
            trial.set_user_attr("source", "verification")
        bearing = search.space.bearing_values(x)
        record = evaluate_design(search.base_cfg, bearing, search.quantities)
        ok = record["status"] == "ok"
        for i, m in enumerate(margins(record["values"], bearing, search.limits, 0.0 if ok else FAILED)):
            trial.set_constraint(str(i), float(m))
        trial.set_user_attr("record", {k: record[k] for k in ("status", "message", "values", "attrs", "wall_time")})
        self.log(f"worker {self.index}: trial #{trial.number} slot {slot} {record['status']} "
                 f"{search.objective} {record['values'][search.objective]:.6g} ({record['wall_time']:.2f} s)")
        return float(record["values"][search.objective]) if ok else float("inf")

    def _initial_pending(self, trials):
        return any(t.user_attrs.get("source") == "initial" and t.state in (TrialState.RUNNING, TrialState.WAITING)
                   for t in trials)

    def work(self):
        """Simulate queued and proposed designs until every slot is taken; returns the stop reason."""
        s = self.study
        study = self.open()
        budget, poll = int(s.budget.max_simulations), float(s.workers.poll_interval)
        stuck = (None, time.monotonic())  # RUNNING trials waited for, and since when
        while True:
            if self.heartbeat:
                optuna.storages.fail_stale_trials(study)
            trials = study.get_trials(deepcopy=False)
            running = frozenset(t.number for t in trials if t.state == TrialState.RUNNING)
            self.candidate = None
            if any(t.state == TrialState.WAITING for t in trials):
                pass
            elif self.claims.count("slot-") < budget and not self._initial_pending(trials):
                self.candidate = self.propose(trials)
                if self.candidate is None:
                    return "no new candidate (all within budget.dedup_distance of stored points)"
            elif running and (self.heartbeat or self.claims.count("slot-") < budget):
                # wait for the initial design, or (with heartbeat) for a dead worker's trial to come back
                if running != stuck[0]:
                    stuck = (running, time.monotonic())
                elif not self.heartbeat and time.monotonic() - stuck[1] > float(s.workers.grace_period):
                    return (f"trials {sorted(running)} RUNNING for more than workers.grace_period without progress: "
                            f"on journal storage a dead worker's trial is retried when `create` runs again")
                time.sleep(poll)
                continue
            else:
                return f"all budget.max_simulations = {budget} slots taken"
            with warnings.catch_warnings():  # PartialFixedSampler: experimental since Optuna 2.4, stable API
                warnings.simplefilter("ignore", optuna.exceptions.ExperimentalWarning)
                study.sampler = PartialFixedSampler(self.candidate or {}, RandomSampler(seed=round_seed(s.seed, self.index)))
            study.optimize(self.objective, n_trials=1, gc_after_trial=False)

    # ------------------------------------------------------------------ report
    def report(self):
        """The report of studies.report from the trials in the storage; returns (text, dataset)."""
        study = self.open()
        stored = self.search.limits
        self.search.run_references()
        if self.search.limits != stored:
            raise StudyConfigError(f"the references give other constraint limits than those stored with the study "
                                   f"({asdict(self.search.limits)} vs {asdict(stored)}): the simulation changed")
        trials = study.get_trials(deepcopy=False)
        ds = verified_points(self.search, trials, self.search.attrs())
        if ds.sizes["design"] == 0:
            raise StudyConfigError(f"the study {self.name!r} holds no simulated design yet: start workers first")
        count = {st: sum(t.state == st for t in trials) for st in TrialState}
        reason = (f"{count[TrialState.COMPLETE]} of budget.max_simulations = {self.study.budget.max_simulations} "
                  f"designs simulated by workers ({count[TrialState.FAIL]} trials of dead workers failed and retried, "
                  f"{count[TrialState.PRUNED]} proposals skipped, {count[TrialState.RUNNING]} running)")
        return write_report(self.search, ds, reason), ds


# ---------------------------------------------------------------------------- command line
def _default_index():
    """Worker index: SLURM's array task id in a job array, else 0."""
    return int(os.environ.get("SLURM_ARRAY_TASK_ID", "0"))


def start_workers(n, overrides, env=None):
    """Start n ``work`` processes with indices 0..n-1; returns the Popen objects."""
    return [subprocess.Popen([sys.executable, "-m", "studies.workers", "work", "--index", str(i), *overrides],
                             env=env) for i in range(n)]


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m studies.workers", description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("command", choices=("run", "create", "work", "report"))
    parser.add_argument("-n", "--workers", type=int, default=2, help="run: worker processes to start (default 2)")
    parser.add_argument("--index", type=int, default=None,
                        help="work: this worker's index (default $SLURM_ARRAY_TASK_ID or 0)")
    parser.add_argument("overrides", nargs="*", help="Hydra-style overrides, e.g. study=size_32208")
    args = parser.parse_intermixed_args(argv)
    if args.workers < 1:
        return refused(f"-n/--workers = {args.workers} is outside the allowed range: an integer >= 1")
    optuna.logging.set_verbosity(optuna.logging.WARNING)
    # heartbeat, fail_stale_trials: experimental in Optuna since 2.9, one warning per call otherwise
    warnings.filterwarnings("ignore", category=optuna.exceptions.ExperimentalWarning)
    t0 = time.perf_counter()

    def log(msg):
        print(f"[{time.perf_counter() - t0:6.1f} s] {msg}", flush=True)

    try:
        cfg = compose(args.overrides)
        index = _default_index() if args.index is None else args.index
        workers = Workers(cfg, args.overrides, index=index, log=log)
        if args.command in ("create", "run"):
            workers.create()
        if args.command == "work":
            log(f"worker {index} ({workers.worker_id}) stopped: {workers.work()}")
        if args.command == "run":
            codes = [p.wait() for p in start_workers(args.workers, args.overrides)]
            if any(codes):
                print(f"error: worker exit codes {codes}; start `python -m studies.workers run` (or `work`) again "
                      f"to resume", file=sys.stderr)
                return 1
        if args.command in ("report", "run"):
            text, _ = workers.report()
            print(text)
            print(f"\nwritten to {workers.search.out}/ in {time.perf_counter() - t0:.1f} s")
    except STUDY_ERRORS as err:
        return refused(err)
    return 0


if __name__ == "__main__":
    sys.exit(main())
