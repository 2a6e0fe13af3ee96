"""Gaussian-process surrogates of simulation outputs (issue 5): fit, predict, validate, save.

- :class:`GPSurrogate`: one output, normalised inputs, anisotropic Matern + noise kernel,
  optional log transform; :func:`save_surrogates` / :func:`load_surrogates` for a set.
- :class:`SuccessClassifier`: probability that a design's simulation gives a result (GP classifier).
- :mod:`surrogate.acquisition`: constrained Bayesian optimisation (log EI x probability of
  feasibility x probability of success, dense candidate set, kriging-believer batches).
- :func:`cross_validate`: k-fold R^2, RMSE and coverage of the prediction interval.
- :mod:`surrogate.store`: the saved set (manifest with SHA-256 of every file, checked before
  unpickling; scikit-learn version checked on load; crash-safe replacement).
"""
from surrogate.acquisition import CandidateSettings, Constraint, distinct_rows, propose
from surrogate.classifier import SuccessClassifier
from surrogate.gp import GPSettings, GPSurrogate
from surrogate.store import (SurrogateIntegrityError, SurrogateLoadError, SurrogateVersionError,
                             SurrogateVersionWarning, load_surrogates, save_surrogates, saved_set)
from surrogate.validation import CrossValidation, cross_validate, cross_validate_outputs

__all__ = ["CandidateSettings", "Constraint", "distinct_rows", "propose", "SuccessClassifier", "GPSettings", "GPSurrogate",
           "save_surrogates", "load_surrogates", "saved_set", "SurrogateLoadError", "SurrogateIntegrityError",
           "SurrogateVersionError", "SurrogateVersionWarning", "CrossValidation", "cross_validate",
           "cross_validate_outputs"]
