"""Frictional torque of whole bearings: energy balance, kinematics, trends and the thesis's 7.2 directions.

MODEL.md 5 and issue "Simulation core II". Loads in N, speeds in rpm, torque in N mm.
"""
import functools

import numpy as np
import pytest

import sim
from sim.physics.kinematics import cage_speed_rolling


def run(bearing, *overrides):
    """One case of ``bearing`` (conf defaults: Fa 4.5 kN, Fr 2 kN, 2000 rpm, FVA 3 at 55 degC)."""
    ds = sim.simulate(sim.load_config([f"bearing={bearing}", *overrides]))
    case = ds.isel(design=0, case=0)
    assert bool(case.converged), f"{bearing} {overrides} did not converge"
    return case


def share(case, component):
    return float(case.torque_component.sel(component=component)) / float(case.torque)


ENERGY_CASES = [
    ("trb_32208", ["load.Fr=0"]),
    ("trb_32208", ["load.Fa=40000", "load.Fr=0"]),
    ("trb_32208", ["load.Fa=40000", "load.Fr=0", "friction.thermal=false", "lubricant.pressure_viscosity_model=barus"]),
    ("trb_32208", ["load.Fr=4000"]),
    ("tsrb_reference", ["load.Fr=0"]),
    ("tsrb_reference", ["load.Fr=4000", "load.tilt=0.02"]),
    ("tsrb_prototype", ["load.Fr=2000", "load.speed=1000", "load.oil_temperature=60"]),
    ("tsrb_pinion", ["load.Fa=35000", "load.Fr=0", "load.speed=1100", "lubricant=pinion_oil",
                     "load.oil_temperature=50"]),
]


@pytest.mark.parametrize("bearing,overrides", ENERGY_CASES)
def test_outer_ring_torque_equals_power_over_speed(bearing, overrides):
    """At the traction equilibrium (every roller's spin moment and the cage's moment zero) the
    torque the rollers exert on the outer ring equals power loss / inner-ring speed (energy
    balance, MODEL.md 5). Both are computed independently: the torque from contact forces and
    couples, the power from the dissipation of each mechanism. The kinematic tolerance
    (friction.tolerance = 1e-6 of mu Q Dpw/2) bounds the mismatch far below the 1 % the issue
    demands; 1e-3 leaves room for the residual of every roller adding up."""
    case = run(bearing, *overrides)
    omega_i = np.pi * float(case.speed) / 30.0
    torque_from_power = float(case.power_loss) * 1e3 / omega_i        # W -> N mm/s, / rad/s
    assert float(case.torque) > 0.0
    assert abs(float(case.torque) - torque_from_power) <= 1e-3 * float(case.torque)
    np.testing.assert_allclose(float(case.torque_component.sum()), float(case.torque), rtol=1e-12)
    assert bool((case.torque_component >= 0).all())


@pytest.mark.parametrize("bearing", ["trb_32208", "tsrb_reference"])
def test_with_rolling_kinematics_the_torque_is_the_power_over_the_speed(bearing):
    """friction.kinematics = rolling imposes the speeds (2.20), (2.22): the roller and cage moments
    are then not balanced, and the torque of the contacts on the outer ring is not the bearing's
    friction torque (it was -1197 N mm for the TRB 32208 at 4.5 / 2 kN, whose power loss is 162 W).
    The friction torque of imposed speeds is the energy balance's, power loss / inner-ring speed
    (as at speed 0): exact by construction (rtol 1e-12, round-off), positive, each component a
    dissipation (>= 0), and the breakdown sums to it."""
    case = run(bearing, "load.Fr=2000", "friction.kinematics=rolling", "friction.cage_guidance=rigid")
    omega_i = np.pi * float(case.speed) / 30.0
    assert float(case.torque) > 0.0
    np.testing.assert_allclose(float(case.torque), float(case.power_loss) * 1e3 / omega_i, rtol=1e-12)
    np.testing.assert_allclose(float(case.torque_component.sum()), float(case.torque), rtol=1e-12)
    assert bool((case.torque_component >= 0).all())


