"""Slice elasticity: load per slice from the rigid penetrations.

Two models (MODEL.md 3):

- independent slices (ISO/TS 16281): each slice carries q = k delta^(10/9) on its own;
- elastically coupled slices (the default), in the spirit of the Alternative Slicing
  Technique of Teutsch & Sauer (2004) (thesis 5.3): the surface deflection of a slice is
  the half-space (Boussinesq) deflection under the loads of all slices. The slice load is
  spread uniformly along the slice and, across the rolling direction, as a Hertzian
  semi-ellipse of half-width b (Johnson eq. 4.43). A load on one slice thus deflects its
  neighbours, and an end slice, with neighbours on one side only, carries more load for
  the same penetration: the edge stress peak of an unprofiled roller (thesis Fig. 5.4).

Influence numbers (deflection of both bodies per unit line load, mm / (N/mm)), all evaluated on
the centre line of the receiving slice (y = 0), for slices w apart on a uniform grid:

- i == k: the centre deflection of the strip itself with its semi-elliptic pressure
  (:func:`self_deflection`): (8/(pi^2 E*)) I(w / (2 b_k));
- i != k, |x_k - x_i| = m w: the same strip (load q_i, half-width b_i) seen from m w away
  (Johnson eq. 3.20 integrated over the strip, x from (m - 1/2) w to (m + 1/2) w):
      C_ki(b_i) = (4/(pi^2 E*)) [I((m + 1/2) w / b_i) - I((m - 1/2) w / b_i)],
      I(beta) = int_0^1 sqrt(1 - t^2) asinh(beta / t) dt.
  Its logarithmic part is the line load on the axis, 1/(pi E*) ln((m + 1/2)/(m - 1/2))
  (:func:`influence_matrix`); the rest, (4/(pi^2 E*)) [R(.) - R(.)] with the remainder R of
  :func:`strip_remainder`, is the strip's width: it weakens the nearest neighbours' coupling by
  2 % at w / b = 3 and by 40 % at w / b = 0.3, and it depends on the source's load through b_i
  (so it enters the Newton tangent, :func:`_neighbour_tables`). With line loads alone a slice's
  own tangent compliance and the alternating sum of its neighbours' cancel at w / b = 0.728 and
  narrower slices solved to a checkerboard of loaded and unloaded slices
  (tests/convergence/test_slices.py); with the strip widths the alternating mode keeps a positive
  compliance at every w / b (the same test).

For a uniformly loaded roller of length L and w >> b the sum telescopes to
(2 q/(pi E*)) (ln(L/b) + 1/2 + ln 2), independent of the slice width: the coupled model
converges with the number of slices.
"""
from collections import namedtuple

import numpy as np

from sim._math.jit import internal_kernel, kernel
from sim._math.linalg import solve_dense
from sim.physics.contact import hertz_line_half_width

# solver.elasticity: independent slices (ISO/TS 16281) or elastically coupled slices
INDEPENDENT, COUPLED = 0, 1
ELASTICITY_MODES = {"independent": INDEPENDENT, "coupled": COUPLED}

# Slice elasticity of one bearing for the kernels (a numba-supported named tuple):
# C (N, N): off-diagonal influence numbers [mm per N/mm] (influence_matrix); E_star: contact
# modulus [MPa]; mode: ELASTICITY_MODES value; k_line: line stiffness of independent slices
# [N/mm per mm^(10/9)] (independent_slice_loads).
SliceElasticity = namedtuple("SliceElasticity", ["C", "E_star", "mode", "k_line"])

