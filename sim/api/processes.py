"""Worker processes that never outlive the process that started them.

A ``concurrent.futures`` or joblib (loky) worker whose parent is killed with SIGKILL keeps
running its task and then lingers, reparented to init (measured: joblib's loky workers survive a
SIGKILLed parent). A killed design study or sweep must not leave simulations running. On Linux
each worker here asks the kernel to send it SIGKILL when its parent dies
(``prctl(PR_SET_PDEATHSIG)``, prctl(2)), before it runs anything; the parent is the process that
created the pool, whose main thread creates the workers. Elsewhere (macOS, Windows have no such
call) the workers end when the pool is shut down or the parent exits normally.
"""
import concurrent.futures as cf
import ctypes
import ctypes.util
import multiprocessing
import os
import signal
import sys

PR_SET_PDEATHSIG = 1          # linux/prctl.h
#: Start method of the workers: fork on Linux (they inherit the warmed kernels and the configs),
#: spawn elsewhere (fork is unsafe on macOS and absent on Windows).
START_METHOD = "fork" if sys.platform.startswith("linux") else "spawn"


def die_with_parent(parent_pid):
    """In a worker: receive SIGKILL when the parent dies (Linux); if the parent is already gone
    (it died between the fork and this call), exit at once. No-op on other systems."""
    if not sys.platform.startswith("linux"):
        return
    libc = ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6", use_errno=True)
    if libc.prctl(PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0) != 0:
        err = ctypes.get_errno()
        raise OSError(err, f"prctl(PR_SET_PDEATHSIG) failed: {os.strerror(err)}")
    if os.getppid() != parent_pid:
        os._exit(1)


def _start_worker(parent_pid, initializer, initargs):
    die_with_parent(parent_pid)
    if initializer is not None:
        initializer(*initargs)


def worker_pool(workers, initializer=None, initargs=()):
    """A ``ProcessPoolExecutor`` of ``workers`` processes that die with this process (module
    docstring), started with :data:`START_METHOD`, running ``initializer(*initargs)`` first."""
    return cf.ProcessPoolExecutor(workers, mp_context=multiprocessing.get_context(START_METHOD),
                                  initializer=_start_worker, initargs=(os.getpid(), initializer, initargs))
