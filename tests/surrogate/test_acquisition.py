"""Constrained Bayesian optimisation (surrogate/acquisition.py, surrogate/classifier.py): the
formulas against closed forms, the search on an analytic problem with a thin feasible region
and a known optimum, the batch and the classifier of failed simulations.

GP settings are those of conf/study/pinion.yaml (restarts 0 where a test fits many GPs, to stay
fast), so the tests check the configuration the design search uses.
"""
import dataclasses

import numpy as np
import pytest
from omegaconf import OmegaConf
from scipy.stats import norm, qmc

import sim
from surrogate import CandidateSettings, Constraint, GPSettings, GPSurrogate, SuccessClassifier, propose
from surrogate.acquisition import log_acquisition, log_expected_improvement, log_h, log_probability_between, polish

STUDY = OmegaConf.load(sim.CONF_DIR / "study" / "pinion.yaml")
SETTINGS = dataclasses.replace(GPSettings.from_config(STUDY.surrogate, seed=0), n_restarts_optimizer=0)
CANDIDATES = CandidateSettings.from_config(STUDY.acquisition)


# ---------------------------------------------------------------------------- formulas
def test_log_expected_improvement_equals_the_closed_form_and_stays_finite_in_the_tail():
    """EI = sd (u Phi(u) + phi(u)), u = (best - mu) / sd (Jones et al. 1998 eq. 15) where it is
    representable; far in the tail log h(u) -> -u^2/2 - ln sqrt(2 pi) - 2 ln|u| (Mills ratio
    asymptotics), where the direct formula gives log(0) = -inf."""
    mu = np.linspace(-3.0, 6.0, 37)
    sd = np.full_like(mu, 0.7)
    u = (1.0 - mu) / sd
    direct = sd * (u * norm.cdf(u) + norm.pdf(u))
    np.testing.assert_allclose(np.exp(log_expected_improvement(mu, sd, 1.0)), direct, rtol=1e-10)
    tail = np.array([-40.0, -1e3, -1e9])
    asymptotic = -0.5 * tail**2 - 0.5 * np.log(2 * np.pi) - 2.0 * np.log(-tail)
    np.testing.assert_allclose(log_h(tail), asymptotic, rtol=1e-3)
    assert np.all(np.diff(log_h(np.linspace(-60.0, 5.0, 500))) > 0.0)   # h is increasing


def test_log_probability_between_matches_normal_cdf_also_deep_in_both_tails():
    mu, sd = np.zeros(4), np.ones(4)
    low, high = np.array([-1.0, -np.inf, 2.0, -40.0]), np.array([1.0, 0.5, np.inf, -39.0])
    expected = norm.cdf(high) - norm.cdf(low)
    np.testing.assert_allclose(np.exp(log_probability_between(mu, sd, low, high)), expected, rtol=1e-12)
    # both limits 30-31 sd above the mean: P = sf(30) - sf(31), about 1e-197, still a finite log
    got = log_probability_between(0.0, 1.0, 30.0, 31.0)
    ref = norm.logsf(30.0) + np.log1p(-np.exp(norm.logsf(31.0) - norm.logsf(30.0)))
    assert got == pytest.approx(ref, rel=1e-10) and got < -400.0


# ---------------------------------------------------------------------------- the search
# On [0, 1]^2: minimise f = 1 + x1 + x2 subject to 0.29 <= |x - (0.5, 0.5)| <= 0.31, a ring of
# width 0.02 covering pi (0.31^2 - 0.29^2) = 3.8 % of the box (the pinion's feasible region is
# thinner still, but in 5 dimensions). The optimum is where the outer circle meets the steepest
# descent direction: x* = (0.5, 0.5) - 0.31 (1, 1) / sqrt 2, f* = 2 - 0.31 sqrt 2 = 1.5616.
BOX = np.array([[0.0, 1.0], [0.0, 1.0]])
CENTRE, RADIUS, WIDTH = np.array([0.5, 0.5]), 0.30, 0.01
F_STAR = 2.0 - (RADIUS + WIDTH) * np.sqrt(2.0)
RING = [Constraint("r", RADIUS - WIDTH, RADIUS + WIDTH)]


