"""Probability that a design's simulation gives a result: a Gaussian-process classifier (issue 16 item 1).

A simulation that fails or does not converge has no output to regress; what a search needs is
the probability that a new design succeeds. That is a binary label, modelled by Gaussian-process
classification (Rasmussen & Williams 2006, ch. 3): a latent GP f with the same anisotropic
Matern prior as the regression surrogates (surrogate.gp) on inputs scaled to the unit cube, the
logistic likelihood p(success | f) = 1 / (1 + exp(-f)), the posterior by the Laplace
approximation (R&W 3.4, Algorithm 3.1) and the predictive probability averaged over it (R&W
eq. 3.25; scikit-learn's GaussianProcessClassifier). Regression on +-1 labels (the earlier
approach) is no probability: its mean leaves [-1, 1] and its noise model is wrong for labels.

When every training point succeeded (or every one failed) there is nothing to classify; the
probability is then the same at every design, Laplace's rule of succession (n_s + 1) / (n + 2)
(Jaynes 2003, "Probability Theory", 18.6), which does not change a ranking of designs.
"""
import warnings

import numpy as np
import sklearn
from sklearn.exceptions import ConvergenceWarning
from sklearn.gaussian_process import GaussianProcessClassifier
from sklearn.gaussian_process.kernels import ConstantKernel, Matern
from threadpoolctl import threadpool_limits

from surrogate.gp import GPSurrogate, _geometric_mean


class SuccessClassifier:
    """P(simulation succeeds | design) over a box of design parameters.

    Parameters
    ----------
    bounds : array_like, shape (d, 2)
        [low, high] of each input in its own unit.
    settings : surrogate.GPSettings
        Kernel bounds, Matern smoothness, optimiser restarts and seed (shared with the regression
        surrogates; the noise and calibration settings do not apply).
    name : str
        Name in the saved set.
    """

    units = "1"
    log = False

    def __init__(self, bounds, settings, name="success"):
        self._box = GPSurrogate(bounds, False, settings, name)   # input scaling and its checks
        self.bounds = self._box.bounds
        self.settings = settings
        self.name = name
        self.gpc = None
        self.constant = None     # the rule-of-succession probability when there is one class only
        self.n_train = 0
        self.n_success = 0

    def fit(self, X, success):
        """Fit to inputs X (n, d) [their units] and labels ``success`` (n,) bool; returns self."""
        U = self._box.scale(X)
        t = np.asarray(success, dtype=bool).ravel()
        if len(t) != len(U) or len(t) < 1:
            raise ValueError(f"{self.name}: need at least one point with one label per row of X "
                             f"(got {len(U)}, {len(t)})")
        self.n_train, self.n_success = len(t), int(t.sum())
        if self.n_success in (0, self.n_train):
            self.gpc, self.constant = None, (self.n_success + 1.0) / (self.n_train + 2.0)
            return self
        s = self.settings
        kernel = (ConstantKernel(_geometric_mean(s.constant_value_bounds), s.constant_value_bounds)
                  * Matern(length_scale=np.full(U.shape[1], _geometric_mean(s.length_scale_bounds)),
                           length_scale_bounds=s.length_scale_bounds, nu=s.nu))
        self.gpc = GaussianProcessClassifier(kernel, n_restarts_optimizer=s.n_restarts_optimizer, random_state=s.seed)
        with threadpool_limits(limits=1, user_api="blas"), warnings.catch_warnings():
            warnings.simplefilter("ignore", ConvergenceWarning)   # a length scale at a bound: see surrogate.gp
            self.gpc.fit(U, t)
        self.constant = None
        return self

    def probability(self, X):
        """P(success) at X (n,) [1]."""
        if self.n_train == 0:
            raise RuntimeError(f"{self.name}: fit the classifier first")
        U = self._box.scale(X)
        if self.gpc is None:
            return np.full(len(U), self.constant)
        return self.gpc.predict_proba(U)[:, list(self.gpc.classes_).index(True)]

    def metadata(self):
        """JSON-able description (surrogate.store)."""
        return {"name": self.name, "units": self.units, "kind": "GaussianProcessClassifier (Laplace, logistic)",
                "bounds": self.bounds.tolist(), "n_train": self.n_train, "n_success": self.n_success,
                "kernel": str(self.gpc.kernel_) if self.gpc is not None else None,
                "constant_probability": self.constant,
                "settings": {k: getattr(self.settings, k) for k in ("nu", "length_scale_bounds", "constant_value_bounds",
                                                                     "n_restarts_optimizer", "seed")},
                "sklearn_version": sklearn.__version__}
