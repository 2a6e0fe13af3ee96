"""Osculation per contact point and race (issue 16 item 7, thesis 8.2) against closed forms.

Raceway arc k of a race is the circle of radius R_k = PCR (2 - kappa_k) (eq. (2.7) per point)
internally tangent to the roller's crown circle (radius PCR, centre C) at contact point p_k
(sim.geometry.Geometry._race_arrays). Its centre is c_k = C - e_k n_k, e_k = R_k - PCR, n_k the
crown's unit normal at p_k. A crown point at the angle theta from p_k (seen from C) then lies
|P - c_k| = sqrt(PCR^2 + e_k^2 + 2 PCR e_k cos(theta)) from c_k (law of cosines), so its gap to
arc k is exactly

    g_k(theta) = R_k - sqrt(PCR^2 + e_k^2 + 2 PCR e_k cos(theta))                    (A)

zero at theta = 0, with g_k'' = PCR e_k / R_k per rad^2, i.e. 1/PCR - 1/R_k per mm^2 of arc
length s = PCR theta: the curvature difference of crown and arc. The raceway is the envelope
(the intersection of the two disks), so the gap is min(g_1, g_2).
"""
import numpy as np
import pytest

import sim
from sim.api.simulation import build_model
from sim.api.bearing_model import roller_shift_relative_to_inner_ring
from sim.physics.contact import (Raceway, RingMotion, SliceContacts, contact_modulus, hertz_line_half_width,
                                 slice_contact_meridian)
from tests.helpers import case, contact_stiffness_and_difference, race_forces, roller_residuals

# kappa per race and point, all different, tighter at the small end (as the tests below need)
ASYM = {"kappa_outer_small": 0.99, "kappa_outer_large": 0.95, "kappa_inner_small": 0.97, "kappa_inner_large": 0.93}


def overrides(kappas):
    return [f"bearing.{k}={v}" for k, v in kappas.items()]


def geometry(bearing, kappas=None):
    return build_model(sim.load_config([f"bearing={bearing}", *overrides(kappas or {})])).geometry


def penetration(g, race, x, pose=(0.0, 0.0, 0.0)):
    """Penetration [mm] of the crown points at x (roller frame, mm) into raceway ``race`` (0 outer,
    1 inner), roller at ``pose``, rings at their nominal position: the slice kernel itself."""
    x = np.atleast_1d(np.asarray(x, dtype=float))
    d, nrm, pts = np.empty(len(x)), np.empty((len(x), 2)), np.empty((len(x), 2))
    a = g.arrays
    slice_contact_meridian(x, g.roller_radius(x), 1 - 2 * race, np.asarray(pose, dtype=float), g.alpha, g.Dpw,
                           Raceway(a["race_kind"][race], a["race_par"][race]), RingMotion(0.0, 0.0, 0.0),
                           SliceContacts(d, nrm, pts))
    return d


def crown_x(g, phi):
    """x [mm] of the crown point whose normal is at the angle phi [rad] from the roller's v axis."""
    return g.crown_centre[0] + g.PCR * np.sin(phi)


def crown_angle(g, x):
    return np.arcsin((x - g.crown_centre[0]) / g.PCR)


def test_arc_radii_follow_eq_2_7_per_point_and_default_to_kappa():
    """R_k = PCR (2 - kappa_k) for each race and point (exact algebra); keys left null take kappa,
    so the symmetric raceway's profile parameters are those of every per-point key set to kappa,
    bit for bit."""
    g = geometry("tsrb_reference", ASYM)
    par = g.arrays["race_par"]
    for race, side in ((0, "outer"), (1, "inner")):
        for point, end in ((0, "small"), (1, "large")):
            assert par[race, 4 + point] == g.PCR * (2.0 - ASYM[f"kappa_{side}_{end}"])
    sym = geometry("tsrb_reference")
    explicit = geometry("tsrb_reference", {k: sym.kappa for k in ASYM})
    np.testing.assert_array_equal(sym.arrays["race_par"], explicit.arrays["race_par"])
    assert np.all(sym.arrays["race_par"][:, 4] == sym.PCR_LB) and np.all(sym.arrays["race_par"][:, 5] == sym.PCR_LB)


