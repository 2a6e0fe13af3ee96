"""Slice contact kernels against closed forms (MODEL.md 3)."""
import numpy as np
import pytest

import sim
from sim.physics.contact import Raceway, RingMotion, SliceContacts, slice_contact_3d, slice_contact_meridian
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
        raceway = Raceway(a["race_kind"][s], a["race_par"][s])
        slice_contact_meridian(a["x"], a["rho"], side, np.zeros(3), g.alpha, g.Dpw, raceway, RingMotion(0.0, 0.0, 0.0),
                               SliceContacts(d, nrm, pts))
        assert d.max() <= 1e-9
        if bearing == "trb_32208":
            from sim.geometry import log_crown_drop
            np.testing.assert_allclose(d, -log_crown_drop(a["x"], g.Dwe, g.Lwe, g.crown_coefficient), atol=1e-9)
        # a radial push by e along v gives penetration e * (n . v) at every slice, closed form
        e = 1e-3
        d2 = np.empty(n)
        slice_contact_meridian(a["x"], a["rho"], side, np.array([0.0, side * e, 0.0]), g.alpha, g.Dpw, raceway,
                               RingMotion(0.0, 0.0, 0.0), SliceContacts(d2, nrm, pts))
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
    raceway = Raceway(a["race_kind"][0], a["race_par"][0])
    slice_contact_meridian(a["x"], a["rho"], 1, pose, g.alpha, g.Dpw, raceway, RingMotion(0.0, 0.0, 0.0),
                           SliceContacts(d_m, nrm, pts))
    origin, zaxis = np.zeros(3), np.array([0.0, 0.0, 1.0])
    for skew in (0.0, 2e-3):
        centre, axis, v = _pose_3d(g, pose, skew)
        d3 = np.empty(n)
        p3 = np.empty((n, 3))
        n3 = np.empty((n, 3))
        slice_contact_3d(centre, axis, a["x"], a["rho"], v, origin, zaxis, raceway, SliceContacts(d3, n3, p3))
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


def _frames_closed_form(g, a, poses, ring, tilt):
    """Contact frames of every roller in closed form (MODEL.md 3), numpy, independent of the
    kernels: roller centre c = (Dpw/2 + xi sin(alpha) + eta cos(alpha), -xi cos(alpha) + eta
    sin(alpha)); axes u' = u cos(theta) + v sin(theta), v' = -u sin(theta) + v cos(theta) with
    u = (sin(alpha), -cos(alpha)), v = (cos(alpha), sin(alpha)); slice point on the roller
    X = c + x u' +- rho v' (+ towards the outer raceway); normal into the ring: the cone's normal
    (RACE_LINE) or the unit vector from the centre of the arc the point penetrates most
    (RACE_LENS), in ring coordinates (the inner ring shifted by (delta_r cos(psi), delta_a) and
    turned by tilt cos(psi)); roller-end / rib point c + (rib0 + rib2 rib3) u' + (rib1 + rib2 rib4) v'
    (the point of the end's touching circle along the nominal rib normal, geometry arrays ``rib``;
    zeros: the centre)."""
    from sim.geometry import RACE_LINE

    Z, n = g.Z, g.n_slices
    X, Nrm = np.empty((Z, 2, n, 2)), np.empty((Z, 2, n, 2))
    Cen, Ax, Xrib = np.empty((Z, 2)), np.empty((Z, 4)), np.empty((Z, 2))
    sa, ca = np.sin(g.alpha), np.cos(g.alpha)
    u, v = np.array([sa, -ca]), np.array([ca, sa])
    rib = a["rib"]
    for j in range(Z):
        psi = 2.0 * np.pi * j / Z
        xi, eta, th = poses[j]
        c = np.array([0.5 * g.Dpw + xi * sa + eta * ca, -xi * ca + eta * sa])
        up, vp = u * np.cos(th) + v * np.sin(th), -u * np.sin(th) + v * np.cos(th)
        Cen[j], Ax[j] = c, np.concatenate([up, vp])
        Xrib[j] = c + (rib[0] + rib[2] * rib[3]) * up + (rib[1] + rib[2] * rib[4]) * vp
        for s, side in ((0, 1.0), (1, -1.0)):
            pts = c + np.outer(a["x"], up) + side * np.outer(a["rho"], vp)       # (n, 2)
            X[j, s] = pts
            shift = np.array([ring[1] * np.cos(psi), ring[0]]) if s == 1 else np.zeros(2)
            phi = tilt * np.cos(psi) if s == 1 else 0.0
            rot = np.array([[np.cos(phi), -np.sin(phi)], [np.sin(phi), np.cos(phi)]])   # ring -> world
            local = (pts - shift) @ rot                                            # world -> ring: Rot(-phi)
            par = a["race_par"][s]
            if a["race_kind"][s] == RACE_LINE:
                nrm = np.tile(par[2:4], (n, 1))
            else:
                arcs = [local - par[2 * k:2 * k + 2] for k in range(2)]
                dist = [np.linalg.norm(d, axis=1) for d in arcs]
                deeper = (dist[1] - par[4] > dist[0] - par[4])[:, None]
                nrm = np.where(deeper, arcs[1] / dist[1][:, None], arcs[0] / dist[0][:, None])
            Nrm[j, s] = nrm @ rot.T
    return {"X": X, "Nrm": Nrm, "Cen": Cen, "Ax": Ax, "Xrib": Xrib}


@pytest.mark.parametrize("overrides,Fa,Fr,tilt_deg", [
    (["bearing=tsrb_reference"], 4500.0, 2000.0, 0.0),
    (["bearing=trb_32208"], 4500.0, 2000.0, 0.0),
    (["bearing=trb_32208"], 40000.0, 0.0, 0.0),
    (["bearing=trb_32208", "bearing.roller_end=torus"], 4500.0, 2000.0, 0.0),
    (["bearing=tsrb_prototype"], 4500.0, 2000.0, 0.25),
    (["bearing=tsrb_reference", "solver.elasticity=independent"], 4500.0, 4000.0, 0.0),
])
def test_solver_frames_are_the_frames_of_the_returned_poses(overrides, Fa, Fr, tilt_deg):
    """The contact frames that BearingModel.solve returns (raw["frames"], from the solver's contact
    evaluations, mirrored or copied for the rollers that a symmetry class stands for) equal the
    closed-form frames at the returned poses and ring (:func:`_frames_closed_form`, MODEL.md 3):
    points and centres to 1e-12 Dpw, unit vectors to 1e-12 (round-off of cos(psi) of mirrored
    azimuths and of the rotations)."""
    from tests.helpers import case

    model = build_model(sim.load_config(overrides))
    g, a = model.geometry, model.geometry.arrays
    op = case(Fa, Fr, tilt=tilt_deg)
    raw = model.solve(op)
    assert raw["converged"]
    ref = _frames_closed_form(g, a, raw["poses"], raw["ring"], np.radians(tilt_deg))
    for name in ("X", "Cen", "Xrib"):
        np.testing.assert_allclose(getattr(raw["frames"], name), ref[name], rtol=0, atol=1e-12 * g.Dpw)
    for name in ("Nrm", "Ax"):
        np.testing.assert_allclose(getattr(raw["frames"], name), ref[name], rtol=0, atol=1e-12)
