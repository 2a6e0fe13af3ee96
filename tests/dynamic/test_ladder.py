"""Validation ladder of the time-domain solver (issue 18 item 4; sim/solvers/dynamic.py).

Each rung can fail: a wrong sign of a Coriolis, gyroscopic or constraint term breaks the free
body's conservation laws, a wrong contact assembly the settled loads, an inconsistency between
the traction kernel's forces and its loss powers the power balance, and any of them the steady
state against the quasi-static solver.
"""
import numpy as np
import pytest

import sim
from sim.api import dynamic_model as dm
from sim.api.cases import operating_points
from sim.api.simulation import build_models, resolved
from sim.physics import friction as F
from sim.solvers import dynamic as dyn
from sim.solvers.dynamic import (E_DAMP, E_DISS, E_ELASTIC, E_IN, E_POCKET, ETA, HR, NCAGE, NRING, NS, PHI, PSI,
                                 RO_FP, RO_QI, RO_QO, RO_QRIB, THETA, TO_P0, TO_TOUT, VETA, VXI, WPHI, XI, Integration,
                                 kinetic_energy, roller_axis)
from sim.solvers.symmetry import mirror_mean

TRB = ["bearing=trb_32208", "load.Fa=4500", "load.Fr=0", "load.speed=2000"]
CAGE = F.COMPONENTS.index("cage")
# the pinion case of thesis 7.4 (Fig. 7.28) with the thesis's TSRB (Table 7.4): 35 kN axial, 1100 rpm, pinion oil 50 degC
PINION_TSRB = ["bearing=tsrb_pinion", "lubricant=pinion_oil", "load.Fa=35000", "load.Fr=0", "load.speed=1100",
               "load.oil_temperature=50"]


def dynamic_case(overrides):
    cfg = sim.load_config(["solver=dynamic"] + overrides)
    plain = resolved(cfg)
    model, friction = build_models(cfg, plain)
    op = operating_points(plain["load"])[0]
    return model, friction, op, plain, dm.prepare(model, friction, op, plain["solver"]["dynamic"])


@pytest.fixture(scope="module")
def trb():
    return dynamic_case(TRB + ["solver.dynamic.start=quasi_static"])


def angular_momentum(y, problem):
    """Inertial angular momentum of the rollers about the bearing centre [N mm s]: m c x c' + H."""
    b, body = problem.bearing, problem.body
    sa, ca = np.sin(b.alpha), np.cos(b.alpha)
    L = np.zeros(3)
    for j in range(b.Z):
        o = j * NS
        phi = y[o + PHI]
        er = np.array([np.cos(phi), np.sin(phi), 0.0])
        et = np.array([-np.sin(phi), np.cos(phi), 0.0])
        ez = np.array([0.0, 0.0, 1.0])
        r = 0.5 * b.Dpw + y[o + XI] * sa + y[o + ETA] * ca
        z = -y[o + XI] * ca + y[o + ETA] * sa
        rdot = y[o + VXI] * sa + y[o + VETA] * ca
        zdot = -y[o + VXI] * ca + y[o + VETA] * sa
        c = r * er + z * ez
        v = rdot * er + r * y[o + WPHI] * et + zdot * ez
        H = y[o + HR:o + HR + 3]
        L += body.m * np.cross(c, v) + H[0] * er + H[1] * et + H[2] * ez
    return L


def rollers_clear_of_the_rings(dc, **body):
    """The case's problem without friction, loads or pocket couple (skew free), with ``body``'s
    changes, and its start state with every roller 1 mm inwards and the inner ring 10 mm away
    along -z, so that no roller touches a ring: (problem, y0)."""
    problem = dc.problem
    par = problem.case.par._replace(skew_clearance=10.0)          # no pocket couple
    changed = problem.body._replace(**{"friction": False, "skew": True, "Fa": 0.0, "Fr": 0.0, **body})
    problem = problem._replace(case=problem.case._replace(par=par), body=changed)
    Z = problem.bearing.Z
    y0 = dc.y0.copy()
    y0[ETA:Z * NS:NS] -= 1.0
    y0[Z * NS] = -10.0
    return problem, y0


def test_free_rigid_bodies_conserve_energy_and_angular_momentum(trb):
    """Rollers clear of both rings (inner ring pulled away, rollers moved inwards), no friction,
    no pocket, skew free: each roller flies and tumbles freely; with a transverse spin component
    it precesses and nutates (tilt and skew both move). Kinetic energy and the inertial angular
    momentum must stay constant to the integrator tolerance: rtol 1e-9 gives a local error of
    1e-9, over ~1e3 steps a global drift below 1e-6, so 1e-6 relative (a wrong gyroscopic or
    Coriolis term gives order-1 errors)."""
    model, friction, op, plain, dc = trb
    problem, y0 = rollers_clear_of_the_rings(dc, half_play=1e6)
    body = problem.body
    Z = problem.bearing.Z
    rng = np.random.default_rng(18)
    for j in range(Z):
        o = j * NS
        y0[o + WPHI] = 2.0                                  # slow orbit: stays clear over the run
        y0[o + VXI] = 0.5 * rng.standard_normal()
        A = roller_axis(y0[o + THETA], 0.0, problem.bearing.alpha)
        omega = 300.0 * A[0] + 1.0 * rng.standard_normal(3)   # spin plus a tumbling component [rad/s]
        wa = omega @ A[0]
        y0[o + HR:o + HR + 3] = body.Ix * wa * A[0] + body.Iy * (omega - wa * A[0])
    scale = np.abs(y0) + 1e-3
    settings = dc.settings._replace(rtol=1e-9, atol=1e-12 * scale, window=0.01, samples=20, max_windows=1)
    integ = Integration(problem, settings).run(y0)
    assert np.all(integ.rol_t[:, :, [RO_QO, RO_QI]] == 0.0), "a roller touched a ring: not a free body"
    tilt = integ.y[:, THETA::NS][:, :Z]
    skew = integ.y[:, PSI::NS][:, :Z]
    assert np.ptp(tilt) > 1e-3 and np.ptp(skew) > 1e-3, "no tumbling: the test would not see the coupling"
    E = np.array([kinetic_energy(y, problem) for y in integ.y])
    L = np.array([angular_momentum(y, problem) for y in integ.y])
    assert np.abs(E / E[0] - 1.0).max() < 1e-6
    assert np.abs(L - L[0]).max() / np.linalg.norm(L[0]) < 1e-6


