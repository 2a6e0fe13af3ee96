"""The torus roller end of the TRB (bearing.roller_end = torus; thesis 5.5.1, docs/roller_end_torus.md):
its elliptical Hertz contact against an independent exact solution, the contact point and normal of
a skewed roller against a direct 3-D closest-point computation, and the exact tangent stiffness of
the off-axis circle in the meridian-plane rib contact."""
import numpy as np
import pytest
from scipy.optimize import brentq, minimize
from scipy.special import ellipe, ellipk

import sim
from sim.api.simulation import build_model
from sim.geometry import Geometry
from sim.physics.contact import hertz_point_radii
from sim.physics.friction import lateral_slip_rate
from tests.helpers import case, contact_stiffness_and_difference, roller_residuals


def torus_geometry(bearing="trb_31313", *overrides):
    cfg = sim.load_config([f"bearing={bearing}", "bearing.roller_end=torus", *overrides])
    return Geometry.from_config(cfg.bearing, cfg.material, cfg.solver.n_slices)


def hertz_exact(R_a, R_b, Q=100.0, E_star=1.0e5):
    """Elliptical Hertz contact by scipy's elliptic integrals and root finder (Johnson 1985,
    3.70-3.72; R_a > R_b): (R_load, R_area, k) as sim.physics.contact.hertz_point_radii defines
    them, from the semi-axes a, b and approach delta of the load Q."""
    A, B = 0.5 / R_a, 0.5 / R_b
    m = brentq(lambda m: (ellipe(m) / (1.0 - m) - ellipk(m)) / (ellipk(m) - ellipe(m)) - B / A, 1e-9, 1.0 - 1e-15,
               xtol=1e-16, rtol=1e-15)
    K, E = ellipk(m), ellipe(m)
    k = 1.0 / np.sqrt(1.0 - m)
    a = (3.0 * Q * (K - E) / (2.0 * np.pi * E_star * m * A)) ** (1.0 / 3.0)
    b = a / k
    delta = 3.0 * Q / (2.0 * np.pi * a * b) * b * K / E_star
    return (3.0 * Q / (4.0 * E_star * delta**1.5)) ** 2, 4.0 * E_star * (a * b) ** 1.5 / (3.0 * Q), k


@pytest.mark.parametrize("ratio", [1.5, 10.0, 100.0, 475.0, 3000.0])
def test_elliptical_hertz_matches_the_exact_solution(ratio):
    """hertz_point_radii (AGM elliptic integrals, bisection on ln k) against scipy's ellipk/ellipe
    and brentq at radius ratios up to the torus's (R_t / r_k = 475 at the TRB 31313's 5 deg):
    equivalent load radius, area radius and semi-axis ratio to 1e-10 (both are exact; the
    bisection stops at 2^-60 of ln(ratio), the AGM at round-off). Both orientations: kappa is the
    semi-axis along the first radius over the other."""
    R_b = 0.8
    ref = hertz_exact(ratio * R_b, R_b)
    got = hertz_point_radii(ratio * R_b, R_b)
    np.testing.assert_allclose(got, ref, rtol=1e-10)
    swapped = hertz_point_radii(R_b, ratio * R_b)
    np.testing.assert_allclose(swapped[:2], ref[:2], rtol=1e-10)
    assert swapped[2] == pytest.approx(1.0 / ref[2], rel=1e-10)


def test_elliptical_hertz_tends_to_the_circle_and_to_hamrock_brewe():
    """Closed forms: Rx == Ry is Johnson's sphere on a plane exactly (R, R, 1); a nearly circular
    contact has the mean radius (R' = R/2 to first order in the radius difference, so R_load and
    R_area -> (Rx + Ry) / 2, error second order, 1e-12 at 1e-6 apart, plus the round-off of the
    ellipticity equation near the circle, eps / 1e-6 ~ 2e-10: tolerance 1e-10, measured 2e-11); and the semi-axis ratio
    follows Hamrock & Brewe's (1983) k = (R_a/R_b)^(2/pi) within the 3 % they state for it
    (measured here: at most 3.7 % short of it between ratios 1.5 and 100)."""
    assert hertz_point_radii(0.8, 0.8) == (0.8, 0.8, 1.0)
    near = hertz_point_radii(1.0 + 1e-6, 1.0)
    np.testing.assert_allclose(near, [1.0 + 0.5e-6, 1.0 + 0.5e-6, near[2]], rtol=1e-10)
    for ratio in (1.5, 2.0, 5.0, 10.0, 30.0, 100.0):
        assert hertz_point_radii(ratio, 1.0)[2] == pytest.approx(ratio ** (2.0 / np.pi), rel=0.04)


