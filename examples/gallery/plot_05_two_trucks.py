"""Traffic: two trucks meeting on the bridge.

Two vehicles in one coupled system: the 3S2 tractor-semitrailer (five axles, from VBI-2D's
vehicle) drives +x in one lane while a two-axle truck drives −x in the other, entering 0.3 s
later. Their load effects add on the deck, and the dynamic sum is compared with the static sum
of both trucks: the impact factor of the multiple-presence event.
"""
import os
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

from vbikit.analysis import point_response
from vbikit.bridge import BRIDGE_PRESETS
from vbikit.contact import MultiPointTire
from vbikit.road import RoadPSD, random_profile
from vbikit.solve import Crossing, simulate
from vbikit.solve.crossing import VehicleMotion
from vbikit.vehicle import semitrailer_3s2, two_axle_truck

OUT = Path(os.environ.get("VBIKIT_GALLERY_OUT", "vbikit-out"))

bridge = BRIDGE_PRESETS["paper-bridge-2"].build(n_modes=10)
road = random_profile(RoadPSD.iso("B"), seed=4)
vehicles = (VehicleMotion(semitrailer_3s2(), speed=80 / 3.6, direction="+x", lateral_offset=1.8),
            VehicleMotion(two_axle_truck(), speed=70 / 3.6, direction="-x", lateral_offset=-1.8, entry_time=0.3))
result = simulate(Crossing(bridge, tire=MultiPointTire(6), road=road, vehicles=vehicles))

fig, ax = plt.subplots(figsize=(7, 3.8), layout="constrained")
for g, y in enumerate(bridge.girder_y, start=1):
    if g in (2, 4):
        r = point_response(result, y=float(y))
        im = r.displacement_impact.impact_factor
        line, = ax.plot(r.time, 1e3 * r.displacement, lw=1, label=f"Girder {g}, dynamic (IM {im:.3f})")
        ax.plot(r.time, 1e3 * r.static_displacement, "--", lw=1, color=line.get_color(), label=f"Girder {g}, static")
        print(f"Girder {g}: IM {im:.4f}")
ax.set(xlabel="time [s]", ylabel="midspan displacement [mm]",
       title="3S2 (+x, 80 km/h) meets a two-axle truck (−x, 70 km/h), Bridge 2, ISO B")
ax.legend(fontsize=8)
OUT.mkdir(parents=True, exist_ok=True)
fig.savefig(OUT / "two_trucks.png", dpi=110)
