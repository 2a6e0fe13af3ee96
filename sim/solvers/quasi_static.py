"""Quasi-static load distribution (MODEL.md 4): unknowns, residuals, Jacobians, Newton.

Unknowns. Inner ring: axial displacement ``delta_a`` along +z (the direction of Fa) and
radial displacement ``delta_r`` along +x (the direction of Fr); its tilt is imposed. Roller j
at azimuth psi_j = 2 pi j / Z, in its meridian plane: shift ``xi`` along its axis (towards
the large end: the roller axial displacement of DATA.md), radial shift ``eta`` along v and
tilt ``theta``. The outer ring is fixed.

Generalised coordinates of one roller and the ring, y = (xi, eta, theta, delta_a, delta_r).
For a contact (slice or rib) with penetration d(y), G = dd/dy; the normal load Q acts on the
roller as the generalised force -Q G (virtual work), and on the ring likewise. The tangent
stiffness is K = w G^T (dq/dd) G for slices (q line load, w slice width) and dQ/dd G G^T
for the rib. Roller equilibrium is solved per roller by Newton; the ring by Newton on the
condensed stiffness K_RR - K_Rq K_qq^-1 K_qR (implicit function theorem), so both levels
converge quadratically up to the neglected geometric stiffness (change of G with y).

Body loads on a loaded roller: centrifugal force m omega_c^2 Dpw/2 along e_r and the
gyroscopic moment I_x omega_R omega_c sin(alpha) (rigid-body dynamics of a roller spinning
about its axis while the cage turns about z). Rollers that the rings do not squeeze (rigid
clearance) are unloaded: the cage holds them and their small centrifugal load on the outer
ring is neglected (documented simplification; the dynamic solver treats them fully).

Iterative kernels return status flags instead of raising (STYLE.md); the wrapper in
:mod:`sim.simulate` decides.
"""
import numpy as np

from sim._jit import kernel
from sim.contact import roller_axes, slice_contact_meridian, hertz_point_load
from sim.solvers.linalg import solve_dense
from sim.elasticity import coupled_slice_loads, coupled_slice_compliance, independent_slice_loads

NY = 5  # generalised coordinates per roller block: xi, eta, theta, delta_a, delta_r


