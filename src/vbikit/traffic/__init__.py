"""Traffic: vehicle records (WIM-like CSV), events of overlapping vehicles, synthetic streams."""
from typing import TYPE_CHECKING

from vbikit._lazy import lazy_exports

if TYPE_CHECKING:  # imported on first use (vbikit._lazy); listed here for type checkers and the API reference
    from vbikit.traffic.events import Event, on_bridge_intervals, partition
    from vbikit.traffic.records import RecordsError, VehicleRecord, format_records, parse_records, read_records, write_records
    from vbikit.traffic.stream import TRUCK_MIX, LaneTraffic, TruckClass, synthetic_stream
    from vbikit.traffic.study import TrafficStudy, stream_statistics, traffic_study

__all__ = [
    "Event",
    "LaneTraffic",
    "RecordsError",
    "TRUCK_MIX",
    "TrafficStudy",
    "TruckClass",
    "VehicleRecord",
    "format_records",
    "on_bridge_intervals",
    "parse_records",
    "partition",
    "read_records",
    "stream_statistics",
    "synthetic_stream",
    "traffic_study",
    "write_records",
]

__getattr__, __dir__ = lazy_exports(globals(), {
    "vbikit.traffic.events": ["Event", "on_bridge_intervals", "partition"],
    "vbikit.traffic.records": ["RecordsError", "VehicleRecord", "format_records", "parse_records", "read_records", "write_records"],
    "vbikit.traffic.stream": ["TRUCK_MIX", "LaneTraffic", "TruckClass", "synthetic_stream"],
    "vbikit.traffic.study": ["TrafficStudy", "stream_statistics", "traffic_study"],
})
