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

from sim._jit import kernel
from sim.contact import roller_axes, slice_contact_meridian, hertz_line_half_width, hertz_line_pressure
from sim.ehl import (film_line, film_point, film_temperature_rise, flash_temperature_rise, solid_load_share,
                     pressure_viscosity, roelands_index, rolling_force_hydrodynamic, rolling_force_hysteresis, traction_per_speed)

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
def contact_frames(poses, ring, tilt, alpha, Dpw, x, rho, race_kind, race_par, rib, X, Nrm, Cen, Ax, Xrib):
    """Contact points and normals of every slice, roller centres and axes at the solved state.

    Parameters
    ----------
    poses : ndarray (Z, 3)
        Roller xi [mm], eta [mm], theta [rad] (sim.solvers.quasi_static).
    ring : ndarray (2,)
        Inner-ring axial and radial displacement [mm].
    tilt : float
        Imposed inner-ring tilt [rad].
    X, Nrm : ndarray (Z, 2, N, 2)
        Contact points [mm] and unit normals into the ring, (r, z) (written).
    Cen, Ax : ndarray (Z, 2) and (Z, 4)
        Roller centres [mm] and axes (u'_r, u'_z, v'_r, v'_z) (written).
    Xrib : ndarray (Z, 2)
        Roller-end / rib contact point [mm] (written; TRB only).
    """
    Z = poses.shape[0]
    n = x.shape[0]
    d = np.empty(n)
    sa = np.sin(alpha)
    ca = np.cos(alpha)
    for j in range(Z):
        psi = 2.0 * np.pi * j / Z
        cpsi = np.cos(psi)
        phi = tilt * cpsi
        pose = poses[j]
        ur, uz, vr, vz = roller_axes(alpha, pose[2])
        Cen[j, 0] = 0.5 * Dpw + pose[0] * sa + pose[1] * ca
        Cen[j, 1] = -pose[0] * ca + pose[1] * sa
        Ax[j, 0] = ur
        Ax[j, 1] = uz
        Ax[j, 2] = vr
        Ax[j, 3] = vz
        slice_contact_meridian(x, rho, 1, pose, alpha, Dpw, race_kind[0], race_par[0], 0.0, 0.0, 0.0,
                               d, Nrm[j, 0], X[j, 0])
        slice_contact_meridian(x, rho, -1, pose, alpha, Dpw, race_kind[1], race_par[1],
                               ring[1] * cpsi, ring[0], phi, d, Nrm[j, 1], X[j, 1])
        ex = rib[0] + rib[2] * rib[3]
        ey = rib[2] * rib[4]
        Xrib[j, 0] = Cen[j, 0] + ex * ur + ey * vr
        Xrib[j, 1] = Cen[j, 1] + ex * uz + ey * vz


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
    (sim.ehl.flash_temperature_rise, film_temperature_rise), with the viscosity at the raised
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
        lo, hi, flo, fhi, side = _illinois(lo, hi, flo, fhi, x, fx, side)
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


@kernel
def _widen(lo, hi, flo, fhi):
    """One step of bracketing the root of a falling function: move the interval (lo, hi) by
    twice its span towards the root. Returns (lo, hi, flo, fhi, x, x_is_hi): x is the new
    end, whose function value the caller computes and stores in flo or fhi."""
    span = hi - lo
    if flo > 0.0:          # both ends positive: the root lies above
        return hi, hi + 2.0 * span, fhi, fhi, hi + 2.0 * span, True
    return lo - 2.0 * span, lo, flo, flo, lo - 2.0 * span, False


@kernel
def _illinois(lo, hi, flo, fhi, x, fx, side):
    """Illinois update of a bracket (lo, hi) with the new point (x, fx) (Dowell & Jarratt 1971):
    regula falsi that halves the kept end's value when the same end is kept twice.
    Returns (lo, hi, flo, fhi, side)."""
    if fx * fhi > 0.0:
        if side == -1:
            flo *= 0.5
        return lo, x, flo, fx, -1
    if side == 1:
        fhi *= 0.5
    return x, hi, fx, fhi, 1


