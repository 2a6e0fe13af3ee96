"""Time-domain multibody solver: inner ring, Z rollers and cage (issue 18 item 2; mm, N, t, s, rad).

Bodies and degrees of freedom
-----------------------------
- Inner ring: prescribed spin speed omega_i about its own axis; translation (delta_a along +z,
  delta_x, delta_y) with mass m_ring under the external Fa (+z) and Fr (+x); an imposed tilt about
  the y axis (``body.tilt``, the quasi-static solver's load.tilt), held by the shaft: in the
  meridian plane of a roller at azimuth phi_j the ring is turned by tilt cos(phi_j), as in the
  quasi-static solver (the tilt's component across the plane, tilt sin(phi_j), is left out of the
  planar contact in both). The outer ring is fixed.
- Roller j, 6 DOF, in the meridian plane through its centre at azimuth phi_j:
  translations xi, eta (the quasi-static solver's coordinates along the nominal roller axes u, v
  of the meridian plane, :mod:`sim.solvers.quasi_static`) and phi_j (orbit); rotations: tilt
  theta (in the meridian plane), skew psi (about v', out of the meridian plane) and spin. The
  roller is axisymmetric: its spin angle is cyclic and never enters (only the spin rate does),
  so the orientation needed is its axis u'' = cos(psi) u'(theta) + sin(psi) e_t, with
  u'(theta) as in :func:`sim.physics.contact.roller_axes`. This two-angle chart of the unit
  sphere relative to the orbiting meridian frame is singular only at |psi| = 90 deg (u'' along
  e_t); the cage pocket bounds the skew to about its clearance (0.1-1 deg), so the chart is
  regular over the whole motion. The rotational state is the angular momentum H (components on
  e_r, e_t, e_z of the roller's meridian frame), not angle rates: H = I_x (omega.u'') u'' +
  I_y (omega - (omega.u'') u''), exact for an axisymmetric rigid body.
- Cage: planar rotation phi_c, omega_c (no radial motion: the pocket forces of a purely
  axially loaded bearing cancel radially; a radially guided cage is not modelled).

Equations (exact rigid-body dynamics, no small-angle step):
- roller centre in cylindrical coordinates (r, phi, z): m (r'' - r phi'^2) = F_r,
  m (r phi'' + 2 r' phi') = F_t, m z'' = F_z (centrifugal and Coriolis terms included);
- Euler's law in the meridian frame, which turns at phi' about z: dH/dt = M - phi' e_z x H.
  The gyroscopic moments of the spinning, orbiting roller are part of it: at steady orbit the
  contacts must supply M = phi' e_z x H = phi' u_r (I_x omega_a - I_y phi' u_z) e_t, whose
  first term I_x omega_R omega_c sin(alpha) is the gyroscopic moment of Harris & Kotzalas
  (2007, Advanced Concepts, ch. 2, roller gyroscopic moment) that the quasi-static solver
  applies (MODEL.md 4);
- axis kinematics: with Omega = omega - phi' e_z (rate relative to the meridian frame),
  theta' cos(psi) = Omega . w'' and psi' = Omega . v', w'' = u'' x v';
- without skew (``body.skew`` false, as the quasi-static solver without friction.skew) psi = 0
  is a constraint: the pocket supplies the couple lambda v' that keeps H.v' = I_y phi' v'_z
  (lambda from the derivative of that identity), and the cage takes its reaction;
- inner ring: m_ring delta'' = F_ext + sum of the contact forces of the rollers (normal loads
  and the reaction of the tractions of its raceway and rib contacts).

Loads (every formula is a physics kernel; this module only assembles them):
- normal contact: :func:`sim.physics.roller_contact.roller_contact` at the roller's pose
  (xi, eta, theta) and the inner ring's displacement projected on the roller's meridian plane
  (the load distribution stays planar in the skew, as in the quasi-static skew model); contact
  damping: stiffness-proportional (Rayleigh) damping on the contact's own exact tangent
  stiffness K, f_d = -beta K dy/dt in the contact chart y = (a, b, theta, delta_a, delta_r),
  a damping ratio zeta = beta omega / 2 at a contact frequency omega (``body.beta``, config);
  delta_r = delta_x cos(phi) + delta_y sin(phi) depends on the roller's orbit angle wherever the
  ring is displaced across its meridian plane (e_perp = -delta_x sin(phi) + delta_y cos(phi)), so
  the contact has a generalized force on phi, Q_phi = (f_r + f_d,r) e_perp [N mm] (f_r the radial
  force of the roller's contacts on the ring), the orbit's tangential force Q_phi / r, and
  d delta_r / dt holds e_perp phi' (the inner raceway's normals meet the ring's own axis, not the
  bearing's: turned by e_perp / r out of the meridian plane). The imposed tilt's turn tilt cos(phi)
  depends on the orbit angle likewise: Q_phi = -f_turn tilt sin(phi), f_turn = -dE/d(turn) the
  moment of the roller's normal forces on the ring about its turning point
  (:func:`sim.physics.roller_contact.ring_turn_force`; tests/dynamic/test_imposed_tilt.py: it
  against the penetrations' differences, and the energy of orbiting rollers on a tilted ring). The ring takes f_r along e_r as
  before: the contact energy, a function of (delta_a, delta_r(phi, delta_x, delta_y)) and the
  roller's pose, is invariant under a common turn of ring and rollers about z, so energy and
  angular momentum about z are conserved (tests/dynamic/test_ladder.py). The drive's torque is
  then the bearing's friction torque (power loss / speed at a steady state); the outer ring's
  differs from it by the orbit moments' mean sum, the power the contacts' normal forces put into
  the rollers' motion in their meridian planes (sliding along the axis and tilting as they cross
  a load zone, against the lateral tractions) per unit orbit angle: 0 where every roller keeps its
  pose (a pure axial load), more than the drive's torque itself for tsrb_pinion_long at 5 / 4 kN,
  6340 rpm (outer ring -324 against the drive's 2426 N mm over windows that do not settle), whose
  rollers slide 1-7 mm along their axes around the orbit;
- raceway and rib traction, rolling resistance and drag: :func:`sim.physics.friction.roller_traction`
  with the roller's own orbit speed phi'_j in place of the cage speed and its own spin and skew
  (2-D slip per slice with skew), :func:`sim.physics.friction.roller_drag`; the film (thickness,
  load share, rolling forces, Hertz data, thermal viscosity) of each roller at its loads and
  speeds of the moment (:func:`sim.physics.friction.roller_lubrication`, in every right-hand
  side: under a radial load a roller crosses the load zone within a fraction of a window; held
  over a window until session 21, a roller carried the traction of its load at the window's
  start around the bearing). The slip is the full rigid-body one
  (:data:`sim.physics.friction.RollerRates`, friction module docstring "Rates"): the skew rate
  psi' (each slice moves by psi' x along e_t, the spin about n gains psi' v'.n; the only damping
  of the skew on the TRB's rib, whose restoring stiffness with I_y would otherwise ring undamped
  at ~2.4 kHz, TRB 31313, 35 kN; damping ratio ~30 with it), the tilt rate Omega.w'' and the
  centre's velocity (r', z') in the meridian plane, their in-plane parts in the lateral slip of
  every slice and the rib (the normal parts, squeeze, are the contact damping's), and the inner
  ring's translation velocity in the slip of its raceway and rib contacts, whose tractions react
  on the ring's translation (as the quasi-static ring balance takes that reaction). The inner ring
  spins about its own axis (friction module docstring, "Inner ring": its pose at each roller,
  delta_r, delta_a and e_perp, in ContactLoads.ring); the drive's torque is its contacts' moment
  about that axis (EV_TRING), whose product with omega_i is the drive's power;
- cage pocket: circumferential penalty at the pitch radius r_pocket on the gap g = r_pocket (phi_j -
  phi_c - 2 pi j / Z), force -k (|g| - c/2) sign(g) beyond the half play c/2 (its moment about z
  r_pocket times it, on the roller as on the cage) plus a damper while in contact (never pulling),
  both set in smoothly over a transition depth (a roller resting on its pocket with a few
  hundredths of a newton sits there: a kink in the force made the integrator's steps 100x
  shorter), its friction
  (:func:`sim.physics.friction.pocket_friction`), and with skew the pocket couple
  (:func:`sim.physics.friction.pocket_skew_couple`) with a damper of the same ratio.

Quadrature states (time integrals, for the power balance and the exact means of a window): work of
the drive and the external loads, contact damping, elastic energy of the contacts, the pocket's
work (spring, damper, skew constraint), the lateral-slip power of skewed rollers (a part of
sliding), the friction dissipation of each mechanism (the kernels' loss powers, in the order of
sim.physics.friction.COMPONENTS), and the angular impulses of the outer-ring and drive torques.
A window's mean of each is its change over the window's duration, to the integrator's tolerance;
means of samples taken at fixed instants missed the short traction peaks of rollers entering a
load zone (prototype TSRB at 1.05 / 1.15 kN, 1891 rpm: sampled torque 3 % below the power loss
over the speed).
"""
from collections import namedtuple

