"""Constraint margins of a design: normalised, <= 0 feasible (issue 5, item 3; STYLE.md, Studies).

One function, :func:`margins`, serves the simulated points, the surrogate predictions and
the benchmark's direct search, so that all three judge a design alike.

=====================  ============================================================
name                   margin
=====================  ============================================================
simulation             0 ok; 1 impossible geometry, failed or not converged (surrogate:
                       minus the predicted convergence label, which is +1 / -1)
axial_displacement     max over the cases of |axial displacement| / limit - 1 (rib-free,
                       thesis Annex A.2.1)
pmax                   max over the cases of pmax_i / limit_i - 1, limit_i that of the case
                       (thesis 7.3: pressure similar to the TRB at the same load)
L10                    1 - L10 / L10_min, L10 over the duty cycle (studies.cycle.cycle_life:
                       (C_eff / P_eq)^p of eq. (2.15) with C_eff (7.1), P (2.12) at the design's
                       rating angle); one case: (C_eff / P)^p
edge_stress            max over the cases of the edge-stress margin
                       (sim.physics.elasticity.edge_interference); only when
                       ``constraints.edge_stress`` is true (thesis 7.3, step 12)
PCR_over_Lwe           PCR / (ratio_max Lwe) - 1 (issue 5), exact
=====================  ============================================================

A constraint violated at any one case of the duty cycle (studies.cycle) makes the design
infeasible: the per-case margins are reduced by their maximum. For a one-case study every
reduction is the identity, so its margins are those of the single-case study bit for bit.
"""
from dataclasses import dataclass

import numpy as np

from sim.api import ratings
from studies.config import StudyConfigError
from studies.cycle import LIFE_EXPONENT, cycle_life, equivalent_load
from studies.evaluate import EDGE_MARGIN

FAILED = 1.0  # margin of a point without results: one limit's worth of violation, so a sampler ranks it


# name of the first margin: 0 when the simulation gave a result, FAILED when not (no physical constraint)
SIMULATION_MARGIN = "simulation"


@dataclass(frozen=True)
class Limits:
    """Limits of the constraints over the study's duty cycle (studies.cycle; one case: its load case).

    Attributes
    ----------
    axial_displacement_max : float  [mm]
    pmax_max : tuple of float  [MPa], one per case
    L10_min : float  [1e6 rev], over the cycle
    edge_stress : bool
        Whether an edge-stress peak is forbidden.
    PCR_over_Lwe_max : float  [1]
    Lwe : float  [mm]
    Fa, Fr : tuple of float  [N], one per case
    speed, share : tuple of float  [rpm], [1], one per case (the weights of the cycle's P_eq)

    Per-case fields given as numbers (limits stored by an older study) are read as one case.
    """

    axial_displacement_max: float
    pmax_max: tuple
    L10_min: float
    edge_stress: bool
    PCR_over_Lwe_max: float
    Lwe: float
    Fa: tuple
    Fr: tuple
    speed: tuple = (1.0,)
    share: tuple = (1.0,)

    def __post_init__(self):
        for key in ("pmax_max", "Fa", "Fr", "speed", "share"):
            object.__setattr__(self, key, tuple(float(v) for v in np.atleast_1d(getattr(self, key))))

    @classmethod
    def from_config(cls, study, trb_cases, Lwe, cycle):
        """Limits from ``study.constraints``; ``"trb"`` entries from the reference TRB's results
        ``trb_cases`` (one values dict per case of ``cycle``, studies.cycle.DutyCycle): its pmax
        at each case, its L10 over the cycle."""
        c = study.constraints
        speed, share = cycle.column("speed"), cycle.share

        def trb(key, quantity, value):
            if not np.all(np.isfinite(value)):
                raise StudyConfigError(f"study.constraints.{key} = 'trb' but the reference TRB {study.reference_trb} has no "
                                       f"{quantity} at every load case (not converged)")
            return value

        def case_values(quantity):
            return np.array([v[quantity] for v in trb_cases], dtype=float)

        pmax = [float(c.pmax_max)] * len(cycle) if c.pmax_max != "trb" else trb("pmax_max", "pmax", case_values("pmax"))
        # one case: the simulation's own L10, which sim.api computes by the same (C_eff / P)^p
        L10 = float(c.L10_min) if c.L10_min != "trb" else cycle_life(
            trb("L10_min", "C_eff", case_values("C_eff")), trb("L10_min", "P", case_values("P")), speed, share)
        return cls(float(c.axial_displacement_max), pmax, L10, bool(c.edge_stress), float(c.PCR_over_Lwe_max),
                   float(Lwe), cycle.column("Fa"), cycle.column("Fr"), speed, share)

    def P(self, ratings_alpha):
        """Equivalent dynamic load (eq. 2.12) [N] of each case for designs rated at ``ratings_alpha``
        [deg] (float or array): a list over the cases."""
        return [ratings.equivalent_dynamic_load(fr, fa, ratings_alpha) for fr, fa in zip(self.Fr, self.Fa)]

    def C_eff_min(self, ratings_alpha):
        """C_eff [N] at which L10 = L10_min for designs rated at ``ratings_alpha`` [deg] (float or
        array): P_eq L10_min^(1/p), P_eq over the cycle (studies.cycle.equivalent_load; the L10
        margin is <= 0 exactly when the C_eff of every case reaches this)."""
        P = np.asarray(equivalent_load(self.P(ratings_alpha), self.speed, self.share), dtype=float)
        return P * self.L10_min ** (1.0 / LIFE_EXPONENT)

    @property
    def names(self):
        """Names of the margins returned by :func:`margins`, in order."""
        return (SIMULATION_MARGIN, "axial_displacement", "pmax", "L10", *(("edge_stress",) if self.edge_stress else ()),
                "PCR_over_Lwe")


