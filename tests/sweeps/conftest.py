"""Sweep tests: one small multirun per session, run as a new user would (a subprocess).

The load distribution only (``friction.enabled=false``) with 8 slices keeps every case at a few
ms, so the sweep tests take seconds; the collector's handling of friction variables is tested by
adding them to run files (test_collector.py).
"""
from types import SimpleNamespace

import pytest

from tests.sweeps.common import SWEEP, multirun


@pytest.fixture(scope="session")
def parallel_sweep(tmp_path_factory):
    """The sweep on all cores (joblib launcher), uninterrupted, with a fresh cache."""
    root = tmp_path_factory.mktemp("parallel")
    out = multirun(["hydra/launcher=parallel", *SWEEP], root / "sweep", root / "cache")
    assert out.returncode == 0, out.stderr[-3000:]
    return SimpleNamespace(dir=root / "sweep", nc=root / "sweep" / "sweep.nc", cache=root / "cache",
                           log=out.stdout + out.stderr)
