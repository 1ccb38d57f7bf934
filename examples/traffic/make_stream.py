"""Write the example stream (examples/traffic/stream.csv): 400 trucks, lane 1 +x and lane 2 −x,
600 trucks/h per lane, the documented truck mix (vbikit.traffic.TRUCK_MIX)."""
from pathlib import Path

from vbikit.traffic import LaneTraffic, synthetic_stream, write_records

lanes = [LaneTraffic(1, "+x", 600, 80, 8), LaneTraffic(2, "-x", 600, 75, 8)]
write_records(synthetic_stream(lanes, 400, seed=2026), Path(__file__).with_name("stream.csv"))
