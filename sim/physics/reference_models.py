"""Published whole-bearing friction torque models of tapered roller bearings (references, not the model).

Independent references for the torque of ``sim.physics.friction`` (issue 14 items 3 and 8). Plain numpy,
SI-free engineering units as each source states them. Nothing here is fitted to this project.

Sources and how far each form could be verified (``search`` tool, November 2026):

* **SKF 2004 model** (SKF General Catalogue 6000 EN, 2008, "The SKF model for calculating the
  frictional moment"; the model restated in Manjunath et al., Machines 11 (2023) 801, Table 1
  and eqs. 16-17, whose text could not be retrieved). Verified on a copy of the catalogue page
  (yumpu.com, "SKF - Rolling Bearings", pp. 104-105): Grr and Gsl of tapered roller bearings
  (Table 2a), M_sl = G_sl mu_sl, mu_sl = phi_bl mu_bl + (1 - phi_bl) mu_EHL, phi_bl =
  exp(-2.6e-8 (n nu)^1.4 d_m), mu_bl ~ 0.15, mu_EHL = 0.002 for tapered roller bearings.
  NOT found on a catalogue page, taken from a public transcription of the SKF tables (a GitHub
  repository found by code search, file ``constants.py``/``equations.py`` of an SKF-friction
  package; its deep-groove ball constants agree with a second, independent transcription):
  M_rr = phi_ish phi_rs G_rr (nu n)^0.6, phi_ish = 1/(1 + 1.84e-9 (n d_m)^1.28 nu^0.64),
  phi_rs = exp(-K_rs nu n (d + D) sqrt(K_z/(2 (D - d)))), and the tapered series constants
  (:data:`SKF_TAPERED_CONSTANTS`). Seal and drag moments are not included.
* **Aihara 1987** (S. Aihara, "A new running torque formula for tapered roller bearings under
  axial load", ASME J. Tribol. 109 (1987) 471-478). Only the abstract could be retrieved; the
  form implemented is the transcription in ``shared/reference/friction_literature.md``
  (project reference file) and is NOT verified against the paper. The symbols e (rib contact
  height), beta and Lambda_r of the rib term are not defined there: they are inputs.
* **Timken** (catalogue running-torque formula with the heat generation factors G1, G2 and the
  factor K of the Timken product pages): the formula itself was not found (the catalogue PDFs
  are stored only by their first pages), so it is not implemented. Timken's 32208 product page
  gives G1 = 27.3, G2 = 15.1, K = 1.56, C1 = 105 kN, C0 = 98 kN (cad.timken.com, X32208M).
"""
from __future__ import annotations

import math

import numpy as np

__all__ = [
    "SKF_TAPERED_CONSTANTS",
    "skf_2004_trb",
    "aihara_rolling_moment",
    "aihara_1987_trb",
    "torque_exponent",
]

#: SKF geometry constants of tapered roller bearings (R1, R2, S1, S2, K_z) by bearing series,
#: SKF General Catalogue 6000 EN (2008) table "geometry constants for rolling and sliding
#: frictional moments"; from the public transcription named in the module docstring (not checked
#: against the printed page). Only the series this project uses are copied.
SKF_TAPERED_CONSTANTS = {
    "322": {"R1": 2.27e-6, "R2": 10.9, "S1": 0.018, "S2": 2.0, "K_z": 6.0},   # TRB 32208
    "313": {"R1": 1.84e-6, "R2": 10.9, "S1": 0.048, "S2": 2.0, "K_z": 6.0},   # TRB 31313
}


def _positive(name, value):
    v = float(value)
    if not (math.isfinite(v) and v > 0.0):
        raise ValueError(f"{name} = {value!r} is outside the allowed range (0, inf)")
    return v


def _non_negative(name, value):
    v = float(value)
    if not (math.isfinite(v) and v >= 0.0):
        raise ValueError(f"{name} = {value!r} is outside the allowed range [0, inf)")
    return v