# Cases whose breakdown had a negative component while the rigid slip of a contact was its
# load-weighted mean slip (session 18, random cases over 7 bearings): the TSRB's sliding down to
# -0.46 % of its torque where the slip changes sign along the contact, a TRB's drilling -2.5e-5.
NEGATIVE_BEFORE = [
    ("tsrb_pinion_alpha", ["load.Fa=18886", "load.Fr=0", "load.speed=1377.8", "load.oil_temperature=73.6",
                           "lubricant=pinion_oil"]),
    ("tsrb_pinion_long", ["load.Fa=17404", "load.Fr=7754", "load.speed=1879.5", "load.oil_temperature=95.1",
                          "lubricant=pinion_oil"]),
    ("trb_31313", ["load.Fa=4907", "load.Fr=3970", "load.speed=2730", "load.oil_temperature=27.6",
                   "lubricant=pinion_oil"]),
]


@pytest.mark.parametrize("bearing,overrides", ENERGY_CASES + NEGATIVE_BEFORE)
def test_every_loss_component_is_a_dissipation(bearing, overrides):
    """Each component of the breakdown is a power the bearing dissipates, so none is negative.
    For sliding and drilling this holds by construction (sim.physics.friction, module
    docstring): a contact's slip power along the rolling direction, sum G_k s_k^2 with the
    slices' traction conductances G_k > 0, splits into the power of the G-weighted mean slip,
    (sum F_t)^2 / sum G_k >= 0 (sliding), and the G-weighted variance of the slip about it, >= 0
    (drilling, with the spin power, itself >= 0). Bound: 0, less the round-off of that
    difference (1e-12 of the torque)."""
    case = run(bearing, *overrides)
    assert float(case.torque_component.min()) >= -1e-12 * float(case.torque)
    np.testing.assert_allclose(float(case.torque_component.sum()), float(case.torque), rtol=1e-12)


def test_a_roller_that_stops_rolling_on_a_ring_has_a_speed_balance():
    """TRB 31313 at Fa 3.0 kN, Fr 3.3 kN, 542 rpm, pinion oil at 75 degC (a random case, session
    18): the two rollers at the end of the load zone carry 3.8 N (2274 N at the top) and their rib
    friction brakes them below rolling on one ring. The rolling couple's direction turned there as
    a sign, their moment about the axis jumped by twice the couple (+0.52 to -1.22 N mm between
    20.97 and 20.98 rad/s) and had no root: the case failed. Regularised like the boundary friction
    (sim.physics.friction), the balance has a root: with a rigid cage, where each roller's spin is
    balanced at its azimuth, the case converges with those rollers skidding (below half their
    rolling speed; measured 0.13 of the fastest). The free rollers' spin inertia along the orbit
    (the default, sim.solvers.kinematics) carries them through that arc spinning (measured 0.83 of
    the fastest). Either way the torque equals power loss / speed (1e-3, as above)."""
    from sim.api.friction_model import coupled_solution
    from sim.api.simulation import build_friction, build_model
    from tests.helpers import case as operating_point

    op = operating_point(3040.4, 3324.8, 542.0, 0.0, 74.9)
    for guidance, skidding in (("rigid", True), ("free", False)):
        cfg = sim.load_config(["bearing=trb_31313", "lubricant=pinion_oil", f"friction.cage_guidance={guidance}"])
        model = build_model(cfg)
        friction = build_friction(cfg, model)
        raw, fr = coupled_solution(model, friction, op)
        assert fr["friction_converged"] and fr["coupling_converged"]
        wR = fr["kinematics"][1]
        assert (wR.min() < 0.5 * wR.max()) == skidding, guidance
        torque_from_power = fr["power_loss"] * 1e3 / (op.speed_rpm * np.pi / 30.0)
        assert abs(fr["torque"] - torque_from_power) <= 1e-3 * fr["torque"]


