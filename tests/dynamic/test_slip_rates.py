"""The rates of the roller in the slip of every slice (issue 18, "full 2-D slip vector in each slice";
sim.physics.friction, module docstring "Rates"): rigid-body kinematics v = v_c + Omega x (X - c)
of the roller's skew rate, tilt rate and centre velocity, and the inner ring's translation, against
closed forms and finite rigid rotations, and the virtual-power identity of the tractions' forces
and moments with the loss powers. Units: N, mm, s, rad.
"""
import numpy as np
import pytest

import sim
from sim.api import dynamic_model as dm
from sim.api.cases import operating_points
from sim.api.simulation import build_models, resolved
from sim.physics import friction as F

CASES = {
    "trb_32208": ["bearing=trb_32208", "load.Fa=4500", "load.Fr=2000", "load.speed=2000"],
    "tsrb_reference": ["bearing=tsrb_reference", "load.Fa=4500", "load.Fr=2000", "load.speed=2000"],
}


@pytest.fixture(scope="module", params=list(CASES))
def case(request):
    """The FrictionCase of a dynamic run at its quasi-static start (frames, loads, film)."""
    cfg = sim.load_config(["solver=dynamic", "solver.dynamic.start=quasi_static"] + CASES[request.param])
    plain = resolved(cfg)
    model, friction = build_models(cfg, plain)
    op = operating_points(plain["load"])[0]
    return dm.prepare(model, friction, op, plain["solver"]["dynamic"]).problem.case


def loaded_slices(case, j=0):
    """(s, k, dr, dz, ar, az) of the loaded slices of roller j: contact point from the centre [mm],
    in-plane tangent a = n x e_t."""
    X, Nrm, Cen, _, _ = case.frames
    out = []
    for s in range(2):
        for k in range(X.shape[2]):
            if case.bearing.q[j, s, k] > 0.0:
                dr, dz = X[j, s, k] - Cen[j]
                out.append((s, k, dr, dz, -Nrm[j, s, k, 1], Nrm[j, s, k, 0]))
    assert len(out) > 4
    return out


def rotate(p, axis, angle):
    """p (3,) turned by ``angle`` about the unit ``axis`` through the origin (Rodrigues)."""
    return (p * np.cos(angle) + np.cross(axis, p) * np.sin(angle)
            + axis * np.dot(axis, p) * (1.0 - np.cos(angle)))


def test_an_axially_translating_roller_without_spin_slips_laterally_by_its_speed(case):
    """Closed form: the roller's centre moving at v along its axis u' (no spin, no rotation) moves
    every point of it at v u'; against a ring at rest that is the slip, along e_t 0 and along the
    surface tangent a exactly v u'.a, i.e. v where the generatrix is parallel to the axis (the
    rest, v u'.n, is squeeze). rtol 1e-15: one rounding of a product."""
    ur, uz = case.frames.Ax[0, :2]
    v = 7.5                                                            # mm/s
    rates = F.NO_RATES._replace(vc_r=v * ur, vc_z=v * uz)
    for s, k, dr, dz, ar, az in loaded_slices(case):
        s_t, s_a = F.rate_slip(rates, s == 1, dr, dz, ar, az, ur, uz)
        assert s_t == 0.0
        assert s_a == pytest.approx(v * (ur * ar + uz * az), rel=1e-15, abs=1e-15)
        # the same point on a generatrix parallel to the axis (a = u'): exactly v
        assert F.rate_slip(rates, s == 1, dr, dz, ur, uz, ur, uz)[1] == pytest.approx(v, rel=1e-15)


def test_a_translating_roller_is_resisted_by_lateral_traction_and_dissipates_its_power(case):
    """The kernel at rest (no spin, rings and orbit still, no skew) with the centre translating at v
    along u': no tangential force, the lateral tractions push the roller against v (F_u v < 0), and
    their loss power (the lateral-slip sliding power, EV_PSKEW, plus the rib's) is exactly -F_u v
    (virtual power, 1e-12: round-off of the slice sums)."""
    ur, uz = case.frames.Ax[0, :2]
    ev = np.zeros(F.NEV)
    for v in (3.0, -40.0):
        F.roller_traction(0, 0.0, 0.0, F.NO_RATES._replace(vc_r=v * ur, vc_z=v * uz), 0.0, 0.0, case, ev)
        assert ev[F.EV_FT] == 0.0
        assert ev[F.EV_FU] * v < 0.0
        assert ev[F.EV_PSKEW] + ev[F.EV_RIB] == pytest.approx(-ev[F.EV_FU] * v, rel=1e-12)


