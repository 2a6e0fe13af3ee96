"""study.verify.solver = dynamic (issue 18 item 5, studies.verify.dynamic_verification): the best
design of a search on a tiny budget (pinion study, 10 slices, 8 Sobol points, no rounds, no local
stage) is re-simulated by the dynamic solver and the quasi-static solver with skew, and report.md
carries the numbers of best_design_dynamic.nc."""
import numpy as np
import pytest
import xarray as xr

import sim
from studies.config import StudyConfigError, compose
from studies.loop import DesignSearch
from studies.report import write_report

# solver.dynamic.max_windows=2 of window_revolutions=0.25: the dynamic runs only
# (studies.config.simulation_config), a time cap; the report gives a run without steady state by its
# last window, and the test checks it either way. (The best design of this search rests its rollers
# on alternate pocket walls; with the film following the rollers, session 21, its three full windows
# took about 10 min.)
TINY = ["study.verify.solver=dynamic", "solver.dynamic.max_windows=2", "solver.dynamic.window_revolutions=0.25",
        "solver.n_slices=10", "study.initial_design.n=8",
        "study.budget.max_simulations=8", "study.n_jobs=1", "study.surrogate.n_restarts_optimizer=0",
        "study.refine.max_simulations=0"]


def test_dynamic_verification_without_friction_is_refused_at_start():
    """The dynamic solver's rollers and cage are driven by traction: with friction off the study is
    refused before anything runs, naming the key, its value and what it allows."""
    with pytest.raises(StudyConfigError, match=r"study\.verify\.solver = 'dynamic'.*quasi_static when "
                                               r"friction\.enabled = false"):
        compose(["study.verify.solver=dynamic", "friction.enabled=false"])


def test_report_gives_the_dynamic_torque_and_skew_of_the_best_design(tmp_path):
    search = DesignSearch(compose(TINY), TINY, out_dir=tmp_path, log=lambda msg: None)
    search.run_references()
    ds, reason = search.run()
    text = write_report(search, ds, reason)
    dyn = xr.load_dataset(tmp_path / "best_design_dynamic.nc").isel(design=0, case=0)
    best = xr.load_dataset(tmp_path / "best_design.nc").isel(design=0, case=0)
    assert dyn.attrs["solver"] == "dynamic" and int(dyn.iterations) <= 2
    # the same design: the dynamic run is of the reported best
    for name in search.space.names:
        assert float(dyn[name]) == pytest.approx(float(best[name]), rel=1e-12)
    row = next(line for line in text.splitlines() if line.startswith("| 0 |"))
    cells = [c.strip() for c in row.strip("|").split("|")]
    last = dyn.isel(time=slice(-int(sim.load_config(["solver=dynamic"]).solver.dynamic.samples_per_window), None))
    # printed to 0.1 N mm and 1e-4 deg
    assert float(cells[1]) == pytest.approx(float(best.torque), abs=0.05)
    assert float(cells[4]) == pytest.approx(float(last.torque_t.mean()), abs=0.05)
    assert float(cells[7]) == pytest.approx(float(np.abs(last.roller_skew_t.mean("time")).max()), abs=5e-5)
    assert cells[9] == str(bool(dyn.converged))
    assert "best_design_dynamic" in text


def test_figure_tables_are_written_in_the_results_contract(tmp_path):
    """A docs/figures table (dims bearing x solver x component, as pinion_breakdown.py builds it)
    written by studies.verify.write_results follows DATA.md (check_result.py, when ../shared is
    there): bearing -> design with bearing_type, a case of one at the study's load, the largest
    roller skew and tilt renamed apart from the per-roller DATA.md variables, provenance attributes;
    the values are the table's."""
    import subprocess
    import sys
    from pathlib import Path

    from matplotlib.figure import Figure

    from studies.verify import write_results

    study = compose([]).study
    comps = ["rolling", "hysteresis", "sliding", "drilling", "rib", "cage", "drag"]
    torque = np.array([[5000.0, 5200.0], [3100.0, 3130.0]])
    share = np.array([0.3, 0.05, 0.05, 0.4, 0.15, 0.05, 0.0])      # of the torque, summing to 1
    ds = xr.Dataset({"torque": (("bearing", "solver"), torque, {"units": "N*mm", "long_name": "frictional torque"}),
                     "tilt": (("bearing", "solver"), np.full((2, 2), 0.02), {"units": "deg",
                                                                             "long_name": "largest |roller tilt|"}),
                     "torque_component": (("bearing", "solver", "component"), torque[:, :, None] * share,
                                          {"units": "N*mm", "long_name": "torque breakdown"})},
                    coords={"bearing": ["tsrb_pinion", "trb_31313"], "solver": ["quasi_static", "dynamic"],
                            "component": comps})
    write_results(tmp_path / "table", ds, lambda d: "table", lambda d: Figure(), study)
    out = xr.load_dataset(tmp_path / "table.nc")
    assert out.torque.dims == ("design", "case", "solver") and "roller_tilt_max" in out.data_vars
    assert out.tilt.dims == ("case",) and out.tilt.values.tolist() == [float(study.load.tilt)]   # DATA.md's case tilt
    assert list(out.bearing_type.values) == ["TSRB", "TRB"] and out.Fa.values.tolist() == [float(study.load.Fa)]
    np.testing.assert_array_equal(out.torque.isel(case=0).values, torque)
    checker = Path(__file__).resolve().parents[2].parent / "shared" / "tools" / "check_result.py"
    if checker.exists():
        chk = subprocess.run([sys.executable, str(checker), str(tmp_path / "table.nc")], capture_output=True, text=True)
        assert chk.returncode == 0, chk.stdout