@pytest.mark.parametrize("bearing,overrides", [
    ("trb_32208", ["load.Fa=4500", "load.Fr=9000"]),
    ("trb_31313", ["load.Fa=35000", "load.Fr=15000", "load.speed=1100", "lubricant=pinion_oil",
                   "load.oil_temperature=50", "friction.skew.enabled=true"]),
    ("tsrb_prototype", ["load.Fa=3300", "load.Fr=3000"]),
])
def test_rollers_free_in_their_pockets_keep_the_energy_balance_and_pay_less_pocket_friction(bearing, overrides):
    """friction.cage_guidance = free (the default): each loaded roller orbits at its own speed, its
    contacts' z-moment about the bearing axis balanced on its own (and with skew its skew moment by
    the pocket's couple); its pocket carries no net traction, only the z-reaction of the moments
    about its centre. Under these radial loads the cage pocket friction is then below the rigid
    cage's (measured 0.35 / 0.002 / 0.99 N mm against 11.0 / 143.5 / 1.38 for the three cases: the
    prototype's rigid cage carries little net traction), every other mechanism stays within 0.5 % of the rigid
    cage's (the speeds move by the roller's own slip only: measured at most 0.12 % (the skewed
    TRB 31313's rib; rolling, hysteresis and drilling 0.05 % at most), the bound 4x that; the
    sliding, near 0, within 1e-3 of the torque), and the outer-ring torque equals power loss /
    speed within 1e-3, as for the rigid cage (test_outer_ring_torque_equals_power_over_speed)."""
    rigid = run(bearing, *overrides, "friction.cage_guidance=rigid")
    free = run(bearing, *overrides, "friction.cage_guidance=free")
    cage = list(rigid.component.values).index("cage")
    assert 0.0 <= float(free.torque_component[cage]) < float(rigid.torque_component[cage])
    others = [k for k in range(rigid.component.size) if k != cage]
    np.testing.assert_allclose(free.torque_component.values[others], rigid.torque_component.values[others],
                               rtol=5e-3, atol=1e-3 * float(rigid.torque))
    omega_i = np.pi * float(free.speed) / 30.0
    assert abs(float(free.torque) - float(free.power_loss) * 1e3 / omega_i) <= 1e-3 * float(free.torque)


@pytest.mark.parametrize("bearing,overrides", [
    ("trb_32208", ["load.Fa=40000", "load.Fr=0"]),
    ("tsrb_pinion", ["load.Fa=35000", "load.Fr=0", "load.speed=1100", "lubricant=pinion_oil",
                     "load.oil_temperature=50", "friction.skew.enabled=true"]),
], ids=["trb_32208", "tsrb_pinion skewed"])
def test_under_a_pure_axial_load_free_and_rigid_guidance_coincide(bearing, overrides):
    """Under a pure axial load every roller is loaded alike, so the rigid cage's balance (the sum of
    the rollers' z-moments) is each roller's own, the free rollers' condition: the two guidances
    give the same speeds, pocket forces and torque, also with the rollers skewed onto their
    pockets (whose couples' z-reactions the pockets carry). With one roller class the rigid
    solution is kept as it is (sim.api.friction_model: solved again to the free rollers' per-roller
    tolerance it moved the torque by 4e-7 here and by up to 1.3e-5 on random pinion designs, all
    within the kinematic tolerance); the bound 1e-6 is that tolerance's, the result bit-identical."""
    rigid = run(bearing, *overrides, "friction.cage_guidance=rigid")
    free = run(bearing, *overrides, "friction.cage_guidance=free")
    np.testing.assert_allclose(free.torque_component.values, rigid.torque_component.values, rtol=1e-6,
                               atol=1e-9 * float(rigid.torque))
    assert float(free.torque_component.sel(component="cage")) > 0.0
    np.testing.assert_allclose(free.Q.values, rigid.Q.values, rtol=1e-6)


def test_cage_speed_follows_rolling_kinematics_under_load():
    """A loaded bearing slips little: the cage speed from the traction balance stays within 1 %
    of rolling without slip (2.20) (the friction moments are 1e-3 of the traction capacity), and
    is below it (the cage lags, losses brake the rollers)."""
    for bearing in ("trb_32208", "tsrb_reference"):
        case = run(bearing)
        g = sim.api.simulation.build_model(sim.load_config([f"bearing={bearing}"])).geometry
        rolling = cage_speed_rolling(2000.0, 0.0, g.Dwe, g.Dpw, g.alpha)
        assert abs(float(case.cage_speed) - rolling) < 0.01 * rolling


def test_srr_of_crowned_roller_changes_sign_along_the_roller():
    """A crowned TSRB roller rolls without slip at two points only and slides elsewhere, with
    opposite signs on either side of a rolling point (thesis 2.3.1, Fig. 2.17, Figs. 7.4-7.5);
    the TRB's tapered roller rolls on a common apex and its SRR stays near zero along the roller."""
    proto = run("tsrb_prototype", "load.Fr=0").srr.sel(race="outer").values
    loaded = proto[np.isfinite(proto)]
    assert loaded.max() > 0.0 > loaded.min()
    assert np.abs(loaded).max() > 0.01          # percent-level differential slip
    trb = run("trb_32208", "load.Fr=0").srr.sel(race="outer").values
    assert np.nanmax(np.abs(trb)) < 0.1 * np.abs(loaded).max()


