"""The lowest modes of a structural FE model (generalised symmetric eigenproblem K φ = λ M φ)."""
from __future__ import annotations

import numpy as np
import scipy.linalg
import scipy.sparse.linalg as spla
from numpy.typing import NDArray


def lowest_modes(K, M, k: int) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The ``k`` smallest eigenvalues λ = ω² [rad²/s²] and their eigenvectors (columns) of the
    sparse symmetric pair (K, M), in ascending order.  Small or nearly complete problems use the
    dense LAPACK solver; others shift-invert Lanczos (scipy ``eigsh``, σ = 0) from a fixed start
    vector, so that the modes are reproducible to the bit."""
    n = K.shape[0]
    k = min(k, n)
    if k >= n - 1 or n < 60:
        lam, vec = scipy.linalg.eigh(K.toarray(), M.toarray(), subset_by_index=[0, k - 1])
    else:
        v0 = np.random.default_rng(0).standard_normal(n)
        lam, vec = spla.eigsh(K, k=k, M=M, sigma=0.0, which="LM", v0=v0)
    order = np.argsort(lam)
    return lam[order], vec[:, order]
