"""The figures of docs/traffic.md: run the example stream (as `vbikit traffic` does), plot the
stream's IM distribution and the event with the largest static effect.

    python examples/traffic/make_stream.py && python examples/traffic/make_figures.py
"""
from pathlib import Path

from vbikit.analysis import point_response
from vbikit.plot import plot_crossing
from vbikit.plot.traffic import plot_stream
from vbikit.solve import simulate
from vbikit.study.run import run_study
from vbikit.traffic import read_records
from vbikit.traffic.study import base_scenario, traffic_study

here = Path(__file__).parent
figures = here.parent.parent / "docs" / "figures"
base, base_dir = base_scenario(str(here / "base" / "bridge2.toml"))
job = traffic_study(read_records(here / "stream.csv"), base, base_dir, seed=1, name="example stream")
ds = run_study(job, here / "stream.nc", workers=2)
plot_stream(ds, figures / "traffic-stream.png")
e = int(ds.attrs["governing_static_event"])
result = simulate(job.crossing(e))
y = float(result.crossing.bridge.girder_y[3])
vehicles = ", ".join(f"{m.vehicle.description.split(' (')[0]} {m.direction}" for m in result.crossing.vehicles)
plot_crossing(result, point_response(result, None, y), figures / "traffic-event.png",
              title=f"event {e}, the largest static effect: {vehicles}\nGirder 4 midspan, "
                    f"IM = {float(ds['impact_factor'][e]):.3f}")
a = ds.attrs
print(f"{a['n_events']} events, {a['n_multiple_presence_events']} with several vehicles; "
      f"{a['n_events'] - a['n_small_static_events']} loading the point: IM mean {a['im_mean_loaded']:.3f}, 95 % "
      f"{a['im_q95_loaded']:.3f}; all events: IM mean {a['im_mean']:.3f} "
      f"(one {a['im_mean_single']:.3f}, several {a['im_mean_multiple']:.3f}), 95 % {a['im_q95']:.3f}; governing static "
      f"event {e} ({len(job.events[e])} vehicles): amplification {a['governing_static_amplification']:.3f}; largest "
      f"dynamic effect {a['governing_dynamic_amplification']:.3f} x the largest static; figures in {figures}")
