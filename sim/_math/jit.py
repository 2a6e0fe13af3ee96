"""The project's one numba setup.

Every hot kernel is decorated with :func:`kernel`: ``njit`` with an on-disk cache (CI and
sweeps pay the compile time once) and strict float semantics, without the C-callable
wrapper numba builds by default for first-class function use (no kernel is passed as a
function value; each wrapper kept a non-inlined copy of its kernel to compile). Setting the
environment variable ``NUMBA_DISABLE_JIT=1`` runs the same code as plain Python (tests pass either way).

Cache validity. Numba keys a cached kernel on its own source file only (modification time and
size): a kernel whose callee in another module changed would load the stale machine code of the
old callee (seen in issue 14: a changed rolling-force formula in ``ehl.py`` left the cached
friction kernels of ``friction.py`` on the old formula). The cache therefore lives in a folder
named by a SHA-256 of every source file of ``sim/`` (:func:`source_fingerprint`): any edit of
the package starts a fresh cache, and two versions of the package never share one. The folder
is ``$NUMBA_CACHE_DIR/sim-<hash>`` when the user set that variable, else
``sim/__pycache__/numba/sim-<hash>`` beside the sources (numba's own default place); where
that is not writable, numba falls back to its user-wide cache as usual.

Old versions' folders. Each version of ``sim/`` leaves a folder of ~15 MB; a checkout that is
pulled or edited often gathered hundreds of MB of machine code that nothing will load again
(session 29: 29 folders, 448 MB). The first :func:`cache_dir` of a process marks its folder as
used (its modification time) and deletes the ``sim-<hash>`` folders beside it beyond the
:data:`KEPT_OTHER_VERSIONS` most recently used (:func:`prune_cache_folders`). A process of an
older version whose folder went meanwhile loses nothing but its cache: numba recreates a missing
cache folder when it saves a kernel and compiles what it cannot load.
"""
import hashlib
import os
import re
import shutil
import time
from functools import lru_cache
from pathlib import Path

import numba
import numba.core.event

SIM_ROOT = Path(__file__).resolve().parents[1]     # the whole sim/ package, every layer
#: characters of the SHA-256 hex digest in the cache folder name (64 bits: no collision in practice)
CACHE_KEY_LENGTH = 16
#: cache folders of other versions of sim/ kept beside the current one, the most recently used:
#: switching between a few branches or worktrees keeps their compiled kernels (housekeeping
#: choice: each folder holds ~15 MB; a version not among them compiles again, ~80 s, when used)
KEPT_OTHER_VERSIONS = 3
_CACHE_FOLDER = re.compile(rf"sim-[0-9a-f]{{{CACHE_KEY_LENGTH}}}")

_JIT_OPTIONS = dict(cache=True, fastmath=False, nogil=True, no_cfunc_wrapper=True)
_njit = numba.njit(**_JIT_OPTIONS)
_njit_internal = numba.njit(no_cpython_wrapper=True, **_JIT_OPTIONS)


def sim_sources():
    """Every source file of ``sim/`` (all subpackages), in a fixed order."""
    return sorted(SIM_ROOT.rglob("*.py"))


def files_fingerprint(root, paths):
    """SHA-256 hex digest over the paths (relative to ``root``) and bytes of ``paths``, in order."""
    h = hashlib.sha256()
    for path in paths:
        h.update(str(Path(path).relative_to(root)).encode())
        h.update(Path(path).read_bytes())
    return h.hexdigest()


@lru_cache(maxsize=1)
def source_fingerprint():
    """SHA-256 hex digest over the relative paths and bytes of :func:`sim_sources`."""
    return files_fingerprint(SIM_ROOT, sim_sources())


@lru_cache(maxsize=1)
def cache_dir():
    """The numba cache folder of this version of ``sim/`` (module docstring); the first call of a
    process prunes the other versions' folders (:func:`prune_cache_folders`)."""
    base = os.environ.get("NUMBA_CACHE_DIR") or str(SIM_ROOT / "__pycache__" / "numba")
    folder = os.path.join(base, f"sim-{source_fingerprint()[:CACHE_KEY_LENGTH]}")
    prune_cache_folders(folder, KEPT_OTHER_VERSIONS)
    return folder


