"""One bracketed root finder for the kernels: bracket widening, then Illinois regula falsi.

Used by the film-temperature solve (sim.physics.friction) and the roller and cage speed solves
(sim.solvers.kinematics), on falling functions of one variable.

The finder works by reverse communication: :func:`root_search` opens a search, and the caller
evaluates the function at ``search.x`` and hands the value to :func:`root_search_step` until
``search.done``. All decisions (widening, regula falsi, Illinois, stopping) are made here; a
caller's loop is only its function evaluation::

    search = root_search(lo, f(lo), hi, tol_f)
    while not search.done:
        search = root_search_step(search, f(search.x), tol_f, tol_x, max_steps)

Why not the finder calling f itself: numba can pass a jitted function as an argument, but a
kernel that passes one embeds the function object's address ("dynamic globals") and cannot be
cached (numba issue #2956), and a finder made per function by a factory closure misses the
on-disk cache on every compile (numba issue #6264). The state is a named tuple passed by value,
which numba compiles and caches like any other argument.
"""
from collections import namedtuple

from sim._math.jit import kernel

# State of a bracketed root search. x: where the caller evaluates next, or the root once done;
# (lo, hi), (flo, fhi): bracket and function values at its ends (one end's value is pending
# while bracketing); side: the end the last Illinois step kept (-1 lo, +1 hi, 0 none yet);
# steps: widenings while bracketing, then regula falsi steps; refining: a sign change is
# bracketed and x is a regula falsi point (else x is a bracket end awaiting its value);
# done, converged: finished, and with |f(x)| <= tol_f or |hi - lo| <= tol_x;
# bracketed: a sign change was found (False: the widening gave up, x means nothing).
RootSearch = namedtuple("RootSearch", ["x", "lo", "hi", "flo", "fhi", "side", "steps", "refining", "done",
                                       "converged", "bracketed"])

# Each widening moves the interval by twice its span towards the root (the bracket triples in
# reach per step, so a root k spans away is found in O(log k) evaluations).
WIDEN_SPANS = 2.0
# Illinois: the value at an end kept twice in a row is halved (Dowell & Jarratt 1971).
ILLINOIS_FACTOR = 0.5


@kernel
def _widen(lo, hi, flo, fhi):
    """One step of bracketing the root of a falling function when f(lo), f(hi) have the same
    sign: move the interval (lo, hi) by WIDEN_SPANS spans towards the root, keeping the near end.
    Returns (lo, hi, flo, fhi, x): x is the new end (lo or hi), whose value is pending."""
    span = hi - lo
    if flo > 0.0:          # both ends positive: the root lies above
        x = hi + WIDEN_SPANS * span
        return hi, x, fhi, fhi, x
    x = lo - WIDEN_SPANS * span
    return x, lo, flo, flo, x


@kernel
def _illinois(lo, hi, flo, fhi, x, fx, side):
    """Illinois update of a bracket (lo, hi) with the new point (x, fx) (Dowell & Jarratt 1971):
    regula falsi that halves the kept end's value when the same end is kept twice.
    Returns (lo, hi, flo, fhi, side)."""
    if fx * fhi > 0.0:
        if side == -1:
            flo *= ILLINOIS_FACTOR
        return lo, x, flo, fx, -1
    if side == 1:
        fhi *= ILLINOIS_FACTOR
    return x, hi, fx, fhi, 1


@kernel
def _regula_falsi(lo, hi, flo, fhi):
    """Zero of the secant through (lo, flo) and (hi, fhi), written from the hi end."""
    return hi - fhi * (hi - lo) / (fhi - flo)


@kernel
def root_search(lo, flo, hi, tol_f):
    """Open a root search on the guess (lo, hi) with the value f(lo) = flo; asks for f(hi).

    Parameters
    ----------
    lo, hi : float
        First guess of a bracket (it is widened until f changes sign).
    flo : float
        f(lo).
    tol_f : float
        Absolute tolerance on f: a point with |f| <= tol_f is the root.

    Returns
    -------
    RootSearch
        Done at lo if |flo| <= tol_f, else asking for f at ``x = hi``.
    """
    if abs(flo) <= tol_f:
        return RootSearch(lo, lo, hi, flo, flo, 0, 0, False, True, True, True)
    return RootSearch(hi, lo, hi, flo, flo, 0, 0, False, False, False, False)


@kernel
def root_search_step(search, fx, tol_f, tol_x, max_steps):
    """Advance a root search by the value fx = f(search.x).

    A point with |f| <= tol_f is the root. While f(lo), f(hi) have the same sign the bracket
    is widened (at most ``max_steps`` times, f assumed falling); then Illinois regula falsi
    steps (at most ``max_steps``) until |f| <= tol_f or the bracket is no wider than tol_x
    (then x is its midpoint). Out of steps: done, not converged, x the last point evaluated.

    Parameters
    ----------
    search : RootSearch
        The state of :func:`root_search` or of the previous step, not done.
    fx : float
        f(search.x).
    tol_f, tol_x : float
        Absolute tolerances on f and on the bracket width (0: f only).
    max_steps : int
        Widenings allowed, and then regula falsi steps allowed.

    Returns
    -------
    RootSearch
    """
    x, lo, hi, flo, fhi, side, steps = search.x, search.lo, search.hi, search.flo, search.fhi, search.side, search.steps
    if abs(fx) <= tol_f:
        return RootSearch(x, lo, hi, flo, fhi, side, steps, search.refining, True, True, True)
    if search.refining:
        lo, hi, flo, fhi, side = _illinois(lo, hi, flo, fhi, x, fx, side)
        steps += 1
        if abs(hi - lo) <= tol_x:
            return RootSearch(0.5 * (lo + hi), lo, hi, flo, fhi, side, steps, True, True, True, True)
        if steps >= max_steps:
            return RootSearch(x, lo, hi, flo, fhi, side, steps, True, True, False, True)
        return RootSearch(_regula_falsi(lo, hi, flo, fhi), lo, hi, flo, fhi, side, steps, True, False, False, True)
    # bracketing: x is the end whose value was pending
    if x == hi:
        fhi = fx
    else:
        flo = fx
    if flo * fhi <= 0.0:
        return RootSearch(_regula_falsi(lo, hi, flo, fhi), lo, hi, flo, fhi, 0, 0, True, False, False, True)
    if steps >= max_steps:
        return RootSearch(x, lo, hi, flo, fhi, side, steps, False, True, False, False)
    lo, hi, flo, fhi, x = _widen(lo, hi, flo, fhi)
    return RootSearch(x, lo, hi, flo, fhi, side, steps + 1, False, False, False, False)