def skewed_contact_3d(g, psi):
    """Deepest point of the skewed torus in the cone rib, by direct 3-D minimisation (scipy).

    Bearing axis z; the roller's meridian plane at azimuth 0 is the (x, z) plane (r along x,
    e_t = y); roller centre (Dpw/2, 0, 0), u = (sin a, 0, -cos a), v = (cos a, 0, sin a) (sim.geometry).
    Skew psi about v through the centre: u'' = cos(psi) u + sin(psi) e_t. Torus points
    P = c + (c_x + r_k cos t) u'' + (a + r_k sin t) e(p), e(p) = -cos(p) v + sin(p) w'', w'' = u'' x v
    (the radial direction of the end plane at rim angle p; a the rim radius). The rib: the cone of revolution about z whose
    generatrix passes through the nominal contact point with the nominal normal N (into the rib);
    penetration of a point = (r - L_r) N_r + (z - L_z) N_z in its own meridian plane (exact for a
    cone of revolution). Returns the deepest point P [mm] and its penetration [mm]."""
    rib = g.arrays["rib"]
    c_x, c_y, r_k, n_x, n_y = rib[:5]
    a_rim = -c_y
    sa, ca = np.sin(g.alpha), np.cos(g.alpha)
    C = np.array([0.5 * g.Dpw, 0.0, 0.0])
    u, v, et = np.array([sa, 0.0, -ca]), np.array([ca, 0.0, sa]), np.array([0.0, 1.0, 0.0])
    u2 = np.cos(psi) * u + np.sin(psi) * et
    w2 = np.cross(u2, v)                                    # completes (u'', v, w'') in the end plane
    N = n_x * np.array([sa, -ca]) + n_y * np.array([ca, sa])                  # (r, z)
    L = np.array([0.5 * g.Dpw + c_x * sa + c_y * ca, -c_x * ca + c_y * sa]) + r_k * N

    def point(s):
        p, t = s
        e = -np.cos(p) * v + np.sin(p) * w2
        return C + (c_x + r_k * np.cos(t)) * u2 + (a_rim + r_k * np.sin(t)) * e

    def depth(s):
        P = point(s)
        return (np.hypot(P[0], P[1]) - L[0]) * N[0] + (P[2] - L[1]) * N[1]

    t0 = np.arctan2(-n_y, n_x)
    res = minimize(lambda s: -depth(s), np.array([0.0, t0]), method="Nelder-Mead",
                   options={"xatol": 1e-13, "fatol": 1e-18, "maxiter": 20000})
    return point(res.x), depth(res.x)


@pytest.mark.parametrize("opening_deg", [5.0, 8.0])
def test_skewed_torus_touches_the_cone_where_the_first_order_theory_says(opening_deg):
    """First order in the skew psi (docs/roller_end_torus.md): the contact point lies at the bearing
    azimuth phi = f psi, f = x_n / (X_r - R_n n_r) with R_n = r_k + a / sin(b), x_n = c_x - a cot(b)
    (the normal meets the roller axis there: the torus acts as a sphere of radius R_n centred on the
    axis at x_n), the same f as the slices' lateral_slip_rate for a surface of revolution about the
    roller axis. Checked against the 3-D deepest point of the skewed torus in the cone rib by a
    central difference in psi = +-2e-5 rad (TRB 31313, r_k 0.8 mm): the difference's error is second
    order, (f psi)^2 ~ 1e-9 relative; the minimiser's position error ~ sqrt(fatol / curvature) ~
    1e-8 mm over a rim displacement f psi X_r ~ 1e-2 mm; tolerance 1e-4.
    The restoring moment of the rib load about v' per radian (its point moving along e_t by X_r f psi,
    its normal turning by f psi), as roller_traction applies it, matches the 3-D moment's
    difference to the same tolerance."""
    g = torus_geometry("trb_31313", f"bearing.rib_opening_angle={opening_deg}")
    R_n, x_n = g.arrays["rib_end"][:2]
    rib = g.arrays["rib"]
    sa, ca = np.sin(g.alpha), np.cos(g.alpha)
    dx, dy = rib[0] + rib[2] * rib[3], rib[1] + rib[2] * rib[4]   # contact point from the roller centre
    X_r = 0.5 * g.Dpw + dx * sa + dy * ca
    nr, nz = rib[3] * sa + rib[4] * ca, -rib[3] * ca + rib[4] * sa
    f_closed = x_n / (X_r - R_n * nr)
    f_kernel = lateral_slip_rate(1.0, X_r, dx * sa + dy * ca, -dx * ca + dy * sa, nr, nz, sa, -ca, ca, sa)[1]
    h = 2e-5
    P_plus, d_plus = skewed_contact_3d(g, h)
    P_minus, _ = skewed_contact_3d(g, -h)
    P0, d0 = skewed_contact_3d(g, 0.0)
    assert abs(d0) < 1e-12 and d_plus < 1e-6                 # touching at zero skew; O(psi^2) after it
    f_3d = (np.arctan2(P_plus[1], P_plus[0]) - np.arctan2(P_minus[1], P_minus[0])) / (2.0 * h)
    assert f_closed == pytest.approx(f_3d, rel=1e-4)
    assert f_kernel == pytest.approx(f_closed, rel=1e-12)
    # moment about v' of a unit rib load -N(P), N the cone's normal at P's azimuth, against the one
    # sim.physics.friction.roller_traction applies per radian of skew (the slices' normal-load form)
    C = np.array([0.5 * g.Dpw, 0.0, 0.0])
    v = np.array([ca, 0.0, sa])

    def moment(P):
        az = np.arctan2(P[1], P[0])
        N3 = np.array([nr * np.cos(az), nr * np.sin(az), nz])
        return np.dot(np.cross(P - C, -N3), v)

    dM_3d = (moment(P_plus) - moment(P_minus)) / (2.0 * h)
    dr, dz = dx * sa + dy * ca, -dx * ca + dy * sa
    dM_kernel = -f_closed * (X_r * (nz * ca - nr * sa) + nr * (dr * sa - dz * ca))
    assert dM_kernel == pytest.approx(dM_3d, rel=1e-4)


