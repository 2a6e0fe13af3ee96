"""Rolling-bearing kinematics without slip (thesis 2.1.5).

The friction issue replaces these by speeds from the traction balance; the quasi-static
load distribution uses them for centrifugal force and gyroscopic moment.
"""
import numpy as np


def angular_speed(n_rpm):
    """omega [rad/s] = pi n / 30 from n [rpm], thesis eq. (2.16)."""
    return np.pi * np.asarray(n_rpm, dtype=float) / 30.0


def cage_speed_rolling(n_inner, n_outer, Dwe, Dpw, alpha):
    """Cage speed for rolling without slip.

    Parameters
    ----------
    n_inner, n_outer : float
        Inner- and outer-ring speeds [rpm].
    Dwe, Dpw : float
        Roller and pitch diameter [mm].
    alpha : float
        Contact angle [rad].

    Returns
    -------
    float
        n_C [rpm] = (1 - Dwe cos(alpha)/Dpw) n_IR/2 + (1 + Dwe cos(alpha)/Dpw) n_OR/2, eq. (2.20).
    """
    g = Dwe * np.cos(alpha) / Dpw
    return (1.0 - g) * 0.5 * n_inner + (1.0 + g) * 0.5 * n_outer


def roller_speed_rolling(n_inner, n_outer, Dwe, Dpw, alpha):
    """Roller speed about its own axis for rolling without slip, relative to the cage.

    Parameters
    ----------
    n_inner, n_outer : float
        Inner- and outer-ring speeds [rpm].
    Dwe, Dpw : float
        Roller and pitch diameter [mm].
    alpha : float
        Contact angle [rad].

    Returns
    -------
    float
        n_R [rpm] = (Dpw/Dwe - Dwe cos^2(alpha)/Dpw) (n_IR - n_OR)/2: the magnitude of eq. (2.22),
        signed positive about the roller axis u (towards the large end, sim.geometry) for a
        faster inner ring; eq. (2.22) itself carries the opposite sign.
    """
    return (Dpw / Dwe - Dwe * np.cos(alpha) ** 2 / Dpw) * 0.5 * (n_inner - n_outer)
