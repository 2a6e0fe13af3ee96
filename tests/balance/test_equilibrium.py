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


@pytest.mark.parametrize("Z", [9, 10])
def test_symmetry_classes(Z):
    """sim.solvers.symmetry: the classes stand for every roller once (weights sum to Z, each
    roller's representative carries its weight), roller Z - j mirrors roller j also under tilt
    (phi = tilt cos(psi) is even in psi), one roller stands for all only without Fr, tilt and
    unequal roller loads, and unequal loads on psi and -psi leave every roller its own class."""
    from sim.solvers.symmetry import symmetry_classes

    zero = np.zeros((Z, 3))
    n, weight, source = symmetry_classes(Z, 0.0, 0.0, zero)
    assert n == 1 and weight.sum() == Z and np.all(source == 0)
    for Fr, tilt in ((2000.0, 0.0), (0.0, 0.004), (2000.0, 0.004)):
        n, weight, source = symmetry_classes(Z, Fr, tilt, zero)
        assert n == Z // 2 + 1 and weight.sum() == Z
        j = np.arange(Z)
        np.testing.assert_array_equal(source, np.where(j < n, j, Z - j))
        np.testing.assert_array_equal(np.bincount(source, minlength=Z), weight)
    loads = np.ones((Z, 3))
    loads[1, 0] = 2.0  # roller 1 unlike roller Z - 1
    n, weight, source = symmetry_classes(Z, 0.0, 0.0, loads)
    assert n == Z and np.all(weight == 1.0) and np.all(source == np.arange(Z))


def test_mirror_reduction_equals_the_full_solve(model_for):
    """Thesis Fig. 6.10 case (prototype, Fa 4.5 kN, Fr 2 kN, tilt 0.25 deg): solving Z // 2 + 1
    mirror classes gives the state of solving all Z rollers (the mirror switched off by a 1e-200 N
    roller load, far below round-off of any residual). Tolerance 1e-9 of the ring displacement
    and of the largest roller load: the solver tolerance (both solves stop within it)."""
    model, _ = model_for("bearing=tsrb_prototype")
    op = case(4500.0, 2000.0, tilt=0.25)
    mirrored = model.solve(op)
    ext = np.zeros((model.geometry.Z, 3))
    ext[1, 1] = 1e-200
    full = model.solve(op, roller_loads=ext)
    assert mirrored["converged"] and full["converged"]
    assert mirrored["solver_info"]["roller_classes"] == model.geometry.Z // 2 + 1
    assert full["solver_info"]["roller_classes"] == model.geometry.Z
    np.testing.assert_allclose(full["ring"], mirrored["ring"], rtol=0, atol=1e-9 * np.abs(mirrored["ring"]).max())
    np.testing.assert_allclose(full["Q"], mirrored["Q"], rtol=0, atol=1e-9 * mirrored["Q"].max())
