"""Small dense systems of the step kernels: LU factors with partial pivoting and their solves, one
right-hand side or many lanes (the lanes innermost).  No allocation inside."""
from __future__ import annotations

from numba import njit

from vbikit.solve.kernels.bundles import _flat_internal, _internal


@_internal
def _lu_factor(a, n, piv):
    """In-place LU factorisation with partial pivoting of a[:n, :n] (row swaps in ``piv``)."""
    for j in range(n):
        best = j
        big = abs(a[j, j])
        for i in range(j + 1, n):
            if abs(a[i, j]) > big:
                big = abs(a[i, j])
                best = i
        piv[j] = best
        if best != j:
            for c in range(n):
                t = a[j, c]
                a[j, c] = a[best, c]
                a[best, c] = t
        d = a[j, j]
        for i in range(j + 1, n):
            lij = a[i, j] / d
            a[i, j] = lij
            if lij != 0.0:
                for c in range(j + 1, n):
                    a[i, c] -= lij * a[j, c]


@_internal
def _lu_solve(a, n, piv, b):
    """Solve a x = b in place in b[:n] with the factors of ``_lu_factor``."""
    for j in range(n):
        k = piv[j]
        if k != j:
            t = b[j]
            b[j] = b[k]
            b[k] = t
    for i in range(n):
        acc = b[i]
        for j in range(i):
            acc -= a[i, j] * b[j]
        b[i] = acc
    for i in range(n - 1, -1, -1):
        acc = b[i]
        for j in range(i + 1, n):
            acc -= a[i, j] * b[j]
        b[i] = acc / a[i, i]


#: the same two routines inlined by numba into their callers, the one-lane kernel's quasi-Newton update
#: (``lean._quasi``; the factorisation also into ``woodbury.vehicle_factors``): not compiled on their own and then optimised again in each caller's LLVM module
#: (numba links a compiled helper into every caller's module, where LLVM optimises it and makes its
#: machine code again); ≈ −0.15 s of the default path's cold compile (benchmarks/README.md)
#: (``getattr``: with NUMBA_DISABLE_JIT=1, as the kernel-coverage job runs, ``njit`` returns the Python
#: function itself, without ``py_func``).  Not cached (``cache=False``): numba names a cache entry by the
#: Python function's module, name and line, so these would share ``_lu_factor``'s and ``_lu_solve``'s and a
#: call from Python would load the linked one, compiled without the wrapper that makes it callable
#: from Python (a segmentation fault); inlined, they are compiled and cached within their callers.
lu_factor_inline = njit(inline="always", cache=False, fastmath=True, error_model="numpy")(
    getattr(_lu_factor, "py_func", _lu_factor))
lu_solve_inline = njit(inline="always", cache=False, fastmath=True, error_model="numpy")(
    getattr(_lu_solve, "py_func", _lu_solve))


@_flat_internal
def solve_held(a, pv, t, lane0, lane1):
    """t[:, lane] ← V⁻¹ t[:, lane] for lanes ``lane0`` … ``lane1`` − 1 with the LU factors ``a``,
    ``pv`` of V (row swaps, then forward and back substitution, the lanes innermost)."""
    n_w, _ = a.shape
    for j in range(n_w):
        kp = pv[j]
        if kp != j:
            for lane in range(lane0, lane1):
                tmp = t[j, lane]
                t[j, lane] = t[kp, lane]
                t[kp, lane] = tmp
    for i in range(n_w):
        for j in range(i):
            e = a[i, j]
            for lane in range(lane0, lane1):
                t[i, lane] -= e * t[j, lane]
    for i in range(n_w - 1, -1, -1):
        for j in range(i + 1, n_w):
            e = a[i, j]
            for lane in range(lane0, lane1):
                t[i, lane] -= e * t[j, lane]
        e = a[i, i]
        for lane in range(lane0, lane1):
            t[i, lane] = t[i, lane] / e
