"""Compiled arithmetic on 3-vectors and 3 x 3 blocks, for the loads' point kernels (numba).

The point kernels run with numba's reference counting off (``_nrt=False``): they allocate
nothing and work on scratch they are given (``cablefem.compiled.kernels``).
"""

import numpy as np
from numba import njit


@njit(cache=True, inline="always", _nrt=False)
def dot(a, b):
    """a . b of two 3-vectors."""
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


@njit(cache=True, inline="always", _nrt=False)
def add_outer(M, a, b, scale):
    """M += scale a b^T (3 x 3)."""
    for i in range(3):
        for j in range(3):
            M[i, j] += scale * a[i] * b[j]


@njit(cache=True, inline="always", _nrt=False)
def add_matmul(M, A, B, scale):
    """M += scale A B (3 x 3)."""
    for i in range(3):
        for j in range(3):
            acc = 0.0
            for k in range(3):
                acc += A[i, k] * B[k, j]
            M[i, j] += scale * acc


@njit(cache=True, inline="always", _nrt=False)
def unit_divisor(stretch):
    """|r'| as a divisor: |r'| itself, or infinity where two points coincide (``loads.unit_tangent``)."""
    return stretch if stretch > 0.0 else np.inf
