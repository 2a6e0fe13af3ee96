"""Contact of one roller with both raceways and the rib: contact frames, slice loads, generalised
forces and their exact stiffness (MODEL.md 3 and 4, meridian plane of each roller, mm, N, rad).

One function, :func:`roller_contact`, evaluates a roller at a pose: the contact frames
(:func:`roller_frames`: contact point, normal and penetration of every slice on both raceways,
roller centre and axes, roller-end / rib point), the slice loads of the slice elasticity
(:mod:`sim.physics.elasticity`), the roller-end / rib Hertz load, and the generalised forces
and tangent stiffness that the quasi-static solver (:mod:`sim.solvers.quasi_static`) needs.
The friction evaluation takes the same frames at the solution.

Generalised coordinates (local chart of :mod:`sim.solvers.quasi_static`):
y = (a, b, theta, delta_a, delta_r), a translation a u' + b v' of the roller centre along the
roller axes u', v' of its current tilt, the roller tilt theta, and the inner ring's axial and
radial displacement. For a contact (slice or rib) with penetration d(y), G = dd/dy; the normal
load Q acts on the roller as the generalised force -Q G (virtual work), and on the ring likewise.
The tangent stiffness is the exact Jacobian K = -df/dy:

- material part: w G^T (dq/dd) G for slices (q line load, w slice width, dq/dd the tangent of
  the slice elasticity on the loaded set) and dQ/dd g g^T for the rib;
- geometric part: w sum_k q_k H_k with H_k the second derivative of the penetration: the
  raceway curvature (t.dP/dy_a)(t.dP/dy_b)/r_c (t the profile tangent, r_c the radius of the
  TSRB arc that bounds the slice, PCR (2 - kappa_k); zero for a straight TRB cone) plus
  n . d2P/dtheta2 = -n.(x u' + y v') of the turning slice point P (and -n.(c_x u' + c_y v') for the centre of
  the roller end's circle at the rib).

Kernels share state through named tuples of arrays (STYLE.md): :data:`BearingArrays` (the
bearing), :data:`ContactFrames` (frames of Z rollers, or of one roller), :data:`RollerContact`
(the contact state of one roller).
"""
from collections import namedtuple

import numpy as np

from sim._math.jit import internal_kernel, kernel
from sim._math.linalg import solve_dense
from sim.geometry import RACE_LENS
from sim.physics.contact import (NO_CONTACT, Raceway, RingMotion, SliceContacts, hertz_point_load, lens_penetration,
                                 roller_axes, slice_contact_meridian, to_ring)
from sim.physics.elasticity import INDEPENDENT, coupled_slice_compliance, coupled_slice_loads, independent_slice_loads

NY = 5  # generalised coordinates of a roller block: a (along u'), b (along v'), theta, delta_a, delta_r

# Kernel inputs of one bearing (sim.api.bearing_model.BearingModel builds it from sim.geometry.Geometry):
# x, rho (N,): slice centres along the roller axis from mid-length and roller radius there [mm];
# w: slice width [mm]; race_kind (2,) int64, race_par (2, 6): outer and inner raceway profiles in
# ring coordinates (sim.physics.contact); R_eq (2, N): radii of relative curvature per race and
# slice [mm]; rib (6,): centre (c_x, c_y) and radius of the roller end's circle that touches the rib in
# the meridian plane (end sphere, or the torus's tube section) [mm], unit rib normal (n_x, n_y) into the
# rib in the roller frame, radius of the sphere on a plane with the rib contact's Hertz load law
# [mm] (sim.geometry's relative radius along e_t made so by sim.api.bearing_model with
# sim.physics.contact.hertz_point_radii; the circle's own radius for the sphere; zeros for a TSRB); alpha: roller-axis angle
# [rad]; Dpw: pitch diameter [mm]; Lwe: roller length [mm]; Z: number of rollers; has_rib: the
# inner ring guides the rollers by a rib (TRB); end_drop (2, 2, M): per race and roller end, the
# unloaded gap's excess over its linear extrapolation from the end slice centres [mm]
# (sim.physics.elasticity.end_profile_drop: the contact ends beyond the end centres).
BearingArrays = namedtuple("BearingArrays", ["x", "rho", "w", "race_kind", "race_par", "R_eq", "rib", "alpha",
                                             "Dpw", "Lwe", "Z", "has_rib", "end_drop"])

