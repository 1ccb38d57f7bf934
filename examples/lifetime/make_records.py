"""Write the example's records (examples/lifetime/wim.csv): one day of two-lane truck traffic
with a daily flow profile, lane 1 +x and lane 2 −x, the documented truck mix
(vbikit.traffic.TRUCK_MIX) — a stand-in for a day of weigh-in-motion records."""
from pathlib import Path

from vbikit.traffic import LaneTraffic, synthetic_stream, write_records
from vbikit.traffic.records import VehicleRecord

#: [substitute] trucks per hour per lane over the day (night low, daytime peak): about 1,000 a day a lane
PROFILE = (12, 10, 10, 12, 18, 30, 48, 60, 64, 64, 62, 60, 60, 62, 62, 60, 56, 50, 42, 34, 28, 22, 18, 14)

records = []
for hour, flow in enumerate(PROFILE):
    lanes = [LaneTraffic(1, "+x", flow, 85, 7), LaneTraffic(2, "-x", flow * 0.9, 80, 7)]
    for r in synthetic_stream(lanes, 0, seed=100 + hour, duration=3600.0):
        records.append(VehicleRecord(round(r.time + 3600.0 * hour, 3), r.direction, r.speed, r.axle_loads,
                                     r.axle_spacings, r.lane, id=f"h{hour:02d}-{r.id}"))
records.sort(key=lambda r: r.time)
write_records(records, Path(__file__).with_name("wim.csv"))
print(len(records), "records")
