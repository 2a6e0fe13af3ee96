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
- Rolling resistance of the lubricant: Zhou & Hoeprich (1991) hydrodynamic rolling force of a
  line contact; of the material: elastic hysteresis (Johnson 1985, 9.2).
- Shear heating of a contact (the thermal reduction of the traction, :mod:`sim.physics.friction`):
  mid-film temperature rise of Couette heating, and the mean flash temperature of the surfaces
  under a moving band heat source (Jaeger 1942, Blok 1937 partition).
"""
import numpy as np

from sim._math.jit import kernel

FILM_PAN_HAMROCK = 0
FILM_DOWSON_HIGGINSON = 1
FILM_FORMULAS = {"pan_hamrock": FILM_PAN_HAMROCK, "dowson_higginson": FILM_DOWSON_HIGGINSON}
PV_BARUS = 0
PV_ROELANDS = 1
PRESSURE_VISCOSITY_MODELS = {"barus": PV_BARUS, "roelands": PV_ROELANDS}
#: Roelands (1966) constants: eta_inf = 6.31e-5 Pa s [MPa s] and p_R = 1/5.1e-9 Pa [MPa].
ROELANDS_ETA_INF = 6.31e-11
ROELANDS_P_R = 196.1


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
    ellipticity k = (Ry/Rx)^(2/pi) (Hamrock & Brewe 1983).

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
    """Hydrodynamic rolling force of a line-contact strip [N] (Zhou & Hoeprich 1991).

    F = 2.86 E' R l G^0.022 U^0.66 W^0.3 with U = eta0 u/(E' R), W = q/(E' R), G = alpha_p E'
    and l the strip length (slice width) [mm]; u entrainment speed [mm/s], q [N/mm].
    """
    if u <= 0.0 or q <= 0.0:
        return 0.0
    U = eta0 * u / (E_prime * R)
    W = q / (E_prime * R)
    G = alpha_p * E_prime
    return 2.86 * E_prime * R * width * G ** 0.022 * U ** 0.66 * W ** 0.3


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


@kernel
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
    if model == PV_BARUS:
        return eta * np.exp(alpha_p * p)
    return eta * np.exp(np.log(eta / ROELANDS_ETA_INF) * ((1.0 + p / ROELANDS_P_R) ** z - 1.0))


@kernel
def traction_per_speed(p, v, h, phi, eta_p, tau0, c_tau, mu_s, v_s, G, t_transit):
    """Traction stress over sliding speed, tau(p, |v|) / |v| [MPa s/mm], thesis (5.17).

    tau = phi mu_s p tanh(|v|/v_s) + (1 - phi) tau_lim tanh(k |v| / tau_lim) with
    tau_lim = tau0 + c_tau p (Bair & Winer 1979) and the low-slip slope of a Maxwell fluid
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
    tau0 [MPa], c_tau [1], mu_s [1], v_s [mm/s], G [MPa] :
        Lubricant and boundary-friction parameters.
    t_transit : float
        Transit time of the lubricant through the contact, contact length / entrainment speed [s].
    """
    g = phi * mu_s * p * _tanh_over_x(v / v_s) / v_s
    if phi < 1.0 and h > 0.0:
        tau_lim = tau0 + c_tau * p
        k = 1.0 / (h * (1.0 / eta_p + 1.0 / (G * t_transit)))   # [MPa s/mm]
        g += (1.0 - phi) * k * _tanh_over_x(k * v / tau_lim)
    return g
