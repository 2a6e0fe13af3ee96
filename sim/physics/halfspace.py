"""Half-space reference solver for frictionless normal contact (test-only).

This module is a *reference* against which the slice model of roller-raceway line
contacts is checked (pressure distributions, edge-stress peaks). It is not used by the
simulation itself and favours clarity over speed, but is fully vectorised numpy and
solves grids of a few 10^4 cells in a fraction of a second.

Model
-----
Both bodies are approximated by elastic half-spaces (Johnson, *Contact Mechanics*,
Cambridge University Press, 1985, ch. 3-4). Only their combined plane-strain modulus
matters,

.. math:: \\frac{1}{E^*} = \\frac{1-\\nu_1^2}{E_1} + \\frac{1-\\nu_2^2}{E_2}.

The potential contact area is discretised into an ``n_x x n_y`` grid of rectangular
cells of size ``dx x dy`` (x along the roller axis, y in rolling direction). The pressure
is constant on each cell; the combined surface normal displacement at cell centres is
``u = K * p`` (discrete convolution) with the influence coefficients ``K`` of Love's
closed form for uniform pressure on a rectangle (Love, Phil. Trans. R. Soc. A 228, 1929;
Johnson 1985, eq. 3.25), see :func:`influence_coefficients_rectangle`.

The gap is ``h = h0 - delta + u(p)`` with the initial separation ``h0`` and the rigid
approach ``delta``. The complementarity conditions ``p >= 0, h >= 0, p h = 0`` are
solved with the conjugate-gradient method of Polonsky & Keer (Wear 231, 1999,
pp. 206-219), optionally with the total-load constraint. The convolution is evaluated
by the DC-FFT scheme of Liu, Wang & Liu (Wear 243, 2000, pp. 101-111): kernel and
pressure are zero-padded to twice the grid size so that the circular FFT convolution
equals the linear (non-periodic) one exactly.

Units: lengths [mm], pressures and moduli [N/mm^2 = MPa], forces [N].
"""
import numpy as np

__all__ = [
    "influence_coefficients_rectangle",
    "solve_contact_halfspace",
    "line_load_along_x",
]


def _ln_sum(a, b):
    """``ln(a + sqrt(a^2 + b^2))`` evaluated without cancellation.

    Parameters
    ----------
    a, b : np.ndarray
        Coordinates [mm]; ``b`` must be non-zero wherever ``a < 0``.

    Returns
    -------
    np.ndarray
        The logarithm (argument in [mm]).

    Notes
    -----
    For ``a < 0`` the sum ``a + r`` cancels; the identity
    ``a + r = b^2 / (r - a)`` is used instead.
    """
    r = np.hypot(a, b)
    pos = a >= 0.0
    with np.errstate(divide="ignore"):
        return np.where(pos, np.log(np.where(pos, a + r, 1.0)),
                        np.log(np.where(pos, 1.0, b * b / (r - a))))


def _love_corner(x, y):
    """Corner function of Love's rectangle solution.

    Parameters
    ----------
    x, y : np.ndarray
        Coordinates of a rectangle corner relative to the field point [mm]
        (never both zero).

    Returns
    -------
    np.ndarray
        ``F(x, y) = x ln(y + r) + y ln(x + r)``, ``r = sqrt(x^2 + y^2)`` [mm, up to an
        additive ``ln`` of a length that cancels in the four-corner sum].

    Notes
    -----
    ``d^2 F / dx dy = 1 / r``, so the four-corner difference of ``F`` is the integral of
    ``1/r`` over the rectangle (Love 1929; Johnson 1985, eq. 3.25).
    """
    return x * _ln_sum(y, x) + y * _ln_sum(x, y)


