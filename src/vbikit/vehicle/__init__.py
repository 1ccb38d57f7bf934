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

__all__ = [
    "GRAVITY",
    "GROUP_KINDS",
    "RAIL_CAR_PRESETS",
    "RailCarParameters",
    "VEHICLE_PRESETS",
    "Vehicle",
    "VehicleBuilder",
    "Wheel",
    "axle_truck",
    "hertz_constant",
    "hertz_stiffness",
    "hs20_44",
    "moving_force",
    "quarter_car",
    "rail_car",
    "semitrailer_3s2",
    "sprung_mass",
    "two_axle_truck",
]

__getattr__, __dir__ = lazy_exports(globals(), {
    "vbikit.vehicle.axles": ["GROUP_KINDS", "axle_truck", "semitrailer_3s2"],
    "vbikit.vehicle.builder": ["VehicleBuilder"],
    "vbikit.vehicle.model": ["GRAVITY", "Vehicle", "Wheel"],
    "vbikit.vehicle.rail_car": ["RAIL_CAR_PRESETS", "RailCarParameters", "hertz_constant", "hertz_stiffness", "rail_car"],
    "vbikit.vehicle.presets": ["VEHICLE_PRESETS", "hs20_44", "moving_force", "quarter_car", "sprung_mass", "two_axle_truck"],
})