def prune_cache_folders(folder, keep):
    """Mark the cache folder ``folder`` as used now (creating it) and delete the other
    ``sim-<hash>`` folders beside it but the ``keep`` most recently used; returns the deleted
    paths. Nothing else in that parent folder is touched. Best effort: a folder that cannot be
    marked (read-only checkout) prunes nothing, one that cannot be deleted (or that another
    process deletes first) is left."""
    folder = Path(folder)
    try:
        folder.mkdir(parents=True, exist_ok=True)
        os.utime(folder)
        others = [p for p in folder.parent.iterdir()
                  if p != folder and p.is_dir() and _CACHE_FOLDER.fullmatch(p.name)]
        others.sort(key=lambda p: p.stat().st_mtime, reverse=True)
    except OSError:
        return []
    for path in others[keep:]:
        shutil.rmtree(path, ignore_errors=True)
    return others[keep:]


def kernel(func):
    """``numba.njit(cache=True, fastmath=False, nogil=True, no_cfunc_wrapper=True)`` with the cache in
    :func:`cache_dir`.

    Numba picks a function's cache folder when it is decorated (``numba.config.CACHE_DIR``); it
    is set for that moment only, so other numba users in the process keep their own setting.
    """
    return _in_cache_dir(_njit, func)


def internal_kernel(func):
    """A :func:`kernel` called only from other kernels: without numba's CPython wrapper
    (``no_cpython_wrapper=True``), so it cannot be called from Python (except under
    ``NUMBA_DISABLE_JIT=1``).

    The wrapper unboxes every argument from its Python object: for a kernel taking a bundle
    such as :data:`sim.physics.friction.FrictionCase` (some 30 arrays and 30 numbers) that is
    ~1800 lines of LLVM IR to generate, optimise and compile, about half of a friction kernel's
    own module; a kernel called only from kernels never runs it.
    """
    return _in_cache_dir(_njit_internal, func)


def _in_cache_dir(decorator, func):
    """``decorator(func)`` with ``numba.config.CACHE_DIR`` set to :func:`cache_dir` meanwhile."""
    previous = numba.config.CACHE_DIR
    numba.config.CACHE_DIR = cache_dir()
    try:
        return decorator(func)
    finally:
        numba.config.CACHE_DIR = previous


# ---------------------------------------------------------------------------- time spent compiling
class _CompileClock(numba.core.event.Listener):
    """Seconds this process spent compiling numba functions: numba broadcasts "numba:compile" around
    each compile (not around a load from its on-disk cache; numba's Event API), nested for the
    callees a compile compiles; only the outermost count, once each."""

    def __init__(self):
        self.depth = 0
        self.started = 0.0
        self.seconds = 0.0

    def on_start(self, event):
        if self.depth == 0:
            self.started = time.perf_counter()
        self.depth += 1

    def on_end(self, event):
        self.depth -= 1
        if self.depth == 0:
            self.seconds += time.perf_counter() - self.started


_COMPILE_CLOCK = _CompileClock()
numba.core.event.register("numba:compile", _COMPILE_CLOCK)


def clock():
    """A mark for :func:`solver_seconds`: (wall time [s], compile time so far [s])."""
    return time.perf_counter(), _COMPILE_CLOCK.seconds


def solver_seconds(mark):
    """Wall seconds since ``mark`` (:func:`clock`) less the numba compiling within them: a case's
    ``wall_time`` (DATA.md: the solver time for the case), which the first case of a process on a
    new machine otherwise reported as ~130 s of compiling for a 0.3 s solve (an independent check of
    session 31)."""
    wall, compiled = mark
    return (time.perf_counter() - wall) - (_COMPILE_CLOCK.seconds - compiled)
