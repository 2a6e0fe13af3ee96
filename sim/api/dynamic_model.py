"""One load case through the time-domain solver (:mod:`sim.solvers.dynamic`): the problem from
the config, the start from the quasi-static solution, the run, and its outputs in output units.

Start: the combined quasi-static solution of the case (load distribution, traction kinematics,
the friction loads fed back once, as :func:`sim.api.simulation.solve_case`): roller poses and
inner-ring displacement; speeds and skews either of that solution
(``solver.dynamic.start = quasi_static``) or of rolling without slip and no skew (``rolling``,
eqs. 2.20, 2.22), from which the rollers and the cage must find their traction and skew balance
themselves.
"""
from collections import namedtuple

import numpy as np

from sim.api.bearing_model import case_results
from sim.api.friction_model import coupled_solution, film_outputs
from sim.errors import InputError
from sim.io import RPM_PER_RAD_S, W_PER_N_MM_PER_S
from sim.physics.kinematics import angular_speed, cage_speed_rolling, roller_speed_rolling
from sim.solvers.dynamic import (A_TIN, A_TOUT, ETA, HR, NCAGE, NRING, NS, PHI, PSI,
                                 RO_FP, RO_QI, RO_QO, RO_QRIB, RO_WR, THETA, TO_DAMP, TO_P0, TO_TIN,
                                 TO_TOUT, WPHI,
                                 XI, DynamicBody, DynamicProblem, DynamicSettings, Integration, roller_axis,
                                 state_size, window_means)

KG_TO_T = 1e-3              # mass: 1 kg = 1e-3 t (kernel units t, mm, s, N)
KG_M2_TO_T_MM2 = 1e3        # inertia: 1 kg m^2 = 1e-3 t x 1e6 mm^2

# A dynamic case ready to run: the problem (sim.solvers.dynamic), its settings, the start state
# y0, the quasi-static result of the case (FrictionModel.evaluate outputs in output units and the
# roller loads Q (Z, 2) [N], for comparison) and its loaded rollers.
DynamicCase = namedtuple("DynamicCase", ["problem", "settings", "y0", "quasi_static", "active"])


def body_and_state(model, friction, op, dyn, raw, kin):
    """:data:`DynamicBody` and start state of one case (module docstring)."""
    g = model.geometry
    a = g.arrays
    Z = g.Z
    par = friction.problem(op, raw, start=kin).case.par
    wi = float(angular_speed(op.speed_rpm))
    wc, wR, psi = kin[0], kin[1].copy(), kin[2].copy()
    if str(dyn["start"]) == "rolling":
        wc = float(angular_speed(cage_speed_rolling(op.speed_rpm, 0.0, g.Dwe, g.Dpw, g.alpha)))
        wR[:] = float(angular_speed(roller_speed_rolling(op.speed_rpm, 0.0, g.Dwe, g.Dpw, g.alpha)))
        psi[:] = 0.0
    m = float(a["mass"])
    k_pocket = 2.0 * friction.pocket_stiffness   # both roller ends
    zeta_p = float(dyn["pocket_damping_ratio"])
    Iy = float(a["inertia_transverse"])
    body = DynamicBody(
        m=m, Ix=float(a["inertia_axial"]), Iy=Iy, m_ring=KG_TO_T * float(dyn["inner_ring_mass"]),
        I_cage=KG_M2_TO_T_MM2 * float(dyn["cage_inertia"]), r_pocket=0.5 * g.Dpw, k_pocket=k_pocket,
        # damper of a ratio zeta on a mass-spring k, m: c = 2 zeta sqrt(k m) (any vibration text)
        c_pocket=2.0 * zeta_p * np.sqrt(k_pocket * m),
        half_play=0.5 * friction.pocket_clearance, pocket_transition=friction.pocket_transition,
        c_skew=2.0 * zeta_p * np.sqrt(par.skew_stiffness * Iy), beta=0.0, Fa=float(op.Fa), Fr=float(op.Fr), wi=wi,
        tilt=float(np.radians(op.tilt_deg)), skew=bool(par.skew), friction=True)
    y0 = np.zeros(state_size(Z))
    for j in range(Z):
        o = j * NS
        xi, eta, theta = raw["poses"][j]
        y0[o + XI] = xi
        y0[o + ETA] = eta
        y0[o + THETA] = theta
        y0[o + PSI] = psi[j] if body.skew else 0.0
        y0[o + PHI] = 2.0 * np.pi * j / Z
        y0[o + WPHI] = wc
        A = roller_axis(theta, y0[o + PSI], g.alpha)
        # omega = wc e_z + wR u'': H = I_x omega_a u'' + I_y (omega - omega_a u'')
        omega = np.array([0.0, 0.0, wc]) + wR[j] * A[0]
        wa = omega @ A[0]
        y0[o + HR:o + HR + 3] = body.Ix * wa * A[0] + Iy * (omega - wa * A[0])
    o_ring = Z * NS
    y0[o_ring] = raw["ring"][0]
    y0[o_ring + 1] = raw["ring"][1]
    y0[o_ring + 2] = raw["ring"][2]
    y0[o_ring + NRING + 1] = wc
    return body, y0



