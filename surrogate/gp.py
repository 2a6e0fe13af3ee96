"""Gaussian-process regression surrogate of one simulation output (issue 5, item 2).

Model (Rasmussen & Williams 2006, "Gaussian Processes for Machine Learning", ch. 2, 4, 5):

- inputs scaled to the unit cube from the design bounds, u = (x - low) / (high - low);
- output z = ln(y) for outputs positive by physics (then every prediction is positive), else
  z = y; z standardised by ``normalize_y``;
- kernel k(u, u') = s^2 Matern_nu(u, u'; l_1..l_d) + sigma_n^2 delta(u, u'): anisotropic
  Matern (R&W eq. 4.14) with one length scale per input and a white-noise term, hyper-
  parameters by maximum marginal likelihood (R&W eq. 5.8) with restarts.

Predictions: in z the posterior is normal N(mu, sd^2) (R&W eq. 2.25, 2.26); for a log output
y is log-normal, mean exp(mu + sd^2/2), variance (exp(sd^2) - 1) exp(2 mu + sd^2), and the
central interval the exponential of the normal one. A search ranks and judges designs in z
(studies.loop, surrogate.acquisition), never by the log-normal mean: exp(mu + sd^2/2) grows
with the uncertainty, so it would rank an unexplored design worse than a known one of the
same median exp(mu).

Calibration (issue 16 item 1): a GP fitted by maximum likelihood to a deterministic, slightly
rough simulation is often overconfident (the pinion pmax GP's 95 % interval covered 84 % in
cross-validation). With ``calibrate`` the posterior standard deviation is multiplied by one
factor per output, c = max(1, q_level(|r_i|) / Phi^-1((1 + level)/2)), with r_i the standardised
k-fold cross-validation residuals of the GP and q_level their empirical quantile: the central
``level`` interval then covers the fraction ``level`` of the held-out points (a recalibration
of the predictive scale, cf. Kuleshov, Fenner & Ermon 2018, "Accurate uncertainties for deep
learning using calibrated regression", ICML). Each fold's residuals come from a GP refitted
without the fold, its marginal-likelihood optimiser started at the full fit's hyperparameters
(one start, no restarts). Closed-form fold residuals with the full fit's hyperparameters
(Dubrule 1983, "Cross validation of kriging in a unique neighborhood") cost no refit but were
measured too optimistic: hyperparameters fitted with the fold see it, and on the main job's
training data (136 points) the 5-fold coverage of pmax and C_eff calibrated that way stayed at
0.90 and 0.88; with refitted folds 0.96 and 0.93 (three fold seeds each). The factor uses the
training data only, so k-fold cross-validation of the calibrated model (surrogate.validation)
measures its coverage on points it has not seen. The factor only widens (c >= 1): it is
estimated from the few residuals in the tail (5 % of n at level 0.95), and narrowing on such an
estimate risks the overconfidence the calibration is there to remove (a smooth noise-free test
function, 64 points: intervals that covered 1.0, narrowed by c = 0.71, covered 0.875 in
cross-validation), while intervals that are too wide only cost a search some exploration.
"""
import copy
import warnings
from dataclasses import asdict, dataclass

import numpy as np
import sklearn
from scipy.stats import norm
from sklearn.exceptions import ConvergenceWarning
from sklearn.gaussian_process import GaussianProcessRegressor
from sklearn.gaussian_process.kernels import ConstantKernel, Matern, WhiteKernel
from sklearn.model_selection import KFold
from threadpoolctl import threadpool_limits


@dataclass(frozen=True)
class GPSettings:
    """Kernel and optimiser settings (config node ``study.surrogate``).

    Attributes
    ----------
    nu : float
        Matern smoothness [1] (0.5, 1.5, 2.5 or inf).
    length_scale_bounds : tuple of float
        Bounds of each length scale on the unit-cube inputs [1].
    constant_value_bounds : tuple of float
        Bounds of the signal variance s^2 of the standardised output [1].
    noise_level_bounds : tuple of float
        Bounds of the white-noise variance sigma_n^2 of the standardised output [1].
    n_restarts_optimizer : int
        Extra random starts of the marginal-likelihood optimiser.
    seed : int
        Seed of those restarts.
    calibrate : bool
        Scale the predictive standard deviation by the cross-validation factor (module docstring).
    level : float
        Central probability of the interval whose cross-validation coverage the factor matches [1].
    folds : int
        k of the calibration's k-fold residuals (folds shuffled with ``seed``).
    """

    nu: float
    length_scale_bounds: tuple
    constant_value_bounds: tuple
    noise_level_bounds: tuple
    n_restarts_optimizer: int
    seed: int
    calibrate: bool
    level: float
    folds: int

    @classmethod
    def from_config(cls, surrogate_cfg, seed):
        """Settings from the ``study.surrogate`` node and the study seed."""
        c = surrogate_cfg
        return cls(float(c["nu"]), tuple(map(float, c["length_scale_bounds"])),
                   tuple(map(float, c["constant_value_bounds"])), tuple(map(float, c["noise_level_bounds"])),
                   int(c["n_restarts_optimizer"]), int(seed), bool(c["calibrate"]), float(c["interval"]),
                   int(c["cv_folds"]))


