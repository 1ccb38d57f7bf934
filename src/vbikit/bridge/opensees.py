"""Modes from a live OpenSeesPy model (or an ospgrillage model, which builds one).

After ``ops.eigen(n)`` on a model whose deck nodes lie on a rectangular grid — ``n_lines``
longitudinal lines (girders) at y_j, each with a node at every station x_i — :func:`modes_from_opensees`
reads the vertical displacement and the two rotations of every mode at those nodes and returns an
:class:`~vbikit.bridge.modefile.ImportedModalBridge`, interpolated like vbikit's own deck
(:class:`~vbikit.bridge.nodal.NodalModes`).

Conventions: OpenSees' global axes with x along the span, y to the left, z up (``-ndm 3 -ndf 6``),
so w = u_z (DOF 3), ∂w/∂y = θ_x (DOF 4) and ∂w/∂x = −θ_y (DOF 5).  OpenSees returns eigenvectors
normalised to the mass matrix (φᵀ M φ = 1), which is what vbikit needs; ``mass_normalised=False``
is for solvers that do not.  The eigenvalues are ω² [rad²/s²].  Pitfalls (docs/bridges.md): with
``-mass`` on elements OpenSees adds axial/in-plane modes unless those DOFs are fixed; ospgrillage
0.6 wrote member masses 1000× too large — check its frequencies against a hand estimate.
"""
from __future__ import annotations

from typing import Any, Optional, Sequence

import numpy as np
from numpy.typing import ArrayLike

from vbikit.bridge.base import DEFAULT_DAMPING_RATIO
from vbikit.bridge.modefile import DEFAULT_LEVER_ARM, ImportedModalBridge
from vbikit.bridge.nodal import NodalModes


def modes_from_opensees(ops: Any, node_tags: ArrayLike, x: Sequence[float], y: Sequence[float],
                        eigenvalues: Sequence[float], damping_ratio: float = DEFAULT_DAMPING_RATIO,
                        strain_lever_arm: ArrayLike = DEFAULT_LEVER_ARM, girder_y: Optional[Sequence[float]] = None,
                        default_lateral_offset: float = 0.0, default_girder: int = 1, name: str = "opensees",
                        dofs: tuple[int, int, int] = (3, 4, 5)) -> ImportedModalBridge:
    """An :class:`ImportedModalBridge` from the modes of the live OpenSees domain ``ops``.

    Parameters
    ----------
    ops : module
        ``openseespy.opensees`` after ``ops.eigen``.
    node_tags : array of int, shape (n_lines, n_stations)
        Deck node tags, line j (ascending y) by station i (ascending x, x_0 = 0, x_last = span).
    x, y : sequences of float
        Station positions [m] (from the bridge entry) and line positions [m] (from the deck centreline, positive left).
    eigenvalues : sequence of float
        What ``ops.eigen`` returned, ω² [rad²/s²], ascending; one mode per value.
    dofs : (int, int, int)
        OpenSees DOF numbers of w, θ_x, θ_y (default 3, 4, 5 of a 6-DOF node).
    Other parameters are those of :class:`ImportedModalBridge`.
    """
    tags = np.asarray(node_tags, int)
    x, y = np.asarray(x, float), np.asarray(y, float)
    lam = np.asarray(eigenvalues, float)
    if tags.shape != (y.size, x.size):
        raise ValueError(f"node_tags must have shape (len(y), len(x)) = {(y.size, x.size)}, got {tags.shape}")
    if lam.ndim != 1 or lam.size < 1 or np.any(~np.isfinite(lam)) or np.any(lam <= 0):
        raise ValueError("eigenvalues must be positive ω² values (what ops.eigen returned)")
    n = lam.size
    w, wx, wy = (np.empty((y.size, x.size, n)) for _ in range(3))
    dw, drx, dry = dofs
    for j in range(y.size):
        for i in range(x.size):
            for k in range(n):
                w[j, i, k] = ops.nodeEigenvector(int(tags[j, i]), k + 1, dw)
                wy[j, i, k] = ops.nodeEigenvector(int(tags[j, i]), k + 1, drx)
                wx[j, i, k] = -ops.nodeEigenvector(int(tags[j, i]), k + 1, dry)
    if x[0] != 0.0:
        raise ValueError(f"the first station must be at x = 0 (the entry support), got {x[0]}")
    sign = np.sign(w.reshape(-1, n)[np.argmax(np.abs(w.reshape(-1, n)), axis=0), np.arange(n)])
    modes = NodalModes(x, y, w * sign, wx * sign, wy * sign)
    return ImportedModalBridge(modes, np.sqrt(lam), np.full(n, float(damping_ratio)), np.asarray(strain_lever_arm, float),
                               None if girder_y is None else np.asarray(girder_y, float), float(default_lateral_offset),
                               int(default_girder), name)