def test_rollers_striking_their_pockets_off_the_pitch_radius_conserve_energy_and_angular_momentum(trb):
    """The free rollers of the test above, 1 mm inside the pitch radius (their centres at r =
    r_pocket - 0.97 mm on average), now in their pockets: undamped walls (c_pocket = 0), the cage free, each
    roller's orbit speed off the cage's by up to +-4 rad/s, so that they strike their pocket walls
    and exchange momentum with the cage. The pocket's force acts at the pocket radius, where its
    gap is measured (sim.solvers.dynamic, "Loads"): the kinetic energy plus the walls' spring energy
    (the pocket's work state) and the angular momentum about z of rollers and cage are invariants,
    kept to the integrator's tolerance (1e-6 of the energy and momentum exchanged, as above).
    Applied at the roller's centre with the cage taking it at the pocket radius (until session 37),
    the pair's moments differed by the force times r - r_pocket: drifts of 4.9 % (energy) and 3.3 %
    (angular momentum) of what was exchanged here, 4.7 % of the drive's power on tsrb_pinion_long
    at 5 / 4 kN, 6340 rpm, whose rollers slide 1.6-11 mm along their axes (no steady state, the
    imbalance reported as kinetic energy)."""
    model, friction, op, plain, dc = trb
    problem, y0 = rollers_clear_of_the_rings(dc, c_pocket=0.0)
    body = problem.body
    Z = problem.bearing.Z
    o_cage = Z * NS + NRING
    o_en = o_cage + NCAGE
    rng = np.random.default_rng(37)
    y0[o_cage + 1] = 2.0                                    # cage speed [rad/s]
    for j in range(Z):
        o = j * NS
        y0[o + WPHI] = 2.0 + 2.0 * rng.standard_normal()
        A = roller_axis(y0[o + THETA], 0.0, problem.bearing.alpha)
        y0[o + HR:o + HR + 3] = body.Ix * 300.0 * A[0]
    scale = np.abs(y0) + 1e-3
    settings = dc.settings._replace(rtol=1e-9, atol=1e-12 * scale, window=0.02, samples=40, max_windows=1)
    integ = Integration(problem, settings).run(y0)
    assert np.all(integ.rol_t[:, :, [RO_QO, RO_QI]] == 0.0), "a roller touched a ring"
    struck = (np.abs(integ.rol_t[:, :, RO_FP]) > 0.0).any(axis=0).sum()
    T = np.array([kinetic_energy(y, problem) for y in integ.y])
    U = integ.y[:, o_en + E_POCKET]                          # work on the walls: their spring energy
    cage = body.I_cage * integ.y[:, o_cage + 1]
    Lz = np.array([angular_momentum(y, problem)[2] for y in integ.y]) + cage
    drift_E = np.abs(T - T[0] + U).max() / np.ptp(U)
    drift_L = np.ptp(Lz) / np.ptp(cage)
    print(f"{struck} of {Z} rollers struck their pockets; energy exchanged {np.ptp(U):.4g} N mm, drift {drift_E:.2e}; angular momentum exchanged with "
          f"the cage {np.ptp(cage):.4g} N mm s, drift {drift_L:.2e}")
    assert struck >= Z // 2, "too few pocket impacts for the test to see their work"
    assert drift_E < 1e-6
    assert drift_L < 1e-6


def test_loaded_contacts_conserve_angular_momentum_and_energy_with_the_ring_across_the_meridian_planes():
    """No friction, no contact damping, no pocket play limit: TRB 32208 from its quasi-static state
    at 4.5 / 8 kN with the radial load removed and the ring moved across the load by half its radial
    displacement, so it swings on the contacts in x and y while the loaded rollers orbit. The
    contact energy depends on each roller's orbit angle through delta_r = delta_x cos(phi) +
    delta_y sin(phi); with its generalized force f_r e_perp on the orbit (sim.solvers.dynamic,
    "Loads") the angular momentum about the bearing axis of rollers, ring translation (m (x v_y -
    y v_x)) and cage is a linear invariant of the equations, which Runge-Kutta methods (Radau IIA)
    keep to round-off (measured 3.6e-14 N mm s, 4e-10 of the ring's term); without it (until
    session 34) the ring's radial contact forces at its displaced centre had a moment about z that
    nothing balanced: 1.7e-4 N mm s, 1.9 x the ring's term, over the 0.2 ms. Energy (kinetic plus
    elastic plus the pocket constraint's work less the axial load's) within 1e-6 of the energy
    exchanged at rtol 1e-8 (the local error over the run's steps; measured 2.5e-10)."""
    overrides = ["bearing=trb_32208", "load.Fa=4500", "load.Fr=8000", "load.speed=2000",
                 "solver.dynamic.start=quasi_static"]
    model, friction, op, plain, dc = dynamic_case(overrides)
    problem = dc.problem
    body = problem.body._replace(friction=False, beta=0.0, half_play=1e6, Fr=0.0)
    problem = problem._replace(body=body)
    Z = problem.bearing.Z
    o = Z * NS
    y0 = dc.y0.copy()
    y0[o + 2] = 0.5 * abs(y0[o + 1])                # across the meridian planes of the load zone
    scale = np.abs(y0) + 1e-3
    settings = dc.settings._replace(rtol=1e-8, atol=1e-11 * scale, window=2e-4, samples=40, max_windows=1)
    integ = Integration(problem, settings).run(y0)
    o_en = o + NRING + NCAGE
    T = np.array([kinetic_energy(y, problem) for y in integ.y])
    U = integ.y[:, o_en + E_ELASTIC]                # elastic energy change [N mm]
    P = integ.y[:, o_en + E_POCKET]                 # work on the pocket (the psi = 0 constraint's couple)
    W = integ.y[:, o_en + E_IN]                     # the axial load's work [N mm]
    exchanged = max(np.ptp(T), np.ptp(U))
    drift = np.abs((T - T[0]) + U + P - W).max() / exchanged
    ring = body.m_ring * (integ.y[:, o + 1] * integ.y[:, o + 5] - integ.y[:, o + 2] * integ.y[:, o + 4])
    cage = body.I_cage * integ.y[:, o + NRING + 1]
    Lz = np.array([angular_momentum(y, problem)[2] for y in integ.y]) + ring + cage
    print(f"energy exchanged {exchanged:.4g} N mm, drift {drift:.2e}; angular momentum about z: change "
          f"{np.ptp(Lz):.3e} against the ring's term {np.abs(ring).max():.3e} N mm s")
    assert np.abs(integ.y[:, o + 2]).max() > 0.2 * abs(y0[o + 1]), "the ring must move across the meridian planes"
    assert integ.rol_t[:, :, RO_QI].min() > 0.0, "every roller must stay loaded"
    assert drift < 1e-6
    assert np.ptp(Lz) < 1e-6 * np.abs(ring).max()


def test_loaded_rollers_settle_to_the_quasi_static_loads(trb):
    """No friction, the inner ring held at its quasi-static position (a ring mass of 1e9 t):
    every roller, started 20 % of the ring's contact approach off its equilibrium, must settle
    through its damped contacts to the quasi-static loads of the same case (without friction
    loads) within 1 % (issue 18). The remaining model differences are the centrifugal force at
    the actual radius and the exact gyroscopic moment (1e-4 of the loads). Each roller is
    independent with the ring held, so this is the one-roller rung Z times over.
    (With the ring free, its axial mode on the contacts, ~3.5 kHz for 1 kg, is damped only
    0.8 % by the stiffness-proportional contact damping and rings for ~10 ms.)"""
    model, friction, op, plain, dc = trb
    problem = dc.problem
    body = problem.body._replace(friction=False, m_ring=1e9)
    problem = problem._replace(body=body)
    ref = model.solve(op)
    Z = problem.bearing.Z
    y0 = dc.y0.copy()
    delta = abs(ref["ring"][0])
    y0[Z * NS:Z * NS + 3] = ref["ring"]
    for j in range(Z):
        y0[j * NS + ETA] += 0.2 * delta
    settings = dc.settings._replace(window=2e-3, samples=20, max_windows=1)
    integ = Integration(problem, settings).run(y0)
    Q = integ.rol_t[-1][:, [RO_QO, RO_QI]]
    Q_start = integ.rol_t[0][:, [RO_QO, RO_QI]]
    assert np.abs(Q_start / ref["Q"] - 1.0).max() > 0.1, "the start must be off the equilibrium"
    err = np.abs(Q / ref["Q"] - 1.0).max()
    print(f"settled roller loads against quasi-static: max relative error {err:.2e}")
    assert err < 0.01


