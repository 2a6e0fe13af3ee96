"""Constrained Bayesian optimisation: where to simulate next (issue 16 item 1).

Acquisition. Constrained expected improvement (Schonlau, Welch & Jones 1998, "Global versus
local search in constrained optimization of computer models"; Gardner, Kusner, Xu, Weinberger
& Cunningham 2014, "Bayesian optimization with inequality constraints", ICML; Gelbart, Snoek &
Adams 2014, "Bayesian optimization with unknown constraints", UAI)::

    a(x) = EI(x) * prod_c P(l_c <= y_c(x) <= h_c) * P(success | x)

with EI on the objective's GP, one GP per constrained output (its limits l_c, h_c; the
probability from the normal posterior of the latent z, exactly, also for a log output, whose
limits are then taken to ln) and P(success) from a GP classifier of failed or unconverged
simulations (surrogate.classifier). While no feasible point is known the EI factor is left out
and the product of probabilities alone is maximised, to find the feasible region first (Gardner
et al. 2014, 3; Gelbart et al. 2014, 3). Everything is computed as a logarithm: EI as LogEI
(Ament, Daulton, Eriksson, Balandat & Bakshy 2023, "Unexpected improvements to expected
improvement for Bayesian optimization", NeurIPS, 4) and the probabilities with log Phi
(scipy.special.log_ndtr), so that designs far from the incumbent or deep in a thin feasible
region's tails are still ranked (a probability of 1e-20 underflows nothing here).

Why this and not a trust region (SCBO, Eriksson & Poloczek 2021, "Scalable constrained
Bayesian optimization", AISTATS): SCBO is built for tens to hundreds of inputs and thousands of
evaluations, where one global GP is too costly and too uninformative; a study here has 5 inputs
and of order 100 simulations, the regime of global GP-based constrained EI (Gardner et al.
2014; Gelbart et al. 2014). From SCBO and TuRBO (Eriksson et al. 2019) the candidate set keeps
the local part: the feasible region of the pinion study is a thin sliver (0.03 % of the box), so
a dense set of perturbations around the incumbent (Gaussian, several scales in unit
coordinates) joins a scrambled Sobol set over the whole box, and a second set is drawn around
the best candidates of the first; the acquisition is maximised over that set. Before each
choice the best candidates that lie at least the largest local scale apart are polished by
L-BFGS-B on the log acquisition (:func:`polish`, ``n_polish`` starts, as BoTorch's
``optimize_acqf`` and Optuna's GPSampler do), and the polished points join the set.

Batches. q designs per round for parallel workers: kriging believer (Ginsbourger, Le Riche &
Carraro 2010, "Kriging is well-suited to parallelize optimization", 3.2): after each choice
every regression GP is conditioned on its own posterior mean there (hyperparameters kept), so
its variance near the chosen design collapses and the next choice goes elsewhere; when the
means say the design is feasible it becomes the believed incumbent. Every chosen design is at
least ``min_distance`` (max-norm, unit cube) from every simulated and every chosen one. Designs
being simulated elsewhere (asynchronous workers, ``X_pending``) are fantasised the same way
before the first choice. The kriging believer alone can keep a whole batch in one basin (the
acquisition near the chosen designs stays as high as in another basin): the last ``n_diverse``
designs of a batch are therefore also held at least ``batch_distance`` (max norm, unit cube) from
every earlier design of the same batch, a hard-radius form of local penalisation (Gonzalez,
Dai, Hennig & Lawrence 2016, "Batch Bayesian optimization via local penalization", AISTATS).
"""
from dataclasses import dataclass

import numpy as np
from scipy.optimize import minimize
from scipy.special import erfcx, log_ndtr
from scipy.stats import qmc
from threadpoolctl import threadpool_limits

_C1 = 0.5 * np.log(2.0 * np.pi)
_C2 = 0.5 * np.log(0.5 * np.pi)
_ASYMPTOTIC = -1.0 / np.sqrt(np.finfo(float).eps)   # below: log h(u) = log phi(u) - 2 ln|u| (Ament et al. 2023)
_SD_MIN = 1e-300   # a posterior standard deviation of 0 (a GP without noise at its own data) is taken as this