@pytest.mark.parametrize("bearing", ["trb_32208", "tsrb_reference"])
def test_torque_rises_with_speed(bearing):
    """Thesis 7.2.5 / sensitivity_directions.speed: torque rises with speed for both bearings
    (1000, 2000, 4000 rpm; the thesis's three speeds)."""
    torques = [float(run(bearing, "load.Fr=0", f"load.speed={n}").torque) for n in (1000, 2000, 4000)]
    assert torques[0] < torques[1] < torques[2]


@pytest.mark.parametrize("bearing", ["trb_32208", "tsrb_reference"])
def test_torque_rises_with_viscosity(bearing):
    """Colder oil is more viscous: in the EHL regime (Lambda > 1 at 40-55 degC) the hydrodynamic
    rolling resistance grows with eta0^0.66 and the torque rises (Stribeck curve right of its
    minimum, thesis 2.3.2)."""
    cold = run(bearing, "load.Fr=0", "load.oil_temperature=40")
    warm = run(bearing, "load.Fr=0", "load.oil_temperature=55")
    assert float(cold.lambda_ratio.min()) > 1.0
    assert float(cold.torque) > float(warm.torque)


def test_rib_friction_dominates_trb_at_low_lambda():
    """Thesis 2.2.1 and 7.2: the roller-end/rib contact is a large share of the TRB's torque in
    mixed friction. At Lambda < 0.5 (90 degC, 300 rpm) the rib takes most of the torque; in the
    EHL regime (55 degC, 2000 rpm) it is a minor share."""
    low = run("trb_32208", "load.Fr=0", "load.oil_temperature=90", "load.speed=300")
    high = run("trb_32208", "load.Fr=0")
    assert float(low.lambda_ratio.max()) < 0.5 < 1.0 < float(high.lambda_ratio.min())
    assert share(low, "rib") > 0.5
    assert share(high, "rib") < share(low, "rib")
    assert float(run("tsrb_reference", "load.Fr=0").torque_component.sel(component="rib")) == 0.0


@pytest.mark.parametrize("Fa,Fr", [(4000, 0), (4000, 4000)])
def test_drilling_is_the_largest_loss_of_the_prototype_and_sliding_the_smallest(Fa, Fr):
    """Thesis 6.3 (Fig. 6.8 discussion): at the rig's moderate axial loads "the drilling friction
    taking place at the prototype outweigh[s] the other types of friction"; thesis 7.1 (Fig. 7.2
    discussion): the sliding friction of a TSRB "has in comparison less of an influence than the
    rolling and the drilling friction" (prototype and reference geometry)."""
    proto = run("tsrb_prototype", f"load.Fa={Fa}", f"load.Fr={Fr}")
    raceway = {c: share(proto, c) for c in ("rolling", "hysteresis", "sliding", "drilling")}
    assert max(raceway, key=raceway.get) == "drilling"
    for bearing in ("tsrb_prototype", "tsrb_reference"):
        case = proto if bearing == "tsrb_prototype" else run(bearing, f"load.Fa={Fa}", f"load.Fr={Fr}")
        assert share(case, "sliding") < min(share(case, "rolling"), share(case, "drilling")), bearing


