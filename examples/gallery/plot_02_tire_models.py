"""The four tire models over a 20 mm depression.

The paper's Fig. 9 case on the beam stand-in of Bridge 2: HS20-44 at 75 km/h over the 20 mm
depression at the bridge entry, ISO class C road, with the single-point, multi-point (n = 6),
deformable-disk and rigid-disk tires. The point tire (and the rigid disk) see the depression's
corners; the multi-point and disk tires average the road over their patch, which shows most in
the deck acceleration.
"""
import os
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

from vbikit.analysis import point_response
from vbikit.bridge import BRIDGE_PRESETS
from vbikit.contact import DiskTire, MultiPointTire, PointTire, RigidDiskTire
from vbikit.road import Defect, RoadPSD, random_profile, with_defects
from vbikit.solve import Crossing, simulate
from vbikit.vehicle import hs20_44

OUT = Path(os.environ.get("VBIKIT_GALLERY_OUT", "vbikit-out"))

bridge = BRIDGE_PRESETS["paper-bridge-2-beam"].build(n_modes=10)
road = with_defects(random_profile(RoadPSD.iso("C"), seed=1), [Defect.of_kind("depression", start=0.0)])
tires = {"point": PointTire(), "multi-point, n = 6": MultiPointTire(6), "disk": DiskTire(), "rigid disk": RigidDiskTire()}

fig, (top, bottom) = plt.subplots(2, 1, figsize=(7, 5.5), sharex=True, layout="constrained")
for label, tire in tires.items():
    result = simulate(Crossing(bridge, hs20_44(), tire, road, speed=75 / 3.6))
    r = point_response(result)
    top.plot(r.time, 1e3 * r.displacement, lw=1, label=f"{label} (IM {r.displacement_impact.impact_factor:.3f})")
    bottom.plot(r.time, r.acceleration, lw=0.8, label=label)
    print(f"{label:<20} IM {r.displacement_impact.impact_factor:.4f}  max |a| {abs(r.acceleration).max():.3f} m/s^2")
top.set(ylabel="midspan displacement [mm]", title="HS20-44 over a 20 mm depression, 16.76 m beam, 75 km/h")
bottom.set(xlabel="time [s]", ylabel="midspan acceleration [m/s²]")
top.legend(fontsize=8)
OUT.mkdir(parents=True, exist_ok=True)
fig.savefig(OUT / "tire_models.png", dpi=110)