def skf_2004_trb(Fr, Fa, n, nu, d, D, Y, R1, R2, S1, S2, K_z=6.0, K_rs=0.0, mu_bl=0.15, mu_EHL=0.002):
    r"""Frictional moment of a single-row tapered roller bearing, SKF model (rolling + sliding).

    .. math::
        G_{rr} = R_1 d_m^{2.38} (F_r + R_2 Y F_a)^{0.31}, \quad
        G_{sl} = S_1 d_m^{0.82} (F_r + S_2 Y F_a)

        M_{rr} = \phi_{ish}\,\phi_{rs}\,G_{rr}\,(\nu n)^{0.6}, \quad
        \phi_{ish} = \frac{1}{1 + 1.84\cdot 10^{-9} (n d_m)^{1.28} \nu^{0.64}}, \quad
        \phi_{rs} = e^{-K_{rs}\,\nu n (d + D) \sqrt{K_z / (2 (D - d))}}

        M_{sl} = G_{sl}\,\mu_{sl}, \quad \mu_{sl} = \phi_{bl}\mu_{bl} + (1 - \phi_{bl})\mu_{EHL},
        \quad \phi_{bl} = e^{-2.6\cdot 10^{-8} (n \nu)^{1.4} d_m}

    with d_m = (d + D)/2 (SKF General Catalogue 6000 EN 2008; see the module docstring for
    which parts were verified on a catalogue page).

    Parameters
    ----------
    Fr, Fa : float
        Radial and axial load [N], >= 0.
    n : float
        Rotational speed [r/min], > 0.
    nu : float
        Kinematic viscosity at the operating temperature [mm^2/s], > 0.
    d, D : float
        Bore and outside diameter [mm], D > d > 0.
    Y : float
        Axial load factor of the bearing (catalogue product table) [-], > 0.
    R1, R2, S1, S2 : float
        SKF geometry constants of the bearing series (:data:`SKF_TAPERED_CONSTANTS`).
    K_z : float, optional
        Bearing type geometry constant of phi_rs (6 for tapered roller bearings).
    K_rs : float, optional
        Replenishment/starvation constant [-]: 3e-8 low-level oil bath and oil jet, 6e-8 grease
        and oil-air (SKF); 0 (default) = fully flooded, phi_rs = 1.
    mu_bl : float, optional
        Boundary friction coefficient ("generally ~ 0.15", SKF).
    mu_EHL : float, optional
        Full-film sliding friction coefficient (0.002 for tapered roller bearings, SKF).

    Returns
    -------
    dict
        ``M_rr``, ``M_sl``, ``M`` [N mm] and ``G_rr``, ``G_sl``, ``phi_ish``, ``phi_rs``,
        ``phi_bl``, ``mu_sl`` [-].
    """
    Fr, Fa = _non_negative("Fr", Fr), _non_negative("Fa", Fa)
    n, nu = _positive("n", n), _positive("nu", nu)
    d, D = _positive("d", d), _positive("D", D)
    if not D > d:
        raise ValueError(f"D = {D!r} must exceed d = {d!r}")
    Y = _positive("Y", Y)
    dm = 0.5 * (d + D)
    G_rr = R1 * dm ** 2.38 * (Fr + R2 * Y * Fa) ** 0.31
    G_sl = S1 * dm ** 0.82 * (Fr + S2 * Y * Fa)
    phi_ish = 1.0 / (1.0 + 1.84e-9 * (n * dm) ** 1.28 * nu ** 0.64)
    phi_rs = math.exp(-K_rs * nu * n * (d + D) * math.sqrt(K_z / (2.0 * (D - d))))
    M_rr = phi_ish * phi_rs * G_rr * (nu * n) ** 0.6
    phi_bl = math.exp(-min(2.6e-8 * (n * nu) ** 1.4 * dm, 700.0))
    mu_sl = phi_bl * mu_bl + (1.0 - phi_bl) * mu_EHL
    M_sl = G_sl * mu_sl
    return {"M_rr": M_rr, "M_sl": M_sl, "M": M_rr + M_sl, "G_rr": G_rr, "G_sl": G_sl,
            "phi_ish": phi_ish, "phi_rs": phi_rs, "phi_bl": phi_bl, "mu_sl": mu_sl}