@kernel
def roller_state(pose, ring, phi, cpsi, alpha, Dpw, x, rho, w, race_kind, race_par, R_eq, C, E_star,
                 mode, k_line, rib, has_rib, q, active, tol_d, f, K, Qout):
    """Contact loads, generalised forces and tangent stiffness of one roller.

    Parameters
    ----------
    pose : ndarray (3,)
        xi [mm], eta [mm], theta [rad].
    ring : ndarray (2,)
        delta_a, delta_r of the inner ring [mm].
    phi : float
        Imposed inner-ring rotation in this meridian plane [rad] (tilt * cos(psi)).
    cpsi : float
        cos(psi) of the roller azimuth.
    q, active : ndarray (2, N)
        Line loads [N/mm] and loaded flags per race (0 outer, 1 inner): warm start in, result out.
    f : ndarray (5,)
        Generalised contact forces on roller (0:3) and inner ring (3:5) [N, N mm] (written).
    K : ndarray (5, 5)
        Tangent stiffness [N/mm, N, N mm] (written).
    Qout : ndarray (4,)
        Outer load, inner load, rib load [N], max interference outer + inner [mm] (written).

    Returns
    -------
    bool
        Whether every slice complementarity problem converged.
    """
    n = x.shape[0]
    d = np.empty(n)
    nrm = np.empty((n, 2))
    pts = np.empty((n, 2))
    G = np.zeros((n, NY))
    dq = np.empty(n)
    Jc = np.empty((n, n))
    ur, uz, vr, vz = roller_axes(alpha, pose[2])
    for a in range(NY):
        f[a] = 0.0
        for b in range(NY):
            K[a, b] = 0.0
    ok = True
    dmax_sum = 0.0
    for s in range(2):
        side = 1 - 2 * s
        if s == 0:
            slice_contact_meridian(x, rho, side, pose, alpha, Dpw, race_kind[0], race_par[0], 0.0, 0.0, 0.0,
                                   d, nrm, pts)
        else:
            slice_contact_meridian(x, rho, side, pose, alpha, Dpw, race_kind[1], race_par[1],
                                   ring[1] * cpsi, ring[0], phi, d, nrm, pts)
        dmax = -1e300
        for k in range(n):
            if d[k] > dmax:
                dmax = d[k]
            y = side * rho[k]
            G[k, 0] = nrm[k, 0] * ur + nrm[k, 1] * uz
            G[k, 1] = nrm[k, 0] * vr + nrm[k, 1] * vz
            G[k, 2] = nrm[k, 0] * (x[k] * vr - y * ur) + nrm[k, 1] * (x[k] * vz - y * uz)
            if s == 1:
                G[k, 3] = -nrm[k, 1]
                G[k, 4] = -nrm[k, 0] * cpsi
        dmax_sum += dmax
        qs = q[s]
        act = active[s]
        if mode == 0:
            independent_slice_loads(d, k_line, qs, dq)
            for k in range(n):
                act[k] = qs[k] > 0.0
                if act[k]:
                    for a in range(NY):
                        for b in range(NY):
                            K[a, b] += w * dq[k] * G[k, a] * G[k, b]
        else:
            conv, its = coupled_slice_loads(d, C, w, R_eq[s], E_star, qs, act, tol_d)
            ok = ok and conv
            nact = 0
            for k in range(n):
                if act[k]:
                    nact += 1
            if nact > 0:
                coupled_slice_compliance(C, w, R_eq[s], E_star, qs, act, Jc)
                Gm = np.zeros((n, NY))
                for k in range(n):
                    if act[k]:
                        for a in range(NY):
                            Gm[k, a] = G[k, a]
                X = solve_dense(Jc, Gm)
                for k in range(n):
                    if act[k]:
                        for a in range(NY):
                            for b in range(NY):
                                K[a, b] += w * G[k, a] * X[k, b]
        Qs = 0.0
        for k in range(n):
            Qs += qs[k] * w
            for a in range(NY):
                f[a] -= w * qs[k] * G[k, a]
        Qout[s] = Qs
    Qout[3] = dmax_sum
    # roller-end / rib contact (TRB): sphere (centre cx on the roller axis, radius R_end) on a plane
    Qout[2] = 0.0
    if has_rib:
        cx = rib[0]
        R_end = rib[2]
        sa = np.sin(alpha)
        ca = np.cos(alpha)
        # nominal rib plane (ring coordinates): normal n0 and a point l0
        n0r = rib[3] * sa + rib[4] * ca
        n0z = -rib[3] * ca + rib[4] * sa
        l0r = 0.5 * Dpw + cx * sa + R_end * n0r
        l0z = -cx * ca + R_end * n0z
        # current sphere centre, world then ring coordinates
        cr = 0.5 * Dpw + pose[0] * sa + pose[1] * ca + cx * ur
        cz = -pose[0] * ca + pose[1] * sa + cx * uz
        tr = cr - ring[1] * cpsi
        tz = cz - ring[0]
        cp = np.cos(phi)
        sp = np.sin(phi)
        lr = cp * tr + sp * tz
        lz = -sp * tr + cp * tz
        drib = (lr - l0r) * n0r + (lz - l0z) * n0z + R_end
        nwr = cp * n0r - sp * n0z
        nwz = sp * n0r + cp * n0z
        Qr, dQ = hertz_point_load(drib, R_end, E_star)
        g = np.empty(NY)
        g[0] = nwr * ur + nwz * uz
        g[1] = nwr * vr + nwz * vz
        g[2] = cx * (nwr * vr + nwz * vz)
        g[3] = -nwz
        g[4] = -nwr * cpsi
        for a in range(NY):
            f[a] -= Qr * g[a]
            for b in range(NY):
                K[a, b] += dQ * g[a] * g[b]
        Qout[2] = Qr
    return ok


