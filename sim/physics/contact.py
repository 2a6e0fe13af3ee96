"""Roller-raceway and roller-end/rib contact geometry: penetration, normal, contact point per slice.

The raceways are surfaces of revolution about the ring axis, so the signed distance of a
point to a raceway is its signed distance, in the point's own meridian plane, to the
raceway profile (exact for surfaces of revolution). The roller is cut into slices normal to
its axis (thesis 5.2.1); per slice the contact point is the point of the slice circle that
penetrates the raceway deepest (thesis (5.11)-(5.14) find it by a ray-torus intersection,
(5.5)-(5.10); MODEL.md 3 allows any exact method):

- :func:`slice_contact_meridian`: roller axis in the meridian plane (shift along the axis,
  radial shift, tilt): the deepest point lies in the meridian plane; closed form.
- :func:`slice_contact_3d`: the full pose including skew: Newton on the angle around the
  slice circle, started from the meridian point; reduces to the former without skew.

Kernel units: mm, rad. Profiles are given as (kind, params) arrays built by
:class:`sim.geometry.Geometry` (``RACE_LINE``: point and unit normal into the ring;
``RACE_LENS``: two arc centres and their radii PCR (2 - kappa_k), eq. (2.7) per contact point
(thesis 8.2; equal, PCR_LB, for the symmetric osculation); the cavity is the intersection of the
two disks, so the penetration is the larger of the two arcs' penetrations).
"""
from collections import namedtuple

import numpy as np

from sim._math.jit import internal_kernel, kernel
from sim.geometry import RACE_LENS, RACE_LINE  # noqa: F401  (profile kinds, defined once)

# Penetration [mm] of a contact that does not exist: below any real penetration (the start of a
# running maximum; the rib row of a roller without a rib, which then never bounds a Newton step).
NO_CONTACT = -np.inf

# Arguments of the slice contact kernels (numba-supported named tuples):
# Raceway: one raceway profile in ring coordinates, kind (RACE_LINE or RACE_LENS) and par (6,) (module
# docstring; sim.geometry.Geometry builds them);
# RingMotion: rigid displacement of a ring in the roller's meridian plane, translation dr, dz [mm] and
# rotation phi [rad] (world = Rot(phi) ring + translation; zeros for the fixed outer ring);
# SliceContacts: what the kernels write per slice, d (N,) penetration [mm], n (N, 2 or 3) unit contact
# normal into the ring and q (N, 2 or 3) contact point on the roller surface [mm].
Raceway = namedtuple("Raceway", ["kind", "par"])
RingMotion = namedtuple("RingMotion", ["dr", "dz", "phi"])
SliceContacts = namedtuple("SliceContacts", ["d", "n", "q"])

# Newton on the angle around a slice circle (slice_contact_3d), numerical choices:
# ANGLE_FD_STEP [rad]: step of the central differences; ~eps^(1/4) balances truncation and
# round-off of a second difference (Press et al. 2007, Numerical Recipes, 5.7);
# ANGLE_MAX_ITER: iteration cap (Newton from the meridian start converges in a few);
# ANGLE_MAX_STEP [rad]: largest step, keeps a step taken far from the maximum near the start;
# ANGLE_GRADIENT_STEP [rad]: fixed uphill step where the penetration is not locally concave;
# ANGLE_TOL [rad]: converged when a step is below it (contact point to ~1e-12 rho).
ANGLE_FD_STEP = 1e-4
ANGLE_MAX_ITER = 30
ANGLE_MAX_STEP = 0.2
ANGLE_GRADIENT_STEP = 1e-2
ANGLE_TOL = 1e-12


@kernel
def race_penetration(qr, qz, kind, par):
    """Signed penetration of a point into a raceway profile, in ring coordinates.

    Parameters
    ----------
    qr, qz : float
        Point in the meridian plane [mm].
    kind : int
        RACE_LINE or RACE_LENS.
    par : ndarray (6,)
        Profile parameters [mm, 1] (see module docstring).

    Returns
    -------
    d : float
        Penetration [mm], > 0 inside the ring material (the rigid-body penetration of
        thesis (5.12); the negative gap otherwise).
    nr, nz : float
        Unit normal of the raceway at the nearest profile point, pointing into the ring.
    """
    if kind == RACE_LINE:
        return (qr - par[0]) * par[2] + (qz - par[1]) * par[3], par[2], par[3]
    best, nr, nz, _ = lens_penetration(qr, qz, par)
    return best, nr, nz


