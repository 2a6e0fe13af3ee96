"""Pareto fronts of a design study (issue 16 item 6): frictional power loss against rating life
L10 and against pmax, on the full simulation, with the TRB the TSRB replaces on the same axes.

    python -m studies.pareto                        # the pinion study (conf/study/pinion.yaml)
    python -m studies.pareto study=size_32208 study.pareto.trials=200

For each pair (x, y) of ``study.pareto.fronts``, two stages on the full simulation (a
quasi-static case with friction costs 40-100 ms, so every point is a simulated design, not a
surrogate prediction):

A. Exploration: an Optuna NSGA-II study (Deb et al. 2002; Deb's constraint domination on the
   margins, as Optuna's NSGAIISampler applies them), ``study.pareto.trials`` simulations.
B. Epsilon constraint (Haimes, Lasdon & Wismer 1971), because the feasible region of the pinion
   study is a thin sliver that a population method seldom hits: COBYLA runs
   (:func:`studies.refine.local_refine`, ``study.refine`` settings) from the best point of A
   (or the study's template design): the best x, from there the best y, then
   ``study.pareto.levels`` levels of y between them, each minimising x with y bounded by the
   level and started from the previous solution.

The study's constraints hold on every front (:mod:`studies.constraints`), except the one on a
front's own objective: on the L10 front the life is traded, not bounded (``L10_min`` dropped);
on the pmax front likewise ``pmax_max``. The front is the set of feasible, non-dominated points
of A and B together; each is simulated once more at the end (``sim.api.simulate_batch``) and
must reproduce its objectives to 1e-9.

Outputs under ``outputs/studies/<name>/pareto/``: per front ``points_<x>_<y>.nc`` (every point as
a design: parameters, objectives at the load case, margins, stage, on_front; :func:`points_to_file`),
``front_<x>_<y>.nc`` (the re-simulated front designs, DATA.md layout), ``front_<x>_<y>.png``, and
``pareto.md``. Resuming: stage A lives in the study's Optuna storage (``<name>-pareto-<x>-<y>``),
stage B's points in ``local_points.nc`` (rewritten after every simulation; COBYLA replays its
sequence against them), so running the command again repeats no simulation.
"""
import argparse
import sys
import time

import numpy as np
import optuna
import xarray as xr
from matplotlib.figure import Figure

from sim.api import simulate_batch
from sim.io import write_bytes_atomic, write_figure_atomic, write_netcdf_atomic
from studies.config import PARETO_OBJECTIVES, storage_spec
from studies.constraints import FAILED, margins, rank_key
from studies.evaluate import RECORDED, case_dataset_coords, design_config, evaluate_design, table_to_file
from studies.optimize import STUDY_ERRORS, elapsed_log, prepared_search, refused
from studies.report import load_case_label
from studies.refine import local_refine
from studies.search import complete_trials, make_sampler, make_storage, open_study, run_trials, trial_margins
from studies.space import DESIGN_PARAMETERS

# objectives a front may pair (studies.config.PARETO_OBJECTIVES): optimisation direction, label, units (DATA.md)
OBJECTIVES = {"power_loss": ("minimize", "frictional power loss", "W"),
              "L10": ("maximize", "basic rating life L10", "1e6 rev"),
              "pmax": ("minimize", "maximum contact pressure", "MPa")}
assert tuple(OBJECTIVES) == PARETO_OBJECTIVES
# the study constraint that bounds an objective: dropped on a front that trades that objective
CONSTRAINT_OF = {"L10": "L10", "pmax": "pmax"}
# objective told to NSGA-II for a minimised objective of a point without result when no trial has
# a value yet (NSGA-II needs a number; its simulation margin keeps it infeasible)
NO_RESULT_MINIMISED = 1e30


def front_name(pair):
    return f"{pair[0]}_{pair[1]}"


def non_dominated(F, directions):
    """Indices of the non-dominated rows of F (n, 2) under the given directions (min/max)."""
    G = np.asarray(F, dtype=float) * np.array([1.0 if d == "minimize" else -1.0 for d in directions])
    keep = []
    for i, g in enumerate(G):
        dominated = np.any(np.all(G <= g, axis=1) & np.any(G < g, axis=1))
        if not dominated:
            keep.append(i)
    return np.array(keep, dtype=int)