@pytest.mark.parametrize("bearing", ["tsrb_reference", "tsrb_pinion"])
def test_unloaded_gap_is_the_closed_form_of_each_arc(bearing):
    """Nominal pose: the kernel's penetration is -min(g_1, g_2) of (A) at every crown point, zero
    at both contact points of both races, and the two arcs meet between the points. Tolerance
    1e-12 mm: round-off of coordinates of ~100 mm (1e-14 mm) through the square roots of (A) and
    of the kernel (the gap is the difference of two lengths near R_k)."""
    g = geometry(bearing, ASYM)
    x = np.linspace(-0.5 * g.Lwe, 0.5 * g.Lwe, 401)
    theta = crown_angle(g, x)
    for race in (0, 1):
        d = penetration(g, race, x)
        gaps = []
        for xk, Rk in zip(g.contact_points_x, g.arc_radii[race]):
            e = Rk - g.PCR
            gaps.append(Rk - np.sqrt(g.PCR**2 + e**2 + 2.0 * g.PCR * e * np.cos(theta - crown_angle(g, xk))))
        np.testing.assert_allclose(d, -np.minimum(*gaps), rtol=0, atol=1e-12)
        np.testing.assert_allclose(penetration(g, race, g.contact_points_x), 0.0, rtol=0, atol=1e-12)
        away = np.all(np.abs(x[:, None] - g.contact_points_x[None, :]) > 0.1, axis=1)
        assert np.all(d[away] < 0.0)
        # the arcs meet (g_1 = g_2) once near the roller, between the contact points
        switch = x[np.flatnonzero(np.diff(np.sign(gaps[0] - gaps[1])))]
        assert len(switch) == 1 and g.contact_points_x[0] < switch[0] < g.contact_points_x[1]


@pytest.mark.parametrize("race", [0, 1])
@pytest.mark.parametrize("point", [0, 1])
def test_gap_curvature_at_each_point_is_the_curvature_difference(race, point):
    """d^2 gap / ds^2 at contact point k, from the kernel by a central second difference along the
    crown (arc length s, step h = 0.2 mm), equals 1/PCR - 1/(PCR (2 - kappa_k)) of that point
    and race. Tolerance 1e-4 relative: truncation of the difference, (h/PCR)^2 / 12 times the
    fourth-to-second derivative ratio of (A) (~1e-5 here), and round-off 4e-14 mm / h^2 against a
    gap curvature of >= 1e-4 /mm (< 1e-8)."""
    g = geometry("tsrb_reference", ASYM)
    h = 0.2
    phi = crown_angle(g, g.contact_points_x[point])
    x = crown_x(g, phi + np.array([-h, 0.0, h]) / g.PCR)
    gap = -penetration(g, race, x)
    curvature = (gap[0] - 2.0 * gap[1] + gap[2]) / h**2
    kappa = g.osculations[race, point]
    expected = 1.0 / g.PCR - 1.0 / (g.PCR * (2.0 - kappa))
    assert curvature == pytest.approx(expected, rel=1e-4)