@internal_kernel
def lens_penetration(qr, qz, par):
    """Penetration of a point into a RACE_LENS profile and the arc that bounds it there.

    Parameters
    ----------
    qr, qz : float
        Point in the meridian plane, ring coordinates [mm].
    par : ndarray (6,)
        (r1, z1, r2, z2, R1, R2): arc centres and radii [mm] (sim.geometry.Geometry._race_arrays).

    Returns
    -------
    d, nr, nz : float
        As :func:`race_penetration`: the larger of the arc penetrations |q - c_k| - R_k [mm] and
        the unit normal (q - c_k)/|q - c_k| of that arc.
    radius : float
        R_k of that arc [mm]: the profile's radius of curvature at the nearest profile point.
    """
    best = NO_CONTACT
    nr = 0.0
    nz = 0.0
    radius = par[4]
    for k in range(2):
        dr = qr - par[2 * k]
        dz = qz - par[2 * k + 1]
        dist = np.sqrt(dr * dr + dz * dz)
        d = dist - par[4 + k]
        if d > best:
            best = d
            nr = dr / dist
            nz = dz / dist
            radius = par[4 + k]
    return best, nr, nz, radius


@internal_kernel
def to_ring(qr, qz, ring_dr, ring_dz, ring_phi):
    """A meridian point in world (r, z) -> the ring's coordinates [mm]: Rot(-phi) (q - translation),
    the ring displaced by (ring_dr, ring_dz) [mm] and turned by ring_phi [rad] (world = Rot(phi) ring
    + translation)."""
    return to_ring_turned(qr, qz, ring_dr, ring_dz, np.cos(ring_phi), np.sin(ring_phi))


@internal_kernel
def to_ring_turned(qr, qz, ring_dr, ring_dz, cp, sp):
    """:func:`to_ring` with the cosine and sine of ring_phi given (a direction: ring_dr = ring_dz = 0)."""
    tr = qr - ring_dr
    tz = qz - ring_dz
    return cp * tr + sp * tz, -sp * tr + cp * tz


@kernel
def roller_axes(alpha, theta):
    """Unit vectors (u', v') of a roller tilted by theta in its meridian plane, in (r, z).

    Parameters
    ----------
    alpha : float
        Roller-axis angle [rad].
    theta : float
        Tilt in the meridian plane [rad], positive turning u towards v.

    Returns
    -------
    ur, uz, vr, vz : float
        u' = u cos(theta) + v sin(theta), v' = -u sin(theta) + v cos(theta), with
        u = (sin(alpha), -cos(alpha)), v = (cos(alpha), sin(alpha)) (sim.geometry).
    """
    sa = np.sin(alpha)
    ca = np.cos(alpha)
    ct = np.cos(theta)
    st = np.sin(theta)
    ur = sa * ct + ca * st
    uz = -ca * ct + sa * st
    vr = -sa * st + ca * ct
    vz = ca * st + sa * ct
    return ur, uz, vr, vz


@kernel
def slice_contact_meridian(x, rho, side, pose, alpha, Dpw, raceway, ring, out):
    """Penetration, normal and contact point of every slice of one roller against one raceway.

    Parameters
    ----------
    x, rho : ndarray (N,)
        Slice centres along the roller axis from mid-length and roller radius there [mm].
    side : int
        +1 outer raceway (top generatrix), -1 inner raceway (bottom generatrix).
    pose : ndarray (3,)
        Roller shift along its axis xi [mm], radial shift eta along v [mm], tilt theta [rad].
    alpha, Dpw : float
        Roller-axis angle [rad], pitch diameter [mm].
    raceway : Raceway
        Raceway profile in ring coordinates (module docstring).
    ring : RingMotion
        Rigid displacement of the ring in this meridian plane: translation dr, dz [mm] and
        rotation phi [rad] (world = Rot(phi) ring + translation).
    out : SliceContacts (written)
        d (N,): penetrations [mm]; n (N, 2): unit contact normals into the ring, world (r, z);
        q (N, 2): contact points on the roller surface, world (r, z) [mm], thesis (5.11).
    """
    kind, par = raceway
    ring_dr, ring_dz, ring_phi = ring
    d_out, n_out, q_out = out
    ur, uz, vr, vz = roller_axes(alpha, pose[2])
    sa = np.sin(alpha)
    ca = np.cos(alpha)
    cr = 0.5 * Dpw + pose[0] * sa + pose[1] * ca
    cz = -pose[0] * ca + pose[1] * sa
    cp = np.cos(ring_phi)
    sp = np.sin(ring_phi)
    for k in range(x.shape[0]):
        y = side * rho[k]
        qr = cr + x[k] * ur + y * vr
        qz = cz + x[k] * uz + y * vz
        lr, lz = to_ring(qr, qz, ring_dr, ring_dz, ring_phi)
        d, nr, nz = race_penetration(lr, lz, kind, par)
        d_out[k] = d
        n_out[k, 0] = cp * nr - sp * nz
        n_out[k, 1] = sp * nr + cp * nz
        q_out[k, 0] = qr
        q_out[k, 1] = qz