def influence_coefficients_rectangle(nx, ny, dx, dy, E_star):
    """Influence coefficients of uniform pressure on rectangular cells (Love 1929).

    The combined normal surface displacement of two half-spaces at the centre of cell
    ``(i, j)`` due to a unit uniform pressure acting on cell ``(k, l)`` of a uniform grid
    is (Love 1929; Johnson 1985, eq. 3.25, with ``(1-nu^2)/E`` replaced by ``1/E*``)

    .. math::

        K(X, Y) = \\frac{1}{\\pi E^*}\\,\\bigl[F(X+a, Y+b) - F(X+a, Y-b)
                  - F(X-a, Y+b) + F(X-a, Y-b)\\bigr],

        F(x, y) = x \\ln\\!\\bigl(y + \\sqrt{x^2+y^2}\\bigr)
                + y \\ln\\!\\bigl(x + \\sqrt{x^2+y^2}\\bigr),

    with the centre offset ``X = (i-k) dx``, ``Y = (j-l) dy`` and the half cell sizes
    ``a = dx/2``, ``b = dy/2``. Expanding the four corners gives Love's form
    ``(X+a) ln[((Y+b)+r_++)/((Y-b)+r_+-)] + (Y+b) ln[((X+a)+r_++)/((X-a)+r_-+)] + ...``.

    Parameters
    ----------
    nx, ny : int
        Number of cells along x (roller axis) and y (rolling direction) [-].
    dx, dy : float
        Cell sizes along x and y [mm].
    E_star : float
        Combined modulus ``1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2`` [N/mm^2].

    Returns
    -------
    np.ndarray, shape (2*nx-1, 2*ny-1)
        Displacement per unit pressure [mm/MPa]; entry ``[nx-1+di, ny-1+dj]`` belongs to
        the index offset ``(di, dj) = (i-k, j-l)``.
    """
    nx, ny = int(nx), int(ny)
    if nx < 1 or ny < 1:
        raise ValueError("nx and ny must be >= 1")
    if not (dx > 0 and dy > 0 and E_star > 0):
        raise ValueError("dx, dy and E_star must be positive")
    X = (np.arange(-(nx - 1), nx) * dx)[:, None]
    Y = (np.arange(-(ny - 1), ny) * dy)[None, :]
    a, b = 0.5 * dx, 0.5 * dy
    s = (_love_corner(X + a, Y + b) - _love_corner(X + a, Y - b)
         - _love_corner(X - a, Y + b) + _love_corner(X - a, Y - b))
    return s / (np.pi * E_star)


def _fast_len(n):
    """Smallest ``m >= n`` of the form ``2^a 3^b 5^c`` (fast FFT length) [-]."""
    best = 2 * n
    p2 = 1
    while p2 < best:
        p3 = p2
        while p3 < best:
            p5 = p3
            while p5 < n:
                p5 *= 5
            best = min(best, p5)
            p3 *= 3
        p2 *= 2
    return best


class _Convolver:
    """DC-FFT linear convolution ``u = K * p`` (Liu, Wang & Liu 2000).

    Parameters
    ----------
    K : np.ndarray, shape (2*nx-1, 2*ny-1)
        Influence coefficients [mm/MPa] from :func:`influence_coefficients_rectangle`.
    nx, ny : int
        Grid size [-].
    """

    def __init__(self, K, nx, ny):
        self.nx, self.ny = nx, ny
        # padded size >= 2n-1: the circular convolution has no periodic wrap-around
        self.shape = (_fast_len(2 * nx - 1), _fast_len(2 * ny - 1))
        Kc = np.zeros(self.shape)
        Kc[: 2 * nx - 1, : 2 * ny - 1] = K
        Kc = np.roll(Kc, (-(nx - 1), -(ny - 1)), axis=(0, 1))  # offset 0 -> index 0
        self.K_hat = np.fft.rfft2(Kc)

    def __call__(self, p):
        """Displacement [mm] at the cell centres for cell pressures ``p`` [MPa]."""
        u = np.fft.irfft2(np.fft.rfft2(p, s=self.shape) * self.K_hat, s=self.shape)
        return u[: self.nx, : self.ny]


