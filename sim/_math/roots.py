"""One bracketed root finder for the kernels: bracket widening, then Illinois regula falsi.

Used by the film-temperature solve (sim.physics.friction) and the roller and cage speed solves
(sim.solvers.kinematics), on falling functions of one variable.

The finder works by reverse communication: :func:`root_search` opens a search, and the caller
evaluates the function at ``search.x`` and hands the value to :func:`root_search_step` until
``search.done``. All decisions (widening, regula falsi, Illinois, stopping) are made here; a
caller's loop is only its function evaluation::

    search = root_search(lo, f(lo), hi, tol_f, tol_x, max_steps)
    while not search.done:
        search = root_search_step(search, f(search.x))

Why not the finder calling f itself: numba can pass a jitted function as an argument, but a
kernel that passes one embeds the function object's address ("dynamic globals") and cannot be
cached (numba issue #2956), and a finder made per function by a factory closure misses the
on-disk cache on every compile (numba issue #6264). The state is a named tuple passed by value,
which numba compiles and caches like any other argument.
"""
from collections import namedtuple

from sim._math.jit import internal_kernel

# State of a bracketed root search. x: where the caller evaluates next, or the root once done;
# (lo, hi), (flo, fhi): bracket and function values at its ends (one end's value is pending
# while bracketing); side: the end the last Illinois step kept (-1 lo, +1 hi, 0 none yet);
# steps: widenings while bracketing, then regula falsi steps; refining: a sign change is
# bracketed and x is a regula falsi point (else x is a bracket end awaiting its value);
# done, converged: finished, and with |f(x)| <= tol_f or |hi - lo| <= tol_x;
# bracketed: a sign change was found (False: the widening gave up, x means nothing);
# tol_f, tol_x, max_steps: the stopping rule of root_search_step.
RootSearch = namedtuple("RootSearch", ["x", "lo", "hi", "flo", "fhi", "side", "steps", "refining", "done",
                                       "converged", "bracketed", "tol_f", "tol_x", "max_steps"])

# Each widening moves the interval by twice its span towards the root, keeping the near end (the
# span doubles per step, so a root k spans away is bracketed in O(log k) evaluations).
WIDEN_SPANS = 2.0
# Illinois: the value at an end kept twice in a row is halved (Dowell & Jarratt 1971).
ILLINOIS_FACTOR = 0.5


@internal_kernel
def root_search(lo, flo, hi, tol_f, tol_x, max_steps):
    """Open a root search on the guess (lo, hi) with the value f(lo) = flo; asks for f(hi).

    Parameters
    ----------
    lo, hi : float
        First guess of a bracket (it is widened until f changes sign).
    flo : float
        f(lo).
    tol_f, tol_x : float
        Absolute tolerances on f (a point with |f| <= tol_f is the root) and on the bracket
        width (0: f only).
    max_steps : int
        Widenings allowed, and then regula falsi steps allowed.

    Returns
    -------
    RootSearch
        Done at lo if |flo| <= tol_f, else asking for f at ``x = hi``.
    """
    found = abs(flo) <= tol_f
    return RootSearch(lo if found else hi, lo, hi, flo, flo, 0, 0, False, found, found, found, tol_f, tol_x,
                      int(max_steps))


@internal_kernel
def root_search_step(search, fx):
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

    Returns
    -------
    RootSearch
    """
    x, lo, hi, flo, fhi, side, steps = search.x, search.lo, search.hi, search.flo, search.fhi, search.side, search.steps
    refining, done, converged, bracketed = search.refining, False, False, search.bracketed
    if abs(fx) <= search.tol_f:
        done = converged = bracketed = True
    elif refining:
        # Illinois update (Dowell & Jarratt 1971): regula falsi that scales the value of an end
        # kept twice in a row by ILLINOIS_FACTOR
        if fx * fhi > 0.0:
            if side == -1:
                flo *= ILLINOIS_FACTOR
            hi, fhi, side = x, fx, -1
        else:
            if side == 1:
                fhi *= ILLINOIS_FACTOR
            lo, flo, side = x, fx, 1
        steps += 1
        if abs(hi - lo) <= search.tol_x:
            x = 0.5 * (lo + hi)
            done = converged = True
        elif steps >= search.max_steps:
            done = True
    else:
        # bracketing: x is the end whose value was pending
        if x == hi:
            fhi = fx
        else:
            flo = fx
        if flo * fhi <= 0.0:
            refining = bracketed = True
            side = 0
            steps = 0
        elif steps >= search.max_steps:
            done = True
        else:
            # widen towards the root of a falling function, keeping the near end; the new
            # end's value is pending
            span = hi - lo
            if flo > 0.0:          # both ends positive: the root lies above
                lo, hi, flo = hi, hi + WIDEN_SPANS * span, fhi
                x = hi
            else:
                lo, hi, fhi = lo - WIDEN_SPANS * span, lo, flo
                x = lo
            steps += 1
    if refining and not done:
        x = hi - fhi * (hi - lo) / (fhi - flo)          # regula falsi: zero of the secant
    return RootSearch(x, lo, hi, flo, fhi, side, steps, refining, done, converged, bracketed, search.tol_f,
                      search.tol_x, search.max_steps)
