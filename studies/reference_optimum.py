"""Reference optimum of a design study (issue 16 item 3): dense sampling plus multi-start local
refinement on the full simulation, the yardstick the search benchmark measures every method against.

    python -m studies.reference_optimum                              # the pinion study
    python -m studies.reference_optimum study=size_32208 --sobol 2048 --starts 16
    python -m studies.reference_optimum --out benchmarks/reference_optima/pinion.yaml

1. Dense sampling: ``--sobol`` scrambled Sobol points over the study box (seed ``--seed``, not
   the study's own, so the search under test never starts from the reference's sample), each a
   full simulation, judged by the study's constraints (:mod:`studies.constraints`).
2. Multi-start refinement: COBYLA under every constraint (:func:`studies.refine.local_refine`,
   the study's ``refine`` trust radii, at most ``--max-per-start`` simulations each) from the
   ``--starts`` best distinct sampled points by :func:`studies.constraints.rank_key` (feasible by
   objective, then the least violation: the pinion study's feasible region is a sliver of
   ~0.03 % of its box, so most starts are infeasible points next to it), from the study's
   template design and, with ``--from-runs``, from the best design of every stored run of the
   search benchmark (the size_32208 landscape is rugged enough that one benchmark run found a
   design 4.7 % below the best of 33 starts from the sample), and with ``--from-reference`` from
   a stored reference optimum (after a physics change that moves it a little).
3. Polish: COBYLA again from the best point with smaller first steps, while that improves it.
4. The reference optimum is the best point of all by rank_key. It is reported with its active
   constraints and bounds and with the spread of the starts' ends: how many reached it within
   0.1 % and 1 %, which says how multi-modal the sliver is and how far one COBYLA run can be
   trusted.

Every simulated point is stored in ``outputs/studies/<name>/reference/points.nc`` (atomic
rewrites after each chunk of the sample and after each local simulation; no pickle), and a rerun
looks every point up there before simulating it: an interrupted run resumes and a completed one
repeats no simulation. The result is written as YAML (``--out``) with the command line, the
package commit, the simulation config and every number needed to re-simulate the design; the
tests re-simulate the stored optima (tests/studies/test_reference_optima.py), so a physics change
that moves them fails there and says to run this command again.
"""
import argparse
import shlex
import sys
import time
from pathlib import Path

import numpy as np
import xarray as xr
from omegaconf import OmegaConf

from sim.api import InputError
from sim.io import utc_now, write_bytes_atomic, write_netcdf_atomic
from studies.constraints import rank_key, violation
from studies.evaluate import STATUS, design_matrix, table_to_file
from sim.api.cli import refused
from studies.optimize import STUDY_ERRORS, elapsed_log, prepared_search
from studies.refine import distinct_starts, local_refine

SOURCE_SAMPLE = "reference_sobol"     # ``source`` of the dense sample's points in points.nc
SOURCE_LOCAL = "reference_local"      # ``source`` of the local runs' points
# Relative distances to the best objective at which a start's end counts as having reached it:
# the 0.1 % and 1 % of issue 16 item 4's benchmark targets.
REACHED = (1e-3, 1e-2)
# Sample points simulated (in study.n_jobs processes) between two writes of points.nc: a kill
# loses at most this many, and a rewrite of a few thousand points (~50 ms) stays small against
# the chunk's simulations (~3 s on 2 cores), engineering choice.
SAMPLE_CHUNK = 64
# Unit-cube distance below which two sampled points count as one start (COBYLA from both would
# retrace one path): 2 % of each range, 10x the trust radius the study's refine stage starts with
# on the pinion study (initial_step 0.05 is 5 % of each range; 0.02 keeps starts that are closer
# than one first step apart from being counted twice), engineering choice.
DISTINCT_STARTS = 0.02


