"""ISO 281 load ratings, equivalent loads and basic rating life of radial roller bearings.

Closed-form relations of the thesis, section 2.1.4 (eqs. 2.8-2.15), which restate
ISO 76 / ISO 281:2007 (DIN ISO 281 [DIN10a]) for radial roller bearings with one row
of rollers. Plain numpy; no numba, because nothing here is a hot loop.

Conventions
-----------
* Lengths in [mm], forces in [N], lives in [10^6 rev]. The ISO constants (44 in
  eq. 2.10, 207.9 in f_c) are dimensional, so C0 and C come out in [N] only if the
  geometry is given in [mm].
* Angles are in degrees at this interface (``alpha_deg``, the nominal contact angle).
* Loads ``Fr``, ``Fa`` (and ``P`` in :func:`basic_rating_life`) may be floats or numpy
  arrays (broadcast against each other). Scalar inputs give Python floats, array inputs
  give arrays. The geometry arguments broadcast the same way.
* Bad input raises ``ValueError`` naming the parameter, the offending value and the
  allowed range.

Notes on the thesis (Table 6.2, ``load_ratings`` in ``thesis_data.yaml``)
-------------------------------------------------------------------------
* Eq. (2.12) is printed with its two branches swapped; :func:`equivalent_dynamic_load`
  implements ISO 281 (see there).
* For the TRB 32208, Table 6.2's e = 0.37, Y = 1.60, Y0 = 0.88 are catalogue values;
  eqs. (2.9)/(2.13) at alpha = 13.55 deg give e = 0.36, Y = 1.66, Y0 = 0.91 (the
  catalogue values correspond to alpha of about 14 deg).
* The functions take the nominal contact angle as given. For a tapered roller bearing ISO 281
  (with ISO 355) means the cup (outer raceway) angle; :class:`sim.geometry.Geometry` passes
  ``ratings_alpha`` = alpha + gamma for a TRB (alpha = roller-axis angle of eq. 2.1) and the
  configured angle for a TSRB (thesis Table 6.2 practice). The catalogue checks are in
  tests/published/test_catalogue_ratings.py.
* For the prototype, C0 = 93.5 kN and C = 72.8 kN of Table 6.2 are not reproduced at
  alpha = 33 deg (92.6 kN, 72.1 kN; -1.0 %), but are reproduced to the printed digits at
  alpha = 32 deg (93.48 kN, 72.84 kN, with f_c = 86.59 ~ printed 86.61), while its
  e, Y, Y0 do match alpha = 33 deg. This is an observation, not a documented fact.
"""
from __future__ import annotations

import numpy as np

__all__ = [
    "static_load_rating",
    "rating_factor_fc",
    "dynamic_load_rating",
    "load_factors",
    "equivalent_static_load",
    "equivalent_dynamic_load",
    "basic_rating_life",
    "static_safety_from_pressure",
]

#: lambda * nu of ISO 281:2007 Table 7 footnote (ISO/TR 1281-1) for radial roller bearings.
LAMBDA_NU = 0.83
#: MPa, the contact stress that defines C0 of every roller bearing (ISO 76: the calculated contact stress at
#: the centre of the most heavily loaded roller / raceway contact under the static load C0; 4200 MPa for
#: self-aligning and 4600 MPa for other ball bearings).
ISO76_ROLLER_CONTACT_STRESS = 4000.0


# --------------------------------------------------------------------------- helpers
def _out(x):
    """Python float for 0-d results, ndarray otherwise."""
    x = np.asarray(x, dtype=float)
    return float(x) if x.ndim == 0 else x


def _require(name, value, ok, allowed):
    """Raise ValueError naming ``name``, the (first) offending value and ``allowed``."""
    ok = np.asarray(ok, dtype=bool)
    if ok.all():
        return
    v = np.broadcast_to(np.asarray(value, dtype=float), ok.shape)
    if v.ndim == 0:
        shown = repr(float(v))
    else:
        idx = tuple(int(k) for k in np.argwhere(~ok)[0])
        shown = f"{float(v[idx])!r} (first offending element, index {idx})"
    raise ValueError(f"{name} = {shown} is outside the allowed range {allowed}")


