"""Field verification: measured records in, the same crossing simulated, compared, calibrated.

Physics models (bridge, vehicle, road, contact), the solver and scenario files never import this
package; it builds its models and checks its runs as a scenario does (vbikit.scenario.build,
vbikit.scenario.preflight).  See docs/field.md.
"""
from typing import TYPE_CHECKING

from vbikit._lazy import lazy_exports

if TYPE_CHECKING:  # imported on first use (vbikit._lazy); listed here for type checkers and the API reference
    from vbikit.bridge.scaled import ScaledBridge
    from vbikit.field.io import (
        FieldFileError,
        FieldSpec,
        load_field_toml,
        read_response_csv,
    )
    from vbikit.field.metrics import channel_metrics
    from vbikit.field.workflow import (
        Calibration,
        CaseComparison,
        calibrate,
        compare_case,
        parse_tires,
    )

__all__ = ["Calibration", "CaseComparison", "FieldFileError", "FieldSpec", "ScaledBridge", "calibrate", "channel_metrics",
           "compare_case", "load_field_toml", "parse_tires", "read_response_csv"]

__getattr__, __dir__ = lazy_exports(globals(), {
    "vbikit.field.io": ["FieldFileError", "FieldSpec", "load_field_toml", "read_response_csv"],
    "vbikit.field.metrics": ["channel_metrics"],
    "vbikit.bridge.scaled": ["ScaledBridge"],
    "vbikit.field.workflow": ["Calibration", "CaseComparison", "calibrate", "compare_case", "parse_tires"],
})