@pytest.mark.parametrize("which", ["tilt", "skew"])
def test_rate_slip_is_the_finite_rigid_rotation(case, which):
    """A tilt rate omega_w (about w'' = -e_t) or a skew rate psi' (about v') through the roller
    centre, against the displacement of the slice's contact point under the finite rotation by
    +-h about that axis (central difference, 3-D, Rodrigues), projected on e_t and a: agreement
    to 1e-8 relative (the difference's error is O(h^2) = 1e-12 of the lever). The tilt moves each
    contact point in the meridian plane by omega_w (dr e_z - dz e_r): its slip along a is affine
    in the contact point (checked exactly by a least-squares fit over the slices)."""
    ur, uz, vr, vz = case.frames.Ax[0]
    w = 2.5                                                            # rad/s
    axis = np.array([0.0, -1.0, 0.0]) if which == "tilt" else np.array([vr, 0.0, vz])
    rates = F.NO_RATES._replace(omega_w=w) if which == "tilt" else F.NO_RATES._replace(psi_dot=w)
    h = 1e-6
    rows = []
    for s, k, dr, dz, ar, az in loaded_slices(case):
        p = np.array([dr, 0.0, dz])
        vel = w * (rotate(p, axis, h) - rotate(p, axis, -h)) / (2.0 * h)
        s_t, s_a = F.rate_slip(rates, s == 1, dr, dz, ar, az, ur, uz)
        scale = w * np.hypot(dr, dz)
        assert s_t == pytest.approx(vel[1], abs=1e-8 * scale)
        assert s_a == pytest.approx(vel[0] * ar + vel[2] * az, abs=1e-8 * scale)
        rows.append((dr * az, dz * ar, s_a))
    if which == "tilt":
        A = np.array(rows)
        coef = np.linalg.lstsq(A[:, :2], A[:, 2], rcond=None)[0]
        assert coef == pytest.approx([w, -w], rel=1e-12)


def test_the_tractions_power_on_the_rates_is_the_loss(case):
    """Virtual power of the kernel: at rest but for arbitrary rates (skew and tilt rate, centre and
    inner-ring velocity; no spin, rings and orbit still, no skew), the power of the kernel's forces
    and moments on the roller (F_u, F_v at the centre, moments about v' and w'') and of its reaction
    on the inner ring (EV_RING_*) on their velocities is minus the sum of the loss powers (sliding,
    drilling, rolling, hysteresis, rib). 1e-10 relative: round-off of the slice and width sums. The
    TRB 32208's roller 0 bears on its rib (93 N), whose in-plane slip joins the balance."""
    ur, uz, vr, vz = case.frames.Ax[0]
    rng = np.random.default_rng(18)
    ev = np.zeros(F.NEV)
    for _ in range(3):
        r = F.RollerRates(*(rng.standard_normal(7) * np.array([3.0, 3.0, 20.0, 20.0, 20.0, 20.0, 20.0])))
        F.roller_traction(0, 0.0, 0.0, r, 0.0, 0.0, case, ev)
        P_roller = (ev[F.EV_FU] * (ur * r.vc_r + uz * r.vc_z) + ev[F.EV_FV] * (vr * r.vc_r + vz * r.vc_z)
                    + ev[F.EV_MS] * r.psi_dot + ev[F.EV_MW] * r.omega_w)
        P_ring = ev[F.EV_RING_R] * r.vi_r + ev[F.EV_RING_T] * r.vi_t + ev[F.EV_RING_Z] * r.vi_z
        loss = sum(ev[F.EV_P0 + i] for i in range(F.NC))
        assert loss > 0.0
        if case.bearing.Qrib[0] > 0.0:          # the TRB: its rib's 2-D slip is in the balance too
            assert ev[F.EV_RIB] > 0.0
        assert P_roller + P_ring == pytest.approx(-loss, rel=1e-10)

