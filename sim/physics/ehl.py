"""EHL film, mixed-friction load share and the local friction laws (MODEL.md 5; thesis 2.3, 5.4).

Kernel units: mm, N, MPa, s; viscosity in MPa s (= 1e6 Pa s); velocities in mm/s. The reduced
modulus of the EHL formulas is Hamrock's ``E' = 2 E*`` (E* of :func:`sim.physics.contact.contact_modulus`).

- Line-contact film per slice: central film of Pan & Hamrock (1989) or the minimum film of
  Dowson & Higginson (thesis eq. (2.26)); point contact (roller end / rib): central film of
  Hamrock & Dowson (1977).
- Solid load share Phi = exp(-B_ZH Lambda^C_ZH), thesis eq. (5.16), Lambda = h / sigma (2.27).
- Traction stress (5.17): tau = Phi tau_S + (1 - Phi) tau_L with the solid part Coulomb
  (mu_s p, regularised by tanh(|v| / v_s)) and the lubricant part visco-elastic (Maxwell:
  the viscosity at the local pressure, Barus or Roelands, in series with the shear modulus G
  over the transit time 2b/u, Johnson & Tevaarwerk 1977) up to a limiting shear stress tau_lim = tau_L0 + c p (Bair & Winer 1979),
  combined smoothly as tau_lim tanh(k |v| / tau_lim).
- Traction stress, non-Newtonian alternative (:func:`traction_eyring`, same return quantity as
  :func:`traction_per_speed`): Maxwell-Eyring film (Johnson & Tevaarwerk 1977), the strain rate
  the sum of an elastic part over the transit time and the Eyring viscous part,
  v/h = tau_M/(G t) + (tau_E0/eta) sinh(tau_M/tau_E0), smoothly bounded by the limiting shear
  stress tau = tau_L tanh(tau_M/tau_L).
- Rolling resistance of the lubricant: Goksem & Hargreaves (1978) isothermal hydrodynamic rolling
  force of a line contact, the Poiseuille shear force on EACH surface; the film dissipates 2 u F (Reynolds,
  derivation in :func:`rolling_force_hydrodynamic`), i.e. the resisting moment about the relative
  rolling axis is 2 F R (:func:`rolling_moment_hydrodynamic`); of the material: elastic hysteresis
  (Johnson 1985, 9.2).
- Inlet shear heating: thermal reduction factor of film and rolling force (Gupta, Cheng, Zhu,
  Forster & Schrand 1992), :func:`film_thermal_factor_gupta` with the thermal loading
  :func:`thermal_loading`.
- Shear heating of a contact (the thermal reduction of the traction, :mod:`sim.physics.friction`):
  mid-film temperature rise of Couette heating, and the mean flash temperature of the surfaces
  under a moving band heat source (Jaeger 1942, Blok 1937 partition).
"""
from collections import namedtuple

import numpy as np

from sim._math.jit import internal_kernel, kernel

FILM_PAN_HAMROCK = 0
FILM_DOWSON_HIGGINSON = 1
FILM_FORMULAS = {"pan_hamrock": FILM_PAN_HAMROCK, "dowson_higginson": FILM_DOWSON_HIGGINSON}
PV_BARUS = 0
PV_ROELANDS = 1
PRESSURE_VISCOSITY_MODELS = {"barus": PV_BARUS, "roelands": PV_ROELANDS}
#: Roelands (1966) constants: eta_inf = 6.31e-5 Pa s [MPa s] and p_R = 1/5.1e-9 Pa [MPa].
ROELANDS_ETA_INF = 6.31e-11
ROELANDS_P_R = 196.1

# Parameters of the traction laws (numba-supported named tuples; sim.api.friction_model.FrictionModel
# builds them once from the lubricant and friction config):
# FilmRheology: tau_E0, Eyring stress [MPa] (traction_eyring; unused by traction_per_speed); tau_L0,
# limiting shear stress at zero pressure [MPa], and c_tau, its pressure coefficient [1]
# (tau_L = tau_L0 + c_tau p, Bair & Winer 1979); G, elastic shear modulus of the film [MPa]
# (Maxwell part, Johnson & Tevaarwerk 1977).
FilmRheology = namedtuple("FilmRheology", ["tau_E0", "tau_L0", "c_tau", "G"])
# SolidFriction: mu_s, solid (asperity) friction coefficient [1]; v_s, sliding speed at which it is
# developed (tanh regularisation) [mm/s].
SolidFriction = namedtuple("SolidFriction", ["mu_s", "v_s"])