class PointStore:
    """Every design simulated for the fronts of one study, shared by all fronts: a simulation
    gives all objectives and all margins at once, so a point found for one front counts on every
    other. Stage B's points persist in ``local_points.nc`` (rewritten atomically after each
    simulation, no pickle); stage A's live in the Optuna storage (user attributes)."""

    def __init__(self, search, out):
        self.search = search
        self.quantities = tuple(dict.fromkeys((*OBJECTIVES, "torque", *RECORDED)))
        self.path = out / "local_points.nc"
        self.local = self._load()
        self.explored = []     # COMPLETE NSGA-II trials of all fronts
        self.storage = make_storage(storage_spec(search.study, search.out))   # stage A's Optuna studies

    def simulate(self, x):
        """(objectives (all of OBJECTIVES; NaN without a result), margins (all of limits.names),
        status) of the design at x."""
        s = self.search
        bearing = s.space.bearing_values(x)
        record = evaluate_design(s.base_cfg, bearing, self.quantities)
        ok = record["status"] == "ok"
        values = np.array([float(record["values"][p]) if ok else np.nan for p in OBJECTIVES])
        return values, margins(record["values"], bearing, s.limits, 0.0 if ok else FAILED), record["status"]

    def _load(self):
        if not self.path.is_file():
            return {}
        with xr.open_dataset(self.path) as ds:
            ds.load()
        return {np.asarray(x, dtype=float).tobytes(): (np.asarray(x, dtype=float), np.asarray(f), np.asarray(m), str(st),
                                                       str(by))
                for x, f, m, st, by in zip(ds.x.values, ds.objective_value.values, ds.margin.values, ds.status.values,
                                           ds.found_by.values)}

    def _save(self):
        rows = list(self.local.values())
        units = ", ".join(f"{p} {OBJECTIVES[p][2]}" for p in OBJECTIVES)
        ds = xr.Dataset({"x": (("point", "parameter"), np.array([r[0] for r in rows]),
                               {"long_name": "design parameters (units: " + ", ".join(
                                   f"{n} {DESIGN_PARAMETERS[n][0]}" for n in self.search.space.names) + ")"}),
                         "objective_value": (("point", "objective"), np.array([r[1] for r in rows]),
                                             {"long_name": f"objectives, NaN without a result (units: {units})"}),
                         "margin": (("point", "constraint"), np.array([r[2] for r in rows]),
                                    {"units": "1", "long_name": "normalised constraint margin, <= 0 feasible"}),
                         "status": ("point", np.array([r[3] for r in rows], dtype=str),
                                    {"long_name": "simulation status"}),
                         "found_by": ("point", np.array([r[4] for r in rows], dtype=str),
                                      {"long_name": "front whose local runs simulated the point first"})},
                        coords={"parameter": list(self.search.space.names), "objective": list(OBJECTIVES),
                                "constraint": list(self.search.limits.names)},
                        attrs={**self.search.attrs(), "title": f"design search {self.search.study.name}: the "
                               "Pareto fronts' local-stage points (resume store of studies.pareto)"})
        write_netcdf_atomic(table_to_file(ds), self.path)

    def point(self, u, found_by):
        """(x, objectives, margins, status, found_by) of the unit-cube point u: stored, else
        simulated and stored with ``found_by`` (the front name)."""
        s = self.search
        x = s.space.low + np.clip(u, 0.0, 1.0) * (s.space.high - s.space.low)
        key = x.tobytes()
        if key not in self.local:
            self.local[key] = (x, *self.simulate(x), found_by)
            self._save()
        return self.local[key]

    def all_points(self, found_by=None):
        """(X, objectives, margins, ok, stage) of every point: NSGA-II trials, then stage B's (only
        those found by the fronts named in ``found_by``, if given)."""
        names = self.search.space.names
        rows = [(np.array([t.params[n] for n in names]), np.array(t.user_attrs["objectives"], dtype=float),
                 np.array(t.user_attrs["margins"], dtype=float), t.user_attrs["status"], "nsga2") for t in self.explored]
        rows += [(x, f, m, st, "epsilon_constraint") for x, f, m, st, by in self.local.values()
                 if found_by is None or by in found_by]
        X, F, M = (np.array([r[k] for r in rows], dtype=float).reshape(len(rows), -1) for k in range(3))
        return X, F, M, np.array([r[3] == "ok" for r in rows]), np.array([r[4] for r in rows], dtype=str)


