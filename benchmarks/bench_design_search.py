"""Design-search benchmark (issue 16 item 4): every method, many seeds, against the reference optimum.

Methods, each started from an initial design of the same size (``study.initial_design.n``):

- ``surrogate``: the search of ``python -m studies.optimize`` (Sobol design, constrained BO on
  calibrated GP surrogates, verification rounds, final local COBYLA stage), its own budget;
- ``tpe``, ``gp``: Optuna's TPESampler / GPSampler asking for every point on the full simulation
  (constraints through ``Trial.set_constraint``), the first n trials random (``n_startup_trials``);
  ``gp`` needs PyTorch (``pip install -e ".[gp]"``) and is skipped without it;
- ``random``: Optuna's RandomSampler on the full simulation;
- ``cobyla``: multi-start COBYLA (:func:`studies.refine.local_refine`, the study's ``refine``
  radii) on the full simulation: the scrambled Sobol design of the study's size and seed, then
  local runs from its best distinct points (by :func:`studies.constraints.rank_key`), one after
  another until the budget is spent.

Each (method, seed) is measured against the stored reference optimum of the study
(``benchmarks/reference_optima/<study>.yaml``, made by ``python -m studies.reference_optimum``):
the full simulations and the wall time until the best feasible design so far is within 1 % and
within 0.1 % of it. Reported per method: median and range over the seeds (a run that never gets
there counts as not reached; a median over more than half such runs is "not reached"), and a
convergence figure (median and quartiles of the gap against simulations).

    python benchmarks/bench_design_search.py                       # pinion, 10 seeds, all methods
    python benchmarks/bench_design_search.py study=size_32208 --seeds 10 --budget 300
    python benchmarks/bench_design_search.py --methods surrogate cobyla --seeds 3
    python benchmarks/bench_design_search.py --stored-only     # the table and figure of what is stored

Every finished (method, seed) run is written at once to
``outputs/benchmarks/design_search/<study>/<method>_seed<k>.nc`` (atomically); a rerun loads
those and runs only the missing ones and those made by other simulation or search code or
another study config (:func:`run_fingerprint`), so an interrupted benchmark resumes. The summary goes to
``summary.md`` and ``convergence.png`` beside them. Wall times are measured on whatever machine
runs this, with ``study.n_jobs`` workers for the surrogate loop's batches and one process for the
direct methods: compare simulations first, seconds second.
"""
import argparse
import hashlib
import importlib.util
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import numpy as np  # noqa: E402
import optuna  # noqa: E402
import xarray as xr  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402
from omegaconf import OmegaConf  # noqa: E402

from sim.io import files_fingerprint, model_fingerprint, write_bytes_atomic, write_figure_atomic, write_netcdf_atomic  # noqa: E402
from studies.config import compose  # noqa: E402
from studies.constraints import rank_key  # noqa: E402
from studies.evaluate import STATUS, design_matrix  # noqa: E402
from studies.loop import DesignSearch, round_seed  # noqa: E402
from studies.reference_optimum import DISTINCT_STARTS  # noqa: E402
from studies.refine import distinct_starts, local_refine  # noqa: E402
from studies.search import make_sampler, open_study, run_trials  # noqa: E402

METHODS = ("surrogate", "tpe", "gp", "random", "cobyla")
TARGETS = (1e-2, 1e-3)     # relative gaps to the reference optimum: 1 % and 0.1 % (issue 16 item 4)


class Trace:
    """Design, objective, feasibility and the wall clock at each full simulation of one run."""

    def __init__(self):
        self.t0 = time.perf_counter()
        self.x, self.y, self.feasible, self.t = [], [], [], []

    def add(self, x, y, feasible):
        self.x.append(np.asarray(x, dtype=float))
        self.y.append(float(y))
        self.feasible.append(bool(feasible))
        self.t.append(time.perf_counter() - self.t0)


def point_values(search, part):
    """(objective or NaN, margins) of each point of a points dataset."""
    M = search.point_margins(part)
    f = np.where(part.status.values == STATUS["ok"], search.objective_values(part), np.nan)
    return f, M