def energy_residual(integ, problem):
    """Relative power balance over a run: (W_in - (W_diss + W_damp + W_elastic + W_pocket + dT)) / W_in."""
    o_en = problem.bearing.Z * NS + NRING + NCAGE
    E0, E1 = integ.y[0], integ.y[-1]
    dT = kinetic_energy(E1, problem) - kinetic_energy(E0, problem)
    W = E1[o_en:] - E0[o_en:]
    out = W[E_DISS:E_DISS + F.NC].sum() + W[E_DAMP] + W[E_ELASTIC] + W[E_POCKET] + dT
    return (W[E_IN] - out) / W[E_IN], W, dT


# a kick of every roller for the combined case's balance: centre velocity along the nominal axis u
# [mm/s] (axial sliding, resisted by the lateral tractions) and a tilt rate [rad/s]
KICK_AXIAL_SPEED = 200.0
KICK_TILT_RATE = 20.0


@pytest.mark.parametrize("overrides, kick", [
    (TRB, False),
    (["bearing=trb_32208", "load.Fa=4500", "load.Fr=2000", "load.speed=2000", "friction.skew.enabled=true"], True),
], ids=["trb_32208", "trb_32208_combined_skew_kicked"])
def test_power_balance_over_a_run(overrides, kick):
    """From rolling kinematics (the rollers and the cage must find their traction balance: a
    transient with kinetic-energy change), the drive and load work must equal the friction
    dissipation (the kernels' loss powers), damping, elastic and pocket energy and the change of
    kinetic energy within 0.5 % (issue 18). The kernels' slip holds the rollers' skew and tilt
    rates and centre velocities (sim.physics.friction "Rates") with their virtual-power forces and
    moments, so the balance closes to the integrator's tolerance (measured 8e-11 axial). The
    combined, skewed case starts every roller sliding along its axis at 200 mm/s and tilting at
    20 rad/s, which the lateral tractions and the contacts' damping take out within the run (its
    kinetic energy 0.5 % of the work): it must close within 1e-5, ten times the measured 1.0e-6
    (the integrator's tolerance); with the tilt rate and the centre velocity left out of the slip
    (as before issue 18's "full 2-D slip") it missed by 4.9e-5, the lateral tractions' power on
    the rates."""
    model, friction, op, plain, dc = dynamic_case(overrides + ["solver.dynamic.start=rolling"])
    if kick:
        y0 = dc.y0.copy()
        b, body = dc.problem.bearing, dc.problem.body
        for j in range(b.Z):
            o = j * NS
            y0[o + VXI] += KICK_AXIAL_SPEED
            A = roller_axis(y0[o + THETA], y0[o + PSI], b.alpha)
            y0[o + HR:o + HR + 3] += body.Iy * KICK_TILT_RATE * A[2]
        dc = dc._replace(y0=y0)
    settings = dc.settings._replace(window=dc.settings.window * 0.2, samples=20, max_windows=1)
    integ = dm.run(dc._replace(settings=settings))
    rel, W, dT = energy_residual(integ, dc.problem)
    print(f"power balance: W_in {W[E_IN]:.4g} N mm, dT {dT:.4g}, diss {W[E_DISS:E_DISS + F.NC].sum():.4g}, "
          f"damp {W[E_DAMP]:.3g}, "
          f"elastic {W[E_ELASTIC]:.3g}, pocket {W[E_POCKET]:.3g}; relative residual {rel:.2e}")
    assert abs(dT) > 1e-3 * abs(W[E_IN]), "no transient: the balance would not test the kinetic energy"
    assert abs(rel) < 0.005
    if kick:
        assert abs(rel) < 1e-5


def steady_run(overrides):
    """A case from rolling kinematics to the steady state the detector finds: (summary in output
    units, the quasi-static result of the case, the Integration)."""
    model, friction, op, plain, dc = dynamic_case(overrides + ["solver.dynamic.start=rolling"])
    integ = dm.run(dc)
    summary, _ = dm.outputs(model, op, dc, integ, 0.0, plain["output"])
    assert integ.steady, f"no steady state in {integ.windows} windows: changes {integ.change}"
    return summary, dc.quasi_static, integ


@pytest.mark.parametrize("overrides", [
    TRB,
    ["bearing=tsrb_reference", "load.Fa=4500", "load.Fr=0", "load.speed=2000"],
], ids=["trb_32208", "tsrb_reference"])
def test_steady_state_matches_the_quasi_static_solver(overrides):
    """From rolling kinematics to the steady state the detector finds: roller loads within 1 %,
    torque within 3 %, cage speed within 0.5 % of the quasi-static solver (issue 18). The models
    differ by the pocket's skew constraint, whose couple the cage takes (not in the
    quasi-static cage balance), the exact gyroscopic and centrifugal loads, and the film
    refreshed per window."""
    summary, qs, integ = steady_run(overrides)
    err_Q = np.abs(summary["Q"] / qs["Q"] - 1.0).max()
    err_T = abs(summary["torque"] / qs["torque"] - 1.0)
    err_c = abs(summary["cage_speed"] / qs["cage_speed"] - 1.0)
    print(f"{overrides[0]}: loads {err_Q:.2e}, torque {err_T:.2e} ({summary['torque']:.2f} vs {qs['torque']:.2f} "
          f"N mm), cage speed {err_c:.2e} ({summary['cage_speed']:.3f} vs {qs['cage_speed']:.3f} rpm), "
          f"{integ.windows} windows")
    assert err_Q < 0.01
    assert err_T < 0.03
    assert err_c < 0.005