class NoQuasiStaticStart(Exception):
    """The quasi-static solution a dynamic run starts from did not converge (its load distribution
    or its kinematics): ``raw`` and ``fr`` as :func:`sim.api.friction_model.coupled_solution` gave
    them, from which :func:`sim.api.simulation.combined_results` tells why."""

    def __init__(self, raw, fr):
        super().__init__("the quasi-static start of the dynamic run did not converge")
        self.raw, self.fr = raw, fr


def quasi_static_start(model, friction, op):
    """The combined quasi-static solution of one case (as :func:`sim.api.simulation.solve_case`):
    (raw solve output, friction evaluation); :class:`NoQuasiStaticStart` when its load distribution
    or kinematics do not converge. A friction-load fixed point that does not settle (``coupling_converged``
    False: skewed rollers flipping between their pocket walls from pass to pass) still gives the
    start, its last pass: the start is an initial state, and the run's own steady-state detector
    decides (such a run reports no steady state, README). InputError, before any friction or time
    step, when the load solution is beyond the static limit (BearingModel.static_limit): the
    elastic contact model does not hold there, and the run would end refused by case_results after
    its whole integration."""
    raw, fr = coupled_solution(model, friction, op)
    if fr is None and raw["converged"]:         # beyond the static limit (coupled_solution)
        raise InputError(f"solver=dynamic at load.Fa = {op.Fa:g} N, load.Fr = {op.Fr:g} N, tilt "
                         f"{op.tilt_deg:g} deg: {model.static_limit(raw)[1]}")
    if fr is None or not (raw["converged"] and fr["friction_converged"]):
        raise NoQuasiStaticStart(raw, fr)
    return raw, fr


def prepare(model, friction, op, dyn):
    """:data:`DynamicCase` of one operating point (``dyn``: the solver.dynamic config node)."""
    g = model.geometry
    raw, fr = quasi_static_start(model, friction, op)
    kin = fr["kinematics"]
    body, y0 = body_and_state(model, friction, op, dyn, raw, kin)
    pb = friction.problem(op, raw, start=kin)
    case = pb.case
    # the run updates frames, line loads and rib data in place: its own copies
    frames = type(case.frames)(*(np.array(x, copy=True) for x in case.frames))
    bearing = case.bearing._replace(q=case.bearing.q.copy(), Qrib=case.bearing.Qrib.copy(),
                                    nrib=case.bearing.nrib.copy(), free=case.bearing.free.copy(),
                                    ring=case.bearing.ring.copy())
    case = case._replace(frames=frames, bearing=bearing)
    problem = DynamicProblem(model.bearing, model.elasticity, case, body)
    # contact damping: ratio zeta at the roller's normal contact frequency sqrt(k / m), k the
    # exact contact stiffness along v' of the start state; beta = 2 zeta / omega (Rayleigh)
    probe = Integration(problem, None)
    probe.f(0.0, y0)
    k_n = float(probe.work.K[1, 1])
    omega_n = np.sqrt(k_n / body.m)
    body = body._replace(beta=2.0 * float(dyn["contact_damping_ratio"]) / omega_n)
    problem = problem._replace(body=body)
    settings = integration_settings(g, op, body, raw, fr, dyn, omega_n)
    return DynamicCase(problem, settings, y0, fr | {"Q": raw["Q"]}, raw["Q"].sum(axis=1) > 0.0)


