"""Slice contact kernels against closed forms (MODEL.md 3)."""
import numpy as np
import pytest

import sim
from sim.physics.contact import slice_contact_3d, slice_contact_meridian
from sim.api.simulation import build_model


def _setup(bearing):
    g = build_model(sim.load_config([f"bearing={bearing}"])).geometry
    return g, g.arrays


def _pose_3d(g, pose, skew):
    """Roller centre and axis in 3-D (azimuth 0: meridian plane = x-z) for a meridian pose plus skew."""
    a, th = g.alpha, pose[2]
    u = np.array([np.sin(a + th), 0.0, -np.cos(a + th)])
    v = np.array([np.cos(a + th), 0.0, np.sin(a + th)])
    centre = np.array([0.5 * g.Dpw + pose[0] * np.sin(a) + pose[1] * np.cos(a), 0.0,
                       -pose[0] * np.cos(a) + pose[1] * np.sin(a)])
    # skew: rotate the axis about v (the normal of the tangent plane at the roller)
    c, s = np.cos(skew), np.sin(skew)
    axis = u * c + np.cross(v, u) * s
    return centre, axis, v


@pytest.mark.parametrize("bearing", ["trb_32208", "tsrb_reference"])
def test_untilted_penetration_is_zero_at_nominal_contact(bearing):
    """Nominal pose, rings unloaded: the TRB roller touches along its crown apex (penetration 0
    at mid-length, negative elsewhere by the log crown drop (2.5)); the TSRB touches at its two
    contact points only (MODEL.md 2). Tolerance 1e-9 mm (round-off of mm-sized coordinates)."""
    g, a = _setup(bearing)
    n = g.n_slices
    d = np.empty(n)
    nrm = np.empty((n, 2))
    pts = np.empty((n, 2))
    for side, s in ((1, 0), (-1, 1)):
        slice_contact_meridian(a["x"], a["rho"], side, np.zeros(3), g.alpha, g.Dpw, a["race_kind"][s],
                               a["race_par"][s], 0.0, 0.0, 0.0, d, nrm, pts)
        assert d.max() <= 1e-9
        if bearing == "trb_32208":
            from sim.geometry import log_crown_drop
            np.testing.assert_allclose(d, -log_crown_drop(a["x"], g.Dwe, g.Lwe, g.crown_coefficient), atol=1e-9)
        # a radial push by e along v gives penetration e * (n . v) at every slice, closed form
        e = 1e-3
        d2 = np.empty(n)
        slice_contact_meridian(a["x"], a["rho"], side, np.array([0.0, side * e, 0.0]), g.alpha, g.Dpw,
                               a["race_kind"][s], a["race_par"][s], 0.0, 0.0, 0.0, d2, nrm, pts)
        nv = nrm[:, 0] * np.cos(g.alpha) + nrm[:, 1] * np.sin(g.alpha)
        np.testing.assert_allclose(d2 - d, e * side * nv, atol=2e-9)


@pytest.mark.parametrize("bearing", ["trb_32208", "tsrb_reference"])
def test_3d_kernel_equals_meridian_without_skew_and_loses_depth_with_skew(bearing):
    """The 3-D kernel (any pose) reproduces the meridian kernel without skew (1e-9 mm), and a
    skew angle phi changes the penetration only at O(phi^2), and the kernel's deepest point matches
    a brute-force search over the slice circle (1e-9 mm)."""
    g, a = _setup(bearing)
    n = g.n_slices
    pose = np.array([0.01, 0.004, 2e-4])
    d_m = np.empty(n)
    nrm = np.empty((n, 2))
    pts = np.empty((n, 2))
    slice_contact_meridian(a["x"], a["rho"], 1, pose, g.alpha, g.Dpw, a["race_kind"][0], a["race_par"][0],
                           0.0, 0.0, 0.0, d_m, nrm, pts)
    origin, zaxis = np.zeros(3), np.array([0.0, 0.0, 1.0])
    for skew in (0.0, 2e-3):
        centre, axis, v = _pose_3d(g, pose, skew)
        d3 = np.empty(n)
        p3 = np.empty((n, 3))
        n3 = np.empty((n, 3))
        slice_contact_3d(centre, axis, a["x"], a["rho"], v, origin, zaxis, a["race_kind"][0], a["race_par"][0],
                         d3, p3, n3)
        if skew == 0.0:
            np.testing.assert_allclose(d3, d_m, atol=1e-9)
            np.testing.assert_allclose(n3[:, [0, 2]], nrm, atol=1e-7)
        else:
            # brute force: deepest point over 20001 angles of each slice circle
            e1 = v - np.dot(v, axis) * axis
            e1 /= np.linalg.norm(e1)
            e2 = np.cross(axis, e1)
            t = np.linspace(-0.2, 0.2, 20001)
            from sim.physics.contact import race_penetration
            for k in (0, n // 2, n - 1):
                c = centre + a["x"][k] * axis
                P = c[None, :] + a["rho"][k] * (np.cos(t)[:, None] * e1 + np.sin(t)[:, None] * e2)
                rr = np.hypot(P[:, 0], P[:, 1])
                best = max(race_penetration(r, z, a["race_kind"][0], a["race_par"][0])[0] for r, z in zip(rr, P[:, 2]))
                assert abs(d3[k] - best) < 1e-9
            # skew is a second-order effect on the penetration: |change| < phi^2 * Lwe
            assert np.all(np.abs(d3 - d_m) < skew**2 * g.Lwe)


@pytest.mark.parametrize("overrides,Fa,Fr,tilt_deg", [
    (["bearing=tsrb_reference"], 4500.0, 2000.0, 0.0),
    (["bearing=trb_32208"], 4500.0, 2000.0, 0.0),
    (["bearing=trb_32208"], 40000.0, 0.0, 0.0),
    (["bearing=tsrb_prototype"], 4500.0, 2000.0, 0.25),
    (["bearing=tsrb_reference", "solver.elasticity=independent"], 4500.0, 4000.0, 0.0),
])
def test_solver_frames_are_the_frames_of_the_returned_poses(overrides, Fa, Fr, tilt_deg):
    """The contact frames that BearingModel.solve returns (raw["frames"], from the solver's contact
    evaluations, mirrored or copied for the rollers that a symmetry class stands for) equal
    contact_frames recomputed at the returned poses and ring (MODEL.md 3): points and centres
    to 1e-12 Dpw, unit vectors to 1e-12 (round-off of cos(psi) of mirrored azimuths)."""
    from sim.physics.roller_contact import contact_frames, empty_frames
    from tests.helpers import case

    model = build_model(sim.load_config(overrides))
    g, a = model.geometry, model.geometry.arrays
    op = case(Fa, Fr, tilt=tilt_deg)
    raw = model.solve(op)
    assert raw["converged"]
    ref = empty_frames(g.Z, g.n_slices)
    contact_frames(raw["poses"], raw["ring"], np.radians(tilt_deg), g.alpha, g.Dpw, a["x"], a["rho"],
                   a["race_kind"], a["race_par"], a["rib"], *ref)
    for name in ("X", "Cen", "Xrib"):
        np.testing.assert_allclose(getattr(raw["frames"], name), getattr(ref, name), rtol=0, atol=1e-12 * g.Dpw)
    for name in ("Nrm", "Ax"):
        np.testing.assert_allclose(getattr(raw["frames"], name), getattr(ref, name), rtol=0, atol=1e-12)
