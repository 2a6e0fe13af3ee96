"""Roller skew as an unknown of the quasi-static friction kinematics (issue 18 item 1).

sim.physics.friction ("Roller skew"): the skew psi turns the roller about its radial axis v';
each slice slips laterally by psi times :func:`lateral_slip_rate`; the traction acts along the
2-D slip; the friction moment about v' and the cage pocket couple balance per roller
(sim.solvers.kinematics). Units: N, mm, s, rad (deg in the Dataset).
"""
import functools
import math

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

import sim
from sim.api.cases import operating_points
from sim.api.friction_model import inner_ring_poses
from sim.api.simulation import build_friction, build_model
from sim.physics import friction as F
from sim.physics.elasticity import END_DROP_POINTS
from sim.solvers.kinematics import (FINAL_TOLERANCE_FACTOR, KinematicsSettings, empty_jacobian, solve_friction,
                                    solve_kinematics, solve_kinematics_newton)

PINION = ["lubricant=pinion_oil", "load.Fa=35000", "load.Fr=0", "load.speed=1100"]
CASES = {
    "tsrb_reference combined": ["bearing=tsrb_reference", "load.Fa=4500", "load.Fr=2000"],
    "trb_32208 combined": ["bearing=trb_32208", "load.Fa=4500", "load.Fr=2000"],
    "tsrb_pinion 35 kN": ["bearing=tsrb_pinion", *PINION],
    "trb_31313 35 kN": ["bearing=trb_31313", *PINION],
    # the thesis's torus roller end (bearing.roller_end = torus, docs/roller_end_torus.md)
    "trb_32208 combined torus": ["bearing=trb_32208", "bearing.roller_end=torus", "load.Fa=4500", "load.Fr=2000"],
    "trb_31313 35 kN torus": ["bearing=trb_31313", "bearing.roller_end=torus", *PINION],
    # the prototype, whose skew reverses with the oil temperature (below; tests/dynamic/test_ladder.py)
    "tsrb_prototype 25 degC": ["bearing=tsrb_prototype", "load.Fa=3462", "load.Fr=0", "load.speed=4199",
                               "load.oil_temperature=25"],
    "tsrb_prototype 60 degC": ["bearing=tsrb_prototype", "load.Fa=3462", "load.Fr=0", "load.speed=4199",
                               "load.oil_temperature=60"],
}


def models(overrides):
    cfg = sim.load_config([*overrides, "friction.skew.enabled=true"])
    model = build_model(cfg)
    return model, build_friction(cfg, model), next(iter(operating_points(cfg.load)))


@functools.lru_cache(maxsize=None)
def solved(name):
    """The kinematic problem of a case after its friction solve (load distribution without the
    friction loads): (FrictionProblem with the solution in wR, psi and the film of the last pass
    in case.film, cage speed [rad/s], converged)."""
    model, friction, op = models(CASES[name])
    pb = friction.problem(op, model.solve(op))
    totals = np.zeros(F.NEV)
    wc, ok = solve_friction(pb.wc, pb.wR, pb.psi, pb.wi, pb.fresh, pb.case, pb.settings, totals,
                            np.zeros((model.geometry.Z, F.NFL)), pb.jac)
    return pb, wc, ok


def dataset(name, skew=True):
    ds = sim.simulate(sim.load_config([*CASES[name], f"friction.skew.enabled={str(skew).lower()}"]))
    case = ds.isel(design=0, case=0)
    assert bool(case.converged)
    return case


# ------------------------------------------------------------------------------------------------
# kinematics of the skewed roller
# ------------------------------------------------------------------------------------------------