def integration_settings(g, op, body, raw, fr, dyn, omega_n):
    """:data:`DynamicSettings` of one case: tolerances and the state scales.

    Scales (absolute tolerance atol = rtol x scale, and the floor of the finite-difference
    steps): roller and ring positions by the inner ring's axial displacement (the contact
    approach, ~10 um), their rates by that times the contact frequency, angles by it over Lwe,
    orbit and cage angles by 1 rad, speeds by the cage speed, momenta by I_x times the roller
    speed, energies by the torque times the inner-ring turn of one window, angular impulses by
    the torque times the window's duration. The window is
    ``window_revolutions`` inner-ring turns rounded to a whole number of roller passes (of cage
    turns under a radial load or a tilt).
    """
    Z = g.Z
    delta = max(abs(raw["ring"][0]), abs(raw["ring"][1]))
    wc = float(fr["kinematics"][0])
    wR = float(np.abs(fr["kinematics"][1]).max())
    # window: about window_revolutions inner-ring turns, rounded to whole roller passes (the cage
    # turning by 2 pi / Z at the quasi-static cage speed). Under a radial load or a tilt, to whole
    # cage turns: each roller may rest on either wall of its pocket, so a roller's state is not its
    # neighbour's one pass on, and the steady state repeats only with the cage turn (README, "Steady
    # states that fluctuate"). With free skew (the rigid-cage solution of the reference TSRB at 1.26 /
    # 1.18 kN, 6386 rpm puts 7 of 17 on the negative wall) windows of one inner-ring turn cycled with
    # a period of about 5 windows, whole cage turns settled it (session 22); without skew the pocket
    # play along the orbit does the same since the inner ring's surface moves about its own axis
    # (session 35): a roller's rolling orbit speed then varies by about delta_r / r around the orbit,
    # and the TRB 31313 at 21.2 / 22 kN, 3390 rpm alternated by +-4.5e-4 in cage speed over 30 windows
    # of one inner-ring turn, while whole cage turns settled it in 5 (+0.04 % against quasi-static)
    passes = max(1, round(float(dyn["window_revolutions"]) * Z * wc / body.wi))
    if op.Fr != 0.0 or op.tilt_deg != 0.0:
        passes = Z * max(1, round(passes / Z))
    window = passes * 2.0 * np.pi / (Z * wc)
    scale = np.zeros(state_size(Z))
    per_roller = np.zeros(NS)
    per_roller[[XI, ETA]] = delta
    per_roller[[XI + 3, ETA + 3]] = delta * omega_n
    per_roller[PHI] = 1.0
    per_roller[WPHI] = wc
    per_roller[[THETA, PSI]] = delta / g.Lwe
    per_roller[HR:HR + 3] = body.Ix * wR
    scale[:Z * NS] = np.tile(per_roller, Z)
    o_ring = Z * NS
    scale[o_ring:o_ring + 3] = delta
    scale[o_ring + 3:o_ring + 6] = delta * omega_n
    scale[o_ring + NRING] = 1.0
    scale[o_ring + NRING + 1] = wc
    o_q = o_ring + NRING + NCAGE
    scale[o_q:] = abs(fr["torque"]) * body.wi * window
    scale[[o_q + A_TOUT, o_q + A_TIN]] = abs(fr["torque"]) * window
    rtol = float(dyn["rtol"])
    return DynamicSettings(str(dyn["method"]), rtol, rtol * scale, window, passes * 2.0 * np.pi / Z,
                           int(dyn["samples_per_window"]),
                           int(dyn["max_windows"]), float(dyn["steady_tolerance_speed"]),
                           float(dyn["steady_tolerance_torque"]), float(dyn["steady_tolerance_load"]),
                           float(dyn["steady_tolerance_skew"]), int(dyn["fluctuation_windows"]), scale,
                           float(dyn["steady_tolerance_power"]))


def run(dcase):
    """Integrate a :data:`DynamicCase`: the finished :class:`sim.solvers.dynamic.Integration`."""
    return Integration(dcase.problem, dcase.settings).run(dcase.y0)


