"""k-fold cross-validation of GP surrogates: R^2, RMSE and interval coverage (issue 5 item 2, issue 16 item 1)."""
from dataclasses import dataclass

import numpy as np
from sklearn.model_selection import KFold

from surrogate.gp import GPSurrogate


@dataclass(frozen=True)
class CrossValidation:
    """Out-of-fold predictions and their scores, in the output's own unit.

    Attributes
    ----------
    y, mean, lower, upper : ndarray
        Observed value, point prediction and central interval of each point, predicted by the
        model fitted without that point's fold. The point prediction is the posterior mean of
        the modelled z, i.e. the median exp(mu) for a log output (as a search ranks designs,
        surrogate.gp), not the log-normal mean.
    level : float
        Probability of the interval [1].
    r2 : float
        1 - sum (y - mean)^2 / sum (y - ybar)^2 [1]; NaN when y is constant.
    rmse : float
        sqrt(mean (y - mean)^2) [output unit].
    coverage : float
        Fraction of points inside their interval [1] (ideally ``level``).
    """

    y: np.ndarray
    mean: np.ndarray
    lower: np.ndarray
    upper: np.ndarray
    level: float
    r2: float
    rmse: float
    coverage: float


def cross_validate(X, y, bounds, log, settings, n_splits, level, name="y", units="1"):
    """k-fold cross-validation of :class:`GPSurrogate` on (X, y).

    Parameters
    ----------
    X : array_like, shape (n, d)
        Inputs [their units].
    y : array_like, shape (n,)
        Output [its unit].
    bounds, log, settings, name, units
        As for :class:`GPSurrogate`.
    n_splits : int
        Number of folds k (2 <= k <= n); folds shuffled with ``settings.seed``.
    level : float
        Interval probability, e.g. 0.95.

    Returns
    -------
    CrossValidation
    """
    X = np.atleast_2d(np.asarray(X, dtype=float))
    y = np.asarray(y, dtype=float).ravel()
    if not 2 <= n_splits <= len(y):
        raise ValueError(f"cv_folds = {n_splits!r} must be in [2, {len(y)}] (number of points)")
    mean, lower, upper = (np.empty_like(y) for _ in range(3))
    for train, test in KFold(n_splits, shuffle=True, random_state=settings.seed).split(X):
        model = GPSurrogate(bounds, log, settings, name, units).fit(X[train], y[train])
        mu = model.predict_latent(X[test])[0]
        mean[test] = np.exp(mu) if log else mu
        lower[test], upper[test] = model.interval(X[test], level)
    ss_res = float(np.sum((y - mean) ** 2))
    ss_tot = float(np.sum((y - y.mean()) ** 2))
    return CrossValidation(y=y, mean=mean, lower=lower, upper=upper, level=float(level),
                           r2=1.0 - ss_res / ss_tot if ss_tot > 0.0 else float("nan"),
                           rmse=float(np.sqrt(ss_res / len(y))),
                           coverage=float(np.mean((y >= lower) & (y <= upper))))


def cross_validate_outputs(sets, bounds, settings, n_splits, level, progress=None):
    """:func:`cross_validate` of every output of a study: {name: CrossValidation}; ``progress(name,
    number of points)``, if given, is called before each output's (a long study's report shows it).

    ``sets`` is {name: (X, y, log, units)} (studies.loop.DesignSearch.training_sets); outputs
    with fewer than ``n_splits`` points are left out. The coverage of each is the fraction of
    its points inside the central ``level`` interval predicted without their fold; with
    ``settings.calibrate`` the calibration factor is found from the training folds only, so
    this measures the calibrated intervals on unseen points.
    """
    result = {}
    for q, (X, y, log, units) in sets.items():
        if len(y) >= n_splits:
            if progress is not None:
                progress(q, len(y))
            result[q] = cross_validate(X, y, bounds, log, settings, n_splits, level, q, units)
    return result
