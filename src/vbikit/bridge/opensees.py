"""Modes from a live OpenSeesPy model (or an ospgrillage model, which builds one).

After ``ops.eigen(n)`` on a model whose deck nodes lie on a grid — ``n_lines`` longitudinal lines
(girders) at y_j, each with a node at every station ξ_i — ``modes_from_opensees`` reads the
vertical displacement and the two rotations of every mode at those nodes and returns an
``ImportedModalBridge``, interpolated like vbikit's own deck
(``NodalModes``).  The grid is rectangular (node (j, i) at (ξ_i, y_j)) or
oblique, the skew mesh of a deck with skew support lines (Hambly, *Bridge Deck Behaviour*, 2nd ed.,
1991, ch. 5; ospgrillage's ``Oblique`` mesh): node (j, i) at (ξ_i + y_j tan θ, y_j), with one tan θ
for the whole deck, fitted from the node coordinates (least squares over every node) and then
checked node by node; the result's modes carry it (``NodalModes.skew_tan``).

Conventions: ``vertical_axis="z"`` (default) for OpenSees' global axes with x along the span, y to
the left, z up (``-ndm 3 -ndf 6``): w = u_z (DOF 3), ∂w/∂y = θ_x (DOF 4), ∂w/∂x = −θ_y (DOF 5).
``vertical_axis="y"`` for models built with y up and z across the deck (ospgrillage's axes: x
along the span, y up, z = x × y to the right): vbikit's lateral coordinate is −z, and w = u_y
(DOF 2), ∂w/∂y = θ_x (DOF 4), ∂w/∂x = +θ_z (DOF 6) (small rotations, u = θ × r).  The slopes are
Cartesian on an oblique grid too (the rotations about the global axes).  OpenSees returns
eigenvectors normalised to the mass matrix (φᵀ M φ = 1), which is what vbikit needs; the
eigenvalues are ω² [rad²/s²].  Every node must sit at its grid point in plan (checked, within
1e-4 of the span).  Pitfalls (docs/bridges.md): with ``-mass`` on elements OpenSees adds
axial/in-plane modes unless those DOFs are fixed; ospgrillage 0.6 makes member masses A·ρ·1e3 —
give ρ/1000, and check its frequencies against a hand estimate.
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
                        dofs: Optional[tuple[int, int, int]] = None, vertical_axis: str = "z",
                        deck_width: Optional[float] = None) -> ImportedModalBridge:
    """An ``ImportedModalBridge`` from the modes of the live OpenSees domain ``ops``.

    Parameters
    ----------
    ops : module
        ``openseespy.opensees`` after ``ops.eigen``.
    node_tags : array of int, shape (n_lines, n_stations)
        Deck node tags, line j (ascending y) by station i (ascending ξ, ξ_0 = 0, ξ_last = span).
    x, y : sequences of float
        Stations ξ_i [m] along the lines, from each line's entry support (on a rectangular grid the
        nodes' x from the bridge entry; on an oblique grid a node's x minus its line's first node's
        x), and line positions [m] in vbikit's frame (from the deck centreline, positive left; with
        ``vertical_axis="y"`` that is y = −z of the model).  The skew is found from the nodes.
    eigenvalues : sequence of float
        What ``ops.eigen`` returned, ω² [rad²/s²], ascending; one mode per value.
    vertical_axis : {"z", "y"}
        The model's vertical axis (see the module docstring): "z" (default) or "y" (ospgrillage).
    dofs : (int, int, int), optional
        OpenSees DOF numbers of w, ∂w/∂y and ∂w/∂x (default: (3, 4, 5) for "z", (2, 4, 6) for "y").
    Other parameters are those of ``ImportedModalBridge``.
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
    skew_tan = _fit_grid(ops, tags, x, y, vertical_axis)
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
    modes = NodalModes(x, y, w * sign, wx * sign, wy * sign, skew_tan)
    return ImportedModalBridge(modes, np.sqrt(lam), np.full(n, float(damping_ratio)), np.asarray(strain_lever_arm, float),
                               None if girder_y is None else np.asarray(girder_y, float), float(default_lateral_offset),
                               int(default_girder), name, deck_width)


def _fit_grid(ops: Any, tags: NDArray[np.int_], x: NDArray[np.float64], y: NDArray[np.float64], vertical_axis: str) -> float:
    """tan θ of the node grid, and every node checked at its grid point.

    Node (j, i) must lie at (x_i − x_0 + (y_j − y_0) tan θ, y_j − y_0) in plan relative to node
    [0][0] (the model may sit anywhere in plan), within 1e-4 of the span.  tan θ is the least-squares
    fit of the x offsets over every node, Σ Δy_j (ΔX_ji − Δx_i) / (n_st Σ Δy_j²); it is 0 (the
    rectangular grid) when it shifts the outermost line by less than the tolerance or there is one line.
    """
    c = np.array([[ops.nodeCoord(int(t)) for t in row] for row in tags], float)  # (n_lines, n_st, 3)
    plan = np.stack([c[..., 0], c[..., 1] if vertical_axis == "z" else -c[..., 2]], axis=-1)
    plan -= plan[0, 0]
    tol = 1e-4 * float(x[-1] - x[0])
    dx, dy = x - x[0], y - y[0]
    skew_tan = 0.0
    if y.size > 1:
        fit = float(np.sum(dy[:, None] * (plan[..., 0] - dx[None, :])) / (x.size * np.sum(dy**2)))
        if abs(fit) * float(dy[-1]) > tol:
            skew_tan = fit
    want = np.stack(np.broadcast_arrays(dx[None, :] + dy[:, None] * skew_tan, dy[:, None]), axis=-1)
    off = np.abs(plan - want).max(axis=-1)
    bad = np.argwhere(off > tol)
    if bad.size:
        j, i = np.unravel_index(np.argmax(off), off.shape)
        grid = (f"with the fitted skew tan θ = {skew_tan:.6g} ({np.degrees(np.arctan(skew_tan)):.4g}°), "
                f"x[{i}] - x[0] + (y[{j}] - y[0]) tan θ, y[{j}] - y[0]" if skew_tan else f"x[{i}] - x[0], y[{j}] - y[0]")
        raise ValueError(f"node_tags[{j}][{i}] (node {int(tags[j, i])}) is at {plan[j, i].round(4).tolist()} m from "
                         f"node_tags[0][0] in plan, {off[j, i]:.4g} m off its grid point {want[j, i].round(4).tolist()} "
                         f"({grid}); allowed: 1e-4 of the span = {tol:.3g} m ({bad.shape[0]} node(s) off). The import "
                         "needs every line to have a node at every station, at x = x_i + y_j tan θ with one skew θ "
                         "for the whole deck (a rectangular or an oblique mesh)")
    return skew_tan
