"""Roller and cage speeds from the traction balance (MODEL.md 5, thesis 5.4): the nonlinear
solves over the friction kernels of :mod:`sim.physics.friction`.

Unknowns: omega_R,j (roller moment about its axis u' = 0, per roller), with friction.skew the
skew psi_j (moment about the roller's radial axis v' of friction and cage pocket = 0, per roller,
sim.physics.friction "Roller skew") and omega_c (cage moment about z = 0: sum over rollers of
the z-moments the contacts exert).
:func:`solve_kinematics_newton` takes Newton steps on all of them at once (roller rows
eliminated); :func:`solve_kinematics` brackets the cage speed, each roller at its own balance
(slower, but it cannot leave the bracket).

Spin inertia (free rollers, :func:`free_roller_speeds`). Under a radial load a roller crosses
the azimuths at the cage speed omega_c, so its spin obeys I_x d omega / dt = M(psi, omega), M the
friction moment about its axis. Balancing M = 0 at each azimuth, as if the roller stayed there,
sets a lightly loaded roller at the load zone's edge to a speed it has no time to reach (TRB 32208
at 3 / 8 kN, 6000 rpm: 40 of 1835 rad/s; in the time domain the rollers fall from 1835 to 1531
rad/s over the unloaded arc and are spun up again when they enter the load zone). Over the Z
roller azimuths (roller j at 2 pi j / Z, arriving from j - 1 for omega_c > 0) the backward-Euler
form is M_j(omega_j) = c (omega_j - omega_j-1), c = I_x omega_c Z / (2 pi) [N mm s]; a roller that
carries nothing keeps its spin. Summed with weights omega_j over the closed orbit, sum M_j omega_j =
c/2 sum (omega_j - omega_j-1)^2 is the spin energy the tractions put in per unit time, dissipated
as slip where a roller is spun up (1/2 I_x d omega^2 per pass): the torque is the outer ring's,
and the power loss the contacts' plus that spin-up slip (sim.api.friction_model, "sliding").
Measured against the time domain (docs/figures/orbit_inertia.md): TRB 32208 3 / 8 kN, 6000 rpm
-2.64 % -> +0.02 %; TRB 31313 21.2 / 22.0 kN, 3390 rpm -2.24 % -> -0.14 %.

Pocket play (free rollers, :func:`free_roller_speeds`). A free roller's orbit speed Omega_j, set by
its own tractions, differs from the cage's by up to about 1 % under a radial load (light rollers
outside the load zone by 10 %): over one orbit that would carry it 1-2 mm along its pocket against a
play of 0.15 mm, so it meets a pocket wall, which then takes its tractions' z-moment as a rigid cage
would (with the pocket friction of that force: fast radially loaded pinion_alpha TSRBs, 135 against
2 N mm). Its place g_j in the pocket (from the pocket's centre along the orbit at the pocket radius
r_pocket, + ahead) is carried along the orbit like its spin, backward Euler over the slot's passage
dt = 2 pi / (Z |omega_c|): g_j = g_j-1 + r_pocket (Omega_j - omega_c) dt, and the z-moment of its
contacts balances the walls' spring at g_j (the time domain's pocket, friction.skew.pocket_clearance,
pocket_stiffness x 2 ends, pocket_transition; sim.physics.friction.pocket_wall_force; the time
domain's damper is left out: it acts on the rate of the place, which a steady pass does not
resolve). The cage speed balances the walls' z-moments on the cage, sum_j T_z,j = 0; where no roller
meets a wall the places must repeat after a lap, so the cage runs at the rollers' mean orbit speed.
A tight, stiff pocket (1 um, 1e7 N/mm) gives the rigid cage's torque within 0.2 %, a wide one (5 mm)
rollers free of the walls. The walls' spring does work on a roller that moves into it, T_z,j (Omega_j -
omega_c) summed over the lap (>= 0: backward Euler's dissipation on a convex spring energy), with the
cage pocket's loss, so that the outer ring's torque is the power loss over the speed. Measured against
the time domain (tests/dynamic/test_ladder.py): pinion_alpha 7.16 / 6.41 kN, 3910 rpm +8.0 % -> +0.26 %;
11.32 / 8.77 kN, 4940 rpm +5.3 % -> -0.12 %; cage speed within 3e-4.

A TRB's rollers outside the load zone rest on the cup and the rib (sim.solvers.quasi_static).
With free rollers their spin follows the same law (the rib and the cup brake them) and their orbit
their own tractions within the pocket play, like every roller's. With a rigid
cage (:func:`solve_friction` alone) their spin is not balanced but held (``KinematicsSettings.held``)
at rolling on the outer raceway (:func:`sim.physics.friction.outer_rolling_speed`): balanced on the
outer ring alone it would skid (TRB 31313 at 32.1 / 48.0 kN, 3821 rpm: its own balance lies at
170-200 rad/s against 1110 rad/s rolling), while the time-domain run slows it only from 1111 to 972
rad/s over the 0.019 s it spends outside the load zone. What the brake takes out of its spin the
inner ring puts back when it enters the load zone, so the torque of a rigid-cage case with held
rollers is the power loss over the speed (sim.api.friction_model); the slip of that spin-up is not
modelled there.
"""
from collections import namedtuple

import numpy as np

from sim._math.jit import internal_kernel, kernel
from sim._math.linalg import copy_vector, solve_dense
from sim._math.roots import root_search, root_search_step
from sim.physics.friction import (COMPONENTS, EV_MS, EV_MU, EV_P0, EV_TZ, NEV, NFL, cage_pocket_loads,
                                  friction_loads, lubrication_state, outer_rolling_speed, pocket_skew_couple,
                                  pocket_wall_force, pocket_wall_stiffness, roller_friction)

SLIDING = COMPONENTS.index("sliding")     # the loss component that takes the free rollers' spin-up slip
CAGE = COMPONENTS.index("cage")           # ... and their pocket walls' work (free_roller_speeds)

# The arrow-shaped Jacobian of the kinematic residuals (roller spin moments M (Z,), with skew the
# friction moments about the skew axis S (Z,), cage z-moments per roller T (Z,)) with respect to
# the roller speeds and skews (diagonal blocks) and the cage speed (column), by forward
# differences: kept between Newton iterations and film passes (chord steps). The skew entries
# hold the friction part only; the pocket couple's slope is added where the step is solved.
KinematicJacobian = namedtuple("KinematicJacobian", [
    "dMdw",         # (Z,) dM_j/d omega_R,j [N mm s]
    "dTdw",         # (Z,) dT_j/d omega_R,j [N mm s]
    "dMdc",         # (Z,) dM_j/d omega_c [N mm s]
    "dTdc",         # (Z,) dT_j/d omega_c [N mm s]
    "dMdp",         # (Z,) dM_j/d psi_j [N mm]   (skew only, below)
    "dSdw",         # (Z,) dS_j/d omega_R,j [N mm s]
    "dSdp",         # (Z,) dS_j/d psi_j [N mm], friction part
    "dSdc",         # (Z,) dS_j/d omega_c [N mm s]
    "dTdp",         # (Z,) dT_j/d psi_j [N mm]
    "known",        # (1,) bool: the arrays hold a Jacobian (of some earlier iterate)
])


def empty_jacobian(Z):
    """A :data:`KinematicJacobian` for Z rollers that holds no Jacobian yet."""
    return KinematicJacobian(*(np.zeros(Z) for _ in range(9)), np.zeros(1, dtype=np.bool_))


# The rollers' kinematic residuals at one point of the Newton solve (:func:`_kinematic_residuals`),
# with the friction loads there, which the quasi-static balance takes back at the solution (so that
# they need not be evaluated again).
KinematicResiduals = namedtuple("KinematicResiduals", [
    "M",            # (Z,) spin moments about the roller axes [N mm]
    "S",            # (Z,) friction moments about the skew axes, without the pocket couple [N mm] (0 without skew)
    "T",            # (Z,) weighted cage z-moments per roller [N mm]
    "loads",        # (Z, NFL) friction loads of the rollers' contacts (sim.physics.friction.friction_loads) [N, N mm]
])


# How the kinematics are solved (numba-supported named tuple, built by sim.api.friction_model):
KinematicsSettings = namedtuple("KinematicsSettings", [
    "active",       # (Z,) bool: rollers that carry load (the others keep rolling speeds and add nothing)
    "weight",       # (Z,) multiplicity of each solved roller (Z for the one roller of a symmetric case, else 1)
    "tol_M",        # N mm, absolute tolerance of each roller's moment balance about its axis
    "tol_T",        # N mm, absolute tolerance of the cage's z-moment balance
    "max_iter",     # int: bracket widenings, regula falsi or Newton steps before giving up
    "traction",     # bool: speeds from the traction balance; False: the given (rolling) speeds are kept
    "seed_factor",  # 1, tolerance factor of a solve that only sets the film of the next pass
    "final",        # bool: the speeds are a result (the last film pass solved to FINAL_TOLERANCE_FACTOR x the
                    # tolerances); False: an iterate of the friction-load coupling (sim.api.friction_model.
                    # coupled_solution), whose speeds only set the next pass's film and start: one film pass,
                    # solved to seed_factor x the tolerances
    "held",         # (Z,) bool: rollers resting on the outer raceway alone (outside the load zone,
                    # sim.solvers.quasi_static): in the rigid solve the cage drives them and their spin is
                    # held at rolling on the outer raceway (sim.physics.friction.outer_rolling_speed)
                    # instead of balanced; not used by the free solve (module docstring)
])

