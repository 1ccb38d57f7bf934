"""Mode shapes of a slab-on-girder deck.

The paper's Bridge 2 as a 3D grillage (five AASHTO Type II girders at 2.13 m, 0.20 m slab,
end and midspan diaphragms): its first modes are bending, torsion and transverse bending of
the deck. ``vbikit bridge paper-bridge-2`` prints the same list and writes the same figure.
"""
import os
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

from vbikit.bridge import BRIDGE_PRESETS
from vbikit.plot.bridge import plot_mode_shapes

OUT = Path(os.environ.get("VBIKIT_GALLERY_OUT", "vbikit-out"))

bridge = BRIDGE_PRESETS["paper-bridge-2"].build(n_modes=6)
for k, (f, label) in enumerate(zip(bridge.frequencies_hz, bridge.mode_descriptions()), start=1):
    print(f"mode {k}: {f:7.2f} Hz  {label}")
plot_mode_shapes(bridge, OUT / "bridge_modes.png", title="paper-bridge-2")