@kernel
def solve_roller(pose, ring, phi, cpsi, body, alpha, Dpw, x, rho, w, race_kind, race_par, R_eq, C, E_star,
                 mode, k_line, rib, has_rib, q, active, tol, max_iter, f, K, Qout):
    """Equilibrium of one roller for a given inner-ring position (Newton with line search).

    Parameters
    ----------
    body : ndarray (3,)
        Centrifugal force [N] (along e_r), gyroscopic moment [N mm], roller length scale [mm].
    tol : float
        Relative force tolerance.

    Returns
    -------
    (status, iterations): status 1 converged and loaded, 2 unloaded (rigid clearance),
    0 not converged.
    """
    Lscale = body[2]
    R = np.empty(3)
    trial = np.empty(3)
    ftmp = np.empty(NY)
    Ktmp = np.empty((NY, NY))
    Qtmp = np.empty(4)
    have_state = False  # the accepted line-search trial already holds the state at ``pose``
    ok = True
    for it in range(max_iter):
        if not have_state:
            ok = roller_state(pose, ring, phi, cpsi, alpha, Dpw, x, rho, w, race_kind, race_par, R_eq, C, E_star,
                              mode, k_line, rib, has_rib, q, active, 1e-13, f, K, Qout)
        have_state = False
        if Qout[3] <= 0.0:
            # rings do not squeeze this roller: unloaded, held by the cage
            for a in range(NY):
                f[a] = 0.0
                for b in range(NY):
                    K[a, b] = 0.0
            for k in range(q.shape[1]):
                q[0, k] = 0.0
                q[1, k] = 0.0
                active[0, k] = False
                active[1, k] = False
            Qout[0] = 0.0
            Qout[1] = 0.0
            Qout[2] = 0.0
            return 2, it
        if Qout[0] <= 0.0 or Qout[1] <= 0.0:
            # touching one race only: centre it radially between both (rigid interference balance)
            dmax = np.empty(2)
            dtmp = np.empty(x.shape[0])
            ntmp = np.empty((x.shape[0], 2))
            ptmp = np.empty((x.shape[0], 2))
            slice_contact_meridian(x, rho, 1, pose, alpha, Dpw, race_kind[0], race_par[0], 0.0, 0.0, 0.0,
                                   dtmp, ntmp, ptmp)
            dmax[0] = dtmp.max()
            slice_contact_meridian(x, rho, -1, pose, alpha, Dpw, race_kind[1], race_par[1],
                                   ring[1] * cpsi, ring[0], phi, dtmp, ntmp, ptmp)
            dmax[1] = dtmp.max()
            pose[1] += 0.5 * (dmax[1] - dmax[0])
            continue
        ur, uz, vr, vz = roller_axes(alpha, pose[2])
        for a in range(3):
            R[a] = f[a]
        R[0] += body[0] * ur
        R[1] += body[0] * vr
        R[2] += body[1]
        scale = Qout[0] + Qout[1] + Qout[2] + abs(body[0])
        err = max(abs(R[0]), abs(R[1]), abs(R[2]) / Lscale)
        if err <= tol * scale and ok:
            return 1, it
        Kq = K[:3, :3].copy()
        reg = 1e-12 * (Kq[0, 0] + Kq[1, 1] + Kq[2, 2] / (Lscale * Lscale))
        Kq[0, 0] += reg
        Kq[1, 1] += reg
        Kq[2, 2] += reg * Lscale * Lscale
        step = solve_dense(Kq, R)
        # line search on the scaled residual
        t = 1.0
        for ls in range(12):
            for a in range(3):
                trial[a] = pose[a] + t * step[a]
            qs = q.copy()
            acts = active.copy()
            ok_trial = roller_state(trial, ring, phi, cpsi, alpha, Dpw, x, rho, w, race_kind, race_par, R_eq, C,
                                    E_star, mode, k_line, rib, has_rib, qs, acts, 1e-13, ftmp, Ktmp, Qtmp)
            tur, tuz, tvr, tvz = roller_axes(alpha, trial[2])
            e0 = ftmp[0] + body[0] * tur
            e1 = ftmp[1] + body[0] * tvr
            e2 = (ftmp[2] + body[1]) / Lscale
            if max(abs(e0), abs(e1), abs(e2)) < err or ls == 11:
                break
            t *= 0.5
        for a in range(3):
            pose[a] = trial[a]
        q[:, :] = qs
        active[:, :] = acts
        f[:] = ftmp
        K[:, :] = Ktmp
        Qout[:] = Qtmp
        ok = ok_trial
        have_state = True
    return 0, max_iter