import numpy as np
from scipy.integrate import solve_ivp
from threadpoolctl import threadpool_limits
from tqdm import tqdm

from sim._math.jit import kernel
from sim.physics.friction import (EV_FT, EV_FU, EV_FV, EV_MS, EV_MU, EV_MW, EV_P0, EV_PSKEW, EV_RING_R, EV_RING_T,
                                  EV_RING_Z, EV_TOUT, EV_TRING, EV_TZ, NC, NEV, RP_COS, RP_DA, RP_DR, RP_PERP, RP_SIN,
                                  RollerRates, film_scratch, pocket_friction, pocket_skew_couple, pocket_wall_force,
                                  roller_drag, roller_lubrication, roller_traction)
from sim.physics.roller_contact import NY, ContactFrames, RollerContact, ring_turn_force, roller_contact

# State layout. Per roller NS entries: xi, eta [mm], phi [rad], xi', eta' [mm/s], phi' [rad/s],
# theta, psi [rad], H_r, H_t, H_z [t mm^2/s = N mm s]; then the inner ring (delta_a, delta_x,
# delta_y [mm], their rates [mm/s]), the cage (phi_c [rad], omega_c [rad/s]) and the quadrature
# states (module docstring): energies [N mm] E_IN ... E_SKEW and E_DISS + i (mechanism i), angular
# impulses [N mm s] A_TOUT, A_TIN.
XI, ETA, PHI, VXI, VETA, WPHI, THETA, PSI, HR, HT, HZ = range(11)
NS = 11
NRING = 6
NCAGE = 2
E_IN, E_DAMP, E_ELASTIC, E_POCKET, E_SKEW = range(5)
E_DISS = 5
A_TOUT = E_DISS + NC
A_TIN = A_TOUT + 1
NE = A_TIN + 1
# States shared by all rollers (inner ring, cage, quadrature states), after the Z NS roller states:
# each roller's share in their derivatives is a row of ``shared_rows`` (:func:`rhs`).
NSH = NRING + NCAGE + NE

# Per-roller outputs of :func:`rhs` (``rol``, Z x NRO): outer, inner raceway and rib loads [N],
# pocket force on the roller along e_t [N], spin omega_R relative to the orbit [rad/s].
RO_QO, RO_QI, RO_QRIB, RO_FP, RO_WR = range(5)
NRO = 5
# Bearing outputs of :func:`rhs` (``tot``): torque on the outer ring [N mm], drive torque of the
# inner ring [N mm] (the friction torque: module docstring, "Loads"), then the loss powers of
# sim.physics.friction.COMPONENTS [N mm/s], then the damping power (contacts and pocket) [N mm/s], then the power of the lateral tractions on the
# lateral slip of the skewed rollers (EV_PSKEW, a part of the sliding power) [N mm/s].
TO_TOUT, TO_TIN = 0, 1
TO_P0 = 2
TO_DAMP = TO_P0 + NC
TO_PSKEW = TO_DAMP + 1
NTO = TO_PSKEW + 1

# Bodies and parameters of one dynamic case (numba-supported named tuple):
DynamicBody = namedtuple("DynamicBody", [
    "m",          # t, roller mass
    "Ix",         # t mm^2, roller moment of inertia about its axis
    "Iy",         # t mm^2, about a transverse axis through its centre
    "m_ring",     # t, inner ring (and what moves with it)
    "I_cage",     # t mm^2, cage about the bearing axis
    "r_pocket",   # mm, radius of the pocket contact (pitch radius)
    "k_pocket",   # N/mm, circumferential pocket stiffness (both roller ends)
    "c_pocket",   # N s/mm, its damper
    "half_play",  # mm, circumferential half play of a roller in its pocket
    "pocket_transition",  # mm, depth over which the pocket contact's stiffness and damping set in
    "c_skew",     # N mm s/rad, damper of the pocket skew couple
    "beta",       # s, stiffness-proportional contact damping
    "Fa",         # N, axial load on the inner ring along +z
    "Fr",         # N, radial load on the inner ring along +x
    "wi",         # rad/s, inner-ring speed
    "tilt",       # rad, imposed inner-ring tilt about the y axis (the quasi-static solver's load.tilt)
    "skew",       # bool, skew is free (else psi = 0 by the pocket)
    "friction",   # bool, traction, drag and pocket friction (else normal contact and pocket only)
])
# Everything of a dynamic case: sim.physics.roller_contact.BearingArrays, SliceElasticity, the
# FrictionCase (its frames, loads and film are updated in place) and the DynamicBody.
DynamicProblem = namedtuple("DynamicProblem", ["bearing", "elasticity", "case", "body"])
# Scratch arrays of one rhs call (sizes from n slices): poses (Z, 3), active (Z, 2, n), and the
# contact state of one roller.
DynamicWork = namedtuple("DynamicWork", ["poses", "active", "f", "K", "Q", "depth", "G", "d", "ribc", "ev",
                                         "ring", "ydot", "fd", "film"])


