"""One bracketed root finder for the kernels: bracket widening and Illinois regula falsi.

Used by the film-temperature solve (sim.physics.friction) and the roller and cage speed solves
(sim.solvers.kinematics), on falling functions of one variable.
"""
from sim._math.jit import kernel


@kernel
def widen(lo, hi, flo, fhi):
    """One step of bracketing the root of a falling function: move the interval (lo, hi) by
    twice its span towards the root. Returns (lo, hi, flo, fhi, x, x_is_hi): x is the new
    end, whose function value the caller computes and stores in flo or fhi."""
    span = hi - lo
    if flo > 0.0:          # both ends positive: the root lies above
        return hi, hi + 2.0 * span, fhi, fhi, hi + 2.0 * span, True
    return lo - 2.0 * span, lo, flo, flo, lo - 2.0 * span, False


@kernel
def illinois(lo, hi, flo, fhi, x, fx, side):
    """Illinois update of a bracket (lo, hi) with the new point (x, fx) (Dowell & Jarratt 1971):
    regula falsi that halves the kept end's value when the same end is kept twice.
    Returns (lo, hi, flo, fhi, side)."""
    if fx * fhi > 0.0:
        if side == -1:
            flo *= 0.5
        return lo, x, flo, fx, -1
    if side == 1:
        fhi *= 0.5
    return x, hi, fx, fhi, 1