# Iteration caps of coupled_slice_loads: ACTIVE_SET_SWITCHES x (n + 1) passes of the active set
# for n slices (each pass that does not end the solve releases or adds a slice: room for every
# slice to switch a few times), NEWTON_MAX_ITER Newton iterations on one active set (the
# deflections are smooth and nearly linear in the loads: a few suffice, the cap only stops a
# stalled solve).
ACTIVE_SET_SWITCHES = 4
NEWTON_MAX_ITER = 60
# Start of the line load from a self deflection (_load_from_self_deflection): the wide-strip
# deflection u = (2 q / (pi E*)) (ln(w/b) + 1/2 + ln 2) with its log term taken as
# WIDE_STRIP_LOG_START (w/b ~ 120), then SELF_DEFLECTION_FIXED_POINT_ITER fixed-point steps
# q <- q u / u_self(q): u_self depends on q through ln(1/b) ~ -ln(q)/2 only, so each step divides
# the error by ~10; the result only starts the Newton iteration.
WIDE_STRIP_LOG_START = 6.0
SELF_DEFLECTION_FIXED_POINT_ITER = 4
# Points of an end strip's profile table (``end_drop`` of loaded_lengths, edge_interference): the
# rigid gap's excess over its linear extrapolation from the two end slice centres, at
# END_DROP_POINTS points equally spaced over the outer half of the end strip (the last at the roller
# end). The contact end is then located between two table points by linear interpolation, to
# |f''| (w / (2 M))^2 / 8 over the field's slope: for the logarithmic crown of a TRB 32208 (10-40
# slices), 0.07-0.5 % of w, 2 % of w for an end 0.04 w from the roller end where the crown's
# curvature is largest, where the straight extrapolation alone erred by up to 0.2 w
# (tests/convergence/test_slices.py); numerical choice.
END_DROP_POINTS = 8


def influence_matrix(x, w, E_star):
    """Off-diagonal line-load influence numbers (diagonal zero; the self term is load dependent):
    the logarithmic part of the strip influences (module docstring), which does not depend on the
    loads; :func:`coupled_slice_loads` adds the strips' widths.

    Parameters
    ----------
    x : ndarray (N,)
        Slice centres [mm].
    w : float
        Slice width [mm].
    E_star : float
        Contact modulus [N/mm^2].

    Returns
    -------
    ndarray (N, N)
        C_ki [mm per N/mm] (module docstring).
    """
    dist = np.abs(x[:, None] - x[None, :])
    np.fill_diagonal(dist, w)  # placeholder > w/2 keeps the log finite; the diagonal is zeroed below
    C = np.log((dist + 0.5 * w) / (dist - 0.5 * w)) / (np.pi * E_star)
    np.fill_diagonal(C, 0.0)
    return np.ascontiguousarray(C)


# Remainder R(beta) of I(beta) (strip_remainder). From STRIP_SERIES_BETA on, the series of
# ln((1 + sqrt(1 + x)) / 2) = x/4 - 3 x^2/32 + 5 x^3/96 - ... (x = sin^2(phi) / beta^2 < 1)
# integrated term by term (int_0^{pi/2} cos^2 sin^2n dphi = pi/16, pi/32, 5 pi/256, ...; sympy):
# R = sum_n STRIP_SERIES[n] beta^-2(n+1), six terms, error < 2e-8 at beta = 2 against adaptive
# quadrature (I >= 2 there). Below, Gauss-Legendre on (0, pi/2); its integrand varies on the scale
# beta near phi = 0, so the rule has 16 nodes below STRIP_NARROW_BETA (error 6e-8 at beta = 0.05)
# and 8 above (4e-6 at beta = 0.25, 4e-8 from 0.4; I >= 0.37 there).
STRIP_SERIES_BETA = 2.0
STRIP_SERIES = np.pi * np.array([1.0 / 64.0, -3.0 / 1024.0, 25.0 / 24576.0, -245.0 / 524288.0,
                                 1323.0 / 5242880.0, -2541.0 / 16777216.0])
STRIP_NARROW_BETA = 0.25
# Far neighbours (_neighbour_tables): from STRIP_FAR_BETA on the series' first two terms, error
# < 25 pi / (24576 beta^6) = 1.2e-8, so that the N^2 table costs a few products per entry.
STRIP_FAR_BETA = 8.0


def _remainder_rule(nodes):
    """Gauss-Legendre rule of the remainder integral on (0, pi/2): sin^2 of the nodes and the weights
    times cos^2 (the kernel then needs one sqrt and one log per node)."""
    t, wt = np.polynomial.legendre.leggauss(nodes)
    phi = 0.25 * np.pi * (t + 1.0)
    return np.sin(phi) ** 2, 0.25 * np.pi * wt * np.cos(phi) ** 2


_WIDE_S2, _WIDE_W = _remainder_rule(8)
_NARROW_S2, _NARROW_W = _remainder_rule(16)


