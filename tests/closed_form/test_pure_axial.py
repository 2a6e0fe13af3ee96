"""Pure axial load: equal shares and the closed form Q = Fa / (Z sin(contact angle)) (MODEL.md 8, level 1)."""
import numpy as np
import pytest

from tests.helpers import case, race_forces


@pytest.mark.parametrize("bearing,Fa", [("trb_32208", 4500.0), ("trb_31313", 35000.0), ("trb_32208", 40000.0)])
def test_trb_outer_load_closed_form(model_for, bearing, Fa):
    """TRB: the outer raceway is a straight cone at alpha + gamma (MODEL.md 2), so every roller
    carries Q_o = Fa / (Z sin(alpha + gamma)) exactly. Tolerance: solver force tolerance 1e-9
    relative, 1e-7 leaves margin for the roller-level tolerance."""
    model, _ = model_for(f"bearing={bearing}")
    raw = model.solve(case(Fa))
    g = model.geometry
    assert raw["converged"]
    expected = Fa / (g.Z * np.sin(g.alpha + g.gamma))
    np.testing.assert_allclose(raw["Q"][:, 0], expected, rtol=1e-7)


@pytest.mark.parametrize("bearing", ["tsrb_reference", "tsrb_prototype", "tsrb_pinion", "trb_32208"])
def test_shares_equal_and_sum_to_Fa(model_for, bearing):
    """Every roller carries the same load and the inner-raceway forces add up to Fa (and to no
    radial force). Tolerance 1e-7 relative: solver tolerance 1e-9 plus roller-level margin;
    the TRB's rib takes part of Fa, so its axial sum is checked with the rib included."""
    model, _ = model_for(f"bearing={bearing}")
    Fa = 4500.0
    raw = model.solve(case(Fa))
    assert raw["converged"]
    Q = raw["Q"]
    np.testing.assert_allclose(Q, np.broadcast_to(Q[0], Q.shape), rtol=1e-12)
    Fx, Fz = race_forces(model, raw)
    assert abs(Fx) < 1e-6 * Fa
    if model.geometry.type == "TSRB":
        # force of the rollers on the inner ring balances the external Fa along +z
        np.testing.assert_allclose(-Fz, Fa, rtol=1e-7)
        assert np.all(raw["Q_rib"] == 0.0)
    else:
        assert np.all(raw["Q_rib"] > 0.0) and -Fz < Fa


def test_trb_rib_takes_the_axial_component(model_for):
    """TRB (thesis Fig. 2.4, 2.1.3): the rib balances the raceway forces along the roller axis,
    Q_rib ~ (Q_o + Q_i) sin(gamma) to first order in the small rib-normal and tilt angles
    (tolerance 3 %: the rib normal is inclined by about 2 deg and the roller tilts slightly)."""
    model, _ = model_for("bearing=trb_32208")
    raw = model.solve(case(4500.0))
    Qo, Qi = raw["Q"][0]
    np.testing.assert_allclose(raw["Q_rib"][0], (Qo + Qi) * np.sin(model.geometry.gamma), rtol=0.03)
