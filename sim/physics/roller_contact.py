"""Contact frames of a solved roller set: contact points and normals of every slice, roller
centres and axes, the roller-end / rib contact point (meridian plane of each roller, mm).
"""
from collections import namedtuple

import numpy as np

from sim._math.jit import kernel
from sim.physics.contact import roller_axes, slice_contact_meridian

# Contact frames of Z rollers with N slices per raceway (a numba-supported named tuple of arrays):
# X, Nrm (Z, 2, N, 2): contact points [mm] and unit normals into the ring, (r, z), race 0 outer,
# 1 inner; Cen (Z, 2): roller centres [mm]; Ax (Z, 4): roller axes (u'_r, u'_z, v'_r, v'_z);
# Xrib (Z, 2): roller-end / rib contact point [mm] (TRB only).
ContactFrames = namedtuple("ContactFrames", ["X", "Nrm", "Cen", "Ax", "Xrib"])


def empty_frames(Z, n):
    """Zeroed :data:`ContactFrames` for Z rollers and n slices."""
    return ContactFrames(np.zeros((Z, 2, n, 2)), np.zeros((Z, 2, n, 2)), np.zeros((Z, 2)), np.zeros((Z, 4)),
                         np.zeros((Z, 2)))


@kernel
def contact_frames(poses, ring, tilt, alpha, Dpw, x, rho, race_kind, race_par, rib, X, Nrm, Cen, Ax, Xrib):
    """Contact points and normals of every slice, roller centres and axes at the solved state.

    Parameters
    ----------
    poses : ndarray (Z, 3)
        Roller xi [mm], eta [mm], theta [rad] (sim.solvers.quasi_static).
    ring : ndarray (2,)
        Inner-ring axial and radial displacement [mm].
    tilt : float
        Imposed inner-ring tilt [rad].
    X, Nrm : ndarray (Z, 2, N, 2)
        Contact points [mm] and unit normals into the ring, (r, z) (written).
    Cen, Ax : ndarray (Z, 2) and (Z, 4)
        Roller centres [mm] and axes (u'_r, u'_z, v'_r, v'_z) (written).
    Xrib : ndarray (Z, 2)
        Roller-end / rib contact point [mm] (written; TRB only).
    """
    Z = poses.shape[0]
    n = x.shape[0]
    d = np.empty(n)
    sa = np.sin(alpha)
    ca = np.cos(alpha)
    for j in range(Z):
        psi = 2.0 * np.pi * j / Z
        cpsi = np.cos(psi)
        phi = tilt * cpsi
        pose = poses[j]
        ur, uz, vr, vz = roller_axes(alpha, pose[2])
        Cen[j, 0] = 0.5 * Dpw + pose[0] * sa + pose[1] * ca
        Cen[j, 1] = -pose[0] * ca + pose[1] * sa
        Ax[j, 0] = ur
        Ax[j, 1] = uz
        Ax[j, 2] = vr
        Ax[j, 3] = vz
        slice_contact_meridian(x, rho, 1, pose, alpha, Dpw, race_kind[0], race_par[0], 0.0, 0.0, 0.0,
                               d, Nrm[j, 0], X[j, 0])
        slice_contact_meridian(x, rho, -1, pose, alpha, Dpw, race_kind[1], race_par[1],
                               ring[1] * cpsi, ring[0], phi, d, Nrm[j, 1], X[j, 1])
        ex = rib[0] + rib[2] * rib[3]
        ey = rib[2] * rib[4]
        Xrib[j, 0] = Cen[j, 0] + ex * ur + ey * vr
        Xrib[j, 1] = Cen[j, 1] + ex * uz + ey * vz