class ParetoFront:
    """The front of ``pair`` = (x, y) objectives on the search's full simulation (module docstring)."""

    def __init__(self, store, pair):
        self.store = store
        self.search = store.search
        self.pair = tuple(pair)
        self.name = front_name(self.pair)
        self.columns = [list(OBJECTIVES).index(p) for p in self.pair]
        self.directions = [OBJECTIVES[p][0] for p in self.pair]
        names = self.search.limits.names
        self.kept = [i for i, n in enumerate(names) if n not in {CONSTRAINT_OF.get(p) for p in self.pair}]
        self.margin_names = [names[i] for i in self.kept]

    # ------------------------------------------------------------------ stage A: NSGA-II
    def evaluate(self, trial):
        f, m, status = self.store.simulate(self.search.space.suggest(trial))
        values = list(f[self.columns])
        if status != "ok":   # a point without result: the worst value seen so far (never a gap), infeasible
            seen = np.array([t.values for t in complete_trials(trial.study)] or [[np.nan, np.nan]])
            worst = [np.nanmax(c) if d == "minimize" else np.nanmin(c) for c, d in zip(seen.T, self.directions)]
            values = [w if np.isfinite(w) else (NO_RESULT_MINIMISED if d == "minimize" else 0.0)
                      for w, d in zip(worst, self.directions)]
        return values, m[self.kept], {"status": status, "objectives": [float(v) for v in f],
                                      "margins": [float(v) for v in m]}

    def explore(self, n_trials, log):
        s = self.search
        name = f"{s.study.name}-pareto-{'-'.join(self.pair)}"
        study = open_study(self.store.storage, name, None, directions=self.directions)

        def sampler_for(k):
            return make_sampler("nsga2", int(s.study.seed) + k, s.study.sampler_settings)

        t0 = time.perf_counter()
        done = len(complete_trials(study))
        log(f"front {' / '.join(self.pair)}: NSGA-II, {done} of {n_trials} simulations already in {name}")
        chunk = int(s.study.sampler_settings.population_size)
        while done < n_trials:
            done = min(n_trials, done + chunk)
            trials = run_trials(study, done, self.evaluate, sampler_for)
            feasible = sum(max(trial_margins(t)) <= 0.0 for t in trials)
            log(f"front {' / '.join(self.pair)}: NSGA-II {len(trials)}/{n_trials} simulations, {feasible} feasible, "
                f"{time.perf_counter() - t0:.0f} s")
        self.store.explored += complete_trials(study)

    # ------------------------------------------------------------------ stage B: epsilon constraint
    def minimise(self, u0, target, level=None):
        """COBYLA (studies.refine.local_refine) on objective ``target`` (0: x, 1: y; maximised
        ones negated) under the kept margins and, with ``level``, the epsilon constraint on y:
        y / level - 1 <= 0 (minimised y) or 1 - y / level <= 0 (maximised y), Haimes et al. 1971."""
        sign = 1.0 if self.directions[target] == "minimize" else -1.0
        y_min = self.directions[1] == "minimize"
        r = self.search.study.refine

        def evaluate(u):
            _, f, m, _, _ = self.store.point(u, self.name)
            f = f[self.columns]
            m = m[self.kept]
            if level is not None:
                m = np.append(m, (f[1] / level - 1.0 if y_min else 1.0 - f[1] / level) if np.isfinite(f[1]) else 0.0)
            return sign * f[target], m

        names = [*self.margin_names, *(["epsilon"] if level is not None else [])]
        return local_refine(evaluate, u0, names, int(r.max_simulations), float(r.initial_step), float(r.final_step),
                            float(r.active_tolerance), int(r.restarts), float(r.restart_shrink))

    def start(self, earlier):
        """Unit-cube start of the local runs: the best point for x by rank_key (feasible by
        objective first, else least violation) among the study's template, every NSGA-II point and
        the local points of the ``earlier`` fronts (not this front's own: a rerun starts where the
        first run started and replays it from the stored points)."""
        s = self.search
        x0, f0, m0, _, _ = self.store.point(np.clip(s.space.unit([s.space.template[n] for n in s.space.names])[0],
                                                    0.0, 1.0), self.name)
        X, F, M, _, _ = self.store.all_points(found_by=set(earlier))
        X, F, M = np.vstack([x0, X]), np.vstack([f0, F]), np.vstack([m0, M])
        sign = 1.0 if self.directions[0] == "minimize" else -1.0
        best = min(range(len(X)), key=lambda i: rank_key(sign * F[i, self.columns[0]], M[i, self.kept]))
        return s.space.unit(X[best])[0]

    def epsilon_constraint(self, n_levels, earlier, log):
        """Anchors (best x; best y from there), then ``n_levels`` epsilon levels of y between
        them, each started from the previous solution (continuation); ``earlier``: the names of
        the fronts whose local runs came before (:meth:`start`)."""
        t0 = time.perf_counter()
        a = self.minimise(self.start(earlier), 0)
        log(f"front {' / '.join(self.pair)}: best {self.pair[0]} {a.value:.6g} ({'feasible' if a.feasible else 'infeasible'}, "
            f"{time.perf_counter() - t0:.0f} s)")
        if not a.feasible:
            return
        b = self.minimise(a.u, 1)
        log(f"front {' / '.join(self.pair)}: best {self.pair[1]} {abs(b.value):.6g} "
            f"({'feasible' if b.feasible else 'infeasible'}, {time.perf_counter() - t0:.0f} s)")
        y_a, y_b = (self.store.point(r.u, self.name)[1][self.columns[1]] for r in (a, b))
        u = a.u
        for level in np.linspace(y_a, y_b, n_levels + 2)[1:-1]:
            res = self.minimise(u, 0, level)
            log(f"front {' / '.join(self.pair)}: {self.pair[1]} level {level:.6g}: {self.pair[0]} {res.value:.6g} "
                f"({'feasible' if res.feasible else 'infeasible'}, {time.perf_counter() - t0:.0f} s)")
            if res.feasible:
                u = res.u

    # ------------------------------------------------------------------ all points
    def table(self):
        """Every simulated point of every front (stage A trials, then stage B points) as a Dataset
        with this front's objectives and margins, feasibility, stage, and whether it is on the front."""
        s = self.search
        X, F, M, ok, stage = self.store.all_points()
        F, M = F[:, self.columns], M[:, self.kept]
        feasible = ok & np.all(M <= 0.0, axis=1) & np.all(np.isfinite(F), axis=1)
        front = np.zeros(len(stage), dtype=bool)
        idx = np.flatnonzero(feasible)
        if idx.size:
            front[idx[non_dominated(F[idx], self.directions)]] = True
        return xr.Dataset(
            {n: ("point", X[:, j], {"units": DESIGN_PARAMETERS[n][0], "long_name": DESIGN_PARAMETERS[n][1]})
             for j, n in enumerate(s.space.names)}
            | {p: ("point", F[:, j], {"units": OBJECTIVES[p][2], "long_name": OBJECTIVES[p][1]})
               for j, p in enumerate(self.pair)}
            | {"margin": (("point", "constraint"), M, {"units": "1", "long_name": "normalised margin, <= 0 feasible"}),
               "feasible": ("point", feasible, {"long_name": "a result, every margin <= 0"}),
               "stage": ("point", stage, {"long_name": "nsga2 or epsilon_constraint"}),
               "on_front": ("point", front, {"long_name": "feasible and non-dominated among all points"})},
            coords={"point": np.arange(len(stage)), "constraint": self.margin_names})


