"""notebooks/sweep_analysis.ipynb runs on a sweep: its code cells, executed in order with exec()
(nbformat/nbconvert are not dependencies), open, select, group and plot without error."""
import json

import matplotlib
import numpy as np
import pytest

from tests.sweeps.common import REPO

NOTEBOOK = REPO / "notebooks" / "sweep_analysis.ipynb"


@pytest.mark.smoke
def test_notebook_runs_on_a_sweep(parallel_sweep, monkeypatch):
    matplotlib.use("Agg")
    monkeypatch.setenv("SWEEP_NC", str(parallel_sweep.nc))
    cells = [c for c in json.loads(NOTEBOOK.read_text())["cells"] if c["cell_type"] == "code"]
    ns = {}
    for cell in cells:
        exec(compile("".join(cell["source"]), f"{NOTEBOOK.name} cell", "exec"), ns)
    assert ns["swept"] == ["PCR"]
    assert ns["pmax"].shape == (3, 4) and np.isnan(ns["pmax"].values[0]).all()
    assert list(ns["mean_by_Fa"].Fa.values) == [3000.0, 5000.0]
    assert len(ns["failures"]) == 4
    matplotlib.pyplot.close("all")