# Contact frames of Z rollers with N slices per raceway (a numba-supported named tuple of arrays):
# X, Nrm (Z, 2, N, 2): contact points [mm] and unit normals into the ring, (r, z), race 0 outer,
# 1 inner; Cen (Z, 2): roller centres [mm]; Ax (Z, 4): roller axes (u'_r, u'_z, v'_r, v'_z);
# Xrib (Z, 2): roller-end / rib contact point [mm] (TRB only). The frames of one roller have the
# same fields without the leading Z axis (roller j: ContactFrames(X[j], Nrm[j], Cen[j], Ax[j], Xrib[j])).
ContactFrames = namedtuple("ContactFrames", ["X", "Nrm", "Cen", "Ax", "Xrib"])

# Contact state of one roller (:func:`roller_contact`), arrays over N slices per raceway:
# pose (3,): xi [mm], eta [mm], theta [rad] of the roller (sim.solvers.quasi_static) (in);
# q, active (2, N): line loads [N/mm] and loaded flags per race (0 outer, 1 inner): warm start
# in, result out; f (5,): generalised contact forces on the roller along u', along v' [N], moment
# about its centre [N mm], and on the inner ring along +z and +x [N]; K (5, 5): tangent stiffness
# -df/dy [N/mm, N, N mm]; Q (3,): outer, inner raceway and rib load [N]; depth (3,): deepest
# penetration of the outer and of the inner raceway and the rib penetration [mm] (0 without a
# rib); G (2 N + 1, 5): dd/dy of every slice (outer rows 0..N-1, inner N..2N-1) and of the rib
# (row 2N); d (2 N + 1,): their penetrations [mm] (NO_CONTACT for the rib row without a rib);
# rib_contact (4,): rib contact point (r, z) [mm] on the roller end and the rib's unit normal
# (r, z) into the rib (the rib load acts on the roller along -n; zeros without a rib);
# frames: ContactFrames of this roller; free (2, N): free penetration of every slice [mm]
# (sim.physics.elasticity.coupled_slice_loads; the rigid ones for independent slices): the contact ends
# between slices (loaded_lengths).
RollerContact = namedtuple("RollerContact", ["pose", "q", "active", "f", "K", "Q", "depth", "G", "d",
                                             "rib_contact", "frames", "free"])

# Slice deflections are solved to at most DEFLECTION_TOL_REL of the roller's deepest penetration:
# its loads are then accurate to ~1e-12 relative, 100x below the final roller tolerance of the
# quasi-static solver (solver.tolerance x roller_tolerance_ratio = 1e-10), also for a lightly
# loaded roller; and to at most DEFLECTION_TOL_ABS [mm], the same 1e-12 of a 0.1 mm penetration,
# deeper than the deepest of the cases here (0.005-0.05 mm: trb_32208 at 4.5-40 kN,
# tsrb_reference at 4.5 kN, tsrb_pinion PCR 200 at 35 kN).
DEFLECTION_TOL_REL = 1e-12
DEFLECTION_TOL_ABS = 1e-13


def empty_frames(Z, n):
    """Zeroed :data:`ContactFrames` for Z rollers and n slices."""
    return ContactFrames(np.zeros((Z, 2, n, 2)), np.zeros((Z, 2, n, 2)), np.zeros((Z, 2)), np.zeros((Z, 4)),
                         np.zeros((Z, 2)))


def empty_roller_contact(n):
    """A zeroed :data:`RollerContact` with its own arrays, for n slices per raceway."""
    frames = ContactFrames(np.zeros((2, n, 2)), np.zeros((2, n, 2)), np.zeros(2), np.zeros(4), np.zeros(2))
    return RollerContact(np.zeros(3), np.zeros((2, n)), np.zeros((2, n), dtype=np.bool_), np.zeros(NY),
                         np.zeros((NY, NY)), np.zeros(3), np.zeros(3), np.zeros((2 * n + 1, NY)),
                         np.zeros(2 * n + 1), np.zeros(4), frames, np.zeros((2, n)))