def points_to_file(front, ds):
    """A front's :meth:`ParetoFront.table` in its DATA.md form for ``points_<x>_<y>.nc``: one design per
    point along ``design``, the objectives per design and case at the study's one load case (its
    coordinates along ``case``), pmax as the per-point tables name their race maximum
    (studies.evaluate.table_to_file), and the search's provenance (its ``training.nc``'s attributes)."""
    s = front.search
    out = ds.rename({"point": "design"}).drop_vars("design")
    for p in front.pair:
        out[p] = out[p].expand_dims(case=1, axis=1)
    out = out.assign_coords(case_dataset_coords(s.cycle))
    out.attrs.update({**s.attrs(), "title": f"design search {s.study.name}: every point simulated for the front "
                                            f"{front_name(front.pair)}"})
    return table_to_file(out)


def reference_point(front, label):
    """(x, y) of a reference bearing of the search (None without result), and for a TSRB whether
    it meets the front's constraints (None for the TRB, which sets the limits)."""
    ref = front.search.references[label]
    if ref.record["status"] != "ok" or ref.ds is None:
        return None, None
    point = [float(ref.ds[p].max()) for p in front.pair]
    b = ref.cfg.bearing
    if b.type != "TSRB":
        return point, None
    m = margins(ref.record["values"], {"PCR": float(b.PCR), "ratings_alpha": float(b.ratings_alpha)},
                front.search.limits, 0.0)[front.kept]
    return point, bool(np.all(m <= 0.0))