def state_size(Z):
    """Length of the state vector of Z rollers."""
    return Z * NS + NRING + NCAGE + NE


def empty_work(Z, n, nq):
    """:data:`DynamicWork` for Z rollers of n slices and nq film width points."""
    return DynamicWork(np.zeros((Z, 3)), np.zeros((Z, 2, n), dtype=np.bool_), np.zeros(NY), np.zeros((NY, NY)),
                       np.zeros(3), np.zeros(3), np.zeros((2 * n + 1, NY)), np.zeros(2 * n + 1), np.zeros(4),
                       np.zeros(NEV), np.zeros(2), np.zeros(NY), np.zeros(NY), film_scratch(n, nq))


@kernel
def roller_axis(theta, psi, alpha):
    """Roller axis u'' and the axes v', w'' = u'' x v' (components e_r, e_t, e_z) at tilt theta
    and skew psi [rad] (module docstring), as a (3, 3) array of rows u'', v', w''."""
    t = alpha + theta
    ur = np.sin(t)
    uz = -np.cos(t)
    cp = np.cos(psi)
    sp = np.sin(psi)
    A = np.empty((3, 3))
    A[0, 0] = cp * ur
    A[0, 1] = sp
    A[0, 2] = cp * uz
    A[1, 0] = -uz
    A[1, 1] = 0.0
    A[1, 2] = ur
    A[2, 0] = sp * ur
    A[2, 1] = -cp
    A[2, 2] = sp * uz
    return A


@kernel
def angular_velocity(H, A, Ix, Iy, w):
    """Angular velocity w (3,) [rad/s] of the axisymmetric roller with momentum H and axis A[0]:
    omega = H_a / I_x u'' + (H - H_a u'') / I_y; returns omega_a = omega . u''."""
    Ha = H[0] * A[0, 0] + H[1] * A[0, 1] + H[2] * A[0, 2]
    for i in range(3):
        w[i] = Ha / Ix * A[0, i] + (H[i] - Ha * A[0, i]) / Iy
    return Ha / Ix