def _positive(name, value):
    v = np.asarray(value, dtype=float)
    with np.errstate(invalid="ignore"):
        _require(name, v, np.isfinite(v) & (v > 0.0), "(0, inf)")
    return v


def _alpha(alpha_deg, *, allow_zero=True):
    a = np.asarray(alpha_deg, dtype=float)
    lo_ok = (a >= 0.0) if allow_zero else (a > 0.0)
    with np.errstate(invalid="ignore"):
        _require("alpha_deg", a, np.isfinite(a) & lo_ok & (a < 90.0),
                 "[0, 90) deg" if allow_zero else
                 "(0, 90) deg (the X/Y factors of eqs. 2.9/2.13 contain cot(alpha))")
    return a


def _load(name, value):
    v = np.asarray(value, dtype=float)
    with np.errstate(invalid="ignore"):
        _require(name, v, np.isfinite(v) & (v >= 0.0), "[0, inf) N")
    return v


def _gamma(Dwe, Dpw, alpha_deg):
    """Validated geometry -> (Dwe, cos(alpha), gamma = Dwe cos(alpha) / Dpw)."""
    Dwe = _positive("Dwe", Dwe)
    Dpw = _positive("Dpw", Dpw)
    a = _alpha(alpha_deg)
    cos_a = np.cos(np.radians(a))
    g = Dwe * cos_a / Dpw
    _require("Dwe*cos(alpha)/Dpw", g, g < 1.0, "(0, 1)")
    return Dwe, cos_a, g


# --------------------------------------------------------------------------- ratings
def static_load_rating(Dwe, Dpw, Lwe, Z, alpha_deg, i=1):
    r"""Basic static load rating C0 of a radial roller bearing, eq. (2.10).

    .. math:: C_0 = 44 \left(1 - \frac{D_{we}\cos\alpha}{D_{pw}}\right)
              i Z L_{we} D_{we} \cos\alpha

    (ISO 76; Hertzian pressure 4000 N/mm^2 at the most heavily loaded contact.)

    Parameters
    ----------
    Dwe : float or array_like
        Roller diameter [mm], > 0.
    Dpw : float or array_like
        Pitch diameter [mm], > 0.
    Lwe : float or array_like
        Effective roller length [mm], > 0.
    Z : float or array_like
        Number of rollers per row [-], > 0.
    alpha_deg : float or array_like
        Nominal contact angle [deg], in [0, 90).
    i : float or array_like, optional
        Number of roller rows [-], > 0. Default 1.

    Returns
    -------
    float or ndarray
        C0 [N] (for geometry in mm).

    Raises
    ------
    ValueError
        If a parameter is out of range or Dwe cos(alpha)/Dpw >= 1.
    """
    Dwe, cos_a, g = _gamma(Dwe, Dpw, alpha_deg)
    Lwe = _positive("Lwe", Lwe)
    Z = _positive("Z", Z)
    i = _positive("i", i)
    return _out(44.0 * (1.0 - g) * i * Z * Lwe * Dwe * cos_a)


def _fc_of_gamma(g):
    """ISO 281 Table 7 footnote formula for f_c as a function of gamma (no checks)."""
    q = ((1.0 - g) / (1.0 + g)) ** (143.0 / 108.0)
    return (207.9 * LAMBDA_NU * g ** (2.0 / 9.0) * (1.0 - g) ** (29.0 / 27.0)
            / (1.0 + g) ** 0.25 * (1.0 + (1.04 * q) ** 4.5) ** (-2.0 / 9.0))