@kernel
def _solve_roller_speed(j, w0, wc, wi, X, Nrm, Cen, Ax, Xrib, Qrib, p0, b, h, Phi, Fh, Fy, R_eq, w, prib, hrib,
                        Phirib, Eta, Etarib, par, tq, wq, ev, tol_M, max_iter):
    """omega_R of roller j with zero moment about its axis (bracketing + Illinois regula falsi).

    Returns (omega_R [rad/s], converged). M(omega_R) falls with omega_R: more spin, more drag.
    """
    lo = 0.9 * w0
    hi = 1.1 * w0
    roller_friction(j, lo, wc, wi, X, Nrm, Cen, Ax, Xrib, Qrib, p0, b, h, Phi, Fh, Fy, R_eq, w, prib, hrib,
                    Phirib, Eta, Etarib, par, tq, wq, ev)
    flo = ev[EV_MU]
    roller_friction(j, hi, wc, wi, X, Nrm, Cen, Ax, Xrib, Qrib, p0, b, h, Phi, Fh, Fy, R_eq, w, prib, hrib,
                    Phirib, Eta, Etarib, par, tq, wq, ev)
    fhi = ev[EV_MU]
    for grow in range(max_iter):
        if flo * fhi <= 0.0:
            break
        lo, hi, flo, fhi, x, x_is_hi = _widen(lo, hi, flo, fhi)
        roller_friction(j, x, wc, wi, X, Nrm, Cen, Ax, Xrib, Qrib, p0, b, h, Phi, Fh, Fy, R_eq, w, prib, hrib,
                        Phirib, Eta, Etarib, par, tq, wq, ev)
        if x_is_hi:
            fhi = ev[EV_MU]
        else:
            flo = ev[EV_MU]
    if flo * fhi > 0.0:
        return w0, False
    side = 0
    x = lo
    for it in range(max_iter):
        x = hi - fhi * (hi - lo) / (fhi - flo)
        roller_friction(j, x, wc, wi, X, Nrm, Cen, Ax, Xrib, Qrib, p0, b, h, Phi, Fh, Fy, R_eq, w, prib, hrib,
                        Phirib, Eta, Etarib, par, tq, wq, ev)
        fx = ev[EV_MU]
        if abs(fx) <= tol_M:
            return x, True
        lo, hi, flo, fhi, side = _illinois(lo, hi, flo, fhi, x, fx, side)
    return x, False


@kernel
def _cage_moment(wc, wi, wR, active, weight, X, Nrm, Cen, Ax, Xrib, Qrib, p0, b, h, Phi, Fh, Fy, R_eq, w, prib,
                 hrib, Phirib, Eta, Etarib, par, tq, wq, ev, tol_M, max_iter, totals):
    """Sum of the z-moments on all rollers at cage speed wc, each roller at its own moment balance.

    wR (Z,) holds start values in and solved speeds out; ``totals`` (NEV,) gets the weighted
    sums of the roller evaluation vectors. Returns (moment [N mm], all rollers converged).
    """
    ok = True
    for i in range(NEV):
        totals[i] = 0.0
    for j in range(wR.shape[0]):
        if not active[j]:
            continue
        wj, conv = _solve_roller_speed(j, wR[j], wc, wi, X, Nrm, Cen, Ax, Xrib, Qrib, p0, b, h, Phi, Fh, Fy,
                                       R_eq, w, prib, hrib, Phirib, Eta, Etarib, par, tq, wq, ev, tol_M, max_iter)
        ok = ok and conv
        wR[j] = wj
        roller_friction(j, wj, wc, wi, X, Nrm, Cen, Ax, Xrib, Qrib, p0, b, h, Phi, Fh, Fy, R_eq, w, prib, hrib,
                        Phirib, Eta, Etarib, par, tq, wq, ev)
        for i in range(NEV):
            totals[i] += weight[j] * ev[i]
    return totals[EV_TZ], ok