@kernel
def film_line(u, q, R, eta0, alpha_p, E_prime, formula):
    """EHL film thickness of a line contact (one slice).

    Parameters
    ----------
    u : float
        Entrainment (mean surface) speed [mm/s], >= 0.
    q : float
        Load per unit length [N/mm].
    R : float
        Radius of relative curvature in the rolling direction [mm].
    eta0 : float
        Dynamic viscosity at ambient pressure [MPa s].
    alpha_p : float
        Barus pressure-viscosity coefficient [1/MPa].
    E_prime : float
        Reduced modulus E' = 2 / ((1 - nu1^2)/E1 + (1 - nu2^2)/E2) [MPa].
    formula : int
        FILM_PAN_HAMROCK: central film, H = 2.922 W^-0.166 U^0.692 G^0.470 (Pan & Hamrock 1989);
        FILM_DOWSON_HIGGINSON: minimum film, H = 1.6 G^0.6 U^0.7 W^-0.13 (thesis eq. (2.26)).
        H = h/R, U = eta0 u / (E' R), W = q / (E' R), G = alpha_p E'.

    Returns
    -------
    float
        Film thickness h [mm]; 0 without entrainment or load.
    """
    if u <= 0.0 or q <= 0.0:
        return 0.0
    U = eta0 * u / (E_prime * R)
    W = q / (E_prime * R)
    G = alpha_p * E_prime
    if formula == FILM_PAN_HAMROCK:
        return R * 2.922 * W ** -0.166 * U ** 0.692 * G ** 0.470
    return R * 1.6 * G ** 0.6 * U ** 0.7 * W ** -0.13


@kernel
def film_point(u, Q, Rx, Ry, eta0, alpha_p, E_prime):
    """Central EHL film thickness of an elliptical point contact (Hamrock & Dowson 1977).

    h_c / Rx' = 2.69 U^0.67 G^0.53 W^-0.067 (1 - 0.61 exp(-0.73 k)), with 1/Rx' = 1/Rx (the
    rolling-direction radius), U = eta0 u/(E' Rx), W = Q/(E' Rx^2), G = alpha_p E' and the
    ellipticity k = (Ry/Rx)^(2/pi) (Hamrock & Brewe 1983). Hamrock & Dowson fitted k = 1-8
    (entrainment along the minor axis); the TRB's roller-end / rib contact is elongated along its
    entrainment, k ~ 0.24 (sim.geometry._sphere_rib), where the same formula is used: Koye & Winer
    1981 (J. Lubr. Technol. 103, 284) measured 57 films of crowned rollers on a sapphire disc with
    the ellipse's major axis both along and across the motion and found them on average 30 % thicker
    than this formula (the minimum film; the k range they covered is not checked here).

    Parameters
    ----------
    u : float
        Entrainment speed [mm/s].
    Q : float
        Normal load [N].
    Rx, Ry : float
        Radii of relative curvature along and across the rolling direction [mm].
    eta0, alpha_p, E_prime :
        As :func:`film_line`.

    Returns
    -------
    float
        h_c [mm]; 0 without entrainment or load.
    """
    if u <= 0.0 or Q <= 0.0:
        return 0.0
    U = eta0 * u / (E_prime * Rx)
    W = Q / (E_prime * Rx * Rx)
    G = alpha_p * E_prime
    k = (Ry / Rx) ** (2.0 / np.pi)
    return Rx * 2.69 * U ** 0.67 * G ** 0.53 * W ** -0.067 * (1.0 - 0.61 * np.exp(-0.73 * k))


@kernel
def solid_load_share(h, sigma, B_ZH, C_ZH):
    """Phi = N_solid / N = exp(-B_ZH Lambda^C_ZH), thesis eq. (5.16), Lambda = h/sigma (2.27) [1]."""
    if h <= 0.0:
        return 1.0
    return np.exp(-B_ZH * (h / sigma) ** C_ZH)