def test_shear_heating_lowers_the_rib_friction_where_the_rib_heats():
    """The TRB's roller-end / rib contact slides at about 1 m/s per 1000 rpm. Its frictional heat
    warms the film and the film's viscosity falls, so the rib friction with shear heating is below
    the isothermal one, the more the faster the rib slides: TRB 32208 at 40 kN, -9 % at 2000 rpm
    and -23 % at 4000 rpm (asserted: a larger reduction at the higher speed, both below 1); TRB
    31313 at 35 kN, 4000 rpm, where the rib carries 820 N per roller: -51 % (asserted: below 80 %).
    At 4.5 kN and 2000 rpm the TRB 32208's rib carries a tenth of the load and the heat is small
    (the rib friction changes by less than 15 %). The raceway rolling resistance, an inlet effect,
    sees the heating only through the slightly changed roller speeds (asserted 1e-4).
    (Measured on the cone rib, sim.geometry._sphere_rib; with the flat rib before it the contact
    was half as large and the TRB 32208 at 40 kN, 2000 rpm lost 53 %.)"""
    def rib_and_rolling(bearing, Fa, speed, thermal):
        case = run(bearing, f"load.Fa={Fa}", "load.Fr=0", f"load.speed={speed}", f"friction.thermal={thermal}")
        return [float(case.torque_component.sel(component=c)) for c in ("rib", "rolling")]

    ratio = {}
    for speed in (2000, 4000):
        hot, cold = rib_and_rolling("trb_32208", 40000, speed, "true"), rib_and_rolling("trb_32208", 40000, speed,
                                                                                       "false")
        ratio[speed] = hot[0] / cold[0]
        assert hot[1] == pytest.approx(cold[1], rel=1e-4)
    assert ratio[4000] < ratio[2000] < 1.0
    hot, cold = rib_and_rolling("trb_31313", 35000, 4000, "true"), rib_and_rolling("trb_31313", 35000, 4000, "false")
    assert hot[0] < 0.8 * cold[0]
    hot, cold = rib_and_rolling("trb_32208", 4500, 2000, "true"), rib_and_rolling("trb_32208", 4500, 2000, "false")
    assert 0.85 * cold[0] < hot[0] <= cold[0]


VARIANTS = {   # thesis Table 7.2, one parameter at a time from tsrb_reference
    "PCR_up": ["bearing.PCR=122.5"], "PCR_down": ["bearing.PCR=36"],
    "alpha_up": ["bearing.alpha=18", "bearing.ratings_alpha=18"],
    "alpha_down": ["bearing.alpha=10", "bearing.ratings_alpha=10"],
    "kappa_up": ["bearing.kappa=0.99"], "kappa_down": ["bearing.kappa=0.90"],
    "aP_up": ["bearing.aP=10", "bearing.aPk=3.5"], "aP_down": ["bearing.aP=7", "bearing.aPk=5"],
    "aPk_up": ["bearing.aPk=5.5"], "aPk_down": ["bearing.aPk=3"],
}
# thesis_data.yaml sensitivity_directions: +1 up, -1 down; 0: "small effect", |relative change| < 10 %
# (every other parameter of Table 7.2 moves the torque by 20-33 % in the thesis and here)
DIRECTIONS = {
    "PCR_up": {"torque": -1, "pmax": +1, "axial_displacement": +1},
    "PCR_down": {"torque": +1, "pmax": -1, "axial_displacement": -1},
    "alpha_up": {"torque": -1, "contact_length_ratio": -1, "C": -1},
    "alpha_down": {"torque": +1, "contact_length_ratio": +1},
    "kappa_up": {"torque": +1, "contact_length_ratio": +1, "pmax": -1},
    "kappa_down": {"torque": -1, "contact_length_ratio": -1, "pmax": +1},
    "aP_up": {"torque": 0, "pmax": 0, "axial_displacement": -1},
    "aP_down": {"torque": 0, "pmax": 0, "axial_displacement": +1},
    "aPk_up": {"torque": -1, "pmax": +1},
    "aPk_down": {"torque": +1, "pmax": -1, "axial_displacement": -1},
}
SCENARIOS = {"pure axial": (4000, 0), "combined": (4000, 4000)}   # thesis Fig. 7.6 scenarios (4,0) and (4,4) kN
APK_REASON = ("aPk measured from the small end (MODEL.md 4): a bigger aPk moves both contact points towards the "
              "large end, past the load centroid PCR sin(gamma), so the roller needs less axial travel and its "
              "contacts less crown; the thesis's directions need the opposite")
APK_PMAX_REASON = ("the thesis's pmax directions are those of the edge stress: aPk 4.25 -> 5.5 mm moves the large-end "
                   "contact further onto the roller end (edge_interference 0.33 -> 0.79 at 4/0 kN), aPk 3 takes it off "
                   "(-0.12); that peak is singular at the sharp end of Lwe and the slice pmax does not contain it "
                   "(tests/published/test_edge_stress.py, docs/aPk_convention.md point 7); with the finite peak of a "
                   "roller corner in pmax, aPk up (4/0 kN) and aPk down (4/4) come out, aPk down (4/0) does not, "
                   "and four other directions turn (docs/edge_peak_corner.md)")