def outputs(model, op, dcase, integ, wall_time, output_cfg):
    """(summary, series): the steady-state summary as :func:`sim.api.bearing_model.case_results`
    plus the friction outputs (torque, breakdown, power, cage speed: exact means over the last window,
    or over the block of windows that fluctuate about the steady state;
    per-roller loads, poses, skew and tilt: at the instant the rollers pass the quasi-static
    azimuths, roller j at 2 pi j / Z, so that they compare roller by roller with the quasi-static
    solution; output units), and the time series (output units; sim.io.SERIES_VARIABLES), rollers
    as numbered at the start."""
    g = model.geometry
    Z = g.Z
    body = dcase.problem.body
    o_ring = Z * NS
    o_cage = o_ring + NRING
    y = integ.y
    rol = integ.rol_t
    tot = integ.tot_t
    roller = y[:, :o_ring].reshape(len(integ.t), Z, NS)
    series = {
        "time": integ.t,
        "roller_skew": np.degrees(roller[:, :, PSI]),
        "roller_tilt": np.degrees(roller[:, :, THETA]),
        "roller_xi": roller[:, :, XI],
        "roller_eta": roller[:, :, ETA],
        "roller_speed": rol[:, :, RO_WR] * RPM_PER_RAD_S,
        "roller_orbit_speed": roller[:, :, WPHI] * RPM_PER_RAD_S,
        "Q": np.stack([rol[:, :, RO_QO], rol[:, :, RO_QI]], axis=-1),
        "Q_rib": rol[:, :, RO_QRIB],
        "pocket_force": rol[:, :, RO_FP],
        "cage_speed": y[:, o_cage + 1] * RPM_PER_RAD_S,
        "ring_displacement": y[:, o_ring:o_ring + 3],
        "torque": tot[:, TO_TOUT],
        "drive_torque": tot[:, TO_TIN],
        "torque_component": tot[:, TO_P0:TO_DAMP] / body.wi,
        "power_loss": tot[:, TO_P0:TO_DAMP].sum(axis=1) * W_PER_N_MM_PER_S,
    }
    # per-roller outputs: of the steady state at the instant the rollers pass the quasi-static
    # azimuths, roller j the one at 2 pi j / Z (Integration._align: under a radial load each roller's
    # load follows its azimuth, so a window mean per roller would mix the load zone with the rest);
    # without a steady state the end state, rollers as numbered in the time series
    if integ.steady:
        yl, rl, order = integ.y_aligned, integ.rol_aligned, integ.azimuth_order
    else:
        yl, rl, order = y[-1], rol[-1], np.arange(Z)
    rl = rl[order]
    state = yl[:o_ring].reshape(Z, NS)[order]
    q = dcase.problem.case.bearing.q[order]
    raw = dict(converged=bool(integ.steady), iterations=int(integ.windows), wall_time=wall_time,
               ring=yl[o_ring:o_ring + 3].copy(), poses=state[:, [XI, ETA, THETA]].copy(), line_load=q,
               pressure=model.hertz_pressure(q), Q=rl[:, [RO_QO, RO_QI]], Q_rib=rl[:, RO_QRIB],
               free=dcase.problem.case.bearing.free[order],
               residual=np.zeros(3),
               solver_info=dict(unrested_rollers=0))   # every roller runs on its own (no rest to fail)
    summary = case_results(model, op, raw, output_cfg)
    if not summary["converged"]:    # no steady state, or beyond the static load limit (case_results)
        summary.setdefault("status", integ.failure or f"no steady state within {integ.windows} windows "
                                                       "(solver.dynamic.max_windows)")
        return summary, series
    # scalars: the exact means over the last window, or the block of windows that fluctuate about
    # the steady state (whole roller passes; quadrature states)
    i0 = integ.average_from
    means = window_means(y[i0], y[-1], integ.t[-1] - integ.t[i0], Z)
    power = means.power
    # the drive's torque (power loss / speed at the steady state): the outer ring's differs from it by
    # the mean sum of the contacts' orbit moments (sim.solvers.dynamic, "Loads": Q_phi)
    torque = means.drive_torque
    # film outputs at the aligned state (its film: Integration._align leaves the problem there)
    srr, film_um, lam = film_outputs(dcase.problem.case, integ.rol_aligned[:, RO_QO] + integ.rol_aligned[:, RO_QI],
                                     float(yl[o_cage + 1]), integ.rol_aligned[:, RO_WR], body.wi)
    summary.update(
        srr=srr, film_thickness=film_um, lambda_ratio=lam,
        roller_tilt=np.degrees(state[:, THETA]),
        roller_skew=np.degrees(state[:, PSI]),
        torque=torque,
        # breakdown in proportion to each mechanism's power (as the quasi-static result)
        torque_component=torque * power / power.sum(),
        power_loss=float(power.sum()) * W_PER_N_MM_PER_S,
        cage_speed=means.cage_speed * RPM_PER_RAD_S,
    )
    if body.skew:   # the lateral-slip part of 'sliding', scaled as the breakdown (FrictionModel.evaluate)
        summary["skew_sliding"] = torque * means.skew_power / power.sum()
    return summary, series