@kernel
def rhs(y, problem, work, dy, rol, tot, shared_rows, film):
    """Time derivative ``dy`` of the state ``y`` (layout above) and the outputs.

    rol (Z, NRO) and tot (NTO,) are written (module constants); shared_rows (Z, NSH) receives
    each roller's contribution to the derivatives of the shared states (inner-ring and cage
    rates, quadrature states [N mm/s, N mm]; the finite-difference Jacobian, :func:`jacobian`,
    separates the rollers by it). ``film``: each roller's film is taken at this state
    (:func:`sim.physics.friction.roller_lubrication`); False: the film of the last call that took it
    is kept (the Jacobian's perturbed states, :func:`jacobian`).
    """
    bearing = problem.bearing
    case = problem.case
    body = problem.body
    par = case.par
    Z = bearing.Z
    alpha = bearing.alpha
    sa = np.sin(alpha)
    ca = np.cos(alpha)
    o_ring = Z * NS
    o_cage = o_ring + NRING
    o_en = o_cage + NCAGE
    da = y[o_ring]
    dxr = y[o_ring + 1]
    dyr = y[o_ring + 2]
    va = y[o_ring + 3]
    vx = y[o_ring + 4]
    vy = y[o_ring + 5]
    wc = y[o_cage + 1]
    m = body.m
    Ix = body.Ix
    Iy = body.Iy
    f = work.f
    K = work.K
    ev = work.ev
    ring = work.ring
    ydot = work.ydot
    fd = work.fd
    w = np.empty(3)
    H = np.empty(3)
    M = np.empty(3)
    for i in range(NTO):
        tot[i] = 0.0
    for j in range(Z):
        o = j * NS
        rows = shared_rows[j]
        for i in range(NSH):
            rows[i] = 0.0
        xi = y[o + XI]
        eta = y[o + ETA]
        phi = y[o + PHI]
        wphi = y[o + WPHI]
        theta = y[o + THETA]
        psi = y[o + PSI] if body.skew else 0.0
        cph = np.cos(phi)
        sph = np.sin(phi)
        ring[0] = da
        ring[1] = dxr * cph + dyr * sph
        pose = work.poses[j]
        pose[0] = xi
        pose[1] = eta
        pose[2] = theta
        frames = case.frames
        state = RollerContact(pose, case.bearing.q[j], work.active[j], f, K, work.Q, work.depth, work.G, work.d,
                              work.ribc, ContactFrames(frames.X[j], frames.Nrm[j], frames.Cen[j], frames.Ax[j],
                                                       frames.Xrib[j]), case.bearing.free[j])
        # the imposed tilt turns the ring by tilt cos(phi) in this meridian plane (as quasi-static)
        turn = body.tilt * cph
        roller_contact(ring, turn, 1.0, bearing, problem.elasticity, state)
        f_turn = ring_turn_force(state, ring, 1.0, bearing.w) if body.tilt != 0.0 else 0.0
        ur = frames.Ax[j, 0]
        uz = frames.Ax[j, 1]
        vr = frames.Ax[j, 2]
        vz = frames.Ax[j, 3]
        r = frames.Cen[j, 0]
        rdot = y[o + VXI] * sa + y[o + VETA] * ca
        zdot = -y[o + VXI] * ca + y[o + VETA] * sa
        A = roller_axis(theta, psi, alpha)
        for i in range(3):
            H[i] = y[o + HR + i]
        wa = angular_velocity(H, A, Ix, Iy, w)
        # rates relative to the meridian frame (module docstring)
        Om0 = w[0]
        Om1 = w[1]
        Om2 = w[2] - wphi
        theta_dot = (Om0 * A[2, 0] + Om1 * A[2, 1] + Om2 * A[2, 2]) / np.cos(psi)
        psi_dot = Om0 * A[1, 0] + Om1 * A[1, 1] + Om2 * A[1, 2] if body.skew else 0.0
        wR = wa - wphi * A[0, 2]
        # contact chart rates and stiffness-proportional damping f_d = -beta K dy/dt
        ydot[0] = rdot * ur + zdot * uz
        ydot[1] = rdot * vr + zdot * vz
        ydot[2] = theta_dot
        ydot[3] = va
        # delta_r = delta_x cos(phi) + delta_y sin(phi) changes with the ring's velocity and with the
        # roller's orbit: d delta_r / d phi = e_perp, the ring's displacement across the meridian plane
        e_perp = -dxr * sph + dyr * cph
        ydot[4] = vx * cph + vy * sph + e_perp * wphi
        P_el = 0.0
        P_damp = 0.0
        for a in range(NY):
            s = 0.0
            for b in range(NY):
                s += K[a, b] * ydot[b]
            fd[a] = -body.beta * s
            P_el -= f[a] * ydot[a]
            P_damp -= fd[a] * ydot[a]
        P_el += f_turn * body.tilt * sph * wphi
        Fr_ = (f[0] + fd[0]) * ur + (f[1] + fd[1]) * vr
        Fz_ = (f[0] + fd[0]) * uz + (f[1] + fd[1]) * vz
        # the contact's generalized force on the orbit angle: its energy depends on phi through
        # delta_r, Q_phi = f_r e_perp [N mm] (f_r = f[4], the radial force of the contacts on the ring),
        # the orbit's force Q_phi / r along e_t. Geometrically: the inner raceway's normals pass
        # through the ring's own axis, turned by e_perp / r from the meridian plane. Without it the
        # contacts did net work on the orbit where the ring is displaced across the meridian plane
        # (tsrb_pinion_long at 5 / 4 kN, 6340 rpm, dx 0.107 mm, dy 0.22 mm: 3.05e5 N mm/s against the
        # contacts' net -2.87e5 N mm/s, a false steady state, session 33)
        Ft_ = (f[4] + fd[4]) * e_perp / r
        # the imposed tilt's turn tilt cos(phi) depends on the orbit angle likewise: Q_phi = f_turn
        # d(turn)/d(phi) = -f_turn tilt sin(phi) (f_turn = -dE/d(turn), ring_turn_force), and the
        # contact energy changes with it at d(turn)/dt = -tilt sin(phi) phi' (in P_el above). It is the
        # energy-consistent form of the normals' tilt across the meridian plane, tilt sin(phi), which
        # the planar contact, as the quasi-static solver's, leaves out of the load distribution
        Ft_ -= f_turn * body.tilt * sph / r
        # moment about the centre, components (e_r, e_t, e_z): the contact moment f_theta conjugate
        # to the tilt, whose rate is theta' = Omega . w'' / cos(psi), is f_theta w'' / cos(psi)
        # (w'' = u'' x v', -e_t without skew; its power f_theta theta' is the elastic energy's).
        # With skew the normals pass through the skewed axis u'' (sim.physics.friction, "Roller
        # skew"), so their moment has no component along u''; the kernel adds the first-order part
        # about v' (EV_MS) and the tangential force (EV_FT). About -e_t instead, the skew gave a
        # spurious spin couple f_theta sin(psi) and z-moment, and the outer-ring and drive torques
        # missed power loss / speed by 8 % at 0.36 deg skew (pinion TSRB, issue 18 item 6)
        for i in range(3):
            M[i] = (f[2] + fd[2]) * A[2, i] / np.cos(psi)
        # cage pocket: circumferential penalty and damper at the pitch radius
        g = body.r_pocket * (phi - y[o_cage] - 2.0 * np.pi * j / Z)
        gdot = body.r_pocket * (wphi - wc)
        Fs, ramp = pocket_wall_force(g, body.half_play, body.k_pocket, body.pocket_transition)
        Fp = Fs - ramp * body.c_pocket * gdot
        if Fp * Fs < 0.0:   # a damper never pulls the roller into the wall
            Fp = 0.0
        # the pocket's force acts at the pocket radius, where its gap is measured: moment Fp r_pocket
        # about z on the roller and -Fp r_pocket on the cage (as the quasi-static free rollers',
        # sim.solvers.kinematics._pocket_moment), a tangential force Fp r_pocket / r at the roller's
        # centre. Applied as Fp at the centre (until session 37) the pair's moments differed by
        # Fp (r - r_pocket), and the pocket did work Fp (r - r_pocket) phi' that no quadrature state
        # held: tsrb_pinion_long at 5 / 4 kN, 6340 rpm (rollers 1.6-11 mm along their axes), 4.7 % of
        # the drive's power (tests/dynamic/test_ladder.py, pocket impacts)
        Ft_ += Fp * body.r_pocket / r
        P_pocket = -Fp * gdot          # pocket work on the relative motion (spring + damper)
        Tcage = -Fp * body.r_pocket     # reaction on the cage about z
        # pocket couple about v' (skew): penalty with damper, or the skew constraint (below)
        Cs = 0.0
        if body.skew:
            Cs, dCs = pocket_skew_couple(psi, par)
            if dCs != 0.0:
                Cs -= body.c_skew * psi_dot
        Qo = work.Q[0]
        Qi = work.Q[1]
        Qr = work.Q[2]
        if body.friction:
            case.bearing.Qrib[j] = Qr
            case.bearing.nrib[j, 0] = work.ribc[2]
            case.bearing.nrib[j, 1] = work.ribc[3]
            # the inner ring's axis in this meridian plane, about which it spins (sim.physics.friction,
            # "Inner ring"; translated, and turned by the imposed tilt's share tilt cos(phi))
            pose_ring = case.bearing.ring[j]
            pose_ring[RP_DR] = ring[1]
            pose_ring[RP_DA] = da
            pose_ring[RP_COS] = np.cos(turn)
            pose_ring[RP_SIN] = np.sin(turn)
            pose_ring[RP_PERP] = e_perp
            # the film at this roller's loads, speed and orbit speed, so that it follows the roller
            # around the bearing (under a radial load a roller crosses the load zone in a fraction
            # of a window)
            if film:
                roller_lubrication(j, wR, wphi, body.wi, case, work.film)
            # the roller's rates relative to its meridian frame (orbiting at phi'): skew rate psi' = Omega.v',
            # tilt rate Omega.w'' = theta' cos(psi), centre velocity (r', z') [rad/s, mm/s]; the inner
            # ring's translation velocity along e_r, e_t, e_z at the roller's azimuth [mm/s], in the
            # slip of its raceway and rib contacts, whose tractions react on the ring (below)
            rates = RollerRates(psi_dot, Om0 * A[2, 0] + Om1 * A[2, 1] + Om2 * A[2, 2], rdot, zdot,
                                vx * cph + vy * sph, -vx * sph + vy * cph, va)
            roller_traction(j, wR, psi, rates, wphi, body.wi, case, ev)
            FD = roller_drag(wphi, r, par, ev)
            M_spin = ev[EV_MU]
            Fpf = pocket_friction(Fp, wR, par, case.bearing.rho_m, ev)
            # the pocket friction's moment on the roller about u'' (its force along v' at the pocket contact,
            # a distance rho_m along e_t from the axis) reacts on the cage: its z-component M_pf u''_z (the
            # roller's spin has a z-component). Its pair's power is -M_pf times the spin relative to the
            # pocket, omega_R + (phi' - omega_c) u''_z: the first term the cage loss (pocket_friction), the
            # second the pocket's work on the orbit relative to the cage. Without the cage's share (until
            # session 34) the cage loss was counted at the relative spin while the moment acted on the
            # absolute one: the fast pinion_alpha at 7.16 / 6.41 kN, 3910 rpm left 0.83 % of the drive's
            # work unbalanced, 0.08 % with the pocket friction off
            M_pf = ev[EV_MU] - M_spin
            Tcage -= M_pf * A[0, 2]
            P_pocket -= M_pf * A[0, 2] * (wphi - wc)
            Ft_ += ev[EV_FT] - FD
            Fr_ += ev[EV_FU] * ur + (ev[EV_FV] + Fpf) * vr
            Fz_ += ev[EV_FU] * uz + (ev[EV_FV] + Fpf) * vz
            for i in range(3):
                M[i] += ev[EV_MU] * A[0, i] + ev[EV_MS] * A[1, i] + ev[EV_MW] * A[2, i]
            tot[TO_TOUT] += ev[EV_TOUT]
            tot[TO_TIN] += ev[EV_TRING]
            for i in range(NC):
                tot[TO_P0 + i] += ev[EV_P0 + i]
                rows[NRING + NCAGE + E_DISS + i] = ev[EV_P0 + i]
            tot[TO_PSKEW] += ev[EV_PSKEW]
            rows[NRING + NCAGE + E_SKEW] = ev[EV_PSKEW]
            rows[NRING + NCAGE + E_IN] = body.wi * ev[EV_TRING]
            rows[NRING + NCAGE + A_TOUT] = ev[EV_TOUT]
            rows[NRING + NCAGE + A_TIN] = ev[EV_TRING]
        # translation (cylindrical coordinates: centrifugal and Coriolis terms)
        a_r = r * wphi * wphi + Fr_ / m
        a_z = Fz_ / m
        phidd = (Ft_ / m - 2.0 * rdot * wphi) / r
        dy[o + XI] = y[o + VXI]
        dy[o + ETA] = y[o + VETA]
        dy[o + PHI] = wphi
        dy[o + VXI] = a_r * sa - a_z * ca
        dy[o + VETA] = a_r * ca + a_z * sa
        dy[o + WPHI] = phidd
        dy[o + THETA] = theta_dot
        dy[o + PSI] = psi_dot
        # Euler in the meridian frame: dH/dt = M - phi' e_z x H
        for i in range(3):
            M[i] += Cs * A[1, i]
        d0 = M[0] + wphi * H[1]
        d1 = M[1] - wphi * H[0]
        d2 = M[2]
        if not body.skew:
            # psi = 0 held by the pocket: lambda v' keeps H.v' = I_y phi' v'_z, dv'/dtheta = -u'
            Hu = H[0] * ur + H[2] * uz
            lam = Iy * (phidd * vz - wphi * uz * theta_dot) + theta_dot * Hu - (d0 * vr + d2 * vz)
            d0 += lam * vr
            d2 += lam * vz
            Cs = lam
        dy[o + HR] = d0
        dy[o + HT] = d1
        dy[o + HZ] = d2
        # the pocket couple's reaction on the cage (its z-component) and its work
        Tcage -= Cs * A[1, 2]
        P_pocket -= Cs * (psi_dot + (wphi - wc) * A[1, 2])
        # inner ring: the roller's normal contact forces (f[3] axial, f[4] radial in its meridian
        # plane) and the reaction of its inner-raceway and rib tractions (e_r, e_t, e_z)
        F_ring_r = f[4] + fd[4]
        F_ring_t = 0.0
        F_ring_z = f[3] + fd[3]
        if body.friction:
            F_ring_r += ev[EV_RING_R]
            F_ring_t += ev[EV_RING_T]
            F_ring_z += ev[EV_RING_Z]
        rows[3] = F_ring_z / body.m_ring
        rows[4] = (F_ring_r * cph - F_ring_t * sph) / body.m_ring
        rows[5] = (F_ring_r * sph + F_ring_t * cph) / body.m_ring
        rows[NRING + 1] = Tcage / body.I_cage
        rows[NRING + NCAGE + E_DAMP] = P_damp
        rows[NRING + NCAGE + E_ELASTIC] = P_el
        rows[NRING + NCAGE + E_POCKET] = P_pocket
        rol[j, RO_QO] = Qo
        rol[j, RO_QI] = Qi
        rol[j, RO_QRIB] = Qr
        rol[j, RO_FP] = Fp
        rol[j, RO_WR] = wR
        tot[TO_DAMP] += P_damp
    # shared states: their own terms, then the rollers' shares
    for i in range(NSH):
        dy[o_ring + i] = 0.0
    dy[o_ring] = va
    dy[o_ring + 1] = vx
    dy[o_ring + 2] = vy
    dy[o_ring + 3] = body.Fa / body.m_ring
    dy[o_ring + 4] = body.Fr / body.m_ring
    dy[o_cage] = wc
    dy[o_en + E_IN] = body.Fa * va + body.Fr * vx
    for j in range(Z):
        for i in range(NSH):
            dy[o_ring + i] += shared_rows[j, i]