@kernel
def solve_bearing(Fa, Fr, tilt, body, alpha, Dpw, Z, x, rho, w, race_kind, race_par, R_eq, C, E_star,
                  mode, k_line, rib, has_rib, tol, max_iter, roller_max_iter, ring0,
                  poses, q, active, Q, Qrib, info):
    """Inner-ring equilibrium under Fa, Fr and an imposed tilt (Newton on the condensed stiffness).

    Parameters
    ----------
    Fa, Fr : float
        Axial load along +z and radial load along +x on the inner ring [N].
    tilt : float
        Imposed inner-ring tilt about the y axis [rad].
    body : ndarray (3,)
        Centrifugal force [N], gyroscopic moment [N mm], length scale [mm] of a loaded roller.
    ring0 : ndarray (2,)
        Start value of (delta_a, delta_r) [mm]; the solution is written back.
    poses : ndarray (Z, 3)
        Roller poses (warm start in, solution out).
    q, active : ndarray (Z, 2, N)
        Slice line loads [N/mm] and loaded flags per roller and race (0 outer, 1 inner).
    Q : ndarray (Z, 2)
        Roller-raceway loads [N] (written). Qrib : ndarray (Z,) rib loads [N] (written).
    info : ndarray (5,)
        iterations, force residual axial [N], radial [N], number of unconverged roller
        classes, number of loaded roller classes (written).

    Returns
    -------
    bool
        converged.
    """
    symmetric = Fr == 0.0 and tilt == 0.0
    nz = Z // 2 + 1  # azimuth classes: roller j and Z - j see the same (cos psi)
    if symmetric:
        nz = 1
    ring = ring0.copy()
    f = np.empty(NY)
    K = np.empty((NY, NY))
    Qo = np.empty(4)
    Fscale = max(Fa, Fr)
    converged = False
    it_ring = 0
    Fres = np.zeros(2)
    Kc = np.zeros((2, 2))
    status = np.zeros(Z, dtype=np.int64)
    ring_prev = ring.copy()
    err_prev = np.inf
    backtracks = 0
    for it_ring in range(max_iter):
        Fres[0] = Fa
        Fres[1] = Fr
        Kc[:, :] = 0.0
        nbad = 0
        nload = 0
        for j in range(nz):
            psi = 2.0 * np.pi * j / Z
            cpsi = np.cos(psi)
            mult = 1.0
            if symmetric:
                mult = float(Z)
            elif j > 0 and 2 * j != Z:
                mult = 2.0
            st, its = solve_roller(poses[j], ring, tilt * cpsi, cpsi, body, alpha, Dpw, x, rho, w, race_kind,
                                   race_par, R_eq, C, E_star, mode, k_line, rib, has_rib, q[j], active[j],
                                   tol * 0.1, roller_max_iter, f, K, Qo)
            status[j] = st
            if st == 0:
                nbad += 1
            if st == 1:
                nload += 1
            Q[j, 0] = Qo[0]
            Q[j, 1] = Qo[1]
            Qrib[j] = Qo[2]
            Fres[0] += mult * f[3]
            Fres[1] += mult * f[4]
            if st == 1:
                Kqq = K[:3, :3].copy()
                Lscale = body[2]
                reg = 1e-12 * (Kqq[0, 0] + Kqq[1, 1] + Kqq[2, 2] / (Lscale * Lscale))
                Kqq[0, 0] += reg
                Kqq[1, 1] += reg
                Kqq[2, 2] += reg * Lscale * Lscale
                X = solve_dense(Kqq, K[:3, 3:].copy())
                for a in range(2):
                    for b in range(2):
                        s = K[3 + a, 3 + b]
                        for c in range(3):
                            s -= K[3 + a, c] * X[c, b]
                        Kc[a, b] += mult * s
        if symmetric:
            Fres[1] = 0.0  # delta_r = 0 by symmetry; the radial sum of one roller class is not a residual
        err = max(abs(Fres[0]), abs(Fres[1]))
        info[1] = Fres[0]
        info[2] = Fres[1]
        if err <= tol * Fscale and nbad == 0:
            converged = True
            break
        # backtracking line search on the ring residual (load can jump between rollers under tilt)
        if (err > err_prev or nbad > 0) and backtracks < 30:
            backtracks += 1
            ring[0] = ring_prev[0] + 0.5 * (ring[0] - ring_prev[0])
            ring[1] = ring_prev[1] + 0.5 * (ring[1] - ring_prev[1])
            continue
        if nbad > 0:
            break  # a roller equilibrium failed: report the case as not converged
        backtracks = 0
        err_prev = err
        ring_prev[0] = ring[0]
        ring_prev[1] = ring[1]
        # Newton step on the ring (delta_r frozen in the symmetric case); with no roller
        # squeezed yet, push the ring further along Fa (bounded by the roller size)
        if symmetric:
            if Kc[0, 0] <= 0.0:
                ring[0] = 2.0 * ring[0] + 1e-4
                if ring[0] > body[2]:
                    break
                continue
            step0 = Fres[0] / Kc[0, 0]
            step1 = 0.0
        else:
            det = Kc[0, 0] * Kc[1, 1] - Kc[0, 1] * Kc[1, 0]
            if nload < 2 or abs(det) <= 1e-14 * (Kc[0, 0] * Kc[1, 1] + 1e-300):
                ring[0] = 2.0 * ring[0] + 1e-4
                if ring[0] > body[2]:
                    break
                continue
            step0 = (Kc[1, 1] * Fres[0] - Kc[0, 1] * Fres[1]) / det
            step1 = (-Kc[1, 0] * Fres[0] + Kc[0, 0] * Fres[1]) / det
        # limit the step to the current approach scale (contacts are stiffening)
        lim = 0.5 * abs(ring[0]) + 2e-3
        sc = 1.0
        if abs(step0) > lim:
            sc = lim / abs(step0)
        if abs(step1) > lim:
            sc = min(sc, lim / abs(step1))
        ring[0] += sc * step0
        ring[1] += sc * step1
    # results of the last state
    ring0[0] = ring[0]
    ring0[1] = ring[1]
    info[0] = it_ring + 1
    nb = 0
    nl = 0
    for j in range(nz):
        if status[j] == 0:
            nb += 1
        if status[j] == 1:
            nl += 1
    info[3] = nb
    info[4] = nl
    # fill the rollers of the other azimuths from their classes
    for j in range(Z):
        src = j
        if symmetric:
            src = 0
        elif j > Z // 2:
            src = Z - j
        if src != j:
            for a in range(3):
                poses[j, a] = poses[src, a]
            for s in range(2):
                Q[j, s] = Q[src, s]
                for k in range(x.shape[0]):
                    q[j, s, k] = q[src, s, k]
                    active[j, s, k] = active[src, s, k]
            Qrib[j] = Qrib[src]
    return converged
