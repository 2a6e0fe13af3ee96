"""Combined-load distribution against the Harris/Stribeck line-contact form (MODEL.md 8, level 1).

For zero clearance and a rigid inner-ring displacement (delta_a, delta_r), the approach of
the roller at azimuth psi along the outer contact normal (angle beta = alpha + gamma) is
delta(psi) = delta_a sin(beta) + delta_r cos(beta) cos(psi); with the line-contact law
Q ~ delta^(10/9) this gives Harris's load distribution (Harris & Kotzalas, Essential
Concepts of Bearing Technology, 5th ed., ch. 7, the Sjovall integrals):
    Q(psi) = Q_max [1 - (1 - cos psi) / (2 eps)]^(10/9),  eps = (1 + delta_a tan(beta)/delta_r)/2.
"""
import numpy as np
import pytest

from tests.helpers import case


@pytest.mark.parametrize("Fa,Fr", [(4500.0, 2000.0), (4500.0, 5000.0), (3000.0, 8000.0)])
def test_trb_distribution_matches_harris(model_for, Fa, Fr):
    """TRB 32208, uncrowned (crown 1e-7: Harris's form assumes the straight line contact; a
    crowned roller stiffens faster than delta^(10/9) while its contact length grows), with
    independent slices (the exact 10/9 law): roller loads follow Harris's form with eps from
    the solved ring displacement. Tolerance 2 % of Q_max: the inner contact (at alpha - gamma)
    and the rib (Hertz 3/2 law) are in series with the outer contact, so the roller's approach
    is the projected ring displacement only to O(gamma^2) and rib compliance. Harris's form is
    static: no centrifugal force (with it the rollers outside the load zone rest on the cup with
    2.4 N at 2000 rpm, tests/balance/test_resting_rollers.py)."""
    model, _ = model_for("bearing=trb_32208", "bearing.crown_coefficient=1e-7", "solver.elasticity=independent",
                         "solver.centrifugal=false")
    raw = model.solve(case(Fa, Fr))
    assert raw["converged"]
    g = model.geometry
    beta = g.alpha + g.gamma
    da, dr, dy = raw["ring"]
    assert dy == 0.0                     # no friction loads: mirror-symmetric, no lateral displacement
    eps = 0.5 * (1.0 + da * np.tan(beta) / dr)
    psi = 2 * np.pi * np.arange(g.Z) / g.Z
    shape = np.clip(1.0 - (1.0 - np.cos(psi)) / (2.0 * eps), 0.0, None) ** (10.0 / 9.0)
    Q = raw["Q"][:, 0]
    np.testing.assert_allclose(Q, Q[0] * shape, atol=0.02 * Q[0])
    if eps < 1.0:  # partly unloaded: the rollers outside the load zone carry nothing
        assert np.all(Q[shape == 0.0] == 0.0)
