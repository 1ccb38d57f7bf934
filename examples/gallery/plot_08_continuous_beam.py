"""A continuous bridge: bending moments over three spans.

An HS20-44 truck crosses a three-span continuous beam (20 + 25 + 20 m) at 80 km/h on an ISO
class B road. Besides the deflection, the load effects a designer checks: the sagging moment at
the middle of the first span and the hogging moment over the first interior support, each
against its static influence-line value (mode-acceleration method), with their impact factors.
"""
import os
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

from vbikit.analysis.effects import load_effect_response
from vbikit.bridge.continuous import ContinuousBeam
from vbikit.contact import MultiPointTire
from vbikit.road import RoadPSD, random_profile
from vbikit.solve import Crossing, simulate
from vbikit.vehicle import hs20_44

OUT = Path(os.environ.get("VBIKIT_GALLERY_OUT", "vbikit-out"))

bridge = ContinuousBeam(spans=(20.0, 25.0, 20.0), EI=1.286e10, mass_per_length=7537.0, n_modes=12)
result = simulate(Crossing(bridge, hs20_44(), MultiPointTire(6), random_profile(RoadPSD.iso("B"), seed=2),
                           speed=80 / 3.6))
sagging = load_effect_response(result, bridge.load_effect("moment", x=10.0))
hogging = load_effect_response(result, bridge.load_effect("moment", x=20.0))

fig, ax = plt.subplots(figsize=(7, 3.8), layout="constrained")
x_front = result.front_position[:, 0]
for r, label in ((sagging, "sagging, x = 10 m"), (hogging, "hogging, over the support at x = 20 m")):
    line, = ax.plot(x_front, r.dynamic / 1e3, lw=1, label=f"{label} (IM {r.impact.impact_factor:.3f})")
    ax.plot(x_front, r.static / 1e3, "--", lw=1, color=line.get_color())
    print(f"{label}: IM {r.impact.impact_factor:.4f}, static peak {r.impact.static_peak / 1e3:.1f} kN m")
for xs in (0.0, 20.0, 45.0, 65.0):
    ax.axvline(xs, color="0.8", lw=0.8)
ax.set(xlabel="front axle position [m]", ylabel="bending moment [kN m]",
       title="HS20-44 over a 20 + 25 + 20 m continuous beam, 80 km/h (dashed: static)")
ax.legend(fontsize=8)
OUT.mkdir(parents=True, exist_ok=True)
fig.savefig(OUT / "continuous_beam.png", dpi=110)
