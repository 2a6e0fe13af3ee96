"""Roller and cage speeds from the traction balance (MODEL.md 5, thesis 5.4): the nonlinear
solves over the friction kernels of :mod:`sim.physics.friction`.

Unknowns: omega_R,j (roller moment about its axis u' = 0, per roller) and omega_c (cage
moment about z = 0: sum over rollers of the z-moments the contacts exert).
:func:`solve_kinematics_newton` takes Newton steps on all of them at once (roller rows
eliminated); :func:`solve_kinematics` brackets the cage speed, each roller at its own balance
(slower, but it cannot leave the bracket).
"""
import numpy as np

from sim._math.jit import kernel
from sim._math.roots import illinois, widen
from sim.physics.friction import EV_MU, EV_TZ, NEV, roller_friction


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
        lo, hi, flo, fhi, x, x_is_hi = widen(lo, hi, flo, fhi)
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
        lo, hi, flo, fhi, side = illinois(lo, hi, flo, fhi, x, fx, side)
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
        lo, hi, flo, fhi, x, x_is_hi = widen(lo, hi, flo, fhi)
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
        lo, hi, flo, fhi, side = illinois(lo, hi, flo, fhi, x, fx, side)
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
