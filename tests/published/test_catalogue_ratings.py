"""ISO 281 factors and load ratings of the TRB configs against bearing catalogues (issue 14 item 4).

ISO 281 (and ISO 355, which defines the angle series of tapered roller bearings) gives a tapered
roller bearing's nominal contact angle as the angle of the outer raceway (cup). In this model's
convention (eq. 2.1, MODEL.md 2) ``alpha`` is the roller-axis angle, so the cup angle is
alpha + gamma; :class:`sim.geometry.Geometry` derives ``ratings_alpha`` from it for a TRB.

Catalogue values (copied here so the tests read nothing outside the repository):

* TRB 32208: e 0.37, Y 1.60, Y0 0.88, C 79 kN, C0 93 kN (Schaeffler 32208-A as printed in thesis
  Table 6.2, "Catalog" column, [Sch17]); SKF 32208 J2/Q prints Y0 0.9. Timken 32208
  (cad.timken.com, part X32208M/Y32208M): C1 = 105 kN, C0 = 98 kN.
* TRB 31313: e 0.83, Y 0.73, Y0 0.4 (Schaeffler medias, series 313: 31310-A, 31318 print the
  same factors); C 163 kN (thesis Table 7.3, Schaeffler 31313-A). The catalogue C0 of the 31313-A
  was not found in the searched sources and is not tested.

Tolerances: 3 % on e, Y, Y0 (issue 14: "cup angles reproduce the catalogue e within 3 %"); the
catalogue prints two significant digits (0.37 carries +-1.4 %, 0.4 carries +-12 %), so 3 % is the
tighter of the two and is what the geometry is required to meet.
"""
import math

import numpy as np
import pytest

import sim
from sim.geometry import Geometry, GeometryError
from sim.physics.ratings import dynamic_load_rating, load_factors, static_load_rating
from sim.api.schema import ConfigError, validate

CATALOGUE = {
    "trb_32208": {"e": 0.37, "Y": 1.60, "Y0": 0.88},   # Schaeffler via thesis Table 6.2
    "trb_31313": {"e": 0.83, "Y": 0.73, "Y0": 0.40},   # Schaeffler 313 series
}


def build(*overrides):
    cfg = sim.load_config(list(overrides))
    return Geometry.from_config(cfg.bearing, cfg.material, cfg.solver.n_slices)


@pytest.mark.parametrize("name", sorted(CATALOGUE))
def test_trb_rating_angle_is_the_cup_angle(name):
    """Closed form: ratings_alpha = alpha + atan(Dwe sin(alpha) / Dpw) (eq. 2.1), in degrees."""
    g = build(f"bearing={name}")
    cup = g.alpha + math.atan(g.Dwe * math.sin(g.alpha) / g.Dpw)
    assert g.ratings_alpha == pytest.approx(math.degrees(cup), rel=1e-12)
    assert g.cup_angle == pytest.approx(cup, rel=1e-12)
    assert g.cone_angle == pytest.approx(2 * g.alpha - cup, rel=1e-12)


@pytest.mark.parametrize("name", sorted(CATALOGUE))
@pytest.mark.parametrize("factor", ["e", "Y", "Y0"])
def test_trb_factors_match_catalogue_within_3_percent(name, factor):
    """Issue 14 item 4: e, Y, Y0 of eqs. (2.9), (2.13) at the cup angle vs the catalogue."""
    g = build(f"bearing={name}")
    f = load_factors(g.ratings_alpha)
    assert f[factor] == pytest.approx(CATALOGUE[name][factor], rel=0.03)


def test_trb_32208_cup_angle_is_table_4_2_catalogue_angle():
    """The 32208's cup angle is Table 4.2's 14 deg (Schaeffler's contact angle), to the 3 printed decimals
    of the configured roller-axis angle (12.013 deg: 0.0005 deg rounding moves the cup angle by < 0.001 deg)."""
    g = build("bearing=trb_32208")
    assert g.ratings_alpha == pytest.approx(14.0, abs=1e-3)
    # and the catalogue e = 0.37 implies 13.86 deg: the 0.14 deg between them is the rounding of e
    assert math.degrees(math.atan(0.37 / 1.5)) == pytest.approx(14.0, abs=0.15)


def test_factors_at_the_old_angles_missed_the_catalogue():
    """Why the change: the roller-axis angles put e 17-18 % off the catalogue (issue 14)."""
    assert load_factors(24.5)["e"] / 0.83 - 1 < -0.15          # TRB 31313 rated at alpha
    assert load_factors(14.0 + 2.3089)["e"] / 0.37 - 1 > 0.15  # TRB 32208 with a cup at 16.3 deg


