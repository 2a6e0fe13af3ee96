"""Closed-form checks of sim/ratings.py (ISO 281 load ratings and basic rating life).

Sources: thesis section 2.1.4, eqs. (2.8)-(2.15); ISO 281:2007 clause 7.1 (f_c formula,
Table 7 footnote); reference numbers of Table 6.2 (``load_ratings`` in
shared/reference/thesis_data.yaml), copied below so the tests do not read outside the repo.
"""
import math

import numpy as np
import pytest

from sim.physics.ratings import (
    basic_rating_life,
    dynamic_load_rating,
    equivalent_dynamic_load,
    equivalent_static_load,
    load_factors,
    rating_factor_fc,
    static_load_rating,
)

# Table 6.2 (thesis_data.yaml: load_ratings)
TRB = dict(alpha_deg=13.55, Dwe=10.0, Dpw=60.0, Lwe=17.0, Z=17)
TRB_BM, TRB_FC = 1.10, 88.54
PROTO = dict(alpha_deg=33.0, Dwe=8.4, Dpw=58.0, Lwe=20.0, Z=17)
PROTO_BM, PROTO_FC = 1.13, 86.61

# Half a unit of the last printed digit: the tolerance that "equal to the printed
# digits" allows for a value rounded to 2 decimals.
HALF_2DP = 0.005


def _geom(d):
    return dict(Dwe=d["Dwe"], Dpw=d["Dpw"], alpha_deg=d["alpha_deg"])


# --------------------------------------------------------------------------- TRB 32208
def test_trb_32208_static_load_rating():
    """Table 6.2, TRB 32208: C0 = 104 kN from eq. (2.10)."""
    c0 = static_load_rating(**TRB)
    # computed 103.59 kN; printed to 3 significant figures (104 kN) -> +-0.5 kN rounding
    assert c0 == pytest.approx(104_000.0, abs=500.0)


def test_trb_32208_dynamic_load_rating():
    """Table 6.2, TRB 32208: C = 86 kN from eq. (2.14) with ISO 281 f_c."""
    c = dynamic_load_rating(**TRB, b_m=TRB_BM)
    # computed 85.73 kN. "86 kN" is printed with 2 significant figures, so the rounding
    # interval is +-0.5 kN (0.58 %); at 3 significant figures it would read 85.7.
    assert c == pytest.approx(86_000.0, abs=500.0)
    # with the printed f_c = 88.54 instead of the formula value: 85.69 kN, same rounding
    c_printed_fc = dynamic_load_rating(**TRB, b_m=TRB_BM, f_c=TRB_FC)
    assert c_printed_fc == pytest.approx(86_000.0, abs=500.0)
    # f_c enters linearly
    assert c / c_printed_fc == pytest.approx(rating_factor_fc(**_geom(TRB)) / TRB_FC, rel=1e-12)


def test_trb_32208_rating_factor_fc():
    """Table 6.2, TRB 32208: f_c = 88.54 vs ISO 281 Table 7 footnote formula.

    The exact geometry gives gamma = 0.16203 and f_c = 88.586; the printed 88.54 is the
    formula at gamma rounded to 0.16 (88.535, the ISO Table 7 step).
    """
    fc = rating_factor_fc(**_geom(TRB))
    # 0.05 % gap from the thesis rounding gamma to two decimals (see docstring): 1e-3
    assert fc == pytest.approx(TRB_FC, rel=1e-3)
    # gamma = 0.16 exactly (Dwe = 9.6, Dpw = 60, alpha = 0) gives 88.5352, which rounds to
    # the printed 88.54: printed digits, +-0.005 (the margin is only 0.0002)
    assert rating_factor_fc(Dwe=9.6, Dpw=60.0, alpha_deg=0.0) == pytest.approx(
        TRB_FC, abs=HALF_2DP)