def _log1mexp(x):
    """log(1 - exp(x)) for x <= 0, accurate at both ends (Maechler 2012, "Accurately computing log(1 - exp(-|a|))")."""
    x = np.asarray(x, dtype=float)
    with np.errstate(divide="ignore"):
        return np.where(x > -np.log(2.0), np.log(-np.expm1(np.minimum(x, -1e-300))), np.log1p(-np.exp(x)))


def log_h(u):
    """log(u Phi(u) + phi(u)), the standardised expected improvement, for any real u (Ament et al. 2023, 4.1)."""
    u = np.asarray(u, dtype=float)
    out = np.empty_like(u)
    with np.errstate(over="ignore"):                          # |u| beyond 1e154: u^2 = inf, the limits are exact
        big = u > -1.0
        ub = u[big]
        out[big] = np.log(ub * np.exp(log_ndtr(ub)) + np.exp(-0.5 * ub**2 - _C1))
        mid = (~big) & (u > _ASYMPTOTIC)
        um = u[mid]
        out[mid] = -0.5 * um**2 - _C1 + _log1mexp(np.log(erfcx(-um / np.sqrt(2.0)) * np.abs(um)) + _C2)
        tail = ~(big | mid)
        out[tail] = -0.5 * u[tail] ** 2 - _C1 - 2.0 * np.log(np.abs(u[tail]))
    return out


def log_expected_improvement(mu, sd, best):
    """log E[max(best - Z, 0)] for Z ~ N(mu, sd^2) (minimisation): log sd + log h((best - mu) / sd)."""
    mu, sd = np.asarray(mu, dtype=float), np.maximum(np.asarray(sd, dtype=float), _SD_MIN)
    return np.log(sd) + log_h((best - mu) / sd)


def log_probability_between(mu, sd, low, high):
    """log P(low <= Z <= high) for Z ~ N(mu, sd^2); low, high may be -inf, inf (broadcast)."""
    mu, sd = np.asarray(mu, dtype=float), np.maximum(np.asarray(sd, dtype=float), _SD_MIN)
    a, b = np.broadcast_arrays((low - mu) / sd, (high - mu) / sd)
    flip = a > 0.0                        # both limits in the upper tail: use P = Phi(-a) - Phi(-b)
    a, b = np.where(flip, -b, a), np.where(flip, -a, b)
    lb, la = log_ndtr(b), log_ndtr(a)
    with np.errstate(invalid="ignore"):
        out = lb + _log1mexp(np.minimum(la - lb, 0.0))
    return np.where(lb == -np.inf, -np.inf, out)             # both limits far below: P = 0


@dataclass(frozen=True)
class Constraint:
    """low <= y <= high on one modelled output y [its unit].

    ``low`` and ``high`` are numbers (-inf, inf for no limit) or callables ``f(X) -> (n,)`` of
    the designs X (n, d) [input units], for a limit that depends on the design.
    """

    output: str
    low: object = -np.inf
    high: object = np.inf

    def limits(self, X):
        """(low, high) at the designs X, each (n,) [output unit]."""
        return tuple(np.broadcast_to(np.asarray(v(X) if callable(v) else v, dtype=float), (len(X),))
                     for v in (self.low, self.high))


def _latent_limits(model, low, high):
    """Limits in the model's latent scale: ln for a log output (a limit <= 0 is no limit below, impossible above)."""
    if not model.log:
        return low, high
    with np.errstate(divide="ignore", invalid="ignore"):
        return (np.where(low > 0.0, np.log(np.maximum(low, 1e-300)), -np.inf),
                np.where(high > 0.0, np.log(np.maximum(high, 1e-300)), -np.inf))


def log_probability_feasible(models, constraints, X):
    """sum_c log P(constraint c holds at X) from the regression surrogates ``models`` {output: GPSurrogate}."""
    total = np.zeros(len(X))
    for c in constraints:
        m = models[c.output]
        mu, sd = m.predict_latent(X)
        lo, hi = _latent_limits(m, *c.limits(X))
        total += log_probability_between(mu, sd, lo, hi)
    return total