def test_trb_31313_dynamic_rating_matches_catalogue():
    """Table 7.3: C = 163 kN (Schaeffler 31313-A). Eq. (2.14) at the cup angle with Table 7.3's roller
    (Dwe 18.0, Lwe 24.2, Z 13) and b_m 1.10: 159.8 kN, -2.0 %. Tolerance 3 %: Table 7.3's roller
    dimensions are rounded to 0.1 mm and C ~ Dwe^(29/27) Lwe^(7/9), and the catalogue rounds to 1 kN;
    at the roller-axis angle 24.5 deg the formula gives 164.7 kN (the rating is insensitive to the
    angle: cos^(7/9) and f_c(gamma) partly cancel)."""
    g = build("bearing=trb_31313")
    C = dynamic_load_rating(g.Dwe, g.Dpw, g.Lwe, g.Z, g.ratings_alpha, g.b_m)
    assert C == pytest.approx(163000.0, rel=0.03)


def test_trb_32208_ratings_against_table_6_2_and_catalogues():
    """Table 6.2: ISO 281 "Calculated" C0 104 kN, C 86 kN at 13.55 deg; catalogue C0 93, C 79 kN.

    At the cup angle 14.0 deg: C0 = 103.4 kN, C = 85.6 kN. The calculated values move by the
    cos(alpha) factors only (-0.5 %, -0.2 %), so Table 6.2's "Calculated" column still applies
    within 1 %. Against the catalogue the formula stays 8-11 % high, as the thesis says of its own
    calculation ("slightly higher than those experimentally obtained by the SCHAEFFLER company"):
    the thesis's roller dimensions (Dwe 10, Lwe 17, Z 17) are its own estimates. Timken's 32208
    (C1 105 kN, C0 98 kN) shows the spread between manufacturers: C sits between the two catalogues.
    """
    g = build("bearing=trb_32208")
    C0 = static_load_rating(g.Dwe, g.Dpw, g.Lwe, g.Z, g.ratings_alpha)
    C = dynamic_load_rating(g.Dwe, g.Dpw, g.Lwe, g.Z, g.ratings_alpha, g.b_m)
    # 1 %: the cos(alpha) change 13.55 -> 14 deg (0.2-0.5 %) plus Table 6.2's rounding to 1 kN (0.5-0.6 %)
    assert C0 == pytest.approx(104000.0, rel=0.01)
    assert C == pytest.approx(86000.0, rel=0.01)
    # the thesis's "slightly higher" than the Schaeffler catalogue: above it, by less than 12 %
    assert 0.0 < C0 / 93000.0 - 1.0 < 0.12
    assert 0.0 < C / 79000.0 - 1.0 < 0.12
    assert 79000.0 < C < 105000.0   # between Schaeffler and Timken


def test_table_6_2_prototype_unchanged():
    """The TSRB keeps the thesis's practice (Table 6.2 rates the prototype at alpha = 33 deg: e 0.97)."""
    g = build("bearing=tsrb_prototype")
    assert g.ratings_alpha == 33.0
    assert load_factors(g.ratings_alpha)["e"] == pytest.approx(0.97, abs=0.005)   # half the last printed digit


def test_closed_form_factor_products():
    """eqs. (2.9), (2.13): e * Y = 0.6 and Y0 / Y = 0.55 at every angle, so one catalogue factor fixes the
    others; the catalogues obey this within their rounding (0.37 * 1.60 = 0.592, 0.83 * 0.73 = 0.606)."""
    for a in np.linspace(5.0, 40.0, 8):
        f = load_factors(a)
        assert f["e"] * f["Y"] == pytest.approx(0.6, rel=1e-12)
        assert f["Y0"] / f["Y"] == pytest.approx(0.55, rel=1e-12)
    for c in CATALOGUE.values():
        assert c["e"] * c["Y"] == pytest.approx(0.6, rel=0.02)   # 2 printed digits: up to 1.4 % each


def test_trb_refuses_a_typed_rating_angle():
    """The cup angle is derived; a TRB config that types ratings_alpha is refused, naming the key."""
    with pytest.raises(ConfigError, match="ratings_alpha"):
        validate(sim.load_config(["bearing=trb_32208", "bearing.ratings_alpha=14"]))
    cfg = sim.load_config(["bearing=trb_32208"])
    bearing = dict(cfg.bearing)
    bearing["ratings_alpha"] = 14.0
    with pytest.raises(GeometryError, match="ratings_alpha"):
        Geometry.from_config(bearing, cfg.material, cfg.solver.n_slices)