def plot_front(front, ds, refs, path, load_label):
    x, y = front.pair
    fig = Figure(figsize=(10.0, 5.2), layout="constrained")
    ax = fig.subplots()
    feas = ds.feasible.values
    ax.plot(ds[x].values[~feas], ds[y].values[~feas], ".", color="0.8", ms=4, label="infeasible (simulated)")
    ax.plot(ds[x].values[feas], ds[y].values[feas], ".", color="C0", ms=5, label="feasible (simulated)")
    on = ds.on_front.values
    order = np.argsort(ds[x].values[on])
    ax.plot(ds[x].values[on][order], ds[y].values[on][order], "o-", color="C3", ms=6, label="Pareto front (re-simulated)")
    for (label, (point, feasible)), marker in zip(refs.items(), ("*", "D")):
        if point is not None:
            note = {None: "", True: ", feasible", False: ", infeasible here"}[feasible]
            ax.plot(*point, marker, ms=13, color="k" if marker == "*" else "C2", label=label + note,
                    mfc="none" if feasible is False else None)
    # the title in lines that fit the figure, the legend outside the axes (session 32, an independent check:
    # a one-line title was cut off, and the legend covered the front's high-L10 end)
    ax.set(xlabel=f"{OBJECTIVES[x][1]} [{OBJECTIVES[x][2]}]", ylabel=f"{OBJECTIVES[y][1]} [{OBJECTIVES[y][2]}]")
    ax.set_title(f"{OBJECTIVES[x][1]} vs {OBJECTIVES[y][1]}\n{int(feas.sum())} feasible of {feas.size} simulated "
                 f"designs\n{load_label}", fontsize=9, wrap=True)
    if y == "L10":
        ax.set_yscale("log")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0)
    write_figure_atomic(fig, path, 120)
    return path


def verify_front(front, ds):
    """Re-simulate every front design (``simulate_batch``): one Dataset (design x case, DATA.md).

    Raises RuntimeError if a re-simulated objective differs from its trial's by more than
    1e-9 relative (the simulation is deterministic; anything else is a bug)."""
    s = front.search
    rows = np.flatnonzero(ds.on_front.values)
    if rows.size == 0:
        return None
    bearings = [s.space.bearing_values(np.array([float(ds[n].values[i]) for n in s.space.names])) for i in rows]
    out = simulate_batch([design_config(s.base_cfg, b) for b in bearings], workers=int(s.study.n_jobs))
    for d, i in enumerate(rows):
        again = [float(out[p].isel(design=d, case=0).max()) for p in front.pair]
        for p, v in zip(front.pair, again):
            if not abs(v / float(ds[p].values[i]) - 1.0) <= 1e-9:
                raise RuntimeError(f"front {front_name(front.pair)}, trial {i}: re-simulated {p} = {v:.6g}, "
                                   f"trial {float(ds[p].values[i]):.6g}")
    return out