def mean_feasible(models, constraints, X):
    """Whether the posterior means (latent medians) satisfy every constraint at X (n,)."""
    ok = np.ones(len(X), dtype=bool)
    for c in constraints:
        m = models[c.output]
        mu, _ = m.predict_latent(X)
        lo, hi = _latent_limits(m, *c.limits(X))
        ok &= (mu >= lo) & (mu <= hi)
    return ok


def log_acquisition(models, objective, constraints, classifier, incumbent, X):
    """log a(X) (module docstring); ``incumbent`` is the best feasible latent objective, or None
    while no feasible design is known (then EI is left out)."""
    out = log_probability_feasible(models, constraints, X)
    if classifier is not None:
        with np.errstate(divide="ignore"):
            out = out + np.log(classifier.probability(X))
    if incumbent is not None:
        mu, sd = models[objective].predict_latent(X)
        out = out + log_expected_improvement(mu, sd, incumbent)
    return out


@dataclass(frozen=True)
class CandidateSettings:
    """The dense candidate set over which the acquisition is maximised (config ``study.acquisition``).

    Attributes
    ----------
    n_global : int
        Scrambled Sobol points over the box.
    n_local : int
        Gaussian perturbations around the centre (the incumbent), split evenly over ``scales``;
        as many again around the ``n_centres`` best candidates of the first set.
    scales : tuple of float
        Standard deviations of the perturbations in unit-cube coordinates [1].
    n_centres : int
        Best first-set candidates around which the second set is drawn.
    n_polish : int
        Best candidates from which the acquisition is maximised locally before each choice
        (:func:`polish`); 0: the best candidate of the set is taken as it is.
    polish_iterations : int
        L-BFGS-B iterations of that local maximisation at most.
    batch_distance : float
        Least max-norm distance in unit coordinates [1] of each of the last ``n_diverse`` designs
        of a batch from every earlier design of the batch; 0: only the kriging believer spreads it.
    n_diverse : int or None
        Designs of a batch, counted from its end, held at ``batch_distance``; None: every design.
    """

    n_global: int
    n_local: int
    scales: tuple
    n_centres: int
    n_polish: int = 0
    polish_iterations: int = 50
    batch_distance: float = 0.0
    n_diverse: object = None

    @classmethod
    def from_config(cls, c):
        n_diverse = c.get("n_diverse")
        return cls(int(c["n_global"]), int(c["n_local"]), tuple(map(float, c["local_scales"])), int(c["n_centres"]),
                   int(c.get("n_polish", 0)), int(c.get("polish_iterations", 50)), float(c.get("batch_distance", 0.0)),
                   None if n_diverse is None else int(n_diverse))


def _perturbed(centres, n, scales, rng):
    """n points N(centre, s^2 I) clipped to [0, 1], cycling through the centres, split over the scales."""
    centres = np.atleast_2d(centres)
    d = centres.shape[1]
    per = np.array_split(np.arange(n), len(scales))
    out = [np.clip(centres[idx % len(centres)] + s * rng.standard_normal((len(idx), d)), 0.0, 1.0)
           for s, idx in zip(scales, per)]
    return np.vstack(out) if out else np.empty((0, d))


_FD_STEP = 1e-6       # forward-difference step of the polish gradient [1, unit cube]
_LOG_FLOOR = -1e6     # log acquisition below this (or -inf) is taken as this in the polish: a finite objective


