"""Command line: simulate one bearing over one load case or a grid; sweeps with ``--multirun``.

    python -m sim.run bearing=tsrb_reference load.Fa=4500 load.Fr=2000 load.speed=2000 load.tilt=0
    python -m sim.run bearing=tsrb_prototype load=test_rig_fig_6_5         # a grid, one process
    python -m sim.run --multirun bearing.PCR=80,100,120 load=sensitivity_scenarios
    python -m sim.run --multirun hydra/launcher=parallel "bearing.kappa=range(0.95,0.995,0.01)"

A single run writes ``result.nc`` in Hydra's run directory and prints a summary; cases come
from the result cache when already computed (:mod:`sim.api.sweep`). A multirun job writes its
result (or ``failed.json``) in its job folder and logs one line; ``sweep.nc`` follows the
last job. Any ``bearing.<param>=`` override works (e.g. ``bearing.PCR=120``).

Exit status (one error path, :mod:`sim.api.cli`): 0 when every case converged; 1 when some
have no result (not converged, or a grid's case beyond the model's validity limits; written with
``converged = False``, each reason a line on stderr, then one line counting them) or the result
file cannot be written (one line naming the file; the converged cases stay in the result
cache); 2 for refused input (one line ``error: ...`` naming the key, its value and the allowed
range or bound; a single case beyond the validity limits is refused input; no run folder is
left behind); 130 when interrupted (Ctrl-C: one line ``interrupted: ...``, finished cases and jobs
kept, the same command resumes); any other exception is a bug and keeps its traceback (exit 1).
"""
import shutil
import sys
from pathlib import Path

import hydra
from hydra.core.hydra_config import HydraConfig
from hydra.types import RunMode
from omegaconf import DictConfig

from sim import CONF_DIR, io
from sim.api.cli import INTERRUPTED, PROJECT_ERRORS, refuse
from sim.api.sweep import NEW_RUN_DIRS, WriteError, remove_stale_files, run_cases, run_job, write_result
from sim.config_schema import undeclared_key


def friction_summary(case):
    """Torque, its largest shares, power loss, film and cage speed of one case [N mm, W, 1, rpm]."""
    parts = sorted(((float(v), str(c)) for c, v in zip(case.component.values, case.torque_component.values)),
                   reverse=True)
    shares = ", ".join(f"{name} {value / float(case.torque):.0%}" for value, name in parts[:3] if value > 0)
    return (f"  torque, power loss    {float(case.torque):8.1f} N mm, {float(case.power_loss):.1f} W ({shares})\n"
            f"  Lambda outer/inner    {float(case.lambda_ratio.sel(race='outer')):8.2f} / "
            f"{float(case.lambda_ratio.sel(race='inner')):.2f}, cage {float(case.cage_speed):.1f} rpm\n")


def summary(ds):
    """Short human-readable summary of a single-design result [pmax MPa, displacement mm]."""
    lines = []
    b = str(ds.bearing_type.values[0])
    for c in range(ds.sizes["case"]):
        case = ds.isel(design=0, case=c)
        head = (f"{b}  Fa={float(case.Fa):.0f} N  Fr={float(case.Fr):.0f} N  "
                f"n={float(case.speed):.0f} rpm  tilt={float(case.tilt):.3f} deg  "
                f"oil {float(case.oil_temperature):.1f} degC")
        if not bool(case.converged):
            reason = io.case_failure(ds, [float(case[name]) for name in io.CASE_COORDS])
            lines.append(f"{head}\n  NO RESULT: {reason or f'not converged after {int(case.iterations)} iterations'}")
            continue
        lines.append(
            f"{head}\n"
            f"  pmax outer/inner      {float(case.pmax.sel(race='outer')):8.0f} / {float(case.pmax.sel(race='inner')):.0f} MPa\n"
            f"  roller axial disp.    {float(case.axial_displacement) * 1e3:8.2f} um (rel. to inner ring, + to large end)\n"
            f"  contact length ratio  {float(case.contact_length_ratio.sel(race='outer')):8.2f} / "
            f"{float(case.contact_length_ratio.sel(race='inner')):.2f} (outer/inner)\n"
            f"  L_eff, C_eff, L10     {float(case.L_eff):8.2f} mm, {float(case.C_eff) / 1e3:.1f} kN, {float(case.L10):.3g} 1e6 rev\n"
            f"  edge stress           {bool(case.edge_stress)} (edge interference "
            f"{float(case.edge_interference.sel(race='outer')):.2f} / {float(case.edge_interference.sel(race='inner')):.2f}, "
            f"> 0: a contact runs onto a roller end)\n"
            + (friction_summary(case) if "torque" in case else "")
            + f"  converged             True in {int(case.iterations)} iterations, {float(case.wall_time) * 1e3:.1f} ms")
    return "\n".join(lines)


