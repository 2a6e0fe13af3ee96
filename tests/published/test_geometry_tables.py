"""Derived bearing geometry of ``sim.geometry.Geometry`` against the thesis's tables.

Checks gamma (eq. 2.1), aA (MODEL.md 2), PCR_LB and s (eq. 2.7) and the rib-free balance
ratio x*/x_large (MODEL.md 4) of the configs in conf/bearing against the published values.
The table numbers are copied from shared/reference/thesis_data.yaml (keys ``bearings``,
``pinion_application.initial_parameters`` and ``sensitivity``) and from MODEL.md 2 and 4, so
the tests do not read files outside the repository. Every tolerance carries its reason.

Units: mm, deg.
"""
import numpy as np
import pytest

import sim
from sim.geometry import Geometry


def build(*overrides):
    """Geometry of a config composed with Hydra overrides, as the simulation builds it."""
    cfg = sim.load_config(list(overrides))
    return Geometry.from_config(cfg.bearing, cfg.material, cfg.solver.n_slices)


# --------------------------------------------------------------------------- gamma, eq. (2.1)
# gamma [deg] as listed in the thesis (thesis_data.yaml: bearings.<name>.gamma)
GAMMA_TABLE = {
    "trb_31313": (4.165, "Table 7.3"),
    "tsrb_prototype": (4.5, "Table 6.1"),
    "tsrb_pinion": (4.165, "Table 7.4"),
    "tsrb_pinion_long": (4.165, "Table 7.5, increased roller length"),
    "tsrb_pinion_alpha": (5.018, "Table 7.5, increased contact angle"),
}


@pytest.mark.parametrize("name", sorted(GAMMA_TABLE))
def test_taper_angle_reproduces_tables(name):
    """Tables 4.2, 6.1, 7.3, 7.4, 7.5: gamma from eq. (2.1) matches the listed taper angle."""
    listed, _source = GAMMA_TABLE[name]
    gamma = np.degrees(build(f"bearing={name}").gamma)
    # thesis_data.yaml: "(2.1) reproduces gamma of Tables 4.2, 6.1, 7.3, 7.4, 7.5 to within
    # 0.1 deg". The tables print 1-3 decimals and Table 4.2's 2.29 (vs 2.309 from (2.1)) is a
    # catalogue value, so 0.1 deg is the documented agreement, not a rounding interval.
    assert gamma == pytest.approx(listed, abs=0.1)


def test_taper_angle_trb_32208_deviates_from_table_4_2():
    """Table 4.2 lists gamma = 2.29 deg for the TRB 32208: eq. (2.1) evaluated at 14 deg (2.31) or at
    the 13.86 deg that the catalogue e = 0.37 implies (2.29), i.e. with the catalogue CUP angle taken
    as the roller axis. The model puts the cup angle alpha + gamma at 14 deg (issue 14 item 4,
    conf/bearing/trb_32208.yaml), so its roller axis is 12.01 deg and (2.1) gives gamma = 1.99 deg."""
    g = build("bearing=trb_32208")
    gamma = np.degrees(g.gamma)
    # 0.01 deg: the 3 printed decimals of alpha = 12.013 move gamma by < 0.001 deg
    assert gamma == pytest.approx(np.degrees(np.arctan(10.0 * np.sin(np.radians(12.013)) / 60.0)), abs=1e-9)
    assert gamma == pytest.approx(1.99, abs=0.01)
    # Table 4.2's number is (2.1) at the cup angle that e = 0.37 implies, to its printed 2 decimals
    cup_e = np.arctan(0.37 / 1.5)
    assert np.degrees(np.arctan(10.0 * np.sin(cup_e) / 60.0)) == pytest.approx(2.29, abs=0.005)


def test_taper_angle_reference_bearing_is_not_table_7_1():
    """Table 7.1 lists gamma = 2.39 deg for the reference TSRB; eq. (2.1) gives 2.31 deg.

    The thesis is inconsistent with itself here (noted in thesis_data.yaml): the reference
    bearing copies TRB 32208 (alpha 14, Dwe 10, Dpw 60), whose gamma is 2.29-2.31. The model
    keeps eq. (2.1) and does not tune to 2.39.
    """
    gamma = np.degrees(build("bearing=tsrb_reference").gamma)
    # atan(10 sin 14 / 60) = 2.3089 deg; 0.01 deg = the second printed decimal of "2.31"
    assert gamma == pytest.approx(2.31, abs=0.01)
    # 0.05 deg: well above the 0.01 deg rounding of either number and below the 0.08 deg gap,
    # so this fails only if someone tunes gamma towards the listed 2.39
    assert abs(gamma - 2.39) > 0.05


# --------------------------------------------------------------------------- aA, MODEL.md 2
# aA [mm] listed in the thesis, for the designs where MODEL.md says the aA(PCR) relation holds
AA_FITS = [
    pytest.param(("bearing=tsrb_reference",), 62.0, id="table_7_1_reference"),
    pytest.param(("bearing=tsrb_pinion",), 20.28, id="table_7_4_pinion"),
    pytest.param(("bearing=tsrb_pinion_long",), 46.6, id="table_7_5_longer_roller"),
    # Table A.5 initial parameters: alpha 24.5, PCR 200, aPk 6.05, kappa 0.99 on the pinion
    # main dimensions (pinion_application.initial_parameters)
    pytest.param(("bearing=tsrb_pinion", "bearing.PCR=200", "bearing.aPk=6.05", "bearing.kappa=0.99"),
                 115.89, id="table_A_5_initial"),
]