class PointStore:
    """Every simulated point of one reference run, keyed by its exact coordinates."""

    def __init__(self, search):
        self.search = search
        self.path = search.out / "reference" / "points.nc"
        self.ds = None
        self.index = {}
        if self.path.is_file():
            self._set(search.own_points(self.path, "delete"))

    def _set(self, ds):
        self.ds = ds
        self.index = {x.tobytes(): i for i, x in enumerate(design_matrix(ds, self.search.space))}

    def _add(self, part):
        ds = part if self.ds is None else xr.concat([self.ds, part], dim="design", combine_attrs="override",
                                                    data_vars="all")
        write_netcdf_atomic(table_to_file(ds), self.path)
        self._set(ds)

    def simulate(self, X, source):
        """Simulate the rows of X not stored yet (n_jobs processes) and store them in one write."""
        new = [x for x in np.atleast_2d(X) if x.tobytes() not in self.index]
        if new:
            self._add(self.search.simulate(np.array(new), source, 0))

    def row(self, x):
        """(objective (NaN without result), margins) of the stored point x."""
        p = self.ds.isel(design=[self.index[np.asarray(x, dtype=float).tobytes()]])
        ok = int(p.status.values[0]) == STATUS["ok"]
        return (float(self.search.objective_values(p)[0]) if ok else np.nan), self.search.point_margins(p)[0]

    def ranked(self, X):
        """(X, objectives, margins) of the stored points among the rows of ``X``, best first by rank_key."""
        ds = self.ds.isel(design=sorted({self.index[x.tobytes()] for x in X}))
        X = design_matrix(ds, self.search.space)
        M = self.search.point_margins(ds)
        f = np.where(ds.status.values == STATUS["ok"], self.search.objective_values(ds), np.nan)
        order = sorted(range(len(X)), key=lambda i: rank_key(f[i], M[i]))
        return X[order], f[order], M[order]


def run_bests(folder, names):
    """The best feasible design (free parameters in ``names`` order) of every search-benchmark run
    stored in ``folder`` (benchmarks/bench_design_search.py: ``design``, ``objective_value``,
    ``feasible`` on ``simulation``), as (label, x)."""
    out = []
    for path in sorted(Path(folder).glob("*.nc")):
        with xr.open_dataset(path) as ds:
            if "design" not in ds or not ds.feasible.values.any():
                continue
            y = np.where(ds.feasible.values, ds.objective_value.values, np.inf)
            i = int(np.argmin(y))
            x = ds.design.sel(parameter=list(names)).values[i]
        out.append((f"best of {path.stem}", np.asarray(x, dtype=float)))
    return out


def stored_optimum(path, search):
    """The design of a stored reference optimum (this module's YAML, e.g. the previous one after a
    physics change, whose optimum has moved only a little) as one (label, x) start; a file of another
    study, or without a value for a free parameter, is refused naming the file and what differs."""
    ref = OmegaConf.to_container(OmegaConf.load(path))
    study = str(search.study.name)
    if ref.get("study") != study:
        raise InputError(f"--from-reference {path}: the optimum of study {ref.get('study')!r}, not of {study!r}")
    missing = [n for n in search.space.names if n not in ref.get("design", {})]
    if missing:
        raise InputError(f"--from-reference {path}: no value for the free parameter(s) {missing}")
    x = np.array([float(ref["design"][n]) for n in search.space.names])
    return f"stored optimum of {Path(path).name} (commit {str(ref.get('git_commit', 'unknown'))[:7]})", x


