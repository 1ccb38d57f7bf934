"""Random road profiles of the ISO 8608 classes.

Paper Eq. 7 with the ISO 8608 displacement PSD Gd(n) = Gd(n0)(n/n0)^−2, n0 = 0.1 cycle/m, at
the geometric mean of classes A–D (the paper's good / average / poor are B / C / D). One seed is
one road; the same seed gives the same road at the same x in every crossing of a study.
"""
import os
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from vbikit.road import RoadPSD, random_profile

OUT = Path(os.environ.get("VBIKIT_GALLERY_OUT", "vbikit-out"))

x = np.linspace(0.0, 50.0, 2001)
fig, ax = plt.subplots(figsize=(7, 3.5), layout="constrained")
for k, cls in enumerate("ABCD"):
    road = random_profile(RoadPSD.iso(cls), seed=3)
    z = road.elevation(x)
    ax.plot(x, 1e3 * z + 40 * k, lw=0.8, label=f"class {cls} (rms {1e3 * z.std():.1f} mm)")
ax.set(xlabel="x [m]", ylabel="elevation [mm] (offset per class)", title="ISO 8608 random roads, seed 3")
ax.legend(fontsize=8, loc="upper right")
OUT.mkdir(parents=True, exist_ok=True)
fig.savefig(OUT / "road_profiles.png", dpi=110)
