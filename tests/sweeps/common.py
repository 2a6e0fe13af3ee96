"""Settings and the command of the sweep tests (the fixture lives in conftest.py)."""
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
FAST = ["friction.enabled=false", "solver.n_slices=8"]
# 3 designs x 2 axial loads as jobs, each job a grid of 2 radial loads: 6 jobs, 3 x 4 points.
# PCR = 8 mm is impossible (sim.geometry: PCR > Lwe / (2 (1 - sin gamma)) = 8.857 mm): a failed design.
SWEEP = ["bearing.PCR=8,90,110", "load.Fa=3000,5000", "load.Fr=[0,2000]"]


# A sweep with friction on, the default (8 slices), over a TSRB and a TRB (whose rib contact adds its own
# friction term): the TSRB's 80 kN case is beyond the static limit after the solve (pmax ~5 GPa,
# tests/published/test_static_capacity.py), the TRB's (C0 / Y0 ~ 118 kN) is not.
FRICTION_SWEEP = ["bearing=tsrb_reference,trb_32208", "load.Fa=3000,80000", "load.Fr=0", "solver.n_slices=8"]


def multirun(args, sweep_dir, cache_dir, fast=True, **kwargs):
    """``python -m sim.run --multirun`` with the fast settings (``fast``: friction off), into
    ``sweep_dir`` with its own cache."""
    cmd = [sys.executable, "-m", "sim.run", "--multirun", *args, *(FAST if fast else []),
           f"output.cache_dir={cache_dir}", f"hydra.sweep.dir={sweep_dir}"]
    return subprocess.run(cmd, cwd=REPO, capture_output=True, text=True, timeout=600, **kwargs)
