"""The design space of a study: free TSRB parameters, their bounds, the template's fixed values."""
from dataclasses import dataclass

import numpy as np
from scipy.stats import qmc

#: the osculation per contact point and race (thesis 8.2; null or absent in the bearing: kappa)
POINT_OSCULATIONS = {
    f"kappa_{race}_{end}": ("1", f"osculation of the {race} raceway at the {end}-end contact point (2.7)")
    for race in ("outer", "inner") for end in ("small", "large")}
#: searchable TSRB parameters (conf/bearing keys, sim.config_schema): name -> (units, long name)
DESIGN_PARAMETERS = {
    "PCR": ("mm", "profile curve radius of the roller"), "kappa": ("1", "osculation (2.7)"),
    "aP": ("mm", "distance between the contact points"), "aPk": ("mm", "small end face to the first contact point"),
    "alpha": ("deg", "roller-axis (mean contact) angle"), **POINT_OSCULATIONS}


@dataclass(frozen=True)
class DesignSpace:
    """Box of free design parameters inside a template TSRB.

    Attributes
    ----------
    names : tuple of str
        Free parameters, in the column order of every design matrix X.
    low, high : ndarray
        Their bounds [mm for PCR, aP, aPk; 1 for kappa; deg for alpha].
    template : dict
        Values of all :data:`DESIGN_PARAMETERS` (and ``ratings_alpha``) in the template bearing;
        a per-point osculation that the template leaves null (it follows kappa) stays None unless
        free, where it starts at the template's kappa, its value in the template.
    """

    names: tuple
    low: np.ndarray
    high: np.ndarray
    template: dict

    @classmethod
    def from_config(cls, study, template_bearing):
        """From ``study.free``/``study.bounds`` and the composed template ``bearing`` node."""
        names = tuple(str(n) for n in study.free)
        bounds = np.array([[float(v) for v in study.bounds[n]] for n in names])
        template = {k: float(template_bearing[k]) for k in (*DESIGN_PARAMETERS, "ratings_alpha")
                    if k not in POINT_OSCULATIONS}
        for k in POINT_OSCULATIONS:   # null or absent: kappa
            value = template_bearing.get(k)
            template[k] = float(value) if value is not None else (template["kappa"] if k in names else None)
        return cls(names, bounds[:, 0], bounds[:, 1], template)

    @property
    def bounds(self):
        """(d, 2) array of [low, high]."""
        return np.column_stack([self.low, self.high])

    def unit(self, X):
        """Design matrix scaled to the unit cube [1]."""
        return (np.atleast_2d(X) - self.low) / (self.high - self.low)

    def sample(self, n, method, seed):
        """Space-filling design of n points (scipy.stats.qmc): scrambled Sobol or Latin hypercube."""
        d = len(self.names)
        if method == "sobol":
            engine = qmc.Sobol(d, scramble=True, seed=seed)
            m = int(np.log2(n))
            U = engine.random_base2(m) if 2**m == n else engine.random(n)
        else:
            U = qmc.LatinHypercube(d, seed=seed).random(n)
        return qmc.scale(U, self.low, self.high)

    def bearing_values(self, x):
        """All design parameters of the bearing at x (free from x, others from the template).

        ``ratings_alpha`` follows ``alpha`` when alpha is free: the TSRB is rated with its
        contact angle, as thesis Table 6.2 does (conf/bearing/tsrb_*.yaml).
        """
        values = dict(self.template)
        values.update({n: float(v) for n, v in zip(self.names, np.ravel(x))})
        if "alpha" in self.names:
            values["ratings_alpha"] = values["alpha"]
        return values

    def include(self, points):
        """Design matrix (n, d) of the designs ``points`` (name: value mappings holding the free
        parameters, ``study.initial_design.include``)."""
        return np.array([[float(p[n]) for n in self.names] for p in points]).reshape(len(points), len(self.names))

    def ratings_alpha(self, X):
        """``ratings_alpha`` [deg] of each design of X (n, d), as :meth:`bearing_values` sets it."""
        X = np.atleast_2d(X)
        if "alpha" in self.names:
            return X[:, self.names.index("alpha")].astype(float)
        return np.full(len(X), self.template["ratings_alpha"])

    def suggest(self, trial):
        """Ask an Optuna trial for one point; returns x in column order."""
        return np.array([trial.suggest_float(n, lo, hi) for n, lo, hi in zip(self.names, self.low, self.high)])

    def from_params(self, params):
        """x from an Optuna params dict."""
        return np.array([float(params[n]) for n in self.names])
