"""Design-search benchmark (issue 5, item 7): surrogate-assisted search against Optuna on the full simulation.

At an equal budget of full simulations (``study.budget.max_simulations`` or ``--budget``), it runs

- ``surrogate``: the search of ``python -m studies.optimize`` (space-filling design, GP
  surrogates, Optuna on the surrogates, verification rounds), in a fresh temporary folder;
- ``tpe``, ``gp``: Optuna's TPESampler / GPSampler asking for every point directly, each
  told the full simulation's objective and constraint margins (studies.loop.DesignSearch.
  simulation_trial; GP needs PyTorch and is skipped without it);

and prints, per method, the full simulations needed to come within ``--tolerance`` (1 %) of
the best verified feasible objective found by any method, the first feasible simulation,
the best value and the wall time. The traces go to a NetCDF file. Run from the repository root::

    python benchmarks/bench_design_search.py [study overrides ...] [--budget N] [--samplers tpe gp]
    python benchmarks/bench_design_search.py study=size_32208 study.objective=pmax

The comparison is in simulations, not seconds: the surrogate search runs its initial design
in ``study.n_jobs`` processes, the direct searches one simulation at a time.
"""
import argparse
import importlib.util
import platform
import sys
import tempfile
import time
from importlib import metadata
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

import numpy as np  # noqa: E402
import optuna  # noqa: E402
import xarray as xr  # noqa: E402

from sim.io import write_netcdf_atomic  # noqa: E402
from studies.config import compose  # noqa: E402
from studies.loop import DesignSearch, round_seed  # noqa: E402
from studies.search import make_sampler, open_study, run_trials, trial_margins  # noqa: E402


def surrogate_trace(search):
    """Objective and feasibility of every full simulation of the surrogate-assisted search, in order."""
    ds, _ = search.run()
    feasible = np.all(search.point_margins(ds) <= 0.0, axis=1)
    return ds[search.objective].values, feasible


def direct_trace(search, sampler, budget, every=10):
    """Objective and feasibility of each trial of Optuna ``sampler`` on the full simulation
    (a progress line every ``every`` simulations)."""
    s = search.study
    t0 = time.perf_counter()

    def evaluate(trial):
        if trial.number and trial.number % every == 0:
            print(f"    {sampler}: {trial.number}/{budget} simulations, {time.perf_counter() - t0:.0f} s", flush=True)
        return search.simulation_trial(trial)

    study = open_study(optuna.storages.InMemoryStorage(), f"direct-{sampler}",
                       make_sampler(sampler, round_seed(s.seed, 0, 0), s.sampler_settings))
    trials = run_trials(study, budget, evaluate,
                        lambda k: make_sampler(sampler, round_seed(s.seed, 0, k), s.sampler_settings))
    y = np.array([t.user_attrs["values"][search.objective] for t in trials], dtype=float)
    feasible = np.array([max(trial_margins(t)) <= 0.0 for t in trials])
    return y, feasible


def first_index(mask):
    """1-based position of the first True (None if none)."""
    hits = np.flatnonzero(mask)
    return int(hits[0]) + 1 if len(hits) else None