@internal_kernel
def _remainder_quadrature(beta, s2, wc2):
    """R(beta) and dR/dbeta by the Gauss-Legendre rule (sin^2 of the nodes, weights x cos^2)."""
    rem = 0.0
    drem = 0.0
    for i in range(s2.shape[0]):
        root = np.sqrt(1.0 + s2[i] / (beta * beta))
        rem += wc2[i] * np.log(0.5 * (1.0 + root))
        drem += wc2[i] * (-(s2[i] / beta**3) / root) / (1.0 + root)
    return rem, drem


@kernel
def strip_remainder(beta):
    """Remainder of the strip integral I(beta) = int_0^1 sqrt(1 - t^2) asinh(beta / t) dt
    = (pi/4) ln(2 beta) + (pi/8)(1 + 2 ln 2) + R(beta), beta > 0:

        R(beta) = int_0^{pi/2} cos^2(phi) ln((1 + sqrt(1 + sin^2(phi) / beta^2)) / 2) dphi,

    returned with dR/dbeta (series or quadrature, see STRIP_SERIES_BETA). R -> 0 as beta grows:
    a strip seen from far compared with its Hertz half-width is a line load.
    """
    if beta >= STRIP_SERIES_BETA:
        ib2 = 1.0 / (beta * beta)
        rem = 0.0
        drem = 0.0
        for n in range(STRIP_SERIES.shape[0] - 1, -1, -1):     # Horner in beta^-2
            rem = (rem + STRIP_SERIES[n]) * ib2
            drem = drem * ib2 - 2.0 * (n + 1) * STRIP_SERIES[n]
        return rem, drem * ib2 / beta
    if beta < STRIP_NARROW_BETA:
        return _remainder_quadrature(beta, _NARROW_S2, _NARROW_W)
    return _remainder_quadrature(beta, _WIDE_S2, _WIDE_W)


@internal_kernel
def self_deflection(q, w, R, E_star):
    """Deflection of a slice under its own load, and its derivative.

    Centre deflection of both half-spaces under a strip of length w carrying q per unit
    length with Hertz's semi-elliptic profile of half-width b (Johnson eqs. 3.20, 4.43):

        u = (1/(pi E*)) int_{-b}^{b} p(y) 2 asinh(w / (2|y|)) dy = (8 q / (pi^2 E*)) I(beta),
        I(beta) = int_0^1 sqrt(1 - t^2) asinh(beta / t) dt,  beta = w / (2 b),

    split as I = (pi/4) ln(2 beta) + (pi/8)(1 + 2 ln 2) + R(beta) (:func:`strip_remainder`).
    For w >> b, R -> 0 and u -> (2q/(pi E*)) (ln(w/b) + 1/2 + ln 2).

    Parameters
    ----------
    q : float
        Line load of the slice [N/mm], > 0.
    w : float
        Slice width [mm].
    R : float
        Radius of relative curvature in the rolling direction [mm].
    E_star : float
        Contact modulus [N/mm^2].

    Returns
    -------
    u, du/dq : float
        Deflection [mm] and its derivative [mm^2/N].
    """
    beta = 0.5 * w / hertz_line_half_width(q, R, E_star)
    rem, drem = strip_remainder(beta)
    integral = 0.25 * np.pi * np.log(2.0 * beta) + 0.125 * np.pi * (1.0 + 2.0 * np.log(2.0)) + rem
    dintegral = 0.25 * np.pi / beta + drem
    c = 8.0 / (np.pi * np.pi * E_star)
    return c * q * integral, c * (integral - 0.5 * beta * dintegral)


@internal_kernel
def _neighbour_tables(q, active, w, R, E_star, rem, trem):
    """Strip-width parts of the neighbour influences of the loaded slices (module docstring).

    For source slice i (loaded) and j = 0 .. N-1: rem[i, j] = R(beta_ij) and trem[i, j] =
    d(q R(beta_ij))/dq = R - (beta/2) dR/dbeta, beta_ij = (j + 1/2) w / b_i (b_i ~ sqrt(q_i)). The
    influence of i on k, m = |k - i| >= 1, is C_ki + (4/(pi^2 E*)) (rem[i, m] - rem[i, m - 1]).
    """
    n = q.shape[0]
    for i in range(n):
        if not active[i]:
            continue
        b = hertz_line_half_width(q[i], R[i], E_star)
        for j in range(n):
            beta = (j + 0.5) * w / b
            if beta >= STRIP_FAR_BETA:
                ib2 = 1.0 / (beta * beta)
                r1 = STRIP_SERIES[0] * ib2              # ~ q: d(q r1)/dq = 2 r1
                r2 = STRIP_SERIES[1] * ib2 * ib2        # ~ q^2: d(q r2)/dq = 3 r2
                rem[i, j] = r1 + r2
                trem[i, j] = 2.0 * r1 + 3.0 * r2
            else:
                r, dr = strip_remainder(beta)
                rem[i, j] = r
                trem[i, j] = r - 0.5 * beta * dr


