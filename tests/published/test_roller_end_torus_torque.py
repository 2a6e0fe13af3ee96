"""Issue 14's TRB 32208 torque targets (pure axial, 2000 rpm, fva3 at 55 degC) with the thesis's
torus roller end (bearing.roller_end = torus: r_k 0.8 mm of thesis Table A.2, rib opening 5 deg
ASSUMED; docs/roller_end_torus.md), the same bands as the validation report's for the default
sphere: 4.5 kN between 0.6 x the thesis's ~650 and 1.2 x SKF 2004's (~1140 N mm as issue 14 states
it; the report recomputes SKF), 40 kN within 660-2800 N mm, torque ~ Fa^n with n in 0.18-0.45 (least
squares over 4.5, 10, 20, 40 kN as studies.validation fits it)."""
import numpy as np
import pytest

import sim

LOADS = (4500.0, 10000.0, 20000.0, 40000.0)
BAND_4K5 = (0.6 * 650.0, 1140.0)      # N mm, issue 14 item 5: 0.6 x thesis to 1.2 x SKF (~1140)
BAND_40K = (660.0, 2800.0)            # N mm, issue 14 item 5
EXPONENT_BAND = (0.18, 0.45)          # 1, issue 14 item 5


@pytest.fixture(scope="module")
def torus():
    cfg = sim.load_config(["bearing=trb_32208", "bearing.roller_end=torus",
                           "load.Fa=[" + ",".join(str(f) for f in LOADS) + "]", "load.Fr=0.0", "load.speed=2000.0",
                           "load.oil_temperature=55.0"])
    ds = sim.simulate(cfg).isel(design=0)
    assert bool(ds.converged.all())
    return ds


def test_torus_trb_32208_torque_meets_the_issue_14_bands(torus):
    T = torus.torque.values.ravel()
    assert BAND_4K5[0] <= T[0] <= BAND_4K5[1]
    assert BAND_40K[0] <= T[-1] <= BAND_40K[1]
    n = np.polyfit(np.log(LOADS), np.log(T), 1)[0]
    assert EXPONENT_BAND[0] <= n <= EXPONENT_BAND[1]


def test_torus_rib_friction_grows_with_the_load_and_stays_a_minority(torus):
    """The rib carries the roller's axial reaction, so its friction grows with Fa; at 40 kN it
    stays below half the torque (the raceways' rolling and sliding carry the rest), as for the
    sphere (639 of 1978 N mm; torus 833 of 2181, docs/roller_end_torus.md)."""
    rib = torus.torque_component.sel(component="rib").values.ravel()
    T = torus.torque.values.ravel()
    assert np.all(np.diff(rib) > 0.0)
    assert rib[-1] < 0.5 * T[-1]
