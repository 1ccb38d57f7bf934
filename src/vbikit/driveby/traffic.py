"""Background traffic on the bridge during a drive-by pass (``[variability] traffic_flow``).

Each pass draws its own trucks: ``vbikit.traffic.synthetic_stream`` (Poisson arrivals with a 2 s
minimum headway, the FHWA truck mix ``TRUCK_MIX`` with its load and spacing scatter, speeds
N(traffic_speed_kmh, 10 %)) on one lane in ``traffic_direction``, seeded by the pass's
``traffic_seed`` (``variability.draw``: a function of the file's seed and the pass index only).
Every truck whose front axle enters the deck while the instrumented vehicle's front axle is on it,
0 ≤ t ≤ span / v (t = 0: the instrumented vehicle enters), joins the crossing as a dynamic
``axle_truck`` (its own suspension and tires) on the bridge's default line: the coupled solution
carries its weight and inertia; the run lasts until the last truck has left.  Not modelled: trucks
already on the deck when the instrumented vehicle enters (the bridge starts at rest).
"""
from __future__ import annotations

from vbikit.driveby.variability import Variability

#: standard deviation of the background trucks' speed, a fraction of the mean [substitute]
TRAFFIC_SPEED_SD = 0.10


def background_vehicles(var: Variability, seed: int, span: float, speed: float) -> tuple:
    """The pass's background trucks as ``VehicleMotion`` s (module docstring)."""
    from vbikit.solve import VehicleMotion
    from vbikit.traffic.stream import LaneTraffic, synthetic_stream
    from vbikit.vehicle.axles import axle_truck

    lane = LaneTraffic(lane=2, direction=var.traffic_direction, flow=float(var.traffic_flow),
                       speed_kmh=var.traffic_speed_kmh, speed_sd_kmh=TRAFFIC_SPEED_SD * var.traffic_speed_kmh)
    records = synthetic_stream([lane], 0, seed=seed, duration=span / speed)
    return tuple(VehicleMotion(axle_truck(r.axle_loads, r.axle_spacings), speed=float(r.speed), direction=r.direction,
                               entry_time=float(r.time)) for r in records)