# First bracket of a roller speed: +-10 % of the start value (rolling kinematics (2.22) or the
# previous solution). Measured: the traction roller speeds lie within 0.1 % of rolling kinematics
# for the TRB 32208 and 2-7 % above it for the crowned TSRBs (reference, prototype tilted 0.25
# deg, pinion), so the first bracket holds the root; otherwise it is widened.
ROLLER_BRACKET = (0.9, 1.1)
# First bracket of the cage speed: +-5 % of the start value (2.20). Measured: the cage runs within
# 0.7 % of rolling kinematics in the same cases; every cage-moment evaluation solves all roller
# speeds, so a tight bracket saves widening steps without risking a miss.
CAGE_BRACKET = (0.95, 1.05)
# Relative step of the forward-difference Jacobian: near the square root of the double precision
# (1.5e-8), where truncation and rounding error of a forward difference balance (Dennis &
# Schnabel 1983, 5.4); conf/friction/default.yaml (friction.tolerance) refers to it.
FD_STEP = 1e-7
# A step from a Jacobian of an earlier iterate (or of the previous film pass) is kept when it
# lowers the scaled residual norm at least to this fraction (squared norm: 0.25, i.e. half the
# norm): such a chord step costs one evaluation of all rollers, a Newton step with a new
# Jacobian three (the cage column, the roller diagonal, the step); a step that falls short is
# dropped and the Jacobian rebuilt at the same point (Kelley 2003, Solving Nonlinear Equations
# with Newton's Method, 2.3: the chord and Shamanskii methods).
CHORD_CONTRACTION = 0.25
# The final film pass is solved to this fraction of the tolerances. The chord and Broyden steps
# (CHORD_CONTRACTION) contract the residual by a factor of a few per step and stop just under
# the tolerance, where the earlier all-Newton solve, contracting quadratically, landed orders
# below it by its last step; at the configured tolerance (relative to mu = 0.1, while the
# bearing's effective friction coefficient is ~1e-3) that difference moved the torque by up to
# 4e-5 relative. At a tenth the torque is as close to a 100x tighter solve as before (measured:
# within 1e-6 for tsrb_reference, tsrb_prototype and trb_32208, combined and pure axial).
FINAL_TOLERANCE_FACTOR = 0.1
# Backtracking halvings before a Newton step is rejected: down to 2^-30 ~ 1e-9 of the step, a
# length at which the speeds change far less than the difference step FD_STEP resolves; a
# direction that lowers the residual norm nowhere up to there is no descent direction, and the
# caller falls back to the bracketing solve.
MAX_HALVINGS = 30
# Skew of the restarts of a free roller's solve on a cage pocket wall (free_roller_speeds), in units
# of the pocket's skew clearance: just beyond it, on the wall's linear penalty branch (the wall
# solutions of the tests lie 1.0001-1.01 clearances out); numerical choice.
FREE_SKEW_WALL_START = 1.001


# A speed held at a value (a held roller's spin in the rigid solve)
# meets its residual's tolerance where it is within HELD_SPEED_TOLERANCE of that value: far below any
# speed difference that moves a loss (the residual is linear in the speed, so one Newton step meets it).
HELD_SPEED_TOLERANCE = 1e-9


@internal_kernel
def _held_residual(speed, held_at, tol):
    """The residual of a speed held at ``held_at`` [rad/s]: its relative deviation, scaled so that
    HELD_SPEED_TOLERANCE of it is the residual's tolerance ``tol`` [N mm]."""
    return tol * (speed / held_at - 1.0) / HELD_SPEED_TOLERANCE


@internal_kernel
def _spin_residual(j, wR, wc, case, settings, ev):
    """The spin residual of roller j at speed wR and cage speed wc [rad/s], ``ev`` its
    evaluation there: the friction moment about its axis [N mm]; for a held roller
    (``settings.held``) held at rolling on the outer raceway (:func:`_held_residual`)."""
    if settings.held[j]:
        return _held_residual(wR, outer_rolling_speed(j, wc, case), settings.tol_M)
    return ev[EV_MU]


@internal_kernel
def _solve_roller_speed(j, w0, psi, wc, wi, case, ev, tol_M, max_iter):
    """omega_R of roller j at skew psi with zero moment about its axis (bracketed root,
    sim._math.roots).

    Returns (omega_R [rad/s], converged); w0 when no bracket is found. M(omega_R) falls with
    omega_R: more spin, more drag. The first bracket is ROLLER_BRACKET x w0, its ends in
    ascending order (the search widens upwards from hi where M > 0 at both ends): a start at a
    negative spin (a roller of ~0.1 N at the load zone's edge, where the film's moment on it is
    flat in its spin beyond a steep step near rolling, and a loose seed pass accepted -270 rad/s:
    tsrb_reference at 7.58 / 21.2 kN, 189 rpm, tilt -0.124 deg) widened downwards, away from the
    root; at w0 = 0, +-(1 - ROLLER_BRACKET[0]) |wc| (a roller spins Dpw / Dwe times faster than
    the cage).
    """
    lo = ROLLER_BRACKET[0] * w0
    hi = ROLLER_BRACKET[1] * w0
    if hi < lo:
        lo, hi = hi, lo
    elif hi == lo:
        lo -= (1.0 - ROLLER_BRACKET[0]) * abs(wc)
        hi += (ROLLER_BRACKET[1] - 1.0) * abs(wc)
    roller_friction(j, lo, psi, wc, wi, case, ev)
    search = root_search(lo, ev[EV_MU], hi, tol_M, 0.0, max_iter)
    while not search.done:
        roller_friction(j, search.x, psi, wc, wi, case, ev)
        search = root_search_step(search, ev[EV_MU])
    if not search.bracketed:
        return w0, False
    return search.x, search.converged


@internal_kernel
def _skew_moment(ev, psi, par):
    """Moment about the skew axis of roller friction (ev[EV_MS]) and cage pocket [N mm]."""
    return ev[EV_MS] + pocket_skew_couple(psi, par)[0]


@internal_kernel
def _solve_roller_skew(j, wR, p0, wc, wi, case, ev, tol_M, max_iter):
    """Skew psi of roller j at speed wR with zero moment about its skew axis (bracketed root;
    the pocket couple makes the moment fall through zero beyond the clearance whatever the
    friction does). First bracket p0 +- the pocket clearance. Returns (psi [rad], converged); p0
    when no bracket is found.
    """
    par = case.par
    lo = p0 - par.skew_clearance
    roller_friction(j, wR, lo, wc, wi, case, ev)
    search = root_search(lo, _skew_moment(ev, lo, par), p0 + par.skew_clearance, tol_M, 0.0, max_iter)
    while not search.done:
        roller_friction(j, wR, search.x, wc, wi, case, ev)
        search = root_search_step(search, _skew_moment(ev, search.x, par))
    if not search.bracketed:
        return p0, False
    return search.x, search.converged


@internal_kernel
def _solve_roller(j, w0, p0, wc, wi, case, ev, tol_M, max_iter):
    """Speed and skew of roller j at cage speed wc with zero moments about its axis and its skew
    axis: the speed alone without skew, else alternately speed (at the skew) and skew (at the
    speed), until both moments are within tol_M (block Gauss-Seidel, at most max_iter sweeps).
    Returns (omega_R [rad/s], psi [rad], converged).
    """
    w, conv = _solve_roller_speed(j, w0, p0, wc, wi, case, ev, tol_M, max_iter)
    if not case.par.skew:
        return w, p0, conv
    psi = p0
    for _ in range(max_iter):
        psi, conv_p = _solve_roller_skew(j, w, psi, wc, wi, case, ev, tol_M, max_iter)
        roller_friction(j, w, psi, wc, wi, case, ev)
        if abs(ev[EV_MU]) <= tol_M and conv_p:
            return w, psi, True
        w, conv = _solve_roller_speed(j, w, psi, wc, wi, case, ev, tol_M, max_iter)
    return w, psi, False


@internal_kernel
def _cage_moment(wc, wi, wR, psi, case, settings, ev, totals):
    """Sum of the z-moments on all rollers at cage speed wc, each roller at its own moment balance.

    wR, psi (Z,) hold start values in and solved speeds and skews out; ``totals`` (NEV,) gets the
    weighted sums of the roller evaluation vectors. Returns (moment [N mm], all rollers converged).
    """
    ok = True
    for i in range(NEV):
        totals[i] = 0.0
    for j in range(wR.shape[0]):
        if not settings.active[j]:
            continue
        if settings.held[j]:
            wj = outer_rolling_speed(j, wc, case)
            pj, conv = psi[j], True
            if case.par.skew:
                pj, conv = _solve_roller_skew(j, wj, psi[j], wc, wi, case, ev, settings.tol_M, settings.max_iter)
        else:
            wj, pj, conv = _solve_roller(j, wR[j], psi[j], wc, wi, case, ev, settings.tol_M, settings.max_iter)
        ok = ok and conv
        wR[j] = wj
        psi[j] = pj
        roller_friction(j, wj, pj, wc, wi, case, ev)
        for i in range(NEV):
            totals[i] += settings.weight[j] * ev[i]
    return totals[EV_TZ], ok


@kernel
def solve_kinematics(wc0, wi, wR, psi, case, settings, totals):
    """Cage speed with zero z-moment on the cage and roller speeds (and skews) with zero moments.

    Parameters
    ----------
    wc0 : float
        Start value, the rolling cage speed (2.20) [rad/s].
    wi : float
        Inner-ring speed [rad/s].
    wR : ndarray (Z,)
        Roller speeds [rad/s]: start values in, solution out.
    psi : ndarray (Z,)
        Roller skews [rad]: start values in, solution out (kept as they are without skew).
    case : sim.physics.friction.FrictionCase
        Frames, bearing arrays, film state, parameters and width quadrature.
    settings : KinematicsSettings
        Rollers solved, their multiplicity, tolerances and iteration limit.
    totals : ndarray (NEV,)
        Bearing sums of the roller evaluation vectors at the solution (written).

    Returns
    -------
    (omega_c [rad/s], converged); wc0 when no bracket is found.
    """
    ev = np.empty(NEV)
    lo = CAGE_BRACKET[0] * wc0
    flo, ok = _cage_moment(lo, wi, wR, psi, case, settings, ev, totals)
    search = root_search(lo, flo, CAGE_BRACKET[1] * wc0, settings.tol_T, 0.0, settings.max_iter)
    while not search.done:
        fx, ok = _cage_moment(search.x, wi, wR, psi, case, settings, ev, totals)
        search = root_search_step(search, fx)
    if not search.bracketed:
        return wc0, False
    return search.x, search.converged and ok