def aihara_rolling_moment(Fa, u, R_e, l, z, D_a, alpha_cup, eta0, alpha_p, E_prime, beta_T, k_oil):
    r"""EHL rolling-resistance moment of one raceway contact, Aihara (1987) as transcribed.

    .. math::
        M_{i,o} = \frac{176}{1 + 0.29 L^{0.78}} \frac{1}{\alpha_p} (G U)^{0.658} W^{0.31} R_e^2\,l,
        \quad G = \alpha_p E', \; U = \frac{\eta_0 u}{E' R_e}, \;
        W = \frac{2 F_a}{D_a\,l\,z \sin\alpha_{cup} E'}, \; L = \frac{\eta_0 \beta u^2}{k}

    (shared/reference/friction_literature.md; unverified against the paper, see the module
    docstring). SI units throughout.

    Parameters
    ----------
    Fa : float
        Axial bearing load [N], >= 0.
    u : float
        Rolling (entrainment) speed of the contact [m/s], > 0.
    R_e : float
        Equivalent radius of the contact in the rolling direction [m], > 0.
    l : float
        Effective roller length [m], > 0.
    z : int
        Number of rollers [-].
    D_a : float
        Mean roller diameter [m], > 0.
    alpha_cup : float
        Cup (outer raceway) contact angle [rad].
    eta0 : float
        Dynamic viscosity at the inlet [Pa s].
    alpha_p : float
        Pressure-viscosity coefficient [1/Pa].
    E_prime : float
        Reduced modulus [Pa] (E/(1 - nu^2) for two equal steels; both conventions of the
        literature coincide for equal materials).
    beta_T : float
        Temperature-viscosity coefficient -d ln(eta)/dT [1/K].
    k_oil : float
        Thermal conductivity of the oil [W/(m K)].

    Returns
    -------
    float
        Rolling-resistance moment of the contact [N m].
    """
    Fa = _non_negative("Fa", Fa)
    for name, v in (("u", u), ("R_e", R_e), ("l", l), ("z", z), ("D_a", D_a), ("eta0", eta0),
                    ("alpha_p", alpha_p), ("E_prime", E_prime), ("beta_T", beta_T), ("k_oil", k_oil)):
        _positive(name, v)
    G = alpha_p * E_prime
    U = eta0 * u / (E_prime * R_e)
    W = 2.0 * Fa / (D_a * l * z * math.sin(alpha_cup) * E_prime)
    L = eta0 * beta_T * u * u / k_oil
    return 176.0 / (1.0 + 0.29 * L ** 0.78) / alpha_p * (G * U) ** 0.658 * W ** 0.31 * R_e ** 2 * l


def aihara_1987_trb(Fa, z, D_a, R_o, R_i, M_i, M_o, e, cos_beta, Lambda_r, mu_0=0.2):
    r"""Running torque of a TRB under axial load, Aihara (1987) as transcribed.

    .. math::
        M = \frac{z}{D_a}(R_o M_i + R_i M_o) + e\,\mu_0 \cos\beta\,F_a\,e^{-1.8 \Lambda_r^{1.2}},
        \quad \mu_0 = 0.2

    (shared/reference/friction_literature.md; unverified against the paper). The rib term
    enters linearly in F_a at a given film parameter Lambda_r of the rib contact.

    Parameters
    ----------
    Fa : float
        Axial load [N].
    z : int
        Number of rollers.
    D_a : float
        Mean roller diameter [m].
    R_o, R_i : float
        Radii of the outer and inner raceway contacts from the bearing axis [m] (read here as
        the contact radii at mid-roller; the transcription does not define them).
    M_i, M_o : float
        Rolling-resistance moments of the inner and outer contact [N m]
        (:func:`aihara_rolling_moment`).
    e : float
        Rib contact height [m] (not defined further in the transcription: an input).
    cos_beta : float
        cos(beta) of the rib term [-] (beta not defined in the transcription: an input).
    Lambda_r : float
        Film parameter of the rib contact [-], >= 0.
    mu_0 : float, optional
        Boundary friction coefficient of the rib, 0.2 (Aihara, as transcribed).

    Returns
    -------
    dict
        ``rolling``, ``rib``, ``M`` [N m].
    """
    rolling = z / D_a * (R_o * M_i + R_i * M_o)
    rib = e * mu_0 * cos_beta * Fa * math.exp(-1.8 * _non_negative("Lambda_r", Lambda_r) ** 1.2)
    return {"rolling": rolling, "rib": rib, "M": rolling + rib}


def torque_exponent(F, M):
    """Least-squares exponent n of M ~ F^n (log-log slope) [-]."""
    F, M = np.asarray(F, dtype=float), np.asarray(M, dtype=float)
    return float(np.polyfit(np.log(F), np.log(M), 1)[0])