@internal_kernel
def _surface_distance_3d(px, py, pz, ring_origin, ring_axis, raceway):
    """Penetration of a 3-D point (px, py, pz) into a raceway of revolution about the unit axis
    ``ring_axis`` through ``ring_origin``, and the normal's (r, z) components in ring coordinates."""
    ax, ay, az = ring_axis[0], ring_axis[1], ring_axis[2]
    dx = px - ring_origin[0]
    dy = py - ring_origin[1]
    dz = pz - ring_origin[2]
    zz = dx * ax + dy * ay + dz * az
    rx = dx - zz * ax
    ry = dy - zz * ay
    rz = dz - zz * az
    rr = np.sqrt(rx * rx + ry * ry + rz * rz)
    return race_penetration(rr, zz, raceway[0], raceway[1])


@kernel
def slice_contact_3d(center, axis, x, rho, side_dir, ring_origin, ring_axis, raceway, out):
    """Slice contact for a roller in any pose (shift, radial, tilt, skew), 3-D.

    For each slice, the point of the slice circle (centre c + x a, radius rho, in the plane
    normal to the roller axis a) that penetrates the raceway deepest is found by Newton
    iteration on its angle, started from ``side_dir`` (the direction from the roller axis
    towards the raceway, e.g. the meridian direction). This is the exact slice-model contact
    of thesis 5.2.2 for a raceway of revolution.

    Parameters
    ----------
    center : ndarray (3,)
        Roller centre (mid-length on its axis) [mm], bearing frame (x, y, z).
    axis : ndarray (3,)
        Unit roller axis towards the large end.
    x, rho : ndarray (N,)
        Slice positions along the axis from the centre and slice radii [mm].
    side_dir : ndarray (3,)
        Start direction, roughly towards the raceway, normal to ``axis`` (normalised here).
    ring_origin, ring_axis : ndarray (3,)
        A point on the ring axis and its unit direction (the ring's own z) [mm, 1].
    raceway : Raceway
        Raceway profile in the ring's (r, z) coordinates.
    out : SliceContacts (written)
        d (N,): penetration [mm]; n (N, 3): unit normal into the ring; q (N, 3): contact point
        on the roller [mm].
    """
    d_out, n_out, p_out = out
    # orthonormal basis (e1, e2) of the slice plane, e1 along side_dir
    s = side_dir[0] * axis[0] + side_dir[1] * axis[1] + side_dir[2] * axis[2]
    e1x = side_dir[0] - s * axis[0]
    e1y = side_dir[1] - s * axis[1]
    e1z = side_dir[2] - s * axis[2]
    n1 = np.sqrt(e1x * e1x + e1y * e1y + e1z * e1z)
    e1x /= n1
    e1y /= n1
    e1z /= n1
    e2x = axis[1] * e1z - axis[2] * e1y
    e2y = axis[2] * e1x - axis[0] * e1z
    e2z = axis[0] * e1y - axis[1] * e1x
    e1 = (e1x, e1y, e1z)
    e2 = (e2x, e2y, e2z)
    h = ANGLE_FD_STEP
    for k in range(x.shape[0]):
        bx = center[0] + x[k] * axis[0]
        by = center[1] + x[k] * axis[1]
        bz = center[2] + x[k] * axis[2]
        base = (bx, by, bz)
        t = 0.0
        for it in range(ANGLE_MAX_ITER):
            fm = _pen_on_circle(t - h, base, rho[k], e1, e2, ring_origin, ring_axis, raceway)
            f0 = _pen_on_circle(t, base, rho[k], e1, e2, ring_origin, ring_axis, raceway)
            fp = _pen_on_circle(t + h, base, rho[k], e1, e2, ring_origin, ring_axis, raceway)
            g1 = (fp - fm) / (2.0 * h)
            g2 = (fp - 2.0 * f0 + fm) / (h * h)
            if g2 >= 0.0:  # not a maximum locally: gradient step
                step = ANGLE_GRADIENT_STEP * np.sign(g1)
            else:
                step = -g1 / g2
            if step > ANGLE_MAX_STEP:
                step = ANGLE_MAX_STEP
            elif step < -ANGLE_MAX_STEP:
                step = -ANGLE_MAX_STEP
            t += step
            if abs(step) < ANGLE_TOL:
                break
        c = np.cos(t)
        sn = np.sin(t)
        px = bx + rho[k] * (c * e1x + sn * e2x)
        py = by + rho[k] * (c * e1y + sn * e2y)
        pz = bz + rho[k] * (c * e1z + sn * e2z)
        d, nr, nz = _surface_distance_3d(px, py, pz, ring_origin, ring_axis, raceway)
        # normal back to 3-D: radial unit of the point's meridian plane and the ring axis
        dx = px - ring_origin[0]
        dy = py - ring_origin[1]
        dz = pz - ring_origin[2]
        zz = dx * ring_axis[0] + dy * ring_axis[1] + dz * ring_axis[2]
        rx = dx - zz * ring_axis[0]
        ry = dy - zz * ring_axis[1]
        rz = dz - zz * ring_axis[2]
        rr = np.sqrt(rx * rx + ry * ry + rz * rz)
        d_out[k] = d
        p_out[k, 0] = px
        p_out[k, 1] = py
        p_out[k, 2] = pz
        n_out[k, 0] = nr * rx / rr + nz * ring_axis[0]
        n_out[k, 1] = nr * ry / rr + nz * ring_axis[1]
        n_out[k, 2] = nr * rz / rr + nz * ring_axis[2]