@internal_kernel
def _kinematic_residuals(wc, wi, wR, psi, case, settings, ev, res, totals):
    """The :data:`KinematicResiduals` ``res`` at (wR, psi, wc) (written; zeros for the inactive
    rollers); sums the weighted roller evaluation vectors into totals."""
    M, S, T, loads = res
    for i in range(NEV):
        totals[i] = 0.0
    for j in range(wR.shape[0]):
        M[j] = 0.0
        S[j] = 0.0
        T[j] = 0.0
        for a in range(loads.shape[1]):
            loads[j, a] = 0.0
        if not settings.active[j]:
            continue
        friction_loads(ev, roller_friction(j, wR[j], psi[j], wc, wi, case, ev), loads[j])
        M[j] = _spin_residual(j, wR[j], wc, case, settings, ev)
        if case.par.skew:
            S[j] = ev[EV_MS]
        T[j] = settings.weight[j] * ev[EV_TZ]
        for i in range(NEV):
            totals[i] += settings.weight[j] * ev[i]


@internal_kernel
def _scaled_norm(T, M, S, psi, settings, par):
    """Squared norm and largest entry of the residuals scaled by their tolerances (the skew
    residuals with the pocket couple)."""
    norm = (T.sum() / settings.tol_T) ** 2
    worst = abs(T.sum()) / settings.tol_T
    for j in range(M.shape[0]):
        norm += (M[j] / settings.tol_M) ** 2
        worst = max(worst, abs(M[j]) / settings.tol_M)
        if par.skew and settings.active[j]:
            r = (S[j] + pocket_skew_couple(psi[j], par)[0]) / settings.tol_M
            norm += r * r
            worst = max(worst, abs(r))
    return norm, worst


@internal_kernel
def _require_friction_load_columns(loads):
    """ValueError unless the friction loads' array (Z, m) has m = NFL columns (the layout
    sim.physics.friction.FRICTION_LOADS): the kernels write NFL per roller, past a narrower array's end."""
    if loads.shape[1] != NFL:
        raise ValueError("the friction loads' array must have NFL columns (sim.physics.friction.FRICTION_LOADS)")


@kernel
def solve_kinematics_newton(wc, presolve, wi, wR, psi, case, settings, totals, jac, loads):
    """Newton on all roller speeds (and skews) and the cage speed together (arrow-shaped Jacobian).

    Roller j's moments depend on its own speed (and skew) and the cage speed only, so the
    Jacobian is a diagonal of 1x1 (2x2 with skew) blocks plus one row and column; it is built by
    forward differences (relative step FD_STEP; for the skew FD_STEP times the larger of |psi|
    and the pocket clearance) and eliminated in O(Z); the pocket couple's slope is exact.
    Backtracking on the scaled residual norm keeps the iteration monotone. A Jacobian already
    in ``jac`` (an earlier iterate's, or the previous film pass's) is tried first: its full
    step is kept if it cuts the squared norm to CHORD_CONTRACTION times its value, else the
    Jacobian is rebuilt at the current point. Same arguments and return value as
    :func:`solve_kinematics`, and ``jac`` (:data:`KinematicJacobian`, read and written) and
    ``loads`` (Z, NFL): the friction loads of the rollers' contacts at the returned speeds (written, what
    :func:`sim.physics.friction.cage_pocket_loads` gives there); wR, psi and wc are start values
    (rolling kinematics and no skew, or a previous solution).
    ``presolve``: for a start far away, such as rolling kinematics of a crowned roller, first
    bring the most loaded active roller to its own moment balance at the start cage speed and
    start every active roller from its speed (measured: the balanced roller speeds of a case
    differ by < 0.1 % from roller to roller while rolling kinematics are 2-7 % off for the
    crowned TSRBs; one bracketed solve instead of one per roller, the Newton iteration does the
    rest); with skew, that roller's skew at its speed (bracketed), the start of every roller's.
    """
    _require_friction_load_columns(loads)
    active, weight, tol_M = settings.active, settings.weight, settings.tol_M
    dMdw, dTdw, dMdc, dTdc, dMdp, dSdw, dSdp, dSdc, dTdp, known = jac
    par = case.par
    skew = par.skew
    Z = wR.shape[0]
    ev = np.empty(NEV)
    # residuals at the current point and at a trial (or difference) point
    res = KinematicResiduals(np.zeros(Z), np.zeros(Z), np.zeros(Z), loads)
    res2 = KinematicResiduals(np.zeros(Z), np.zeros(Z), np.zeros(Z), np.zeros(loads.shape))
    M, S, T = res.M, res.S, res.T
    M2, S2, T2, loads2 = res2
    dw = np.zeros(Z)
    dp = np.zeros(Z)
    St = np.zeros(Z)
    Dt = np.zeros(Z)
    wtrial = np.zeros(Z)
    ptrial = np.zeros(Z)
    tmp = np.zeros(NEV)
    # start: the most loaded roller at its own moment balance for the start cage speed (1-D,
    # bracketed), the others at its speed
    if presolve:
        q = case.bearing.q
        jmax = np.int64(-1)   # not the literal -1: it typed the call below Literal[int](-1), a second copy
                              # of _solve_roller_speed and roller_friction to compile (measured)
        qmax = -1.0
        for j in range(Z):
            if active[j] and q[j].sum() > qmax:
                jmax = j
                qmax = q[j].sum()
        if jmax >= 0:
            w_star = _solve_roller_speed(jmax, wR[jmax], psi[jmax], wc, wi, case, ev, tol_M, settings.max_iter)[0]
            p_star = psi[jmax]
            if skew:
                p_star = _solve_roller_skew(jmax, w_star, p_star, wc, wi, case, ev, tol_M, settings.max_iter)[0]
            for j in range(Z):
                if active[j]:
                    wR[j] = w_star
                    psi[j] = p_star
    _kinematic_residuals(wc, wi, wR, psi, case, settings, ev, res, totals)
    for _ in range(settings.max_iter):
        norm, worst = _scaled_norm(T, M, S, psi, settings, par)
        if worst <= 1.0:
            return wc, True
        chord = known[0]
        if not chord:
            # Jacobian by forward differences
            hc = FD_STEP * abs(wc)
            _kinematic_residuals(wc + hc, wi, wR, psi, case, settings, ev, res2, tmp)
            for j in range(Z):
                dMdc[j] = (M2[j] - M[j]) / hc
                dSdc[j] = (S2[j] - S[j]) / hc
                dTdc[j] = (T2[j] - T[j]) / hc
            for j in range(Z):
                if not active[j]:
                    continue
                hj = FD_STEP * abs(wR[j])
                roller_friction(j, wR[j] + hj, psi[j], wc, wi, case, ev)
                dMdw[j] = (_spin_residual(j, wR[j] + hj, wc, case, settings, ev) - M[j]) / hj
                dTdw[j] = (weight[j] * ev[EV_TZ] - T[j]) / hj
                if skew:
                    dSdw[j] = (ev[EV_MS] - S[j]) / hj
                    hp = FD_STEP * max(abs(psi[j]), par.skew_clearance)
                    roller_friction(j, wR[j], psi[j] + hp, wc, wi, case, ev)
                    dMdp[j] = (_spin_residual(j, wR[j], wc, case, settings, ev) - M[j]) / hp
                    dSdp[j] = (ev[EV_MS] - S[j]) / hp
                    dTdp[j] = (weight[j] * ev[EV_TZ] - T[j]) / hp
            known[0] = True
        # skew rows: the total moment St (friction and pocket) and its slope Dt. A slope that does
        # not restore (Dt >= 0: inside the clearance, where the friction moment may grow with the
        # skew) has no equilibrium there; Newton would send the roller the wrong way, and a step
        # across the clearance does not lower the residual norm on the way (the moment keeps its
        # size until the roller reaches the pocket). Such a roller is first brought to its own
        # skew balance at the current speeds (bracketed, to the pocket the moment pushes it to).
        if skew:
            moved = False
            for j in range(Z):
                Sj, kp = pocket_skew_couple(psi[j], par)
                St[j] = S[j] + Sj
                Dt[j] = dSdp[j] + kp
                if active[j] and Dt[j] >= 0.0 and abs(St[j]) > tol_M:
                    psi[j] = _solve_roller_skew(j, wR[j], psi[j], wc, wi, case, ev, tol_M, settings.max_iter)[0]
                    moved = True
            if moved:
                _kinematic_residuals(wc, wi, wR, psi, case, settings, ev, res, totals)
                continue
        # eliminate the roller rows: dx_j = -J_j^-1 (R_j + c_j dc), J_j the roller's block
        # [[dMdw, dMdp], [dSdw, Dt]], c_j its cage column; without skew J_j = dM_j/dw_j
        num = T.sum()
        den = dTdc.sum()
        for j in range(Z):
            if not (active[j] and dMdw[j] != 0.0):
                continue
            if skew:
                det = dMdw[j] * Dt[j] - dMdp[j] * dSdw[j]
                if det == 0.0:
                    continue
                # r_j^T J_j^-1 for the row r_j = (dTdw, dTdp)
                g1 = (dTdw[j] * Dt[j] - dTdp[j] * dSdw[j]) / det
                g2 = (dTdp[j] * dMdw[j] - dTdw[j] * dMdp[j]) / det
                num -= g1 * M[j] + g2 * St[j]
                den -= g1 * dMdc[j] + g2 * dSdc[j]
            else:
                num -= dTdw[j] * M[j] / dMdw[j]
                den -= dTdw[j] * dMdc[j] / dMdw[j]
        if den == 0.0:
            if chord:           # rebuild the Jacobian here
                known[0] = False
                continue
            return wc, False
        dc = -num / den
        for j in range(Z):
            dw[j] = 0.0
            dp[j] = 0.0
            if not (active[j] and dMdw[j] != 0.0):
                continue
            if skew:
                r1 = M[j] + dMdc[j] * dc
                r2 = St[j] + dSdc[j] * dc
                det = dMdw[j] * Dt[j] - dMdp[j] * dSdw[j]
                if det != 0.0:
                    dw[j] = -(Dt[j] * r1 - dMdp[j] * r2) / det
                    dp[j] = -(dMdw[j] * r2 - dSdw[j] * r1) / det
            else:
                dw[j] = -(M[j] + dMdc[j] * dc) / dMdw[j]
        step = 1.0
        accepted = False
        for _ in range(1 if chord else MAX_HALVINGS):
            for j in range(Z):
                wtrial[j] = wR[j] + step * dw[j]
                ptrial[j] = psi[j] + step * dp[j]
            _kinematic_residuals(wc + step * dc, wi, wtrial, ptrial, case, settings, ev, res2, tmp)
            trial = _scaled_norm(T2, M2, S2, ptrial, settings, par)[0]
            if trial < (CHORD_CONTRACTION * norm if chord else norm):
                accepted = True
                break
            step *= 0.5
        if not accepted:
            if chord:           # rebuild the Jacobian here and take a Newton step
                known[0] = False
                continue
            return wc, False
        # block Broyden update of each roller's block along the step taken (least change in
        # the norm of the relative speed changes; the skew relative to the pocket clearance):
        # the next chord step uses the secant slopes
        for j in range(Z):
            if not active[j]:
                continue
            s1 = step * dw[j]
            s2 = step * dc
            a1 = 1.0 / (wR[j] * wR[j])
            a2 = 1.0 / (wc * wc)
            den = a1 * s1 * s1 + a2 * s2 * s2
            if skew:
                s3 = step * dp[j]
                a3 = 1.0 / (par.skew_clearance * par.skew_clearance)
                den += a3 * s3 * s3
                if den > 0.0:
                    rM = (M2[j] - M[j]) - (dMdw[j] * s1 + dMdc[j] * s2 + dMdp[j] * s3)
                    rS = (S2[j] - S[j]) - (dSdw[j] * s1 + dSdc[j] * s2 + dSdp[j] * s3)
                    rT = (T2[j] - T[j]) - (dTdw[j] * s1 + dTdc[j] * s2 + dTdp[j] * s3)
                    dMdw[j] += rM * a1 * s1 / den
                    dMdc[j] += rM * a2 * s2 / den
                    dMdp[j] += rM * a3 * s3 / den
                    dSdw[j] += rS * a1 * s1 / den
                    dSdc[j] += rS * a2 * s2 / den
                    dSdp[j] += rS * a3 * s3 / den
                    dTdw[j] += rT * a1 * s1 / den
                    dTdc[j] += rT * a2 * s2 / den
                    dTdp[j] += rT * a3 * s3 / den
            elif den > 0.0:
                rM = (M2[j] - M[j]) - (dMdw[j] * s1 + dMdc[j] * s2)
                rT = (T2[j] - T[j]) - (dTdw[j] * s1 + dTdc[j] * s2)
                dMdw[j] += rM * a1 * s1 / den
                dMdc[j] += rM * a2 * s2 / den
                dTdw[j] += rT * a1 * s1 / den
                dTdc[j] += rT * a2 * s2 / den
        wc += step * dc
        for j in range(Z):
            wR[j] = wtrial[j]
            psi[j] = ptrial[j]
            M[j] = M2[j]
            S[j] = S2[j]
            T[j] = T2[j]
            for a in range(loads.shape[1]):
                loads[j, a] = loads2[j, a]
        for i in range(NEV):
            totals[i] = tmp[i]
    return wc, False