def run(search, n_sobol, seed, n_starts, max_per_start, log, extra_starts=()):
    """The reference optimum of ``search`` (references already run); returns the result dict.
    ``extra_starts``: (label, x) of further local-run starts (e.g. :func:`run_bests`)."""
    space = search.space
    span = space.high - space.low
    store = PointStore(search)
    stored_before = 0 if store.ds is None else store.ds.sizes["design"]
    t0 = time.perf_counter()
    X = space.sample(n_sobol, "sobol", seed)
    for start in range(0, n_sobol, SAMPLE_CHUNK):
        store.simulate(X[start:start + SAMPLE_CHUNK], SOURCE_SAMPLE)
        log(f"dense sample: {min(start + SAMPLE_CHUNK, n_sobol)} of {n_sobol} points")
    Xs, fs, Ms = store.ranked(X)
    n_feasible = int(sum(violation(m) == 0.0 and np.isfinite(f) for f, m in zip(fs, Ms)))
    log(f"dense sample: {n_feasible} feasible of {n_sobol} ({time.perf_counter() - t0:.0f} s)")

    starts = distinct_starts(space.unit(Xs), n_starts, DISTINCT_STARTS)
    labels = [f"sample rank {k + 1}" for k in range(len(starts))]
    template = space.unit(np.array([space.template[n] for n in space.names]))[0]
    starts.append(np.clip(template, 0.0, 1.0))
    labels.append("template design")
    for label, x in extra_starts:
        starts.append(np.clip(space.unit(x)[0], 0.0, 1.0))
        labels.append(label)
    r = search.study.refine

    # the points this run has evaluated, in order: a rerun against a fuller store replays the same
    # sequence only if every choice (the polish starts) is made among these, not among all stored
    visited = list(X)

    def evaluate(u):
        x = space.low + u * span
        store.simulate(x[None, :], SOURCE_LOCAL)
        visited.append(x)
        return store.row(x)

    ends = []
    for k, (label, u0) in enumerate(zip(labels, starts)):
        res = local_refine(evaluate, u0, search.limits.names, max_per_start, float(r.initial_step),
                           float(r.final_step), float(r.active_tolerance))
        ends.append((label, u0, res))
        log(f"start {k + 1} of {len(starts)} ({label}): {res.evaluations} points, {search.objective} "
            f"{res.start_value:.6g} -> {res.value:.6g} ({'feasible' if res.feasible else 'infeasible'})")

    # polish: COBYLA again from the best point of all starts, as the study's local stage restarts
    # (refine.restarts runs at most, each first step refine.restart_shrink times the previous one,
    # while a run improves on the best: one trust-region run is not trusted to have converged)
    Xa, fa, Ma = store.ranked(visited)
    if int(r.restarts) > 0:
        shrink = float(r.restart_shrink)
        res = local_refine(evaluate, space.unit(Xa[0])[0], search.limits.names, max_per_start * int(r.restarts),
                           float(r.initial_step) * shrink, float(r.final_step), float(r.active_tolerance),
                           int(r.restarts) - 1, shrink)
        Xa, fa, Ma = store.ranked(visited)
        log(f"polish: {res.runs} runs, {res.evaluations} points, {search.objective} {res.start_value:.6g} -> "
            f"{fa[0]:.6g}")
    best_x, best_f, best_m = Xa[0], float(fa[0]), Ma[0]
    feasible = violation(best_m) == 0.0 and np.isfinite(best_f)
    u = space.unit(best_x)[0]
    tol = float(r.active_tolerance)
    names = search.limits.names
    result = {
        "study": str(search.study.name),
        "objective": search.objective,
        "objective_units": str(store.ds[search.objective].attrs.get("units", "")),
        "load_case": {k: float(search.study.load[k]) for k in search.study.load},
        "duty_cycle": (None if search.study.get("duty_cycle") is None
                       else OmegaConf.to_container(search.study.duty_cycle, resolve=True)),
        "feasible": bool(feasible),
        "value": best_f,
        "design": {n: float(v) for n, v in zip(space.names, best_x)},
        "margins": {str(n): float(m) for n, m in zip(names, best_m)},
        "active_constraints": [str(n) for n, m in zip(names[1:], best_m[1:]) if abs(m) <= tol],
        "active_bounds": [f"{space.names[i]} {'low' if u[i] <= tol else 'high'}" for i in range(len(u))
                          if u[i] <= tol or u[i] >= 1.0 - tol],
        "simulations": len({x.tobytes() for x in visited}),
        # the others were found in points.nc (a resumed or repeated run): wall_time_s is this run's
        "simulated_in_this_run": int(store.ds.sizes["design"] - stored_before),
        "sample": {"n": int(n_sobol), "seed": int(seed), "feasible": n_feasible,
                   "best_feasible": float(fs[0]) if n_feasible else None},
        "starts": [{"start": label, "unit_point": [float(v) for v in u0], "evaluations": int(res.evaluations),
                    "value": float(res.value), "feasible": bool(res.feasible),
                    "relative_to_best": float(res.value / best_f - 1.0) if res.feasible and feasible else None}
                   for label, u0, res in ends],
        "starts_reaching": {f"{t:g}": int(sum(1 for _, _, res in ends if res.feasible and feasible
                                              and res.value <= best_f * (1.0 + t))) for t in REACHED},
        "refine": {"initial_step": float(r.initial_step), "final_step": float(r.final_step), "max_per_start":
                   int(max_per_start), "active_tolerance": tol, "polish_runs": int(r.restarts),
                   "polish_shrink": float(r.restart_shrink)},
    }
    return result


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m studies.reference_optimum", description=__doc__.split("\n\n")[0])
    parser.add_argument("overrides", nargs="*", help="study overrides, e.g. study=size_32208")
    parser.add_argument("--sobol", type=int, default=4096,
                        help="dense sample size (default 4096 = 2^12: about 5 points per axis in 5-D)")
    parser.add_argument("--seed", type=int, default=12345, help="seed of the dense sample (default 12345)")
    parser.add_argument("--starts", type=int, default=128,
                        help="local runs from the best distinct sample points (default 128: their ends spread by "
                             "0.5-20 %% on the shipped studies, and on size_32208 the best of 33 starts was 5 %% above "
                             "the best of 128), plus one from the template design")
    parser.add_argument("--max-per-start", type=int, default=150,
                        help="simulations per local run at most (default 150: 30 per free parameter)")
    parser.add_argument("--from-runs", type=Path, default=None,
                        help="also start from the best feasible design of every search-benchmark run in this "
                             "folder (outputs/benchmarks/design_search/<name>/): the reference is then the best "
                             "known design of the dense sample, the starts and every benchmarked method")
    parser.add_argument("--from-reference", type=Path, default=None,
                        help="also start from the design of this stored reference optimum (its YAML): after a "
                             "physics change that moves the optimum a little, its old place is the start that "
                             "finds it again")
    parser.add_argument("--out", default=None, help="result YAML (default outputs/studies/<name>/reference/"
                                                    "reference_optimum.yaml)")
    args = parser.parse_args(argv)
    for key, value, low in (("--sobol", args.sobol, 2), ("--starts", args.starts, 0), ("--max-per-start",
                                                                                         args.max_per_start, 7)):
        if value < low:
            print(f"error: {key} = {value} is outside the allowed range: an integer >= {low}", file=sys.stderr)
            return 2
    t0 = time.perf_counter()
    log = elapsed_log()
    try:
        search, _ = prepared_search(args.overrides, log)
    except STUDY_ERRORS as err:
        return refused(err)
    try:
        extra = run_bests(args.from_runs, search.space.names) if args.from_runs is not None else []
        if args.from_reference is not None:
            extra.append(stored_optimum(args.from_reference, search))
        result = run(search, args.sobol, args.seed, args.starts, args.max_per_start, log, extra)
    except STUDY_ERRORS as err:          # points.nc of another configuration
        return refused(err)
    result["command"] = "python -m studies.reference_optimum " + " ".join(shlex.quote(a) for a in (argv or sys.argv[1:]))
    ref_attrs = search.attrs()
    result["git_commit"] = str(ref_attrs.get("git_commit", "unknown"))
    result["package_version"] = str(ref_attrs.get("package_version", "unknown"))
    result["created"] = utc_now()
    result["wall_time_s"] = round(time.perf_counter() - t0, 1)
    result["simulation_overrides"] = list(args.overrides)
    out = search.out / "reference" / "reference_optimum.yaml" if args.out is None else args.out
    text = OmegaConf.to_yaml(OmegaConf.create(result))
    write_bytes_atomic(out, text.encode())
    print(text)
    print(f"written to {out}")
    return 0 if result["feasible"] else 1


if __name__ == "__main__":
    sys.exit(main())
