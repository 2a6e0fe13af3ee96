"""Azimuth symmetry of a load case: which rollers one solution stands for.

The inner ring carries Fa along +z and Fr along +x and is tilted about the y axis; with no load
along y (Fy, the friction loads' share, sim.api.friction_model.coupled_solution) the load case is
symmetric about the x-z plane: roller j at psi_j = 2 pi j / Z and roller Z - j at -psi_j see the
same ring displacement in their meridian planes (the same cos(psi), the same rotation
phi = tilt cos(psi); the ring's lateral displacement is 0). They are mirror images when their
external roller loads are equal. Without radial and lateral load and tilt, and with equal external
loads on every roller, all rollers are alike (axisymmetric case). The quasi-static solver and the
friction evaluation reduce their roller loops by the same classes.
"""
import numpy as np

from sim._math.jit import kernel


@kernel
def symmetry_classes(Z, Fr, Fy, tilt, roller_loads):
    """Roller classes of a load case (module docstring).

    Parameters
    ----------
    Z : int
        Number of rollers (>= 3).
    Fr, Fy : float
        Radial load (along x) and lateral load (along y) on the inner ring [N].
    tilt : float
        Imposed inner-ring tilt [rad].
    roller_loads : ndarray (Z, m)
        External loads per roller in its own frame (any m; compared exactly), e.g. the
        ``roller_loads`` of :meth:`sim.api.bearing_model.BearingModel.solve` [N, N, N mm].

    Returns
    -------
    n_classes : int
        Number of rollers to solve, the representatives 0 .. n_classes - 1: 1 (axisymmetric),
        Z // 2 + 1 (mirror), Z (no symmetry).
    weight : ndarray (Z,)
        Rollers each representative stands for: Z (axisymmetric); 2 for 0 < j < Z / 2 and 1 for
        j = 0 and j = Z / 2 (mirror); 1 (no symmetry); 0 for the rollers that are represented.
        Sums to Z.
    source : ndarray (Z,) int64
        Representative of every roller: 0 (axisymmetric); Z - j for j > Z // 2 (mirror); j
        otherwise.
    """
    mirror = Fy == 0.0
    equal = True
    for j in range(Z):
        for a in range(roller_loads.shape[1]):
            if roller_loads[j, a] != roller_loads[(Z - j) % Z, a]:
                mirror = False
            if roller_loads[j, a] != roller_loads[0, a]:
                equal = False
    axisymmetric = Fr == 0.0 and Fy == 0.0 and tilt == 0.0 and equal
    weight = np.zeros(Z)
    source = np.empty(Z, dtype=np.int64)
    if axisymmetric:
        n_classes = 1
        weight[0] = float(Z)
        for j in range(Z):
            source[j] = 0
    elif mirror:
        n_classes = Z // 2 + 1
        for j in range(Z):
            if j < n_classes:
                source[j] = j
                weight[j] = 2.0 if j > 0 and 2 * j != Z else 1.0
            else:
                source[j] = Z - j
    else:
        n_classes = Z
        for j in range(Z):
            source[j] = j
            weight[j] = 1.0
    return n_classes, weight, source


def mirror_mean(loads):
    """The mean of each roller's loads (Z, m) in its own frame and its mirror image's (roller Z - j,
    module docstring): the mirror-symmetric part of per-roller loads, such as the friction loads fed
    back into the load distribution (sim.api.friction_model.coupled_solution)."""
    Z = loads.shape[0]
    return 0.5 * (loads + loads[(Z - np.arange(Z)) % Z])