@internal_kernel
def _neighbour_influence(C, c4, rem, trem, k, i):
    """Influence of loaded slice i on slice k != i [mm per N/mm] and its tangent d(q_i C)/dq_i."""
    m = abs(k - i)
    return C[k, i] + c4 * (rem[i, m] - rem[i, m - 1]), C[k, i] + c4 * (trem[i, m] - trem[i, m - 1])


@internal_kernel
def independent_slice_loads(d, k_line, q, dq):
    """Line load of independent slices, ISO/TS 16281.

    Parameters
    ----------
    d : ndarray (N,)
        Rigid penetrations [mm].
    k_line : float
        Line stiffness [N/mm per mm^(10/9)]: q = k_line d^(10/9) per unit length.
    q, dq : ndarray (N,)
        Line loads [N/mm] and dq/dd [N/mm^2] (written).

    Returns
    -------
    int
        Number of loaded slices.
    """
    n = 0
    for k in range(d.shape[0]):
        if d[k] > 0.0:
            q[k] = k_line * d[k] ** (10.0 / 9.0)
            dq[k] = (10.0 / 9.0) * k_line * d[k] ** (1.0 / 9.0)
            n += 1
        else:
            q[k] = 0.0
            dq[k] = 0.0
    return n


@kernel
def coupled_slice_loads(d, C, w, R, E_star, q, active, tol, free):
    """Line loads of elastically coupled slices (complementarity problem).

    Finds q >= 0 with, for every loaded slice, sum_i C_ki(b_i) q_i + u_self(q_k) = d_k, and for
    every unloaded slice sum_i C_ki(b_i) q_i >= d_k (the neighbours' deflection opens the gap),
    C_ki(b_i) the strip influences of the module docstring.
    Active-set Newton, warm-started from ``q``/``active``.

    Parameters
    ----------
    d : ndarray (N,)
        Rigid penetrations [mm].
    C : ndarray (N, N)
        Off-diagonal line-load influence numbers [mm per N/mm] (:func:`influence_matrix`), to which
        the strip widths are added here.
    w : float
        Slice width [mm].
    R : ndarray (N,)
        Radii of relative curvature [mm].
    E_star : float
        Contact modulus [N/mm^2].
    q : ndarray (N,)
        Line loads [N/mm]: warm start in, solution out.
    active : ndarray (N,) bool
        Loaded slices: warm start in, solution out.
    tol : float
        Deflection tolerance [mm].
    free : ndarray (N,)
        Written: the free penetrations d_k - sum_{i != k} C_ki q_i of the solution [mm] (loaded
        slices: their own deflection u_self(q_k) > 0; unloaded ones: minus the gap the neighbours
        open, <= 0 up to ``tol``), from the sums the solve forms anyway; :func:`loaded_lengths`
        places the contact ends by them.

    Returns
    -------
    (converged, iterations)
    """
    n = d.shape[0]
    dmax = 0.0
    nact = 0
    for k in range(n):
        if d[k] > dmax:
            dmax = d[k]
        if active[k] and q[k] > 0.0:
            nact += 1
        else:
            active[k] = False
            q[k] = 0.0
    if dmax <= 0.0:
        for k in range(n):
            q[k] = 0.0
            active[k] = False
            free[k] = d[k]
        return True, 0
    if nact == 0:  # cold start: every penetrating slice, loads from its own deflection only
        for k in range(n):
            if d[k] > 0.0:
                active[k] = True
                q[k] = _load_from_self_deflection(d[k], w, R[k], E_star)
    idx = np.empty(n, dtype=np.int64)
    rem = np.empty((n, n))      # strip-width parts of the neighbour influences (_neighbour_tables)
    trem = np.empty((n, n))
    c4 = 4.0 / (np.pi * np.pi * E_star)
    total = 0
    for outer in range(ACTIVE_SET_SWITCHES * (n + 1)):
        m = 0
        for k in range(n):
            if active[k]:
                idx[m] = k
                m += 1
        changed = False
        # Newton on the active set; a slice whose Newton step crosses zero load is released
        J = np.empty((m, m))
        F = np.empty((m, 1))       # one column: the shape of the other sim._math.linalg.solve_dense call
        tables_current = False     # rem, trem are those of the present q
        for it in range(NEWTON_MAX_ITER):
            total += 1
            fmax = 0.0
            _neighbour_tables(q, active, w, R, E_star, rem, trem)
            tables_current = True
            for a in range(m):
                k = idx[a]
                s = 0.0
                for bb in range(m):
                    i = idx[bb]
                    if i == k:
                        continue
                    c, dc = _neighbour_influence(C, c4, rem, trem, k, i)
                    J[a, bb] = dc
                    s += c * q[i]
                u, du = self_deflection(q[k], w, R[k], E_star)
                J[a, a] = du
                F[a, 0] = s + u - d[k]
                free[k] = d[k] - s
                if abs(F[a, 0]) > fmax:
                    fmax = abs(F[a, 0])
            if fmax <= tol or m == 0:
                break
            dq = solve_dense(J, -F)
            for a in range(m):
                k = idx[a]
                if q[k] + dq[a, 0] <= 0.0:
                    q[k] = 0.0
                    active[k] = False
                    changed = True
            if changed:
                break
            for a in range(m):
                q[idx[a]] += dq[a, 0]
            tables_current = False
        if changed:
            continue
        # add penetrating slices that the loaded slices' deflection does not open (all judged on the
        # solved set, whose strip tables these are; then added together). A converged Newton loop
        # leaves the tables of its solution; only one that ran out of iterations moved q after them.
        if not tables_current:
            _neighbour_tables(q, active, w, R, E_star, rem, trem)
        for k in range(n):
            if not active[k]:
                s = 0.0
                for a in range(m):
                    s += _neighbour_influence(C, c4, rem, trem, k, idx[a])[0] * q[idx[a]]
                free[k] = d[k] - s
        for k in range(n):
            if not active[k] and free[k] > tol:
                active[k] = True
                q[k] = _load_from_self_deflection(free[k], w, R[k], E_star)
                changed = True
        if not changed:
            return True, total
    return False, total