def surrogate_run(search, trace):
    """The surrogate loop, each simulated batch timed when it finishes."""
    simulate = search.simulate

    def timed(X, source, round_index):
        part = simulate(X, source, round_index)
        for x, f, m in zip(design_matrix(part, search.space), *point_values(search, part)):
            trace.add(x, f, np.isfinite(f) and np.all(m <= 0.0))
        return part

    search.simulate = timed
    search.run()


def direct_run(search, sampler_for, budget, trace):
    """An Optuna sampler on the full simulation (``sampler_for(k)``: the sampler after k trials)."""
    def evaluate(trial):
        value, m, attrs = search.simulation_trial(trial)
        trace.add(search.space.from_params(trial.params),
                  attrs["values"][search.objective] if attrs["status"] == "ok" else np.nan, max(m) <= 0.0)
        return value, m, attrs

    study = open_study(optuna.storages.InMemoryStorage(), "direct", sampler_for(0))
    run_trials(study, budget, evaluate, sampler_for)


def cobyla_run(search, seed, budget, trace):
    """Multi-start COBYLA from the study-size Sobol design (see the module docstring)."""
    s = search.study
    space = search.space
    span = space.high - space.low
    seen = {}

    def simulate(X):
        part = search.simulate(X, "initial", 0)
        for x, f, m in zip(X, *point_values(search, part)):
            seen[x.tobytes()] = (f, m)
            trace.add(x, f, np.isfinite(f) and np.all(m <= 0.0))

    X0 = space.sample(int(s.initial_design.n), "sobol", seed)
    simulate(X0)

    class Spent(Exception):
        pass

    def evaluate(u):
        x = space.low + u * span
        if x.tobytes() not in seen:
            if len(trace.y) >= budget:
                raise Spent
            simulate(x[None, :])
        return seen[x.tobytes()]

    order = sorted(range(len(X0)), key=lambda i: rank_key(*seen[X0[i].tobytes()]))
    starts = distinct_starts(space.unit(X0[order]), len(order), DISTINCT_STARTS)
    r = s.refine
    for u0 in starts:
        try:
            local_refine(evaluate, u0, search.limits.names, budget, float(r.initial_step), float(r.final_step),
                         float(r.active_tolerance))
        except Spent:
            return


def reach(y, feasible, t, reference, gap):
    """(simulations, seconds) until the best feasible value is within ``gap`` of ``reference``
    (None, None if never)."""
    ok = np.flatnonzero(np.asarray(feasible) & (np.asarray(y) <= reference * (1.0 + gap)))
    return (int(ok[0]) + 1, float(t[ok[0]])) if ok.size else (None, None)


def best_so_far_gap(y, feasible, reference):
    """Relative gap of the best feasible value so far to the reference after each simulation (inf before any)."""
    v = np.where(np.asarray(feasible), np.asarray(y, dtype=float), np.inf)
    return np.minimum.accumulate(v) / reference - 1.0


# sources that decide a run besides the simulation (sim/, sim.io.model_fingerprint): the search code
SEARCH_SOURCES = ("studies", "surrogate")


def run_fingerprint(cfg):
    """SHA-256 of what decides a run: the simulation code (:func:`sim.io.model_fingerprint`), the
    search code (``SEARCH_SOURCES``) and the composed study config; a stored run with another one
    is run again (a changed local stage or budget makes the old runs a different method)."""
    search = files_fingerprint(REPO, [p for folder in SEARCH_SOURCES for p in sorted((REPO / folder).rglob("*.py"))])
    study = OmegaConf.to_yaml(cfg.study, resolve=True)
    return hashlib.sha256(f"{model_fingerprint()}\n{search}\n{study}".encode()).hexdigest()