@pytest.mark.parametrize("overrides", [
    ["bearing=trb_31313", "load.Fa=20000", "load.Fr=10000", "load.speed=1500", "load.oil_temperature=60"],
    ["bearing=tsrb_reference", "load.Fa=6000", "load.Fr=3000", "load.speed=1000", "load.oil_temperature=45"],
    ["bearing=tsrb_reference", "load.Fa=4000", "load.Fr=4000", "load.speed=2000"],
], ids=["trb_31313", "tsrb_reference", "tsrb_reference_fig_7_6"])
def test_steady_state_under_a_radial_load_matches_the_quasi_static_solver(overrides):
    """Under a radial load each roller's load follows its azimuth, so the steady state is periodic
    with the roller pass: the detector compares windows of whole roller passes and the rollers'
    means as a set, and the summary gives each roller at the azimuth 2 pi j / Z of the quasi-static
    solution (sim.api.dynamic_model.outputs). Until session 18 the windows were one inner-ring turn
    and the per-roller means were compared roller by roller: they changed by ~0.5 from window to
    window and no run under a radial load found a steady state. Targets of issue 18: roller loads
    within 1 % (here of the largest: the load zone ends at small loads), cage speed within 0.5 %,
    torque within 3 %. The quasi-static default has the rollers free in their pockets
    (friction.cage_guidance = free: no tangential pocket force, sim.solvers.kinematics.free_roller_speeds),
    as the time domain finds them: its torque must match the dynamic one within 1 % (measured 0.19 %
    and 0.007 %; its pocket friction 4.11 and 1.57 N mm against the rigid cage's 21.71 and 3.25). A rigid cage (friction.cage_guidance = rigid) holds every roller at the cage speed
    at its azimuth and so carries each roller's net tangential traction, which under a radial load
    changes sign around the bearing; in the time domain a roller moves within its pocket play and
    touches its pockets far more lightly (README, dynamic solver). So against the rigid cage the
    torque without the cage component must agree within 1 %, and the dynamic cage component must
    not exceed the rigid one. The third case is the thesis's combined scenario of Fig. 7.6: until
    session 37 it found no window in 40 min (the film temperature's solver tolerance,
    tests/friction/test_ehl.py); now 3 windows, 36 s: loads 0.2 %, torque -0.08 %, cage 1e-5."""
    summary, qs, integ = steady_run(overrides)
    rigid = sim.simulate(sim.load_config(overrides + ["friction.cage_guidance=rigid"])).isel(design=0, case=0)
    assert bool(rigid.converged)
    Q = qs["Q"]
    assert Q.min() < 0.7 * Q.max(), "the radial load must make the load distribution non-uniform"
    err_Q = np.abs(summary["Q"] - Q).max() / Q.max()
    err_T = abs(summary["torque"] / qs["torque"] - 1.0)
    cage_d, cage_r = summary["torque_component"][CAGE], float(rigid.torque_component[CAGE])
    rest = (summary["torque"] - cage_d) / (float(rigid.torque) - cage_r) - 1.0
    err_c = abs(summary["cage_speed"] / qs["cage_speed"] - 1.0)
    print(f"{overrides[0]}: loads {err_Q:.2e}, torque {err_T:.2e}, without the cage against the rigid cage "
          f"{rest:.2e}, cage pocket friction {cage_d:.2f} vs {cage_r:.2f} N mm (rigid), cage speed {err_c:.2e}, "
          f"{integ.windows} windows")
    assert err_Q < 0.01
    assert err_T < 0.01
    assert abs(rest) < 0.01
    assert cage_d <= cage_r
    assert err_c < 0.005


def test_rollers_outside_the_load_zone_rest_as_in_the_time_domain():
    """TRB 31313 at 32.1 / 48.0 kN, 3821 rpm (the case of tests/balance/test_resting_rollers.py):
    6 of 13 rollers leave the load zone, and in the time domain their centrifugal force (70 N)
    runs them on the cup and on the rib. The quasi-static solver rests them there
    (sim.solvers.quasi_static, QuasiStaticProblem.rest): their cup and rib loads must match the time
    domain's at the same azimuths within 2 % and 10 % (a roller's rib load there scatters
    32.3-34.6 N over the run, the cup load 65.7-66.2 N), and the torque issue 18's 3 % (the rest
    included; measured 2528.7 N mm against 2569.1, -1.6 %; with their spin held at rolling on the
    cup, before the free rollers' spin inertia of session 24, 2589.5, -2.3 %). Until session 22 the
    quasi-static solver left them unloaded and read 2351 N mm, 7 % below."""
    overrides = ["bearing=trb_31313", "load.Fa=32100", "load.Fr=48000", "load.speed=3821", "load.oil_temperature=47"]
    summary, qs, integ = steady_run(overrides)
    rib = sim.simulate(sim.load_config(overrides)).isel(design=0, case=0).Q_rib.values
    resting = qs["Q"][:, 1] == 0.0
    assert resting.sum() == 6
    assert np.all(summary["Q"][resting, 1] == 0.0)
    np.testing.assert_allclose(summary["Q"][resting, 0], qs["Q"][resting, 0], rtol=0.02)
    np.testing.assert_allclose(summary["Q_rib"][resting], rib[resting], rtol=0.10)
    err_T = summary["torque"] / qs["torque"] - 1.0
    print(f"torque {summary['torque']:.1f} vs {qs['torque']:.1f} N mm ({err_T:+.3%}), {integ.windows} windows")
    assert abs(err_T) < 0.03


def test_quasi_static_roller_spins_follow_their_inertia_along_the_orbit_as_in_the_time_domain():
    """TRB 32208 at 3 / 8 kN, 6000 rpm: the rollers leave the load zone unloaded and coast, their
    spin falling from 1835 to 1547 rad/s over the unloaded arc, until the inner ring spins them up
    again where they enter it. The quasi-static free rollers follow it with their spin inertia
    (sim.solvers.kinematics, "Spin inertia"; until session 24 each roller was balanced at its azimuth,
    which set the slowest to 40 rad/s and read the torque 2.6 % low). Against the time domain's
    rollers at the same azimuths: the slowest spin at the same slot and within 1 % (measured 0.05 %),
    which also fixes the orbit's direction (its mirror image puts it at another slot); every slot
    within 10 % (measured 0.9 % but for the slot where the rollers are spun up, 8.9 %: the backward
    Euler step reaches the balance within one roller pitch, the time domain in about 1.5); the torque
    within 1 % (measured -0.03 %; 858.7 against 859.0 N mm)."""
    summary, qs, integ = steady_run(["bearing=trb_32208", "load.Fa=3000", "load.Fr=8000", "load.speed=6000"])
    w_dyn = integ.rol_aligned[integ.azimuth_order][:, dyn.RO_WR]
    w_qs = qs["kinematics"][1]
    print(f"spins over the time domain's: {np.round(w_qs / w_dyn - 1.0, 4)}; torque {summary['torque']:.2f} vs "
          f"{qs['torque']:.2f} N mm, {integ.windows} windows")
    assert np.argmin(w_qs) == np.argmin(w_dyn)
    assert w_qs.min() == pytest.approx(w_dyn.min(), rel=0.01)
    assert w_qs.min() < 0.9 * w_qs.max()
    np.testing.assert_allclose(w_qs, w_dyn, rtol=0.1)
    assert summary["torque"] == pytest.approx(qs["torque"], rel=0.01)


@pytest.fixture(scope="module", params=[
    ["load.Fa=7160", "load.Fr=6410", "load.speed=3910", "load.oil_temperature=52"],
    ["load.Fa=11320", "load.Fr=8770", "load.speed=4940", "load.oil_temperature=50"],
], ids=["3910rpm", "4940rpm"])
def fast_radial(request):
    """pinion_alpha TSRB, fast and radially loaded (random cases, sessions 24 and 25), from rolling
    kinematics to the steady state: (summary, quasi-static result, the Integration)."""
    return steady_run(["bearing=tsrb_pinion_alpha", "lubricant=pinion_oil"] + request.param)