def test_trb_32208_load_factors():
    """Table 6.2, TRB 32208: X0 = 0.5, X = 0.4 (eqs. 2.9, 2.13); e, Y, Y0 see below.

    Table 6.2 prints e = 0.37, Y = 1.60, Y0 = 0.88 for the TRB: these are catalogue
    values, not eqs. (2.9)/(2.13) at alpha = 13.55 deg, which give 0.3615, 1.660, 0.913.
    The formula values are tested here.
    """
    f = load_factors(TRB["alpha_deg"])
    a = math.radians(TRB["alpha_deg"])
    # X0 and X are constants; printed digits
    assert f["X0"] == pytest.approx(0.5, abs=HALF_2DP)
    assert f["X"] == pytest.approx(0.4, abs=HALF_2DP)
    # formula values (eq. 2.13, 2.9) to floating-point accuracy
    assert f["e"] == pytest.approx(1.5 * math.tan(a), rel=1e-12)
    assert f["Y"] == pytest.approx(0.4 / math.tan(a), rel=1e-12)
    assert f["Y0"] == pytest.approx(0.22 / math.tan(a), rel=1e-12)
    # ... which round to 0.36 / 1.66 / 0.91, not the printed catalogue 0.37 / 1.60 / 0.88
    assert f["e"] == pytest.approx(0.36, abs=HALF_2DP)
    assert f["Y"] == pytest.approx(1.66, abs=HALF_2DP)
    assert f["Y0"] == pytest.approx(0.91, abs=HALF_2DP)


def test_trb_32208_catalogue_factors_match_alpha_14():
    """Observation: the catalogue e, Y, Y0 of Table 6.2 (0.37, 1.60, 0.88) are eqs. (2.9)/
    (2.13) at alpha = 14 deg (the angle section 2.1.4 quotes for the TRB 32208)."""
    f = load_factors(14.0)
    # printed digits, +-0.005
    assert f["e"] == pytest.approx(0.37, abs=HALF_2DP)
    assert f["Y"] == pytest.approx(1.60, abs=HALF_2DP)
    assert f["Y0"] == pytest.approx(0.88, abs=HALF_2DP)


# --------------------------------------------------------------------------- prototype
def test_prototype_load_factors():
    """Table 6.2, prototype (alpha = 33 deg): e = 0.97, Y = 0.62, Y0 = 0.34, X = 0.4, X0 = 0.5."""
    f = load_factors(PROTO["alpha_deg"])
    # printed digits, +-0.005
    assert f["e"] == pytest.approx(0.97, abs=HALF_2DP)
    assert f["Y"] == pytest.approx(0.62, abs=HALF_2DP)
    assert f["Y0"] == pytest.approx(0.34, abs=HALF_2DP)
    assert f["X"] == pytest.approx(0.4, abs=HALF_2DP)
    assert f["X0"] == pytest.approx(0.5, abs=HALF_2DP)


# The thesis's own printed factors do not reproduce its printed C: eq. (2.14) with
# f_c = 86.61 and b_m = 1.13 at alpha = 33 deg gives C = 72.23 kN, 0.78 % below the
# printed 72.8 kN; with the formula f_c = 86.48 it is 72.12 kN (-0.94 %), and C0 from
# eq. (2.10) is 92.59 kN vs 93.5 kN (-0.97 %). Rounding of the printed values explains
# at most 0.07 %. The tolerance is set to 1.5 %, above the ~1 % observed inconsistency
# of the source, and far below any real formula error (e.g. a wrong exponent).
PROTO_REL = 0.015


def test_prototype_static_load_rating():
    """Table 6.2, prototype: C0 = 93.5 kN, eq. (2.10) (see PROTO_REL for the tolerance)."""
    assert static_load_rating(**PROTO) == pytest.approx(93_500.0, rel=PROTO_REL)


