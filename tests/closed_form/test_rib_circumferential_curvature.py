"""The TRB's roller-end / rib contact along the circumference (e_t): the relative curvature the
Hertz contact uses (sim.geometry: ``rib[5]``, ``rib_end[2]``, Meusnier's theorem on the cone rib)
against the gap of the two surfaces computed directly in 3-D, for the sphere and the torus end.

Before this check the sphere's rib was taken as flat along e_t (relative radius R_end, a circular
contact), although the rib is a cone about the bearing axis whose normal meets that axis near the
apex: along e_t it is concave with a radius close to the apex distance, and the end sphere nearly
conforms to it (relative radius ~ R_end / (1 - roller_end_radius_ratio), about 10 R_end)."""
import numpy as np
import pytest

import sim
from sim.geometry import Geometry


def geometry(*overrides):
    cfg = sim.load_config(list(overrides))
    return Geometry.from_config(cfg.bearing, cfg.material, cfg.solver.n_slices)


def circumferential_gap(g, p):
    """Gap [mm] between the roller end and the cone rib at the point of the end reached from the
    nominal contact point P by turning it through p [rad] about the roller axis (the end is a
    surface of revolution about that axis, sphere or torus, so the point stays on it; the curve is
    tangent to e_t at P, arc length |y_P| p).

    3-D frame as tests/closed_form/test_roller_end_torus.py: bearing axis z, the roller's meridian
    plane the (x, z) plane, roller centre C = (Dpw/2, 0, 0), axes u = (sin a, 0, -cos a),
    v = (cos a, 0, sin a), e_t = (0, 1, 0). The rib is the cone of revolution about z through P
    with normal N (into the rib) there; a point's penetration is (r - L_r) N_r + (z - L_z) N_z in
    its own meridian plane (exact for a cone of revolution); the gap is minus it."""
    rib = g.arrays["rib"]
    c_x, c_y, radius, n_x, n_y = rib[:5]
    x_p, y_p = c_x + radius * n_x, c_y + radius * n_y          # contact point, roller frame
    sa, ca = np.sin(g.alpha), np.cos(g.alpha)
    C = np.array([0.5 * g.Dpw, 0.0, 0.0])
    u, v, et = np.array([sa, 0.0, -ca]), np.array([ca, 0.0, sa]), np.array([0.0, 1.0, 0.0])
    N = n_x * np.array([sa, -ca]) + n_y * np.array([ca, sa])     # (r, z)
    L = np.array([0.5 * g.Dpw + x_p * sa + y_p * ca, -x_p * ca + y_p * sa])
    Y = C + x_p * u + y_p * (np.cos(p) * v + np.sin(p) * et)
    return -((np.hypot(Y[0], Y[1]) - L[0]) * N[0] + (Y[2] - L[1]) * N[1]), abs(y_p)


@pytest.mark.parametrize("overrides", [
    ("bearing=trb_31313",),
    ("bearing=trb_32208",),
    ("bearing=trb_32208", "bearing.roller_end_radius_ratio=0.8"),
    ("bearing=trb_31313", "bearing.roller_end_radius_ratio=0.97", "bearing.rib_contact_height_ratio=0.25"),
    ("bearing=trb_31313", "bearing.roller_end=torus"),
    ("bearing=trb_32208", "bearing.roller_end=torus", "bearing.rib_opening_angle=8"),
])
def test_rib_relative_curvature_along_e_t_is_the_3d_gap(overrides):
    """The gap along the circumference grows as k_t s^2 / 2 with k_t = 1 / R_t, the relative
    curvature the Hertz contact takes (rib[5], rib_end[2]). Gap at p = 1e-3 and 2e-3 rad,
    Richardson-extrapolated (the next term is O(s^4), ~1e-6 relative at these arcs; the gap,
    ~1e-8 mm, carries a coordinate round-off of ~1e-14 mm, 1e-6 relative): tolerance 1e-4. The
    sphere also conforms to the rib by about roller_end_radius_ratio: R_t within 15 % of
    R_end / (1 - ratio) (the normal meets the bearing axis near, not at, the apex)."""
    g = geometry(*overrides)
    R_t = g.arrays["rib"][5]
    assert R_t == g.arrays["rib_end"][2] and R_t > 0.0
    k = []
    for p in (1e-3, 2e-3):
        gap, rim = circumferential_gap(g, p)
        k.append(2.0 * gap / (rim * p) ** 2)
    k_3d = (4.0 * k[0] - k[1]) / 3.0
    assert 1.0 / R_t == pytest.approx(k_3d, rel=1e-4)
    if g.roller_end == "sphere":
        R_end = g.arrays["rib"][2]
        ratio = g.roller_end_radius_ratio
        assert R_t == pytest.approx(R_end / (1.0 - ratio), rel=0.15)
        assert R_t > 3.0 * R_end       # far from the circular contact of a flat rib