def solve_contact_halfspace(h0, dx, dy, E_star, load=None, approach=None,
                            tol=1e-10, max_iter=2000):
    """Frictionless normal contact of two half-spaces on a rectangular grid.

    Solves ``p >= 0``, ``h = h0 - delta + u(p) >= 0``, ``p h = 0`` with the
    conjugate-gradient method of Polonsky & Keer (Wear 231, 1999) and DC-FFT
    convolution (Liu, Wang & Liu, Wear 243, 2000). Exactly one of ``load`` and
    ``approach`` must be given:

    * ``load``: the total load ``W = sum(p) dx dy`` is imposed (Polonsky & Keer's load
      constraint, the mean gap over the contact set is removed every step) and the
      approach ``delta`` is an output;
    * ``approach``: ``delta`` is imposed and the same CG iteration is run without the
      load constraint (plain projected CG on the complementarity problem).

    Parameters
    ----------
    h0 : array_like, shape (nx, ny)
        Initial separation at the cell centres before the rigid approach [mm]; may be
        negative (interference). Use a large value (e.g. 1 mm) for points that can
        never touch (outside a roller's length).
    dx, dy : float
        Cell sizes along x (axis 0) and y (axis 1) [mm].
    E_star : float
        Combined modulus ``1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2`` [N/mm^2].
    load : float, optional
        Total normal load ``W`` [N], ``> 0``.
    approach : float, optional
        Rigid approach ``delta`` [mm].
    tol : float
        Convergence tolerance on the relative pressure change per iteration,
        ``sum|p_new - p_old| / sum p_new`` [-] (Polonsky & Keer's criterion).
    max_iter : int
        Maximum number of CG iterations [-].

    Returns
    -------
    p : np.ndarray, shape (nx, ny)
        Cell pressures [MPa].
    approach : float
        Rigid approach ``delta`` [mm] (the input value in approach mode).
    converged : bool
        Whether ``tol`` was reached within ``max_iter`` iterations.
    iterations : int
        Number of CG iterations performed [-].

    Raises
    ------
    ValueError
        If neither or both of ``load``/``approach`` are given (message names them), or
        if ``load`` is not positive or ``h0`` is not 2-D.
    """
    if (load is None) == (approach is None):
        raise ValueError("give exactly one of 'load' [N] or 'approach' [mm] "
                         f"(got load={load!r}, approach={approach!r})")
    if load is not None and not load > 0:
        raise ValueError(f"'load' must be positive [N], got {load!r}")
    h0 = np.asarray(h0, dtype=float)
    if h0.ndim != 2:
        raise ValueError(f"'h0' must be 2-D (nx, ny), got shape {h0.shape}")
    nx, ny = h0.shape
    area = dx * dy
    conv = _Convolver(influence_coefficients_rectangle(nx, ny, dx, dy, E_star), nx, ny)
    load_mode = load is not None

    # ---- initial guess ----------------------------------------------------------
    if load_mode:
        # uniform pressure on the quarter of the cells with the smallest initial
        # separation (any p >= 0 with the right load is admissible; this one is cheap)
        h_rel = h0 - h0.min()
        span = np.percentile(h_rel, 25.0)
        mask = h_rel <= span if span > 0 else np.ones_like(h0, dtype=bool)
        p = np.where(mask, 1.0, 0.0)
        p *= load / (area * p.sum())
    else:
        delta = float(approach)
        interf = np.maximum(delta - h0, 0.0)
        if not interf.any():
            return np.zeros_like(h0), delta, True, 0
        u1 = conv(interf)
        p = interf * (interf.max() / u1.max())   # pressure scale from rigid overlap

    # ---- Polonsky & Keer (1999) CG iteration --------------------------------------
    G_old = 1.0
    t = np.zeros_like(h0)
    restart = True             # delta = 0 in P&K notation (steepest-descent step)
    converged = False
    it = 0
    g_mean = 0.0
    for it in range(1, max_iter + 1):
        contact = p > 0.0
        if not contact.any():
            # complete loss of contact: cannot happen in load mode (p rescaled);
            # in approach mode there is then no overlap left either
            break
        g = h0 + conv(p)
        if load_mode:
            g_mean = g[contact].mean()
            g = g - g_mean                   # gap with the current approach
        else:
            g = g - delta
        G = np.sum(g[contact] ** 2)
        beta = 0.0 if restart else G / G_old
        t = np.where(contact, g + beta * t, 0.0)
        G_old = G
        r = conv(t)
        if load_mode:
            r = r - r[contact].mean()
        rt = np.sum(r[contact] * t[contact])
        if not rt > 0.0:
            # no descent possible: exact solution if the contact gap vanishes,
            # otherwise a breakdown that is reported as not converged
            converged = G == 0.0
            break
        tau = np.sum(g[contact] * t[contact]) / rt
        p_old = p
        p = p - tau * t
        p = np.maximum(p, 0.0)
        overlap = (p <= 0.0) & (g < 0.0)
        if overlap.any():
            restart = True
            p = np.where(overlap, p - tau * g, p)
        else:
            restart = False
        if load_mode:
            p *= load / (area * p.sum())
        psum = p.sum()
        if psum <= 0.0:
            p = np.zeros_like(p)
            converged = True
            break
        err = np.abs(p - p_old).sum() / psum
        if err < tol:
            converged = True
            break

    if load_mode:
        contact = p > 0.0
        delta = float((h0 + conv(p))[contact].mean())
    return p, delta, converged, it


def line_load_along_x(p, dy):
    """Load per unit length along the roller axis.

    Parameters
    ----------
    p : array_like, shape (nx, ny)
        Cell pressures [MPa].
    dy : float
        Cell size in rolling direction [mm].

    Returns
    -------
    np.ndarray, shape (nx,)
        ``q_i = sum_j p_ij dy`` [N/mm] per x cell.
    """
    return np.asarray(p, dtype=float).sum(axis=1) * dy
