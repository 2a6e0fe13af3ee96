"""Throughput of ``sim.api.simulate_batch`` and the per-call overhead of ``sim.simulate``.

Batch: 16 designs of the reference TSRB (PCR 80, 100, 120, 150 mm x kappa 0.93, 0.95, 0.97,
0.98) x 6 combined load cases (Fa 3000, 4500, 6000 N x Fr 1000, 2000 N, 2000 rpm, 55 degC),
friction on (the default config): 96 cases per batch. After one warm-up batch (the numba
kernels loaded from the on-disk cache, or compiled), ``--repeats`` timed batches, each of new
designs (PCR shifted by 1 um per repeat, so that no cached model or YAML of an earlier batch
serves it); reported are the median and best cases per second, on ``--workers`` processes
and, for comparison, in this process alone (``workers=1``, ``--serial-repeats`` batches),
with the target of 150 combined cases with friction per second on 2 cores, and the solver
wall time of the cases: the physics bound of the rate and the share of it reached.

Overhead: for the reference TSRB at Fa 4500 N, Fr 2000 N (one combined case), the medians
of ``--calls`` warm calls (interleaved: one of each per round) of

- physics: ``solve_case`` (the load distribution twice and the traction kinematics) with
  models built beforehand;
- ``sim.simulate(cfg)``: the whole call (config read, cached models and YAML, Dataset);
- its parts: ``OmegaConf.to_container`` (read once per call), ``OmegaConf.to_yaml`` (what the
  provenance cost per call before it was cached), ``sim.io.build_dataset``;

and the ratio simulate / physics (target <= 1.2). The machine may be shared: every number is
a median of repeats, and timings of the same run are comparable with each other.

Run from the repository root::

    python benchmarks/bench_batch.py [--repeats 5] [--workers N] [--calls 41]

Exit code 0 when every case of the batch converged and the batch equals ``workers=1``.
"""
import argparse
import os
import platform
import statistics
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent

PCR = (80.0, 100.0, 120.0, 150.0)      # mm
KAPPA = (0.93, 0.95, 0.97, 0.98)       # 1
LOAD = ["load.Fa=[3000,4500,6000]", "load.Fr=[1000,2000]"]   # 6 combined cases, default speed and oil
REFERENCE = ["bearing=tsrb_reference", "load.Fa=4500", "load.Fr=2000"]
TARGET_CASES_PER_S = 150.0
TARGET_RATIO = 1.2


