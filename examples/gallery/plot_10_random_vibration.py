"""Random vibration without sampling: the demo crossing's mean ± kσ by pseudo-excitation.

The ``vbikit demo`` scenario (HS20-44, 16.76 m beam, multi-point tires n = 6, ISO 8608 class C,
75 km/h) run with ``vbikit.run_random``: the mean history is the smooth-road crossing and σ(t)
comes from one deterministic complex crossing per wavenumber line (pseudo-excitation method, Lin;
Lu, Lin, Kennedy & Williams 2009), no road sampled. Twenty Monte-Carlo crossings on sampled class C
roads (grey, ``vbikit.random.montecarlo``) scatter inside the bands; the impact factor's
distribution is in the summary (``vbikit run SCENARIO --random --json`` prints the same).
"""
import os
from pathlib import Path

import numpy as np

from vbikit import run_random
from vbikit.random import PseudoRoad
from vbikit.random.figure import plot_random
from vbikit.random.montecarlo import monte_carlo
from vbikit.analysis import point_response
from vbikit.road import RoadPSD
from vbikit.scenario import demo_scenario_text, scenario_from_toml

OUT = Path(os.environ.get("VBIKIT_GALLERY_OUT", "vbikit-out"))

scenario = scenario_from_toml(demo_scenario_text())
rr = run_random(scenario)
s = rr.summary
q = s["impact_factor_quantiles"]
print(f"IM mean {s['impact_factor_mean']:.3f} ± {s['impact_factor_std']:.3f}; "
      + ", ".join(f"{k}: {v:.3f}" for k, v in q.items()))

# the same crossing on 20 sampled roads, for the figure (the engine's batched lanes)
n = rr.pem.time.size
samples = monte_carlo(rr.mean.crossing, PseudoRoad(RoadPSD.iso("C")), list(range(20)),
                      lambda res: point_response(res, rr.points[0].x, rr.points[0].y).displacement[:n])
inside = np.mean([np.abs(smp - rr.points[0].displacement[:n]) <= 3 * rr.pem.std("displacement")[:n, 0] + 1e-12
                  for smp in samples])
OUT.mkdir(parents=True, exist_ok=True)
plot_random(rr, OUT / "random_vibration.png", samples,
            title=f"demo, class C: mean ± kσ by pseudo-excitation; IM mean {s['impact_factor_mean']:.3f}, "
                  f"95 % {q['0.95']:.3f}")
print(f"Monte-Carlo samples inside ±3σ at {inside:.1%} of their points")
