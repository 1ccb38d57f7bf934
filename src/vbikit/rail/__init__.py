"""Railway bridges: trains (HSLM-A/B, real trains), speed sweeps, EN 1991-2 / EN 1990 dynamic checks."""
from typing import TYPE_CHECKING

from vbikit._lazy import lazy_exports

if TYPE_CHECKING:  # imported on first use (vbikit._lazy); listed here for type checkers and the API reference
    from vbikit.rail.trains import (
        HSLM_A_TABLE,
        TRAIN_PRESETS,
        CarGeometry,
        Train,
        TrainError,
        TrainPreset,
        get_train,
        hslm_a,
        hslm_b,
        ice3,
        parse_train_table,
        read_train_table,
    )

__all__ = [
    "HSLM_A_TABLE",
    "TRAIN_PRESETS",
    "CarGeometry",
    "Train",
    "TrainError",
    "TrainPreset",
    "get_train",
    "hslm_a",
    "hslm_b",
    "ice3",
    "parse_train_table",
    "read_train_table",
]

__getattr__, __dir__ = lazy_exports(globals(), {
    "vbikit.rail.trains": ["HSLM_A_TABLE", "TRAIN_PRESETS", "CarGeometry", "Train", "TrainError", "TrainPreset",
                           "get_train", "hslm_a", "hslm_b", "ice3", "parse_train_table", "read_train_table"],
})
