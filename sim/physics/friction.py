"""Roller kinematics from the traction balance, and the frictional torque (MODEL.md 5, thesis 5.4).

Frame: the cage frame, rotating with the cage at omega_c about the bearing axis z; the outer
ring turns at -omega_c, the inner ring at omega_i - omega_c, roller j about its own axis u'
at omega_R,j. Local basis at a roller's azimuth: (e_r, e_t, e_z), right-handed, meridian
coordinates (r, z) as in :mod:`sim.geometry`.

Per slice and raceway (kernel :func:`_slice_friction`), at the contact point X with normal
n (into the ring) and rolling tangent a = n x e_t:

- sliding speed of the roller against the ring along e_t, s = omega_R (u' x (X - c)).e_t - Omega X_r,
  and across the contact width y (along e_t) the spin omega_s = (omega_R u' - Omega e_z).n adds
  y omega_s along a; the traction -tau v/|v| of (5.17) is integrated over the Hertz width
  (y = b sin(t), Gauss-Legendre in t) giving the force F_t along e_t and the spin moment M_n
  about n. Their power is split per raceway contact of a roller: ``sliding`` is the power of
  the contact's rigid slip, the load-weighted mean s_m of s along the roller, -sum(F_t) s_m;
  ``drilling`` is the rest, -sum(F_t (s - s_m)) - sum(M_n omega_s): the relative rotation
  about the contact normal, which along a line contact shows as s varying along the roller
  (a crowned roller rolls without slip at two points only, thesis 2.3.1, Figs. 2.16, 2.17).
- rolling resistance (lubricant, Zhou & Hoeprich 1991; hysteresis, Johnson 1985) as a couple
  M = (F_h + F_y) R_eq about a, opposing the relative rolling omega_rel.a, on roller and ring;
  its power is (F_h + F_y) times the rolling speed. (5.18) in this form: the solid rolling
  share Phi M_T,S,r is the micro-slip of the asperity contacts, which the width integration of
  the Phi-weighted solid traction resolves explicitly; it has no separate coefficient.
- film viscosity in the traction: per contact, the ambient viscosity lowered by the contact's
  own shear heating (:func:`_viscosity_factor`: flash + mid-film temperature, solved
  self-consistently at the speeds of the previous kinematic pass, like the film thickness),
  then raised to the local pressure (Barus or Roelands) at every width point; both are fixed
  while the roller and cage speeds are solved.
- TRB roller end / rib: point contact, sliding along e_t, traction (5.17) at the Hertz mean
  pressure with the rib's own roughness and B_ZH, C_ZH; its rolling resistance and spin are
  neglected (sliding dominated, thesis 5.5.1).
- cage pocket: the cage supplies the tangential force F_cage that balances the roller along
  e_t; its pocket friction mu_c |F_cage| acts on the spinning roller surface: a moment about
  u' and a force mu_c F_cage sign(omega_R) along v', in the roller's meridian plane. That force
  is the friction load that enters the quasi-static balance (``roller_loads``); the raceway
  tractions act along e_t (out of the meridian plane, balanced by the cage) and their spin
  integrals are even across the width, so they add no meridian-plane force.
- drag (optional): fluid drag on the rollers, F_D = 1/2 rho X C_D Dwe Lwe (omega_c Dpw/2)^2
  (Harris & Kotzalas 2007, drag on rolling elements), reacted by the housing (outer ring).

Unknowns: omega_R,j (roller moment about u' = 0, per roller) and omega_c (cage moment about z
= 0: sum over rollers of the z-moments the contacts exert). At that equilibrium the torque the
rollers and the oil exert on the outer ring equals power loss / omega_i exactly (energy
balance); the kernels compute both independently so the identity checks the solution.
"""
import numpy as np

from sim._math.jit import kernel
from sim._math.roots import illinois
from sim.physics.contact import hertz_line_half_width, hertz_line_pressure
from sim.physics.ehl import (film_line, film_point, film_temperature_rise, flash_temperature_rise, solid_load_share,
                     pressure_viscosity, rolling_force_hydrodynamic, rolling_force_hysteresis, traction_per_speed)