def cpu_name():
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("overrides", nargs="*", help="study overrides as for python -m studies.optimize")
    parser.add_argument("--budget", type=int, help="full simulations per method (default study.budget.max_simulations)")
    parser.add_argument("--samplers", nargs="+", default=["tpe", "gp"], choices=["tpe", "gp", "nsga2"],
                        help="Optuna samplers run directly on the simulation")
    parser.add_argument("--tolerance", type=float, default=0.01, help="relative distance to the best (0.01 = 1 %%)")
    parser.add_argument("--netcdf", type=Path, default=REPO / "outputs" / "benchmarks" / "design_search.nc")
    args = parser.parse_args(argv)
    optuna.logging.set_verbosity(optuna.logging.WARNING)

    with tempfile.TemporaryDirectory() as tmp:
        overrides = list(args.overrides)
        if args.budget is not None:
            overrides.append(f"study.budget.max_simulations={args.budget}")
        cfg = compose(overrides)
        budget = int(cfg.study.budget.max_simulations)
        search = DesignSearch(cfg, overrides, out_dir=tmp, log=lambda msg: None)
        t0 = time.perf_counter()
        search.run_references()
        print(f"tsrb-workbench {_version('tsrb-workbench')}, "
              f"commit {search.references['reference TRB'].ds.attrs.get('git_commit', 'unknown')[:12]}, "
              f"optuna {optuna.__version__}, scikit-learn {_version('scikit-learn')}, "
              f"numba {_version('numba')}")
        print(f"CPU {cpu_name()}, {cfg.solver.n_slices} slices; study {cfg.study.name}, objective "
              f"{search.objective}, budget {budget} full simulations per method, references "
              f"{time.perf_counter() - t0:.1f} s")
        traces, walls = {}, {}
        methods = ["surrogate"] + [s for s in args.samplers
                                   if s != "gp" or importlib.util.find_spec("torch") is not None]
        for method in methods:
            t0 = time.perf_counter()
            traces[method] = surrogate_trace(search) if method == "surrogate" else direct_trace(search, method, budget)
            walls[method] = time.perf_counter() - t0
            print(f"  {method}: {len(traces[method][0])} simulations in {walls[method]:.1f} s", flush=True)
        if "gp" in args.samplers and "gp" not in methods:
            print("  gp: skipped (Optuna's GPSampler needs PyTorch)")

    best = min((float(np.min(y[f])) for y, f in traces.values() if f.any()), default=np.nan)
    target = best * (1.0 + args.tolerance) if np.isfinite(best) else np.nan
    units = search.references["reference TRB"].record["attrs"].get(search.objective, {}).get("units", "")
    print(f"\nbest verified feasible {search.objective}: {best:.6g} {units}; target within "
          f"{100 * args.tolerance:g} %: {target:.6g}")
    print(f"{'method':<10} {'sims':>5} {'wall [s]':>9} {'first feasible':>15} {'within tol.':>12} "
          f"{'best feasible':>14} {'dev. [%]':>9}")
    rows = {}
    for method, (y, f) in traces.items():
        best_m = float(np.min(y[f])) if f.any() else np.nan
        rows[method] = (first_index(f), first_index(f & (y <= target)), best_m)
        print(f"{method:<10} {len(y):>5} {walls[method]:>9.1f} {str(rows[method][0] or '-'):>15} "
              f"{str(rows[method][1] or '-'):>12} {best_m:>14.6g} {100 * (best_m / best - 1.0):>9.2f}")
    for label, ref in search.references.items():
        print(f"{label} {ref.bearing}: {search.objective} {ref.record['values'][search.objective]:.6g} {units}")

    n = max(len(y) for y, _ in traces.values())
    pad = {m: (np.pad(y, (0, n - len(y)), constant_values=np.nan), np.pad(f, (0, n - len(f))))
           for m, (y, f) in traces.items()}
    out = xr.Dataset(
        {search.objective: (("method", "simulation"), np.array([pad[m][0] for m in traces]), {"units": units}),
         "feasible": (("method", "simulation"), np.array([pad[m][1] for m in traces]),
                      {"long_name": "all constraints satisfied"}),
         "simulations_to_tolerance": ("method", [rows[m][1] or -1 for m in traces],
                                      {"units": "1", "long_name": "full simulations to within tolerance of the "
                                                                  "best (-1: never)"}),
         "wall_time": ("method", [walls[m] for m in traces], {"units": "s"})},
        coords={"method": list(traces), "simulation": np.arange(1, n + 1)},
        attrs={"Conventions": "CF-1.10", "title": "design-search benchmark", "study": str(cfg.study.name),
               "objective": search.objective, "budget": budget, "tolerance": args.tolerance,
               "best_feasible": best, "cpu": cpu_name()})
    write_netcdf_atomic(out, args.netcdf)
    print(f"written: {args.netcdf}")
    return 0


def _version(package):
    try:
        return metadata.version(package)
    except metadata.PackageNotFoundError:
        return "(not installed)"


if __name__ == "__main__":
    sys.exit(main())