def parse_args(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--repeats", type=int, default=5, help="timed batches after one warm-up (default 5)")
    p.add_argument("--serial-repeats", type=int, default=1, help="timed batches with workers=1 (default 1; 0: skip)")
    p.add_argument("--workers", type=int, default=None, help="processes (default: one per available core)")
    p.add_argument("--calls", type=int, default=41, help="timed calls per overhead item (default 41)")
    args = p.parse_args(argv)
    if args.repeats < 1 or args.calls < 1:
        p.error("--repeats and --calls must be >= 1")
    return args


def interleaved_ms(items, n):
    """Median ms of each callable of ``items`` (name -> f) over ``n`` rounds, one call of each per
    round, so that a load change on a shared machine hits all of them alike."""
    times = {name: [] for name in items}
    for _ in range(n):
        for name, f in items.items():
            t0 = time.perf_counter()
            f()
            times[name].append(time.perf_counter() - t0)
    return {name: 1e3 * statistics.median(t) for name, t in times.items()}


def timed(f, n):
    """(median s, best s, last result) of ``n`` calls of f."""
    times, out = [], None
    for _ in range(n):
        t0 = time.perf_counter()
        out = f()
        times.append(time.perf_counter() - t0)
    return statistics.median(times), min(times), out


def main(argv=None):
    args = parse_args(argv)
    for var in ("NUMBA_NUM_THREADS", "OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ.setdefault(var, "1")     # one thread per process: the workers are the parallelism
    if str(REPO) not in sys.path:
        sys.path.insert(0, str(REPO))
    from omegaconf import OmegaConf

    import sim
    from sim import io
    from sim.api import simulate_batch
    from sim.api.cases import operating_points
    from sim.api.simulation import build_friction, build_model, default_workers, solve_case

    workers = args.workers or default_workers()
    print("batch benchmark (sim.api.simulate_batch) and per-call overhead of sim.simulate")
    print(f"  git commit : {io.git_commit()}")
    print(f"  python     : {platform.python_version()}, {os.cpu_count()} cpus, {workers} workers, "
          f"load average {os.getloadavg()[0]:.2f}")
    print()

    # ------------------------------------------------------------------ overhead of one call
    cfg = sim.load_config(REFERENCE)
    sim.simulate(cfg)                                  # kernels and caches warm
    model = build_model(cfg)
    friction = build_friction(cfg, model)
    ops = operating_points(cfg.load)
    results = [solve_case(model, friction, op, cfg.output) for op in ops]
    text = OmegaConf.to_yaml(cfg, resolve=True)
    n = args.calls
    parts = interleaved_ms({
        "physics (solve_case)": lambda: [solve_case(model, friction, op, cfg.output) for op in ops],
        "simulate (whole call)": lambda: sim.simulate(cfg),
        "OmegaConf.to_container": lambda: OmegaConf.to_container(cfg, resolve=True),
        "OmegaConf.to_yaml (uncached)": lambda: OmegaConf.to_yaml(cfg, resolve=True),
        "build_model + build_friction (uncached)": lambda: build_friction(cfg, build_model(cfg)),
        "io.build_dataset": lambda: io.build_dataset(model.geometry, ops, results, text, model.settings),
    }, n)
    ratio = parts["simulate (whole call)"] / parts["physics (solve_case)"]
    print(f"per-call overhead, reference TSRB, one combined case, median of {n} warm calls, interleaved:")
    for name, ms in parts.items():
        print(f"  {name:42s} {ms:8.2f} ms")
    print(f"  {'ratio simulate / physics':42s} {ratio:8.2f}    (target <= {TARGET_RATIO})")
    print()

    # ------------------------------------------------------------------ the batch
    def designs(batch):
        """The 16 designs, PCR shifted by ``batch`` um: new content for every batch."""
        return [sim.load_config(["bearing=tsrb_reference", f"bearing.PCR={p + 1e-3 * batch}", f"bearing.kappa={k}",
                                 *LOAD]) for p in PCR for k in KAPPA]

    batches = iter(range(10**6))
    cfgs = designs(next(batches))
    n_cases = sum(len(operating_points(c.load)) for c in cfgs)
    print(f"batch: {len(cfgs)} designs x {n_cases // len(cfgs)} combined cases with friction = {n_cases} cases")
    t0 = time.perf_counter()
    simulate_batch(cfgs, workers=workers)
    print(f"  warm-up batch      : {time.perf_counter() - t0:6.2f} s")
    runs = [designs(next(batches)) for _ in range(args.repeats)]
    med, best, ds = timed(lambda: simulate_batch(runs.pop(0), workers=workers), args.repeats)
    cfgs = designs(args.repeats)   # the designs of the last timed batch
    rate = n_cases / med
    print(f"  {workers} workers          : median {med:6.3f} s, best {best:6.3f} s of {args.repeats} -> "
          f"{rate:6.1f} cases/s median, {n_cases / best:6.1f} best (target >= {TARGET_CASES_PER_S:.0f} on 2 cores)")
    converged = int(ds.converged.sum())
    print(f"  converged          : {converged} of {n_cases}; failed rows: {ds.sizes['failure']}")
    solver = float(ds.wall_time.sum())
    print(f"  solver wall time   : {solver:6.3f} s summed over the cases of the last batch "
          f"({1e3 * solver / n_cases:.1f} ms per case): at most {workers * n_cases / solver:6.1f} cases/s on "
          f"{workers} workers; the batch reached {100 * rate * solver / (workers * n_cases):.0f} % of it")
    same = True
    if args.serial_repeats > 0:
        serial = simulate_batch(cfgs, workers=1)   # the designs of ds, for the comparison
        runs = [designs(next(batches)) for _ in range(args.serial_repeats)]
        smed, sbest, _ = timed(lambda: simulate_batch(runs.pop(0), workers=1), args.serial_repeats)
        print(f"  1 worker (here)    : median {smed:6.3f} s -> {n_cases / smed:6.1f} cases/s; speed-up "
              f"{smed / med:.2f}x")
        a, b = (d.drop_vars("wall_time").drop_attrs() for d in (ds, serial))
        same = a.identical(b)
        print(f"  equal to workers=1 : {same}")
    print()
    ok = converged == n_cases and same
    print("OK" if ok else "FAILED")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