# Loss and torque channels of the kernels (order of the DATA.md `component` coordinate).
COMPONENTS = ["rolling", "hysteresis", "sliding", "drilling", "rib", "cage", "drag"]
NC = len(COMPONENTS)
# roller evaluation vector: M_u, T_z on roller, T_z on outer ring, F_t along e_t (contacts + rib), then powers
EV_MU, EV_TZ, EV_TOUT, EV_FT = 0, 1, 2, 3
EV_P0 = 4
NEV = EV_P0 + NC
# Friction parameters, packed for the kernels (built by FrictionModel from the config)
(PAR_ETA0, PAR_ALPHA, PAR_TAU0, PAR_CTAU, PAR_MU_S, PAR_V_S, PAR_HYST, PAR_MU_CAGE, PAR_SIGMA, PAR_B, PAR_C,
 PAR_SIGMA_RIB, PAR_B_RIB, PAR_C_RIB, PAR_EPRIME, PAR_FILM, PAR_DRAG_K, PAR_RHO_M, PAR_G,
 PAR_THERMAL, PAR_BETA, PAR_K_OIL, PAR_K_STEEL, PAR_KAPPA_STEEL, PAR_DT_TOL, PAR_PV_MODEL, PAR_Z) = range(27)
NPAR = 27


@kernel
def _surface_speeds(wR, Om, Xr, Xz, cr, cz, ur, uz):
    """Speeds along e_t of the roller surface and of the ring surface at (Xr, Xz) [mm/s]."""
    return wR * (uz * (Xr - cr) - ur * (Xz - cz)), Om * Xr


@kernel
def _heat_flux(theta, p0k, bk, hk, phik, st, ws, par, tq, wq):
    """Mean frictional heat flux of a contact [N/(mm s)]: (lubricant film, total).

    Line slice (bk > 0): traction (5.17) at the Hertz pressure p0 cos(t) and the sliding speed
    sqrt(st^2 + (y ws)^2), y = b sin(t), averaged over the width as in :func:`_slice_friction`;
    point contact (bk = 0, the rib): at the mean pressure p0k and the speed |st|. ``theta``
    scales the ambient viscosity (thermal reduction).
    """
    eta = par[PAR_ETA0] * theta
    q_tot = 0.0
    q_sol = 0.0
    npts = tq.shape[0] if bk > 0.0 else 1
    for i in range(npts):
        if bk > 0.0:
            ct = np.cos(tq[i])
            p = p0k * ct
            vy = bk * np.sin(tq[i]) * ws
            v = np.sqrt(st * st + vy * vy)
            weight = ct * wq[i]                  # sum of cos(t) w over (0, pi/2) = 1
        else:
            p = p0k
            v = abs(st)
            weight = 1.0
        eta_p = pressure_viscosity(p, eta, par[PAR_ALPHA], par[PAR_Z], int(par[PAR_PV_MODEL]))
        g = traction_per_speed(p, v, hk, phik, eta_p, par[PAR_TAU0], par[PAR_CTAU], par[PAR_MU_S], par[PAR_V_S],
                               par[PAR_G], 1e300)
        q_tot += weight * g * v * v
        q_sol += weight * phik * par[PAR_MU_S] * p * v * np.tanh(v / par[PAR_V_S])
    return q_tot - q_sol, q_tot


@kernel
def _viscosity_factor(p0k, bk, hk, phik, st, ws, half_length, U1, U2, par, tq, wq):
    """Thermal reduction of the film viscosity in the traction, theta = exp(-beta dT) [1].

    dT is the film temperature of the contact's own shear heating: the flash temperature of the
    surfaces under the total frictional heat plus the mid-film rise under the film's heat
    (sim.physics.ehl.flash_temperature_rise, film_temperature_rise), with the viscosity at the raised
    temperature, eta0 exp(alpha p - beta dT) (Reynolds' exponential law, beta the local
    slope of the lubricant's Ubbelohde-Walther line). Heating falls as dT rises, so
    f(dT) = dT - rise(q(theta(dT))) has one root in [0, rise(q(1))], found by Illinois
    steps to par[PAR_DT_TOL] K. The maximum traction (limiting shear) is not reduced; the
    Maxwell transit-time term is left out of the heat estimate (it only matters at
    microslip, where the heat is negligible).
    """
    if par[PAR_THERMAL] == 0.0 or hk <= 0.0:
        return 1.0
    beta = par[PAR_BETA]
    tol = par[PAR_DT_TOL]

    def rise(dT):
        q_film, q_tot = _heat_flux(np.exp(-beta * dT), p0k, bk, hk, phik, st, ws, par, tq, wq)
        return (film_temperature_rise(q_film, hk, par[PAR_K_OIL])
                + flash_temperature_rise(q_tot, half_length, U1, U2, par[PAR_K_STEEL], par[PAR_KAPPA_STEEL]))

    hi = rise(0.0)
    if hi <= tol:
        return np.exp(-beta * hi)
    lo = 0.0
    flo = -hi
    fhi = hi - rise(hi)
    if abs(fhi) <= tol:      # heat independent of the viscosity: the film is at its limiting shear stress
        return np.exp(-beta * hi)
    side = 0
    for _ in range(100):
        if fhi - flo <= 0.0 or hi - lo <= tol:
            break
        x = (lo * fhi - hi * flo) / (fhi - flo)
        fx = x - rise(x)
        if abs(fx) <= tol:
            lo = x
            hi = x
            break
        lo, hi, flo, fhi, side = illinois(lo, hi, flo, fhi, x, fx, side)
    return np.exp(-beta * 0.5 * (lo + hi))


