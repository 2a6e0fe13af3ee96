"""A small numerical solution of the steady 1-D line-contact lubrication problem (test helper).

Used by ``tests/friction/test_rolling_resistance.py`` to check the closed-form rolling-resistance
kernels of :mod:`sim.physics.ehl` against the Reynolds equation itself. Plain numpy, no numba:
it is a reference, not a production kernel.

Problem (Hamrock, Schmid & Jacobson 2004, *Fundamentals of Fluid Film Lubrication*, ch. 16-18;
Venner & Lubrecht 2000, ch. 3): a cylinder of equivalent radius R on a plane, load w per unit
length, surfaces moving at U1 (lower, z = 0) and U2 (upper, z = h) along x; incompressible
Newtonian film with a pressure-dependent viscosity (isoviscous, Barus or Roelands), viscosity
uniform across the film (isothermal).

- Reynolds:      d/dx( h^3/(12 eta) dp/dx ) = u_m dh/dx,   u_m = (U1 + U2)/2
- Film:          h = h0 + x^2/(2R) + v(x),  v = -(4/(pi E')) int p(s) ln|x - s| ds (+ const,
                 absorbed in h0), E' = 2 E* (Hamrock); v = 0 for rigid surfaces
- Load balance:  int p dx = w
- Boundaries:    p = 0 at the inlet (fully flooded: the inlet a few half-widths upstream);
                 Reynolds (Swift-Stieber) outlet p = dp/dx = 0 at the film rupture, imposed by a
                 penalty on negative pressure (Wu 1986), negative pressures of O(1e-4 dX) left.

Dimensionless (Hertz half-width b = sqrt(8 w R/(pi E')), p_h = 2 w/(pi b)): X = x/b,
P = p/p_h, H = h R/b^2, eta_bar = eta/eta0,
    d/dX( H^3/(eta_bar lambda) dP/dX ) = dH/dX,  lambda = 12 eta0 u_m R^2 / (b^3 p_h),
    H = H0 + X^2/2 - (1/pi) int P(S) ln|X - S| dS,  int P dX = pi/2.
Discretisation: uniform grid, conservative central Poiseuille term, second-order upwind wedge
term, pressure piecewise constant per cell in the deformation integral (exact log integral).
Solved by Newton-Raphson on all nodal pressures and H0 together with a dense Jacobian
(Houpert & Hamrock 1986 solved heavily loaded line contacts the same way), damped and with a
backtracking line search on the residual norm. Isothermal and incompressible (the Dowson-
Higginson density would lower the central film by the density rise, ~15 % at 1.3 GPa, and add
compression work to the energy balance; it is left out so that the energy identity is exact).

Outputs per unit length (dimensional, kernel units mm, N, MPa, s): pressure and film; the
tangential shear force of the film on each surface, F_i = int tau_i dx with
    tau_1 = +eta (U2 - U1)/h - (h/2) dp/dx   (on the lower surface, +x),
    tau_2 = -eta (U2 - U1)/h - (h/2) dp/dx   (on the upper surface, +x);
and the viscous dissipation D = int int eta (du/dz)^2 dz dx, evaluated from the velocity field
u(x, z) = U1 + (U2 - U1) z/h + (dp/dx/(2 eta)) (z^2 - z h) by Gauss quadrature across the film.
"""
from dataclasses import dataclass

import numpy as np
from threadpoolctl import threadpool_limits

ROELANDS_ETA_INF = 6.31e-11   # MPa s (6.31e-5 Pa s), Roelands (1966)
ROELANDS_P_R = 196.1          # MPa
PENALTY = 1e8                 # cavitation penalty (times 1/dX), dimensionless


@dataclass
class Solution:
    x: np.ndarray          # node positions [mm]
    p: np.ndarray          # pressure [MPa]
    h: np.ndarray          # film [mm]
    eta: np.ndarray        # viscosity at p [MPa s]
    b: float               # Hertz half-width [mm]
    p_h: float             # Hertz pressure [MPa]
    load: float            # int p dx [N/mm]
    h_c: float             # film at x = 0 [mm]
    h_min: float           # minimum film [mm]
    F1: float              # shear force on the lower surface (speed U1), +x [N/mm]
    F2: float              # shear force on the upper surface (speed U2), +x [N/mm]
    F_poiseuille: float    # int (h/2) dp/dx dx > 0: the rolling (Poiseuille) force retarding each surface [N/mm]
    F_poiseuille_central: float  # the same with the central film (discretisation check) [N/mm]
    dissipation: float     # int int eta (du/dz)^2 dz dx [N/(mm s)] = [N mm/s per mm]
    pressure_moment: float # int p x dx [N]: load times the offset of the pressure centre
    flux: np.ndarray       # volume flux per unit length in the full film, per cell [mm^2/s]
    iterations: int
    residual: float


