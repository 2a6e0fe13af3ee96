"""Quasi-static load distribution (MODEL.md 4): unknowns, residuals, Jacobians, Newton.

Unknowns. Inner ring: axial displacement ``delta_a`` along +z (the direction of Fa), radial
displacement ``delta_r`` along +x (the direction of Fr) and, where the load case is not
mirror-symmetric about the x-z plane (friction loads: the tangential tractions of the load zone
add up along y), lateral displacement ``delta_y`` along +y (:func:`solve_bearing`); its tilt is
imposed. Roller j
at azimuth psi_j = 2 pi j / Z, in its meridian plane: shift ``xi`` along its nominal axis u
(towards the large end: the roller axial displacement of DATA.md), radial shift ``eta`` along
the nominal v and tilt ``theta`` (positive turning u towards v). The outer ring is fixed.

Generalised coordinates and forces. The residual of a roller is written in its own tilted
frame: the force along u' and along v' and the moment about its centre (about u' x v' = -e_t,
positive when it turns u' towards v'), so a Newton step is taken in the local chart
y = (a, b, theta, delta_a, delta_r): a translation a u' + b v' of the roller centre (u', v'
of the current tilt; :func:`_local_to_pose` turns it into xi, eta), the tilt and the ring.
The contact state of a roller at a pose (contact frames, slice and rib loads, the generalised
forces f = -sum Q G, G = dd/dy of every contact, and the exact contact stiffness K = -df/dy) is
:func:`sim.physics.roller_contact.roller_contact`. The solver adds:

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
- :meth:`sim.api.bearing_model.BearingModel.solve` continues from the axisymmetric case in Fr,
  tilt and roller loads when the direct solve fails.

Body loads on a loaded roller: centrifugal force m omega_c^2 Dpw/2 along e_r and the
gyroscopic moment I_x omega_R omega_c sin(alpha) (rigid-body dynamics of a roller spinning
about its axis while the cage turns about z). External roller loads (friction, from
:mod:`sim.physics.friction`): per roller [force along u' towards the large end, force along v',
moment about u' x v'], [N, N, N mm], added to the roller residual like the body loads.
Rollers that the rings do not squeeze (rigid clearance) carry no load between the rings: the
cage holds them. With ``QuasiStaticProblem.rest`` (the centrifugal force on) such a roller rests
instead, as the time-domain solver's unloaded rollers run. A TRB roller rests on the cup and its
rib: the centrifugal force's component along u' pushes it up the cup onto the rib.
:func:`solve_roller` puts it onto both (:func:`_onto_the_rest`) and solves its equilibrium there
like any other, the inner raceway touching or not, so that a roller leaving the load zone goes
over into its rest continuously and the ring's Newton matrix takes its rib stiffness. TRB 31313 at
32.1 / 48.0 kN, 3821 rpm: 66.0 N on the cup and 33.9 N on the rib per roller, tilt -0.011 deg (the
time-domain run: 66 N, 32-35 N, -0.011 deg); their EHL rolling loss, which hardly depends on the
load, is 9 % of the torque (README, "Rollers outside the load zone"). A TSRB has no rib: the outer
raceway, whose normal is inclined to the roller axis, pushes the roller along its axis into the
wedge between both raceways until the inner raceway holds it too. :func:`solve_roller` moves it
there once (:func:`_onto_the_rest`) and then solves it like any other roller, free to leave both
rings (prototype TSRB at 1.05 / 1.15 kN, 1891 rpm: 4.8-5.1 N on the inner raceway, as in the time
domain). The rest is a second solve from the converged one without it
(sim.api.bearing_model.BearingModel.solve): from the start the ring's iteration stalled where the
rest's rib loads are large. Where that second solve finds no equilibrium (a TSRB's lightest wedged
rollers, 2-5 N, whose tilt balances the gyroscopic moment on one or two slices; a TRB whose rest's
rib loads walk the ring's iteration away), the converged solution without the rest stands and its
unloaded rollers are reported (``unrested_rollers``, and a warning); a roller released by the
rest's solve itself is counted the same way.

Iterative kernels return status flags instead of raising (STYLE.md); the wrapper in
:mod:`sim.api.bearing_model` decides. Kernels share state through named tuples (STYLE.md):
:data:`QuasiStaticProblem` (bearing arrays, slice elasticity, Newton settings, body loads),
:data:`RollerSet` (the rollers in and out), the roller's
:data:`sim.physics.roller_contact.RollerContact`, :data:`RollerWork` and :data:`SolveReport`.
"""
from collections import namedtuple

import numpy as np

from sim._math.jit import internal_kernel, kernel
from sim._math.linalg import copy_matrix, copy_vector
from sim.physics.contact import roller_axes
from sim.physics.roller_contact import NY, ContactFrames, RollerContact, roller_contact
from sim.solvers.symmetry import symmetry_classes

# Newton settings of the kernels, from sim.api.bearing_model.SolverSettings under the same names
# (conf/solver/quasi_static.yaml gives meaning, units and reasons): tolerance (relative force
# residual), max_iterations (ring), roller_max_iterations, roller_tolerance_ratio, forcing,
# roller_step_interference, roller_step_length (/ Lwe), line_search_halvings, ring_step_fraction.
NewtonSettings = namedtuple("NewtonSettings", ["tolerance", "max_iterations", "roller_max_iterations",
                                               "roller_tolerance_ratio", "forcing", "roller_step_interference",
                                               "roller_step_length", "line_search_halvings", "ring_step_fraction"])

# Body loads on a loaded roller (module docstring): centrifugal force along e_r [N] and gyroscopic
# moment about u' x v' [N mm].
BodyLoads = namedtuple("BodyLoads", ["centrifugal", "gyroscopic"])

# The fixed inputs of one quasi-static solve: sim.physics.roller_contact.BearingArrays,
# sim.physics.elasticity.SliceElasticity, NewtonSettings, BodyLoads, and rest: the rollers that the
# rings do not squeeze rest, a TRB's on the cup and the rib, a TSRB's in the wedge between both
# raceways (module docstring; the centrifugal force on, sim.api.bearing_model.BearingModel.solve).
QuasiStaticProblem = namedtuple("QuasiStaticProblem", ["bearing", "elasticity", "settings", "body", "rest"])