def test_torus_rib_stiffness_is_the_exact_derivative_of_the_forces():
    """The tangent stiffness K = -df/dy of one roller (sim.physics.roller_contact) with the torus's
    off-axis circle (centre (c_x, -a) in the roller frame: G row cx v'.n - cy u'.n and geometric
    term -Q n.(cx u' + cy v')) equals a central finite difference of its generalised forces. TRB
    32208, torus, 4.5 kN axial and 2 kN radial, independent slices (a smooth load law), the most
    loaded roller. Step 1e-7 mm / rad; tolerance 1e-4 of each column's largest entry, as
    tests/closed_form/test_asymmetric_osculation.py (truncation (h/d)^2 of the least loaded slice,
    round-off eps f / h ~ 1e-9)."""
    model = build_model(sim.load_config(["bearing=trb_32208", "bearing.roller_end=torus",
                                         "solver.elasticity=independent"]))
    raw = model.solve(case(4500.0, 2000.0, speed=0.0))
    assert raw["converged"]
    j = int(np.argmax(raw["Q_rib"]))
    assert raw["Q_rib"][j] > 0.0
    K, J = contact_stiffness_and_difference(model, raw, j, np.cos(2.0 * np.pi * j / model.geometry.Z))
    scale = np.abs(J).max(axis=0)
    assert np.all(np.abs(K - J).max(axis=0) / scale < 1e-4)


def test_torus_bearing_is_in_balance():
    """Inner ring and every loaded roller in balance with the torus end (tolerances of
    tests/balance/test_equilibrium.py: 1e-8 of the load)."""
    model = build_model(sim.load_config(["bearing=trb_31313", "bearing.roller_end=torus"]))
    op = case(35000.0, 5000.0, speed=0.0)
    raw = model.solve(op)
    assert raw["converged"]
    np.testing.assert_allclose(raw["residual"], 0.0, atol=1e-8 * 35000.0)
    assert np.all(roller_residuals(model, raw, op) < 1e-8)
    assert np.all(raw["Q_rib"] > 0.0)


def test_geometry_refuses_an_opening_at_which_the_end_conforms_to_the_rib():
    """Below the opening angle where the torus's circumferential curvature 1/R_n equals the cone
    rib's n_r / X_r the end would touch the rib at two points off the meridian plane: refused with
    the key, its value and the limit (3.83 deg for the TRB 31313 at r_k 0.8 mm)."""
    from sim.errors import GeometryError

    g = torus_geometry("trb_31313")
    limit = np.degrees(g._torus_opening_limit())
    assert 3.7 < limit < 4.0
    with pytest.raises(GeometryError) as err:
        torus_geometry("trb_31313", "bearing.rib_opening_angle=3.5")
    assert err.value.key == "bearing.rib_opening_angle" and err.value.rule == "torus_rib_convex"
    assert err.value.limit == pytest.approx(limit, rel=1e-9)
    torus_geometry("trb_31313", f"bearing.rib_opening_angle={limit * 1.01}")