@internal_kernel
def _signed_penetration(free, loaded, k):
    """The signed field of the contact ends at slice k [mm]: free_k on a loaded slice (its own
    deflection, > 0), min(free_k, 0) on an unloaded one (minus the gap its neighbours open)."""
    return free[k] if loaded[k] else min(free[k], 0.0)


@kernel
def loaded_lengths(free, loaded, w, end_drop, out):
    """Loaded length of each slice strip [mm]: the contact ends placed between slice centres.

    The strip of slice k is [x_k - w/2, x_k + w/2] (centres w apart, the end strips reach the
    roller ends). The contact is where the piecewise-linear interpolant of the signed field
    f_k = free_k on loaded slices (> 0), min(free_k, 0) on unloaded ones (the free penetrations of
    :func:`coupled_slice_loads`, the rigid penetrations of independent slices)
    between the slice centres is positive, and beyond the end centres its linear extrapolation from
    the last two centres less the profile's own curvature there (:func:`_outer_half_strip`, the
    table ``end_drop``: a logarithmic crown falls far faster towards the roller end than the line
    through the end centres; session 14's linear extrapolation alone read the TRB 32208's loaded
    length at 40 kN 2.9 % long with 20 slices, and before it the field was extended as a constant);
    ``out[k]`` is its length inside strip k. A strip counts fully when it and its
    neighbours are loaded, and a contact end between a loaded slice k and an unloaded k + 1 lies
    at x_k + w f_k / (f_k - f_{k+1}): at the slice's own deflection against the gap the
    neighbours open. Where a slice enters or leaves contact (f_k -> 0) the end reaches its
    centre from both sides, so the total loaded length is continuous in the pose, where counting
    loaded slices (w each) steps by w. For one contact zone, the sum equals the loaded-slice
    count times w whenever the end fields are equal and opposite (f_k = -f_{k+1}).

    free (N,): free penetrations [mm]; loaded (N,) bool: slices with load; w: slice width [mm];
    end_drop (2, M): the profile table of this contact's ends, end 0 beyond slice 0, end 1 beyond
    slice N - 1 [mm] (:func:`end_profile_drop`; zeros: the plain linear extrapolation); out (N,):
    written [mm].
    """
    n = free.shape[0]
    for k in range(n):
        out[k] = 0.0
    if n == 0:
        return
    fprev = _signed_penetration(free, loaded, np.int64(0))   # not the literal 0: a second, Literal[int] copy
    if fprev > 0.0:
        out[0] += _outer_half_strip(fprev, _signed_penetration(free, loaded, min(np.int64(1), n - 1)), end_drop[0], w)
    for k in range(n - 1):
        fnext = _signed_penetration(free, loaded, k + 1)
        if fprev > 0.0 and fnext > 0.0:
            out[k] += 0.5 * w
            out[k + 1] += 0.5 * w
        elif fprev > 0.0:           # contact ends in (x_k, x_k+1]: t w from x_k
            t = fprev / (fprev - fnext)
            out[k] += min(t, 0.5) * w
            out[k + 1] += max(t - 0.5, 0.0) * w
        elif fnext > 0.0:           # contact starts in [x_k, x_k+1): t w before x_k+1
            t = fnext / (fnext - fprev)
            out[k + 1] += min(t, 0.5) * w
            out[k] += max(t - 0.5, 0.0) * w
        fprev = fnext
    if fprev > 0.0:
        out[n - 1] += _outer_half_strip(fprev, _signed_penetration(free, loaded, max(n - 2, 0)), end_drop[1], w)