def test_tighter_small_end_osculation_widens_its_contact():
    """Small end tighter than the large end (kappa_s > kappa_l): the contact at the small-end point
    is the wider one, two closed forms:

    - rigid interference: the roller pushed into the outer raceway along the bisector of the two
      contact normals (equal approach delta at both points) overlaps the raceway over an arc
      length 2 sqrt(2 delta / c_k), c_k = 1/PCR - 1/R_k, from (A) to leading order; tolerance
      2 %: the next terms of (A) and of the roller's displacement along the profile, of
      order (s/PCR)^2 and the approach's variation over the width (about 1 % here);
    - Hertz line contact across the profile (Johnson eq. 4.43, relative radius 1/c_k): at equal
      load per unit length the half widths are in the ratio sqrt(c_l / c_s) > 1, exact algebra
      on the kernel's curvatures of the test above."""
    kappas = {"kappa_outer_small": 0.99, "kappa_outer_large": 0.95}
    g = geometry("tsrb_reference", kappas)
    c = 1.0 / g.PCR - 1.0 / g.arc_radii[0]
    assert c[0] < c[1]
    phi = crown_angle(g, g.contact_points_x)
    bisector = 0.5 * (phi[0] + phi[1])
    delta = 2e-4  # mm, approach along each contact normal: overlaps of 1.4 and 3.1 mm, apart (aP = 8.5 mm)
    # a shift t along the bisector's unit normal (x, y) approaches both points by t cos((phi_1 - phi_2)/2)
    t = delta / np.cos(0.5 * (phi[1] - phi[0]))
    # pose: (xi along the roller axis, eta along v, theta); the crown normal at angle phi is (sin(phi), cos(phi))
    pose = (t * np.sin(bisector), t * np.cos(bisector), 0.0)
    s = np.linspace(-12.0, 12.0, 24001)  # mm of crown arc length around each point (step 1 um)
    widths = []
    for k in (0, 1):
        x = crown_x(g, phi[k] + s / g.PCR)
        inside = x[(np.abs(x) < 0.5 * g.Lwe)]
        d = penetration(g, 0, inside, pose)
        # the roller moved by the shift's axial part: penetration at the roller's own x, arc length from the point
        sk = s[np.abs(x) < 0.5 * g.Lwe]
        near = np.abs(sk) < 0.5 * (phi[1] - phi[0]) * g.PCR   # this point's side of the arcs' meeting point
        loaded = sk[near & (d > 0.0)]
        widths.append(loaded.max() - loaded.min())
    expected = 2.0 * np.sqrt(2.0 * delta / c)
    np.testing.assert_allclose(widths, expected, rtol=0.02)
    assert widths[0] > widths[1]
    E_star = contact_modulus(g.E, g.nu)
    b = [hertz_line_half_width(100.0, 1.0 / ck, E_star) for ck in c]
    assert b[0] / b[1] == pytest.approx(np.sqrt(c[1] / c[0]), rel=1e-12) and b[0] > b[1]


def solved(bearing, Fa, Fr, kappas, *extra):
    model = build_model(sim.load_config([f"bearing={bearing}", *overrides(kappas), *extra]))
    op = case(Fa, Fr, speed=0.0)
    raw = model.solve(op)
    assert raw["converged"]
    return model, op, raw


@pytest.mark.parametrize("bearing,Fa,Fr", [("tsrb_reference", 4500.0, 2000.0), ("tsrb_pinion", 35000.0, 5000.0)])
def test_force_balance_with_asymmetric_osculation(bearing, Fa, Fr):
    """Inner ring and every loaded roller in balance to the solver tolerance with four different
    osculations (tolerances of tests/balance/test_equilibrium.py: 1e-8 of the load, the ring
    force recomputed from the slice loads and the kernel's normals, which follow the local arc)."""
    model, op, raw = solved(bearing, Fa, Fr, ASYM)
    Fx, Fz = race_forces(model, raw, 1)
    np.testing.assert_allclose([Fx + Fr, Fz + Fa], 0.0, atol=1e-8 * max(Fa, Fr))
    np.testing.assert_allclose(raw["residual"], 0.0, atol=1e-8 * max(Fa, Fr))
    assert np.all(roller_residuals(model, raw, op) < 1e-8)


def test_symmetric_per_point_keys_reproduce_the_symmetric_solution_exactly():
    """Every per-point osculation set to kappa gives the symmetric solution bit for bit (the same
    arc radii, the same floating-point operations)."""
    _, _, sym = solved("tsrb_pinion", 35000.0, 5000.0, {})
    _, _, same = solved("tsrb_pinion", 35000.0, 5000.0, {k: 0.95 for k in ASYM})  # tsrb_pinion's kappa
    for key in ("ring", "poses", "line_load", "Q", "pressure"):
        np.testing.assert_array_equal(sym[key], same[key])