def test_prototype_dynamic_load_rating():
    """Table 6.2, prototype: C = 72.8 kN, eq. (2.14) (see PROTO_REL for the tolerance)."""
    assert dynamic_load_rating(**PROTO, b_m=PROTO_BM) == pytest.approx(72_800.0, rel=PROTO_REL)
    c_printed_fc = dynamic_load_rating(**PROTO, b_m=PROTO_BM, f_c=PROTO_FC)
    # the inconsistency quoted above: 72.23 kN; 0.1 % tolerance only pins that number
    assert c_printed_fc == pytest.approx(72_229.0, rel=1e-3)
    assert c_printed_fc == pytest.approx(72_800.0, rel=PROTO_REL)


def test_prototype_fc_formula_vs_printed():
    """Table 6.2, prototype: f_c = 86.61 vs ISO 281 formula 86.48 (gamma = 0.1215)."""
    fc = rating_factor_fc(**_geom(PROTO))
    # the documented 0.15 % mismatch (see rating_factor_fc docstring); 0.3 % bounds it
    assert fc == pytest.approx(PROTO_FC, rel=3e-3)
    assert fc == pytest.approx(86.478, abs=HALF_2DP / 5)   # value documented in the docstring


def test_prototype_ratings_reproduced_at_alpha_32():
    """Observation (not stated in the thesis): Table 6.2's prototype C0 = 93.5 kN and
    C = 72.8 kN are reproduced at alpha = 32 deg, with f_c = 86.59 (printed 86.61)."""
    p32 = dict(PROTO, alpha_deg=32.0)
    # printed to 0.1 kN -> +-50 N rounding interval
    assert static_load_rating(**p32) == pytest.approx(93_500.0, abs=50.0)
    assert dynamic_load_rating(**p32, b_m=PROTO_BM) == pytest.approx(72_800.0, abs=50.0)
    # 0.03 %: f_c printed with 4 digits, gap 0.02
    assert rating_factor_fc(**_geom(p32)) == pytest.approx(PROTO_FC, rel=3e-4)


# --------------------------------------------------------------------------- equivalent loads
ALPHA = 33.0
F = load_factors(ALPHA)


def test_equivalent_static_load_branches():
    """Eq. (2.8): P0 = max(X0 Fr + Y0 Fa, Fr) with eq. (2.9) factors."""
    # exact arithmetic on the same float operations -> rel 1e-12
    assert equivalent_static_load(5000.0, 0.0, ALPHA) == pytest.approx(5000.0, rel=1e-12)
    assert equivalent_static_load(0.0, 4000.0, ALPHA) == pytest.approx(F["Y0"] * 4000.0, rel=1e-12)
    # small Fa: X0 Fr + Y0 Fa < Fr -> Fr governs
    assert 0.5 * 5000.0 + F["Y0"] * 1000.0 < 5000.0
    assert equivalent_static_load(5000.0, 1000.0, ALPHA) == pytest.approx(5000.0, rel=1e-12)
    # large Fa: combined term governs
    assert 0.5 * 2000.0 + F["Y0"] * 8000.0 > 2000.0
    assert equivalent_static_load(2000.0, 8000.0, ALPHA) == pytest.approx(
        0.5 * 2000.0 + F["Y0"] * 8000.0, rel=1e-12)
    assert equivalent_static_load(0.0, 0.0, ALPHA) == 0.0


def test_equivalent_dynamic_load_branches():
    """ISO 281 eq. (2.12) (thesis prints the branches swapped): P = Fr for Fa/Fr <= e,
    P = X Fr + Y Fa for Fa/Fr > e; pure axial counts as Fa/Fr > e."""
    e, X, Y = F["e"], F["X"], F["Y"]
    # exact arithmetic on the same float operations -> rel 1e-12
    assert equivalent_dynamic_load(5000.0, 0.0, ALPHA) == pytest.approx(5000.0, rel=1e-12)
    Fa_small = 0.5 * e * 5000.0                     # Fa/Fr = e/2 <= e -> P = Fr
    assert equivalent_dynamic_load(5000.0, Fa_small, ALPHA) == pytest.approx(5000.0, rel=1e-12)
    assert equivalent_dynamic_load(2000.0, 4000.0, ALPHA) == pytest.approx(
        X * 2000.0 + Y * 4000.0, rel=1e-12)
    assert 4000.0 / 2000.0 > e
    assert equivalent_dynamic_load(0.0, 4000.0, ALPHA) == pytest.approx(Y * 4000.0, rel=1e-12)
    assert equivalent_dynamic_load(0.0, 0.0, ALPHA) == 0.0