@kernel
def lubrication_state(wR, wc, wi, active, q, Qrib, X, Nrm, Cen, Ax, Xrib, R_eq, w, E_star, rib, par, tq, wq,
                      h, Phi, Fh, Fy, p0, b, hrib, Phirib, prib, Eta, Etarib):
    """Film, solid load share, rolling resistance forces, Hertz data and thermal viscosity factor
    of every loaded contact, at the speeds wR, wc.

    Parameters
    ----------
    wR : ndarray (Z,)
        Roller speeds about u' [rad/s]. wc, wi: cage and inner-ring speeds [rad/s].
    active : ndarray (Z,) of bool
        Rollers to evaluate; the others' arrays are left as they are (the caller never reads them).
    q : ndarray (Z, 2, N)
        Line loads [N/mm]. Qrib (Z,): rib loads [N].
    R_eq : ndarray (2, N)
        Radii of relative curvature [mm]. w: slice width [mm]. E_star: contact modulus [MPa].
    par : ndarray (NPAR,)
        Friction parameters (module constants PAR_*). tq, wq: width quadrature nodes and weights.
    h, Phi, Fh, Fy, p0, b : ndarray (Z, 2, N)
        Film [mm], solid load share [1], hydrodynamic and hysteresis rolling forces [N],
        Hertz pressure [MPa] and half-width [mm] (written; 0 where unloaded).
    Eta : ndarray (Z, 2, N, len(tq))
        Film viscosity at the pressure p0 cos(tq) of each width point, after the thermal
        reduction [MPa s] (written where loaded): fixed while the kinematics are solved.
    hrib, Phirib, prib, Etarib : ndarray (Z,)
        Rib film [mm], load share [1], Hertz mean pressure [MPa] and film viscosity at that
        pressure [MPa s] (written).
    """
    Z = q.shape[0]
    n = q.shape[2]
    Ep = par[PAR_EPRIME]
    for j in range(Z):
        if not active[j]:
            continue
        cr = Cen[j, 0]
        cz = Cen[j, 1]
        ur = Ax[j, 0]
        uz = Ax[j, 1]
        for s in range(2):
            Om = -wc if s == 0 else wi - wc
            for k in range(n):
                qk = q[j, s, k]
                if qk <= 0.0:
                    h[j, s, k] = 0.0
                    Phi[j, s, k] = 0.0
                    Fh[j, s, k] = 0.0
                    Fy[j, s, k] = 0.0
                    p0[j, s, k] = 0.0
                    b[j, s, k] = 0.0
                    continue
                v1, v2 = _surface_speeds(wR[j], Om, X[j, s, k, 0], X[j, s, k, 1], cr, cz, ur, uz)
                u = 0.5 * abs(v1 + v2)
                R = R_eq[s, k]
                hk = film_line(u, qk, R, par[PAR_ETA0], par[PAR_ALPHA], Ep, int(par[PAR_FILM]))
                h[j, s, k] = hk
                Phi[j, s, k] = solid_load_share(hk, par[PAR_SIGMA], par[PAR_B], par[PAR_C])
                Fh[j, s, k] = rolling_force_hydrodynamic(u, qk, R, w, par[PAR_ETA0], par[PAR_ALPHA], Ep)
                bk = hertz_line_half_width(qk, R, E_star)
                b[j, s, k] = bk
                p0[j, s, k] = hertz_line_pressure(qk, R, E_star)
                Fy[j, s, k] = rolling_force_hysteresis(qk, bk, R, w, par[PAR_HYST])
                ws = wR[j] * (ur * Nrm[j, s, k, 0] + uz * Nrm[j, s, k, 1]) - Om * Nrm[j, s, k, 1]
                theta = _viscosity_factor(p0[j, s, k], bk, hk, Phi[j, s, k], v1 - v2, ws, bk, v1, v2, par, tq, wq)
                for i in range(tq.shape[0]):
                    Eta[j, s, k, i] = pressure_viscosity(p0[j, s, k] * np.cos(tq[i]), par[PAR_ETA0] * theta,
                                                         par[PAR_ALPHA], par[PAR_Z], int(par[PAR_PV_MODEL]))
        hrib[j] = 0.0
        Phirib[j] = 0.0
        prib[j] = 0.0
        Etarib[j] = 0.0
        if Qrib[j] > 0.0:
            v1, v2 = _surface_speeds(wR[j], wi - wc, Xrib[j, 0], Xrib[j, 1], cr, cz, ur, uz)
            u = 0.5 * abs(v1 + v2)
            R_end = rib[2]
            # sphere on a locally flat rib: circular Hertz contact, a = (3 Q R / (4 E*))^(1/3) (Johnson 4.22)
            a = (3.0 * Qrib[j] * R_end / (4.0 * E_star)) ** (1.0 / 3.0)
            prib[j] = Qrib[j] / (np.pi * a * a)
            hrib[j] = film_point(u, Qrib[j], R_end, R_end, par[PAR_ETA0], par[PAR_ALPHA], Ep)
            Phirib[j] = solid_load_share(hrib[j], par[PAR_SIGMA_RIB], par[PAR_B_RIB], par[PAR_C_RIB])
            theta = _viscosity_factor(prib[j], 0.0, hrib[j], Phirib[j], v1 - v2, 0.0, a, v1, v2, par, tq, wq)
            Etarib[j] = pressure_viscosity(prib[j], par[PAR_ETA0] * theta, par[PAR_ALPHA], par[PAR_Z],
                                           int(par[PAR_PV_MODEL]))