@kernel
def solve_friction(wc, wR, psi, wi, fresh, case, settings, totals, roller_loads, jac):
    """Film, roller and cage speeds, roller skews and friction loads of one solved case, in one
    kernel call (the orchestration of :meth:`sim.api.friction_model.FrictionModel.evaluate`).

    The film (:func:`sim.physics.friction.lubrication_state`) is taken at the speeds of the
    previous pass and fixed while the speeds are solved. ``fresh`` (wR, wc are rolling
    kinematics): with ``settings.traction`` two passes, the first (film at rolling kinematics)
    only sets the film and the start of the second, so it stops at ``settings.seed_factor`` times
    the tolerances and starts with the presolve of :func:`solve_kinematics_newton`; else one
    pass from the given speeds (a previous solution). The last pass is solved to
    FINAL_TOLERANCE_FACTOR times the tolerances; without ``settings.final`` the first pass is the
    only one, at ``settings.seed_factor`` times the tolerances (an iterate of the load coupling). A
    Newton solve that fails is repeated from its start by the bracketing :func:`solve_kinematics`. Without ``settings.traction`` the speeds
    stay as given (with skew, each roller's skew is solved at them) and ``totals`` sums the
    weighted roller evaluations.

    Parameters
    ----------
    wc : float
        Cage speed [rad/s], start value.
    wR : ndarray (Z,)
        Roller speeds [rad/s]: start values in, solution out.
    psi : ndarray (Z,)
        Roller skews [rad]: start values in, solution out (zeros stay zeros without ``case.par.skew``).
    wi : float
        Inner-ring speed [rad/s].
    fresh : bool
        The start is rolling kinematics (not a previous solution).
    case : sim.physics.friction.FrictionCase
        ``case.film`` is written.
    settings : KinematicsSettings
    totals : ndarray (NEV,)
        Bearing sums of the roller evaluation vectors at the solution (written).
    roller_loads : ndarray (Z, NFL)
        Friction loads of the rollers' contacts, on the rollers and the inner ring (:func:`sim.physics.friction.cage_pocket_loads`, written; by
        the Newton solve of the last pass when it converged, which evaluated them there).
    jac : KinematicJacobian
        The Newton solves' Jacobian, read and written: :func:`empty_jacobian`, or the one a
        solve of the same case left (its first steps are then chord steps).

    Returns
    -------
    (omega_c [rad/s], converged)
    """
    _require_friction_load_columns(roller_loads)
    active, weight = settings.active, settings.weight
    passes = 2 if settings.traction and fresh and settings.final else 1
    converged = True
    loads_known = False     # roller_loads hold the friction loads at the solution
    ev = np.empty(NEV)
    for film_pass in range(passes):
        lubrication_state(wR, np.full(wR.shape[0], wc), wi, active, case)
        if settings.traction:
            final = settings.final and film_pass == passes - 1
            loose = FINAL_TOLERANCE_FACTOR if final else settings.seed_factor
            pass_settings = KinematicsSettings(active, weight, loose * settings.tol_M, loose * settings.tol_T,
                                               settings.max_iter, True, settings.seed_factor, final, settings.held)
            start_c = wc
            start_R = wR.copy()
            start_p = psi.copy()
            wc, converged = solve_kinematics_newton(wc, film_pass == 0 and fresh, wi, wR, psi, case, pass_settings,
                                                    totals, jac, roller_loads)
            loads_known = converged
            if not converged:   # bracketing is slower but cannot leave the bracket
                copy_vector(wR, start_R)
                copy_vector(psi, start_p)
                wc, converged = solve_kinematics(start_c, wi, wR, psi, case, pass_settings, totals)
    if not settings.traction:
        for i in range(NEV):
            totals[i] = 0.0
        for j in range(wR.shape[0]):
            if active[j]:
                if case.par.skew:
                    tol = FINAL_TOLERANCE_FACTOR * settings.tol_M
                    psi[j], conv = _solve_roller_skew(j, wR[j], psi[j], wc, wi, case, ev, tol, settings.max_iter)
                    converged = converged and conv
                roller_friction(j, wR[j], psi[j], wc, wi, case, ev)
                for i in range(NEV):
                    totals[i] += weight[j] * ev[i]
    if not loads_known:
        cage_pocket_loads(wR, psi, wc, wi, active, case, roller_loads)
    return wc, converged


# What ties a free roller to the rest of the bearing in its residuals (_free_roller_residuals):
FreeRollerTerms = namedtuple("FreeRollerTerms", [
    "upstream",     # rad/s: the spin of the roller one slot ahead of it on the orbit
    "c_spin",       # N mm s: I_x |omega_c| Z / (2 pi), the spin inertia along the orbit (module docstring)
    "wc",           # rad/s: the cage speed
    "base",         # mm: its place in its pocket at the slot's start (from the pocket's centre, + ahead)
    "reach",        # mm s: r_pocket dt, the place it moves over the slot's passage dt per rad/s of orbit
                    # speed above the cage's
    "half_play",    # mm: half the pocket's circumferential play
    "k_pocket",     # N/mm: the pocket walls' stiffness (both roller ends)
    "transition",   # mm: depth over which it sets in
    "r_pocket",     # mm: radius of the pocket contact
])

# Scratch of one free roller's Newton solve (_free_roller):
FreeRollerWork = namedtuple("FreeRollerWork", [
    "tol",          # (m,) tolerances of the residuals [N mm]
    "ev",           # (NEV,) the roller's evaluation at the returned x (written)
    "r",            # (m,) its residuals there (written)
    "J",            # (m, m) Jacobian: a chord start in (with chord), the last one built out
])

# The free rollers' solution of one case, kept between the passes of its load coupling
# (sim.api.friction_model: the kinematics' fifth entry):
FreeRollers = namedtuple("FreeRollers", [
    "orbit",        # (Z,) orbit speeds [rad/s]: start in, solution out
    "gap",          # (Z,) each roller's place in its pocket at the end of its slot, from the pocket's centre at
                    # the pocket radius, + ahead [mm]: start in, solution out
    "wc",           # (1,) the cage speed [rad/s]: start in (the rigid cage's), solution out
    "J",            # (Z, m, m) each roller's last Jacobian (m = 2, 3 with skew)
    "known",        # (Z,) bool: J[j] holds one
    "inertia",      # N mm s^2: I_x, the roller's moment of inertia about its axis
    "half_play",    # mm: half the pocket's circumferential play (friction.skew.pocket_clearance / 2)
    "k_pocket",     # N/mm: the pocket walls' stiffness, both roller ends (2 friction.skew.pocket_stiffness)
    "transition",   # mm: depth over which it sets in (friction.skew.pocket_transition)
    "r_pocket",     # mm: radius of the pocket contact (the pitch radius, as the time domain's)
])


