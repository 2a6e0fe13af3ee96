"""Saving and loading fitted surrogates: integrity-checked files, versions, crash-safe replacement.

A set of surrogates (:func:`save_surrogates`) is one folder::

    <folder>/manifest.json     what the folder holds, written last (below)
    <folder>/<name>.joblib     the fitted GPSurrogate or SuccessClassifier, pickled by joblib
    <folder>/<name>.json       its metadata (the model's ``metadata()``) and the model file's SHA-256

    manifest.json = {"format": "surrogate set", "version": 1, "created": ISO 8601 UTC,
                     "versions": {"sklearn", "numpy", "scipy", "joblib", "python"},
                     "models": {name: {"model": "<name>.joblib", "sha256": hex,
                                       "metadata": "<name>.json", "metadata_sha256": hex}}}

Trust. A ``.joblib`` file is a pickle: loading one can run arbitrary code. Load only folders
this tool wrote. Before anything is unpickled, the bytes read are hashed and compared with the
SHA-256 recorded at save time (the manifest and the model's JSON); only files the manifest
names are read, so a file dropped into or replaced in the folder is refused, never unpickled.
This is an integrity check (a damaged, partial, swapped or foreign file), not an
authentication: whoever can rewrite the manifest too can make a file pass, so never load a
surrogate folder from an untrusted source.

Versions. A model pickled by one scikit-learn may fail to load, or predict differently, under
another; the versions are recorded at save time and checked before loading: a different
scikit-learn is refused (:class:`SurrogateVersionError`, naming both versions and how to
refit) unless ``on_version_mismatch="warn"``.

Crash safety. :func:`save_surrogates` writes the new set completely (files fsynced, manifest
last) into a hidden sibling folder, then swaps: old folder -> ``<folder>.old``, new -> folder,
then removes ``<folder>.old``. Each rename is atomic, so at every instant the folder or, between
the two renames, ``<folder>.old`` holds a complete set, and :func:`load_surrogates` reads
whichever is complete.
"""
import datetime as _dt
import hashlib
import io
import json
import os
import platform
import secrets
import shutil
import warnings
from pathlib import Path

import joblib
import numpy as np
import scipy
import sklearn

from surrogate.classifier import SuccessClassifier
from surrogate.gp import GPSurrogate

try:
    from sklearn.exceptions import InconsistentVersionWarning
except ImportError:  # scikit-learn < 1.3
    InconsistentVersionWarning = UserWarning

MANIFEST = "manifest.json"
SET_FORMAT = "surrogate set"
SET_VERSION = 1
BACKUP_SUFFIX = ".old"           # the previous set while a save swaps it for the new one
STAGING_PREFIX = ".{name}.new-"  # hidden sibling folder a save writes before the swap


class SurrogateLoadError(RuntimeError):
    """Saved surrogates that are not loaded: missing integrity record, damaged or foreign file."""


class SurrogateIntegrityError(SurrogateLoadError):
    """A file does not match the SHA-256 recorded when the surrogates were saved."""


class SurrogateVersionError(SurrogateLoadError):
    """Surrogates saved with another scikit-learn than the installed one."""


class SurrogateVersionWarning(UserWarning):
    """Surrogates loaded although saved with another scikit-learn (``on_version_mismatch="warn"``)."""


def versions():
    """Versions of what a pickled model depends on."""
    return {"sklearn": sklearn.__version__, "numpy": np.__version__, "scipy": scipy.__version__,
            "joblib": joblib.__version__, "python": platform.python_version()}


def check_sklearn_version(saved, where, on_mismatch="error"):
    """Refuse (``on_mismatch="error"``) or warn (``"warn"``) when ``saved`` is not the installed scikit-learn."""
    if on_mismatch not in ("error", "warn"):
        raise ValueError(f"on_version_mismatch = {on_mismatch!r} must be 'error' or 'warn'")
    installed = sklearn.__version__
    if saved == installed:
        return
    message = (f"{where} was saved with scikit-learn {saved}, but scikit-learn {installed} is installed; a fitted "
               f"model pickled by one version may fail to load or predict differently in another. Refit: delete "
               f"{where} and run the study again (it refits the surrogates from its simulations), or install "
               f"scikit-learn=={saved} to use the saved models (or load with on_version_mismatch='warn').")
    if on_mismatch == "warn":
        warnings.warn(message, SurrogateVersionWarning, stacklevel=3)
    else:
        raise SurrogateVersionError(message)


def _sha256(data):
    return hashlib.sha256(data).hexdigest()


def _write_synced(path, data):
    """Write bytes and flush them to disk (a renamed folder must not hold empty files after a power cut)."""
    with open(path, "wb") as f:
        f.write(data)
        f.flush()
        os.fsync(f.fileno())