def margins(values, bearing, limits, simulation):
    """Normalised constraint margins of one design (<= 0 feasible).

    Parameters
    ----------
    values : dict
        ``pmax`` [MPa], ``axial_displacement`` [mm], ``C_eff`` [N], ``edge_stress_margin`` [1];
        simulated or predicted, each a number or one value per case of ``limits``; NaN where
        there is no result.
    bearing : dict
        Design parameters (``PCR`` [mm], ``ratings_alpha`` [deg]).
    limits : Limits
    simulation : float
        Margin of the simulation itself (0 ok, :data:`FAILED`, or a predicted value).

    Returns
    -------
    ndarray
        One margin per name of ``limits.names``. Without results (any NaN) the result-based
        margins are 0: the ``simulation`` margin alone marks the point infeasible.
    """
    geometric = exact_margin(bearing, limits)
    keys = ("pmax", "axial_displacement", "C_eff", *((EDGE_MARGIN,) if limits.edge_stress else ()))
    v = {k: np.atleast_1d(np.asarray(values[k], dtype=float)) for k in keys}
    if not all(np.all(np.isfinite(x)) for x in v.values()):
        return np.array([simulation, *([0.0] * (len(limits.names) - 2)), geometric])
    L10 = cycle_life(v["C_eff"], limits.P(bearing["ratings_alpha"]), limits.speed, limits.share)
    out = [simulation, float(np.max(np.abs(v["axial_displacement"]) / limits.axial_displacement_max - 1.0)),
           float(np.max(v["pmax"] / np.array(limits.pmax_max) - 1.0)), 1.0 - L10 / limits.L10_min]
    if limits.edge_stress:
        out.append(float(np.max(v[EDGE_MARGIN])))
    out.append(geometric)
    return np.array(out, dtype=float)


def exact_margin(bearing, limits):
    """The PCR_over_Lwe margin, known without a simulation: PCR / (ratio_max Lwe) - 1."""
    return bearing["PCR"] / (limits.PCR_over_Lwe_max * limits.Lwe) - 1.0


def violation(m):
    """Total violation: the sum of the positive margins (0 for a feasible design)."""
    return float(np.sum(np.maximum(np.asarray(m, dtype=float), 0.0)))


def rank_key(objective, m):
    """Sort key of designs: feasible ones by objective, then infeasible ones by violation, then the
    points without result (NaN objective) by violation."""
    v = violation(m)
    if not np.isfinite(objective):
        return (2, v)
    return (0, float(objective)) if v == 0.0 else (1, v)