# The rollers of a bearing, in and out of solve_bearing (Z rollers, N slices per raceway):
# poses (Z, 3): xi [mm], eta [mm], theta [rad]; q, active (Z, 2, N): slice line loads [N/mm] and
# loaded flags per race (0 outer, 1 inner); Q (Z, 2): roller-raceway loads [N]; Q_rib (Z,): rib
# loads [N]; rib_contact (Z, 4): rib contact point (r, z) [mm] on the roller end and unit rib
# normal (r, z) into the rib, in the roller's meridian plane (zeros without a rib or for a roller
# not in equilibrium); frames: sim.physics.roller_contact.ContactFrames of the Z rollers; free
# (Z, 2, N): free penetrations of the slices [mm] (sim.physics.elasticity.coupled_slice_loads).
RollerSet = namedtuple("RollerSet", ["poses", "q", "active", "Q", "Q_rib", "rib_contact", "frames", "free"])

# What solve_bearing reports: converged; iterations (ring Newton iterations; axisymmetric case:
# Newton iterations of the load-controlled roller); residual_axial, residual_radial,
# residual_lateral: force residual on the inner ring [N]; unconverged_classes and loaded_classes:
# roller classes without equilibrium and loaded ones; roller_iterations (Newton), contact_evaluations (roller_contact
# calls), ring_backtracks; roller_classes: rollers solved (sim.solvers.symmetry); unrested_rollers:
# rollers outside the load zone released although problem.rest (left unloaded).
SolveReport = namedtuple("SolveReport", ["converged", "iterations", "residual_axial", "residual_radial",
                                         "residual_lateral", "unconverged_classes", "loaded_classes",
                                         "roller_iterations", "contact_evaluations", "ring_backtracks", "roller_classes",
                                         "unrested_rollers"])

# Load control of one roller solve: Fa_share, the roller's share Fa / Z of the axial load [N]
# with the ring's axial displacement a fourth unknown (axisymmetric case), 0 for a fixed ring;
# ring_scale, the length scale of the ring displacement [mm] (its start estimate); force_floor,
# the roller's absolute force tolerance at the least [N]: its share of the ring's final tolerance,
# roller_tolerance_ratio x tolerance x max(Fa, Fr) / Z (solve_bearing), so that the rollers'
# residuals together stay 1 / roller_tolerance_ratio below the ring's. Without it a roller that
# carries almost nothing (a TSRB roller at a load zone's edge, 0.3 N of a 3.7 kN largest load) was
# to balance to 1e-10 of its own load, 3e-11 N, below the round-off of its contact forces (its
# stiffness times the double-precision spacing of its pose, some 3e-10 N): it stalled, and the
# ring with it (pinion TSRB at 8.03 / 11.58 kN, 60 rpm, with the friction loads: session 29).
LoadControl = namedtuple("LoadControl", ["Fa_share", "ring_scale", "force_floor"])

# Work arrays of solve_roller (allocated once per bearing solve): the trial contact state and
# ring; the residuals at the current, trial and best extended state; the step; the Jacobian and
# its damped copy (NQ x NQ); the residual of the returned state (forces along u', v' [N], moment
# [N mm] and the max-norm of the line search [N]).
RollerWork = namedtuple("RollerWork", ["trial", "ring_trial", "R", "R_trial", "R_best", "step", "Kq", "K_lm",
                                       "residual"])

NQ = 4  # unknowns of a roller solve: a, b, theta, and delta_a under load control

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
# Travel of a roller step [mm]: the largest of its centre's moves and its ends' move from the
# tilt step, the tilt times the ends' distance from the centre, END_ARM x Lwe; an extended step
# travels at most one roller length.
END_ARM = 0.5
# A TRB roller that the rings do not squeeze is put onto the cup and the rib (_onto_the_rest)
# REST_START_DEPTH [mm] into each, 1 nm, far below its approach under its centrifugal force (0.1-2
# um for the 1-100 N of the rollers here), for solve_roller's bounded Newton steps to go on from;
# each move along v' or u' opens the other gap by a few percent of itself (the cup and rib angles
# to v' and u', 4 and 21 deg for the TRB 31313), so REST_CLOSING_MOVES alternations close both to
# round-off (measured: 2-3).
REST_START_DEPTH = 1e-6
REST_CLOSING_MOVES = 8
# A TSRB roller (no rib) that the rings do not squeeze is moved into the wedge between both raceways
# (_onto_the_rest), and a TRB roller onto its rib, along u' by at most WEDGE_MAX_TRAVEL x Lwe: the
# raceways close on a roller by the small angle between its generatrix and theirs (a few degrees),
# so that a roller of the unloaded side reaches both from some 0.1 mm (pinion_alpha TSRB at 11.4 /
# 14.4 kN, 1660 rpm, before the rest: the unloaded-side rollers that stayed loaded sat 0.12 mm
# further along u' than the released ones; the same bound holds a TRB roller's move onto its rib);
# a quarter of the roller's length bounds the search well inside the raceway (numerical choice: a
# roller that reaches no contact within it is released as before).
WEDGE_MAX_TRAVEL = 0.25


@internal_kernel
def _local_to_pose(pose, da, db, dth):
    """Apply a local step (da along u', db along v' of the current tilt [mm], dth [rad]) to a pose."""
    c = np.cos(pose[2])
    s = np.sin(pose[2])
    pose[0] += c * da - s * db
    pose[1] += s * da + c * db
    pose[2] += dth


@internal_kernel
def _kinematic_pose(ring, phi, cpsi, bearing, pose):
    """Start pose of a roller: rigid, midway between the rings (written to ``pose``).

    The inner-ring point at the nominal roller centre (Dpw/2, 0) moves by
    Delta = Rot(phi) P0 + (delta_r cos(psi), delta_a) - P0 in the meridian plane; the roller
    centre takes half of it along v (both raceways share the approach), all of it along u when
    the inner ring has a rib (the roller end stays on it) and half otherwise, and half of the
    ring rotation phi.
    """
    r0 = 0.5 * bearing.Dpw
    dr = r0 * (np.cos(phi) - 1.0) + ring[1] * cpsi
    dz = r0 * np.sin(phi) + ring[0]
    sa = np.sin(bearing.alpha)
    ca = np.cos(bearing.alpha)
    du = dr * sa - dz * ca
    dv = dr * ca + dz * sa
    pose[0] = du if bearing.has_rib else 0.5 * du
    pose[1] = 0.5 * dv
    pose[2] = 0.5 * phi


