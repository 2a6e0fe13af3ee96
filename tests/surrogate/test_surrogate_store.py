"""Saved surrogates (surrogate/store.py, issue 13 item 6): crash-safe replacement, scikit-learn
version check, and nothing unpickled that does not match the SHA-256 recorded at save time.
"""
import json
import os
import pickle
import shutil
import warnings

import joblib
import numpy as np
import pytest
import sklearn
from omegaconf import OmegaConf
from scipy.stats import qmc

import sim
from surrogate import (GPSettings, GPSurrogate, SurrogateIntegrityError, SurrogateLoadError, SurrogateVersionError,
                       SurrogateVersionWarning, load_surrogates, save_surrogates, saved_set, store)

BOUNDS = np.array([[30.0, 150.0], [0.90, 0.995]])
XT = qmc.scale(qmc.Sobol(2, seed=9).random(16), BOUNDS[:, 0], BOUNDS[:, 1])


def fitted(offset):
    """Two small fitted surrogates; ``offset`` tells one set from another by its predictions."""
    cfg = OmegaConf.load(sim.CONF_DIR / "study" / "pinion.yaml")
    settings = GPSettings.from_config(cfg.surrogate, seed=0)
    X = qmc.scale(qmc.Sobol(2, seed=1).random(8), BOUNDS[:, 0], BOUNDS[:, 1])
    y = 1.0 + np.sin(X[:, 0] / 40.0) + X[:, 1] + offset
    return {"pmax": GPSurrogate(BOUNDS, True, settings, "pmax", "MPa").fit(X, y),
            "torque": GPSurrogate(BOUNDS, False, settings, "torque", "N m").fit(X, -y)}


@pytest.fixture(scope="module")
def old():
    return fitted(0.0)


@pytest.fixture(scope="module")
def new():
    return fitted(5.0)


def same(a, b):
    """Two sets with the same names and bit-identical predictions."""
    return set(a) == set(b) and all(
        all(np.array_equal(p, q) for p, q in zip(a[n].predict(XT), b[n].predict(XT))) for n in a)


class Payload:
    """A crafted pickle: loading it makes a folder, the proof that it ran."""

    def __init__(self, marker):
        self.marker = str(marker)

    def __reduce__(self):
        return os.mkdir, (self.marker,)


@pytest.fixture
def no_unpickling(monkeypatch):
    """Fails the test if joblib.load is called (the refusals must come before any unpickling)."""
    def refuse(*args, **kwargs):
        raise AssertionError("joblib.load called")

    monkeypatch.setattr(store.joblib, "load", refuse)