def test_equivalent_dynamic_load_continuous_at_e_and_not_below_fr():
    """ISO 281 (2.12)/(2.13): both branches equal Fr at Fa/Fr = e (X + Y e = 1), and P >= Fr
    everywhere -- which the thesis's swapped printing would violate."""
    Fr = 3000.0
    e = F["e"]
    below = equivalent_dynamic_load(Fr, e * Fr * (1 - 1e-9), ALPHA)
    above = equivalent_dynamic_load(Fr, e * Fr * (1 + 1e-9), ALPHA)
    # jump across the boundary is O(1e-9) relative, from the 1e-9 offsets only
    assert below == pytest.approx(Fr, rel=1e-8)
    assert above == pytest.approx(Fr, rel=1e-8)
    Fa = np.linspace(0.0, 10.0 * e * Fr, 201)
    P = equivalent_dynamic_load(Fr, Fa, ALPHA)
    # 1e-9 relative slack for floating-point round-off around the boundary
    assert np.all(P >= Fr * (1 - 1e-9))
    swapped = np.where(Fa / Fr <= e, F["X"] * Fr + F["Y"] * Fa, Fr)   # thesis as printed
    assert np.any(swapped < Fr * (1 - 1e-3))


def test_equivalent_loads_vectorised():
    """Array Fr/Fa broadcast and match the scalar evaluation element by element."""
    Fr = np.array([0.0, 1000.0, 4000.0, 8000.0])[:, None]
    Fa = np.array([0.0, 500.0, 3000.0, 4500.0])[None, :]
    for fun in (equivalent_static_load, equivalent_dynamic_load):
        out = fun(Fr, Fa, ALPHA)
        assert isinstance(out, np.ndarray) and out.shape == (4, 4)
        ref = [[fun(float(r), float(a), ALPHA) for a in Fa[0]] for r in Fr[:, 0]]
        # same operations elementwise -> identical up to round-off
        np.testing.assert_allclose(out, ref, rtol=1e-14, atol=0.0)
    assert isinstance(equivalent_dynamic_load(1000.0, 500.0, ALPHA), float)


# --------------------------------------------------------------------------- life
def test_basic_rating_life_closed_form():
    """Eq. (2.15): L10 = (C/P)^p, p = 10/3 for roller bearings; P = 0 -> inf."""
    C = 86_000.0
    # same closed form, round-off only -> rel 1e-12
    assert basic_rating_life(C, 8600.0) == pytest.approx(10.0 ** (10.0 / 3.0), rel=1e-12)
    assert basic_rating_life(C, C) == pytest.approx(1.0, rel=1e-12)
    assert basic_rating_life(C, 4300.0, p=3.0) == pytest.approx(8000.0, rel=1e-12)
    assert basic_rating_life(C, 0.0) == math.inf
    P = np.array([0.0, 4300.0, 8600.0, 86_000.0])
    L = basic_rating_life(C, P)
    assert np.isinf(L[0])
    np.testing.assert_allclose(L[1:], (C / P[1:]) ** (10.0 / 3.0), rtol=1e-12)


