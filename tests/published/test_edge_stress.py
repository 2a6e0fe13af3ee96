"""Edge stress: a contact that runs onto a roller end (sim.physics.elasticity.edge_interference).

Thesis 7.2.1 (Figs. 7.8, 7.9): the reference TSRB's maximum pressure "is already affected by a
stress concentration of the roller edge" (Fig. 7.9 b), more so with a flatter roller (PCR 122.5,
Fig. 7.9 c), while the more crowned PCR 36 (aA = 0) lowers the maximum pressure. A sharp roller
end under load concentrates the pressure without bound (the rigid flat punch's inverse square
root, Johnson 1985, Contact Mechanics, chapter 2), so a slice model's end-slice pressure grows as
its slices narrow; the verdict "edge contact or not" must not.
"""
import numpy as np
import pytest

import sim
from sim.physics.elasticity import edge_interference

SLICES = (20, 40, 80)


def run(*overrides):
    return sim.simulate(sim.load_config(["friction.enabled=false", *overrides])).isel(design=0, case=0)


@pytest.mark.parametrize("n", SLICES)
def test_thesis_7_2_1_edge_contact_of_the_reference_and_its_crown_variants(n):
    """tsrb_reference at Fa 4 kN, Fr 0 (scenario 1 of Fig. 7.6): edge contact for the reference and
    the flatter PCR 122.5 (more interference, as Fig. 7.9 c against b), none for PCR 36, at every
    slice count."""
    def edge(*extra):
        case = run("bearing=tsrb_reference", "load.Fa=4000", "load.Fr=0", f"solver.n_slices={n}", *extra)
        assert bool(case.edge_stress) == bool(case.edge_interference.max() > 0.0)
        return float(case.edge_interference.max())

    reference, flatter, crowned = edge(), edge("bearing.PCR=122.5"), edge("bearing.PCR=36")
    assert 0.0 < reference < flatter
    assert crowned < 0.0


def test_pmax_of_an_edge_contact_grows_with_the_slices_that_of_an_inner_contact_converges():
    """Why the verdict is not taken from the end-slice pressure: kappa 0.99 under combined load
    (Fa = Fr = 4 kN) runs onto the large end and its pmax, the end slice's, keeps rising from 20
    to 40 to 80 slices (by more than 10 % in all: the end slice averages a peak ~ 1/sqrt(distance),
    which grows like w^-1/2 as the slice width w shrinks); the crowned PCR 36 contact ends inside
    the roller and its pmax changes by less than 1 % from 40 to 80 slices
    (test_slices.test_results_converge_with_slices: the same 1 % on other bearings)."""
    def pmax(n, *extra):
        case = run("bearing=tsrb_reference", *extra, f"solver.n_slices={n}")
        return float(case.pmax.sel(race="outer")), bool(case.edge_stress)

    edge = [pmax(n, "bearing.kappa=0.99", "load.Fa=4000", "load.Fr=4000") for n in SLICES]
    assert all(flag for _, flag in edge)
    assert edge[0][0] < edge[1][0] < edge[2][0] and edge[2][0] > 1.10 * edge[0][0]
    inner = [pmax(n, "bearing.PCR=36", "load.Fa=4000", "load.Fr=0") for n in SLICES[1:]]
    assert not any(flag for _, flag in inner)
    assert inner[1][0] == pytest.approx(inner[0][0], rel=0.01)


@pytest.mark.parametrize("Fa, n", [(20000.0, 20), (20000.0, 40), (20000.0, 80), (40000.0, 40), (40000.0, 80)])
def test_logarithmic_profile_keeps_the_contact_off_the_roller_ends(Fa, n):
    """TRB 32208 with its DIN 26281 logarithmic profile (eq. 2.5: the crown drop grows without bound
    towards the ends) up to 40 kN, the top of the thesis's load range (Fig. 7.21): no edge contact.
    At 40 kN the contact ends 0.1-0.3 mm from the roller ends (80 slices of 0.2 mm: the end slice
    unloaded, the next one loaded); 20 slices of 0.8 mm cannot place an end that close to the roller
    end (its extrapolation from the end centres, 0.4 mm in, says edge contact), so 40 kN starts at
    40 slices. The verdict needs slices narrower than the distance from the contact end to the
    roller end, like any end position of a slice model."""
    case = run("bearing=trb_32208", f"load.Fa={Fa}", "load.Fr=0", f"solver.n_slices={n}")
    assert not bool(case.edge_stress)
    assert float(case.edge_interference.max()) < 0.0