def test_power_balance_of_a_fast_radially_loaded_tsrb_closes_at_its_steady_state(fast_radial):
    """Issue 18's power balance, 0.5 %, over the steady windows of the fast cases, whose rollers ride on
    their pocket walls. The pocket friction's moment about the roller axis has a z-component (the axis is
    inclined), which the cage must take: without it (until session 34) the cage loss was counted at the
    spin relative to the pocket while the moment acted on the absolute spin, and 0.83 % (3910 rpm) and
    0.61 % (4940 rpm) of the drive's work stayed open (measured with it: -7.8e-4 and -3.9e-4)."""
    summary, qs, integ = fast_radial
    drive, lost, _ = dyn.window_work(integ.y[integ.average_from], integ.y[-1], integ.Z)
    rel = (lost - drive) / drive
    print(f"power balance over the steady windows: {rel:+.2e} of the drive's work")
    assert abs(rel) < 0.005


def test_steady_state_of_a_fast_radially_loaded_tsrb_matches_the_quasi_static_solver(fast_radial):
    """The free rollers' orbit speeds differ from the cage's by up to 1 %, which would carry a roller
    some 1.5 mm along its pocket over an orbit against the 0.15 mm play, so the rollers ride on the
    pocket walls, whose cage pocket friction is most of the difference from rollers free of the walls
    (135 against 2 N mm). With the pocket play along the orbit (sim.solvers.kinematics, "Pocket play")
    issue 18's torque and cage speed targets hold: within 3 % and 0.5 % (measured: torque -0.85 % and
    -0.93 %, cage speed -2.2e-4 and +1.5e-4, session 34, the time domain's torque the drive's with the
    orbit moments and the pocket friction's reaction on the cage, its outer ring's -1.21 % and -1.18 %;
    session 27 +0.11 % and -0.19 %, session 25 +0.27 % and -0.12 %; without the play +8.0 % and +5.3 %,
    cage speed -1e-3)."""
    summary, qs, integ = fast_radial
    err_T = summary["torque"] / qs["torque"] - 1.0
    err_c = summary["cage_speed"] / qs["cage_speed"] - 1.0
    cage = F.COMPONENTS.index("cage")
    print(f"torque {summary['torque']:.1f} vs {qs['torque']:.1f} N mm ({err_T:+.2%}), cage speed {err_c:+.1e}, pocket "
          f"friction {summary['torque_component'][cage]:.1f} vs {qs['torque_component'][cage]:.1f} N mm")
    assert abs(err_T) < 0.03
    assert abs(err_c) < 0.005


def test_a_radially_loaded_trb_settles_over_whole_cage_turns():
    """TRB 31313 at 21.2 / 22 kN, 3390 rpm, 45 degC (pinion oil): its free rollers' rolling orbit
    speed varies by about delta_r / r = 8e-4 around the orbit (the inner ring's surface about its own
    axis), some 0.14 mm along the pocket over half a turn against the 0.15 mm play, so each rests on
    either wall and the steady state repeats with the cage turn. Windows of one inner-ring turn
    alternated by +-4.5e-4 in cage speed and found no steady state in 30 windows (session 35);
    windows of whole cage turns under every radial load (sim.api.dynamic_model.integration_settings)
    settle it (measured: 5 windows, torque +0.04 %, cage speed -3.6e-4, loads 0.39 %, power balance
    2e-5). Issue
    18's targets: torque within 3 %, cage speed within 0.5 %, power balance within 0.5 %, the
    largest load difference within 1 % of the largest load (session 34: 0.49 %)."""
    summary, qs, integ = steady_run(["bearing=trb_31313", "lubricant=pinion_oil", "load.Fa=21200", "load.Fr=22000",
                                     "load.speed=3390", "load.oil_temperature=45"])
    assert integ.settings.window_angle == pytest.approx(2.0 * np.pi, rel=1e-12), "whole cage turns"
    drive, lost, _ = dyn.window_work(integ.y[integ.average_from], integ.y[-1], integ.Z)
    err_T = summary["torque"] / qs["torque"] - 1.0
    err_c = summary["cage_speed"] / qs["cage_speed"] - 1.0
    err_Q = np.abs(summary["Q"] - qs["Q"]).max() / qs["Q"].max()
    print(f"{integ.windows} windows, torque {err_T:+.2%}, cage speed {err_c:+.1e}, loads {err_Q:.2e}, power "
          f"{(lost - drive) / drive:+.1e}")
    assert abs(err_T) < 0.03 and abs(err_c) < 0.005 and abs(lost - drive) < 0.005 * drive
    assert err_Q < 0.01


@pytest.mark.xfail(strict=True, reason=(
    "the rollers' axial motion along the orbit: in the time domain the TSRB rollers move along their axes at up to "
    "25 mm/s as they cross the load zone's edges, and the lateral slip of that motion loads each by 4-6 N along its "
    "axis (at 3910 rpm; the rhs with and without the rollers' velocities), which shifts their axial positions and "
    "so their loads; the quasi-static solution has no such rate (session 27: the time domain's rate-induced "
    "loads added to it bring 4.1 % down to 1.2 %). The ring's lateral force is the same in both (tractions 33 "
    "against 30 N). Loads differ by up to 4.25 % (3910 rpm) and 2.46 % (4940 rpm) of the largest (4.1 and 2.6 % "
    "before session 37's pocket-radius correction)"))
def test_roller_loads_of_a_fast_radially_loaded_tsrb_match_the_quasi_static_solver(fast_radial):
    """Issue 18's load target for the cases above: every roller's loads within 1 % of the largest."""
    summary, qs, integ = fast_radial
    err = np.abs(summary["Q"] - qs["Q"]).max() / qs["Q"].max()
    sym = np.abs(mirror_mean(summary["Q"]) - mirror_mean(qs["Q"])).max() / qs["Q"].max()
    print(f"loads {err:.2e}, their mirror-symmetric part {sym:.2e} of the largest")
    assert err < 0.01


