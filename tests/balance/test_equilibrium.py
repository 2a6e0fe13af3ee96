"""Force balance of the inner ring and of every roller under combined load (MODEL.md 8, level 2)."""
import numpy as np
import pytest

from sim.contact import roller_axes
from sim.solvers.quasi_static import roller_state
from tests.helpers import case, contact_forces_on_inner_ring

CASES = [("tsrb_reference", 4500.0, 2000.0, 0.0), ("tsrb_reference", 4000.0, 6000.0, 0.0),
         ("tsrb_reference", 4500.0, 2000.0, 2.5 / 60.0), ("trb_32208", 4500.0, 2000.0, 0.0),
         ("trb_32208", 5000.0, 8000.0, 2.5 / 60.0), ("tsrb_pinion", 35000.0, 5000.0, 0.0)]


def _roller_residuals(model, raw, op):
    g = model.geometry
    a = g.arrays
    body = model.body_loads(op)
    out = []
    for j in range(g.Z):
        psi = 2 * np.pi * j / g.Z
        q = raw["line_load"][j].copy()
        act = q > 0
        f = np.zeros(5)
        K = np.zeros((5, 5))
        Q = np.zeros(4)
        roller_state(raw["poses"][j].copy(), raw["ring"], np.radians(op.tilt) * np.cos(psi), np.cos(psi), g.alpha,
                     g.Dpw, a["x"], a["rho"], a["w"], a["race_kind"], a["race_par"], a["R_eq"], model.C, model.E_star,
                     model.mode, model.k_line, a["rib"], g.type == "TRB", q, act, 1e-13, f, K, Q)
        if Q[0] + Q[1] == 0.0:
            continue  # unloaded roller, held by the cage
        ur, uz, vr, vz = roller_axes(g.alpha, raw["poses"][j, 2])
        r = f[:3] + np.array([body[0] * ur, body[0] * vr, body[1]])
        scale = Q[0] + Q[1] + Q[2]
        out.append(max(abs(r[0]), abs(r[1]), abs(r[2]) / g.Lwe) / scale)
    return np.array(out)


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
        Fx, Fz = contact_forces_on_inner_ring(model, raw)
        np.testing.assert_allclose([Fx + Fr, Fz + Fa], 0.0, atol=1e-8 * scale)
    np.testing.assert_allclose(raw["residual"], 0.0, atol=1e-8 * scale)
    assert np.all(_roller_residuals(model, raw, op) < 1e-8)


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