def rating_factor_fc(Dwe, Dpw, alpha_deg):
    r"""Geometry factor f_c of the dynamic load rating of radial roller bearings.

    ISO 281:2007 clause 7.1, Table 7 footnote (from ISO/TR 1281-1), used in eq. (2.14):

    .. math:: f_c = 207.9\,\lambda\nu\,\frac{\gamma^{2/9}(1-\gamma)^{29/27}}{(1+\gamma)^{1/4}}
              \left[1 + \left(1.04\left(\frac{1-\gamma}{1+\gamma}\right)^{143/108}
              \right)^{9/2}\right]^{-2/9},
              \qquad \gamma = \frac{D_{we}\cos\alpha}{D_{pw}},\quad \lambda\nu = 0.83

    Parameters
    ----------
    Dwe : float or array_like
        Roller diameter [mm], > 0.
    Dpw : float or array_like
        Pitch diameter [mm], > 0.
    alpha_deg : float or array_like
        Nominal contact angle [deg], in [0, 90).

    Returns
    -------
    float or ndarray
        f_c [N/mm^(50/27)] -- dimensional, so that C of eq. (2.14) is in [N] for
        lengths in [mm].

    Raises
    ------
    ValueError
        If a parameter is out of range or gamma = Dwe cos(alpha)/Dpw >= 1.

    Notes
    -----
    The formula is evaluated as is for every 0 < gamma < 1 (ISO 281 tabulates it for a
    limited gamma range only; no interpolation in the table is done here).

    Comparison with Table 6.2 (``load_ratings`` in ``thesis_data.yaml``):

    * TRB 32208 (Dwe 10, Dpw 60, alpha 13.55 deg): gamma = 0.16203, f_c = 88.586.
      Table 6.2 prints 88.54, which is this formula at gamma = 0.16 exactly (88.535,
      rounding to 88.54), i.e. the thesis apparently rounded gamma to two decimals (the
      ISO Table 7 step). Difference 0.05 %, irrelevant for C at its printed 2 digits
      (86 kN).
    * Prototype (Dwe 8.4, Dpw 58, alpha 33 deg): gamma = 0.12146, f_c = 86.478 vs. the
      printed 86.61 (-0.15 %). Neither gamma rounding (0.12 -> 86.35) nor interpolation
      in Table 7 gives 86.61; the formula reaches 86.61 at gamma = 0.1231, close to
      gamma = 0.1228 of alpha = 32 deg (f_c = 86.59), see the module notes.
    """
    _, _, g = _gamma(Dwe, Dpw, alpha_deg)
    return _out(_fc_of_gamma(g))


def dynamic_load_rating(Dwe, Dpw, Lwe, Z, alpha_deg, b_m, i=1, f_c=None):
    r"""Basic dynamic load rating C of a radial roller bearing, eq. (2.14).

    .. math:: C = b_m f_c (i L_{we} \cos\alpha)^{7/9} Z^{3/4} D_{we}^{29/27}

    Parameters
    ----------
    Dwe : float or array_like
        Roller diameter [mm], > 0.
    Dpw : float or array_like
        Pitch diameter [mm], > 0.
    Lwe : float or array_like
        Effective roller length [mm], > 0.
    Z : float or array_like
        Number of rollers per row [-], > 0.
    alpha_deg : float or array_like
        Nominal contact angle [deg], in [0, 90).
    b_m : float or array_like
        Rating factor for contemporary material and manufacturing quality [-], > 0
        (ISO 281 Table 1; Table 6.2 uses 1.10 for the TRB and 1.13 for the prototype).
    i : float or array_like, optional
        Number of roller rows [-], > 0. Default 1.
    f_c : float or array_like, optional
        Geometry factor [N/mm^(50/27)], > 0. ``None`` (default) computes it with
        :func:`rating_factor_fc`.

    Returns
    -------
    float or ndarray
        C [N] (for geometry in mm).

    Raises
    ------
    ValueError
        If a parameter is out of range or Dwe cos(alpha)/Dpw >= 1.
    """
    Dwe, cos_a, g = _gamma(Dwe, Dpw, alpha_deg)
    Lwe = _positive("Lwe", Lwe)
    Z = _positive("Z", Z)
    i = _positive("i", i)
    b_m = _positive("b_m", b_m)
    fc = _fc_of_gamma(g) if f_c is None else _positive("f_c", f_c)
    return _out(b_m * fc * (i * Lwe * cos_a) ** (7.0 / 9.0) * Z ** 0.75
                * Dwe ** (29.0 / 27.0))