@internal_kernel
def _pocket_moment(orbit, terms):
    """z-moment [N mm] of the pocket walls (:func:`pocket_wall_force`, the spring alone) on a roller at
    the end of its slot, its place moved from ``terms.base`` at the orbit speed ``orbit`` [rad/s]
    (:data:`FreeRollerTerms`; module docstring, "Pocket play")."""
    place = terms.base + terms.reach * (orbit - terms.wc)
    return terms.r_pocket * pocket_wall_force(place, terms.half_play, terms.k_pocket, terms.transition)[0]


@internal_kernel
def _free_residuals_at(x, ev, terms, tol, par, r):
    """Residuals of a free roller at x = (omega_R, orbit speed[, psi]) [rad/s, rad] from its
    evaluation ``ev`` there (:func:`roller_friction`), written to r [N mm] (:func:`_free_roller_residuals`);
    returns their squared norm scaled by ``tol``."""
    r[0] = ev[EV_MU] - terms.c_spin * (x[0] - terms.upstream)
    r[1] = ev[EV_TZ] + _pocket_moment(x[1], terms)
    if x.shape[0] > 2:
        r[2] = ev[EV_MS] + pocket_skew_couple(x[2], par)[0]
    norm = 0.0
    for a in range(x.shape[0]):
        norm += (r[a] / tol[a]) ** 2
    return norm


@internal_kernel
def _free_roller_residuals(j, x, terms, wi, case, tol, ev, r):
    """Residuals of roller j free in its pocket at x = (omega_R, orbit speed[, psi]) [rad/s, rad]
    (``terms``: :data:`FreeRollerTerms`): r = (moment about its axis less the spin inertia's c_spin
    (omega_R - upstream); z-moment of its contacts and drag about the bearing axis and of the pocket
    walls at its place at the slot's end (:func:`_pocket_moment`)[; moment about the skew axis with
    the pocket's skew couple]) [N mm]; ``ev`` holds the roller's evaluation there
    (:func:`roller_friction` at its own orbit speed). Returns (the pocket friction force along v'
    [N], the residuals' squared norm scaled by ``tol``): the pocket pushes the roller with the
    tangential force its z-moment balance leaves, F_D - F_t: the walls' force and M_z / r_c (M_z the
    contacts' moments about the roller centre, along e_z: the skew couple's, or the planar model's
    unbalanced skew moment; zero for a roller on its own without them), as in the time domain,
    where the cage takes the couples' z-reactions through the pockets."""
    psi = x[2] if x.shape[0] > 2 else 0.0
    F_pocket = roller_friction(j, x[0], psi, x[1], wi, case, ev)
    return F_pocket, _free_residuals_at(x, ev, terms, tol, case.par, r)


@internal_kernel
def _free_roller(j, x, terms, wi, case, work, max_iter, chord):
    """Newton on the residuals of :func:`_free_roller_residuals` from x (written), scaled by
    ``work.tol``: a step from a Jacobian built here (forward differences) backtracks until the
    residual norm falls; a step from a Jacobian of an earlier point (``work.J`` in, with ``chord``:
    the rigid solve's, or this roller's previous solve's, updated along every accepted step by
    :func:`_broyden_update`) is kept only where it cuts the squared norm to CHORD_CONTRACTION of its
    value, else the Jacobian is rebuilt at the same point (the chord and Shamanskii methods, as
    :func:`solve_kinematics_newton`). Returns (converged, the pocket friction
    force along v' [N], ``work.J`` holds a Jacobian), with ``work.ev`` the roller's evaluation and
    ``work.r`` its residuals at the returned x."""
    tol, ev, r, J = work
    m = x.shape[0]
    rt = np.empty(m)
    xt = np.empty(m)
    R = np.empty((m, 1))
    F_pocket, norm = _free_roller_residuals(j, x, terms, wi, case, tol, ev, r)
    have = chord          # J holds a Jacobian
    fresh = False         # ... built at the present x
    for _ in range(max_iter):
        if norm <= 1.0:
            return True, F_pocket, have
        if not have:
            for b in range(m):
                h = FD_STEP * (max(abs(x[2]), case.par.skew_clearance) if b == 2 else abs(x[b]))
                copy_vector(xt, x)
                xt[b] += h
                _free_roller_residuals(j, xt, terms, wi, case, tol, ev, rt)
                for a in range(m):
                    J[a, b] = (rt[a] - r[a]) / h
            have = True
            fresh = True
        for a in range(m):
            R[a, 0] = -r[a]
        dx = solve_dense(J, R)
        if not np.all(np.isfinite(dx)):
            if not fresh:
                have = False
                continue
            F_pocket, norm = _free_roller_residuals(j, x, terms, wi, case, tol, ev, r)   # ev back at x from the differences
            return False, F_pocket, have
        step = 1.0
        accepted = False
        trial = norm
        trial_pocket = 0.0
        for _ in range(MAX_HALVINGS if fresh else 1):
            for a in range(m):
                xt[a] = x[a] + step * dx[a, 0]
            trial_pocket, trial = _free_roller_residuals(j, xt, terms, wi, case, tol, ev, rt)
            if trial < (norm if fresh else CHORD_CONTRACTION * norm):
                accepted = True
                break
            step *= 0.5
        if not accepted and fresh:
            F_pocket, norm = _free_roller_residuals(j, x, terms, wi, case, tol, ev, r)   # ev back at x from the trials
            return False, F_pocket, have
        if not accepted:
            have = False        # rebuild at x (ev is rebuilt with it)
            continue
        # Broyden update along the step taken (as solve_kinematics_newton's): the next chord step
        # uses its secant slope
        _broyden_update(J, x, xt, r, rt, case.par.skew_clearance)
        copy_vector(x, xt)
        copy_vector(r, rt)
        norm = trial
        F_pocket = trial_pocket
        fresh = False
    return norm <= 1.0, F_pocket, have


@internal_kernel
def _broyden_update(J, x, xt, r, rt, skew_clearance):
    """Broyden's (1965) rank-one update of J (m, m) with the secant of the step x -> xt and the
    residuals r -> rt, least change in the norm of the step scaled by |x| (speeds) and the pocket's
    skew clearance (skew): J += (dr - J s) (W s)^T / (s^T W s), W = diag(1 / scale^2)."""
    m = x.shape[0]
    den = 0.0
    for b in range(m):
        scale = skew_clearance if b == 2 else abs(x[b])
        den += (xt[b] - x[b]) ** 2 / (scale * scale)
    if den == 0.0:
        return
    for a in range(m):
        miss = rt[a] - r[a]
        for b in range(m):
            miss -= J[a, b] * (xt[b] - x[b])
        for b in range(m):
            scale = skew_clearance if b == 2 else abs(x[b])
            J[a, b] += miss * (xt[b] - x[b]) / (scale * scale * den)


@internal_kernel
def _solve_free_roller(j, x, start, terms, wi, case, work, max_iter, chord):
    """:func:`_free_roller` from x; with skew, where that fails, again from the start spin
    start[0] [rad/s] with the skew just beyond each pocket wall, the side of the start skew start[1]
    [rad] first: the pocket's skew couple has a kink at |psi| = clearance, and where the friction
    skew moment grows with the skew (no stable skew inside the play) the Newton step from the rigid
    solution's skew heads across a wall it cannot pass (FREE_SKEW_WALL_START). Where it still fails,
    again from the start spin and skew with its place in the middle of the play, where no wall acts
    and the residuals are smooth in the orbit speed: a start at a wall's onset can trap Newton's steps
    in the kink of the walls' spring, whose slope there is thousands of times the contacts' (prototype
    TSRB at 4.5 / 4.4 kN, 2000 rpm: a 54 N roller arriving at the wall's onset stalled 0.43 N mm from
    balance, and converged from the middle of the play to a place 6 um inside it). Where that fails too,
    again from the start spin with its place on the pocket wall its z-moment residual drives it to,
    one onset depth ``terms.transition`` deep: where the contacts' traction saturates (mixed
    friction; a TRB roller on the cup and the rib, dragged by the rib) the z-moment is flat in the
    orbit speed over the play, and only the walls' spring balances it. Returns as :func:`_free_roller`."""
    ok, F_pocket, have = _free_roller(j, x, terms, wi, case, work, max_iter, chord)
    side = -1.0 if start[1] < 0.0 else 1.0
    for _ in range(2 if x.shape[0] > 2 and not ok else 0):
        x[0] = start[0]
        x[1] = terms.wc
        x[2] = side * FREE_SKEW_WALL_START * case.par.skew_clearance
        ok, F_pocket, have = _free_roller(j, x, terms, wi, case, work, max_iter, have)
        if ok:
            break
        side = -side
    if not ok:
        x[0] = start[0]
        x[1] = terms.wc - terms.base / terms.reach      # place 0: the middle of the play
        if x.shape[0] > 2:
            x[2] = start[1]
        ok, F_pocket, have = _free_roller(j, x, terms, wi, case, work, max_iter, False)
    if not ok:
        wall = terms.half_play + terms.transition
        x[0] = start[0]
        x[1] = terms.wc + ((wall if work.r[1] > 0.0 else -wall) - terms.base) / terms.reach
        if x.shape[0] > 2:
            x[2] = start[1]
        ok, F_pocket, have = _free_roller(j, x, terms, wi, case, work, max_iter, False)
    return ok, F_pocket, have


@internal_kernel
def _free_roller_jacobian(jac, j, x, par, terms, J):
    """The free roller j's Jacobian at x = (omega_R, orbit speed[, psi]) from the rigid solve's
    (:data:`KinematicJacobian` of its last Jacobian point, per roller: T_j unweighted): the same
    residuals M_j (with the spin inertia's slope -c_spin [N mm s]), T_j with the pocket walls' slope
    at its place (``terms``, :func:`_pocket_moment`), S_j + pocket couple, the orbit speed in the
    place of the cage speed, written to J."""
    J[0, 0] = jac.dMdw[j] - terms.c_spin
    J[0, 1] = jac.dMdc[j]
    J[1, 0] = jac.dTdw[j]
    J[1, 1] = jac.dTdc[j]
    place = terms.base + terms.reach * (x[1] - terms.wc)
    J[1, 1] -= terms.r_pocket * terms.reach * pocket_wall_stiffness(place, terms.half_play, terms.k_pocket,
                                                                    terms.transition)
    if J.shape[0] > 2:
        J[0, 2] = jac.dMdp[j]
        J[1, 2] = jac.dTdp[j]
        J[2, 0] = jac.dSdw[j]
        J[2, 1] = jac.dSdc[j]
        J[2, 2] = jac.dSdp[j] + pocket_skew_couple(x[2], par)[1]