def _geometric_mean(bounds):
    """Start value of a hyperparameter: the geometric mean of its bounds (unbiased in log space)."""
    return float(np.sqrt(bounds[0] * bounds[1]))


class GPSurrogate:
    """GP regression of one scalar output over a box of design parameters.

    Parameters
    ----------
    bounds : array_like, shape (d, 2)
        [low, high] of each input in its own unit (mm, deg, 1).
    log : bool
        Model ln(y); the output must then be > 0 (positive by physics).
    settings : GPSettings
    name, units : str, optional
        Output name and unit, kept in the saved metadata and used for plots.
    """

    def __init__(self, bounds, log, settings, name="y", units="1"):
        self.bounds = np.asarray(bounds, dtype=float)
        if self.bounds.ndim != 2 or self.bounds.shape[1] != 2 or np.any(self.bounds[:, 1] <= self.bounds[:, 0]):
            raise ValueError(f"bounds = {self.bounds.tolist()} must be [[low, high], ...] with low < high")
        self.log = bool(log)
        self.settings = settings
        self.name = name
        self.units = units
        self.gp = None
        self.n_train = 0
        self.z_mean, self.z_std = 0.0, 1.0   # standardisation of z (R&W 2.7: zero-mean prior on it)
        self.scale_factor = 1.0              # calibration factor of the standard deviation [1]

    # ------------------------------------------------------------------ transforms
    def scale(self, X):
        """Inputs to the unit cube, u = (x - low) / (high - low) [1]."""
        X = np.atleast_2d(np.asarray(X, dtype=float))
        if X.shape[1] != self.bounds.shape[0]:
            raise ValueError(f"X has {X.shape[1]} columns, the surrogate {self.bounds.shape[0]} inputs")
        return (X - self.bounds[:, 0]) / (self.bounds[:, 1] - self.bounds[:, 0])

    def _to_latent(self, y):
        y = np.asarray(y, dtype=float)
        if self.log:
            if np.any(~(y > 0.0)):
                raise ValueError(f"{self.name}: log transform needs y > 0, got min {np.nanmin(y)!r}")
            return np.log(y)
        return y

    def _kernel(self, d):
        s = self.settings
        return (ConstantKernel(_geometric_mean(s.constant_value_bounds), s.constant_value_bounds)
                * Matern(length_scale=np.full(d, _geometric_mean(s.length_scale_bounds)),
                         length_scale_bounds=s.length_scale_bounds, nu=s.nu)
                + WhiteKernel(_geometric_mean(s.noise_level_bounds), s.noise_level_bounds))

    # ------------------------------------------------------------------ fit / predict
    def fit(self, X, y):
        """Fit to finite training data X (n, d) [input units], y (n,) [output unit]; returns self."""
        U = self.scale(X)
        y = np.asarray(y, dtype=float).ravel()
        if len(y) != len(U) or len(y) < 2:
            raise ValueError(f"{self.name}: need at least 2 points with one y per row of X (got {len(U)}, {len(y)})")
        if not (np.all(np.isfinite(U)) and np.all(np.isfinite(y))):
            raise ValueError(f"{self.name}: training data must be finite")
        z = self._to_latent(y)
        self.z_mean = float(np.mean(z))
        self.z_std = float(np.std(z)) or 1.0     # a constant output: unit scale (sklearn's normalize_y does the same)
        s = self.settings
        self.gp = GaussianProcessRegressor(kernel=self._kernel(U.shape[1]), n_restarts_optimizer=s.n_restarts_optimizer,
                                           random_state=s.seed)
        # One BLAS thread: the matrices are small (n of order 100), where threading costs more
        # than it gains (measured 7x slower on 2 busy cores). A length scale at its upper bound
        # means an input without influence and is a valid optimum, so sklearn's warning is muted.
        with threadpool_limits(limits=1, user_api="blas"), warnings.catch_warnings():
            warnings.simplefilter("ignore", ConvergenceWarning)
            self.gp.fit(U, (z - self.z_mean) / self.z_std)
        self.n_train = len(y)
        self.scale_factor = self._calibration_factor() if s.calibrate else 1.0
        return self

    def cv_residuals(self):
        """Standardised k-fold cross-validation residuals (z_i - mu_-I) / sd_-I, each fold predicted
        by a GP refitted without it from this fit's hyperparameters (module docstring),
        uncalibrated [1]; k = min(folds, n)."""
        U, zs = self.gp.X_train_, self.gp.y_train_
        r = np.empty(len(zs))
        folds = KFold(min(self.settings.folds, len(zs)), shuffle=True, random_state=self.settings.seed)
        with threadpool_limits(limits=1, user_api="blas"), warnings.catch_warnings():
            warnings.simplefilter("ignore", ConvergenceWarning)
            for train, test in folds.split(U):
                gp = GaussianProcessRegressor(kernel=self.gp.kernel_, n_restarts_optimizer=0).fit(U[train], zs[train])
                mu, sd = gp.predict(U[test], return_std=True)
                r[test] = (zs[test] - mu) / sd
        return r

    def _calibration_factor(self):
        """c = max(1, q_level(|r|) / Phi^-1((1 + level) / 2)) (module docstring)."""
        level = self.settings.level
        return max(1.0, float(np.quantile(np.abs(self.cv_residuals()), level) / norm.ppf(0.5 + 0.5 * level)))

    def predict_latent(self, X):
        """Posterior mean and (calibrated) standard deviation of z (ln y for a log output) at X."""
        if self.gp is None:
            raise RuntimeError(f"{self.name}: fit the surrogate first")
        mu, sd = self.gp.predict(self.scale(X), return_std=True)
        return self.z_mean + self.z_std * mu, self.scale_factor * self.z_std * sd

    def conditioned(self, X, z):
        """A copy conditioned on extra observations (X, z) in the latent scale, with this fit's
        hyperparameters, standardisation and calibration factor (no refit): the fantasised
        points of a kriging-believer batch (surrogate.acquisition)."""
        X = np.atleast_2d(np.asarray(X, dtype=float))
        out = copy.copy(self)
        out.gp = GaussianProcessRegressor(kernel=self.gp.kernel_, optimizer=None)
        U = np.vstack([self.gp.X_train_, self.scale(X)])
        zs = np.concatenate([self.gp.y_train_, (np.asarray(z, dtype=float) - self.z_mean) / self.z_std])
        with threadpool_limits(limits=1, user_api="blas"):
            out.gp.fit(U, zs)
        out.n_train = len(zs)
        return out

    def predict(self, X):
        """Predicted mean and standard deviation of y at X [output unit].

        Log outputs: log-normal moments, mean = exp(mu + sd^2/2) > 0 and
        std = mean sqrt(exp(sd^2) - 1).
        """
        mu, sd = self.predict_latent(X)
        if not self.log:
            return mu, sd
        mean = np.exp(mu + 0.5 * sd**2)
        return mean, mean * np.sqrt(np.expm1(sd**2))

    def interval(self, X, level):
        """Central prediction interval of probability ``level`` at X: (lower, upper) [output unit]."""
        if not 0.0 < level < 1.0:
            raise ValueError(f"interval level = {level!r} must be in (0, 1)")
        mu, sd = self.predict_latent(X)
        half = norm.ppf(0.5 + 0.5 * level) * sd
        lo, hi = mu - half, mu + half
        return (np.exp(lo), np.exp(hi)) if self.log else (lo, hi)

    # ------------------------------------------------------------------ persistence
    def metadata(self):
        """JSON-able description: output, transform, bounds, fitted kernel, settings, versions.

        Saving and loading: :mod:`surrogate.store` (``save_surrogates``, ``load_surrogates``).
        """
        return {"name": self.name, "units": self.units, "log": self.log, "bounds": self.bounds.tolist(),
                "n_train": self.n_train, "kernel": str(self.gp.kernel_) if self.gp is not None else None,
                "log_marginal_likelihood": (float(self.gp.log_marginal_likelihood_value_)
                                            if self.gp is not None else None),
                "z_mean": self.z_mean, "z_std": self.z_std, "calibration_factor": self.scale_factor,
                "settings": asdict(self.settings), "sklearn_version": sklearn.__version__}