@internal_kernel
def _pen_on_circle(t, base, rho, e1, e2, ring_origin, ring_axis, raceway):
    """Penetration [mm] of the point at angle t [rad] on the slice circle base + rho (cos t e1 +
    sin t e2) (base, e1, e2: 3-tuples, mm and unit vectors) into the raceway."""
    c = np.cos(t)
    s = np.sin(t)
    px = base[0] + rho * (c * e1[0] + s * e2[0])
    py = base[1] + rho * (c * e1[1] + s * e2[1])
    pz = base[2] + rho * (c * e1[2] + s * e2[2])
    d, nr, nz = _surface_distance_3d(px, py, pz, ring_origin, ring_axis, raceway)
    return d


@kernel
def hertz_line_half_width(line_load, R, E_star):
    """Hertz line contact semi-width.

    Parameters
    ----------
    line_load : float
        Load per unit length [N/mm].
    R : float
        Radius of relative curvature in the rolling direction [mm].
    E_star : float
        Contact modulus, 1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2 [N/mm^2].

    Returns
    -------
    float
        b [mm] = sqrt(4 w R / (pi E*)) (Johnson, Contact Mechanics, eq. 4.43).
    """
    return np.sqrt(4.0 * line_load * R / (np.pi * E_star))


@kernel
def hertz_line_pressure(line_load, R, E_star):
    """Hertz line contact maximum pressure.

    Parameters
    ----------
    line_load : float
        Load per unit length [N/mm].
    R : float
        Radius of relative curvature [mm].
    E_star : float
        Contact modulus [N/mm^2].

    Returns
    -------
    float
        p0 [MPa] = sqrt(w E* / (pi R)) (Johnson eq. 4.45).
    """
    return np.sqrt(line_load * E_star / (np.pi * R))


@internal_kernel
def hertz_point_load(delta, R, E_star):
    """Load of a Hertz sphere-on-plane contact from its approach.

    Parameters
    ----------
    delta : float
        Approach [mm].
    R : float
        Sphere radius [mm].
    E_star : float
        Contact modulus [N/mm^2].

    Returns
    -------
    Q, dQ/ddelta : float
        Q [N] = (4/3) E* sqrt(R) delta^(3/2) (Johnson eq. 4.23) and its derivative [N/mm].
    """
    if delta <= 0.0:
        return 0.0, 0.0
    k = 4.0 / 3.0 * E_star * np.sqrt(R)
    return k * delta**1.5, 1.5 * k * np.sqrt(delta)