# Directions our model does not reproduce (README, known deviations). Strict: the day one of them
# comes out as the thesis says, the test fails and this table must be updated.
DEVIATIONS = {
    ("PCR_down", "pmax"): ("PCR 36 (aA = 0): pmax +11 to +12 % here, with a contact 20 % shorter under the same load. The "
                           "thesis's cause is reproduced: the reference's contact runs onto the large roller end "
                           "(edge_stress, as Fig. 7.9 b) and PCR 36's does not (tests/published/test_edge_stress.py); "
                           "but that edge peak is singular for the sharp end of Lwe, and the slice pmax (20 slices, "
                           "the end slice at 651 MPa) does not contain it, so our pmax compares the inner peaks; "
                           "a finite corner's peak in pmax turns the combined case but not the pure axial one, and "
                           "four other directions the other way (docs/edge_peak_corner.md)"),
    ("PCR_down", "torque"): ("PCR 36: drilling +75 % as the thesis says (7.2.1), but the contact 20-27 % shorter lowers "
                             "the EHL rolling loss by more (-2 to -4 % in all): the rolling force per unit length "
                             "hardly depends on load (Goksem & Hargreaves 1978; the 1-D Reynolds solution, "
                             "tests/friction/test_rolling_resistance.py), so it scales with the contact length; a "
                             "W^0.25-0.3 fit (Zhou & Hoeprich 1991, used in MBS models like the thesis's) loads it "
                             "onto fewer, busier slices instead"),
    ("kappa_up", "pmax", "combined"): ("kappa 0.99: pmax +5 % here under combined load (pure axial: -3 %, as the thesis): the "
                                       "contact runs onto the large roller end and pmax is the end slice's, which grows with "
                                       "the slice count (1231 MPa at 20 slices, above 1300 at 40; "
                                       "tests/published/test_edge_stress.py); the thesis marks such edge peaks as not "
                                       "comparable (Figs. 7.8, 7.22); with a finite corner's peak pmax rises by 40 % "
                                       "(docs/edge_peak_corner.md)"),
    ("aPk_up", "torque"): ("aPk 4.25 -> 5.5 mm: drilling +25 % (the contact zones further from the pitch line), "
                           "the rolling loss unchanged (the contact length moves by less than a slice). The "
                           "pure-axial case passed before only because a slice left the contact there and cut the "
                           "rolling loss by 6 % (slice quantisation, gone with the contact ends between slices). "
                           + APK_REASON),
    ("aPk_up", "pmax", "pure axial"): APK_PMAX_REASON,
    ("aPk_down", "torque"): APK_REASON,
    ("aPk_down", "pmax"): APK_PMAX_REASON,
    ("aPk_down", "axial_displacement"): APK_REASON,
}


def quantity(case, name):
    value = case[name]
    if "race" in value.dims:
        value = value.sel(race="outer")
    return float(value)


@functools.lru_cache(maxsize=None)
def sensitivity_case(scenario, variant):
    Fa, Fr = SCENARIOS[scenario]
    return run("tsrb_reference", f"load.Fa={Fa}", f"load.Fr={Fr}", *VARIANTS.get(variant, []))


def _direction_params():
    for scenario in SCENARIOS:
        for variant, directions in DIRECTIONS.items():
            for name, sign in directions.items():
                reason = DEVIATIONS.get((variant, name), DEVIATIONS.get((variant, name, scenario)))
                marks = [pytest.mark.xfail(strict=True, reason=reason)] if reason else []
                yield pytest.param(scenario, variant, name, sign, marks=marks, id=f"{scenario}-{variant}-{name}")


@pytest.mark.parametrize("scenario,variant,name,sign", list(_direction_params()))
def test_sensitivity_direction_of_thesis_7_2(scenario, variant, name, sign):
    """Every direction of thesis 7.2 (thesis_data.yaml sensitivity_directions), one parameter at
    a time from tsrb_reference, on two load scenarios of Fig. 7.6 (pure axial and combined)."""
    base = sensitivity_case(scenario, "reference")
    change = quantity(sensitivity_case(scenario, variant), name) / quantity(base, name) - 1.0
    if sign == 0:
        assert abs(change) < 0.10, f"{variant}: {name} changed by {change:+.3f}, thesis: small effect"
    else:
        assert np.sign(change) == sign, f"{variant}: {name} changed by {change:+.4f}, thesis says {sign:+d}"