# Relative finite-difference step of the Jacobian: sqrt of the double-precision epsilon, the
# optimum of a forward difference (Dennis & Schnabel 1983, Numerical Methods for Unconstrained
# Optimization, 5.4), on max(|y_i|, scale_i).
FD_STEP = np.sqrt(np.finfo(np.float64).eps)


@kernel
def jacobian(y, f0, rows0, problem, work, scale, J, rol, tot):
    """Forward-difference Jacobian J = d(rhs)/dy at y (f0 = rhs(y), rows0 its shared_rows).

    A roller's derivatives depend only on its own state, the inner ring and the cage, and the
    derivatives of the shared states (ring and cage rates, quadrature states) are sums over
    rollers (each roller's share in ``shared_rows``): one rhs call perturbing state k of every
    roller at once gives column k of every roller block and its shared rows (NS calls), and one
    call per ring and cage state its full column (Curtis, Powell & Reid 1974 column grouping,
    with the shared rows separated by roller). Nothing depends on the quadrature states: their
    columns are zero. (Left zero, their rows lagged the Newton iterations of the implicit steps
    by one iteration, which made scipy's Radau recompute the Jacobian more often: TRB 32208
    4.5 kN 2000 rpm, 10 revolutions, 10987 rhs and 455 Jacobians against 9861 and 390.) Without
    skew the skew column is zero too (psi is held at 0).

    The film is held at f0's (``rhs`` with film False; the caller computes f0 just before, so
    ``problem.case.film`` holds the film at y): the Jacobian only steers the implicit steps'
    Newton iterations, whose residuals take the film at every state. What it leaves out: the film
    thickness's and the thermal viscosity factor's dependence on the speeds (the film goes as the
    entrainment speed^0.67, which a state's perturbation moves by ~1e-8), and, as the film holds
    the Hertz data and the viscosity at the width points' pressures, the tractions' dependence on
    the normal load through them (the contact's own forces and stiffness are recomputed). Measured
    (benchmarks/bench_dynamic.py, 10 revolutions): the numbers of right-hand sides and Jacobians
    within 1-8 % of the full Jacobian's, the torque at the end unchanged to 0.01 N mm, 5-6 % less
    CPU time.
    """
    Z = problem.bearing.Z
    nst = y.shape[0]
    o_ring = Z * NS
    o_en = o_ring + NRING + NCAGE
    yp = y.copy()
    fp = np.empty(nst)
    rows1 = np.empty((Z, NSH))
    for a in range(nst):
        for b in range(nst):
            J[a, b] = 0.0
    for k in range(NS):
        if k == PSI and not problem.body.skew:
            continue        # psi is held at 0 without skew: its column is zero (no rhs reads it)
        for j in range(Z):
            o = j * NS + k
            yp[o] = y[o] + FD_STEP * max(abs(y[o]), scale[o])
        rhs(yp, problem, work, fp, rol, tot, rows1, False)
        for j in range(Z):
            o = j * NS
            h = yp[o + k] - y[o + k]
            for i in range(NS):
                J[o + i, o + k] = (fp[o + i] - f0[o + i]) / h
            for i in range(NSH):
                J[o_ring + i, o + k] = (rows1[j, i] - rows0[j, i]) / h
            yp[o + k] = y[o + k]
    for c in range(o_ring, o_en):
        yp[c] = y[c] + FD_STEP * max(abs(y[c]), scale[c])
        h = yp[c] - y[c]
        rhs(yp, problem, work, fp, rol, tot, rows1, False)
        for i in range(nst):
            J[i, c] = (fp[i] - f0[i]) / h
        yp[c] = y[c]


