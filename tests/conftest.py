"""Shared fixtures; plain helpers live in tests/helpers.py."""
import pytest

import sim
from sim.api.simulation import build_model


@pytest.fixture
def model_for():
    """model_for(*overrides) -> (BearingModel, cfg), composed like the command line."""

    def make(*overrides):
        cfg = sim.load_config(list(overrides))
        return build_model(cfg), cfg

    return make