def _viscosity(p, eta0, alpha, model):
    """eta(p) and d ln(eta)/dp; p [MPa]."""
    if model == "iso":
        return np.full_like(p, eta0), np.zeros_like(p)
    if model == "barus":
        return eta0 * np.exp(alpha * p), np.full_like(p, alpha)
    z = alpha * ROELANDS_P_R / np.log(eta0 / ROELANDS_ETA_INF)
    lnr = np.log(eta0 / ROELANDS_ETA_INF)
    s = 1.0 + np.maximum(p, 0.0) / ROELANDS_P_R
    eta = eta0 * np.exp(lnr * (s ** z - 1.0))
    return eta, lnr * z * s ** (z - 1.0) / ROELANDS_P_R


def _influence(X, dX):
    """K[i, j] = -(1/pi) int_{cell j} ln|X_i - S| dS (exact for a constant pressure per cell)."""
    def G(t):
        a = np.abs(t)
        out = np.zeros_like(t)
        nz = a > 0.0
        out[nz] = t[nz] * np.log(a[nz]) - t[nz]
        return out
    d = X[:, None] - X[None, :]
    return -(G(d + 0.5 * dX) - G(d - 0.5 * dX)) / np.pi


def solve_line_contact(w, R, E_prime, eta0, alpha, U1, U2, *, viscosity="roelands", elastic=True,
                       x_in=-4.0, x_out=1.5, n=601, H0_guess=None, max_iter=200, tol=1e-10, verbose=False):
    """Solve the steady line contact; see the module docstring.

    w [N/mm], R [mm], E' [MPa], eta0 [MPa s], alpha [1/MPa], U1, U2 [mm/s] (mean u_m > 0);
    x_in, x_out in Hertz half-widths. Raises RuntimeError when Newton does not converge.
    """
    u_m = 0.5 * (U1 + U2)
    b = np.sqrt(8.0 * w * R / (np.pi * E_prime))
    p_h = 2.0 * w / (np.pi * b)
    lam = 12.0 * eta0 * u_m * R ** 2 / (b ** 3 * p_h)
    X = np.linspace(x_in, x_out, n)
    dX = X[1] - X[0]
    K = _influence(X, dX) if elastic else np.zeros((n, n))
    quad = np.full(n, dX)
    quad[0] = quad[-1] = 0.5 * dX

    # initial guess: Hertz pressure and a film near the Pan-Hamrock value (elastic); Martin's
    # rigid-isoviscous film h = 4.9 eta0 u_m R / w with a pressure bump over sqrt(2 R h) (rigid).
    # Only a starting point: Newton converges to the same solution from either.
    if elastic:
        P = np.sqrt(np.clip(1.0 - X ** 2, 0.0, None))
    else:
        h_m = 4.9 * eta0 * u_m * R / w
        L = np.sqrt(2.0 * R * h_m) / b
        P = np.exp(-((X + 0.5 * L) / (0.7 * L)) ** 2) * (X < 0.3 * L)
    # a small positive floor: no node starts cavitated, Newton finds the rupture from downstream
    # in one sweep instead of releasing one node per iteration
    P = np.maximum(P, 1e-3 * np.max(P))
    P[0] = P[-1] = 0.0
    P *= (np.pi / 2) / np.sum(quad * P)
    if H0_guess is not None:
        H0 = H0_guess
    elif elastic:
        h_c = 2.922 * R * (w / (E_prime * R)) ** -0.166 * (eta0 * u_m / (E_prime * R)) ** 0.692 \
            * (alpha * E_prime) ** 0.470 if alpha > 0.0 else 0.3 * b ** 2 / R
        H0 = h_c * R / b ** 2 - np.min(X ** 2 / 2 + K @ P)
    else:
        H0 = h_m * R / b ** 2

    interior = np.arange(1, n - 1)
    with threadpool_limits(1):      # dense solves of a few hundred unknowns: one BLAS thread is fastest
        return _newton(X, dX, K, quad, P, H0, interior, n, b, p_h, lam, R, eta0, alpha, viscosity, U1, U2,
                       max_iter, tol, verbose)