def ring_problem(X):
    r = np.linalg.norm(X - CENTRE, axis=1)
    return 1.0 + X[:, 0] + X[:, 1], r, np.abs(r - RADIUS) <= WIDTH


def run_search(seed, n_initial, budget, q):
    """The loop of studies.loop on the ring problem: fit, propose q, evaluate, until ``budget``."""
    X = qmc.Sobol(2, seed=seed).random(n_initial)
    while len(X) < budget:
        f, r, feasible = ring_problem(X)
        models = {"f": GPSurrogate(BOX, False, SETTINGS, "f").fit(X, f), "r": GPSurrogate(BOX, False, SETTINGS, "r").fit(X, r)}
        incumbent = float(f[feasible].min()) if feasible.any() else None
        violation = np.maximum(np.abs(r - RADIUS) - WIDTH, 0.0)
        centre = X[np.argmin(np.where(feasible, f, np.inf))] if feasible.any() else X[np.argmin(violation)]
        new, _ = propose(models, "f", RING, None, incumbent, centre, BOX, X, q, CANDIDATES, lambda x: True,
                         1e-3, seed * 1000 + len(X))
        X = np.vstack([X, new])
    f, _, feasible = ring_problem(X)
    return X, np.minimum.accumulate(np.where(feasible, f, np.inf))


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_reaches_the_constrained_optimum_of_a_thin_feasible_ring(seed):
    """8 Sobol points (not within 1 % of f*, mostly infeasible), then rounds of q = 2: within 1 % of
    f* after 24 evaluations, every seed; never below f* (no infeasible point counted)."""
    X, best = run_search(seed, 8, 24, 2)
    assert len(X) == 24
    assert best[7] > 1.01 * F_STAR           # the initial design alone is not there (inf: nothing feasible)
    assert best[-1] >= F_STAR - 1e-12
    assert best[-1] <= 1.01 * F_STAR, f"seed {seed}: best {best[-1]:.5f}, f* {F_STAR:.5f}"


def test_batch_holds_q_distinct_designs_by_the_kriging_believer():
    """With no minimum distance the batch differs only because each choice is fantasised
    (kriging believer): q = 4 distinct designs, none repeated, all in the box; without the
    fantasy (q = 1 four times on the same models) the same design comes back every time."""
    X = qmc.Sobol(2, seed=5).random(16)
    f, r, feasible = ring_problem(X)
    models = {"f": GPSurrogate(BOX, False, SETTINGS, "f").fit(X, f), "r": GPSurrogate(BOX, False, SETTINGS, "r").fit(X, r)}
    incumbent = float(f[feasible].min()) if feasible.any() else None
    batch, log_a = propose(models, "f", RING, None, incumbent, X[0], BOX, X, 4, CANDIDATES, lambda x: True, 0.0, 7)
    assert batch.shape == (4, 2) and np.all((batch >= 0.0) & (batch <= 1.0))
    gaps = [np.max(np.abs(batch[i] - batch[j])) for i in range(4) for j in range(i)]
    assert min(gaps) > 1e-6
    singles = [propose(models, "f", RING, None, incumbent, X[0], BOX, X, 1, CANDIDATES, lambda x: True, 0.0, 7)[0]
               for _ in range(4)]
    assert all(np.array_equal(s, singles[0]) for s in singles) and np.array_equal(singles[0][0], batch[0])
    assert np.all(np.isfinite(log_a))