@kernel
def rolling_force_hydrodynamic(u, q, R, width, eta0, alpha_p, E_prime):
    """Hydrodynamic (Poiseuille) rolling force of a line-contact strip, on EACH surface [N].

    F = l (4.318/alpha_p) (G U)^0.658 W^0.0126 R (Goksem & Hargreaves, ASME J. Lubr. Technol. 100
    (1978) 346-358, isothermal EHL line contact, as quoted in reference/friction_literature.md)
    with U = eta0 u/(E' R), W = q/(E' R), G = alpha_p E' and l the strip length (the loaded
    length of a slice strip, :func:`sim.physics.elasticity.loaded_lengths`) [mm]; u entrainment
    (mean) speed [mm/s], q [N/mm], alpha_p [1/MPa], R, E' as in :func:`film_line`;
    F [N] = [MPa mm] [mm].

    Why this form: in the elastohydrodynamic regime the force comes from the inlet, whose
    geometry the load hardly changes, so F per unit length is almost independent of the load.
    The project's 1-D Reynolds solution (tests/friction/reynolds_1d.py, isothermal, elastic,
    Roelands) gives d ln F/d ln W = -0.004 to +0.03 over W = 0.6-6e-4 at U = 1e-11 and 3e-11,
    against 0.0126 here (tests/friction/test_rolling_resistance.py); the fits with W^0.246
    (Zhou & Hoeprich 1991, eq. 17) and W^0.3 (this kernel before issue 14) make the rolling
    loss of a whole bearing grow like Fa^0.3 on their own. Whole-bearing formulas that carry
    W^0.31 (Aihara 1987, SKF's G_rr) are calibrated on measured torque that also holds the
    hysteresis, rib and sliding losses, which this model computes separately.
    Magnitude: the numerical force is 1.16-1.32 times this F at Moes M = 15-77; omitting the
    compressibility (Dowson-Higginson density) there thickens the film by 15-19 % at 1.1-1.4 GPa,
    and the rest (up to ~13 %) is the scatter of a three-exponent fit.

    Notes
    -----
    Rolling loss of the film, from the Reynolds equation (isothermal Newtonian film, viscosity
    eta(x) uniform across it, surfaces 1 at z = 0 and 2 at z = h moving at U1, U2 along x,
    u = (U1 + U2)/2, film rupture at x_e with p = dp/dx = 0, h_e = h(x_e)):

    1. Velocity u(z) = U1 + (U2 - U1) z/h + (p'/(2 eta)) (z^2 - z h); flux per unit length
       q_x = u h - h^3 p'/(12 eta), constant by continuity: h^3 p'/(12 eta) = u (h - h_e).
    2. Shear of the film on the surfaces (+x): tau_1 = eta (U2 - U1)/h - (h/2) p',
       tau_2 = -eta (U2 - U1)/h - (h/2) p'. The Poiseuille part -(h/2) p' is the SAME on both
       surfaces: in pure rolling each surface is retarded by F = int (h/2) p' dx (> 0: the
       inlet, where p' > 0 and h is large, outweighs the outlet).
    3. Dissipation D = int int eta (du/dz)^2 dz dx = int [eta (U2 - U1)^2/h + h^3 p'^2/(12 eta)] dx.
       With step 1, int h^3 p'^2/(12 eta) dx = u int p' (h - h_e) dx = u int p' h dx (p = 0 at
       both ends), hence
           D = -(tau_1 U1 + tau_2 U2) integrated = eta-Couette part + 2 u F:
       the power taken from the two surfaces, both at speed u, is 2 u F.
    4. Moments: the pressure acts normal to each surface (through the roller axis for the
       roller), so only the shear turns a body; with the rolling speeds u = omega_1 R_1 =
       omega_2 R_2 and 1/R = 1/R_1 + 1/R_2, the couple between roller and ring about the axis of
       relative rolling (omega_rel = u/R) that dissipates 2 u F is M = 2 F R. Equivalently
       (integrating step 2 by parts, h' = x/R plus the elastic term whose moment vanishes by the
       symmetry of the log kernel) the pressure centre lies e = 2 F R/q upstream of the line of
       centres: q e = 2 F R, the form of Zhou & Hoeprich and Biboulet & Houpert (2010).

    A model that applies F R as the couple (power F u) counts the loss once; Reynolds puts it on
    both surfaces. ``tests/friction/test_rolling_resistance.py`` checks this against a numerical
    1-D line-contact solution (:mod:`tests.friction.reynolds_1d`).
    """
    if u <= 0.0 or q <= 0.0:
        return 0.0
    U = eta0 * u / (E_prime * R)
    W = q / (E_prime * R)
    G = alpha_p * E_prime
    return width * 4.318 / alpha_p * (G * U) ** 0.658 * W ** 0.0126 * R


