"""Test helpers: load cases and independent recomputation of forces from a solved state."""
import numpy as np

from sim.simulation import OperatingPoint


def case(Fa, Fr=0.0, speed=2000.0, tilt=0.0, oil_temperature=55.0):
    return OperatingPoint(float(Fa), float(Fr), float(speed), float(tilt), float(oil_temperature))


def contact_forces_on_inner_ring(model, raw):
    """Resultant of all slice loads on the inner raceway, recomputed from the solved state [N].

    Independent of the solver's residual bookkeeping: normals from the contact kernel at the
    final poses, loads from the returned line loads, summed as 3-D vectors over azimuths.
    """
    from sim.contact import slice_contact_meridian

    g = model.geometry
    a = g.arrays
    n = g.n_slices
    d = np.empty(n)
    nrm = np.empty((n, 2))
    pts = np.empty((n, 2))
    Fx = Fz = 0.0
    for j in range(g.Z):
        psi = 2 * np.pi * j / g.Z
        slice_contact_meridian(a["x"], a["rho"], -1, raw["poses"][j], g.alpha, g.Dpw, a["race_kind"][1],
                               a["race_par"][1], raw["ring"][1] * np.cos(psi), raw["ring"][0], 0.0, d, nrm, pts)
        load = raw["line_load"][j, 1] * a["w"]
        Fx += np.sum(load * nrm[:, 0]) * np.cos(psi)
        Fz += np.sum(load * nrm[:, 1])
    return Fx, Fz