def test_inadmissible_and_pending_designs_are_never_proposed():
    """``admissible`` (exact checks, e.g. the geometry) vetoes a design; a pending design (being
    simulated elsewhere) keeps every proposal at least min_distance away."""
    X = qmc.Sobol(2, seed=3).random(16)
    f, r, _ = ring_problem(X)
    models = {"f": GPSurrogate(BOX, False, SETTINGS, "f").fit(X, f), "r": GPSurrogate(BOX, False, SETTINGS, "r").fit(X, r)}
    left = lambda x: x[0] < 0.5                                      # noqa: E731
    batch, _ = propose(models, "f", RING, None, None, None, BOX, X, 3, CANDIDATES, left, 0.05, 1)
    assert len(batch) == 3 and np.all(batch[:, 0] < 0.5)
    first = propose(models, "f", RING, None, None, None, BOX, X, 1, CANDIDATES, lambda x: True, 0.05, 1)[0]
    again, _ = propose(models, "f", RING, None, None, None, BOX, X, 2, CANDIDATES, lambda x: True, 0.05, 1, first)
    assert np.all(np.max(np.abs(again - first), axis=1) >= 0.05)


# ---------------------------------------------------------------------------- polish of the acquisition maximum
def two_bumps(U):
    """log of two Gaussian bumps, one at (0.25, 0.3) and a higher one centred outside the box at
    (0.7, 1.2): its maximum in the box is on the bound x2 = 1 at x1 = 0.7."""
    a = -np.sum((U - [0.25, 0.3]) ** 2, axis=1) / 0.02
    b = 1.0 - np.sum((U - [0.7, 1.2]) ** 2, axis=1) / 0.02
    return np.logaddexp(a, b)


def test_polish_takes_each_start_to_the_maximum_of_its_own_basin_within_the_box():
    """The starts are optimised together on the sum of their values, which is separable: each
    ends at its own bump's maximum (the sum is not traded between starts), the box kept."""
    U = polish(two_bumps, np.array([[0.2, 0.35], [0.6, 0.8], [0.75, 0.95]]), 50)
    assert np.all((U >= 0.0) & (U <= 1.0))
    np.testing.assert_allclose(U[0], [0.25, 0.3], atol=1e-3)
    np.testing.assert_allclose(U[1:], [[0.7, 1.0], [0.7, 1.0]], atol=1e-3)


def test_polished_choice_is_never_worse_than_the_candidate_sets_best():
    """With the polish the first design of a batch has a log acquisition at least that of the
    best candidate of the set (the polished points join the set), on the same models and seed."""
    X = qmc.Sobol(2, seed=5).random(16)
    f, r, feasible = ring_problem(X)
    models = {"f": GPSurrogate(BOX, False, SETTINGS, "f").fit(X, f), "r": GPSurrogate(BOX, False, SETTINGS, "r").fit(X, r)}
    incumbent = float(f[feasible].min()) if feasible.any() else None
    plain = dataclasses.replace(CANDIDATES, n_polish=0)
    polished = dataclasses.replace(CANDIDATES, n_polish=4)
    _, a0 = propose(models, "f", RING, None, incumbent, X[0], BOX, X, 1, plain, lambda x: True, 1e-3, 7)
    _, a1 = propose(models, "f", RING, None, incumbent, X[0], BOX, X, 1, polished, lambda x: True, 1e-3, 7)
    assert a1[0] >= a0[0]


def test_batch_distance_keeps_the_designs_of_one_batch_apart():
    """acquisition.batch_distance: every two designs of a batch at least that far apart (max norm,
    unit cube), where the kriging believer alone puts them closer on the same models and seed."""
    X = qmc.Sobol(2, seed=5).random(16)
    f, r, feasible = ring_problem(X)
    models = {"f": GPSurrogate(BOX, False, SETTINGS, "f").fit(X, f), "r": GPSurrogate(BOX, False, SETTINGS, "r").fit(X, r)}
    incumbent = float(f[feasible].min()) if feasible.any() else None

    def closest(batch):
        return min(np.max(np.abs(batch[i] - batch[j])) for i in range(len(batch)) for j in range(i))

    free, _ = propose(models, "f", RING, None, incumbent, X[0], BOX, X, 4,
                      dataclasses.replace(CANDIDATES, batch_distance=0.0), lambda x: True, 1e-3, 7)
    spread, _ = propose(models, "f", RING, None, incumbent, X[0], BOX, X, 4,
                        dataclasses.replace(CANDIDATES, batch_distance=0.2, n_diverse=None), lambda x: True, 1e-3, 7)
    assert closest(free) < 0.2 and len(spread) == 4 and closest(spread) >= 0.2
    half, _ = propose(models, "f", RING, None, incumbent, X[0], BOX, X, 4,
                      dataclasses.replace(CANDIDATES, batch_distance=0.2, n_diverse=2), lambda x: True, 1e-3, 7)
    np.testing.assert_array_equal(half[:2], free[:2])          # the first q - n_diverse: the believer's alone
    assert all(np.max(np.abs(half[k] - half[j])) >= 0.2 for k in (2, 3) for j in range(k))


