"""Design search of issue 5: ``python -m studies.optimize [overrides ...]``.

Runs the whole search on the embedded defaults (``conf/study/pinion.yaml``: the pinion TSRB
of thesis 7.4 against TRB 31313 and Table 7.4's design), resuming from the study folder
``outputs/studies/<name>/`` when run again. Overrides use Hydra syntax::

    python -m studies.optimize study=size_32208
    python -m studies.optimize study.budget.verify_per_round=8 study.budget.max_simulations=200
    python -m studies.optimize study.objective=pmax study.name=pinion_pmax

Exit status 0 with a verified feasible design, 1 when none was found, 2 for a bad config: one
line ``error: ...`` on stderr naming the key, its value and the allowed range, before the study
folder is made (a folder made for a study refused later, e.g. when the reference TRB gives no
result at the load case, is removed again while empty). Any other exception keeps its traceback.
"""
import argparse
import sys
import time
from pathlib import Path

from sim.api.cli import INTERRUPTED, PROJECT_ERRORS, refused
from sim.api.sweep import remove_stale_files
from studies.config import LOAD_KEYS, StudyConfigError, compose, output_dir
from studies.loop import DesignSearch
from studies.report import write_report

STUDY_ERRORS = PROJECT_ERRORS + (StudyConfigError,)


def new_folders(path):
    """``path`` and those of its parents that do not exist yet, deepest first."""
    path = Path(path).absolute()
    new = []
    while not path.exists():
        new.append(path)
        path = path.parent
    return new


def remove_if_empty(folders):
    """Remove the folders (deepest first) that hold nothing, i.e. that a refused study made."""
    for folder in folders:
        try:
            folder.rmdir()
        except OSError:
            return


def _reference_failure(search, study):
    """Message naming the load case when a reference simulation gave no result ('' otherwise)."""
    for label, ref in search.references.items():
        for k, record in enumerate(ref.records):
            if record["status"] == "ok":
                continue
            case = search.cycle.cases[k]
            where, key = ((f"case {k} of study.duty_cycle", f"study.duty_cycle[{k}]") if study.get("duty_cycle")
                          else ("the study's load case study.load", "study.load"))
            load = ", ".join(f"{name} = {case[name]!r}" for name in LOAD_KEYS)
            return (f"the {label} {ref.bearing} gives no result at {where} ({load}): "
                    f"{record['status']}: {record['message']}; choose another {key}")
    return ""


def prepared_search(overrides, log, one_case=None):
    """The design search of the command-line ``overrides`` with its references simulated and its
    limits set: (search, folders it created). Every input is checked before anything is written;
    a refusal after that (from the references: their load case named) removes the folders it
    made, so a refused command leaves nothing behind. ``one_case``: the name of a command that
    runs one load case, which refuses a duty cycle (DesignSearch.require_one_case) before any
    simulation. Raises one of :data:`STUDY_ERRORS`."""
    cfg = compose(overrides)
    new = new_folders(output_dir(cfg.study))
    for folder in (output_dir(cfg.study), output_dir(cfg.study) / "pareto"):
        remove_stale_files(folder)      # temporaries of a write a kill -9 interrupted (session 32, an independent check)
    try:
        search = DesignSearch(cfg, overrides, log=log)
        if one_case is not None:
            search.require_one_case(one_case)
        try:
            search.run_references()
        except StudyConfigError as err:
            raise StudyConfigError(_reference_failure(search, cfg.study) or str(err)) from err
    except STUDY_ERRORS:
        remove_if_empty(new)
        raise
    return search, new


def elapsed_log():
    """A progress printer that starts each line with the seconds since it was made."""
    t0 = time.perf_counter()

    def log(msg):
        print(f"[{time.perf_counter() - t0:6.1f} s] {msg}", flush=True)

    return log


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m studies.optimize", description=__doc__.split("\n\n")[0],
                                     epilog="Overrides: study=NAME selects conf/study/NAME.yaml; study.KEY=VALUE "
                                            "changes one key; solver.*, material.*, ... go to every simulation.")
    parser.add_argument("overrides", nargs="*", help="Hydra-style overrides, e.g. study.budget.max_simulations=200")
    args = parser.parse_args(argv)
    try:
        return _optimize(args.overrides)
    except KeyboardInterrupt:   # Ctrl-C: training.nc holds the simulations of every finished chunk and round
        print("\ninterrupted: the simulations of the finished rounds are kept in the study folder (training.nc); "
              "the same command resumes from them", file=sys.stderr)
        return INTERRUPTED


def _optimize(overrides):
    """:func:`main`'s search of the command-line ``overrides``: its exit status."""
    t0 = time.perf_counter()
    try:
        search, new = prepared_search(overrides, elapsed_log())
    except STUDY_ERRORS as err:
        return refused(err)
    try:
        ds, reason = search.run()
    except STUDY_ERRORS as err:
        remove_if_empty(new)
        return refused(err)
    print(write_report(search, ds, reason))
    print(f"\nwritten to {search.out}/ in {time.perf_counter() - t0:.1f} s")
    _, key = search.best(ds)
    return 0 if key[0] == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