@kernel
def rolling_moment_hydrodynamic(u, q, R, width, eta0, alpha_p, E_prime):
    """Resisting couple of the EHL rolling loss of a line-contact strip [N mm].

    M = 2 F R with F the Poiseuille force on each surface (:func:`rolling_force_hydrodynamic`)
    and R the radius of relative curvature [mm]: with the relative rolling speed omega_rel =
    u/R it dissipates M omega_rel = 2 u F, the Reynolds-equation loss of the film (derivation
    in :func:`rolling_force_hydrodynamic`, Notes 3-4). Arguments as there.
    """
    return 2.0 * R * rolling_force_hydrodynamic(u, q, R, width, eta0, alpha_p, E_prime)


@kernel
def thermal_loading(eta0, beta, u, k_oil):
    """Thermal loading parameter of inlet shear heating, L = eta0 beta u^2 / k [1].

    L = -(d eta/dT) u^2 / k_f with -(d eta/dT) = eta0 beta at the inlet temperature (Gupta et al.
    1992; Zhou & Hoeprich 1991; Wilson & Sheu 1983 use the same group).

    Parameters
    ----------
    eta0 : float
        Inlet (bulk oil) viscosity at ambient pressure [MPa s].
    beta : float
        Temperature-viscosity coefficient -d ln(eta)/dT [1/K]
        (:meth:`sim.physics.lubricant.Lubricant.temperature_viscosity_coefficient`).
    u : float
        Entrainment (rolling, mean surface) speed [mm/s].
    k_oil : float
        Thermal conductivity of the oil [W/(m K)] (= N/(s K) in any length unit).

    Returns
    -------
    float
        L [1]: eta0 [N s/mm^2] u^2 [mm^2/s^2] = [N/s] over k [N/(s K)] times beta [1/K].
    """
    return eta0 * beta * u * u / k_oil


@kernel
def film_thermal_factor_gupta(p_h, E_prime, L, srr):
    """Inlet shear-heating reduction factor of the EHL film, phi_T [1] (Gupta et al. 1992).

    phi_T = [1 - 13.2 (p_h/E') L^0.42] / [1 + 0.213 (1 + 2.23 |S|^0.83) L^0.64]

    Gupta, Cheng, Zhu, Forster & Schrand, "Viscoelastic effects in MIL-L-7808-type lubricant,
    Part I: Analytical formulation", Tribology Transactions 35(2) (1992) 269-274, fit to thermal
    inlet-zone EHL solutions; the same form is quoted for the rolling force (F = phi_T F_iso,
    Zhou & Hoeprich 1991, eqs. 21-22) and by Wingertszahn et al. (2023, Lubricants 11, 369,
    eqs. 12-14). The expression is transcribed from those quotations (project file
    reference/friction_literature.md); the 1992 paper itself was not readable here.

    Parameters
    ----------
    p_h : float
        Maximum Hertz pressure [MPa].
    E_prime : float
        Reduced modulus E' = 2 E* [MPa] (Hamrock's, as in :func:`film_line`).
    L : float
        Thermal loading, :func:`thermal_loading` [1], >= 0.
    srr : float
        Slide-to-roll ratio S = (U1 - U2)/u [1] (its magnitude is used).

    Returns
    -------
    float
        phi_T in [0, 1]: 1 at L = 0, decreasing in L and in |S|. The numerator reaches 0 at
        L = (E'/(13.2 p_h))^(1/0.42), far beyond the fitted range; it is floored at 0 there, and
        the friction model reports a case with such a contact as not converged
        (:meth:`sim.api.friction_model.FrictionModel.evaluate`).
    """
    if L <= 0.0:
        return 1.0
    num = 1.0 - 13.2 * (p_h / E_prime) * L ** 0.42
    if num <= 0.0:
        return 0.0
    return num / (1.0 + 0.213 * (1.0 + 2.23 * abs(srr) ** 0.83) * L ** 0.64)


@kernel
def rolling_force_hysteresis(q, b, R, width, loss_factor):
    """Elastic-hysteresis rolling resistance of a line-contact strip [N].

    F = loss_factor (2 / (3 pi)) (b / R) q l (Johnson 1985, eq. 9.20 for a cylinder: resisting
    moment M = loss_factor 2 b q / (3 pi) per unit length, F = M / R); b half-width [mm],
    R [mm], q [N/mm], l strip length [mm].
    """
    return loss_factor * 2.0 / (3.0 * np.pi) * b / R * q * width


