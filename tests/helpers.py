"""Test helpers: load cases, independent recomputation of forces from a solved state, killed searches."""
import numpy as np
import pytest

from sim.api import OperatingPoint


def case(Fa, Fr=0.0, speed=2000.0, tilt=0.0, oil_temperature=55.0):
    return OperatingPoint(float(Fa), float(Fr), float(speed), float(tilt), float(oil_temperature))


def ring_in_meridian(raw, psi):
    """The inner ring's displacement of a solved state seen in the meridian plane at azimuth psi
    [rad]: (delta_a, delta_r cos(psi) + delta_y sin(psi)) [mm] (sim.solvers.quasi_static.solve_bearing)."""
    da, dr, dy = raw["ring"]
    return np.array([da, dr * np.cos(psi) + dy * np.sin(psi)])


def roller_race_force(model, raw, j, race=1, tilt_deg=0.0):
    """Force (radial, axial) [N] of roller j's slice loads of one race (0 outer, 1 inner) on its
    ring, in the roller's meridian plane, recomputed from the solved state: normals from the
    contact kernel at the returned pose (imposed tilt of the inner ring included), loads from the
    returned line loads; each slice presses the ring with +q w n (n into the ring)."""
    from sim.physics.contact import Raceway, RingMotion, SliceContacts, slice_contact_meridian

    g = model.geometry
    a = g.arrays
    n = g.n_slices
    d, nrm, pts = np.empty(n), np.empty((n, 2)), np.empty((n, 2))
    psi = 2 * np.pi * j / g.Z
    if race == 0:
        slice_contact_meridian(a["x"], a["rho"], 1, raw["poses"][j], g.alpha, g.Dpw,
                               Raceway(a["race_kind"][0], a["race_par"][0]), RingMotion(0.0, 0.0, 0.0),
                               SliceContacts(d, nrm, pts))
    else:
        slice_contact_meridian(a["x"], a["rho"], -1, raw["poses"][j], g.alpha, g.Dpw,
                               Raceway(a["race_kind"][1], a["race_par"][1]),
                               RingMotion(ring_in_meridian(raw, psi)[1], raw["ring"][0],
                                          np.radians(tilt_deg) * np.cos(psi)), SliceContacts(d, nrm, pts))
    load = raw["line_load"][j, race] * a["w"]
    return np.array([np.sum(load * nrm[:, 0]), np.sum(load * nrm[:, 1])])


def race_forces(model, raw, race=1, tilt_deg=0.0, lateral=False):
    """Resultant (x, z) [N] of the slice loads of one race (0 outer, 1 inner) on its ring, all
    rollers, recomputed from the solved state (:func:`roller_race_force`, independent of the
    solver's residual bookkeeping); (x, y, z) with ``lateral``: each roller's radial component
    summed as a 3-D vector over the azimuths (x = times cos(psi), y = times sin(psi))."""
    Fx = Fy = Fz = 0.0
    for j in range(model.geometry.Z):
        psi = 2 * np.pi * j / model.geometry.Z
        radial, axial = roller_race_force(model, raw, j, race, tilt_deg)
        Fx += radial * np.cos(psi)
        Fy += radial * np.sin(psi)
        Fz += axial
    return (Fx, Fy, Fz) if lateral else (Fx, Fz)