def _system(X, dX, K, quad, P, H0, n, p_h, lam, eta0, alpha, viscosity, jacobian):
    """Residuals of the discrete problem at (P, H0) and, if asked, the Newton matrix.

    Returns (Rv, load_residual, scale, M): Rv the interior Reynolds residuals (with the
    cavitation penalty), scale the largest wedge term (for relative norms), M the Jacobian of
    (Rv, load) with respect to (P interior, H0) or None.
    """
    i = np.arange(1, n - 1)
    H = H0 + X ** 2 / 2 + K @ P
    eta, dlneta = _viscosity(P * p_h, eta0, alpha, viscosity)
    eps = H ** 3 / ((eta / eta0) * lam)
    ef = 0.5 * (eps[1:] + eps[:-1])                    # faces i+1/2, i = 0..n-2
    dP = np.diff(P)
    A = (ef[i] * dP[i] - ef[i - 1] * dP[i - 1]) / dX ** 2
    # second-order upwind wedge (first order at the second node)
    wedge = np.empty(n - 2)
    wedge[0] = (H[1] - H[0]) / dX
    wedge[1:] = (1.5 * H[2:-1] - 2.0 * H[1:-2] + 0.5 * H[:-3]) / dX
    # cavitation by a penalty (Wu 1986): -xi min(P, 0) added to the Reynolds residual drives
    # negative pressures to O(1/xi); as xi -> inf this is Reynolds' outlet condition p = dp/dx = 0
    neg = P[i] < 0.0
    xi = PENALTY / dX
    Rv = A - wedge - xi * np.where(neg, P[i], 0.0)
    load = np.sum(quad * P) - np.pi / 2
    scale = max(np.max(np.abs(wedge)), 1e-300)
    if not jacobian:
        return Rv, load, scale, None
    # d eps_j / d P_k (dense) and d eps_j / d H0
    deps_dP = eps[:, None] * (3.0 * K / H[:, None])
    deps_dP[np.arange(n), np.arange(n)] += -eps * dlneta * p_h
    deps_dH0 = 3.0 * eps / H
    def_dP = 0.5 * (deps_dP[1:] + deps_dP[:-1])
    def_dH0 = 0.5 * (deps_dH0[1:] + deps_dH0[:-1])
    rows = np.arange(n - 2)
    J = (def_dP[i] * dP[i][:, None] - def_dP[i - 1] * dP[i - 1][:, None]) / dX ** 2
    J[rows, i + 1] += ef[i] / dX ** 2
    J[rows, i] -= (ef[i] + ef[i - 1]) / dX ** 2
    J[rows, i - 1] += ef[i - 1] / dX ** 2
    # minus d wedge / dP = minus (upwind difference of the rows of K)
    dW = np.empty((n - 2, n))
    dW[0] = (K[1] - K[0]) / dX
    dW[1:] = (1.5 * K[2:-1] - 2.0 * K[1:-2] + 0.5 * K[:-3]) / dX
    J -= dW
    JH0 = (def_dH0[i] * dP[i] - def_dH0[i - 1] * dP[i - 1]) / dX ** 2 - np.r_[0.0, np.zeros(n - 3)]
    J[np.nonzero(neg)[0], i[neg]] -= xi
    nn = n - 2
    M = np.zeros((nn + 1, nn + 1))
    M[:nn, :nn] = J[:, i]
    M[:nn, nn] = JH0            # the wedge of X^2/2 + H0 does not depend on H0
    M[nn, :nn] = quad[i]
    return Rv, load, scale, M