@kernel
def film_temperature_rise(q_film, h, k_oil):
    """Mid-plane temperature rise of a sheared film over its surfaces [K].

    Heat q_film = tau v per unit area generated uniformly across a film of thickness h and
    conducted to both walls gives a parabolic profile with the peak q_film h / (8 k_oil) at
    mid-film, where the shear concentrates (Crook 1961; Olver & Spikes 1998).

    q_film [N/(mm s)] (= kW/m^2), h [mm], k_oil [W/(m K)] (= N/(s K) in any length unit).
    """
    return q_film * h / (8.0 * k_oil)


@kernel
def flash_temperature_rise(q, half_length, U1, U2, k_s, kappa_s):
    """Mean surface temperature rise of a contact band under frictional heating [K].

    Each surface passes the band of length 2 half_length at its speed U_i; at high Peclet
    number (U l / (2 kappa) > 5, bearing contacts: 10-100) it heats as a semi-infinite solid
    under a constant flux for the time x/U_i: T(x) = 2 q_i sqrt(kappa x / (pi U_i)) / k
    (Carslaw & Jaeger 1959, semi-infinite solid under a constant surface flux; Jaeger 1942),
    mean over the band 2/3 of the exit value. Blok's
    (1937) partition q_i ~ sqrt(U_i) makes both surfaces equally hot:
    T = (4/3) q sqrt(2 l kappa / pi) / (k (sqrt(U1) + sqrt(U2))).

    q [N/(mm s)], half_length [mm], U1, U2 [mm/s], k_s [W/(m K)], kappa_s [mm^2/s].
    """
    su = np.sqrt(abs(U1)) + np.sqrt(abs(U2))
    if q <= 0.0 or su <= 0.0:
        return 0.0
    return 4.0 / 3.0 * q * np.sqrt(2.0 * half_length * kappa_s / np.pi) / (k_s * su)


@internal_kernel
def _tanh_over_x(x):
    """tanh(x)/x, continuous at 0 (series 1 - x^2/3 below 1e-4, where its error is < 1e-17)."""
    if x < 1e-4:
        return 1.0 - x * x / 3.0
    return np.tanh(x) / x


@kernel
def roelands_index(eta0, alpha_p):
    """Roelands pressure-viscosity index Z [1] with the Barus coefficient as its slope at p = 0.

    d ln(eta)/dp at p = 0 of :func:`pressure_viscosity` is ln(eta0/eta_inf) Z / p_R, so
    Z = alpha_p p_R / ln(eta0/eta_inf) (Hamrock, Schmid & Jacobson 2004, ch. 4). eta0 [MPa s]
    at the oil temperature, alpha_p [1/MPa].
    """
    return alpha_p * ROELANDS_P_R / np.log(eta0 / ROELANDS_ETA_INF)


@kernel
def pressure_viscosity(p, eta, alpha_p, z, model):
    """Viscosity at pressure p [MPa s].

    PV_BARUS: eta exp(alpha_p p). PV_ROELANDS (Roelands 1966):
    eta exp(ln(eta/eta_inf) ((1 + p/p_R)^z - 1)), eta_inf = 6.31e-5 Pa s, p_R = 196.1 MPa; as
    eta falls with temperature the pressure rise weakens too (the coupling Barus lacks).

    p [MPa] >= 0; eta: ambient-pressure viscosity at the film temperature [MPa s]; alpha_p
    [1/MPa]; z: :func:`roelands_index` of the oil at its bulk temperature [1].
    """
    return viscosity_at_pressure(eta, viscosity_log_ratio(eta, model), pressure_term(p, alpha_p, z, model), model)


@kernel
def viscosity_log_ratio(eta, model):
    """The factor of :func:`pressure_viscosity` that depends on the ambient viscosity eta [MPa s]
    alone: Roelands ln(eta/eta_inf) [1]; Barus none (0.0, unused)."""
    if model == PV_BARUS:
        return 0.0
    return np.log(eta / ROELANDS_ETA_INF)


@kernel
def pressure_term(p, alpha_p, z, model):
    """The factor of :func:`pressure_viscosity` that depends on the pressure alone [1]: Barus
    exp(alpha_p p), Roelands (1 + p/p_R)^z - 1. A caller that needs the viscosity at the same
    pressures for several ambient viscosities (the film temperature solve) evaluates it once."""
    if model == PV_BARUS:
        return np.exp(alpha_p * p)
    return (1.0 + p / ROELANDS_P_R) ** z - 1.0