# Integration and steady-state settings (conf/solver/dynamic.yaml, sim.api.dynamic_model):
# method ('Radau' or 'BDF', scipy.integrate.solve_ivp), rtol [1], atol (state vector), window
# [s] (the first steady-state window) and window_angle [rad] (the cage's turn of every window:
# whole roller passes), samples per window, max_windows (time cap),
# tol_speed, tol_torque, tol_load, tol_skew: relative changes of the window means of cage speed,
# drive torque and roller loads, and of the skews over the pocket's skew clearance, below
# which two consecutive windows count as steady, fluctuation_windows (the block of windows whose
# means may instead fluctuate about a steady state, fluctuates_about_a_steady_state), scale (state
# vector: finite-difference step floors, sim.api.dynamic_model), tol_power (the steady windows' power
# balance, Integration.unbalanced_power).
DynamicSettings = namedtuple("DynamicSettings", ["method", "rtol", "atol", "window", "window_angle", "samples",
                                                 "max_windows", "tol_speed", "tol_torque", "tol_load", "tol_skew",
                                                 "fluctuation_windows", "scale", "tol_power"])


class Integration:
    """Time integration of one dynamic case with the steady-state detector.

    After :meth:`run`: ``t`` (samples,), ``y`` (samples, state), ``rol_t`` (samples, Z, NRO),
    ``tot_t`` (samples, NTO), ``steady``
    (bool), ``windows``, ``change`` (the last relative changes of speed, torque, loads, skews),
    ``changes`` (those of every window after the first, in order), ``averaged_windows`` (1, or
    the block of windows whose mean is the steady state when they fluctuate about it),
    ``average_from`` (the sample where those windows begin),
    ``rhs_calls``, ``jac_calls``, ``lu_calls`` (LU decompositions of the Newton matrices),
    ``failure`` (None, or why the integrator stopped: the run then has no steady state, and the
    samples it reached stay in the series).
    """

    def __init__(self, problem, settings):
        self.problem, self.settings = problem, settings
        Z, n = problem.bearing.Z, problem.bearing.x.shape[0]
        self.Z = Z
        self.work = empty_work(Z, n, problem.case.quad.wq.shape[0])
        nst = state_size(Z)
        self.rol = np.zeros((Z, NRO))
        self.tot = np.zeros(NTO)
        self.shared_rows = np.zeros((Z, NSH))
        self.J = np.zeros((nst, nst))
        self.rhs_calls = 0
        self.jac_calls = 0
        self.lu_calls = 0

    def f(self, t, y):
        dy = np.empty_like(y)
        rhs(y, self.problem, self.work, dy, self.rol, self.tot, self.shared_rows, True)
        self.rhs_calls += 1
        return dy

    def jac(self, t, y):
        f0 = self.f(t, y)
        rows0 = self.shared_rows.copy()
        jacobian(y, f0, rows0, self.problem, self.work, self.settings.scale, self.J, self.rol, self.tot)
        self.jac_calls += 1
        return self.J.copy()

    def outputs(self, y):
        """(rol, tot) at state y."""
        self.f(0.0, y)
        return self.rol.copy(), self.tot.copy()

    def run(self, y0):
        """Integrate window by window until two consecutive windows agree (settings), or the last
        ``fluctuation_windows`` fluctuate about a steady state, or ``max_windows`` windows have run;
        returns self."""
        s = self.settings
        o_cage = self.Z * NS + NRING
        y = np.array(y0, dtype=float)
        ts, ys, rols, tots = [0.0], [y.copy()], [], []
        r0, t0 = self.outputs(y)
        rols.append(r0)
        tots.append(t0)
        self.steady = False
        self.failure = None
        self.windows = 0
        self.changes = []
        # one BLAS thread: the dense LU of the Newton matrix (~200 x 200) is 100x slower under
        # OpenBLAS's threads on a shared machine (measured 157 ms against 0.44 ms)
        # progress of a long run, one step per window (shown on a terminal only: disable=None)
        with threadpool_limits(1), tqdm(total=s.max_windows, desc="dynamic windows", unit="window", disable=None,
                                        leave=False) as bar:
            self._windows(y, s, o_cage, ts, ys, rols, tots, bar)
        return self

    def _windows(self, y, s, o_cage, ts, ys, rols, tots, bar):
        history = []
        self.averaged_windows = 1
        t = 0.0
        duration = s.window
        for w in range(s.max_windows):
            t_end = t + duration
            t_eval = np.minimum(t + duration * np.arange(1, s.samples + 1) / s.samples, t_end)
            sol = solve_ivp(self.f, (t, t_end), y, method=s.method, rtol=s.rtol, atol=s.atol, jac=self.jac,
                            t_eval=t_eval)
            self.lu_calls += sol.nlu
            for i in range(sol.t.shape[0]):
                r, tt = self.outputs(sol.y[:, i])
                ts.append(sol.t[i])
                ys.append(sol.y[:, i].copy())
                rols.append(r)
                tots.append(tt)
            if not sol.success:     # the samples it reached stay; no steady state
                self.failure = f"dynamic integration failed after t = {ts[-1]:.6g} s: {sol.message}"
                break
            self.windows = w + 1
            bar.update()
            y = sol.y[:, -1].copy()
            t = sol.t[-1]
            win = slice(len(ts) - sol.t.shape[0], len(ts))
            Y = np.array(ys[win])
            R = np.array(rols[win])
            # cage speed and torque: exact means (quadrature states, window_means); per-roller means
            # of the samples, sorted: under a radial load or a tilt the steady state is periodic in
            # the frame of the load, each roller's load and skew following its azimuth, so over a
            # window of whole roller passes (sim.api.dynamic_model.integration_settings) the set of the
            # rollers' means repeats, one roller's mean passing to another
            exact = window_means(ys[win.start - 1], Y[-1], ts[-1] - ts[win.start - 1], self.Z)
            # the next window: the cage's turn of whole roller passes at this window's cage speed
            # (the first at the quasi-static one, which may differ by a few 0.1 %: the rollers' arcs
            # of a window then crept from window to window, and with them the means of a roller
            # at a load zone's steep edge, 2.4e-3 of the largest load per window, prototype TSRB
            # at 1.05 / 1.15 kN)
            if exact.cage_speed > 0.0:
                duration = s.window_angle / exact.cage_speed
            means = (exact.cage_speed, exact.drive_torque,
                     np.sort(R[:, :, RO_QO:RO_QRIB + 1].mean(axis=0), axis=0),
                     np.sort(Y[:, PSI:self.Z * NS:NS].mean(axis=0)))
            history.append(means)
            if len(history) > 1:
                prev = history[-2]
                d_speed = abs(means[0] - prev[0]) / abs(means[0])
                d_torque = abs(means[1] - prev[1]) / max(abs(means[1]), np.finfo(float).tiny)
                d_load = np.abs(means[2] - prev[2]).max() / np.abs(means[2]).max()
                # skews against the pocket's skew clearance (0 without free skew)
                d_skew = np.abs(means[3] - prev[3]).max() / self.problem.case.par.skew_clearance
                self.change = (d_speed, d_torque, d_load, d_skew)
                self.changes.append(self.change)
                bar.set_postfix_str(f"change: cage speed {d_speed:.1e}, torque {d_torque:.1e}, loads {d_load:.1e}, "
                                    f"skews {d_skew:.1e}")
                if (d_speed < s.tol_speed and d_torque < s.tol_torque and d_load < s.tol_load
                        and d_skew < s.tol_skew):
                    self.steady = True
                    break
                # or the last windows fluctuate about a steady state (rollers rattling where a narrow
                # load zone ends): their mean, over the whole block, is then the steady state
                k = s.fluctuation_windows
                if len(history) > k and fluctuates_about_a_steady_state(
                        history[-k:], (s.tol_speed, s.tol_torque, s.tol_load, s.tol_skew),
                        self.problem.case.par.skew_clearance):
                    self.steady = True
                    self.averaged_windows = k
                    break
        self.t = np.array(ts)
        self.y = np.array(ys)
        self.rol_t = np.array(rols)
        self.tot_t = np.array(tots)
        # the sample at which the windows of the steady state's means begin (the state there and at
        # the end give their exact means, window_means)
        self.average_from = len(ts) - 1 - self.averaged_windows * s.samples
        if self.steady:     # settled means: a steady state only if their windows' power balance closes
            self.failure = self.unbalanced_power(self.y[self.average_from], self.y[-1], s.tol_power)
            self.steady = self.failure is None
        if self.steady:
            self._align(y, t, s)

    def unbalanced_power(self, y_from, y_to, tol):
        """Why the windows from state y_from to y_to, whose means settled, are no steady state, or
        None: at a steady state the drive's work goes into friction, contact damping and the pocket
        (quadrature states); the kinetic and the contacts' elastic energy return to themselves with
        the roller passes. Their balance must close within ``tol`` of the drive's work
        (solver.dynamic.steady_tolerance_power). It did not where the means settled while energy
        still went elsewhere: into a cage too heavy to move within the run (cage_inertia 1e3 kg m^2:
        3.6 % of the drive's work, the cage speed unchanged at 8e-9 per window), or out of the contacts, whose
        elastic forces did net work over the windows (tsrb_pinion_long at 5 / 4 kN, 5500 rpm: rollers
        sliding 1-6.7 mm along their axes around the orbit, the contacts delivering 53 % of the drive's
        power; session 33's checker D)."""
        drive, lost, elastic = window_work(y_from, y_to, self.Z)
        if abs(drive - lost) <= tol * abs(drive):
            return None
        return (f"no steady state: the window means settled, but the drive's work {drive:.6g} N mm and the work "
                f"dissipated {lost:.6g} N mm (friction, contact damping, pocket) differ by "
                f"{(lost - drive) / abs(drive):+.2%} (solver.dynamic.steady_tolerance_power = {tol:g}); the "
                f"contacts' elastic forces did {elastic:.6g} N mm of net work, the rest went into kinetic "
                f"energy")

    def _align(self, y, t, s):
        """The steady state at the instant the rollers pass the azimuths 2 pi j / Z of the
        quasi-static solution (roller j at psi_j, the radial load along psi = 0): integrated on from
        the end of the last window (state y at time t) until roller 0's orbit angle reaches the next
        multiple of 2 pi / Z (less than one roller pass). Sets
        ``y_aligned``, ``rol_aligned`` (state and per-roller outputs there; the problem's
        frames and line loads are left at that state) and ``azimuth_order`` (Z,): the roller at
        azimuth 2 pi j / Z is roller ``azimuth_order[j]``."""
        Z = self.Z
        pitch = 2.0 * np.pi / Z
        dphi = (-y[PHI]) % pitch
        if dphi > 1e-9 * pitch:
            sol = solve_ivp(self.f, (t, t + dphi / y[WPHI]), y, method=s.method, rtol=s.rtol, atol=s.atol,
                            jac=self.jac)
            if not sol.success:     # the run ends at its last window, without a steady state
                self.steady = False
                self.failure = (f"dynamic integration failed after t = {t:.6g} s (aligning the steady state): "
                                f"{sol.message}")
                return
            y = sol.y[:, -1].copy()
        slot = np.rint(np.mod(y[PHI:Z * NS:NS], 2.0 * np.pi) / pitch).astype(np.int64) % Z
        if not np.array_equal(np.sort(slot), np.arange(Z)):
            raise RuntimeError(f"rollers not one per azimuth slot at the aligned instant: slots {slot.tolist()}")
        self.y_aligned = y
        self.rol_aligned = self.outputs(y)[0]
        self.azimuth_order = np.argsort(slot)


