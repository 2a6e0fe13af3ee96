"""The project's one numba setup.

Every hot kernel is decorated with :data:`kernel`: ``njit`` with an on-disk cache (CI and
sweeps pay the compile time once) and strict float semantics. Setting the environment
variable ``NUMBA_DISABLE_JIT=1`` runs the same code as plain Python (tests pass either way).
"""
import numba

kernel = numba.njit(cache=True, fastmath=False, nogil=True)
