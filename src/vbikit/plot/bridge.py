"""Figures of a bridge's mode shapes (matplotlib, imported only when a figure is drawn)."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from vbikit._files import save_figure
from vbikit.bridge.base import DescribesModes, GirderDeck, ModalBridge


def plot_mode_shapes(bridge: ModalBridge, path: str | Path, n_modes: int = 6, title: str = "") -> Path:
    """Filled contours of the first ``n_modes`` mass-normalised mode shapes φ(x, y) over the deck plan
    (x along the span, y across; girder lines dashed; a skew deck drawn as its parallelogram), one
    panel per mode with its frequency."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    deck = bridge if isinstance(bridge, GirderDeck) else None
    girder_y = deck.girder_y if deck is not None else None
    half = deck.deck_width if deck is not None else None
    half = 0.5 * half if half is not None else (np.abs(girder_y).max() + 0.5 if girder_y is not None else 1.0)
    x = np.linspace(*bridge.deck_extent, 121)
    y = np.linspace(-half, half, 41)
    X, Y = np.meshgrid(x, y)
    phi = bridge.mode_shapes(X.ravel(), Y.ravel())
    xi = bridge.span_coordinate(X.ravel(), Y.ravel())
    phi[(xi < 0.0) | (xi > bridge.span)] = np.nan  # beyond a skew deck's oblique ends: not drawn
    n = min(n_modes, phi.shape[1])
    labels = bridge.mode_descriptions() if isinstance(bridge, DescribesModes) else [""] * n
    cols = 2 if n > 1 else 1
    rows = int(np.ceil(n / cols))
    fig, axes = plt.subplots(rows, cols, figsize=(5.5 * cols, 2.4 * rows + 0.6), squeeze=False, constrained_layout=True)
    for k, ax in enumerate(axes.ravel()):
        if k >= n:
            ax.axis("off")
            continue
        z = phi[:, k].reshape(X.shape)
        lim = np.nanmax(np.abs(z)) or 1.0
        ax.contourf(X, Y, z / lim, levels=np.linspace(-1, 1, 21), cmap="RdBu_r")
        ax.contour(X, Y, z, levels=[0.0], colors="k", linewidths=0.6)
        for yg in (girder_y if girder_y is not None else []):
            ax.axhline(yg, color="0.3", lw=0.5, ls="--")
        ax.set_title(f"mode {k + 1}: {bridge.frequencies_hz[k]:.2f} Hz  {labels[k].split(',')[0]}", fontsize="small")
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        ax.set_aspect("equal" if x[-1] - x[0] < 6 * half else "auto")
    if title:
        fig.suptitle(title)
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    save_figure(fig, path, dpi=110)
    return path
