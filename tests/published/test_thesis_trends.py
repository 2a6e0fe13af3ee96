"""Trends the thesis reports (MODEL.md 8, level 3; thesis_data.yaml reported_results)."""
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import sim
from tests.helpers import case

REPO = Path(__file__).resolve().parents[2]


def test_axial_displacement_rises_steeply_with_PCR():
    """Table A.6 (pinion, alpha 24.5, aPk 6.05, kappa 0.99, Fa = 35 kN, 1100 rpm): the roller
    axial displacement falls steeply as PCR shrinks (2.0, 0.85, 0.07, 0.047 mm for PCR 200,
    150, 100, 90). Direction and order of magnitude, not the exact numbers (MODEL.md 8):
    monotone, PCR 150 at least 3x PCR 100, PCR 90 within a factor 5 of 0.047 mm."""
    disp = {}
    for PCR in (150, 100, 90):
        ds = sim.simulate(sim.load_config(
            ["bearing=tsrb_pinion", f"bearing.PCR={PCR}", "bearing.aPk=6.05", "bearing.kappa=0.99",
             "load.Fa=35000", "load.Fr=0", "load.speed=1100"]))
        assert bool(ds.converged.all())
        disp[PCR] = float(ds.axial_displacement.squeeze())
    assert disp[150] > disp[100] > disp[90] > 0.0
    assert disp[150] > 3.0 * disp[100]
    assert 0.047 / 5 < disp[90] < 0.047 * 5


def test_prototype_contact_shorter_than_trb():
    """Thesis 6.4/7.1 (reported_results.contact_length): at Fa = 4.5 kN the prototype loads
    0.35-0.50 of its roller length, the TRB 32208 0.80-0.88: the prototype's ratio is smaller
    at every radial load 0, 2, 4 kN."""
    for Fr in (0.0, 2000.0, 4000.0):
        r = {}
        for b in ("tsrb_prototype", "trb_32208"):
            ds = sim.simulate(sim.load_config([f"bearing={b}", "load.Fa=4500", f"load.Fr={Fr}"]))
            r[b] = float(ds.contact_length_ratio.sel(race="outer").squeeze())
        assert r["tsrb_prototype"] < r["trb_32208"], (Fr, r)


def test_load_centroid_at_PCR_sin_gamma(model_for):
    """MODEL.md 4 closed form: with no rib, friction or centrifugal force, the load centroid of
    both races along the roller (from mid-length) sits at x* = PCR sin(gamma), to first order
    in the crown angles. Tolerance 10 % of x*: the neglected terms are of order
    (Lwe/(2 PCR))^2 and gamma^2 relative, a few per cent here, plus slice discretisation."""
    for bearing in ("tsrb_reference", "tsrb_pinion"):
        model, _ = model_for(f"bearing={bearing}", "solver.centrifugal=false", "solver.gyroscopic=false")
        raw = model.solve(case(4500.0 if bearing == "tsrb_reference" else 35000.0, speed=0.0))
        assert raw["converged"]
        q = raw["line_load"][0]             # (race, slice)
        x = model.geometry.arrays["x"]
        # contact points on the roller move with the roller shift xi relative to the rings
        centroid = np.sum(q * x[None, :]) / np.sum(q)
        x_star = model.geometry.load_centroid_x
        np.testing.assert_allclose(centroid, x_star, rtol=0.10)


@pytest.mark.smoke
def test_command_line_writes_checked_result(tmp_path):
    """The documented command line writes result.nc in Hydra's run directory, and the file
    passes the project's contract checker (../shared/tools/check_result.py) when present."""
    cmd = [sys.executable, "-m", "sim.run", "bearing=trb_32208", "load.Fa=4500", "load.Fr=2000",
           "load.speed=2000", "load.tilt=0", f"hydra.run.dir={tmp_path}"]
    out = subprocess.run(cmd, cwd=REPO, capture_output=True, text=True, timeout=600)
    assert out.returncode == 0, out.stderr
    assert "pmax" in out.stdout
    result = tmp_path / "result.nc"
    ds = xr.open_dataset(result)
    assert bool(ds.converged.all()) and ds.sizes["design"] == 1 and ds.sizes["case"] == 1
    assert float(ds.torque.squeeze()) > 0.0 and "torque_component" in ds and "film_thickness" in ds
    ds.close()
    checker = REPO.parent / "shared" / "tools" / "check_result.py"
    if checker.exists():
        chk = subprocess.run([sys.executable, str(checker), str(result)], capture_output=True, text=True)
        assert chk.returncode == 0, chk.stdout


def test_friction_disabled_writes_no_torque():
    """With friction.enabled=false the result holds the load distribution only: no placeholder torque."""
    ds = sim.simulate(sim.load_config(["bearing=trb_32208", "friction.enabled=false", "solver.n_slices=10"]))
    assert bool(ds.converged.all())
    for name in ("torque", "torque_component", "power_loss", "srr", "film_thickness", "lambda_ratio"):
        assert name not in ds


def test_bad_load_input_is_refused():
    """Bad input gets an error naming the key, its value and the allowed range, before any numerics."""
    with pytest.raises(ValueError, match=r"load\.Fa = -1 is outside the allowed range"):
        sim.simulate(sim.load_config(["load.Fa=-1"]))
    with pytest.raises(ValueError, match=r"solver\.elasticity = 'rigid'"):
        sim.simulate(sim.load_config(["solver.elasticity=rigid"]))