def test_life_chain_trb_32208():
    """Eqs. (2.12)-(2.15) chained for the TRB 32208 at Fr = 8 kN, Fa = 5 kN (Table 6.3 maxima)."""
    C = dynamic_load_rating(**TRB, b_m=TRB_BM)
    f = load_factors(TRB["alpha_deg"])
    P_ref = f["X"] * 8000.0 + f["Y"] * 5000.0          # Fa/Fr = 0.625 > e = 0.36
    P = equivalent_dynamic_load(8000.0, 5000.0, TRB["alpha_deg"])
    # round-off only -> rel 1e-12
    assert P == pytest.approx(P_ref, rel=1e-12)
    assert basic_rating_life(C, P) == pytest.approx((C / P_ref) ** (10.0 / 3.0), rel=1e-12)


# --------------------------------------------------------------------------- bad input
BASE = dict(Dwe=10.0, Dpw=60.0, Lwe=17.0, Z=17, alpha_deg=13.55)


@pytest.mark.parametrize(
    "fun, kwargs, name, allowed",
    [
        (static_load_rating, dict(BASE, alpha_deg=90.0), "alpha_deg", "[0, 90)"),
        (static_load_rating, dict(BASE, alpha_deg=-1.0), "alpha_deg", "[0, 90)"),
        (static_load_rating, dict(BASE, Dwe=0.0), "Dwe", "(0, inf)"),
        (static_load_rating, dict(BASE, Dpw=-60.0), "Dpw", "(0, inf)"),
        (static_load_rating, dict(BASE, Lwe=0.0), "Lwe", "(0, inf)"),
        (static_load_rating, dict(BASE, Z=0), "Z", "(0, inf)"),
        (static_load_rating, dict(BASE, i=0), "i", "(0, inf)"),
        (static_load_rating, dict(BASE, Dwe=70.0), "Dwe*cos(alpha)/Dpw", "(0, 1)"),
        (dynamic_load_rating, dict(BASE, b_m=0.0), "b_m", "(0, inf)"),
        (dynamic_load_rating, dict(BASE, b_m=1.1, f_c=-1.0), "f_c", "(0, inf)"),
        (dynamic_load_rating, dict(BASE, b_m=1.1, Dwe=float("nan")), "Dwe", "(0, inf)"),
        (rating_factor_fc, dict(Dwe=10.0, Dpw=10.0, alpha_deg=0.0), "Dwe*cos(alpha)/Dpw", "(0, 1)"),
        (load_factors, dict(alpha_deg=0.0), "alpha_deg", "(0, 90)"),
        (load_factors, dict(alpha_deg=95.0), "alpha_deg", "(0, 90)"),
        (equivalent_static_load, dict(Fr=-1.0, Fa=0.0, alpha_deg=33.0), "Fr", "[0, inf)"),
        (equivalent_dynamic_load, dict(Fr=1.0, Fa=np.array([1.0, -2.0]), alpha_deg=33.0),
         "Fa", "[0, inf)"),
        (basic_rating_life, dict(C=0.0, P=1.0), "C", "(0, inf)"),
        (basic_rating_life, dict(C=1.0, P=-1.0), "P", "[0, inf]"),
        (basic_rating_life, dict(C=1.0, P=1.0, p=0.0), "p", "(0, inf)"),
    ],
)
def test_bad_input_raises_value_error_naming_parameter(fun, kwargs, name, allowed):
    """Bad input: ValueError with parameter name, offending value and allowed range."""
    with pytest.raises(ValueError) as exc:
        fun(**kwargs)
    msg = str(exc.value)
    assert msg.startswith(f"{name} = ")
    assert allowed in msg


def test_bad_input_message_shows_value():
    """The message carries the offending value (first offending element for arrays)."""
    with pytest.raises(ValueError, match=r"alpha_deg = 91\.5 is outside the allowed range"):
        static_load_rating(**dict(BASE, alpha_deg=91.5))
    with pytest.raises(ValueError, match=r"Fa = -2\.0 \(first offending element, index \(1,\)\)"):
        equivalent_dynamic_load(1.0, np.array([1.0, -2.0, -3.0]), 33.0)