@internal_kernel
def roller_frames(pose, ring, phi, cpsi, bearing, d, frames):
    """Contact frames of one roller at a pose: slice contact points, normals and penetrations on
    both raceways, roller centre and axes, roller-end / rib point.

    Parameters
    ----------
    pose : ndarray (3,)
        xi [mm], eta [mm], theta [rad].
    ring : ndarray (2,)
        delta_a, delta_r of the inner ring [mm] (the outer ring is fixed).
    phi : float
        Imposed inner-ring rotation in this meridian plane [rad] (tilt * cos(psi)).
    cpsi : float
        cos(psi) of the roller azimuth psi.
    bearing : BearingArrays
    d : ndarray (>= 2 N,)
        Slice penetrations [mm], outer race 0..N-1, inner N..2N-1 (written).
    frames : ContactFrames of one roller
        X, Nrm (2, N, 2), Cen (2,), Ax (4,), Xrib (2,) (written). Xrib is the point of the
        roller-end sphere along the nominal rib normal turned with the roller (zeros of rib
        give the roller centre).
    """
    n = bearing.x.shape[0]
    alpha = bearing.alpha
    sa = np.sin(alpha)
    ca = np.cos(alpha)
    ur, uz, vr, vz = roller_axes(alpha, pose[2])
    Cen = frames.Cen
    Ax = frames.Ax
    Cen[0] = 0.5 * bearing.Dpw + pose[0] * sa + pose[1] * ca
    Cen[1] = -pose[0] * ca + pose[1] * sa
    Ax[0] = ur
    Ax[1] = uz
    Ax[2] = vr
    Ax[3] = vz
    for s in range(2):
        # outer ring fixed; inner ring displaced by (delta_r cos(psi), delta_a) and turned by phi.
        # side is a run-time value: one signature of slice_contact_meridian
        side = 1 - 2 * s
        if s == 0:
            slice_contact_meridian(bearing.x, bearing.rho, side, pose, alpha, bearing.Dpw,
                                   Raceway(bearing.race_kind[0], bearing.race_par[0]), RingMotion(0.0, 0.0, 0.0),
                                   SliceContacts(d[:n], frames.Nrm[0], frames.X[0]))
        else:
            slice_contact_meridian(bearing.x, bearing.rho, side, pose, alpha, bearing.Dpw,
                                   Raceway(bearing.race_kind[1], bearing.race_par[1]),
                                   RingMotion(ring[1] * cpsi, ring[0], phi),
                                   SliceContacts(d[n:2 * n], frames.Nrm[1], frames.X[1]))
    rib = bearing.rib
    ex = rib[0] + rib[2] * rib[3]
    ey = rib[1] + rib[2] * rib[4]
    frames.Xrib[0] = Cen[0] + ex * ur + ey * vr
    frames.Xrib[1] = Cen[1] + ex * uz + ey * vz


