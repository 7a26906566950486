"""Banded LU with partial pivoting, compiled (numba): LAPACK's dgbtf2 and dgbtrs written out.

``cablefem.compiled.steps`` factors a line's banded step tangent inside its compiled loop.
numba cannot cache a function that calls LAPACK through a ctypes pointer (the
addresses ``scipy.linalg.cython_lapack`` exports), and compiling on every start
would cost ~30 s; at the bandwidths of a line (kl = ku = 3 (order + 1) - 1) the
unblocked algorithm is what dgbtrf runs anyway.
"""

from numba import njit
from numba import uint64 as _index

# Every index below is cast to an unsigned integer before it reaches an array: numba gives a signed
# index it cannot prove non-negative a fix-up for negative (wrap-around) indices on every access,
# ~3x the instructions of the solve's inner loop (callgrind); the arithmetic is unchanged.


@njit(cache=True, _nrt=False)
def lu_factor(lu, n, kl, ku, ipiv, multipliers):
    """Factor a banded matrix in place by LU with partial pivoting; False if it is singular.

    ``lu`` (n (2 kl + ku + 1),) holds LAPACK's column-major band layout flat: row i, column j
    at lu[j ld + kl + ku + i - j], ld = 2 kl + ku + 1, the top kl rows of each column free for
    the fill that row swaps make. The algorithm is LAPACK's unblocked dgbtf2 (Golub & Van Loan,
    Alg. 4.3.5 with row pivoting): U reaches ku columns right of the diagonal without swaps and
    up to kl + ku with them, and the work follows that reach. Flat indexing runs ~25 % faster
    than 2-D indexing here (numba). ``multipliers``: scratch (kl + 1,)."""
    ld = 2 * kl + ku + 1
    d = kl + ku  # row of the diagonal
    reach = 0
    for j in range(n):
        below = min(kl, n - 1 - j)
        diag = j * ld + d
        p = 0
        for i in range(1, below + 1):
            if abs(lu[_index(diag + i)]) > abs(lu[_index(diag + p)]):
                p = i
        ipiv[j] = j + p
        if lu[_index(diag + p)] == 0.0:
            return False
        reach = max(reach, min(n - 1, j + ku + p))
        if p:
            for c in range(j, reach + 1):
                q = c * ld + d + j - c
                lu[_index(q)], lu[_index(q + p)] = lu[_index(q + p)], lu[_index(q)]
        inverse = 1.0 / lu[_index(diag)]
        for i in range(1, below + 1):
            lu[_index(diag + i)] *= inverse
            multipliers[i] = lu[_index(diag + i)]
        for c in range(j + 1, reach + 1):
            q = c * ld + d + j - c
            top = lu[_index(q)]
            for i in range(1, below + 1):
                lu[_index(q + i)] -= multipliers[i] * top
    return True


@njit(cache=True, _nrt=False)
def lu_solve(lu, n, kl, ku, ipiv, rhs):
    """Solve in place with the factors of ``lu_factor`` (LAPACK's dgbtrs)."""
    ld = 2 * kl + ku + 1
    d = kl + ku
    for j in range(n):  # L y = P b
        p = ipiv[j]
        if p != j:
            rhs[_index(j)], rhs[_index(p)] = rhs[_index(p)], rhs[_index(j)]
        for i in range(1, min(kl, n - 1 - j) + 1):
            rhs[_index(j + i)] -= lu[_index(j * ld + d + i)] * rhs[_index(j)]
    for j in range(n - 1, -1, -1):  # U x = y
        rhs[_index(j)] /= lu[_index(j * ld + d)]
        for i in range(max(0, j - d), j):
            rhs[_index(i)] -= lu[_index(j * ld + d + i - j)] * rhs[_index(j)]