# ---------------------------------------------------------------------------- failures
def fails(X):
    """Simulations fail inside a disk of radius 0.3 around (0.7, 0.3) (a region of unconverged designs)."""
    return np.linalg.norm(X - np.array([0.7, 0.3]), axis=1) < 0.3


def test_classifier_learns_a_failure_region():
    """GP classification of 64 Sobol points: P(success) < 0.2 at the disk's centre, > 0.8 far from
    it, and the 0.5 contour classifies 90 % of 1024 fresh points right (the disk is 28 % of the box)."""
    X = qmc.Sobol(2, seed=0).random(64)
    clf = SuccessClassifier(BOX, SETTINGS).fit(X, ~fails(X))
    p = clf.probability(np.array([[0.7, 0.3], [0.1, 0.9], [0.2, 0.8]]))
    assert p[0] < 0.2 and np.all(p[1:] > 0.8)
    Xt = qmc.Sobol(2, seed=1).random(1024)
    accuracy = np.mean((clf.probability(Xt) > 0.5) == ~fails(Xt))
    assert accuracy > 0.9


def test_acquisition_is_weighted_by_the_probability_of_success():
    """An objective whose minimum lies inside the failure disk: the log acquisition with the
    classifier is the one without plus log P(success) at every design, and its best design moves
    from deep inside the disk (P(success) < 0.05) to where success is at least 10x as likely."""
    X = qmc.Sobol(2, seed=0).random(64)
    ok = ~fails(X)
    f = 1.0 + (X[:, 0] - 0.7) ** 2 + (X[:, 1] - 0.3) ** 2
    model = {"f": GPSurrogate(BOX, False, SETTINGS, "f").fit(X[ok], f[ok])}
    clf = SuccessClassifier(BOX, SETTINGS).fit(X, ok)
    grid = qmc.Sobol(2, seed=2).random(4096)
    free = log_acquisition(model, "f", [], None, float(f[ok].min()), grid)
    weighted = log_acquisition(model, "f", [], clf, float(f[ok].min()), grid)
    p = clf.probability(grid)
    np.testing.assert_allclose(weighted, free + np.log(p), rtol=1e-12)
    i, j = np.argmax(free), np.argmax(weighted)
    assert fails(grid[i][None, :])[0] and p[i] < 0.05
    assert p[j] >= 10.0 * p[i]


def test_classifier_with_one_class_is_the_rule_of_succession():
    X = qmc.Sobol(2, seed=0).random(8)
    clf = SuccessClassifier(BOX, SETTINGS).fit(X, np.ones(8, dtype=bool))
    np.testing.assert_array_equal(clf.probability(X[:3]), np.full(3, 9.0 / 10.0))
    with pytest.raises(ValueError, match="one label per row"):
        SuccessClassifier(BOX, SETTINGS).fit(X, np.ones(7, dtype=bool))


def test_a_zero_standard_deviation_gives_finite_or_minus_infinite_logs_not_nan():
    """sd = 0 (a GP exactly at its data): EI is max(best - mu, 0), the probability 0 or 1."""
    assert log_expected_improvement(0.0, 0.0, 1.0) == pytest.approx(0.0, abs=1e-12)          # log(1 - 0)
    assert log_expected_improvement(2.0, 0.0, 1.0) == -np.inf                                 # no improvement possible
    assert log_probability_between(0.0, 0.0, -1.0, 1.0) == pytest.approx(0.0, abs=1e-12)
    assert log_probability_between(2.0, 0.0, -1.0, 1.0) == -np.inf
