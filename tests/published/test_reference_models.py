"""The published TRB torque models of sim/reference_models.py against hand-computed values.

No published worked example of either model was found (module docstring of
sim.physics.reference_models), so each test evaluates the quoted formula step by step by hand for one
point and checks the limits and exponents the formulas imply. Tolerances are floating-point
(1e-12) where the same arithmetic is repeated, and stated where a hand-rounded number is used.
"""
import math

import pytest

from sim.physics.reference_models import (SKF_TAPERED_CONSTANTS, aihara_1987_trb, aihara_rolling_moment, skf_2004_trb,
                                  torque_exponent)

C322 = SKF_TAPERED_CONSTANTS["322"]


def test_skf_hand_value_32208():
    """SKF General Catalogue 6000 EN (2008): TRB 32208 (d 40, D 80, Y 1.6), Fa 4.5 kN, Fr 0, 2000 r/min,
    nu 46 mm^2/s. By hand (4 significant digits at each step):
    d_m = 60; G_rr = 2.27e-6 * 60^2.38 * (10.9*1.6*4500)^0.31 = 2.27e-6 * 17061 * 32.914 = 1.2747;
    (nu n)^0.6 = 92000^0.6 = 951.20; phi_ish = 1/(1 + 1.84e-9 * 120000^1.28 * 46^0.64) = 1/(1 + 1.84e-9 *
    3.1721e6 * 11.592) = 0.93663; M_rr = 0.93663 * 1.2747 * 951.20 = 1135.7 N mm.
    G_sl = 0.018 * 60^0.82 * 2*1.6*4500 = 0.018 * 28.713 * 14400 = 7442.5; phi_bl = exp(-2.6e-8 *
    92000^1.4 * 60) ~ 8e-7, so mu_sl = 0.002 and M_sl = 14.885 N mm.
    Tolerance 0.3 %: the hand chain is rounded to 4 digits at 6 steps."""
    r = skf_2004_trb(0.0, 4500.0, 2000.0, 46.0, 40.0, 80.0, 1.6, **{k: C322[k] for k in ("R1", "R2", "S1", "S2")})
    assert r["G_rr"] == pytest.approx(1.2747, rel=3e-3)
    assert r["phi_ish"] == pytest.approx(0.93663, rel=3e-3)
    assert r["M_rr"] == pytest.approx(1135.7, rel=3e-3)
    assert r["mu_sl"] == pytest.approx(0.002, rel=1e-4)   # phi_bl * (0.15 - 0.002) = 1.4e-7
    assert r["M_sl"] == pytest.approx(14.885, rel=3e-3)
    assert r["M"] == pytest.approx(r["M_rr"] + r["M_sl"], rel=1e-12)


def test_skf_exponents_and_limits():
    """G_rr ~ (Fr + R2 Y Fa)^0.31: pure axial M_rr ~ Fa^0.31 exactly; G_sl linear; phi_bl -> 1 and
    mu_sl -> mu_bl when n nu -> 0; phi_rs = 1 for K_rs = 0 and < 1 otherwise."""
    kw = {k: C322[k] for k in ("R1", "R2", "S1", "S2")}
    a = skf_2004_trb(0.0, 4500.0, 2000.0, 46.0, 40.0, 80.0, 1.6, **kw)
    b = skf_2004_trb(0.0, 40000.0, 2000.0, 46.0, 40.0, 80.0, 1.6, **kw)
    assert b["M_rr"] / a["M_rr"] == pytest.approx((40000.0 / 4500.0) ** 0.31, rel=1e-12)
    assert b["G_sl"] / a["G_sl"] == pytest.approx(40000.0 / 4500.0, rel=1e-12)
    slow = skf_2004_trb(0.0, 4500.0, 1e-3, 1e-3, 40.0, 80.0, 1.6, **kw)
    assert slow["phi_bl"] == pytest.approx(1.0, abs=1e-9)
    assert slow["mu_sl"] == pytest.approx(0.15, abs=1e-9)
    assert a["phi_rs"] == 1.0
    starved = skf_2004_trb(0.0, 4500.0, 2000.0, 46.0, 40.0, 80.0, 1.6, K_rs=3e-8, **kw)
    # by hand: 3e-8 * 46 * 2000 * 120 * sqrt(6 / 80) = 0.09066 -> phi_rs = 0.9133
    assert starved["phi_rs"] == pytest.approx(math.exp(-3e-8 * 46 * 2000 * 120 * math.sqrt(6.0 / 80.0)), rel=1e-12)
    assert starved["phi_rs"] == pytest.approx(0.9133, abs=1e-4)


