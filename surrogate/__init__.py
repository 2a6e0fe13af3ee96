"""Gaussian-process surrogates of simulation outputs (issue 5): fit, predict, validate, save.

- :class:`GPSurrogate`: one output, normalised inputs, anisotropic Matern + noise kernel,
  optional log transform; :func:`save_surrogates` / :func:`load_surrogates` for a set.
- :func:`cross_validate`: k-fold R^2, RMSE and coverage of the prediction interval.
- :mod:`surrogate.store`: the saved set (manifest with SHA-256 of every file, checked before
  unpickling; scikit-learn version checked on load; crash-safe replacement).
"""
from surrogate.gp import GPSettings, GPSurrogate
from surrogate.store import (SurrogateIntegrityError, SurrogateLoadError, SurrogateVersionError,
                             SurrogateVersionWarning, load_surrogates, save_surrogates, saved_set)
from surrogate.validation import CrossValidation, cross_validate

__all__ = ["GPSettings", "GPSurrogate", "save_surrogates", "load_surrogates", "saved_set", "SurrogateLoadError",
           "SurrogateIntegrityError", "SurrogateVersionError", "SurrogateVersionWarning", "CrossValidation",
           "cross_validate"]