@kernel
def solve_kinematics(wc0, wi, wR, active, weight, X, Nrm, Cen, Ax, Xrib, Qrib, p0, b, h, Phi, Fh, Fy, R_eq, w,
                     prib, hrib, Phirib, Eta, Etarib, par, tq, wq, tol_M, tol_T, max_iter, totals):
    """Cage speed with zero z-moment on the cage and roller speeds with zero spin moment.

    Parameters
    ----------
    wc0 : float
        Start value, the rolling cage speed (2.20) [rad/s]. wi: inner-ring speed [rad/s].
    wR : ndarray (Z,)
        Roller speeds [rad/s]: start values in, solution out.
    active : ndarray (Z,) bool
        Rollers that carry load (the others keep rolling speeds and add nothing).
    weight : ndarray (Z,)
        Multiplicity of each solved roller (Z for the one roller of a symmetric case, else 1).
    tol_M, tol_T : float
        Absolute tolerances of the roller and cage moment balances [N mm].
    totals : ndarray (NEV,)
        Bearing sums of the roller evaluation vectors at the solution (written).

    Returns
    -------
    (omega_c [rad/s], converged)
    """
    ev = np.empty(NEV)
    lo = 0.95 * wc0
    hi = 1.05 * wc0
    flo, ok = _cage_moment(lo, wi, wR, active, weight, X, Nrm, Cen, Ax, Xrib, Qrib, p0, b, h, Phi, Fh, Fy, R_eq,
                            w, prib, hrib, Phirib, Eta, Etarib, par, tq, wq, ev, tol_M, max_iter, totals)
    fhi, ok = _cage_moment(hi, wi, wR, active, weight, X, Nrm, Cen, Ax, Xrib, Qrib, p0, b, h, Phi, Fh, Fy, R_eq,
                            w, prib, hrib, Phirib, Eta, Etarib, par, tq, wq, ev, tol_M, max_iter, totals)
    for grow in range(max_iter):
        if flo * fhi <= 0.0:
            break
        lo, hi, flo, fhi, x, x_is_hi = _widen(lo, hi, flo, fhi)
        fx, ok = _cage_moment(x, wi, wR, active, weight, X, Nrm, Cen, Ax, Xrib, Qrib, p0, b, h, Phi, Fh, Fy, R_eq,
                              w, prib, hrib, Phirib, Eta, Etarib, par, tq, wq, ev, tol_M, max_iter, totals)
        if x_is_hi:
            fhi = fx
        else:
            flo = fx
    if flo * fhi > 0.0:
        return wc0, False
    side = 0
    x = lo
    for it in range(max_iter):
        x = hi - fhi * (hi - lo) / (fhi - flo)
        fx, ok = _cage_moment(x, wi, wR, active, weight, X, Nrm, Cen, Ax, Xrib, Qrib, p0, b, h, Phi, Fh, Fy, R_eq,
                              w, prib, hrib, Phirib, Eta, Etarib, par, tq, wq, ev, tol_M, max_iter, totals)
        if abs(fx) <= tol_T:
            return x, ok
        lo, hi, flo, fhi, side = _illinois(lo, hi, flo, fhi, x, fx, side)
    return x, False


@kernel
def _kinematic_residuals(wc, wi, wR, active, weight, X, Nrm, Cen, Ax, Xrib, Qrib, p0, b, h, Phi, Fh, Fy, R_eq, w,
                         prib, hrib, Phirib, Eta, Etarib, par, tq, wq, ev, M, T, totals):
    """Roller spin moments M (Z,) and cage z-moments per roller T (Z,) [N mm] at (wR, wc); sums into totals."""
    for i in range(NEV):
        totals[i] = 0.0
    for j in range(wR.shape[0]):
        M[j] = 0.0
        T[j] = 0.0
        if not active[j]:
            continue
        roller_friction(j, wR[j], wc, wi, X, Nrm, Cen, Ax, Xrib, Qrib, p0, b, h, Phi, Fh, Fy, R_eq, w, prib, hrib,
                        Phirib, Eta, Etarib, par, tq, wq, ev)
        M[j] = ev[EV_MU]
        T[j] = weight[j] * ev[EV_TZ]
        for i in range(NEV):
            totals[i] += weight[j] * ev[i]


