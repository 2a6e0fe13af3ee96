"""The torus roller end (bearing.roller_end = torus, docs/roller_end_torus.md) in the time domain:
TRB 31313 at the pinion case (conf/study/pinion.yaml: 35 kN, 1100 rpm, pinion oil 50 degC), skew
and tilt free, against the quasi-static solver with skew. The torus's rib contact slips laterally
with the skew and its lateral traction, turned to the contact point's meridian plane (lever
x_n / r_centre ~ -7), pushes the roller along e_t: without that force in the orbit the steady
state's outer-ring torque left the power loss / speed by 1.0 % and the quasi-static torque by
1.0 % (measured), against 0.05 % and 0.07 % with it."""
import pytest

from studies.config import compose
from studies.verify import solver_summary, variant_config
from tests.dynamic.test_pinion import CAGE_SPEED_AGREEMENT, POWER_BALANCE, TORQUE_AGREEMENT


@pytest.fixture(scope="module")
def runs():
    study = compose([]).study
    out = {}
    for v in ("quasi_static_skew", "dynamic"):
        cfg = variant_config(study, study["reference_trb"], v)
        cfg.bearing.roller_end = "torus"      # the study fixes the bearings; the torus is their option
        out[v] = solver_summary(cfg)[0]
    return out


def test_torus_steady_state_balances_torque_and_power(runs):
    """Ladder target (issue 18): outer-ring torque, drive torque and power loss / speed within 0.5 %."""
    r = runs["dynamic"]
    assert r["converged"]
    assert abs(r["torque"] / r["loss_torque"] - 1.0) < POWER_BALANCE
    assert abs(r["drive_torque"] / r["loss_torque"] - 1.0) < POWER_BALANCE


def test_torus_steady_state_matches_the_quasi_static_solver_with_skew(runs):
    """Ladder targets: torque within 3 %, cage speed within 0.5 %; and the skew, which both solve
    from the same moments, within 1 % (0.05 % measured)."""
    d, q = runs["dynamic"], runs["quasi_static_skew"]
    assert abs(d["torque"] / q["torque"] - 1.0) < TORQUE_AGREEMENT
    assert abs(d["cage_speed"] / q["cage_speed"] - 1.0) < CAGE_SPEED_AGREEMENT
    assert d["skew"] == pytest.approx(q["skew"], rel=0.01)