def contact_modulus(E, nu):
    """Contact modulus E* of two equal steel bodies [N/mm^2]: 1/E* = 2 (1 - nu^2)/E (Johnson eq. 4.22)."""
    return E / (2.0 * (1.0 - nu**2))


#: bisection steps on ln(k) of :func:`hertz_point_radii`: 2^-60 of ln(R_long / R_short), below round-off
ELLIPSE_BISECTION_STEPS = 60


@internal_kernel
def elliptic_integral_sums(k):
    """Complete elliptic integral K(m) of the first kind and S = (K - E) / K, E of the second kind,
    for the parameter m = 1 - 1/k^2, k >= 1, by the arithmetic-geometric mean (Abramowitz & Stegun
    17.6.3-17.6.4: a_0 = 1, b_0 = 1/k, c_0^2 = m; K = pi / (2 a_N), E / K = 1 - sum 2^(n-1) c_n^2,
    c_(n+1) = c_n^2 / (4 a_(n+1)) without cancellation). Quadratic convergence: stops at round-off."""
    a = 1.0
    b = 1.0 / k
    c2 = (1.0 - b) * (1.0 + b)      # c_0^2 = m
    S = 0.5 * c2
    w = 0.5
    for _ in range(64):
        a_next = 0.5 * (a + b)
        b = np.sqrt(a * b)
        c2 = c2 * c2 / (16.0 * a_next * a_next)
        a = a_next
        w *= 2.0
        S += w * c2
        if w * c2 <= 1e-17 * S:
            break
    return 0.5 * np.pi / a, S


@kernel
def hertz_point_radii(Rx, Ry):
    """Radii of the circular Hertz contact equivalent to an elliptical one (same load-approach
    law, same contact area), for relative radii of curvature Rx, Ry [mm] along the two principal
    directions, and the ellipticity along x.

    Exact Hertz theory (Johnson 1985, eqs. 3.70-3.72; gap A x^2 + B y^2, A = 1/(2 R_a) <= B =
    1/(2 R_b)): the semi-axis ratio k = a/b >= 1 solves B/A = (k^2 E - K) / (K - E), with the
    complete elliptic integrals K, E of m = 1 - 1/k^2 (:func:`elliptic_integral_sums`; bisection
    on ln k in [0, ln(R_a / R_b)], where k < R_a / R_b); then a^3 = 3 Q (K - E) / (2 pi E* m A),
    delta = 3 Q K / (2 pi a E*). A sphere of radius R_load on a plane, Q = 4/3 E* sqrt(R_load)
    delta^(3/2) (Johnson 4.23), has the same Q(delta) for R_load = pi^2 (K - E) R_a / (2 m K^3);
    a circle of radius (3 Q R_area / (4 E*))^(1/3) has the ellipse's area pi a b for
    R_area = 4 (K - E) R_a / (pi m k^(3/2)). Both tend to R as R_a, R_b -> R; the circle
    (Rx == Ry) returns (Rx, Rx, 1) exactly. tests/closed_form/test_roller_end_torus.py checks
    them against Johnson's circular limit and Hamrock & Brewe 1983 near it.

    Returns
    -------
    R_load, R_area : float
        [mm], as above.
    kappa : float
        Semi-axis along x over the one along y [1] (k or 1/k).
    """
    if Rx == Ry:
        return Rx, Rx, 1.0
    R_a = max(Rx, Ry)
    ratio = R_a / min(Rx, Ry)
    lo = 0.0
    hi = np.log(ratio)
    for _ in range(ELLIPSE_BISECTION_STEPS):
        t = 0.5 * (lo + hi)
        k = np.exp(t)
        S = elliptic_integral_sums(k)[1]
        # B/A = (k^2 E - K) / (K - E) = (k^2 - 1) / S - k^2 with S = (K - E) / K
        if (k * k - 1.0) / S - k * k < ratio:
            lo = t
        else:
            hi = t
    k = np.exp(0.5 * (lo + hi))
    K, S = elliptic_integral_sums(k)
    m = (1.0 - 1.0 / k) * (1.0 + 1.0 / k)
    KmE = K * S                                             # K - E
    kappa = k if Rx > Ry else 1.0 / k
    return np.pi ** 2 * KmE * R_a / (2.0 * m * K ** 3), 4.0 * KmE * R_a / (np.pi * m * k ** 1.5), kappa