EDGE_DIRECTIONS = {   # thesis 7.2.1 and 7.2.4: pmax changes the thesis puts down to the roller-edge stress
    "PCR=122.5": +1,  # 7.2.1: "pressure peaks ... from the stress concentration in the edge area" (Fig. 7.8 *)
    "PCR=36": -1,     # 7.2.1: aA = 0 "turns into a reduction of the maximum pressure"
    "aPk=5.5": +1,    # 7.2.4: up aPk, "maximum pressure increased due to the stress concentration on the roller edge"
    "aPk=3": -1,      # 7.2.4: down aPk, "maximum pressure due to the stress concentration on the roller edge decreased"
}


@pytest.mark.parametrize("Fr", [0.0, 4000.0])
@pytest.mark.parametrize("change", list(EDGE_DIRECTIONS))
def test_thesis_edge_stress_directions_of_7_2(change, Fr):
    """Each change of Table 7.2 that the thesis explains by the stress concentration on the roller
    edge moves this model's edge interference the same way, from tsrb_reference at Fa = 4 kN, pure
    axial and with Fr = 4 kN (scenarios 1 and 4 of Fig. 7.6). With aPk from the small end
    (docs/aPk_convention.md), 'up aPk' moves the contacts towards the large end, onto its edge."""
    def interference(*extra):
        case = run("bearing=tsrb_reference", "load.Fa=4000", f"load.Fr={Fr}", *extra)
        return float(case.edge_interference.max())

    moved = interference(f"bearing.{change}") - interference()
    assert moved * EDGE_DIRECTIONS[change] > 0.0


@pytest.mark.parametrize("overrides,Fa,Fr", [(["bearing.PCR=36"], 4000.0, 0.0), (["bearing.kappa=0.90"], 4000.0, 0.0),
                                             (["bearing=trb_32208"], 20000.0, 4000.0)])
def test_slice_pmax_is_the_halfspace_peak_where_no_contact_reaches_a_roller_end(overrides, Fa, Fr):
    """Interior contacts of real bearings (TSRB PCR 36 and kappa 0.90 of thesis Table 7.2, TRB 32208's
    logarithmic profile): the most loaded roller's outer contact solved again by the 2-D half-space
    reference (Boussinesq rectangles, Polonsky & Keer CG; tests.helpers.halfspace_contact_peak, 80
    cells per mm along the roller, 40 over 5 Hertz half-widths across) on the exact rigid gap of the
    solved pose, at the same load, peaks at the slice model's pmax within 2 %. Where a contact runs
    onto a roller end the two part (the end's peak: docs/edge_peak_corner.md). The 2 %: the grid's
    cell size across (b/8) and the slice model's Hertz profile per slice (found: 0.1-0.5 %)."""
    from sim.api.simulation import build_model
    from tests.helpers import case, halfspace_contact_peak

    model = build_model(sim.load_config(["bearing=tsrb_reference", *overrides]))
    raw = model.solve(case(Fa, Fr))
    j = int(np.argmax(raw["Q"].sum(axis=1)))
    free = np.ascontiguousarray(raw["free"][j:j + 1])
    edge = np.empty(2)
    edge_interference(free, raw["pressure"][j:j + 1] > 0.0, model.bearing.end_drop, edge)
    assert edge[0] < 0.0                       # the contact ends inside the roller
    peak, x = halfspace_contact_peak(model, raw, j, 0, 1.0, 80, 40)
    assert peak == pytest.approx(raw["pressure"][j, 0].max(), rel=0.02)
    assert abs(x) < 0.5 * model.geometry.Lwe - 0.5
