"""Coverage of the surrogates' 95 % intervals per output, with and without calibration (issue 16 item 1).

Reads the ``training.nc`` of a design search (its study config is taken from the same overrides),
runs the k-fold cross-validation of every modelled output (``surrogate.cross_validate_outputs``,
as the study report does) with ``study.surrogate.calibrate`` false and true, for several fold
shufflings, and prints the coverage of each::

    python benchmarks/bench_calibration.py outputs/studies/pinion/training.nc [overrides ...] --seeds 3

A fresh Sobol sample for it: ``python -m studies.optimize study.name=sobol256 study.seed=7
study.initial_design.n=256 study.budget.max_simulations=256 study.refine.max_simulations=0``.
"""
import argparse
import dataclasses
import time
from pathlib import Path

import numpy as np
import xarray as xr

from studies.config import compose
from studies.evaluate import table_from_file
from studies.loop import DesignSearch
from surrogate import cross_validate_outputs


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("training", help="training.nc of a design search")
    parser.add_argument("overrides", nargs="*", help="the study's overrides (the same config as the search)")
    parser.add_argument("--seeds", type=int, default=3, help="fold shufflings (seeds 0..n-1)")
    args = parser.parse_args(argv)
    search = DesignSearch(compose(args.overrides), args.overrides, out_dir=Path(args.training).parent, log=lambda m: None)
    search.run_references()
    ds = table_from_file(xr.load_dataset(args.training))
    sets = search.training_sets(ds)
    s = search.study.surrogate
    print(f"{args.training}: {ds.sizes['design']} simulations; {s.cv_folds}-fold, {100 * s.interval:g} % intervals, "
          f"fold seeds 0-{args.seeds - 1}")
    print("| output | n | log | coverage, not calibrated | coverage, calibrated |")
    print("| --- | --- | --- | --- | --- |")
    rows = {q: [] for q in sets}
    t0 = time.perf_counter()
    for calibrate in (False, True):
        for seed in range(args.seeds):
            settings = dataclasses.replace(search.settings, calibrate=calibrate, seed=seed)
            for q, cv in cross_validate_outputs(sets, search.space.bounds, settings, int(s.cv_folds),
                                                float(s.interval)).items():
                rows[q].append(cv.coverage)
    for q, (X, y, log, _) in sets.items():
        plain, calibrated = np.array(rows[q][:args.seeds]), np.array(rows[q][args.seeds:])
        print(f"| {q} | {len(y)} | {log} | {plain.mean():.3f} ({', '.join(f'{c:.3f}' for c in plain)}) | "
              f"{calibrated.mean():.3f} ({', '.join(f'{c:.3f}' for c in calibrated)}) |")
    print(f"({time.perf_counter() - t0:.0f} s)")


if __name__ == "__main__":
    main()