@kernel
def viscosity_at_pressure(eta, log_ratio, term, model):
    """:func:`pressure_viscosity` from its parts [MPa s]: ``log_ratio`` of
    :func:`viscosity_log_ratio` and ``term`` of :func:`pressure_term`."""
    if model == PV_BARUS:
        return eta * term
    return eta * np.exp(log_ratio * term)


@kernel
def traction_per_speed(p, v, h, phi, eta_p, rheology, solid, t_transit):
    """Traction stress over sliding speed, tau(p, |v|) / |v| [MPa s/mm], thesis (5.17).

    tau = phi mu_s p tanh(|v|/v_s) + (1 - phi) tau_lim tanh(k |v| / tau_lim) with
    tau_lim = tau_L0 + c_tau p (Bair & Winer 1979) and the low-slip slope of a Maxwell fluid
    sheared for the transit time t of a contact, 1/k = h (1/eta(p) + 1/(G t)) (Johnson &
    Tevaarwerk 1977). The traction on a surface is -tau v/|v|: the returned ratio times -v.

    Parameters
    ----------
    p : float
        Contact pressure [MPa].
    v : float
        Sliding speed |v| [mm/s].
    h : float
        Film thickness [mm] (0: no film, phi must then be 1).
    phi : float
        Solid load share (5.16) [1].
    eta_p : float
        Film viscosity at the pressure p (:func:`pressure_viscosity`) [MPa s].
    rheology : FilmRheology
        tau_L0 [MPa], c_tau [1], G [MPa] of the film (tau_E0 is not used by this law).
    solid : SolidFriction
        mu_s [1], v_s [mm/s] of the asperity contacts.
    t_transit : float
        Transit time of the lubricant through the contact, contact length / entrainment speed [s].
    """
    g = traction_solid(p, v, phi, solid)
    if phi < 1.0 and h > 0.0:
        g += film_traction_maxwell(p, v, h, phi, eta_p, rheology, t_transit)
    return g


@kernel
def traction_solid(p, v, phi, solid):
    """Solid (asperity) part of the traction over sliding speed, phi mu_s p tanh(|v|/v_s)/|v|
    [MPa s/mm], of :func:`traction_per_speed` and :func:`traction_eyring` (same arguments;
    solid: :data:`SolidFriction`)."""
    return phi * solid.mu_s * p * _tanh_over_x(v / solid.v_s) / solid.v_s


@kernel
def film_traction_maxwell(p, v, h, phi, eta_p, rheology, t_transit):
    """Film part (1 - phi) tau_lim tanh(k |v|/tau_lim)/|v| of :func:`traction_per_speed` [MPa s/mm]
    (same arguments; h > 0)."""
    tau_lim = rheology.tau_L0 + rheology.c_tau * p
    k = 1.0 / (h * (1.0 / eta_p + 1.0 / (rheology.G * t_transit)))   # [MPa s/mm]
    return (1.0 - phi) * k * _tanh_over_x(k * v / tau_lim)


# Relative error of the Eyring stress at which its Halley solve stops: half the double precision
# unit roundoff 2^-53 ~ 1.1e-16, i.e. the root to rounding (the solve is the inner loop of the
# traction; its value then does not depend on the iteration count, which the finite-difference
# Jacobian of the kinematics needs).
EYRING_REL_ERROR = 1e-16
# Halley steps of the Eyring solve before it reports no convergence; from the start above the root
# it is reached in at most 3 steps (measured: 20000 pairs S, De log-uniform in [1e-300, 1e300], 20 %
# De = 0; tests/friction/test_traction_law.py asserts at most 6 over S in [1e-12, 1e250]).
EYRING_MAX_STEPS = 100
# S above which cosh(asinh S) = sqrt(1 + S^2) is S to rounding (1 + S^2 rounds to S^2 from
# S = 2^27 on) and below the overflow of S^2 (1.3e154): sqrt(1 + S^2) instead of the slower
# hypot(1, S) below it.
EYRING_LARGE_S = 1e150


