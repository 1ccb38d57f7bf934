"""Modes from a live OpenSeesPy model (or an ospgrillage model, which builds one).

After ``ops.eigen(n)`` on a model whose deck nodes lie on a rectangular grid — ``n_lines``
longitudinal lines (girders) at y_j, each with a node at every station x_i — :func:`modes_from_opensees`
reads the vertical displacement and the two rotations of every mode at those nodes and returns an
:class:`~vbikit.bridge.modefile.ImportedModalBridge`, interpolated like vbikit's own deck
(:class:`~vbikit.bridge.nodal.NodalModes`).

Conventions: ``vertical_axis="z"`` (default) for OpenSees' global axes with x along the span, y to
the left, z up (``-ndm 3 -ndf 6``): w = u_z (DOF 3), ∂w/∂y = θ_x (DOF 4), ∂w/∂x = −θ_y (DOF 5).
``vertical_axis="y"`` for models built with y up and z across the deck (ospgrillage's axes: x
along the span, y up, z = x × y to the right): vbikit's lateral coordinate is −z, and w = u_y
(DOF 2), ∂w/∂y = θ_x (DOF 4), ∂w/∂x = +θ_z (DOF 6) (small rotations, u = θ × r).  OpenSees
returns eigenvectors normalised to the mass matrix (φᵀ M φ = 1), which is what vbikit needs; the
eigenvalues are ω² [rad²/s²].  Every node must sit at its grid point in plan (checked).  Pitfalls
(docs/bridges.md): with ``-mass`` on elements OpenSees adds axial/in-plane modes unless those
DOFs are fixed; ospgrillage 0.6 makes member masses A·ρ·1e3 — give ρ/1000, and check its
frequencies against a hand estimate.
"""
from __future__ import annotations

from typing import Any, Optional, Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

from vbikit.bridge.base import DEFAULT_DAMPING_RATIO
from vbikit.bridge.modefile import DEFAULT_LEVER_ARM, ImportedModalBridge
from vbikit.bridge.nodal import NodalModes

#: vertical axis → (OpenSees DOFs of w, ∂w/∂y, ∂w/∂x; the sign of ∂w/∂x against that rotation)
_FRAMES: dict[str, tuple[tuple[int, int, int], float]] = {"z": ((3, 4, 5), -1.0), "y": ((2, 4, 6), 1.0)}


def modes_from_opensees(ops: Any, node_tags: ArrayLike, x: Sequence[float], y: Sequence[float],
                        eigenvalues: Sequence[float], damping_ratio: float = DEFAULT_DAMPING_RATIO,
                        strain_lever_arm: ArrayLike = DEFAULT_LEVER_ARM, girder_y: Optional[Sequence[float]] = None,
                        default_lateral_offset: float = 0.0, default_girder: int = 1, name: str = "opensees",
                        dofs: Optional[tuple[int, int, int]] = None, vertical_axis: str = "z") -> ImportedModalBridge:
    """An :class:`ImportedModalBridge` from the modes of the live OpenSees domain ``ops``.

    Parameters
    ----------
    ops : module
        ``openseespy.opensees`` after ``ops.eigen``.
    node_tags : array of int, shape (n_lines, n_stations)
        Deck node tags, line j (ascending y) by station i (ascending x, x_0 = 0, x_last = span).
    x, y : sequences of float
        Station positions [m] (from the bridge entry) and line positions [m] in vbikit's frame (from
        the deck centreline, positive left; with ``vertical_axis="y"`` that is y = −z of the model).
    eigenvalues : sequence of float
        What ``ops.eigen`` returned, ω² [rad²/s²], ascending; one mode per value.
    vertical_axis : {"z", "y"}
        The model's vertical axis (see the module docstring): "z" (default) or "y" (ospgrillage).
    dofs : (int, int, int), optional
        OpenSees DOF numbers of w, ∂w/∂y and ∂w/∂x (default: (3, 4, 5) for "z", (2, 4, 6) for "y").
    Other parameters are those of :class:`ImportedModalBridge`.
    """
    if vertical_axis not in _FRAMES:
        raise ValueError(f"vertical_axis must be one of {', '.join(_FRAMES)}, got {vertical_axis!r}")
    default_dofs, sign_x = _FRAMES[vertical_axis]
    tags = np.asarray(node_tags, int)
    x, y = np.asarray(x, float), np.asarray(y, float)
    lam = np.asarray(eigenvalues, float)
    if tags.shape != (y.size, x.size):
        raise ValueError(f"node_tags must have shape (len(y), len(x)) = {(y.size, x.size)}, got {tags.shape}")
    if lam.ndim != 1 or lam.size < 1 or np.any(~np.isfinite(lam)) or np.any(lam <= 0):
        raise ValueError("eigenvalues must be positive ω² values (what ops.eigen returned)")
    if x[0] != 0.0:
        raise ValueError(f"the first station must be at x = 0 (the entry support), got {x[0]}")
    _check_grid(ops, tags, x, y, vertical_axis)
    n = lam.size
    w, wx, wy = (np.empty((y.size, x.size, n)) for _ in range(3))
    dw, drx, dry = default_dofs if dofs is None else dofs
    for j in range(y.size):
        for i in range(x.size):
            for k in range(n):
                w[j, i, k] = ops.nodeEigenvector(int(tags[j, i]), k + 1, dw)
                wy[j, i, k] = ops.nodeEigenvector(int(tags[j, i]), k + 1, drx)
                wx[j, i, k] = sign_x * ops.nodeEigenvector(int(tags[j, i]), k + 1, dry)
    sign = np.sign(w.reshape(-1, n)[np.argmax(np.abs(w.reshape(-1, n)), axis=0), np.arange(n)])
    modes = NodalModes(x, y, w * sign, wx * sign, wy * sign)
    return ImportedModalBridge(modes, np.sqrt(lam), np.full(n, float(damping_ratio)), np.asarray(strain_lever_arm, float),
                               None if girder_y is None else np.asarray(girder_y, float), float(default_lateral_offset),
                               int(default_girder), name)


def _check_grid(ops: Any, tags: NDArray[np.int_], x: NDArray[np.float64], y: NDArray[np.float64], vertical_axis: str) -> None:
    """Every node at its grid point (x_i, y_j), relative to node [0][0] (the model may sit anywhere
    in plan), within 1e-4 of the span; a skewed mesh (stations shifted line by line) fails here."""
    c = np.array([[ops.nodeCoord(int(t)) for t in row] for row in tags], float)  # (n_lines, n_st, 3)
    plan = np.stack([c[..., 0], c[..., 1] if vertical_axis == "z" else -c[..., 2]], axis=-1)
    plan -= plan[0, 0]
    want = np.stack(np.broadcast_arrays((x - x[0])[None, :], (y - y[0])[:, None]), axis=-1)
    bad = np.argwhere(np.abs(plan - want).max(axis=-1) > 1e-4 * float(x[-1] - x[0]))
    if bad.size:
        j, i = bad[0]
        raise ValueError(f"node_tags[{j}][{i}] (node {int(tags[j, i])}) is at {plan[j, i].round(4).tolist()} m from node_tags[0][0] "
                         f"in plan, not at the grid point {want[j, i].round(4).tolist()} (x[{i}] - x[0], y[{j}] - y[0]); "
                         "the import needs a rectangular grid: every line with a node at every station (no skewed mesh)")