# Film of the free rollers (free_roller_speeds): taken again at a roller's speed wherever the solve
# moved that by more than this fraction from the speed its film was taken at, and the roller solved
# again. The spin inertia moves the lightly loaded rollers' spins by up to a factor 40 from the rigid
# solution's (module docstring); the film thickness goes as the entrainment speed^0.67 (Pan &
# Hamrock 1989), so a spin within 1e-3 of its film's moves the film by < 7e-4 and the torque far less
# (measured in the tests, tests/friction/test_orbit_inertia.py). The same for a roller's orbit speed.
FREE_FILM_SPIN_TOLERANCE = 1e-3
# A lap of the orbit whose pocket places, summed, move by less than this fraction of the half play
# counts as periodic (free_roller_speeds, no roller on a wall): the orbit speeds then average to the
# cage speed within 1e-3 h / (r_pocket 2 pi), ~2e-7 of it (h = 0.075, r_pocket = 50 mm); numerical choice.
POCKET_LAP_TOLERANCE = 1e-3
# Sweeps of free_roller_speeds at one cage speed with rollers on walls after which the place the first
# roller arrives with is no longer the one the lap ended with but a root search on the lap's closure
# (regula falsi with the Illinois modification, Dowell & Jarratt 1971, on G(b) = place after the lap -
# b): a lightly loaded roller near a wall can make the lap's map of that place swing by as much as it
# is moved (a slope near -1), so that plain sweeps alternate between two states (TRB 32208 at 12.98 /
# 28.91 kN, 7916 rpm: the 128 N rollers opposite the load zone on and off the wall behind them); the
# two states bracket the closure's root. Numerical choice: the sweeps that converge settle in 2-5.
LOOP_PLAIN_SWEEPS = 8
# Sweeps of free_roller_speeds also settle where they still solve rollers again but move no roller's spin or
# orbit speed by more than this fraction of itself: a roller on a pocket wall turns such changes into
# residuals beyond its tolerances (the wall's stiffness), and the sweeps never found every roller within
# them at once (TRB 31313 at 121.7 / 174.0 kN, 1320 rpm: orbit speeds moving by 1e-9 of themselves in a
# cycle of 5 sweeps, z-moment residuals 3-8 x their tolerance, 0.1 N mm; TRB 32208 at 23.8 / 56.8 kN, 7826
# rpm: one or two rollers solved again in each of 60 sweeps). Far below what the outputs resolve (the film
# follows the speeds to FREE_FILM_SPIN_TOLERANCE). Numerical choice.
FREE_SETTLE_CHANGE = 1e-8
# Cage speed steps of the free rollers' cage balance (free_roller_speeds) before a bracket is found: at
# most this fraction of the cage speed times 2^k at the k-th step (the free orbit speeds lie within about
# 1 % of the rigid cage's, README, "Free rollers and their pocket play"); numerical choice.
CAGE_PROBE_STEP = 1e-3
# A bracket of the free rollers' cage speed (free_roller_speeds) narrower than this fraction of it ends the
# cage balance, the states at its ends averaged to balance the cage: far below what moves a loss (the time
# domain's steady state resolves the cage speed to 1e-4, solver.dynamic.steady_tolerance_speed); numerical choice.
CAGE_SPEED_RESOLUTION = 1e-9
# Before a bracket of the free rollers' cage balance (free_roller_speeds), a Newton step after which the balance
# moved by less than this fraction of what the step's slope predicted is followed by probe steps
# (CAGE_PROBE_STEP): the slope from the rollers' linearisations sees the walls' stiffness, while the z-moments
# of rollers on walls in mixed friction can be flat in the cage speed (TRB 31313 at 56.8 / 97.2 kN, 620 rpm,
# 106 degC, tilt -0.05 deg: the balance stayed at 1.6055 N mm over 60 Newton steps of 2e-5 of the cage speed
# each); numerical choice.
CAGE_STALL = 0.1
# How far beyond the cage speed at which the next roller inside the play meets a wall a Newton step of the
# cage balance may go (free_roller_speeds), relative to that step: onto the wall, where the balance's slope
# changes; numerical choice.
CONTACT_OVERSHOOT = 1e-3


@internal_kernel
def _orbit_successor(j, direction, Z):
    """The azimuth slot after slot j along the orbit (direction +-1, the sign of the cage speed; -direction:
    the slot before it, where roller j arrives from)."""
    return (j + direction + Z) % Z


@internal_kernel
def _slot(free, wc, Z):
    """(c_spin = I_x |omega_c| Z / (2 pi) [N mm s], the spin inertia along the orbit; reach = r_pocket dt
    [mm s], the place a roller moves over the slot's passage dt = 2 pi / (Z |omega_c|) per rad/s of
    orbit speed above the cage's) at the cage speed wc [rad/s] (module docstring)."""
    dt = 2.0 * np.pi / (Z * abs(wc))
    return free.inertia * abs(wc) * Z / (2.0 * np.pi), free.r_pocket * dt


@internal_kernel
def _centre_in_play(gap):
    """Shifts the places ``gap`` [mm] by their common offset so that they are centred in the play (no
    roller on a wall: the offset is free, module docstring "Pocket play")."""
    centre = 0.5 * (gap.max() + gap.min())
    for j in range(gap.shape[0]):
        gap[j] -= centre


@internal_kernel
def _place_shares(free, active, reach, jac, c_spin, share, grip):
    """Each roller's linearised response to a change e = d base - reach d omega_c of its place's start
    (its base) and the cage speed, at the free rollers' present solution (:data:`FreeRollers` ``free``:
    places, Jacobians), written to ``share`` (Z,) (its place moves by share e) and ``grip`` (Z,) (its
    contacts' z-moment by grip e [N mm / mm]). A roller beyond the play (depth in the walls' spring,
    local stiffness k_loc, :func:`pocket_wall_stiffness`) holds its z-balance T_c(Omega) + r_p P(g) = 0,
    g = base + reach (Omega - omega_c): with its grip a = -dT_c/dOmega (its spin, and skew, balanced: the Schur complement of its
    Jacobian ``free.J[j]`` where known, else the rigid solve's ``jac``) and the walls' K = r_p k_loc
    reach, share a / (a + K) and grip a K / ((a + K) reach); a roller inside the play share 1, grip 0
    (one that carries nothing: inside the play share 1, on a wall 0)."""
    Z = free.gap.shape[0]
    h, k, d_s, rp = free.half_play, free.k_pocket, free.transition, free.r_pocket
    for j in range(Z):
        share[j] = 1.0
        grip[j] = 0.0
        depth = abs(free.gap[j]) - h
        if depth <= 0.0:
            continue
        if not active[j]:
            share[j] = 0.0
            continue
        K = rp * pocket_wall_stiffness(free.gap[j], h, k, d_s) * reach
        J = free.J[j]
        if free.known[j]:
            m = J.shape[0]
            # the contacts' slope along the orbit speed with the other unknowns balanced (Schur complement)
            t = J[1, 1] + K
            if m == 2:
                t -= J[1, 0] * J[0, 1] / J[0, 0]
            else:
                A = np.empty((2, 2))
                A[0, 0] = J[0, 0]
                A[0, 1] = J[0, 2]
                A[1, 0] = J[2, 0]
                A[1, 1] = J[2, 2]
                bvec = np.empty((2, 1))
                bvec[0, 0] = J[0, 1]
                bvec[1, 0] = J[2, 1]
                y = solve_dense(A, bvec)
                t -= J[1, 0] * y[0, 0] + J[1, 2] * y[1, 0]
            a = -t
        elif jac.known[0]:
            a = -(jac.dTdc[j] - jac.dTdw[j] * jac.dMdc[j] / (jac.dMdw[j] - c_spin))
        else:
            a = 0.0
        if a <= 0.0:
            share[j] = 0.0
            continue
        share[j] = a / (a + K)
        grip[j] = a * K / ((a + K) * reach)


@internal_kernel
def _cage_slope(free, active, reach, first, direction, jac, c_spin):
    """Slope of the free rollers' cage balance F = sum_j T_z,j with the cage speed [N mm s] at their
    present solution, linearised roller by roller along the orbit (:func:`_place_shares`): around the
    lap the place changes per unit cage speed are periodic, u_j = s_j (u_j-1 - reach), solved from one
    pass, u = B / (1 - A), A the product of the shares s_j; the z-moments change by grip_j (u_j-1 -
    reach)."""
    Z = free.gap.shape[0]
    share = np.empty(Z)
    grip = np.empty(Z)
    _place_shares(free, active, reach, jac, c_spin, share, grip)
    # one pass around the lap from u = 0, then the periodic solution
    u = 0.0
    prod = 1.0
    j = first
    for _ in range(Z):
        u = share[j] * (u - reach)
        prod *= share[j]
        j = _orbit_successor(j, direction, Z)
    if prod >= 1.0:
        return 0.0      # no roller on a wall: the places' offset is free
    u = u / (1.0 - prod)
    slope = 0.0
    for _ in range(Z):
        slope += grip[j] * (u - reach)
        u = share[j] * (u - reach)
        j = _orbit_successor(j, direction, Z)
    return slope


# The free rollers' state at one cage speed of their cage balance (free_roller_speeds):
BalanceState = namedtuple("BalanceState", [
    "F",            # (1,) the cage balance, the sum of the rollers' z-moments [N mm]
    "x",            # (Z, m) each roller's spin, orbit speed[, skew] [rad/s, rad]
    "ev",           # (Z, NEV) its evaluation there
    "F_pocket",     # (Z,) its pocket friction force [N]
    "gap",          # (Z,) its place in its pocket [mm]
])


