"""Quasi-static load distribution (MODEL.md 4): unknowns, residuals, Jacobians, Newton.

Unknowns. Inner ring: axial displacement ``delta_a`` along +z (the direction of Fa) and
radial displacement ``delta_r`` along +x (the direction of Fr); its tilt is imposed. Roller j
at azimuth psi_j = 2 pi j / Z, in its meridian plane: shift ``xi`` along its nominal axis u
(towards the large end: the roller axial displacement of DATA.md), radial shift ``eta`` along
the nominal v and tilt ``theta`` (positive turning u towards v). The outer ring is fixed.

Generalised coordinates and forces. The residual of a roller is written in its own tilted
frame: the force along u' and along v' and the moment about its centre (about u' x v' = -e_t,
positive when it turns u' towards v'), so a Newton step is taken in the local chart
y = (a, b, theta, delta_a, delta_r): a translation a u' + b v' of the roller centre (u', v'
of the current tilt; :func:`_local_to_pose` turns it into xi, eta), the tilt and the ring.
For a contact (slice or rib) with penetration d(y), G = dd/dy; the normal load Q acts on the
roller as the generalised force -Q G (virtual work), and on the ring likewise. The tangent
stiffness is the exact Jacobian K = -df/dy:

- material part: w G^T (dq/dd) G for slices (q line load, w slice width, dq/dd the tangent of
  the slice elasticity on the loaded set) and dQ/dd g g^T for the rib;
- geometric part: w sum_k q_k H_k with H_k the second derivative of the penetration: the
  raceway curvature (t.dP/dy_a)(t.dP/dy_b)/r_c (t the profile tangent, r_c = PCR_LB of a
  TSRB arc; zero for a straight TRB cone) plus n . d2P/dtheta2 = -n.(x u' + y v') of the
  turning slice point P (and -c_x n.u' for the rib sphere centre);
- the turning residual frame: d(F.u')/dtheta = F.v' and d(F.v')/dtheta = -F.u' of the
  total roller force F, which vanish at equilibrium except for the follower part of the
  external roller loads.

Solution strategy.

- Roller (:func:`solve_roller`, ring fixed): Newton with the exact Jacobian, each step bounded
  so that no contact penetration changes by more than a fraction of the roller's interference
  (and no long jumps), then a backtracking line search on the roller's potential energy: the
  work of the residual forces along the step (trapezoidal rule) must be positive (Armijo).
  Roller equilibrium is a minimum of the elastic energy minus the work of the body loads, and
  unlike the residual norm that energy does not reward a roller for losing load. An uphill or
  failing Newton direction falls back to Levenberg-Marquardt steps; a full step with poor
  progress is extended, so a roller that misaligned rings push out of a wedge (no loaded
  equilibrium) comes free (unloaded, the cage holds it). A roller without decrease reports
  status 0 and keeps its last accepted state.
- Ring (:func:`solve_bearing`): Newton on the condensed stiffness K_RR - K_Rq K_qq^-1 K_qR
  (implicit function theorem), with the rollers' first-order correction -K_Rq K_qq^-1 R_q of
  their remaining residuals R_q, and the roller poses predicted along the same tangent,
  dq = K_qq^-1 (R_q - K_qR dr), after every ring step. Early ring iterations solve the rollers
  only as accurately as the ring residual needs (inexact Newton, Dembo, Eisenstat & Steihaug
  1982, SIAM J. Numer. Anal. 19(2)); a roller without equilibrium yet is kept while its
  residual is below that level. A ring step without decrease is halved, the rollers restored
  to the accepted iterate and predicted again; the converged state has every roller at the
  final tolerance.
- Axisymmetric case (no radial load, no tilt, equal roller loads): one roller, with the ring's
  axial displacement solved together with it under load control (the roller's share Fa / Z),
  so that a TSRB whose contact migrates to the roller edge keeps its load on the way.
- :meth:`sim.api.simulation.BearingModel.solve` continues from the axisymmetric case in Fr, tilt
  and roller loads when the direct solve fails.

Body loads on a loaded roller: centrifugal force m omega_c^2 Dpw/2 along e_r and the
gyroscopic moment I_x omega_R omega_c sin(alpha) (rigid-body dynamics of a roller spinning
about its axis while the cage turns about z). External roller loads (friction, from
:mod:`sim.physics.friction`): per roller [force along u' towards the large end, force along v',
moment about u' x v'], [N, N, N mm], added to the roller residual like the body loads.
Rollers that the rings do not squeeze (rigid clearance) are unloaded: the cage holds them,
their small centrifugal load on the outer ring is neglected and so is any external load on
them (documented simplification; the dynamic solver treats them fully).

Iterative kernels return status flags instead of raising (STYLE.md); the wrapper in
:mod:`sim.api.simulation` decides.
"""
import numpy as np

from sim._math.jit import kernel
from sim.physics.contact import roller_axes, slice_contact_meridian, hertz_point_load
from sim.physics.elasticity import coupled_slice_loads, coupled_slice_compliance, independent_slice_loads
from sim.geometry import RACE_LENS
from sim._math.linalg import solve_dense

NY = 5  # generalised coordinates per roller block: a (along u'), b (along v'), theta, delta_a, delta_r

# Solver parameters, packed for the kernels by sim.api.simulation.BearingModel from SolverSettings
# (conf/solver/quasi_static.yaml); meaning and units there.
(SP_TOL, SP_MAX_ITER, SP_ROLLER_MAX_ITER, SP_ROLLER_TOL_RATIO, SP_FORCING, SP_TRUST, SP_MAX_STEP,
 SP_BACKTRACKS, SP_RING_STEP) = range(9)
NSP = 9

# Per-roller contact summary written by _roller_state (aux): largest penetration of the outer
# and the inner raceway [mm], rib penetration [mm], rib contact point (r, z) [mm] on the roller
# end and the rib's unit normal (r, z) into the rib (the rib load acts on the roller along -n).
AUX_DMAX_O, AUX_DMAX_I, AUX_DRIB, AUX_RIB_R, AUX_RIB_Z, AUX_RIB_NR, AUX_RIB_NZ = range(7)
NAUX = 7