def roller_residuals(model, raw, op, ext=None, reported=False):
    """Relative residual of every loaded roller: contact forces (recomputed from the returned
    poses and ring) + centrifugal force + gyroscopic moment + external load ``ext`` (Z, 3),
    over its loads [1]. ``reported``: only the rollers the solver reports loaded (Q or Q_rib
    > 0); the returned pose of a roller it released may still touch the rib (a TRB roller out of
    the load zone, tilted ring: issue 15 fuzz finding)."""
    from sim.physics.contact import roller_axes
    from sim.physics.roller_contact import empty_roller_contact, roller_contact

    g = model.geometry
    body = model.body_loads(op)
    ext = np.zeros((g.Z, 3)) if ext is None else ext
    out = []
    for j in range(g.Z):
        psi = 2 * np.pi * j / g.Z
        state = empty_roller_contact(g.n_slices)
        state.pose[:] = raw["poses"][j]
        state.q[:] = raw["line_load"][j]
        state.active[:] = state.q > 0
        roller_contact(ring_in_meridian(raw, psi), np.radians(op.tilt_deg) * np.cos(psi), 1.0, model.bearing,
                       model.elasticity, state)
        f, Q = state.f, state.Q
        if Q[0] + Q[1] == 0.0 or (reported and raw["Q"][j].sum() + raw["Q_rib"][j] == 0.0):
            continue  # unloaded roller, held by the cage
        ur, uz, vr, vz = roller_axes(g.alpha, raw["poses"][j, 2])
        r = f[:3] + np.array([body.centrifugal * ur, body.centrifugal * vr, body.gyroscopic]) + ext[j]
        out.append(max(abs(r[0]), abs(r[1]), abs(r[2]) / g.Lwe) / (Q[0] + Q[1] + Q[2]))
    return np.array(out)


def killed_search_run(search, on_batch=2):
    """Run a design search (studies.loop.DesignSearch) that is killed (KeyboardInterrupt) when it
    starts its ``on_batch``-th batch of full simulations; returns the sizes of the batches asked for."""
    calls, original = [], search.simulate

    def dies(X, source, round_index):
        calls.append(len(X))
        if len(calls) == on_batch:
            raise KeyboardInterrupt("killed")
        return original(X, source, round_index)

    search.simulate = dies
    with pytest.raises(KeyboardInterrupt):
        search.run()
    return calls


def assert_study_refused(study, key, value, words):
    """Setting ``key`` of a study config node to ``value`` makes studies.config.validate raise a
    StudyConfigError whose message holds every one of ``words`` (key, value, allowed range)."""
    from omegaconf import OmegaConf

    from studies.config import StudyConfigError, validate

    study = study.copy()
    OmegaConf.update(study, key, value, merge=False)
    with pytest.raises(StudyConfigError) as err:
        validate(study)
    for w in words:
        assert w in str(err.value)


# Half-space sub-model of one solved contact (halfspace_contact_peak): grid width across the contact
# in Hertz half-widths b of the mean line load; reach past each roller end in corner radii (the drop
# there, 0.2 r_c, is far above any elastic approach here, ~0.005 mm); one-sided difference step for
# the generatrix slope at the roller ends [mm].
HALFSPACE_WIDTH_ACROSS = 5.0
HALFSPACE_CORNER_EXTENT = 0.6
HALFSPACE_FD_STEP = 1e-4