@internal_kernel
def _sinh_cosh(x):
    """(sinh x, cosh x) for x >= 0 from one expm1 (accurate near 0 too: no e^x - e^-x cancellation)."""
    em = np.expm1(x)
    if em == np.inf:                    # x > ln(DBL_MAX): sinh, cosh overflow later than e^x
        return np.sinh(x), np.cosh(x)
    ep = 1.0 + em
    sh = 0.5 * em * (1.0 + 1.0 / ep)    # (e^x - e^-x)/2 = (em + em/(1 + em))/2
    return sh, sh + 1.0 / ep


@kernel
def eyring_maxwell_stress(S, De):
    """Stress of a Maxwell-Eyring film at a given strain rate, x = tau/tau_E0 [1].

    Solves De x + sinh(x) = S for x >= 0: the steady strain rate gamma_dot of a Maxwell element
    with an Eyring dashpot, gamma_dot = tau/(G t) + (tau_E0/eta) sinh(tau/tau_E0) (Johnson &
    Tevaarwerk 1977, eq. (3) with the elastic rate over the transit time t taken as tau/(G t), the
    approximation :func:`traction_per_speed` makes for the Maxwell fluid), divided by
    tau_E0/eta: S = eta gamma_dot/tau_E0 (the Eyring number), De = eta/(G t) (a Deborah number).

    Halley's method (cubic convergence; f2 = sinh x, the second derivative, comes with
    f1 = De + cosh x from the same expm1) from x0 = min(asinh(S), S/De), both upper bounds of
    the root (f(asinh S) = De x0 >= 0, f(S/De) = sinh(S/De) >= 0) of f(x) = De x + sinh(x) - S,
    which is increasing and convex on x >= 0. The step is dx = n / (1 - n f2/(2 f1)) with the
    Newton step n = f/f1: from the start 0 <= n < 1 (n = De x0/(De + cosh x0) <= S/cosh x0 < 1
    when x0 = asinh S <= S/De; n = sinh(x0)/(De + cosh x0) < 1 when x0 = S/De) and f2/f1 < 1,
    so the denominator stays above 1/2 and nothing overflows (no f1^2). At x0 = asinh(S) the
    first step needs no transcendental: f = De x0, f1 = De + sqrt(1 + S^2), f2 = S. Stopping
    rule: Halley's error e' = x' - r of the next iterate obeys
    e' = (f2^2/(4 f1^2) - f3/(6 f1)) e^3 + O(e^4) (f3 = cosh x, the third derivative) with
    e = dx + e', so K |dx|^3 <= eps x' with K = cosh/(6 f1) + (f2/f1)^2/4 bounds e'/x' by eps
    to first order: x' is the root to rounding, one sinh/cosh evaluation before the step |dx|
    itself would fall below rounding. (Newton's method, used before, took one sinh/cosh more
    at about half the width points of a combined case.) At De = 0 (no elastic part, the heat
    estimate of the thermal film solve) x0 = asinh(S) is the root: returned without a step.

    Parameters
    ----------
    S : float
        Eyring number eta gamma_dot / tau_E0 [1], >= 0.
    De : float
        eta / (G t) [1], >= 0 (0: purely viscous Eyring).

    Returns
    -------
    x : float
        tau / tau_E0 [1].
    converged : bool
    iterations : int
        Halley steps taken.
    """
    if S <= 0.0:
        return 0.0, True, 0
    x = np.arcsinh(S)
    if De == 0.0:                       # purely viscous: sinh(x) = S, the start is the root
        return x, True, 0
    sh = S                              # sinh(x)
    ch = np.sqrt(1.0 + S * S) if S < EYRING_LARGE_S else S     # cosh(x)
    fp = De + ch                        # f'(x)
    f = De * x
    if f > S:                           # the elastic bound S/De lies below asinh(S)
        x = S / De
        sh, ch = _sinh_cosh(x)
        fp = De + ch
        f = sh                          # De x - S = 0
    for it in range(1, EYRING_MAX_STEPS + 1):
        n = f / fp                      # Newton step
        c = sh / fp                     # f''/f'
        dx = n / (1.0 - 0.5 * n * c)    # Halley step
        x_next = x - dx
        if x_next <= 0.0:               # guard only: the steps from the start stay right of 0
            x_next = 0.5 * S / (1.0 + De)
        done = (ch / (6.0 * fp) + 0.25 * c * c) * dx * dx * abs(dx) <= EYRING_REL_ERROR * x_next
        x = x_next
        if done:
            return x, True, it
        sh, ch = _sinh_cosh(x)
        fp = De + ch
        f = De * x + sh - S
    return x, False, EYRING_MAX_STEPS