@internal_kernel
def _keep_state(state, F, xs, evs, F_pocket, gap):
    """Copies the free rollers' state with the cage balance F [N mm] into ``state`` (:data:`BalanceState`)."""
    state.F[0] = F
    state.x[:] = xs
    state.ev[:] = evs
    state.F_pocket[:] = F_pocket
    state.gap[:] = gap


@internal_kernel
def _restore_state(state, xs, evs, F_pocket, gap):
    """Copies ``state`` (:data:`BalanceState`) back into the free rollers' arrays."""
    xs[:] = state.x
    evs[:] = state.ev
    F_pocket[:] = state.F_pocket
    gap[:] = state.gap


@internal_kernel
def _mean_state(a, b, xs, evs, F_pocket, gap):
    """The mean of the states a and b (:data:`BalanceState`, cage balances of opposite signs) in the
    shares that balance the cage, s a.F + (1 - s) b.F = 0, written to the rollers' arrays."""
    s = b.F[0] / (b.F[0] - a.F[0])
    xs[:] = s * a.x + (1.0 - s) * b.x
    evs[:] = s * a.ev + (1.0 - s) * b.ev
    F_pocket[:] = s * a.F_pocket + (1.0 - s) * b.F_pocket
    gap[:] = s * a.gap + (1.0 - s) * b.gap