# Slice deflections are solved to at most this fraction of the roller's deepest penetration:
# its loads are then accurate to ~1e-12 relative, 100x below the final roller tolerance
# (solver.tolerance x roller_tolerance_ratio = 1e-10) also for a lightly loaded roller.
DEFLECTION_TOL_REL = 1e-12
# Relative regularisation of the roller stiffness at round-off level (not a physical limit):
# keeps a rigid-body direction that no contact resists solvable; the step bounds limit the move.
REG = 1e-12
# Sufficient-decrease constant of the backtracking line searches (Armijo; Dennis & Schnabel
# 1996, Numerical Methods for Unconstrained Optimization, 6.3: "a small number, 1e-4").
ARMIJO = 1e-4
# Levenberg-Marquardt fallback of the roller Newton step: damping mu diag(K) starting at
# LM_MU0, raised by LM_FACTOR per try (Marquardt 1963, J. SIAM 11(2): tenfold), LM_TRIES tries
# (mu up to 1e6: a step of ~1e-6 of the undamped one, below the round-off of the residual).
LM_MU0 = 1.0
LM_FACTOR = 10.0
LM_TRIES = 7
# A full roller step that does not halve the residual is extended (doubled while the residual
# keeps falling): Newton converging normally divides it by far more, a roller sliding out of a
# wedge loses ~30 % of its load (and residual) per bounded step (Nocedal & Wright 2006,
# Numerical Optimization, 3.5: extrapolation in a line search).
EXTEND = 0.5


