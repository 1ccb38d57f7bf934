"""Field verification: measured records in, the same crossing simulated, compared, calibrated.

Physics models (bridge, vehicle, road, contact) never import this package; it uses the solver
and the models.  See docs/field.md.
"""
from typing import TYPE_CHECKING

from vbikit._lazy import lazy_exports

if TYPE_CHECKING:  # imported on first use (vbikit._lazy); listed here for type checkers and the API reference
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
        ScaledBridge,
        calibrate,
        compare_case,
        parse_tires,
    )

__all__ = ["Calibration", "CaseComparison", "FieldFileError", "FieldSpec", "ScaledBridge", "calibrate", "channel_metrics",
           "compare_case", "load_field_toml", "parse_tires", "read_response_csv"]

__getattr__, __dir__ = lazy_exports(globals(), {
    "vbikit.field.io": ["FieldFileError", "FieldSpec", "load_field_toml", "read_response_csv"],
    "vbikit.field.metrics": ["channel_metrics"],
    "vbikit.field.workflow": ["Calibration", "CaseComparison", "ScaledBridge", "calibrate", "compare_case", "parse_tires"],
})
