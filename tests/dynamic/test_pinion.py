"""The pinion case of issue 18 item 6 (docs/figures/pinion_breakdown.py through studies.verify):
what its table must satisfy whatever the numbers, for the pinion TSRB (thesis Table 7.4) and the
TRB 31313 at the load of conf/study/pinion.yaml, by the quasi-static solver without and with skew
and by the dynamic solver with skew and tilt free."""
import pytest

from studies.config import compose
from studies.verify import VARIANTS, solver_summary, variant_config

ROLES = ("thesis_design", "reference_trb")
# relative kinematic tolerance to which the quasi-static torque equals power loss / speed
# (README "Torque": the traction equilibrium is solved to moment residuals of 1e-6 mu Q Dwe/2;
# tests/friction hold torque x omega = power to 1e-3)
QS_POWER_TOLERANCE = 1e-3
# issue 18 ladder targets: power balance 0.5 %, steady state against quasi-static torque 3 %, cage speed 0.5 %
POWER_BALANCE = 0.005
TORQUE_AGREEMENT = 0.03
CAGE_SPEED_AGREEMENT = 0.005


@pytest.fixture(scope="module")
def runs():
    study = compose([]).study
    return {(role, v): solver_summary(variant_config(study, study[role], v))[0] for role in ROLES for v in VARIANTS}


def test_the_breakdown_sums_to_the_torque_and_skew_sliding_is_part_of_sliding(runs):
    """sim.io: torque_component splits the outer-ring torque in proportion to each mechanism's
    power, skew_sliding is the lateral-slip share of 'sliding'. A mechanism missing from the
    split or counted twice breaks the sum; 1e-9: the round-off of a sum of seven terms."""
    for (role, v), r in runs.items():
        assert r["converged"], (role, v)
        assert sum(r["component"].values()) == pytest.approx(r["torque"], rel=1e-9), (role, v)
        if v != "quasi_static":
            assert 0.0 <= r["skew_sliding"] <= r["component"]["sliding"], (role, v)


def test_quasi_static_torque_is_the_power_loss_over_the_speed(runs):
    """At the traction equilibrium the torque on the outer ring times the inner-ring speed is the
    power lost (no energy is stored), with and without skew."""
    for role in ROLES:
        for v in ("quasi_static", "quasi_static_skew"):
            r = runs[role, v]
            assert abs(r["torque"] / r["loss_torque"] - 1.0) < QS_POWER_TOLERANCE, (role, v)


@pytest.mark.parametrize("role", ROLES)
def test_dynamic_steady_state_balances_torque_and_power(runs, role):
    """At a steady state the drive torque, the outer-ring torque and the power loss / speed are
    one number (angular momentum and energy of rollers and cage do not change); target the
    ladder's power balance, 0.5 %. With the TSRB's rollers skewed 0.36 deg on their pockets this
    holds only if the tilt's contact moment turns with the skew (sim.solvers.dynamic.rhs): about
    the unskewed axis the three missed one another by up to 8 %."""
    r = runs[role, "dynamic"]
    assert r["converged"]
    assert abs(r["torque"] / r["loss_torque"] - 1.0) < POWER_BALANCE
    assert abs(r["drive_torque"] / r["loss_torque"] - 1.0) < POWER_BALANCE


@pytest.mark.parametrize("role", ROLES)
def test_dynamic_steady_state_matches_the_quasi_static_solver_with_skew(runs, role):
    """Skew free in both solvers (the TRB 31313's rib holds its rollers near zero skew, the TSRB's
    rest on their pockets): the dynamic steady state must give the quasi-static torque within 3 %
    and cage speed within 0.5 % (ladder targets)."""
    d, q = runs[role, "dynamic"], runs[role, "quasi_static_skew"]
    assert abs(d["torque"] / q["torque"] - 1.0) < TORQUE_AGREEMENT
    assert abs(d["cage_speed"] / q["cage_speed"] - 1.0) < CAGE_SPEED_AGREEMENT


def test_the_tsrb_skews_more_and_loses_more_to_skew_than_the_trb(runs):
    """Thesis 7.4 (Fig. 7.28), the dynamic ladder's trend rung of issue 18 item 4: the TSRB's
    roller skew is larger than the TRB 31313's, whose rib restores it; so is the sliding the skew
    causes. Both solvers with skew, the dynamic one at the steady state its detector found (skew
    and tilt free, from rolling kinematics and zero skew)."""
    for v in ("quasi_static_skew", "dynamic"):
        tsrb, trb = runs["thesis_design", v], runs["reference_trb", v]
        assert tsrb["converged"] and trb["converged"], v
        assert tsrb["skew"] > trb["skew"], v
        assert tsrb["skew_sliding"] > trb["skew_sliding"], v


# thesis Fig. 7.28 (as issue 18 reads it): roller skew of the order of 0.1-0.6 deg at this case
THESIS_SKEW_DEG = (0.1, 0.6)


@pytest.mark.parametrize("role", [
    "thesis_design",
    pytest.param("reference_trb", marks=pytest.mark.xfail(
        strict=True, reason="TRB 31313 dynamic skew 0.014 deg (quasi-static 0.014): the roller-end sphere's centre "
                            "lies 5.6 mm from the bearing axis, so the rib load turns with the skew, a restoring "
                            "stiffness of 7.2e5 of the 7.5e5 N mm/rad against a friction moment of 213 N mm; "
                            "0.007-0.032 deg over the ASSUMED rib ranges, 0.1 deg needs an end-radius ratio of 0.6 "
                            "(README, dynamic solver); the thesis's own torus-plane end (bearing.roller_end=torus, "
                            "r_k 0.8 mm) skews 0.061 deg at the ASSUMED rib opening of 5 deg and 0.12-0.36 deg at "
                            "6-10 deg, an angle no source found gives (docs/roller_end_torus.md)")),
])
def test_dynamic_skew_is_of_the_order_of_thesis_fig_7_28(runs, role):
    """Thesis Fig. 7.28 (pinion case, skew and tilt free): roller skew of the order of 0.1-0.6
    deg. The bounds are the issue's reading of the figure (order of magnitude, no tolerance
    beyond them). The TSRB rests on its pocket (atan(c / Lwe) = 0.355 deg at the ASSUMED 0.15 mm
    clearance); the TRB 31313 does not reach it (strict xfail: the reason states the numbers)."""
    skew = runs[role, "dynamic"]["skew"]
    assert THESIS_SKEW_DEG[0] <= skew <= THESIS_SKEW_DEG[1]