def test_lateral_slip_of_a_skewed_cylinder_is_its_surface_speed_times_psi():
    """A cylindrical roller (axis along the bearing axis) skewed by psi slides along its axis at
    the roller surface speed times psi (Harris & Kotzalas 2007, Advanced Concepts, roller
    skewing: axial sliding omega_R D/2 sin(psi)), on both raceways, and its contact points turn
    to the azimuth x psi / r_c of the slice centre (the normals of both cylinders pass through
    the bearing axis)."""
    rho, cr, wR = 5.0, 30.0, 120.0                       # mm, mm, rad/s
    ur, uz, vr, vz = 0.0, -1.0, 1.0, 0.0                 # u' along -z, v' radial (sim.physics.contact.roller_axes(0, 0))
    for x in (-6.0, 0.0, 2.5):
        for s, y in ((0, rho), (1, -rho)):
            dr, dz = y * vr + x * ur, y * vz + x * uz
            nr = 1.0 if s == 0 else -1.0
            v1 = wR * (uz * dr - ur * dz)                    # roller surface speed along e_t
            rate, f = F.lateral_slip_rate(v1, cr + dr, dr, dz, nr, 0.0, ur, uz, vr, vz)
            assert abs(rate) == pytest.approx(wR * rho, rel=1e-14)
            assert f == pytest.approx(x / cr, rel=1e-14, abs=1e-16)


def _skewed_slice_slip(X, n, c, u, v, wR, Om, psi):
    """Lateral slip [mm/s] of one roller slice skewed by psi [rad] about v', found in 3-D: the
    slice (the circle of the roller at the contact's axial position, about the turned axis) is
    searched for the point deepest in the ring, a cone through X with normal n in (r, z); the
    relative velocity there is projected on the ring's generatrix at that point's azimuth."""
    e = lambda r, t, z: np.array([r, t, z])                     # (e_r, e_t, e_z) at the roller's azimuth
    U, V, C, Xc = e(u[0], 0, u[1]), e(v[0], 0, v[1]), e(c[0], 0, c[1]), e(X[0], 0, X[1])
    x, y = np.dot(Xc - C, U), np.dot(Xc - C, V)
    Ut = math.cos(psi) * U + math.sin(psi) * e(0, 1, 0)          # skewed axis, turned about v'
    W = np.cross(Ut, V)

    def point(t):
        return C + x * Ut + y * (math.cos(t) * V + math.sin(t) * W)

    def depth(t):                                                   # penetration into the ring cone
        p = point(t)
        return np.dot(np.array([math.hypot(p[0], p[1]) - X[0], p[2] - X[1]]), n)

    t = minimize_scalar(lambda t: -depth(t), bounds=(-0.05, 0.05), method="bounded",
                        options={"xatol": 1e-15}).x
    p = point(t)
    phi = math.atan2(p[1], p[0])
    a = np.array([-n[1] * math.cos(phi), -n[1] * math.sin(phi), n[0]])    # generatrix (-n_z, n_r) at phi
    vrel = wR * np.cross(Ut, p - C) - Om * np.cross(e(0, 0, 1), p)
    return np.dot(vrel, a)