@internal_kernel
def _outer_half_strip(f_end, f_next, drop, w):
    """Loaded length [mm] of the outer half of an end strip (from the end slice's centre to the roller
    end) whose slice is loaded (f_end > 0).

    The signed field beyond the end centre, t w away (0 < t <= 1/2), is the line through the end
    centre and its neighbour (f_next), f_end + (f_end - f_next) t, less ``drop`` (M,): how much
    further the rigid gap has opened there than that line says, at t = (i + 1) / (2 M). The rigid
    penetration is the approach (linear in x for a rigid pose) less the profile's gap, and the
    elastic part is smooth, so only the gap's curvature is missing from the line (a pose that
    turns the profile by a small angle changes the table to second order). The contact ends at
    the first table point where the field is <= 0, interpolated linearly from the point before,
    or at the roller end (w / 2) when it stays positive (edge contact, exactly when
    :func:`_contact_edge_interference` is > 0). With a zero table this is the linear
    extrapolation of session 14, to rounding.
    """
    m = drop.shape[0]
    slope = f_end - f_next
    t_prev = 0.0
    f_prev = f_end
    for i in range(m):
        t = 0.5 * (i + 1) / m
        f = f_end + slope * t - drop[i]
        if f <= 0.0:
            return (t_prev + (t - t_prev) * f_prev / (f_prev - f)) * w
        t_prev = t
        f_prev = f
    return 0.5 * w


@internal_kernel
def _contact_edge_interference(free, loaded, end_drop):
    """Interference of one contact at the roller ends, relative to its largest elastic approach [1].

    The signed field of :func:`loaded_lengths` (:func:`_signed_penetration`) is extrapolated
    linearly from the two end centres to each roller end, half a slice beyond the end centre,
    less the profile's gap there beyond that line (the last entry of the end's ``end_drop``
    table, :func:`_outer_half_strip`): g_end = 1.5 g_0 - 0.5 g_1 - drop. g_end > 0 means the
    contact runs onto the roller end: the elastic half-space solution of a
    contact truncated by a sharp edge has a pressure singularity there (like the rigid flat punch,
    p = P / (pi sqrt(a^2 - x^2)): Johnson 1985, Contact Mechanics, chapter 2), so the end slice's
    pressure is then a slice average of a peak that grows without bound as the slices are refined
    (thesis 7.2.1: the "stress concentration in the roller edge"). The extrapolation is capped by
    g_0 so that an unloaded end slice (g_0 <= 0) never counts as edge contact, and is divided by
    the largest g of the contact (its largest own deflection), which makes it dimensionless and
    continuous in the pose as slices enter or leave the contact. Its sign converges with the
    slices once they are narrower than the distance from the contact end to the roller end; its
    magnitude is a margin for the searches (the own deflections depend on the slice width).

    free (N,): free penetrations [mm] (:func:`coupled_slice_loads`); loaded (N,) bool; end_drop
    (2, M): the profile table of both ends [mm] (:func:`loaded_lengths`).
    Returns max over both ends of min(g_end, g_0) / max(g) [1]; -inf for a contact without load
    (no interference anywhere).
    """
    n = free.shape[0]
    m = end_drop.shape[1]
    gmax = 0.0
    for k in range(n):
        if loaded[k] and free[k] > gmax:
            gmax = free[k]
    if gmax <= 0.0:
        return -np.inf
    worst = -np.inf
    for end in range(2):
        k0 = 0 if end == 0 else n - 1
        k1 = min(1, n - 1) if end == 0 else max(n - 2, 0)
        g0 = _signed_penetration(free, loaded, k0)
        g1 = _signed_penetration(free, loaded, k1)
        worst = max(worst, min(1.5 * g0 - 0.5 * g1 - end_drop[end, m - 1], g0) / gmax)
    return worst