@kernel
def _slice_friction(wR, Om, Xr, Xz, nr, nz, cr, cz, ur, uz, p0k, bk, hk, phik, eta, Frr, Req, w, par, tq, wq, ev,
                    outer):
    """Add one slice's friction to the roller evaluation vector ``ev`` (module docstring).

    ``eta`` (len(tq),): film viscosity at the pressure of each width point [MPa s]. Returns the
    tangential force F_t [N], the sliding speed s [mm/s] and the rolling-resistance power
    [N mm/s]; the caller splits -F_t s into sliding and drilling.
    """
    v1, v2 = _surface_speeds(wR, Om, Xr, Xz, cr, cz, ur, uz)
    st = v1 - v2
    ws = wR * (ur * nr + uz * nz) - Om * nz                 # spin about n
    ar = -nz                                                 # a = n x e_t in (r, z)
    az = nr
    wroll = wR * (ur * ar + uz * az) - Om * az               # relative rolling about a
    t_transit = 2.0 * bk / max(0.5 * abs(v1 + v2), 1e-300)   # [s]; entrainment 0 -> purely viscous
    # width integral, y = b sin(t), t in (0, pi/2), both halves (|v| is even in y)
    Ft = 0.0
    Mn = 0.0
    for i in range(tq.shape[0]):
        ct = np.cos(tq[i])
        y = bk * np.sin(tq[i])
        p = p0k * ct
        vy = y * ws
        v = np.sqrt(st * st + vy * vy)
        g = traction_per_speed(p, v, hk, phik, eta[i], par[PAR_TAU0], par[PAR_CTAU], par[PAR_MU_S], par[PAR_V_S],
                               par[PAR_G], t_transit)
        dA = 2.0 * w * bk * ct * wq[i]
        Ft -= g * st * dA
        Mn -= g * y * vy * dA
    Mrr = Frr * Req
    sg = 1.0 if wroll > 0.0 else -1.0
    dr = Xr - cr
    dz = Xz - cz
    ev[EV_MU] += Ft * (uz * dr - ur * dz) + Mn * (ur * nr + uz * nz) - sg * Mrr * (ur * ar + uz * az)
    tz = Ft * Xr + Mn * nz - sg * Mrr * az                   # z-moment on the roller
    ev[EV_TZ] += tz
    if outer:
        ev[EV_TOUT] -= tz                                    # reaction on the outer ring
    ev[EV_FT] += Ft
    ev[EV_P0 + 3] -= Mn * ws                                 # spin power (drilling)
    return Ft, st, Mrr * abs(wroll)                          # [N], [mm/s], rolling-resistance power [N mm/s]


