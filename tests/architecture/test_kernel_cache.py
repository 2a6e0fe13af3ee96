"""The numba cache is keyed on the whole of ``sim/`` (sim._math.jit): a kernel never runs the
stale machine code of a callee that changed in another module; the folders of old versions are
pruned."""
import os
import shutil

import numba
import pytest

from sim._math import jit
from sim.physics import ehl


def _fingerprint_of(root, monkeypatch):
    monkeypatch.setattr(jit, "SIM_ROOT", root)
    return jit.source_fingerprint.__wrapped__()


def test_any_edit_of_any_module_changes_the_cache_folder(tmp_path, monkeypatch):
    """Copy sim/, change one character of ehl.py (a callee of the friction kernels): the
    fingerprint, and with it the cache folder name, changes; an unchanged copy keeps it."""
    copy = tmp_path / "sim"
    shutil.copytree(jit.SIM_ROOT, copy, ignore=shutil.ignore_patterns("__pycache__"))
    before = _fingerprint_of(copy, monkeypatch)
    assert before == jit.source_fingerprint()          # same bytes, same paths: same key
    ehl_py = copy / "physics" / "ehl.py"
    ehl_py.write_text(ehl_py.read_text().replace("4.318", "4.319", 1))
    assert _fingerprint_of(copy, monkeypatch) != before


@pytest.mark.skipif(os.environ.get("NUMBA_DISABLE_JIT") == "1", reason="no compiled kernels without the JIT")
def test_kernels_are_cached_in_the_fingerprinted_folder():
    """A compiled kernel's index file lands in cache_dir(), named by the fingerprint, and the
    process-wide numba setting is left as it was."""
    ehl.film_line(3000.0, 100.0, 4.0, 4e-8, 0.021, 228000.0, ehl.FILM_PAN_HAMROCK)
    folder = jit.cache_dir()
    assert folder.endswith("sim-" + jit.source_fingerprint()[:jit.CACHE_KEY_LENGTH])
    index_files = [f for _, _, files in os.walk(folder) for f in files if f.startswith("ehl.film_line")]
    assert any(f.endswith(".nbi") for f in index_files), index_files
    assert numba.config.CACHE_DIR == os.environ.get("NUMBA_CACHE_DIR", "")


def test_old_versions_cache_folders_are_pruned_to_the_most_recently_used(tmp_path):
    """Six other versions' folders with staggered use times, a folder of something else and a
    file: pruning for a new version keeps it and the KEPT_OTHER_VERSIONS most recently used
    others, deletes the older ones and leaves everything not named sim-<hash> alone."""
    keep = jit.KEPT_OTHER_VERSIONS
    old = []
    for age in range(6):
        path = tmp_path / f"sim-{age:016x}"
        (path / "physics").mkdir(parents=True)
        (path / "physics" / "ehl.film_line-1.py312.nbi").write_bytes(b"index")
        os.utime(path, (1e9 - 1e4 * age, 1e9 - 1e4 * age))     # age 0 used last
        old.append(path)
    (tmp_path / "sim-notahash").mkdir()
    (tmp_path / "user_kernels").mkdir()
    (tmp_path / "notes.txt").write_text("not a cache")
    current = tmp_path / f"sim-{'f' * jit.CACHE_KEY_LENGTH}"
    deleted = jit.prune_cache_folders(current, keep)
    assert sorted(deleted) == sorted(old[keep:])
    assert current.is_dir() and all(p.is_dir() for p in old[:keep])
    assert not any(p.exists() for p in old[keep:])
    assert {"sim-notahash", "user_kernels", "notes.txt"} <= {p.name for p in tmp_path.iterdir()}
    # the current folder is now the most recently used: pruning again for an older version keeps it
    assert jit.prune_cache_folders(old[0], keep) == []
    assert current.is_dir()


def test_the_solver_time_leaves_out_numba_compiling():
    """A case's wall_time (DATA.md: the solver time for the case) leaves out the numba compiling within
    it (jit.solver_seconds, from numba's "numba:compile" events): the first case of a process on a new
    machine reported ~130 s of compiling for a 0.3 s solve (an independent check of session 31). A
    window spent almost only compiling a fresh function counts almost nothing."""
    import numba

    mark = jit.clock()
    add = numba.njit(lambda x: x + 1.5)    # no cache: compiled at the first call
    assert add(1.0) == 2.5
    solver = jit.solver_seconds(mark)
    end = jit.clock()
    wall, compiled = end[0] - mark[0], end[1] - mark[1]
    assert 0.0 < compiled <= wall
    assert 0.0 <= solver <= wall - compiled < 0.5 * wall      # read before the end mark: at most its window