def fluctuates_about_a_steady_state(block, tolerances, skew_clearance):
    """Whether consecutive windows' means ``block`` (the detector's tuples: cage speed, torque,
    sorted per-roller loads, sorted skews) fluctuate about a steady state: for every quantity,
    relative as the detector's changes (cage speed and torque to their block means, loads to the
    largest, skews to the pocket's skew clearance), the standard error of its mean over the block
    is below its tolerance (``tolerances``, in that order), and the means of the block's first and
    second halves differ by less than the tolerance plus twice the standard error of their
    difference (no drift beyond the tolerance that the scatter does not explain; a bare
    significance test would reject a stationary block for one of its ~20 loads most of the time).
    Windows of a run whose rollers rattle where a narrow load zone ends (TRB 32208 at 4.5 / 9 kN,
    2000 rpm) scatter by 1e-3 - 2e-3 in torque from window to window and never agree pairwise."""
    K = len(block)
    h = K // 2
    scales = (abs(np.mean([b[0] for b in block])), abs(np.mean([b[1] for b in block])),
              max(np.abs(b[2]).max() for b in block), skew_clearance)
    for i, (tol, scale) in enumerate(zip(tolerances, scales)):
        if scale <= 0.0:
            continue                        # a quantity that is 0 throughout (no skew, no rib)
        x = np.array([np.ravel(b[i]) for b in block], dtype=float) / scale
        if np.any(x.std(axis=0, ddof=1) / np.sqrt(K) >= tol):
            return False
        first, second = x[:h], x[K - h:]
        spread = np.sqrt((first.var(axis=0, ddof=1) + second.var(axis=0, ddof=1)) / h)
        if np.any(np.abs(first.mean(axis=0) - second.mean(axis=0)) > tol + 2.0 * spread):
            return False
    return True


