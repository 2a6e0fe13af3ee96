"""Gaussian-process surrogates of simulation outputs (issue 5): fit, predict, validate, save.

- :class:`GPSurrogate`: one output, normalised inputs, anisotropic Matern + noise kernel,
  optional log transform; :func:`save_surrogates` / :func:`load_surrogates` for a set.
- :func:`cross_validate`: k-fold R^2, RMSE and coverage of the prediction interval.
"""
from surrogate.gp import GPSettings, GPSurrogate, load_surrogates, save_surrogates
from surrogate.validation import CrossValidation, cross_validate

__all__ = ["GPSettings", "GPSurrogate", "save_surrogates", "load_surrogates", "CrossValidation", "cross_validate"]