def _discard_run_dir(out_dir, job_name):
    """Remove the run folder Hydra created for a run that was then refused, if it holds nothing
    but Hydra's own files (``.hydra/`` and the log)."""
    if str(out_dir.resolve()) not in NEW_RUN_DIRS:
        return
    if {p.name for p in out_dir.iterdir()} <= {".hydra", f"{job_name}.log"}:
        shutil.rmtree(out_dir, ignore_errors=True)


@hydra.main(config_path="../conf", config_name="config", version_base="1.3")
def main(cfg: DictConfig) -> None:
    hc = HydraConfig.get()
    out_dir = Path(hc.runtime.output_dir)
    if hc.mode == RunMode.MULTIRUN:
        run_job(cfg, out_dir, hc.job.num, list(hc.overrides.task))
        return
    remove_stale_files((out_dir / cfg.output.file).parent)   # an interrupted write into a re-used run folder
    try:
        ds, n = run_cases(cfg)   # the input was checked before the run folder existed (SweepCallback.on_run_start)
    except PROJECT_ERRORS as exc:
        _discard_run_dir(out_dir, hc.job.name)
        refuse(exc)
    try:
        out = write_result(ds, out_dir / cfg.output.file, cfg)
    except WriteError as exc:
        refuse(exc, status=1)
    print(summary(ds))
    print(f"written: {out} ({n['cases']} cases, {n['cached']} from the cache)")
    if not bool(ds.converged.all()):
        print(ds.attrs.get(io.FAILED_CASES, ""), file=sys.stderr)
        print(f"{n['cases'] - int(ds.converged.sum())} of {n['cases']} cases have no result (written with "
              "converged = False; the reasons above and in its failed_cases attribute)", file=sys.stderr)
        raise SystemExit(1)


def undeclared_overrides(argv):
    """The command line's overrides of undeclared keys (sim.config_schema.undeclared_key): ``key=value``
    items, not flags, additions (``+``, which sim.api.schema.validate refuses itself) or deletions."""
    keys = (a.split("=", 1)[0] for a in argv if "=" in a and not a.startswith(("-", "+", "~")))
    return [p for p in map(undeclared_key, keys) if p]


def missing_config_file(argv):
    """Hydra's reason when an override of a single run names a config file that does not exist
    (``bearing=tsrb_pinnion``, ``hydra/launcher=foo``: "Could not find ..." with the available
    options), else "". A multirun checks every job's config itself (SweepCallback.on_multirun_start)."""
    from hydra import compose, initialize_config_dir
    from hydra.errors import MissingConfigException

    if any(a in ("-m", "--multirun") for a in argv):
        return ""
    overrides = [a for a in argv if "=" in a and not a.startswith("-")]
    with initialize_config_dir(config_dir=str(CONF_DIR), version_base="1.3"):
        try:
            compose(config_name="config", overrides=overrides, return_hydra_config=True)
        except MissingConfigException as exc:
            return str(exc)
        except Exception:   # noqa: BLE001  any other composition error: hydra.main below reports it as ever
            return ""
    return ""


if __name__ == "__main__":
    problems = undeclared_overrides(sys.argv[1:])
    if problems:    # one line and exit 2, as any refused input, where Hydra would print several and exit 1
        refuse("run refused before anything ran: " + "; ".join(problems))
    missing = missing_config_file(sys.argv[1:])
    if missing:
        refuse(f"run refused before anything ran: {missing}")
    try:
        main()
    except KeyboardInterrupt:   # Ctrl-C; a parallel sweep's workers end with it (joblib's loky aborts them)
        print("\ninterrupted: every finished case is kept in the result cache (output.cache_dir) and every "
              "finished job of a multirun in its folder; the same command resumes from them", file=sys.stderr)
        raise SystemExit(INTERRUPTED)