def test_skf_refuses_bad_input():
    kw = {k: C322[k] for k in ("R1", "R2", "S1", "S2")}
    with pytest.raises(ValueError, match="nu"):
        skf_2004_trb(0.0, 4500.0, 2000.0, -1.0, 40.0, 80.0, 1.6, **kw)
    with pytest.raises(ValueError, match="D"):
        skf_2004_trb(0.0, 4500.0, 2000.0, 46.0, 80.0, 40.0, 1.6, **kw)


AIH = dict(u=3.0, R_e=4.2e-3, l=0.017, z=17, D_a=0.010, alpha_cup=math.radians(14.0), eta0=0.0396,
           alpha_p=2.1e-8, E_prime=2.286e11, beta_T=0.043, k_oil=0.13)


def test_aihara_rolling_hand_value():
    """Aihara (1987) as transcribed, one contact, by hand (4 digits per step):
    G = 2.1e-8 * 2.286e11 = 4801; U = 0.0396 * 3 / (2.286e11 * 4.2e-3) = 1.2373e-10; GU = 5.940e-7,
    (GU)^0.658 = 8.001e-5; W = 2 * 4500 / (0.010 * 0.017 * 17 * sin 14 * 2.286e11) = 5.631e-5,
    W^0.31 = 0.04816; L = 0.0396 * 0.043 * 9 / 0.13 = 0.1179, 1 + 0.29 L^0.78 = 1.0547;
    M = 176 / 1.0547 / 2.1e-8 * 8.001e-5 * 0.04816 * (4.2e-3)^2 * 0.017 = 9.18e-3 N m.
    Tolerance 0.5 %: 4-digit rounding at 8 steps."""
    M = aihara_rolling_moment(4500.0, **AIH)
    assert M == pytest.approx(9.18e-3, rel=5e-3)


def test_aihara_exponents_and_rib_limits():
    """Rolling part ~ Fa^0.31 and ~ (u)^0.658 at negligible thermal load; rib term = e mu_0 cos(beta) Fa
    at Lambda_r = 0 and falls as exp(-1.8 Lambda_r^1.2)."""
    cold = dict(AIH, beta_T=1e-12)   # L -> 0: thermal factor 1
    r = aihara_rolling_moment(40000.0, **cold) / aihara_rolling_moment(4500.0, **cold)
    assert r == pytest.approx((40000.0 / 4500.0) ** 0.31, rel=1e-9)
    r = aihara_rolling_moment(4500.0, **dict(cold, u=6.0)) / aihara_rolling_moment(4500.0, **cold)
    assert r == pytest.approx(2.0 ** 0.658, rel=1e-6)
    t = aihara_1987_trb(10000.0, 17, 0.01, 0.035, 0.025, 0.0, 0.0, e=1.5e-3, cos_beta=1.0, Lambda_r=0.0)
    assert t["rib"] == pytest.approx(1.5e-3 * 0.2 * 10000.0, rel=1e-12)
    t1 = aihara_1987_trb(10000.0, 17, 0.01, 0.035, 0.025, 0.0, 0.0, e=1.5e-3, cos_beta=1.0, Lambda_r=1.0)
    assert t1["rib"] / t["rib"] == pytest.approx(math.exp(-1.8), rel=1e-12)
    # bearing sum (z / D_a)(R_o M_i + R_i M_o) by hand: 1700 * (0.035 * 0.01 + 0.025 * 0.02) = 1.445 N m
    t2 = aihara_1987_trb(0.0, 17, 0.01, 0.035, 0.025, 0.01, 0.02, e=0.0, cos_beta=1.0, Lambda_r=0.0)
    assert t2["M"] == pytest.approx(1.445, rel=1e-12)


def test_torque_exponent_recovers_a_power_law():
    F = [4500.0, 10000.0, 20000.0, 40000.0]
    assert torque_exponent(F, [3.0 * f ** 0.31 for f in F]) == pytest.approx(0.31, rel=1e-12)
