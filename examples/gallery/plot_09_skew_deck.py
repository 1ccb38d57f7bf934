"""A skew deck: frequencies and impact factors against the skew angle.

The paper's Bridge 2 with both support lines turned by 0 … 40° (``[bridge.deck] skew``; the
oblique grillage mesh, docs/bridges.md "Skew supports"): the first bending and torsion
frequencies hardly move, the transverse modes soften. An HS20-44 at 75 km/h in its default lane
on four ISO class C roads (the same seeds at every angle): Girder 4's deflection and midspan
moment impact factors, each read at the girder's own midspan (its bearings move with the skew).
"""
import os
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from vbikit.analysis import point_response
from vbikit.analysis.effects import load_effect_response
from vbikit.bridge import paper_deck
from vbikit.contact import MultiPointTire
from vbikit.road import RoadPSD, random_profile
from vbikit.solve import Crossing, simulate
from vbikit.vehicle import hs20_44

OUT = Path(os.environ.get("VBIKIT_GALLERY_OUT", "vbikit-out"))
skews = [0.0, 10.0, 20.0, 30.0, 40.0]
roads = [random_profile(RoadPSD.iso("C"), seed=s, length=300.0) for s in range(4)]
frequencies, im_deflection, im_moment = [], [], []
for skew in skews:
    bridge = paper_deck(2, n_modes=10, skew=skew)
    frequencies.append(bridge.frequencies_hz[:4])
    y4 = float(bridge.girder_y[3])
    x4 = bridge.default_x_at(y4)  # Girder 4's own midspan
    moment = bridge.load_effect("moment", x4, girder=4)
    d, m = [], []
    for road in roads:
        result = simulate(Crossing(bridge, vehicle=hs20_44(), speed=75 / 3.6, road=road, tire=MultiPointTire()))
        d.append(point_response(result, x4, y4).displacement_impact.impact_factor)
        m.append(load_effect_response(result, moment).impact.impact_factor)
    im_deflection.append(np.mean(d))
    im_moment.append(np.mean(m))
    print(f"skew {skew:4.0f}°: f1..f4 = {', '.join(f'{f:.2f}' for f in frequencies[-1])} Hz, "
          f"Girder 4 IM deflection {im_deflection[-1]:.3f}, moment {im_moment[-1]:.3f}")

fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 3.8), constrained_layout=True)
for k, label in enumerate(["1st bending", "1st torsion", "transverse, 2 nodal lines", "transverse, 3 nodal lines"]):
    ax1.plot(skews, [f[k] for f in frequencies], "o-", label=label)
ax1.set_xlabel("skew angle [°]")
ax1.set_ylabel("frequency [Hz]")
ax1.set_title("Bridge 2, first four modes")
ax1.legend(fontsize="small")
ax2.plot(skews, im_deflection, "o-", label="deflection")
ax2.plot(skews, im_moment, "s-", label="midspan moment")
ax2.set_xlabel("skew angle [°]")
ax2.set_ylabel("impact factor (mean of 4 roads)")
ax2.set_title("HS20-44, 75 km/h, class C, Girder 4")
ax2.legend(fontsize="small")
OUT.mkdir(parents=True, exist_ok=True)
fig.savefig(OUT / "skew_deck.png", dpi=110)
