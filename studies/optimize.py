"""Design search of issue 5: ``python -m studies.optimize [overrides ...]``.

Runs the whole search on the embedded defaults (``conf/study/pinion.yaml``: the pinion TSRB
of thesis 7.4 against TRB 31313 and Table 7.4's design), resuming from the study folder
``outputs/studies/<name>/`` and its Optuna storage when run again. Overrides use Hydra syntax::

    python -m studies.optimize study=size_32208
    python -m studies.optimize study.sampler=nsga2 study.budget.max_simulations=200
    python -m studies.optimize study.objective=pmax study.name=pinion_pmax

Exit status 0 with a verified feasible design, 1 when none was found, 2 for a bad config.
"""
import argparse
import sys
import time

import optuna

from studies.config import StudyConfigError, compose
from studies.loop import DesignSearch
from studies.report import write_report


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m studies.optimize", description=__doc__.split("\n\n")[0],
                                     epilog="Overrides: study=NAME selects conf/study/NAME.yaml; study.KEY=VALUE "
                                            "changes one key; solver.*, material.*, ... go to every simulation.")
    parser.add_argument("overrides", nargs="*", help="Hydra-style overrides, e.g. study.sampler=gp")
    args = parser.parse_args(argv)
    optuna.logging.set_verbosity(optuna.logging.WARNING)
    t0 = time.perf_counter()
    try:
        cfg = compose(args.overrides)
        search = DesignSearch(cfg, args.overrides, log=lambda msg: print(f"[{time.perf_counter() - t0:6.1f} s] {msg}",
                                                                        flush=True))
        search.run_references()
    except StudyConfigError as err:
        print(f"error: {err}", file=sys.stderr)
        return 2
    ds, reason = search.run()
    print(write_report(search, ds, reason))
    print(f"\nwritten to {search.out}/ in {time.perf_counter() - t0:.1f} s")
    _, key = search.best(ds)
    return 0 if key[0] == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