@kernel
def solve_kinematics_newton(wc, presolve, wi, wR, active, weight, X, Nrm, Cen, Ax, Xrib, Qrib, p0, b, h, Phi, Fh,
                            Fy, R_eq, w, prib, hrib, Phirib, Eta, Etarib, par, tq, wq, tol_M, tol_T, max_iter, totals):
    """Newton on all roller speeds and the cage speed together (arrow-shaped Jacobian).

    Roller j's spin moment depends on its own speed and the cage speed only, so the Jacobian
    is a diagonal block plus one row and column; it is built by forward differences (step
    1e-7 of the speed, a relative step near the square root of the double precision) and
    eliminated in O(Z). Backtracking on the scaled residual norm keeps the iteration
    monotone. Same arguments and return value as :func:`solve_kinematics`; wR and wc are
    start values (rolling kinematics or a previous solution). ``presolve``: first bring every
    roller to its own moment balance at the start cage speed (for a start far away, such as
    rolling kinematics of a crowned roller).
    """
    Z = wR.shape[0]
    ev = np.empty(NEV)
    M = np.zeros(Z)
    T = np.zeros(Z)
    M2 = np.zeros(Z)
    T2 = np.zeros(Z)
    dMdw = np.zeros(Z)
    dTdw = np.zeros(Z)
    dMdc = np.zeros(Z)
    dTdc = np.zeros(Z)
    dw = np.zeros(Z)
    wtrial = np.zeros(Z)
    tmp = np.zeros(NEV)
    # start: every roller at its own moment balance for the start cage speed (1-D, bracketed)
    for j in range(Z):
        if presolve and active[j]:
            wR[j], conv = _solve_roller_speed(j, wR[j], wc, wi, X, Nrm, Cen, Ax, Xrib, Qrib, p0, b, h, Phi, Fh, Fy,
                                              R_eq, w, prib, hrib, Phirib, Eta, Etarib, par, tq, wq, ev, tol_M, max_iter)
    _kinematic_residuals(wc, wi, wR, active, weight, X, Nrm, Cen, Ax, Xrib, Qrib, p0, b, h, Phi, Fh, Fy, R_eq, w,
                         prib, hrib, Phirib, Eta, Etarib, par, tq, wq, ev, M, T, totals)
    for it in range(max_iter):
        norm = (T.sum() / tol_T) ** 2
        worst = abs(T.sum()) / tol_T
        for j in range(Z):
            norm += (M[j] / tol_M) ** 2
            worst = max(worst, abs(M[j]) / tol_M)
        if worst <= 1.0:
            return wc, True
        # Jacobian by forward differences
        hc = 1e-7 * abs(wc)
        _kinematic_residuals(wc + hc, wi, wR, active, weight, X, Nrm, Cen, Ax, Xrib, Qrib, p0, b, h, Phi, Fh, Fy,
                             R_eq, w, prib, hrib, Phirib, Eta, Etarib, par, tq, wq, ev, M2, T2, tmp)
        for j in range(Z):
            dMdc[j] = (M2[j] - M[j]) / hc
            dTdc[j] = (T2[j] - T[j]) / hc
        for j in range(Z):
            wtrial[j] = wR[j]
        for j in range(Z):
            if not active[j]:
                continue
            hj = 1e-7 * abs(wR[j])
            wtrial[j] = wR[j] + hj
            roller_friction(j, wtrial[j], wc, wi, X, Nrm, Cen, Ax, Xrib, Qrib, p0, b, h, Phi, Fh, Fy, R_eq, w,
                            prib, hrib, Phirib, Eta, Etarib, par, tq, wq, ev)
            wtrial[j] = wR[j]
            dMdw[j] = (ev[EV_MU] - M[j]) / hj
            dTdw[j] = (weight[j] * ev[EV_TZ] - T[j]) / hj
        # eliminate the roller rows: dw_j = -(M_j + dMdc_j dc) / dMdw_j
        num = T.sum()
        den = dTdc.sum()
        for j in range(Z):
            if active[j] and dMdw[j] != 0.0:
                num -= dTdw[j] * M[j] / dMdw[j]
                den -= dTdw[j] * dMdc[j] / dMdw[j]
        if den == 0.0:
            return wc, False
        dc = -num / den
        for j in range(Z):
            dw[j] = -(M[j] + dMdc[j] * dc) / dMdw[j] if active[j] and dMdw[j] != 0.0 else 0.0
        step = 1.0
        accepted = False
        for ls in range(30):
            for j in range(Z):
                wtrial[j] = wR[j] + step * dw[j]
            _kinematic_residuals(wc + step * dc, wi, wtrial, active, weight, X, Nrm, Cen, Ax, Xrib, Qrib, p0, b, h,
                                 Phi, Fh, Fy, R_eq, w, prib, hrib, Phirib, Eta, Etarib, par, tq, wq, ev, M2, T2, tmp)
            trial = (T2.sum() / tol_T) ** 2
            for j in range(Z):
                trial += (M2[j] / tol_M) ** 2
            if trial < norm:
                accepted = True
                break
            step *= 0.5
        if not accepted:
            return wc, False
        wc += step * dc
        for j in range(Z):
            wR[j] = wtrial[j]
            M[j] = M2[j]
            T[j] = T2[j]
        for i in range(NEV):
            totals[i] = tmp[i]
    return wc, False