@pytest.mark.parametrize("overrides, listed", AA_FITS)
def test_centre_offset_aA_reproduces_tables(overrides, listed):
    """Tables 7.1, 7.4, 7.5 (longer roller) and A.5: aA from the PCR relation of MODEL.md 2."""
    aA = build(*overrides).aA
    # MODEL.md 2: the relation is a reconstruction (Fig. 2.7 gives no formula) that
    # "reproduces Tables 7.1, 7.4, 7.5 (longer roller) and A.5 within about 1 mm"; computed
    # 61.13, 19.53, 45.85, 116.05 -> deviations 0.16-0.87 mm.
    assert aA == pytest.approx(listed, abs=1.0)


AA_MISFITS = [
    pytest.param("tsrb_prototype", 0.25, id="table_6_1_prototype"),
    pytest.param("tsrb_pinion_alpha", 15.6, id="table_7_5_bigger_alpha"),
]


@pytest.mark.parametrize("name, listed", AA_MISFITS)
def test_centre_offset_aA_documented_mismatch(name, listed):
    """Tables 6.1 and 7.5 (bigger alpha) do NOT follow the aA(PCR) relation (MODEL.md 2).

    MODEL.md: "Table 6.1 and Table 7.5 (bigger alpha) do not fit it; document the mismatch,
    do not tune to it." The configs keep PCR as the design variable and derive aA, so the
    computed aA (2.25 mm prototype, 6.47 mm bigger alpha) differs from the listed one.
    """
    aA = build(f"bearing={name}").aA
    # 1 mm is the agreement the relation achieves where it holds (test above); a deviation
    # beyond it is the documented mismatch. Fails if someone tunes the relation to these rows.
    assert abs(aA - listed) > 1.0


def test_pcr_36_puts_centre_on_bearing_axis():
    """Table 7.2 / section 7.2 (thesis_data sensitivity.note_PCR_36): PCR = 36 gives aA = 0."""
    aA = build("bearing=tsrb_reference", "bearing.PCR=36").aA
    # the thesis states "aA = 0" without decimals; 1 mm is the accuracy of the aA(PCR)
    # reconstruction (MODEL.md 2). Computed: -0.30 mm.
    assert aA == pytest.approx(0.0, abs=1.0)


def test_pcr_28_puts_centre_beyond_bearing_axis():
    """Table 7.2 (sensitivity PCR down2 = 28) and note_PCR_36: PCR = 28 gives aA < 0."""
    aA = build("bearing=tsrb_reference", "bearing.PCR=28").aA
    # a sign, no tolerance needed: computed -7.98 mm
    assert aA < 0.0


# --------------------------------------------------------------------------- PCR_LB and s, eq. (2.7)
@pytest.mark.parametrize("name, s_listed, source", [
    ("tsrb_reference", 5.0, "Table 7.1 kappa 0.95 with PCR 100: 's = 5 mm as for CARB 2208'"),
    ("tsrb_prototype", 2.0, "Table 6.1 lists s = 2 mm"),
])
def test_raceway_profile_radius_and_osculation(name, s_listed, source):
    """Eq. (2.7), Tables 7.1 and 6.1: PCR_LB = PCR (2 - kappa) and s = PCR_LB - PCR."""
    g = build(f"bearing={name}")
    # both are exact algebra on config values (kappa of the prototype is typed as
    # 1 - 2/43.83 to 15 digits); 1e-9 mm only absorbs floating-point rounding
    assert g.PCR_LB == pytest.approx(g.PCR * (2.0 - g.kappa), abs=1e-9)
    assert g.s == pytest.approx(g.PCR_LB - g.PCR, abs=1e-9)
    assert g.s == pytest.approx(s_listed, abs=1e-9), source


# --------------------------------------------------------------------------- x*/x_large, MODEL.md 4
@pytest.mark.parametrize("name, ratio", [
    ("tsrb_reference", 0.95),     # Table 7.1
    ("tsrb_pinion", 0.82),        # Table 7.4
    ("tsrb_pinion_long", 0.92),   # Table 7.5, longer roller
    ("tsrb_pinion_alpha", 0.87),  # Table 7.5, bigger alpha
])
def test_load_centroid_ratio(name, ratio):
    """MODEL.md 4 (from Tables 7.1, 7.4, 7.5): x*/x_large of the designs the thesis settled on.

    x* = PCR sin(gamma) is the rib-free axial balance point, x_large = aPk + aP - Lwe/2 the
    large-end contact point (aPk from the small end face).
    """
    g = build(f"bearing={name}")
    x_star, x_large = g.load_centroid_x, g.contact_points_x[1]
    # MODEL.md prints two digits: half a unit of the last digit (0.005) is the rounding
    # interval, tighter than the 0.01 asked for. Computed 0.948, 0.817, 0.918, 0.875.
    assert x_star / x_large == pytest.approx(ratio, abs=0.005)


@pytest.mark.parametrize("name, x_star", [
    ("tsrb_reference", 4.03),   # Table 7.1 geometry
    ("tsrb_pinion", 6.54),      # Table 7.4 geometry
])
def test_load_centroid_position(name, x_star):
    """MODEL.md 4: x* = PCR sin(gamma) = 4.03 mm (reference), 6.54 mm (pinion)."""
    # MODEL.md prints two decimals: half a unit of the last digit. Computed 4.029, 6.537.
    assert build(f"bearing={name}").load_centroid_x == pytest.approx(x_star, abs=0.005)