# Exact means over a time span, from the quadrature states and the cage angle at its ends
# (:func:`window_means`): cage speed [rad/s], outer-ring and drive torques [N mm], loss power of
# each mechanism (NC,) [N mm/s], contact and pocket damping power and lateral-slip power [N mm/s].
WindowMeans = namedtuple("WindowMeans", ["cage_speed", "torque", "drive_torque", "power", "damping", "skew_power"])


def window_work(y_start, y_end, Z):
    """Work from state y_start to y_end (Z rollers; quadrature states) [N mm]: the drive's and the
    external loads' (E_IN), the work dissipated (friction, contact damping, pocket) and the net work of
    the contacts' elastic forces."""
    o_q = Z * NS + NRING + NCAGE
    d = np.asarray(y_end)[o_q:o_q + NE] - np.asarray(y_start)[o_q:o_q + NE]
    return float(d[E_IN]), float(d[E_DISS:E_DISS + NC].sum() + d[E_DAMP] + d[E_POCKET]), float(-d[E_ELASTIC])


def window_means(y_start, y_end, duration, Z):
    """:data:`WindowMeans` over a span of ``duration`` [s] from state y_start to y_end (Z rollers)."""
    o_cage = Z * NS + NRING
    o_q = o_cage + NCAGE
    d = (np.asarray(y_end) - np.asarray(y_start)) / duration
    return WindowMeans(float(d[o_cage]), float(d[o_q + A_TOUT]), float(d[o_q + A_TIN]),
                       d[o_q + E_DISS:o_q + E_DISS + NC].copy(), float(d[o_q + E_DAMP]), float(d[o_q + E_SKEW]))


@kernel
def kinetic_energy(y, problem):
    """Kinetic energy of rollers, inner-ring translation and cage at state y [N mm]: rollers
    1/2 m (r'^2 + z'^2 + r^2 phi'^2) + 1/2 H . omega; the ring's prescribed spin is left out
    (constant)."""
    bearing = problem.bearing
    body = problem.body
    Z = bearing.Z
    sa = np.sin(bearing.alpha)
    ca = np.cos(bearing.alpha)
    w = np.empty(3)
    H = np.empty(3)
    E = 0.0
    for j in range(Z):
        o = j * NS
        r = 0.5 * bearing.Dpw + y[o + XI] * sa + y[o + ETA] * ca
        v2 = y[o + VXI] ** 2 + y[o + VETA] ** 2 + (r * y[o + WPHI]) ** 2
        A = roller_axis(y[o + THETA], y[o + PSI] if body.skew else 0.0, bearing.alpha)
        for i in range(3):
            H[i] = y[o + HR + i]
        angular_velocity(H, A, body.Ix, body.Iy, w)
        E += 0.5 * body.m * v2 + 0.5 * (H[0] * w[0] + H[1] * w[1] + H[2] * w[2])
    o = Z * NS
    E += 0.5 * body.m_ring * (y[o + 3] ** 2 + y[o + 4] ** 2 + y[o + 5] ** 2)
    E += 0.5 * body.I_cage * y[o + NRING + 1] ** 2
    return E