@kernel
def edge_interference(free, loaded, end_drop, out):
    """Worst :func:`_contact_edge_interference` of each race over all rollers [1] (> 0: some roller's
    contact with that race runs onto a roller end).

    free (Z, 2, N): free penetrations [mm]; loaded (Z, 2, N) bool; end_drop (2, 2, M): the profile
    table of each race's ends [mm] (:func:`end_profile_drop`); out (2,): written (-inf for a race
    without a loaded contact).
    """
    for s in range(2):
        out[s] = -np.inf
        for r in range(free.shape[0]):
            out[s] = max(out[s], _contact_edge_interference(free[r, s], loaded[r, s], end_drop[s]))


def end_profile_drop(x, gap, w):
    """The profile table of :func:`loaded_lengths` for one race [mm], (2, END_DROP_POINTS).

    x (N >= 2,): slice centres [mm] (along the roller axis, uniform spacing w); gap: callable, the
    unloaded rigid gap between roller and raceway at positions along the roller axis [mm] (array in,
    array out; it may grow without bound at a roller end, like the logarithmic crown);
    w: slice width [mm]. End 0 lies beyond slice 0, end 1 beyond slice N - 1; entry i at
    (i + 1) / (2 M) of w beyond the end centre: the gap there less its linear extrapolation from
    the end centre and its neighbour.
    """
    n = x.shape[0]
    t = 0.5 * np.arange(1, END_DROP_POINTS + 1) / END_DROP_POINTS
    table = np.empty((2, END_DROP_POINTS))
    for end, (k0, k1) in enumerate(((0, 1), (n - 1, n - 2))):
        outward = np.sign(x[k0] - x[k1])
        g0, g1 = gap(np.array([x[k0], x[k1]]))
        table[end] = gap(x[k0] + outward * t * w) - (g0 + (g0 - g1) * t)
    return table


@internal_kernel
def _load_from_self_deflection(u, w, R, E_star):
    """Line load [N/mm] whose self deflection is u [mm] (fixed point on the slowly varying log)."""
    q = u * np.pi * E_star / (2.0 * WIDE_STRIP_LOG_START)
    for it in range(SELF_DEFLECTION_FIXED_POINT_ITER):
        us, dus = self_deflection(q, w, R, E_star)
        q = q * u / us
    return q


@kernel
def coupled_slice_compliance(C, w, R, E_star, q, active, J):
    """Tangent of the coupled slices on the active set: dq/dd = J^-1 (J written, N x N, zero-padded).

    J[a, b] = d(deflection_a)/dq_b for a, b loaded (the neighbours' strip influences with their
    load-dependent widths, _neighbour_influence; the self deflection's du/dq on the diagonal);
    unloaded rows/columns hold the identity so that J stays invertible and dq/dd is zero there
    after masking.
    """
    n = q.shape[0]
    rem = np.empty((n, n))
    trem = np.empty((n, n))
    _neighbour_tables(q, active, w, R, E_star, rem, trem)
    c4 = 4.0 / (np.pi * np.pi * E_star)
    for a in range(n):
        for b in range(n):
            if active[a] and active[b] and a != b:
                J[a, b] = _neighbour_influence(C, c4, rem, trem, a, b)[1]
            else:
                J[a, b] = 1.0 if a == b else 0.0
        if active[a]:
            u, du = self_deflection(q[a], w, R[a], E_star)
            J[a, a] = du