@internal_kernel
def _ring_projections(n, Z, lateral):
    """The azimuths psi_j = 2 pi j / Z of rollers j < n as projections of their meridian planes'
    (axial, radial) on the ring's (axial, x, y): rows (1, cos(psi_j), sin(psi_j)), the last 0 where
    the ring has no lateral displacement (:func:`solve_bearing`)."""
    proj = np.empty((n, 3))
    for j in range(n):
        psi = 2.0 * np.pi * j / Z
        proj[j, 0] = 1.0
        proj[j, 1] = np.cos(psi)
        proj[j, 2] = np.sin(psi) if lateral else 0.0
    return proj


@internal_kernel
def _meridian(ring, proj, out):
    """A ring displacement (or step) (delta_a, delta_r, delta_y) [mm] seen in the meridian plane of
    the roller of projection ``proj`` (a row of :func:`_ring_projections`): (delta_a, delta_r cos(psi) +
    delta_y sin(psi)), written to ``out``."""
    out[0] = ring[0]
    out[1] = ring[1] * proj[1] + ring[2] * proj[2]


@internal_kernel
def _solve_small(A, b, out, m):
    """Solve the leading m x m block A[:m, :m] out[:m] = b[:m] (m <= NQ) by Gaussian elimination
    with partial pivoting on a small work copy. Returns False when singular to working precision.
    """
    M = np.empty((NQ, NQ + 1))
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


@internal_kernel
def _roller_residual(f, theta, alpha, Lwe, body, ext, R):
    """Residual of one roller (contact forces f at tilt theta + body + external loads) in its
    frame; returns the max-norm.

    R[0], R[1] forces along u', v' [N]; R[2] moment [N mm]; norm max(|R0|, |R1|, |R2| / Lwe) [N].
    """
    ur, uz, vr, vz = roller_axes(alpha, theta)
    R[0] = f[0] + body.centrifugal * ur + ext[0]
    R[1] = f[1] + body.centrifugal * vr + ext[1]
    R[2] = f[2] + body.gyroscopic + ext[2]
    return max(abs(R[0]), abs(R[1]), abs(R[2]) / Lwe)


@internal_kernel
def _trial_pose(pose, t, p, trial, ring, ring_t, lc):
    """Trial pose ``pose + t p`` (local chart) and ring (delta_a + t p[3] under load control)
    (written to trial and ring_t)."""
    copy_vector(trial, pose)
    _local_to_pose(trial, t * p[0], t * p[1], t * p[2])
    ring_t[0] = ring[0] + t * p[3] if lc else ring[0]
    ring_t[1] = ring[1]


@internal_kernel
def _trial_residual(f, theta, alpha, Lwe, body, ext, Fa_share, R):
    """Roller residual (R[0:3]) and, under load control (Fa_share > 0), the ring's
    (R[3] = Fa_share + f[3]); returns the max-norm [N] (moment / Lwe)."""
    err = _roller_residual(f, theta, alpha, Lwe, body, ext, R)
    if Fa_share > 0.0:
        R[3] = Fa_share + f[3]
        err = max(err, abs(R[3]))
    return err


@internal_kernel
def _work(R0, R1, p, m, t):
    """Work of the residual forces along the step t p, trapezoidal rule [N mm]: the decrease of
    the potential energy, exact for a quadratic energy."""
    s = 0.0
    for a in range(m):
        s += (R0[a] + R1[a]) * p[a]
    return 0.5 * t * s


