"""Force balance of the inner ring and of every roller under combined load (MODEL.md 8, level 2)."""
import numpy as np
import pytest

from tests.helpers import case, race_forces, roller_residuals

CASES = [("tsrb_reference", 4500.0, 2000.0, 0.0), ("tsrb_reference", 4000.0, 6000.0, 0.0),
         ("tsrb_reference", 4500.0, 2000.0, 2.5 / 60.0), ("trb_32208", 4500.0, 2000.0, 0.0),
         ("trb_32208", 5000.0, 8000.0, 2.5 / 60.0), ("tsrb_pinion", 35000.0, 5000.0, 0.0)]


@pytest.mark.parametrize("bearing,Fa,Fr,tilt", CASES)
def test_ring_and_roller_balance(model_for, bearing, Fa, Fr, tilt):
    """Inner ring: external (Fa, Fr) + roller forces = 0; each loaded roller: contact + body
    forces and moment = 0. Tolerance: the solver's relative force tolerance (1e-9) times 10
    for the roller level (it is solved to 0.1 of it but re-evaluated from the stored loads)."""
    model, _ = model_for(f"bearing={bearing}")
    op = case(Fa, Fr, tilt=tilt)
    raw = model.solve(op)
    assert raw["converged"]
    scale = max(Fa, Fr)
    if model.geometry.type == "TSRB" and tilt == 0.0:
        # independent recomputation from slice loads and kernel normals (no rib)
        Fx, Fz = race_forces(model, raw, 1, tilt)
        np.testing.assert_allclose([Fx + Fr, Fz + Fa], 0.0, atol=1e-8 * scale)
    np.testing.assert_allclose(raw["residual"], 0.0, atol=1e-8 * scale)
    assert np.all(roller_residuals(model, raw, op) < 1e-8)


def test_radial_load_makes_roller_0_the_most_loaded(model_for):
    """Roller 0 sits under Fr (MODEL.md 1): it is the most loaded, loads fall with |psi|, and
    rollers at +psi and -psi carry equal loads (symmetry, to round-off)."""
    model, _ = model_for("bearing=trb_32208")
    raw = model.solve(case(4500.0, 4000.0))
    Q = raw["Q"][:, 0]
    assert np.argmax(Q) == 0
    half = Q[: model.geometry.Z // 2 + 1]
    assert np.all(np.diff(half) <= 1e-9 * Q[0])
    np.testing.assert_allclose(Q[1:], Q[1:][::-1], rtol=1e-12)
