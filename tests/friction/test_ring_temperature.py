"""friction.inner_ring_temperature_rise: the oil at the inner ring's contacts warmer than at the
outer ring's (sim.api.friction_model: eta0_inner from the lubricant at the raised temperature,
sim.physics.friction.roller_lubrication: the inner raceway and rib films and tractions with it)."""
from pathlib import Path

import numpy as np
import pytest
from omegaconf import OmegaConf

import sim
from sim.physics.lubricant import Lubricant

REPO = Path(__file__).resolve().parents[2]

# Pan & Hamrock (1989) central film: h ~ (eta0 u)^0.692 (sim.physics.ehl.film_line)
PAN_HAMROCK_SPEED_EXPONENT = 0.692
ISOTHERMAL = ["friction.inlet_shear_heating=false", "friction.thermal=false"]


def case(*overrides):
    ds = sim.simulate(sim.load_config(["bearing=trb_32208", *ISOTHERMAL, *overrides])).isel(design=0, case=0)
    assert bool(ds.converged)
    return ds


@pytest.mark.parametrize("rise", [10.0, -15.0])
def test_the_inner_films_follow_the_viscosity_at_the_inner_rings_temperature(rise):
    """Isothermal films without inlet heating: every inner-raceway film scales by the viscosity
    ratio to the power 0.692 (Pan & Hamrock), the outer films stay; 1e-4: the roller speeds and
    loads move with the traction balance (measured 5e-6 on the outer films at +10 K)."""
    base, warm = case(), case(f"friction.inner_ring_temperature_rise={rise}")
    lub = Lubricant.from_config(OmegaConf.to_container(OmegaConf.load(REPO / "conf" / "lubricant" / "fva3.yaml")))
    T = float(base.oil_temperature)
    ratio = (lub.dynamic_viscosity(T + rise) / lub.dynamic_viscosity(T)) ** PAN_HAMROCK_SPEED_EXPONENT
    h0, h1 = base.film_thickness, warm.film_thickness
    loaded = np.isfinite(h0.values) & np.isfinite(h1.values)
    inner = (h1 / h0).sel(race="inner").values[loaded[1]]
    outer = (h1 / h0).sel(race="outer").values[loaded[0]]
    np.testing.assert_allclose(inner, ratio, rtol=1e-4)
    np.testing.assert_allclose(outer, 1.0, rtol=1e-4)
    # a thinner inner film (warmer ring) loses less to rolling and traction
    assert (float(warm.torque) < float(base.torque)) == (rise > 0.0)
