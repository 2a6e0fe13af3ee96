"""The inner ring's balance with the torus roller end (bearing.roller_end = torus,
docs/roller_end_torus.md): its rib contact slips laterally with the skew, and the reaction of that
traction, turned to the contact point's meridian plane, acts on the ring. The check of
tests/balance/test_equilibrium.py (ring balance recomputed from the solved state: Fa, Fr + the
normal loads of its raceway slices and rib + the friction evaluation's reaction = 0, to 1e-4 of
the load) on the torus cases."""
import pytest

from tests.balance.test_equilibrium import PINION_SKEW
from tests.balance.test_equilibrium import test_inner_ring_balances_the_reaction_of_its_contacts_tractions as balance


@pytest.mark.parametrize("overrides", [
    ["bearing=trb_31313", "bearing.roller_end=torus", *PINION_SKEW],
    ["bearing=trb_32208", "bearing.roller_end=torus", "load.Fa=4500", "load.Fr=2000", "friction.skew.enabled=true"],
], ids=["trb_31313_torus_skew", "trb_32208_torus_combined_skew"])
def test_inner_ring_balances_the_torus_rib_reaction(model_for, overrides):
    balance(model_for, overrides)
