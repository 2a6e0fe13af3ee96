"""notebooks/sweep_analysis.ipynb runs on a sweep: its code cells, executed in order with exec()
(nbformat/nbconvert are not dependencies), open, select, group and plot without error."""
import json

import matplotlib
import numpy as np
import pytest

from tests.sweeps.common import REPO

NOTEBOOK = REPO / "notebooks" / "sweep_analysis.ipynb"


def run_notebook(sweep_nc, monkeypatch):
    """The notebook's code cells executed in order on ``sweep_nc``: their namespace."""
    matplotlib.use("Agg")
    monkeypatch.setenv("SWEEP_NC", str(sweep_nc))
    cells = [c for c in json.loads(NOTEBOOK.read_text())["cells"] if c["cell_type"] == "code"]
    ns = {}
    for cell in cells:
        exec(compile("".join(cell["source"]), f"{NOTEBOOK.name} cell", "exec"), ns)
    return ns


@pytest.mark.smoke
def test_notebook_runs_on_a_sweep(parallel_sweep, monkeypatch):
    ns = run_notebook(parallel_sweep.nc, monkeypatch)
    assert ns["swept"] == ["PCR"]
    assert ns["breakdown"] is None      # friction off: no torque cell output
    assert ns["pmax"].shape == (3, 4) and np.isnan(ns["pmax"].values[0]).all()
    assert list(ns["mean_by_Fa"].Fa.values) == [3000.0, 5000.0]
    assert len(ns["failures"]) == 4
    matplotlib.pyplot.close("all")


def test_notebook_shows_the_torque_of_a_friction_sweep(friction_sweep, monkeypatch):
    """On a sweep with friction (the default; a TSRB and a TRB), the torque cell plots torque against Fa
    and the breakdown of the largest torque (the TRB's at 80 kN): its components sum to that torque (DATA.md; rtol 1e-9, the
    round-off of seven terms written to NetCDF and read back is ~1e-15)."""
    ns = run_notebook(friction_sweep.nc, monkeypatch)
    torque = ns["torque"]
    assert np.isfinite(torque.values[0, 0]) and np.isnan(torque.values[0, 1])   # 80 kN: no result
    np.testing.assert_allclose(ns["breakdown"].sum(), float(np.nanmax(torque.values)), rtol=1e-9)
    assert len(ns["failures"]) == 1
    matplotlib.pyplot.close("all")