@kernel
def free_roller_speeds(wi, wR, psi, free, case, settings, totals, loads, jac):
    """Rollers free in their cage pockets (``friction.cage_guidance = free``): from the rigid-cage
    solution (cage speed ``free.wc`` [rad/s], roller speeds wR and skews psi (Z,), :func:`solve_friction`),
    each loaded roller's own orbit speed and spin speed (and skew), its place in its pocket, and the
    cage speed (module docstring, "Spin inertia" and "Pocket play"). Roller j arrives from slot j-1
    (omega_c > 0) after the slot's passage dt = 2 pi / (Z |omega_c|); backward-Euler steps over it:

    - about its axis the friction moment M_j changes its spin: M_j(omega_j) = c_spin (omega_j -
      omega_j-1), c_spin = I_x |omega_c| Z / (2 pi) [N mm s];
    - its place in its pocket moves from the place g_j-1 it arrives with: g_j = g_j-1 + r_pocket
      (Omega_j - omega_c) dt; the z-moment of its contacts and drag about the bearing axis balances the
      pocket walls' at g_j (the spring of the time domain's pocket, :func:`pocket_wall_force`: 0 inside
      the play, stiffness ``free.k_pocket`` beyond it; sim.solvers.dynamic);
    - (with skew: zero moment about its skew axis with the pocket's couple;)
    - the cage: the walls' z-moments on it balance, sum_j T_z,j = 0; with no roller on a wall the
      orbit speeds average to the cage speed over a lap (the places are periodic; their common offset
      is then free and centred in the play).

    A roller below the kinematic tolerance (not ``settings.active``) keeps the spin it arrives with
    and orbits with the cage, its place that of the roller ahead within the play. ``settings.held``
    is not used: rollers on the outer raceway alone balance like the others (the cage pushes those
    that lag, from the wall behind them).

    Solved roller by roller along the orbit from the most loaded one (Gauss-Seidel), sweep after
    sweep, until a sweep finds every roller's residuals within the tolerances at the spin and place
    of the roller ahead (recomputed from its stored evaluation: they enter the residuals explicitly),
    or solves rollers again without moving any speed by more than FREE_SETTLE_CHANGE of itself.
    A loaded roller's moment falls steeply with its spin (dM/domega << -c_spin), so a sweep
    contracts the spin errors by the product of c_spin / (c_spin - dM/domega) over the rollers: two
    or three sweeps. The first roller arrives with the place the last lap ended with; with rollers on
    walls, after LOOP_PLAIN_SWEEPS sweeps, with the root of the lap's closure instead (the place it
    arrives with = the place the lap ends with; regula falsi once two laps bracket it), and a plain
    sweep confirms it. With no roller on a wall the cage speed is set to the rollers' mean orbit speed
    after each sweep. With rollers on walls, once the sweeps settle, the cage speed takes a Newton
    step on the cage balance, its slope from the rollers' linearisations (:func:`_cage_slope`), at
    most to where the next roller meets a wall (CONTACT_OVERSHOOT), within a bracket (regula falsi
    outside it; where it narrows below CAGE_SPEED_RESOLUTION, the mean of the states at its ends that
    balances the cage; a roller whose solve fails sends the cage speed half way back to the last
    state solved); at most settings.max_iter steps. Then the film of every roller whose spin or orbit
    speed moved by more than FREE_FILM_SPIN_TOLERANCE from its film's is taken again, at its own
    spin and orbit speed (as the time domain's, sim.solvers.dynamic), and the cage balanced again (at
    most settings.max_iter film passes). The film it starts with is the caller's, taken at the start's
    spins and orbit speeds (``free.orbit``).

    Every roller is its own class (``settings.weight`` all 1: its neighbours differ); under a pure
    axial load, where the rigid cage's balance is every roller's own and no spin changes along the
    orbit, the caller keeps the rigid solution. Writes wR, psi, ``totals`` (NEV,) (sums of the
    roller evaluations, and in the sliding and cage powers the spin-up slip and the pocket walls'
    work, module docstring), ``loads`` (Z, NFL) (friction loads: the pocket friction force; with
    skew the lateral tractions) and ``free`` (:data:`FreeRollers`: orbit speeds, places, cage
    speed, the Jacobians). Starts: wR, psi and ``free``. A roller's solve starts as a chord from its
    Jacobian ``free.J[j]`` where ``free.known[j]`` (an earlier pass of this case's load coupling,
    sim.api.friction_model), else from ``jac``, the rigid solve's :data:`KinematicJacobian` per
    roller (its cage-moment entries unweighted), where it holds one. Tolerances as the rigid
    solve's last pass (:func:`solve_friction`): FINAL_TOLERANCE_FACTOR (an iterate of the load
    coupling, not ``settings.final``: ``settings.seed_factor``) x settings.tol_M on the moments, on
    each roller's z-moment x tol_T over the number of rollers, on the cage's x tol_T. Returns
    converged (every roller, the sweeps, the cage and the film passes)."""
    _require_friction_load_columns(loads)
    Z = wR.shape[0]
    active = settings.active
    for j in range(Z):
        if settings.weight[j] != 1.0:
            raise ValueError("free_roller_speeds solves every roller on its own: settings.weight must be all 1")
    skew = case.par.skew
    m = 3 if skew else 2
    tol = np.empty(m)
    loose = FINAL_TOLERANCE_FACTOR if settings.final else settings.seed_factor
    tol[0] = loose * settings.tol_M
    tol[1] = loose * settings.tol_T / Z
    if skew:
        tol[2] = tol[0]
    tol_cage = loose * settings.tol_T
    ev = np.empty(NEV)
    r = np.empty(m)
    x = np.empty(m)
    start = np.empty(2)
    xs = np.empty((Z, m))            # each roller's solution (spin, orbit speed[, skew])
    evs = np.zeros((Z, NEV))         # its evaluation there
    F_pocket = np.zeros(Z)           # its pocket friction force there
    solved = np.zeros(Z, dtype=np.bool_)    # xs, evs hold its solution at its present film
    orbit, gap, known = free.orbit, free.gap, free.known
    h, rp = free.half_play, free.r_pocket
    wc = free.wc[0]
    w_film = wR.copy()               # the spins the rollers' film was taken at
    o_film = orbit.copy()            # ... and their orbit speeds (the start's: the caller's film)
    q = np.zeros(Z)
    for j in range(Z):
        xs[j, 0] = wR[j]
        xs[j, 1] = orbit[j]
        if skew:
            xs[j, 2] = psi[j]
        q[j] = case.bearing.q[j].sum()
    direction = 1 if wc >= 0.0 else -1
    first = -1
    for j in range(Z):
        if active[j] and (first < 0 or q[j] > q[first]):
            first = j
    # the cage balance falls with the cage speed: per film, a bracket (lo: the rollers drive the cage, hi: they
    # brake it), the previous step's point and the rollers on walls there, the states at the bracket's ends
    at_lo = BalanceState(np.zeros(1), xs.copy(), evs.copy(), F_pocket.copy(), gap.copy())
    at_hi = BalanceState(np.zeros(1), xs.copy(), evs.copy(), F_pocket.copy(), gap.copy())
    c_spin = 0.0
    converged = False
    failed = False
    for _ in range(settings.max_iter):          # film passes
        lo = -np.inf
        hi = np.inf
        F_lo = 0.0
        F_hi = 0.0
        probes = 0
        retreats = 0
        have_state = False          # at_lo or at_hi holds the state at wc_prev
        wc_prev = 0.0
        F_prev = 0.0                # the cage balance at wc_prev
        dF_pred = 0.0               # the change of it that the last Newton step's slope predicted
        balanced = False
        for _ in range(settings.max_iter):      # cage speed steps at this film
            c_spin, reach = _slot(free, wc, Z)
            settled = False
            behind = _orbit_successor(first, -direction, Z)
            arrive = gap[behind]        # the place the first roller arrives with
            plain = True                # ... the place the last lap ended with (else the root search's)
            b_lo = 0.0                  # the closure's bracket: G(b_lo) > 0 > G(b_hi)
            b_hi = 0.0
            G_lo = 0.0
            G_hi = 0.0
            side = 0                    # the end replaced last (+1 lo, -1 hi, 0 none yet)
            for sweep in range(settings.max_iter):      # sweeps along the orbit
                solves = 0
                still = True                # no solve moved a speed by more than FREE_SETTLE_CHANGE of itself
                j = first
                for _ in range(Z):
                    u = _orbit_successor(j, -direction, Z)
                    base = arrive if j == first else gap[u]
                    if not active[j]:
                        xs[j, 0] = xs[u, 0]
                        xs[j, 1] = wc
                        gap[j] = max(-h, min(h, base))
                        j = _orbit_successor(j, direction, Z)
                        continue
                    terms = FreeRollerTerms(xs[u, 0], c_spin, wc, base, reach, h, free.k_pocket, free.transition, rp)
                    if solved[j] and _free_residuals_at(xs[j], evs[j], terms, tol, case.par, r) <= 1.0:
                        gap[j] = base + reach * (xs[j, 1] - wc)
                        j = _orbit_successor(j, direction, Z)
                        continue
                    for a in range(m):
                        x[a] = xs[j, a]
                    chord = known[j]
                    if not chord and jac.known[0]:
                        _free_roller_jacobian(jac, j, x, case.par, terms, free.J[j])
                        chord = True
                    start[0] = wR[j]
                    start[1] = psi[j]
                    ok, F_pocket[j], known[j] = _solve_free_roller(j, x, start, terms, wi, case,
                                                                   FreeRollerWork(tol, ev, r, free.J[j]),
                                                                   settings.max_iter, chord)
                    if not ok:
                        failed = True
                        break
                    still = (still and solved[j] and abs(x[0] - xs[j, 0]) <= FREE_SETTLE_CHANGE * abs(xs[j, 0])
                             and abs(x[1] - xs[j, 1]) <= FREE_SETTLE_CHANGE * abs(xs[j, 1]))
                    for a in range(m):
                        xs[j, a] = x[a]
                    for i in range(NEV):
                        evs[j, i] = ev[i]
                    gap[j] = base + reach * (x[1] - wc)
                    solved[j] = True
                    solves += 1
                    j = _orbit_successor(j, direction, Z)
                if failed:
                    break
                # with no roller on a wall the places must repeat after a lap: the cage at the rollers' mean orbit
                # speed at once (it moves no residual but by c_spin), the places centred in the play
                lap = 0.0
                walls = 0
                for j in range(Z):
                    if active[j]:
                        lap += reach * (xs[j, 1] - wc)
                        if abs(gap[j]) > h:
                            walls += 1
                if walls == 0:
                    if abs(lap) > POCKET_LAP_TOLERANCE * h:
                        wc += lap / (reach * Z)
                        c_spin, reach = _slot(free, wc, Z)
                        solves += 1         # a sweep more, at that cage speed
                        still = False
                    _centre_in_play(gap)
                if plain and (solves == 0 or still):
                    settled = True
                    break
                # the lap's closure (LOOP_PLAIN_SWEEPS): with rollers on walls, after that many sweeps
                G = gap[behind] - arrive
                if walls == 0:              # the places' common offset is free: no closure to solve
                    G_lo = 0.0
                    G_hi = 0.0
                    side = 0
                elif sweep + 1 >= LOOP_PLAIN_SWEEPS and G != 0.0:
                    if G > 0.0:
                        if side == 1:
                            G_hi *= 0.5     # Illinois: the same end replaced twice
                        b_lo = arrive
                        G_lo = G
                        side = 1
                    else:
                        if side == -1:
                            G_lo *= 0.5
                        b_hi = arrive
                        G_hi = G
                        side = -1
                # (every roller within its tolerances at the proposed place: a plain sweep confirms it)
                if solves > 0 and G_lo > 0.0 and G_hi < 0.0:
                    arrive = (b_lo * G_hi - b_hi * G_lo) / (G_hi - G_lo)
                    plain = False
                else:
                    arrive = gap[behind]
                    plain = True
            if failed and have_state and retreats < MAX_HALVINGS:
                # a roller's solve failed at this cage speed, started from a state solved far from it: back to
                # the last state solved (a bracket's end) and half the step
                _restore_state(at_lo if wc_prev == lo else at_hi, xs, evs, F_pocket, gap)
                for j in range(Z):
                    solved[j] = active[j]
                wc = 0.5 * (wc + wc_prev)
                failed = False
                retreats += 1
                continue
            if failed or not settled:
                break
            # the places of the rollers inside the play (which do not enter their residuals) from the places the
            # lap ended with: the first roller's came from the lap before
            j = first
            for _ in range(Z):
                u = _orbit_successor(j, -direction, Z)
                if not active[j]:
                    gap[j] = max(-h, min(h, gap[u]))
                elif abs(gap[j]) <= h:
                    gap[j] = gap[u] + reach * (xs[j, 1] - wc)
                j = _orbit_successor(j, direction, Z)
            # the cage (without a roller on a wall the sweeps left it at the mean orbit speed)
            F = 0.0
            walls = 0
            for j in range(Z):
                if active[j]:
                    F += evs[j, EV_TZ]
                    if abs(gap[j]) > h:
                        walls += 1
            wc_new = wc
            if walls == 0:
                _centre_in_play(gap)
            elif abs(F) > tol_cage:
                # Newton with the balance's slope from the rollers' linearisations (_cage_slope), within a
                # bracket: outside it regula falsi with the Illinois modification (Dowell & Jarratt 1971); before
                # a bracket, steps of at most CAGE_PROBE_STEP x 2^k of the cage speed at the k-th step
                if F > 0.0:
                    if lo == wc_prev:
                        F_hi *= 0.5         # Illinois: the other end stayed twice
                    lo = wc
                    F_lo = F
                    _keep_state(at_lo, F, xs, evs, F_pocket, gap)
                else:
                    if hi == wc_prev:
                        F_lo *= 0.5
                    hi = wc
                    F_hi = F
                    _keep_state(at_hi, F, xs, evs, F_pocket, gap)
                if hi - lo <= CAGE_SPEED_RESOLUTION * abs(wc):
                    # the balance still changes sign within CAGE_SPEED_RESOLUTION: it jumps there (a roller's skew
                    # going over to its other pocket wall: with skew free each roller may rest on either,
                    # sim.physics.friction "Roller skew"; the time domain's steady state then repeats with the cage
                    # turn, not the roller pass) or is that steep. The steady state spends shares of the time in
                    # both states that balance the cage: their mean in those shares (a continuous balance: the
                    # last step of regula falsi)
                    _mean_state(at_lo, at_hi, xs, evs, F_pocket, gap)
                    wc = hi
                    balanced = True
                    break
                slope = _cage_slope(free, active, reach, first, direction, jac, c_spin)
                limit = CAGE_PROBE_STEP * abs(wc) * 2.0 ** probes
                if (have_state and not (np.isfinite(lo) and np.isfinite(hi))
                        and abs(F - F_prev) < CAGE_STALL * abs(dF_pred)):
                    # no bracket yet and the balance moved by far less than its slope predicted (rollers on walls
                    # whose z-moments are flat in the cage speed): probe steps, doubling, until it changes sign
                    slope = 0.0
                wc_new = wc - F / slope if slope < 0.0 else wc + limit * np.sign(F)
                # the slope holds until the next roller inside the play meets the wall the balance needs (the
                # places move by -reach per unit cage speed per slot since the last roller on a wall, the rollers
                # that carry nothing passing their place on): no Newton step far beyond it
                contact = np.inf
                chain = 0
                j = first
                for k in range(2 * Z):
                    if active[j] and abs(gap[j]) > h:
                        chain = 0
                    elif active[j]:
                        chain += 1
                        if k >= Z:
                            room = gap[j] + h if F > 0.0 else h - gap[j]
                            contact = min(contact, room / (reach * chain))
                    j = _orbit_successor(j, direction, Z)
                if abs(wc_new - wc) > contact * (1.0 + CONTACT_OVERSHOOT):
                    wc_new = wc + np.sign(F) * contact * (1.0 + CONTACT_OVERSHOOT)
                if not (lo < wc_new < hi):
                    if np.isfinite(lo) and np.isfinite(hi):
                        wc_new = (lo * F_hi - hi * F_lo) / (F_hi - F_lo)
                    else:
                        wc_new = wc + max(-limit, min(limit, wc_new - wc))
                        probes += 1
                elif slope >= 0.0:
                    probes += 1     # a probe step, doubling as CAGE_PROBE_STEP says (it only doubled where clamped)
                F_prev = F
                dF_pred = slope * (wc_new - wc)
                wc_prev = wc
                have_state = True
            if wc_new == wc:
                balanced = True
                break
            wc = wc_new
        if failed or not balanced:
            break
        # the film at the solution's spins and orbit speeds (each roller's own, as its slip: where a roller
        # rides on a pocket wall its orbit speed differs from the cage's by up to ~1 %, ten times its slip)
        stale = np.zeros(Z, dtype=np.bool_)
        for j in range(Z):
            if active[j] and (abs(xs[j, 0] - w_film[j]) > FREE_FILM_SPIN_TOLERANCE * abs(w_film[j])
                              or abs(xs[j, 1] - o_film[j]) > FREE_FILM_SPIN_TOLERANCE * abs(o_film[j])):
                stale[j] = True
                solved[j] = False
                w_film[j] = xs[j, 0]
                o_film[j] = xs[j, 1]
        if not np.any(stale):
            converged = True
            break
        lubrication_state(w_film, o_film, wi, stale, case)
    free.wc[0] = wc
    for i in range(NEV):
        totals[i] = 0.0
    for j in range(Z):
        wR[j] = xs[j, 0]
        orbit[j] = xs[j, 1]
        # the spin-up slip, sum_j M_j omega_j = c_spin / 2 sum_j (omega_j - omega_j-1)^2 over the closed
        # orbit (module docstring, "Spin inertia"), with the sliding power
        step = xs[j, 0] - xs[_orbit_successor(j, -direction, Z), 0]
        totals[EV_P0 + SLIDING] += 0.5 * c_spin * step * step
        if not active[j]:
            for a in range(loads.shape[1]):
                loads[j, a] = 0.0
            continue
        if skew:
            psi[j] = xs[j, 2]
        for i in range(NEV):
            totals[i] += evs[j, i]
        friction_loads(evs[j], F_pocket[j], loads[j])
        # the pocket walls' work on the roller's motion in its pocket, T_z,j (Omega_j - omega_c) (module
        # docstring, "Pocket play"), with the cage pocket's power
        totals[EV_P0 + CAGE] += evs[j, EV_TZ] * (xs[j, 1] - wc)
    return converged
