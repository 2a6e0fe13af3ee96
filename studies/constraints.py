"""Constraint margins of a design: normalised, <= 0 feasible (issue 5, item 3; STYLE.md, Studies).

One function, :func:`margins`, serves the simulated points, the surrogate predictions and
the benchmark's direct search, so that all three judge a design alike.

=====================  ============================================================
name                   margin
=====================  ============================================================
simulation             0 ok; 1 impossible geometry, failed or not converged (surrogate:
                       minus the predicted convergence label, which is +1 / -1)
axial_displacement     |axial displacement| / limit - 1 (rib-free, thesis Annex A.2.1)
pmax                   pmax / limit - 1 (thesis 7.3: pressure similar to the TRB)
L10                    1 - L10 / L10_min, L10 = (C_eff / P)^p of eq. (2.15) with C_eff (7.1)
                       and P (2.12) at the design's rating angle
edge_stress            edge-stress margin (studies.evaluate.edge_stress_margin); only when
                       ``constraints.edge_stress`` is true (thesis 7.3, step 12)
PCR_over_Lwe           PCR / (ratio_max Lwe) - 1 (issue 5), exact
=====================  ============================================================
"""
from dataclasses import dataclass

import numpy as np

from sim.api import ratings
from studies.config import StudyConfigError
from studies.evaluate import EDGE_MARGIN

FAILED = 1.0  # margin of a point without results: one limit's worth of violation, so a sampler ranks it
LIFE_EXPONENT = 10.0 / 3.0  # p of L10 = (C / P)^p for roller bearings, ISO 281 / thesis eq. (2.15)


@dataclass(frozen=True)
class Limits:
    """Limits of the constraints at the study's load case.

    Attributes
    ----------
    axial_displacement_max : float  [mm]
    pmax_max : float  [MPa]
    L10_min : float  [1e6 rev]
    edge_stress : bool
        Whether an edge-stress peak is forbidden.
    PCR_over_Lwe_max : float  [1]
    Lwe : float  [mm]
    Fa, Fr : float  [N]
    """

    axial_displacement_max: float
    pmax_max: float
    L10_min: float
    edge_stress: bool
    PCR_over_Lwe_max: float
    Lwe: float
    Fa: float
    Fr: float

    @classmethod
    def from_config(cls, study, trb_values, Lwe):
        """Limits from ``study.constraints``; ``"trb"`` entries from the reference TRB's results."""
        c = study.constraints

        def limit(key, quantity):
            if c[key] != "trb":
                return float(c[key])
            value = trb_values[quantity]
            if not np.isfinite(value):
                raise StudyConfigError(f"study.constraints.{key} = 'trb' but the reference TRB {study.reference_trb} has no "
                                 f"{quantity} at this load (not converged)")
            return float(value)

        return cls(float(c.axial_displacement_max), limit("pmax_max", "pmax"), limit("L10_min", "L10"),
                   bool(c.edge_stress), float(c.PCR_over_Lwe_max), float(Lwe), float(study.load.Fa),
                   float(study.load.Fr))

    def C_eff_min(self, ratings_alpha):
        """C_eff [N] at which L10 = L10_min for designs rated at ``ratings_alpha`` [deg] (float or
        array): P L10_min^(1/p), P of eq. (2.12) (the L10 margin is <= 0 exactly for C_eff >= this)."""
        P = np.asarray(ratings.equivalent_dynamic_load(self.Fr, self.Fa, ratings_alpha), dtype=float)
        return P * self.L10_min ** (1.0 / LIFE_EXPONENT)

    @property
    def names(self):
        """Names of the margins returned by :func:`margins`, in order."""
        return ("simulation", "axial_displacement", "pmax", "L10", *(("edge_stress",) if self.edge_stress else ()),
                "PCR_over_Lwe")


def margins(values, bearing, limits, simulation):
    """Normalised constraint margins of one design (<= 0 feasible).

    Parameters
    ----------
    values : dict
        ``pmax`` [MPa], ``axial_displacement`` [mm], ``C_eff`` [N], ``edge_stress_margin`` [1];
        simulated or predicted; NaN where there is no result.
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
    needed = [values[k] for k in ("pmax", "axial_displacement", "C_eff", *((EDGE_MARGIN,) if limits.edge_stress else ()))]
    if not np.all(np.isfinite(needed)):
        return np.array([simulation, *([0.0] * (len(limits.names) - 2)), geometric])
    P = float(ratings.equivalent_dynamic_load(limits.Fr, limits.Fa, bearing["ratings_alpha"]))
    L10 = float(ratings.basic_rating_life(values["C_eff"], P, LIFE_EXPONENT)) if values["C_eff"] > 0.0 else 0.0
    out = [simulation, abs(values["axial_displacement"]) / limits.axial_displacement_max - 1.0,
           values["pmax"] / limits.pmax_max - 1.0, 1.0 - L10 / limits.L10_min]
    if limits.edge_stress:
        out.append(values[EDGE_MARGIN])
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