@kernel
def roller_contact(ring, phi, cpsi, bearing, elasticity, state):
    """Contact frames, slice and rib loads, generalised forces and exact tangent stiffness of one
    roller at ``state.pose`` (module docstring).

    Parameters
    ----------
    ring : ndarray (2,)
        delta_a, delta_r of the inner ring [mm].
    phi : float
        Imposed inner-ring rotation in this meridian plane [rad] (tilt * cos(psi)).
    cpsi : float
        cos(psi) of the roller azimuth psi.
    bearing : BearingArrays
    elasticity : sim.physics.elasticity.SliceElasticity
    state : RollerContact
        pose in; q, active warm start in and result out; everything else written.

    Returns
    -------
    bool
        Whether every slice complementarity problem converged.
    """
    x = bearing.x
    rho = bearing.rho
    w = bearing.w
    n = x.shape[0]
    pose = state.pose
    f = state.f
    K = state.K
    Gall = state.G
    dall = state.d
    frames = state.frames
    roller_frames(pose, ring, phi, cpsi, bearing, dall, frames)
    ur = frames.Ax[0]
    uz = frames.Ax[1]
    vr = frames.Ax[2]
    vz = frames.Ax[3]
    dq = np.empty(n)
    for a in range(NY):
        f[a] = 0.0
        for b in range(NY):
            K[a, b] = 0.0
    ok = True
    T = np.empty(NY)
    for s in range(2):
        side = 1 - 2 * s
        d = dall[s * n:(s + 1) * n]
        nrm = frames.Nrm[s]
        G = Gall[s * n:(s + 1) * n]
        dmax = NO_CONTACT
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
            else:
                G[k, 3] = 0.0
                G[k, 4] = 0.0
        state.depth[s] = dmax
        qs = state.q[s]
        act = state.active[s]
        # material stiffness w G^T (dq/dd) G on the loaded slices
        if elasticity.mode == INDEPENDENT:
            independent_slice_loads(d, elasticity.k_line, qs, dq)
            for k in range(n):
                state.free[s, k] = d[k]
                act[k] = qs[k] > 0.0
                if act[k]:
                    for a in range(NY):
                        for b in range(a, NY):
                            K[a, b] += w * dq[k] * G[k, a] * G[k, b]
        else:
            # deflection tolerance: DEFLECTION_TOL_ABS, and at most DEFLECTION_TOL_REL of the deepest
            # penetration, so that lightly loaded rollers get the same relative accuracy
            conv, its = coupled_slice_loads(d, elasticity.C, w, bearing.R_eq[s], elasticity.E_star, qs, act,
                                            min(DEFLECTION_TOL_ABS, DEFLECTION_TOL_REL * max(dmax, 0.0)), state.free[s])
            ok = ok and conv
            m = 0
            for k in range(n):
                if act[k]:
                    m += 1
            if m > 0:
                # dq/dd = J^-1 on the loaded set (sim.physics.elasticity.coupled_slice_compliance)
                Jfull = np.empty((n, n))
                coupled_slice_compliance(elasticity.C, w, bearing.R_eq[s], elasticity.E_star, qs, act, Jfull)
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
        lens = bearing.race_kind[s] == RACE_LENS
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
                # curvature of the raceway arc: (t . dP/dy)^2 / r_c, t = (-n_z, n_r), r_c = d + R_k of the
                # arc k that bounds the slice (PCR (2 - kappa_k), eq. (2.7) per contact point)
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
                if s == 0:
                    lr, lz = frames.X[0, k, 0], frames.X[0, k, 1]
                else:
                    lr, lz = to_ring(frames.X[1, k, 0], frames.X[1, k, 1], ring[1] * cpsi, ring[0], phi)
                r_arc = lens_penetration(lr, lz, bearing.race_par[s])[3]  # radius of the arc bounding slice k
                kap = wq / (d[k] + r_arc)
                for a in range(NY):
                    for b in range(a, NY):
                        K[a, b] += kap * T[a] * T[b]
        state.Q[s] = Qs
    # roller-end / rib contact (TRB): a circle of radius r centred at (cx, cy) in the roller frame
    # (the end sphere, cy = 0, or the torus's tube section, cy = -rim radius) on a plane
    state.Q[2] = 0.0
    state.depth[2] = 0.0
    g = Gall[2 * n]
    for a in range(NY):
        g[a] = 0.0
    dall[2 * n] = NO_CONTACT  # no rib
    rib_contact = state.rib_contact
    for a in range(4):
        rib_contact[a] = 0.0
    if bearing.has_rib:
        rib = bearing.rib
        cx = rib[0]
        cy = rib[1]
        R_end = rib[2]
        sa = np.sin(bearing.alpha)
        ca = np.cos(bearing.alpha)
        # nominal rib plane (ring coordinates): normal n0 and a point l0 (u0 = (sa, -ca), v0 = (ca, sa))
        n0r = rib[3] * sa + rib[4] * ca
        n0z = -rib[3] * ca + rib[4] * sa
        l0r = 0.5 * bearing.Dpw + cx * sa + cy * ca + R_end * n0r
        l0z = -cx * ca + cy * sa + R_end * n0z
        # current circle centre, world then ring coordinates
        cr = frames.Cen[0] + cx * ur + cy * vr
        cz = frames.Cen[1] + cx * uz + cy * vz
        tr = cr - ring[1] * cpsi
        tz = cz - ring[0]
        cp = np.cos(phi)
        sp = np.sin(phi)
        lr = cp * tr + sp * tz
        lz = -sp * tr + cp * tz
        drib = (lr - l0r) * n0r + (lz - l0z) * n0z + R_end
        nwr = cp * n0r - sp * n0z
        nwz = sp * n0r + cp * n0z
        # circular (sphere) or elliptical (torus) Hertz: the equivalent sphere of the same Q(delta)
        Qr, dQ = hertz_point_load(drib, rib[5], elasticity.E_star)
        g[0] = nwr * ur + nwz * uz
        g[1] = nwr * vr + nwz * vz
        # d centre / dtheta = cx v' - cy u'
        g[2] = cx * (nwr * vr + nwz * vz) - cy * (nwr * ur + nwz * uz)
        g[3] = -nwz
        g[4] = -nwr * cpsi
        for a in range(NY):
            f[a] -= Qr * g[a]
            for b in range(a, NY):
                K[a, b] += dQ * g[a] * g[b]
        # the circle centre turns with the roller: n . d2c/dtheta2 = -n . (cx u' + cy v')
        K[2, 2] -= Qr * cx * (nwr * ur + nwz * uz) + Qr * cy * (nwr * vr + nwz * vz)
        state.Q[2] = Qr
        dall[2 * n] = drib
        state.depth[2] = drib
        rib_contact[0] = cr + R_end * nwr
        rib_contact[1] = cz + R_end * nwz
        rib_contact[2] = nwr
        rib_contact[3] = nwz
    for a in range(NY):
        for b in range(a):
            K[a, b] = K[b, a]
    return ok