def _sync_dir(path):
    """fsync a folder, so renames and new entries in it are on disk."""
    fd = os.open(path, os.O_RDONLY)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)


def _check_name(name):
    """A model name is a file stem in the set's folder: no separator, no leading dot, not the manifest."""
    if not isinstance(name, str) or not name or name != Path(name).name or name.startswith(".") \
            or f"{name}.json" == MANIFEST:
        raise ValueError(f"surrogate name {name!r} cannot be a file name in the set's folder")
    return name


# ------------------------------------------------------------------ one model
def save_model(model, path):
    """Write ``<path>.joblib`` (the pickled model) and ``<path>.json`` (metadata with its SHA-256).

    Returns the manifest entry ``{"model", "sha256", "metadata", "metadata_sha256"}``. Not atomic
    on its own: :func:`save_surrogates` writes into a staging folder and swaps it into place.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    buffer = io.BytesIO()
    joblib.dump(model, buffer)
    data = buffer.getvalue()
    meta = dict(model.metadata(), model_file=path.name + ".joblib", model_sha256=_sha256(data), versions=versions())
    text = json.dumps(meta, indent=2).encode()
    _write_synced(path.with_name(path.name + ".joblib"), data)
    _write_synced(path.with_name(path.name + ".json"), text)
    return {"model": path.name + ".joblib", "sha256": meta["model_sha256"],
            "metadata": path.name + ".json", "metadata_sha256": _sha256(text)}


def _read_verified(path, sha256):
    """The bytes of ``path`` if their SHA-256 is ``sha256``; else SurrogateIntegrityError."""
    try:
        data = Path(path).read_bytes()
    except FileNotFoundError:
        raise SurrogateIntegrityError(f"{path} is missing; the set is incomplete: delete it and refit") from None
    if not isinstance(sha256, str) or _sha256(data) != sha256:
        raise SurrogateIntegrityError(f"{path} does not match the SHA-256 recorded when it was saved (damaged, "
                                      f"replaced or not written by this tool): not loaded; delete the folder and refit")
    return data


def _verified_model_bytes(path, on_version_mismatch, expected=None, check_version=True):
    """The model file's bytes of the surrogate saved at ``path``, read and checked, not unpickled.

    The JSON is read first (checked against ``expected``, the set manifest's entry, when given);
    its scikit-learn version is checked (unless ``check_version`` is False: the set's was), then
    the model file's bytes are compared with the SHA-256 it records.
    """
    meta_path = path.with_name(path.name + ".json")
    meta_bytes = (_read_verified(meta_path, expected["metadata_sha256"]) if expected is not None
                  else _read_text_or_refuse(meta_path))
    meta = json.loads(meta_bytes)
    if not isinstance(meta, dict) or "model_sha256" not in meta:
        raise SurrogateLoadError(f"{meta_path} records no SHA-256 of its model (saved by an older version of this "
                                 f"tool, or not by it): not loaded; delete it and refit")
    if check_version:
        check_sklearn_version(meta.get("sklearn_version"), meta_path, on_version_mismatch)
    if expected is not None and meta["model_sha256"] != expected["sha256"]:
        raise SurrogateIntegrityError(f"{meta_path} and the set's manifest record different model files")
    return _read_verified(path.with_name(path.name + ".joblib"), meta["model_sha256"])


def _unpickle(data, path, on_version_mismatch):
    """The GPSurrogate or SuccessClassifier in verified bytes ``data`` (of ``<path>.joblib``)."""
    with warnings.catch_warnings():
        if on_version_mismatch == "warn":  # already warned, with the versions and how to refit
            warnings.simplefilter("ignore", InconsistentVersionWarning)
        model = joblib.load(io.BytesIO(data))
    if not isinstance(model, (GPSurrogate, SuccessClassifier)):
        raise SurrogateLoadError(f"{path}.joblib does not hold a GPSurrogate or SuccessClassifier")
    return model


def _stem(path):
    path = Path(path)
    return path.with_suffix("") if path.suffix in (".joblib", ".json") else path


def load_model(path, on_version_mismatch="error"):
    """Load one surrogate written by :func:`save_model` (``path`` with or without suffix).

    Its JSON is read first: the scikit-learn version is checked, then the model file's bytes
    are compared with the SHA-256 the JSON records, and only then unpickled (the bytes that
    were hashed). Only for files this tool wrote (module docstring).
    """
    path = _stem(path)
    return _unpickle(_verified_model_bytes(path, on_version_mismatch), path, on_version_mismatch)


def _read_text_or_refuse(path):
    try:
        return Path(path).read_bytes()
    except FileNotFoundError:
        raise SurrogateLoadError(f"{path} is missing: no surrogate saved at {path.with_suffix('')}") from None


# ------------------------------------------------------------------ a set of models
def backup_folder(folder):
    """Where :func:`save_surrogates` keeps the previous set during the swap: ``<folder>.old``."""
    folder = Path(folder)
    return folder.with_name(folder.name + BACKUP_SUFFIX)


def saved_set(folder):
    """The folder holding the set saved as ``folder``, or None if none was saved.

    ``folder`` itself when it holds a manifest; else ``<folder>.old`` when it does (a save
    interrupted between its two renames); else, if ``folder`` exists without a manifest, the
    folder (load refuses it: not written by this version); else None.
    """
    folder = Path(folder)
    if (folder / MANIFEST).is_file():
        return folder
    if (backup_folder(folder) / MANIFEST).is_file():
        return backup_folder(folder)
    return folder if folder.is_dir() else None


def save_surrogates(models, folder):
    """Save a dict name -> GPSurrogate or SuccessClassifier as the set ``folder`` (module docstring), replacing any old set.

    The new set is written completely into a hidden sibling folder first, then swapped in with
    two atomic renames; a crash at any point leaves a complete set (the old or the new one) that
    :func:`load_surrogates` loads. Not for two concurrent saves of one folder.
    """
    folder = Path(folder)
    folder.parent.mkdir(parents=True, exist_ok=True)
    names = [_check_name(name) for name in models]
    prefix = STAGING_PREFIX.format(name=folder.name)
    for debris in folder.parent.glob(prefix + "*"):   # of an interrupted save: never loadable, never loaded
        shutil.rmtree(debris, ignore_errors=True)
    staging = folder.parent / f"{prefix}{secrets.token_hex(6)}"
    staging.mkdir()
    try:
        entries = {name: save_model(models[name], staging / name) for name in names}
        manifest = {"format": SET_FORMAT, "version": SET_VERSION,
                    "created": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
                    "sklearn_version": sklearn.__version__, "versions": versions(), "models": entries}
        _write_synced(staging / MANIFEST, json.dumps(manifest, indent=2).encode())
        _sync_dir(staging)
    except BaseException:
        shutil.rmtree(staging, ignore_errors=True)
        raise
    backup = backup_folder(folder)
    if folder.exists():
        if backup.exists():  # left by an older interrupted save after its new set was in place: older than folder
            shutil.rmtree(backup)
        os.replace(folder, backup)
    os.replace(staging, folder)
    _sync_dir(folder.parent)
    shutil.rmtree(backup, ignore_errors=True)
    return folder


def load_surrogates(folder, on_version_mismatch="error"):
    """Load the set saved as ``folder``: dict name -> GPSurrogate or SuccessClassifier.

    Reads the manifest (of ``folder``, or of ``<folder>.old`` after a save interrupted between
    its renames), checks the scikit-learn version it records, and loads exactly the models it
    names, each after checking its files' SHA-256 (module docstring: only for folders this tool
    wrote). FileNotFoundError if nothing was saved; SurrogateVersionError on another
    scikit-learn (``on_version_mismatch="warn"``: warn and load); SurrogateLoadError if a file
    is missing, altered or not from this tool.
    """
    folder = Path(folder)
    source = saved_set(folder)
    if source is None:
        raise FileNotFoundError(f"no surrogates saved at {folder}")
    if not (source / MANIFEST).is_file():
        raise SurrogateLoadError(f"{folder} has no {MANIFEST} (saved by an older version of this tool, or not by "
                                 f"it), so its files cannot be checked before unpickling: not loaded; delete it and "
                                 f"refit")
    manifest = json.loads((source / MANIFEST).read_bytes())
    if manifest.get("format") != SET_FORMAT or manifest.get("version") != SET_VERSION:
        raise SurrogateLoadError(f"{source / MANIFEST} is not a {SET_FORMAT!r} manifest of version {SET_VERSION}")
    check_sklearn_version(manifest.get("sklearn_version"), folder, on_version_mismatch)
    verified = {}
    for name, entry in manifest["models"].items():  # every file checked before anything is unpickled
        _check_name(name)
        if entry.get("model") != f"{name}.joblib" or entry.get("metadata") != f"{name}.json":
            raise SurrogateLoadError(f"{source / MANIFEST}: entry {name!r} names other files than {name}.joblib/.json")
        verified[name] = _verified_model_bytes(source / name, on_version_mismatch, entry, check_version=False)
    return {name: _unpickle(data, source / name, on_version_mismatch) for name, data in verified.items()}
