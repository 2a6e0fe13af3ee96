"""Worker processes on one study (studies/workers.py, issue 17 items 1-3), on a real PostgreSQL
server (conftest.py) and on a journal file.

A real, small study: the pinion search of tests/studies/test_design_search_loop.py (10 slices,
friction off, objective pmax; ~30 ms a simulation), 8 initial designs and 20 in all, so that
the workers contend for the storage most of the time. Workers are separate processes
(``python -m studies.workers work``), killed with real signals.
"""
import os
import signal
import subprocess
import sys
import threading
import time
from collections import Counter

import numpy as np
import optuna
import pytest
from optuna.trial import TrialState

from studies.config import compose
from studies.workers import FileClaims, RDBClaims, Workers, claim, design_key, study_name, verified_points

BUDGET = 20
TINY = ["study.objective=pmax", "friction.enabled=false", "solver.n_slices=10", "study.initial_design.n=8",
        f"study.budget.max_simulations={BUDGET}", "study.n_jobs=1",
        "study.surrogate.n_restarts_optimizer=0", "study.sampler_settings.n_startup_trials=10",
        # heartbeat every second, a trial without one for 3 s is failed and retried (default 10 s / 60 s)
        "study.workers.heartbeat_interval=1", "study.workers.grace_period=3", "study.workers.poll_interval=0.2"]
RUN_TIMEOUT = 600  # s, bound on a group of workers; 3 workers x 20 designs take ~30-60 s on 2 busy cores


def overrides(storage):
    return [*TINY, f"study.storage={storage}"]


def created(storage, folder):
    """The study made once, before any worker starts (Workers.create in this process)."""
    ov = overrides(storage)
    workers = Workers(compose(ov), ov, out_dir=folder, log=lambda msg: None)
    workers.create()
    return workers


def start(storage, folder, n, first_index=0):
    logs = [open(folder / f"worker{first_index + i}.log", "a") for i in range(n)]
    procs = [subprocess.Popen([sys.executable, "-m", "studies.workers", "work", "--index", str(first_index + i),
                               *overrides(storage)], cwd=folder, stdout=log, stderr=subprocess.STDOUT)
             for i, log in enumerate(logs)]
    return procs


def finish(procs, folder):
    for p in procs:
        p.wait(RUN_TIMEOUT)
    codes = [p.returncode for p in procs]
    assert codes == [0] * len(procs), "\n".join(f.read_text() for f in sorted(folder.glob("worker*.log")))


def trials_of(workers):
    return optuna.load_study(study_name=study_name(workers.study), storage=workers.storage).get_trials()


def check_exact(workers):
    """BUDGET COMPLETE trials, one per slot, no design twice, nothing left RUNNING or WAITING;
    the report's dataset built from the storage holds each of them once."""
    trials = trials_of(workers)
    by = Counter(t.state for t in trials)
    done = [t for t in trials if t.state == TrialState.COMPLETE]
    assert len(done) == BUDGET and by[TrialState.RUNNING] == by[TrialState.WAITING] == 0, by
    assert sorted(t.user_attrs["slot"] for t in done) == list(range(BUDGET))
    names = workers.search.space.names
    assert len({design_key(t.params, names) for t in done}) == BUDGET
    assert all("skipped" in t.user_attrs for t in trials if t.state == TrialState.PRUNED)
    ds = verified_points(workers.search, trials)
    assert ds.sizes["design"] == BUDGET and list(ds.source.values[:8]) == ["initial"] * 8
    return trials


def test_three_workers_lose_no_trial_and_duplicate_none(postgres_url, tmp_path):
    workers = created(postgres_url, tmp_path)
    t0 = time.perf_counter()
    finish(start(postgres_url, tmp_path, 3), tmp_path)
    print(f"3 workers, {BUDGET} designs on PostgreSQL: {time.perf_counter() - t0:.1f} s")
    trials = check_exact(workers)
    assert Counter(t.state for t in trials)[TrialState.FAIL] == 0
    assert len({t.user_attrs["worker"] for t in trials if t.state == TrialState.COMPLETE}) >= 2  # shared work
    text, ds = workers.report()  # the report from the storage alone
    assert f"{BUDGET} of budget.max_simulations = {BUDGET}" in text and (tmp_path / "verified.nc").is_file()


def _running_trial_of(workers, pids):
    """A RUNNING trial that a worker in ``pids`` has claimed (its design is being simulated)."""
    for t in trials_of(workers):
        if t.state == TrialState.RUNNING and "worker" in t.user_attrs:
            pid = int(t.user_attrs["worker"].rsplit(":", 1)[1])
            if pid in pids:
                return t.number, pid
    return None