def run_one(method, seed, overrides, budget, n0, reference, fingerprint):
    """One (method, seed) run in a fresh folder -> Dataset of its trace (``fingerprint``: its
    :func:`run_fingerprint`, stored with it)."""
    with tempfile.TemporaryDirectory() as tmp:
        ov = list(overrides) + [f"study.seed={seed}"]
        search = DesignSearch(compose(ov), ov, out_dir=tmp, log=lambda msg: None)
        search.run_references()
        trace = Trace()
        settings = {"n_startup_trials": n0, "population_size": n0}
        if method == "surrogate":
            surrogate_run(search, trace)
        elif method == "cobyla":
            cobyla_run(search, seed, budget, trace)
        elif method == "random":
            direct_run(search, lambda k: optuna.samplers.RandomSampler(seed=round_seed(seed, 0, k)), budget, trace)
        else:
            direct_run(search, lambda k: make_sampler(method, round_seed(seed, 0, k), settings), budget, trace)
        names = search.space.names
    return xr.Dataset(
        {"objective_value": ("simulation", np.array(trace.y), {"units": reference[1],
                                                               "long_name": f"{reference[2]} of each full simulation"}),
         "feasible": ("simulation", np.array(trace.feasible), {"long_name": "all constraints satisfied"}),
         "elapsed": ("simulation", np.array(trace.t), {"units": "s", "long_name": "wall time when the simulation "
                                                                                  "finished, from the run's start"}),
         "design": (("simulation", "parameter"), np.array(trace.x).reshape(len(trace.x), len(names)),
                    {"long_name": "free design parameters of the simulated design (study units)"})},
        coords={"simulation": np.arange(1, len(trace.y) + 1), "parameter": list(names)},
        attrs={"method": method, "seed": seed, "budget": budget, "initial_design": n0,
               "model_fingerprint": model_fingerprint(), "run_fingerprint": fingerprint})