def polish(log_a, U0, iterations):
    """Local maximisation of a log acquisition from several starts in the unit cube.

    As BoTorch's ``optimize_acqf`` (Balandat et al. 2020, "BoTorch: a framework for efficient
    Monte-Carlo Bayesian optimization", NeurIPS, appendix F: raw samples, then L-BFGS-B from the
    best of them) and Optuna's GPSampler (``optuna._gp.optim_mixed``: L-BFGS-B from the best of
    a random sample): the k starts are optimised together by L-BFGS-B (Byrd, Lu, Nocedal & Zhu
    1995) on the sum of their log acquisitions within the box, which is separable, so each start
    follows its own gradient (BoTorch's ``gen_candidates_scipy`` does the same). The gradient is
    a forward difference of step ``_FD_STEP`` (backward at the upper bound), all k (d + 1) points
    in one call of ``log_a`` (the GP predictions are vectorised; scikit-learn gives no gradient).

    Parameters
    ----------
    log_a : callable
        ``log_a(U) -> (n,)`` log acquisition at the unit-cube points U (n, d).
    U0 : array_like, shape (k, d)
        Starts in [0, 1]^d (the best candidates of the set).
    iterations : int
        L-BFGS-B iterations at most.

    Returns
    -------
    U : ndarray, shape (k, d)
        The polished points in [0, 1]^d (a start where no step improved stays where it was).
    """
    U0 = np.clip(np.atleast_2d(np.asarray(U0, dtype=float)), 0.0, 1.0)
    k, d = U0.shape
    step = np.eye(d)[None, :, :] * _FD_STEP                      # (1, d, d)

    def f_and_grad(z):
        U = np.clip(z.reshape(k, d), 0.0, 1.0)
        H = np.where(U[:, None, :] + step > 1.0, -step, step)    # (k, d, d), backward at the upper bound
        P = np.concatenate([U[:, None, :], U[:, None, :] + H], axis=1).reshape(-1, d)
        v = np.maximum(np.nan_to_num(log_a(P), nan=_LOG_FLOOR, neginf=_LOG_FLOOR), _LOG_FLOOR).reshape(k, d + 1)
        grad = (v[:, 1:] - v[:, :1]) / np.diagonal(H, axis1=1, axis2=2)
        return -float(v[:, 0].sum()), -grad.ravel()

    res = minimize(f_and_grad, U0.ravel(), jac=True, method="L-BFGS-B", bounds=[(0.0, 1.0)] * (k * d),
                   options={"maxiter": int(iterations)})
    return np.clip(res.x.reshape(k, d), 0.0, 1.0)


def distinct_rows(U, count, min_distance):
    """Indices of the first ``count`` (>= 1) rows of U, in their order (best first), that lie at
    least ``min_distance`` (max norm, unit cube) from every row taken before: one start per basin
    for a multi-start local method (the acquisition's polish here, the local stage's starts in
    studies.refine)."""
    chosen = []
    for i, u in enumerate(U):
        if all(np.max(np.abs(u - U[j])) >= min_distance for j in chosen):
            chosen.append(i)
            if len(chosen) == count:
                break
    return chosen


def _distinct_best(U, a, k, distance):
    """Indices of the k best finite-valued rows of U by ``a`` that are :func:`distinct_rows`: the
    starts of :func:`polish` lie in different basins, not all in the cloud of local candidates
    around the incumbent (BoTorch draws its starts spread out for the same reason:
    ``initialize_q_batch``, Boltzmann sampling of the raw samples)."""
    order = [i for i in np.argsort(-a, kind="stable") if np.isfinite(a[i])]
    return [order[p] for p in distinct_rows(U[order], k, distance)]


def _believe(models, X):
    """Each regression model conditioned on its own posterior mean at the designs X (kriging believer)."""
    return {k: m.conditioned(X, m.predict_latent(X)[0]) for k, m in models.items()}


def propose(models, objective, constraints, classifier, incumbent, centre, bounds, X_seen, q, settings,
            admissible, min_distance, seed, X_pending=None):
    """q designs by constrained EI over a dense candidate set, kriging-believer batch (:func:`_propose`).

    The GP predictions run on one BLAS thread, as the fits do (surrogate.gp): on the 2 busy cores
    of the target machine a prediction of 24 points at 32 training points took 18 ms with two
    OpenBLAS threads and 1.1 ms with one (the triangular solve of the posterior variance).
    """
    with threadpool_limits(limits=1, user_api="blas"):
        return _propose(models, objective, constraints, classifier, incumbent, centre, bounds, X_seen, q, settings,
                        admissible, min_distance, seed, X_pending)