@internal_kernel
def _roller_jacobian(K, R, ext, Lscale, Kq, m):
    """Jacobian -dR/dy of the roller residual in the local chart (written to ``Kq[:m, :m]``).

    m = 3: roller unknowns; m = 4: also delta_a, with the ring's axial residual as fourth row.
    The contact stiffness K plus the turning residual frame: R0 = F.u' + ext0 and
    R1 = F.v' + ext1 give dR0/dtheta += F.v' = R1 - ext1 and dR1/dtheta += -F.u' = -(R0 - ext0);
    plus the round-off regularisation REG of the roller block (Lscale = Lwe [mm]).
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


@internal_kernel
def _bounded_step(Kq, R, m, G, d, d_step, arm, max_len, ring_step, p):
    """Newton step Kq p = R (first m unknowns) and its bound factor c in (0, 1] (solve_roller).

    c keeps the first-order change G p of the contact penetrations d within d_step [mm]
    (roller_step_interference x the roller's interference scale): a penetrating contact may lose
    at most that, any contact may gain at most its gap plus that (a contact far from touching may
    close its gap). It keeps the roller travel max(|p_a|, |p_b|, arm |p_theta|) within max_len
    [mm] (arm: the roller ends' distance from its centre [mm]) and the ring travel |p[3]| within
    ring_step [mm] (inf for a fixed ring, where p[3] = 0). Returns c, or -1 when Kq is singular.
    """
    if not _solve_small(Kq, R, p, m):
        return -1.0
    c = 1.0
    for k in range(G.shape[0]):
        v = 0.0
        for a in range(m):
            v += G[k, a] * p[a]
        if v > 0.0:
            lim = d_step + max(-d[k], 0.0)
        elif d[k] > 0.0:
            lim = d_step
        else:
            continue
        if abs(v) * c > lim:
            c = lim / abs(v)
    travel = max(abs(p[0]), abs(p[1]), arm * abs(p[2]))
    if c * travel > max_len:
        c = max_len / travel
    if c * abs(p[3]) > ring_step:
        c = ring_step / abs(p[3])
    return c


@kernel
def solve_roller(ring, phi, cpsi, ext, problem, tol, control, state, work):
    """Equilibrium of one roller (bounded Newton, honest line search), optionally load-controlled.

    Fixed ring (``control.Fa_share <= 0``): the roller's (a, b, theta) balance its contact, body
    and external loads at the given ring position. Load control (``control.Fa_share > 0``, the
    axisymmetric case where every roller is alike): the ring's axial displacement ring[0] is a
    fourth unknown and Fa_share + f[3] = 0 (the roller's share of Fa on the ring) a fourth
    residual, so that a roller that can only balance far from its start (a TSRB whose contact
    migrates to the roller edge, thesis Table A.6) keeps its load on the way; ring[0] is
    written back.

    Each Newton step (exact Jacobian, module docstring) is bounded (:func:`_bounded_step`): no
    slice or rib penetration changes, to first order, by more than roller_step_interference
    times the roller's interference scale (a contact away from touching may first close its
    gap), the roller moves by at most roller_step_length x Lwe and the ring by at most
    ring_step_fraction of its displacement. The step is then halved until the potential energy
    falls by the Armijo fraction of its first-order decrease (the work of the residual forces
    along the step, trapezoidal rule, :func:`_work`); without decrease, damped
    Levenberg-Marquardt steps are tried. A full step that does not halve the residual is
    extended while the energy keeps falling: a roller that a wedge of misaligned rings pushes
    out of its contacts has no loaded equilibrium, it comes free and the cage holds it. A
    roller touching one race only is centred between both, unless its loads press it onto
    that race (it rests there, the other ring does not squeeze it: unloaded). With
    ``problem.rest`` a roller the rings do not squeeze is put onto the cup and the rib and solved
    there (module docstring): no step may take it off the cup. A roller that gets no decrease is
    reported as not converged and left at its last accepted state.

    Parameters
    ----------
    ring : ndarray (2,)
        delta_a, delta_r [mm] (delta_a solved and written under load control).
    phi : float
        Imposed inner-ring rotation in the roller's meridian plane [rad] (tilt * cos(psi)).
    cpsi : float
        cos(psi) of the roller azimuth psi.
    ext : ndarray (3,)
        External load on the roller: force along u' towards the large end [N], force along v'
        [N], moment about u' x v' (positive turning u' towards v') [N mm].
    problem : QuasiStaticProblem
    tol : float
        Relative force tolerance of the roller (of its contact and body loads), with the
        absolute floor ``control.force_floor``; under load control the ring residual is held to
        settings.tolerance x Fa_share.
    control : LoadControl
    state : sim.physics.roller_contact.RollerContact
        The roller: pose start in, result out; q, active warm start in; the contact state of the
        returned pose out (need not be valid on entry).
    work : RollerWork
        Work arrays; ``work.residual`` is written with the residual at the returned pose when
        the roller is loaded (converged or not).

    Returns
    -------
    (status, iterations, evaluations): status 1 converged and loaded, 2 unloaded (rigid
    clearance, or pushed free), 0 not converged; Newton iterations; contact-state evaluations.
    """
    bearing = problem.bearing
    elasticity = problem.elasticity
    settings = problem.settings
    body = problem.body
    Lscale = bearing.Lwe
    alpha = bearing.alpha
    arm = END_ARM * Lscale
    max_len = settings.roller_step_length * Lscale
    trust = settings.roller_step_interference
    max_iter = settings.roller_max_iterations
    nbt = settings.line_search_halvings
    tol_ring = settings.tolerance
    Fa_share = control.Fa_share
    lc = Fa_share > 0.0
    m = 4 if lc else 3
    pose = state.pose
    f = state.f
    Q = state.Q
    depth = state.depth
    trial = work.trial
    ring_t = work.ring_trial
    R = work.R
    Rt = work.R_trial
    Rb = work.R_best
    p = work.step
    p.fill(0.0)
    Kq = work.Kq
    Klm = work.K_lm
    Rout = work.residual

    def try_step(t):
        """Contact state of the pose a step t along p, with the slice loads of the current state
        as warm start (into work.trial and work.ring_trial)."""
        _trial_pose(pose, t, p, trial.pose, ring, ring_t, lc)
        copy_matrix(trial.q, state.q)
        copy_matrix(trial.active, state.active)
        return roller_contact(ring_t, phi, cpsi, bearing, elasticity, trial)

    def step_bound(K_step):
        """_bounded_step with the roller's current interference scale and ring displacement."""
        d_step = trust * (max(depth[0], 0.0) + max(depth[1], 0.0) + max(depth[2], 0.0))
        ring_step = settings.ring_step_fraction * max(abs(ring[0]), control.ring_scale) if lc else np.inf
        return _bounded_step(K_step, R, m, state.G, state.d, d_step, arm, max_len, ring_step, p)
    # a TRB roller the rings do not squeeze rests on the cup and rib; a TSRB roller is moved into the
    # wedge between both raceways once before it may be released (module docstring)
    resting = problem.rest and not lc and bearing.has_rib
    wedging = problem.rest and not lc and not bearing.has_rib
    evals = 1
    ok = roller_contact(ring, phi, cpsi, bearing, elasticity, state)
    for it in range(max_iter):
        if depth[0] + depth[1] <= 0.0 and not (resting and depth[0] > 0.0):
            if resting and _onto_the_rest(ring, phi, cpsi, bearing, elasticity, state):
                # rings do not squeeze this roller: with problem.rest it rests on the cup and rib
                evals += 1
                continue
            if wedging:
                wedging = False
                evals += 1
                if _onto_the_rest(ring, phi, cpsi, bearing, elasticity, state):
                    continue
            if not lc:
                # rings do not squeeze this roller: unloaded, held by the cage
                _release(f, state.K, state.q, state.active, Q)
                return 2, it, evals
            # load control and nothing squeezed yet: push the ring along Fa by its length scale
            ring[0] += max(abs(ring[0]), control.ring_scale)
            if ring[0] > Lscale:
                return 0, it, evals  # moved by a roller length and still nothing carries the load
            _kinematic_pose(ring, phi, cpsi, bearing, pose)
            state.q.fill(0.0)
            state.active.fill(False)
            ok = roller_contact(ring, phi, cpsi, bearing, elasticity, state)
            evals += 1
            continue
        if Q[0] <= 0.0 or Q[1] <= 0.0:
            # touching one race only. With problem.rest a roller on the cup goes on to its
            # equilibrium there (module docstring). Otherwise, if its loads (contact, body,
            # external) press it onto that race (along v' outwards onto the outer one, inwards
            # onto the inner one), it rests there and the other ring does not squeeze it:
            # unloaded as far as the rings' balance goes. Otherwise, or under load control,
            # centre it along v between both races (rigid interference balance).
            _roller_residual(f, pose[2], alpha, Lscale, body, ext, R)
            pressed_out = Q[1] <= 0.0 and R[1] >= 0.0
            if resting and Q[0] > 0.0:
                # with problem.rest it rests on the cup (and, once the Newton steps close that gap,
                # on the rib): on to the equilibrium below
                if depth[2] <= 0.0 and _onto_the_rest(ring, phi, cpsi, bearing, elasticity, state):
                    evals += 1
            elif wedging and Q[0] > 0.0 and pressed_out:
                # a TSRB roller on the outer raceway alone: into the wedge once (module docstring)
                wedging = False
                evals += 1
                _onto_the_rest(ring, phi, cpsi, bearing, elasticity, state)
                continue
            elif not lc and (pressed_out or (Q[0] <= 0.0 and R[1] <= 0.0)):
                _release(f, state.K, state.q, state.active, Q)
                return 2, it, evals
            else:
                pose[1] += 0.5 * (depth[1] - depth[0])
                ok = roller_contact(ring, phi, cpsi, bearing, elasticity, state)
                evals += 1
                continue
        err = _roller_residual(f, pose[2], alpha, Lscale, body, ext, R)
        scale = Q[0] + Q[1] + Q[2] + abs(body.centrifugal) + abs(ext[0]) + abs(ext[1]) + abs(ext[2]) / Lscale
        done = err <= max(tol * scale, control.force_floor) and ok
        merit = err
        if lc:
            R[3] = Fa_share + f[3]
            done = done and abs(R[3]) <= tol_ring * Fa_share
            merit = max(err, abs(R[3]))
        if done:
            _residual_out(R, merit, Rout)
            return 1, it, evals
        _roller_jacobian(state.K, R, ext, Lscale, Kq, m)
        c = step_bound(Kq)
        if c <= 0.0:
            _residual_out(R, merit, Rout)
            return 0, it, evals
        travel = max(abs(p[0]), abs(p[1]), arm * abs(p[2]))
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
                if resting and trial.depth[0] <= 0.0:
                    pass        # off the cup: a shorter step
                elif trial.depth[0] + trial.depth[1] <= 0.0 and not resting:
                    if not lc:
                        free = True
                        accepted = True
                        break
                else:
                    merit_t = _trial_residual(trial.f, trial.pose[2], alpha, Lscale, body, ext, Fa_share, Rt)
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
                t = step_bound(Klm)
                if t <= 0.0:
                    continue
                slope = 0.0
                for a in range(m):
                    slope += R[a] * p[a]
                if slope <= 0.0:
                    continue
                ok_t = try_step(t)
                evals += 1
                if resting and trial.depth[0] <= 0.0:
                    continue    # off the cup
                if trial.depth[0] + trial.depth[1] <= 0.0 and not resting:
                    if not lc:
                        free = True
                        accepted = True
                        break
                    continue
                merit_t = _trial_residual(trial.f, trial.pose[2], alpha, Lscale, body, ext, Fa_share, Rt)
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
                if resting and trial.depth[0] <= 0.0:
                    break       # off the cup: back to the best step
                if trial.depth[0] + trial.depth[1] <= 0.0 and not resting:
                    if not lc:
                        free = True
                    break
                _trial_residual(trial.f, trial.pose[2], alpha, Lscale, body, ext, Fa_share, Rt)
                if _work(Rb, Rt, p, m, t_try - t_best) <= 0.0:
                    break
                t_best = t_try
                for a in range(m):
                    Rb[a] = Rt[a]
            if not free and t != t_best:
                t = t_best
                ok_t = try_step(t)
                evals += 1
        # accept the trial state (a roller pushed free: its pose, no load)
        copy_vector(pose, trial.pose)
        copy_matrix(state.q, trial.q)
        copy_matrix(state.active, trial.active)
        copy_matrix(state.free, trial.free)
        copy_vector(f, trial.f)
        copy_matrix(state.K, trial.K)
        copy_vector(Q, trial.Q)
        copy_vector(depth, trial.depth)
        copy_matrix(state.G, trial.G)
        copy_vector(state.d, trial.d)
        copy_vector(state.rib_contact, trial.rib_contact)
        for s in range(2):
            copy_matrix(state.frames.X[s], trial.frames.X[s])
            copy_matrix(state.frames.Nrm[s], trial.frames.Nrm[s])
        copy_vector(state.frames.Cen, trial.frames.Cen)
        copy_vector(state.frames.Ax, trial.frames.Ax)
        copy_vector(state.frames.Xrib, trial.frames.Xrib)
        if free:
            _release(f, state.K, state.q, state.active, Q)
            return 2, it + 1, evals
        ring[0] = ring_t[0]
        ok = ok_t
    merit = _roller_residual(f, pose[2], alpha, Lscale, body, ext, R)
    if lc:
        merit = max(merit, abs(Fa_share + f[3]))
    _residual_out(R, merit, Rout)
    return 0, max_iter, evals


@internal_kernel
def _residual_out(R, merit, Rout):
    """Rout = (R0 [N], R1 [N], R2 [N mm], residual max-norm [N]) of the returned state."""
    Rout[0] = R[0]
    Rout[1] = R[1]
    Rout[2] = R[2]
    Rout[3] = merit


@internal_kernel
def _release(f, K, q, active, Q):
    """State of a roller the rings do not squeeze: no load, no stiffness (the cage holds it)."""
    for a in range(NY):
        f[a] = 0.0
        for b in range(NY):
            K[a, b] = 0.0
    q.fill(0.0)
    active.fill(False)
    Q[0] = 0.0
    Q[1] = 0.0
    Q[2] = 0.0


@internal_kernel
def _onto_the_rest(ring, phi, cpsi, bearing, elasticity, state):
    """Move a roller that the rings do not squeeze onto its rest under its centrifugal force
    (solve_roller with ``problem.rest``, module docstring): along v' onto the outer raceway (at its
    nearest slice) and along u' onto what holds it along its axis, a TRB's rib or a TSRB's inner
    raceway (the wedge between both raceways; at its nearest slice), each to a penetration of
    REST_START_DEPTH. Each move opens the other gap a little (neither is square to u' and v'), so
    they alternate until both touch; the moves along u' travel at most WEDGE_MAX_TRAVEL x Lwe in
    all. Evaluates ``state`` there; returns whether the roller touches the outer raceway and, a
    TSRB's, the inner one (the state is that of the last move)."""
    n = bearing.x.shape[0]
    G = state.G
    d = state.d
    depth = state.depth
    travel = 0.0
    for _ in range(REST_CLOSING_MOVES):
        ko = 0
        ka = 2 * n                               # the rib's row of G and d
        for i in range(n):
            if d[i] > d[ko]:
                ko = i
        if not bearing.has_rib:
            ka = n
            for i in range(n, 2 * n):
                if d[i] > d[ka]:
                    ka = i
        close_outer = depth[0] <= 0.0 and G[ko, 1] > 0.0
        close_axial = d[ka] <= 0.0 and G[ka, 0] != 0.0
        if not (close_outer or close_axial):
            break
        if close_outer:
            _local_to_pose(state.pose, 0.0, (REST_START_DEPTH - depth[0]) / G[ko, 1], 0.0)
        if close_axial:
            du = (REST_START_DEPTH - d[ka]) / G[ka, 0]
            travel += abs(du)
            if travel > WEDGE_MAX_TRAVEL * bearing.Lwe:
                return False
            _local_to_pose(state.pose, du, 0.0, 0.0)
        roller_contact(ring, phi, cpsi, bearing, elasticity, state)
    return depth[0] > 0.0 and (bearing.has_rib or depth[1] > 0.0)


@kernel
def solve_bearing(Fa, Fr, Fy, tilt, ext, problem, ring0, rollers, warm):
    """Inner-ring equilibrium under Fa, Fr, Fy and an imposed tilt (Newton on the condensed stiffness).

    Symmetry (:func:`sim.solvers.symmetry.symmetry_classes`): roller j and Z - j are mirror
    images (same cos(psi), same phi) when their external loads are equal and Fy = 0, so only
    Z // 2 + 1 azimuth classes are solved and the ring's lateral displacement delta_y is 0; with
    no radial load, no tilt and equal external loads on every roller, one roller is solved for all.
    Otherwise every roller is solved and delta_y is a third ring unknown: roller j sees the ring's
    radial displacement delta_r cos(psi_j) + delta_y sin(psi_j) in its meridian plane, and the
    radial force f_r of its contacts on the ring adds f_r (cos(psi_j), sin(psi_j)) to the ring's
    x and y balance (the condensed stiffness and the roller tangents projected the same way).

    Parameters
    ----------
    Fa, Fr, Fy : float
        Axial load along +z, radial load along +x and lateral load along +y on the inner ring [N]
        (Fy: the friction loads' share, sim.api.friction_model.coupled_solution).
    tilt : float
        Imposed inner-ring tilt about the y axis [rad].
    ext : ndarray (Z, 3)
        External load per roller, [along u' towards the large end N, along v' N, about u' x v'
        N mm] (:func:`solve_roller`).
    problem : QuasiStaticProblem
    ring0 : ndarray (3,)
        Start value of (delta_a, delta_r, delta_y) [mm], the first two not both zero: its size is the
        ring's length scale (BearingModel.initial_ring: the Hertz approach); the solution is written back.
    rollers : RollerSet
        Poses, q and active are a warm start in when ``warm``; everything is written. The
        frames are those of the last contact evaluation of each roller: of the returned poses
        when converged.
    warm : bool
        Start from the given poses, q and active (continuation) instead of rigid poses.

    Returns
    -------
    SolveReport
    """
    bearing = problem.bearing
    settings = problem.settings
    Z = bearing.Z
    alpha = bearing.alpha
    n = bearing.x.shape[0]
    poses = rollers.poses
    q = rollers.q
    active = rollers.active
    frames = rollers.frames
    free = rollers.free
    tol = settings.tolerance
    max_iter = settings.max_iterations
    nbt = settings.line_search_halvings
    forcing = settings.forcing
    ring_frac = settings.ring_step_fraction
    roller_tol_final = tol * settings.roller_tolerance_ratio
    Lscale = bearing.Lwe
    # azimuth classes
    nz, mult, source = symmetry_classes(Z, Fr, Fy, tilt, ext)
    axisym = nz == 1
    lateral = nz == Z                       # delta_y free (docstring)
    nr = 3 if lateral else 2                # ring unknowns
    ring = ring0.copy()
    if not lateral:
        ring[2] = 0.0
    ring_j = np.empty(2)                    # (delta_a, radial displacement in roller j's meridian plane)
    ring_prev = np.empty(2)                 # ... in the meridian plane of the roller solved before it
    step_j = np.empty(2)                    # a ring step seen in roller j's meridian plane
    # length scale of the ring: the start estimate (an approach), or the current displacement
    ring_scale = max(abs(ring0[0]), abs(ring0[1]))
    # contact state of the roller being solved (its pose, slice loads and frames: views into rollers)
    f = np.empty(NY)
    K = np.empty((NY, NY))
    Qc = np.empty(3)
    depth = np.empty(3)
    G = np.empty((2 * n + 1, NY))
    dpen = np.empty(2 * n + 1)
    ribc = np.empty(4)
    trial = RollerContact(np.empty(3), np.empty((2, n)), np.empty((2, n), dtype=np.bool_), np.empty(NY),
                          np.empty((NY, NY)), np.empty(3), np.empty(3), np.empty((2 * n + 1, NY)), np.empty(2 * n + 1),
                          np.empty(4), ContactFrames(np.empty((2, n, 2)), np.empty((2, n, 2)), np.empty(2), np.empty(4),
                                                     np.empty(2)), np.empty((2, n)))
    work = RollerWork(trial, np.empty(2), np.empty(NQ), np.empty(NQ), np.empty(NQ), np.empty(NQ), np.empty((NQ, NQ)),
                      np.empty((NQ, NQ)), np.empty(NQ))
    Rq = work.residual
    n3 = Rq.shape[0] - 1  # the roller's unknowns, a run-time value: one signature of the small solvers
    Kq = np.empty((NQ, NQ))
    col = np.empty(NQ)
    xcol = np.empty(NQ)
    Fscale = max(Fa, Fr)
    status = np.full(nz, -1, dtype=np.int64)  # -1: no state yet
    unrested = np.zeros(nz, dtype=np.bool_)     # classes released although problem.rest
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
    step = np.zeros(3)
    t_ring = 1.0
    backtracks = 0
    n_backtracks = 0
    # first pass: the ring residual is of the order of the load and the roller loads add up to
    # about 2 F / sin(alpha) (both raceways, F along the contact normals)
    roller_tol = max(roller_tol_final, 0.5 * forcing * np.sin(alpha))
    converged = False
    it_ring = 0
    Ffail = np.zeros(3)  # ring forces (axial, x, y) of rollers without equilibrium (inexact states)
    Fres = np.zeros(3)   # ring residual with the rollers' first-order correction (Newton)
    Ftrue = np.zeros(3)  # ring residual of the rollers as they are
    Kc = np.zeros((3, 3))
    Kl = np.zeros((2, 2))  # a roller's condensed stiffness in its meridian plane (axial, radial)
    fl = np.zeros(2)     # its ring forces with its first-order correction
    projs = _ring_projections(nz, Z, lateral)  # each class's (axial, radial) -> the ring's (axial, x, y)
    kin = np.empty(3)
    kin_prev = np.empty(3)
    roller_its = 0
    roller_evals = 0
    nbad = 0
    nload = 0
    residual_axial = 0.0
    residual_radial = 0.0
    residual_lateral = 0.0
    Fa_share = 0.0
    if axisym:
        # every roller alike: one roller, with the ring's axial displacement solved with it under
        # load control (solve_roller, one pass); delta_r = 0 by symmetry
        Fa_share = Fa / Z
        ring[1] = 0.0
        roller_tol = roller_tol_final
    control = LoadControl(Fa_share, ring_scale, roller_tol_final * Fscale / Z)
    for it_ring in range(max_iter):
        Fres[0] = Fa
        Fres[1] = Fr
        Fres[2] = Fy
        Ftrue[0] = Fa
        Ftrue[1] = Fr
        Ftrue[2] = Fy
        unrested.fill(False)
        Kc.fill(0.0)
        nbad = 0
        nload = 0
        load_sum = 0.0
        fail_sum = 0.0
        Ffail.fill(0.0)
        for j in range(nz):
            proj = projs[j]
            cpsi = proj[1]
            phi = tilt * cpsi
            _meridian(ring, proj, ring_j)
            if status[j] != 1 and status[j] != 3:
                # no valid state: rigid kinematic pose, plus the deviation of the neighbour solved
                # just before (warm start of its slice loads too)
                _kinematic_pose(ring_j, phi, 1.0, bearing, kin)
                if j > 0 and status[j - 1] == 1:
                    _meridian(ring, projs[j - 1], ring_prev)
                    _kinematic_pose(ring_prev, tilt * projs[j - 1, 1], 1.0, bearing, kin_prev)
                    for a in range(3):
                        poses[j, a] = kin[a] + poses[j - 1, a] - kin_prev[a]
                    copy_matrix(q[j], q[j - 1])
                    copy_matrix(active[j], active[j - 1])
                else:
                    for a in range(3):
                        poses[j, a] = kin[a]
                    q[j].fill(0.0)
                    active[j].fill(False)
            state = RollerContact(poses[j], q[j], active[j], f, K, Qc, depth, G, dpen, ribc,
                                  ContactFrames(frames.X[j], frames.Nrm[j], frames.Cen[j], frames.Ax[j],
                                                frames.Xrib[j]), free[j])
            st, its, nev = solve_roller(ring_j, phi, 1.0, ext[j], problem, roller_tol, control, state, work)
            if axisym:
                ring[0] = ring_j[0]             # solved with the roller under load control
            roller_its += its
            roller_evals += nev
            if st == 2 and problem.rest:
                unrested[j] = True      # released where it should rest: unloaded, counted in the report
            status[j] = st
            rollers.Q[j, 0] = Qc[0]
            rollers.Q[j, 1] = Qc[1]
            rollers.Q_rib[j] = Qc[2]
            for a in range(4):
                rollers.rib_contact[j, a] = ribc[a] if st == 1 else 0.0
            X[j].fill(0.0)
            zc[j].fill(0.0)
            if st == 0:
                nbad += 1
                if depth[0] + depth[1] > 0.0:
                    # kept as an inexact state if the ring residual allows (below)
                    fail_sum += mult[j] * Rq[3]
                    Ffail[0] += mult[j] * f[3]
                    for a in range(1, 3):
                        Ffail[a] += mult[j] * f[4] * proj[a]
            if st != 1:
                continue
            nload += 1
            load_sum += mult[j] * (Qc[0] + Qc[1] + Qc[2])
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
                fl[a] = f[3 + a]
                for c in range(3):
                    fl[a] -= K[3 + a, c] * zc[j, c]
                for b in range(2):
                    s = K[3 + a, 3 + b]
                    for c in range(3):
                        s -= K[3 + a, c] * X[j, c, b]
                    Kl[a, b] = s
            # projected on the ring's (axial, x, y): T^T f and T^T K T, T = [[1, 0, 0], [0, cos, sin]]
            for A in range(3):
                ta = proj[A]
                ia = 0 if A == 0 else 1
                Ftrue[A] += mult[j] * ta * f[3 + ia]
                Fres[A] += mult[j] * ta * fl[ia]
                for B in range(3):
                    Kc[A, B] += mult[j] * ta * proj[B] * Kl[ia, 0 if B == 0 else 1]
        if axisym:
            # the roller solve balanced the ring's axial load too (load control); delta_r = 0 by
            # symmetry, the radial sum of one roller class is not a residual
            converged = nbad == 0 and nload == 1
            residual_axial = Ftrue[0]
            residual_radial = 0.0
            residual_lateral = 0.0
            it_ring = max(roller_its - 1, 0)  # reported: the roller's Newton iterations
            break
        err = max(abs(Fres[0]), abs(Fres[1]), abs(Fres[2]))
        n_inexact = 0
        if nbad > 0 and roller_tol > roller_tol_final:
            # rollers without equilibrium yet (lightly loaded, far from the solution) are kept as
            # they are while their residuals stay below forcing x the ring residual, like the
            # inexact rollers (they enter the ring residual, not its stiffness)
            err_with = max(abs(Fres[0] + Ffail[0]), abs(Fres[1] + Ffail[1]), abs(Fres[2] + Ffail[2]))
            if fail_sum <= forcing * err_with:
                for j in range(nz):
                    if status[j] == 0 and rollers.Q[j, 0] + rollers.Q[j, 1] > 0.0:
                        status[j] = 3
                        n_inexact += 1
                if n_inexact == nbad:
                    nbad = 0
                    for a in range(3):
                        Fres[a] += Ffail[a]
                        Ftrue[a] += Ffail[a]
                    err = err_with
                else:
                    for j in range(nz):
                        if status[j] == 3:
                            status[j] = 0
                    n_inexact = 0
        residual_axial = Ftrue[0]
        residual_radial = Ftrue[1]
        residual_lateral = Ftrue[2]
        if nbad == 0 and err <= tol * Fscale:
            if (roller_tol <= roller_tol_final and n_inexact == 0
                    and max(abs(Ftrue[0]), abs(Ftrue[1]), abs(Ftrue[2])) <= tol * Fscale):
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
            for a in range(nr):
                ring[a] = ring_acc[a] + t_ring * step[a]
            for j in range(nz):
                status[j] = st_acc[j]
                copy_matrix(q[j], q_acc[j])
                copy_matrix(active[j], act_acc[j])
                for a in range(3):
                    poses[j, a] = pose_acc[j, a]
                if st_acc[j] == 1:
                    _meridian(step, projs[j], step_j)
                    _local_to_pose(poses[j],
                                   z_acc[j, 0] - t_ring * (X_acc[j, 0, 0] * step_j[0] + X_acc[j, 0, 1] * step_j[1]),
                                   z_acc[j, 1] - t_ring * (X_acc[j, 1, 0] * step_j[0] + X_acc[j, 1, 1] * step_j[1]),
                                   z_acc[j, 2] - t_ring * (X_acc[j, 2, 0] * step_j[0] + X_acc[j, 2, 1] * step_j[1]))
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
            copy_vector(pose_acc[j], poses[j])
            copy_matrix(q_acc[j], q[j])
            copy_matrix(act_acc[j], active[j])
            copy_matrix(X_acc[j], X[j])
            copy_vector(z_acc[j], zc[j])
        copy_vector(ring_acc, ring)
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
        elif lateral:
            push = Kc[2, 2] <= REG * max(Kc[0, 0], Kc[1, 1]) or not _solve_small(Kc, Fres, step, 3)
        else:
            step[0] = (Kc[1, 1] * Fres[0] - Kc[0, 1] * Fres[1]) / det
            step[1] = (-Kc[1, 0] * Fres[0] + Kc[0, 0] * Fres[1]) / det
        if push:
            step[0] = max(abs(ring[0]), ring_scale)
            step[1] = 0.0
            step[2] = 0.0
            if ring[0] + step[0] > Lscale:
                break  # moved by a roller length and still nothing carries the load
        else:
            # limit the step to a fraction of the current ring displacement (contacts stiffen)
            lim = ring_frac * max(abs(ring[0]), abs(ring[1]), abs(ring[2]), ring_scale)
            sc = 1.0
            for a in range(nr):
                if abs(step[a]) > lim:
                    sc = min(sc, lim / abs(step[a]))
            for a in range(nr):
                step[a] *= sc
        for a in range(nr):
            ring[a] += step[a]
        # predictor: each roller takes its Newton correction and follows the ring along its tangent
        for j in range(nz):
            if status[j] == 1:
                _meridian(step, projs[j], step_j)
                _local_to_pose(poses[j], zc[j, 0] - (X[j, 0, 0] * step_j[0] + X[j, 0, 1] * step_j[1]),
                               zc[j, 1] - (X[j, 1, 0] * step_j[0] + X[j, 1, 1] * step_j[1]),
                               zc[j, 2] - (X[j, 2, 0] * step_j[0] + X[j, 2, 1] * step_j[1]))
    # results of the last state
    copy_vector(ring0, ring)
    # fill the rollers of the other azimuths from their classes
    for j in range(Z):
        src = source[j]
        if src != j:
            for a in range(3):
                poses[j, a] = poses[src, a]
            for s in range(2):
                rollers.Q[j, s] = rollers.Q[src, s]
                for k in range(n):
                    q[j, s, k] = q[src, s, k]
                    active[j, s, k] = active[src, s, k]
                    free[j, s, k] = free[src, s, k]
            rollers.Q_rib[j] = rollers.Q_rib[src]
            for a in range(4):
                rollers.rib_contact[j, a] = rollers.rib_contact[src, a]
            for s in range(2):
                for k in range(n):
                    for a in range(2):
                        frames.X[j, s, k, a] = frames.X[src, s, k, a]
                        frames.Nrm[j, s, k, a] = frames.Nrm[src, s, k, a]
            for a in range(2):
                frames.Cen[j, a] = frames.Cen[src, a]
                frames.Xrib[j, a] = frames.Xrib[src, a]
            for a in range(4):
                frames.Ax[j, a] = frames.Ax[src, a]
    n_unrested = 0
    for j in range(nz):
        if unrested[j]:
            n_unrested += int(mult[j])
    return SolveReport(converged, it_ring + 1, residual_axial, residual_radial, residual_lateral, nbad, nload,
                       roller_its, roller_evals, n_backtracks, nz, n_unrested)