def test_tsrb_rollers_outside_the_load_zone_rest_in_the_wedge_as_in_the_time_domain():
    """Prototype TSRB at 1.05 / 1.15 kN, 1891 rpm: 6 of its 17 rollers leave the load zone of the
    rigid rings. In the time domain their centrifugal force (1.4 N) runs them on the outer raceway,
    which pushes them along their axis into the wedge between both raceways, where each carries about
    5 N on the inner raceway. The quasi-static solver moves them there (no rib:
    sim.solvers.quasi_static._onto_the_rest): every roller's raceway loads must match the time
    domain's at the same azimuths within issue 18's 1 % of the largest load, those rollers' inner
    loads within 10 % each (their scatter over the run; without the rest they read 0), and the torque
    within 3 % (measured +0.13 %: 319.2 against 319.6 N mm; without the rest 315.3, -1.4 %)."""
    overrides = ["bearing=tsrb_prototype", "load.Fa=1050", "load.Fr=1150", "load.speed=1891"]
    summary, qs, integ = steady_run(overrides)
    bare = sim.simulate(sim.load_config(overrides + ["solver.centrifugal=false"])).isel(design=0, case=0)
    outside = bare.Q.sel(race="inner").values == 0.0
    assert outside.sum() >= 4
    assert np.all(qs["Q"][outside] > 0.0)
    assert np.abs(summary["Q"] - qs["Q"]).max() < 0.01 * qs["Q"].max()
    np.testing.assert_allclose(summary["Q"][outside, 1], qs["Q"][outside, 1], rtol=0.10)
    err_T = summary["torque"] / qs["torque"] - 1.0
    print(f"torque {summary['torque']:.1f} vs {qs['torque']:.1f} N mm ({err_T:+.3%}), {integ.windows} windows")
    assert abs(err_T) < 0.03


def test_skewed_rollers_under_a_radial_load_settle_over_whole_cage_turns():
    """Reference TSRB at 1.26 / 1.18 kN, 6386 rpm, skew free: each roller may rest on either pocket
    wall, so the steady state repeats with the cage turn, not the roller pass. With windows of one
    inner-ring turn (7 roller passes) the window means cycled with a period of about 5 windows and
    no steady state came in 30 (session 21, 231 s); windows of whole cage turns
    (sim.api.dynamic_model.integration_settings, the rule for free skew under a radial load or a
    tilt) settle it (measured: 5 windows, 141 s, 850.5 N mm against the free quasi-static 850.7,
    loads within 8.4e-3 of the largest). Issue 18's targets: loads within 1 %, torque within 3 %,
    cage speed within 0.5 % (free quasi-static, the default)."""
    overrides = ["bearing=tsrb_reference", "load.Fa=1260", "load.Fr=1180", "load.speed=6386",
                 "load.oil_temperature=48", "friction.skew.enabled=true"]
    model, friction, op, plain, dc = dynamic_case(overrides + ["solver.dynamic.start=rolling"])
    assert dc.settings.window_angle == pytest.approx(2.0 * np.pi, rel=1e-12)
    integ = dm.run(dc)
    assert integ.steady, f"no steady state in {integ.windows} windows"
    summary, _ = dm.outputs(model, op, dc, integ, 0.0, plain["output"])
    qs = dc.quasi_static
    assert np.abs(summary["Q"] - qs["Q"]).max() / qs["Q"].max() < 0.01
    assert abs(summary["torque"] / qs["torque"] - 1.0) < 0.03
    assert abs(summary["cage_speed"] / qs["cage_speed"] - 1.0) < 0.005


@pytest.fixture(scope="module")
def skew_run():
    """TRB 32208 with free skew (friction.skew.enabled) from rolling kinematics and no skew, to
    the steady state the detector finds (skews included)."""
    model, friction, op, plain, dc = dynamic_case(TRB + ["friction.skew.enabled=true", "solver.dynamic.start=rolling"])
    integ = dm.run(dc)
    summary, _ = dm.outputs(model, op, dc, integ, 0.0, plain["output"])
    return integ, summary, dc.quasi_static


def test_free_skew_steady_state_matches_the_quasi_static_solver(skew_run):
    """Skew free: loads, torque and cage speed within the targets of the unskewed rung (1 %, 3 %,
    0.5 %) of the quasi-static solution with skew."""
    integ, summary, qs = skew_run
    assert integ.steady, f"no steady state in {integ.windows} windows: changes {integ.change}"
    err_Q = np.abs(summary["Q"] / qs["Q"] - 1.0).max()
    err_T = abs(summary["torque"] / qs["torque"] - 1.0)
    err_c = abs(summary["cage_speed"] / qs["cage_speed"] - 1.0)
    print(f"skew free: loads {err_Q:.2e}, torque {err_T:.2e}, cage speed {err_c:.2e}")
    assert err_Q < 0.01
    assert err_T < 0.03
    assert err_c < 0.005


def test_free_skew_settles_to_the_quasi_static_skew(skew_run):
    """The TRB rollers hold their skew inside the pocket clearance, where the friction moment about
    v' vanishes (the rib load restores, sim.physics.friction "Roller skew"). Target: the
    quasi-static skew within 1 %, the load target of the ladder. (Measured 0.4 %; 3.8 % while the
    slip left out the skew rate: the skew then rang undamped on the rib's restoring stiffness about
    the equilibrium, and the window mean of 40 samples of that oscillation was off it; see
    test_the_rib_held_skew_is_overdamped_and_creeps_at_the_traction_rate.)"""
    integ, summary, qs = skew_run
    err_skew = np.abs(summary["roller_skew"] / qs["roller_skew"] - 1.0).max()
    print(f"skew free: skew {summary['roller_skew'][0]:.5f} vs {qs['roller_skew'][0]:.5f} deg ({err_skew:.2e})")
    assert err_skew < 0.01


def test_the_transient_converges_with_the_integrator_tolerance():
    """Convergence rung (issue 18 item 4): the pinion TSRB (its cheapest case: 35 kN, 1100 rpm,
    pinion oil 50 degC) from rolling kinematics over 0.1 revolution, sampled 20 times, at rtol
    1e-3 ... 1e-7 against rtol 1e-10 (the configured method). Error-per-step control with an
    error estimate of order q makes an integrator of order p tolerance proportional with a
    global error ~ rtol^(p/(q+1)) (Hairer, Norsett & Wanner 1993, Solving ODEs I, II.4): BDF at
    order k = 1 ... 5 (q = k) 0.5-0.83; Radau IIA (order 5, stage order 3 under stiffness, q = 3,
    Hairer & Wanner 1996, IV.8) 0.75-1.25. The least-squares order of the cage speed's RMS error
    must lie in [0.5, 1.5] (above 1.5 the reference itself would be in doubt). The
    torque, which carries the contacts' vibration, converges less orderly (its error has stalled
    over two decades of rtol, until the steps resolve the contact modes; README); over the four
    decades it must still fall by two at least, the least any order >= 0.5 gives."""
    model, friction, op, plain, dc = dynamic_case(PINION_TSRB + ["solver.dynamic.start=rolling"])
    o_cage = dc.problem.bearing.Z * NS + NRING + 1
    tols = [1e-3, 1e-4, 1e-5, 1e-6, 1e-7]
    runs = {}
    for rtol in [1e-10] + tols:
        settings = dc.settings._replace(rtol=rtol, atol=rtol * dc.settings.scale, window=0.1 * dc.settings.window,
                                        samples=20, max_windows=1)
        integ = Integration(dc.problem, settings).run(dc.y0)
        runs[rtol] = (integ.y[1:, o_cage], integ.tot_t[1:, TO_TOUT])
    ref = runs[1e-10]
    err = np.array([[np.sqrt(np.mean((runs[r][k] / ref[k] - 1.0) ** 2)) for k in range(2)] for r in tols])
    order = np.polyfit(np.log10(tols), np.log10(err[:, 0]), 1)[0]
    print("rtol " + " ".join(f"{r:.0e}" for r in tols) + "\ncage speed " + " ".join(f"{e:.2e}" for e in err[:, 0])
          + "\ntorque " + " ".join(f"{e:.2e}" for e in err[:, 1]) + f"\nobserved order (cage speed) {order:.2f}")
    assert 0.5 <= order <= 1.5
    assert err[-1, 1] < 1e-2 * err[0, 1]