# --------------------------------------------------------------------------- loads
def load_factors(alpha_deg):
    r"""Radial/axial load factors of single-row radial roller bearings, eqs. (2.9), (2.13).

    .. math:: X_0 = 0.5,\quad Y_0 = 0.22\cot\alpha, \qquad
              e = 1.5\tan\alpha,\quad X = 0.4,\quad Y = 0.4\cot\alpha

    Parameters
    ----------
    alpha_deg : float or array_like
        Nominal contact angle [deg], in (0, 90). alpha = 0 is rejected: the factors
        contain cot(alpha), and ISO 281 gives no X/Y for alpha = 0 roller bearings.

    Returns
    -------
    dict
        ``{"X0", "Y0", "e", "X", "Y"}`` [-], floats for scalar ``alpha_deg`` (arrays of
        its shape otherwise).

    Raises
    ------
    ValueError
        If ``alpha_deg`` is outside (0, 90).

    Notes
    -----
    These are the ISO formula values. Bearing catalogues print rounded/manufacturer
    values: for the TRB 32208 Table 6.2 lists e = 0.37, Y = 1.60, Y0 = 0.88, whereas
    the formulas at alpha = 13.55 deg give 0.3615, 1.660, 0.913.
    """
    a = _alpha(alpha_deg, allow_zero=False)
    t = np.tan(np.radians(a))
    one = np.ones_like(t)
    return {
        "X0": _out(0.5 * one),
        "Y0": _out(0.22 / t),
        "e": _out(1.5 * t),
        "X": _out(0.4 * one),
        "Y": _out(0.4 / t),
    }


def equivalent_static_load(Fr, Fa, alpha_deg):
    r"""Equivalent static load P0, eq. (2.8) with the factors of eq. (2.9).

    .. math:: P_0 = \max(X_0 F_r + Y_0 F_a,\; F_r)

    Parameters
    ----------
    Fr : float or array_like
        Radial load [N], >= 0.
    Fa : float or array_like
        Axial load [N], >= 0 (broadcast against ``Fr``).
    alpha_deg : float
        Nominal contact angle [deg], in (0, 90).

    Returns
    -------
    float or ndarray
        P0 [N].

    Raises
    ------
    ValueError
        If a load is negative or not finite, or ``alpha_deg`` is outside (0, 90).
    """
    Fr = _load("Fr", Fr)
    Fa = _load("Fa", Fa)
    f = load_factors(alpha_deg)
    return _out(np.maximum(f["X0"] * Fr + f["Y0"] * Fa, Fr))


