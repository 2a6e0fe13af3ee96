"""Optuna with its own ask-and-tell API: samplers, storage, and a resumable constrained loop.

Constraints reach the samplers as Optuna 5 documents it: each trial stores its margins
(<= 0 feasible) with ``Trial.set_constraint`` before it is told, and TPE, GP and NSGA-II read
them from the trial (``FrozenTrial.constraints``); :func:`trial_margins` reads them back in
order.

Resuming: a study lives in its storage. :func:`run_trials` counts the COMPLETE trials there
and asks only for the missing ones; the sampler is re-seeded from that count before every
ask, so an interrupted and resumed study proposes the same points as an uninterrupted one.
A trial left RUNNING by a killed process is marked FAIL (and so ignored by the samplers).
One process drives a study at a time here; studies.workers runs several on one study.

Studies whose trials cost milliseconds (on surrogates) run in memory and are written to the
storage when finished (:func:`persist_study`, :func:`finished_study`): SQLite through
SQLAlchemy costs about 90 ms per trial, more than the trial itself. An interrupted one is
redone, identically, since the sampler seeds depend only on the trial count.
"""
from pathlib import Path

import numpy as np
import optuna
from optuna.storages import JournalStorage, RDBStorage, RetryHeartbeatStaleTrialCallback
from optuna.storages.journal import JournalFileBackend
from optuna.trial import TrialState

FINISHED_ATTR = "finished"  # study user attribute: all trials of a persisted study are written


def trial_margins(trial):
    """Constraint margins of a finished trial, in the order they were set (<= 0 feasible)."""
    margins = trial.constraints
    return [margins[key] for key in sorted(margins, key=int)]


def make_sampler(name, seed, settings):
    """A constrained Optuna sampler.

    Parameters
    ----------
    name : str
        ``tpe`` (TPESampler), ``gp`` (GPSampler, needs PyTorch) or ``nsga2`` (NSGAIISampler).
    seed : int
    settings : mapping
        ``n_startup_trials`` (TPE, GP) and ``population_size`` (NSGA-II).
    """
    samplers = {
        "tpe": lambda: optuna.samplers.TPESampler(seed=seed, n_startup_trials=int(settings["n_startup_trials"])),
        "gp": lambda: optuna.samplers.GPSampler(seed=seed, n_startup_trials=int(settings["n_startup_trials"])),
        "nsga2": lambda: optuna.samplers.NSGAIISampler(seed=seed, population_size=int(settings["population_size"])),
    }
    if name not in samplers:
        raise ValueError(f"sampler = {name!r} is not one of {sorted(samplers)}")
    if name == "gp":
        import torch

        # GPSampler fits one small GP per objective and constraint: on 2 busy cores one torch
        # thread is 3x faster than the default pool (measured, 5 inputs, 6 constraints)
        torch.set_num_threads(1)
    return samplers[name]()


def make_storage(spec, heartbeat=None):
    """Optuna storage from a spec: an RDB URL (``sqlite:///x.db``, ``postgresql+psycopg://...``) or
    ``journal:<file>``.

    The folder of a SQLite or journal file is created. ``heartbeat`` (the study's ``workers``
    node: ``heartbeat_interval``, ``grace_period`` [s], ``max_retry``) turns on Optuna's
    heartbeat for an RDB URL: a RUNNING trial without heartbeat for ``grace_period`` is marked
    FAIL and enqueued again (RetryHeartbeatStaleTrialCallback), at most ``max_retry`` times. The journal
    storage has no heartbeat in Optuna 5 (studies.workers retries its stale trials at start).
    """
    if spec.startswith("journal:"):
        path = Path(spec[len("journal:"):])
        path.parent.mkdir(parents=True, exist_ok=True)
        return JournalStorage(JournalFileBackend(str(path)))
    if spec.startswith("sqlite:///"):
        Path(spec[len("sqlite:///"):]).parent.mkdir(parents=True, exist_ok=True)
    if heartbeat is None:
        return spec
    return RDBStorage(spec, engine_kwargs={"pool_pre_ping": True},  # a server may drop idle connections
                      heartbeat_interval=int(heartbeat["heartbeat_interval"]),
                      grace_period=int(heartbeat["grace_period"]),
                      heartbeat_stale_trial_callback=RetryHeartbeatStaleTrialCallback(max_retry=int(heartbeat["max_retry"])))


def open_study(storage, name, sampler, directions=None):
    """Create or load (``load_if_exists``) a study: one objective minimised, or ``directions``
    (a list of "minimize"/"maximize", multi-objective)."""
    if directions is None:
        return optuna.create_study(storage=storage, study_name=name, sampler=sampler, direction="minimize",
                                   load_if_exists=True)
    return optuna.create_study(storage=storage, study_name=name, sampler=sampler, directions=list(directions),
                               load_if_exists=True)


def finished_study(storage, name):
    """The study ``name`` if :func:`persist_study` finished writing it, else None (a partial copy is deleted)."""
    try:
        study = optuna.load_study(study_name=name, storage=storage)
    except KeyError:
        return None
    if study.user_attrs.get(FINISHED_ATTR):
        return study
    optuna.delete_study(study_name=name, storage=storage)
    return None


def persist_study(study, storage):
    """Copy a finished (in-memory) study's trials into ``storage`` and mark it finished."""
    target = optuna.create_study(storage=storage, study_name=study.study_name, direction="minimize")
    target.add_trials(study.get_trials(deepcopy=False))
    target.set_user_attr(FINISHED_ATTR, True)
    return target


def complete_trials(study):
    """COMPLETE trials of a study, in trial order."""
    return study.get_trials(deepcopy=False, states=(TrialState.COMPLETE,))


def run_trials(study, n_trials, evaluate, sampler_for):
    """Ask and tell until ``study`` holds ``n_trials`` COMPLETE trials.

    Parameters
    ----------
    study : optuna.Study
    n_trials : int
    evaluate : callable
        ``evaluate(trial) -> (value, margins, user_attrs)``: it suggests the parameters, and
        returns the objective (a list of values for a multi-objective study), the constraint margins (<= 0 feasible) and extra attributes.
        A design that cannot be evaluated is a result (positive margin), not an exception.
    sampler_for : callable
        ``sampler_for(k)`` -> sampler used to ask for the trial after k complete ones.

    Returns
    -------
    list of optuna.trial.FrozenTrial
        The complete trials.
    """
    for stale in study.get_trials(deepcopy=False, states=(TrialState.RUNNING,)):
        study.tell(stale.number, state=TrialState.FAIL)
    done = len(complete_trials(study))
    while done < n_trials:
        study.sampler = sampler_for(done)
        trial = study.ask()
        try:
            value, margins, attrs = evaluate(trial)
        except BaseException:
            study.tell(trial, state=TrialState.FAIL)
            raise
        for key, val in attrs.items():
            trial.set_user_attr(key, val)
        for i, m in enumerate(margins):
            trial.set_constraint(str(i), float(m))
        study.tell(trial, [float(v) for v in value] if np.ndim(value) else float(value))
        done += 1
    return complete_trials(study)