@pytest.mark.parametrize("bearing,Fa", [("tsrb_reference", 4500.0), ("tsrb_pinion", 35000.0)])
def test_swapping_the_point_osculations(bearing, Fa):
    """Mirror: the small- and large-end osculations swapped (0.99 / 0.93 against 0.93 / 0.99, both
    races), pure axial load, no rib, friction or body forces.

    - The load centroid does not follow the osculation: force balance along the roller axis puts
      it at x* = PCR sin(gamma) for any raceway (MODEL.md 4: a crown point at x pushes along the
      axis in proportion to x - PCR sin(gamma)). Both stay within 1.5 % of x* (the neglected
      terms, roller shift and tilt and slice discretisation: 0.1-1 % here) and within 1 % of x*
      of each other.
    - What moves is the roller: the large-end point carries most of the load (x* lies nearer to
      it), and the approach needed there for a given load falls with tighter osculation, so the
      roller slides less towards the large end when the large end is the tighter one: its axial
      displacement is smaller than with the osculations swapped.
    """
    tight_small = {"kappa_outer_small": 0.99, "kappa_inner_small": 0.99,
                   "kappa_outer_large": 0.93, "kappa_inner_large": 0.93}
    tight_large = {"kappa_outer_small": 0.93, "kappa_inner_small": 0.93,
                   "kappa_outer_large": 0.99, "kappa_inner_large": 0.99}
    out = {}
    for name, kappas in (("tight_small", tight_small), ("tight_large", tight_large)):
        model, _, raw = solved(bearing, Fa, 0.0, kappas, "solver.centrifugal=false", "solver.gyroscopic=false")
        g = model.geometry
        q = raw["line_load"][0]
        centroid = np.sum(q * g.arrays["x"][None, :]) / np.sum(q)
        xi = roller_shift_relative_to_inner_ring(g, raw["poses"][:, 0], raw["ring"], 0.0)[0]
        out[name] = centroid, xi
        assert centroid == pytest.approx(g.load_centroid_x, rel=0.015)
    x_star = g.load_centroid_x
    assert abs(out["tight_small"][0] - out["tight_large"][0]) < 0.01 * x_star
    assert 0.0 < out["tight_large"][1] < out["tight_small"][1]


def test_roller_stiffness_uses_the_radius_of_the_bounding_arc():
    """The exact tangent stiffness K = -df/dy of one roller (sim.physics.roller_contact) equals a
    central finite difference of its generalised forces with four different osculations: its
    geometric part takes the radius of the arc that bounds each slice, PCR (2 - kappa_k), not one
    PCR_LB. Independent slices (a smooth load law); roller of the solved pinion at 35 kN, 5 kN
    radial. Chart: a, b along the roller's current axes u', v', theta about its centre (pose
    (xi, eta, theta) with xi, eta along the untilted u, v), ring delta_a, delta_r. Step 1e-7 mm /
    rad. Tolerance 1e-4 of each column's largest entry: the difference's truncation error is
    (h / d)^2 of a slice at penetration d, largest at the rim of the loaded zone where d^(10/9) is
    least smooth (1e-5 of the tangential column a, measured), and round-off eps f / h ~ 1e-9; one
    PCR_LB for both arcs instead (radii 6 % apart) errs by 3e-3 of column a, where the material
    part nearly vanishes (measured with that mutation)."""
    model, _, raw = solved("tsrb_pinion", 35000.0, 5000.0, {"kappa_outer_small": 0.99, "kappa_outer_large": 0.93,
                                                         "kappa_inner_small": 0.93, "kappa_inner_large": 0.99},
                           "solver.elasticity=independent")
    K, J = contact_stiffness_and_difference(model, raw, 0, 1.0)
    scale = np.abs(J).max(axis=0)
    error = np.abs(K - J).max(axis=0) / scale
    assert np.all(error < 1e-4), error


@pytest.mark.parametrize("value", [1.0, 0.0, -0.5, 1.2])
def test_per_point_osculation_outside_its_range_is_refused_before_anything_runs(value):
    """A per-point osculation outside (0, 1) is refused by the schema, naming key, value and range,
    through the config (ConfigError) and through Geometry.from_config (GeometryError). No rule that
    combines keys is needed: any four values in (0, 1) give raceway arcs that contain the crown
    (R_k >= PCR, internal tangency) and touch it at exactly its two contact points (tests above)."""
    from omegaconf import OmegaConf

    from sim.errors import ConfigError, GeometryError
    from sim.geometry import Geometry

    with pytest.raises(ConfigError) as err:
        sim.simulate(sim.load_config(["bearing=tsrb_reference", f"bearing.kappa_inner_large={value}"]))
    assert f"bearing.kappa_inner_large = {value!r} is outside the allowed range: a number in (0, 1)" in str(err.value)
    cfg = sim.load_config(["bearing=tsrb_reference"])
    bearing = dict(OmegaConf.to_container(cfg.bearing, resolve=True), kappa_inner_large=value)
    with pytest.raises(GeometryError, match=r"bearing.kappa_inner_large = .* is outside the allowed range"):
        Geometry.from_config(bearing, OmegaConf.to_container(cfg.material, resolve=True), 10)