@kernel
def traction_eyring(p, v, h, phi, eta_p, rheology, solid, t_transit):
    """Traction stress over sliding speed of an Eyring (Maxwell-Eyring) film, tau/|v| [MPa s/mm].

    Drop-in alternative to :func:`traction_per_speed` (the same arguments, of which this law
    also reads the Eyring stress ``rheology.tau_E0``; same return quantity, the traction on a surface is the
    returned ratio times -v):

        tau = phi mu_s p tanh(|v|/v_s) + (1 - phi) tau_L tanh(tau_M / tau_L),
        tau_L = tau_L0 + c_tau p,
        |v|/h = tau_M/(G t) + (tau_E0/eta(p)) sinh(tau_M/tau_E0).

    The film stress tau_M is the Maxwell-Eyring law of Johnson & Tevaarwerk (1977, Proc. R. Soc.
    Lond. A 356, 215-236), elastic rate over the transit time t (as in traction_per_speed) plus
    the Ree-Eyring viscous rate (Eyring 1936; Evans & Johnson 1986, Proc. IMechE C 200);
    :func:`eyring_maxwell_stress` solves it. The limiting shear stress tau_L (Bair & Winer 1979,
    ASME J. Lubr. Technol. 101: tau_L rising linearly with pressure) bounds it
    smoothly by tanh, the form of the project's solid part and of the issue's request.

    The papers are cited as in the tribology literature (Greenwood 2020, Lubricants 8, 51, and
    the project's reference/friction_literature.md); their texts were not read in this session,
    the equations are the standard forms they are known for.

    Regimes: |v| -> 0: tau/|v| -> 1/(h (1/eta + 1/(G t))), the slope of traction_per_speed
    (linear, Newtonian eta/h when G t >> eta); moderate slip: tau_M ~ tau_E0 ln(2 eta |v|/(h
    tau_E0)), the logarithmic Eyring rise that Newtonian-then-limited laws lack; high slip:
    tau -> tau_L (the plateau). With tau_E0 -> inf the law is traction_per_speed's
    Maxwell-Newtonian film except for its tanh limit (here of tau_M, there of k |v|, the same).

    Parameters
    ----------
    p : float
        Contact pressure [MPa].
    v : float
        Sliding speed |v| [mm/s].
    h : float
        Film thickness [mm] (0: no film, phi must then be 1).
    phi : float
        Solid load share (5.16) [1].
    eta_p : float
        Film viscosity at the pressure p [MPa s] (:func:`pressure_viscosity`).
    rheology : FilmRheology
        tau_E0, the Eyring stress [MPa], > 0: mineral oils 2-10 MPa (Johnson & Tevaarwerk 1977;
        Evans & Johnson 1986), ~ 2 Lambda/alpha after Bair & Winer; tau_L0 [MPa] and c_tau [1],
        the limiting shear stress at zero pressure and its pressure slope; G [MPa], the elastic
        shear modulus of the film.
    solid : SolidFriction
        mu_s [1], v_s [mm/s]: solid friction coefficient and its regularising speed.
    t_transit : float
        Transit time through the contact, contact length / entrainment speed [s] (inf: no
        elastic part).

    Returns
    -------
    float
        tau/|v| [MPa s/mm], finite at v = 0 (its limit).
    """
    g = traction_solid(p, v, phi, solid)
    if phi < 1.0 and h > 0.0:
        g += film_traction_eyring(p, v, h, phi, eta_p, rheology, t_transit)
    return g


@internal_kernel
def film_traction_eyring(p, v, h, phi, eta_p, rheology, t_transit):
    """Film part (1 - phi) tau_L tanh(tau_M/tau_L)/|v| of :func:`traction_eyring` [MPa s/mm]
    (same arguments; h > 0)."""
    tau_E0 = rheology.tau_E0
    tau_L = rheology.tau_L0 + rheology.c_tau * p
    De = eta_p / (rheology.G * t_transit)
    S = eta_p * v / (h * tau_E0)
    x = eyring_maxwell_stress(S, De)[0]
    r = x / S if S > 0.0 else 1.0 / (1.0 + De)      # tau_M/(tau_E0 S) = tau_M h/(eta |v|)
    tau_M = tau_E0 * x
    return (1.0 - phi) * (eta_p / h) * r * _tanh_over_x(tau_M / tau_L)