@pytest.mark.parametrize("scenario", list(SCENARIOS))
def test_alpha_up_torque_reduction_of_thesis_7_2(scenario):
    """alpha up: about -25 % torque in the thesis; accept -10 to -40 % (one model against another)."""
    change = float(sensitivity_case(scenario, "alpha_up").torque) / float(sensitivity_case(scenario, "reference").torque)
    assert -0.40 < change - 1.0 < -0.10


def test_cage_pocket_friction_enters_the_load_distribution():
    """The cage pocket friction force acts on the roller in its meridian plane (along v') and the
    quasi-static balance takes it back (issue: friction forces enter the force balance), with the
    cage rigid (friction.cage_guidance = rigid: the free rollers carry no pocket force). With no
    pocket friction the roller loads are those of the frictionless balance up to the lateral sum of
    the inner raceway's tangential tractions, which moves the ring across the load: 3.2e-3 of the
    loads here, tolerance 5e-3 (session 35; 1.2e-4 in session 27, before the inner ring's surface
    moved about its own axis: on the ring displaced by delta_r the rigid cage's rollers slip by
    about omega_i delta_r / 2 on each raceway, which the free rollers' own orbit speeds take up);
    with pocket friction they change beyond the solver's
    tolerance (1e-9; measured 5.8e-5), while the bearing still balances Fa and the energy balance
    still holds."""
    base = ["bearing=trb_32208", "load.Fr=4000", "friction.cage_guidance=rigid"]
    free = sim.simulate(sim.load_config(base + ["friction.cage_friction_coefficient=0"])).isel(design=0, case=0)
    rough = sim.simulate(sim.load_config(base + ["friction.cage_friction_coefficient=0.3"])).isel(design=0, case=0)
    plain = sim.simulate(sim.load_config(base + ["friction.enabled=false"])).isel(design=0, case=0)
    # without pocket friction only the tractions' lateral sum feeds back
    np.testing.assert_allclose(free.Q.values, plain.Q.values, rtol=5e-3)
    assert float(free.ring_displacement.sel(direction="lateral")) != 0.0
    change = np.abs(rough.Q.values - free.Q.values).max() / free.Q.values.max()
    print(f"pocket friction changes the loads by {change:.2e} of the largest")
    assert change > 1e-6
    assert float(rough.torque_component.sel(component="cage")) > 0.0
    omega_i = np.pi * float(rough.speed) / 30.0
    assert abs(float(rough.torque) - float(rough.power_loss) * 1e3 / omega_i) <= 1e-3 * float(rough.torque)


def test_torque_has_no_steps_where_slices_enter_or_leave_contact():
    """The EHL rolling force per unit length hardly depends on the load (Goksem & Hargreaves,
    W^0.0126), so a rolling loss counted per loaded slice stepped by a whole slice's share when a
    slice left contact: 0.6 % of the torque on this pinion TSRB (35 kN, 1100 rpm; aPk 10.075 ->
    10.1 mm near the study's optimum), against a trend of 0.04 % per 0.025 mm. With the loss over
    the loaded length of each strip (contact ends between slice centres), the torque is
    continuous: over an aPk sweep in which slices leave the contact, no step exceeds twice the
    median step (a step of one slice's share would be ~15 times it)."""
    design = ["bearing.PCR=50.4", "bearing.kappa=0.989", "bearing.aP=6.0", "bearing.alpha=32.0"]
    load = ["lubricant=pinion_oil", "load.Fa=35000", "load.Fr=0", "load.speed=1100", "load.oil_temperature=50"]
    torque, loaded = [], []
    for aPk in np.linspace(9.8, 11.0, 25):
        case = run("tsrb_pinion", *design, f"bearing.aPk={aPk:.4f}", *load)
        torque.append(float(case.torque))
        loaded.append(int((case.pressure > 0.0).sum()))
    assert len(set(loaded)) >= 2, loaded                  # slices did enter or leave the contact
    steps = np.abs(np.diff(torque))
    assert steps.max() < 2.0 * np.median(steps), (steps.max(), np.median(steps))