@pytest.mark.parametrize("name", ["trb_32208 combined", "trb_31313 35 kN"])
def test_lateral_slip_rate_against_the_skewed_roller_in_3d(name):
    """lateral_slip_rate (first order in psi) against the exact 3-D kinematics of the skewed
    slice on the conical raceways of a TRB (contact frames of the solved case), psi = 1e-6 rad:
    agreement to 1e-4 relative (the neglected terms are O(psi), the point search 1e-15 rad)."""
    pb, wc, _ = solved(name)
    X, Nrm, Cen, Ax, _ = pb.case.frames
    j, wR = 0, pb.wR[0]
    for s in range(2):
        Om = -wc if s == 0 else pb.wi - wc
        for k in (1, X.shape[2] // 2, X.shape[2] - 2):
            dr, dz = X[j, s, k] - Cen[j]
            v1 = wR * (Ax[j, 1] * dr - Ax[j, 0] * dz)
            rate, _ = F.lateral_slip_rate(v1, X[j, s, k, 0], dr, dz, *Nrm[j, s, k], *Ax[j])
            psi = 1e-6
            exact = _skewed_slice_slip(X[j, s, k], Nrm[j, s, k], Cen[j], Ax[j, :2], Ax[j, 2:], wR, Om, psi)
            assert exact / psi == pytest.approx(rate, rel=1e-4), (s, k)


# ------------------------------------------------------------------------------------------------
# a synthetic roller: barrel profile, symmetric or shifted loads
# ------------------------------------------------------------------------------------------------

N_SYN = 11
X_SYN = np.linspace(-6.0, 6.0, N_SYN)      # slice positions along the roller [mm]


@functools.lru_cache(maxsize=1)
def _par_quad():
    model, friction, op = models(CASES["tsrb_reference combined"])
    return friction.problem(op, model.solve(op)).case.par, friction.quad


def synthetic(crown=0.0, tilt_load=0.0):
    """One roller (Z = 1) with the roller axis along the bearing axis (alpha 0) and the radius
    rho(x) = 5 - crown x^2 [mm] (a barrel for crown > 0, rolling in raceways of the same profile:
    the contact radius, and so the rolling speed of the ring, varies along the roller), line load
    q(x) = 400 (1 + tilt_load x / 6) N/mm on both raceways; speeds at rolling kinematics of the
    mid-slice. Friction parameters of the reference TSRB at 55 degC. Returns (case, wR, wc, wi)."""
    par, quad = _par_quad()
    rho = 5.0 - crown * X_SYN ** 2
    drho = -2.0 * crown * X_SYN
    cr = 30.0
    ur, uz, vr, vz = 0.0, -1.0, 1.0, 0.0
    frames = F_frames = (np.zeros((1, 2, N_SYN, 2)), np.zeros((1, 2, N_SYN, 2)), np.array([[cr, 0.0]]),
                         np.array([[ur, uz, vr, vz]]), np.zeros((1, 2)))
    X, Nrm = F_frames[0], F_frames[1]
    for s, sgn in ((0, 1.0), (1, -1.0)):
        X[0, s, :, 0] = cr + X_SYN * ur + sgn * rho * vr
        X[0, s, :, 1] = X_SYN * uz + sgn * rho * vz
        nr = sgn * vr - drho * ur                    # outward roller normal s v' - rho' u' = into the ring
        nz = sgn * vz - drho * uz
        norm = np.hypot(nr, nz)
        Nrm[0, s, :, 0] = nr / norm
        Nrm[0, s, :, 1] = nz / norm
    from sim.physics.roller_contact import ContactFrames
    frames = ContactFrames(*frames)
    q = np.empty((1, 2, N_SYN))
    q[0, :] = 400.0 * (1.0 + tilt_load * X_SYN / 6.0)
    R_o, R_i = cr + 5.0, cr - 5.0
    R_eq = np.array([np.full(N_SYN, 5.0 * R_o / (R_o - 5.0)), np.full(N_SYN, 5.0 * R_i / (R_i + 5.0))])
    bearing = F.ContactLoads(q=q, Qrib=np.zeros(1), R_eq=R_eq, w=X_SYN[1] - X_SYN[0], E_star=2.27e5,
                             rib_end=np.zeros(6), nrib=np.zeros((1, 2)), rho_m=5.0,
                             free=np.full((1, 2, N_SYN), 1e-3),     # every slice loaded: full strips
                             end_drop=np.zeros((2, 2, END_DROP_POINTS)),  # a straight profile
                             ring=inner_ring_poses(1, np.zeros(3), 0.0))   # centred, untilted
    shape = (1, 2, N_SYN)
    film = F.FilmState(*(np.zeros(shape) for _ in range(6)), np.zeros(shape + (quad.wq.shape[0],)),
                       *(np.zeros(1) for _ in range(4)))
    case = F.FrictionCase(frames, bearing, film, par._replace(drag_k=0.0), quad)
    wc = 100.0
    wR = np.array([wc * R_o / 5.0])
    wi = wc * (R_o + R_i) / R_i
    F.lubrication_state(wR, np.array([wc]), wi, np.ones(1, dtype=bool), case)
    return case, wR, wc, wi


def _settings(case):
    tol = 1e-6 * 0.1 * 2 * 400.0 * 12.0 * 5.0           # relative 1e-6 of mu Q rho_m, as FrictionModel
    return KinematicsSettings(np.ones(1, dtype=bool), np.ones(1), tol, tol * 6.0, 60, True, 100.0, True, np.zeros(1, dtype=bool))


def test_lateral_traction_vanishes_without_skew_and_grows_with_the_law_slope():
    """Cylindrical roller at pure rolling (no slip, no spin): the lateral traction is 0 at
    psi = 0 and, for small psi, -g0 s_l per unit area with g0 = lim tau/|v| (v -> 0) of the
    traction law at each width point (sim.physics.friction._traction, both halves of the
    width): exact to the law's curvature at slip ~1e-9 mm/s (checked to 1e-9)."""
    case, wR, wc, wi = synthetic()
    ev = np.zeros(F.NEV)
    F.roller_friction(0, wR[0], 0.0, wc, wi, case, ev)
    assert ev[F.EV_FU] == 0.0 and ev[F.EV_FV] == 0.0 and ev[F.EV_PSKEW] == 0.0
    X, Nrm, Cen, Ax, _ = case.frames
    fl = case.film
    cos_t, sin_t, wq = case.quad
    psi = 1e-12
    expected = 0.0
    for s in range(2):
        Om = -wc if s == 0 else wi - wc
        for k in range(N_SYN):
            dr, dz = X[0, s, k] - Cen[0]
            v1 = wR[0] * (Ax[0, 1] * dr - Ax[0, 0] * dz)
            assert abs(v1 - Om * X[0, s, k, 0]) < 1e-9 * abs(v1)           # pure rolling
            rate, _ = F.lateral_slip_rate(v1, X[0, s, k, 0], dr, dz, *Nrm[0, s, k], *Ax[0])
            t_transit = 2.0 * fl.b[0, s, k] / abs(v1)
            g0 = sum(F._traction(case.par, fl.p0[0, s, k] * cos_t[i], 1e-15, fl.h[0, s, k], fl.Phi[0, s, k],
                                 fl.Eta[0, s, k, i], t_transit) * 2.0 * case.bearing.w * fl.b[0, s, k] * cos_t[i] * wq[i]
                     for i in range(wq.shape[0]))
            ua = Ax[0, 0] * -Nrm[0, s, k, 1] + Ax[0, 1] * Nrm[0, s, k, 0]
            expected += -g0 * psi * rate * ua
    F.roller_friction(0, wR[0], psi, wc, wi, case, ev)
    one = ev[F.EV_FU]
    assert one == pytest.approx(expected, rel=1e-9)
    F.roller_friction(0, wR[0], 2.0 * psi, wc, wi, case, ev)
    assert ev[F.EV_FU] == pytest.approx(2.0 * one, rel=1e-9)


def test_no_skew_moment_without_asymmetry_and_opposite_skew_for_the_mirror_image():
    """Barrel roller (differential slip along it, thesis 2.3.1): with loads symmetric about the
    roller's mid-length the slice tractions, spin and rolling couples are mirror images and their
    moment about the skew axis is 0 (to rounding of the 1e2 N mm each race contributes), so the
    roller stays unskewed; loads shifted towards one end give a skew moment, the mirror-image
    loads the opposite moment and the opposite skew (to the solver tolerance)."""
    ev = np.zeros(F.NEV)
    results = {}
    for tilt_load in (0.0, 0.5, -0.5):
        case, wR, wc, wi = synthetic(crown=0.004, tilt_load=tilt_load)
        F.roller_friction(0, wR[0], 0.0, wc, wi, case, ev)
        S0 = ev[F.EV_MS]
        psi = np.zeros(1)
        totals = np.zeros(F.NEV)
        settings = _settings(case)
        wc_s, ok = solve_friction(wc, wR, psi, wi, True, case, settings, totals, np.zeros((1, F.NFL)), empty_jacobian(1))
        assert ok
        results[tilt_load] = (S0, psi[0], settings.tol_M)
    S0, psi0, tol = results[0.0]
    assert abs(S0) < 1e-9 * 100.0 and abs(psi0) < 1e-12           # rad
    (Sp, psip, _), (Sm, psim, _) = results[0.5], results[-0.5]
    assert abs(Sp) > 1.0                                               # N mm: the shifted loads do skew it
    assert Sm == pytest.approx(-Sp, rel=1e-9)
    assert psip != 0.0 and psim == pytest.approx(-psip, rel=1e-6)


# ------------------------------------------------------------------------------------------------
# whole bearings
# ------------------------------------------------------------------------------------------------

@pytest.mark.parametrize("name", list(CASES))
def test_skew_and_spin_moment_balance_of_every_roller(name):
    """At the solution every active roller's moments about its axis and about its skew axis
    (friction plus cage pocket couple) are zero to the final tolerance of the solve
    (FINAL_TOLERANCE_FACTOR x friction.tolerance x mu Q Dwe/2), re-evaluated from the film the
    last pass used."""
    pb, wc, ok = solved(name)
    assert ok
    ev = np.zeros(F.NEV)
    tol = FINAL_TOLERANCE_FACTOR * pb.settings.tol_M
    for j in np.flatnonzero(pb.settings.active):
        F.roller_friction(j, pb.wR[j], pb.psi[j], wc, pb.wi, pb.case, ev)
        assert abs(ev[F.EV_MU]) <= tol, j
        assert abs(ev[F.EV_MS] + F.pocket_skew_couple(pb.psi[j], pb.case.par)[0]) <= tol, j


@pytest.mark.parametrize("name", list(CASES))
def test_torque_equals_power_over_speed_with_skew(name):
    """Energy balance with skew: the outer-ring torque equals power loss / inner-ring speed
    within 1 % (issue 18; the first-order kinematics leave O(psi^2) terms out of the moments);
    the lateral-slip power (a part of the sliding component) is a dissipation."""
    case = dataset(name)
    power_over_speed = float(case.power_loss) * 1e3 / (float(case.speed) * math.pi / 30.0)
    assert float(case.torque) == pytest.approx(power_over_speed, rel=1e-2)
    assert float(case.skew_sliding) > 0.0          # the lateral traction opposes the lateral slip: it dissipates


def test_skew_switch_off_writes_no_skew_and_on_writes_it_per_roller():
    off, on = dataset("tsrb_reference combined", skew=False), dataset("tsrb_reference combined")
    assert "roller_skew" not in off and "skew_sliding" not in off
    assert on.roller_skew.dims == ("roller",) and on.roller_skew.attrs["units"] == "deg"
    assert np.isfinite(on.roller_skew.values).all()


def test_skew_changes_sign_with_the_inner_outer_friction_balance():
    """Kellstroem (1979) and Blomqvist: the direction of roller skew is set by the balance of the
    friction at the inner and at the outer raceway contact; reversing it reverses the skew. In
    the pinion TSRB the two races' tractions give skew moments of opposite sign (outer < 0 <
    inner, checked here); with the film viscosity of one race raised five-fold (more traction
    there) the roller skews to the side of that race's moment, the sign flips between the two."""
    pb, wc, _ = solved("tsrb_pinion 35 kN")
    case, j = pb.case, 0
    moments = race_skew_moments(pb, wc, j)
    assert moments[0] < 0.0 < moments[1]
    skews = []
    eta = case.film.Eta.copy()
    for s in range(2):
        case.film.Eta[:, s] *= 5.0
        wR, psi, totals = pb.wR.copy(), pb.psi.copy(), np.zeros(F.NEV)
        wc_s, ok = solve_kinematics_newton(wc, False, pb.wi, wR, psi, case, pb.settings, totals, empty_jacobian(len(wR)),
                                           np.zeros((len(wR), F.NFL)))
        if not ok:
            wR, psi = pb.wR.copy(), pb.psi.copy()
            wc_s, ok = solve_kinematics(wc, pb.wi, wR, psi, case, pb.settings, totals)
        assert ok
        skews.append(psi[j])
        case.film.Eta[:] = eta
    assert skews[0] < 0.0 < skews[1]


def race_skew_moments(pb, wc, j):
    """Skew moments (about v', unskewed) of roller j's outer and inner raceway contacts alone [N mm]
    at the solved speeds of ``pb``."""
    case = pb.case
    ev = np.zeros(F.NEV)
    moments = []
    p0 = case.film.p0.copy()
    for s in range(2):
        case.film.p0[j, 1 - s] = 0.0                   # this race's contacts alone
        F.roller_friction(j, pb.wR[j], 0.0, wc, pb.wi, case, ev)
        moments.append(ev[F.EV_MS])
        case.film.p0[:] = p0
    return moments


def test_the_oil_temperature_reverses_the_race_balance_and_the_skew_of_the_prototype():
    """The same balance shifted by a physical parameter: the prototype TSRB at 3.46 kN, 4199 rpm.
    At 25 degC (lambda ~6) its outer race's skew moment outweighs the inner's (measured -45.6
    against 44.1 N mm) and the rollers skew negative; at 60 degC (lambda ~2.4) the inner's does
    (50.1 against -46.5) and they skew positive, each on its pocket wall (atan(c / Lwe) = 0.43
    deg). The dynamic ladder checks the same reversal in the time domain."""
    for temperature, sign in (("25", -1.0), ("60", +1.0)):
        pb, wc, ok = solved(f"tsrb_prototype {temperature} degC")
        assert ok
        outer, inner = race_skew_moments(pb, wc, 0)
        assert outer < 0.0 < inner
        assert np.sign(outer + inner) == sign
        # pure axial: one roller class, its first roller solved for all (sim.solvers.symmetry)
        assert np.sign(pb.psi[0]) == sign
        assert abs(pb.psi[0]) >= pb.case.par.skew_clearance


def test_pinion_tsrb_rests_on_its_pocket_and_the_trb_31313_is_held_by_its_rib():
    """Thesis Fig. 7.28 (35 kN, 1100 rpm): the TSRB skews more than the TRB 31313. Here: the
    TSRB's friction moment about the skew axis keeps its sign across the whole pocket clearance
    (the 2-D traction law gives no free skew equilibrium: the lateral slip does not bring the
    moment to zero), so its rollers rest on the pocket (|psi| >= clearance); the TRB's roller end
    on the rib turns its normal load with the skew (the end-sphere centre lies near the bearing
    axis) into a restoring moment, a free equilibrium inside the clearance."""
    tsrb, wc, _ = solved("tsrb_pinion 35 kN")
    trb, _, _ = solved("trb_31313 35 kN")
    c = tsrb.case.par.skew_clearance
    ev = np.zeros(F.NEV)
    signs = set()
    for psi in np.linspace(-c, c, 9):
        F.roller_friction(0, tsrb.wR[0], psi, wc, tsrb.wi, tsrb.case, ev)
        signs.add(np.sign(ev[F.EV_MS]))
    assert len(signs) == 1
    assert abs(tsrb.psi[0]) >= c
    assert 0.0 < abs(trb.psi[0]) < trb.case.par.skew_clearance
    assert abs(tsrb.psi[0]) > abs(trb.psi[0])


@pytest.mark.parametrize("name", ["tsrb_pinion 35 kN", "trb_31313 35 kN"])
def test_bracketing_fallback_finds_the_newton_solution(name):
    """The fallback of solve_friction (sim.solvers.kinematics.solve_kinematics: cage speed
    bracketed, each roller's speed and skew alternately bracketed) reaches the Newton solution:
    skews within 1e-6 rad (the penalty couple's resolution of the moment tolerance is ~1e-9 rad
    for the TSRB, the TRB rib stiffness ~1e5 N mm/rad resolves it to ~1e-8 rad), roller speeds
    to 1e-6 relative."""
    pb, wc, _ = solved(name)
    active = pb.settings.active
    wR, psi, totals = pb.wR.copy(), np.zeros_like(pb.psi), np.zeros(F.NEV)
    wR[active] *= 1.01
    wc_b, ok = solve_kinematics(wc * 0.99, pb.wi, wR, psi, pb.case, pb.settings, totals)
    assert ok
    np.testing.assert_allclose(psi[active], pb.psi[active], rtol=0.0, atol=1e-6)
    np.testing.assert_allclose(wR[active], pb.wR[active], rtol=1e-6)


def test_the_torus_rib_holds_the_trb_31313_less_than_the_sphere_and_less_the_wider_it_opens():
    """docs/roller_end_torus.md: the rib load's restoring skew stiffness is Q_rib times a lever that
    grows as the point where the contact normal meets the roller axis (x_n) approaches the bearing
    axis: 888 N mm/(N rad) for the sphere, 305 / 161 / 80 for the torus (r_k 0.8 mm) at rib
    opening angles 5 / 6 / 8 deg. So at the pinion case the torus skews more than the sphere, and
    more the wider the rib opens, each inside the pocket clearance (a free equilibrium). Only the
    order is asserted (the friction moment changes with the rib too: the torus's contact sits
    lower on the end face, its sliding speed is smaller)."""
    skews = {}
    for name, extra in (("sphere", []), ("5", ["bearing.roller_end=torus"]),
                        ("6", ["bearing.roller_end=torus", "bearing.rib_opening_angle=6.0"]),
                        ("8", ["bearing.roller_end=torus", "bearing.rib_opening_angle=8.0"])):
        model, friction, op = models(["bearing=trb_31313", *PINION, *extra])
        pb = friction.problem(op, model.solve(op))
        wc, ok = solve_friction(pb.wc, pb.wR, pb.psi, pb.wi, pb.fresh, pb.case, pb.settings, np.zeros(F.NEV),
                                np.zeros((model.geometry.Z, F.NFL)), pb.jac)
        assert ok
        skews[name] = abs(pb.psi[0])
        assert 0.0 < skews[name] < pb.case.par.skew_clearance, name
    assert skews["sphere"] < skews["5"] < skews["6"] < skews["8"]



def test_free_rollers_find_the_pocket_wall_across_the_couples_kink():
    """friction.cage_guidance = free (the default) with skew. tsrb_reference at 1.26 / 1.18 kN,
    6386 rpm, 48 degC: the rigid cage rests rollers 0-3 and 14-16 on the negative pocket wall, the
    others on the positive one. Free of the pocket friction, their friction skew moment grows with
    the skew inside the play and keeps one sign, so their free equilibrium is the positive wall;
    the Newton from the rigid skew stepped across the couple's kink at -clearance, where no
    backtracking lowers the residual, and the case did not converge. Restarted on each wall
    (sim.solvers.kinematics.FREE_SKEW_WALL_START) every roller rests on the positive wall, as the
    dynamic solver finds them (every roller at +0.506 deg, torque 844.0 N mm against 849.4 here,
    README "Radial loads"), and torque = power loss / speed holds within 1e-3 (as for the rigid
    cage: test_rollers_free_in_their_pockets_keep_the_energy_balance_and_pay_no_pocket_friction)."""
    overrides = ["bearing=tsrb_reference", "load.Fa=1257", "load.Fr=1181", "load.speed=6386",
                 "load.oil_temperature=48", "friction.skew.enabled=true"]
    rigid = sim.simulate(sim.load_config(overrides + ["friction.cage_guidance=rigid"])).isel(design=0, case=0)
    free = sim.simulate(sim.load_config(overrides + ["friction.cage_guidance=free"])).isel(design=0, case=0)
    assert bool(rigid.converged) and bool(free.converged)
    _, friction, _ = models(overrides)
    clearance = math.degrees(friction.par.skew_clearance)
    assert (rigid.roller_skew.values < -clearance).any()
    assert (free.roller_skew.values > clearance).all()
    omega_i = math.pi * float(free.speed) / 30.0
    assert abs(float(free.torque) - float(free.power_loss) * 1e3 / omega_i) <= 1e-3 * float(free.torque)
