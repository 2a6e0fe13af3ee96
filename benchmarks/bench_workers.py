"""Speed-up of the design search with N worker processes on one study (issue 17, item 6).

For each N of ``--workers`` (default 1 2 4) and each repeat, a fresh study in a fresh temporary
storage (``--storage journal`` in a temporary folder, or ``--storage <RDB URL>`` whose database
must be empty and is reused, one study name per run) is created once
(``studies.workers.Workers.create``: references, initial design queued), then N
``python -m studies.workers work`` processes run it to ``study.budget.max_simulations``; the time
from the start of the workers to the end of the last is measured. Prints the median per N, the
speed-up against N = 1 and the simulations per minute. Run from the repository root::

    python benchmarks/bench_workers.py [study overrides ...] [--workers 1 2 4] [--repeats 3]
    python benchmarks/bench_workers.py --storage postgresql+psycopg://user@host:5432/db

The default study is the pinion search with a budget of 48 simulations (16 initial), so one run
takes a minute or two; a worker's start-up (imports, numba cache load) is part of the time, as in
real use.
"""
import argparse
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

import optuna  # noqa: E402
from optuna.trial import TrialState  # noqa: E402

from studies.config import compose  # noqa: E402
from studies.workers import Workers, study_name  # noqa: E402

DEFAULT = ["study.initial_design.n=16", "study.budget.max_simulations=48",
           "study.n_jobs=1"]


def one_run(overrides, n, folder):
    workers = Workers(compose(overrides), overrides, out_dir=folder, log=lambda msg: None)
    workers.create()
    t0 = time.perf_counter()
    procs = [subprocess.Popen([sys.executable, "-m", "studies.workers", "work", "--index", str(i), *overrides],
                              cwd=folder, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL) for i in range(n)]
    codes = [p.wait() for p in procs]
    wall = time.perf_counter() - t0
    if any(codes):
        raise SystemExit(f"a worker failed: exit codes {codes}")
    trials = optuna.load_study(study_name=study_name(workers.study), storage=workers.storage).get_trials()
    return wall, sum(t.state == TrialState.COMPLETE for t in trials)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("overrides", nargs="*")
    parser.add_argument("--workers", type=int, nargs="+", default=[1, 2, 4])
    parser.add_argument("--repeats", type=int, default=1)
    parser.add_argument("--storage", default="journal")
    args = parser.parse_intermixed_args()
    print(f"{platform.node()}, {platform.processor() or platform.machine()}, python {platform.python_version()}")
    rows = []
    for n in args.workers:
        walls = []
        for r in range(args.repeats):
            with tempfile.TemporaryDirectory(prefix="bench-workers-") as tmp:
                storage = f"journal:{tmp}/study.log" if args.storage == "journal" else args.storage
                name = f"bench_{n}_{r}_{int(time.time())}"
                overrides = [*DEFAULT, *args.overrides, f"study.storage={storage}", f"study.name={name}"]
                wall, done = one_run(overrides, n, Path(tmp))
                walls.append(wall)
                print(f"  {n} workers, run {r + 1}: {wall:.1f} s, {done} simulations, load average after "
                      f"{os.getloadavg()[0]:.1f} on {os.cpu_count()} cores", flush=True)
        rows.append((n, statistics.median(walls), done))
    base = rows[0][1]
    print("\n| workers | wall [s] (median) | speed-up | simulations / min |\n| --- | --- | --- | --- |")
    for n, wall, done in rows:
        print(f"| {n} | {wall:.1f} | {base / wall:.2f} | {60 * done / wall:.1f} |")


if __name__ == "__main__":
    main()
