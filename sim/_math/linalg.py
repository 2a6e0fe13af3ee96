"""Small dense linear algebra inside kernels: solves (Gaussian elimination with partial
pivoting) and element-wise copies.

The systems of the slice model are small (at most a few hundred unknowns) and solved
thousands of times per load case; an in-kernel elimination avoids the per-call overhead of
a LAPACK round trip and allocates nothing but the work copy. The copies are explicit loops:
no broadcasting machinery to compile.
"""
import numpy as np

from sim._math.jit import internal_kernel


@internal_kernel
def copy_vector(dst, src):
    """dst[i] = src[i] for arrays of equal shape (N,)."""
    for i in range(dst.shape[0]):
        dst[i] = src[i]


@internal_kernel
def copy_matrix(dst, src):
    """dst[i, k] = src[i, k] for arrays of equal shape (N, M)."""
    for i in range(dst.shape[0]):
        for k in range(dst.shape[1]):
            dst[i, k] = src[i, k]


@internal_kernel
def solve_dense(A, B):
    """Solve A X = B for square A (n x n) and B (n x m); returns X (A and B untouched).

    Returns NaN where A is singular to working precision; callers check the result. B is 2-D
    only (one column for a single right-hand side): each array shape is a kernel of its own to
    compile.
    """
    n = A.shape[0]
    M = A.copy()
    X = B.copy()
    m = X.shape[1]
    for c in range(n):
        piv = c
        big = abs(M[c, c])
        for r in range(c + 1, n):
            if abs(M[r, c]) > big:
                big = abs(M[r, c])
                piv = r
        if big == 0.0:
            X[:, :] = np.nan
            return X
        if piv != c:
            for k in range(n):
                tmp = M[c, k]
                M[c, k] = M[piv, k]
                M[piv, k] = tmp
            for k in range(m):
                tmp = X[c, k]
                X[c, k] = X[piv, k]
                X[piv, k] = tmp
        inv = 1.0 / M[c, c]
        for r in range(c + 1, n):
            fct = M[r, c] * inv
            if fct != 0.0:
                for k in range(c + 1, n):
                    M[r, k] -= fct * M[c, k]
                for k in range(m):
                    X[r, k] -= fct * X[c, k]
    for c in range(n - 1, -1, -1):
        inv = 1.0 / M[c, c]
        for k in range(m):
            s = X[c, k]
            for j in range(c + 1, n):
                s -= M[c, j] * X[j, k]
            X[c, k] = s * inv
    return X