# ------------------------------------------------------------------ format
def test_set_round_trip_and_manifest(old, tmp_path):
    """Bit-identical predictions after loading; the manifest records versions and every file's SHA-256;
    only the set folder is left (no staging folder, no backup)."""
    folder = save_surrogates(old, tmp_path / "round_001")
    assert same(load_surrogates(folder), old)
    manifest = json.loads((folder / "manifest.json").read_text())
    assert manifest["format"] == "surrogate set" and manifest["version"] == 1
    assert manifest["sklearn_version"] == sklearn.__version__ == manifest["versions"]["sklearn"]
    for name, entry in manifest["models"].items():
        assert entry["model"] == f"{name}.joblib" and entry["metadata"] == f"{name}.json"
        assert entry["sha256"] == store._sha256((folder / entry["model"]).read_bytes())
        assert entry["metadata_sha256"] == store._sha256((folder / entry["metadata"]).read_bytes())
        assert json.loads((folder / entry["metadata"]).read_text())["model_sha256"] == entry["sha256"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["round_001"]
    assert sorted(p.name for p in folder.iterdir()) == ["manifest.json", "pmax.joblib", "pmax.json",
                                                        "torque.joblib", "torque.json"]


def test_single_model_round_trip(old, tmp_path):
    entry = store.save_model(old["pmax"], tmp_path / "m" / "pmax")
    assert entry["model"] == "pmax.joblib" and (tmp_path / "m" / "pmax.json").exists()
    loaded = store.load_model(tmp_path / "m" / "pmax.joblib")
    assert same({"pmax": loaded}, {"pmax": old["pmax"]})


def test_replacing_a_set_keeps_no_old_file(old, new, tmp_path):
    save_surrogates(old, tmp_path / "s")
    save_surrogates({"pmax": new["pmax"]}, tmp_path / "s")
    assert same(load_surrogates(tmp_path / "s"), {"pmax": new["pmax"]})
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s"]


# ------------------------------------------------------------------ crash at every step
class Crash(BaseException):
    """A simulated kill (BaseException, as KeyboardInterrupt: no except Exception catches it)."""


def crash_at(monkeypatch, k):
    """Make the k-th file-system step of a save crash, as a kill would leave it: a file half written,
    a folder half removed, a rename or fsync not done. Returns the step counter."""
    count = {"n": 0}

    def step(real, partial=None):
        def wrapper(*args, **kwargs):
            count["n"] += 1
            if count["n"] == k:
                if partial:
                    partial(*args)
                raise Crash(f"step {k}: {real.__name__}")
            return real(*args, **kwargs)
        return wrapper

    def half_write(path, data):
        with open(path, "wb") as f:
            f.write(data[:len(data) // 2])

    def half_remove(path, *args, **kwargs):
        files = sorted(p for p in path.rglob("*") if p.is_file())
        for p in files[:len(files) // 2 + 1]:
            p.unlink()

    monkeypatch.setattr(store, "_write_synced", step(store._write_synced, half_write))
    monkeypatch.setattr(store, "_sync_dir", step(store._sync_dir))
    monkeypatch.setattr(store.os, "replace", step(os.replace))
    monkeypatch.setattr(store.shutil, "rmtree", step(shutil.rmtree, half_remove))
    monkeypatch.setattr(store.joblib, "dump", step(joblib.dump))
    return count


@pytest.mark.parametrize("before", ["old set", "old set and a stale backup", "nothing"])
def test_crash_at_every_step_leaves_a_loadable_set(old, new, tmp_path, monkeypatch, before):
    """Kill save_surrogates at each of its file-system steps in turn (k = 1, 2, ... until one save
    completes): every time the folder loads as the complete old set or the complete new one (or,
    on a first save, as nothing saved); the next save succeeds and leaves only the new set."""
    k, outcomes = 0, []
    while True:
        k += 1
        folder = tmp_path / str(k) / "round_001"
        if before != "nothing":
            save_surrogates(old, folder)
        if before == "old set and a stale backup":
            shutil.copytree(folder, store.backup_folder(folder))
        with monkeypatch.context() as m:
            counter = crash_at(m, k)
            try:
                save_surrogates(new, folder)
                crashed = False
            except Crash:
                crashed = True
        if saved_set(folder) is None:
            assert before == "nothing" and crashed
            outcomes.append("nothing")
            with pytest.raises(FileNotFoundError):
                load_surrogates(folder)
        else:
            loaded = load_surrogates(folder)
            assert same(loaded, old) or same(loaded, new), f"crash at step {k}: neither set"
            outcomes.append("old" if same(loaded, old) else "new")
        save_surrogates(new, folder)  # the next run saves again
        assert same(load_surrogates(folder), new)
        assert sorted(p.name for p in folder.parent.iterdir()) == ["round_001"]
        if not crashed:
            assert counter["n"] < k
            break
    assert k > 8  # every write, fsync, rename and removal of the save was a crash point
    first = "nothing" if before == "nothing" else "old"
    assert outcomes[0] == first and outcomes[-1] == "new"
    assert outcomes == sorted(outcomes, key=[first, "new"].index)  # old ... old, then new ... new


# ------------------------------------------------------------------ scikit-learn version
def test_same_version_loads_without_warning(old, tmp_path):
    save_surrogates(old, tmp_path / "s")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert same(load_surrogates(tmp_path / "s"), old)


@pytest.mark.parametrize("faked", ["saved", "installed"])
def test_other_sklearn_version_is_refused_or_warned(old, tmp_path, monkeypatch, faked):
    """Saved under a (faked) other scikit-learn, or loaded under one: refused by default with both
    versions and how to refit; loaded with a SurrogateVersionWarning when asked to."""
    real = sklearn.__version__
    if faked == "saved":
        with monkeypatch.context() as m:
            m.setattr(sklearn, "__version__", "0.20.fake")
            save_surrogates(old, tmp_path / "s")
        saved, installed = "0.20.fake", real
    else:
        save_surrogates(old, tmp_path / "s")
        monkeypatch.setattr(sklearn, "__version__", "9.9.fake")
        saved, installed = real, "9.9.fake"
    with pytest.raises(SurrogateVersionError) as err:
        load_surrogates(tmp_path / "s")
    message = str(err.value)
    assert f"saved with scikit-learn {saved}" in message and f"scikit-learn {installed} is installed" in message
    assert "Refit" in message and str(tmp_path / "s") in message
    with pytest.raises(SurrogateVersionError):
        store.load_model(tmp_path / "s" / "pmax")
    with pytest.warns(SurrogateVersionWarning, match=f"scikit-learn {saved}.*{installed} is installed"):
        assert same(load_surrogates(tmp_path / "s", on_version_mismatch="warn"), old)


# ------------------------------------------------------------------ nothing foreign is unpickled
def test_replaced_model_file_is_refused_before_unpickling(old, tmp_path, no_unpickling):
    folder = save_surrogates(old, tmp_path / "s")
    (folder / "pmax.joblib").write_bytes(pickle.dumps(Payload(tmp_path / "ran")))
    with pytest.raises(SurrogateIntegrityError, match="pmax.joblib does not match the SHA-256"):
        load_surrogates(folder)
    with pytest.raises(SurrogateIntegrityError):
        store.load_model(folder / "pmax")
    assert not (tmp_path / "ran").exists()


def test_dropped_files_are_ignored(old, tmp_path, monkeypatch):
    """A model dropped into the folder, with a JSON recording its own SHA-256, is not in the
    manifest: never read. The set loads as saved."""
    folder = save_surrogates(old, tmp_path / "s")
    data = pickle.dumps(Payload(tmp_path / "ran"))
    (folder / "evil.joblib").write_bytes(data)
    (folder / "evil.json").write_text(json.dumps({"model_sha256": store._sha256(data),
                                                  "sklearn_version": sklearn.__version__}))
    assert same(load_surrogates(folder), old)
    assert not (tmp_path / "ran").exists()


@pytest.mark.parametrize("edit", ["add entry", "path outside", "metadata swapped", "no manifest", "bad format"])
def test_altered_manifest_or_old_folder_is_refused(old, tmp_path, no_unpickling, edit):
    folder = save_surrogates(old, tmp_path / "s")
    manifest = json.loads((folder / "manifest.json").read_text())
    data = pickle.dumps(Payload(tmp_path / "ran"))
    if edit == "add entry":   # an entry whose hash is not that of the file
        (folder / "evil.joblib").write_bytes(data)
        (folder / "evil.json").write_text(json.dumps({"model_sha256": store._sha256(data),
                                                      "sklearn_version": sklearn.__version__}))
        manifest["models"]["evil"] = dict(manifest["models"]["pmax"], model="evil.joblib", metadata="evil.json")
    elif edit == "path outside":
        (tmp_path / "evil.joblib").write_bytes(data)
        manifest["models"]["../evil"] = dict(manifest["models"]["pmax"], model="../evil.joblib")
    elif edit == "metadata swapped":
        (folder / "pmax.json").write_bytes((folder / "torque.json").read_bytes())
    elif edit == "bad format":
        manifest["version"] = 99
    if edit == "no manifest":  # a folder of the former format: model files without integrity record
        (folder / "manifest.json").unlink()
    else:
        (folder / "manifest.json").write_text(json.dumps(manifest))
    with pytest.raises((SurrogateLoadError, ValueError)):
        load_surrogates(folder)
    assert not (tmp_path / "ran").exists()


def test_former_single_model_without_hash_is_refused(old, tmp_path, no_unpickling):
    (tmp_path / "pmax.joblib").write_bytes(pickle.dumps(Payload(tmp_path / "ran")))
    (tmp_path / "pmax.json").write_text(json.dumps(old["pmax"].metadata()))
    with pytest.raises(SurrogateLoadError, match="records no SHA-256"):
        store.load_model(tmp_path / "pmax")
    assert not (tmp_path / "ran").exists()


def test_unsafe_names_are_refused(old, tmp_path):
    for name in ("../x", ".hidden", "a/b", "manifest", ""):
        with pytest.raises(ValueError, match="cannot be a file name"):
            save_surrogates({name: old["pmax"]}, tmp_path / "s")
    assert saved_set(tmp_path / "s") is None


def test_success_classifier_saves_and_loads_with_the_regression_surrogates(tmp_path):
    """A round's set holds the GP classifier of failed simulations beside the regression GPs
    (studies.loop): its probabilities read back bit for bit, its metadata is JSON."""
    from surrogate import SuccessClassifier

    settings = GPSettings(2.5, (0.01, 100.0), (0.01, 100.0), (1e-10, 0.1), 0, 0, True, 0.95, 5)
    X = qmc.Sobol(2, seed=0).random(32)
    ok = X[:, 0] + X[:, 1] > 0.8
    bounds = [[0.0, 1.0], [0.0, 1.0]]
    models = {"success": SuccessClassifier(bounds, settings).fit(X, ok),
              "y": GPSurrogate(bounds, False, settings, "y").fit(X, X.sum(axis=1))}
    save_surrogates(models, tmp_path / "set")
    loaded = load_surrogates(tmp_path / "set")
    XT = qmc.Sobol(2, seed=1).random(16)
    np.testing.assert_array_equal(loaded["success"].probability(XT), models["success"].probability(XT))
    assert '"kind": "GaussianProcessClassifier' in (tmp_path / "set" / "success.json").read_text()