# the prototype TSRB (thesis Table 6.1) at 3.46 kN, 4199 rpm: its quasi-static skew reverses between
# 31 and 40 degC oil (tests/friction/test_skew.py: the outer race's skew moment outweighs the inner's
# in the thicker film)
SKEW_REVERSAL = ["bearing=tsrb_prototype", "load.Fa=3462", "load.Fr=0", "load.speed=4199"]
SKEW_REVERSAL_TEMPERATURES = {25.0: -1.0, 60.0: +1.0}     # degC: sign of the skew


def test_skew_changes_sign_with_the_inner_outer_friction_balance_in_time():
    """Trend rung (issue 18 item 4), Kellstroem (1979) and Blomqvist in the time domain: a roller
    skews towards the side to which the friction of the dominating raceway contact turns it, so
    reversing the balance of inner and outer raceway friction reverses the skew. Along a crowned
    roller the rolling speed matches each ring on a line only, so each race's circumferential
    tractions change sign along the roller and leave a moment about the skew axis v' of opposite
    signs (outer < 0 < inner). In the prototype TSRB at 3.46 kN and 4199 rpm the oil temperature
    shifts that balance: at 25 degC the outer race's moment is the larger (-45.6 against 44.1 N mm),
    at 60 degC the inner's (50.1 against -46.5; tests/friction/test_skew.py). From rolling
    kinematics and zero skew, skew and tilt free, integrated for 0.3 revolution (4.0 ms; the rollers
    creep onto their pockets within ~2 ms), every roller's skew over the window's last quarter
    must have the sign the balance gives (signs only: their size is the pocket clearance's,
    atan(c / Lwe) = 0.43 deg). Until session 21 this rung raised one race's film viscosity
    five-fold by hand, which the film computed in every right-hand side no longer keeps."""
    for temperature, sign in SKEW_REVERSAL_TEMPERATURES.items():
        model, friction, op, plain, dc = dynamic_case(SKEW_REVERSAL + [f"load.oil_temperature={temperature}",
                                                                       "friction.skew.enabled=true",
                                                                       "solver.dynamic.start=rolling"])
        Z = dc.problem.bearing.Z
        settings = dc.settings._replace(window=0.3 * dc.settings.window, samples=20, max_windows=1)
        integ = Integration(dc.problem, settings).run(dc.y0)
        skew = np.degrees(integ.y[-5:, PSI:Z * NS:NS])
        print(f"{temperature} degC: skew of the last quarter {skew.min():.4f} to {skew.max():.4f} deg")
        assert np.all(np.sign(skew) == sign)


def test_the_rib_held_skew_is_overdamped_and_creeps_at_the_traction_rate():
    """The TRB 31313 at the pinion case (35 kN, 1100 rpm, pinion oil 50 degC). Its roller end on
    the rib turns the rib load with the skew, a restoring stiffness k ~ 8e5 N mm/rad about v'
    (sim.physics.friction, "Roller skew"), which with the roller's transverse inertia I_y would
    make a 2.4 kHz skew mode. A skew rate psi' moves every slice by psi' x along the rolling
    direction (rigid-body kinematics, x along the roller axis), and the tractions' slope against
    slip resists it: c = -dM/dpsi' ~ 3e3 N mm s, a damping ratio c / (2 sqrt(k I_y)) ~ 27. So the
    skew creeps: the inertia term I_y psi'' is negligible (lag I_y / c ~ 1 us) and
    c(psi) psi' = M(psi), M the moment about v' of the tractions and the rib at the quasi-static
    kinematics (roller_traction), whence the time to half the equilibrium skew psi* is
    t_1/2 = int_0^(psi*/2) c / M dpsi. From the quasi-static solution with the skew set to 0 the
    run must reach psi*/2 at that time within 20 %, and rise monotonically without overshoot. The
    prediction holds the loads, tilt, speeds and film of the quasi-static solution in M and c; in
    the run they respond to the lateral tractions along the path (measured 4 % with the film held
    over the window, 16 % since session 21 with the film following the loads: the run creeps
    faster), so the bound tests the creep law's order and shape, not its path. Without the skew rate in the slip the skew
    rang undamped between 0 and 2 psi* (quarter period 0.1 ms against t_1/2 ~ 3 ms)."""
    overrides = ["bearing=trb_31313"] + PINION_TSRB[1:] + ["friction.skew.enabled=true",
                                                           "solver.dynamic.start=quasi_static"]
    model, friction, op, plain, dc = dynamic_case(overrides)
    problem = dc.problem
    raw, fr = dm.quasi_static_start(model, friction, op)
    kin = fr["kinematics"]
    wc, wR, psi = kin[0], kin[1], kin[2]
    _, y0 = dm.body_and_state(model, friction, op, plain["solver"]["dynamic"], raw,
                                 (wc, wR, np.zeros_like(psi), kin[3]))
    ev = np.zeros(F.NEV)

    def moment(p, p_dot):
        F.roller_traction(0, wR[0], p, F.NO_RATES._replace(psi_dot=p_dot), wc, problem.body.wi, problem.case, ev)
        return ev[F.EV_MS]

    psi_eq = psi[0]
    rate = 1e-3                                           # rad/s, difference step of the skew rate (M is smooth in it)
    p = np.linspace(0.0, 0.5 * psi_eq, 21)
    c = np.array([-(moment(x, rate) - moment(x, -rate)) / (2.0 * rate) for x in p])
    t_half = np.trapezoid(c / np.array([moment(x, 0.0) for x in p]), p)
    k = moment(0.0, 0.0) / psi_eq
    print(f"k {k:.3g} N mm/rad, c {c[0]:.3g} ... {c[-1]:.3g} N mm s, zeta {c.min() / (2 * np.sqrt(k * problem.body.Iy)):.3g}")
    assert c.min() > 2.0 * np.sqrt(k * problem.body.Iy), "not overdamped: the creep law would not apply"
    settings = dc.settings._replace(window=0.1 * dc.settings.window, samples=200, max_windows=1)
    integ = Integration(problem, settings).run(y0)
    s, t = integ.y[:, PSI], integ.t
    i = np.flatnonzero(s >= 0.5 * psi_eq)[0]
    t_run = t[i - 1] + (0.5 * psi_eq - s[i - 1]) / (s[i] - s[i - 1]) * (t[i] - t[i - 1])
    print(f"time to half the skew {psi_eq:.3e} rad: predicted {t_half * 1e3:.3f} ms, run {t_run * 1e3:.3f} ms")
    assert abs(t_run / t_half - 1.0) < 0.20
    assert np.all(np.diff(s) >= 0.0) and s.max() <= psi_eq


