"""Multibody vehicle models (mass, damping, stiffness, wheels) and presets."""
from typing import TYPE_CHECKING

from vbikit._lazy import lazy_exports

if TYPE_CHECKING:  # imported on first use (vbikit._lazy); listed here for type checkers and the API reference
    from vbikit.vehicle.axles import GROUP_KINDS, axle_truck, semitrailer_3s2
    from vbikit.vehicle.builder import VehicleBuilder
    from vbikit.vehicle.model import GRAVITY, Vehicle, Wheel
    from vbikit.vehicle.presets import (
        VEHICLE_PRESETS,
        hs20_44,
        moving_force,
        quarter_car,
        sprung_mass,
        two_axle_truck,
    )
    from vbikit.vehicle.rail_car import RAIL_CAR_PRESETS, RailCarParameters, hertz_constant, hertz_stiffness, rail_car
    from vbikit.vehicle.trains import (HSLM_A_TABLE, TRAIN_PRESETS, CarGeometry, Train, TrainError, TrainPreset, get_train,
                                       hslm_a, hslm_b, ice3, parse_train_table, rail_distributed, read_train_table,
                                       train_vehicle)

__all__ = [
    "CarGeometry",
    "GRAVITY",
    "GROUP_KINDS",
    "HSLM_A_TABLE",
    "RAIL_CAR_PRESETS",
    "RailCarParameters",
    "TRAIN_PRESETS",
    "Train",
    "TrainError",
    "TrainPreset",
    "VEHICLE_PRESETS",
    "Vehicle",
    "VehicleBuilder",
    "Wheel",
    "axle_truck",
    "get_train",
    "hertz_constant",
    "hertz_stiffness",
    "hs20_44",
    "hslm_a",
    "hslm_b",
    "ice3",
    "moving_force",
    "parse_train_table",
    "quarter_car",
    "rail_car",
    "rail_distributed",
    "read_train_table",
    "semitrailer_3s2",
    "sprung_mass",
    "train_vehicle",
    "two_axle_truck",
]

__getattr__, __dir__ = lazy_exports(globals(), {
    "vbikit.vehicle.axles": ["GROUP_KINDS", "axle_truck", "semitrailer_3s2"],
    "vbikit.vehicle.builder": ["VehicleBuilder"],
    "vbikit.vehicle.model": ["GRAVITY", "Vehicle", "Wheel"],
    "vbikit.vehicle.rail_car": ["RAIL_CAR_PRESETS", "RailCarParameters", "hertz_constant", "hertz_stiffness", "rail_car"],
    "vbikit.vehicle.trains": ["HSLM_A_TABLE", "TRAIN_PRESETS", "CarGeometry", "Train", "TrainError", "TrainPreset", "get_train", "hslm_a", "hslm_b", "ice3", "parse_train_table", "rail_distributed", "read_train_table", "train_vehicle"],
    "vbikit.vehicle.presets": ["VEHICLE_PRESETS", "hs20_44", "moving_force", "quarter_car", "sprung_mass", "two_axle_truck"],
})