def _newton(X, dX, K, quad, P, H0, interior, n, b, p_h, lam, R, eta0, alpha, viscosity, U1, U2, max_iter, tol,
            verbose):
    i = interior
    nn = n - 2
    res = np.inf
    it = 0

    def merit(Pt, H0t):
        Ht = H0t + X ** 2 / 2 + K @ Pt
        if np.min(Ht) <= 0.0:
            return np.inf
        Rv, load, scale, _ = _system(X, dX, K, quad, Pt, H0t, n, p_h, lam, eta0, alpha, viscosity, False)
        return np.sum((Rv / scale) ** 2) + (load / (np.pi / 2)) ** 2

    for it in range(1, max_iter + 1):
        H = H0 + X ** 2 / 2 + K @ P
        if np.min(H) <= 0.0:
            H0 += 1.1 * (-np.min(H)) + 1e-3
            continue
        Rv, load, scale, M = _system(X, dX, K, quad, P, H0, n, p_h, lam, eta0, alpha, viscosity, True)
        res = max(np.max(np.abs(Rv)) / scale, abs(load) / (np.pi / 2))
        if res < tol:
            break
        delta = np.linalg.solve(M, -np.r_[Rv, load])
        # damping: pressure step at most half the peak pressure, H0 step at most half the minimum
        # film; then backtracking on the squared residual norm (Armijo-free halving, at most 12 times)
        step = 1.0
        mp = np.max(np.abs(delta[:nn])) / max(np.max(P), 1e-300)
        if mp > 0.5:
            step = min(step, 0.5 / mp)
        if abs(delta[nn]) > 0.5 * np.min(H):
            step = min(step, 0.5 * np.min(H) / abs(delta[nn]))
        m0 = np.sum((Rv / scale) ** 2) + (load / (np.pi / 2)) ** 2
        for _ in range(12):
            Pt = P.copy()
            Pt[i] += step * delta[:nn]
            if merit(Pt, H0 + step * delta[nn]) < m0:
                break
            step *= 0.5
        if verbose:
            print(f"it {it:3d} res {res:.3e} step {step:.3g} H0 {H0:.5g} ncav {int(np.sum(P[i] < 0))}")
        P[i] += step * delta[:nn]
        H0 += step * delta[nn]
    else:
        raise RuntimeError(f"Reynolds line contact: no convergence after {max_iter} iterations, residual {res:.3g}")

    H = H0 + X ** 2 / 2 + K @ P
    x = X * b
    p = np.maximum(P, 0.0) * p_h
    h = H * b ** 2 / R
    eta, _ = _viscosity(p, eta0, alpha, viscosity)
    return _forces(x, p, h, eta, U1, U2, b, p_h, it, res)


def _forces(x, p, h, eta, U1, U2, b, p_h, iterations, residual):
    """Surface shear forces and the dissipation of a solved film (module docstring).

    Evaluated per cell (i, i+1) on the discrete scheme's own face values, so that the film
    whose flux the discrete Reynolds equation conserves is the film that carries the stresses:
    the upwind film h_f = 1.5 h_i - 0.5 h_(i-1) of the wedge term and the face mobility
    h^3/(12 eta) = mean of the two nodes', i.e. the face viscosity eta_f = h_f^3 / mean(h^3/eta)
    (across the outlet spike eta falls by orders of magnitude within one cell; a plain mean of
    eta would be wrong there). The Couette part acts only where the film is full (p > 0 at
    either end of the cell); in the cavitated outlet the film is ruptured and not integrated.
    ``F_poiseuille_central`` evaluates the Poiseuille force with the central film (h_i +
    h_(i+1))/2 instead: the difference (7-9 % at M = 15-67, concentrated at the outlet constriction,
    where h has a kink) is the discretisation uncertainty of the force.
    """
    dx = np.diff(x)
    dpdx = np.diff(p) / dx
    hf = np.empty_like(dx)
    hf[0] = h[0]
    hf[1:] = 1.5 * h[1:-1] - 0.5 * h[:-2]
    mob = 0.5 * (h[1:] ** 3 / eta[1:] + h[:-1] ** 3 / eta[:-1])
    ef = hf ** 3 / mob
    full = (p[1:] > 0.0) | (p[:-1] > 0.0)
    dU = U2 - U1
    couette = np.where(full, ef * dU / hf, 0.0)
    tau1 = couette - 0.5 * hf * dpdx
    tau2 = -couette - 0.5 * hf * dpdx
    F1 = np.sum(tau1 * dx)
    F2 = np.sum(tau2 * dx)
    Fp = np.sum(0.5 * hf * dpdx * dx)
    Fp_central = np.sum(0.25 * (h[1:] + h[:-1]) * dpdx * dx)
    # dissipation from the velocity field: 3-point Gauss-Legendre across the film
    zg, wg = np.polynomial.legendre.leggauss(3)
    D = 0.0
    for zq, wq in zip(zg, wg):
        z = 0.5 * hf * (zq + 1.0)
        dudz = np.where(full, dU / hf, 0.0) + dpdx / (2.0 * ef) * (2.0 * z - hf)
        D += np.sum(0.5 * hf * wq * ef * dudz ** 2 * dx)
    flux = -mob / 12.0 * dpdx + 0.5 * (U1 + U2) * hf
    trapz = getattr(np, "trapezoid", None) or np.trapz
    return Solution(x, p, h, eta, b, p_h, float(trapz(p, x)), float(np.interp(0.0, x, h)), float(np.min(h)),
                    float(F1), float(F2), float(Fp), float(Fp_central), float(D), float(trapz(p * x, x)),
                    flux[(p[1:] > 0.0) & (p[:-1] > 0.0)], iterations, float(residual))