def equivalent_dynamic_load(Fr, Fa, alpha_deg):
    r"""Equivalent dynamic load P per ISO 281, eq. (2.12) with the factors of eq. (2.13).

    .. math::
        P = \begin{cases} F_r & F_a/F_r \le e \\
                          X F_r + Y F_a & F_a/F_r > e \end{cases}

    A pure axial load (Fr = 0, Fa > 0) counts as Fa/Fr > e; Fr = Fa = 0 gives P = 0.

    Parameters
    ----------
    Fr : float or array_like
        Radial load [N], >= 0.
    Fa : float or array_like
        Axial load [N], >= 0 (broadcast against ``Fr``).
    alpha_deg : float
        Nominal contact angle [deg], in (0, 90).

    Returns
    -------
    float or ndarray
        P [N].

    Raises
    ------
    ValueError
        If a load is negative or not finite, or ``alpha_deg`` is outside (0, 90).

    Notes
    -----
    The thesis prints eq. (2.12) with the branches swapped (P = X Fr + Y Fa for
    Fa/Fr <= e, P = Fr for Fa/Fr > e). That version is a typo: it would give P < Fr for
    small axial loads, ignore Fa completely for large ones and give P = 0 under pure
    axial load. ISO 281 (implemented here) is as above. With X = 0.4, Y = 0.4 cot(alpha),
    e = 1.5 tan(alpha) both branches equal Fr at Fa/Fr = e, so P is continuous and the
    side on which the boundary is put does not matter.
    """
    Fr = _load("Fr", Fr)
    Fa = _load("Fa", Fa)
    f = load_factors(alpha_deg)
    # Fa > e*Fr  <=>  Fa/Fr > e for Fr > 0, and makes pure axial load (Fr = 0 < Fa) axial.
    axial = Fa > f["e"] * Fr
    return _out(np.where(axial, f["X"] * Fr + f["Y"] * Fa, Fr))


# --------------------------------------------------------------------------- life
def basic_rating_life(C, P, p=10.0 / 3.0):
    r"""Basic rating life L10, eq. (2.15).

    .. math:: L_{10} = (C/P)^p

    Parameters
    ----------
    C : float or array_like
        Basic dynamic load rating [N], > 0.
    P : float or array_like
        Equivalent dynamic load [N], >= 0; P = 0 gives an infinite life.
    p : float, optional
        Life exponent [-], > 0: 10/3 for roller bearings (default), 3 for ball bearings.

    Returns
    -------
    float or ndarray
        L10 [10^6 rev].

    Raises
    ------
    ValueError
        If C <= 0, P < 0, p <= 0 or a value is not finite (P = inf is accepted, L10 = 0).
    """
    C = _positive("C", C)
    P = np.asarray(P, dtype=float)
    with np.errstate(invalid="ignore"):
        _require("P", P, ~np.isnan(P) & (P >= 0.0), "[0, inf] N")
    p = _positive("p", p)
    with np.errstate(divide="ignore"):
        ratio = np.divide(C, P)
    return _out(ratio ** p)


def static_safety_from_pressure(pmax):
    r"""Static safety factor s0 = C0 / P0 of a solved case from its largest contact pressure.

    .. math:: s_0 = \left(\frac{4000\ \mathrm{MPa}}{p_{max}}\right)^2

    ISO 76 defines C0 of a roller bearing as the load that raises the most loaded contact to
    ISO76_ROLLER_CONTACT_STRESS at its centre, and eq. (2.10) estimates it for straight rollers
    in line contact along Lwe. A line contact's pressure grows as the square root of its load
    (Hertz, p0 = sqrt(q E* / (pi R)): the slice model's per-slice law), so to first order the load
    the bearing carries at 4000 MPa is P0 (4000 / pmax)^2 with pmax the pressure the load
    distribution gives at P0: s0 from the solved contact, without eq. (2.10)'s assumption of a
    contact along the whole roller (first order: the load distribution and a crowned contact's
    length change with the load, so the load at 4000 MPa found by solving differs from that
    estimate, by -2 % for the TRB 32208 and +8 % for tsrb_reference at eq. (2.10)'s limit). s0 < 1 is exactly pmax > 4000 MPa. It matches C0 / P0 where eq. (2.10)'s assumption
    holds (the TRBs, pure axial: the load at 4000 MPa within 1-6 % of eq. (2.10)'s,
    tests/published/test_static_capacity.py) and is 2.2-3.7 times lower for the TSRBs, whose
    crowned rollers touch each raceway in two short zones.

    Parameters
    ----------
    pmax : float or array_like
        Largest contact pressure of the case [MPa], > 0.

    Returns
    -------
    float or ndarray
        s0 [1].
    """
    pmax = _positive("pmax", pmax)
    return _out((ISO76_ROLLER_CONTACT_STRESS / pmax) ** 2)