def _propose(models, objective, constraints, classifier, incumbent, centre, bounds, X_seen, q, settings,
             admissible, min_distance, seed, X_pending=None):
    """q designs by constrained EI over a dense candidate set, kriging-believer batch (module docstring).

    Parameters
    ----------
    models : dict
        {output: GPSurrogate} fitted regression surrogates (objective and constrained outputs).
    objective : str
        Key of the objective's surrogate in ``models``.
    constraints : sequence of Constraint
    classifier : SuccessClassifier or None
    incumbent : float or None
        Best feasible objective observed, in the objective surrogate's latent scale (ln y for a
        log output); None while no feasible design is known.
    centre : array_like, shape (d,) or None
        Design [input units] around which the local candidates are drawn (the incumbent, or
        the least infeasible design); None: none.
    bounds : array_like, shape (d, 2)
        The box [input units].
    X_seen : array_like, shape (m, d)
        Designs already simulated [input units].
    q : int
        Designs wanted.
    settings : CandidateSettings
    admissible : callable
        ``admissible(x) -> bool`` for one design x (d,) [input units]: exact checks that need no
        simulation (possible geometry, exact constraints). Called only on the best candidates.
    min_distance : float
        Least max-norm distance in unit coordinates to every simulated and every chosen design.
    seed : int
    X_pending : array_like, shape (p, d), optional
        Designs being simulated elsewhere [input units]: fantasised and kept at ``min_distance``.

    Returns
    -------
    X : ndarray, shape (k, d), k <= q
        The chosen designs, in order of choice (k < q when no admissible candidate is left).
    log_a : ndarray, shape (k,)
        log acquisition of each at the moment it was chosen.
    """
    bounds = np.asarray(bounds, dtype=float)
    low, span = bounds[:, 0], bounds[:, 1] - bounds[:, 0]
    d = len(low)
    rng = np.random.default_rng(seed)
    U = qmc.Sobol(d, scramble=True, seed=rng).random(settings.n_global)
    if centre is not None:
        U = np.vstack([U, _perturbed((np.asarray(centre, dtype=float) - low) / span, settings.n_local,
                                     settings.scales, rng)])
    models = dict(models)
    X_seen = np.atleast_2d(np.asarray(X_seen, dtype=float)).reshape(-1, d)
    if X_pending is not None and len(X_pending):
        X_pending = np.atleast_2d(np.asarray(X_pending, dtype=float))
        models = _believe(models, X_pending)
        X_seen = np.vstack([X_seen, X_pending])
    a = log_acquisition(models, objective, constraints, classifier, incumbent, low + U * span)
    top = U[np.argsort(-a, kind="stable")[:settings.n_centres]]
    U = np.vstack([U, _perturbed(top, settings.n_local, settings.scales, rng)])
    X = low + U * span
    seen = (X_seen - low) / span
    checked = {}
    chosen, values, batch = [], [], []
    first_diverse = 0 if settings.n_diverse is None else max(q - settings.n_diverse, 0)
    for k in range(q):
        spread = k >= first_diverse
        a = log_acquisition(models, objective, constraints, classifier, incumbent, X)
        if settings.n_polish:
            starts = _distinct_best(U, a, settings.n_polish, max(settings.scales, default=0.0))
            if starts:
                def log_a(V, models=models, incumbent=incumbent):
                    return log_acquisition(models, objective, constraints, classifier, incumbent, low + V * span)
                V = polish(log_a, U[starts], settings.polish_iterations)
                U, X = np.vstack([U, V]), np.vstack([X, low + V * span])
                a = np.concatenate([a, log_a(V)])
        pick = None
        for i in np.argsort(-a, kind="stable"):
            if not np.isfinite(a[i]):
                break
            if len(seen) and np.min(np.max(np.abs(seen - U[i]), axis=1)) < min_distance:
                continue
            if spread and batch and np.min(np.max(np.abs(np.array(batch) - U[i]), axis=1)) < settings.batch_distance:
                continue
            if i not in checked:
                checked[i] = bool(admissible(X[i]))
            if checked[i]:
                pick = i
                break
        if pick is None:
            break
        x = X[pick]
        chosen.append(x)
        values.append(float(a[pick]))
        seen = np.vstack([seen, U[pick][None, :]])
        batch.append(U[pick])
        believed = float(models[objective].predict_latent(x[None, :])[0][0])
        if mean_feasible(models, constraints, x[None, :])[0] and (incumbent is None or believed < incumbent):
            incumbent = believed
        models = _believe(models, x[None, :])
    return np.array(chosen).reshape(len(chosen), d), np.array(values)