@kernel
def ring_turn_force(state, ring, cpsi, w):
    """Generalised force of one roller's contacts on the inner ring's turn phi in the roller's
    meridian plane, -dE/dphi [N mm] (E the contacts' elastic energy), at the state
    :func:`roller_contact` left in ``state`` (slice loads, frames, rib load and contact).

    The ring's points move with the turn as world = Rot(phi) ring + T, T = (delta_r cpsi, delta_a)
    (:func:`sim.physics.contact.to_ring`), so a surface point P moves by dP/dphi = (-(P_z - T_z),
    P_r - T_r), and a contact's penetration changes by -n . dP/dphi (n its unit normal into the
    ring, as the translation columns of G are -n). So -dE/dphi = sum Q (P - T) x n over the loaded
    inner slices (Q = w q, P the contact point X) and the rib (its circle centre or contact point,
    the same product): the moment of the normal forces on the ring about T, positive in the sense
    of phi ((a x b) = a_r b_z - a_z b_r). The dynamic solver's orbit force of an imposed tilt,
    whose turn tilt cos(phi_j) depends on the roller's azimuth, is this times d(turn)/d(phi_j).

    Parameters
    ----------
    state : RollerContact
    ring : ndarray (2,)
        delta_a, delta_r of the inner ring [mm], as given to :func:`roller_contact`.
    cpsi : float
        cos(psi), as given to :func:`roller_contact`.
    w : float
        Slice width [mm].
    """
    n = state.q.shape[1]
    Tr = ring[1] * cpsi
    Tz = ring[0]
    X = state.frames.X[1]
    Nrm = state.frames.Nrm[1]
    m = 0.0
    for k in range(n):
        if state.q[1, k] > 0.0:
            m += w * state.q[1, k] * ((X[k, 0] - Tr) * Nrm[k, 1] - (X[k, 1] - Tz) * Nrm[k, 0])
    if state.Q[2] > 0.0:
        rc = state.rib_contact
        m += state.Q[2] * ((rc[0] - Tr) * rc[3] - (rc[1] - Tz) * rc[2])
    return m

