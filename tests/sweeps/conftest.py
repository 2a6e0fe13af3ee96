"""Sweep tests: one small multirun per session, run as a new user would (a subprocess).

The load distribution only (``friction.enabled=false``) with 8 slices keeps every case at a few
ms, so the sweep tests take seconds; the collector's handling of friction variables is tested by
adding them to run files (test_collector.py) and on a small sweep with friction (``friction_sweep``).
"""
from types import SimpleNamespace

import pytest

from tests.sweeps.common import FRICTION_SWEEP, SWEEP, multirun


@pytest.fixture(scope="session")
def parallel_sweep(tmp_path_factory):
    """The sweep on all cores (joblib launcher), uninterrupted, with a fresh cache."""
    root = tmp_path_factory.mktemp("parallel")
    out = multirun(["hydra/launcher=parallel", *SWEEP], root / "sweep", root / "cache")
    assert out.returncode == 0, out.stderr[-3000:]
    return SimpleNamespace(dir=root / "sweep", nc=root / "sweep" / "sweep.nc", cache=root / "cache",
                           log=out.stdout + out.stderr)


@pytest.fixture(scope="session")
def friction_sweep(tmp_path_factory):
    """A sweep with friction on, as the README runs one (common.FRICTION_SWEEP): its folder and log."""
    root = tmp_path_factory.mktemp("friction")
    out = multirun(FRICTION_SWEEP, root / "sweep", root / "cache", fast=False)
    assert out.returncode == 0, out.stderr[-3000:]
    return SimpleNamespace(dir=root / "sweep", nc=root / "sweep" / "sweep.nc", log=out.stdout + out.stderr,
                           stderr=out.stderr)