class FrictionModel:
    """Friction parameters of one bearing, lubricant and friction config; evaluates solved cases.

    Parameters
    ----------
    geometry : sim.geometry.Geometry
    E_star : float
        Contact modulus [MPa].
    lubricant : sim.lubricant.Lubricant
    friction : mapping
        The ``friction`` config node (conf/friction/default.yaml).
    surface : mapping
        ``bearing.surface``: sigma [um], B_ZH, C_ZH (and the rib's for a TRB).
    """

    def __init__(self, geometry, E_star, lubricant, friction, surface, material):
        from sim.ehl import FILM_FORMULAS, PRESSURE_VISCOSITY_MODELS
        from sim.simulation import InputError, _check_range

        g = self.geometry = geometry
        self.E_star = E_star
        self.lubricant = lubricant
        film = str(friction["film_thickness"])
        if film not in FILM_FORMULAS:
            raise InputError(f"friction.film_thickness = {film!r} is not one of {sorted(FILM_FORMULAS)}")
        kin = str(friction["kinematics"])
        if kin not in ("traction", "rolling"):
            raise InputError(f"friction.kinematics = {kin!r} is not one of ['rolling', 'traction']")
        self.traction_kinematics = kin == "traction"
        npts = friction["width_points"]
        if not (isinstance(npts, (int, np.integer)) and 2 <= int(npts) <= 64):
            raise InputError(f"friction.width_points = {npts!r} is outside the allowed range [2, 64] (integer)")
        t, wt = np.polynomial.legendre.leggauss(int(npts))
        self.tq = 0.25 * np.pi * (t + 1.0)          # nodes on (0, pi/2)
        self.wq = 0.25 * np.pi * wt
        self.tolerance = _check_range("friction.tolerance", friction["tolerance"], 1e-14, 1e-2, low_open=True)
        self.max_iterations = int(_check_range("friction.max_iterations", friction["max_iterations"], 1, 10000))
        self.seed_tolerance_factor = _check_range("friction.seed_tolerance_factor", friction["seed_tolerance_factor"],
                                                  1.0, 1e4)
        drag = friction["drag"]
        model = str(drag["model"])
        if model not in ("none", "roller_drag"):
            raise InputError(f"friction.drag.model = {model!r} is not one of ['none', 'roller_drag']")
        par = np.zeros(NPAR)
        par[PAR_ALPHA] = lubricant.pressure_viscosity
        par[PAR_PV_MODEL] = PRESSURE_VISCOSITY_MODELS[lubricant.pressure_viscosity_model]
        par[PAR_TAU0] = lubricant.limiting_shear_stress_0
        par[PAR_CTAU] = lubricant.limiting_shear_coefficient
        par[PAR_G] = lubricant.shear_modulus
        par[PAR_MU_S] = _check_range("friction.solid_friction_coefficient", friction["solid_friction_coefficient"], 0.0, 1.0)
        par[PAR_V_S] = 1e3 * _check_range("friction.solid_slip_velocity", friction["solid_slip_velocity"], 0.0, 1.0, low_open=True)
        par[PAR_HYST] = _check_range("friction.hysteresis_loss_factor", friction["hysteresis_loss_factor"], 0.0, 0.5)
        par[PAR_MU_CAGE] = _check_range("friction.cage_friction_coefficient", friction["cage_friction_coefficient"], 0.0, 1.0)
        sigma = 1e-3 * _check_range("bearing.surface.sigma", surface["sigma"], 0.0, 10.0, low_open=True)
        par[PAR_SIGMA] = sigma
        par[PAR_B] = _check_range("bearing.surface.B_ZH", surface["B_ZH"], 0.0, 20.0, low_open=True)
        par[PAR_C] = _check_range("bearing.surface.C_ZH", surface["C_ZH"], 0.0, 5.0, low_open=True)
        if g.type == "TRB":
            for key in ("sigma_rib", "B_ZH_rib", "C_ZH_rib"):
                if key not in surface:
                    raise InputError(f"bearing.surface.{key} is missing (roller-end / rib mixed friction of a TRB)")
            par[PAR_SIGMA_RIB] = 1e-3 * _check_range("bearing.surface.sigma_rib", surface["sigma_rib"], 0.0, 10.0, low_open=True)
            par[PAR_B_RIB] = _check_range("bearing.surface.B_ZH_rib", surface["B_ZH_rib"], 0.0, 20.0, low_open=True)
            par[PAR_C_RIB] = _check_range("bearing.surface.C_ZH_rib", surface["C_ZH_rib"], 0.0, 5.0, low_open=True)
        par[PAR_THERMAL] = 1.0 if bool(friction["thermal"]) else 0.0
        par[PAR_K_OIL] = lubricant.thermal_conductivity
        if friction["thermal"]:
            for key in ("thermal_conductivity", "specific_heat"):
                if key not in material:
                    raise InputError(f"material.{key} is missing (flash temperature of friction.thermal)")
            k_s = _check_range("material.thermal_conductivity", material["thermal_conductivity"], 1.0, 500.0)
            c_s = _check_range("material.specific_heat", material["specific_heat"], 100.0, 5000.0)
            par[PAR_K_STEEL] = k_s
            par[PAR_KAPPA_STEEL] = 1e6 * k_s / (float(material["density"]) * c_s)     # mm^2/s
        par[PAR_DT_TOL] = _check_range("friction.temperature_tolerance", friction["temperature_tolerance"], 0.0, 10.0,
                                       low_open=True)
        par[PAR_EPRIME] = 2.0 * E_star
        par[PAR_FILM] = FILM_FORMULAS[film]
        par[PAR_RHO_M] = 0.5 * g.Dwe
        self.drag_factor = 0.0
        if model == "roller_drag":
            cd = _check_range("friction.drag.drag_coefficient", drag["drag_coefficient"], 0.0, 10.0)
            X = _check_range("friction.drag.oil_volume_fraction", drag["oil_volume_fraction"], 0.0, 1.0)
            # F_D = 1/2 rho X C_D Dwe Lwe (omega_c Dpw/2)^2; rho [t/mm^3] = 1e-12 rho [kg/m^3]
            self.drag_factor = 0.5 * X * cd * g.Dwe * g.Lwe * (0.5 * g.Dpw) ** 2 * 1e-12
        self.drag_model = model
        self.par = par

    def evaluate(self, op, raw, start=None):
        """Kinematics, film and friction of one solved case (raw: BearingModel.solve output).

        ``start``: the ``kinematics`` entry of a previous evaluation of the same case (cage and
        roller speeds [rad/s]); the film is then taken at those speeds and one Newton solve
        follows, instead of starting from rolling kinematics.

        Returns a dict of DATA.md outputs in output units (torque N mm, power W, film um,
        cage speed rpm), ``friction_converged``, the cage pocket ``roller_loads`` (Z, 3) [N]
        and ``kinematics`` (omega_c, omega_R (Z,)) [rad/s].
        """
        from sim.kinematics import angular_speed, cage_speed_rolling, roller_speed_rolling

        g = self.geometry
        a = g.arrays
        Z, n = g.Z, g.n_slices
        par = self.par.copy()
        eta0 = self.lubricant.dynamic_viscosity(op.oil_temperature) * 1e-6      # MPa s
        par[PAR_ETA0] = eta0
        par[PAR_BETA] = float(self.lubricant.temperature_viscosity_coefficient(op.oil_temperature))
        par[PAR_Z] = roelands_index(eta0, par[PAR_ALPHA])
        par[PAR_DRAG_K] = self.drag_factor * float(self.lubricant.density(op.oil_temperature))
        X = np.zeros((Z, 2, n, 2))
        Nrm = np.zeros((Z, 2, n, 2))
        Cen = np.zeros((Z, 2))
        Ax = np.zeros((Z, 4))
        Xrib = np.zeros((Z, 2))
        contact_frames(raw["poses"], raw["ring"], np.radians(op.tilt), g.alpha, g.Dpw, a["x"], a["rho"],
                       a["race_kind"], a["race_par"], a["rib"], X, Nrm, Cen, Ax, Xrib)
        q = raw["line_load"]
        Qrib = raw["Q_rib"]
        wi = float(angular_speed(op.speed))
        wc = float(angular_speed(cage_speed_rolling(op.speed, 0.0, g.Dwe, g.Dpw, g.alpha)))
        wR = np.full(Z, float(angular_speed(roller_speed_rolling(op.speed, 0.0, g.Dwe, g.Dpw, g.alpha))))
        if start is not None:
            wc, wR = start[0], start[1].copy()
        load = raw["Q"].sum(axis=1)
        # symmetry: pure axial untilted, every roller alike; untilted, roller j mirrors roller Z - j
        symmetric = op.Fr == 0.0 and op.tilt == 0.0
        mirrored = op.tilt == 0.0
        # rollers below the kinematic tolerance of the most loaded one cannot move the balances
        active = load > self.tolerance * load.max()
        weight = np.ones(Z)
        if symmetric:
            active[1:] = False
            weight[0] = Z
        elif mirrored:
            active[Z // 2 + 1:] = False
            weight[1:(Z + 1) // 2] = 2.0
        shape = (Z, 2, n)
        h, Phi, Fh, Fy, p0, b = (np.zeros(shape) for _ in range(6))
        Eta = np.zeros(shape + (self.tq.shape[0],))
        hrib, Phirib, prib, Etarib = np.zeros(Z), np.zeros(Z), np.zeros(Z), np.zeros(Z)
        totals = np.zeros(NEV)
        ev = np.zeros(NEV)
        mu_ref = max(par[PAR_MU_S], par[PAR_CTAU])
        tol_M = self.tolerance * mu_ref * float(load.max()) * par[PAR_RHO_M]
        tol_T = self.tolerance * mu_ref * float(load.sum()) * 0.5 * g.Dpw
        converged = True
        # film from the speeds of the previous pass: rolling kinematics, then the traction solution
        passes = 2 if self.traction_kinematics and start is None else 1
        for film_pass in range(passes):
            lubrication_state(wR, wc, wi, active, q, Qrib, X, Nrm, Cen, Ax, Xrib, a["R_eq"], g.slice_width, self.E_star,
                              a["rib"], par, self.tq, self.wq, h, Phi, Fh, Fy, p0, b, hrib, Phirib, prib, Eta, Etarib)
            if self.traction_kinematics:
                # a pass followed by another only sets the film of the next: looser tolerance
                loose = self.seed_tolerance_factor if film_pass < passes - 1 else 1.0
                args = (wi, wR, active, weight, X, Nrm, Cen, Ax, Xrib, Qrib, p0, b, h, Phi, Fh, Fy, a["R_eq"],
                        g.slice_width, prib, hrib, Phirib, Eta, Etarib, par, self.tq, self.wq, loose * tol_M,
                        loose * tol_T, self.max_iterations, totals)
                start_c, start_R = wc, wR.copy()
                wc, converged = solve_kinematics_newton(wc, film_pass == 0 and start is None, *args)
                if not converged:   # bracketing is slower but cannot leave the bracket
                    wR[:] = start_R
                    wc, converged = solve_kinematics(start_c, *args)
        if not self.traction_kinematics:
            for j in np.flatnonzero(active):
                roller_friction(j, wR[j], wc, wi, X, Nrm, Cen, Ax, Xrib, Qrib, p0, b, h, Phi, Fh, Fy, a["R_eq"],
                                g.slice_width, prib, hrib, Phirib, Eta, Etarib, par, self.tq, self.wq, ev)
                totals += weight[j] * ev
        # cage pocket friction on each roller, force along v' (module docstring): the friction
        # load the quasi-static balance takes back (BearingModel.solve(op, roller_loads))
        roller_loads = np.zeros((Z, 3))
        for jj in np.flatnonzero(active):
            roller_friction(jj, wR[jj], wc, wi, X, Nrm, Cen, Ax, Xrib, Qrib, p0, b, h, Phi, Fh, Fy, a["R_eq"],
                            g.slice_width, prib, hrib, Phirib, Eta, Etarib, par, self.tq, self.wq, ev)
            F_cage = par[PAR_DRAG_K] * wc * wc - ev[EV_FT]
            roller_loads[jj, 1] = par[PAR_MU_CAGE] * F_cage * np.sign(wR[jj])
        if symmetric:
            wR[:] = wR[0]
            roller_loads[:] = roller_loads[0]
        elif mirrored:
            wR[Z // 2 + 1:] = wR[1:(Z + 1) // 2][::-1]
            roller_loads[Z // 2 + 1:] = roller_loads[1:(Z + 1) // 2][::-1]
        power = totals[EV_P0:EV_P0 + NC]                       # N mm/s
        j = int(np.argmax(load))
        v_roll = np.zeros((2, n))
        v_ring = np.zeros((2, n))
        for s in range(2):
            Om = -wc if s == 0 else wi - wc
            v_roll[s] = wR[j] * (Ax[j, 1] * (X[j, s, :, 0] - Cen[j, 0]) - Ax[j, 0] * (X[j, s, :, 1] - Cen[j, 1]))
            v_ring[s] = Om * X[j, s, :, 0]
        loaded = p0[j] > 0.0
        srr = np.where(loaded, 2.0 * (v_roll - v_ring) / (v_roll + v_ring), np.nan)   # eq. (2.25)
        film = np.where(loaded, h[j] * 1e3, np.nan)                                   # um
        kmax = np.argmax(q[j], axis=1)
        lam = np.array([h[j, s, kmax[s]] / par[PAR_SIGMA] for s in range(2)])
        return {
            "friction_converged": bool(converged),
            "torque": float(totals[EV_TOUT]),
            # breakdown in proportion to each mechanism's power: sums to the outer-ring torque exactly
            # (which itself equals power / omega_i up to the kinematic tolerance, module docstring)
            "torque_component": totals[EV_TOUT] * power / power.sum(),
            "power_loss": float(power.sum()) * 1e-3,
            "srr": srr,
            "film_thickness": film,
            "lambda_ratio": lam,
            "cage_speed": wc * 30.0 / np.pi,
            "roller_loads": roller_loads,
            "kinematics": (wc, wR.copy()),
        }