def halfspace_contact_peak(model, raw, j, race, corner_radius, per_mm, across):
    """Peak pressure [MPa] of roller j's contact with ``race`` (0 outer, 1 inner: the inner ring's
    displacement is applied in roller j's meridian plane, untilted) at the solved state ``raw``,
    from the 2-D half-space reference (sim.physics.halfspace) at the same contact load, and its x
    from mid-roller [mm].

    The rigid gap is the slice kernel's (sim.physics.contact.slice_contact_meridian) on
    ``per_mm`` columns per mm; past each end of Lwe the generatrix continues along its tangent and
    drops by a corner circle of radius ``corner_radius`` [mm] tangent to it, r_c - sqrt(r_c^2 - s^2)
    at a distance s past the end; the radius of relative curvature across the roller is the slice
    model's R_eq, interpolated; ``across`` cells over HALFSPACE_WIDTH_ACROSS Hertz half-widths.
    """
    from sim.physics.contact import Raceway, RingMotion, SliceContacts, slice_contact_meridian
    from sim.physics.halfspace import solve_contact_halfspace

    g, b = model.geometry, model.bearing
    half = 0.5 * g.Lwe
    reach = half + HALFSPACE_CORNER_EXTENT * corner_radius
    nx = int(round(2.0 * reach * per_mm))
    dx = 2.0 * reach / nx
    x = -reach + (np.arange(nx) + 0.5) * dx
    inside = half * (1.0 - 1e-9)         # the TRB's logarithmic drop is unbounded at the very ends
    x_end = np.clip(x, -inside, inside)
    s = np.abs(x) - half
    step = HALFSPACE_FD_STEP
    slope = (g.roller_radius(x_end) - g.roller_radius(x_end - np.sign(x_end) * step)) / step
    corner = corner_radius - np.sqrt(np.maximum(corner_radius ** 2 - s ** 2, 0.0))
    rho = g.roller_radius(x_end) + np.where(s > 0.0, slope * s - corner, 0.0)
    psi = 2.0 * np.pi * j / g.Z
    ring = RingMotion(0.0, 0.0, 0.0) if race == 0 else RingMotion(ring_in_meridian(raw, psi)[1], raw["ring"][0], 0.0)
    d, nrm, pts = np.empty(nx), np.empty((nx, 2)), np.empty((nx, 2))
    slice_contact_meridian(x, rho, 1 - 2 * race, raw["poses"][j], b.alpha, b.Dpw,
                           Raceway(b.race_kind[race], b.race_par[race]), ring, SliceContacts(d, nrm, pts))
    order = np.argsort(b.x)              # slices run from the large end: np.interp needs increasing x
    R = np.interp(x, b.x[order], b.R_eq[race][order])
    load = float(raw["Q"][j, race])
    half_width = np.sqrt(4.0 * (load / g.Lwe) * R.max() / (np.pi * model.E_star))
    dy = HALFSPACE_WIDTH_ACROSS * half_width / across
    y = (np.arange(across) - 0.5 * across + 0.5) * dy
    p, _, converged, _ = solve_contact_halfspace(-d[:, None] + y[None, :] ** 2 / (2.0 * R[:, None]), dx, dy,
                                                 model.E_star, load=load)
    assert converged
    return float(p.max()), float(x[int(np.argmax(p.max(axis=1)))])


def contact_stiffness_and_difference(model, raw, j, cpsi, h=1e-7):
    """The tangent stiffness K = -df/dy of roller j of a solved state (sim.physics.roller_contact,
    ring rotation cos(psi_j) = ``cpsi``) and its central finite difference J with step ``h``
    [mm, rad], in the contact chart y = (a, b along the roller's current axes u', v'; theta;
    ring delta_a, delta_r): (K, J), both (5, 5). Asserts that no slice changes its contact state
    within the step (the difference would cross a kink)."""
    from sim.physics.roller_contact import empty_roller_contact, roller_contact

    n = model.geometry.n_slices

    def forces(pose, ring):
        state = empty_roller_contact(n)
        state.pose[:] = pose
        roller_contact(ring, 0.0, cpsi, model.bearing, model.elasticity, state)
        return state.f.copy(), state.K.copy(), state.active.copy()

    pose0, ring0 = raw["poses"][j].copy(), raw["ring"][:2].copy()
    _, K, active = forces(pose0, ring0)
    th = pose0[2]
    steps = [np.array([np.cos(th), np.sin(th), 0.0, 0.0, 0.0]), np.array([-np.sin(th), np.cos(th), 0.0, 0.0, 0.0]),
             np.array([0.0, 0.0, 1.0, 0.0, 0.0]), np.array([0.0, 0.0, 0.0, 1.0, 0.0]),
             np.array([0.0, 0.0, 0.0, 0.0, 1.0])]
    J = np.empty((5, 5))
    for col, e in enumerate(steps):
        fp, _, act_p = forces(pose0 + h * e[:3], ring0 + h * e[3:])
        fm, _, act_m = forces(pose0 - h * e[:3], ring0 - h * e[3:])
        assert np.array_equal(act_p, active) and np.array_equal(act_m, active)  # no slice changes state
        J[:, col] = -(fp - fm) / (2.0 * h)
    return K, J