def test_worker_killed_mid_trial_is_failed_and_retried(postgres_url, tmp_path):
    """SIGSTOP freezes the worker while its trial is RUNNING (checked in the storage), SIGKILL
    kills it there; its trial is marked FAIL after the grace period and retried by another worker
    with the same design and slot; the count stays exact."""
    workers = created(postgres_url, tmp_path)
    procs = start(postgres_url, tmp_path, 3)
    pids = {p.pid: p for p in procs}
    deadline = time.monotonic() + RUN_TIMEOUT
    victim = None
    while victim is None and time.monotonic() < deadline:
        found = _running_trial_of(workers, pids)
        if found is None:
            time.sleep(0.01)
            continue
        number, pid = found
        os.kill(pid, signal.SIGSTOP)
        if next(t for t in trials_of(workers) if t.number == number).state == TrialState.RUNNING:
            os.kill(pid, signal.SIGKILL)
            victim = (number, pids.pop(pid))
        else:  # finished before it was frozen: try again
            os.kill(pid, signal.SIGCONT)
    assert victim is not None, "no RUNNING trial seen"
    victim[1].wait(30)
    assert victim[1].returncode == -signal.SIGKILL
    finish(list(pids.values()), tmp_path)
    trials = check_exact(workers)
    killed = next(t for t in trials if t.number == victim[0])
    assert killed.state == TrialState.FAIL
    retries = [t for t in trials if t.system_attrs.get("failed_trial") == killed.number]
    assert [t.state for t in retries] == [TrialState.COMPLETE]
    assert retries[0].params == killed.params and retries[0].user_attrs["slot"] == killed.user_attrs["slot"]


def test_study_resumed_after_all_workers_die_continues(postgres_url, tmp_path):
    workers = created(postgres_url, tmp_path)
    procs = start(postgres_url, tmp_path, 2)
    deadline = time.monotonic() + RUN_TIMEOUT
    while sum(t.state == TrialState.COMPLETE for t in trials_of(workers)) < 10 and time.monotonic() < deadline:
        time.sleep(0.05)
    for p in procs:
        os.kill(p.pid, signal.SIGKILL)
    for p in procs:
        p.wait(30)
    before = {t.number: t.value for t in trials_of(workers) if t.state == TrialState.COMPLETE}
    assert 10 <= len(before) < BUDGET
    workers = created(postgres_url, tmp_path)  # `create` again: checks the config, keeps everything
    finish(start(postgres_url, tmp_path, 2, first_index=2), tmp_path)
    trials = check_exact(workers)
    after = {t.number: t.value for t in trials if t.state == TrialState.COMPLETE}
    assert all(after[n] == v for n, v in before.items())  # nothing redone, nothing lost


def test_journal_storage_workers(tmp_path):
    storage = f"journal:{tmp_path / 'journal' / 'study.log'}"
    workers = created(storage, tmp_path)
    finish(start(storage, tmp_path, 2), tmp_path)
    check_exact(workers)


@pytest.mark.parametrize("backend", ["postgresql", "files"])
def test_claims_are_exact_under_contention(backend, request, tmp_path):
    """8 threads claim 40 designs (each twice) for 10 slots: 10 distinct designs get one slot each."""
    if backend == "postgresql":
        url = request.getfixturevalue("postgres_url")
        claims = RDBClaims(optuna.storages.RDBStorage(url).engine, "contention")
    else:
        claims = FileClaims(tmp_path / "claims")
    claims.create_table()
    won, lock = [], threading.Lock()

    def claimer(offset):
        for i in range(40):
            j = (i + offset) % 40
            slot, reason = claim(claims, f"x={j}", j, 10)
            if slot is not None:
                with lock:
                    won.append((j, slot))

    threads = [threading.Thread(target=claimer, args=(k * 5,)) for k in range(8)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    designs = {j for j, _ in won}
    assert len(designs) == 10 and sorted({s for _, s in won}) == list(range(10))
    # a design is claimed by its own chain: each claim of it (first or a later one) sees the same slot
    assert all(len({s for j2, s in won if j2 == j}) == 1 for j in designs)


def test_a_trial_still_being_suggested_has_no_known_design():
    """The race of a worker reading another's RUNNING trial between two suggest_float calls."""
    import optuna
    from studies.workers import known_design

    study = optuna.create_study()
    trial = study.ask()
    trial.suggest_float("PCR", 20.0, 150.0)
    frozen = study.trials[0]
    assert known_design(frozen, ("PCR", "aP")) is None
    trial.suggest_float("aP", 6.0, 18.0)
    x = known_design(study.trials[0], ("PCR", "aP"))
    assert x is not None and x.shape == (2,)