def front_summary(front, ds, refs):
    """Markdown lines: the front's extent and where the references sit against it."""
    x, y = front.pair
    on = ds.on_front.values
    head = (f"{int(ds.feasible.sum())} feasible of {ds.sizes['point']} simulated designs (constraints: "
            f"{', '.join(front.margin_names)})")
    if not on.any():
        return [f"## {OBJECTIVES[x][1]} against {OBJECTIVES[y][1]}", "", f"{head}: no feasible design, so no "
                f"front (figure `front_{front_name(front.pair)}.png` shows the designs simulated).", ""]
    lines = [f"## {OBJECTIVES[x][1]} against {OBJECTIVES[y][1]}", "",
             f"{head}; {int(on.sum())} on the front, each re-simulated "
             f"(`front_{front_name(front.pair)}.nc`), figure `front_{front_name(front.pair)}.png`.", ""]
    head = [*front.search.space.names, f"{x} [{OBJECTIVES[x][2]}]", f"{y} [{OBJECTIVES[y][2]}]"]
    rows = sorted(np.flatnonzero(on), key=lambda i: float(ds[x].values[i]))
    lines += ["| " + " | ".join(head) + " |", "|" + " --- |" * len(head)]
    lines += ["| " + " | ".join(f"{float(ds[n].values[i]):.4g}" for n in (*front.search.space.names, x, y)) + " |"
              for i in rows]
    lines.append("")
    for label, (point, feasible) in refs.items():
        if point is None:
            lines.append(f"- {label}: no result at this load.")
            continue
        better = [i for i in rows if all(
            (float(ds[p].values[i]) <= v) if OBJECTIVES[p][0] == "minimize" else (float(ds[p].values[i]) >= v)
            for p, v in zip(front.pair, point))]
        note = {None: "", True: " (meets this front's constraints)", False: " (violates this front's constraints)"}[feasible]
        lines.append(f"- {label}{note}: {x} = {point[0]:.4g} {OBJECTIVES[x][2]}, {y} = {point[1]:.4g} "
                     f"{OBJECTIVES[y][2]}; {len(better)} front design(s) are at least as good in both.")
    return lines + [""]


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m studies.pareto", description=__doc__.split("\n\n")[0])
    parser.add_argument("overrides", nargs="*", help="Hydra-style overrides, e.g. study=size_32208 study.pareto.trials=200")
    args = parser.parse_args(argv)
    optuna.logging.set_verbosity(optuna.logging.WARNING)
    log = elapsed_log()
    try:
        search, _ = prepared_search(args.overrides, log, one_case="python -m studies.pareto")
    except STUDY_ERRORS as err:
        return refused(err)
    out = search.out / "pareto"
    out.mkdir(parents=True, exist_ok=True)
    load_label = load_case_label(search.study)
    lines = [f"# Pareto fronts of study {search.study.name}", "", f"Load case: {load_label}. Generated by "
             f"`python -m studies.pareto {' '.join(args.overrides)}`.", ""]
    store = PointStore(search, out)
    fronts = [ParetoFront(store, pair) for pair in search.study.pareto.fronts]
    for front in fronts:   # stage A of every front first: stage B then starts from all their points
        front.explore(int(search.study.pareto.trials), log)
    if int(search.study.refine.max_simulations) > 0:     # 0: no local stage (stage B), as for a search
        for k, front in enumerate(fronts):
            front.epsilon_constraint(int(search.study.pareto.levels), [f.name for f in fronts[:k]], log)
    empty = []      # fronts without a feasible design
    for front in fronts:
        ds = front.table()
        name = front_name(front.pair)
        if not ds.on_front.values.any():
            empty.append(name)
        write_netcdf_atomic(points_to_file(front, ds), out / f"points_{name}.nc")
        verified = verify_front(front, ds)
        if verified is not None:
            write_netcdf_atomic(verified, out / f"front_{name}.nc")
        refs = {f"{label} ({r.bearing})": reference_point(front, label) for label, r in search.references.items()}
        plot_front(front, ds, refs, out / f"front_{name}.png", load_label)
        lines += front_summary(front, ds, refs)
    write_bytes_atomic(out / "pareto.md", ("\n".join(lines) + "\n").encode())
    log(f"written to {out}/")
    if empty:   # as studies.optimize without a feasible design: exit 1 (session 32, an independent check)
        print(f"no feasible design, so no front: {', '.join(empty)} (pareto.md lists the designs simulated)",
              file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