def test_a_roller_touching_its_rib_off_the_load_zone_has_a_rib_film_and_finite_rates():
    """The film follows each roller's loads in every right-hand side
    (sim.physics.friction.roller_lubrication). Until session 20 it was held over a window, so a
    roller could touch its rib with no rib film; the rib traction then divided by the film's zero
    rib pressure (ZeroDivisionError before anything ran: TRB 31313 at 32 / 48 kN, 3821 rpm, where
    at the start state a roller outside the quasi-static load zone touches its rib; since session
    22 the quasi-static solution rests it there). At that state every roller on its rib now has a
    rib film and pays rib friction, and the rates are finite."""
    _, _, _, _, dc = dynamic_case(["bearing=trb_31313", "load.Fa=32058", "load.Fr=48018", "load.speed=3821",
                                   "load.oil_temperature=47"])
    integ = Integration(dc.problem, None)
    dy = integ.f(0.0, dc.y0)
    assert np.isfinite(dy).all()
    on_rib = integ.rol[:, RO_QRIB] > 0.0
    film = dc.problem.case.film
    between_rings = dc.quasi_static["Q"][:, 1] > 0.0
    assert on_rib.any() and not between_rings[on_rib].all(), "a roller off the quasi-static load zone must touch its rib"
    assert np.all(film.prib[on_rib] > 0.0) and np.all(film.hrib[on_rib] > 0.0)
    assert integ.tot[TO_P0 + F.COMPONENTS.index("rib")] > 0.0


def test_free_rollers_hold_where_a_rigid_cage_is_far_off_the_dynamic_torque():
    """TRB 32208 at 19.5 / 26.7 kN, 1201 rpm, FVA 3 at 108 degC (from 200 random cases, the one
    where the two guidances part most): a rigid cage carries every loaded roller's net traction,
    and its pocket friction (302 N mm) puts the torque 44 % above the time domain's (976 against
    676.5 N mm, of it pocket friction 6.4 N mm); the free rollers (the default since session 20)
    come within issue 18's 3 % (measured 680.6 N mm, +0.6 %; -1.9 % while the time domain held the
    film per window, session 20) and their pocket friction within 1 N mm of the dynamic (measured
    6.5 against 6.4 N mm; the bound is a third of a percent of the rigid cage's 302 N mm, which it
    would exceed by 295)."""
    overrides = ["bearing=trb_32208", "load.Fa=19484", "load.Fr=26690", "load.speed=1201", "load.oil_temperature=108"]
    dynamic = sim.simulate(sim.load_config(overrides + ["solver=dynamic"])).isel(design=0, case=0)
    free = sim.simulate(sim.load_config(overrides)).isel(design=0, case=0)
    rigid = sim.simulate(sim.load_config(overrides + ["friction.cage_guidance=rigid"])).isel(design=0, case=0)
    assert bool(dynamic.converged) and bool(free.converged) and bool(rigid.converged)
    torque = float(dynamic.torque)
    assert abs(float(free.torque) / torque - 1.0) < 0.03
    assert float(rigid.torque) / torque - 1.0 > 0.3
    assert abs(float(free.torque_component.sel(component="cage")) - float(dynamic.torque_component.sel(component="cage"))) < 1.0


def synthetic_windows(rng, n, torque_scatter, drift=0.0):
    """n window means of the detector's layout: cage speed 100 rad/s with a relative scatter 2e-5,
    torque 1000 N mm with ``torque_scatter`` and a relative drift ``drift`` over the block, 17
    roller loads (sorted) 100-2000 N with a scatter of 2e-4 of the largest, skews 0."""
    loads = np.linspace(100.0, 2000.0, 17)
    out = []
    for i in range(n):
        trend = 1.0 + drift * i / (n - 1)
        out.append((100.0 * (1.0 + 2e-5 * rng.standard_normal()),
                    1000.0 * trend * (1.0 + torque_scatter * rng.standard_normal()),
                    np.sort(loads + 2000.0 * 2e-4 * rng.standard_normal(17))[:, None],
                    np.zeros(17)))
    return out


TOLERANCES = (1e-4, 1e-3, 1e-3, 1e-3)      # conf/solver/dynamic.yaml: speed, torque, load, skew


def test_windows_that_scatter_about_a_steady_state_are_told_from_a_drift_and_from_too_much_scatter():
    """sim.solvers.dynamic.fluctuates_about_a_steady_state over blocks of 6 windows (the config's
    fluctuation_windows), 400 seeded blocks each. Scatter 1.5e-3 in torque (as measured on the TRB
    32208 at 4.5 / 9 kN, 2000 rpm), no drift: the block mean's standard error is 6e-4 < 1e-3, and
    the halves' test (their difference below the tolerance plus twice its standard error, for
    cage speed, torque and each of 17 loads) accepts at least 80 %. The same with a drift of 1 %
    over the block (halves 6e-3 apart, 5 standard errors beyond the tolerance): at most 1 %
    accepted. Scatter 6e-3 (standard error 2.4e-3): at most 5 % accepted (six windows' sample
    standard deviation falls below 0.41 of the true one, which passes, with probability ~3 %:
    chi-square with 5 degrees of freedom). A run whose windows agree pairwise is steady earlier
    anyway."""
    rng = np.random.default_rng(2026)
    skew_clearance = 1.0

    def accepted(scatter, drift):
        return np.mean([dyn.fluctuates_about_a_steady_state(synthetic_windows(rng, 6, scatter, drift), TOLERANCES,
                                                            skew_clearance) for _ in range(400)])

    stationary, drifting, noisy = accepted(1.5e-3, 0.0), accepted(1.5e-3, 0.01), accepted(6e-3, 0.0)
    print(f"accepted: stationary {stationary:.3f}, drifting {drifting:.3f}, too noisy {noisy:.3f}")
    assert stationary >= 0.80
    assert drifting <= 0.01
    assert noisy <= 0.05


def test_settled_windows_whose_power_balance_does_not_close_are_no_steady_state():
    """Session 33's checker D: a cage of 1e3 kg m^2 (within the schema's range, far beyond the 2e-5 -
    1e-3 of a real one) does not move within the run, so its window means settled (cage speed 8e-9 per
    window) and the run was reported converged, 4.8 % below the quasi-static torque, while 3.6 % of the
    drive's work went into the cage's kinetic energy. A steady state must close its power balance
    (solver.dynamic.steady_tolerance_power, 0.5 %): this one is reported as none, naming the
    imbalance. (The time domain's tsrb_pinion_long at 5 / 4 kN, 5500 rpm, whose contacts did net work of
    53 % of the drive's there, is refused the same way; README, dynamic solver.)"""
    *_, dc = dynamic_case(["bearing=tsrb_prototype", "load.Fa=2500", "load.Fr=1500", "load.speed=3000",
                           "load.oil_temperature=60", "solver.dynamic.cage_inertia=1000"])
    integ = dm.run(dc)
    assert integ.windows >= 2 and not integ.steady
    assert "steady_tolerance_power" in integ.failure and "-3." in integ.failure, integ.failure