def summary(runs, reference, out):
    """Markdown table of the medians and ranges, and the convergence figure."""
    ref = reference[0]
    lines = [f"Reference optimum {reference[2]} {ref:.6g} {reference[1]} ({reference[3]}).", "",
             "| method | seeds | " + " | ".join(f"sims to {100 * g:g} %: median [min, max], reached"
                                              f" | wall to {100 * g:g} % [s]: median" for g in TARGETS)
             + " | final gap [%]: median [min, max] | simulations per run: median |",
             "| --- | --- | " + " | ".join("--- | ---" for _ in TARGETS) + " | --- | --- |"]
    fig = Figure(figsize=(7.5, 4.8))
    ax = fig.subplots()
    for method, by_seed in runs.items():
        cells = []
        for g in TARGETS:
            hits = [reach(d.objective_value.values, d.feasible.values, d.elapsed.values, ref, g) for d in by_seed]
            n = np.array([h[0] if h[0] is not None else np.inf for h in hits], dtype=float)
            w = np.array([h[1] if h[1] is not None else np.inf for h in hits], dtype=float)
            reached = int(np.isfinite(n).sum())
            med = float(np.median(n))
            rng = (f"[{np.min(n):.0f}, {np.max(n):.0f}]" if reached == len(n) else
                   f"[{np.min(n):.0f}, not reached]" if reached else "")
            cells.append(f"{med:.0f} {rng}, {reached}/{len(n)}" if np.isfinite(med) else f"not reached {rng}, "
                         f"{reached}/{len(n)}")
            cells.append(f"{np.median(w):.0f}" if np.isfinite(np.median(w)) else "-")
        final = np.array([best_so_far_gap(d.objective_value.values, d.feasible.values, ref)[-1] for d in by_seed])
        lines.append(f"| {method} | {len(by_seed)} | " + " | ".join(cells) +
                     f" | {100 * np.median(final):.2f} [{100 * np.min(final):.2f}, {100 * np.max(final):.2f}] | "
                     f"{np.median([d.sizes['simulation'] for d in by_seed]):.0f} |")
        n = max(d.sizes["simulation"] for d in by_seed)
        G = np.array([np.pad(best_so_far_gap(d.objective_value.values, d.feasible.values, ref),
                             (0, n - d.sizes["simulation"]), mode="edge") for d in by_seed])
        G = np.clip(G, 1e-5, 10.0)            # before the first feasible design: drawn at the top (1000 %)
        x = np.arange(1, n + 1)
        line, = ax.plot(x, 100 * np.median(G, axis=0), label=f"{method} (median of {len(by_seed)})")
        ax.fill_between(x, 100 * np.quantile(G, 0.25, axis=0), 100 * np.quantile(G, 0.75, axis=0),
                        color=line.get_color(), alpha=0.15)
    for g in TARGETS:
        ax.axhline(100 * g, color="0.4", lw=0.8, ls="--")
    ax.set_yscale("log")
    ax.set_xlabel("full simulations [1]")
    ax.set_ylabel("gap of the best feasible design to the reference optimum [%]\n(1000 %: no feasible design yet)",
                  fontsize=9)
    ax.set_title(f"{reference[3]}\nbest feasible design so far (line: median, band: quartiles over seeds)",
                 fontsize=9)
    ax.legend(fontsize=8)
    fig.tight_layout()
    write_figure_atomic(fig, out / "convergence.png", 120)
    text = "\n".join(lines) + "\n"
    write_bytes_atomic(out / "summary.md", text.encode())
    return text


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("overrides", nargs="*", help="study overrides as for python -m studies.optimize")
    parser.add_argument("--methods", nargs="+", default=list(METHODS), choices=METHODS)
    parser.add_argument("--seeds", type=int, default=10, help="seeds 0..N-1 per method (default 10)")
    parser.add_argument("--first-seed", type=int, default=0,
                        help="run seeds first..N-1 only (default 0), e.g. a second process on the same --out folder")
    parser.add_argument("--budget", type=int, default=300,
                        help="full simulations per run of the direct methods and COBYLA (default 300); the "
                             "surrogate loop keeps the study's budget and local stage")
    parser.add_argument("--stored-only", action="store_true",
                        help="summarise the runs already stored (as many seeds as each method has), run nothing")
    parser.add_argument("--reference", type=Path, help="reference optimum YAML (default "
                                                       "benchmarks/reference_optima/<study name>.yaml)")
    parser.add_argument("--out", type=Path, help="folder of the stored runs and the summary (default "
                                                 "outputs/benchmarks/design_search/<study name>), e.g. one per variant")
    args = parser.parse_args(argv)
    optuna.logging.set_verbosity(optuna.logging.WARNING)
    cfg = compose(args.overrides)
    name = str(cfg.study.name)
    path = args.reference or REPO / "benchmarks" / "reference_optima" / f"{name}.yaml"
    if not path.is_file():
        print(f"error: no reference optimum {path}: run python -m studies.reference_optimum "
              f"{' '.join(args.overrides)} --out {path}", file=sys.stderr)
        return 2
    stored = OmegaConf.load(path)
    if str(stored.objective) != str(cfg.study.objective):
        print(f"error: {path} is an optimum of {stored.objective}, the study minimises {cfg.study.objective}",
              file=sys.stderr)
        return 2
    units = {"Fa": "N", "Fr": "N", "speed": "rpm", "tilt": "deg", "oil_temperature": "degC"}
    load = ", ".join(f"{k} {float(v):g} {units[k]}" for k, v in stored.load_case.items())
    reference = (float(stored.value), str(stored.objective_units), str(stored.objective), f"study {name}, {load}")
    n0 = int(cfg.study.initial_design.n)
    out = args.out or REPO / "outputs" / "benchmarks" / "design_search" / name
    methods = [m for m in args.methods if m != "gp" or importlib.util.find_spec("torch") is not None]
    if len(methods) < len(args.methods):
        print("gp: skipped (Optuna's GPSampler needs PyTorch: pip install -e \".[gp]\")")
    fingerprint = run_fingerprint(cfg)
    runs = {}
    for method in methods:
        runs[method] = []
        for seed in range(args.first_seed, args.seeds):
            file = out / f"{method}_seed{seed}.nc"
            ds = xr.load_dataset(file) if file.is_file() else None
            if ds is not None and ds.attrs.get("run_fingerprint") != fingerprint:
                print(f"{file}: computed by another version of the simulation or search code or study config "
                      f"(run_one's run_fingerprint): {'left out' if args.stored_only else 'run again'}", flush=True)
                ds = None
            if ds is None and args.stored_only:
                continue
            if ds is None:
                t0 = time.perf_counter()
                ds = run_one(method, seed, args.overrides, args.budget, n0, reference, fingerprint)
                write_netcdf_atomic(ds, file)
                hit = reach(ds.objective_value.values, ds.feasible.values, ds.elapsed.values, reference[0], TARGETS[0])
                print(f"{method} seed {seed}: {ds.sizes['simulation']} simulations in {time.perf_counter() - t0:.0f} s; "
                      f"within 1 % after {hit[0] or 'never'}", flush=True)
            runs[method].append(ds)
    runs = {m: r for m, r in runs.items() if r}
    if not runs:
        print(f"no stored runs of this simulation code in {out}/")
        return 0
    print(summary(runs, reference, out))
    print(f"written to {out}/")
    return 0


if __name__ == "__main__":
    sys.exit(main())