@kernel
def roller_friction(j, wR, wc, wi, X, Nrm, Cen, Ax, Xrib, Qrib, p0, b, h, Phi, Fh, Fy, R_eq, w, prib, hrib,
                    Phirib, Eta, Etarib, par, tq, wq, ev):
    """Friction of roller j at roller speed wR and cage speed wc [rad/s]: fills ``ev`` (NEV,).

    ev: moment about the roller axis [N mm], z-moment of the contacts on the roller [N mm],
    z-moment on the outer ring [N mm], tangential contact force [N], then the powers [N mm/s]
    of COMPONENTS.
    """
    for i in range(NEV):
        ev[i] = 0.0
    cr = Cen[j, 0]
    cz = Cen[j, 1]
    ur = Ax[j, 0]
    uz = Ax[j, 1]
    n = p0.shape[2]
    for s in range(2):
        Om = -wc if s == 0 else wi - wc
        F_sum = 0.0     # sum of F_t over the contact [N]
        P_slip = 0.0    # -sum F_t s [N mm/s]
        qs_sum = 0.0    # load-weighted sliding speed [N mm/s / mm]
        q_sum = 0.0
        for k in range(n):
            if p0[j, s, k] <= 0.0:
                continue
            frr = Fh[j, s, k] + Fy[j, s, k]
            Ft, st, prr = _slice_friction(wR, Om, X[j, s, k, 0], X[j, s, k, 1], Nrm[j, s, k, 0], Nrm[j, s, k, 1],
                                          cr, cz, ur, uz, p0[j, s, k], b[j, s, k], h[j, s, k], Phi[j, s, k],
                                          Eta[j, s, k], frr,
                                          R_eq[s, k], w, par, tq, wq, ev, s == 0)
            F_sum += Ft
            P_slip -= Ft * st
            qk = p0[j, s, k] * b[j, s, k]
            qs_sum += qk * st
            q_sum += qk
            if frr > 0.0:
                ev[EV_P0 + 0] += prr * Fh[j, s, k] / frr
                ev[EV_P0 + 1] += prr * Fy[j, s, k] / frr
        if q_sum > 0.0:
            P_rigid = -F_sum * qs_sum / q_sum
            ev[EV_P0 + 2] += P_rigid
            ev[EV_P0 + 3] += P_slip - P_rigid
    if Qrib[j] > 0.0:
        v1, v2 = _surface_speeds(wR, wi - wc, Xrib[j, 0], Xrib[j, 1], cr, cz, ur, uz)
        st = v1 - v2
        a_rib = np.sqrt(Qrib[j] / (np.pi * prib[j]))               # Hertz radius [mm]
        t_transit = 2.0 * a_rib / max(0.5 * abs(v1 + v2), 1e-300)
        g = traction_per_speed(prib[j], abs(st), hrib[j], Phirib[j], Etarib[j], par[PAR_TAU0], par[PAR_CTAU],
                               par[PAR_MU_S], par[PAR_V_S], par[PAR_G], t_transit)
        F = -g * st * Qrib[j] / prib[j]
        ev[EV_MU] += F * (uz * (Xrib[j, 0] - cr) - ur * (Xrib[j, 1] - cz))
        ev[EV_TZ] += F * Xrib[j, 0]
        ev[EV_FT] += F
        ev[EV_P0 + 4] -= F * st
    # drag on the roller (reacted by the housing = outer ring) and the cage pocket force
    FD = par[PAR_DRAG_K] * wc * wc
    rc = cr
    ev[EV_TZ] -= FD * rc
    ev[EV_TOUT] += FD * rc
    ev[EV_P0 + 6] += FD * wc * rc
    Fcage = FD - ev[EV_FT]
    Pc = par[PAR_MU_CAGE] * abs(Fcage) * par[PAR_RHO_M]
    ev[EV_MU] -= Pc if wR > 0.0 else -Pc
    ev[EV_P0 + 5] += Pc * abs(wR)
