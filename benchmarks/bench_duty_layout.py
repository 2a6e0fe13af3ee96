"""Surrogate layout of a duty-cycle study (issue 16 item 5): one set per case or one over design x case.

    python benchmarks/bench_duty_layout.py outputs/studies/pinion_duty/training.nc [overrides ...]

On the space-filling designs of a finished duty-cycle search (``source == initial``, each
simulated at every case), every constrained output is predicted for designs held out (k-fold
over designs, the study's ``surrogate.cv_folds`` and seed: a held-out design is what a proposal
is, a design not simulated at any case) by

- per case: one GP per case on the design parameters (studies.loop, the shipped layout);
- design x case: one GP on (design parameters, Fa, speed) over all (design, case) pairs;
- design x case, fewer simulations: the same with one case of every training design left out
  (chosen at random, seeded): 2/3 of the simulations for a three-case cycle.

It prints RMSE (output unit) and the coverage of the 95 % intervals per output and case. The
layout that needs fewer simulations for the accuracy the search needs wins; a design x case GP
saves simulations only if it may skip cases, and the last row measures what that costs.
"""
import argparse
import sys
import time

import numpy as np
import xarray as xr

from studies.config import compose
from studies.cycle import DutyCycle
from studies.evaluate import STATUS, design_matrix, table_from_file
from studies.space import DesignSpace
from surrogate import GPSettings, GPSurrogate
from surrogate.validation import KFold

OUTPUTS = ("pmax", "axial_displacement", "C_eff", "edge_stress_margin", "power_loss")
CASE_INPUTS = ("Fa", "speed")   # the load quantities that vary over the shipped cycle


def predictions(X, y, bounds, log, settings, train, test, level):
    model = GPSurrogate(bounds, log, settings).fit(X[train], y[train])
    mu = model.predict_latent(X[test])[0]
    lower, upper = model.interval(X[test], level)
    return (np.exp(mu) if log else mu), lower, upper


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("training", help="training.nc of a duty-cycle search")
    parser.add_argument("overrides", nargs="*", default=["study=pinion_duty"], help="the study's overrides")
    args = parser.parse_args(argv)
    study = compose(args.overrides).study
    ds = table_from_file(xr.load_dataset(args.training))
    ds = ds.isel(design=np.flatnonzero((ds.source.values == "initial") & (ds.status.values == STATUS["ok"])))
    cycle = DutyCycle.from_config(study)
    bearing = {k: float(ds[k].values[0]) for k in ("PCR", "kappa", "aP", "aPk", "alpha", "ratings_alpha")}
    space = DesignSpace.from_config(study, bearing)
    settings = GPSettings.from_config(study.surrogate, study.seed)
    level = float(study.surrogate.interval)
    X = design_matrix(ds, space)
    n, m = len(X), len(cycle)
    case_X = np.column_stack([cycle.column(k) for k in CASE_INPUTS])
    joint_X = np.array([[*x, *case_X[k]] for x in X for k in range(m)])    # design-major: row i m + k
    joint_bounds = np.vstack([space.bounds, np.column_stack([case_X.min(axis=0), case_X.max(axis=0)])])
    rng = np.random.default_rng(study.seed)
    dropped = rng.integers(0, m, size=n)   # the case of each design left out in the fewer-simulations variant
    folds = list(KFold(int(study.surrogate.cv_folds), shuffle=True, random_state=settings.seed).split(X))
    log_outputs = set(study.surrogate.log_outputs)
    print(f"{n} designs x {m} cases = {n * m} simulations; {len(folds)}-fold over designs; {100 * level:g} % intervals")
    print(f"{'output':<20} {'case':>4} {'per case RMSE / cover':>24} {'design x case':>24} {'design x case, 2/3 sims':>26}")
    totals = {"per case": 0.0, "design x case": 0.0, "2/3 sims": 0.0}
    for q in OUTPUTS:
        Y = ds[q].transpose("design", "case").values
        log = q in log_outputs
        results = {key: np.empty((n, m, 3)) for key in totals}
        t0 = time.perf_counter()
        for train, test in folds:
            for k in range(m):
                results["per case"][test, k] = np.column_stack(predictions(X, Y[:, k], space.bounds, log, settings,
                                                                           train, test, level))
            rows = (train[:, None] * m + np.arange(m)).ravel()
            test_rows = (test[:, None] * m + np.arange(m)).ravel()
            few = np.array([r for r in rows if r % m != dropped[r // m]])
            for key, used in (("design x case", rows), ("2/3 sims", few)):
                pred = predictions(joint_X, Y.ravel(), joint_bounds, log, settings, used, test_rows, level)
                results[key][test] = np.column_stack(pred).reshape(len(test), m, 3)
        for k in range(m):
            cells = []
            for key in totals:
                mean, lower, upper = results[key][:, k].T
                rmse = float(np.sqrt(np.mean((mean - Y[:, k]) ** 2)))
                cover = float(np.mean((Y[:, k] >= lower) & (Y[:, k] <= upper)))
                totals[key] += rmse / float(np.std(Y[:, k]))
                cells.append(f"{rmse:12.4g} / {cover:5.2f}")
            print(f"{q:<20} {k:>4} {cells[0]:>24} {cells[1]:>24} {cells[2]:>26}")
        print(f"{'':<20} fits {time.perf_counter() - t0:.1f} s")
    print("sum over outputs and cases of RMSE / standard deviation (lower is better): " +
          ", ".join(f"{k} {v:.3f}" for k, v in totals.items()))
    return 0


if __name__ == "__main__":
    sys.exit(main())
