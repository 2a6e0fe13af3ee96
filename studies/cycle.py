"""Duty cycle of a design study (issue 16 item 5): load cases with time shares.

A study runs every design at each case of its cycle. ``study.duty_cycle`` lists the cases, each
``{Fa, Fr, speed, share}`` (``tilt`` and ``oil_temperature`` may be given too; what a case does not
set comes from ``study.load``); ``study.duty_cycle: null`` is the one-case cycle of ``study.load``
with share 1, the single-case study. The shares are fractions of operating time and sum to 1
(checked by :func:`studies.config.validate`).

Cycle quantities:

- objective: the time-weighted mean sum_i share_i y_i of the per-case objective y_i; for the
  power loss [W] (torque x angular speed, DATA.md ``power_loss``) that is the mean power loss over
  the cycle, i.e. the energy lost per unit time;
- equivalent dynamic load over the cycle (:func:`equivalent_load`) and the rating life from it
  (:func:`cycle_life`).
"""
from dataclasses import dataclass

import numpy as np

from sim.api import ratings
from studies.evaluate import EDGE_MARGIN

LOAD_KEYS = ("Fa", "Fr", "speed", "tilt", "oil_temperature")   # a load case's quantities (DATA.md case coordinates)

LIFE_EXPONENT = 10.0 / 3.0  # p of L10 = (C / P)^p for roller bearings, ISO 281:2007 eq. (2) / thesis eq. (2.15)


def equivalent_load(P, speed, share, p=LIFE_EXPONENT):
    """Equivalent dynamic load of a cycle of constant-load cases (mean effective load).

    P_eq = (sum_i share_i n_i P_i^p / sum_i share_i n_i)^(1/p): the constant load that does the
    same fatigue damage in the same number of revolutions (Palmgren-Miner summation of the
    Lundberg-Palmgren life; Harris & Kotzalas 2007, "Essential Concepts of Bearing Technology",
    5th ed., mean effective load under variable load and speed; ISO 281:2007 with p = 10/3 for
    roller bearings).

    Parameters
    ----------
    P : array_like, shape (m, ...)
        Equivalent dynamic load of each case [N] (ISO 281, eq. 2.12); trailing dims broadcast
        (e.g. one column per design).
    speed : array_like, shape (m,)
        Rotational speed of each case [rpm] (> 0); only ratios matter.
    share : array_like, shape (m,)
        Time share of each case [1].
    p : float
        Life exponent [1].

    Returns
    -------
    float or ndarray
        P_eq [N]. A one-case cycle returns its P unchanged (the formula's identity, taken exactly
        so that the single-case study keeps its numbers bit for bit).
    """
    P = np.asarray(P, dtype=float)
    if P.shape[0] == 1:
        return P[0] if P.ndim > 1 else float(P[0])
    w = np.asarray(speed, dtype=float) * np.asarray(share, dtype=float)
    w = w.reshape((-1,) + (1,) * (P.ndim - 1))
    out = (np.sum(w * P ** p, axis=0) / np.sum(w)) ** (1.0 / p)
    return float(out) if np.ndim(out) == 0 else out


def cycle_life(C_eff, P, speed, share, p=LIFE_EXPONENT):
    """Basic rating life over a cycle: L10 = (C / P_eq)^p [1e6 rev] (ISO 281:2007 eq. (2), thesis
    eq. (2.15)) with P_eq of :func:`equivalent_load` and C the least effective dynamic rating
    C_eff (thesis eq. 7.1) of the cycle's cases [N]: ISO 281 gives a bearing one rating, the
    TSRB's depends on its loaded length and so on the case, and the least is the conservative
    choice. 0 when C <= 0 (as sim.api.bearing_model does for one case), NaN without a result."""
    C = float(np.min(np.asarray(C_eff, dtype=float)))
    P_eq = equivalent_load(P, speed, share, p)
    if not (np.isfinite(C) and np.isfinite(P_eq)):
        return float("nan")
    return float(ratings.basic_rating_life(C, P_eq, p)) if C > 0.0 else 0.0


@dataclass(frozen=True)
class DutyCycle:
    """Load cases of a study with their time shares.

    Attributes
    ----------
    cases : tuple of dict
        Each a complete load case {Fa [N], Fr [N], speed [rpm], tilt [deg], oil_temperature [degC]}.
    share : ndarray, shape (m,)
        Time share of each case [1], summing to 1.
    """

    cases: tuple
    share: np.ndarray

    @classmethod
    def from_config(cls, study):
        """``study.duty_cycle`` over ``study.load``, or the one case ``study.load`` with share 1."""
        base = {k: float(study.load[k]) for k in LOAD_KEYS}
        entries = study.get("duty_cycle") or [{"share": 1.0}]
        cases = tuple({**base, **{k: float(e[k]) for k in LOAD_KEYS if k in e}} for e in entries)
        return cls(cases, np.array([float(e["share"]) for e in entries]))

    def __len__(self):
        return len(self.cases)

    def column(self, key):
        """One load quantity of every case, as an array (m,)."""
        return np.array([c[key] for c in self.cases])

    def weighted(self, values):
        """Time-weighted mean sum_i share_i y_i over the last axis of ``values`` (..., m); NaN stays NaN.
        A one-case cycle returns its values unchanged (share 1: y * 1 = y exactly)."""
        return np.sum(np.asarray(values, dtype=float) * self.share, axis=-1)

    def label(self, k):
        """'Fa 60 kN, Fr 0 kN, 550 rpm, share 0.1' of case k."""
        c = self.cases[k]
        return f"Fa {c['Fa'] / 1e3:g} kN, Fr {c['Fr'] / 1e3:g} kN, {c['speed']:g} rpm, share {self.share[k]:g}"


def summary_values(values, cycle, objective):
    """One number per quantity for a design over the cycle, from its per-case values
    {quantity: array (m,)} (studies.evaluate.case_values), for tables and the direct search:

    the objective: time-weighted mean (:meth:`DutyCycle.weighted`); pmax, edge_stress,
    edge_stress_margin: maximum over the cases; axial_displacement: the value of largest
    magnitude; L_eff, C_eff: minimum; P: :func:`equivalent_load`; L10: :func:`cycle_life`.
    Other quantities: the time-weighted mean. A one-case cycle gives its values unchanged.
    """
    v = {q: np.asarray(x, dtype=float) for q, x in values.items()}
    speed, share = cycle.column("speed"), cycle.share
    rules = {"pmax": np.max, "edge_stress": np.max, EDGE_MARGIN: np.max, "L_eff": np.min, "C_eff": np.min,
             "axial_displacement": lambda x: x[np.argmax(np.abs(x))],
             "P": lambda x: equivalent_load(x, speed, share),
             "L10": lambda x: cycle_life(v["C_eff"], v["P"], speed, share)}
    out = {q: float(rules.get(q, cycle.weighted)(x)) for q, x in v.items()}
    if objective in v:
        out[objective] = float(cycle.weighted(v[objective]))
    return out