@kernel
def _roller_state(pose, ring, phi, cpsi, alpha, Dpw, x, rho, w, race_kind, race_par, R_eq, C, E_star,
                  mode, k_line, rib, has_rib, q, active, tol_d, f, K, Qout, Gout, aux):
    """Contact loads, generalised forces and exact tangent stiffness of one roller (module docstring).

    Parameters as :func:`roller_state`, and

    Gout : ndarray (2 N + 1, 6)
        dd/dy (columns 0..4) and the penetration d [mm] (column 5) of every slice (outer rows
        0..N-1, inner N..2N-1) and of the rib (row 2N) (written).
    aux : ndarray (NAUX,)
        Contact summary (AUX_* indices) (written).

    Returns
    -------
    bool
        Whether every slice complementarity problem converged.
    """
    n = x.shape[0]
    d = np.empty(n)
    nrm = np.empty((n, 2))
    pts = np.empty((n, 2))
    dq = np.empty(n)
    ur, uz, vr, vz = roller_axes(alpha, pose[2])
    for a in range(NY):
        f[a] = 0.0
        for b in range(NY):
            K[a, b] = 0.0
    ok = True
    dmax_sum = 0.0
    T = np.empty(NY)
    for s in range(2):
        side = 1 - 2 * s
        if s == 0:
            slice_contact_meridian(x, rho, side, pose, alpha, Dpw, race_kind[0], race_par[0], 0.0, 0.0, 0.0,
                                   d, nrm, pts)
        else:
            slice_contact_meridian(x, rho, side, pose, alpha, Dpw, race_kind[1], race_par[1],
                                   ring[1] * cpsi, ring[0], phi, d, nrm, pts)
        G = Gout[s * n:(s + 1) * n]
        dmax = -1e300
        for k in range(n):
            if d[k] > dmax:
                dmax = d[k]
            y = side * rho[k]
            G[k, NY] = d[k]
            G[k, 0] = nrm[k, 0] * ur + nrm[k, 1] * uz
            G[k, 1] = nrm[k, 0] * vr + nrm[k, 1] * vz
            G[k, 2] = nrm[k, 0] * (x[k] * vr - y * ur) + nrm[k, 1] * (x[k] * vz - y * uz)
            if s == 1:
                G[k, 3] = -nrm[k, 1]
                G[k, 4] = -nrm[k, 0] * cpsi
            else:
                G[k, 3] = 0.0
                G[k, 4] = 0.0
        aux[s] = dmax
        dmax_sum += dmax
        qs = q[s]
        act = active[s]
        # material stiffness w G^T (dq/dd) G on the loaded slices
        if mode == 0:
            independent_slice_loads(d, k_line, qs, dq)
            for k in range(n):
                act[k] = qs[k] > 0.0
                if act[k]:
                    for a in range(NY):
                        for b in range(a, NY):
                            K[a, b] += w * dq[k] * G[k, a] * G[k, b]
        else:
            # deflection tolerance: tol_d, and at most DEFLECTION_TOL_REL of the deepest
            # penetration, so that lightly loaded rollers get the same relative accuracy
            conv, its = coupled_slice_loads(d, C, w, R_eq[s], E_star, qs, act,
                                            min(tol_d, DEFLECTION_TOL_REL * max(dmax, 0.0)))
            ok = ok and conv
            m = 0
            for k in range(n):
                if act[k]:
                    m += 1
            if m > 0:
                # dq/dd = J^-1 on the loaded set (sim.physics.elasticity.coupled_slice_compliance)
                Jfull = np.empty((n, n))
                coupled_slice_compliance(C, w, R_eq[s], E_star, qs, act, Jfull)
                idx = np.empty(m, dtype=np.int64)
                m = 0
                for k in range(n):
                    if act[k]:
                        idx[m] = k
                        m += 1
                Jm = np.empty((m, m))
                Gm = np.empty((m, NY))
                for a in range(m):
                    for b in range(m):
                        Jm[a, b] = Jfull[idx[a], idx[b]]
                    for b in range(NY):
                        Gm[a, b] = G[idx[a], b]
                X = solve_dense(Jm, Gm)
                for i in range(m):
                    for a in range(NY):
                        ga = w * Gm[i, a]
                        for b in range(a, NY):
                            K[a, b] += ga * X[i, b]
        # forces and geometric stiffness of the loaded slices
        Qs = 0.0
        lens = race_kind[s] == RACE_LENS
        for k in range(n):
            if qs[k] <= 0.0:
                continue
            wq = w * qs[k]
            Qs += wq
            for a in range(NY):
                f[a] -= wq * G[k, a]
            y = side * rho[k]
            # n . d2P/dtheta2 = -n . (x u' + y v')
            K[2, 2] -= wq * (nrm[k, 0] * (x[k] * ur + y * vr) + nrm[k, 1] * (x[k] * uz + y * vz))
            if lens:
                # curvature of the raceway arc: (t . dP/dy)^2 / r_c, t = (-n_z, n_r), r_c = d + PCR_LB
                tr = -nrm[k, 1]
                tz = nrm[k, 0]
                T[0] = tr * ur + tz * uz
                T[1] = tr * vr + tz * vz
                T[2] = tr * (x[k] * vr - y * ur) + tz * (x[k] * vz - y * uz)
                if s == 1:
                    T[3] = -tz
                    T[4] = -tr * cpsi
                else:
                    T[3] = 0.0
                    T[4] = 0.0
                kap = wq / (d[k] + race_par[s, 4])
                for a in range(NY):
                    for b in range(a, NY):
                        K[a, b] += kap * T[a] * T[b]
        Qout[s] = Qs
    Qout[3] = dmax_sum
    # roller-end / rib contact (TRB): sphere (centre cx on the roller axis, radius R_end) on a plane
    Qout[2] = 0.0
    aux[AUX_DRIB] = 0.0
    for a in range(NY + 1):
        Gout[2 * n, a] = 0.0
    Gout[2 * n, NY] = -1e300  # no rib
    aux[AUX_RIB_R] = 0.0
    aux[AUX_RIB_Z] = 0.0
    aux[AUX_RIB_NR] = 0.0
    aux[AUX_RIB_NZ] = 0.0
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
        g = Gout[2 * n]
        g[0] = nwr * ur + nwz * uz
        g[1] = nwr * vr + nwz * vz
        g[2] = cx * (nwr * vr + nwz * vz)
        g[3] = -nwz
        g[4] = -nwr * cpsi
        for a in range(NY):
            f[a] -= Qr * g[a]
            for b in range(a, NY):
                K[a, b] += dQ * g[a] * g[b]
        # the sphere centre turns with the roller: n . d2c/dtheta2 = -cx n . u'
        K[2, 2] -= Qr * cx * (nwr * ur + nwz * uz)
        Qout[2] = Qr
        g[NY] = drib
        aux[AUX_DRIB] = drib
        aux[AUX_RIB_R] = cr + R_end * nwr
        aux[AUX_RIB_Z] = cz + R_end * nwz
        aux[AUX_RIB_NR] = nwr
        aux[AUX_RIB_NZ] = nwz
    for a in range(NY):
        for b in range(a):
            K[a, b] = K[b, a]
    return ok


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
        Generalised contact forces on the roller, along u', along v' [N], moment about its centre
        [N mm] (0:3), and on the inner ring along +z and +x [N] (3:5) (written).
    K : ndarray (5, 5)
        Tangent stiffness -df/dy in the local chart of the module docstring [N/mm, N, N mm]
        (written).
    Qout : ndarray (4,)
        Outer load, inner load, rib load [N], max interference outer + inner [mm] (written).

    Returns
    -------
    bool
        Whether every slice complementarity problem converged.
    """
    n = x.shape[0]
    Gout = np.empty((2 * n + 1, NY + 1))
    aux = np.empty(NAUX)
    return _roller_state(pose, ring, phi, cpsi, alpha, Dpw, x, rho, w, race_kind, race_par, R_eq, C, E_star,
                         mode, k_line, rib, has_rib, q, active, tol_d, f, K, Qout, Gout, aux)


@kernel
def _copy1(dst, src):
    """dst[i] = src[i] (equal shapes; explicit loop: no broadcasting machinery to compile)."""
    for i in range(dst.shape[0]):
        dst[i] = src[i]


@kernel
def _copy2(dst, src):
    """dst[i, k] = src[i, k] (equal shapes; explicit loop: no broadcasting machinery to compile)."""
    for i in range(dst.shape[0]):
        for k in range(dst.shape[1]):
            dst[i, k] = src[i, k]


@kernel
def _local_to_pose(pose, da, db, dth):
    """Apply a local step (da along u', db along v' of the current tilt [mm], dth [rad]) to a pose."""
    c = np.cos(pose[2])
    s = np.sin(pose[2])
    pose[0] += c * da - s * db
    pose[1] += s * da + c * db
    pose[2] += dth


@kernel
def _kinematic_pose(ring, phi, cpsi, alpha, Dpw, has_rib, pose):
    """Start pose of a roller: rigid, midway between the rings (written to ``pose``).

    The inner-ring point at the nominal roller centre (Dpw/2, 0) moves by
    Delta = Rot(phi) P0 + (delta_r cos(psi), delta_a) - P0 in the meridian plane; the roller
    centre takes half of it along v (both raceways share the approach), all of it along u when
    the inner ring has a rib (the roller end stays on it) and half otherwise, and half of the
    ring rotation phi.
    """
    r0 = 0.5 * Dpw
    dr = r0 * (np.cos(phi) - 1.0) + ring[1] * cpsi
    dz = r0 * np.sin(phi) + ring[0]
    sa = np.sin(alpha)
    ca = np.cos(alpha)
    du = dr * sa - dz * ca
    dv = dr * ca + dz * sa
    pose[0] = du if has_rib else 0.5 * du
    pose[1] = 0.5 * dv
    pose[2] = 0.5 * phi


@kernel
def _solve_small(A, b, out, m):
    """Solve the leading m x m block A[:m, :m] out[:m] = b[:m] (m <= 4) by Gaussian elimination
    with partial pivoting, without allocation. Returns False when singular to working precision.
    """
    M = np.empty((4, 5))
    for i in range(m):
        for j in range(m):
            M[i, j] = A[i, j]
        M[i, m] = b[i]
    for c in range(m):
        piv = c
        for r in range(c + 1, m):
            if abs(M[r, c]) > abs(M[piv, c]):
                piv = r
        if M[piv, c] == 0.0:
            return False
        if piv != c:
            for k in range(m + 1):
                tmp = M[c, k]
                M[c, k] = M[piv, k]
                M[piv, k] = tmp
        for r in range(c + 1, m):
            fct = M[r, c] / M[c, c]
            for k in range(c, m + 1):
                M[r, k] -= fct * M[c, k]
    for c in range(m - 1, -1, -1):
        s = M[c, m]
        for k in range(c + 1, m):
            s -= M[c, k] * out[k]
        out[c] = s / M[c, c]
    for c in range(m):
        if not np.isfinite(out[c]):
            return False
    return True


@kernel
def _roller_residual(f, body, ext, theta, alpha, Lscale, R):
    """Residual of one roller (contact + body + external loads) in its frame; returns the max-norm.

    R[0], R[1] forces along u', v' [N]; R[2] moment [N mm]; norm max(|R0|, |R1|, |R2| / Lscale) [N].
    """
    ur, uz, vr, vz = roller_axes(alpha, theta)
    R[0] = f[0] + body[0] * ur + ext[0]
    R[1] = f[1] + body[0] * vr + ext[1]
    R[2] = f[2] + body[1] + ext[2]
    return max(abs(R[0]), abs(R[1]), abs(R[2]) / Lscale)


@kernel
def _trial_pose(pose, t, p, trial, ring, ring_t, lc, q, active, qtmp, acttmp):
    """Trial pose ``pose + t p`` (local chart) and ring (delta_a + t p[3] under load control),
    with the slice loads of the current state as warm start (written to trial, ring_t, qtmp,
    acttmp)."""
    trial[0] = pose[0]
    trial[1] = pose[1]
    trial[2] = pose[2]
    _local_to_pose(trial, t * p[0], t * p[1], t * p[2])
    ring_t[0] = ring[0] + t * p[3] if lc else ring[0]
    ring_t[1] = ring[1]
    _copy2(qtmp, q)
    _copy2(acttmp, active)


@kernel
def _trial_residual(f, body, ext, theta, alpha, Lscale, lc, Fa_share, R):
    """Roller residual (R[0:3]) and, under load control, the ring's (R[3] = Fa_share + f[3]);
    returns the max-norm [N] (moment / Lscale)."""
    err = _roller_residual(f, body, ext, theta, alpha, Lscale, R)
    if lc:
        R[3] = Fa_share + f[3]
        err = max(err, abs(R[3]))
    return err


@kernel
def _work(R0, R1, p, m, t):
    """Work of the residual forces along the step t p, trapezoidal rule [N mm]: the decrease of
    the potential energy, exact for a quadratic energy."""
    s = 0.0
    for a in range(m):
        s += (R0[a] + R1[a]) * p[a]
    return 0.5 * t * s


@kernel
def _roller_jacobian(K, R, ext, Lscale, Kq, m):
    """Jacobian -dR/dy of the roller residual in the local chart (written to ``Kq[:m, :m]``).

    m = 3: roller unknowns; m = 4: also delta_a, with the ring's axial residual as fourth row.
    The contact stiffness K plus the turning residual frame: R0 = F.u' + ext0 and
    R1 = F.v' + ext1 give dR0/dtheta += F.v' = R1 - ext1 and dR1/dtheta += -F.u' = -(R0 - ext0);
    plus the round-off regularisation REG of the roller block.
    """
    for a in range(m):
        for b in range(m):
            Kq[a, b] = K[a, b]
    Kq[0, 2] -= R[1] - ext[1]
    Kq[1, 2] += R[0] - ext[0]
    reg = REG * (abs(Kq[0, 0]) + abs(Kq[1, 1]) + abs(Kq[2, 2]) / (Lscale * Lscale))
    Kq[0, 0] += reg
    Kq[1, 1] += reg
    Kq[2, 2] += reg * Lscale * Lscale


@kernel
def _bounded_step(Kq, R, m, Gout, aux, trust, max_len, Lscale, lc, ring, ring_frac, ring_scale, p):
    """Newton step Kq p = R (first m unknowns) and its bound factor c in (0, 1] (solve_roller).

    c keeps the first-order change of the slice and rib penetrations within trust x the
    roller's interference scale D (largest outer + inner + rib penetration): a penetrating
    contact may lose at most trust D, any contact may gain at most its gap plus trust D (a
    contact far from touching may close its gap). It keeps the roller travel within max_len
    and, under load control, the ring travel within ring_frac x its displacement. Returns c,
    or -1 when Kq is singular.
    """
    if not _solve_small(Kq, R, p, m):
        return -1.0
    dscale = aux[AUX_DMAX_O] + aux[AUX_DMAX_I] + max(aux[AUX_DRIB], 0.0)
    c = 1.0
    for k in range(Gout.shape[0]):
        v = 0.0
        for a in range(m):
            v += Gout[k, a] * p[a]
        d = Gout[k, NY]
        if v > 0.0:
            lim = trust * dscale + max(-d, 0.0)
        elif d > 0.0:
            lim = trust * dscale
        else:
            continue
        if abs(v) * c > lim:
            c = lim / abs(v)
    travel = max(abs(p[0]), abs(p[1]), 0.5 * Lscale * abs(p[2]))
    if c * travel > max_len:
        c = max_len / travel
    if lc:
        lim = ring_frac * max(abs(ring[0]), ring_scale)
        if c * abs(p[3]) > lim:
            c = lim / abs(p[3])
    return c


@kernel
def solve_roller(pose, ring, phi, cpsi, body, ext, alpha, Dpw, x, rho, w, race_kind, race_par, R_eq, C, E_star,
                 mode, k_line, rib, has_rib, q, active, tol, spar, Fa_share, ring_scale, f, K, Qout, Gout, aux, Rout):
    """Equilibrium of one roller (bounded Newton, honest line search), optionally load-controlled.

    Fixed ring (``Fa_share <= 0``): the roller's (a, b, theta) balance its contact, body and
    external loads at the given ring position. Load control (``Fa_share > 0``, the
    axisymmetric case where every roller is alike): the ring's axial displacement ring[0] is a
    fourth unknown and Fa_share + f[3] = 0 (the roller's share of Fa on the ring) a fourth
    residual, so that a roller that can only balance far from its start (a TSRB whose contact
    migrates to the roller edge, thesis Table A.6) keeps its load on the way; ring[0] is
    written back.

    Each Newton step (exact Jacobian, module docstring) is bounded (:func:`_bounded_step`): no
    slice or rib penetration changes, to first order, by more than ``spar[SP_TRUST]`` times the
    roller's interference scale (a contact away from touching may first close its gap), the
    roller moves by at most ``spar[SP_MAX_STEP]`` Lwe and the ring by at most
    ``spar[SP_RING_STEP]`` of its displacement. The step is then halved until the potential
    energy falls by the Armijo fraction of its first-order decrease (the work of the residual
    forces along the step, trapezoidal rule, :func:`_work`); without decrease, damped
    Levenberg-Marquardt steps are tried. A full step that does not halve the residual is
    extended while the energy keeps falling: a roller that a wedge of misaligned rings pushes
    out of its contacts has no loaded equilibrium, it comes free and the cage holds it. A
    roller touching one race only is centred between both, unless its loads press it onto
    that race (it rests there, the other ring does not squeeze it: unloaded). A roller that
    gets no decrease is reported as not converged and left at its last accepted state.

    Parameters
    ----------
    pose : ndarray (3,)
        xi [mm], eta [mm], theta [rad]: start in, result out.
    ring : ndarray (2,)
        delta_a, delta_r [mm] (delta_a solved and written under load control).
    body : ndarray (3,)
        Centrifugal force [N] (along e_r), gyroscopic moment [N mm], roller length Lwe [mm].
    ext : ndarray (3,)
        External load on the roller: force along u' towards the large end [N], force along v'
        [N], moment about u' x v' (positive turning u' towards v') [N mm].
    tol : float
        Relative force tolerance of the roller (of its contact and body loads); under load
        control the ring residual is held to spar[SP_TOL] Fa_share.
    spar : ndarray (NSP,)
        Solver parameters (SP_* indices).
    Fa_share : float
        Fa / Z [N] under load control, <= 0 for a fixed ring.
    ring_scale : float
        Length scale of the ring displacement [mm] (its start estimate): bounds ring steps and
        pushes the ring on when nothing is squeezed (load control).
    f, K, Qout, Gout, aux :
        State at the returned pose (as :func:`_roller_state`), valid on entry is not required.
    Rout : ndarray (4,)
        Residual at the returned pose: forces along u', v' [N], moment [N mm], and the residual
        max-norm used by the line search [N] (written when loaded, converged or not).

    Returns
    -------
    (status, iterations, evaluations): status 1 converged and loaded, 2 unloaded (rigid
    clearance, or pushed free), 0 not converged; Newton iterations; contact-state evaluations.
    """
    Lscale = body[2]
    max_iter = int(spar[SP_ROLLER_MAX_ITER])
    trust = spar[SP_TRUST]
    max_len = spar[SP_MAX_STEP] * Lscale
    nbt = int(spar[SP_BACKTRACKS])
    ring_frac = spar[SP_RING_STEP]
    tol_ring = spar[SP_TOL]
    lc = Fa_share > 0.0
    m = 4 if lc else 3
    n = x.shape[0]
    R = np.empty(4)
    Rt = np.empty(4)
    Rb = np.empty(4)
    p = np.zeros(4)
    trial = np.empty(3)
    ring_t = np.empty(2)
    Kq = np.empty((4, 4))
    Klm = np.empty((4, 4))
    ftmp = np.empty(NY)
    Ktmp = np.empty((NY, NY))
    Qtmp = np.empty(4)
    Gtmp = np.empty((2 * n + 1, NY + 1))
    auxtmp = np.empty(NAUX)
    qtmp = np.empty_like(q)
    acttmp = np.empty_like(active)

    def try_step(t):
        """Contact state of the pose a step t along p (into the *tmp arrays and trial, ring_t)."""
        _trial_pose(pose, t, p, trial, ring, ring_t, lc, q, active, qtmp, acttmp)
        return _roller_state(trial, ring_t, phi, cpsi, alpha, Dpw, x, rho, w, race_kind, race_par, R_eq, C, E_star,
                             mode, k_line, rib, has_rib, qtmp, acttmp, 1e-13, ftmp, Ktmp, Qtmp, Gtmp, auxtmp)
    evals = 1
    ok = _roller_state(pose, ring, phi, cpsi, alpha, Dpw, x, rho, w, race_kind, race_par, R_eq, C, E_star,
                       mode, k_line, rib, has_rib, q, active, 1e-13, f, K, Qout, Gout, aux)
    for it in range(max_iter):
        if Qout[3] <= 0.0:
            if not lc:
                # rings do not squeeze this roller: unloaded, held by the cage
                _release(f, K, q, active, Qout)
                return 2, it, evals
            # load control and nothing squeezed yet: push the ring along Fa by its length scale
            ring[0] += max(abs(ring[0]), ring_scale)
            if ring[0] > Lscale:
                return 0, it, evals  # moved by a roller length and still nothing carries the load
            _kinematic_pose(ring, phi, cpsi, alpha, Dpw, has_rib, pose)
            q.fill(0.0)
            active.fill(False)
            ok = _roller_state(pose, ring, phi, cpsi, alpha, Dpw, x, rho, w, race_kind, race_par, R_eq, C, E_star,
                               mode, k_line, rib, has_rib, q, active, 1e-13, f, K, Qout, Gout, aux)
            evals += 1
            continue
        if Qout[0] <= 0.0 or Qout[1] <= 0.0:
            # touching one race only. If its loads (contact, body, external) press it onto that
            # race (along v' outwards onto the outer one, inwards onto the inner one), it rests
            # there and the other ring does not squeeze it: unloaded as far as the rings' balance
            # goes (its centrifugal load on the outer ring is neglected, module docstring).
            # Otherwise, or under load control, centre it along v between both races (rigid
            # interference balance).
            _roller_residual(f, body, ext, pose[2], alpha, Lscale, R)
            if not lc and ((Qout[1] <= 0.0 and R[1] >= 0.0) or (Qout[0] <= 0.0 and R[1] <= 0.0)):
                _release(f, K, q, active, Qout)
                return 2, it, evals
            pose[1] += 0.5 * (aux[AUX_DMAX_I] - aux[AUX_DMAX_O])
            ok = _roller_state(pose, ring, phi, cpsi, alpha, Dpw, x, rho, w, race_kind, race_par, R_eq, C, E_star,
                               mode, k_line, rib, has_rib, q, active, 1e-13, f, K, Qout, Gout, aux)
            evals += 1
            continue
        err = _roller_residual(f, body, ext, pose[2], alpha, Lscale, R)
        scale = Qout[0] + Qout[1] + Qout[2] + abs(body[0]) + abs(ext[0]) + abs(ext[1]) + abs(ext[2]) / Lscale
        done = err <= tol * scale and ok
        merit = err
        if lc:
            R[3] = Fa_share + f[3]
            done = done and abs(R[3]) <= tol_ring * Fa_share
            merit = max(err, abs(R[3]))
        if done:
            _residual_out(R, merit, Rout)
            return 1, it, evals
        _roller_jacobian(K, R, ext, Lscale, Kq, m)
        c = _bounded_step(Kq, R, m, Gout, aux, trust, max_len, Lscale, lc, ring, ring_frac, ring_scale, p)
        if c <= 0.0:
            _residual_out(R, merit, Rout)
            return 0, it, evals
        travel = max(abs(p[0]), abs(p[1]), 0.5 * Lscale * abs(p[2]))
        # backtracking line search on the potential energy of the roller (and, under load
        # control, of the ring's load share): the work of the residual forces along the step,
        # by the trapezoidal rule from the residuals at both ends (exact for a quadratic
        # energy), must be a fraction ARMIJO of its first-order value R.p t (Armijo). A trial
        # free of both rings (no residual: the cage holds it) counts at a fixed ring and is
        # refused under load control. An uphill Newton direction (R.p <= 0) goes to the
        # damped steps.
        slope = 0.0
        for a in range(m):
            slope += R[a] * p[a]
        t = c
        accepted = False
        free = False
        merit_t = merit
        ok_t = ok
        if slope > 0.0:
            for ls in range(nbt + 1):
                ok_t = try_step(t)
                evals += 1
                if Qtmp[3] <= 0.0:
                    if not lc:
                        free = True
                        accepted = True
                        break
                else:
                    merit_t = _trial_residual(ftmp, body, ext, trial[2], alpha, Lscale, lc, Fa_share, Rt)
                    if _work(R, Rt, p, m, t) >= ARMIJO * t * slope:
                        accepted = True
                        break
                t *= 0.5
        if not accepted:
            # Newton direction without decrease (near-singular stiffness of a lightly loaded
            # roller, contacts switching along it): Levenberg-Marquardt steps (K + mu diag K)^-1 R,
            # mu raised tenfold per try, which turn towards the scaled force direction
            mu = LM_MU0
            for k in range(LM_TRIES):
                for a in range(m):
                    for b in range(m):
                        Klm[a, b] = Kq[a, b]
                    Klm[a, a] += mu * abs(Kq[a, a])
                mu *= LM_FACTOR
                t = _bounded_step(Klm, R, m, Gout, aux, trust, max_len, Lscale, lc, ring, ring_frac, ring_scale, p)
                if t <= 0.0:
                    continue
                slope = 0.0
                for a in range(m):
                    slope += R[a] * p[a]
                if slope <= 0.0:
                    continue
                ok_t = try_step(t)
                evals += 1
                if Qtmp[3] <= 0.0:
                    if not lc:
                        free = True
                        accepted = True
                        break
                    continue
                merit_t = _trial_residual(ftmp, body, ext, trial[2], alpha, Lscale, lc, Fa_share, Rt)
                if _work(R, Rt, p, m, t) >= ARMIJO * t * slope:
                    accepted = True
                    break
            c = -1.0  # no extension of a damped step
        if not accepted:
            _residual_out(R, merit, Rout)
            return 0, it + 1, evals
        if not free and t == c and merit_t > EXTEND * merit:
            # poor progress of a full step: extend it while the energy keeps falling; a trial
            # free of both rings ends it (fixed ring: unloaded)
            t_best = t
            for a in range(m):
                Rb[a] = Rt[a]
            while 2.0 * t * travel <= Lscale:
                t_try = 2.0 * t_best
                try_step(t_try)
                evals += 1
                t = t_try
                if Qtmp[3] <= 0.0:
                    if not lc:
                        free = True
                    break
                _trial_residual(ftmp, body, ext, trial[2], alpha, Lscale, lc, Fa_share, Rt)
                if _work(Rb, Rt, p, m, t_try - t_best) <= 0.0:
                    break
                t_best = t_try
                for a in range(m):
                    Rb[a] = Rt[a]
            if not free and t != t_best:
                t = t_best
                ok_t = try_step(t)
                evals += 1
        pose[0] = trial[0]
        pose[1] = trial[1]
        pose[2] = trial[2]
        if free:
            _release(f, K, q, active, Qout)
            Qout[3] = Qtmp[3]
            return 2, it + 1, evals
        ring[0] = ring_t[0]
        _copy2(q, qtmp)
        _copy2(active, acttmp)
        _copy1(f, ftmp)
        _copy2(K, Ktmp)
        _copy1(Qout, Qtmp)
        _copy2(Gout, Gtmp)
        _copy1(aux, auxtmp)
        ok = ok_t
    merit = _roller_residual(f, body, ext, pose[2], alpha, Lscale, R)
    if lc:
        merit = max(merit, abs(Fa_share + f[3]))
    _residual_out(R, merit, Rout)
    return 0, max_iter, evals


@kernel
def _residual_out(R, merit, Rout):
    """Rout = (R0 [N], R1 [N], R2 [N mm], residual max-norm [N]) of the returned state."""
    Rout[0] = R[0]
    Rout[1] = R[1]
    Rout[2] = R[2]
    Rout[3] = merit


@kernel
def _release(f, K, q, active, Qout):
    """State of a roller the rings do not squeeze: no load, no stiffness (the cage holds it)."""
    for a in range(NY):
        f[a] = 0.0
        for b in range(NY):
            K[a, b] = 0.0
    q.fill(0.0)
    active.fill(False)
    Qout[0] = 0.0
    Qout[1] = 0.0
    Qout[2] = 0.0


@kernel
def solve_bearing(Fa, Fr, tilt, body, ext, alpha, Dpw, Z, x, rho, w, race_kind, race_par, R_eq, C, E_star,
                  mode, k_line, rib, has_rib, spar, ring0, poses, q, active, Q, Qrib, rib_contact, info):
    """Inner-ring equilibrium under Fa, Fr and an imposed tilt (Newton on the condensed stiffness).

    Symmetry: roller j and Z - j are mirror images (same cos(psi), same phi) when their
    external loads are equal, so only Z // 2 + 1 azimuth classes are solved; with no radial
    load, no tilt and equal external loads on every roller, one roller is solved for all.

    Parameters
    ----------
    Fa, Fr : float
        Axial load along +z and radial load along +x on the inner ring [N].
    tilt : float
        Imposed inner-ring tilt about the y axis [rad].
    body : ndarray (3,)
        Centrifugal force [N], gyroscopic moment [N mm], length Lwe [mm] of a loaded roller.
    ext : ndarray (Z, 3)
        External load per roller, [along u' towards the large end N, along v' N, about u' x v'
        N mm] (:func:`solve_roller`).
    spar : ndarray (NSP,)
        Solver parameters (SP_* indices).
    ring0 : ndarray (2,)
        Start value of (delta_a, delta_r) [mm], not both zero: its size is the ring's length
        scale (BearingModel.initial_ring: the Hertz approach); the solution is written back.
    poses : ndarray (Z, 3)
        Roller poses xi [mm], eta [mm], theta [rad] (warm start in when ``info[0] < 0``,
        solution out).
    q, active : ndarray (Z, 2, N)
        Slice line loads [N/mm] and loaded flags per roller and race (0 outer, 1 inner)
        (warm start in with the poses, solution out).
    Q : ndarray (Z, 2)
        Roller-raceway loads [N] (written). Qrib : ndarray (Z,) rib loads [N] (written).
    rib_contact : ndarray (Z, 4)
        Rib contact point (r, z) [mm] on the roller end and unit rib normal (r, z) into the
        rib, in the roller's meridian plane (zeros without a rib) (written).
    info : ndarray (9,)
        In: info[0] < 0 takes the given poses, q, active as a warm start (continuation).
        Out: ring iterations (axisymmetric case: Newton iterations of the load-controlled
        roller), force residual axial [N], radial [N], number of unconverged roller classes,
        number of loaded roller classes, roller Newton iterations, roller contact-state
        evaluations, ring backtracks, roller classes solved.

    Returns
    -------
    bool
        converged.
    """
    n = x.shape[0]
    tol = spar[SP_TOL]
    max_iter = int(spar[SP_MAX_ITER])
    nbt = int(spar[SP_BACKTRACKS])
    forcing = spar[SP_FORCING]
    ring_frac = spar[SP_RING_STEP]
    roller_tol_final = tol * spar[SP_ROLLER_TOL_RATIO]
    Lscale = body[2]
    warm = info[0] < 0.0
    # azimuth classes
    mirror = True
    equal = True
    for j in range(Z):
        for a in range(3):
            if ext[j, a] != ext[(Z - j) % Z, a]:
                mirror = False
            if ext[j, a] != ext[0, a]:
                equal = False
    axisym = Fr == 0.0 and tilt == 0.0 and equal
    if axisym:
        nz = 1
    elif mirror:
        nz = Z // 2 + 1
    else:
        nz = Z
    mult = np.empty(nz)
    for j in range(nz):
        if axisym:
            mult[j] = float(Z)
        elif mirror and j > 0 and 2 * j != Z:
            mult[j] = 2.0
        else:
            mult[j] = 1.0
    ring = ring0.copy()
    # length scale of the ring: the start estimate (an approach), or the current displacement
    ring_scale = max(abs(ring0[0]), abs(ring0[1]))
    f = np.empty(NY)
    K = np.empty((NY, NY))
    Qo = np.empty(4)
    Gout = np.empty((2 * n + 1, NY + 1))
    aux = np.empty(NAUX)
    Rq = np.empty(4)
    n3 = Rq.shape[0] - 1  # the roller's unknowns, a run-time value: one signature of the small solvers
    Kq = np.empty((4, 4))
    col = np.empty(4)
    xcol = np.empty(4)
    Fscale = max(Fa, Fr)
    status = np.full(nz, -1, dtype=np.int64)  # -1: no state yet
    if warm:
        for j in range(nz):
            status[j] = 1
    # per class: X = K_qq^-1 K_qR and the Newton correction z = K_qq^-1 R_q of the roller
    # (local chart), so that dq = z - X dring to first order
    X = np.zeros((nz, 3, 2))
    zc = np.zeros((nz, 3))
    # last accepted ring iterate and its rollers
    ring_acc = ring.copy()
    pose_acc = poses[:nz].copy()
    q_acc = q[:nz].copy()
    act_acc = active[:nz].copy()
    st_acc = status.copy()
    X_acc = X.copy()
    z_acc = zc.copy()
    have_acc = False
    err_acc = np.inf
    err_prev = np.inf
    step = np.zeros(2)
    t_ring = 1.0
    backtracks = 0
    n_backtracks = 0
    # first pass: the ring residual is of the order of the load and the roller loads add up to
    # about 2 F / sin(alpha) (both raceways, F along the contact normals)
    roller_tol = max(roller_tol_final, 0.5 * forcing * np.sin(alpha))
    converged = False
    it_ring = 0
    Ffail = np.zeros(2)  # ring forces of rollers without equilibrium (inexact states)
    Fres = np.zeros(2)   # ring residual with the rollers' first-order correction (Newton)
    Ftrue = np.zeros(2)  # ring residual of the rollers as they are
    Kc = np.zeros((2, 2))
    kin = np.empty(3)
    kin_prev = np.empty(3)
    roller_its = 0
    roller_evals = 0
    nbad = 0
    nload = 0
    Fa_share = 0.0
    if axisym:
        # every roller alike: one roller, with the ring's axial displacement solved with it under
        # load control (solve_roller, one pass); delta_r = 0 by symmetry
        Fa_share = Fa / Z
        ring[1] = 0.0
        roller_tol = roller_tol_final
    for it_ring in range(max_iter):
        Fres[0] = Fa
        Fres[1] = Fr
        Ftrue[0] = Fa
        Ftrue[1] = Fr
        Kc.fill(0.0)
        nbad = 0
        nload = 0
        load_sum = 0.0
        fail_sum = 0.0
        Ffail.fill(0.0)
        for j in range(nz):
            psi = 2.0 * np.pi * j / Z
            cpsi = np.cos(psi)
            phi = tilt * cpsi
            if status[j] != 1 and status[j] != 3:
                # no valid state: rigid kinematic pose, plus the deviation of the neighbour solved
                # just before (warm start of its slice loads too)
                _kinematic_pose(ring, phi, cpsi, alpha, Dpw, has_rib, kin)
                if j > 0 and status[j - 1] == 1:
                    cprev = np.cos(2.0 * np.pi * (j - 1) / Z)
                    _kinematic_pose(ring, tilt * cprev, cprev, alpha, Dpw, has_rib, kin_prev)
                    for a in range(3):
                        poses[j, a] = kin[a] + poses[j - 1, a] - kin_prev[a]
                    _copy2(q[j], q[j - 1])
                    _copy2(active[j], active[j - 1])
                else:
                    for a in range(3):
                        poses[j, a] = kin[a]
                    q[j].fill(0.0)
                    active[j].fill(False)
            st, its, nev = solve_roller(poses[j], ring, phi, cpsi, body, ext[j], alpha, Dpw, x, rho, w, race_kind,
                                        race_par, R_eq, C, E_star, mode, k_line, rib, has_rib, q[j], active[j],
                                        roller_tol, spar, Fa_share, ring_scale, f, K, Qo, Gout, aux, Rq)
            roller_its += its
            roller_evals += nev
            status[j] = st
            Q[j, 0] = Qo[0]
            Q[j, 1] = Qo[1]
            Qrib[j] = Qo[2]
            for a in range(4):
                rib_contact[j, a] = aux[AUX_RIB_R + a] if st == 1 else 0.0
            X[j].fill(0.0)
            zc[j].fill(0.0)
            if st == 0:
                nbad += 1
                if Qo[3] > 0.0:
                    # kept as an inexact state if the ring residual allows (below)
                    fail_sum += mult[j] * Rq[3]
                    for a in range(2):
                        Ffail[a] += mult[j] * f[3 + a]
            if st != 1:
                continue
            nload += 1
            load_sum += mult[j] * (Qo[0] + Qo[1] + Qo[2])
            # condensation (module docstring): X = K_qq^-1 K_qR, z = K_qq^-1 R_q,
            # Kc += K_RR - K_Rq X, ring residual += f_R - K_Rq z
            _roller_jacobian(K, Rq, ext[j], Lscale, Kq, n3)
            for b in range(2):
                for a in range(3):
                    col[a] = K[a, 3 + b]
                if _solve_small(Kq, col, xcol, n3):
                    for a in range(3):
                        X[j, a, b] = xcol[a]
            if _solve_small(Kq, Rq, xcol, n3):
                for a in range(3):
                    zc[j, a] = xcol[a]
            for a in range(2):
                Ftrue[a] += mult[j] * f[3 + a]
                corr = f[3 + a]
                for c in range(3):
                    corr -= K[3 + a, c] * zc[j, c]
                Fres[a] += mult[j] * corr
                for b in range(2):
                    s = K[3 + a, 3 + b]
                    for c in range(3):
                        s -= K[3 + a, c] * X[j, c, b]
                    Kc[a, b] += mult[j] * s
        if axisym:
            # the roller solve balanced the ring's axial load too (load control); delta_r = 0 by
            # symmetry, the radial sum of one roller class is not a residual
            converged = nbad == 0 and nload == 1
            info[1] = Ftrue[0]
            info[2] = 0.0
            it_ring = max(roller_its - 1, 0)  # reported: the roller's Newton iterations
            break
        err = max(abs(Fres[0]), abs(Fres[1]))
        n_inexact = 0
        if nbad > 0 and roller_tol > roller_tol_final:
            # rollers without equilibrium yet (lightly loaded, far from the solution) are kept as
            # they are while their residuals stay below forcing x the ring residual, like the
            # inexact rollers (they enter the ring residual, not its stiffness)
            err_with = max(abs(Fres[0] + Ffail[0]), abs(Fres[1] + Ffail[1]))
            if fail_sum <= forcing * err_with:
                for j in range(nz):
                    if status[j] == 0 and Q[j, 0] + Q[j, 1] > 0.0:
                        status[j] = 3
                        n_inexact += 1
                if n_inexact == nbad:
                    nbad = 0
                    Fres[0] += Ffail[0]
                    Fres[1] += Ffail[1]
                    Ftrue[0] += Ffail[0]
                    Ftrue[1] += Ffail[1]
                    err = err_with
                else:
                    for j in range(nz):
                        if status[j] == 3:
                            status[j] = 0
                    n_inexact = 0
        info[1] = Ftrue[0]
        info[2] = Ftrue[1]
        if nbad == 0 and err <= tol * Fscale:
            if roller_tol <= roller_tol_final and n_inexact == 0 and max(abs(Ftrue[0]), abs(Ftrue[1])) <= tol * Fscale:
                converged = True
                break
            if roller_tol > roller_tol_final:
                # the ring is there: solve the rollers to the final tolerance (starting from their
                # Newton correction) and check again
                roller_tol = roller_tol_final
                for j in range(nz):
                    if status[j] == 1:
                        _local_to_pose(poses[j], zc[j, 0], zc[j, 1], zc[j, 2])
                continue
        # backtracking line search on the ring residual: restore the rollers of the accepted
        # iterate and predict them along the tangent for the shorter step
        if have_acc and (nbad > 0 or err >= (1.0 - ARMIJO * t_ring) * err_acc):
            if backtracks >= nbt:
                break  # no decrease along the Newton direction: report the case as not converged
            backtracks += 1
            n_backtracks += 1
            t_ring *= 0.5
            for a in range(2):
                ring[a] = ring_acc[a] + t_ring * step[a]
            for j in range(nz):
                status[j] = st_acc[j]
                _copy2(q[j], q_acc[j])
                _copy2(active[j], act_acc[j])
                for a in range(3):
                    poses[j, a] = pose_acc[j, a]
                if st_acc[j] == 1:
                    _local_to_pose(poses[j],
                                   z_acc[j, 0] - t_ring * (X_acc[j, 0, 0] * step[0] + X_acc[j, 0, 1] * step[1]),
                                   z_acc[j, 1] - t_ring * (X_acc[j, 1, 0] * step[0] + X_acc[j, 1, 1] * step[1]),
                                   z_acc[j, 2] - t_ring * (X_acc[j, 2, 0] * step[0] + X_acc[j, 2, 1] * step[1]))
            continue
        if nbad > 0:
            break  # a roller equilibrium failed at the start value
        # accept this iterate
        have_acc = True
        backtracks = 0
        t_ring = 1.0
        err_acc = err
        for j in range(nz):
            st_acc[j] = status[j]
            _copy1(pose_acc[j], poses[j])
            _copy2(q_acc[j], q[j])
            _copy2(act_acc[j], active[j])
            _copy2(X_acc[j], X[j])
            _copy1(z_acc[j], zc[j])
        ring_acc[0] = ring[0]
        ring_acc[1] = ring[1]
        # rollers for the next ring iterate: forcing x the ring residual expected there, from
        # quadratic convergence err_next ~ err^3 / err_prev^2 (Eisenstat & Walker 1996, SIAM J.
        # Sci. Comput. 17(1), choice 2, with the observed rate), never above the current one
        err_next = err
        if err_prev < np.inf:
            err_next = err * min(1.0, (err / err_prev) ** 2)
        err_prev = err
        roller_tol = max(roller_tol_final,
                         min(roller_tol, forcing * max(err_next, tol * Fscale) / max(load_sum, Fscale)))
        # Newton step on the ring; with fewer than two roller classes squeezed (singular Kc),
        # push the ring further along Fa by its length scale
        push = False
        det = Kc[0, 0] * Kc[1, 1] - Kc[0, 1] * Kc[1, 0]
        if nload < 2 or abs(det) <= REG * abs(Kc[0, 0] * Kc[1, 1]) or Kc[0, 0] * Kc[1, 1] == 0.0:
            push = True
        else:
            step[0] = (Kc[1, 1] * Fres[0] - Kc[0, 1] * Fres[1]) / det
            step[1] = (-Kc[1, 0] * Fres[0] + Kc[0, 0] * Fres[1]) / det
        if push:
            step[0] = max(abs(ring[0]), ring_scale)
            step[1] = 0.0
            if ring[0] + step[0] > Lscale:
                break  # moved by a roller length and still nothing carries the load
        else:
            # limit the step to a fraction of the current ring displacement (contacts stiffen)
            lim = ring_frac * max(abs(ring[0]), abs(ring[1]), ring_scale)
            sc = 1.0
            if abs(step[0]) > lim:
                sc = lim / abs(step[0])
            if abs(step[1]) > lim:
                sc = min(sc, lim / abs(step[1]))
            step[0] *= sc
            step[1] *= sc
        ring[0] += step[0]
        ring[1] += step[1]
        # predictor: each roller takes its Newton correction and follows the ring along its tangent
        for j in range(nz):
            if status[j] == 1:
                _local_to_pose(poses[j], zc[j, 0] - (X[j, 0, 0] * step[0] + X[j, 0, 1] * step[1]),
                               zc[j, 1] - (X[j, 1, 0] * step[0] + X[j, 1, 1] * step[1]),
                               zc[j, 2] - (X[j, 2, 0] * step[0] + X[j, 2, 1] * step[1]))
    # results of the last state
    ring0[0] = ring[0]
    ring0[1] = ring[1]
    info[0] = it_ring + 1
    info[3] = nbad
    info[4] = nload
    info[5] = roller_its
    info[6] = roller_evals
    info[7] = n_backtracks
    info[8] = nz
    # fill the rollers of the other azimuths from their classes
    for j in range(Z):
        src = j
        if axisym:
            src = 0
        elif mirror and j > Z // 2:
            src = Z - j
        if src != j:
            for a in range(3):
                poses[j, a] = poses[src, a]
            for s in range(2):
                Q[j, s] = Q[src, s]
                for k in range(n):
                    q[j, s, k] = q[src, s, k]
                    active[j, s, k] = active[src, s, k]
            Qrib[j] = Qrib[src]
            for a in range(4):
                rib_contact[j, a] = rib_contact[src, a]
    return converged
